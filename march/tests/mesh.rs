//! Meshing (feature `mesh`) through the public API.

#![allow(clippy::unwrap_used)]

extern crate alloc;

mod support;

use alloc::collections::BTreeSet;

use creature_march::glam::Vec2;
use creature_march::{MarchError, Mesh2, MeshOptions, Ring, trace, triangulate};
use creature_metaball::{Ball2, Falloff, Field2};
use support::creature;

/// The mesh invariants: indices in range, every vertex used, counter-clockwise non-degenerate
/// triangles inside the outline, ring vertices first, Euler characteristic.
fn check_mesh(mesh: &Mesh2, rings: &[Ring], ring_points_kept: bool) {
    let n = mesh.positions.len();
    assert!(mesh.positions.iter().all(|p| p.is_finite()));
    let mut used = vec![false; n];
    let mut edges = BTreeSet::new();
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        assert!(
            (b - a).perp_dot(c - a) > 0.0,
            "counter-clockwise and not degenerate"
        );
        let centroid = (a + b + c) / 3.0;
        let inside = rings.iter().filter(|r| r.contains(centroid)).count();
        assert_eq!(
            inside % 2,
            1,
            "triangle centroid {centroid} outside the outline"
        );
        for k in 0..3 {
            used[t[k] as usize] = true;
            let (u, v) = (t[k], t[(k + 1) % 3]);
            edges.insert((u.min(v), u.max(v)));
        }
    }
    assert!(used.iter().all(|&u| u), "every vertex is used");
    if ring_points_kept {
        let mut k = 0;
        for r in rings {
            for p in &r.points {
                assert_eq!(mesh.positions[k], *p, "ring vertex {k} is a mesh vertex");
                k += 1;
            }
        }
        assert_eq!(mesh.outline_len, k);
    }
    let outers = rings.iter().filter(|r| !r.hole).count() as i64;
    let holes = rings.len() as i64 - outers;
    let euler = n as i64 - edges.len() as i64 + mesh.triangles.len() as i64;
    assert_eq!(
        euler,
        outers - holes,
        "V - E + F = Σ (1 - holes) over components"
    );
}

#[test]
fn creatures_mesh_with_the_minimum_angle() {
    for seed in [3, 11, 42, 77, 1000] {
        let balls = creature(seed);
        let rings = trace(|p| balls.value(p), &balls.centres(), 5.0, 1.0).unwrap();
        let mesh = triangulate(&rings, &MeshOptions::DEFAULT).unwrap();
        check_mesh(&mesh, &rings, true);
        assert!(mesh.quality.refinement_complete, "seed {seed}");
        assert!(
            mesh.quality.min_angle >= 20.0 - 1e-3,
            "seed {seed}: {:?}",
            mesh.quality
        );
        assert_eq!(mesh.quality.below_20, 0);
        assert_eq!(mesh.quality.below_limit, 0);
        assert!(
            mesh.positions.len() > mesh.outline_len,
            "interior points were added"
        );
    }
}

/// The pipeline the `creature` facade runs: `creature-metaball`'s culled field, traced and
/// meshed with the defaults, keeps every guarantee.
#[test]
fn culled_metaball_fields_mesh_with_every_guarantee() {
    for seed in [2, 17, 64] {
        let balls = creature(seed);
        let metaballs: Vec<Ball2> = balls
            .0
            .iter()
            .enumerate()
            .map(|(i, &(c, r))| Ball2::new(c, r, i as u32))
            .collect();
        let field = Field2::new(&metaballs, Falloff::SEED).unwrap();
        let rings = trace(|p| field.value(p), &balls.centres(), 5.0, 1.0).unwrap();
        for c in balls.centres() {
            let outer = rings.iter().filter(|r| !r.hole && r.contains(c)).count();
            assert_eq!(outer, 1, "seed {seed}: centre {c}");
        }
        let mesh = triangulate(&rings, &MeshOptions::DEFAULT).unwrap();
        check_mesh(&mesh, &rings, true);
        assert!(mesh.quality.refinement_complete, "seed {seed}");
        assert!(mesh.quality.min_angle >= 20.0 - 1e-3, "seed {seed}");
        assert_eq!(mesh.quality.below_20, 0);
    }
}

#[test]
fn simplification_keeps_the_outline_and_drops_points() {
    let balls = creature(8);
    let rings = trace(|p| balls.value(p), &balls.centres(), 5.0, 1.0).unwrap();
    let full = triangulate(&rings, &MeshOptions::DEFAULT).unwrap();
    let lean = triangulate(&rings, &MeshOptions::DEFAULT.with_simplify(0.5)).unwrap();
    assert!(lean.outline_len < full.outline_len);
    check_mesh(&lean, &rings, false);
    assert!(lean.quality.min_angle >= 20.0 - 1e-3);
}

