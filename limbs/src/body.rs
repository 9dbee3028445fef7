//! The planner's input: plain data about a body's spine, as an auto-rigger or a game provides it.

use alloc::vec::Vec;

use glam::{Vec2, Vec3};

use crate::LimbsError;

/// The most bones a [`Body`] may have. Real spines have 4 to 30; the limit bounds the planner's
/// worst-case work (its repairs try every bone against every layout).
pub const MAX_BONES: usize = 64;

/// The largest magnitude accepted for any coordinate or size of a [`Body`], so that sums and
/// squares in the planner stay finite.
pub const MAX_EXTENT: f32 = 1.0e6;

/// What kind of creature the limbs are planned for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum CreatureKind {
    /// Walks on legs, maybe with arms: placement keeps it statically stable.
    Walker,
    /// Flies on buzzing (insect) or flapping (bird) wings, with 1 to 8 hanging leg pairs.
    Flier,
    /// Swims with dorsal fins, pectoral fin pairs and a tail.
    Swimmer,
    /// Crawls on its belly without limbs (a snake): the plan is empty.
    Slitherer,
}

/// Which end of [`Body::bones`] is the head.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HeadEnd {
    /// `bones[0]` is nearest the head.
    First,
    /// The last bone is nearest the head (the usual order when `along` grows toward the head).
    Last,
}

/// One spine bone that carries sockets (the auto-rigger gives sockets to every bone but the
/// first and last).
///
/// All positions are in body space, with the workspace's (glTF's) convention: right-handed,
/// +Y up, the creature facing +Z, so its left is +X and its right −X. Any length unit (metres
/// in `creature`). The planner never assumes the facing: it takes `left` and `right` as given,
/// so a body facing elsewhere works as long as `left` is the creature's own left.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpineBone {
    /// Position of the bone along the body axis, in body units. Must strictly increase with the
    /// bone's index in [`Body::bones`]; spans and overlap checks are measured in this
    /// coordinate.
    pub along: f32,
    /// The left socket: the closest surface point on the creature's left side (+X for a
    /// creature facing +Z).
    pub left: Vec3,
    /// The right socket: the closest surface point on the creature's right side (−X for a
    /// creature facing +Z).
    pub right: Vec3,
    /// The top socket: the closest surface point on the body's top.
    pub top: Vec3,
    /// Width of the body at this bone (the left–right socket distance), zero or more.
    pub width: f32,
    /// Height above the ground of the lower of the two side sockets, zero or more. A leg on
    /// this bone is at least this long.
    pub clearance: f32,
}

impl SpineBone {
    /// A bone whose width is the distance between its side sockets.
    ///
    /// ```
    /// use creature_limbs::{SpineBone, glam::Vec3};
    /// // Facing +Z: the left socket is on +X, the right one on −X.
    /// let bone = SpineBone::from_sockets(0.5, Vec3::new(0.2, 1.0, 0.5), Vec3::new(-0.2, 1.0, 0.5),
    ///     Vec3::new(0.0, 1.2, 0.5), 1.0);
    /// assert!((bone.width - 0.4).abs() < 1e-6);
    /// ```
    #[must_use]
    pub fn from_sockets(along: f32, left: Vec3, right: Vec3, top: Vec3, clearance: f32) -> Self {
        Self {
            along,
            left,
            right,
            top,
            width: left.distance(right),
            clearance,
        }
    }

    /// The midpoint of the two side sockets.
    #[must_use]
    pub fn center(&self) -> Vec3 {
        (self.left + self.right) * 0.5
    }

    /// The ground height under this bone, in body space (before any lift).
    #[must_use]
    pub fn ground(&self) -> f32 {
        self.left.y.min(self.right.y) - self.clearance
    }
}

/// A body to plan limbs for: its spine bones, its length and which end is the head.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// The bones that carry sockets, ordered along the body (strictly increasing
    /// [`SpineBone::along`]).
    pub bones: Vec<SpineBone>,
    /// The body's overall length, head tip to tail tip, in body units. Limb sizes that the
    /// options give as fractions are fractions of this length.
    pub length: f32,
    /// Which end of `bones` is the head.
    pub head: HeadEnd,
}

impl Body {
    /// A body from its parts (not validated: [`plan`](crate::plan) and
    /// [`validate`](Self::validate) do that).
    #[must_use]
    pub const fn new(bones: Vec<SpineBone>, length: f32, head: HeadEnd) -> Self {
        Self {
            bones,
            length,
            head,
        }
    }

    /// Checks everything [`plan`](crate::plan) requires of a body.
    ///
    /// # Errors
    ///
    /// [`LimbsError::NoBones`], [`TooManyBones`](LimbsError::TooManyBones),
    /// [`NonFinite`](LimbsError::NonFinite), [`TooLarge`](LimbsError::TooLarge),
    /// [`Negative`](LimbsError::Negative), [`InvalidLength`](LimbsError::InvalidLength)
    /// or [`NotIncreasing`](LimbsError::NotIncreasing), for the first problem found.
    pub fn validate(&self) -> Result<(), LimbsError> {
        if self.bones.is_empty() {
            return Err(LimbsError::NoBones);
        }
        if self.bones.len() > MAX_BONES {
            return Err(LimbsError::TooManyBones {
                count: self.bones.len(),
                max: MAX_BONES,
            });
        }
        if !(self.length > 0.0 && self.length <= MAX_EXTENT) {
            return Err(LimbsError::InvalidLength {
                length: self.length,
            });
        }
        let mut previous: Option<f32> = None;
        for (i, bone) in self.bones.iter().enumerate() {
            check_scalar("along", i, bone.along)?;
            check_vec("left socket", i, bone.left)?;
            check_vec("right socket", i, bone.right)?;
            check_vec("top socket", i, bone.top)?;
            check_scalar("width", i, bone.width)?;
            check_scalar("clearance", i, bone.clearance)?;
            if bone.width < 0.0 {
                return Err(LimbsError::Negative {
                    what: "width",
                    bone: i,
                    value: bone.width,
                });
            }
            if bone.clearance < 0.0 {
                return Err(LimbsError::Negative {
                    what: "clearance",
                    bone: i,
                    value: bone.clearance,
                });
            }
            if let Some(prev) = previous
                && !(bone.along > prev)
            {
                return Err(LimbsError::NotIncreasing {
                    bone: i,
                    along: bone.along,
                    previous: prev,
                });
            }
            previous = Some(bone.along);
        }
        Ok(())
    }

