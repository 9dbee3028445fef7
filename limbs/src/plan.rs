//! The planner's output: which sockets get which limbs, how big, and how stable the result is.

use alloc::vec::Vec;

use glam::{Vec2, Vec3};

use crate::CreatureKind;

/// What a limb is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum LimbKind {
    /// A walking leg (walkers) or a hanging leg (fliers): a two-bone IK chain.
    Leg,
    /// An arm: a two-bone IK chain that never reaches the ground.
    Arm,
    /// An insect wing, scaled at random per axis, on a top socket.
    BuzzingWing,
    /// A bird wing, scaled uniformly, on a side socket.
    FlappingWing,
    /// A dorsal fin on a top socket.
    DorsalFin,
    /// A pectoral fin on a side socket.
    PectoralFin,
    /// A tail at the tail tip.
    Tail,
}

/// Which socket of its bone a limb attaches to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Socket {
    /// [`SpineBone::left`](crate::SpineBone::left).
    Left,
    /// [`SpineBone::right`](crate::SpineBone::right).
    Right,
    /// [`SpineBone::top`](crate::SpineBone::top).
    Top,
    /// The tip of the tail-end bone, beyond its sockets (tails only).
    Tip,
}

/// Which side of the body a limb is on (buzzing wings share the top socket but still come as a
/// left and a right wing). Sides are the creature's own: with the workspace's glTF convention
/// (right-handed, +Y up, facing +Z) its left is +X.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Side {
    /// The creature's left (+X when it faces +Z).
    Left,
    /// The creature's right (−X when it faces +Z).
    Right,
    /// On the body's midline (dorsal fins, tails).
    Center,
}

/// Which way leg knees bend, chosen once per creature.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Knee {
    /// Knees point toward the head (a human's).
    Forward,
    /// Knees point toward the tail (a bird's).
    Backward,
    /// Knees point away from the body (a spider's).
    Sideways,
}

/// A stretch of the body, in [`SpineBone::along`](crate::SpineBone::along) units and as the
/// bones inside it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// Where the stretch starts (smaller `along`).
    pub start: f32,
    /// Where the stretch ends (larger `along`); `end >= start`.
    pub end: f32,
    /// Index of the first bone inside the stretch.
    pub first_bone: usize,
    /// Index of the last bone inside the stretch (`>= first_bone`; the limb's own bone is
    /// always inside).
    pub last_bone: usize,
}

impl Span {
    /// Whether two stretches share more than an end point.
    #[must_use]
    pub fn overlaps(&self, other: &Self) -> bool {
        self.start < other.end && other.start < self.end
    }
}

/// One limb of a [`Plan`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limb {
    /// What it is.
    pub kind: LimbKind,
    /// Which of the kind's two authored styles to use (0 or 1: butterfly or fly wings, the two
    /// fin and tail styles); 0 for legs, arms and flapping wings.
    pub variant: u8,
    /// Index of its bone in [`Body::bones`](crate::Body::bones).
    pub bone: usize,
    /// The socket of that bone it attaches to.
    pub socket: Socket,
    /// Its side of the body.
    pub side: Side,
    /// Index in [`Plan::limbs`] of its mirror twin, if it has one.
    pub mirror: Option<usize>,
    /// Scale of the limb's model, authored with unit reach along its main axis: Y for legs,
    /// arms and dorsal fins, X for wings and pectoral fins, Z for tails. Uniform for legs,
    /// arms and flapping wings.
    pub scale: Vec3,
    /// Reach from the socket along the main axis, in body units. A walker's leg reaches
    /// exactly from its socket to the ground (after [`Plan::lift`]).
    pub length: f32,
    /// Where the foot rests, in body space (before lift is applied to the body: the body's
    /// points move up by [`Plan::lift`], so the foot is `lift` below the original ground).
    /// Legs only.
    pub foot: Option<Vec3>,
    /// For legs and arms, the stretch of body swept while walking; for wings, fins and tails,
    /// the stretch they cover.
    pub span: Span,
}

/// How a walker's final legs were laid out: which of the seed's rules gave them, or that the
/// planner had to rebuild the layout. It always describes the legs in [`Plan::limbs`]; pairs
/// added to a rule's layout are also listed as [`Repair::AddedPair`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum WalkerLayout {
    /// Long or nearly uniform body: as many non-overlapping leg pairs as fit (the seed's first
    /// rule).
    Fill,
    /// The widest bone plus a second pair on the next widest free bone of similar width (the
    /// seed's second rule), with any pairs added to make it stand.
    TwoWide,
    /// A single pair on the widest bone, standing by itself: the centre of mass lies over the
    /// segment between its feet (the seed's biped rule, or its balancing rule when no bone was
    /// free for a balancing pair and none was needed).
    Biped,
    /// The widest bone plus one or more balancing pairs: the seed's balancing rule, or a biped
    /// whose single pair did not stand and got a balancing pair as a repair.
    Balanced,
    /// No seed rule's layout could be made to stand by adding pairs (the seed's "large first
    /// pair covering every slot"), so the planner rebuilt it from other bones, with shorter
    /// strides as a last resort: see the [`Repair::DroppedPair`], [`Repair::AddedPair`] and
    /// [`Repair::ShortenedStride`] entries.
    Rebuilt,
}

