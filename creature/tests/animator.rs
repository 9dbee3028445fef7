//! The live animator through the public API: walkers crossing flat ground and procedural
//! terrain to a target, measured on the skinned output (the joints' world transforms and the
//! mesh skinned by the skinning matrices, as a GPU would), and bad input.

#![allow(clippy::unwrap_used)]

use creature::d3::{self, Animator, Intent, Kind};
use creature::gait::{Ground, Plane};
use creature::glam::{Vec3, Vec4Swizzles};
use creature::terrain::{TerrainParams, terrain};

fn walker(seed: u64) -> d3::Creature {
    d3::generate(
        seed,
        &d3::Params::DEFAULT
            .with_kind(Kind::Walker)
            .with_clips(false),
    )
    .unwrap()
}

fn flier(seed: u64) -> d3::Creature {
    d3::generate(seed, &d3::Params::DEFAULT.with_kind(Kind::Flier)).unwrap()
}

fn swimmer(seed: u64) -> d3::Creature {
    d3::generate(seed, &d3::Params::DEFAULT.with_kind(Kind::Swimmer)).unwrap()
}

fn slitherer(seed: u64) -> d3::Creature {
    d3::generate(seed, &d3::Params::DEFAULT.with_kind(Kind::Slitherer)).unwrap()
}

/// The mesh skinned by the animator's skinning matrices (linear blend, as a vertex shader).
fn skinned(c: &d3::Creature, animator: &Animator) -> Vec<Vec3> {
    let m = animator.skinning_matrices();
    c.mesh
        .positions
        .iter()
        .zip(&c.mesh.joints)
        .zip(&c.mesh.weights)
        .map(|((&p, js), ws)| {
            js.iter()
                .zip(ws)
                .map(|(&j, &w)| w * (m[usize::from(j)] * p.extend(1.0)).xyz())
                .sum()
        })
        .collect()
}

/// Per leg (not arm) of the walker, the vertices bound mostly to its foot joint.
fn foot_vertices(c: &d3::Creature) -> Vec<Vec<usize>> {
    let setup = c.gait.as_ref().unwrap();
    let most = |v: usize| {
        let (js, ws) = (&c.mesh.joints[v], &c.mesh.weights[v]);
        let k = (0..4).fold(0, |k, i| if ws[i] > ws[k] { i } else { k });
        usize::from(js[k])
    };
    setup
        .hip_joints
        .iter()
        .zip(&setup.legs)
        .filter(|(_, leg)| leg.kind == creature::gait::LimbKind::Leg)
        .map(|(&hip, _)| {
            (0..c.mesh.positions.len())
                .filter(|&v| most(v) == hip + 2)
                .collect()
        })
        .collect()
}

/// Per leg, how high its sole (its lowest foot vertex over the ground under it) is in the
/// skinned `positions`.
fn soles<G: Ground>(positions: &[Vec3], feet: &[Vec<usize>], ground: &G) -> Vec<f32> {
    feet.iter()
        .map(|vs| {
            vs.iter()
                .map(|&v| positions[v].y - height(ground, positions[v]))
                .fold(f32::INFINITY, f32::min)
        })
        .collect()
}

/// Whether each of the walker's legs (not arms) is planted.
fn planted(c: &d3::Creature, animator: &Animator) -> Vec<bool> {
    let setup = c.gait.as_ref().unwrap();
    animator
        .controller()
        .leg_states()
        .iter()
        .zip(&setup.legs)
        .filter(|(_, leg)| leg.kind == creature::gait::LimbKind::Leg)
        .map(|(state, _)| state.planted)
        .collect()
}

fn height<G: Ground + ?Sized>(ground: &G, p: Vec3) -> f32 {
    ground
        .cast_down_point(Vec3::new(p.x, 1e4, p.z), 2e4)
        .unwrap()
        .y
}

/// A sole `sole` high over the ground is never in it (by 0.5% of the body `length`), and on
/// it (within 1%) when `planted`.
fn foot_on(sole: f32, planted: bool, length: f32, label: &str) {
    assert!(
        sole > -0.005 * length,
        "{label}: a sole {sole} in the ground"
    );
    if planted {
        assert!(
            sole.abs() < 0.01 * length,
            "{label}: a planted sole {sole} over the ground"
        );
    }
}

/// Walks `c` from the origin to `target` (10 body lengths away) on `ground`, checking every
/// frame the feet as posed (none below the surface, the planted ones on it) and every fifth
/// frame the body as skinned (no vertex on spine joints only in the ground); panics unless it
/// arrives within 4 minutes.
fn walks_to<G: Ground>(c: &d3::Creature, ground: &G, target: Vec3, label: &str) {
    let body: Vec<bool> = c
        .mesh
        .joints
        .iter()
        .zip(&c.mesh.weights)
        .map(|(js, ws)| {
            js.iter().zip(ws).all(|(&j, &w)| {
                w == 0.0 || c.skeleton.joints[usize::from(j)].part == d3::Part::Spine
            })
        })
        .collect();
    let feet = foot_vertices(c);
    let mut animator = Animator::new(c).unwrap().with_pose(Vec3::ZERO, 0.0);
    for frame in 0..30 * 240 {
        animator
            .update(1.0 / 30.0, Intent::GoTo(target), ground)
            .unwrap();
        let posed = skinned(c, &animator);
        for (sole, planted) in soles(&posed, &feet, ground)
            .into_iter()
            .zip(planted(c, &animator))
        {
            foot_on(sole, planted, c.length, &format!("{label} frame {frame}"));
        }
        if frame % 5 == 0 {
            for (v, p) in posed.into_iter().enumerate() {
                if body[v] {
                    let under = height(ground, p);
                    assert!(
                        p.y > under - 0.005 * c.length,
                        "{label} frame {frame}: body vertex {v} at {p} in the ground at {under}"
                    );
                }
            }
        }
        let p = animator.position();
        if Vec3::new(p.x, 0.0, p.z).distance(target) < 0.3 * c.length {
            return;
        }
    }
    panic!("{label}: stopped at {}", animator.position());
}

#[test]
fn a_walker_reaches_a_target_on_flat_ground_with_its_feet_planted_on_it() {
    for seed in [1, 2, 3] {
        let c = walker(seed);
        let target = Vec3::new(6.0 * c.length, 0.0, 8.0 * c.length);
        walks_to(&c, &Plane::GROUND, target, &format!("seed {seed}"));
    }
}

#[test]
fn skinning_matrices_pose_the_mesh_as_the_joints_world_transforms() {
    let c = walker(4);
    let mut animator = Animator::new(&c).unwrap();
    for _ in 0..20 {
        let intent = Intent::Move {
            velocity: Vec3::Z * c.speed,
            turn_rate: 0.3,
        };
        animator.update(1.0 / 30.0, intent, &Plane::GROUND).unwrap();
    }
    // Each joint's skinning matrix takes its rest position to its world position.
    for ((m, w), j) in animator
        .skinning_matrices()
        .iter()
        .zip(animator.world_transforms())
        .zip(&c.skeleton.joints)
    {
        let moved = (*m * j.position.extend(1.0)).xyz();
        assert!(moved.distance(w.translation.into()) < 1e-3 * c.length);
    }
    assert!(skinned(&c, &animator).iter().all(|p| p.is_finite()));
}

/// Terrain from `seed` 40 body lengths of `c` across: hills 0.8 of its length high, a slope of
/// `slope` degrees, steps `step` high.
fn hilly(c: &d3::Creature, seed: u64, slope: f32, step: f32) -> creature::gait::HeightField {
    let params = TerrainParams::DEFAULT
        .with_extent(40.0 * c.length, 321)
        .with_hills(0.8 * c.length, 6.0 * c.length)
        .with_slope(slope)
        .with_steps(step, 3.0 * c.length);
    terrain(seed, &params).unwrap()
}

