//! The live animator's fliers and swimmers: steered like walkers (see [`Animator::wanted`]),
//! held above the ground under them, their wings beating or their bodies waving as the baked
//! `fly` and `swim` clips pose them, faster the faster they go.

use alloc::boxed::Box;
use alloc::vec::Vec;

use glam::{Affine3A, Quat, Vec3, Vec3A};

use creature_gait::{Controller, FlapParams, GaitOptions, Ground, SwimParams};

use super::super::flight::{
    FlightChains, chain_bend_limited, flap_params, flight_chain_joints, wing_joint_rotation,
    wing_joints,
};
use super::super::swim::{Motion, bend_scale, fin_joints, fin_rotation, swim, swim_spine};
use super::super::walk::turn_bend_total;
use super::{Animator, Drive, fract};
use crate::Error;
use crate::d3::Creature;
use crate::math::Roots;

/// A flier's model origin (its rest pose's ground level) is held this many body lengths above
/// the highest ground under and ahead of it.
const FLY_HEIGHT: f32 = 0.75;

/// The least gap (body lengths) between a flier's skin and the ground under each joint.
const FLY_CLEARANCE: f32 = 0.05;

/// A swimmer swims this many body lengths higher than its clip over the highest ground
/// under and ahead of it; half of it is the least gap between its skin and the ground.
const SWIM_CLEARANCE: f32 = 0.02;

/// The wing beat's frequency hovering, as a share of its frequency at the creature's speed
/// (it rises linearly with the speed, to `2 − HOVER_BEAT` times at twice the speed).
const HOVER_BEAT: f32 = 0.8;

/// The wing beat's amplitude hovering, as a share of its amplitude at the creature's speed
/// (rising as the frequency does).
const HOVER_SWEEP: f32 = 0.85;

/// The body wave's frequency at rest, as a share of its frequency at the creature's speed.
const REST_WAVE: f32 = 0.5;

/// Seconds a flier takes to land when told to stand, and to take off again.
const LANDING_TIME: f32 = 1.5;
const TAKE_OFF_TIME: f32 = 0.75;

/// The most a flier banks into a turn (radians): 35°, at its full turn rate and speed.
const MAX_BANK: f32 = 0.61;

/// The most a flier pitches climbing or diving (radians): 20°.
const MAX_PITCH: f32 = 0.35;

/// Seconds ahead the ground is looked at (and half that), so a flier or swimmer climbs before
/// a hill.
const LOOK_AHEAD: f32 = 0.8;

/// Rays down for the ground start this many body lengths above the creature's model origin.
const RAY_ABOVE: f32 = 4.0;

/// And reach this many body lengths below it.
const RAY_BELOW: f32 = 100.0;

/// The fastest a flier or swimmer turns (rad/s): a quarter turn a second.
const TURN_RATE: f32 = core::f32::consts::FRAC_PI_2;

/// Keeping a flier or a swimmer off the ground.
#[derive(Debug, Clone)]
pub(super) struct Hold {
    /// How high the model origin is held above the highest ground under and ahead (metres).
    height: f32,
    /// How far the skin reaches horizontally from the model origin (metres).
    radius: f32,
    /// Per joint, how far below it its skin may reach (metres).
    below: Vec<f32>,
    /// The least gap between the skin and the ground (metres).
    clearance: f32,
    /// The speed (m/s), smoothed.
    speed: f32,
    /// The wing beat's or body wave's frequency in the last update (per second).
    frequency: f32,
}

