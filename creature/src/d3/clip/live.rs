//! The live animator: a walker driven every frame by the gait controller on any ground, its
//! joints posed (two-bone legs turning about their knee hinges, feet flat on the ground, neck
//! and tail bent toward the turn), ready for a GPU; fliers and swimmers steered the same way,
//! held above the ground (submodule `fly_swim`). A walker's plain `walk`
//! ([`Creature::bake_walk`]) is its frames on flat ground (submodule `bake`).

use alloc::vec::Vec;

use glam::{Affine3A, Mat3A, Mat4, Quat, Vec2, Vec3, Vec3A, Vec4};

use creature_gait::{Controller, Gait, Ground, LegState, LimbKind, Pose, solve_two_bone_joints};
use creature_limbs::CreatureKind;

use super::floor::knee_above;
use super::kinematics::{Hinge, HingeLanes, rotation_arc};
use super::walk::{MAX_ARM_TURN_RATE, hop_tail_swing, soft_reach, turn_bend_total};
use super::{CLIP_FPS, Clip};
use crate::Error;
use crate::d3::{Creature, GaitSetup};
use crate::math::{Roots, max_f};

pub(super) mod bake;
mod fly_swim;
mod slither;

/// What a live creature is asked to do in one update of an [`Animator`].
///
/// ```
/// use creature::d3::Intent;
/// use creature::glam::Vec3;
///
/// let walk = Intent::Move { velocity: Vec3::Z * 1.5, turn_rate: 0.2 };
/// let go = Intent::GoTo(Vec3::new(10.0, 0.0, 4.0));
/// assert_ne!(walk, go);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Intent {
    /// Stand still (idle: breathing, the feet settling; a flier lands, a swimmer sways).
    Stand,
    /// Move at `velocity` (m/s, world; its vertical part is ignored: a flier or swimmer keeps
    /// its own height over the ground) while turning at
    /// `turn_rate` (rad/s about +Y, positive toward +X from +Z). A speed above twice the
    /// creature's [`speed`](Creature::speed) (a walker's
    /// [`run_speed`](crate::d3::GaitSetup::run_speed) if that is more) is lowered to that, a
    /// turn rate faster than the animator's [`max_turn_rate`](Animator::max_turn_rate) to
    /// that. A walker changes gait with its speed: it runs past a Froude number of 2.5, or, a
    /// hopper, hops past [`HOP_FROUDE`](crate::d3::HOP_FROUDE) (see
    /// [`GaitSetup::options`](crate::d3::GaitSetup::options)).
    Move {
        /// Velocity over the ground, m/s.
        velocity: Vec3,
        /// Turn rate, rad/s.
        turn_rate: f32,
    },
    /// Walk (fly, swim) to a point (world; its height is ignored): turn toward it, go at the
    /// creature's speed (slower while facing away, and slowing to a stop on arrival, within
    /// [`ARRIVAL_RADIUS`] of the body's length; a flier then hovers until told to stand).
    GoTo(Vec3),
}

/// Within this fraction of its body length of a [`Intent::GoTo`] target, a creature has arrived
/// and stands.
pub const ARRIVAL_RADIUS: f32 = 0.25;

/// A creature driven live: one [`update`](Self::update) per frame with a time step, an
/// [`Intent`] and any [`Ground`](creature_gait::Ground) (a
/// [`HeightField`](creature_gait::HeightField), a [`Plane`](creature_gait::Plane), your own
/// raycast). Each update runs the gait controller (feet placed by raycasts, steps, the body's
/// bob, sway and lean), follows the terrain under the feet with the body's height, pitch and
/// roll, turns the head to look at an [`Intent::GoTo`] target (else where the body turns), and
/// poses every joint: [`local_transforms`](Self::local_transforms) (each joint in
/// its parent's frame, the root in the world), [`world_transforms`](Self::world_transforms)
/// and [`skinning_matrices`](Self::skinning_matrices) (joint world × inverse bind, for a GPU
/// skinning shader). An update allocates nothing.
///
/// A planted foot stays as it landed: its sole keeps the yaw it landed with (it does not spin
/// on the ground as the body turns over it; its next step turns it to the body's heading) and
/// is fitted to the ground once where it stands. A ground that changes under a planted foot
/// is followed from that foot's next step, as the gait controller follows it.
///
/// Fliers and swimmers are steered by the same intents (at most a quarter turn a second) and
/// held above the ground under them:
///
/// - A flier keeps its model origin (its rest pose's ground level) three quarters of its body
///   length above the highest ground under its reach now and ahead of it (where it will be in
///   0.4 and 0.8 s), climbing faster than it sinks; every joint is kept at least as far above
///   the ground under it as its skin reaches, plus 5% of the body length. It banks into its
///   turns (its up axis tilts toward the side it turns to, up to 35° at its full turn rate and
///   speed) and, flying forward, pitches up climbing, down diving. Its wings beat as in its
///   baked `fly` clip,
///   faster and wider the faster it flies (at 0.8 of the clip's beat hovering, the clip's at its
///   speed, 1.2 times at twice it; see [`beat_frequency`](Self::beat_frequency)), and its
///   legs, arms and tail are the clip's damped chains, trailing tucked back. Told to
///   [`Stand`](Intent::Stand), it lands: it comes down onto its rest pose, leaning with the
///   plane through the ground under its skin's bottom rim (up to 30°), its lowest vertex on
///   that ground and none in it, its wings and chains settling to rest over 1.5 s; told
///   anything else, it takes off in 0.75 s, rising before it moves off.
/// - A swimmer swims at the height of its baked `swim` clip (its fins clear of the bottom)
///   plus 2% of its body length above the highest ground under and ahead of it. Its spine
///   waves as in that clip, faster the faster it swims (half the clip's rate at rest, the
///   clip's at its speed), blending into the idle sway below half its speed, and bends toward
///   its turn as a walker's tail does; each joint keeps within the clip's bend limits.
///
/// A slitherer crawls forward along its heading (at the speed of the intent's velocity along
/// it; it never crawls backward) by lateral undulation: its head crawls along a path whose
/// heading swings from side to side, every joint of its spine lies on the path the head has
/// crawled (no part of its belly slides sideways), and it steers by turning that path (its
/// tightest turn bending its joints as far again as its wave does; asked to turn faster than
/// it crawls for that, it crawls faster, up to its speed).
/// Each joint lies on the ground under it, its bone tilted with the ground's slope. Its
/// [`lead`](Self::lead), the head's place, goes to an [`Intent::GoTo`] target; its
/// [`beat_frequency`](Self::beat_frequency) is its body waves per second. Lying still, it
/// raises the front of its body.
///
/// ```
/// use creature::d3::{generate, Animator, Intent, Kind, Params};
/// use creature::gait::Plane;
/// use creature::glam::Vec3;
///
/// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker).with_clips(false))?;
/// let mut animator = Animator::new(&walker)?;
/// let target = Vec3::new(0.0, 0.0, 3.0 * walker.length);
/// for _ in 0..30 * 20 {
///     animator.update(1.0 / 30.0, Intent::GoTo(target), &Plane::GROUND)?;
/// }
/// assert!(animator.position().distance(target) < walker.length);
/// assert_eq!(animator.skinning_matrices().len(), walker.skeleton.joints.len());
///
/// // A flier crossing the same ground, above it.
/// let bird = generate(7, &Params::DEFAULT.with_kind(Kind::Flier).with_clips(false))?;
/// let mut flight = Animator::new(&bird)?;
/// for _ in 0..30 * 20 {
///     flight.update(1.0 / 30.0, Intent::GoTo(target), &Plane::GROUND)?;
/// }
/// assert!(flight.world_transforms().iter().all(|w| w.translation.y > 0.0));
/// assert!(flight.beat_frequency().is_some());
/// # Ok::<(), creature::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Animator {
    controller: Controller,
    /// What moves the body: a walker's legs, a flier's wings, a swimmer's wave, a
    /// slitherer's path.
    drive: Drive,
    /// The body's place on the ground (x, z; y the ground's height it follows) and heading.
    position: Vec3,
    heading: f32,
    /// The body's lean following the terrain (pitch, roll), smoothed.
    lean: Vec2,
    /// The turn rate of the last update (the neck and tail bend toward it), smoothed.
    turn: f32,
    speed: f32,
    /// The fastest an intent moves it: twice its speed, or a walker's run speed if more.
    top_speed: f32,
    max_turn_rate: f32,
    length: f32,
    rest_root: Vec3,
    root: usize,
    /// Joints in an order with every parent before its children, and each one's parent.
    order: Vec<usize>,
    parents: Vec<Option<usize>>,
    rest_local: Vec<Vec3>,
    rest_position: Vec<Vec3>,
    /// The neck's and tail's joints with their bend per unit of the turn's total bend, and
    /// their limit.
    bends: Vec<(usize, f32, f32)>,
    /// A hopper's joints its tail swings on (see `walk::hop_tail_swing`), and how far the
    /// tail is swung up (radians over those joints, eased toward the swing its feet ask).
    swinging: Vec<(usize, f32)>,
    tail_swing: f32,
    legs: Vec<LiveLeg>,
    /// The `head` joint, which turns to look where the body turns or at a
    /// [`Intent::GoTo`] target.
    head: Option<usize>,
    /// Per joint, the leg (index into `legs`) whose hip it is.
    leg_at: Vec<Option<usize>>,
    /// Per joint, whether its local transform turns: a walker's root, legs' joints and neck's
    /// and tail's bending joints; a flier's wings and chains; a swimmer's spine and fins; a
    /// slitherer's spine. The others only sit at their rest offset.
    turns: Vec<bool>,
    /// A walker's joints in `order`, each with its parent, its leg (if it is one's hip) and
    /// whether it turns: what its posing reads of each joint, in one place.
    plan: Vec<PlanStep>,
    /// Each leg's pose this update, made before its joints are posed.
    leg_poses: Vec<LegPose>,
    /// The legs' hinges, four legs at a time.
    hinge_lanes: Vec<HingeLanes>,
    /// The time step the smoothing shares were last computed for, and the shares (terrain,
    /// turn bend).
    smoothing: (f32, f32, f32),
    /// Half the side of the square round a walker's body (about its position) whose
    /// [height bounds](Ground::height_bounds) may settle the rays under its legs' rest
    /// positions and knees: twice as far as any of those reaches.
    under_half: f32,
    /// When to ask the ground for that square's bounds.
    asking_under: Asking,
    /// Whether the next update starts afresh (feet put under the body where it stands).
    fresh: bool,
    /// How far a walker's body (its mesh skinned to spine joints only) stands off the ground
    /// at rest (infinite for other kinds): its bob and breathing dip it no further.
    clearance: f32,
    local: Vec<Affine3A>,
    world: Vec<Affine3A>,
    skinning: Vec<Mat4>,
}

/// One joint of a walker's posing ([`Animator`]'s `plan`).
#[derive(Debug, Clone, Copy)]
struct PlanStep {
    joint: usize,
    parent: Option<usize>,
    /// The leg (index into `legs`) whose hip it is.
    leg: Option<usize>,
    turns: bool,
}

/// A leg's pose this update ([`Animator`]'s `leg_poses`), made before the joints are posed.
#[derive(Debug, Clone, Copy)]
struct LegPose {
    /// The hip's place (world), as the controller solved it.
    root: Vec3A,
    /// The segments' directions (upper, lower; body space, unit).
    segments: (Vec3, Vec3),
    /// The sole's world rotation.
    sole: Mat3A,
    /// The hip's rotation in body space.
    hip: Mat3A,
    /// The knee's rotation in the hip's frame.
    knee: Mat3A,
}

/// What moves an [`Animator`]'s body.
#[derive(Debug, Clone)]
enum Drive {
    /// A walker: the gait controller's legs (the animator's own fields).
    Walk,
    /// A flier: its wings, chains and flying height.
    Fly(alloc::boxed::Box<fly_swim::Flight>),
    /// A swimmer: its body wave and swimming height.
    Swim(alloc::boxed::Box<fly_swim::Swimming>),
    /// A slitherer: its body wave and the path it crawls along.
    Slither(alloc::boxed::Box<slither::Slithering>),
}

