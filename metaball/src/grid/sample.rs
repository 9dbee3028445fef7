//! Sampling many points at once: a whole grid ([`Core::sample_grid`]) or a small block
//! ([`Core::sample_block`]), ball by ball, with one row and one column factor per ball.

use alloc::vec;
use alloc::vec::Vec;

use super::candidates::{BIT_WORDS, BitBalls, MAX_BLOCK_CELLS};
use super::factor_cache::FactorCache;
use super::tile::TILE;
use super::{Core, Entry, saturate};
use crate::math;

impl Core<2> {
    /// Samples the culled field on a regular grid, ball by ball: for Gaussian falloffs
    /// `exp(−a (dx² + dy²)/R²) = exp(−a dx²/R²) · exp(−a dy²/R²)`, so each ball needs one
    /// `exp` per covered row and column instead of one per covered sample. Every sample sums
    /// exactly the balls [`value`](Core::value) sums (the same cutoff test on the same squared
    /// distance), in ball order; the terms differ from `value`'s only by rounding.
    pub(crate) fn sample_grid(
        &self,
        origin: [f32; 2],
        step: f32,
        width: usize,
        height: usize,
    ) -> Vec<f32> {
        let mut out = vec![0.0f32; width * height];
        let mut scratch = vec![0.0f32; 2 * width];
        self.sample_into::<false>(
            origin,
            step,
            [width, height],
            self.balls.iter(),
            &mut scratch,
            &mut out,
        );
        out
    }

    /// [`sample_grid`](Core::sample_grid) into `out` (`cols × rows` samples, row-major), for a
    /// small block: only the balls listed by the culling cells the block overlaps are visited
    /// (every ball whose cutoff reaches a sample of the block is among them), in ball order,
    /// so each sample sums the balls `value` sums; the factors come from the batched `exp`.
    /// The caller checks that `out` holds `cols × rows` samples.
    pub(crate) fn sample_block(
        &self,
        origin: [f32; 2],
        step: f32,
        cols: usize,
        rows: usize,
        out: &mut [f32],
        cache: Option<&mut FactorCache>,
    ) {
        if cols == 0 || rows == 0 {
            return;
        }
        if self.cell_count() == 0 {
            // No ball reaches epsilon anywhere (an empty grid): every sample is +0.
            out.fill(0.0);
            return;
        }
        let far = [
            origin[0] + step * (cols - 1) as f32,
            origin[1] + step * (rows - 1) as f32,
        ];
        let size = [cols, rows];
        let tile = cols <= TILE && rows <= TILE;
        if tile {
            // `sample_tile` writes every sample.
            let mut seen = [0u64; BIT_WORDS];
            if let Some(balls) = self.bit_candidates(origin, far, &mut seen) {
                return match cache {
                    Some(cache) => self.sample_tile_cached(cache, origin, step, size, balls, out),
                    None => self.sample_tile(origin, step, size, balls, out),
                };
            }
        } else {
            out.fill(0.0);
        }
        let mut inline = [0.0f32; 3 * BLOCK_INLINE_SIDE];
        let mut heap = Vec::new();
        let scratch: &mut [f32] = if tile {
            &mut []
        } else if cols <= BLOCK_INLINE_SIDE && rows <= BLOCK_INLINE_SIDE {
            &mut inline
        } else {
            heap.resize(2 * cols.max(rows) + rows, 0.0);
            &mut heap
        };
        let (x0, x1) = (self.clamp_axis(0, origin[0]), self.clamp_axis(0, far[0]));
        let (y0, y1) = (self.clamp_axis(1, origin[1]), self.clamp_axis(1, far[1]));
        let spanned = (x1 - x0 + 1) * (y1 - y0 + 1);
        if spanned == 1 {
            // One cell: its list is already the balls in ball order, each once.
            let list = self.cell_entries(y0 * self.dims[0] + x0);
            if tile {
                self.sample_tile_either(cache, origin, step, size, list.iter(), out);
            } else {
                self.sample_into::<true>(origin, step, size, list.iter(), scratch, out);
            }
        } else if spanned <= MAX_BLOCK_CELLS {
            // The union of the cells' lists, in ball order, each ball once: a bit per ball.
            let words = self.balls.len().div_ceil(64);
            let mut inline_seen = [0u64; SEEN_INLINE_WORDS];
            let mut heap_seen = Vec::new();
            let seen: &mut [u64] = if words <= SEEN_INLINE_WORDS {
                &mut inline_seen[..words]
            } else {
                heap_seen.resize(words, 0);
                &mut heap_seen
            };
            for y in y0..=y1 {
                for x in x0..=x1 {
                    for e in self.cell_entries(y * self.dims[0] + x) {
                        let i = e.index as usize;
                        seen[i / 64] |= 1 << (i % 64);
                    }
                }
            }
            let balls = BitBalls {
                words: seen,
                base: 0,
                bits: 0,
                balls: &self.balls,
            };
            if tile {
                self.sample_tile_either(cache, origin, step, size, balls, out);
            } else {
                self.sample_into::<true>(origin, step, size, balls, scratch, out);
            }
        } else if tile {
            let balls = self.balls.iter();
            self.sample_tile_either(cache, origin, step, size, balls, out);
        } else {
            self.sample_into::<true>(origin, step, size, self.balls.iter(), scratch, out);
        }
    }

