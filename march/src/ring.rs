//! Closed rings, their geometry, and the checks shared by every producer and consumer.

use alloc::vec::Vec;

use glam::Vec2;

use crate::MarchError;
use crate::sort::sort_unstable_by;

/// A closed outline: the points of a polygon, the last point not repeated.
///
/// Outer rings run counter-clockwise and holes clockwise, with y up (so the inside is always on
/// the left of the direction of travel); a hole's [`parent`](Self::parent) is the index of the
/// outer ring it cuts into, in the same list.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Ring {
    /// The vertices, in order; the edge from the last back to the first closes the ring.
    pub points: Vec<Vec2>,
    /// `true` for a hole (clockwise), `false` for an outer ring (counter-clockwise).
    pub hole: bool,
    /// For a hole, the index of the enclosing outer ring; `None` for an outer ring.
    pub parent: Option<usize>,
}

impl Ring {
    /// Signed area by the shoelace formula: positive for counter-clockwise rings
    /// (y up), negative for clockwise ones, 0 for fewer than three points.
    ///
    /// ```
    /// use creature_march::{glam::Vec2, Ring};
    ///
    /// let square = Ring {
    ///     points: vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y],
    ///     hole: false,
    ///     parent: None,
    /// };
    /// assert_eq!(square.signed_area(), 1.0);
    /// ```
    #[must_use]
    pub fn signed_area(&self) -> f32 {
        signed_area(&self.points) as f32
    }

    /// Total edge length, closing edge included.
    #[must_use]
    pub fn perimeter(&self) -> f32 {
        let n = self.points.len();
        if n < 2 {
            return 0.0;
        }
        (0..n)
            .map(|i| self.points[i].distance(self.points[(i + 1) % n]))
            .sum()
    }

    /// Whether `p` lies inside the polygon (even–odd rule; points exactly on an edge may go
    /// either way).
    #[must_use]
    pub fn contains(&self, p: Vec2) -> bool {
        contains(&self.points, p)
    }

    /// The axis-aligned bounding box `(min, max)`, or `None` for an empty ring.
    #[must_use]
    pub fn bounds(&self) -> Option<(Vec2, Vec2)> {
        bounds(&self.points)
    }
}

/// A point in `f64`, for exact-enough predicates on `f32` input (glam's `f64` types are not
/// enabled).
#[derive(Debug, Clone, Copy, PartialEq)]
struct D2 {
    x: f64,
    y: f64,
}

impl D2 {
    fn perp_dot(self, o: Self) -> f64 {
        self.x * o.y - self.y * o.x
    }

    fn min(self, o: Self) -> Self {
        Self {
            x: self.x.min(o.x),
            y: self.y.min(o.y),
        }
    }

    fn max(self, o: Self) -> Self {
        Self {
            x: self.x.max(o.x),
            y: self.y.max(o.y),
        }
    }
}

impl core::ops::Sub for D2 {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self {
            x: self.x - o.x,
            y: self.y - o.y,
        }
    }
}

trait IntoD2 {
    fn into_d2(self) -> D2;
}

impl IntoD2 for Vec2 {
    fn into_d2(self) -> D2 {
        D2 {
            x: f64::from(self.x),
            y: f64::from(self.y),
        }
    }
}

pub(crate) fn bounds(points: &[Vec2]) -> Option<(Vec2, Vec2)> {
    (!points.is_empty()).then(|| span(points))
}

/// [`bounds`] of at least one point.
fn span(points: &[Vec2]) -> (Vec2, Vec2) {
    let first = points[0];
    points
        .iter()
        .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)))
}

/// Shoelace area in `f64`, relative to the first point for precision.
pub(crate) fn signed_area(points: &[Vec2]) -> f64 {
    let n = points.len();
    if n < 3 {
        return 0.0;
    }
    let o = points[0].into_d2();
    let mut twice = 0.0;
    for i in 1..n - 1 {
        let a = points[i].into_d2() - o;
        let b = points[i + 1].into_d2() - o;
        twice += a.perp_dot(b);
    }
    twice * 0.5
}

