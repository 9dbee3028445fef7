//! Falloff functions: how much one ball contributes at a distance from its centre.

use crate::MetaballError;
use crate::ball::validate_radius;
use crate::field::check_epsilon;
use crate::math;

/// The field value that separates inside (`value ≥ ISO_LEVEL`) from outside, for every falloff.
///
/// The seeds test `D(p) ≥ 1.0` everywhere; the falloffs below are scaled so that the same level
/// works for all of them, and [`Falloff::iso_radius`] gives where a lone ball meets it.
pub const ISO_LEVEL: f32 = 1.0;

/// The seeds' blobbiness `B`: the exponential falloff `exp(B r²/R² − B)` with `B = −0.5`.
pub const SEED_BLOBBINESS: f32 = -0.5;

/// Accepted blobbiness for [`Falloff::Exponential`]: from −80 (a sharp ball, peak `e^80`) to
/// −0.001 (a very soft one).
pub const BLOBBINESS_RANGE: (f32, f32) = (-80.0, -1e-3);

/// Accepted range for [`Falloff::Wyvill`]'s peak and [`Falloff::Blinn`]'s strength.
pub const STRENGTH_RANGE: (f32, f32) = (1e-6, 1e6);

/// Accepted range for [`Falloff::Blinn`]'s sharpness.
pub const SHARPNESS_RANGE: (f32, f32) = (1e-3, 80.0);

/// How one ball's contribution falls off with the distance `r` from its centre, for a ball of
/// radius `R`. A field is the sum of its balls' contributions; a point is inside where the sum
/// is at least [`ISO_LEVEL`] (1.0).
///
/// | falloff | `f(r)` | support | lone ball's iso radius |
/// | --- | --- | --- | --- |
/// | `Exponential { blobbiness: B }` (seeds, default) | `exp(B r²/R² − B)` | unbounded | `R` |
/// | `Wyvill { peak: s }` | `s (1 − r²/R²)³` for `r < R`, else 0 | `R` | `R √(1 − s^(−1/3))` (0 if `s ≤ 1`) |
/// | `Blinn { strength: b, sharpness: a }` | `b exp(−a r²/R²)` | unbounded | `R √(ln b / a)` (0 if `b ≤ 1`) |
///
/// The seeds' falloff is Blinn's 1982 "blobby molecule" in his radius/blobbiness form with the
/// threshold 1: `Exponential { blobbiness: B }` equals `Blinn { strength: e^(−B), sharpness:
/// −B }` (up to rounding), and puts the iso line of a lone ball exactly at `R` whatever `B`.
/// `Blinn` frees the two constants. `Wyvill` is the compactly supported soft-object kernel
/// `(1 − r²/R²)³` scaled by its peak; `peak = 2` is the common threshold-½ form.
///
/// Unbounded falloffs are cut off by a field at the radius where a ball's contribution drops
/// below a small epsilon ([`Falloff::cutoff_radius`]); see [`FieldOptions`](crate::FieldOptions).
///
/// ```
/// use creature_metaball::{Falloff, ISO_LEVEL};
///
/// let seed = Falloff::default();
/// assert_eq!(seed, Falloff::SEED);
/// assert_eq!(seed.iso_radius(10.0), 10.0);
/// assert!((seed.evaluate(10.0, 10.0) - ISO_LEVEL).abs() < 1e-6);
///
/// let wyvill = Falloff::WYVILL;
/// let r = wyvill.iso_radius(10.0);
/// assert!((wyvill.evaluate(r, 10.0) - ISO_LEVEL).abs() < 1e-5);
/// assert_eq!(wyvill.evaluate(10.0, 10.0), 0.0); // compact support
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Falloff {
    /// The seeds' `exp(B r²/R² − B)`; `B` in [`BLOBBINESS_RANGE`], the seeds use
    /// [`SEED_BLOBBINESS`] (−0.5). Equals 1 at `r = R` and `e^(−B)` at the centre.
    Exponential {
        /// `B < 0`: closer to zero makes softer balls that merge from further away.
        blobbiness: f32,
    },
    /// Wyvill's compactly supported `s (1 − r²/R²)³`, zero from `r = R` on: exact culling.
    Wyvill {
        /// The value `s` at the centre, in [`STRENGTH_RANGE`]; a lone ball is visible only if
        /// `s > 1`.
        peak: f32,
    },
    /// Blinn's `b exp(−a r²/R²)`.
    Blinn {
        /// `b`, the value at the centre, in [`STRENGTH_RANGE`].
        strength: f32,
        /// `a`, in [`SHARPNESS_RANGE`]: larger falls off faster.
        sharpness: f32,
    },
}

