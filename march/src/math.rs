//! Scalar float helpers for the mesher with a `std` backend and a `libm` backend (libm wins
//! when both are on: its results are the same on every platform), so call sites never branch. Vector math goes through glam, which picks
//! its backend the same way.

#[cfg(all(feature = "std", not(feature = "libm")))]
mod backend {
    pub(crate) fn tan(x: f32) -> f32 {
        x.tan()
    }
    pub(crate) fn atan2(y: f32, x: f32) -> f32 {
        y.atan2(x)
    }
    pub(crate) fn sin_f64(x: f64) -> f64 {
        x.sin()
    }
    pub(crate) fn tan_f64(x: f64) -> f64 {
        x.tan()
    }
}

#[cfg(feature = "libm")]
mod backend {
    pub(crate) fn tan(x: f32) -> f32 {
        libm::tanf(x)
    }
    pub(crate) fn atan2(y: f32, x: f32) -> f32 {
        libm::atan2f(y, x)
    }
    pub(crate) fn sin_f64(x: f64) -> f64 {
        libm::sin(x)
    }
    pub(crate) fn tan_f64(x: f64) -> f64 {
        libm::tan(x)
    }
}

pub(crate) use backend::*;
