//! `trace_field` on a field that fills whole tiles cheaply: `creature-metaball`'s `Field2`
//! through `tests/support`'s `TiledField` newtype (the one the README shows), against `trace`
//! on the same field point by point.

#![allow(clippy::unwrap_used)]

extern crate alloc;

mod support;

use creature_march::glam::Vec2;
use creature_march::{MarchOptions, Ring, TileField, trace, trace_field, validate_rings};
use creature_metaball::{Ball2, Falloff, Field2};
use support::{TiledField, creature, hausdorff};

fn field_of(balls: &support::Balls) -> Field2 {
    let metaballs: Vec<Ball2> = balls
        .0
        .iter()
        .enumerate()
        .map(|(i, &(c, r))| Ball2::new(c, r, i as u32))
        .collect();
    Field2::new(&metaballs, Falloff::SEED).unwrap()
}

fn points(rings: &[Ring]) -> usize {
    rings.iter().map(|r| r.points.len()).sum()
}

#[test]
fn tiled_metaball_fields_trace_the_outline_the_closure_traces() {
    for seed in 1..6 {
        let balls = creature(seed);
        let field = field_of(&balls);
        let hints = balls.centres();
        for step in [2.39f32, 5.0] {
            for holes in [true, false] {
                let options = MarchOptions::DEFAULT.with_holes(holes);
                let closure = creature_march::trace_with(
                    |p: Vec2| field.value(p),
                    &hints,
                    step,
                    1.0,
                    &options,
                )
                .unwrap();
                let tiled =
                    trace_field(&TiledField::new(&field), &hints, step, 1.0, &options).unwrap();
                validate_rings(&tiled).unwrap();
                let at = format!("creature {seed}, step {step}, holes {holes}");
                assert_eq!(tiled.len(), closure.len(), "{at}");
                let h = hausdorff(&tiled, &closure);
                assert!(h <= step, "{at}: hausdorff {h} > step {step}");
                // Node samples differ by rounding only: the rings are all but identical.
                assert!(h <= 1e-3 * step, "{at}: hausdorff {h}");
                assert!(points(&tiled).abs_diff(points(&closure)) <= 2, "{at}");
            }
        }
    }
}

#[test]
fn tiled_metaball_fields_find_holes() {
    // A ring of balls around an empty middle: one outer ring, one hole, found by the scan.
    let balls = support::Balls(
        (0..16)
            .map(|k| {
                let a = k as f32 * core::f32::consts::TAU / 16.0;
                (40.0 * Vec2::from_angle(a), 9.0)
            })
            .collect(),
    );
    let field = field_of(&balls);
    let hints = [balls.0[0].0];
    let tiled = trace_field(
        &TiledField::new(&field),
        &hints,
        1.5,
        1.0,
        &MarchOptions::DEFAULT,
    )
    .unwrap();
    let closure = trace(|p: Vec2| field.value(p), &hints, 1.5, 1.0).unwrap();
    assert_eq!(tiled.len(), 2);
    assert_eq!(tiled.iter().filter(|r| r.hole).count(), 1);
    assert!(hausdorff(&tiled, &closure) <= 1.5);
}

#[test]
fn the_tiled_newtype_fills_tiles_from_the_block_sampler() {
    let balls = creature(3);
    let field = field_of(&balls);
    let tiled = TiledField::new(&field);
    assert!(tiled.prefers_tiles());
    let mut tile = [0.0f32; creature_march::TILE_NODES];
    tiled.sample_tile([-16, 8], 2.0, &mut tile);
    for (n, &v) in tile.iter().enumerate() {
        let node = [-16 + (n % 8) as i32, 8 + (n / 8) as i32];
        let expected = field.value(creature_march::node_point(node, 2.0));
        assert!(
            (v - expected).abs() <= 1e-6 * expected.max(1.0),
            "node {node:?}"
        );
    }
}
