//! Meshing rings with a constrained Delaunay triangulation and Delaunay refinement (feature
//! `mesh`; the triangulation itself is in `cdt`).

use alloc::vec::Vec;

use glam::Vec2;

use crate::cdt::{Cdt, CdtError, FIRST_VERTEX, NONE};
use crate::sort::sort_unstable_by;
use crate::{MarchError, Ring};

/// The most interior points [`triangulate`] puts on its lattice (about 4 million, 32 MiB of
/// points); see [`MeshOptions::interior_spacing`].
pub const MAX_INTERIOR_POINTS: usize = 1 << 22;

/// The widest the rings' bounding box may be, along either axis, for [`triangulate`] to put
/// interior points in it (2⁶², about 4.6e18); see [`MeshOptions::interior_spacing`].
///
/// The lattice is laid out in `f32`: where each row crosses the ring edges, and how far each
/// point lies from them. Those take products of two lengths in the box, up to twice the
/// square of its extent, which stays below `f32::MAX` (about 2¹²⁸) up to this bound. Past it
/// a crossing could overflow to infinity and a row span without end.
pub const MAX_INTERIOR_EXTENT: f32 = (1u64 << 62) as f32;

/// Options for [`triangulate`].
///
/// Lengths are in the rings' units; the defaults suit the 2D seed's creatures (pixels, outline
/// step 5).
///
/// ```
/// use creature_march::MeshOptions;
///
/// let options = MeshOptions::DEFAULT.with_interior_spacing(10.0).with_min_angle(25.0);
/// assert_eq!(options.clearance, 0.5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct MeshOptions {
    /// Spacing of the interior points, which lie on a uniform sheared (triangular) lattice:
    /// rows `spacing × √3/2` apart, each shifted by half a spacing from the one below. 0 adds
    /// no interior points. Default 20 (the seed's, in its pixel units). A spacing that would
    /// put more than [`MAX_INTERIOR_POINTS`] in the rings' bounding box is an error, and so is
    /// any spacing above 0 for rings whose bounding box is wider or taller than
    /// [`MAX_INTERIOR_EXTENT`] (about 4.6e18).
    pub interior_spacing: f32,
    /// Interior points closer than `clearance × interior_spacing` to any ring edge are
    /// dropped, so they cannot make slivers against the outline. From 0 to 2. Default 0.5.
    pub clearance: f32,
    /// Delaunay refinement (Ruppert's, with Üngör's off-centres) adds points until every triangle's
    /// smallest angle is at least this many degrees; ring edges may be split, the outline's
    /// shape is kept up to the rounding of the split points to `f32` (which moves the mesh's
    /// area by at most 2⁻¹⁴ of the rings' area in all: a split that would move it further is
    /// not made, and [`MeshQuality::refinement_complete`] may then be `false`). 0 turns
    /// refinement off. From 0 to 33. Default 20.
    pub min_angle: f32,
    /// The most points refinement may add; `None` allows ten times the starting count.
    /// Default `None`.
    pub max_added_vertices: Option<usize>,
    /// Before meshing, drop ring points within this distance of the line through their kept
    /// neighbours (near-duplicates included), fewer points, faster triangulation. If the
    /// simplified rings would intersect, the rings are meshed unsimplified. 0 keeps every ring
    /// point as a mesh vertex. Default 0.
    pub simplify: f32,
}

impl MeshOptions {
    /// The defaults, usable in `const` context.
    pub const DEFAULT: Self = Self {
        interior_spacing: 20.0,
        clearance: 0.5,
        min_angle: 20.0,
        max_added_vertices: None,
        simplify: 0.0,
    };

    /// Sets [`interior_spacing`](Self::interior_spacing).
    #[must_use]
    pub const fn with_interior_spacing(mut self, interior_spacing: f32) -> Self {
        self.interior_spacing = interior_spacing;
        self
    }

    /// Sets [`clearance`](Self::clearance).
    #[must_use]
    pub const fn with_clearance(mut self, clearance: f32) -> Self {
        self.clearance = clearance;
        self
    }

    /// Sets [`min_angle`](Self::min_angle), in degrees.
    #[must_use]
    pub const fn with_min_angle(mut self, min_angle: f32) -> Self {
        self.min_angle = min_angle;
        self
    }

    /// Sets [`max_added_vertices`](Self::max_added_vertices).
    #[must_use]
    pub const fn with_max_added_vertices(mut self, max_added_vertices: Option<usize>) -> Self {
        self.max_added_vertices = max_added_vertices;
        self
    }

    /// Sets [`simplify`](Self::simplify).
    #[must_use]
    pub const fn with_simplify(mut self, simplify: f32) -> Self {
        self.simplify = simplify;
        self
    }

