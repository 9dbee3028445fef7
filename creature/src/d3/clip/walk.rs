//! Walkers' clips from the gait controller: the looping `walk`, `run` and `hop` (cut and
//! closed into a loop), `turn` (a full turn in place, its rate retried to complete at the cut)
//! and `idle`; the controller run at [`CLIP_FPS`] on flat ground, and the clip from a run (the
//! root's motion, the legs by two-bone IK, the neck and tail bent toward a turn). The plain
//! `walk` is the live animator's (`live/bake.rs`).

use alloc::vec::Vec;

use glam::{Affine3A, Quat, Vec3};

use creature_gait::{GaitOptions, Leg, LimbKind, Plane, Pose, solve_two_bone_joints};

use super::floor::knee_above;
use super::gait_run::{GaitRun, best_cut, heading, ranked_cuts};
use super::kinematics::{Hinge, forward_kinematics};
use super::swing::even_swings;
use super::{CLIP_FPS, Clip, Track, loop_error};
use crate::Error;
use crate::d3::Creature;
use crate::d3::gait::MAX_SWING_TIME;
use crate::math::Roots;

/// Seconds the controller runs before a clip's first frame, so the gait is in its steady
/// rhythm.
pub(super) const WARM_UP: f32 = 1.0;

/// The most an arm's joint turns from one frame to the next, in radians (12 rad/s at
/// [`CLIP_FPS`]).
const MAX_ARM_TURN_PER_FRAME: f32 = 0.4;

/// [`MAX_ARM_TURN_PER_FRAME`] in radians per second: the live animator's arms turn no faster.
pub(crate) const MAX_ARM_TURN_RATE: f32 = MAX_ARM_TURN_PER_FRAME * CLIP_FPS;

/// Each rotation turned no further than `max` radians from the one before it, following the
/// track as closely as that allows.
fn limit_turn_rate(rotations: &mut [Quat], max: f32) {
    for f in 1..rotations.len() {
        let (before, now) = (rotations[f - 1], rotations[f]);
        let angle = before.angle_between(now);
        if angle > max {
            rotations[f] = before.slerp(now, max / angle).unit();
        }
    }
}

/// The most a leg's joint turns from one frame to the next while its foot is in the air, in
/// radians (18 rad/s at [`CLIP_FPS`]; the audit of delivered creatures allows 20).
const MAX_LEG_TURN_PER_FRAME: f32 = 0.6;

/// [`MAX_LEG_TURN_PER_FRAME`] in radians per second: the gait's swings are made long enough for
/// it (see `swing_time_for_joints`).
pub(crate) const MAX_LEG_TURN_RATE: f32 = MAX_LEG_TURN_PER_FRAME * CLIP_FPS;

/// Each rotation whose frame is `free` turned no further than `max` radians from its
/// neighbours, the others kept: forward, backward and forward again, each frame moved toward
/// the one before (after), so a limited stretch leaves and rejoins the kept frames within the
/// limit where the limit allows.
fn limit_free_turn_rate(rotations: &mut [Quat], free: &[bool], max: f32) {
    let n = rotations.len().min(free.len());
    // Most tracks turn slower everywhere: two unit quaternions are within `max` of each other
    // when their dot product's size is at least cos(max / 2).
    let near = crate::math::cos(0.5 * max);
    if (1..n).all(|k| !(free[k] || free[k - 1]) || rotations[k].dot(rotations[k - 1]).abs() >= near)
    {
        return;
    }
    let toward = |from: Quat, to: Quat| {
        let angle = from.angle_between(to);
        if angle > max {
            Some(from.slerp(to, max / angle).unit())
        } else {
            None
        }
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

/// Where a foot off the ground reaching `to` from `hip` goes on a leg `length` long: short of
/// the target, softly, once it is beyond [`SOFT_REACH`] of the length, so the leg never
/// straightens fully in the air (a straight knee turns fast for the least change of distance:
/// a foot lifting off behind a body that rises flicked the knee 39° between two keys). The
/// foot rises toward the hip (`up`, in the same frame) rather than moving across the ground,
/// so a foot just lifting off does not slide; only one too far out for that comes in toward
/// the hip.
pub(super) fn soft_reach(hip: Vec3, to: Vec3, length: f32, up: Vec3) -> Vec3 {
    let (start, span) = (SOFT_REACH * length, SOFT_SPAN * length);
    let v = to - hip;
    let d = v.norm();
    if !(d > start && span > 0.0) {
        return to;
    }
    let soft = start + span * (1.0 - crate::math::exp(-(d - start) / span));
    let below = v.dot(up);
    let across = v - up * below;
    let room = soft * soft - across.length_squared();
    if below < 0.0 && room >= 0.0 {
        hip + across - up * crate::math::sqrt(room)
    } else {
        hip + v * (soft / d)
    }
}

/// Where (× leg length) [`soft_reach`] begins to hold a foot in the air short of its target.
const SOFT_REACH: f32 = 0.9;

/// How far (× leg length) beyond [`SOFT_REACH`] a foot in the air reaches at most.
const SOFT_SPAN: f32 = 0.08;

/// How near the ground (× body length) a foot counts as on it, and how far a planted foot may
/// slide, as the audit of delivered creatures counts them.
const GROUND_CONTACT: f32 = 0.005;

/// The longest a `turn` takes to turn once (seconds), however long the walker.
const MAX_TURN_SECONDS: f32 = 12.0;

/// How many cuts of its window a turn tries to close its loop at.
const TURN_CUTS: usize = 8;

/// How many times a turn whose legs pass through each other is tried slower.
const TURN_SLOWDOWNS: usize = 2;

/// Each slower turn's rate, as a fraction of the one before.
const TURN_SLOWDOWN: f32 = 0.7;

/// What a closing is judged by, for a run (see [`Creature::closed_or_cut`]): its feet's
/// midline margin and overreach ([`margin_and_overreach`](GaitRun::margin_and_overreach)),
/// [`foot_spacing`](GaitRun::foot_spacing) and [`ground_slide`](GaitRun::ground_slide).
struct Figures {
    midline: f32,
    apart: f32,
    slide: f32,
    overreach: f32,
}

impl Figures {
    /// The figures of the first `frames` frames of `run`.
    fn of(run: &GaitRun, frames: usize, legs: &[Leg], ground: f32) -> Self {
        let (midline, overreach) = run.margin_and_overreach(frames, legs);
        Self {
            midline,
            apart: run.foot_spacing(frames, legs),
            slide: run.ground_slide(frames, ground),
            overreach,
        }
    }
}

/// A looping `walk` (see [`Creature::bake_walk_loop`]).
pub(crate) fn walk_loop(c: &Creature, at_rest: &mut AtRest) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    forward_loop(c, ("walk", false), c.speed, &setup.options, at_rest)
}

/// How many times a run whose legs turn too fast is baked again with longer swings.
const RUN_RETRIES: usize = 2;

/// A looping `run` (see [`Creature::bake_run_loop`]). A run whose walking legs turn a joint
/// faster than [`MAX_LEG_TURN_RATE`] between two frames (a small walker, whose strides take
/// five frames) is baked again (up to [`RUN_RETRIES`] times) with its shortest swing
/// (`GaitOptions::min_swing_time`) longer by as much, and a tenth: the slowest is kept (a
/// retry the controller rejects ends the retries, the best so far kept).
pub(crate) fn run_loop(c: &Creature, at_rest: &mut AtRest) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let speed = setup.run_speed().ok_or(Error::NoGait)?;
    let mut options = setup.options;
    if options.hop {
        // A hopper hops at the run's speed.
        return forward_loop(c, ("run", true), speed, &options, at_rest);
    }
    let legs: Vec<usize> = setup
        .legs
        .iter()
        .zip(&setup.hip_joints)
        .filter(|(leg, _)| leg.kind == LimbKind::Leg)
        .flat_map(|(_, &hip)| [hip, hip + 1, hip + 2])
        .collect();
    let limit = MAX_LEG_TURN_RATE * (1.0 + 1e-3);
    let mut best = forward_loop(c, ("run", false), speed, &options, at_rest)?;
    let mut best_rate = fastest_turn(&best, &legs);
    let mut rate = best_rate;
    for _ in 0..RUN_RETRIES {
        if rate <= limit {
            break;
        }
        options.min_swing_time =
            (options.min_swing_time * 1.1 * rate / MAX_LEG_TURN_RATE).min(MAX_SWING_TIME);
        let Ok(clip) = forward_loop(c, ("run", false), speed, &options, at_rest) else {
            break;
        };
        rate = fastest_turn(&clip, &legs);
        if rate < best_rate {
            (best, best_rate) = (clip, rate);
        }
    }
    Ok(best)
}

