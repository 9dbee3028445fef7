//! Step 2: following one contour cell by cell until it closes, with its crossings (refined
//! on the field when asked) and saddle cells.

use alloc::vec::Vec;

use glam::Vec2;

use super::Tracer;
use super::nodes::{Nodes, TILE_MASK};
use super::rings::Traced;
use crate::cell;
use crate::sort::sort_unstable_by;
use crate::tile::TileField;
use crate::{MarchError, Saddle};

impl<F: TileField + ?Sized> Tracer<'_, F> {
    fn joined(&mut self, i: i32, j: i32, values: [f32; 4]) -> bool {
        match self.options.saddle {
            Saddle::Centre => {
                let v = match self.centres.get((i, j)) {
                    Some(v) => v,
                    None => {
                        let p = (Vec2::new(i as f32, j as f32) + 0.5) * self.step;
                        let v = self.field.value(p);
                        self.centres.insert((i, j), v);
                        v
                    }
                };
                cell::is_inside(v, self.iso)
            }
            Saddle::Asymptotic => cell::asymptotic_joined(values, self.iso),
        }
    }

    /// Follows the contour entering cell `start` through its in→out edge `k` until it closes.
    /// Returns the new ring's index.
    ///
    /// The cell's corners are kept relative to the entry edge: `a` (corner `k`, inside) and
    /// `b` (corner `k + 1`, outside) are carried over from the previous cell, `c` and `d`
    /// (corners `k + 2`, `k + 3`) are read. Which of `c` and `d` are inside settles the exit
    /// edge (see [`cell::exit_edge`]): `k + 1` when both are, `k + 2` when only `d` is, `k + 3`
    /// when neither is, and the saddle rule when only `c` is.
    pub(super) fn trace_ring(
        &mut self,
        start: (i32, i32),
        k: usize,
        hint: usize,
        nested: bool,
    ) -> Result<usize, MarchError> {
        let id = self.rings.len();
        let iso = self.iso;
        let mut path = Path::new();
        let start_k = k & 3;
        let mut at = Step {
            ci: start.0,
            cj: start.1,
            k: start_k,
            a: 0.0,
            b: 0.0,
        };
        let (i, j) = at.corner(0);
        at.a = self.node(i, j);
        let (i, j) = at.corner(1);
        at.b = self.node(i, j);
        let closed = |at: &Step| (at.ci, at.cj) == start && at.k == start_k;
        // The budget left for this ring, counted locally and settled when it closes.
        let budget = self.options.max_cells.saturating_sub(self.cells);
        let mut cells = 0;
        loop {
            // Any cell: its far corners through the tile cache; saddles settled.
            cells += 1;
            if cells > budget {
                return Err(self.out_of_budget(hint));
            }
            let (i, j) = at.corner(2);
            let c = self.node(i, j);
            let (i, j) = at.corner(3);
            let d = self.node(i, j);
            let (p, off_node) = self.crossing(at.edge(), at.a, at.b);
            path.push(p, &at);
            path.on_node(off_node);
            if at.k & 1 == 1 {
                // A vertical entry edge, from node (x, cj) up: marked crossed.
                let x = at.corner(0).0;
                let tile = self.tile(x, at.cj);
                self.nodes.mark_crossed(tile, 1 << Nodes::slot(x, at.cj));
            }
            let flags =
                usize::from(cell::is_inside(c, iso)) | usize::from(cell::is_inside(d, iso)) << 1;
            let mut turn = Step::turn(flags);
            if flags == 1 {
                let mut values = [0.0; 4];
                for (n, v) in [at.a, at.b, c, d].into_iter().enumerate() {
                    values[(at.k + n) & 3] = v;
                }
                if !self.joined(at.ci, at.cj, values) {
                    turn = 3;
                }
            }
            at.advance(turn, c, d);
            if closed(&at) {
                break;
            }
            // Cells whose corners all lie in one tile whose nodes are all sampled: the inside
            // flags from the tile's mask, kept in a register, and the samples read only for
            // the crossings, so that the walk does not wait on them.
            if at.ci & TILE_MASK == TILE_MASK || at.cj & TILE_MASK == TILE_MASK {
                continue;
            }
            let tile = self.tile(at.ci, at.cj);
            let Some(inside) = self.nodes.all_inside(tile) else {
                continue;
            };
            // The vertical entry edges crossed in the tile, marked when the walk leaves it.
            let mut crossed = 0u64;
            let closed_here = loop {
                let (slot_c, slot_d) = (at.slot(2), at.slot(3));
                let flags = (inside >> slot_c & 1) | (inside >> slot_d & 1) << 1;
                if flags == 1 {
                    // A saddle: settled above.
                    break false;
                }
                cells += 1;
                if cells > budget {
                    return Err(self.out_of_budget(hint));
                }
                let c = self.nodes.sampled(tile, slot_c);
                let d = self.nodes.sampled(tile, slot_d);
                let (p, off_node) = self.crossing(at.edge(), at.a, at.b);
                path.push(p, &at);
                path.on_node(off_node);
                crossed |= ((at.k & 1) as u64) << Nodes::slot(at.corner(0).0, at.cj);
                at.advance(Step::turn(flags as usize), c, d);
                if closed(&at) {
                    break true;
                }
                if at.ci & TILE_MASK == TILE_MASK || at.cj & TILE_MASK == TILE_MASK {
                    break false;
                }
            };
            self.nodes.mark_crossed(tile, crossed);
            if closed_here {
                break;
            }
        }
        self.cells += cells;
        path.unpinch();
        let Path {
            points,
            mut verticals,
            crossed,
            on_node,
        } = path;
        verticals.truncate(crossed);
        if let Some(table) = &mut self.ring_of_edge {
            for &edge in &verticals {
                table.insert(edge, id as u32);
            }
        }
        let mut ring = Traced::new(points, verticals, nested);
        ring.on_node = on_node;
        self.rings.push(ring);
        Ok(id)
    }

    /// The crossing between an inside node `a` and an outside node `b` (an edge of the grid),
    /// in world units, refined on the field when asked; with, for a refined crossing exactly
    /// on a node, the same crossing kept [`cell::NODE_GAP`] off it (see [`Path::unpinch`]).
    #[inline(always)]
    fn crossing(
        &mut self,
        (a, b): ((i32, i32), (i32, i32)),
        v_in: f32,
        v_out: f32,
    ) -> (Vec2, Option<Vec2>) {
        let pa = Vec2::new(a.0 as f32, a.1 as f32);
        let pb = Vec2::new(b.0 as f32, b.1 as f32);
        let t = cell::crossing(v_in, v_out, self.iso);
        let step = self.step;
        let at = |t: f32| (pa + (pb - pa) * t) * step;
        if self.options.refine_steps > 0 {
            let t = self.refine(pa, pb, t, v_in, v_out);
            let off = t.clamp(cell::NODE_GAP, 1.0 - cell::NODE_GAP);
            (at(t), (off != t).then(|| at(off)))
        } else {
            // Off the nodes, as in the grid: two crossings beside an outside node a hair below
            // the iso-level would otherwise both sit on it and pinch the ring.
            (at(t.clamp(cell::NODE_GAP, 1.0 - cell::NODE_GAP)), None)
        }
    }

    /// Illinois false-position steps on the field along the edge, bracketing the crossing.
    #[inline(never)]
    fn refine(&mut self, pa: Vec2, pb: Vec2, t0: f32, v_in: f32, v_out: f32) -> f32 {
        let steps = self.options.refine_steps;
        let (mut a, mut fa) = (0.0f32, v_in - self.iso);
        let (mut b, mut fb) = (1.0f32, v_out - self.iso);
        if fa == 0.0 {
            // The inside node sits on the iso-line.
            return 0.0;
        }
        let mut t = t0;
        let mut side = 0i8;
        for _ in 0..steps {
            let v = self.field.value((pa + (pb - pa) * t) * self.step);
            if v == self.iso {
                return t;
            }
            if cell::is_inside(v, self.iso) {
                a = t;
                fa = v - self.iso;
                if side == 1 {
                    fb *= 0.5;
                }
                side = 1;
            } else {
                b = t;
                fb = v - self.iso;
                if side == -1 {
                    fa *= 0.5;
                }
                side = -1;
            }
            let secant = a + (b - a) * fa / (fa - fb);
            t = if secant.is_finite() && secant >= a && secant <= b {
                secant
            } else {
                0.5 * (a + b)
            };
            if !(b - a > f32::EPSILON) {
                break;
            }
        }
        t
    }
}