#[test]
fn a_walker_crosses_hilly_stepped_terrain_to_a_target_feet_on_the_surface() {
    // Slopes up to 30°, steps up to a quarter of the leg's length.
    for (seed, slope) in [(11, 12.0), (12, 20.0), (13, 30.0)] {
        let c = walker(seed);
        let setup = c.gait.as_ref().unwrap();
        let leg = setup
            .legs
            .iter()
            .map(|l| l.size)
            .fold(f32::INFINITY, f32::min);
        let ground = hilly(&c, seed, slope, 0.25 * leg);
        let target = Vec3::new(6.0 * c.length, 0.0, 8.0 * c.length);
        walks_to(&c, &ground, target, &format!("seed {seed}, slope {slope}°"));
    }
}

#[test]
fn bad_time_steps_and_intents_are_errors_and_leave_the_pose() {
    for c in [walker(5), flier(5), swimmer(5), slitherer(5)] {
        bad_input_leaves_the_pose(&c);
    }
}

fn bad_input_leaves_the_pose(c: &d3::Creature) {
    let mut animator = Animator::new(c).unwrap();
    animator
        .update(1.0 / 30.0, Intent::Stand, &Plane::GROUND)
        .unwrap();
    let before = animator.skinning_matrices().to_vec();
    for dt in [f32::NAN, f32::INFINITY, -1.0] {
        assert!(animator.update(dt, Intent::Stand, &Plane::GROUND).is_err());
    }
    for intent in [
        Intent::GoTo(Vec3::NAN),
        Intent::Move {
            velocity: Vec3::new(f32::INFINITY, 0.0, 0.0),
            turn_rate: 0.0,
        },
        Intent::Move {
            velocity: Vec3::ZERO,
            turn_rate: f32::NAN,
        },
    ] {
        assert!(animator.update(1.0 / 30.0, intent, &Plane::GROUND).is_err());
    }
    assert_eq!(animator.skinning_matrices(), &before[..]);
    // A zero and a huge time step are fine (the huge one taken as `MAX_STEP`).
    for dt in [0.0, 1e6] {
        animator
            .update(dt, Intent::GoTo(Vec3::Z * 100.0), &Plane::GROUND)
            .unwrap();
        assert!(animator.skinning_matrices().iter().all(|m| m.is_finite()));
    }
}

#[test]
fn the_same_updates_give_the_same_pose() {
    for c in [walker(6), flier(6), swimmer(6), slitherer(6)] {
        same_updates_same_pose(&c);
    }
}

fn same_updates_same_pose(c: &d3::Creature) {
    let run = || {
        let mut a = Animator::new(c).unwrap();
        for k in 0..90 {
            let intent = Intent::Move {
                velocity: Vec3::new(0.2, 0.0, 1.0) * c.speed,
                turn_rate: if k < 45 { 0.5 } else { -0.5 },
            };
            a.update(1.0 / 30.0, intent, &Plane::GROUND).unwrap();
        }
        a.skinning_matrices().to_vec()
    };
    assert_eq!(run(), run());
}

/// A ground that casts as `G` does but gives no height bounds: an animator on it casts every
/// ray.
struct RaysOnly<'a, G: ?Sized>(&'a G);

impl<G: Ground + ?Sized> Ground for RaysOnly<'_, G> {
    fn cast_ray(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
    ) -> Option<creature::gait::RayHit> {
        self.0.cast_ray(origin, direction, max_distance)
    }

    fn cast_down(&self, origin: Vec3, max_distance: f32) -> Option<creature::gait::RayHit> {
        self.0.cast_down(origin, max_distance)
    }

    fn cast_down_point(&self, origin: Vec3, max_distance: f32) -> Option<Vec3> {
        self.0.cast_down_point(origin, max_distance)
    }
}

/// The rays the animator skips where a ground's height bounds settle their answers (a foot
/// high in a step, a sole over flat ground) change no pose: on flat ground, on hills and on
/// flat terraces, walking a weaving circle, every skinning matrix is what the rays give, bit
/// for bit.
#[test]
fn height_bounds_skip_rays_without_changing_the_pose() {
    for seed in [3, 7, 32, 58] {
        let c = walker(seed);
        let hills = hilly(&c, 5, 10.0, 0.0);
        let step = 4.0 * c.length;
        let terraces = creature::gait::HeightField::from_fn(
            creature::glam::Vec2::splat(-20.0 * c.length),
            0.25 * c.length,
            161,
            161,
            |x, z| 0.05 * c.length * ((x / step).floor() + (z / step).floor()),
        )
        .unwrap();
        let grounds: [(&dyn Ground, &str); 3] = [
            (&Plane::GROUND, "flat"),
            (&hills, "hills"),
            (&terraces, "terraces"),
        ];
        for (ground, name) in grounds {
            let mut bounded = Animator::new(&c).unwrap();
            let mut rays = Animator::new(&c).unwrap();
            for k in 0..300 {
                let turn_rate = 0.8 * (k as f32 * 0.02).sin();
                let heading = bounded.heading();
                let intent = Intent::Move {
                    velocity: Vec3::new(heading.sin(), 0.0, heading.cos()) * c.speed,
                    turn_rate,
                };
                bounded.update(1.0 / 60.0, intent, ground).unwrap();
                rays.update(1.0 / 60.0, intent, &RaysOnly(ground)).unwrap();
                assert_eq!(
                    bounded.skinning_matrices(),
                    rays.skinning_matrices(),
                    "walker {seed} on {name}, update {k}"
                );
            }
        }
    }
}

#[test]
fn a_walk_baked_over_terrain_keeps_its_planted_feet_on_it_as_a_viewer_plays_it() {
    // The clip as exported, posed by forward kinematics frame by frame (`Creature::pose`).
    for seed in [21, 22] {
        let c = walker(seed);
        let params = TerrainParams::DEFAULT
            .with_extent(30.0 * c.length, 241)
            .with_hills(0.6 * c.length, 6.0 * c.length)
            .with_slope(15.0);
        let ground = terrain(seed, &params).unwrap();
        let target = Vec3::new(6.0, 0.0, 8.0) * c.length;
        let clip = c.bake_to(&ground, target, 240.0).unwrap();
        let end = clip.root_translation[clip.frames - 1];
        assert!(
            Vec3::new(end.x - target.x, 0.0, end.z - target.z).length() < c.length,
            "seed {seed}: ends at {end} after {} frames",
            clip.frames
        );
        let setup = c.gait.as_ref().unwrap();
        let feet = foot_vertices(&c);
        for f in 0..clip.frames {
            let posed = c.posed_positions(&clip, f).unwrap();
            let contacts = clip.contacts[f]
                .iter()
                .zip(&setup.legs)
                .filter(|(_, leg)| leg.kind == creature::gait::LimbKind::Leg)
                .map(|(&planted, _)| planted);
            for (sole, planted) in soles(&posed, &feet, &ground).into_iter().zip(contacts) {
                foot_on(sole, planted, c.length, &format!("seed {seed} frame {f}"));
            }
        }
    }
}

#[test]
fn baking_a_walk_to_a_target_checks_its_input() {
    let c = walker(8);
    for seconds in [0.0, -1.0, f32::NAN, 1e4] {
        assert!(matches!(
            c.bake_to(&Plane::GROUND, Vec3::Z, seconds),
            Err(creature::Error::OutOfRange { .. })
        ));
    }
    assert!(matches!(
        c.bake_to(&Plane::GROUND, Vec3::NAN, 10.0),
        Err(creature::Error::NonFinite { .. })
    ));
    // A walker whose gait set-up was taken away.
    let mut lame = c.clone();
    lame.gait = None;
    assert_eq!(
        lame.bake_to(&Plane::GROUND, Vec3::Z, 10.0).err(),
        Some(creature::Error::NoGait)
    );
}