    /// Checks every field against its documented range.
    ///
    /// # Errors
    ///
    /// [`MarchError::NonFinite`], [`MarchError::NotPositive`] or [`MarchError::OutOfRange`]
    /// naming the first field out of range.
    pub fn validate(&self) -> Result<(), MarchError> {
        let finite = [
            ("interior spacing", self.interior_spacing),
            ("clearance", self.clearance),
            ("min angle", self.min_angle),
            ("simplify", self.simplify),
        ];
        for (what, value) in finite {
            if !value.is_finite() {
                return Err(MarchError::NonFinite { what, index: 0 });
            }
        }
        if self.interior_spacing < 0.0 {
            return Err(MarchError::NotPositive {
                what: "interior spacing",
                value: self.interior_spacing,
            });
        }
        if self.simplify < 0.0 {
            return Err(MarchError::NotPositive {
                what: "simplify",
                value: self.simplify,
            });
        }
        let ranges = [
            ("clearance", self.clearance, 0.0, 2.0),
            ("min angle", self.min_angle, 0.0, 33.0),
        ];
        for (what, value, min, max) in ranges {
            if !(value >= min && value <= max) {
                return Err(MarchError::OutOfRange {
                    what,
                    value,
                    min,
                    max,
                });
            }
        }
        Ok(())
    }
}

impl Default for MeshOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A 2D triangle mesh.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh2 {
    /// Vertex positions. The first [`outline_len`](Self::outline_len) are the ring points, ring
    /// after ring in the input order (all of them unless [`MeshOptions::simplify`] dropped
    /// some); then interior lattice points; then points added by refinement.
    pub positions: Vec<Vec2>,
    /// Triangles as indices into `positions`, counter-clockwise (y up). Every vertex is used.
    pub triangles: Vec<[u32; 3]>,
    /// How many leading `positions` are ring points.
    pub outline_len: usize,
    /// Measured triangle quality.
    pub quality: MeshQuality,
}

/// Triangle quality of a [`Mesh2`], measured on its `f32` positions.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MeshQuality {
    /// The smallest angle of any triangle, in degrees (0 for an empty mesh).
    pub min_angle: f32,
    /// How many triangles have an angle below 20°.
    pub below_20: usize,
    /// How many triangles have an angle below [`MeshOptions::min_angle`].
    pub below_limit: usize,
    /// Whether refinement reached the angle limit everywhere within its vertex budget (also
    /// `true` when refinement is off): `false` when the budget ran out, or when triangles at
    /// an input corner sharper than the limit (which refinement cannot split) stay below it.
    pub refinement_complete: bool,
}

/// Triangulates the inside of `rings` (even–odd: holes stay empty): a constrained Delaunay
/// triangulation of the ring edges plus interior points on a sheared lattice, refined to a
/// minimum angle, as [`MeshOptions`] set.
///
/// Takes the output of [`trace`](crate::trace) or [`march_grid`](crate::march_grid), or any
/// rings passing [`validate_rings`](crate::validate_rings). No rings give an empty mesh.
///
/// # Errors
///
/// Invalid options; [`MarchError::TooFewPoints`], [`MarchError::NonFinite`] or
/// [`MarchError::BadParent`] for a malformed ring; [`MarchError::RingsCross`] when ring edges
/// cross, touch or overlap. With an [`interior_spacing`](MeshOptions::interior_spacing) above
/// 0: [`MarchError::InteriorTooDense`] when the lattice would hold more than
/// [`MAX_INTERIOR_POINTS`], [`MarchError::ExtentTooLarge`] when the rings' bounding box is
/// wider or taller than [`MAX_INTERIOR_EXTENT`] (scale such rings down, or mesh them without
/// interior points).
///
/// ```
/// use creature_march::{glam::Vec2, trace, triangulate, MeshOptions};
///
/// let field = |p: Vec2| 1.0 - p.length() / 60.0; // a disc of radius 60
/// let rings = trace(field, &[Vec2::ZERO], 5.0, 0.0)?;
/// let mesh = triangulate(&rings, &MeshOptions::DEFAULT)?;
/// assert!(mesh.triangles.len() > 30);
/// assert!(mesh.quality.min_angle >= 20.0);
/// assert_eq!(mesh.outline_len, rings[0].points.len());
/// # Ok::<(), creature_march::MarchError>(())
/// ```
pub fn triangulate(rings: &[Ring], options: &MeshOptions) -> Result<Mesh2, MarchError> {
    options.validate()?;
    crate::ring::validate_structure(rings)?;
    let original: Vec<&[Vec2]> = rings.iter().map(|r| r.points.as_slice()).collect();
    if options.simplify > 0.0 {
        let simplified: Vec<Vec<Vec2>> = rings
            .iter()
            .map(|r| simplify(&r.points, options.simplify))
            .collect();
        let lists: Vec<&[Vec2]> = simplified.iter().map(Vec::as_slice).collect();
        // Simplified rings that would intersect are meshed unsimplified.
        match mesh_rings(&lists, options) {
            Err(MarchError::RingsCross { .. }) => {}
            result => return result,
        }
    }
    mesh_rings(&original, options)
}

