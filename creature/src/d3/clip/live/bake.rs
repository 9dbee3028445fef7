//! A walker's plain `walk` baked on flat ground by its [`Animator`]: the animator's frames as
//! they are, what a game driving it shows.

use alloc::vec::Vec;

use glam::{Affine3A, Quat, Vec3};

use creature_gait::{GaitOptions, LimbKind, Plane, Pose};

use super::super::gait_run::GaitRun;
use super::super::walk::{GROUND_CONTACT, MAX_LEG_TURN_PER_FRAME, WARM_UP, clip_seconds};
use super::super::{CLIP_FPS, Clip, Track, limit_looping_turn_rate, loop_error};
use super::{Animator, Closing, Drive, Intent, Posing};
use crate::Error;
use crate::d3::{Creature, GaitSetup};
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
        let (dt, moving) = driven(&animator, step, (speed, yaw_rate));
        animator.walk(dt, Intent::Stand, moving, &ground)?;
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

/// Walker `c`'s animator with the gait `options` (its set-up's, or others for a clip of its
/// own), as a fresh one for `c` but for them.
fn walker_animator(c: &Creature, options: &GaitOptions) -> Result<Animator, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    if setup.options == *options {
        return Animator::new(c);
    }
    let setup = GaitSetup {
        options: *options,
        ..setup.clone()
    };
    Animator::walker(c, &setup)
}

/// Update `step` of an animator driven on flat ground as [`record`] drives it, forward at
/// `speed` along its heading and turning at `yaw_rate`: its time step (0 for the first, which
/// poses it afresh where it stands) and the velocity and turn rate it is driven with.
fn driven(animator: &Animator, step: usize, (speed, yaw_rate): (f32, f32)) -> (f32, (Vec3, f32)) {
    let dt = if step == 0 { 0.0 } else { 1.0 / CLIP_FPS };
    let heading = animator.heading + yaw_rate * dt;
    let forward = Vec3::new(crate::math::sin(heading), 0.0, crate::math::cos(heading));
    (dt, (forward * speed, yaw_rate))
}

/// Walker `c`'s gait (with `options`) over `seconds` after a warm-up of [`WARM_UP`] seconds,
/// its animator driven as [`record`] drives it but not posed: per frame, the reacted body,
/// the feet and which are planted, relative to the place and heading of the first frame.
///
/// # Errors
/// As [`record`].
pub(in crate::d3::clip) fn gait_run(
    c: &Creature,
    options: &GaitOptions,
    seconds: f32,
    motion: (f32, f32),
) -> Result<GaitRun, Error> {
    clip_seconds(seconds)?;
    let mut animator = walker_animator(c, options)?;
    let warm_up = (WARM_UP * CLIP_FPS) as usize;
    let frames = (seconds * CLIP_FPS + 0.5) as usize + 1;
    let legs = animator.controller.legs().len();
    let mut run = GaitRun {
        bodies: Vec::with_capacity(frames),
        feet: Vec::with_capacity(frames * legs),
        contacts: Vec::with_capacity(frames * legs),
        legs,
    };
    let mut start = Pose::IDENTITY;
    for step in 0..warm_up + frames {
        let (dt, moving) = driven(&animator, step, motion);
        animator.walk_posed(dt, Intent::Stand, moving, &Plane::GROUND, Posing::Skip)?;
        if step < warm_up {
            continue;
        }
        if step == warm_up {
            start = Pose::from_yaw(animator.position, animator.heading);
        }
        let unstart = start.rotation.inverse();
        let relative = |p: Vec3| unstart * (p - start.translation);
        let body = animator.controller.reacted_pose();
        run.bodies.push(Pose {
            translation: relative(body.translation),
            rotation: (unstart * body.rotation).unit(),
        });
        let states = animator.controller.leg_states();
        // One state per leg, the controller's order: the run's frames hold `legs` each.
        debug_assert_eq!(states.len(), legs, "one leg state per leg");
        run.contacts.extend(states.iter().map(|s| s.planted));
        run.feet.extend(states.iter().map(|s| relative(s.foot)));
    }
    Ok(run)
}

