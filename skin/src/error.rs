//! The crate's error type.

use core::fmt;

/// What went wrong when computing or applying skinning weights.
///
/// Every variant carries the offending value or index, and its `Display` message says what to
/// change in the input.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum SkinError {
    /// A float input (vertex, bone end, normal, transform, contribution, option) was NaN or
    /// infinite.
    NonFinite {
        /// Which input, e.g. `"vertex"`, `"bone"`, `"normal"`, `"transform"`, `"contribution"`.
        what: &'static str,
        /// Position of the value in its list (0 for single values).
        index: usize,
    },
    /// A coordinate was finite but larger in magnitude than
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE): squared distances would overflow `f32`.
    CoordinateTooLarge {
        /// Which input, `"vertex"` or `"bone"`.
        what: &'static str,
        /// Position of the value in its list.
        index: usize,
        /// The offending coordinate.
        value: f32,
    },
    /// The number of influences per vertex must be between 1 and
    /// [`MAX_INFLUENCES`](crate::MAX_INFLUENCES).
    InvalidInfluenceCount {
        /// The `k` that was asked for.
        k: usize,
    },
    /// No bones were given: every vertex needs at least one bone to bind to.
    NoBones,
    /// More bones than a `u16` joint index can address.
    TooManyBones {
        /// How many bones were given.
        count: usize,
    },
    /// A bone id does not fit a `u16` joint index.
    BoneIdTooLarge {
        /// Position of the pair in the contributions.
        index: usize,
        /// The bone id given.
        bone: u32,
    },
    /// A contribution value was negative.
    NegativeContribution {
        /// Position of the pair in the contributions.
        index: usize,
        /// The value given.
        value: f32,
    },
    /// Every contribution of a vertex was zero (or there were none), so there is nothing to
    /// normalise.
    ZeroContribution,
    /// A falloff parameter was not a finite positive number.
    InvalidFalloff {
        /// The parameter, e.g. `"power"` or `"spread"`.
        what: &'static str,
        /// The value given.
        value: f32,
    },
    /// Two lists that must have one entry per vertex had different lengths.
    WrongLength {
        /// Which list, e.g. `"influences"` or `"output"`.
        what: &'static str,
        /// The length it must have.
        expected: usize,
        /// The length it had.
        found: usize,
    },
    /// A vertex's influences name a joint with no transform.
    JointOutOfRange {
        /// The vertex.
        vertex: usize,
        /// The joint index it names.
        joint: u16,
        /// How many transforms were given.
        joints: usize,
    },
    /// A vertex's weights contain a negative, NaN or infinite value.
    InvalidWeights {
        /// The vertex.
        vertex: usize,
    },
    /// Dual-quaternion skinning needs a rotation in every used transform, but this one's
    /// linear part is singular (a zero or repeated axis).
    SingularTransform {
        /// The joint.
        joint: usize,
    },
    /// A skinned position overflowed `f32`.
    NonFiniteResult {
        /// The vertex.
        index: usize,
    },
}

impl fmt::Display for SkinError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NonFinite { what, index } => {
                write!(f, "{what} {index} is NaN or infinite: pass finite values")
            }
            Self::CoordinateTooLarge { what, index, value } => write!(
                f,
                "{what} {index} has coordinate {value:e}: keep coordinates within ±{:e} \
                 (scale the model down)",
                crate::MAX_COORDINATE
            ),
            Self::InvalidInfluenceCount { k } => write!(
                f,
                "{k} influences per vertex were asked for: pass a count from 1 to {}",
                crate::MAX_INFLUENCES
            ),
            Self::NoBones => write!(f, "no bones were given: pass at least one bone"),
            Self::TooManyBones { count } => write!(
                f,
                "{count} bones were given: pass at most {} (joint indices are u16)",
                crate::MAX_BONES
            ),
            Self::BoneIdTooLarge { index, bone } => write!(
                f,
                "contribution {index} names bone {bone}: bone ids must be at most {} (joint \
                 indices are u16)",
                u16::MAX
            ),
            Self::NegativeContribution { index, value } => write!(
                f,
                "contribution {index} is {value}: pass values of zero or more"
            ),
            Self::ZeroContribution => write!(
                f,
                "the vertex has no positive contribution: give it one, or use \
                 from_contributions_or with a fallback bone"
            ),
            Self::InvalidFalloff { what, value } => write!(
                f,
                "falloff {what} is {value}: pass a finite value greater than zero"
            ),
            Self::WrongLength {
                what,
                expected,
                found,
            } => write!(
                f,
                "{what} has {found} entries: pass exactly {expected}, one per vertex"
            ),
            Self::JointOutOfRange {
                vertex,
                joint,
                joints,
            } => write!(
                f,
                "vertex {vertex} is bound to joint {joint} but only {joints} transforms were \
                 given: pass a transform for every joint"
            ),
            Self::InvalidWeights { vertex } => write!(
                f,
                "vertex {vertex} has a negative, NaN or infinite weight: weights must be finite \
                 and zero or more"
            ),
            Self::SingularTransform { joint } => write!(
                f,
                "transform {joint} has a singular linear part, so it has no rotation for \
                 dual-quaternion skinning: fix the transform or use Blend::Linear"
            ),
            Self::NonFiniteResult { index } => write!(
                f,
                "vertex {index} skinned to a non-finite position: the transforms are too large \
                 for f32; scale them down"
            ),
        }
    }
}

impl core::error::Error for SkinError {}

#[cfg(test)]
mod tests {
    use alloc::string::ToString;

    use super::*;

    #[test]
    fn messages_say_what_to_fix() {
        let msg = SkinError::InvalidInfluenceCount { k: 5 }.to_string();
        assert!(msg.contains("from 1 to 4"), "{msg}");
        let msg = SkinError::TooManyBones { count: 70_000 }.to_string();
        assert!(msg.contains("at most 65536"), "{msg}");
        let msg = SkinError::ZeroContribution.to_string();
        assert!(msg.contains("from_contributions_or"), "{msg}");
        let msg = SkinError::JointOutOfRange {
            vertex: 3,
            joint: 9,
            joints: 2,
        }
        .to_string();
        assert!(msg.contains("joint 9") && msg.contains("only 2"), "{msg}");
    }

    #[test]
    fn error_trait_is_implemented_without_std() {
        fn takes_error(_: &dyn core::error::Error) {}
        takes_error(&SkinError::NoBones);
    }
}