/// [`triangulate`] on validated options and rings whose structure is valid.
fn mesh_rings(outline: &[&[Vec2]], options: &MeshOptions) -> Result<Mesh2, MarchError> {
    let Some((lo, hi)) = outline
        .iter()
        .filter_map(|r| crate::ring::bounds(r))
        .reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h)))
    else {
        return Ok(Mesh2 {
            quality: MeshQuality {
                refinement_complete: true,
                ..MeshQuality::default()
            },
            ..Mesh2::default()
        });
    };
    let outline_len: usize = outline.iter().map(|r| r.len()).sum();
    let mut points: Vec<Vec2> = Vec::with_capacity(2 * outline_len);
    points.extend(outline.iter().flat_map(|r| r.iter().copied()));
    if options.interior_spacing > 0.0 {
        interior_points(outline, options, &mut points)?;
    }
    let count = points.len();
    let budget = options
        .max_added_vertices
        .unwrap_or_else(|| count.saturating_mul(10));
    let expected = if options.min_angle > 0.0 {
        2 * count
    } else {
        count
    };
    let mut cdt = Cdt::new(lo.as_dvec2(), hi.as_dvec2(), expected);
    // Every point in a biased randomised order (Amenta, Choi and Rote): rounds of doubling
    // size, each a pseudo-random half of what is left, each along a Z curve through the box.
    // The curve keeps the walks short; the rounds keep the flips few (rings inserted along
    // the curve alone cost about twice the flips: points on a convex arc in order are the
    // incremental algorithm's worst case). The ring points go in first, then the ring edges
    // (most of them already there), then the interior points, each group in this order.
    // One integer key per point, sorted as integers: the round (5 bits), the curve position
    // (2 × 15 bits) and the point's index (29 bits; more points than that sort by pairs).
    let mut order: Vec<u64> = Vec::with_capacity(count);
    let mut pairs: Vec<(u64, u32)> = Vec::new();
    let key = |k: usize, p: Vec2| {
        let round = 31 - mix(k as u32).leading_zeros().min(31);
        (u64::from(round) << 30) | u64::from(morton_key(p, lo, hi) >> 2)
    };
    if count < 1 << 29 {
        order.extend(
            points
                .iter()
                .enumerate()
                .map(|(k, &p)| (key(k, p) << 29) | k as u64),
        );
        order.sort_unstable();
    } else {
        pairs.extend(
            points
                .iter()
                .enumerate()
                .map(|(k, &p)| (key(k, p), k as u32)),
        );
        pairs.sort_unstable();
    }
    let sorted = || {
        order
            .iter()
            .map(|&key| (key & ((1 << 29) - 1)) as usize)
            .chain(pairs.iter().map(|&(_, k)| k as usize))
    };
    // The vertex of each point, and the point of each vertex (for error reports).
    let mut vertex = alloc::vec![NONE; count];
    let mut point_of = alloc::vec![NONE; count + FIRST_VERTEX];
    let crossing = |k: usize, obstacle: u32, point_of: &[u32]| {
        let ring_a = ring_of(outline, k);
        // The obstacle may be unknown (`NONE`) or not an outline point: then it names no
        // other ring.
        let ring_b = point_of
            .get(obstacle as usize)
            .filter(|&&j| (j as usize) < outline_len)
            .map_or(ring_a, |&j| ring_of(outline, j as usize));
        MarchError::RingsCross {
            ring_a: ring_a.min(ring_b),
            ring_b: ring_a.max(ring_b),
            near: points[k],
        }
    };
    // The ring points, then the ring edges, then the interior points: an edge inserted after
    // the interior points would cross every edge between them and the far side of the ring
    // (or a super vertex), which flipping out of its way costs the square of their number
    // (regression: a thin triangle 6.5e6 long with interior spacing 20, some 30,000 lattice
    // points inside, took minutes). Inserted first, an edge crosses ring edges only.
    for k in sorted().filter(|&k| k < outline_len) {
        match cdt.insert(points[k].as_dvec2()) {
            Ok(v) => {
                vertex[k] = v;
                point_of[v as usize] = k as u32;
            }
            Err(CdtError::Occupied(v) | CdtError::Crossing(v)) => {
                return Err(crossing(k, v, &point_of));
            }
        }
    }
    let mut start = 0;
    for ring in outline {
        let n = ring.len();
        for i in 0..n {
            let (a, b) = (start + i, start + (i + 1) % n);
            if let Err(CdtError::Occupied(v) | CdtError::Crossing(v)) =
                cdt.insert_constraint(vertex[a], vertex[b])
            {
                return Err(crossing(a, v, &point_of));
            }
        }
        start += n;
    }
    for k in sorted().filter(|&k| k >= outline_len) {
        // Interior points keep a clearance from the rings and are distinct; one that still
        // lands on a vertex or a ring edge is left out.
        if let Ok(v) = cdt.insert(points[k].as_dvec2()) {
            vertex[k] = v;
            point_of[v as usize] = k as u32;
        }
    }
    cdt.mark_inside();
    let mut refinement_complete = true;
    if options.min_angle > 0.0 {
        refinement_complete = cdt.refine(f64::from(options.min_angle), budget);
    }
    Ok(extract(
        &cdt,
        &vertex[..outline_len],
        options.min_angle,
        refinement_complete,
    ))
}

