//! The culled field's engine, shared by 2D and 3D: per-ball constants plus a uniform grid of
//! cells, each listing (by ball index) the balls whose cutoff box overlaps it.

use alloc::vec;
use alloc::vec::Vec;
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
    index: u32,
}

/// Per-ball constants and the grid.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Core<const D: usize> {
    kernel: Kernel,
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
    ) {
        out.fill(0.0);
        if cols == 0 || rows == 0 {
            return;
        }
        let mut inline = [0.0f32; 3 * BLOCK_INLINE_SIDE];
        let mut heap = Vec::new();
        let scratch: &mut [f32] = if cols <= BLOCK_INLINE_SIDE && rows <= BLOCK_INLINE_SIDE {
            &mut inline
        } else {
            heap.resize(2 * cols.max(rows) + rows, 0.0);
            &mut heap
        };
        let far = [
            origin[0] + step * (cols - 1) as f32,
            origin[1] + step * (rows - 1) as f32,
        ];
        let (x0, x1) = (self.clamp_axis(0, origin[0]), self.clamp_axis(0, far[0]));
        let (y0, y1) = (self.clamp_axis(1, origin[1]), self.clamp_axis(1, far[1]));
        let spanned = (x1 - x0 + 1) * (y1 - y0 + 1);
        let cell_entries = |c: usize| match (self.starts.get(c), self.starts.get(c + 1)) {
            (Some(&a), Some(&b)) => self.entries.get(a as usize..b as usize).unwrap_or(&[]),
            _ => &[],
        };
        let size = [cols, rows];
        let mut sample = |balls: &mut dyn Iterator<Item = &Entry<2>>, out: &mut [f32]| {
            if cols <= TILE && rows <= TILE {
                self.sample_tile(origin, step, size, balls, out);
            } else {
                self.sample_into::<true>(origin, step, size, balls, scratch, out);
            }
        };
        if spanned == 1 {
            // One cell: its list is already the balls in ball order, each once.
            let list = cell_entries(y0 * self.dims[0] + x0);
            sample(&mut list.iter(), out);
        } else if spanned <= MAX_BLOCK_CELLS {
            // The union of the cells' lists, in ball order, each ball once: a bit per ball.
            let mut seen: SmallVec<[u64; 8]> = SmallVec::new();
            seen.resize(self.balls.len().div_ceil(64), 0);
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
            let mut balls = seen.iter().enumerate().flat_map(|(w, &bits)| {
                let mut bits = bits;
                core::iter::from_fn(move || {
                    if bits == 0 {
                        return None;
                    }
                    let bit = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    Some(w * 64 + bit)
                })
                .filter_map(|i| self.balls.get(i))
            });
            sample(&mut balls, out);
        } else {
            sample(&mut self.balls.iter(), out);
        }
    }

    /// [`sample_into`](Core::sample_into) with `BATCH` for blocks of at most
    /// [`TILE`] × [`TILE`] samples, on fixed-size arrays so that every step runs
    /// [`TILE`] lanes wide: each ball's column and row exponents in one batch each, and each
    /// row's cutoff test and accumulation over all [`TILE`] columns (columns past `width` get
    /// an infinite distance, so they fail the test). Each sample gets the terms of exactly the
    /// balls whose `dx² + dy² < r_c²`, in ball order, as in `sample_into`.
    fn sample_tile(
        &self,
        origin: [f32; 2],
        step: f32,
        [width, height]: [usize; 2],
        balls: &mut dyn Iterator<Item = &Entry<2>>,
        out: &mut [f32],
    ) {
        let (scale, sharpness) = match self.kernel {
            Kernel::Exponential { b } => (math::exp(-b), -b),
            Kernel::Gauss {
                strength,
                sharpness,
            } => (strength, sharpness),
            Kernel::Wyvill { .. } => {
                let mut scratch = [0.0f32; 0];
                return self.sample_into::<true>(
                    origin,
                    step,
                    [width, height],
                    balls,
                    &mut scratch,
                    out,
                );
            }
        };
        if width == 0 || height == 0 {
            return;
        }
        let mut xs = [0.0f32; TILE];
        let mut ys = [0.0f32; TILE];
        for k in 0..TILE {
            xs[k] = origin[0] + step * k as f32;
            ys[k] = origin[1] + step * k as f32;
        }
        let far = [
            xs[(width - 1).min(TILE - 1)],
            ys[(height - 1).min(TILE - 1)],
        ];
        let mut acc = [[0.0f32; TILE]; TILE];
        for ball in balls {
            if !(ball.cutoff_d2 > 0.0) {
                continue;
            }
            let center = ball.center;
            // A ball whose padded cutoff disc misses the block's rectangle reaches none of its
            // samples (the padding dwarfs the rounding of these differences).
            let gap_x = (origin[0] - center[0]).max(center[0] - far[0]).max(0.0);
            let gap_y = (origin[1] - center[1]).max(center[1] - far[1]).max(0.0);
            let reach = pad(math::sqrt(ball.cutoff_d2));
            if !(gap_x * gap_x + gap_y * gap_y <= reach * reach) {
                continue;
            }
            let mut dx2 = [0.0f32; TILE];
            let mut dy2 = [0.0f32; TILE];
            // Column exponents, then row exponents.
            let mut factors = [0.0f32; 2 * TILE];
            for k in 0..TILE {
                let dx = xs[k] - center[0];
                let d = dx * dx;
                dx2[k] = if k < width { d } else { f32::INFINITY };
                factors[k] = -sharpness * (d * ball.inv_r2);
                let dy = ys[k] - center[1];
                let d = dy * dy;
                dy2[k] = d;
                factors[TILE + k] = -sharpness * (d * ball.inv_r2);
            }
            math::exp_nonpositive_lanes(&mut factors);
            let (fx, fy) = factors.split_at(TILE);
            for ((row, &dy2), &fy) in acc.iter_mut().zip(&dy2).zip(fy).take(height) {
                let row_factor = scale * fy;
                for ((sample, &dx2), &fx) in row.iter_mut().zip(&dx2).zip(fx) {
                    // Same expression as `distance2`: (0 + dx²) + dy²; +0 for the others
                    // keeps the bits (a sample starts at +0 and only grows).
                    let term = if dx2 + dy2 < ball.cutoff_d2 {
                        row_factor * fx
                    } else {
                        0.0
                    };
                    *sample += term;
                }
            }
        }
        for (samples, row) in out.chunks_exact_mut(width).zip(&acc).take(height) {
            for (sample, &a) in samples.iter_mut().zip(row) {
                *sample = saturate(a);
            }
        }
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
        let (scale, sharpness) = match self.kernel {
            Kernel::Exponential { b } => (math::exp(-b), -b),
            Kernel::Gauss {
                strength,
                sharpness,
            } => (strength, sharpness),
            Kernel::Wyvill { .. } => {
                for (n, sample) in out.iter_mut().enumerate().take(width * height) {
                    *sample = self.value([x_of(n % width), y_of(n / width)]);
                }
                return;
            }
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
            let reach = pad(math::sqrt(ball.cutoff_d2));
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

/// Blocks of at most `TILE × TILE` samples take the fixed-width path.
const TILE: usize = 8;

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
            compiled.push(Entry {
                center,
                inv_r2: 1.0 / r2,
                cutoff_d2: r2 * q_cut,
                index: u32::try_from(index).unwrap_or(u32::MAX),
            });
            ids.push(id);
            value_error += per_ball_value_error;
            gradient_error += kernel.gradient_error(epsilon, radius);
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
            balls: compiled,
            ids,
            origin: lo,
            cell: 1.0,
            inv_cell: 1.0,
            dims: [0; D],
            starts: vec![0],
            entries: Vec::new(),
            bounds: (lo, hi),
            value_error,
            gradient_error,
        };
        if cutoffs.is_empty() {
            // No ball reaches epsilon anywhere: the culled field is zero everywhere.
            return core;
        }
        cutoffs.sort_by(f32::total_cmp);
        let median = cutoffs[cutoffs.len() / 2];
        let padded: Vec<f32> = core
            .balls
            .iter()
            .map(|b| pad(math::sqrt(b.cutoff_d2)))
            .collect();
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
                            covered *= f64::from(math::floor(2.0 * r / cell)) + 2.0;
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
            for_each_cell(from, to, self.dims, |c| counts[c] += 1);
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
            index: 0,
        };
        let mut entries = vec![empty; running as usize];
        for (ball, range) in self.balls.iter().zip(&ranges) {
            if let Some((from, to)) = *range {
                for_each_cell(from, to, self.dims, |c| {
                    if let Some(slot) = cursor.get_mut(c) {
                        if let Some(entry) = entries.get_mut(*slot as usize) {
                            *entry = *ball;
                        }
                        *slot += 1;
                    }
                });
            }
        }
        self.starts = starts;
        self.entries = entries;
    }

    /// The cell coordinate of `x` along axis `k`, clamped into the grid.
    fn clamp_axis(&self, k: usize, x: f32) -> usize {
        // For t > 0 the truncating cast is `floor` (which is a library call on targets
        // without SSE4.1); t ≤ 0 and NaN give cell 0.
        let t = (x - self.origin[k]) * self.inv_cell;
        if !(t > 0.0) {
            0
        } else {
            (t as usize).min(self.dims[k].saturating_sub(1))
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
            cell += (t as usize).min(dim - 1) * stride;
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
        match self.kernel {
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
        gradient_sum(self.kernel, self.nearby(&p), &p, true)
    }

    /// The exact value and gradient over every ball.
    pub(crate) fn value_and_gradient_exact(&self, p: [f32; D]) -> (f32, [f32; D]) {
        if !p.iter().all(|x| x.is_finite()) {
            return (0.0, [0.0; D]);
        }
        gradient_sum(self.kernel, &self.balls, &p, false)
    }

    /// Calls `visit(ball index, contribution)` for every ball within its cutoff of `p` that
    /// contributes a positive amount, in ball order. Each contribution is finite: a valid
    /// kernel's value is at most its peak (`e^80` at worst).
    fn for_each_contribution(&self, p: &[f32; D], mut visit: impl FnMut(u32, f32)) {
        for e in self.nearby(p) {
            let d2 = distance2(p, &e.center);
            if d2 < e.cutoff_d2 {
                let f = self.kernel.value(d2 * e.inv_r2);
                if f > 0.0 && f.is_finite() {
                    visit(e.index, f);
                }
            }
        }
    }

    /// Per-id sums in `f64`: at most 2^32 terms of at most `e^80 ≈ 5.5e34` each, so they never
    /// overflow even where the `f32` value saturates.
    pub(crate) fn shares(&self, p: [f32; D], k: usize) -> Shares {
        let mut per_id: SmallVec<[(u32, f64); 16]> = SmallVec::new();
        if k == 0 {
            return Shares::new();
        }
        self.for_each_contribution(&p, |index, f| {
            let id = self.ids.get(index as usize).copied().unwrap_or(0);
            if let Some(s) = per_id.iter_mut().find(|s| s.0 == id) {
                s.1 += f64::from(f);
            } else {
                per_id.push((id, f64::from(f)));
            }
        });
        per_id.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        per_id.truncate(k);
        let total: f64 = per_id.iter().map(|s| s.1).sum();
        if !(total > 0.0 && total.is_finite()) {
            return Shares::new();
        }
        per_id
            .into_iter()
            .map(|(id, weight)| Share {
                id,
                // In (0, 1]: the cast cannot overflow.
                weight: (weight / total) as f32,
            })
            .collect()
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

/// The value (an `f32` sum in ball order, the same bits as [`culled_sum`] / the exact sum) and
/// the gradient, whose terms `2 f'(q) (p − c) / R²` are formed and summed in `f64`: one tiny
/// steep ball can exceed `f32` on its own (`e^80 · 160 / R` for `R = 1e-6`), and terms of both
/// signs could then meet as `∞ − ∞`. Each component saturates to `±f32::MAX`.
fn gradient_sum<const D: usize>(
    kernel: Kernel,
    entries: &[Entry<D>],
    p: &[f32; D],
    culled: bool,
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
        let (f, slope2) = kernel.value_and_slope(d2 * e.inv_r2);
        value += f;
        if slope2 != 0.0 {
            let scale = f64::from(slope2) * f64::from(e.inv_r2);
            for k in 0..D {
                gradient[k] += scale * f64::from(delta[k]);
            }
        }
    }
    (saturate(value), gradient.map(saturate_f64))
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
        let kernel = Falloff::SEED.kernel();
        let core = Core::<2>::build(&balls, kernel, 1e-4, None);
        for i in 0..2000 {
            let a = i as f32;
            let p = [
                ((a * 0.377).fract() - 0.5) * 400.0,
                ((a * 0.291).fract() - 0.5) * 400.0,
            ];
            // Brute force over the balls within their cutoff, in ball order.
            let mut expected = 0.0;
            for ball in &core.balls {
                let d2 = distance2(&p, &ball.center);
                if d2 < ball.cutoff_d2 {
                    expected += kernel.value(d2 * ball.inv_r2);
                }
            }
            assert_eq!(core.value(p).to_bits(), expected.to_bits(), "at {p:?}");
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
                    core.sample_block(origin, step, cols, rows, &mut block);
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
