//! Proptest strategies for this crate's inputs (feature `proptest`).
//!
//! Valid inputs ([`lattice`], [`deformed_lattice`], [`body_lattice`], [`local_point`]) and
//! adversarial ones for the error paths ([`non_finite_vec3`], [`degenerate_axes`],
//! [`bad_divisions`]), so a downstream property suite can generate lattices the way this
//! crate's own suite does.
//!
//! ```
//! use creature_ffd::strategies;
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::deterministic();
//! runner.run(&(strategies::lattice(), strategies::local_point()), |(lattice, local)| {
//!     let p = lattice.world_coords(local);
//!     prop_assert_eq!(lattice.deform(p), p);
//!     Ok(())
//! }).unwrap();
//! ```

use alloc::vec::Vec;

use glam::{EulerRot, Mat3, Quat, Vec3};
use proptest::prelude::*;

use crate::{Axis, Lattice, MAX_DIVISIONS};

/// Divisions `[l, m, n]`, each in `1..=6` (kept small so properties stay fast).
pub fn divisions() -> impl Strategy<Value = [usize; 3]> {
    [1usize..=6, 1usize..=6, 1usize..=6]
}

/// A finite coordinate in `[-range, range]`.
fn coordinate(range: f32) -> impl Strategy<Value = f32> {
    -range..=range
}

/// A point with every coordinate in `[-range, range]`.
pub fn vec3_in(range: f32) -> impl Strategy<Value = Vec3> {
    (coordinate(range), coordinate(range), coordinate(range))
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A well-conditioned frame: origin in `[-100, 100]³`, three edges of length 0.1 to 50,
/// rotated at random and sheared by at most 0.5 of another edge. Always accepted by
/// [`Lattice::new`].
pub fn frame() -> impl Strategy<Value = (Vec3, [Vec3; 3])> {
    let angles = (-3.2f32..3.2, -1.6f32..1.6, -3.2f32..3.2);
    let lengths = (0.1f32..50.0, 0.1f32..50.0, 0.1f32..50.0);
    let shears = (-0.5f32..0.5, -0.5f32..0.5);
    (vec3_in(100.0), angles, lengths, shears).prop_map(|(origin, (a, b, c), (x, y, z), (p, q))| {
        let rotation = Mat3::from_quat(Quat::from_euler(EulerRot::XYZ, a, b, c));
        let s = rotation * Vec3::X * x;
        let t = rotation * Vec3::Y * y + s.normalize() * (p * y);
        let u = rotation * Vec3::Z * z + t.normalize() * (q * z);
        (origin, [s, t, u])
    })
}

/// A valid, undeformed lattice on a random [`frame`] with random [`divisions`].
pub fn lattice() -> impl Strategy<Value = Lattice> {
    (frame(), divisions()).prop_filter_map("frame rejected", |((origin, axes), divisions)| {
        Lattice::new(origin, axes, divisions).ok()
    })
}

/// Local coordinates in the closed unit cube: a point inside any lattice via
/// [`Lattice::world_coords`].
pub fn local_point() -> impl Strategy<Value = Vec3> {
    (0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0).prop_map(|(s, t, u)| Vec3::new(s, t, u))
}

/// A [`lattice`] whose control points are each moved by up to `fraction` of a cell along each
/// edge. Fractions up to about 0.1 give mild, fold-free, invertible deformations.
pub fn deformed_lattice(fraction: f32) -> impl Strategy<Value = Lattice> {
    lattice().prop_flat_map(move |lattice| {
        let count = lattice.control_point_count();
        let unit = -fraction..=fraction;
        (
            Just(lattice),
            proptest::collection::vec((unit.clone(), unit.clone(), unit), count),
        )
            .prop_map(|(mut lattice, moves)| {
                let [l, m, n] = lattice.divisions();
                let [s, t, u] = lattice.axes();
                let cell = [s / l as f32, t / m as f32, u / n as f32];
                let mut idx = 0;
                for k in 0..=n {
                    for j in 0..=m {
                        for i in 0..=l {
                            let (a, b, c) = moves[idx];
                            idx += 1;
                            let Some(p) = lattice.control_point([i, j, k]) else {
                                continue;
                            };
                            let moved = p + cell[0] * a + cell[1] * b + cell[2] * c;
                            // Cannot fail: the index is in range and the point finite.
                            let _ = lattice.set_control_point([i, j, k], moved);
                        }
                    }
                }
                lattice
            })
    })
}

/// The creature body's 3×3×11 lattice, shaped the seed's way: every slice scaled across the
/// body by positive factors in `[0.3, 2]` and the slices spaced by positive gaps, so it never
/// folds (see the [`slices`](crate::slices) docs). Proportions are a body's: an overall size of
/// 0.1 to 10, each edge 0.3 to 3 times that, gaps 0.2 to 2 times an even spacing.
pub fn body_lattice() -> impl Strategy<Value = Lattice> {
    let angles = (-3.2f32..3.2, -1.6f32..1.6, -3.2f32..3.2);
    let shape = (0.1f32..10.0, 0.3f32..3.0, 0.3f32..3.0, 0.3f32..3.0);
    (
        vec3_in(10.0),
        angles,
        shape,
        proptest::collection::vec((0.3f32..2.0, 0.3f32..2.0), 11),
        proptest::collection::vec(0.2f32..2.0, 10),
    )
        .prop_filter_map(
            "frame rejected",
            |(origin, (a, b, c), (size, x, y, z), scales, gaps)| {
                let rotation = Mat3::from_quat(Quat::from_euler(EulerRot::XYZ, a, b, c));
                let axes = [
                    rotation * Vec3::X * (size * x),
                    rotation * Vec3::Y * (size * y),
                    rotation * Vec3::Z * (size * z),
                ];
                let mut lattice = Lattice::new(origin, axes, [2, 2, 10]).ok()?;
                for (k, (x, y)) in scales.into_iter().enumerate() {
                    lattice.scale_slice(Axis::U, k, Vec3::new(x, y, 1.0)).ok()?;
                }
                let spacing = axes[2].length() / 10.0;
                let gaps: Vec<f32> = gaps.into_iter().map(|g| g * spacing).collect();
                lattice.distribute_slices(Axis::U, &gaps).ok()?;
                Some(lattice)
            },
        )
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

/// Three edge vectors spanning no volume: one zero, two parallel, or all three coplanar.
pub fn degenerate_axes() -> impl Strategy<Value = [Vec3; 3]> {
    (
        vec3_in(10.0),
        vec3_in(10.0),
        -2.0f32..2.0,
        -2.0f32..2.0,
        0usize..3,
    )
        .prop_map(|(a, b, x, y, kind)| match kind {
            0 => [a, Vec3::ZERO, b],
            1 => [a, a * x, b],
            _ => [a, b, a * x + b * y],
        })
}

/// Divisions with at least one axis at 0 or above [`MAX_DIVISIONS`].
pub fn bad_divisions() -> impl Strategy<Value = [usize; 3]> {
    let bad = prop_oneof![Just(0usize), (MAX_DIVISIONS + 1)..=(4 * MAX_DIVISIONS)];
    (divisions(), bad, 0usize..3).prop_map(|(mut d, bad, axis)| {
        d[axis] = bad;
        d
    })
}
