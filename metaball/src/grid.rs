//! The culled field's engine, shared by 2D and 3D: per-ball constants plus a uniform grid of
//! cells, each listing (by ball index) the balls whose cutoff box overlaps it.

use alloc::vec;
use alloc::vec::Vec;
use glam::Vec4;
use smallvec::SmallVec;

use crate::falloff::Kernel;
use crate::math;
use crate::{Attribute, MetaballError, Share, Shares};

/// One ball as the inner loops read it, copied into every cell it overlaps.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Entry<const D: usize> {
    center: [f32; D],
    inv_r2: f32,
    /// `r_c²`: the ball is skipped at squared distances from here on.
    cutoff_d2: f32,
    /// The padded cutoff radius `pad(r_c)`, for quick rejections that rounding cannot make
    /// wrong.
    reach: f32,
    index: u32,
}

/// Per-ball constants and the grid.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Core<const D: usize> {
    kernel: Kernel,
    /// `(scale, a)` of a Gaussian kernel `scale · exp(−a q)` whose row and column factors
    /// stay normal floats wherever a ball reaches ([`separable`]); `None` for the others,
    /// which the grid and block samplers evaluate point by point.
    separable: Option<(f32, f32)>,
    /// Every ball, in input order (the exact sum runs over these).
    balls: Vec<Entry<D>>,
    ids: Vec<u32>,
    origin: [f32; D],
    cell: f32,
    inv_cell: f32,
    dims: [usize; D],
    /// `starts[c]..starts[c + 1]` indexes `entries` for cell `c` (cells x-fastest).
    starts: Vec<u32>,
    entries: Vec<Entry<D>>,
    /// For 2D fields of at most `64 ×` [`BIT_WORDS`] balls (empty otherwise): per cell,
    /// `words` `u64`s with bit `i` set when ball `i` is in the cell's list. A block's
    /// candidate balls are the bitwise or of the few cells under it, in ball order.
    bits: Vec<u64>,
    words: usize,
    bounds: ([f32; D], [f32; D]),
    value_error: f32,
    gradient_error: f32,
}

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
        let cell_entries = |c: usize| match (self.starts.get(c), self.starts.get(c + 1)) {
            (Some(&a), Some(&b)) => self.entries.get(a as usize..b as usize).unwrap_or(&[]),
            _ => &[],
        };
        if spanned == 1 {
            // One cell: its list is already the balls in ball order, each once.
            let list = cell_entries(y0 * self.dims[0] + x0);
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
                inline_seen.get_mut(..words).unwrap_or(&mut [])
            } else {
                heap_seen.resize(words, 0);
                &mut heap_seen
            };
            for y in y0..=y1 {
                for x in x0..=x1 {
                    for e in cell_entries(y * self.dims[0] + x) {
                        let i = e.index as usize;
                        if let Some(word) = seen.get_mut(i / 64) {
                            *word |= 1 << (i % 64);
                        }
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

    /// Whether every sample of the `cols × rows` block (as [`sample_block`](Core::sample_block)
    /// or [`value`](Core::value) computes it) is provably at least `level`: the sum over the
    /// balls whose cutoff covers the whole block of each one's smallest contribution there (at
    /// the block's farthest corner from it), less a slack for rounding, reaches `level`.
    /// `false` when unsure; never `true` wrongly.
    ///
    /// Rounding is monotonic, so a sample's computed squared distance to a ball is at most the
    /// corner's; the terms and sums a sample computes differ from the exact ones by at most a
    /// few `1e-7` relative per term plus `n ε` over `n` terms, all covered by the slack (the
    /// bound is summed in `f64`). Contributions are never negative, so balls left out only
    /// lower the bound.
    pub(crate) fn block_at_least(
        &self,
        origin: [f32; 2],
        step: f32,
        cols: usize,
        rows: usize,
        level: f32,
    ) -> bool {
        if cols == 0 || rows == 0 {
            // No samples.
            return true;
        }
        let far = [
            origin[0] + step * (cols - 1) as f32,
            origin[1] + step * (rows - 1) as f32,
        ];
        let target = self.proof_target(level);
        let mut sum = 0.0f64;
        let mut add = |ball: &Entry<2>| {
            let dx = (origin[0] - ball.center[0])
                .abs()
                .max((far[0] - ball.center[0]).abs());
            let dy = (origin[1] - ball.center[1])
                .abs()
                .max((far[1] - ball.center[1]).abs());
            let d2 = dx * dx + dy * dy;
            if d2 < ball.cutoff_d2 {
                let q = d2 * ball.inv_r2;
                sum += f64::from(match self.separable {
                    Some((scale, a)) => scale * math::exp_nonpositive(-a * q),
                    None => self.kernel.value(q),
                });
            }
            sum >= target
        };
        let mut seen = [0u64; BIT_WORDS];
        match self.bit_candidates(origin, far, &mut seen) {
            Some(mut balls) => balls.any(&mut add),
            // Every ball: a superset of the candidates.
            None => self.balls.iter().any(add),
        }
    }

    /// What a block proof's sum of smallest contributions must reach for every sample to be
    /// at least `level`: `level` over one less the slack for the samples' rounding (`1e-5`
    /// plus `ε` per ball, relative).
    fn proof_target(&self, level: f32) -> f64 {
        let slack = 1e-5 + (self.balls.len() as f64 + 8.0) * f64::from(f32::EPSILON);
        f64::from(level) / (1.0 - slack)
    }

    /// [`block_at_least`](Core::block_at_least) for an 8 × 8 block through a factor cache:
    /// each ball whose cutoff covers every sample adds the least of its 8 row factors (kept
    /// scaled) times the least of its 8 column factors — the factors the block's samples take,
    /// from `cache` or computed and remembered as
    /// [`sample_tile_cached`](Core::sample_tile_cached) does — less the same slack. A sample
    /// adds the rounded product of its row's and column's factors for each such ball (no
    /// less than the rounded product of the least ones) and never less than 0 for the others.
    /// Other blocks, and falloffs without the separable form, go to `block_at_least`.
    pub(crate) fn block_at_least_cached(
        &self,
        cache: &mut FactorCache,
        origin: [f32; 2],
        step: f32,
        level: f32,
    ) -> bool {
        let far = [origin[0] + step * 7.0, origin[1] + step * 7.0];
        let mut seen = [0u64; BIT_WORDS];
        let (Some((scale, sharpness)), Some(balls)) =
            (self.separable, self.bit_candidates(origin, far, &mut seen))
        else {
            return self.block_at_least(origin, step, TILE, TILE, level);
        };
        cache.prepare(self.balls.len(), step);
        let lanes = TileLanes::new(origin, step, TILE, TILE);
        let minus_sharpness = Vec4::splat(-sharpness);
        let keys = [
            cache.slot_base(0, lanes.first[0]),
            cache.slot_base(1, lanes.first[1]),
        ];
        let target = self.proof_target(level);
        let mut sum = 0.0f64;
        for ball in balls {
            let Some((dx2, dy2, false)) = lanes.reach(ball) else {
                continue;
            };
            let factors = |d2: [Vec4; 2]| -> [f32; TILE] {
                let mut lanes = [0.0f32; TILE];
                exponents(&mut lanes, d2, minus_sharpness, ball.inv_r2);
                for lane in &mut lanes {
                    *lane = math::exp_nonpositive_floored(*lane);
                }
                lanes
            };
            let index = ball.index as usize;
            let columns = cache.get_or_insert(keys[0], index, || factors(dx2));
            let rows = cache.get_or_insert(keys[1], index, || {
                let mut rows = factors(dy2);
                for row in &mut rows {
                    *row *= scale;
                }
                rows
            });
            let least = |f: [f32; TILE]| {
                let m = Vec4::from_slice(&f[..4]).min(Vec4::from_slice(&f[4..]));
                m.min_element()
            };
            sum += f64::from(least(rows) * least(columns));
            if sum >= target {
                return true;
            }
        }
        false
    }

    /// The candidate balls of the block from `origin` to `far`, in ball order: those whose
    /// bits are set in any of the cells under it (every ball whose padded cutoff box meets the
    /// block), gathered in `seen` (zeros on entry); `None` when the grid keeps no bits or the
    /// block covers more than [`MAX_BLOCK_CELLS`] cells. A field of at most 64 balls keeps its
    /// one word in a register, not in `seen`.
    #[inline]
    fn bit_candidates<'s>(
        &'s self,
        origin: [f32; 2],
        far: [f32; 2],
        seen: &'s mut [u64; BIT_WORDS],
    ) -> Option<BitBalls<'s, 2>> {
        let words = self.words;
        if words == 0 {
            return None;
        }
        let width = self.dims[0];
        let (x0, x1) = (self.clamp_axis(0, origin[0]), self.clamp_axis(0, far[0]));
        let (y0, y1) = (self.clamp_axis(1, origin[1]), self.clamp_axis(1, far[1]));
        if (x1 - x0 + 1) * (y1 - y0 + 1) > MAX_BLOCK_CELLS {
            return None;
        }
        if words == 1 {
            let mut bits = 0;
            for y in y0..=y1 {
                let row = y * width;
                for x in x0..=x1 {
                    bits |= self.bits.get(row + x).copied().unwrap_or(0);
                }
            }
            // The one word, already loaded: no words left to read.
            return Some(BitBalls {
                words: &[],
                base: 64,
                bits,
                balls: &self.balls,
            });
        }
        for y in y0..=y1 {
            let row = y * width;
            for x in x0..=x1 {
                let at = (row + x) * words;
                for (w, word) in seen.iter_mut().enumerate().take(words) {
                    *word |= self.bits.get(at + w).copied().unwrap_or(0);
                }
            }
        }
        Some(BitBalls {
            words: seen.get(..words).unwrap_or(&[]),
            base: 0,
            bits: 0,
            balls: &self.balls,
        })
    }

    /// [`sample_tile_cached`](Core::sample_tile_cached) with a cache, else
    /// [`sample_tile`](Core::sample_tile).
    fn sample_tile_either<'a>(
        &self,
        cache: Option<&mut FactorCache>,
        origin: [f32; 2],
        step: f32,
        size: [usize; 2],
        balls: impl Iterator<Item = &'a Entry<2>>,
        out: &mut [f32],
    ) {
        match cache {
            Some(cache) => self.sample_tile_cached(cache, origin, step, size, balls, out),
            None => self.sample_tile(origin, step, size, balls, out),
        }
    }

    /// [`sample_tile`](Core::sample_tile), with each reaching ball's column factors (for a
    /// block 8 columns wide) and row factors (8 rows high) taken from `cache` when an earlier
    /// block on the same grid spacing had the same first column (row), else computed as
    /// `sample_tile` computes them and remembered. Rows are remembered multiplied by the
    /// kernel's scale, the products `scale · row factor` that `sample_tile` takes for each
    /// row. The factors are the same bits either way, and so are the sums: the same terms,
    /// added in the same order.
    fn sample_tile_cached<'a>(
        &self,
        cache: &mut FactorCache,
        origin: [f32; 2],
        step: f32,
        [width, height]: [usize; 2],
        balls: impl Iterator<Item = &'a Entry<2>>,
        out: &mut [f32],
    ) {
        let Some((scale, sharpness)) = self.separable else {
            return self.sample_tile(origin, step, [width, height], balls, out);
        };
        if width == 0 || height == 0 {
            return;
        }
        cache.prepare(self.balls.len(), step);
        let lanes = TileLanes::new(origin, step, width, height);
        let minus_sharpness = Vec4::splat(-sharpness);
        // Only whole rows and columns are remembered: a shorter one repeats its last lane.
        let keys = [
            (width == TILE).then(|| cache.slot_base(0, lanes.first[0])),
            (height == TILE).then(|| cache.slot_base(1, lanes.first[1])),
        ];
        let mut acc = [[Vec4::ZERO; 2]; TILE];
        for ball in balls {
            let Some((dx2, dy2, partial)) = lanes.reach(ball) else {
                continue;
            };
            let factors = |d2: [Vec4; 2]| -> [f32; TILE] {
                let mut lanes = [0.0f32; TILE];
                exponents(&mut lanes, d2, minus_sharpness, ball.inv_r2);
                // A loop, not `map`, which the compiler leaves as a call, unvectorised.
                for lane in &mut lanes {
                    *lane = math::exp_nonpositive_floored(*lane);
                }
                lanes
            };
            let index = ball.index as usize;
            let columns = match keys[0] {
                Some(key) => cache.get_or_insert(key, index, || factors(dx2)),
                None => factors(dx2),
            };
            // Rows are kept multiplied by the kernel's scale: the products `scale · row
            // factor` the sums take, computed once per row instead of once per tile.
            let scaled = || {
                let mut rows = factors(dy2);
                for row in &mut rows {
                    *row *= scale;
                }
                rows
            };
            let rows = match keys[1] {
                Some(key) => cache.get_or_insert(key, index, scaled),
                None => scaled(),
            };
            let columns = [
                Vec4::from_slice(&columns[..4]),
                Vec4::from_slice(&columns[4..]),
            ];
            // `1.0 · x` is `x`: the rows are scaled already.
            if partial {
                accumulate_partial(&mut acc, 1.0, columns, &rows, dx2, dy2, ball.cutoff_d2);
            } else {
                accumulate_whole(&mut acc, 1.0, columns, &rows);
            }
        }
        write_rows(&acc, width, height, out);
    }

    /// [`sample_into`](Core::sample_into) with `BATCH` for blocks of at most
    /// [`TILE`] × [`TILE`] samples, four lanes at a time ([`Vec4`]): per ball, the squared
    /// column and row distances, from whose extremes the ball is classed as reaching no sample
    /// (skipped), every sample (no per-sample cutoff test) or some (tested per sample); then,
    /// a batch of up to [`TILE_BATCH`] reaching balls at a time, their column and row factors
    /// (16 lanes of [`math::exp_nonpositive`] each, the batch's `exp`s overlapping), and
    /// `(scale · row factor) · column factor` added to each sample, ball by ball.
    ///
    /// Rounded addition is monotonic, so `fl(min dx² + min dy²) ≥ r_c²` proves every sample's
    /// `fl(dx² + dy²) ≥ r_c²`, and `fl(max dx² + max dy²) < r_c²` the opposite: each sample gets
    /// the terms of exactly the balls whose `dx² + dy² < r_c²`, in ball order, as in
    /// `sample_into`, with the same bits as a test at every sample.
    fn sample_tile<'a>(
        &self,
        origin: [f32; 2],
        step: f32,
        [width, height]: [usize; 2],
        balls: impl Iterator<Item = &'a Entry<2>>,
        out: &mut [f32],
    ) {
        let Some((scale, sharpness)) = self.separable else {
            let mut scratch = [0.0f32; 0];
            return self.sample_into::<true>(
                origin,
                step,
                [width, height],
                balls,
                &mut scratch,
                out,
            );
        };
        if width == 0 || height == 0 {
            return;
        }
        let lanes = TileLanes::new(origin, step, width, height);
        let minus_sharpness = Vec4::splat(-sharpness);
        let mut acc = [[Vec4::ZERO; 2]; TILE];
        // Reaching balls wait in a batch for their factors, so that the `exp`s of several
        // balls (independent, each a long chain of dependent steps) overlap.
        let mut batch = [[0.0f32; 2 * TILE]; TILE_BATCH];
        let mut waiting: [Option<(&Entry<2>, bool)>; TILE_BATCH] = [None; TILE_BATCH];
        let mut balls = balls.peekable();
        while balls.peek().is_some() {
            let mut len = 0;
            for ball in balls.by_ref() {
                let Some((dx2, dy2, partial)) = lanes.reach(ball) else {
                    continue;
                };
                let (Some(batched), Some(slot)) = (batch.get_mut(len), waiting.get_mut(len)) else {
                    break;
                };
                // Column exponents, then row exponents.
                let (columns, rows) = batched.split_at_mut(TILE);
                exponents(columns, dx2, minus_sharpness, ball.inv_r2);
                exponents(rows, dy2, minus_sharpness, ball.inv_r2);
                *slot = Some((ball, partial));
                len += 1;
                if len == TILE_BATCH {
                    break;
                }
            }
            let batch = batch.get_mut(..len).unwrap_or(&mut []);
            // Exponents below −87 (beyond [`SEPARABLE_FLOOR`]) belong to samples beyond the
            // cutoff, whose terms are masked to +0, or to lanes past the block: their factors
            // are never read, so they need not be flushed to 0.
            for factors in batch.iter_mut() {
                for f in factors.iter_mut() {
                    *f = math::exp_nonpositive_floored(*f);
                }
            }
            for (factors, &slot) in batch.iter().zip(&waiting) {
                let Some((ball, partial)) = slot else {
                    continue;
                };
                let columns = [
                    Vec4::from_slice(&factors[..4]),
                    Vec4::from_slice(&factors[4..8]),
                ];
                let rows = &factors[TILE..];
                if partial {
                    let (dx2, dy2) = squares(lanes.xs, lanes.ys, ball.center);
                    accumulate_partial(&mut acc, scale, columns, rows, dx2, dy2, ball.cutoff_d2);
                } else {
                    accumulate_whole(&mut acc, scale, columns, rows);
                }
            }
        }
        write_rows(&acc, width, height, out);
    }

    /// Adds the contributions of `balls` (in ball order, each once, a superset of the balls
    /// reaching any sample) to the zeroed `width × height` samples in `out`, then saturates.
    /// `scratch` holds at least `2 × width` floats, and `2 × max(width, height) + height` with
    /// `BATCH`, which evaluates each ball's row and column factors with
    /// [`math::exp_nonpositive_batch`] instead of the backend's `exp` one at a time.
    fn sample_into<'a, const BATCH: bool>(
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
            let (Some(d2s), Some(factors)) =
                (column_d2.get_mut(j0..=j1), column_factor.get_mut(j0..=j1))
            else {
                continue;
            };
            for ((j, d2), factor) in (j0..=j1).zip(d2s.iter_mut()).zip(factors.iter_mut()) {
                let dx = x_of(j) - center[0];
                let dx2 = dx * dx;
                *d2 = dx2;
                let exponent = -sharpness * (dx2 * ball.inv_r2);
                *factor = if BATCH { exponent } else { math::exp(exponent) };
            }
            let rows = if BATCH {
                math::exp_nonpositive_batch(factors);
                let Some(rows) = row_factor.get_mut(i0..=i1) else {
                    continue;
                };
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
                    scale * rows.get(i - i0).copied().unwrap_or(0.0)
                } else {
                    scale * math::exp(-sharpness * (dy2 * ball.inv_r2))
                };
                let Some(row) = out.get_mut(i * width + j0..=i * width + j1) else {
                    continue;
                };
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

