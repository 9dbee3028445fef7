//! The [`Controller`]: per-leg stepping state and the five layers, updated together by
//! [`Controller::update`] in this order:
//!
//! 1. action and sequencing ([`stepping`]): ground rays, foot placement, steps and the leg
//!    groups' turns;
//! 2. reaction ([`reaction`]): the body's bob, breathing, sway, pitch, roll and hip roll,
//!    scaled back to keep planted feet in reach;
//! 3. intent ([`look`]): the head's smoothed look-at;
//! 4. follow-through ([`chains`]): damped spring chains (tails, fins, dangling legs);
//! 5. the legs' two-bone IK ([`joints`]), four legs at a time.
//!
//! Construction and settings are in [`setup`], the read-outs in [`readout`] and the figures
//! measured on demand in [`measure`].

use alloc::vec::Vec;

use glam::{Mat3A, Quat, Vec3, Vec3A, Vec4};

use crate::error::{GaitError, finite, finite3, in_range};
use crate::gaits::Gait;
use crate::ground::Ground;
use crate::ik::{TwoBone, V3, solve_two_bone};
use crate::leg::{Chain, Layout, Leg, LimbKind, Pose};
use crate::math::{Roots, abs, floor_non_negative, smoothing, sqrt};
use crate::metrics::GaitMetrics;
use crate::options::GaitOptions;

mod chains;
mod joints;
mod look;
mod measure;
mod reaction;
mod readout;
mod setup;
mod stepping;

use chains::ChainState;
use joints::LegLanes;
use reaction::HipPair;
use stepping::cast_anchor;

/// Largest accepted coordinate of the body's position, metres.
pub const MAX_COORDINATE: f32 = 1.0e6;
/// Largest accepted linear speed, metres per second.
pub const MAX_SPEED: f32 = 1.0e4;
/// Largest accepted angular speed, radians per second.
pub const MAX_ANGULAR_SPEED: f32 = 1.0e3;
/// Largest accepted time step, seconds.
pub const MAX_TIME_STEP: f32 = 1.0e3;

/// The state and read-out of one leg (or arm).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct LegState {
    /// The foot's position in world space (procedural, before blending).
    pub foot: Vec3,
    /// Ground normal under the foot (world), +Y for arms and legs without ground.
    pub normal: Vec3,
    /// Whether the foot stands still on the ground (grounded and not stepping). Arms are
    /// "planted" while they are not stepping (they hold their place in the air).
    pub planted: bool,
    /// Whether the ground ray under the rest position hit.
    pub grounded: bool,
    /// Whether the leg is in a step.
    pub stepping: bool,
    /// Progress of the current (or last) step, `0..=1`.
    pub progress: f32,
    /// Where the current (or last) step started, world.
    pub step_start: Vec3,
    /// The current (or last) step's target, world; kept current while the body moves.
    pub step_target: Vec3,
    /// The rest position projected onto the ground (the ray hit), world; for arms, the rest
    /// position itself.
    pub anchor: Vec3,
    /// Steps taken since the controller was created.
    pub steps: u32,
    /// Of those, escape steps (taken outside the group's turn).
    pub escapes: u32,
    /// Hip roll (radians, about the body's forward axis): positive when this foot is higher
    /// than its partner's, so this side's hip rises (3D seed). 0 without a partner.
    pub hip_roll: f32,
    /// The solved leg (hip, knee, foot and segment rotations, world), after the body's reaction
    /// and the blend weight.
    pub joints: TwoBone,
    prev_anchor: Vec3,
    prev_foot: Vec3,
    prev_planted: bool,
    swing_length: f32,
    lift: f32,
    escaping: bool,
    /// How far the step progressed in the last update (a run hands over a frame early when the
    /// next would carry it past the handover).
    pace: f32,
}

impl LegState {
    fn new(foot: Vec3) -> Self {
        Self {
            foot,
            normal: Vec3::Y,
            planted: false,
            grounded: false,
            stepping: false,
            progress: 1.0,
            step_start: foot,
            step_target: foot,
            anchor: foot,
            steps: 0,
            escapes: 0,
            hip_roll: 0.0,
            joints: solve_two_bone(foot, foot, 0.0, 0.0, Vec3::Z),
            prev_anchor: foot,
            prev_foot: foot,
            prev_planted: false,
            swing_length: 1.0,
            lift: 0.0,
            escaping: false,
            pace: 0.0,
        }
    }

