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
            // Walkers' idle, walk, turn and run (a hopper's hop); the others' two.
            assert_eq!(clips.len(), if kind == d3::Kind::Walker { 4 } else { 2 });
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

#[test]
fn glb_3d_on_terrain_adds_the_terrain_as_a_second_node() {
    use creature::glam::Vec3;
    use creature::terrain::{TerrainParams, terrain, terrain_mesh};
    let c = generate(
        7,
        &d3::Params::DEFAULT
            .with_kind(d3::Kind::Walker)
            .with_clips(false),
    )
    .unwrap();
    let ground = terrain(7, &TerrainParams::DEFAULT.with_extent(20.0, 41)).unwrap();
    let clip = c.bake_to(&ground, Vec3::Z * 2.0, 20.0).unwrap();
    let mesh = terrain_mesh(&ground);
    let clips = [clip];
    let glb = export::glb_3d_on_terrain(&c, &clips, &mesh).unwrap();
    let json_len = u32_at(&glb, 12) as usize;
    let json = String::from_utf8(glb[20..20 + json_len].to_vec()).unwrap();
    // The terrain's material, mesh and node; the creature's scene lists three nodes.
    assert_eq!(json.matches("\"name\":\"terrain\"").count(), 3, "{json}");
    assert!(json.contains("\"name\":\"walk_to\""));
    // The skeleton under a node of its own, the scene's first, beside the two meshes (with its
    // root joint at the top, Blender made the terrain a child of the creature's armature).
    let doc: serde_json::Value = serde_json::from_str(&json).unwrap();
    let nodes = &doc["nodes"];
    let name = |i: &serde_json::Value| nodes[i.as_u64().unwrap() as usize]["name"].clone();
    let top: Vec<_> = doc["scenes"][0]["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .collect();
    let names: Vec<_> = top.iter().map(|&i| name(i)).collect();
    assert_eq!(names, ["rig", "creature", "terrain"], "{json}");
    let rig = &nodes[top[0].as_u64().unwrap() as usize];
    let children: Vec<_> = rig["children"]
        .as_array()
        .unwrap()
        .iter()
        .map(name)
        .collect();
    assert_eq!(children, ["spine_0"], "{json}");
    assert!(glb.len() > export::glb_3d(&c, &clips).unwrap().len());
    // A broken terrain mesh is an error.
    let mut broken = mesh.clone();
    broken.triangles[0][1] = u32::MAX;
    assert!(export::glb_3d_on_terrain(&c, &clips, &broken).is_err());
    let mut empty = mesh;
    empty.triangles.clear();
    assert!(export::glb_3d_on_terrain(&c, &clips, &empty).is_err());
}
