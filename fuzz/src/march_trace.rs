//! `creature-march`'s contour tracer: `trace_with` over a union of discs (valid flavour) or an
//! arbitrary field, step, iso and hints. Its rings must be what `march_grid`'s are (valid,
//! oriented), every disc whose centre is a hint and which spans several cells must be found,
//! and the rings must mesh with `triangulate`.

use arbitrary::Arbitrary;
use creature_march::{MarchOptions, MeshOptions, contains_each, trace_with, triangulate};
use glam::Vec2;

use crate::march_grid::check_rings;
use crate::{map, pick, pick2};

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub valid: bool,
    pub step: f32,
    pub iso: f32,
    pub refine: u8,
    pub holes: bool,
    pub discs: Vec<([f32; 2], f32)>,
    pub hints: Vec<[f32; 2]>,
}

pub fn run(input: &Input) {
    let v = input.valid;
    let step = pick(v, input.step, 0.25, 5.0);
    // Radii up to 24 steps (and 30): rings of at most about 150 points a disc, enough for the
    // "a disc over 4 steps wide is found" check below, and fast to mesh.
    let discs: Vec<(Vec2, f32)> = input
        .discs
        .iter()
        .take(8)
        .map(|(c, r)| {
            (
                pick2(v, *c, -50.0, 50.0),
                pick(v, *r, 0.5, (24.0 * step).min(30.0)),
            )
        })
        .collect();
    // A signed-distance-like field: positive inside the union of the discs.
    let field = |p: Vec2| {
        discs
            .iter()
            .map(|(c, r)| 1.0 - p.distance(*c) / r)
            .fold(f32::NEG_INFINITY, f32::max)
    };
    let iso = pick(v, input.iso, -0.2, 0.5);
    let mut hints: Vec<Vec2> = input
        .hints
        .iter()
        .take(4)
        .map(|h| pick2(v, *h, -60.0, 60.0))
        .collect();
    if v {
        hints.extend(discs.iter().map(|(c, _)| *c));
    }
    let options = MarchOptions::DEFAULT
        .with_refine_steps(u32::from(input.refine % 5))
        .with_holes(input.holes)
        .with_max_cells(1 << 16);
    let result = trace_with(field, &hints, step, iso, &options);
    assert_eq!(
        format!("{:?}", trace_with(field, &hints, step, iso, &options)),
        format!("{result:?}"),
        "determinism"
    );
    let Ok(rings) = result else {
        return;
    };
    check_rings(&rings, None);
    if v && !discs.is_empty() {
        // A disc a few cells wide whose centre is a hint is outlined: its centre is inside.
        let centres: Vec<Vec2> = discs
            .iter()
            .filter(|(_, r)| (1.0 - iso) * r > 4.0 * step)
            .map(|(c, _)| *c)
            .collect();
        let found = contains_each(&rings, &centres);
        for (c, inside) in centres.iter().zip(found) {
            assert!(inside, "the disc around hint {c} was not traced");
        }
    }
    // At most about 400 interior points in the rings' bounding box: meshing dominates the
    // run time, and the triangulate target checks dense meshes.
    let (lo, hi) = rings
        .iter()
        .flat_map(|r| &r.points)
        .fold((Vec2::INFINITY, Vec2::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let extent = hi - lo;
    let sparsest = (extent.x * extent.y / 400.0).sqrt();
    let mut spacing = map(input.step, 1.0, 8.0) * if v { step } else { 1.0 };
    if sparsest.is_finite() {
        spacing = spacing.max(sparsest);
    }
    if let Err(e) = triangulate(&rings, &MeshOptions::DEFAULT.with_interior_spacing(spacing)) {
        assert!(
            matches!(
                e,
                creature_march::MarchError::InteriorTooDense { .. }
                    | creature_march::MarchError::ExtentTooLarge { .. }
            ),
            "triangulate fails on trace's rings: {e:?}"
        );
    }
}