/// The smallest exponent a row or column factor of a reaching ball may have for the separable
/// samplers: far enough above [`math::exp_nonpositive`]'s floor (−87, where it flushes to 0)
/// and the normal range of `f32` that rounding in `dx² / R²` cannot cross it.
const SEPARABLE_FLOOR: f32 = -80.0;

/// `(scale, a)` for a Gaussian kernel `scale · exp(−a q)` that the grid and block samplers may
/// split into a row factor `exp(−a dy²/R²)` times a column factor `exp(−a dx²/R²)`: each
/// factor is at least the product, whose exponent is at least `−a q_c` wherever a ball
/// reaches, so the factors of reaching balls stay normal floats when `−a q_c` is at least
/// [`SEPARABLE_FLOOR`]. Otherwise (regression: the steepest exponential falloff,
/// `blobbiness = −80`, at the default epsilon has `−a q_c ≈ −89`) a factor could flush to 0
/// and a sample read 0 where [`Core::value`] reads up to `1e-3`; such kernels, and Wyvill's,
/// are sampled point by point.
fn separable(kernel: Kernel, q_cut: f32) -> Option<(f32, f32)> {
    kernel
        .gaussian()
        .filter(|&(_, sharpness)| -sharpness * q_cut >= SEPARABLE_FLOOR)
}

