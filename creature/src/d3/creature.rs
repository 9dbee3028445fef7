//! The 3D creature as plain data, and its clip baking and posing methods (the bakers are in
//! the `clip` module).

use alloc::string::String;
use alloc::vec::Vec;

use glam::{Affine3A, Mat4, Vec3};

use creature_autorig::Rig;
use creature_limbs::{CreatureKind, Plan};

use super::accessories::BackKind;
use super::clip::{self, Clip};
use super::wings::WingKind;
use crate::Error;

/// A skinned triangle mesh: one for the whole creature (body, head, limbs), one skin.
///
/// Right-handed, +Y up, the creature facing +Z (its left is +X), in metres, the ground at
/// `y = 0`. Triangles are counter-clockwise seen from outside.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals (per face when [`Params::flat_normals`](crate::d3::Params::flat_normals) is on).
    pub normals: Vec<Vec3>,
    /// Linear RGB vertex colours in `[0, 1]`.
    pub colours: Vec<Vec3>,
    /// Triangles as vertex indices.
    pub indices: Vec<[u32; 3]>,
    /// Up to four joints per vertex (indices into [`Skeleton::joints`]).
    pub joints: Vec<[u16; 4]>,
    /// Their weights, summing to 1; unused slots have weight 0.
    pub weights: Vec<[f32; 4]>,
}

/// What part of the creature a joint moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Part {
    /// The spine (from the auto-rigger), which also carries the head.
    Spine,
    /// A limb: the index in [`Creature::plan`]'s `limbs`.
    Limb(usize),
}

/// One joint of the skeleton, in its rest pose.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// What the joint is, unique in the skeleton (the glTF node's name). The spine, from its
    /// root toward the head: `spine_0` (the root), `spine_1`, …, then `head` (the joint that
    /// carries the head, on kinds with one) and `head_end`; from the root toward the tail:
    /// `tail_1`, …, `tail_end`. Limbs: `<limb>_<side><n>_<segment>`, where `<limb>` is `leg`,
    /// `arm`, `wing`, `fin_dorsal`, `fin_pectoral` or `fin_tail`; `<side>` is `l` (the
    /// creature's left, +X), `r` or `c` (the midline); `<n>` counts that limb type's limbs on
    /// that side from the front; and `<segment>` is `hip`, `knee`, `foot` for legs, `shoulder`,
    /// `elbow`, `hand` for arms, and `1`, `2`, … from the body out along wings and fins. For
    /// example `leg_l0_foot` is the front left foot.
    pub name: String,
    /// Rest position in model space.
    pub position: Vec3,
    /// Parent joint, `None` for the root.
    pub parent: Option<usize>,
    /// What it moves.
    pub part: Part,
}

/// The creature's skeleton: one tree; the spine joints first (the auto-rigger's order, root
/// first), then each limb's joints. Rest rotations are the identity, so a joint's rest
/// transform is a translation.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Skeleton {
    /// The joints.
    pub joints: Vec<Joint>,
}

impl Skeleton {
    /// The rest translation of each joint relative to its parent (model space for the root).
    #[must_use]
    pub fn rest_translations(&self) -> Vec<Vec3> {
        self.joints
            .iter()
            .map(|j| {
                let parent = j
                    .parent
                    .and_then(|p| self.joints.get(p))
                    .map_or(Vec3::ZERO, |p| p.position);
                j.position - parent
            })
            .collect()
    }

    /// The inverse bind matrices (glTF's): the inverse of each joint's model-space rest
    /// transform.
    #[must_use]
    pub fn inverse_bind_matrices(&self) -> Vec<Mat4> {
        self.joints
            .iter()
            .map(|j| Mat4::from_translation(-j.position))
            .collect()
    }
}