/// The fastest any of `joints`' tracks in `clip` turns between two frames (radians per
/// second).
fn fastest_turn(clip: &Clip, joints: &[usize]) -> f32 {
    clip.tracks
        .iter()
        .filter(|t| joints.contains(&t.joint))
        .flat_map(|t| t.rotations.windows(2).map(|w| w[0].angle_between(w[1])))
        .fold(0.0, f32::max)
        * clip.fps
}

/// A looping `hop` (see [`Creature::bake_hop_loop`]).
pub(crate) fn hop_loop(c: &Creature, at_rest: &mut AtRest) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let speed = setup.hop_speed().ok_or(Error::NoGait)?;
    forward_loop(c, ("hop", true), speed, &setup.options, at_rest)
}

/// A looping clip named `name` moving forward at `speed`: 4 s of the controller (with
/// `options`), cut at the frame from 1 s on closest to the first and closed where that keeps
/// the feet plausible. With `swing` (a hop), the tail swings against the legs (see
/// [`hop_tail_swing`]).
fn forward_loop(
    c: &Creature,
    (name, swing): (&'static str, bool),
    speed: f32,
    options: &GaitOptions,
    at_rest: &mut AtRest,
) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let run = c.simulate_gait_with(options, 4.0, speed, 0.0)?;
    let first = CLIP_FPS as usize;
    let end = best_cut(&run, first..run.frames(), |_| 0.0);
    let travel = Pose::from_yaw(Vec3::Z * (speed * end as f32 / CLIP_FPS), 0.0);
    let run = c.closed_or_cut(run, end, &travel, &setup.legs);
    let swing = swing.then_some(setup.legs.as_slice());
    c.clip_from_run(name, &run, (0.0, swing), at_rest, None)
}

/// Radians a hopper's tail swings up per leg length its feet are ahead of their hips, on
/// average.
const HOP_TAIL_GAIN: f32 = 3.0;

/// The most a hopper's tail swings up, over the whole tail (radians).
const HOP_TAIL_LIMIT: f32 = 0.8;

/// How far a hopper's tail swings up against its legs (radians over the whole tail, about the
/// body's left axis) with its walking `legs`' feet at `feet` (body space): as the feet swing
/// forward in a hop's flight, the tail swings up (their turns about the hips in opposite
/// senses, as a kangaroo's tail balances its legs), and it comes down to rest as the feet pass
/// back under the body in stance; never below rest (the tail stays off the ground).
/// [`HOP_TAIL_GAIN`] × the feet's mean lead over their hips along the body, × their legs'
/// lengths, at most [`HOP_TAIL_LIMIT`].
pub(super) fn hop_tail_swing(legs: &[Leg], feet: impl Iterator<Item = Vec3>) -> f32 {
    let (mut lead, mut count) = (0.0f32, 0u32);
    for (leg, foot) in legs.iter().zip(feet) {
        if leg.kind == LimbKind::Leg {
            lead += (foot.z - leg.hip.z) / (leg.upper + leg.lower).max(1e-6);
            count += 1;
        }
    }
    if count == 0 {
        return 0.0;
    }
    (HOP_TAIL_GAIN * lead / count as f32).clamp(0.0, HOP_TAIL_LIMIT)
}

