//! Forward kinematics: the joints' model-space transforms at a clip's frame, the mesh skinned
//! by them, and the rotation helpers the bakers share (an exact shortest arc, the angle
//! between two rotations).

use alloc::vec::Vec;

use glam::{Affine3A, Mat3, Mat3A, Mat4, Quat, Vec3, Vec3A, Vec4};

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
    #[cfg(test)]
    pub(super) fn matrices(&self, now: (Vec3, Vec3)) -> (Mat3A, Mat3A) {
        let hip = Mat3A::from(bend_frame(now, self.pole)) * self.unframe;
        let knee = Mat3A::from_quat(rotation_arc(self.rest_lower, hip.transpose() * now.1));
        (hip, knee)
    }
}

/// Three coordinates of four vectors, a SIMD lane each.
type Lanes3 = [Vec4; 3];

/// The cross product of four pairs of vectors, lane for lane.
#[inline(always)]
fn cross4(a: &Lanes3, b: &Lanes3) -> Lanes3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The dot product of four pairs of vectors, lane for lane.
#[inline(always)]
fn dot4(a: &Lanes3, b: &Lanes3) -> Vec4 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Four vectors in lanes.
#[inline(always)]
fn lanes3(v: [Vec3; 4]) -> Lanes3 {
    let m = Mat4::from_cols(
        v[0].extend(0.0),
        v[1].extend(0.0),
        v[2].extend(0.0),
        v[3].extend(0.0),
    )
    .transpose();
    [m.x_axis, m.y_axis, m.z_axis]
}

/// Four vectors out of lanes.
#[inline(always)]
fn unlanes3(v: &Lanes3) -> [Vec3A; 4] {
    let m = Mat4::from_cols(v[0], v[1], v[2], Vec4::ZERO).transpose();
    [m.x_axis, m.y_axis, m.z_axis, m.w_axis].map(Vec3A::from_vec4)
}

/// Four [`Hinge`]s in SIMD lanes (a group of four limbs, the last group padded with its last
/// limb): their [`matrices`](Self::matrices) made together, the long chains of square roots
/// and divisions of four limbs side by side.
#[derive(Debug, Clone, Copy)]
pub(super) struct HingeLanes {
    rest_lower: Lanes3,
    /// The rest frame's inverse, column by column.
    unframe: [Lanes3; 3],
    pole: Lanes3,
}

impl HingeLanes {
    /// The lanes of `hinges` (one to four, a group of a creature's limbs; the lanes past them
    /// repeat the last).
    pub(super) fn new(hinges: &[Hinge]) -> Self {
        debug_assert!((1..=4).contains(&hinges.len()));
        let last = hinges.len() - 1;
        let pick =
            |f: &dyn Fn(&Hinge) -> Vec3| lanes3(core::array::from_fn(|l| f(&hinges[l.min(last)])));
        Self {
            rest_lower: pick(&|h| h.rest_lower),
            unframe: [
                pick(&|h| h.unframe.x_axis.into()),
                pick(&|h| h.unframe.y_axis.into()),
                pick(&|h| h.unframe.z_axis.into()),
            ],
            pole: pick(&|h| h.pole),
        }
    }

