//! Analytic two-bone inverse kinematics with a pole hint.

use glam::{Mat3A, Mat4, Quat, Vec3, Vec4};

/// Whether glam runs its SSE2 code: on x86 with SSE2, unless any crate in the build turns on
/// glam's `scalar-math` (this crate's `libm` feature does; it drops `Quat`'s 16-byte
/// alignment, whatever glam's `cuda` says). The lanes' quaternion products and normalisations
/// follow glam's order of operations, so they match its `Quat` bit for bit: SSE2's, or else
/// the scalar one. Glam's other back ends (wasm's `simd128`, NEON, the nightly `core-simd`)
/// have orders of their own, which these do not follow.
const GLAM_SSE2: bool = cfg!(all(
    any(target_arch = "x86", target_arch = "x86_64"),
    target_feature = "sse2"
)) && core::mem::align_of::<Quat>() == 16;

/// `Vec4::select` on every component of a lane vector (`$T { $f, .. }`), the mask left to
/// glam's own type (`BVec4A` with SIMD, `BVec4` with `scalar-math`, which any crate in the
/// build may turn on).
macro_rules! select_lanes {
    ($mask:expr, $a:expr, $b:expr, $T:ident { $($f:ident),* }) => {{
        let (mask, a, b) = ($mask, $a, $b);
        $T { $($f: Vec4::select(mask, a.$f, b.$f)),* }
    }};
}

use crate::math::{Roots, quat_from_axes, sqrt, sqrt4};

/// A solved two-bone chain: root (hip or shoulder), middle joint (knee or elbow) and end
/// (foot or hand), in the same space as the inputs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoBone {
    /// The root joint (the input root).
    pub root: Vec3,
    /// The middle joint, bent toward the pole.
    pub middle: Vec3,
    /// The end of the chain: the target when reachable, else the nearest reachable point on the
    /// line from the root toward the target.
    pub end: Vec3,
    /// Rotation of the upper bone: maps +Y onto the root→middle direction and +Z onto the bend
    /// direction (glTF bones point along +Y).
    pub upper_rotation: Quat,
    /// Rotation of the lower bone: maps +Y onto the middle→end direction and +Z onto the same
    /// bend side.
    pub lower_rotation: Quat,
    /// Whether the target was reached (within rounding); false when it was too far or too near.
    pub reached: bool,
}

/// Solves a two-bone chain of lengths `upper` and `lower` from `root` toward `target`, bending
/// the middle joint toward `pole` (a direction, not a point).
///
/// Analytic (law of cosines). Targets beyond `upper + lower` give the fully extended chain
/// pointing at the target; targets closer than `|upper − lower|` give the most folded chain
/// pointing at it. Segment lengths are kept exactly (to rounding) and the result is never NaN:
/// non-finite inputs are replaced (target → root straight down, pole → any perpendicular),
/// non-positive or non-finite lengths are treated as 0.
///
/// ```
/// use creature_gait::{glam::Vec3, solve_two_bone};
///
/// let hip = Vec3::new(0.0, 1.0, 0.0);
/// let foot = Vec3::new(0.0, 0.2, 0.3);
/// let leg = solve_two_bone(hip, foot, 0.5, 0.5, Vec3::Z);
/// assert!(leg.reached);
/// assert!((leg.end - foot).length() < 1e-5);
/// assert!((leg.middle.distance(hip) - 0.5).abs() < 1e-5);
/// assert!(leg.middle.z > 0.15); // the knee points forward, toward the pole
/// ```
#[must_use]
pub fn solve_two_bone(root: Vec3, target: Vec3, upper: f32, lower: f32, pole: Vec3) -> TwoBone {
    let (root, target, upper, lower, pole) = sanitise(root, target, upper, lower, pole);
    solve_finite(root, target, upper, lower, pole)
}