/// A full `turn` in place (see [`Creature::bake_turn`]): at the creature's turn rate, or, if
/// its legs pass through each other there (as capsules of their skin's radius, as the audit
/// of delivered creatures measures them), at up to [`TURN_SLOWDOWNS`] slower rates, each
/// [`TURN_SLOWDOWN`] of the one before, until they do not: the turn with the legs least
/// deep in each other.
pub(crate) fn turn(c: &Creature, at_rest: &mut AtRest) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let mut rate = c.turn_rate(&setup.legs);
    // Legs nearer each other than this (× body length) count as touching: what is measured
    // here and on the exported file differs by float rounding.
    let touching = -1e-4 * c.length;
    let mut best = turn_at(c, rate, at_rest)?;
    for _ in 0..TURN_SLOWDOWNS {
        if best.1 <= touching {
            break;
        }
        rate *= TURN_SLOWDOWN;
        let slower = turn_at(c, rate, at_rest)?;
        if slower.1 < best.1 {
            best = slower;
        }
    }
    Ok(best.0)
}

/// A full `turn` in place at `rate` (rad/s, about), with how deep its legs overlap (as
/// [`Creature::clip_from_run`] measures it; −0.1 × the body length where no two come nearer).
fn turn_at(c: &Creature, rate: f32, at_rest: &mut AtRest) -> Result<(Clip, f32), Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let full = core::f32::consts::TAU;
    let mut rate = rate;
    // The cut: half a second either side of the full turn at that rate.
    let seconds = full / rate;
    let window = ((seconds - 0.5) * CLIP_FPS) as usize..((seconds + 0.5) * CLIP_FPS) as usize + 1;
    // The turn's shortfall (or excess) at the cut is spread over the clip, which moves the
    // hips over the planted feet: it weighs as far as it moves the farthest hip.
    let radius = setup
        .legs
        .iter()
        .map(|l| glam::Vec2::new(l.hip.x, l.hip.z).norm())
        .fold(0.0, f32::max);
    // Cut at the frame near 4 s with the first frame's feet planted; then try again at
    // the rate that completes the turn exactly at that frame (the steps shift with the
    // rate), keeping the best of three.
    // A try at `rate`: its score, run, cut and the rate that completes the turn at the cut.
    let attempt = |rate: f32| -> Result<(f32, GaitRun, usize, f32), Error> {
        // Up to the window's last frame: no later frame is cut at or looked at.
        let run = c.simulate_gait(seconds + 0.5 + 1.0 / CLIP_FPS, 0.0, rate)?;
        let shortfall = |f: usize| radius * (f as f32 / CLIP_FPS * rate - full).abs();
        let end = best_cut(&run, window.clone(), shortfall);
        let score = run.mismatch(end) + shortfall(end);
        let next = full / (end.max(1) as f32 / CLIP_FPS);
        Ok((score, run, end, next))
    };
    let (mut score, run, end, mut next) = attempt(rate)?;
    let mut best = (score, rate, run, end);
    for _ in 1..3 {
        if score <= 0.0 || next == rate {
            break;
        }
        rate = next;
        let (tried, run, end, after) = attempt(rate)?;
        if tried < best.0 {
            best = (tried, rate, run, end);
        }
        (score, next) = (tried, after);
    }
    let (_, rate, run, end) = best;
    // The best cut first; if closing its loop would bring feet across the body or out of
    // reach, the next best cuts of the window (whose shortfall the closing spreads too).
    let shortfall = |f: usize| radius * (f as f32 / CLIP_FPS * rate - full).abs();
    let mut ends = alloc::vec![end];
    ends.extend(
        ranked_cuts(&run, window.clone(), shortfall, TURN_CUTS)
            .into_iter()
            .filter(|&f| f != end),
    );
    // Cut plainly (no cut closes well), at the frame of the run that completes the turn most
    // nearly.
    let plain = window
        .filter(|&f| f < run.frames())
        .min_by(|&a, &b| shortfall(a).total_cmp(&shortfall(b)))
        .unwrap_or(end);
    let run = c.closed_or_cut_among(run, &ends, plain, &Pose::IDENTITY, &setup.legs);
    // Only legs nearer than a tenth of the body length matter.
    let mut overlap = -0.1 * c.length;
    let clip = c.clip_from_run("turn", &run, (rate, None), at_rest, Some(&mut overlap))?;
    Ok((clip, overlap))
}

/// A clip of `seconds` moving forward at `speed` and turning at `yaw_rate` from a run of the
/// gait controller (see [`Creature::bake_idle`]).
pub(crate) fn gait(
    c: &Creature,
    name: &'static str,
    seconds: f32,
    speed: f32,
    yaw_rate: f32,
    at_rest: &mut AtRest,
) -> Result<Clip, Error> {
    let run = c.simulate_gait(seconds, speed, yaw_rate)?;
    c.clip_from_run(name, &run, (yaw_rate, None), at_rest, None)
}

/// `seconds` if a walker's clip may last that long: at least one frame interval, at most 60 s.
///
/// # Errors
/// [`Error::OutOfRange`] otherwise (or for NaN).
pub(super) fn clip_seconds(seconds: f32) -> Result<f32, Error> {
    let (min, max) = (1.0 / CLIP_FPS, 60.0);
    if (min..=max).contains(&seconds) {
        Ok(seconds)
    } else {
        Err(Error::OutOfRange {
            what: "seconds",
            value: seconds,
            min,
            max,
        })
    }
}

/// What baking a walker's clips measures of the creature at rest, the same for every clip:
/// measured by the first clip that needs it and kept for the others baked with it
/// ([`Creature::bake_clips`]).
#[derive(Debug, Default)]
pub(crate) struct AtRest {
    /// Per skeleton joint, how far the vertices it moves reach from it
    /// ([`Creature::joint_reach`]: for a knee or a foot, the radius of its ring).
    reach: Option<Vec<f32>>,
    /// The body's vertices (those skinned to spine joints only) with the spine unbent, as a
    /// clip that does not turn holds it ([`Creature::body_shape`]).
    unbent_body: Option<Vec<Vec3>>,
    /// Per leg of the gait set-up, the radii of its upper and lower segments' skin
    /// ([`Creature::leg_radii`]).
    leg_radii: Option<Vec<[f32; 2]>>,
}

impl Creature {
    /// `run` cut after frame `end` with its loop closed by `motion`, unless closing it leaves a
    /// planted foot further out of its leg's reach than the plain cut does (the spread
    /// correction can stretch a leg that was nearly straight), brings a foot much nearer the
    /// body's midline (or across it) or two feet on a side much nearer each other along the
    /// body (or past each other), or would slide a foot that
    /// never lifts in the clip (a walker so slow that it takes no step in it): then the plain
    /// cut, whose [`Clip::loop_error`] says how far it is from looping (`legs`: the run's).
    fn closed_or_cut(&self, run: GaitRun, end: usize, motion: &Pose, legs: &[Leg]) -> GaitRun {
        self.closed_or_cut_among(run, &[end], end, motion, legs)
    }

