//! The two shaping curves of a step: how far a foot may stray in each direction
//! ([`ReachCurve`]) and how high it lifts along a step ([`HeightCurve`]).

use crate::math::sin_half_turn;

/// How far a planted foot may stray from its rest position before the leg steps, as a function
/// of direction, in units of the leg's [`size`](crate::Leg::size).
///
/// The argument is the dot product `d ∈ [−1, 1]` of the unit stray direction with the body's
/// forward axis: −1 straight back, 0 sideways, 1 straight forward (the Trifox article's
/// animation curve). The same curve sizes the overshoot along the motion direction.
/// Two `Custom` curves compare equal when they hold the same function pointer.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub enum ReachCurve {
    /// Piecewise linear through `back` at −1, `side` at 0 and `front` at 1.
    Linear {
        /// Reach straight backwards.
        back: f32,
        /// Reach sideways.
        side: f32,
        /// Reach straight forwards.
        front: f32,
    },
    /// Any function of `d`. Outputs are clamped to `[0.01, 10]`; NaN gives 0.01.
    Custom(fn(f32) -> f32),
}

impl ReachCurve {
    /// The default: 0.45 back, 0.375 sideways, 0.3 forward (1.5 : 1 back to front, the
    /// article's example, scaled to a leg's length).
    pub const DEFAULT: Self = Self::Linear {
        back: 0.45,
        side: 0.375,
        front: 0.3,
    };

    /// The reach for direction `d` (clamped into `[−1, 1]`); always finite, in `[0.01, 10]`.
    #[must_use]
    #[inline]
    pub fn evaluate(&self, d: f32) -> f32 {
        let d = if d.is_nan() { 0.0 } else { d.clamp(-1.0, 1.0) };
        let value = match *self {
            Self::Linear { back, side, front } => {
                if d < 0.0 {
                    side + (side - back) * d
                } else {
                    side + (front - side) * d
                }
            }
            Self::Custom(f) => f(d),
        };
        if value.is_nan() {
            0.01
        } else {
            value.clamp(0.01, 10.0)
        }
    }

    /// The largest value over `d ∈ [−1, 1]` (exact for `Linear`, sampled for `Custom`).
    #[must_use]
    pub fn max_value(&self) -> f32 {
        match *self {
            Self::Linear { .. } => self
                .evaluate(-1.0)
                .max(self.evaluate(0.0))
                .max(self.evaluate(1.0)),
            Self::Custom(_) => (0..=32)
                .map(|k| self.evaluate(-1.0 + k as f32 / 16.0))
                .fold(0.01, f32::max),
        }
    }
}

impl PartialEq for ReachCurve {
    fn eq(&self, other: &Self) -> bool {
        match (*self, *other) {
            (
                Self::Linear { back, side, front },
                Self::Linear {
                    back: b,
                    side: s,
                    front: f,
                },
            ) => back == b && side == s && front == f,
            (Self::Custom(a), Self::Custom(b)) => core::ptr::fn_addr_eq(a, b),
            _ => false,
        }
    }
}

impl Default for ReachCurve {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// How high a stepping foot is lifted along the step, in units of the step height, as a
/// function of the step's progress `t ∈ [0, 1]`.
/// Two `Custom` curves compare equal when they hold the same function pointer.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub enum HeightCurve {
    /// `sin(π t)`: the seeds' arc.
    Sine,
    /// `4 t (1 − t)`: a parabola, slightly fuller at the ends.
    Parabola,
    /// Any function of `t`. Outputs are clamped to `[−1, 4]`; NaN gives 0. The foot lands
    /// exactly on its target at `t = 1` whatever the curve says there.
    Custom(fn(f32) -> f32),
}

impl HeightCurve {
    /// The default, [`HeightCurve::Sine`].
    pub const DEFAULT: Self = Self::Sine;

    /// The lift at progress `t` (clamped into `[0, 1]`); always finite.
    #[must_use]
    #[inline]
    pub fn evaluate(&self, t: f32) -> f32 {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        let value = match *self {
            // `t` is in [0, 1] here.
            Self::Sine => sin_half_turn(0.5 * t),
            Self::Parabola => 4.0 * t * (1.0 - t),
            Self::Custom(f) => f(t),
        };
        if value.is_nan() {
            0.0
        } else {
            value.clamp(-1.0, 4.0)
        }
    }
}

impl PartialEq for HeightCurve {
    fn eq(&self, other: &Self) -> bool {
        match (*self, *other) {
            (Self::Sine, Self::Sine) | (Self::Parabola, Self::Parabola) => true,
            (Self::Custom(a), Self::Custom(b)) => core::ptr::fn_addr_eq(a, b),
            _ => false,
        }
    }
}

impl Default for HeightCurve {
    fn default() -> Self {
        Self::DEFAULT
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_reach_is_longer_backwards() {
        let c = ReachCurve::DEFAULT;
        assert_eq!(c.evaluate(-1.0), 0.45);
        assert_eq!(c.evaluate(1.0), 0.3);
        assert!((c.evaluate(0.0) - 0.375).abs() < 1e-7);
        assert!(c.evaluate(-0.5) > c.evaluate(0.5));
        assert_eq!(c.evaluate(7.0), 0.3);
        assert_eq!(c.max_value(), 0.45);
    }

    #[test]
    fn custom_curves_are_sanitised() {
        let c = ReachCurve::Custom(|_| f32::NAN);
        assert_eq!(c.evaluate(0.0), 0.01);
        let c = ReachCurve::Custom(|d| 100.0 * d);
        assert_eq!(c.evaluate(1.0), 10.0);
        assert_eq!(c.max_value(), 10.0);
        let h = HeightCurve::Custom(|_| f32::INFINITY);
        assert_eq!(h.evaluate(0.5), 4.0);
        let h = HeightCurve::Custom(|_| f32::NAN);
        assert_eq!(h.evaluate(0.5), 0.0);
    }

    #[test]
    fn height_curves_peak_mid_step() {
        for c in [HeightCurve::Sine, HeightCurve::Parabola] {
            assert!(c.evaluate(0.0).abs() < 1e-6);
            assert!((c.evaluate(0.5) - 1.0).abs() < 1e-6);
            assert!(c.evaluate(1.0).abs() < 1e-6);
        }
    }
}
