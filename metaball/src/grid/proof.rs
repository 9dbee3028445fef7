//! Proving that every sample of a block reaches a level, without sampling it.

use glam::Vec4;

use super::candidates::BIT_WORDS;
use super::factor_cache::FactorCache;
use super::tile::{TILE, TileLanes, exponents};
use super::{Core, Entry};
use crate::math;

impl Core<2> {
    /// Whether every sample of the `cols × rows` block (as [`sample_block`](Core::sample_block)
    /// or [`value`](Core::value) computes it) is provably at least `level`: the sum over the
    /// balls whose cutoff covers the whole block of each one's smallest contribution there (at
    /// the block's farthest corner from it), less a slack for rounding, reaches `level`.
    /// `false` when unsure; never `true` wrongly.
    ///
    /// Rounding is monotonic, so a sample's computed squared distance to a ball is at most the
    /// corner's; the terms and sums a sample computes differ from the exact ones by at most a
    /// few `1e-7` relative per term plus `n ε` over `n` terms, all covered by the slack (the
    /// bound is summed in `f64`). Contributions are never negative, so balls left out only
    /// lower the bound.
    pub(crate) fn block_at_least(
        &self,
        origin: [f32; 2],
        step: f32,
        cols: usize,
        rows: usize,
        level: f32,
    ) -> bool {
        if cols == 0 || rows == 0 {
            // No samples.
            return true;
        }
        let far = [
            origin[0] + step * (cols - 1) as f32,
            origin[1] + step * (rows - 1) as f32,
        ];
        let target = self.proof_target(level);
        let mut sum = 0.0f64;
        let mut add = |ball: &Entry<2>| {
            let dx = (origin[0] - ball.center[0])
                .abs()
                .max((far[0] - ball.center[0]).abs());
            let dy = (origin[1] - ball.center[1])
                .abs()
                .max((far[1] - ball.center[1]).abs());
            let d2 = dx * dx + dy * dy;
            if d2 < ball.cutoff_d2 {
                let q = d2 * ball.inv_r2;
                sum += f64::from(match self.separable {
                    Some((scale, a)) => scale * math::exp_nonpositive(-a * q),
                    None => self.kernel.value(q),
                });
            }
            sum >= target
        };
        let mut seen = [0u64; BIT_WORDS];
        match self.bit_candidates(origin, far, &mut seen) {
            Some(mut balls) => balls.any(&mut add),
            // Every ball: a superset of the candidates.
            None => self.balls.iter().any(add),
        }
    }

    /// What a block proof's sum of smallest contributions must reach for every sample to be
    /// at least `level`: `level` over one less the slack for the samples' rounding (`1e-5`,
    /// plus `ε` per ball, plus `8 L 2⁻²⁴` for the rounding of the terms' exponents, `L` the
    /// largest: a sample's and the corner's exponent, each rounded within `4 L 2⁻²⁴`, move
    /// the term by up to `e^{8 L 2⁻²⁴}`, beyond `1e-5` for a steep falloff with `L` past 20;
    /// see [`sample_error_bound`](super::sample_error_bound)).
    fn proof_target(&self, level: f32) -> f64 {
        let exponents = 8.0 * f64::from(self.cutoff_exponent) / f64::from(1u32 << 24);
        let slack = 1e-5 + exponents + (self.balls.len() as f64 + 8.0) * f64::from(f32::EPSILON);
        f64::from(level) / (1.0 - slack)
    }