/// The ring holding point `k` of the rings' concatenation.
fn ring_of(outline: &[&[Vec2]], k: usize) -> usize {
    let mut start = 0;
    for (r, ring) in outline.iter().enumerate() {
        start += ring.len();
        if k < start {
            return r;
        }
    }
    0
}

/// A deterministic hash of an index (the finaliser of MurmurHash3), for the insertion rounds.
fn mix(k: u32) -> u32 {
    let mut h = k.wrapping_add(0x9e37_79b9);
    h ^= h >> 16;
    h = h.wrapping_mul(0x85eb_ca6b);
    h ^= h >> 13;
    h = h.wrapping_mul(0xc2b2_ae35);
    h ^ (h >> 16)
}

/// The point's position along a Z (Morton) curve through the box `lo..hi`, on a 2¹⁶ × 2¹⁶
/// grid: bits of x and y interleaved.
fn morton_key(p: Vec2, lo: Vec2, hi: Vec2) -> u32 {
    let scale = 65535.0 / (hi - lo).max(Vec2::splat(f32::MIN_POSITIVE));
    // In the box, so the casts only truncate (and saturate).
    let q = ((p - lo) * scale).max(Vec2::ZERO);
    let spread = |v: f32| {
        let mut x = (v as u32).min(0xffff);
        x = (x | (x << 8)) & 0x00ff_00ff;
        x = (x | (x << 4)) & 0x0f0f_0f0f;
        x = (x | (x << 2)) & 0x3333_3333;
        (x | (x << 1)) & 0x5555_5555
    };
    spread(q.x) | (spread(q.y) << 1)
}

/// Interior lattice points inside the rings (even–odd) and at least the clearance away from
/// every ring edge.
///
/// (Grading the lattice towards the outline — nested lattices of halved spacing in distance
/// bands — was tried with the spade-based mesher this crate had before its own: the cost grows
/// with the vertex count, and the graded set, 810 points before and 1,095 after refinement on
/// the bench creature against 993 from this lattice, was slower.)
///
/// # Errors
/// [`MarchError::ExtentTooLarge`] when the rings' bounding box is wider or taller than
/// [`MAX_INTERIOR_EXTENT`]; [`MarchError::InteriorTooDense`] when the lattice over it would
/// hold more than [`MAX_INTERIOR_POINTS`].
fn interior_points(
    rings: &[&[Vec2]],
    options: &MeshOptions,
    out: &mut Vec<Vec2>,
) -> Result<(), MarchError> {
    let Some((lo, hi)) = crate::ring::bounds(&rings.concat()) else {
        return Ok(());
    };
    // Before anything else: past the bound the `f32` arithmetic below overflows (regression:
    // a ring 1.7e38 tall and 33,200 wide gave row crossings at ±infinity, and a row of points
    // that never ended). `hi - lo` is infinite when it overflows, and so refused too.
    let extent = (hi - lo).max_element();
    if !(extent <= MAX_INTERIOR_EXTENT) {
        return Err(MarchError::ExtentTooLarge {
            extent,
            max: MAX_INTERIOR_EXTENT,
        });
    }
    let spacing = options.interior_spacing;
    let row = spacing * 0.866_025_4;
    // Checked before any row is counted: in `f64`, where a tiny spacing cannot overflow.
    let lattice = (f64::from(hi.x - lo.x) / f64::from(spacing) + 1.0)
        * (f64::from(hi.y - lo.y) / f64::from(row) + 1.0);
    if !(lattice <= MAX_INTERIOR_POINTS as f64) {
        return Err(MarchError::InteriorTooDense {
            points: lattice as f32,
            max: MAX_INTERIOR_POINTS,
        });
    }
    let clearance = (options.clearance * spacing).max(spacing * 1e-4);
    let segments: Vec<(Vec2, Vec2)> = rings
        .iter()
        .flat_map(|r| (0..r.len()).map(move |i| (r[i], r[(i + 1) % r.len()])))
        .collect();
    let buckets = Buckets::new(&segments, lo, hi, clearance);
    let rows = ((hi.y - lo.y) / row) as usize + 1;
    let row_y = |k: usize| lo.y + row * (k as f32 + 0.5);
    // The crossings of every row, gathered segment by segment (each crosses a few rows):
    // (row, x), then sorted by row and x.
    let mut crossings: Vec<(u32, f32)> = Vec::with_capacity(2 * rows + segments.len() / 4);
    for &(a, b) in &segments {
        let (low, high) = (a.y.min(b.y), a.y.max(b.y));
        // Rows whose y may lie in [low, high), one wider on each side; the exact test below
        // decides (y strictly between the ends' sides, the even–odd rule's half-open one).
        let first = ((low - lo.y) / row - 1.5).max(0.0) as usize;
        let last = (((high - lo.y) / row).max(0.0) as usize + 1).min(rows);
        for k in first..last {
            let y = row_y(k);
            if (a.y > y) != (b.y > y) {
                crossings.push((k as u32, a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y)));
            }
        }
    }
    sort_unstable_by(&mut crossings, &mut |p, q| {
        p.0.cmp(&q.0).then(p.1.total_cmp(&q.1))
    });
    for span in crossings.chunk_by(|p, q| p.0 == q.0) {
        let k = span[0].0 as usize;
        let y = row_y(k);
        if y >= hi.y {
            break;
        }
        let x0 = lo.x + spacing * if k.is_multiple_of(2) { 0.25 } else { 0.75 };
        for pair in span.chunks_exact(2) {
            let (from, to) = (pair[0].1, pair[1].1);
            // Spans lie within the box, so the offsets are non-negative: `as` floors them.
            let mut m = ((from - x0) / spacing).max(0.0) as usize;
            loop {
                let x = x0 + spacing * m as f32;
                if x > to {
                    break;
                }
                let p = Vec2::new(x, y);
                if x >= from && buckets.clear_of(&segments, p, clearance) {
                    out.push(p);
                }
                m += 1;
            }
        }
    }
    Ok(())
}