/// A looping clip named `name`: the animator of walker `c` (with `options`) driven again as
/// [`gait_run`] drove it to record `raw` (with the same `motion`), each frame of `closed`
/// (`raw` cut, its loop perhaps closed) posed with the closed body, each foot moved as the
/// closing moved it and planted as it has it; the clip's contacts are the closed run's. Each
/// sole's turn about +Y (the heading it landed with) is closed too: posed once to measure how
/// far each sole's last frame is turned from its first, the animator is driven a last time
/// with that turn taken back over the sole's swings (held while it stands, so a planted sole
/// never turns). `frame` sees the animator after each frame of that last drive is posed.
///
/// With `limit`, each walking leg's hip, knee and foot then turn no faster than
/// [`MAX_LEG_TURN_PER_FRAME`] from frame to frame where its foot is more than twice
/// [`GROUND_CONTACT`] of the body's length above the ground in a swing (the loop's seam kept),
/// and a limited frame lowers the foot joint no nearer than that to where it stands (nor
/// below where the animator put it): it goes back toward the animator's pose as far as it
/// must. A baker's pass: the live animator does not see the frames to come.
///
/// # Errors
/// As [`record`].
pub(in crate::d3::clip) fn posed_loop(
    c: &Creature,
    options: &GaitOptions,
    name: &'static str,
    motion: (f32, f32),
    runs: (&GaitRun, &GaitRun),
    limit: bool,
    mut frame: impl FnMut(&Animator),
) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let (_, closed) = runs;
    let (frames, legs) = (closed.frames(), closed.legs);
    // Each sole's heading (radians about +Y) in the first and the last frame.
    let feet: Vec<usize> = setup.hip_joints.iter().map(|&hip| hip + 2).collect();
    let mut ends = alloc::vec![(0.0f32, 0.0f32); legs];
    let sole_heading = |a: &Animator, foot: usize| {
        let forward = a.world_transforms()[foot].matrix3.z_axis;
        glam::Vec2::new(forward.z, forward.x).to_angle()
    };
    let no_turns = alloc::vec![0.0f32; frames * legs];
    let mut f = 0;
    drive_closed(c, options, name, motion, runs, &no_turns, |a| {
        for (end, &foot) in ends.iter_mut().zip(&feet) {
            let heading = sole_heading(a, foot);
            if f == 0 {
                end.0 = heading;
            }
            end.1 = heading;
        }
        f += 1;
    })?;
    // Each sole's turn taken back over its swings, by the share of them each frame ends
    // (evenly over the clip for a foot that never lifts).
    let mut turns = no_turns;
    for (leg, &(first, last)) in ends.iter().enumerate() {
        let turn = super::wrap(first - last);
        let swings = (1..frames).filter(|&f| !closed.planted(f, leg)).count();
        let mut done = 0;
        for f in 1..frames {
            let share = if swings == 0 {
                f as f32 / (frames - 1) as f32
            } else {
                done += usize::from(!closed.planted(f, leg));
                done as f32 / swings as f32
            };
            turns[f * legs + leg] = turn * share;
        }
    }
    // Each walking leg's hip's parent (world) per frame, as posed.
    let walking: Vec<(usize, usize)> = setup
        .legs
        .iter()
        .zip(&setup.hip_joints)
        .enumerate()
        .filter(|(_, (leg, _))| limit && leg.kind == LimbKind::Leg)
        .map(|(i, (_, &hip))| (i, hip))
        .collect();
    let joints = &c.skeleton.joints;
    let mut parents: Vec<Vec<Affine3A>> = alloc::vec![Vec::with_capacity(frames); walking.len()];
    let mut clip = drive_closed(c, options, name, motion, runs, &turns, |a| {
        let world = a.world_transforms();
        for (slot, &(_, hip)) in parents.iter_mut().zip(&walking) {
            slot.push(joints[hip].parent.map_or(Affine3A::IDENTITY, |p| world[p]));
        }
        frame(a);
    })?;
    // A walking leg's joints turn no faster than a leg's may while its foot is high in a
    // swing: limited only there, so the foot lifts, lands and stands where the gait puts it.
    let ground = 2.0 * GROUND_CONTACT * c.length;
    let rest = c.skeleton.rest_translations();
    // A clip that loops is limited round its seam (its first and last frames, the same pose),
    // from its first frame the foot is down on.
    let looping = clip.loop_error < 1e-3 && frames >= 2;
    for (&(i, hip), parents) in walking.iter().zip(&parents) {
        let track = |clip: &Clip, joint: usize| clip.tracks.iter().position(|t| t.joint == joint);
        let (Some(h), Some(k), Some(o)) = (
            track(&clip, hip),
            track(&clip, hip + 1),
            track(&clip, hip + 2),
        ) else {
            continue;
        };
        let posed: [Vec<Quat>; 3] = [h, k, o].map(|t| clip.tracks[t].rotations.clone());
        let hips = clip.tracks[h].translations.clone();
        // The foot joint's height (world; the ground is at 0) at frame `f` with the hip and
        // knee turned as `q` has them.
        let height = |f: usize, q: &[Quat; 3]| {
            let hip_at = hips.as_ref().map_or(rest[hip], |t| t[f]);
            let foot = hip_at + q[0] * (rest[hip + 1] + q[1] * rest[hip + 2]);
            parents[f].transform_point3(foot).y
        };
        let animated_at = |f: usize| [0, 1, 2].map(|j| posed[j][f]);
        // Where the foot joint is with the foot on the ground: its height at rest.
        let stands = joints[hip + 2].position.y;
        // Off the ground: in a swing, or planted where the leg cannot reach.
        let free: Vec<bool> = (0..frames)
            .map(|f| {
                (!closed.planted(f, i) && closed.foot(f, i).y > ground)
                    || height(f, &animated_at(f)) > stands + ground
            })
            .collect();
        let start = (0..frames.saturating_sub(1)).find(|&f| !free[f]);
        for t in [h, k, o] {
            let rotations = &mut clip.tracks[t].rotations;
            match start {
                // A foot never down in the loop (a leg too short for the ground).
                None if looping => limit_looping_turn_rate(rotations, MAX_LEG_TURN_PER_FRAME),
                Some(start) if looping => {
                    // Round the loop from `start` (the last frame is the first again).
                    let cycle = frames - 1;
                    let order = |k: usize| (start + k) % cycle;
                    let mut turned: Vec<Quat> = (0..=cycle).map(|k| rotations[order(k)]).collect();
                    let loose: Vec<bool> =
                        (0..=cycle).map(|k| k < cycle && free[order(k)]).collect();
                    limit_free_turn_rate(&mut turned, &loose, MAX_LEG_TURN_PER_FRAME);
                    for (k, q) in turned.into_iter().take(cycle).enumerate() {
                        rotations[order(k)] = q;
                    }
                    rotations[cycle] = rotations[0];
                }
                _ => limit_free_turn_rate(rotations, &free, MAX_LEG_TURN_PER_FRAME),
            }
        }
        // A limited frame lowers the foot to no less than `ground` over where it stands (nor
        // lower than the animator put it, if that is lower): else it goes back toward the
        // animator's pose only as far as it must (a foot lowered near the ground in a quick
        // swing was seen to slide there).
        for f in (0..frames).filter(|&f| free[f]) {
            let limited = [h, k, o].map(|t| clip.tracks[t].rotations[f]);
            let animated = animated_at(f);
            let lowest = height(f, &animated).min(stands + ground);
            let height = |q: &[Quat; 3]| height(f, q);
            if limited == animated || height(&limited) >= lowest {
                continue;
            }
            let blend = |t: f32| [0, 1, 2].map(|j| limited[j].slerp(animated[j], t).unit());
            // `hi` is safe (the animator's pose at 1), `lo` is not.
            let (mut lo, mut hi) = (0.0f32, 1.0f32);
            for _ in 0..10 {
                let t = 0.5 * (lo + hi);
                if height(&blend(t)) >= lowest {
                    hi = t;
                } else {
                    lo = t;
                }
            }
            let chosen = if hi < 1.0 { blend(hi) } else { animated };
            for (t, q) in [h, k, o].into_iter().zip(chosen) {
                clip.tracks[t].rotations[f] = q;
            }
        }
        if looping {
            // The seam's two frames, each made safe, are one pose again.
            for t in [h, k, o] {
                let rotations = &mut clip.tracks[t].rotations;
                rotations[frames - 1] = rotations[0];
            }
        }
    }
    clip.loop_error = loop_error(&clip);
    Ok(clip)
}

