//! Fliers' `hover` and `fly` clips: the wings beat by the flap motion, the body bobs and
//! drifts, and the legs, arms and tail are damped chains of a legless gait controller.

use alloc::vec::Vec;

use glam::{Quat, Vec3};

use creature_gait::{Chain, Controller, FlapParams, GaitOptions, Plane, Pose, Side};
use creature_limbs::LimbKind;

use super::kinematics::rotation_arc;
use super::{Clip, empty_clip, frames_for, loop_error, side_sign, sin_turns};
use crate::Error;
use crate::d3::Creature;

/// A flier's `hover` (speed 0) or `fly` clip.
pub(crate) fn flight(c: &Creature, name: &'static str, speed: f32) -> Result<Clip, Error> {
    let (flap, buzzing) = flap_params(c);
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
    let wings = wing_joints(c);
    let chains = flight_chain_joints(c);
    let flight = FlightChains::new(c, &chains, speed)?;
    let mut joints: Vec<usize> = wings.iter().map(|w| w.0).collect();
    joints.extend(flight.animated());
    let mut clip = empty_clip(name, fps, frames, &joints);
    let rest_root = c.rest_root();
    // The bob, and a slow figure-eight drift about the flight path (1.5% of the body
    // length hovering, 0.75% flying), once per clip, so hanging chains swing.
    let drift = c.length * if speed > 0.0 { 0.0075 } else { 0.015 };
    let offset = |t: f32| {
        let a = t / seconds;
        flap.body_offset(t, speed)
            + Vec3::new(drift * sin_turns(a), 0.0, drift * sin_turns(2.0 * a))
            + Vec3::Z * (speed * t)
    };
    let dt = 1.0 / fps;
    let limits = c.bend_limits();
    let mut flight = flight;
    // Whole clips of warm-up (at least FLIGHT_WARM_UP seconds), so the chains' start-up
    // has died away (their damping halves it in about 0.2 s) and frame 0 is in phase.
    let periods = crate::math::ceil_non_negative(FLIGHT_WARM_UP / seconds).max(1);
    let warm_up = periods * (frames - 1);
    for step in 0..warm_up + frames {
        let t = (step as f32 - warm_up as f32) * dt;
        let position = offset(t);
        // The chains are simulated in the frame that flies with the body at its steady speed
        // (their damping then acts on motion relative to the flight, as the air's would; the
        // trail is in their rest direction), so only the bob and the drift move them.
        flight.update(dt, position - Vec3::Z * (speed * t))?;
        if step < warm_up {
            continue;
        }
        let t = t.max(0.0);
        clip.root_translation.push(rest_root + position);
        clip.root_rotation.push(Quat::IDENTITY);
        let mut tracks = clip.tracks.iter_mut();
        // `wings` first: zip then takes no track past the last wing joint.
        for (&(_, sign, k), track) in wings.iter().zip(tracks.by_ref()) {
            track.rotations.push(wing_joint_rotation(&flap, t, sign, k));
        }
        for (track, rotation) in tracks.zip(flight.rotations(c)?) {
            track
                .rotations
                .push(chain_bend_limited(rotation, limits[track.joint]));
        }
    }
    // The chains' joints turn no faster than a leg's may (round the loop): a chain hanging
    // from another (legs on a long tail) is turned by the whole tail above it, and its hip
    // would otherwise whip round as the tail swings.
    let max_turn = super::walk::MAX_LEG_TURN_RATE / fps;
    for track in clip.tracks.iter_mut().skip(wings.len()) {
        super::limit_looping_turn_rate(&mut track.rotations, max_turn);
    }
    // Clear of the ground in every frame: the lowest any vertex can be (each joint's height
    // less the reach of the vertices it moves), lifted to the clearance.
    let reach = c.joint_reach();
    let mut lowest = f32::INFINITY;
    for f in 0..frames {
        for (m, r) in super::pose(c, &clip, f).iter().zip(&reach) {
            lowest = lowest.min(m.translation.y - r);
        }
    }
    let lift = (FLIGHT_CLEARANCE * c.length - lowest).max(0.0);
    for t in &mut clip.root_translation {
        t.y += lift;
    }
    clip.loop_error = loop_error(&clip);
    Ok(clip)
}

/// A flier's wing beat (buzzing wings at 8 beats per second, the fastest a 30 fps clip
/// shows), and whether its wings buzz.
pub(super) fn flap_params(c: &Creature) -> (FlapParams, bool) {
    let buzzing = c.plan.limbs_of(LimbKind::BuzzingWing).count() > 0;
    let flap = if buzzing {
        FlapParams::BUZZING.with_frequency(8.0)
    } else {
        FlapParams::FLAPPING
    };
    (flap, buzzing)
}

