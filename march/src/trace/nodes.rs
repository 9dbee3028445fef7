//! The node sample store: dense 8 × 8 tiles of samples and inside flags, found through a
//! small direct-mapped cache, then a hash table.

use alloc::vec::Vec;

use super::table::Table;
use crate::tile::TILE_NODES;

/// Side of a node tile: tiles hold `TILE × TILE` nodes.
pub(super) const TILE_SHIFT: i32 = 3;
pub(super) const TILE_MASK: i32 = (1 << TILE_SHIFT) - 1;
const _: () = assert!(TILE_NODES == 1 << (2 * TILE_SHIFT));

/// Bit `s`: `values[s]` is inside `iso` (a NaN is not), four lanes at a time: one compare and
/// its sign mask per four samples. Out of line (once per tile filled): inlined, it slowed the
/// point-by-point walk, which never calls it, by 9% through the code around it.
#[inline(never)]
fn inside_bits(values: &[f32; TILE_NODES], iso: f32) -> u64 {
    let iso = glam::Vec4::splat(iso);
    values
        .chunks_exact(4)
        .enumerate()
        .fold(0, |bits, (k, four)| {
            let inside = glam::Vec4::from_slice(four).cmpge(iso).bitmask();
            bits | u64::from(inside) << (4 * k)
        })
}

/// Bit 0 of each byte of `spread`, gathered into bit `k` for byte `k`: a multiplication
/// whose partial products never overlap, so never carry.
#[inline]
fn gather_bytes(spread: u64) -> u64 {
    (spread & 0x0101_0101_0101_0101).wrapping_mul(0x0102_0408_1020_4080) >> 56
}

/// Column `column` of a tile's bit mask (bit `8 × row + column`), as bit `row` of a byte.
#[inline]
fn column_bits(mask: u64, column: i32) -> u32 {
    gather_bytes(mask >> (column & TILE_MASK)) as u32
}

/// Node samples for an 8 × 8 block of grid nodes.
#[derive(Clone)]
struct Tile {
    values: [f32; TILE_NODES],
    /// Bit `s`: `values[s]` has been sampled.
    sampled: u64,
    /// Bit `s`: the node in slot `s` is inside (known where sampled, or proven).
    inside: u64,
    /// Every bit set when the field proved every node inside without sampling
    /// ([`TileField::tile_inside`]): the inside flags are known, the values not.
    proven: u64,
    /// Bit `s`: a traced ring crosses the edge from the node in slot `s` up to the node above.
    crossed: u64,
}

/// Slots of the tile cache: a tile goes to the slot of the low 2 bits of its column and the
/// low 5 bits of its row, so any block of 4 × 32 neighbouring tiles fits at once: a contour's
/// neighbourhood, and the tiles a hole scan runs up through, column after column.
const CACHE_SLOTS: usize = 128;

/// A sparse grid of node samples in dense tiles: the compact cache behind "each node is
/// sampled once". Contours are local, so lookups mostly hit one of a few neighbouring tiles,
/// which a small direct-mapped cache remembers; other tiles are found through a hash table.
pub(super) struct Nodes {
    tiles: Vec<Tile>,
    index: Table<u32>,
    /// Tile coordinates and index of a recently used tile, by [`Nodes::cache_slot`].
    cache: [(i32, i32, u32); CACHE_SLOTS],
}

impl Nodes {
    pub(super) fn new() -> Self {
        Self {
            // A creature's outline and hole scan touch a couple of hundred tiles: room for
            // 256 before either grows (the table keeps half its slots empty).
            tiles: Vec::with_capacity(256),
            index: Table::with_slots(512),
            // No tile has coordinate `i32::MIN`: node coordinates stay within ±2^30.
            cache: [(i32::MIN, i32::MIN, 0); CACHE_SLOTS],
        }
    }

    #[inline]
    pub(super) fn slot(i: i32, j: i32) -> usize {
        ((j & TILE_MASK) << TILE_SHIFT | (i & TILE_MASK)) as usize
    }

    #[inline]
    fn cache_slot((x, y): (i32, i32)) -> usize {
        ((x & 3) | (y & 31) << 2) as usize
    }

    /// The index of the tile at tile coordinates `key`, if the cache holds it.
    #[inline]
    pub(super) fn cached(&self, key: (i32, i32)) -> Option<usize> {
        let (x, y, tile) = self.cache[Self::cache_slot(key)];
        ((x, y) == key).then_some(tile as usize)
    }

    /// The index of the tile at tile coordinates `key`, created (unsampled) when missing, and
    /// whether it was created. Caches it.
    pub(super) fn find_or_add(&mut self, key: (i32, i32)) -> (usize, bool) {
        let next = self.tiles.len() as u32;
        let (tile, created) = self.index.get_or_insert(key, next);
        if created {
            self.tiles.push(Tile {
                values: [0.0; TILE_NODES],
                sampled: 0,
                inside: 0,
                proven: 0,
                crossed: 0,
            });
        }
        let tile = tile as usize;
        self.cache[Self::cache_slot(key)] = (key.0, key.1, tile as u32);
        (tile, created)
    }

    /// The index of the tile holding node `(i, j)`, if any node of it was touched.
    #[inline]
    pub(super) fn find(&self, i: i32, j: i32) -> Option<usize> {
        let key = (i >> TILE_SHIFT, j >> TILE_SHIFT);
        self.cached(key)
            .or_else(|| self.index.get(key).map(|t| t as usize))
    }

    /// Stores the sample `v` of `slot` of `tile`, inside or not.
    pub(super) fn set(&mut self, tile: usize, slot: usize, v: f32, inside: bool) {
        let t = &mut self.tiles[tile];
        t.values[slot] = v;
        t.sampled |= 1 << slot;
        t.inside |= u64::from(inside) << slot;
    }