/// How a walker's update poses it.
#[derive(Debug, Clone, Copy)]
pub(super) enum Posing<'a> {
    /// As the controller has it (live).
    Live,
    /// Not at all: only the controller's feet and body are wanted (a baked loop's first run).
    Skip,
    /// With a baked loop's closing of the frame.
    Closed(Closing<'a>),
}

/// A baked loop's closing of one frame (see `bake::posed_loop`): the reacted body as the
/// closed loop has it, and per leg (the controller's order) how far its foot moves (world),
/// whether it is planted and how far its sole turns about +Y (radians).
#[derive(Debug, Clone, Copy)]
pub(super) struct Closing<'a> {
    pub(super) body: Pose,
    pub(super) feet: &'a [Vec3],
    pub(super) planted: &'a [bool],
    pub(super) soles: &'a [f32],
}

/// One leg's (or arm's) posing: its joints, its knee hinge and how far its knee's ring of
/// vertices reaches.
#[derive(Debug, Clone)]
struct LiveLeg {
    rest_upper: Vec3,
    rest_lower: Vec3,
    hinge: Hinge,
    knee_radius: f32,
    /// The sole's radius about the foot joint.
    foot_radius: f32,
    /// The sole's rim: the foot's farthest vertices near its bottom, at rest (level, facing
    /// +Z), in each of [`RIM`]'s directions: their horizontal offset from the joint and their
    /// height over the foot's lowest vertex.
    sole: RimLanes,
    /// The ground under the rim at the last fit ([`SoleFit::ground`]): kept here, not moved
    /// about with each fit.
    rim_ground: RimLanes,
    /// The sole's vertices at rest, as offsets from the foot joint, lowest first
    /// ([`sole_points`]).
    sole_points: Vec<Vec3A>,
    /// The farthest any of `sole_points` reaches from the foot joint horizontally.
    sole_reach: f32,
    /// The sole's yaw (world, about +Y): see [`turn_sole`](Self::turn_sole); as an angle
    /// (radians from +Z) and as a rotation.
    yaw: (f32, Quat),
    /// The yaw the foot lifted off with (radians), which a step turns from.
    lifted: f32,
    /// The sole's fit where the foot last stood planted: the foot joint's place and the yaw
    /// it was made for, the sole's normal and its lift there.
    fitted: Option<(Vec3, Quat, Vec3, f32)>,
    /// The last landing fit of a step: its target, the heading it was made for and the lift
    /// of the sole resting there.
    landing: Option<(Vec3, Quat, f32)>,
    /// The progress of the step the foot was in at the last update (none if it was in none).
    stepped: Option<f32>,
    /// The farthest any of `sole`'s offsets reaches from the joint (a little more: it bounds
    /// them turned, rounding included): the half-side of the square round the joint whose
    /// height bounds the fits ask.
    rim_reach: f32,
    /// When to ask the ground for height bounds under the sole (its swinging fit's, then its
    /// landing fit's).
    asking: [Asking; 2],
    /// The lowest of `sole`'s heights over the foot's lowest vertex.
    rim_low: f32,
    /// Their mean.
    rim_mean: f32,
    /// The last [`sole_rotation`](Self::sole_rotation): the normal and yaw it was made for,
    /// and the rotation.
    sole_turn: Option<(Vec3, Quat, Mat3A)>,
}

/// When a fit asks the ground for its [height bounds](Ground::height_bounds): every time while
/// they spare it its rays (flat ground, a foot high in a step), less and less often while they
/// do not (hills, whose bounds under a sole are rarely flat or low enough), down to one time in
/// eight. Either way the fit is the same: the bounds only skip rays whose answer they settle.
#[derive(Debug, Clone, Copy)]
struct Asking {
    /// Fits to make without asking before asking again.
    wait: u8,
    /// The wait after the next answer that spares nothing.
    backoff: u8,
}

impl Asking {
    const EVERY_TIME: Self = Self {
        wait: 0,
        backoff: 1,
    };

    /// `bounds()` if it is time to ask, else `None`; then whether they spared the fit rays
    /// (`spared(bounds)`) sets when to ask next.
    fn ask(
        &mut self,
        bounds: impl FnOnce() -> Option<(f32, f32)>,
        spared: impl FnOnce(Option<(f32, f32)>) -> bool,
    ) -> Option<(f32, f32)> {
        if self.wait > 0 {
            self.wait -= 1;
            return None;
        }
        let bounds = bounds();
        if spared(bounds) {
            self.backoff = 1;
        } else {
            self.wait = self.backoff;
            self.backoff = (2 * self.backoff).min(7);
        }
        bounds
    }
}

impl LiveLeg {
    /// The sole's yaw this frame, the body turned to `heading`: a planted foot keeps the yaw
    /// it landed with (it does not spin on the ground as the body turns over it); a stepping
    /// one turns from the yaw it lifted off with to the heading over its step (eased), and
    /// lands turned with the body (the controller plants it in the update its step ends: the
    /// last hundredth or so of the turn is taken then; a step that ends and starts again in one
    /// update turns on from there); a foot off the ground and not stepping
    /// turns toward the heading by at most `most` (radians). An arm's hand turns with the
    /// heading.
    ///
    /// `heading` is the body's yaw as an angle (radians) and as a rotation; the sole turns by
    /// angles (a turn about +Y from one yaw to another is the difference of their angles, the
    /// shorter way round), its rotation made from its angle where it turns.
    fn turn_sole(
        &mut self,
        kind: LimbKind,
        state: &LegState,
        heading: (f32, Quat),
        most: f32,
    ) -> Quat {
        if most == f32::INFINITY {
            // Afresh: the foot put down under the body.
            self.fitted = None;
            self.landing = None;
        }
        let stepped = self.stepped.take();
        if kind != LimbKind::Leg || most == f32::INFINITY {
            self.lifted = heading.0;
            self.yaw = heading;
        } else if state.planted {
            if stepped.is_some() {
                // Just landed.
                self.yaw = heading;
            }
            self.lifted = self.yaw.0;
        } else if state.stepping {
            if stepped.is_some_and(|p| state.progress < p) {
                // The last step ended (turned with the body) and this one began in one update.
                self.lifted = heading.0;
            }
            self.stepped = Some(state.progress);
            let t = state.progress.clamp(0.0, 1.0);
            let turn = wrap(heading.0 - self.lifted) * (t * t * (3.0 - 2.0 * t));
            self.yaw = yawed(self.lifted + turn);
        } else {
            let turn = wrap(heading.0 - self.yaw.0);
            self.yaw = if turn.abs() > most {
                yawed(self.yaw.0 + most.copysign(turn))
            } else {
                heading
            };
            self.lifted = self.yaw.0;
        }
        self.yaw.1
    }

    /// Whether the sole with its joint at `foot` is certainly high above ground of height
    /// `bounds` (see [`Ground::height_bounds`]), its rays `reach` long each way: every ray of
    /// its fit ([`fit_sole`]) hits, the rim's mean height over the ground is at least twice
    /// the sole's radius (a swinging foot is level there) and its lowest point's more than
    /// the radius (no lift), with a margin for the fit's rounding.
    fn high_above(&self, foot: Vec3, reach: f32, (low, high): (f32, f32)) -> bool {
        let top = foot.y + reach;
        let margin = 1e-4 * (self.foot_radius + foot.y.abs() + high.abs() + reach);
        self.foot_radius > 0.0
            && top >= high
            && top - low <= 2.0 * reach
            && foot.y + self.rim_mean - high >= 2.0 * self.foot_radius + margin
            && foot.y + self.rim_low - high >= self.foot_radius + margin
    }

    /// The sole's world rotation (a matrix): level, turned to `yaw`, tilted to the ground's
    /// `normal`; made again only when either changes (a planted foot's stay).
    fn sole_rotation(&mut self, normal: Vec3, yaw: Quat) -> Mat3A {
        match self.sole_turn {
            Some((n, y, matrix)) if n == normal && y == yaw => matrix,
            _ => {
                let matrix = Mat3A::from_quat(rotation_arc(Vec3::Y, normal) * yaw);
                self.sole_turn = Some((normal, yaw, matrix));
                matrix
            }
        }
    }

    /// [`fit`](Self::fit), made once where a foot stands planted (the ground under a planted
    /// foot is taken not to change, as the gait controller takes it).
    fn fitted_sole<G: Ground + ?Sized>(
        &mut self,
        ground: &G,
        leg: &creature_gait::Leg,
        state: &LegState,
        (heading, yaw): (Quat, Quat),
        plant: f32,
    ) -> Option<(Vec3, f32)> {
        let end = state.joints.end;
        if !state.planted {
            return self.fit(ground, leg, state, (heading, yaw), plant);
        }
        if let Some((at, turned, normal, lift)) = self.fitted
            && at == end
            && turned == yaw
        {
            return Some((normal, lift));
        }
        let fitted = self.fit(ground, leg, state, (heading, yaw), plant);
        self.fitted = fitted.map(|(normal, lift)| (end, yaw, normal, lift));
        fitted
    }

    /// The sole of leg `leg` in state `state` fitted to `ground` with the body at `heading`
    /// and the sole at `yaw`: its normal and how far it rises off the ground; `None` where a
    /// ray misses.
    fn fit<G: Ground + ?Sized>(
        &mut self,
        ground: &G,
        leg: &creature_gait::Leg,
        state: &LegState,
        (heading, yaw): (Quat, Quat),
        plant: f32,
    ) -> Option<(Vec3, f32)> {
        let solved = &state.joints;
        let flat = FLAT_SOLE * self.foot_radius;
        let end = solved.end;
        // A swinging foot certainly high above the ground under it (see `high_above`).
        let mut high = false;
        let mut asking = self.asking[0];
        let bounds = asking.ask(
            || ground.height_bounds(Vec2::new(end.x, end.z), self.rim_reach),
            |b| {
                b.is_some_and(|b| {
                    high = !state.planted && self.high_above(end, leg.size, b);
                    b.0 == b.1 || high
                })
            },
        );
        self.asking[0] = asking;
        let mut lift = 0.0;
        let normal = if high {
            // High in a step over ground the bounds settle: level (see below), and the rim
            // clear of the ground by more than the sole's radius. What the fit would give,
            // without its rays.
            Vec3::Y
        } else {
            let rim = &mut self.rim_ground;
            let fit = fit_sole(ground, solved.end, yaw, &self.sole, leg.size, bounds, rim)?;
            // A swinging foot levels off as it rises from the ground.
            let level = if state.planted {
                1.0
            } else {
                (1.0 - fit.height / (2.0 * self.foot_radius)).clamp(0.0, 1.0)
            };
            let normal = Vec3::Y.lerp(fit.normal, level).unit_or(Vec3::Y);
            // Every sole vertex tested (on the ground's plane where the ground under the rim
            // is flat, else where it is), unless the rim stands clear of the ground by more
            // than the sole's radius (a foot high in a step).
            let sole = rotation_arc(Vec3::Y, normal) * yaw;
            if fit.clearance > self.foot_radius {
            } else if let Some(plane) = fit.plane_within(flat) {
                lift = plane.plane_lift(sole, &self.sole_points, self.sole_reach);
            } else {
                lift = sole_lift(ground, solved.end, sole, &self.sole_points, leg.size);
            }
            normal
        };
        // A stepping foot comes down onto where its sole will rest at the step's target (on a
        // step's crest under a toe, not the ground under its joint), turned with the body as
        // it will land: raised by that sole's lift over the step's second half, it does not
        // skid over the crest as it lands.
        let landing = 2.0 * state.progress - 1.0;
        if leg.kind == LimbKind::Leg && state.stepping && !state.planted && landing > 0.0 {
            let target = state.step_target;
            // While the step's target still follows the body, a fit made within a sole's radius
            // of it and 2° of its heading serves (the lift of a sole resting there
            // changes by a fraction of a millimetre on hills; it anticipates the landing, and
            // the fit under the foot itself keeps the sole out of the ground); once the target
            // stays put (the step's last `plant` of progress), the fit is made for it exactly,
            // so the foot lands on the lift it will stand on.
            let following = state.progress < 1.0 - plant;
            let rest = match self.landing {
                Some((at, turned, rest))
                    if turned.dot(heading).abs() >= LANDING_TURN_COS
                        && (at == target
                            || (following
                                && (at - target).length_squared()
                                    <= self.foot_radius * self.foot_radius)) =>
                {
                    Some(rest)
                }
                _ => {
                    let reach = self.rim_reach;
                    let bounds = self.asking[1].ask(
                        || ground.height_bounds(Vec2::new(target.x, target.z), reach),
                        |b| b.is_some_and(|(low, high)| low == high),
                    );
                    let rim = &mut self.rim_ground;
                    fit_sole(ground, target, heading, &self.sole, leg.size, bounds, rim)
                }
                .map(|fit| {
                    let sole = rotation_arc(Vec3::Y, fit.normal) * heading;
                    let rest = if let Some(plane) = fit.plane_within(flat) {
                        plane.plane_lift(sole, &self.sole_points, self.sole_reach)
                    } else {
                        sole_lift(ground, target, sole, &self.sole_points, leg.size)
                    };
                    self.landing = Some((target, heading, rest));
                    rest
                }),
            };
            if let Some(rest) = rest {
                lift = lift.max(rest * landing.min(1.0));
            }
        }
        Some((normal, lift))
    }
}