/// A flier's wings and chains.
#[derive(Debug, Clone)]
pub(super) struct Flight {
    hold: Hold,
    flap: FlapParams,
    buzzing: bool,
    /// Wing joints: each with its side's sign and its place along its wing.
    wings: Vec<(usize, f32, usize)>,
    /// Legs, arms and tail: damped chains (as in the `fly` clip).
    chains: FlightChains,
    /// The chains' animated joints, their bend limits and (room for) their rotations.
    chain_joints: Vec<usize>,
    chain_limits: Vec<f32>,
    chain_rotations: Vec<Quat>,
    /// A slot per joint, for the chains' rotations.
    global: Vec<Option<Quat>>,
    /// The wing beat's phase and the (buzzing) bob's, in turns.
    beat: f32,
    bob: f32,
    /// The body's pitch (radians), smoothed.
    pitch: f32,
    /// Per joint, how far below it its skin reaches at rest (standing, landed).
    rest_below: Vec<f32>,
    /// How far it has landed: 0 flying, 1 standing on the ground.
    landed: f32,
    /// How far its model origin rose or sank in the last update (metres).
    sink: f32,
    /// How high its lowest vertex is over its model origin at rest (metres, at least 0): a
    /// landed flier is lowered by this onto the ground.
    rest_lift: f32,
    /// Where it finds the ground it lands on ([`footprint`]).
    footprint: [Vec3; 9],
    /// Per joint, its skin's bottom rim at rest ([`bottom_rims`]), kept above the ground
    /// landing.
    rims: Vec<[Vec3A; 8]>,
    /// Its lean (pitch, roll) with the ground it lands on, smoothed.
    lean: glam::Vec2,
}

/// A swimmer's body wave.
#[derive(Debug, Clone)]
pub(super) struct Swimming {
    hold: Hold,
    params: SwimParams,
    /// The spine from the head (the root) toward the tail: joints, places along it, each
    /// place's share of the wave (its skin's limit), of the turn's bend, and its limit.
    spine: Vec<usize>,
    along: Vec<f32>,
    scale: Vec<f32>,
    turn_share: Vec<f32>,
    limits: Vec<f32>,
    fins: Vec<(usize, Motion, f32, usize)>,
    /// The swimming wave's and the idle sway's phases, in turns.
    wave: f32,
    idle: f32,
}

/// Where a flier or swimmer goes in one update (see [`Animator::steer`]).
struct Steer {
    heading: f32,
    position: Vec3,
    /// The speed (m/s), smoothed, and as a share of the creature's speed (at most 2).
    speed: f32,
    relative: f32,
    /// The turn rate (rad/s), smoothed, and the share of the way such smoothing goes in the
    /// update.
    turn: f32,
    share: f32,
}

/// Per joint, how far below it its skin reaches at rest (metres): down to the lowest vertex
/// it moves.
fn rest_below(c: &Creature) -> Vec<f32> {
    let joints = &c.skeleton.joints;
    let mut lowest: Vec<f32> = joints.iter().map(|j| j.position.y).collect();
    c.for_each_skinned(|j, p| lowest[j] = lowest[j].min(p.y));
    joints
        .iter()
        .zip(&lowest)
        .map(|(j, &l)| j.position.y - l)
        .collect()
}

/// The slope a skin's bottom rim is chosen for: 30° (tan).
const RIM_SLOPE: f32 = 0.577_350_3;

/// Per joint, its skin's bottom rim at rest: of the vertices bound to it, in each of eight
/// directions (every 45° about the vertical), the one that ground rising that way at
/// [`RIM_SLOPE`] would reach first, as an offset from the joint; the joint's place where it
/// has none.
fn bottom_rims(c: &Creature) -> Vec<[Vec3A; 8]> {
    let joints = &c.skeleton.joints;
    let mut rims = alloc::vec![[(f32::NEG_INFINITY, Vec3A::ZERO); 8]; joints.len()];
    // Each vertex on every joint it is bound to (it moves partly with each).
    c.for_each_skinned(|j, p| rim_candidate(&mut rims[j], Vec3A::from(p - joints[j].position)));
    rims.into_iter().map(|rim| rim.map(|(_, d)| d)).collect()
}

/// The whole skin's bottom rim at rest ([`bottom_rims`] with the model origin for the joint)
/// and its lowest vertex: where a landing flier finds the ground it stands on.
fn footprint(c: &Creature) -> [Vec3; 9] {
    let mut rim = [(f32::NEG_INFINITY, Vec3A::ZERO); 8];
    let mut lowest = Vec3::ZERO;
    for (k, &p) in c.mesh.positions.iter().enumerate() {
        rim_candidate(&mut rim, Vec3A::from(p));
        if k == 0 || p.y < lowest.y {
            lowest = p;
        }
    }
    let mut points = [lowest; 9];
    for (point, (_, d)) in points.iter_mut().zip(rim) {
        *point = Vec3::from(d);
    }
    points
}

