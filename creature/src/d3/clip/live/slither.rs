//! The live animator's slitherers: lateral undulation without slip. The head crawls along a
//! path whose heading swings from side to side (a serpenoid: the heading is the way it goes
//! plus `amplitude · sin(2π s / wavelength)` at the path's length `s`), and every joint of
//! the spine lies on the path the head has crawled, so the wave travels from head to tail as
//! fast as the body moves forward and no part of the body slides sideways (as a snake in
//! grass, pushing against what it passes). The path turns where the creature steers, so its
//! body bends into the turn and follows it. Each joint lies on the ground under it, its bone
//! tilted with the ground's slope.

use alloc::vec::Vec;

use glam::{Affine3A, Mat3A, Quat, Vec2, Vec3, Vec3A};

use creature_gait::Ground;

use super::super::swim::swim_spine;
use super::{Animator, fract, tilted};
use crate::Error;
use crate::d3::Creature;
use crate::math::Roots;

/// The most the path's heading swings either side of the way the creature goes (radians), and
/// the least: a thick body's wave is as large as its skin allows in between.
pub(crate) const SLITHER_AMPLITUDE: f32 = 0.6;
const MIN_AMPLITUDE: f32 = 0.25;

/// The share of the sharpest curve its skin allows (each joint's bend limit over its bones)
/// that the wave's sharpest bend takes, and that its tightest turn takes on top of it. (The
/// limits are cautious: the audit measures the skin itself.)
const BEND_SHARE: f32 = 0.7;

/// The body wave's length along the path, in body lengths: more than the body, so each wave
/// carries it forward more than its length (the path's length over the ground it covers is
/// [`Slithering::stretch`]).
pub(crate) const SLITHER_WAVELENGTH: f32 = 1.25;

/// Points of the head's path kept per wavelength.
const PATH_SAMPLES: usize = 80;

/// The tightest a slitherer's path ever turns, as curvature × body length: a circle a quarter
/// of its length in radius.
const MAX_CURVATURE: f32 = 4.0;

/// Lying still, it raises the front of its body: the head this many body lengths (bobbing by
/// a quarter of it, this many times a second), less and less over this share of the body from
/// the head. (It does not sway: the wave's bends leave its skin too little to bend further.)
const IDLE_LIFT: f32 = 0.06;
const IDLE_LIFT_REACH: f32 = 0.3;
pub(crate) const IDLE_RATE: f32 = 0.3;

/// Rays down for the ground under a joint start this many body lengths above the ground it
/// lay on in the last update and reach as far below it.
const RAY_REACH: f32 = 2.0;

/// A slitherer's body wave and the path it crawls along.
#[derive(Debug, Clone)]
pub(in crate::d3::clip) struct Slithering {
    /// The spine from the head (the root) toward the tail's tip: its joints, each one's
    /// distance from the head along the rest spine over the ground (metres), and each one's
    /// height over the ground at rest.
    spine: Vec<usize>,
    arc: Vec<f32>,
    rise: Vec<f32>,
    /// Per spine bone (joint `i` to `i + 1`): its rest frame's inverse (side, up, along the
    /// bone toward the tail, as rows).
    rest_frames: Vec<Mat3A>,
    /// The wave's amplitude (radians) and length (metres of path).
    amplitude: f32,
    wavelength: f32,
    /// Metres of path per metre the body covers over the ground.
    stretch: f32,
    /// The tightest its path turns (per metre).
    curvature: f32,
    /// Metres of path between two kept points.
    step: f32,
    /// The head's path: a ring of its points (x, z), `step` apart, the newest at `newest`.
    path: Vec<Vec2>,
    newest: usize,
    /// Points added, modulo [`PATH_SAMPLES`]: the wave's phase at the newest point.
    count: usize,
    /// How far the head is past the newest point (metres of path, less than `step`).
    past: f32,
    /// The idle bob's phase (turns).
    idle: f32,
    /// The speed over the ground (m/s), smoothed, and the waves per second of the last update.
    speed: f32,
    frequency: f32,
    /// Per spine joint, the ground under it in the last update: height and normal.
    ground: Vec<(f32, Vec3)>,
    /// Scratch per spine bone: first how far along the path it reaches (indexed by its end
    /// joint), then how far its joints rise for it to clear the ground (by its first joint).
    raise: Vec<f32>,
    /// Whether the spine is every joint of the skeleton (none to pose by forward kinematics).
    whole: bool,
}

