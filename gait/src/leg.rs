//! Plain data describing the limbs: [`Leg`], [`Chain`], [`Pose`], and the layout rules that
//! derive leg groups and opposite legs.

use alloc::vec::Vec;

use glam::{Quat, Vec3};

use crate::error::{GaitError, finite3, positive};
use crate::gaits::{self, Gait, Sides};
use crate::sort::sort_by;

/// What a limb does with the ground.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub enum LimbKind {
    /// A leg: its foot is placed on the ground by ray casts, and it takes part in the leg
    /// groups' sequencing.
    #[default]
    Leg,
    /// An arm (3D seed): it steps like a leg but ignores the ground's height, keeping its hand
    /// at the rest height in the air, and bobs gently when idle. Arms are not sequenced.
    Arm,
}

/// One leg (or arm): plain data in the body's space.
///
/// Body space: right-handed, Y up, +Z forward, so +X is the creature's left. Lengths in metres.
///
/// ```
/// use creature_gait::{Leg, glam::Vec3};
///
/// // A left leg: hip 0.8 m up, foot resting straight below, knee pointing forward.
/// let leg = Leg::new(Vec3::new(0.3, 0.8, 0.5), Vec3::new(0.35, 0.0, 0.5), 0.45, 0.45)
///     .with_pole(Vec3::Z);
/// assert_eq!(leg.size, 0.9); // defaults to upper + lower
/// leg.validate(0)?;
/// # Ok::<(), creature_gait::GaitError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Leg {
    /// Hip (or shoulder) position in body space.
    pub hip: Vec3,
    /// Rest position of the foot in body space: where the foot stands when the body is still.
    /// The ground ray is cast down from above it.
    pub rest: Vec3,
    /// Length of the upper segment (thigh), metres, > 0.
    pub upper: f32,
    /// Length of the lower segment (shin), metres, > 0.
    pub lower: f32,
    /// Knee direction hint in body space (non-zero): the knee bends toward it. Default +Z
    /// (forward).
    pub pole: Vec3,
    /// The leg's size, metres, > 0: it scales reach, overshoot, step height and escape
    /// distance (the 3D seed's per-leg size). Default `upper + lower`.
    pub size: f32,
    /// The leg's group for sequencing, or `None` (default) to derive groups from the layout.
    /// Either every leg has a group or none has.
    pub group: Option<u8>,
    /// Leg or arm. Default [`LimbKind::Leg`].
    pub kind: LimbKind,
}

impl Leg {
    /// A leg with the given hip, rest foot position and segment lengths; pole +Z, size
    /// `upper + lower`, no group, kind [`LimbKind::Leg`].
    #[must_use]
    pub const fn new(hip: Vec3, rest: Vec3, upper: f32, lower: f32) -> Self {
        Self {
            hip,
            rest,
            upper,
            lower,
            pole: Vec3::Z,
            size: upper + lower,
            group: None,
            kind: LimbKind::Leg,
        }
    }

    /// Sets the knee direction hint (body space).
    #[must_use]
    pub const fn with_pole(mut self, pole: Vec3) -> Self {
        self.pole = pole;
        self
    }

    /// Sets the size (see [`Leg::size`]).
    #[must_use]
    pub const fn with_size(mut self, size: f32) -> Self {
        self.size = size;
        self
    }

    /// Sets the group.
    #[must_use]
    pub const fn with_group(mut self, group: u8) -> Self {
        self.group = Some(group);
        self
    }

    /// Sets the kind (leg or arm).
    #[must_use]
    pub const fn with_kind(mut self, kind: LimbKind) -> Self {
        self.kind = kind;
        self
    }

    /// The leg's full length, `upper + lower`.
    #[must_use]
    pub fn length(&self) -> f32 {
        self.upper + self.lower
    }

