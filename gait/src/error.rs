//! The crate's error type.

use core::fmt;

/// What went wrong when building a [`Controller`](crate::Controller), a ground, or updating.
///
/// Every variant carries the offending value or index, and its `Display` message says what to
/// change in the input. The controller's state is left untouched when an update fails.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum GaitError {
    /// A float input was NaN or infinite.
    NonFinite {
        /// Which input, e.g. `"dt"`, `"pose"`, `"velocity"`, `"leg hip"`, `"height"`.
        what: &'static str,
        /// Position of the value in its list (leg, chain or sample index), 0 for single values.
        index: usize,
    },
    /// The time step was negative.
    NegativeTimeStep {
        /// The time step given, in seconds.
        dt: f32,
    },
    /// A value that must be greater than zero was not (segment lengths, sizes, cell size, …).
    NotPositive {
        /// Which input, e.g. `"upper segment"`, `"leg size"`, `"cell size"`.
        what: &'static str,
        /// Position of the value in its list, 0 for single values.
        index: usize,
        /// The value given.
        value: f32,
    },
    /// A value lies outside its allowed range.
    OutOfRange {
        /// Which input, e.g. `"blend weight"`, `"overshoot"`.
        what: &'static str,
        /// The value given.
        value: f32,
        /// The smallest allowed value.
        min: f32,
        /// The largest allowed value.
        max: f32,
    },
    /// A direction that must be non-zero was zero (or too short to normalise).
    ZeroVector {
        /// Which input, e.g. `"leg pole"`, `"plane normal"`, `"pose rotation"`.
        what: &'static str,
        /// Position of the value in its list, 0 for single values.
        index: usize,
    },
    /// A controller needs at least one leg.
    NoLegs,
    /// Some legs have a group and this one has none: set every leg's group, or none.
    MixedGroups {
        /// The first leg without a group.
        leg: usize,
    },
    /// A height field needs at least 2 × 2 samples.
    GridTooSmall {
        /// Samples along X.
        columns: usize,
        /// Samples along Z.
        rows: usize,
    },
    /// A list had the wrong length.
    WrongLength {
        /// Which list, e.g. `"heights"`.
        what: &'static str,
        /// The length it must have.
        expected: usize,
        /// The length it had.
        found: usize,
    },
    /// An index (leg, chain) does not exist.
    IndexOutOfRange {
        /// Which kind of index, e.g. `"leg"`, `"chain"`.
        what: &'static str,
        /// The index that was asked for.
        index: usize,
        /// How many there are.
        len: usize,
    },
}

impl fmt::Display for GaitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NonFinite { what, index } => {
                write!(f, "{what} {index} is NaN or infinite: pass finite values")
            }
            Self::NegativeTimeStep { dt } => write!(
                f,
                "time step {dt} is negative: pass the elapsed time since the last update (0 or \
                 more seconds)"
            ),
            Self::NotPositive { what, index, value } => {
                write!(f, "{what} {index} is {value}: it must be greater than zero")
            }
            Self::OutOfRange {
                what,
                value,
                min,
                max,
            } => write!(f, "{what} is {value}: pass a value from {min} to {max}"),
            Self::ZeroVector { what, index } => write!(
                f,
                "{what} {index} is zero or too short to give a direction: pass a non-zero vector"
            ),
            Self::NoLegs => write!(
                f,
                "no legs were given: a controller needs at least one leg (use `Controller::chains_only` for a legless body)"
            ),
            Self::MixedGroups { leg } => write!(
                f,
                "leg {leg} has no group while other legs have one: set every leg's group, or \
                 none to derive the groups from the layout"
            ),
            Self::GridTooSmall { columns, rows } => write!(
                f,
                "a height field of {columns} x {rows} samples is too small: use at least 2 x 2"
            ),
            Self::WrongLength {
                what,
                expected,
                found,
            } => write!(f, "{what} has {found} entries: pass exactly {expected}"),
            Self::IndexOutOfRange { what, index, len } => write!(
                f,
                "{what} {index} does not exist: there are {len} (indices 0 to {})",
                len.saturating_sub(1)
            ),
        }
    }
}

impl core::error::Error for GaitError {}

/// Checks that a float is finite.
pub(crate) fn finite(value: f32, what: &'static str, index: usize) -> Result<(), GaitError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(GaitError::NonFinite { what, index })
    }
}

/// Checks that a vector is finite.
pub(crate) fn finite3(
    value: glam::Vec3,
    what: &'static str,
    index: usize,
) -> Result<(), GaitError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(GaitError::NonFinite { what, index })
    }
}

/// Checks that a float is finite and greater than zero.
pub(crate) fn positive(value: f32, what: &'static str, index: usize) -> Result<(), GaitError> {
    finite(value, what, index)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(GaitError::NotPositive { what, index, value })
    }
}

/// Checks that a float is finite and in `[min, max]`.
pub(crate) fn in_range(
    value: f32,
    what: &'static str,
    min: f32,
    max: f32,
) -> Result<(), GaitError> {
    if value.is_finite() && value >= min && value <= max {
        Ok(())
    } else {
        Err(GaitError::OutOfRange {
            what,
            value,
            min,
            max,
        })
    }
}

#[cfg(test)]
mod tests {
    use alloc::string::ToString;

    use super::*;

    #[test]
    fn messages_say_what_to_fix() {
        let msg = GaitError::NegativeTimeStep { dt: -1.0 }.to_string();
        assert!(msg.contains("0 or more"), "{msg}");
        let msg = GaitError::GridTooSmall {
            columns: 1,
            rows: 5,
        }
        .to_string();
        assert!(msg.contains("at least 2 x 2"), "{msg}");
        let msg = GaitError::IndexOutOfRange {
            what: "leg",
            index: 4,
            len: 4,
        }
        .to_string();
        assert!(msg.contains("0 to 3"), "{msg}");
        let msg = GaitError::MixedGroups { leg: 2 }.to_string();
        assert!(msg.contains("every leg"), "{msg}");
    }

    #[test]
    fn error_trait_is_implemented_without_std() {
        fn takes_error(_: &dyn core::error::Error) {}
        takes_error(&GaitError::NoLegs);
    }

    #[test]
    fn validators_reject_nan() {
        assert!(finite(f32::NAN, "x", 0).is_err());
        assert!(positive(f32::NAN, "x", 0).is_err());
        assert!(positive(0.0, "x", 0).is_err());
        assert!(in_range(f32::NAN, "x", 0.0, 1.0).is_err());
        assert!(in_range(0.5, "x", 0.0, 1.0).is_ok());
    }
}
