//! Golden hashes: the exact output for 10 fixed seeds, checked in at `tests/golden/2d.txt`.
//!
//! Any change to a creature changes its hash. If the change is intended, regenerate with
//! `cargo xtask bless` (it runs this file with `CREATURE_BLESS=1`), review the diff and add a
//! CHANGELOG line: same seed, same creature is a promise.
//!
//! The hashes are of the exact bits, one file per float backend: `2d.txt` with the `std`
//! backend on x86_64 (another platform's `exp` may differ in the last bit and change them),
//! `2d-libm.txt` with the `libm` feature (which wins over `std`, and turns glam's SIMD off),
//! the same on every platform.

#![cfg(feature = "std")]
#![allow(clippy::unwrap_used)]

use core::fmt::Write as _;
use std::path::PathBuf;

use creature::{d2, generate_2d};

/// The 3D creatures' golden hashes (`tests/golden/3d.txt`), in this file so that
/// `cargo xtask bless` regenerates them too.
mod golden3d;

pub(crate) const SEEDS: [u64; 10] = [0, 1, 2, 3, 7, 42, 99, 1234, 65_535, u64::MAX];

/// FNV-1a over every number of the creature, in a fixed order.
pub(crate) struct Fnv(pub(crate) u64);

impl Fnv {
    pub(crate) fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
    pub(crate) fn f32s(&mut self, values: impl IntoIterator<Item = f32>) {
        for v in values {
            self.bytes(&v.to_bits().to_le_bytes());
        }
    }
    pub(crate) fn u32s(&mut self, values: impl IntoIterator<Item = u32>) {
        for v in values {
            self.bytes(&v.to_le_bytes());
        }
    }
}

fn hash(c: &d2::Creature) -> u64 {
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    for b in &c.bones {
        h.u32s([b.parent.map_or(u32::MAX, |p| p as u32)]);
        h.f32s(b.position.to_array());
        h.f32s([b.thickness, b.multiplier, b.rotation]);
        h.f32s(b.colour.to_array());
        h.f32s(b.texture_weights.to_array());
    }
    for e in &c.eyes {
        h.f32s([e.position.x, e.position.y, e.radius]);
    }
    for b in &c.balls {
        h.f32s([b.ball.center.x, b.ball.center.y, b.ball.radius]);
        h.u32s([b.ball.id]);
    }
    for ring in &c.outline {
        h.f32s(ring.iter().flat_map(|p| p.to_array()));
    }
    let m = &c.mesh;
    h.f32s(m.positions.iter().flat_map(|p| p.to_array()));
    h.f32s(m.uvs.iter().flat_map(|p| p.to_array()));
    h.u32s(m.indices.iter().flatten().copied());
    h.u32s(m.joints.iter().flatten().map(|&j| u32::from(j)));
    h.f32s(m.weights.iter().flatten().copied());
    for image in [&c.texture, &c.normal_map].into_iter().flatten() {
        h.bytes(&image.rgba);
    }
    h.0
}

#[test]
fn golden_hashes() {
    let mut text = String::from("# seed hash bones vertices triangles (cargo xtask bless)\n");
    for seed in SEEDS {
        let c = generate_2d(seed, &d2::Params::DEFAULT).unwrap();
        writeln!(
            text,
            "{seed} {:016x} {} {} {}",
            hash(&c),
            c.bones.len(),
            c.mesh.positions.len(),
            c.mesh.indices.len()
        )
        .unwrap();
    }
    check_or_bless("2d.txt", &text);
}

/// Compares `text` with `tests/golden/{file}` (with the `libm` feature, `{stem}-libm.txt`: its
/// float results differ from `std`'s), or rewrites the file when `CREATURE_BLESS=1`.
pub(crate) fn check_or_bless(file: &str, text: &str) {
    let file = if cfg!(feature = "libm") {
        file.replace(".txt", "-libm.txt")
    } else {
        file.to_string()
    };
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(file);
    if std::env::var_os("CREATURE_BLESS").is_some_and(|v| v == "1") {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, text).unwrap();
        return;
    }
    let stored = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        stored == text,
        "{} differs from the output; if the change is intended, run `cargo xtask bless`, \
         review the diff and add a CHANGELOG line\n--- stored\n{stored}--- now\n{text}",
        path.display()
    );
}