    /// The sample in `slot` of `tile`, if it has been taken.
    #[inline(always)]
    pub(super) fn sample(&self, tile: usize, slot: usize) -> Option<f32> {
        let t = &self.tiles[tile];
        (t.sampled & (1 << slot) != 0).then(|| t.values[slot])
    }

    /// Whether the node in `slot` of `tile` is inside, if that is known (sampled, or proven).
    #[inline(always)]
    pub(super) fn known_inside(&self, tile: usize, slot: usize) -> Option<bool> {
        let t = &self.tiles[tile];
        ((t.sampled | t.proven) & (1 << slot) != 0).then_some(t.inside & (1 << slot) != 0)
    }

    /// Fills every sample of `tile` with `fill`, and marks which are inside `iso`.
    pub(super) fn fill(
        &mut self,
        tile: usize,
        iso: f32,
        fill: impl FnOnce(&mut [f32; TILE_NODES]),
    ) {
        let t = &mut self.tiles[tile];
        fill(&mut t.values);
        t.sampled = u64::MAX;
        t.inside = inside_bits(&t.values, iso);
    }

    /// Marks every node of `tile` (unsampled) as proven inside.
    pub(super) fn prove_inside(&mut self, tile: usize) {
        let t = &mut self.tiles[tile];
        t.inside = u64::MAX;
        t.proven = u64::MAX;
    }

    /// The inside flags of `tile` (sampled or proven nodes only), and which of its nodes'
    /// edges up traced rings cross.
    #[inline]
    pub(super) fn flags(&self, tile: usize) -> (u64, u64) {
        let t = &self.tiles[tile];
        (t.inside, t.crossed)
    }

    /// The inside flags of column `column` of `tile`: bit `r` for row `r` (sampled or proven
    /// nodes only).
    #[inline]
    pub(super) fn column_inside(&self, tile: usize, column: i32) -> u32 {
        column_bits(self.tiles[tile].inside, column)
    }

    /// The sample in `slot` of `tile`, which has been taken.
    #[inline]
    pub(super) fn sampled(&self, tile: usize, slot: usize) -> f32 {
        let t = &self.tiles[tile];
        debug_assert!(
            t.sampled & (1 << slot) != 0,
            "slot {slot} of tile {tile} unsampled"
        );
        t.values[slot]
    }

    /// The inside flags of `tile`, if all its nodes are sampled.
    #[inline]
    pub(super) fn all_inside(&self, tile: usize) -> Option<u64> {
        let t = &self.tiles[tile];
        (t.sampled == u64::MAX).then_some(t.inside)
    }

    /// Records that a ring crosses the edges from the nodes of `tile` whose bits are set in
    /// `slots` up.
    #[inline]
    pub(super) fn mark_crossed(&mut self, tile: usize, slots: u64) {
        self.tiles[tile].crossed |= slots;
    }

    /// Whether a traced ring crosses the edge from node `(i, j)` up.
    #[inline]
    pub(super) fn crossed(&self, i: i32, j: i32) -> bool {
        self.find(i, j)
            .is_some_and(|tile| self.tiles[tile].crossed >> Self::slot(i, j) & 1 != 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell;

    #[test]
    fn node_tiles_keep_samples_apart() {
        let mut nodes = Nodes::new();
        let coords = [
            (0, 0),
            (-1, 0),
            (7, 7),
            (8, 7),
            (-8, -9),
            (-9, -8),
            (1000, -1000),
        ];
        for (n, &(i, j)) in coords.iter().enumerate() {
            let (tile, _) = nodes.find_or_add((i >> TILE_SHIFT, j >> TILE_SHIFT));
            // Even samples inside, odd ones outside.
            nodes.set(tile, Nodes::slot(i, j), n as f32, n % 2 == 0);
        }
        for (n, &(i, j)) in coords.iter().enumerate() {
            let tile = nodes.find(i, j).unwrap();
            let slot = Nodes::slot(i, j);
            assert_eq!(nodes.tiles[tile].values[slot], n as f32);
            assert_ne!(nodes.tiles[tile].sampled & 1 << slot, 0);
            let column = nodes.column_inside(tile, i & TILE_MASK);
            assert_eq!(column >> (j & TILE_MASK) & 1, u32::from(n % 2 == 0));
        }
        assert_eq!(nodes.find(1, 8), None);
        assert_eq!(nodes.find(-100, 5), None);
    }

    #[test]
    fn tile_masks_give_rows_and_columns() {
        let mut values = [0.0f32; TILE_NODES];
        // Inside (≥ 0.5): the diagonal, all of row 5, and NaN nowhere.
        for (slot, v) in values.iter_mut().enumerate() {
            let (column, row) = (slot % 8, slot / 8);
            if column == row || row == 5 {
                *v = 1.0;
            }
        }
        values[9] = f32::NAN; // (1, 1): NaN is outside
        values[18] = 0.5; // (2, 2): exactly the iso-level is inside
        let bits = inside_bits(&values, 0.5);
        for (slot, &v) in values.iter().enumerate() {
            assert_eq!(bits >> slot & 1 == 1, cell::is_inside(v, 0.5), "{slot}");
        }
        for column in 0..8 {
            let expected = (0..8)
                .filter(|&row| cell::is_inside(values[row * 8 + column as usize], 0.5))
                .fold(0u32, |b, row| b | 1 << row);
            assert_eq!(column_bits(bits, column), expected, "column {column}");
        }
        assert_eq!(column_bits(u64::MAX, 7), 0xff);
        assert_eq!(column_bits(0x8000_0000_0000_0000, 7), 0x80);
        assert_eq!(column_bits(0x8000_0000_0000_0000, 6), 0);
    }
}
