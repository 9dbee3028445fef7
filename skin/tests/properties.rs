//! Property tests of the invariants the crate promises, driven by its public strategies.

use creature_skin::glam::{Affine3A, Vec3};
use creature_skin::{
    Blend, Falloff, Influences, NearestOptions, SkinError, from_contributions, nearest_k,
    nearest_k_with, skin_normals, skin_positions, strategies,
};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;

/// The invariants every binding must satisfy.
fn check_binding(inf: &Influences, k: usize, bones: usize) -> Result<(), TestCaseError> {
    prop_assert!((inf.weight_sum() - 1.0).abs() <= 1e-6, "sum {:?}", inf);
    prop_assert!(
        inf.weights.windows(2).all(|p| p[0] >= p[1]),
        "unsorted {:?}",
        inf
    );
    // Equal weights by joint index, smallest first.
    for s in 0..3 {
        if inf.weights[s] == inf.weights[s + 1] && inf.weights[s] > 0.0 {
            prop_assert!(inf.joints[s] < inf.joints[s + 1], "tie order {:?}", inf);
        }
    }
    prop_assert!(inf.count() >= 1 && inf.count() <= k, "count {:?}", inf);
    for (slot, (&j, &w)) in inf.joints.iter().zip(&inf.weights).enumerate() {
        prop_assert!(w.is_finite() && w >= 0.0);
        prop_assert!(usize::from(j) < bones, "joint {} of {}", j, bones);
        if w == 0.0 {
            prop_assert_eq!(j, 0, "empty slot {} keeps a joint", slot);
        }
    }
    check_quantised(inf)
}

