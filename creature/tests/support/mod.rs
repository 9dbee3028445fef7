//! Shared checks for the integration tests: what a valid creature is.

#![allow(dead_code, unreachable_pub)]

use core::fmt;

use creature::gait::{Plane, Pose};
use creature::glam::{Vec2, Vec3};
use creature::limbs::{CreatureKind, LimbKind};
use creature::march::{Ring, validate_rings};
use creature::{Error, d2, d3};

/// Every problem of `c`, empty when it is valid: finite data, a closed simple outline, every
/// ball centre and every triangle inside it, minimum angle ≥ 20°, weights summing to 1 with at
/// most 4 influences on valid joints, and a non-empty texture when there is one.
pub fn check(c: &d2::Creature) -> Vec<String> {
    let mut p = Vec::new();
    let m = &c.mesh;
    let n = m.positions.len();
    if n == 0 || m.indices.is_empty() {
        p.push("empty mesh".to_string());
        return p;
    }
    if m.uvs.len() != n || m.joints.len() != n || m.weights.len() != n {
        p.push("attribute lengths differ".to_string());
    }
    if !m.positions.iter().all(|v| v.is_finite()) || !m.uvs.iter().all(|v| v.is_finite()) {
        p.push("non-finite vertex".to_string());
    }
    if m.positions
        .iter()
        .any(|v| !(-1e-6..=1.0 + 1e-6).contains(&v.z))
    {
        p.push("z outside [0, 1]".to_string());
    }
    // Outline: closed (rings of ≥ 3 points), simple (no crossings), one outer ring.
    let rings: Vec<Ring> = c
        .outline
        .iter()
        .enumerate()
        .map(|(i, pts)| Ring {
            points: pts.clone(),
            hole: i > 0,
            parent: (i > 0).then_some(0),
        })
        .collect();
    if let Err(e) = validate_rings(&rings) {
        p.push(format!("outline not simple: {e}"));
    }
    let inside = |q: Vec2| rings.iter().filter(|r| r.contains(q)).count() % 2 == 1;
    let outside_balls = c.balls.iter().filter(|b| !inside(b.ball.center)).count();
    if outside_balls > 0 {
        p.push(format!("{outside_balls} ball centres outside"));
    }
    let mut outside_triangles = 0;
    for t in &m.indices {
        if t.iter().any(|&i| i as usize >= n) {
            p.push("index out of range".to_string());
            break;
        }
        let centroid = t
            .iter()
            .map(|&i| m.positions[i as usize].truncate())
            .sum::<Vec2>()
            / 3.0;
        if !inside(centroid) {
            outside_triangles += 1;
        }
    }
    if outside_triangles > 0 {
        p.push(format!("{outside_triangles} triangles outside"));
    }
    if !(c.quality.min_angle >= 20.0) {
        p.push(format!("min angle {}", c.quality.min_angle));
    }
    for (j, w) in m.joints.iter().zip(&m.weights) {
        let sum: f32 = w.iter().sum();
        if (sum - 1.0).abs() > 1e-5 || w.iter().any(|x| !x.is_finite() || *x < 0.0) {
            p.push(format!("weights {w:?}"));
            break;
        }
        if j.iter().any(|&j| j as usize >= c.bones.len()) {
            p.push(format!("joints {j:?}"));
            break;
        }
    }
    if let Some(t) = &c.texture
        && !t.rgba.chunks_exact(4).any(|px| px[3] > 0)
    {
        p.push("empty texture".to_string());
    }
    p
}

/// Counts over a sweep.
#[derive(Default)]
pub struct SweepStats {
    pub creatures: usize,
    pub bones: Vec<usize>,
    pub balls: Vec<usize>,
    pub vertices: Vec<usize>,
    pub triangles: Vec<usize>,
    pub min_angle: f32,
    pub incomplete_refinement: usize,
}

impl SweepStats {
    pub fn add(&mut self, c: &d2::Creature) {
        if self.creatures == 0 {
            self.min_angle = f32::MAX;
        }
        self.creatures += 1;
        self.bones.push(c.bones.len());
        self.balls.push(c.balls.len());
        self.vertices.push(c.mesh.positions.len());
        self.triangles.push(c.mesh.indices.len());
        self.min_angle = self.min_angle.min(c.quality.min_angle);
        if !c.quality.refinement_complete {
            self.incomplete_refinement += 1;
        }
    }
}

fn spread(v: &[usize]) -> String {
    let mut v = v.to_vec();
    v.sort_unstable();
    if v.is_empty() {
        return "-".into();
    }
    let at = |q: f32| v[((v.len() - 1) as f32 * q) as usize];
    format!(
        "{}/{}/{} ({}–{})",
        at(0.1),
        at(0.5),
        at(0.9),
        v[0],
        v[v.len() - 1]
    )
}

