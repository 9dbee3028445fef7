//! Golden outputs for a fixed ball set: field values, gradients, shares, a sampled grid and
//! bone coverings, stored as text with quantised floats under `tests/golden/` and compared
//! with a tolerance, so results are pinned across builds, backends (`std` / `libm`) and
//! platforms, not only between two runs of one process.
//!
//! The files change only when regenerated on purpose:
//! `CREATURE_BLESS=1 cargo test -p creature-metaball --test golden` (what `cargo xtask bless`
//! runs). A changed output for the same inputs is a breaking change: record it in the
//! CHANGELOG.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

use core::fmt::Write as _;
use std::path::PathBuf;

use creature_metaball::glam::{Vec2, Vec3};
use creature_metaball::{
    Ball2, Ball3, CoverOptions, Falloff, Field2, Field3, FieldOptions, Share, cover_segment,
    cover_segment_with, cover_segment3,
};

/// A small creature-like set: a body of three balls (id 0), a two-bone limb (ids 1, 2) and a
/// detached head (id 3), radii 4 to 14.
const BALLS: [Ball2; 9] = [
    Ball2::new(Vec2::new(0.0, 0.0), 14.0, 0),
    Ball2::new(Vec2::new(22.0, 3.0), 12.5, 0),
    Ball2::new(Vec2::new(42.0, 4.0), 11.0, 0),
    Ball2::new(Vec2::new(10.0, -18.0), 6.0, 1),
    Ball2::new(Vec2::new(13.0, -30.0), 5.5, 1),
    Ball2::new(Vec2::new(17.0, -41.0), 5.0, 2),
    Ball2::new(Vec2::new(24.0, -47.0), 4.0, 2),
    Ball2::new(Vec2::new(66.0, 16.0), 9.0, 3),
    Ball2::new(Vec2::new(74.0, 21.0), 4.5, 3),
];

/// Sample points spread over the set, none on a symmetry line.
fn points() -> Vec<Vec2> {
    let mut out = Vec::new();
    for i in 0..6 {
        for j in 0..4 {
            let (i, j) = (i as f32, j as f32);
            out.push(Vec2::new(
                -12.0 + 17.3 * i + 2.9 * j,
                -44.0 + 19.1 * j + 1.7 * i,
            ));
        }
    }
    out
}

/// Seven significant digits: more than `f32` rounding differences between platforms, so the
/// comparison below decides.
fn f(x: f32) -> String {
    format!("{x:.6e}")
}

fn v2(v: Vec2) -> String {
    format!("{} {}", f(v.x), f(v.y))
}

fn v3(v: Vec3) -> String {
    format!("{} {} {}", f(v.x), f(v.y), f(v.z))
}

/// Shares as `id:weight` pairs. Refuses near-ties: their order could flip with the last bit
/// of `exp`, which would make the golden file platform-dependent.
fn shares(s: &[Share]) -> String {
    for w in s.windows(2) {
        assert!(
            w[0].weight - w[1].weight > 1e-4,
            "near-tie in {s:?}: move the sample point"
        );
    }
    s.iter()
        .map(|s| format!("{}:{}", s.id, f(s.weight)))
        .collect::<Vec<_>>()
        .join(" ")
}

fn render_field(falloff: Falloff) -> String {
    let field = Field2::with_options(&BALLS, &FieldOptions::DEFAULT.with_falloff(falloff)).unwrap();
    let mut s = String::new();
    let _ = writeln!(s, "falloff {falloff:?}");
    let _ = writeln!(s, "error_bound {}", f(field.error_bound()));
    let _ = writeln!(
        s,
        "gradient_error_bound {}",
        f(field.gradient_error_bound())
    );
    let (min, max) = field.bounds();
    let _ = writeln!(s, "bounds {} {}", v2(min), v2(max));
    let stats = field.grid_stats();
    let _ = writeln!(
        s,
        "grid {} {} {}",
        f(stats.cell_size),
        stats.cells,
        stats.entries
    );
    for p in points() {
        let (value, gradient) = field.value_and_gradient(p);
        let _ = writeln!(
            s,
            "at {} value {} exact {} gradient {} exact {} shares {}",
            v2(p),
            f(value),
            f(field.value_exact(p)),
            v2(gradient),
            v2(field.gradient_exact(p)),
            shares(&field.shares(p, 4)),
        );
    }
    let colours: Vec<Vec3> = BALLS
        .iter()
        .map(|b| Vec3::new(b.id as f32, 1.0 / (1.0 + b.id as f32), b.radius))
        .collect();
    for p in points().into_iter().step_by(5) {
        let blended = field.blend(p, &colours).unwrap();
        let _ = writeln!(
            s,
            "blend {} {}",
            v2(p),
            blended.map_or("none".to_owned(), v3)
        );
    }
    let samples = field
        .sample_grid(Vec2::new(-20.0, -55.0), 12.5, 9, 7)
        .unwrap();
    for row in samples.chunks(9) {
        let _ = writeln!(
            s,
            "grid_row {}",
            row.iter().map(|&x| f(x)).collect::<Vec<_>>().join(" ")
        );
    }
    s
}

