//! Plans the limbs of one sample body as a walker, a flier and a swimmer, and prints each plan:
//! the layout and its repairs, the stability margin, and every limb with its bone, socket, size
//! and sweep.
//!
//! Run: `cargo run -p creature-limbs --example plan -- [seed]` (default seed 7).

use creature_limbs::glam::Vec3;
use creature_limbs::{Body, CreatureKind, HeadEnd, LimbsError, Plan, PlanOptions, SpineBone, plan};

// SplitMix64: any `rand_core` 0.10 generator works; this one needs no dependency (the
// README writes it out).
#[path = "../tests/support/split_mix.rs"]
mod split_mix;

use split_mix::SplitMix;

/// Ten bones along +Z, the head at the last one, with hips (bone 2) and a chest (bone 7).
/// glTF's convention: right-handed, +Y up, facing +Z, so the left socket is on +X.
fn sample_body() -> Body {
    let widths = [0.35, 0.7, 0.85, 0.55, 0.4, 0.4, 0.6, 0.75, 0.5, 0.3];
    let bones = widths
        .iter()
        .enumerate()
        .map(|(i, &w)| {
            let z = i as f32 * 0.4;
            let height = 1.6 + 0.05 * (i % 3) as f32;
            SpineBone::from_sockets(
                z,
                Vec3::new(w / 2.0, height, z),
                Vec3::new(-w / 2.0, height, z),
                Vec3::new(0.0, height + w / 2.0, z),
                height,
            )
        })
        .collect();
    Body::new(bones, 4.4, HeadEnd::Last)
}

fn print_plan(title: &str, p: &Plan) {
    println!("== {title} ==");
    if let Some(layout) = p.layout {
        println!("layout {layout:?}, lift {:.3}", p.lift);
    }
    if let Some(margin) = p.stability_margin {
        println!(
            "stability margin {margin:.3} (centre of mass at x {:.3}, z {:.3}; support hull of {} points)",
            p.center_of_mass.x,
            p.center_of_mass.y,
            p.support.len()
        );
    }
    if let Some(knee) = p.knee {
        println!("knees {knee:?}");
    }
    for r in &p.repairs {
        println!("repair {r:?}");
    }
    for (i, l) in p.limbs.iter().enumerate() {
        print!(
            "limb {i:2} {:<12} bone {:2} {:<5} {:<6} length {:.3} sweeps bones {}..={}",
            format!("{:?}", l.kind),
            l.bone,
            format!("{:?}", l.socket),
            format!("{:?}", l.side),
            l.length,
            l.span.first_bone,
            l.span.last_bone,
        );
        if let Some(f) = l.foot {
            print!(" foot ({:.3}, {:.3}, {:.3})", f.x, f.y, f.z);
        }
        println!();
    }
    println!();
}

fn main() -> Result<(), LimbsError> {
    let seed = std::env::args()
        .nth(1)
        .and_then(|s| s.parse::<u64>().ok())
        .unwrap_or(7);
    let body = sample_body();
    let options = PlanOptions::DEFAULT;
    for (title, kind) in [
        ("walker", CreatureKind::Walker),
        ("flier", CreatureKind::Flier),
        ("swimmer", CreatureKind::Swimmer),
    ] {
        let p = plan(&body, kind, &options, &mut SplitMix(seed))?;
        print_plan(&format!("{title}, seed {seed}"), &p);
    }
    Ok(())
}
