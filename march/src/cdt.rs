//! A constrained Delaunay triangulation with Delaunay refinement, the engine of
//! [`triangulate`](crate::triangulate) (feature `mesh`).
//!
//! Triangles live in one flat array, as in Shewchuk's Triangle and delaunator: triangle `t`
//! has the counter-clockwise vertices `v`; its half-edge `e = 4t + i` (`i` in `0..3`; the
//! fourth slot is unused, so that no division by three is needed) runs from `v[i]` to
//! `v[(i + 1) % 3]`, and `twin[i]` is the opposite half-edge in the neighbouring triangle.
//! Three far "super" vertices (0, 1, 2) enclose everything, so every point lands inside some
//! triangle and only the triangles at the super vertices have hull edges.
//!
//! Orientation and in-circle tests are Shewchuk's adaptive exact predicates (the `robust`
//! crate). Every vertex has `f32` coordinates (refinement rounds the points it adds), so the
//! triangulation is exactly valid for the `f32` mesh it produces.
//!
//! Points are inserted by splitting the triangle (or edge) they land in and flipping edges
//! that are not locally Delaunay (Lawson); constraint edges by Sloan's flips; refinement is
//! Ruppert's algorithm with Shewchuk's rule of never inserting a circumcentre that would
//! encroach upon a constraint edge (those edges are split at their midpoints instead).

use alloc::collections::VecDeque;
use alloc::vec::Vec;

use glam::DVec2;
use robust::{Coord, orient2d};

/// "No half-edge" (a hull edge of the super triangle), "no vertex".
pub(crate) const NONE: u32 = u32::MAX;

/// The first inserted vertex: 0, 1 and 2 are the super triangle's.
pub(crate) const FIRST_VERTEX: usize = 3;

/// Why the triangulation could not be built: the input breaks its promises. Each variant
/// names a vertex of what was in the way ([`NONE`] if unknown).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CdtError {
    /// A point coincides with this vertex, or lies on a constraint edge from it.
    Occupied(u32),
    /// A constraint edge crosses another one (from this vertex) or passes through this
    /// vertex.
    Crossing(u32),
}

/// Where a point lies in the triangulation.
enum Location {
    /// Strictly inside a triangle.
    Triangle(u32),
    /// On the interior of an edge (a half-edge of it).
    Edge(u32),
    /// On a vertex.
    Vertex(u32),
}

/// Where a walk towards a point stopped.
enum Walk {
    /// It reached the point's location.
    Found(Location),
    /// It would have crossed this constraint half-edge (or left the super triangle: `NONE`).
    Blocked(u32),
}

/// One triangle.
#[derive(Debug, Clone, Copy)]
struct Tri {
    /// Counter-clockwise vertices.
    v: [u32; 3],
    /// The twin of each edge, or [`NONE`].
    twin: [u32; 3],
    /// Bit `i` set: edge `i` is a constraint.
    fixed: u8,
    /// Whether the triangle lies inside the rings (set by [`Cdt::mark_inside`], then kept).
    inside: bool,
}

fn coord(p: DVec2) -> Coord<f64> {
    Coord { x: p.x, y: p.y }
}

/// `> 0` when `c` lies left of `a → b`, `< 0` right, `0` on the line (exact).
fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    orient2d(coord(a), coord(b), coord(c))
}

/// Whether `d` lies certainly inside the circle through the counter-clockwise `a`, `b`, `c`:
/// the in-circle determinant in floating point, trusted only beyond its error bound
/// (Shewchuk's first filter). Near-cocircular points (every sheared lattice has exactly
/// cocircular ones) count as outside, so no flip is ever undone and flipping terminates;
/// the triangulation stays exactly valid (that rests on the exact orientation test), and
/// is Delaunay up to those ties.
fn in_circle(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    /// `(10 + 96ε)ε` with `ε = 2⁻⁵³` (Shewchuk's `iccerrboundA`).
    const BOUND: f64 = (10.0 + 96.0 * f64::EPSILON / 2.0) * (f64::EPSILON / 2.0);
    let (ad, bd, cd) = (a - d, b - d, c - d);
    let (bc, cb) = (bd.x * cd.y, cd.x * bd.y);
    let (ca, ac) = (cd.x * ad.y, ad.x * cd.y);
    let (ab, ba) = (ad.x * bd.y, bd.x * ad.y);
    let (al, bl, cl) = (
        ad.length_squared(),
        bd.length_squared(),
        cd.length_squared(),
    );
    let det = al * (bc - cb) + bl * (ca - ac) + cl * (ab - ba);
    let permanent =
        (bc.abs() + cb.abs()) * al + (ca.abs() + ac.abs()) * bl + (ab.abs() + ba.abs()) * cl;
    det > BOUND * permanent
}

/// Rounds to the nearest `f32`, so a point added by refinement is exactly an output vertex.
fn to_f32_exact(p: DVec2) -> DVec2 {
    DVec2::new(f64::from(p.x as f32), f64::from(p.y as f32))
}

/// The triangle of a half-edge.
const fn tri_of(e: u32) -> usize {
    (e >> 2) as usize
}

/// The half-edge's index in its triangle (`min` tells the compiler it is below 3).
fn slot(e: u32) -> usize {
    ((e & 3) as usize).min(2)
}

/// The slot after `i` (below 3) in its triangle.
const fn after(i: usize) -> usize {
    if i >= 2 { 0 } else { i + 1 }
}

/// The slot before `i` (below 3) in its triangle.
const fn before(i: usize) -> usize {
    if i == 0 { 2 } else { i - 1 }
}

/// The next half-edge counter-clockwise in the same triangle.
const fn next(e: u32) -> u32 {
    if e & 3 == 2 { e - 2 } else { e + 1 }
}

/// The previous half-edge in the same triangle.
const fn prev(e: u32) -> u32 {
    if e & 3 == 0 { e + 2 } else { e - 1 }
}

/// Half-edge `i` of triangle `t`.
const fn edge(t: u32, i: u32) -> u32 {
    4 * t + i
}

/// Where a walk round a vertex's star is ([`Cdt::star_step`]).
struct Star {
    /// The half-edge the walk started with.
    first: u32,
    /// The half-edge it gives next ([`NONE`] when done).
    next: u32,
    /// Whether it turned back at the hull and now goes clockwise from `first`.
    backwards: bool,
}

/// Refinement's work lists.
#[derive(Default)]
struct Queues {
    /// Constraint half-edges that may be encroached upon.
    segments: VecDeque<u32>,
    /// Triangles that may be bad, with their vertices when queued (a triangle changed since
    /// is skipped: its new self was queued when it changed).
    bad: VecDeque<(u32, [u32; 3])>,
}

