//! Gait set-up of a 3D walker: its legs and arms registered with `creature-gait`.

use alloc::vec::Vec;

use creature_gait::{Controller, GaitOptions, GaitSpeeds, Leg, LimbKind};
use glam::Vec2;

use crate::Error;
use crate::math::{asin, sqrt};

/// A walker's legs and arms as `creature-gait` takes them (body space = the creature's model
/// space at rest, the ground at `y = 0`), with the gait options, ready for a [`Controller`].
///
/// ```
/// use creature::d3::{generate, Kind, Params};
/// use creature::gait::{Plane, Pose, glam::Vec3};
///
/// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
/// let setup = walker.gait.as_ref().expect("walkers have a gait set-up");
/// let mut controller = setup.controller()?;
/// let ground = Plane::horizontal(0.0);
/// let velocity = Vec3::Z * walker.speed;
/// let mut position = Vec3::ZERO;
/// for _ in 0..30 {
///     position += velocity / 30.0;
///     controller.update(1.0 / 30.0, Pose::from_yaw(position, 0.0), velocity, Vec3::ZERO, &ground)?;
/// }
/// assert!(controller.metrics().max_skate <= 1e-3 * walker.length);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct GaitSetup {
    /// The legs and arms, hips and rest feet (hands) where the mesh has them.
    pub legs: Vec<Leg>,
    /// For each of [`legs`](Self::legs), its index in the creature's limb plan.
    pub limbs: Vec<usize>,
    /// For each of [`legs`](Self::legs), its hip joint in the skeleton; the knee and the foot
    /// are the next two joints.
    pub hip_joints: Vec<usize>,
    /// Gait options: the defaults, with the creature's speed factor as the speed multiplier
    /// and gaits by speed (`creature_gait::GaitSpeeds`): below a Froude number of 2.5 the
    /// pattern walkers always walked in (up to three pairs of legs a trot's two alternating
    /// groups, from four pairs a three-group wave), a run from 2.5; a hopping biped
    /// (`hop` set, see [`Params::hop_chance`](crate::d3::Params::hop_chance)) walks up to
    /// [`HOP_FROUDE`] and hops from there.
    pub options: GaitOptions,
}

impl GaitSetup {
    /// The speed its `run` clip runs at (m/s): a Froude number `v² / (g · leg)` of
    /// [`RUN_FROUDE`] on the legs' mean size, or `None` without legs (arms only).
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    ///
    /// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
    /// let setup = walker.gait.as_ref().expect("walkers have a gait set-up");
    /// let run = setup.run_speed().expect("walkers have legs");
    /// assert!(run > walker.speed);
    /// # Ok::<(), creature::Error>(())
    /// ```
    #[must_use]
    pub fn run_speed(&self) -> Option<f32> {
        mean_leg_size(&self.legs).map(|leg| sqrt(RUN_FROUDE * GRAVITY * leg))
    }

    /// The speed its `hop` clip hops at (m/s) if it hops (its
    /// [`options`](Self::options)' `hop`): a Froude number of [`HOP_CLIP_FROUDE`] on the legs'
    /// mean size; else `None`.
    #[must_use]
    pub fn hop_speed(&self) -> Option<f32> {
        if !self.options.hop {
            return None;
        }
        mean_leg_size(&self.legs).map(|leg| sqrt(HOP_CLIP_FROUDE * GRAVITY * leg))
    }

    /// A fresh controller for these legs.
    ///
    /// # Errors
    /// [`Error::Gait`] if `creature-gait` rejects the legs or options (an edited set-up).
    pub fn controller(&self) -> Result<Controller, Error> {
        Ok(Controller::new(&self.legs, &self.options)?)
    }
}

/// The fastest a walking gait goes on legs of mean size `leg` (m, hip to foot): a Froude number
/// `v² / (g · leg)` of [`MAX_WALK_FROUDE`]. Faster, the body vaulting over a stance leg would
/// need more than gravity to stay on it: animals run there, and a walk's swings would flick
/// their joints through a right angle between two frames.
pub(crate) fn walk_speed_limit(leg: f32) -> f32 {
    sqrt(MAX_WALK_FROUDE * GRAVITY * leg.max(0.0))
}

/// The mean size of the legs (not arms) of `legs`, or `None` without legs.
pub(crate) fn mean_leg_size(legs: &[Leg]) -> Option<f32> {
    let sizes = legs
        .iter()
        .filter(|l| l.kind == LimbKind::Leg)
        .map(|l| l.size);
    let (sum, count) = sizes.fold((0.0f32, 0u32), |(s, n), size| (s + size, n + 1));
    (count > 0).then(|| sum / count as f32)
}

