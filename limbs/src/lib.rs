#![doc = include_str!("../README.md")]
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![doc(test(attr(deny(warnings))))]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!(
    "creature-limbs needs its `std` feature (default) or its `libm` feature for float math"
);

mod body;
mod error;
mod options;
mod plan;
mod planner;
mod random;
mod sort;
// The tests' generator, shared with the integration tests, bench and example.
#[cfg(test)]
#[path = "../tests/support/split_mix.rs"]
mod split_mix;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;
mod support;

pub use body::{Body, CreatureKind, HeadEnd, MAX_BONES, MAX_EXTENT, SpineBone};
pub use error::LimbsError;
pub use options::PlanOptions;
pub use plan::{Knee, Limb, LimbKind, Plan, Repair, Side, Socket, Span, WalkerLayout};
pub use planner::plan;
pub use support::{convex_hull, signed_distance, support_margin};

/// The `glam` version this crate's signatures use.
pub use glam;
/// The `rand_core` version whose [`Rng`](rand_core::Rng) trait [`plan`] takes.
pub use rand_core;