impl Animator {
    /// An animator for `creature` at its rest place, facing +Z: a walker standing, a flier
    /// hovering, a swimmer at its swimming height, a slitherer lying in its wave's shape
    /// (each over flat ground at `y = 0` until the first update).
    ///
    /// # Errors
    /// [`Error::NoGait`] for a walker without a gait set-up (or a kind this version does not
    /// animate); [`Error::Gait`] if the gait controller rejects its set-up (an edited
    /// creature); [`Error::BadParent`] for a skeleton whose parents form a cycle, a leg whose
    /// hip, knee and foot joints are not a chain or a slitherer's spine that is not one;
    /// [`Error::Degenerate`] for a gait set-up whose `hip_joints` and `legs` differ in length
    /// or a slitherer with fewer than two spine joints.
    pub fn new(creature: &Creature) -> Result<Self, Error> {
        match (&creature.gait, creature.kind) {
            (Some(setup), _) => Self::walker(creature, setup),
            (None, CreatureKind::Flier) => Self::flier(creature),
            (None, CreatureKind::Swimmer) => Self::swimmer(creature),
            (None, CreatureKind::Slitherer) => Self::slitherer(creature),
            (None, _) => Err(Error::NoGait),
        }
    }

    /// What every kind's animator shares: the skeleton's order and rest pose, driven by
    /// `drive` through `controller`; no legs, no head turning, nothing bending to a turn.
    fn bare(
        creature: &Creature,
        controller: Controller,
        max_turn_rate: f32,
        drive: Drive,
    ) -> Result<Self, Error> {
        let joints = &creature.skeleton.joints;
        let n = joints.len();
        let parents: Vec<Option<usize>> = joints.iter().map(|j| j.parent).collect();
        let order = parents_first(&parents)?;
        let root = order.first().copied().unwrap_or(0);
        let rest_local = creature.skeleton.rest_translations();
        let local: Vec<Affine3A> = rest_local
            .iter()
            .map(|&t| Affine3A::from_translation(t))
            .collect();
        Ok(Self {
            controller,
            drive,
            position: Vec3::ZERO,
            heading: 0.0,
            lean: Vec2::ZERO,
            turn: 0.0,
            speed: creature.speed,
            top_speed: (2.0 * creature.speed).max(
                creature
                    .gait
                    .as_ref()
                    .and_then(|g| g.run_speed())
                    .unwrap_or(0.0),
            ),
            max_turn_rate,
            length: creature.length,
            rest_root: creature.rest_root(),
            root,
            order,
            parents,
            rest_local,
            rest_position: joints.iter().map(|j| j.position).collect(),
            bends: Vec::new(),
            swinging: Vec::new(),
            tail_swing: 0.0,
            legs: Vec::new(),
            head: None,
            leg_at: alloc::vec![None; n],
            turns: alloc::vec![false; n],
            plan: Vec::new(),
            leg_poses: Vec::new(),
            hinge_lanes: Vec::new(),
            smoothing: (0.0, 0.0, 0.0),
            under_half: 0.0,
            asking_under: Asking::EVERY_TIME,
            fresh: true,
            clearance: f32::INFINITY,
            world: local.clone(),
            local,
            skinning: alloc::vec![Mat4::IDENTITY; n],
        })
    }

    /// A walker's animator: its legs driven by the gait controller.
    fn walker(creature: &Creature, setup: &GaitSetup) -> Result<Self, Error> {
        let mut controller = setup.controller()?;
        let joints = &creature.skeleton.joints;
        let head = joints.iter().position(|j| j.name == "head");
        if let Some(head) = head {
            controller.set_head(joints[head].position)?;
        }
        let mut animator = Self::bare(
            creature,
            controller,
            creature.turn_rate(&setup.legs),
            Drive::Walk,
        )?;
        let n = joints.len();
        // How high the body (the mesh skinned to spine joints only) is off the ground at rest.
        let spine = |j: u16| {
            joints
                .get(usize::from(j))
                .is_some_and(|j| j.part == crate::d3::Part::Spine)
        };
        let mesh = &creature.mesh;
        animator.clearance = mesh
            .positions
            .iter()
            .zip(mesh.joints.iter().zip(&mesh.weights))
            .filter(|(_, (js, ws))| {
                js.iter()
                    .zip(ws.iter())
                    .all(|(&j, &w)| w == 0.0 || spine(j))
            })
            .map(|(p, _)| p.y)
            .fold(f32::INFINITY, f32::min);
        let parents = &animator.parents;
        let rest = |j: usize| joints.get(j).map_or(Vec3::ZERO, |j| j.position);
        if setup.hip_joints.len() != setup.legs.len() {
            return Err(Error::Degenerate {
                what: "gait set-up (its hip_joints and legs differ in length)",
            });
        }
        for (i, &hip) in setup.hip_joints.iter().enumerate() {
            // A leg's chain is its hip, knee and foot, one after the other.
            let chain =
                hip + 2 < n && parents[hip + 1] == Some(hip) && parents[hip + 2] == Some(hip + 1);
            if !chain {
                return Err(Error::BadParent {
                    bone: hip + 1,
                    parent: parents.get(hip + 1).copied().flatten(),
                });
            }
            animator.leg_at[hip] = Some(i);
        }
        animator.head = head;
        // The farthest a leg's rest position or knee (and a leg's size above it, where its
        // ray starts) is from the body's origin horizontally, doubled.
        animator.under_half = 2.0
            * setup
                .legs
                .iter()
                .map(|leg| {
                    let rest = Vec2::new(leg.rest.x, leg.rest.z).norm();
                    let hip = Vec2::new(leg.hip.x, leg.hip.z).norm();
                    rest.max(hip + leg.upper) + leg.size
                })
                .fold(0.0, f32::max);
        animator.bends = creature.turn_bend_shares();
        if setup.options.hop {
            // (Each a joint of the tail's turn bend too: it turns already.)
            animator.swinging = creature.swinging_tail();
        }
        let turns = &mut animator.turns;
        if let Some(head) = head {
            turns[head] = true;
        }
        for &(j, _, _) in &animator.bends {
            turns[j] = true;
        }
        for &hip in &setup.hip_joints {
            turns[hip..hip + 3].fill(true);
        }
        animator.plan = animator
            .order
            .iter()
            .map(|&joint| PlanStep {
                joint,
                parent: animator.parents[joint],
                leg: animator.leg_at[joint],
                turns: animator.turns[joint],
            })
            .collect();
        animator.legs = setup
            .legs
            .iter()
            .zip(&setup.hip_joints)
            .map(|(leg, &hip)| {
                let rest_upper = (rest(hip + 1) - rest(hip)).unit_or(Vec3::NEG_Y);
                let rest_lower = (rest(hip + 2) - rest(hip + 1)).unit_or(Vec3::NEG_Y);
                let sole = sole_points(creature, hip + 2);
                let rim = sole_rim(&sole);
                LiveLeg {
                    rim_reach: rim.iter().map(|d| d.norm()).fold(0.0, f32::max) * (1.0 + 1e-5),
                    asking: [Asking::EVERY_TIME; 2],
                    rim_low: rim.iter().map(|d| d.y).fold(f32::INFINITY, f32::min),
                    rim_mean: rim.iter().map(|d| d.y).sum::<f32>() / RIM_SAMPLES as f32,
                    rest_upper,
                    rest_lower,
                    hinge: Hinge::new((rest_upper, rest_lower), leg.pole),
                    knee_radius: creature.ring_radius(hip + 1),
                    foot_radius: creature.ring_radius(hip + 2),
                    sole: RimLanes::new(&rim),
                    rim_ground: RimLanes::ZERO,
                    sole_reach: sole
                        .iter()
                        .map(|p| Vec3A::new(p.x, 0.0, p.z).norm())
                        .fold(0.0, f32::max),
                    sole_points: sole,
                    yaw: (0.0, Quat::IDENTITY),
                    lifted: 0.0,
                    fitted: None,
                    landing: None,
                    sole_turn: None,
                    stepped: None,
                }
            })
            .collect();
        animator.leg_poses = alloc::vec![
            LegPose {
                root: Vec3A::ZERO,
                segments: (Vec3::NEG_Y, Vec3::NEG_Y),
                sole: Mat3A::IDENTITY,
                hip: Mat3A::IDENTITY,
                knee: Mat3A::IDENTITY,
            };
            setup.legs.len()
        ];
        let hinges: Vec<Hinge> = animator.legs.iter().map(|l| l.hinge).collect();
        animator.hinge_lanes = hinges.chunks(4).map(HingeLanes::new).collect();
        animator.pose_joints(
            &Pose::IDENTITY,
            (0.0, Quat::IDENTITY),
            None::<(&creature_gait::Plane, _)>,
            f32::INFINITY,
            None,
        );
        Ok(animator)
    }

    /// Places the creature at `position` (its height is taken from the ground at the next
    /// update: the nearest ground below it, however far; put under the ground, the ground
    /// over it) facing `heading` (radians about +Y from +Z), its feet under it.
    #[must_use]
    pub fn with_pose(mut self, position: Vec3, heading: f32) -> Self {
        self.position = position;
        self.heading = heading;
        self.fresh = true;
        self
    }

    /// One frame: `dt` seconds (0 poses without moving; above [`MAX_STEP`] seconds, a frame
    /// hitch, it is taken as `MAX_STEP` so the feet do not jump), the creature's `intent`, on
    /// `ground`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite `dt` or intent, [`Error::OutOfRange`] for a
    /// negative `dt`; the pose is unchanged then. [`Error::Gait`] if the controller rejects a
    /// walker's position beyond its range (`creature_gait::MAX_COORDINATE`).
    pub fn update<G: Ground + ?Sized>(
        &mut self,
        dt: f32,
        intent: Intent,
        ground: &G,
    ) -> Result<(), Error> {
        let dt = time_step(dt)?;
        let (velocity, turn_rate) = self.wanted(intent)?;
        // The drive is taken out while it moves the body (a `Box` moved: no allocation) and put
        // back whatever happens.
        match core::mem::replace(&mut self.drive, Drive::Walk) {
            Drive::Walk => self.walk(dt, intent, (velocity, turn_rate), ground),
            Drive::Fly(mut flight) => {
                let stand = matches!(intent, Intent::Stand);
                let done = self.fly(&mut flight, dt, (velocity, turn_rate, stand), ground);
                self.drive = Drive::Fly(flight);
                done
            }
            Drive::Swim(mut swimming) => {
                let done = self.swim(&mut swimming, dt, (velocity, turn_rate), ground);
                self.drive = Drive::Swim(swimming);
                done
            }
            Drive::Slither(mut slithering) => {
                let done = self.slither(&mut slithering, dt, (velocity, turn_rate), &ground);
                self.drive = Drive::Slither(slithering);
                done
            }
        }
    }

