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
        /// Which value: `"along"`, `"left socket"`, `"right socket"`, `"top socket"`,
        /// `"width"` or `"clearance"`.
        what: &'static str,
        /// The bone it belongs to.
        bone: usize,
    },
    /// A float of the body was larger in magnitude than [`MAX_EXTENT`](crate::MAX_EXTENT).
    TooLarge {
        /// Which value (as for [`NonFinite`](Self::NonFinite)).
        what: &'static str,
        /// The bone it belongs to.
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
    /// The body length was NaN, infinite, zero or negative, or larger than
    /// [`MAX_EXTENT`](crate::MAX_EXTENT).
    InvalidLength {
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
    /// An option was NaN, infinite, outside the range documented on its field of
    /// [`PlanOptions`](crate::PlanOptions), or a `[min, max]` pair had `min > max`.
    InvalidOption {
        /// The option's field name in [`PlanOptions`](crate::PlanOptions).
        name: &'static str,
        /// The offending value (the minimum, for a reversed range).
        value: f32,
    },
    /// No layout of leg pairs keeps this walker standing: even legs on every bone tall enough
    /// for them (at strides short enough not to overlap) leave the centre of mass less than
    /// `required` inside the support region. Typically the body's mass lies beyond its last
    /// bone that can carry legs (a heavy end too low for legs), or the options ask for more
    /// margin than its feet can give.
    NoStableLayout {
        /// The margin with legs on every bone tall enough for them: the most any layout can
        /// reach, in body units (negative: it tips over).
        margin: f32,
        /// The margin required: [`PlanOptions::min_margin`](crate::PlanOptions::min_margin) ×
        /// body length.
        required: f32,
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
            Self::InvalidLength { length } => write!(
                f,
                "the body length is {length}: pass a finite length greater than zero and at \
                 most {:e}",
                crate::MAX_EXTENT
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
                "option `{name}` is {value}: keep it within the range documented on \
                 PlanOptions::{name} (and a [min, max] pair needs min <= max)"
            ),
            Self::NoStableLayout { margin, required } => write!(
                f,
                "no layout of leg pairs keeps this walker standing: even legs on every bone tall \
                 enough for them give a stability margin of {margin}, below the required \
                 {required}; put bones that can carry legs under the body's heavy parts, or \
                 lower `min_leg_length` or `min_margin`, or raise `foot_radius`"
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
        let msg = LimbsError::InvalidLength { length: f32::NAN }.to_string();
        assert!(msg.starts_with("the body length is NaN"), "{msg}");
        assert!(!msg.contains("bone"), "{msg}");
        let msg = LimbsError::InvalidOption {
            name: "fin_size",
            value: 0.5,
        }
        .to_string();
        assert!(msg.contains("PlanOptions::fin_size"), "{msg}");
        let msg = LimbsError::NoStableLayout {
            margin: -0.5,
            required: 0.1,
        }
        .to_string();
        assert!(msg.contains("lower `min_leg_length`"), "{msg}");
    }

    #[test]
    fn error_trait_is_implemented_without_std() {
        fn takes_error(_: &dyn core::error::Error) {}
        takes_error(&LimbsError::NoBones);
    }
}