    /// [`closed_or_cut`](Self::closed_or_cut) at the first of `ends` whose loop closes well;
    /// the plain cut after frame `plain` if none does.
    fn closed_or_cut_among(
        &self,
        run: GaitRun,
        ends: &[usize],
        plain: usize,
        motion: &Pose,
        legs: &[Leg],
    ) -> GaitRun {
        for &end in ends {
            if let Some(closed) = self.close_well(&run, end, motion, legs) {
                return closed;
            }
        }
        let mut cut = run;
        cut.truncate(plain + 1);
        cut
    }

    /// `run` closed at `end` by `motion`, if that keeps planted feet still, within reach and on
    /// their side of the body (see [`closed_or_cut`](Self::closed_or_cut)).
    fn close_well(
        &self,
        run: &GaitRun,
        end: usize,
        motion: &Pose,
        legs: &[Leg],
    ) -> Option<GaitRun> {
        // The plain cut's figures: those of the run's frames up to `end`.
        let ground = GROUND_CONTACT * self.length;
        let plain = Figures::of(run, end + 1, legs, ground);
        [false, true]
            .into_iter()
            .find_map(|hold_seam| self.closed_well(run, &plain, end, motion, legs, hold_seam))
    }

    /// `run` closed at `end` by `motion` (holding feet down at the seam or not), if that is no
    /// worse than the plain cut, whose figures are `cut` (see [`close_well`](Self::close_well)).
    fn closed_well(
        &self,
        run: &GaitRun,
        cut: &Figures,
        end: usize,
        motion: &Pose,
        legs: &[Leg],
        hold_seam: bool,
    ) -> Option<GaitRun> {
        let mut closed = run.clone();
        let ground = GROUND_CONTACT * self.length;
        let planted_shift = closed.close_loop(end, motion, hold_seam, ground);
        let tolerance = 1e-4 * self.length;
        let now = Figures::of(&closed, closed.frames(), legs, ground);
        // Closing must not bring a foot nearer the midline than the plain cut does, past it, or
        // nearer than half its margin.
        let side_kept = now.midline >= (0.5 * cut.midline).min(cut.midline - tolerance);
        // Nor bring two feet on a side nearer each other along the body than the plain cut
        // does, past each other, or nearer than half their spacing.
        let apart_kept = now.apart >= (0.5 * cut.apart).min(cut.apart - tolerance);
        // Nor slide a foot along the ground (a correction made while the foot is only lifting
        // off) more than the plain cut does or half what the audit allows.
        let slide_kept =
            now.slide <= (cut.slide + tolerance).max(0.5 * GROUND_CONTACT * self.length);
        (planted_shift <= tolerance
            && side_kept
            && apart_kept
            && slide_kept
            && now.overreach <= cut.overreach + tolerance)
            .then_some(closed)
    }

    /// Runs the gait controller at [`CLIP_FPS`] over flat ground for `seconds` after the
    /// warm-up, moving forward at `speed` and turning at `yaw_rate`; records the reacted body
    /// pose and the feet per frame, relative to the clip's starting place and heading.
    fn simulate_gait(&self, seconds: f32, speed: f32, yaw_rate: f32) -> Result<GaitRun, Error> {
        let setup = self.gait.as_ref().ok_or(Error::NoGait)?;
        self.simulate_gait_with(&setup.options, seconds, speed, yaw_rate)
    }

