//! Forward kinematics: the joints' model-space transforms at a clip's frame, the mesh skinned
//! by them, and the rotation helpers the bakers share (an exact shortest arc, the angle
//! between two rotations).

use alloc::vec::Vec;

use glam::{Affine3A, Mat3, Mat3A, Quat, Vec3};

use super::Clip;
use crate::Error;
use crate::d3::Creature;
use crate::math::Roots;

/// [`Creature::pose`]: the joints' model-space transforms at frame `frame` of `clip` (clamped
/// to its last frame), the clip's tracks (any clip a caller passes: a track's missing frame or
/// joint falls back to the rest pose) over the rest translations, by forward kinematics.
pub(crate) fn pose(c: &Creature, clip: &Clip, frame: usize) -> Vec<Affine3A> {
    let joints = &c.skeleton.joints;
    let frame = frame.min(clip.frames.saturating_sub(1));
    let local_rest = c.skeleton.rest_translations();
    let mut local: Vec<Affine3A> = local_rest
        .iter()
        .map(|&t| Affine3A::from_translation(t))
        .collect();
    for track in &clip.tracks {
        let translation = track
            .translations
            .as_ref()
            .and_then(|t| t.get(frame).copied())
            .or_else(|| local_rest.get(track.joint).copied())
            .unwrap_or(Vec3::ZERO);
        let rotation = track
            .rotations
            .get(frame)
            .copied()
            .unwrap_or(Quat::IDENTITY);
        if let Some(l) = local.get_mut(track.joint) {
            *l = Affine3A::from_rotation_translation(rotation, translation);
        }
    }
    if let Some(root) = joints.iter().position(|j| j.parent.is_none())
        && let (Some(&t), Some(&r)) = (
            clip.root_translation.get(frame),
            clip.root_rotation.get(frame),
        )
        && let Some(l) = local.get_mut(root)
    {
        *l = Affine3A::from_rotation_translation(r, t);
    }
    forward_kinematics(joints, &local)
}

/// The mesh skinned by the joints' model-space transforms `pose` (one per joint, as
/// [`pose`] gives them; the rest pose's joints are pure translations).
pub(crate) fn skinned(c: &Creature, pose: &[Affine3A]) -> Result<Vec<Vec3>, Error> {
    let transforms: Vec<Affine3A> = pose
        .iter()
        .zip(&c.skeleton.joints)
        .map(|(m, j)| *m * Affine3A::from_translation(-j.position))
        .collect();
    let influences: Vec<creature_skin::Influences> = c
        .mesh
        .joints
        .iter()
        .zip(&c.mesh.weights)
        .map(|(&joints, &weights)| creature_skin::Influences { joints, weights })
        .collect();
    let mut out = alloc::vec![Vec3::ZERO; c.mesh.positions.len()];
    creature_skin::skin_positions(
        &c.mesh.positions,
        &influences,
        &transforms,
        creature_skin::Blend::Linear,
        &mut out,
    )?;
    Ok(out)
}

/// Model-space transforms from local ones, parents resolved by walking up each chain (parents
/// may come after children in the list).
pub(super) fn forward_kinematics(joints: &[crate::d3::Joint], local: &[Affine3A]) -> Vec<Affine3A> {
    let n = joints.len();
    let mut global: Vec<Option<Affine3A>> = alloc::vec![None; n];
    for start in 0..n {
        let mut chain = Vec::new();
        let mut at = Some(start);
        while let Some(j) = at {
            if global.get(j).is_some_and(Option::is_some) || chain.len() > n {
                break;
            }
            chain.push(j);
            at = joints.get(j).and_then(|j| j.parent);
        }
        let mut above = at
            .and_then(|j| global.get(j).copied().flatten())
            .unwrap_or(Affine3A::IDENTITY);
        for &j in chain.iter().rev() {
            above *= local.get(j).copied().unwrap_or(Affine3A::IDENTITY);
            if let Some(g) = global.get_mut(j) {
                *g = Some(above);
            }
        }
    }
    global
        .into_iter()
        .map(|g| g.unwrap_or(Affine3A::IDENTITY))
        .collect()
}