/// Whether each point lies inside the rings, by the even–odd rule over all of them (inside
/// an outer ring and not in one of its holes): the answers [`Ring::contains`] gives, counted
/// over `rings`, for many points at once. Each edge is tested only against the points level
/// with it (points sorted by height), so the cost is about `(edges + points) × log(points)`
/// rather than `edges × points`. Non-finite points are outside.
///
/// ```
/// use creature_march::{contains_each, glam::Vec2, Ring};
///
/// let square = |o: Vec2, s: f32, hole: bool| {
///     let mut points = vec![o, o + Vec2::X * s, o + Vec2::splat(s), o + Vec2::Y * s];
///     if hole {
///         points.reverse();
///     }
///     Ring { points, hole, parent: hole.then_some(0) }
/// };
/// let rings = [square(Vec2::ZERO, 10.0, false), square(Vec2::splat(4.0), 2.0, true)];
/// let points = [Vec2::splat(1.0), Vec2::splat(5.0), Vec2::splat(11.0)];
/// assert_eq!(contains_each(&rings, &points), [true, false, false]);
/// ```
#[must_use]
pub fn contains_each(rings: &[Ring], points: &[Vec2]) -> Vec<bool> {
    let mut inside = alloc::vec![false; points.len()];
    // Finite points by height.
    let mut order: Vec<(f32, u32)> = points
        .iter()
        .enumerate()
        .filter(|(_, p)| p.is_finite())
        .map(|(k, p)| (p.y, k as u32))
        .collect();
    sort_unstable_by(&mut order, &mut |a, b| {
        a.0.total_cmp(&b.0).then(a.1.cmp(&b.1))
    });
    let (Some(&(bottom, _)), Some(&(top, _))) = (order.first(), order.last()) else {
        return inside;
    };
    // Height buckets over the points' range: `first[b]` is the first point (in `order`) of
    // bucket `b` or above, so an edge finds the points level with it in a bucket or two.
    let buckets = order.len().clamp(1, 1024);
    let scale = buckets as f32 / (top - bottom).max(f32::MIN_POSITIVE);
    let bucket = |y: f32| (((y - bottom) * scale).max(0.0) as usize).min(buckets - 1);
    let mut first = alloc::vec![0u32; buckets + 1];
    for &(y, _) in &order {
        first[bucket(y) + 1] += 1;
    }
    for b in 0..buckets {
        first[b + 1] += first[b];
    }
    for ring in rings {
        let n = ring.points.len();
        if n < 3 {
            continue;
        }
        for i in 0..n {
            let (a, b) = (ring.points[i], ring.points[(i + n - 1) % n]);
            // The points with `(a.y > y) != (b.y > y)`: heights in [low, high).
            let (low, high) = (a.y.min(b.y), a.y.max(b.y));
            if !(high > bottom && low <= top) {
                continue;
            }
            let from = first[bucket(low)] as usize;
            let (a, b) = (a.into_d2(), b.into_d2());
            for &(y, k) in &order[from..] {
                if y >= high {
                    break;
                }
                if y < low {
                    continue;
                }
                let p = points[k as usize].into_d2();
                // As in `contains`, so the answers agree bit for bit.
                let x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
                if p.x < x {
                    inside[k as usize] = !inside[k as usize];
                }
            }
        }
    }
    inside
}

/// Even–odd point-in-polygon test.
pub(crate) fn contains(points: &[Vec2], p: Vec2) -> bool {
    let n = points.len();
    if n < 3 {
        return false;
    }
    let p = p.into_d2();
    let mut inside = false;
    let mut j = n - 1;
    for i in 0..n {
        let a = points[i].into_d2();
        let b = points[j].into_d2();
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if p.x < x {
                inside = !inside;
            }
        }
        j = i;
    }
    inside
}

/// Drops consecutive points closer than `distance` (exact duplicates always), wrap-around
/// included.
pub(crate) fn weld(points: &mut Vec<Vec2>, distance: f32) {
    let d2 = distance * distance;
    let close = |a: Vec2, b: Vec2| {
        let q = a.distance_squared(b);
        q <= d2 || a == b
    };
    // Most traced rings have nothing to weld: a scan of all the neighbours first, without an
    // exit per pair (on the outline bench's ring, faster than `dedup_by` finding nothing).
    let any_close = points.windows(2).fold(false, |any, w| match w {
        [a, b] => any | close(*a, *b),
        _ => any,
    });
    if any_close {
        // In place: each point is compared with the last one kept.
        points.dedup_by(|p, q| close(*p, *q));
    }
    while points.len() > 1 {
        match (points.first(), points.last()) {
            (Some(&a), Some(&b)) if close(a, b) => {
                points.pop();
            }
            _ => break,
        }
    }
}

/// Turns raw traced point lists into finished rings: welds, drops rings left with fewer than
/// three points or no area, sets `hole` from the orientation and assigns parents.
pub(crate) fn finish(raw: Vec<Vec<Vec2>>, weld_distance: f32) -> Vec<Ring> {
    finish_with_areas(raw.into_iter().map(|points| (points, None)), weld_distance)
}

