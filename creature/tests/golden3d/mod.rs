//! Golden hashes of 3D creatures and their baked clips: the exact output for 10 fixed seeds per
//! kind, checked in at `tests/golden/3d.txt`.
//!
//! Any change to a creature changes its hash. If the change is intended, regenerate with
//! `cargo xtask bless` (it runs `tests/golden.rs`, which holds this module, with
//! `CREATURE_BLESS=1`), review the diff and add a CHANGELOG line: same seed, same creature is a
//! promise. The hashes are of exact bits with the `std` float backend on x86_64.

use core::fmt::Write as _;
use std::path::PathBuf;

use creature::{Creature, Kind, Params, generate};

const SEEDS: [u64; 10] = [0, 1, 2, 3, 7, 42, 99, 1234, 65_535, u64::MAX];

/// FNV-1a over every number of the creature, in a fixed order.
struct Fnv(u64);

impl Fnv {
    fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn f32s(&mut self, values: impl IntoIterator<Item = f32>) {
        for v in values {
            self.bytes(&v.to_bits().to_le_bytes());
        }
    }
    fn u32s(&mut self, values: impl IntoIterator<Item = u32>) {
        for v in values {
            self.bytes(&v.to_le_bytes());
        }
    }
}

fn hash(c: &Creature) -> u64 {
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    let m = &c.mesh;
    for attribute in [&m.positions, &m.normals, &m.colours] {
        h.f32s(attribute.iter().flat_map(|p| p.to_array()));
    }
    h.u32s(m.indices.iter().flatten().copied());
    h.u32s(m.joints.iter().flatten().map(|&j| u32::from(j)));
    h.f32s(m.weights.iter().flatten().copied());
    for j in &c.skeleton.joints {
        h.f32s(j.position.to_array());
        h.u32s([j.parent.map_or(u32::MAX, |p| p as u32)]);
    }
    for l in &c.plan.limbs {
        h.u32s([l.bone as u32]);
        h.f32s([l.length]);
        h.f32s(l.scale.to_array());
    }
    h.f32s([c.body_scale, c.speed, c.length, c.ground_offset]);
    for clip in &c.clips {
        h.bytes(clip.name.as_bytes());
        h.f32s(clip.root_translation.iter().flat_map(|v| v.to_array()));
        h.f32s(clip.root_rotation.iter().flat_map(|q| q.to_array()));
        for track in &clip.tracks {
            h.u32s([track.joint as u32]);
            for t in track.translations.iter().flatten() {
                h.f32s(t.to_array());
            }
            h.f32s(track.rotations.iter().flat_map(|q| q.to_array()));
        }
    }
    h.0
}

#[test]
fn golden_hashes() {
    let mut text =
        String::from("# kind seed hash vertices triangles joints limbs (cargo xtask bless)\n");
    for (name, kind) in [
        ("walker", Kind::Walker),
        ("flier", Kind::Flier),
        ("swimmer", Kind::Swimmer),
    ] {
        for seed in SEEDS {
            let c = generate(seed, &Params::DEFAULT.with_kind(kind)).unwrap();
            writeln!(
                text,
                "{name} {seed} {:016x} {} {} {} {}",
                hash(&c),
                c.mesh.positions.len(),
                c.mesh.indices.len(),
                c.skeleton.joints.len(),
                c.plan.limbs.len()
            )
            .unwrap();
        }
    }
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden/3d.txt");
    if std::env::var_os("CREATURE_BLESS").is_some_and(|v| v == "1") {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &text).unwrap();
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
