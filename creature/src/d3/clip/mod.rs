//! Baked animation clips of 3D creatures: the [`Clip`] and [`Track`] types, and what every
//! baker shares (frame counts, empty clips, loop errors, the root's rest position, the tail
//! chain). The bakers and their helpers are in the submodules:
//!
//! - `walk`: walkers' gait-driven `walk`, `turn`, `idle`, `run` and `hop` (the controller
//!   run, the loop cut and closed, legs by two-bone IK; a hopper's tail swing);
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
mod live;
mod swim;
mod walk;

pub use live::{ARRIVAL_RADIUS, Animator, Intent, MAX_STEP};
pub(crate) use walk::MAX_LEG_TURN_RATE;

pub(crate) use flight::flight;
pub(crate) use kinematics::{pose, skinned};
pub(crate) use live::bake::{live_walk, slither};
pub(crate) use swim::swim;
pub(crate) use walk::{gait, hop_loop, run_loop, turn, walk_loop};

/// How far a spine joint may bend, in radians per unit of its bone length over the body's
/// half-thickness (see `Creature::bend_limits`): linear-blend skinning over whole-bone blends
/// stretches the outer skin by about this much over 1 per radian.
const BEND_PER_THICKNESS: f32 = 0.15;

/// A segment `a b`, set up once for the distances to it of many points.
#[derive(Clone, Copy)]
struct Segment {
    a: Vec3,
    ab: Vec3,
    length_squared: f32,
}

impl Segment {
    fn new(a: Vec3, b: Vec3) -> Self {
        let ab = b - a;
        Self {
            a,
            ab,
            length_squared: ab.length_squared(),
        }
    }

    /// The distance from `p` to the segment.
    fn distance(&self, p: Vec3) -> f32 {
        let (a, ab) = (self.a, self.ab);
        let t = if self.length_squared > 0.0 {
            ((p - a).dot(ab) / self.length_squared).clamp(0.0, 1.0)
        } else {
            0.0
        };
        p.distance(a + ab * t)
    }
}

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
    /// ([`bake_walk_loop`](Creature::bake_walk_loop)), `run`
    /// ([`bake_run_loop`](Creature::bake_run_loop)) and `hop`
    /// ([`bake_hop_loop`](Creature::bake_hop_loop)) have their loops closed where that keeps the
    /// feet plausible, as `turn` ([`bake_turn`](Creature::bake_turn)) does (in the sweep of
    /// 10,000 walkers, 93% of walks, 99% of runs, 95% of hops and 80% of turns close); a plain
    /// [`bake_walk`](Creature::bake_walk) does not loop.
    pub loop_error: f32,
}

impl Clip {
    /// The clip's length in seconds (`(frames − 1) / fps`).
    #[must_use]
    pub fn duration(&self) -> f32 {
        self.frames.saturating_sub(1) as f32 / self.fps
    }

