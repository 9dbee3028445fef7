//! Bernstein basis polynomials with precomputed binomial coefficients.

use crate::MAX_DIVISIONS;

/// Basis values for one axis: `B_i^n(x)` for `i = 0..=n`.
pub(crate) type Basis = [f32; MAX_DIVISIONS + 1];

/// Binomial coefficients `C(n, i)` for one degree `n`, exact in `f32` for `n <= MAX_DIVISIONS`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Binomials {
    degree: usize,
    coefficients: Basis,
    /// `C(n - 1, i)`, for derivatives.
    lower: Basis,
}

impl Binomials {
    /// Coefficients of degree `degree` (1 to `MAX_DIVISIONS`).
    pub(crate) fn new(degree: usize) -> Self {
        debug_assert!((1..=MAX_DIVISIONS).contains(&degree));
        Self {
            degree,
            coefficients: row(degree),
            lower: row(degree - 1),
        }
    }

    /// Fills `out[0..=n]` with `B_i^n(x)` (as much of it as `out` holds). Valid for any finite
    /// `x` (extrapolation outside `[0, 1]`).
    #[inline]
    pub(crate) fn eval(&self, x: f32, out: &mut [f32]) {
        eval_row(&self.coefficients, self.degree, x, out);
    }

    /// Fills `out[0..=n]` with `d/dx B_i^n(x) = n (B_{i-1}^{n-1}(x) - B_i^{n-1}(x))`.
    #[inline]
    pub(crate) fn eval_derivative(&self, x: f32, out: &mut Basis) {
        let n = self.degree;
        let mut lower = [0.0; MAX_DIVISIONS + 1];
        eval_row(&self.lower, n - 1, x, &mut lower);
        let scale = n as f32;
        for i in 0..=n {
            let left = if i > 0 { lower[i - 1] } else { 0.0 };
            let right = if i < n { lower[i] } else { 0.0 };
            out[i] = scale * (left - right);
        }
    }
}

/// Row `n` of Pascal's triangle, as `f32`. The recurrence is exact in `f64` for
/// `n <= MAX_DIVISIONS` (every intermediate is below 2^53); entries above 2^24 are then
/// correctly rounded to `f32`.
fn row(n: usize) -> Basis {
    let mut out = [0.0f64; MAX_DIVISIONS + 1];
    out[0] = 1.0;
    for i in 1..=n {
        // C(n, i) = C(n, i - 1) * (n - i + 1) / i, exact in f64 for n <= MAX_DIVISIONS.
        out[i] = out[i - 1] * (n - i + 1) as f64 / i as f64;
    }
    let mut result = [0.0f32; MAX_DIVISIONS + 1];
    for (r, o) in result.iter_mut().zip(out) {
        *r = o as f32;
    }
    result
}

#[inline]
fn eval_row(coefficients: &Basis, n: usize, x: f32, out: &mut [f32]) {
    let y = 1.0 - x;
    let len = (n + 1).min(out.len());
    let out = &mut out[..len];
    let coefficients = &coefficients[..len];
    // out[i] <- C(n, i) x^i, then times y^(n - i) walking down.
    let mut power = 1.0;
    for (slot, c) in out.iter_mut().zip(coefficients) {
        *slot = *c * power;
        power *= x;
    }
    let mut power = 1.0;
    for slot in out.iter_mut().rev() {
        *slot *= power;
        power *= y;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pascal_rows_are_exact() {
        let r = row(10);
        assert_eq!(
            &r[..11],
            &[
                1.0, 10.0, 45.0, 120.0, 210.0, 252.0, 210.0, 120.0, 45.0, 10.0, 1.0
            ]
        );
        assert_eq!(row(0)[0], 1.0);
    }

    #[test]
    fn basis_is_a_partition_of_unity() {
        for n in 1..=12 {
            let b = Binomials::new(n);
            for step in 0..=20 {
                let x = step as f32 / 20.0;
                let mut out = [0.0; MAX_DIVISIONS + 1];
                b.eval(x, &mut out);
                let sum: f32 = out[..=n].iter().sum();
                assert!((sum - 1.0).abs() < 1e-5, "n {n} x {x} sum {sum}");
                assert!(out[..=n].iter().all(|&v| v >= 0.0));
            }
        }
    }

    #[test]
    fn endpoints_interpolate() {
        let b = Binomials::new(4);
        let mut out = [0.0; MAX_DIVISIONS + 1];
        b.eval(0.0, &mut out);
        assert_eq!(&out[..5], &[1.0, 0.0, 0.0, 0.0, 0.0]);
        b.eval(1.0, &mut out);
        assert_eq!(&out[..5], &[0.0, 0.0, 0.0, 0.0, 1.0]);
    }

    #[test]
    fn derivative_matches_central_difference() {
        for n in 1..=10 {
            let b = Binomials::new(n);
            let (x, h) = (0.37f32, 1e-3f32);
            let mut lo = [0.0; MAX_DIVISIONS + 1];
            let mut hi = [0.0; MAX_DIVISIONS + 1];
            let mut d = [0.0; MAX_DIVISIONS + 1];
            b.eval(x - h, &mut lo);
            b.eval(x + h, &mut hi);
            b.eval_derivative(x, &mut d);
            for i in 0..=n {
                let numeric = (hi[i] - lo[i]) / (2.0 * h);
                assert!(
                    (numeric - d[i]).abs() < 2e-2,
                    "n {n} i {i}: {numeric} vs {}",
                    d[i]
                );
            }
        }
    }

    #[test]
    fn derivatives_sum_to_zero() {
        let b = Binomials::new(10);
        let mut d = [0.0; MAX_DIVISIONS + 1];
        b.eval_derivative(0.8, &mut d);
        let sum: f32 = d[..=10].iter().sum();
        assert!(sum.abs() < 1e-4, "{sum}");
    }
}