/// The angle (radians) of the rotation between unit quaternions `p` and `q`, accurate for
/// small angles too (`Quat::angle_between` takes an arc cosine of a dot product near 1, which
/// rounds angles below about 1e-3 to 0): for unit quaternions `|p − q| = 2 sin(θ / 4)`.
pub(super) fn angle_between(p: Quat, q: Quat) -> f32 {
    let d = (p - q).norm().min((p + q).norm());
    4.0 * crate::math::asin((0.5 * d).min(1.0))
}

/// A two-bone limb's knee as a hinge, its rest frame set up once for every frame: the hip's
/// rotation (in the limb's parent's frame at rest, here body space) and the knee's (in the
/// hip's frame) turning its segments' rest directions `rest` (upper, lower) to `now`, unit. The hip turns the upper segment
/// onto its direction and the rest's bend plane onto the present one, so the knee only bends
/// about its rest hinge axis: the shortest arc for the hip would twist the thigh as it swings
/// and turn the knee about a wandering axis (a sideways knee flicked through 70° between two
/// frames as the foot landed). A bend plane (the segments' cross product) comes from `pole`
/// across the hip-to-end direction where the limb is nearly straight.
#[derive(Debug, Clone, Copy)]
pub(super) struct Hinge {
    /// The lower segment's rest direction.
    rest_lower: Vec3,
    /// The rest frame (upper segment, bend normal, their cross product), inverted (in SIMD
    /// lanes: the product with it is the same, lane for lane, as with a `Mat3`).
    unframe: Mat3A,
    /// The knee's pole (the bend plane of a nearly straight limb).
    pole: Vec3,
}

impl Hinge {
    /// The hinge of a limb whose segments point along `rest` (upper, lower) at rest.
    pub(super) fn new(rest: (Vec3, Vec3), pole: Vec3) -> Self {
        Self {
            rest_lower: rest.1,
            unframe: Mat3A::from(bend_frame(rest, pole).transpose()),
            pole,
        }
    }

    /// The hip's and knee's rotations turning the limb's segments to `now` (the reference
    /// [`matrices`](Self::matrices) is tested against).
    #[cfg(test)]
    pub(super) fn rotations(&self, now: (Vec3, Vec3)) -> (Quat, Quat) {
        let hip =
            crate::math::quat_from_mat3a(&(Mat3A::from(bend_frame(now, self.pole)) * self.unframe))
                .unit();
        let knee = rotation_arc(self.rest_lower, hip.inverse() * now.1);
        (hip, knee)
    }

    /// The hip's and knee's rotations turning the limb's segments to `now`, as matrices: the
    /// hip's frame turned by the rest frame's inverse (no round trip through a quaternion), and
    /// the knee's [`rotation_arc`].
    pub(super) fn matrices(&self, now: (Vec3, Vec3)) -> (Mat3A, Mat3A) {
        let hip = Mat3A::from(bend_frame(now, self.pole)) * self.unframe;
        let knee = Mat3A::from_quat(rotation_arc(self.rest_lower, hip.transpose() * now.1));
        (hip, knee)
    }
}

/// The frame of a two-bone limb's segments `(upper, lower)`: the upper segment, the bend
/// plane's normal (from `pole` across the limb where it is nearly straight), and their cross
/// product.
fn bend_frame((upper, lower): (Vec3, Vec3), pole: Vec3) -> Mat3 {
    let bend = upper.cross(lower);
    let normal = if bend.length_squared() > 1e-6 {
        bend
    } else {
        pole.cross(upper + lower)
    };
    let normal = normal.reject_from_normalized(upper);
    let normal = normal
        .try_unit()
        .unwrap_or_else(|| upper.any_orthonormal_vector());
    Mat3::from_cols(upper, normal, upper.cross(normal))
}

