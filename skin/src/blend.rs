//! Skinning: moving rest-pose vertices and normals by blended joint transforms.

use alloc::vec::Vec;

use glam::{Affine3A, Mat3A, Quat, Vec3, Vec3A, Vec4};

use crate::error::SkinError;
use crate::influences::{Influences, MAX_INFLUENCES};

/// How the transforms of a vertex's joints are combined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Blend {
    /// Linear blend skinning: the weighted average of the joints' affine transforms. Exact for
    /// any affine transform (scale and shear included), but a joint twisted far from its rest
    /// pose pinches the skin (the "candy-wrapper" effect).
    #[default]
    Linear,
    /// Dual-quaternion skinning (Kavan et al. 2007): the weighted average of the joints' rigid
    /// motions, renormalised, so twisted joints keep their volume. Uses only each transform's
    /// rotation and translation: scale and shear are ignored, and a transform whose linear part
    /// is singular is an error ([`SkinError::SingularTransform`]).
    DualQuaternion,
}

/// Skins rest-pose positions: `out[i]` is `rest[i]` moved by its joints' transforms blended with
/// its weights.
///
/// `transforms[j]` is joint `j`'s skinning transform: its current world transform times the
/// inverse of its bind (rest) transform, so that identity transforms leave the mesh at rest. For
/// `Mat4` skinning matrices, convert with [`Affine3A::from_mat4`].
///
/// Weights should sum to 1, as every constructor in this crate makes them (and glTF requires).
/// Linear blending uses them as given, without dividing by their sum per vertex: it evaluates
/// `(I + Σ wᵢ (Mᵢ − I)) p`, so identity transforms reproduce the rest mesh exactly, a vertex whose
/// weights are all zero stays at its rest position, and weights summing to `s` apply `s` times
/// the blended motion (quantised weights read back as `byte / 255` sum to 1 within rounding, so
/// the difference is at the last bits). Dual quaternions are normalised by construction, so
/// their weights' scale never matters.
///
/// The linear path runs one tight pass with two cheap running checks (the smallest weight and
/// the sum of the outputs); only if those find something does it go over the vertices again,
/// checking each in turn, to return the error below for the first bad one.
///
/// ```
/// use creature_skin::{glam::{Affine3A, Vec3}, skin_positions, Blend, Influences};
///
/// let rest = [Vec3::new(0.0, 0.0, 1.0)];
/// let influences = [Influences { joints: [0, 1, 0, 0], weights: [0.5, 0.5, 0.0, 0.0] }];
/// let transforms = [Affine3A::IDENTITY, Affine3A::from_translation(Vec3::Y * 2.0)];
/// let mut out = [Vec3::ZERO];
/// skin_positions(&rest, &influences, &transforms, Blend::Linear, &mut out)?;
/// assert_eq!(out[0], Vec3::new(0.0, 1.0, 1.0));
/// # Ok::<(), creature_skin::SkinError>(())
/// ```
///
/// # Errors
/// - [`SkinError::WrongLength`] unless `influences` and `out` have one entry per position;
/// - [`SkinError::NonFinite`] for a non-finite position or transform;
/// - [`SkinError::InvalidWeights`] / [`SkinError::JointOutOfRange`] for a vertex with a
///   negative or non-finite weight, or a positive weight on a joint with no transform;
/// - [`SkinError::SingularTransform`] (dual quaternions only) for a used joint without rotation;
/// - [`SkinError::NonFiniteResult`] if a position overflows.
///
/// Each vertex is checked in turn (position, weights and joints, result), and the first problem
/// is returned. On error, `out` may have been partly written.
pub fn skin_positions(
    rest: &[Vec3],
    influences: &[Influences],
    transforms: &[Affine3A],
    blend: Blend,
    out: &mut [Vec3],
) -> Result<(), SkinError> {
    check_lengths(rest.len(), influences.len(), out.len())?;
    check_transforms(transforms)?;
    match blend {
        Blend::Linear => {
            // One delta per joint, and a poisoned stand-in for every joint beyond them.
            let mut deltas: Vec<Delta> = transforms.iter().map(Delta::new).collect();
            deltas.push(Delta::POISON);
            if !linear_positions(rest, influences, &deltas, out) {
                let deltas = deltas.get(..transforms.len()).unwrap_or_default();
                // Something needs a closer look: redo every vertex with every check, naming the
                // first problem, in vertex order. (Valid vertices get the same bits again.)
                for (i, ((&p, inf), o)) in
                    rest.iter().zip(influences).zip(out.iter_mut()).enumerate()
                {
                    finite_input("position", i, p)?;
                    weight_sum(i, inf, deltas.len())?;
                    let used = inf
                        .joints
                        .map(|j| deltas.get(usize::from(j)).unwrap_or(&Delta::ZERO));
                    *o = finite_output(i, Delta::blend(used, inf.weights).apply(p))?;
                }
            }
        }
        Blend::DualQuaternion => {
            let dual = dual_quaternions(transforms);
            for (i, ((&p, inf), o)) in rest.iter().zip(influences).zip(out.iter_mut()).enumerate() {
                let p = finite_input("position", i, p)?;
                let moved = match blend_dual(i, inf, &dual)? {
                    Some((r, t)) => r * p + t,
                    None => p,
                };
                *o = finite_output(i, moved)?;
            }
        }
    }
    Ok(())
}

