//! The audit of delivered creatures: each 3D kind's creatures exported to `.glb`, read back and
//! played as a viewer does (`creature-audit`). Runs `CREATURE_AUDIT_SEEDS` seeds per kind
//! (default 12 in a debug build; `cargo xtask sweep` runs 10,000 in release) and prints, per
//! check, how many creatures fail it. Each kind's enforced checks must hold on every seed;
//! the checks not yet enforced for a kind (the generator does not pass them yet) are counted
//! and printed only.

#![allow(clippy::unwrap_used, clippy::std_instead_of_alloc)]

use std::collections::BTreeMap;

use creature::d3::{self, Kind};
use creature::export::glb_3d;
use creature_audit::{Check, Limits, Report, audit_glb};

fn seeds() -> u64 {
    std::env::var("CREATURE_AUDIT_SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(12)
}

/// A report's failures, one after another.
fn listed(report: &Report) -> String {
    report
        .failures()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("; ")
}

/// Audits `seeds` creatures of `kind`; the number failing each check, and the first failures.
fn audit_kind(
    kind: Kind,
    first_seed: u64,
    seeds: u64,
) -> (BTreeMap<Check, (usize, String)>, Vec<String>) {
    let params = d3::Params::DEFAULT.with_kind(kind);
    let mut counts: BTreeMap<Check, (usize, String)> = BTreeMap::new();
    let mut examples = Vec::new();
    for seed in first_seed..first_seed + seeds {
        let c = d3::generate(seed, &params).unwrap();
        let glb = glb_3d(&c, &c.clips).unwrap();
        let report: Report = audit_glb(&glb, &Limits::DEFAULT).unwrap();
        let mut failed: Vec<Check> = report.failures().map(|m| m.check).collect();
        failed.sort();
        failed.dedup();
        for check in &failed {
            let entry = counts.entry(*check).or_default();
            entry.0 += 1;
            if entry.1.is_empty()
                && let Some(m) = report.failures().find(|m| m.check == *check)
            {
                entry.1 = format!("seed {seed}: {m}");
            }
        }
        if !failed.is_empty() {
            examples.push(format!("seed {seed}: {}", listed(&report)));
        }
    }
    (counts, examples)
}

fn run(kind: Kind, enforced: &[Check]) {
    let n = seeds();
    let first = std::env::var("CREATURE_AUDIT_FIRST_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    let (counts, examples) = audit_kind(kind, first, n);
    println!("audit {kind:?}: {n} seeds, {} fail", examples.len());
    for check in Check::ALL {
        if let Some((k, first)) = counts.get(&check) {
            println!("  {:<22} {k:>5}   first: {first}", check.name());
        }
    }
    if std::env::var_os("CREATURE_AUDIT_VERBOSE").is_some() {
        for e in &examples {
            println!("  {e}");
        }
    }
    let broken: Vec<String> = enforced
        .iter()
        .filter_map(|c| counts.get(c).map(|(k, _)| format!("{}: {k}", c.name())))
        .collect();
    assert!(
        broken.is_empty(),
        "{kind:?}s failing enforced checks ({n} seeds): {}",
        broken.join(", ")
    );
}

#[test]
fn audit_walkers() {
    // Not yet enforced for walkers (issue 16 is open): feet sliding, feet crossing and legs
    // intersecting in turns, jerks, and the skin squashed at limb roots.
    run(
        Kind::Walker,
        &[
            Check::Tips,
            Check::FootInAir,
            Check::FootNeverDown,
            Check::BelowGround,
            Check::Stretch,
        ],
    );
}

#[test]
fn regression_turning_walkers_keep_planted_feet_down_and_still() {
    // Seed 5003: closing the turn's loop held a planted foot 6% of the body length up (the
    // correction between two swings at different heights, held through the stance). 5004: the
    // correction made while a foot was only lifting off slid it along the ground. 5005: a foot
    // landing exactly at the midline margin stepped again at once, dragged around the turn.
    let params = d3::Params::DEFAULT.with_kind(Kind::Walker);
    for seed in [5003, 5004, 5005] {
        let c = d3::generate(seed, &params).unwrap();
        let report = audit_glb(&glb_3d(&c, &c.clips).unwrap(), &Limits::DEFAULT).unwrap();
        for check in [Check::FootInAir, Check::FootNeverDown, Check::FootSlides] {
            assert!(!report.fails(check), "seed {seed}: {}", listed(&report));
        }
    }
}

#[test]
fn audit_fliers() {
    run(Kind::Flier, &Check::ALL);
}

#[test]
fn audit_swimmers() {
    run(Kind::Swimmer, &Check::ALL);
}