/// [`finish`], for point lists some of which come with their [`signed_area`] (exactly that
/// value, which is kept unless welding removes a point).
pub(crate) fn finish_with_areas(
    raw: impl ExactSizeIterator<Item = (Vec<Vec2>, Option<f64>)>,
    weld_distance: f32,
) -> Vec<Ring> {
    let mut rings: Vec<(Vec<Vec2>, f64)> = Vec::with_capacity(raw.len());
    for (mut points, area) in raw {
        let count = points.len();
        weld(&mut points, weld_distance);
        let area = match area {
            Some(area) if points.len() == count => area,
            _ => signed_area(&points),
        };
        if points.len() >= 3 && area != 0.0 {
            rings.push((points, area));
        }
    }
    // Parents: the smallest outer ring containing a hole's first point (boxes only when
    // there is a hole to place).
    let boxes: Vec<(Vec2, Vec2)> = if rings.iter().any(|(_, area)| *area < 0.0) {
        rings.iter().map(|(p, _)| span(p)).collect()
    } else {
        Vec::new()
    };
    let mut parents: Vec<Option<usize>> = Vec::with_capacity(rings.len());
    for (h, (points, area)) in rings.iter().enumerate() {
        if *area > 0.0 {
            parents.push(None);
            continue;
        }
        let probe = points[0];
        let mut best: Option<(usize, f64)> = None;
        for (o, (outer, outer_area)) in rings.iter().enumerate() {
            if o == h || *outer_area <= 0.0 {
                continue;
            }
            // There is a hole (this one), so every ring has its box.
            let (lo, hi) = boxes[o];
            if probe.cmplt(lo).any() || probe.cmpgt(hi).any() {
                continue;
            }
            if best.is_some_and(|(_, a)| a <= *outer_area) {
                continue;
            }
            if contains(outer, probe) {
                best = Some((o, *outer_area));
            }
        }
        parents.push(best.map(|(o, _)| o));
    }
    // A hole without an enclosing outer ring can only come from a numerically degenerate field;
    // it is dropped, so every hole in the output knows its parent.
    let mut index = Vec::with_capacity(rings.len());
    let mut next = 0usize;
    for (i, (_, area)) in rings.iter().enumerate() {
        let keep = *area > 0.0 || parents[i].is_some();
        index.push(keep.then_some(next));
        next += usize::from(keep);
    }
    rings
        .into_iter()
        .enumerate()
        .filter_map(|(i, (points, area))| {
            index[i]?;
            let parent = parents[i].and_then(|p| index[p]);
            Some(Ring {
                points,
                hole: area < 0.0,
                parent,
            })
        })
        .collect()
}

/// Checks that rings are usable as a polygon with holes: every ring has at least three finite
/// points, holes name an outer ring as parent and outer rings name none, and no two edges
/// (of the same ring or of different rings) cross, touch or overlap, and no edge has zero
/// length.
///
/// Orientation is not checked: the even–odd rule needs none.
///
/// # Errors
///
/// [`MarchError::NonFinite`], [`MarchError::TooFewPoints`], [`MarchError::BadParent`] or
/// [`MarchError::RingsCross`] for the first problem found.
///
/// ```
/// use creature_march::{glam::Vec2, validate_rings, MarchError, Ring};
///
/// let bow_tie = Ring {
///     points: vec![Vec2::ZERO, Vec2::ONE, Vec2::X, Vec2::Y],
///     hole: false,
///     parent: None,
/// };
/// assert!(matches!(validate_rings(&[bow_tie]), Err(MarchError::RingsCross { .. })));
/// ```
pub fn validate_rings(rings: &[Ring]) -> Result<(), MarchError> {
    validate_structure(rings)?;
    let lists: Vec<&[Vec2]> = rings.iter().map(|r| r.points.as_slice()).collect();
    find_crossing(&lists).map_or(Ok(()), |(ring_a, ring_b, near)| {
        Err(MarchError::RingsCross {
            ring_a,
            ring_b,
            near,
        })
    })
}

/// Everything [`validate_rings`] checks except intersections.
pub(crate) fn validate_structure(rings: &[Ring]) -> Result<(), MarchError> {
    for (r, ring) in rings.iter().enumerate() {
        if ring.points.len() < 3 {
            return Err(MarchError::TooFewPoints {
                ring: r,
                len: ring.points.len(),
            });
        }
        if !ring.points.iter().all(|p| p.is_finite()) {
            return Err(MarchError::NonFinite {
                what: "point of ring",
                index: r,
            });
        }
        let parent_ok = match (ring.hole, ring.parent) {
            (false, None) => true,
            (true, Some(p)) => rings.get(p).is_some_and(|outer| !outer.hole),
            _ => false,
        };
        if !parent_ok {
            return Err(MarchError::BadParent {
                ring: r,
                parent: ring.parent,
            });
        }
    }
    Ok(())
}