/// Skins rest-pose normals with the same blend as [`skin_positions`]; the results are unit
/// length.
///
/// Linear blending transforms each normal by the inverse transpose of the blended linear part
/// (through its cofactor matrix, so no inverse is taken), which is right for non-uniform scale
/// too. Dual quaternions rotate it by the blended rotation. A normal whose transform is singular
/// there, and a vertex with all-zero weights, keep their rest direction; a zero rest normal
/// stays zero.
///
/// ```
/// use creature_skin::{glam::{Affine3A, Vec3}, skin_normals, Blend, Influences};
///
/// let normals = [Vec3::X];
/// let influences = [Influences::single(0)];
/// let quarter_turn = Affine3A::from_rotation_y(core::f32::consts::FRAC_PI_2);
/// let mut out = [Vec3::ZERO];
/// skin_normals(&normals, &influences, &[quarter_turn], Blend::DualQuaternion, &mut out)?;
/// assert!(out[0].abs_diff_eq(-Vec3::Z, 1e-6));
/// # Ok::<(), creature_skin::SkinError>(())
/// ```
///
/// # Errors
/// As [`skin_positions`], with `"normal"` for a non-finite rest normal.
pub fn skin_normals(
    rest_normals: &[Vec3],
    influences: &[Influences],
    transforms: &[Affine3A],
    blend: Blend,
    out: &mut [Vec3],
) -> Result<(), SkinError> {
    check_lengths(rest_normals.len(), influences.len(), out.len())?;
    check_transforms(transforms)?;
    let dual = match blend {
        Blend::Linear => Vec::new(),
        Blend::DualQuaternion => dual_quaternions(transforms),
    };
    for (i, ((&n, inf), o)) in rest_normals
        .iter()
        .zip(influences)
        .zip(out.iter_mut())
        .enumerate()
    {
        let n = finite_input("normal", i, n)?;
        let rest = crate::math::normalize_or(n, Vec3A::ZERO);
        let moved = match blend {
            Blend::Linear => {
                let sum = weight_sum(i, inf, transforms.len())?;
                if sum > 0.0 {
                    // Weights as given: the direction does not depend on their scale.
                    let mut m = Mat3A::ZERO;
                    for (j, w) in inf.iter() {
                        m += transforms[usize::from(j)].matrix3 * w;
                    }
                    // cof(M) = det(M) M⁻ᵀ; flip for mirrors so the direction is M⁻ᵀ n's.
                    let cofactor = Mat3A::from_cols(
                        m.y_axis.cross(m.z_axis),
                        m.z_axis.cross(m.x_axis),
                        m.x_axis.cross(m.y_axis),
                    );
                    let sign = if m.determinant() < 0.0 { -1.0 } else { 1.0 };
                    crate::math::normalize_or(cofactor * n * sign, rest)
                } else {
                    rest
                }
            }
            Blend::DualQuaternion => match blend_dual(i, inf, &dual)? {
                Some((r, _)) => crate::math::normalize_or(r * n, rest),
                None => rest,
            },
        };
        *o = Vec3::from(moved);
    }
    Ok(())
}