/// Keeps `d` in each of `rim`'s eight directions (every 45° about the vertical, from +X
/// toward +Z) where ground rising that way at [`RIM_SLOPE`] would reach it before the vertex
/// kept there.
fn rim_candidate(rim: &mut [(f32, Vec3A); 8], d: Vec3A) {
    use core::f32::consts::FRAC_1_SQRT_2 as D;
    const DIRECTIONS: [(f32, f32); 8] = [
        (1.0, 0.0),
        (D, D),
        (0.0, 1.0),
        (-D, D),
        (-1.0, 0.0),
        (-D, -D),
        (0.0, -1.0),
        (D, -D),
    ];
    for (slot, (x, z)) in rim.iter_mut().zip(DIRECTIONS) {
        let over = RIM_SLOPE * (d.x * x + d.z * z) - d.y;
        if over > slot.0 {
            *slot = (over, d);
        }
    }
}

/// The plane through the ground under `points` (offsets from the model origin at rest, as
/// [`footprint`]'s) with the model origin at `origin` turned by `yaw`: its height at the
/// origin and its slopes along the body's forward and left axes as a pitch and a roll
/// (radians, each within [`MAX_LEAN`](super::MAX_LEAN)); `None` unless every ray hits finite
/// ground and the points span an area.
fn ground_plane<G: Ground + ?Sized>(
    ground: &G,
    (origin, yaw): (Vec3, Quat),
    points: &[Vec3; 9],
    (above, range): (f32, f32),
) -> Option<(f32, glam::Vec2)> {
    let mut hits = [(0.0f32, 0.0f32, 0.0f32); 9];
    for (hit, p) in hits.iter_mut().zip(points) {
        let at = origin + yaw * Vec3::new(p.x, 0.0, p.z);
        let g = ground.cast_down_point(at + Vec3::Y * above, range)?;
        if !g.y.is_finite() {
            return None;
        }
        *hit = (p.x, p.z, g.y - origin.y);
    }
    let (a, p, q) = super::plane_fit(hits.into_iter())?;
    let lean = |slope: f32| {
        glam::Vec2::new(1.0, slope)
            .to_angle()
            .clamp(-super::MAX_LEAN, super::MAX_LEAN)
    };
    Some((origin.y + a, glam::Vec2::new(-lean(q), lean(p))))
}

/// How high the lowest vertex is over the model origin at rest (at least 0; 0 for no mesh).
fn rest_lift(c: &Creature) -> f32 {
    let lowest = c
        .mesh
        .positions
        .iter()
        .map(|p| p.y)
        .fold(f32::INFINITY, f32::min);
    if lowest.is_finite() {
        lowest.max(0.0)
    } else {
        0.0
    }
}

/// How far the skin reaches horizontally from the model origin at rest (metres).
fn skin_radius(c: &Creature) -> f32 {
    c.mesh
        .positions
        .iter()
        .map(|p| glam::Vec2::new(p.x, p.z).norm())
        .fold(0.0, f32::max)
}

impl Flight {
    /// Whether it has landed (its rest pose on the ground) and come to rest: it moved up or
    /// down no more than a ten-thousandth of `length` in the last update (over no ground at
    /// all, it has "landed" where it hovers).
    pub(super) fn landed(&self, length: f32) -> bool {
        self.landed >= 1.0 && self.sink <= 1e-4 * length
    }
}

impl Swimming {
    /// How fast it swims now (m/s).
    pub(super) const fn speed(&self) -> f32 {
        self.hold.speed
    }
}

