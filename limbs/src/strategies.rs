//! Proptest strategies for this crate's inputs (feature `proptest`).
//!
//! Valid inputs ([`body`], [`spine_bone`], [`creature_kind`], [`options`]) and adversarial
//! ones for the error paths ([`invalid_body`], [`invalid_options`]), so a downstream property
//! suite can generate bodies the way this crate's own suite does. A plan also needs a
//! generator: draw a `u64` seed and feed it to any `rand_core` 0.10 generator.
//!
//! ```
//! use creature_limbs::{plan, strategies, PlanOptions, CreatureKind};
//! use creature_limbs::rand_core::{Infallible, TryRng};
//! use proptest::test_runner::TestRunner;
//!
//! struct Step(u64);
//! impl TryRng for Step {
//!     type Error = Infallible;
//!     fn try_next_u32(&mut self) -> Result<u32, Infallible> { Ok((self.try_next_u64()? >> 32) as u32) }
//!     fn try_next_u64(&mut self) -> Result<u64, Infallible> {
//!         self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1);
//!         Ok(self.0)
//!     }
//!     fn try_fill_bytes(&mut self, _: &mut [u8]) -> Result<(), Infallible> { Ok(()) }
//! }
//!
//! let mut runner = TestRunner::deterministic();
//! runner.run(&(strategies::body(), proptest::num::u64::ANY), |(body, seed)| {
//!     let p = plan(&body, CreatureKind::Walker, &PlanOptions::DEFAULT, &mut Step(seed)).unwrap();
//!     assert!(p.stability_margin.is_some_and(|m| m > 0.0));
//!     Ok(())
//! }).unwrap();
//! runner.run(&strategies::invalid_body(), |body| {
//!     assert!(plan(&body, CreatureKind::Swimmer, &PlanOptions::DEFAULT, &mut Step(1)).is_err());
//!     Ok(())
//! }).unwrap();
//! ```

use alloc::vec::Vec;

use glam::Vec3;
use proptest::prelude::*;

use crate::{Body, CreatureKind, HeadEnd, MAX_BONES, PlanOptions, SpineBone};

/// A bone at `along` with a width in `[0.02, 2]`, a clearance in `[0, 3]` (zero included: a
/// body lying on the ground), side sockets up to 0.1 apart in height and a local ground height
/// in `[-0.5, 0.5]` (a bent spine).
pub fn spine_bone(along: f32) -> impl Strategy<Value = SpineBone> {
    (
        0.02f32..2.0,
        prop_oneof![1 => Just(0.0f32), 9 => 0.0f32..3.0],
        -0.05f32..0.05,
        -0.5f32..0.5,
        -0.1f32..0.1,
    )
        .prop_map(move |(width, clearance, tilt, ground, sway)| {
            let y = ground + clearance + tilt.abs();
            let left = Vec3::new(sway - width / 2.0, y + tilt, along);
            let right = Vec3::new(sway + width / 2.0, y - tilt, along);
            let top = Vec3::new(sway, y + width / 2.0, along);
            SpineBone {
                along,
                left,
                right,
                top,
                width,
                clearance,
            }
        })
}

/// A valid body: 1 to 16 bones spaced 0.1 to 1 apart (random gaps), each from [`spine_bone`];
/// the length is the bones' extent plus up to two gaps at each end; either end may be the
/// head.
pub fn body() -> impl Strategy<Value = Body> {
    body_with(1..=16)
}

/// A valid body with a bone count drawn from `bones` (clamped to `1..=MAX_BONES`), built as
/// [`body`] builds them.
pub fn body_with(bones: core::ops::RangeInclusive<usize>) -> impl Strategy<Value = Body> {
    let lo = (*bones.start()).clamp(1, MAX_BONES);
    let hi = (*bones.end()).clamp(lo, MAX_BONES);
    (
        proptest::collection::vec(0.1f32..1.0, lo..=hi),
        0.0f32..2.0,
        prop::bool::ANY,
    )
        .prop_flat_map(|(gaps, extra, head_last)| {
            let mut along = Vec::with_capacity(gaps.len());
            let mut a = 0.0f32;
            for g in &gaps {
                along.push(a);
                a += g;
            }
            let extent = along.last().copied().unwrap_or(0.0);
            let length = extent + (0.2 + extra) * gaps.iter().copied().fold(0.1f32, f32::max);
            let bones: Vec<_> = along.into_iter().map(spine_bone).collect();
            (bones, Just(length), Just(head_last))
        })
        .prop_map(|(bones, length, head_last)| Body {
            bones,
            length,
            head: if head_last {
                HeadEnd::Last
            } else {
                HeadEnd::First
            },
        })
}

