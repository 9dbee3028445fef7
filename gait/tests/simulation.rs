//! Deterministic walking simulations through the public API: the plausibility figures.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use core::f32::consts::TAU;

use creature_gait::glam::{Quat, Vec3};
use creature_gait::{Controller, GaitOptions, Leg, Plane, Pose};
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
    // A planted foot never leaves its leg's reach: it steps out of turn first, and the body's
    // reaction is held back (before, a 12-legged body overstretched by up to 0.17 m on terrain).
    assert!(f.max_overstretch <= 1e-5, "overstretch: {label}");
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
            let escapes = walk(pairs, speed, false).escapes;
            // Twelve legs take turns in a three-group wave: at 1 m/s a foot cannot wait its turn
            // within reach, so a few steps (4 in 20 m) go out of turn rather than overstretch.
            let allowed = if pairs == 6 && speed > 0.5 { 4 } else { 0 };
            assert!(
                escapes <= allowed,
                "{pairs} pairs at {speed}: {escapes} escapes"
            );
        }
    }
}

/// Regression: a long six-legged body (hips up to 4.1 m ahead of its origin, legs 1.5 to 2.6 m,
/// the legs of a walker the `creature` facade built, its speed multiplier 4.9, at 30 fps)
/// turning in place left its outer feet
/// planted out of reach while they waited for their group, and its pitch and roll reaction
/// lifted the far hips further: overstretch up to 0.14 m. Planted feet now step out of turn
/// once out of reach, and the reaction is held back to keep them in reach.
#[test]
fn regression_a_long_body_turning_in_place_never_overstretches() {
    let legs: Vec<creature_gait::Leg> = [
        (0.276, 1.689, 4.143, 1.098),
        (-0.251, 1.454, 4.143, 0.945),
        (0.569, 1.611, 2.143, 1.047),
        (-0.525, 1.180, 2.143, 0.767),
        (0.570, 1.522, 0.069, 0.989),
        (-0.528, 1.997, 0.069, 1.298),
    ]
    .into_iter()
    .map(|(x, y, z, segment)| {
        creature_gait::Leg::new(Vec3::new(x, y, z), Vec3::new(x, 0.0, z), segment, segment)
            .with_size(y)
    })
    .collect();
    let dt = 1.0 / 30.0;
    for rate in [0.5f32, 1.0, 1.5] {
        let options = options().with_speed_multiplier(4.9);
        let mut controller = Controller::new(&legs, &options).unwrap();
        let mut worst = 0.0f32;
        for k in 0..300 {
            let t = k as f32 * dt;
            controller
                .update(
                    dt,
                    Pose::from_yaw(Vec3::ZERO, rate * t),
                    Vec3::ZERO,
                    Vec3::Y * rate,
                    &Plane::GROUND,
                )
                .unwrap();
            worst = worst.max(controller.metrics().max_overstretch);
        }
        assert!(worst <= 1e-5, "{rate} rad/s: overstretch {worst}");
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
/// `pairs` pairs running at `speed` (speed multiplier `multiplier`) while turning at `rate`,
/// from ahead of the foot's rest position (along that position's own motion, which a tight
/// turn points far from the body's velocity at the ends of a long body); but for steps that
/// the feet's limits force: a foot at the body's midline margin or out of its leg's reach.
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
                let shown = controller.reacted_pose();
                let x = (shown.rotation.inverse() * (s.step_start - shown.translation)).x;
                let margin = o.midline_margin * legs[i].rest.x.abs();
                let at_midline = x * legs[i].rest.x.signum() < 1.1 * margin;
                let hip = shown.rotation * legs[i].hip + shown.translation;
                let reach = legs[i].upper + legs[i].lower;
                let out_of_reach = s.step_start.distance(hip) > 0.98 * reach;
                // The rest position's motion, as the controller sees it.
                let rest = shown.rotation * legs[i].rest + shown.translation;
                let mut motion = velocity + turn.cross(rest - shown.translation);
                motion.y = 0.0;
                let ahead = (s.step_start - s.anchor).dot(motion.normalize_or_zero());
                if let Some(landed) = landed_at[i].filter(|&landed| {
                    k < landed + frames && ahead > 0.0 && !at_midline && !out_of_reach
                }) {
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

/// The largest horizontal move, in one update, of a foot that is within `near` of flat ground
/// before or after it (touching down or lifting off), over 10 s of walking at 1 m/s.
fn landing_skid(options: &GaitOptions, near: f32) -> f32 {
    let legs = creature_legs(2, 1.0);
    let mut controller = Controller::new(&legs, options).unwrap();
    let mut previous: Vec<Vec3> = Vec::new();
    let mut worst = 0.0f32;
    for step in 0..600 {
        let t = step as f32 * DT;
        let pose = Pose::from_yaw(Vec3::new(0.0, 0.8, t), 0.0);
        controller
            .update(DT, pose, Vec3::Z, Vec3::ZERO, &Plane::GROUND)
            .unwrap();
        let feet: Vec<Vec3> = controller.leg_states().iter().map(|s| s.foot).collect();
        for (now, before) in feet.iter().zip(&previous) {
            if now.y.min(before.y) <= near {
                let moved = (*now - *before) * Vec3::new(1.0, 0.0, 1.0);
                worst = worst.max(moved.length());
            }
        }
        previous = feet;
    }
    worst
}

#[test]
fn regression_feet_lift_and_land_vertically_without_skidding() {
    // Near the ground (under 1 cm on this 1 m creature) a foot moves only up or down.
    let near = 0.01;
    let skid = landing_skid(&options(), near);
    assert!(skid <= 1e-5, "skid {skid}");
    // Moving across all through the swing (the gait before plant_fraction) skids.
    let before = landing_skid(&options().with_plant_fraction(0.0), near);
    assert!(before > 1e-3, "skid without the vertical phases {before}");
}

/// The farthest a foot goes past the midline to the other side (in the shown body's frame,
/// × the body length) turning in place at `rate` for 10 s.
fn turn_crossing(options: &GaitOptions, rate: f32) -> f32 {
    // Three pairs: the front and hind feet far from the turn's centre, as on a long body.
    let length = 1.0;
    let legs = creature_legs(3, length);
    let mut controller = Controller::new(&legs, options).unwrap();
    let mut worst = f32::NEG_INFINITY;
    for step in 0..600 {
        let t = step as f32 * DT;
        let pose = Pose::from_yaw(Vec3::Y * 0.8 * length, rate * t);
        controller
            .update(DT, pose, Vec3::ZERO, Vec3::Y * rate, &Plane::GROUND)
            .unwrap();
        let shown = controller.reacted_pose();
        let to_body = shown.rotation.inverse();
        for (leg, state) in legs.iter().zip(controller.leg_states()) {
            let x = (to_body * (state.foot - shown.translation)).x;
            worst = worst.max(-x * leg.rest.x.signum() / length);
        }
    }
    worst
}

#[test]
fn regression_turning_in_place_never_crosses_the_feet() {
    for rate in [0.5, 1.0, 1.5] {
        let past = turn_crossing(&options(), rate);
        assert!(
            past < 0.0,
            "at {rate} rad/s a foot went {past} × length past the midline"
        );
    }
    // Without the midline margin a long body's front feet swing across.
    let before = turn_crossing(&options().with_midline_margin(0.0), 1.5);
    assert!(before > 0.0, "{before}");
}

/// A generated walker's legs: each `(left hip, segment length)` mirrored to the right, its
/// foot at rest straight under the hip on the ground.
fn mirrored_legs(pairs: &[(Vec3, f32)]) -> Vec<Leg> {
    let mut legs = Vec::new();
    for &(hip, upper) in pairs {
        for side in [1.0, -1.0] {
            let hip = Vec3::new(side * hip.x, hip.y, hip.z);
            let rest = Vec3::new(hip.x, 0.0, hip.z);
            legs.push(Leg::new(hip, rest, upper, upper).with_pole(Vec3::Z));
        }
    }
    legs
}

/// A generated walker's legs (creature seed 5005): a long body whose front hips are near the
/// midline (0.47 m out, 1.6 m ahead of the centre).
fn narrow_front_legs() -> Vec<Leg> {
    mirrored_legs(&[
        (Vec3::new(0.466, 2.734, 1.611), 1.777),
        (Vec3::new(0.635, 2.395, -1.188), 1.557),
    ])
}

/// The farthest a foot moves across the ground between two updates while it stays on it (×
/// `length`), turning `legs` in place at `rate` for 10 s.
fn turn_drag(legs: &[Leg], length: f32, rate: f32) -> f32 {
    let mut controller = Controller::new(legs, &options()).unwrap();
    let mut before: Vec<Vec3> = Vec::new();
    let mut worst = 0.0f32;
    for step in 0..600 {
        let pose = Pose::from_yaw(Vec3::ZERO, rate * step as f32 * DT);
        controller
            .update(DT, pose, Vec3::ZERO, Vec3::Y * rate, &Plane::GROUND)
            .unwrap();
        let feet: Vec<Vec3> = controller.leg_states().iter().map(|s| s.foot).collect();
        for (a, b) in before.iter().zip(&feet) {
            if a.y <= 1e-5 && b.y <= 1e-5 {
                worst = worst.max(Vec3::new(b.x - a.x, 0.0, b.z - a.z).length() / length);
            }
        }
        before = feet;
    }
    worst
}

#[test]
fn regression_turning_in_place_never_drags_a_foot_at_the_midline_margin() {
    // A step target clamped exactly to the midline margin landed the foot where the next step
    // started at once: the turning body dragged it along the ground, a new step every update.
    let cases = [
        (narrow_front_legs(), 4.2),
        (creature_legs(2, 1.0), 1.0),
        (creature_legs(3, 1.0), 1.0),
    ];
    for (legs, length) in &cases {
        for rate in [0.5, 1.0, 1.57, 2.0] {
            let drag = turn_drag(legs, *length, rate);
            assert!(
                drag < 1e-4,
                "{} legs at {rate} rad/s: a foot on the ground moved {drag} × length in one update",
                legs.len()
            );
        }
    }
}

#[test]
fn regression_a_lifting_foot_does_not_drift_across_the_midline() {
    // A generated walker's legs (creature seed 5465: front hips 0.27 m off the midline, 1.4 m
    // ahead) turning in place at 1.57 rad/s, 30 updates a second: a foot that reached the
    // midline margin stepped, but drifted on across the midline while it lifted off (and for
    // the update the shown body lags by).
    let legs = mirrored_legs(&[
        (Vec3::new(0.275, 2.205, 1.395), 1.434),
        (Vec3::new(0.461, 1.902, -0.648), 1.236),
    ]);
    let (dt, rate) = (1.0 / 30.0, 1.57);
    let mut controller = Controller::new(&legs, &options()).unwrap();
    let mut worst = f32::NEG_INFINITY;
    for step in 0..300 {
        let pose = Pose::from_yaw(Vec3::ZERO, rate * step as f32 * dt);
        controller
            .update(dt, pose, Vec3::ZERO, Vec3::Y * rate, &Plane::GROUND)
            .unwrap();
        let shown = controller.reacted_pose();
        for (leg, state) in legs.iter().zip(controller.leg_states()) {
            let x = (shown.rotation.inverse() * (state.foot - shown.translation)).x;
            worst = worst.max(-x * leg.rest.x.signum());
        }
    }
    assert!(worst < 0.0, "a foot went {worst} m past the midline");
}

#[test]
fn regression_swaying_never_carries_a_foot_across_the_midline() {
    // A generated walker's legs (creature seed 6904: rear hips 0.073 m off the midline, a
    // 1.36 m body) walking at 0.564 m/s, 30 updates a second: the sway (the planted feet's
    // mean angle about the body's origin) turned the body 5° while a rear foot trailed 1 m
    // behind it, which carried that foot across the midline in the body's frame.
    let legs = mirrored_legs(&[
        (Vec3::new(0.1529, 0.8968, 0.5747), 0.5829),
        (Vec3::new(0.0730, 0.9174, -0.3794), 0.5963),
    ]);
    let options = GaitOptions::DEFAULT.with_speed_multiplier(1.1);
    let worst = least_side_kept(&legs, &options, 0.564);
    // The sway keeps at least half of each foot's margin, and the steps keep the feet near
    // their hips' lines: a quarter of the side is well clear of the midline.
    assert!(worst > 0.25, "a foot kept only {worst} of its side");
}

#[test]
fn regression_rolling_never_carries_a_lifted_foot_across_the_midline() {
    // A generated walker's legs (creature property case 334: an 8.85 m body, front hips
    // 0.88 m off the midline, rear hips 0.34 m) walking at 6.82 m/s: a front foot and the
    // diagonal rear foot lift together, and the roll fitted to the lifted feet's heights (the
    // wide pair's lever beating the narrow one's) turned the body 13° about its origin on the
    // ground, which carried the lifted rear foot across the midline in the body's frame.
    let legs = mirrored_legs(&[
        (Vec3::new(0.876, 5.919, 4.566), 3.849),
        (Vec3::new(0.336, 5.512, -1.770), 3.583),
    ]);
    let options = GaitOptions::DEFAULT.with_speed_multiplier(3.34);
    let worst = least_side_kept(&legs, &options, 6.82);
    // The roll, like the sway, keeps at least half of each foot's margin.
    assert!(worst > 0.25, "a foot kept only {worst} of its side");
}

#[test]
fn regression_a_foot_lifting_off_near_the_midline_is_not_carried_across_it() {
    // A generated walker's legs (creature property case 871: a 14.3 m body on 11 m legs whose
    // hips are 0.6 m and 0.5 m off the midline) turning in place: a foot near the midline
    // lifted off, and the turn and the body's lean carried it across the midline in the
    // body's frame while it rose (here twice its hip's distance from the midline). A lifted
    // foot now moves out as it rises.
    let legs = mirrored_legs(&[
        (Vec3::new(0.599, 10.946, 10.875), 7.122),
        (Vec3::new(0.514, 12.573, -0.157), 8.178),
    ]);
    let options = GaitOptions::DEFAULT.with_speed_multiplier(1.37);
    // The least a lifted foot keeps of its side, as a fraction of its hip's distance from the
    // midline, in the body's frame as shown.
    let mut worst = f32::INFINITY;
    drive(&legs, &options, (0.0, 0.3), |controller| {
        let shown = controller.reacted_pose();
        for (leg, state) in legs.iter().zip(controller.leg_states()) {
            if !state.stepping || state.foot.y < 0.01 * leg.upper {
                continue;
            }
            let local = shown.rotation.inverse() * (state.foot - shown.translation);
            worst = worst.min(local.x * leg.rest.x.signum() / leg.rest.x.abs());
        }
    });
    assert!(
        worst > 0.0,
        "a lifted foot went {:.2} of its side across",
        -worst
    );
}

#[test]
fn regression_a_long_narrow_body_sways_no_foot_across_the_midline() {
    // A generated walker's legs (creature property case 5001: a 27 m body on 26 m legs, front
    // hips 0.61 m off the midline 17.3 m ahead of the body's origin) turning in place: the
    // sway (up to 0.3 rad) turned the body 3.6° in one update, and with it a planted front
    // foot 1 m across the body's frame and over the midline. The sway is now held to what
    // keeps the feet at rest on their sides: 0.61 / 17.3 rad here.
    let legs = mirrored_legs(&[
        (Vec3::new(0.613, 19.796, 17.315), 12.868),
        (Vec3::new(1.020, 16.251, -1.111), 10.563),
    ]);
    let options = GaitOptions::DEFAULT.with_speed_multiplier(0.3);
    let limit = 0.613 / 17.315;
    let (mut sway, mut worst) = (0.0f32, f32::INFINITY);
    drive(&legs, &options, (0.0, 0.546), |controller| {
        sway = sway.max(controller.body().yaw.abs());
        let shown = controller.reacted_pose();
        for (leg, state) in legs.iter().zip(controller.leg_states()) {
            let local = shown.rotation.inverse() * (state.foot - shown.translation);
            worst = worst.min(local.x * leg.rest.x.signum() / leg.rest.x.abs());
        }
    });
    assert!(
        sway <= limit * 1.0001,
        "swayed {sway} rad, more than {limit}"
    );
    assert!(worst > 0.0, "a foot went {:.2} of its side across", -worst);
}

/// The least any foot keeps of its side of the midline in the body's frame as shown (its `x`
/// as a fraction of its hip's distance from the midline), walking `legs` straight at `speed`
/// for 10 s.
fn least_side_kept(legs: &[Leg], options: &GaitOptions, speed: f32) -> f32 {
    let mut worst = f32::INFINITY;
    for local in feet_walking_straight(legs, options, speed) {
        for (leg, foot) in legs.iter().zip(local) {
            worst = worst.min(foot.x * leg.rest.x.signum() / leg.rest.x.abs());
        }
    }
    worst
}

/// Drives a controller of `legs` for 10 s, 30 updates a second, moving forward at `speed` and
/// turning at `rate`; `each` sees it after every update.
fn drive(
    legs: &[Leg],
    options: &GaitOptions,
    (speed, rate): (f32, f32),
    mut each: impl FnMut(&Controller),
) {
    let dt = 1.0 / 30.0;
    let mut controller = Controller::new(legs, options).unwrap();
    for step in 0..300 {
        let t = step as f32 * dt;
        let pose = Pose::from_yaw(Vec3::Z * (speed * t), rate * t);
        controller
            .update(dt, pose, Vec3::Z * speed, Vec3::Y * rate, &Plane::GROUND)
            .unwrap();
        each(&controller);
    }
}

/// The feet in the body's frame as shown, per update, walking `legs` straight at `speed` for
/// 10 s, 30 updates a second.
fn feet_walking_straight(legs: &[Leg], options: &GaitOptions, speed: f32) -> Vec<Vec<Vec3>> {
    let mut feet = Vec::new();
    drive(legs, options, (speed, 0.0), |controller| {
        let shown = controller.reacted_pose();
        feet.push(
            controller
                .leg_states()
                .iter()
                .map(|s| shown.rotation.inverse() * (s.foot - shown.translation))
                .collect(),
        );
    });
    feet
}

/// The nearest two feet on a side come along the body (front foot's `z` minus the rear
/// foot's, in the body's frame as shown), walking `legs` straight at `speed` for 10 s.
fn nearest_along(legs: &[Leg], options: &GaitOptions, speed: f32) -> f32 {
    let mut least = f32::INFINITY;
    for local in feet_walking_straight(legs, options, speed) {
        for (a, leg_a) in legs.iter().enumerate() {
            for (b, leg_b) in legs.iter().enumerate() {
                if leg_a.rest.x * leg_b.rest.x > 0.0 && leg_a.rest.z > leg_b.rest.z {
                    least = least.min(local[a].z - local[b].z);
                }
            }
        }
    }
    least
}

#[test]
fn regression_a_rear_foot_does_not_land_on_a_trailing_front_foot() {
    // A generated walker's legs (creature seed 7988: hips 0.69 m apart along the body, legs
    // 1.4 m tall) walking at 0.84 m/s: a rear foot's step, overshooting ahead of its rest
    // position, landed beside the front foot still planted far behind its own, and the front
    // leg swung through the rear one.
    let legs = mirrored_legs(&[
        (Vec3::new(0.4512, 1.3988, 0.2703), 0.9092),
        (Vec3::new(0.3920, 1.3888, -0.4179), 0.9027),
    ]);
    let spaced = nearest_along(&legs, &GaitOptions::DEFAULT, 0.839);
    let unspaced = nearest_along(&legs, &GaitOptions::DEFAULT.with_foot_spacing(0.0), 0.839);
    // The spacing: a quarter of the legs' size, at most half the hips' distance (0.34 m).
    assert!(spaced > 0.3, "feet {spaced} m apart along the body");
    assert!(unspaced < 0.1, "without the spacing: {unspaced} m");
}

#[test]
fn regression_a_rear_foot_does_not_land_ahead_of_a_front_foot_lifting_off() {
    // A generated walker's legs (creature property case 622: a 6.6 m centipede, six legs a
    // side, hips 0.9 m apart along the body, legs about 1 m tall, knees out) walking at
    // 2.31 m/s: a rear foot re-aimed its step at the front foot's landing place as soon as the
    // front foot lifted, and landed ahead of it while it was still lifting off, crossing the
    // two legs.
    let length = 6.611;
    let rows = [
        (Vec3::new(0.167, 0.233, 0.515), 0.687, 0.188, Vec3::Z),
        (Vec3::new(0.178, 0.180, 0.399), 0.399, 0.117, Vec3::X),
        (Vec3::new(0.179, 0.149, 0.260), 0.283, 0.098, Vec3::X),
        (Vec3::new(0.179, 0.147, 0.107), 0.132, 0.097, Vec3::X),
        (Vec3::new(0.179, 0.162, -0.048), -0.039, 0.106, Vec3::X),
        (Vec3::new(0.167, 0.194, -0.196), -0.196, 0.126, Vec3::NEG_Z),
    ];
    let mut legs = Vec::new();
    for (hip, rest_z, segment, pole) in rows {
        for side in [1.0, -1.0] {
            let mirror = Vec3::new(side, 1.0, 1.0);
            let hip = hip * mirror * length;
            let rest = Vec3::new(hip.x, 0.0, rest_z * length);
            let segment = segment * length;
            legs.push(Leg::new(hip, rest, segment, segment).with_pole(pole * mirror));
        }
    }
    let options = GaitOptions::DEFAULT.with_speed_multiplier(1.41);
    let nearest = nearest_along(&legs, &options, 2.31);
    assert!(
        nearest > 0.0,
        "a front foot {} m behind a rear one",
        -nearest
    );
}

/// The fewest updates any step of `legs` lasts, turning in place at `rate` for 10 s, 30
/// updates a second.
fn shortest_swing(legs: &[Leg], options: &GaitOptions, rate: f32) -> usize {
    let mut running = vec![0usize; legs.len()];
    let mut shortest = usize::MAX;
    drive(legs, options, (0.0, rate), |controller| {
        for (run, state) in running.iter_mut().zip(controller.leg_states()) {
            if state.stepping {
                *run += 1;
            } else if *run > 0 {
                shortest = shortest.min(*run);
                *run = 0;
            }
        }
    });
    shortest
}

#[test]
fn regression_a_long_body_turning_in_place_lifts_every_step() {
    // A long body's outer feet, turning in place, have rest positions that move so fast that a
    // step's progress (by the rest position's motion) ran to the end in an update or two: the
    // foot jumped along the ground (creature seed 8370, 0.22 m in one frame). A step lasts
    // `min_swing_time` (0.1 s: 3 updates) at least.
    let legs = mirrored_legs(&[
        (Vec3::new(0.6318, 1.4108, 1.5514), 0.9170),
        (Vec3::new(0.4844, 1.4073, -0.0290), 0.9148),
        (Vec3::new(0.3160, 1.1726, -1.6262), 0.7622),
    ]);
    let options = GaitOptions::DEFAULT.with_speed_multiplier(1.17);
    let rate = core::f32::consts::TAU / 4.43;
    let quick = shortest_swing(&legs, &options.with_min_swing_time(1e-6), rate);
    assert!(quick <= 2, "without the minimum: {quick} updates");
    let shortest = shortest_swing(&legs, &options, rate);
    assert!(shortest >= 3, "a step of {shortest} updates");
}

#[test]
fn regression_a_chain_on_a_body_moving_far_per_update_stays_behind_its_root() {
    // The body moved 0.5 m in an update while the chain's segments are 0.1 m: every sub-step
    // pinned the root at the new place at once, so the chain's first joint, left 0.5 m back,
    // was projected behind the root and the chain whirled. The sub-steps now carry the rest
    // (the root included) from the last update's place to this one's. (Damped at 0.7 of
    // critical, the chain trails without ringing.)
    let mut c = Controller::chains_only(1.0, &GaitOptions::DEFAULT).unwrap();
    let chain = c
        .add_chain(
            creature_gait::Chain::new(Vec3::ZERO, Vec3::NEG_Y, 2, 0.1)
                .with_spring(1_000.0, 44.0)
                .with_gravity(9.81),
        )
        .unwrap();
    let ground = Plane::horizontal(-100.0);
    let (dt, speed) = (1.0 / 30.0, 15.0);
    let mut worst = 0.0f32;
    for frame in 0..90 {
        let at = Vec3::Z * (speed * dt * frame as f32);
        c.update(
            dt,
            Pose::from_yaw(at, 0.0),
            Vec3::Z * speed,
            Vec3::ZERO,
            &ground,
        )
        .unwrap();
        let points = c.chain(chain).unwrap();
        for w in points.windows(2) {
            // Trailing (−Z) and hanging (−Y) it may be; never ahead of, nor above, its root.
            let d = (w[1] - w[0]).normalize();
            worst = worst.max(d.angle_between(Vec3::new(0.0, -1.0, -1.0).normalize()));
        }
    }
    assert!(
        worst < core::f32::consts::FRAC_PI_2 * 0.9,
        "{} degrees",
        worst.to_degrees()
    );
}

#[test]
fn regression_a_fast_step_lands_short_of_a_straight_leg() {
    // A long-strided walker (speed multiplier 3) put its feet down at the full length of its
    // legs ahead of the hip: the leg landed straight, and a straight knee turns fast for the
    // least shortening as the body comes over the foot (a knee turned 42° between two frames
    // of a baked walk). A step now lands within 95% of the leg's length from its hip.
    // Legs whose feet stand ahead of their hips, as a generated walker's can.
    let legs: Vec<Leg> = creature_legs(2, 1.0)
        .into_iter()
        .map(|l| {
            Leg::new(
                l.hip,
                l.hip + Vec3::new(0.1 * l.hip.x.signum(), -0.6, 0.45),
                0.5,
                0.5,
            )
            .with_pole(Vec3::Z)
        })
        .collect();
    let o = GaitOptions::DEFAULT.with_speed_multiplier(3.0);
    let mut controller = Controller::new(&legs, &o).unwrap();
    let ground = Plane::GROUND;
    let speed = 2.5;
    let mut pose = Pose::new(Vec3::new(0.0, 0.6, 0.0), Quat::IDENTITY);
    controller.reset(pose, &ground).unwrap();
    let mut was: Vec<bool> = controller.leg_states().iter().map(|s| s.planted).collect();
    let (mut landings, mut worst) = (0, 0.0f32);
    for _ in 0..(10.0 / DT) as usize {
        pose.translation.z += speed * DT;
        controller
            .update(DT, pose, Vec3::Z * speed, Vec3::ZERO, &ground)
            .unwrap();
        let body = controller.reacted_pose();
        for ((leg, state), was) in legs.iter().zip(controller.leg_states()).zip(&mut was) {
            if state.planted && !*was {
                landings += 1;
                let hip = body.transform_point(leg.hip);
                worst = worst.max(hip.distance(state.foot) / (leg.upper + leg.lower));
            }
            *was = state.planted;
        }
    }
    assert!(landings >= 20, "{landings}");
    assert!(
        worst <= 0.95 + 1e-3,
        "a foot landed {worst} of its leg's length away"
    );
}

#[test]
fn regression_a_long_front_leg_steps_before_the_hind_foot_lands_on_it() {
    // A generated walker's legs (creature property case 9734 of 20,000): front legs 8.1 m long
    // with hips 0.28 m out, 1.25 m ahead of hind legs 4.2 m long with hips 0.62 m out, walking
    // at 6.8 m/s. A front foot trailed 2.6 m behind its hip, past where the hind leg can land:
    // the landing reach kept the hind step's target short of the foot spacing, the hind foot
    // came down 2 cm from the front foot still on the ground, and the legs passed through each
    // other. A foot trailing onto a hind foot of its side now steps first, out of turn.
    let mut legs = mirrored_legs(&[(Vec3::new(0.284, 6.251, -0.569), 4.063)]);
    legs.extend(mirrored_legs(&[(Vec3::new(0.619, 3.265, -1.815), 2.122)]));
    let options = GaitOptions::DEFAULT
        .with_speed_multiplier(3.387)
        .with_min_swing_time(0.129);
    // The spacing the hind feet keep behind the front feet: a quarter of the legs' mean size,
    // at most half their rest positions' distance along the body.
    let spacing = (0.25 * 0.5 * (legs[0].size + legs[2].size)).min(0.5 * (0.569 - 1.815f32).abs());
    let mut least = f32::INFINITY;
    drive(&legs, &options, (6.832, 0.0), |controller| {
        let body = controller.reacted_pose();
        let along = |p: Vec3| (body.rotation.inverse() * (p - body.translation)).z;
        let states = controller.leg_states();
        for (front, hind) in [(0, 2), (1, 3)] {
            let (f, h) = (&states[front], &states[hind]);
            // Both feet on the ground (planted, or not yet off it).
            if f.foot.y < 0.01 && h.foot.y < 0.01 {
                least = least.min(along(f.foot) - along(h.foot));
            }
        }
    });
    assert!(
        least >= 0.5 * spacing,
        "a front foot on the ground {least:.3} m ahead of its hind foot (spacing {spacing:.3} m)"
    );
}