impl Animator {
    /// A flier's animator: hovering at its flying height over flat ground.
    pub(super) fn flier(c: &Creature) -> Result<Self, Error> {
        let (flap, buzzing) = flap_params(c);
        let chains = FlightChains::new(c, &flight_chain_joints(c), c.speed.max(1e-3))?;
        let chain_joints: Vec<usize> = chains.animated().collect();
        let limits = c.bend_limits();
        let flight = Flight {
            hold: Hold {
                height: FLY_HEIGHT * c.length,
                radius: skin_radius(c),
                below: c.joint_reach(),
                clearance: FLY_CLEARANCE * c.length,
                speed: 0.0,
                frequency: HOVER_BEAT * flap.frequency,
            },
            flap,
            buzzing,
            wings: wing_joints(c),
            chain_limits: chain_joints
                .iter()
                .map(|&j| limits.get(j).copied().unwrap_or(f32::INFINITY))
                .collect(),
            chain_rotations: alloc::vec![Quat::IDENTITY; chain_joints.len()],
            chain_joints,
            chains,
            global: alloc::vec![None; c.skeleton.joints.len()],
            beat: 0.0,
            bob: 0.0,
            pitch: 0.0,
            rest_below: rest_below(c),
            landed: 0.0,
            sink: 0.0,
            rest_lift: rest_lift(c),
            footprint: footprint(c),
            rims: bottom_rims(c),
            lean: glam::Vec2::ZERO,
        };
        let controller = Controller::chains_only(c.length.max(1e-3), &GaitOptions::DEFAULT)?;
        let turned: Vec<usize> = (flight.wings.iter().map(|w| w.0))
            .chain(flight.chain_joints.iter().copied())
            .collect();
        let drive = Drive::Fly(Box::new(flight));
        Self::start(Self::bare(c, controller, TURN_RATE, drive)?.turning(&turned))
    }

    /// A swimmer's animator: at its swimming height over flat ground.
    pub(super) fn swimmer(c: &Creature) -> Result<Self, Error> {
        let params = SwimParams::DEFAULT;
        let (spine, along) = swim_spine(c);
        let limits = c.bend_limits();
        // The wave's share at each place, for the swimming wave (full weight) and the idle
        // sway over a period each (any blend of the two then keeps within the limits).
        let samples = 64;
        let unit = unit_swim(&params);
        let scale = bend_scale(&limits, &spine, 2 * samples, |f, i| {
            let (t, speed) = if f < samples {
                (f as f32 / samples as f32, params.full_speed)
            } else {
                ((f - samples) as f32 / samples as f32, 0.0)
            };
            unit.bone_yaw(t, speed, along[i]) - unit.bone_yaw(t, speed, along[i - 1])
        });
        let bends = c.turn_bend_shares();
        let turn_share = spine
            .iter()
            .map(|&j| {
                bends
                    .iter()
                    .find(|b| b.0 == j)
                    .map_or(0.0, |&(_, divisor, _)| 1.0 / divisor)
            })
            .collect();
        // The swimming height of its clip (raised where a fin would dip into the ground).
        let rest_root = c.rest_root();
        let clip_lift = |clip: &super::Clip| {
            clip.root_translation
                .first()
                .map_or(0.0, |t| (t.y - rest_root.y).max(0.0))
        };
        let lift = match c.clips.iter().find(|clip| clip.name == "swim") {
            Some(clip) => clip_lift(clip),
            None => clip_lift(&swim(c, "swim", c.speed)),
        };
        // Each joint's skin reaches down to its lowest vertex at rest (the wave turns the
        // spine about the vertical; the fins' dips are the clip's lift).
        let below = rest_below(c).into_iter().map(|b| b + lift).collect();
        let swimming = Swimming {
            hold: Hold {
                height: lift + SWIM_CLEARANCE * c.length,
                radius: skin_radius(c),
                below,
                clearance: 0.5 * SWIM_CLEARANCE * c.length,
                speed: 0.0,
                frequency: REST_WAVE * params.frequency,
            },
            params,
            limits: spine
                .iter()
                .map(|&j| limits.get(j).copied().unwrap_or(f32::INFINITY))
                .collect(),
            spine,
            along,
            scale,
            turn_share,
            fins: fin_joints(c),
            wave: 0.0,
            idle: 0.0,
        };
        let controller = Controller::chains_only(c.length.max(1e-3), &GaitOptions::DEFAULT)?;
        // The spine's bones between the root and the tail's tip, and the fins.
        let bones = swimming.spine.len().saturating_sub(1);
        let turned: Vec<usize> = (swimming.spine.iter().take(bones).skip(1).copied())
            .chain(swimming.fins.iter().map(|f| f.0))
            .collect();
        let drive = Drive::Swim(Box::new(swimming));
        Self::start(Self::bare(c, controller, TURN_RATE, drive)?.turning(&turned))
    }

