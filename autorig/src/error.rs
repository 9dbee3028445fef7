//! The crate's error type.

use core::fmt;

/// What went wrong when rigging a body mesh.
///
/// Every variant carries the offending value or index, and its `Display` message says what to
/// change in the input.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum AutorigError {
    /// No vertices were given (or no triangle uses any).
    NoVertices,
    /// A vertex position was NaN or infinite.
    NonFinite {
        /// The vertex.
        index: usize,
    },
    /// A vertex coordinate was finite but beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    CoordinateTooLarge {
        /// The vertex.
        index: usize,
        /// The offending coordinate.
        value: f32,
    },
    /// A triangle names a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The vertex index it names.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
    /// Every vertex is at the same position: there is no body to rig.
    AllCoincident,
    /// Every vertex lies on one line: the body has no cross-section, so no sides or top.
    Collinear,
    /// Every vertex has the same Z (within rounding): the body has no front-to-back extent, so
    /// no head–tail axis. Bodies must run along Z, head towards +Z.
    NoLengthAlongZ,
    /// A float option was not finite and positive.
    InvalidOption {
        /// The option, e.g. `"bone_length"` or `"centre_tolerance"`.
        what: &'static str,
        /// The value given.
        value: f32,
    },
    /// The bone-count limits are unusable: `min_bones` must be at least 2 and at most
    /// `max_bones`, and `max_bones` at most [`RigOptions::MAX_BONES`](crate::RigOptions::MAX_BONES).
    InvalidBoneCount {
        /// The `min_bones` given.
        min: usize,
        /// The `max_bones` given.
        max: usize,
    },
}

impl fmt::Display for AutorigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NoVertices => write!(
                f,
                "the mesh has no vertices (or no triangle uses any): pass a body mesh"
            ),
            Self::NonFinite { index } => write!(
                f,
                "vertex {index} is NaN or infinite: pass finite coordinates"
            ),
            Self::CoordinateTooLarge { index, value } => write!(
                f,
                "vertex {index} has coordinate {value:e}: keep coordinates within ±{:e} (scale \
                 the mesh down)",
                crate::MAX_COORDINATE
            ),
            Self::IndexOutOfRange {
                triangle,
                index,
                vertices,
            } => write!(
                f,
                "triangle {triangle} uses vertex {index} but there are only {vertices} vertices: \
                 fix the index buffer"
            ),
            Self::AllCoincident => write!(
                f,
                "every vertex is at the same position: pass a body with some size"
            ),
            Self::Collinear => write!(
                f,
                "every vertex lies on one line: pass a body with a cross-section (width and \
                 height)"
            ),
            Self::NoLengthAlongZ => write!(
                f,
                "every vertex has the same z: the body must run along Z, head towards +Z; rotate \
                 it into that frame"
            ),
            Self::InvalidOption { what, value } => write!(
                f,
                "option {what} is {value}: pass a finite value greater than zero"
            ),
            Self::InvalidBoneCount { min, max } => write!(
                f,
                "bone counts from {min} to {max} are unusable: need 2 <= min_bones <= max_bones \
                 <= {}",
                crate::RigOptions::MAX_BONES
            ),
        }
    }
}

impl core::error::Error for AutorigError {}

#[cfg(test)]
mod tests {
    use alloc::string::ToString;

    use super::*;

    #[test]
    fn messages_say_what_to_fix() {
        let msg = AutorigError::IndexOutOfRange {
            triangle: 3,
            index: 99,
            vertices: 10,
        }
        .to_string();
        assert!(
            msg.contains("triangle 3") && msg.contains("only 10"),
            "{msg}"
        );
        let msg = AutorigError::InvalidBoneCount { min: 5, max: 2 }.to_string();
        assert!(msg.contains("2 <= min_bones"), "{msg}");
        let msg = AutorigError::NoLengthAlongZ.to_string();
        assert!(msg.contains("along Z"), "{msg}");
    }

    #[test]
    fn error_trait_is_implemented_without_std() {
        fn takes_error(_: &dyn core::error::Error) {}
        takes_error(&AutorigError::NoVertices);
    }
}