    /// A walker's update (see [`update`](Self::update)): `dt` already checked and capped,
    /// the velocity and turn rate its intent asks.
    fn walk<G: Ground + ?Sized>(
        &mut self,
        dt: f32,
        intent: Intent,
        motion: (Vec3, f32),
        ground: &G,
    ) -> Result<(), Error> {
        self.walk_posed(dt, intent, motion, ground, Posing::Live)
    }

    /// [`walk`](Self::walk), posed as `posing` says.
    pub(super) fn walk_posed<G: Ground + ?Sized>(
        &mut self,
        dt: f32,
        intent: Intent,
        (velocity, turn_rate): (Vec3, f32),
        ground: &G,
        posing: Posing<'_>,
    ) -> Result<(), Error> {
        let heading = wrap(self.heading + turn_rate * dt);
        let mut position = self.position + velocity * dt;
        // The body follows the ground under its rest feet: height, pitch and roll; afresh, it
        // is put straight onto the ground where it stands.
        let yaw = Quat::from_rotation_y(heading);
        let reach = self.length;
        let flat = self.flat_under(position, ground);
        let (mut height, mut slope) =
            self.ground_under(position, yaw, ground, (reach, reach), flat);
        if self.fresh && height.is_none() {
            let cast = |origin, range| match self.ground_under(origin, yaw, ground, range, None) {
                (Some(height), slope) => Some((height, slope)),
                (None, _) => None,
            };
            if let Some((top, lean)) = put_down(position, (reach, reach), |&(top, _)| top, cast) {
                (height, slope) = (Some(top), lean);
            }
        }
        let k = if self.fresh {
            1.0
        } else {
            self.smoothing(dt).0
        };
        if let Some(height) = height {
            position.y += (height - position.y) * k;
        }
        let lean = self.lean + (slope - self.lean) * k;
        let rotation = (yaw * Quat::from_rotation_x(lean.x) * Quat::from_rotation_z(lean.y)).unit();
        let pose = Pose::new(position, rotation);
        if self.fresh {
            self.controller.reset(pose, ground)?;
        }
        // The head looks at a target to go to (at the height of its head), else where the body
        // turns.
        let look = match intent {
            // Until it is within a body length: a target beside or behind the head as the
            // body arrives would wrench it round.
            Intent::GoTo(target)
                if Vec2::new(target.x - position.x, target.z - position.z).norm() > self.length =>
            {
                Some(Vec3::new(
                    target.x,
                    position.y
                        + self
                            .rest_position
                            .get(self.head.unwrap_or(0))
                            .map_or(0.0, |p| p.y),
                    target.z,
                ))
            }
            _ => None,
        };
        self.controller.set_look_target(look)?;
        if matches!(posing, Posing::Skip) {
            // Only the feet and the body are wanted: no pose.
            self.controller.update_feet_and_body(
                dt,
                pose,
                velocity,
                Vec3::Y * turn_rate,
                ground,
            )?;
            self.fresh = false;
            (self.position, self.heading, self.lean) = (position, heading, lean);
            self.turn += (turn_rate - self.turn) * self.smoothing(dt).1;
            return Ok(());
        }
        self.controller
            .update(dt, pose, velocity, Vec3::Y * turn_rate, ground)?;
        // Arms hang free, damped: no joint of theirs turns faster than the baked clips' do
        // (the two-bone solution flips an elbow as the hand passes its pole).
        let arm_turn = if self.fresh {
            f32::INFINITY
        } else {
            MAX_ARM_TURN_RATE * dt
        };
        let reacted = self.controller.reacted_pose();
        let closing = match posing {
            Posing::Closed(closing) => Some(closing),
            _ => None,
        };
        let mut body = closing.map_or(reacted, |c| c.body);
        // The body's bob and breathing dip it no further than it stands off the ground at
        // rest: a body resting on the ground is not pushed into it (a 35 cm walker's belly
        // went 0.45 mm under the floor as it breathed).
        let floor = position.y - self.clearance;
        if body.translation.y < floor {
            body.translation.y = floor;
        }
        if !self.swinging.is_empty() {
            // A hopper's tail swings against its legs while it hops, and eases back to rest
            // when it walks.
            let swing = if self.controller.gait() == Gait::Hop {
                let unturn = body.rotation.inverse();
                let feet = self.controller.leg_states().iter().enumerate();
                let feet = feet.map(|(i, s)| {
                    let moved = closing.map_or(Vec3::ZERO, |c| c.feet[i]);
                    unturn * (s.joints.end + moved - body.translation)
                });
                hop_tail_swing(self.controller.legs(), feet)
            } else {
                0.0
            };
            let k = if self.fresh {
                1.0
            } else if swing == 0.0 && self.tail_swing == 0.0 {
                // At rest and staying there (walking): nothing to ease.
                0.0
            } else {
                smoothing(dt, TAIL_SWING_TIME)
            };
            self.tail_swing += (swing - self.tail_swing) * k;
            if self.tail_swing < 1e-6 {
                // At rest (and no subnormal tail of the easing).
                self.tail_swing = 0.0;
            }
        }
        self.fresh = false;
        (self.position, self.heading, self.lean) = (position, heading, lean);
        self.turn += (turn_rate - self.turn) * self.smoothing(dt).1;
        self.pose_joints(
            &body,
            (heading, yaw),
            Some((ground, flat)),
            arm_turn,
            closing.map(|c| (reacted, c)),
        );
        Ok(())
    }

    /// The shares of the way the terrain's follower and the turn's bend go in `dt` (see
    /// [`smoothing`]), computed again only when `dt` changes.
    fn smoothing(&mut self, dt: f32) -> (f32, f32) {
        if dt != self.smoothing.0 {
            self.smoothing = (
                dt,
                smoothing(dt, TERRAIN_TIME),
                smoothing(dt, TURN_BEND_TIME),
            );
        }
        (self.smoothing.1, self.smoothing.2)
    }

    /// The velocity (horizontal) and turn rate `intent` asks for, within the creature's limits.
    fn wanted(&self, intent: Intent) -> Result<(Vec3, f32), Error> {
        let top = self.top_speed;
        Ok(match intent {
            Intent::Stand => (Vec3::ZERO, 0.0),
            Intent::Move {
                velocity,
                turn_rate,
            } => {
                if !velocity.is_finite() {
                    return Err(Error::NonFinite {
                        what: "intent velocity",
                    });
                }
                if !turn_rate.is_finite() {
                    return Err(Error::NonFinite {
                        what: "intent turn rate",
                    });
                }
                let level = Vec3::new(velocity.x, 0.0, velocity.z).clamp_length_max(top);
                let turn = turn_rate.clamp(-self.max_turn_rate, self.max_turn_rate);
                (level, turn)
            }
            Intent::GoTo(target) => {
                if !target.is_finite() {
                    return Err(Error::NonFinite {
                        what: "intent target",
                    });
                }
                let lead = self.lead();
                let to = Vec2::new(target.x - lead.x, target.z - lead.z);
                let distance = to.norm();
                if distance <= ARRIVAL_RADIUS * self.length {
                    return Ok((Vec3::ZERO, 0.0));
                }
                // Off by `error` from facing the target: turn toward it, walking forward
                // only as much as it faces it, slowing down over the last body length.
                let error = wrap(Vec2::new(to.y, to.x).to_angle() - self.heading);
                let turn = (TURN_GAIN * error).clamp(-self.max_turn_rate, self.max_turn_rate);
                let facing = crate::math::cos(error).max(0.0);
                let arriving = (distance / self.length).min(1.0);
                let forward = Vec3::new(
                    crate::math::sin(self.heading),
                    0.0,
                    crate::math::cos(self.heading),
                );
                (forward * (self.speed * facing * arriving), turn)
            }
        })
    }

    /// The ground under a walker's body at `position` where its
    /// [height bounds](Ground::height_bounds) say it is flat (asked as [`Asking`] says).
    fn flat_under<G: Ground + ?Sized>(&mut self, position: Vec3, ground: &G) -> Option<FlatUnder> {
        let centre = Vec2::new(position.x, position.z);
        let half = self.under_half;
        let bounds = self.asking_under.ask(
            || ground.height_bounds(centre, half),
            |b| b.is_some_and(|(low, high)| low == high),
        );
        match bounds {
            Some((low, high)) if low == high => Some(FlatUnder {
                centre,
                half: 0.5 * half,
                height: low,
            }),
            _ => None,
        }
    }

    /// The mean height of the ground under the legs' rest positions with the body at `origin`
    /// turned by `yaw` (none if no ray hits), and
    /// the slopes of those heights along the body's forward and left axes, as a pitch and a
    /// roll (radians, each within [`MAX_LEAN`]); the rays are cast from `above` the body to
    /// `below` it (and a leg's size further): its length each, or [`FRESH_RANGE`] to put it
    /// down afresh. Where the ground is `flat` under the body, no ray is cast.
    fn ground_under<G: Ground + ?Sized>(
        &self,
        origin: Vec3,
        yaw: Quat,
        ground: &G,
        (above, below): (f32, f32),
        flat: Option<FlatUnder>,
    ) -> (Option<f32>, Vec2) {
        // Least-squares slopes of the heights along x and z: sums of e, x, z, x², z², ex, ez.
        let mut count = 0.0f32;
        let (mut e, mut x, mut z) = (0.0f32, 0.0f32, 0.0f32);
        let (mut xx, mut zz, mut ex, mut ez) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
        for leg in self.controller.legs() {
            if leg.kind != LimbKind::Leg {
                continue;
            }
            let rest = Vec3::new(leg.rest.x, 0.0, leg.rest.z);
            let from = origin + yaw * rest + Vec3::Y * above;
            let range = above + below + leg.size;
            let hit = match flat.and_then(|f| f.hit(from, range)) {
                Some(height) => Some(height),
                None => ground.cast_down_point(from, range).map(|hit| hit.y),
            };
            if let Some(hit) = hit {
                let h = hit - origin.y;
                count += 1.0;
                (e, x, z) = (e + h, x + rest.x, z + rest.z);
                (xx, zz) = (xx + rest.x * rest.x, zz + rest.z * rest.z);
                (ex, ez) = (ex + h * rest.x, ez + h * rest.z);
            }
        }
        if count == 0.0 {
            return (None, Vec2::ZERO);
        }
        let slope = |num: f32, den: f32| {
            if den > 1e-9 * self.length * self.length * count * count {
                Vec2::new(den, num).to_angle().clamp(-MAX_LEAN, MAX_LEAN)
            } else {
                0.0
            }
        };
        let pitch = -slope(count * ez - e * z, count * zz - z * z);
        let roll = slope(count * ex - e * x, count * xx - x * x);
        (Some(origin.y + e / count), Vec2::new(pitch, roll))
    }