    /// [`simulate_gait`](Self::simulate_gait) with the controller's `options` in place of the
    /// set-up's.
    fn simulate_gait_with(
        &self,
        options: &GaitOptions,
        seconds: f32,
        speed: f32,
        yaw_rate: f32,
    ) -> Result<GaitRun, Error> {
        clip_seconds(seconds)?;
        let setup = self.gait.as_ref().ok_or(Error::NoGait)?;
        let mut controller = creature_gait::Controller::new(&setup.legs, options)?;
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
            contacts: Vec::with_capacity(frames * legs),
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
            // Only the feet and the reacted body are recorded (the legs are solved from them).
            controller.update_feet_and_body(
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
                rotation: (unstart * body.rotation).unit(),
            });
            let states = controller.leg_states();
            // One state per leg (the controller's order): the run's frames hold `legs` each.
            debug_assert_eq!(states.len(), legs, "one leg state per leg");
            if states.len() != legs {
                return Err(Error::Degenerate {
                    what: "gait controller's leg states",
                });
            }
            run.contacts.extend(states.iter().map(|s| s.planted));
            run.feet.extend(states.iter().map(|s| relative(s.foot)));
        }
        Ok(run)
    }

    /// A clip from a recorded gait run: the root's motion, each leg's hip translation, hip
    /// and knee rotations by two-bone IK from the hip to the recorded foot (the leg's pole
    /// bending the knee), and a foot rotation that keeps the sole level (turned with the
    /// body's heading only); the neck and tail bent toward a turn at `yaw_rate`. With
    /// `overlap`, also how deep any two legs are in each other in any frame of the clip (as
    /// capsules of their skin's radii, [`leg_radii`](Self::leg_radii); ≤ 0 where they are
    /// apart), if deeper than it was. With `tail_swing`'s legs (a hopper's), the tail swings
    /// against them ([`hop_tail_swing`]) frame by frame.
    fn clip_from_run(
        &self,
        name: &'static str,
        run: &GaitRun,
        (yaw_rate, tail_swing): (f32, Option<&[Leg]>),
        at_rest: &mut AtRest,
        overlap: Option<&mut f32>,
    ) -> Result<Clip, Error> {
        let setup = self.gait.as_ref().ok_or(Error::NoGait)?;
        let frames = run.frames();
        let joints = &self.skeleton.joints;
        let rest_root = self.rest_root();
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
            contacts: (0..run.frames())
                .map(|f| run.frame_contacts(f).to_vec())
                .collect(),
            loop_error: 0.0,
        };
        // Per leg: the hip's parent (a spine joint, maybe bent) in body space, the rest
        // directions of the leg's two segments, and its three tracks.
        let reach: &[f32] = at_rest.reach.get_or_insert_with(|| self.joint_reach());
        let ring_radius = |joint: usize| reach.get(joint).copied().unwrap_or(0.0);
        let mut legs: Vec<LegTracks<'_>> = setup
            .legs
            .iter()
            .zip(&setup.hip_joints)
            .map(|(leg, &hip)| {
                let parent = joints
                    .get(hip)
                    .and_then(|j| j.parent)
                    .and_then(|p| body_global.get(p).copied())
                    .unwrap_or(Affine3A::IDENTITY);
                let rest_upper = (rest(hip + 1) - rest(hip)).unit_or(Vec3::NEG_Y);
                let rest_lower = (rest(hip + 2) - rest(hip + 1)).unit_or(Vec3::NEG_Y);
                LegTracks {
                    leg,
                    hip,
                    parent,
                    unparent: parent.inverse(),
                    parent_rotation: crate::math::quat_from_mat3a(&parent.matrix3).unit(),
                    rest_upper,
                    rest_lower,
                    hinge: Hinge::new((rest_upper, rest_lower), leg.pole),
                    knee_radius: ring_radius(hip + 1),
                    translations: Vec::with_capacity(frames),
                    rotations: core::array::from_fn(|_| Vec::with_capacity(frames)),
                }
            })
            .collect();
        // Nothing under the floor: a frame whose body would dip below it (its lean, bob or
        // breathing, on a body that reaches down to the ground) leans less and, if need be,
        // rises, before the legs are solved, so the feet stay planted.
        // The body as this clip bends it (a clip that does not turn: unbent, as measured once).
        let shape = if spine_rotations.is_empty() {
            match &at_rest.unbent_body {
                Some(shape) => shape.clone(),
                None => {
                    let shape = self.body_shape(&body_global)?;
                    at_rest.unbent_body = Some(shape.clone());
                    shape
                }
            }
        } else {
            self.body_shape(&body_global)?
        };
        let bodies = self.above_the_floor(shape, run, &setup.legs);
        // Each swing's frames spaced by its joints' turn, so they turn at an even rate.
        let feet = even_swings(run, &bodies, &setup.legs, GROUND_CONTACT * self.length);
        // A hopper's tail swing, frame by frame.
        let swings: Vec<f32> = match tail_swing {
            Some(legs) => bodies
                .iter()
                .enumerate()
                .map(|(frame, body)| {
                    let feet = &feet[frame * run.legs..(frame + 1) * run.legs];
                    hop_tail_swing(legs, feet.iter().map(|&f| body.inverse_transform_point(f)))
                })
                .collect(),
            None => Vec::new(),
        };
        for (frame, body) in bodies.iter().enumerate() {
            clip.root_translation
                .push(body.translation + body.rotation * rest_root);
            clip.root_rotation.push(body.rotation);
            let heading = heading(body.rotation);
            let up = body.rotation.inverse() * Vec3::Y;
            for (i, tracks) in legs.iter_mut().enumerate() {
                let (leg, unparent) = (tracks.leg, tracks.unparent);
                let (rest_upper, rest_lower) = (tracks.rest_upper, tracks.rest_lower);
                let mut foot = body.inverse_transform_point(feet[frame * run.legs + i]);
                if !run.planted(frame, i) {
                    foot = soft_reach(leg.hip, foot, leg.upper + leg.lower, up);
                }
                let [root, middle, end] =
                    solve_two_bone_joints(leg.hip, foot, leg.upper, leg.lower, leg.pole);
                let floor = tracks.knee_radius - body.translation.y;
                let middle = knee_above(root, middle, end, up, floor);
                let upper = (middle - root).unit_or(rest_upper);
                let lower = (end - middle).unit_or(rest_lower);
                let (hip_rotation, knee_rotation) = tracks.hinge.rotations((upper, lower));
                let parent_rotation = tracks.parent_rotation;
                tracks.translations.push(unparent.transform_point3(root));
                let [hip, knee, foot] = &mut tracks.rotations;
                hip.push((parent_rotation.inverse() * hip_rotation).unit());
                knee.push(knee_rotation.unit());
                // The foot stays level (its sole flat on the ground), turned with the body's
                // heading only: its world rotation is the heading's yaw.
                foot.push(
                    ((body.rotation * hip_rotation * knee_rotation).inverse() * heading).unit(),
                );
            }
        }
        // Each leg's hip, knee and foot tracks, then the neck and tail bent toward a turn.
        let ground = GROUND_CONTACT * self.length;
        // With `overlap`: each walking leg's hip, knee and foot per frame, in body space.
        let mut segments: Vec<(usize, Vec<[Vec3; 3]>)> = Vec::new();
        for (i, tracks) in legs.into_iter().enumerate() {
            let [mut hip, mut knee, mut foot] = tracks.rotations.clone();
            if tracks.leg.kind == LimbKind::Leg {
                // A quick swing's joints turn no faster than a leg's may: limited only while
                // the foot is off the ground, so it lifts, lands and stands exactly where the
                // gait puts it.
                let free: Vec<bool> = (0..frames)
                    .map(|f| !run.planted(f, i) && run.foot(f, i).y > ground)
                    .collect();
                for rotations in [&mut hip, &mut knee] {
                    limit_free_turn_rate(rotations, &free, MAX_LEG_TURN_PER_FRAME);
                }
                // The foot of a limited frame turned level again, then limited too.
                let parent = tracks.parent_rotation;
                let [hip_0, knee_0, foot_0] = &tracks.rotations;
                let limited = |f: usize, hip: &[Quat], knee: &[Quat]| {
                    free[f] && (hip[f] != hip_0[f] || knee[f] != knee_0[f])
                };
                for f in (0..frames).filter(|&f| limited(f, &hip, &knee)) {
                    let body = &bodies[f];
                    foot[f] = ((body.rotation * parent * hip[f] * knee[f]).inverse()
                        * heading(body.rotation))
                    .unit();
                }
                limit_free_turn_rate(&mut foot, &free, MAX_LEG_TURN_PER_FRAME);
                // Unless that lowers the foot (its sole, tilted or not) to within `ground` of the
                // ground or brings it across the body's midline: that frame goes back toward the gait's pose,
                // only as far as it must (the gait's pose itself is safe), so it jumps as
                // little as it can from its limited neighbours.
                let mut foot_radius = None;
                for f in 0..frames {
                    if !(limited(f, &hip, &knee) || foot[f] != foot_0[f]) {
                        continue;
                    }
                    let body = &bodies[f];
                    let unlimited = tracks.foot_at(f, hip_0, knee_0);
                    let side = tracks.leg.rest.x;
                    let foot_radius =
                        *foot_radius.get_or_insert_with(|| ring_radius(tracks.hip + 2));
                    let safe = |h: Quat, k: Quat, o: Quat| {
                        let at = tracks.foot_at_with(f, h, k);
                        let kept_side = side == 0.0
                            || at.x * side.signum() >= (unlimited.x * side.signum()).min(0.0);
                        let up = (body.rotation * parent * h * k * o) * Vec3::Y;
                        let tilt = up.cross(Vec3::Y).norm();
                        let sole = body.transform_point(at).y - foot_radius * tilt;
                        // Clear of the ground (a foot near it counts as on it, and would be
                        // seen to slide to where it lands).
                        sole > ground && kept_side
                    };
                    let limited_pose = (hip[f], knee[f], foot[f]);
                    let toward = |t: f32| {
                        (
                            limited_pose.0.slerp(hip_0[f], t).unit(),
                            limited_pose.1.slerp(knee_0[f], t).unit(),
                            limited_pose.2.slerp(foot_0[f], t).unit(),
                        )
                    };
                    if safe(limited_pose.0, limited_pose.1, limited_pose.2) {
                        continue;
                    }
                    // Bisect the blend: `hi` is safe (the gait's pose at 1), `lo` is not.
                    let (mut lo, mut hi) = (0.0f32, 1.0f32);
                    for _ in 0..10 {
                        let t = 0.5 * (lo + hi);
                        let (h, k, o) = toward(t);
                        if safe(h, k, o) {
                            hi = t;
                        } else {
                            lo = t;
                        }
                    }
                    if hi < 1.0 {
                        (hip[f], knee[f], foot[f]) = toward(hi);
                    } else {
                        hip[f] = hip_0[f];
                        knee[f] = knee_0[f];
                        foot[f] = foot_0[f];
                    }
                }
            }
            if tracks.leg.kind == LimbKind::Arm {
                // Arms hang free: damped, no joint turns faster than the limit (the two-bone
                // solution can flip an elbow between two frames as the hand passes its pole).
                for rotations in [&mut hip, &mut knee, &mut foot] {
                    limit_turn_rate(rotations, MAX_ARM_TURN_PER_FRAME);
                }
            }
            if overlap.is_some() && tracks.leg.kind == LimbKind::Leg {
                let (upper, lower) = (
                    rest(tracks.hip + 1) - rest(tracks.hip),
                    rest(tracks.hip + 2) - rest(tracks.hip + 1),
                );
                let points = (0..frames)
                    .map(|f| {
                        let root = tracks.parent.transform_point3(tracks.translations[f]);
                        let turn = tracks.parent_rotation * hip[f];
                        let knee_at = root + turn * upper;
                        [root, knee_at, knee_at + turn * knee[f] * lower]
                    })
                    .collect();
                segments.push((i, points));
            }
            clip.tracks.push(Track {
                joint: tracks.hip,
                translations: Some(tracks.translations),
                rotations: hip,
            });
            for (joint, rotations) in [(tracks.hip + 1, knee), (tracks.hip + 2, foot)] {
                clip.tracks.push(Track {
                    joint,
                    translations: None,
                    rotations,
                });
            }
        }
        // The tail's share of its swing, each joint no further than its skin allows.
        let tail = if swings.is_empty() {
            Vec::new()
        } else {
            self.swinging_tail()
        };
        let share = 1.0 / tail.len().max(1) as f32;
        for &(joint, q) in &spine_rotations {
            if tail.iter().any(|t| t.0 == joint) {
                continue;
            }
            clip.tracks.push(Track {
                joint,
                translations: None,
                rotations: alloc::vec![q; frames],
            });
        }
        for &(joint, limit) in &tail {
            let turn = spine_rotations
                .iter()
                .find(|s| s.0 == joint)
                .map_or(Quat::IDENTITY, |s| s.1);
            clip.tracks.push(Track {
                joint,
                translations: None,
                rotations: swings
                    .iter()
                    .map(|&swing| (turn * Quat::from_rotation_x((swing * share).min(limit))).unit())
                    .collect(),
            });
        }
        if let Some(overlap) = overlap {
            let radii: &[[f32; 2]] = at_rest
                .leg_radii
                .get_or_insert_with(|| self.leg_radii(&setup.hip_joints));
            *overlap = deepest_overlap(&segments, radii, frames, *overlap);
        }
        clip.loop_error = loop_error(&clip);
        Ok(clip)
    }

    /// For each of the legs whose hip joints are `hips` (the knee and the foot the next two
    /// joints), the mean distance from its upper and its lower segment of the rest vertices
    /// weighted most to that segment's joints (the first of equal weights): the radius of the
    /// capsules the audit of delivered creatures measures legs as.
    fn leg_radii(&self, hips: &[usize]) -> Vec<[f32; 2]> {
        let joints = &self.skeleton.joints;
        let rest = |j: usize| joints.get(j).map_or(Vec3::ZERO, |j| j.position);
        // Per joint: the leg it belongs to, and whether to its upper and its lower segment
        // (a knee to both).
        let mut of_joint: Vec<Option<(usize, [bool; 2])>> = alloc::vec![None; joints.len()];
        for (leg, &hip) in hips.iter().enumerate() {
            for (joint, segments) in [
                (hip, [true, false]),
                (hip + 1, [true, true]),
                (hip + 2, [false, true]),
            ] {
                if let Some(slot) = of_joint.get_mut(joint) {
                    *slot = Some((leg, segments));
                }
            }
        }
        let mut sums = alloc::vec![[(0.0f32, 0u32); 2]; hips.len()];
        self.for_each_vertex(|p, js, ws| {
            let k = (0..4).fold(0, |k, i| if ws[i] > ws[k] { i } else { k });
            let Some(&Some((leg, segments))) = of_joint.get(usize::from(js[k])) else {
                return;
            };
            for segment in (0..2).filter(|&s| segments[s]) {
                let a = rest(hips[leg] + segment);
                let b = rest(hips[leg] + segment + 1);
                let (sum, n) = &mut sums[leg][segment];
                *sum += segment_distance(p, p, a, b);
                *n += 1;
            }
        });
        sums.iter()
            .map(|s| s.map(|(sum, n)| if n == 0 { 0.0 } else { sum / n as f32 }))
            .collect()
    }

    /// Local rotations of the neck and tail joints bending toward a turn at `yaw_rate`.
    fn turn_bend(&self, yaw_rate: f32) -> Vec<(usize, Quat)> {
        if yaw_rate == 0.0 {
            return Vec::new();
        }
        let total = turn_bend_total(yaw_rate);
        self.turn_bend_shares()
            .into_iter()
            .map(|(j, divisor, limit)| {
                (
                    j,
                    Quat::from_rotation_y((total / divisor).clamp(-limit, limit)),
                )
            })
            .collect()
    }

    /// The neck's and tail's joints that bend toward a turn: each with the divisor of the
    /// turn's total bend ([`turn_bend_total`]) that is its share (the neck's joint count, the
    /// tail's negated: it bends the other way) and the most its skin lets it bend.
    pub(super) fn turn_bend_shares(&self) -> Vec<(usize, f32, f32)> {
        let spine = &self.rig.spine;
        let root = self.rig.root();
        let Some(c) = spine.iter().position(|&j| Some(j) == root) else {
            return Vec::new();
        };
        let bones = spine.len().saturating_sub(1);
        let neck: Vec<usize> = spine.iter().take(bones).skip(c + 1).copied().collect();
        let tail = self.tail_chain();
        // Each joint its share, no more than its skin allows.
        let limits = self.bend_limits();
        let mut out = Vec::with_capacity(neck.len() + tail.len());
        out.extend(neck.iter().map(|&j| (j, neck.len() as f32, limits[j])));
        out.extend(tail.iter().map(|&j| (j, -(tail.len() as f32), limits[j])));
        out
    }

    /// The fastest a walker turns in place (rad/s): a quarter turn a second, or slower, no
    /// foot's rest position sweeping round faster than the creature walks (a long body's end
    /// feet would be carried past the midline between two frames), but a full turn in at most
    /// `MAX_TURN_SECONDS`.
    pub(super) fn turn_rate(&self, legs: &[Leg]) -> f32 {
        let farthest = legs
            .iter()
            .filter(|l| l.kind == LimbKind::Leg)
            .map(|l| glam::Vec2::new(l.rest.x, l.rest.z).norm())
            .fold(0.0, f32::max);
        let mut rate = core::f32::consts::FRAC_PI_2;
        if farthest * rate > self.speed {
            rate = (self.speed / farthest).max(core::f32::consts::TAU / MAX_TURN_SECONDS);
        }
        rate
    }
}

