//! `creature-march`'s mesher: `validate_rings` and `triangulate` on star-shaped rings with
//! holes (valid flavour) or arbitrary point lists, differentially against spade's constrained
//! Delaunay triangulation: whatever `validate_rings` accepts, spade and `triangulate` must
//! both accept, the meshes must cover the same area, and every ring vertex must be kept.

use arbitrary::Arbitrary;
use creature_march::{MarchError, Mesh2, MeshOptions, Ring, triangulate, validate_rings};
use glam::Vec2;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use crate::{map, pick};

#[derive(Debug, Clone, Arbitrary)]
pub struct RingIn {
    pub hole: bool,
    pub parent: u8,
    pub points: Vec<[f32; 2]>,
}

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub valid: bool,
    pub spacing: f32,
    pub clearance: f32,
    pub min_angle: f32,
    pub budget: u16,
    pub simplify: f32,
    pub center: [f32; 2],
    pub scale: f32,
    pub rings: Vec<RingIn>,
}

/// A star-shaped ring around `center`: angles strictly increasing, radii in
/// `[lo, hi] × scale`, so it is simple; clockwise for a hole.
fn star(center: Vec2, scale: f32, lo: f32, hi: f32, raw: &[[f32; 2]], hole: bool) -> Vec<Vec2> {
    let n = raw.len().max(3);
    let mut points: Vec<Vec2> = (0..n)
        .map(|i| {
            let r = raw.get(i).copied().unwrap_or([0.0, 0.0]);
            let angle = (i as f32 + map(r[0], 0.0, 0.9)) / n as f32 * core::f32::consts::TAU;
            center + Vec2::from_angle(angle) * map(r[1], lo, hi) * scale
        })
        .collect();
    if hole {
        points.reverse();
    }
    points
}

#[must_use]
pub fn rings(input: &Input) -> Vec<Ring> {
    if input.valid {
        let center = Vec2::new(
            map(input.center[0], -1e3, 1e3),
            map(input.center[1], -1e3, 1e3),
        );
        let scale = map(input.scale, 1e-2, 1e3);
        let mut out = Vec::new();
        for (i, r) in input.rings.iter().take(3).enumerate() {
            let raw = &r.points[..r.points.len().min(48)];
            match i {
                0 => out.push(Ring {
                    points: star(center, scale, 0.5, 1.0, raw, false),
                    hole: false,
                    parent: None,
                }),
                1 if r.hole => out.push(Ring {
                    points: star(center, scale, 0.1, 0.45, raw, true),
                    hole: true,
                    parent: Some(0),
                }),
                _ => out.push(Ring {
                    points: star(
                        center + Vec2::X * 3.0 * scale * (i as f32),
                        scale,
                        0.5,
                        1.0,
                        raw,
                        false,
                    ),
                    hole: false,
                    parent: None,
                }),
            }
        }
        out
    } else {
        input
            .rings
            .iter()
            .take(4)
            .map(|r| Ring {
                points: r.points.iter().take(64).map(|p| Vec2::from(*p)).collect(),
                hole: r.hole,
                parent: r.hole.then_some(usize::from(r.parent)),
            })
            .collect()
    }
}

#[must_use]
pub fn options(input: &Input, rings: &[Ring]) -> MeshOptions {
    let v = input.valid;
    let extent = extent(rings);
    let spacing = if v {
        if input.spacing.to_bits().is_multiple_of(4) {
            0.0
        } else {
            map(input.spacing, 0.03, 1.0) * extent
        }
    } else {
        input.spacing
    };
    let budget = match input.budget {
        u16::MAX => None,
        b => Some(usize::from(b % 2000)),
    };
    let simplify = if v && input.simplify.to_bits().is_multiple_of(2) {
        0.0
    } else {
        pick(v, input.simplify, 0.0, 0.02) * if v { extent } else { 1.0 }
    };
    MeshOptions::DEFAULT
        .with_interior_spacing(spacing)
        .with_clearance(pick(v, input.clearance, 0.0, 2.0))
        .with_min_angle(pick(v, input.min_angle, 0.0, 33.0))
        .with_max_added_vertices(budget)
        .with_simplify(simplify)
}

