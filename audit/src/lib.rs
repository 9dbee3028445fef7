#![doc = include_str!("../README.md")]
// A host tool for tests and xtask: `std` paths are the natural ones here.
#![allow(clippy::std_instead_of_core, clippy::std_instead_of_alloc)]

mod geometry;
mod model;
mod pose;

use std::fmt;

use glam::{Vec2, Vec3};

pub use geometry::Terrain;
pub use model::{Channel, Clip, Model, Node, Values};
use pose::Poser;

/// Why a file could not be audited.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum AuditError {
    /// The file is not a glTF the reader accepts.
    Gltf(String),
    /// The file parses but lacks what the audit needs.
    Unsupported {
        /// What is missing or wrong.
        what: &'static str,
    },
}

impl fmt::Display for AuditError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Gltf(e) => write!(f, "not a readable glTF: {e}"),
            Self::Unsupported { what } => write!(
                f,
                "cannot audit this file: {what} (the audit needs one skinned triangle mesh whose \
                 joints are named as `creature` names them)"
            ),
        }
    }
}

impl std::error::Error for AuditError {}

/// The thresholds, as fractions of the body length (the spine's length) where they are
/// lengths.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Limits {
    /// A foot is on the ground when its lowest vertex is at most this high; no vertex may be
    /// deeper than this below the ground.
    pub ground: f32,
    /// The most a foot may slide horizontally over one stretch on the ground (touchdown
    /// included), and the most it may move in [`Limits::hold_frames`] frames to count as held
    /// still.
    pub slide: f32,
    /// Consecutive frames a foot must keep still in the air to count as a planted foot held in
    /// mid-air.
    pub hold_frames: usize,
    /// The most a joint may turn between two keys, in degrees.
    pub key_turn_degrees: f32,
    /// The fastest a joint may turn, in radians per second.
    pub angular_speed: f32,
    /// The range every edge's length must stay in, as a multiple of its rest length.
    pub stretch: [f32; 2],
}

impl Limits {
    /// The plausible-motion thresholds: ground and slide 0.5% of the body length, held still
    /// for 3 frames, 45° per key, 20 rad/s, edges within 0.8–1.25× their rest length.
    pub const DEFAULT: Self = Self {
        ground: 0.005,
        slide: 0.005,
        hold_frames: 3,
        key_turn_degrees: 45.0,
        angular_speed: 20.0,
        stretch: [0.8, 1.25],
    };
}

impl Default for Limits {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[non_exhaustive]
pub enum Check {
    /// Walkers at rest: the margin of the mesh's centre of volume inside the convex hull of
    /// its ground contacts (× body length); fails at 0 or below.
    Tips,
    /// The height of a foot held still off the ground (× body length).
    FootInAir,
    /// A walker's foot that never reaches the ground in a clip: its lowest height.
    FootNeverDown,
    /// How far a foot slides while on the ground (× body length).
    FootSlides,
    /// How far a foot goes past the body's midline to the other side (× body length).
    FeetCross,
    /// How deep two legs' segments (capsules of their mesh radius) overlap (× body length).
    LegsIntersect,
    /// The most a joint turns between two keys, in degrees.
    KeyTurn,
    /// The fastest a joint turns, in radians per second.
    AngularSpeed,
    /// How deep a vertex goes below the ground (× body length).
    BelowGround,
    /// The longest edge as a multiple of its rest length.
    Stretch,
    /// The shortest edge as a multiple of its rest length.
    Squash,
    /// A slitherer's body off the ground: the height of its lowest vertex (× body length) in
    /// a frame.
    OffGround,
    /// How far a slitherer's belly slides sideways while on the ground (× body length): each
    /// vertex's moves across the body where it is (its joints' bones, skinned and blended as
    /// the vertex is, level), added up over a stretch on the ground, a new stretch each body
    /// length it moves. A body crawling along its own path slides only along itself.
    BellySlides,
}

impl Check {
    /// Every check, in report order.
    pub const ALL: [Self; 13] = [
        Self::Tips,
        Self::FootInAir,
        Self::FootNeverDown,
        Self::FootSlides,
        Self::FeetCross,
        Self::LegsIntersect,
        Self::KeyTurn,
        Self::AngularSpeed,
        Self::BelowGround,
        Self::Stretch,
        Self::Squash,
        Self::OffGround,
        Self::BellySlides,
    ];

