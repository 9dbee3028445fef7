//! Scalar float helpers with a `std` backend and a `libm` backend (libm wins when both are on:
//! its results are the same on every platform),
//! so call sites never branch. Vector math goes through glam, which picks its backend the same
//! way.

#[cfg(all(feature = "std", not(feature = "libm")))]
mod backend {
    #[inline]
    pub(crate) fn exp(x: f32) -> f32 {
        x.exp()
    }
    #[inline]
    pub(crate) fn ln(x: f32) -> f32 {
        x.ln()
    }
    #[inline]
    pub(crate) fn sqrt(x: f32) -> f32 {
        x.sqrt()
    }
    #[inline]
    pub(crate) fn cbrt(x: f32) -> f32 {
        x.cbrt()
    }
    #[inline]
    pub(crate) fn ceil(x: f32) -> f32 {
        x.ceil()
    }
}

#[cfg(feature = "libm")]
mod backend {
    #[inline]
    pub(crate) fn exp(x: f32) -> f32 {
        libm::expf(x)
    }
    #[inline]
    pub(crate) fn ln(x: f32) -> f32 {
        libm::logf(x)
    }
    #[inline]
    pub(crate) fn sqrt(x: f32) -> f32 {
        // IEEE 754 rounds a square root correctly: `std`'s (one instruction) has exactly
        // libm's bits, where libm's own is software (on wasm, several times slower).
        #[cfg(feature = "std")]
        {
            x.sqrt()
        }
        #[cfg(not(feature = "std"))]
        {
            libm::sqrtf(x)
        }
    }
    #[inline]
    pub(crate) fn cbrt(x: f32) -> f32 {
        libm::cbrtf(x)
    }
    #[inline]
    pub(crate) fn ceil(x: f32) -> f32 {
        libm::ceilf(x)
    }
}

#[cfg(any(feature = "std", feature = "libm"))]
pub(crate) use backend::{cbrt, ceil, exp, ln, sqrt};

const LOG2E: f32 = core::f32::consts::LOG2_E;
/// 1.5 × 2²³ + 127: adding and subtracting it rounds to the nearest integer (its ulp is 1),
/// and its low nine bits hold 127, the exponent bias (see [`two_to_the`]).
const ROUND: f32 = 12_583_039.0;
/// `ln 2` split Cody–Waite style: `LN2_HI` (355/512) has few bits, so `n × LN2_HI` is exact.
const LN2_HI: f32 = 0.693_359_4;
const LN2_LO: f32 = -2.121_944_4e-4;
/// Below this, [`exp_nonpositive`] gives 0.
const LOWEST: f32 = -87.0;

/// `exp(x)` for every `x` in `xs`, in place, for `x ≤ 0` (the falloffs' exponents): see
/// [`exp_nonpositive`].
#[inline]
pub(crate) fn exp_nonpositive_batch(xs: &mut [f32]) {
    for x in xs.iter_mut() {
        *x = exp_nonpositive(*x);
    }
}

/// Cephes' coefficients for `(exp(r) − 1 − r) / r²` on `|r| ≤ ln 2 / 2`, highest first.
const P0: f32 = 1.987_569_2e-4;
const P1: f32 = 1.398_199_9e-3;
const P2: f32 = 8.333_452e-3;
const P3: f32 = 4.166_579_6e-2;
const P4: f32 = 1.666_666_5e-1;
const P5: f32 = 0.5;

/// `exp(r)` for `|r| ≤ ln 2 / 2`: `1 + r + r² P(r)` with Cephes' degree-5 `P`, evaluated in
/// Estrin's scheme (pairs of terms, then `r²` and `r⁴`), whose dependency chain is about half
/// as long as Horner's: the latency of a single `exp` is what a point query waits for.
#[inline(always)]
fn polynomial(r: f32) -> f32 {
    let r2 = r * r;
    let r4 = r2 * r2;
    let low = P4 * r + P5;
    let mid = P2 * r + P3;
    let high = P0 * r + P1;
    let p = (low + mid * r2) + high * r4;
    p * r2 + r + 1.0
}

/// `2ⁿ` for the `t = v log₂e + ROUND` of [`exp_nonpositive`]: `t` lies in `[2²³, 2²⁴)`,
/// where the ulp is 1, so its bits are those of `ROUND` plus `n`, and since `ROUND`'s low
/// nine bits hold 127, shifting them up by 23 leaves exactly the exponent field `n + 127` of
/// `2ⁿ` (`−126 ≤ n ≤ 0`: a normal float). Bits, not a cast: a cast saturates and so does not
/// vectorise.
#[inline(always)]
fn two_to_the(t: f32) -> f32 {
    f32::from_bits(t.to_bits() << 23)
}

/// `exp(x)` for `x ≤ 0`: Cody–Waite range reduction to `r = x − n ln 2` with
/// `|r| ≤ ln 2 / 2`, Cephes' degree-7 polynomial for `exp(r)` ([`polynomial`]), then the
/// exponent bits of `2ⁿ`.
/// Plain `f32` arithmetic without branches, and the same bits on every platform (whichever
/// backend is on). Within 1.5e-7 relative of the true `exp` (tested; 8.0e-8 measured) for
/// `x ≥ −87`; below that, where `exp(x)` is under `1.7e-38`, it gives 0 (NaN too). Positive
/// inputs are clamped to 0 (giving 1): callers never pass them.
#[inline(always)]
pub(crate) fn exp_nonpositive(x: f32) -> f32 {
    let kept = x >= LOWEST;
    let v = if kept { x } else { LOWEST };
    let v = v.min(0.0);
    let t = v * LOG2E + ROUND;
    let n = t - ROUND;
    let r = (v - n * LN2_HI) - n * LN2_LO;
    let p = polynomial(r);
    if kept { p * two_to_the(t) } else { 0.0 }
}

