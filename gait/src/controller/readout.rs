//! The read-outs of a [`Controller`]: legs, options, leg states, groups, body reaction, look
//! and figures.

use super::{BodyReaction, Controller, LegState, Look};
use crate::error::GaitError;
use crate::gaits::Gait;
use crate::leg::{Leg, LimbKind, Pose};
use crate::math::Roots;
use crate::metrics::GaitMetrics;
use crate::options::GaitOptions;

/// Read-outs.
impl Controller {
    /// The legs, as given.
    #[must_use]
    pub fn legs(&self) -> &[Leg] {
        &self.legs
    }

    /// The options, as given.
    #[must_use]
    pub const fn options(&self) -> &GaitOptions {
        &self.options
    }

    /// Every leg's state (foot, planted, step, joints), in the order of the legs.
    #[must_use]
    pub fn leg_states(&self) -> &[LegState] {
        &self.states
    }

    /// One leg's state.
    ///
    /// # Errors
    /// [`GaitError::IndexOutOfRange`] for a leg that does not exist.
    pub fn leg_state(&self, leg: usize) -> Result<&LegState, GaitError> {
        self.states.get(leg).ok_or(GaitError::IndexOutOfRange {
            what: "leg",
            index: leg,
            len: self.states.len(),
        })
    }

    /// Each leg's group (consecutive from 0; derived from the layout unless the legs set it;
    /// arms get 0 and are not sequenced).
    #[must_use]
    pub fn groups(&self) -> &[u8] {
        &self.layout.groups
    }

    /// The gait the legs step in now (without [`GaitOptions::gaits`], always [`Gait::Walk`],
    /// or [`Gait::Hop`] for a hopper).
    #[must_use]
    pub const fn gait(&self) -> Gait {
        self.gait
    }

    /// How many groups take turns.
    #[must_use]
    pub const fn group_count(&self) -> u8 {
        self.layout.group_count
    }

    /// The group whose turn it is.
    #[must_use]
    pub const fn active_group(&self) -> u8 {
        self.active_group
    }

    /// The leg that must be planted before `leg` may step (the 3D seed's opposite-foot
    /// reference, derived only when groups are derived), or `None`.
    #[must_use]
    pub fn opposite(&self, leg: usize) -> Option<usize> {
        self.layout.opposite.get(leg).copied().flatten()
    }

    /// The other leg of `leg`'s left/right pair, or `None`.
    #[must_use]
    pub fn partner(&self, leg: usize) -> Option<usize> {
        self.layout.partner.get(leg).copied().flatten()
    }

    /// The body's reaction (bob and breathing offset, sway/pitch/roll rotation).
    #[must_use]
    pub const fn body(&self) -> &BodyReaction {
        &self.reaction
    }

    /// The body's pose with the reaction applied: where to draw the body.
    #[must_use]
    pub fn reacted_pose(&self) -> Pose {
        Pose::new(
            self.pose.translation + self.reaction.offset,
            (self.pose.rotation * self.reaction.rotation).unit(),
        )
    }

    /// The head's look-at.
    #[must_use]
    pub const fn look(&self) -> &Look {
        &self.look
    }

    /// The current blend weight of the procedural layer.
    #[must_use]
    pub const fn blend(&self) -> f32 {
        self.blend
    }

    /// The figures of the last update: the steps it started, and the skate, overstretch,
    /// legs in the air and stability margin of the state it left, measured when asked (an
    /// update does not pay for figures nobody reads; the result is the same whenever it is
    /// asked before the next update).
    #[must_use]
    pub fn metrics(&self) -> GaitMetrics {
        self.measure()
    }

    /// Whether every leg stands on the ground (no step under way, every ray hit).
    #[must_use]
    pub fn all_planted(&self) -> bool {
        self.legs
            .iter()
            .zip(&self.states)
            .all(|(leg, s)| leg.kind != LimbKind::Leg || (s.planted && s.grounded))
    }
}
