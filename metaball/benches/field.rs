//! Sampling a 256×256 grid over a 50-ball creature-like field (the seed's median creature has
//! 49 balls): the culled field against the plain all-balls reference in
//! `tests/support/reference.rs` (every ball at every sample, as the seed does) and against the
//! crate's own exact sum; the same grid filled block by block with `Field2::sample_block`
//! (8 × 8 blocks, as `creature-march`'s tile cache asks for them), plain and through a
//! `BlockSampler`; and `value_and_gradient`
//! and top-4 `shares` at every sample (what the `creature` facade asks at each outline and
//! mesh vertex).
//!
//! Run: `cargo bench -p creature-metaball --bench field`

// Setup outside the timed code may fail loudly: a broken input is a broken bench.
#![allow(clippy::expect_used)]

use core::hint::black_box;

use creature_metaball::glam::Vec2;
use creature_metaball::{Ball2, Falloff, Field2, SEED_BLOBBINESS};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

#[path = "../tests/support/reference.rs"]
#[allow(dead_code)]
mod reference;

const SIDE: usize = 256;

/// The fixed creature and the grid (origin, step) spanning its outline's box plus a margin.
fn inputs() -> (Vec<Ball2>, Vec2, f32) {
    let balls = reference::creature();
    let mut min = Vec2::splat(f32::INFINITY);
    let mut max = Vec2::splat(f32::NEG_INFINITY);
    for b in &balls {
        min = min.min(b.center - 1.5 * b.radius);
        max = max.max(b.center + 1.5 * b.radius);
    }
    let step = (max - min).max_element() / (SIDE - 1) as f32;
    (balls, min, step)
}

/// The sum over every sample of a per-point query (each point through `black_box`), written
/// out at each use: through a shared generic helper, `value`'s loop ran 50% slower (code
/// placement), which would measure the harness rather than the field.
macro_rules! per_point {
    ($origin:expr, $step:expr, |$p:ident| $query:expr) => {{
        let mut sum = 0.0f32;
        for row in 0..SIDE {
            for column in 0..SIDE {
                let $p = black_box($origin + $step * Vec2::new(column as f32, row as f32));
                sum += $query;
            }
        }
        sum
    }};
}

/// Fills the `SIDE × SIDE` grid of `samples` block by block: `sample` fills the 8 × 8 block
/// whose first sample is at the given corner.
fn by_blocks(
    origin: Vec2,
    step: f32,
    samples: &mut [f32],
    mut sample: impl FnMut(Vec2, &mut [f32]) -> Result<(), creature_metaball::MetaballError>,
) {
    let mut block = [0.0f32; 64];
    for by in 0..SIDE / 8 {
        for bx in 0..SIDE / 8 {
            let corner = origin + step * Vec2::new((bx * 8) as f32, (by * 8) as f32);
            sample(corner, &mut block).expect("valid block");
            for (row, chunk) in block.chunks_exact(8).enumerate() {
                let at = (by * 8 + row) * SIDE + bx * 8;
                samples[at..at + 8].copy_from_slice(chunk);
            }
        }
    }
    black_box(&samples);
}

fn bench(c: &mut Criterion) {
    let (balls, origin, step) = inputs();
    let field = Field2::new(&balls, Falloff::SEED).expect("valid creature");
    let mut group = c.benchmark_group(format!("field_256x256_{}_balls", balls.len()));
    group.throughput(Throughput::Elements((SIDE * SIDE) as u64));
    group.sample_size(20);
    group.bench_function("culled_sample_grid", |b| {
        b.iter(|| {
            field
                .sample_grid(black_box(origin), black_box(step), SIDE, SIDE)
                .expect("valid grid")
        });
    });
    group.bench_function("culled_sample_block_8x8", |b| {
        // The same samples, as 1,024 blocks of 8 × 8 (as a contour tracer's tile cache asks).
        let mut samples = vec![0.0f32; SIDE * SIDE];
        b.iter(|| {
            by_blocks(origin, step, &mut samples, |corner, block| {
                field.sample_block(black_box(corner), black_box(step), 8, 8, block)
            });
        });
    });
    group.bench_function("culled_block_sampler_8x8", |b| {
        // The same 1,024 blocks through a `BlockSampler` (a new one per pass, as per trace):
        // each ball's column factors are reused down the grid, row factors along it.
        let mut samples = vec![0.0f32; SIDE * SIDE];
        b.iter(|| {
            let mut sampler = field.block_sampler();
            by_blocks(origin, step, &mut samples, |corner, block| {
                sampler.sample_block(black_box(corner), black_box(step), 8, 8, block)
            });
        });
    });
    group.bench_function("culled_value_per_point", |b| {
        b.iter(|| per_point!(origin, step, |p| field.value(p)));
    });
    group.bench_function("culled_value_and_gradient_per_point", |b| {
        b.iter(|| {
            per_point!(origin, step, |p| {
                let (v, g) = field.value_and_gradient(p);
                v + g.x + g.y
            })
        });
    });
    group.bench_function("culled_shares_4_per_point", |b| {
        b.iter(|| {
            per_point!(origin, step, |p| {
                field.shares(p, 4).first().map_or(0.0, |s| s.weight)
            })
        });
    });
    group.bench_function("exact_all_balls", |b| {
        b.iter(|| per_point!(origin, step, |p| field.value_exact(p)));
    });
    group.bench_function("reference_all_balls", |b| {
        b.iter(|| {
            let mut samples = Vec::with_capacity(SIDE * SIDE);
            for row in 0..SIDE {
                for column in 0..SIDE {
                    let p = origin + step * Vec2::new(column as f32, row as f32);
                    samples.push(reference::value(&balls, SEED_BLOBBINESS, black_box(p)));
                }
            }
            samples
        });
    });
    group.finish();

    let stats = field.grid_stats();
    println!(
        "grid: {} balls, cell {:.1}, {} cells, {} entries ({:.1} per cell); error bound {:e}",
        balls.len(),
        stats.cell_size,
        stats.cells,
        stats.entries,
        stats.entries as f32 / stats.cells as f32,
        field.error_bound()
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
