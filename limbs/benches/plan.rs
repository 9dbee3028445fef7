//! Planning the limbs of a 12-bone walker, against the seed's placement written plainly
//! (`tests/support/reference.rs`: bone marking, no leg sizes in overlap, no balance check) in
//! the same run, plus a flier and a swimmer on the same body.
//!
//! Run: `cargo bench -p creature-limbs --bench plan`

// Setup outside the timed code may fail loudly: a broken input is a broken bench.
#![allow(clippy::expect_used, missing_docs)]

use core::hint::black_box;

use creature_limbs::{CreatureKind, PlanOptions, plan};
use criterion::{Criterion, criterion_group, criterion_main};

#[path = "../tests/support/mod.rs"]
mod support;

use support::reference::seed_walker;
use support::{SplitMix, walker_body};

fn bench(c: &mut Criterion) {
    let body = walker_body(12);
    let options = PlanOptions::DEFAULT;
    // The inputs are fixed; check once, outside the timed code, that planning succeeds.
    plan(&body, CreatureKind::Walker, &options, &mut SplitMix(1)).expect("valid body");
    let mut group = c.benchmark_group("plan_12_bones");
    group.bench_function("creature_limbs_walker", |b| {
        let mut rng = SplitMix(1);
        b.iter(|| plan(black_box(&body), CreatureKind::Walker, &options, &mut rng));
    });
    group.bench_function("reference_seed_walker", |b| {
        b.iter(|| seed_walker(black_box(&body), options.sweep));
    });
    group.bench_function("creature_limbs_flier", |b| {
        let mut rng = SplitMix(2);
        b.iter(|| plan(black_box(&body), CreatureKind::Flier, &options, &mut rng));
    });
    group.bench_function("creature_limbs_swimmer", |b| {
        let mut rng = SplitMix(3);
        b.iter(|| plan(black_box(&body), CreatureKind::Swimmer, &options, &mut rng));
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