/// Each rotation whose frame is `free` turned no further than `max` radians from its
/// neighbours, the others kept: forward, backward and forward again, each frame moved toward
/// the one before (after), so a limited stretch leaves and rejoins the kept frames within the
/// limit where the limit allows. A track that turns no faster is kept as it is.
fn limit_free_turn_rate(rotations: &mut [Quat], free: &[bool], max: f32) {
    let n = rotations.len().min(free.len());
    // Two unit quaternions are within `max` of each other when their dot product's size is
    // at least cos(max / 2).
    let near = crate::math::cos(0.5 * max);
    if (1..n).all(|k| !(free[k] || free[k - 1]) || rotations[k].dot(rotations[k - 1]).abs() >= near)
    {
        return;
    }
    let toward = |from: Quat, to: Quat| {
        let angle = from.angle_between(to);
        (angle > max).then(|| from.slerp(to, max / angle).unit())
    };
    for pass in 0..3 {
        for k in 1..n {
            let (f, near) = if pass == 1 {
                (n - 1 - k, n - k)
            } else {
                (k, k - 1)
            };
            if free[f]
                && let Some(q) = toward(rotations[near], rotations[f])
            {
                rotations[f] = q;
            }
        }
    }
}

/// [`posed_loop`]'s drive: each sole turned about +Y by `turns` (radians; per frame, `legs`
/// each) on top of the closing of `closed`.
fn drive_closed(
    c: &Creature,
    options: &GaitOptions,
    name: &'static str,
    motion: (f32, f32),
    (raw, closed): (&GaitRun, &GaitRun),
    turns: &[f32],
    mut frame: impl FnMut(&Animator),
) -> Result<Clip, Error> {
    let mut animator = walker_animator(c, options)?;
    // Bent toward its turn from the start, as one that has been turning a while.
    animator.turn = motion.1;
    let warm_up = (WARM_UP * CLIP_FPS) as usize;
    let (frames, legs) = (closed.frames(), closed.legs);
    debug_assert!(
        raw.legs == legs && raw.frames() >= frames && turns.len() == frames * legs,
        "the closed run is the raw one cut"
    );
    let mut clip = animator.empty_clip(name);
    let mut start = Pose::IDENTITY;
    // Per leg, its foot's move this frame (world).
    let mut moves = alloc::vec![Vec3::ZERO; legs];
    for step in 0..warm_up + frames {
        let (dt, moving) = driven(&animator, step, motion);
        let ground = &Plane::GROUND;
        match step.checked_sub(warm_up) {
            // The warm-up, and the first frame (the closing does not move it), as live.
            None | Some(0) => {
                animator.walk_posed(dt, Intent::Stand, moving, ground, Posing::Live)?;
            }
            Some(f) => {
                let closed_body = &closed.bodies[f];
                let body = Pose {
                    translation: start.transform_point(closed_body.translation),
                    rotation: (start.rotation * closed_body.rotation).unit(),
                };
                for (leg, slot) in moves.iter_mut().enumerate() {
                    *slot = start.rotation * (closed.foot(f, leg) - raw.foot(f, leg));
                }
                let closing = Closing {
                    body,
                    feet: &moves,
                    planted: closed.frame_contacts(f),
                    soles: &turns[f * legs..(f + 1) * legs],
                };
                let posing = Posing::Closed(closing);
                animator.walk_posed(dt, Intent::Stand, moving, ground, posing)?;
            }
        }
        if step < warm_up {
            continue;
        }
        if step == warm_up {
            start = Pose::from_yaw(animator.position, animator.heading);
        }
        animator.push_frame(&mut clip, &start);
        frame(&animator);
    }
    clip.contacts = (0..frames)
        .map(|f| closed.frame_contacts(f).to_vec())
        .collect();
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
