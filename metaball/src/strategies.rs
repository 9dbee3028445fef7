//! Proptest strategies for this crate's inputs (feature `proptest`).
//!
//! Valid inputs ([`ball2`], [`ball_set2`], [`creature_balls`], [`falloff`], [`field2`],
//! [`ball3`], [`ball_set3`], [`field3`], [`segment`]) and adversarial ones for the error paths
//! ([`bad_ball2`], [`bad_ball3`], [`bad_falloff`], [`bad_multiplier`], [`bad_thickness`],
//! [`non_finite_f32`]), so a downstream property suite can generate ball sets and fields the
//! way this crate's own suite does.
//!
//! ```
//! use creature_metaball::strategies;
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::deterministic();
//! runner.run(&(strategies::field2(), strategies::vec2_in(100.0)), |(field, p)| {
//!     let err = (field.value(p) - field.value_exact(p)).abs();
//!     prop_assert!(err <= field.error_bound() + 1e-4 * field.value_exact(p).max(1.0));
//!     Ok(())
//! }).unwrap();
//! ```

use alloc::vec::Vec;

use glam::{Vec2, Vec3};
use proptest::prelude::*;

use crate::{
    Ball2, Ball3, CoverOptions, Falloff, Field2, Field3, FieldOptions, MULTIPLIER_RANGE,
    cover_segment_with,
};

/// A point with both coordinates in `[-range, range]`.
pub fn vec2_in(range: f32) -> impl Strategy<Value = Vec2> {
    (-range..=range, -range..=range).prop_map(|(x, y)| Vec2::new(x, y))
}

/// A point with every coordinate in `[-range, range]`.
pub fn vec3_in(range: f32) -> impl Strategy<Value = Vec3> {
    (-range..=range, -range..=range, -range..=range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A valid ball: centre in `[-100, 100]²`, radius in `[0.5, 30]`, id in `0..8`.
pub fn ball2() -> impl Strategy<Value = Ball2> {
    (vec2_in(100.0), 0.5f32..30.0, 0u32..8).prop_map(|(c, r, id)| Ball2::new(c, r, id))
}

/// A valid 3D ball: centre in `[-100, 100]³`, radius in `[0.5, 30]`, id in `0..8`.
pub fn ball3() -> impl Strategy<Value = Ball3> {
    (vec3_in(100.0), 0.5f32..30.0, 0u32..8).prop_map(|(c, r, id)| Ball3::new(c, r, id))
}

/// 1 to `max` valid balls (see [`ball2`]).
pub fn ball_set2(max: usize) -> impl Strategy<Value = Vec<Ball2>> {
    proptest::collection::vec(ball2(), 1..=max.max(1))
}

/// 1 to `max` valid 3D balls (see [`ball3`]).
pub fn ball_set3(max: usize) -> impl Strategy<Value = Vec<Ball3>> {
    proptest::collection::vec(ball3(), 1..=max.max(1))
}

/// Any valid falloff: the seeds', or a random exponential, Wyvill or Blinn one.
pub fn falloff() -> impl Strategy<Value = Falloff> {
    prop_oneof![
        Just(Falloff::SEED),
        (-4.0f32..-0.1).prop_map(|blobbiness| Falloff::Exponential { blobbiness }),
        (1.1f32..10.0).prop_map(|peak| Falloff::Wyvill { peak }),
        (1.1f32..10.0, 0.2f32..4.0).prop_map(|(strength, sharpness)| Falloff::Blinn {
            strength,
            sharpness
        }),
    ]
}

/// Valid field options: any [`falloff`], epsilon from `1e-7` to `1e-2`, automatic or explicit
/// cell size.
pub fn field_options() -> impl Strategy<Value = FieldOptions> {
    (
        falloff(),
        -7.0f32..-2.0,
        proptest::option::of(0.5f32..200.0),
    )
        .prop_map(|(falloff, exponent, cell)| {
            FieldOptions::DEFAULT
                .with_falloff(falloff)
                .with_epsilon(10f32.powf(exponent))
                .with_cell_size(cell)
        })
}

/// A valid 2D field of up to 24 balls with random [`field_options`].
pub fn field2() -> impl Strategy<Value = Field2> {
    (ball_set2(24), field_options()).prop_filter_map("field rejected", |(balls, options)| {
        Field2::with_options(&balls, &options).ok()
    })
}

/// A valid 3D field of up to 16 balls with random [`field_options`].
pub fn field3() -> impl Strategy<Value = Field3> {
    (ball_set3(16), field_options()).prop_filter_map("field rejected", |(balls, options)| {
        Field3::with_options(&balls, &options).ok()
    })
}

/// A bone segment to cover: `(from, to, thickness, multiplier, interior_joint)`, ends in
/// `[-200, 200]²`, thickness in `[2, 40]`, multiplier in `[1, 1.6]`.
pub fn segment() -> impl Strategy<Value = (Vec2, Vec2, f32, f32, bool)> {
    (
        vec2_in(200.0),
        vec2_in(200.0),
        2.0f32..40.0,
        MULTIPLIER_RANGE.0..=MULTIPLIER_RANGE.1,
        any::<bool>(),
    )
}

/// A creature-like ball set, built the seed's way: a straight spine of 2 to 5 segments along
/// +y (thickness 10–40, length 50–100) with limb pairs (thickness 5–15, length 50–80) on
/// some joints, each segment covered by [`cover_segment_with`] with interior joints, ids =
/// the parent bone's index.
pub fn creature_balls() -> impl Strategy<Value = Vec<Ball2>> {
    let spine = proptest::collection::vec(
        (
            10.0f32..40.0,
            50.0f32..100.0,
            MULTIPLIER_RANGE.0..=MULTIPLIER_RANGE.1,
        ),
        2..=5,
    );
    let limbs = proptest::collection::vec(
        (
            any::<bool>(),
            5.0f32..15.0,
            50.0f32..80.0,
            MULTIPLIER_RANGE.0..=MULTIPLIER_RANGE.1,
        ),
        6,
    );
    (spine, limbs).prop_map(|(spine, limbs)| {
        let mut balls = Vec::new();
        let mut joints = Vec::with_capacity(spine.len() + 1);
        joints.push(Vec2::ZERO);
        let mut thickness = Vec::with_capacity(spine.len());
        for (i, &(t, length, m)) in spine.iter().enumerate() {
            let parent = joints[i];
            let child = parent + Vec2::new(0.0, length);
            joints.push(child);
            thickness.push(t);
            let options = CoverOptions::DEFAULT.with_interior_joint(i > 0);
            if let Ok(covering) = cover_segment_with(child, parent, t, m, i as u32, &options) {
                balls.extend(covering);
            }
        }
        let mut bone = joints.len() as u32;
        for (i, &(present, t, length, m)) in limbs.iter().enumerate() {
            let Some(&joint) = joints.get(i) else { break };
            if !present {
                continue;
            }
            let body = thickness
                .get(i)
                .copied()
                .unwrap_or(0.0)
                .max(thickness.get(i.wrapping_sub(1)).copied().unwrap_or(0.0));
            for side in [-1.0f32, 1.0] {
                let socket = joint + Vec2::new(side * 1.1 * body, 0.0);
                let tip = socket + Vec2::new(side * length, 0.0);
                if let Ok(covering) =
                    cover_segment_with(tip, socket, t, m, bone, &CoverOptions::DEFAULT)
                {
                    balls.extend(covering);
                }
                bone += 2;
            }
        }
        balls
    })
}

/// A float that is NaN or ±infinity.
pub fn non_finite_f32() -> impl Strategy<Value = f32> {
    prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY)]
}

