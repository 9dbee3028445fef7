//! Gaits by speed through the public API: walk, trot and run chosen by the Froude number at
//! the documented thresholds, for every leg count and size, changed without a joint jumping.

#![allow(clippy::unwrap_used)]

mod support;

use creature_gait::glam::{Quat, Vec3};
use creature_gait::{Controller, Gait, GaitOptions, GaitSpeeds, Plane, Pose};
use support::creature_legs;

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;

/// One frame of a drive: the speed, the gait, and which legs step in turn (not escaping).
struct Sample {
    speed: f32,
    gait: Gait,
    /// The most any joint turned since the frame before, radians.
    turn: f32,
    stepping: Vec<bool>,
    all_up: bool,
    /// The body's height as shown (the reaction's bob included).
    height: f32,
}

/// What a drive saw, worst over its frames.
#[derive(Default)]
struct Drive {
    samples: Vec<Sample>,
    max_joint_turn: f32,
    max_skate: f32,
    max_overstretch: f32,
    escapes: u32,
    steps: u32,
}

impl Drive {
    /// The gaits in the order they came, each with the speed it came at.
    fn changes(&self) -> Vec<(f32, Gait)> {
        let mut changes: Vec<(f32, Gait)> = Vec::new();
        for s in &self.samples {
            if changes.last().is_none_or(|&(_, g)| g != s.gait) {
                changes.push((s.speed, s.gait));
            }
        }
        changes
    }

    /// The most a joint turned between frames within `frames` frames of a change of gait,
    /// and elsewhere.
    fn turns_near_changes_and_elsewhere(&self, frames: usize) -> (f32, f32) {
        let mut near = vec![false; self.samples.len()];
        for k in 1..self.samples.len() {
            if self.samples[k].gait != self.samples[k - 1].gait {
                let end = (k + frames).min(near.len());
                near[k.saturating_sub(frames)..end].fill(true);
            }
        }
        let (mut at, mut away) = (0.0f32, 0.0f32);
        for (s, near) in self.samples.iter().zip(near) {
            if near {
                at = at.max(s.turn);
            } else {
                away = away.max(s.turn);
            }
        }
        (at, away)
    }

    /// Asserts each change after the first gait came at its threshold in `thresholds` (the
    /// first `rising` speeding up, the rest slowing down), or up to 0.15 of a Froude number
    /// later, on legs `length` long.
    fn changes_at(&self, thresholds: &[f32], rising: usize, length: f32, label: &str) {
        let changes = self.changes();
        for (k, (&(speed, gait), &threshold)) in changes[1..].iter().zip(thresholds).enumerate() {
            let f = speed * speed / (G * length);
            let late = if k < rising {
                f - threshold
            } else {
                threshold - f
            };
            assert!(
                (0.0..=0.15).contains(&late),
                "{label}: {gait:?} at Froude {f}, threshold {threshold}"
            );
        }
    }

    /// Asserts no joint turned more than 45° a frame, nor 1.5 times as fast within half a
    /// second of a change as elsewhere; no skate or overstretch on legs `length` long; at most
    /// a tenth of the steps out of turn.
    fn smooth(&self, length: f32, label: &str) {
        let turn = self.max_joint_turn.to_degrees();
        assert!(turn <= 45.0, "{label}: a joint turned {turn}° in a frame");
        let (near, away) = self.turns_near_changes_and_elsewhere(30);
        assert!(
            near <= 1.5 * away,
            "{label}: {near} rad a frame near a change, {away} elsewhere"
        );
        assert!(
            self.max_skate <= 1e-4 * length,
            "{label}: skate {}",
            self.max_skate
        );
        assert!(
            self.max_overstretch <= 1e-5 * length,
            "{label}: overstretch"
        );
        assert!(
            self.escapes * 10 <= self.steps,
            "{label}: {} of {} steps escaped",
            self.escapes,
            self.steps
        );
    }

