#![doc = include_str!("../README.md")]
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![doc(test(attr(deny(warnings))))]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!(
    "creature-ffd needs its `std` feature (default) or its `libm` feature for float math"
);

mod analysis;
mod bernstein;
mod error;
mod lattice;
mod math;
pub mod slices;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;

pub use analysis::{FoldReport, InverseOptions, MAX_FOLD_SAMPLES, SINGULAR_DETERMINANT};
pub use error::FfdError;
pub use lattice::{Axis, Lattice, MAX_COORDINATE, MAX_DIVISIONS, MIN_VOLUME_RATIO, OutsidePolicy};

/// The `glam` version this crate's signatures use.
pub use glam;
