//! Balls: a centre, a radius and the caller's id.

use glam::{Vec2, Vec3};

use crate::MetaballError;

/// Accepted ball radii: from `1e-6` to `1e9` (in the caller's units), so that `1/R²` and the
/// culling radii stay finite in `f32`.
pub const RADIUS_RANGE: (f32, f32) = (1e-6, 1e9);

/// Largest accepted absolute value of a ball-centre coordinate.
pub const MAX_COORDINATE: f32 = 1e12;

/// A 2D metaball.
///
/// `radius` is the ball's `R` in its [`Falloff`](crate::Falloff) (for the seeds' falloff, the
/// radius of a lone ball's iso line). `id` is yours: a bone index, a colour index; several
/// balls may share it, and [`Field2::shares`](crate::Field2::shares) sums per id.
///
/// ```
/// use creature_metaball::{Ball2, glam::Vec2};
///
/// let ball = Ball2::new(Vec2::new(1.0, 2.0), 3.0, 7);
/// assert!(ball.validate().is_ok());
/// assert!(Ball2::new(Vec2::ZERO, -1.0, 0).validate().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ball2 {
    /// Centre.
    pub center: Vec2,
    /// Radius `R`, in [`RADIUS_RANGE`].
    pub radius: f32,
    /// The caller's id (bone, colour, material); not interpreted by this crate.
    pub id: u32,
}

impl Ball2 {
    /// A ball at `center` with `radius` and the caller's `id`. Not validated here: fields
    /// validate their balls, or call [`Ball2::validate`].
    #[must_use]
    pub const fn new(center: Vec2, radius: f32, id: u32) -> Self {
        Self { center, radius, id }
    }

    /// Checks the centre (finite, each coordinate within ±[`MAX_COORDINATE`]) and the radius
    /// (finite, positive, in [`RADIUS_RANGE`]).
    ///
    /// # Errors
    /// [`MetaballError::NonFinite`], [`MetaballError::NotPositive`] or
    /// [`MetaballError::OutOfRange`], with index 0.
    pub fn validate(&self) -> Result<(), MetaballError> {
        validate_ball(&self.center.to_array(), self.radius, 0)
    }
}

/// A 3D metaball: the same as [`Ball2`] with a [`Vec3`] centre.
///
/// ```
/// use creature_metaball::{Ball3, glam::Vec3};
///
/// let ball = Ball3::new(Vec3::new(1.0, 2.0, 3.0), 0.5, 1);
/// assert!(ball.validate().is_ok());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ball3 {
    /// Centre.
    pub center: Vec3,
    /// Radius `R`, in [`RADIUS_RANGE`].
    pub radius: f32,
    /// The caller's id (bone, colour, material); not interpreted by this crate.
    pub id: u32,
}

impl Ball3 {
    /// A ball at `center` with `radius` and the caller's `id`. Not validated here: fields
    /// validate their balls, or call [`Ball3::validate`].
    #[must_use]
    pub const fn new(center: Vec3, radius: f32, id: u32) -> Self {
        Self { center, radius, id }
    }

    /// Checks the centre (finite, each coordinate within ±[`MAX_COORDINATE`]) and the radius
    /// (finite, positive, in [`RADIUS_RANGE`]).
    ///
    /// # Errors
    /// [`MetaballError::NonFinite`], [`MetaballError::NotPositive`] or
    /// [`MetaballError::OutOfRange`], with index 0.
    pub fn validate(&self) -> Result<(), MetaballError> {
        validate_ball(&self.center.to_array(), self.radius, 0)
    }
}

pub(crate) fn validate_ball(
    center: &[f32],
    radius: f32,
    index: usize,
) -> Result<(), MetaballError> {
    for &c in center {
        if !c.is_finite() {
            return Err(MetaballError::NonFinite {
                what: "ball center",
                index,
            });
        }
        if !(c.abs() <= MAX_COORDINATE) {
            return Err(MetaballError::OutOfRange {
                what: "ball center coordinate",
                index,
                value: c,
                min: -MAX_COORDINATE,
                max: MAX_COORDINATE,
            });
        }
    }
    validate_radius(radius, index)
}

/// Checks a ball radius: finite, positive, in [`RADIUS_RANGE`] (`what: "ball radius"`).
pub(crate) fn validate_radius(radius: f32, index: usize) -> Result<(), MetaballError> {
    if !radius.is_finite() {
        return Err(MetaballError::NonFinite {
            what: "ball radius",
            index,
        });
    }
    if !(radius > 0.0) {
        return Err(MetaballError::NotPositive {
            what: "ball radius",
            index,
            value: radius,
        });
    }
    let (min, max) = RADIUS_RANGE;
    if !(radius >= min && radius <= max) {
        return Err(MetaballError::OutOfRange {
            what: "ball radius",
            index,
            value: radius,
            min,
            max,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation_names_the_problem() {
        assert!(Ball2::new(Vec2::ONE, 1.0, 0).validate().is_ok());
        assert_eq!(
            Ball2::new(Vec2::new(f32::NAN, 0.0), 1.0, 0).validate(),
            Err(MetaballError::NonFinite {
                what: "ball center",
                index: 0
            })
        );
        assert_eq!(
            Ball2::new(Vec2::ZERO, 0.0, 0).validate(),
            Err(MetaballError::NotPositive {
                what: "ball radius",
                index: 0,
                value: 0.0
            })
        );
        assert!(matches!(
            Ball3::new(Vec3::ZERO, 1e-9, 0).validate(),
            Err(MetaballError::OutOfRange { .. })
        ));
        assert!(matches!(
            Ball3::new(Vec3::new(0.0, 2e12, 0.0), 1.0, 0).validate(),
            Err(MetaballError::OutOfRange { .. })
        ));
        assert!(matches!(
            Ball3::new(Vec3::ZERO, f32::INFINITY, 0).validate(),
            Err(MetaballError::NonFinite { .. })
        ));
    }
}