    /// A short name.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Tips => "tips",
            Self::FootInAir => "foot held in the air",
            Self::FootNeverDown => "foot never down",
            Self::FootSlides => "foot slides",
            Self::FeetCross => "feet cross",
            Self::LegsIntersect => "legs intersect",
            Self::KeyTurn => "turn per key",
            Self::AngularSpeed => "angular speed",
            Self::BelowGround => "below ground",
            Self::Stretch => "skin stretch",
            Self::Squash => "skin squash",
            Self::OffGround => "body off the ground",
            Self::BellySlides => "belly slides sideways",
        }
    }

    /// Whether `value` fails against `limit`: the stability margin and the shortest edge fail
    /// below (or at, for the margin) their limit, everything else above it.
    #[must_use]
    pub fn fails(self, value: f32, limit: f32) -> bool {
        match self {
            Self::Tips => !(value > limit),
            Self::Squash => !(value >= limit),
            _ => !(value <= limit),
        }
    }
}

/// The worst value of one check over one clip (or the rest pose), where it happened.
#[derive(Debug, Clone, PartialEq)]
pub struct Measure {
    /// The check.
    pub check: Check,
    /// The clip, `None` for the rest pose.
    pub clip: Option<String>,
    /// The worst value.
    pub value: f32,
    /// Its limit.
    pub limit: f32,
    /// The frame of the worst value.
    pub frame: usize,
    /// Where: a joint, a leg or legs, an edge's joints.
    pub at: String,
}

impl Measure {
    /// Whether the worst value is beyond the limit.
    #[must_use]
    pub fn fails(&self) -> bool {
        self.check.fails(self.value, self.limit)
    }
}

impl fmt::Display for Measure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.clip {
            Some(c) => write!(f, "{c} frame {}: ", self.frame)?,
            None => write!(f, "rest: ")?,
        }
        write!(
            f,
            "{} {:.4} (limit {}) at {}",
            self.check.name(),
            self.value,
            self.limit,
            self.at
        )
    }
}

/// One creature's audit: the worst value of every check per clip.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// The body length (the spine's length) the length limits are fractions of.
    pub body_length: f32,
    /// Whether it is a walker (it has a `walk` clip): the stance checks apply.
    pub walker: bool,
    /// Whether it is a slitherer (it has a `slither` clip): the belly checks apply.
    pub slitherer: bool,
    /// The measures.
    pub measures: Vec<Measure>,
}

impl Report {
    /// The measures beyond their limits.
    pub fn failures(&self) -> impl Iterator<Item = &Measure> {
        self.measures.iter().filter(|m| m.fails())
    }

    /// Whether every measure is within its limit.
    #[must_use]
    pub fn passes(&self) -> bool {
        self.failures().next().is_none()
    }

    /// Whether `check` fails anywhere.
    #[must_use]
    pub fn fails(&self, check: Check) -> bool {
        self.failures().any(|m| m.check == check)
    }
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let failures: Vec<&Measure> = self.failures().collect();
        if failures.is_empty() {
            return write!(f, "passes");
        }
        for (i, m) in failures.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{m}")?;
        }
        Ok(())
    }
}

/// Audits a `.glb` file: [`Model::from_glb`], then [`audit`].
///
/// # Errors
/// As [`Model::from_glb`] and [`audit`].
pub fn audit_glb(bytes: &[u8], limits: &Limits) -> Result<Report, AuditError> {
    audit(&Model::from_glb(bytes)?, limits)
}

/// A two-bone leg found by its joints' names.
struct Leg {
    name: String,
    left: bool,
    joints: [usize; 3],
    /// The vertices bound mostly to the foot joint.
    foot: Vec<usize>,
    /// Mesh radii of the upper and lower segments.
    radius: [f32; 2],
}

