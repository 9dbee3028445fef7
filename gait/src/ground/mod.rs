//! Grounds the feet stand on: the [`Ground`] trait (a ray cast) and its implementations
//! [`Plane`], [`HeightField`] and [`FnGround`] (any closure).

use glam::{Vec2, Vec3, Vec4};

use crate::error::{GaitError, finite3};

mod height_field;

pub use height_field::HeightField;

/// Where a ray met the ground.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// The hit point, in world space (metres).
    pub point: Vec3,
    /// The ground's unit normal at the hit point, pointing out of the ground.
    pub normal: Vec3,
    /// Distance from the ray's origin to the hit point, along the (unit) direction.
    pub distance: f32,
}

impl RayHit {
    /// True when every field is finite and the normal has a length. The controller uses such a
    /// hit when its point is also within [`MAX_COORDINATE`](crate::MAX_COORDINATE) of the ray's
    /// origin along every axis (see [`Ground`]).
    #[must_use]
    pub fn is_valid(&self) -> bool {
        self.point.is_finite()
            && self.normal.is_finite()
            && self.distance.is_finite()
            && self.normal.length_squared() > 1e-12
    }
}

/// Anything feet can stand on: a ray cast.
///
/// The controller casts rays straight down (world −Y) from above each leg's rest position and
/// step target. Implementations report the first place where the ray enters the ground
/// *from above* (crossing the surface against its normal) within `max_distance`; a ray that
/// starts inside the ground reports no hit until it comes out and crosses the surface again.
///
/// The controller ignores (takes as no hit, so the leg dangles) a hit with a non-finite field
/// and a hit whose point lies farther than [`MAX_COORDINATE`](crate::MAX_COORDINATE) from the
/// ray's origin along any axis: no ray it casts is that long, and such a point would overflow
/// the feet's distances and support hull. These are not errors: the ground is asked during
/// [`Controller::update`](crate::Controller::update), which either fails before changing
/// anything or succeeds.
///
/// ```
/// use creature_gait::{Ground, Plane, glam::Vec3};
///
/// let floor = Plane::horizontal(0.5);
/// let hit = floor.cast_ray(Vec3::new(1.0, 2.0, 3.0), Vec3::NEG_Y, 10.0).unwrap();
/// assert_eq!(hit.point, Vec3::new(1.0, 0.5, 3.0));
/// assert_eq!(hit.distance, 1.5);
/// ```
pub trait Ground {
    /// Casts a ray from `origin` along the unit vector `direction`, at most `max_distance` far.
    fn cast_ray(&self, origin: Vec3, direction: Vec3, max_distance: f32) -> Option<RayHit>;

    /// Casts a ray straight down (world −Y) from `origin`, at most `max_distance` far: the
    /// query the controller makes, with [`cast_down_point`](Self::cast_down_point). The
    /// default calls [`cast_ray`](Self::cast_ray)`(origin, Vec3::NEG_Y, max_distance)`;
    /// override it when
    /// vertical rays have a cheaper answer (as [`HeightField`] does: one bilinear lookup).
    /// An override must return what `cast_ray` would.
    #[inline]
    fn cast_down(&self, origin: Vec3, max_distance: f32) -> Option<RayHit> {
        self.cast_ray(origin, Vec3::NEG_Y, max_distance)
    }

    /// The point of [`cast_down`](Self::cast_down)'s hit when the hit is
    /// [valid](RayHit::is_valid), else `None`: what the default returns. The controller asks
    /// only this under the legs whose ground normal it does not need (it asks `cast_down` for
    /// the same ray when it does), and [`HeightField`] answers it with its bilinear height
    /// alone. An override must return what the default would.
    ///
    /// ```
    /// use creature_gait::{Ground, HeightField, glam::{Vec2, Vec3}};
    ///
    /// let field = HeightField::new(Vec2::ZERO, 1.0, 2, 2, vec![0.0, 1.0, 0.0, 1.0])?;
    /// let origin = Vec3::new(0.5, 3.0, 0.5);
    /// let hit = field.cast_down(origin, 10.0).unwrap();
    /// assert_eq!(field.cast_down_point(origin, 10.0), Some(hit.point));
    /// # Ok::<(), creature_gait::GaitError>(())
    /// ```
    #[inline]
    fn cast_down_point(&self, origin: Vec3, max_distance: f32) -> Option<Vec3> {
        self.cast_down(origin, max_distance)
            .filter(RayHit::is_valid)
            .map(|hit| hit.point)
    }