/// The triangulation.
pub(crate) struct Cdt {
    /// Vertex positions; 0, 1 and 2 are the super vertices.
    pub(crate) points: Vec<DVec2>,
    tris: Vec<Tri>,
    /// A half-edge leaving each vertex.
    out_edge: Vec<u32>,
    /// Where the last walk ended: the next one starts there.
    last: u32,
    /// State of the walk's pseudo-random edge order (deterministic).
    rng: u32,
    /// Edges waiting to be checked by [`Cdt::legalize`].
    stack: Vec<u32>,
    /// The last cavity dug by [`Cdt::dig`]: its triangles, and the half-edges on its
    /// boundary (in its triangles, each with its twin outside, or a constraint or hull edge).
    cavity: Vec<u32>,
    boundary: Vec<u32>,
    /// Per triangle, the dig that put it in a cavity (`stamp` is the current one).
    dug: Vec<u32>,
    stamp: u32,
    /// The new triangles' data while a cavity is refilled: (a, b, twin, constraint bit).
    fan: Vec<(u32, u32, u32, u8)>,
    /// How much more twice-area the rounded split points of constraint edges may still add
    /// to or cut from the inside ([`Cdt::refine`] sets it; see [`MAX_BULGE`]).
    bulge_left: f64,
}

/// The most a refinement may move the inside's area by splitting constraint edges, relative to
/// that area: a split point is the edge's midpoint rounded to `f32`, off the edge by up to half
/// a unit in the last place, so each split adds or cuts a sliver (a "bulge"). Harmless on an
/// ordinary outline (about 1e-6 of the area in all), it is not on a sliver as thin as that
/// rounding, whose area it could change by several per cent (regression: the thin triangle
/// (−8, −8), (3.00003, 3), (0, 0) gained 0.4 %); splits past this budget are not made.
const MAX_BULGE: f64 = 1.0 / 16384.0;

impl Cdt {
    /// An empty triangulation whose super triangle encloses the box `lo..hi` with room to
    /// spare, with room for about `capacity` vertices.
    pub(crate) fn new(lo: DVec2, hi: DVec2, capacity: usize) -> Self {
        let centre = (lo + hi) * 0.5;
        let r = (hi - lo).max_element().max(1.0) * 64.0;
        let mut points = Vec::with_capacity(capacity + 3);
        // Beyond f32's range for the largest inputs: only the predicates see them.
        points.extend([
            centre + DVec2::new(-r, -r),
            centre + DVec2::new(r, -r),
            centre + DVec2::new(0.0, r),
        ]);
        let mut tris = Vec::with_capacity(2 * capacity + 1);
        tris.push(Tri {
            v: [0, 1, 2],
            twin: [NONE; 3],
            fixed: 0,
            inside: false,
        });
        let mut out_edge = Vec::with_capacity(capacity + 3);
        out_edge.extend([0, 1, 2]);
        Self {
            points,
            tris,
            out_edge,
            last: 0,
            rng: 0x9e37_79b9,
            stack: Vec::new(),
            cavity: Vec::new(),
            boundary: Vec::new(),
            dug: Vec::new(),
            stamp: 0,
            fan: Vec::new(),
            bulge_left: 0.0,
        }
    }

    /// Number of triangles, the super vertices' included.
    pub(crate) fn triangle_count(&self) -> usize {
        self.tris.len()
    }

    /// The triangle's vertices (counter-clockwise) and whether it lies inside the rings
    /// (meaningful after [`Cdt::mark_inside`]).
    pub(crate) fn triangle(&self, t: usize) -> ([u32; 3], bool) {
        let tri = &self.tris[t];
        (tri.v, tri.inside)
    }

    fn origin(&self, e: u32) -> u32 {
        self.tris[tri_of(e)].v[slot(e)]
    }

    fn dest(&self, e: u32) -> u32 {
        self.origin(next(e))
    }

    fn apex(&self, e: u32) -> u32 {
        self.origin(prev(e))
    }

    fn twin_of(&self, e: u32) -> u32 {
        self.tris[tri_of(e)].twin[slot(e)]
    }

    fn is_fixed(&self, e: u32) -> bool {
        self.tris[tri_of(e)].fixed & (1 << slot(e)) != 0
    }

    fn is_inside(&self, t: u32) -> bool {
        self.tris[t as usize].inside
    }

    fn point(&self, v: u32) -> DVec2 {
        self.points[v as usize]
    }

    /// Appends `count` triangles for [`Cdt::set`] to fill; returns the first index.
    fn new_triangles(&mut self, count: usize) -> u32 {
        let first = self.tris.len() as u32;
        let blank = Tri {
            v: [0; 3],
            twin: [NONE; 3],
            fixed: 0,
            inside: false,
        };
        self.tris.extend(core::iter::repeat_n(blank, count));
        first
    }

    /// Sets triangle `t`: its vertices, its edges' twins (and theirs back) and constraint
    /// bits, and its side; records a half-edge leaving each vertex.
    fn set(&mut self, t: u32, v: [u32; 3], twin: [u32; 3], fixed: u8, inside: bool) {
        self.tris[t as usize] = Tri {
            v,
            twin,
            fixed,
            inside,
        };
        for i in 0..3 {
            let e = edge(t, i as u32);
            if twin[i] != NONE {
                self.tris[tri_of(twin[i])].twin[slot(twin[i])] = e;
            }
            self.out_edge[v[i] as usize] = e;
        }
    }

    /// A deterministic pseudo-random number in `0..3` (xorshift).
    fn random3(&mut self) -> u32 {
        self.rng ^= self.rng << 13;
        self.rng ^= self.rng >> 17;
        self.rng ^= self.rng << 5;
        // The high bits scaled to 0..3, a multiply instead of a division.
        ((u64::from(self.rng) * 3) >> 32) as u32
    }