/// Panics unless `clip`, baked for 120 s at most, ends within `length` of `target`
/// (horizontally) before its last allowed frame: it arrived and settled.
fn ends_settled_at(clip: &d3::Clip, target: Vec3, length: f32, label: &str) {
    let end = clip.root_translation[clip.frames - 1];
    let off = Vec3::new(end.x - target.x, 0.0, end.z - target.z).length();
    assert!(off < length, "{label}: ends {off} from the target");
    assert!(clip.frames < 120 * 30, "{label}: never settled");
}

/// The lowest of `posed`'s heights above `ground` under each.
fn lowest_posed_gap<G: Ground + ?Sized>(posed: &[Vec3], ground: &G) -> f32 {
    posed
        .iter()
        .map(|&p| p.y - height(ground, p))
        .fold(f32::INFINITY, f32::min)
}

#[test]
fn a_flight_baked_over_terrain_takes_off_arrives_and_lands_as_a_viewer_plays_it() {
    for seed in [1, 2] {
        let c = flier(seed);
        let hilly = hills(&c, seed, 0.5, 12.0);
        let target = Vec3::new(6.0, 0.0, 8.0) * c.length;
        for (ground, label) in [
            (&hilly as &dyn Ground, "hills"),
            (&Plane::GROUND as &dyn Ground, "flat"),
        ] {
            let label = format!("seed {seed} on {label}");
            let clip = c.bake_to(ground, target, 120.0).unwrap();
            assert_eq!(clip.name, "fly_to");
            assert!(clip.contacts.is_empty());
            let gaps: Vec<f32> = (0..clip.frames)
                .map(|f| lowest_posed_gap(&c.posed_positions(&clip, f).unwrap(), ground))
                .collect();
            // Never in the ground; flying between its ends, on the ground at them (on flat
            // ground its lowest vertex on it; on hills leaning with the plane of the ground
            // under it, within 3% of its length: it stood 15% of its length above the hills
            // for seed 1 when it landed level on the highest ground under its reach).
            let lowest = gaps.iter().fold(f32::INFINITY, |a, &b| a.min(b));
            assert!(lowest > -1e-3 * c.length, "{label}: {lowest} in the ground");
            let highest = gaps.iter().fold(0.0f32, |a, &b| a.max(b));
            assert!(highest > 0.3 * c.length, "{label}: flies {highest} up");
            let on = if label.ends_with("flat") { 0.01 } else { 0.03 } * c.length;
            let (first, last) = (gaps[0], gaps[clip.frames - 1]);
            assert!(first < on, "{label}: starts {first} up");
            assert!(last < on, "{label}: ends {last} up");
            ends_settled_at(&clip, target, c.length, &label);
        }
    }
}

#[test]
fn a_flier_landing_on_a_slope_leans_with_it() {
    // A 20° slope rising toward +Z; facing up it (heading 0) the flier's nose rises, and at
    // any heading its up axis ends along the slope's normal.
    let (sin, cos) = 20f32.to_radians().sin_cos();
    let normal = Vec3::new(0.0, cos, -sin);
    let slope = Plane::new(Vec3::ZERO, normal).unwrap();
    for seed in [1, 2] {
        let c = flier(seed);
        let root = root(&c);
        for heading in [0.0f32, 1.0, -2.5] {
            let mut animator = Animator::new(&c).unwrap().with_pose(Vec3::ZERO, heading);
            for _ in 0..30 * 5 {
                animator.update(1.0 / 30.0, Intent::Stand, &slope).unwrap();
            }
            let body = animator.world_transforms()[root].matrix3;
            let up = Vec3::from(body.y_axis);
            let off = up.angle_between(normal).to_degrees();
            assert!(
                off < 3.0,
                "seed {seed} heading {heading}: up {off}° off the normal"
            );
            if heading == 0.0 {
                let forward = Vec3::from(body.z_axis);
                assert!(
                    forward.y > 0.3,
                    "seed {seed}: nose at {forward} facing uphill"
                );
            }
            let gap = lowest_gap(&c, &animator, &slope);
            assert!(gap.abs() < 0.01 * c.length, "seed {seed}: stands {gap} up");
        }
    }
}

#[test]
fn a_swim_baked_over_the_seabed_arrives_above_it_as_a_viewer_plays_it() {
    for seed in [1, 2] {
        let c = swimmer(seed);
        let ground = hills(&c, seed, 0.3, 10.0);
        let target = Vec3::new(-8.0, 0.0, 6.0) * c.length;
        let clip = c.bake_to(&ground, target, 120.0).unwrap();
        assert_eq!(clip.name, "swim_to");
        for f in 0..clip.frames {
            let gap = lowest_posed_gap(&c.posed_positions(&clip, f).unwrap(), &ground);
            assert!(gap > 0.0, "seed {seed} frame {f}: {gap} in the seabed");
        }
        ends_settled_at(&clip, target, c.length, &format!("seed {seed}"));
    }
}

#[test]
fn the_head_looks_toward_a_target_before_the_body_faces_it() {
    let c = walker(9);
    let head = c
        .skeleton
        .joints
        .iter()
        .position(|j| j.name == "head")
        .unwrap();
    let mut animator = Animator::new(&c).unwrap();
    let target = Vec3::new(6.0, 0.0, 2.0) * c.length;
    for _ in 0..12 {
        animator
            .update(1.0 / 30.0, Intent::GoTo(target), &Plane::GROUND)
            .unwrap();
    }
    let world = animator.world_transforms();
    let facing = |m: &creature::glam::Affine3A| {
        let f = m.matrix3 * creature::glam::Vec3A::Z;
        creature::glam::Vec2::new(f.x, f.z).normalize()
    };
    let to = |m: &creature::glam::Affine3A| {
        let p = Vec3::from(m.translation);
        creature::glam::Vec2::new(target.x - p.x, target.z - p.z).normalize()
    };
    let root = c
        .skeleton
        .joints
        .iter()
        .position(|j| j.parent.is_none())
        .unwrap();
    let off = |j: usize| facing(&world[j]).angle_to(to(&world[j])).abs();
    // The neck's bend toward the turn alone leaves the head 0.8 rad off; the look turns it on
    // as far as the neck's skin allows (turned on its own joint to 0.1 rad off, the head tore
    // the skin of the neck: edges stretched to 1.8×, squashed to 0.3×).
    assert!(
        off(head) < 0.75 * off(root),
        "head {} rad off the target, body {}",
        off(head),
        off(root)
    );
    let posed = skinned(&c, &animator);
    for t in &c.mesh.indices {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            let (a, b) = (a as usize, b as usize);
            let rest = c.mesh.positions[a].distance(c.mesh.positions[b]);
            let ratio = posed[a].distance(posed[b]) / rest;
            assert!(
                rest == 0.0 || (0.8..=1.25).contains(&ratio),
                "edge {a}-{b}: {ratio}× its rest length"
            );
        }
    }
}

/// Rolling hills for fliers and swimmers to cross: `hills` body lengths high, 6 apart, sloping
/// up to `slope` degrees.
fn hills(c: &d3::Creature, seed: u64, hills: f32, slope: f32) -> creature::gait::HeightField {
    let params = TerrainParams::DEFAULT
        .with_extent(40.0 * c.length, 321)
        .with_hills(hills * c.length, 6.0 * c.length)
        .with_slope(slope);
    terrain(seed, &params).unwrap()
}