impl Falloff {
    /// The seeds' falloff: `Exponential { blobbiness: -0.5 }`.
    pub const SEED: Self = Self::Exponential {
        blobbiness: SEED_BLOBBINESS,
    };

    /// Wyvill's kernel with peak 2 (the threshold-½ form): a lone ball's iso radius is
    /// `R √(1 − 2^(−1/3)) ≈ 0.454 R`.
    pub const WYVILL: Self = Self::Wyvill { peak: 2.0 };

    /// Blinn's form with strength 2 and sharpness 1: a lone ball's iso radius is
    /// `R √(ln 2) ≈ 0.833 R`.
    pub const BLINN: Self = Self::Blinn {
        strength: 2.0,
        sharpness: 1.0,
    };

    /// Checks the falloff's constants against [`BLOBBINESS_RANGE`], [`STRENGTH_RANGE`] and
    /// [`SHARPNESS_RANGE`].
    ///
    /// # Errors
    /// [`MetaballError::NonFinite`] or [`MetaballError::OutOfRange`] naming the constant.
    pub fn validate(&self) -> Result<(), MetaballError> {
        match *self {
            Self::Exponential { blobbiness } => check("blobbiness", blobbiness, BLOBBINESS_RANGE),
            Self::Wyvill { peak } => check("peak", peak, STRENGTH_RANGE),
            Self::Blinn {
                strength,
                sharpness,
            } => {
                check("strength", strength, STRENGTH_RANGE)?;
                check("sharpness", sharpness, SHARPNESS_RANGE)
            }
        }
    }

    /// A lone ball's contribution at `distance` from its centre, for a ball of `radius`.
    ///
    /// Total, never NaN nor infinite: 0 for a non-finite or non-positive radius, a NaN
    /// distance, or a falloff that fails [`validate`](Self::validate).
    #[must_use]
    pub fn evaluate(&self, distance: f32, radius: f32) -> f32 {
        if !(radius > 0.0) || !radius.is_finite() || distance.is_nan() || self.validate().is_err() {
            return 0.0;
        }
        let q = (distance / radius) * (distance / radius);
        let value = self.kernel().value(q);
        if value.is_finite() { value } else { 0.0 }
    }

    /// The value at a ball's centre: `e^(−B)`, `peak` or `strength`; 0 for a falloff that
    /// fails [`validate`](Self::validate) (whose peak could be infinite or NaN).
    #[must_use]
    pub fn peak(&self) -> f32 {
        if self.validate().is_err() {
            return 0.0;
        }
        self.kernel().value(0.0)
    }

    /// Where the field of a lone ball of `radius` crosses [`ISO_LEVEL`]: its visible radius.
    /// 0 when the ball never reaches the iso level alone (Wyvill peak or Blinn strength ≤ 1).
    ///
    /// Total, never NaN nor infinite: 0 too wherever [`try_iso_radius`](Self::try_iso_radius)
    /// returns an error (a falloff that fails [`validate`](Self::validate), a radius outside
    /// [`RADIUS_RANGE`](crate::RADIUS_RANGE)); use that to tell the cases apart.
    ///
    /// ```
    /// use creature_metaball::Falloff;
    ///
    /// assert_eq!(Falloff::SEED.iso_radius(4.0), 4.0);
    /// // Blinn with sharpness 0 would put the iso line at infinity: rejected, so 0.
    /// let flat = Falloff::Blinn { strength: 2.0, sharpness: 0.0 };
    /// assert_eq!(flat.iso_radius(4.0), 0.0);
    /// assert!(flat.try_iso_radius(4.0).is_err());
    /// ```
    #[must_use]
    pub fn iso_radius(&self, radius: f32) -> f32 {
        self.try_iso_radius(radius).unwrap_or(0.0)
    }

