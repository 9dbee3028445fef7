//! Proptest strategies for this crate's inputs (feature `proptest`).
//!
//! Valid inputs — metaball-like fields ([`blobs`], [`separated_blobs`], [`annulus`]), sampled
//! grids ([`grid`]) and simple rings ([`star_ring`]) — and adversarial ones for the error
//! paths ([`non_finite_f32`], [`bad_step`], [`bad_grid`], [`self_intersecting_ring`],
//! [`crossing_rings`]), so a downstream property suite can generate them the way this crate's
//! own suite does. The fields are plain structs with a `value` method, so they work as the
//! closure `|p| blobs.value(p)` for [`trace`](crate::trace) without any metaball crate.
//!
//! ```
//! use creature_march::{strategies, trace};
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::deterministic();
//! runner.run(&strategies::separated_blobs(1..4), |blobs| {
//!     let rings = trace(|p| blobs.value(p), &blobs.centres(), 2.0, 1.0).unwrap();
//!     prop_assert_eq!(rings.len(), blobs.balls.len());
//!     Ok(())
//! }).unwrap();
//! ```

use alloc::vec::Vec;
use core::ops::Range;

use glam::Vec2;
use proptest::prelude::*;

use crate::Ring;

/// A sum of the seed's metaballs, `Σ exp(0.5 − 0.5·d²/R²)`, inside where `>= 1` (a lone
/// ball's inside is its disc of radius `R`).
#[derive(Debug, Clone, PartialEq)]
pub struct Blobs {
    /// `(centre, radius)` of every ball.
    pub balls: Vec<(Vec2, f32)>,
}

impl Blobs {
    /// The iso-level of this field.
    pub const ISO: f32 = 1.0;

    /// The field at `p`.
    #[must_use]
    pub fn value(&self, p: Vec2) -> f32 {
        self.balls
            .iter()
            .map(|&(c, r)| (0.5 - 0.5 * p.distance_squared(c) / (r * r)).exp())
            .sum()
    }

    /// The ball centres: the hints that find every component.
    #[must_use]
    pub fn centres(&self) -> Vec<Vec2> {
        self.balls.iter().map(|&(c, _)| c).collect()
    }
}

/// An annulus field: inside (`>= 0`) between radii `inner` and `outer` around `centre`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Annulus {
    /// Centre of both circles.
    pub centre: Vec2,
    /// Radius of the hole.
    pub inner: f32,
    /// Outer radius.
    pub outer: f32,
}

impl Annulus {
    /// The iso-level of this field.
    pub const ISO: f32 = 0.0;

    /// The field at `p`: the distance inside the band (negative outside it).
    #[must_use]
    pub fn value(&self, p: Vec2) -> f32 {
        let d = p.distance(self.centre);
        (d - self.inner).min(self.outer - d)
    }

    /// A point in the middle of the band, a hint for [`trace`](crate::trace).
    #[must_use]
    pub fn hint(&self) -> Vec2 {
        self.centre + Vec2::X * (0.5 * (self.inner + self.outer))
    }
}

/// A point with both coordinates in `[-range, range]`.
pub fn vec2_in(range: f32) -> impl Strategy<Value = Vec2> {
    (-range..=range, -range..=range).prop_map(|(x, y)| Vec2::new(x, y))
}

/// `count` balls with centres in `[-100, 100]²` and radii from 4 to 20, touching or not.
pub fn blobs(count: Range<usize>) -> impl Strategy<Value = Blobs> {
    proptest::collection::vec((vec2_in(100.0), 4.0f32..20.0), count)
        .prop_map(|balls| Blobs { balls })
}

/// `count` balls, radii 4 to 12, on a row spaced 60 apart (so each is its own component),
/// jittered by up to 5 in each direction.
pub fn separated_blobs(count: Range<usize>) -> impl Strategy<Value = Blobs> {
    proptest::collection::vec((vec2_in(5.0), 4.0f32..12.0), count).prop_map(|balls| Blobs {
        balls: balls
            .into_iter()
            .enumerate()
            .map(|(i, (jitter, r))| (Vec2::new(60.0 * i as f32, 0.0) + jitter, r))
            .collect(),
    })
}