    /// The clip in place: the root's horizontal travel removed (every frame's root at the
    /// first frame's `x` and `z`; its height, its rotation and every other track kept), so a
    /// viewer that plays it on a loop does not snap the creature back to the start. Engines
    /// that move a character by its root motion want the clip as baked; see
    /// [`Params::in_place`](crate::d3::Params::in_place) to bake them so.
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    ///
    /// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
    /// let walk = walker.clips.iter().find(|c| c.name == "walk").expect("walkers walk");
    /// let here = walk.clone().in_place();
    /// let (first, last) = (here.root_translation[0], here.root_translation[here.frames - 1]);
    /// assert_eq!((first.x, first.z), (last.x, last.z));
    /// assert!(walk.root_translation[walk.frames - 1].z > first.z);
    /// # Ok::<(), creature::Error>(())
    /// ```
    #[must_use]
    pub fn in_place(mut self) -> Self {
        if let Some(&start) = self.root_translation.first() {
            for t in &mut self.root_translation {
                t.x = start.x;
                t.z = start.z;
            }
        }
        self
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

    /// Per skeleton joint, the most its rotation may bend the spine (radians) before the skin
    /// around it stretches or squashes past what the audit allows: [`BEND_PER_THICKNESS`] times
    /// the shorter of its two bones over the body's thickness there (the farthest from the
    /// spine of the vertices it moves together with another joint), and no more than any mesh
    /// edge around it allows ([`edge_bend_limits`](Self::edge_bend_limits)). Joints off the
    /// spine (and spine tips) have no limit (`f32::INFINITY`).
    fn bend_limits(&self) -> Vec<f32> {
        let joints = &self.skeleton.joints;
        let mut limits = alloc::vec![f32::INFINITY; joints.len()];
        let spine = &self.rig.spine;
        let points: Vec<Vec3> = spine.iter().map(|&j| joints[j].position).collect();
        if points.len() < 3 {
            return limits;
        }
        // Each spine joint's place on the polyline.
        let mut place = alloc::vec![usize::MAX; joints.len()];
        for (k, &j) in spine.iter().enumerate() {
            place[j] = k;
        }
        // The spine's bones: `bones[k]` from place `k` to place `k + 1`.
        let bones: Vec<Segment> = points
            .windows(2)
            .map(|w| Segment::new(w[0], w[1]))
            .collect();
        // Per vertex, its spine joints' places and weights.
        let spines: Vec<SpineWeights> = self
            .mesh
            .joints
            .iter()
            .zip(&self.mesh.weights)
            .map(|(js, ws)| SpineWeights::of(js, ws, &place))
            .collect();
        let mut thickness = alloc::vec![0.0f32; joints.len()];
        for (((p, js), ws), spined) in self
            .mesh
            .positions
            .iter()
            .zip(&self.mesh.joints)
            .zip(&self.mesh.weights)
            .zip(&spines)
        {
            // Body vertices: blended between spine joints; the distance to the bones on either
            // side of the most weighted one.
            let blended = spined.len;
            let mut most = (0.0f32, usize::MAX);
            for &(k, w) in &spined.entries[..spined.len] {
                if w > most.0 {
                    most = (w, k);
                }
            }
            if blended < 2 {
                continue;
            }
            let k = most.1;
            let before = k
                .checked_sub(1)
                .map_or(f32::INFINITY, |i| bones[i].distance(*p));
            let after = bones.get(k).map_or(f32::INFINITY, |b| b.distance(*p));
            let d = before.min(after);
            for (&j, &w) in js.iter().zip(ws) {
                if w > 0.0 {
                    let t = &mut thickness[usize::from(j)];
                    *t = t.max(d);
                }
            }
        }
        // A joint no vertex is mostly weighted to (a coarse mesh) still bends the skin its
        // neighbours carry: it takes the nearest spine joint's thickness.
        let along: Vec<f32> = spine.iter().map(|&j| thickness[j]).collect();
        // An edge whose two ends follow spine joints several apart (the skin's nearest joints
        // jump where the spine bends up into the neck, or a coarse mesh has fewer rings than
        // joints) is stretched by all their bends together, each as far as it moves one end
        // more than the other: each joint of such an edge keeps within the edge's share.
        let by_edges = self.edge_bend_limits(&place, &points, &spines);
        for k in 1..points.len() - 1 {
            let shorter = points[k]
                .distance(points[k - 1])
                .min(points[k].distance(points[k + 1]));
            let r = nearest_positive(&along, k);
            if r > 0.0 {
                limits[spine[k]] = (BEND_PER_THICKNESS * shorter / r).min(by_edges[k]);
            }
        }
        limits
    }

    /// Per spine place (`place` maps a skeleton joint to its place on the spine, `usize::MAX`
    /// off it; `points` the spine joints' rest positions; `spines` each vertex's
    /// [`SpineWeights`]), the most that joint may bend for
    /// the mesh edges around it: a joint's bend turns the skin it carries (its own and its
    /// descendants' weights) about it, so it moves an edge's two ends apart by the angle times
    /// their distance from it times the difference of those weights at the two ends. Bending
    /// every such joint of an edge alike, their sum stays within [`BEND_PER_THICKNESS`] of the
    /// edge's rest length. `f32::INFINITY` where no edge limits a joint.
    fn edge_bend_limits(
        &self,
        place: &[usize],
        points: &[Vec3],
        spines: &[SpineWeights],
    ) -> Vec<f32> {
        let mesh = &self.mesh;
        let count = points.len();
        let mut limits = alloc::vec![f32::INFINITY; count];
        let root = self
            .rig
            .root()
            .map_or(usize::MAX, |r| place.get(r).copied().unwrap_or(usize::MAX));
        // The skin weight a bend at place `k` carries: the tail side's joints from the tip to
        // `k`, the head side's from `k` on (the root's own rotation moves the whole body).
        let carried = |v: &SpineWeights, k: usize| -> f32 {
            v.entries[..v.len]
                .iter()
                .filter(|&&(q, _)| (k < root && q <= k) || (k > root && q >= k))
                .map(|&(_, w)| w)
                .sum()
        };
        // Per place from an edge's first, whether its two ends carry different weights there.
        let mut differs: Vec<bool> = Vec::with_capacity(count);
        for t in &mesh.indices {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                let (a, b) = (a as usize, b as usize);
                let (sa, sb) = (&spines[a], &spines[b]);
                if sa.len == 0 || sb.len == 0 || sa == sb {
                    continue;
                }
                let (pa, pb) = (mesh.positions[a], mesh.positions[b]);
                let edge = pa.distance(pb);
                if !(edge > 0.0) {
                    continue;
                }
                // The joints between the two ends' weights (the spine's tips do not bend).
                let (a0, a1) = sa.range();
                let (b0, b1) = sb.range();
                let (first, last) = (a0.min(b0).max(1), a1.max(b1).min(count - 2));
                let mut moved = 0.0f32;
                differs.clear();
                for (k, &at) in points.iter().enumerate().take(last + 1).skip(first) {
                    let (ca, cb) = (carried(sa, k), carried(sb, k));
                    differs.push(ca != cb);
                    let apart = (ca - cb).abs();
                    if apart > 0.0 {
                        let lever = pa.distance_squared(at).max(pb.distance_squared(at));
                        moved += apart * crate::math::sqrt(lever);
                    }
                }
                if !(moved > 0.0) {
                    continue;
                }
                let limit = BEND_PER_THICKNESS * edge / moved;
                for (l, &differ) in limits.iter_mut().take(last + 1).skip(first).zip(&differs) {
                    if *l > limit && differ {
                        *l = limit;
                    }
                }
            }
        }
        limits
    }