/// The largest Froude number (`v² / (g · leg length)`) a walker walks at: the inverted
/// pendulum's limit.
pub(crate) const MAX_WALK_FROUDE: f32 = 1.0;

/// A walker's gaits by speed, for `legs`: `GaitSpeeds::DEFAULT`'s run (from a Froude number
/// of 2.5, back below 2), and below it the pattern walkers always walked in at every walking
/// speed: up to three pairs the trot's (two alternating groups: diagonal pairs, tripods), from
/// four pairs the walk's (a three-group wave). (`creature_gait`'s walk on four legs, one foot
/// at a time, swings each foot in a quarter of a stride: at the walkers' speeds, faster than
/// their joints may turn.) A biped that `hops` walks up to [`HOP_FROUDE`] and hops from there
/// (a biped's walk and trot step alike).
pub(crate) fn walker_gaits(legs: &[Leg], hops: bool) -> GaitSpeeds {
    let scale = legs.iter().map(|l| l.size).fold(0.0f32, f32::max).max(1e-6);
    let walking = || legs.iter().filter(|l| l.kind == LimbKind::Leg);
    // Pairs as `creature_gait` counts them: the most legs on one side (or the midline).
    let left = walking().filter(|l| l.rest.x > 1e-4 * scale).count();
    let right = walking().filter(|l| l.rest.x < -1e-4 * scale).count();
    let centre = walking().count() - left - right;
    let run = GaitSpeeds::DEFAULT.run;
    if hops && walking_legs(legs) == 2 {
        GaitSpeeds::DEFAULT.with_thresholds(HOP_FROUDE, run)
    } else if left.max(right).max(centre) > WAVE_PAIRS {
        GaitSpeeds::DEFAULT.with_thresholds(run, run)
    } else {
        GaitSpeeds::DEFAULT.with_thresholds(0.0, run)
    }
}

/// How many of `legs` are walking legs (not arms).
pub(crate) fn walking_legs(legs: &[Leg]) -> usize {
    legs.iter().filter(|l| l.kind == LimbKind::Leg).count()
}

/// The Froude number from which a hopping biped hops ([`Params::hop_chance`](crate::d3::Params::hop_chance)):
/// a little above the fastest walkers walk (1), so its `walk` stays a walk, and it walks
/// again once it slows below 0.8 of it (the gaits' hysteresis), still above 1.
pub const HOP_FROUDE: f32 = 1.3;

/// The Froude number a hopper's `hop` clip hops at: between [`HOP_FROUDE`] and the run's
/// 2.5, a bounding hop (faster ones, their swings the shortest a leg may take, flutter).
pub const HOP_CLIP_FROUDE: f32 = 1.75;

/// The most pairs whose walkers trot (two alternating groups) at walking speeds; more walk in
/// a three-group wave (`creature_gait` derives the same).
const WAVE_PAIRS: usize = 3;

/// The Froude number a walker's `run` clip runs at: past `GaitSpeeds::DEFAULT`'s 2.5, where
/// it runs, with room for its hysteresis.
pub const RUN_FROUDE: f32 = 2.75;

/// Standard gravity, m/s².
const GRAVITY: f32 = 9.81;

/// The longest a swing may be made to take (seconds): `GaitOptions::min_swing_time`'s range.
pub(crate) const MAX_SWING_TIME: f32 = 10.0;

/// The shortest swing (seconds, before the controller's `√size` scaling of small legs, see
/// [`GaitOptions::min_swing_time`]) in which no joint of `legs` need turn faster than
/// `max_rate` (radians per second), `options` sizing the steps: a leg's hip and knee turn
/// from the foot's farthest reach behind (lift-off), through its full lift above the rest
/// position, to its farthest reach ahead (landing). A fast walker's quick swing would
/// otherwise flick its knee through a right angle between two frames. The default
/// `min_swing_time` at least; at most 10 s (the option's range).
pub(crate) fn swing_time_for_joints(legs: &[Leg], options: &GaitOptions, max_rate: f32) -> f32 {
    let mut least = options.min_swing_time;
    for leg in legs.iter().filter(|l| l.kind == LimbKind::Leg) {
        let size = leg.size;
        let lift = options.step_height * size * options.speed_multiplier.max(1.0);
        let hip = Vec2::new(leg.hip.z, leg.hip.y);
        let rest = Vec2::new(leg.rest.z, leg.rest.y);
        let feet = [
            rest - Vec2::X * (options.reach.evaluate(-1.0) * size),
            rest + Vec2::Y * (lift * options.height_curve.evaluate(0.5)),
            rest + Vec2::X * (options.reach.evaluate(1.0) * size),
        ];
        let angles = feet.map(|foot| leg_angles(foot - hip, leg.upper, leg.lower));
        let turn = |k: usize| {
            let [a, b, c] = angles.map(|x| x[k]);
            (b - a).abs() + (c - b).abs()
        };
        // The thigh turns with the foot's direction and with its angle to that direction.
        let (hip_turn, knee_turn) = (turn(0) + turn(1), turn(2));
        let time = hip_turn.max(knee_turn) / max_rate;
        least = least.max(time / sqrt(size.min(1.0)));
    }
    if least.is_finite() {
        least.min(MAX_SWING_TIME)
    } else {
        MAX_SWING_TIME
    }
}