/// A flier's wing joints: each with its side's sign (+1 left) and its place along its wing
/// (0 at the root).
pub(super) fn wing_joints(c: &Creature) -> Vec<(usize, f32, usize)> {
    let mut wings = Vec::new();
    for (index, limb) in c.plan.limbs.iter().enumerate() {
        if matches!(limb.kind, LimbKind::BuzzingWing | LimbKind::FlappingWing) {
            let sign = side_sign(limb.side);
            for (k, joint) in c.limb_joints(index).into_iter().enumerate() {
                wings.push((joint, sign, k));
            }
        }
    }
    wings
}

/// A flier's damped chains: its legs and arms (hanging under gravity) and its tail (with the
/// spine joint it hangs from as the tip), each with its gravity.
pub(super) fn flight_chain_joints(c: &Creature) -> Vec<(Vec<usize>, f32)> {
    let mut chains = Vec::new();
    for (index, limb) in c.plan.limbs.iter().enumerate() {
        if matches!(limb.kind, LimbKind::Leg | LimbKind::Arm) {
            chains.push((c.limb_joints(index), 9.81));
        }
    }
    let tail = c.tail_chain();
    if let Some(&tip) = c.rig.spine.first()
        && !tail.is_empty()
    {
        let mut joints = tail;
        joints.push(tip);
        chains.push((joints, 0.0));
    }
    chains
}

/// The local rotation of the wing joint `k` along its wing (0 the root, which beats by the
/// flap motion; the others lag behind it) on the side of `sign`, at time `t` of `flap`'s beat.
pub(super) fn wing_joint_rotation(flap: &FlapParams, t: f32, sign: f32, k: usize) -> Quat {
    let rotation = if k == 0 {
        flap.wing_rotation(t, if sign > 0.0 { Side::Left } else { Side::Right })
    } else {
        Quat::from_rotation_z(
            sign * 0.25 * flap.amplitude * sin_turns(flap.frequency * t - 0.12 * k as f32),
        )
    };
    rotation.normalize()
}

/// A damped chain joint's rotation bent no further than its share of the skin's `limit`: a
/// spine joint (the tail) bends no further than its skin allows; a damped chain bends all its
/// joints the same way at once, so each takes part of its limit (its neighbours' bends add up
/// in the skin between them).
pub(super) fn chain_bend_limited(rotation: Quat, limit: f32) -> Quat {
    let limit = CHAIN_BEND_SHARE * limit;
    let angle = rotation.angle_between(Quat::IDENTITY);
    if angle > limit {
        Quat::IDENTITY.slerp(rotation, limit / angle).normalize()
    } else {
        rotation
    }
}

/// The part of its bend limit each joint of a flier's tail chain may take.
const CHAIN_BEND_SHARE: f32 = 0.75;

/// How far a flier's chains trail behind their limbs in flight, as a fraction of their length.
const FLIGHT_TRAIL: f32 = 0.3;

/// A flier's chains' damping as a fraction of critical damping.
const CHAIN_DAMPING_RATIO: f32 = 0.7;

/// The least height of a flier's lowest vertex in flight, as a fraction of its body length.
const FLIGHT_CLEARANCE: f32 = 0.02;

/// Seconds of simulation before a flier's clip starts (rounded up to whole bob periods).
const FLIGHT_WARM_UP: f32 = 3.0;

/// A flier's legs, arms and tail as damped chains of a legless gait controller: each chain is
/// straight at rest along its limb (root to tip), pulled toward that rest by a spring, by
/// gravity (legs and arms) and held back by damping, so it sways with the body's bob and
/// trails in flight. Each bone turns by its segment's deflection from the rest direction.
#[derive(Debug, Clone)]
pub(super) struct FlightChains {
    controller: Controller,
    /// Per chain: its skeleton joints (root first, the tip last; all but the tip animated),
    /// its rest direction and its index in the controller.
    chains: Vec<(Vec<usize>, Vec3, usize)>,
    /// Each joint's bend limit ([`Creature::bend_limits`]), as the clips limit the chains.
    limits: Vec<f32>,
}