/// An annulus with the centre in `[-50, 50]²`, hole radius 5 to 20 and band width 5 to 20.
pub fn annulus() -> impl Strategy<Value = Annulus> {
    (vec2_in(50.0), 5.0f32..20.0, 5.0f32..20.0).prop_map(|(centre, inner, width)| Annulus {
        centre,
        inner,
        outer: inner + width,
    })
}

/// A sampled grid `(values, width, height)`, 1 to 24 samples per side, values in `[-1, 1]`
/// with about one in twenty NaN (outside).
pub fn grid() -> impl Strategy<Value = (Vec<f32>, usize, usize)> {
    (1usize..=24, 1usize..=24).prop_flat_map(|(w, h)| {
        let value = prop_oneof![19 => -1.0f32..1.0, 1 => Just(f32::NAN)];
        (proptest::collection::vec(value, w * h), Just(w), Just(h))
    })
}

/// A grid whose sample count does not match `width × height`.
pub fn bad_grid() -> impl Strategy<Value = (Vec<f32>, usize, usize)> {
    (1usize..=16, 1usize..=16, 1usize..=8, any::<bool>()).prop_map(|(w, h, off, more)| {
        let n = if more {
            w * h + off
        } else {
            (w * h).saturating_sub(off)
        };
        let n = if n == w * h { n + 1 } else { n };
        (alloc::vec![0.0; n], w, h)
    })
}

/// A float that is NaN or ±infinity.
pub fn non_finite_f32() -> impl Strategy<Value = f32> {
    prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY)]
}

/// A step [`trace`](crate::trace) rejects: zero, negative or not finite.
pub fn bad_step() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(-0.0f32),
        -100.0f32..-1e-6,
        non_finite_f32()
    ]
}

/// A simple counter-clockwise star-shaped ring: 3 to 40 vertices at increasing angles around a
/// centre in `[-100, 100]²`, radii 5 to 50.
pub fn star_ring() -> impl Strategy<Value = Ring> {
    (
        vec2_in(100.0),
        proptest::collection::vec(5.0f32..50.0, 3..40),
    )
        .prop_map(|(c, radii)| {
            let n = radii.len() as f32;
            let points = radii
                .iter()
                .enumerate()
                .map(|(i, &r)| {
                    let a = core::f32::consts::TAU * i as f32 / n;
                    c + Vec2::new(a.cos(), a.sin()) * r
                })
                .collect();
            Ring {
                points,
                hole: false,
                parent: None,
            }
        })
}

/// A ring that intersects itself: a bow tie, a repeated point, or a spike folding back.
pub fn self_intersecting_ring() -> impl Strategy<Value = Ring> {
    (vec2_in(100.0), 1.0f32..50.0, 0usize..3).prop_map(|(o, s, kind)| {
        let points = match kind {
            0 => alloc::vec![o, o + Vec2::splat(s), o + Vec2::X * s, o + Vec2::Y * s],
            1 => alloc::vec![o, o, o + Vec2::X * s, o + Vec2::Y * s],
            _ => alloc::vec![o, o + Vec2::X * (2.0 * s), o + Vec2::X * s, o + Vec2::Y * s],
        };
        Ring {
            points,
            hole: false,
            parent: None,
        }
    })
}

/// Two overlapping squares (their edges cross).
pub fn crossing_rings() -> impl Strategy<Value = Vec<Ring>> {
    (vec2_in(100.0), 2.0f32..50.0, 0.1f32..0.9).prop_map(|(o, s, f)| {
        let square = |o: Vec2| Ring {
            points: alloc::vec![o, o + Vec2::X * s, o + Vec2::splat(s), o + Vec2::Y * s],
            hole: false,
            parent: None,
        };
        alloc::vec![square(o), square(o + Vec2::splat(s * f))]
    })
}
