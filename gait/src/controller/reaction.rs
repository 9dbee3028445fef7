//! Reaction: the body's bob, breathing, sway (yaw), pitch and roll from its feet, each leg's
//! hip roll, and the reaction scaled back so no planted foot is out of reach.

use glam::{Mat3A, Quat, Vec2, Vec3, Vec3A, Vec4};

use super::joints::lane;
use super::{Controller, LegState};
use crate::ik::V3;
use crate::leg::{LimbKind, Pose};
use crate::math::{
    Roots, atan2, atan2_lanes, clamp_sym, quat_yxz, quat_yxz_sin_cos, sin_cos, sin_cos_lanes,
    sin_turns_arg, sqrt,
};

/// A leg's hip roll (see `Controller::react`): none without a partner, else its own angle
/// from the height difference to partner `j` over the lever, or the opposite of the partner's
/// angle when the partner comes first with the same lever (one arctangent per pair).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum HipPair {
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
    let db = states[j].foot.y - rests[j].y;
    da - db
}

/// Bisection steps of [`Controller::keep_within_reach`]: the reaction kept is within 2⁻¹⁰ of
/// the most that keeps every planted foot in reach.
const REACH_BISECTIONS: u32 = 10;

impl Controller {
    pub(super) fn react(&mut self, pose: &Pose, rotation: &Mat3A) {
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
        for ((((leg, state), rest_world), angles), lift) in self
            .legs
            .iter()
            .zip(&self.states)
            .zip(&self.rest_world)
            .zip(&self.angles)
            .zip(&self.hop_lifts)
        {
            if leg.kind != LimbKind::Leg || !state.grounded {
                continue;
            }
            // (A hop's rise, which the body takes whole, left out.)
            let e = state.foot.y - lift - rest_world.y;
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
        // The sway no further than keeps the feet at rest on their sides.
        let yaw_limit = o.sway_limit.min(self.sway_side_limit);
        let (bob_t, yaw_t, pitch_t, roll_t) = if count == 0 {
            (0.0, 0.0, 0.0, 0.0)
        } else {
            let n = count as f32;
            let bob_limit = o.bob_limit * self.mean_size;
            (
                clamp_sym(o.bob_gain * height / n, bob_limit),
                clamp_sym(o.sway_gain * yaw / n, yaw_limit),
                clamp_sym(o.sway_gain * pitch, o.sway_limit),
                clamp_sym(o.sway_gain * roll, o.sway_limit),
            )
        };
        let yaw = clamp_sym(
            self.reaction.yaw + (yaw_t - self.reaction.yaw) * k,
            yaw_limit,
        );
        let yaw = self.sway_keeping_sides(pose, rotation, yaw);
        let r = &mut self.reaction;
        r.bob = clamp_sym(r.bob + (bob_t - r.bob) * k, o.bob_limit * self.mean_size);
        r.yaw = yaw;
        r.pitch = clamp_sym(r.pitch + (pitch_t - r.pitch) * k, o.sway_limit);
        let roll = clamp_sym(r.roll + (roll_t - r.roll) * k, o.sway_limit);
        let (yaw, pitch) = (r.yaw, r.pitch);
        let roll = self.roll_keeping_sides(pose, rotation, (yaw, pitch), roll);
        let r = &mut self.reaction;
        r.roll = roll;
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
        r.offset = Vec3::Y * ((r.bob + breathe + self.hop_rise) * w);
        r.rotation = quat_yxz_sin_cos(s, c);

        // Hip roll: the height difference between a foot and its partner (3D seed). A pair
        // with the same lever rolls by opposite angles: one arctangent per pair.
        for i in 0..self.legs.len() {
            let state = &self.states[i];
            let roll = match self.hip_pairs[i] {
                HipPair::Own(j, width) if state.grounded && self.states[j].grounded => {
                    let rise = hip_rise(
                        state,
                        &self.rest_world[i],
                        &self.states,
                        &self.rest_world,
                        j,
                    );
                    clamp_sym(o.hip_roll_gain * atan2(rise, width), o.hip_roll_limit)
                }
                HipPair::Mirror(j) if state.grounded && self.states[j].grounded => {
                    let mirrored = -self.states[j].hip_roll;
                    self.states[i].hip_roll = mirrored;
                    continue;
                }
                _ => 0.0,
            };
            self.states[i].hip_roll = roll * self.blend;
        }
    }

    /// `yaw` (a sway before blending) turned back toward none, as little as needed, so that the
    /// sway carries no walking foot off the midline (planted or swinging) across more than
    /// half its margin from it, nor a foot already across any further: the sway turns the
    /// body about its origin, so a foot moves across the body's frame by as much as it lies
    /// ahead or behind, and a long body with a narrow stance would cross its end feet.
    ///
    /// In the body's frame (`pose` with `rotation`, unreacted), a foot at `(x, z)` seen from
    /// the sway `ψ` is at `x cos ψ − z sin ψ`; see [`keeping_sides`](Self::keeping_sides) for the rest.
    fn sway_keeping_sides(&self, pose: &Pose, rotation: &Mat3A, yaw: f32) -> f32 {
        self.keeping_sides(pose, rotation, yaw, |local| local.z)
    }

    /// `roll` (before blending) turned back toward none, as little as needed, so that the roll
    /// carries no walking foot across more than half its margin from the midline, nor a foot
    /// already across any further: the roll turns the body about its origin on the ground, so
    /// a lifted foot moves across the body's frame by as much as it is lifted, and a body
    /// whose narrow rear legs lift with its wide front ones would swing them across.
    ///
    /// In the body's frame (`pose` with `rotation` and the reaction's blended `yaw` and
    /// `pitch`), a foot at `(x, y)` seen from the roll `ρ` is at `x cos ρ + y sin ρ`.
    fn roll_keeping_sides(
        &self,
        pose: &Pose,
        rotation: &Mat3A,
        (yaw, pitch): (f32, f32),
        roll: f32,
    ) -> f32 {
        if roll * self.blend == 0.0 {
            return roll;
        }
        let w = self.blend;
        let turned = *rotation * Mat3A::from_quat(quat_yxz(yaw * w, pitch * w, 0.0));
        self.keeping_sides(pose, &turned, roll, |local| -local.y)
    }

    /// `angle` (before blending) of a turn of the body's frame (`pose` with `rotation`) that
    /// moves a foot at `local` across it to `x cos θ − along(local) sin θ`, held back as
    /// little as needed so that no walking foot crosses more than half its margin from the
    /// midline, nor a foot already across any further.
    ///
    /// On its side (`a`, `b` the foot's `x` and `along` times its side's sign) a foot keeps
    /// `a cos θ − b sin θ = R cos(θ + φ)` with `R = |(a, b)|` and `φ = atan2(b, a)`. That is at
    /// least `need` for `θ + φ` within `±acos(need / R)`, an interval about `θ = 0` (where it
    /// is `a ≥ need`): a turn past it is held at its end.
    fn keeping_sides(
        &self,
        pose: &Pose,
        rotation: &Mat3A,
        angle: f32,
        along: impl Fn(Vec3A) -> f32,
    ) -> f32 {
        let w = self.blend;
        let mut turn = angle * w;
        if turn == 0.0 {
            return angle;
        }
        let (sin, cos) = sin_cos(turn);
        let inverse = rotation.transpose();
        let mut held = false;
        for (leg, state) in self.legs.iter().zip(&self.states) {
            if leg.kind != LimbKind::Leg || leg.rest.x == 0.0 {
                continue;
            }
            let local = inverse * Vec3A::from(state.foot - pose.translation);
            let side = leg.rest.x.signum();
            let (a, b) = (side * local.x, side * along(local));
            let need = (0.5 * a).min(a);
            if a * cos - b * sin >= need {
                continue;
            }
            let radius = sqrt(a * a + b * b);
            if !(radius > 0.0) {
                continue;
            }
            let reach = atan2(sqrt((radius * radius - need * need).max(0.0)), need);
            let phi = atan2(b, a);
            turn = if turn > 0.0 {
                turn.min(reach - phi).max(0.0)
            } else {
                turn.max(-reach - phi).min(0.0)
            };
            held = true;
        }
        if held { turn / w } else { angle }
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

    /// Scales the body's reaction (bob, breathing, sway) back toward none, as little as needed,
    /// so that no planted foot is beyond its leg's reach from the reacted hip: on a long body a
    /// small pitch or roll moves the far hips a long way. A foot out of reach of the unreacted
    /// body already steps (see `action`).
    pub(super) fn keep_within_reach(&mut self, pose: &Pose) {
        let reaction = self.reaction;
        // The reacted body's hips, four legs at a time; kept for the IK when every planted foot
        // is within reach of them (as usual), which then need not place them again.
        let rotation = Mat3A::from_quat((pose.rotation * reaction.rotation).unit());
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
            // A mask of glam's own type (it depends on glam's features).
            let planted = |k: usize| f32::from(u8::from(lane(states, k).planted));
            let planted =
                Vec4::new(planted(0), planted(1), planted(2), planted(3)).cmpgt(Vec4::ZERO);
            let d = feet.sub(*hips);
            out |= (d.dot(d).cmpgt(lanes.reach2) & planted).any();
        }
        if !out {
            self.reacted_rotation = Some(rotation);
            return;
        }
        let out_of_reach = |offset: Vec3, rotation: Quat| {
            let rotation = Mat3A::from_quat((pose.rotation * rotation).unit());
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
        self.reaction.rotation = Quat::IDENTITY.slerp(reaction.rotation, low).unit();
    }

    /// Each swinging foot moved out across the reacted body (level, along its left axis) to at
    /// least half its margin from the midline on its own side (see
    /// [`GaitOptions::midline_margin`](crate::GaitOptions::midline_margin)): a foot lifting
    /// off near the midline of a turning body is otherwise carried across it while it rises,
    /// and more so when the body's lean swings back. A foot moves out no further than it is
    /// lifted (off the ground first, then out: it neither slides on lift-off nor on
    /// touchdown), and no planted foot moves (one near the midline steps, see `action`).
    /// Returns whether any foot moved.
    pub(super) fn keep_swings_on_their_sides(&mut self, pose: &Pose) -> bool {
        // The reacted body's rotation, as `keep_within_reach` left it when it kept the reaction.
        let rotation = self
            .reacted_rotation
            .unwrap_or_else(|| Mat3A::from_quat((pose.rotation * self.reaction.rotation).unit()));
        let origin = pose.translation + self.reaction.offset;
        let left = Vec3::from(rotation.x_axis);
        let level = Vec3::new(left.x, 0.0, left.z);
        // How far the foot moves across the body per unit moved along `level`.
        let across = level.dot(left);
        if !(across > 0.5) {
            // The body lies on its side: no level direction moves a foot across it.
            return false;
        }
        let margin = 0.5 * self.options.midline_margin;
        let mut moved = false;
        for (leg, state) in self.legs.iter().zip(&mut self.states) {
            let side = leg.rest.x;
            if leg.kind != LimbKind::Leg || side == 0.0 || !state.stepping {
                continue;
            }
            let short = margin * side.abs() - side.signum() * left.dot(state.foot - origin);
            if short > 0.0 {
                let lift = self.options.height_curve.evaluate(state.progress) * state.lift;
                state.foot += level * (side.signum() * (short / across).min(lift));
                moved = true;
            }
        }
        moved
    }
}
