//! The crate's error type.

use core::fmt;

use glam::Vec2;

/// What went wrong when marching a grid, tracing a field or meshing rings.
///
/// Every variant carries the offending value or index, and its `Display` message says what to
/// change in the input.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum MarchError {
    /// A float input (iso-level, step, hint, ring point, option) was NaN or infinite.
    NonFinite {
        /// Which input, e.g. `"iso"`, `"step"`, `"hint"`, `"ring point"`.
        what: &'static str,
        /// Position of the value in its list (hint index, ring index), 0 for single values.
        index: usize,
    },
    /// A value that must be positive (or, where documented, non-negative) was not.
    NotPositive {
        /// Which input, e.g. `"step"`, `"interior spacing"`.
        what: &'static str,
        /// The value given.
        value: f32,
    },
    /// An option lies outside its documented range.
    OutOfRange {
        /// Which option, e.g. `"weld"`, `"min angle"`.
        what: &'static str,
        /// The value given.
        value: f32,
        /// Smallest accepted value.
        min: f32,
        /// Largest accepted value.
        max: f32,
    },
    /// The sample slice does not hold `width × height` values.
    GridSize {
        /// Columns given.
        width: usize,
        /// Rows given.
        height: usize,
        /// Length of the sample slice.
        len: usize,
    },
    /// The grid is too large to index with 32-bit edge numbers.
    GridTooLarge {
        /// Columns given.
        width: usize,
        /// Rows given.
        height: usize,
    },
    /// A hint lies so far from the origin (in steps) that grid coordinates lose precision.
    TooFar {
        /// Index of the hint.
        index: usize,
        /// Its distance from the origin in steps along the larger axis.
        steps: f32,
        /// The largest supported distance, [`MAX_GRID_COORDINATE`](crate::MAX_GRID_COORDINATE).
        max: f32,
    },
    /// A trace or a walk to the outline did not finish within the cell budget
    /// ([`MarchOptions::max_cells`](crate::MarchOptions::max_cells)): the field is unbounded
    /// above the hint, or the outline is longer than the budget allows.
    BudgetExceeded {
        /// Index of the hint whose trace ran out, or `usize::MAX` for the hole scan.
        hint: usize,
        /// Cells visited when it stopped.
        cells: usize,
    },
    /// The interior lattice would hold more points than
    /// [`MAX_INTERIOR_POINTS`](crate::MAX_INTERIOR_POINTS): the
    /// [`interior_spacing`](crate::MeshOptions::interior_spacing) is too small for the rings'
    /// extent.
    InteriorTooDense {
        /// About how many points the lattice would hold.
        points: f32,
        /// The most it may hold.
        max: usize,
    },
    /// The rings' bounding box is wider or taller than
    /// [`MAX_INTERIOR_EXTENT`](crate::MAX_INTERIOR_EXTENT) (about 4.6e18), too large for an
    /// interior lattice ([`interior_spacing`](crate::MeshOptions::interior_spacing) above 0).
    ExtentTooLarge {
        /// The box's larger side (infinite when it overflows `f32`).
        extent: f32,
        /// The largest accepted.
        max: f32,
    },
    /// A ring has fewer than three points.
    TooFewPoints {
        /// Index of the ring.
        ring: usize,
        /// Its number of points.
        len: usize,
    },
    /// A hole's `parent` is missing, out of range, or names another hole; or an outer ring
    /// names a parent.
    BadParent {
        /// Index of the ring.
        ring: usize,
        /// Its `parent` field.
        parent: Option<usize>,
    },
    /// Two ring edges cross, touch or overlap (the same ring when `ring_a == ring_b`: it
    /// intersects itself), or an edge has zero length.
    RingsCross {
        /// Ring of the first edge.
        ring_a: usize,
        /// Ring of the second edge.
        ring_b: usize,
        /// A point near the intersection.
        near: Vec2,
    },
}