fn render_field3() -> String {
    let balls: Vec<Ball3> = BALLS
        .iter()
        .enumerate()
        .map(|(i, b)| Ball3::new(b.center.extend(3.0 * i as f32 - 12.0), b.radius, b.id))
        .collect();
    let field = Field3::new(&balls, Falloff::SEED).unwrap();
    let mut s = String::new();
    for (k, p) in points().into_iter().enumerate() {
        let p = p.extend(2.5 * k as f32 - 30.0);
        let (value, gradient) = field.value_and_gradient(p);
        let _ = writeln!(
            s,
            "at {} value {} gradient {} shares {}",
            v3(p),
            f(value),
            v3(gradient),
            shares(&field.shares(p, 4)),
        );
    }
    s
}

fn render_covers() -> String {
    let mut s = String::new();
    let mut section = |name: &str, balls: Vec<(Vec3, f32, u32)>| {
        let _ = writeln!(s, "{name} {}", balls.len());
        for (c, r, id) in balls {
            let _ = writeln!(s, "ball {} radius {} id {id}", v3(c), f(r));
        }
    };
    let flat = |b: Vec<Ball2>| -> Vec<(Vec3, f32, u32)> {
        b.into_iter()
            .map(|b| (b.center.extend(0.0), b.radius, b.id))
            .collect()
    };
    // A two-bone limb the seed's way: each bone from its child end to its parent joint.
    let (shoulder, elbow, hand) = (
        Vec2::new(0.0, 0.0),
        Vec2::new(61.0, -7.5),
        Vec2::new(113.0, 21.0),
    );
    section(
        "upper_arm",
        flat(cover_segment(elbow, shoulder, 12.0, 1.4, 0).unwrap()),
    );
    section(
        "forearm_interior_joint",
        flat(
            cover_segment_with(
                hand,
                elbow,
                8.0,
                1.2,
                1,
                &CoverOptions::DEFAULT.with_interior_joint(true),
            )
            .unwrap(),
        ),
    );
    section(
        "beads_m1",
        flat(cover_segment(Vec2::new(-5.0, 2.0), Vec2::new(-5.0, 97.0), 9.0, 1.0, 2).unwrap()),
    );
    section(
        "smooth_3d",
        cover_segment3(
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(-40.0, 25.0, 60.0),
            7.5,
            1.6,
            4,
        )
        .unwrap()
        .into_iter()
        .map(|b| (b.center, b.radius, b.id))
        .collect(),
    );
    s
}

/// Token-wise comparison: numbers within a relative `2e-5` (plus `1e-8` absolute, for values
/// that cancel to near zero), everything else exactly.
fn same(expected: &str, actual: &str) -> bool {
    let (e, a): (Vec<_>, Vec<_>) = (
        expected.split_whitespace().collect(),
        actual.split_whitespace().collect(),
    );
    e.len() == a.len()
        && e.iter().zip(&a).all(|(x, y)| {
            let split = |t: &str| match t.split_once(':') {
                Some((id, w)) => (Some(id.to_owned()), w.to_owned()),
                None => (None, t.to_owned()),
            };
            let ((xi, xw), (yi, yw)) = (split(x), split(y));
            xi == yi
                && match (xw.parse::<f64>(), yw.parse::<f64>()) {
                    (Ok(x), Ok(y)) => (x - y).abs() <= 2e-5 * x.abs().max(y.abs()) + 1e-8,
                    _ => xw == yw,
                }
        })
}

fn check(name: &str, actual: &str) {
    let path: PathBuf = [env!("CARGO_MANIFEST_DIR"), "tests", "golden", name]
        .iter()
        .collect();
    if std::env::var_os("CREATURE_BLESS").is_some_and(|v| v == "1") {
        std::fs::write(&path, actual).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        same(&expected, actual),
        "{name} differs from {}; if the change is intended, rerun with CREATURE_BLESS=1\n\
         --- expected\n{expected}\n--- actual\n{actual}",
        path.display()
    );
}

#[test]
fn golden_field_seed() {
    check("field_seed.txt", &render_field(Falloff::SEED));
}

#[test]
fn golden_field_wyvill() {
    check("field_wyvill.txt", &render_field(Falloff::WYVILL));
}

#[test]
fn golden_field_blinn() {
    check(
        "field_blinn.txt",
        &render_field(Falloff::Blinn {
            strength: 3.0,
            sharpness: 1.3,
        }),
    );
}

#[test]
fn golden_field3_seed() {
    check("field3_seed.txt", &render_field3());
}

#[test]
fn golden_cover_segment() {
    check("cover.txt", &render_covers());
}

#[test]
fn the_comparison_catches_a_changed_digit_but_not_rounding() {
    assert!(same(
        "a 1.000000e0 3:5.000000e-1",
        "a 1.000001e0 3:5.000001e-1"
    ));
    assert!(!same("a 1.000000e0", "a 1.001000e0"));
    assert!(!same("3:5.000000e-1", "4:5.000000e-1"));
    assert!(!same("a 1.0", "a 1.0 2.0"));
    assert!(!same("", "a"));
}