/// Measured quality of a 3D creature: tests assert on these.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Quality {
    /// For walkers, the signed horizontal distance (metres) from the mesh's centre of volume
    /// (body, head and limbs) to the edge of the convex hull of its vertices on the ground
    /// (within 0.5% of the body length of the lowest): positive means it stands; `None` for
    /// fliers and swimmers.
    pub stability_margin: Option<f32>,
    /// Smallest Jacobian determinant of the body's FFD lattice over a sample grid (above 0:
    /// the body does not fold).
    pub ffd_min_determinant: f32,
    /// Largest `|Σ weights − 1|` over the vertices.
    pub max_weight_sum_error: f32,
    /// Lowest vertex height (the ground is `y = 0`; never below it).
    pub min_height: f32,
    /// Smallest triangle area, × the square of the body length.
    pub min_triangle_area: f32,
    /// Total bend of the neck and of the tail, in degrees (0 for swimmers).
    pub bend_degrees: [f32; 2],
    /// Countershading as delivered: the mean relative luminance of the body's faces (with
    /// flat normals, where each face has one colour) or vertices facing down minus that of
    /// those facing up (more than 60° from the sideways, in the rest pose; pattern included),
    /// in `[-1, 1]`; above 0 when the belly is lighter than the back.
    pub belly_contrast: f32,
    /// Eyes on the head (a swimmer's on its body's front) that face the front or a side view
    /// in the rest pose: their outward normal more than a little forward (`+z`) or mostly to a
    /// side. Two or more on every default creature.
    pub eyes_in_view: u32,
    /// For creatures with legs, the least over its legs of its thigh's radius over its shin's,
    /// each the farthest any vertex bound to the segment's upper joint (the hip's, the knee's)
    /// is from the segment between its joints; `None` without legs. At least
    /// [`Params::thigh_thickness`](crate::d3::Params::thigh_thickness)'s least.
    pub thigh_to_shin_radius: Option<f32>,
    /// For fliers (flapping or buzzing wings), their span tip to tip (the extent across the body of
    /// the vertices bound to their joints) over the body length; `None` otherwise. At least
    /// [`Params::wing_span`](crate::d3::Params::wing_span)'s least.
    pub wing_span_to_body_length: Option<f32>,
    /// For fliers (flapping or buzzing wings), their area (both wings, one face: the triangles bound
    /// to their joints, halved) over the volume of the body and head (the triangles bound to
    /// spine joints alone) to the power 2/3; `None` otherwise. At least
    /// [`Params::wing_area`](crate::d3::Params::wing_area)'s least.
    pub wing_area_to_body_volume: Option<f32>,
    /// Spikes or plates along the back (walkers with a back row, see
    /// [`Params::back_ornament_chance`](crate::d3::Params::back_ornament_chance)), each rigid
    /// on the spine joint it stands on; 0 for a bare back.
    pub back_ornaments: u32,
    /// What a walker wears on its back (see [`Params::back_kinds`](crate::d3::Params::back_kinds));
    /// `None` for a bare back.
    pub back_kind: Option<BackKind>,
    /// For fliers with flapping wings, what they are made of (drawn by
    /// [`Params::wing_kinds`](crate::d3::Params::wing_kinds)); `None` otherwise.
    pub wing_kind: Option<WingKind>,
    /// For creatures with a head on a neck (walkers, fliers), how narrow the neck is: its
    /// width over the narrower of the head's and the body's, each across the body (`x`, as
    /// the front view shows it) in the rest pose as delivered. The body's width at a spine
    /// joint spans the skin vertices bound to it most; the body's is the widest of these short
    /// of the head, the neck's the narrowest from there to the head; the head's spans all its
    /// parts (skull, face, ornaments). Below 1, the neck is narrower than both, so head and
    /// body read as distinct; `None` for swimmers (a fish's head is its body's front).
    pub neck_to_head_and_body: Option<f32>,
}

/// A generated 3D creature: plain data.
#[derive(Debug, Clone, PartialEq)]
pub struct Creature {
    /// The kind it was generated as (a [`Kind::Random`](crate::d3::Kind::Random) resolved).
    pub kind: CreatureKind,
    /// The skinned mesh.
    pub mesh: Mesh,
    /// The skeleton: spine joints, then limb joints.
    pub skeleton: Skeleton,
    /// The spine rig (bent and grounded) whose joints are the skeleton's first joints.
    pub rig: Rig,
    /// The limb plan (in the body frame before grounding: add [`Creature::ground_offset`] to
    /// its positions).
    pub plan: Plan,
    /// How far the body frame was moved up to put the ground at `y = 0`.
    pub ground_offset: f32,
    /// The body profiles blended (indices 0–8) with their weights.
    pub profiles: Vec<(usize, f32)>,
    /// The uniform body scale drawn.
    pub body_scale: f32,
    /// Movement speed in m/s: the body scale times a random factor, for a walker at most what
    /// its legs walk (see [`Params::speed_factor`](super::Params::speed_factor)).
    pub speed: f32,
    /// Walkers' legs and arms registered for `creature-gait`; `None` for fliers and swimmers.
    pub gait: Option<crate::d3::GaitSetup>,
    /// The kind's baked clips (walkers `idle`, `walk`, `turn`, and `run`, or `hop` for a hopper;
    /// fliers `hover`, `fly`; swimmers `idle`, `swim`; slitherers `idle`, `slither`; see
    /// [`bake_clips`](Self::bake_clips)), empty when [`Params::clips`](crate::d3::Params::clips)
    /// is off.
    pub clips: Vec<crate::d3::Clip>,
    /// Body length (the spine's length), in metres.
    pub length: f32,
    /// The colours drawn: base, belly, accent and the body's pattern (the mesh's vertex
    /// colours are made from them).
    pub palette: crate::d3::Palette,
    /// Quality figures.
    pub quality: Quality,
}

