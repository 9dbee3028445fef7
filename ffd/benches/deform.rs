//! Deforming 100,000 points with the creature body's 3×3×11 lattice, against the plain
//! reference implementation in `tests/support/reference.rs` (binomials and `powf` per control
//! point per point).
//!
//! Also the lattice's fold check (`fold_report(8)`) against sampling `jacobian_local` at
//! every point of its grid.
//!
//! Run: `cargo bench -p creature-ffd --bench deform`

// Setup outside the timed code may fail loudly: a broken input is a broken bench.
#![allow(clippy::expect_used)]

use core::hint::black_box;

use creature_ffd::glam::Vec3;
use creature_ffd::{Axis, Lattice};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

#[path = "../tests/support/reference.rs"]
mod reference;

const POINTS: usize = 100_000;

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

/// The body lattice shaped the seed's way (random slice scales, random positive gaps) and
/// `POINTS` points inside it.
fn inputs() -> (Lattice, Vec<Vec3>) {
    let mut rng = Xorshift(0x9e37_79b9);
    let mut lattice = Lattice::new(
        Vec3::new(-0.5, -0.5, -2.0),
        [Vec3::X, Vec3::Y, Vec3::Z * 4.0],
        [2, 2, 10],
    )
    .expect("valid lattice");
    for k in 0..11 {
        let scale = Vec3::new(0.5 + rng.next_f32(), 0.5 + rng.next_f32(), 1.0);
        lattice
            .scale_slice(Axis::U, k, scale)
            .expect("positive scale");
    }
    let gaps: Vec<f32> = (0..10).map(|_| 0.2 + 0.4 * rng.next_f32()).collect();
    lattice
        .distribute_slices(Axis::U, &gaps)
        .expect("positive gaps");
    let points = (0..POINTS)
        .map(|_| lattice.world_coords(Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32())))
        .collect();
    (lattice, points)
}

fn bench(c: &mut Criterion) {
    let (lattice, points) = inputs();
    let mut group = c.benchmark_group("deform_100k_3x3x11");
    group.throughput(Throughput::Elements(POINTS as u64));
    group.sample_size(20);
    // One buffer reused by every iteration, refilled from the inputs with `copy_from_slice`
    // (included in the timing; about 1.2 MB copied, a few percent of the total): a fresh
    // allocation per iteration would time the allocator and page faults, not the deformation.
    let mut buffer = points.clone();
    group.bench_function("creature_ffd_deform_in_place", |b| {
        b.iter(|| {
            buffer.copy_from_slice(&points);
            lattice.deform_in_place(black_box(&mut buffer));
        });
    });
    group.bench_function("reference_powf", |b| {
        b.iter(|| {
            buffer.copy_from_slice(&points);
            for p in buffer.iter_mut() {
                *p = reference::deform(
                    lattice.origin(),
                    lattice.axes(),
                    lattice.divisions(),
                    lattice.control_points(),
                    black_box(*p),
                );
            }
        });
    });
    group.finish();
}

/// The body lattice's fold check as the generator runs it (8³ samples), against the same
/// grid sampled by `jacobian_local` point by point.
fn bench_fold(c: &mut Criterion) {
    let (lattice, _) = inputs();
    let mut group = c.benchmark_group("fold_report_8_3x3x11");
    group.bench_function("creature_ffd_fold_report", |b| {
        b.iter(|| black_box(black_box(&lattice).fold_report(8)));
    });
    group.bench_function("reference_jacobian_per_sample", |b| {
        b.iter(|| {
            let step = 1.0 / 7.0;
            let mut min = f32::INFINITY;
            for a in 0..8 {
                for b in 0..8 {
                    for c in 0..8 {
                        let local = Vec3::new(a as f32, b as f32, c as f32) * step;
                        min = min.min(black_box(&lattice).jacobian_local(local).determinant());
                    }
                }
            }
            black_box(min)
        });
    });
    group.finish();
}

criterion_group!(benches, bench, bench_fold);
criterion_main!(benches);
