//! Outlining a 50-ball creature-like field on a 256×256 grid (issue 3's outline bench):
//! `trace` against `march_grid` against the `contour` crate (contour-rs), at the same
//! resolution on the same field.
//!
//! The field is `creature-metaball`'s culled `Field2` (the seed's falloff) over the layout of
//! `tests/support`'s seed-style skeleton, as the `creature` facade will build it. The grid is
//! sampled once, outside the timed code, with `Field2::sample_grid`.
//!
//! - `march_grid`, `contour_rs_contours` (`ContourBuilder::contours`, smoothed: linear
//!   interpolation like ours, holes assigned to their polygons like ours; the crate's `f32`
//!   feature is off, so it reads `f64` samples, converted outside the timed code),
//!   `contour_rs_lines` (`ContourBuilder::lines`: rings only) and the plain
//!   `reference_marching_squares` of `tests/support/reference.rs` all read the pre-sampled
//!   grid.
//! - `trace_field` calls `Field2::value` itself, only along the outline (and the nodes a hole
//!   scan needs); `trace_grid_lookup` reads the pre-sampled grid instead, node by node through a
//!   lookup closure, and `trace_tiles_grid` copies the pre-sampled grid into the tracer's tiles
//!   (eight rows of eight samples a tile), to separate the following from the sampling. All
//!   trace on the grid's own nodes (same step, same origin).
//! - `trace_tiles_field` (and `_no_hole_scan`) trace through `trace_field` with
//!   `tests/support`'s `TiledField` newtype, which fills each 8×8 node tile the trace touches
//!   through one `BlockSampler` per trace and proves tiles inside with its
//!   `block_is_at_least`; `trace_tiles_field_uncached` fills each with a plain
//!   `Field2::sample_block` call and proves nothing.
//! - `sample_grid_then_march_grid` and `sample_grid_then_contour_rs` are the full-grid
//!   pipelines `trace_field` replaces; `block_sweep_then_contour_rs` samples the grid faster,
//!   8 × 8 block by block through one `BlockSampler` (`sample_grid` and `block_sweep` time the
//!   sampling alone).
//!
//! Run: `cargo bench -p creature-march --bench outline`

// Setup outside the timed code may fail loudly: a broken input is a broken bench.
#![allow(clippy::expect_used)]

extern crate alloc;

use core::hint::black_box;

use contour::ContourBuilder;
use creature_march::glam::Vec2;
use creature_march::{
    MarchOptions, TILE_NODES, TILE_SIZE, TileField, march_grid, trace, trace_field, trace_with,
};
use creature_metaball::{Ball2, Falloff, Field2};
use criterion::{Criterion, criterion_group, criterion_main};

#[path = "../tests/support/mod.rs"]
mod support;

const SIZE: usize = 256;

/// The pre-sampled grid as a tile-filling field: a tile is eight row copies (NaN, outside,
/// beyond the grid). Between nodes (hints), the nearest node.
struct GridTiles<'a> {
    values: &'a [f32],
    /// The grid's first node.
    origin: (i32, i32),
    step: f32,
}

impl GridTiles<'_> {
    fn at(&self, x: i32, y: i32) -> f32 {
        let (x, y) = (x - self.origin.0, y - self.origin.1);
        if (0..SIZE as i32).contains(&x) && (0..SIZE as i32).contains(&y) {
            self.values[y as usize * SIZE + x as usize]
        } else {
            f32::NAN
        }
    }
}

impl TileField for GridTiles<'_> {
    fn value(&self, p: Vec2) -> f32 {
        let node = (p / self.step).round();
        self.at(node.x as i32, node.y as i32)
    }

    fn prefers_tiles(&self) -> bool {
        true
    }

    fn sample_tile(&self, [i, j]: [i32; 2], _step: f32, out: &mut [f32; TILE_NODES]) {
        let x = i - self.origin.0;
        let inside_columns = x >= 0 && x as usize + TILE_SIZE <= SIZE;
        for (row, samples) in out.chunks_exact_mut(TILE_SIZE).enumerate() {
            let y = j + row as i32 - self.origin.1;
            if inside_columns && (0..SIZE as i32).contains(&y) {
                let start = y as usize * SIZE + x as usize;
                samples.copy_from_slice(&self.values[start..start + TILE_SIZE]);
            } else {
                for (col, sample) in samples.iter_mut().enumerate() {
                    *sample = self.at(i + col as i32, j + row as i32);
                }
            }
        }
    }
}

