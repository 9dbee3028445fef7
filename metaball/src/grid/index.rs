//! The spatial index: building the grid of culling cells and finding the cell of a point.

use alloc::vec;
use alloc::vec::Vec;

use super::candidates::BIT_WORDS;
use super::{Core, Entry, separable};
use crate::falloff::Kernel;
use crate::math;

/// Relative padding of each ball's cutoff box, so rounding in the cell lookup can never drop a
/// ball the distance test would keep.
const BOX_PAD: f32 = 1e-4;

/// The grid box's padding relative to the magnitude of its coordinates: `2^-20`, at least 8 units
/// in the last place (an ulp of `x` is at most `|x| · 2^-23`). It covers the rounding of
/// `centre ± cutoff`, of the distance test, of the box's own corners and of the cell lookup
/// `(x − origin) / cell`, each a unit or less, where the extent-relative [`BOX_PAD`] vanishes.
const MAGNITUDE_PAD: f32 = 1.0 / 1_048_576.0;

impl<const D: usize> Core<D> {
    /// Builds the grid. Inputs are already validated: finite centres within range, radii in
    /// range, a valid kernel, `0 < epsilon < 1`, `cell_size` positive and finite if given,
    /// `balls` non-empty.
    pub(crate) fn build(
        balls: &[([f32; D], f32, u32)],
        kernel: Kernel,
        epsilon: f32,
        cell_size: Option<f32>,
    ) -> Self {
        let q_cut = kernel.cutoff_q(epsilon);
        let per_ball_value_error = kernel.value_error(epsilon);
        let gradient_scale = kernel.gradient_error_scale(epsilon);
        let mut value_error = 0.0f32;
        let mut gradient_error = 0.0f32;
        let mut compiled = Vec::with_capacity(balls.len());
        let mut ids = Vec::with_capacity(balls.len());
        let mut lo = [f32::INFINITY; D];
        let mut hi = [f32::NEG_INFINITY; D];
        let mut cutoffs: Vec<f32> = Vec::with_capacity(balls.len());
        debug_assert!(balls.len() <= crate::MAX_FIELD_BALLS);
        for (index, &(center, radius, id)) in balls.iter().enumerate() {
            let r2 = radius * radius;
            let inv_r2 = 1.0 / r2;
            let (cutoff, cutoff_d2) = match kernel {
                // Compact support: the kernel is exactly 0 from `q = 1` on, so culling must
                // keep every ball whose rounded `q = d² · (1/R²)` is below 1, or the culled
                // value misses a term `value_exact` sums while `error_bound` is 0
                // (regression: `d² = R²` can round to `q < 1`).
                Kernel::Wyvill { .. } => {
                    let d2 = first_d2_reaching(r2 * q_cut, inv_r2, q_cut);
                    (next_up(math::sqrt(d2)), d2)
                }
                _ => (radius * math::sqrt(q_cut), r2 * q_cut),
            };
            compiled.push(Entry {
                center,
                inv_r2,
                cutoff_d2,
                reach: pad(math::sqrt(cutoff_d2)),
                // The caller keeps to `MAX_FIELD_BALLS` (`u32::MAX`) balls.
                index: index as u32,
            });
            ids.push(id);
            value_error += per_ball_value_error;
            gradient_error += gradient_scale / radius;
            for k in 0..D {
                lo[k] = lo[k].min(center[k] - cutoff);
                hi[k] = hi[k].max(center[k] + cutoff);
            }
            if cutoff > 0.0 {
                cutoffs.push(cutoff);
            }
        }
        let mut core = Self {
            kernel,
            separable: separable(kernel, q_cut),
            balls: compiled,
            ids,
            origin: lo,
            cell: 1.0,
            inv_cell: 1.0,
            dims: [0; D],
            starts: vec![0],
            entries: Vec::new(),
            bits: Vec::new(),
            words: 0,
            bounds: (lo, hi),
            value_error,
            gradient_error,
            sample_error: 0.0,
            cutoff_exponent: 0.0,
        };
        if cutoffs.is_empty() {
            // No ball reaches epsilon anywhere: the culled field is zero everywhere.
            return core;
        }
        // The median: the same value a full sort puts in the middle.
        let middle = cutoffs.len() / 2;
        let (_, &mut median, _) = cutoffs.select_nth_unstable_by(middle, f32::total_cmp);
        let padded: Vec<f32> = core.balls.iter().map(|b| b.reach).collect();
        let mut extent = [0.0f32; D];
        let mut origin = lo;
        for k in 0..D {
            // Grow the box by the padding too, and by a few units in the last place of its
            // coordinates: far from the origin a tiny ball's cutoff box rounds to a point (or
            // to a box a few ulps wide), and a point its distance test keeps could otherwise
            // land on or past the grid's far edge and find no cell (regression: two balls of
            // radius 1e-5 near (−1e4, −1e4) read 0 at their centres with a `cell_size`).
            let magnitude = lo[k].abs().max(hi[k].abs());
            let margin = pad(hi[k] - lo[k]) - (hi[k] - lo[k])
                + magnitude * MAGNITUDE_PAD
                + f32::MIN_POSITIVE;
            origin[k] = lo[k] - margin;
            extent[k] = (hi[k] + margin) - origin[k];
        }
        let n = balls.len() as f64;
        let cell_budget = 16.0 * n + 1024.0;
        let entry_budget = 64.0 * n + 4096.0;
        let max_extent = extent.iter().fold(0.0f32, |m, &e| m.max(e));
        let mut cell = cell_size.unwrap_or(median).max(max_extent * 1e-6);
        let mut dims = [1usize; D];
        for _ in 0..256 {
            if cell >= max_extent {
                cell = max_extent.max(f32::MIN_POSITIVE);
                dims = [1; D];
                break;
            }
            let mut cells = 1.0f64;
            for &e in &extent {
                cells *= f64::from(math::ceil(e / cell)).max(1.0);
            }
            if cells <= cell_budget {
                let mut total = 0.0f64;
                for (ball, &r) in core.balls.iter().zip(&padded) {
                    if ball.cutoff_d2 > 0.0 {
                        let mut covered = 1.0f64;
                        for _ in 0..D {
                            covered *= f64::from(floor_nonnegative(2.0 * r / cell)) + 2.0;
                        }
                        total += covered;
                    }
                }
                if total <= entry_budget {
                    for k in 0..D {
                        // `cells <= cell_budget` bounds each factor, so the cast is exact.
                        dims[k] = (math::ceil(extent[k] / cell) as usize).max(1);
                    }
                    break;
                }
            }
            cell *= 2.0;
        }
        core.origin = origin;
        core.cell = cell;
        core.inv_cell = 1.0 / cell;
        core.dims = dims;
        core.fill(&padded);
        if let Some((_, sharpness)) = core.separable {
            let most = core
                .starts
                .windows(2)
                .map(|w| w[1] - w[0])
                .max()
                .unwrap_or(0);
            core.cutoff_exponent = sharpness * q_cut;
            core.sample_error = super::sample_error_bound(core.cutoff_exponent, most);
        }
        core
    }

