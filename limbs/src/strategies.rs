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
//!     // A walker either stands, or the planner says no layout of its legs can.
//!     match plan(&body, CreatureKind::Walker, &PlanOptions::DEFAULT, &mut Step(seed)) {
//!         Ok(p) => assert!(p.stability_margin.is_some_and(|m| m > 0.0)),
//!         Err(e) => assert!(matches!(e, creature_limbs::LimbsError::NoStableLayout { .. })),
//!     }
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

/// A bone at `along` of a creature facing +Z (glTF's convention: its left socket on +X), with a
/// width in `[0.02, 2]`, a clearance in `[0, 3]` (zero included: a body lying on the ground),
/// side sockets up to 0.1 apart in height, a sideways sway in `[-0.1, 0.1]` and a local ground
/// height in `[-0.5, 0.5]` (a bent spine).
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
            let left = Vec3::new(sway + width / 2.0, y + tilt, along);
            let right = Vec3::new(sway - width / 2.0, y - tilt, along);
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

/// A valid body: 1 to 16 bones spaced 0.1 to 1 apart (random gaps) along +Z, each from
/// [`spine_bone`]; the length is the bones' extent plus up to two gaps at each end; either end
/// may be the head. The creature faces its head, so a body whose head is the first bone (toward
/// −Z) is mirrored in x: its left sockets are on −X.
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
        .prop_map(|(mut bones, length, head_last)| {
            if !head_last {
                // Facing −Z: the creature's left is −X.
                let flip = Vec3::new(-1.0, 1.0, 1.0);
                for b in &mut bones {
                    b.left *= flip;
                    b.right *= flip;
                    b.top *= flip;
                }
            }
            Body {
                bones,
                length,
                head: if head_last {
                    HeadEnd::Last
                } else {
                    HeadEnd::First
                },
            }
        })
}

/// Any creature kind.
pub fn creature_kind() -> impl Strategy<Value = CreatureKind> {
    prop_oneof![
        Just(CreatureKind::Walker),
        Just(CreatureKind::Flier),
        Just(CreatureKind::Swimmer),
        Just(CreatureKind::Slitherer),
    ]
}

/// A float in `[lo, hi]`: usually in the typical sub-range `[typ_lo, typ_hi]`, sometimes
/// anywhere in the range, sometimes exactly at an end.
fn scalar_in(lo: f32, hi: f32, typ_lo: f32, typ_hi: f32) -> impl Strategy<Value = f32> {
    prop_oneof![
        6 => typ_lo..=typ_hi,
        2 => lo..=hi,
        1 => Just(lo),
        1 => Just(hi),
    ]
}

/// A `[min, max]` pair within `[lo, hi]`, drawn as [`scalar_in`] draws and sorted.
fn range_in(lo: f32, hi: f32, typ_lo: f32, typ_hi: f32) -> impl Strategy<Value = [f32; 2]> {
    (
        scalar_in(lo, hi, typ_lo, typ_hi),
        scalar_in(lo, hi, typ_lo, typ_hi),
    )
        .prop_map(|(a, b)| [a.min(b), a.max(b)])
}

/// A `[min, max]` count pair within `[0, hi]`, usually at most `typ_hi`.
fn count_range_in(hi: usize, typ_hi: usize) -> impl Strategy<Value = [usize; 2]> {
    prop_oneof![4 => (0..=typ_hi, 0..=typ_hi), 1 => (0..=hi, 0..=hi)]
        .prop_map(|(a, b)| [a.min(b), a.max(b)])
}