/// A creature with about 50 balls, its culled field, and the grid that covers it: origin node
/// (in steps) and step.
fn inputs() -> (support::Balls, Field2, (i32, i32), f32) {
    let mut seed = 1;
    let balls = loop {
        let b = support::creature(seed);
        if (45..=55).contains(&b.0.len()) {
            break b;
        }
        seed += 1;
    };
    let metaballs: Vec<Ball2> = balls
        .0
        .iter()
        .enumerate()
        .map(|(i, &(c, r))| Ball2::new(c, r, i as u32))
        .collect();
    let field = Field2::new(&metaballs, Falloff::SEED).expect("valid balls");
    let centres = balls.centres();
    let lo = centres.iter().fold(Vec2::MAX, |a, &c| a.min(c)) - Vec2::splat(60.0);
    let hi = centres.iter().fold(Vec2::MIN, |a, &c| a.max(c)) + Vec2::splat(60.0);
    let step = (hi - lo).max_element() / (SIZE - 1) as f32;
    let origin = ((lo.x / step).floor() as i32, (lo.y / step).floor() as i32);
    (balls, field, origin, step)
}

fn bench(c: &mut Criterion) {
    let (balls, field, origin, step) = inputs();
    let corner = Vec2::new(origin.0 as f32, origin.1 as f32) * step;
    let sample = |f: &Field2| {
        f.sample_grid(corner, step, SIZE, SIZE)
            .expect("a valid grid")
    };
    let values = sample(&field);
    // The same grid, swept 8 × 8 block by block through one `BlockSampler` (a new one per
    // sweep): the other way this crate's dependency offers to sample a grid.
    let sweep = |f: &Field2| {
        let mut sampler = f.block_sampler();
        let mut v = vec![0.0f32; SIZE * SIZE];
        let mut block = [0.0f32; TILE_NODES];
        for ty in 0..SIZE / TILE_SIZE {
            for tx in 0..SIZE / TILE_SIZE {
                let first = Vec2::new((tx * TILE_SIZE) as f32, (ty * TILE_SIZE) as f32);
                sampler
                    .sample_block(
                        corner + first * step,
                        step,
                        TILE_SIZE,
                        TILE_SIZE,
                        &mut block,
                    )
                    .expect("a valid block");
                for (r, row) in block.chunks_exact(TILE_SIZE).enumerate() {
                    let at = (ty * TILE_SIZE + r) * SIZE + tx * TILE_SIZE;
                    v[at..at + TILE_SIZE].copy_from_slice(row);
                }
            }
        }
        v
    };
    let swept = sweep(&field);
    let worst = values
        .iter()
        .zip(&swept)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    assert!(worst < 1e-4, "the sweep samples the grid: {worst}");
    let values64: Vec<f64> = values.iter().map(|&v| f64::from(v)).collect();
    let hints = balls.centres();
    let culled = |p: Vec2| field.value(p);
    // Nodes sit on the grid's samples; rounding by truncation (no libm call).
    let lookup = |p: Vec2| {
        let x = p.x / step - origin.0 as f32 + 0.5;
        let y = p.y / step - origin.1 as f32 + 0.5;
        if !(x >= 0.0 && y >= 0.0 && x < SIZE as f32 && y < SIZE as f32) {
            return f32::NEG_INFINITY;
        }
        values[y as usize * SIZE + x as usize]
    };
    let builder = ContourBuilder::new(SIZE, SIZE, true);
    let grid_tiles = GridTiles {
        values: &values,
        origin,
        step,
    };

    // The same outline, four ways.
    let grid = march_grid(&values, SIZE, SIZE, 1.0).expect("valid grid");
    let looked_up = trace(lookup, &hints, step, 1.0).expect("valid trace");
    let copied =
        trace_field(&grid_tiles, &hints, step, 1.0, &MarchOptions::DEFAULT).expect("valid trace");
    let traced = trace(culled, &hints, step, 1.0).expect("valid trace");
    // A new tile sampler per trace, as for a new field: its factor cache starts empty.
    let tiled = || support::TiledField::new(&field);
    let uncached = support::UncachedTiledField(&field);
    let traced_tiles =
        trace_field(&tiled(), &hints, step, 1.0, &MarchOptions::DEFAULT).expect("valid trace");
    let traced_uncached =
        trace_field(&uncached, &hints, step, 1.0, &MarchOptions::DEFAULT).expect("valid trace");
    let theirs = builder
        .contours(&values64, &[1.0])
        .expect("valid contour-rs grid");
    let polygons = &theirs[0].geometry().0;
    let their_rings = polygons.len() + polygons.iter().map(|p| p.interiors().len()).sum::<usize>();
    let their_points: usize = polygons
        .iter()
        .map(|p| {
            p.exterior().0.len() - 1 + p.interiors().iter().map(|r| r.0.len() - 1).sum::<usize>()
        })
        .sum();
    assert_eq!(grid.len(), looked_up.len(), "same rings");
    assert_eq!(looked_up, copied, "same samples, same rings");
    assert_eq!(grid.len(), traced.len(), "same rings");
    assert_eq!(grid.len(), traced_tiles.len(), "same rings");
    assert_eq!(traced_tiles, traced_uncached, "same samples, same rings");
    assert_eq!(grid.len(), their_rings, "same rings as contour-rs");
    let points =
        |rings: &[creature_march::Ring]| rings.iter().map(|r| r.points.len()).sum::<usize>();
    eprintln!(
        "{} balls, step {step:.3}, {} rings; outline points: march_grid {}, trace {}, trace_field {}, contour-rs {}",
        balls.0.len(),
        grid.len(),
        points(&grid),
        points(&traced),
        points(&traced_tiles),
        their_points,
    );

    let mut group = c.benchmark_group("outline_256x256_50_balls");
    group.sample_size(20);
    group.bench_function("march_grid", |b| {
        b.iter(|| march_grid(black_box(&values), SIZE, SIZE, 1.0));
    });
    group.bench_function("contour_rs_contours", |b| {
        b.iter(|| builder.contours(black_box(&values64), &[1.0]));
    });
    group.bench_function("contour_rs_lines", |b| {
        b.iter(|| builder.lines(black_box(&values64), &[1.0]));
    });
    group.bench_function("reference_marching_squares", |b| {
        b.iter(|| support::reference::contours(black_box(&values), SIZE, SIZE, 1.0));
    });
    group.bench_function("trace_field", |b| {
        b.iter(|| trace(culled, black_box(&hints), step, 1.0));
    });
    let no_holes = MarchOptions::DEFAULT.with_holes(false);
    group.bench_function("trace_field_no_hole_scan", |b| {
        b.iter(|| trace_with(culled, black_box(&hints), step, 1.0, &no_holes));
    });
    group.bench_function("trace_tiles_field", |b| {
        b.iter(|| {
            trace_field(
                &tiled(),
                black_box(&hints),
                step,
                1.0,
                &MarchOptions::DEFAULT,
            )
        });
    });
    group.bench_function("trace_tiles_field_no_hole_scan", |b| {
        b.iter(|| trace_field(&tiled(), black_box(&hints), step, 1.0, &no_holes));
    });
    group.bench_function("trace_tiles_field_uncached", |b| {
        b.iter(|| {
            trace_field(
                &uncached,
                black_box(&hints),
                step,
                1.0,
                &MarchOptions::DEFAULT,
            )
        });
    });
    group.bench_function("trace_grid_lookup", |b| {
        b.iter(|| trace(lookup, black_box(&hints), step, 1.0));
    });
    group.bench_function("trace_tiles_grid", |b| {
        b.iter(|| {
            trace_field(
                &grid_tiles,
                black_box(&hints),
                step,
                1.0,
                &MarchOptions::DEFAULT,
            )
        });
    });
    group.bench_function("sample_grid_then_march_grid", |b| {
        b.iter(|| {
            let v = sample(black_box(&field));
            march_grid(&v, SIZE, SIZE, 1.0)
        });
    });
    group.bench_function("sample_grid", |b| {
        b.iter(|| sample(black_box(&field)));
    });
    group.bench_function("block_sweep", |b| {
        b.iter(|| sweep(black_box(&field)));
    });
    // contour-rs on freshly sampled values (converted to `f64` in the timed code).
    let contour_rs = |values: Vec<f32>| {
        let values: Vec<f64> = values.into_iter().map(f64::from).collect();
        builder.contours(&values, &[1.0])
    };
    group.bench_function("block_sweep_then_contour_rs", |b| {
        b.iter(|| contour_rs(sweep(black_box(&field))));
    });
    group.bench_function("sample_grid_then_contour_rs", |b| {
        b.iter(|| contour_rs(sample(black_box(&field))));
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