    /// Walks from triangle `start` to the point `p` (a visibility walk, starting each step at
    /// a random edge so it cannot circle). With `stop_at_constraints`, it stops at the first
    /// constraint edge it would cross.
    fn walk(&mut self, start: u32, p: DVec2, stop_at_constraints: bool) -> Walk {
        let mut t = start;
        // The edge the walk entered `t` through: `p` lies strictly on `t`'s side of it.
        let mut entry = 3;
        let limit = 4 * self.tris.len() + 64;
        'steps: for _ in 0..limit {
            let v = self.tris[t as usize].v;
            let first = self.random3();
            let mut on_line = [false; 3];
            for k in 0..3 {
                let i = (first + k) % 3;
                if i == entry {
                    continue;
                }
                let a = self.point(v[i as usize]);
                let b = self.point(v[((i + 1) % 3) as usize]);
                let o = orient(a, b, p);
                if o < 0.0 {
                    let e = edge(t, i);
                    if stop_at_constraints && self.is_fixed(e) {
                        return Walk::Blocked(e);
                    }
                    let across = self.twin_of(e);
                    if across == NONE {
                        // Outside the super triangle: points never are (it encloses their
                        // box), but say so rather than loop.
                        return Walk::Blocked(NONE);
                    }
                    t = tri_of(across) as u32;
                    entry = slot(across) as u32;
                    continue 'steps;
                }
                on_line[i as usize] = o == 0.0;
            }
            self.last = t;
            return Walk::Found(locate_in(t, v, on_line));
        }
        // A walk cannot take this long in a valid triangulation; look everywhere.
        self.scan(p)
    }

    /// Finds `p` by testing every triangle (the walk's fallback).
    fn scan(&mut self, p: DVec2) -> Walk {
        for t in 0..self.tris.len() as u32 {
            let v = self.tris[t as usize].v;
            let o = [0, 1, 2].map(|i| orient(self.point(v[i]), self.point(v[(i + 1) % 3]), p));
            if o.iter().all(|&x| x >= 0.0) {
                self.last = t;
                return Walk::Found(locate_in(t, v, o.map(|x| x == 0.0)));
            }
        }
        Walk::Blocked(NONE)
    }

    /// Inserts a point (f32-exact coordinates) and restores the constrained Delaunay
    /// property. A point on a vertex or on a constraint edge is refused.
    pub(crate) fn insert(&mut self, p: DVec2) -> Result<u32, CdtError> {
        match self.walk(self.last, p, false) {
            Walk::Found(Location::Triangle(t)) => Ok(self.split_triangle(t, p)),
            Walk::Found(Location::Edge(e)) if !self.is_fixed(e) && self.twin_of(e) != NONE => {
                Ok(self.split_edge(e, p))
            }
            Walk::Found(Location::Edge(e)) => Err(CdtError::Occupied(self.origin(e))),
            Walk::Found(Location::Vertex(v)) => Err(CdtError::Occupied(v)),
            Walk::Blocked(_) => Err(CdtError::Occupied(NONE)),
        }
    }

    fn add_point(&mut self, p: DVec2) -> u32 {
        let v = self.points.len() as u32;
        self.points.push(p);
        self.out_edge.push(NONE);
        v
    }

    /// Splits triangle `t` = (a, b, c) at `p` (strictly inside) into (a, b, v), (b, c, v)
    /// and (c, a, v), keeping `t`'s edge a → b in place; then flips.
    fn split_triangle(&mut self, t: u32, p: DVec2) -> u32 {
        let v = self.add_point(p);
        let Tri {
            v: [a, b, c],
            twin: [n0, n1, n2],
            fixed,
            inside,
        } = self.tris[t as usize];
        let t1 = self.tris.len() as u32;
        let t2 = t1 + 1;
        self.tris[t as usize] = Tri {
            v: [a, b, v],
            twin: [n0, edge(t1, 2), edge(t2, 1)],
            fixed: fixed & 1,
            inside,
        };
        self.tris.push(Tri {
            v: [b, c, v],
            twin: [n1, edge(t2, 2), edge(t, 1)],
            fixed: (fixed >> 1) & 1,
            inside,
        });
        self.tris.push(Tri {
            v: [c, a, v],
            twin: [n2, edge(t, 2), edge(t1, 1)],
            fixed: (fixed >> 2) & 1,
            inside,
        });
        for (n, e) in [(n1, edge(t1, 0)), (n2, edge(t2, 0))] {
            if n != NONE {
                self.tris[tri_of(n)].twin[slot(n)] = e;
            }
        }
        // a and b still leave through t's edges; c's edge c → a moved to t2.
        self.out_edge[c as usize] = edge(t2, 0);
        self.out_edge[v as usize] = edge(t, 2);
        self.last = t;
        self.stack.clear();
        self.stack.extend([edge(t, 0), edge(t1, 0), edge(t2, 0)]);
        self.legalize(v);
        v
    }

    /// Splits the edge of half-edge `e` (which has a twin) at `p` (on it, or so close that
    /// all four new triangles keep their orientation), then flips. A constraint edge stays
    /// one in both halves.
    fn split_edge(&mut self, e: u32, p: DVec2) -> u32 {
        let v = self.add_point(p);
        let f = self.twin_of(e);
        let (t, u) = (tri_of(e) as u32, tri_of(f) as u32);
        let fixed = u8::from(self.is_fixed(e));
        let (a, b, c, d) = (self.origin(e), self.dest(e), self.apex(e), self.apex(f));
        let (e_next, e_prev) = (self.twin_of(next(e)), self.twin_of(prev(e)));
        let (f_next, f_prev) = (self.twin_of(next(f)), self.twin_of(prev(f)));
        let fe_next = u8::from(self.is_fixed(next(e)));
        let fe_prev = u8::from(self.is_fixed(prev(e)));
        let ff_next = u8::from(self.is_fixed(next(f)));
        let ff_prev = u8::from(self.is_fixed(prev(f)));
        let (t_inside, u_inside) = (self.is_inside(t), self.is_inside(u));
        let t2 = self.new_triangles(2);
        let u2 = t2 + 1;
        // t = (c, a, v), t2 = (b, c, v), u = (d, b, v), u2 = (a, d, v).
        let (t_fixed, t2_fixed) = (fe_prev | fixed << 1, fe_next | fixed << 2);
        let (u_fixed, u2_fixed) = (ff_prev | fixed << 1, ff_next | fixed << 2);
        self.set(
            t,
            [c, a, v],
            [e_prev, edge(u2, 2), edge(t2, 1)],
            t_fixed,
            t_inside,
        );
        self.set(
            t2,
            [b, c, v],
            [e_next, edge(t, 2), edge(u, 1)],
            t2_fixed,
            t_inside,
        );
        self.set(
            u,
            [d, b, v],
            [f_prev, edge(t2, 2), edge(u2, 1)],
            u_fixed,
            u_inside,
        );
        self.set(
            u2,
            [a, d, v],
            [f_next, edge(u, 2), edge(t, 1)],
            u2_fixed,
            u_inside,
        );
        self.last = t;
        self.stack.clear();
        self.stack
            .extend([edge(t, 0), edge(t2, 0), edge(u, 0), edge(u2, 0)]);
        self.legalize(v);
        v
    }

    /// Flips the edges on the stack (each opposite the new vertex `v` in its triangle) that
    /// are not locally Delaunay, pushing the two edges each flip exposes.
    fn legalize(&mut self, v: u32) {
        let pv = self.point(v);
        while let Some(e) = self.stack.pop() {
            let tri = &self.tris[tri_of(e)];
            let i = slot(e);
            let across = tri.twin[i];
            if tri.fixed & (1 << i) != 0 || across == NONE {
                continue;
            }
            let (a, b) = (tri.v[i], tri.v[after(i)]);
            let q = self.apex(across);
            if in_circle(self.point(a), self.point(b), pv, self.point(q)) {
                let (aq, qb) = self.flip(e);
                self.stack.push(aq);
                self.stack.push(qb);
            }
        }
    }

    /// Flips the edge of half-edge `e` (a → b, apex p; twin b → a, apex q) to p–q, in place:
    /// e's slot becomes a → q and its twin's b → p, the slots after them the new diagonal,
    /// and the edges p → a and q → b stay where they were. Both triangles keep their side.
    /// Returns the half-edges a → q and q → b (the ones opposite p).
    fn flip(&mut self, e: u32) -> (u32, u32) {
        let (t, i) = (tri_of(e), slot(e));
        let f = self.tris[t].twin[i];
        let (u, j) = (tri_of(f), slot(f));
        let (i1, j1) = (after(i), after(j));
        // a → q comes from u (slot j1), b → p from t (slot i1).
        let (a, q, aq, aq_fixed) = {
            let tu = &self.tris[u];
            (tu.v[j1], tu.v[before(j)], tu.twin[j1], (tu.fixed >> j1) & 1)
        };
        let tt = &mut self.tris[t];
        let (b, p, bp, bp_fixed) = (tt.v[i1], tt.v[before(i)], tt.twin[i1], (tt.fixed >> i1) & 1);
        tt.v[i1] = q;
        tt.twin[i] = aq;
        tt.twin[i1] = edge(u as u32, j1 as u32);
        tt.fixed = (tt.fixed & !((1 << i) | (1 << i1))) | aq_fixed << i;
        let tu = &mut self.tris[u];
        tu.v[j1] = p;
        tu.twin[j] = bp;
        tu.twin[j1] = edge(t as u32, i1 as u32);
        tu.fixed = (tu.fixed & !((1 << j) | (1 << j1))) | bp_fixed << j;
        let (e_aq, e_bp) = (edge(t as u32, i as u32), edge(u as u32, j as u32));
        if aq != NONE {
            self.tris[tri_of(aq)].twin[slot(aq)] = e_aq;
        }
        if bp != NONE {
            self.tris[tri_of(bp)].twin[slot(bp)] = e_bp;
        }
        self.out_edge[a as usize] = e_aq;
        self.out_edge[b as usize] = e_bp;
        (e_aq, prev(e_bp))
    }

    /// The half-edge from `a` to `b`, if the triangulation has that edge. It walks both
    /// stars in step, so it costs twice the smaller one: a vertex's star can hold a large
    /// part of the points (a super vertex's every point on the hull of a long thin set, a
    /// ring vertex at the end of a long thin ring), and walking it for each of the thousands
    /// of edges a long constraint crosses took minutes (regression: a 4-point ring 131,075
    /// long with interior spacing 20).
    fn find_edge(&self, a: u32, b: u32) -> Option<u32> {
        let (mut from_a, mut from_b) = (self.star(a), self.star(b));
        // Each star has fewer edges than there are triangles; the bound only guards the loop.
        for _ in 0..=self.tris.len() {
            let e = self.star_step(&mut from_a)?;
            if self.dest(e) == b {
                return Some(e);
            }
            let f = self.star_step(&mut from_b)?;
            if self.dest(f) == a {
                // `b → a`; its twin is `a → b` (none for a hull edge, which has one side).
                return Some(self.twin_of(f)).filter(|&e| e != NONE);
            }
        }
        None
    }

    /// A walk round the star of `v`, for [`Cdt::star_step`].
    fn star(&self, v: u32) -> Star {
        let first = self.out_edge[v as usize];
        Star {
            first,
            next: first,
            backwards: false,
        }
    }

    /// The next half-edge leaving the star's vertex, each once, `None` when all were given.
    /// An inserted vertex's star is a closed fan (it lies strictly inside the super
    /// triangle): counter-clockwise from its first edge back to it. A super vertex's star is
    /// open at the hull: counter-clockwise to the hull, then clockwise from the first edge
    /// (regression: a constraint crossing an edge from a super vertex, as thin rings with a
    /// long extent have, could not find that edge to flip it, and the rings were reported as
    /// crossing).
    fn star_step(&self, star: &mut Star) -> Option<u32> {
        let e = star.next;
        if e == NONE {
            return None;
        }
        star.next = if star.backwards {
            let back = self.twin_of(e);
            if back == NONE { NONE } else { next(back) }
        } else {
            let turned = self.twin_of(prev(e));
            if turned == star.first {
                NONE
            } else if turned == NONE {
                star.backwards = true;
                let back = self.twin_of(star.first);
                if back == NONE { NONE } else { next(back) }
            } else {
                turned
            }
        };
        Some(e)
    }

    /// Makes `a`–`b` a constraint edge: marks it when present, otherwise flips the edges it
    /// crosses out of its way (Sloan) and restores the Delaunay property around it.
    pub(crate) fn insert_constraint(&mut self, a: u32, b: u32) -> Result<(), CdtError> {
        if let Some(e) = self.find_edge(a, b) {
            self.mark_fixed(e);
            return Ok(());
        }
        let crossed = self.crossed_edges(a, b)?;
        let (pa, pb) = (self.point(a), self.point(b));
        let mut budget = 64 * (crossed.len() + 4) * (crossed.len() + 4);
        let mut queue: VecDeque<[u32; 2]> = crossed.into_iter().collect();
        let mut created: Vec<[u32; 2]> = Vec::new();
        while let Some([x, y]) = queue.pop_front() {
            budget = budget.saturating_sub(1);
            let Some(e) = self
                .find_edge(x, y)
                .filter(|&e| budget > 0 && self.twin_of(e) != NONE)
            else {
                return Err(CdtError::Crossing(NONE));
            };
            let p = self.apex(e);
            let q = self.apex(self.twin_of(e));
            let (px, py, pp, pq) = (self.point(x), self.point(y), self.point(p), self.point(q));
            // Flippable when the quadrilateral x, q, y, p is strictly convex.
            let convex = orient(pp, pq, px) * orient(pp, pq, py) < 0.0
                && orient(px, py, pp) * orient(px, py, pq) < 0.0;
            if !convex {
                queue.push_back([x, y]);
                continue;
            }
            self.flip(e);
            let (op, oq) = (orient(pa, pb, pp), orient(pa, pb, pq));
            if op * oq < 0.0 {
                queue.push_back([p, q]);
            } else {
                created.push([p, q]);
            }
        }
        let Some(e) = self.find_edge(a, b) else {
            return Err(CdtError::Crossing(NONE));
        };
        self.mark_fixed(e);
        // Restore the Delaunay property on the new edges (the constraint excepted).
        let mut swapped = true;
        let mut rounds = 0;
        while swapped && rounds < 64 {
            swapped = false;
            rounds += 1;
            for pair in &mut created {
                let [x, y] = *pair;
                let Some(e) = self.find_edge(x, y) else {
                    continue;
                };
                let across = self.twin_of(e);
                if self.is_fixed(e) || across == NONE {
                    continue;
                }
                let (p, q) = (self.apex(e), self.apex(across));
                if in_circle(self.point(x), self.point(y), self.point(p), self.point(q)) {
                    self.flip(e);
                    *pair = [p, q];
                    swapped = true;
                }
            }
        }
        Ok(())
    }

    /// The edges the segment `a`–`b` crosses, in order from `a`, as vertex pairs (each with
    /// its first vertex right of `a → b`).
    fn crossed_edges(&self, a: u32, b: u32) -> Result<Vec<[u32; 2]>, CdtError> {
        let (pa, pb) = (self.point(a), self.point(b));
        let ahead = |p: DVec2| (p - pa).dot(pb - pa) > 0.0;
        // The triangle (a, x, y) around `a` whose edge x → y the segment leaves through.
        let first = self.out_edge[a as usize];
        let mut e = first;
        let mut start = None;
        for _ in 0..self.tris.len() {
            let (vx, vy) = (self.dest(e), self.apex(e));
            let (x, y) = (self.point(vx), self.point(vy));
            let (ox, oy) = (orient(pa, pb, x), orient(pa, pb, y));
            // A vertex on the segment.
            if ox == 0.0 && ahead(x) {
                return Err(CdtError::Crossing(vx));
            }
            if oy == 0.0 && ahead(y) {
                return Err(CdtError::Crossing(vy));
            }
            if ox < 0.0 && oy > 0.0 {
                start = Some(next(e));
                break;
            }
            e = self.twin_of(prev(e));
            if e == NONE || e == first {
                break;
            }
        }
        let mut crossing = start.ok_or(CdtError::Crossing(NONE))?;
        let mut crossed = Vec::new();
        for _ in 0..self.tris.len() {
            let across = self.twin_of(crossing);
            if self.is_fixed(crossing) || across == NONE {
                return Err(CdtError::Crossing(self.origin(crossing)));
            }
            crossed.push([self.origin(crossing), self.dest(crossing)]);
            let z = self.apex(across);
            if z == b {
                return Ok(crossed);
            }
            // `across` runs y → x in the triangle (y, x, z): the segment leaves it through
            // x → z when z lies left of it, through z → y when right.
            let oz = orient(pa, pb, self.point(z));
            crossing = if oz > 0.0 {
                next(across)
            } else if oz < 0.0 {
                prev(across)
            } else {
                return Err(CdtError::Crossing(z));
            };
        }
        Err(CdtError::Crossing(NONE))
    }

    fn mark_fixed(&mut self, e: u32) {
        self.tris[tri_of(e)].fixed |= 1 << slot(e);
        let f = self.twin_of(e);
        if f != NONE {
            self.tris[tri_of(f)].fixed |= 1 << slot(f);
        }
    }

    /// Marks the triangles inside the constraint rings (even–odd: crossing a constraint edge
    /// toggles the side), by a flood fill from a super vertex's triangle.
    pub(crate) fn mark_inside(&mut self) {
        let mut seen = alloc::vec![false; self.tris.len()];
        let start = tri_of(self.out_edge[0]);
        let mut stack = alloc::vec![start];
        seen[start] = true;
        self.tris[start].inside = false;
        while let Some(t) = stack.pop() {
            let tri = self.tris[t];
            for i in 0..3 {
                let f = tri.twin[i];
                if f == NONE || seen[tri_of(f)] {
                    continue;
                }
                let u = tri_of(f);
                seen[u] = true;
                self.tris[u].inside = tri.inside ^ (tri.fixed & (1 << i) != 0);
                stack.push(u);
            }
        }
    }

    /// Delaunay refinement of the inside triangles: constraint edges with a vertex in their
    /// diametral circle are split at their midpoints, then every triangle with an angle below
    /// `min_angle_deg` gets its circumcentre (unless that would encroach upon a constraint
    /// edge, which is split instead), until none is left or `budget` vertices were added.
    /// Triangles whose smallest angle lies between two constraint edges (an input corner)
    /// are left alone. Returns whether it finished within the budget.
    pub(crate) fn refine(&mut self, min_angle_deg: f64, budget: usize) -> bool {
        let limit = self.points.len().saturating_add(budget);
        let sin = crate::math::sin_f64(min_angle_deg.to_radians());
        let sin2 = sin * sin;
        // Off-centres make triangles with an apex angle a tenth above the limit.
        let tan_half = (min_angle_deg * 1.1).min(60.0).to_radians() * 0.5;
        let tan_half = crate::math::tan_f64(tan_half);
        let mut inside_area2 = 0.0;
        for tri in self.tris.iter().filter(|t| t.inside) {
            let [a, b, c] = tri.v.map(|v| self.point(v));
            inside_area2 += orient(a, b, c);
        }
        self.bulge_left = inside_area2 * MAX_BULGE;
        let mut queues = Queues::default();
        for t in 0..self.tris.len() as u32 {
            let tri = &self.tris[t as usize];
            if !tri.inside || tri.fixed == 0 {
                continue;
            }
            let fixed = tri.fixed;
            for i in 0..3 {
                let e = edge(t, i);
                if fixed & (1 << i) != 0 && self.encroached(e) {
                    queues.segments.push_back(e);
                }
            }
        }
        let mut scanned = false;
        loop {
            // Encroached constraint edges first.
            while let Some(e) = queues.segments.pop_front() {
                if self.points.len() >= limit {
                    return false;
                }
                if self.is_fixed(e) && self.encroached(e) {
                    self.split_and_queue(e, sin2, &mut queues);
                }
            }
            if !scanned {
                scanned = true;
                for t in 0..self.tris.len() as u32 {
                    if self.is_bad(t, sin2) {
                        queues.bad.push_back((t, self.tris[t as usize].v));
                    }
                }
            }
            let Some((t, vertices)) = queues.bad.pop_front() else {
                return true;
            };
            if self.tris[t as usize].v != vertices || !self.is_bad(t, sin2) {
                continue;
            }
            if self.points.len() >= limit {
                return false;
            }
            let Some(centre) = self.steiner_point(t, tan_half) else {
                continue;
            };
            // The constraint edges the centre would encroach upon (or lies beyond); when
            // there are none, where to insert it.
            let (encroached, at) = match self.walk(t, centre, true) {
                Walk::Blocked(e) if e != NONE => (alloc::vec![e], None),
                Walk::Found(Location::Edge(e)) if self.is_fixed(e) => (alloc::vec![e], None),
                Walk::Found(Location::Edge(e)) if self.is_inside(tri_of(e) as u32) => {
                    self.dig(centre, tri_of(e) as u32);
                    (self.encroached_on_boundary(centre), Some(Location::Edge(e)))
                }
                Walk::Found(Location::Triangle(u)) if self.is_inside(u) => {
                    self.dig(centre, u);
                    (
                        self.encroached_on_boundary(centre),
                        Some(Location::Triangle(u)),
                    )
                }
                // On a vertex, or (only through the walk's fallback) outside: leave it.
                _ => continue,
            };
            if encroached.is_empty() {
                let v = match (self.fill_cavity(centre), at) {
                    (Some(v), _) => v,
                    (None, Some(Location::Edge(e))) => self.split_edge(e, centre),
                    (None, Some(Location::Triangle(u))) => self.split_triangle(u, centre),
                    _ => continue,
                };
                self.queue_around(v, sin2, &mut queues);
            } else {
                // Split them instead, and come back to the triangle if anything changed.
                let mut split = false;
                for e in encroached {
                    if self.points.len() >= limit {
                        return false;
                    }
                    if self.is_fixed(e) {
                        split |= self.split_and_queue(e, sin2, &mut queues);
                    }
                }
                if split {
                    queues.bad.push_back((t, vertices));
                }
            }
        }
    }

    /// Splits a constraint edge at its midpoint and queues what that changes; `false` when
    /// it cannot be split.
    fn split_and_queue(&mut self, e: u32, sin2: f64, queues: &mut Queues) -> bool {
        match self.split_segment(e) {
            Some(v) => {
                self.queue_around(v, sin2, queues);
                true
            }
            None => false,
        }
    }

    /// After inserting `v`: queues the bad triangles around it and the constraint edges of
    /// its star that a vertex encroaches upon.
    fn queue_around(&self, v: u32, sin2: f64, queues: &mut Queues) {
        let first = self.out_edge[v as usize];
        let mut e = first;
        for _ in 0..self.tris.len() {
            let t = tri_of(e) as u32;
            if self.is_bad(t, sin2) {
                queues.bad.push_back((t, self.tris[t as usize].v));
            }
            // The edge opposite v.
            let s = next(e);
            if self.is_inside(t) && self.is_fixed(s) && self.encroached(s) {
                queues.segments.push_back(s);
            }
            e = self.twin_of(prev(e));
            if e == NONE || e == first {
                break;
            }
        }
    }

    /// Whether the apex of an inside triangle on either side of a constraint half-edge lies
    /// strictly inside its diametral circle.
    fn encroached(&self, e: u32) -> bool {
        let (a, b) = (self.point(self.origin(e)), self.point(self.dest(e)));
        [e, self.twin_of(e)].into_iter().any(|s| {
            s != NONE && self.is_inside(tri_of(s) as u32) && {
                let p = self.point(self.apex(s));
                (a - p).dot(b - p) < 0.0
            }
        })
    }

    /// Digs `p`'s cavity: the triangles whose circumcircle certainly holds it, reached from
    /// triangle `t` (which holds `p`) without crossing a constraint edge; fills
    /// [`Cdt::cavity`] and [`Cdt::boundary`].
    fn dig(&mut self, p: DVec2, t: u32) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.dug.fill(0);
            self.stamp = 1;
        }
        self.dug.resize(self.tris.len(), 0);
        self.cavity.clear();
        self.boundary.clear();
        self.cavity.push(t);
        self.dug[t as usize] = self.stamp;
        let mut k = 0;
        while let Some(&c) = self.cavity.get(k) {
            k += 1;
            for i in 0..3 {
                let e = edge(c, i);
                let f = self.twin_of(e);
                if f == NONE || self.is_fixed(e) {
                    self.boundary.push(e);
                    continue;
                }
                let u = tri_of(f);
                if self.dug[u] == self.stamp {
                    continue;
                }
                let [x, y, z] = self.tris[u].v.map(|v| self.point(v));
                if in_circle(x, y, z, p) {
                    self.dug[u] = self.stamp;
                    self.cavity.push(u as u32);
                } else {
                    self.boundary.push(e);
                }
            }
        }
    }

    /// The constraint half-edges on the boundary of the cavity [`Cdt::dig`] dug for `p` that
    /// `p` would encroach upon once inserted.
    fn encroached_on_boundary(&self, p: DVec2) -> Vec<u32> {
        self.boundary
            .iter()
            .copied()
            .filter(|&e| {
                self.is_fixed(e) && {
                    let (a, b) = (self.point(self.origin(e)), self.point(self.dest(e)));
                    (a - p).dot(b - p) < 0.0
                }
            })
            .collect()
    }

    /// Inserts `p` into the cavity [`Cdt::dig`] dug for it (Bowyer–Watson): its triangles
    /// give way to a fan from `p` to the boundary, which is the Delaunay result, with no
    /// flips. `None`, changing nothing, unless the cavity is a disk with `p` strictly
    /// inside every boundary edge (ties in the in-circle filter can break that; the caller
    /// then inserts by flips).
    fn fill_cavity(&mut self, p: DVec2) -> Option<u32> {
        let n = self.boundary.len();
        if n != self.cavity.len() + 2 {
            return None;
        }
        self.fan.clear();
        for &e in &self.boundary {
            let (a, b) = (self.origin(e), self.dest(e));
            if !(orient(self.point(a), self.point(b), p) > 0.0) {
                return None;
            }
            let fixed = u8::from(self.is_fixed(e));
            self.fan.push((a, b, self.twin_of(e), fixed));
        }
        // Order the boundary into its loop (each edge starts where the last one ended), so
        // fan triangle k's neighbours are k - 1 and k + 1.
        for k in 1..n {
            let end = self.fan[k - 1].1;
            let next = (k..n).find(|&m| self.fan[m].0 == end)?;
            self.fan.swap(k, next);
        }
        if self.fan[n - 1].1 != self.fan[0].0 {
            return None;
        }
        let inside = self.is_inside(self.cavity[0]);
        let v = self.add_point(p);
        let first_new = self.new_triangles(2);
        self.cavity.extend([first_new, first_new + 1]);
        for k in 0..n {
            let (a, b, twin, fixed) = self.fan[k];
            let t = self.cavity[k];
            self.tris[t as usize] = Tri {
                v: [a, b, v],
                twin: [
                    twin,
                    edge(self.cavity[(k + 1) % n], 2),
                    edge(self.cavity[(k + n - 1) % n], 1),
                ],
                fixed,
                inside,
            };
            if twin != NONE {
                self.tris[tri_of(twin)].twin[slot(twin)] = edge(t, 0);
            }
            self.out_edge[a as usize] = edge(t, 0);
        }
        self.out_edge[v as usize] = edge(self.cavity[0], 2);
        self.last = self.cavity[0];
        Some(v)
    }

    /// Splits a constraint edge at its (f32-rounded) midpoint; `None` when the edge is too
    /// short to split, the rounded midpoint would fold a triangle, or the sliver it adds to or
    /// cuts from the inside would exceed what is left of the refinement's [`MAX_BULGE`].
    fn split_segment(&mut self, e: u32) -> Option<u32> {
        let f = self.twin_of(e);
        if f == NONE {
            return None;
        }
        let (a, b) = (self.point(self.origin(e)), self.point(self.dest(e)));
        let m = to_f32_exact((a + b) * 0.5);
        let (c, d) = (self.point(self.apex(e)), self.point(self.apex(f)));
        // The four new triangles (c, a, m), (b, c, m), (d, b, m), (a, d, m) keep their
        // orientation (which also rules out a midpoint rounded onto an end).
        let ok = orient(c, a, m) > 0.0
            && orient(b, c, m) > 0.0
            && orient(d, b, m) > 0.0
            && orient(a, d, m) > 0.0;
        // Twice the sliver's area: zero when the rounded midpoint is on the edge.
        let bulge = orient(a, b, m).abs();
        if !ok || !(bulge <= self.bulge_left) {
            return None;
        }
        self.bulge_left -= bulge;
        Some(self.split_edge(e, m))
    }

    /// Whether `t` is an inside triangle whose smallest angle is below the limit (`sin2` its
    /// squared sine) and not at an input corner between two constraint edges.
    fn is_bad(&self, t: u32, sin2: f64) -> bool {
        let tri = &self.tris[t as usize];
        if !tri.inside {
            return false;
        }
        let [pa, pb, pc] = tri.v.map(|v| self.point(v));
        // Edge i runs from vertex i to i + 1; the smallest angle is opposite the shortest.
        let l = [
            pa.distance_squared(pb),
            pb.distance_squared(pc),
            pc.distance_squared(pa),
        ];
        let i = if l[0] <= l[1] && l[0] <= l[2] {
            0
        } else if l[1] <= l[2] {
            1
        } else {
            2
        };
        // sin(smallest) = 2·area / (product of the two other edges).
        let area2 = (pb - pa).perp_dot(pc - pa);
        if !(area2 * area2 < sin2 * l[(i + 1) % 3] * l[(i + 2) % 3]) {
            return false;
        }
        // The smallest angle lies between edges i + 1 and i + 2: both constraints make an
        // input corner, which refinement cannot fix.
        let corner = (1 << ((i + 1) % 3)) | (1 << ((i + 2) % 3));
        tri.fixed & corner != corner
    }

    /// Where refinement puts a point for a bad triangle, rounded to `f32` (`None` if the
    /// triangle is degenerate): its circumcentre, or Üngör's off-centre when that is nearer
    /// the shortest edge — the apex of the isosceles triangle on that edge whose apex
    /// angle has the tangent of half of it `tan_half` (a little above the limit), so the
    /// new triangle there is good and fewer points are needed.
    fn steiner_point(&self, t: u32, tan_half: f64) -> Option<DVec2> {
        let [a, b, c] = self.tris[t as usize].v.map(|v| self.point(v));
        let (ab, ac) = (b - a, c - a);
        let d = 2.0 * ab.perp_dot(ac);
        let (l1, l2) = (ab.length_squared(), ac.length_squared());
        let centre = a + DVec2::new(ac.y * l1 - ab.y * l2, ab.x * l2 - ac.x * l1) / d;
        // The shortest edge and its midpoint; the circumcentre lies on its bisector.
        let bc = c - b;
        let (p, q) = if l1 <= l2 && l1 <= bc.length_squared() {
            (a, b)
        } else if l2 <= bc.length_squared() {
            (a, c)
        } else {
            (b, c)
        };
        let m = (p + q) * 0.5;
        let (to_centre, half) = (centre - m, p.distance(q) * 0.5);
        let (far, near) = (to_centre.length(), half / tan_half);
        let point = if near < far {
            m + to_centre * (near / far)
        } else {
            centre
        };
        let point = to_f32_exact(point);
        (d != 0.0 && point.is_finite()).then_some(point)
    }
}

