#![doc = include_str!("../README.md")]
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![doc(test(attr(deny(warnings))))]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!(
    "creature-autorig needs its `std` feature (default) or its `libm` feature for float math"
);

mod build;
mod error;
mod options;
mod skeleton;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;

pub use build::{MAX_COORDINATE, rig};
pub use error::AutorigError;
pub use options::{RigOptions, RootAt};
pub use skeleton::{Joint, Rig, Socket};

/// The `glam` version this crate's signatures use.
pub use glam;
