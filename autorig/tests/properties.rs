//! Property tests of the invariants the crate promises, driven by its public strategies.

use creature_autorig::glam::Vec3;
use creature_autorig::{AutorigError, RigOptions, rig, strategies};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;

proptest! {
    #![proptest_config(ProptestConfig {
        cases: cases_or_env(128),
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/properties.txt",
        ))),
        ..ProptestConfig::default()
    })]

    #[test]
    fn rigs_are_well_formed(
        (positions, triangles) in strategies::capsule_body(),
        options in strategies::rig_options(),
    ) {
        let rig = rig(&positions, &triangles, &options).unwrap();
        // One tree, one root, the spine through every joint from tail to head.
        prop_assert!(rig.is_tree());
        prop_assert_eq!(rig.joints.iter().filter(|j| j.parent.is_none()).count(), 1);
        prop_assert_eq!(rig.spine.len(), rig.joints.len());
        prop_assert_eq!(rig.spine.first(), Some(&rig.tail));
        prop_assert_eq!(rig.spine.last(), Some(&rig.head));
        let bones = rig.spine.len() - 1;
        prop_assert!(bones >= options.min_bones && bones <= options.max_bones);
        prop_assert!(rig.joints[rig.head].position.z > rig.joints[rig.tail].position.z);
        // Every joint inside the bounding box.
        let (min, max) = positions
            .iter()
            .fold((positions[0], positions[0]), |(a, b), &p| (a.min(p), b.max(p)));
        for j in &rig.joints {
            prop_assert!(j.position.cmpge(min).all() && j.position.cmple(max).all(), "{}", j.position);
        }
        // Every socket point a mesh vertex; widths and clearances finite and sane.
        prop_assert_eq!(rig.sockets.len(), bones.saturating_sub(2));
        for s in &rig.sockets {
            prop_assert_eq!(positions[s.left_vertex as usize], s.left);
            prop_assert_eq!(positions[s.right_vertex as usize], s.right);
            prop_assert_eq!(positions[s.top_vertex as usize], s.top);
            prop_assert!(s.width.is_finite() && s.width >= 0.0);
            prop_assert!(s.clearance.is_finite() && s.clearance >= 0.0);
            prop_assert!(s.bone >= 1 && s.bone + 1 < bones);
            // Handedness: `left` is on the bone's +X side (the creature's left, facing +Z with
            // +Y up), `right` on its −X side, both square to the bone.
            let [from, to] = rig.spine_bones()[s.bone];
            let left_dir = Vec3::Y.cross(to - from).normalize_or(Vec3::X);
            let spread = (s.left - s.right).dot(left_dir);
            prop_assert!(spread >= -1e-5 * s.width.max(1.0), "{:?}: {}", s, spread);
        }
        // Skinning segments: one per joint with children, aligned with the joint order.
        for (i, (joint, _)) in rig.bones().into_iter().enumerate() {
            prop_assert_eq!(joint, i);
        }
    }

    #[test]
    fn the_tips_are_the_capsule_tips(
        (positions, triangles) in strategies::capsule_body(),
    ) {
        // `capsule_body` puts the tail tip at vertex 0 and the head tip at vertex 1.
        let rig = rig(&positions, &triangles, &RigOptions::default()).unwrap();
        prop_assert_eq!(rig.joints[rig.tail].position, positions[0]);
        prop_assert_eq!(rig.joints[rig.head].position, positions[1]);
    }

    #[test]
    fn rigging_is_deterministic(
        (positions, triangles) in strategies::capsule_body(),
        options in strategies::rig_options(),
    ) {
        prop_assert_eq!(
            rig(&positions, &triangles, &options),
            rig(&positions, &triangles, &options)
        );
    }

    #[test]
    fn non_finite_vertices_are_errors(((positions, triangles), index) in strategies::non_finite_body()) {
        prop_assert_eq!(
            rig(&positions, &triangles, &RigOptions::default()),
            Err(AutorigError::NonFinite { index })
        );
    }

    #[test]
    fn bad_triangles_are_errors(((positions, triangles), triangle) in strategies::bad_triangles()) {
        let result = rig(&positions, &triangles, &RigOptions::default());
        prop_assert!(
            matches!(result, Err(AutorigError::IndexOutOfRange { triangle: t, .. }) if t == triangle),
            "{:?}", result
        );
    }

    #[test]
    fn degenerate_bodies_are_errors(positions in strategies::degenerate_body()) {
        let result = rig(&positions, &[], &RigOptions::default());
        prop_assert!(
            matches!(
                result,
                Err(AutorigError::AllCoincident | AutorigError::Collinear | AutorigError::NoLengthAlongZ)
            ),
            "{:?}", result
        );
    }

    #[test]
    fn adding_a_translation_moves_the_rig(
        (positions, triangles) in strategies::capsule_body(),
        shift in (-3.0f32..3.0, -3.0f32..3.0, -3.0f32..3.0).prop_map(|(x, y, z)| Vec3::new(x, y, z)),
    ) {
        let moved: Vec<Vec3> = positions.iter().map(|&p| p + shift).collect();
        let a = rig(&positions, &triangles, &RigOptions::default()).unwrap();
        let b = rig(&moved, &triangles, &RigOptions::default()).unwrap();
        // The tips are the same vertices, moved.
        prop_assert_eq!(a.joints[a.head].position + shift, b.joints[b.head].position);
        prop_assert_eq!(a.joints[a.tail].position + shift, b.joints[b.tail].position);
        prop_assert_eq!(a.joints.len(), b.joints.len());
        // Joint by joint the rig moves too, except where rounding tips a threshold (which side
        // of the root gets an odd bone out): the spine's length is the same either way.
        let length = a.spine_length();
        prop_assert!((length - b.spine_length()).abs() <= 0.01 * length);
        let same_split = a.joints.iter().zip(&b.joints).all(|(p, q)| p.parent == q.parent)
            && a.children(0).count() == b.children(0).count()
            && a.spine.iter().position(|&j| j == 0) == b.spine.iter().position(|&j| j == 0);
        if same_split {
            for (p, q) in a.joints.iter().zip(&b.joints) {
                prop_assert!(
                    (p.position + shift).distance(q.position) < 1e-3 * length.max(1.0),
                    "{} vs {}", p.position + shift, q.position
                );
            }
        }
    }
}

/// `default` cases, or `PROPTEST_CASES` when set (for longer soaks).
fn cases_or_env(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}
