//! Procedural terrain through the public API: determinism, its slope, hills and steps, bad
//! parameters.

#![allow(clippy::unwrap_used)]

use creature::Error;
use creature::gait::Ground;
use creature::gait::HeightField;
use creature::glam::Vec3;
use creature::terrain::{TerrainMesh, TerrainParams, terrain, terrain_mesh};

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
    let cells = (field.columns() - 1) * (field.rows() - 1);
    assert!(mesh.positions.len() >= field.heights().len() + cells);
    assert!(mesh.triangles.len() >= 4 * cells);
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

/// Height of the triangle mesh `mesh` (as a viewer draws it) at `(x, z)`: the triangle whose
/// projection holds the point, found among those near it (bucketed by `field`'s cells).
struct MeshHeights<'a> {
    mesh: &'a TerrainMesh,
    field: &'a HeightField,
    buckets: Vec<Vec<usize>>,
}

impl<'a> MeshHeights<'a> {
    fn new(mesh: &'a TerrainMesh, field: &'a HeightField) -> Self {
        let mut buckets = vec![Vec::new(); field.columns() * field.rows()];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let centre = tri
                .iter()
                .map(|&v| mesh.positions[v as usize])
                .sum::<Vec3>()
                / 3.0;
            let (i, j) = Self::cell(field, centre.x, centre.z);
            buckets[j * field.columns() + i].push(t);
        }
        Self {
            mesh,
            field,
            buckets,
        }
    }

    fn cell(field: &HeightField, x: f32, z: f32) -> (usize, usize) {
        let at = |v: f32, o: f32, n: usize| {
            (((v - o) / field.cell()).floor().max(0.0) as usize).min(n - 1)
        };
        (
            at(x, field.origin().x, field.columns()),
            at(z, field.origin().y, field.rows()),
        )
    }

    fn height(&self, x: f32, z: f32) -> f32 {
        let (ci, cj) = Self::cell(self.field, x, z);
        for j in cj.saturating_sub(1)..=(cj + 1).min(self.field.rows() - 1) {
            for i in ci.saturating_sub(1)..=(ci + 1).min(self.field.columns() - 1) {
                for &t in &self.buckets[j * self.field.columns() + i] {
                    let [a, b, c] = self.mesh.triangles[t].map(|v| self.mesh.positions[v as usize]);
                    let (ab, ac) = (b - a, c - a);
                    let det = ab.x * ac.z - ab.z * ac.x;
                    let (px, pz) = (x - a.x, z - a.z);
                    let u = (px * ac.z - pz * ac.x) / det;
                    let v = (ab.x * pz - ab.z * px) / det;
                    if u >= -1e-5 && v >= -1e-5 && u + v <= 1.0 + 1e-5 {
                        return a.y + u * ab.y + v * ac.y;
                    }
                }
            }
        }
        panic!("({x}, {z}) is off the terrain mesh");
    }
}

/// Regression (three.js playing a `--terrain` .glb): the planted feet stood on the height
/// field's bilinear surface, but the exported mesh cut each cell into two flat triangles, so
/// on the steps' corners a viewer drew the terrain up to 1.5% of the walker's length away from
/// where the feet had been placed. Under every planted foot and every skinned vertex of a walk
/// as `--terrain` makes it, the exported mesh is now within 0.5% of the body's length (the
/// audit's tolerance under the ground) of the surface the gait walked on.
#[test]
fn the_exported_terrain_mesh_is_the_ground_the_walk_stood_on() {
    for seed in [3u64, 12] {
        let c = creature::d3::generate(
            seed,
            &creature::d3::Params::DEFAULT
                .with_kind(creature::d3::Kind::Walker)
                .with_clips(false),
        )
        .unwrap();
        let setup = c.gait.as_ref().unwrap();
        let leg = setup
            .legs
            .iter()
            .map(|l| l.size)
            .fold(f32::INFINITY, f32::min);
        let params = TerrainParams::DEFAULT
            .with_extent(24.0 * c.length, 193)
            .with_hills(0.5 * c.length, 6.0 * c.length)
            .with_slope(12.0)
            .with_steps(0.2 * leg, 3.0 * c.length);
        let field = terrain(seed, &params).unwrap();
        let mesh = terrain_mesh(&field);
        let heights = MeshHeights::new(&mesh, &field);
        let clip = c
            .bake_to(&field, Vec3::new(3.0, 0.0, 4.0) * c.length, 60.0)
            .unwrap();
        let gap =
            |p: Vec3| (heights.height(p.x, p.z) - field.height(p.x, p.z).unwrap()).abs() / c.length;
        let (mut feet, mut skin) = (0.0f32, 0.0f32);
        for f in 0..clip.frames {
            let pose = c.pose(&clip, f);
            for ((&hip, &planted), leg) in setup
                .hip_joints
                .iter()
                .zip(&clip.contacts[f])
                .zip(&setup.legs)
            {
                if planted && leg.kind == creature::gait::LimbKind::Leg {
                    feet = feet.max(gap(Vec3::from(pose[hip + 2].translation)));
                }
            }
            if f % 4 == 0 {
                for p in c.posed_positions(&clip, f).unwrap() {
                    skin = skin.max(gap(p));
                }
            }
        }
        assert!(
            feet < 0.005 && skin < 0.005,
            "seed {seed}: the mesh drawn {:.2}% of the body's length off the walked surface \
             under a planted foot, {:.2}% under the skin",
            100.0 * feet,
            100.0 * skin
        );
    }
}
