//! The crate's error type.

use core::fmt;

/// What went wrong when building a field, covering a bone, blending attributes or asking a
/// falloff for a radius.
///
/// Every variant carries the offending value or index, and its `Display` message says what to
/// change in the input.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum MetaballError {
    /// A float input (ball centre, radius, segment end, thickness, option) was NaN or infinite.
    NonFinite {
        /// Which input, e.g. `"ball center"`, `"ball radius"`, `"segment start"`.
        what: &'static str,
        /// Position of the value in its list (ball index), 0 for single values.
        index: usize,
    },
    /// A value that must be greater than zero was not.
    NotPositive {
        /// Which input, e.g. `"ball radius"`, `"thickness"`, `"cell size"`.
        what: &'static str,
        /// Position of the value in its list (ball index), 0 for single values.
        index: usize,
        /// The value given.
        value: f32,
    },
    /// A finite value lies outside the range this crate supports for it.
    OutOfRange {
        /// Which input, e.g. `"multiplier"`, `"ball radius"`, `"blobbiness"`, `"epsilon"`.
        what: &'static str,
        /// Position of the value in its list (ball index), 0 for single values.
        index: usize,
        /// The value given.
        value: f32,
        /// Smallest accepted value.
        min: f32,
        /// Largest accepted value.
        max: f32,
    },
    /// A field needs at least one ball.
    NoBalls,
    /// A list had the wrong length.
    WrongLength {
        /// Which list: `"attributes"` (one per ball) or `"block samples"` (columns × rows,
        /// [`Field2::sample_block`](crate::Field2::sample_block)).
        what: &'static str,
        /// The length it must have.
        expected: usize,
        /// The length it had.
        found: usize,
    },
    /// Covering a bone would need more balls than [`MAX_COVER_BALLS`](crate::MAX_COVER_BALLS).
    TooManyCoverBalls {
        /// How many balls the bone would need (`f32`: it may exceed every integer type).
        needed: f32,
        /// The largest number of balls one covering may produce.
        max: usize,
    },
    /// A field was given more balls than it can index ([`MAX_FIELD_BALLS`](crate::MAX_FIELD_BALLS)).
    TooManyFieldBalls {
        /// How many balls were given.
        count: usize,
        /// The largest number of balls one field may hold.
        max: usize,
    },
    /// Blending finite attributes gave a non-finite result: their magnitudes are within
    /// rounding of `f32::MAX`, or the attribute type's own arithmetic overflowed.
    BlendOverflow {
        /// How many attributes (the balls reaching the point) were blended.
        blended: usize,
    },
}

impl fmt::Display for MetaballError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NonFinite { what, index } => {
                write!(f, "{what} {index} is NaN or infinite: pass finite values")
            }
            Self::NotPositive { what, index, value } => {
                write!(f, "{what} {index} is {value}: it must be greater than zero")
            }
            Self::OutOfRange {
                what,
                index,
                value,
                min,
                max,
            } => write!(
                f,
                "{what} {index} is {value:e}: pass a value from {min:e} to {max:e}"
            ),
            Self::NoBalls => write!(f, "no balls were given: pass at least one ball"),
            Self::WrongLength {
                what,
                expected,
                found,
            } if what.starts_with("block") => write!(
                f,
                "{what} has {found} entries: pass exactly {expected} (columns × rows)"
            ),
            Self::WrongLength {
                what,
                expected,
                found,
            } => write!(
                f,
                "{what} has {found} entries: pass exactly {expected} (one per ball)"
            ),
            Self::TooManyCoverBalls { needed, max } => write!(
                f,
                "covering the bone needs {needed:e} balls, more than the limit of {max}: use a \
                 shorter bone, a larger thickness or a smaller multiplier"
            ),
            Self::TooManyFieldBalls { count, max } => write!(
                f,
                "the field was given {count} balls, more than the limit of {max}: split the balls \
                 over several fields"
            ),
            Self::BlendOverflow { blended } => write!(
                f,
                "blending {blended} finite attributes overflowed to a non-finite value: scale the \
                 attributes down, away from f32::MAX"
            ),
        }
    }
}

impl core::error::Error for MetaballError {}

#[cfg(test)]
mod tests {
    use alloc::string::ToString;

    use super::*;

    #[test]
    fn messages_say_what_to_fix() {
        let msg = MetaballError::NotPositive {
            what: "ball radius",
            index: 3,
            value: -1.0,
        }
        .to_string();
        assert!(msg.contains("ball radius 3"), "{msg}");
        assert!(msg.contains("greater than zero"), "{msg}");
        let msg = MetaballError::OutOfRange {
            what: "multiplier",
            index: 0,
            value: 2.0,
            min: 1.0,
            max: 1.6,
        }
        .to_string();
        assert!(msg.contains("from 1e0 to 1.6e0"), "{msg}");
        let msg = MetaballError::WrongLength {
            what: "attributes",
            expected: 4,
            found: 3,
        }
        .to_string();
        assert!(msg.contains("exactly 4"), "{msg}");
        assert!(MetaballError::NoBalls.to_string().contains("at least one"));
        let msg = MetaballError::BlendOverflow { blended: 3 }.to_string();
        assert!(
            msg.contains("3 finite attributes") && msg.contains("scale"),
            "{msg}"
        );
    }

    /// Regression: one `TooManyBalls` variant served both a too-long bone and a too-large field,
    /// and told a caller with five billion balls to "use a shorter bone".
    #[test]
    fn too_many_balls_messages_fit_where_they_arise() {
        let cover = MetaballError::TooManyCoverBalls {
            needed: 1e9,
            max: 1 << 16,
        }
        .to_string();
        assert!(cover.contains("covering the bone") && cover.contains("shorter bone"));
        let field = MetaballError::TooManyFieldBalls {
            count: 5_000_000_000,
            max: u32::MAX as usize,
        }
        .to_string();
        assert!(field.contains("5000000000 balls"), "{field}");
        assert!(field.contains("several fields"), "{field}");
        assert!(
            !field.contains("bone") && !field.contains("thickness"),
            "{field}"
        );
    }

    #[test]
    fn error_trait_is_implemented_without_std() {
        fn takes_error(_: &dyn core::error::Error) {}
        takes_error(&MetaballError::NoBalls);
    }
}