    /// The samples while in `gait`, after its first second (a steady state).
    fn steady(&self, gait: Gait) -> impl Iterator<Item = &Sample> {
        self.samples
            .iter()
            .filter(move |s| s.gait == gait)
            .skip((1.0 / DT) as usize)
    }
}

fn angle(a: Quat, b: Quat) -> f32 {
    2.0 * a.dot(b).abs().min(1.0).acos()
}

/// Drives `pairs` pairs of legs `length` long, with gaits by speed, along +Z at `speed(t)` for
/// `seconds` on flat ground, at 60 frames a second for 1 m legs and as many per `√(l / g)`
/// for others (a leg `l` long swings in a time proportional to that at the same Froude
/// number: at 60 frames a second, a mouse's trot turns its joints further between frames
/// than a horse's, whatever its gait).
fn drive(pairs: usize, length: f32, seconds: f32, speed: impl Fn(f32) -> f32) -> Drive {
    let options = GaitOptions::DEFAULT.with_gaits(GaitSpeeds::DEFAULT);
    drive_with(&options, pairs, length, seconds, speed)
}

/// [`drive`] with `options`.
fn drive_with(
    options: &GaitOptions,
    pairs: usize,
    length: f32,
    seconds: f32,
    speed: impl Fn(f32) -> f32,
) -> Drive {
    let dt = DT * length.sqrt();
    let legs = creature_legs(pairs, length);
    let mut c = Controller::new(&legs, options).unwrap();
    let mut d = Drive::default();
    let mut z = 0.0f32;
    let mut last: Option<Vec<(Quat, Quat)>> = None;
    for k in 0..(seconds / dt) as usize {
        let v = speed(k as f32 * dt);
        z += v * dt;
        let pose = Pose::from_yaw(Vec3::new(0.0, 0.8 * length, z), 0.0);
        c.update(dt, pose, Vec3::Z * v, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        let m = c.metrics();
        d.max_skate = d.max_skate.max(m.max_skate);
        d.max_overstretch = d.max_overstretch.max(m.max_overstretch);
        let states = c.leg_states();
        let joints: Vec<(Quat, Quat)> = states
            .iter()
            .map(|s| (s.joints.upper_rotation, s.joints.lower_rotation))
            .collect();
        let mut turn = 0.0f32;
        if let Some(last) = &last {
            for (a, b) in last.iter().zip(&joints) {
                turn = turn.max(angle(a.0, b.0)).max(angle(a.1, b.1));
            }
        }
        d.max_joint_turn = d.max_joint_turn.max(turn);
        last = Some(joints);
        d.samples.push(Sample {
            turn,
            speed: v,
            gait: c.gait(),
            stepping: states
                .iter()
                .map(|s| s.stepping && !s.is_escaping())
                .collect(),
            all_up: states.iter().all(|s| !s.planted),
            height: c.reacted_pose().translation.y,
        });
    }
    d.escapes = c.leg_states().iter().map(|s| s.escapes).sum();
    d.steps = c.leg_states().iter().map(|s| s.steps).sum();
    d
}

/// The speed of a Froude number on legs `length` long.
fn speed_at(froude: f32, length: f32) -> f32 {
    (froude * G * length).sqrt()
}

#[test]
fn speeding_up_and_slowing_down_walks_trots_runs_and_back_at_the_documented_froude_numbers() {
    let s = GaitSpeeds::DEFAULT;
    for length in [0.3f32, 1.0, 3.0] {
        for pairs in [1, 2, 3, 4] {
            // 0.1 to 3.5 and back, over 24 s.
            let (low, top) = (speed_at(0.1, length), speed_at(3.5, length));
            let d = drive(pairs, length, 24.0, |t| {
                low + (top - low) * (1.0 - (t / 12.0 - 1.0).abs())
            });
            let label = format!("{pairs} pairs of {length} m legs");
            let changes = d.changes();
            let gaits: Vec<Gait> = changes.iter().map(|c| c.1).collect();
            use Gait::{Run, Trot, Walk};
            assert_eq!(gaits, [Walk, Trot, Run, Trot, Walk], "{label}");
            // Each change at its threshold, or up to a stride later (it waits for a handover
            // between groups): within 0.15 of a Froude number on this ramp.
            let expected = [s.trot, s.run, s.run * s.hysteresis, s.trot * s.hysteresis];
            d.changes_at(&expected, 2, length, &label);
            // No joint jumps: the steps under way finish as they began. Within half a second
            // of a change, no joint turns much faster than anywhere else on the ramp (at
            // speeds up to a Froude number of 3.5): a foot carried across its step in a frame
            // would be several times as fast. The worst measured is 1.38 times (four 0.3 m
            // legs, the trot's first strides after a bound: a foot that had just landed waits
            // for its diagonal group's next turn and then steps the further). Out-of-turn
            // steps stay rare.
            d.smooth(length, &label);
        }
    }
}

#[test]
fn a_run_has_a_flight_phase_and_walks_and_trots_have_none() {
    for pairs in [1, 2] {
        for (froude, gait) in [(0.3, Gait::Walk), (1.0, Gait::Trot), (3.0, Gait::Run)] {
            let v = speed_at(froude, 1.0);
            let d = drive(pairs, 1.0, 8.0, |_| v);
            let steady: Vec<&Sample> = d.steady(gait).collect();
            assert!(steady.len() > 300, "{pairs} pairs stayed in {gait:?}");
            let flying = steady.iter().filter(|s| s.all_up).count();
            if gait == Gait::Run {
                // At least a twentieth of the time with every foot off the ground.
                assert!(
                    flying * 20 >= steady.len(),
                    "{pairs} pairs: {flying} frames of flight"
                );
            } else {
                assert_eq!(flying, 0, "{pairs} pairs flew in a {gait:?}");
            }
        }
    }
}

#[test]
fn four_legs_walk_one_foot_at_a_time_trot_in_diagonals_and_bound_in_pairs() {
    // Legs: 0 hind left, 1 hind right, 2 fore left, 3 fore right.
    let run = |froude: f32, gait: Gait| {
        let v = speed_at(froude, 1.0);
        let d = drive(2, 1.0, 8.0, |_| v);
        let steady: Vec<Vec<bool>> = d.steady(gait).map(|s| s.stepping.clone()).collect();
        assert!(steady.len() > 300, "stayed in {gait:?}");
        steady
    };
    let together =
        |frames: &[Vec<bool>], a: usize, b: usize| frames.iter().filter(|s| s[a] && s[b]).count();
    let walk = run(0.3, Gait::Walk);
    // (Steps out of turn, rare, are left out: `stepping` counts steps in turn.)
    assert!(walk.iter().all(|s| s.iter().filter(|&&x| x).count() <= 1));
    let trot = run(1.0, Gait::Trot);
    for (a, b) in [(0, 1), (2, 3), (0, 2), (1, 3)] {
        assert_eq!(
            together(&trot, a, b),
            0,
            "legs {a} and {b} stepped together in a trot"
        );
    }
    assert!(together(&trot, 0, 3) > 0 && together(&trot, 1, 2) > 0);
    let bound = run(3.0, Gait::Run);
    // The pairs land and lift together: most of a leg's swing, its partner swings too.
    for (a, b) in [(0, 1), (2, 3)] {
        let alone = bound.iter().filter(|s| s[a] != s[b]).count();
        assert!(
            alone * 4 <= together(&bound, a, b),
            "legs {a} and {b} bound apart"
        );
    }
}

#[test]
fn a_reset_walks_again_in_the_groups_of_a_controller_just_built() {
    let legs = creature_legs(2, 1.0);
    let options = GaitOptions::DEFAULT.with_gaits(GaitSpeeds::DEFAULT);
    let fresh = Controller::new(&legs, &options).unwrap();
    let mut c = fresh.clone();
    let v = speed_at(3.0, 1.0);
    for k in 0..240 {
        let pose = Pose::from_yaw(Vec3::new(0.0, 0.8, v * DT * k as f32), 0.0);
        c.update(DT, pose, Vec3::Z * v, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
    }
    assert_eq!(c.gait(), Gait::Run);
    c.reset(
        Pose::from_yaw(Vec3::new(0.0, 0.8, 0.0), 0.0),
        &Plane::GROUND,
    )
    .unwrap();
    assert_eq!(c.gait(), Gait::Walk);
    assert_eq!(c.groups(), fresh.groups());
    assert_eq!(c.group_count(), fresh.group_count());
    assert_eq!(c.active_group(), 0);
}

#[test]
fn below_the_run_the_pattern_of_one_gait_is_kept_bit_for_bit_and_a_reset_returns_to_it() {
    // Up to three pairs, the trot's groups are the ones a controller without gaits by speed
    // walks in: trotting from a Froude number of 0, the feet are the same, bit for bit, until
    // it runs. From four pairs, the walk's (a three-group wave): walking up to the run.
    for pairs in [1, 2, 3, 4, 5] {
        let legs = creature_legs(pairs, 1.0);
        let (from, gait) = if pairs <= 3 {
            (0.0, Gait::Trot)
        } else {
            (2.5, Gait::Walk)
        };
        let speeds = GaitSpeeds::DEFAULT.with_thresholds(from, 2.5);
        let mut by_speed =
            Controller::new(&legs, &GaitOptions::DEFAULT.with_gaits(speeds)).unwrap();
        let mut one = Controller::new(&legs, &GaitOptions::DEFAULT).unwrap();
        assert_eq!(by_speed.gait(), gait);
        let mut z = 0.0;
        for k in 0..600 {
            let v = speed_at(2.4, 1.0) * k as f32 / 600.0;
            z += v * DT;
            let pose = Pose::from_yaw(Vec3::new(0.0, 0.8, z), 0.0);
            for c in [&mut by_speed, &mut one] {
                c.update(DT, pose, Vec3::Z * v, Vec3::ZERO, &Plane::GROUND)
                    .unwrap();
            }
            assert_eq!(
                by_speed.leg_states(),
                one.leg_states(),
                "{pairs} pairs, frame {k}"
            );
            assert_eq!(by_speed.gait(), gait);
        }
        // A reset comes back to that gait, from a run.
        let v = speed_at(3.0, 1.0);
        for k in 0..240 {
            let pose = Pose::from_yaw(Vec3::new(0.0, 0.8, z + v * DT * k as f32), 0.0);
            by_speed
                .update(DT, pose, Vec3::Z * v, Vec3::ZERO, &Plane::GROUND)
                .unwrap();
        }
        assert_eq!(by_speed.gait(), Gait::Run, "{pairs} pairs");
        by_speed
            .reset(Pose::from_yaw(Vec3::new(0.0, 0.8, z), 0.0), &Plane::GROUND)
            .unwrap();
        assert_eq!(by_speed.gait(), gait, "{pairs} pairs");
        assert_eq!(by_speed.groups(), one.groups(), "{pairs} pairs");
    }
}

#[test]
fn without_gaits_by_speed_the_controller_walks_in_one_pattern_at_every_speed() {
    let legs = creature_legs(2, 1.0);
    let mut c = Controller::new(&legs, &GaitOptions::DEFAULT).unwrap();
    let groups = c.groups().to_vec();
    let v = speed_at(3.0, 1.0);
    for k in 0..240 {
        let pose = Pose::from_yaw(Vec3::new(0.0, 0.8, v * DT * k as f32), 0.0);
        c.update(DT, pose, Vec3::Z * v, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        assert_eq!(c.gait(), Gait::Walk);
        assert_eq!(c.groups(), groups);
    }
}

#[test]
fn bad_gait_speeds_are_rejected_with_the_field_named() {
    let legs = creature_legs(2, 1.0);
    let bad = GaitOptions::DEFAULT.with_gaits(GaitSpeeds::DEFAULT.with_thresholds(1.0, 0.5));
    let error = Controller::new(&legs, &bad).unwrap_err().to_string();
    assert!(error.contains("run Froude number"), "{error}");
    let bad = GaitOptions::DEFAULT.with_gaits(GaitSpeeds::DEFAULT.with_gravity(f32::NAN));
    assert!(Controller::new(&legs, &bad).is_err());
}

/// The frames of `samples` in which any leg lifted off in turn, and those in which every leg
/// did (each on the ground, or out of turn, the frame before).
fn lift_offs<'a>(samples: impl Iterator<Item = &'a Sample>) -> (usize, usize) {
    let (mut any, mut all) = (0, 0);
    let mut last: Option<&Vec<bool>> = None;
    for s in samples {
        if let Some(last) = last {
            let lifted: Vec<bool> = last
                .iter()
                .zip(&s.stepping)
                .map(|(a, b)| !a && *b)
                .collect();
            if lifted.iter().any(|&x| x) {
                any += 1;
                all += usize::from(lifted.iter().all(|&l| l));
            }
        }
        last = Some(&s.stepping);
    }
    (any, all)
}

#[test]
fn a_hopper_walks_then_hops_with_its_feet_together_and_its_body_thrown_up() {
    let s = GaitSpeeds::DEFAULT;
    let options = GaitOptions::DEFAULT
        .with_gaits(GaitSpeeds::DEFAULT)
        .with_hop(true);
    for (pairs, length) in [(1, 0.3f32), (1, 1.0), (1, 3.0), (2, 1.0)] {
        // 0.1 to 3.5 and back, over 24 s.
        let (low, top) = (speed_at(0.1, length), speed_at(3.5, length));
        let d = drive_with(&options, pairs, length, 24.0, |t| {
            low + (top - low) * (1.0 - (t / 12.0 - 1.0).abs())
        });
        let label = format!("{pairs} pairs of {length} m legs");
        let changes = d.changes();
        let gaits: Vec<Gait> = changes.iter().map(|c| c.1).collect();
        assert_eq!(gaits, [Gait::Walk, Gait::Hop, Gait::Walk], "{label}");
        // Hopping from the trot's threshold, walking again below its hysteresis.
        d.changes_at(&[s.trot, s.trot * s.hysteresis], 1, length, &label);
        d.smooth(length, &label);
        // Every foot lifts off together: in nine of ten lift-offs (the rest, a foot that
        // escaped out of turn catching up).
        let hop: Vec<&Sample> = d.samples.iter().filter(|s| s.gait == Gait::Hop).collect();
        let (lifts, together) = lift_offs(hop.iter().copied());
        assert!(
            lifts > 20 && together * 10 >= lifts * 9,
            "{label}: {together} of {lifts} lift-offs together"
        );
        // A flight in every hop: a quarter of the time at least with every foot up (a
        // walk never has one, as a test above shows), the body thrown up 7.5% of its leg at
        // least (the feet's lift alone raises it 5.5-6.5%; with its flight's arc, 8.6-13.4%).
        let up = hop.iter().filter(|s| s.all_up).count();
        assert!(
            up * 4 >= hop.len(),
            "{label}: {up} of {} frames in flight",
            hop.len()
        );
        let rise = hop.iter().map(|s| s.height).fold(f32::MIN, f32::max) - 0.8 * length;
        assert!(rise >= 0.075 * length, "{label}: the body rose {rise}");
    }
}

#[test]
fn without_gaits_by_speed_a_hopper_hops_at_every_speed() {
    let options = GaitOptions::DEFAULT.with_hop(true);
    let legs = creature_legs(1, 1.0);
    assert_eq!(Controller::new(&legs, &options).unwrap().gait(), Gait::Hop);
    for froude in [0.1, 0.3, 2.0] {
        let v = speed_at(froude, 1.0);
        let d = drive_with(&options, 1, 1.0, 6.0, |_| v);
        assert!(d.samples.iter().all(|s| s.gait == Gait::Hop));
        let (lifts, together) = lift_offs(d.samples.iter());
        assert!(
            lifts > 5 && together == lifts,
            "Froude {froude}: {together} of {lifts}"
        );
    }
}
