//! The [`Controller`]: per-leg stepping state and the five layers (action, sequencing,
//! reaction, intent, follow-through), updated together.

use alloc::vec::Vec;

use glam::{BVec4A, Mat3A, Quat, Vec2, Vec3, Vec3A, Vec4};

use crate::error::{GaitError, finite, finite3, in_range};
use crate::ground::Ground;
use crate::ik::{Lanes, SPARE, TwoBone, V3, solve_lanes, solve_two_bone};
use crate::leg::{Chain, Layout, Leg, LimbKind, Pose, layout};
use crate::math::{
    abs, atan2, atan2_lanes, ceil, clamp_sym, cos, floor_non_negative, quat_yxz, quat_yxz_sin_cos,
    sin_cos_lanes, sin_turns, sin_turns_arg, smoothing, sqrt,
};
use crate::metrics::{GaitMetrics, support_margin};
use crate::options::GaitOptions;

/// Largest accepted coordinate of the body's position, metres.
pub const MAX_COORDINATE: f32 = 1.0e6;
/// Largest accepted linear speed, metres per second.
pub const MAX_SPEED: f32 = 1.0e4;
/// Largest accepted angular speed, radians per second.
pub const MAX_ANGULAR_SPEED: f32 = 1.0e3;
/// Largest accepted time step, seconds.
pub const MAX_TIME_STEP: f32 = 1.0e3;

/// Chains are integrated in sub-steps of at most this many seconds…
const CHAIN_SUBSTEP: f32 = 1.0 / 120.0;
/// …and at most this many sub-steps per update (longer updates are simulated as this long).
const MAX_CHAIN_SUBSTEPS: u32 = 64;

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

#[derive(Debug, Clone, PartialEq)]
struct ChainState {
    positions: Vec<Vec3>,
    velocities: Vec<Vec3>,
    output: Vec<Vec3>,
    /// The rest joints of the current update (reused storage: no allocation per update).
    rest: Vec<Vec3>,
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
    swing_fraction: f32,
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

/// Up to four legs' hips, poles and segment lengths, one per SIMD lane; missing lanes repeat
/// the first leg.
#[derive(Debug, Clone, Copy, PartialEq)]
struct LegLanes {
    hip: V3,
    rest: V3,
    pole: V3,
    upper: Vec4,
    lower: Vec4,
    /// The square of each leg's reach (`upper + lower`), infinite for arms: no foot is out of
    /// an arm's reach (see `keep_within_reach`).
    reach2: Vec4,
}

impl LegLanes {
    fn new(legs: &[Leg]) -> Self {
        let leg = |k: usize| legs.get(k).or(legs.first()).copied();
        let lanes = [leg(0), leg(1), leg(2), leg(3)];
        let get = |f: fn(&Leg) -> Vec3| lanes.map(|l| l.as_ref().map_or(Vec3::ZERO, f));
        let len = |f: fn(&Leg) -> f32| {
            let [a, b, c, d] = lanes.map(|l| l.as_ref().map_or(0.0, f));
            Vec4::new(a, b, c, d)
        };
        Self {
            hip: V3::gather(get(|l| l.hip)),
            rest: V3::gather(get(|l| l.rest)),
            pole: V3::gather(get(|l| l.pole)),
            upper: len(|l| l.upper),
            lower: len(|l| l.lower),
            reach2: len(|l| match l.kind {
                LimbKind::Leg => (l.upper + l.lower) * (l.upper + l.lower),
                LimbKind::Arm => f32::INFINITY,
            }),
        }
    }
}

/// A leg's hip roll (see `Controller::react`): none without a partner, else its own angle
/// from the height difference to partner `j` over the lever, or the opposite of the partner's
/// angle when the partner comes first with the same lever (one arctangent per pair).
#[derive(Debug, Clone, Copy, PartialEq)]
enum HipPair {
    None,
    Own(usize, f32),
    Mirror(usize),
}

/// How much higher a foot stands above its rest height than partner `j`'s.
#[inline(always)]
fn hip_rise(
    state: &LegState,
    rest_world: &Vec3,
    states: &[LegState],
    rests: &[Vec3],
    j: usize,
) -> f32 {
    let da = state.foot.y - rest_world.y;
    let db = match (states.get(j), rests.get(j)) {
        (Some(s), Some(r)) => s.foot.y - r.y,
        _ => 0.0,
    };
    da - db
}

/// Bisection steps of [`Controller::keep_within_reach`]: the reaction kept is within 2⁻¹⁰ of
/// the most that keeps every planted foot in reach.
const REACH_BISECTIONS: u32 = 10;
const WANT: u8 = 1;
const ESCAPE: u8 = 2;

impl Controller {
    /// A controller for `legs` (any number ≥ 1, arms included) with `options`. The feet are
    /// placed on the ground at the first [`update`](Self::update) (or by
    /// [`reset`](Self::reset)). A body without legs takes [`chains_only`](Self::chains_only).
    ///
    /// # Errors
    /// [`GaitError::NoLegs`], the first leg's error from [`Leg::validate`],
    /// [`GaitError::MixedGroups`], or the options' error from [`GaitOptions::validate`].
    pub fn new(legs: &[Leg], options: &GaitOptions) -> Result<Self, GaitError> {
        if legs.is_empty() {
            return Err(GaitError::NoLegs);
        }
        for (i, leg) in legs.iter().enumerate() {
            leg.validate(i)?;
        }
        let mean_size = legs.iter().map(|l| l.size).sum::<f32>() / legs.len() as f32;
        Self::build(legs, mean_size, options)
    }

