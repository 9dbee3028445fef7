//! Property tests of the invariants the crate promises, driven by its public strategies.

use creature_gait::glam::{Quat, Vec2, Vec3, Vec4};
use creature_gait::strategies::{self, MotionStep};
use creature_gait::{
    Controller, Gait, GaitOptions, GaitSpeeds, Ground, HeightField, Leg, Plane, Pose, RayHit, Side,
    solve_two_bone,
};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use proptest::test_runner::TestCaseError;

/// `cases` cases, or `PROPTEST_CASES` when set (for longer soaks).
fn config(cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(cases);
    ProptestConfig {
        cases,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/properties.txt",
        ))),
        ..ProptestConfig::default()
    }
}

/// Drives a controller through a motion sequence over `ground`, riding at `ride` above the
/// ground under the body; checks finiteness, skate, ground contact and boundedness every frame.
fn soak(
    legs: &[Leg],
    ground: &(impl Ground + ?Sized),
    height: impl Fn(f32, f32) -> Option<f32>,
    motion: &[MotionStep],
) -> Result<f32, TestCaseError> {
    soak_with(legs, &GaitOptions::DEFAULT, ground, height, motion)
}

/// [`soak`] with `options`.
fn soak_with(
    legs: &[Leg],
    options: &GaitOptions,
    ground: &(impl Ground + ?Sized),
    height: impl Fn(f32, f32) -> Option<f32>,
    motion: &[MotionStep],
) -> Result<f32, TestCaseError> {
    let mut c = Controller::new(legs, options).map_err(|e| TestCaseError::fail(e.to_string()))?;
    c.add_chain(creature_gait::Chain::new(
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::NEG_Z,
        6,
        0.2,
    ))
    .map_err(|e| TestCaseError::fail(e.to_string()))?;
    let ride = legs.iter().map(|l| -l.rest.y).fold(0.0, f32::max);
    // The sway keeps the feet at rest on their sides: no more than the narrowest walking
    // foot's distance from the midline over the farthest one's distance ahead or behind.
    let walking = || {
        legs.iter()
            .filter(|l| l.kind == creature_gait::LimbKind::Leg && l.rest.x != 0.0)
    };
    let narrowest = walking()
        .map(|l| l.rest.x.abs())
        .fold(f32::INFINITY, f32::min);
    let farthest = walking().map(|l| l.rest.z.abs()).fold(0.0, f32::max);
    let sway_bound = if farthest > 0.0 {
        GaitOptions::DEFAULT.sway_limit.min(narrowest / farthest)
    } else {
        GaitOptions::DEFAULT.sway_limit
    };
    let reach = legs.iter().map(|l| l.length()).fold(0.0, f32::max);
    let (mut position, mut yaw, mut seconds) = (Vec3::ZERO, 0.0f32, 0.0f32);
    for step in motion {
        for _ in 0..step.frames {
            let rotation = Quat::from_rotation_y(yaw);
            let velocity = rotation * Vec3::new(step.strafe, 0.0, step.speed);
            position += velocity * step.dt;
            // Stay on the ground's patch: bounce back toward the centre.
            if position.length() > 12.0 {
                position *= 0.5;
            }
            yaw += step.yaw_rate * step.dt;
            seconds += step.dt;
            let y = height(position.x, position.z).unwrap_or(0.0) + ride;
            let pose = Pose::new(Vec3::new(position.x, y, position.z), rotation);
            c.update(step.dt, pose, velocity, Vec3::Y * step.yaw_rate, ground)
                .map_err(|e| TestCaseError::fail(e.to_string()))?;
            prop_assert!(c.metrics().max_skate <= 1e-4);
            for s in c.leg_states() {
                prop_assert!(s.foot.is_finite() && s.joints.middle.is_finite());
                prop_assert!(s.progress >= 0.0 && s.progress <= 1.0);
                if s.planted
                    && let Some(h) = height(s.foot.x, s.foot.z)
                {
                    prop_assert!((s.foot.y - h).abs() <= 1e-3, "foot off the ground");
                }
                // Bounded: no foot is left far behind (teleports aside, the escape
                // distance keeps it close).
                prop_assert!(s.foot.distance(pose.translation) <= 10.0 * reach + 30.0);
            }
            prop_assert!(c.body().offset.is_finite() && c.body().rotation.is_finite());
            prop_assert!(
                c.body().yaw.abs() <= sway_bound * (1.0 + 1e-6),
                "swayed {} rad, more than {sway_bound}",
                c.body().yaw
            );
            prop_assert!(c.look().rotation.is_finite());
            for p in c.chain(0).map_err(|e| TestCaseError::fail(e.to_string()))? {
                prop_assert!(p.is_finite());
            }
        }
    }
    Ok(seconds)
}