/// A change the planner made because a rule of the seed's algorithm would have broken a
/// guarantee.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Repair {
    /// A bone was passed over for legs because a leg there would be shorter than
    /// [`PlanOptions::min_leg_length`](crate::PlanOptions::min_leg_length) (the seed's "tiny
    /// legs under a low body").
    SkippedLowBone {
        /// The bone.
        bone: usize,
        /// The leg length it would have had.
        leg_length: f32,
    },
    /// The whole body was raised, because no bone was high enough for a leg of
    /// [`PlanOptions::min_leg_length`](crate::PlanOptions::min_leg_length): afterwards the
    /// highest bone's legs are that long. It is the only reason for a lift besides
    /// [`Repair::LiftedToStand`].
    Lifted {
        /// How far, in body units.
        by: f32,
    },
    /// No layout on the bones tall enough for legs could stand (e.g. a body touching the
    /// ground but for one end), so the whole body was raised until every bone is tall enough
    /// for legs of [`PlanOptions::min_leg_length`](crate::PlanOptions::min_leg_length), and the
    /// layout rebuilt on all of them. `by` is the whole lift ([`Plan::lift`]); the
    /// [`Repair::Lifted`] and [`Repair::SkippedLowBone`] entries of the first try are dropped.
    LiftedToStand {
        /// How far, in body units.
        by: f32,
    },
    /// A leg pair that the seed's rule did not place was added to make the walker stand. Its
    /// bone has legs in the final plan.
    AddedPair {
        /// Its bone.
        bone: usize,
    },
    /// A leg pair that the seed's rule placed was removed, because its layout could not be
    /// made to stand (the seed's "large first pair covering every slot"); the layout is
    /// [`WalkerLayout::Rebuilt`]. Its bone has no legs in the final plan.
    DroppedPair {
        /// Its bone.
        bone: usize,
    },
    /// A walker's strides were shortened: its legs and arms sweep `sweep ×` their length on
    /// each side instead of [`PlanOptions::sweep`](crate::PlanOptions::sweep), so that pairs
    /// that stand fit without overlapping (a short spine under long legs). The last resort,
    /// used only when no layout stands at full stride; the layout is
    /// [`WalkerLayout::Rebuilt`] and the limbs' spans use the shorter stride.
    ShortenedStride {
        /// The stride used, per unit of leg length (below `PlanOptions::sweep`).
        sweep: f32,
    },
    /// Evenly spread flier legs were shortened so they do not overlap.
    ShortenedLegs {
        /// Their new length.
        length: f32,
    },
    /// Fewer leg pairs, fins or fin pairs were placed than drawn, for lack of free bones.
    FewerThanDrawn {
        /// Which limb.
        kind: LimbKind,
        /// How many (pairs for paired limbs) were drawn.
        drawn: usize,
        /// How many were placed.
        placed: usize,
    },
    /// Arms were shortened so their sweep stays clear of the legs'.
    ShortenedArms {
        /// Their new length.
        length: f32,
    },
    /// Drawn arms were left out because they would have been shorter than
    /// [`PlanOptions::min_arm_length`](crate::PlanOptions::min_arm_length) × body length: a
    /// low socket, a small draw from `arm_length`, or too little room beside the legs' sweeps.
    DroppedArms {
        /// The length they would have had.
        length: f32,
    },
}

/// The planner's answer: limbs, the creature-wide knee direction, the body lift, and for
/// walkers the measured balance.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// The creature kind planned for.
    pub kind: CreatureKind,
    /// The limbs. Mirror twins are stored next to each other, left first.
    pub limbs: Vec<Limb>,
    /// Knee direction of every leg and arm (`None` for swimmers).
    pub knee: Option<Knee>,
    /// How far the body must be raised (body units, zero or more) so every walking leg reaches
    /// the ground as planned.
    pub lift: f32,
    /// For walkers, how the final legs were laid out.
    pub layout: Option<WalkerLayout>,
    /// For walkers, the signed distance in the ground plane from the centre of mass to the
    /// edge of the support region (the feet's convex hull grown by
    /// [`foot_radius`](crate::PlanOptions::foot_radius) × body length): positive means
    /// statically stable. At least `min_margin × body length`. `None` for fliers and swimmers.
    pub stability_margin: Option<f32>,
    /// The body's centre of mass projected to the ground, as `(x, z)`
    /// (see [`Body::center_of_mass`](crate::Body::center_of_mass)).
    pub center_of_mass: Vec2,
    /// For walkers, the convex hull of the feet in the ground plane as `(x, z)`,
    /// counter-clockwise seen from above; empty for fliers and swimmers.
    pub support: Vec<Vec2>,
    /// What the planner changed to keep its guarantees, in order.
    pub repairs: Vec<Repair>,
}

impl Plan {
    /// The limbs of one kind, in plan order.
    pub fn limbs_of(&self, kind: LimbKind) -> impl Iterator<Item = &Limb> + '_ {
        self.limbs.iter().filter(move |l| l.kind == kind)
    }

    /// Number of mirrored leg pairs.
    #[must_use]
    pub fn leg_pairs(&self) -> usize {
        self.limbs_of(LimbKind::Leg).count() / 2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_that_touch_do_not_overlap() {
        let a = Span {
            start: 0.0,
            end: 1.0,
            first_bone: 0,
            last_bone: 1,
        };
        let b = Span {
            start: 1.0,
            end: 2.0,
            first_bone: 1,
            last_bone: 2,
        };
        assert!(!a.overlaps(&b));
        let c = Span { start: 0.9, ..b };
        assert!(a.overlaps(&c) && c.overlaps(&a));
    }
}