    /// A controller without legs, for bodies that fly or swim: it drives follow-through
    /// [`Chain`]s (dangling legs, tails, fins: add them with [`add_chain`](Self::add_chain)),
    /// breathing and the head's look-at, with no stepping and no body reaction to feet.
    /// `size` (metres) stands in for the mean leg size of [`new`](Self::new): it scales the
    /// breathing amplitude and the look-at distance.
    ///
    /// ```
    /// use creature_gait::glam::Vec3;
    /// use creature_gait::{Chain, Controller, GaitOptions, Plane, Pose};
    ///
    /// // A hovering body with one dangling leg: gravity pulls it down, it swings behind when
    /// // the body flies forward.
    /// let mut c = Controller::chains_only(0.5, &GaitOptions::DEFAULT)?;
    /// let leg = c.add_chain(Chain::new(Vec3::new(0.1, 0.0, 0.0), Vec3::NEG_Y, 2, 0.2).with_gravity(9.81))?;
    /// let ground = Plane::horizontal(-10.0);
    /// for i in 0..60 {
    ///     let t = i as f32 / 30.0;
    ///     c.update(1.0 / 30.0, Pose::from_yaw(Vec3::Z * (2.0 * t), 0.0), Vec3::Z * 2.0, Vec3::ZERO, &ground)?;
    /// }
    /// let joints = c.chain(leg)?;
    /// assert_eq!(joints.len(), 3);
    /// // The tip trails behind its root.
    /// assert!(joints[2].z < joints[0].z);
    /// # Ok::<(), creature_gait::GaitError>(())
    /// ```
    ///
    /// # Errors
    /// [`GaitError::NonFinite`] or [`GaitError::NotPositive`] for `size`, or the options' error
    /// from [`GaitOptions::validate`].
    pub fn chains_only(size: f32, options: &GaitOptions) -> Result<Self, GaitError> {
        finite(size, "size", 0)?;
        if !(size > 0.0) {
            return Err(GaitError::NotPositive {
                what: "size",
                index: 0,
                value: size,
            });
        }
        Self::build(&[], size, options)
    }

    fn build(legs: &[Leg], mean_size: f32, options: &GaitOptions) -> Result<Self, GaitError> {
        options.validate()?;
        let layout = layout(legs)?;
        let swing_fraction = 1.0 / f32::from(layout.group_count.max(2));
        // Each leg's hip-roll lever: the hips' X distance to its partner (or a floor).
        let hip_width: Vec<f32> = legs
            .iter()
            .enumerate()
            .map(|(i, a)| match layout.partner[i].and_then(|j| legs.get(j)) {
                Some(b) => abs(a.hip.x - b.hip.x).max(1e-3 * a.size),
                None => 0.0,
            })
            .collect();
        let hip_pairs = (0..legs.len())
            .map(|i| match layout.partner[i] {
                Some(j) if j < i && hip_width.get(j) == hip_width.get(i) => HipPair::Mirror(j),
                Some(j) => HipPair::Own(j, hip_width.get(i).copied().unwrap_or(0.0)),
                None => HipPair::None,
            })
            .collect();
        Ok(Self {
            legs: legs.to_vec(),
            options: *options,
            layout,
            states: legs.iter().map(|l| LegState::new(l.rest)).collect(),
            chains: Vec::new(),
            chain_states: Vec::new(),
            initialized: false,
            active_group: 0,
            turn_taken: false,
            mean_size,
            swing_fraction,
            pose: Pose::IDENTITY,
            reaction: BodyReaction::NEUTRAL,
            look: Look {
                rotation: Quat::IDENTITY,
                target: Vec3::Z,
                yaw: 0.0,
                pitch: 0.0,
            },
            look_target: None,
            head: Vec3::ZERO,
            idle_phase: 0.0,
            blend: 1.0,
            blend_target: 1.0,
            blend_rate: 0.0,
            metrics: GaitMetrics::default(),
            wants: alloc::vec![0; legs.len()],
            motion: alloc::vec![Vec3::ZERO; legs.len()],
            rest_world: legs.iter().map(|l| l.rest).collect(),
            hip_pairs,
            has_arms: legs.iter().any(|l| l.kind == LimbKind::Arm),
            cos_turn: cos(options.max_turn_angle),
            smoothing_dt: -1.0,
            react_k: 0.0,
            look_k: 0.0,
            look_cache: None,
            leg_lanes: legs.chunks(4).map(LegLanes::new).collect(),
            angles: alloc::vec![0.0; legs.len()],
            strayed: alloc::vec![(0.0, 0.0); legs.len()],
            hips: legs.chunks(4).map(|l| LegLanes::new(l).hip).collect(),
            feet: legs.chunks(4).map(|l| LegLanes::new(l).rest).collect(),
            reacted_rotation: None,
            centre_of_mass: Vec3A::from(options.centre_of_mass),
        })
    }

    /// Adds a follow-through chain (tail, fin, wing trailing bones, dangling leg) and returns
    /// its index. Its joints start at rest at the next update.
    ///
    /// # Errors
    /// The chain's error from [`Chain::validate`].
    pub fn add_chain(&mut self, chain: Chain) -> Result<usize, GaitError> {
        chain.validate(self.chains.len())?;
        let mut rest = Vec::with_capacity(chain.segments + 1);
        chain_rest(&chain, &self.pose, 0.0, &mut rest);
        self.chains.push(chain);
        self.chain_states.push(ChainState {
            velocities: alloc::vec![Vec3::ZERO; rest.len()],
            output: rest.clone(),
            positions: rest.clone(),
            rest,
        });
        if self.initialized {
            // Start the new chain at rest on the current pose.
            let i = self.chains.len() - 1;
            self.reset_chain(i);
        }
        Ok(self.chains.len() - 1)
    }

    /// Sets the head's position in body space (the look-at's origin). Default zero.
    ///
    /// # Errors
    /// [`GaitError::NonFinite`] for a non-finite position.
    pub fn set_head(&mut self, head: Vec3) -> Result<(), GaitError> {
        finite3(head, "head", 0)?;
        self.head = head;
        self.look_cache = None;
        Ok(())
    }

    /// Makes the head look at a world point (`Some`) or where the body turns (`None`,
    /// default). The gaze is smoothed and limited by the options either way.
    ///
    /// # Errors
    /// [`GaitError::NonFinite`] for a non-finite point.
    pub fn set_look_target(&mut self, target: Option<Vec3>) -> Result<(), GaitError> {
        if let Some(t) = target {
            finite3(t, "look target", 0)?;
        }
        self.look_target = target;
        Ok(())
    }

    /// Sets the procedural layer's blend weight at once: 1 (default) is fully procedural,
    /// 0 is the plain rest pose (feet at their rest positions, no reaction, head forward,
    /// chains rigid), ready for an authored animation to take over.
    ///
    /// # Errors
    /// [`GaitError::OutOfRange`] outside `[0, 1]`.
    pub fn set_blend(&mut self, weight: f32) -> Result<(), GaitError> {
        in_range(weight, "blend weight", 0.0, 1.0)?;
        self.blend = weight;
        self.blend_target = weight;
        self.blend_rate = 0.0;
        Ok(())
    }