/// One ball's contribution `scale · exp(−a q)` at a point within its cutoff, for a field
/// whose kernel is [`separable`]: `exp` from [`math::exp_nonpositive`] (within `1.5e-7` of
/// the true `exp`, the same bits on every platform), whose argument, at least `−a q_c`, stays
/// above its floor. What the culled point queries (`value`, `value_and_gradient`, `shares`,
/// `blend`) sum, through [`split_terms`]; the exact ones use the platform's `exp`.
#[cfg(test)]
fn split_value(scale: f32, a: f32, q: f32) -> f32 {
    scale * math::exp_nonpositive(-a * q)
}

/// Blocks of at most `TILE × TILE` samples take the fixed-width path.
const TILE: usize = 8;

/// The squared distances from `center` of the columns' `xs` and the rows' `ys`.
#[inline(always)]
fn squares(xs: [Vec4; 2], ys: [Vec4; 2], center: [f32; 2]) -> ([Vec4; 2], [Vec4; 2]) {
    let cx = Vec4::splat(center[0]);
    let cy = Vec4::splat(center[1]);
    let dx = [xs[0] - cx, xs[1] - cx];
    let dy = [ys[0] - cy, ys[1] - cy];
    (
        [dx[0] * dx[0], dx[1] * dx[1]],
        [dy[0] * dy[0], dy[1] * dy[1]],
    )
}

/// A tile's sample coordinates, four lanes a vector: the columns' x, then the rows' y. Lanes
/// past the block repeat its last column or row: they leave the extremes alone, and their sums
/// are never read.
struct TileLanes {
    xs: [Vec4; 2],
    ys: [Vec4; 2],
    /// The first column's x and row's y.
    first: [f32; 2],
    /// The last lane's (the last column's and row's).
    last: [f32; 2],
    /// `first` then `last`, as one vector.
    ends: Vec4,
}

impl TileLanes {
    /// Whether `ball` reaches a sample of the tile: if so, the squared column and row
    /// distances (`dx²` per column, `dy²` per row) and whether it misses some sample
    /// (`partial`); `None` when it reaches none (also for a ball with no cutoff, `r_c² = 0`).
    /// Finite coordinates and centres, so no NaN (at worst +∞).
    #[inline(always)]
    fn reach(&self, ball: &Entry<2>) -> Option<([Vec4; 2], [Vec4; 2], bool)> {
        let [cx, cy] = ball.center;
        // The squared distances of the first and last column and row, first: the lanes the
        // extremes need, the same bits as in `squares`, which only a reaching ball needs.
        let ends = self.ends - Vec4::new(cx, cy, cx, cy);
        let [ax, ay, bx, by] = (ends * ends).to_array();
        let (lo_x, hi_x) = extremes(self.first[0], self.last[0], cx, ax, bx);
        let (lo_y, hi_y) = extremes(self.first[1], self.last[1], cy, ay, by);
        if !(lo_x + lo_y < ball.cutoff_d2) {
            return None;
        }
        let (dx2, dy2) = squares(self.xs, self.ys, ball.center);
        Some((dx2, dy2, !(hi_x + hi_y < ball.cutoff_d2)))
    }

    /// For a block of `width × height` samples (both in `1..=TILE`).
    #[inline(always)]
    fn new(origin: [f32; 2], step: f32, width: usize, height: usize) -> Self {
        // `origin + step × k` for lane `k` clamped to the block, in vector registers: lanes
        // written one by one and read as vectors would stall on store forwarding.
        let lanes = |origin: f32, size: usize| {
            let last = Vec4::splat((size - 1) as f32);
            let (origin, step) = (Vec4::splat(origin), Vec4::splat(step));
            [LANE_INDEX[0], LANE_INDEX[1]].map(|k| origin + step * k.min(last))
        };
        let xs = lanes(origin[0], width);
        let ys = lanes(origin[1], height);
        Self {
            xs,
            ys,
            first: [xs[0].x, ys[0].x],
            last: [xs[1].w, ys[1].w],
            ends: Vec4::new(xs[0].x, ys[0].x, xs[1].w, ys[1].w),
        }
    }
}

/// The lane indices `0, 1, …, 7` of a tile's columns (rows), exact in `f32`.
const LANE_INDEX: [Vec4; 2] = [Vec4::new(0.0, 1.0, 2.0, 3.0), Vec4::new(4.0, 5.0, 6.0, 7.0)];

/// The exponents `−a d²/R²` of eight squared distances `d2` into `out` (eight lanes).
#[inline(always)]
fn exponents(out: &mut [f32], d2: [Vec4; 2], minus_sharpness: Vec4, inv_r2: f32) {
    let inv_r2 = Vec4::splat(inv_r2);
    for (four, d2) in out.chunks_exact_mut(4).zip(d2) {
        four.copy_from_slice(&(minus_sharpness * (d2 * inv_r2)).to_array());
    }
}

/// Adds one ball's terms `(scale · row factor) · column factor` to every sample of a tile
/// (a ball whose cutoff covers the whole tile).
#[inline(always)]
fn accumulate_whole(acc: &mut [[Vec4; 2]; TILE], scale: f32, columns: [Vec4; 2], rows: &[f32]) {
    for (sums, &fy) in acc.iter_mut().zip(rows) {
        let row_factor = Vec4::splat(scale * fy);
        for (sum, &fx) in sums.iter_mut().zip(&columns) {
            *sum += row_factor * fx;
        }
    }
}

/// Adds one ball's terms to the samples of a tile within its cutoff: `dx2`, `dy2` are the
/// squared column and row distances.
#[inline(always)]
fn accumulate_partial(
    acc: &mut [[Vec4; 2]; TILE],
    scale: f32,
    columns: [Vec4; 2],
    rows: &[f32],
    dx2: [Vec4; 2],
    dy2: [Vec4; 2],
    cutoff_d2: f32,
) {
    let cutoff_d2 = Vec4::splat(cutoff_d2);
    let dy2 = [dy2[0].to_array(), dy2[1].to_array()];
    let dy2 = dy2.as_flattened();
    for ((sums, &fy), &dy2) in acc.iter_mut().zip(rows).zip(dy2) {
        let row_factor = Vec4::splat(scale * fy);
        let dy2 = Vec4::splat(dy2);
        for ((sum, &dx2), &fx) in sums.iter_mut().zip(&dx2).zip(&columns) {
            // Same expression as `distance2`: (0 + dx²) + dy². Outside, +0, which keeps the
            // bits: a sample starts at +0 and only grows.
            let inside = (dx2 + dy2).cmplt(cutoff_d2);
            *sum += Vec4::select(inside, row_factor * fx, Vec4::ZERO);
        }
    }
}

