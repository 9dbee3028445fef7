//! Scalar float helpers with a `std` backend and a `libm` backend, so call sites never branch.
//! Everything vector-valued goes through glam's methods, which pick the backend themselves.

/// Square root: `std`'s whenever it is there, with `libm` too (IEEE 754 rounds a square root
/// correctly, so it has exactly libm's bits, where libm's own is software on wasm).
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
#[cfg(all(feature = "std", not(feature = "libm")))]
#[inline]
pub(crate) fn powf(x: f32, y: f32) -> f32 {
    x.powf(y)
}

/// `x` raised to `y`.
#[cfg(any(feature = "libm", not(feature = "std")))]
#[inline]
pub(crate) fn powf(x: f32, y: f32) -> f32 {
    libm::powf(x, y)
}

/// `v / |v|`, or `fallback` for a zero or non-finite `v`, exact to rounding at every finite
/// scale: where `|v|²` leaves the normal `f32` range (tiny or huge vectors) `v` is first
/// divided by its largest component, so the length is not lost to underflow or overflow.
/// Elsewhere it is glam's `normalize_or`, bit for bit.
#[inline]
pub(crate) fn normalize_or(v: glam::Vec3A, fallback: glam::Vec3A) -> glam::Vec3A {
    let l2 = v.length_squared();
    if l2 >= f32::MIN_POSITIVE && l2.is_finite() {
        return v.normalize_or(fallback);
    }
    let m = v.abs().max_element();
    if !(m > 0.0 && m.is_finite()) {
        return fallback;
    }
    (v / m).normalize_or(fallback)
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