impl Creature {
    /// Bakes a `walk` clip of `seconds` (at least one frame interval, at most 60 s): the
    /// walker's [`Animator`](crate::d3::Animator) driven over flat ground at `y = 0`, forward
    /// (+Z) at its [`speed`](Creature::speed), for a second's warm-up and then the clip's
    /// frames, each the animator's pose: the root's motion (with the body's bob and sway),
    /// each leg's hip translation and its hip, knee and foot rotations (the sole flat on the
    /// ground, keeping the yaw it landed with), the neck, tail and head, and the feet's
    /// contacts. It is what a game driving the animator with an
    /// [`Intent::Move`](crate::d3::Intent::Move) shows, frame for frame: a fresh animator at
    /// the origin, updated first with a time step of 0 and then every 1/30 s, the clip's
    /// frames from the 31st update on, relative to where the creature then stands and faces.
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
    /// [`Error::OutOfRange`] for `seconds` outside `[1/30, 60]` or NaN, the controller's
    /// errors as [`Error::Gait`], and for an edited creature the animator's
    /// ([`Animator::new`](crate::d3::Animator::new)).
    pub fn bake_walk(&self, seconds: f32) -> Result<Clip, Error> {
        clip::live_walk(self, seconds)
    }

    /// Bakes a looping `walk`: the walker's [`Animator`](crate::d3::Animator) is driven on
    /// flat ground as [`bake_walk`](Self::bake_walk) drives it (forward at the creature's
    /// speed, after a second's warm-up) for 4 s; its gait (the feet and the body) is cut at
    /// the frame from 1 s on that comes closest to the first (the same feet planted, the feet
    /// nearest their first places relative to the body), so the clip lasts whole strides, and
    /// the loop is closed exactly (see [`Clip::loop_error`]): the small mismatch of the body's
    /// pose is spread over the clip, and each foot's over its swings only, so a planted foot
    /// never moves. The animator, driven again, poses each frame with that closing: the clip is
    /// the live animator's frames, each moved by the closing alone (the first not at all), but
    /// for the slowing and limiting below. The
    /// root travels forward (root motion): its forward translation does not come back. If
    /// closing would stretch a planted leg beyond its reach (a nearly straight leg), a foot
    /// across the body or slide a foot that is low over the ground, the clip is only cut, and
    /// its `loop_error` says how far it is from looping.
    ///
    /// A clip whose walking legs turn a joint faster than 18 rad/s between two frames (a small
    /// or very fast walker, whose swings take three or four frames) is baked again, up to
    /// twice, with its shortest swing (`GaitOptions::min_swing_time`) longer by as much and a
    /// tenth, and the slowest kept; if that still turns faster than 20 rad/s, its legs' joints
    /// are limited to 18 rad/s wherever the foot is off the ground (in a swing, or planted
    /// where the leg cannot reach), none lowering its foot near the ground. The live animator
    /// does neither: it runs with the set-up's swings and cannot see the frames to come.
    /// `turn` is baked the same way, and `run` with up to four retries. Every looping clip of
    /// the first 10,000 walkers holds the audit of delivered creatures.
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
    /// [`Error::NoGait`] for a creature without a gait set-up (fliers and swimmers), and the
    /// controller's errors as [`Error::Gait`].
    pub fn bake_walk_loop(&self) -> Result<Clip, Error> {
        clip::walk_loop(self)
    }

