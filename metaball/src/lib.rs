#![doc = include_str!("../README.md")]
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![doc(test(attr(deny(warnings))))]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!(
    "creature-metaball needs its `std` feature (default) or its `libm` feature for float math"
);

mod ball;
mod cover;
mod error;
mod falloff;
mod field;
mod grid;
mod math;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;

pub use ball::{Ball2, Ball3, MAX_COORDINATE, RADIUS_RANGE};
pub use cover::{
    CoverOptions, MAX_COVER_BALLS, MULTIPLIER_RANGE, SEED_MULTIPLIER, SEED_SPACING,
    THICKNESS_RANGE, cover_radius_factor, cover_segment, cover_segment_with, cover_segment3,
    cover_segment3_with,
};
pub use error::MetaballError;
pub use falloff::{
    BLOBBINESS_RANGE, Falloff, ISO_LEVEL, SEED_BLOBBINESS, SHARPNESS_RANGE, STRENGTH_RANGE,
};
pub use field::{
    Attribute, BlockSampler, DEFAULT_EPSILON, EPSILON_RANGE, Field2, Field3, FieldOptions,
    GridStats, MAX_FIELD_BALLS, MAX_GRID_SAMPLES, Share, Shares,
};

/// The `glam` version this crate's signatures use.
pub use glam;
/// The `smallvec` version [`Shares`] uses.
pub use smallvec;
