//! Covering a bone with balls, exactly as the 2D seed does.

use alloc::vec::Vec;

use glam::{Vec2, Vec3};

use crate::ball::MAX_COORDINATE;
use crate::math;
use crate::{Ball2, Ball3, MetaballError};

/// The seeds' ball spacing in thicknesses at multiplier 1: `2.97 T`, just under the `3.13 R`
/// at which two seed balls stop touching.
pub const SEED_SPACING: f32 = 2.97;

/// Accepted smoothness multipliers: 1 (beads) to 1.6 (a smooth tube), both inclusive.
pub const MULTIPLIER_RANGE: (f32, f32) = (1.0, 1.6);

/// The seed's multiplier for bones that have none.
pub const SEED_MULTIPLIER: f32 = 1.6;

/// Accepted bone thicknesses (the resulting radii stay within
/// [`RADIUS_RANGE`](crate::RADIUS_RANGE)).
pub const THICKNESS_RANGE: (f32, f32) = (1e-5, 1e9);

/// The most balls one covering may produce.
pub const MAX_COVER_BALLS: usize = 1 << 16;

/// How [`cover_segment_with`] treats the segment's ends.
///
/// ```
/// use creature_metaball::CoverOptions;
///
/// let joint = CoverOptions::DEFAULT.with_interior_joint(true);
/// assert!(joint.interior_joint);
/// assert!(!CoverOptions::default().interior_joint);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct CoverOptions {
    /// `to` is an interior joint, shared with the next segment towards the root, which puts
    /// its own ball there: the last ball then sits half a step short of `to` (the seed's
    /// last-ball rule, applied whenever the parent bone is not the root), avoiding a double
    /// ball at every joint. Default: `false` (balls at both tips).
    pub interior_joint: bool,
}

impl CoverOptions {
    /// Balls at both tips.
    pub const DEFAULT: Self = Self {
        interior_joint: false,
    };

    /// Sets [`interior_joint`](Self::interior_joint).
    #[must_use]
    pub const fn with_interior_joint(mut self, interior_joint: bool) -> Self {
        self.interior_joint = interior_joint;
        self
    }
}

impl Default for CoverOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The seed's radius factor for a multiplier: `m / √(2 ln(m²) + 1)`; 1 at `m = 1`, about
/// 0.913 at 1.2 and 0.943 at 1.6. A covering's ball radius is `thickness` times this.
#[must_use]
pub fn cover_radius_factor(multiplier: f32) -> f32 {
    multiplier / math::sqrt(2.0 * math::ln(multiplier * multiplier) + 1.0)
}

/// Covers the segment `from → to` with balls of the seed falloff, exactly as the 2D seed does
/// (reference §2.4), balls at both tips. See [`cover_segment_with`].
///
/// ```
/// use creature_metaball::{cover_segment, Falloff, Field2, glam::Vec2};
///
/// let balls = cover_segment(Vec2::ZERO, Vec2::new(100.0, 0.0), 10.0, 1.6, 7)?;
/// assert_eq!(balls.len(), 7); // ceil(100 / 29.7 × 1.6) = 6 steps, 7 balls
/// assert!(balls.iter().all(|b| b.id == 7));
/// let field = Field2::new(&balls, Falloff::SEED)?;
/// assert!(field.contains(Vec2::new(50.0, 9.0)));  // about T thick…
/// assert!(!field.contains(Vec2::new(50.0, 13.0))); // …and no more
/// # Ok::<(), creature_metaball::MetaballError>(())
/// ```
///
/// # Errors
/// As [`cover_segment_with`].
pub fn cover_segment(
    from: Vec2,
    to: Vec2,
    thickness: f32,
    multiplier: f32,
    id: u32,
) -> Result<Vec<Ball2>, MetaballError> {
    cover_segment_with(from, to, thickness, multiplier, id, &CoverOptions::DEFAULT)
}

