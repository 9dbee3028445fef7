//! The bench's workload (`benches/update.rs`: 1,000 hexapods walking over a 401 × 401 height
//! field, one update each per frame) as a plain program, for a profiler or an instruction
//! count, which the bench's harness would drown:
//!
//! ```text
//! cargo build --release -p creature-gait --example herd
//! valgrind --tool=callgrind target/release/examples/herd 400 50
//! ```
//!
//! Arguments: warm-up frames (default 400), measured frames (default 50) and creatures (default
//! and most 1,000); the creatures are built and warmed up as in the bench (`benches/herd`). It
//! prints the leg-updates of the measured frames, their time, and a hash of every leg's state,
//! joints and the metrics after them (same build, same hash: the run is deterministic).

#[path = "../benches/herd/mod.rs"]
mod herd;

use std::time::Instant;

use creature_gait::GaitError;
use herd::{Herd, hexapod, terrain};

/// FNV-1a over the bits of every float the read-outs hold.
fn hash(herd: &Herd) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    let mut add = |x: f32| {
        for b in x.to_bits().to_le_bytes() {
            h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    };
    for c in &herd.controllers {
        for s in c.leg_states() {
            let j = &s.joints;
            for v in [s.foot, s.normal, s.step_target, j.root, j.middle, j.end] {
                v.to_array().into_iter().for_each(&mut add);
            }
            for q in [j.upper_rotation, j.lower_rotation] {
                q.to_array().into_iter().for_each(&mut add);
            }
            add(s.progress);
            add(s.hip_roll);
            add(f32::from(u8::from(s.planted)));
            add(s.steps as f32);
        }
        let p = c.reacted_pose();
        p.translation.to_array().into_iter().for_each(&mut add);
        p.rotation.to_array().into_iter().for_each(&mut add);
        let m = c.metrics();
        add(m.max_skate);
        add(m.max_overstretch);
        add(m.stability_margin.unwrap_or(f32::NAN));
        add(m.legs_in_air as f32);
    }
    h
}

fn main() -> Result<(), GaitError> {
    let mut args = std::env::args().skip(1).map(|a| a.parse::<usize>());
    let warm_up = args.next().and_then(Result::ok).unwrap_or(400);
    let frames = args.next().and_then(Result::ok).unwrap_or(50);
    let creatures = args.next().and_then(Result::ok).unwrap_or(1000);
    let field = terrain()?;
    let mut herd = Herd::new(creatures.min(1000), &field, &field)?;
    for _ in 0..warm_up {
        herd.step(&field, &field)?;
    }
    let start = Instant::now();
    for _ in 0..frames {
        herd.step(&field, &field)?;
    }
    let elapsed = start.elapsed();
    let updates = frames * herd.controllers.len() * hexapod().len();
    println!(
        "{updates} leg-updates in {:.3} ms ({:.3} ms per frame), hash {:016x}",
        elapsed.as_secs_f64() * 1e3,
        elapsed.as_secs_f64() * 1e3 / frames.max(1) as f64,
        hash(&herd)
    );
    Ok(())
}