/// The total bend (radians) of the neck and of the tail toward a turn at `yaw_rate` (rad/s):
/// 0.35 at 1.5 rad/s and faster.
pub(super) fn turn_bend_total(yaw_rate: f32) -> f32 {
    0.35 * yaw_rate.signum() * (yaw_rate.abs() / 1.5).min(1.0)
}

/// How deep any two of `legs` (each its index into `radii` and its hip, knee and foot per
/// frame) are in each other as capsules of their segments' radii, in the first `frames`
/// frames, or `floor` if no two are deeper than that (≤ 0 where they are apart, by minus the
/// least gap).
fn deepest_overlap(
    legs: &[(usize, Vec<[Vec3; 3]>)],
    radii: &[[f32; 2]],
    frames: usize,
    floor: f32,
) -> f32 {
    // Each segment's half length (the legs are rigid).
    let halves: Vec<[f32; 2]> = legs
        .iter()
        .map(|(_, p)| {
            p.first().map_or([0.0; 2], |p| {
                [0.5 * p[0].distance(p[1]), 0.5 * p[1].distance(p[2])]
            })
        })
        .collect();
    let mut depth = floor;
    for (n, (a, pa)) in legs.iter().enumerate() {
        for (m, (b, pb)) in legs.iter().enumerate().skip(n + 1) {
            let (ra, rb) = (radii[*a], radii[*b]);
            for (pa, pb) in pa.iter().zip(pb).take(frames) {
                for i in 0..2 {
                    for k in 0..2 {
                        // Two segments are no nearer than their midpoints' distance less their
                        // half lengths: most pairs cannot be deeper than the deepest yet.
                        let (a0, a1, b0, b1) = (pa[i], pa[i + 1], pb[k], pb[k + 1]);
                        let reach = ra[i] + rb[k];
                        let far = halves[n][i] + halves[m][k] + reach - depth;
                        if (0.5 * (a0 + a1 - b0 - b1)).length_squared() >= far * far {
                            continue;
                        }
                        depth = depth.max(reach - segment_distance(a0, a1, b0, b1));
                    }
                }
            }
        }
    }
    depth
}

