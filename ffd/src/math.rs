//! Scalar float helpers. Everything else goes through glam's methods, which already pick
//! `std` or `libm` by feature, so call sites never branch on the backend.

/// Absolute value by clearing the sign bit: identical on every platform and backend.
#[inline]
pub(crate) fn abs(x: f32) -> f32 {
    f32::from_bits(x.to_bits() & 0x7fff_ffff)
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
