//! `creature-march`'s marching squares: `march_grid_with` on small grids of arbitrary samples
//! and options. Its rings must pass `validate_rings`, be oriented (outer rings
//! counter-clockwise, holes clockwise with an outer parent), lie within the grid, and mesh
//! with `triangulate` (whose docs take `march_grid`'s output).

use arbitrary::Arbitrary;
use creature_march::{
    MarchOptions, MeshOptions, Ring, Saddle, march_grid_with, triangulate, validate_rings,
};

use crate::{map, pick};

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub valid: bool,
    pub size: [u8; 2],
    pub iso: f32,
    pub asymptotic: bool,
    pub weld: f32,
    pub values: Vec<f32>,
}

/// Asserts what every `march_grid`/`trace` output promises.
pub fn check_rings(rings: &[Ring], within: Option<(f32, f32)>) {
    if let Err(e) = validate_rings(rings) {
        panic!("output rings fail validate_rings: {e:?}");
    }
    for ring in rings {
        assert!(ring.points.iter().all(|p| p.is_finite()));
        if let Some((w, h)) = within {
            assert!(
                ring.points
                    .iter()
                    .all(|p| p.x >= 0.0 && p.y >= 0.0 && p.x <= w && p.y <= h),
                "ring point outside the grid"
            );
        }
        let area = ring.signed_area();
        if ring.hole {
            let parent = ring.parent.expect("a hole has a parent");
            assert!(!rings[parent].hole, "a hole's parent is a hole");
            assert!(area <= 0.0, "hole with area {area}");
        } else {
            assert!(ring.parent.is_none());
            assert!(area >= 0.0, "outer ring with area {area}");
        }
    }
}

pub fn run(input: &Input) {
    let v = input.valid;
    let (w, h) = (
        usize::from(input.size[0] % 24),
        usize::from(input.size[1] % 24),
    );
    let mut values: Vec<f32> = input
        .values
        .iter()
        .take(600)
        .map(|x| pick(v, *x, -1.0, 1.0))
        .collect();
    if v && !values.is_empty() {
        // Tile the samples over the whole grid.
        values = (0..w * h).map(|i| values[i % values.len()]).collect();
    }
    let options = MarchOptions::DEFAULT
        .with_saddle(if input.asymptotic {
            Saddle::Asymptotic
        } else {
            Saddle::Centre
        })
        .with_weld(pick(v, input.weld, 0.0, 0.5));
    let iso = pick(v, input.iso, -0.5, 0.5);
    let result = march_grid_with(&values, w, h, iso, &options);
    assert_eq!(
        format!("{:?}", march_grid_with(&values, w, h, iso, &options)),
        format!("{result:?}"),
        "determinism"
    );
    if v && values.len() == w * h {
        assert!(result.is_ok(), "valid grid rejected: {result:?}");
    }
    let Ok(rings) = result else {
        return;
    };
    check_rings(&rings, Some(((w.max(1) - 1) as f32, (h.max(1) - 1) as f32)));
    let mesh = triangulate(
        &rings,
        &MeshOptions::DEFAULT.with_interior_spacing(map(input.iso, 0.5, 4.0)),
    );
    if let Err(e) = mesh {
        panic!("triangulate fails on march_grid's rings: {e:?}");
    }
}