/// [`Path::unpinch`] across rings: where refined crossings of two or more rings sit on the
/// same grid node (a node on the iso-level that an outer ring and a hole beside it both pass
/// through), the rings would touch there. Every crossing on such a node moves
/// [`cell::NODE_GAP`] off it along its own edge, and the moved rings' areas are measured
/// again. Rings meet nowhere else: every other crossing lies inside its own grid edge.
pub(super) fn unpinch_across(rings: &mut [Traced]) {
    let key = |p: Vec2| (p.x.to_bits(), p.y.to_bits());
    // (node, ring, point, the point off the node), grouped by node.
    let mut on_nodes: Vec<((u32, u32), usize, usize, Vec2)> = rings
        .iter()
        .enumerate()
        .flat_map(|(r, ring)| {
            ring.on_node
                .iter()
                .map(move |&(i, off)| (key(ring.points[i]), r, i, off))
        })
        .collect();
    if on_nodes.len() < 2 {
        return;
    }
    sort_unstable_by(&mut on_nodes, &mut |&(n, r, i, _), &(m, s, j, _)| {
        (n, r, i).cmp(&(m, s, j))
    });
    let mut moved = Vec::new();
    for group in on_nodes.chunk_by(|a, b| a.0 == b.0) {
        if group[0].1 != group[group.len() - 1].1 {
            for &(_, r, i, off) in group {
                rings[r].points[i] = off;
                moved.push(r);
            }
        }
    }
    moved.sort_unstable();
    moved.dedup();
    for r in moved {
        rings[r].area = crate::ring::signed_area(&rings[r].points);
    }
}

