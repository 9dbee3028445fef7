#![doc = include_str!("../README.md")]
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![doc(test(attr(deny(warnings))))]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!(
    "creature-skin needs its `std` feature (default) or its `libm` feature for float math"
);

mod blend;
mod contributions;
mod error;
mod influences;
mod math;
mod nearest;
mod report;
mod sort;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;

pub use blend::{Blend, skin_normals, skin_positions};
pub use contributions::{from_contributions, from_contributions_or};
pub use error::SkinError;
pub use influences::{Influences, MAX_INFLUENCES};
pub use nearest::{
    Falloff, MAX_BONES, MAX_COORDINATE, NearestOptions, distance_to_bone, nearest_k, nearest_k_with,
};
pub use report::{SkinReport, report};

/// The `glam` version this crate's signatures use.
pub use glam;
