//! The legs four at a time in SIMD lanes, and their two-bone IK after the body's reaction and
//! the blend weight.

use glam::{Mat3A, Vec3, Vec4};

use super::Controller;
use crate::ik::{Lanes, SPARE, V3, solve_lanes};
use crate::leg::{Leg, LimbKind};

/// Up to four legs' hips, poles and segment lengths, one per SIMD lane; missing lanes repeat
/// the first leg.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct LegLanes {
    pub(super) hip: V3,
    pub(super) rest: V3,
    pole: V3,
    upper: Vec4,
    lower: Vec4,
    /// The square of each leg's reach (`upper + lower`), infinite for arms: no foot is out of
    /// an arm's reach (see `keep_within_reach`).
    pub(super) reach2: Vec4,
}

impl LegLanes {
    pub(super) fn new(legs: &[Leg]) -> Self {
        let lanes: [&Leg; 4] = core::array::from_fn(|k| lane(legs, k));
        let get = |f: fn(&Leg) -> Vec3| lanes.map(f);
        let len = |f: fn(&Leg) -> f32| Vec4::from_array(lanes.map(f));
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

/// Lane `k` of a group of one to four legs' items (`chunks(4)` of a per-leg slice): the
/// item itself, or the group's first for a missing lane.
#[inline(always)]
pub(super) fn lane<T>(group: &[T], k: usize) -> &T {
    debug_assert!(
        (1..=4).contains(&group.len()),
        "a group of one to four legs"
    );
    group.get(k).unwrap_or(&group[0])
}

impl Controller {
    /// The feet the action placed, four legs at a time (`feet`), for the reaction, the reach
    /// check and the IK; missing lanes repeat the first leg.
    pub(super) fn gather_feet(&mut self) {
        for (feet, states) in self.feet.iter_mut().zip(self.states.chunks(4)) {
            *feet = V3::gather(match states {
                [a, b, c, d] => [a.foot, b.foot, c.foot, d.foot],
                _ => core::array::from_fn(|k| lane(states, k).foot),
            });
        }
    }

    pub(super) fn solve_joints(&mut self) {
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
            // Missing lanes repeat the first leg.
            let targets = if w == 1.0 {
                *feet
            } else {
                let states = &*states;
                V3::gather(core::array::from_fn(|k| {
                    lane(rest, k).lerp(lane(states, k).foot, w)
                }))
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
            // The last group may have one to three legs: its missing lanes are solved into
            // spares (`chunks_mut(4)` gives no other lengths).
            let [s0, s1, s2] = &mut spare;
            let out = match states {
                [a, b, c, d] => [&mut a.joints, &mut b.joints, &mut c.joints, &mut d.joints],
                [a, b, c] => [&mut a.joints, &mut b.joints, &mut c.joints, s0],
                [a, b] => [&mut a.joints, &mut b.joints, s0, s1],
                [a] => [&mut a.joints, s0, s1, s2],
                [] | [_, _, _, _, _, ..] => continue,
            };
            solve_lanes(&problem, out);
        }
    }
}