    /// Ramps the blend weight toward `weight` over the following updates, at the rate of
    /// [`GaitOptions::blend_time`] for a full 0 → 1 change (instantly when that is 0).
    ///
    /// # Errors
    /// [`GaitError::OutOfRange`] outside `[0, 1]`.
    pub fn blend_to(&mut self, weight: f32) -> Result<(), GaitError> {
        in_range(weight, "blend weight", 0.0, 1.0)?;
        self.blend_target = weight;
        if self.options.blend_time <= 0.0 {
            self.blend = weight;
            self.blend_rate = 0.0;
        } else {
            self.blend_rate = 1.0 / self.options.blend_time;
        }
        Ok(())
    }

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
        self.look_cache = None;
        self.look = Look {
            rotation: Quat::IDENTITY,
            target: pose.transform_point(self.head + Vec3::Z * self.mean_size * 2.0),
            yaw: 0.0,
            pitch: 0.0,
        };
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
            in_range(velocity.length(), "speed", 0.0, MAX_SPEED)?;
        }
        if !(angular_velocity.length_squared() <= MAX_ANGULAR_SPEED * MAX_ANGULAR_SPEED) {
            in_range(
                angular_velocity.length(),
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
        self.action(dt, &pose, &rotation, velocity, angular_velocity, ground);
        self.gather_feet();
        self.react(&pose, &rotation);
        self.keep_within_reach(&pose);
        self.intend(&pose, angular_velocity);
        for i in 0..self.chains.len() {
            self.follow(i, dt, &pose, angular_velocity);
        }
        self.solve_joints();
        Ok(())
    }

    // ----- action: stepping -------------------------------------------------------------------

    fn action<G: Ground + ?Sized>(
        &mut self,
        dt: f32,
        pose: &Pose,
        rotation: &Mat3A,
        velocity: Vec3,
        angular_velocity: Vec3,
        ground: &G,
    ) {
        let o = &self.options;
        let forward = horizontal(pose.rotation * Vec3::Z)
            .try_normalize()
            .unwrap_or(Vec3::Z);
        let body = pose.translation;
        let rotation = *rotation;
        let speed_factor = o.speed_multiplier.max(1.0);
        let arm_idle = if self.has_arms {
            sin_turns(self.idle_phase)
        } else {
            0.0
        };

        // Is the body still? (Every rest position slower than the threshold.)
        let still_limit = o.still_speed * self.mean_size;
        let mut still = true;

        // 1. Anchors, and progress of the steps under way.
        let mut steps_started = 0usize;
        let mut escapes_started = 0usize;
        for (i, leg) in self.legs.iter().enumerate() {
            let rest_world = rotation * leg.rest + body;
            // `cast_anchor` without the normal, which only a step whose target stays at the
            // anchor uses: it is cast again then (`anchor_normal`).
            let (anchor, grounded) = if leg.kind == LimbKind::Arm {
                (rest_world, true)
            } else {
                let (origin, max_distance) = down_ray(rest_world, leg.size, o);
                match ground.cast_down_point(origin, max_distance) {
                    Some(point) => (point, true),
                    None => (rest_world, false),
                }
            };
            let anchor_normal =
                || cast_down(ground, rest_world, leg.size, o).map_or(Vec3::Y, |(_, n)| n);
            let motion = horizontal(velocity + angular_velocity.cross(rest_world - body));
            if still && motion.length() > still_limit {
                still = false;
            }
            let (Some(state), Some(rest_slot), Some(motion_slot), Some(want)) = (
                self.states.get_mut(i),
                self.rest_world.get_mut(i),
                self.motion.get_mut(i),
                self.wants.get_mut(i),
            ) else {
                continue;
            };
            *rest_slot = rest_world;
            *motion_slot = motion;
            state.prev_foot = state.foot;
            state.prev_planted = state.planted;
            state.prev_anchor = state.anchor;
            state.anchor = anchor;
            let was_grounded = state.grounded;
            state.grounded = grounded;
            if leg.kind == LimbKind::Leg && !grounded {
                // Nothing under the leg: it dangles at its rest position.
                state.foot = anchor;
                state.normal = Vec3::Y;
                state.stepping = false;
                state.planted = false;
                state.progress = 1.0;
                continue;
            }
            if state.stepping {
                let (target, target_normal) = step_target(
                    leg,
                    o,
                    anchor,
                    anchor_normal,
                    motion,
                    forward,
                    rest_world.y,
                    ground,
                );
                state.step_target = target;
                let moved = horizontal(anchor - state.prev_anchor).length();
                let by_motion = moved / state.swing_length.max(1e-6);
                state.progress = (state.progress + by_motion.max(o.settle_rate * dt)).min(1.0);
                if state.progress >= 1.0 {
                    state.foot = target;
                    state.normal = target_normal;
                    state.stepping = false;
                    state.escaping = false;
                    state.planted = true;
                } else {
                    let lift = o.height_curve.evaluate(state.progress) * state.lift;
                    state.foot = state.step_start.lerp(target, state.progress) + Vec3::Y * lift;
                    state.normal = target_normal;
                }
            } else if leg.kind == LimbKind::Arm {
                // Arms hold their place in XZ and follow the body's height, idling gently.
                state.foot.y = anchor.y + arm_idle * o.arm_idle_amplitude * leg.size;
            } else if !was_grounded {
                // Ground came back under a dangling leg: force a step onto it.
                *want = WANT | ESCAPE;
                continue;
            }
            *want = 0;
        }

        // 2. Which planted legs want to step.
        for ((((leg, state), want), motion), strayed) in self
            .legs
            .iter()
            .zip(&self.states)
            .zip(&mut self.wants)
            .zip(&self.motion)
            .zip(&mut self.strayed)
        {
            if state.stepping || (leg.kind == LimbKind::Leg && !state.grounded) {
                *want = 0;
                continue;
            }
            if *want != 0 {
                continue; // forced above
            }
            let stray = horizontal(state.foot - state.anchor);
            let distance = stray.length();
            let d = if distance > 1e-9 {
                stray.dot(forward) / distance
            } else {
                0.0
            };
            let reach_here = o.reach.evaluate(d);
            *strayed = (distance, reach_here);
            let allowed = reach_here * leg.size;
            let mut flags = if distance > allowed { WANT } else { 0 };
            // Turning (in place): the foot's direction from the body has turned too far from the
            // rest direction. Only for a foot that trails its rest position's motion: one that
            // landed ahead (at the overshoot) is left to the reach, or it would step again at
            // once. |atan2(cross, dot)| > max_turn_angle ⟺
            // dot < cos(max_turn_angle) · |(cross, dot)|, without the arctangent.
            if flags == 0 && distance > 0.1 * allowed && stray.dot(*motion) < 0.0 {
                let from_body = horizontal(state.foot - body);
                let rest_dir = horizontal(state.anchor - body);
                let tiny = 1e-6 * leg.size * leg.size;
                if from_body.length_squared() > tiny && rest_dir.length_squared() > tiny {
                    let cross = from_body.cross(rest_dir).y;
                    let dot = from_body.dot(rest_dir);
                    if dot < self.cos_turn * sqrt(cross * cross + dot * dot) {
                        flags = WANT;
                    }
                }
            }
            if flags == 0 && still && distance > o.settle_distance * leg.size {
                flags = WANT;
            }
            if distance > o.escape_factor * allowed {
                flags |= ESCAPE;
            }
            // Out of the leg's reach (the body moved on while the foot waited for its group,
            // e.g. the outer legs of a long body turning in place): step now, out of turn,
            // rather than overstretch.
            let reach = leg.upper + leg.lower;
            if leg.kind == LimbKind::Leg
                && state.foot.distance_squared(rotation * leg.hip + body) > reach * reach
            {
                flags |= WANT | ESCAPE;
            }
            *want = flags;
        }

        // 3. Sequencing: the active group keeps the turn while any of its legs steps. One pass
        //    finds what step 4 needs of the group that then has the turn, this one or the next.
        //    (Plain boolean arithmetic, no branches: which legs step and want to varies too
        //    much to predict.)
        let count = self.layout.group_count.max(1);
        let active = self.active_group;
        let next = (active + 1) % count;
        let (mut group_stepping, mut group_wants, mut next_moves) = (false, false, false);
        for (((leg, state), want), group) in self
            .legs
            .iter()
            .zip(&self.states)
            .zip(&self.wants)
            .zip(&self.layout.groups)
        {
            let sequenced = leg.kind == LimbKind::Leg;
            let wants = want & WANT != 0;
            group_stepping |= sequenced & (*group == active) & state.stepping;
            group_wants |= sequenced & (*group == active) & wants;
            next_moves |= sequenced & (*group == next) & (state.stepping | wants);
        }
        let advance = !group_stepping && (self.turn_taken || !group_wants);
        if advance {
            self.active_group = next;
            self.turn_taken = false;
        }
        let active = self.active_group;

        // 4. Start the steps that are allowed. Once the active group moves, its other legs that
        //    trail behind their rest position by more than `group_join` of their reach join it,
        //    so a group steps together instead of leaving a leg to wait a whole cycle. Feet
        //    that are ahead (just landed) never join: they would step again at once.
        let group_moves = if advance {
            next_moves
        } else {
            group_stepping | group_wants
        };
        if group_moves {
            for (((((leg, state), want), group), motion), &(distance, reach_here)) in self
                .legs
                .iter()
                .zip(&self.states)
                .zip(&mut self.wants)
                .zip(&self.layout.groups)
                .zip(&self.motion)
                .zip(&self.strayed)
            {
                let idle = (leg.kind == LimbKind::Leg)
                    & (*group == active)
                    & !state.stepping
                    & state.grounded
                    & (*want == 0);
                let stray = horizontal(state.foot - state.anchor);
                let trailing = stray.dot(*motion) < 0.0;
                // The stray's length and the reach in its direction, as step 2 found them
                // (every idle leg went through it, and no foot has moved since).
                let far = distance > o.group_join * reach_here * leg.size;
                if idle & trailing & far {
                    *want = WANT;
                }
            }
        }
        for i in 0..self.legs.len() {
            let flags = self.wants[i];
            if flags == 0 {
                continue;
            }
            let leg = &self.legs[i];
            let sequenced = leg.kind == LimbKind::Leg;
            let opposite_busy = self.layout.opposite[i]
                .and_then(|j| self.states.get(j))
                .is_some_and(|s| s.stepping);
            let in_turn = !sequenced || (self.layout.groups[i] == active && !opposite_busy);
            let escape = sequenced && !in_turn && flags & ESCAPE != 0;
            if !(escape || (flags & WANT != 0 && in_turn)) {
                continue;
            }
            let state = &mut self.states[i];
            let normal = state.normal;
            let (target, target_normal) = step_target(
                leg,
                o,
                state.anchor,
                || normal,
                self.motion[i],
                forward,
                self.rest_world[i].y,
                ground,
            );
            state.stepping = true;
            state.planted = false;
            state.escaping = escape;
            state.progress = 0.0;
            state.step_start = state.foot;
            state.step_target = target;
            state.normal = target_normal;
            state.lift = o.step_height * leg.size * speed_factor;
            state.swing_length = horizontal(target - state.foot)
                .length()
                .max(0.05 * leg.size)
                * self.swing_fraction;
            state.steps = state.steps.saturating_add(1);
            if sequenced {
                steps_started += 1;
                if escape {
                    state.escapes = state.escapes.saturating_add(1);
                    escapes_started += 1;
                } else {
                    self.turn_taken = true;
                }
            }
        }
        self.metrics.steps_started = steps_started;
        self.metrics.escapes_started = escapes_started;
    }

    // ----- reaction ---------------------------------------------------------------------------

    fn react(&mut self, pose: &Pose, rotation: &Mat3A) {
        self.foot_angles(pose, rotation);
        let o = &self.options;
        // Bob: the feet's mean height offset from rest. Sway: their mean top-view angle offset
        // about the body's origin (Trifox). Pitch and roll: the slopes of the height offsets
        // along the body's forward and left axes (a least-squares fit), so the body leans with
        // lifted feet and with the ground, without a bias from feet trailing behind.
        let mut count = 0usize;
        let (mut height, mut yaw) = (0.0f32, 0.0f32);
        let (mut ez, mut zz, mut ex, mut xx) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
        let mut centre = Vec2::ZERO;
        for (leg, state) in self.legs.iter().zip(&self.states) {
            if leg.kind == LimbKind::Leg && state.grounded {
                count += 1;
                centre += Vec2::new(leg.rest.x, leg.rest.z);
            }
        }
        if count > 0 {
            centre /= count as f32;
        }
        for (((leg, state), rest_world), angles) in self
            .legs
            .iter()
            .zip(&self.states)
            .zip(&self.rest_world)
            .zip(&self.angles)
        {
            if leg.kind != LimbKind::Leg || !state.grounded {
                continue;
            }
            let e = state.foot.y - rest_world.y;
            height += e;
            yaw += angles;
            let rest = leg.rest;
            let (x, z) = (rest.x - centre.x, rest.z - centre.y);
            ex += e * x;
            xx += x * x;
            ez += e * z;
            zz += z * z;
        }
        let slope = |num: f32, den: f32| if den > 1e-12 { atan2(num, den) } else { 0.0 };
        let (pitch, roll) = (-slope(ez, zz), slope(ex, xx));
        let k = self.react_k;
        let r = &mut self.reaction;
        let (bob_t, yaw_t, pitch_t, roll_t) = if count == 0 {
            (0.0, 0.0, 0.0, 0.0)
        } else {
            let n = count as f32;
            let bob_limit = o.bob_limit * self.mean_size;
            (
                clamp_sym(o.bob_gain * height / n, bob_limit),
                clamp_sym(o.sway_gain * yaw / n, o.sway_limit),
                clamp_sym(o.sway_gain * pitch, o.sway_limit),
                clamp_sym(o.sway_gain * roll, o.sway_limit),
            )
        };
        r.bob = clamp_sym(r.bob + (bob_t - r.bob) * k, o.bob_limit * self.mean_size);
        r.yaw = clamp_sym(r.yaw + (yaw_t - r.yaw) * k, o.sway_limit);
        r.pitch = clamp_sym(r.pitch + (pitch_t - r.pitch) * k, o.sway_limit);
        r.roll = clamp_sym(r.roll + (roll_t - r.roll) * k, o.sway_limit);
        let w = self.blend;
        // The breathing's sine and the rotation's three half-angle sines and cosines, four
        // lanes at once (`sin_turns` and `quat_yxz` bit for bit).
        let (sign, turn) = sin_turns_arg(self.idle_phase);
        let (s, c) = sin_cos_lanes(Vec4::new(
            0.5 * (r.yaw * w),
            0.5 * (r.pitch * w),
            0.5 * (r.roll * w),
            turn,
        ));
        let breathe = o.breathe_amplitude * self.mean_size * (sign * s.w);
        r.offset = Vec3::Y * ((r.bob + breathe) * w);
        r.rotation = quat_yxz_sin_cos(s, c);

        // Hip roll: the height difference between a foot and its partner (3D seed). A pair
        // with the same lever rolls by opposite angles: one arctangent per pair.
        for i in 0..self.legs.len() {
            let (Some(pair), Some(state)) = (self.hip_pairs.get(i), self.states.get(i)) else {
                continue;
            };
            let roll = match *pair {
                HipPair::Own(j, width)
                    if state.grounded && self.states.get(j).is_some_and(|s| s.grounded) =>
                {
                    let rise = hip_rise(
                        state,
                        &self.rest_world[i],
                        &self.states,
                        &self.rest_world,
                        j,
                    );
                    clamp_sym(o.hip_roll_gain * atan2(rise, width), o.hip_roll_limit)
                }
                HipPair::Mirror(j)
                    if state.grounded && self.states.get(j).is_some_and(|s| s.grounded) =>
                {
                    let mirrored = -self.states[j].hip_roll;
                    self.states[i].hip_roll = mirrored;
                    continue;
                }
                _ => 0.0,
            };
            self.states[i].hip_roll = roll * self.blend;
        }
    }

    /// Each foot's angle from its leg's rest direction, seen from above about the body's origin
    /// (measured from +Z toward +X), four legs at a time (see `atan2_lanes`); computed for every
    /// leg, used for those on the ground.
    fn foot_angles(&mut self, pose: &Pose, rotation: &Mat3A) {
        let inverse = rotation.transpose();
        let t = pose.translation;
        let t = V3 {
            x: Vec4::splat(t.x),
            y: Vec4::splat(t.y),
            z: Vec4::splat(t.z),
        };
        for ((lanes, angles), feet) in self
            .leg_lanes
            .iter()
            .zip(self.angles.chunks_mut(4))
            .zip(&self.feet)
        {
            let local = feet.sub(t).rotate(&inverse);
            let rest = lanes.rest;
            let cross = rest.z * local.x - rest.x * local.z;
            let dot = rest.z * local.z + rest.x * local.x;
            for (angle, yaw) in angles.iter_mut().zip(atan2_lanes(cross, dot).to_array()) {
                *angle = yaw;
            }
        }
    }

    /// The feet the action placed, four legs at a time (`feet`), for the reaction, the reach
    /// check and the IK; missing lanes repeat the first leg.
    fn gather_feet(&mut self) {
        for (feet, states) in self.feet.iter_mut().zip(self.states.chunks(4)) {
            *feet = V3::gather(match states {
                [a, b, c, d] => [a.foot, b.foot, c.foot, d.foot],
                [first, ..] => {
                    let foot = |k: usize| states.get(k).unwrap_or(first).foot;
                    [foot(0), foot(1), foot(2), foot(3)]
                }
                [] => continue,
            });
        }
    }

    /// Scales the body's reaction (bob, breathing, sway) back toward none, as little as needed,
    /// so that no planted foot is beyond its leg's reach from the reacted hip: on a long body a
    /// small pitch or roll moves the far hips a long way. A foot out of reach of the unreacted
    /// body already steps (see `action`).
    fn keep_within_reach(&mut self, pose: &Pose) {
        let reaction = self.reaction;
        // The reacted body's hips, four legs at a time; kept for the IK when every planted foot
        // is within reach of them (as usual), which then need not place them again.
        let rotation = Mat3A::from_quat((pose.rotation * reaction.rotation).normalize());
        let origin = pose.translation + reaction.offset;
        let mut out = false;
        for (((lanes, hips), feet), states) in self
            .leg_lanes
            .iter()
            .zip(&mut self.hips)
            .zip(&self.feet)
            .zip(self.states.chunks(4))
        {
            *hips = lanes.hip.transform(&rotation, origin);
            // Four legs at a time: `foot.distance_squared(hip) > reach²` (arms: never), for the
            // planted feet (missing lanes repeat the first leg).
            let Some(first) = states.first() else {
                continue;
            };
            let planted = |k: usize| states.get(k).unwrap_or(first).planted;
            let planted = BVec4A::new(planted(0), planted(1), planted(2), planted(3));
            let d = feet.sub(*hips);
            out |= (d.dot(d).cmpgt(lanes.reach2) & planted).any();
        }
        if !out {
            self.reacted_rotation = Some(rotation);
            return;
        }
        let out_of_reach = |offset: Vec3, rotation: Quat| {
            let rotation = Mat3A::from_quat((pose.rotation * rotation).normalize());
            let origin = pose.translation + offset;
            self.legs.iter().zip(&self.states).any(|(leg, state)| {
                let reach = leg.upper + leg.lower;
                leg.kind == LimbKind::Leg
                    && state.planted
                    && state.foot.distance_squared(rotation * leg.hip + origin) > reach * reach
            })
        };
        if !out_of_reach(reaction.offset, reaction.rotation) {
            return;
        }
        // Bisection on the share of the reaction kept: 0 (none) to 1 (all).
        let (mut low, mut high) = (0.0f32, 1.0f32);
        for _ in 0..REACH_BISECTIONS {
            let mid = 0.5 * (low + high);
            let rotation = Quat::IDENTITY.slerp(reaction.rotation, mid);
            if out_of_reach(reaction.offset * mid, rotation) {
                high = mid;
            } else {
                low = mid;
            }
        }
        self.reaction.offset = reaction.offset * low;
        self.reaction.rotation = Quat::IDENTITY.slerp(reaction.rotation, low).normalize();
    }

    // ----- intent -----------------------------------------------------------------------------

    fn intend(&mut self, pose: &Pose, angular_velocity: Vec3) {
        let o = &self.options;
        let (yaw_t, pitch_t) = match self.look_target {
            Some(target) => {
                let local = pose.inverse_transform_point(target) - self.head;
                let flat = Vec2::new(local.x, local.z).length();
                if local.length_squared() > 1e-12 {
                    (atan2(local.x, local.z), atan2(local.y, flat))
                } else {
                    (0.0, o.look_pitch)
                }
            }
            None => (angular_velocity.y * o.look_ahead, o.look_pitch),
        };
        let yaw_t = clamp_sym(yaw_t, o.look_limit);
        let pitch_t = clamp_sym(pitch_t, o.look_limit);
        let k = self.look_k;
        let look = &mut self.look;
        look.yaw = clamp_sym(look.yaw + (yaw_t - look.yaw) * k, o.look_limit);
        look.pitch = clamp_sym(look.pitch + (pitch_t - look.pitch) * k, o.look_limit);
        // A settled gaze (same angles and blend as the last update) keeps its rotation.
        let key = [
            look.yaw.to_bits(),
            look.pitch.to_bits(),
            self.blend.to_bits(),
        ];
        let local = match self.look_cache {
            Some((cached, local)) if cached == key => local,
            _ => {
                let full = quat_yxz(look.yaw, -look.pitch, 0.0);
                look.rotation = if self.blend == 1.0 {
                    full.normalize()
                } else {
                    Quat::IDENTITY.slerp(full, self.blend).normalize()
                };
                let local = Vec3A::from(self.head + full * Vec3::Z * (2.0 * self.mean_size));
                self.look_cache = Some((key, local));
                local
            }
        };
        look.target = transform_a(pose, local);
    }

    // ----- follow-through ---------------------------------------------------------------------

    fn reset_chain(&mut self, i: usize) {
        let Some(chain) = self.chains.get(i) else {
            return;
        };
        if let Some(s) = self.chain_states.get_mut(i) {
            chain_rest(chain, &self.pose, 0.0, &mut s.rest);
            s.velocities.iter_mut().for_each(|v| *v = Vec3::ZERO);
            s.output.clone_from(&s.rest);
            s.positions.clone_from(&s.rest);
        }
    }

    fn follow(&mut self, i: usize, dt: f32, pose: &Pose, angular_velocity: Vec3) {
        let (Some(chain), Some(state)) = (self.chains.get(i), self.chain_states.get_mut(i)) else {
            return;
        };
        chain_rest(
            chain,
            pose,
            angular_velocity.y * chain.turn_bend,
            &mut state.rest,
        );
        let rest = &state.rest;
        let rate = (2.0 * sqrt(chain.stiffness) + chain.damping).max(1.0 / CHAIN_SUBSTEP);
        let substeps = (ceil(dt * rate) as u32).clamp(1, MAX_CHAIN_SUBSTEPS);
        let h = (dt / substeps as f32).min(1.0 / rate);
        let len = chain.segment_length;
        if dt > 0.0 {
            for _ in 0..substeps {
                if let Some(root) = state.positions.first_mut() {
                    *root = rest[0];
                }
                for k in 1..state.positions.len() {
                    let x = state.positions[k];
                    let v = state.velocities[k];
                    let accel = (rest[k] - x) * chain.stiffness - v * chain.damping
                        + Vec3::NEG_Y * chain.gravity;
                    let v = v + accel * h;
                    let moved = x + v * h;
                    // Constant segment length: project onto the sphere around the parent.
                    let parent = state.positions[k - 1];
                    let dir = (moved - parent)
                        .try_normalize()
                        .unwrap_or_else(|| (rest[k] - rest[k - 1]).normalize_or(Vec3::NEG_Z));
                    let fixed = parent + dir * len;
                    state.velocities[k] = (fixed - x) / h;
                    state.positions[k] = fixed;
                }
            }
        } else if let Some(root) = state.positions.first_mut() {
            *root = rest[0];
            for k in 1..state.positions.len() {
                let parent = state.positions[k - 1];
                let dir = (state.positions[k] - parent).normalize_or(Vec3::NEG_Z);
                state.positions[k] = parent + dir * len;
            }
        }
        if !state.positions.iter().all(|p| p.is_finite())
            || !state.velocities.iter().all(|v| v.is_finite())
        {
            state.positions.clone_from(rest);
            state.velocities.iter_mut().for_each(|v| *v = Vec3::ZERO);
        }
        let w = self.blend;
        for (out, (p, r)) in state
            .output
            .iter_mut()
            .zip(state.positions.iter().zip(rest))
        {
            *out = r.lerp(*p, w);
        }
    }

    // ----- IK and metrics ---------------------------------------------------------------------

    fn solve_joints(&mut self) {
        let w = self.blend;
        // The hips placed by `keep_within_reach` for this update, if it kept the reaction.
        let kept = self.reacted_rotation.take();
        let (rotation, translation) = match kept {
            Some(rotation) => (rotation, Vec3::ZERO),
            None => {
                let reacted = self.reacted_pose();
                (Mat3A::from_quat(reacted.rotation), reacted.translation)
            }
        };
        // Four legs at a time, one per SIMD lane (see `solve_lanes`).
        let mut spare = [SPARE; 3];
        for ((((lanes, hips), feet), states), rest) in self
            .leg_lanes
            .iter()
            .zip(&self.hips)
            .zip(&self.feet)
            .zip(self.states.chunks_mut(4))
            .zip(self.rest_world.chunks(4))
        {
            let target = |s: &LegState, r: Option<&Vec3>| match r {
                Some(r) => r.lerp(s.foot, w),
                None => s.foot,
            };
            // Missing lanes repeat the first leg.
            let targets = match &*states {
                _ if w == 1.0 => *feet,
                [first, ..] => {
                    let lane = |k: usize| match states.get(k) {
                        Some(s) => target(s, rest.get(k)),
                        None => target(first, rest.first()),
                    };
                    V3::gather([lane(0), lane(1), lane(2), lane(3)])
                }
                [] => continue,
            };
            let problem = Lanes {
                root: if kept.is_some() {
                    *hips
                } else {
                    lanes.hip.transform(&rotation, translation)
                },
                target: targets,
                pole: lanes.pole.rotate(&rotation),
                upper: lanes.upper,
                lower: lanes.lower,
            };
            match states {
                [a, b, c, d] => solve_lanes(
                    &problem,
                    [&mut a.joints, &mut b.joints, &mut c.joints, &mut d.joints],
                ),
                _ => {
                    let mut out = states
                        .iter_mut()
                        .map(|s| &mut s.joints)
                        .chain(spare.iter_mut());
                    if let (Some(a), Some(b), Some(c), Some(d)) =
                        (out.next(), out.next(), out.next(), out.next())
                    {
                        solve_lanes(&problem, [a, b, c, d]);
                    }
                }
            }
        }
    }

    /// Skate, overstretch, legs in the air and the stability margin of the state the last
    /// update left (see [`Controller::metrics`]).
    fn measure(&self) -> GaitMetrics {
        let mut skate = 0.0f32;
        let mut over = 0.0f32;
        let mut in_air = 0usize;
        let mut support: Vec<Vec2> = Vec::with_capacity(self.legs.len());
        for (leg, state) in self.legs.iter().zip(&self.states) {
            if leg.kind != LimbKind::Leg {
                continue;
            }
            // Squared distances: the square root (monotonic) is taken of the largest only.
            if state.prev_planted && state.planted {
                skate = skate.max(state.foot.distance_squared(state.prev_foot));
            }
            if state.stepping || !state.grounded {
                in_air += 1;
            } else {
                support.push(Vec2::new(state.foot.x, state.foot.z));
                let reach = leg.length();
                let d2 = state.foot.distance_squared(state.joints.root);
                if d2 > reach * reach {
                    over = over.max(sqrt(d2) - reach);
                }
            }
        }
        let com = transform_a(&self.pose, self.centre_of_mass);
        let mut hull = Vec::with_capacity(support.len() + 1);
        GaitMetrics {
            max_skate: sqrt(skate),
            max_overstretch: over.max(0.0),
            legs_in_air: in_air,
            stability_margin: support_margin(&mut support, &mut hull, Vec2::new(com.x, com.z)),
            ..self.metrics
        }
    }
}

/// Read-outs.
impl Controller {
    /// The legs, as given.
    #[must_use]
    pub fn legs(&self) -> &[Leg] {
        &self.legs
    }