proptest! {
    #![proptest_config(config(24))]

    #[test]
    fn random_motion_on_a_plane_stays_finite_grounded_and_skate_free(
        legs in strategies::leg_layout(),
        motion in strategies::motion_sequence(40),
    ) {
        soak(&legs, &Plane::GROUND, |_, _| Some(0.0), &motion)?;
    }

    #[test]
    fn random_motion_on_a_height_field_stays_finite_grounded_and_skate_free(
        legs in strategies::leg_layout(),
        field in strategies::height_field(0.4),
        motion in strategies::motion_sequence(40),
    ) {
        soak(&legs, &field, |x, z| field.height(x, z), &motion)?;
    }

    /// Gaits by speed: short legs (so the motion's speeds reach a trot and a run), with the
    /// same invariants whatever gait they are in and when they change, hopping or not.
    #[test]
    fn random_motion_with_gaits_by_speed_stays_finite_grounded_and_skate_free(
        legs in strategies::leg_layout(),
        field in strategies::height_field(0.2),
        motion in strategies::motion_sequence(40),
        scale in 0.2f32..1.0,
        hop in any::<bool>(),
    ) {
        let legs: Vec<Leg> = legs
            .iter()
            .map(|l| {
                let mut l = *l;
                (l.hip, l.rest, l.upper, l.lower, l.size) =
                    (l.hip * scale, l.rest * scale, l.upper * scale, l.lower * scale, l.size * scale);
                l
            })
            .collect();
        let options = GaitOptions::DEFAULT.with_gaits(GaitSpeeds::DEFAULT).with_hop(hop);
        soak_with(&legs, &options, &field, |x, z| field.height(x, z), &motion)?;
    }

    /// The gait chosen for a speed is at least the one its thresholds reach and at most the
    /// one their hysteresis keeps, coming from any gait (a hop as a trot).
    #[test]
    fn the_chosen_gait_lies_between_the_thresholds_and_their_hysteresis(
        trot in 0.0f32..5.0,
        above in 0.0f32..5.0,
        hysteresis in 0.05f32..=1.0,
        speed in 0.0f32..20.0,
        leg in 0.01f32..5.0,
        from in 0usize..4,
    ) {
        let speeds = GaitSpeeds::DEFAULT
            .with_thresholds(trot, trot + above)
            .with_hysteresis(hysteresis);
        prop_assert!(speeds.validate().is_ok());
        let froude = speeds.froude(speed, leg);
        let at = |scale: f32| {
            if froude >= speeds.run * scale {
                Gait::Run
            } else if froude >= speeds.trot * scale {
                Gait::Trot
            } else {
                Gait::Walk
            }
        };
        let from = [Gait::Walk, Gait::Trot, Gait::Run, Gait::Hop][from];
        let chosen = speeds.choose(from, speed, leg);
        // A hop is taken as the trot it replaces, and never chosen.
        prop_assert!(chosen != Gait::Hop);
        let from = if from == Gait::Hop { Gait::Trot } else { from };
        prop_assert!(chosen >= at(1.0) && chosen <= at(hysteresis));
        // Staying where it is whenever that is allowed.
        if from >= at(1.0) && from <= at(hysteresis) {
            prop_assert_eq!(chosen, from);
        }
    }
}

proptest! {
    #![proptest_config(config(4))]

    /// Many simulated minutes: four cases of 80 steps of up to 2 s each.
    #[test]
    fn minutes_of_random_motion_stay_finite_and_bounded(
        legs in strategies::leg_layout(),
        motion in strategies::motion_sequence(80),
    ) {
        let field = HeightField::from_fn(
            creature_gait::glam::Vec2::splat(-20.0), 1.0, 41, 41,
            |x, z| 0.2 * (x * 0.5).sin() + 0.15 * (z * 0.3).cos(),
        ).map_err(|e| TestCaseError::fail(e.to_string()))?;
        soak(&legs, &field, |x, z| field.height(x, z), &motion)?;
    }
}