/// A joint's skinning transform minus the identity, so that blending these with the weights and
/// adding the result to `p` leaves `p` exactly where it is for identity transforms and for a
/// vertex with no weight.
#[derive(Clone, Copy)]
struct Delta {
    x: Vec3A,
    y: Vec3A,
    z: Vec3A,
    t: Vec3A,
}

impl Delta {
    const ZERO: Self = Self {
        x: Vec3A::ZERO,
        y: Vec3A::ZERO,
        z: Vec3A::ZERO,
        t: Vec3A::ZERO,
    };

    /// `Σ dᵢ wᵢ`.
    #[inline(always)]
    fn blend(d: [&Self; MAX_INFLUENCES], w: [f32; MAX_INFLUENCES]) -> Self {
        let [d0, d1, d2, d3] = d;
        let [w0, w1, w2, w3] = w;
        Self {
            x: d0.x * w0 + d1.x * w1 + d2.x * w2 + d3.x * w3,
            y: d0.y * w0 + d1.y * w1 + d2.y * w2 + d3.y * w3,
            z: d0.z * w0 + d1.z * w1 + d2.z * w2 + d3.z * w3,
            t: d0.t * w0 + d1.t * w1 + d2.t * w2 + d3.t * w3,
        }
    }

    /// Stands in for a joint with no transform in the fast pass: NaN, so that the vertex's
    /// output is NaN, and the vertex is redone with every check.
    const POISON: Self = Self {
        x: Vec3A::NAN,
        y: Vec3A::NAN,
        z: Vec3A::NAN,
        t: Vec3A::NAN,
    };

    /// `p` moved by the blended delta: `(I + D) p`, with the identity added column by column,
    /// so a zero delta gives `p` back exactly (up to the sign of a zero).
    #[inline(always)]
    fn apply(&self, p: Vec3) -> Vec3A {
        (self.x + Vec3A::X) * p.x + (self.y + Vec3A::Y) * p.y + (self.z + Vec3A::Z) * p.z + self.t
    }

    fn new(t: &Affine3A) -> Self {
        let m = t.matrix3 - Mat3A::IDENTITY;
        Self {
            x: m.x_axis,
            y: m.y_axis,
            z: m.z_axis,
            t: t.translation,
        }
    }
}

/// Linear blend skinning of positions in one tight pass: `out[i] = p + Σ wⱼ (Mⱼ − I) p`, with
/// the weights used as given. Returns false if the result cannot be trusted as it is, so that
/// the caller redoes the vertices with every check: a negative weight, or a non-finite output.
/// A non-finite position, a NaN or infinite weight always give a non-finite output, and so does
/// any slot naming a joint with no transform (it reads [`Delta::POISON`], which the caller puts
/// last in `deltas`), whether that is an error (a positive weight) or not (an empty slot).
///
/// The checks cost two vector operations per vertex (a minimum of the weights, a sum of the
/// outputs; the joint lookups clamp the index, a compare and a conditional move each, which
/// indexing needs anyway) and no branch: they are what keeps a bad input from coming out as NaN
/// or as silently wrong positions.
fn linear_positions(
    rest: &[Vec3],
    influences: &[Influences],
    deltas: &[Delta],
    out: &mut [Vec3],
) -> bool {
    // The smallest weight seen. (A NaN weight is skipped here, but gives a NaN output.)
    let mut smallest = Vec4::ZERO;
    // Finite while every output is finite (a non-finite output makes the sum non-finite; a sum
    // overflowing from finite outputs only sends the caller down the slow path, which finds
    // nothing wrong and gives the same result).
    let mut total = Vec3A::ZERO;
    // Joints past the last transform read the poisoned stand-in at the end.
    let stand_in = deltas.len().saturating_sub(1);
    for ((&p, inf), o) in rest.iter().zip(influences).zip(out.iter_mut()) {
        smallest = Vec4::from_array(inf.weights).min(smallest);
        let used = inf.joints.map(|j| {
            deltas
                .get(usize::from(j).min(stand_in))
                .unwrap_or(&Delta::POISON)
        });
        let moved = Delta::blend(used, inf.weights).apply(p);
        total += moved;
        *o = Vec3::from(moved);
    }
    smallest.cmpge(Vec4::ZERO).all() && total.is_finite()
}