    /// [`iso_radius`](Self::iso_radius), with its inputs checked: the result is finite and
    /// non-negative.
    ///
    /// # Errors
    /// As [`validate`](Self::validate) for the falloff; [`MetaballError::NonFinite`],
    /// [`MetaballError::NotPositive`] or [`MetaballError::OutOfRange`] for a radius that is
    /// not finite, not positive or outside [`RADIUS_RANGE`](crate::RADIUS_RANGE) (`what:
    /// "ball radius"`).
    pub fn try_iso_radius(&self, radius: f32) -> Result<f32, MetaballError> {
        self.validate()?;
        validate_radius(radius, 0)?;
        // With the constants and the radius in range every branch is finite: at most
        // 1e9 · √(ln 1e6 / 1e-3) ≈ 1.2e11.
        Ok(match *self {
            Self::Exponential { .. } => radius,
            Self::Wyvill { peak } => {
                if peak > 1.0 {
                    radius * math::sqrt(1.0 - 1.0 / math::cbrt(peak))
                } else {
                    0.0
                }
            }
            Self::Blinn {
                strength,
                sharpness,
            } => {
                if strength > 1.0 {
                    radius * math::sqrt(math::ln(strength) / sharpness)
                } else {
                    0.0
                }
            }
        })
    }

    /// The distance beyond which a ball of `radius` contributes less than `epsilon` (and is
    /// skipped by a culled field). `radius` itself for `Wyvill`, whose support ends there; 0 for
    /// a `Blinn` ball whose strength is already at most `epsilon`.
    ///
    /// Total, never NaN nor infinite: 0 too wherever
    /// [`try_cutoff_radius`](Self::try_cutoff_radius) returns an error (a falloff that fails
    /// [`validate`](Self::validate), a radius outside [`RADIUS_RANGE`](crate::RADIUS_RANGE), an
    /// epsilon outside [`EPSILON_RANGE`](crate::EPSILON_RANGE)).
    ///
    /// ```
    /// use creature_metaball::{DEFAULT_EPSILON, Falloff};
    ///
    /// let rc = Falloff::SEED.cutoff_radius(10.0, DEFAULT_EPSILON);
    /// assert!((rc - 44.1).abs() < 0.1); // R √(1 + ln ε / B)
    /// // Blobbiness 0 would divide by zero: rejected, so 0.
    /// let flat = Falloff::Exponential { blobbiness: 0.0 };
    /// assert_eq!(flat.cutoff_radius(10.0, DEFAULT_EPSILON), 0.0);
    /// assert!(flat.try_cutoff_radius(10.0, DEFAULT_EPSILON).is_err());
    /// ```
    #[must_use]
    pub fn cutoff_radius(&self, radius: f32, epsilon: f32) -> f32 {
        self.try_cutoff_radius(radius, epsilon).unwrap_or(0.0)
    }

    /// [`cutoff_radius`](Self::cutoff_radius), with its inputs checked: the result is finite
    /// and non-negative.
    ///
    /// # Errors
    /// As [`try_iso_radius`](Self::try_iso_radius), plus [`MetaballError::NonFinite`] or
    /// [`MetaballError::OutOfRange`] for an epsilon outside
    /// [`EPSILON_RANGE`](crate::EPSILON_RANGE) (`what: "epsilon"`).
    pub fn try_cutoff_radius(&self, radius: f32, epsilon: f32) -> Result<f32, MetaballError> {
        self.validate()?;
        validate_radius(radius, 0)?;
        check_epsilon(epsilon)?;
        // In range, `cutoff_q` is at most 1 + ln(1e-12) / −1e-3 ≈ 2.8e4 (exponential) or
        // ln(1e6 / 1e-12) / 1e-3 ≈ 4.1e4 (Blinn): the result stays below 1e9 · 204.
        Ok(radius * math::sqrt(self.kernel().cutoff_q(epsilon)))
    }