/// The unit direction (x, z) of a path heading `angle` (radians from +Z toward +X).
fn direction(angle: f32) -> Vec2 {
    Vec2::new(crate::math::sin(angle), crate::math::cos(angle))
}

impl Slithering {
    /// The wave's phase (turns) halfway between the path's points `count` and `count + 1`.
    fn mid_phase(count: isize) -> f32 {
        let samples = PATH_SAMPLES as isize;
        (count.rem_euclid(samples) as f32 + 0.5) / PATH_SAMPLES as f32
    }

    /// The path's heading at `phase` (turns) of the wave, the way it goes being `heading`.
    fn heading_at(&self, heading: f32, phase: f32) -> f32 {
        heading + self.amplitude * crate::math::sin(core::f32::consts::TAU * phase)
    }

    /// The ring's index `k` points older than the newest (`k` less than the ring's length).
    fn older(&self, k: usize) -> usize {
        debug_assert!(
            k < self.path.len(),
            "{k} points back in a ring of {}",
            self.path.len()
        );
        // (No division: this is in the pose's innermost loop.)
        if k <= self.newest {
            self.newest - k
        } else {
            self.newest + self.path.len() - k
        }
    }

    /// A path as if the head had always crawled straight along `heading` to `head`, the wave
    /// at phase 0 there.
    fn fill(&mut self, head: Vec2, heading: f32) {
        self.newest = 0;
        self.count = 0;
        self.past = 0.0;
        self.path[0] = head;
        for k in 1..self.path.len() {
            let phase = Self::mid_phase(-(k as isize));
            let back = direction(self.heading_at(heading, phase)) * self.step;
            let (from, to) = (self.older(k - 1), self.older(k));
            self.path[to] = self.path[from] - back;
        }
    }

    /// The head crawls `distance` metres further along its path, which goes along `heading`.
    /// A crawl past every point kept (a creature edited to crawl its length many times in
    /// one update) is taken straight along `heading`, the path behind it filled afresh.
    fn advance(&mut self, distance: f32, heading: f32) {
        let kept = self.step * self.path.len() as f32;
        if !(self.past + distance < kept) {
            let head = self.head(heading) + direction(heading) * distance;
            self.fill(head, heading);
            return;
        }
        self.past += distance;
        while self.past >= self.step {
            let phase = Self::mid_phase(self.count as isize);
            let next =
                self.path[self.newest] + direction(self.heading_at(heading, phase)) * self.step;
            self.newest = (self.newest + 1) % self.path.len();
            self.path[self.newest] = next;
            self.count = (self.count + 1) % PATH_SAMPLES;
            self.past -= self.step;
        }
    }

    /// Where the head is (x, z), the path going along `heading`.
    fn head(&self, heading: f32) -> Vec2 {
        let phase = Self::mid_phase(self.count as isize);
        self.path[self.newest] + direction(self.heading_at(heading, phase)) * self.past
    }

    /// The path's point `behind` metres behind the head at `head` (the oldest kept point
    /// beyond the path's end).
    fn point(&self, behind: f32, head: Vec2) -> Vec2 {
        if behind <= self.past {
            if self.past <= 0.0 {
                return head;
            }
            return head.lerp(self.path[self.newest], behind / self.past);
        }
        let back = (behind - self.past) / self.step;
        let k = crate::math::floor_f(back);
        let last = self.path.len() - 1;
        let at = k as usize;
        if at >= last {
            return self.path[self.older(last)];
        }
        self.path[self.older(at)].lerp(self.path[self.older(at + 1)], back - k)
    }

    /// The body waves per second, crawling at `speed` (m/s over the ground).
    pub(in crate::d3::clip) fn frequency_at(&self, speed: f32) -> f32 {
        speed * self.stretch / self.wavelength
    }

    /// The waves per second of the last update.
    pub(super) const fn frequency(&self) -> f32 {
        self.frequency
    }

