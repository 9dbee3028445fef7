//! Swimmers' `idle` and `swim` clips: the spine waves from head to tail, the tail fin follows
//! with a lag and the other fins flutter.

use alloc::vec::Vec;

use glam::{Quat, Vec3};

use creature_gait::SwimParams;
use creature_limbs::LimbKind;

use super::{Clip, empty_clip, frames_for, loop_error, side_sign, sin_turns};
use crate::d3::Creature;

/// A swimmer's `idle` (speed 0) or `swim` clip.
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
    // Animated: spine joints carrying a bone (not the root, not the tail tip), then fins.
    let mut animated: Vec<(usize, Motion, f32, usize)> = spine
        .iter()
        .enumerate()
        .skip(1)
        .take(spine.len().saturating_sub(2))
        .map(|(i, &j)| (j, Motion::Spine, 0.0, i))
        .collect();
    for (index, limb) in c.plan.limbs.iter().enumerate() {
        let motion = if limb.kind == LimbKind::Tail {
            Motion::TailFin
        } else {
            Motion::Fin
        };
        for (k, joint) in c.limb_joints(index).into_iter().enumerate() {
            animated.push((joint, motion, side_sign(limb.side), k));
        }
    }
    let joints: Vec<usize> = animated.iter().map(|a| a.0).collect();
    let mut clip = empty_clip(name, fps, frames, &joints);
    // The yaw at time `t` of the spine joint `i` (from the head); the head's is the first's (a
    // rig edited to have no spine: as at the tail's end).
    // Each spine joint's share of the wave scaled down where its bend would tear the skin:
    // thick parts on short bones swim stiffer and thin tails keep their sweep, as fish do. The
    // largest bend of each joint over the clip against its limit.
    let limits = c.bend_limits();
    let mut scale = alloc::vec![1.0f32; spine.len()];
    for f in 0..frames {
        let t = f as f32 / fps;
        for (i, &j) in spine.iter().enumerate().skip(1) {
            let bend = (swim_params.bone_yaw(t, wave_speed, along[i])
                - swim_params.bone_yaw(t, wave_speed, along[i - 1]))
            .abs();
            if bend * scale[i] > limits[j] {
                scale[i] = limits[j] / bend;
            }
        }
    }
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
                Motion::Spine => Quat::from_rotation_y(bend_at(t, k)),
                Motion::TailFin => Quat::from_rotation_y(
                    0.3 * swim_params.amplitude
                        * sin_turns(rate * t - swim_params.wavelength - 0.2 * k as f32),
                ),
                _ => Quat::from_rotation_z(sign * 0.15 * sin_turns(rate * t - 0.3 * k as f32)),
            };
            track.rotations.push(rotation.normalize());
        }
    }
    clip.loop_error = loop_error(&clip);
    clip
}

/// What drives an animated joint of a swimmer clip.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Motion {
    Spine,
    TailFin,
    Fin,
}
