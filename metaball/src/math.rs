//! Scalar float helpers with a `std` backend and a `libm` backend (std wins when both are on),
//! so call sites never branch. Vector math goes through glam, which picks its backend the same
//! way.

#[cfg(feature = "std")]
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
    #[inline]
    pub(crate) fn floor(x: f32) -> f32 {
        x.floor()
    }
}

#[cfg(all(not(feature = "std"), feature = "libm"))]
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
        libm::sqrtf(x)
    }
    #[inline]
    pub(crate) fn cbrt(x: f32) -> f32 {
        libm::cbrtf(x)
    }
    #[inline]
    pub(crate) fn ceil(x: f32) -> f32 {
        libm::ceilf(x)
    }
    #[inline]
    pub(crate) fn floor(x: f32) -> f32 {
        libm::floorf(x)
    }
}

#[cfg(any(feature = "std", feature = "libm"))]
pub(crate) use backend::{cbrt, ceil, exp, floor, ln, sqrt};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn backend_agrees_with_known_values() {
        assert!((exp(0.5) - 1.648_721_3).abs() < 1e-6);
        assert!((ln(core::f32::consts::E) - 1.0).abs() < 1e-6);
        assert_eq!(sqrt(16.0), 4.0);
        assert!((cbrt(8.0) - 2.0).abs() < 1e-6);
        assert_eq!(ceil(1.2), 2.0);
        assert_eq!(floor(-1.2), -2.0);
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

    /// With both features the std backend is in use; libm, called directly, must agree with it
    /// to within 2 ulp (each is within about 1 ulp of the exact result), and exactly where both
    /// are exact (`sqrt`, `ceil`, `floor`).
    #[cfg(all(feature = "std", feature = "libm"))]
    #[test]
    fn std_and_libm_backends_agree() {
        for x in SAMPLES {
            assert!(ulps(exp(x), libm::expf(x)) <= 2, "exp({x})");
            assert!(ulps(cbrt(x), libm::cbrtf(x)) <= 2, "cbrt({x})");
            assert_eq!(ceil(x).to_bits(), libm::ceilf(x).to_bits(), "ceil({x})");
            assert_eq!(floor(x).to_bits(), libm::floorf(x).to_bits(), "floor({x})");
            let y = x.abs();
            assert_eq!(sqrt(y).to_bits(), libm::sqrtf(y).to_bits(), "sqrt({y})");
            if y > 0.0 {
                assert!(ulps(ln(y), libm::logf(y)) <= 2, "ln({y})");
            }
        }
    }

    /// Without `std` the backend is libm itself, bit for bit.
    #[cfg(all(feature = "libm", not(feature = "std")))]
    #[test]
    fn libm_backend_is_libm() {
        for x in SAMPLES {
            let y = x.abs();
            assert_eq!(exp(x).to_bits(), libm::expf(x).to_bits());
            assert_eq!(ln(y).to_bits(), libm::logf(y).to_bits());
            assert_eq!(sqrt(y).to_bits(), libm::sqrtf(y).to_bits());
            assert_eq!(cbrt(x).to_bits(), libm::cbrtf(x).to_bits());
            assert_eq!(ceil(x).to_bits(), libm::ceilf(x).to_bits());
            assert_eq!(floor(x).to_bits(), libm::floorf(x).to_bits());
        }
    }
}
