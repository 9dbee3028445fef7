//! The crate's error type.

use core::fmt;

use glam::Vec3;

/// What went wrong when building, editing or inverting a [`Lattice`](crate::Lattice).
///
/// Every variant carries the offending value or index, and its `Display` message says what to
/// change in the input.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum FfdError {
    /// A float input (origin, axis, point, normal, scale, offset, gap, tolerance) was NaN or
    /// infinite.
    NonFinite {
        /// Which input, e.g. `"origin"`, `"axis"`, `"point"`, `"control point"`.
        what: &'static str,
        /// Position of the value in its list (axis number, point index), `None` for a single
        /// value.
        index: Option<usize>,
    },
    /// A lattice needs at least one division along every axis.
    ZeroDivisions {
        /// The axis (0 = S, 1 = T, 2 = U) with zero divisions.
        axis: usize,
    },
    /// Too many divisions along one axis: Bernstein polynomials of that degree lose all precision
    /// in `f32`.
    TooManyDivisions {
        /// The axis (0 = S, 1 = T, 2 = U).
        axis: usize,
        /// The requested divisions.
        divisions: usize,
        /// The largest supported value, [`MAX_DIVISIONS`](crate::MAX_DIVISIONS).
        max: usize,
    },
    /// The three axes span (almost) no volume: they are zero, parallel or coplanar.
    DegenerateAxes {
        /// `|S · (T × U)| / (|S| |T| |U|)`, in `[0, 1]`; 1 for orthogonal axes.
        volume_ratio: f32,
    },
    /// A control point index lies outside the lattice.
    IndexOutOfRange {
        /// The index that was asked for.
        index: [usize; 3],
        /// The lattice's divisions; valid indices run from 0 to these, inclusive.
        divisions: [usize; 3],
    },
    /// A slice index lies outside the lattice.
    SliceOutOfRange {
        /// The axis the slices are taken along (0 = S, 1 = T, 2 = U).
        axis: usize,
        /// The slice that was asked for.
        slice: usize,
        /// How many slices there are along that axis (divisions + 1).
        count: usize,
    },
    /// [`Lattice::around`](crate::Lattice::around) needs at least one point.
    NoPoints,
    /// A scale factor or gap that must be greater than zero was not.
    NotPositive {
        /// Which input: `"scale"` (the index is the axis) or `"gap"` (the index is the gap's).
        what: &'static str,
        /// Position of the value in its list, 0 for single values.
        index: usize,
        /// The value given.
        value: f32,
    },
    /// [`Lattice::around`](crate::Lattice::around) was given a negative or non-finite padding.
    InvalidPadding {
        /// The padding given.
        value: f32,
    },
    /// [`Lattice::around`](crate::Lattice::around)'s points, with their padding, span more than
    /// `f32` can represent.
    TooLarge,
    /// A list had the wrong length.
    WrongLength {
        /// Which list, e.g. `"gaps"`.
        what: &'static str,
        /// The length it must have.
        expected: usize,
        /// The length it had.
        found: usize,
    },
    /// The deformation's Jacobian is singular (or nearly) at a point: the lattice is folded or
    /// crushed there, so normals and inversion are undefined.
    SingularJacobian {
        /// Local `(s, t, u)` coordinates of the point.
        local: Vec3,
        /// The Jacobian's determinant there.
        determinant: f32,
    },
    /// [`Lattice::inverse`](crate::Lattice::inverse) did not reach the tolerance.
    NoConvergence {
        /// The deformed point whose preimage was sought.
        target: Vec3,
        /// Distance between the deformed best guess and the target when it gave up.
        residual: f32,
        /// Newton iterations spent.
        iterations: u32,
    },
    /// A lattice corner or control point had a coordinate beyond
    /// ±[`MAX_COORDINATE`](crate::MAX_COORDINATE) (or one that overflowed `f32` when a slice was
    /// moved or a lattice's corners were added up).
    CoordinateTooLarge {
        /// Which input: `"lattice corner"` (the index is the corner's, bit `a` set for the far
        /// end of axis `a`) or `"control point"` (the index is its storage index).
        what: &'static str,
        /// Position of the point in its list.
        index: usize,
        /// The offending coordinate.
        value: f32,
    },
    /// A deformed point overflowed `f32` (a point far outside the lattice, extrapolated), or,
    /// from [`Lattice::deform_normal`](crate::Lattice::deform_normal), the Jacobian did.
    NonFiniteResult {
        /// Index of the input point (0 for a single point).
        index: usize,
    },
}

