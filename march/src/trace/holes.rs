//! Step 3: the hole scan, over the nodes each outer ring encloses.

use alloc::vec::Vec;

use super::Tracer;
use super::nodes::{TILE_MASK, TILE_SHIFT};
use super::rings::encloses;
use crate::MarchError;
use crate::sort::sort_unstable_by;
use crate::tile::TileField;

impl<F: TileField + ?Sized> Tracer<'_, F> {
    /// Scans the nodes enclosed by every outer ring not scanned yet, tracing each crossing
    /// that is not part of a known ring.
    pub(super) fn scan_pending(&mut self) -> Result<(), MarchError> {
        while self.scanned < self.rings.len() {
            let r = self.scanned;
            self.scanned += 1;
            if !self.rings[r].outer || self.rings[r].nested {
                continue;
            }
            let verticals = core::mem::take(&mut self.rings[r].verticals);
            let scanned = if self.tiled {
                self.scan_bands(&verticals)
            } else {
                column_pairs(&verticals)
                    .try_for_each(|(x, bottom, top)| self.scan_column(x, bottom, top))
            };
            self.rings[r].verticals = verticals;
            scanned?;
        }
        Ok(())
    }

    /// [`Tracer::scan_column`] for every column pair `verticals` holds (a ring's sorted
    /// vertical crossings), when sampling by tiles: a band of eight columns (a column of
    /// tiles) at a time, each tile of the band at once. The tiles holding the enclosed nodes
    /// are proven or filled, as `scan_column` would; in each, the inside flags of the tile and
    /// of the row below it give every node whose flag differs from the node below's. Those
    /// whose edge no traced ring crosses (few: the ring's own crossings are traced) and whose
    /// two nodes the ring encloses start a ring, in the order `scan_column` meets them (by
    /// column, then row), so the same rings come out in the same order.
    fn scan_bands(&mut self, verticals: &[(i32, i32)]) -> Result<(), MarchError> {
        let mut visit: Vec<u64> = Vec::new();
        let mut starts: Vec<(i32, i32, bool)> = Vec::new();
        let mut rest = verticals;
        while let Some(&(first, _)) = rest.first() {
            let band = first >> TILE_SHIFT;
            // A band holds few crossings: a linear scan.
            let end = rest
                .iter()
                .position(|v| v.0 >> TILE_SHIFT != band)
                .unwrap_or(rest.len());
            let (pairs, next) = rest.split_at(end);
            rest = next;
            // The tile rows holding enclosed nodes with a node above them to check.
            let (mut low, mut high) = (i32::MAX, i32::MIN);
            let mut nodes = 0;
            for (_, bottom, top) in column_pairs(pairs) {
                nodes += (top - bottom - 1).max(0) as usize;
                if top - bottom >= 2 {
                    low = low.min((bottom + 1) >> TILE_SHIFT);
                    high = high.max(top >> TILE_SHIFT);
                }
            }
            self.count_scanned(nodes)?;
            if low > high {
                continue;
            }
            visit.clear();
            visit.resize(((i64::from(high) - i64::from(low)) as usize >> 6) + 1, 0);
            let enclosed =
                column_pairs(pairs)
                    .filter(|p| p.2 - p.1 >= 2)
                    .map(|(_, bottom, top)| {
                        (
                            ((bottom + 1) >> TILE_SHIFT) - low,
                            (top >> TILE_SHIFT) - low,
                        )
                    });
            if let [word] = visit.as_mut_slice() {
                // Up to 64 tile rows (the usual case): the word kept in a register.
                *word = enclosed.fold(0, |bits, (from, to)| bits | bit_range(from, to));
            } else {
                for (from, to) in enclosed {
                    set_bits(&mut visit, from, to);
                }
            }
            starts.clear();
            let x = band << TILE_SHIFT;
            for (word, &bits) in visit.iter().enumerate() {
                let mut bits = bits;
                while bits != 0 {
                    let ty = low + (word << 6) as i32 + bits.trailing_zeros() as i32;
                    bits &= bits - 1;
                    let y = ty << TILE_SHIFT;
                    // Rows 1 to 7 against the row below in the tile; row 0 against the tile
                    // below's row 7, when that tile exists (else its nodes lie outside the
                    // ring, and row 0's edges down cross it: nothing to check).
                    let (below, crossed_below) = self
                        .nodes
                        .find(x, y - 1)
                        .map_or((!0, !0), |t| self.nodes.flags(t));
                    // A new tile just above one holding an outside node is filled without
                    // asking the field to prove it inside: the field dips below the level
                    // within a tile of it, where a bound over the whole tile seldom holds,
                    // and a failed proof costs about half a fill on top of the fill. Either
                    // way the flags are the same.
                    let tile = if below == !0 {
                        self.flag_tile(x, y)
                    } else {
                        self.tile(x, y)
                    };
                    let (inside, crossed) = self.nodes.flags(tile);
                    let row_7 = 8 * TILE_MASK;
                    let changes = inside ^ (inside << 8 | below >> row_7);
                    let crossed = crossed << 8 | crossed_below >> row_7;
                    let mut changes = changes & !crossed;
                    while changes != 0 {
                        let slot = changes.trailing_zeros() as i32;
                        changes &= changes - 1;
                        let node = (x + (slot & TILE_MASK), y + (slot >> TILE_SHIFT));
                        if encloses(pairs, node.0, node.1) && encloses(pairs, node.0, node.1 - 1) {
                            starts.push((node.0, node.1, inside >> slot & 1 != 0));
                        }
                    }
                }
            }
            // `scan_column`'s order: by column, then row.
            sort_unstable_by(&mut starts, &mut Ord::cmp);
            for &(x, up, inside) in &starts {
                self.trace_nested(x, up, inside)?;
            }
        }
        Ok(())
    }

    /// Scans nodes `bottom + 1 ..= top` of column `x` (enclosed by a ring), point by point,
    /// tracing every crossing between two of them that no ring has crossed yet. The nodes
    /// above the first are counted against the budget at once ([`Tracer::count_scanned`]).
    /// Runs a tile's rows at a time: each node is sampled, then the inside flags of the
    /// column's segment come from the tile's mask, and only the rows where the flag changes
    /// are looked at. (Sampling by tiles, [`Tracer::scan_bands`] scans instead.)
    fn scan_column(&mut self, x: i32, bottom: i32, top: i32) -> Result<(), MarchError> {
        self.count_scanned((top - bottom - 1).max(0) as usize)?;
        let mut below = self.inside(x, bottom + 1);
        let mut y = bottom + 1;
        while y < top {
            // Nodes y + 1 ..= last lie in one tile, in rows `first ..= last_row` of it.
            let last = ((y + 1) | TILE_MASK).min(top);
            for up in y + 1..=last {
                self.node(x, up);
            }
            let tile = self.flag_tile(x, y + 1);
            let first = (y + 1) & TILE_MASK;
            let last_row = last & TILE_MASK;
            let rows = (u32::MAX << first) & (u32::MAX >> (31 - last_row));
            // Bit r: the node in row r of the segment is inside.
            let inside = self.nodes.column_inside(tile, x & TILE_MASK) & rows;
            // Bit r: the node below it is inside.
            let previous = (inside << 1) | (u32::from(below) << first);
            let mut changes = (inside ^ previous) & rows;
            let base = (y + 1) & !TILE_MASK;
            while changes != 0 {
                let up = base + changes.trailing_zeros() as i32;
                changes &= changes - 1;
                self.trace_nested(x, up, inside & (1 << (up - base)) != 0)?;
            }
            below = inside & (1 << last_row) != 0;
            y = last;
        }
        Ok(())
    }

    /// Traces the ring crossing the edge from node `(x, up − 1)` to node `(x, up)` (whose
    /// inside flag is `inside`, the other node's the opposite) inside a scanned ring, unless
    /// a traced ring crosses it already. Rings traced during a scan may cross edges the scan
    /// has yet to reach: it asks each time.
    fn trace_nested(&mut self, x: i32, up: i32, inside: bool) -> Result<(), MarchError> {
        if !self.nodes.crossed(x, up - 1) {
            if inside {
                self.trace_ring((x, up - 1), 3, usize::MAX, true)?;
            } else {
                self.trace_ring((x - 1, up - 1), 1, usize::MAX, true)?;
            }
        }
        Ok(())
    }
}

