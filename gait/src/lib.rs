#![doc = include_str!("../README.md")]
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![doc(test(attr(deny(warnings))))]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!(
    "creature-gait needs its `std` feature (default) or its `libm` feature for float math"
);

mod controller;
mod curve;
mod error;
mod gaits;
mod ground;
mod ik;
mod leg;
mod math;
mod metrics;
mod motion;
mod options;
mod sort;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;

pub use controller::{
    BodyReaction, Controller, LegState, Look, MAX_ANGULAR_SPEED, MAX_COORDINATE, MAX_SPEED,
    MAX_TIME_STEP,
};
pub use curve::{HeightCurve, ReachCurve};
pub use error::GaitError;
pub use gaits::{Gait, GaitSpeeds};
pub use ground::{FnGround, Ground, HeightField, Plane, RayHit};
pub use ik::{TwoBone, solve_two_bone, solve_two_bone_joints};
pub use leg::{Chain, Leg, LimbKind, MAX_CHAIN_SEGMENTS, Pose};
pub use metrics::{GaitMetrics, support_margin};
pub use motion::{FlapParams, Side, SwimParams, WingKind};
pub use options::GaitOptions;

/// The `glam` version this crate's signatures use.
pub use glam;