/// Saturates a tile's sums into the `width × height` samples of `out`.
#[inline(always)]
fn write_rows(acc: &[[Vec4; 2]; TILE], width: usize, height: usize, out: &mut [f32]) {
    for (samples, row) in out.chunks_exact_mut(width).zip(acc).take(height) {
        let row = row.map(|sums| saturate4(sums).to_array());
        let row = row.as_flattened();
        if let (Ok(samples), Ok(row)) = (
            <&mut [f32; TILE]>::try_from(&mut *samples),
            <&[f32; TILE]>::try_from(row),
        ) {
            // A whole row: a fixed-size copy (a variable-length one is a `memcpy` call).
            *samples = *row;
        } else {
            for (sample, &a) in samples.iter_mut().zip(row) {
                *sample = a;
            }
        }
    }
}

/// Slots per ball and axis in a [`FactorCache`]: blocks whose first column (row) lies in the
/// same `8 × step` band modulo this many bands share a slot.
const CACHE_WAYS: usize = 16;

/// Factor rows a [`FactorCache`] makes room for per ball at first.
const FACTORS_PER_BALL: usize = 16;

/// The tag of an empty [`FactorCache`] slot: a NaN, which no block's (finite) first column or
/// row has.
const EMPTY_TAG: u32 = 0x7fc0_0001;

/// Row and column factors of 8 × 8 blocks, remembered per ball and per first column (row) for
/// one grid spacing: what `BlockSampler` keeps between blocks. (Row factors are kept
/// multiplied by the kernel's scale: see [`Core::sample_tile_cached`].)
#[derive(Debug, Clone, Default)]
pub(crate) struct FactorCache {
    /// The bits of the spacing the factors are for.
    step: u32,
    /// `1 / (8 × step)`: a coordinate's band.
    inv_band: f32,
    /// Per ball, per axis, per slot: the bits of the first coordinate whose factors the slot
    /// holds (or [`EMPTY_TAG`]), and where in `factors` they are.
    slots: Vec<(u32, u32)>,
    /// Factors, in the order slots were first filled (so a cache only touches, and zeroes,
    /// the memory it uses).
    factors: Vec<[f32; TILE]>,
    /// Lookups answered from the cache.
    #[cfg(test)]
    hits: usize,
}

impl FactorCache {
    /// Empties the cache unless it is sized for `balls` and holds factors for `step`.
    fn prepare(&mut self, balls: usize, step: f32) {
        let slots = balls * 2 * CACHE_WAYS;
        if self.slots.len() != slots || self.step != step.to_bits() {
            self.slots.clear();
            self.slots.resize(slots, (EMPTY_TAG, 0));
            self.factors.clear();
            // Room for a typical trace's rows and columns (about ten per ball), so that the
            // factors rarely move as they grow.
            self.factors.reserve(balls * FACTORS_PER_BALL);
            self.step = step.to_bits();
            self.inv_band = 1.0 / (TILE as f32 * step);
        }
    }

    /// Where the factors of the row (`axis` 1) or column (`axis` 0) band starting at `first`
    /// live, for ball 0, and the tag they carry.
    #[inline]
    fn slot_base(&self, axis: usize, first: f32) -> (usize, u32) {
        // A saturating cast: any deterministic slot will do.
        let band = (first * self.inv_band) as i32 as usize & (CACHE_WAYS - 1);
        (axis * CACHE_WAYS + band, first.to_bits())
    }

    /// Ball `ball`'s factors under `key`, computed by `compute` and remembered on a miss.
    #[inline]
    fn get_or_insert(
        &mut self,
        (base, tag): (usize, u32),
        ball: usize,
        compute: impl FnOnce() -> [f32; TILE],
    ) -> [f32; TILE] {
        let Some(slot) = self.slots.get_mut(ball * 2 * CACHE_WAYS + base) else {
            return compute();
        };
        if slot.0 == tag
            && let Some(&factors) = self.factors.get(slot.1 as usize)
        {
            #[cfg(test)]
            {
                self.hits += 1;
            }
            return factors;
        }
        let factors = compute();
        if slot.0 == EMPTY_TAG {
            let Ok(row) = u32::try_from(self.factors.len()) else {
                return factors;
            };
            self.factors.push(factors);
            *slot = (tag, row);
        } else if let Some(kept) = self.factors.get_mut(slot.1 as usize) {
            *kept = factors;
            slot.0 = tag;
        }
        factors
    }
}

/// How many reaching balls [`Core::sample_tile`] gathers before their `exp`s.
const TILE_BATCH: usize = 8;

/// A lower bound on the squared distances `a = d²(first)`, …, `b = d²(last)` from `center` of
/// a monotonic row of coordinates (exact unless `center` lies within `[first, last]`, where it
/// is 0), and their largest value. `|coordinate − center|` falls then rises along the row, and
/// so does its rounded square: the largest is at an end, and so is the smallest when the centre
/// lies beyond one.
#[inline(always)]
fn extremes(first: f32, last: f32, center: f32, a: f32, b: f32) -> (f32, f32) {
    let lo = if center < first {
        a
    } else if center > last {
        b
    } else {
        0.0
    };
    (lo, a.max(b))
}

/// 2D fields of up to `64 ×` this many balls keep a bit set of balls per culling cell.
const BIT_WORDS: usize = 4;

/// The balls whose bits are set in `words` (bit `i % 64` of word `i / 64` for ball `i`), in
/// ball order.
struct BitBalls<'a, const D: usize> {
    words: &'a [u64],
    /// 64 more than the index of the first ball of the word in `bits`.
    base: usize,
    /// What is left of the current word.
    bits: u64,
    balls: &'a [Entry<D>],
}

impl<'a, const D: usize> Iterator for BitBalls<'a, D> {
    type Item = &'a Entry<D>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        loop {
            while self.bits == 0 {
                let (&first, rest) = self.words.split_first()?;
                self.bits = first;
                self.words = rest;
                self.base += 64;
            }
            let i = self.base - 64 + self.bits.trailing_zeros() as usize;
            self.bits &= self.bits - 1;
            if let Some(ball) = self.balls.get(i) {
                return Some(ball);
            }
        }
    }
}

/// Fields of up to `64 ×` this many balls merge the culling cells' lists on the stack.
const SEEN_INLINE_WORDS: usize = 8;

/// Blocks up to this many columns wide and rows high keep their factors on the stack.
const BLOCK_INLINE_SIDE: usize = 16;

/// A block spanning more culling cells than this visits every ball instead of merging the
/// cells' lists.
const MAX_BLOCK_CELLS: usize = 16;

