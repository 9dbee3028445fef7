//! The seed's skeleton generator (reference §2.3), with limbs that stay attached.

use alloc::vec::Vec;
use core::f32::consts::{FRAC_PI_2, TAU};

use crate::rng::{rng_for, uniform};
use glam::{Vec2, Vec3};
use rand_core::Rng;

use super::Params;
use crate::Error;
use crate::d2::{Bone, BoneKind, Eye, Skeleton};

fn colour(rng: &mut impl Rng) -> Vec3 {
    let r = uniform(rng);
    let g = uniform(rng);
    let b = uniform(rng);
    Vec3::new(r, g, b)
}

/// [`skeleton`] with the generator [`generate_2d`](crate::generate_2d) uses for `seed`.
///
/// # Errors
/// As [`skeleton`].
pub fn skeleton_from_seed(seed: u64, params: &Params) -> Result<Skeleton, Error> {
    skeleton(&mut rng_for(seed), params)
}

/// Draws a skeleton the 2D seed's way (reference §2.3, thesis §4.1):
///
/// - a straight spine along +y from the root (the tail tip, at the origin, no thickness):
///   [`Params::spine_bones`] bones, each segment with its thickness, length, colour, texture
///   weights `(a, 1 − a)` and multiplier; the last bone is the head;
/// - eyes on a circle inside the head;
/// - for every spine bone (the root included), with [`Params::limb_probability`], a
///   mirrored limb pair: a socket joint at `±socket_offset × max(T_i, T_i+1)` along x, then
///   straight segments along ±x, each side with its own colours.
///
/// Bones are stored as the seed stores them: the spine, then for each spine bone with limbs
/// the left limb's bones (−x), then the right limb's.
///
/// ```
/// use creature::d2::{skeleton, BoneKind, Params};
/// use creature::rand_pcg::Pcg64Mcg;
/// use creature::rand_core::SeedableRng;
///
/// let mut rng = Pcg64Mcg::seed_from_u64(42);
/// let skeleton = skeleton(&mut rng, &Params::DEFAULT)?;
/// assert_eq!(skeleton.bones[0].kind, BoneKind::Root);
/// assert!(skeleton.bones.iter().any(|b| b.kind == BoneKind::Head));
/// assert!(!skeleton.eyes.is_empty());
/// # Ok::<(), creature::Error>(())
/// ```
///
/// # Errors
/// The errors of [`Params::validate`].
pub fn skeleton(rng: &mut impl Rng, params: &Params) -> Result<Skeleton, Error> {
    params.validate()?;
    let n = params.spine_bones.at(uniform(rng)).max(2) as usize;
    let mut bones: Vec<Bone> = Vec::with_capacity(n * 8);
    bones.push(Bone {
        parent: None,
        offset: Vec2::ZERO,
        position: Vec2::ZERO,
        rotation: 0.0,
        thickness: 0.0,
        multiplier: 1.0,
        colour: Vec3::ZERO,
        texture_weights: Vec2::new(1.0, 0.0),
        kind: BoneKind::Root,
    });
    for i in 1..n {
        let thickness = params.spine_thickness.at(uniform(rng));
        let length = params.spine_length.at(uniform(rng));
        let a = uniform(rng);
        let colour = colour(rng);
        let multiplier = params.spine_multiplier.at(uniform(rng));
        let offset = Vec2::new(0.0, length);
        let position = bones[i - 1].position + offset;
        bones.push(Bone {
            parent: Some(i - 1),
            offset,
            position,
            rotation: 0.0,
            thickness,
            multiplier,
            colour,
            texture_weights: Vec2::new(a, 1.0 - a),
            kind: if i == n - 1 {
                BoneKind::Head
            } else {
                BoneKind::Spine
            },
        });
    }

    // Eyes: uniform count (the seed's floor(1 + 7U)), on a circle inside the head.
    let head = n - 1;
    let head_bone = bones[head];
    let span = params.eye_count.max - params.eye_count.min + 1;
    let count =
        (params.eye_count.min + (uniform(rng) * span as f32) as u32).min(params.eye_count.max);
    let size = head_bone.thickness * params.eye_size.at(uniform(rng));
    let ring = (head_bone.thickness - size / 2.0).max(0.0);
    let turn = if count % 2 == 1 { FRAC_PI_2 } else { 0.0 };
    let eyes = (0..count)
        .map(|j| Eye {
            position: head_bone.position
                + Vec2::from_angle(TAU * j as f32 / count as f32 + turn) * ring,
            radius: size / 2.0,
            bone: head,
        })
        .collect();

    // Limbs.
    for i in 0..n {
        if !(uniform(rng) < params.limb_probability) {
            continue;
        }
        let k = params.limb_bones.at(uniform(rng)) as usize;
        let mut segments: Vec<(f32, f32, f32)> = Vec::with_capacity(k);
        for j in 0..k {
            let length = params.limb_length.at(uniform(rng));
            let thickness = params.limb_thickness.at(uniform(rng));
            let multiplier = params.limb_multiplier.at(uniform(rng));
            segments.push((length, if j == 0 { 0.0 } else { thickness }, multiplier));
        }
        let here = bones[i].thickness;
        let next = bones.get(i + 1).map_or(here, |b| b.thickness);
        let socket = params.socket_offset * here.max(next);
        for dir in [-1.0f32, 1.0] {
            let first = bones.len();
            for (j, &(length, thickness, multiplier)) in segments.iter().enumerate() {
                let (parent, offset, kind, colour) = if j == 0 {
                    (
                        i,
                        Vec2::new(dir * socket, 0.0),
                        BoneKind::Socket,
                        Vec3::ZERO,
                    )
                } else {
                    (
                        first + j - 1,
                        Vec2::new(dir * length, 0.0),
                        BoneKind::Limb,
                        colour(rng),
                    )
                };
                let position = bones[parent].position + offset;
                bones.push(Bone {
                    parent: Some(parent),
                    offset,
                    position,
                    rotation: 0.0,
                    thickness,
                    multiplier,
                    colour,
                    texture_weights: Vec2::new(1.0, 0.0),
                    kind,
                });
            }
        }
    }
    Ok(Skeleton { bones, eyes })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_stays_in_the_unit_interval() {
        let mut rng = rng_for(1);
        for _ in 0..10_000 {
            let u = uniform(&mut rng);
            assert!((0.0..1.0).contains(&u));
        }
    }

    #[test]
    fn skeletons_follow_the_seed_layout() {
        for seed in 0..200 {
            let s = skeleton_from_seed(seed, &Params::DEFAULT).unwrap();
            let spine = s
                .bones
                .iter()
                .take_while(|b| !matches!(b.kind, BoneKind::Socket))
                .count();
            assert!((3..=6).contains(&spine), "seed {seed}: {spine} spine bones");
            for (i, b) in s.bones.iter().enumerate() {
                if let Some(p) = b.parent {
                    assert!(p < i);
                    assert_eq!(b.position, s.bones[p].position + b.offset);
                }
                match b.kind {
                    BoneKind::Spine | BoneKind::Head => {
                        assert!((10.0..40.0).contains(&b.thickness));
                        assert!((50.0..100.0).contains(&b.offset.y));
                    }
                    BoneKind::Limb => {
                        assert!((5.0..15.0).contains(&b.thickness));
                        assert!((50.0..80.0).contains(&b.offset.x.abs()));
                    }
                    BoneKind::Socket | BoneKind::Root => assert_eq!(b.thickness, 0.0),
                }
            }
            assert!((1..=7).contains(&s.eyes.len()));
        }
    }

    #[test]
    fn limb_probability_zero_and_one() {
        let none = Params::DEFAULT.with_limb_probability(0.0);
        let all = Params::DEFAULT.with_limb_probability(1.0);
        for seed in 0..20 {
            let s = skeleton_from_seed(seed, &none).unwrap();
            assert!(s.bones.iter().all(|b| b.kind != BoneKind::Socket));
            let s = skeleton_from_seed(seed, &all).unwrap();
            let spine = s
                .bones
                .iter()
                .filter(|b| matches!(b.kind, BoneKind::Root | BoneKind::Spine | BoneKind::Head))
                .count();
            let sockets = s
                .bones
                .iter()
                .filter(|b| b.kind == BoneKind::Socket)
                .count();
            assert_eq!(sockets, 2 * spine);
        }
    }
}