/// [`solve_two_bone`]'s joints alone, bit for bit: the root, the middle joint and the end,
/// without the bone rotations (for a caller that turns its own bones: a third of the work).
///
/// ```
/// use creature_gait::{glam::Vec3, solve_two_bone, solve_two_bone_joints};
///
/// let (hip, foot) = (Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.2, 0.3));
/// let leg = solve_two_bone(hip, foot, 0.5, 0.5, Vec3::Z);
/// assert_eq!(solve_two_bone_joints(hip, foot, 0.5, 0.5, Vec3::Z), [leg.root, leg.middle, leg.end]);
/// ```
#[must_use]
pub fn solve_two_bone_joints(
    root: Vec3,
    target: Vec3,
    upper: f32,
    lower: f32,
    pole: Vec3,
) -> [Vec3; 3] {
    let (root, target, upper, lower, pole) = sanitise(root, target, upper, lower, pole);
    let mut shape = Shape::aim(root, target, pole);
    shape.bend(upper, lower);
    [shape.root, shape.middle, shape.end]
}

/// [`solve_two_bone`]'s inputs made finite, its lengths non-negative.
#[inline]
fn sanitise(
    root: Vec3,
    target: Vec3,
    upper: f32,
    lower: f32,
    pole: Vec3,
) -> (Vec3, Vec3, f32, f32, Vec3) {
    let root = if root.is_finite() { root } else { Vec3::ZERO };
    let upper = if upper.is_finite() && upper > 0.0 {
        upper
    } else {
        0.0
    };
    let lower = if lower.is_finite() && lower > 0.0 {
        lower
    } else {
        0.0
    };
    let target = if target.is_finite() {
        target
    } else {
        root - Vec3::Y * (upper + lower)
    };
    let pole = if pole.is_finite() { pole } else { Vec3::ZERO };
    (root, target, upper, lower, pole)
}

/// [`solve_two_bone`] for inputs already known to be finite with lengths `>= 0` (the
/// controller's, which are validated at its boundary): no sanitising.
#[inline]
pub(crate) fn solve_finite(
    root: Vec3,
    target: Vec3,
    upper: f32,
    lower: f32,
    pole: Vec3,
) -> TwoBone {
    let mut shape = Shape::aim(root, target, pole);
    shape.bend(upper, lower);
    shape.rotate()
}

/// A two-bone chain being solved, in three steps: [`aim`](Self::aim) (the direction to the
/// target), [`bend`](Self::bend) (the middle joint) and [`rotate`](Self::rotate) (the bone
/// rotations). The reference for [`solve_lanes`], which does the same operations for four
/// chains at once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Shape {
    root: Vec3,
    target: Vec3,
    pole: Vec3,
    dir: Vec3,
    distance: f32,
    bend: Vec3,
    middle: Vec3,
    end: Vec3,
    along: f32,
    across: f32,
    clamped: f32,
    reached: bool,
}

impl Shape {
    /// Storage before a first solve: a straight chain of zero length.
    pub(crate) const EMPTY: Self = Self {
        root: Vec3::ZERO,
        target: Vec3::ZERO,
        pole: Vec3::Z,
        dir: Vec3::NEG_Y,
        distance: 0.0,
        bend: Vec3::Z,
        middle: Vec3::ZERO,
        end: Vec3::ZERO,
        along: 0.0,
        across: 0.0,
        clamped: 0.0,
        reached: true,
    };

    /// The first step: the unit direction from `root` to `target` and their distance.
    #[inline]
    pub(crate) fn aim(root: Vec3, target: Vec3, pole: Vec3) -> Self {
        let offset = target - root;
        let distance = offset.norm();
        let dir = if distance.is_finite() && distance > 1e-12 {
            offset / distance
        } else if pole.length_squared() > 1e-24 {
            // Target on the root: fold along any direction perpendicular to the pole.
            pole.unit().any_orthonormal_vector()
        } else {
            Vec3::NEG_Y
        };
        let distance = if distance.is_finite() { distance } else { 0.0 };
        Self {
            root,
            target,
            pole,
            dir,
            distance,
            ..Self::EMPTY
        }
    }

