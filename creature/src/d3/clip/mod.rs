//! Baked animation clips of 3D creatures: the [`Clip`] and [`Track`] types, and what every
//! baker shares (frame counts, empty clips, loop errors, the root's rest position, the tail
//! chain). The bakers and their helpers are in the submodules:
//!
//! - `walk`: walkers' gait-driven `walk`, `turn` and `idle` (the controller run, the loop cut
//!   and closed, legs by two-bone IK);
//! - `gait_run`: a recorded controller run, its mismatch, best cut, loop closing and overreach;
//! - `floor`: keeping the body and knees above the floor;
//! - `flight`: fliers' `hover` and `fly` (flapping wings, damped chains);
//! - `swim`: swimmers' `idle` and `swim` (a spine wave, fins);
//! - `kinematics`: forward kinematics, posing and skinning, rotation helpers.

use alloc::vec::Vec;

use glam::{Quat, Vec3};

use crate::d3::Creature;
use kinematics::angle_between;

mod flight;
mod floor;
mod gait_run;
mod kinematics;
mod swim;
mod walk;

pub(crate) use flight::flight;
pub(crate) use kinematics::{pose, skinned};
pub(crate) use swim::swim;
pub(crate) use walk::{gait, turn, walk_loop};

/// Frames per second of baked clips.
pub const CLIP_FPS: f32 = 30.0;

/// One joint's animated local transform, one value per frame of its [`Clip`].
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    /// The joint (index into [`Skeleton::joints`](crate::d3::Skeleton::joints)).
    pub joint: usize,
    /// Local translation per frame (relative to the parent, in its frame); `None` keeps the
    /// rest translation.
    pub translations: Option<Vec<Vec3>>,
    /// Local rotation per frame (unit quaternions; the rest rotation is the identity).
    pub rotations: Vec<Quat>,
}

/// A baked clip: frames at [`CLIP_FPS`], the root's motion and the animated joints' local
/// transforms. Joints without a track keep their rest transform.
#[derive(Debug, Clone, PartialEq)]
pub struct Clip {
    /// The clip's name, e.g. `"walk"`.
    pub name: &'static str,
    /// Frames per second.
    pub fps: f32,
    /// Number of frames (at least 2).
    pub frames: usize,
    /// The root joint's translation per frame (model space: it carries the root motion).
    pub root_translation: Vec<Vec3>,
    /// The root joint's rotation per frame.
    pub root_rotation: Vec<Quat>,
    /// The other animated joints.
    pub tracks: Vec<Track>,
    /// Per frame, per leg of the [`GaitSetup`](crate::d3::GaitSetup): whether the foot is planted
    /// (empty for fliers and swimmers).
    pub contacts: Vec<Vec<bool>>,
    /// How far the last frame is from the first, measured: the largest of the angles
    /// (radians) between a joint's (or the root's) first and last rotations, the root's
    /// height change and a track's translation change (metres); the root's forward travel
    /// (root motion) aside. Below 1e-3 for the clips of [`bake_clips`](Creature::bake_clips):
    /// `idle`, `hover`, `fly`, `swim` loop by construction, `walk`
    /// ([`bake_walk_loop`](Creature::bake_walk_loop)) and `turn`
    /// ([`bake_turn`](Creature::bake_turn)) have their loops closed (except the few where that
    /// would overstretch a leg); a plain [`bake_walk`](Creature::bake_walk) does not loop.
    pub loop_error: f32,
}

impl Clip {
    /// The clip's length in seconds (`(frames − 1) / fps`).
    #[must_use]
    pub fn duration(&self) -> f32 {
        self.frames.saturating_sub(1) as f32 / self.fps
    }
}

impl Creature {
    /// The root joint's rest position (a skeleton edited to have no root: the first joint's;
    /// none at all: the origin).
    fn rest_root(&self) -> Vec3 {
        let joints = &self.skeleton.joints;
        joints
            .iter()
            .find(|j| j.parent.is_none())
            .or(joints.first())
            .map_or(Vec3::ZERO, |j| j.position)
    }

    /// The spine joints from the root toward the tail tip that carry a bone (the tip itself
    /// excluded), nearest the root first.
    fn tail_chain(&self) -> Vec<usize> {
        let spine = &self.rig.spine;
        let root = self.rig.root();
        let Some(c) = spine.iter().position(|&j| Some(j) == root) else {
            return Vec::new();
        };
        spine.iter().take(c).skip(1).rev().copied().collect()
    }
}

/// A baked clip's [`Clip::loop_error`]: the largest rotation angle between its first and last
/// frames (root and tracks), the root's height change, and the largest change of a track's
/// translation. The bakers fill every per-frame list, with at least 2 frames.
fn loop_error(clip: &Clip) -> f32 {
    let last = clip.frames - 1;
    debug_assert!(
        clip.root_rotation.len() == clip.frames
            && clip.root_translation.len() == clip.frames
            && clip.tracks.iter().all(|t| t.rotations.len() == clip.frames
                && t.translations
                    .as_ref()
                    .is_none_or(|t| t.len() == clip.frames)),
        "a value per frame"
    );
    let angle = |v: &[Quat]| angle_between(v[0], v[last]);
    let mut error = angle(&clip.root_rotation);
    for track in &clip.tracks {
        error = error.max(angle(&track.rotations));
        if let Some(t) = &track.translations {
            error = error.max(t[0].distance(t[last]));
        }
    }
    let root = &clip.root_translation;
    error.max((root[0].y - root[last].y).abs())
}

/// Frames for `seconds` at about [`CLIP_FPS`], and the exact rate that fits them.
fn frames_for(seconds: f32) -> (usize, f32) {
    let frames = ((seconds * CLIP_FPS + 0.5) as usize).max(1) + 1;
    (frames, (frames - 1) as f32 / seconds.max(1e-6))
}

/// A clip skeleton with per-frame rotation tracks for `joints` (identity rotations to fill).
fn empty_clip(name: &'static str, fps: f32, frames: usize, joints: &[usize]) -> Clip {
    Clip {
        name,
        fps,
        frames,
        root_translation: Vec::with_capacity(frames),
        root_rotation: Vec::with_capacity(frames),
        tracks: joints
            .iter()
            .map(|&joint| Track {
                joint,
                translations: None,
                rotations: Vec::with_capacity(frames),
            })
            .collect(),
        contacts: Vec::new(),
        loop_error: 0.0,
    }
}

fn sin_turns(turns: f32) -> f32 {
    crate::math::sin(core::f32::consts::TAU * turns)
}

fn side_sign(side: creature_limbs::Side) -> f32 {
    match side {
        creature_limbs::Side::Left => 1.0,
        creature_limbs::Side::Right => -1.0,
        creature_limbs::Side::Center => 1.0,
    }
}