/// The enclosed stretches `(column, bottom, top)` of a ring's sorted vertical crossings: the
/// nodes `bottom + 1 ..= top` of the column lie inside the ring. Crossings come in pairs per
/// column for a closed ring; a pair across two columns (never from a closed ring) is skipped.
fn column_pairs(verticals: &[(i32, i32)]) -> impl Iterator<Item = (i32, i32, i32)> + '_ {
    verticals.chunks_exact(2).filter_map(|pair| match *pair {
        [(x, bottom), (x2, top)] if x == x2 => Some((x, bottom, top)),
        _ => None,
    })
}

/// Bits `from & 63 ..= to & 63` of a word (`from & 63 ≤ to & 63`).
#[inline]
fn bit_range(from: i32, to: i32) -> u64 {
    (u64::MAX << (from & 63)) & (u64::MAX >> (63 - (to & 63)))
}

/// Sets bits `from ..= to` (`0 ≤ from ≤ to`, both within `words`) of the bit set `words`.
#[inline]
fn set_bits(words: &mut [u64], from: i32, to: i32) {
    let (from, to) = (from as usize, to as usize);
    if from >> 6 == to >> 6 {
        words[from >> 6] |= bit_range(from as i32, to as i32);
        return;
    }
    let words = &mut words[from >> 6..=to >> 6];
    let top = words.len() - 1;
    for (k, word) in words.iter_mut().enumerate() {
        let low = if k == 0 { from & 63 } else { 0 };
        let high = if k == top { to & 63 } else { 63 };
        *word |= bit_range(low as i32, high as i32);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_bits_sets_exactly_the_range() {
        for from in 0..200 {
            for to in from..200 {
                let mut words = [0u64; 4];
                set_bits(&mut words, from, to);
                for bit in 0..256 {
                    let set = words[bit / 64] >> (bit % 64) & 1 == 1;
                    assert_eq!(
                        set,
                        (from..=to).contains(&(bit as i32)),
                        "{from}..={to}: {bit}"
                    );
                }
            }
        }
    }
}
