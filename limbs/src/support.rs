//! Support polygons and stability margins in the ground plane.

use alloc::vec::Vec;

use glam::Vec2;

use crate::sort::sort_by;

/// The convex hull of `points`, counter-clockwise (in a right-handed x–y frame), without
/// repeated or collinear points. Fewer than three distinct points give the distinct ones
/// (at most two: a point or a segment's end points). Non-finite points are skipped.
#[must_use]
pub fn convex_hull(points: &[Vec2]) -> Vec<Vec2> {
    let mut pts: Vec<Vec2> = points.iter().copied().filter(|p| p.is_finite()).collect();
    sort_by(&mut pts, &mut |a, b| {
        a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y))
    });
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut hull: Vec<Vec2> = Vec::with_capacity(pts.len() * 2);
    for pass in 0..2 {
        let start = hull.len();
        let iter: &mut dyn Iterator<Item = &Vec2> = if pass == 0 {
            &mut pts.iter()
        } else {
            &mut pts.iter().rev()
        };
        for &p in iter {
            while hull.len() >= start + 2 {
                let n = hull.len();
                let (a, b) = (hull[n - 2], hull[n - 1]);
                if (b - a).perp_dot(p - a) <= 0.0 {
                    hull.pop();
                } else {
                    break;
                }
            }
            hull.push(p);
        }
        hull.pop();
    }
    if hull.len() < 3 {
        // All collinear: keep the two extremes.
        let first = pts[0];
        let last = pts[pts.len() - 1];
        return alloc::vec![first, last];
    }
    hull
}

/// Distance from `p` to the segment `a`–`b`.
fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// Signed distance from `p` to the boundary of a convex polygon given counter-clockwise (as
/// [`convex_hull`] returns it): positive inside, negative outside. A two-point polygon is a
/// segment and a one-point polygon a point (so `p` is never inside); an empty one gives
/// negative infinity.
#[must_use]
pub fn signed_distance(polygon: &[Vec2], p: Vec2) -> f32 {
    match polygon.len() {
        0 => f32::NEG_INFINITY,
        1 => -p.distance(polygon[0]),
        2 => -segment_distance(p, polygon[0], polygon[1]),
        n => {
            let mut inside = true;
            let mut nearest = f32::INFINITY;
            for i in 0..n {
                let a = polygon[i];
                let b = polygon[(i + 1) % n];
                if (b - a).perp_dot(p - a) < 0.0 {
                    inside = false;
                }
                nearest = nearest.min(segment_distance(p, a, b));
            }
            if inside { nearest } else { -nearest }
        }
    }
}

/// The static stability margin of a body whose centre of mass projects to `center_of_mass`,
/// standing on round feet of radius `foot_radius` centred at `feet` (ground-plane points):
/// the signed distance from the centre of mass to the edge of the feet's convex hull grown by
/// the foot radius. Positive means the body stands; it can lose that much offset before
/// tipping. With no feet the margin is negative infinity.
///
/// ```
/// use creature_limbs::{support_margin, glam::Vec2};
/// let feet = [Vec2::new(-1.0, -1.0), Vec2::new(1.0, -1.0), Vec2::new(1.0, 1.0), Vec2::new(-1.0, 1.0)];
/// assert_eq!(support_margin(&feet, 0.1, Vec2::ZERO), 1.1);
/// // A biped: the support region is the stadium around the segment between its feet.
/// let feet = [Vec2::new(-1.0, 0.0), Vec2::new(1.0, 0.0)];
/// assert!((support_margin(&feet, 0.2, Vec2::new(0.0, 0.05)) - 0.15).abs() < 1e-6);
/// ```
#[must_use]
pub fn support_margin(feet: &[Vec2], foot_radius: f32, center_of_mass: Vec2) -> f32 {
    let hull = convex_hull(feet);
    foot_radius + signed_distance(&hull, center_of_mass)
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::*;

    #[test]
    fn hull_drops_interior_and_collinear_points() {
        let pts = [
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(0.0, 2.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 0.0),
        ];
        let hull = convex_hull(&pts);
        assert_eq!(hull.len(), 4);
        // Counter-clockwise: positive area.
        let area: f32 = (0..hull.len())
            .map(|i| hull[i].perp_dot(hull[(i + 1) % hull.len()]))
            .sum();
        assert!(area > 0.0);
    }

    #[test]
    fn collinear_points_give_a_segment() {
        let hull = convex_hull(&[Vec2::ZERO, Vec2::X, Vec2::X * 2.0]);
        assert_eq!(hull, vec![Vec2::ZERO, Vec2::X * 2.0]);
    }

    #[test]
    fn signed_distance_signs() {
        let square = convex_hull(&[Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y]);
        assert!((signed_distance(&square, Vec2::splat(0.5)) - 0.5).abs() < 1e-6);
        assert!((signed_distance(&square, Vec2::new(2.0, 0.5)) + 1.0).abs() < 1e-6);
        assert_eq!(signed_distance(&[], Vec2::ZERO), f32::NEG_INFINITY);
    }
}