/// Audits `model`: poses the rest pose and every frame of every clip with linear-blend
/// skinning as a viewer does, and measures every [`Check`] on the skinned mesh. The body
/// length is the length of the joints named `spine_*`, `tail_*`, `head` and `head_end`; legs
/// are the joints `leg_<side><n>_hip`, `_knee` and `_foot`; the body frame is `spine_0`'s.
/// A model with a `walk` or `walk_to` clip is a walker (the stance checks apply); one with a
/// `slither` or `slither_to` clip is a slitherer (the belly checks apply). Heights in
/// the clips are measured above the model's [`terrain`](Model::terrain) under each point when
/// it has one, else above `y = 0`; the rest pose stands on `y = 0`.
///
/// # Errors
/// [`AuditError::Unsupported`] when the model has no named spine.
pub fn audit(model: &Model, limits: &Limits) -> Result<Report, AuditError> {
    let mut poser = Poser::new(model)?;
    poser.rest();
    let spine_like = |name: &str| {
        name.starts_with("spine_") || name.starts_with("tail_") || name.starts_with("head")
    };
    let rest: Vec<Vec3> = (0..model.skin.len())
        .map(|j| poser.joint_world(j).w_axis.truncate())
        .collect();
    let mut length = 0.0;
    for (j, &node) in model.skin.iter().enumerate() {
        let Some(parent) = model.nodes[node].parent else {
            continue;
        };
        if let Some(p) = model.skin.iter().position(|&n| n == parent)
            && spine_like(model.joint_name(j))
            && spine_like(model.joint_name(p))
        {
            length += rest[j].distance(rest[p]);
        }
    }
    if !(length > 0.0) {
        return Err(AuditError::Unsupported {
            what: "no spine joints (spine_*, tail_*, head)",
        });
    }
    let body = model.joint("spine_0").ok_or(AuditError::Unsupported {
        what: "no spine_0 joint",
    })?;
    let walker = model
        .clips
        .iter()
        .any(|c| c.name == "walk" || c.name == "walk_to");
    let slitherer = model
        .clips
        .iter()
        .any(|c| c.name == "slither" || c.name == "slither_to");
    // Per joint, its bone's direction at rest: toward its child on the spine (the last one's
    // from its parent).
    let axes = bone_axes(model, &rest, spine_like);
    // Heights in the clips are above the terrain when the file has one (off it there is no
    // ground), else above `y = 0`; the rest pose stands on `y = 0`.
    let ground = |p: Vec3| match &model.terrain {
        None => 0.0,
        Some(t) => t.height(p.x, p.z).unwrap_or(f32::NEG_INFINITY),
    };
    let dominant = dominant(model);
    let legs = legs(model, &dominant, &rest);
    let edges = edges(model, length);

    let mut report = Report {
        body_length: length,
        walker,
        slitherer,
        measures: Vec::new(),
    };
    let worst = |check: Check, clip: Option<&str>, limit: f32| Worst {
        check,
        clip: clip.map(str::to_owned),
        limit,
        value: None,
        frame: 0,
        at: String::new(),
    };

    // The rest pose: stability and ground.
    if walker {
        let mut tips = worst(Check::Tips, None, 0.0);
        let value = match geometry::centre_of_volume(&poser.positions, &model.triangles) {
            Some((centre, _)) => {
                let contacts: Vec<Vec2> = poser
                    .positions
                    .iter()
                    .filter(|p| p.y <= limits.ground * length)
                    .map(|p| Vec2::new(p.x, p.z))
                    .collect();
                let hull = geometry::convex_hull(&contacts);
                geometry::margin(&hull, Vec2::new(centre.x, centre.z)) / length
            }
            None => f32::NEG_INFINITY,
        };
        tips.min(value, 0, || "centre of volume".into());
        report.measures.push(tips.done());
    }
    let mut below = worst(Check::BelowGround, None, limits.ground);
    let (depth, at) = lowest(&poser.positions);
    below.max(-depth / length, 0, || format!("vertex {at}"));
    report.measures.push(below.done());

    for clip in &model.clips {
        let name = Some(clip.name.as_str());
        let times = clip.frame_times();
        let mut below = worst(Check::BelowGround, name, limits.ground);
        let mut stretch = worst(Check::Stretch, name, limits.stretch[1]);
        let mut squash = worst(Check::Squash, name, limits.stretch[0]);
        let mut cross = worst(Check::FeetCross, name, 0.0);
        let mut intersect = worst(Check::LegsIntersect, name, 0.0);
        let mut off = worst(Check::OffGround, name, limits.ground);
        let mut belly = worst(Check::BellySlides, name, limits.slide);
        // A slitherer's: per vertex, where it was in the last frame and its sideways slide
        // since it came down on the ground (`None` off it).
        let mut last: Vec<Vec3> = Vec::new();
        let mut last_axes: Vec<Vec3> = Vec::new();
        let mut sideways: Vec<Option<Slide>> = Vec::new();
        // Per leg, per frame: the foot's lowest height and its centre.
        let mut soles = vec![Vec::with_capacity(times.len()); legs.len()];
        let mut centres = vec![Vec::with_capacity(times.len()); legs.len()];
        for (frame, &t) in times.iter().enumerate() {
            poser.at(clip, t);
            let p = &poser.positions;
            let (depth, at) = lowest_above(p, ground);
            below.max(-depth / length, frame, || format!("vertex {at}"));
            if slitherer {
                off.max(depth / length, frame, || format!("vertex {at}"));
                if last.is_empty() {
                    sideways = vec![None; p.len()];
                    last_axes = (0..p.len()).map(|v| poser.blended(v, &axes)).collect();
                } else {
                    belly_slides(
                        (&poser, &axes),
                        (&last, p),
                        (&mut last_axes, &mut sideways),
                        (limits.ground * length, length, &ground),
                    );
                }
                for (v, s) in sideways.iter().enumerate() {
                    if let Some((s, _)) = s {
                        belly.max(s.abs() / length, frame, || format!("vertex {v}"));
                    }
                }
                last.clear();
                last.extend_from_slice(p);
            }
            for &(a, b, rest) in &edges {
                let ratio = p[a].distance(p[b]) / rest;
                let at = || {
                    let (ja, jb) = (dominant[a], dominant[b]);
                    format!(
                        "edge {a}-{b} ({} to {})",
                        model.joint_name(ja),
                        model.joint_name(jb)
                    )
                };
                stretch.max(ratio, frame, at);
                squash.min(ratio, frame, at);
            }
            if !walker {
                continue;
            }
            let to_body = poser.joint_world(body).inverse();
            for (k, leg) in legs.iter().enumerate() {
                let (sole, centre) = leg
                    .foot
                    .iter()
                    .fold((f32::INFINITY, Vec3::ZERO), |(s, c), &v| {
                        (s.min(p[v].y - ground(p[v])), c + p[v])
                    });
                let centre = centre / leg.foot.len().max(1) as f32;
                soles[k].push(sole);
                centres[k].push(centre);
                let x = to_body.transform_point3(centre).x;
                let past = if leg.left { -x } else { x };
                cross.max(past / length, frame, || leg.name.clone());
            }
            for (a, leg_a) in legs.iter().enumerate() {
                for leg_b in &legs[a + 1..] {
                    let depth = leg_overlap(&poser, leg_a, leg_b);
                    intersect.max(depth / length, frame, || {
                        format!("{} and {}", leg_a.name, leg_b.name)
                    });
                }
            }
        }
        report
            .measures
            .extend([below.done(), stretch.done(), squash.done()]);
        if slitherer {
            report.measures.extend([off.done(), belly.done()]);
        }
        let (mut turn, mut speed) = (
            worst(Check::KeyTurn, name, limits.key_turn_degrees),
            worst(Check::AngularSpeed, name, limits.angular_speed),
        );
        for channel in &clip.channels {
            let Values::Rotation(r) = &channel.values else {
                continue;
            };
            let joint = &model.nodes[channel.node].name;
            for k in 1..r.len() {
                let angle = r[k - 1].normalize().angle_between(r[k].normalize());
                let dt = channel.times[k] - channel.times[k - 1];
                turn.max(angle.to_degrees(), k, || joint.clone());
                if dt > 0.0 {
                    speed.max(angle / dt, k, || joint.clone());
                }
            }
        }
        report.measures.extend([turn.done(), speed.done()]);
        if !walker {
            continue;
        }
        report.measures.extend([cross.done(), intersect.done()]);
        let ground = limits.ground * length;
        let mut in_air = worst(Check::FootInAir, name, limits.ground);
        let mut never = worst(Check::FootNeverDown, name, limits.ground);
        let mut slides = worst(Check::FootSlides, name, limits.slide);
        for (k, leg) in legs.iter().enumerate() {
            let (sole, centre) = (&soles[k], &centres[k]);
            let lowest = sole
                .iter()
                .copied()
                .enumerate()
                .fold(
                    (f32::INFINITY, 0),
                    |m, (f, s)| {
                        if s < m.0 { (s, f) } else { m }
                    },
                );
            never.max(lowest.0 / length, lowest.1, || leg.name.clone());
            // Each stretch on the ground: the farthest the foot gets from where it landed.
            let mut start = None;
            for f in 0..sole.len() {
                if sole[f] <= ground {
                    let s = *start.get_or_insert(f);
                    let d = horizontal(centre[f] - centre[s]);
                    slides.max(d / length, f, || leg.name.clone());
                } else {
                    start = None;
                }
            }
            // Held still in the air: `hold_frames` moves that add up to at most `slide`.
            let hold = limits.hold_frames.max(1);
            for f in hold..sole.len() {
                let window = f - hold..=f;
                let path: f32 = (f - hold + 1..=f)
                    .map(|i| centre[i].distance(centre[i - 1]))
                    .sum();
                let height = window
                    .clone()
                    .map(|i| sole[i])
                    .fold(f32::INFINITY, f32::min);
                if height > ground && path <= limits.slide * length {
                    in_air.max(height / length, f, || leg.name.clone());
                }
            }
        }
        report
            .measures
            .extend([in_air.done(), never.done(), slides.done()]);
    }
    Ok(report)
}