    /// The second step: the bend direction and the joints for bones `upper` and `lower`.
    #[inline]
    pub(crate) fn bend(&mut self, upper: f32, lower: f32) {
        let (root, target, pole, dir, distance) =
            (self.root, self.target, self.pole, self.dir, self.distance);
        // Bend direction: the pole's part perpendicular to the chain.
        let bend = (pole - dir * pole.dot(dir))
            .try_unit()
            .unwrap_or_else(|| dir.any_orthonormal_vector());

        let reach = upper + lower;
        let fold = (upper - lower).abs();
        let clamped = distance.clamp(fold, reach);
        let reached = clamped == distance || (clamped - distance).abs() <= 1e-6 * reach.max(1e-12);
        let end = if clamped == distance {
            target
        } else {
            root + dir * clamped
        };
        // Law of cosines: the middle joint's projection along the chain and its height off it.
        let (along, across) = if clamped <= 0.0 || upper == 0.0 {
            (0.0, 0.0)
        } else {
            let along = ((upper * upper - lower * lower + clamped * clamped) / (2.0 * clamped))
                .clamp(-upper, upper);
            (along, sqrt((upper * upper - along * along).max(0.0)))
        };
        self.bend = bend;
        self.middle = root + dir * along + bend * across;
        self.end = end;
        self.along = along;
        self.across = across;
        self.clamped = clamped;
        self.reached = reached;
    }

    /// The last step: the solved chain with its bone rotations.
    #[inline]
    pub(crate) fn rotate(&self) -> TwoBone {
        // Both bones lie in the plane of `dir` and `bend`: one frame for the chain, then a
        // turn about its normal per bone (no trigonometry, one matrix-to-quaternion per leg).
        let frame = chain_frame(self.dir, self.bend);
        TwoBone {
            root: self.root,
            middle: self.middle,
            end: self.end,
            upper_rotation: bone_rotation(frame, self.along, self.across),
            lower_rotation: bone_rotation(frame, self.clamped - self.along, -self.across),
            reached: self.reached,
        }
    }
}

/// Four two-bone problems, one per SIMD lane, for [`solve_lanes`]: finite inputs, lengths
/// `>= 0` (as for `solve_finite`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Lanes {
    pub(crate) root: V3,
    pub(crate) target: V3,
    pub(crate) pole: V3,
    pub(crate) upper: Vec4,
    pub(crate) lower: Vec4,
}

/// A chain of zero length at the origin: storage for unused lanes.
pub(crate) const SPARE: TwoBone = TwoBone {
    root: Vec3::ZERO,
    middle: Vec3::ZERO,
    end: Vec3::ZERO,
    upper_rotation: Quat::IDENTITY,
    lower_rotation: Quat::IDENTITY,
    reached: true,
};

/// Solves four chains at once into `out`, bit for bit as `solve_finite` solves each: the lanes
/// do every operation of the scalar solve in the same order, and a chain that needs one of its
/// rare branches (target on the root, pole along the chain) is solved again on its own.
pub(crate) fn solve_lanes(p: &Lanes, out: [&mut TwoBone; 4]) {
    let [o0, o1, o2, o3] = out;
    let zero = Vec4::ZERO;
    let (root, target, pole, upper, lower) = (p.root, p.target, p.pole, p.upper, p.lower);
    let [r0, r1, r2, r3] = root.split();
    (o0.root, o1.root, o2.root, o3.root) = (r0, r1, r2, r3);

    // `Shape::aim`.
    let offset = target.sub(root);
    let distance = sqrt4(offset.dot(offset));
    let common = distance.is_finite_mask() & distance.cmpgt(Vec4::splat(1e-12));
    let dir = V3 {
        x: offset.x / distance,
        y: offset.y / distance,
        z: offset.z / distance,
    };

    // `Shape::bend`.
    let off_axis = pole.sub(dir.scale(pole.dot(dir)));
    let rcp = Vec4::ONE / sqrt4(off_axis.dot(off_axis));
    let common = common & rcp.is_finite_mask() & rcp.cmpgt(zero);
    let bend = off_axis.scale(rcp);
    let reach = upper + lower;
    let fold = (upper - lower).abs();
    let clamped = distance.max(fold).min(reach);
    let exact = clamped.cmpeq(distance);
    let reached = exact
        | (clamped - distance)
            .abs()
            .cmple(Vec4::splat(1e-6) * reach.max(Vec4::splat(1e-12)));
    (o0.reached, o1.reached, o2.reached, o3.reached) = (
        reached.test(0),
        reached.test(1),
        reached.test(2),
        reached.test(3),
    );
    let [e0, e1, e2, e3] =
        select_lanes!(exact, target, root.add(dir.scale(clamped)), V3 { x, y, z }).split();
    (o0.end, o1.end, o2.end, o3.end) = (e0, e1, e2, e3);
    let folded = clamped.cmple(zero) | upper.cmpeq(zero);
    let along = ((upper * upper - lower * lower + clamped * clamped)
        / (Vec4::splat(2.0) * clamped))
        .max(-upper)
        .min(upper);
    let across = sqrt4((upper * upper - along * along).max(zero));
    let along = Vec4::select(folded, zero, along);
    let across = Vec4::select(folded, zero, across);
    let [m0, m1, m2, m3] = root.add(dir.scale(along)).add(bend.scale(across)).split();
    (o0.middle, o1.middle, o2.middle, o3.middle) = (m0, m1, m2, m3);

    // `Shape::rotate`.
    let frame = from_axes4(dir.cross(bend), dir, bend).normalize();
    let [u0, u1, u2, u3] = bone_rotation4(frame, along, across).split();
    (
        o0.upper_rotation,
        o1.upper_rotation,
        o2.upper_rotation,
        o3.upper_rotation,
    ) = (u0, u1, u2, u3);
    let [l0, l1, l2, l3] = bone_rotation4(frame, clamped - along, -across).split();
    (
        o0.lower_rotation,
        o1.lower_rotation,
        o2.lower_rotation,
        o3.lower_rotation,
    ) = (l0, l1, l2, l3);

    let rare = !common.bitmask();
    if rare & 0xf != 0 {
        for (k, o) in [o0, o1, o2, o3].into_iter().enumerate() {
            if rare & (1 << k) != 0 {
                *o = solve_finite(
                    root.lane(k),
                    target.lane(k),
                    upper[k],
                    lower[k],
                    pole.lane(k),
                );
            }
        }
    }
}