/// A uniform grid of segment indices, for clearance queries.
struct Buckets {
    lo: Vec2,
    cell: f32,
    nx: usize,
    ny: usize,
    starts: Vec<usize>,
    items: Vec<u32>,
}

impl Buckets {
    /// Buckets of about `cell` (at most 256 along the longer side) over the box `lo..hi`.
    fn new(segments: &[(Vec2, Vec2)], lo: Vec2, hi: Vec2, cell: f32) -> Self {
        let extent = (hi - lo).max(Vec2::splat(cell));
        let cell = cell.max(extent.max_element() / 256.0);
        let nx = (extent.x / cell) as usize + 1;
        let ny = (extent.y / cell) as usize + 1;
        let index = |p: Vec2| {
            let q = (p - lo) / cell;
            (
                (q.x.max(0.0) as usize).min(nx - 1),
                (q.y.max(0.0) as usize).min(ny - 1),
            )
        };
        let ranges: Vec<((usize, usize), (usize, usize))> = segments
            .iter()
            .map(|&(a, b)| (index(a.min(b)), index(a.max(b))))
            .collect();
        let mut starts = alloc::vec![0usize; nx * ny + 1];
        for &((i0, j0), (i1, j1)) in &ranges {
            for j in j0..=j1 {
                for i in i0..=i1 {
                    starts[j * nx + i + 1] += 1;
                }
            }
        }
        for c in 0..nx * ny {
            starts[c + 1] += starts[c];
        }
        let mut fill = starts.clone();
        let mut items = alloc::vec![0u32; starts[nx * ny]];
        for (k, &((i0, j0), (i1, j1))) in ranges.iter().enumerate() {
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let c = j * nx + i;
                    items[fill[c]] = k as u32;
                    fill[c] += 1;
                }
            }
        }
        Self {
            lo,
            cell,
            nx,
            ny,
            starts,
            items,
        }
    }

    /// Whether no segment comes closer to `p` than `clearance`: looks at the cells the disc
    /// of that radius overlaps.
    fn clear_of(&self, segments: &[(Vec2, Vec2)], p: Vec2, clearance: f32) -> bool {
        // Non-negative before the casts (which then truncate, i.e. floor) and clamped after.
        let cell_of = |q: Vec2| {
            let c = ((q - self.lo) / self.cell).max(Vec2::ZERO);
            (
                (c.x as usize).min(self.nx - 1),
                (c.y as usize).min(self.ny - 1),
            )
        };
        let (i0, j0) = cell_of(p - clearance);
        let (i1, j1) = cell_of(p + clearance);
        let limit = clearance * clearance;
        for j in j0..=j1 {
            for i in i0..=i1 {
                let c = j * self.nx + i;
                for &k in &self.items[self.starts[c]..self.starts[c + 1]] {
                    let (a, b) = segments[k as usize];
                    if distance_squared_to_segment(p, a, b) < limit {
                        return false;
                    }
                }
            }
        }
        true
    }
}

fn distance_squared_to_segment(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance_squared(a + ab * t)
}

