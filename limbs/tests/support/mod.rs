//! Helpers shared by the integration tests and the benchmark.
#![allow(dead_code, unreachable_pub)]

pub mod reference;
mod split_mix;

use creature_limbs::glam::{Vec2, Vec3};
use creature_limbs::{Body, HeadEnd, LimbKind, Plan, PlanOptions, SpineBone, support_margin};
pub(crate) use split_mix::SplitMix;

/// A straight body along +Z: bone `i` at `along = i * spacing` with the given widths and
/// clearances, side sockets at half the width, ground at y = 0. The creature faces its head:
/// +Z for `HeadEnd::Last` (its left socket on +X, glTF's convention), −Z for `HeadEnd::First`
/// (its left on −X).
pub fn straight_body(widths: &[f32], clearances: &[f32], spacing: f32, head: HeadEnd) -> Body {
    let s = if head == HeadEnd::Last { 1.0 } else { -1.0 };
    let bones = widths
        .iter()
        .zip(clearances)
        .enumerate()
        .map(|(i, (&w, &c))| {
            let z = i as f32 * spacing;
            SpineBone::from_sockets(
                z,
                Vec3::new(s * w / 2.0, c, z),
                Vec3::new(-s * w / 2.0, c, z),
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

/// The walking leg lengths on `bone` with the body raised by `lift`, computed as the planner
/// documents them (socket height above the bone's ground, plus the lift).
pub fn walking_legs(body: &Body, bone: usize, lift: f32) -> (f32, f32) {
    let b = &body.bones[bone];
    let ground = b.ground();
    (b.left.y - ground + lift, b.right.y - ground + lift)
}

/// The stability margin of leg pairs on `pairs`, measured independently of the planner with
/// the public `support_margin`: feet under the side sockets, radius `foot_radius × length`.
pub fn margin_of(body: &Body, options: &PlanOptions, pairs: &[usize]) -> f32 {
    let feet: Vec<Vec2> = pairs
        .iter()
        .flat_map(|&p| {
            let b = &body.bones[p];
            [
                Vec2::new(b.left.x, b.left.z),
                Vec2::new(b.right.x, b.right.z),
            ]
        })
        .collect();
    support_margin(
        &feet,
        options.foot_radius * body.length,
        body.center_of_mass(),
    )
}

/// The documented lift (just enough for the highest bone's legs to reach `min_leg_length`) and
/// the bones whose legs are then clearly at least that long (a relative tolerance in the
/// planner's favour).
pub fn tall_enough_bones(body: &Body, options: &PlanOptions) -> (f32, Vec<usize>) {
    let n = body.bones.len();
    let min_len = options.min_leg_length * body.length;
    let tallest = (0..n)
        .map(|i| {
            let (l, r) = walking_legs(body, i, 0.0);
            l.min(r)
        })
        .fold(f32::NEG_INFINITY, f32::max);
    let lift = (min_len - tallest).max(0.0);
    let eligible = (0..n)
        .filter(|&i| {
            let (l, r) = walking_legs(body, i, lift);
            l.min(r) >= min_len * (1.0 + 1e-4)
        })
        .collect();
    (lift, eligible)
}

/// Exhaustive search (bodies of at most 12 bones) for the best stability margin over every set
/// of leg pairs on bones whose legs are clearly at least `min_leg_length` long (a relative
/// tolerance in the planner's favour) with pairwise non-overlapping sweeps. The lift is the
/// planner's documented one: just enough for the highest bone.
pub fn best_possible_margin(body: &Body, options: &PlanOptions) -> f32 {
    assert!(body.bones.len() <= 12);
    let (lift, eligible) = tall_enough_bones(body, options);
    let span = |i: usize| {
        let (l, r) = walking_legs(body, i, lift);
        let half = options.sweep * l.max(r);
        let a = body.bones[i].along;
        (a - half, a + half)
    };
    let mut best = f32::NEG_INFINITY;
    for mask in 1u32..(1 << eligible.len()) {
        let chosen: Vec<usize> = (0..eligible.len())
            .filter(|k| mask & (1 << k) != 0)
            .map(|k| eligible[k])
            .collect();
        let compatible = chosen.iter().enumerate().all(|(x, &a)| {
            chosen[x + 1..].iter().all(|&b| {
                let (sa, sb) = (span(a), span(b));
                // Strictly apart, with a small tolerance in the planner's favour.
                let gap = (sb.0 - sa.1).max(sa.0 - sb.1);
                gap >= 1e-4 * (1.0 + sa.1.abs() + sb.1.abs())
            })
        });
        if compatible {
            best = best.max(margin_of(body, options, &chosen));
        }
    }
    best
}
