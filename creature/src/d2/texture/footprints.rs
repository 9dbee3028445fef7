//! Each ball's footprint on the image: the texels within its cutoff circle as runs per row,
//! the seed falloff split into column and row factors, and the texels holding the balls'
//! centres (with the least coverage each keeps).

use alloc::vec::Vec;
use core::ops::Range;

use glam::Vec2;

use creature_metaball::{DEFAULT_EPSILON, Falloff, SEED_BLOBBINESS};

use super::noise;
use crate::d2::Ball;
use crate::math;

/// The least coverage of a texel holding a ball's centre: one step of alpha.
const MIN_COVERAGE: f32 = 1.0 / 255.0;

/// The texel holding a ball's centre, and a lower bound on its coverage.
///
/// Each ball alone reaches the iso-level out to its radius `R` (the seed falloff is 1 there),
/// so its disk is inside the creature. The disk's centre lies in the texel, which therefore
/// holds at least a quarter disk of radius `min(R, tx/2, ty/2)`: that area over the texel's
/// is its least coverage (and at least [`MIN_COVERAGE`]). The first-order coverage already
/// exceeds it unless the ball is thin next to a texel; then it is what keeps a part thinner
/// than a texel, lying between texel centres, from vanishing from the texture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Centre {
    pub(super) row: usize,
    pub(super) column: usize,
    pub(super) least: f32,
}

/// One ball's footprint on the image: the texels within its cutoff circle, the seed falloff
/// split into x and y factors, `f = e^(−B) · exp(B dx² / R²) · exp(B dy² / R²)`.
pub(super) struct Footprint {
    /// The first row of the footprint, and where its runs start in [`Footprints::runs`] (one
    /// per row).
    pub(super) first_row: usize,
    pub(super) runs: Range<usize>,
    pub(super) colour: [f32; 3],
    pub(super) wood: f32,
}

/// One row of a footprint: the texels whose centres lie within the cutoff circle (the culled
/// field's support), from image column `column`, their column factors from `factors` in
/// [`Footprints::fx`], and the row factors `fy` and `2k dy fy`.
#[derive(Clone, Copy)]
pub(super) struct Run {
    pub(super) column: usize,
    pub(super) factors: usize,
    pub(super) len: usize,
    pub(super) fy: f32,
    pub(super) fy_dy: f32,
}

/// Every ball's footprint, and their column factors: per column of a footprint, the x factor
/// `fx` at the texel's centre and `2k dx fx`, so each texel adds f = fx·fy,
/// ∂f/∂x = (2k dx fx)·fy, ∂f/∂y = fx·(2k dy fy), and f times the colour and wood weight;
/// and the texels holding the balls' centres, by row.
pub(super) struct Footprints {
    pub(super) balls: Vec<Footprint>,
    pub(super) runs: Vec<Run>,
    pub(super) fx: Vec<f32>,
    pub(super) fx_dx: Vec<f32>,
    pub(super) centres: Vec<Centre>,
    pub(super) n: usize,
}

