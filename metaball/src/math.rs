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
}
