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
mod tests {
    use super::*;
    use crate::split_mix::SplitMix;

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
