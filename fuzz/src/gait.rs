//! `creature-gait`: a `Controller` with arbitrary legs and chains over an arbitrary ground (a
//! closure whose hits come from the input, heights and normals included), driven by a sequence
//! of arbitrary time steps, poses and velocities. After every accepted update the state is
//! finite (feet, knees, reacted pose with a unit rotation, chains, metrics); a rejected update
//! changes nothing; the same sequence gives the same states.

use arbitrary::Arbitrary;
use creature_gait::{Chain, Controller, FnGround, GaitOptions, Leg, Pose, RayHit};
use glam::{Quat, Vec3};

use crate::{map, pick, pick3};

#[derive(Debug, Clone, Arbitrary)]
pub struct LegIn {
    pub hip: [f32; 3],
    pub foot: [f32; 3],
    pub upper: f32,
    pub lower: f32,
}

#[derive(Debug, Clone, Arbitrary)]
pub struct ChainIn {
    pub root: [f32; 3],
    pub direction: [f32; 3],
    pub segments: u8,
    pub length: f32,
}

#[derive(Debug, Clone, Arbitrary)]
pub struct StepIn {
    pub dt: f32,
    pub position: [f32; 3],
    pub rotation: [f32; 4],
    pub velocity: [f32; 3],
    pub angular: [f32; 3],
}

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub valid: bool,
    pub legs: Vec<LegIn>,
    pub chains: Vec<ChainIn>,
    /// Hit heights, picked by the ray's origin; an empty list is no ground at all.
    pub heights: Vec<f32>,
    pub normal: [f32; 3],
    pub steps: Vec<StepIn>,
}

fn controller(input: &Input) -> Option<Controller> {
    let v = input.valid;
    let legs: Vec<Leg> = input
        .legs
        .iter()
        .take(8)
        .map(|l| {
            let hip = pick3(v, l.hip, -1.0, 1.0);
            let (hip, rest) = if v {
                (
                    hip + Vec3::Y,
                    hip + pick3(true, l.foot, -0.3, 0.3) - Vec3::Y * 0.6,
                )
            } else {
                (hip, Vec3::from(l.foot))
            };
            Leg::new(
                hip,
                rest,
                pick(v, l.upper, 0.3, 1.0),
                pick(v, l.lower, 0.3, 1.0),
            )
        })
        .collect();
    let options = GaitOptions::DEFAULT;
    let mut c = if legs.is_empty() {
        Controller::chains_only(pick(v, input.normal[0], 0.1, 2.0), &options).ok()?
    } else {
        let c = Controller::new(&legs, &options);
        if v {
            assert!(c.is_ok(), "valid legs rejected: {c:?}");
        }
        c.ok()?
    };
    for ch in input.chains.iter().take(3) {
        let chain = Chain::new(
            pick3(v, ch.root, -1.0, 1.0),
            if v {
                Vec3::NEG_Z + pick3(true, ch.direction, -0.5, 0.5)
            } else {
                Vec3::from(ch.direction)
            },
            if v {
                usize::from(ch.segments % 8) + 1
            } else {
                usize::from(ch.segments)
            },
            pick(v, ch.length, 0.05, 0.5),
        );
        let before = format!("{c:?}");
        match c.add_chain(chain) {
            Ok(_) => {}
            Err(_) => assert_eq!(
                format!("{c:?}"),
                before,
                "a rejected chain changed the controller"
            ),
        }
    }
    Some(c)
}

/// Asserts the controller's readable state is finite.
fn check(c: &Controller) {
    let pose = c.reacted_pose();
    assert!(
        pose.translation.is_finite() && pose.rotation.is_finite() && pose.rotation.is_normalized(),
        "reacted pose {pose:?}"
    );
    for (i, s) in c.leg_states().iter().enumerate() {
        assert!(
            s.foot.is_finite()
                && s.normal.is_finite()
                && s.joints.middle.is_finite()
                && s.joints.end.is_finite(),
            "leg {i}: {s:?}"
        );
        assert!(
            s.progress.is_finite() && s.hip_roll.is_finite(),
            "leg {i}: {s:?}"
        );
    }
    for chain in 0..c.chain_count() {
        assert!(
            c.chain(chain).unwrap().iter().all(|p| p.is_finite()),
            "chain {chain}"
        );
    }
    let m = c.metrics();
    assert!(
        m.max_skate.is_finite() && m.max_overstretch.is_finite(),
        "metrics {m:?}"
    );
    assert!(
        m.stability_margin.is_none_or(f32::is_finite),
        "stability margin {:?}",
        m.stability_margin
    );
    let body = c.body();
    assert!(
        body.offset.is_finite() && body.rotation.is_finite(),
        "body {body:?}"
    );
    let look = c.look();
    assert!(
        look.rotation.is_finite() && look.target.is_finite(),
        "look {look:?}"
    );
}

/// Runs the whole sequence, returning every state.
fn simulate(input: &Input) -> Vec<String> {
    let Some(mut c) = controller(input) else {
        return Vec::new();
    };
    let v = input.valid;
    let heights: Vec<f32> = input
        .heights
        .iter()
        .take(16)
        .map(|h| pick(v, *h, -0.5, 0.5))
        .collect();
    let normal = if v {
        Vec3::Y + pick3(true, input.normal, -0.3, 0.3)
    } else {
        Vec3::from(input.normal)
    };
    let ground = FnGround(|origin: Vec3, direction: Vec3, max: f32| {
        if heights.is_empty() {
            return None;
        }
        // The same origin always gets the same height. An arbitrary ground may ignore
        // `max_distance`: the controller must not trust it.
        let i = (origin.x.to_bits() ^ origin.z.to_bits().rotate_left(7)) as usize % heights.len();
        let h = heights[i];
        let distance = if direction.y < 0.0 {
            (origin.y - h) / -direction.y
        } else {
            f32::NAN
        };
        (distance >= 0.0 && (distance <= max || !v)).then(|| RayHit {
            point: origin + direction * distance,
            normal: if v { normal.normalize() } else { normal },
            distance,
        })
    });
    let mut states = Vec::new();
    let mut time = 0.0f32;
    for s in input.steps.iter().take(24) {
        let dt = pick(v, s.dt, 0.0, 0.1);
        time += dt;
        let (pose, velocity, angular) = if v {
            let velocity = pick3(true, s.velocity, -3.0, 3.0) * Vec3::new(1.0, 0.1, 1.0);
            let yaw = map(s.rotation[0], -3.2, 3.2);
            (
                Pose::from_yaw(
                    velocity * time + Vec3::Y * map(s.position[1], 0.8, 1.2),
                    yaw,
                ),
                velocity,
                Vec3::Y * map(s.angular[1], -2.0, 2.0),
            )
        } else {
            (
                Pose::new(Vec3::from(s.position), Quat::from_array(s.rotation)),
                Vec3::from(s.velocity),
                Vec3::from(s.angular),
            )
        };
        let before = format!("{c:?}");
        match c.update(dt, pose, velocity, angular, &ground) {
            Ok(()) => check(&c),
            Err(e) => {
                assert!(!v, "valid update rejected: {e:?}");
                assert_eq!(
                    format!("{c:?}"),
                    before,
                    "a rejected update ({e:?}) changed the controller"
                );
            }
        }
        states.push(format!("{c:?}"));
    }
    states
}

pub fn run(input: &Input) {
    let states = simulate(input);
    assert_eq!(simulate(input), states, "determinism");
}