impl fmt::Display for SweepStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "valid creatures: {}; p10/median/p90 (min–max):",
            self.creatures
        )?;
        writeln!(f, "  bones {}", spread(&self.bones))?;
        writeln!(f, "  balls {}", spread(&self.balls))?;
        writeln!(f, "  vertices {}", spread(&self.vertices))?;
        writeln!(f, "  triangles {}", spread(&self.triangles))?;
        write!(
            f,
            "  smallest angle {:.2}°, refinement incomplete in {}",
            self.min_angle, self.incomplete_refinement
        )
    }
}

// --- 3D creatures ---

/// Every problem of `c`, empty when it is valid: [`check_3d_data`] and [`check_3d_estimates`].
pub fn check_3d(c: &d3::Creature) -> Vec<String> {
    let mut p = check_3d_data(c);
    if p.iter().all(|s| s != "empty mesh") {
        p.extend(check_3d_estimates(c));
    }
    p
}

/// The problems of `c`'s data: finite attributes, indices in range, no degenerate triangle,
/// weights on valid joints, one skeleton tree, the lattice, bends, the rest pose above the
/// floor, walkers' feet on the ground at rest and their walk and turn clips baked and
/// well-formed. How the creature stands and moves as delivered is the audit's
/// (`creature-audit`, `tests/audit.rs`).
pub fn check_3d_data(c: &d3::Creature) -> Vec<String> {
    let mut p = Vec::new();
    let m = &c.mesh;
    let n = m.positions.len();
    if n == 0 || m.indices.is_empty() {
        return vec!["empty mesh".into()];
    }
    if m.normals.len() != n || m.colours.len() != n || m.joints.len() != n || m.weights.len() != n {
        p.push("attribute lengths differ".into());
    }
    if !m
        .positions
        .iter()
        .chain(&m.normals)
        .chain(&m.colours)
        .all(|v| v.is_finite())
    {
        p.push("non-finite vertex data".into());
    }
    if m.colours
        .iter()
        .any(|c| c.min_element() < 0.0 || c.max_element() > 1.0)
    {
        p.push("vertex colour outside [0, 1]".into());
    }
    if m.indices.iter().flatten().any(|&i| i as usize >= n) {
        p.push("index out of range".into());
    }
    let size = c.length;
    let degenerate = m
        .indices
        .iter()
        .filter(|t| {
            let [a, b, d] = t.map(|i| m.positions[i as usize]);
            (b - a).cross(d - a).length() <= 1e-9 * size * size
        })
        .count();
    if degenerate > 0 {
        p.push(format!("{degenerate} degenerate triangles"));
    }
    let joints = c.skeleton.joints.len();
    for (j, w) in m.joints.iter().zip(&m.weights) {
        if (w.iter().sum::<f32>() - 1.0).abs() > 1e-4
            || w.iter().any(|&x| !(0.0..=1.0).contains(&x))
        {
            p.push(format!("bad weights {w:?}"));
            break;
        }
        if j.iter()
            .zip(w)
            .any(|(&j, &w)| w > 0.0 && usize::from(j) >= joints)
        {
            p.push(format!("joint out of range {j:?}"));
            break;
        }
    }
    for (i, joint) in c.skeleton.joints.iter().enumerate() {
        if joint.parent.is_some_and(|q| q >= joints || q == i) {
            p.push(format!("joint {i} has a bad parent"));
        }
    }
    if c.skeleton
        .joints
        .iter()
        .filter(|j| j.parent.is_none())
        .count()
        != 1
    {
        p.push("not one root".into());
    }
    if !(c.quality.ffd_min_determinant > 0.0) {
        p.push("the lattice folds".into());
    }
    if c.quality.min_height < -1e-5 * size {
        p.push(format!("under the floor: {}", c.quality.min_height));
    }
    if c.quality.max_weight_sum_error > 1e-4 {
        p.push("weight sums".into());
    }
    if c.quality
        .bend_degrees
        .iter()
        .any(|&b| !(0.0..=100.0 + 1e-3).contains(&b))
    {
        p.push(format!("bend {:?}", c.quality.bend_degrees));
    }
    if c.kind == CreatureKind::Walker {
        // Every foot at rest reaches the ground (y = 0).
        for leg in c.plan.limbs_of(LimbKind::Leg) {
            let foot = leg.foot.unwrap_or(Vec3::splat(f32::NAN)) + Vec3::Y * c.ground_offset;
            if !(foot.y.abs() <= 1e-3 * size) {
                p.push(format!("foot not on the ground: {foot}"));
            }
        }
        if c.plan.leg_pairs() == 0 {
            p.push("walker without legs".into());
        }
        if let Err(e) = baked_skate(c) {
            p.push(format!("bake: {e}"));
        }
    }
    p
}

