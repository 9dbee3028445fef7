//! The geometry the checks need: a closed mesh's centre of volume, a convex hull in the ground
//! plane and a point's margin inside it, and the distance between two segments.

use glam::{Vec2, Vec3};

/// The centre of the volume enclosed by a triangle mesh (signed tetrahedra from a reference
/// point inside its bounds, accumulated in `f64`), and that volume. Closed parts count by
/// their volume; a two-sheet membrane counts as the thin plate between its sheets. `None` when
/// the volume is not positive.
pub(crate) fn centre_of_volume(positions: &[Vec3], triangles: &[[u32; 3]]) -> Option<(Vec3, f32)> {
    let (lo, hi) = positions.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let o = 0.5 * (lo + hi);
    let d = |p: Vec3| (p - o).to_array().map(f64::from);
    let mut volume = 0.0f64;
    let mut moment = [0.0f64; 3];
    for t in triangles {
        let [a, b, c] = t.map(|i| d(positions[i as usize]));
        let cross = [
            b[1] * c[2] - b[2] * c[1],
            b[2] * c[0] - b[0] * c[2],
            b[0] * c[1] - b[1] * c[0],
        ];
        let v = (a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2]) / 6.0;
        volume += v;
        for k in 0..3 {
            moment[k] += v * (a[k] + b[k] + c[k]) / 4.0;
        }
    }
    (volume > 0.0).then(|| {
        let m = moment.map(|m| (m / volume) as f32);
        (o + Vec3::from_array(m), volume as f32)
    })
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain); fewer than three
/// points when they are all on one line.
pub(crate) fn convex_hull(points: &[Vec2]) -> Vec<Vec2> {
    let mut p: Vec<Vec2> = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: Vec2, a: Vec2, b: Vec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<Vec2> = Vec::with_capacity(2 * p.len());
    // The lower hull left to right, then the upper hull back, never popping into the lower.
    for &q in &p {
        while hull.len() >= 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0 {
            hull.pop();
        }
        hull.push(q);
    }
    let lower = hull.len() + 1;
    for &q in p.iter().rev().skip(1) {
        while hull.len() >= lower && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0 {
            hull.pop();
        }
        hull.push(q);
    }
    hull.pop();
    hull
}

/// The signed distance from `q` to the boundary of the convex polygon `hull`
/// (counter-clockwise): positive inside, negative outside. A hull of one or two points (or
/// none) has no inside: minus the distance to it.
pub(crate) fn margin(hull: &[Vec2], q: Vec2) -> f32 {
    match hull.len() {
        0 => f32::NEG_INFINITY,
        1 => -q.distance(hull[0]),
        2 => -point_segment(q, hull[0], hull[1]),
        n => {
            let mut inside = true;
            let mut nearest = f32::INFINITY;
            for i in 0..n {
                let (a, b) = (hull[i], hull[(i + 1) % n]);
                if (b - a).perp_dot(q - a) < 0.0 {
                    inside = false;
                }
                nearest = nearest.min(point_segment(q, a, b));
            }
            if inside { nearest } else { -nearest }
        }
    }
}