#[test]
fn an_annulus_mesh_leaves_the_hole_empty() {
    let field = |p: Vec2| {
        let d = p.length();
        (d - 30.0).min(80.0 - d)
    };
    let rings = trace(field, &[Vec2::new(55.0, 0.0)], 4.0, 0.0).unwrap();
    assert_eq!(rings.len(), 2);
    let mesh = triangulate(&rings, &MeshOptions::DEFAULT).unwrap();
    check_mesh(&mesh, &rings, true);
    let area: f32 = mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            0.5 * (b - a).perp_dot(c - a)
        })
        .sum();
    let rings_area: f32 = rings.iter().map(Ring::signed_area).sum();
    assert!((area - rings_area).abs() < 1e-3 * rings_area);
}

#[test]
fn unrefined_meshes_report_their_slivers() {
    let balls = creature(21);
    let rings = trace(|p| balls.value(p), &balls.centres(), 5.0, 1.0).unwrap();
    let options = MeshOptions::DEFAULT.with_min_angle(0.0).with_clearance(0.0);
    let mesh = triangulate(&rings, &options).unwrap();
    check_mesh(&mesh, &rings, true);
    let recount = mesh
        .triangles
        .iter()
        .filter(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            let angle = |p: Vec2, q: Vec2, r: Vec2| (q - p).angle_to(r - p).abs().to_degrees();
            angle(a, b, c).min(angle(b, c, a)).min(angle(c, a, b)) < 20.0
        })
        .count();
    assert_eq!(mesh.quality.below_20, recount);
    assert!(mesh.quality.refinement_complete);
}

fn square(o: Vec2, s: f32) -> Ring {
    Ring {
        points: vec![o, o + Vec2::X * s, o + Vec2::splat(s), o + Vec2::Y * s],
        hole: false,
        parent: None,
    }
}

#[test]
fn bad_rings_are_typed_errors() {
    let options = MeshOptions::DEFAULT;
    let crossing = [square(Vec2::ZERO, 10.0), square(Vec2::splat(5.0), 10.0)];
    assert!(matches!(
        triangulate(&crossing, &options),
        Err(MarchError::RingsCross {
            ring_a: 0,
            ring_b: 1,
            ..
        })
    ));
    // A corner of one ring on an edge of another, and two rings sharing part of an edge:
    // found exactly by the triangulation.
    let touching = [
        square(Vec2::ZERO, 10.0),
        Ring {
            points: vec![
                Vec2::new(10.0, 5.0),
                Vec2::new(20.0, 0.0),
                Vec2::new(20.0, 10.0),
            ],
            hole: false,
            parent: None,
        },
    ];
    let overlapping = [square(Vec2::ZERO, 10.0), square(Vec2::new(10.0, 2.0), 5.0)];
    for rings in [touching, overlapping] {
        assert!(matches!(
            triangulate(&rings, &options),
            Err(MarchError::RingsCross {
                ring_a: 0,
                ring_b: 1,
                ..
            })
        ));
    }
    let bow_tie = Ring {
        points: vec![Vec2::ZERO, Vec2::ONE, Vec2::X, Vec2::Y],
        hole: false,
        parent: None,
    };
    assert!(matches!(
        triangulate(&[bow_tie], &options),
        Err(MarchError::RingsCross {
            ring_a: 0,
            ring_b: 0,
            ..
        })
    ));
    let short = Ring {
        points: vec![Vec2::ZERO, Vec2::X],
        hole: false,
        parent: None,
    };
    assert!(matches!(
        triangulate(&[short], &options),
        Err(MarchError::TooFewPoints { ring: 0, len: 2 })
    ));
    let mut nan = square(Vec2::ZERO, 1.0);
    nan.points[2].x = f32::NAN;
    assert!(matches!(
        triangulate(&[nan], &options),
        Err(MarchError::NonFinite { .. })
    ));
    let orphan = Ring {
        hole: true,
        ..square(Vec2::ZERO, 1.0)
    };
    assert!(matches!(
        triangulate(&[orphan], &options),
        Err(MarchError::BadParent {
            ring: 0,
            parent: None
        })
    ));
    // A nonzero coordinate below 2^-142 (which the spade-based mesher rejected) and one
    // near f32's largest: exact predicates take every finite f32.
    let tiny = Ring {
        points: vec![Vec2::new(1e-44, 0.0), Vec2::X, Vec2::ONE, Vec2::Y],
        hole: false,
        parent: None,
    };
    let mesh = triangulate(&[tiny], &options).unwrap();
    assert_eq!(mesh.outline_len, 4);
    assert!(mesh.quality.min_angle >= 20.0);
    let huge = square(Vec2::splat(-1.5e38), 3e38);
    let mesh = triangulate(&[huge], &options.with_interior_spacing(0.0)).unwrap();
    assert_eq!(mesh.triangles.len(), 2);
    assert!(matches!(
        triangulate(
            &[square(Vec2::ZERO, 1.0)],
            &options.with_min_angle(f32::NAN)
        ),
        Err(MarchError::NonFinite { .. })
    ));
    let empty = triangulate(&[], &options).unwrap();
    assert!(empty.positions.is_empty() && empty.triangles.is_empty());
}