/// The worst value seen of one check.
struct Worst {
    check: Check,
    clip: Option<String>,
    limit: f32,
    value: Option<f32>,
    frame: usize,
    at: String,
}

impl Worst {
    fn max(&mut self, value: f32, frame: usize, at: impl FnOnce() -> String) {
        // NaN is the worst of all.
        if self.value.is_none_or(|v| value > v || value.is_nan())
            && !self.value.is_some_and(f32::is_nan)
        {
            self.set(value, frame, at);
        }
    }

    fn min(&mut self, value: f32, frame: usize, at: impl FnOnce() -> String) {
        if self.value.is_none_or(|v| value < v || value.is_nan())
            && !self.value.is_some_and(f32::is_nan)
        {
            self.set(value, frame, at);
        }
    }

    fn set(&mut self, value: f32, frame: usize, at: impl FnOnce() -> String) {
        self.value = Some(value);
        self.frame = frame;
        self.at = at();
    }

    /// The measure; with nothing seen, a value at the limit's passing side (0 for the
    /// `max` checks whose limits are positive, the limit itself otherwise).
    fn done(self) -> Measure {
        let value = self.value.unwrap_or(match self.check {
            Check::Squash | Check::Stretch => 1.0,
            Check::Tips => f32::INFINITY,
            _ => 0.0,
        });
        Measure {
            check: self.check,
            clip: self.clip,
            value,
            limit: self.limit,
            frame: self.frame,
            at: self.at,
        }
    }
}

