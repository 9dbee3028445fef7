//! Scalar float helpers with a `std` and a `libm` backend; call sites never branch.

#[cfg(all(feature = "std", not(feature = "libm")))]
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
    #[inline]
    pub(crate) fn powf(x: f32, y: f32) -> f32 {
        x.powf(y)
    }
}

#[cfg(feature = "libm")]
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
    pub(crate) fn asin(x: f32) -> f32 {
        libm::asinf(x)
    }
    #[inline]
    pub(crate) fn powf(x: f32, y: f32) -> f32 {
        libm::powf(x, y)
    }
}

pub(crate) use backend::{asin, cos, exp, powf, sin, sqrt};

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

/// `min` without NaN handling: `b` when either is NaN. One instruction, also in vectorised
/// loops (`f32::min` needs a few to return the number).
#[inline]
pub(crate) fn min(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// `max` without NaN handling: `b` when either is NaN (see [`min`]).
#[inline]
pub(crate) fn max(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

/// `floor` for `|v| < 2²²`, without `std` and without a float-to-integer conversion, so loops
/// of it vectorise: adding and subtracting 1.5 · 2²³ rounds to the nearest integer, then one
/// step down where that rounded up.
#[inline]
pub(crate) fn floor_f(v: f32) -> f32 {
    const ROUND: f32 = 12_582_912.0;
    let r = (v + ROUND) - ROUND;
    if r > v { r - 1.0 } else { r }
}

/// `ceil` for `|v| < 2²²` (see [`floor_f`]).
#[inline]
pub(crate) fn ceil_f(v: f32) -> f32 {
    -floor_f(-v)
}

/// `e^x` from arithmetic alone: `x` clamped to [−87, 88] (a NaN gives `e^−87`), split as
/// `2^n · e^r` with `|r| ≤ ln 2 / 2` and `e^r` a degree-7 Taylor polynomial; within 2 units in
/// the last place of `f32` over that range. The same bits with `std` or `libm` and on every
/// platform, and no call, so loops of it vectorise.
#[inline]
pub(crate) fn exp_poly(x: f32) -> f32 {
    // 1.5 · 2²³: adding it rounds to an integer, held in the low mantissa bits.
    const ROUND: f32 = 12_582_912.0;
    // ln 2 in two parts (0.693145751953125 and 1.4286068e-6, the first with 16 significant
    // bits, so `n · LN2_HI` is exact for |n| < 256).
    const LN2_HI: f32 = f32::from_bits(0x3f31_7200);
    const LN2_LO: f32 = f32::from_bits(0x35bf_be8e);
    let x = min(max(x, -87.0), 88.0);
    let t = x * core::f32::consts::LOG2_E + ROUND;
    let n = t - ROUND;
    let r = x - n * LN2_HI - n * LN2_LO;
    let p = 1.0
        + r * (1.0
            + r * (1.0 / 2.0
                + r * (1.0 / 6.0
                    + r * (1.0 / 24.0
                        + r * (1.0 / 120.0 + r * (1.0 / 720.0 + r * (1.0 / 5040.0)))))));
    // `t`'s bits are those of ROUND plus n; 2^n from its exponent bits (n in [−126, 127]).
    let n = t.to_bits().wrapping_sub(ROUND.to_bits()) as i32;
    p * f32::from_bits(((n + 127) as u32) << 23)
}

/// glam's lengths and normalisations with the square root taken by [`sqrt`]. Under `libm`,
/// glam calls libm's software square root (on wasm, where `std`'s is one instruction, it was
/// a sixth of the live animator's time); these give glam's bits all the same (glam's scalar order
/// of operations, which `libm` turns on, and a square root rounded exactly either way).
/// Without `libm`, glam's own.
pub(crate) trait Roots: Sized {
    /// `length`.
    fn norm(self) -> f32;
    /// `normalize`.
    fn unit(self) -> Self;
    /// `normalize_or`.
    fn unit_or(self, fallback: Self) -> Self;
    /// `try_normalize`.
    fn try_unit(self) -> Option<Self>;
}

macro_rules! roots {
    ($($T:ty),*) => {$(
        impl Roots for $T {
            #[inline]
            fn norm(self) -> f32 {
                #[cfg(feature = "libm")]
                return sqrt(self.dot(self));
                #[cfg(not(feature = "libm"))]
                return self.length();
            }
            #[inline]
            fn unit(self) -> Self {
                #[cfg(feature = "libm")]
                return self * (1.0 / self.norm());
                #[cfg(not(feature = "libm"))]
                return self.normalize();
            }
            #[inline]
            fn unit_or(self, fallback: Self) -> Self {
                self.try_unit().unwrap_or(fallback)
            }
            #[inline]
            fn try_unit(self) -> Option<Self> {
                #[cfg(feature = "libm")]
                {
                    let rcp = 1.0 / self.norm();
                    (rcp.is_finite() && rcp > 0.0).then(|| self * rcp)
                }
                #[cfg(not(feature = "libm"))]
                return self.try_normalize();
            }
        }
    )*};
}

roots!(glam::Vec2, glam::Vec3, glam::Vec3A, glam::Vec4);

impl Roots for glam::Quat {
    #[inline]
    fn norm(self) -> f32 {
        glam::Vec4::from(self).norm()
    }
    #[inline]
    fn unit(self) -> Self {
        #[cfg(feature = "libm")]
        return Self::from_vec4(glam::Vec4::from(self).unit());
        #[cfg(not(feature = "libm"))]
        return self.normalize();
    }
    #[inline]
    fn unit_or(self, fallback: Self) -> Self {
        self.try_unit().unwrap_or(fallback)
    }
    #[inline]
    fn try_unit(self) -> Option<Self> {
        glam::Vec4::from(self).try_unit().map(Self::from_vec4)
    }
}

/// glam's `Quat::from_rotation_axes` (its `from_mat3` and `from_mat3a`) with the square root
/// taken by [`sqrt`], as [`Roots`] takes it: the same bits as glam's under `libm`; glam's own
/// without it.
#[inline]
pub(crate) fn quat_from_axes(
    x_axis: glam::Vec3,
    y_axis: glam::Vec3,
    z_axis: glam::Vec3,
) -> glam::Quat {
    #[cfg(not(feature = "libm"))]
    return glam::Quat::from_rotation_axes(x_axis, y_axis, z_axis);
    #[cfg(feature = "libm")]
    {
        use glam::Quat;
        let (m00, m01, m02) = x_axis.into();
        let (m10, m11, m12) = y_axis.into();
        let (m20, m21, m22) = z_axis.into();
        if m22 <= 0.0 {
            let dif10 = m11 - m00;
            let omm22 = 1.0 - m22;
            if dif10 <= 0.0 {
                let four_xsq = omm22 - dif10;
                let inv4x = 0.5 / sqrt(four_xsq);
                Quat::from_xyzw(
                    four_xsq * inv4x,
                    (m01 + m10) * inv4x,
                    (m02 + m20) * inv4x,
                    (m12 - m21) * inv4x,
                )
            } else {
                let four_ysq = omm22 + dif10;
                let inv4y = 0.5 / sqrt(four_ysq);
                Quat::from_xyzw(
                    (m01 + m10) * inv4y,
                    four_ysq * inv4y,
                    (m12 + m21) * inv4y,
                    (m20 - m02) * inv4y,
                )
            }
        } else {
            let sum10 = m11 + m00;
            let opm22 = 1.0 + m22;
            if sum10 <= 0.0 {
                let four_zsq = opm22 - sum10;
                let inv4z = 0.5 / sqrt(four_zsq);
                Quat::from_xyzw(
                    (m02 + m20) * inv4z,
                    (m12 + m21) * inv4z,
                    four_zsq * inv4z,
                    (m01 - m10) * inv4z,
                )
            } else {
                let four_wsq = opm22 + sum10;
                let inv4w = 0.5 / sqrt(four_wsq);
                Quat::from_xyzw(
                    (m12 - m21) * inv4w,
                    (m20 - m02) * inv4w,
                    (m01 - m10) * inv4w,
                    four_wsq * inv4w,
                )
            }
        }
    }
}

/// [`quat_from_axes`] of a matrix's columns (glam's `Quat::from_mat3a`).
#[inline]
pub(crate) fn quat_from_mat3a(m: &glam::Mat3A) -> glam::Quat {
    quat_from_axes(m.x_axis.into(), m.y_axis.into(), m.z_axis.into())
}

/// The larger of `a` and `b`; `a` where they are equal or `b` is NaN: `f32::max` for a running
/// maximum that starts from a number, without the library call it is on wasm (`fmaxf`, whose
/// NaN rules wasm's own `max` instruction does not share).
#[inline]
pub(crate) fn max_f(a: f32, b: f32) -> f32 {
    if b > a { b } else { a }
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
        assert!((powf(2.0, 10.0) - 1024.0).abs() < 1e-3);
        assert_eq!(round_non_negative(2.5), 3);
        assert_eq!(round_non_negative(2.49), 2);
        assert_eq!(ceil_non_negative(2.0), 2);
        assert_eq!(ceil_non_negative(2.01), 3);
        assert_eq!(ceil_non_negative(0.0), 0);
        assert_eq!((min(1.0, 2.0), max(1.0, 2.0)), (1.0, 2.0));
        assert_eq!((min(f32::NAN, 2.0), max(f32::NAN, 2.0)), (2.0, 2.0));
        let cases = [
            (0.0, 0.0, 0.0),
            (0.5, 0.0, 1.0),
            (1.0, 1.0, 1.0),
            (2.5, 2.0, 3.0),
            (-0.5, -1.0, 0.0),
            (-1.5, -2.0, -1.0),
            (3.999_999_8, 3.0, 4.0),
            (-3.999_999_8, -4.0, -3.0),
            (4e6 + 0.5, 4e6, 4e6 + 1.0),
        ];
        for (v, floor, ceil) in cases {
            assert_eq!((floor_f(v), ceil_f(v)), (floor, ceil), "{v}");
        }
    }

    #[test]
    fn polynomial_exp_is_within_two_ulp() {
        let mut worst = 0.0f64;
        for i in 0..=200_000 {
            let x = -87.0 + 175.0 * i as f32 / 200_000.0;
            let exact = f64::from(x).exp();
            let ulp = f64::from(f32::EPSILON) * exact;
            worst = worst.max((f64::from(exp_poly(x)) - exact).abs() / ulp);
        }
        assert!(worst <= 2.0, "{worst} ulp");
        assert_eq!(exp_poly(0.0), 1.0);
        assert_eq!(exp_poly(-1000.0), exp_poly(-87.0));
        assert_eq!(exp_poly(f32::NAN), exp_poly(-87.0));
        assert!(exp_poly(1000.0).is_finite());
    }

    #[test]
    fn roots_are_glams_lengths_and_normalisations_bit_for_bit() {
        use glam::{Quat, Vec3, Vec3A, Vec4};
        let mut x = 0x9E37_79B9u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            f32::from_bits(x & 0x807F_FFFF | 0x3F00_0000) * 3.0
        };
        for _ in 0..2000 {
            let (a, b, c, d) = (next(), next(), next(), next());
            let v = Vec3::new(a, b, c);
            assert_eq!(v.norm().to_bits(), v.length().to_bits());
            assert_eq!(v.unit(), v.normalize());
            assert_eq!(v.try_unit(), v.try_normalize());
            assert_eq!(v.unit_or(Vec3::X), v.normalize_or(Vec3::X));
            let w = Vec3A::new(a, b, c);
            assert_eq!(w.unit(), w.normalize());
            let q = Quat::from_xyzw(a, b, c, d);
            assert_eq!(q.unit(), q.normalize());
            assert_eq!(Vec4::new(a, b, c, d).norm(), Vec4::new(a, b, c, d).length());
        }
        for v in [
            Vec3::ZERO,
            Vec3::splat(f32::NAN),
            Vec3::splat(1e-30),
            Vec3::splat(3e38),
        ] {
            assert_eq!(v.try_unit(), v.try_normalize());
            assert_eq!(v.unit_or(Vec3::Y), v.normalize_or(Vec3::Y));
        }
    }

    #[test]
    fn quat_from_axes_is_glams_bit_for_bit() {
        use glam::{Mat3A, Quat, Vec3};
        let mut x = 0x1234_5677u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
        };
        for _ in 0..4000 {
            let q = Quat::from_xyzw(next(), next(), next(), next()).normalize();
            let m = Mat3A::from_quat(q);
            assert_eq!(quat_from_mat3a(&m), Quat::from_mat3a(&m));
            let (a, b, c) = (
                Vec3::from(m.x_axis),
                Vec3::from(m.y_axis),
                Vec3::from(m.z_axis),
            );
            assert_eq!(quat_from_axes(a, b, c), Quat::from_rotation_axes(a, b, c));
        }
    }
}
