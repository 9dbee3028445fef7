//! The facade's error type: bad parameters, invalid creatures, and every sub-crate's error.

use alloc::string::String;
use core::fmt;

use glam::Vec2;

use creature_autorig::AutorigError;
use creature_ffd::FfdError;
use creature_gait::GaitError;
use creature_limbs::LimbsError;
use creature_march::MarchError;
use creature_metaball::MetaballError;
use creature_skin::SkinError;

/// What went wrong when generating, building or exporting a creature.
///
/// Parameter errors name the field and say what to pass; pipeline errors name the stage; the
/// sub-crates' errors are wrapped as they are (`From` converts them, so `?` works).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// A parameter was NaN or infinite.
    NonFinite {
        /// The [`d2::Params`](crate::d2::Params) field or skeleton input, e.g. `"spine_thickness"`.
        what: &'static str,
    },
    /// A parameter lies outside the range this crate supports for it.
    OutOfRange {
        /// The field, e.g. `"limb_probability"`.
        what: &'static str,
        /// The value given.
        value: f32,
        /// Smallest accepted value.
        min: f32,
        /// Largest accepted value.
        max: f32,
    },
    /// A range parameter has its minimum above its maximum.
    EmptyRange {
        /// The field, e.g. `"spine_length"`.
        what: &'static str,
        /// The minimum given.
        min: f32,
        /// The maximum given.
        max: f32,
    },
    /// A set of weights has every weight 0, so nothing can be drawn from it.
    AllZero {
        /// The field, e.g. `"patterns"`.
        what: &'static str,
    },
    /// A skeleton bone's parent is missing, itself, or a later bone (parents come first), or the
    /// first bone has a parent.
    BadParent {
        /// The bone.
        bone: usize,
        /// Its parent index, if it has one.
        parent: Option<usize>,
    },
    /// A skeleton has no bones, or no bone with a thickness (nothing to cover with balls).
    EmptySkeleton,
    /// A skeleton has more bones than glTF joints can index.
    TooManyBones {
        /// Bones given.
        bones: usize,
        /// The largest supported count.
        max: usize,
    },
    /// The outline did not come out as one piece: some balls form a separate component (the
    /// seed silently dropped such parts).
    Detached {
        /// How many outer rings the outline has.
        components: usize,
    },
    /// A ball centre lies outside the traced outline: the outline step is too coarse for a
    /// thin part (lower `outline_step`, or raise the thicknesses).
    BallOutside {
        /// The ball's index in [`d2::Creature::balls`](crate::d2::Creature::balls).
        ball: usize,
        /// The bone that owns it.
        bone: usize,
        /// Its centre.
        center: Vec2,
    },
    /// The outline, mesh or rig came out degenerate (for example a zero-height bounding box).
    Degenerate {
        /// What was degenerate.
        what: &'static str,
    },
    /// A creature kind, limb type or socket that this version of the facade has no entry for:
    /// the `creature-limbs` in use is newer than this `creature`.
    Unsupported {
        /// What has no entry, e.g. `"limb type"`.
        what: &'static str,
    },
    /// A walking clip was asked of a creature without a gait set-up (fliers and swimmers):
    /// their clips come from [`Creature::bake_clips`](crate::d3::Creature::bake_clips).
    NoGait,
    /// Encoding an export failed (feature `export`).
    Export {
        /// The format, e.g. `"png"`, `"glb"`.
        format: &'static str,
        /// The encoder's message.
        message: String,
    },
    /// From `creature-metaball`.
    Metaball(MetaballError),
    /// From `creature-march`.
    March(MarchError),
    /// From `creature-skin`.
    Skin(SkinError),
    /// From `creature-ffd`.
    Ffd(FfdError),
    /// From `creature-autorig`.
    Rig(AutorigError),
    /// From `creature-limbs`.
    Limbs(LimbsError),
    /// From `creature-gait`.
    Gait(GaitError),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite { what } => write!(f, "{what} is NaN or infinite: pass finite values"),
            Self::OutOfRange {
                what,
                value,
                min,
                max,
            } => write!(f, "{what} is {value}: pass a value from {min} to {max}"),
            Self::EmptyRange { what, min, max } => write!(
                f,
                "{what} runs from {min} to {max}: its minimum must not exceed its maximum"
            ),
            Self::AllZero { what } => write!(
                f,
                "every weight of {what} is 0: give at least one a weight above 0"
            ),
            Self::BadParent { bone, parent } => match parent {
                Some(p) => write!(
                    f,
                    "bone {bone} has parent {p}: a parent must be an earlier bone"
                ),
                None => write!(
                    f,
                    "bone {bone} has no parent: only the first bone may be a root"
                ),
            },
            Self::EmptySkeleton => write!(
                f,
                "the skeleton has no bone with a thickness: give at least one bone a thickness above 0"
            ),
            Self::TooManyBones { bones, max } => {
                write!(f, "the skeleton has {bones} bones: use at most {max}")
            }
            Self::Detached { components } => write!(
                f,
                "the outline has {components} separate pieces: keep every part connected to the body"
            ),
            Self::BallOutside { ball, bone, center } => write!(
                f,
                "ball {ball} of bone {bone} at {center} lies outside the outline: lower outline_step or thicken the bone"
            ),
            Self::Degenerate { what } => write!(f, "the {what} is degenerate"),
            Self::Unsupported { what } => write!(
                f,
                "this {what} is new to this version of creature: update creature to the release made for your creature-limbs"
            ),
            Self::NoGait => write!(
                f,
                "this creature has no gait set-up: only walkers walk (use bake_clips for fliers and swimmers)"
            ),
            Self::Export { format, message } => write!(f, "could not encode {format}: {message}"),
            Self::Metaball(e) => write!(f, "metaballs: {e}"),
            Self::March(e) => write!(f, "outline or mesh: {e}"),
            Self::Skin(e) => write!(f, "skin weights: {e}"),
            Self::Ffd(e) => write!(f, "ffd: {e}"),
            Self::Rig(e) => write!(f, "autorig: {e}"),
            Self::Limbs(e) => write!(f, "limbs: {e}"),
            Self::Gait(e) => write!(f, "gait: {e}"),
        }
    }
}

impl core::error::Error for Error {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Self::Metaball(e) => Some(e),
            Self::March(e) => Some(e),
            Self::Skin(e) => Some(e),
            Self::Ffd(e) => Some(e),
            Self::Rig(e) => Some(e),
            Self::Limbs(e) => Some(e),
            Self::Gait(e) => Some(e),
            _ => None,
        }
    }
}

macro_rules! wrap {
    ($($source:ty => $variant:ident),* $(,)?) => {
        $(impl From<$source> for Error {
            fn from(e: $source) -> Self {
                Self::$variant(e)
            }
        })*
    };
}

wrap! {
    MetaballError => Metaball,
    MarchError => March,
    SkinError => Skin,
    FfdError => Ffd,
    AutorigError => Rig,
    LimbsError => Limbs,
    GaitError => Gait,
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    #[test]
    fn messages_are_lowercase_and_say_what_to_do() {
        let e = Error::EmptyRange {
            what: "spine_length",
            min: 5.0,
            max: 1.0,
        };
        let text = e.to_string();
        assert!(text.starts_with("spine_length"));
        assert!(text.contains("must not exceed"));
        let wrapped: Error = MetaballError::NoBalls.into();
        assert!(matches!(wrapped, Error::Metaball(MetaballError::NoBalls)));
        assert!(core::error::Error::source(&wrapped).is_some());
    }
}
