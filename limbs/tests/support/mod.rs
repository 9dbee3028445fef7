//! Helpers shared by the integration tests and the benchmark.
#![allow(dead_code, unreachable_pub)]

pub mod reference;

use core::convert::Infallible;

use creature_limbs::glam::Vec3;
use creature_limbs::rand_core::TryRng;
use creature_limbs::{Body, HeadEnd, LimbKind, Plan, SpineBone};

/// SplitMix64: a tiny deterministic generator for tests.
pub struct SplitMix(pub u64);

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

/// A straight body along +Z: bone `i` at `along = i * spacing` with the given widths and
/// clearances, side sockets at half the width, ground at y = 0.
pub fn straight_body(widths: &[f32], clearances: &[f32], spacing: f32, head: HeadEnd) -> Body {
    let bones = widths
        .iter()
        .zip(clearances)
        .enumerate()
        .map(|(i, (&w, &c))| {
            let z = i as f32 * spacing;
            SpineBone::from_sockets(
                z,
                Vec3::new(-w / 2.0, c, z),
                Vec3::new(w / 2.0, c, z),
                Vec3::new(0.0, c + w / 2.0, z),
                c,
            )
        })
        .collect();
    let length = spacing * (widths.len() as f32 + 1.0);
    Body::new(bones, length, head)
}

/// The `n`-bone walker used by the bench and the golden files: a hip bulge and a chest bulge.
pub fn walker_body(n: usize) -> Body {
    let widths: Vec<f32> = (0..n)
        .map(|i| {
            let t = i as f32 / (n.max(2) - 1) as f32;
            0.3 + 0.5 * (-(t - 0.2) * (t - 0.2) * 40.0).exp()
                + 0.35 * (-(t - 0.75) * (t - 0.75) * 40.0).exp()
        })
        .collect();
    let clearances: Vec<f32> = (0..n).map(|i| 1.8 + 0.05 * (i % 3) as f32).collect();
    straight_body(&widths, &clearances, 0.4, HeadEnd::Last)
}

/// Whether any two legs on the same side have overlapping sweeps, or share a bone.
pub fn legs_overlap(plan: &Plan) -> bool {
    let legs: Vec<_> = plan
        .limbs
        .iter()
        .filter(|l| l.kind == LimbKind::Leg)
        .collect();
    for (i, a) in legs.iter().enumerate() {
        for b in &legs[i + 1..] {
            if a.side == b.side && (a.bone == b.bone || a.span.overlaps(&b.span)) {
                return true;
            }
        }
    }
    false
}