    /// Whether the falloff is exactly zero beyond a finite radius (so culling is exact).
    #[must_use]
    pub const fn has_compact_support(&self) -> bool {
        matches!(self, Self::Wyvill { .. })
    }

    pub(crate) fn kernel(&self) -> Kernel {
        match *self {
            Self::Exponential { blobbiness } => Kernel::Exponential { b: blobbiness },
            Self::Wyvill { peak } => Kernel::Wyvill { peak },
            Self::Blinn {
                strength,
                sharpness,
            } => Kernel::Gauss {
                strength,
                sharpness,
            },
        }
    }
}

impl Default for Falloff {
    /// [`Falloff::SEED`].
    fn default() -> Self {
        Self::SEED
    }
}

fn check(what: &'static str, value: f32, (min, max): (f32, f32)) -> Result<(), MetaballError> {
    if !value.is_finite() {
        return Err(MetaballError::NonFinite { what, index: 0 });
    }
    if !(value >= min && value <= max) {
        return Err(MetaballError::OutOfRange {
            what,
            index: 0,
            value,
            min,
            max,
        });
    }
    Ok(())
}

/// A falloff as a function of `q = r²/R²`, the form the field's inner loops use.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Kernel {
    Exponential { b: f32 },
    Gauss { strength: f32, sharpness: f32 },
    Wyvill { peak: f32 },
}

impl Kernel {
    /// `f(q)`.
    #[inline(always)]
    pub(crate) fn value(self, q: f32) -> f32 {
        match self {
            Self::Exponential { b } => math::exp(b * q - b),
            Self::Gauss {
                strength,
                sharpness,
            } => strength * math::exp(-sharpness * q),
            Self::Wyvill { peak } => {
                if q < 1.0 {
                    let t = 1.0 - q;
                    peak * t * t * t
                } else {
                    0.0
                }
            }
        }
    }

    /// `(f(q), 2 f'(q))`: the gradient with respect to `p` is `2 f'(q) (p − c) / R²`.
    #[inline(always)]
    pub(crate) fn value_and_slope(self, q: f32) -> (f32, f32) {
        match self {
            Self::Exponential { b } => {
                let f = math::exp(b * q - b);
                (f, 2.0 * b * f)
            }
            Self::Gauss {
                strength,
                sharpness,
            } => {
                let f = strength * math::exp(-sharpness * q);
                (f, -2.0 * sharpness * f)
            }
            Self::Wyvill { peak } => {
                if q < 1.0 {
                    let t = 1.0 - q;
                    (peak * t * t * t, -6.0 * peak * t * t)
                } else {
                    (0.0, 0.0)
                }
            }
        }
    }

    /// `(s, a)` of a Gaussian kernel written `s exp(−a q)` (`Exponential { b }` is
    /// `e^(−b) exp(b q)`); `None` for Wyvill's.
    pub(crate) fn gaussian(self) -> Option<(f32, f32)> {
        match self {
            Self::Exponential { b } => Some((math::exp(-b), -b)),
            Self::Gauss {
                strength,
                sharpness,
            } => Some((strength, sharpness)),
            Self::Wyvill { .. } => None,
        }
    }

    /// `q_c = r_c²/R²` beyond which `f(q) < epsilon` (`0 < epsilon < 1`).
    pub(crate) fn cutoff_q(self, epsilon: f32) -> f32 {
        match self {
            // exp(B(q − 1)) = ε  ⇔  q = 1 + ln ε / B.
            Self::Exponential { b } => 1.0 + math::ln(epsilon) / b,
            // b exp(−a q) = ε  ⇔  q = ln(b/ε) / a.
            Self::Gauss {
                strength,
                sharpness,
            } => {
                if strength > epsilon {
                    math::ln(strength / epsilon) / sharpness
                } else {
                    0.0
                }
            }
            Self::Wyvill { .. } => 1.0,
        }
    }