impl fmt::Display for FfdError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NonFinite {
                what,
                index: Some(index),
            } => write!(f, "{what} {index} is NaN or infinite: pass finite values"),
            Self::NonFinite { what, index: None } => {
                write!(f, "{what} is NaN or infinite: pass finite values")
            }
            Self::ZeroDivisions { axis } => write!(
                f,
                "axis {axis} has zero divisions: every axis needs at least 1 division"
            ),
            Self::TooManyDivisions {
                axis,
                divisions,
                max,
            } => write!(
                f,
                "axis {axis} has {divisions} divisions: use at most {max} (Bernstein bases of \
                 higher degree lose precision in f32)"
            ),
            Self::DegenerateAxes { volume_ratio } => write!(
                f,
                "the lattice axes are zero, parallel or coplanar (volume ratio {volume_ratio:e}): \
                 give three independent edge vectors, or pad a flat point set"
            ),
            Self::IndexOutOfRange { index, divisions } => write!(
                f,
                "control point {index:?} is outside the lattice: indices run from [0, 0, 0] to \
                 {divisions:?}"
            ),
            Self::SliceOutOfRange { axis, slice, count } => write!(
                f,
                "slice {slice} along axis {axis} does not exist: the lattice has {count} slices \
                 there (0 to {})",
                count.saturating_sub(1)
            ),
            Self::NoPoints => write!(f, "no points were given: pass at least one point"),
            Self::NotPositive { what, index, value } => {
                write!(f, "{what} {index} is {value}: it must be greater than zero")
            }
            Self::InvalidPadding { value } => {
                write!(
                    f,
                    "padding is {value}: pass a finite padding of zero or more"
                )
            }
            Self::TooLarge => write!(
                f,
                "the points and padding span more than f32 can represent: scale or recentre them"
            ),
            Self::WrongLength {
                what,
                expected,
                found,
            } => write!(f, "{what} has {found} entries: pass exactly {expected}"),
            Self::SingularJacobian { local, determinant } => write!(
                f,
                "the deformation is folded or crushed at local coordinates {local} (Jacobian \
                 determinant {determinant:e}): move the control points so slices do not cross"
            ),
            Self::NoConvergence {
                target,
                residual,
                iterations,
            } => write!(
                f,
                "no undeformed point maps to {target} within tolerance after {iterations} \
                 iterations (residual {residual:e}): the point may be outside the deformed \
                 lattice or the lattice folds; raise max_iterations or loosen the tolerance"
            ),
            Self::CoordinateTooLarge { what, index, value } => write!(
                f,
                "{what} {index} has coordinate {value:e}: keep lattices and control points \
                 within ±{:e} (scale the model down or move it nearer the origin)",
                crate::MAX_COORDINATE
            ),
            Self::NonFiniteResult { index } => write!(
                f,
                "point {index} deformed to a non-finite position: it lies too far outside the \
                 lattice to extrapolate; enlarge the lattice or use OutsidePolicy::Unchanged"
            ),
        }
    }
}

impl core::error::Error for FfdError {}

#[cfg(test)]
mod tests {
    use alloc::string::ToString;

    use super::*;

    #[test]
    fn messages_say_what_to_fix() {
        let msg = FfdError::ZeroDivisions { axis: 2 }.to_string();
        assert!(msg.contains("at least 1"), "{msg}");
        let msg = FfdError::InvalidPadding { value: -1.0 }.to_string();
        assert!(msg.contains("zero or more"), "{msg}");
        let msg = FfdError::NonFinite {
            what: "origin",
            index: None,
        }
        .to_string();
        assert_eq!(msg, "origin is NaN or infinite: pass finite values");
        let msg = FfdError::NonFinite {
            what: "point",
            index: Some(3),
        }
        .to_string();
        assert_eq!(msg, "point 3 is NaN or infinite: pass finite values");
        let msg = FfdError::SliceOutOfRange {
            axis: 2,
            slice: 11,
            count: 11,
        }
        .to_string();
        assert!(msg.contains("0 to 10"), "{msg}");
        let msg = FfdError::CoordinateTooLarge {
            what: "control point",
            index: 4,
            value: -3e38,
        }
        .to_string();
        assert!(msg.contains("within ±1e15"), "{msg}");
    }

    #[test]
    fn error_trait_is_implemented_without_std() {
        fn takes_error(_: &dyn core::error::Error) {}
        takes_error(&FfdError::NoPoints);
    }
}
