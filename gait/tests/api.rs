//! Integration tests of the layers, the errors, the grounds and the IK through the public API.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use approx::assert_relative_eq;
use creature_gait::glam::{Quat, Vec2, Vec3};
use creature_gait::{
    Chain, Controller, FnGround, GaitError, GaitOptions, Ground, HeightCurve, HeightField, Leg,
    LimbKind, Plane, Pose, RayHit, ReachCurve, solve_two_bone,
};
use support::creature_legs;

const DT: f32 = 1.0 / 60.0;

fn quadruped() -> Controller {
    Controller::new(&creature_legs(2, 1.0), &GaitOptions::DEFAULT).unwrap()
}

fn standing() -> Pose {
    Pose::new(Vec3::new(0.0, 0.8, 0.0), Quat::IDENTITY)
}

// ----- errors --------------------------------------------------------------------------------

#[test]
fn bad_inputs_are_typed_errors_and_leave_the_state_alone() {
    let mut c = quadruped();
    let g = Plane::GROUND;
    c.update(DT, standing(), Vec3::ZERO, Vec3::ZERO, &g)
        .unwrap();
    let before = c.clone();
    let cases: [(f32, Pose, Vec3, Vec3); 7] = [
        (f32::NAN, standing(), Vec3::ZERO, Vec3::ZERO),
        (-0.1, standing(), Vec3::ZERO, Vec3::ZERO),
        (
            DT,
            Pose::new(Vec3::NAN, Quat::IDENTITY),
            Vec3::ZERO,
            Vec3::ZERO,
        ),
        (
            DT,
            Pose::new(Vec3::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 0.0)),
            Vec3::ZERO,
            Vec3::ZERO,
        ),
        (DT, standing(), Vec3::INFINITY, Vec3::ZERO),
        (DT, standing(), Vec3::ZERO, Vec3::new(0.0, f32::NAN, 0.0)),
        (
            DT,
            Pose::new(Vec3::splat(1e9), Quat::IDENTITY),
            Vec3::ZERO,
            Vec3::ZERO,
        ),
    ];
    for (dt, pose, v, w) in cases {
        assert!(c.update(dt, pose, v, w, &g).is_err());
        assert_eq!(c, before);
    }
    assert_eq!(
        c.update(-1.0, standing(), Vec3::ZERO, Vec3::ZERO, &g),
        Err(GaitError::NegativeTimeStep { dt: -1.0 })
    );
}

#[test]
fn bad_legs_and_options_are_rejected() {
    assert_eq!(
        Controller::new(&[], &GaitOptions::DEFAULT),
        Err(GaitError::NoLegs)
    );
    let mut legs = creature_legs(1, 1.0);
    legs[1].lower = 0.0;
    assert!(matches!(
        Controller::new(&legs, &GaitOptions::DEFAULT),
        Err(GaitError::NotPositive { index: 1, .. })
    ));
    let legs = creature_legs(1, 1.0);
    assert!(matches!(
        Controller::new(&legs, &GaitOptions::DEFAULT.with_overshoot(3.0)),
        Err(GaitError::OutOfRange { .. })
    ));
    let mut c = Controller::new(&legs, &GaitOptions::DEFAULT).unwrap();
    assert!(c.set_blend(1.5).is_err());
    assert!(c.set_head(Vec3::NAN).is_err());
    assert!(
        c.add_chain(Chain::new(Vec3::ZERO, Vec3::ZERO, 3, 0.1))
            .is_err()
    );
    assert!(matches!(
        c.leg_state(9),
        Err(GaitError::IndexOutOfRange { .. })
    ));
    assert!(matches!(c.chain(0), Err(GaitError::IndexOutOfRange { .. })));
}

#[test]
fn a_ground_that_returns_garbage_is_treated_as_no_ground() {
    let garbage = FnGround(|_: Vec3, _: Vec3, _: f32| {
        Some(RayHit {
            point: Vec3::NAN,
            normal: Vec3::ZERO,
            distance: f32::NAN,
        })
    });
    let mut c = quadruped();
    for k in 0..30 {
        let pose = Pose::new(Vec3::new(0.0, 0.8, k as f32 * 0.05), Quat::IDENTITY);
        c.update(DT, pose, Vec3::Z * 3.0, Vec3::ZERO, &garbage)
            .unwrap();
    }
    for s in c.leg_states() {
        assert!(!s.grounded && !s.planted && s.foot.is_finite());
    }
}

