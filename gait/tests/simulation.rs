//! Deterministic walking simulations through the public API: the plausibility figures.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use core::f32::consts::TAU;

use creature_gait::glam::{Quat, Vec3};
use creature_gait::{Controller, GaitOptions, Plane, Pose};
use support::{Figures, Frame, creature_legs, options, random_terrain, run, straight};

const DT: f32 = 1.0 / 60.0;

fn walk(pairs: usize, speed: f32, terrain: bool) -> Figures {
    let legs = creature_legs(pairs, 1.0);
    let mut controller = Controller::new(&legs, &options()).unwrap();
    if terrain {
        let field = random_terrain(7, 0.3);
        run(
            &mut controller,
            &field,
            |x, z| field.height(x, z).unwrap(),
            0.8,
            DT,
            straight(speed, 20.0, DT),
        )
        .unwrap()
    } else {
        run(
            &mut controller,
            &Plane::GROUND,
            |_, _| 0.0,
            0.8,
            DT,
            straight(speed, 20.0, DT),
        )
        .unwrap()
    }
}

fn check_walk(pairs: usize, speed: f32, terrain: bool) {
    let f = walk(pairs, speed, terrain);
    let label = format!("{pairs} pairs at {speed} m/s, terrain {terrain}: {f:?}");
    assert!(f.max_skate <= 1e-4, "skate: {label}");
    assert!(f.max_ground_gap <= 1e-3, "ground gap: {label}");
    // A rigid 4.5 m body over ±0.3 m bumps cannot keep every foot within reach: the 12-legged
    // creature on terrain gets a looser bound; elsewhere a foot waits for its group's turn at
    // most to the escape distance.
    let tolerance = if pairs >= 6 && terrain { 0.2 } else { 0.1 };
    assert!(f.max_overstretch <= tolerance, "overstretch: {label}");
    assert_eq!(f.opposite_overlaps, 0, "partners stepped together: {label}");
    // 20 m with a stride of well under 2 m: every leg stepped many times.
    assert!(f.steps.iter().all(|&s| s >= 10), "steps: {label}");
    assert!(f.max_in_air < 2 * pairs, "all feet in the air: {label}");
}

#[test]
fn walking_20_m_on_a_plane_at_three_speeds_with_2_4_6_and_12_legs() {
    for pairs in [1, 2, 3, 6] {
        for speed in [0.3, 1.0, 3.0] {
            check_walk(pairs, speed, false);
        }
    }
}

#[test]
fn walking_20_m_on_a_random_height_field_at_three_speeds_with_2_4_6_and_12_legs() {
    for pairs in [1, 2, 3, 6] {
        for speed in [0.3, 1.0, 3.0] {
            check_walk(pairs, speed, true);
        }
    }
}

#[test]
fn slow_walks_need_no_escape_steps() {
    for pairs in [1, 2, 3, 6] {
        for speed in [0.3, 1.0] {
            assert_eq!(
                walk(pairs, speed, false).escapes,
                0,
                "{pairs} pairs at {speed}"
            );
        }
    }
}

#[test]
fn a_hexapod_tripod_keeps_its_centre_of_mass_over_the_support_polygon() {
    for speed in [0.3, 1.0] {
        let f = walk(3, speed, false);
        assert!(f.min_margin > 0.0, "{speed}: {f:?}");
    }
}

#[test]
fn turning_in_place_360_degrees_steps_every_leg_without_skating() {
    for pairs in [1, 2, 3] {
        let legs = creature_legs(pairs, 1.0);
        let mut controller = Controller::new(&legs, &options()).unwrap();
        let rate = 1.0;
        let frames = (TAU / rate / DT) as usize;
        let turn = (0..=frames).map(|k| Frame {
            position: Vec3::ZERO,
            yaw: rate * DT * k as f32,
            velocity: Vec3::ZERO,
            yaw_rate: rate,
        });
        let f = run(&mut controller, &Plane::GROUND, |_, _| 0.0, 0.8, DT, turn).unwrap();
        assert!(f.max_skate <= 1e-4, "{f:?}");
        assert!(f.max_overstretch <= 0.1, "{f:?}");
        assert!(f.steps.iter().all(|&s| s >= 3), "{pairs} pairs: {f:?}");
        assert_eq!(f.opposite_overlaps, 0, "{f:?}");
    }
}