    /// Checks the leg; `index` is only used in the error.
    ///
    /// # Errors
    /// [`GaitError::NonFinite`] for a non-finite position or pole, [`GaitError::NotPositive`]
    /// for a segment length or size that is not positive, [`GaitError::OutOfRange`] for a
    /// coordinate, length or size beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE),
    /// [`GaitError::ZeroVector`] for a zero pole.
    pub fn validate(&self, index: usize) -> Result<(), GaitError> {
        finite3(self.hip, "leg hip", index)?;
        finite3(self.rest, "leg rest position", index)?;
        finite3(self.pole, "leg pole", index)?;
        positive(self.upper, "upper segment of leg", index)?;
        positive(self.lower, "lower segment of leg", index)?;
        positive(self.size, "size of leg", index)?;
        positive(self.upper + self.lower, "length of leg", index)?;
        // Poses are capped at MAX_COORDINATE; so are the legs, whose squared lengths and hull
        // areas would otherwise overflow to infinity and NaN.
        let max = crate::MAX_COORDINATE;
        crate::error::in_range(self.hip.abs().max_element(), "leg hip coordinate", 0.0, max)?;
        crate::error::in_range(
            self.rest.abs().max_element(),
            "leg rest coordinate",
            0.0,
            max,
        )?;
        crate::error::in_range(self.upper + self.lower, "length of leg", 0.0, max)?;
        crate::error::in_range(self.size, "size of leg", 0.0, max)?;
        if self.pole.length_squared() < 1e-12 {
            return Err(GaitError::ZeroVector {
                what: "leg pole",
                index,
            });
        }
        Ok(())
    }
}

/// A follow-through chain (tail, fin, a wing's trailing bones, a flier's dangling leg): joints
/// that trail the body through a damped spring, with constant segment length.
///
/// Joint 0 is pinned to `root` on the body; joints `1..=segments` rest along `direction`
/// (turned about the body's up axis by `turn_bend` seconds of the yaw rate, so the chain bends
/// into turns as in the 3D seed) and are pulled toward those rest positions.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Chain {
    /// Root of the chain in body space.
    pub root: Vec3,
    /// Rest direction in body space (non-zero; normalised when used). A tail: −Z.
    pub direction: Vec3,
    /// Number of segments, 1 to [`MAX_CHAIN_SEGMENTS`].
    pub segments: usize,
    /// Length of each segment, metres, > 0.
    pub segment_length: f32,
    /// Spring stiffness toward the rest pose, per second squared, in `[0, 10 000]`. Default 60.
    pub stiffness: f32,
    /// Damping of the joints' velocity, per second, in `[0, 1000]`. Default 8.
    pub damping: f32,
    /// Downward acceleration, m/s², in `[0, 100]`: 0 for tails, 9.81 for dangling legs.
    /// Default 0.
    pub gravity: f32,
    /// Seconds of yaw rate by which the rest direction turns (bending into turns), in
    /// `[-2, 2]`. Default 0.
    pub turn_bend: f32,
}

/// The most segments a [`Chain`] may have.
pub const MAX_CHAIN_SEGMENTS: usize = 64;

impl Chain {
    /// A chain from `root` along `direction` with `segments` segments of `segment_length`;
    /// stiffness 60, damping 8, no gravity, no turn bend.
    #[must_use]
    pub const fn new(root: Vec3, direction: Vec3, segments: usize, segment_length: f32) -> Self {
        Self {
            root,
            direction,
            segments,
            segment_length,
            stiffness: 60.0,
            damping: 8.0,
            gravity: 0.0,
            turn_bend: 0.0,
        }
    }

    /// Sets stiffness and damping.
    #[must_use]
    pub const fn with_spring(mut self, stiffness: f32, damping: f32) -> Self {
        self.stiffness = stiffness;
        self.damping = damping;
        self
    }

    /// Sets the downward acceleration.
    #[must_use]
    pub const fn with_gravity(mut self, gravity: f32) -> Self {
        self.gravity = gravity;
        self
    }

    /// Sets the turn bend (seconds of yaw rate).
    #[must_use]
    pub const fn with_turn_bend(mut self, turn_bend: f32) -> Self {
        self.turn_bend = turn_bend;
        self
    }

