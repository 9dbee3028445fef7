//! Point queries: the culled value, gradient, shares and blend at one point, and the exact
//! all-balls sums.

use smallvec::SmallVec;

use super::{Core, Entry, distance2, saturate};
use crate::falloff::Kernel;
use crate::math;
use crate::{Attribute, MetaballError, Share, Shares};

impl<const D: usize> Core<D> {
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
        let id = self.ids[index as usize];
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
        debug_assert_eq!(attributes.len(), self.balls.len());
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
            let a = attributes[index as usize];
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

/// One ball's contribution `scale · exp(−a q)` at a point within its cutoff, for a field
/// whose kernel is [`separable`]: `exp` from [`math::exp_nonpositive`] (within `1.5e-7` of
/// the true `exp`, the same bits on every platform), whose argument, at least `−a q_c`, stays
/// above its floor. What the culled point queries (`value`, `value_and_gradient`, `shares`,
/// `blend`) sum, through [`split_terms`]; the exact ones use the platform's `exp`.
#[cfg(test)]
fn split_value(scale: f32, a: f32, q: f32) -> f32 {
    scale * math::exp_nonpositive(-a * q)
}

/// An `f64` gradient component as `f32`, saturated to `±f32::MAX`.
#[inline]
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
            // `n ≤ lane < POINT_BATCH`.
            kept[n] = lane as u8;
            f[n] = -a * (d2 * e.inv_r2);
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
            visit(&block[usize::from(lane)], f);
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

/// Per-id contribution sums at a point (inline for the usual few ids).
type PerId = SmallVec<[(u32, f64); 16]>;

/// The `k` largest per-id sums (`k > 0`), largest first, renormalised to sum to 1; empty where
/// they sum to 0.
#[inline]
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
    use alloc::vec;
    use alloc::vec::Vec;

    use super::super::test_support::*;
    use super::*;
    use crate::Falloff;

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
