//! Scalar float helpers with a `std` and a `libm` backend; call sites never branch.

#[cfg(feature = "std")]
mod backend {
    #[inline]
    pub(crate) fn exp(x: f32) -> f32 {
        x.exp()
    }
    #[inline]
    pub(crate) fn sin(x: f32) -> f32 {
        x.sin()
    }
    #[inline]
    pub(crate) fn cos(x: f32) -> f32 {
        x.cos()
    }
    #[inline]
    pub(crate) fn sqrt(x: f32) -> f32 {
        x.sqrt()
    }
    #[inline]
    pub(crate) fn asin(x: f32) -> f32 {
        x.asin()
    }
}

#[cfg(not(feature = "std"))]
mod backend {
    #[inline]
    pub(crate) fn exp(x: f32) -> f32 {
        libm::expf(x)
    }
    #[inline]
    pub(crate) fn sin(x: f32) -> f32 {
        libm::sinf(x)
    }
    #[inline]
    pub(crate) fn cos(x: f32) -> f32 {
        libm::cosf(x)
    }
    #[inline]
    pub(crate) fn sqrt(x: f32) -> f32 {
        libm::sqrtf(x)
    }
    #[inline]
    pub(crate) fn asin(x: f32) -> f32 {
        libm::asinf(x)
    }
}

pub(crate) use backend::{asin, cos, exp, sin, sqrt};

/// Rounds half away from zero, for non-negative finite input of moderate size.
#[inline]
pub(crate) fn round_non_negative(x: f32) -> u32 {
    (x + 0.5) as u32
}

/// The smallest integer not below `x`, for non-negative finite input (saturating for huge
/// input). `f32::ceil` needs `std`; this works without it.
#[inline]
pub(crate) fn ceil_non_negative(x: f32) -> usize {
    let whole = x as usize;
    if (whole as f32) < x {
        whole.saturating_add(1)
    } else {
        whole
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn backends_agree_with_known_values() {
        assert!((exp(0.0) - 1.0).abs() < 1e-7);
        assert!((exp(1.0) - core::f32::consts::E).abs() < 1e-6);
        assert!(sin(0.0).abs() < 1e-7);
        assert!((sin(core::f32::consts::FRAC_PI_2) - 1.0).abs() < 1e-6);
        assert_eq!(round_non_negative(2.5), 3);
        assert_eq!(round_non_negative(2.49), 2);
        assert_eq!(ceil_non_negative(2.0), 2);
        assert_eq!(ceil_non_negative(2.01), 3);
        assert_eq!(ceil_non_negative(0.0), 0);
    }
}
