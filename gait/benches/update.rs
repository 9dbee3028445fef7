//! 1,000 hexapods (6,000 leg-updates) walking over a height field, one update per creature per
//! iteration, one core: the height field's own downward query (`Ground::cast_down`, one
//! bilinear lookup) against a plain reference ground (a fixed-step ray march of the same height
//! field, as one would first write it, through `FnGround`), in the same run.
//!
//! Run: `cargo bench -p creature-gait --bench update -- --warm-up-time 1 --measurement-time 3`

// Setup outside the timed code may fail loudly: a broken input is a broken bench.
#![allow(clippy::expect_used)]

use core::hint::black_box;

use creature_gait::glam::{Quat, Vec2, Vec3};
use creature_gait::{Controller, FnGround, GaitOptions, Ground, HeightField, Leg, Pose, RayHit};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

const CREATURES: usize = 1000;
const DT: f32 = 1.0 / 60.0;

fn hexapod() -> Vec<Leg> {
    let mut legs = Vec::new();
    for k in 0..3 {
        let z = 0.9 - 0.9 * k as f32;
        for side in [1.0f32, -1.0] {
            legs.push(Leg::new(
                Vec3::new(0.25 * side, 0.0, z),
                Vec3::new(0.35 * side, -0.8, z),
                0.5,
                0.5,
            ));
        }
    }
    legs
}

fn terrain() -> HeightField {
    HeightField::from_fn(Vec2::splat(-100.0), 0.5, 401, 401, |x, z| {
        0.3 * (x * 0.37).sin() * (z * 0.29).cos() + 0.05 * (x * 2.1 + z * 1.7).sin()
    })
    .expect("valid field")
}

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

struct Herd {
    controllers: Vec<Controller>,
    positions: Vec<Vec3>,
    velocities: Vec<Vec3>,
}

fn herd(ground: &impl Ground, field: &HeightField) -> Herd {
    let legs = hexapod();
    let mut herd = Herd {
        controllers: Vec::new(),
        positions: Vec::new(),
        velocities: Vec::new(),
    };
    for i in 0..CREATURES {
        let position = Vec3::new(
            (i % 40) as f32 * 4.0 - 80.0,
            0.0,
            (i / 40) as f32 * 6.0 - 80.0,
        );
        let velocity = Vec3::new(0.0, 0.0, 0.5 + (i % 7) as f32 * 0.2);
        let mut c = Controller::new(&legs, &GaitOptions::DEFAULT).expect("valid legs");
        // Warm up: a second of walking so steps are under way.
        let mut p = position;
        for _ in 0..60 {
            p += velocity * DT;
            let y = field.height(p.x, p.z).expect("on the field") + 0.8;
            c.update(
                DT,
                Pose::new(Vec3::new(p.x, y, p.z), Quat::IDENTITY),
                velocity,
                Vec3::ZERO,
                ground,
            )
            .expect("valid update");
        }
        herd.controllers.push(c);
        herd.positions.push(p);
        herd.velocities.push(velocity);
    }
    herd
}

fn step(herd: &mut Herd, ground: &impl Ground, field: &HeightField) {
    for ((c, p), v) in herd
        .controllers
        .iter_mut()
        .zip(&mut herd.positions)
        .zip(&herd.velocities)
    {
        *p += *v * DT;
        if p.z > 90.0 {
            p.z -= 170.0;
        }
        let y = field.height(p.x, p.z).unwrap_or(0.0) + 0.8;
        let pose = Pose::new(Vec3::new(p.x, y, p.z), Quat::IDENTITY);
        black_box(c.update(DT, pose, *v, Vec3::ZERO, ground)).expect("valid update");
    }
}

fn bench(c: &mut Criterion) {
    let field = terrain();
    let reference = FnGround(|o: Vec3, d: Vec3, m: f32| marched(&field, o, d, m));
    let mut group = c.benchmark_group("1000_hexapods_height_field");
    group.throughput(Throughput::Elements((CREATURES * 6) as u64));
    group.sample_size(20);
    let mut exact = herd(&field, &field);
    group.bench_function("creature_gait_exact_cast", |b| {
        b.iter(|| step(&mut exact, &field, &field));
    });
    let mut slow = herd(&reference, &field);
    group.bench_function("reference_ray_march", |b| {
        b.iter(|| step(&mut slow, &reference, &field));
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
