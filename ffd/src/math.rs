//! Scalar float helpers. Everything else goes through glam's methods, which already pick
//! `std` or `libm` by feature, so call sites never branch on the backend.

/// Absolute value by clearing the sign bit: identical on every platform and backend.
#[inline]
pub(crate) fn abs(x: f32) -> f32 {
    f32::from_bits(x.to_bits() & 0x7fff_ffff)
}

/// `v / |v|`, or `fallback` for a zero or non-finite `v`, exact to rounding at every finite
/// scale: where `|v|²` leaves the normal `f32` range (tiny or huge vectors) `v` is first
/// divided by its largest component, so the length is not lost to underflow or overflow.
/// Elsewhere it is glam's `normalize_or`, bit for bit.
#[inline]
pub(crate) fn normalize_or(v: glam::Vec3, fallback: glam::Vec3) -> glam::Vec3 {
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
    fn abs_clears_the_sign_bit() {
        assert_eq!(abs(-2.5), 2.5);
        assert_eq!(abs(2.5), 2.5);
        assert_eq!(abs(-0.0).to_bits(), 0.0f32.to_bits());
        assert!(abs(f32::NAN).is_nan());
    }
}