fn check_lengths(vertices: usize, influences: usize, out: usize) -> Result<(), SkinError> {
    if influences != vertices {
        return Err(SkinError::WrongLength {
            what: "influences",
            expected: vertices,
            found: influences,
        });
    }
    if out != vertices {
        return Err(SkinError::WrongLength {
            what: "output",
            expected: vertices,
            found: out,
        });
    }
    Ok(())
}

fn check_transforms(transforms: &[Affine3A]) -> Result<(), SkinError> {
    match transforms.iter().position(|t| !t.is_finite()) {
        Some(index) => Err(SkinError::NonFinite {
            what: "transform",
            index,
        }),
        None => Ok(()),
    }
}

#[inline]
fn finite_input(what: &'static str, index: usize, v: Vec3) -> Result<Vec3A, SkinError> {
    if v.is_finite() {
        Ok(Vec3A::from(v))
    } else {
        Err(SkinError::NonFinite { what, index })
    }
}

#[inline]
fn finite_output(index: usize, v: Vec3A) -> Result<Vec3, SkinError> {
    if v.is_finite() {
        Ok(Vec3::from(v))
    } else {
        Err(SkinError::NonFiniteResult { index })
    }
}

/// The sum of a vertex's weights, after checking them and their joints.
#[inline]
fn weight_sum(vertex: usize, inf: &Influences, joints: usize) -> Result<f32, SkinError> {
    let w = Vec4::from_array(inf.weights);
    // NaN fails `>= 0`; infinity fails `is_finite`.
    if !(w.cmpge(Vec4::ZERO).all() && w.is_finite()) {
        return Err(SkinError::InvalidWeights { vertex });
    }
    // Fast path: every slot's joint exists (canonical empty slots name joint 0).
    if !inf.joints.iter().all(|&j| usize::from(j) < joints)
        && let Some((joint, _)) = inf.iter().find(|&(j, _)| usize::from(j) >= joints)
    {
        return Err(SkinError::JointOutOfRange {
            vertex,
            joint,
            joints,
        });
    }
    Ok(w.element_sum())
}

/// A joint's rigid motion as a unit dual quaternion `(real, dual)`, or `None` when its linear
/// part has no rotation.
type Dual = Option<(Vec4, Vec4)>;

fn dual_quaternions(transforms: &[Affine3A]) -> Vec<Dual> {
    transforms
        .iter()
        .map(|t| {
            let rotation = rotation_of(t.matrix3)?;
            let tr = t.translation;
            // dual = ½ (0, t) ⊗ real
            let dual = Quat::from_xyzw(tr.x, tr.y, tr.z, 0.0) * rotation * 0.5;
            Some((Vec4::from(rotation), Vec4::from(dual)))
        })
        .collect()
}

/// The rotation of a linear map by Gram–Schmidt on its first two columns (scale, shear and any
/// mirror are dropped), or `None` when the map is singular to single precision.
fn rotation_of(m: Mat3A) -> Option<Quat> {
    // Reject maps that are flat to single precision: |det| against the product of the column
    // lengths (1 for a rotation, 0 for zero, parallel or coplanar columns).
    let lengths = m.x_axis.length() * m.y_axis.length() * m.z_axis.length();
    if !(m.determinant().abs() > 1e-6 * lengths) {
        return None;
    }
    let x = m.x_axis.try_normalize()?;
    let y = (m.y_axis - x * x.dot(m.y_axis)).try_normalize()?;
    let z = x.cross(y);
    Some(Quat::from_mat3a(&Mat3A::from_cols(x, y, z)).normalize())
}