proptest! {
    #![proptest_config(config(512))]

    #[test]
    fn ik_reaches_or_fully_extends_and_keeps_lengths(
        (root, target, upper, lower, pole) in strategies::two_bone(),
    ) {
        let s = solve_two_bone(root, target, upper, lower, pole);
        let scale = upper + lower + root.length() + target.length();
        prop_assert!((s.middle.distance(root) - upper).abs() <= 1e-5 * scale);
        prop_assert!((s.end.distance(s.middle) - lower).abs() <= 1e-5 * scale);
        let d = root.distance(target);
        let dir = (target - root) / d;
        if d <= upper + lower && d >= (upper - lower).abs() {
            prop_assert!(s.end.distance(target) <= 1e-5 * scale);
        } else {
            let clamped = d.clamp((upper - lower).abs(), upper + lower);
            prop_assert!(s.end.distance(root + dir * clamped) <= 1e-5 * scale);
        }
        // The knee is on the pole's side of the chain.
        let off = s.middle - root;
        let across = off - dir * off.dot(dir);
        prop_assert!(across.dot(pole) >= -1e-4 * scale);
    }

    #[test]
    fn vertical_casts_on_a_height_field_return_its_height(
        field in strategies::height_field(1.0),
        x in -20.0f32..20.0,
        z in -20.0f32..20.0,
    ) {
        let hit = field.cast_ray(Vec3::new(x, 10.0, z), Vec3::NEG_Y, 30.0);
        let h = field.height(x, z);
        prop_assert_eq!(hit.map(|h| h.point.y), h);
    }

    #[test]
    fn slanted_casts_land_on_the_surface(
        field in strategies::height_field(1.0),
        origin in strategies::vec3_in(15.0),
        direction in strategies::vec3_in(1.0),
    ) {
        let origin = Vec3::new(origin.x, 3.0 + origin.y.abs(), origin.z);
        let direction = Vec3::new(direction.x, -0.2 - direction.y.abs(), direction.z).normalize();
        if let Some(hit) = field.cast_ray(origin, direction, 100.0) {
            let h = field.height(hit.point.x, hit.point.z);
            prop_assert!(h.is_some());
            prop_assert!((hit.point.y - h.unwrap_or(0.0)).abs() <= 1e-3);
            prop_assert!(hit.normal.is_normalized());
        }
    }

    #[test]
    fn bad_legs_are_rejected(leg in strategies::bad_leg()) {
        prop_assert!(leg.validate(0).is_err());
        prop_assert!(Controller::new(&[leg], &GaitOptions::DEFAULT).is_err());
    }

    #[test]
    fn bad_motion_is_rejected_without_change(
        legs in strategies::leg_layout(),
        dt in strategies::bad_time_step(),
        bad in strategies::non_finite_vec3(),
    ) {
        let mut c = Controller::new(&legs, &GaitOptions::DEFAULT)
            .map_err(|e| TestCaseError::fail(e.to_string()))?;
        let pose = Pose::new(Vec3::new(0.0, 1.0, 0.0), Quat::IDENTITY);
        c.update(0.01, pose, Vec3::ZERO, Vec3::ZERO, &Plane::GROUND)
            .map_err(|e| TestCaseError::fail(e.to_string()))?;
        let before = c.clone();
        prop_assert!(c.update(dt, pose, Vec3::ZERO, Vec3::ZERO, &Plane::GROUND).is_err());
        prop_assert!(c.update(0.01, pose, bad, Vec3::ZERO, &Plane::GROUND).is_err());
        prop_assert!(c.update(0.01, pose, Vec3::ZERO, bad, &Plane::GROUND).is_err());
        prop_assert!(c.update(0.01, Pose::new(bad, Quat::IDENTITY), Vec3::ZERO, Vec3::ZERO, &Plane::GROUND).is_err());
        prop_assert_eq!(c, before);
    }
}

