//! 1,000 hexapods (6,000 leg-updates) walking over a height field, one update per creature per
//! iteration, one core: the height field's own downward query (`Ground::cast_down`, one
//! bilinear lookup) against a plain reference ground (a fixed-step ray march of the same height
//! field, as one would first write it, through `FnGround`), in the same run.
//!
//! Then 1,000 hexapods at 0.5 to 5.3 m/s (Froude numbers 0.03 to 2.9: walks, trots and runs)
//! with gaits by speed against the same herd in one gait.
//!
//! Run: `cargo bench -p creature-gait --bench update -- --warm-up-time 1 --measurement-time 3`

// Setup outside the timed code may fail loudly: a broken input is a broken bench.
#![allow(clippy::expect_used)]

use core::hint::black_box;

mod herd;

use creature_gait::glam::Vec3;
use creature_gait::{FnGround, GaitOptions, GaitSpeeds, Ground, HeightField, RayHit};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use herd::{CREATURES, Herd, terrain};

/// The plain reference ground: march down in 1 cm steps until below the bilinear height.
fn marched(field: &HeightField, origin: Vec3, direction: Vec3, max: f32) -> Option<RayHit> {
    let mut t = 0.0f32;
    while t <= max {
        let p = origin + direction * t;
        if let Some(h) = field.height(p.x, p.z)
            && p.y <= h
        {
            return Some(RayHit {
                point: Vec3::new(p.x, h, p.z),
                normal: Vec3::Y,
                distance: t,
            });
        }
        t += 0.01;
    }
    None
}

fn step(herd: &mut Herd, ground: &impl Ground, field: &HeightField) {
    black_box(herd.step(ground, field)).expect("valid update");
}

fn bench(c: &mut Criterion) {
    let field = terrain().expect("valid field");
    let reference = FnGround(|o: Vec3, d: Vec3, m: f32| marched(&field, o, d, m));
    let mut group = c.benchmark_group("1000_hexapods_height_field");
    group.throughput(Throughput::Elements((CREATURES * 6) as u64));
    group.sample_size(20);
    let mut exact = Herd::new(CREATURES, &field, &field).expect("valid herd");
    group.bench_function("creature_gait_exact_cast", |b| {
        b.iter(|| step(&mut exact, &field, &field));
    });
    let mut slow = Herd::new(CREATURES, &reference, &field).expect("valid herd");
    group.bench_function("reference_ray_march", |b| {
        b.iter(|| step(&mut slow, &reference, &field));
    });
    group.finish();

    let mut group = c.benchmark_group("1000_hexapods_walk_trot_run");
    group.throughput(Throughput::Elements((CREATURES * 6) as u64));
    group.sample_size(20);
    let fast = |i: usize| 0.5 + (i % 7) as f32 * 0.8;
    let by_speed = GaitOptions::DEFAULT.with_gaits(GaitSpeeds::DEFAULT);
    let mut one =
        Herd::with(CREATURES, &field, &field, &GaitOptions::DEFAULT, fast).expect("valid herd");
    group.bench_function("one_gait", |b| {
        b.iter(|| step(&mut one, &field, &field));
    });
    let mut changing = Herd::with(CREATURES, &field, &field, &by_speed, fast).expect("valid herd");
    group.bench_function("gaits_by_speed", |b| {
        b.iter(|| step(&mut changing, &field, &field));
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