/// Valid options with every field varied across its documented range (see
/// [`PlanOptions`]): each value is usually drawn from a typical sub-range around the default,
/// sometimes from the whole range, and sometimes exactly at either end, so that extreme but
/// valid settings (a zero foot radius, a 100× stride, a minimum margin of a whole body length)
/// are exercised too. Such settings can make a walker impossible to balance:
/// [`plan`](crate::plan) then returns
/// [`LimbsError::NoStableLayout`](crate::LimbsError::NoStableLayout).
pub fn options() -> impl Strategy<Value = PlanOptions> {
    let walking = (
        scalar_in(0.0, 100.0, 0.1, 1.0),
        scalar_in(0.0, 0.25, 0.02, 0.15),
        prop_oneof![6 => 0.001f32..=0.05, 2 => 0.001f32..=1.0, 1 => Just(1.0f32)],
        scalar_in(0.001, 100.0, 0.001, 0.2),
        scalar_in(0.0, 1.0e6, 0.5, 10.0),
        scalar_in(0.0, 1.0, 0.3, 1.0),
        scalar_in(0.0, 1.0, 0.3, 1.0),
        prop_oneof![4 => 0usize..=4, 1 => 0usize..=MAX_BONES],
    );
    let arms = (
        scalar_in(0.0, 100.0, 0.0, 2.0),
        range_in(0.0, 1.0, 0.0, 1.0),
        scalar_in(0.001, 100.0, 0.001, 0.2),
    );
    let parts = (
        prop_oneof![4 => 0usize..=8, 1 => 0usize..=64],
        range_in(0.001, 100.0, 0.01, 0.5),
        range_in(0.001, 100.0, 0.1, 1.0),
        range_in(0.001, 100.0, 0.2, 1.5),
        range_in(0.001, 100.0, 0.5, 1.5),
        count_range_in(64, 4),
        count_range_in(64, 3),
        range_in(0.001, 100.0, 0.05, 0.4),
        range_in(0.001, 100.0, 0.1, 0.6),
    );
    (walking, arms, parts).prop_map(
        |(
            (sweep, foot, margin, min_leg, long, uniform, second, central),
            (arm_chance, arm_length, min_arm),
            (flier_pairs, flier_leg, buzzing, flapping, stretch, dorsal, pectoral, fin, tail),
        )| {
            PlanOptions::DEFAULT
                .with_sweep(sweep)
                .with_foot_radius(foot)
                .with_min_margin(margin)
                .with_min_leg_length(min_leg)
                .with_long_body_ratio(long)
                .with_uniform_width_ratio(uniform)
                .with_second_pair_ratio(second)
                .with_central_bones(central)
                .with_arm_chance(arm_chance)
                .with_arm_length(arm_length)
                .with_min_arm_length(min_arm)
                .with_max_flier_leg_pairs(flier_pairs)
                .with_flier_leg_length(flier_leg)
                .with_buzzing_wing_size(buzzing)
                .with_flapping_wing_size(flapping)
                .with_stretch(stretch)
                .with_dorsal_fins(dorsal)
                .with_pectoral_pairs(pectoral)
                .with_fin_size(fin)
                .with_tail_size(tail)
        },
    )
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

/// Options with one field out of its documented range (NaN or infinite, below or above the
/// range, zero where it must be positive, or a reversed `[min, max]` pair), each field equally
/// likely.
pub fn invalid_options() -> impl Strategy<Value = PlanOptions> {
    (0usize..20, non_finite_f32(), prop::bool::ANY).prop_map(|(field, bad, nan)| {
        let d = PlanOptions::DEFAULT;
        let x = |out_of_range: f32| if nan { bad } else { out_of_range };
        match field {
            0 => d.with_sweep(x(-0.5)),
            1 => d.with_foot_radius(x(0.26)),
            2 => d.with_min_margin(x(0.0)),
            3 => d.with_min_leg_length(x(0.0)),
            4 => d.with_long_body_ratio(x(2.0e6)),
            5 => d.with_uniform_width_ratio(x(1.5)),
            6 => d.with_second_pair_ratio(x(-0.1)),
            7 => d.with_central_bones(MAX_BONES + 1),
            8 => d.with_arm_chance(x(101.0)),
            9 => d.with_arm_length([0.5, x(0.4)]),
            10 => d.with_min_arm_length(x(0.0)),
            11 => d.with_max_flier_leg_pairs(65),
            12 => d.with_flier_leg_length([x(0.0), 0.4]),
            13 => d.with_buzzing_wing_size([0.3, x(100.5)]),
            14 => d.with_flapping_wing_size([x(1.2), 1.0]),
            15 => d.with_stretch([x(-1.0), 1.3]),
            16 => d.with_dorsal_fins(if nan { [3, 1] } else { [0, 65] }),
            17 => d.with_pectoral_pairs(if nan { [2, 0] } else { [0, 65] }),
            18 => d.with_fin_size([0.1, x(0.05)]),
            _ => d.with_tail_size([x(0.0), 0.45]),
        }
    })
}
