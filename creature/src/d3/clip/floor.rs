//! Nothing under the floor: a clip's body poses leaned back or raised so that no body vertex
//! dips below `y = 0`, and knees turned so that they never bend through the ground.

use alloc::vec::Vec;

use glam::{Affine3A, Quat, Vec3, Vec4};

use creature_gait::{Leg, Pose};

use super::gait_run::GaitRun;
use crate::Error;
use crate::d3::{Creature, Part};

impl Creature {
    /// How far the mesh's vertices skinned to `joint` reach from its rest position: for a
    /// knee, the radius of the ring around it.
    pub(super) fn ring_radius(&self, joint: usize) -> f32 {
        let Some(centre) = self.skeleton.joints.get(joint).map(|j| j.position) else {
            return 0.0;
        };
        let mesh = &self.mesh;
        mesh.positions
            .iter()
            .zip(&mesh.joints)
            .zip(&mesh.weights)
            .filter(|((_, js), ws)| {
                js.iter()
                    .zip(ws.iter())
                    .any(|(&j, &w)| usize::from(j) == joint && w > 0.0)
            })
            .map(|((p, _), _)| p.distance(centre))
            .fold(0.0f32, f32::max)
    }

    /// The body's vertices, bent by `body_global` (the clip's constant spine pose in body
    /// space): the part of the mesh skinned to spine joints only.
    pub(super) fn body_shape(&self, body_global: &[Affine3A]) -> Result<Vec<Vec3>, Error> {
        let joints = &self.skeleton.joints;
        let spine = |j: u16| {
            joints
                .get(usize::from(j))
                .is_some_and(|j| j.part == Part::Spine)
        };
        let mesh = &self.mesh;
        Ok(super::skinned(self, body_global)?
            .into_iter()
            .zip(mesh.joints.iter().zip(&mesh.weights))
            .filter(|(_, (js, ws))| {
                js.iter()
                    .zip(ws.iter())
                    .all(|(&j, &w)| w == 0.0 || spine(j))
            })
            .map(|(s, _)| s)
            .collect())
    }

    /// The run's body poses, each changed as little as needed so that no vertex of the body
    /// (`shape`, as [`body_shape`](Self::body_shape) gives it for the clip's spine pose) is
    /// below the floor `y = 0`: first its lean (the rotation's swing away from the vertical
    /// axis) is scaled back toward none, then, if the upright body still dips, it is raised,
    /// but never so far that a planted foot leaves its leg's reach (`legs`, the run's). Frames
    /// that do not dip are returned unchanged, bit for bit.
    pub(super) fn above_the_floor(
        &self,
        mut shape: Vec<Vec3>,
        run: &GaitRun,
        legs: &[Leg],
    ) -> Vec<Pose> {
        // A vertex s of the body is at height (R s).y + t.y = u · s + t.y with u = Rᵀ ŷ. With
        // |u − ŷ| ≤ δ over the clip (less lean only brings u closer to ŷ), u · s lies within
        // δ|s| of s.y: only the vertices that can be lowest in some frame are kept.
        let delta = run
            .bodies
            .iter()
            .map(|b| (b.rotation.inverse() * Vec3::Y - Vec3::Y).length())
            .fold(0.0f32, f32::max);
        let bound = shape
            .iter()
            .map(|s| s.y + delta * s.length())
            .fold(f32::INFINITY, f32::min);
        shape.retain(|s| s.y - delta * s.length() <= bound);
        // Four vertices at a time, one per SIMD lane (the last four padded with their first):
        // each lane's `up · s` is the scalar dot product, bit for bit, and the least of them
        // the same whatever the order.
        let lanes: Vec<[Vec4; 3]> = shape
            .chunks(4)
            .map(|four| {
                let at = |k: usize| four.get(k).unwrap_or(&four[0]);
                let lane = |axis: fn(&Vec3) -> f32| {
                    Vec4::new(axis(at(0)), axis(at(1)), axis(at(2)), axis(at(3)))
                };
                [lane(|v| v.x), lane(|v| v.y), lane(|v| v.z)]
            })
            .collect();
        let low = |rotation: Quat, height: f32| {
            let up = rotation.inverse() * Vec3::Y;
            let (ux, uy, uz) = (Vec4::splat(up.x), Vec4::splat(up.y), Vec4::splat(up.z));
            // `min` keeps the running least (a NaN height is passed over, as `f32::min` does).
            let least = lanes
                .iter()
                .fold(Vec4::INFINITY, |least, [x, y, z]| {
                    (ux * *x + uy * *y + uz * *z).min(least)
                })
                .min_element();
            least + height
        };
        run.bodies
            .iter()
            .enumerate()
            .map(|(frame, &body)| {
                if low(body.rotation, body.translation.y) >= 0.0 {
                    return body;
                }
                // The heading: the rotation's twist about the vertical axis.
                let q = body.rotation;
                let twist = glam::Vec2::new(q.y, q.w);
                let heading = if twist.length_squared() > 1e-12 {
                    let twist = twist.normalize();
                    Quat::from_xyzw(0.0, twist.x, 0.0, twist.y)
                } else {
                    Quat::IDENTITY
                };
                let leaned = |share: f32| heading.slerp(q, share).normalize();
                let mut rotation = heading;
                if low(heading, body.translation.y) >= 0.0 {
                    // Bisection on the share of the lean kept.
                    let (mut keep, mut drop) = (0.0f32, 1.0f32);
                    for _ in 0..FLOOR_BISECTIONS {
                        let mid = 0.5 * (keep + drop);
                        if low(leaned(mid), body.translation.y) >= 0.0 {
                            keep = mid;
                        } else {
                            drop = mid;
                        }
                    }
                    rotation = leaned(keep);
                }
                let mut pose = Pose {
                    rotation,
                    translation: body.translation,
                };
                let needed = -low(rotation, body.translation.y);
                if needed > 0.0 {
                    // Raise, as far as the planted feet allow.
                    let mut lift = needed;
                    for (i, leg) in legs.iter().enumerate() {
                        if !run.planted(frame, i) {
                            continue;
                        }
                        let hip = pose.transform_point(leg.hip);
                        let foot = run.foot(frame, i);
                        let reach = leg.upper + leg.lower;
                        // |foot − (hip + ŷ l)| ≤ reach: l ≤ (foot − hip).y + √(reach² − d²),
                        // d the horizontal distance.
                        let d = foot - hip;
                        let across2 = d.x * d.x + d.z * d.z;
                        let room = d.y + crate::math::sqrt((reach * reach - across2).max(0.0));
                        lift = lift.min(room.max(0.0));
                    }
                    pose.translation.y += lift;
                }
                pose
            })
            .collect()
    }
}