/// Issue 17, finding 1: thin rings with a long extent passed `validate_rings` but
/// `triangulate` said their edges cross (`RingsCross { ring_a: 0, ring_b: 0, .. }`), with any
/// options.
#[test]
fn thin_rings_with_a_long_extent_triangulate() {
    let rings = [
        vec![
            Vec2::new(3.0, 6.0),
            Vec2::new(0.0, 3.0),
            Vec2::new(-100.0, -100.0),
        ],
        vec![
            Vec2::new(-8.0, -8.0),
            Vec2::new(3.0, 3.0),
            Vec2::new(-100.0, -99.957_275),
            Vec2::new(-100.0, -100.0),
        ],
    ];
    for points in rings {
        let ring = Ring {
            points,
            hole: false,
            parent: None,
        };
        let rings = [ring];
        creature_march::validate_rings(&rings).unwrap();
        for options in [
            MeshOptions::DEFAULT,
            MeshOptions::DEFAULT.with_interior_spacing(0.0),
            MeshOptions::DEFAULT
                .with_min_angle(0.0)
                .with_interior_spacing(0.0),
        ] {
            let mesh = triangulate(&rings, &options)
                .unwrap_or_else(|e| panic!("{:?} with {options:?}: {e:?}", rings[0].points));
            check_mesh(&mesh, &rings, true);
        }
    }
}

/// Twice the signed area of a mesh, in `f64` (exact products of `f32` coordinates).
fn mesh_area2(mesh: &Mesh2) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_dvec2());
            (b - a).perp_dot(c - a)
        })
        .sum()
}

/// Regression (fuzz, `triangulate`): refinement split the ring edges of a triangle about
/// 1.5e-5 wide at midpoints rounded to `f32`, each off its edge by up to half a unit in the
/// last place, and the mesh covered 0.4 % more than the triangle (spade's CDT: exactly it).
/// The slivers the rounded split points add or cut are now bounded by 2⁻¹⁴ of the area.
#[test]
fn regression_refinement_keeps_the_area_of_a_thin_triangle() {
    let points = vec![
        Vec2::new(-8.0, -8.0),
        Vec2::new(3.000_03, 3.0),
        Vec2::new(0.0, 0.0),
    ];
    let exact = {
        let [a, b, c] = [points[0], points[1], points[2]].map(Vec2::as_dvec2);
        (b - a).perp_dot(c - a)
    };
    assert!(exact > 0.0);
    let rings = vec![Ring {
        points,
        hole: false,
        parent: None,
    }];
    for options in [
        MeshOptions::DEFAULT,
        MeshOptions::DEFAULT.with_min_angle(33.0),
        MeshOptions::DEFAULT.with_interior_spacing(0.0),
    ] {
        let mesh = triangulate(&rings, &options).unwrap();
        check_mesh(&mesh, &rings, true);
        let area = mesh_area2(&mesh);
        assert!(
            (area - exact).abs() <= exact / 16384.0,
            "mesh twice-area {area} vs the triangle's {exact} ({options:?})"
        );
    }
}

/// Regression (fuzz, `triangulate`, a 10 s timeout): a 4-point ring 131,075 long and about 100
/// wide with interior spacing 20 puts some 37,000 lattice points inside; its long left edge
/// lies on their hull, so before the constraint is inserted thousands of edges from those
/// points to a far super vertex cross it, and finding each edge by walking the super vertex's
/// star made inserting it cubic. It meshes in well under a second now.
#[test]
fn regression_a_long_ring_with_a_dense_lattice_meshes_quickly() {
    let rings = vec![Ring {
        points: vec![
            Vec2::new(0.0, 7.089_700_3e-38),
            Vec2::new(0.75, 3.0),
            Vec2::new(-100.0, -99.957_275),
            Vec2::new(1.387_778_8e-15, -131_075.03),
        ],
        hole: false,
        parent: None,
    }];
    let options = MeshOptions::DEFAULT
        .with_min_angle(20.035_156)
        .with_max_added_vertices(Some(255));
    let mesh = triangulate(&rings, &options).unwrap();
    assert!(mesh.positions.len() > 10_000, "{}", mesh.positions.len());
    check_mesh(&mesh, &rings, true);
}