fn point_segment(q: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((q - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    q.distance(a + ab * t)
}

/// The smallest distance between segments `p0 p1` and `q0 q1`.
pub(crate) fn segment_distance(p0: Vec3, p1: Vec3, q0: Vec3, q1: Vec3) -> f32 {
    // Ericson, Real-Time Collision Detection, 5.1.9.
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.dot(d1), d2.dot(d2), d2.dot(r));
    let eps = 1e-12;
    let (s, t) = if a <= eps && e <= eps {
        (0.0, 0.0)
    } else if a <= eps {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(r);
        if e <= eps {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let mut s = if denom > eps {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
            (s, t)
        }
    };
    (p0 + d1 * s).distance(q0 + d2 * t)
}

/// A terrain: an unskinned triangle mesh the creature walks on, looked up by height under a
/// point (triangles bucketed on a grid over their bounds in the ground plane).
#[derive(Debug, Clone, PartialEq)]
pub struct Terrain {
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    origin: Vec2,
    cell: f32,
    columns: usize,
    rows: usize,
    buckets: Vec<Vec<u32>>,
}

impl Terrain {
    /// The terrain of a triangle mesh (in world space); `None` when it has no triangle with an
    /// area seen from above, or a non-finite position.
    #[must_use]
    pub fn new(positions: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Option<Self> {
        if positions.iter().any(|p| !p.is_finite())
            || triangles
                .iter()
                .flatten()
                .any(|&v| v as usize >= positions.len())
        {
            return None;
        }
        let flat = |p: Vec3| Vec2::new(p.x, p.z);
        let (lo, hi) = triangles.iter().flatten().fold(
            (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY)),
            |(lo, hi), &v| {
                (
                    lo.min(flat(positions[v as usize])),
                    hi.max(flat(positions[v as usize])),
                )
            },
        );
        let size = hi - lo;
        if !(size.x > 0.0 && size.y > 0.0) {
            return None;
        }
        // About two triangles per bucket.
        let cell = (size.x * size.y * 2.0 / triangles.len() as f32).sqrt();
        let columns = ((size.x / cell).ceil() as usize).clamp(1, 4096);
        let rows = ((size.y / cell).ceil() as usize).clamp(1, 4096);
        let cell = (size.x / columns as f32).max(size.y / rows as f32);
        let mut terrain = Self {
            positions,
            triangles,
            origin: lo,
            cell,
            columns,
            rows,
            buckets: vec![Vec::new(); columns * rows],
        };
        for (t, tri) in terrain.triangles.iter().enumerate() {
            let corners = tri.map(|v| flat(terrain.positions[v as usize]));
            let (a, b) = corners
                .iter()
                .fold((corners[0], corners[0]), |(lo, hi), &c| {
                    (lo.min(c), hi.max(c))
                });
            let (i0, j0) = terrain.bucket(a);
            let (i1, j1) = terrain.bucket(b);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    terrain.buckets[j * columns + i].push(t as u32);
                }
            }
        }
        Some(terrain)
    }

    /// The bucket holding `p` (clamped to the grid).
    fn bucket(&self, p: Vec2) -> (usize, usize) {
        let at = |v: f32, n: usize| (v.max(0.0) as usize).min(n - 1);
        let q = (p - self.origin) / self.cell;
        (at(q.x, self.columns), at(q.y, self.rows))
    }

    /// The terrain's height under `(x, z)` (the highest of its triangles there), `None` off it.
    #[must_use]
    pub fn height(&self, x: f32, z: f32) -> Option<f32> {
        let p = Vec2::new(x, z);
        let q = (p - self.origin) / self.cell;
        if !(q.x >= -1e-4
            && q.y >= -1e-4
            && q.x <= self.columns as f32 + 1e-4
            && q.y <= self.rows as f32 + 1e-4)
        {
            return None;
        }
        let (i, j) = self.bucket(p);
        let mut best: Option<f32> = None;
        for &t in &self.buckets[j * self.columns + i] {
            let [a, b, c] = self.triangles[t as usize].map(|v| self.positions[v as usize]);
            let (ab, ac) = (b - a, c - a);
            let det = ab.x * ac.z - ab.z * ac.x;
            if det == 0.0 {
                continue;
            }
            let (px, pz) = (x - a.x, z - a.z);
            let u = (px * ac.z - pz * ac.x) / det;
            let v = (ab.x * pz - ab.z * px) / det;
            let e = 1e-5;
            if u >= -e && v >= -e && u + v <= 1.0 + e {
                let h = a.y + u * ab.y + v * ac.y;
                best = Some(best.map_or(h, |b: f32| b.max(h)));
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cube_has_its_centre_and_volume() {
        // A unit cube from (1, 2, 3), triangles wound outward.
        let p: Vec<Vec3> = (0..8)
            .map(|i| {
                Vec3::new(1.0, 2.0, 3.0)
                    + Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32)
            })
            .collect();
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let tris: Vec<[u32; 3]> = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        let (c, v) = centre_of_volume(&p, &tris).unwrap();
        assert!((v - 1.0).abs() < 1e-5, "{v}");
        assert!(c.distance(Vec3::new(1.5, 2.5, 3.5)) < 1e-5, "{c}");
        // Inside out: no positive volume.
        let flipped: Vec<[u32; 3]> = tris.iter().map(|t| [t[0], t[2], t[1]]).collect();
        assert!(centre_of_volume(&p, &flipped).is_none());
    }

    #[test]
    fn margins_are_positive_inside_and_negative_outside() {
        let square = [
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(0.0, 2.0),
            Vec2::new(1.0, 1.0),
        ];
        let hull = convex_hull(&square);
        assert_eq!(hull.len(), 4);
        assert!((margin(&hull, Vec2::new(1.0, 0.5)) - 0.5).abs() < 1e-6);
        assert!((margin(&hull, Vec2::new(3.0, 1.0)) + 1.0).abs() < 1e-6);
        // Two feet: a segment has no inside.
        let two = convex_hull(&[Vec2::new(0.0, 0.0), Vec2::new(0.0, 2.0)]);
        assert!(margin(&two, Vec2::new(0.0, 1.0)) <= 0.0);
    }

    #[test]
    fn segment_distances() {
        let d = segment_distance(
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(0.5, 1.0, -1.0),
            Vec3::new(0.5, 1.0, 1.0),
        );
        assert!((d - 1.0).abs() < 1e-6);
        let d = segment_distance(
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
        );
        assert!((d - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_terrain_answers_the_height_of_its_triangles() {
        // Two triangles over the unit square, rising along X: y = x.
        let positions = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 1.0, 1.0),
        ];
        let terrain = Terrain::new(positions, vec![[0, 2, 1], [1, 2, 3]]).unwrap();
        for (x, z) in [(0.25, 0.5), (0.75, 0.1), (0.5, 0.9), (1.0, 1.0), (0.0, 0.0)] {
            let h = terrain.height(x, z).unwrap();
            assert!((h - x).abs() < 1e-5, "({x}, {z}): {h}");
        }
        assert_eq!(terrain.height(1.5, 0.5), None);
        assert_eq!(terrain.height(0.5, -0.5), None);
        assert!(Terrain::new(vec![Vec3::ZERO; 3], vec![[0, 1, 2]]).is_none());
        assert!(Terrain::new(vec![Vec3::NAN; 3], vec![[0, 1, 2]]).is_none());
        assert!(Terrain::new(vec![Vec3::ZERO; 3], vec![[0, 1, 5]]).is_none());
    }
}
