//! Property tests of the invariants the crate promises, driven by its public strategies.

#![allow(clippy::unwrap_used)]

extern crate alloc;

mod support;

use creature_march::glam::Vec2;
use creature_march::{
    MarchError, MarchOptions, Ring, Saddle, TILE_NODES, TILE_SIZE, TileField, contains_each,
    march_grid, march_grid_with, node_point, strategies, trace, trace_field, trace_with,
    validate_rings,
};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use support::{hausdorff, is_simple, sample, to_world};

/// A blob field read tile by tile through [`TileField`]'s default `sample_tile`.
struct DefaultTiles(strategies::Blobs);

impl TileField for DefaultTiles {
    fn value(&self, p: Vec2) -> f32 {
        self.0.value(p)
    }
    fn prefers_tiles(&self) -> bool {
        true
    }
}

fn well_formed(rings: &[Ring]) -> Result<(), TestCaseError> {
    prop_assert!(validate_rings(rings).is_ok(), "{:?}", validate_rings(rings));
    for r in rings {
        prop_assert!(r.points.len() >= 3);
        prop_assert!(r.points.iter().all(|p| p.is_finite()));
        prop_assert_eq!(r.hole, r.signed_area() < 0.0);
        prop_assert_eq!(r.hole, r.parent.is_some());
        if let Some(p) = r.parent {
            prop_assert!(!rings[p].hole);
        }
        prop_assert!(is_simple(r));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: cases_or_env(64),
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/properties.txt",
        ))),
        ..ProptestConfig::default()
    })]

    #[test]
    fn a_single_ball_encloses_the_disc_area(
        centre in strategies::vec2_in(100.0),
        radius in 5.0f32..40.0,
    ) {
        let balls = strategies::Blobs { balls: vec![(centre, radius)] };
        let step = radius / 60.0;
        let rings = trace(|p| balls.value(p), &[centre], step, 1.0).unwrap();
        prop_assert_eq!(rings.len(), 1);
        let disc = core::f32::consts::PI * radius * radius;
        let area = rings[0].signed_area();
        prop_assert!((area - disc).abs() / disc < 0.005, "{} vs {}", area, disc);
    }

    #[test]
    fn trace_finds_every_component(blobs in strategies::blobs(1..12), step in 1.0f32..4.0) {
        let field = |p: Vec2| blobs.value(p);
        let rings = trace(field, &blobs.centres(), step, 1.0).unwrap();
        well_formed(&rings)?;
        for c in blobs.centres() {
            let outer = rings.iter().filter(|r| !r.hole && r.contains(c)).count();
            prop_assert_eq!(outer, 1, "centre {} in {} outer rings", c, outer);
        }
    }

    #[test]
    fn separated_balls_give_one_ring_each(blobs in strategies::separated_blobs(1..6)) {
        let rings = trace(|p| blobs.value(p), &blobs.centres(), 1.0, 1.0).unwrap();
        prop_assert_eq!(rings.len(), blobs.balls.len());
        well_formed(&rings)?;
    }

    #[test]
    fn an_annulus_is_one_outer_ring_and_one_hole(
        annulus in strategies::annulus(),
        step in 0.5f32..1.5,
    ) {
        let rings = trace(|p| annulus.value(p), &[annulus.hint()], step, 0.0).unwrap();
        well_formed(&rings)?;
        prop_assert_eq!(rings.len(), 2);
        prop_assert_eq!(rings.iter().filter(|r| r.hole).count(), 1);
    }

    #[test]
    fn grid_and_trace_agree(blobs in strategies::blobs(1..8), step in 2.0f32..5.0) {
        let field = |p: Vec2| blobs.value(p);
        let options = MarchOptions::DEFAULT.with_saddle(Saddle::Asymptotic);
        let traced = trace_with(field, &blobs.centres(), step, 1.0, &options).unwrap();
        // A grid covering every ball's reach (radius < 20, a few radii of margin).
        let origin = ((-180.0 / step).floor() as i32, (-180.0 / step).floor() as i32);
        let size = (360.0 / step).ceil() as usize + 2;
        let values = sample(field, origin, size, size, step);
        let grid = march_grid_with(&values, size, size, 1.0, &options).unwrap();
        let grid = to_world(&grid, origin, step);
        well_formed(&grid)?;
        // The trace sees the components holding a hint; a component of a ball field holds a
        // ball centre save in rare configurations, which are skipped.
        let holds_centre = |r: &Ring| blobs.centres().iter().any(|&c| r.contains(c));
        prop_assume!(grid.iter().all(|r| r.hole || holds_centre(r)));
        prop_assert_eq!(traced.len(), grid.len());
        let (traced_outer, grid_outer) = (traced, grid);
        let h = hausdorff(&traced_outer, &grid_outer);
        prop_assert!(h <= step, "hausdorff {} > step {}", h, step);
    }

    #[test]
    fn the_default_tile_sampler_is_point_sampling(
        blobs in strategies::blobs(1..6),
        first in (-40i32..40, -40i32..40),
        step in 0.1f32..5.0,
    ) {
        let field = DefaultTiles(blobs);
        let first = [first.0 * TILE_SIZE as i32, first.1 * TILE_SIZE as i32];
        let mut tile = [f32::NAN; TILE_NODES];
        field.sample_tile(first, step, &mut tile);
        for row in 0..TILE_SIZE {
            for col in 0..TILE_SIZE {
                let node = [first[0] + col as i32, first[1] + row as i32];
                let expected = field.0.value(node_point(node, step));
                prop_assert_eq!(tile[row * TILE_SIZE + col].to_bits(), expected.to_bits());
            }
        }
    }

    #[test]
    fn tracing_tile_by_tile_with_the_default_sampler_is_tracing_the_closure(
        blobs in strategies::blobs(1..10),
        step in 1.0f32..4.0,
        holes in any::<bool>(),
        asymptotic in any::<bool>(),
    ) {
        let saddle = if asymptotic { Saddle::Asymptotic } else { Saddle::Centre };
        let options = MarchOptions::DEFAULT.with_holes(holes).with_saddle(saddle);
        let hints = blobs.centres();
        let closure = trace_with(|p| blobs.value(p), &hints, step, 1.0, &options).unwrap();
        let tiles = trace_field(&DefaultTiles(blobs), &hints, step, 1.0, &options).unwrap();
        // The same rings, bit for bit.
        prop_assert_eq!(closure, tiles);
    }

    /// Wavy fields with many components, holes and islands in holes, straddling tiles at
    /// every offset: the tile-by-tile hole scan (a band of tiles at a time) traces the same
    /// rings, bit for bit and in the same order, as the point-by-point one (a column at a
    /// time).
    #[test]
    fn the_tile_hole_scan_is_the_column_hole_scan(
        waves in proptest::collection::vec((0.05f32..0.6, 0.05f32..0.6, 0.0f32..6.3, 0.0f32..6.3), 1..4),
        level in -0.4f32..0.6,
        hints in proptest::collection::vec(strategies::vec2_in(40.0), 1..12),
        step in 0.4f32..2.0,
    ) {
        // Inside a disc of radius 45, a sum of products of waves; outside, nothing.
        let field = |p: Vec2| {
            let wavy: f32 = waves
                .iter()
                .map(|&(a, b, c, d)| (a * p.x + c).sin() * (b * p.y + d).sin())
                .sum();
            (wavy / waves.len() as f32 + level).min((45.0 - p.length()) * 0.1)
        };
        let points = trace(field, &hints, step, 0.0).unwrap();
        let tiles = support::PreferTiles(field).trace(&hints, step, 0.0).unwrap();
        prop_assert_eq!(points, tiles);
    }

    #[test]
    fn grid_rings_are_closed_simple_and_oriented((values, w, h) in strategies::grid(), iso in -0.5f32..0.5) {
        let rings = march_grid(&values, w, h, iso).unwrap();
        well_formed(&rings)?;
        let asymptotic = MarchOptions::DEFAULT.with_saddle(Saddle::Asymptotic);
        well_formed(&march_grid_with(&values, w, h, iso, &asymptotic).unwrap())?;
    }

    #[test]
    fn bad_grids_are_rejected((values, w, h) in strategies::bad_grid()) {
        let is_size_error = matches!(march_grid(&values, w, h, 0.0), Err(MarchError::GridSize { .. }));
        prop_assert!(is_size_error);
    }

    #[test]
    fn bad_steps_and_isos_are_rejected(step in strategies::bad_step(), iso in strategies::non_finite_f32()) {
        let f = |p: Vec2| 1.0 - p.length();
        prop_assert!(trace(f, &[Vec2::ZERO], step, 0.0).is_err());
        prop_assert!(trace(f, &[Vec2::ZERO], 0.1, iso).is_err());
        prop_assert!(march_grid(&[0.0; 4], 2, 2, iso).is_err());
    }

    #[test]
    fn star_rings_are_valid(ring in strategies::star_ring()) {
        prop_assert!(validate_rings(&[ring]).is_ok());
    }

    /// The batch inside test answers as [`Ring::contains`] counted over the rings, also for
    /// points on the grid lines where ring points sit, and for rings with holes.
    #[test]
    fn contains_each_agrees_with_contains(
        blobs in strategies::blobs(1..6),
        annulus in strategies::annulus(),
        points in proptest::collection::vec(strategies::vec2_in(120.0), 0..200),
    ) {
        let mut rings = trace(|p| blobs.value(p), &blobs.centres(), 2.0, 1.0).unwrap();
        // The rings' own points, and points level with them, are the hard cases.
        let mut points = points;
        points.extend(rings.iter().flat_map(|r| r.points.iter().step_by(7).map(|&p| p + Vec2::new(0.25, 0.0))));
        points.push(Vec2::new(f32::NAN, 0.0));
        let one = |rings: &[Ring], p: Vec2| rings.iter().filter(|r| r.contains(p)).count() % 2 == 1;
        let expected: Vec<bool> = points.iter().map(|&p| one(&rings, p)).collect();
        prop_assert_eq!(contains_each(&rings, &points), expected);
        rings = trace(|p| annulus.value(p), &[annulus.hint()], 1.0, 0.0).unwrap();
        let expected: Vec<bool> = points.iter().map(|&p| one(&rings, p)).collect();
        prop_assert_eq!(contains_each(&rings, &points), expected);
    }

    #[test]
    fn self_intersecting_and_crossing_rings_are_rejected(
        ring in strategies::self_intersecting_ring(),
        pair in strategies::crossing_rings(),
    ) {
        let self_crossing = matches!(validate_rings(&[ring]), Err(MarchError::RingsCross { ring_a: 0, ring_b: 0, .. }));
        prop_assert!(self_crossing);
        let crossing = matches!(validate_rings(&pair), Err(MarchError::RingsCross { ring_a: 0, ring_b: 1, .. }));
        prop_assert!(crossing);
    }
}

