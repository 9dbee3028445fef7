//! A walker's plain `walk` baked on flat ground by its [`Animator`]: the animator's frames as
//! they are, what a game driving it shows.

use alloc::vec::Vec;

use glam::Vec3;

use creature_gait::{Plane, Pose};

use super::super::walk::{WARM_UP, clip_seconds};
use super::super::{CLIP_FPS, Clip, Track, loop_error};
use super::{Animator, Drive, Intent};
use crate::Error;
use crate::d3::Creature;
use crate::math::Roots;

/// Walker `c`'s animator on flat ground (`y = 0`) for `seconds` after the warm-up, moving
/// forward at `speed` (m/s, along its heading) and turning at `yaw_rate` (rad/s), as an
/// [`Intent::Move`] drives it but without the intent's clamps (the baker keeps to the
/// creature's limits itself), recorded frame by frame after a warm-up of [`WARM_UP`] seconds:
/// its frames as a clip named `name`, the root relative to the place and heading of the first
/// (its [`loop_error`](Clip::loop_error) measured).
///
/// # Errors
/// [`Error::OutOfRange`] for `seconds` outside `[1/30, 60]` or NaN, [`Error::NoGait`] for a
/// creature without a gait set-up, and the animator's and controller's errors.
pub(in crate::d3::clip) fn record(
    c: &Creature,
    name: &'static str,
    seconds: f32,
    speed: f32,
    yaw_rate: f32,
) -> Result<Clip, Error> {
    clip_seconds(seconds)?;
    if c.gait.is_none() {
        return Err(Error::NoGait);
    }
    let mut animator = Animator::new(c)?;
    debug_assert!(matches!(animator.drive, Drive::Walk), "a gait set-up walks");
    let ground = Plane::GROUND;
    let warm_up = (WARM_UP * CLIP_FPS) as usize;
    let frames = (seconds * CLIP_FPS + 0.5) as usize + 1;
    let mut clip = animator.empty_clip(name);
    let mut start = Pose::IDENTITY;
    for step in 0..warm_up + frames {
        // The first update poses it afresh where it stands.
        let dt = if step == 0 { 0.0 } else { 1.0 / CLIP_FPS };
        let heading = animator.heading + yaw_rate * dt;
        let forward = Vec3::new(crate::math::sin(heading), 0.0, crate::math::cos(heading));
        animator.walk(dt, Intent::Stand, (forward * speed, yaw_rate), &ground)?;
        if step < warm_up {
            continue;
        }
        if step == warm_up {
            start = Pose::from_yaw(animator.position, animator.heading);
        }
        animator.push_frame(&mut clip, &start);
    }
    clip.loop_error = loop_error(&clip);
    Ok(clip)
}

/// A plain `walk` of `seconds` (see [`Creature::bake_walk`]): the animator's frames walking
/// forward at the creature's speed.
///
/// # Errors
/// As [`record`].
pub(crate) fn live_walk(c: &Creature, seconds: f32) -> Result<Clip, Error> {
    record(c, "walk", seconds, c.speed, 0.0)
}

/// A slitherer's looping `idle` (`speed` 0: lying still, the front of its body raised and
/// bobbing once) or `slither` (crawling straight ahead at `speed`, one wave), baked on flat
/// ground by its [`Animator`]: each frame as the animator poses it, the root relative to the
/// first.
///
/// # Errors
/// [`Error::Unsupported`] for a creature that is not a slitherer; [`Error::OutOfRange`] for a
/// wave longer than a minute or shorter than a frame (a creature edited to crawl very slowly
/// or very fast); the animator's errors.
pub(crate) fn slither(c: &Creature, name: &'static str, speed: f32) -> Result<Clip, Error> {
    let mut animator = Animator::new(c)?;
    let Drive::Slither(slithering) = &animator.drive else {
        return Err(Error::Unsupported {
            what: "slither clips of a creature that is not a slitherer",
        });
    };
    let (seconds, intent) = if speed > 0.0 {
        let velocity = Vec3::Z * speed;
        (
            1.0 / slithering.frequency_at(speed),
            Intent::Move {
                velocity,
                turn_rate: 0.0,
            },
        )
    } else {
        (1.0 / super::slither::IDLE_RATE, Intent::Stand)
    };
    let (frames, fps) = super::super::frames_for(clip_seconds(seconds)?);
    let mut clip = animator.empty_clip(name);
    clip.fps = fps;
    let mut start = Pose::IDENTITY;
    for frame in 0..frames {
        let dt = if frame == 0 { 0.0 } else { 1.0 / fps };
        animator.update(dt, intent, &Plane::GROUND)?;
        if frame == 0 {
            start = Pose::from_yaw(animator.position, animator.heading);
        }
        animator.push_frame(&mut clip, &start);
    }
    clip.loop_error = loop_error(&clip);
    Ok(clip)
}

impl Animator {
    /// A clip named `name` without frames, with a track for every joint the animator turns
    /// (translations too for the legs' hips).
    pub(super) fn empty_clip(&self, name: &'static str) -> Clip {
        Clip {
            name,
            fps: CLIP_FPS,
            frames: 0,
            root_translation: Vec::new(),
            root_rotation: Vec::new(),
            tracks: (0..self.turns.len())
                .filter(|&j| self.turns[j] && j != self.root)
                .map(|joint| Track {
                    joint,
                    translations: self.leg_at[joint].map(|_| Vec::new()),
                    rotations: Vec::new(),
                })
                .collect(),
            contacts: Vec::new(),
            loop_error: 0.0,
        }
    }

    /// Appends the animator's pose to `clip` (made by [`empty_clip`](Self::empty_clip)): the
    /// root's transform relative to `start`, each track's joint's local transform; a walker's
    /// contacts as its controller has them.
    pub(super) fn push_frame(&self, clip: &mut Clip, start: &Pose) {
        let root = self.local[self.root];
        let unstart = start.rotation.inverse();
        clip.root_translation
            .push(unstart * (Vec3::from(root.translation) - start.translation));
        clip.root_rotation
            .push((unstart * crate::math::quat_from_mat3a(&root.matrix3)).unit());
        for track in &mut clip.tracks {
            let local = self.local[track.joint];
            track
                .rotations
                .push(crate::math::quat_from_mat3a(&local.matrix3).unit());
            if let Some(t) = track.translations.as_mut() {
                t.push(Vec3::from(local.translation));
            }
        }
        if matches!(self.drive, Drive::Walk) {
            clip.contacts.push(
                self.controller
                    .leg_states()
                    .iter()
                    .map(|s| s.planted)
                    .collect(),
            );
        }
        clip.frames += 1;
    }
}
