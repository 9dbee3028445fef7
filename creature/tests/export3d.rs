//! glTF export of 3D creatures (feature `export`). With `CREATURE_GLB_DIR` set, writes
//! `walker-N.glb`, `flier-N.glb` and `swimmer-N.glb` there for `cargo xtask verify-gltf DIR`.

#![cfg(feature = "export")]
#![allow(clippy::unwrap_used)]

use creature::{d3, export, generate};

fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
}

#[test]
fn glb_3d_is_a_well_formed_skinned_container() {
    let dir = std::env::var_os("CREATURE_GLB_DIR");
    for (name, kind) in [
        ("walker", d3::Kind::Walker),
        ("flier", d3::Kind::Flier),
        ("swimmer", d3::Kind::Swimmer),
    ] {
        for seed in 0..4 {
            let c = generate(seed, &d3::Params::DEFAULT.with_kind(kind)).unwrap();
            let clips = c.clips.clone();
            assert_eq!(clips, c.bake_clips().unwrap());
            assert_eq!(clips.len(), if kind == d3::Kind::Walker { 3 } else { 2 });
            let glb = export::glb_3d(&c, &clips).unwrap();
            assert_eq!(&glb[0..4], b"glTF");
            assert_eq!(u32_at(&glb, 8) as usize, glb.len());
            let json_len = u32_at(&glb, 12) as usize;
            let json = String::from_utf8(glb[20..20 + json_len].to_vec()).unwrap();
            for key in [
                "\"skins\"",
                "\"inverseBindMatrices\"",
                "\"JOINTS_0\"",
                "\"WEIGHTS_0\"",
                "\"COLOR_0\"",
                "\"NORMAL\"",
            ] {
                assert!(json.contains(key), "{key} missing");
            }
            for joint in &c.skeleton.joints {
                let node = format!("\"name\":\"{}\"", joint.name);
                assert_eq!(json.matches(&node).count(), 1, "{node}");
            }
            for clip in &clips {
                assert!(json.contains(&format!("\"name\":\"{}\"", clip.name)));
            }
            assert_eq!(glb, export::glb_3d(&c, &clips).unwrap());
            if let Some(dir) = &dir {
                let path = std::path::Path::new(dir).join(format!("{name}-{seed}.glb"));
                std::fs::write(path, &glb).unwrap();
            }
        }
    }
}
