//! A plain reference metaball field, written the way the seed computes it: every ball, every
//! sample, no cutoff and no grid (`F(p) = Σ exp(B |p − c|²/R² − B)`), and the seed's skinning
//! (per-id sums over all balls, sort, top k, L1 normalisation). Shared by the integration tests
//! (as an oracle) and the benchmark (as the baseline).

// The fixed skeleton below is valid: a failure to cover it is a broken test input.
#![allow(clippy::expect_used)]

use creature_metaball::Ball2;
use creature_metaball::glam::Vec2;

/// The seed's field at `p` with blobbiness `b`.
pub(crate) fn value(balls: &[Ball2], b: f32, p: Vec2) -> f32 {
    let mut sum = 0.0;
    for ball in balls {
        let r2 = (p - ball.center).length_squared();
        sum += (b * r2 / (ball.radius * ball.radius) - b).exp();
    }
    sum
}

/// The seed's skinning weights at `p`: the `k` ids with the largest summed contribution,
/// normalised by their L1 sum; `(id, weight)`, largest first.
pub(crate) fn shares(balls: &[Ball2], b: f32, p: Vec2, k: usize) -> Vec<(u32, f32)> {
    let mut per_id: Vec<(u32, f32)> = Vec::new();
    for ball in balls {
        let r2 = (p - ball.center).length_squared();
        let f = (b * r2 / (ball.radius * ball.radius) - b).exp();
        match per_id.iter_mut().find(|(id, _)| *id == ball.id) {
            Some(entry) => entry.1 += f,
            None => per_id.push((ball.id, f)),
        }
    }
    per_id.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    per_id.truncate(k);
    let total: f32 = per_id.iter().map(|s| s.1).sum();
    per_id.into_iter().map(|(id, w)| (id, w / total)).collect()
}

/// A creature-like ball set built the seed's way from a fixed skeleton: a spine of four
/// segments along +y and two limb pairs, every bone covered like the seed's
/// `generateMetaballs` (child end first, interior-joint rule, id = parent bone). About 50
/// balls, like the seed's median creature (49).
pub(crate) fn creature() -> Vec<Ball2> {
    use creature_metaball::{CoverOptions, cover_segment_with};
    // (thickness, length, multiplier) per spine segment.
    let spine = [
        (22.0, 70.0, 1.3),
        (34.0, 90.0, 1.5),
        (28.0, 80.0, 1.2),
        (18.0, 60.0, 1.55),
    ];
    let mut balls = Vec::new();
    let mut joints = vec![Vec2::ZERO];
    for (i, &(t, length, m)) in spine.iter().enumerate() {
        let parent = joints[i];
        let child = parent + Vec2::new(0.0, length);
        joints.push(child);
        let options = CoverOptions::DEFAULT.with_interior_joint(i > 0);
        balls.extend(
            cover_segment_with(child, parent, t, m, i as u32, &options).expect("valid bone"),
        );
    }
    // Limb pairs on spine joints 1 and 2: (joint, body thickness, [(thickness, length, m)]).
    let limbs = [
        (
            1usize,
            34.0f32,
            [(9.0f32, 60.0f32, 1.4f32), (7.0, 55.0, 1.2)],
        ),
        (2, 34.0, [(12.0, 70.0, 1.6), (10.0, 65.0, 1.1)]),
    ];
    let mut bone = joints.len() as u32;
    for (joint, body, segments) in limbs {
        for side in [-1.0f32, 1.0] {
            let mut at = joints[joint] + Vec2::new(side * 1.1 * body, 0.0);
            let socket_bone = bone;
            bone += 1;
            for (s, &(t, length, m)) in segments.iter().enumerate() {
                let tip = at + Vec2::new(side * length, 0.0);
                let options = CoverOptions::DEFAULT.with_interior_joint(s > 0);
                let owner = if s == 0 { socket_bone } else { bone - 1 };
                balls.extend(
                    cover_segment_with(tip, at, t, m, owner, &options).expect("valid bone"),
                );
                at = tip;
                bone += 1;
            }
        }
    }
    balls
}
