//! Value ranges shared by both generators' parameters, and the checks that validate them.

use crate::Error;

/// A float range `[min, max)` a value is drawn from uniformly (`min + U·(max − min)`, `U` in
/// `[0, 1)`); `min == max` gives that value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// Lower end (inclusive).
    pub min: f32,
    /// Upper end (exclusive, unless equal to `min`).
    pub max: f32,
}

impl Span {
    /// A range from `min` to `max`.
    #[must_use]
    pub const fn new(min: f32, max: f32) -> Self {
        Self { min, max }
    }

    /// `min + u·(max − min)`.
    #[must_use]
    pub(crate) fn at(&self, u: f32) -> f32 {
        self.min + u * (self.max - self.min)
    }

    pub(crate) fn check(&self, what: &'static str, lo: f32, hi: f32) -> Result<(), Error> {
        if !self.min.is_finite() || !self.max.is_finite() {
            return Err(Error::NonFinite { what });
        }
        for value in [self.min, self.max] {
            if !(value >= lo && value <= hi) {
                return Err(Error::OutOfRange {
                    what,
                    value,
                    min: lo,
                    max: hi,
                });
            }
        }
        if self.min > self.max {
            return Err(Error::EmptyRange {
                what,
                min: self.min,
                max: self.max,
            });
        }
        Ok(())
    }
}

/// An integer range `min..=max`, drawn the seed's way: `round(min + U·(max − min))`, so the
/// two ends are half as likely as the values between them (3..=6 gives 1/6, 1/3, 1/3, 1/6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IntSpan {
    /// Smallest value.
    pub min: u32,
    /// Largest value.
    pub max: u32,
}

impl IntSpan {
    /// A range from `min` to `max`, both included.
    #[must_use]
    pub const fn new(min: u32, max: u32) -> Self {
        Self { min, max }
    }

    /// `round(min + u·(max − min))`, clamped into the range.
    #[must_use]
    pub(crate) fn at(&self, u: f32) -> u32 {
        let span = self.max.saturating_sub(self.min) as f32;
        (self.min + crate::math::round_non_negative(u * span)).min(self.max)
    }

    pub(crate) fn check(&self, what: &'static str, lo: u32, hi: u32) -> Result<(), Error> {
        for value in [self.min, self.max] {
            count(what, value, lo, hi)?;
        }
        if self.min > self.max {
            return Err(Error::EmptyRange {
                what,
                min: self.min as f32,
                max: self.max as f32,
            });
        }
        Ok(())
    }
}

/// Checks that `value` is finite and in `[min, max]`.
pub(crate) fn scalar(what: &'static str, value: f32, min: f32, max: f32) -> Result<(), Error> {
    if !value.is_finite() {
        return Err(Error::NonFinite { what });
    }
    if !(min..=max).contains(&value) {
        return Err(Error::OutOfRange {
            what,
            value,
            min,
            max,
        });
    }
    Ok(())
}

/// Checks that `value` is in `[min, max]`.
pub(crate) fn count(what: &'static str, value: u32, min: u32, max: u32) -> Result<(), Error> {
    if value < min || value > max {
        return Err(Error::OutOfRange {
            what,
            value: value as f32,
            min: min as f32,
            max: max as f32,
        });
    }
    Ok(())
}