    /// The options, as given.
    #[must_use]
    pub const fn options(&self) -> &GaitOptions {
        &self.options
    }

    /// Every leg's state (foot, planted, step, joints), in the order of the legs.
    #[must_use]
    pub fn leg_states(&self) -> &[LegState] {
        &self.states
    }

    /// One leg's state.
    ///
    /// # Errors
    /// [`GaitError::IndexOutOfRange`] for a leg that does not exist.
    pub fn leg_state(&self, leg: usize) -> Result<&LegState, GaitError> {
        self.states.get(leg).ok_or(GaitError::IndexOutOfRange {
            what: "leg",
            index: leg,
            len: self.states.len(),
        })
    }

    /// Each leg's group (consecutive from 0; derived from the layout unless the legs set it;
    /// arms get 0 and are not sequenced).
    #[must_use]
    pub fn groups(&self) -> &[u8] {
        &self.layout.groups
    }

    /// How many groups take turns.
    #[must_use]
    pub const fn group_count(&self) -> u8 {
        self.layout.group_count
    }

    /// The group whose turn it is.
    #[must_use]
    pub const fn active_group(&self) -> u8 {
        self.active_group
    }

    /// The leg that must be planted before `leg` may step (the 3D seed's opposite-foot
    /// reference, derived only when groups are derived), or `None`.
    #[must_use]
    pub fn opposite(&self, leg: usize) -> Option<usize> {
        self.layout.opposite.get(leg).copied().flatten()
    }

