//! `creature-autorig`: `rig` on arbitrary point clouds and triangle lists with arbitrary
//! options. A rig is a tree with finite joints, its bone count within the options, one socket
//! per bone but the first and last (with valid vertex indices and finite measures).

use arbitrary::Arbitrary;
use creature_autorig::{RigOptions, RootAt, rig};
use glam::Vec3;

use crate::{map, pick};

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub valid: bool,
    pub head_root: bool,
    pub follow: bool,
    pub centre_tolerance: f32,
    pub bone_length: f32,
    pub bones: [u16; 2],
    pub triangles: Vec<[u16; 3]>,
    pub positions: Vec<[f32; 3]>,
}

pub fn run(input: &Input) {
    let v = input.valid;
    let positions: Vec<Vec3> = input
        .positions
        .iter()
        .take(300)
        .map(|p| {
            if v {
                // A blob elongated along Z, as bodies are.
                Vec3::new(
                    map(p[0], -1.0, 1.0),
                    map(p[1], -1.0, 1.0),
                    map(p[2], -4.0, 4.0),
                )
            } else {
                Vec3::from(*p)
            }
        })
        .collect();
    let n = positions.len().max(1) as u32;
    let triangles: Vec<[u32; 3]> = input
        .triangles
        .iter()
        .take(300)
        .map(|t| t.map(|i| if v { u32::from(i) % n } else { u32::from(i) }))
        .collect();
    let (min_bones, max_bones) = if v {
        let min = usize::from(input.bones[0] % 6) + 2;
        (min, min + usize::from(input.bones[1] % 24))
    } else {
        (usize::from(input.bones[0]), usize::from(input.bones[1]))
    };
    let options = RigOptions::DEFAULT
        .with_root(if input.head_root {
            RootAt::Head
        } else {
            RootAt::Centre
        })
        .with_centre_tolerance(pick(v, input.centre_tolerance, 0.01, 1.0))
        .with_bone_length(pick(v, input.bone_length, 0.05, 4.0))
        .with_bone_count(min_bones, max_bones)
        .with_follow_medial_line(input.follow);
    let result = rig(&positions, &triangles, &options);
    assert_eq!(
        format!("{:?}", rig(&positions, &triangles, &options)),
        format!("{result:?}"),
        "determinism"
    );
    let Ok(r) = result else {
        return;
    };
    assert!(r.is_tree(), "not a tree: {r:?}");
    assert!(r.root().is_some());
    assert!(
        r.joints.iter().all(|j| j.position.is_finite()),
        "non-finite joint"
    );
    assert!(r.head < r.joints.len() && r.tail < r.joints.len());
    let bones = r.spine.len() - 1;
    assert!(
        (options.min_bones..=options.max_bones).contains(&bones),
        "{bones} bones outside {}..={}",
        options.min_bones,
        options.max_bones
    );
    assert!(r.spine.iter().all(|&j| j < r.joints.len()));
    assert_eq!(
        r.sockets.len(),
        bones.saturating_sub(2),
        "one socket per bone but the first and last"
    );
    for s in &r.sockets {
        assert!(
            s.left.is_finite() && s.right.is_finite() && s.top.is_finite(),
            "{s:?}"
        );
        assert!(
            s.width.is_finite() && s.width >= 0.0 && s.clearance.is_finite(),
            "{s:?}"
        );
        assert!(
            [s.left_vertex, s.right_vertex, s.top_vertex]
                .iter()
                .all(|&i| (i as usize) < positions.len())
        );
        assert!(s.joint < r.joints.len());
    }
    assert!(r.spine_length().is_finite());
}