impl FlightChains {
    pub(super) fn new(
        c: &Creature,
        chains: &[(Vec<usize>, f32)],
        speed: f32,
    ) -> Result<Self, Error> {
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
            // Flying, a chain rests trailing by about 30% of its length behind its limb.
            let rest = if speed > 0.0 {
                (direction - FLIGHT_TRAIL * Vec3::Z).normalize_or(direction)
            } else {
                direction
            };
            // The spring such that gravity sags a chain by about 15% of its length, damped to
            // [`CHAIN_DAMPING_RATIO`] of critical (at least 6 /s), so the bob does not ring it.
            let stiffness = (gravity / (0.15 * length)).clamp(20.0, 10_000.0);
            let damping = (2.0 * CHAIN_DAMPING_RATIO * crate::math::sqrt(stiffness)).max(6.0);
            let chain = Chain::new(position(root), rest, segments, length / segments as f32)
                .with_spring(stiffness, damping)
                .with_gravity(*gravity);
            let index = controller.add_chain(chain)?;
            out.push((joints.clone(), direction, index));
        }
        Ok(Self {
            controller,
            chains: out,
            limits: c.bend_limits(),
        })
    }

    /// The animated joints, in the order of [`rotations`](Self::rotations).
    pub(super) fn animated(&self) -> impl Iterator<Item = usize> + '_ {
        self.chains
            .iter()
            .flat_map(|(joints, _, _)| joints.iter().take(joints.len().saturating_sub(1)))
            .copied()
    }

    pub(super) fn update(&mut self, dt: f32, position: Vec3) -> Result<(), Error> {
        // No ground under a flier.
        let ground = Plane::horizontal(f32::MIN / 4.0);
        self.controller.update(
            dt,
            Pose::from_yaw(position, 0.0),
            Vec3::ZERO,
            Vec3::ZERO,
            &ground,
        )?;
        Ok(())
    }

    /// The animated joints' local rotations now: each bone's global rotation is its segment's
    /// deflection from the chain's rest direction, taken relative to the nearest animated
    /// ancestor's.
    ///
    /// # Errors
    /// [`Error::Gait`] if the controller has no chain of an index it gave (never).
    fn rotations(&self, c: &Creature) -> Result<Vec<Quat>, Error> {
        let parents: Vec<Option<usize>> = c.skeleton.joints.iter().map(|j| j.parent).collect();
        let mut global = alloc::vec![None; parents.len()];
        let mut out = alloc::vec![Quat::IDENTITY; self.animated().count()];
        self.rotations_into(&parents, &mut global, &mut out)?;
        Ok(out)
    }

    /// [`rotations`](Self::rotations) into `out` (in the order of
    /// [`animated`](Self::animated)) for a skeleton of `parents` (each joint's), with `global`
    /// (a slot per joint) to work in: allocates nothing.
    ///
    /// # Errors
    /// As [`rotations`](Self::rotations).
    pub(super) fn rotations_into(
        &self,
        parents: &[Option<usize>],
        global: &mut [Option<Quat>],
        out: &mut [Quat],
    ) -> Result<(), Error> {
        global.fill(None);
        for (chain_joints, direction, index) in &self.chains {
            let points = self.controller.chain(*index)?;
            // A point per joint: the chain was made with a segment between each two.
            debug_assert_eq!(points.len(), chain_joints.len(), "a point per joint");
            for (k, &j) in chain_joints.iter().enumerate().take(chain_joints.len() - 1) {
                let d = (points[k + 1] - points[k]).normalize_or(*direction);
                if let Some(g) = global.get_mut(j) {
                    *g = Some(rotation_arc(*direction, d));
                }
            }
        }
        // The nearest animated ancestor of a joint.
        let nearest = |j: usize| {
            let mut at = parents.get(j).copied().flatten();
            let mut hops = 0;
            while let Some(p) = at {
                if let Some(Some(_)) = global.get(p) {
                    return Some(p);
                }
                hops += 1;
                if hops > parents.len() {
                    break;
                }
                at = parents.get(p).copied().flatten();
            }
            None
        };
        let raw = |j: usize| global.get(j).copied().flatten().unwrap_or(Quat::IDENTITY);
        let ancestor = |j: usize| nearest(j).map_or(Quat::IDENTITY, raw);
        // A joint's rotation as its track has it: its deflection from its nearest animated
        // ancestor's, limited.
        let limit = |j: usize| self.limits.get(j).copied().unwrap_or(f32::INFINITY);
        let local =
            |j: usize| chain_bend_limited((ancestor(j).inverse() * raw(j)).normalize(), limit(j));
        for (slot, j) in out.iter_mut().zip(self.animated()) {
            *slot = (ancestor(j).inverse() * raw(j)).normalize();
        }
        // A chain hanging from another one (legs on a flier's tail) hangs from that chain as its
        // tracks turn it (each bend limited), not as it was simulated: a tail held to its
        // skin's limits would otherwise whirl the legs on it through its whole swing.
        for (chain_joints, _, _) in &self.chains {
            let Some(&root) = chain_joints.first() else {
                continue;
            };
            let Some(mut at) = nearest(root) else {
                continue;
            };
            // The ancestors' limited rotations, composed from the top down.
            let mut applied = local(at);
            let mut hops = 0;
            while let Some(up) = nearest(at) {
                applied = local(up) * applied;
                at = up;
                hops += 1;
                if hops > parents.len() {
                    break;
                }
            }
            if let Some((slot, _)) = out
                .iter_mut()
                .zip(self.animated())
                .find(|&(_, j)| j == root)
            {
                *slot = (applied.inverse() * raw(root)).normalize();
            }
        }
        Ok(())
    }
}