    /// Whether the current step is an escape step.
    #[must_use]
    pub const fn is_escaping(&self) -> bool {
        self.stepping && self.escaping
    }
}

/// The body's reaction to its legs, relative to the driving pose (after the blend weight).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyReaction {
    /// Offset to add to the body's position (world): the bob plus idle breathing, along +Y.
    pub offset: Vec3,
    /// Rotation to apply after the body's rotation (body space): sway (yaw), pitch and roll.
    pub rotation: Quat,
    /// The bob alone, metres (before blending).
    pub bob: f32,
    /// Sway angle about the body's up axis, radians (before blending).
    pub yaw: f32,
    /// Pitch about the body's left (+X) axis, radians (before blending).
    pub pitch: f32,
    /// Roll about the body's forward (+Z) axis, radians (before blending).
    pub roll: f32,
}

impl BodyReaction {
    const NEUTRAL: Self = Self {
        offset: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        bob: 0.0,
        yaw: 0.0,
        pitch: 0.0,
        roll: 0.0,
    };
}

/// The head's smoothed look-at (intent layer).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Look {
    /// Rotation of the head in body space (after blending): +Z turned toward where the body
    /// turns, or toward the look target.
    pub rotation: Quat,
    /// The point the head looks at, world.
    pub target: Vec3,
    /// Smoothed yaw, radians (before blending).
    pub yaw: f32,
    /// Smoothed pitch, radians, positive up (before blending).
    pub pitch: f32,
}

/// The gait controller: give it legs once, then call [`update`](Self::update) every frame
/// with the body's pose and motion; read the feet, joints, body reaction, head and chains.
///
/// ```
/// use creature_gait::{Controller, GaitOptions, Leg, Plane, Pose, glam::Vec3};
///
/// let legs = [
///     Leg::new(Vec3::new(0.2, 0.9, 0.0), Vec3::new(0.25, 0.0, 0.0), 0.5, 0.5),
///     Leg::new(Vec3::new(-0.2, 0.9, 0.0), Vec3::new(-0.25, 0.0, 0.0), 0.5, 0.5),
/// ];
/// let mut biped = Controller::new(&legs, &GaitOptions::DEFAULT)?;
/// let ground = Plane::GROUND;
/// let velocity = Vec3::new(0.0, 0.0, 1.0);
/// for frame in 0..120 {
///     let pose = Pose::new(velocity * (frame as f32 / 60.0), Default::default());
///     biped.update(1.0 / 60.0, pose, velocity, Vec3::ZERO, &ground)?;
/// }
/// assert!(biped.leg_states().iter().all(|leg| leg.steps > 0));
/// assert!(biped.metrics().max_skate <= 1e-6);
/// # Ok::<(), creature_gait::GaitError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Controller {
    legs: Vec<Leg>,
    options: GaitOptions,
    layout: Layout,
    states: Vec<LegState>,
    chains: Vec<Chain>,
    chain_states: Vec<ChainState>,
    initialized: bool,
    active_group: u8,
    turn_taken: bool,
    mean_size: f32,
    /// The most the sway may turn the body (radians) before it carries a foot at rest across
    /// the midline: the narrowest walking foot's distance from the midline over the farthest's
    /// distance ahead or behind the body's origin (infinite with no such feet).
    sway_side_limit: f32,
    swing_fraction: f32,
    /// The gait the legs step in now (see `GaitOptions::gaits`), and the one the speed asks
    /// for, taken when a group hands over to the next.
    gait: Gait,
    wanted_gait: Gait,
    /// The walking legs' mean size (the Froude number's length), or 0 without walking legs.
    walking_size: f32,
    /// The progress past which a stepping group hands over to the next: 1 (when its steps
    /// land), but in a run, whose groups' swings overlap, `(1 / max(n, 2)) / 0.6` with `n`
    /// groups (5/6 with two).
    handover: f32,
    pose: Pose,
    reaction: BodyReaction,
    look: Look,
    look_target: Option<Vec3>,
    head: Vec3,
    idle_phase: f32,
    blend: f32,
    blend_target: f32,
    blend_rate: f32,
    metrics: GaitMetrics,
    wants: Vec<u8>,
    motion: Vec<Vec3>,
    /// Each leg's hop: the apex its step's flight rises to (a ballistic arc over the
    /// swing's expected time), 0 for a step that is not a hop's.
    hop_heights: Vec<f32>,
    /// How far the body is risen in a hop's flight this update (see `action`).
    hop_rise: f32,
    /// How far each foot is raised with the body in a hop's flight this update (the bob,
    /// which follows the feet's lift, leaves it out: the body rises once).
    hop_lifts: Vec<f32>,

    // Per-update scratch and per-leg invariants, so an update does no allocation and does not
    // recompute what the legs and options fix.
    /// Each leg's rest position in world space, this update.
    rest_world: Vec<Vec3>,
    /// Each leg's hip-roll partner and lever (see `HipPair`).
    hip_pairs: Vec<HipPair>,
    has_arms: bool,
    /// `cos(max_turn_angle)`: the turning-in-place check without `atan2`.
    cos_turn: f32,
    /// The `dt` the smoothing factors below were computed for (−1: none yet).
    smoothing_dt: f32,
    react_k: f32,
    look_k: f32,
    /// The look-at's `(yaw, pitch, blend)` bits of the last update and what they gave: the
    /// head's rotation is then unchanged and its target, in body space, is this point (a
    /// `Vec3A`: its fourth lane is defined, see `intend`).
    look_cache: Option<([u32; 3], Vec3A)>,
    /// The legs four at a time (the last group padded with its first leg), in SIMD lanes
    /// for the IK: hips, poles and segment lengths.
    leg_lanes: Vec<LegLanes>,
    /// The feet, four legs at a time (the last group padded with its first leg), once the
    /// action has placed them (see `gather_feet`).
    feet: Vec<V3>,
    /// The reacted body's hips, four legs at a time, and its rotation when they are this
    /// update's (see `keep_within_reach`).
    hips: Vec<V3>,
    reacted_rotation: Option<Mat3A>,
    /// Each planted leg's stray from its anchor and the reach in that direction, this update
    /// (step 2 of `action`, for step 4).
    strayed: Vec<(f32, f32)>,
    /// Each leg's arctangents of the reaction, this update (see `foot_angles`).
    angles: Vec<f32>,
    /// The options' centre of mass (see `transform_a`).
    centre_of_mass: Vec3A,
}