/// Per joint, its bone's unit direction at rest (`rest` the joints' places): toward its one
/// child that is `spine_like` by name, else from its parent; zero without either.
fn bone_axes(model: &Model, rest: &[Vec3], spine_like: impl Fn(&str) -> bool) -> Vec<Vec3> {
    let parent_of = |j: usize| {
        let node = model.nodes[model.skin[j]].parent?;
        model.skin.iter().position(|&n| n == node)
    };
    let mut axes = vec![Vec3::ZERO; model.skin.len()];
    for j in 0..model.skin.len() {
        if let Some(p) = parent_of(j) {
            let from_parent = (rest[j] - rest[p]).normalize_or_zero();
            if axes[j] == Vec3::ZERO {
                axes[j] = from_parent;
            }
            if spine_like(model.joint_name(j)) && spine_like(model.joint_name(p)) {
                axes[p] = from_parent;
            }
        }
    }
    axes
}

/// A belly vertex's slide across the body since its stretch on the ground began, and how far
/// it has moved since then.
type Slide = (f32, f32);

/// One frame of the belly check: each vertex of `now` on the ground (within `ground` of it)
/// adds its move since `last` across the body there (its joints' bone `axes` skinned and
/// blended as the vertex is, by `poser`, now and in the last frame, `along`: across their
/// mean, so a move along a curve is measured against the curve's direction halfway, level)
/// to its slide in `sideways`, with how far it has moved since its slide started; a vertex
/// off the ground has none, and one that has moved a `length` starts another.
fn belly_slides(
    (poser, axes): (&Poser, &[Vec3]),
    (last, now): (&[Vec3], &[Vec3]),
    (along, sideways): (&mut [Vec3], &mut [Option<Slide>]),
    (ground, length, height): (f32, f32, &dyn Fn(Vec3) -> f32),
) {
    for (v, slide) in sideways.iter_mut().enumerate() {
        let p = now[v];
        let before = along[v];
        along[v] = poser.blended(v, axes);
        if p.y - height(p) > ground {
            *slide = None;
            continue;
        }
        let along = before.normalize_or_zero() + along[v].normalize_or_zero();
        let across = Vec3::new(-along.z, 0.0, along.x).normalize_or_zero();
        let step = p - last[v];
        let (sideways, travelled) = slide.filter(|&(_, t)| t < length).unwrap_or((0.0, 0.0));
        *slide = Some((sideways + step.dot(across), travelled + step.length()));
    }
}