/// `> 0` when `c` lies left of `a → b`, `< 0` right, `0` on the line: exact (Shewchuk's
/// adaptive predicate). In plain `f64`, `3 − 1e-45` rounds to 3, and a ring whose edges cross
/// 1e-45 from the origin passed `validate_rings`, then failed `triangulate` (regression:
/// `regression_validate_rings_sees_a_crossing_at_tiny_coordinates`).
fn orient(a: D2, b: D2, c: D2) -> f64 {
    let coord = |p: D2| robust::Coord { x: p.x, y: p.y };
    robust::orient2d(coord(a), coord(b), coord(c))
}

fn on_segment(a: D2, b: D2, p: D2) -> bool {
    p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
}

/// Whether closed segments `ab` and `cd` share any point.
fn segments_meet(a: D2, b: D2, c: D2, d: D2) -> bool {
    let o1 = orient(a, b, c);
    let o2 = orient(a, b, d);
    let o3 = orient(c, d, a);
    let o4 = orient(c, d, b);
    if ((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0))
        && ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0))
    {
        return true;
    }
    (o1 == 0.0 && on_segment(a, b, c))
        || (o2 == 0.0 && on_segment(a, b, d))
        || (o3 == 0.0 && on_segment(c, d, a))
        || (o4 == 0.0 && on_segment(c, d, b))
}

struct Segment {
    ring: usize,
    edge: usize,
    len: usize,
    a: D2,
    b: D2,
    lo: D2,
    hi: D2,
}

