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