    /// Adds the contributions of `balls` (in ball order, each once, a superset of the balls
    /// reaching any sample) to the zeroed `width × height` samples in `out`, then saturates.
    /// `scratch` holds at least `2 × width` floats, and `2 × max(width, height) + height` with
    /// `BATCH`, which evaluates each ball's row and column factors with
    /// [`math::exp_nonpositive_batch`] instead of the backend's `exp` one at a time.
    pub(super) fn sample_into<'a, const BATCH: bool>(
        &self,
        origin: [f32; 2],
        step: f32,
        [width, height]: [usize; 2],
        balls: impl Iterator<Item = &'a Entry<2>>,
        scratch: &mut [f32],
        out: &mut [f32],
    ) {
        let x_of = |j: usize| origin[0] + step * j as f32;
        let y_of = |i: usize| origin[1] + step * i as f32;
        let Some((scale, sharpness)) = self.separable else {
            for (n, sample) in out.iter_mut().enumerate().take(width * height) {
                *sample = self.value([x_of(n % width), y_of(n / width)]);
            }
            return;
        };
        if width == 0 || height == 0 {
            return;
        }
        let far = [x_of(width - 1), y_of(height - 1)];
        let (column_d2, rest) = scratch.split_at_mut(width);
        let (column_factor, row_factor) = rest.split_at_mut(width);
        for ball in balls {
            if !(ball.cutoff_d2 > 0.0) {
                continue;
            }
            let center = ball.center;
            let reach = ball.reach;
            // A ball whose padded cutoff box misses the samples' box reaches none of them.
            if !(center[0] + reach >= origin[0]
                && center[0] - reach <= far[0]
                && center[1] + reach >= origin[1]
                && center[1] - reach <= far[1])
            {
                continue;
            }
            let Some((j0, j1)) =
                index_range(center[0] - reach, center[0] + reach, origin[0], step, width)
            else {
                continue;
            };
            let Some((i0, i1)) = index_range(
                center[1] - reach,
                center[1] + reach,
                origin[1],
                step,
                height,
            ) else {
                continue;
            };
            // `j1 < width` and `i1 < height` (`index_range`); `scratch` holds the rows and
            // columns, `out` the samples.
            let d2s = &mut column_d2[j0..=j1];
            let factors = &mut column_factor[j0..=j1];
            for ((j, d2), factor) in (j0..=j1).zip(d2s.iter_mut()).zip(factors.iter_mut()) {
                let dx = x_of(j) - center[0];
                let dx2 = dx * dx;
                *d2 = dx2;
                let exponent = -sharpness * (dx2 * ball.inv_r2);
                *factor = if BATCH { exponent } else { math::exp(exponent) };
            }
            let rows = if BATCH {
                math::exp_nonpositive_batch(factors);
                let rows = &mut row_factor[i0..=i1];
                for (i, f) in (i0..=i1).zip(rows.iter_mut()) {
                    let dy = y_of(i) - center[1];
                    *f = -sharpness * ((dy * dy) * ball.inv_r2);
                }
                math::exp_nonpositive_batch(rows);
                &*rows
            } else {
                &[]
            };
            for i in i0..=i1 {
                let dy = y_of(i) - center[1];
                let dy2 = dy * dy;
                let row_factor = if BATCH {
                    scale * rows[i - i0]
                } else {
                    scale * math::exp(-sharpness * (dy2 * ball.inv_r2))
                };
                let row = &mut out[i * width + j0..=i * width + j1];
                for ((sample, &dx2), &factor) in row.iter_mut().zip(&*d2s).zip(&*factors) {
                    // Same expression as `distance2`: (0 + dx²) + dy². Adding +0 instead of
                    // skipping keeps the bits (a sample starts at +0 and only grows), and lets
                    // the loop run without branches.
                    let term = if dx2 + dy2 < ball.cutoff_d2 {
                        row_factor * factor
                    } else {
                        0.0
                    };
                    *sample += term;
                }
            }
        }
        for sample in out.iter_mut() {
            *sample = saturate(*sample);
        }
    }
}

