//! Gaits by speed: [`Gait`] (walk, trot, run, and a hopper's hop), the [`GaitSpeeds`] at
//! which a walker changes between them (Froude numbers, as biomechanics compares animals of
//! different sizes), and the leg groups each gait steps in.

use alloc::vec::Vec;

use crate::error::{GaitError, in_range};
use crate::leg::{Leg, LimbKind};

/// A walking pattern. With [`GaitOptions::gaits`](crate::GaitOptions::gaits) set, the
/// [`Controller`](crate::Controller) chooses one by the body's speed (see [`GaitSpeeds`]);
/// without, it always walks in [`Gait::Walk`]'s groups as derived before gaits existed (see
/// [`Gait::Walk`]), or, a hopper ([`GaitOptions::hop`](crate::GaitOptions::hop)), always
/// hops.
///
/// Which legs step together, by the walking legs' left/right pairs (back to front):
///
/// | legs | [`Walk`](Gait::Walk) | [`Trot`](Gait::Trot) | [`Run`](Gait::Run) |
/// | --- | --- | --- | --- |
/// | 2 | left, right | left, right | left, right, with a flight phase |
/// | 4 | one at a time: left hind, left fore, right hind, right fore | diagonal pairs | bound: hind pair, fore pair, with a flight phase |
/// | 6 and more | a wave from the back in three groups (two legs at a time on six) | two alternating groups (tripods on six) | two alternating groups, swings overlapping (a fast tripod on six; rarely all feet up) |
///
/// A hopper ([`GaitOptions::hop`](crate::GaitOptions::hop)) hops instead of trotting and
/// running: [`Hop`](Gait::Hop), every walking leg in one group.
///
/// Legs whose [`group`](crate::Leg::group) the caller set keep their groups in every gait;
/// a run still lengthens and overlaps its swings (all feet up at once only with two groups).
///
/// Gaits are ordered by speed, `Walk < Trot < Run`; `Hop`, a style rather than a speed,
/// comes last.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[non_exhaustive]
pub enum Gait {
    /// At low speed: the slowest sequence the legs allow, every foot on the ground most of
    /// the time. Without [`GaitSpeeds`], the controller's only gait, in the groups it has
    /// always derived: two alternating groups (the trot's) up to three pairs, a three-group
    /// wave beyond.
    #[default]
    Walk,
    /// At middle speed: two alternating groups (diagonal pairs, tripods); a group lifts off
    /// as the other lands.
    Trot,
    /// At high speed: longer swings, and the next group lifts off before the one in the air
    /// lands, so with two groups for a moment no foot is on the ground (a flight phase).
    Run,
    /// A hopper's gait from the trot's speed up (or at every speed without gaits by speed):
    /// every walking leg lifts off together once one wants to step and swings while the body
    /// travels 1.5 times the way from its foot to its step's target at lift-off (all feet in
    /// the air: a flight phase), and they land together; they stand until the body has
    /// carried them back out of reach.
    Hop,
}

/// A hop's swing: the body's travel while the feet are in the air over the way from a foot to
/// its step's target at lift-off (a run's is 0.6). The feet are in the air for most of a hop
/// and stand for the rest, as a hopping kangaroo's do (duty factor about 0.3–0.4 at speed).
pub(crate) const HOP_SWING_FRACTION: f32 = 1.5;

impl Gait {
    /// Every gait, in order (the index of each is `gait as usize`).
    pub(crate) const ALL: [Self; 4] = [Self::Walk, Self::Trot, Self::Run, Self::Hop];
}