impl fmt::Display for MarchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NonFinite { what, index } => {
                write!(f, "{what} {index} is NaN or infinite: pass finite values")
            }
            Self::NotPositive { what, value } => {
                write!(f, "{what} is {value}: it must be greater than zero")
            }
            Self::OutOfRange {
                what,
                value,
                min,
                max,
            } => write!(f, "{what} is {value}: pass a value from {min} to {max}"),
            Self::GridSize { width, height, len } => write!(
                f,
                "a {width}×{height} grid needs {} samples but {len} were given: pass exactly \
                 width × height values, row by row",
                width.saturating_mul(height)
            ),
            Self::GridTooLarge { width, height } => write!(
                f,
                "a {width}×{height} grid is too large to march: split it into tiles of at most \
                 2^30 samples"
            ),
            Self::TooFar { index, steps, max } => write!(
                f,
                "hint {index} lies {steps} steps from the origin: keep hints within {max} steps, \
                 or use a larger step"
            ),
            Self::InteriorTooDense { points, max } => write!(
                f,
                "the interior lattice would hold about {points} points, more than {max}: raise \
                 interior_spacing (or set it to 0 for no interior points)"
            ),
            Self::ExtentTooLarge { extent, max } => write!(
                f,
                "the rings' bounding box is {extent} across, more than {max} for interior \
                 points: scale the rings down, or set interior_spacing to 0 for no interior \
                 points"
            ),
            Self::BudgetExceeded { hint, cells } => {
                if hint == usize::MAX {
                    write!(
                        f,
                        "the hole scan stopped after {cells} cells: raise max_cells or use a \
                         larger step"
                    )
                } else {
                    write!(
                        f,
                        "the trace from hint {hint} did not close within {cells} cells: the \
                         field may be inside all the way up from the hint; bound the field, \
                         raise max_cells or use a larger step"
                    )
                }
            }
            Self::TooFewPoints { ring, len } => write!(
                f,
                "ring {ring} has {len} points: a ring needs at least 3 distinct points"
            ),
            Self::BadParent { ring, parent } => match parent {
                Some(p) => write!(
                    f,
                    "ring {ring} names parent {p}, which is out of range, a hole, or given to \
                     an outer ring: a hole's parent must be the index of an outer ring, and \
                     outer rings have none"
                ),
                None => write!(
                    f,
                    "hole {ring} has no parent: set it to the index of its outer ring"
                ),
            },
            Self::RingsCross {
                ring_a,
                ring_b,
                near,
            } => {
                if ring_a == ring_b {
                    write!(
                        f,
                        "ring {ring_a} intersects itself or has a zero-length edge near \
                         {near}: pass simple rings"
                    )
                } else {
                    write!(
                        f,
                        "rings {ring_a} and {ring_b} cross or touch near {near}: rings must \
                         not intersect"
                    )
                }
            }
        }
    }
}

impl core::error::Error for MarchError {}

#[cfg(test)]
mod tests {
    use alloc::string::ToString;

    use super::*;

    #[test]
    fn messages_say_what_to_fix() {
        let msg = MarchError::GridSize {
            width: 3,
            height: 4,
            len: 5,
        }
        .to_string();
        assert!(msg.contains("12 samples"), "{msg}");
        let msg = MarchError::BadParent {
            ring: 2,
            parent: None,
        }
        .to_string();
        assert!(msg.contains("set it"), "{msg}");
        let msg = MarchError::RingsCross {
            ring_a: 1,
            ring_b: 1,
            near: Vec2::ZERO,
        }
        .to_string();
        assert!(msg.contains("itself"), "{msg}");
        let msg = MarchError::ExtentTooLarge {
            extent: f32::INFINITY,
            max: 4.611_686e18,
        }
        .to_string();
        assert!(msg.contains("interior_spacing to 0"), "{msg}");
    }

    #[test]
    fn error_trait_is_implemented_without_std() {
        fn takes_error(_: &dyn core::error::Error) {}
        takes_error(&MarchError::NotPositive {
            what: "step",
            value: 0.0,
        });
    }
}
