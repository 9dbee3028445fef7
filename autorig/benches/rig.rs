//! Rigging a 5,000-vertex body, against a plain reference implementation of the seed's rules in
//! the same run (straight chord, every socket found by scanning every vertex).
//!
//! Run: `cargo bench -p creature-autorig --bench rig`

// Setup outside the timed code may fail loudly: a broken input is a broken bench.
#![allow(clippy::expect_used)]

use core::hint::black_box;

use creature_autorig::glam::Vec3;
use creature_autorig::{RigOptions, rig};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

#[path = "../tests/support/mod.rs"]
mod support;

/// A small deterministic generator (xorshift32), so inputs are the same on every run.
struct Xorshift(u32);

impl Xorshift {
    fn next_f32(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        (self.0 >> 8) as f32 / (1u32 << 24) as f32
    }
}

/// A 5,002-vertex capsule body (50 rings of 100), bulged and bent a little at random.
fn body() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let (mut positions, triangles) = support::capsule_mesh(0.5, 4.0, 50, 100);
    let mut rng = Xorshift(0x9e37_79b9);
    let bulge: Vec<f32> = (0..8).map(|_| 0.8 + 0.4 * rng.next_f32()).collect();
    for p in &mut positions {
        let u = (p.z + 2.0) / 4.0 * 7.0;
        let k = (u as usize).min(6);
        let f = u - k as f32;
        let scale = bulge[k] * (1.0 - f) + bulge[k + 1] * f;
        *p = Vec3::new(
            p.x * scale,
            p.y * scale + 0.2 * (1.0 - (p.z / 2.0).powi(2)),
            p.z,
        );
    }
    (positions, triangles)
}

/// The seed's rules written plainly: tips in a tube around the Z line through the bounding-box
/// centre, joints evenly on the straight chord, and for each socket bone the vertex nearest to
/// a point far out on each side, found by scanning every vertex.
/// A reference socket: left, right and top points, and the width.
type ReferenceSocket = (Vec3, Vec3, Vec3, f32);

fn reference(positions: &[Vec3], bone_length: f32) -> (Vec<Vec3>, Vec<ReferenceSocket>) {
    let (min, max) = positions
        .iter()
        .fold((positions[0], positions[0]), |(a, b), &p| {
            (a.min(p), b.max(p))
        });
    let centre = (min + max) * 0.5;
    let half_width = 0.25 * (max - min).x.max((max - min).y);
    let near: Vec<Vec3> = positions
        .iter()
        .copied()
        .filter(|p| (p.x - centre.x).abs() <= half_width && (p.y - centre.y).abs() <= half_width)
        .collect();
    let tail = near
        .iter()
        .copied()
        .fold(near[0], |a, p| if p.z < a.z { p } else { a });
    let head = near
        .iter()
        .copied()
        .fold(near[0], |a, p| if p.z > a.z { p } else { a });
    let bones = ((head.distance(tail) / bone_length).round() as usize).clamp(3, 24);
    let joints: Vec<Vec3> = (0..=bones)
        .map(|i| tail.lerp(head, i as f32 / bones as f32))
        .collect();
    let far = 10.0 * (max - min).length();
    let nearest = |target: Vec3| {
        positions.iter().copied().fold(positions[0], |a, p| {
            if p.distance(target) < a.distance(target) {
                p
            } else {
                a
            }
        })
    };
    let sockets = (1..bones - 1)
        .map(|b| {
            let mid = (joints[b] + joints[b + 1]) * 0.5;
            // The creature's left is +X (right-handed, Y up, +Z forward).
            let left = nearest(mid + Vec3::X * far);
            let right = nearest(mid - Vec3::X * far);
            let top = nearest(mid + Vec3::Y * far);
            (left, right, top, left.distance(right))
        })
        .collect();
    (joints, sockets)
}

fn bench(c: &mut Criterion) {
    let (positions, triangles) = body();
    assert_eq!(positions.len(), 5_002);
    let options = RigOptions::default();
    let mut group = c.benchmark_group("rig_5k_vertices");
    group.throughput(Throughput::Elements(positions.len() as u64));
    group.sample_size(30);
    group.bench_function("creature_autorig_rig", |b| {
        b.iter(|| rig(black_box(&positions), black_box(&triangles), &options).expect("valid body"));
    });
    group.bench_function("creature_autorig_rig_point_cloud", |b| {
        b.iter(|| rig(black_box(&positions), &[], &options).expect("valid body"));
    });
    group.bench_function("reference_seed_scan", |b| {
        b.iter(|| reference(black_box(&positions), options.bone_length));
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
