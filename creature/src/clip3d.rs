//! Baked animation clips of 3D creatures: the gait controller run at a fixed step on flat
//! ground, joint transforms sampled per frame.

use alloc::vec::Vec;

use glam::{Affine3A, Quat, Vec3};

use creature_gait::{FlapParams, Plane, Pose, Side, SwimParams};
use creature_limbs::{CreatureKind, LimbKind};

use crate::Error;
use crate::types3d::{Creature, Part};

/// Frames per second of baked clips.
pub const CLIP_FPS: f32 = 30.0;
/// Seconds the controller runs before a clip's first frame, so the gait is in its steady
/// rhythm.
const WARM_UP: f32 = 1.0;

/// One joint's animated local transform, one value per frame of its [`Clip`].
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    /// The joint (index into [`Skeleton3d::joints`](crate::Skeleton3d::joints)).
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
    /// Per frame, per leg of the [`GaitSetup`](crate::GaitSetup): whether the foot is planted
    /// (empty for fliers and swimmers).
    pub contacts: Vec<Vec<bool>>,
    /// How far the last frame is from the first, measured: the largest of the angles
    /// (radians) between a joint's (or the root's) first and last rotations, the root's
    /// height change and a track's translation change (metres). Near 0 for clips that loop by
    /// construction (`idle`, `hover`, `fly`, `swim`); `walk` from
    /// [`bake_walk_loop`](Creature::bake_walk_loop) is cut where it comes closest; `turn`
    /// does not loop exactly.
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
    /// Bakes a `walk` clip of `seconds` (at least one frame interval, at most 60 s): the
    /// walker moves forward (+Z) at its [`speed`](Creature::speed) over flat ground at
    /// `y = 0`, its legs stepping by the gait controller; each frame records the root's
    /// motion (with the body's bob and sway), each leg's hip translation, its hip and knee
    /// rotations (from the controller's two-bone IK) and a foot rotation that keeps the sole
    /// level (turned with the body's heading only), and the feet's contacts.
    ///
    /// ```
    /// use creature::{generate, Kind, Params};
    ///
    /// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
    /// let walk = walker.bake_walk(2.0)?;
    /// assert_eq!(walk.frames, 61);
    /// let pose = walker.pose(&walk, 30);
    /// assert_eq!(pose.len(), walker.skeleton.joints.len());
    /// # Ok::<(), creature::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NoGait`] for a creature without a gait set-up (fliers and swimmers),
    /// [`Error::OutOfRange`] for `seconds` outside `[1/30, 60]` or NaN, and the controller's
    /// errors as [`Error::Gait`].
    pub fn bake_walk(&self, seconds: f32) -> Result<Clip, Error> {
        self.bake_gait("walk", seconds, self.speed, 0.0)
    }

    /// Bakes a looping `walk`: 4 s are baked as by [`bake_walk`](Self::bake_walk), then cut at
    /// the frame from 1 s on that best matches the first (same feet planted, smallest
    /// [`Clip::loop_error`]), so the clip lasts whole strides.
    ///
    /// ```
    /// use creature::{generate, Kind, Params};
    ///
    /// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
    /// let walk = walker.bake_walk_loop()?;
    /// assert!(walk.duration() >= 1.0 && walk.duration() <= 4.0);
    /// assert!(walk.loop_error < walker.bake_walk(walk.duration() + 0.2)?.loop_error + 1e-6);
    /// # Ok::<(), creature::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`bake_walk`](Self::bake_walk).
    pub fn bake_walk_loop(&self) -> Result<Clip, Error> {
        let mut clip = self.bake_gait("walk", 4.0, self.speed, 0.0)?;
        let first = (CLIP_FPS as usize)
            .min(clip.frames.saturating_sub(1))
            .max(1);
        let mut best = (f32::INFINITY, clip.frames - 1);
        for end in first..clip.frames {
            if clip.contacts.get(end) != clip.contacts.first() {
                continue;
            }
            let error = error_between(&clip, 0, end);
            if error < best.0 {
                best = (error, end);
            }
        }
        let (error, end) = best;
        let keep = end + 1;
        clip.frames = keep;
        clip.root_translation.truncate(keep);
        clip.root_rotation.truncate(keep);
        clip.contacts.truncate(keep);
        for track in &mut clip.tracks {
            track.rotations.truncate(keep);
            if let Some(t) = track.translations.as_mut() {
                t.truncate(keep);
            }
        }
        clip.loop_error = if error.is_finite() {
            error
        } else {
            loop_error(&clip)
        };
        Ok(clip)
    }

    /// Bakes a walker's `idle` clip: standing still, breathing (one breath: the gait's
    /// breathing rate), arms bobbing; it loops.
    ///
    /// # Errors
    /// As [`bake_walk`](Self::bake_walk).
    pub fn bake_idle(&self) -> Result<Clip, Error> {
        let rate = self
            .gait
            .as_ref()
            .map_or(0.25, |g| g.options.breathe_rate)
            .max(1.0 / 60.0);
        self.bake_gait("idle", 1.0 / rate, 0.0, 0.0)
    }

    /// Bakes a walker's `turn` clip: turning in place to its left at a quarter turn per second
    /// for 4 s (one full turn), the legs stepping with the rotation and the neck and tail bent
    /// toward the turn (0.35 rad over each, shared by its bones). The root turns a full circle
    /// (its sway aside); the legs' phase need not come back, so the clip does not loop
    /// exactly.
    ///
    /// # Errors
    /// As [`bake_walk`](Self::bake_walk).
    pub fn bake_turn(&self) -> Result<Clip, Error> {
        self.bake_gait("turn", 4.0, 0.0, core::f32::consts::FRAC_PI_2)
    }

    fn bake_gait(
        &self,
        name: &'static str,
        seconds: f32,
        speed: f32,
        yaw_rate: f32,
    ) -> Result<Clip, Error> {
        let max = 60.0;
        let min = 1.0 / CLIP_FPS;
        if !(min..=max).contains(&seconds) {
            return Err(Error::OutOfRange {
                what: "seconds",
                value: seconds,
                min,
                max,
            });
        }
        let setup = self.gait.as_ref().ok_or(Error::NoGait)?;
        let mut controller = setup.controller()?;
        let ground = Plane::horizontal(0.0);
        let dt = 1.0 / CLIP_FPS;
        let velocity = Vec3::Z * speed;
        let spin = Vec3::Y * yaw_rate;
        let warm_up = (WARM_UP * CLIP_FPS) as usize;
        let frames = (seconds * CLIP_FPS + 0.5) as usize + 1;
        let joints = &self.skeleton.joints;
        let (_, rest_root) = self.root_joint();
        let rest = |j: usize| joints.get(j).map_or(Vec3::ZERO, |j| j.position);

        // Turning: the neck and tail bend toward the turn (constant over the clip).
        let spine_rotations = self.turn_bend(yaw_rate);
        let mut local: Vec<Affine3A> = self
            .skeleton
            .rest_translations()
            .iter()
            .map(|&t| Affine3A::from_translation(t))
            .collect();
        for &(j, q) in &spine_rotations {
            let t = local
                .get(j)
                .map_or(Vec3::ZERO, |l| Vec3::from(l.translation));
            if let Some(l) = local.get_mut(j) {
                *l = Affine3A::from_rotation_translation(q, t);
            }
        }
        let body_global = forward_kinematics(joints, &local);

        let legs = setup.hip_joints.len();
        let mut clip = Clip {
            name,
            fps: CLIP_FPS,
            frames,
            root_translation: Vec::with_capacity(frames),
            root_rotation: Vec::with_capacity(frames),
            tracks: Vec::with_capacity(3 * legs + spine_rotations.len()),
            contacts: Vec::with_capacity(frames),
            loop_error: 0.0,
        };
        for &hip in &setup.hip_joints {
            clip.tracks.push(Track {
                joint: hip,
                translations: Some(Vec::with_capacity(frames)),
                rotations: Vec::with_capacity(frames),
            });
            clip.tracks.push(Track {
                joint: hip + 1,
                translations: None,
                rotations: Vec::with_capacity(frames),
            });
            clip.tracks.push(Track {
                joint: hip + 2,
                translations: None,
                rotations: Vec::with_capacity(frames),
            });
        }
        for &(joint, q) in &spine_rotations {
            clip.tracks.push(Track {
                joint,
                translations: None,
                rotations: alloc::vec![q; frames],
            });
        }
        // The clip starts at the rest pose's place and heading: the warm-up's travel is
        // taken off.
        let start = Pose::from_yaw(
            Vec3::Z * (warm_up as f32 * dt * speed),
            warm_up as f32 * dt * yaw_rate,
        );
        let unstart = start.rotation.inverse();
        for step in 0..warm_up + frames {
            let time = step as f32 * dt;
            controller.update(
                dt,
                Pose::from_yaw(Vec3::Z * (time * speed), time * yaw_rate),
                velocity,
                spin,
                &ground,
            )?;
            if step < warm_up {
                continue;
            }
            let body = controller.reacted_pose();
            let rotation = (unstart * body.rotation).normalize();
            let translation = unstart * (body.translation - start.translation);
            clip.root_translation
                .push(translation + rotation * rest_root);
            clip.root_rotation.push(rotation);
            let states = controller.leg_states();
            clip.contacts
                .push(states.iter().map(|s| s.planted).collect());
            for (leg, state) in states.iter().enumerate() {
                let Some(&hip) = setup.hip_joints.get(leg) else {
                    continue;
                };
                let ik = state.joints;
                let to_body = |p: Vec3| body.inverse_transform_point(p);
                let (hip_b, knee_b, foot_b) =
                    (to_body(ik.root), to_body(ik.middle), to_body(ik.end));
                let rest_upper = (rest(hip + 1) - rest(hip)).normalize_or(Vec3::NEG_Y);
                let rest_lower = (rest(hip + 2) - rest(hip + 1)).normalize_or(Vec3::NEG_Y);
                let upper = (knee_b - hip_b).normalize_or(rest_upper);
                let hip_rotation = Quat::from_rotation_arc(rest_upper, upper);
                let lower = (foot_b - knee_b).normalize_or(rest_lower);
                let knee_rotation =
                    Quat::from_rotation_arc(rest_lower, hip_rotation.inverse() * lower);
                // The hip's parent (a spine joint, maybe bent) in body space.
                let parent = joints
                    .get(hip)
                    .and_then(|j| j.parent)
                    .and_then(|p| body_global.get(p).copied())
                    .unwrap_or(Affine3A::IDENTITY);
                let parent_rotation = Quat::from_mat3a(&parent.matrix3).normalize();
                if let Some(track) = clip.tracks.get_mut(3 * leg) {
                    if let Some(t) = track.translations.as_mut() {
                        t.push(parent.inverse().transform_point3(hip_b));
                    }
                    track
                        .rotations
                        .push((parent_rotation.inverse() * hip_rotation).normalize());
                }
                if let Some(track) = clip.tracks.get_mut(3 * leg + 1) {
                    track.rotations.push(knee_rotation.normalize());
                }
                // The foot stays level (its sole flat on the ground), turned with the body's
                // heading only: its world rotation is the heading's yaw.
                if let Some(track) = clip.tracks.get_mut(3 * leg + 2) {
                    let forward = body.rotation * Vec3::Z;
                    let heading =
                        Quat::from_rotation_y(glam::Vec2::new(forward.z, forward.x).to_angle());
                    track.rotations.push(
                        ((body.rotation * hip_rotation * knee_rotation).inverse() * heading)
                            .normalize(),
                    );
                }
            }
        }
        clip.loop_error = loop_error(&clip);
        Ok(clip)
    }

    /// Local rotations of the neck and tail joints bending toward a turn at `yaw_rate`.
    fn turn_bend(&self, yaw_rate: f32) -> Vec<(usize, Quat)> {
        if yaw_rate == 0.0 {
            return Vec::new();
        }
        let total = 0.35 * yaw_rate.signum() * (yaw_rate.abs() / 1.5).min(1.0);
        let spine = &self.rig.spine;
        let root = self.rig.root();
        let Some(c) = spine.iter().position(|&j| Some(j) == root) else {
            return Vec::new();
        };
        let bones = spine.len().saturating_sub(1);
        let neck: Vec<usize> = spine.iter().take(bones).skip(c + 1).copied().collect();
        let tail = self.tail_chain();
        let mut out = Vec::with_capacity(neck.len() + tail.len());
        for &j in &neck {
            out.push((j, Quat::from_rotation_y(total / neck.len() as f32)));
        }
        for &j in &tail {
            out.push((j, Quat::from_rotation_y(-total / tail.len() as f32)));
        }
        out
    }

    /// The joints' model-space transforms at frame `frame` of `clip` (clamped to its last
    /// frame), by forward kinematics from the root: skin with
    /// `pose[j] * inverse_bind_matrices()[j]`.
    #[must_use]
    pub fn pose(&self, clip: &Clip, frame: usize) -> Vec<Affine3A> {
        let joints = &self.skeleton.joints;
        let frame = frame.min(clip.frames.saturating_sub(1));
        let local_rest = self.skeleton.rest_translations();
        let mut local: Vec<Affine3A> = local_rest
            .iter()
            .map(|&t| Affine3A::from_translation(t))
            .collect();
        for track in &clip.tracks {
            let translation = track
                .translations
                .as_ref()
                .and_then(|t| t.get(frame).copied())
                .or_else(|| local_rest.get(track.joint).copied())
                .unwrap_or(Vec3::ZERO);
            let rotation = track
                .rotations
                .get(frame)
                .copied()
                .unwrap_or(Quat::IDENTITY);
            if let Some(l) = local.get_mut(track.joint) {
                *l = Affine3A::from_rotation_translation(rotation, translation);
            }
        }
        if let Some(root) = joints.iter().position(|j| j.parent.is_none())
            && let (Some(&t), Some(&r)) = (
                clip.root_translation.get(frame),
                clip.root_rotation.get(frame),
            )
            && let Some(l) = local.get_mut(root)
        {
            *l = Affine3A::from_rotation_translation(r, t);
        }
        forward_kinematics(joints, &local)
    }
}