/// [`exp_nonpositive`] without its flush to 0: `exp(x)` for `−87 ≤ x ≤ 0`, the same bits
/// there, and `exp(−87)` (a normal float, about `1.6e-38`) for anything below or NaN. Callers
/// pass no positive input. Two operations fewer per lane, for lanes whose tiny values are
/// masked out or never read.
#[inline(always)]
pub(crate) fn exp_nonpositive_floored(x: f32) -> f32 {
    // NaN fails `>=`: it counts as under.
    let v = if x >= LOWEST { x } else { LOWEST };
    let t = v * LOG2E + ROUND;
    let n = t - ROUND;
    let r = (v - n * LN2_HI) - n * LN2_LO;
    let p = polynomial(r);
    p * two_to_the(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn batch_exp_is_within_its_documented_error() {
        let mut worst = 0.0f64;
        let mut xs: alloc::vec::Vec<f32> =
            (0..200_000).map(|i| -87.0 * i as f32 / 200_000.0).collect();
        xs.extend([0.0, -0.0, -1e-30, -f32::MIN_POSITIVE, -86.999, -87.0]);
        let mut ys = xs.clone();
        exp_nonpositive_batch(&mut ys);
        for (&x, &y) in xs.iter().zip(&ys) {
            let e = f64::from(x).exp();
            let rel = ((f64::from(y) - e) / e).abs();
            worst = worst.max(rel);
            let b = f64::from(exp(x));
            assert!(((f64::from(y) - b) / b).abs() <= 2e-7, "{x}: {y} vs {b}");
        }
        assert!(worst < 1.5e-7, "{worst}");
        for &x in &xs {
            if x >= LOWEST {
                assert_eq!(
                    exp_nonpositive_floored(x).to_bits(),
                    exp_nonpositive(x).to_bits(),
                    "{x}"
                );
            }
        }
        let floor = exp_nonpositive_floored(LOWEST);
        assert!(
            floor > 0.0 && floor.is_normal() && floor < 1.7e-38,
            "{floor}"
        );
        for x in [-87.5f32, -1e4, f32::NEG_INFINITY, f32::NAN] {
            assert_eq!(exp_nonpositive_floored(x).to_bits(), floor.to_bits(), "{x}");
        }
        let mut edge = [-87.5f32, -1e4, f32::NEG_INFINITY, f32::NAN, 3.0];
        exp_nonpositive_batch(&mut edge);
        assert_eq!(edge, [0.0, 0.0, 0.0, 0.0, 1.0]);
    }

    #[test]
    fn backend_agrees_with_known_values() {
        assert!((exp(0.5) - 1.648_721_3).abs() < 1e-6);
        assert!((ln(core::f32::consts::E) - 1.0).abs() < 1e-6);
        assert_eq!(sqrt(16.0), 4.0);
        assert!((cbrt(8.0) - 2.0).abs() < 1e-6);
        assert_eq!(ceil(1.2), 2.0);
    }

    /// Sample inputs: small and large, around 1, near the ends of what the crate feeds in.
    #[cfg(feature = "libm")]
    const SAMPLES: [f32; 12] = [
        -80.0, -27.6, -3.5, -0.5, 0.0, 1e-6, 0.3, 1.0, 2.0, 19.4, 80.0, 1e6,
    ];

    /// Units in the last place between two finite floats of the same sign.
    #[cfg(all(feature = "std", feature = "libm"))]
    fn ulps(a: f32, b: f32) -> u32 {
        a.to_bits().abs_diff(b.to_bits())
    }

    /// With both features the libm backend is in use; `std`'s functions, called directly, must
    /// agree with it to within 2 ulp (each is within about 1 ulp of the exact result), and
    /// exactly where both are exact (`sqrt`, `ceil`).
    #[cfg(all(feature = "std", feature = "libm"))]
    #[test]
    fn std_and_libm_backends_agree() {
        for x in SAMPLES {
            assert!(ulps(exp(x), x.exp()) <= 2, "exp({x})");
            assert!(ulps(cbrt(x), x.cbrt()) <= 2, "cbrt({x})");
            assert_eq!(ceil(x).to_bits(), x.ceil().to_bits(), "ceil({x})");
            let y = x.abs();
            assert_eq!(sqrt(y).to_bits(), y.sqrt().to_bits(), "sqrt({y})");
            if y > 0.0 {
                assert!(ulps(ln(y), y.ln()) <= 2, "ln({y})");
            }
        }
    }

    /// With `libm` the backend is libm itself, bit for bit.
    #[cfg(feature = "libm")]
    #[test]
    fn libm_backend_is_libm() {
        for x in SAMPLES {
            let y = x.abs();
            assert_eq!(exp(x).to_bits(), libm::expf(x).to_bits());
            assert_eq!(ln(y).to_bits(), libm::logf(y).to_bits());
            assert_eq!(sqrt(y).to_bits(), libm::sqrtf(y).to_bits());
            assert_eq!(cbrt(x).to_bits(), libm::cbrtf(x).to_bits());
            assert_eq!(ceil(x).to_bits(), libm::ceilf(x).to_bits());
        }
    }
}
