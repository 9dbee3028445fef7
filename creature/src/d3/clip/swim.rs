//! Swimmers' `idle` and `swim` clips: the spine waves from head to tail, the tail fin follows
//! with a lag and the other fins flutter.

use alloc::vec::Vec;

use glam::{Quat, Vec3};

use creature_gait::SwimParams;
use creature_limbs::LimbKind;

use super::{Clip, empty_clip, frames_for, loop_error, side_sign, sin_turns};
use crate::d3::Creature;

/// A swimmer's `idle` (speed 0) or `swim` clip, raised where a fluttering fin would dip below
/// the ground its rest pose lies on.
pub(crate) fn swim(c: &Creature, name: &'static str, speed: f32) -> Clip {
    let swim_params = SwimParams::DEFAULT;
    // Swimming waves at full weight (any speed moves the body); idle is the sway alone.
    let (wave_speed, rate) = if speed > 0.0 {
        (swim_params.full_speed, swim_params.frequency)
    } else {
        (0.0, swim_params.idle_frequency)
    };
    let seconds = if speed > 0.0 { 2.0 / rate } else { 1.0 / rate };
    let (frames, fps) = frames_for(seconds);
    let rest_root = c.rest_root();
    // Spine joints from the head (the root) toward the tail, with their place along it.
    let (spine, along) = swim_spine(c);
    // Animated: spine joints carrying a bone (not the root, not the tail tip), then fins.
    let mut animated: Vec<(usize, Motion, f32, usize)> = spine
        .iter()
        .enumerate()
        .skip(1)
        .take(spine.len().saturating_sub(2))
        .map(|(i, &j)| (j, Motion::Spine, 0.0, i))
        .collect();
    animated.extend(fin_joints(c));
    let joints: Vec<usize> = animated.iter().map(|a| a.0).collect();
    let mut clip = empty_clip(name, fps, frames, &joints);
    // The yaw at time `t` of the spine joint `i` (from the head); the head's is the first's (a
    // rig edited to have no spine: as at the tail's end).
    // Each spine joint's share of the wave scaled down where its bend would tear the skin:
    // thick parts on short bones swim stiffer and thin tails keep their sweep, as fish do. The
    // largest bend of each joint over the clip against its limit.
    let limits = c.bend_limits();
    let scale = bend_scale(&limits, &spine, frames, |f, i| {
        let t = f as f32 / fps;
        swim_params.bone_yaw(t, wave_speed, along[i])
            - swim_params.bone_yaw(t, wave_speed, along[i - 1])
    });
    let yaw_at = |t: f32, i: usize| swim_params.bone_yaw(t, wave_speed, along[i]);
    let bend_at = |t: f32, i: usize| scale[i] * (yaw_at(t, i) - yaw_at(t, i - 1));
    let head_along = along.first().copied().unwrap_or(1.0);
    for f in 0..frames {
        let t = f as f32 / fps;
        let head = swim_params.bone_yaw(t, wave_speed, head_along);
        clip.root_translation
            .push(rest_root + Vec3::Z * (speed * t));
        clip.root_rotation.push(Quat::from_rotation_y(head));
        for (track, &(_, motion, sign, k)) in clip.tracks.iter_mut().zip(&animated) {
            let rotation = match motion {
                // Each bone's yaw relative to its parent's (the previous along the spine): `k`
                // is from 1 to the spine's length − 2.
                Motion::Spine => Quat::from_rotation_y(bend_at(t, k)).normalize(),
                _ => fin_rotation(&swim_params, motion, rate * t, sign, k),
            };
            track.rotations.push(rotation);
        }
    }
    // Above the ground in every frame: a fin resting on it dips when it flutters. The whole
    // clip is raised by the deepest dip of any vertex, so it still loops.
    let lowest = lowest_fin_vertex(c, &clip);
    for t in &mut clip.root_translation {
        t.y -= lowest;
    }
    clip.loop_error = loop_error(&clip);
    clip
}

/// A swimmer's spine joints from the head (the root) toward the tail, with each one's place
/// along it (0 at the head, 1 at the tail's tip).
pub(super) fn swim_spine(c: &Creature) -> (Vec<usize>, Vec<f32>) {
    let spine: Vec<usize> = c.rig.spine.iter().rev().copied().collect();
    let length = c.rig.spine_length().max(1e-6);
    let mut along = Vec::with_capacity(spine.len());
    let mut arc = 0.0f32;
    for (i, &j) in spine.iter().enumerate() {
        if i > 0 {
            let previous = spine[i - 1];
            let p = |j: usize| c.rig.joints.get(j).map_or(Vec3::ZERO, |j| j.position);
            arc += p(previous).distance(p(j));
        }
        along.push(arc / length);
    }
    (spine, along)
}