    /// Counting sort of the balls into their cells, in ball order.
    fn fill(&mut self, padded: &[f32]) {
        let cells: usize = self.dims.iter().product();
        let mut counts = vec![0u32; cells + 1];
        let mut ranges = Vec::with_capacity(self.balls.len());
        for (ball, &r) in self.balls.iter().zip(padded) {
            if !(ball.cutoff_d2 > 0.0) {
                ranges.push(None);
                continue;
            }
            let mut from = [0usize; D];
            let mut to = [0usize; D];
            for k in 0..D {
                from[k] = self.clamp_axis(k, ball.center[k] - r);
                to[k] = self.clamp_axis(k, ball.center[k] + r);
            }
            for_each_run(from, to, self.dims, |run| {
                for count in &mut counts[run] {
                    *count += 1;
                }
            });
            ranges.push(Some((from, to)));
        }
        let mut starts = Vec::with_capacity(cells + 1);
        let mut running = 0u32;
        for &c in &counts[..cells] {
            starts.push(running);
            running += c;
        }
        starts.push(running);
        let mut cursor = starts.clone();
        let empty = Entry {
            center: [0.0; D],
            inv_r2: 0.0,
            cutoff_d2: 0.0,
            reach: 0.0,
            index: 0,
        };
        let mut entries = vec![empty; running as usize];
        let words = self.balls.len().div_ceil(64);
        let keep_bits = D == 2 && words <= BIT_WORDS;
        let mut bits = vec![0u64; if keep_bits { cells * words } else { 0 }];
        for (i, (ball, range)) in self.balls.iter().zip(&ranges).enumerate() {
            if let Some((from, to)) = *range {
                for_each_run(from, to, self.dims, |run| {
                    let (first, len) = (run.start, run.len());
                    for slot in &mut cursor[run] {
                        entries[*slot as usize] = *ball;
                        *slot += 1;
                    }
                    if keep_bits {
                        let (at, bit) = (first * words + i / 64, 1u64 << (i % 64));
                        let span = (len - 1) * words + 1;
                        let run = &mut bits[at..at + span];
                        for word in run.iter_mut().step_by(words) {
                            *word |= bit;
                        }
                    }
                });
            }
        }
        self.starts = starts;
        self.entries = entries;
        if keep_bits {
            self.bits = bits;
            self.words = words;
        }
    }