    /// Every joint's local, world and skinning transform for the body at `body` (the reacted
    /// pose) with its legs as the controller solved them, their knees above `ground` (none:
    /// nothing to keep them above), their feet level with `heading` and tilted to the ground
    /// under them.
    ///
    /// With `closing` (the controller's reacted body and a baked loop's closing of this frame,
    /// `body` the closed body), each leg's hip stays where it is on the body, and its foot is
    /// moved by the closing and planted as it says.
    fn pose_joints<G: Ground + ?Sized>(
        &mut self,
        body: &Pose,
        (heading_angle, heading): (f32, Quat),
        ground: Option<(&G, Option<FlatUnder>)>,
        arm_turn: f32,
        closing: Option<(Pose, Closing<'_>)>,
    ) {
        // Neck and tail bent toward the turn, as the baked clips bend them; the neck turned on
        // toward the look, its rest shared among the neck's joints, none past what its skin
        // allows (a head turned alone on its joint tore the neck's skin).
        let total = turn_bend_total(self.turn);
        let neck = self.bends.iter().filter(|b| b.1 > 0.0).count();
        let look = match self.head {
            Some(head) if neck > 0 && self.bends.iter().any(|b| b.0 == head) => {
                Quat::from_rotation_y(total).inverse() * self.controller.look().rotation
            }
            _ => Quat::IDENTITY,
        };
        let look_share = Quat::IDENTITY.slerp(look, 1.0 / neck.max(1) as f32);
        let swing = self.tail_swing / self.swinging.len().max(1) as f32;
        // The neck's joints share one bend, the tail's another (each listed together): each
        // turned and measured once.
        let mut shared: Option<(f32, Quat, f32)> = None;
        // The last bend's turn and its matrix: a joint turned as the one before it (a neck's
        // or tail's joints within their limits) takes the matrix as it is.
        let mut last: Option<(Quat, Mat3A)> = None;
        for &(joint, divisor, limit) in &self.bends {
            let (turn, angle) = match shared {
                Some((of, turn, angle)) if of == divisor => (turn, angle),
                _ => {
                    let bend = Quat::from_rotation_y(total / divisor);
                    let turn = if divisor > 0.0 {
                        (bend * look_share).unit()
                    } else {
                        bend
                    };
                    let angle = turn.angle_between(Quat::IDENTITY);
                    shared = Some((divisor, turn, angle));
                    (turn, angle)
                }
            };
            let mut turn = if angle > limit {
                Quat::IDENTITY.slerp(turn, limit / angle).unit()
            } else {
                turn
            };
            if swing != 0.0
                && let Some(&(_, most)) = self.swinging.iter().find(|s| s.0 == joint)
            {
                turn = (turn * Quat::from_rotation_x(swing.min(most))).unit();
            }
            let matrix3 = match last {
                Some((of, matrix3)) if of == turn => matrix3,
                _ => Mat3A::from_quat(turn),
            };
            last = Some((turn, matrix3));
            self.local[joint] = Affine3A {
                matrix3,
                translation: self.rest_local[joint].into(),
            };
        }
        self.local[self.root] = Affine3A::from_rotation_translation(
            body.rotation,
            body.translation + body.rotation * self.rest_root,
        );
        let body_turn = self.local[self.root].matrix3;
        let unturn = body.rotation.inverse();
        let up = unturn * Vec3::Y;
        // The body's rotation and its inverse as matrices (for the legs' points).
        let body_unturn = body_turn.transpose();
        let states = self.controller.leg_states();
        let setup = self.controller.legs();
        let plant = self.controller.options().plant_fraction;
        // The head, where it turns alone to the look (no neck shares it).
        let head_alone = self.head.filter(|_| look == Quat::IDENTITY);
        // Each leg's chain first (its sole fitted to the ground, its knee solved and kept
        // above it), then its hip's and knee's rotations, then the joints in order.
        for i in 0..setup.len() {
            // A leg's chain solved from the hip to the foot in body space.
            let leg = &setup[i];
            // A closed loop's leg: its hip where it is on the body, its foot moved and
            // planted as the closing has it, its knee solved again.
            let closed;
            let state = match &closing {
                Some((reacted, closing)) => {
                    let mut s = states[i];
                    let root = reacted.inverse_transform_point(s.joints.root);
                    s.joints.root = body.transform_point(root);
                    s.joints.end += closing.feet[i];
                    s.foot += closing.feet[i];
                    s.planted = closing.planted[i];
                    let end = unturn * (s.joints.end - body.translation);
                    let [_, middle, _] =
                        solve_two_bone_joints(root, end, leg.upper, leg.lower, leg.pole);
                    s.joints.middle = body.transform_point(middle);
                    closed = s;
                    &closed
                }
                None => &states[i],
            };
            let mut yaw =
                self.legs[i].turn_sole(leg.kind, state, (heading_angle, heading), arm_turn);
            if let Some((_, closing)) = &closing {
                yaw = (Quat::from_rotation_y(closing.soles[i]) * yaw).unit();
            }
            // The controller's two-bone solution (world, the knee toward the pole), in
            // body space.
            let solved = &state.joints;
            let to_body = |p: Vec3| Vec3::from(body_unturn * Vec3A::from(p - body.translation));
            let (root, mut end) = (to_body(solved.root), to_body(solved.end));
            let mut middle = to_body(solved.middle);
            // The sole fitted to the ground across its width, and raised off it where an
            // edge would be in it (a step's edge under a foot): a planted foot's fit is
            // made once where it stands (the ground under a planted foot is taken not to
            // change, as the controller takes it).
            let mut normal = state.normal;
            // Whether the foot moved off the solution (its knee solved again, once).
            let mut moved = false;
            if let Some((g, _)) = ground {
                let fitted = self.legs[i].fitted_sole(g, leg, state, (heading, yaw), plant);
                if let Some((fit, lift)) = fitted {
                    normal = fit;
                    if lift > 0.0 {
                        end = to_body(solved.end + Vec3::Y * lift);
                        moved = true;
                    }
                }
            }
            // The sole flat on the ground: level, turned to its yaw, tilted to the ground's
            // normal.
            let sole_turn = self.legs[i].sole_rotation(normal, yaw);
            let live = &self.legs[i];
            // A foot in the air short of a straight leg, as the baked clips hold it.
            if !state.planted {
                let soft = soft_reach(root, end, leg.upper + leg.lower, up);
                if soft != end {
                    end = soft;
                    moved = true;
                }
            }
            if moved {
                [_, middle, _] = solve_two_bone_joints(root, end, leg.upper, leg.lower, leg.pole);
            }
            let floor = ground.map_or(f32::NEG_INFINITY, |(g, flat)| {
                let knee = Vec3::from(body_turn * Vec3A::from(middle)) + body.translation;
                let above = Vec3::new(knee.x, knee.y + leg.size, knee.z);
                let range = 2.0 * leg.size;
                match flat.and_then(|f| f.hit(above, range)) {
                    Some(height) => Some(height),
                    None => g.cast_down_point(above, range).map(|hit| hit.y),
                }
                .map_or(f32::NEG_INFINITY, |hit| {
                    hit + live.knee_radius - body.translation.y
                })
            });
            let middle = knee_above(root, middle, end, up, floor);
            self.leg_poses[i] = LegPose {
                root: solved.root.into(),
                segments: (
                    (middle - root).unit_or(live.rest_upper),
                    (end - middle).unit_or(live.rest_lower),
                ),
                sole: sole_turn,
                hip: Mat3A::IDENTITY,
                knee: Mat3A::IDENTITY,
            };
        }
        // The hips' and knees' rotations, four legs at a time.
        for (lanes, poses) in self.hinge_lanes.iter().zip(self.leg_poses.chunks_mut(4)) {
            // The group's last leg again in the lanes past it (a chunk is never empty).
            let last = poses.len() - 1;
            let now = core::array::from_fn(|l| poses[l.min(last)].segments);
            for (pose, (hip, knee)) in poses.iter_mut().zip(lanes.matrices(now)) {
                (pose.hip, pose.knee) = (hip, knee);
            }
        }
        // (Taken out while the joints are posed, and put back: no allocation.)
        let plan = core::mem::take(&mut self.plan);
        for &PlanStep {
            joint: j,
            parent,
            leg,
            turns,
        } in &plan
        {
            // The parent's world transform is read where it is needed (a copy of it for
            // every joint cost more than a fifth of the posing's own arithmetic).
            // A leg's hip's world transform where its solution gives it.
            let mut solved_world = None;
            if let Some(i) = leg {
                let leg = &setup[i];
                let LegPose {
                    root,
                    sole,
                    hip,
                    knee,
                    ..
                } = self.leg_poses[i];
                let (knee_joint, foot_joint) = (j + 1, j + 2);
                // The hip's world transform as solved; the knee's and the foot's as matrices
                // (the foot turned in the world as its sole).
                let hip_world = Affine3A {
                    matrix3: body_turn * hip,
                    translation: root,
                };
                let foot = (hip_world.matrix3 * knee).transpose() * sole;
                if leg.kind == LimbKind::Arm && arm_turn != f32::INFINITY {
                    // An arm's joints turned from their last pose no more than `arm_turn`.
                    let damped = |old: &Affine3A, new: &Mat3A| {
                        let new = crate::math::quat_from_mat3a(new).unit();
                        let old = crate::math::quat_from_mat3a(&old.matrix3).unit();
                        let angle = old.angle_between(new);
                        if angle > arm_turn {
                            old.slerp(new, arm_turn / angle).unit()
                        } else {
                            new
                        }
                    };
                    let hip_local =
                        parent.map_or(hip_world, |p| self.world[p].inverse() * hip_world);
                    self.local[j] = Affine3A::from_rotation_translation(
                        damped(&self.local[j], &hip_local.matrix3),
                        hip_local.translation.into(),
                    );
                    self.local[knee_joint] = Affine3A::from_rotation_translation(
                        damped(&self.local[knee_joint], &knee),
                        self.rest_local[knee_joint],
                    );
                    self.local[foot_joint] = Affine3A::from_rotation_translation(
                        damped(&self.local[foot_joint], &foot),
                        self.rest_local[foot_joint],
                    );
                } else {
                    // The hip's local transform that in its parent's frame (a rotation's
                    // inverse is its transpose).
                    self.local[j] = parent.map_or(hip_world, |p| {
                        let p = &self.world[p];
                        let unturn = p.matrix3.transpose();
                        Affine3A {
                            matrix3: unturn * hip_world.matrix3,
                            translation: unturn * (hip_world.translation - p.translation),
                        }
                    });
                    solved_world = Some(hip_world);
                    self.local[knee_joint] = Affine3A {
                        matrix3: knee,
                        translation: self.rest_local[knee_joint].into(),
                    };
                    self.local[foot_joint] = Affine3A {
                        matrix3: foot,
                        translation: self.rest_local[foot_joint].into(),
                    };
                }
            }
            if Some(j) == head_alone {
                // No neck to share it: the look, a rotation in body space, as the head's world
                // rotation.
                let look = body.rotation * self.controller.look().rotation;
                let turn = parent.map_or(look, |p| {
                    crate::math::quat_from_mat3a(&self.world[p].matrix3).inverse() * look
                });
                self.local[j] =
                    Affine3A::from_rotation_translation(turn.unit(), self.rest_local[j]);
            }
            if let Some(world) = solved_world {
                self.world[j] = world;
                continue;
            }
            let local = &self.local[j];
            self.world[j] = match parent {
                // Most joints only sit at their rest offset: a translation within the parent.
                Some(p) if turns => self.world[p] * *local,
                Some(p) => {
                    let p = &self.world[p];
                    Affine3A {
                        matrix3: p.matrix3,
                        translation: p.transform_point3a(local.translation),
                    }
                }
                None => *local,
            };
        }
        self.plan = plan;
        self.skin();
    }

    /// Every joint's skinning matrix from its world transform.
    fn skin(&mut self) {
        for ((skin, world), &rest) in self
            .skinning
            .iter_mut()
            .zip(&self.world)
            .zip(&self.rest_position)
        {
            // world × translation(−rest), the inverse bind matrix.
            *skin = Mat4::from(Affine3A {
                matrix3: world.matrix3,
                translation: world.translation - world.matrix3 * Vec3A::from(rest),
            });
        }
    }

    /// Where the creature stands (x, z) and the ground height its body follows (y); for a
    /// flier or swimmer, the height of its model origin (its rest pose's ground level); for a
    /// slitherer, its model origin were its body straight behind its head (x, z) and the
    /// ground under its head (y).
    #[must_use]
    pub const fn position(&self) -> Vec3 {
        self.position
    }

    /// The point that goes to an [`Intent::GoTo`] target: the [`position`](Self::position);
    /// for a slitherer, its head's place on the ground (its body follows where its head goes).
    #[must_use]
    pub fn lead(&self) -> Vec3 {
        match self.drive {
            Drive::Slither(_) => {
                let ahead = Quat::from_rotation_y(self.heading) * self.rest_root;
                Vec3::new(
                    self.position.x + ahead.x,
                    self.position.y,
                    self.position.z + ahead.z,
                )
            }
            _ => self.position,
        }
    }

    /// The creature's heading, radians about +Y from +Z.
    #[must_use]
    pub const fn heading(&self) -> f32 {
        self.heading
    }

    /// The fastest the creature turns (rad/s): a quarter turn a second, slower for a long
    /// walker whose end feet would otherwise sweep round faster than it walks (as its `turn`
    /// clip).
    #[must_use]
    pub const fn max_turn_rate(&self) -> f32 {
        self.max_turn_rate
    }

    /// Each joint's transform in its parent's frame (the root's in the world), as a glTF
    /// node's TRS.
    #[must_use]
    pub fn local_transforms(&self) -> &[Affine3A] {
        &self.local
    }

    /// Each joint's transform in the world.
    #[must_use]
    pub fn world_transforms(&self) -> &[Affine3A] {
        &self.world
    }

    /// Each joint's skinning matrix: its world transform times its inverse bind matrix
    /// ([`Skeleton::inverse_bind_matrices`](crate::d3::Skeleton::inverse_bind_matrices)), so
    /// a vertex at its rest position `p` goes to `Σ wᵢ Mᵢ p`.
    #[must_use]
    pub fn skinning_matrices(&self) -> &[Mat4] {
        &self.skinning
    }

    /// The gait controller driving the legs (its leg states, metrics and body reaction); a
    /// flier's or swimmer's has no legs.
    #[must_use]
    pub const fn controller(&self) -> &Controller {
        &self.controller
    }

    /// Whether the creature has come to rest: a walker with every foot planted, a flier
    /// landed and still, a swimmer or slitherer slowed to a twentieth of its speed.
    fn settled(&self) -> bool {
        match &self.drive {
            Drive::Walk => self.controller.all_planted(),
            Drive::Fly(flight) => flight.landed(self.length),
            Drive::Swim(swimming) => swimming.speed() <= 0.05 * self.speed,
            Drive::Slither(slithering) => slithering.speed() <= 0.05 * self.speed,
        }
    }
}

/// The longest time step an update takes: a longer one (a frame hitch) is taken as this.
pub const MAX_STEP: f32 = 0.1;

/// How far below a creature put down afresh ([`Animator::new`], [`Animator::with_pose`]) its
/// ground is looked for when rays from just above it find none (it was put high above it),
/// and then how far above (it was put under the ground): as far as a position may be from the
/// origin.
const FRESH_RANGE: f32 = creature_gait::MAX_COORDINATE;

/// The ground under a creature put down afresh where its rays, cast from `above` the body to
/// `below` it, find none: it was put high above the ground (the nearest ground below, however
/// far, is taken) or under it (the ground found from [`FRESH_RANGE`] above, then again from
/// `above` it: the first cast's rays, a million metres long, may round a ground's hit point).
/// `cast(origin, (above, below))` casts the creature's rays with the body at `origin`;
/// `height` is a hit's height.
pub(super) fn put_down<T>(
    position: Vec3,
    (above, below): (f32, f32),
    height: impl Fn(&T) -> f32,
    mut cast: impl FnMut(Vec3, (f32, f32)) -> Option<T>,
) -> Option<T> {
    cast(position, (above, FRESH_RANGE)).or_else(|| {
        let far = cast(position, (FRESH_RANGE, below))?;
        let on = Vec3::new(position.x, height(&far), position.z);
        cast(on, (above, below)).or(Some(far))
    })
}

/// How fast the body follows the terrain's height and slope (seconds, the time constant).
const TERRAIN_TIME: f32 = 0.15;

/// How fast the neck and tail bend follows the turn rate (seconds).
const TURN_BEND_TIME: f32 = 0.3;

/// The most a sole tilts to fit the ground under it (radians): a step's edge under a foot
/// is a steep ramp across it.
const MAX_SOLE_TILT: f32 = 0.45;

/// `cos(MAX_SOLE_TILT)`, rounded to the nearest `f32` (unit test
/// `max_sole_tilt_cos_is_its_cosine`).
const MAX_SOLE_TILT_COS: f32 = 0.900_447_13;

/// The ground under a sole's rim within this fraction of the sole's radius of a plane is
/// taken as that plane: the sole's vertices are tested against it without a ray each.
const FLAT_SOLE: f32 = 0.01;

/// The directions a sole's rim is sampled in: ahead, behind, left, right, then every 22.5°
/// between them (toes and claws reach out between the four).
const RIM: [Vec3; RIM_SAMPLES] = {
    let mut rim = [Vec3::ZERO; RIM_SAMPLES];
    // cos and sin of k × 22.5° for k = 0..16.
    const C: [f32; 5] = [
        1.0,
        0.923_879_5,
        core::f32::consts::FRAC_1_SQRT_2,
        0.382_683_43,
        0.0,
    ];
    let mut k = 0;
    let mut at = 4;
    while k < 16 {
        let (cos, sin) = match k / 4 {
            0 => (C[k % 4], C[4 - k % 4]),
            1 => (-C[4 - k % 4], C[k % 4]),
            2 => (-C[k % 4], -C[4 - k % 4]),
            _ => (C[4 - k % 4], -C[k % 4]),
        };
        let d = Vec3::new(sin, 0.0, cos);
        match k {
            0 => rim[0] = d,
            8 => rim[1] = d,
            4 => rim[2] = d,
            12 => rim[3] = d,
            _ => {
                rim[at] = d;
                at += 1;
            }
        }
        k += 1;
    }
    rim
};

/// How far the body may turn from the heading a step's landing fit was made for before the fit
/// is made again, as the least `|a · b|` of two unit quaternions that close: the cosine of half
/// of 2°.
const LANDING_TURN_COS: f32 = 0.999_847_7;

/// How many directions [`RIM`] samples.
const RIM_SAMPLES: usize = 16;

/// The rim of a sole (its [`sole_points`]): in each of [`RIM`]'s directions, the vertex that
/// reaches farthest that way (its horizontal offset from the joint and its height over the
/// sole's lowest vertex); the joint itself where the foot has no vertex.
fn sole_rim(points: &[Vec3A]) -> [Vec3; RIM_SAMPLES] {
    let bottom = points.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
    let mut rim = [(0.0f32, Vec3::ZERO); RIM_SAMPLES];
    for p in points {
        let d = Vec3::new(p.x, p.y - bottom, p.z);
        for (k, dir) in RIM.iter().enumerate() {
            let reach = d.dot(*dir);
            if reach > rim[k].0 {
                rim[k] = (reach, d);
            }
        }
    }
    rim.map(|(_, d)| d)
}

/// The sole of foot joint `foot` at rest: every vertex bound mostly to the foot near its
/// bottom, as its offset from the joint, each position once (a mesh with flat normals
/// repeats a position per face).
fn sole_points(creature: &Creature, foot: usize) -> Vec<Vec3A> {
    let centre = creature
        .skeleton
        .joints
        .get(foot)
        .map_or(Vec3::ZERO, |j| j.position);
    let mesh = &creature.mesh;
    let mut points: Vec<Vec3> = mesh
        .positions
        .iter()
        .zip(&mesh.joints)
        .zip(&mesh.weights)
        .filter(|&((_, js), ws)| {
            let most = js.iter().zip(ws).fold(
                (0u16, 0.0f32),
                |m, (&j, &w)| if w > m.1 { (j, w) } else { m },
            );
            usize::from(most.0) == foot
        })
        .map(|((&p, _), _)| p - centre)
        .collect();
    // The sole: the vertices near the foot's bottom (as the rim's), not the ankle above it.
    let bottom = points.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
    let band = 0.25 * creature.ring_radius(foot);
    points.retain(|p| p.y - bottom <= band);
    // Lowest first (the order `plane_lift` stops early in), each position once.
    crate::sort::sort_by(&mut points, &mut |a, b| {
        a.y.total_cmp(&b.y)
            .then(a.x.total_cmp(&b.x))
            .then(a.z.total_cmp(&b.z))
    });
    points.dedup();
    points.into_iter().map(Vec3A::from).collect()
}

/// Flat ground under a walker's body: [height bounds](Ground::height_bounds) whose lowest and
/// highest are one `height` under a square twice as wide as the one of half-side `half` about
/// `centre` (world x, z) that its rays are taken from (rounding cannot carry a ray's x or z
/// outside it).
#[derive(Debug, Clone, Copy)]
struct FlatUnder {
    centre: Vec2,
    half: f32,
    height: f32,
}

impl FlatUnder {
    /// The height a ray straight down from `from`, `range` long, hits, where the bounds
    /// settle it: `from` over the square, at or above the ground, and the ray reaching it
    /// (every such ray hits there); else `None` (cast it).
    fn hit(&self, from: Vec3, range: f32) -> Option<f32> {
        let inside = (from.x - self.centre.x).abs() <= self.half
            && (from.z - self.centre.y).abs() <= self.half;
        (inside && from.y >= self.height && from.y - self.height <= range).then_some(self.height)
    }
}

/// The ground under a sole, sampled on its rim: ahead of, behind, to either side of its
/// middle and between them.
struct SoleFit<'a> {
    /// The plane through the samples' normal, tilted at most [`MAX_SOLE_TILT`].
    normal: Vec3,
    /// The sole's middle above the samples' mean.
    height: f32,
    /// How far the level sole's rim stands above the ground at its lowest sample (negative
    /// where a sample is in it).
    clearance: f32,
    /// The ground under each rim sample: its offset from the foot joint along world x and z
    /// and its height over the joint.
    ground: &'a RimLanes,
}

