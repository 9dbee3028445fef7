//! Integration tests through the public API only: a capsule body bound to a three-bone spine.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

use approx::assert_abs_diff_eq;
use creature_skin::glam::{Affine3A, Mat4, Quat, Vec3};
use creature_skin::{
    Blend, Falloff, Influences, NearestOptions, SkinError, from_contributions,
    from_contributions_or, nearest_k, nearest_k_with, report, skin_normals, skin_positions,
};

/// A capsule of radius 0.5 along Z from -2 to 2 (rings of 16 vertices), with outward normals.
fn capsule() -> (Vec<Vec3>, Vec<Vec3>) {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for ring in 0..=20 {
        let z = -2.0 + 4.0 * ring as f32 / 20.0;
        // Round the ends: shrink the radius inside the last 0.5.
        let end = (z.abs() - 1.5).max(0.0);
        let radius = (0.25 - end * end).max(0.0).sqrt();
        for seg in 0..16 {
            let a = seg as f32 / 16.0 * core::f32::consts::TAU;
            let dir = Vec3::new(a.cos(), a.sin(), 0.0);
            positions.push(dir * radius + Vec3::Z * z);
            normals.push((dir * radius + Vec3::Z * z.signum() * end).normalize_or(Vec3::Z));
        }
    }
    (positions, normals)
}

/// Three bones along the capsule's axis, tail to head.
fn spine() -> [[Vec3; 2]; 3] {
    [
        [Vec3::Z * -2.0, Vec3::Z * -0.6],
        [Vec3::Z * -0.6, Vec3::Z * 0.6],
        [Vec3::Z * 0.6, Vec3::Z * 2.0],
    ]
}

#[test]
fn a_capsule_binds_cleanly_to_its_spine() {
    let (positions, _) = capsule();
    let influences = nearest_k(&positions, &spine(), 4).unwrap();
    let r = report(&influences);
    assert!(r.is_clean(1e-6), "{r:?}");
    // Three bones: nobody uses four.
    assert_eq!(r.histogram[4], 0);
    // Vertices around the middle of the capsule belong to the middle bone.
    for (p, inf) in positions.iter().zip(&influences) {
        if p.z.abs() < 0.1 {
            assert_eq!(inf.joints[0], 1, "{p}");
        }
        if p.z > 1.0 {
            assert_eq!(inf.joints[0], 2, "{p}");
        }
    }
    // And the weights are glTF-ready.
    for inf in &influences {
        let q = inf.quantize_u8();
        assert_eq!(q.iter().map(|&v| u32::from(v)).sum::<u32>(), 255);
    }
}

#[test]
fn bending_the_head_bone_moves_only_the_front() {
    let (positions, normals) = capsule();
    let influences = nearest_k(&positions, &spine(), 4).unwrap();
    // Turn the head bone 60° about +Y around its head joint at z = 0.6.
    let pivot = Vec3::Z * 0.6;
    let turn = Affine3A::from_translation(pivot)
        * Affine3A::from_quat(Quat::from_rotation_y(1.0))
        * Affine3A::from_translation(-pivot);
    let transforms = [Affine3A::IDENTITY, Affine3A::IDENTITY, turn];
    for blend in [Blend::Linear, Blend::DualQuaternion] {
        let mut moved = vec![Vec3::ZERO; positions.len()];
        skin_positions(&positions, &influences, &transforms, blend, &mut moved).unwrap();
        for (p, m) in positions.iter().zip(&moved) {
            if p.z < -1.0 {
                // The tail end is bound (almost) only to the still bones.
                assert!(p.distance(*m) < 0.02, "{blend:?}: {p} moved to {m}");
            }
            if p.z > 1.9 {
                assert_abs_diff_eq!(*m, turn.transform_point3(*p), epsilon = 0.05);
            }
        }
        let mut turned = vec![Vec3::ZERO; normals.len()];
        skin_normals(&normals, &influences, &transforms, blend, &mut turned).unwrap();
        for n in &turned {
            assert_abs_diff_eq!(n.length(), 1.0, epsilon = 1e-5);
        }
    }
}