proptest! {
    #![proptest_config(config(256))]

    /// Flier motions: finite for any time and speed, within their amplitudes, periodic.
    #[test]
    fn flapping_is_finite_bounded_and_periodic(
        p in strategies::flap_params(),
        t in -100.0f32..100.0,
        speed in -50.0f32..50.0,
    ) {
        prop_assert!(p.validate().is_ok());
        let angle = p.wing_angle(t);
        let bob = p.body_bob(t, speed);
        prop_assert!(angle.is_finite() && bob.is_finite());
        prop_assert!(angle.abs() <= p.bias.abs() + p.amplitude + 1e-5);
        prop_assert!(bob.abs() <= p.bob + 1e-6);
        for side in [Side::Left, Side::Right] {
            prop_assert!(p.wing_rotation(t, side).is_normalized());
        }
        // One period later (f32 rounding of f·t aside): the same angle.
        let later = p.wing_angle(t + 1.0 / p.frequency);
        let slack = 2e-6 * (p.frequency * t.abs() + 1.0) * 6.3 * p.amplitude + 1e-5;
        prop_assert!((later - angle).abs() <= slack, "{angle} vs {later}");
        // Non-finite time or speed gives a finite (idle) answer.
        prop_assert!(p.wing_angle(f32::NAN).is_finite());
        prop_assert!(p.body_bob(f32::INFINITY, f32::NAN).is_finite());
    }

    /// Swimmer motions: finite, within `max_yaw` (and the idle amplitude when still),
    /// periodic while swimming.
    #[test]
    fn swimming_is_finite_bounded_and_periodic(
        p in strategies::swim_params(),
        t in -100.0f32..100.0,
        speed in -20.0f32..20.0,
        u in -0.5f32..1.5,
    ) {
        prop_assert!(p.validate().is_ok());
        let yaw = p.bone_yaw(t, speed, u);
        prop_assert!(yaw.is_finite() && yaw.abs() <= p.max_yaw() + 1e-5);
        prop_assert!(p.bone_yaw(t, 0.0, u).abs() <= p.idle_amplitude + 1e-6);
        let fast = p.full_speed;
        let now = p.bone_yaw(t, fast, u);
        let later = p.bone_yaw(t + 1.0 / p.frequency, fast, u);
        let slack = 2e-6 * (p.frequency * t.abs() + 10.0) * 6.3 * p.max_yaw() + 1e-5;
        prop_assert!((later - now).abs() <= slack, "{now} vs {later}");
        prop_assert!(p.bone_yaw(f32::NAN, f32::NAN, f32::NAN).is_finite());
        let mut yaws = [0.0f32; 7];
        p.bone_yaws(t, speed, &mut yaws);
        prop_assert!(yaws.iter().all(|y| y.is_finite() && y.abs() <= p.max_yaw() + 1e-5));
    }

    /// `Ground::height_bounds` keeps its promise on the height field (smooth, and stepped with
    /// flat patches, whose bounds are exact) and the horizontal plane: every downward hit over
    /// the square lies within the bounds, and a ray from at or above the highest that reaches
    /// the lowest hits.
    #[test]
    fn height_bounds_hold_every_downward_hit(
        field in strategies::height_field(0.5),
        steps in prop::collection::vec(-4i32..4, 16),
        centre in (-22.0f32..22.0, -22.0f32..22.0),
        half in 0.0f32..1.5,
        points in prop::collection::vec((-1.0f32..=1.0, -1.0f32..=1.0, 0.0f32..2.0, -1.0f32..3.0), 8),
    ) {
        let stepped = HeightField::from_fn(Vec2::splat(-20.0), 0.5, 81, 81, |x, z| {
            let i = (((x + 20.0) / 10.0) as usize).min(3);
            let j = (((z + 20.0) / 10.0) as usize).min(3);
            0.25 * steps[j * 4 + i] as f32
        })
        .map_err(|e| TestCaseError::fail(format!("{e}")))?;
        let centre = Vec2::new(centre.0, centre.1);
        let plane = Plane::horizontal(0.3);
        let grounds: [&dyn Ground; 3] = [&field, &stepped, &plane];
        for ground in grounds {
            let Some((low, high)) = ground.height_bounds(centre, half) else {
                continue;
            };
            prop_assert!(low <= high);
            for &(u, v, above, spare) in &points {
                let (x, z) = (centre.x + u * half, centre.y + v * half);
                // Any downward ray's hit lies within the bounds.
                let origin = Vec3::new(x, low + spare, z);
                for hit in [
                    ground.cast_down_point(origin, 2.0).map(|p| p.y),
                    ground.cast_down(origin, 2.0).map(|h| h.point.y),
                ]
                .into_iter()
                .flatten()
                {
                    prop_assert!(low <= hit && hit <= high, "{hit} outside {low}..{high}");
                }
                // One from above the highest that reaches the lowest hits.
                let origin = Vec3::new(x, high + above, z);
                let reach = origin.y - low;
                let hit = ground.cast_down_point(origin, reach);
                prop_assert!(hit.is_some_and(|p| low <= p.y && p.y <= high), "{hit:?} for {low}..{high}");
            }
        }
        // A flat patch is bounded exactly.
        if let Some((low, high)) = stepped.height_bounds(Vec2::new(-15.0, -15.0), 0.5) {
            prop_assert_eq!(low, high);
        } else {
            prop_assert!(false, "a square inside the grid has bounds");
        }
    }

    /// `Ground::cast_down` (the controller's only query) returns what `cast_ray` straight down
    /// does, for the height field's override and the trait's default alike.
    #[test]
    fn cast_down_matches_a_vertical_cast_ray(
        field in strategies::height_field(0.5),
        x in -25.0f32..25.0,
        z in -25.0f32..25.0,
        y in -2.0f32..3.0,
        max in 0.0f32..5.0,
    ) {
        let origin = Vec3::new(x, y, z);
        prop_assert_eq!(field.cast_down(origin, max), field.cast_ray(origin, Vec3::NEG_Y, max));
        let plane = Plane::horizontal(0.3);
        prop_assert_eq!(plane.cast_down(origin, max), plane.cast_ray(origin, Vec3::NEG_Y, max));
        // `cast_down_point`: the height field's own answer (no normal) against the default.
        for max in [max, f32::INFINITY] {
            let full = field.cast_down(origin, max).filter(RayHit::is_valid).map(|h| h.point);
            prop_assert_eq!(field.cast_down_point(origin, max), full);
        }
        // Heights whose sums overflow: an infinite distance is not a valid hit.
        let steep = HeightField::new(Vec2::ZERO, 1.0, 2, 2, vec![-3e38, 3e38, 3e38, -3e38])
            .map_err(|e| TestCaseError::fail(format!("{e}")))?;
        let origin = Vec3::new(x.rem_euclid(1.0), 3e38 * y.signum(), z.rem_euclid(1.0));
        for max in [max, f32::INFINITY] {
            let full = steep.cast_down(origin, max).filter(RayHit::is_valid).map(|h| h.point);
            prop_assert_eq!(steep.cast_down_point(origin, max), full);
        }
    }

    /// `Ground::cast_down_four` finds what four `cast_down_point`s find, bit for bit: the
    /// height field's lookups four at a time (rays on and off the grid, above and below the
    /// ground, of any length, heights whose sums overflow) and the trait's default.
    #[test]
    fn four_rays_at_once_are_four_rays(
        field in strategies::height_field(0.5),
        rays in prop::collection::vec((-22.0f32..22.0, -2.0f32..3.0, -22.0f32..22.0, -0.5f32..5.0), 4),
        odd in 0usize..8,
        lane in 0usize..4,
    ) {
        let mut ray: [(f32, f32, f32, f32); 4] = core::array::from_fn(|l| rays[l]);
        // Now and then one ray of the four is odd: a NaN or infinite coordinate or length.
        let odd_value = [f32::NAN, f32::INFINITY, -f32::INFINITY, 3e38];
        match odd {
            0 => ray[lane].0 = odd_value[lane],
            1 => ray[lane].1 = odd_value[lane],
            2 => ray[lane].3 = odd_value[lane],
            _ => {}
        }
        let lanes = |f: fn(&(f32, f32, f32, f32)) -> f32| Vec4::from_array(ray.each_ref().map(f));
        let (x, y, z, max) = (lanes(|r| r.0), lanes(|r| r.1), lanes(|r| r.2), lanes(|r| r.3));
        let steep = HeightField::new(Vec2::splat(-22.0), 44.0, 2, 2, vec![-3e38, 3e38, 3e38, -3e38])
            .map_err(|e| TestCaseError::fail(format!("{e}")))?;
        let plane = Plane::horizontal(0.3);
        let grounds: [&dyn Ground; 3] = [&field, &steep, &plane];
        for ground in grounds {
            let four = ground.cast_down_four(x, y, z, max).map(|h| h.map(f32::to_bits));
            let one: [Option<u32>; 4] = core::array::from_fn(|l| {
                ground
                    .cast_down_point(Vec3::new(x[l], y[l], z[l]), max[l])
                    .map(|hit| hit.y.to_bits())
            });
            prop_assert_eq!(four, one);
        }
    }
}