impl SoleFit<'_> {
    /// The plane nearest the ground under the rim (least squares), where none of the ground
    /// under the rim is farther than `flat` off it; `None` where some is, or where the rim
    /// spans no area. Fitted only when asked: a foot high in a step needs none.
    fn plane_within(&self, flat: f32) -> Option<RimPlane> {
        let g = self.ground;
        let (a, p, q) = plane_fit_lanes(g)?;
        // Four samples at a time, as `(h - a - p x - q z).abs()` computes each; their largest
        // in the samples' order (as a fold of `max_f` finds it).
        let (a4, p4, q4) = (Vec4::splat(a), Vec4::splat(p), Vec4::splat(q));
        let mut off_plane = 0.0;
        for k in 0..LANE_GROUPS {
            let off = (g.y[k] - a4 - p4 * g.x[k] - q4 * g.z[k]).abs();
            for off in off.to_array() {
                off_plane = max_f(off_plane, off);
            }
        }
        (off_plane <= flat).then_some(RimPlane { plane: (a, p, q) })
    }
}

/// The plane of the ground under a sole's rim ([`SoleFit::plane_within`]).
struct RimPlane {
    /// Its height over the foot joint at the joint and its slopes along world x and z.
    plane: (f32, f32, f32),
}

impl RimPlane {
    /// [`sole_lift`] on the ground's plane under the rim: how far the sole turned to `turn`
    /// must rise for none of its `points` (lowest first, none farther than `reach` from the
    /// joint horizontally) to be below that plane (0 when none is).
    fn plane_lift(&self, turn: Quat, points: &[Vec3A], reach: f32) -> f32 {
        // The plane's height over a turned point, less the point's: a dot product with the
        // plane's gradient turned back into the sole's frame.
        let (a, p, q) = self.plane;
        let down = Vec3A::from(turn.inverse() * Vec3::new(p, -1.0, q));
        // Where `down` points down in the sole's frame, no point higher than one whose
        // bound falls short of the lift so far can raise it: the scan stops there (the
        // bound's margin covers rounding).
        let across = Vec3A::new(down.x, 0.0, down.z).norm() * reach;
        let margin = 1e-5 * (a.abs() + across + 1.0);
        let mut lift = 0.0f32;
        for &point in points {
            if down.y < 0.0 && a + down.y * point.y + across + margin < lift {
                break;
            }
            lift = max_f(lift, a + down.dot(point));
        }
        lift
    }
}