#[test]
fn mat4_skinning_matrices_convert_losslessly() {
    let (positions, _) = capsule();
    let influences = nearest_k(&positions, &spine(), 2).unwrap();
    let mats = [
        Mat4::IDENTITY,
        Mat4::from_translation(Vec3::Y),
        Mat4::from_rotation_x(0.3),
    ];
    let affines: Vec<Affine3A> = mats.iter().map(|&m| Affine3A::from_mat4(m)).collect();
    let mut out = vec![Vec3::ZERO; positions.len()];
    skin_positions(&positions, &influences, &affines, Blend::Linear, &mut out).unwrap();
    for ((p, inf), o) in positions.iter().zip(&influences).zip(&out) {
        let expected: Vec3 = inf
            .iter()
            .map(|(j, w)| mats[usize::from(j)].transform_point3(*p) * w)
            .sum();
        assert_abs_diff_eq!(*o, expected, epsilon = 1e-5);
    }
}

#[test]
fn a_metaball_field_binds_like_the_2d_seed() {
    // Balls along two bones; each ball contributes exp(-0.5 r²/R² + 0.5) to its bone.
    let balls: Vec<(Vec3, f32, u32)> = (0..8)
        .map(|i| (Vec3::new(i as f32 * 0.4, 0.0, 0.0), 0.3, u32::from(i >= 4)))
        .collect();
    let field = |p: Vec3| {
        balls
            .iter()
            .map(move |&(c, r, bone)| (bone, (-0.5 * p.distance_squared(c) / (r * r) + 0.5).exp()))
    };
    let left = from_contributions(field(Vec3::new(0.2, 0.2, 0.0)), 4).unwrap();
    let right = from_contributions(field(Vec3::new(2.8, 0.2, 0.0)), 4).unwrap();
    let middle = from_contributions(field(Vec3::new(1.4, 0.3, 0.0)), 4).unwrap();
    assert_eq!(left.joints[0], 0);
    assert!(left.weights[0] > 0.99);
    assert_eq!(right.joints[0], 1);
    assert_abs_diff_eq!(middle.weights[0], 0.5, epsilon = 1e-3);
    // Far from every ball the field underflows to zero: the fallback binds it.
    let far = from_contributions_or(field(Vec3::new(0.0, 1e4, 0.0)), 4, 1).unwrap();
    assert_eq!(far, Influences::single(1));
    assert_eq!(
        from_contributions(field(Vec3::new(0.0, 1e4, 0.0)), 4),
        Err(SkinError::ZeroContribution)
    );
}

#[test]
fn inverse_distance_weights_bind_a_capsule_but_leak_far() {
    let (positions, _) = capsule();
    let options = NearestOptions::default().with_falloff(Falloff::InverseDistance { power: 2.0 });
    let influences = nearest_k_with(&positions, &spine(), &options).unwrap();
    assert!(report(&influences).is_clean(1e-6));
    // Every vertex keeps some weight on all three bones, however far: the head bone tugs at
    // the tail tip. The default smooth falloff gives it exactly zero there.
    // (Except vertices exactly on the axis, at a tip, which lie on a bone.)
    let on_axis = positions
        .iter()
        .filter(|p| p.x == 0.0 && p.y == 0.0)
        .count();
    assert_eq!(report(&influences).histogram[3], positions.len() - on_axis);
    let default = nearest_k(&positions, &spine(), 4).unwrap();
    let tail_tip = positions
        .iter()
        .position(|p| p.z < -1.7 && p.x > 0.1)
        .unwrap();
    assert!(influences[tail_tip].weight_of(2) > 0.01);
    assert_eq!(default[tail_tip].weight_of(2), 0.0);
}

#[test]
fn errors_name_the_culprit() {
    let (mut positions, _) = capsule();
    positions[7].y = f32::NAN;
    let err = nearest_k(&positions, &spine(), 4).unwrap_err();
    assert_eq!(
        err,
        SkinError::NonFinite {
            what: "vertex",
            index: 7
        }
    );
    assert!(err.to_string().contains("vertex 7"));
}

/// Issue 17, finding 8: linear skinning of normals returned 0.9978 or 1.0139 long for tiny
/// normals and extreme matrices (squared lengths outside the normal `f32` range).
#[test]
fn regression_skinned_normals_are_unit_at_extreme_scales() {
    let influences = [Influences::single(0)];
    for (scale, normal) in [
        (1.0, Vec3::new(2e-22, 1e-22, 0.0)),
        (1e15, Vec3::new(0.3, -0.5, 0.8)),
        (1e12, Vec3::new(2e-22, 0.0, 1e-22)),
    ] {
        let transforms = [Affine3A::from_scale(Vec3::new(scale, 2.0 * scale, scale))];
        let mut out = [Vec3::ZERO];
        skin_normals(&[normal], &influences, &transforms, Blend::Linear, &mut out).unwrap();
        assert!(
            out[0].is_normalized(),
            "{scale} {normal} Linear: {}",
            out[0].length()
        );
    }
}
