//! Walkers' looping clips, each baked by the live animator on flat ground at [`CLIP_FPS`]
//! (`live/bake.rs`): `walk`, `run` and `hop` (cut at whole strides and closed into a loop),
//! `turn` (a full turn in place, its rate retried to complete at the cut) and `idle`. A loop's
//! cut and closing are chosen on the animator's gait (the feet and the body, not posed), and
//! the animator, driven again, poses each frame with the closing.

use alloc::vec::Vec;

use glam::{Affine3A, Vec3};

use creature_gait::{GaitOptions, Leg, LimbKind, Pose};

use super::gait_run::{GaitRun, best_cut, ranked_cuts};
use super::live::bake::{gait_run, posed_loop, record};
use super::{CLIP_FPS, Clip};
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

/// The most a leg's joint turns from one frame to the next while its foot is in the air, in
/// radians (18 rad/s at [`CLIP_FPS`]; the audit of delivered creatures allows 20).
pub(super) const MAX_LEG_TURN_PER_FRAME: f32 = 0.6;

/// [`MAX_LEG_TURN_PER_FRAME`] in radians per second: the gait's swings are made long enough for
/// it (see `swing_time_for_joints`).
pub(crate) const MAX_LEG_TURN_RATE: f32 = MAX_LEG_TURN_PER_FRAME * CLIP_FPS;

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
pub(super) const GROUND_CONTACT: f32 = 0.005;

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

/// A looping `walk` (see [`Creature::bake_walk_loop`]), its swings slowed if need be
/// ([`slow_enough`]).
pub(crate) fn walk_loop(c: &Creature) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    slow_enough(c, &setup.options, SLOW_RETRIES, |options, limit| {
        forward_loop(c, "walk", c.speed, options, limit)
    })
}

/// How fast (radians per second) a walking leg's joint may turn in a clip still too fast
/// after its retries before its swings are limited (see [`slow_enough`]): what the audit of
/// delivered creatures allows.
const FLICK_RATE: f32 = 20.0;

/// How many times a clip whose legs turn too fast is baked again with longer swings (more
/// often, a walk's feet were seen to come down beside each other).
const SLOW_RETRIES: usize = 2;

/// [`SLOW_RETRIES`] for a run, whose swings are the quickest: its joints' speed comes down
/// unevenly with longer swings.
const RUN_RETRIES: usize = 4;

/// A looping `run` (see [`Creature::bake_run_loop`]), its swings slowed if need be
/// ([`slow_enough`]; a small walker's strides take five frames).
pub(crate) fn run_loop(c: &Creature) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let speed = setup.run_speed().ok_or(Error::NoGait)?;
    // A hopper hops at the run's speed, slowed and limited as a run is.
    slow_enough(c, &setup.options, RUN_RETRIES, |options, limit| {
        forward_loop(c, "run", speed, options, limit)
    })
}

/// The clip `bake` bakes with the gait `options` (and no limit, `false`); if its walking legs
/// turn a joint faster than [`MAX_LEG_TURN_RATE`] between two frames (a quick swing's joints
/// are not all slowed by `swing_time_for_joints`, which takes them to turn evenly), baked
/// again (up to `retries` times) with its shortest swing
/// (`GaitOptions::min_swing_time`) longer by as much, and a tenth, the slowest kept (a retry
/// the controller rejects ends the retries); if even that turns faster than [`FLICK_RATE`],
/// baked once more with
/// the slowest one's options and its legs' joints limited in their swings (`true`, see
/// `posed_loop`), kept if it turns slower. The live animator runs with the set-up's options
/// and no limit.
fn slow_enough(
    c: &Creature,
    options: &GaitOptions,
    retries: usize,
    mut bake: impl FnMut(&GaitOptions, bool) -> Result<Clip, Error>,
) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let mut options = *options;
    let legs: Vec<usize> = setup
        .legs
        .iter()
        .zip(&setup.hip_joints)
        .filter(|(leg, _)| leg.kind == LimbKind::Leg)
        .flat_map(|(_, &hip)| [hip, hip + 1, hip + 2])
        .collect();
    let limit = MAX_LEG_TURN_RATE * (1.0 + 1e-3);
    let mut best = bake(&options, false)?;
    let mut best_rate = fastest_turn(&best, &legs);
    let mut best_options = options;
    let mut rate = best_rate;
    for _ in 0..retries {
        if rate <= limit {
            break;
        }
        let longer = (options.min_swing_time * 1.1 * rate / MAX_LEG_TURN_RATE).min(MAX_SWING_TIME);
        if !(longer > options.min_swing_time) {
            break;
        }
        options.min_swing_time = longer;
        let Ok(clip) = bake(&options, false) else {
            break;
        };
        rate = fastest_turn(&clip, &legs);
        if rate < best_rate {
            (best, best_rate, best_options) = (clip, rate, options);
        }
    }
    if best_rate > FLICK_RATE
        && let Ok(clip) = bake(&best_options, true)
        && fastest_turn(&clip, &legs) < best_rate
    {
        best = clip;
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
pub(crate) fn hop_loop(c: &Creature) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let speed = setup.hop_speed().ok_or(Error::NoGait)?;
    forward_loop(c, "hop", speed, &setup.options, false)
}