/// The smallest distance between segments `p0 p1` and `q0 q1` (Ericson, *Real-Time Collision
/// Detection*, 5.1.9).
fn segment_distance(p0: Vec3, p1: Vec3, q0: Vec3, q1: Vec3) -> f32 {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.dot(d1), d2.dot(d2), d2.dot(r));
    let eps = 1e-12;
    let (s, t) = if a <= eps && e <= eps {
        (0.0, 0.0)
    } else if a <= eps {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(r);
        if e <= eps {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let s = if denom > eps {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let t = (b * s + f) / e;
            if t < 0.0 {
                (((-c) / a).clamp(0.0, 1.0), 0.0)
            } else if t > 1.0 {
                (((b - c) / a).clamp(0.0, 1.0), 1.0)
            } else {
                (s, t)
            }
        }
    };
    (p0 + d1 * s).distance(q0 + d2 * t)
}

/// One leg of a walking clip being baked: what solving it needs, and its tracks' values.
struct LegTracks<'a> {
    leg: &'a Leg,
    /// The hip joint; the knee and the foot are the next two.
    hip: usize,
    /// The hip's parent (a spine joint, maybe bent) in body space, and its rotation.
    parent: Affine3A,
    /// `parent`'s inverse: body space into the hip's parent's frame.
    unparent: Affine3A,
    parent_rotation: Quat,
    /// The rest directions of the leg's upper and lower segments.
    rest_upper: Vec3,
    rest_lower: Vec3,
    /// The knee's hinge, from those and the leg's pole.
    hinge: Hinge,
    /// How far the knee's ring of vertices reaches (it stays this far above the floor).
    knee_radius: f32,
    /// The hip's translation per frame.
    translations: Vec<Vec3>,
    /// The hip's, the knee's and the foot's rotations per frame.
    rotations: [Vec<Quat>; 3],
}

