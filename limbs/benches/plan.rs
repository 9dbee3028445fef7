//! Planning the limbs of a 12-bone walker, against the seed's placement written plainly
//! (`tests/support/reference.rs`: bone marking, no leg sizes in overlap, no balance check) in
//! the same run, plus a flier and a swimmer on the same body, and the repair path (a walker
//! whose seed layout tips and is rebuilt).
//!
//! Run: `cargo bench -p creature-limbs --bench plan`

// Setup outside the timed code may fail loudly: a broken input is a broken bench.
#![allow(clippy::expect_used, missing_docs)]

use core::hint::black_box;

use creature_limbs::{CreatureKind, HeadEnd, PlanOptions, WalkerLayout, plan};
use criterion::{Criterion, criterion_group, criterion_main};

#[path = "../tests/support/mod.rs"]
mod support;

use support::reference::seed_walker;
use support::{SplitMix, straight_body, walker_body};

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

    // The repair path: the seed's "large first pair covering every slot" (its golden file),
    // which the planner rebuilds from other bones.
    let heavy = straight_body(
        &[0.4, 0.4, 0.4, 0.4, 0.4, 1.0],
        &[1.0, 1.0, 1.0, 1.0, 1.0, 6.0],
        0.5,
        HeadEnd::Last,
    );
    let p = plan(&heavy, CreatureKind::Walker, &options, &mut SplitMix(3)).expect("stands");
    assert_eq!(p.layout, Some(WalkerLayout::Rebuilt));
    let mut group = c.benchmark_group("plan_6_bones_front_heavy");
    group.bench_function("creature_limbs_walker_rebuilt", |b| {
        let mut rng = SplitMix(3);
        b.iter(|| plan(black_box(&heavy), CreatureKind::Walker, &options, &mut rng));
    });
    group.bench_function("reference_seed_walker", |b| {
        b.iter(|| seed_walker(black_box(&heavy), options.sweep));
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