    /// Checks the chain; `index` is only used in errors.
    ///
    /// # Errors
    /// [`GaitError::NonFinite`], [`GaitError::ZeroVector`] (direction),
    /// [`GaitError::NotPositive`] (segment length, zero segments) or
    /// [`GaitError::OutOfRange`] (segments, a root coordinate or the chain's length beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE), stiffness, damping, gravity, turn bend).
    pub fn validate(&self, index: usize) -> Result<(), GaitError> {
        finite3(self.root, "chain root", index)?;
        finite3(self.direction, "chain direction", index)?;
        if self.direction.length_squared() < 1e-12 {
            return Err(GaitError::ZeroVector {
                what: "chain direction",
                index,
            });
        }
        positive(self.segment_length, "segment length of chain", index)?;
        if self.segments == 0 {
            return Err(GaitError::NotPositive {
                what: "segment count of chain",
                index,
                value: 0.0,
            });
        }
        let max = crate::MAX_COORDINATE;
        crate::error::in_range(
            self.root.abs().max_element(),
            "chain root coordinate",
            0.0,
            max,
        )?;
        crate::error::in_range(
            self.segment_length * self.segments as f32,
            "length of chain",
            0.0,
            max,
        )?;
        if self.segments > MAX_CHAIN_SEGMENTS {
            return Err(GaitError::OutOfRange {
                what: "chain segments",
                value: self.segments as f32,
                min: 1.0,
                max: MAX_CHAIN_SEGMENTS as f32,
            });
        }
        crate::error::in_range(self.stiffness, "chain stiffness", 0.0, 10_000.0)?;
        crate::error::in_range(self.damping, "chain damping", 0.0, 1000.0)?;
        crate::error::in_range(self.gravity, "chain gravity", 0.0, 100.0)?;
        crate::error::in_range(self.turn_bend, "chain turn bend", -2.0, 2.0)?;
        Ok(())
    }
}

/// A rigid body pose: rotation then translation (world = rotation · body + translation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Position of the body's origin in world space.
    pub translation: Vec3,
    /// Orientation of the body (normalised by the controller).
    pub rotation: Quat,
}

impl Pose {
    /// The identity pose.
    pub const IDENTITY: Self = Self {
        translation: Vec3::ZERO,
        rotation: Quat::IDENTITY,
    };

    /// A pose from a translation and a rotation.
    #[must_use]
    pub const fn new(translation: Vec3, rotation: Quat) -> Self {
        Self {
            translation,
            rotation,
        }
    }

    /// A pose at `translation` turned by `yaw` radians about +Y.
    #[must_use]
    pub fn from_yaw(translation: Vec3, yaw: f32) -> Self {
        Self {
            translation,
            rotation: Quat::from_rotation_y(yaw),
        }
    }

    /// Maps a body-space point to world space.
    #[must_use]
    pub fn transform_point(&self, point: Vec3) -> Vec3 {
        self.rotation * point + self.translation
    }

    /// Maps a body-space direction to world space.
    #[must_use]
    pub fn transform_vector(&self, vector: Vec3) -> Vec3 {
        self.rotation * vector
    }

    /// Maps a world-space point to body space.
    #[must_use]
    pub fn inverse_transform_point(&self, point: Vec3) -> Vec3 {
        self.rotation.inverse() * (point - self.translation)
    }
}

impl Default for Pose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

/// How the legs are sequenced: each leg's group, the number of groups, and the seed's
/// opposite-leg references.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Layout {
    /// Each leg's group in the current gait (a copy of `by_gait`'s).
    pub(crate) groups: Vec<u8>,
    pub(crate) group_count: u8,
    /// Each gait's groups and group count, by `Gait as usize` (the caller's groups in each, if
    /// the caller set them).
    pub(crate) by_gait: [(Vec<u8>, u8); 4],
    /// The leg that must be planted before this one may step (3D seed rule).
    pub(crate) opposite: Vec<Option<usize>>,
    /// The other leg of this leg's left/right pair (hip roll).
    pub(crate) partner: Vec<Option<usize>>,
    /// The walking leg on this one's side whose rest position is the nearest behind it (the
    /// foot it must not trail onto, see `GaitOptions::foot_spacing`).
    pub(crate) hind: Vec<Option<usize>>,
}

/// Two consecutive pairs whose sizes are within this ratio step diagonally (3D seed).
const DIAGONAL_SCALE_RATIO: f32 = 0.8;