fn check_quantised(inf: &Influences) -> Result<(), TestCaseError> {
    let q8 = inf.quantize_u8();
    let q16 = inf.quantize_u16();
    prop_assert_eq!(q8.iter().map(|&v| u32::from(v)).sum::<u32>(), 255);
    prop_assert_eq!(q16.iter().map(|&v| u32::from(v)).sum::<u32>(), 65535);
    for a in 0..4 {
        for b in 0..4 {
            // A larger weight never gets fewer units (equal weights may differ by one unit:
            // 255 does not split evenly, and the lower slot wins the tie).
            if inf.weights[a] > inf.weights[b] || (inf.weights[a] == inf.weights[b] && a < b) {
                prop_assert!(q8[a] >= q8[b], "order lost: {:?} -> {:?}", inf.weights, q8);
                prop_assert!(
                    q16[a] >= q16[b],
                    "order lost: {:?} -> {:?}",
                    inf.weights,
                    q16
                );
            }
        }
        // Never more than one unit from the exact share.
        prop_assert!((f32::from(q8[a]) - inf.weights[a] * 255.0).abs() < 1.0 + 1e-3);
        prop_assert!((f32::from(q16[a]) - inf.weights[a] * 65535.0).abs() < 1.0 + 0.1);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: cases_or_env(256),
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/properties.txt",
        ))),
        ..ProptestConfig::default()
    })]

    #[test]
    fn nearest_k_weights_are_normalised_sorted_and_in_range(
        vertices in strategies::vertices(40),
        bones in strategies::bones(12),
        k in strategies::k(),
        smooth in any::<bool>(),
        parameter in 0.2f32..4.0,
    ) {
        let falloff = if smooth {
            Falloff::Smooth { spread: parameter }
        } else {
            Falloff::InverseDistance { power: parameter }
        };
        let options = NearestOptions::DEFAULT.with_k(k).with_falloff(falloff);
        let influences = nearest_k_with(&vertices, &bones, &options).unwrap();
        prop_assert_eq!(influences.len(), vertices.len());
        for (v, inf) in vertices.iter().zip(&influences) {
            check_binding(inf, k, bones.len())?;
            // Every bone used is among the k nearest (checked by brute force).
            let distance = |b: usize| creature_skin::distance_to_bone(*v, bones[b]);
            let mut all: Vec<f32> = (0..bones.len()).map(distance).collect();
            all.sort_by(f32::total_cmp);
            let kth = all[k.min(bones.len()) - 1];
            for (j, _) in inf.iter() {
                prop_assert!(distance(usize::from(j)) <= kth, "{:?} at {}", inf, v);
            }
        }
        prop_assert!(creature_skin::report(&influences).is_clean(1e-6));
    }

    #[test]
    fn the_first_joint_is_a_nearest_bone(
        vertices in strategies::vertices(20),
        bones in strategies::bones(12),
    ) {
        let influences = nearest_k(&vertices, &bones, 4).unwrap();
        for (v, inf) in vertices.iter().zip(&influences) {
            // The nearest bone has the largest weight. (It need not be in the first slot: when
            // two weights are equal in f32, the smaller joint index comes first.)
            let distance = |b: usize| creature_skin::distance_to_bone(*v, bones[b]);
            let nearest = (0..bones.len())
                .min_by(|&a, &b| distance(a).total_cmp(&distance(b)))
                .unwrap();
            let first = distance(usize::from(inf.joints[0]));
            prop_assert!(
                first <= distance(nearest) + 1e-5 || inf.weight_of(nearest as u16) == inf.weights[0],
                "{:?}", inf
            );
        }
    }

    #[test]
    fn a_vertex_near_only_one_bone_takes_it_whole(
        bones in 2usize..12,
        chosen in 0usize..12,
        along in 0.0f32..1.0,
        offset in strategies::vec3_in(0.01),
        k in strategies::k(),
    ) {
        // Bones on a line of cells 100 apart; the vertex within 0.02 of one of them.
        let bone_list: Vec<[Vec3; 2]> = (0..bones)
            .map(|i| {
                let head = Vec3::new(100.0 * i as f32, 0.0, 0.0);
                [head, head + Vec3::new(3.0, 4.0, 5.0)]
            })
            .collect();
        let chosen = chosen % bones;
        let [head, tail] = bone_list[chosen];
        let vertex = head.lerp(tail, along) + offset;
        let inf = nearest_k(&[vertex], &bone_list, k).unwrap()[0];
        prop_assert_eq!(usize::from(inf.joints[0]), chosen);
        prop_assert!(inf.weights[0] >= 1.0 - 1e-6, "{:?}", inf);
    }

    #[test]
    fn mirrored_input_gives_mirrored_weights(
        spine in prop::collection::vec((strategies::vec3_in(5.0), strategies::vec3_in(2.0)), 1..4),
        limbs in prop::collection::vec((strategies::vec3_in(5.0), strategies::vec3_in(2.0)), 0..3),
        vertex in strategies::vec3_in(8.0),
        k in strategies::k(),
    ) {
        // Spine bones on the plane x = 0, limb bones in left/right pairs; the vertex off the
        // plane so that no left/right pair ties.
        prop_assume!(vertex.x.abs() > 0.01);
        let mirror = |v: Vec3| Vec3::new(-v.x, v.y, v.z);
        let flat = |v: Vec3| Vec3::new(0.0, v.y, v.z);
        let mut bones: Vec<[Vec3; 2]> =
            spine.iter().map(|&(h, d)| [flat(h), flat(h + d)]).collect();
        let spine_count = bones.len();
        for &(h, d) in &limbs {
            let h = Vec3::new(h.x.abs() + 0.5, h.y, h.z);
            bones.push([h, h + d]);
            bones.push([mirror(h), mirror(h + d)]);
        }
        // Mirroring swaps each left/right pair; spine bones map to themselves.
        let partner = |j: u16| -> u16 {
            let j = usize::from(j);
            if j < spine_count { j as u16 } else { (spine_count + ((j - spine_count) ^ 1)) as u16 }
        };
        let both = nearest_k(&[vertex, mirror(vertex)], &bones, k).unwrap();
        for (j, w) in both[0].iter() {
            let mirrored = both[1].weight_of(partner(j));
            prop_assert!((w - mirrored).abs() <= 1e-6, "joint {}: {} vs {}", j, w, mirrored);
        }
        prop_assert_eq!(both[0].count(), both[1].count());
    }

    #[test]
    fn weights_do_not_depend_on_scale(
        vertices in strategies::vertices(10),
        bones in strategies::bones(6),
        scale in prop_oneof![Just(0.5f32), Just(2.0f32), Just(0.125f32)],
    ) {
        // Powers of two scale exactly, so the result must be identical.
        let scaled_vertices: Vec<Vec3> = vertices.iter().map(|&v| v * scale).collect();
        let scaled_bones: Vec<[Vec3; 2]> =
            bones.iter().map(|b| [b[0] * scale, b[1] * scale]).collect();
        prop_assert_eq!(
            nearest_k(&vertices, &bones, 4).unwrap(),
            nearest_k(&scaled_vertices, &scaled_bones, 4).unwrap()
        );
    }

    #[test]
    fn contributions_keep_the_top_k_totals(
        pairs in strategies::contributions(10),
        k in strategies::k(),
    ) {
        let inf = from_contributions(pairs.iter().copied(), k).unwrap();
        check_binding(&inf, k, 10)?;
        let mut totals = [0.0f64; 10];
        for &(b, v) in &pairs {
            totals[b as usize] += f64::from(v);
        }
        let kept_min = inf
            .iter()
            .map(|(j, _)| totals[usize::from(j)])
            .fold(f64::INFINITY, f64::min);
        for (bone, &total) in totals.iter().enumerate() {
            if inf.weight_of(bone as u16) == 0.0 {
                prop_assert!(total <= kept_min, "bone {} ({}) beats a kept one ({})", bone, total, kept_min);
            }
        }
        // Kept weights are in the totals' proportions.
        let (j0, w0) = inf.iter().next().unwrap();
        for (j, w) in inf.iter() {
            let expected = totals[usize::from(j)] / totals[usize::from(j0)];
            prop_assert!((f64::from(w / w0) - expected).abs() <= 1e-5 * expected.max(1.0));
        }
    }

    #[test]
    fn any_influences_quantise_exactly(inf in strategies::influences(20)) {
        check_quantised(&inf)?;
    }

    #[test]
    fn identity_transforms_return_the_rest_mesh(
        vertices in strategies::vertices(30),
        bones in strategies::bones(8),
        dual in any::<bool>(),
    ) {
        let influences = nearest_k(&vertices, &bones, 4).unwrap();
        let transforms = vec![Affine3A::IDENTITY; bones.len()];
        let blend = if dual { Blend::DualQuaternion } else { Blend::Linear };
        let mut out = vec![Vec3::ZERO; vertices.len()];
        skin_positions(&vertices, &influences, &transforms, blend, &mut out).unwrap();
        prop_assert_eq!(&out, &vertices);
        let normals: Vec<Vec3> = vertices.iter().map(|v| v.normalize_or(Vec3::Y)).collect();
        skin_normals(&normals, &influences, &transforms, blend, &mut out).unwrap();
        for (n, m) in normals.iter().zip(&out) {
            prop_assert!(n.distance(*m) <= 1e-6, "{} vs {}", n, m);
        }
    }

    #[test]
    fn dual_quaternions_and_linear_agree_on_translations(
        vertices in strategies::vertices(30),
        bones in strategies::bones(8),
        shifts in prop::collection::vec(strategies::vec3_in(10.0), 8),
    ) {
        let influences = nearest_k(&vertices, &bones, 4).unwrap();
        let transforms: Vec<Affine3A> =
            shifts.iter().take(bones.len()).map(|&t| Affine3A::from_translation(t)).collect();
        let mut lbs = vec![Vec3::ZERO; vertices.len()];
        let mut dqs = vec![Vec3::ZERO; vertices.len()];
        skin_positions(&vertices, &influences, &transforms, Blend::Linear, &mut lbs).unwrap();
        skin_positions(&vertices, &influences, &transforms, Blend::DualQuaternion, &mut dqs).unwrap();
        for (a, b) in lbs.iter().zip(&dqs) {
            prop_assert!(a.distance(*b) <= 1e-4, "{} vs {}", a, b);
        }
    }

    #[test]
    fn a_single_rigid_joint_moves_vertices_rigidly(
        vertices in strategies::vertices(20),
        transform in strategies::rigid_transform(),
        dual in any::<bool>(),
    ) {
        let influences = vec![Influences::single(0); vertices.len()];
        let blend = if dual { Blend::DualQuaternion } else { Blend::Linear };
        let mut out = vec![Vec3::ZERO; vertices.len()];
        skin_positions(&vertices, &influences, &[transform], blend, &mut out).unwrap();
        for (v, o) in vertices.iter().zip(&out) {
            prop_assert!(o.distance(transform.transform_point3(*v)) <= 1e-4);
        }
    }

    #[test]
    fn skinned_normals_are_unit_length(
        normals in prop::collection::vec(strategies::vec3_in(1.0), 0..20),
        influences in prop::collection::vec(strategies::influences(4), 20),
        transforms in prop::collection::vec(strategies::rigid_transform(), 4),
        dual in any::<bool>(),
    ) {
        let influences = &influences[..normals.len()];
        let blend = if dual { Blend::DualQuaternion } else { Blend::Linear };
        let mut out = vec![Vec3::ZERO; normals.len()];
        skin_normals(&normals, influences, &transforms, blend, &mut out).unwrap();
        for (n, o) in normals.iter().zip(&out) {
            if n.length() > 1e-3 {
                prop_assert!((o.length() - 1.0).abs() <= 1e-5, "{}", o);
            }
        }
    }

    #[test]
    fn non_finite_input_is_an_error(
        vertices in strategies::vertices(10),
        bones in strategies::bones(5),
        bad in strategies::non_finite_vec3(),
        at_bone in any::<bool>(),
    ) {
        let (mut vertices, mut bones) = (vertices, bones);
        let result = if at_bone {
            bones[0][1] = bad;
            nearest_k(&vertices, &bones, 4)
        } else {
            vertices.push(bad);
            nearest_k(&vertices, &bones, 4)
        };
        prop_assert!(matches!(result, Err(SkinError::NonFinite { .. })), "{:?}", result);
    }

    #[test]
    fn bad_k_is_an_error(k in strategies::bad_k(), bones in strategies::bones(3)) {
        prop_assert_eq!(
            nearest_k(&[Vec3::ZERO], &bones, k),
            Err(SkinError::InvalidInfluenceCount { k })
        );
        prop_assert_eq!(
            from_contributions([(0, 1.0)], k),
            Err(SkinError::InvalidInfluenceCount { k })
        );
    }

    #[test]
    fn bad_weights_are_an_error(inf in strategies::bad_influences(3)) {
        let mut out = [Vec3::ZERO];
        let transforms = [Affine3A::IDENTITY; 3];
        for blend in [Blend::Linear, Blend::DualQuaternion] {
            prop_assert_eq!(
                skin_positions(&[Vec3::ONE], &[inf], &transforms, blend, &mut out),
                Err(SkinError::InvalidWeights { vertex: 0 })
            );
        }
        let report = creature_skin::report(&[inf]);
        prop_assert_eq!(report.invalid, vec![0]);
    }
}

/// `default` cases, or `PROPTEST_CASES` when set (for longer soaks).
fn cases_or_env(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}
