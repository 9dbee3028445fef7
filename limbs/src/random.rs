//! Draws from the caller's generator. Every draw takes exactly one `next_u32`, so the sequence
//! of draws (documented on [`plan`](crate::plan)) fixes the output for a given generator.

use rand_core::Rng;

/// Uniform in `[0, 1)`, 24 bits.
pub(crate) fn unit<R: Rng + ?Sized>(rng: &mut R) -> f32 {
    (rng.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Uniform in `[lo, hi]` (returns `lo` when `hi <= lo`).
pub(crate) fn between<R: Rng + ?Sized>(rng: &mut R, [lo, hi]: [f32; 2]) -> f32 {
    let t = unit(rng);
    if hi > lo { lo + (hi - lo) * t } else { lo }
}

/// Uniform integer in `0..n` (0 when `n == 0`), by multiply-shift.
pub(crate) fn below<R: Rng + ?Sized>(rng: &mut R, n: usize) -> usize {
    let x = u64::from(rng.next_u32());
    ((x * n as u64) >> 32) as usize
}

/// Uniform integer in `[lo, hi]`.
pub(crate) fn count<R: Rng + ?Sized>(rng: &mut R, [lo, hi]: [usize; 2]) -> usize {
    lo + below(rng, hi.saturating_sub(lo) + 1)
}

/// A fair coin.
pub(crate) fn coin<R: Rng + ?Sized>(rng: &mut R) -> bool {
    rng.next_u32() >> 31 == 1
}

#[cfg(test)]
pub(crate) mod tests {
    use core::convert::Infallible;

    use rand_core::TryRng;

    use super::*;

    /// SplitMix64, for unit tests.
    pub(crate) struct SplitMix(pub(crate) u64);

    impl TryRng for SplitMix {
        type Error = Infallible;
        fn try_next_u32(&mut self) -> Result<u32, Infallible> {
            Ok((self.try_next_u64()? >> 32) as u32)
        }
        fn try_next_u64(&mut self) -> Result<u64, Infallible> {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            Ok(z ^ (z >> 31))
        }
        fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
            for chunk in dst.chunks_mut(8) {
                let bytes = self.try_next_u64()?.to_le_bytes();
                chunk.copy_from_slice(&bytes[..chunk.len()]);
            }
            Ok(())
        }
    }

    #[test]
    fn draws_stay_in_range() {
        let mut rng = SplitMix(7);
        for _ in 0..1000 {
            let u = unit(&mut rng);
            assert!((0.0..1.0).contains(&u));
            assert!(below(&mut rng, 5) < 5);
            let c = count(&mut rng, [1, 8]);
            assert!((1..=8).contains(&c));
            let b = between(&mut rng, [2.0, 3.0]);
            assert!((2.0..=3.0).contains(&b));
        }
        assert_eq!(below(&mut rng, 0), 0);
    }
}