    /// Marks `joints` as turned by the drive (their local rotations change).
    pub(super) fn turning(mut self, joints: &[usize]) -> Self {
        for &j in joints {
            if let Some(turns) = self.turns.get_mut(j) {
                *turns = true;
            }
        }
        self
    }

    /// Poses a new flier or swimmer over flat ground at `y = 0`; its first update starts
    /// afresh.
    fn start(mut self) -> Result<Self, Error> {
        self.update(0.0, super::Intent::Stand, &creature_gait::Plane::GROUND)?;
        self.fresh = true;
        Ok(self)
    }

    /// Where a flier or swimmer goes in `dt` at `velocity` turning at `turn_rate`: its model
    /// origin follows the highest ground under and ahead of it (held `height` above it; a
    /// landing flier's `landing = (plane, share)`, that share of the way from there to the
    /// height `plane` of the ground it lands on), rising faster than it sinks; afresh, it is
    /// put there. Nothing is changed.
    fn steer<G: Ground + ?Sized>(
        &mut self,
        (hold, height, landing): (&Hold, f32, Option<(f32, f32)>),
        dt: f32,
        (velocity, turn_rate): (Vec3, f32),
        ground: &G,
    ) -> Steer {
        let (rise, share) = self.smoothing(dt);
        let speed = if self.fresh {
            velocity.norm()
        } else {
            hold.speed + (velocity.norm() - hold.speed) * share
        };
        let mut position = self.position + velocity * dt;
        let top = self.ground_top(hold, position, velocity, ground);
        if let Some(top) = top {
            let base = landing.map_or(top, |(plane, share)| top + (plane - top) * share);
            let target = base + height;
            position.y = if self.fresh {
                target
            } else {
                let k = if target > self.position.y {
                    rise
                } else {
                    share
                };
                self.position.y + (target - self.position.y) * k
            };
        }
        Steer {
            heading: super::wrap(self.heading + turn_rate * dt),
            position,
            speed,
            relative: if self.speed > 0.0 {
                (speed / self.speed).min(2.0)
            } else {
                0.0
            },
            turn: self.turn + (turn_rate - self.turn) * share,
            share,
        }
    }

    /// The highest ground under the skin's reach about `position` now and ahead along
    /// `velocity` (nine rays at each of three times), if any ray hits.
    fn ground_top<G: Ground + ?Sized>(
        &self,
        hold: &Hold,
        position: Vec3,
        velocity: Vec3,
        ground: &G,
    ) -> Option<f32> {
        let (above, below) = (RAY_ABOVE * self.length, RAY_BELOW * self.length);
        let top = self.ground_top_from(hold, (position, velocity), (above, below), ground);
        if top.is_some() || !self.fresh {
            return top;
        }
        super::put_down(
            position,
            (above, below),
            |&top| top,
            |origin, range| self.ground_top_from(hold, (origin, velocity), range, ground),
        )
    }

    /// [`ground_top`](Self::ground_top) with its rays cast from `above` the body to `below`
    /// it.
    fn ground_top_from<G: Ground + ?Sized>(
        &self,
        hold: &Hold,
        (position, velocity): (Vec3, Vec3),
        (above, below): (f32, f32),
        ground: &G,
    ) -> Option<f32> {
        use core::f32::consts::FRAC_1_SQRT_2 as D;
        let range = above + below;
        let r = hold.radius;
        let ring = [
            (0.0, 0.0),
            (r, 0.0),
            (-r, 0.0),
            (0.0, r),
            (0.0, -r),
            (D * r, D * r),
            (D * r, -D * r),
            (-D * r, D * r),
            (-D * r, -D * r),
        ];
        let mut top: Option<f32> = None;
        for ahead in [0.0, 0.5 * LOOK_AHEAD, LOOK_AHEAD] {
            let centre = position + velocity * ahead + Vec3::Y * above;
            for (x, z) in ring {
                if let Some(hit) = ground.cast_down_point(centre + Vec3::new(x, 0.0, z), range)
                    && hit.y.is_finite()
                {
                    top = Some(top.map_or(hit.y, |t| t.max(hit.y)));
                }
            }
        }
        top
    }

