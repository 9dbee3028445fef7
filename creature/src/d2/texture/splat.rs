//! The accumulation pass: a band of rows as seven planes of sums (field, gradient, colour and
//! wood weight), each ball's runs on the band's rows added in, and the planes cleared where
//! they were.

use alloc::vec;
use alloc::vec::Vec;
use core::ops::Range;

use super::footprints::Footprints;

impl Footprints {
    /// Adds every ball's contribution to the image rows `rows` (plane row 0 is `rows.start`)
    /// and widens the rows' spans to the columns it reaches (and to the texels holding the
    /// balls' centres).
    #[inline(never)]
    pub(super) fn splat(&self, planes: &mut Planes, rows: Range<usize>) {
        let n = self.n;
        for centre in self.centres.iter().filter(|c| rows.contains(&c.row)) {
            let span = &mut planes.spans[centre.row - rows.start];
            span.0 = span.0.min(centre.column);
            span.1 = span.1.max(centre.column + 1);
        }
        for ball in &self.balls {
            let runs = &self.runs[ball.runs.clone()];
            // The ball's runs on these rows.
            let skip = rows.start.saturating_sub(ball.first_row);
            let first = ball.first_row.max(rows.start);
            let [cr, cg, cb] = ball.colour;
            for (local, run) in (first - rows.start..rows.len()).zip(runs.iter().skip(skip)) {
                if run.len == 0 {
                    continue;
                }
                let factors = run.factors..run.factors + run.len;
                let (fx, fx_dx) = (&self.fx[factors.clone()], &self.fx_dx[factors]);
                let span = &mut planes.spans[local];
                span.0 = span.0.min(run.column);
                span.1 = span.1.max(run.column + run.len);
                let fy = run.fy;
                // Seven contiguous runs in one loop, `plane += column factor × row factor`:
                // vector multiply-adds.
                let start = local * n + run.column;
                let span = start..start + run.len;
                let p = &mut *planes;
                accumulate(
                    [
                        &mut p.sum[span.clone()],
                        &mut p.gx[span.clone()],
                        &mut p.gy[span.clone()],
                        &mut p.r[span.clone()],
                        &mut p.g[span.clone()],
                        &mut p.b[span.clone()],
                        &mut p.wood[span],
                    ],
                    (fx, fx_dx),
                    [fy, fy, run.fy_dy, fy * cr, fy * cg, fy * cb, fy * ball.wood],
                );
            }
        }
    }
}

/// `plane += column factor × row factor` for seven planes at once (field, gradient x and y,
/// colour r, g, b and wood weight; the gradient x's column factors are `fx_dx`, the others'
/// `fx`): one pass of vector multiply-adds.
#[inline]
fn accumulate(planes: [&mut [f32]; 7], (fx, fx_dx): (&[f32], &[f32]), factors: [f32; 7]) {
    let [sum, gx, gy, r, g, b, wood] = planes;
    sum_7(sum, gx, gy, r, g, b, wood, fx, fx_dx, factors);
}

/// [`accumulate`]'s loop: the planes as separate parameters, so the compiler knows they do
/// not overlap (no run-time overlap checks before each run).
#[allow(clippy::too_many_arguments)]
#[inline(never)] // inlined, the compiler loses that the planes do not overlap
fn sum_7(
    sum: &mut [f32],
    gx: &mut [f32],
    gy: &mut [f32],
    r: &mut [f32],
    g: &mut [f32],
    b: &mut [f32],
    wood: &mut [f32],
    fx: &[f32],
    fx_dx: &[f32],
    [f_sum, f_gx, f_gy, f_r, f_g, f_b, f_wood]: [f32; 7],
) {
    let texels = sum
        .iter_mut()
        .zip(gx.iter_mut().zip(gy.iter_mut()))
        .zip(r.iter_mut().zip(g.iter_mut()))
        .zip(b.iter_mut().zip(wood.iter_mut()))
        .zip(fx.iter().zip(fx_dx));
    for ((((sum, (gx, gy)), (r, g)), (b, wood)), (&fx, &fx_dx)) in texels {
        *sum += fx * f_sum;
        *gx += fx_dx * f_gx;
        *gy += fx * f_gy;
        *r += fx * f_r;
        *g += fx * f_g;
        *b += fx * f_b;
        *wood += fx * f_wood;
    }
}

/// Per-texel sums of a band of rows, one plane each (so rows are contiguous runs the compiler
/// vectorises): field, gradient x and y, colour r, g, b (field-weighted) and wood weight
/// (field-weighted); and per row the columns some ball reaches. Outside a row's span every
/// sum is 0.
pub(super) struct Planes {
    pub(super) n: usize,
    pub(super) sum: Vec<f32>,
    pub(super) gx: Vec<f32>,
    pub(super) gy: Vec<f32>,
    pub(super) r: Vec<f32>,
    pub(super) g: Vec<f32>,
    pub(super) b: Vec<f32>,
    pub(super) wood: Vec<f32>,
    /// Per row: the columns `start..end` some ball reaches (`start ≥ end`: none).
    pub(super) spans: Vec<(usize, usize)>,
}

impl Planes {
    pub(super) fn new(rows: usize, n: usize) -> Self {
        let len = rows * n;
        // Planes of different lengths (by 80 bytes each), so that the same texel of two planes
        // is unlikely to sit at the same address modulo 4 KiB, which would make the
        // processor treat a load from one as depending on a store to the other.
        let plane = |k: usize| vec![0.0; len + 20 * k];
        Self {
            n,
            sum: plane(0),
            gx: plane(1),
            gy: plane(2),
            r: plane(3),
            g: plane(4),
            b: plane(5),
            wood: plane(6),
            spans: vec![(n, 0); rows],
        }
    }

    /// Zeroes the rows' spans (all that was summed into) and empties the spans.
    #[inline(never)]
    pub(super) fn clear(&mut self) {
        let n = self.n;
        for (row, span) in self.spans.iter_mut().enumerate() {
            if span.0 < span.1 {
                let texels = row * n + span.0..row * n + span.1;
                for plane in [
                    &mut self.sum,
                    &mut self.gx,
                    &mut self.gy,
                    &mut self.r,
                    &mut self.g,
                    &mut self.b,
                    &mut self.wood,
                ] {
                    plane[texels.clone()].fill(0.0);
                }
            }
            *span = (n, 0);
        }
    }
}