    /// Bounds `(lowest, highest)` on the ground's height under the horizontal square of
    /// half-side `half` (`>= 0`) centred on `centre` (world x and z), or `None` (the default)
    /// where the ground cannot tell cheaply. A caller can then skip casts whose answer the
    /// bounds settle: a foot well above the ground, or every hit on flat ground (where
    /// `lowest == highest`, the height of every hit).
    ///
    /// An implementation that returns bounds promises, for every ray cast straight down
    /// ([`cast_down`](Self::cast_down) or [`cast_down_point`](Self::cast_down_point)) from a
    /// finite origin whose x and z lie in the square, with a finite `max_distance`:
    /// - a hit's height is within the bounds;
    /// - the ray hits when it starts at or above `highest` and reaches `lowest`
    ///   (`origin.y - lowest <= max_distance`, in `f32`).
    ///
    /// [`Plane`] bounds a horizontal plane exactly (its height twice) and [`HeightField`] the
    /// squares inside its grid; closures ([`FnGround`]) and tilted planes say nothing.
    ///
    /// ```
    /// use creature_gait::{Ground, HeightField, Plane, glam::{Vec2, Vec3}};
    ///
    /// assert_eq!(Plane::horizontal(0.5).height_bounds(Vec2::new(3.0, 4.0), 1.0), Some((0.5, 0.5)));
    /// let field = HeightField::new(Vec2::ZERO, 1.0, 3, 2, vec![0.0, 1.0, 2.0, 0.0, 1.0, 2.0])?;
    /// let bounds = field.height_bounds(Vec2::new(0.5, 0.5), 0.25);
    /// let hit = field.cast_down_point(Vec3::new(0.7, 5.0, 0.6), 10.0);
    /// assert!(bounds.zip(hit).is_some_and(|((low, high), hit)| low <= hit.y && hit.y <= high && high < 1.1));
    /// // Off the grid, a ray may find nothing: no bounds.
    /// assert_eq!(field.height_bounds(Vec2::new(1.9, 0.5), 0.25), None);
    /// # Ok::<(), creature_gait::GaitError>(())
    /// ```
    #[inline]
    fn height_bounds(&self, centre: Vec2, half: f32) -> Option<(f32, f32)> {
        let _ = (centre, half);
        None
    }

    /// Four rays straight down at once, from `(x[i], y[i], z[i])`, `max_distance[i]` long:
    /// for each, the height of its hit as [`cast_down_point`](Self::cast_down_point) finds it
    /// (bit for bit), or `None` where it misses. The default casts the four rays;
    /// [`HeightField`] looks the four up together, and a caller with many rays (the feet's
    /// soles, vertex by vertex) saves most of a lookup's overhead.
    ///
    /// ```
    /// use creature_gait::{Ground, HeightField, glam::{Vec2, Vec3, Vec4}};
    ///
    /// let field = HeightField::new(Vec2::ZERO, 1.0, 3, 2, vec![0.0, 1.0, 2.0, 0.0, 1.0, 2.0])?;
    /// let (x, z) = (Vec4::new(0.5, 1.5, 1.9, 3.0), Vec4::splat(0.5));
    /// let hits = field.cast_down_four(x, Vec4::splat(5.0), z, Vec4::splat(10.0));
    /// assert_eq!(hits, [Some(0.5), Some(1.5), Some(1.9), None]); // the last is off the grid
    /// let one = field.cast_down_point(Vec3::new(1.5, 5.0, 0.5), 10.0);
    /// assert_eq!(one.map(|hit| hit.y), hits[1]);
    /// # Ok::<(), creature_gait::GaitError>(())
    /// ```
    #[inline]
    fn cast_down_four(&self, x: Vec4, y: Vec4, z: Vec4, max_distance: Vec4) -> [Option<f32>; 4] {
        core::array::from_fn(|i| {
            self.cast_down_point(Vec3::new(x[i], y[i], z[i]), max_distance[i])
                .map(|hit| hit.y)
        })
    }
}

impl<G: Ground + ?Sized> Ground for &G {
    #[inline]
    fn cast_ray(&self, origin: Vec3, direction: Vec3, max_distance: f32) -> Option<RayHit> {
        (**self).cast_ray(origin, direction, max_distance)
    }

    #[inline]
    fn cast_down(&self, origin: Vec3, max_distance: f32) -> Option<RayHit> {
        (**self).cast_down(origin, max_distance)
    }

    #[inline]
    fn cast_down_point(&self, origin: Vec3, max_distance: f32) -> Option<Vec3> {
        (**self).cast_down_point(origin, max_distance)
    }

    #[inline]
    fn height_bounds(&self, centre: Vec2, half: f32) -> Option<(f32, f32)> {
        (**self).height_bounds(centre, half)
    }