/// Derives the layout: groups from the caller or from the legs' positions, for each gait (the
/// walk's as before gaits by speed unless `by_speed`).
pub(crate) fn layout(legs: &[Leg], by_speed: bool) -> Result<Layout, GaitError> {
    let n = legs.len();
    let mut left: Vec<usize> = Vec::new();
    let mut right: Vec<usize> = Vec::new();
    let mut centre: Vec<usize> = Vec::new();
    let scale = legs.iter().map(|l| l.size).fold(0.0f32, f32::max).max(1e-6);
    for (i, leg) in legs.iter().enumerate() {
        if leg.kind != LimbKind::Leg {
            continue;
        }
        if leg.rest.x > 1e-4 * scale {
            left.push(i);
        } else if leg.rest.x < -1e-4 * scale {
            right.push(i);
        } else {
            centre.push(i);
        }
    }
    // Back to front (ascending Z), ties by index: deterministic.
    let mut by_z = |a: &usize, b: &usize| {
        let (za, zb) = (legs[*a].rest.z, legs[*b].rest.z);
        za.total_cmp(&zb).then(a.cmp(b))
    };
    sort_by(&mut left, &mut by_z);
    sort_by(&mut right, &mut by_z);
    sort_by(&mut centre, &mut by_z);

    let mut partner = alloc::vec![None; n];
    let mut opposite = alloc::vec![None; n];
    for k in 0..left.len().min(right.len()) {
        partner[left[k]] = Some(right[k]);
        partner[right[k]] = Some(left[k]);
    }
    let mut hind = alloc::vec![None; n];
    for side in [&left, &right] {
        for pair in side.windows(2) {
            if let &[back, front] = pair
                && legs[back].rest.z < legs[front].rest.z
            {
                hind[front] = Some(back);
            }
        }
    }

    let explicit = legs.iter().filter(|l| l.group.is_some()).count();
    if explicit > 0 {
        let mut groups: Vec<u8> = Vec::with_capacity(n);
        for (leg, l) in legs.iter().enumerate() {
            match l.group {
                Some(group) => groups.push(group),
                None => return Err(GaitError::MixedGroups { leg }),
            }
        }
        // Renumber to consecutive groups in ascending order of the caller's labels.
        let mut labels: Vec<u8> = groups.clone();
        sort_by(&mut labels, &mut Ord::cmp);
        labels.dedup();
        let groups: Vec<u8> = groups
            .iter()
            // `labels` is sorted and holds every group once: its index of `g`.
            .map(|g| labels.partition_point(|l| l < g) as u8)
            .collect();
        let group_count = labels.len().max(1) as u8;
        let by_gait = core::array::from_fn(|_| (groups.clone(), group_count));
        return Ok(Layout {
            groups,
            group_count,
            by_gait,
            opposite,
            partner,
            hind,
        });
    }

    let sides = Sides {
        left,
        right,
        centre,
    };
    let by_gait = Gait::ALL.map(|gait| gaits::groups(legs, &sides, gait, by_speed));
    let (groups, group_count) = by_gait[Gait::Walk as usize].clone();
    let Sides { left, right, .. } = sides;
    // The seed's opposite references: a foot steps only while its opposite is planted; the
    // left foot of a pair after the first watches the previous left foot when the two pairs
    // are of similar size, so diagonals move together.
    for k in 0..left.len().min(right.len()) {
        let (l, r) = (left[k], right[k]);
        opposite[r] = Some(l);
        opposite[l] = Some(r);
        if k > 0 {
            let prev = (legs[left[k - 1]].size + legs[right[k - 1]].size) * 0.5;
            let this = (legs[l].size + legs[r].size) * 0.5;
            if prev.min(this) >= DIAGONAL_SCALE_RATIO * prev.max(this) {
                opposite[l] = Some(left[k - 1]);
            }
        }
    }
    Ok(Layout {
        groups,
        group_count,
        by_gait,
        opposite,
        partner,
        hind,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout_(legs: &[Leg]) -> Result<Layout, GaitError> {
        layout(legs, false)
    }

    fn pairs(count: usize) -> Vec<Leg> {
        let mut legs = Vec::new();
        for k in 0..count {
            let z = 1.0 - k as f32 * 0.6;
            for side in [1.0f32, -1.0] {
                legs.push(Leg::new(
                    Vec3::new(0.3 * side, 0.8, z),
                    Vec3::new(0.4 * side, 0.0, z),
                    0.5,
                    0.5,
                ));
            }
        }
        legs
    }

    #[test]
    fn biped_alternates() {
        let l = layout_(&pairs(1)).unwrap();
        assert_eq!(l.group_count, 2);
        assert_ne!(l.groups[0], l.groups[1]);
        assert_eq!(l.opposite[0], Some(1));
        assert_eq!(l.opposite[1], Some(0));
    }

    #[test]
    fn quadruped_trots_with_diagonals_together() {
        let legs = pairs(2); // 0 FL, 1 FR, 2 BL, 3 BR
        let l = layout_(&legs).unwrap();
        assert_eq!(l.groups[0], l.groups[3]);
        assert_eq!(l.groups[1], l.groups[2]);
        assert_ne!(l.groups[0], l.groups[1]);
        // The front-left watches the back-left (previous left), the seed's rule.
        assert_eq!(l.opposite[0], Some(2));
        assert_eq!(l.partner[0], Some(1));
    }

    #[test]
    fn hexapod_uses_a_tripod() {
        let l = layout_(&pairs(3)).unwrap();
        // Left front, right middle, left back together.
        assert_eq!(l.groups[0], l.groups[3]);
        assert_eq!(l.groups[0], l.groups[4]);
        assert_eq!(l.groups[1], l.groups[2]);
        assert_eq!(l.groups[1], l.groups[5]);
    }

    #[test]
    fn many_legs_make_a_three_group_wave() {
        let legs = pairs(6);
        let l = layout_(&legs).unwrap();
        assert_eq!(l.group_count, 3);
        for k in 0..6 {
            assert_ne!(l.groups[2 * k], l.groups[2 * k + 1], "pair {k}");
            if k > 0 {
                assert_ne!(l.groups[2 * k], l.groups[2 * k - 2], "left neighbours {k}");
            }
        }
    }

    #[test]
    fn dissimilar_pairs_keep_plain_opposites() {
        let mut legs = pairs(2);
        legs[0].size = 0.3;
        legs[1].size = 0.3;
        let l = layout_(&legs).unwrap();
        assert_eq!(l.opposite[0], Some(1));
    }

    #[test]
    fn mixed_groups_are_rejected_and_labels_renumbered() {
        let mut legs = pairs(1);
        legs[0].group = Some(7);
        assert_eq!(layout_(&legs), Err(GaitError::MixedGroups { leg: 1 }));
        legs[1].group = Some(3);
        let l = layout_(&legs).unwrap();
        assert_eq!(l.groups, alloc::vec![1, 0]);
        assert_eq!(l.group_count, 2);
    }

    #[test]
    fn leg_validation() {
        let leg = Leg::new(Vec3::ZERO, Vec3::NEG_Y, 0.5, 0.5);
        assert!(leg.validate(0).is_ok());
        assert!(matches!(
            leg.with_pole(Vec3::ZERO).validate(2),
            Err(GaitError::ZeroVector { index: 2, .. })
        ));
        let mut bad = leg;
        bad.upper = 0.0;
        assert!(matches!(
            bad.validate(0),
            Err(GaitError::NotPositive { .. })
        ));
        bad = leg;
        bad.hip = Vec3::NAN;
        assert!(matches!(bad.validate(0), Err(GaitError::NonFinite { .. })));
    }

    #[test]
    fn chain_validation() {
        let c = Chain::new(Vec3::ZERO, Vec3::NEG_Z, 4, 0.2);
        assert!(c.validate(0).is_ok());
        assert!(
            Chain::new(Vec3::ZERO, Vec3::ZERO, 4, 0.2)
                .validate(0)
                .is_err()
        );
        assert!(
            Chain::new(Vec3::ZERO, Vec3::NEG_Z, 0, 0.2)
                .validate(0)
                .is_err()
        );
        assert!(
            Chain::new(Vec3::ZERO, Vec3::NEG_Z, 65, 0.2)
                .validate(0)
                .is_err()
        );
        assert!(c.with_spring(-1.0, 1.0).validate(0).is_err());
    }
}
