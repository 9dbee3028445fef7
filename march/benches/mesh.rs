//! Outline and mesh of a median seed-like creature (about 49 balls, step 5, interior spacing
//! 20, refinement to 20°), against issue 3's goal of 0.15 ms (the seed's JavaScript takes
//! about 39 ms for outline, interior points and CDT; reference-2d.md §3.2).
//!
//! The field is `creature-metaball`'s culled `Field2` with the seed's falloff, as the
//! `creature` facade builds it. `outline_trace_tiles` traces through `trace_field` with
//! `tests/support`'s `TiledField` (each 8×8 node tile filled by one `Field2::sample_block`
//! call), as the facade does. Also timed: `simplify: 0.5` (a tenth of the step: fewer outline
//! vertices, the facade's setting), the exact all-balls field (the seed's, 49 `exp` per
//! sample), and references in the same run: spade 2.15 (this crate's mesher before its own)
//! building and refining the constrained Delaunay triangulation of the same outline without
//! interior points, beside `triangulate` doing the same, and spade's plain Delaunay bulk load
//! of the outline points alone (no constraint edges, no refinement), a floor for any
//! spade-based mesher.
//!
//! Run: `cargo bench -p creature-march --features mesh --bench mesh`

#![allow(clippy::expect_used)]

extern crate alloc;

use core::hint::black_box;

use creature_march::glam::Vec2;
use creature_march::{MarchOptions, MeshOptions, trace, trace_field, trace_with, triangulate};
use creature_metaball::{Ball2, Falloff, Field2};
use criterion::{Criterion, criterion_group, criterion_main};
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, DelaunayTriangulation, Point2,
    RefinementParameters, Triangulation,
};

#[path = "../tests/support/mod.rs"]
mod support;

fn bench(c: &mut Criterion) {
    let mut seed = 1;
    let balls = loop {
        let b = support::creature(seed);
        if (47..=51).contains(&b.0.len()) {
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
    let hints = balls.centres();
    let culled = |p: Vec2| field.value(p);
    let exact = |p: Vec2| field.value_exact(p);
    let rings = trace(culled, &hints, 5.0, 1.0).expect("outline");
    let options = MeshOptions::DEFAULT;
    let mesh = triangulate(&rings, &options).expect("mesh");
    eprintln!(
        "seed {seed}: {} balls, {} rings, {} outline points, {} vertices ({} on the outline), {} triangles, {:?}",
        balls.0.len(),
        rings.len(),
        rings.iter().map(|r| r.points.len()).sum::<usize>(),
        mesh.positions.len(),
        mesh.outline_len,
        mesh.triangles.len(),
        mesh.quality
    );

    let lean = MeshOptions::DEFAULT.with_simplify(0.5);
    let lean_mesh = triangulate(&rings, &lean).expect("mesh");
    eprintln!(
        "simplify 0.5: {} vertices ({} on the outline), {} triangles, {:?}",
        lean_mesh.positions.len(),
        lean_mesh.outline_len,
        lean_mesh.triangles.len(),
        lean_mesh.quality
    );
    let outline_points: Vec<Point2<f64>> = rings
        .iter()
        .flat_map(|r| r.points.iter())
        .map(|p| Point2::new(f64::from(p.x), f64::from(p.y)))
        .collect();
    let outline_edges: Vec<[usize; 2]> = {
        let mut edges = Vec::new();
        let mut base = 0;
        for r in &rings {
            let n = r.points.len();
            edges.extend((0..n).map(|i| [base + i, base + (i + 1) % n]));
            base += n;
        }
        edges
    };
    let outline_only = MeshOptions::DEFAULT.with_interior_spacing(0.0);
    let bare = triangulate(&rings, &outline_only).expect("mesh");
    eprintln!(
        "outline only: {} vertices, {} triangles, {:?}",
        bare.positions.len(),
        bare.triangles.len(),
        bare.quality
    );
    let no_holes = MarchOptions::DEFAULT.with_holes(false);

    let mut group = c.benchmark_group("creature_49_balls_step_5");
    group.sample_size(50);
    // A new tile sampler per trace, as for a new field: its factor cache starts empty.
    let tiled = || support::TiledField::new(&field);
    group.bench_function("outline_trace", |b| {
        b.iter(|| trace(culled, black_box(&hints), 5.0, 1.0));
    });
    group.bench_function("outline_trace_no_hole_scan", |b| {
        b.iter(|| trace_with(culled, black_box(&hints), 5.0, 1.0, &no_holes));
    });
    group.bench_function("outline_trace_tiles", |b| {
        b.iter(|| {
            trace_field(
                &tiled(),
                black_box(&hints),
                5.0,
                1.0,
                &MarchOptions::DEFAULT,
            )
        });
    });
    group.bench_function("triangulate", |b| {
        b.iter(|| triangulate(black_box(&rings), &options));
    });
    group.bench_function("triangulate_simplify_0.5", |b| {
        b.iter(|| triangulate(black_box(&rings), &lean));
    });
    group.bench_function("outline_and_triangulate", |b| {
        b.iter(|| {
            let rings = trace(culled, black_box(&hints), 5.0, 1.0).expect("outline");
            triangulate(&rings, &options)
        });
    });
    group.bench_function("outline_and_triangulate_simplify_0.5", |b| {
        b.iter(|| {
            let rings = trace(culled, black_box(&hints), 5.0, 1.0).expect("outline");
            triangulate(&rings, &lean)
        });
    });
    group.bench_function("outline_trace_tiles_and_triangulate_simplify_0.5", |b| {
        b.iter(|| {
            let rings = trace_field(
                &tiled(),
                black_box(&hints),
                5.0,
                1.0,
                &MarchOptions::DEFAULT,
            )
            .expect("outline");
            triangulate(&rings, &lean)
        });
    });
    group.bench_function("triangulate_outline_only", |b| {
        b.iter(|| triangulate(black_box(&rings), &outline_only));
    });
    group.bench_function("reference_spade_cdt_refined_outline_only", |b| {
        b.iter(|| {
            let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::bulk_load_cdt(
                black_box(outline_points.clone()),
                outline_edges.clone(),
            )
            .expect("valid outline");
            let parameters = RefinementParameters::<f64>::new()
                .with_angle_limit(AngleLimit::from_deg(20.0))
                .exclude_outer_faces(true);
            cdt.refine(parameters);
            cdt.num_vertices()
        });
    });
    group.bench_function("reference_exact_field_outline_and_triangulate", |b| {
        b.iter(|| {
            let rings = trace(exact, black_box(&hints), 5.0, 1.0).expect("outline");
            triangulate(&rings, &options)
        });
    });
    group.bench_function("floor_spade_delaunay_of_the_outline_points", |b| {
        b.iter(|| {
            DelaunayTriangulation::<Point2<f64>>::bulk_load(black_box(outline_points.clone()))
        });
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
