//! Test bodies built by hand.
#![allow(dead_code)]

use creature_autorig::glam::Vec3;

/// A body mesh: positions and triangles.
pub(crate) type Mesh = (Vec<Vec3>, Vec<[u32; 3]>);

/// A closed capsule mesh along Z, centred on the origin: `rings` rings of `segments` vertices
/// (the end rings shrunk onto hemispherical caps) plus a tip vertex at each end (tail tip first,
/// at index 0, head tip second), triangulated. `length` is tip to tip. The ring vertex `k`
/// of each ring sits at angle `2πk / segments` from +X towards +Y, so vertex 0 of a ring is on
/// its +X side.
pub(crate) fn capsule_mesh(radius: f32, length: f32, rings: usize, segments: usize) -> Mesh {
    let rings = rings.max(2);
    let segments = segments.max(3);
    let half = length * 0.5;
    let mut positions = vec![Vec3::new(0.0, 0.0, -half), Vec3::new(0.0, 0.0, half)];
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