    /// Every joint's world transform from the local ones (parents first).
    pub(super) fn forward_kinematics(&mut self) {
        for &j in &self.order {
            self.world[j] = match self.parents[j] {
                Some(p) => self.world[p] * self.local[j],
                None => self.local[j],
            };
        }
    }

    /// Lifts the whole pose (and the position) so that each joint's skin, reaching
    /// `below(joint)` under it, clears the ground under the joint by `clearance`.
    fn keep_above<G: Ground + ?Sized>(
        &mut self,
        (below, rims): (impl Fn(usize) -> f32, Option<&[[Vec3A; 8]]>),
        clearance: f32,
        ground: &G,
    ) {
        let above = RAY_ABOVE * self.length;
        let mut lift = 0.0f32;
        for (joint, world) in self.world.iter().enumerate() {
            let below = below(joint);
            let p = Vec3::from(world.translation);
            let from = p + Vec3::Y * above;
            let range = 2.0 * above + below;
            let Some(hit) = ground.cast_down_point(from, range) else {
                continue;
            };
            lift = lift.max(hit.y + below + clearance - p.y);
            // Near the ground, its skin's bottom rim above the ground under each of its
            // points too (on a slope, the rim's uphill side is nearer the ground).
            let Some(rim) = rims.and_then(|rims| rims.get(joint)) else {
                continue;
            };
            let reach = rim
                .iter()
                .map(|d| d.x.abs().max(d.z.abs()))
                .fold(0.0, f32::max);
            if p.y - below - clearance - hit.y < 2.0 * reach {
                for &d in rim {
                    let q = Vec3::from(world.transform_point3a(d));
                    let from = Vec3::new(q.x, from.y, q.z);
                    if let Some(hit) = ground.cast_down_point(from, from.y - q.y + range) {
                        lift = lift.max(hit.y + clearance - q.y);
                    }
                }
            }
        }
        if lift > 0.0 && lift.is_finite() {
            self.position.y += lift;
            self.local[self.root].translation.y += lift;
            for world in &mut self.world {
                world.translation.y += lift;
            }
        }
    }

