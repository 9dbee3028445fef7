//! Options shared by [`march_grid_with`](crate::march_grid_with) and
//! [`trace_with`](crate::trace_with).

use crate::MarchError;

/// How an ambiguous (saddle) cell is settled: two diagonal corners inside, the other two
/// outside. Either the two inside corners are joined by one band of inside, or they are cut
/// off as two separate corners.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub enum Saddle {
    /// Join the inside corners when the cell centre is inside: for [`trace`](crate::trace)
    /// the field is sampled at the centre (the seed's rule, one extra sample per saddle); for
    /// [`march_grid`](crate::march_grid) the centre value is the mean of the four corners.
    #[default]
    Centre,
    /// The asymptotic decider: join the inside corners when the bilinear interpolant's value at
    /// its saddle point, `(a·c − b·d) / (a + c − b − d)` for corners `a, c` inside and `b, d`
    /// outside, is at least the iso-level. Needs no extra sample, and is the choice for which
    /// the grid and the trace agree exactly on the same samples.
    Asymptotic,
}

/// Options for [`march_grid_with`](crate::march_grid_with) and
/// [`trace_with`](crate::trace_with).
///
/// ```
/// use creature_march::{MarchOptions, Saddle};
///
/// let options = MarchOptions::DEFAULT
///     .with_saddle(Saddle::Asymptotic)
///     .with_refine_steps(3);
/// assert_eq!(options.weld, 0.01);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct MarchOptions {
    /// How saddle cells are settled. Default [`Saddle::Centre`].
    pub saddle: Saddle,
    /// Consecutive ring points closer than `weld × step` are merged (the grid's step is one
    /// cell), removing the near-duplicates a contour makes where it passes near a grid node.
    /// From 0 (merge exact duplicates only) to 0.5. Default 0.01.
    pub weld: f32,
    /// Trace only: refine every crossing with this many Illinois (false-position) steps on the
    /// field along its cell edge, so the outline sits on the iso-line rather than on the linear
    /// interpolant. A refined crossing may sit exactly on a grid node on the iso-line, except
    /// where the ring reaches that node twice apart or another ring reaches it too: those
    /// crossings stay `1e-3` of a cell off the node along their edges, as linear ones always
    /// do, so no ring touches itself or another.
    /// Each step costs one field sample per ring point. From 0 (off) to 32. Default 0.
    pub refine_steps: u32,
    /// Trace only: the largest number of cells (walk steps, traced cells and scanned nodes
    /// together) one call may visit before it returns
    /// [`MarchError::BudgetExceeded`]. At most 2²⁸. Default 4,194,304 (2²²).
    pub max_cells: usize,
    /// Trace only: after tracing a component's outer ring, scan the grid nodes it encloses for
    /// holes (and islands inside holes), so holes are found even when no walk from a hint
    /// crosses them. Costs one sample per enclosed node. Default `true`.
    pub holes: bool,
}

/// The largest [`MarchOptions::max_cells`].
pub const MAX_CELLS: usize = 1 << 28;

/// The largest distance of a hint from the origin, in steps along either axis: beyond it grid
/// coordinates lose precision in `f32`.
pub const MAX_GRID_COORDINATE: f32 = 4_194_304.0;

impl MarchOptions {
    /// The defaults, usable in `const` context.
    pub const DEFAULT: Self = Self {
        saddle: Saddle::Centre,
        weld: 0.01,
        refine_steps: 0,
        max_cells: 1 << 22,
        holes: true,
    };

    /// Sets [`saddle`](Self::saddle).
    #[must_use]
    pub const fn with_saddle(mut self, saddle: Saddle) -> Self {
        self.saddle = saddle;
        self
    }

    /// Sets [`weld`](Self::weld).
    #[must_use]
    pub const fn with_weld(mut self, weld: f32) -> Self {
        self.weld = weld;
        self
    }

    /// Sets [`refine_steps`](Self::refine_steps).
    #[must_use]
    pub const fn with_refine_steps(mut self, refine_steps: u32) -> Self {
        self.refine_steps = refine_steps;
        self
    }

    /// Sets [`max_cells`](Self::max_cells).
    #[must_use]
    pub const fn with_max_cells(mut self, max_cells: usize) -> Self {
        self.max_cells = max_cells;
        self
    }

    /// Sets [`holes`](Self::holes).
    #[must_use]
    pub const fn with_holes(mut self, holes: bool) -> Self {
        self.holes = holes;
        self
    }

    /// Checks every field against its documented range.
    ///
    /// # Errors
    ///
    /// [`MarchError::OutOfRange`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), MarchError> {
        if !(self.weld >= 0.0 && self.weld <= 0.5) {
            return Err(MarchError::OutOfRange {
                what: "weld",
                value: self.weld,
                min: 0.0,
                max: 0.5,
            });
        }
        if self.refine_steps > 32 {
            return Err(MarchError::OutOfRange {
                what: "refine steps",
                value: self.refine_steps as f32,
                min: 0.0,
                max: 32.0,
            });
        }
        if self.max_cells > MAX_CELLS {
            return Err(MarchError::OutOfRange {
                what: "max cells",
                value: self.max_cells as f32,
                min: 0.0,
                max: MAX_CELLS as f32,
            });
        }
        Ok(())
    }
}

impl Default for MarchOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_valid_and_setters_set() {
        assert_eq!(MarchOptions::default(), MarchOptions::DEFAULT);
        assert!(MarchOptions::DEFAULT.validate().is_ok());
        let o = MarchOptions::DEFAULT
            .with_saddle(Saddle::Asymptotic)
            .with_weld(0.1)
            .with_refine_steps(4)
            .with_max_cells(10)
            .with_holes(false);
        assert_eq!(o.saddle, Saddle::Asymptotic);
        assert_eq!(o.weld, 0.1);
        assert_eq!(o.refine_steps, 4);
        assert_eq!(o.max_cells, 10);
        assert!(!o.holes);
    }

    #[test]
    fn out_of_range_options_are_rejected() {
        assert!(
            MarchOptions::DEFAULT
                .with_weld(f32::NAN)
                .validate()
                .is_err()
        );
        assert!(MarchOptions::DEFAULT.with_weld(0.6).validate().is_err());
        assert!(
            MarchOptions::DEFAULT
                .with_refine_steps(33)
                .validate()
                .is_err()
        );
        assert!(
            MarchOptions::DEFAULT
                .with_max_cells(MAX_CELLS + 1)
                .validate()
                .is_err()
        );
    }
}