// ----- grounds -------------------------------------------------------------------------------

#[test]
fn height_field_vertical_casts_are_exact() {
    let f = support::random_terrain(5, 0.4);
    for k in 0..100 {
        let (x, z) = (-30.0 + k as f32 * 0.61, 25.0 - k as f32 * 0.47);
        let hit = f
            .cast_ray(Vec3::new(x, 10.0, z), Vec3::NEG_Y, 20.0)
            .unwrap();
        assert_eq!(hit.point.y, f.height(x, z).unwrap());
        assert!(hit.normal.is_normalized() && hit.normal.y > 0.0);
    }
}

#[test]
fn a_closure_ground_walks_like_a_plane() {
    let plane = Plane::horizontal(0.25);
    let closure = FnGround(|o: Vec3, d: Vec3, m: f32| plane.cast_ray(o, d, m));
    let walk = |ground: &dyn Ground| {
        let mut c = quadruped();
        for k in 0..200 {
            let pose = Pose::new(Vec3::new(0.0, 1.05, k as f32 * DT), Quat::IDENTITY);
            c.update(DT, pose, Vec3::Z, Vec3::ZERO, ground).unwrap();
        }
        c
    };
    assert_eq!(walk(&plane), walk(&closure));
}

#[test]
fn feet_stand_on_a_tilted_plane() {
    let slope = Plane::new(Vec3::ZERO, Vec3::new(0.0, 1.0, -0.2)).unwrap();
    let mut c = quadruped();
    for k in 0..300 {
        let z = k as f32 * DT;
        let pose = Pose::new(Vec3::new(0.0, 0.8 + 0.2 * z, z), Quat::IDENTITY);
        c.update(DT, pose, Vec3::new(0.0, 0.2, 1.0), Vec3::ZERO, &slope)
            .unwrap();
        for s in c.leg_states().iter().filter(|s| s.planted) {
            assert!((s.foot - slope.point()).dot(slope.normal()).abs() < 1e-4);
        }
    }
}

#[test]
fn a_leg_over_a_hole_dangles_then_lands_when_ground_returns() {
    let field = HeightField::new(Vec2::new(-2.0, -2.0), 1.0, 5, 5, vec![0.0; 25]).unwrap();
    let mut c = quadruped();
    let mut dangled = false;
    for k in 0..300 {
        let z = -1.0 + k as f32 * 0.02; // walks off the field's edge at z = 2
        let pose = Pose::new(Vec3::new(0.0, 0.8, z), Quat::IDENTITY);
        c.update(DT, pose, Vec3::Z * 1.2, Vec3::ZERO, &field)
            .unwrap();
        dangled |= c.leg_states().iter().any(|s| !s.grounded);
    }
    assert!(dangled);
    assert!(
        c.leg_states()
            .iter()
            .all(|s| !s.grounded && s.foot.is_finite())
    );
}

// ----- curves --------------------------------------------------------------------------------