/// The speeds at which a walker changes gait, as Froude numbers `v² / (g · l)`: `v` the body's
/// horizontal speed, `l` the walking legs' mean [`size`](crate::Leg::size) and `g` gravity.
/// Animals of every size change gait at about the same Froude number (Alexander, 1989: walk
/// to trot, or walk to run for two legs, about 0.5; trot to gallop about 2.5), so a small
/// creature and a big one change at comparable points.
///
/// Speeding up, the gait changes at [`trot`](Self::trot) and [`run`](Self::run); slowing
/// down, at [`hysteresis`](Self::hysteresis) of them, so a speed hovering at a threshold does
/// not flicker between gaits. A new gait takes over when a group hands over to the next (its
/// steps landed, or a run's are in flight), so every step under way finishes as it began and
/// no joint jumps.
///
/// ```
/// use creature_gait::{Gait, GaitSpeeds};
///
/// let speeds = GaitSpeeds::DEFAULT;
/// // A 1 m leg: walking below about 2.2 m/s, trotting from there, running from 5 m/s.
/// assert_eq!(speeds.froude(2.0, 1.0), 2.0 * 2.0 / 9.81);
/// assert_eq!(speeds.choose(Gait::Walk, 2.0, 1.0), Gait::Walk);
/// assert_eq!(speeds.choose(Gait::Walk, 2.5, 1.0), Gait::Trot);
/// assert_eq!(speeds.choose(Gait::Walk, 5.0, 1.0), Gait::Run);
/// // Slowing down, the run holds a little below where it began.
/// assert_eq!(speeds.choose(Gait::Run, 4.8, 1.0), Gait::Run);
/// assert_eq!(speeds.choose(Gait::Run, 4.0, 1.0), Gait::Trot);
/// # Ok::<(), creature_gait::GaitError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct GaitSpeeds {
    /// The Froude number from which a walker trots, in `[0, 100]`. Default 0.5. Two legs
    /// have no trot: a biped's trot is its walk's pattern at the trot's speed.
    pub trot: f32,
    /// The Froude number from which a walker runs, in `[trot, 100]`. Default 2.5.
    pub run: f32,
    /// The fraction of a threshold the Froude number falls below before the gait changes
    /// back down, in `(0, 1]`. Default 0.8.
    pub hysteresis: f32,
    /// Gravity, m/s², in `(0, 100]`. Default 9.81.
    pub gravity: f32,
}

impl GaitSpeeds {
    /// Trot from a Froude number of 0.5, run from 2.5, change back at 0.8 of those, on Earth.
    pub const DEFAULT: Self = Self {
        trot: 0.5,
        run: 2.5,
        hysteresis: 0.8,
        gravity: 9.81,
    };

    /// Sets the Froude numbers from which a walker trots and runs (both at once: `trot` may be
    /// no more than `run`).
    #[must_use]
    pub const fn with_thresholds(mut self, trot: f32, run: f32) -> Self {
        self.trot = trot;
        self.run = run;
        self
    }

    /// Sets [`hysteresis`](Self::hysteresis).
    #[must_use]
    pub const fn with_hysteresis(mut self, value: f32) -> Self {
        self.hysteresis = value;
        self
    }

    /// Sets [`gravity`](Self::gravity).
    #[must_use]
    pub const fn with_gravity(mut self, value: f32) -> Self {
        self.gravity = value;
        self
    }

    /// The Froude number of `speed` (m/s) on legs of `leg` metres: `speed² / (gravity · leg)`
    /// (0 for a leg that is not positive).
    #[must_use]
    pub fn froude(&self, speed: f32, leg: f32) -> f32 {
        if leg > 0.0 {
            speed * speed / (self.gravity * leg)
        } else {
            0.0
        }
    }

    /// The gait for `speed` on legs of `leg` metres, coming from `current`: up at the
    /// thresholds, down below [`hysteresis`](Self::hysteresis) of them. Coming from
    /// [`Gait::Hop`], the hop is taken as a trot (a hopper hops from the trot's speed up): the
    /// answer is never `Hop`.
    #[must_use]
    pub fn choose(&self, current: Gait, speed: f32, leg: f32) -> Gait {
        let current = if current == Gait::Hop {
            Gait::Trot
        } else {
            current
        };
        let froude = self.froude(speed, leg);
        let at = |scale: f32| {
            if froude >= self.run * scale {
                Gait::Run
            } else if froude >= self.trot * scale {
                Gait::Trot
            } else {
                Gait::Walk
            }
        };
        // At least the gait the thresholds reach, at most the one their hysteresis keeps
        // (`max` then `min`: no panic on fields never validated).
        current.max(at(1.0)).min(at(self.hysteresis))
    }

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`GaitError::OutOfRange`] naming the first bad field.
    pub fn validate(&self) -> Result<(), GaitError> {
        in_range(self.trot, "trot Froude number", 0.0, 100.0)?;
        in_range(self.run, "run Froude number", self.trot, 100.0)?;
        in_range(self.hysteresis, "gait hysteresis", f32::MIN_POSITIVE, 1.0)?;
        in_range(self.gravity, "gait gravity", f32::MIN_POSITIVE, 100.0)?;
        Ok(())
    }
}