/// A looping clip named `name` moving forward at `speed`: 4 s of the animator (with the gait
/// `options`) on flat ground, cut at the frame from 1 s on closest to the first and closed
/// where that keeps the feet plausible (a hopper's tail swinging against its legs as it hops,
/// as live); with `limit`, its legs' joints limited in their swings (see `posed_loop`).
fn forward_loop(
    c: &Creature,
    name: &'static str,
    speed: f32,
    options: &GaitOptions,
    limit: bool,
) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let run = gait_run(c, options, 4.0, (speed, 0.0))?;
    let first = CLIP_FPS as usize;
    let end = best_cut(&run, first..run.frames(), |_| 0.0);
    let travel = Pose::from_yaw(Vec3::Z * (speed * end as f32 / CLIP_FPS), 0.0);
    let closed = c.closed_or_cut(run.clone(), end, &travel, &setup.legs);
    posed_loop(
        c,
        options,
        name,
        (speed, 0.0),
        (&run, &closed),
        limit,
        |_| {},
    )
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
pub(crate) fn turn(c: &Creature) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    slow_enough(c, &setup.options, SLOW_RETRIES, |options, limit| {
        turn_with(c, options, limit)
    })
}

/// [`turn`] with the gait `options`.
fn turn_with(c: &Creature, options: &GaitOptions, limit: bool) -> Result<Clip, Error> {
    let setup = c.gait.as_ref().ok_or(Error::NoGait)?;
    let radii = c.leg_radii(&setup.hip_joints);
    let mut rate = c.turn_rate(&setup.legs);
    // Legs nearer each other than this (× body length) count as touching: what is measured
    // here and on the exported file differs by float rounding.
    let touching = -1e-4 * c.length;
    let mut best = turn_at(c, (options, limit), rate, &radii)?;
    for _ in 0..TURN_SLOWDOWNS {
        if best.1 <= touching {
            break;
        }
        rate *= TURN_SLOWDOWN;
        let slower = turn_at(c, (options, limit), rate, &radii)?;
        if slower.1 < best.1 {
            best = slower;
        }
    }
    Ok(best.0)
}

/// A full `turn` in place at `rate` (rad/s, about), with how deep its legs overlap (as
/// [`deepest_overlap`] measures it on the posed frames; −0.1 × the body length where no two
/// come nearer); with `limit`, its legs' joints limited in their swings (see `posed_loop`).
fn turn_at(
    c: &Creature,
    (options, limit): (&GaitOptions, bool),
    rate: f32,
    radii: &[[f32; 2]],
) -> Result<(Clip, f32), Error> {
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
        let run = gait_run(c, options, seconds + 0.5 + 1.0 / CLIP_FPS, (0.0, rate))?;
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
    let closed = c.closed_or_cut_among(run.clone(), &ends, plain, &Pose::IDENTITY, &setup.legs);
    // Each walking leg's hip, knee and foot per frame, in the body's frame.
    let walking: Vec<usize> = (0..setup.legs.len())
        .filter(|&i| setup.legs[i].kind == LimbKind::Leg)
        .collect();
    let mut segments: Vec<(usize, Vec<[Vec3; 3]>)> = walking
        .iter()
        .map(|&i| (i, Vec::with_capacity(closed.frames())))
        .collect();
    let root = c.skeleton.joints.iter().position(|j| j.parent.is_none());
    let clip = posed_loop(
        c,
        options,
        "turn",
        (0.0, rate),
        (&run, &closed),
        limit,
        |animator| {
            let world = animator.world_transforms();
            let body = root.map_or(Affine3A::IDENTITY, |r| world[r].inverse());
            for (i, points) in &mut segments {
                let hip = setup.hip_joints[*i];
                points.push(core::array::from_fn(|k| {
                    body.transform_point3(Vec3::from(world[hip + k].translation))
                }));
            }
        },
    )?;
    // Only legs nearer than a tenth of the body length matter.
    let overlap = deepest_overlap(&segments, radii, closed.frames(), -0.1 * c.length);
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
) -> Result<Clip, Error> {
    record(c, name, seconds, speed, yaw_rate)
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
        let plain = Figures::of(run, end + 1, legs, 2.0 * ground);
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
        let now = Figures::of(&closed, closed.frames(), legs, 2.0 * ground);
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
}