/// Regression (fuzz, `triangulate`): `quality.min_angle` of a near-equilateral triangle came
/// out as 60.000004° (`atan2` of the rounded tangent), above the 60° no triangle's smallest
/// angle can exceed.
#[test]
fn regression_min_angle_of_an_equilateral_triangle_is_at_most_60() {
    let mut above = Vec::new();
    for k in 0..400 {
        let center = Vec2::new(k as f32 * 7.3 - 1000.0, -8.0 + k as f32 * 0.37);
        for scale in [0.01, 0.7, 1.0, 37.5, 1000.0] {
            let points: Vec<Vec2> = (0..3)
                .map(|i| {
                    let angle = i as f32 / 3.0 * core::f32::consts::TAU;
                    center + Vec2::from_angle(angle) * 0.5 * scale
                })
                .collect();
            let rings = vec![Ring {
                points,
                hole: false,
                parent: None,
            }];
            let options = MeshOptions::DEFAULT
                .with_interior_spacing(0.0)
                .with_min_angle(0.0);
            let mesh = triangulate(&rings, &options).unwrap();
            assert_eq!(mesh.triangles.len(), 1);
            if !(mesh.quality.min_angle <= 60.0) {
                above.push((center, scale, mesh.quality.min_angle));
            }
        }
    }
    assert!(
        above.is_empty(),
        "{} above 60°: {:?}",
        above.len(),
        &above[..above.len().min(4)]
    );
}

/// Regression (fuzz, `triangulate`, a 10 s timeout that ran for minutes): a thin triangle
/// 6.5e6 long holds some 30,000 interior lattice points at spacing 20; inserting its long
/// edges after them meant flipping tens of thousands of crossing edges out of the way,
/// quadratic in their number. The ring edges now go in before the interior points.
#[test]
fn regression_a_long_thin_triangle_with_many_interior_points_meshes_quickly() {
    let rings = vec![Ring {
        points: vec![
            Vec2::new(3.0, 6.0),
            Vec2::new(0.0, 3.0),
            Vec2::new(-6_553_600.0, -43.25),
        ],
        hole: false,
        parent: None,
    }];
    let options = MeshOptions::DEFAULT
        .with_clearance(0.0)
        .with_min_angle(5.5e-44)
        .with_max_added_vertices(Some(0));
    let mesh = triangulate(&rings, &options).unwrap();
    assert!(mesh.positions.len() > 20_000, "{}", mesh.positions.len());
    let area: f64 = mesh_area2(&mesh);
    let [a, b, c] =
        [rings[0].points[0], rings[0].points[1], rings[0].points[2]].map(Vec2::as_dvec2);
    // The ring is clockwise; the mesh's triangles are counter-clockwise.
    let exact = (b - a).perp_dot(c - a).abs();
    assert!((area - exact).abs() <= exact * 1e-9, "{area} vs {exact}");
}

/// Regression (fuzz, `triangulate`): `quality.min_angle` was computed in `f32`, where the
/// products of coordinates 5e-32 and 9e-38 from the origin underflow, and a mesh whose
/// smallest angle is 0.00016° reported 29.5°.
#[test]
fn regression_min_angle_of_a_mesh_with_tiny_coordinates_is_measured() {
    let rings = vec![Ring {
        points: vec![
            Vec2::new(3.0, -5.354_085e-32),
            Vec2::new(-5.375_081_3e-32, -5.375_081_3e-32),
            Vec2::new(2.69e-43, 9.403_955e-38),
            Vec2::new(4.48e-43, 2.015_625),
        ],
        hole: false,
        parent: None,
    }];
    let options = MeshOptions::DEFAULT.with_max_added_vertices(Some(255));
    let mesh = triangulate(&rings, &options).unwrap();
    let mut smallest = f64::INFINITY;
    for t in &mesh.triangles {
        let p = t.map(|i| mesh.positions[i as usize].as_dvec2());
        for k in 0..3 {
            let (u, w) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            smallest = smallest.min(u.angle_to(w).abs().to_degrees());
        }
    }
    assert!(
        (f64::from(mesh.quality.min_angle) - smallest).abs() <= 0.01,
        "reported {} but the smallest angle is {smallest}",
        mesh.quality.min_angle
    );
}