    /// [`Hinge::matrices`] for the four limbs, lane for lane (the same arithmetic, four at a
    /// time): each limb's hip's and knee's rotations turning its segments to `now` (unit).
    pub(super) fn matrices(&self, now: [(Vec3, Vec3); 4]) -> [(Mat3A, Mat3A); 4] {
        let upper = lanes3(now.map(|n| n.0));
        let lower = lanes3(now.map(|n| n.1));
        // The bend frame: the upper segment, the bend plane's normal, their cross product.
        let bend = cross4(&upper, &lower);
        let bent = dot4(&bend, &bend).cmpgt(Vec4::splat(1e-6));
        let sum = [
            upper[0] + lower[0],
            upper[1] + lower[1],
            upper[2] + lower[2],
        ];
        let across = cross4(&self.pole, &sum);
        let normal: Lanes3 = core::array::from_fn(|c| Vec4::select(bent, bend[c], across[c]));
        let along = dot4(&normal, &upper);
        let mut normal: Lanes3 = core::array::from_fn(|c| normal[c] - upper[c] * along);
        let rcp = Vec4::ONE / sqrt4(dot4(&normal, &normal));
        let unit = rcp.is_finite_mask() & rcp.cmpgt(Vec4::ZERO);
        normal = core::array::from_fn(|c| normal[c] * rcp);
        if !unit.all() {
            normal = across_upper(normal, &upper, unit.bitmask());
        }
        let third = cross4(&upper, &normal);
        // The hip: the frame times the rest frame's inverse, column by column.
        let hip: [Lanes3; 3] = core::array::from_fn(|j| {
            let u = &self.unframe[j];
            core::array::from_fn(|c| upper[c] * u[0] + normal[c] * u[1] + third[c] * u[2])
        });
        // The lower segment in the hip's frame, and the knee's shortest arc to it from rest.
        let local = [
            dot4(&hip[0], &lower),
            dot4(&hip[1], &lower),
            dot4(&hip[2], &lower),
        ];
        let rest = &self.rest_lower;
        let dot = dot4(rest, &local);
        let axis = cross4(rest, &local);
        let w = Vec4::ONE + dot;
        let scale = Vec4::ONE / sqrt4(dot4(&axis, &axis) + w * w);
        let mut q = [axis[0] * scale, axis[1] * scale, axis[2] * scale, w * scale];
        let opposite = dot.cmplt(Vec4::splat(-1.0 + 1e-6));
        if opposite.any() {
            q = half_turns(q, rest, &local, opposite.bitmask());
        }
        let [x, y, z, w] = q;
        // The knee's matrix from its quaternion (as `Mat3A::from_quat`).
        let (x2, y2, z2) = (x + x, y + y, z + z);
        let (xx, xy, xz) = (x * x2, x * y2, x * z2);
        let (yy, yz, zz) = (y * y2, y * z2, z * z2);
        let (wx, wy, wz) = (w * x2, w * y2, w * z2);
        let knee = [
            [Vec4::ONE - (yy + zz), xy + wz, xz - wy],
            [xy - wz, Vec4::ONE - (xx + zz), yz + wx],
            [xz + wy, yz - wx, Vec4::ONE - (xx + yy)],
        ];
        let [h0, h1, h2] = hip.each_ref().map(unlanes3);
        let [k0, k1, k2] = knee.each_ref().map(unlanes3);
        core::array::from_fn(|l| {
            (
                Mat3A::from_cols(h0[l], h1[l], h2[l]),
                Mat3A::from_cols(k0[l], k1[l], k2[l]),
            )
        })
    }
}

/// [`HingeLanes::matrices`]' bend normals where a lane's is not a unit vector (a limb along its
/// pole: no bend plane; `unit` has bit `l` set where lane `l`'s is one): any unit vector
/// across that lane's upper segment (as `bend_frame`).
#[cold]
#[inline(never)]
fn across_upper(normal: Lanes3, upper: &Lanes3, unit: u32) -> Lanes3 {
    let mut lanes = unlanes3(&normal);
    let ups = unlanes3(upper);
    for (l, n) in lanes.iter_mut().enumerate() {
        if unit & (1 << l) == 0 {
            *n = ups[l].any_orthonormal_vector();
        }
    }
    lanes3(lanes.map(Vec3::from))
}