/// Covers the segment `from → to` with balls, exactly as the 2D seed covers a bone (reference
/// §2.4, thesis §4.2):
///
/// - radius `R = thickness · m / √(2 ln(m²) + 1)` ([`cover_radius_factor`]);
/// - `n = ⌈|to − from| / (2.97 · thickness) · m⌉` steps, so the spacing `|to − from| / n` is at
///   most `2.97 · thickness / m`;
/// - `n + 1` balls at `from + (to − from) · j/n`, `j = 0..=n`, both tips included, in that
///   order; with [`CoverOptions::interior_joint`] the last one at `(n − ½)/n` instead.
///
/// Every ball gets `id`. To lerp per-ball attributes the seed's way (its colours), use the
/// same `α_j`. The seed calls this with `from` = the bone's own (child) end and `to` = its
/// parent joint, `id` = the parent bone, `multiplier` 1.6 when the bone has none
/// ([`SEED_MULTIPLIER`]), and `interior_joint` when the parent is not the root.
///
/// With the seeds' falloff the covered segment is connected (every point of it is inside),
/// and about `thickness` thick (from 0.43 T between beads at `m = 1` to 1.14 T at 1.6).
///
/// A zero-length segment gives one ball at `from` (the seed would produce NaN there).
///
/// # Errors
/// - [`MetaballError::NonFinite`] / [`MetaballError::OutOfRange`] for an end that is not
///   finite or beyond ±[`MAX_COORDINATE`](crate::MAX_COORDINATE);
/// - [`MetaballError::NotPositive`] / [`MetaballError::OutOfRange`] for a thickness ≤ 0 or
///   outside [`THICKNESS_RANGE`];
/// - [`MetaballError::OutOfRange`] for a multiplier outside [`MULTIPLIER_RANGE`] `[1, 1.6]`;
/// - [`MetaballError::TooManyCoverBalls`] beyond [`MAX_COVER_BALLS`].
pub fn cover_segment_with(
    from: Vec2,
    to: Vec2,
    thickness: f32,
    multiplier: f32,
    id: u32,
    options: &CoverOptions,
) -> Result<Vec<Ball2>, MetaballError> {
    check_end("segment start", &from.to_array())?;
    check_end("segment end", &to.to_array())?;
    let plan = plan(from.distance(to), thickness, multiplier, options)?;
    Ok(plan
        .alphas()
        .map(|alpha| Ball2::new(from + (to - from) * alpha, plan.radius, id))
        .collect())
}

/// [`cover_segment`] in 3D.
///
/// # Errors
/// As [`cover_segment_with`].
pub fn cover_segment3(
    from: Vec3,
    to: Vec3,
    thickness: f32,
    multiplier: f32,
    id: u32,
) -> Result<Vec<Ball3>, MetaballError> {
    cover_segment3_with(from, to, thickness, multiplier, id, &CoverOptions::DEFAULT)
}

/// [`cover_segment_with`] in 3D: the same count, radius and placement.
///
/// # Errors
/// As [`cover_segment_with`].
pub fn cover_segment3_with(
    from: Vec3,
    to: Vec3,
    thickness: f32,
    multiplier: f32,
    id: u32,
    options: &CoverOptions,
) -> Result<Vec<Ball3>, MetaballError> {
    check_end("segment start", &from.to_array())?;
    check_end("segment end", &to.to_array())?;
    let plan = plan(from.distance(to), thickness, multiplier, options)?;
    Ok(plan
        .alphas()
        .map(|alpha| Ball3::new(from + (to - from) * alpha, plan.radius, id))
        .collect())
}

fn check_end(what: &'static str, p: &[f32]) -> Result<(), MetaballError> {
    for &c in p {
        if !c.is_finite() {
            return Err(MetaballError::NonFinite { what, index: 0 });
        }
        if !(c.abs() <= MAX_COORDINATE) {
            return Err(MetaballError::OutOfRange {
                what,
                index: 0,
                value: c,
                min: -MAX_COORDINATE,
                max: MAX_COORDINATE,
            });
        }
    }
    Ok(())
}

/// Step count and radius of one covering.
struct Plan {
    steps: u32,
    radius: f32,
    interior_joint: bool,
}

impl Plan {
    fn alphas(&self) -> impl Iterator<Item = f32> + '_ {
        let n = self.steps;
        (0..=n).map(move |i| {
            if n == 0 {
                0.0
            } else if self.interior_joint && i == n {
                (i as f32 - 0.5) / n as f32
            } else {
                i as f32 / n as f32
            }
        })
    }
}