/// Goes from the origin to `target` (its height ignored) on `ground`, checking every update
/// that every joint is at least `margin` body lengths above the ground under it and every
/// fifth that every skinned vertex is above it; panics unless it arrives within a minute.
/// The updates taken.
fn goes_to<G: Ground>(
    c: &d3::Creature,
    ground: &G,
    target: Vec3,
    margin: f32,
    label: &str,
) -> usize {
    let mut animator = Animator::new(c).unwrap();
    for frame in 0..30 * 60 {
        animator
            .update(1.0 / 30.0, Intent::GoTo(target), ground)
            .unwrap();
        for (j, w) in animator.world_transforms().iter().enumerate() {
            let p = Vec3::from(w.translation);
            let under = height(ground, p);
            assert!(
                p.y > under + margin * c.length,
                "{label} frame {frame}: joint {j} at {p}, the ground at {under}"
            );
        }
        if frame % 5 == 0 {
            for (v, p) in skinned(c, &animator).into_iter().enumerate() {
                let under = height(ground, p);
                assert!(
                    p.y > under,
                    "{label} frame {frame}: vertex {v} at {p} in the ground at {under}"
                );
            }
        }
        let p = animator.position();
        if Vec3::new(p.x, 0.0, p.z).distance(target) < 0.3 * c.length {
            return frame;
        }
    }
    panic!("{label}: stopped at {}", animator.position());
}

#[test]
fn a_flier_flies_over_hills_to_a_target_ten_lengths_away_clear_of_the_ground() {
    for seed in [1, 2, 3, 4] {
        let c = flier(seed);
        let ground = hills(&c, seed, 0.8, 25.0);
        let target = Vec3::new(6.0, 0.0, 8.0) * c.length;
        goes_to(&c, &ground, target, 0.05, &format!("flier {seed}"));
    }
}

#[test]
fn a_swimmer_swims_over_the_seabed_to_a_target_ten_lengths_away_above_it() {
    for seed in [1, 2, 3, 4] {
        let c = swimmer(seed);
        let ground = hills(&c, seed, 0.3, 10.0);
        for target in [Vec3::new(6.0, 0.0, 8.0), Vec3::new(-8.0, 0.0, -6.0)] {
            let label = format!("swimmer {seed} to {target}");
            goes_to(&c, &ground, target * c.length, 0.0, &label);
        }
    }
}

/// The root joint's index.
fn root(c: &d3::Creature) -> usize {
    c.skeleton
        .joints
        .iter()
        .position(|j| j.parent.is_none())
        .unwrap()
}

#[test]
fn a_flier_banks_into_its_turns_and_flies_level_straight_ahead() {
    let c = flier(7);
    let root = root(&c);
    // The root's up axis along the body's left (+X at heading 0), averaged over the last second
    // of two seconds of turning at `turn_rate`.
    let roll = |turn_rate: f32| {
        let mut animator = Animator::new(&c).unwrap();
        let mut sum = 0.0;
        for frame in 0..60 {
            let intent = Intent::Move {
                velocity: Vec3::Z * c.speed,
                turn_rate,
            };
            animator.update(1.0 / 30.0, intent, &Plane::GROUND).unwrap();
            if frame >= 30 {
                let h = animator.heading();
                let left = Vec3::new(h.cos(), 0.0, -h.sin());
                let up = animator.world_transforms()[root].matrix3.y_axis;
                sum += Vec3::from(up).dot(left) / 30.0;
            }
        }
        sum
    };
    let (left, right, straight) = (roll(1.0), roll(-1.0), roll(0.0));
    assert!(left > 0.2, "turning left, rolled {left}");
    assert!(right < -0.2, "turning right, rolled {right}");
    assert!(straight.abs() < 0.01, "flying straight, rolled {straight}");
}

/// Upward crossings per second of the mean by `angle` of `joint`'s local rotation about
/// `axis` over 6 s of moving straight ahead at `speed`, the animator's
/// [`beat_frequency`](Animator::beat_frequency) then, and the angle's range.
fn beats(c: &d3::Creature, joint: usize, axis: Vec3, speed: f32) -> (f32, f32, f32) {
    let mut animator = Animator::new(c).unwrap();
    let intent = Intent::Move {
        velocity: Vec3::Z * speed,
        turn_rate: 0.0,
    };
    // Up to speed first.
    for _ in 0..60 {
        animator.update(1.0 / 60.0, intent, &Plane::GROUND).unwrap();
    }
    let mut angles = Vec::new();
    for _ in 0..360 {
        animator.update(1.0 / 60.0, intent, &Plane::GROUND).unwrap();
        // The signed angle of a turn about `axis`.
        let q = animator.local_transforms()[joint]
            .to_scale_rotation_translation()
            .1;
        angles.push(2.0 * q.xyz().dot(axis).atan2(q.w));
    }
    let mean = angles.iter().sum::<f32>() / angles.len() as f32;
    let crossings = angles
        .windows(2)
        .filter(|w| w[0] < mean && w[1] >= mean)
        .count();
    let range = angles.iter().fold(f32::NEG_INFINITY, |a, &b| a.max(b))
        - angles.iter().fold(f32::INFINITY, |a, &b| a.min(b));
    (
        crossings as f32 / 6.0,
        animator.beat_frequency().unwrap(),
        range,
    )
}

fn joint(c: &d3::Creature, name: &str) -> usize {
    c.skeleton
        .joints
        .iter()
        .position(|j| j.name.starts_with(name))
        .unwrap()
}

#[test]
fn wings_beat_faster_and_wider_the_faster_a_flier_flies() {
    for seed in [2, 3] {
        let c = flier(seed);
        let wing = joint(&c, "wing_l0_1");
        let (slow, slow_reported, slow_sweep) = beats(&c, wing, Vec3::Z, 0.0);
        let (fast, fast_reported, fast_sweep) = beats(&c, wing, Vec3::Z, 2.0 * c.speed);
        assert!(fast > slow * 1.3, "seed {seed}: {slow} then {fast} beats/s");
        assert!(
            fast_sweep > slow_sweep * 1.2,
            "seed {seed}: sweeps {slow_sweep} then {fast_sweep} rad"
        );
        // What is reported is what is seen (within a crossing in 6 s).
        for (seen, reported) in [(slow, slow_reported), (fast, fast_reported)] {
            assert!((seen - reported).abs() <= 0.2, "{seen} vs {reported}");
        }
    }
}

#[test]
fn a_swimmer_waves_faster_the_faster_it_swims() {
    let c = swimmer(3);
    // A spine joint halfway along the body.
    let joint = c.rig.spine[c.rig.spine.len() / 2];
    let (slow, _, _) = beats(&c, joint, Vec3::Y, 0.5 * c.speed);
    let (fast, reported, _) = beats(&c, joint, Vec3::Y, 2.0 * c.speed);
    assert!(fast > slow * 1.5, "{slow} then {fast} waves/s");
    assert!((fast - reported).abs() <= 0.2, "{fast} vs {reported}");
}