    /// A flier's update (see [`update`](Self::update)): steered by `velocity` and
    /// `turn_rate`, banking into the turn and pitching as it climbs, its wings beating faster
    /// and wider the faster it flies; told to `stand`, it lands (and takes off when it is told
    /// anything else).
    pub(super) fn fly<G: Ground + ?Sized>(
        &mut self,
        flight: &mut Flight,
        dt: f32,
        (velocity, turn_rate, stand): (Vec3, f32, bool),
        ground: &G,
    ) -> Result<(), Error> {
        // Landing: coming down onto its rest pose, the wings and the chains settling; taking
        // off, it rises before it flies off.
        let before = self.position.y;
        let landed = if stand {
            (flight.landed + dt / LANDING_TIME).min(1.0)
        } else {
            (flight.landed - dt / TAKE_OFF_TIME).max(0.0)
        };
        let down = landed * landed * (3.0 - 2.0 * landed);
        let (velocity, turn_rate) = (velocity * (1.0 - down), turn_rate * (1.0 - down));
        // Landing, it comes down onto the plane of the ground under its footprint, leaning
        // with it.
        let plane = if down > 0.0 {
            let above = RAY_ABOVE * self.length;
            ground_plane(
                ground,
                (self.position, Quat::from_rotation_y(self.heading)),
                &flight.footprint,
                (above, above + RAY_BELOW * self.length),
            )
        } else {
            None
        };
        let Steer {
            heading,
            position,
            speed,
            relative,
            turn,
            share,
        } = self.steer(
            (
                &flight.hold,
                flight.hold.height * (1.0 - down) - flight.rest_lift * down,
                plane.map(|(height, _)| (height, down)),
            ),
            dt,
            (velocity, turn_rate),
            ground,
        );
        // Wings: beats faster and wider with speed; the body bobs with them.
        let flap = &flight.flap;
        let frequency = flap.frequency * (HOVER_BEAT + (1.0 - HOVER_BEAT) * relative);
        let amplitude = (flap.amplitude * (HOVER_SWEEP + (1.0 - HOVER_SWEEP) * relative)).min(1.5)
            * (1.0 - down);
        let beat = fract(flight.beat + frequency * dt);
        let bob_phase = fract(flight.bob + flap.idle_frequency * dt);
        // The flap with its phases in turns: a frequency of 1 per turn.
        let unit = flap
            .with_frequency(1.0)
            .with_idle_frequency(1.0)
            .with_amplitude(amplitude)
            .with_bias(flap.bias * (1.0 - down))
            .with_bob(flap.bob * (1.0 - down));
        let bob = unit.body_bob(if flight.buzzing { bob_phase } else { beat }, speed);
        // The chains swing with the bob in the body's frame, as in the `fly` clip.
        flight.chains.update(dt, Vec3::Y * bob)?;
        flight.chains.rotations_into(
            &self.parents,
            &mut flight.global,
            &mut flight.chain_rotations,
        )?;
        // Banked into the turn (its up tilted toward the side it turns to) as far as it turns
        // and flies, pitched up climbing and down diving.
        let bank = -MAX_BANK * (turn / self.max_turn_rate).clamp(-1.0, 1.0) * relative.min(1.0);
        let climb = if dt > 0.0 && !self.fresh {
            (position.y - self.position.y) / dt
        } else {
            0.0
        };
        // Only flying forward: hovering (and landing) it climbs and sinks level.
        let glide = speed.max(1e-3);
        let pitch_target = -glam::Vec2::new(glide, climb)
            .to_angle()
            .clamp(-MAX_PITCH, MAX_PITCH)
            * relative.min(1.0);
        let pitch = flight.pitch + (pitch_target - flight.pitch) * share;
        let lean_target = plane.map_or(glam::Vec2::ZERO, |(_, lean)| lean * down);
        let lean = if self.fresh {
            lean_target
        } else {
            flight.lean + (lean_target - flight.lean) * share
        };
        flight.lean = lean;
        (self.position, self.heading, self.turn) = (position, heading, turn);
        (flight.beat, flight.bob, flight.pitch) = (beat, bob_phase, pitch);
        flight.landed = landed;
        (flight.hold.speed, flight.hold.frequency) = (speed, frequency);
        self.fresh = false;
        let yaw = Quat::from_rotation_y(heading);
        let rotation =
            (yaw * Quat::from_rotation_x(pitch + lean.x) * Quat::from_rotation_z(bank + lean.y))
                .unit();
        self.local[self.root] = Affine3A::from_rotation_translation(
            rotation,
            position + yaw * self.rest_root + Vec3::Y * bob,
        );
        for &(joint, sign, k) in &flight.wings {
            self.local[joint] = Affine3A::from_rotation_translation(
                wing_joint_rotation(&unit, beat, sign, k),
                self.rest_local[joint],
            );
        }
        for ((&joint, &limit), &rotation) in flight
            .chain_joints
            .iter()
            .zip(&flight.chain_limits)
            .zip(&flight.chain_rotations)
        {
            // Landed, the legs stand at rest (reaching down) and the tail rests.
            let mut rotation = chain_bend_limited(rotation, limit);
            if down > 0.0 {
                rotation = rotation.slerp(Quat::IDENTITY, down);
            }
            self.local[joint] =
                Affine3A::from_rotation_translation(rotation.unit(), self.rest_local[joint]);
        }
        self.forward_kinematics();
        let hold = &flight.hold;
        let rest = &flight.rest_below;
        self.keep_above(
            (
                |j| hold.below[j] + (rest[j] - hold.below[j]) * down,
                // Landing, its skin's bottom rims too.
                (down > 0.0).then_some(&flight.rims[..]),
            ),
            hold.clearance * (1.0 - down),
            ground,
        );
        flight.sink = (self.position.y - before).abs();
        self.skin();
        Ok(())
    }