/// Finds a pair of intersecting edges among closed rings: `(ring_a, ring_b, point near)`.
/// Adjacent edges of a ring may share their common vertex, but not fold back onto each
/// other; zero-length edges count as a self-intersection. Sweep over x: O(n log n + pairs
/// overlapping in x).
pub(crate) fn find_crossing(rings: &[&[Vec2]]) -> Option<(usize, usize, Vec2)> {
    let mut segments: Vec<Segment> = Vec::new();
    for (r, points) in rings.iter().enumerate() {
        let n = points.len();
        for i in 0..n {
            let a = points[i].into_d2();
            let b = points[(i + 1) % n].into_d2();
            if a == b {
                return Some((r, r, points[i]));
            }
            // A spike: the next edge folds back along this one.
            let c = points[(i + 2) % n].into_d2();
            // Collinear, so `c` is on the ray from `b` through `a` exactly when one of the two
            // lies on the segment from `b` to the other (comparisons only: exact).
            if n >= 3 && orient(a, b, c) == 0.0 && (on_segment(b, a, c) || on_segment(b, c, a)) {
                return Some((r, r, points[(i + 1) % n]));
            }
            segments.push(Segment {
                ring: r,
                edge: i,
                len: n,
                a,
                b,
                lo: a.min(b),
                hi: a.max(b),
            });
        }
    }
    segments.sort_by(|s, t| {
        s.lo.x
            .total_cmp(&t.lo.x)
            .then(s.ring.cmp(&t.ring))
            .then(s.edge.cmp(&t.edge))
    });
    for (k, s) in segments.iter().enumerate() {
        for t in &segments[k + 1..] {
            if t.lo.x > s.hi.x {
                break;
            }
            if t.lo.y > s.hi.y || t.hi.y < s.lo.y {
                continue;
            }
            if s.ring == t.ring {
                let n = s.len;
                let adjacent = (s.edge + 1) % n == t.edge || (t.edge + 1) % n == s.edge;
                if adjacent {
                    continue;
                }
            }
            if segments_meet(s.a, s.b, t.a, t.b) {
                let near = Vec2::new(
                    ((s.a.x + s.b.x) * 0.5) as f32,
                    ((s.a.y + s.b.y) * 0.5) as f32,
                );
                let (a, b) = if s.ring <= t.ring {
                    (s.ring, t.ring)
                } else {
                    (t.ring, s.ring)
                };
                return Some((a, b, near));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::*;

    fn square(o: Vec2, s: f32, ccw: bool) -> Vec<Vec2> {
        let mut p = vec![o, o + Vec2::X * s, o + Vec2::splat(s), o + Vec2::Y * s];
        if !ccw {
            p.reverse();
        }
        p
    }

    #[test]
    fn area_and_containment() {
        let r = Ring {
            points: square(Vec2::ZERO, 2.0, true),
            hole: false,
            parent: None,
        };
        assert_eq!(r.signed_area(), 4.0);
        assert_eq!(r.perimeter(), 8.0);
        assert!(r.contains(Vec2::ONE));
        assert!(!r.contains(Vec2::splat(3.0)));
        assert_eq!(r.bounds(), Some((Vec2::ZERO, Vec2::splat(2.0))));
    }

    #[test]
    fn weld_merges_near_duplicates_and_wraps() {
        let mut p = vec![
            Vec2::ZERO,
            Vec2::new(0.001, 0.0),
            Vec2::X,
            Vec2::ONE,
            Vec2::new(0.0, 0.0005),
        ];
        weld(&mut p, 0.01);
        assert_eq!(p, vec![Vec2::ZERO, Vec2::X, Vec2::ONE]);
        let mut q = vec![Vec2::ZERO, Vec2::ZERO, Vec2::X];
        weld(&mut q, 0.0);
        assert_eq!(q, vec![Vec2::ZERO, Vec2::X]);
    }

    #[test]
    fn finish_assigns_holes_and_parents() {
        let rings = finish(
            vec![
                square(Vec2::splat(1.0), 1.0, false),
                square(Vec2::ZERO, 3.0, true),
                square(Vec2::splat(10.0), 1.0, true),
            ],
            0.0,
        );
        assert_eq!(rings.len(), 3);
        assert!(rings[0].hole);
        assert_eq!(rings[0].parent, Some(1));
        assert!(!rings[1].hole && rings[1].parent.is_none());
        assert!(!rings[2].hole);
    }

    #[test]
    fn known_areas_give_what_finish_gives() {
        // One ring that welding leaves alone, and a sliver it shortens (a near-duplicate
        // point), which turns it from counter-clockwise to clockwise: its area before welding
        // must not be kept.
        let whole = square(Vec2::splat(20.0), 3.0, true);
        let sliver = vec![
            Vec2::ZERO,
            Vec2::new(10.0, 0.0),
            Vec2::new(10.0, 0.4),
            Vec2::new(5.0, -0.1),
        ];
        assert!(signed_area(&sliver) > 0.0);
        let raw = vec![whole, sliver];
        let known = raw.iter().map(|p| (p.clone(), Some(signed_area(p))));
        let rings = finish_with_areas(known, 0.5);
        assert_eq!(rings, finish(raw, 0.5));
        // The sliver, welded, is a hole with no outer ring around it: dropped.
        assert_eq!(rings.len(), 1);
    }

    #[test]
    fn orphan_holes_and_degenerate_rings_are_dropped() {
        let rings = finish(
            vec![
                square(Vec2::ZERO, 1.0, false),
                vec![Vec2::ZERO, Vec2::X, Vec2::X * 2.0],
            ],
            0.0,
        );
        assert!(rings.is_empty());
    }

    #[test]
    fn crossing_detection() {
        let a = square(Vec2::ZERO, 2.0, true);
        let b = square(Vec2::ONE, 2.0, true);
        let c = square(Vec2::splat(5.0), 1.0, true);
        assert!(find_crossing(&[&a, &c]).is_none());
        assert_eq!(find_crossing(&[&a, &b]).map(|x| (x.0, x.1)), Some((0, 1)));
        // Touching at a corner counts.
        let d = square(Vec2::splat(2.0), 1.0, true);
        assert!(find_crossing(&[&a, &d]).is_some());
        // A spike folding back onto itself.
        let spike = vec![Vec2::ZERO, Vec2::X * 2.0, Vec2::X, Vec2::Y];
        assert!(find_crossing(&[&spike]).is_some());
        // Zero-length edge.
        let dup = vec![Vec2::ZERO, Vec2::ZERO, Vec2::X, Vec2::Y];
        assert!(find_crossing(&[&dup]).is_some());
    }

    #[test]
    fn validate_rings_checks_parents() {
        let outer = Ring {
            points: square(Vec2::ZERO, 4.0, true),
            hole: false,
            parent: None,
        };
        let hole = Ring {
            points: square(Vec2::ONE, 1.0, false),
            hole: true,
            parent: Some(0),
        };
        assert!(validate_rings(&[outer.clone(), hole.clone()]).is_ok());
        let orphan = Ring {
            parent: None,
            ..hole.clone()
        };
        assert_eq!(
            validate_rings(&[outer.clone(), orphan]),
            Err(MarchError::BadParent {
                ring: 1,
                parent: None
            })
        );
        let wrong = Ring {
            parent: Some(1),
            ..hole
        };
        assert!(validate_rings(&[outer, wrong]).is_err());
    }
}