#[test]
fn a_swimmer_bends_its_body_toward_its_turn() {
    let c = swimmer(4);
    let tail = joint(&c, "tail_end");
    let root = root(&c);
    // The tail tip's mean place along the body's left over two seconds of turning.
    let side = |turn_rate: f32| {
        let mut animator = Animator::new(&c).unwrap();
        let mut sum = 0.0;
        for frame in 0..120 {
            let intent = Intent::Move {
                velocity: Vec3::Z * c.speed,
                turn_rate,
            };
            animator.update(1.0 / 30.0, intent, &Plane::GROUND).unwrap();
            if frame >= 60 {
                let world = animator.world_transforms();
                let h = animator.heading();
                let left = Vec3::new(h.cos(), 0.0, -h.sin());
                let off = Vec3::from(world[tail].translation - world[root].translation);
                sum += off.dot(left) / 60.0;
            }
        }
        sum
    };
    let (left, right) = (side(1.0), side(-1.0));
    assert!(
        left > right + 0.05 * c.length,
        "tail tip {left} turning left, {right} right"
    );
}

#[test]
fn a_swimmer_swims_at_its_clip_height_over_flat_ground() {
    for seed in [1, 5] {
        let c = swimmer(seed);
        let swim = c.clips.iter().find(|clip| clip.name == "swim").unwrap();
        let root = root(&c);
        let mut animator = Animator::new(&c).unwrap();
        for _ in 0..60 {
            let intent = Intent::Move {
                velocity: Vec3::Z * c.speed,
                turn_rate: 0.0,
            };
            animator.update(1.0 / 30.0, intent, &Plane::GROUND).unwrap();
            let y = animator.world_transforms()[root].translation.y;
            let clip = swim.root_translation[0].y;
            assert!(
                y >= clip && y < clip + 0.03 * c.length,
                "seed {seed}: root at {y}, the clip's at {clip}"
            );
        }
    }
}

/// The lowest skinned vertex's height above `ground` under it.
fn lowest_gap<G: Ground>(c: &d3::Creature, animator: &Animator, ground: &G) -> f32 {
    skinned(c, animator)
        .into_iter()
        .map(|p| p.y - height(ground, p))
        .fold(f32::INFINITY, f32::min)
}

#[test]
fn a_flier_told_to_stand_lands_on_its_rest_pose_and_takes_off_when_told_to_go() {
    for seed in [1, 2, 3] {
        let c = flier(seed);
        let ground = Plane::GROUND;
        let wing = joint(&c, "wing_l0_1");
        let mut animator = Animator::new(&c).unwrap();
        let go = Intent::GoTo(Vec3::new(0.0, 0.0, 4.0) * c.length);
        for _ in 0..60 {
            animator.update(1.0 / 30.0, go, &ground).unwrap();
        }
        let flying = lowest_gap(&c, &animator, &ground);
        assert!(flying > 0.3 * c.length, "seed {seed}: flying {flying} up");
        // Landing: never into the ground, and after 3 s standing on it, the wings still.
        let mut wing_angles = Vec::new();
        for frame in 0..90 {
            animator.update(1.0 / 30.0, Intent::Stand, &ground).unwrap();
            let gap = lowest_gap(&c, &animator, &ground);
            assert!(gap > -1e-3 * c.length, "seed {seed} frame {frame}: {gap}");
            if frame >= 60 {
                let q = animator.local_transforms()[wing]
                    .to_scale_rotation_translation()
                    .1;
                wing_angles.push(q.angle_between(creature::glam::Quat::IDENTITY));
            }
        }
        // Its lowest vertex on the ground (it stood its rest pose's height, a third of its
        // length for a median flier, above it).
        let standing = lowest_gap(&c, &animator, &ground);
        assert!(
            standing < 0.01 * c.length,
            "seed {seed}: standing {standing} up"
        );
        let wings = wing_angles.iter().fold(0.0f32, |a, &b| a.max(b));
        assert!(wings < 1e-3, "seed {seed}: wings at {wings} rad landed");
        // Taking off: up in the air again within 2 s.
        for _ in 0..60 {
            animator.update(1.0 / 30.0, go, &ground).unwrap();
        }
        let up = lowest_gap(&c, &animator, &ground);
        assert!(up > 0.3 * c.length, "seed {seed}: taken off {up} up");
    }
}

/// Regression: a planted foot turned with the body's heading, so as a walker turned its soles
/// spun on the ground about their joints, their toes sweeping over it (0.54% of the body's
/// length over a stance for walker 3 at half its turn rate). Measured on the mesh as skinned:
/// while a foot stays planted, none of its vertices moves over the ground by more than 0.2%.
#[test]
fn regression_planted_soles_do_not_spin_as_the_body_turns_over_them() {
    for seed in [3, 11, 32, 58] {
        let c = walker(seed);
        let ground = terrain(seed, &TerrainParams::for_creature(&c)).unwrap();
        let feet = foot_vertices(&c);
        let mut animator = Animator::new(&c).unwrap();
        let turn = 0.5 * animator.max_turn_rate();
        // Per leg, where its vertices were when it last landed.
        let mut landed: Vec<Option<Vec<Vec3>>> = vec![None; feet.len()];
        let mut worst = 0.0f32;
        for _ in 0..60 * 8 {
            let heading = animator.heading();
            let velocity = Vec3::new(heading.sin(), 0.0, heading.cos()) * c.speed;
            let intent = Intent::Move {
                velocity,
                turn_rate: turn,
            };
            animator.update(1.0 / 60.0, intent, &ground).unwrap();
            let posed = skinned(&c, &animator);
            for ((foot, planted), at) in feet.iter().zip(planted(&c, &animator)).zip(&mut landed) {
                if !planted {
                    *at = None;
                    continue;
                }
                let now: Vec<Vec3> = foot.iter().map(|&v| posed[v]).collect();
                let first = at.get_or_insert_with(|| now.clone());
                for (a, b) in first.iter().zip(&now) {
                    worst = worst.max(Vec3::new(a.x - b.x, 0.0, a.z - b.z).length() / c.length);
                }
            }
        }
        assert!(
            worst <= 0.002,
            "walker {seed}: a planted sole's vertex moved {worst} body lengths over the ground"
        );
    }
}

/// The live animator driven on flat ground as the baker drives it: from standing, forward
/// (+Z) at `speed` and turning at `turn_rate`, for a second's warm-up and then `frames`
/// frames, each frame's mesh skinned by the skinning matrices as a GPU would, relative to
/// where the creature stood and faced at the first of them.
fn live_frames(c: &d3::Creature, speed: f32, turn_rate: f32, frames: usize) -> Vec<Vec<Vec3>> {
    use creature::glam::Quat;
    let mut animator = Animator::new(c).unwrap();
    let warm_up = 30;
    let mut start = None;
    let mut out = Vec::with_capacity(frames);
    for frame in 0..warm_up + frames {
        let dt = if frame == 0 { 0.0 } else { 1.0 / 30.0 };
        let heading = animator.heading() + turn_rate * dt;
        let velocity = Vec3::new(heading.sin(), 0.0, heading.cos()) * speed;
        let intent = Intent::Move {
            velocity,
            turn_rate,
        };
        animator.update(dt, intent, &Plane::GROUND).unwrap();
        if frame < warm_up {
            continue;
        }
        let (at, facing) = *start.get_or_insert((
            animator.position(),
            Quat::from_rotation_y(animator.heading()),
        ));
        let back = facing.inverse();
        out.push(
            skinned(c, &animator)
                .into_iter()
                .map(|p| back * (p - at))
                .collect(),
        );
    }
    out
}

/// The farthest any vertex of `clip`'s frames (skinned as a viewer plays it) is from its
/// place in `live`'s, × the body's length.
fn farthest_from_live(c: &d3::Creature, clip: &d3::Clip, live: &[Vec<Vec3>]) -> f32 {
    let mut far = 0.0f32;
    for (frame, live) in live.iter().enumerate().take(clip.frames) {
        let baked = c.posed_positions(clip, frame).unwrap();
        for (b, l) in baked.iter().zip(live) {
            far = far.max(b.distance(*l));
        }
    }
    far / c.length
}