/// Four `Vec3`s, one per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct V3 {
    pub(crate) x: Vec4,
    pub(crate) y: Vec4,
    pub(crate) z: Vec4,
}

impl V3 {
    /// `m * v + t` for each lane's `v`, in the order of operations of `Mat3A * Vec3`
    /// (`(x_axis v.x + y_axis v.y) + z_axis v.z`).
    #[inline(always)]
    pub(crate) fn transform(self, m: &Mat3A, t: Vec3) -> Self {
        let row = |a: f32, b: f32, c: f32, t: f32| {
            Vec4::splat(a) * self.x
                + Vec4::splat(b) * self.y
                + Vec4::splat(c) * self.z
                + Vec4::splat(t)
        };
        Self {
            x: row(m.x_axis.x, m.y_axis.x, m.z_axis.x, t.x),
            y: row(m.x_axis.y, m.y_axis.y, m.z_axis.y, t.y),
            z: row(m.x_axis.z, m.y_axis.z, m.z_axis.z, t.z),
        }
    }

    /// `m * v` for each lane's `v`, as [`transform`](Self::transform) without a translation.
    #[inline(always)]
    pub(crate) fn rotate(self, m: &Mat3A) -> Self {
        let row = |a: f32, b: f32, c: f32| {
            Vec4::splat(a) * self.x + Vec4::splat(b) * self.y + Vec4::splat(c) * self.z
        };
        Self {
            x: row(m.x_axis.x, m.y_axis.x, m.z_axis.x),
            y: row(m.x_axis.y, m.y_axis.y, m.z_axis.y),
            z: row(m.x_axis.z, m.y_axis.z, m.z_axis.z),
        }
    }

    /// The four lanes (a transpose).
    #[inline(always)]
    pub(crate) fn split(self) -> [Vec3; 4] {
        let m = Mat4::from_cols(self.x, self.y, self.z, Vec4::ZERO).transpose();
        [
            m.x_axis.truncate(),
            m.y_axis.truncate(),
            m.z_axis.truncate(),
            m.w_axis.truncate(),
        ]
    }

    #[inline(always)]
    pub(crate) fn gather(v: [Vec3; 4]) -> Self {
        Self {
            x: Vec4::new(v[0].x, v[1].x, v[2].x, v[3].x),
            y: Vec4::new(v[0].y, v[1].y, v[2].y, v[3].y),
            z: Vec4::new(v[0].z, v[1].z, v[2].z, v[3].z),
        }
    }

    #[inline(always)]
    fn lane(self, k: usize) -> Vec3 {
        Vec3::new(self.x[k], self.y[k], self.z[k])
    }