/// Blends a vertex's dual quaternions; returns the rotation and translation, or `None` for a
/// vertex with no weight.
fn blend_dual(
    vertex: usize,
    inf: &Influences,
    dual: &[Dual],
) -> Result<Option<(Quat, Vec3A)>, SkinError> {
    let sum = weight_sum(vertex, inf, dual.len())?;
    if !(sum > 0.0) {
        return Ok(None);
    }
    let mut real = Vec4::ZERO;
    let mut du = Vec4::ZERO;
    let mut pivot: Option<Vec4> = None;
    for (j, w) in inf.iter() {
        let index = usize::from(j);
        let Some(Some((r, d))) = dual.get(index).copied() else {
            return Err(SkinError::SingularTransform { joint: index });
        };
        // Take the shorter way round: align every rotation with the first one.
        let pivot = *pivot.get_or_insert(r);
        let w = if pivot.dot(r) < 0.0 { -w } else { w };
        real += r * w;
        du += d * w;
    }
    // Aligned unit quaternions with positive weights cannot cancel: |real| ≥ the first weight.
    let len = real.length();
    if !(len > 0.0) {
        return Ok(None);
    }
    let r = real / len;
    let d = du / len;
    let (rv, dv) = (Vec3A::from(r.truncate()), Vec3A::from(d.truncate()));
    let t = (dv * r.w - rv * d.w + rv.cross(dv)) * 2.0;
    Ok(Some((Quat::from_vec4(r), t)))
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO: [Influences; 1] = [Influences {
        joints: [0, 1, 0, 0],
        weights: [0.5, 0.5, 0.0, 0.0],
    }];

    #[test]
    fn identity_leaves_the_rest_pose_exactly() {
        let rest = [Vec3::new(0.3, -1.2, 4.5)];
        let transforms = [Affine3A::IDENTITY; 2];
        for blend in [Blend::Linear, Blend::DualQuaternion] {
            let mut out = [Vec3::ZERO];
            skin_positions(&rest, &TWO, &transforms, blend, &mut out).unwrap();
            assert_eq!(out, rest, "{blend:?}");
        }
    }

    #[test]
    fn unbound_vertices_stay_at_rest() {
        let rest = [Vec3::ONE];
        let far = [Affine3A::from_translation(Vec3::X * 9.0)];
        let mut out = [Vec3::ZERO];
        for blend in [Blend::Linear, Blend::DualQuaternion] {
            skin_positions(&rest, &[Influences::NONE], &far, blend, &mut out).unwrap();
            assert_eq!(out, rest);
        }
    }

    #[test]
    fn dual_quaternions_keep_volume_where_linear_pinches() {
        // A point 1 off the twist axis, half bound to a joint twisted by 180°.
        let rest = [Vec3::new(1.0, 0.0, 0.0)];
        let twist = Affine3A::from_rotation_z(core::f32::consts::PI);
        let transforms = [Affine3A::IDENTITY, twist];
        let mut lbs = [Vec3::ZERO];
        let mut dqs = [Vec3::ZERO];
        skin_positions(&rest, &TWO, &transforms, Blend::Linear, &mut lbs).unwrap();
        skin_positions(&rest, &TWO, &transforms, Blend::DualQuaternion, &mut dqs).unwrap();
        // LBS collapses the point onto the axis; DQS turns it by 90° and keeps the radius.
        assert!(lbs[0].length() < 1e-6, "{}", lbs[0]);
        assert!((dqs[0].length() - 1.0).abs() < 1e-5, "{}", dqs[0]);
    }

    #[test]
    fn dual_quaternions_follow_a_rigid_joint_exactly() {
        let rest = [Vec3::new(1.0, 2.0, 3.0)];
        let m = Affine3A::from_rotation_translation(
            Quat::from_rotation_y(0.7) * Quat::from_rotation_x(-0.3),
            Vec3::new(4.0, -1.0, 0.5),
        );
        let mut out = [Vec3::ZERO];
        skin_positions(
            &rest,
            &[Influences::single(0)],
            &[m],
            Blend::DualQuaternion,
            &mut out,
        )
        .unwrap();
        assert!(
            out[0].abs_diff_eq(m.transform_point3(rest[0]), 1e-5),
            "{}",
            out[0]
        );
    }

    #[test]
    fn normals_use_the_inverse_transpose() {
        // Squash x by 2: a normal tilted in x/y tilts further towards y.
        let squash = Affine3A::from_scale(Vec3::new(0.5, 1.0, 1.0));
        let n = [Vec3::new(1.0, 1.0, 0.0)];
        let mut out = [Vec3::ZERO];
        skin_normals(
            &n,
            &[Influences::single(0)],
            &[squash],
            Blend::Linear,
            &mut out,
        )
        .unwrap();
        let expected = Vec3::new(2.0, 1.0, 0.0).normalize();
        assert!(out[0].abs_diff_eq(expected, 1e-6), "{}", out[0]);
        // A mirror keeps M⁻ᵀ n's direction.
        let mirror = Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0));
        skin_normals(
            &n,
            &[Influences::single(0)],
            &[mirror],
            Blend::Linear,
            &mut out,
        )
        .unwrap();
        assert!(out[0].abs_diff_eq(Vec3::new(-1.0, 1.0, 0.0).normalize(), 1e-6));
        // A singular blend keeps the rest direction.
        let flat = Affine3A::from_scale(Vec3::new(0.0, 1.0, 1.0));
        skin_normals(
            &n,
            &[Influences::single(0)],
            &[flat],
            Blend::Linear,
            &mut out,
        )
        .unwrap();
        assert!(
            out[0].abs_diff_eq(Vec3::new(1.0, 0.0, 0.0), 1e-6),
            "{}",
            out[0]
        );
    }

    #[test]
    fn bad_input_is_an_error() {
        let rest = [Vec3::ZERO];
        let one = [Affine3A::IDENTITY];
        let mut out = [Vec3::ZERO];
        let mut short: [Vec3; 0] = [];
        assert!(matches!(
            skin_positions(&rest, &[], &one, Blend::Linear, &mut out),
            Err(SkinError::WrongLength {
                what: "influences",
                ..
            })
        ));
        assert!(matches!(
            skin_positions(&rest, &TWO[..], &one, Blend::Linear, &mut short),
            Err(SkinError::WrongLength { what: "output", .. })
        ));
        assert_eq!(
            skin_positions(&rest, &TWO, &one, Blend::Linear, &mut out),
            Err(SkinError::JointOutOfRange {
                vertex: 0,
                joint: 1,
                joints: 1
            })
        );
        let nan = [Influences {
            joints: [0; 4],
            weights: [f32::NAN, 0.0, 0.0, 0.0],
        }];
        assert_eq!(
            skin_positions(&rest, &nan, &one, Blend::Linear, &mut out),
            Err(SkinError::InvalidWeights { vertex: 0 })
        );
        let bad = [Affine3A::from_translation(Vec3::NAN)];
        assert_eq!(
            skin_positions(
                &rest,
                &[Influences::single(0)],
                &bad,
                Blend::Linear,
                &mut out
            ),
            Err(SkinError::NonFinite {
                what: "transform",
                index: 0
            })
        );
        let flat = [Affine3A::from_scale(Vec3::new(0.0, 1.0, 1.0))];
        assert_eq!(
            skin_positions(
                &rest,
                &[Influences::single(0)],
                &flat,
                Blend::DualQuaternion,
                &mut out
            ),
            Err(SkinError::SingularTransform { joint: 0 })
        );
        let huge = [Affine3A::from_scale(Vec3::splat(f32::MAX))];
        assert_eq!(
            skin_positions(
                &[Vec3::splat(10.0)],
                &[Influences::single(0)],
                &huge,
                Blend::Linear,
                &mut out
            ),
            Err(SkinError::NonFiniteResult { index: 0 })
        );
    }

    #[test]
    fn an_empty_slot_may_name_a_missing_joint() {
        // Canonical padding names joint 0; any other joint in an empty slot is fine too, even
        // one with no transform (the fast pass sends this vertex to the checked pass).
        let rest = [Vec3::new(1.0, 2.0, 3.0), Vec3::new(-1.0, 0.5, 0.0)];
        let influences = [
            Influences::single(0),
            Influences {
                joints: [0, 7, 0, 0],
                weights: [1.0, 0.0, 0.0, 0.0],
            },
        ];
        let shift = [Affine3A::from_translation(Vec3::X)];
        let mut out = [Vec3::ZERO; 2];
        skin_positions(&rest, &influences, &shift, Blend::Linear, &mut out).unwrap();
        assert_eq!(out, [rest[0] + Vec3::X, rest[1] + Vec3::X]);
        // No transforms at all: vertices without weight stay put.
        skin_positions(
            &rest[..1],
            &[Influences::NONE],
            &[],
            Blend::Linear,
            &mut out[..1],
        )
        .unwrap();
        assert_eq!(out[0], rest[0]);
    }

    #[test]
    fn the_checked_pass_gives_the_same_bits_as_the_fast_one() {
        let rest: Vec<Vec3> = (0..20)
            .map(|i| Vec3::new(i as f32 * 0.37, 1.0 - i as f32 * 0.11, 0.25 * i as f32))
            .collect();
        let influences: Vec<Influences> = (0..20u16)
            .map(|i| Influences {
                joints: [i % 3, (i + 1) % 3, 0, 0],
                weights: [0.7, 0.3, 0.0, 0.0],
            })
            .collect();
        let transforms = [
            Affine3A::from_rotation_translation(Quat::from_rotation_y(0.4), Vec3::Y),
            Affine3A::from_scale(Vec3::new(1.5, 0.5, 1.0)),
            Affine3A::from_rotation_x(-0.8),
        ];
        let mut fast = alloc::vec![Vec3::ZERO; rest.len()];
        skin_positions(&rest, &influences, &transforms, Blend::Linear, &mut fast).unwrap();
        // One vertex with an empty slot on a missing joint sends every vertex through the
        // checked pass.
        let mut odd = influences.clone();
        odd[5].joints[3] = 99;
        let mut checked = alloc::vec![Vec3::ZERO; rest.len()];
        skin_positions(&rest, &odd, &transforms, Blend::Linear, &mut checked).unwrap();
        for (a, b) in fast.iter().zip(&checked) {
            assert_eq!(
                a.to_array().map(f32::to_bits),
                b.to_array().map(f32::to_bits)
            );
        }
    }

    #[test]
    fn linear_weights_are_used_as_given() {
        // Half a weight applies half the motion; no division by the sum.
        let rest = [Vec3::ZERO];
        let half = [Influences {
            joints: [0, 0, 0, 0],
            weights: [0.5, 0.0, 0.0, 0.0],
        }];
        let mut out = [Vec3::ONE];
        let shift = [Affine3A::from_translation(Vec3::X * 2.0)];
        skin_positions(&rest, &half, &shift, Blend::Linear, &mut out).unwrap();
        assert_eq!(out[0], Vec3::X);
    }

    #[test]
    fn the_first_bad_vertex_is_named() {
        let rest = [Vec3::splat(10.0), Vec3::NAN];
        let huge = [Affine3A::from_scale(Vec3::splat(f32::MAX))];
        let mut out = [Vec3::ZERO; 2];
        let one = [Influences::single(0); 2];
        assert_eq!(
            skin_positions(&rest, &one, &huge, Blend::Linear, &mut out),
            Err(SkinError::NonFiniteResult { index: 0 })
        );
        let negative = [
            Influences::single(0),
            Influences {
                joints: [0; 4],
                weights: [1.5, -0.5, 0.0, 0.0],
            },
        ];
        assert_eq!(
            skin_positions(
                &[Vec3::ONE; 2],
                &negative,
                &[Affine3A::IDENTITY],
                Blend::Linear,
                &mut out
            ),
            Err(SkinError::InvalidWeights { vertex: 1 })
        );
    }

    #[test]
    fn rotation_of_drops_scale_and_rejects_singular_maps() {
        let q = Quat::from_rotation_x(0.4);
        let m = Mat3A::from_quat(q) * Mat3A::from_diagonal(Vec3::new(2.0, 3.0, 0.5));
        let r = rotation_of(m).unwrap();
        assert!(r.abs_diff_eq(q, 1e-6) || r.abs_diff_eq(-q, 1e-6));
        assert!(rotation_of(Mat3A::ZERO).is_none());
        assert!(rotation_of(Mat3A::from_cols(Vec3A::X, Vec3A::X * 2.0, Vec3A::Z)).is_none());
    }
}