/// A swimmer's fin joints (each limb's): what moves each, its side's sign and its place along
/// its fin.
pub(super) fn fin_joints(c: &Creature) -> Vec<(usize, Motion, f32, usize)> {
    let mut fins = Vec::new();
    for (index, limb) in c.plan.limbs.iter().enumerate() {
        let motion = if limb.kind == LimbKind::Tail {
            Motion::TailFin
        } else {
            Motion::Fin
        };
        for (k, joint) in c.limb_joints(index).into_iter().enumerate() {
            fins.push((joint, motion, side_sign(limb.side), k));
        }
    }
    fins
}

/// Per place along the swimmer's `spine`, the share of the wave's bend it takes so that its
/// joint bends no further than its skin allows (`limits`, per joint): thick parts on short
/// bones swim stiffer and thin tails keep their sweep, as fish do. `bend(sample, i)` is the
/// wave's bend at place `i` (from 1) in each of `samples`.
pub(super) fn bend_scale(
    limits: &[f32],
    spine: &[usize],
    samples: usize,
    bend: impl Fn(usize, usize) -> f32,
) -> Vec<f32> {
    let mut scale = alloc::vec![1.0f32; spine.len()];
    for f in 0..samples {
        for (i, &j) in spine.iter().enumerate().skip(1) {
            let bend = bend(f, i).abs();
            if bend * scale[i] > limits[j] {
                scale[i] = limits[j] / bend;
            }
        }
    }
    scale
}

/// A fin joint's rotation (`motion` a [`Motion::TailFin`] or a [`Motion::Fin`]; the tail fin
/// following the wave with a lag, the others fluttering), at `turns` (the clip's rate times
/// the time), on the side of `sign`, `k` along its fin.
pub(super) fn fin_rotation(
    params: &SwimParams,
    motion: Motion,
    turns: f32,
    sign: f32,
    k: usize,
) -> Quat {
    let rotation = match motion {
        Motion::TailFin => Quat::from_rotation_y(
            0.3 * params.amplitude * sin_turns(turns - params.wavelength - 0.2 * k as f32),
        ),
        _ => Quat::from_rotation_z(sign * FIN_FLUTTER * sin_turns(turns - 0.3 * k as f32)),
    };
    rotation.normalize()
}

/// The lowest height over the clip of any vertex a fluttering fin moves (0 if none goes below
/// the ground), skinned as a viewer does. Only fins roll: the spine and the tail fin turn about
/// the vertical, which keeps every other vertex at its rest height, on or above the ground.
pub(super) fn lowest_fin_vertex(c: &Creature, clip: &Clip) -> f32 {
    // Per joint of a fin: its fin's root joint and the most its rolls can turn it (each of its
    // chain's joints rolls at most `FIN_FLUTTER`). A vertex at `p` turned by at most `angle`
    // about the root `r` drops by at most |p − r| · angle: only those that may reach the
    // ground are posed.
    let mut fin: Vec<Option<(Vec3, f32)>> = alloc::vec![None; c.skeleton.joints.len()];
    for (index, limb) in c.plan.limbs.iter().enumerate() {
        if limb.kind == LimbKind::Tail {
            continue;
        }
        let joints = c.limb_joints(index);
        let Some(&root) = joints.first() else {
            continue;
        };
        let angle = FIN_FLUTTER * joints.len() as f32;
        for j in joints {
            fin[j] = Some((c.skeleton.joints[root].position, angle));
        }
    }
    let mesh = &c.mesh;
    let moved: Vec<usize> = (0..mesh.positions.len())
        .filter(|&v| {
            let p = mesh.positions[v];
            mesh.joints[v]
                .iter()
                .zip(&mesh.weights[v])
                .filter(|&(_, &w)| w > 0.0)
                .filter_map(|(&j, _)| fin[usize::from(j)])
                .any(|(root, angle)| p.y < p.distance(root) * angle)
        })
        .collect();
    let mut lowest = 0.0f32;
    if moved.is_empty() {
        return lowest;
    }
    let rest: Vec<Vec3> = c.skeleton.joints.iter().map(|j| j.position).collect();
    for f in 0..clip.frames {
        let pose = super::pose(c, clip, f);
        for &v in &moved {
            let p = mesh.positions[v];
            let y: f32 = mesh.joints[v]
                .iter()
                .zip(&mesh.weights[v])
                .map(|(&j, &w)| {
                    let j = usize::from(j);
                    w * pose[j].transform_point3(p - rest[j]).y
                })
                .sum();
            lowest = lowest.min(y);
        }
    }
    lowest
}

/// The most a fin's joint rolls about its parent in a swimmer's clips, in radians.
const FIN_FLUTTER: f32 = 0.15;

/// What drives an animated joint of a swimmer clip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Motion {
    Spine,
    TailFin,
    Fin,
}