impl Controller {
    /// Places every foot on the ground under its rest position, ends all steps, puts chains
    /// at rest and clears the reaction and the head: a fresh start at `pose`.
    ///
    /// # Errors
    /// As [`update`](Self::update) for a bad pose.
    pub fn reset<G: Ground + ?Sized>(&mut self, pose: Pose, ground: &G) -> Result<(), GaitError> {
        let pose = validate_pose(pose)?;
        self.pose = pose;
        let rotation = Mat3A::from_quat(pose.rotation);
        for i in 0..self.legs.len() {
            let leg = self.legs[i];
            let rest_world = rotation * leg.rest + pose.translation;
            self.rest_world[i] = rest_world;
            let (anchor, normal, grounded) = cast_anchor(&leg, rest_world, &self.options, ground);
            let state = &mut self.states[i];
            *state = LegState::new(anchor);
            state.anchor = anchor;
            state.prev_anchor = anchor;
            state.normal = normal;
            state.grounded = grounded;
            state.planted = grounded || leg.kind == LimbKind::Arm;
            state.prev_planted = state.planted;
        }
        for i in 0..self.chains.len() {
            self.reset_chain(i);
        }
        self.reaction = BodyReaction::NEUTRAL;
        self.hop_heights.fill(0.0);
        self.hop_rise = 0.0;
        self.hop_lifts.fill(0.0);
        self.look_cache = None;
        self.look = Look {
            rotation: Quat::IDENTITY,
            target: pose.transform_point(self.head + Vec3::Z * self.mean_size * 2.0),
            yaw: 0.0,
            pitch: 0.0,
        };
        // A fresh start takes the gait (and groups) of a controller just built.
        let rest = self.rest_gait();
        if self.gait != rest {
            self.change_gait(rest);
        }
        self.wanted_gait = rest;
        self.active_group = 0;
        self.turn_taken = false;
        self.initialized = true;
        self.gather_feet();
        self.solve_joints();
        self.metrics = GaitMetrics::default();
        Ok(())
    }

