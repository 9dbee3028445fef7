//! Action and sequencing: each leg's ground ray and anchor, which planted feet want to step,
//! the leg groups' turns, and the steps themselves (start, progress, landing).

use glam::{Mat3A, Vec3};

use super::{Controller, LegState, MAX_COORDINATE, horizontal};
use crate::gaits::Gait;
use crate::ground::Ground;
use crate::leg::{Leg, LimbKind, Pose};
use crate::math::{Roots, abs, sin_turns, sqrt};
use crate::options::GaitOptions;

const WANT: u8 = 1;
const ESCAPE: u8 = 2;

impl Controller {
    pub(super) fn action<G: Ground + ?Sized>(
        &mut self,
        dt: f32,
        pose: &Pose,
        rotation: &Mat3A,
        velocity: Vec3,
        angular_velocity: Vec3,
        ground: &G,
    ) {
        if let Some(speeds) = &self.options.gaits {
            let speed = horizontal(velocity).norm();
            let gait = speeds.choose(self.gait, speed, self.walking_size);
            self.wanted_gait = super::setup::hopping(&self.options, gait);
        }
        let o = &self.options;
        let forward = horizontal(pose.rotation * Vec3::Z)
            .try_unit()
            .unwrap_or(Vec3::Z);
        let body = pose.translation;
        let rotation = *rotation;
        // The body as it was last shown (the reaction's lean and lag included): the frame in
        // which feet must stay on their own side of the midline.
        let shown = (
            body + self.reaction.offset,
            rotation * Mat3A::from_quat(self.reaction.rotation),
        );
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
                    Some(point) if near_ray(origin, point) => (point, true),
                    _ => (rest_world, false),
                }
            };
            let anchor_normal =
                || cast_down(ground, rest_world, leg.size, o).map_or(Vec3::Y, |(_, n)| n);
            let motion = horizontal(velocity + angular_velocity.cross(rest_world - body));
            if still && motion.norm() > still_limit {
                still = false;
            }
            self.rest_world[i] = rest_world;
            self.motion[i] = motion;
            let want = &mut self.wants[i];
            let state = &mut self.states[i];
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
                    (leg, i, &self.legs, &self.states),
                    o,
                    anchor,
                    anchor_normal,
                    motion,
                    (forward, shown.0, &shown.1),
                    rest_world.y,
                    ground,
                );
                let state = &mut self.states[i];
                // The target follows the motion until the foot is over it; then it comes
                // straight down onto it.
                let plant = o.plant_fraction;
                if state.progress < 1.0 - plant {
                    state.step_target = target;
                    state.normal = target_normal;
                }
                let target = state.step_target;
                let moved = horizontal(anchor - state.prev_anchor).norm();
                let by_motion = moved / state.swing_length.max(1e-6);
                let before = state.progress;
                state.progress = (state.progress
                    + by_motion
                        .max(o.settle_rate * dt)
                        .min(dt / (o.min_swing_time * sqrt(leg.size.min(1.0)))))
                .min(1.0);
                state.pace = state.progress - before;
                if state.progress >= 1.0 {
                    state.foot = target;
                    state.stepping = false;
                    state.escaping = false;
                    state.planted = true;
                } else {
                    // Up first and down last, across in between (smoothly), so the foot
                    // neither scuffs on lift-off nor skids on landing.
                    let lift = o.height_curve.evaluate(state.progress) * state.lift;
                    let across =
                        ((state.progress - plant) / (1.0 - 2.0 * plant).max(1e-6)).clamp(0.0, 1.0);
                    let across = across * across * (3.0 - 2.0 * across);
                    state.foot = state.step_start.lerp(target, across) + Vec3::Y * lift;
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
        for (index, ((((leg, state), want), motion), strayed)) in self
            .legs
            .iter()
            .zip(&self.states)
            .zip(&mut self.wants)
            .zip(&self.motion)
            .zip(&mut self.strayed)
            .enumerate()
        {
            if state.stepping || (leg.kind == LimbKind::Leg && !state.grounded) {
                *want = 0;
                continue;
            }
            if *want != 0 {
                continue; // forced above
            }
            let stray = horizontal(state.foot - state.anchor);
            let distance = stray.norm();
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
            // Coming near the body's midline (a long body turning in place swings its outer
            // feet across): step now, out of turn, before the feet cross. Where the foot will be
            // once it is off the ground: it drifts on (opposite its rest position's motion,
            // in the body's frame) for the update the body as shown lags by and the lift-off,
            // no longer than `plant_fraction` of a step at the slowest progress.
            let side = leg.rest.x;
            if leg.kind == LimbKind::Leg && side != 0.0 {
                let to_body = shown.1.transpose();
                let lead = dt + o.plant_fraction / o.settle_rate;
                let local_x = (to_body * (state.foot - shown.0 - *motion * lead)).x;
                if local_x * side.signum() < o.midline_margin * side.abs() {
                    flags |= WANT | ESCAPE;
                }
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
            // Trailing onto the foot of the leg behind it on its side (a long front leg
            // striding back past where a short hind leg can land, whose step's target the
            // landing reach keeps short of the spacing): step now, out of turn, before the hind
            // foot lands on it and the legs pass through each other, if another foot stays
            // down.
            if flags & ESCAPE == 0
                && o.foot_spacing > 0.0
                && let Some(hind) = self.layout.hind[index]
                && trails_onto_a_hind_foot(
                    (leg, &self.legs[hind], &self.states[hind]),
                    o,
                    state.foot,
                    (body, &rotation),
                )
                && self
                    .legs
                    .iter()
                    .zip(&self.states)
                    .filter(|(l, s)| l.kind == LimbKind::Leg && s.grounded && !s.stepping)
                    .count()
                    >= 2
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
        let handover = self.handover;
        // A run hands over when the next update would carry a step past the handover: at 30
        // frames a second a quick swing lands in three, and would never be seen in between.
        let early = self.gait == Gait::Run;
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
            // A run's group hands over while its feet are still in the air (`handover` < 1).
            let pace = if early { state.pace } else { 0.0 };
            group_stepping |= sequenced
                & (*group == active)
                & state.stepping
                & (state.progress + pace < handover);
            group_wants |= sequenced & (*group == active) & wants;
            next_moves |= sequenced & (*group == next) & (state.stepping | wants);
        }
        let advance = !group_stepping && (self.turn_taken || !group_wants);
        if advance {
            if self.wanted_gait == self.gait {
                self.active_group = next;
                self.turn_taken = false;
            } else {
                // A new gait takes over here, between two groups' turns.
                self.change_gait(self.wanted_gait);
                let active = self.active_group;
                next_moves = self
                    .legs
                    .iter()
                    .zip(&self.states)
                    .zip(&self.wants)
                    .zip(&self.layout.groups)
                    .any(|(((leg, state), want), group)| {
                        leg.kind == LimbKind::Leg
                            && *group == active
                            && (state.stepping || want & WANT != 0)
                    });
            }
        }
        let o = &self.options;
        let active = self.active_group;

        // 4. Start the steps that are allowed. Once the active group moves, its other legs that
        //    trail behind their rest position by more than `group_join` of their reach join it,
        //    so a group steps together instead of leaving a leg to wait a whole cycle. Feet
        //    that are ahead (just landed) never join: they would step again at once.
        //    In a run, the group whose turn comes lifts off at the handover, every trailing leg
        //    of it: its swings overlap the last group's, for a moment no foot on the ground.
        //    In a hop, every leg of the one group lifts off with the first that wants to, all
        //    feet together (trailing or not: they landed together), once every foot of the
        //    last hop has landed (a foot landing before the others stands until they do).
        let lift_all = advance & (self.gait == Gait::Run);
        let hopping = self.gait == Gait::Hop;
        let hop = hopping & !group_stepping;
        let group_moves = if advance {
            next_moves | lift_all
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
                let far = lift_all | (distance > o.group_join * reach_here * leg.size);
                if idle & ((trailing & far) | hop) {
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
            // A run's groups lift off while the others are in the air; a hop's feet together,
            // and none before every foot of the last hop has landed (feet that fell out of
            // step, one escaping, hop together again).
            let opposite_busy = !matches!(self.gait, Gait::Run | Gait::Hop)
                && self.layout.opposite[i].is_some_and(|j| self.states[j].stepping);
            let landing = hopping & group_stepping;
            let in_turn =
                !sequenced || (self.layout.groups[i] == active && !opposite_busy && !landing);
            let escape = sequenced && !in_turn && flags & ESCAPE != 0;
            if !(escape || (flags & WANT != 0 && in_turn)) {
                continue;
            }
            let normal = self.states[i].normal;
            let (target, target_normal) = step_target(
                (leg, i, &self.legs, &self.states),
                o,
                self.states[i].anchor,
                || normal,
                self.motion[i],
                (forward, shown.0, &shown.1),
                self.rest_world[i].y,
                ground,
            );
            let state = &mut self.states[i];
            state.stepping = true;
            state.planted = false;
            state.escaping = escape;
            state.progress = 0.0;
            state.pace = 0.0;
            state.step_start = state.foot;
            state.step_target = target;
            state.normal = target_normal;
            state.lift = o.step_height * leg.size * speed_factor;
            state.swing_length =
                horizontal(target - state.foot).norm().max(0.05 * leg.size) * self.swing_fraction;
            state.steps = state.steps.saturating_add(1);
            // A hop's flight: the arc a body thrown up rises to over the swing's expected time
            // (its length at the leg's speed, or the settle rate's time, no shorter than the
            // shortest swing), no higher than `HOP_RISE` of the leg.
            self.hop_heights[i] = if sequenced && self.gait == Gait::Hop {
                let rate = (self.motion[i].norm() / state.swing_length.max(1e-6))
                    .max(o.settle_rate)
                    .min(1.0 / (o.min_swing_time * sqrt(leg.size.min(1.0))));
                let time = 1.0 / rate;
                let gravity = o.gaits.map_or(GRAVITY, |s| s.gravity);
                (gravity * time * time / 8.0).min(HOP_RISE * leg.size)
            } else {
                0.0
            };
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

        // 5. A hop's flight: the body rises on the mean of its walking legs' arcs (each
        //    `4 h p (1 − p)` over its step's progress `p`: none at lift-off and landing), and
        //    the feet in the air with it, so the legs keep their swing's shape (the reaction's
        //    bob leaves that rise out: see `hop_lifts`). (Only while hopping or a hop's step
        //    is in the air: every other update skips it.)
        if self.gait != Gait::Hop && self.hop_rise == 0.0 {
            return;
        }
        let mut rise = 0.0f32;
        let mut walking = 0usize;
        for ((leg, state), &height) in self.legs.iter().zip(&self.states).zip(&self.hop_heights) {
            if leg.kind == LimbKind::Leg {
                walking += 1;
                if state.stepping && height > 0.0 {
                    rise += arc(height, state.progress);
                }
            }
        }
        let rise = if rise > 0.0 {
            rise / walking as f32
        } else {
            0.0
        };
        self.hop_rise = rise;
        // Each foot rises with the body, no higher than its own arc (a foot lifting off or
        // landing out of step with the others does not jump).
        for ((state, &height), lift) in self
            .states
            .iter_mut()
            .zip(&self.hop_heights)
            .zip(&mut self.hop_lifts)
        {
            *lift = if state.stepping && height > 0.0 {
                rise.min(arc(height, state.progress))
            } else {
                0.0
            };
            state.foot.y += *lift;
        }
    }
}

/// A hop's arc `height` high at progress `p` of its step: `4 h p (1 − p)`.
#[inline(always)]
fn arc(height: f32, p: f32) -> f32 {
    4.0 * height * p * (1.0 - p)
}

/// The most a hop's body rises in its flight, × the leg's size.
const HOP_RISE: f32 = 0.2;

/// Gravity (m/s²) of a hop's flight without gaits by speed (whose `gravity` it takes).
const GRAVITY: f32 = 9.81;

/// The ray hit under a leg's rest position (`rest_world`): `(point, normal, grounded)`; arms
/// and misses give the rest position itself.
#[inline(always)]
pub(super) fn cast_anchor<G: Ground + ?Sized>(
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
/// non-finite fields, or not [`near_ray`], are ignored.
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
        n.unit_or(Vec3::Y)
    } else {
        return None;
    };
    if !(near_ray(origin, hit.point) && hit.distance.is_finite()) {
        return None;
    }
    Some((hit.point, normal))
}

/// Whether a ground hit is one the controller uses: within [`MAX_COORDINATE`] of the ray's
/// `origin` on every axis (so finite). The legs, poses and rays are bounded by it too, so the
/// feet's distances, squared lengths and support hull stay far from overflow; a ground that
/// reports a hit farther away (regression: 1e30 away gave a stability margin of −∞) is taken
/// to have missed, as for a non-finite hit (see [`Ground`]).
#[inline(always)]
fn near_ray(origin: Vec3, point: Vec3) -> bool {
    (point - origin)
        .abs()
        .cmple(Vec3::splat(MAX_COORDINATE))
        .all()
}

/// The ray of [`cast_down`]: its origin above `point` and its length.
#[inline(always)]
fn down_ray(point: Vec3, size: f32, o: &GaitOptions) -> (Vec3, f32) {
    let above = o.cast_height * size;
    (point + Vec3::Y * above, above + o.cast_depth * size)
}

/// The farthest a step lands from its hip, × the leg's length (upper + lower).
const LANDING_REACH: f32 = 0.95;

/// Where a step should land: ahead of the anchor along the anchor's horizontal `motion`, by the
/// reach in that direction × overshoot (ramped in with speed, × the speed multiplier, capped at
/// the reach), kept on the leg's own side of the body's midline (see
/// [`GaitOptions::midline_margin`]), projected onto the ground from `rest_y` (the rest
/// position's height) or the anchor, whichever is higher, and apart from the feet of the
/// legs beside it (see [`GaitOptions::foot_spacing`]). `leg` is the leg, its index, and every
/// leg with its state; `frame` is the body's forward direction, position and rotation.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn step_target<G: Ground + ?Sized>(
    leg: (&Leg, usize, &[Leg], &[LegState]),
    o: &GaitOptions,
    anchor: Vec3,
    anchor_normal: impl FnOnce() -> Vec3,
    motion: Vec3,
    frame: (Vec3, Vec3, &Mat3A),
    rest_y: f32,
    ground: &G,
) -> (Vec3, Vec3) {
    let (leg, index, legs, states) = leg;
    let (forward, body, rotation) = frame;
    let speed = motion.norm();
    let mut target = anchor;
    if speed > 1e-6 {
        let dir = motion / speed;
        let reach = o.reach.evaluate(dir.dot(forward)) * leg.size;
        let ramp = (speed / (o.overshoot_speed * leg.size)).min(1.0);
        let length = (reach * o.overshoot * ramp * o.speed_multiplier.max(1.0)).min(reach);
        target += dir * length;
        // A turn's overshoot runs along the circle toward the midline: no closer to it than
        // halfway from the margin to the rest position, so a foot that lands there is not
        // already at the margin, which would start its next step at once (a turning body
        // dragged such a foot along the ground, a new one-frame step every frame).
        let side = leg.rest.x;
        if leg.kind == LimbKind::Leg && side != 0.0 {
            let mut local = rotation.transpose() * (target - body);
            let least = 0.5 * (1.0 + o.midline_margin) * side.abs();
            if local.x * side.signum() < least {
                local.x = side.signum() * least;
                target = *rotation * local + body;
            }
        }
    }
    if leg.kind == LimbKind::Arm {
        return (target, Vec3::Y);
    }
    if o.foot_spacing > 0.0 {
        target = spaced_target(
            leg,
            index,
            legs,
            states,
            o,
            anchor,
            target,
            (body, rotation),
        );
    }
    // Landing no further from the hip than `landing_reach` of the leg's length: a leg that
    // lands straight bends fast as the body comes over it.
    {
        let hip = *rotation * leg.hip + body;
        let most = LANDING_REACH * (leg.upper + leg.lower);
        let drop = hip.y - target.y;
        let across = horizontal(target - hip);
        let room = most * most - drop * drop;
        let far = across.length_squared();
        if room > 0.0 && far > room {
            target = Vec3::new(hip.x, target.y, hip.z) + across * sqrt(room / far);
        }
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

/// Whether `foot` (of walking leg `leg`) is along the body within [`TRAILING_SPACING`] of
/// [`GaitOptions::foot_spacing`] of the foot of `hind`, the walking leg behind it on its side
/// (of where that lands, if it is stepping and lands further forward). `frame` is the body's
/// position and rotation.
#[inline(always)]
fn trails_onto_a_hind_foot(
    legs: (&Leg, &Leg, &LegState),
    o: &GaitOptions,
    foot: Vec3,
    frame: (Vec3, &Mat3A),
) -> bool {
    let (leg, hind, state) = legs;
    let (body, rotation) = frame;
    if !state.grounded {
        return false;
    }
    let forward = Vec3::from(rotation.z_axis);
    let along = |p: Vec3| forward.dot(p - body);
    let gap = leg.rest.z - hind.rest.z;
    let spacing = (o.foot_spacing * 0.5 * (leg.size + hind.size)).min(0.5 * abs(gap));
    let behind = if state.stepping {
        along(state.foot).max(along(state.step_target))
    } else {
        along(state.foot)
    };
    along(foot) < behind + TRAILING_SPACING * spacing
}

/// The part of [`GaitOptions::foot_spacing`] a foot keeps ahead of a hind foot on its side
/// before it steps out of turn ([`trails_onto_a_hind_foot`]): less than the whole, so a foot
/// whose hind neighbour landed just that far behind it is not moved at once.
const TRAILING_SPACING: f32 = 1.0;

/// `target` (of walking leg `leg`, index `index` of `legs`) moved along the body, as little as
/// needed and no further than the reach from `anchor`, so that it stays
/// [`GaitOptions::foot_spacing`] behind the foot of each leg on the same side whose rest
/// position is ahead (where it is and where it lands, if it is stepping), and as far ahead of
/// each one behind. `frame` is the body's position and rotation.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn spaced_target(
    leg: &Leg,
    index: usize,
    legs: &[Leg],
    states: &[LegState],
    o: &GaitOptions,
    anchor: Vec3,
    target: Vec3,
    frame: (Vec3, &Mat3A),
) -> Vec3 {
    let (body, rotation) = frame;
    // Along the body: the body's forward axis (the rotation's third column).
    let forward = Vec3::from(rotation.z_axis);
    let along = |p: Vec3| forward.dot(p - body);
    let before = along(target);
    let mut z = before;
    for (j, (other, state)) in legs.iter().zip(states).enumerate() {
        let gap = other.rest.z - leg.rest.z;
        if j == index
            || other.kind != LimbKind::Leg
            || !state.grounded
            || !(other.rest.x * leg.rest.x > 0.0)
            || gap == 0.0
        {
            continue;
        }
        let spacing = (o.foot_spacing * 0.5 * (leg.size + other.size)).min(0.5 * abs(gap));
        // A stepping foot is kept clear of both where it is and where it lands: a rear foot
        // that landed ahead of a front foot only lifting off crossed its leg.
        let (now, lands) = (along(state.foot), along(state.step_target));
        z = if gap > 0.0 {
            let other = if state.stepping { now.min(lands) } else { now };
            z.min(other - spacing)
        } else {
            let other = if state.stepping { now.max(lands) } else { now };
            z.max(other + spacing)
        };
    }
    if z == before {
        return target;
    }
    // No further from the anchor than the reach that way.
    let home = along(anchor);
    let back = o.reach.evaluate(-1.0) * leg.size;
    let ahead = o.reach.evaluate(1.0) * leg.size;
    let z = z.clamp(home.min(before) - back, home.max(before) + ahead);
    target + forward * (z - before)
}
