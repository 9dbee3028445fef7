//! Plausibility figures of the last update, measured when asked, and the support-polygon
//! margin.

use alloc::vec::Vec;

use glam::Vec2;

use crate::math::sqrt;

/// Figures of the last [`Controller::update`](crate::Controller::update), for tests and for
/// users tuning a creature, measured by [`Controller::metrics`](crate::Controller::metrics)
/// when asked. Arms are left out of every figure.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct GaitMetrics {
    /// Foot skate: the largest distance a foot that was planted before and after the update
    /// moved during it, metres (0 by construction; measured, not assumed).
    pub max_skate: f32,
    /// Overstretch: the largest distance by which a grounded foot lies beyond its leg's reach
    /// (`upper + lower`) from its hip (after the body's reaction), metres; 0 when every foot is
    /// within reach.
    pub max_overstretch: f32,
    /// Legs in the air (stepping, or with no ground under them).
    pub legs_in_air: usize,
    /// Legs that started a step in this update.
    pub steps_started: usize,
    /// Legs that started an escape step (out of their group's turn) in this update.
    pub escapes_started: usize,
    /// Signed horizontal distance of the centre of mass from the edge of the planted feet's
    /// support polygon (convex hull in XZ), metres: positive inside, negative outside (with
    /// fewer than three planted feet the polygon is a segment or a point, so it is ≤ 0).
    /// `None` when no foot is planted.
    pub stability_margin: Option<f32>,
}

/// Signed horizontal distance of `point` to the convex hull of `points` (`(x, z)` pairs, e.g.
/// feet on the ground): positive inside, negative outside; with fewer than three points not
/// on one line the hull is a segment or a point, so the margin is at most 0. `None` for no
/// points. `points` is sorted and deduplicated in place; `scratch` is reused storage for the
/// hull.
///
/// ```
/// use creature_gait::{glam::Vec2, support_margin};
///
/// let mut feet = vec![Vec2::new(-1.0, -1.0), Vec2::new(1.0, -1.0), Vec2::new(1.0, 1.0), Vec2::new(-1.0, 1.0)];
/// let margin = support_margin(&mut feet, &mut Vec::new(), Vec2::new(0.0, 0.5));
/// assert_eq!(margin, Some(0.5));
/// ```
pub fn support_margin(points: &mut Vec<Vec2>, scratch: &mut Vec<Vec2>, point: Vec2) -> Option<f32> {
    support_hull(points, scratch);
    hull_margin(scratch, point)
}

/// Sorts and deduplicates `points`, then writes their convex hull into `hull`.
fn support_hull(points: &mut Vec<Vec2>, hull: &mut Vec<Vec2>) {
    // Lexicographic order, by an insertion sort (a few points, one per planted foot; no
    // allocation). Points equal in this order are equal bit for bit: any sort gives this one.
    let after = |a: Vec2, b: Vec2| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)).is_gt();
    for k in 1..points.len() {
        let mut j = k;
        while j > 0 && after(points[j - 1], points[j]) {
            points.swap(j - 1, j);
            j -= 1;
        }
    }
    points.dedup();
    convex_hull(points, hull);
}

/// Signed distance of `point` to the convex polygon `hull` (counter-clockwise, positive
/// inside; a point or a segment gives ≤ 0), `None` for an empty hull.
fn hull_margin(hull: &[Vec2], point: Vec2) -> Option<f32> {
    if hull.is_empty() {
        return None;
    }
    if let [only] = hull {
        return Some(-only.distance(point));
    }
    // Squared distances to the edges; one square root of the smallest (monotonic).
    let mut min_edge = f32::INFINITY;
    let mut inside = hull.len() >= 3;
    let mut previous = hull[hull.len() - 1];
    for &b in hull {
        let a = previous;
        previous = b;
        min_edge = min_edge.min(segment_distance_squared(point, a, b));
        if (b - a).perp_dot(point - a) < 0.0 {
            inside = false;
        }
    }
    let min_edge = sqrt(min_edge);
    Some(if inside { min_edge } else { -min_edge })
}

fn segment_distance_squared(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance_squared(a + ab * t)
}

/// Andrew's monotone chain on sorted, deduplicated points; counter-clockwise, no collinear
/// points. Writes into `hull` and returns it.
fn convex_hull<'a>(points: &[Vec2], hull: &'a mut Vec<Vec2>) -> &'a [Vec2] {
    hull.clear();
    if points.len() <= 2 {
        hull.extend_from_slice(points);
        return hull;
    }
    for &p in points {
        while hull.len() >= 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
            hull.pop();
        }
        hull.push(p);
    }
    let lower = hull.len() + 1;
    for &p in points.iter().rev().skip(1) {
        while hull.len() >= lower && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
            hull.pop();
        }
        hull.push(p);
    }
    hull.pop();
    hull
}

fn cross(o: Vec2, a: Vec2, b: Vec2) -> f32 {
    (a - o).perp_dot(b - o)
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::*;

    #[test]
    fn square_margin() {
        let mut pts = vec![
            Vec2::new(-1.0, -1.0),
            Vec2::new(1.0, -1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(-1.0, 1.0),
            Vec2::new(0.0, 0.5),
        ];
        let mut scratch = Vec::new();
        assert_eq!(
            support_margin(&mut pts.clone(), &mut scratch, Vec2::ZERO),
            Some(1.0)
        );
        assert_eq!(
            support_margin(&mut pts, &mut scratch, Vec2::new(3.0, 0.0)),
            Some(-2.0)
        );
    }

    #[test]
    fn degenerate_supports_are_non_positive() {
        let mut scratch = Vec::new();
        let mut two = vec![Vec2::new(-1.0, 0.0), Vec2::new(1.0, 0.0)];
        assert_eq!(
            support_margin(&mut two, &mut scratch, Vec2::new(0.0, 0.5)),
            Some(-0.5)
        );
        let mut one = vec![Vec2::new(1.0, 0.0)];
        assert_eq!(
            support_margin(&mut one, &mut scratch, Vec2::ZERO),
            Some(-1.0)
        );
        let mut line = vec![Vec2::ZERO, Vec2::X, Vec2::new(2.0, 0.0)];
        assert_eq!(support_margin(&mut line, &mut scratch, Vec2::X), Some(-0.0));
        assert_eq!(
            support_margin(&mut Vec::new(), &mut scratch, Vec2::ZERO),
            None
        );
    }
}
