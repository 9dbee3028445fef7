//! Fields that [`trace_field`](crate::trace_field) can sample a whole tile of grid nodes at a
//! time.

use glam::Vec2;

/// Side of the tracer's node tiles: a tile holds `TILE_SIZE × TILE_SIZE` grid nodes.
pub const TILE_SIZE: usize = 8;

/// Nodes in one tile: `TILE_SIZE × TILE_SIZE` = 64.
pub const TILE_NODES: usize = TILE_SIZE * TILE_SIZE;

/// The world point of grid node `[i, j]` for grid spacing `step`: `step × (i, j)`, computed
/// as `Vec2::new(i as f32, j as f32) * step`, the exact expression the tracer uses for every
/// node (so a field sampled here sees the same bits the tracer would pass it).
///
/// ```
/// use creature_march::{glam::Vec2, node_point};
///
/// assert_eq!(node_point([-3, 5], 0.5), Vec2::new(-1.5, 2.5));
/// ```
#[must_use]
#[inline]
pub fn node_point([i, j]: [i32; 2], step: f32) -> Vec2 {
    Vec2::new(i as f32, j as f32) * step
}

/// A scalar field that the contour tracer ([`trace_field`](crate::trace_field)) reads, either
/// point by point ([`value`](Self::value)) or a tile of `8 × 8` grid nodes at a time
/// ([`sample_tile`](Self::sample_tile)).
///
/// Every `Fn(Vec2) -> f32` is a `TileField` (point by point), so closures work unchanged. A
/// field that can fill a block of samples for much less than one [`value`](Self::value) call
/// per node — a metaball field that splits each Gaussian into row and column factors, a
/// lookup into a sampled image, a SIMD evaluator — implements this trait on its own type,
/// overrides [`sample_tile`](Self::sample_tile) and returns `true` from
/// [`prefers_tiles`](Self::prefers_tiles): the tracer then fills each tile it touches with one
/// `sample_tile` call instead of sampling the tile's nodes one by one as it needs them.
///
/// The tracer samples tile by tile only with `prefers_tiles() == true`, because a tile holds
/// 64 nodes while the outline through it typically needs a dozen of them: for a field whose
/// tile costs 64 `value` calls (the default [`sample_tile`](Self::sample_tile)), point by point
/// is cheaper.
///
/// Inside means `value >= iso`; NaN samples are outside, as everywhere in this crate.
///
/// # Example: a field that fills tiles cheaply
///
/// ```
/// use creature_march::{
///     glam::Vec2, node_point, trace, trace_field, MarchOptions, TileField, TILE_NODES, TILE_SIZE,
/// };
///
/// /// A disc of radius 10 whose tiles are filled row by row.
/// struct Disc;
///
/// impl TileField for Disc {
///     fn value(&self, p: Vec2) -> f32 {
///         100.0 - p.length_squared()
///     }
///     fn prefers_tiles(&self) -> bool {
///         true
///     }
///     fn sample_tile(&self, [i, j]: [i32; 2], step: f32, out: &mut [f32; TILE_NODES]) {
///         for (row, samples) in out.chunks_exact_mut(TILE_SIZE).enumerate() {
///             let y = node_point([i, j + row as i32], step).y;
///             for (col, sample) in samples.iter_mut().enumerate() {
///                 let x = node_point([i + col as i32, j], step).x;
///                 *sample = 100.0 - (x * x + y * y);
///             }
///         }
///     }
/// }
///
/// let tiled = trace_field(&Disc, &[Vec2::ZERO], 1.0, 0.0, &MarchOptions::DEFAULT)?;
/// let pointwise = trace(|p: Vec2| 100.0 - p.length_squared(), &[Vec2::ZERO], 1.0, 0.0)?;
/// assert_eq!(tiled.len(), 1);
/// assert_eq!(tiled[0].points.len(), pointwise[0].points.len());
/// # Ok::<(), creature_march::MarchError>(())
/// ```
///
/// A newtype wires in a field from another crate, for instance a `creature-metaball`
/// `Field2`, whose `BlockSampler` fills a block with its separable fast path, reusing each
/// ball's row and column factors between tiles (so it keeps state: a `RefCell`, one per trace):
///
/// ```ignore
/// struct Tiled<'a>(RefCell<creature_metaball::BlockSampler<'a>>);
///
/// impl TileField for Tiled<'_> {
///     fn value(&self, p: Vec2) -> f32 { self.0.borrow().field().value(p) }
///     fn prefers_tiles(&self) -> bool { true }
///     fn sample_tile(&self, first: [i32; 2], step: f32, out: &mut [f32; TILE_NODES]) {
///         let origin = node_point(first, step);
///         let ok = self.0.borrow_mut().sample_block(origin, step, TILE_SIZE, TILE_SIZE, out);
///         if ok.is_err() { out.fill(f32::NAN) } // only for a non-finite point: outside
///     }
/// }
/// ```
pub trait TileField {
    /// The field at `p`. The tracer calls it for points that are not grid nodes (hints, saddle
    /// cell centres, refinement steps), and for every node when
    /// [`prefers_tiles`](Self::prefers_tiles) is `false`.
    fn value(&self, p: Vec2) -> f32;