    /// Per skeleton joint, the farthest any vertex it moves (with any weight) is from it at
    /// rest: a skinned vertex is never lower than the lowest of its joints' heights less their
    /// reach.
    fn joint_reach(&self) -> Vec<f32> {
        let joints = &self.skeleton.joints;
        let mut reach = alloc::vec![0.0f32; joints.len()];
        self.for_each_skinned(|j, p| {
            reach[j] = reach[j].max(p.distance(joints[j].position));
        });
        reach
    }

    /// Calls `visit(joint, position)` for each rest vertex and each joint (a valid index) that
    /// moves it with some weight.
    fn for_each_skinned(&self, mut visit: impl FnMut(usize, Vec3)) {
        let joints = self.skeleton.joints.len();
        self.for_each_vertex(|p, js, ws| {
            for (&j, &w) in js.iter().zip(ws) {
                let j = usize::from(j);
                if w > 0.0 && j < joints {
                    visit(j, p);
                }
            }
        });
    }

    /// Calls `visit(position, joints, weights)` for each rest vertex of the mesh.
    fn for_each_vertex(&self, mut visit: impl FnMut(Vec3, &[u16; 4], &[f32; 4])) {
        for ((&p, js), ws) in self
            .mesh
            .positions
            .iter()
            .zip(&self.mesh.joints)
            .zip(&self.mesh.weights)
        {
            visit(p, js, ws);
        }
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

    /// The joints a hopper's tail swings on ([`walk::hop_tail_swing`]), nearest the root
    /// first, each with the most it swings ([`SWING_STRETCH`] times the most its skin lets it
    /// bend sideways, on top of a turn's bend): the [`tail_chain`](Self::tail_chain)'s
    /// joints behind every limb's root (turning one a leg hangs from would move the leg off
    /// where the gait put its foot).
    pub(super) fn swinging_tail(&self) -> Vec<(usize, f32)> {
        let joints = &self.skeleton.joints;
        let chain = self.tail_chain();
        // The chain's joints no limb hangs from, nor any joint between it and the root.
        let carries = |j: usize| {
            joints
                .iter()
                .enumerate()
                .any(|(i, k)| k.parent == Some(j) && !self.rig.spine.contains(&i))
        };
        let free = chain
            .iter()
            .rposition(|&j| carries(j))
            .map_or(0, |last| last + 1);
        let limits = self.bend_limits();
        chain[free..]
            .iter()
            .map(|&j| (j, SWING_STRETCH * limits[j]))
            .collect()
    }
}

/// How much further than a turn's bend limit (`bend_limits`, cautious: at 1.4 times them the
/// audit's skin stretch stays within 1.18) a hopper's tail swings up.
const SWING_STRETCH: f32 = 1.3;

/// A vertex's spine joints: their places on the spine and weights (at most four).
#[derive(Clone, Copy, Default, PartialEq)]
struct SpineWeights {
    entries: [(usize, f32); 4],
    len: usize,
}

impl SpineWeights {
    /// The spine joints among a vertex's joints `js` with weights `ws` (`place` maps a skeleton
    /// joint to its place on the spine, `usize::MAX` off it): those weighted, in their order.
    fn of(js: &[u16; 4], ws: &[f32; 4], place: &[usize]) -> Self {
        let mut out = Self::default();
        for (&j, &w) in js.iter().zip(ws) {
            let k = place[usize::from(j)];
            if w > 0.0 && k != usize::MAX {
                out.entries[out.len] = (k, w);
                out.len += 1;
            }
        }
        out
    }