    /// Advances the controller by `dt` seconds (fixed or variable; 0 is allowed) with the body
    /// at `pose`, moving at `velocity` (world, m/s) and turning at `angular_velocity` (world,
    /// rad/s), over `ground`. The same sequence of inputs gives the same state, bit for bit.
    ///
    /// Per leg: a ray is cast down from above the rest position; a planted foot that strays
    /// beyond its reach (or turns too far from its rest direction) steps, if its group has the
    /// turn and its opposite is planted, or at once past the escape distance; a stepping foot
    /// progresses with the motion of its rest position (or the fixed settle rate, whichever is
    /// faster) toward a target kept ahead of the rest position along the motion. Then the
    /// body's reaction, the head's look-at, the chains and the leg IK are updated.
    ///
    /// # Errors
    /// [`GaitError::NonFinite`] for a non-finite `dt`, pose, velocity or angular velocity,
    /// [`GaitError::NegativeTimeStep`], [`GaitError::OutOfRange`] beyond [`MAX_TIME_STEP`],
    /// [`MAX_COORDINATE`], [`MAX_SPEED`] or [`MAX_ANGULAR_SPEED`], and
    /// [`GaitError::ZeroVector`] for a zero rotation quaternion. On error nothing changes.
    pub fn update<G: Ground + ?Sized>(
        &mut self,
        dt: f32,
        pose: Pose,
        velocity: Vec3,
        angular_velocity: Vec3,
        ground: &G,
    ) -> Result<(), GaitError> {
        self.advance(dt, pose, velocity, angular_velocity, ground, true)
    }

    /// [`update`](Self::update) without the layers that only read out: the feet, steps and body
    /// reaction are the same, bit for bit, but the head's look-at, the chains and the legs'
    /// joints ([`LegState::joints`], and the overstretch [`metrics`](Self::metrics) measures
    /// from them) are left as they were. For a caller that only records the feet and the
    /// reacted body (a baked clip solves its legs itself): it skips a fifth of an update's
    /// work.
    ///
    /// # Errors
    /// As [`update`](Self::update).
    pub fn update_feet_and_body<G: Ground + ?Sized>(
        &mut self,
        dt: f32,
        pose: Pose,
        velocity: Vec3,
        angular_velocity: Vec3,
        ground: &G,
    ) -> Result<(), GaitError> {
        self.advance(dt, pose, velocity, angular_velocity, ground, false)
    }