    /// Number of bones.
    #[must_use]
    pub fn bone_count(&self) -> usize {
        self.bones.len()
    }

    /// Index in [`bones`](Self::bones) of the bone at position `k` counted from the head
    /// (`k = 0` is the bone nearest the head). `k` must be below the bone count.
    #[must_use]
    pub fn from_head(&self, k: usize) -> usize {
        match self.head {
            HeadEnd::First => k,
            HeadEnd::Last => self.bones.len().saturating_sub(1).saturating_sub(k),
        }
    }

    /// Position counted from the head (0 = nearest the head) of the bone at `index`.
    #[must_use]
    pub fn head_rank(&self, index: usize) -> usize {
        self.from_head(index)
    }

    /// The centre of mass of the body projected to the ground, as `(x, z)`: the side-socket
    /// midpoints weighted by width squared (a cross-section area), or equally when every width
    /// is zero. The body must be valid.
    #[must_use]
    pub fn center_of_mass(&self) -> Vec2 {
        let mut sum = Vec2::ZERO;
        let mut total = 0.0f32;
        for bone in &self.bones {
            let w = bone.width * bone.width;
            let c = bone.center();
            sum += Vec2::new(c.x, c.z) * w;
            total += w;
        }
        if total > 0.0 {
            return sum / total;
        }
        let n = self.bones.len().max(1) as f32;
        self.bones
            .iter()
            .map(|b| {
                let c = b.center();
                Vec2::new(c.x, c.z)
            })
            .fold(Vec2::ZERO, |a, b| a + b)
            / n
    }
}

fn check_scalar(what: &'static str, bone: usize, value: f32) -> Result<(), LimbsError> {
    if !value.is_finite() {
        return Err(LimbsError::NonFinite { what, bone });
    }
    if value.abs() > MAX_EXTENT {
        return Err(LimbsError::TooLarge { what, bone, value });
    }
    Ok(())
}

fn check_vec(what: &'static str, bone: usize, value: Vec3) -> Result<(), LimbsError> {
    if !value.is_finite() {
        return Err(LimbsError::NonFinite { what, bone });
    }
    let m = value.abs().max_element();
    if m > MAX_EXTENT {
        return Err(LimbsError::TooLarge {
            what,
            bone,
            value: m,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::*;

    fn bone(along: f32) -> SpineBone {
        SpineBone::from_sockets(
            along,
            Vec3::new(0.5, 1.0, along),
            Vec3::new(-0.5, 1.0, along),
            Vec3::new(0.0, 1.5, along),
            1.0,
        )
    }

    #[test]
    fn head_order_follows_the_head_end() {
        let body = Body::new(vec![bone(0.0), bone(1.0), bone(2.0)], 3.0, HeadEnd::Last);
        assert_eq!(body.from_head(0), 2);
        assert_eq!(body.from_head(2), 0);
        let body = Body {
            head: HeadEnd::First,
            ..body
        };
        assert_eq!(body.from_head(0), 0);
    }

    #[test]
    fn validation_finds_each_problem() {
        let good = Body::new(vec![bone(0.0), bone(1.0)], 3.0, HeadEnd::Last);
        assert_eq!(good.validate(), Ok(()));
        let mut b = good.clone();
        b.bones.clear();
        assert_eq!(b.validate(), Err(LimbsError::NoBones));
        let mut b = good.clone();
        b.bones[1].along = 0.0;
        assert!(matches!(
            b.validate(),
            Err(LimbsError::NotIncreasing { bone: 1, .. })
        ));
        let mut b = good.clone();
        b.bones[0].width = -1.0;
        assert!(matches!(
            b.validate(),
            Err(LimbsError::Negative { what: "width", .. })
        ));
        let mut b = good.clone();
        b.bones[1].top.x = f32::NAN;
        assert!(matches!(
            b.validate(),
            Err(LimbsError::NonFinite {
                what: "top socket",
                bone: 1
            })
        ));
        let mut b = good.clone();
        b.length = 0.0;
        assert!(matches!(
            b.validate(),
            Err(LimbsError::InvalidLength { .. })
        ));
        let mut b = good.clone();
        b.length = f32::INFINITY;
        assert!(matches!(
            b.validate(),
            Err(LimbsError::InvalidLength { .. })
        ));
        let mut b = good;
        b.bones[0].clearance = 1.0e30;
        assert!(matches!(b.validate(), Err(LimbsError::TooLarge { .. })));
    }

    #[test]
    fn center_of_mass_weights_wide_bones() {
        let mut a = bone(0.0);
        let b = bone(1.0);
        a.width = 3.0;
        let body = Body::new(vec![a, b], 2.0, HeadEnd::Last);
        let com = body.center_of_mass();
        assert!(com.y < 0.5 && com.y > 0.0, "{com}");
    }
}