    /// [`block_at_least`](Core::block_at_least) for an 8 × 8 block through a factor cache:
    /// each ball whose cutoff covers every sample adds the least of its 8 row factors (kept
    /// scaled) times the least of its 8 column factors — the factors the block's samples take,
    /// from `cache` or computed and remembered as
    /// [`sample_tile_cached`](Core::sample_tile_cached) does — less the same slack. A sample
    /// adds the rounded product of its row's and column's factors for each such ball (no
    /// less than the rounded product of the least ones) and never less than 0 for the others.
    /// Other blocks, and falloffs without the separable form, go to `block_at_least`.
    pub(crate) fn block_at_least_cached(
        &self,
        cache: &mut FactorCache,
        origin: [f32; 2],
        step: f32,
        level: f32,
    ) -> bool {
        let far = [origin[0] + step * 7.0, origin[1] + step * 7.0];
        let mut seen = [0u64; BIT_WORDS];
        let (Some((scale, sharpness)), Some(balls)) =
            (self.separable, self.bit_candidates(origin, far, &mut seen))
        else {
            return self.block_at_least(origin, step, TILE, TILE, level);
        };
        cache.prepare(self.balls.len(), step);
        let lanes = TileLanes::new(origin, step, TILE, TILE);
        let minus_sharpness = Vec4::splat(-sharpness);
        let keys = [
            cache.slot_base(0, lanes.first[0]),
            cache.slot_base(1, lanes.first[1]),
        ];
        let target = self.proof_target(level);
        let mut sum = 0.0f64;
        for ball in balls {
            let Some((dx2, dy2, false)) = lanes.reach(ball) else {
                continue;
            };
            let factors = |d2: [Vec4; 2]| -> [f32; TILE] {
                let mut lanes = [0.0f32; TILE];
                exponents(&mut lanes, d2, minus_sharpness, ball.inv_r2);
                for lane in &mut lanes {
                    *lane = math::exp_nonpositive_floored(*lane);
                }
                lanes
            };
            let index = ball.index as usize;
            let columns = cache.get_or_insert(keys[0], index, || factors(dx2));
            let rows = cache.get_or_insert(keys[1], index, || {
                let mut rows = factors(dy2);
                for row in &mut rows {
                    *row *= scale;
                }
                rows
            });
            let least = |f: [f32; TILE]| {
                let m = Vec4::from_slice(&f[..4]).min(Vec4::from_slice(&f[4..]));
                m.min_element()
            };
            sum += f64::from(least(rows) * least(columns));
            if sum >= target {
                return true;
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::super::test_support::*;
    use super::*;
    use crate::Falloff;

    /// `block_at_least` is never wrong: whenever it proves a level, every sample of the block
    /// (block sampler and point queries alike) reaches it, up to levels a hair under the
    /// smallest sample; and it does prove levels comfortably below the smallest sample.
    #[test]
    fn block_bounds_never_claim_too_much() {
        let (mut proven, mut proven_cached) = (0, 0);
        for (count, spread) in [(1, 10.0), (12, 60.0), (60, 200.0), (300, 400.0)] {
            let balls = scattered(count, spread);
            for falloff in [Falloff::SEED, Falloff::BLINN, Falloff::WYVILL] {
                let core = Core::<2>::build(&balls, falloff.kernel(), 1e-4, None);
                // Shared by the blocks of one field, as a `BlockSampler` keeps it.
                let mut cache = FactorCache::default();
                for i in 0..200 {
                    let a = i as f32;
                    let origin = [
                        ((a * 0.377).fract() - 0.5) * spread * 0.8,
                        ((a * 0.291).fract() - 0.5) * spread * 0.8,
                    ];
                    let step = [0.3, 1.0, 2.39][i % 3];
                    let size = [[8, 8], [5, 8], [8, 3], [1, 1]][i / 3 % 4];
                    let mut block = vec![0.0f32; size[0] * size[1]];
                    core.sample_block(origin, step, size[0], size[1], &mut block, None);
                    let mut min = block.iter().copied().fold(f32::INFINITY, f32::min);
                    for n in 0..block.len() {
                        let p = [
                            origin[0] + step * (n % size[0]) as f32,
                            origin[1] + step * (n / size[0]) as f32,
                        ];
                        min = min.min(core.value(p));
                    }
                    let above = f32::from_bits(min.to_bits() + 1);
                    for level in [0.5 * min, min * (1.0 - 1e-4), min, above] {
                        let at = (count, falloff, i, level, min);
                        if core.block_at_least(origin, step, size[0], size[1], level) {
                            assert!(min >= level, "{at:?}");
                        }
                        if size == [8, 8]
                            && core.block_at_least_cached(&mut cache, origin, step, level)
                        {
                            assert!(min >= level, "cached {at:?}");
                            proven_cached += usize::from(level == 0.5 * min && min > 0.0);
                        }
                    }
                    if min > 0.0 && core.block_at_least(origin, step, size[0], size[1], 0.5 * min) {
                        proven += 1;
                    }
                }
            }
        }
        assert!(proven > 500, "{proven}");
        assert!(proven_cached > 100, "{proven_cached}");
        // No samples: any level holds.
        let core = Core::<2>::build(&scattered(3, 10.0), Falloff::SEED.kernel(), 1e-4, None);
        assert!(core.block_at_least([0.0; 2], 1.0, 0, 8, 1e30));
    }
}
