//! The sweep: every creature of many seeds must be valid. Runs `CREATURE_SWEEP_SEEDS` seeds
//! (default 60 in a debug build; `cargo xtask sweep` runs 10,000 in release) of 2D creatures
//! and of each 3D kind, and prints the counts.

#![cfg(feature = "std")]
#![allow(clippy::unwrap_used)]

extern crate alloc;

mod support;

use creature::{d2, d3, generate, generate_2d};

#[test]
fn sweep() {
    let seeds: u64 = std::env::var("CREATURE_SWEEP_SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(60);
    let params = d2::Params::DEFAULT.with_texture_size(64);
    let mut stats = support::SweepStats::default();
    let mut failures = Vec::new();
    for seed in 0..seeds {
        match generate_2d(seed, &params) {
            Ok(c) => {
                let problems = support::check(&c);
                stats.add(&c);
                if !problems.is_empty() {
                    failures.push(format!("seed {seed}: {}", problems.join("; ")));
                }
            }
            Err(e) => failures.push(format!("seed {seed}: error: {e}")),
        }
    }
    println!("sweep: {seeds} seeds, {} invalid", failures.len());
    println!("{stats}");
    for f in failures.iter().take(20) {
        println!("  {f}");
    }
    assert!(
        failures.is_empty(),
        "{} of {seeds} creatures invalid",
        failures.len()
    );
}

fn sweep_3d(kind: d3::Kind) {
    let seeds: u64 = std::env::var("CREATURE_SWEEP_SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(60);
    let params = d3::Params::DEFAULT.with_kind(kind);
    let mut failures = Vec::new();
    let (mut vertices, mut joints, mut pairs) = (0usize, 0usize, 0usize);
    // Clips whose loop closes (loop error under 1e-3), and all clips, by name.
    let mut loops: alloc::collections::BTreeMap<&str, (usize, usize)> = Default::default();
    for seed in 0..seeds {
        match generate(seed, &params) {
            Ok(c) => {
                for clip in &c.clips {
                    let entry = loops.entry(clip.name).or_default();
                    entry.0 += usize::from(clip.loop_error < 1e-3);
                    entry.1 += 1;
                }
                vertices += c.mesh.positions.len();
                joints += c.skeleton.joints.len();
                pairs += c.plan.leg_pairs();
                // The data only: how it stands and moves is the audit's (`tests/audit.rs`,
                // which `cargo xtask sweep` runs on the same seeds).
                let mut problems = support::check_3d_data(&c);
                // The proxy for countershading (the belly lighter than the back).
                if c.quality.belly_contrast < 0.1 {
                    problems.push(format!(
                        "back–belly luminance contrast {} below 0.1",
                        c.quality.belly_contrast
                    ));
                }
                // The proxy for a face: its eyes show in the front or side preview.
                if c.quality.eyes_in_view < 2 {
                    problems.push(format!(
                        "{} eyes facing the front or side views, not 2",
                        c.quality.eyes_in_view
                    ));
                }
                // The proxy for a head distinct from the body: the neck narrower than
                // both.
                match c.quality.neck_to_head_and_body {
                    Some(r) if r >= 1.0 => problems.push(format!(
                        "the neck {r} × as wide as the narrower of head and body, not less"
                    )),
                    Some(_) => {}
                    None if !matches!(kind, d3::Kind::Swimmer | d3::Kind::Slitherer) => {
                        problems.push("a head, but no neck measured".into());
                    }
                    None => {}
                }
                // The proxies for proportioned limbs: thighs thicker than shins, and
                // wings (flapping or buzzing) big enough to fly.
                let legs = c
                    .plan
                    .limbs
                    .iter()
                    .any(|l| l.kind == creature::limbs::LimbKind::Leg);
                match c.quality.thigh_to_shin_radius {
                    Some(r) if r < 1.3 => {
                        problems.push(format!("thigh only {r} × the shin's radius, not 1.3"));
                    }
                    None if legs => problems.push("legs, but no thigh-to-shin radius".into()),
                    _ => {}
                }
                let winged = c.plan.limbs.iter().any(|l| {
                    matches!(
                        l.kind,
                        creature::limbs::LimbKind::FlappingWing
                            | creature::limbs::LimbKind::BuzzingWing
                    )
                });
                match c.quality.wing_span_to_body_length {
                    Some(span) if span < 1.2 => {
                        problems.push(format!("wing span {span} × the body length, not 1.2"));
                    }
                    None if winged => problems.push("wings, but no span".into()),
                    _ => {}
                }
                match c.quality.wing_area_to_body_volume {
                    Some(area) if area < params.wing_area.min * 0.999 => problems.push(format!(
                        "wing area {area} × the body volume^(2/3), under {}",
                        params.wing_area.min
                    )),
                    None if winged => problems.push("wings, but no area".into()),
                    _ => {}
                }
                if !problems.is_empty() {
                    failures.push(format!("seed {seed}: {}", problems.join("; ")));
                }
            }
            Err(e) => failures.push(format!("seed {seed}: error: {e}")),
        }
    }
    let n = seeds.max(1) as usize;
    println!(
        "sweep {kind:?}: {seeds} seeds, {} invalid; mean vertices {}, joints {}, leg pairs {:.2}",
        failures.len(),
        vertices / n,
        joints / n,
        pairs as f32 / n as f32
    );
    let looping: Vec<String> = loops
        .iter()
        .map(|(name, (closed, all))| format!("{name} {closed}/{all}"))
        .collect();
    println!("  clips that loop (error < 1e-3): {}", looping.join(", "));
    for f in failures.iter().take(20) {
        println!("  {f}");
    }
    assert!(
        failures.is_empty(),
        "{} of {seeds} {kind:?}s invalid",
        failures.len()
    );
}

#[test]
fn sweep_walkers() {
    sweep_3d(d3::Kind::Walker);
}

#[test]
fn sweep_fliers() {
    sweep_3d(d3::Kind::Flier);
}

#[test]
fn sweep_swimmers() {
    sweep_3d(d3::Kind::Swimmer);
}

#[test]
fn sweep_slitherers() {
    sweep_3d(d3::Kind::Slitherer);
}
