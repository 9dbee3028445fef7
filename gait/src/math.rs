//! Scalar float math with a `std` backend and a `libm` backend (`std` wins when both are on).
//! Call sites never branch on the backend; vector math goes through glam, which picks its
//! backend by the same features.

#[cfg(all(feature = "std", not(feature = "libm")))]
mod backend {
    #[inline]
    pub(crate) fn sin(x: f32) -> f32 {
        x.sin()
    }
    #[inline]
    pub(crate) fn cos(x: f32) -> f32 {
        x.cos()
    }
    #[inline]
    pub(crate) fn atan2(y: f32, x: f32) -> f32 {
        y.atan2(x)
    }
    #[inline]
    pub(crate) fn exp(x: f32) -> f32 {
        x.exp()
    }
    #[inline]
    pub(crate) fn sqrt(x: f32) -> f32 {
        x.sqrt()
    }
    #[inline]
    pub(crate) fn floor(x: f32) -> f32 {
        x.floor()
    }
    #[inline]
    pub(crate) fn ceil(x: f32) -> f32 {
        x.ceil()
    }
}

#[cfg(feature = "libm")]
mod backend {
    #[inline]
    pub(crate) fn sin(x: f32) -> f32 {
        libm::sinf(x)
    }
    #[inline]
    pub(crate) fn cos(x: f32) -> f32 {
        libm::cosf(x)
    }
    #[inline]
    pub(crate) fn atan2(y: f32, x: f32) -> f32 {
        libm::atan2f(y, x)
    }
    #[inline]
    pub(crate) fn exp(x: f32) -> f32 {
        libm::expf(x)
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
    pub(crate) fn floor(x: f32) -> f32 {
        libm::floorf(x)
    }
    #[inline]
    pub(crate) fn ceil(x: f32) -> f32 {
        libm::ceilf(x)
    }
}

#[cfg(not(any(feature = "std", feature = "libm")))]
mod backend {
    // The crate root raises a `compile_error!`; these keep the other errors quiet.
    pub(crate) fn sin(x: f32) -> f32 {
        x
    }
    pub(crate) fn cos(x: f32) -> f32 {
        x
    }
    pub(crate) fn atan2(y: f32, _x: f32) -> f32 {
        y
    }
    pub(crate) fn exp(x: f32) -> f32 {
        x
    }
    pub(crate) fn sqrt(x: f32) -> f32 {
        x
    }
    pub(crate) fn floor(x: f32) -> f32 {
        x
    }
    pub(crate) fn ceil(x: f32) -> f32 {
        x
    }
}

pub(crate) use backend::{ceil, cos, exp, floor, sin, sqrt};

use core::f32::consts::{FRAC_PI_2, PI};
use core::ops::{Add, Mul, Sub};

use glam::Vec4;

/// `atan2(y, x)` for finite input, without a library call: the same on every platform and
/// backend. Octant reduction to `a = min/max ∈ [0, 1]`, then `a · P(a²)` with a degree-8
/// Chebyshev fit of `atan(√t)/√t` on `[0, 1]` (fit error 1.8e-8 rad, below the f32 rounding of
/// the result: within 3e-7 rad of f64, one ulp of π). Signed zeros and the axes follow IEEE
/// `atan2`; non-finite input goes to the backend's `atan2`.
#[inline]
pub(crate) fn atan2(y: f32, x: f32) -> f32 {
    if !(x.is_finite() && y.is_finite()) {
        return backend::atan2(y, x);
    }
    let (ax, ay) = (abs(x), abs(y));
    let (small, large) = if ay > ax { (ax, ay) } else { (ay, ax) };
    let mut r = if large == 0.0 {
        0.0
    } else {
        let a = small / large;
        a * atan_poly(a * a)
    };
    if ay > ax {
        r = FRAC_PI_2 - r;
    }
    if x.is_sign_negative() {
        r = PI - r;
    }
    if y.is_sign_negative() { -r } else { r }
}

/// [`atan2`] of four lanes, bit for bit: the same operations, each lane taking its own
/// branches by selection. Lanes with non-finite input (which `atan2` sends to the backend)
/// are computed one by one.
#[inline(always)]
pub(crate) fn atan2_lanes(y: Vec4, x: Vec4) -> Vec4 {
    let zero = Vec4::ZERO;
    let (ax, ay) = (x.abs(), y.abs());
    let swap = ay.cmpgt(ax);
    let small = Vec4::select(swap, ax, ay);
    let large = Vec4::select(swap, ay, ax);
    let a = small / large;
    let r = Vec4::select(large.cmpeq(zero), zero, a * atan_poly(a * a));
    let r = Vec4::select(swap, Vec4::splat(FRAC_PI_2) - r, r);
    let r = Vec4::select(Vec4::ONE.copysign(x).cmplt(zero), Vec4::splat(PI) - r, r);
    // `r` is +0 or positive here: negating it for a negative `y` is taking `y`'s sign.
    let r = r.copysign(y);
    if (x.is_finite_mask() & y.is_finite_mask()).all() {
        r
    } else {
        Vec4::new(
            atan2(y.x, x.x),
            atan2(y.y, x.y),
            atan2(y.z, x.z),
            atan2(y.w, x.w),
        )
    }
}

/// `atan(√t)/√t` on `[0, 1]`: the degree-8 Chebyshev fit of [`atan2`], for a scalar or four
/// lanes alike.
#[inline(always)]
fn atan_poly<T>(t: T) -> T
where
    T: Copy + Mul<Output = T> + Mul<f32, Output = T> + Add<f32, Output = T> + Sub<f32, Output = T>,
{
    let p = t * 0.002_766_283_5 - 0.015_731_249;
    let p = p * t + 0.042_137_624;
    let p = p * t - 0.074_568_55;
    let p = p * t + 0.106_183_71;
    let p = p * t - 0.141_977_98;
    let p = p * t + 0.199_918_72;
    let p = p * t - 0.333_330_37;
    p * t + 0.999_999_98
}

/// Absolute value by clearing the sign bit: identical on every platform and backend.
#[inline]
pub(crate) fn abs(x: f32) -> f32 {
    f32::from_bits(x.to_bits() & 0x7fff_ffff)
}

/// `(sin x, cos x)` without a library call, for `|x| ≤ π/2` (Taylor polynomials to x¹³ and
/// x¹⁴: within 1.5e-7 of the true values, the same on every platform); larger or non-finite
/// `x` goes to the backend.
#[inline]
pub(crate) fn sin_cos(x: f32) -> (f32, f32) {
    if !(abs(x) <= FRAC_PI_2) {
        return (sin(x), cos(x));
    }
    let t = x * x;
    let s = 1.0 / 6_227_020_800.0;
    let s = s * t - 1.0 / 39_916_800.0;
    let s = s * t + 1.0 / 362_880.0;
    let s = s * t - 1.0 / 5040.0;
    let s = s * t + 1.0 / 120.0;
    let s = s * t - 1.0 / 6.0;
    let s = s * t + 1.0;
    let c = 1.0 / 87_178_291_200.0;
    let c = c * t - 1.0 / 479_001_600.0;
    let c = c * t + 1.0 / 3_628_800.0;
    let c = c * t - 1.0 / 40320.0;
    let c = c * t + 1.0 / 720.0;
    let c = c * t - 1.0 / 24.0;
    let c = c * t + 0.5;
    (x * s, 1.0 - t * c)
}

/// [`sin_cos`] of four lanes, bit for bit: the same operations lane by lane. Lanes outside
/// `|x| ≤ π/2` (which `sin_cos` sends to the backend) are computed one by one.
#[inline(always)]
pub(crate) fn sin_cos_lanes(x: Vec4) -> (Vec4, Vec4) {
    let t = x * x;
    let s = t * (1.0 / 6_227_020_800.0) - 1.0 / 39_916_800.0;
    let s = s * t + 1.0 / 362_880.0;
    let s = s * t - 1.0 / 5040.0;
    let s = s * t + 1.0 / 120.0;
    let s = s * t - 1.0 / 6.0;
    let s = s * t + 1.0;
    let c = t * (1.0 / 87_178_291_200.0) - 1.0 / 479_001_600.0;
    let c = c * t + 1.0 / 3_628_800.0;
    let c = c * t - 1.0 / 40320.0;
    let c = c * t + 1.0 / 720.0;
    let c = c * t - 1.0 / 24.0;
    let c = c * t + 0.5;
    if x.abs().cmple(Vec4::splat(FRAC_PI_2)).all() {
        (x * s, Vec4::ONE - t * c)
    } else {
        let [a, b, c, d] = x.to_array().map(sin_cos);
        (Vec4::new(a.0, b.0, c.0, d.0), Vec4::new(a.1, b.1, c.1, d.1))
    }
}

/// `sin(2π · turns)` for any finite `turns` (non-finite gives 0): reduced to a quarter turn,
/// then [`sin_cos`]. Periodic with period 1 exactly (it only sees the fractional part).
#[inline]
pub(crate) fn sin_turns(turns: f32) -> f32 {
    if !turns.is_finite() {
        return 0.0;
    }
    let (sign, x) = sin_turns_arg(turns);
    sign * sin_cos(x).0
}

/// The reduction of [`sin_turns`]: `(sign, x)` with `sin_turns(turns) = sign · sin_cos(x).0`,
/// bit for bit (`x` within a quarter turn; `(1, 0)` for non-finite `turns`).
#[inline]
pub(crate) fn sin_turns_arg(turns: f32) -> (f32, f32) {
    if !turns.is_finite() {
        return (1.0, 0.0);
    }
    let whole = if turns >= 0.0 {
        floor_non_negative(turns)
    } else {
        floor(turns)
    };
    fold_turn(turns - whole)
}

/// `(sign, x)` with `sin(2π p) = sign · sin(x)` for a fraction of a turn `p` in `[0, 1]`:
/// folded to the first quarter turn.
#[inline(always)]
fn fold_turn(mut p: f32) -> (f32, f32) {
    let mut sign = 1.0;
    if p >= 0.5 {
        p -= 0.5;
        sign = -1.0;
    }
    if p > 0.25 {
        p = 0.5 - p;
    }
    (sign, core::f32::consts::TAU * p)
}

/// [`sin_turns`] for `turns` in `[0, 0.5]` (as the sine height curve's), bit for bit: the
/// whole turns are 0 there, so the reduction needs no floor.
#[inline]
pub(crate) fn sin_half_turn(turns: f32) -> f32 {
    let (sign, x) = fold_turn(turns);
    sign * sin_cos(x).0
}

/// The rotation `from_rotation_y(yaw) · from_rotation_x(pitch) · from_rotation_z(roll)` (glam's
/// `EulerRot::YXZ`), with [`sin_cos`] for the half angles.
#[inline]
pub(crate) fn quat_yxz(yaw: f32, pitch: f32, roll: f32) -> glam::Quat {
    let (sy, cy) = sin_cos(0.5 * yaw);
    let (sx, cx) = sin_cos(0.5 * pitch);
    let (sz, cz) = sin_cos(0.5 * roll);
    quat_yxz_sin_cos(Vec4::new(sy, sx, sz, 0.0), Vec4::new(cy, cx, cz, 0.0))
}

/// [`quat_yxz`] from the sines `s` and cosines `c` of its half angles: yaw, pitch and roll in
/// lanes 0, 1 and 2 (lane 3 unused).
#[inline]
pub(crate) fn quat_yxz_sin_cos(s: Vec4, c: Vec4) -> glam::Quat {
    glam::Quat::from_xyzw(0.0, s.x, 0.0, c.x)
        * glam::Quat::from_xyzw(s.y, 0.0, 0.0, c.y)
        * glam::Quat::from_xyzw(0.0, 0.0, s.z, c.z)
}

/// `floor(x)` for `x >= 0` without a library call: truncation, exact below 2²³ (every float
/// from 2²³ up is an integer already). Not for negative or NaN input.
#[inline]
pub(crate) fn floor_non_negative(x: f32) -> f32 {
    if x < 8_388_608.0 {
        (x as u32) as f32
    } else {
        x
    }
}

/// The fraction of the remaining distance an exponential smoother covers in `dt` with time
/// constant `tau` (`tau <= 0` snaps).
#[inline]
pub(crate) fn smoothing(dt: f32, tau: f32) -> f32 {
    if tau <= 0.0 {
        1.0
    } else {
        1.0 - exp(-dt / tau)
    }
}

/// `x` clamped into `[-limit, limit]`; NaN becomes 0.
#[inline]
pub(crate) fn clamp_sym(x: f32, limit: f32) -> f32 {
    if x.is_nan() {
        0.0
    } else {
        x.clamp(-limit, limit)
    }
}

/// glam's lengths and normalisations with the square root taken by [`sqrt`]. Under `libm`,
/// glam calls libm's software square root (on wasm, where `std`'s is one instruction, it was
/// a sixth of the animator's time); these give glam's bits all the same (glam's scalar order
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

roots!(glam::Vec2, glam::Vec3, glam::Vec3A, Vec4);

impl Roots for glam::Quat {
    #[inline]
    fn norm(self) -> f32 {
        Vec4::from(self).norm()
    }
    #[inline]
    fn unit(self) -> Self {
        #[cfg(feature = "libm")]
        return Self::from_vec4(Vec4::from(self).unit());
        #[cfg(not(feature = "libm"))]
        return self.normalize();
    }
    #[inline]
    fn unit_or(self, fallback: Self) -> Self {
        self.try_unit().unwrap_or(fallback)
    }
    #[inline]
    fn try_unit(self) -> Option<Self> {
        Vec4::from(self).try_unit().map(Self::from_vec4)
    }
}

/// glam's `Vec4::sqrt`, each lane by [`sqrt`] under `libm` (see [`Roots`]).
#[inline]
pub(crate) fn sqrt4(v: Vec4) -> Vec4 {
    #[cfg(feature = "libm")]
    return Vec4::new(sqrt(v.x), sqrt(v.y), sqrt(v.z), sqrt(v.w));
    #[cfg(not(feature = "libm"))]
    return v.sqrt();
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn abs_clears_the_sign_bit() {
        assert_eq!(abs(-2.5), 2.5);
        assert_eq!(abs(-0.0).to_bits(), 0.0f32.to_bits());
    }

    #[test]
    #[cfg(feature = "std")]
    fn atan2_is_within_rounding_of_f64() {
        let mut worst = 0.0f64;
        for i in -60..=60 {
            for j in -60..=60 {
                let (y, x) = (
                    i as f32 * 0.37 * (1.0 + (j * j) as f32 * 1e-3),
                    j as f32 * 0.41,
                );
                let exact = f64::from(y).atan2(f64::from(x));
                worst = worst.max((f64::from(atan2(y, x)) - exact).abs());
            }
        }
        for k in 0..2000 {
            let a = k as f32 * (PI / 1000.0) - PI;
            let (y, x) = (sin(a) * 7.0, cos(a) * 7.0);
            let exact = f64::from(y).atan2(f64::from(x));
            worst = worst.max((f64::from(atan2(y, x)) - exact).abs());
        }
        assert!(worst <= 3e-7, "worst error {worst}"); // about one ulp of π
        // IEEE signed zeros and axes.
        assert_eq!(atan2(0.0, 0.0).to_bits(), 0.0f32.to_bits());
        assert_eq!(atan2(-0.0, 0.0).to_bits(), (-0.0f32).to_bits());
        assert_eq!(atan2(0.0, -0.0), PI);
        assert_eq!(atan2(-0.0, -1.0), -PI);
        assert_eq!(atan2(2.0, 0.0), FRAC_PI_2);
        assert_eq!(atan2(-2.0, 0.0), -FRAC_PI_2);
        assert!(atan2(f32::NAN, 1.0).is_nan());
        assert_eq!(atan2(1.0, f32::INFINITY), 0.0);
        // Odd in y, exactly: pairs of hip rolls rely on it.
        for k in 1..100 {
            let (y, x) = (k as f32 * 0.013, 0.31 + k as f32 * 0.07);
            assert_eq!(atan2(-y, x), -atan2(y, x));
        }
    }

    #[test]
    fn atan2_lanes_is_atan2_bit_for_bit() {
        // Every octant, the axes, signed zeros and non-finite lanes among finite ones.
        let mut values: alloc::vec::Vec<f32> = (-40..=40).map(|k| k as f32 * 0.173).collect();
        values.extend([0.0, -0.0, 1e-30, -1e-30, 3e7, f32::INFINITY, f32::NAN]);
        for (n, &y) in values.iter().enumerate() {
            let xs: [f32; 4] = core::array::from_fn(|k| values[(n * 7 + k * 13) % values.len()]);
            let ys = [y, -y, xs[3], 0.5 * y];
            let lanes = atan2_lanes(Vec4::from_array(ys), Vec4::from_array(xs));
            for k in 0..4 {
                assert_eq!(
                    lanes[k].to_bits(),
                    atan2(ys[k], xs[k]).to_bits(),
                    "atan2({}, {})",
                    ys[k],
                    xs[k]
                );
            }
        }
    }

    #[test]
    fn polynomial_sin_cos_match_the_backend() {
        for k in -400..=400 {
            let x = k as f32 * (FRAC_PI_2 / 400.0);
            let (s, c) = sin_cos(x);
            assert!(abs(s - sin(x)) <= 2e-7 && abs(c - cos(x)) <= 2e-7, "{x}");
        }
        for x in [2.0f32, -3.0, 100.0] {
            assert_eq!(sin_cos(x), (sin(x), cos(x)));
        }
        for k in -300..=300 {
            let p = k as f32 * (7.0 / 512.0); // p + 3 is exact
            assert!(
                abs(sin_turns(p) - sin(core::f32::consts::TAU * p)) <= 2e-6,
                "{p}"
            );
            assert_eq!(sin_turns(p), sin_turns(p + 3.0), "{p}");
        }
        assert_eq!(sin_turns(f32::NAN), 0.0);
        // The half turn's shortcut, on every float of `[0, 0.5]` near its branch points and
        // on a grid: the same bits.
        let mut turns: alloc::vec::Vec<f32> = (0..=5000).map(|k| k as f32 * 1e-4).collect();
        for edge in [0.0f32, 0.25, 0.5] {
            let mut x = edge;
            for _ in 0..50 {
                turns.push(x);
                x = f32::from_bits(x.to_bits().saturating_sub(1));
            }
            let mut x = edge;
            for _ in 0..50 {
                turns.push(x);
                x = f32::from_bits(x.to_bits() + 1);
            }
        }
        for t in turns.into_iter().filter(|t| (0.0..=0.5).contains(t)) {
            assert_eq!(sin_half_turn(t).to_bits(), sin_turns(t).to_bits(), "{t}");
        }
        let q = quat_yxz(0.3, -0.2, 0.25);
        let g = glam::Quat::from_euler(glam::EulerRot::YXZ, 0.3, -0.2, 0.25);
        assert!(q.dot(g) > 1.0 - 1e-6);
    }

    #[test]
    fn floor_non_negative_is_the_floor() {
        for x in [
            0.0f32,
            0.25,
            0.999_999_9,
            1.0,
            1.5,
            12_345.678,
            8_388_607.5,
            1e9,
        ] {
            assert_eq!(floor_non_negative(x), floor(x), "{x}");
        }
    }

    #[test]
    fn smoothing_is_a_fraction() {
        assert_eq!(smoothing(0.1, 0.0), 1.0);
        let s = smoothing(0.1, 0.1);
        assert!(s > 0.6 && s < 0.7);
        assert_eq!(smoothing(0.0, 0.1), 0.0);
    }

    #[test]
    fn clamp_sym_removes_nan() {
        assert_eq!(clamp_sym(f32::NAN, 1.0), 0.0);
        assert_eq!(clamp_sym(5.0, 1.0), 1.0);
        assert_eq!(clamp_sym(-5.0, 1.0), -1.0);
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
    fn quat_from_axes_and_lane_roots_are_glams_bit_for_bit() {
        use glam::{Mat3, Quat, Vec2};
        let mut x = 0x1234_5677u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
        };
        for _ in 0..4000 {
            let q = Quat::from_xyzw(next(), next(), next(), next()).normalize();
            let m = Mat3::from_quat(q);
            assert_eq!(
                quat_from_axes(m.x_axis, m.y_axis, m.z_axis),
                Quat::from_mat3(&m)
            );
            let v = Vec4::new(next(), next(), next(), next());
            assert_eq!(sqrt4(v.abs()), v.abs().sqrt());
            assert_eq!(v.unit(), v.normalize());
            let w = Vec2::new(v.x, v.y);
            assert_eq!(w.unit(), w.normalize());
            assert_eq!(w.norm().to_bits(), w.length().to_bits());
        }
    }
}