/// [`HingeLanes::matrices`]' knee quaternions (`q`, its x, y, z and w lanes) where the lower
/// segment turned nearly opposite its rest direction (`opposite`): any half turn about an axis
/// across the rest direction (as [`rotation_arc`]); `opposite` has bit `l` set for lane `l`.
#[cold]
#[inline(never)]
fn half_turns(q: [Vec4; 4], rest: &Lanes3, local: &Lanes3, opposite: u32) -> [Vec4; 4] {
    let (rests, locals) = (unlanes3(rest), unlanes3(local));
    let mut q = q.map(|v| v.to_array());
    for l in 0..4 {
        if opposite & (1 << l) != 0 {
            let arc = Quat::from_rotation_arc(rests[l].into(), locals[l].into());
            (q[0][l], q[1][l], q[2][l], q[3][l]) = (arc.x, arc.y, arc.z, arc.w);
        }
    }
    q.map(Vec4::from_array)
}

/// Four square roots, lane for lane (exactly rounded, as [`crate::math::sqrt`]).
#[inline(always)]
fn sqrt4(v: Vec4) -> Vec4 {
    #[cfg(not(feature = "libm"))]
    return v.sqrt();
    #[cfg(feature = "libm")]
    return Vec4::from_array(v.to_array().map(crate::math::sqrt));
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
    fn hinge_lanes_are_four_hinges() {
        // Four limbs at a time (rests, poles and bends of every kind, the last group of a
        // creature's limbs padded), and the rare cases lane by lane: a straight limb along its
        // pole (no bend plane) and a knee folded right back (no shortest arc): each lane's
        // matrices those of its hinge alone, and they turn as its quaternions do.
        let s = core::f32::consts::FRAC_1_SQRT_2;
        let near = |a: Mat3A, b: Mat3A, within: f32| {
            [
                a.x_axis - b.x_axis,
                a.y_axis - b.y_axis,
                a.z_axis - b.z_axis,
            ]
            .iter()
            .all(|d| d.length() <= within)
        };
        let rests = [
            (Vec3::new(0.0, -s, s), Vec3::new(0.0, -s, -s)),
            (Vec3::NEG_Y, Vec3::NEG_Y),
            (Vec3::new(s, -s, 0.0), Vec3::NEG_Y),
        ];
        let poles = [Vec3::Z, Vec3::X, Vec3::NEG_Y, Vec3::new(0.6, 0.0, 0.8)];
        let mut cases = Vec::new();
        for k in 0..120 {
            let t = k as f32;
            let rest = rests[k % 3];
            let turn = Quat::from_rotation_y(0.7 * t)
                * Quat::from_rotation_z(0.4 * crate::math::sin(t))
                * Quat::from_rotation_x(0.3 * crate::math::cos(1.3 * t));
            let bend = Quat::from_rotation_x(-0.02 * t);
            cases.push((rest, poles[k % 4], (turn * rest.0, turn * bend * rest.1)));
        }
        // Straight along its pole, and folded right back.
        cases.push((
            (Vec3::NEG_Y, Vec3::NEG_Y),
            Vec3::NEG_Y,
            (Vec3::NEG_Y, Vec3::NEG_Y),
        ));
        cases.push(((Vec3::NEG_Y, Vec3::NEG_Y), Vec3::Z, (Vec3::NEG_Y, Vec3::Y)));
        for group in cases.chunks(4) {
            let hinges: Vec<Hinge> = group.iter().map(|&(r, p, _)| Hinge::new(r, p)).collect();
            let now = core::array::from_fn(|l| group[l.min(group.len() - 1)].2);
            let lanes = HingeLanes::new(&hinges).matrices(now);
            for ((hinge, &(rest, _, now)), (hip, knee)) in hinges.iter().zip(group).zip(lanes) {
                let (hip_m, knee_m) = hinge.matrices(now);
                assert!(near(hip, hip_m, 1e-6), "{now:?}: hip {hip} against {hip_m}");
                assert!(
                    near(knee, knee_m, 1e-6),
                    "{now:?}: knee {knee} against {knee_m}"
                );
                // The segments turned onto `now`.
                assert!((hip * rest.0).distance(now.0) < 1e-5, "{now:?}");
                assert!((hip * knee * rest.1).distance(now.1) < 1e-5, "{now:?}");
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
