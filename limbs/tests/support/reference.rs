//! The seed's walker leg placement, written as the seed's pseudocode reads: legs sized by
//! their socket's height, each placed leg marking the bones inside its own sweep as unusable,
//! a candidate accepted when its bone is unmarked (its own size ignored), no balance check and
//! no minimum leg length. Shared by the integration tests (to show the seed's failure cases)
//! and the benchmark (as the baseline).

use creature_limbs::Body;

/// Bones that get leg pairs, in placement order.
pub fn seed_walker(body: &Body, sweep: f32) -> Vec<usize> {
    let bones = &body.bones;
    let n = bones.len();
    let mut marked = vec![false; n];
    let mut pairs = Vec::new();
    let place = |i: usize, marked: &mut Vec<bool>, pairs: &mut Vec<usize>| {
        pairs.push(i);
        let half = sweep * bones[i].clearance;
        for (j, b) in bones.iter().enumerate() {
            if (b.along - bones[i].along).abs() <= half {
                marked[j] = true;
            }
        }
        marked[i] = true;
    };
    let widest = bones.iter().map(|b| b.width).fold(0.0f32, f32::max);
    let narrowest = bones.iter().map(|b| b.width).fold(f32::INFINITY, f32::min);
    let height = bones.iter().map(|b| b.clearance).sum::<f32>() / n as f32;
    if body.length > 3.0 * height || narrowest >= 0.75 * widest {
        for i in 0..n {
            if !marked[i] {
                place(i, &mut marked, &mut pairs);
            }
        }
        return pairs;
    }
    let w = (0..n)
        .max_by(|&a, &b| bones[a].width.total_cmp(&bones[b].width).then(b.cmp(&a)))
        .unwrap_or(0);
    place(w, &mut marked, &mut pairs);
    let next = (0..n)
        .filter(|&i| !marked[i])
        .max_by(|&a, &b| bones[a].width.total_cmp(&bones[b].width).then(b.cmp(&a)));
    match next {
        Some(s) if bones[s].width >= 0.75 * bones[w].width => place(s, &mut marked, &mut pairs),
        _ => {
            if (2 * w).abs_diff(n - 1) > 4 {
                let opposite = bones[0].along + bones[n - 1].along - bones[w].along;
                let balance = (0..n).filter(|&i| !marked[i]).min_by(|&a, &b| {
                    (bones[a].along - opposite)
                        .abs()
                        .total_cmp(&(bones[b].along - opposite).abs())
                });
                if let Some(b) = balance {
                    place(b, &mut marked, &mut pairs);
                }
            }
        }
    }
    pairs
}
