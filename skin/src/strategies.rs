//! Proptest strategies for this crate's inputs (feature `proptest`).
//!
//! Valid inputs ([`bones`], [`vertices`], [`influences`], [`contributions`], [`rigid_transform`])
//! and adversarial ones for the error paths ([`non_finite_vec3`], [`bad_k`],
//! [`bad_influences`]), so a downstream property suite can generate skinning inputs the way
//! this crate's own suite does.
//!
//! ```
//! use creature_skin::{nearest_k, strategies};
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::deterministic();
//! runner.run(&(strategies::vertices(50), strategies::bones(8)), |(vertices, bones)| {
//!     for inf in nearest_k(&vertices, &bones, 4).unwrap() {
//!         prop_assert!((inf.weight_sum() - 1.0).abs() <= 1e-6);
//!     }
//!     Ok(())
//! }).unwrap();
//! ```

use alloc::vec::Vec;

use glam::{Affine3A, EulerRot, Quat, Vec3};
use proptest::prelude::*;

use crate::{Influences, MAX_INFLUENCES};

/// A finite coordinate in `[-range, range]`.
fn coordinate(range: f32) -> impl Strategy<Value = f32> {
    -range..=range
}

/// A point with every coordinate in `[-range, range]`.
pub fn vec3_in(range: f32) -> impl Strategy<Value = Vec3> {
    (coordinate(range), coordinate(range), coordinate(range))
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// One bone: a head in `[-10, 10]³` and a tail up to 3 away in each coordinate (sometimes equal
/// to the head: a point bone).
pub fn bone() -> impl Strategy<Value = [Vec3; 2]> {
    (vec3_in(10.0), vec3_in(3.0), 0u8..10).prop_map(|(head, offset, kind)| {
        if kind == 0 {
            [head, head]
        } else {
            [head, head + offset]
        }
    })
}

/// 1 to `max` bones (at least 1).
pub fn bones(max: usize) -> impl Strategy<Value = Vec<[Vec3; 2]>> {
    proptest::collection::vec(bone(), 1..=max.max(1))
}

/// 0 to `max` vertices in `[-12, 12]³`.
pub fn vertices(max: usize) -> impl Strategy<Value = Vec<Vec3>> {
    proptest::collection::vec(vec3_in(12.0), 0..=max)
}

/// A valid influence count, 1 to [`MAX_INFLUENCES`].
pub fn k() -> impl Strategy<Value = usize> {
    1..=MAX_INFLUENCES
}

/// An invalid influence count: 0 or more than [`MAX_INFLUENCES`].
pub fn bad_k() -> impl Strategy<Value = usize> {
    prop_oneof![Just(0usize), (MAX_INFLUENCES + 1)..64]
}

/// Normalised, sorted influences on joints below `joints` (at least 1), as this crate builds
/// them.
pub fn influences(joints: u16) -> impl Strategy<Value = Influences> {
    let joints = joints.max(1);
    proptest::collection::vec((0..joints, 0.0f32..1.0), 1..=MAX_INFLUENCES).prop_map(|pairs| {
        let mut inf = Influences::NONE;
        let mut filled = 0;
        for (j, w) in pairs {
            // One slot per joint, every slot positive.
            if inf.joints[..filled].contains(&j) {
                continue;
            }
            inf.joints[filled] = j;
            inf.weights[filled] = w + 0.01;
            filled += 1;
        }
        crate::nearest::normalise(&mut inf);
        inf
    })
}

/// Influences with a negative, NaN or infinite weight.
pub fn bad_influences(joints: u16) -> impl Strategy<Value = Influences> {
    let bad = prop_oneof![
        Just(f32::NAN),
        Just(f32::INFINITY),
        Just(f32::NEG_INFINITY),
        -10.0f32..-1e-6,
    ];
    (influences(joints), bad, 0..MAX_INFLUENCES).prop_map(|(mut inf, bad, slot)| {
        inf.weights[slot] = bad;
        inf
    })
}

/// `(bone, value)` contributions for one vertex: 1 to 40 pairs on bones below `bones`, values in
/// `[0, 10]`, at least one positive.
pub fn contributions(bones: u32) -> impl Strategy<Value = Vec<(u32, f32)>> {
    let bones = bones.max(1);
    proptest::collection::vec((0..bones, 0.0f32..10.0), 1..40).prop_map(|mut pairs| {
        if let Some(first) = pairs.first_mut() {
            first.1 += 0.5;
        }
        pairs
    })
}

/// A rigid transform: any rotation and a translation in `[-10, 10]³`.
pub fn rigid_transform() -> impl Strategy<Value = Affine3A> {
    ((-3.2f32..3.2, -1.6f32..1.6, -3.2f32..3.2), vec3_in(10.0)).prop_map(|((a, b, c), t)| {
        Affine3A::from_rotation_translation(Quat::from_euler(EulerRot::XYZ, a, b, c), t)
    })
}

/// A float that is NaN or ±infinity.
pub fn non_finite_f32() -> impl Strategy<Value = f32> {
    prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY)]
}

/// A vector with at least one NaN or infinite coordinate.
pub fn non_finite_vec3() -> impl Strategy<Value = Vec3> {
    (vec3_in(10.0), non_finite_f32(), 0usize..3).prop_map(|(v, bad, axis)| {
        let mut a = v.to_array();
        a[axis] = bad;
        Vec3::from_array(a)
    })
}
