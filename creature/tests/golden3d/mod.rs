//! Golden hashes of 3D creatures and their baked clips: the exact output for 10 fixed seeds per
//! kind, checked in at `tests/golden/3d.txt`.
//!
//! Any change to a creature changes its hash. If the change is intended, regenerate with
//! `cargo xtask bless` (it runs `tests/golden.rs`, which holds this module, with
//! `CREATURE_BLESS=1`), review the diff and add a CHANGELOG line: same seed, same creature is a
//! promise. The hashes are of exact bits with the `std` float backend on x86_64.

use core::fmt::Write as _;
use creature::{d3, generate};

use super::{Fnv, SEEDS, check_or_bless};

fn hash(c: &d3::Creature) -> u64 {
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
        ("walker", d3::Kind::Walker),
        ("flier", d3::Kind::Flier),
        ("swimmer", d3::Kind::Swimmer),
        ("slitherer", d3::Kind::Slitherer),
    ] {
        for seed in SEEDS {
            let c = generate(seed, &d3::Params::DEFAULT.with_kind(kind)).unwrap();
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
    check_or_bless("3d.txt", &text);
}
