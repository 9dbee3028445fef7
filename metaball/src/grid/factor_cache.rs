//! The row and column factors of 8 × 8 tiles, kept per ball between tiles for one grid
//! spacing: what a `BlockSampler` remembers.

use alloc::vec::Vec;

use super::tile::TILE;

/// Slots per ball and axis in a [`FactorCache`]: blocks whose first column (row) lies in the
/// same `8 × step` band modulo this many bands share a slot.
const CACHE_WAYS: usize = 16;

/// Factor rows a [`FactorCache`] makes room for per ball at first.
const FACTORS_PER_BALL: usize = 16;

/// The tag of an empty [`FactorCache`] slot: a NaN, which no block's (finite) first column or
/// row has.
const EMPTY_TAG: u32 = 0x7fc0_0001;

/// Row and column factors of 8 × 8 blocks, remembered per ball and per first column (row) for
/// one grid spacing: what `BlockSampler` keeps between blocks. (Row factors are kept
/// multiplied by the kernel's scale: see [`Core::sample_tile_cached`].)
#[derive(Debug, Clone, Default)]
pub(crate) struct FactorCache {
    /// The bits of the spacing the factors are for.
    step: u32,
    /// `1 / (8 × step)`: a coordinate's band.
    inv_band: f32,
    /// Per ball, per axis, per slot: the bits of the first coordinate whose factors the slot
    /// holds (or [`EMPTY_TAG`]), and where in `factors` they are.
    slots: Vec<(u32, u32)>,
    /// Factors, in the order slots were first filled (so a cache only touches, and zeroes,
    /// the memory it uses).
    factors: Vec<[f32; TILE]>,
    /// Lookups answered from the cache.
    #[cfg(test)]
    pub(super) hits: usize,
}

impl FactorCache {
    /// Empties the cache unless it is sized for `balls` and holds factors for `step`.
    #[inline]
    pub(super) fn prepare(&mut self, balls: usize, step: f32) {
        let slots = balls * 2 * CACHE_WAYS;
        if self.slots.len() != slots || self.step != step.to_bits() {
            self.slots.clear();
            self.slots.resize(slots, (EMPTY_TAG, 0));
            self.factors.clear();
            // Room for a typical trace's rows and columns (about ten per ball), so that the
            // factors rarely move as they grow.
            self.factors.reserve(balls * FACTORS_PER_BALL);
            self.step = step.to_bits();
            self.inv_band = 1.0 / (TILE as f32 * step);
        }
    }

    /// Where the factors of the row (`axis` 1) or column (`axis` 0) band starting at `first`
    /// live, for ball 0, and the tag they carry.
    #[inline]
    pub(super) fn slot_base(&self, axis: usize, first: f32) -> (usize, u32) {
        // A saturating cast: any deterministic slot will do.
        let band = (first * self.inv_band) as i32 as usize & (CACHE_WAYS - 1);
        (axis * CACHE_WAYS + band, first.to_bits())
    }

    /// Ball `ball`'s factors under `key`, computed by `compute` and remembered on a miss.
    #[inline]
    pub(super) fn get_or_insert(
        &mut self,
        (base, tag): (usize, u32),
        ball: usize,
        compute: impl FnOnce() -> [f32; TILE],
    ) -> [f32; TILE] {
        // `prepare` made room for every ball, both axes and every way.
        let slot = &mut self.slots[ball * 2 * CACHE_WAYS + base];
        // A finite coordinate's tag is never `EMPTY_TAG`: a matching slot holds factors.
        if slot.0 == tag {
            let factors = self.factors[slot.1 as usize];
            #[cfg(test)]
            {
                self.hits += 1;
            }
            return factors;
        }
        let factors = compute();
        if slot.0 == EMPTY_TAG {
            let Ok(row) = u32::try_from(self.factors.len()) else {
                return factors;
            };
            self.factors.push(factors);
            *slot = (tag, row);
        } else {
            self.factors[slot.1 as usize] = factors;
            slot.0 = tag;
        }
        factors
    }
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::super::Core;
    use super::super::test_support::*;
    use super::*;
    use crate::Falloff;

    /// A factor cache shared by many tiles (a walk over neighbouring tiles that revisits
    /// rows and columns, changes spacing mid-way, mixes in short blocks and every candidate
    /// path) gives the same bits as sampling each tile afresh, and actually hits.
    #[test]
    fn cached_factors_give_the_same_tiles_bit_for_bit() {
        let mut hits = 0;
        // One word of candidate bits per cell, three, and none (over 256 balls).
        for (count, spread) in [(12, 60.0), (60, 200.0), (150, 300.0), (300, 400.0)] {
            let balls = scattered(count, spread);
            for falloff in [Falloff::SEED, Falloff::BLINN, Falloff::WYVILL] {
                for cell_size in [None, Some(4.0), Some(1e3)] {
                    let core = Core::<2>::build(&balls, falloff.kernel(), 1e-4, cell_size);
                    let mut cache = FactorCache::default();
                    let mut state = 0x2545_f491_u32;
                    let (mut i, mut j) = (0i32, 0i32);
                    for n in 0..300 {
                        state ^= state << 13;
                        state ^= state >> 17;
                        state ^= state << 5;
                        // A random walk of tiles, like a contour's.
                        match state % 4 {
                            0 => i += 1,
                            1 => i -= 1,
                            2 => j += 1,
                            _ => j -= 1,
                        }
                        let step = if n < 150 { 2.39 } else { 0.7 };
                        let size = match state / 4 % 8 {
                            0 => [5, 8],
                            1 => [8, 3],
                            _ => [8, 8],
                        };
                        let origin = [8.0 * step * i as f32, 8.0 * step * j as f32];
                        let origin = [origin[0] - spread * 0.3, origin[1] - spread * 0.2];
                        let mut fresh = vec![f32::NAN; size[0] * size[1]];
                        let mut cached = fresh.clone();
                        core.sample_block(origin, step, size[0], size[1], &mut fresh, None);
                        let cache = Some(&mut cache);
                        core.sample_block(origin, step, size[0], size[1], &mut cached, cache);
                        for (k, (a, b)) in fresh.iter().zip(&cached).enumerate() {
                            let at = (count, falloff, cell_size, n, k);
                            assert_eq!(a.to_bits(), b.to_bits(), "{at:?}: {a} vs {b}");
                        }
                    }
                    if core.separable.is_some() {
                        assert!(cache.hits > 100, "{}", cache.hits);
                    }
                    hits += cache.hits;
                }
            }
        }
        assert!(hits > 10_000, "{hits}");
    }
}