impl LegTracks<'_> {
    /// The foot (the lower segment's end) in body space at frame `frame` with the hip and knee
    /// rotations `hip` and `knee` (tracks as [`rotations`](Self::rotations) holds them).
    fn foot_at(&self, frame: usize, hip: &[Quat], knee: &[Quat]) -> Vec3 {
        self.foot_at_with(frame, hip[frame], knee[frame])
    }

    /// [`foot_at`](Self::foot_at) with frame `frame`'s hip and knee rotations given.
    fn foot_at_with(&self, frame: usize, hip: Quat, knee: Quat) -> Vec3 {
        let root = self.parent.transform_point3(self.translations[frame]);
        let turn = self.parent_rotation * hip;
        root + turn * (self.rest_upper * self.leg.upper)
            + turn * (knee * (self.rest_lower * self.leg.lower))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_foot_in_the_air_stops_softly_short_of_a_straight_leg() {
        let hip = Vec3::new(0.1, 1.0, 0.0);
        let toward = Vec3::new(0.0, -0.6, 0.8);
        let at = |d: f32| soft_reach(hip, hip + toward * d, 2.0, Vec3::Y);
        // Within 90% of the length: the target itself.
        assert_eq!(at(1.7), hip + toward * 1.7);
        // Beyond: short of it, never further than 98%, nearer the farther, and straight above
        // the target (it does not slide across the ground).
        let mut before = 1.8f32;
        for k in 1..200 {
            let d = 1.8 + 0.01 * k as f32;
            let (target, reached) = (hip + toward * d, at(d));
            let r = reached.distance(hip);
            assert!(r <= d && r < 0.98 * 2.0, "{d}: {r}");
            assert!(r >= before - 1e-5, "{d}: {r} < {before}");
            if 0.8 * d < 1.8 {
                assert!(reached.y >= target.y);
                assert!((reached.x - target.x).abs() < 1e-6);
                assert!((reached.z - target.z).abs() < 1e-5);
            }
            before = r;
        }
        // Continuous where it begins.
        assert!((at(1.8 + 1e-4).distance(hip) - 1.8).abs() < 2e-4);
        // Too far out to rise to its reach: in toward the hip.
        let out = soft_reach(hip, hip + Vec3::new(0.0, -0.1, 2.5), 2.0, Vec3::Y);
        assert!(out.distance(hip) < 0.98 * 2.0);
        assert!(
            (out - hip)
                .normalize()
                .dot(Vec3::new(0.0, -0.1, 2.5).normalize())
                > 0.9999
        );
    }

    #[test]
    fn segments_distances_and_legs_overlap() {
        let v = Vec3::new;
        // Crossing at right angles 0.5 apart; parallel, side by side; end to end; a point.
        let crossing = segment_distance(
            v(-1.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.0, 0.5, -1.0),
            v(0.0, 0.5, 1.0),
        );
        assert!((crossing - 0.5).abs() < 1e-6);
        let parallel = segment_distance(
            v(0.0, 0.0, 0.0),
            v(0.0, 2.0, 0.0),
            v(0.3, 1.0, 0.0),
            v(0.3, 3.0, 0.0),
        );
        assert!((parallel - 0.3).abs() < 1e-6);
        let apart = segment_distance(
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(3.0, 0.0, 0.0),
            v(4.0, 0.0, 0.0),
        );
        assert!((apart - 2.0).abs() < 1e-6);
        let point = segment_distance(
            v(0.0, 1.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(-1.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
        );
        assert!((point - 1.0).abs() < 1e-6);
        // Two upright legs 0.5 apart, radii 0.2 and 0.1: apart by 0.2 until the second frame,
        // whose second leg leans its foot 0.4 toward the first.
        let leg = |x: f32, lean: f32| [v(x, 2.0, 0.0), v(x, 1.0, 0.0), v(x + lean, 0.0, 0.0)];
        let legs = [
            (0, alloc::vec![leg(0.0, 0.0), leg(0.0, 0.0)]),
            (1, alloc::vec![leg(0.5, 0.0), leg(0.5, -0.4)]),
        ];
        let radii = [[0.2, 0.2], [0.1, 0.1]];
        let floor = f32::NEG_INFINITY;
        assert!((deepest_overlap(&legs, &radii, 1, floor) + 0.2).abs() < 1e-6);
        assert!((deepest_overlap(&legs, &radii, 2, floor) - 0.2).abs() < 1e-6);
        assert!((deepest_overlap(&legs, &radii, 2, -0.1) - 0.2).abs() < 1e-6);
        assert_eq!(deepest_overlap(&legs, &radii, 1, -0.1), -0.1);
        assert_eq!(deepest_overlap(&legs[..1], &radii, 2, floor), floor);
    }

    #[test]
    fn free_frames_turn_within_the_limit_and_kept_frames_stay() {
        // Kept at 0 and 1 rad about X, with three free frames between that jump straight to
        // the end: limited to 0.3 rad a frame, they leave and rejoin the kept frames.
        let angles = [0.0, 0.0, 1.0, 1.0, 1.0];
        let mut track: Vec<Quat> = angles.iter().map(|&a| Quat::from_rotation_x(a)).collect();
        let free = [false, true, true, true, false];
        limit_free_turn_rate(&mut track, &free, 0.3);
        assert_eq!(track[0], Quat::from_rotation_x(0.0));
        assert_eq!(track[4], Quat::from_rotation_x(1.0));
        for pair in track.windows(2) {
            assert!(pair[0].angle_between(pair[1]) <= 0.3 + 1e-5, "{track:?}");
        }
    }
}