/// The rings' bounding box, in `f64`.
fn bounds(rings: &[Ring]) -> (glam::DVec2, glam::DVec2) {
    let (mut lo, mut hi) = (
        glam::DVec2::splat(f64::INFINITY),
        glam::DVec2::splat(f64::NEG_INFINITY),
    );
    for p in rings.iter().flat_map(|r| &r.points) {
        lo = lo.min(p.as_dvec2());
        hi = hi.max(p.as_dvec2());
    }
    (lo, hi)
}

fn extent(rings: &[Ring]) -> f32 {
    let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    for p in rings.iter().flat_map(|r| &r.points) {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    (hi - lo).max_element()
}

fn orient_exact(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    let coord = |p: Vec2| robust::Coord {
        x: f64::from(p.x),
        y: f64::from(p.y),
    };
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// Whether the closed segments `ab` and `cd` share a point (exact predicates).
fn segments_meet(a: Vec2, b: Vec2, c: Vec2, d: Vec2) -> bool {
    let (o1, o2) = (orient_exact(a, b, c), orient_exact(a, b, d));
    let (o3, o4) = (orient_exact(c, d, a), orient_exact(c, d, b));
    let within = |a: Vec2, b: Vec2, p: Vec2| p.cmpge(a.min(b)).all() && p.cmple(a.max(b)).all();
    (o1 * o2 < 0.0 && o3 * o4 < 0.0)
        || (o1 == 0.0 && within(a, b, c))
        || (o2 == 0.0 && within(a, b, d))
        || (o3 == 0.0 && within(c, d, a))
        || (o4 == 0.0 && within(c, d, b))
}

/// The reference for what `validate_rings` promises of rings whose structure is valid: no
/// zero-length edge, adjacent edges of a ring meeting only at their shared vertex, and no
/// other two edges (of one ring or two) sharing any point. Brute force over all edge pairs
/// with Shewchuk's exact orientation test, independent of the crate's sweep.
fn rings_are_simple(rings: &[Ring]) -> bool {
    let mut edges = Vec::new();
    for (r, ring) in rings.iter().enumerate() {
        let n = ring.points.len();
        for i in 0..n {
            let (a, b) = (ring.points[i], ring.points[(i + 1) % n]);
            if a == b {
                return false;
            }
            edges.push((r, i, n, a, b));
        }
    }
    for (k, &(r, i, n, a, b)) in edges.iter().enumerate() {
        for &(s, j, _, c, d) in &edges[k + 1..] {
            if r == s && (j == (i + 1) % n || i == (j + 1) % n) {
                // Adjacent: they share one vertex; they must not fold onto each other (in a
                // triangle each edge is adjacent to both others, so check both ends).
                let shared_ok = |p: Vec2, q: Vec2, shared: Vec2| {
                    orient_exact(p, shared, q) != 0.0
                        || (p.as_dvec2() - shared.as_dvec2()).dot(q.as_dvec2() - shared.as_dvec2())
                            < 0.0
                };
                if (b == c && !shared_ok(a, d, b)) || (d == a && !shared_ok(c, b, a)) {
                    return false;
                }
                continue;
            }
            if segments_meet(a, b, c, d) {
                return false;
            }
        }
    }
    true
}

/// Twice the areas of triangles, summed exactly: a Shewchuk expansion (non-overlapping `f64`
/// parts, smallest first, grown by error-free sums), rounded once at the end.
///
/// `robust::orient2d` gives an orientation's exact *sign*, but its value is only the plain
/// `f64` estimate `(a − c) × (b − c)` whenever that clears its error bound: off by up to about
/// `3.3e-16` times the sum of the two products' magnitudes, all of a thin triangle's area
/// (regression: the tiny ring (−8, −8), (3, 3), (4.8e-33, −3.03e-13), a triangle 3e-13 wide
/// and 15 long, has the exact area 1.667407e-12; `orient2d` read 1.667999e-12 for the mesh's
/// two halves and 1.662670e-12 for spade's one triangle, 0.3 % apart, past the 1e-3 check,
/// though both meshes cover the ring exactly).
#[derive(Debug, Default)]
struct ExactArea {
    parts: Vec<f64>,
}

impl ExactArea {
    /// Adds `x` exactly (Shewchuk's grow-expansion, zero parts dropped).
    fn add(&mut self, x: f64) {
        let mut q = x;
        let mut kept = 0;
        for i in 0..self.parts.len() {
            let e = self.parts[i];
            // Knuth's two-sum: `s + err == q + e` exactly.
            let s = q + e;
            let b = s - q;
            let err = (q - (s - b)) + (e - b);
            if err != 0.0 {
                self.parts[kept] = err;
                kept += 1;
            }
            q = s;
        }
        self.parts.truncate(kept);
        if q != 0.0 {
            self.parts.push(q);
        }
    }

    /// Adds `a × b` exactly: the rounded product and its error (`mul_add`, exact unless the
    /// error underflows, which products of `f32` coordinates cannot: they are exact in `f64`).
    fn add_product(&mut self, a: f64, b: f64) {
        let p = a * b;
        self.add(a.mul_add(b, -p));
        self.add(p);
    }

    /// Adds twice the signed area of the triangle `abc` (positive counter-clockwise):
    /// `(b − a) × (c − a)` expanded into six products, each summed exactly.
    fn add_triangle(&mut self, [a, b, c]: [[f64; 2]; 3]) {
        for (p, q, r) in [(a, b, c), (b, c, a), (c, a, b)] {
            // Σ over the rotations of p.x (q.y − r.y).
            self.add_product(p[0], q[1]);
            self.add_product(-p[0], r[1]);
        }
    }

    /// The sum, rounded: the parts added smallest first (non-overlapping, so within a few
    /// units in the last place).
    fn value(&self) -> f64 {
        self.parts.iter().sum()
    }
}

/// The area spade's constrained triangulation of the ring edges covers inside the rings, or
/// `None` when spade cannot take the points (coordinates outside its range).
fn spade_area(rings: &[Ring]) -> Option<Result<f64, String>> {
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    for ring in rings {
        let mut handles = Vec::new();
        for p in &ring.points {
            handles.push(
                cdt.insert(Point2::new(f64::from(p.x), f64::from(p.y)))
                    .ok()?,
            );
        }
        for i in 0..handles.len() {
            let (a, b) = (handles[i], handles[(i + 1) % handles.len()]);
            if a == b || !cdt.can_add_constraint(a, b) {
                return Some(Err(format!(
                    "spade rejects edge {i} of a ring: {:?}",
                    ring.points
                )));
            }
            cdt.add_constraint(a, b);
        }
    }
    // Which faces lie inside, by even–odd parity of the constraint edges crossed from the
    // outer face (as the mesher decides), not by testing a centroid: a sliver's centroid
    // rounds onto its edge's line, and its area in plain `f64` cancels to 0 (regression: the
    // ring (3.000002, 6), (0, 5.9e-39), (−100, −100), (0, 0) has a wedge 5.9e-39 wide that
    // the centroid test left out, and spade's area was 3 % of the ring's).
    let mut inside: Vec<Option<bool>> = vec![None; cdt.num_all_faces()];
    let mut stack = Vec::new();
    for face in cdt.inner_faces() {
        for e in face.adjacent_edges() {
            if e.rev().face().is_outer() && inside[face.fix().index()].is_none() {
                let side = e.is_constraint_edge();
                inside[face.fix().index()] = Some(side);
                stack.push((face, side));
            }
        }
    }
    while let Some((face, side)) = stack.pop() {
        for e in face.adjacent_edges() {
            if let Some(next) = e.rev().face().as_inner() {
                let slot = &mut inside[next.fix().index()];
                if slot.is_none() {
                    let next_side = side ^ e.is_constraint_edge();
                    *slot = Some(next_side);
                    stack.push((next, next_side));
                }
            }
        }
    }
    // Summed exactly: `orient2d`'s value is only an estimate (see `ExactArea`). Spade's inner
    // faces are counter-clockwise.
    let mut area = ExactArea::default();
    for face in cdt.inner_faces() {
        if inside[face.fix().index()] == Some(true) {
            area.add_triangle(face.positions().map(|p| [p.x, p.y]));
        }
    }
    Some(Ok(area.value() / 2.0))
}

fn check_mesh(mesh: &Mesh2, rings: &[Ring], options: &MeshOptions) -> f64 {
    let n = mesh.positions.len();
    assert!(
        mesh.positions.iter().all(|p| p.is_finite()),
        "non-finite mesh vertex"
    );
    let mut used = vec![false; n];
    let mut area = ExactArea::default();
    for t in &mesh.triangles {
        for &i in t {
            assert!((i as usize) < n, "triangle index {i} of {n}");
            used[i as usize] = true;
        }
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let o = robust::orient2d(
            robust::Coord {
                x: f64::from(a.x),
                y: f64::from(a.y),
            },
            robust::Coord {
                x: f64::from(b.x),
                y: f64::from(b.y),
            },
            robust::Coord {
                x: f64::from(c.x),
                y: f64::from(c.y),
            },
        );
        assert!(
            o > 0.0,
            "triangle {t:?} ({a}, {b}, {c}) is not counter-clockwise"
        );
        // The exact area, not `o / 2` (see `ExactArea`).
        area.add_triangle([a, b, c].map(|p| p.as_dvec2().to_array()));
    }
    assert!(used.iter().all(|u| *u), "a vertex no triangle uses");
    if options.simplify == 0.0 {
        let ring_points: Vec<Vec2> = rings
            .iter()
            .flat_map(|r| r.points.iter().copied())
            .collect();
        assert_eq!(mesh.outline_len, ring_points.len(), "outline_len");
        assert_eq!(
            &mesh.positions[..mesh.outline_len],
            &ring_points[..],
            "ring vertices not kept in order"
        );
    }
    let q = mesh.quality;
    assert!(
        q.min_angle.is_finite() && (0.0..=60.0).contains(&q.min_angle),
        "min_angle {}",
        q.min_angle
    );
    assert!(q.below_limit <= mesh.triangles.len() && q.below_20 <= mesh.triangles.len());
    area.value() / 2.0
}

pub fn run(input: &Input) {
    let rings = rings(input);
    let options = options(input, &rings);
    if options.validate().is_ok() && options.interior_spacing > 0.0 {
        // Keep an execution short: skip between ~20k interior lattice points and well past
        // MAX_INTERIOR_POINTS, where triangulate refuses at once. The count is triangulate's
        // own, over the bounding box (a thin box holds far fewer points than the square of
        // its extent: a triangle 6.5e6 by 49 took minutes). Simplified rings may have a
        // smaller box, so with `simplify` every large lattice is skipped.
        let (lo, hi) = bounds(&rings);
        let spacing = f64::from(options.interior_spacing);
        let count = ((hi.x - lo.x) / spacing + 1.0) * ((hi.y - lo.y) / (spacing * 0.866) + 1.0);
        let refused = count > 4.0 * creature_march::MAX_INTERIOR_POINTS as f64;
        if count > 20_000.0 && (!refused || options.simplify > 0.0) {
            return;
        }
    }
    let valid = validate_rings(&rings);
    if input.valid {
        // Star rings are simple in exact arithmetic, but not always once their points are
        // rounded to `f32` (a tiny scale far from the origin leaves a ring a few units in the
        // last place across, where rounding can fold it), nor is a hole always inside its
        // outer ring (three points with an angle gap past 180° leave the centre outside). So
        // validate_rings is checked against the exact reference, both ways.
        assert_eq!(
            valid.is_ok(),
            rings_are_simple(&rings),
            "validate_rings vs the exact reference: {valid:?}"
        );
    }
    let result = triangulate(&rings, &options);
    assert_eq!(
        format!("{:?}", triangulate(&rings, &options)),
        format!("{result:?}"),
        "determinism"
    );
    if let Err(MarchError::ExtentTooLarge { extent: e, max }) = result {
        // Only for an interior lattice over a box past the bound (the box in `f64`, where
        // its side cannot overflow).
        let (lo, hi) = bounds(&rings);
        assert!(
            options.interior_spacing > 0.0 && (hi - lo).max_element() > f64::from(max),
            "ExtentTooLarge ({e}) for a box {lo}..{hi} with spacing {}",
            options.interior_spacing
        );
    }
    if options.validate().is_err() {
        assert!(result.is_err(), "invalid options accepted: {options:?}");
        return;
    }
    if valid.is_err() {
        // triangulate may still mesh rings validate_rings rejects (it checks crossings as it
        // meshes); only its output is checked.
        if let Ok(mesh) = &result {
            check_mesh(mesh, &rings, &options);
        }
        return;
    }
    if rings.is_empty() {
        assert!(result.as_ref().is_ok_and(|m| m.triangles.is_empty()));
        return;
    }
    let spade = spade_area(&rings);
    let mesh = match result {
        Ok(mesh) => mesh,
        Err(MarchError::InteriorTooDense { .. } | MarchError::ExtentTooLarge { .. }) => return,
        Err(e) => panic!(
            "validate_rings accepts the rings but triangulate fails: {e:?} (spade: {spade:?})"
        ),
    };
    let area = check_mesh(&mesh, &rings, &options);
    // The reported smallest angle, against one computed in f64.
    let mut smallest = if mesh.triangles.is_empty() {
        0.0
    } else {
        f64::INFINITY
    };
    for t in &mesh.triangles {
        let p = t.map(|i| mesh.positions[i as usize].as_dvec2());
        for k in 0..3 {
            let (a, b) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            smallest = smallest.min(a.angle_to(b).abs().to_degrees());
        }
    }
    assert!(
        (f64::from(mesh.quality.min_angle) - smallest).abs() <= 0.01,
        "quality.min_angle {} but the smallest angle is {smallest}",
        mesh.quality.min_angle
    );
    match spade {
        Some(Ok(reference)) if options.simplify == 0.0 => {
            let tolerance = 1e-3 * reference.max(area) + 1e-300;
            assert!(
                (area - reference).abs() <= tolerance,
                "mesh area {area} vs spade's {reference}"
            );
        }
        Some(Err(e)) => {
            panic!("validate_rings and triangulate accept the rings, spade does not: {e}")
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use arbitrary::{Arbitrary, Unstructured};

    use super::ExactArea;

    /// The smoke's finding: a ring 3e-13 wide whose mesh and spade's triangulation both cover
    /// it exactly, but whose areas from `orient2d`'s estimates were 0.3 % apart.
    #[test]
    fn regression_tiny_ring_areas_are_summed_exactly() {
        let bytes = include_bytes!("../corpus/triangulate/new-tiny-ring-area-orient2d-estimate");
        let input = super::Input::arbitrary_take_rest(Unstructured::new(bytes)).unwrap();
        super::run(&input);
        // The ring, and its mesh's two halves split at the midpoint (−2.5, −2.5) of the long
        // edge: 2 A = 11 (|y| + x) for the third vertex (x, y).
        let (a, b) = ([-8.0, -8.0], [3.0, 3.0]);
        let c = [
            f64::from(4.814_825e-33_f32),
            f64::from(-3.031_648_8e-13_f32),
        ];
        let twice = 11.0 * (-c[1] + c[0]);
        let mut ring = ExactArea::default();
        ring.add_triangle([a, c, b]);
        let mut halves = ExactArea::default();
        halves.add_triangle([c, b, [-2.5, -2.5]]);
        halves.add_triangle([a, c, [-2.5, -2.5]]);
        for sum in [ring.value(), halves.value()] {
            assert!((sum - twice).abs() <= 1e-15 * twice, "{sum} vs {twice}");
        }
    }
}
