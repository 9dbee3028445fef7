//! `generate` (3D) per kind over 16 fixed seeds, and `generate_2d` end to end, without a texture and with a 256² texture and normal map, over
//! 16 fixed seeds; the texture pass alone (`d2::render_texture`, 256², the same 16 creatures);
//! and, as the reference in the same run, the texture rendered the seed's way (every ball's
//! `exp` at every pixel, field sum and colour blend, no culling).

#![allow(clippy::expect_used)]

use core::hint::black_box;

use creature::d3::{Animator, Intent};
use creature::glam::Vec2;
use creature::glam::Vec3;
use creature::metaball::{Ball2, Falloff};
use creature::{d2, d3, generate, generate_2d};
use criterion::{Criterion, criterion_group, criterion_main};

const SEEDS: u64 = 16;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("generate_2d");
    let plain = d2::Params::DEFAULT.with_texture(false);
    let textured = d2::Params::DEFAULT;
    group.bench_function("no_texture_per_creature", |b| {
        let mut seed = 0;
        b.iter(|| {
            seed = (seed + 1) % SEEDS;
            black_box(generate_2d(black_box(seed), &plain).expect("valid"))
        });
    });
    group.bench_function("texture_256_per_creature", |b| {
        let mut seed = 0;
        b.iter(|| {
            seed = (seed + 1) % SEEDS;
            black_box(generate_2d(black_box(seed), &textured).expect("valid"))
        });
    });
    // The texture pass alone: albedo and normal map of the same 16 creatures, as
    // `generate_2d` renders them (its noise seed included).
    let creatures: Vec<_> = (0..SEEDS)
        .map(|seed| {
            let c = generate_2d(seed, &plain).expect("valid");
            let options = d2::TextureOptions::DEFAULT.with_noise_seed((seed ^ (seed >> 32)) as u32);
            (c.balls, c.bounds, options)
        })
        .collect();
    group.bench_function("texture_256_only", |b| {
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) % creatures.len();
            let (balls, bounds, options) = &creatures[i];
            black_box(d2::render_texture(black_box(balls), *bounds, options).expect("valid"))
        });
    });
    // Reference: the seed's texture pass, every ball at every pixel (value + colour blend),
    // on creature 7.
    let creature = generate_2d(7, &plain).expect("valid");
    let balls: Vec<Ball2> = creature.balls.iter().map(|b| b.ball).collect();
    let colours: Vec<creature::glam::Vec3> = creature.balls.iter().map(|b| b.colour).collect();
    let (min, max) = creature.bounds;
    group.sample_size(10);
    group.bench_function("reference_texture_256_all_balls", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for row in 0..256 {
                for col in 0..256 {
                    let p = min
                        + (max - min)
                            * Vec2::new((col as f32 + 0.5) / 256.0, (row as f32 + 0.5) / 256.0);
                    let mut sum = 0.0;
                    let mut colour = creature::glam::Vec3::ZERO;
                    for (ball, c) in balls.iter().zip(&colours) {
                        let f = Falloff::SEED.evaluate(ball.center.distance(p), ball.radius);
                        sum += f;
                        colour += *c * f;
                    }
                    acc += sum + colour.x / sum.max(1e-9);
                }
            }
            black_box(acc)
        });
    });
    group.finish();
}

/// `generate` (3D) end to end per kind: body, FFD, rig, skin, bend, head, limbs, gait set-up.
fn bench_3d(c: &mut Criterion) {
    let mut group = c.benchmark_group("generate_3d");
    for (name, kind) in [
        ("walker_per_creature", d3::Kind::Walker),
        ("flier_per_creature", d3::Kind::Flier),
        ("swimmer_per_creature", d3::Kind::Swimmer),
    ] {
        // As the issue defines it: everything but baking the clips.
        let params = d3::Params::DEFAULT.with_kind(kind).with_clips(false);
        group.bench_function(name, |b| {
            let mut seed = 0;
            b.iter(|| {
                seed = (seed + 1) % SEEDS;
                black_box(generate(black_box(seed), &params).expect("valid"))
            });
        });
    }
    // Walkers as `generate` delivers them with the default params: clips baked.
    let params = d3::Params::DEFAULT.with_kind(d3::Kind::Walker);
    group.bench_function("walker_with_clips_per_creature", |b| {
        let mut seed = 0;
        b.iter(|| {
            seed = (seed + 1) % SEEDS;
            black_box(generate(black_box(seed), &params).expect("valid"))
        });
    });
    // Baking 2 s of walk (61 frames after a 1 s warm-up) for walker 7.
    let walker = generate(
        7,
        &d3::Params::DEFAULT
            .with_kind(d3::Kind::Walker)
            .with_clips(false),
    )
    .expect("valid");
    group.bench_function("bake_walk_2s", |b| {
        b.iter(|| black_box(walker.bake_walk(black_box(2.0)).expect("walker")));
    });
    // Every clip of a kind (walkers: idle 4 s, looping walk from 4 s, turn 4 s), creature 7
    // (walker 7 made not to hop: a hopper bakes a hop too).
    for (name, kind) in [
        ("bake_clips_walker", d3::Kind::Walker),
        ("bake_clips_flier", d3::Kind::Flier),
        ("bake_clips_swimmer", d3::Kind::Swimmer),
    ] {
        let params = d3::Params::DEFAULT
            .with_kind(kind)
            .with_clips(false)
            .with_hop_chance(0.0);
        let creature = generate(7, &params).expect("valid");
        group.bench_function(name, |b| {
            b.iter(|| black_box(black_box(&creature).bake_clips().expect("clips")));
        });
    }
    group.finish();
}