#[cfg(feature = "mesh")]
mod mesh {
    use alloc::collections::BTreeSet;

    use creature_march::{MeshOptions, triangulate};

    use super::*;

    proptest! {
        #![proptest_config(ProptestConfig {
            cases: cases_or_env(32),
            failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
                "proptest-regressions/properties.txt",
            ))),
            ..ProptestConfig::default()
        })]

        #[test]
        fn meshes_fill_the_outline_with_good_triangles(
            blobs in strategies::blobs(1..10),
            spacing in 4.0f32..12.0,
        ) {
            let rings = trace(|p| blobs.value(p), &blobs.centres(), 2.0, 1.0).unwrap();
            let mesh = triangulate(&rings, &MeshOptions::DEFAULT.with_interior_spacing(spacing)).unwrap();
            // Every ring vertex is a mesh vertex, in order.
            let ring_points: Vec<Vec2> = rings.iter().flat_map(|r| r.points.iter().copied()).collect();
            prop_assert_eq!(&mesh.positions[..mesh.outline_len], &ring_points[..]);
            let mut edges = BTreeSet::new();
            for t in &mesh.triangles {
                let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
                prop_assert!((b - a).perp_dot(c - a) > 0.0);
                let centroid = (a + b + c) / 3.0;
                prop_assert_eq!(rings.iter().filter(|r| r.contains(centroid)).count() % 2, 1);
                for k in 0..3 {
                    let (u, v) = (t[k], t[(k + 1) % 3]);
                    edges.insert((u.min(v), u.max(v)));
                }
            }
            let outers = rings.iter().filter(|r| !r.hole).count() as i64;
            let holes = rings.len() as i64 - outers;
            let euler = mesh.positions.len() as i64 - edges.len() as i64 + mesh.triangles.len() as i64;
            prop_assert_eq!(euler, outers - holes);
            if mesh.quality.refinement_complete {
                prop_assert!(mesh.quality.min_angle >= 20.0 - 1e-2, "{:?}", mesh.quality);
            }
        }

        /// Without interior points or refinement the mesh is a constrained Delaunay
        /// triangulation of the rings: every edge but the ring edges passes the exact
        /// empty-circle test (up to rounding ties: cocircular points, which mirror-symmetric
        /// fields make, have several), and it agrees with spade's (the crate's mesher before
        /// its own) except at such ties.
        #[test]
        fn unrefined_meshes_are_constrained_delaunay_triangulations(
            blobs in strategies::blobs(1..8),
            step in 1.0f32..4.0,
        ) {
            let rings = trace(|p| blobs.value(p), &blobs.centres(), step, 1.0).unwrap();
            let options = MeshOptions::DEFAULT.with_interior_spacing(0.0).with_min_angle(0.0);
            let mesh = triangulate(&rings, &options).unwrap();
            let ring_edges = ring_edges(&rings);
            let ties = delaunay_violations(&mesh.positions, &mesh.triangles, &ring_edges)?;
            let ours = triangle_set(&mesh.positions, &mesh.triangles);
            let spade = spade_inside_triangles(&rings);
            prop_assert_eq!(ours.len(), spade.len());
            if ties == 0 {
                prop_assert!(ours == spade, "{} of {} triangles differ from spade's", ours.difference(&spade).count(), ours.len());
            }
        }

        /// Holes stay empty and refined meshes keep every ring vertex, also for rings with
        /// holes.
        #[test]
        fn annuli_are_meshed_around_their_hole(annulus in strategies::annulus(), step in 0.5f32..2.0) {
            let rings = trace(|p| annulus.value(p), &[annulus.hint()], step, 0.0).unwrap();
            prop_assert_eq!(rings.len(), 2);
            let mesh = triangulate(&rings, &MeshOptions::DEFAULT.with_interior_spacing(4.0 * step)).unwrap();
            let ring_points: Vec<Vec2> = rings.iter().flat_map(|r| r.points.iter().copied()).collect();
            prop_assert_eq!(&mesh.positions[..mesh.outline_len], &ring_points[..]);
            let area: f32 = mesh.triangles.iter().map(|t| {
                let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
                0.5 * (b - a).perp_dot(c - a)
            }).sum();
            let rings_area: f32 = rings.iter().map(Ring::signed_area).sum();
            prop_assert!((area - rings_area).abs() <= 1e-3 * rings_area.abs(), "{} {}", area, rings_area);
            for t in &mesh.triangles {
                let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
                let centroid = (a + b + c) / 3.0;
                prop_assert!(rings[0].contains(centroid) && !rings[1].contains(centroid));
            }
            if mesh.quality.refinement_complete {
                prop_assert!(mesh.quality.min_angle >= 20.0 - 1e-2, "{:?}", mesh.quality);
            }
        }

        /// Issue 17, finding 1: thin triangles and quadrilaterals with a long extent (one
        /// vertex far from the others, the others a hair off the line to it) that
        /// `validate_rings` accepts are triangulated, as spade triangulates them: both
        /// accept, with the same number of triangles covering the same area, and every ring
        /// vertex is a mesh vertex, unrefined and refined.
        #[test]
        fn thin_long_rings_triangulate_like_spade(
            (points, quad) in thin_long_ring(),
        ) {
            let ring = Ring { points, hole: false, parent: None };
            let rings = [ring];
            prop_assume!(validate_rings(&rings).is_ok());
            // The shoelace sum in f64: products of f32s are exact there, the sum nearly so.
            let n = rings[0].points.len();
            let expected = (0..n).map(|i| {
                let (p, q) = (rings[0].points[i].as_dvec2(), rings[0].points[(i + 1) % n].as_dvec2());
                p.perp_dot(q)
            }).sum::<f64>().abs() * 0.5;
            let spade = spade_inside_triangles(&rings);
            prop_assert_eq!(spade.len(), if quad { 2 } else { 1 });
            let unrefined = MeshOptions::DEFAULT.with_interior_spacing(0.0).with_min_angle(0.0);
            let extent = rings[0].points.iter().map(|p| p.distance(rings[0].points[0])).fold(0.0f32, f32::max);
            for options in [unrefined, MeshOptions::DEFAULT.with_interior_spacing(extent / 16.0)] {
                let mesh = triangulate(&rings, &options)
                    .map_err(|e| TestCaseError::fail(format!("{:?}: {e}", rings[0].points)))?;
                prop_assert_eq!(&mesh.positions[..mesh.outline_len], &rings[0].points[..]);
                let area: f64 = mesh.triangles.iter().map(|t| {
                    let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_dvec2());
                    prop_assert!((b - a).perp_dot(c - a) > 0.0);
                    Ok(0.5 * (b - a).perp_dot(c - a))
                }).sum::<Result<f64, TestCaseError>>()?;
                // Refinement rounds the points it adds on ring edges to f32: each moves the
                // outline by at most an ulp of the coordinates, over at most the perimeter.
                let slack = if options.min_angle == 0.0 {
                    0.0
                } else {
                    let perimeter: f64 = (0..n).map(|i| {
                        (rings[0].points[(i + 1) % n] - rings[0].points[i]).as_dvec2().length()
                    }).sum();
                    let magnitude = rings[0].points.iter().map(|p| p.abs().max_element()).fold(0.0f32, f32::max);
                    perimeter * f64::from(magnitude) * f64::from(f32::EPSILON)
                };
                prop_assert!((area - expected).abs() <= 1e-6 * expected + slack, "{} vs {}", area, expected);
                if options.min_angle == 0.0 {
                    prop_assert_eq!(mesh.triangles.len(), spade.len());
                    let spade_area: f64 = spade.iter().map(|t| {
                        let [a, b, c] = t.map(|(x, y)| Vec2::new(f32::from_bits(x), f32::from_bits(y)).as_dvec2());
                        0.5 * (b - a).perp_dot(c - a).abs()
                    }).sum();
                    prop_assert!((area - spade_area).abs() <= 1e-6 * expected, "{} vs spade {}", area, spade_area);
                }
            }
        }

        #[test]
        fn crossing_rings_never_reach_the_triangulator(pair in strategies::crossing_rings()) {
            let crossing = matches!(triangulate(&pair, &MeshOptions::DEFAULT), Err(MarchError::RingsCross { .. }));
            prop_assert!(crossing);
        }
    }

    /// A thin triangle, or quadrilateral (then `true`), with a long extent: a corner `a` near
    /// the origin, a far corner `b` 10 to 10⁶ away in any direction, a corner `c` between
    /// them a hair (10⁻⁷ to 10⁻¹ of the length) off the line `a`–`b`, and for a
    /// quadrilateral a corner `d` next to `b` (10⁻⁵ to 10⁻² of the length away, back towards
    /// `a` on `c`'s side), in either orientation.
    fn thin_long_ring() -> impl Strategy<Value = (Vec<Vec2>, bool)> {
        (
            (-10.0f32..10.0, -10.0f32..10.0),
            0.0f32..core::f32::consts::TAU,
            1.0f32..6.0,
            0.01f32..0.99,
            -7.0f32..-1.0,
            any::<bool>(),
            proptest::option::of((-3.0f32..0.0, 0.0f32..core::f32::consts::TAU)),
            any::<bool>(),
        )
            .prop_map(
                |((ax, ay), angle, log_length, t, log_width, left, near, reverse)| {
                    let a = Vec2::new(ax, ay);
                    let length = 10f32.powf(log_length);
                    let direction = Vec2::from_angle(angle);
                    let b = a + direction * length;
                    let width = length * 10f32.powf(log_width) * if left { 1.0 } else { -1.0 };
                    let c = a + direction * (t * length) + direction.perp() * width;
                    let mut points = vec![a, b, c];
                    if let Some((log_offset, turn)) = near {
                        // Back from `b`, on `c`'s side of the line: a → b → d → c stays simple
                        // but for a few (left to `validate_rings`).
                        let side = direction.perp() * width.signum();
                        let (sin, cos) = (0.25 * turn).sin_cos();
                        let offset = length * 10f32.powf(log_offset - 2.0);
                        points.insert(2, b + (side * sin - direction * cos) * offset);
                    }
                    if reverse {
                        points.reverse();
                    }
                    let quad = points.len() == 4;
                    (points, quad)
                },
            )
    }

    /// The rings' edges as sorted pairs of their ends' bits.
    fn ring_edges(rings: &[Ring]) -> BTreeSet<[(u32, u32); 2]> {
        let bits = |p: Vec2| (p.x.to_bits(), p.y.to_bits());
        rings
            .iter()
            .flat_map(|r| {
                let n = r.points.len();
                (0..n).map(move |i| {
                    let mut e = [bits(r.points[i]), bits(r.points[(i + 1) % n])];
                    e.sort_unstable();
                    e
                })
            })
            .collect()
    }

    /// Checks every edge shared by two triangles, except ring edges, with the exact
    /// in-circle test: fails on a violation beyond rounding; returns the number of ties
    /// (the opposite corner on the circle, or within the floating-point filter's bound).
    fn delaunay_violations(
        positions: &[Vec2],
        triangles: &[[u32; 3]],
        ring_edges: &BTreeSet<[(u32, u32); 2]>,
    ) -> Result<usize, TestCaseError> {
        use alloc::collections::BTreeMap;
        let coord = |p: Vec2| robust::Coord {
            x: f64::from(p.x),
            y: f64::from(p.y),
        };
        let mut apex: BTreeMap<(u32, u32), u32> = BTreeMap::new();
        for t in triangles {
            for k in 0..3 {
                apex.insert((t[k], t[(k + 1) % 3]), t[(k + 2) % 3]);
            }
        }
        let mut ties = 0;
        for (&(a, b), &c) in &apex {
            let Some(&d) = apex.get(&(b, a)) else {
                continue;
            };
            let [pa, pb, pc, pd] = [a, b, c, d].map(|i| positions[i as usize]);
            let mut key = [
                (pa.x.to_bits(), pa.y.to_bits()),
                (pb.x.to_bits(), pb.y.to_bits()),
            ];
            key.sort_unstable();
            if ring_edges.contains(&key) {
                continue;
            }
            let exact = robust::incircle(coord(pa), coord(pb), coord(pc), coord(pd));
            if exact > 0.0 {
                // Only a near-tie may stay: within 1e-12 of the determinant's scale.
                let (ad, bd, cd) = (
                    (pa - pd).as_dvec2(),
                    (pb - pd).as_dvec2(),
                    (pc - pd).as_dvec2(),
                );
                let scale = ad.length_squared() * bd.length() * cd.length()
                    + bd.length_squared() * cd.length() * ad.length()
                    + cd.length_squared() * ad.length() * bd.length();
                prop_assert!(
                    exact <= 1e-12 * scale,
                    "edge {:?}-{:?} is not Delaunay ({} vs {})",
                    pa,
                    pb,
                    exact,
                    scale
                );
            }
            if exact >= 0.0 {
                ties += 1;
            }
        }
        Ok(ties)
    }

    /// Triangles as sorted triples of their corners' bits, for comparing meshes.
    fn triangle_set(positions: &[Vec2], triangles: &[[u32; 3]]) -> BTreeSet<[(u32, u32); 3]> {
        triangles
            .iter()
            .map(|t| {
                let mut corners = t.map(|i| {
                    let p = positions[i as usize];
                    (p.x.to_bits(), p.y.to_bits())
                });
                corners.sort_unstable();
                corners
            })
            .collect()
    }

    /// spade's constrained Delaunay triangulation of the rings, inside faces only (even–odd
    /// across the constraint edges, by a flood fill from the hull).
    fn spade_inside_triangles(rings: &[Ring]) -> BTreeSet<[(u32, u32); 3]> {
        use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};
        let mut points = Vec::new();
        let mut edges = Vec::new();
        for ring in rings {
            let base = points.len();
            let n = ring.points.len();
            points.extend(
                ring.points
                    .iter()
                    .map(|p| Point2::new(f64::from(p.x), f64::from(p.y))),
            );
            edges.extend((0..n).map(|i| [base + i, base + (i + 1) % n]));
        }
        let cdt =
            ConstrainedDelaunayTriangulation::<Point2<f64>>::bulk_load_cdt(points, edges).unwrap();
        let mut side = vec![None; cdt.num_all_faces()];
        let mut stack = Vec::new();
        for edge in cdt.convex_hull() {
            if let Some(face) = edge.rev().face().as_inner() {
                let inside = edge.is_constraint_edge();
                if side[face.fix().index()].is_none() {
                    side[face.fix().index()] = Some(inside);
                    stack.push(face.fix());
                }
            }
        }
        while let Some(f) = stack.pop() {
            let here = side[f.index()].unwrap();
            for edge in cdt.face(f).adjacent_edges() {
                if let Some(other) = edge.rev().face().as_inner()
                    && side[other.fix().index()].is_none()
                {
                    side[other.fix().index()] = Some(here ^ edge.is_constraint_edge());
                    stack.push(other.fix());
                }
            }
        }
        cdt.inner_faces()
            .filter(|f| side[f.fix().index()] == Some(true))
            .map(|f| {
                let mut corners = f.vertices().map(|v| {
                    let p = v.position();
                    ((p.x as f32).to_bits(), (p.y as f32).to_bits())
                });
                corners.sort_unstable();
                corners
            })
            .collect()
    }

    /// Regression (found by the mesh property at 20,000 cases): two blobs that barely touch
    /// pinch the outline into corners sharper than 20°, where refinement cannot split the
    /// triangles; the mesh reported `refinement_complete` with a 17° triangle. Complete now
    /// means the limit holds everywhere.
    #[test]
    fn regression_a_pinched_outline_is_not_reported_complete_below_the_limit() {
        let blobs = strategies::Blobs {
            balls: vec![
                (Vec2::new(47.901_512, -22.280_396), 16.846_96),
                (Vec2::new(27.431_643, -52.895_958), 18.680_899),
                (Vec2::new(95.493_286, -23.054_695), 13.739_39),
            ],
        };
        let rings = trace(|p| blobs.value(p), &blobs.centres(), 2.0, 1.0).unwrap();
        let options = MeshOptions::DEFAULT.with_interior_spacing(4.0);
        let mesh = triangulate(&rings, &options).unwrap();
        let q = mesh.quality;
        assert!(q.min_angle < options.min_angle, "{q:?}");
        assert!(q.below_limit > 0 && !q.refinement_complete, "{q:?}");
    }
}

/// `default` cases, or `PROPTEST_CASES` when set (for longer soaks).
fn cases_or_env(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}