/// How far a sole whose joint is at `foot` (world), turned to `rotation` (world), must rise
/// for none of its `points` (offsets from the joint at rest) to be in `ground`: 0 when none is.
/// Every vertex is tested where it is, so a crest between the rim's samples (a step's edge
/// under a toe) lifts the sole as much as it needs.
fn sole_lift<G: Ground + ?Sized>(
    ground: &G,
    foot: Vec3,
    rotation: Quat,
    points: &[Vec3A],
    reach: f32,
) -> f32 {
    let turn = glam::Mat3A::from_quat(rotation);
    let foot = Vec3A::from(foot);
    // Four points at a time (the last four again for the remainder: the largest lift is the
    // same), in their order.
    let mut lift = 0.0;
    let mut start = 0;
    while start < points.len() {
        let first = start.min(points.len().saturating_sub(4));
        let four: [Vec3A; 4] = core::array::from_fn(|l| {
            let p = points.get(first + l).map_or(Vec3A::ZERO, |&p| p);
            foot + turn * p
        });
        let lanes = |along: fn(&Vec3A) -> f32| Vec4::from_array(four.each_ref().map(along));
        let (x, y, z) = (lanes(|p| p.x), lanes(|p| p.y), lanes(|p| p.z));
        let hits = ground.cast_down_four(x, y + Vec4::splat(reach), z, Vec4::splat(2.0 * reach));
        for (hit, at) in hits.into_iter().zip(&four).take(points.len().min(4)) {
            if let Some(height) = hit {
                lift = max_f(lift, height - at.y);
            }
        }
        start = first + 4;
    }
    lift
}

/// The ground under a sole of `radius` at `foot` (world) turned with `heading`: `None` when a
/// ray misses. The ground under the rim is written to `under` (the fit's
/// [`ground`](SoleFit::ground)).
fn fit_sole<'a, G: Ground + ?Sized>(
    ground: &G,
    foot: Vec3,
    heading: Quat,
    rim: &RimLanes,
    reach: f32,
    bounds: Option<(f32, f32)>,
    under: &'a mut RimLanes,
) -> Option<SoleFit<'a>> {
    // A matrix turns the 16 offsets in half the arithmetic of the quaternion; four at a time,
    // lane for lane as `turn * d` turns each.
    let turn = glam::Mat3A::from_quat(heading);
    let top = foot.y + reach;
    // On ground the bounds (of the square round the rim) say is flat, every ray that reaches
    // it hits it at its height: none is cast.
    let flat = bounds.and_then(|(low, high)| {
        (low == high && top >= high && top - low <= 2.0 * reach).then_some(low)
    });
    let (tx, ty, tz) = (turn.x_axis, turn.y_axis, turn.z_axis);
    let turned = |k: usize, along: fn(Vec3A) -> f32| {
        let axis = |v: Vec3A| Vec4::splat(along(v));
        axis(tx) * rim.x[k] + axis(ty) * rim.y[k] + axis(tz) * rim.z[k]
    };
    let foot_y = Vec4::splat(foot.y);
    // Per sample: its offset turned (x and z), and the ground's height there over the sole's
    // vertex, in the sole's level frame (`height - foot.y - d.y`).
    let fit = under;
    let mut heights = [Vec4::ZERO; LANE_GROUPS];
    for (k, heights) in heights.iter_mut().enumerate() {
        let (x, y, z) = (turned(k, |v| v.x), turned(k, |v| v.y), turned(k, |v| v.z));
        let height = match flat {
            Some(height) => Vec4::splat(height),
            None => {
                // From above each sample (`foot.x + d.x`, `top`, `foot.z + d.z`).
                let (x, z) = (Vec4::splat(foot.x) + x, Vec4::splat(foot.z) + z);
                match ground.cast_down_four(x, Vec4::splat(top), z, Vec4::splat(2.0 * reach)) {
                    [Some(a), Some(b), Some(c), Some(d)] => Vec4::new(a, b, c, d),
                    _ => return None,
                }
            }
        };
        let h = height - foot_y - y;
        (fit.x[k], fit.z[k], *heights) = (x, z, h);
        // The ground under the rim for its plane (heights over the joint).
        fit.y[k] = h + rim.y[k];
    }
    let sample = |i: usize| {
        let (k, l) = (i / 4, i % 4);
        (Vec3::new(fit.x[k][l], 0.0, fit.z[k][l]), heights[k][l])
    };
    // The slope along and across the heading, from the rim's ends.
    let slope = |(da, a): (Vec3, f32), (db, b): (Vec3, f32)| {
        let run = da - db;
        let length = run.length_squared();
        if length > 0.0 {
            run * ((a - b) / length)
        } else {
            Vec3::ZERO
        }
    };
    let normal =
        (Vec3::Y - slope(sample(0), sample(1)) - slope(sample(2), sample(3))).unit_or(Vec3::Y);
    // At most the steepest tilt: the normal's horizontal part scaled down.
    let normal = tilted(normal, (MAX_SOLE_TILT, MAX_SOLE_TILT_COS));
    let all = heights.map(|h| h.to_array());
    let all = all.as_flattened();
    let mean = all.iter().sum::<f32>() / RIM_SAMPLES as f32;
    let highest = all.iter().copied().fold(f32::NEG_INFINITY, max_f);
    Some(SoleFit {
        normal,
        height: -mean,
        clearance: -highest,
        ground: fit,
    })
}

/// Groups of four of a sole's [`RIM_SAMPLES`] (SIMD lanes).
const LANE_GROUPS: usize = RIM_SAMPLES / 4;

/// A sole's rim samples, four to a SIMD lane group (sample `4 k + l` is lane `l` of group
/// `k`): for its rim's offsets from the foot joint (x, y, z), or for the ground under it
/// (x, height, z; [`SoleFit::ground`]).
#[derive(Debug, Clone, Copy)]
struct RimLanes {
    x: [Vec4; LANE_GROUPS],
    y: [Vec4; LANE_GROUPS],
    z: [Vec4; LANE_GROUPS],
}

impl RimLanes {
    const ZERO: Self = Self {
        x: [Vec4::ZERO; LANE_GROUPS],
        y: [Vec4::ZERO; LANE_GROUPS],
        z: [Vec4::ZERO; LANE_GROUPS],
    };

    fn new(rim: &[Vec3; RIM_SAMPLES]) -> Self {
        let lanes = |along: fn(&Vec3) -> f32| {
            core::array::from_fn(|k| {
                Vec4::from_array(core::array::from_fn(|l| along(&rim[4 * k + l])))
            })
        };
        Self {
            x: lanes(|d| d.x),
            y: lanes(|d| d.y),
            z: lanes(|d| d.z),
        }
    }

    /// Sample `i`'s x, y and z.
    fn get(&self, i: usize) -> (f32, f32, f32) {
        let (k, l) = (i / 4, i % 4);
        (self.x[k][l], self.y[k][l], self.z[k][l])
    }
}

/// [`plane_fit`] through the ground under a rim (`(x, height, z)`), in the samples' order: the
/// same sums, term for term, each term computed four at a time.
fn plane_fit_lanes(g: &RimLanes) -> Option<(f32, f32, f32)> {
    let (mut n, mut sx, mut sz, mut sh) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
    for i in 0..RIM_SAMPLES {
        let (x, h, z) = g.get(i);
        (n, sx, sz, sh) = (n + 1.0, sx + x, sz + z, sh + h);
    }
    let (mx, mz, mh) = (sx / n, sz / n, sh / n);
    let (mx4, mz4, mh4) = (Vec4::splat(mx), Vec4::splat(mz), Vec4::splat(mh));
    let (mut xx, mut xz, mut zz, mut xh, mut zh) = (0.0f32, 0.0f32, 0.0f32, 0.0f32, 0.0f32);
    for k in 0..LANE_GROUPS {
        let (x, z, h) = (g.x[k] - mx4, g.z[k] - mz4, g.y[k] - mh4);
        let [x2, xz2, z2, xh2, zh2] = [x * x, x * z, z * z, x * h, z * h].map(|t| t.to_array());
        for l in 0..4 {
            (xx, xz, zz) = (xx + x2[l], xz + xz2[l], zz + z2[l]);
            (xh, zh) = (xh + xh2[l], zh + zh2[l]);
        }
    }
    let det = xx * zz - xz * xz;
    (det > 1e-12 * (xx + zz) * (xx + zz)).then(|| {
        let (p, q) = ((xh * zz - zh * xz) / det, (zh * xx - xh * xz) / det);
        (mh - p * mx - q * mz, p, q)
    })
}

/// The least-squares plane `h = a + p x + q z` through `samples` `(x, z, h)`: `(a, p, q)`, or
/// `None` where the samples span no area (or there are none).
fn plane_fit(samples: impl Iterator<Item = (f32, f32, f32)> + Clone) -> Option<(f32, f32, f32)> {
    let (mut n, mut sx, mut sz, mut sh) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
    for (x, z, h) in samples.clone() {
        (n, sx, sz, sh) = (n + 1.0, sx + x, sz + z, sh + h);
    }
    let (mx, mz, mh) = (sx / n, sz / n, sh / n);
    let (mut xx, mut xz, mut zz, mut xh, mut zh) = (0.0f32, 0.0f32, 0.0f32, 0.0f32, 0.0f32);
    for (x, z, h) in samples {
        let (x, z, h) = (x - mx, z - mz, h - mh);
        (xx, xz, zz) = (xx + x * x, xz + x * z, zz + z * z);
        (xh, zh) = (xh + x * h, zh + z * h);
    }
    let det = xx * zz - xz * xz;
    (det > 1e-12 * (xx + zz) * (xx + zz)).then(|| {
        let (p, q) = ((xh * zz - zh * xz) / det, (zh * xx - xh * xz) / det);
        (mh - p * mx - q * mz, p, q)
    })
}

/// A yaw `angle` (radians about +Y, taken into one turn about 0) and its rotation.
fn yawed(angle: f32) -> (f32, Quat) {
    let angle = wrap(angle);
    (angle, Quat::from_rotation_y(angle))
}

/// `x` less its whole part (for non-negative phases).
fn fract(x: f32) -> f32 {
    x - crate::math::floor_f(x)
}

/// `normal` (a unit vector) tilted from straight up by at most `most` radians (whose cosine is
/// `cos`): where it leans further, its horizontal part scaled down to that.
fn tilted(normal: Vec3, (most, cos): (f32, f32)) -> Vec3 {
    if normal.y >= cos {
        return normal;
    }
    let level = Vec3::new(normal.x, 0.0, normal.z).unit_or(Vec3::X);
    level * crate::math::sin(most) + Vec3::Y * cos
}

/// How quickly (seconds, a time constant) a hopper's tail eases to the swing its feet ask.
const TAIL_SWING_TIME: f32 = 0.05;

/// Turn rate (rad/s) per radian a [`Intent::GoTo`] target is off the heading.
const TURN_GAIN: f32 = 2.0;

/// The most the body leans with the terrain (radians): 30°.
const MAX_LEAN: f32 = core::f32::consts::FRAC_PI_6;

/// The share `1 − e^(−dt/τ)` of the way a first-order follower goes in `dt`.
fn smoothing(dt: f32, tau: f32) -> f32 {
    1.0 - crate::math::exp(-dt / tau)
}

/// `dt` checked (finite, not negative) and capped at [`MAX_STEP`].
fn time_step(dt: f32) -> Result<f32, Error> {
    if !dt.is_finite() {
        return Err(Error::NonFinite { what: "dt" });
    }
    if dt < 0.0 {
        return Err(Error::OutOfRange {
            what: "dt",
            value: dt,
            min: 0.0,
            max: f32::INFINITY,
        });
    }
    Ok(dt.min(MAX_STEP))
}

/// `angle` wrapped into `[-π, π)`.
fn wrap(angle: f32) -> f32 {
    use core::f32::consts::{PI, TAU};
    angle - TAU * crate::math::floor_f((angle + PI) / TAU)
}