    /// The first and last of the places (some entry there).
    fn range(&self) -> (usize, usize) {
        self.entries[..self.len]
            .iter()
            .fold((usize::MAX, 0), |(a, b), &(k, _)| (a.min(k), b.max(k)))
    }
}

/// `values[k]` if positive, or else the positive value nearest to `k` (the earlier one of two
/// as near); 0 if there is none.
fn nearest_positive(values: &[f32], k: usize) -> f32 {
    (0..values.len())
        .flat_map(|d| [k.checked_sub(d), k.checked_add(d)])
        .flatten()
        .filter_map(|i| values.get(i).copied())
        .find(|&v| v > 0.0)
        .unwrap_or(0.0)
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
/// Each rotation of a looping track (its last frame the first's again) turned no further than
/// `max` radians from the one before it, round the loop: the track is followed as closely as
/// that allows, from the end of the loop into its start, until the limited loop repeats
/// itself; the last frame is then the first again. A track that turns no faster is kept.
pub(super) fn limit_looping_turn_rate(rotations: &mut [Quat], max: f32) {
    let n = rotations.len();
    // Two unit quaternions are within `max` of each other when their dot product's size is
    // at least cos(max / 2).
    let near = crate::math::cos(0.5 * max);
    if n < 3 || (1..n).all(|k| rotations[k].dot(rotations[k - 1]).abs() >= near) {
        return;
    }
    let cycle = n - 1;
    let wanted: Vec<Quat> = rotations[..cycle].to_vec();
    let mut before = rotations[cycle - 1];
    // The limited track settles once it has caught up with the wanted one; three times round
    // is plenty for a rate that catches up within a loop.
    for _ in 0..3 {
        for (slot, &want) in rotations[..cycle].iter_mut().zip(&wanted) {
            let angle = before.angle_between(want);
            let q = if angle > max {
                before.slerp(want, max / angle).normalize()
            } else {
                want
            };
            *slot = q;
            before = q;
        }
    }
    rotations[cycle] = rotations[0];
}

pub(super) fn frames_for(seconds: f32) -> (usize, f32) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_looping_track_turns_within_the_limit_round_its_seam() {
        // A loop of 12 frames about Y that jumps 1.2 rad at frame 5 and back at the seam.
        let mut track: Vec<Quat> = (0..13)
            .map(|f| Quat::from_rotation_y(if (5..12).contains(&f) { 1.2 } else { 0.0 }))
            .collect();
        let max = 0.5;
        limit_looping_turn_rate(&mut track, max);
        for k in 1..track.len() {
            assert!(
                track[k - 1].angle_between(track[k]) <= max + 1e-5,
                "frame {k}"
            );
        }
        assert_eq!(track[0], track[12], "the last frame is the first again");
        // It follows the wanted track as soon as it has caught up.
        assert!(track[8].angle_between(Quat::from_rotation_y(1.2)) < 1e-5);
        assert!(track[3].angle_between(Quat::IDENTITY) < 1e-5);
    }

    #[test]
    fn a_looping_track_within_the_limit_is_kept() {
        let track: Vec<Quat> = (0..13)
            .map(|f| Quat::from_rotation_x(0.4 * sin_turns(f as f32 / 12.0)))
            .collect();
        let mut limited = track.clone();
        limit_looping_turn_rate(&mut limited, 0.5);
        assert_eq!(limited, track);
    }
}