/// One live update of `walker` on `ground`, walking in a circle.
fn bench_walker<G: creature::gait::Ground>(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    walker: &creature::d3::Creature,
    ground: &G,
) {
    let mut animator = Animator::new(walker).expect("a walker");
    for _ in 0..120 {
        animator
            .update(1.0 / 60.0, circling(&animator, walker.speed), ground)
            .expect("walks");
    }
    group.bench_function(name, |b| {
        b.iter(|| {
            let intent = circling(&animator, walker.speed);
            animator
                .update(black_box(1.0 / 60.0), black_box(intent), ground)
                .expect("walks");
            black_box(animator.skinning_matrices().len())
        });
    });
}

/// Forward at `speed` along the animator's heading, turning at 0.5 rad/s: a circle (of radius
/// 2 × speed) the creature keeps to, on the terrain, however long the bench runs.
fn circling(animator: &Animator, speed: f32) -> Intent {
    let heading = animator.heading();
    Intent::Move {
        velocity: Vec3::new(heading.sin(), 0.0, heading.cos()) * speed,
        turn_rate: 0.5,
    }
}

/// One live update (`d3::Animator`: gait, pose and skinning matrices) of walker 7 and of
/// median walker 32 on flat ground and on the default procedural terrain, walking in a circle
/// along its heading; of flier 7, swimmer 7 and slitherer 7 (steering, ground under and
/// ahead, wings or wave or path, pose, skinning) going round over that terrain; and, as the reference in the same
/// run, sampling a baked `walk` clip of walker 7 (`Creature::pose` at a frame, then each
/// joint's skinning matrix).
fn bench_animator(c: &mut Criterion) {
    use creature::gait::Plane;
    use creature::glam::Mat4;
    use creature::terrain::{TerrainParams, terrain};

    let mut group = c.benchmark_group("animate_3d");
    let hills = terrain(7, &TerrainParams::DEFAULT).expect("valid");
    // Walker 32 is a median walker of seeds 0-399: 4 legs, 21 joints, 3,492 vertices (the
    // medians are 4, 21 and about 3,500); walker 7 is a biped, two legs fewer.
    let median = generate(32, &d3::Params::DEFAULT.with_kind(d3::Kind::Walker)).expect("valid");
    let walker = generate(7, &d3::Params::DEFAULT.with_kind(d3::Kind::Walker)).expect("valid");
    // Each ground by its own type, as a game calls `update` (a `&dyn Ground` would add a
    // virtual call per ray).
    bench_walker(
        &mut group,
        "animator_update_walker_flat",
        &walker,
        &Plane::GROUND,
    );
    bench_walker(
        &mut group,
        "animator_update_walker_terrain",
        &walker,
        &hills,
    );
    bench_walker(
        &mut group,
        "animator_update_median_walker_flat",
        &median,
        &Plane::GROUND,
    );
    bench_walker(
        &mut group,
        "animator_update_median_walker_terrain",
        &median,
        &hills,
    );
    // Fliers and swimmers over the same hills, turning as the walker does.
    for (name, kind) in [
        ("animator_update_flier_terrain", d3::Kind::Flier),
        ("animator_update_swimmer_terrain", d3::Kind::Swimmer),
        ("animator_update_slitherer_terrain", d3::Kind::Slitherer),
    ] {
        let c = generate(7, &d3::Params::DEFAULT.with_kind(kind)).expect("valid");
        let mut animator = Animator::new(&c).expect("a flier or swimmer");
        for _ in 0..120 {
            animator
                .update(1.0 / 60.0, circling(&animator, c.speed), &hills)
                .expect("moves");
        }
        group.bench_function(name, |b| {
            b.iter(|| {
                let intent = circling(&animator, c.speed);
                animator
                    .update(black_box(1.0 / 60.0), black_box(intent), &hills)
                    .expect("moves");
                black_box(animator.skinning_matrices().len())
            });
        });
    }
    let walk = walker
        .clips
        .iter()
        .find(|clip| clip.name == "walk")
        .expect("a walk clip");
    let inverse = walker.skeleton.inverse_bind_matrices();
    group.bench_function("reference_sample_baked_walk", |b| {
        let mut frame = 0;
        b.iter(|| {
            frame = (frame + 1) % walk.frames;
            let pose = walker.pose(walk, black_box(frame));
            let skinning: Vec<Mat4> = pose
                .iter()
                .zip(&inverse)
                .map(|(p, inverse)| Mat4::from(*p) * *inverse)
                .collect();
            black_box(skinning)
        });
    });
    group.finish();
}

criterion_group!(benches, bench, bench_3d, bench_animator);
criterion_main!(benches);