#[test]
fn custom_reach_and_height_curves_are_used() {
    fn short(_: f32) -> f32 {
        0.1
    }
    fn square(t: f32) -> f32 {
        if t > 0.0 && t < 1.0 { 1.0 } else { 0.0 }
    }
    let o = GaitOptions::DEFAULT
        .with_reach(ReachCurve::Custom(short))
        .with_height_curve(HeightCurve::Custom(square));
    let mut short_steps = Controller::new(&creature_legs(2, 1.0), &o).unwrap();
    let mut default = quadruped();
    let mut peak = 0.0f32;
    for k in 0..300 {
        let pose = Pose::new(Vec3::new(0.0, 0.8, k as f32 * DT), Quat::IDENTITY);
        short_steps
            .update(DT, pose, Vec3::Z, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        default
            .update(DT, pose, Vec3::Z, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        for s in short_steps
            .leg_states()
            .iter()
            .filter(|s| s.stepping && s.progress > 0.0)
        {
            peak = peak.max(s.foot.y);
        }
    }
    let count = |c: &Controller| c.leg_states().iter().map(|s| s.steps).sum::<u32>();
    assert!(count(&short_steps) > count(&default));
    assert_relative_eq!(peak, 0.15, epsilon = 1e-5); // the square curve lifts straight to 0.15
}

// ----- reaction, intent, follow-through, blend, arms ----------------------------------------

#[test]
fn the_body_bobs_and_sways_within_its_limits() {
    let o = GaitOptions::DEFAULT;
    let mut c = quadruped();
    let mut max_bob = 0.0f32;
    let mut max_angle = 0.0f32;
    for k in 0..600 {
        let t = k as f32 * DT;
        let pose = Pose::new(Vec3::new(0.0, 0.8, t * 1.5), Quat::IDENTITY);
        c.update(DT, pose, Vec3::Z * 1.5, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        let b = c.body();
        max_bob = max_bob.max(b.bob.abs());
        max_angle = max_angle
            .max(b.yaw.abs())
            .max(b.pitch.abs())
            .max(b.roll.abs());
        assert!(b.offset.is_finite() && b.rotation.is_normalized());
    }
    assert!(max_bob > 1e-3, "the body never bobbed");
    assert!(max_bob <= o.bob_limit);
    assert!(max_angle > 1e-4 && max_angle <= o.sway_limit);
}

#[test]
fn the_bob_rises_while_feet_are_lifted_and_is_damped() {
    let mut c = quadruped();
    c.update(DT, standing(), Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
        .unwrap();
    // Teleport forward: every foot steps; the mean foot height rises, so the bob does.
    let far = Pose::new(Vec3::new(0.0, 0.8, 1.0), Quat::IDENTITY);
    let mut bobs = Vec::new();
    for _ in 0..10 {
        c.update(DT, far, Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        bobs.push(c.body().bob);
    }
    assert!(bobs[4] > bobs[0] && bobs[0] >= 0.0, "{bobs:?}");
    // Damped: the first frame moves only part of the way.
    assert!(bobs[0] < 0.5 * bobs[4], "{bobs:?}");
}

#[test]
fn hips_roll_toward_the_lifted_foot() {
    let mut c = Controller::new(&creature_legs(1, 1.0), &GaitOptions::DEFAULT).unwrap();
    let mut seen = false;
    for k in 0..240 {
        let pose = Pose::new(Vec3::new(0.0, 0.8, k as f32 * DT), Quat::IDENTITY);
        c.update(DT, pose, Vec3::Z, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        let s = c.leg_states();
        if s[0].stepping && s[0].progress > 0.3 && s[0].progress < 0.7 && s[1].planted {
            assert!(s[0].hip_roll > 0.0 && s[1].hip_roll < 0.0);
            seen = true;
        }
    }
    assert!(seen);
}

#[test]
fn the_head_looks_into_turns_smoothly_and_within_limits() {
    let o = GaitOptions::DEFAULT;
    let mut c = quadruped();
    c.update(DT, standing(), Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
        .unwrap();
    let rate = 1.5;
    let mut yaws = Vec::new();
    for k in 0..120 {
        let pose = Pose::from_yaw(Vec3::new(0.0, 0.8, 0.0), rate * DT * k as f32);
        c.update(DT, pose, Vec3::ZERO, Vec3::Y * rate, &Plane::GROUND)
            .unwrap();
        yaws.push(c.look().yaw);
    }
    assert!(
        yaws[0] > 0.0 && yaws[0] < 0.2 * rate * o.look_ahead,
        "not smoothed: {}",
        yaws[0]
    );
    let settled = *yaws.last().unwrap();
    assert_relative_eq!(
        settled,
        (rate * o.look_ahead).min(o.look_limit),
        epsilon = 1e-3
    );
    // Turning left (+Y) turns the gaze to the left (+X in body space).
    assert!((c.look().rotation * Vec3::Z).x > 0.0);
    // An explicit target: look right.
    c.set_look_target(Some(Vec3::new(-10.0, 0.8, 0.0))).unwrap();
    for _ in 0..120 {
        c.update(DT, standing(), Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
    }
    assert_relative_eq!(c.look().yaw, -o.look_limit, epsilon = 1e-3);
}

#[test]
fn a_tail_lags_behind_keeps_its_segment_lengths_and_returns_to_rest() {
    let mut c = quadruped();
    let tail = c
        .add_chain(Chain::new(Vec3::new(0.0, 0.0, -0.6), Vec3::NEG_Z, 6, 0.15).with_turn_bend(0.2))
        .unwrap();
    let mut lag = 0.0f32;
    for k in 0..240 {
        let yaw = 1.2 * DT * k as f32;
        let pose = Pose::from_yaw(Vec3::new(0.0, 0.8, 0.0), yaw);
        c.update(DT, pose, Vec3::ZERO, Vec3::Y * 1.2, &Plane::GROUND)
            .unwrap();
        let joints = c.chain(tail).unwrap();
        for w in joints.windows(2) {
            assert!((w[0].distance(w[1]) - 0.15).abs() < 1e-4);
        }
        let rest_tip = pose.transform_point(Vec3::new(0.0, 0.0, -0.6 - 0.9));
        lag = lag.max(joints[6].distance(rest_tip));
    }
    assert!(lag > 0.05, "the tail never lagged: {lag}");
    let pose = Pose::from_yaw(Vec3::new(0.0, 0.8, 0.0), 1.2 * DT * 240.0);
    for _ in 0..600 {
        c.update(DT, pose, Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
    }
    let tip = c.chain(tail).unwrap()[6];
    assert!(tip.distance(pose.transform_point(Vec3::new(0.0, 0.0, -1.5))) < 1e-3);
}

#[test]
fn a_dangling_chain_hangs_under_gravity() {
    let mut c = quadruped();
    let leg = c
        .add_chain(
            Chain::new(Vec3::ZERO, Vec3::NEG_Z, 3, 0.2)
                .with_spring(0.0, 2.0)
                .with_gravity(9.81),
        )
        .unwrap();
    for _ in 0..600 {
        c.update(DT, standing(), Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
    }
    let joints = c.chain(leg).unwrap();
    assert!(joints[3].y < joints[0].y - 0.55, "{joints:?}");
}

#[test]
fn a_legless_controller_drives_chains_and_breathes_without_nan() {
    assert!(matches!(
        Controller::chains_only(0.0, &GaitOptions::DEFAULT),
        Err(GaitError::NotPositive { what: "size", .. })
    ));
    assert!(matches!(
        Controller::chains_only(f32::NAN, &GaitOptions::DEFAULT),
        Err(GaitError::NonFinite { what: "size", .. })
    ));
    let mut c = Controller::chains_only(0.5, &GaitOptions::DEFAULT).unwrap();
    let leg = c
        .add_chain(
            Chain::new(Vec3::new(0.2, -0.1, 0.0), Vec3::new(0.0, -1.0, 1.0), 2, 0.2)
                .with_gravity(9.81),
        )
        .unwrap();
    let tail = c
        .add_chain(Chain::new(Vec3::new(0.0, 0.0, -0.5), Vec3::NEG_Z, 4, 0.1))
        .unwrap();
    let g = Plane::horizontal(-5.0);
    let dt = 1.0 / 60.0;
    let mut heights = Vec::new();
    for i in 0..600 {
        let t = i as f32 * dt;
        // Hover: a bob of 5 cm, no travel.
        let pose = Pose::from_yaw(Vec3::Y * (0.05 * (t * 6.0).sin()), 0.0);
        c.update(dt, pose, Vec3::ZERO, Vec3::ZERO, &g).unwrap();
        heights.push(c.reacted_pose().translation.y);
        for chain in [leg, tail] {
            assert!(c.chain(chain).unwrap().iter().all(|p| p.is_finite()));
        }
    }
    assert!(c.leg_states().is_empty());
    assert_eq!(c.metrics().legs_in_air, 0);
    assert!(heights.iter().all(|h| h.is_finite()));
    // Gravity pulls the dangling leg's tip below its rest direction (45° forward-down).
    let joints = c.chain(leg).unwrap();
    let d = (joints[2] - joints[0]).normalize();
    assert!(d.y < -(0.5f32.sqrt()) + 1e-3, "{d}");
    // Segment lengths are kept.
    for w in joints.windows(2) {
        assert_relative_eq!(w[0].distance(w[1]), 0.2, max_relative = 1e-3);
    }
}

#[test]
fn blending_out_returns_the_rest_pose_and_blending_in_ramps() {
    let mut c = quadruped();
    let pose = Pose::new(Vec3::new(0.0, 0.8, 0.0), Quat::IDENTITY);
    c.update(DT, pose, Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
        .unwrap();
    c.set_blend(0.0).unwrap();
    for k in 0..30 {
        let p = Pose::new(Vec3::new(0.0, 0.8, k as f32 * 0.05), Quat::IDENTITY);
        c.update(DT, p, Vec3::Z * 3.0, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        for (leg, s) in c.legs().iter().zip(c.leg_states()) {
            let rest = p.transform_point(leg.rest);
            assert!(s.joints.end.distance(rest) < 1e-5);
        }
        assert_eq!(c.body().offset, Vec3::ZERO);
    }
    c.blend_to(1.0).unwrap();
    c.update(DT, pose, Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
        .unwrap();
    assert_relative_eq!(
        c.blend(),
        DT / GaitOptions::DEFAULT.blend_time,
        epsilon = 1e-6
    );
    for _ in 0..30 {
        c.update(DT, pose, Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
    }
    assert_eq!(c.blend(), 1.0);
}

#[test]
fn arms_ignore_the_ground_and_idle() {
    let mut legs = creature_legs(1, 1.0);
    legs.push(
        Leg::new(
            Vec3::new(0.3, 0.3, 0.5),
            Vec3::new(0.4, -0.1, 0.8),
            0.35,
            0.35,
        )
        .with_kind(LimbKind::Arm),
    );
    let mut c = Controller::new(&legs, &GaitOptions::DEFAULT).unwrap();
    let mut heights = Vec::new();
    for _ in 0..240 {
        c.update(DT, standing(), Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        heights.push(c.leg_states()[2].foot.y);
    }
    let (lo, hi) = heights
        .iter()
        .fold((f32::MAX, f32::MIN), |(a, b), &h| (a.min(h), b.max(h)));
    assert!(lo > 0.6, "the hand went to the ground: {lo}");
    assert!(hi - lo > 0.005 && hi - lo < 0.1, "idle motion {lo}..{hi}");
}

#[test]
fn explicit_groups_are_respected() {
    // All four legs in one group: they may step together.
    let legs: Vec<Leg> = creature_legs(2, 1.0)
        .into_iter()
        .map(|l| l.with_group(4))
        .collect();
    let mut c = Controller::new(&legs, &GaitOptions::DEFAULT).unwrap();
    assert_eq!(c.group_count(), 1);
    assert_eq!(c.opposite(0), None);
    let mut max_air = 0;
    for k in 0..300 {
        let pose = Pose::new(Vec3::new(0.0, 0.8, k as f32 * DT * 1.5), Quat::IDENTITY);
        c.update(DT, pose, Vec3::Z * 1.5, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        max_air = max_air.max(c.metrics().legs_in_air);
    }
    assert_eq!(max_air, 4);
}

// ----- IK ------------------------------------------------------------------------------------

#[test]
fn ik_reaches_reachable_targets_within_1e_5_relative() {
    for k in 0..200 {
        let a = k as f32 * 0.731;
        let root = Vec3::new(a.sin(), 1.0 + 0.3 * a.cos(), 0.2 * a);
        let (upper, lower) = (
            0.3 + 0.2 * (a * 1.7).sin().abs(),
            0.25 + 0.3 * (a * 0.3).cos().abs(),
        );
        let dir = Vec3::new((a * 2.1).cos(), -1.0, (a * 1.3).sin()).normalize();
        let reach = (upper - lower).abs()
            + (upper + lower - (upper - lower).abs()) * (0.05 + 0.9 * (a * 0.77).sin().abs());
        let target = root + dir * reach;
        let s = solve_two_bone(root, target, upper, lower, Vec3::Z);
        assert!(s.reached);
        assert!(s.end.distance(target) <= 1e-5 * (upper + lower), "{k}");
        assert_relative_eq!(s.middle.distance(root), upper, max_relative = 1e-5);
        assert_relative_eq!(s.end.distance(s.middle), lower, max_relative = 1e-5);
    }
}

#[test]
fn ik_extends_fully_toward_unreachable_targets_and_bends_toward_the_pole() {
    let root = Vec3::new(0.0, 1.0, 0.0);
    let target = Vec3::new(3.0, -2.0, 1.0);
    let s = solve_two_bone(root, target, 0.5, 0.6, Vec3::Y);
    assert!(!s.reached);
    let dir = (target - root).normalize();
    assert!(s.end.distance(root + dir * 1.1) < 1e-5);
    // Bending toward the pole: the knee lies on the pole's side of the root-target line.
    for pole in [Vec3::X, Vec3::NEG_X, Vec3::Z, Vec3::NEG_Z] {
        let s = solve_two_bone(root, Vec3::new(0.0, 0.2, 0.0), 0.5, 0.5, pole);
        let off = s.middle - root;
        let across = off - Vec3::NEG_Y * off.dot(Vec3::NEG_Y);
        assert!(across.dot(pole) > 0.2, "{pole}");
    }
}

#[test]
fn leg_joints_are_solved_from_hip_to_foot() {
    let mut c = quadruped();
    for k in 0..120 {
        let pose = Pose::new(Vec3::new(0.0, 0.8, k as f32 * DT), Quat::IDENTITY);
        c.update(DT, pose, Vec3::Z, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
    }
    let reacted = c.reacted_pose();
    for (leg, s) in c.legs().iter().zip(c.leg_states()) {
        assert!(s.joints.root.distance(reacted.transform_point(leg.hip)) < 1e-5);
        assert!(s.joints.reached);
        assert!(s.joints.end.distance(s.foot) < 1e-4);
        // The knee points forward (pole +Z).
        assert!(s.joints.middle.z > (s.joints.root.z + s.joints.end.z) * 0.5);
    }
}

/// Metrics are measured when asked, from the state the last update left: asking after every
/// update or only once at the end gives the same figures, and asking twice changes nothing.
#[test]
fn metrics_do_not_depend_on_when_they_are_asked() {
    let g = Plane::horizontal(0.0);
    let (mut every, mut once) = (quadruped(), quadruped());
    every.reset(standing(), &g).unwrap();
    once.reset(standing(), &g).unwrap();
    let dt = 1.0 / 60.0;
    let mut worst_skate = 0.0f32;
    for i in 0..240 {
        let pose = Pose::from_yaw(Vec3::new(0.0, 0.5, 0.8 * i as f32 * dt), 0.0);
        let v = Vec3::new(0.0, 0.0, 0.8);
        every.update(dt, pose, v, Vec3::ZERO, &g).unwrap();
        once.update(dt, pose, v, Vec3::ZERO, &g).unwrap();
        let m = every.metrics();
        assert_eq!(m, every.metrics());
        worst_skate = worst_skate.max(m.max_skate);
    }
    assert_eq!(every.metrics(), once.metrics());
    assert!(worst_skate <= 1e-4);
    assert!(once.metrics().stability_margin.is_some());
}

// ----- regressions of issue 17 (fuzzing) ------------------------------------------------------

/// Finding 5: a finite quaternion whose squared length overflows gave NaN in the reacted pose
/// and the knees (after a first update) or a misleading zero-vector error (on the first).
#[test]
fn regression_a_huge_finite_quaternion_is_normalised_not_nan() {
    let g = Plane::horizontal(0.0);
    let huge = Quat::from_xyzw(-3.226_371_5e19, -1.0, -1.0, -1.0);
    for first in [true, false] {
        let mut c = quadruped();
        if !first {
            c.update(DT, standing(), Vec3::ZERO, Vec3::ZERO, &g)
                .unwrap();
        }
        c.update(
            DT,
            Pose::new(Vec3::new(0.0, 0.8, 0.0), huge),
            Vec3::ZERO,
            Vec3::ZERO,
            &g,
        )
        .unwrap();
        let pose = c.reacted_pose();
        assert!(
            pose.rotation.is_finite() && pose.rotation.is_normalized(),
            "{pose:?}"
        );
        for state in c.leg_states() {
            assert!(
                state.joints.middle.is_finite() && state.foot.is_finite(),
                "{state:?}"
            );
        }
    }
}

/// Finding 6: legs and chains had no size bound while poses are capped at `MAX_COORDINATE`:
/// `f32::MAX` lengths and far hips gave NaN joints and an infinite stability margin.
#[test]
fn regression_legs_and_chains_beyond_max_coordinate_are_errors() {
    let hip = Vec3::new(0.2, 0.0, 0.3);
    let rest = Vec3::new(0.3, -0.8, 0.3);
    let out_of_range =
        |r: Result<Controller, GaitError>| matches!(r, Err(GaitError::OutOfRange { .. }));
    let new = |leg: Leg| Controller::new(&[leg], &GaitOptions::DEFAULT);
    assert!(out_of_range(new(Leg::new(hip, rest, f32::MAX, 1.66))));
    assert!(out_of_range(new(Leg::new(
        Vec3::new(0.0, 0.0, 1e30),
        rest,
        0.5,
        0.5
    ))));
    assert!(out_of_range(new(Leg::new(
        hip,
        Vec3::splat(-1e30),
        0.5,
        0.5
    ))));
    assert!(new(Leg::new(hip, rest, 0.5, 0.5)).is_ok());
    let mut c = quadruped();
    assert!(matches!(
        c.add_chain(Chain::new(Vec3::ZERO, Vec3::NEG_Z, 3, f32::MAX)),
        Err(GaitError::OutOfRange { .. })
    ));
    assert!(matches!(
        c.add_chain(Chain::new(Vec3::splat(1e30), Vec3::NEG_Z, 3, 0.2)),
        Err(GaitError::OutOfRange { .. })
    ));
    assert!(
        c.add_chain(Chain::new(Vec3::ZERO, Vec3::NEG_Z, 3, 0.2))
            .is_ok()
    );
}

/// Finding 6, ground hits: a ground whose hits lie 1e30 away (as a buggy physics ray cast
/// might report) gave `stability_margin: Some(-inf)`, infinite skate and overstretch, and
/// joints far out of range. Hits farther than `MAX_COORDINATE` from the ray's origin (on any
/// axis) are now ignored like non-finite ones: no hit, the leg dangles.
#[test]
fn regression_ground_hits_beyond_max_coordinate_are_no_hits() {
    for far in [1e30f32, -1e30, 2e6, f32::MAX] {
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            let bogus = FnGround(move |origin: Vec3, _direction: Vec3, _max: f32| {
                Some(RayHit {
                    point: origin + axis * far,
                    normal: Vec3::Y,
                    distance: 0.5,
                })
            });
            let mut c = quadruped();
            for _ in 0..3 {
                c.update(DT, standing(), Vec3::new(0.5, 0.0, 0.0), Vec3::ZERO, &bogus)
                    .unwrap();
            }
            let m = c.metrics();
            let at = (far, axis);
            assert!(m.max_skate.is_finite(), "{at:?}: {m:?}");
            assert!(m.max_overstretch.is_finite(), "{at:?}: {m:?}");
            assert!(
                m.stability_margin.is_none_or(f32::is_finite),
                "{at:?}: {m:?}"
            );
            for state in c.leg_states() {
                assert!(!state.grounded, "{at:?}: {state:?}");
                assert!(state.joints.middle.is_finite(), "{at:?}: {state:?}");
                assert!(state.foot.abs().max_element() <= 10.0, "{at:?}: {state:?}");
            }
        }
    }
    // Hits within MAX_COORDINATE of the ray's origin are kept.
    let low = FnGround(|origin: Vec3, _direction: Vec3, _max: f32| {
        Some(RayHit {
            point: Vec3::new(origin.x, 0.0, origin.z),
            normal: Vec3::Y,
            distance: origin.y,
        })
    });
    let mut c = quadruped();
    c.update(DT, standing(), Vec3::ZERO, Vec3::ZERO, &low)
        .unwrap();
    assert!(c.leg_states().iter().all(|s| s.grounded));
}