    /// The cell coordinate of `x` along axis `k`, clamped into the grid.
    pub(super) fn clamp_axis(&self, k: usize, x: f32) -> usize {
        // For t > 0 the truncating cast is `floor` (which is a library call on targets
        // without SSE4.1), saturating at `u32::MAX` (cheaper than `as usize`, and far beyond
        // any grid's size); t ≤ 0 and NaN give cell 0.
        let t = (x - self.origin[k]) * self.inv_cell;
        if !(t > 0.0) {
            0
        } else {
            (t as u32 as usize).min(self.dims[k].saturating_sub(1))
        }
    }

    /// The entries of the cell holding `p`, empty outside the grid (or for a NaN `p`).
    #[inline]
    pub(super) fn nearby(&self, p: &[f32; D]) -> &[Entry<D>] {
        let mut cell = 0usize;
        let mut stride = 1usize;
        for ((&x, &origin), &dim) in p.iter().zip(&self.origin).zip(&self.dims) {
            let t = (x - origin) * self.inv_cell;
            // The cell budget keeps `dim` far below 2^24, so `dim as f32` is exact; NaN fails.
            if !(t >= 0.0 && t < dim as f32) {
                return &[];
            }
            // `as u32` is exact here and cheaper than `as usize`.
            cell += (t as u32 as usize).min(dim - 1) * stride;
            stride *= dim;
        }
        self.cell_entries(cell)
    }

    /// The entries of cell `c` (flat index, `c < cell_count()`), in ball order.
    #[inline]
    pub(super) fn cell_entries(&self, c: usize) -> &[Entry<D>] {
        &self.entries[self.starts[c] as usize..self.starts[c + 1] as usize]
    }

    pub(crate) fn len(&self) -> usize {
        self.balls.len()
    }

    pub(crate) fn bounds(&self) -> ([f32; D], [f32; D]) {
        self.bounds
    }

    pub(crate) fn value_error(&self) -> f32 {
        self.value_error
    }

    pub(crate) fn gradient_error(&self) -> f32 {
        self.gradient_error
    }

    pub(crate) fn sample_error(&self) -> f32 {
        self.sample_error
    }

    pub(crate) fn cell_size(&self) -> f32 {
        self.cell
    }

    pub(crate) fn cell_count(&self) -> usize {
        self.starts.len() - 1
    }

    pub(crate) fn entry_count(&self) -> usize {
        self.entries.len()
    }
}

/// `floor(x)` for `x ≥ 0` (NaN and +∞ unchanged) without a library call: below 2²³ a truncating cast,
/// from there on `x` is already an integer.
fn floor_nonnegative(x: f32) -> f32 {
    if x < 8_388_608.0 {
        (x as u32) as f32
    } else {
        x
    }
}

/// The smallest squared distance `d2` (non-negative, starting the search at `guess`, which is
/// within a few units in the last place) whose rounded `d2 · inv_r2` is at least `q_cut`: a ball
/// is culled exactly where its kernel sees `q ≥ q_cut`. The product is monotonic in `d2`, so
/// stepping one `f32` at a time finds it; `inv_r2` and `guess` are normal for radii in
/// [`RADIUS_RANGE`](crate::RADIUS_RANGE), and the bounded loops only guard against the
/// impossible.
fn first_d2_reaching(guess: f32, inv_r2: f32, q_cut: f32) -> f32 {
    let mut d2 = guess;
    for _ in 0..64 {
        if d2 * inv_r2 >= q_cut {
            break;
        }
        d2 = next_up(d2);
    }
    for _ in 0..64 {
        let below = next_down(d2);
        if !(below >= 0.0 && below * inv_r2 >= q_cut) {
            break;
        }
        d2 = below;
    }
    d2
}

/// The next `f32` above a finite non-negative `x`.
fn next_up(x: f32) -> f32 {
    f32::from_bits(x.to_bits() + 1)
}

/// The next `f32` below a positive finite `x` (0 stays 0).
fn next_down(x: f32) -> f32 {
    if x > 0.0 {
        f32::from_bits(x.to_bits() - 1)
    } else {
        x
    }
}

fn pad(r: f32) -> f32 {
    r * (1.0 + BOX_PAD) + f32::MIN_POSITIVE
}

/// Calls `f` with the flat indices of each run of cells along axis 0 (contiguous) in the
/// inclusive box `from..=to`.
fn for_each_run<const D: usize>(
    from: [usize; D],
    to: [usize; D],
    dims: [usize; D],
    mut f: impl FnMut(core::ops::Range<usize>),
) {
    let len = to[0] + 1 - from[0];
    let mut outer_from = from;
    let mut outer_to = to;
    outer_to[0] = from[0];
    outer_from[0] = from[0];
    for_each_cell(outer_from, outer_to, dims, |c| f(c..c + len));
}

