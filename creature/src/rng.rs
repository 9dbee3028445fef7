//! The one random-number source of both generators: `Pcg64Mcg` seeded from the caller's seed,
//! and the uniform draws every stage takes from it.

use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// A uniform draw in `[0, 1)` with 24 random bits (exact in `f32`).
pub(crate) fn uniform(rng: &mut impl Rng) -> f32 {
    (rng.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The generator [`generate`](crate::generate) and [`generate_2d`](crate::generate_2d) use for `seed`: `Pcg64Mcg` seeded with
/// `rand_core`'s `seed_from_u64`.
#[must_use]
pub(crate) fn rng_for(seed: u64) -> Pcg64Mcg {
    Pcg64Mcg::seed_from_u64(seed)
}

/// The index at `u` in `[0, 1)` of `weights`' cumulative sum (each finite, not negative, one
/// above 0): index `i` for `u` in its share. Rounding at the top end gives the last index with
/// a weight.
pub(crate) fn pick_weighted(weights: &[f32], u: f32) -> usize {
    let total: f32 = weights.iter().sum();
    let mut left = u * total;
    for (i, &w) in weights.iter().enumerate() {
        if w > 0.0 && left < w {
            return i;
        }
        left -= w;
    }
    weights.iter().rposition(|&w| w > 0.0).unwrap_or(0)
}

/// Checks every one of `weights` is finite and from 0 to 1000, and one is above 0.
///
/// # Errors
/// [`Error::NonFinite`](crate::Error::NonFinite) or
/// [`Error::OutOfRange`](crate::Error::OutOfRange) for a bad weight,
/// [`Error::AllZero`](crate::Error::AllZero) when none is above 0; each naming `what`.
pub(crate) fn check_weights(what: &'static str, weights: &[f32]) -> Result<(), crate::Error> {
    for &w in weights {
        crate::span::scalar(what, w, 0.0, 1000.0)?;
    }
    if weights.iter().all(|&w| w == 0.0) {
        return Err(crate::Error::AllZero { what });
    }
    Ok(())
}