    /// Bakes a looping `run`, as [`bake_walk_loop`](Self::bake_walk_loop) bakes the walk, at
    /// the set-up's [`run_speed`](crate::d3::GaitSetup::run_speed) (a Froude number of
    /// [`RUN_FROUDE`](crate::d3::RUN_FROUDE)): the gait controller changes to a run in the
    /// second of warm-up (see `creature_gait::Gait`), so the clip runs: longer swings that
    /// overlap, on two and four legs almost always a moment with no foot on the ground. A
    /// hopper ([`bake_hop_loop`](Self::bake_hop_loop)) hops at that speed instead.
    ///
    /// A run whose legs turn too fast is baked again with longer swings (up to four times) and
    /// then limited, as the walk is (a small walker's strides take five frames at 30 fps); a
    /// hopper's hop at this speed too. Every run of the
    /// first 10,000 walkers holds the audit of delivered creatures; on two and four legs, all
    /// but 3 of 9,901 have frames with every foot off the ground.
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    ///
    /// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
    /// let run = walker.bake_run_loop()?;
    /// assert!(run.duration() >= 1.0 && run.duration() <= 4.0);
    /// # Ok::<(), creature::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NoGait`] for a creature without a gait set-up (fliers and swimmers) or without
    /// legs, and the controller's errors as [`Error::Gait`].
    pub fn bake_run_loop(&self) -> Result<Clip, Error> {
        clip::run_loop(self)
    }

    /// Bakes a hopping biped's looping `hop` (see [`Params::hop_chance`](crate::d3::Params::hop_chance)):
    /// hopping straight ahead at [`GaitSetup::hop_speed`](crate::d3::GaitSetup::hop_speed)
    /// (a Froude number of [`HOP_CLIP_FROUDE`](crate::d3::HOP_CLIP_FROUDE)), both feet
    /// together, the body thrown up in each flight, the tail swinging up against the legs as
    /// they swing forward; cut and closed as [`bake_walk_loop`](Self::bake_walk_loop)'s.
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    ///
    /// let biped = generate(7, &Params::DEFAULT.with_kind(Kind::Walker).with_hop_chance(1.0))?;
    /// let hop = biped.bake_hop_loop()?;
    /// assert_eq!(hop.name, "hop");
    /// # Ok::<(), creature::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NoGait`] for a creature that does not hop (no gait set-up, or one whose
    /// options do not hop), and the controller's errors as [`Error::Gait`].
    pub fn bake_hop_loop(&self) -> Result<Clip, Error> {
        clip::hop_loop(self)
    }

    /// Bakes a walker's `idle` clip: standing still, breathing (one breath: the gait's
    /// breathing rate), arms bobbing; it loops. It is the frames of the walker's
    /// [`Animator`](crate::d3::Animator) standing on flat ground after a second's warm-up, as
    /// a game standing it there shows them.
    ///
    /// # Errors
    /// [`Error::NoGait`] for a creature without a gait set-up (fliers and swimmers), and the
    /// controller's errors as [`Error::Gait`].
    pub fn bake_idle(&self) -> Result<Clip, Error> {
        let rate = self
            .gait
            .as_ref()
            .map_or(0.25, |g| g.options.breathe_rate)
            .max(1.0 / 60.0);
        clip::gait(self, "idle", 1.0 / rate, 0.0, 0.0)
    }

    /// Bakes a walker's `turn` clip: turning in place to its left at about a quarter turn per
    /// second, slower for a long walker whose farthest foot would sweep round faster than it
    /// walks (one turn in 12 s at the slowest), one full turn, the legs stepping with the
    /// rotation and the neck and tail bent toward the turn (0.35 rad over each, shared by its
    /// bones): the walker's [`Animator`](crate::d3::Animator) turned on flat ground. It is cut,
    /// like [`bake_walk_loop`](Self::bake_walk_loop), at the frame within
    /// half a second of the full turn with the same feet planted as the first that best
    /// completes the turn; the rate is then retried
    /// (up to twice) so that the turn completes exactly at the cut, and the best try kept.
    /// Its loop is closed exactly (the root ends where it started, a full turn later, any
    /// shortfall of the turn spread over the clip, each foot's mismatch spread over its swings
    /// in the body's frame) when that keeps every planted foot still, within its leg's reach
    /// and on its own side of the body; the next best cuts of the window are tried before
    /// giving up. Otherwise the clip is the plain cut, and [`Clip::loop_error`] says how far it
    /// is from looping: plausible feet come before a seamless loop.
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    ///
    /// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
    /// let turn = walker.bake_turn()?;
    /// assert!(turn.duration() > 3.0 && turn.duration() < 12.6);
    /// # Ok::<(), creature::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NoGait`] for a creature without a gait set-up (fliers and swimmers), and the
    /// controller's errors as [`Error::Gait`].
    pub fn bake_turn(&self) -> Result<Clip, Error> {
        clip::turn(self)
    }