    /// The speed over the ground (m/s), smoothed.
    pub(super) const fn speed(&self) -> f32 {
        self.speed
    }
}

impl Animator {
    /// A slitherer's animator: lying straight on flat ground, its body in the wave's shape.
    pub(super) fn slitherer(c: &Creature) -> Result<Self, Error> {
        if !c.speed.is_finite() {
            return Err(Error::NonFinite {
                what: "creature speed",
            });
        }
        // (At most as fast as a place may be far from the origin: its crawl in an update stays
        // a number.)
        let fastest = creature_gait::MAX_COORDINATE;
        if !(0.0..=fastest).contains(&c.speed) {
            return Err(Error::OutOfRange {
                what: "creature speed",
                value: c.speed,
                min: 0.0,
                max: fastest,
            });
        }
        let (spine, _) = swim_spine(c);
        if spine.len() < 2 {
            return Err(Error::Degenerate {
                what: "slitherer spine (fewer than two joints)",
            });
        }
        // A chain from the head, each joint the next one's parent.
        let joints = &c.skeleton.joints;
        if let Some(&root) = spine.first()
            && let Some(parent) = joints.get(root).and_then(|j| j.parent)
        {
            return Err(Error::BadParent {
                bone: root,
                parent: Some(parent),
            });
        }
        for pair in spine.windows(2) {
            let parent = joints.get(pair[1]).and_then(|j| j.parent);
            if pair[0] >= joints.len() || parent != Some(pair[0]) {
                return Err(Error::BadParent {
                    bone: pair[1],
                    parent,
                });
            }
        }
        let rest: Vec<Vec3> = spine
            .iter()
            .map(|&j| c.skeleton.joints[j].position)
            .collect();
        let mut arc = Vec::with_capacity(spine.len());
        let mut along = 0.0f32;
        for (i, p) in rest.iter().enumerate() {
            if i > 0 {
                along += Vec2::new(p.x - rest[i - 1].x, p.z - rest[i - 1].z).norm();
            }
            arc.push(along);
        }
        let rest_frames = rest
            .windows(2)
            .map(|pair| {
                let along = (pair[1] - pair[0]).unit_or(Vec3::NEG_Z);
                frame(along, Vec3::Y).transpose()
            })
            .collect();
        let bend = c.bend_limits();
        let limits: Vec<f32> = spine
            .iter()
            .map(|&j| bend.get(j).copied().unwrap_or(f32::INFINITY))
            .collect();
        let limits_of = |i: usize| Some(limits[i]).filter(|l| l.is_finite());
        let length = c.length.max(1e-3);
        let wavelength = SLITHER_WAVELENGTH * length;
        // The wave's amplitude: its sharpest bend (the serpenoid's curvature peaks at
        // `2π · amplitude / wavelength`) within [`BEND_SHARE`] of each joint's limit over the
        // bones either side, but at least [`MIN_AMPLITUDE`].
        // The sharpest curve its skin allows: each joint's limit over its bones either side.
        let bendable = (1..spine.len() - 1)
            .filter_map(|i| Some(limits_of(i)? / (0.5 * (arc[i + 1] - arc[i - 1]))))
            .fold(f32::INFINITY, f32::min);
        // (`bendable` is a number: `f32::min` passes NaN over.)
        let amplitude = (BEND_SHARE * bendable * wavelength / core::f32::consts::TAU)
            .clamp(MIN_AMPLITUDE, SLITHER_AMPLITUDE);
        // Its tightest turn: as much again, at most [`MAX_CURVATURE`].
        let curvature = (BEND_SHARE * bendable).min(MAX_CURVATURE / length);
        let step = wavelength / PATH_SAMPLES as f32;
        // The path's points span the body and two more.
        let points = crate::math::ceil_non_negative(along / step) + 3;
        let slithering = Slithering {
            rise: rest.iter().map(|p| p.y).collect(),
            ground: alloc::vec![(0.0, Vec3::Y); spine.len()],
            raise: alloc::vec![0.0; spine.len()],
            whole: spine.len() == joints.len(),

            spine,
            arc,
            rest_frames,
            amplitude,
            wavelength,
            stretch: 1.0 / mean_cos(amplitude),
            curvature,
            step,
            path: alloc::vec![Vec2::ZERO; points],
            newest: 0,
            count: 0,
            past: 0.0,
            idle: 0.0,
            speed: 0.0,
            frequency: 0.0,
        };
        let controller =
            creature_gait::Controller::chains_only(length, &creature_gait::GaitOptions::DEFAULT)?;
        let bones = slithering.spine.len() - 1;
        let turned: Vec<usize> = slithering.spine[1..bones].to_vec();
        let max_turn = curvature * c.speed * slithering.stretch;
        let drive = super::Drive::Slither(alloc::boxed::Box::new(slithering));
        let mut animator = Self::bare(c, controller, max_turn, drive)?.turning(&turned);
        animator.update(0.0, super::Intent::Stand, &creature_gait::Plane::GROUND)?;
        animator.fresh = true;
        Ok(animator)
    }