/// A radius every field rejects: non-finite, zero, negative, or outside
/// [`RADIUS_RANGE`](crate::RADIUS_RANGE).
pub fn bad_radius() -> impl Strategy<Value = f32> {
    prop_oneof![
        non_finite_f32(),
        Just(0.0f32),
        Just(-0.0f32),
        -1e6f32..-1e-30,
        Just(1e-9f32),
        Just(1e10f32),
    ]
}

/// A ball every field rejects: a non-finite or out-of-range centre coordinate, or a
/// [`bad_radius`].
pub fn bad_ball2() -> impl Strategy<Value = Ball2> {
    prop_oneof![
        (ball2(), non_finite_f32(), any::<bool>()).prop_map(|(mut b, bad, x)| {
            if x {
                b.center.x = bad;
            } else {
                b.center.y = bad;
            }
            b
        }),
        (ball2(), Just(1e13f32)).prop_map(|(mut b, far)| {
            b.center.x = far;
            b
        }),
        (ball2(), bad_radius()).prop_map(|(mut b, r)| {
            b.radius = r;
            b
        }),
    ]
}

/// A 3D ball every field rejects.
pub fn bad_ball3() -> impl Strategy<Value = Ball3> {
    prop_oneof![
        (ball3(), non_finite_f32(), 0usize..3).prop_map(|(mut b, bad, axis)| {
            let mut c = b.center.to_array();
            c[axis] = bad;
            b.center = Vec3::from_array(c);
            b
        }),
        (ball3(), bad_radius()).prop_map(|(mut b, r)| {
            b.radius = r;
            b
        }),
    ]
}

/// A falloff whose constants are rejected: non-finite, zero, of the wrong sign or out of
/// range.
pub fn bad_falloff() -> impl Strategy<Value = Falloff> {
    prop_oneof![
        prop_oneof![non_finite_f32(), 0.0f32..100.0, Just(-100.0f32)]
            .prop_map(|blobbiness| Falloff::Exponential { blobbiness }),
        prop_oneof![non_finite_f32(), -10.0f32..=0.0, Just(1e7f32)]
            .prop_map(|peak| Falloff::Wyvill { peak }),
        prop_oneof![non_finite_f32(), -10.0f32..=0.0].prop_map(|sharpness| Falloff::Blinn {
            strength: 2.0,
            sharpness
        }),
    ]
}

/// A culling epsilon every field rejects: not finite, or outside
/// [`EPSILON_RANGE`](crate::EPSILON_RANGE).
pub fn bad_epsilon() -> impl Strategy<Value = f32> {
    prop_oneof![
        non_finite_f32(),
        Just(0.0f32),
        -1.0f32..0.0,
        Just(1e-13f32),
        0.11f32..10.0,
    ]
}

/// A multiplier outside `[1, 1.6]` (or not finite).
pub fn bad_multiplier() -> impl Strategy<Value = f32> {
    prop_oneof![non_finite_f32(), -10.0f32..0.999, 1.601f32..10.0]
}

/// A thickness that is not finite or not positive.
pub fn bad_thickness() -> impl Strategy<Value = f32> {
    prop_oneof![non_finite_f32(), Just(0.0f32), -100.0f32..0.0]
}
