//! Node samples on first use, through the tile store: point by point, or a tile at a time.

use super::Tracer;
use super::nodes::{Nodes, TILE_MASK, TILE_SHIFT};
use crate::cell;
use crate::tile::{TileField, node_point};

impl<F: TileField + ?Sized> Tracer<'_, F> {
    /// The sample at node `(i, j)`, taken on first use: the node alone, or (tiled) the whole
    /// tile holding it, when its tile is first touched.
    #[inline(always)]
    pub(super) fn node(&mut self, i: i32, j: i32) -> f32 {
        let tile = self.tile(i, j);
        let slot = Nodes::slot(i, j);
        match self.nodes.sample(tile, slot) {
            Some(v) => v,
            None => self.sample_node(tile, slot, i, j),
        }
    }

    /// Samples node `(i, j)`, in `slot` of `tile`: alone (point by point), or, tiled, with
    /// the rest of its tile (one proven inside and left unsampled so far).
    #[inline]
    fn sample_node(&mut self, tile: usize, slot: usize, i: i32, j: i32) -> f32 {
        if self.tiled {
            let first = [i & !TILE_MASK, j & !TILE_MASK];
            let (field, step, iso) = (self.field, self.step, self.iso);
            self.nodes
                .fill(tile, iso, |out| field.sample_tile(first, step, out));
            return self.nodes.sampled(tile, slot);
        }
        let v = self.field.value(node_point([i, j], self.step));
        self.nodes.set(tile, slot, v, cell::is_inside(v, self.iso));
        v
    }

    /// The index of the tile holding node `(i, j)`: from the tile cache, else found or
    /// created (and, tiled, filled) by [`Tracer::tile_miss`].
    #[inline(always)]
    pub(super) fn tile(&mut self, i: i32, j: i32) -> usize {
        self.lookup_tile(i, j, false)
    }

    /// The tile holding node `(i, j)`, for its inside flags only: as [`Tracer::tile`], but
    /// a new tile the field proves inside is not sampled.
    #[inline(always)]
    pub(super) fn flag_tile(&mut self, i: i32, j: i32) -> usize {
        self.lookup_tile(i, j, true)
    }

    /// [`Tracer::tile`] (`flags` false) or [`Tracer::flag_tile`] (true).
    #[inline(always)]
    fn lookup_tile(&mut self, i: i32, j: i32, flags: bool) -> usize {
        let key = (i >> TILE_SHIFT, j >> TILE_SHIFT);
        match self.nodes.cached(key) {
            Some(tile) => tile,
            None => self.tile_miss(key, flags),
        }
    }

    /// The tile at tile coordinates `key`, past the cache: found or created. A new tile is
    /// filled when the tracer samples by tiles, unless only its inside flags are needed
    /// (`flags`) and the field proves it inside ([`TileField::tile_inside`]): then it is left
    /// unsampled.
    #[inline(never)]
    fn tile_miss(&mut self, key: (i32, i32), flags: bool) -> usize {
        let (tile, created) = self.nodes.find_or_add(key);
        if created && self.tiled {
            let first = [key.0 << TILE_SHIFT, key.1 << TILE_SHIFT];
            let (field, step, iso) = (self.field, self.step, self.iso);
            if flags && field.tile_inside(first, step, iso) {
                self.nodes.prove_inside(tile);
            } else {
                self.nodes
                    .fill(tile, iso, |out| field.sample_tile(first, step, out));
            }
        }
        tile
    }

    /// Whether node `(i, j)` is inside: from its tile's flags when known (sampled, or proven),
    /// else from its sample.
    #[inline]
    pub(super) fn inside(&mut self, i: i32, j: i32) -> bool {
        let tile = self.flag_tile(i, j);
        let slot = Nodes::slot(i, j);
        match self.nodes.known_inside(tile, slot) {
            Some(inside) => inside,
            None => cell::is_inside(self.sample_node(tile, slot, i, j), self.iso),
        }
    }
}