/// Relative padding of each ball's cutoff box, so rounding in the cell lookup can never drop a
/// ball the distance test would keep.
const BOX_PAD: f32 = 1e-4;

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
        for (index, &(center, radius, id)) in balls.iter().enumerate() {
            let r2 = radius * radius;
            let cutoff = radius * math::sqrt(q_cut);
            let cutoff_d2 = r2 * q_cut;
            compiled.push(Entry {
                center,
                inv_r2: 1.0 / r2,
                cutoff_d2,
                reach: pad(math::sqrt(cutoff_d2)),
                index: u32::try_from(index).unwrap_or(u32::MAX),
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
            // Grow the box by the padding too.
            let margin = pad(hi[k] - lo[k]) - (hi[k] - lo[k]) + f32::MIN_POSITIVE;
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
                for count in counts.get_mut(run).unwrap_or(&mut []) {
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
                    for slot in cursor.get_mut(run).unwrap_or(&mut []) {
                        if let Some(entry) = entries.get_mut(*slot as usize) {
                            *entry = *ball;
                        }
                        *slot += 1;
                    }
                    if keep_bits {
                        let (at, bit) = (first * words + i / 64, 1u64 << (i % 64));
                        let span = (len - 1) * words + 1;
                        let run = bits.get_mut(at..at + span).unwrap_or(&mut []);
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
    fn clamp_axis(&self, k: usize, x: f32) -> usize {
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
    fn nearby(&self, p: &[f32; D]) -> &[Entry<D>] {
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
        match (self.starts.get(cell), self.starts.get(cell + 1)) {
            (Some(&a), Some(&b)) => self.entries.get(a as usize..b as usize).unwrap_or(&[]),
            _ => &[],
        }
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

    pub(crate) fn cell_size(&self) -> f32 {
        self.cell
    }

    pub(crate) fn cell_count(&self) -> usize {
        self.starts.len() - 1
    }

    pub(crate) fn entry_count(&self) -> usize {
        self.entries.len()
    }

    /// The culled sum.
    pub(crate) fn value(&self, p: [f32; D]) -> f32 {
        let entries = self.nearby(&p);
        match self.separable {
            Some((scale, a)) => {
                let mut sum = 0.0;
                split_terms(entries, &p, scale, a, |_, f| sum += f);
                saturate(sum)
            }
            None => match self.kernel {
                Kernel::Exponential { b } => {
                    culled_sum(entries, &p, |q| Kernel::Exponential { b }.value(q))
                }
                Kernel::Gauss {
                    strength,
                    sharpness,
                } => culled_sum(entries, &p, |q| {
                    Kernel::Gauss {
                        strength,
                        sharpness,
                    }
                    .value(q)
                }),
                Kernel::Wyvill { peak } => {
                    culled_sum(entries, &p, |q| Kernel::Wyvill { peak }.value(q))
                }
            },
        }
    }

    /// The exact sum over every ball, in ball order.
    pub(crate) fn value_exact(&self, p: [f32; D]) -> f32 {
        if !p.iter().all(|x| x.is_finite()) {
            return 0.0;
        }
        let mut sum = 0.0;
        for ball in &self.balls {
            sum += self.kernel.value(distance2(&p, &ball.center) * ball.inv_r2);
        }
        saturate(sum)
    }

    /// The culled value and gradient.
    pub(crate) fn value_and_gradient(&self, p: [f32; D]) -> (f32, [f32; D]) {
        let entries = self.nearby(&p);
        match self.separable {
            Some((scale, a)) => {
                let mut value = 0.0f32;
                let mut gradient = [0.0f64; D];
                split_terms(entries, &p, scale, a, |e, f| {
                    value += f;
                    add_gradient(&mut gradient, e, &p, -2.0 * a * f);
                });
                (saturate(value), gradient.map(saturate_f64))
            }
            None => gradient_sum(entries, &p, true, |q| self.kernel.value_and_slope(q)),
        }
    }

    /// The exact value and gradient over every ball.
    pub(crate) fn value_and_gradient_exact(&self, p: [f32; D]) -> (f32, [f32; D]) {
        if !p.iter().all(|x| x.is_finite()) {
            return (0.0, [0.0; D]);
        }
        gradient_sum(&self.balls, &p, false, |q| self.kernel.value_and_slope(q))
    }

    /// Calls `visit(ball index, contribution)` for every ball within its cutoff of `p` that
    /// contributes a positive amount, in ball order. Each contribution is finite: a valid
    /// kernel's value is at most its peak (`e^80` at worst).
    fn for_each_contribution(&self, p: &[f32; D], visit: impl FnMut(u32, f32)) {
        match self.separable {
            Some((scale, a)) => {
                let mut visit = visit;
                split_terms(self.nearby(p), p, scale, a, |e, f| visit(e.index, f));
            }
            None => self.contributions(p, |q| self.kernel.value(q), visit),
        }
    }

    /// [`for_each_contribution`](Core::for_each_contribution) with the kernel `f(q)`.
    #[inline(always)]
    fn contributions(
        &self,
        p: &[f32; D],
        kernel: impl Fn(f32) -> f32,
        mut visit: impl FnMut(u32, f32),
    ) {
        for e in self.nearby(p) {
            let d2 = distance2(p, &e.center);
            if d2 < e.cutoff_d2 {
                let f = kernel(d2 * e.inv_r2);
                if f > 0.0 && f.is_finite() {
                    visit(e.index, f);
                }
            }
        }
    }

    /// Per-id sums in `f64`: at most 2^32 terms of at most `e^80 ≈ 5.5e34` each, so they never
    /// overflow even where the `f32` value saturates.
    pub(crate) fn shares(&self, p: [f32; D], k: usize) -> Shares {
        if k == 0 {
            return Shares::new();
        }
        let mut per_id = PerId::new();
        self.for_each_contribution(&p, |index, f| self.add_share(&mut per_id, index, f));
        top_shares(per_id, k)
    }

    /// [`value_and_gradient`](Core::value_and_gradient) and [`shares`](Core::shares) at `p`
    /// from one pass over the balls (for the separable falloffs; two passes for Wyvill's):
    /// the same results, bit for bit, as the two calls.
    pub(crate) fn value_gradient_and_shares(
        &self,
        p: [f32; D],
        k: usize,
    ) -> (f32, [f32; D], Shares) {
        let Some((scale, a)) = self.separable else {
            let (value, gradient) = self.value_and_gradient(p);
            return (value, gradient, self.shares(p, k));
        };
        let mut value = 0.0f32;
        let mut gradient = [0.0f64; D];
        let mut per_id = PerId::new();
        split_terms(self.nearby(&p), &p, scale, a, |e, f| {
            value += f;
            add_gradient(&mut gradient, e, &p, -2.0 * a * f);
            if k > 0 {
                self.add_share(&mut per_id, e.index, f);
            }
        });
        let shares = if k == 0 {
            Shares::new()
        } else {
            top_shares(per_id, k)
        };
        (saturate(value), gradient.map(saturate_f64), shares)
    }

    /// Adds ball `index`'s contribution `f` to its id's sum.
    #[inline(always)]
    fn add_share(&self, per_id: &mut PerId, index: u32, f: f32) {
        let id = self.ids.get(index as usize).copied().unwrap_or(0);
        // A bone's balls are usually consecutive: the last id first.
        match per_id.last_mut() {
            Some(last) if last.0 == id => last.1 += f64::from(f),
            _ => {
                if let Some(s) = per_id.iter_mut().find(|s| s.0 == id) {
                    s.1 += f64::from(f);
                } else {
                    per_id.push((id, f64::from(f)));
                }
            }
        }
    }

    /// `Σ (f_i / Σ f_j) a_i` over the balls reaching `p`, the weights normalised in `f64`
    /// before they touch the attributes. `attributes` has one entry per ball (checked by the
    /// caller); only the entries of contributing balls are read, and checked.
    pub(crate) fn blend<T: Attribute>(
        &self,
        p: [f32; D],
        attributes: &[T],
    ) -> Result<Option<T>, MetaballError> {
        let mut contributions: SmallVec<[(u32, f32); 16]> = SmallVec::new();
        let mut total = 0.0f64;
        self.for_each_contribution(&p, |index, f| {
            total += f64::from(f);
            contributions.push((index, f));
        });
        if !(total > 0.0 && total.is_finite()) {
            return Ok(None);
        }
        let mut acc: Option<T> = None;
        for &(index, f) in &contributions {
            let Some(&a) = attributes.get(index as usize) else {
                continue;
            };
            if !a.is_finite() {
                return Err(MetaballError::NonFinite {
                    what: "attribute",
                    index: index as usize,
                });
            }
            let term = a * ((f64::from(f) / total) as f32);
            acc = Some(match acc {
                Some(sum) => sum + term,
                None => term,
            });
        }
        match acc {
            Some(v) if !v.is_finite() => Err(MetaballError::BlendOverflow {
                blended: contributions.len(),
            }),
            other => Ok(other),
        }
    }
}

/// The grid indices `k` in `0..count` with `lo ≤ origin + step k ≤ hi` (a superset, by a
/// rounding margin), or `None` if there are none.
///
/// Truncating casts stand in for `floor` and `ceil` (which are library calls on targets
/// without SSE4.1): after clamping to `[0, count − 1]`, `t as usize` is `floor(t)` and
/// `t as usize + 1` is at least `ceil(t)`, so the range only ever grows by one index at the
/// top, still a superset.
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
    let first = (first.max(0.0) as usize).min(count - 1);
    let last = (last.clamp(0.0, max) as usize + 1).min(count - 1);
    Some((first, last))
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

fn pad(r: f32) -> f32 {
    r * (1.0 + BOX_PAD) + f32::MIN_POSITIVE
}

#[inline(always)]
fn distance2<const D: usize>(p: &[f32; D], c: &[f32; D]) -> f32 {
    let mut d2 = 0.0;
    for k in 0..D {
        let d = p[k] - c[k];
        d2 += d * d;
    }
    d2
}

/// A sum of non-negative finite contributions that overflowed `f32` is `+∞`: it saturates to
/// `f32::MAX`, so a point deep inside an extreme field still reads as inside (regression:
/// it used to read 0, outside). A NaN cannot arise from such a sum; it would read 0.
fn saturate(x: f32) -> f32 {
    if x.is_nan() { 0.0 } else { x.min(f32::MAX) }
}

/// [`saturate`] on four lanes.
#[inline(always)]
fn saturate4(x: Vec4) -> Vec4 {
    // `min` gives the bound for a NaN lane, which the select then zeroes.
    Vec4::select(x.cmpeq(x), x.min(Vec4::splat(f32::MAX)), Vec4::ZERO)
}

/// An `f64` gradient component as `f32`, saturated to `±f32::MAX`.
fn saturate_f64(x: f64) -> f32 {
    if x.is_nan() {
        0.0
    } else {
        // Clamped into the f32 range first, so the cast rounds rather than overflows.
        x.clamp(-f64::from(f32::MAX), f64::from(f32::MAX)) as f32
    }
}

#[inline(always)]
fn culled_sum<const D: usize>(
    entries: &[Entry<D>],
    p: &[f32; D],
    kernel: impl Fn(f32) -> f32,
) -> f32 {
    let mut sum = 0.0;
    for e in entries {
        let d2 = distance2(p, &e.center);
        if d2 < e.cutoff_d2 {
            sum += kernel(d2 * e.inv_r2);
        }
    }
    saturate(sum)
}

/// The value (an `f32` sum in ball order, the same bits as [`culled_sum`] / the exact sum with
/// the same `value_and_slope`) and the gradient, whose terms `2 f'(q) (p − c) / R²` are formed and summed in `f64`: one tiny
/// steep ball can exceed `f32` on its own (`e^80 · 160 / R` for `R = 1e-6`), and terms of both
/// signs could then meet as `∞ − ∞`. Each component saturates to `±f32::MAX`.
#[inline(always)]
fn gradient_sum<const D: usize>(
    entries: &[Entry<D>],
    p: &[f32; D],
    culled: bool,
    value_and_slope: impl Fn(f32) -> (f32, f32),
) -> (f32, [f32; D]) {
    let mut value = 0.0f32;
    let mut gradient = [0.0f64; D];
    for e in entries {
        let mut delta = [0.0f32; D];
        let mut d2 = 0.0;
        for k in 0..D {
            delta[k] = p[k] - e.center[k];
            d2 += delta[k] * delta[k];
        }
        if culled && !(d2 < e.cutoff_d2) {
            continue;
        }
        let (f, slope2) = value_and_slope(d2 * e.inv_r2);
        value += f;
        add_gradient(&mut gradient, e, p, slope2);
    }
    (saturate(value), gradient.map(saturate_f64))
}

/// Adds one ball's gradient term `slope2 (p − c) / R²` (`slope2 = 2 f'(q)`), in `f64`.
#[inline(always)]
fn add_gradient<const D: usize>(gradient: &mut [f64; D], e: &Entry<D>, p: &[f32; D], slope2: f32) {
    if slope2 != 0.0 {
        let scale = f64::from(slope2) * f64::from(e.inv_r2);
        for k in 0..D {
            gradient[k] += scale * f64::from(p[k] - e.center[k]);
        }
    }
}

/// Calls `visit(entry, scale · exp(−a q))` for each of `entries` within its cutoff of `p`, in
/// order, with [`split_value`]'s bits: up to [`POINT_BATCH`] entries at a time, the `exp`s of
/// those within their cutoff computed together as vectors whose long dependency chains
/// overlap.
#[inline(always)]
fn split_terms<'a, const D: usize>(
    entries: &'a [Entry<D>],
    p: &[f32; D],
    scale: f32,
    a: f32,
    mut visit: impl FnMut(&'a Entry<D>, f32),
) {
    for block in entries.chunks(POINT_BATCH) {
        // The exponents of the entries within their cutoff, gathered without a branch per
        // entry (whether a ball reaches is as good as random), then their `exp`s four at a
        // time, then the visits in order.
        let mut kept = [0u8; POINT_BATCH];
        let mut f = [0.0f32; POINT_BATCH];
        let mut n = 0;
        for (lane, e) in block.iter().enumerate() {
            let d2 = distance2(p, &e.center);
            if let (Some(slot), Some(f)) = (kept.get_mut(n), f.get_mut(n)) {
                *slot = lane as u8;
                *f = -a * (d2 * e.inv_r2);
            }
            n += usize::from(d2 < e.cutoff_d2);
        }
        // Within its cutoff an exponent is above −87, where the floored `exp` has the same
        // bits; the lanes past `n` are never read.
        if n <= 2 {
            // Too few for a vector: one lane at a time (the same bits), shorter chains.
            for f in f.iter_mut().take(n) {
                *f = scale * math::exp_nonpositive_floored(*f);
            }
        } else {
            for lanes in f.chunks_exact_mut(4).take(n.div_ceil(4)) {
                for f in lanes {
                    *f = scale * math::exp_nonpositive_floored(*f);
                }
            }
        }
        for (&lane, &f) in kept.iter().zip(&f).take(n) {
            if let Some(e) = block.get(usize::from(lane)) {
                visit(e, f);
            }
        }
    }
}

/// How many culling-cell entries a point query evaluates at once.
const POINT_BATCH: usize = 16;

/// Sorts a short slice by `order` (a strict order, so any sort gives the same result).
fn insertion_sort<T: Copy>(xs: &mut [T], order: impl Fn(&T, &T) -> core::cmp::Ordering) {
    for i in 1..xs.len() {
        let mut j = i;
        while j > 0 && order(&xs[j - 1], &xs[j]) == core::cmp::Ordering::Greater {
            xs.swap(j - 1, j);
            j -= 1;
        }
    }
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

/// Per-id contribution sums at a point (inline for the usual few ids).
type PerId = SmallVec<[(u32, f64); 16]>;

/// The `k` largest per-id sums (`k > 0`), largest first, renormalised to sum to 1; empty where
/// they sum to 0.
fn top_shares(mut per_id: PerId, k: usize) -> Shares {
    // Largest first, ties by id: ids are distinct, so this is a strict order and the
    // first `k` after a partial selection and a sort are those of a full sort.
    let order = |a: &(u32, f64), b: &(u32, f64)| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0));
    let kept = k.min(per_id.len());
    let top = if kept < per_id.len() {
        let (top, _, _) = per_id.select_nth_unstable_by(kept, order);
        top
    } else {
        &mut per_id[..]
    };
    insertion_sort(top, order);
    let total: f64 = top.iter().map(|s| s.1).sum();
    if !(total > 0.0 && total.is_finite()) {
        return Shares::new();
    }
    top.iter()
        .map(|&(id, weight)| Share {
            id,
            // In (0, 1]: the cast cannot overflow.
            weight: (weight / total) as f32,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Falloff;

    fn scattered(count: usize, spread: f32) -> Vec<([f32; 2], f32, u32)> {
        (0..count)
            .map(|i| {
                let a = i as f32;
                let x = ((a * 0.618_034).fract() - 0.5) * spread;
                let y = ((a * 0.414_213_5).fract() - 0.5) * spread;
                (
                    [x, y],
                    2.0 + 10.0 * (a * 0.732_050_8).fract(),
                    (i % 5) as u32,
                )
            })
            .collect()
    }

    #[test]
    fn culled_sum_skips_exactly_the_balls_beyond_their_cutoff() {
        let balls = scattered(60, 300.0);
        for falloff in [Falloff::SEED, Falloff::BLINN, Falloff::WYVILL, STEEP] {
            let kernel = falloff.kernel();
            let core = Core::<2>::build(&balls, kernel, 1e-4, None);
            // The separable kernels' terms, with the inline `exp`; the others' from the kernel.
            let term = |q: f32| match core.separable {
                Some((scale, a)) => split_value(scale, a, q),
                None => kernel.value(q),
            };
            for i in 0..2000 {
                let a = i as f32;
                let p = [
                    ((a * 0.377).fract() - 0.5) * 400.0,
                    ((a * 0.291).fract() - 0.5) * 400.0,
                ];
                // Brute force over the balls within their cutoff, in ball order.
                let mut expected = 0.0;
                let mut exact = 0.0;
                for ball in &core.balls {
                    let d2 = distance2(&p, &ball.center);
                    if d2 < ball.cutoff_d2 {
                        expected += term(d2 * ball.inv_r2);
                        exact += kernel.value(d2 * ball.inv_r2);
                    }
                }
                let expected = saturate(expected);
                let at = (falloff, p);
                assert_eq!(core.value(p).to_bits(), expected.to_bits(), "{at:?}");
                let (v, _) = core.value_and_gradient(p);
                assert_eq!(v.to_bits(), expected.to_bits(), "{at:?}");
                // The inline `exp` is within 1.5e-7 of the platform's.
                assert!((expected - exact).abs() <= 2e-7 * exact, "{at:?}");
                assert_eq!(
                    core.separable.is_some(),
                    falloff != Falloff::WYVILL && falloff != STEEP
                );
            }
        }
    }

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
    fn three_d_grid_agrees_with_the_exact_sum() {
        let balls: Vec<([f32; 3], f32, u32)> = (0..40)
            .map(|i| {
                let a = i as f32;
                (
                    [
                        (a * 0.618_034).fract() * 50.0,
                        (a * 0.414_213_5).fract() * 50.0,
                        (a * 0.732_050_8).fract() * 50.0,
                    ],
                    1.0 + (a * 0.5).fract() * 4.0,
                    i,
                )
            })
            .collect();
        let core = Core::<3>::build(&balls, Falloff::SEED.kernel(), 1e-5, None);
        for i in 0..500 {
            let a = i as f32;
            let p = [
                (a * 0.377).fract() * 60.0 - 5.0,
                (a * 0.291).fract() * 60.0 - 5.0,
                (a * 0.123).fract() * 60.0 - 5.0,
            ];
            let exact = core.value_exact(p);
            assert!((core.value(p) - exact).abs() <= core.value_error() + 1e-5 * exact.max(1.0));
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
    }

    #[test]
    fn non_finite_points_are_outside() {
        let core = Core::<2>::build(&scattered(10, 50.0), Falloff::SEED.kernel(), 1e-4, None);
        for p in [
            [f32::NAN, 0.0],
            [f32::INFINITY, 0.0],
            [0.0, f32::NEG_INFINITY],
        ] {
            assert_eq!(core.value(p), 0.0);
            assert_eq!(core.value_exact(p), 0.0);
            assert_eq!(core.value_and_gradient(p), (0.0, [0.0; 2]));
            assert!(core.shares(p, 4).is_empty());
        }
    }

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
                        assert!((s - v).abs() <= 1e-6 * v.max(1.0), "{falloff:?} at {p:?}");
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
                        assert!((b - v).abs() <= 1e-6 * v.max(1.0), "{at:?}: {b} vs {v}");
                        assert!((b - g).abs() <= 1e-6 * g.max(1.0), "{at:?}: {b} vs {g}");
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

    /// The 8 × 8 tile path's definition, over every ball in ball order: the terms
    /// `(scale · exp(−a dy²/R²)) · exp(−a dx²/R²)` of the balls with `(0 + dx²) + dy² < r_c²`,
    /// each factor from [`math::exp_nonpositive`], then saturated.
    fn tile_by_definition(
        core: &Core<2>,
        origin: [f32; 2],
        step: f32,
        size: [usize; 2],
    ) -> Vec<f32> {
        let (scale, sharpness) = core.separable.unwrap();
        let mut out = vec![0.0f32; size[0] * size[1]];
        for (n, sample) in out.iter_mut().enumerate() {
            let x = origin[0] + step * (n % size[0]) as f32;
            let y = origin[1] + step * (n / size[0]) as f32;
            let mut sum = 0.0f32;
            for ball in &core.balls {
                let (dx, dy) = (x - ball.center[0], y - ball.center[1]);
                let (dx2, dy2) = (dx * dx, dy * dy);
                if dx2 + dy2 < ball.cutoff_d2 {
                    let fx = math::exp_nonpositive(-sharpness * (dx2 * ball.inv_r2));
                    let fy = math::exp_nonpositive(-sharpness * (dy2 * ball.inv_r2));
                    sum += (scale * fy) * fx;
                }
            }
            *sample = saturate(sum);
        }
        out
    }

    /// `block_at_least` is never wrong: whenever it proves a level, every sample of the block
    /// (block sampler and point queries alike) reaches it, up to levels a hair under the
    /// smallest sample; and it does prove levels comfortably below the smallest sample.
    #[test]
    fn block_bounds_never_claim_too_much() {
        let (mut proven, mut proven_cached) = (0, 0);
        for (count, spread) in [(1, 10.0), (12, 60.0), (60, 200.0), (300, 400.0)] {
            let balls = scattered(count, spread);
            for falloff in [Falloff::SEED, Falloff::BLINN, Falloff::WYVILL] {
                let core = Core::<2>::build(&balls, falloff.kernel(), 1e-4, None);
                // Shared by the blocks of one field, as a `BlockSampler` keeps it.
                let mut cache = FactorCache::default();
                for i in 0..200 {
                    let a = i as f32;
                    let origin = [
                        ((a * 0.377).fract() - 0.5) * spread * 0.8,
                        ((a * 0.291).fract() - 0.5) * spread * 0.8,
                    ];
                    let step = [0.3, 1.0, 2.39][i % 3];
                    let size = [[8, 8], [5, 8], [8, 3], [1, 1]][i / 3 % 4];
                    let mut block = vec![0.0f32; size[0] * size[1]];
                    core.sample_block(origin, step, size[0], size[1], &mut block, None);
                    let mut min = block.iter().copied().fold(f32::INFINITY, f32::min);
                    for n in 0..block.len() {
                        let p = [
                            origin[0] + step * (n % size[0]) as f32,
                            origin[1] + step * (n / size[0]) as f32,
                        ];
                        min = min.min(core.value(p));
                    }
                    let above = f32::from_bits(min.to_bits() + 1);
                    for level in [0.5 * min, min * (1.0 - 1e-4), min, above] {
                        let at = (count, falloff, i, level, min);
                        if core.block_at_least(origin, step, size[0], size[1], level) {
                            assert!(min >= level, "{at:?}");
                        }
                        if size == [8, 8]
                            && core.block_at_least_cached(&mut cache, origin, step, level)
                        {
                            assert!(min >= level, "cached {at:?}");
                            proven_cached += usize::from(level == 0.5 * min && min > 0.0);
                        }
                    }
                    if min > 0.0 && core.block_at_least(origin, step, size[0], size[1], 0.5 * min) {
                        proven += 1;
                    }
                }
            }
        }
        assert!(proven > 500, "{proven}");
        assert!(proven_cached > 100, "{proven_cached}");
        // No samples: any level holds.
        let core = Core::<2>::build(&scattered(3, 10.0), Falloff::SEED.kernel(), 1e-4, None);
        assert!(core.block_at_least([0.0; 2], 1.0, 0, 8, 1e30));
    }

    /// A factor cache shared by many tiles (a walk over neighbouring tiles that revisits
    /// rows and columns, changes spacing mid-way, mixes in short blocks and every candidate
    /// path) gives the same bits as sampling each tile afresh, and actually hits.
    #[test]
    fn cached_factors_give_the_same_tiles_bit_for_bit() {
        let mut hits = 0;
        // One word of candidate bits per cell, three, and none (over 256 balls).
        for (count, spread) in [(12, 60.0), (60, 200.0), (150, 300.0), (300, 400.0)] {
            let balls = scattered(count, spread);
            for falloff in [Falloff::SEED, Falloff::BLINN, Falloff::WYVILL] {
                for cell_size in [None, Some(4.0), Some(1e3)] {
                    let core = Core::<2>::build(&balls, falloff.kernel(), 1e-4, cell_size);
                    let mut cache = FactorCache::default();
                    let mut state = 0x2545_f491_u32;
                    let (mut i, mut j) = (0i32, 0i32);
                    for n in 0..300 {
                        state ^= state << 13;
                        state ^= state >> 17;
                        state ^= state << 5;
                        // A random walk of tiles, like a contour's.
                        match state % 4 {
                            0 => i += 1,
                            1 => i -= 1,
                            2 => j += 1,
                            _ => j -= 1,
                        }
                        let step = if n < 150 { 2.39 } else { 0.7 };
                        let size = match state / 4 % 8 {
                            0 => [5, 8],
                            1 => [8, 3],
                            _ => [8, 8],
                        };
                        let origin = [8.0 * step * i as f32, 8.0 * step * j as f32];
                        let origin = [origin[0] - spread * 0.3, origin[1] - spread * 0.2];
                        let mut fresh = vec![f32::NAN; size[0] * size[1]];
                        let mut cached = fresh.clone();
                        core.sample_block(origin, step, size[0], size[1], &mut fresh, None);
                        let cache = Some(&mut cache);
                        core.sample_block(origin, step, size[0], size[1], &mut cached, cache);
                        for (k, (a, b)) in fresh.iter().zip(&cached).enumerate() {
                            let at = (count, falloff, cell_size, n, k);
                            assert_eq!(a.to_bits(), b.to_bits(), "{at:?}: {a} vs {b}");
                        }
                    }
                    if core.separable.is_some() {
                        assert!(cache.hits > 100, "{}", cache.hits);
                    }
                    hits += cache.hits;
                }
            }
        }
        assert!(hits > 10_000, "{hits}");
    }

    /// Every way a tile finds its candidate balls (one culling cell, the cells' bit sets for up
    /// to 256 balls, merged lists beyond, every ball for a tile over many cells), every class
    /// of ball (reaching no sample, every sample, some) and partial tiles: the same bits as the
    /// definition, so exactly the balls `value` sums reach each sample, in ball order.
    #[test]
    fn tiles_are_their_definition_bit_for_bit() {
        let mut checked = 0;
        for (count, spread) in [(12, 60.0), (60, 200.0), (150, 300.0), (300, 400.0)] {
            let balls = scattered(count, spread);
            for falloff in [
                Falloff::SEED,
                Falloff::BLINN,
                Falloff::Exponential { blobbiness: -3.0 },
            ] {
                for cell_size in [None, Some(4.0), Some(1e3)] {
                    let core = Core::<2>::build(&balls, falloff.kernel(), 1e-4, cell_size);
                    assert_eq!(core.words > 0, count <= 64 * BIT_WORDS);
                    for i in 0..40 {
                        let a = i as f32;
                        let origin = [
                            ((a * 0.377).fract() - 0.5) * spread * 1.2,
                            ((a * 0.291).fract() - 0.5) * spread * 1.2,
                        ];
                        let step = [0.3, 1.0, 2.39, 7.0, 40.0][i % 5];
                        let size = [[8, 8], [8, 8], [5, 8], [8, 3], [1, 1]][i / 5 % 5];
                        let mut block = vec![f32::NAN; size[0] * size[1]];
                        core.sample_block(origin, step, size[0], size[1], &mut block, None);
                        let expected = tile_by_definition(&core, origin, step, size);
                        for (n, (b, e)) in block.iter().zip(&expected).enumerate() {
                            let at = (count, falloff, cell_size, origin, step, size, n);
                            assert_eq!(b.to_bits(), e.to_bits(), "{at:?}: {b} vs {e}");
                            let p = [
                                origin[0] + step * (n % size[0]) as f32,
                                origin[1] + step * (n / size[0]) as f32,
                            ];
                            let v = core.value(p);
                            assert!((b - v).abs() <= 1e-6 * v.max(1.0), "{at:?}: {b} vs {v}");
                            assert_eq!(*b == 0.0, v == 0.0, "{at:?}");
                            checked += usize::from(v > 0.0);
                        }
                    }
                }
            }
        }
        assert!(checked > 10_000, "{checked}");
        // Tiles whose nearest sample sits just inside or outside a lone ball's cutoff, on
        // either side and corner-wise: the classification's edge cases.
        for falloff in [Falloff::SEED, Falloff::BLINN] {
            let core = Core::<2>::build(&[([3.0, -2.0], 2.5, 0)], falloff.kernel(), 1e-4, None);
            let rc = math::sqrt(core.balls[0].cutoff_d2);
            for i in 0..400 {
                let t = 1.0 + (i as f32 - 200.0) * 2e-7;
                let step = [0.5, 3.0][i % 2];
                let far = 7.0 * step;
                let (x, y, step) = match i % 5 {
                    0 => (3.0 + rc * t, -2.0, step),
                    1 => (3.0 - rc * t - far, -2.0 - far / 2.0, step),
                    2 => (3.0, -2.0 + rc * t, step),
                    3 => (3.0 + rc * t * 0.6, -2.0 + rc * t * 0.8, step),
                    // From the centre: only the far corner can be beyond the cutoff.
                    _ => (3.0, -2.0, rc * t / (7.0 * core::f32::consts::SQRT_2)),
                };
                let mut block = [f32::NAN; 64];
                core.sample_block([x, y], step, 8, 8, &mut block, None);
                let expected = tile_by_definition(&core, [x, y], step, [8, 8]);
                for (b, e) in block.iter().zip(&expected) {
                    assert_eq!(
                        b.to_bits(),
                        e.to_bits(),
                        "{falloff:?} at {x}, {y}: {b} vs {e}"
                    );
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

    #[test]
    fn cells_list_balls_in_ball_order() {
        let core = Core::<2>::build(&scattered(80, 200.0), Falloff::SEED.kernel(), 1e-4, None);
        for c in 0..core.cell_count() {
            let list = &core.entries[core.starts[c] as usize..core.starts[c + 1] as usize];
            assert!(list.windows(2).all(|w| w[0].index < w[1].index));
        }
    }

    /// The sharpest accepted falloff: a peak of `e^80 ≈ 5.5e34`.
    const STEEP: Falloff = Falloff::Exponential { blobbiness: -80.0 };

    /// Regression: an overflowing sum was turned into 0 (`finite_or_zero`), so with an extreme
    /// falloff and thousands of coincident balls a point deep inside read as outside.
    #[test]
    fn overflowing_sum_saturates_instead_of_reading_outside() {
        // 10,000 × 5.5e34 = 5.5e38 > f32::MAX.
        let balls = vec![([3.0f32, -2.0], 1.0f32, 7u32); 10_000];
        let core = Core::<2>::build(&balls, STEEP.kernel(), 1e-4, None);
        let centre = [3.0, -2.0];
        assert_eq!(core.value(centre), f32::MAX);
        assert_eq!(core.value_exact(centre), f32::MAX);
        let (v, g) = core.value_and_gradient(centre);
        assert_eq!(v, f32::MAX);
        assert_eq!(g, [0.0, 0.0]);
        let samples = core.sample_grid([2.0, -2.0], 0.5, 5, 1);
        assert_eq!(samples[2], f32::MAX);
        assert!(samples.iter().all(|s| s.is_finite()));
        // Just off the centre the gradient is too steep for f32: it saturates, pointing back.
        let off = [3.1, -2.0];
        let (v, g) = core.value_and_gradient(off);
        assert!(v > 1.0 && v.is_finite());
        assert_eq!(g[0], -f32::MAX);
        assert_eq!(g[1], 0.0);
        assert_eq!(core.value_and_gradient_exact(off), (v, g));
        // Shares and blends sum in f64, so they survive the overflow.
        let shares = core.shares(centre, 4);
        assert_eq!(shares.len(), 1);
        assert_eq!((shares[0].id, shares[0].weight), (7, 1.0));
        let ones = vec![2.5f32; balls.len()];
        let blended = core.blend(centre, &ones).unwrap().unwrap();
        assert!((blended - 2.5).abs() < 1e-3, "{blended}");
    }

    /// Regression: the gradient's per-ball scale `2 f'(q) / R²` was formed in `f32`, so one tiny
    /// steep ball overflowed it and `value_and_gradient` returned `(0, 0)`: outside, although
    /// `value` read 1e26.
    #[test]
    fn one_steep_tiny_ball_keeps_its_value_and_gradient() {
        let core = Core::<2>::build(&[([0.0, 0.0], 1e-6, 0)], STEEP.kernel(), 1e-4, None);
        let p = [5e-7, 0.0];
        let (v, g) = core.value_and_gradient(p);
        assert_eq!(v.to_bits(), core.value(p).to_bits());
        assert!(v > 1e25, "{v}");
        // d/dx exp(B x²/R² − B) = 2 B x / R² · f: about −160 · 5e-7 · 1e12 · 1.1e26.
        let expected = 2.0 * -80.0 * 5e-7 * 1e12 * f64::from(v);
        assert!(
            (f64::from(g[0]) - expected).abs() <= 1e-5 * expected.abs(),
            "{g:?} vs {expected}"
        );
        assert_eq!(g[1], 0.0);
    }

    #[test]
    fn blend_reports_non_finite_attributes_of_reaching_balls_only() {
        let balls = [([0.0f32, 0.0], 1.0f32, 0u32), ([100.0, 0.0], 1.0, 1)];
        let core = Core::<2>::build(&balls, Falloff::SEED.kernel(), 1e-4, None);
        assert_eq!(
            core.blend([0.0, 0.0], &[f32::NAN, 1.0]),
            Err(MetaballError::NonFinite {
                what: "attribute",
                index: 0
            })
        );
        // The far ball does not reach the origin: its attribute is not read.
        assert_eq!(core.blend([0.0, 0.0], &[4.0, f32::INFINITY]), Ok(Some(4.0)));
        // Nothing reaches here: nothing is read.
        assert_eq!(core.blend([50.0, 0.0], &[f32::NAN, f32::NAN]), Ok(None));
    }

    /// Finite attributes within rounding of `f32::MAX` can still overflow: a typed error, never
    /// an infinity.
    #[test]
    fn blend_of_huge_finite_attributes_overflows_to_an_error() {
        let balls = vec![([0.0f32, 0.0], 1.0f32, 0u32); 10];
        let core = Core::<2>::build(&balls, Falloff::SEED.kernel(), 1e-4, None);
        // Each weight is 0.1 rounded up in f32 (0.10000000149), and the ten terms, rounded as
        // they are added, pass f32::MAX.
        assert_eq!(
            core.blend([0.0, 0.0], &[f32::MAX; 10]),
            Err(MetaballError::BlendOverflow { blended: 10 })
        );
        let half = core
            .blend([0.0, 0.0], &[f32::MAX / 2.0; 10])
            .unwrap()
            .unwrap();
        assert!(half.is_finite());
    }
}
