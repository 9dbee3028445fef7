//! Procedural terrain through the public API: determinism, its slope, hills and steps, bad
//! parameters.

#![allow(clippy::unwrap_used)]

use creature::Error;
use creature::gait::Ground;
use creature::glam::Vec3;
use creature::terrain::{TerrainParams, terrain, terrain_mesh};

fn flat() -> TerrainParams {
    TerrainParams::DEFAULT
        .with_hills(0.0, 10.0)
        .with_slope(0.0)
        .with_steps(0.0, 4.0)
}

#[test]
fn same_seed_same_terrain_and_seeds_differ() {
    let a = terrain(11, &TerrainParams::DEFAULT).unwrap();
    let b = terrain(11, &TerrainParams::DEFAULT).unwrap();
    let bits = |h: &[f32]| h.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(a.heights()), bits(b.heights()));
    assert_ne!(a, terrain(12, &TerrainParams::DEFAULT).unwrap());
    assert!(a.heights().iter().all(|h| h.is_finite()));
}

#[test]
fn a_plain_slope_rises_at_its_incline() {
    for degrees in [5.0f32, 30.0] {
        let field = terrain(3, &flat().with_slope(degrees)).unwrap();
        // The steepest rise between neighbouring samples along X or Z and their diagonal is
        // at most the incline's, and the plane's gradient reaches it.
        let (x, z) = (
            field.height(1.0, 0.0).unwrap() - field.height(0.0, 0.0).unwrap(),
            field.height(0.0, 1.0).unwrap() - field.height(0.0, 0.0).unwrap(),
        );
        let rise = (x * x + z * z).sqrt();
        assert!(
            (rise - degrees.to_radians().tan()).abs() < 1e-3,
            "{degrees}°: {rise}"
        );
    }
}

#[test]
fn hills_span_at_most_their_height() {
    let field = terrain(5, &flat().with_hills(2.0, 6.0)).unwrap();
    let (lo, hi) = field
        .heights()
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), &v| {
            (l.min(v), h.max(v))
        });
    assert!(hi - lo <= 2.0 + 1e-4 && hi - lo > 1.0, "{lo} to {hi}");
}

#[test]
fn steps_are_whole_steps_high() {
    let field = terrain(9, &flat().with_steps(0.25, 3.0)).unwrap();
    let heights = field.heights();
    let mut edges = 0;
    for h in heights {
        let steps = h / 0.25;
        assert!((steps - steps.round()).abs() < 1e-3, "{h}");
    }
    // Neighbours along X (within a row).
    for pair in heights
        .chunks(field.columns())
        .flat_map(|row| row.windows(2))
    {
        let d = (pair[1] - pair[0]).abs();
        assert!(d < 1e-4 || (d - 0.25).abs() < 1e-3, "{d}");
        edges += usize::from(d > 1e-4);
    }
    assert!(edges > 0);
}

#[test]
fn a_gait_can_stand_on_it() {
    let field = terrain(1, &TerrainParams::DEFAULT).unwrap();
    let hit = field
        .cast_ray(Vec3::new(0.3, 100.0, -2.0), Vec3::NEG_Y, 200.0)
        .unwrap();
    assert!((hit.point.y - field.height(0.3, -2.0).unwrap()).abs() < 1e-3);
    assert!(hit.normal.y > 0.0);
    let mesh = terrain_mesh(&field);
    assert_eq!(mesh.positions.len(), field.heights().len());
}

#[test]
fn bad_params_are_errors() {
    let nan = TerrainParams::DEFAULT.with_slope(f32::NAN);
    assert!(matches!(
        terrain(0, &nan),
        Err(Error::NonFinite {
            what: "slope degrees"
        })
    ));
    let steep = TerrainParams::DEFAULT.with_slope(60.0);
    assert!(matches!(
        terrain(0, &steep),
        Err(Error::OutOfRange {
            what: "slope degrees",
            ..
        })
    ));
    let one = TerrainParams::DEFAULT.with_extent(10.0, 1);
    assert!(matches!(
        terrain(0, &one),
        Err(Error::OutOfRange {
            what: "terrain samples",
            ..
        })
    ));
    let none = TerrainParams::DEFAULT.with_extent(0.0, 10);
    assert!(matches!(
        terrain(0, &none),
        Err(Error::OutOfRange {
            what: "terrain size",
            ..
        })
    ));
    assert!(!terrain(0, &steep).unwrap_err().to_string().is_empty());
}