    #[inline]
    fn cast_down_four(&self, x: Vec4, y: Vec4, z: Vec4, max_distance: Vec4) -> [Option<f32>; 4] {
        (**self).cast_down_four(x, y, z, max_distance)
    }
}

/// Any closure `Fn(origin, direction, max_distance) -> Option<RayHit>` as a ground: the way to
/// plug in an engine's physics ray cast.
///
/// ```
/// use creature_gait::{FnGround, Ground, RayHit, glam::Vec3};
///
/// // A floor at y = 0 that only exists for x > 0.
/// let half = FnGround(|origin: Vec3, direction: Vec3, max: f32| {
///     if origin.x <= 0.0 || direction.y >= 0.0 || origin.y < 0.0 {
///         return None;
///     }
///     let distance = origin.y / -direction.y;
///     (distance <= max).then(|| RayHit {
///         point: origin + direction * distance,
///         normal: Vec3::Y,
///         distance,
///     })
/// });
/// assert!(half.cast_ray(Vec3::new(1.0, 1.0, 0.0), Vec3::NEG_Y, 5.0).is_some());
/// assert!(half.cast_ray(Vec3::new(-1.0, 1.0, 0.0), Vec3::NEG_Y, 5.0).is_none());
/// ```
#[derive(Debug, Clone, Copy)]
pub struct FnGround<F>(pub F);

impl<F: Fn(Vec3, Vec3, f32) -> Option<RayHit>> Ground for FnGround<F> {
    #[inline]
    fn cast_ray(&self, origin: Vec3, direction: Vec3, max_distance: f32) -> Option<RayHit> {
        (self.0)(origin, direction, max_distance)
    }
}

/// An infinite plane: the set of points `p` with `(p − point) · normal = 0`, solid below.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    point: Vec3,
    normal: Vec3,
}

impl Plane {
    /// The horizontal plane `y = 0`, normal +Y.
    pub const GROUND: Self = Self {
        point: Vec3::ZERO,
        normal: Vec3::Y,
    };

    /// A plane through `point` with the given normal (normalised here).
    ///
    /// # Errors
    /// [`GaitError::NonFinite`] for a non-finite input, [`GaitError::ZeroVector`] for a zero
    /// normal.
    pub fn new(point: Vec3, normal: Vec3) -> Result<Self, GaitError> {
        finite3(point, "plane point", 0)?;
        finite3(normal, "plane normal", 0)?;
        let normal = normal.try_normalize().ok_or(GaitError::ZeroVector {
            what: "plane normal",
            index: 0,
        })?;
        Ok(Self { point, normal })
    }

    /// The horizontal plane `y = height`. A non-finite height gives `y = 0`.
    #[must_use]
    pub fn horizontal(height: f32) -> Self {
        let height = if height.is_finite() { height } else { 0.0 };
        Self {
            point: Vec3::new(0.0, height, 0.0),
            normal: Vec3::Y,
        }
    }

    /// A point on the plane.
    #[must_use]
    pub const fn point(&self) -> Vec3 {
        self.point
    }

    /// The plane's unit normal.
    #[must_use]
    pub const fn normal(&self) -> Vec3 {
        self.normal
    }
}

impl Default for Plane {
    fn default() -> Self {
        Self::GROUND
    }
}

impl Plane {
    /// The hit `distance` along the ray from `origin` along `direction`, if within
    /// `max_distance`.
    #[inline]
    fn hit_at(
        &self,
        origin: Vec3,
        direction: Vec3,
        distance: f32,
        max_distance: f32,
    ) -> Option<RayHit> {
        if !(distance >= 0.0 && distance <= max_distance) {
            return None;
        }
        // Vertical rays onto a horizontal plane land exactly on its height.
        let mut point = origin + direction * distance;
        if self.normal == Vec3::Y && direction.x == 0.0 && direction.z == 0.0 {
            point.y = self.point.y;
        }
        Some(RayHit {
            point,
            normal: self.normal,
            distance,
        })
    }
}

impl Ground for Plane {
    fn cast_ray(&self, origin: Vec3, direction: Vec3, max_distance: f32) -> Option<RayHit> {
        let denom = direction.dot(self.normal);
        if !(denom < -1e-12) {
            return None; // parallel, leaving, or NaN
        }
        let distance = (self.point - origin).dot(self.normal) / denom;
        self.hit_at(origin, direction, distance, max_distance)
    }

