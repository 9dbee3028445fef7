//! `creature-skin`: `nearest_k_with` and `from_contributions(_or)` weights (summing to 1 within
//! 1e-5, valid joints, exact glTF quantisation sums), then `skin_positions` and `skin_normals`
//! (linear and dual quaternion) with arbitrary transforms: finite results, unit normals.

use arbitrary::Arbitrary;
use creature_skin::{
    Blend, Falloff, Influences, NearestOptions, from_contributions, from_contributions_or,
    nearest_k_with, skin_normals, skin_positions,
};
use glam::{Affine3A, Mat3A, Quat, Vec3, Vec3A};

use crate::{pick, pick3};

#[derive(Debug, Clone, Arbitrary)]
pub struct Transform {
    pub rotation: [f32; 4],
    pub scale: [f32; 3],
    pub translation: [f32; 3],
    /// Used as the whole 3×4 matrix in the arbitrary flavour.
    pub extra: [f32; 2],
}

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub valid: bool,
    pub dual_quaternion: bool,
    pub k: u8,
    pub inverse_distance: bool,
    pub falloff: f32,
    pub bones: Vec<([f32; 3], [f32; 3])>,
    pub transforms: Vec<Transform>,
    pub contributions: Vec<(u16, f32)>,
    pub vertices: Vec<([f32; 3], [f32; 3])>,
}

fn transform(v: bool, t: &Transform) -> Affine3A {
    if v {
        let q = Quat::from_array(t.rotation.map(|x| pick(true, x, -1.0, 1.0)));
        let q = if q.length() > 1e-3 {
            q.normalize()
        } else {
            Quat::IDENTITY
        };
        Affine3A::from_scale_rotation_translation(
            pick3(true, t.scale, 0.25, 4.0),
            q,
            pick3(true, t.translation, -10.0, 10.0),
        )
    } else {
        let [a, b, c, d] = t.rotation;
        let [e, f, g] = t.scale;
        let [h, i, j] = t.translation;
        let [k, l] = t.extra;
        Affine3A {
            matrix3: Mat3A::from_cols(
                Vec3A::new(a, b, c),
                Vec3A::new(d, e, f),
                Vec3A::new(g, h, i),
            ),
            translation: Vec3A::new(j, k, l),
        }
    }
}

fn check_influences(inf: &Influences, joints: usize) {
    crate::check_weights(inf.weights, inf.joints, joints);
    assert_eq!(
        inf.quantize_u8().iter().map(|&x| u32::from(x)).sum::<u32>(),
        255,
        "{inf:?}"
    );
    assert_eq!(
        inf.quantize_u16()
            .iter()
            .map(|&x| u32::from(x))
            .sum::<u32>(),
        65535,
        "{inf:?}"
    );
}

pub fn run(input: &Input) {
    let v = input.valid;
    let k = if v {
        usize::from(input.k % 4) + 1
    } else {
        usize::from(input.k)
    };
    let bones: Vec<[Vec3; 2]> = input
        .bones
        .iter()
        .take(32)
        .map(|(a, b)| [pick3(v, *a, -5.0, 5.0), pick3(v, *b, -5.0, 5.0)])
        .collect();
    let vertices: Vec<Vec3> = input
        .vertices
        .iter()
        .take(64)
        .map(|(p, _)| pick3(v, *p, -6.0, 6.0))
        .collect();
    let normals: Vec<Vec3> = input
        .vertices
        .iter()
        .take(64)
        .map(|(_, n)| pick3(v, *n, -1.0, 1.0))
        .collect();
    let parameter = pick(v, input.falloff, 0.1, 4.0);
    let falloff = if input.inverse_distance {
        Falloff::InverseDistance { power: parameter }
    } else {
        Falloff::Smooth { spread: parameter }
    };
    let options = NearestOptions::DEFAULT.with_k(k).with_falloff(falloff);
    let result = nearest_k_with(&vertices, &bones, &options);
    assert_eq!(
        format!("{:?}", nearest_k_with(&vertices, &bones, &options)),
        format!("{result:?}"),
        "determinism"
    );
    if v && !bones.is_empty() {
        assert!(
            result.is_ok(),
            "valid bones and vertices rejected: {result:?}"
        );
    }
    if let Ok(influences) = &result {
        assert_eq!(influences.len(), vertices.len());
        for inf in influences {
            assert!(inf.count() <= k);
            check_influences(inf, bones.len());
        }
    }
    // Contributions, as a metaball field gives them.
    let pairs: Vec<(u32, f32)> = input
        .contributions
        .iter()
        .take(32)
        .map(|&(bone, value)| {
            (
                u32::from(bone % if v { 16 } else { u16::MAX }),
                pick(v, value, 0.0, 2.0),
            )
        })
        .collect();
    if let Ok(inf) = from_contributions(pairs.iter().copied(), k) {
        check_influences(&inf, usize::MAX);
        for (j, w) in inf.iter() {
            assert!(
                w == 0.0 || pairs.iter().any(|&(b, c)| b == u32::from(j) && c > 0.0),
                "joint {j} has no contribution"
            );
        }
    }
    if let Ok(inf) = from_contributions_or(pairs.iter().copied(), k, 3) {
        check_influences(&inf, usize::MAX);
    }
    // Skinning with the nearest-bone influences.
    let Ok(influences) = result else {
        return;
    };
    let transforms: Vec<Affine3A> = input
        .transforms
        .iter()
        .take(32)
        .map(|t| transform(v, t))
        .collect();
    let blend = if input.dual_quaternion {
        Blend::DualQuaternion
    } else {
        Blend::Linear
    };
    let mut out = vec![Vec3::ZERO; vertices.len()];
    let positions = skin_positions(&vertices, &influences, &transforms, blend, &mut out);
    if positions.is_ok() {
        assert!(
            out.iter().all(|p| p.is_finite()),
            "non-finite skinned position"
        );
        let mut again = vec![Vec3::ZERO; vertices.len()];
        skin_positions(&vertices, &influences, &transforms, blend, &mut again).unwrap();
        assert_eq!(out, again, "determinism");
    } else if v && transforms.len() >= bones.len() {
        panic!("valid skinning rejected: {positions:?}");
    }
    let mut out = vec![Vec3::ZERO; normals.len()];
    if skin_normals(&normals, &influences, &transforms, blend, &mut out).is_ok() {
        for (n, rest) in out.iter().zip(&normals) {
            if *rest == Vec3::ZERO {
                assert_eq!(*n, Vec3::ZERO);
            } else {
                assert!(
                    n.is_finite() && n.is_normalized(),
                    "skinned normal {n} (length {}) of {rest}",
                    n.length()
                );
            }
        }
    }
}