    #[inline(always)]
    pub(crate) fn add(self, o: Self) -> Self {
        Self {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }

    #[inline(always)]
    pub(crate) fn sub(self, o: Self) -> Self {
        Self {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }

    #[inline(always)]
    fn scale(self, s: Vec4) -> Self {
        Self {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }

    /// `Vec3::dot`'s order: `(x x' + y y') + z z'`.
    #[inline(always)]
    pub(crate) fn dot(self, o: Self) -> Vec4 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// `Vec3::cross`.
    #[inline(always)]
    fn cross(self, o: Self) -> Self {
        Self {
            x: self.y * o.z - o.y * self.z,
            y: self.z * o.x - o.z * self.x,
            z: self.x * o.y - o.x * self.y,
        }
    }
}

/// Four quaternions, one per lane.
#[derive(Clone, Copy)]
struct Q4 {
    x: Vec4,
    y: Vec4,
    z: Vec4,
    w: Vec4,
}

impl Q4 {
    /// The four lanes (a transpose).
    #[inline(always)]
    fn split(self) -> [Quat; 4] {
        let m = Mat4::from_cols(self.x, self.y, self.z, self.w).transpose();
        [
            Quat::from_vec4(m.x_axis),
            Quat::from_vec4(m.y_axis),
            Quat::from_vec4(m.z_axis),
            Quat::from_vec4(m.w_axis),
        ]
    }

    /// `a * b` in glam's order of operations (see [`GLAM_SSE2`]).
    #[inline(always)]
    fn mul(a: Self, b: Self) -> Self {
        if GLAM_SSE2 {
            // SSE2's `Quat::mul_quat`.
            Self {
                x: (a.x * b.w + a.w * b.x) + (a.y * b.z - a.z * b.y),
                y: (a.w * b.y - a.x * b.z) + (a.z * b.x + a.y * b.w),
                z: (a.x * b.y + a.w * b.z) + (a.z * b.w - a.y * b.x),
                w: (a.w * b.w - a.x * b.x) + (-(a.z * b.z) - a.y * b.y),
            }
        } else {
            // The scalar `Quat::mul_quat`.
            Self {
                x: a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                y: a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                z: a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
                w: a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
            }
        }
    }

    /// `Quat::normalize` in glam's order of operations (see [`GLAM_SSE2`]): SSE2's
    /// `(x² + z²) + (y² + w²)` then a division, or the scalar `x² + y² + z² + w²` then a
    /// product with the reciprocal of its root.
    #[inline(always)]
    fn normalize(self) -> Self {
        if GLAM_SSE2 {
            let length =
                sqrt4((self.x * self.x + self.z * self.z) + (self.y * self.y + self.w * self.w));
            Self {
                x: self.x / length,
                y: self.y / length,
                z: self.z / length,
                w: self.w / length,
            }
        } else {
            let recip = Vec4::ONE
                / sqrt4(self.x * self.x + self.y * self.y + self.z * self.z + self.w * self.w);
            Self {
                x: self.x * recip,
                y: self.y * recip,
                z: self.z * recip,
                w: self.w * recip,
            }
        }
    }
}

/// `Quat::from_mat3(&glam::Mat3::from_cols(x, y, z))`, lane by lane (glam's four branches, each
/// lane taking its own).
#[inline(always)]
fn from_axes4(x: V3, y: V3, z: V3) -> Q4 {
    let (m00, m01, m02) = (x.x, x.y, x.z);
    let (m10, m11, m12) = (y.x, y.y, y.z);
    let (m20, m21, m22) = (z.x, z.y, z.z);
    let zero = Vec4::ZERO;
    let low_z = m22.cmple(zero);
    let dif10 = m11 - m00;
    let sum10 = m11 + m00;
    let omm22 = Vec4::ONE - m22;
    let opm22 = Vec4::ONE + m22;
    let case_x = low_z & dif10.cmple(zero);
    let case_z = !low_z & sum10.cmple(zero);
    let (low, x_case, z_case) = (low_z.bitmask(), case_x.bitmask(), case_z.bitmask());
    // Usually every lane takes the same branch (legs are alike): then only its formulas.
    if low == 0 && z_case == 0xf {
        let four = opm22 - sum10;
        let inv = Vec4::splat(0.5) / sqrt4(four);
        return Q4 {
            x: (m02 + m20) * inv,
            y: (m12 + m21) * inv,
            z: four * inv,
            w: (m01 - m10) * inv,
        };
    }
    if low == 0 && z_case == 0 {
        let four = opm22 + sum10;
        let inv = Vec4::splat(0.5) / sqrt4(four);
        return Q4 {
            x: (m12 - m21) * inv,
            y: (m20 - m02) * inv,
            z: (m01 - m10) * inv,
            w: four * inv,
        };
    }
    if low == 0xf && x_case == 0xf {
        let four = omm22 - dif10;
        let inv = Vec4::splat(0.5) / sqrt4(four);
        return Q4 {
            x: four * inv,
            y: (m01 + m10) * inv,
            z: (m02 + m20) * inv,
            w: (m12 - m21) * inv,
        };
    }
    let four = Vec4::select(
        low_z,
        Vec4::select(case_x, omm22 - dif10, omm22 + dif10),
        Vec4::select(case_z, opm22 - sum10, opm22 + sum10),
    );
    let inv = Vec4::splat(0.5) / sqrt4(four);
    let own = four * inv;
    let p01 = (m01 + m10) * inv;
    let p02 = (m02 + m20) * inv;
    let p12 = (m12 + m21) * inv;
    let d12 = (m12 - m21) * inv;
    let d20 = (m20 - m02) * inv;
    let d01 = (m01 - m10) * inv;
    // (x, y, z, w) for the cases x, y, z and w of glam's `from_rotation_axes`.
    let pick = |cx: Vec4, cy: Vec4, cz: Vec4, cw: Vec4| {
        Vec4::select(
            low_z,
            Vec4::select(case_x, cx, cy),
            Vec4::select(case_z, cz, cw),
        )
    };
    Q4 {
        x: pick(own, p01, p02, d12),
        y: pick(p01, own, p12, d20),
        z: pick(p02, p12, own, d01),
        w: pick(d12, d20, d01, own),
    }
}

/// `bone_rotation` for four lanes.
#[inline(always)]
fn bone_rotation4(frame: Q4, along: Vec4, across: Vec4) -> Q4 {
    let zero = Vec4::ZERO;
    let r2 = along * along + across * across;
    let bone = r2.cmpgt(zero) & r2.is_finite_mask();
    let r = sqrt4(r2);
    let forward = along.cmpge(zero);
    let all_forward = forward.all();
    let (x, w) = if all_forward {
        (across, r + along)
    } else {
        (
            Vec4::select(forward, across, r - along),
            Vec4::select(forward, r + along, across),
        )
    };
    let inv = Vec4::ONE / sqrt4(x * x + w * w);
    let half = Q4 {
        x: x * inv,
        y: zero,
        z: zero,
        w: w * inv,
    };
    let q = Q4::mul(frame, half);
    let flip = Q4 {
        x: zero,
        y: Vec4::ONE,
        z: zero,
        w: zero,
    };
    // The half turn and the fallback only where a lane needs them (rarely).
    let q = if all_forward {
        q
    } else {
        select_lanes!(forward, q, Q4::mul(q, flip), Q4 { x, y, z, w })
    };
    let keep = bone
        & q.x.is_finite_mask()
        & q.y.is_finite_mask()
        & q.z.is_finite_mask()
        & q.w.is_finite_mask();
    if keep.all() {
        return q;
    }
    let identity = Q4 {
        x: zero,
        y: zero,
        z: zero,
        w: Vec4::ONE,
    };
    select_lanes!(keep, q, identity, Q4 { x, y, z, w })
}

/// The rotation taking +Y onto `dir` and +Z onto `bend` (orthonormal).
#[inline]
fn chain_frame(dir: Vec3, bend: Vec3) -> Quat {
    quat_from_axes(dir.cross(bend), dir, bend).unit()
}

/// The rotation of a bone whose direction is `along · dir + across · bend` in the chain's
/// `frame`: +Y onto the bone, +Z onto `bend` made perpendicular to the bone (on `bend`'s side
/// of the bone; for a bone perpendicular to `dir`, +Z is `−dir` or `+dir`). Identity for a
/// zero bone.
#[inline]
fn bone_rotation(frame: Quat, along: f32, across: f32) -> Quat {
    let r2 = along * along + across * across;
    if !(r2 > 0.0 && r2.is_finite()) {
        return Quat::IDENTITY;
    }
    let r = sqrt(r2);
    // The turn by θ = atan2(across, along) about the frame's +X, as a half-angle quaternion
    // from whichever of two proportional forms is well conditioned: (sin θ, 1 + cos θ) or
    // (1 − cos θ, sin θ), scaled by r. A bone pointing back along `dir` (along < 0) keeps +Z on
    // `bend`'s side by a half turn about its own axis.
    let (x, w) = if along >= 0.0 {
        (across, r + along)
    } else {
        (r - along, across)
    };
    let inv = 1.0 / sqrt(x * x + w * w);
    let q = frame * Quat::from_xyzw(x * inv, 0.0, 0.0, w * inv);
    let q = if along >= 0.0 {
        q
    } else {
        q * Quat::from_xyzw(0.0, 1.0, 0.0, 0.0)
    };
    if q.is_finite() { q } else { Quat::IDENTITY }
}

#[cfg(test)]
mod tests {
    use alloc::vec::Vec;

    use super::*;
    use crate::math::{cos, sin};

    #[test]
    fn reachable_target_is_reached_with_lengths_kept() {
        let root = Vec3::new(0.2, 1.0, -0.3);
        let target = Vec3::new(0.5, 0.3, 0.1);
        let s = solve_two_bone(root, target, 0.6, 0.5, Vec3::Z);
        assert!(s.reached);
        assert!(s.end.distance(target) < 1e-5);
        assert!((s.middle.distance(root) - 0.6).abs() < 1e-5);
        assert!((s.end.distance(s.middle) - 0.5).abs() < 1e-5);
    }

    #[test]
    fn unreachable_target_gives_full_extension_toward_it() {
        let s = solve_two_bone(Vec3::ZERO, Vec3::new(0.0, -5.0, 0.0), 1.0, 1.0, Vec3::Z);
        assert!(!s.reached);
        assert!(s.end.distance(Vec3::new(0.0, -2.0, 0.0)) < 1e-6);
        assert!(s.middle.distance(Vec3::new(0.0, -1.0, 0.0)) < 1e-3);
    }

    #[test]
    fn too_near_target_gives_folded_chain() {
        let s = solve_two_bone(Vec3::ZERO, Vec3::new(0.0, -0.1, 0.0), 1.0, 0.5, Vec3::Z);
        assert!(!s.reached);
        assert!((s.end.length() - 0.5).abs() < 1e-5);
    }

    #[test]
    fn degenerate_inputs_never_give_nan() {
        let cases = [
            (Vec3::ZERO, Vec3::ZERO, 1.0, 1.0, Vec3::Z),
            (Vec3::ZERO, Vec3::NAN, 1.0, 1.0, Vec3::Z),
            (Vec3::ZERO, Vec3::new(0.0, -1.0, 0.0), 1.0, 1.0, Vec3::NEG_Y),
            (Vec3::ZERO, Vec3::new(0.0, -1.0, 0.0), 0.0, 0.0, Vec3::ZERO),
            (Vec3::NAN, Vec3::ONE, f32::NAN, f32::INFINITY, Vec3::NAN),
        ];
        for (root, target, a, b, pole) in cases {
            let s = solve_two_bone(root, target, a, b, pole);
            assert!(s.middle.is_finite() && s.end.is_finite());
            assert!(s.upper_rotation.is_finite() && s.lower_rotation.is_finite());
        }
    }

    #[test]
    fn bone_rotations_turn_z_toward_the_bend_also_for_folded_chains() {
        // Targets near the root fold the chain so that one bone points back (its projection on
        // the root → target direction is negative): the other branch of `bone_rotation`.
        let root = Vec3::new(0.1, 1.0, -0.2);
        for (upper, lower) in [(1.0, 0.4), (0.4, 1.0), (0.5, 0.5), (0.7, 0.6)] {
            for k in 0..40 {
                let a = k as f32 * 0.37;
                let r = 0.05 + 1.6 * (k as f32 / 40.0);
                let target = root + Vec3::new(r * sin(a), -r * cos(a * 0.5), 0.3 * r * cos(a));
                let pole = Vec3::new(0.2, 0.1, 1.0);
                let s = solve_two_bone(root, target, upper, lower, pole);
                let dir = (s.end - s.root).normalize();
                let bend = (pole - dir * pole.dot(dir)).normalize();
                for (q, from, to) in [
                    (s.upper_rotation, s.root, s.middle),
                    (s.lower_rotation, s.middle, s.end),
                ] {
                    let y = (to - from).normalize();
                    let expected = bend - y * bend.dot(y);
                    if expected.length() < 1e-3 {
                        continue; // bone along the bend: any perpendicular will do
                    }
                    assert!((q * Vec3::Y).distance(y) < 1e-4, "{k}: {q:?}");
                    assert!((q * Vec3::Z).distance(expected.normalize()) < 1e-3, "{k}");
                    assert!((q.length() - 1.0).abs() < 1e-5);
                }
            }
        }
    }

    #[test]
    fn four_lanes_solve_bit_for_bit_as_one() {
        // Reachable, unreachable, folded and straight-down targets, zero and unequal lengths,
        // a target on the root and a pole along the chain (the lanes' rare branches), four at
        // a time in every position.
        let mut problems = Vec::new();
        for k in 0..243 {
            let a = k as f32 * 0.61;
            let r = 0.02 + 2.2 * ((k * 7) % 23) as f32 / 23.0;
            let root = Vec3::new(0.3 * cos(a), 1.0 + 0.1 * sin(2.0 * a), -0.2 * sin(a));
            let mut target = root + Vec3::new(r * sin(a), -r * cos(0.5 * a), 0.4 * r * cos(a));
            let (mut upper, lower) = (0.3 + 0.05 * (k % 9) as f32, 0.25 + 0.07 * (k % 5) as f32);
            let mut pole = Vec3::new(0.2 * sin(3.0 * a), 0.1, 1.0);
            match k % 17 {
                3 => target = root,
                5 => pole = target - root,
                7 => target = root - Vec3::Y * (upper + lower),
                11 => upper = 0.0,
                13 => target = root + Vec3::Z * 1e-7,
                _ => {}
            }
            problems.push((root, target, upper, lower, pole));
        }
        let bits = |c: &TwoBone| {
            let v = [c.root, c.middle, c.end].map(|v| v.to_array().map(f32::to_bits));
            let q = [c.upper_rotation, c.lower_rotation].map(|q| q.to_array().map(f32::to_bits));
            (v, q, c.reached)
        };
        // Mixed neighbours, and four alike (every lane taking the same branches, the lanes'
        // shortcuts).
        let alike: Vec<_> = problems
            .iter()
            .flat_map(|&(root, target, upper, lower, pole)| {
                (0..4).map(move |k| {
                    let nudge = Vec3::new(1e-3, -2e-3, 1.5e-3) * k as f32;
                    (root, target + nudge, upper, lower, pole)
                })
            })
            .collect();
        for p in problems.windows(4).chain(alike.chunks(4)) {
            let lanes = Lanes {
                root: V3::gather([p[0].0, p[1].0, p[2].0, p[3].0]),
                target: V3::gather([p[0].1, p[1].1, p[2].1, p[3].1]),
                upper: Vec4::new(p[0].2, p[1].2, p[2].2, p[3].2),
                lower: Vec4::new(p[0].3, p[1].3, p[2].3, p[3].3),
                pole: V3::gather([p[0].4, p[1].4, p[2].4, p[3].4]),
            };
            let mut out = [SPARE; 4];
            let [a, b, c, d] = &mut out;
            solve_lanes(&lanes, [a, b, c, d]);
            for (chain, &(root, target, upper, lower, pole)) in out.iter().zip(p) {
                let one = solve_finite(root, target, upper, lower, pole);
                assert_eq!(bits(chain), bits(&one));
            }
        }
    }

    #[test]
    fn bone_rotations_point_along_the_bones() {
        let s = solve_two_bone(Vec3::Y, Vec3::new(0.3, 0.0, 0.2), 0.7, 0.6, Vec3::X);
        let up = s.upper_rotation * Vec3::Y;
        assert!(up.distance((s.middle - s.root).normalize()) < 1e-5);
        let low = s.lower_rotation * Vec3::Y;
        assert!(low.distance((s.end - s.middle).normalize()) < 1e-5);
    }
}
