//! Golden plans for fixed bodies and seeds, stored as text with quantised floats under
//! `tests/golden/` and compared with a tolerance.
//!
//! The files change only when regenerated on purpose:
//! `CREATURE_BLESS=1 cargo test -p creature-limbs --test golden` (what `cargo xtask bless`
//! runs). A changed plan for the same inputs is a breaking change: record it in the CHANGELOG.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use core::fmt::Write as _;
use std::path::PathBuf;

use creature_limbs::{Body, CreatureKind, HeadEnd, Plan, PlanOptions, plan};
use support::{SplitMix, straight_body, walker_body};

/// Floats with three decimals; everything else as `Debug`.
fn render(p: &Plan) -> String {
    let mut s = String::new();
    let f = |x: f32| format!("{x:.3}");
    let _ = writeln!(s, "kind {:?}", p.kind);
    let _ = writeln!(s, "knee {:?}", p.knee);
    let _ = writeln!(s, "layout {:?}", p.layout);
    let _ = writeln!(s, "lift {}", f(p.lift));
    let _ = writeln!(
        s,
        "stability_margin {}",
        p.stability_margin.map_or("none".to_owned(), f)
    );
    let _ = writeln!(
        s,
        "center_of_mass {} {}",
        f(p.center_of_mass.x),
        f(p.center_of_mass.y)
    );
    for v in &p.support {
        let _ = writeln!(s, "support {} {}", f(v.x), f(v.y));
    }
    for r in &p.repairs {
        let _ = writeln!(s, "repair {r:?}");
    }
    for (i, l) in p.limbs.iter().enumerate() {
        let _ = write!(
            s,
            "limb {i} {:?} variant {} bone {} {:?} {:?} mirror {:?} scale {} {} {} length {} span {} {} bones {} {}",
            l.kind,
            l.variant,
            l.bone,
            l.socket,
            l.side,
            l.mirror,
            f(l.scale.x),
            f(l.scale.y),
            f(l.scale.z),
            f(l.length),
            f(l.span.start),
            f(l.span.end),
            l.span.first_bone,
            l.span.last_bone,
        );
        if let Some(foot) = l.foot {
            let _ = write!(s, " foot {} {} {}", f(foot.x), f(foot.y), f(foot.z));
        }
        s.push('\n');
    }
    s
}

/// Token-wise comparison: numbers within `1e-3`, everything else exactly.
fn same(expected: &str, actual: &str) -> bool {
    let (e, a): (Vec<_>, Vec<_>) = (
        expected.split_whitespace().collect(),
        actual.split_whitespace().collect(),
    );
    e.len() == a.len()
        && e.iter()
            .zip(&a)
            .all(|(x, y)| match (x.parse::<f32>(), y.parse::<f32>()) {
                (Ok(x), Ok(y)) => (x - y).abs() <= 1.5e-3,
                _ => x == y,
            })
}

fn check(name: &str, body: &Body, kind: CreatureKind, seed: u64) {
    let p = plan(body, kind, &PlanOptions::DEFAULT, &mut SplitMix(seed)).unwrap();
    let actual = render(&p);
    let path: PathBuf = [env!("CARGO_MANIFEST_DIR"), "tests", "golden", name]
        .iter()
        .collect();
    if std::env::var_os("CREATURE_BLESS").is_some_and(|v| v == "1") {
        std::fs::write(&path, &actual).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        same(&expected, &actual),
        "{name} differs from {}; if the change is intended, rerun with CREATURE_BLESS=1\n\
         --- expected\n{expected}\n--- actual\n{actual}",
        path.display()
    );
}

#[test]
fn golden_walker_hips_and_chest() {
    check(
        "walker_12_seed_1.txt",
        &walker_body(12),
        CreatureKind::Walker,
        1,
    );
}

#[test]
fn golden_walker_centipede() {
    let body = straight_body(&[0.5; 14], &[0.3; 14], 0.3, HeadEnd::Last);
    check(
        "walker_centipede_seed_2.txt",
        &body,
        CreatureKind::Walker,
        2,
    );
}

#[test]
fn golden_walker_front_heavy() {
    let body = straight_body(
        &[0.4, 0.4, 0.4, 0.4, 0.4, 1.0],
        &[1.0, 1.0, 1.0, 1.0, 1.0, 6.0],
        0.5,
        HeadEnd::Last,
    );
    check(
        "walker_front_heavy_seed_3.txt",
        &body,
        CreatureKind::Walker,
        3,
    );
}

#[test]
fn golden_flier() {
    check(
        "flier_10_seed_4.txt",
        &walker_body(10),
        CreatureKind::Flier,
        4,
    );
    check(
        "flier_10_seed_5.txt",
        &walker_body(10),
        CreatureKind::Flier,
        5,
    );
}

#[test]
fn golden_swimmer() {
    check(
        "swimmer_10_seed_6.txt",
        &walker_body(10),
        CreatureKind::Swimmer,
        6,
    );
}