impl Footprints {
    // Out of line (like `splat`, `Planes::clear` and `Finisher::rows`) so that profiles name
    // the stages; each runs once per render or band.
    #[inline(never)]
    pub(super) fn new(balls: &[Ball], (min, max): (Vec2, Vec2), texel: Vec2, n: usize) -> Self {
        // Room for every footprint's columns and rows at once (at most the box of the cutoff
        // circle each), so the tables do not grow step by step.
        let (columns, rows) = balls.iter().fold((0, 0), |(columns, rows), b| {
            let diameter = 2.0 * Falloff::SEED.cutoff_radius(b.ball.radius, DEFAULT_EPSILON);
            let span = |texel: f32| math::ceil_non_negative(diameter / texel).saturating_add(2);
            (columns + span(texel.x).min(n), rows + span(texel.y).min(n))
        });
        let mut out = Self {
            balls: Vec::with_capacity(balls.len()),
            runs: Vec::with_capacity(rows),
            fx: Vec::with_capacity(columns),
            fx_dx: Vec::with_capacity(columns),
            centres: Vec::with_capacity(balls.len()),
            n,
        };
        let peak = math::exp(-SEED_BLOBBINESS);
        let inverse = texel.recip();
        let n_f = n as f32;
        let mut scratch = RowScratch::default();
        let quarter_disk = core::f32::consts::FRAC_PI_4 / (texel.x * texel.y);
        let half = texel.min_element() * 0.5;
        for b in balls {
            let centre = b.ball.center;
            let (column, row) = (
                noise::floor_i((centre.x - min.x) / texel.x),
                noise::floor_i((max.y - centre.y) / texel.y),
            );
            if let (Ok(column @ 0..), Ok(row @ 0..)) =
                (usize::try_from(column), usize::try_from(row))
                && column < n
                && row < n
            {
                let r = b.ball.radius.min(half);
                out.centres.push(Centre {
                    row,
                    column,
                    least: (r * r * quarter_disk).max(MIN_COVERAGE),
                });
            }
            let k = SEED_BLOBBINESS / (b.ball.radius * b.ball.radius);
            let cutoff = Falloff::SEED.cutoff_radius(b.ball.radius, DEFAULT_EPSILON);
            let Some(columns) = pixel_range(
                centre.x - cutoff - min.x,
                centre.x + cutoff - min.x,
                texel.x,
                n,
            ) else {
                continue;
            };
            let Some(rows) = pixel_range(
                max.y - centre.y - cutoff,
                max.y - centre.y + cutoff,
                texel.y,
                n,
            ) else {
                continue;
            };
            // Column and row factors, each in a loop of its own (they vectorise).
            let offset = out.fx.len();
            let x = move |c: i32| min.x + (c as f32 + 0.5) * texel.x - centre.x;
            // Exclusive ranges: inclusive ones do not vectorise.
            let (c0, c1) = (columns.0 as i32, columns.1 as i32);
            out.fx
                .extend((c0..c1 + 1).map(move |c| math::exp_poly(k * x(c) * x(c))));
            let fx = &out.fx[offset..];
            out.fx_dx.extend(
                (c0..c1 + 1)
                    .zip(fx)
                    .map(move |(c, &fx)| fx * x(c) * 2.0 * k),
            );
            let y = move |r: i32| max.y - (r as f32 + 0.5) * texel.y - centre.y;
            let (r0, r1) = (rows.0 as i32, rows.1 as i32);
            let cutoff2 = cutoff * cutoff;
            // The columns whose centres are within the cutoff circle on each row, as floats
            // (from `first` to `last`, none if `first > last`), intersected with `columns`.
            let (c0f, c1f) = (c0 as f32, c1 as f32);
            let half = move |y: f32| math::sqrt(math::max(cutoff2 - y * y, 0.0));
            // Clamped next to the image first, where `ceil_f` and `floor_f` are exact.
            let column =
                move |x: f32| math::min(math::max((x - min.x) * inverse.x - 0.5, -1.0), n_f);
            scratch.first.clear();
            scratch.first.extend((r0..r1 + 1).map(move |r| {
                let first = math::ceil_f(column(centre.x - half(y(r))));
                if y(r) * y(r) <= cutoff2 {
                    math::max(first, c0f)
                } else {
                    f32::MAX
                }
            }));
            scratch.last.clear();
            scratch.last.extend(
                (r0..r1 + 1)
                    .map(move |r| math::min(math::floor_f(column(centre.x + half(y(r)))), c1f)),
            );
            scratch.fy.clear();
            scratch
                .fy
                .extend((r0..r1 + 1).map(move |r| peak * math::exp_poly(k * y(r) * y(r))));
            let first_run = out.runs.len();
            let rows_f = scratch.first.iter().zip(&scratch.last);
            for ((r, (&first, &last)), &fy) in (r0..r1 + 1).zip(rows_f).zip(&scratch.fy) {
                out.runs.push(if first <= last {
                    // Whole numbers from c0 to c1.
                    let (a, z) = (first as usize, last as usize);
                    Run {
                        column: a,
                        factors: offset + a - columns.0,
                        len: z + 1 - a,
                        fy,
                        fy_dy: fy * y(r) * 2.0 * k,
                    }
                } else {
                    Run {
                        column: 0,
                        factors: 0,
                        len: 0,
                        fy: 0.0,
                        fy_dy: 0.0,
                    }
                });
            }
            out.balls.push(Footprint {
                first_row: rows.0,
                runs: first_run..out.runs.len(),
                colour: b.colour.to_array(),
                wood: b.texture_weights.x,
            });
        }
        // Centres in one texel are kept in any order (their coverages combine by `max`).
        crate::sort::sort_by(&mut out.centres, &mut |a, b| {
            (a.row, a.column).cmp(&(b.row, b.column))
        });
        out
    }
}

/// Per row of a footprint, before they become [`Run`]s: the first and last column and the row
/// factor (reused from ball to ball).
#[derive(Default)]
struct RowScratch {
    first: Vec<f32>,
    last: Vec<f32>,
    fy: Vec<f32>,
}

/// The pixels whose centres `(i + 0.5) · texel` lie in `[lo, hi]`, clamped to the image.
fn pixel_range(lo: f32, hi: f32, texel: f32, n: usize) -> Option<(usize, usize)> {
    let top = n as f32 - 1.0;
    let a = (lo / texel - 0.5).clamp(-1.0, n as f32);
    let b = (hi / texel - 0.5).clamp(-1.0, n as f32);
    if !(b >= 0.0 && a <= top) {
        return None;
    }
    let first = (-noise::floor_i(-a)).max(0) as usize;
    let last = (noise::floor_i(b).max(0) as usize).min(n - 1);
    (first <= last).then_some((first, last))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_range_clamps_and_rejects() {
        assert_eq!(pixel_range(-5.0, 5.0, 1.0, 10), Some((0, 4)));
        assert_eq!(pixel_range(2.4, 3.6, 1.0, 10), Some((2, 3)));
        assert_eq!(pixel_range(20.0, 30.0, 1.0, 10), None);
        assert_eq!(pixel_range(-30.0, -20.0, 1.0, 10), None);
        assert_eq!(pixel_range(5.0, 100.0, 1.0, 10), Some((5, 9)));
    }
}