/// The largest angle between first and last rotations (root and tracks), plus the root's
/// height change.
fn loop_error(clip: &Clip) -> f32 {
    error_between(clip, 0, clip.frames.saturating_sub(1))
}

/// The largest rotation angle between frames `a` and `b` (root and tracks), the root's height
/// change, and the largest change of a track's translation.
fn error_between(clip: &Clip, a: usize, b: usize) -> f32 {
    let angle = |v: &[Quat]| match (v.get(a), v.get(b)) {
        (Some(p), Some(q)) => p.angle_between(*q),
        _ => 0.0,
    };
    let mut error = angle(&clip.root_rotation);
    for track in &clip.tracks {
        error = error.max(angle(&track.rotations));
        if let Some(t) = &track.translations
            && let (Some(p), Some(q)) = (t.get(a), t.get(b))
        {
            error = error.max(p.distance(*q));
        }
    }
    if let (Some(p), Some(q)) = (clip.root_translation.get(a), clip.root_translation.get(b)) {
        error = error.max((p.y - q.y).abs());
    }
    error
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

impl Creature {
    /// The mesh's positions skinned (linear blend) with the pose at frame `frame` of `clip`.
    ///
    /// ```
    /// use creature::{generate, Kind, Params};
    ///
    /// let fish = generate(4, &Params::DEFAULT.with_kind(Kind::Swimmer))?;
    /// let swim = &fish.bake_clips()?[1];
    /// let posed = fish.posed_positions(swim, 10)?;
    /// assert_eq!(posed.len(), fish.mesh.positions.len());
    /// # Ok::<(), creature::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Skin`] if the mesh's joints and weights are not valid for its skeleton.
    pub fn posed_positions(&self, clip: &Clip, frame: usize) -> Result<Vec<Vec3>, Error> {
        let pose = self.pose(clip, frame);
        let transforms: Vec<Affine3A> = pose
            .iter()
            .zip(&self.skeleton.joints)
            .map(|(m, j)| *m * Affine3A::from_translation(-j.position))
            .collect();
        let influences: Vec<creature_skin::Influences> = self
            .mesh
            .joints
            .iter()
            .zip(&self.mesh.weights)
            .map(|(&joints, &weights)| creature_skin::Influences { joints, weights })
            .collect();
        let mut out = alloc::vec![Vec3::ZERO; self.mesh.positions.len()];
        creature_skin::skin_positions(
            &self.mesh.positions,
            &influences,
            &transforms,
            creature_skin::Blend::Linear,
            &mut out,
        )?;
        Ok(out)
    }

    /// The skeleton joints of limb `limb` of the plan, in chain order (root first).
    #[must_use]
    pub fn limb_joints(&self, limb: usize) -> Vec<usize> {
        self.skeleton
            .joints
            .iter()
            .enumerate()
            .filter(|(_, j)| j.part == Part::Limb(limb))
            .map(|(i, _)| i)
            .collect()
    }

    /// The clips of the creature's kind, each looping except `walk` and `turn`: walkers
    /// `idle`, `walk` (whole strides, see [`bake_walk_loop`](Self::bake_walk_loop)) and
    /// `turn` (a full turn in place); fliers `hover` and `fly`;
    /// swimmers `idle` and `swim`.
    ///
    /// Fliers' wings beat by `gait::FlapParams` (flapping wings slow, 4 bones with a lagging
    /// tip; buzzing wings at 8 beats per second, the fastest a 30 fps clip shows), the body
    /// bobs, dangling legs swing with the bob and the tail sways. Swimmers' spines wave from
    /// head to tail by `gait::SwimParams` (`idle`: the gentle sway), the tail fin following
    /// with a lag and the other fins fluttering. Each looping clip lasts a whole number of
    /// its motion's periods.
    ///
    /// ```
    /// use creature::{generate, Kind, Params};
    ///
    /// for kind in [Kind::Walker, Kind::Flier, Kind::Swimmer] {
    ///     let c = generate(3, &Params::DEFAULT.with_kind(kind))?;
    ///     let clips = c.bake_clips()?;
    ///     assert!(clips.len() >= 2);
    ///     for clip in clips.iter().filter(|c| c.name != "walk" && c.name != "turn") {
    ///         assert!(clip.loop_error < 1e-2, "{} {}", clip.name, clip.loop_error);
    ///     }
    /// }
    /// # Ok::<(), creature::Error>(())
    /// ```
    ///
    /// # Errors
    /// The controller's errors for walkers, as [`bake_walk`](Self::bake_walk).
    pub fn bake_clips(&self) -> Result<Vec<Clip>, Error> {
        Ok(match self.kind {
            CreatureKind::Walker => {
                alloc::vec![self.bake_idle()?, self.bake_walk_loop()?, self.bake_turn()?]
            }
            CreatureKind::Flier => {
                alloc::vec![
                    self.bake_flight("hover", 0.0),
                    self.bake_flight("fly", self.speed)
                ]
            }
            CreatureKind::Swimmer => {
                alloc::vec![
                    self.bake_swim("idle", 0.0),
                    self.bake_swim("swim", self.speed)
                ]
            }
        })
    }

    fn root_joint(&self) -> (usize, Vec3) {
        let root = self
            .skeleton
            .joints
            .iter()
            .position(|j| j.parent.is_none())
            .unwrap_or(0);
        let position = self
            .skeleton
            .joints
            .get(root)
            .map_or(Vec3::ZERO, |j| j.position);
        (root, position)
    }

    /// A flier's `hover` (speed 0) or `fly` clip.
    fn bake_flight(&self, name: &'static str, speed: f32) -> Clip {
        let buzzing = self.plan.limbs_of(LimbKind::BuzzingWing).count() > 0;
        let flap = if buzzing {
            FlapParams::BUZZING.with_frequency(8.0)
        } else {
            FlapParams::FLAPPING
        };
        // Buzzing: the hover bob's period (10 beats); flapping: 3 beats (bob in time).
        let bob_rate = if buzzing {
            flap.idle_frequency
        } else {
            flap.frequency
        };
        let seconds = if buzzing {
            1.0 / bob_rate
        } else {
            3.0 / flap.frequency
        };
        let (frames, fps) = frames_for(seconds);
        // (joint, kind of motion, side sign, index in chain)
        let mut animated = Vec::new();
        for (index, limb) in self.plan.limbs.iter().enumerate() {
            let sign = side_sign(limb.side);
            for (k, joint) in self.limb_joints(index).into_iter().enumerate() {
                let motion = match limb.kind {
                    LimbKind::BuzzingWing | LimbKind::FlappingWing => Motion::Wing,
                    LimbKind::Leg | LimbKind::Arm if k < 2 => Motion::Dangle,
                    _ => continue,
                };
                animated.push((joint, motion, sign, k));
            }
        }
        let (_, rest_root) = self.root_joint();
        let tail = self.tail_chain();
        for (k, &j) in tail.iter().enumerate() {
            animated.push((j, Motion::Tail, 1.0, k));
        }
        let joints: Vec<usize> = animated.iter().map(|a| a.0).collect();
        let mut clip = empty_clip(name, fps, frames, &joints);
        for f in 0..frames {
            let t = f as f32 / fps;
            clip.root_translation
                .push(rest_root + flap.body_offset(t, speed) + Vec3::Z * (speed * t));
            clip.root_rotation.push(Quat::IDENTITY);
            for (track, &(_, motion, sign, k)) in clip.tracks.iter_mut().zip(&animated) {
                let phase = bob_rate * t - 0.1 * k as f32;
                let rotation = match motion {
                    Motion::Wing if k == 0 => {
                        flap.wing_rotation(t, if sign > 0.0 { Side::Left } else { Side::Right })
                    }
                    Motion::Wing => Quat::from_rotation_z(
                        sign * 0.25
                            * flap.amplitude
                            * sin_turns(flap.frequency * t - 0.12 * k as f32),
                    ),
                    Motion::Dangle => Quat::from_rotation_x(0.12 * sin_turns(phase - 0.15)),
                    _ => Quat::from_rotation_x(0.04 * sin_turns(phase - 0.25)),
                };
                track.rotations.push(rotation.normalize());
            }
        }
        clip.loop_error = loop_error(&clip);
        clip
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

    /// A swimmer's `idle` (speed 0) or `swim` clip.
    fn bake_swim(&self, name: &'static str, speed: f32) -> Clip {
        let swim_params = SwimParams::DEFAULT;
        // Swimming waves at full weight (any speed moves the body); idle is the sway alone.
        let (wave_speed, rate) = if speed > 0.0 {
            (swim_params.full_speed, swim_params.frequency)
        } else {
            (0.0, swim_params.idle_frequency)
        };
        let seconds = if speed > 0.0 { 2.0 / rate } else { 1.0 / rate };
        let (frames, fps) = frames_for(seconds);
        let (_, rest_root) = self.root_joint();
        // Spine joints from the head (the root) toward the tail, with their place along it.
        let spine: Vec<usize> = self.rig.spine.iter().rev().copied().collect();
        let length = self.rig.spine_length().max(1e-6);
        let mut along = Vec::with_capacity(spine.len());
        let mut arc = 0.0f32;
        for (i, &j) in spine.iter().enumerate() {
            if i > 0 {
                let previous = spine.get(i - 1).copied().unwrap_or(j);
                let p = |j: usize| self.rig.joints.get(j).map_or(Vec3::ZERO, |j| j.position);
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
        for (index, limb) in self.plan.limbs.iter().enumerate() {
            let motion = if limb.kind == LimbKind::Tail {
                Motion::TailFin
            } else {
                Motion::Fin
            };
            for (k, joint) in self.limb_joints(index).into_iter().enumerate() {
                animated.push((joint, motion, side_sign(limb.side), k));
            }
        }
        let joints: Vec<usize> = animated.iter().map(|a| a.0).collect();
        let mut clip = empty_clip(name, fps, frames, &joints);
        let yaw_at = |t: f32, i: usize| {
            swim_params.bone_yaw(t, wave_speed, along.get(i).copied().unwrap_or(1.0))
        };
        for f in 0..frames {
            let t = f as f32 / fps;
            let head = yaw_at(t, 0);
            clip.root_translation
                .push(rest_root + Vec3::Z * (speed * t));
            clip.root_rotation.push(Quat::from_rotation_y(head));
            for (track, &(_, motion, sign, k)) in clip.tracks.iter_mut().zip(&animated) {
                let rotation = match motion {
                    // Each bone's yaw relative to its parent's (the previous along the spine).
                    Motion::Spine => Quat::from_rotation_y(yaw_at(t, k) - yaw_at(t, k - 1)),
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
}

/// What drives an animated joint of a flier or swimmer clip.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Motion {
    Wing,
    Dangle,
    Tail,
    Spine,
    TailFin,
    Fin,
}

fn side_sign(side: creature_limbs::Side) -> f32 {
    match side {
        creature_limbs::Side::Left => 1.0,
        creature_limbs::Side::Right => -1.0,
        creature_limbs::Side::Center => 1.0,
    }
}

/// Model-space transforms from local ones, parents resolved by walking up each chain (parents
/// may come after children in the list).
fn forward_kinematics(joints: &[crate::Joint3d], local: &[Affine3A]) -> Vec<Affine3A> {
    let n = joints.len();
    let mut global: Vec<Option<Affine3A>> = alloc::vec![None; n];
    for start in 0..n {
        let mut chain = Vec::new();
        let mut at = Some(start);
        while let Some(j) = at {
            if global.get(j).is_some_and(Option::is_some) || chain.len() > n {
                break;
            }
            chain.push(j);
            at = joints.get(j).and_then(|j| j.parent);
        }
        let mut above = at
            .and_then(|j| global.get(j).copied().flatten())
            .unwrap_or(Affine3A::IDENTITY);
        for &j in chain.iter().rev() {
            above *= local.get(j).copied().unwrap_or(Affine3A::IDENTITY);
            if let Some(g) = global.get_mut(j) {
                *g = Some(above);
            }
        }
    }
    global
        .into_iter()
        .map(|g| g.unwrap_or(Affine3A::IDENTITY))
        .collect()
}
