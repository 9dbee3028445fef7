//! The crate's error type.

use core::fmt;

/// What was wrong with a [`Body`](crate::Body) or [`PlanOptions`](crate::PlanOptions) given to
/// [`plan`](crate::plan).
///
/// Every variant carries the offending value or bone index, and its `Display` message says what
/// to change in the input.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum LimbsError {
    /// The body has no spine bones with sockets.
    NoBones,
    /// The body has more bones than [`MAX_BONES`](crate::MAX_BONES).
    TooManyBones {
        /// How many bones were given.
        count: usize,
        /// The largest supported count.
        max: usize,
    },
    /// A float of the body was NaN or infinite.
    NonFinite {
        /// Which value, e.g. `"along"`, `"left socket"`, `"width"`, `"clearance"`,
        /// `"body length"`.
        what: &'static str,
        /// The bone it belongs to (0 for the body length).
        bone: usize,
    },
    /// A float of the body was larger in magnitude than [`MAX_EXTENT`](crate::MAX_EXTENT).
    TooLarge {
        /// Which value.
        what: &'static str,
        /// The bone it belongs to (0 for the body length).
        bone: usize,
        /// The value given (for vectors, its largest coordinate in magnitude).
        value: f32,
    },
    /// A width or clearance was negative.
    Negative {
        /// `"width"` or `"clearance"`.
        what: &'static str,
        /// The bone.
        bone: usize,
        /// The value given.
        value: f32,
    },
    /// The body length was zero or negative.
    NonPositiveLength {
        /// The value given.
        length: f32,
    },
    /// The bones' positions along the body do not strictly increase with their index.
    NotIncreasing {
        /// The first bone whose `along` is not greater than its predecessor's.
        bone: usize,
        /// Its `along`.
        along: f32,
        /// The predecessor's `along`.
        previous: f32,
    },
    /// An option was NaN, infinite, out of its allowed range, or a `[min, max]` pair had
    /// `min > max`.
    InvalidOption {
        /// The option's field name in [`PlanOptions`](crate::PlanOptions).
        name: &'static str,
        /// The offending value (the minimum, for a reversed range).
        value: f32,
    },
}

impl fmt::Display for LimbsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NoBones => write!(
                f,
                "the body has no bones: pass at least one spine bone with sockets"
            ),
            Self::TooManyBones { count, max } => write!(
                f,
                "the body has {count} bones: pass at most {max} (merge neighbouring bones)"
            ),
            Self::NonFinite { what, bone } => write!(
                f,
                "{what} of bone {bone} is NaN or infinite: pass finite values"
            ),
            Self::TooLarge { what, bone, value } => write!(
                f,
                "{what} of bone {bone} is {value:e}: keep every coordinate and size within \
                 ±{:e} (rescale the body)",
                crate::MAX_EXTENT
            ),
            Self::Negative { what, bone, value } => write!(
                f,
                "{what} of bone {bone} is {value}: it must be zero or more"
            ),
            Self::NonPositiveLength { length } => write!(
                f,
                "the body length is {length}: it must be greater than zero"
            ),
            Self::NotIncreasing {
                bone,
                along,
                previous,
            } => write!(
                f,
                "bone {bone} sits at {along} along the body, not after bone {} at {previous}: \
                 order the bones from one end to the other with strictly increasing `along`",
                bone.saturating_sub(1)
            ),
            Self::InvalidOption { name, value } => write!(
                f,
                "option `{name}` is {value}: see its documented range in PlanOptions (ranges \
                 need min <= max)"
            ),
        }
    }
}

impl core::error::Error for LimbsError {}

#[cfg(test)]
mod tests {
    use alloc::string::ToString;

    use super::*;

    #[test]
    fn messages_say_what_to_fix() {
        let msg = LimbsError::NoBones.to_string();
        assert!(msg.contains("at least one"), "{msg}");
        let msg = LimbsError::NotIncreasing {
            bone: 3,
            along: 1.0,
            previous: 2.0,
        }
        .to_string();
        assert!(msg.contains("after bone 2"), "{msg}");
        assert!(msg.contains("strictly increasing"), "{msg}");
        let msg = LimbsError::Negative {
            what: "width",
            bone: 1,
            value: -1.0,
        }
        .to_string();
        assert!(msg.contains("zero or more"), "{msg}");
    }

    #[test]
    fn error_trait_is_implemented_without_std() {
        fn takes_error(_: &dyn core::error::Error) {}
        takes_error(&LimbsError::NoBones);
    }
}
