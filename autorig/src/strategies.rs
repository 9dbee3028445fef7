//! Proptest strategies for this crate's inputs (feature `proptest`).
//!
//! Valid inputs ([`capsule_body`], [`rig_options`]) and adversarial ones for the error paths
//! ([`non_finite_body`], [`bad_triangles`], [`degenerate_body`]), so a downstream property suite
//! can generate body meshes the way this crate's own suite does.
//!
//! ```
//! use creature_autorig::{rig, strategies};
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::deterministic();
//! runner.run(&(strategies::capsule_body(), strategies::rig_options()), |((positions, triangles), options)| {
//!     let rig = rig(&positions, &triangles, &options).unwrap();
//!     prop_assert!(rig.is_tree());
//!     Ok(())
//! }).unwrap();
//! ```

use alloc::vec::Vec;

use glam::{EulerRot, Quat, Vec3};
use proptest::prelude::*;

use crate::{RigOptions, RootAt};

/// A body mesh: positions and triangles.
pub type Mesh = (Vec<Vec3>, Vec<[u32; 3]>);

/// A closed capsule mesh along Z, centred on the origin: `rings` rings of `segments` vertices
/// (the end rings shrunk onto hemispherical caps) plus a tip vertex at each end (tail tip first,
/// at index 0, head tip second), triangulated. `length` is tip to tip. The ring vertex `k`
/// of each ring sits at angle `2πk / segments` from +X towards +Y, so vertex 0 of a ring is on
/// its +X side.
#[must_use]
pub fn capsule_mesh(radius: f32, length: f32, rings: usize, segments: usize) -> Mesh {
    let rings = rings.max(2);
    let segments = segments.max(3);
    let half = length * 0.5;
    let mut positions = alloc::vec![Vec3::new(0.0, 0.0, -half), Vec3::new(0.0, 0.0, half)];
    for r in 0..rings {
        // Rings evenly spaced strictly between the tips.
        let z = -half + length * (r + 1) as f32 / (rings + 1) as f32;
        let cap = (z.abs() - (half - radius)).max(0.0);
        let ring_radius = (radius * radius - cap * cap).max(0.0).sqrt();
        for k in 0..segments {
            let a = k as f32 / segments as f32 * core::f32::consts::TAU;
            positions.push(Vec3::new(ring_radius * a.cos(), ring_radius * a.sin(), z));
        }
    }
    let ring = |r: usize, k: usize| (2 + r * segments + k % segments) as u32;
    let mut triangles = Vec::new();
    for k in 0..segments {
        triangles.push([0, ring(0, k + 1), ring(0, k)]);
        triangles.push([1, ring(rings - 1, k), ring(rings - 1, k + 1)]);
        for r in 0..rings - 1 {
            triangles.push([ring(r, k), ring(r, k + 1), ring(r + 1, k + 1)]);
            triangles.push([ring(r, k), ring(r + 1, k + 1), ring(r + 1, k)]);
        }
    }
    (positions, triangles)
}

/// A creature-like body: a [`capsule_mesh`] (radius 0.1 to 1, length 4 to 12 radii, 4 to 24
/// rings of 6 to 24 vertices), squashed across (X and Y scaled by 0.6 to 1.4), bent up or down
/// in Y along its length by up to half its radius, tilted by up to 0.1 rad, and moved by up to 5
/// units. Always accepted by [`rig`](crate::rig).
pub fn capsule_body() -> impl Strategy<Value = Mesh> {
    (
        (0.1f32..1.0, 4.0f32..12.0, 4usize..24, 6usize..24),
        (0.6f32..1.4, 0.6f32..1.4, -0.5f32..0.5),
        (-0.1f32..0.1, -0.1f32..0.1, -0.1f32..0.1),
        (-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0),
    )
        .prop_map(
            |((radius, ratio, rings, segments), (sx, sy, bend), (a, b, c), (x, y, z))| {
                let length = radius * ratio;
                let (mut positions, triangles) = capsule_mesh(radius, length, rings, segments);
                let tilt = Quat::from_euler(EulerRot::XYZ, a, b, c);
                let half = length * 0.5;
                for p in &mut positions {
                    let u = p.z / half;
                    let bent = Vec3::new(p.x * sx, p.y * sy + bend * radius * (1.0 - u * u), p.z);
                    *p = tilt * bent + Vec3::new(x, y, z);
                }
                (positions, triangles)
            },
        )
}

/// Valid options: either root, tolerance 0.02 to 0.5, bone length 0.05 to 2, bone counts from
/// 2..6 up to 6..30, medial line on or off.
pub fn rig_options() -> impl Strategy<Value = RigOptions> {
    (
        any::<bool>(),
        0.02f32..0.5,
        0.05f32..2.0,
        2usize..6,
        0usize..24,
        any::<bool>(),
    )
        .prop_map(|(head, tolerance, bone_length, min, extra, medial)| {
            RigOptions::DEFAULT
                .with_root(if head { RootAt::Head } else { RootAt::Centre })
                .with_centre_tolerance(tolerance)
                .with_bone_length(bone_length)
                .with_bone_count(min, min + extra)
                .with_follow_medial_line(medial)
        })
}

/// A [`capsule_body`] with one vertex made NaN or infinite; also returns that vertex's index.
pub fn non_finite_body() -> impl Strategy<Value = (Mesh, usize)> {
    let bad = prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY)];
    (capsule_body(), any::<prop::sample::Index>(), bad, 0usize..3).prop_map(
        |((mut positions, triangles), which, bad, axis)| {
            let index = which.index(positions.len());
            let mut a = positions[index].to_array();
            a[axis] = bad;
            positions[index] = Vec3::from_array(a);
            ((positions, triangles), index)
        },
    )
}

/// A [`capsule_body`] whose triangle list gains one triangle naming a vertex past the end; also
/// returns that triangle's index.
pub fn bad_triangles() -> impl Strategy<Value = (Mesh, usize)> {
    (capsule_body(), 0u32..1000, 0usize..3).prop_map(|((positions, mut triangles), over, slot)| {
        let mut tri = [0, 1, 2];
        tri[slot] = positions.len() as u32 + over;
        triangles.push(tri);
        let index = triangles.len() - 1;
        ((positions, triangles), index)
    })
}

/// Point sets with no body: all at one point, all on one line (any direction), or all in one
/// plane of constant Z. No triangles.
pub fn degenerate_body() -> impl Strategy<Value = Vec<Vec3>> {
    let point =
        || (-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0).prop_map(|(x, y, z)| Vec3::new(x, y, z));
    (
        point(),
        point(),
        prop::collection::vec(-3.0f32..3.0, 1..40),
        0u8..3,
    )
        .prop_map(|(origin, direction, ts, kind)| match kind {
            0 => ts.iter().map(|_| origin).collect(),
            1 => ts.iter().map(|&t| origin + direction * t).collect(),
            _ => ts
                .iter()
                .enumerate()
                .map(|(i, &t)| {
                    Vec3::new(origin.x + t, origin.y + (i as f32 * 0.37).sin(), origin.z)
                })
                .collect(),
        })
}