/// Bisection steps on the share of a body's lean kept to hold it above the floor.
const FLOOR_BISECTIONS: usize = 16;

/// The knee `middle` of a solved two-bone chain from `root` to `end`, turned about the
/// root–end axis as little as needed so that its height along `up` is at least `floor` (as
/// high as it can go when no turn reaches that): a knee never bends through the ground. The
/// chain's bone lengths and ends are unchanged; a knee already high enough is returned as is.
pub(super) fn knee_above(root: Vec3, middle: Vec3, end: Vec3, up: Vec3, floor: f32) -> Vec3 {
    if up.dot(middle) >= floor {
        return middle;
    }
    let Some(dir) = (end - root).try_normalize() else {
        return middle;
    };
    let centre = root + dir * dir.dot(middle - root);
    let offset = middle - centre;
    let across = offset.length();
    if !(across > 0.0) {
        return middle;
    }
    let b1 = offset / across;
    let b2 = dir.cross(b1);
    // Height of the knee turned by φ: h(φ) = c + across (cos φ u₁ + sin φ u₂).
    let c = up.dot(centre);
    let (u1, u2) = (up.dot(b1), up.dot(b2));
    let m = crate::math::sqrt(u1 * u1 + u2 * u2);
    if !(m > 1e-9) {
        return middle;
    }
    let (u1, u2) = (u1 / m, u2 / m);
    // The turn (cos φ, sin φ) whose height is `floor`, nearest to no turn; the highest knee
    // when even that is too low.
    let k = (floor - c) / (across * m);
    let (cos, sin) = if k >= 1.0 {
        (u1, u2)
    } else {
        let k = k.max(-1.0);
        let w = crate::math::sqrt((1.0 - k * k).max(0.0));
        let a = (k * u1 - w * u2, k * u2 + w * u1);
        let b = (k * u1 + w * u2, k * u2 - w * u1);
        if a.0 >= b.0 { a } else { b }
    };
    centre + across * (cos * b1 + sin * b2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_knee_turns_just_above_the_floor_keeping_its_bones() {
        let (root, end) = (Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.2, 1.2));
        // A knee bent down, below y = 0.3.
        let knee = Vec3::new(0.0, 0.1, 0.4);
        let (upper, lower) = (root.distance(knee), end.distance(knee));
        let lifted = knee_above(root, knee, end, Vec3::Y, 0.3);
        assert!((lifted.y - 0.3).abs() < 1e-5, "{lifted}");
        assert!((root.distance(lifted) - upper).abs() < 1e-5);
        assert!((end.distance(lifted) - lower).abs() < 1e-5);
        // The smaller of the two turns: it stays on the side it was (x < 0 or x > 0 are
        // equally near here; either keeps the bones).
        assert_eq!(knee_above(root, knee, end, Vec3::Y, 0.05), knee);
        // Out of reach of any turn: the highest knee.
        let highest = knee_above(root, knee, end, Vec3::Y, 5.0);
        for k in 0..64 {
            let turn = Quat::from_axis_angle((end - root).normalize(), k as f32 * 0.1);
            let other = root + turn * (knee - root);
            assert!(other.y <= highest.y + 1e-5);
        }
    }
}