    /// [`update`](Self::update), with the look-at, chains and IK only if `read_outs`.
    fn advance<G: Ground + ?Sized>(
        &mut self,
        dt: f32,
        pose: Pose,
        velocity: Vec3,
        angular_velocity: Vec3,
        ground: &G,
        read_outs: bool,
    ) -> Result<(), GaitError> {
        finite(dt, "dt", 0)?;
        if dt < 0.0 {
            return Err(GaitError::NegativeTimeStep { dt });
        }
        in_range(dt, "dt", 0.0, MAX_TIME_STEP)?;
        let pose = validate_pose(pose)?;
        finite3(velocity, "velocity", 0)?;
        finite3(angular_velocity, "angular velocity", 0)?;
        // A squared length within the squared limit (exact: 1e8 and 1e6 are floats) has a
        // length within the limit, so the square root is only taken to report an error.
        if !(velocity.length_squared() <= MAX_SPEED * MAX_SPEED) {
            in_range(velocity.norm(), "speed", 0.0, MAX_SPEED)?;
        }
        if !(angular_velocity.length_squared() <= MAX_ANGULAR_SPEED * MAX_ANGULAR_SPEED) {
            in_range(
                angular_velocity.norm(),
                "angular speed",
                0.0,
                MAX_ANGULAR_SPEED,
            )?;
        }
        if !self.initialized {
            self.reset(pose, ground)?;
        }
        self.pose = pose;

        // Blend ramp.
        if self.blend_rate > 0.0 {
            let step = self.blend_rate * dt;
            if abs(self.blend_target - self.blend) <= step {
                self.blend = self.blend_target;
                self.blend_rate = 0.0;
            } else if self.blend_target > self.blend {
                self.blend += step;
            } else {
                self.blend -= step;
            }
        }
        self.idle_phase += dt * self.options.breathe_rate;
        self.idle_phase -= floor_non_negative(self.idle_phase);
        if dt != self.smoothing_dt {
            self.smoothing_dt = dt;
            self.react_k = smoothing(dt, self.options.reaction_time);
            self.look_k = smoothing(dt, self.options.look_time);
        }

        // The pose's rotation as a matrix, for the action and the reaction.
        let rotation = Mat3A::from_quat(pose.rotation);
        // On WebAssembly, one action for every kind of ground (its queries through a vtable),
        // not a copy per kind: each copy is about 15 KB of the module. The same arithmetic
        // either way.
        #[cfg(target_arch = "wasm32")]
        let ground: &dyn Ground = &ground;
        self.action(dt, &pose, &rotation, velocity, angular_velocity, ground);
        self.gather_feet();
        self.react(&pose, &rotation);
        self.keep_within_reach(&pose);
        if self.keep_swings_on_their_sides(&pose) {
            self.gather_feet();
        }
        if !read_outs {
            // The hips `keep_within_reach` kept are this update's only (as `solve_joints`
            // would have taken them).
            self.reacted_rotation = None;
            return Ok(());
        }
        self.intend(&pose, angular_velocity);
        for i in 0..self.chains.len() {
            self.follow(i, dt, &pose, angular_velocity);
        }
        self.solve_joints();
        Ok(())
    }
}

/// `pose.transform_point(point)`, bit for bit, for a point kept as a `Vec3A`. Rotating a
/// `Vec3` field by a quaternion loads it with the four bytes after it as the unused fourth
/// lane, and when those are a denormal as a float, every SIMD multiplication of the rotation
/// takes a microcode assist: 13 % of an update's time for the look-at's target alone. A
/// `Vec3A` in memory has its own, defined, fourth lane.
#[inline]
fn transform_a(pose: &Pose, point: Vec3A) -> Vec3 {
    Vec3::from(pose.rotation * point) + pose.translation
}

/// `v` without its vertical component.
#[inline]
fn horizontal(v: Vec3) -> Vec3 {
    Vec3::new(v.x, 0.0, v.z)
}

