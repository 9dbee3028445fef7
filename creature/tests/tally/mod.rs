//! The audit's failures counted over many creatures, per check (`tests/audit.rs` over seeds,
//! `tests/properties.rs` over random valid params): printed, and asserted for the checks a
//! kind enforces.

// Test support: a failure here is a test failure.
#![allow(clippy::unwrap_used, clippy::std_instead_of_alloc)]

use std::collections::BTreeMap;

use creature::d3;
use creature::export::glb_3d;
use creature_audit::{Check, Limits, Report, audit_glb};

/// A report's failures, one after another.
pub(crate) fn listed(report: &Report) -> String {
    report
        .failures()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("; ")
}

/// Creatures audited so far: how many fail each check (with the first failure), and every
/// failing creature's failures.
#[derive(Default)]
pub(crate) struct Tally {
    creatures: usize,
    counts: BTreeMap<Check, (usize, String)>,
    failing: Vec<String>,
}

impl Tally {
    /// Exports `c` to `.glb`, audits it and counts its failures under `label`.
    pub(crate) fn add(&mut self, label: &str, c: &d3::Creature) {
        let glb = glb_3d(c, &c.clips).unwrap();
        let report = audit_glb(&glb, &Limits::DEFAULT).unwrap();
        self.creatures += 1;
        let mut failed: Vec<Check> = report.failures().map(|m| m.check).collect();
        failed.sort();
        failed.dedup();
        for check in &failed {
            let entry = self.counts.entry(*check).or_default();
            entry.0 += 1;
            if entry.1.is_empty()
                && let Some(m) = report.failures().find(|m| m.check == *check)
            {
                entry.1 = format!("{label}: {m}");
            }
        }
        if !failed.is_empty() {
            self.failing.push(format!("{label}: {}", listed(&report)));
        }
    }

    /// Prints the counts under `title` (every failing creature too with
    /// `CREATURE_AUDIT_VERBOSE`); an error naming the checks of `enforced` that any creature
    /// fails.
    pub(crate) fn finish(self, title: &str, enforced: &[Check]) -> Result<(), String> {
        let n = self.creatures;
        println!("audit {title}: {n} creatures, {} fail", self.failing.len());
        for check in Check::ALL {
            if let Some((k, first)) = self.counts.get(&check) {
                println!("  {:<22} {k:>5}   first: {first}", check.name());
            }
        }
        if std::env::var_os("CREATURE_AUDIT_VERBOSE").is_some() {
            for e in &self.failing {
                println!("  {e}");
            }
        }
        let broken: Vec<String> = enforced
            .iter()
            .filter_map(|c| {
                self.counts
                    .get(c)
                    .map(|(k, _)| format!("{}: {k}", c.name()))
            })
            .collect();
        if broken.is_empty() {
            Ok(())
        } else {
            Err(format!(
                "{title}: {n} creatures, failing enforced checks: {}",
                broken.join(", ")
            ))
        }
    }
}