    /// A slitherer's update (see [`update`](Self::update)): it crawls forward along its
    /// heading at the speed of `velocity`'s part along it, turning at `turn_rate`, no tighter
    /// than [`Slithering::curvature`] allows (asked to turn faster than its crawl allows, it
    /// crawls faster, up to its speed).
    ///
    /// (One body for every ground: its rays through a virtual call, which costs little
    /// against the pose, and keeps one copy of it in a WebAssembly module.)
    pub(super) fn slither(
        &mut self,
        s: &mut Slithering,
        dt: f32,
        (velocity, turn_rate): (Vec3, f32),
        ground: &dyn Ground,
    ) -> Result<(), Error> {
        let (share, _) = self.smoothing(dt);
        let forward = direction(self.heading);
        let wanted = (velocity.x * forward.x + velocity.z * forward.y).max(0.0);
        let mut speed = if self.fresh {
            wanted
        } else {
            s.speed + (wanted - s.speed) * share
        };
        // A turn needs the body to crawl along it: at least fast enough for the turn's circle.
        let curvature = s.curvature;
        let creep = if curvature > 0.0 {
            (turn_rate.abs() / (curvature * s.stretch)).min(self.speed)
        } else {
            0.0
        };
        speed = speed.max(creep);
        let path_speed = speed * s.stretch;

        let turn = turn_rate.clamp(-curvature * path_speed, curvature * path_speed);
        let heading = super::wrap(self.heading + turn * dt);
        let yaw = Quat::from_rotation_y(heading);
        let root_offset = yaw * self.rest_root;
        if self.fresh {
            let head = Vec2::new(
                self.position.x + root_offset.x,
                self.position.z + root_offset.z,
            );
            s.fill(head, heading);
        } else {
            s.advance(path_speed * dt, heading);
        }
        s.idle = fract(s.idle + IDLE_RATE * dt);
        let relative = if self.speed > 0.0 {
            speed / self.speed
        } else {
            0.0
        };
        // Lying still it raises its front; crawling from half its speed, not at all.
        let still = 1.0 - (2.0 * relative).min(1.0);

        let head = s.head(heading);
        // Each joint on the ground under its place on the path, straight above it by its rest
        // height over the ground's normal (`rise / normal.y`).
        let reach = RAY_REACH * self.length;
        let fresh_height = self.position.y;
        // Each joint its bone's length from the one before: as far along the path as the bone
        // reaches level, less where the ground climbs or falls that way (its slope in the last
        // update under the joint before, at most 45°, along the bone before that; for the
        // first bone, along the path at the head), so the bones reach their places on a hill
        // too. Each bone's share of the path is found first, then every place along it, then
        // the ground under each (nothing waits on a ray): afresh, twice, the second time with
        // the slopes and the bones the first found.
        let n = s.spine.len();
        for _ in 0..1 + usize::from(self.fresh) {
            // Per bone (its end joint `i`), how far along the path it reaches (scratch).
            for i in 1..n {
                let ahead = if i == 1 {
                    s.point(s.step, head) - head
                } else {
                    let a = Vec3::from(
                        self.world[s.spine[i - 1]].translation
                            - self.world[s.spine[i - 2]].translation,
                    );
                    Vec2::new(a.x, a.z)
                };
                let normal = s.ground[i - 1].1;
                // The slope's square (at most 1), without a root: (n · a)² / (n_y² |a|²).
                let rise = normal.x * ahead.x + normal.z * ahead.y;
                let run = normal.y * normal.y * ahead.length_squared().max(1e-18);
                let slope2 = if normal.y > 0.0 {
                    (rise * rise / run).min(1.0)
                } else {
                    0.0
                };
                s.raise[i] = (s.arc[i] - s.arc[i - 1]) / crate::math::sqrt(1.0 + slope2);
            }
            let mut behind = 0.0;
            let bob = 0.75 + 0.25 * crate::math::sin(core::f32::consts::TAU * s.idle);
            for i in 0..n {
                if i > 0 {
                    behind += s.raise[i];
                }
                let at = s.point(behind, head);
                let mut lift = 0.0;
                let lifted = behind / (IDLE_LIFT_REACH * self.length);
                if still > 0.0 && lifted < 1.0 {
                    lift = still * bob * IDLE_LIFT * self.length * (1.0 - lifted) * (1.0 - lifted);
                }
                // Kept in the scratch of its world transform: the place (x, z) and its lift.
                self.world[s.spine[i]].translation = Vec3::new(at.x, lift, at.y).into();
            }
            for i in 0..s.spine.len() {
                let placed = Vec3::from(self.world[s.spine[i]].translation);
                let (at, lift) = (Vec2::new(placed.x, placed.z), placed.y);
                let last = if self.fresh {
                    fresh_height
                } else {
                    s.ground[i].0
                };
                let cast = |origin: Vec3, (above, below): (f32, f32)| {
                    ground
                        .cast_down(origin + Vec3::Y * above, above + below)
                        .filter(creature_gait::RayHit::is_valid)
                };
                let origin = Vec3::new(at.x, last, at.y);
                let hit = if self.fresh {
                    super::put_down(origin, (reach, reach), |h| h.point.y, cast)
                } else {
                    cast(origin, (reach, reach))
                };
                s.ground[i] = match hit {
                    // (A unit normal, as a ground's should be, is taken as it is.)
                    Some(hit) if (hit.normal.length_squared() - 1.0).abs() <= 1e-6 => {
                        (hit.point.y, hit.normal)
                    }
                    Some(hit) => (hit.point.y, hit.normal.unit_or(Vec3::Y)),
                    None => (last, Vec3::Y),
                };
                // The joint's place, kept in the same scratch: straight above the ground, as
                // high as its rest height along the normal puts it on a plane (at most twice as
                // high, on a step's face).
                let (height, normal) = s.ground[i];
                let up = (s.rise[i] + lift) / normal.y.max(0.5);
                let joint = Vec3::new(at.x, height + up, at.y);
                self.world[s.spine[i]].translation = joint.into();
            }
        }
        // Each bone clear of the ground under its middle (a crest or a step's edge between two
        // joints): both its joints raised as far as its middle is short of its height there.
        // Where the ground under its joints is one plane (their normals alike, its height
        // between them as that plane has it), its middle is taken to be on it: no ray is cast
        // (an obstacle narrower than a bone between them, on a ground of your own, is not
        // seen).
        for i in 0..s.spine.len() - 1 {
            let (a, b) = (
                Vec3::from(self.world[s.spine[i]].translation),
                Vec3::from(self.world[s.spine[i + 1]].translation),
            );
            let ((ground_a, normal_a), (ground_b, normal_b)) = (s.ground[i], s.ground[i + 1]);
            let normal = normal_a + normal_b;
            let run = b - a;
            let planar = normal_a.dot(normal_b) > PLANAR
                && normal.y > 0.0
                && ((ground_b - ground_a) * normal.y + normal.x * run.x + normal.z * run.z).abs()
                    < PLANAR_GAP * run.norm() * normal.y;
            if planar {
                s.raise[i] = 0.0;
                continue;
            }
            let middle = 0.5 * (a + b);
            let rise = 0.5 * (s.rise[i] + s.rise[i + 1]);
            let origin = Vec3::new(middle.x, middle.y + reach, middle.z);
            s.raise[i] = ground
                .cast_down_point(origin, 2.0 * reach)
                .map_or(0.0, |hit| (hit.y + rise - middle.y).max(0.0));
        }
        let last = s.spine.len() - 1;
        for i in 0..=last {
            let before = if i > 0 { s.raise[i - 1] } else { 0.0 };
            let after = if i < last { s.raise[i] } else { 0.0 };
            self.world[s.spine[i]].translation.y += before.max(after);
        }
        // Each bone along the path, its up the ground's normal: its turn made afresh from the
        // two frames (orthonormal), so no rounding grows down the chain.
        // Where the joint is as posed so far (a bone is as long as it is, so its end may miss
        // its place a little: the next one aims at its own place from there), and the turn of
        // the bone before. Each joint's world transform is set here (its local one too): the
        // spine's forward kinematics, done as it is posed.
        let mut at = self.world[s.spine[0]].translation;
        let mut parent = Mat3A::IDENTITY;
        let back = -Vec3::new(forward.x, 0.0, forward.y);
        let last = s.spine.len() - 1;
        let cos_tilt2 = crate::math::cos(MAX_TILT) * crate::math::cos(MAX_TILT);
        for i in 0..last {
            let to = self.world[s.spine[i + 1]].translation;
            let along = Vec3::from(to - at).unit_or(back);
            // The normals' mean, tilted at most `MAX_TILT` (unscaled where it is within: `frame`
            // takes any length).
            let sum = s.ground[i].1 + s.ground[i + 1].1;
            let normal = if sum.y > 0.0 && sum.y * sum.y >= cos_tilt2 * sum.length_squared() {
                sum
            } else {
                tilted(sum.unit_or(Vec3::Y), (MAX_TILT, crate::math::cos(MAX_TILT)))
            };
            let turn = frame(along, normal) * s.rest_frames[i];
            let joint = s.spine[i];
            self.local[joint] = if i == 0 {
                Affine3A {
                    matrix3: turn,
                    translation: at,
                }
            } else {
                Affine3A {
                    matrix3: parent.transpose() * turn,
                    translation: self.rest_local[joint].into(),
                }
            };
            self.world[joint] = Affine3A {
                matrix3: turn,
                translation: at,
            };
            parent = turn;
            at += turn * Vec3A::from(self.rest_local[s.spine[i + 1]]);
        }
        // The tail's tip: where its bone ends, turned as it.
        self.world[s.spine[last]] = Affine3A {
            matrix3: parent,
            translation: at,
        };
        let (height, _) = s.ground[0];
        self.position = Vec3::new(head.x - root_offset.x, height, head.y - root_offset.z);
        self.heading = heading;
        self.turn = turn;
        s.speed = speed;
        s.frequency = s.frequency_at(speed);
        self.fresh = false;
        if !s.whole {
            // Joints off the spine follow it.
            self.forward_kinematics();
        }
        self.skin();
        Ok(())
    }
}