/// The location of a point in triangle `t` given which edges' lines it lies on.
fn locate_in(t: u32, v: [u32; 3], on_line: [bool; 3]) -> Location {
    match on_line {
        [false, false, false] => Location::Triangle(t),
        [true, false, false] => Location::Edge(edge(t, 0)),
        [false, true, false] => Location::Edge(edge(t, 1)),
        [false, false, true] => Location::Edge(edge(t, 2)),
        // On two edges' lines: their shared vertex.
        [true, true, _] => Location::Vertex(v[1]),
        [_, true, true] => Location::Vertex(v[2]),
        [true, _, true] => Location::Vertex(v[0]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    impl Cdt {
        /// Every structural invariant: counter-clockwise triangles (exactly), twins that
        /// point back with swapped ends, symmetric constraint bits, a side that changes only
        /// across constraints (when `sided`), vertex edges that leave their vertex.
        fn check(&self, sided: bool) {
            for (t, tri) in self.tris.iter().enumerate() {
                let [a, b, c] = tri.v.map(|v| self.point(v));
                assert!(
                    orient(a, b, c) > 0.0,
                    "triangle {t} is not counter-clockwise"
                );
                for i in 0..3 {
                    let e = edge(t as u32, i as u32);
                    let f = tri.twin[i];
                    if f == NONE {
                        assert!(
                            tri.v[i] < 3 && tri.v[after(i)] < 3,
                            "hull edge off the super triangle"
                        );
                        continue;
                    }
                    assert_eq!(self.twin_of(f), e);
                    assert_eq!(
                        (self.origin(f), self.dest(f)),
                        (self.dest(e), self.origin(e))
                    );
                    assert_eq!(self.is_fixed(e), self.is_fixed(f));
                    if sided && !self.is_fixed(e) {
                        assert_eq!(tri.inside, self.is_inside(tri_of(f) as u32));
                    }
                }
            }
            for (v, &e) in self.out_edge.iter().enumerate() {
                assert_eq!(
                    self.origin(e) as usize,
                    v,
                    "vertex {v}'s edge does not leave it"
                );
            }
        }

        /// Whether the edges that are not constraints are locally Delaunay (up to ties).
        fn is_delaunay(&self) -> bool {
            (0..self.tris.len() as u32).all(|t| {
                (0..3).all(|i| {
                    let e = edge(t, i);
                    let f = self.twin_of(e);
                    f == NONE || self.is_fixed(e) || {
                        let [a, b, c] = self.tris[t as usize].v.map(|v| self.point(v));
                        !in_circle(a, b, c, self.point(self.apex(f)))
                    }
                })
            })
        }

        fn smallest_inside_angle(&self) -> f64 {
            let mut smallest = f64::INFINITY;
            for tri in self.tris.iter().filter(|t| t.inside) {
                let p = tri.v.map(|v| self.point(v));
                for k in 0..3 {
                    let (u, w) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
                    smallest = smallest.min(u.perp_dot(w).abs().atan2(u.dot(w)).to_degrees());
                }
            }
            smallest
        }
    }

    /// Deterministic points in a box (xorshift), on the f32 grid.
    fn points(count: usize, seed: u32, size: f64) -> Vec<DVec2> {
        let mut s = seed;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            f64::from(s >> 8) / f64::from(1u32 << 24) * size
        };
        (0..count)
            .map(|_| to_f32_exact(DVec2::new(next(), next())))
            .collect()
    }

    fn square(cdt: &mut Cdt, lo: f64, hi: f64) -> [u32; 4] {
        let corners = [
            DVec2::new(lo, lo),
            DVec2::new(hi, lo),
            DVec2::new(hi, hi),
            DVec2::new(lo, hi),
        ];
        let v = corners.map(|p| cdt.insert(p).unwrap());
        for k in 0..4 {
            cdt.insert_constraint(v[k], v[(k + 1) % 4]).unwrap();
        }
        v
    }

    #[test]
    fn random_points_give_a_valid_delaunay_triangulation() {
        let mut cdt = Cdt::new(DVec2::ZERO, DVec2::splat(100.0), 500);
        for p in points(500, 7, 100.0) {
            cdt.insert(p).unwrap();
        }
        cdt.check(false);
        assert!(cdt.is_delaunay());
        // Euler: 2n + 1 triangles for n points inside the super triangle.
        assert_eq!(cdt.tris.len(), 2 * 500 + 1);
    }

    #[test]
    fn lattice_points_with_exact_ties_terminate_and_stay_valid() {
        let mut cdt = Cdt::new(DVec2::ZERO, DVec2::splat(20.0), 441);
        for j in 0..21 {
            for i in 0..21 {
                cdt.insert(DVec2::new(f64::from(i), f64::from(j))).unwrap();
            }
        }
        cdt.check(false);
        assert!(cdt.is_delaunay());
    }

    #[test]
    fn duplicates_and_points_on_constraints_are_refused() {
        let mut cdt = Cdt::new(DVec2::ZERO, DVec2::splat(10.0), 8);
        let [a, ..] = square(&mut cdt, 0.0, 10.0);
        assert_eq!(cdt.insert(DVec2::ZERO), Err(CdtError::Occupied(a)));
        assert!(matches!(
            cdt.insert(DVec2::new(5.0, 0.0)),
            Err(CdtError::Occupied(_))
        ));
        // On an edge that is not a constraint: split.
        assert!(cdt.insert(DVec2::new(5.0, 5.0)).is_ok());
        cdt.check(false);
    }

    #[test]
    fn constraints_are_flipped_into_place_and_crossings_refused() {
        let mut cdt = Cdt::new(DVec2::ZERO, DVec2::splat(100.0), 300);
        for p in points(300, 11, 100.0) {
            cdt.insert(p).unwrap();
        }
        let a = cdt.insert(DVec2::new(-1.0, 50.0)).unwrap();
        let b = cdt.insert(DVec2::new(101.0, 50.5)).unwrap();
        cdt.insert_constraint(a, b).unwrap();
        cdt.check(false);
        assert!(cdt.find_edge(a, b).is_some_and(|e| cdt.is_fixed(e)));
        assert!(cdt.is_delaunay());
        let c = cdt.insert(DVec2::new(50.0, -1.0)).unwrap();
        let d = cdt.insert(DVec2::new(50.5, 101.0)).unwrap();
        assert!(matches!(
            cdt.insert_constraint(c, d),
            Err(CdtError::Crossing(v)) if v == a || v == b
        ));
        // Through a vertex.
        let m = cdt.insert(DVec2::new(-1.0, 0.0)).unwrap();
        let n = cdt.insert(DVec2::new(-1.0, 100.0)).unwrap();
        assert_eq!(cdt.insert_constraint(m, n), Err(CdtError::Crossing(a)));
    }

    #[test]
    fn refinement_meets_the_angle_limit_inside_only() {
        let mut cdt = Cdt::new(DVec2::ZERO, DVec2::splat(100.0), 200);
        square(&mut cdt, 0.0, 100.0);
        // A thin sliver of points along the bottom.
        for x in 1..40 {
            cdt.insert(DVec2::new(f64::from(x) * 2.5, 0.25)).unwrap();
        }
        cdt.mark_inside();
        assert!(cdt.smallest_inside_angle() < 5.0);
        assert!(cdt.refine(30.0, 10_000));
        cdt.check(true);
        assert!(cdt.smallest_inside_angle() >= 30.0 - 1e-9);
        // Every vertex stays in the square.
        assert!(
            cdt.points[3..]
                .iter()
                .all(|p| p.cmpge(DVec2::ZERO).all() && p.cmple(DVec2::splat(100.0)).all())
        );
    }

    #[test]
    fn refinement_stops_at_its_budget() {
        let mut cdt = Cdt::new(DVec2::ZERO, DVec2::splat(100.0), 200);
        square(&mut cdt, 0.0, 100.0);
        for x in 1..40 {
            cdt.insert(DVec2::new(f64::from(x) * 2.5, 0.25)).unwrap();
        }
        cdt.mark_inside();
        let before = cdt.points.len();
        assert!(!cdt.refine(30.0, 5));
        assert_eq!(cdt.points.len(), before + 5);
        cdt.check(true);
    }
}