/// One code path for a plain walk: `bake_walk` drives the animator as a game would (an
/// `Intent::Move` forward on flat ground after a second's warm-up): skinned as a viewer plays
/// it, its mesh agrees with the live one frame for frame.
#[test]
fn a_baked_walk_is_the_live_animators_frames_on_flat_ground() {
    for seed in [3, 11, 32, 58, 123] {
        let c = walker(seed);
        let walk = c.bake_walk(2.0).unwrap();
        let live = live_frames(&c, c.speed, 0.0, walk.frames);
        let far = farthest_from_live(&c, &walk, &live);
        assert!(far < 1e-5, "seed {seed}: walk {far}");
    }
}

/// One code path for the walkers' baked clips too: `bake_clips` drives the animator on flat
/// ground as a game would (as `live_frames` does) and records its frames; a loop's closing then
/// moves them, so that its last frame is its first again, by a share of the loop's mismatch
/// that grows over the clip. Skinned as a viewer plays them: `idle` is the live animator's
/// frames exactly; `walk` and `run` (a hopper's `hop`) their first frame exactly and no frame
/// further from the live one than the last is (the whole mismatch, which the closing takes
/// back). (The `turn` is the animator's too, at a rate of its own.)
#[test]
fn the_baked_loops_are_the_live_animators_frames_on_flat_ground() {
    let (mut farthest, mut failed) = (Vec::new(), Vec::new());
    for seed in [3, 7, 11, 32, 58, 123] {
        let c = walker(seed);
        let setup = c.gait.as_ref().unwrap();
        let clips = c.bake_clips().unwrap();
        assert_eq!(clips.len(), 4, "seed {seed}");
        for clip in clips.iter().filter(|clip| clip.name != "turn") {
            let speed = match clip.name {
                "idle" => 0.0,
                "walk" => c.speed,
                "run" => setup.run_speed().unwrap(),
                "hop" => setup.hop_speed().unwrap(),
                other => panic!("seed {seed}: a walker's {other}"),
            };
            let live = live_frames(&c, speed, 0.0, clip.frames);
            let first = farthest_from_live(&c, clip, &live[..1]);
            let far = farthest_from_live(&c, clip, &live);
            let last = clip.frames - 1;
            let seam = {
                let baked = c.posed_positions(clip, last).unwrap();
                baked
                    .iter()
                    .zip(&live[last])
                    .map(|(b, l)| b.distance(*l))
                    .fold(0.0f32, f32::max)
                    / c.length
            };
            farthest.push((seed, clip.name, far, seam));
            let within = if clip.name == "idle" {
                1e-5
            } else {
                1.05 * seam + 1e-5
            };
            if first >= 1e-5 || far >= within {
                failed.push((seed, clip.name, first, far, seam));
            }
        }
    }
    println!("farthest from live, and at the seam, × body length: {farthest:?}");
    assert!(failed.is_empty(), "{failed:?}");
}

#[test]
fn regression_a_gait_set_up_with_more_hips_than_legs_is_an_error_not_a_panic() {
    // An edited set-up with a hip joint more than it has legs made `Animator::new` (and
    // `bake_walk`, which runs it) index past its legs.
    let mut c = walker(7);
    let setup = c.gait.as_mut().unwrap();
    let extra = setup.hip_joints[0];
    setup.hip_joints.push(extra);
    assert!(matches!(
        Animator::new(&c),
        Err(creature::Error::Degenerate { .. })
    ));
    assert!(matches!(
        c.bake_walk(1.0),
        Err(creature::Error::Degenerate { .. })
    ));
}

/// Creatures put down afresh under the terrain's surface, or high above it, are put onto it by
/// their first update: a walker's soles on the ground and planted, a flier and a swimmer above
/// it. Their rays, cast from just above the body, had found no ground: they stayed where they
/// were put, buried (a quarter of the playground's herd of 1,000 walkers on its 80 m terrain,
/// put down at height 0). Put between a floor and a roof, they come down to the floor.
#[test]
fn regression_a_creature_put_down_under_or_over_the_terrain_is_put_onto_it() {
    let ground = terrain(3, &TerrainParams::DEFAULT.with_extent(80.0, 193)).unwrap();
    // The highest ground on a 2 m grid over the terrain's middle 60 m.
    let (mut place, mut top) = (Vec3::ZERO, f32::NEG_INFINITY);
    for i in -15..=15 {
        for k in -15..=15 {
            let p = Vec3::new(2.0 * i as f32, 0.0, 2.0 * k as f32);
            let h = height(&ground, p);
            if h > top {
                (place, top) = (p, h);
            }
        }
    }
    for (label, c) in [
        ("walker 7", walker(7)),
        ("walker 11", walker(11)),
        ("flier 7", flier(7)),
        ("swimmer 7", swimmer(7)),
        ("slitherer 7", slitherer(7)),
    ] {
        // Deeper under the ground, and higher over it, than their rays reach from the body
        // (a flier's and a swimmer's start 4 lengths above it and reach 100 below).
        // (A slitherer's, 2 lengths above and below it.)
        let walks = c.gait.is_some() || c.kind == creature::limbs::CreatureKind::Slitherer;
        let deep = if walks { 2.0 } else { 5.0 };
        assert!(
            top > deep * c.length,
            "{label}: the ground at {place} is not above it"
        );
        for y in [0.0, top + 200.0 * c.length] {
            let label = format!("{label} put down at height {y} over ground at {top}");
            let mut animator = Animator::new(&c)
                .unwrap()
                .with_pose(Vec3::new(place.x, y, place.z), 0.0);
            animator.update(1.0 / 60.0, Intent::Stand, &ground).unwrap();
            stands_on(&c, &animator, &ground, &label);
        }
        // A floor at 0 under a roof 10 lengths up: put down between them, on the floor.
        let roof = 10.0 * c.length;
        let storeys = creature::gait::FnGround(|origin: Vec3, direction: Vec3, max: f32| {
            let h = if origin.y >= roof {
                roof
            } else if origin.y >= 0.0 {
                0.0
            } else {
                return None;
            };
            let distance = (origin.y - h) / -direction.y;
            (direction.y < 0.0 && distance <= max).then(|| creature::gait::RayHit {
                point: origin + direction * distance,
                normal: Vec3::Y,
                distance,
            })
        });
        let mut animator = Animator::new(&c)
            .unwrap()
            .with_pose(Vec3::new(0.0, 5.0 * c.length, 0.0), 0.0);
        animator
            .update(1.0 / 60.0, Intent::Stand, &storeys)
            .unwrap();
        let label = format!("{label} put down between a floor and a roof");
        stands_on(&c, &animator, &Plane::GROUND, &label);
    }
}

/// `c` as `animator` poses it stands on `ground`: a walker's soles on it and planted, a
/// slitherer's belly on it, a flier's or swimmer's lowest vertex above it by less than 5
/// lengths.
fn stands_on<G: Ground>(c: &d3::Creature, animator: &Animator, ground: &G, label: &str) {
    if c.kind == creature::limbs::CreatureKind::Slitherer {
        let gap = lowest_gap(c, animator, ground);
        assert!(
            gap.abs() <= ON_GROUND * c.length,
            "{label}: its lowest vertex {gap} over the ground"
        );
    } else if c.gait.is_some() {
        let posed = skinned(c, animator);
        let soles = soles(&posed, &foot_vertices(c), ground);
        for (sole, planted) in soles.into_iter().zip(planted(c, animator)) {
            assert!(planted, "{label}: a foot not planted");
            foot_on(sole, planted, c.length, label);
        }
    } else {
        let gap = lowest_gap(c, animator, ground);
        assert!(
            gap > 0.0 && gap < 5.0 * c.length,
            "{label}: its lowest vertex {gap} over the ground"
        );
    }
}