/// The ground under two joints is one plane when their normals' cosine is above this and the
/// height between them is that plane's within this share of the distance between them.
const PLANAR: f32 = 0.9995;
const PLANAR_GAP: f32 = 0.01;

/// The most a slitherer's body rolls or pitches with the ground's normal under it (radians):
/// a step's face tilts the normal far more than the ground the body lies on.
const MAX_TILT: f32 = 0.35;

/// The rotation whose columns are the side, the up (`up` square to `along`, a unit vector)
/// and `along`.
fn frame(along: Vec3, up: Vec3) -> Mat3A {
    // `up` along the bone (a cliff): any up square to it (+Z and +Y are not both along it).
    let up = (up - along * up.dot(along))
        .try_unit()
        .or_else(|| (Vec3::Z - along * along.z).try_unit())
        .unwrap_or(Vec3::Y);
    let side = up.cross(along);
    Mat3A::from_cols(side.into(), up.into(), along.into())
}

/// The mean over a period of `cos(amplitude · sin θ)`: the share of its path's length a
/// serpenoid of that amplitude covers along its way.
fn mean_cos(amplitude: f32) -> f32 {
    let n = 64;
    let sum: f32 = (0..n)
        .map(|k| {
            let theta = core::f32::consts::TAU * (k as f32 + 0.5) / n as f32;
            crate::math::cos(amplitude * crate::math::sin(theta))
        })
        .sum();
    sum / n as f32
}