    /// The joints' model-space transforms at frame `frame` of `clip` (clamped to its last
    /// frame), by forward kinematics from the root: skin with
    /// `pose[j] * inverse_bind_matrices()[j]`.
    #[must_use]
    pub fn pose(&self, clip: &Clip, frame: usize) -> Vec<Affine3A> {
        clip::pose(self, clip, frame)
    }

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
        clip::skinned(self, &self.pose(clip, frame))
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

    /// The clips of the creature's kind, each looping (the turn where that keeps its feet
    /// plausible): walkers `idle`, `walk` (whole strides, see
    /// [`bake_walk_loop`](Self::bake_walk_loop)), `turn` (a full turn in place, see
    /// [`bake_turn`](Self::bake_turn)) and `run` (see [`bake_run_loop`](Self::bake_run_loop);
    /// for a hopping biped `hop` instead, see [`bake_hop_loop`](Self::bake_hop_loop), and
    /// nothing for a walker on arms alone); fliers `hover` and `fly`; swimmers `idle` and
    /// `swim`; slitherers `idle` and `slither`.
    ///
    /// Fliers' wings beat by `gait::FlapParams` (flapping wings slow, 4 bones with a lagging
    /// tip; buzzing wings at 8 beats per second, the fastest a 30 fps clip shows), the body
    /// bobs, and its legs, arms and tail are damped chains (`gait::Chain` on a legless
    /// `gait::Controller`): the legs hang under gravity, swing with the bob and trail in
    /// flight, the tail follows through; the chains run three seconds (whole periods) before
    /// the first frame, so their start-up has died away and the clip loops. Swimmers' spines wave from
    /// head to tail by `gait::SwimParams` (`idle`: the gentle sway), the tail fin following
    /// with a lag and the other fins fluttering. Slitherers are baked by their
    /// [`Animator`](crate::d3::Animator) on flat ground: `slither` crawls straight ahead at
    /// their speed for one wave, every joint of the spine on the path the head crawled;
    /// `idle` lies still, the front of the body raised and bobbing. Each looping clip lasts a
    /// whole number of its motion's periods.
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    ///
    /// for kind in [Kind::Walker, Kind::Flier, Kind::Swimmer, Kind::Slitherer] {
    ///     let c = generate(3, &Params::DEFAULT.with_kind(kind))?;
    ///     let clips = c.bake_clips()?;
    ///     assert!(clips.len() >= 2);
    ///     for clip in clips.iter().filter(|clip| clip.name != "turn") {
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
                // As `bake_idle`, `bake_walk_loop`, `bake_turn` and `bake_run_loop` (or
                // `bake_hop_loop`) bake them.
                let mut clips =
                    alloc::vec![self.bake_idle()?, clip::walk_loop(self)?, clip::turn(self)?];
                match &self.gait {
                    Some(g) if g.options.hop => clips.push(clip::hop_loop(self)?),
                    Some(g) if g.run_speed().is_some() => {
                        clips.push(clip::run_loop(self)?);
                    }
                    _ => {}
                }
                clips
            }
            CreatureKind::Flier => {
                alloc::vec![
                    clip::flight(self, "hover", 0.0)?,
                    clip::flight(self, "fly", self.speed)?
                ]
            }
            CreatureKind::Swimmer => {
                alloc::vec![
                    clip::swim(self, "idle", 0.0),
                    clip::swim(self, "swim", self.speed)
                ]
            }
            CreatureKind::Slitherer => {
                alloc::vec![
                    clip::slither(self, "idle", 0.0)?,
                    clip::slither(self, "slither", self.speed)?
                ]
            }
            _ => {
                return Err(Error::Unsupported {
                    what: "creature kind",
                });
            }
        })
    }
}