#[test]
fn a_walker_asked_to_go_faster_runs_and_slows_back_to_a_trot_its_feet_on_the_ground() {
    use creature::gait::Gait;
    // Walkers that run (walker 7, a biped, hops unless asked not to).
    let runner = d3::Params::DEFAULT
        .with_kind(Kind::Walker)
        .with_clips(false)
        .with_hop_chance(0.0);
    for seed in [7, 11, 42] {
        let c = d3::generate(seed, &runner).unwrap();
        let run = c.gait.as_ref().unwrap().run_speed().unwrap();
        // To its run speed over 3 s, held 2 s, back to its walking speed over 3 s.
        let speed = |t: f32| {
            let ramp = if t < 3.0 {
                t / 3.0
            } else if t < 5.0 {
                1.0
            } else {
                (8.0 - t) / 3.0
            };
            c.speed + (run - c.speed) * ramp.max(0.0)
        };
        let (gaits, flying) = ramp_feet_on_the_ground(&c, speed, 240, |_, _| {}, seed);
        assert_eq!(gaits, [Gait::Trot, Gait::Run, Gait::Trot], "seed {seed}");
        if foot_vertices(&c).len() <= 4 {
            assert!(flying > 0, "seed {seed}: never every foot off the ground");
        }
    }
}

/// Drives `c` straight ahead on flat ground at `speed(t)` for `frames` frames at 30 a second,
/// each frame its skinned soles never in the ground and on it when planted, then `each` with
/// the animator and its gait. The gaits in the order they came, and the frames in which every
/// foot was off the ground.
fn ramp_feet_on_the_ground(
    c: &d3::Creature,
    speed: impl Fn(f32) -> f32,
    frames: usize,
    mut each: impl FnMut(&Animator, creature::gait::Gait),
    seed: u64,
) -> (Vec<creature::gait::Gait>, usize) {
    let feet = foot_vertices(c);
    let ground = Plane::GROUND;
    let mut animator = Animator::new(c).unwrap();
    let mut gaits = vec![animator.controller().gait()];
    let mut flying = 0;
    for frame in 0..frames {
        let intent = Intent::Move {
            velocity: Vec3::Z * speed(frame as f32 / 30.0),
            turn_rate: 0.0,
        };
        animator.update(1.0 / 30.0, intent, &ground).unwrap();
        let gait = animator.controller().gait();
        if gaits.last() != Some(&gait) {
            gaits.push(gait);
        }
        let planted = planted(c, &animator);
        flying += usize::from(planted.iter().all(|&p| !p));
        let posed = skinned(c, &animator);
        assert!(posed.iter().all(|p| p.is_finite()));
        for (sole, planted) in soles(&posed, &feet, &ground).into_iter().zip(planted) {
            foot_on(
                sole,
                planted,
                c.length,
                &format!("seed {seed} frame {frame}"),
            );
        }
        each(&animator, gait);
    }
    (gaits, flying)
}

/// A belly is on the ground when its lowest vertex is within this many body lengths of it, and
/// no vertex may be deeper (the audit of delivered creatures' `ground`).
const ON_GROUND: f32 = 0.005;

/// The steps a slitherer crosses, in body lengths.
const STEP: f32 = 0.015;

/// Crawls `c` from the origin toward `target` on `ground` for at most `seconds`: every fifth
/// update, its skinned belly on the ground (the lowest vertex within [`ON_GROUND`] of it, none
/// deeper). The updates taken to arrive within 0.3 body lengths, `None` if it did not, and
/// how far it went from where it started (over the ground) and how many body waves it made
/// (by `beat_frequency`).
fn crawls<G: Ground>(
    c: &d3::Creature,
    ground: &G,
    intent: impl Fn(&Animator) -> Intent,
    seconds: f32,
    label: &str,
) -> (Option<usize>, f32, f32) {
    let mut animator = Animator::new(c).unwrap();
    let mut waves = 0.0;
    let dt = 1.0 / 30.0;
    let start = animator.position();
    let distance = |a: &Animator| {
        let moved = a.position() - start;
        Vec3::new(moved.x, 0.0, moved.z).length()
    };
    for frame in 0..(seconds / dt) as usize {
        let wanted = intent(&animator);
        animator.update(dt, wanted, ground).unwrap();
        waves += animator.beat_frequency().unwrap() * dt;
        if frame % 5 == 0 {
            let posed = skinned(c, &animator);
            let gaps: Vec<f32> = posed.iter().map(|&p| p.y - height(ground, p)).collect();
            let (v, lowest) =
                gaps.iter()
                    .copied()
                    .enumerate()
                    .fold(
                        (0, f32::INFINITY),
                        |m, (v, g)| if g < m.1 { (v, g) } else { m },
                    );
            assert!(
                lowest.abs() <= ON_GROUND * c.length,
                "{label} frame {frame}: its lowest vertex {v} (at rest {}, joints {:?} {:?}) {lowest} over the ground",
                c.mesh.positions[v],
                c.mesh.joints[v],
                c.mesh.weights[v],
            );
        }
        if let Intent::GoTo(target) = wanted {
            let p = animator.lead();
            if Vec3::new(p.x, 0.0, p.z).distance(target) < 0.3 * c.length {
                return (Some(frame), distance(&animator), waves);
            }
        }
    }
    eprintln!(
        "{label}: at {} heading {} after {seconds} s",
        animator.position(),
        animator.heading()
    );
    (None, distance(&animator), waves)
}

#[test]
fn a_slitherer_crawls_more_than_its_length_per_body_wave_its_belly_on_flat_ground() {
    for seed in [0, 5, 11, 23, 58] {
        let c = slitherer(seed);
        let label = format!("slitherer {seed}");
        let forward = |a: &Animator| Intent::Move {
            velocity: Vec3::new(a.heading().sin(), 0.0, a.heading().cos()) * c.speed,
            turn_rate: 0.0,
        };
        let (_, distance, waves) = crawls(&c, &Plane::GROUND, forward, 8.0, &label);
        assert!(waves > 2.0, "{label}: {waves} waves");
        let per_wave = distance / waves / c.length;
        // (The issue asks for one; the wave is made to carry it 1.14 or more: less would be
        // a body slipping back.)
        assert!(per_wave >= 1.1, "{label}: {per_wave} body lengths per wave");
        // And at its speed: 8 s at the speed it was asked (its head, where the position is,
        // swinging from side to side).
        assert!(
            (distance - 8.0 * c.speed).abs() < 0.05 * 8.0 * c.speed,
            "{label}: {distance} m in 8 s at {} m/s",
            c.speed
        );
    }
}

#[test]
fn a_slitherer_climbs_a_fifteen_degree_slope_to_a_target_on_its_belly() {
    let angle = 15f32.to_radians();
    let slope = Plane::new(Vec3::ZERO, Vec3::new(0.0, angle.cos(), -angle.sin())).unwrap();
    for seed in [1, 2, 3, 4] {
        let c = slitherer(seed);
        let label = format!("slitherer {seed} up 15°");
        let target = Vec3::new(2.0, 0.0, 10.0) * c.length;
        let (arrived, _, _) = crawls(&c, &slope, |_| Intent::GoTo(target), 60.0, &label);
        assert!(arrived.is_some(), "{label}: did not arrive");
    }
}