    /// The other leg of `leg`'s left/right pair, or `None`.
    #[must_use]
    pub fn partner(&self, leg: usize) -> Option<usize> {
        self.layout.partner.get(leg).copied().flatten()
    }

    /// The body's reaction (bob and breathing offset, sway/pitch/roll rotation).
    #[must_use]
    pub const fn body(&self) -> &BodyReaction {
        &self.reaction
    }

    /// The body's pose with the reaction applied: where to draw the body.
    #[must_use]
    pub fn reacted_pose(&self) -> Pose {
        Pose::new(
            self.pose.translation + self.reaction.offset,
            (self.pose.rotation * self.reaction.rotation).normalize(),
        )
    }

    /// The head's look-at.
    #[must_use]
    pub const fn look(&self) -> &Look {
        &self.look
    }

    /// How many chains there are.
    #[must_use]
    pub fn chain_count(&self) -> usize {
        self.chains.len()
    }

    /// A chain's joint positions (world, root first, `segments + 1` of them), after blending.
    ///
    /// # Errors
    /// [`GaitError::IndexOutOfRange`] for a chain that does not exist.
    pub fn chain(&self, chain: usize) -> Result<&[Vec3], GaitError> {
        self.chain_states
            .get(chain)
            .map(|s| s.output.as_slice())
            .ok_or(GaitError::IndexOutOfRange {
                what: "chain",
                index: chain,
                len: self.chain_states.len(),
            })
    }