/// The lowest height among `p`, and its vertex.
/// The lowest height of `p` above `ground` under it, and its index.
fn lowest_above(p: &[Vec3], ground: impl Fn(Vec3) -> f32) -> (f32, usize) {
    p.iter().enumerate().fold((f32::INFINITY, 0), |m, (i, &v)| {
        let h = v.y - ground(v);
        if h < m.0 { (h, i) } else { m }
    })
}

fn lowest(p: &[Vec3]) -> (f32, usize) {
    p.iter().enumerate().fold(
        (f32::INFINITY, 0),
        |m, (i, v)| if v.y < m.0 { (v.y, i) } else { m },
    )
}

fn horizontal(v: Vec3) -> f32 {
    Vec2::new(v.x, v.z).length()
}

/// The legs named `leg_<side><n>_hip`, `_knee`, `_foot`, with their feet's vertices and mesh
/// radii.
fn legs(model: &Model, dominant: &[usize], rest: &[Vec3]) -> Vec<Leg> {
    let mut legs = Vec::new();
    for j in 0..model.skin.len() {
        let Some(prefix) = model.joint_name(j).strip_suffix("_hip") else {
            continue;
        };
        if !prefix.starts_with("leg_") {
            continue;
        }
        let (Some(knee), Some(foot)) = (
            model.joint(&format!("{prefix}_knee")),
            model.joint(&format!("{prefix}_foot")),
        ) else {
            continue;
        };
        let joints = [j, knee, foot];
        let near = |a: usize, b: usize| -> f32 {
            // The mean distance of the segment's vertices from it.
            let (sum, n) = dominant
                .iter()
                .enumerate()
                .filter(|&(_, &d)| d == a || d == b)
                .map(|(v, _)| {
                    geometry::segment_distance(
                        model.positions[v],
                        model.positions[v],
                        rest[a],
                        rest[b],
                    )
                })
                .fold((0.0, 0usize), |(s, n), d| (s + d, n + 1));
            if n == 0 { 0.0 } else { sum / n as f32 }
        };
        legs.push(Leg {
            name: prefix.to_owned(),
            left: prefix.as_bytes().get(4) == Some(&b'l'),
            joints,
            foot: dominant
                .iter()
                .enumerate()
                .filter(|&(_, &d)| d == foot)
                .map(|(v, _)| v)
                .collect(),
            radius: [near(j, knee), near(knee, foot)],
        });
    }
    legs
}

/// Each vertex's most weighted joint (the first of equals).
fn dominant(model: &Model) -> Vec<usize> {
    model
        .joints
        .iter()
        .zip(&model.weights)
        .map(|(j, w)| {
            let k = (0..4).fold(0, |k, i| if w[i] > w[k] { i } else { k });
            usize::from(j[k])
        })
        .collect()
}

/// How deep two legs' segments overlap as capsules (≤ 0: apart).
fn leg_overlap(poser: &Poser<'_>, a: &Leg, b: &Leg) -> f32 {
    let at = |leg: &Leg| leg.joints.map(|j| poser.joint_world(j).w_axis.truncate());
    let (pa, pb) = (at(a), at(b));
    let mut depth = f32::NEG_INFINITY;
    for i in 0..2 {
        for k in 0..2 {
            let d = geometry::segment_distance(pa[i], pa[i + 1], pb[k], pb[k + 1]);
            depth = depth.max(a.radius[i] + b.radius[k] - d);
        }
    }
    depth
}

/// The mesh's edges (each once) with their rest lengths; edges shorter than 1e-6 of the body
/// length are left out.
fn edges(model: &Model, length: f32) -> Vec<(usize, usize, f32)> {
    let mut pairs: Vec<(usize, usize)> = model
        .triangles
        .iter()
        .flat_map(|t| {
            let t = t.map(|i| i as usize);
            [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]
        })
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs
        .into_iter()
        .filter_map(|(a, b)| {
            let rest = model.positions[a].distance(model.positions[b]);
            (rest > 1e-6 * length).then_some((a, b, rest))
        })
        .collect()
}