    /// The largest value one ball can contribute beyond its cutoff: the value error bound per
    /// ball.
    pub(crate) fn value_error(self, epsilon: f32) -> f32 {
        match self {
            Self::Exponential { .. } => epsilon,
            Self::Gauss { strength, .. } => strength.min(epsilon),
            Self::Wyvill { .. } => 0.0,
        }
    }

    /// [`gradient_error_scale`](Self::gradient_error_scale) for one radius.
    #[cfg(test)]
    pub(crate) fn gradient_error(self, epsilon: f32, radius: f32) -> f32 {
        self.gradient_error_scale(epsilon) / radius
    }

    /// The largest gradient magnitude one ball of radius `R` can contribute beyond its cutoff
    /// (the gradient error bound per ball), times `R`: the bound is this divided by `R`,
    /// so a field computes it once.
    ///
    /// For a Gaussian `s exp(−a q)` the magnitude is `s exp(−a r²/R²) 2 a r / R²`, which grows
    /// up to `r* = R / √(2a)` and falls after, so its supremum over `r ≥ r_c` is its value at
    /// `max(r_c, r*)`: `s exp(−a q) 2 a √q / R` with `q = max(q_c, 1/(2a))`.
    pub(crate) fn gradient_error_scale(self, epsilon: f32) -> f32 {
        let Some((strength, sharpness)) = self.gaussian() else {
            return 0.0;
        };
        let q = self.cutoff_q(epsilon).max(0.5 / sharpness);
        strength * math::exp(-sharpness * q) * 2.0 * sharpness * math::sqrt(q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_lone_ball_meets_the_iso_level_at_its_documented_radius() {
        for falloff in [
            Falloff::SEED,
            Falloff::Exponential { blobbiness: -2.0 },
            Falloff::WYVILL,
            Falloff::Wyvill { peak: 8.0 },
            Falloff::BLINN,
            Falloff::Blinn {
                strength: 5.0,
                sharpness: 0.3,
            },
        ] {
            let r = falloff.iso_radius(7.0);
            assert!(r > 0.0, "{falloff:?}");
            let v = falloff.evaluate(r, 7.0);
            assert!((v - ISO_LEVEL).abs() < 1e-5, "{falloff:?}: {v}");
            assert!(falloff.evaluate(r * 0.99, 7.0) > ISO_LEVEL);
            assert!(falloff.evaluate(r * 1.01, 7.0) < ISO_LEVEL);
        }
        assert_eq!(Falloff::Wyvill { peak: 1.0 }.iso_radius(3.0), 0.0);
        assert_eq!(
            Falloff::Blinn {
                strength: 0.5,
                sharpness: 1.0
            }
            .iso_radius(3.0),
            0.0
        );
    }

    #[test]
    fn seed_falloff_matches_the_seed_constants() {
        // 1 at r = R, e^0.5 at the centre.
        assert!((Falloff::SEED.evaluate(3.0, 3.0) - 1.0).abs() < 1e-6);
        assert!((Falloff::SEED.peak() - 1.648_721_3).abs() < 1e-6);
        // Two equal balls just touch at a spacing of 2·√(1 + 2 ln 2)·R ≈ 3.09 R (reference §2.4).
        let half = (1.0f32 + 2.0 * core::f32::consts::LN_2).sqrt();
        assert!((2.0 * Falloff::SEED.evaluate(half, 1.0) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn exponential_is_blinn_in_the_radius_blobbiness_form() {
        let blinn = Falloff::Blinn {
            strength: 0.5f32.exp(),
            sharpness: 0.5,
        };
        for i in 0..50 {
            let r = i as f32 * 0.1;
            let a = Falloff::SEED.evaluate(r, 1.3);
            let b = blinn.evaluate(r, 1.3);
            assert!((a - b).abs() <= 1e-6 * a.max(1e-30), "{r}: {a} vs {b}");
        }
    }

    #[test]
    fn cutoff_is_where_the_contribution_drops_to_epsilon() {
        for falloff in [Falloff::SEED, Falloff::BLINN] {
            let rc = falloff.cutoff_radius(4.0, 1e-4);
            assert!(
                (falloff.evaluate(rc, 4.0) - 1e-4).abs() < 1e-8,
                "{falloff:?}"
            );
        }
        assert_eq!(Falloff::WYVILL.cutoff_radius(4.0, 1e-4), 4.0);
        // A Blinn ball weaker than epsilon is culled entirely.
        let weak = Falloff::Blinn {
            strength: 1e-5,
            sharpness: 1.0,
        };
        assert_eq!(weak.cutoff_radius(4.0, 1e-4), 0.0);
    }

    #[test]
    fn slope_is_the_derivative() {
        for falloff in [Falloff::SEED, Falloff::WYVILL, Falloff::BLINN] {
            let k = falloff.kernel();
            for q in [0.1f32, 0.5, 0.9, 2.0] {
                let h = 1e-3;
                let numeric = (k.value(q + h) - k.value(q - h)) / (2.0 * h);
                let (_, slope2) = k.value_and_slope(q);
                assert!(
                    (slope2 / 2.0 - numeric).abs() < 1e-3 * (1.0 + numeric.abs()),
                    "{falloff:?} at {q}: {slope2} vs {numeric}"
                );
            }
        }
    }

    #[test]
    fn gradient_error_bounds_the_gradient_beyond_the_cutoff() {
        for falloff in [
            Falloff::SEED,
            Falloff::BLINN,
            Falloff::Exponential { blobbiness: -0.01 },
        ] {
            let k = falloff.kernel();
            let radius = 2.5;
            let bound = k.gradient_error(1e-3, radius);
            let rc = falloff.cutoff_radius(radius, 1e-3);
            for i in 0..400 {
                let r = rc + i as f32 * 0.05;
                let q = (r / radius) * (r / radius);
                let (_, slope2) = k.value_and_slope(q);
                let magnitude = (slope2 * r / (radius * radius)).abs();
                assert!(
                    magnitude <= bound * 1.0001,
                    "{falloff:?} at {r}: {magnitude} > {bound}"
                );
            }
        }
    }

    #[test]
    fn validation_rejects_bad_constants() {
        assert!(Falloff::SEED.validate().is_ok());
        assert!(Falloff::WYVILL.validate().is_ok());
        assert!(Falloff::BLINN.validate().is_ok());
        assert!(matches!(
            Falloff::Exponential { blobbiness: 0.5 }.validate(),
            Err(MetaballError::OutOfRange {
                what: "blobbiness",
                ..
            })
        ));
        assert!(matches!(
            Falloff::Wyvill { peak: f32::NAN }.validate(),
            Err(MetaballError::NonFinite { what: "peak", .. })
        ));
        assert!(matches!(
            Falloff::Blinn {
                strength: 2.0,
                sharpness: 0.0
            }
            .validate(),
            Err(MetaballError::OutOfRange {
                what: "sharpness",
                ..
            })
        ));
    }

    /// Regression: `iso_radius` and `cutoff_radius` did not validate, so Blinn with sharpness
    /// 0 put the iso line at infinity, exponential blobbiness 0 gave a NaN cutoff, and a NaN
    /// radius gave NaN.
    #[test]
    fn radii_of_rejected_inputs_are_errors_and_zero_never_nan() {
        let flat_blinn = Falloff::Blinn {
            strength: 2.0,
            sharpness: 0.0,
        };
        assert!(matches!(
            flat_blinn.try_iso_radius(3.0),
            Err(MetaballError::OutOfRange {
                what: "sharpness",
                ..
            })
        ));
        assert_eq!(flat_blinn.iso_radius(3.0), 0.0);
        let flat_exp = Falloff::Exponential { blobbiness: 0.0 };
        assert!(matches!(
            flat_exp.try_cutoff_radius(3.0, 1e-4),
            Err(MetaballError::OutOfRange {
                what: "blobbiness",
                ..
            })
        ));
        assert_eq!(flat_exp.cutoff_radius(3.0, 1e-4), 0.0);
        assert_eq!(
            Falloff::SEED.try_iso_radius(f32::NAN),
            Err(MetaballError::NonFinite {
                what: "ball radius",
                index: 0
            })
        );
        assert_eq!(Falloff::SEED.iso_radius(f32::NAN), 0.0);
        assert!(matches!(
            Falloff::SEED.try_cutoff_radius(3.0, 0.0),
            Err(MetaballError::OutOfRange {
                what: "epsilon",
                ..
            })
        ));
        assert!(matches!(
            Falloff::SEED.try_cutoff_radius(3.0, f32::NAN),
            Err(MetaballError::NonFinite {
                what: "epsilon",
                ..
            })
        ));
        assert!(matches!(
            Falloff::WYVILL.try_cutoff_radius(-1.0, 1e-4),
            Err(MetaballError::NotPositive { .. })
        ));
        // An extreme but rejected blobbiness would have an infinite peak.
        assert_eq!(Falloff::Exponential { blobbiness: -1e3 }.peak(), 0.0);
        assert_eq!(
            Falloff::Exponential { blobbiness: -1e3 }.evaluate(0.0, 1.0),
            0.0
        );
        // Valid inputs give the same radii as before.
        assert_eq!(Falloff::SEED.try_iso_radius(3.0), Ok(3.0));
        assert_eq!(Falloff::WYVILL.try_cutoff_radius(4.0, 1e-4), Ok(4.0));
    }

    #[test]
    fn radii_are_finite_for_every_combination_of_edge_inputs() {
        let specials = [
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            0.0,
            -0.0,
            -1.0,
            f32::MIN_POSITIVE,
            1e-12,
            1e-6,
            1e-3,
            0.5,
            1.0,
            80.0,
            1e6,
            1e9,
            f32::MAX,
        ];
        let mut falloffs = alloc::vec::Vec::new();
        for &a in &specials {
            falloffs.push(Falloff::Exponential { blobbiness: a });
            falloffs.push(Falloff::Exponential { blobbiness: -a });
            falloffs.push(Falloff::Wyvill { peak: a });
            for &b in &specials {
                falloffs.push(Falloff::Blinn {
                    strength: a,
                    sharpness: b,
                });
            }
        }
        for falloff in falloffs {
            assert!(falloff.peak().is_finite(), "{falloff:?}");
            for &radius in &specials {
                let iso = falloff.iso_radius(radius);
                assert!(iso.is_finite() && iso >= 0.0, "{falloff:?} {radius}: {iso}");
                assert_eq!(
                    falloff.try_iso_radius(radius).is_ok(),
                    falloff.validate().is_ok() && validate_radius(radius, 0).is_ok()
                );
                for &epsilon in &specials {
                    let rc = falloff.cutoff_radius(radius, epsilon);
                    assert!(
                        rc.is_finite() && rc >= 0.0,
                        "{falloff:?} {radius} {epsilon}"
                    );
                    if let Ok(rc) = falloff.try_cutoff_radius(radius, epsilon) {
                        assert!(rc.is_finite() && rc >= 0.0);
                    }
                }
                for &distance in &specials {
                    assert!(falloff.evaluate(distance, radius).is_finite());
                }
            }
        }
    }

    #[test]
    fn evaluate_never_returns_nan() {
        assert_eq!(Falloff::SEED.evaluate(f32::NAN, 1.0), 0.0);
        assert_eq!(Falloff::SEED.evaluate(1.0, 0.0), 0.0);
        assert_eq!(Falloff::SEED.evaluate(1.0, f32::NAN), 0.0);
        assert_eq!(Falloff::SEED.evaluate(f32::INFINITY, 1.0), 0.0);
    }
}
