//! Building a [`Controller`] and changing its settings between updates.

use alloc::vec::Vec;

use glam::{Quat, Vec3, Vec3A};

use super::{BodyReaction, Controller, HipPair, LegLanes, LegState, Look};
use crate::error::{GaitError, finite, finite3, in_range};
use crate::gaits::{Gait, HOP_SWING_FRACTION, RUN_SWING_FRACTION};
use crate::leg::{Leg, LimbKind, Pose, layout};
use crate::math::{Roots, abs, cos};
use crate::metrics::GaitMetrics;
use crate::options::GaitOptions;

/// The gait a controller with `options` and walking legs of mean size `walking_size` takes
/// standing still: the one its gait speeds give at speed 0 (a walk, unless they trot or run
/// from 0), or a walk without gaits by speed.
fn rest_gait(options: &GaitOptions, walking_size: f32) -> Gait {
    let gait = options
        .gaits
        .map_or(Gait::Walk, |s| s.choose(Gait::Walk, 0.0, walking_size));
    hopping(options, gait)
}

/// `gait` as `options` take it: a hopper hops where others trot or run, and at every speed
/// without gaits by speed.
pub(super) fn hopping(options: &GaitOptions, gait: Gait) -> Gait {
    if options.hop && (gait != Gait::Walk || options.gaits.is_none()) {
        Gait::Hop
    } else {
        gait
    }
}

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
    /// [`Chain`](crate::Chain)s (dangling legs, tails, fins: add them with
    /// [`add_chain`](Self::add_chain)), breathing and the head's look-at, with no stepping and no
    /// body reaction to feet.
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
        let mut layout = layout(legs, options.gaits.is_some())?;
        let walking_legs = legs.iter().filter(|l| l.kind == LimbKind::Leg);
        let (sum, count) = walking_legs.fold((0.0f32, 0u32), |(s, n), l| (s + l.size, n + 1));
        let walking_size = if count > 0 { sum / count as f32 } else { 0.0 };
        let gait = rest_gait(options, walking_size);
        (layout.groups, layout.group_count) = layout.by_gait[gait as usize].clone();
        let (swing_fraction, handover) = Self::swing(gait, layout.group_count);
        // Each leg's hip-roll lever: the hips' X distance to its partner (or a floor).
        let hip_width: Vec<f32> = legs
            .iter()
            .enumerate()
            .map(|(i, a)| match layout.partner[i].map(|j| &legs[j]) {
                Some(b) => abs(a.hip.x - b.hip.x).max(1e-3 * a.size),
                None => 0.0,
            })
            .collect();
        let hip_pairs = (0..legs.len())
            .map(|i| match layout.partner[i] {
                Some(j) if j < i && hip_width[j] == hip_width[i] => HipPair::Mirror(j),
                Some(j) => HipPair::Own(j, hip_width[i]),
                None => HipPair::None,
            })
            .collect();
        // The sway turns the body about its origin, moving a foot across it by as much as the
        // foot lies ahead or behind: a long body with a narrow stance would sway its end feet
        // across the midline (and its stepping then chases them back over it).
        let walking = || {
            legs.iter()
                .filter(|l| l.kind == LimbKind::Leg && l.rest.x != 0.0)
        };
        let narrowest = walking()
            .map(|l| abs(l.rest.x))
            .fold(f32::INFINITY, f32::min);
        let farthest = walking().map(|l| abs(l.rest.z)).fold(0.0, f32::max);
        let sway_side_limit = if farthest > 0.0 {
            narrowest / farthest
        } else {
            f32::INFINITY
        };
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
            sway_side_limit,
            swing_fraction,
            gait,
            wanted_gait: gait,
            walking_size,
            handover,
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
            hop_heights: alloc::vec![0.0; legs.len()],
            hop_rise: 0.0,
            hop_lifts: alloc::vec![0.0; legs.len()],
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

    /// The gait it takes standing still (see [`rest_gait`]).
    pub(super) fn rest_gait(&self) -> Gait {
        rest_gait(&self.options, self.walking_size)
    }

    /// A gait's swing fraction (a swing's share of its step's length in the body's travel) and
    /// handover progress (see `handover`), with `group_count` groups.
    pub(super) fn swing(gait: Gait, group_count: u8) -> (f32, f32) {
        let alternating = 1.0 / f32::from(group_count.max(2));
        match gait {
            Gait::Run => (RUN_SWING_FRACTION, alternating / RUN_SWING_FRACTION),
            // One group: it hands over to itself as its feet land.
            Gait::Hop => (HOP_SWING_FRACTION, 1.0),
            Gait::Walk | Gait::Trot => (alternating, 1.0),
        }
    }

    /// Steps in `gait` from now on: its groups, swing and handover; the group whose turn it
    /// is, the one of the leg that trails the farthest behind its anchor along its motion
    /// (it would want to step first).
    pub(super) fn change_gait(&mut self, gait: Gait) {
        let (groups, count) = &self.layout.by_gait[gait as usize];
        self.layout.groups.copy_from_slice(groups);
        self.layout.group_count = *count;
        (self.swing_fraction, self.handover) = Self::swing(gait, *count);
        self.gait = gait;
        let mut first = (f32::NEG_INFINITY, 0u8);
        for (((leg, state), motion), group) in self
            .legs
            .iter()
            .zip(&self.states)
            .zip(&self.motion)
            .zip(&self.layout.groups)
        {
            if leg.kind != LimbKind::Leg || state.stepping || !state.grounded {
                continue;
            }
            let trail = -(state.foot - state.anchor).dot(motion.try_unit().unwrap_or(Vec3::ZERO));
            if trail > first.0 {
                first = (trail, *group);
            }
        }
        self.active_group = first.1;
        self.turn_taken = false;
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
}