/// Drops points within `tolerance` of the segment joining the last kept point and the next
/// point, checking every point dropped since the last kept one (at most 32 in a row).
fn simplify(points: &[Vec2], tolerance: f32) -> Vec<Vec2> {
    let n = points.len();
    if n <= 3 {
        return points.to_vec();
    }
    let mut out = Vec::with_capacity(n);
    let mut dropped: Vec<Vec2> = Vec::new();
    out.push(points[0]);
    // Squared distances against the squared tolerance: no square roots.
    let limit = tolerance * tolerance;
    for i in 1..n {
        let p = points[i];
        let next = points[(i + 1) % n];
        let last = out[out.len() - 1];
        let droppable = dropped.len() < 32
            && distance_squared_to_segment(p, last, next) <= limit
            && dropped
                .iter()
                .all(|&q| distance_squared_to_segment(q, last, next) <= limit);
        if droppable {
            dropped.push(p);
        } else {
            out.push(p);
            dropped.clear();
        }
    }
    if out.len() < 3 { points.to_vec() } else { out }
}

/// The inside triangles, with unused vertices removed: the ring points first, in order, then
/// the other vertices in the order the triangles first use them.
fn extract(cdt: &Cdt, ring_vertices: &[u32], min_angle: f32, refinement_complete: bool) -> Mesh2 {
    let outline_len = ring_vertices.len();
    let mut remap = alloc::vec![u32::MAX; cdt.points.len()];
    let mut positions: Vec<Vec2> = Vec::with_capacity(cdt.points.len());
    for (k, &v) in ring_vertices.iter().enumerate() {
        remap[v as usize] = k as u32;
        let p = cdt.points[v as usize];
        positions.push(Vec2::new(p.x as f32, p.y as f32));
    }
    let mut triangles = Vec::with_capacity(cdt.triangle_count());
    for t in 0..cdt.triangle_count() {
        let (vertices, inside) = cdt.triangle(t);
        if !inside {
            continue;
        }
        let tri = vertices.map(|v| {
            let v = v as usize;
            if remap[v] == u32::MAX {
                remap[v] = positions.len() as u32;
                let p = cdt.points[v];
                positions.push(Vec2::new(p.x as f32, p.y as f32));
            }
            remap[v]
        });
        triangles.push(tri);
    }
    let quality = quality(&positions, &triangles, min_angle, refinement_complete);
    Mesh2 {
        positions,
        triangles,
        outline_len,
        quality,
    }
}

/// The smallest angle of a triangle, in degrees.
#[cfg(test)]
fn min_angle_deg(a: Vec2, b: Vec2, c: Vec2) -> f32 {
    let (y, x) = min_angle_tan(a, b, c);
    crate::math::atan2(y, x).to_degrees()
}

/// A triangle's smallest angle as `(y, x)` with `tan = y / x`, without trigonometry: every
/// angle's tangent is `2·area / dot` of its two edges, the smallest angle is the one opposite
/// the shortest edge (it is acute: at most 60°), and the twice-area is taken at the corner
/// between the two shorter edges, where it loses the least to rounding.
///
/// In `f64`, scaled back into `f32` with the ratio kept: in `f32` the edges' products
/// overflow for coordinates near `f32::MAX` (finding 12 of issue 17) and underflow for tiny
/// ones (regression: a sliver with vertices 5e-32 and 9e-38 from the origin read 29.5° for
/// 0.00016°); in `f64` neither happens to the products of `f32` coordinates.
fn min_angle_tan(a: Vec2, b: Vec2, c: Vec2) -> (f32, f32) {
    let [a, b, c] = [a, b, c].map(|p| p.as_dvec2());
    let corners = [
        (b - a, c - a, (c - b).length_squared()),
        (c - b, a - b, (a - c).length_squared()),
        (a - c, b - c, (b - a).length_squared()),
    ];
    let smallest = corners
        .iter()
        .fold(corners[0], |s, &k| if k.2 < s.2 { k } else { s });
    let widest = corners
        .iter()
        .fold(corners[0], |w, &k| if k.2 > w.2 { k } else { w });
    let (y, x) = (
        widest.0.perp_dot(widest.1).abs(),
        smallest.0.dot(smallest.1),
    );
    let m = y.abs().max(x.abs());
    if m > 0.0 && m.is_finite() {
        ((y / m) as f32, (x / m) as f32)
    } else {
        (0.0, 1.0)
    }
}