    /// What [`cast_ray`](Self::cast_ray) finds straight down, without its division when the
    /// plane is horizontal.
    #[inline]
    fn cast_down(&self, origin: Vec3, max_distance: f32) -> Option<RayHit> {
        if self.normal != Vec3::Y {
            return self.cast_ray(origin, Vec3::NEG_Y, max_distance);
        }
        // `(point − origin) · normal / (−Y · normal)` for the normal +Y, exactly (the
        // division by −1 a negation).
        let distance = -(self.point - origin).dot(self.normal);
        self.hit_at(origin, Vec3::NEG_Y, distance, max_distance)
    }

    /// [`cast_down`](Self::cast_down)'s point, checked as the default checks it but knowing
    /// what it does of a horizontal plane's hit: its normal (+Y) is valid and its height the
    /// plane's, so the hit is valid exactly when its point's x and z and its distance are
    /// finite. (A median walker's animator casts about 48 of these an update on flat ground.)
    #[inline]
    fn cast_down_point(&self, origin: Vec3, max_distance: f32) -> Option<Vec3> {
        if self.normal != Vec3::Y {
            return self
                .cast_ray(origin, Vec3::NEG_Y, max_distance)
                .filter(RayHit::is_valid)
                .map(|hit| hit.point);
        }
        let distance = -(self.point - origin).dot(self.normal);
        if !(distance >= 0.0 && distance <= max_distance) {
            return None;
        }
        // `hit_at`'s point: `origin − Y × distance` with its height set to the plane's.
        let point = origin + Vec3::NEG_Y * distance;
        let point = Vec3::new(point.x, self.point.y, point.z);
        (point.is_finite() && distance.is_finite()).then_some(point)
    }

    /// A horizontal plane's height, twice (every hit is at its height, and a finite ray that
    /// reaches it hits it); `None` for a tilted plane.
    #[inline]
    fn height_bounds(&self, _centre: Vec2, _half: f32) -> Option<(f32, f32)> {
        (self.normal == Vec3::Y).then_some((self.point.y, self.point.y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_horizontal_planes_vertical_casts_are_its_general_casts() {
        let values = [
            -3.5,
            -1.0,
            -0.0,
            0.0,
            1e-30,
            0.25,
            1.0,
            7.0,
            1e30,
            f32::INFINITY,
            f32::NAN,
        ];
        for plane in [
            Plane::GROUND,
            Plane::horizontal(1.0),
            Plane::horizontal(-2.5),
        ] {
            for &x in &values {
                for &y in &values {
                    for &max in &[0.0, 0.5, 3.0, f32::INFINITY, f32::NAN] {
                        let origin = Vec3::new(x, y, -x);
                        let general = plane.cast_ray(origin, Vec3::NEG_Y, max);
                        let down = plane.cast_down(origin, max);
                        let bits = |h: Option<RayHit>| {
                            h.map(|h| (h.point.to_array().map(f32::to_bits), h.distance.to_bits()))
                        };
                        assert_eq!(bits(general), bits(down), "{origin} {max}");
                        assert_eq!(
                            plane
                                .cast_down_point(origin, max)
                                .map(|p| p.to_array().map(f32::to_bits)),
                            general
                                .filter(RayHit::is_valid)
                                .map(|h| h.point.to_array().map(f32::to_bits)),
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn plane_hits_from_above_only() {
        let plane = Plane::horizontal(1.0);
        let hit = plane
            .cast_ray(Vec3::new(0.0, 3.0, 0.0), Vec3::NEG_Y, 5.0)
            .unwrap();
        assert_eq!(hit.point.y, 1.0);
        assert_eq!(hit.distance, 2.0);
        assert!(
            plane
                .cast_ray(Vec3::new(0.0, 0.0, 0.0), Vec3::NEG_Y, 5.0)
                .is_none()
        );
        assert!(
            plane
                .cast_ray(Vec3::new(0.0, 3.0, 0.0), Vec3::Y, 5.0)
                .is_none()
        );
        assert!(
            plane
                .cast_ray(Vec3::new(0.0, 3.0, 0.0), Vec3::NEG_Y, 1.0)
                .is_none()
        );
        assert!(Plane::new(Vec3::ZERO, Vec3::ZERO).is_err());
    }

    #[test]
    fn tilted_plane_hit_lies_on_plane() {
        let plane = Plane::new(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.3, 1.0, -0.2)).unwrap();
        let hit = plane
            .cast_ray(
                Vec3::new(2.0, 10.0, -1.0),
                Vec3::new(0.1, -1.0, 0.2).normalize(),
                50.0,
            )
            .unwrap();
        assert!((hit.point - plane.point()).dot(plane.normal()).abs() < 1e-5);
    }
}