/// The joints ordered parents first (by their depth below the root).
fn parents_first(parents: &[Option<usize>]) -> Result<Vec<usize>, Error> {
    let n = parents.len();
    let mut depth = alloc::vec![0usize; n];
    for (joint, depth) in depth.iter_mut().enumerate() {
        let mut at = joint;
        while let Some(parent) = parents[at] {
            if parent >= n || *depth >= n {
                return Err(Error::BadParent {
                    bone: at,
                    parent: Some(parent),
                });
            }
            at = parent;
            *depth += 1;
        }
    }
    let mut order: Vec<usize> = (0..n).collect();
    crate::sort::sort_by(&mut order, &mut |&a, &b| depth[a].cmp(&depth[b]));
    Ok(order)
}

impl Creature {
    /// A clip of this creature going over `ground` to `target` (world; its height is ignored)
    /// from the origin, facing +Z, driven by an [`Animator`] at [`CLIP_FPS`] (see
    /// [`Intent::GoTo`]), then standing: it ends once the creature has arrived and settled, or
    /// after `max_seconds`. Its frames are the animator's poses: the root's world transform
    /// and the local rotations of every joint the animator turns (and the hips' translations).
    ///
    /// - A walker's clip is `walk_to`: it walks there and ends with every foot planted; it
    ///   carries each leg's contacts.
    /// - A flier's is `fly_to`: it starts landed on the ground at the origin, takes off, flies
    ///   there and lands (see [`Animator`]); its frames have no contacts.
    /// - A swimmer's is `swim_to`: it swims there and ends once it has slowed to a sway.
    /// - A slitherer's is `slither_to`: it crawls there (its head to the target) and ends
    ///   once it has slowed to lie still.
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    /// use creature::glam::Vec3;
    /// use creature::terrain::{terrain, TerrainParams};
    ///
    /// let hills = terrain(7, &TerrainParams::DEFAULT)?;
    /// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker).with_clips(false))?;
    /// let clip = walker.bake_to(&hills, Vec3::new(1.0, 0.0, 3.0) * walker.length, 30.0)?;
    /// assert_eq!(clip.name, "walk_to");
    /// assert!(clip.frames > 1);
    /// let bird = generate(7, &Params::DEFAULT.with_kind(Kind::Flier).with_clips(false))?;
    /// assert_eq!(bird.bake_to(&hills, Vec3::new(0.0, 0.0, 3.0), 30.0)?.name, "fly_to");
    /// # Ok::<(), creature::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Animator::new`] (a walker without a gait set-up, or a kind this version does not
    /// animate: [`Error::NoGait`]) and
    /// [`Animator::update`] (a non-finite target); [`Error::OutOfRange`] for `max_seconds`
    /// outside `[1 / CLIP_FPS, 600]`.
    pub fn bake_to<G: Ground + ?Sized>(
        &self,
        ground: &G,
        target: Vec3,
        max_seconds: f32,
    ) -> Result<Clip, Error> {
        let min = 1.0 / CLIP_FPS;
        if !(min..=600.0).contains(&max_seconds) {
            return Err(Error::OutOfRange {
                what: "max_seconds",
                value: max_seconds,
                min,
                max: 600.0,
            });
        }
        if !target.is_finite() {
            return Err(Error::NonFinite {
                what: "intent target",
            });
        }
        let mut animator = Animator::new(self)?;
        let name = match animator.drive {
            Drive::Walk => "walk_to",
            Drive::Fly(_) => {
                // Landed at the origin before the first frame (within a minute): the clip
                // takes off.
                for _ in 0..60 * CLIP_FPS as usize {
                    animator.update(1.0 / CLIP_FPS, Intent::Stand, ground)?;
                    if animator.settled() {
                        break;
                    }
                }
                "fly_to"
            }
            Drive::Swim(_) => "swim_to",
            Drive::Slither(_) => "slither_to",
        };
        let most = (max_seconds * CLIP_FPS) as usize + 1;
        let mut clip = animator.empty_clip(name);
        let arrived = ARRIVAL_RADIUS * self.length;
        let mut intent = Intent::GoTo(target);
        for frame in 0..most {
            let dt = if frame == 0 { 0.0 } else { 1.0 / CLIP_FPS };
            animator.update(dt, intent, ground)?;
            animator.push_frame(&mut clip, &Pose::IDENTITY);
            let at = animator.lead();
            if Vec2::new(target.x - at.x, target.z - at.z).norm() <= arrived {
                // Arrived (a go-to's intent now, as a stand's): it stands, a flier lands.
                intent = Intent::Stand;
                if animator.settled() {
                    break;
                }
            }
        }
        clip.loop_error = super::loop_error(&clip);
        Ok(clip)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_wrap_into_one_turn_about_zero() {
        use core::f32::consts::PI;
        for (angle, wrapped) in [
            (0.0, 0.0),
            (1.0, 1.0),
            (PI + 0.5, 0.5 - PI),
            (-PI - 0.5, PI - 0.5),
            (7.0 * PI, -PI),
        ] {
            assert!(
                (wrap(angle) - wrapped).abs() < 1e-5,
                "{angle} → {}",
                wrap(angle)
            );
        }
    }

    #[test]
    fn joints_are_ordered_parents_first_and_a_cycle_is_an_error() {
        // 0 ← 2 ← 1 ← 3: the parents come after their children in the list.
        let order = parents_first(&[None, Some(2), Some(0), Some(1)]).unwrap();
        assert_eq!(order, [0, 2, 1, 3]);
        assert!(matches!(
            parents_first(&[None, Some(2), Some(1)]),
            Err(Error::BadParent { .. })
        ));
        assert!(matches!(
            parents_first(&[Some(5)]),
            Err(Error::BadParent { .. })
        ));
    }

    #[test]
    fn a_soles_plane_lift_stops_early_only_where_no_later_point_could_raise_it() {
        // A sole of points at several heights and reaches, lowest first as `sole_points`
        // sorts them, against planes and turns of every kind: the early stop gives the full
        // scan's lift.
        let mut points: Vec<Vec3A> = (0..60)
            .map(|k| {
                let k = k as f32;
                let angle = 2.399_963 * k;
                let reach = 0.05 + 0.4 * (crate::math::sin(k * 0.37) * 0.5 + 0.5);
                Vec3A::new(
                    reach * crate::math::cos(angle),
                    0.1 * (crate::math::sin(k * 1.7) * 0.5 + 0.5),
                    reach * crate::math::sin(angle),
                )
            })
            .collect();
        points.sort_by(|a, b| a.y.total_cmp(&b.y));
        let reach = points
            .iter()
            .map(|p| Vec3A::new(p.x, 0.0, p.z).length())
            .fold(0.0, f32::max);
        let mut stopped_early = 0;
        for i in 0..400 {
            let t = i as f32;
            let plane = (
                0.2 * crate::math::sin(t * 0.91) - 0.05,
                0.8 * crate::math::sin(t * 0.53),
                0.8 * crate::math::cos(t * 0.29),
            );
            let fit = RimPlane { plane };
            let turn = Quat::from_rotation_y(t * 0.7)
                * Quat::from_rotation_x(0.5 * crate::math::sin(t * 0.13))
                * Quat::from_rotation_z(0.5 * crate::math::cos(t * 0.17));
            let full = {
                let (a, p, q) = plane;
                points.iter().fold(0.0f32, |lift, &point| {
                    let at = glam::Mat3A::from_quat(turn) * point;
                    lift.max(a + p * at.x + q * at.z - at.y)
                })
            };
            let lift = fit.plane_lift(turn, &points, reach);
            assert!((lift - full).abs() <= 1e-5, "{i}: {lift} against {full}");
            // Count the cases the bound ends before the last point.
            let down = Vec3A::from(turn.inverse() * Vec3::new(plane.1, -1.0, plane.2));
            let across = Vec3A::new(down.x, 0.0, down.z).length() * reach;
            if down.y < 0.0 && plane.0 + down.y * points[59].y + across < full {
                stopped_early += 1;
            }
        }
        assert!(stopped_early > 0, "the bound never stopped a scan early");
    }

    #[test]
    fn a_go_to_turns_toward_the_target_and_stops_on_arrival() {
        let walker = crate::d3::generate(
            3,
            &crate::d3::Params::DEFAULT
                .with_kind(crate::d3::Kind::Walker)
                .with_clips(false),
        )
        .unwrap();
        let animator = Animator::new(&walker).unwrap();
        // A target to the right (+X): a positive turn, toward +X from +Z.
        let (_, turn) = animator.wanted(Intent::GoTo(Vec3::X * 10.0)).unwrap();
        assert!(turn > 0.0);
        // Straight ahead: no turn, full speed.
        let (velocity, turn) = animator
            .wanted(Intent::GoTo(Vec3::Z * 10.0 * walker.length))
            .unwrap();
        assert_eq!(turn, 0.0);
        assert!((velocity.length() - walker.speed).abs() < 1e-4 * walker.speed);
        // Within the arrival radius: stand.
        let near = Vec3::Z * 0.1 * walker.length;
        assert_eq!(
            animator.wanted(Intent::GoTo(near)).unwrap(),
            (Vec3::ZERO, 0.0)
        );
        // A move faster than twice the creature's speed (or its run speed) is slowed to that.
        let fast = Intent::Move {
            velocity: Vec3::Z * 1e6,
            turn_rate: 1e6,
        };
        let (velocity, turn) = animator.wanted(fast).unwrap();
        let run = walker.gait.as_ref().unwrap().run_speed().unwrap();
        let top = (2.0 * walker.speed).max(run);
        assert!((velocity.length() - top).abs() < 1e-3 * walker.speed);
        assert_eq!(turn, animator.max_turn_rate());
    }

    #[test]
    fn max_sole_tilt_cos_is_its_cosine() {
        let cos = f64::from(MAX_SOLE_TILT).cos();
        assert_eq!(MAX_SOLE_TILT_COS, cos as f32);
        assert!((MAX_SOLE_TILT_COS - crate::math::cos(MAX_SOLE_TILT)).abs() <= f32::EPSILON);
    }

    #[test]
    fn landing_turn_cos_is_the_cosine_of_one_degree() {
        let cos = crate::math::cos(core::f32::consts::PI / 180.0);
        assert!((cos - LANDING_TURN_COS).abs() <= f32::EPSILON, "{cos}");
    }

    #[test]
    fn a_landing_fit_is_made_for_the_step_target_once_it_stays_put() {
        // Walker 32 circling on the default terrain: while a step's target follows the body,
        // its landing fit may be one made within a sole's radius of it; over the step's last
        // `plant_fraction` of progress (the target put), it is the fit for that target.
        let walker = crate::d3::generate(
            32,
            &crate::d3::Params::DEFAULT
                .with_kind(crate::d3::Kind::Walker)
                .with_clips(false),
        )
        .unwrap();
        let hills = crate::terrain::terrain(7, &crate::terrain::TerrainParams::DEFAULT).unwrap();
        let mut animator = Animator::new(&walker).unwrap();
        let plant = animator.controller.options().plant_fraction;
        let (mut put, mut near) = (0, 0);
        for _ in 0..600 {
            let heading = animator.heading();
            let intent = Intent::Move {
                velocity: Vec3::new(heading.sin(), 0.0, heading.cos()) * walker.speed,
                turn_rate: 0.5,
            };
            animator.update(1.0 / 60.0, intent, &hills).unwrap();
            let legs = animator.controller.legs();
            let states = animator.controller.leg_states();
            for ((live, leg), state) in animator.legs.iter().zip(legs).zip(states) {
                if leg.kind != LimbKind::Leg
                    || !(state.stepping && !state.planted && state.progress > 0.5)
                {
                    continue;
                }
                let (at, _, _) = live.landing.unwrap();
                let target = state.step_target;
                if state.progress >= 1.0 - plant {
                    assert_eq!(at, target, "progress {}", state.progress);
                    put += 1;
                } else {
                    let off = (at - target).length();
                    assert!(off <= 1.000_001 * live.foot_radius, "{off} m off");
                    near += usize::from(at != target);
                }
            }
        }
        assert!(put > 0 && near > 0, "{put} landings put, {near} near");
    }
}