fn plan(
    length: f32,
    thickness: f32,
    multiplier: f32,
    options: &CoverOptions,
) -> Result<Plan, MetaballError> {
    if !thickness.is_finite() {
        return Err(MetaballError::NonFinite {
            what: "thickness",
            index: 0,
        });
    }
    if !(thickness > 0.0) {
        return Err(MetaballError::NotPositive {
            what: "thickness",
            index: 0,
            value: thickness,
        });
    }
    let (min, max) = THICKNESS_RANGE;
    if !(thickness >= min && thickness <= max) {
        return Err(MetaballError::OutOfRange {
            what: "thickness",
            index: 0,
            value: thickness,
            min,
            max,
        });
    }
    if !multiplier.is_finite() {
        return Err(MetaballError::NonFinite {
            what: "multiplier",
            index: 0,
        });
    }
    let (min, max) = MULTIPLIER_RANGE;
    if !(multiplier >= min && multiplier <= max) {
        return Err(MetaballError::OutOfRange {
            what: "multiplier",
            index: 0,
            value: multiplier,
            min,
            max,
        });
    }
    // The seed's order of operations: ceil(distance / (2.97 T) · m).
    let steps = math::ceil(length / (SEED_SPACING * thickness) * multiplier);
    if !(steps.is_finite() && steps < MAX_COVER_BALLS as f32) {
        return Err(MetaballError::TooManyCoverBalls {
            needed: steps + 1.0,
            max: MAX_COVER_BALLS,
        });
    }
    Ok(Plan {
        // Finite, non-negative and below 2^16: the cast is exact.
        steps: steps as u32,
        radius: thickness * cover_radius_factor(multiplier),
        interior_joint: options.interior_joint,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radius_factor_matches_the_reference_table() {
        assert_eq!(cover_radius_factor(1.0), 1.0);
        assert!((cover_radius_factor(1.2) - 0.913).abs() < 5e-4);
        assert!((cover_radius_factor(1.4) - 0.914).abs() < 5e-4);
        assert!((cover_radius_factor(1.6) - 0.943).abs() < 5e-4);
    }

    #[test]
    fn count_radius_and_placement_follow_the_seed() {
        // |B − P| = 100, T = 10, m = 1: ceil(100 / 29.7) = 4 steps, 5 balls at 25 spacing.
        let balls = cover_segment(Vec2::ZERO, Vec2::new(0.0, 100.0), 10.0, 1.0, 3).unwrap();
        assert_eq!(balls.len(), 5);
        for (j, b) in balls.iter().enumerate() {
            assert_eq!(b.center, Vec2::new(0.0, 25.0 * j as f32));
            assert_eq!(b.radius, 10.0);
            assert_eq!(b.id, 3);
        }
    }

    #[test]
    fn interior_joint_moves_only_the_last_ball_half_a_step() {
        let from = Vec2::new(10.0, 0.0);
        let to = Vec2::new(10.0, 80.0);
        let tips = cover_segment(from, to, 8.0, 1.3, 0).unwrap();
        let joint = cover_segment_with(
            from,
            to,
            8.0,
            1.3,
            0,
            &CoverOptions::DEFAULT.with_interior_joint(true),
        )
        .unwrap();
        assert_eq!(tips.len(), joint.len());
        let n = tips.len() - 1;
        assert_eq!(tips[..n], joint[..n]);
        assert_eq!(tips[n].center, to);
        let step = 80.0 / n as f32;
        assert!((joint[n].center.y - (80.0 - step / 2.0)).abs() < 1e-4);
    }

    #[test]
    fn zero_length_segment_gives_one_ball() {
        let p = Vec2::new(1.0, 2.0);
        for joint in [false, true] {
            let options = CoverOptions::DEFAULT.with_interior_joint(joint);
            let balls = cover_segment_with(p, p, 5.0, 1.2, 1, &options).unwrap();
            assert_eq!(balls.len(), 1);
            assert_eq!(balls[0].center, p);
        }
    }

    #[test]
    fn bad_inputs_are_errors() {
        let (a, b) = (Vec2::ZERO, Vec2::X * 10.0);
        assert!(matches!(
            cover_segment(a, b, 0.0, 1.2, 0),
            Err(MetaballError::NotPositive {
                what: "thickness",
                ..
            })
        ));
        assert!(matches!(
            cover_segment(a, b, -1.0, 1.2, 0),
            Err(MetaballError::NotPositive { .. })
        ));
        assert!(matches!(
            cover_segment(a, b, 1.0, 0.99, 0),
            Err(MetaballError::OutOfRange {
                what: "multiplier",
                ..
            })
        ));
        assert!(matches!(
            cover_segment(a, b, 1.0, 1.61, 0),
            Err(MetaballError::OutOfRange {
                what: "multiplier",
                ..
            })
        ));
        assert!(matches!(
            cover_segment(a, b, 1.0, f32::NAN, 0),
            Err(MetaballError::NonFinite { .. })
        ));
        assert!(matches!(
            cover_segment(Vec2::NAN, b, 1.0, 1.2, 0),
            Err(MetaballError::NonFinite {
                what: "segment start",
                ..
            })
        ));
        assert!(matches!(
            cover_segment(a, Vec2::new(1e12, -1e12), 1e-5, 1.6, 0),
            Err(MetaballError::TooManyCoverBalls { .. })
        ));
        // Both multiplier bounds are accepted.
        assert!(cover_segment(a, b, 1.0, 1.0, 0).is_ok());
        assert!(cover_segment(a, b, 1.0, 1.6, 0).is_ok());
    }

    #[test]
    fn three_d_matches_two_d_along_an_axis() {
        let flat = cover_segment(Vec2::ZERO, Vec2::new(70.0, 0.0), 9.0, 1.45, 2).unwrap();
        let space = cover_segment3(Vec3::ZERO, Vec3::new(70.0, 0.0, 0.0), 9.0, 1.45, 2).unwrap();
        assert_eq!(flat.len(), space.len());
        for (a, b) in flat.iter().zip(&space) {
            assert_eq!(a.center.x, b.center.x);
            assert_eq!(a.radius, b.radius);
        }
    }
}