#[test]
fn start_stop_start_plants_every_foot_within_a_second_and_keeps_them_still() {
    let legs = creature_legs(2, 1.0);
    let mut controller = Controller::new(&legs, &options()).unwrap();
    let speed = 1.2;
    let mut z = 0.0f32;
    let mut planted_after = None;
    let mut steps_at_restart = 0;
    for k in 0..480 {
        let t = k as f32 * DT;
        let moving = !(2.0..4.0).contains(&t);
        let v = if moving { speed } else { 0.0 };
        z += v * DT;
        let pose = Pose::new(Vec3::new(0.0, 0.8, z), Quat::IDENTITY);
        controller
            .update(DT, pose, Vec3::new(0.0, 0.0, v), Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        assert!(controller.metrics().max_skate <= 1e-4);
        if !moving {
            if controller.all_planted() {
                planted_after.get_or_insert(t - 2.0);
            }
            if t > 3.0 {
                // Neutral pose reached: every foot down and still until the creature moves.
                assert!(controller.all_planted(), "a foot moved at rest, t = {t}");
                assert_eq!(controller.metrics().steps_started, 0);
            }
        }
        if k == 240 {
            steps_at_restart = controller.leg_states().iter().map(|s| s.steps).sum::<u32>();
        }
    }
    let steps_at_end = controller.leg_states().iter().map(|s| s.steps).sum::<u32>();
    assert!(
        steps_at_end >= steps_at_restart + 8,
        "{steps_at_restart} -> {steps_at_end}"
    );
    let after = planted_after.unwrap();
    assert!(
        after <= 1.0,
        "feet hung in the air for {after} s after stopping"
    );
}

#[test]
fn larger_legs_step_less_often_than_smaller_ones_at_the_same_speed() {
    let count = |length: f32| {
        let legs = creature_legs(2, length);
        let mut controller = Controller::new(&legs, &options()).unwrap();
        let f = run(
            &mut controller,
            &Plane::GROUND,
            |_, _| 0.0,
            0.8 * length,
            DT,
            straight(1.0, 20.0, DT),
        )
        .unwrap();
        f.steps.iter().sum::<u32>()
    };
    let (small, large) = (count(0.6), count(1.5));
    assert!(
        large < small,
        "large legs {large} steps, small legs {small}"
    );
}

#[test]
fn partners_never_step_together_outside_escapes_with_derived_groups() {
    // Checked per frame in `run`; here also with a running gait (speed multiplier 2).
    let legs = creature_legs(2, 1.0);
    let o = GaitOptions::DEFAULT.with_speed_multiplier(2.0);
    let mut controller = Controller::new(&legs, &o).unwrap();
    let f = run(
        &mut controller,
        &Plane::GROUND,
        |_, _| 0.0,
        0.8,
        DT,
        straight(2.5, 20.0, DT),
    )
    .unwrap();
    assert_eq!(f.opposite_overlaps, 0, "{f:?}");
    assert!(f.max_skate <= 1e-4);
}

#[test]
fn a_running_gait_takes_fewer_longer_steps() {
    let steps = |multiplier: f32| {
        let legs = creature_legs(2, 1.0);
        let o = GaitOptions::DEFAULT.with_speed_multiplier(multiplier);
        let mut controller = Controller::new(&legs, &o).unwrap();
        let f = run(
            &mut controller,
            &Plane::GROUND,
            |_, _| 0.0,
            0.8,
            DT,
            straight(2.0, 20.0, DT),
        )
        .unwrap();
        f.steps.iter().sum::<u32>()
    };
    assert!(steps(1.8) < steps(1.0));
}

#[test]
fn the_same_inputs_give_the_same_state_bit_for_bit_with_variable_dt() {
    let simulate = || {
        let legs = creature_legs(3, 1.0);
        let field = random_terrain(3, 0.2);
        let mut controller = Controller::new(&legs, &options()).unwrap();
        controller
            .add_chain(creature_gait::Chain::new(
                Vec3::new(0.0, 0.0, -1.4),
                Vec3::NEG_Z,
                5,
                0.2,
            ))
            .unwrap();
        let mut position = Vec3::new(0.0, 0.0, -5.0);
        let mut yaw = 0.0f32;
        for k in 0..600 {
            let dt = 1.0 / 50.0 + 0.01 * ((k * 7 % 11) as f32 / 11.0);
            let rate = 0.6 * ((k / 100) as f32 - 2.5).signum();
            let velocity = Quat::from_rotation_y(yaw) * Vec3::new(0.0, 0.0, 1.1);
            position += velocity * dt;
            yaw += rate * dt;
            let y = field.height(position.x, position.z).unwrap() + 0.8;
            let pose = Pose::from_yaw(Vec3::new(position.x, y, position.z), yaw);
            controller
                .update(dt, pose, velocity, Vec3::new(0.0, rate, 0.0), &field)
                .unwrap();
        }
        controller
    };
    let (a, b) = (simulate(), simulate());
    assert_eq!(a, b);
    assert!(a.leg_states().iter().all(|s| s.steps > 3));
}

#[test]
fn a_teleport_makes_every_leg_escape_and_land_on_the_new_ground() {
    let legs = creature_legs(2, 1.0);
    let mut controller = Controller::new(&legs, &options()).unwrap();
    let ground = Plane::GROUND;
    controller
        .update(
            DT,
            Pose::new(Vec3::new(0.0, 0.8, 0.0), Quat::IDENTITY),
            Vec3::ZERO,
            Vec3::ZERO,
            &ground,
        )
        .unwrap();
    let far = Pose::new(Vec3::new(0.0, 0.8, 3.0), Quat::IDENTITY);
    controller
        .update(DT, far, Vec3::ZERO, Vec3::ZERO, &ground)
        .unwrap();
    assert_eq!(controller.metrics().steps_started, 4);
    assert!(controller.metrics().escapes_started >= 2);
    for _ in 0..60 {
        controller
            .update(DT, far, Vec3::ZERO, Vec3::ZERO, &ground)
            .unwrap();
    }
    assert!(controller.all_planted());
    for s in controller.leg_states() {
        assert!(s.foot.distance(s.anchor) <= 0.1 + 1e-5, "{s:?}");
    }
}

/// Steps that start within `frames` updates of the same leg's landing, for a creature with
/// `pairs` pairs running at `speed` (speed multiplier `multiplier`) while turning at `rate`.
fn quick_resteps(
    pairs: usize,
    multiplier: f32,
    speed: f32,
    rate: f32,
    frames: usize,
) -> Vec<String> {
    let legs = creature_legs(pairs, 1.0);
    let o = GaitOptions::DEFAULT.with_speed_multiplier(multiplier);
    let mut controller = Controller::new(&legs, &o).unwrap();
    let mut landed_at: Vec<Option<usize>> = vec![None; legs.len()];
    let mut was_stepping = vec![false; legs.len()];
    let (mut position, mut steps, mut quick) = (Vec3::ZERO, 0, Vec::new());
    for k in 0..400 {
        let rotation = Quat::from_rotation_y(rate * DT * k as f32);
        let velocity = rotation * Vec3::new(0.0, 0.0, speed);
        position += velocity * DT;
        let pose = Pose::new(Vec3::new(position.x, 0.8, position.z), rotation);
        let turn = Vec3::new(0.0, rate, 0.0);
        controller
            .update(DT, pose, velocity, turn, &Plane::GROUND)
            .unwrap();
        for (i, s) in controller.leg_states().iter().enumerate() {
            if s.stepping && !was_stepping[i] {
                steps += 1;
                if let Some(landed) = landed_at[i].filter(|&landed| k < landed + frames) {
                    let ahead = (s.step_start - s.anchor).dot(velocity) / speed;
                    quick.push(format!(
                        "leg {i} landed at frame {landed}, stepped again at {k} from {ahead:.3} m ahead"
                    ));
                }
            }
            if !s.stepping && was_stepping[i] {
                landed_at[i] = Some(k);
            }
            was_stepping[i] = s.stepping;
        }
    }
    assert!(steps >= 20, "only {steps} steps");
    quick
}

/// Regression: feet that had just landed *ahead* of their rest position (at the overshoot,
/// which a running gait makes long) were made to step again at once, by two rules: in a
/// group's turn, every leg of the group past `group_join` of its reach joined the step (fix:
/// only trailing feet join), and the turning check measured a foot ahead of its rest position
/// as turned too far (fix: it only applies to trailing feet, as the reach check does for
/// feet ahead). A running biped walking straight exercised the second, a running
/// twelve-legged creature turning the first.
#[test]
fn regression_landed_feet_do_not_rejoin_group_turn() {
    for (pairs, multiplier, speed, rate) in
        [(1, 2.0, 2.0, 0.0), (6, 2.0, 1.0, 1.5), (3, 1.5, 1.0, 1.5)]
    {
        let quick = quick_resteps(pairs, multiplier, speed, rate, 5);
        assert!(
            quick.is_empty(),
            "{pairs} pairs, ×{multiplier} at {speed} m/s turning {rate} rad/s: {quick:#?}"
        );
    }
}