/// A two-bone leg's angles (radians) reaching `to` (from the hip, in the leg's plane: along
/// the body and up) with segments `upper` and `lower`: the direction to the foot from straight
/// down, the thigh's angle from that direction, and the knee's bend.
fn leg_angles(to: Vec2, upper: f32, lower: f32) -> [f32; 3] {
    let (a, b) = (upper, lower);
    let d = to
        .length()
        .clamp((a - b).abs() + 1e-6 * (a + b), a + b)
        .max(1e-12);
    let acos = |x: f32| core::f32::consts::FRAC_PI_2 - asin(x.clamp(-1.0, 1.0));
    [
        Vec2::new(-to.y, to.x).to_angle(),
        acos((a * a + d * d - b * b) / (2.0 * a * d)),
        core::f32::consts::PI - acos((a * a + b * b - d * d) / (2.0 * a * b)),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn leg() -> Leg {
        // A 1 m tall leg whose knee bends forward at rest.
        Leg::new(Vec3::Y, Vec3::ZERO, 0.65, 0.65)
            .with_pole(Vec3::Z)
            .with_size(1.0)
    }

    #[test]
    fn a_slow_walkers_swing_keeps_the_default_shortest_swing() {
        let options = GaitOptions::DEFAULT;
        let time = swing_time_for_joints(&[leg()], &options, 18.0);
        assert_eq!(time, options.min_swing_time);
    }

    #[test]
    fn a_fast_walkers_high_steps_take_long_enough_for_its_joints() {
        // Four times the speed lifts the foot four times as high (0.6 of the leg): the knee
        // folds and unfolds through about two radians in a swing.
        let options = GaitOptions::DEFAULT.with_speed_multiplier(4.0);
        let time = swing_time_for_joints(&[leg()], &options, 18.0);
        let [low, high, far] = [
            Vec2::new(-0.45, -1.0),
            Vec2::new(0.0, -0.4),
            Vec2::new(0.3, -1.0),
        ]
        .map(|to| leg_angles(to, 0.65, 0.65)[2]);
        let knee = (high - low).abs() + (high - far).abs();
        assert!(knee > 2.0, "{knee}");
        assert!(
            time >= knee / 18.0 && time > options.min_swing_time,
            "{time}"
        );
        // Slower joints, longer swings; a small leg's time is before the controller's √size.
        assert!(swing_time_for_joints(&[leg()], &options, 9.0) > time);
        let small = Leg::new(Vec3::Y * 0.25, Vec3::ZERO, 0.1625, 0.1625)
            .with_pole(Vec3::Z)
            .with_size(0.25);
        let small_time = swing_time_for_joints(&[small], &options, 18.0);
        assert!(
            (small_time * 0.5 - time).abs() < 0.05 * time,
            "{small_time} {time}"
        );
    }

    #[test]
    fn a_walk_is_no_faster_than_froude_one() {
        // A 1 m leg walks at most √g m/s; legs alone set it, an arm does not.
        let limit = walk_speed_limit(1.0);
        assert!((limit - GRAVITY.sqrt()).abs() < 1e-5, "{limit}");
        assert!((walk_speed_limit(4.0) - 2.0 * limit).abs() < 1e-5);
        assert_eq!(walk_speed_limit(-1.0), 0.0);
        let arm = leg().with_size(3.0).with_kind(LimbKind::Arm);
        assert_eq!(mean_leg_size(&[leg(), arm]), Some(1.0));
        assert_eq!(mean_leg_size(&[arm]), None);
    }

    #[test]
    fn arms_and_broken_legs_give_a_finite_time() {
        let arm = leg().with_kind(LimbKind::Arm);
        let options = GaitOptions::DEFAULT.with_speed_multiplier(4.0);
        assert_eq!(
            swing_time_for_joints(&[arm], &options, 18.0),
            options.min_swing_time
        );
        let zero = Leg::new(Vec3::Y, Vec3::Y, 0.0, 0.0);
        let time = swing_time_for_joints(&[zero], &options, 18.0);
        assert!(time.is_finite() && time <= 10.0, "{time}");
    }
}