fn validate_pose(pose: Pose) -> Result<Pose, GaitError> {
    finite3(pose.translation, "pose translation", 0)?;
    if !pose.rotation.is_finite() {
        return Err(GaitError::NonFinite {
            what: "pose rotation",
            index: 0,
        });
    }
    let t = pose.translation.abs().max_element();
    in_range(t, "pose coordinate", 0.0, MAX_COORDINATE)?;
    // The square root of these two squared lengths, and only these, rounds to exactly 1
    // (that of 1 + 2⁻²³ is a hair below 1 + 2⁻²⁴): such a rotation is kept as it is, since
    // dividing by exactly 1 changes nothing.
    let len2 = pose.rotation.length_squared();
    if len2 == 1.0 || len2 == 1.0 + f32::EPSILON {
        return Ok(pose);
    }
    if len2 == f32::INFINITY {
        // Finite components whose squares overflow: scaled by the largest first, the length
        // is between 1 and 2 and the division exact enough.
        let scaled = Vec4::from(pose.rotation) / Vec4::from(pose.rotation).abs().max_element();
        let rotation = Quat::from_vec4(scaled / scaled.norm());
        return Ok(Pose::new(pose.translation, rotation));
    }
    let len = sqrt(len2);
    if !(len > 1e-6) {
        return Err(GaitError::ZeroVector {
            what: "pose rotation",
            index: 0,
        });
    }
    let rotation = if len == 1.0 {
        pose.rotation
    } else {
        pose.rotation / len
    };
    Ok(Pose::new(pose.translation, rotation))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ground::Plane;
    use crate::math::{cos, quat_yxz};

    #[test]
    fn feet_and_body_alone_are_those_of_a_full_update() {
        // A six-legged walker turning while it walks, with a leg stretched far enough that the
        // reaction is scaled back at times: every update's feet, steps, reaction and metrics
        // are the same bit for bit with or without the read-out layers.
        let legs: Vec<Leg> = [
            (0.3, 0.6),
            (-0.3, 0.6),
            (0.35, 0.0),
            (-0.35, 0.0),
            (0.3, -0.6),
        ]
        .iter()
        .map(|&(x, z)| {
            Leg::new(
                Vec3::new(x, 0.0, z),
                Vec3::new(1.3 * x, -0.8, z),
                0.45,
                0.45,
            )
        })
        .chain([Leg::new(
            Vec3::new(-0.3, 0.0, -0.6),
            Vec3::new(-0.5, -0.8, -0.7),
            0.45,
            0.45,
        )])
        .collect();
        let mut full = Controller::new(&legs, &GaitOptions::DEFAULT).unwrap();
        let mut lean = full.clone();
        let dt = 1.0 / 30.0;
        for f in 0..300 {
            let t = f as f32 * dt;
            let pose = Pose::from_yaw(Vec3::new(0.0, 0.8, 0.9 * t), 0.7 * t);
            let (velocity, spin) = (Vec3::Z * 0.9, Vec3::Y * 0.7);
            full.update(dt, pose, velocity, spin, &Plane::GROUND)
                .unwrap();
            lean.update_feet_and_body(dt, pose, velocity, spin, &Plane::GROUND)
                .unwrap();
            assert_eq!(full.reacted_pose(), lean.reacted_pose(), "frame {f}");
            assert_eq!(full.body(), lean.body(), "frame {f}");
            let (a, b) = (full.metrics(), lean.metrics());
            assert_eq!(
                (
                    a.steps_started,
                    a.escapes_started,
                    a.max_skate,
                    a.legs_in_air
                ),
                (
                    b.steps_started,
                    b.escapes_started,
                    b.max_skate,
                    b.legs_in_air
                ),
                "frame {f}"
            );
            for (a, b) in full.leg_states().iter().zip(lean.leg_states()) {
                assert_eq!(
                    (
                        a.foot, a.planted, a.stepping, a.progress, a.steps, a.escapes
                    ),
                    (
                        b.foot, b.planted, b.stepping, b.progress, b.steps, b.escapes
                    ),
                    "frame {f}"
                );
            }
        }
        assert!(full.leg_states().iter().all(|l| l.steps > 2));
    }

    #[test]
    fn validate_pose_skips_exactly_the_square_roots_that_are_one() {
        // The two squared lengths `validate_pose` keeps without a square root are those, among
        // their neighbours, whose square root is exactly 1.
        let kept = |x: f32| x == 1.0 || x == 1.0 + f32::EPSILON;
        let mut x = f32::from_bits(1.0f32.to_bits() - 200);
        for _ in 0..400 {
            assert_eq!(sqrt(x) == 1.0, kept(x), "{x}");
            x = f32::from_bits(x.to_bits() + 1);
        }
        // And such a rotation is kept as it is, others divided by their length.
        let q = Quat::from_xyzw(0.0, 0.6, 0.0, 0.8);
        assert!(kept(q.length_squared()));
        assert_eq!(validate_pose(Pose::new(Vec3::ZERO, q)).unwrap().rotation, q);
        let q = Quat::from_xyzw(0.6, 0.0, 0.0, 0.8000002);
        let v = validate_pose(Pose::new(Vec3::ZERO, q)).unwrap().rotation;
        assert_eq!(v, q / q.length());
    }

    #[test]
    fn transform_a_is_transform_point() {
        for k in 0..200 {
            let a = k as f32 * 0.37;
            let pose = Pose::new(
                Vec3::new(3.0 * cos(a), 0.5 * a, -2.0),
                quat_yxz(a, 0.3 * cos(2.0 * a), -0.2 * a),
            );
            let p = Vec3::new(0.7 * a - 5.0, cos(3.0 * a), 0.01 * k as f32);
            let (a, b) = (transform_a(&pose, Vec3A::from(p)), pose.transform_point(p));
            assert_eq!(
                a.to_array().map(f32::to_bits),
                b.to_array().map(f32::to_bits)
            );
        }
    }
}