/// The problems the generator's own estimates show: walkers' stability margin (from bone
/// widths and a nominal foot), 2 s of the gait controller's foot skate and overstretch, the
/// baked walk's and turn's planted feet moving, legs of a side sweeping the same stretch of
/// the body, and the skinned mesh under the floor in every third frame. The sweep leaves
/// these to the audit of the delivered creature; the regression tests of the bugs they found
/// keep them.
pub fn check_3d_estimates(c: &d3::Creature) -> Vec<String> {
    let mut p = Vec::new();
    let size = c.length;
    if c.kind == CreatureKind::Walker {
        if !(c.quality.stability_margin.unwrap_or(-1.0) > 0.0) {
            p.push(format!("unstable: {:?}", c.quality.stability_margin));
        }
        match walk(c) {
            Ok((skate, overstretch)) => {
                if skate > 1e-3 * size {
                    p.push(format!("foot skate {skate}"));
                }
                if overstretch > 1e-3 * size {
                    p.push(format!("overstretch {overstretch}"));
                }
            }
            Err(e) => p.push(format!("walk: {e}")),
        }
        // Nothing under the floor while animated either (every third frame of every clip).
        for clip in &c.clips {
            for frame in (0..clip.frames).step_by(3) {
                match c.posed_positions(clip, frame) {
                    Ok(posed) => {
                        let low = posed.iter().map(|v| v.y).fold(f32::INFINITY, f32::min);
                        if low < -1e-3 * size {
                            p.push(format!(
                                "{} frame {frame} under the floor: {low}",
                                clip.name
                            ));
                            break;
                        }
                    }
                    Err(e) => p.push(format!("posing {}: {e}", clip.name)),
                }
            }
        }
        if let Ok(skate) = baked_skate(c)
            && skate > 1e-3 * size
        {
            p.push(format!("baked walk or turn skates {skate}"));
        }
        // No two legs on one side sweep overlapping stretches of the body.
        let legs: Vec<_> = c.plan.limbs_of(LimbKind::Leg).collect();
        for (i, a) in legs.iter().enumerate() {
            for b in legs.iter().skip(i + 1) {
                if a.side == b.side && a.span.overlaps(&b.span) {
                    p.push(format!("legs overlap on bones {} and {}", a.bone, b.bone));
                }
            }
        }
    }
    p
}

/// Walks `c` forward at its speed for 2 s at 30 fps on flat ground; the worst foot skate and
/// overstretch seen.
pub fn walk(c: &d3::Creature) -> Result<(f32, f32), Error> {
    let setup = c.gait.as_ref().ok_or(Error::Degenerate {
        what: "gait set-up",
    })?;
    let mut controller = setup.controller()?;
    let ground = Plane::horizontal(0.0);
    let velocity = Vec3::Z * c.speed;
    let mut position = Vec3::ZERO;
    let (mut skate, mut overstretch) = (0.0f32, 0.0f32);
    for _ in 0..60 {
        position += velocity / 30.0;
        controller.update(
            1.0 / 30.0,
            Pose::from_yaw(position, 0.0),
            velocity,
            Vec3::ZERO,
            &ground,
        )?;
        skate = skate.max(controller.metrics().max_skate);
        overstretch = overstretch.max(controller.metrics().max_overstretch);
    }
    Ok((skate, overstretch))
}

/// Measures, by forward kinematics of the walker's `walk` and `turn` clips, the largest
/// distance a foot joint moves between two frames in which it is planted; also checks the
/// clips' data.
pub fn baked_skate(c: &d3::Creature) -> Result<f32, Error> {
    let mut skate = 0.0f32;
    let mut baked = 0;
    for clip in c
        .clips
        .iter()
        .filter(|c| c.name == "walk" || c.name == "turn")
    {
        skate = skate.max(skate_of(c, clip)?);
        baked += 1;
    }
    if baked != 2 {
        return Err(Error::Degenerate {
            what: "walker without its walk and turn clips",
        });
    }
    Ok(skate)
}

pub fn skate_of(c: &d3::Creature, clip: &creature::d3::Clip) -> Result<f32, Error> {
    let setup = c.gait.as_ref().ok_or(Error::Degenerate { what: "gait" })?;
    assert_eq!(clip.root_translation.len(), clip.frames);
    assert_eq!(clip.contacts.len(), clip.frames);
    for track in &clip.tracks {
        assert_eq!(track.rotations.len(), clip.frames);
        assert!(
            track
                .rotations
                .iter()
                .all(|q| q.is_finite() && q.is_normalized())
        );
    }
    let mut skate = 0.0f32;
    let mut previous = c.pose(clip, 0);
    for frame in 1..clip.frames {
        let pose = c.pose(clip, frame);
        for (leg, &hip) in setup.hip_joints.iter().enumerate() {
            if setup.legs[leg].kind != creature::gait::LimbKind::Leg {
                continue;
            }
            if clip.contacts[frame - 1][leg] && clip.contacts[frame][leg] {
                let a = previous[hip + 2].translation;
                let b = pose[hip + 2].translation;
                skate = skate.max(Vec3::from(a).distance(Vec3::from(b)));
            }
        }
        previous = pose;
    }
    Ok(skate)
}