/// Fields of up to `64 ×` this many balls merge the culling cells' lists on the stack.
const SEEN_INLINE_WORDS: usize = 8;

/// Blocks up to this many columns wide and rows high keep their factors on the stack.
const BLOCK_INLINE_SIDE: usize = 16;

/// The grid indices `k` in `0..count` with `lo ≤ origin + step k ≤ hi` (a superset, by a
/// rounding margin), or `None` if there are none.
///
/// Truncating casts stand in for `floor` and `ceil` (which are library calls on targets
/// without SSE4.1): after clamping to `[0, count − 1]`, `t as usize` is `floor(t)` and
/// `t as usize + 1` is at least `ceil(t)`, so the range only ever grows by one index at the
/// top, still a superset.
#[inline]
fn index_range(lo: f32, hi: f32, origin: f32, step: f32, count: usize) -> Option<(usize, usize)> {
    if count == 0 {
        return None;
    }
    let first = (lo - origin) / step;
    let last = (hi - origin) / step;
    let max = (count - 1) as f32;
    // `ceil(last) >= 0` and `floor(first) <= max`, as in floats; a NaN fails.
    if !(last > -1.0 && first < max + 1.0) {
        return None;
    }
    // Clamped into [0, count − 1] before the casts.
    let mut first = (first.max(0.0) as usize).min(count - 1);
    let mut last = (last.clamp(0.0, max) as usize + 1).min(count - 1);
    // The samples are where `origin + step * i` rounds to: a step below the coordinates'
    // resolution puts several on one spot, past the indices the division gives. Widened
    // over every sample whose rounded coordinate is in `[lo, hi]` (at most `count` steps).
    let at = |i: usize| origin + step * i as f32;
    while first > 0 && at(first - 1) >= lo {
        first -= 1;
    }
    while last + 1 < count && at(last + 1) <= hi {
        last += 1;
    }
    Some((first, last))
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::super::test_support::*;
    use super::*;
    use crate::Falloff;

    #[test]
    fn grid_sampling_sums_the_same_balls_as_point_sampling() {
        let balls = scattered(40, 150.0);
        for falloff in [Falloff::SEED, Falloff::BLINN, Falloff::WYVILL] {
            let core = Core::<2>::build(&balls, falloff.kernel(), 1e-4, None);
            for (origin, step, width, height) in [
                ([-90.0, -80.0], 2.5, 70, 64),
                ([-300.0, 10.0], 7.0, 90, 3),
                ([0.0, 0.0], 1e3, 1, 1),
                ([500.0, 500.0], 1.0, 5, 5),
            ] {
                let samples = core.sample_grid(origin, step, width, height);
                assert_eq!(samples.len(), width * height);
                for i in 0..height {
                    for j in 0..width {
                        let p = [origin[0] + step * j as f32, origin[1] + step * i as f32];
                        let v = core.value(p);
                        let s = samples[i * width + j];
                        assert!(
                            (s - v).abs() <= core.sample_error() * v,
                            "{falloff:?} at {p:?}"
                        );
                        assert_eq!(s == 0.0, v == 0.0);
                    }
                }
            }
            assert!(core.sample_grid([0.0, 0.0], 1.0, 0, 7).is_empty());
        }
    }

    #[test]
    fn block_sampling_sums_the_same_balls_as_point_sampling() {
        // Blocks inside one culling cell, across several, across more than
        // `MAX_BLOCK_CELLS`, off the grid, a single sample, and wider than the stack scratch.
        let balls = scattered(60, 200.0);
        for falloff in [Falloff::SEED, Falloff::BLINN, Falloff::WYVILL] {
            for cell_size in [None, Some(3.0), Some(1e3)] {
                let core = Core::<2>::build(&balls, falloff.kernel(), 1e-4, cell_size);
                for (origin, step, cols, rows) in [
                    ([-10.0, -10.0], 0.5, 8, 8),
                    ([-50.0, 20.0], 2.39, 8, 8),
                    ([-120.0, -120.0], 3.0, 80, 80),
                    ([-100.0, -100.0], 25.0, 9, 9),
                    ([900.0, -900.0], 1.0, 8, 8),
                    ([3.0, 4.0], 1.0, 1, 1),
                    ([3.0, 4.0], 1.0, 17, 3),
                    ([3.0, 4.0], 1.0, 3, 17),
                ] {
                    let grid = core.sample_grid(origin, step, cols, rows);
                    let mut block = vec![f32::NAN; cols * rows];
                    core.sample_block(origin, step, cols, rows, &mut block, None);
                    for (n, (g, b)) in grid.iter().zip(&block).enumerate() {
                        let p = [
                            origin[0] + step * (n % cols) as f32,
                            origin[1] + step * (n / cols) as f32,
                        ];
                        let v = core.value(p);
                        let at = (falloff, cell_size, origin, n);
                        let bound = core.sample_error() * v;
                        assert!((b - v).abs() <= bound, "{at:?}: {b} vs {v}");
                        assert!((b - g).abs() <= 2.0 * bound, "{at:?}: {b} vs {g}");
                        assert_eq!(*b == 0.0, v == 0.0, "{at:?}");
                        if falloff == Falloff::WYVILL {
                            // No separable path: the point values themselves.
                            assert_eq!(b.to_bits(), v.to_bits());
                        }
                    }
                }
            }
        }
    }

    /// Regression: the separable samplers split `scale · exp(−a q)` into a row and a column
    /// factor; for the steepest exponential falloff (`blobbiness = −80`, peak `e^80`) a factor
    /// of a reaching ball can be below `e^−87`, where the tile's `exp` flushed it to 0, so
    /// `sample_block` read 0 where `value` read up to `8.6e-4` (and `sample_grid`, with the
    /// platform's `exp`, did the same at small epsilons). Such kernels are now sampled point by
    /// point.
    #[test]
    fn steep_falloffs_sample_what_value_reads() {
        for epsilon in [1e-4, 1e-12] {
            let core = Core::<2>::build(&[([0.0, 0.0], 1.0, 0)], STEEP.kernel(), epsilon, None);
            assert!(core.separable.is_none());
            for i in 0..200 {
                let x = 1.0 + i as f32 * 6e-4;
                let v = core.value([x, 0.0]);
                let mut block = [f32::NAN; 1];
                core.sample_block([x, 0.0], 1.0, 1, 1, &mut block, None);
                let mut tile = [f32::NAN; 64];
                core.sample_block([x, 0.0], 0.25, 8, 8, &mut tile, None);
                let grid = core.sample_grid([x, 0.0], 1.0, 1, 1);
                for s in [block[0], tile[0], grid[0]] {
                    assert_eq!(s.to_bits(), v.to_bits(), "eps {epsilon} at {x}: {s} vs {v}");
                }
            }
            assert!(core.value([1.04, 0.0]) > 1e-4);
        }
        // A gentler steep falloff still splits.
        let gentler = Falloff::Exponential { blobbiness: -60.0 };
        assert!(
            Core::<2>::build(&[([0.0, 0.0], 1.0, 0)], gentler.kernel(), 1e-4, None)
                .separable
                .is_some()
        );
    }
}