    /// A swimmer's update (see [`update`](Self::update)): steered by `velocity` and
    /// `turn_rate`, its body bent toward the turn, its wave faster the faster it swims.
    pub(super) fn swim<G: Ground + ?Sized>(
        &mut self,
        swimming: &mut Swimming,
        dt: f32,
        (velocity, turn_rate): (Vec3, f32),
        ground: &G,
    ) -> Result<(), Error> {
        let Steer {
            heading,
            position,
            speed,
            relative,
            turn,
            ..
        } = self.steer(
            (&swimming.hold, swimming.hold.height, None),
            dt,
            (velocity, turn_rate),
            ground,
        );
        let params = &swimming.params;
        let frequency = params.frequency * (REST_WAVE + (1.0 - REST_WAVE) * relative);
        let wave = fract(swimming.wave + frequency * dt);
        let idle = fract(swimming.idle + params.idle_frequency * dt);
        (self.position, self.heading, self.turn) = (position, heading, turn);
        (swimming.wave, swimming.idle) = (wave, idle);
        (swimming.hold.speed, swimming.hold.frequency) = (speed, frequency);
        self.fresh = false;
        // The wave swims fully from half the creature's speed; below, it blends with the sway.
        let weight = relative.min(0.5) * 2.0;
        let unit = unit_swim(params);
        let yaw_at = |u: f32| {
            weight * unit.bone_yaw(wave, params.full_speed, u)
                + (1.0 - weight) * unit.bone_yaw(idle, 0.0, u)
        };
        let bend = turn_bend_total(turn);
        let yaw = Quat::from_rotation_y(heading);
        let mut previous = yaw_at(swimming.along.first().copied().unwrap_or(1.0));
        self.local[self.root] = Affine3A::from_rotation_translation(
            (yaw * Quat::from_rotation_y(previous)).unit(),
            position + yaw * self.rest_root,
        );
        // Each spine bone's yaw relative to its parent's, with its share of the turn's bend,
        // within its skin's limit (not the root, not the tail tip).
        let bones = swimming.spine.len().saturating_sub(1);
        for i in 1..bones {
            let now = yaw_at(swimming.along[i]);
            let limit = swimming.limits[i];
            let angle = (swimming.scale[i] * (now - previous) + bend * swimming.turn_share[i])
                .max(-limit)
                .min(limit);
            previous = now;
            let joint = swimming.spine[i];
            self.local[joint] = Affine3A::from_rotation_translation(
                Quat::from_rotation_y(angle),
                self.rest_local[joint],
            );
        }
        for &(joint, motion, sign, k) in &swimming.fins {
            self.local[joint] = Affine3A::from_rotation_translation(
                fin_rotation(params, motion, wave, sign, k),
                self.rest_local[joint],
            );
        }
        self.forward_kinematics();
        let hold = &swimming.hold;
        self.keep_above((|j| hold.below[j], None), hold.clearance, ground);
        self.skin();
        Ok(())
    }

    /// A flier's wing beats or a swimmer's or slitherer's body waves per second in the last
    /// update (they follow its speed); `None` for a walker. (A landing flier's wings slow their sweep to
    /// rest, not their rate.)
    #[must_use]
    pub fn beat_frequency(&self) -> Option<f32> {
        match &self.drive {
            Drive::Walk => None,
            Drive::Fly(flight) => Some(flight.hold.frequency),
            Drive::Swim(swimming) => Some(swimming.hold.frequency),
            Drive::Slither(slithering) => Some(slithering.frequency()),
        }
    }
}

/// `params` with its phases in turns: a frequency of 1 per turn for the wave and the sway.
fn unit_swim(params: &SwimParams) -> SwimParams {
    params
        .with_wiggle(1.0, params.amplitude)
        .with_idle(1.0, params.idle_amplitude)
}