    /// The current blend weight of the procedural layer.
    #[must_use]
    pub const fn blend(&self) -> f32 {
        self.blend
    }

    /// The figures of the last update: the steps it started, and the skate, overstretch,
    /// legs in the air and stability margin of the state it left, measured when asked (an
    /// update does not pay for figures nobody reads; the result is the same whenever it is
    /// asked before the next update).
    #[must_use]
    pub fn metrics(&self) -> GaitMetrics {
        self.measure()
    }

    /// Whether every leg stands on the ground (no step under way, every ray hit).
    #[must_use]
    pub fn all_planted(&self) -> bool {
        self.legs
            .iter()
            .zip(&self.states)
            .all(|(leg, s)| leg.kind != LimbKind::Leg || (s.planted && s.grounded))
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

/// The ray hit under a leg's rest position (`rest_world`): `(point, normal, grounded)`; arms
/// and misses give the rest position itself.
#[inline(always)]
fn cast_anchor<G: Ground + ?Sized>(
    leg: &Leg,
    rest_world: Vec3,
    o: &GaitOptions,
    ground: &G,
) -> (Vec3, Vec3, bool) {
    if leg.kind == LimbKind::Arm {
        return (rest_world, Vec3::Y, true);
    }
    match cast_down(ground, rest_world, leg.size, o) {
        Some((point, normal)) => (point, normal, true),
        None => (rest_world, Vec3::Y, false),
    }
}

/// A ray straight down from above `point`: `(hit point, unit normal)` or `None`; hits with
/// non-finite fields are ignored.
#[inline(always)]
fn cast_down<G: Ground + ?Sized>(
    ground: &G,
    point: Vec3,
    size: f32,
    o: &GaitOptions,
) -> Option<(Vec3, Vec3)> {
    let (origin, max_distance) = down_ray(point, size, o);
    let hit = ground.cast_down(origin, max_distance)?;
    // `hit.is_valid()`, then unit normals (as `HeightField` and `Plane` give) kept and others
    // normalised; a normal that passes as a unit is finite and long enough already.
    let n = hit.normal;
    let n2 = n.length_squared();
    let normal = if abs(n2 - 1.0) <= 1e-6 {
        n
    } else if n.is_finite() && n2 > 1e-12 {
        n.normalize_or(Vec3::Y)
    } else {
        return None;
    };
    if !(hit.point.is_finite() && hit.distance.is_finite()) {
        return None;
    }
    Some((hit.point, normal))
}

/// The ray of [`cast_down`]: its origin above `point` and its length.
#[inline(always)]
fn down_ray(point: Vec3, size: f32, o: &GaitOptions) -> (Vec3, f32) {
    let above = o.cast_height * size;
    (point + Vec3::Y * above, above + o.cast_depth * size)
}

/// Where a step should land: ahead of the anchor along the anchor's horizontal `motion`, by the
/// reach in that direction × overshoot (ramped in with speed, × the speed multiplier, capped at
/// the reach), projected onto the ground from `rest_y` (the rest position's height) or the
/// anchor, whichever is higher.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn step_target<G: Ground + ?Sized>(
    leg: &Leg,
    o: &GaitOptions,
    anchor: Vec3,
    anchor_normal: impl FnOnce() -> Vec3,
    motion: Vec3,
    forward: Vec3,
    rest_y: f32,
    ground: &G,
) -> (Vec3, Vec3) {
    let speed = motion.length();
    let mut target = anchor;
    if speed > 1e-6 {
        let dir = motion / speed;
        let reach = o.reach.evaluate(dir.dot(forward)) * leg.size;
        let ramp = (speed / (o.overshoot_speed * leg.size)).min(1.0);
        let length = (reach * o.overshoot * ramp * o.speed_multiplier.max(1.0)).min(reach);
        target += dir * length;
    }
    if leg.kind == LimbKind::Arm {
        return (target, Vec3::Y);
    }
    if target == anchor {
        return (anchor, anchor_normal());
    }
    // Cast from the rest height so steep ground ahead is found from above.
    let probe = Vec3::new(target.x, rest_y.max(anchor.y), target.z);
    match cast_down(ground, probe, leg.size, o) {
        Some(hit) => hit,
        None => (anchor, anchor_normal()),
    }
}

/// A chain's rest joints in world space, its direction turned by `yaw` about the body's up,
/// written into `out` (reused storage).
fn chain_rest(chain: &Chain, pose: &Pose, yaw: f32, out: &mut Vec<Vec3>) {
    let yaw = clamp_sym(yaw, core::f32::consts::FRAC_PI_2);
    let dir = quat_yxz(yaw, 0.0, 0.0) * chain.direction.normalize_or(Vec3::NEG_Z);
    out.clear();
    out.extend(
        (0..=chain.segments)
            .map(|k| pose.transform_point(chain.root + dir * (chain.segment_length * k as f32))),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ground::Plane;

    fn quadruped(options: &GaitOptions) -> Controller {
        let legs: Vec<Leg> = [(0.2, 0.4), (-0.2, 0.4), (0.2, -0.4), (-0.2, -0.4)]
            .iter()
            .map(|&(x, z)| Leg::new(Vec3::new(x, 0.0, z), Vec3::new(1.2 * x, -0.8, z), 0.5, 0.5))
            .collect();
        Controller::new(&legs, options).unwrap()
    }

    fn walk(c: &mut Controller, from: usize, frames: usize) {
        let dt = 1.0 / 60.0;
        for f in from..from + frames {
            let pose = Pose::new(Vec3::new(0.0, 0.8, f as f32 * dt), Quat::IDENTITY);
            c.update(dt, pose, Vec3::Z, Vec3::ZERO, &Plane::GROUND)
                .unwrap();
        }
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

    #[test]
    fn a_settled_gaze_follows_a_new_head_position() {
        // The look-at keeps its rotation while its angles stand still; moving the head must
        // still move the gaze's target.
        let mut late = quadruped(&GaitOptions::DEFAULT);
        walk(&mut late, 0, 600);
        late.set_head(Vec3::new(0.0, 0.3, 0.6)).unwrap();
        walk(&mut late, 600, 1);
        let mut early = quadruped(&GaitOptions::DEFAULT);
        early.set_head(Vec3::new(0.0, 0.3, 0.6)).unwrap();
        walk(&mut early, 0, 601);
        assert_eq!(late.look(), early.look());
    }

    #[test]
    fn a_reset_recomputes_an_instant_gaze() {
        // With no smoothing the gaze's angles are the same before and after a reset, which
        // sets its rotation to identity: the next update must compute it again.
        let options = GaitOptions::DEFAULT.with_look(0.4, 1.0, 0.0);
        let mut walked = quadruped(&options);
        walk(&mut walked, 0, 120);
        let pose = Pose::new(Vec3::new(0.0, 0.8, 2.0), Quat::IDENTITY);
        walked.reset(pose, &Plane::GROUND).unwrap();
        walk(&mut walked, 120, 1);
        let mut fresh = quadruped(&options);
        fresh.reset(pose, &Plane::GROUND).unwrap();
        walk(&mut fresh, 120, 1);
        assert_eq!(walked.look(), fresh.look());
        assert_ne!(walked.look().rotation, Quat::IDENTITY);
    }
}