fn quality(
    positions: &[Vec2],
    triangles: &[[u32; 3]],
    limit: f32,
    refinement_complete: bool,
) -> MeshQuality {
    let tan_20 = crate::math::tan(20.0f32.to_radians());
    let tan_limit = crate::math::tan(limit.to_radians());
    let mut q = MeshQuality {
        min_angle: 0.0,
        below_20: 0,
        below_limit: 0,
        refinement_complete,
    };
    // The smallest angle so far as (twice area, dot): compared by cross-multiplying.
    let mut worst: Option<(f32, f32)> = None;
    for t in triangles {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let (y, x) = min_angle_tan(a, b, c);
        // angle < L  ⇔  y / x < tan L, for an acute angle (x > 0); a degenerate triangle
        // (y = 0) counts as below every limit.
        q.below_20 += usize::from(y < tan_20 * x || y == 0.0);
        q.below_limit += usize::from(y < tan_limit * x || y == 0.0);
        if worst.is_none_or(|(wy, wx)| y * wx < wy * x) {
            worst = Some((y, x));
        }
    }
    if let Some((y, x)) = worst {
        // No triangle's smallest angle exceeds 60°; rounding of the tangent and `atan2` gave
        // 60.000004 for near-equilateral ones (regression:
        // `regression_min_angle_of_an_equilateral_triangle_is_at_most_60`).
        q.min_angle = crate::math::atan2(y, x).to_degrees().min(60.0);
    }
    // Refinement leaves alone the triangles at input corners sharper than the limit (a
    // pinch between two blobs): it is complete only where the limit really holds.
    if limit > 0.0 {
        q.refinement_complete &= q.below_limit == 0;
    }
    q
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::*;

    fn square(o: Vec2, s: f32, ccw: bool) -> Ring {
        let mut points = vec![o, o + Vec2::X * s, o + Vec2::splat(s), o + Vec2::Y * s];
        if !ccw {
            points.reverse();
        }
        Ring {
            points,
            hole: !ccw,
            parent: if ccw { None } else { Some(0) },
        }
    }

    #[test]
    fn a_square_without_interior_points_is_two_triangles() {
        let options = MeshOptions::DEFAULT
            .with_interior_spacing(0.0)
            .with_min_angle(0.0);
        let mesh = triangulate(&[square(Vec2::ZERO, 1.0, true)], &options).unwrap();
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.triangles.len(), 2);
        assert!((mesh.quality.min_angle - 45.0).abs() < 1e-3);
        assert_eq!(mesh.quality.below_20, 0);
    }

    #[test]
    fn a_hole_stays_empty() {
        let rings = [
            square(Vec2::ZERO, 100.0, true),
            square(Vec2::splat(40.0), 20.0, false),
        ];
        let mesh = triangulate(&rings, &MeshOptions::DEFAULT).unwrap();
        for t in &mesh.triangles {
            let c = t.iter().map(|&i| mesh.positions[i as usize]).sum::<Vec2>() / 3.0;
            assert!(!(c.x > 40.0 && c.x < 60.0 && c.y > 40.0 && c.y < 60.0));
        }
        assert!(mesh.quality.min_angle >= 20.0);
        assert!(mesh.quality.refinement_complete);
    }

    #[test]
    fn simplify_drops_collinear_points() {
        let points: Vec<Vec2> = (0..10)
            .map(|i| Vec2::new(i as f32, 0.0))
            .chain([Vec2::new(9.0, 5.0), Vec2::new(0.0, 5.0)])
            .collect();
        let s = simplify(&points, 0.01);
        assert_eq!(s.len(), 4);
    }

    #[test]
    fn options_are_validated() {
        assert!(MeshOptions::DEFAULT.validate().is_ok());
        assert!(
            MeshOptions::DEFAULT
                .with_min_angle(40.0)
                .validate()
                .is_err()
        );
        assert!(
            MeshOptions::DEFAULT
                .with_interior_spacing(-1.0)
                .validate()
                .is_err()
        );
        assert!(
            MeshOptions::DEFAULT
                .with_simplify(f32::NAN)
                .validate()
                .is_err()
        );
        assert!(MeshOptions::DEFAULT.with_clearance(3.0).validate().is_err());
    }

    #[test]
    fn trig_free_min_angle_matches_the_three_angles() {
        let mut s = 12_345u32;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            (s >> 8) as f32 / (1u32 << 24) as f32 * 10.0
        };
        // The previous implementation: three `atan2`s (accurate for small angles, unlike an
        // `acos` of the normalised dot product).
        let angle = |p: Vec2, q: Vec2, r: Vec2| {
            let (u, v) = (q - p, r - p);
            u.perp_dot(v).abs().atan2(u.dot(v)).to_degrees()
        };
        let mut triangles = Vec::new();
        let mut positions = Vec::new();
        let mut below = (0, 0);
        let mut smallest = 180.0f32;
        for t in 0..2000u32 {
            let [a, b, c] = [0; 3].map(|_| Vec2::new(next(), next()));
            let direct = angle(a, b, c).min(angle(b, c, a)).min(angle(c, a, b));
            assert!(
                (min_angle_deg(a, b, c) - direct).abs() < 1e-2,
                "{a} {b} {c}"
            );
            positions.extend([a, b, c]);
            triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
            below.0 += usize::from(direct < 20.0);
            below.1 += usize::from(direct < 30.0);
            smallest = smallest.min(direct);
        }
        let q = quality(&positions, &triangles, 30.0, true);
        // Counts may differ only for angles within rounding of the limits.
        assert!(q.below_20.abs_diff(below.0) <= 1 && q.below_limit.abs_diff(below.1) <= 1);
        assert!((q.min_angle - smallest).abs() < 1e-2);
    }

    /// Issue 17, finding 3: a tiny `interior_spacing` passed validation, then overflowed the
    /// row count (1e-30 on a 10 × 10 square) or tried to allocate gigabytes (1e-3 on a
    /// 100 × 100 one). Now a typed error before any row is counted.
    #[test]
    fn regression_a_too_dense_interior_lattice_is_an_error() {
        let square = |s: f32| Ring {
            points: alloc::vec![
                Vec2::ZERO,
                Vec2::new(s, 0.0),
                Vec2::new(s, s),
                Vec2::new(0.0, s)
            ],
            hole: false,
            parent: None,
        };
        for (side, spacing) in [(10.0, 1e-30), (100.0, 1e-3), (100.0, 0.04)] {
            let options = MeshOptions::DEFAULT.with_interior_spacing(spacing);
            assert!(options.validate().is_ok());
            assert!(
                matches!(
                    triangulate(&[square(side)], &options),
                    Err(MarchError::InteriorTooDense { .. })
                ),
                "{side} {spacing}"
            );
        }
        let fine = MeshOptions::DEFAULT.with_interior_spacing(1.0);
        assert!(triangulate(&[square(100.0)], &fine).is_ok());
    }

    /// Fuzz (`triangulate/new-triangulate-timeout-extent`): a ring 1.7e38 tall and 33,200
    /// wide with interior spacing 8.7e37 ran for minutes and past 2 GB: the lattice's row
    /// crossings overflowed `f32` to ±infinity, and a row's points never ended. Rings wider
    /// or taller than `MAX_INTERIOR_EXTENT` are now an error with interior points, and still
    /// meshed without them; at the bound the lattice is laid out.
    #[test]
    fn regression_an_interior_lattice_over_a_huge_extent_is_an_error() {
        let ring = |points: &[[f32; 2]]| Ring {
            points: points.iter().map(|&p| Vec2::from(p)).collect(),
            hole: false,
            parent: None,
        };
        let found = ring(&[
            [0.0, 0.0],
            [100.0, 0.0],
            [100.0, 100.0],
            [-1.084_202_2e-19, -1.701_425e38],
            [33_199.996, 0.503_079_6],
        ]);
        let options = MeshOptions::DEFAULT.with_interior_spacing(8.711_229e37);
        assert_eq!(
            triangulate(&[found], &options),
            Err(MarchError::ExtentTooLarge {
                extent: 1.701_425e38 + 100.0,
                max: MAX_INTERIOR_EXTENT,
            })
        );
        // A box whose side overflows `f32` is refused too.
        let wide = ring(&[[-3e38, 0.0], [3e38, 0.0], [0.0, 1.0]]);
        assert!(matches!(
            triangulate(core::slice::from_ref(&wide), &options),
            Err(MarchError::ExtentTooLarge { extent, .. }) if extent == f32::INFINITY
        ));
        // Without interior points such rings still mesh.
        let none = options.with_interior_spacing(0.0);
        let mesh = triangulate(&[wide], &none).unwrap();
        assert!(mesh.positions.iter().all(|p| p.is_finite()));
        // At the bound, a tall triangle gets its lattice: finite points inside the box.
        let e = MAX_INTERIOR_EXTENT;
        let tall = ring(&[[0.0, 0.0], [e / 2.0, 0.0], [e / 4.0, e]]);
        let lattice = options
            .with_interior_spacing(e / 16.0)
            .with_max_added_vertices(Some(100));
        let mesh = triangulate(&[tall], &lattice).unwrap();
        assert!(
            mesh.positions.len() > mesh.outline_len,
            "no interior points"
        );
        assert!(
            mesh.positions.iter().all(|p| p.is_finite()
                && p.cmpge(Vec2::ZERO).all()
                && p.cmple(Vec2::splat(e)).all())
        );
    }

    /// Issue 17, finding 12: a vertex at `x = f32::MAX` overflowed the edges' products, and
    /// the quality reported 45° for a triangle whose smallest angle is about 0.
    #[test]
    fn regression_min_angle_at_huge_coordinates() {
        let positions = [Vec2::ZERO, Vec2::new(0.0, f32::MAX), Vec2::new(1e19, 0.0)];
        let q = quality(&positions, &[[0, 1, 2]], 20.0, true);
        assert!(
            q.min_angle.is_finite() && q.min_angle < 1e-3,
            "{}",
            q.min_angle
        );
        assert_eq!((q.below_20, q.below_limit), (1, 1));
        assert!(!q.refinement_complete);
        // A huge but well-shaped triangle keeps its angles.
        let big = [
            Vec2::new(-3e38, 0.0),
            Vec2::new(3e38, 0.0),
            Vec2::new(0.0, 3e38),
        ];
        let q = quality(&big, &[[0, 1, 2]], 20.0, true);
        assert!((q.min_angle - 45.0).abs() < 1e-3, "{}", q.min_angle);
    }

    #[test]
    fn min_angle_of_an_equilateral_triangle() {
        let m = min_angle_deg(Vec2::ZERO, Vec2::X, Vec2::new(0.5, 0.866_025_4));
        assert!((m - 60.0).abs() < 1e-3);
    }
}