#[test]
fn a_slitherer_turns_round_over_hills_to_a_target_behind_it_on_its_belly() {
    for seed in [1, 2, 3, 4] {
        let c = slitherer(seed);
        // Steps 1.5% of its length high (about a third of its body's thickness), as
        // `TerrainParams::for_creature` makes them for it.
        let params = TerrainParams::DEFAULT
            .with_extent(40.0 * c.length, 321)
            .with_hills(0.3 * c.length, 6.0 * c.length)
            .with_slope(10.0)
            .with_steps(STEP * c.length, 3.0 * c.length);
        let ground = terrain(seed, &params).unwrap();
        for target in [Vec3::new(6.0, 0.0, 8.0), Vec3::new(-8.0, 0.0, -6.0)] {
            let label = format!("slitherer {seed} to {target}");
            let target = target * c.length;
            let (arrived, _, _) = crawls(&c, &ground, |_| Intent::GoTo(target), 90.0, &label);
            assert!(arrived.is_some(), "{label}: did not arrive");
        }
    }
}

/// A creature edited to a speed that is not a number or below zero is a typed error; one edited
/// to crawl a millionth of a metre or a million metres a second animates without a panic, a
/// hang or a NaN (a crawl past its whole kept path is taken straight), and one too slow to
/// bake a wave in a minute (or so fast a wave is shorter than a frame) is a typed error, not a
/// clip of a million seconds.
#[test]
fn regression_an_edited_slitherers_speed_is_an_error_or_animates() {
    let c = slitherer(3);
    for speed in [f32::NAN, f32::INFINITY, -1.0] {
        let mut edited = c.clone();
        edited.speed = speed;
        assert!(Animator::new(&edited).is_err(), "speed {speed}");
    }
    for speed in [0.0, 1e-6, 1e6] {
        let mut edited = c.clone();
        edited.speed = speed;
        let mut animator = Animator::new(&edited).unwrap();
        for k in 0..20 {
            let intent = Intent::Move {
                velocity: Vec3::Z * speed,
                turn_rate: if k % 2 == 0 { 1.0 } else { -1.0 },
            };
            animator.update(0.1, intent, &Plane::GROUND).unwrap();
            assert!(
                animator.skinning_matrices().iter().all(|m| m.is_finite()),
                "speed {speed}"
            );
        }
        // Standing still its `slither` is its lying still; a wave longer than a minute, or
        // shorter than a frame, is no clip.
        let baked = edited.bake_clips().map(|clips| clips.len());
        assert_eq!(baked.is_ok(), speed == 0.0, "speed {speed}: {baked:?}");
    }
}

/// The mean size of `c`'s walking legs (a Froude number's length).
fn setup_leg(c: &d3::Creature) -> f32 {
    let legs = &c.gait.as_ref().unwrap().legs;
    let walking: Vec<f32> = legs
        .iter()
        .filter(|l| l.kind == creature::gait::LimbKind::Leg)
        .map(|l| l.size)
        .collect();
    walking.iter().sum::<f32>() / walking.len() as f32
}

/// The height of joint `joint` over the root, in the body's frame (its rotation taken off).
fn over_root(animator: &Animator, joint: usize, root: usize) -> f32 {
    let world = animator.world_transforms();
    let root = world[root];
    (root.inverse().transform_point3a(world[joint].translation)).y
}

#[test]
fn a_hopper_asked_to_go_faster_hops_its_tail_up_and_walks_again_its_feet_on_the_ground() {
    use creature::gait::Gait;
    let params = d3::Params::DEFAULT
        .with_kind(Kind::Walker)
        .with_hop_chance(1.0);
    for seed in [7, 11, 101] {
        let c = d3::generate(seed, &params).unwrap();
        let hop = c.gait.as_ref().unwrap().hop_speed().unwrap();
        let joints = &c.skeleton.joints;
        let tail = joints.iter().position(|j| j.name == "tail_end").unwrap();
        let root = joints.iter().position(|j| j.parent.is_none()).unwrap();
        let rest = over_root(&Animator::new(&c).unwrap(), tail, root);
        let (mut highest, mut last) = (f32::MIN, 0.0);
        // To its hop speed over 3 s, held 2 s, back to the fastest a walker walks (a Froude
        // number of 1, above the hop's hysteresis) over 3 s, held 2 s.
        let fastest = (9.81 * setup_leg(&c)).sqrt();
        let speed = |t: f32| {
            if t < 3.0 {
                c.speed + (hop - c.speed) * t / 3.0
            } else if t < 5.0 {
                hop
            } else {
                hop + (fastest - hop) * ((t - 5.0) / 3.0).min(1.0)
            }
        };
        let tail_up = |animator: &Animator, gait: Gait| {
            let up = over_root(animator, tail, root) - rest;
            if gait == Gait::Hop {
                highest = highest.max(up);
            }
            last = up;
        };
        let (gaits, flying) = ramp_feet_on_the_ground(&c, speed, 300, tail_up, seed);
        assert_eq!(gaits, [Gait::Walk, Gait::Hop, Gait::Walk], "seed {seed}");
        assert!(
            flying >= 10,
            "seed {seed}: {flying} frames with both feet up"
        );
        // The tail's tip swung up 2.5% of the body's length at least while hopping (measured
        // 3.3-7.3%), and back down after (within a hundredth).
        assert!(
            highest >= 0.025 * c.length,
            "seed {seed}: the tail rose {highest}"
        );
        assert!(
            last.abs() <= 0.01 * c.length,
            "seed {seed}: the tail stayed {last} up"
        );
    }
}

#[test]
fn a_hopper_hops_over_hilly_stepped_terrain_its_feet_on_the_surface() {
    use creature::gait::Gait;
    let params = d3::Params::DEFAULT
        .with_kind(Kind::Walker)
        .with_clips(false)
        .with_hop_chance(1.0);
    for (seed, slope) in [(7, 12.0), (11, 20.0), (101, 12.0)] {
        let c = d3::generate(seed, &params).unwrap();
        let setup = c.gait.as_ref().unwrap();
        let hop = setup.hop_speed().unwrap();
        let leg = setup
            .legs
            .iter()
            .map(|l| l.size)
            .fold(f32::INFINITY, f32::min);
        let ground = hilly(&c, seed, slope, 0.15 * leg);
        let feet = foot_vertices(&c);
        let mut animator = Animator::new(&c).unwrap();
        let target = Vec3::new(6.0 * c.length, 0.0, 8.0 * c.length);
        let (mut hopped, mut arrived) = (0, false);
        for frame in 0..30 * 20 {
            // Toward the target at its hop speed, turning as a go-to turns.
            let to = target - animator.position();
            if Vec3::new(to.x, 0.0, to.z).length() < c.length {
                arrived = true;
                break;
            }
            let error = (to.x.atan2(to.z) - animator.heading() + core::f32::consts::PI)
                .rem_euclid(core::f32::consts::TAU)
                - core::f32::consts::PI;
            let h = animator.heading();
            let intent = Intent::Move {
                velocity: Vec3::new(h.sin(), 0.0, h.cos()) * hop,
                turn_rate: 2.0 * error,
            };
            animator.update(1.0 / 30.0, intent, &ground).unwrap();
            hopped += usize::from(animator.controller().gait() == Gait::Hop);
            let posed = skinned(&c, &animator);
            assert!(posed.iter().all(|p| p.is_finite()));
            let planted = planted(&c, &animator);
            for (sole, planted) in soles(&posed, &feet, &ground).into_iter().zip(planted) {
                foot_on(
                    sole,
                    planted,
                    c.length,
                    &format!("hopper {seed} frame {frame}"),
                );
            }
        }
        assert!(arrived, "hopper {seed} did not arrive");
        assert!(hopped >= 30, "hopper {seed} hopped {hopped} frames");
    }
}
