//! Analytic two-bone inverse kinematics with a pole hint.

use glam::{Mat3, Quat, Vec3};

use crate::math::sqrt;

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
    solve_finite(root, target, upper, lower, pole)
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
/// rotations). Solving many chains step by step, each step for all of them, lets a processor
/// overlap the square roots and divisions of neighbouring chains; the results are those of
/// [`solve_finite`].
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
        let distance = offset.length();
        let dir = if distance.is_finite() && distance > 1e-12 {
            offset / distance
        } else if pole.length_squared() > 1e-24 {
            // Target on the root: fold along any direction perpendicular to the pole.
            pole.normalize().any_orthonormal_vector()
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
            .try_normalize()
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

/// The rotation taking +Y onto `dir` and +Z onto `bend` (orthonormal).
#[inline]
fn chain_frame(dir: Vec3, bend: Vec3) -> Quat {
    Quat::from_mat3(&Mat3::from_cols(dir.cross(bend), dir, bend)).normalize()
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
    fn bone_rotations_point_along_the_bones() {
        let s = solve_two_bone(Vec3::Y, Vec3::new(0.3, 0.0, 0.2), 0.7, 0.6, Vec3::X);
        let up = s.upper_rotation * Vec3::Y;
        assert!(up.distance((s.middle - s.root).normalize()) < 1e-5);
        let low = s.lower_rotation * Vec3::Y;
        assert!(low.distance((s.end - s.middle).normalize()) < 1e-5);
    }
}
