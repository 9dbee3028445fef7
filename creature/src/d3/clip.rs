//! Baked animation clips of 3D creatures: the gait controller run at a fixed step on flat
//! ground, joint transforms sampled per frame.

use alloc::vec::Vec;

use glam::{Affine3A, Quat, Vec3};

use creature_gait::{
    Chain, Controller, FlapParams, GaitOptions, Plane, Pose, Side, SwimParams, solve_two_bone,
};
use creature_limbs::{CreatureKind, LimbKind};

use crate::Error;
use crate::d3::{Creature, Part};

/// Frames per second of baked clips.
pub const CLIP_FPS: f32 = 30.0;
/// Seconds the controller runs before a clip's first frame, so the gait is in its steady
/// rhythm.
const WARM_UP: f32 = 1.0;

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
    /// Bakes a `walk` clip of `seconds` (at least one frame interval, at most 60 s): the
    /// walker moves forward (+Z) at its [`speed`](Creature::speed) over flat ground at
    /// `y = 0`, its legs stepping by the gait controller; each frame records the root's
    /// motion (with the body's bob and sway), each leg's hip translation, its hip and knee
    /// rotations (from the controller's two-bone IK) and a foot rotation that keeps the sole
    /// level (turned with the body's heading only), and the feet's contacts.
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
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

    /// Bakes a looping `walk`: 4 s are simulated as by [`bake_walk`](Self::bake_walk), then
    /// cut at the frame from 1 s on that comes closest to the first (the same feet planted,
    /// the feet nearest their first places relative to the body), so the clip lasts whole
    /// strides; the loop is then closed exactly (see [`Clip::loop_error`]): the small mismatch
    /// of the body's pose is spread over the clip, and each foot's over its swings only, so a
    /// planted foot never moves. The root travels forward (root motion): its forward
    /// translation does not come back. If closing would stretch a planted leg beyond its reach
    /// (a nearly straight leg; 68 walkers in 10,000 with the default params), the clip is only
    /// cut, and its `loop_error` says how far it is from looping.
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    ///
    /// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
    /// let walk = walker.bake_walk_loop()?;
    /// assert!(walk.duration() >= 1.0 && walk.duration() <= 4.0);
    /// assert!(walk.loop_error < 1e-3);
    /// # Ok::<(), creature::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`bake_walk`](Self::bake_walk).
    pub fn bake_walk_loop(&self) -> Result<Clip, Error> {
        let run = self.simulate_gait(4.0, self.speed, 0.0)?;
        let first = CLIP_FPS as usize;
        let end = best_cut(&run, first..run.frames(), |_| 0.0);
        let travel = Pose::from_yaw(Vec3::Z * (self.speed * end as f32 / CLIP_FPS), 0.0);
        let run = self.closed_or_cut(run, end, &travel);
        self.clip_from_run("walk", &run, 0.0)
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

    /// Bakes a walker's `turn` clip: turning in place to its left at about a quarter turn per
    /// second, one full turn, the legs stepping with the rotation and the neck and tail bent
    /// toward the turn (0.35 rad over each, shared by its bones). It is cut, like
    /// [`bake_walk_loop`](Self::bake_walk_loop), at the frame from 3.5 s to 4.5 s with the
    /// same feet planted as the first that best completes the turn; the rate is then retried
    /// (up to twice) so that the turn completes exactly at the cut, and the best try kept.
    /// Its loop is closed exactly: the root ends where it started, a full turn later, any
    /// shortfall of the turn spread over the clip; unless that would stretch a planted leg
    /// beyond its reach (183 walkers in 10,000 with the default params), as in
    /// [`bake_walk_loop`](Self::bake_walk_loop).
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    ///
    /// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
    /// let turn = walker.bake_turn()?;
    /// assert!(turn.duration() > 3.0 && turn.duration() < 5.0);
    /// assert!(turn.loop_error < 1e-3);
    /// # Ok::<(), creature::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`bake_walk`](Self::bake_walk).
    pub fn bake_turn(&self) -> Result<Clip, Error> {
        let full = core::f32::consts::TAU;
        let window = (3.5 * CLIP_FPS) as usize..(4.5 * CLIP_FPS) as usize + 1;
        // The turn's shortfall (or excess) at the cut is spread over the clip, which moves the
        // hips over the planted feet: it weighs as far as it moves the farthest hip.
        let radius = self.gait.as_ref().map_or(0.0, |g| {
            g.legs
                .iter()
                .map(|l| glam::Vec2::new(l.hip.x, l.hip.z).length())
                .fold(0.0, f32::max)
        });
        // Cut at the frame near 4 s with the first frame's feet planted; then try again at
        // the rate that completes the turn exactly at that frame (the steps shift with the
        // rate), keeping the best of three.
        let mut rate = core::f32::consts::FRAC_PI_2;
        let mut best: Option<(f32, f32, GaitRun, usize)> = None;
        for _ in 0..3 {
            let run = self.simulate_gait(5.0, 0.0, rate)?;
            let shortfall = |f: usize| radius * (f as f32 / CLIP_FPS * rate - full).abs();
            let end = best_cut(&run, window.clone(), shortfall);
            let score = run.mismatch(end) + shortfall(end);
            let next = full / (end.max(1) as f32 / CLIP_FPS);
            if best.as_ref().is_none_or(|b| score < b.0) {
                best = Some((score, rate, run, end));
            }
            if score <= 0.0 || next == rate {
                break;
            }
            rate = next;
        }
        let Some((_, rate, run, end)) = best else {
            return Err(Error::NoGait);
        };
        let run = self.closed_or_cut(run, end, &Pose::IDENTITY);
        self.clip_from_run("turn", &run, rate)
    }

    fn bake_gait(
        &self,
        name: &'static str,
        seconds: f32,
        speed: f32,
        yaw_rate: f32,
    ) -> Result<Clip, Error> {
        let run = self.simulate_gait(seconds, speed, yaw_rate)?;
        self.clip_from_run(name, &run, yaw_rate)
    }

    /// `run` cut after frame `end` with its loop closed by `motion`, unless closing it leaves a
    /// planted foot further out of its leg's reach than the plain cut does (the spread
    /// correction can stretch a leg that was nearly straight), or would slide a foot that
    /// never lifts in the clip (a walker so slow that it takes no step in it): then the plain
    /// cut, whose [`Clip::loop_error`] says how far it is from looping.
    fn closed_or_cut(&self, run: GaitRun, end: usize, motion: &Pose) -> GaitRun {
        let mut closed = run.clone();
        let planted_shift = closed.close_loop(end, motion);
        let mut cut = run;
        cut.truncate(end + 1);
        let tolerance = 1e-4 * self.length;
        if planted_shift <= tolerance && self.overreach(&closed) <= self.overreach(&cut) + tolerance
        {
            closed
        } else {
            cut
        }
    }

    /// How far (metres) the farthest planted foot of `run` is beyond its leg's reach. Only
    /// walking legs: an arm holding its place is not on the ground, and may lag out of reach.
    fn overreach(&self, run: &GaitRun) -> f32 {
        let Some(setup) = self.gait.as_ref() else {
            return 0.0;
        };
        let mut worst = 0.0f32;
        for (frame, body) in run.bodies.iter().enumerate() {
            for (i, leg) in setup.legs.iter().enumerate() {
                if leg.kind == creature_gait::LimbKind::Leg && run.planted(frame, i) {
                    let d = body
                        .inverse_transform_point(run.foot(frame, i))
                        .distance(leg.hip);
                    worst = worst.max(d - (leg.upper + leg.lower));
                }
            }
        }
        worst
    }

    /// Runs the gait controller at [`CLIP_FPS`] over flat ground for `seconds` after the
    /// warm-up, moving forward at `speed` and turning at `yaw_rate`; records the reacted body
    /// pose and the feet per frame, relative to the clip's starting place and heading.
    fn simulate_gait(&self, seconds: f32, speed: f32, yaw_rate: f32) -> Result<GaitRun, Error> {
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
        let legs = setup.legs.len();
        let mut run = GaitRun {
            bodies: Vec::with_capacity(frames),
            feet: Vec::with_capacity(frames * legs),
            contacts: Vec::with_capacity(frames),
            legs,
        };
        // The clip starts at the rest pose's place and heading: the warm-up's travel is
        // taken off.
        let start = Pose::from_yaw(
            Vec3::Z * (warm_up as f32 * dt * speed),
            warm_up as f32 * dt * yaw_rate,
        );
        let unstart = start.rotation.inverse();
        let relative = |p: Vec3| unstart * (p - start.translation);
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
            run.bodies.push(Pose {
                translation: relative(body.translation),
                rotation: (unstart * body.rotation).normalize(),
            });
            let states = controller.leg_states();
            run.contacts
                .push(states.iter().map(|s| s.planted).collect());
            run.feet.extend(states.iter().map(|s| relative(s.foot)));
        }
        Ok(run)
    }

    /// A clip from a recorded gait run: the root's motion, each leg's hip translation, hip
    /// and knee rotations by two-bone IK from the hip to the recorded foot (the leg's pole
    /// bending the knee), and a foot rotation that keeps the sole level (turned with the
    /// body's heading only); the neck and tail bent toward a turn at `yaw_rate`.
    fn clip_from_run(
        &self,
        name: &'static str,
        run: &GaitRun,
        yaw_rate: f32,
    ) -> Result<Clip, Error> {
        let setup = self.gait.as_ref().ok_or(Error::NoGait)?;
        let frames = run.frames();
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

        let mut clip = Clip {
            name,
            fps: CLIP_FPS,
            frames,
            root_translation: Vec::with_capacity(frames),
            root_rotation: Vec::with_capacity(frames),
            tracks: Vec::with_capacity(3 * run.legs + spine_rotations.len()),
            contacts: run.contacts.clone(),
            loop_error: 0.0,
        };
        // Per leg: the hip's parent (a spine joint, maybe bent) in body space, the rest
        // directions of the leg's two segments, and its three tracks.
        let mut frames_of_leg = Vec::with_capacity(run.legs);
        for (leg, &hip) in setup.legs.iter().zip(&setup.hip_joints) {
            let parent = joints
                .get(hip)
                .and_then(|j| j.parent)
                .and_then(|p| body_global.get(p).copied())
                .unwrap_or(Affine3A::IDENTITY);
            let rest_upper = (rest(hip + 1) - rest(hip)).normalize_or(Vec3::NEG_Y);
            let rest_lower = (rest(hip + 2) - rest(hip + 1)).normalize_or(Vec3::NEG_Y);
            let knee_radius = self.ring_radius(hip + 1);
            frames_of_leg.push((leg, parent, rest_upper, rest_lower, knee_radius));
            clip.tracks.push(Track {
                joint: hip,
                translations: Some(Vec::with_capacity(frames)),
                rotations: Vec::with_capacity(frames),
            });
            for joint in [hip + 1, hip + 2] {
                clip.tracks.push(Track {
                    joint,
                    translations: None,
                    rotations: Vec::with_capacity(frames),
                });
            }
        }
        for &(joint, q) in &spine_rotations {
            clip.tracks.push(Track {
                joint,
                translations: None,
                rotations: alloc::vec![q; frames],
            });
        }
        // Nothing under the floor: a frame whose body would dip below it (its lean, bob or
        // breathing, on a body that reaches down to the ground) leans less and, if need be,
        // rises, before the legs are solved, so the feet stay planted.
        let bodies = self.above_the_floor(&body_global, run)?;
        for (frame, body) in bodies.iter().enumerate() {
            clip.root_translation
                .push(body.translation + body.rotation * rest_root);
            clip.root_rotation.push(body.rotation);
            let forward = body.rotation * Vec3::Z;
            let heading = Quat::from_rotation_y(glam::Vec2::new(forward.z, forward.x).to_angle());
            let up = body.rotation.inverse() * Vec3::Y;
            for (i, &(leg, parent, rest_upper, rest_lower, knee_radius)) in
                frames_of_leg.iter().enumerate()
            {
                let foot = body.inverse_transform_point(run.foot(frame, i));
                let ik = solve_two_bone(leg.hip, foot, leg.upper, leg.lower, leg.pole);
                let floor = knee_radius - body.translation.y;
                let middle = knee_above(ik.root, ik.middle, ik.end, up, floor);
                let upper = (middle - ik.root).normalize_or(rest_upper);
                let hip_rotation = rotation_arc(rest_upper, upper);
                let lower = (ik.end - middle).normalize_or(rest_lower);
                let knee_rotation = rotation_arc(rest_lower, hip_rotation.inverse() * lower);
                let parent_rotation = Quat::from_mat3a(&parent.matrix3).normalize();
                if let Some(track) = clip.tracks.get_mut(3 * i) {
                    if let Some(t) = track.translations.as_mut() {
                        t.push(parent.inverse().transform_point3(ik.root));
                    }
                    track
                        .rotations
                        .push((parent_rotation.inverse() * hip_rotation).normalize());
                }
                if let Some(track) = clip.tracks.get_mut(3 * i + 1) {
                    track.rotations.push(knee_rotation.normalize());
                }
                // The foot stays level (its sole flat on the ground), turned with the body's
                // heading only: its world rotation is the heading's yaw.
                if let Some(track) = clip.tracks.get_mut(3 * i + 2) {
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

    /// How far the mesh's vertices skinned to `joint` reach from its rest position: for a
    /// knee, the radius of the ring around it.
    fn ring_radius(&self, joint: usize) -> f32 {
        let Some(centre) = self.skeleton.joints.get(joint).map(|j| j.position) else {
            return 0.0;
        };
        let mesh = &self.mesh;
        mesh.positions
            .iter()
            .zip(&mesh.joints)
            .zip(&mesh.weights)
            .filter(|((_, js), ws)| {
                js.iter()
                    .zip(ws.iter())
                    .any(|(&j, &w)| usize::from(j) == joint && w > 0.0)
            })
            .map(|((p, _), _)| p.distance(centre))
            .fold(0.0f32, f32::max)
    }

    /// The run's body poses, each changed as little as needed so that no vertex of the body
    /// (the part of the mesh skinned to spine joints only, bent by `body_global`, the clip's
    /// constant spine pose in body space) is below the floor `y = 0`: first its lean (the
    /// rotation's swing away from the vertical axis) is scaled back toward none, then, if the
    /// upright body still dips, it is raised, but never so far that a planted foot leaves its
    /// leg's reach. Frames that do not dip are returned unchanged, bit for bit.
    fn above_the_floor(&self, body_global: &[Affine3A], run: &GaitRun) -> Result<Vec<Pose>, Error> {
        let joints = &self.skeleton.joints;
        let spine = |j: u16| {
            joints
                .get(usize::from(j))
                .is_some_and(|j| j.part == Part::Spine)
        };
        let mesh = &self.mesh;
        let mut shape: Vec<Vec3> = self
            .skinned(body_global)?
            .into_iter()
            .zip(mesh.joints.iter().zip(&mesh.weights))
            .filter(|(_, (js, ws))| {
                js.iter()
                    .zip(ws.iter())
                    .all(|(&j, &w)| w == 0.0 || spine(j))
            })
            .map(|(s, _)| s)
            .collect();
        // A vertex s of the body is at height (R s).y + t.y = u · s + t.y with u = Rᵀ ŷ. With
        // |u − ŷ| ≤ δ over the clip (less lean only brings u closer to ŷ), u · s lies within
        // δ|s| of s.y: only the vertices that can be lowest in some frame are kept.
        let delta = run
            .bodies
            .iter()
            .map(|b| (b.rotation.inverse() * Vec3::Y - Vec3::Y).length())
            .fold(0.0f32, f32::max);
        let bound = shape
            .iter()
            .map(|s| s.y + delta * s.length())
            .fold(f32::INFINITY, f32::min);
        shape.retain(|s| s.y - delta * s.length() <= bound);
        let low = |rotation: Quat, height: f32| {
            let up = rotation.inverse() * Vec3::Y;
            shape
                .iter()
                .map(|s| up.dot(*s))
                .fold(f32::INFINITY, f32::min)
                + height
        };
        let legs = self.gait.as_ref().map_or(&[][..], |g| g.legs.as_slice());
        Ok(run
            .bodies
            .iter()
            .enumerate()
            .map(|(frame, &body)| {
                if low(body.rotation, body.translation.y) >= 0.0 {
                    return body;
                }
                // The heading: the rotation's twist about the vertical axis.
                let q = body.rotation;
                let twist = glam::Vec2::new(q.y, q.w);
                let heading = if twist.length_squared() > 1e-12 {
                    let twist = twist.normalize();
                    Quat::from_xyzw(0.0, twist.x, 0.0, twist.y)
                } else {
                    Quat::IDENTITY
                };
                let leaned = |share: f32| heading.slerp(q, share).normalize();
                let mut rotation = heading;
                if low(heading, body.translation.y) >= 0.0 {
                    // Bisection on the share of the lean kept.
                    let (mut keep, mut drop) = (0.0f32, 1.0f32);
                    for _ in 0..FLOOR_BISECTIONS {
                        let mid = 0.5 * (keep + drop);
                        if low(leaned(mid), body.translation.y) >= 0.0 {
                            keep = mid;
                        } else {
                            drop = mid;
                        }
                    }
                    rotation = leaned(keep);
                }
                let mut pose = Pose {
                    rotation,
                    translation: body.translation,
                };
                let needed = -low(rotation, body.translation.y);
                if needed > 0.0 {
                    // Raise, as far as the planted feet allow.
                    let mut lift = needed;
                    for (i, leg) in legs.iter().enumerate() {
                        if !run.planted(frame, i) {
                            continue;
                        }
                        let hip = pose.transform_point(leg.hip);
                        let foot = run.foot(frame, i);
                        let reach = leg.upper + leg.lower;
                        // |foot − (hip + ŷ l)| ≤ reach: l ≤ (foot − hip).y + √(reach² − d²),
                        // d the horizontal distance.
                        let d = foot - hip;
                        let across2 = d.x * d.x + d.z * d.z;
                        let room = d.y + crate::math::sqrt((reach * reach - across2).max(0.0));
                        lift = lift.min(room.max(0.0));
                    }
                    pose.translation.y += lift;
                }
                pose
            })
            .collect())
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

/// A gait controller's run, frame by frame: the reacted body pose and the feet (world, relative
/// to the clip's start) and which feet are planted.
#[derive(Debug, Clone)]
struct GaitRun {
    bodies: Vec<Pose>,
    /// Frame-major: `legs` feet per frame.
    feet: Vec<Vec3>,
    contacts: Vec<Vec<bool>>,
    legs: usize,
}

impl GaitRun {
    fn frames(&self) -> usize {
        self.bodies.len()
    }

    fn foot(&self, frame: usize, leg: usize) -> Vec3 {
        self.feet
            .get(frame * self.legs + leg)
            .copied()
            .unwrap_or(Vec3::ZERO)
    }

    /// How far frame `end` is from repeating frame 0: the largest of each foot's offset from
    /// its first place relative to the body (metres), the root's height change and its tilt
    /// (radians) change, the heading aside.
    fn mismatch(&self, end: usize) -> f32 {
        let (Some(a), Some(b)) = (self.bodies.first(), self.bodies.get(end)) else {
            return f32::INFINITY;
        };
        let level = |p: &Pose| {
            let f = p.rotation * Vec3::Z;
            Quat::from_rotation_y(glam::Vec2::new(f.z, f.x).to_angle()).inverse() * p.rotation
        };
        let mut error = angle_between(level(a), level(b));
        error = error.max((a.translation.y - b.translation.y).abs());
        for leg in 0..self.legs {
            let pa = a.inverse_transform_point(self.foot(0, leg));
            let pb = b.inverse_transform_point(self.foot(end, leg));
            error = error.max(pa.distance(pb));
        }
        error
    }

    /// Keeps frames `0..=end` and closes the loop: frame `end` becomes frame 0 moved by
    /// `motion` (the root motion over the clip). The body's mismatch is spread linearly over
    /// the frames; each foot's over its swing frames only (in proportion to their count), so
    /// planted feet stay where they are; a foot that never swings takes it linearly, sliding:
    /// returns the longest such slide (0 when every foot swings or none has to move).
    fn close_loop(&mut self, end: usize, motion: &Pose) -> f32 {
        let keep = (end + 1).min(self.frames());
        if keep < 2 {
            return 0.0;
        }
        self.truncate(keep);
        let last = keep - 1;
        let (Some(&first), Some(&end_body)) = (self.bodies.first(), self.bodies.get(last)) else {
            return 0.0;
        };
        let mut planted_shift = 0.0f32;
        let target = Pose {
            translation: motion.transform_point(first.translation),
            rotation: (motion.rotation * first.rotation).normalize(),
        };
        let turn = (target.rotation * end_body.rotation.inverse()).normalize();
        let shift = target.translation - end_body.translation;
        for (f, body) in self.bodies.iter_mut().enumerate() {
            let s = f as f32 / last as f32;
            body.rotation = (Quat::IDENTITY.slerp(turn, s) * body.rotation).normalize();
            body.translation += shift * s;
        }
        for leg in 0..self.legs {
            let delta = motion.transform_point(self.foot(0, leg)) - self.foot(last, leg);
            let swings = (1..keep).filter(|&f| !self.planted(f, leg)).count();
            if swings == 0 {
                // Never lifted: its correction can only slide it.
                planted_shift = planted_shift.max(delta.length());
            }
            let mut done = 0usize;
            for f in 1..keep {
                let s = if swings == 0 {
                    f as f32 / last as f32
                } else {
                    if !self.planted(f, leg) {
                        done += 1;
                    }
                    done as f32 / swings as f32
                };
                if let Some(p) = self.feet.get_mut(f * self.legs + leg) {
                    let y = p.y;
                    *p += delta * s;
                    // A lifted foot at the ends may be corrected downward: never below the
                    // ground (y = 0) it was above.
                    if y >= 0.0 {
                        p.y = p.y.max(0.0);
                    }
                }
            }
        }
        planted_shift
    }

    /// Keeps the first `frames` frames.
    fn truncate(&mut self, frames: usize) {
        self.bodies.truncate(frames);
        self.contacts.truncate(frames);
        self.feet.truncate(frames * self.legs);
    }

    fn planted(&self, frame: usize, leg: usize) -> bool {
        self.contacts
            .get(frame)
            .and_then(|c| c.get(leg))
            .copied()
            .unwrap_or(false)
    }
}

/// Bisection steps on the share of a body's lean kept to hold it above the floor.
const FLOOR_BISECTIONS: usize = 16;

/// The frame of `range` with the same feet planted as frame 0 that has the smallest
/// [`GaitRun::mismatch`] plus `penalty(frame)`; the best frame of the range regardless of
/// contacts if none has them, the last frame if the range is empty.
fn best_cut(
    run: &GaitRun,
    range: core::ops::Range<usize>,
    penalty: impl Fn(usize) -> f32,
) -> usize {
    let last = run.frames().saturating_sub(1);
    let range = range.start.min(last).max(1)..range.end.min(last + 1);
    let score = |f: usize| run.mismatch(f) + penalty(f);
    let same = |f: &usize| run.contacts.get(*f) == run.contacts.first();
    let best = |candidates: &mut dyn Iterator<Item = usize>| {
        candidates.fold(None, |best: Option<(f32, usize)>, f| {
            let e = score(f);
            match best {
                Some((b, _)) if b <= e => best,
                _ => Some((e, f)),
            }
        })
    };
    best(&mut range.clone().filter(same))
        .or_else(|| best(&mut range.clone()))
        .map_or(last, |(_, f)| f)
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
        (Some(p), Some(q)) => angle_between(*p, *q),
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

/// The angle (radians) of the rotation between unit quaternions `p` and `q`, accurate for
/// small angles too (`Quat::angle_between` takes an arc cosine of a dot product near 1, which
/// rounds angles below about 1e-3 to 0): for unit quaternions `|p − q| = 2 sin(θ / 4)`.
fn angle_between(p: Quat, q: Quat) -> f32 {
    let d = (p - q).length().min((p + q).length());
    4.0 * crate::math::asin((0.5 * d).min(1.0))
}

/// The knee `middle` of a solved two-bone chain from `root` to `end`, turned about the
/// root–end axis as little as needed so that its height along `up` is at least `floor` (as
/// high as it can go when no turn reaches that): a knee never bends through the ground. The
/// chain's bone lengths and ends are unchanged; a knee already high enough is returned as is.
fn knee_above(root: Vec3, middle: Vec3, end: Vec3, up: Vec3, floor: f32) -> Vec3 {
    if up.dot(middle) >= floor {
        return middle;
    }
    let Some(dir) = (end - root).try_normalize() else {
        return middle;
    };
    let centre = root + dir * dir.dot(middle - root);
    let offset = middle - centre;
    let across = offset.length();
    if !(across > 0.0) {
        return middle;
    }
    let b1 = offset / across;
    let b2 = dir.cross(b1);
    // Height of the knee turned by φ: h(φ) = c + across (cos φ u₁ + sin φ u₂).
    let c = up.dot(centre);
    let (u1, u2) = (up.dot(b1), up.dot(b2));
    let m = crate::math::sqrt(u1 * u1 + u2 * u2);
    if !(m > 1e-9) {
        return middle;
    }
    let (u1, u2) = (u1 / m, u2 / m);
    // The turn (cos φ, sin φ) whose height is `floor`, nearest to no turn; the highest knee
    // when even that is too low.
    let k = (floor - c) / (across * m);
    let (cos, sin) = if k >= 1.0 {
        (u1, u2)
    } else {
        let k = k.max(-1.0);
        let w = crate::math::sqrt((1.0 - k * k).max(0.0));
        let a = (k * u1 - w * u2, k * u2 + w * u1);
        let b = (k * u1 + w * u2, k * u2 - w * u1);
        if a.0 >= b.0 { a } else { b }
    };
    centre + across * (cos * b1 + sin * b2)
}

/// The shortest rotation from unit vector `from` to unit vector `to`. Unlike
/// `Quat::from_rotation_arc`, which returns the identity below about 5e-4 rad (1.7 mm at the
/// foot of a 3.4 m leg), it is exact for small angles: (from × to, 1 + from · to) normalised.
fn rotation_arc(from: Vec3, to: Vec3) -> Quat {
    let dot = from.dot(to);
    if dot < -1.0 + 1e-6 {
        // Nearly opposite: any half turn about an axis across `from`.
        return Quat::from_rotation_arc(from, to);
    }
    let axis = from.cross(to);
    Quat::from_xyzw(axis.x, axis.y, axis.z, 1.0 + dot).normalize()
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
    /// use creature::d3::{generate, Kind, Params};
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
        self.skinned(&self.pose(clip, frame))
    }

    /// The mesh skinned by the joints' model-space transforms `pose` (one per joint, as
    /// [`pose`](Self::pose) gives them; the rest pose's joints are pure translations).
    fn skinned(&self, pose: &[Affine3A]) -> Result<Vec<Vec3>, Error> {
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

    /// The clips of the creature's kind, each looping: walkers `idle`, `walk` (whole
    /// strides, see [`bake_walk_loop`](Self::bake_walk_loop)) and `turn` (a full turn in
    /// place, see [`bake_turn`](Self::bake_turn)); fliers `hover` and `fly`; swimmers `idle`
    /// and `swim`.
    ///
    /// Fliers' wings beat by `gait::FlapParams` (flapping wings slow, 4 bones with a lagging
    /// tip; buzzing wings at 8 beats per second, the fastest a 30 fps clip shows), the body
    /// bobs, and its legs, arms and tail are damped chains (`gait::Chain` on a legless
    /// `gait::Controller`): the legs hang under gravity, swing with the bob and trail in
    /// flight, the tail follows through; the chains run three seconds (whole periods) before
    /// the first frame, so their start-up has died away and the clip loops. Swimmers' spines wave from
    /// head to tail by `gait::SwimParams` (`idle`: the gentle sway), the tail fin following
    /// with a lag and the other fins fluttering. Each looping clip lasts a whole number of
    /// its motion's periods.
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    ///
    /// for kind in [Kind::Walker, Kind::Flier, Kind::Swimmer] {
    ///     let c = generate(3, &Params::DEFAULT.with_kind(kind))?;
    ///     let clips = c.bake_clips()?;
    ///     assert!(clips.len() >= 2);
    ///     for clip in &clips {
    ///         assert!(clip.loop_error < 1e-3, "{} {}", clip.name, clip.loop_error);
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
                    self.bake_flight("hover", 0.0)?,
                    self.bake_flight("fly", self.speed)?
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
    fn bake_flight(&self, name: &'static str, speed: f32) -> Result<Clip, Error> {
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
        // Wings beat by the flap motion; legs, arms and the tail are damped chains.
        let mut wings = Vec::new();
        for (index, limb) in self.plan.limbs.iter().enumerate() {
            if matches!(limb.kind, LimbKind::BuzzingWing | LimbKind::FlappingWing) {
                let sign = side_sign(limb.side);
                for (k, joint) in self.limb_joints(index).into_iter().enumerate() {
                    wings.push((joint, sign, k));
                }
            }
        }
        let mut chains = Vec::new();
        for (index, limb) in self.plan.limbs.iter().enumerate() {
            if matches!(limb.kind, LimbKind::Leg | LimbKind::Arm) {
                chains.push((self.limb_joints(index), 9.81));
            }
        }
        let tail = self.tail_chain();
        if let Some(&tip) = self.rig.spine.first()
            && !tail.is_empty()
        {
            let mut joints = tail.clone();
            joints.push(tip);
            chains.push((joints, 0.0));
        }
        let flight = FlightChains::new(self, &chains, speed)?;
        let mut joints: Vec<usize> = wings.iter().map(|w| w.0).collect();
        joints.extend(flight.animated());
        let mut clip = empty_clip(name, fps, frames, &joints);
        let (_, rest_root) = self.root_joint();
        // The bob, and a slow figure-eight drift about the flight path (1.5% of the body
        // length hovering, 0.75% flying), once per clip, so hanging chains swing.
        let drift = self.length * if speed > 0.0 { 0.0075 } else { 0.015 };
        let offset = |t: f32| {
            let a = t / seconds;
            flap.body_offset(t, speed)
                + Vec3::new(drift * sin_turns(a), 0.0, drift * sin_turns(2.0 * a))
                + Vec3::Z * (speed * t)
        };
        let dt = 1.0 / fps;
        let mut flight = flight;
        // Whole clips of warm-up (at least FLIGHT_WARM_UP seconds), so the chains' start-up
        // has died away (their damping halves it in about 0.2 s) and frame 0 is in phase.
        let periods = crate::math::ceil_non_negative(FLIGHT_WARM_UP / seconds).max(1);
        let warm_up = periods * (frames - 1);
        for step in 0..warm_up + frames {
            let t = (step as f32 - warm_up as f32) * dt;
            let position = offset(t);
            flight.update(dt, position, Vec3::Z * speed)?;
            if step < warm_up {
                continue;
            }
            let t = t.max(0.0);
            clip.root_translation.push(rest_root + position);
            clip.root_rotation.push(Quat::IDENTITY);
            let mut tracks = clip.tracks.iter_mut();
            // `wings` first: zip then takes no track past the last wing joint.
            for (&(_, sign, k), track) in wings.iter().zip(tracks.by_ref()) {
                let rotation = if k == 0 {
                    flap.wing_rotation(t, if sign > 0.0 { Side::Left } else { Side::Right })
                } else {
                    Quat::from_rotation_z(
                        sign * 0.25
                            * flap.amplitude
                            * sin_turns(flap.frequency * t - 0.12 * k as f32),
                    )
                };
                track.rotations.push(rotation.normalize());
            }
            for (track, rotation) in tracks.zip(flight.rotations(self)) {
                track.rotations.push(rotation);
            }
        }
        clip.loop_error = loop_error(&clip);
        Ok(clip)
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

/// Seconds of simulation before a flier's clip starts (rounded up to whole bob periods).
const FLIGHT_WARM_UP: f32 = 3.0;

/// A flier's legs, arms and tail as damped chains of a legless gait controller: each chain is
/// straight at rest along its limb (root to tip), pulled toward that rest by a spring, by
/// gravity (legs and arms) and held back by damping, so it sways with the body's bob and
/// trails in flight. Each bone turns by its segment's deflection from the rest direction.
struct FlightChains {
    controller: Controller,
    /// Per chain: its skeleton joints (root first, the tip last; all but the tip animated),
    /// its rest direction and its index in the controller.
    chains: Vec<(Vec<usize>, Vec3, usize)>,
}

impl FlightChains {
    fn new(c: &Creature, chains: &[(Vec<usize>, f32)], speed: f32) -> Result<Self, Error> {
        let position = |j: usize| c.skeleton.joints.get(j).map_or(Vec3::ZERO, |j| j.position);
        let mut controller = Controller::chains_only(c.length.max(1e-3), &GaitOptions::DEFAULT)?;
        let mut out = Vec::with_capacity(chains.len());
        for (joints, gravity) in chains {
            let (Some(&root), Some(&tip)) = (joints.first(), joints.last()) else {
                continue;
            };
            let segments = joints.len().saturating_sub(1);
            let span = position(tip) - position(root);
            let length: f32 = joints
                .windows(2)
                .map(|w| match w {
                    [a, b] => position(*a).distance(position(*b)),
                    _ => 0.0,
                })
                .sum();
            if segments == 0 || !(length > 1e-6) || span.length_squared() < 1e-12 {
                continue;
            }
            let direction = span.normalize();
            // Damping 6 /s; the spring such that gravity sags a chain by about 15% of its
            // length and flight trails it by about 30%.
            let damping = 6.0;
            let stiffness = (gravity / (0.15 * length))
                .max(damping * speed / (0.3 * length))
                .clamp(20.0, 10_000.0);
            let chain = Chain::new(
                position(root),
                direction,
                segments,
                length / segments as f32,
            )
            .with_spring(stiffness, damping)
            .with_gravity(*gravity);
            let index = controller.add_chain(chain)?;
            out.push((joints.clone(), direction, index));
        }
        Ok(Self {
            controller,
            chains: out,
        })
    }

    /// The animated joints, in the order of [`rotations`](Self::rotations).
    fn animated(&self) -> impl Iterator<Item = usize> + '_ {
        self.chains
            .iter()
            .flat_map(|(joints, _, _)| joints.iter().take(joints.len().saturating_sub(1)))
            .copied()
    }

    fn update(&mut self, dt: f32, position: Vec3, velocity: Vec3) -> Result<(), Error> {
        // No ground under a flier.
        let ground = Plane::horizontal(f32::MIN / 4.0);
        self.controller.update(
            dt,
            Pose::from_yaw(position, 0.0),
            velocity,
            Vec3::ZERO,
            &ground,
        )?;
        Ok(())
    }

    /// The animated joints' local rotations now: each bone's global rotation is its segment's
    /// deflection from the chain's rest direction, taken relative to the nearest animated
    /// ancestor's.
    fn rotations(&self, c: &Creature) -> Vec<Quat> {
        let joints = &c.skeleton.joints;
        let mut global: Vec<Option<Quat>> = alloc::vec![None; joints.len()];
        for (chain_joints, direction, index) in &self.chains {
            let Ok(points) = self.controller.chain(*index) else {
                continue;
            };
            for (k, &j) in chain_joints.iter().enumerate().take(chain_joints.len() - 1) {
                let (Some(a), Some(b)) = (points.get(k), points.get(k + 1)) else {
                    continue;
                };
                let d = (*b - *a).normalize_or(*direction);
                if let Some(g) = global.get_mut(j) {
                    *g = Some(rotation_arc(*direction, d));
                }
            }
        }
        let ancestor = |j: usize| {
            let mut at = joints.get(j).and_then(|j| j.parent);
            let mut hops = 0;
            while let Some(p) = at {
                if let Some(Some(g)) = global.get(p) {
                    return *g;
                }
                hops += 1;
                if hops > joints.len() {
                    break;
                }
                at = joints.get(p).and_then(|j| j.parent);
            }
            Quat::IDENTITY
        };
        self.animated()
            .map(|j| {
                let g = global.get(j).copied().flatten().unwrap_or(Quat::IDENTITY);
                (ancestor(j).inverse() * g).normalize()
            })
            .collect()
    }
}

/// What drives an animated joint of a swimmer clip.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Motion {
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
fn forward_kinematics(joints: &[crate::d3::Joint], local: &[Affine3A]) -> Vec<Affine3A> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_knee_turns_just_above_the_floor_keeping_its_bones() {
        let (root, end) = (Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.2, 1.2));
        // A knee bent down, below y = 0.3.
        let knee = Vec3::new(0.0, 0.1, 0.4);
        let (upper, lower) = (root.distance(knee), end.distance(knee));
        let lifted = knee_above(root, knee, end, Vec3::Y, 0.3);
        assert!((lifted.y - 0.3).abs() < 1e-5, "{lifted}");
        assert!((root.distance(lifted) - upper).abs() < 1e-5);
        assert!((end.distance(lifted) - lower).abs() < 1e-5);
        // The smaller of the two turns: it stays on the side it was (x < 0 or x > 0 are
        // equally near here; either keeps the bones).
        assert_eq!(knee_above(root, knee, end, Vec3::Y, 0.05), knee);
        // Out of reach of any turn: the highest knee.
        let highest = knee_above(root, knee, end, Vec3::Y, 5.0);
        for k in 0..64 {
            let turn = Quat::from_axis_angle((end - root).normalize(), k as f32 * 0.1);
            let other = root + turn * (knee - root);
            assert!(other.y <= highest.y + 1e-5);
        }
    }

    #[test]
    fn rotation_arc_is_exact_for_tiny_angles() {
        let from = Vec3::NEG_Y;
        for angle in [0.0f32, 1e-6, 1e-4, 4e-4, 1e-2, 1.0, 3.0] {
            let to = Quat::from_rotation_x(angle) * from;
            let q = rotation_arc(from, to);
            assert!(q.is_normalized());
            assert!(
                (q * from).distance(to) < 1e-6,
                "{angle}: {}",
                (q * from).distance(to)
            );
        }
        let q = rotation_arc(Vec3::X, Vec3::NEG_X);
        assert!((q * Vec3::X).distance(Vec3::NEG_X) < 1e-6);
    }
}