/// Any creature kind.
pub fn creature_kind() -> impl Strategy<Value = CreatureKind> {
    prop_oneof![
        Just(CreatureKind::Walker),
        Just(CreatureKind::Flier),
        Just(CreatureKind::Swimmer),
    ]
}

/// Valid options around the defaults: sweep `[0, 1]`, foot radius `[0.05, 0.3]`, minimum
/// margin `[0.005, 0.05]`, minimum leg length `[0, 0.2]`, arm chance `[0, 2]`.
pub fn options() -> impl Strategy<Value = PlanOptions> {
    (
        0.0f32..1.0,
        0.05f32..0.3,
        0.005f32..0.05,
        0.0f32..0.2,
        0.0f32..2.0,
    )
        .prop_map(|(sweep, foot, margin, min_leg, arms)| {
            PlanOptions::DEFAULT
                .with_sweep(sweep)
                .with_foot_radius(foot)
                .with_min_margin(margin)
                .with_min_leg_length(min_leg)
                .with_arm_chance(arms)
        })
}

/// A float that is NaN or ±infinity.
pub fn non_finite_f32() -> impl Strategy<Value = f32> {
    prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY)]
}

/// An invalid body, each kind of fault equally likely: no bones, a NaN or infinite value, a
/// value beyond [`MAX_EXTENT`](crate::MAX_EXTENT), a negative width or clearance, bones out
/// of order, a non-positive length, or too many bones.
pub fn invalid_body() -> impl Strategy<Value = Body> {
    (
        body_with(2..=8),
        0usize..8,
        non_finite_f32(),
        any::<prop::sample::Index>(),
    )
        .prop_map(|(mut body, fault, bad, index)| {
            let i = index.index(body.bones.len());
            match fault {
                0 => body.bones.clear(),
                1 => match i % 5 {
                    0 => body.bones[i].along = bad,
                    1 => body.bones[i].left.x = bad,
                    2 => body.bones[i].top.y = bad,
                    3 => body.bones[i].width = bad,
                    _ => body.bones[i].clearance = bad,
                },
                2 => body.bones[i].right.z = 1.0e9,
                3 => body.bones[i].width = -0.5,
                4 => body.bones[i].clearance = -0.01,
                5 => {
                    let j = if i == 0 { 1 } else { i - 1 };
                    body.bones[i.max(j)].along = body.bones[i.min(j)].along;
                }
                6 => body.length = if i % 2 == 0 { 0.0 } else { -1.0 },
                _ => {
                    let last = body.bones[body.bones.len() - 1];
                    while body.bones.len() <= MAX_BONES {
                        let mut b = last;
                        b.along += body.bones.len() as f32;
                        body.bones.push(b);
                    }
                }
            }
            body
        })
}

/// Options with one field out of its documented range (NaN, negative, zero where it must be
/// positive, or a reversed range).
pub fn invalid_options() -> impl Strategy<Value = PlanOptions> {
    (0usize..6, non_finite_f32()).prop_map(|(fault, bad)| match fault {
        0 => PlanOptions::DEFAULT.with_sweep(bad),
        1 => PlanOptions::DEFAULT.with_foot_radius(0.0),
        2 => PlanOptions::DEFAULT.with_min_margin(-1.0),
        3 => PlanOptions::DEFAULT.with_fin_size([0.5, 0.1]),
        4 => PlanOptions::DEFAULT.with_uniform_width_ratio(1.5),
        _ => PlanOptions::DEFAULT.with_dorsal_fins([3, 1]),
    })
}