    /// Whether the tracer should fill each tile it touches with one
    /// [`sample_tile`](Self::sample_tile) call (`true`) rather than sample its nodes one by one
    /// with [`value`](Self::value) as it needs them (`false`, the default). Return `true` only
    /// when `sample_tile` costs well under [`TILE_NODES`] `value` calls.
    fn prefers_tiles(&self) -> bool {
        false
    }

    /// Whether every node of the tile whose first node is `first` (as in
    /// [`sample_tile`](Self::sample_tile)) is certainly inside: its sample at least `iso`.
    /// Return `true` only when sure — a wrong `true` puts the outline in the wrong place —
    /// and `false` when unsure (the default).
    ///
    /// The tracer asks (for fields that [prefer tiles](Self::prefers_tiles)) before it fills
    /// a new tile whose inside flags alone it needs — the walk from a hint up to its outline,
    /// and the hole scan, which reads every node a ring encloses — and leaves a tile proven
    /// inside unsampled until a sample of it is needed (then it fills the whole tile as
    /// usual, so the rings are the same bit for bit). The hole scan does not ask about a tile
    /// just above one holding an outside node: the field dips below the level there, where
    /// a bound over a whole tile seldom holds, so it fills that tile at once. Worth overriding
    /// when a proof costs much less than a tile: a metaball field proves it from each nearby
    /// ball's smallest contribution over the tile, with one `exp` a ball (or none, from the
    /// factors a `BlockSampler` keeps).
    fn tile_inside(&self, first: [i32; 2], step: f32, iso: f32) -> bool {
        let _ = (first, step, iso);
        false
    }

    /// Fills `out` with the field on the tile of grid nodes whose first (lowest `x`, lowest
    /// `y`) node is `first = [i, j]`: `out[row * TILE_SIZE + col]` is the field at grid node
    /// `[i + col, j + row]`, whose world point is
    /// [`node_point([i + col, j + row], step)`](node_point) — rows of constant `y`, `x`
    /// fastest, `y` up. The tracer passes tiles aligned to multiples of [`TILE_SIZE`].
    ///
    /// The default calls [`value`](Self::value) at each node's [`node_point`], so its samples
    /// are bit for bit those of point-by-point sampling. An override may differ from `value`
    /// by rounding (the tracer then uses the tile's values for the nodes, and `value` only
    /// for points between nodes); it should write every entry.
    fn sample_tile(&self, first: [i32; 2], step: f32, out: &mut [f32; TILE_NODES]) {
        let [i, j] = first;
        for (row, samples) in out.chunks_exact_mut(TILE_SIZE).enumerate() {
            for (col, sample) in samples.iter_mut().enumerate() {
                // Tiles hold 8 × 8 nodes: the offsets fit in i32.
                let node = [i.wrapping_add(col as i32), j.wrapping_add(row as i32)];
                *sample = self.value(node_point(node, step));
            }
        }
    }
}

/// Every closure or function `Fn(Vec2) -> f32` is a point-by-point field.
impl<F: Fn(Vec2) -> f32> TileField for F {
    #[inline]
    fn value(&self, p: Vec2) -> f32 {
        self(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_tiles_are_rows_of_node_values() {
        let field = |p: Vec2| p.x * 1000.0 + p.y;
        assert!(!field.prefers_tiles());
        let mut out = [f32::NAN; TILE_NODES];
        field.sample_tile([-8, 16], 0.5, &mut out);
        for row in 0..TILE_SIZE {
            for col in 0..TILE_SIZE {
                let node = (-8 + col as i32, 16 + row as i32);
                let p = Vec2::new(node.0 as f32, node.1 as f32) * 0.5;
                assert_eq!(out[row * TILE_SIZE + col].to_bits(), field(p).to_bits());
            }
        }
        assert_eq!(out[0], -4000.0 + 8.0);
        assert_eq!(out[TILE_SIZE], -4000.0 + 8.5);
        assert_eq!(out[1], -3500.0 + 8.0);
    }
}