/// The shortest rotation from unit vector `from` to unit vector `to`. Unlike
/// `Quat::from_rotation_arc`, which returns the identity below about 5e-4 rad (1.7 mm at the
/// foot of a 3.4 m leg), it is exact for small angles: (from × to, 1 + from · to) normalised.
pub(super) fn rotation_arc(from: Vec3, to: Vec3) -> Quat {
    let dot = from.dot(to);
    if dot < -1.0 + 1e-6 {
        // Nearly opposite: any half turn about an axis across `from`.
        return Quat::from_rotation_arc(from, to);
    }
    let axis = from.cross(to);
    Quat::from_xyzw(axis.x, axis.y, axis.z, 1.0 + dot).unit()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hinge_bends_the_knee_about_its_rest_axis() {
        // A leg at rest with its knee forward (hinge axis +X), then turned as a whole (swung
        // out and forward) with its knee bent 30° more: the hip carries the turn, the knee
        // only bends, about +X.
        let s = core::f32::consts::FRAC_1_SQRT_2;
        let rest = (Vec3::new(0.0, -s, s), Vec3::new(0.0, -s, -s));
        let turn = Quat::from_rotation_y(0.7) * Quat::from_rotation_z(0.4);
        let bend = Quat::from_rotation_x(-0.52);
        let now = (turn * rest.0, turn * bend * rest.1);
        for pole in [Vec3::Z, Vec3::X, Vec3::NEG_Y] {
            let (hip, knee) = Hinge::new(rest, pole).rotations(now);
            assert!((hip * rest.0).distance(now.0) < 1e-5);
            assert!((hip * knee * rest.1).distance(now.1) < 1e-5);
            let (axis, angle) = knee.to_axis_angle();
            assert!((angle - 0.52).abs() < 1e-4, "{angle}");
            assert!(axis.abs().distance(Vec3::X) < 1e-4, "{axis}");
        }
        // Straight at rest and now: the bend plane comes from the pole, and nothing bends.
        let straight = (Vec3::NEG_Y, Vec3::NEG_Y);
        let turned = (turn * Vec3::NEG_Y, turn * Vec3::NEG_Y);
        let (hip, knee) = Hinge::new(straight, Vec3::Z).rotations(turned);
        assert!((hip * Vec3::NEG_Y).distance(turned.0) < 1e-5);
        assert!(knee.angle_between(Quat::IDENTITY) < 1e-4);
    }

    #[test]
    fn a_hinges_matrices_are_its_rotations() {
        // Limbs bent, straight and folded back, turned every way: the matrices the live
        // animator poses legs with turn as the quaternions do.
        let s = core::f32::consts::FRAC_1_SQRT_2;
        let close = |m: Mat3A, q: Quat| {
            let q = Mat3A::from_quat(q);
            [
                m.x_axis - q.x_axis,
                m.y_axis - q.y_axis,
                m.z_axis - q.z_axis,
            ]
            .iter()
            .all(|d| d.length() < 1e-5)
        };
        for k in 0..200 {
            let t = k as f32;
            let rest = if k % 2 == 0 {
                (Vec3::new(0.0, -s, s), Vec3::new(0.0, -s, -s))
            } else {
                (Vec3::NEG_Y, Vec3::NEG_Y)
            };
            let turn = Quat::from_rotation_y(0.7 * t)
                * Quat::from_rotation_z(0.4 * crate::math::sin(t))
                * Quat::from_rotation_x(0.3 * crate::math::cos(1.3 * t));
            // Bent from a little to 148° (folded further, the arc to the lower segment is
            // ill-conditioned: its axis a cross product of nearly opposite vectors).
            let bend = Quat::from_rotation_x(-0.013 * t);
            let now = (turn * rest.0, turn * bend * rest.1);
            for pole in [Vec3::Z, Vec3::X, Vec3::NEG_Y] {
                let hinge = Hinge::new(rest, pole);
                let (hip, knee) = hinge.rotations(now);
                let (hip_m, knee_m) = hinge.matrices(now);
                assert!(close(hip_m, hip), "{k} {pole}: hip {hip_m} against {hip}");
                assert!(
                    close(knee_m, knee),
                    "{k} {pole}: knee {knee_m} against {knee}"
                );
            }
        }
    }

    #[test]
    fn rotation_arc_is_exact_for_tiny_angles() {
        let from = Vec3::NEG_Y;
        for angle in [0.0f32, 1e-6, 1e-4, 4e-4, 1e-2, 1.0, 3.0] {
            let to = Quat::from_rotation_x(angle) * from;
            let q = rotation_arc(from, to);
            assert!(q.is_normalized());
            assert!(
                (q * from).distance(to) < 1e-6,
                "{angle}: {}",
                (q * from).distance(to)
            );
        }
        let q = rotation_arc(Vec3::X, Vec3::NEG_X);
        assert!((q * Vec3::X).distance(Vec3::NEG_X) < 1e-6);
    }
}
