//! The legs four at a time in SIMD lanes, and their two-bone IK after the body's reaction and
//! the blend weight.

use glam::{Mat3A, Vec3, Vec4};

use super::{Controller, LegState};
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

impl Controller {
    /// The feet the action placed, four legs at a time (`feet`), for the reaction, the reach
    /// check and the IK; missing lanes repeat the first leg.
    pub(super) fn gather_feet(&mut self) {
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
}