/// Where a contour walk is: cell `(ci, cj)`, entered through its edge `k` from corner `k`
/// (inside, sample `a`) to corner `k + 1` (outside, sample `b`).
struct Step {
    ci: i32,
    cj: i32,
    k: usize,
    a: f32,
    b: f32,
}

impl Step {
    /// The exit edge, counted from the entry edge, by the inside flags of corners `k + 2` and
    /// `k + 3` (`c | d << 1`): `k + 3` when neither is inside, `k + 2` when only `d` is,
    /// `k + 1` when both are; a saddle (only `c`) goes to `k + 1` when joined, else `k + 3`.
    /// As [`cell::exit_edge`], with the entry edge's corners known to be inside, outside.
    const TURN: [usize; 4] = [3, 1, 2, 1];

    /// `TURN[flags & 3]` from a constant's bit pairs rather than a table (see
    /// [`cell::corner`]).
    #[inline(always)]
    const fn turn(flags: usize) -> usize {
        const PACKED: usize =
            Step::TURN[0] | Step::TURN[1] << 2 | Step::TURN[2] << 4 | Step::TURN[3] << 6;
        PACKED >> (2 * (flags & 3)) & 3
    }

    /// Grid node of corner `k + n`.
    #[inline]
    fn corner(&self, n: usize) -> (i32, i32) {
        let (di, dj) = cell::corner(self.k + n);
        (self.ci + di, self.cj + dj)
    }

    /// Tile slot of corner `k + n`, for a cell whose corners lie in one tile.
    #[inline]
    fn slot(&self, n: usize) -> usize {
        let (i, j) = self.corner(n);
        Nodes::slot(i, j)
    }

    /// The entry edge: its inside node, then its outside node.
    #[inline]
    fn edge(&self) -> ((i32, i32), (i32, i32)) {
        (self.corner(0), self.corner(1))
    }

    /// Leaves through edge `k + turn` into the next cell, given the samples `c`, `d` of
    /// corners `k + 2`, `k + 3`. The exit edge, seen from the next cell, runs from its inside
    /// end to its outside end: `c`–`b`, `d`–`c` or `a`–`d`.
    #[inline]
    fn advance(&mut self, turn: usize, c: f32, d: f32) {
        let exit = (self.k + turn) & 3;
        // Turn 1: `c`–`b`; 2: `d`–`c`; 3: `a`–`d` (selects, not an array in memory, which
        // took longer). The turn is never 0 (back through the entry edge): `Step::turn` gives
        // 1 to 3, and so does the saddle rule.
        debug_assert!(matches!(turn, 1..=3), "turn {turn}");
        let (a, b) = match turn & 3 {
            1 => (c, self.b),
            2 => (d, c),
            _ => (self.a, d),
        };
        self.a = a;
        self.b = b;
        let (di, dj) = cell::across(exit);
        self.ci += di;
        self.cj += dj;
        self.k = (exit + 2) & 3;
    }
}

