//! The fixed-width path for blocks of at most 8 × 8 samples: four lanes at a time, each
//! reaching ball classed as covering every sample or some, its factors from a batched `exp`.

use glam::Vec4;

use super::factor_cache::FactorCache;
use super::{Core, Entry};
use crate::math;

impl Core<2> {
    /// [`sample_tile_cached`](Core::sample_tile_cached) with a cache, else
    /// [`sample_tile`](Core::sample_tile).
    pub(super) fn sample_tile_either<'a>(
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
    pub(super) fn sample_tile_cached<'a>(
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
    pub(super) fn sample_tile<'a>(
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
                // `len < TILE_BATCH`: the batch is sent off once full.
                let (batched, slot) = (&mut batch[len], &mut waiting[len]);
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
            let batch = &mut batch[..len];
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
}

/// Blocks of at most `TILE × TILE` samples take the fixed-width path.
pub(super) const TILE: usize = 8;

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
pub(super) struct TileLanes {
    xs: [Vec4; 2],
    ys: [Vec4; 2],
    /// The first column's x and row's y.
    pub(super) first: [f32; 2],
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
    pub(super) fn reach(&self, ball: &Entry<2>) -> Option<([Vec4; 2], [Vec4; 2], bool)> {
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
    pub(super) fn new(origin: [f32; 2], step: f32, width: usize, height: usize) -> Self {
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
pub(super) fn exponents(out: &mut [f32], d2: [Vec4; 2], minus_sharpness: Vec4, inv_r2: f32) {
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

/// [`saturate`] on four lanes.
#[inline(always)]
fn saturate4(x: Vec4) -> Vec4 {
    // `min` gives the bound for a NaN lane, which the select then zeroes.
    Vec4::select(x.cmpeq(x), x.min(Vec4::splat(f32::MAX)), Vec4::ZERO)
}

#[cfg(test)]
mod tests {
    use alloc::vec;
    use alloc::vec::Vec;

    use super::super::candidates::BIT_WORDS;
    use super::super::saturate;
    use super::super::test_support::*;
    use super::*;
    use crate::Falloff;

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
                            assert!(
                                (b - v).abs() <= core.sample_error() * v,
                                "{at:?}: {b} vs {v}"
                            );
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
}