impl Default for GaitSpeeds {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The swing's share of a run's stride (the body's travel while a foot is in the air over its
/// step's length): more than the half that two alternating groups leave each, so the groups'
/// swings overlap (the flight phase), and a foot is on the ground for 0.4 of the stride, as a
/// running animal's is (duty factor 0.3–0.4).
pub(crate) const RUN_SWING_FRACTION: f32 = 0.6;

/// The walking legs of `legs` by side, back to front (ascending Z, ties by index): left
/// (+X), right (−X) and on the midline.
pub(crate) struct Sides {
    pub(crate) left: Vec<usize>,
    pub(crate) right: Vec<usize>,
    pub(crate) centre: Vec<usize>,
}

impl Sides {
    /// The most legs on one side (or the midline).
    pub(crate) fn pairs(&self) -> usize {
        self.left.len().max(self.right.len()).max(self.centre.len())
    }
}

/// How many pairs a side may have before the walk without gaits by speed becomes a
/// three-group travelling wave instead of two alternating groups.
pub(crate) const ALTERNATING_PAIRS: usize = 3;

/// How many pairs a side may have before the walk by speed becomes a three-group travelling
/// wave instead of one leg at a time (six legs one at a time fall behind a walk's speeds).
pub(crate) const ONE_AT_A_TIME_PAIRS: usize = 2;

/// Each leg's group in `gait` (arms group 0, unsequenced), and the number of groups, from the
/// walking legs by side. `Gait::Walk` without `by_speed` is the layout's original derivation.
pub(crate) fn groups(legs: &[Leg], sides: &Sides, gait: Gait, by_speed: bool) -> (Vec<u8>, u8) {
    let mut groups = alloc::vec![0u8; legs.len()];
    let pairs = sides.pairs();
    let Sides {
        left,
        right,
        centre,
    } = sides;
    let alternate = |groups: &mut Vec<u8>, count: usize| {
        for (k, &i) in left.iter().enumerate() {
            groups[i] = (k % count) as u8;
        }
        for (k, &i) in right.iter().enumerate() {
            groups[i] = ((k + 1) % count) as u8;
        }
        for (k, &i) in centre.iter().enumerate() {
            groups[i] = (k % count) as u8;
        }
    };
    let count = match gait {
        Gait::Walk if !by_speed || pairs > ONE_AT_A_TIME_PAIRS => {
            let count = if by_speed || pairs > ALTERNATING_PAIRS {
                3
            } else {
                2
            };
            alternate(&mut groups, count);
            count
        }
        Gait::Walk => {
            // One leg at a time: up each side from the back (left, then right, then the
            // midline), a lateral-sequence walk on four legs, a wave on six.
            let order = left.iter().chain(right).chain(centre);
            let mut count = 0;
            for &i in order {
                groups[i] = count as u8;
                count += 1;
            }
            count.max(1)
        }
        Gait::Run if left.len() == 2 && right.len() == 2 && centre.is_empty() => {
            // A bound: the hind pair, then the fore pair.
            for (k, &i) in left.iter().chain(right).enumerate() {
                groups[i] = (k % 2) as u8;
            }
            2
        }
        Gait::Trot | Gait::Run => {
            alternate(&mut groups, 2);
            2
        }
        // Every leg in group 0 (as built).
        Gait::Hop => 1,
    };
    debug_assert!(
        legs.iter()
            .zip(&groups)
            .all(|(l, g)| l.kind == LimbKind::Leg || *g == 0)
    );
    (groups, count as u8)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn pairs(count: usize) -> (Vec<Leg>, Sides) {
        let mut legs = Vec::new();
        let (mut left, mut right) = (Vec::new(), Vec::new());
        for k in 0..count {
            let z = k as f32 * 0.6;
            for side in [1.0f32, -1.0] {
                if side > 0.0 {
                    left.push(legs.len());
                } else {
                    right.push(legs.len());
                }
                legs.push(Leg::new(
                    Vec3::new(0.3 * side, 0.8, z),
                    Vec3::new(0.4 * side, 0.0, z),
                    0.5,
                    0.5,
                ));
            }
        }
        let sides = Sides {
            left,
            right,
            centre: Vec::new(),
        };
        (legs, sides)
    }

    #[test]
    fn thresholds_with_hysteresis() {
        let s = GaitSpeeds::DEFAULT;
        let at = |froude: f32| crate::math::sqrt(froude * 9.81);
        assert_eq!(s.choose(Gait::Walk, at(0.49), 1.0), Gait::Walk);
        assert_eq!(s.choose(Gait::Walk, at(0.51), 1.0), Gait::Trot);
        assert_eq!(s.choose(Gait::Trot, at(0.41), 1.0), Gait::Trot);
        assert_eq!(s.choose(Gait::Trot, at(0.39), 1.0), Gait::Walk);
        assert_eq!(s.choose(Gait::Walk, at(3.0), 1.0), Gait::Run);
        assert_eq!(s.choose(Gait::Run, at(2.1), 1.0), Gait::Run);
        assert_eq!(s.choose(Gait::Run, at(1.9), 1.0), Gait::Trot);
        assert_eq!(s.choose(Gait::Run, at(0.1), 1.0), Gait::Walk);
        // Twice the leg, twice the squared speed for the same gait.
        assert_eq!(s.choose(Gait::Walk, at(2.0 * 0.51), 2.0), Gait::Trot);
        assert_eq!(s.choose(Gait::Walk, at(2.0 * 0.49), 2.0), Gait::Walk);
        assert_eq!(s.froude(3.0, 0.0), 0.0);
        assert!(s.validate().is_ok());
        assert!(s.with_thresholds(1.0, 0.5).validate().is_err());
        assert!(s.with_hysteresis(0.0).validate().is_err());
        assert!(s.with_gravity(f32::NAN).validate().is_err());
    }

    #[test]
    fn four_legs_walk_one_at_a_time_trot_diagonally_and_bound() {
        let (legs, sides) = pairs(2); // 0 HL, 1 HR, 2 FL, 3 FR
        let (walk, n) = groups(&legs, &sides, Gait::Walk, true);
        assert_eq!((walk, n), (alloc::vec![0, 2, 1, 3], 4));
        let (trot, n) = groups(&legs, &sides, Gait::Trot, true);
        assert_eq!(n, 2);
        assert_eq!(trot[0], trot[3]);
        assert_eq!(trot[1], trot[2]);
        assert_ne!(trot[0], trot[1]);
        let (bound, n) = groups(&legs, &sides, Gait::Run, true);
        assert_eq!((bound, n), (alloc::vec![0, 0, 1, 1], 2));
        // Without gaits by speed, the walk is the trot's pattern, as it always was.
        assert_eq!(groups(&legs, &sides, Gait::Walk, false).0, trot);
    }

    #[test]
    fn six_legs_wave_then_tripods_and_many_legs_keep_three_groups() {
        let (legs, sides) = pairs(3);
        let (wave, n) = groups(&legs, &sides, Gait::Walk, true);
        assert_eq!(n, 3);
        // Each side from the back, the right a group behind the left.
        assert_eq!(wave, alloc::vec![0, 1, 1, 2, 2, 0]);
        let (tripod, n) = groups(&legs, &sides, Gait::Run, true);
        assert_eq!(n, 2);
        assert_eq!(tripod[0], tripod[3]);
        assert_eq!(tripod[0], tripod[4]);
        let (legs, sides) = pairs(5);
        assert_eq!(groups(&legs, &sides, Gait::Walk, true).1, 3);
        assert_eq!(groups(&legs, &sides, Gait::Trot, true).1, 2);
    }
}