/// A ring's points and the vertical edges it crosses, while it is traced.
struct Path {
    points: Vec<Vec2>,
    /// The vertical edges crossed, as `(column, lower row)`: the first `crossed`. Each cell
    /// writes its entry edge at `crossed` and keeps it (advancing `crossed`) only when the
    /// edge is vertical: no branch on it.
    verticals: Vec<(i32, i32)>,
    crossed: usize,
    /// Refined crossings that sit exactly on a grid node: the index of the point and the same
    /// crossing kept [`cell::NODE_GAP`] off the node. Rare (a node on the iso-level, or
    /// refinement converging onto a node).
    on_node: Vec<(usize, Vec2)>,
}

impl Path {
    fn new() -> Self {
        Self {
            points: Vec::with_capacity(64),
            verticals: alloc::vec![(0, 0); 64],
            crossed: 0,
            on_node: Vec::new(),
        }
    }

    /// Notes that the point just pushed lies on a grid node, `off` being its crossing kept off
    /// the node.
    #[inline(always)]
    fn on_node(&mut self, off: Option<Vec2>) {
        if let Some(off) = off {
            self.on_node.push((self.points.len() - 1, off));
        }
    }

    /// A refined crossing on a node stays there (on the iso-line) unless the ring reaches
    /// that node more than once apart (not as consecutive points, which the weld merges):
    /// the ring would then touch itself there. Every crossing on such a node moves
    /// [`cell::NODE_GAP`] off it along its own edge, as an unrefined crossing is, so the
    /// visits no longer meet. The crossings left on nodes stay in `on_node`, for
    /// [`unpinch_across`] to compare with the other rings'.
    fn unpinch(&mut self) {
        if self.on_node.len() < 2 {
            return;
        }
        let n = self.points.len();
        let key = |p: Vec2| (p.x.to_bits(), p.y.to_bits());
        // Grouped by node (same position, bit for bit), in ring order within a group.
        let mut order: Vec<usize> = (0..self.on_node.len()).collect();
        let at = |e: usize| (key(self.points[self.on_node[e].0]), self.on_node[e].0);
        sort_unstable_by(&mut order, &mut |&a, &b| at(a).cmp(&at(b)));
        let mut start = 0;
        while start < order.len() {
            let node = key(self.points[self.on_node[order[start]].0]);
            let mut end = start + 1;
            while end < order.len() && key(self.points[self.on_node[order[end]].0]) == node {
                end += 1;
            }
            let group = &order[start..end];
            // Runs of consecutive (cyclic) indices: a visit of the node each.
            let first = self.on_node[group[0]].0;
            let last = self.on_node[group[group.len() - 1]].0;
            let mut runs = group
                .windows(2)
                .filter(|w| self.on_node[w[1]].0 != self.on_node[w[0]].0 + 1)
                .count()
                + 1;
            if runs > 1 && first == 0 && last == n - 1 {
                // The first and last runs are one, across the ring's start.
                runs -= 1;
            }
            if runs > 1 {
                for &e in group {
                    let (i, off) = self.on_node[e];
                    self.points[i] = off;
                }
            }
            start = end;
        }
        let points = &self.points;
        self.on_node.retain(|&(i, off)| points[i] != off);
    }

    /// Records the crossing `p` of the entry edge of the cell at `at`.
    #[inline]
    fn push(&mut self, p: Vec2, at: &Step) {
        self.points.push(p);
        if self.crossed == self.verticals.len() {
            self.verticals.resize(2 * self.crossed, (0, 0));
        }
        // The right (1) or left (3) edge is vertical, from row `cj` up.
        self.verticals[self.crossed] = (at.corner(0).0, at.cj);
        self.crossed += at.k & 1;
    }
}
