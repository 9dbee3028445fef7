//! The culled field's engine, shared by 2D and 3D: per-ball constants plus a uniform grid of
//! cells, each listing (by ball index) the balls whose cutoff box overlaps it.
//!
//! - [`index`]: building the grid, finding a point's cell.
//! - [`point`]: point queries (value, gradient, shares, blend) and the exact sums.
//! - [`sample`]: whole grids and blocks of samples, row and column factors per ball.
//! - [`candidates`]: a block's candidate balls, from per-cell bit sets.
//! - [`tile`]: the fixed-width path for blocks of at most 8 × 8 samples.
//! - [`factor_cache`]: row and column factors kept between tiles (`BlockSampler`).
//! - [`proof`]: proving a whole block at least a level without sampling it.
//!
//! The sampling paths are hot (a contour tracer's tiles): a small non-generic helper called
//! from another of these modules needs `#[inline]`, or it cannot inline across codegen units.

use alloc::vec::Vec;

use crate::falloff::Kernel;

mod candidates;
mod factor_cache;
mod index;
mod point;
mod proof;
mod sample;
mod tile;

pub(crate) use factor_cache::FactorCache;

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
    /// The relative bound of the split samplers against [`Core::value`]
    /// ([`sample_error_bound`]); 0 when they sample `value` itself.
    sample_error: f32,
    /// `L = a q_c`, the largest exponent of a reaching ball's term, for a [`separable`]
    /// kernel; 0 for the others. The rounding of a term's exponent, which the block proofs'
    /// slack must cover, grows with it.
    cutoff_exponent: f32,
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

/// The relative bound `(7 L + 2 n + 11) · 2⁻²⁴` of a split sample (`sample_grid`,
/// `sample_block`) against [`Core::value`] at the same point, for a separable kernel
/// `scale · exp(−a q)` whose exponent at the cutoff is `L = a q_c` (at most 80, see
/// [`separable`]; `L = ln(scale / epsilon)`) and at most `n` balls reaching a point (the most
/// any culling cell lists). With `u = 2⁻²⁴` and `X = a (dx² + dy²)/R² ≤ L` a term's exponent
/// (`dx`, `dy`, `1/R²` and `a` are the same floats in both):
///
/// - `value` rounds `dx²`, `dy²`, their sum, the product with `1/R²` and with `a`: its exponent
///   is `X (1 + θ)`, `|θ| ≤ 4u`; the sampler rounds `dx²`, `· 1/R²` and `· a` per axis: its
///   two exponents sum to `X (1 + θ')`, `|θ'| ≤ 3u`. The terms' ratio is `e^{X (θ − θ')}`, within
///   `7uX` of 1;
/// - `value` takes one `exp` and one product with the scale, the sampler two `exp`s and two
///   products: each `exp` is within `1.5e-7 ≤ 2.52u` (the crate's, and the platform's within
///   an ulp), each product within `u`, together `3 · 2.52u + 3u ≤ 10.6u`;
/// - both add the same terms in the same order from +0: `n − 1` roundings each, `2(n − 1)u`
///   of the sum between them.
///
/// Together `(7X + 2n + 8.6) u` to first order; the second-order terms (`X ≤ 80`, so the
/// relative errors are below `1e-4`) are under `0.1u`, and the `+ 11` covers them. The worst
/// case a proptest found (`tests/properties.rs`) is reported beside it.
fn sample_error_bound(exponent_at_cutoff: f32, most_balls: u32) -> f32 {
    let l = f64::from(exponent_at_cutoff.max(0.0));
    let bound = (7.0 * l + 2.0 * f64::from(most_balls) + 11.0) / f64::from(1u32 << 24);
    bound as f32
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
#[inline]
fn saturate(x: f32) -> f32 {
    if x.is_nan() { 0.0 } else { x.min(f32::MAX) }
}

#[cfg(test)]
mod test_support {
    use alloc::vec::Vec;

    use crate::Falloff;

    pub(super) fn scattered(count: usize, spread: f32) -> Vec<([f32; 2], f32, u32)> {
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

    /// The sharpest accepted falloff: a peak of `e^80 ≈ 5.5e34`.
    pub(super) const STEEP: Falloff = Falloff::Exponential { blobbiness: -80.0 };
}
