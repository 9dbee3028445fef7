//! Scalar float helpers with a `std` backend and a `libm` backend, so call sites never branch.
//! Everything vector-valued goes through glam's methods, which pick the backend themselves.

/// Square root.
#[cfg(feature = "std")]
#[inline]
pub(crate) fn sqrt(x: f32) -> f32 {
    x.sqrt()
}

/// Square root.
#[cfg(not(feature = "std"))]
#[inline]
pub(crate) fn sqrt(x: f32) -> f32 {
    libm::sqrtf(x)
}

/// `x` raised to `y`.
#[cfg(feature = "std")]
#[inline]
pub(crate) fn powf(x: f32, y: f32) -> f32 {
    x.powf(y)
}

/// `x` raised to `y`.
#[cfg(not(feature = "std"))]
#[inline]
pub(crate) fn powf(x: f32, y: f32) -> f32 {
    libm::powf(x, y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn backends_agree_on_exact_cases() {
        assert_eq!(sqrt(4.0), 2.0);
        assert_eq!(sqrt(0.0), 0.0);
        assert_eq!(powf(2.0, 3.0), 8.0);
        assert_eq!(powf(0.25, 0.5), 0.5);
    }
}
