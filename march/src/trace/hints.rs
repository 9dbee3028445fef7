//! Step 1: from each hint to the outline of its component (unless one is traced already).

use glam::Vec2;

use super::{Table, Tracer};
use crate::MarchError;
use crate::cell::{self, CORNERS};
use crate::tile::TileField;

impl<F: TileField + ?Sized> Tracer<'_, F> {
    /// Whether grid node `(x, y)` is already known to be inside a traced component: the
    /// innermost traced ring enclosing it is an outer ring. Exact (crossing parity), no
    /// sampling.
    fn covered(&self, x: i32, y: i32) -> bool {
        let p = Vec2::new(x as f32, y as f32) * self.step;
        let mut best: Option<(bool, f32)> = None;
        for ring in &self.rings {
            if p.cmplt(ring.lo).any() || p.cmpgt(ring.hi).any() {
                continue;
            }
            let size = (ring.hi - ring.lo).element_product();
            if best.is_some_and(|(_, s)| s <= size) {
                continue;
            }
            if ring.encloses(x, y) {
                best = Some((ring.outer, size));
            }
        }
        best.is_some_and(|(outer, _)| outer)
    }

    /// The ring crossing the vertical edge from node `(x, y)` up, if any.
    fn crossing_ring(&mut self, x: i32, y: i32) -> Option<usize> {
        if !self.nodes.crossed(x, y) {
            return None;
        }
        let rings = &self.rings;
        let table = self.ring_of_edge.get_or_insert_with(|| {
            let edges = rings.iter().map(|r| r.verticals.len()).sum::<usize>();
            let mut table = Table::with_slots((2 * edges + 16).next_power_of_two());
            for (id, r) in rings.iter().enumerate() {
                for &edge in &r.verticals {
                    table.insert(edge, id as u32);
                }
            }
            table
        });
        table.get((x, y)).map(|r| r as usize)
    }

    pub(super) fn outline_hint(&mut self, index: usize, hint: Vec2) -> Result<(), MarchError> {
        // The corners of the cell holding the hint, nearest first.
        let g = hint / self.step;
        // `floor` by truncation (exact: hints lie within `MAX_GRID_COORDINATE` steps, where
        // `f32` holds every integer), not a library call on targets without SSE4.1.
        let floor = |v: f32| {
            let t = v as i32;
            if t as f32 > v { t - 1 } else { t }
        };
        let base = (floor(g.x), floor(g.y));
        let mut corners = CORNERS.map(|(di, dj)| {
            let (i, j) = (base.0 + di, base.1 + dj);
            (Vec2::new(i as f32, j as f32).distance_squared(g), (i, j))
        });
        // Already outlined: the nearest node (the first of the nearest, in corner order) lies
        // in a traced component (what the walk below would find, without sampling).
        let nearest = corners[1..]
            .iter()
            .fold(
                corners[0],
                |a, &b| if b.0.total_cmp(&a.0).is_lt() { b } else { a },
            )
            .1;
        if self.covered(nearest.0, nearest.1) {
            return Ok(());
        }
        // A stable insertion sort of four: ties keep the corner order.
        for n in 1..corners.len() {
            let mut m = n;
            while m > 0 && corners[m].0.total_cmp(&corners[m - 1].0).is_lt() {
                corners.swap(m, m - 1);
                m -= 1;
            }
        }
        let corners = corners.map(|(_, c)| c);
        if !cell::is_inside(self.field.value(hint), self.iso) {
            return Ok(());
        }
        let mut start = None;
        for (i, j) in corners {
            if self.inside(i, j) {
                start = Some((i, j));
                break;
            }
        }
        let Some((x, y0)) = start else {
            return Ok(());
        };
        // Walk up the column, tracing every crossing not traced yet, until an outer ring
        // enclosing the start node turns up.
        let mut y = y0;
        let mut below = true;
        loop {
            self.tick(index)?;
            let above = self.inside(x, y + 1);
            if above != below {
                let ring = match self.crossing_ring(x, y) {
                    Some(r) => r,
                    None if below => self.trace_ring((x - 1, y), 1, index, false)?,
                    None => self.trace_ring((x, y), 3, index, false)?,
                };
                let ring = &self.rings[ring];
                if ring.outer && ring.encloses(x, y0) {
                    return Ok(());
                }
            }
            below = above;
            y += 1;
        }
    }
}
