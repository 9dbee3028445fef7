//! Rigging options.

use crate::error::AutorigError;

/// Where the spine's root joint sits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum RootAt {
    /// At the body's centre, with bones running out to the head and to the tail (the seed's
    /// walkers and fliers: the neck and tail then move independently).
    #[default]
    Centre,
    /// At the head, with bones running back to the tail (the seed's swimmers: the body undulates
    /// from the head).
    Head,
}

/// Options for [`rig`](crate::rig).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct RigOptions {
    /// Where the root joint sits. Default [`RootAt::Centre`].
    pub root: RootAt,
    /// Half-width of the tube around the body's centre line (the line through the bounding-box
    /// centre along Z) in which the head and tail vertices are sought, as a fraction of the
    /// larger of the body's X and Y extents. Default 0.25. When the tube holds fewer than two
    /// vertices it is widened (doubled) until it does.
    pub centre_tolerance: f32,
    /// Target length of a spine bone, in the mesh's units: the bone count is the spine's length
    /// divided by this, rounded, then clamped to `min_bones..=max_bones`. Default 0.4.
    pub bone_length: f32,
    /// Fewest spine bones, at least 2. Default 3 (the fewest that leave a socket: the first and
    /// last bones get none).
    pub min_bones: usize,
    /// Most spine bones, at most [`MAX_BONES`](Self::MAX_BONES). Default 24.
    pub max_bones: usize,
    /// Follow the body's medial line (centroids of cross-sections along the head–tail axis), so
    /// a bent body gets a spine inside it. With `false`, joints lie on the straight head–tail
    /// chord, as in the seed. Default `true`.
    pub follow_medial_line: bool,
}

impl RigOptions {
    /// The largest accepted `max_bones`.
    pub const MAX_BONES: usize = 1024;

    /// The defaults listed on each field.
    pub const DEFAULT: Self = Self {
        root: RootAt::Centre,
        centre_tolerance: 0.25,
        bone_length: 0.4,
        min_bones: 3,
        max_bones: 24,
        follow_medial_line: true,
    };

    /// Sets [`root`](Self::root).
    #[must_use]
    pub const fn with_root(mut self, root: RootAt) -> Self {
        self.root = root;
        self
    }

    /// Sets [`centre_tolerance`](Self::centre_tolerance).
    #[must_use]
    pub const fn with_centre_tolerance(mut self, centre_tolerance: f32) -> Self {
        self.centre_tolerance = centre_tolerance;
        self
    }

    /// Sets [`bone_length`](Self::bone_length).
    #[must_use]
    pub const fn with_bone_length(mut self, bone_length: f32) -> Self {
        self.bone_length = bone_length;
        self
    }

    /// Sets [`min_bones`](Self::min_bones) and [`max_bones`](Self::max_bones).
    #[must_use]
    pub const fn with_bone_count(mut self, min_bones: usize, max_bones: usize) -> Self {
        self.min_bones = min_bones;
        self.max_bones = max_bones;
        self
    }

    /// Sets [`follow_medial_line`](Self::follow_medial_line).
    #[must_use]
    pub const fn with_follow_medial_line(mut self, follow: bool) -> Self {
        self.follow_medial_line = follow;
        self
    }

    /// Checks every option; [`rig`](crate::rig) calls this first.
    ///
    /// # Errors
    /// [`AutorigError::InvalidOption`] or [`AutorigError::InvalidBoneCount`].
    pub fn validate(&self) -> Result<(), AutorigError> {
        for (what, value) in [
            ("centre_tolerance", self.centre_tolerance),
            ("bone_length", self.bone_length),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(AutorigError::InvalidOption { what, value });
            }
        }
        if self.min_bones < 2 || self.min_bones > self.max_bones || self.max_bones > Self::MAX_BONES
        {
            return Err(AutorigError::InvalidBoneCount {
                min: self.min_bones,
                max: self.max_bones,
            });
        }
        Ok(())
    }
}

impl Default for RigOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_setters_set() {
        assert_eq!(RigOptions::default().validate(), Ok(()));
        let o = RigOptions::DEFAULT
            .with_root(RootAt::Head)
            .with_bone_length(1.0)
            .with_bone_count(4, 8)
            .with_centre_tolerance(0.2)
            .with_follow_medial_line(false);
        assert_eq!(o.root, RootAt::Head);
        assert_eq!((o.min_bones, o.max_bones), (4, 8));
        assert!(!o.follow_medial_line);
        assert_eq!(o.validate(), Ok(()));
    }

    #[test]
    fn bad_options_are_errors() {
        assert_eq!(
            RigOptions::DEFAULT.with_bone_length(0.0).validate(),
            Err(AutorigError::InvalidOption {
                what: "bone_length",
                value: 0.0
            })
        );
        assert!(matches!(
            RigOptions::DEFAULT
                .with_centre_tolerance(f32::NAN)
                .validate(),
            Err(AutorigError::InvalidOption {
                what: "centre_tolerance",
                ..
            })
        ));
        for (min, max) in [(1, 5), (6, 5), (2, 2000)] {
            assert_eq!(
                RigOptions::DEFAULT.with_bone_count(min, max).validate(),
                Err(AutorigError::InvalidBoneCount { min, max })
            );
        }
    }
}
