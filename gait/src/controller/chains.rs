//! Follow-through: damped spring chains (tails, fins, wing trailing bones, dangling legs)
//! hanging from the body, integrated in fixed sub-steps with constant segment lengths.

use alloc::vec::Vec;

use glam::Vec3;

use super::Controller;
use crate::error::GaitError;
use crate::leg::{Chain, Pose};
use crate::math::{Roots, ceil, clamp_sym, quat_yxz, sqrt};

/// Chains are integrated in sub-steps of at most this many seconds…
const CHAIN_SUBSTEP: f32 = 1.0 / 120.0;

/// …and at most this many sub-steps per update (longer updates are simulated as this long).
const MAX_CHAIN_SUBSTEPS: u32 = 64;

#[derive(Debug, Clone, PartialEq)]
pub(super) struct ChainState {
    positions: Vec<Vec3>,
    velocities: Vec<Vec3>,
    output: Vec<Vec3>,
    /// The rest joints of the current update (reused storage: no allocation per update).
    rest: Vec<Vec3>,
    /// The rest joints of the previous update: the sub-steps move the rest (the root pinned
    /// to the body included) from these to `rest`, so a body that moves far in one update
    /// does not yank the chain across its root.
    previous: Vec<Vec3>,
}

impl Controller {
    /// Adds a follow-through chain (tail, fin, wing trailing bones, dangling leg) and returns
    /// its index. Its joints start at rest at the next update.
    ///
    /// # Errors
    /// The chain's error from [`Chain::validate`].
    pub fn add_chain(&mut self, chain: Chain) -> Result<usize, GaitError> {
        chain.validate(self.chains.len())?;
        let mut rest = Vec::with_capacity(chain.segments + 1);
        chain_rest(&chain, &self.pose, 0.0, &mut rest);
        self.chains.push(chain);
        self.chain_states.push(ChainState {
            velocities: alloc::vec![Vec3::ZERO; rest.len()],
            output: rest.clone(),
            positions: rest.clone(),
            previous: rest.clone(),
            rest,
        });
        if self.initialized {
            // Start the new chain at rest on the current pose.
            let i = self.chains.len() - 1;
            self.reset_chain(i);
        }
        Ok(self.chains.len() - 1)
    }

    pub(super) fn reset_chain(&mut self, i: usize) {
        let s = &mut self.chain_states[i];
        chain_rest(&self.chains[i], &self.pose, 0.0, &mut s.rest);
        s.velocities.iter_mut().for_each(|v| *v = Vec3::ZERO);
        s.output.clone_from(&s.rest);
        s.positions.clone_from(&s.rest);
        s.previous.clone_from(&s.rest);
    }

    pub(super) fn follow(&mut self, i: usize, dt: f32, pose: &Pose, angular_velocity: Vec3) {
        let (chain, state) = (&self.chains[i], &mut self.chain_states[i]);
        // A validated chain has a segment at least: a root and a joint.
        debug_assert!(state.positions.len() >= 2 && state.positions.len() == state.rest.len());
        core::mem::swap(&mut state.previous, &mut state.rest);
        chain_rest(
            chain,
            pose,
            angular_velocity.y * chain.turn_bend,
            &mut state.rest,
        );
        let (rest, previous) = (&state.rest, &state.previous);
        let rate = (2.0 * sqrt(chain.stiffness) + chain.damping).max(1.0 / CHAIN_SUBSTEP);
        let substeps = (ceil(dt * rate) as u32).clamp(1, MAX_CHAIN_SUBSTEPS);
        let h = (dt / substeps as f32).min(1.0 / rate);
        let len = chain.segment_length;
        if dt > 0.0 {
            for step in 1..=substeps {
                // The rest of this sub-step: on the way from the previous update's to this one's.
                let t = step as f32 / substeps as f32;
                let at = |k: usize| previous[k].lerp(rest[k], t);
                state.positions[0] = at(0);
                for k in 1..state.positions.len() {
                    let x = state.positions[k];
                    let v = state.velocities[k];
                    let accel = (at(k) - x) * chain.stiffness - v * chain.damping
                        + Vec3::NEG_Y * chain.gravity;
                    let v = v + accel * h;
                    let moved = x + v * h;
                    // Constant segment length: project onto the sphere around the parent.
                    let parent = state.positions[k - 1];
                    let dir = (moved - parent)
                        .try_unit()
                        .unwrap_or_else(|| (rest[k] - rest[k - 1]).unit_or(Vec3::NEG_Z));
                    let fixed = parent + dir * len;
                    state.velocities[k] = (fixed - x) / h;
                    state.positions[k] = fixed;
                }
            }
        } else {
            state.positions[0] = rest[0];
            for k in 1..state.positions.len() {
                let parent = state.positions[k - 1];
                let dir = (state.positions[k] - parent).unit_or(Vec3::NEG_Z);
                state.positions[k] = parent + dir * len;
            }
        }
        if !state.positions.iter().all(|p| p.is_finite())
            || !state.velocities.iter().all(|v| v.is_finite())
        {
            state.positions.clone_from(rest);
            state.velocities.iter_mut().for_each(|v| *v = Vec3::ZERO);
        }
        let w = self.blend;
        for (out, (p, r)) in state
            .output
            .iter_mut()
            .zip(state.positions.iter().zip(rest))
        {
            *out = r.lerp(*p, w);
        }
    }

    /// How many chains there are.
    #[must_use]
    pub fn chain_count(&self) -> usize {
        self.chains.len()
    }

    /// A chain's joint positions (world, root first, `segments + 1` of them), after blending.
    ///
    /// # Errors
    /// [`GaitError::IndexOutOfRange`] for a chain that does not exist.
    pub fn chain(&self, chain: usize) -> Result<&[Vec3], GaitError> {
        self.chain_states
            .get(chain)
            .map(|s| s.output.as_slice())
            .ok_or(GaitError::IndexOutOfRange {
                what: "chain",
                index: chain,
                len: self.chain_states.len(),
            })
    }
}

/// A chain's rest joints in world space, its direction turned by `yaw` about the body's up,
/// written into `out` (reused storage).
fn chain_rest(chain: &Chain, pose: &Pose, yaw: f32, out: &mut Vec<Vec3>) {
    let yaw = clamp_sym(yaw, core::f32::consts::FRAC_PI_2);
    let dir = quat_yxz(yaw, 0.0, 0.0) * chain.direction.unit_or(Vec3::NEG_Z);
    out.clear();
    out.extend(
        (0..=chain.segments)
            .map(|k| pose.transform_point(chain.root + dir * (chain.segment_length * k as f32))),
    );
}