/// Calls `f` with the flat index of every cell in the inclusive box `from..=to`.
fn for_each_cell<const D: usize>(
    from: [usize; D],
    to: [usize; D],
    dims: [usize; D],
    mut f: impl FnMut(usize),
) {
    let mut at = from;
    loop {
        let mut flat = 0usize;
        let mut stride = 1usize;
        for k in 0..D {
            flat += at[k] * stride;
            stride *= dims[k];
        }
        f(flat);
        // Odometer increment, axis 0 fastest.
        let mut k = 0;
        loop {
            if k == D {
                return;
            }
            if at[k] < to[k] {
                at[k] += 1;
                break;
            }
            at[k] = from[k];
            k += 1;
        }
    }
}

#[cfg(test)]
mod tests {

    use super::super::test_support::*;
    use super::*;
    use crate::Falloff;

    #[test]
    fn grid_stays_within_its_budgets_for_a_wild_spread() {
        // Tiny balls a trillion units apart, and a tiny explicit cell size.
        let balls = [
            ([-1e11, 0.0], 1e-3, 0),
            ([1e11, 5.0], 1e-3, 1),
            ([0.0, 0.0], 1e6, 2),
        ];
        for cell in [None, Some(1e-6)] {
            let core = Core::<2>::build(&balls, Falloff::SEED.kernel(), 1e-4, cell);
            assert!(core.cell_count() as f64 <= 16.0 * 3.0 + 1024.0);
            assert!(core.entry_count() as f64 <= 64.0 * 3.0 + 4096.0);
            assert!(core.value([0.0, 0.0]) > 1.0);
            assert!(core.value([1e11, 5.0]) > 1.0);
        }
    }

    #[test]
    fn balls_weaker_than_epsilon_leave_an_empty_grid() {
        let weak = Falloff::Blinn {
            strength: 1e-5,
            sharpness: 1.0,
        };
        let core = Core::<2>::build(&[([0.0, 0.0], 1.0, 0)], weak.kernel(), 1e-4, None);
        assert_eq!(core.entry_count(), 0);
        assert_eq!(core.value([0.0, 0.0]), 0.0);
        assert!(core.value_exact([0.0, 0.0]) <= core.value_error());
        // Blocks of every path read +0, with or without a factor cache.
        let mut cache = super::super::FactorCache::default();
        for [cols, rows] in [[8, 8], [5, 3], [20, 3]] {
            let mut block = vec![f32::NAN; cols * rows];
            core.sample_block([-1.0, -1.0], 0.25, cols, rows, &mut block, None);
            assert!(block.iter().all(|s| s.to_bits() == 0));
            block.fill(f32::NAN);
            core.sample_block([-1.0, -1.0], 0.25, cols, rows, &mut block, Some(&mut cache));
            assert!(block.iter().all(|s| s.to_bits() == 0));
        }
        assert!(
            core.sample_grid([-1.0, -1.0], 0.25, 9, 9)
                .iter()
                .all(|s| s.to_bits() == 0)
        );
    }

    /// Issue 17, finding 2, swept: tiny balls a few ulps apart at every magnitude up to
    /// `MAX_COORDINATE`, with and without a cell size; every centre finds its balls.
    #[test]
    fn tiny_balls_far_out_are_found_at_every_magnitude() {
        for magnitude in [1.0f32, 1e3, 1e4, -1e4, 1e6, 1e9, -1e12, 1e12] {
            for ulps in [0i32, 1, 2, 3, 7] {
                let ulp = f32::from_bits(magnitude.abs().to_bits() + 1) - magnitude.abs();
                let a = [magnitude, magnitude + ulp];
                let b = [magnitude, magnitude + ulp * (1 + ulps) as f32];
                let balls = [
                    (a, 1e-6, 0),
                    (b, 1e-5, 1),
                    ([magnitude, magnitude], 1e-6, 2),
                ];
                for cell in [None, Some(1.0), Some(1e-6), Some(1e9)] {
                    let core = Core::<2>::build(&balls, Falloff::SEED.kernel(), 1e-4, cell);
                    for p in [a, b, [magnitude, magnitude]] {
                        let exact = core.value_exact(p);
                        let culled = core.value(p);
                        let at = (magnitude, ulps, cell, p);
                        assert!(exact > 1.0, "{at:?}");
                        assert!(
                            (culled - exact).abs() <= core.value_error() + 1e-6 * exact,
                            "{at:?}: {culled} vs {exact}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn cells_list_balls_in_ball_order() {
        let core = Core::<2>::build(&scattered(80, 200.0), Falloff::SEED.kernel(), 1e-4, None);
        for c in 0..core.cell_count() {
            let list = &core.entries[core.starts[c] as usize..core.starts[c + 1] as usize];
            assert!(list.windows(2).all(|w| w[0].index < w[1].index));
        }
    }
}
