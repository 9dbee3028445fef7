//! A recorded gait controller run (per frame the body, the feet and their contacts), how far a
//! frame is from repeating the first, the best frame to cut a loop at, closing the loop, and
//! how far a planted foot ends up beyond its leg's reach.

use alloc::vec::Vec;

use core::f32::consts::{PI, TAU};

use glam::{Quat, Vec3};

use creature_gait::{Leg, LimbKind, Pose};

use super::kinematics::angle_between;

/// A gait controller's run, frame by frame: the reacted body pose and the feet (world, relative
/// to the clip's start) and which feet are planted. Every frame has its body, `legs` feet and
/// `legs` contacts (the controller's leg states, one per leg), so a frame below
/// [`frames`](Self::frames) and a leg below `legs` index them directly.
#[derive(Debug, Clone)]
pub(super) struct GaitRun {
    /// The body pose per frame.
    pub(super) bodies: Vec<Pose>,
    /// Frame-major: `legs` feet per frame.
    pub(super) feet: Vec<Vec3>,
    /// Frame-major: per frame, per leg, whether the foot is planted.
    pub(super) contacts: Vec<bool>,
    /// Legs per frame.
    pub(super) legs: usize,
}

impl GaitRun {
    pub(super) fn frames(&self) -> usize {
        self.bodies.len()
    }

    pub(super) fn foot(&self, frame: usize, leg: usize) -> Vec3 {
        self.feet[frame * self.legs + leg]
    }

    /// How far frame `end` is from repeating frame 0: the largest of each foot's offset from
    /// its first place relative to the body (metres), the root's height change and its tilt
    /// (radians) change, the heading aside. `end` is a frame of the run.
    pub(super) fn mismatch(&self, end: usize) -> f32 {
        self.mismatch_from(&self.first_frame(), end)
    }

    /// Frame 0 as [`mismatch`](Self::mismatch) compares a frame with it, for many frames.
    pub(super) fn first_frame(&self) -> FirstFrame {
        let a = &self.bodies[0];
        FirstFrame {
            level: level(a),
            height: a.translation.y,
            feet: (0..self.legs)
                .map(|leg| a.inverse_transform_point(self.foot(0, leg)))
                .collect(),
        }
    }

    /// [`mismatch`](Self::mismatch) with frame 0 as `first` gives it (of this run).
    pub(super) fn mismatch_from(&self, first: &FirstFrame, end: usize) -> f32 {
        let b = &self.bodies[end];
        let mut error = angle_between(first.level, level(b));
        error = error.max((first.height - b.translation.y).abs());
        for (leg, &pa) in first.feet.iter().enumerate() {
            let pb = b.inverse_transform_point(self.foot(end, leg));
            error = error.max(pa.distance(pb));
        }
        error
    }

    /// Keeps frames `0..=end` and closes the loop: frame `end` becomes frame 0 moved by
    /// `motion` (the root motion over the clip). The body's mismatch is spread linearly over
    /// the frames; each foot's across over its swing frames only (in proportion to the foot's
    /// height, turning with the body's heading) and up or down along its final swing, so
    /// planted feet stay where they are, on the ground, and feet lifting off or landing move
    /// only up and down; a foot that never swings takes it linearly, sliding:
    /// returns the longest such slide (0 when every foot swings or none has to move).
    ///
    /// With `hold_seam`, a foot planted at frame 0 that lifts off just before the cut stays
    /// down until it (frame `end` is frame 0 again), rather than lift off only to be brought
    /// back along the ground.
    ///
    /// A foot no higher than `ground` counts as on the ground: it takes none of the correction
    /// across.
    pub(super) fn close_loop(
        &mut self,
        end: usize,
        motion: &Pose,
        hold_seam: bool,
        ground: f32,
    ) -> f32 {
        let keep = (end + 1).min(self.frames());
        if keep < 2 {
            return 0.0;
        }
        self.truncate(keep);
        let last = keep - 1;
        for leg in 0..self.legs {
            if hold_seam
                && self.planted(0, leg)
                && let Some(down) = (1..last).rev().find(|&f| self.planted(f, leg))
            {
                let stance = self.foot(down, leg);
                for f in down + 1..keep {
                    self.feet[f * self.legs + leg] = stance;
                    self.contacts[f * self.legs + leg] = true;
                }
            }
        }
        // A foot still landing at frame 0 (lifted) that lands by the cut is still landing at
        // it: frame `end` is frame 0 again, so its final swing's correction reaches it.
        for leg in 0..self.legs {
            if !self.planted(0, leg) {
                self.contacts[last * self.legs + leg] = false;
            }
        }
        let (first, end_body) = (self.bodies[0], self.bodies[last]);
        let mut planted_shift = 0.0f32;
        let target = Pose {
            translation: motion.transform_point(first.translation),
            rotation: (motion.rotation * first.rotation).normalize(),
        };
        let turn = (target.rotation * end_body.rotation.inverse()).normalize();
        let shift = target.translation - end_body.translation;
        for (f, body) in self.bodies.iter_mut().enumerate() {
            let s = f as f32 / last as f32;
            body.rotation = (Quat::IDENTITY.slerp(turn, s) * body.rotation).normalize();
            body.translation += shift * s;
        }
        // Each foot's correction turns with the body while it is made (its swings), and is
        // held while the foot is planted: a correction outward at the end of a turn in place
        // is outward all along (in world space, half a turn earlier, it would pull the foot
        // across the body). It reaches the exact world correction with the last swing.
        // Each frame's heading from the last frame's, unwrapped: over a full turn it runs
        // through ±π, where a rotation taken the shortest way round flips the correction to the
        // other side of the body from one frame to the next.
        let mut turned = alloc::vec![0.0f32; keep];
        for f in (0..last).rev() {
            // Both in [-π, π]: one turn at most to take off.
            let mut step =
                heading_angle(self.bodies[f].rotation) - heading_angle(self.bodies[f + 1].rotation);
            if step > PI {
                step -= TAU;
            } else if step < -PI {
                step += TAU;
            }
            turned[f] = turned[f + 1] + step;
        }
        for leg in 0..self.legs {
            let delta = motion.transform_point(self.foot(0, leg)) - self.foot(last, leg);
            // Progress through the correction: by the swing frames' heights above the ground,
            // so a foot takes none of it while it is lifting off or landing near the ground.
            let lift: Vec<f32> = (0..keep)
                .map(|f| {
                    if self.planted(f, leg) {
                        0.0
                    } else {
                        (self.foot(f, leg).y - ground).max(0.0)
                    }
                })
                .collect();
            let swings: f32 = lift[1..].iter().sum();
            if !(swings > 0.0) {
                // Never lifted: its correction can only slide it.
                planted_shift = planted_shift.max(delta.length());
            }
            // Across (turning with the body while made) and up or down apart: a planted foot
            // keeps its height on the ground, so a correction up or down (a cut between two
            // swings at different heights) is made along the final swing, from its lift-off to
            // the last frame.
            let across = Vec3::new(delta.x, 0.0, delta.z);
            let lift_off = (0..keep).rev().find(|&f| self.planted(f, leg)).unwrap_or(0);
            // Per swing frame, the lift of the frames from it to its swing's end.
            let mut ahead = alloc::vec![0.0f32; keep + 1];
            for f in (1..keep).rev() {
                if lift[f] > 0.0 {
                    ahead[f] = lift[f] + ahead[f + 1];
                }
            }
            let mut done = 0.0f32;
            let mut offset = Vec3::ZERO;
            // The heading the correction is turned by, as last made.
            let mut angle: Option<f32> = None;
            for (f, &up) in lift.iter().enumerate().skip(1) {
                if !(swings > 0.0) {
                    offset = across * (f as f32 / last as f32);
                } else if up > 0.0 {
                    done += up;
                    let s = (done / swings).min(1.0);
                    // Turned by the heading only: the body's lean would tip the correction
                    // up or down. The body turned on over the stance before this swing, while
                    // the correction was held: the turn catches up over the swing by its
                    // frames' lift, none of it at once as the foot leaves the ground (a
                    // correction swung across by the stance's turn as the foot lifted off
                    // slid it along the ground).
                    let want = (1.0 - s) * turned[f];
                    let turn = match angle {
                        Some(a) => a + (want - a) * (up / ahead[f]).min(1.0),
                        None => want,
                    };
                    angle = Some(turn);
                    offset = Quat::from_rotation_y(turn) * across * s;
                }
                let rise = if f > lift_off {
                    delta.y * (f - lift_off) as f32 / (last - lift_off) as f32
                } else {
                    0.0
                };
                let p = &mut self.feet[f * self.legs + leg];
                let y = p.y;
                *p += offset + Vec3::Y * rise;
                // A lifted foot at the ends may be corrected downward: never below the
                // ground (y = 0) it was above.
                if y >= 0.0 {
                    p.y = p.y.max(0.0);
                }
            }
        }
        planted_shift
    }

    /// Keeps the first `frames` frames.
    pub(super) fn truncate(&mut self, frames: usize) {
        self.bodies.truncate(frames);
        self.contacts.truncate(frames * self.legs);
        self.feet.truncate(frames * self.legs);
    }

    /// Frame `frame`'s contacts, one per leg.
    pub(super) fn frame_contacts(&self, frame: usize) -> &[bool] {
        &self.contacts[frame * self.legs..][..self.legs]
    }

    pub(super) fn planted(&self, frame: usize, leg: usize) -> bool {
        self.contacts[frame * self.legs + leg]
    }

    /// Over the first `frames` frames, in one pass (each foot taken into the body's frame once
    /// for both): the midline margin, how far (metres) the foot nearest the body's midline is
    /// on its own side of it (negative: a foot crossed to the other side; only walking legs
    /// off the midline), and the overreach, how far (metres) the farthest planted foot is
    /// beyond its leg's reach (only walking legs: an arm holding its place is not on the
    /// ground, and may lag out of reach). `legs`: the run's.
    pub(super) fn margin_and_overreach(&self, frames: usize, legs: &[Leg]) -> (f32, f32) {
        let mut least = f32::INFINITY;
        let mut worst = 0.0f32;
        for (frame, body) in self.bodies.iter().enumerate().take(frames) {
            for (i, leg) in legs.iter().enumerate() {
                if leg.kind != LimbKind::Leg {
                    continue;
                }
                let (off_midline, planted) = (leg.rest.x != 0.0, self.planted(frame, i));
                if !(off_midline || planted) {
                    continue;
                }
                let local = body.inverse_transform_point(self.foot(frame, i));
                if off_midline {
                    least = least.min(local.x * leg.rest.x.signum());
                }
                if planted {
                    worst = worst.max(local.distance(leg.hip) - (leg.upper + leg.lower));
                }
            }
        }
        (least, worst)
    }
}

impl GaitRun {
    /// The farthest (metres) any foot moves across the ground while it is on it (no higher
    /// than `ground`), from where it came down, over the first `frames` frames: a slide,
    /// planted or not.
    pub(super) fn ground_slide(&self, frames: usize, ground: f32) -> f32 {
        let mut worst = 0.0f32;
        for leg in 0..self.legs {
            let mut down: Option<Vec3> = None;
            for f in 0..frames.min(self.frames()) {
                let p = self.foot(f, leg);
                if p.y <= ground {
                    let d = p - *down.get_or_insert(p);
                    worst = worst.max(glam::Vec2::new(d.x, d.z).length());
                } else {
                    down = None;
                }
            }
        }
        worst
    }
}

impl GaitRun {
    /// How far (metres) the two nearest feet of walking legs on the same side are apart along
    /// the body, in their rest positions' order, over the first `frames` frames (negative: a foot passed the
    /// other; `legs`, the run's). Infinite with no two legs on a side.
    pub(super) fn foot_spacing(&self, frames: usize, legs: &[Leg]) -> f32 {
        // The pairs: a leg ahead of another on its side.
        let pairs: Vec<(usize, usize)> = (0..legs.len())
            .flat_map(|i| (0..legs.len()).map(move |j| (i, j)))
            .filter(|&(i, j)| {
                let (a, b) = (&legs[i], &legs[j]);
                a.kind == LimbKind::Leg
                    && b.kind == LimbKind::Leg
                    && a.rest.x * b.rest.x > 0.0
                    && a.rest.z > b.rest.z
            })
            .collect();
        let mut least = f32::INFINITY;
        if pairs.is_empty() {
            return least;
        }
        for (frame, body) in self.bodies.iter().enumerate().take(frames) {
            // Along the body: its forward axis.
            let forward = body.rotation * Vec3::Z;
            let along = |leg: usize| forward.dot(self.foot(frame, leg) - body.translation);
            for &(i, j) in &pairs {
                least = least.min(along(i) - along(j));
            }
        }
        least
    }
}

/// Frame 0 of a run as [`GaitRun::mismatch`] compares other frames with it: its body's tilt
/// (its rotation with the heading taken off), its height and the feet in its frame.
pub(super) struct FirstFrame {
    level: Quat,
    height: f32,
    feet: Vec<Vec3>,
}

/// A body's rotation with its heading taken off: its tilt.
fn level(p: &Pose) -> Quat {
    heading(p.rotation).inverse() * p.rotation
}

/// The rotation about the vertical that turns +Z to where `rotation` points it (the heading,
/// lean and roll aside).
pub(super) fn heading(rotation: Quat) -> Quat {
    Quat::from_rotation_y(heading_angle(rotation))
}

/// The angle of [`heading`] about the vertical, in `[-π, π]`.
fn heading_angle(rotation: Quat) -> f32 {
    let f = rotation * Vec3::Z;
    glam::Vec2::new(f.z, f.x).to_angle()
}

/// The frame of `range` with the same feet planted as frame 0 that has the smallest
/// [`GaitRun::mismatch`] plus `penalty(frame)`; the best frame of the range regardless of
/// contacts if none has them, the last frame if the range is empty.
pub(super) fn best_cut(
    run: &GaitRun,
    range: core::ops::Range<usize>,
    penalty: impl Fn(usize) -> f32,
) -> usize {
    let last = run.frames().saturating_sub(1);
    let range = range.start.min(last).max(1)..range.end.min(last + 1);
    if range.is_empty() {
        return last;
    }
    let first = run.first_frame();
    let score = |f: usize| run.mismatch_from(&first, f) + penalty(f);
    // Frames of the range are frames of the run (from 1: frame 0 is there too).
    let same = |f: &usize| run.frame_contacts(*f) == run.frame_contacts(0);
    let best = |candidates: &mut dyn Iterator<Item = usize>| {
        candidates.fold(None, |best: Option<(f32, usize)>, f| {
            let e = score(f);
            match best {
                Some((b, _)) if b <= e => best,
                _ => Some((e, f)),
            }
        })
    };
    best(&mut range.clone().filter(same))
        .or_else(|| best(&mut range.clone()))
        .map_or(last, |(_, f)| f)
}

/// Up to `count` frames of `range` in the order [`best_cut`] ranks them: those with the same
/// feet planted as frame 0 first, each group by [`GaitRun::mismatch`] plus `penalty(frame)`.
pub(super) fn ranked_cuts(
    run: &GaitRun,
    range: core::ops::Range<usize>,
    penalty: impl Fn(usize) -> f32,
    count: usize,
) -> Vec<usize> {
    let last = run.frames().saturating_sub(1);
    let range = range.start.min(last).max(1)..range.end.min(last + 1);
    if range.is_empty() {
        return Vec::new();
    }
    let first = run.first_frame();
    let mut scored: Vec<(bool, f32, usize)> = range
        .map(|f| {
            (
                run.frame_contacts(f) != run.frame_contacts(0),
                run.mismatch_from(&first, f) + penalty(f),
                f,
            )
        })
        .collect();
    crate::sort::sort_by(&mut scored, &mut |a, b| {
        a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.cmp(&b.2))
    });
    scored.into_iter().take(count).map(|(_, _, f)| f).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One leg over 11 frames: swinging down at frame 0, planted on frames 4 to 6, swinging up
    /// again to frame 10 (higher than at frame 0); the body leaning (about X) on some frames.
    fn one_leg_run() -> GaitRun {
        let heights = [0.3, 0.2, 0.1, 0.05, 0.0, 0.0, 0.0, 0.1, 0.2, 0.35, 0.5];
        let bodies = (0..heights.len())
            .map(|f| Pose {
                translation: Vec3::new(0.0, 1.0, 0.0),
                rotation: Quat::from_rotation_y(0.2 * f as f32)
                    * Quat::from_rotation_x(0.3 * (f % 3) as f32),
            })
            .collect();
        GaitRun {
            bodies,
            feet: heights
                .iter()
                .enumerate()
                .map(|(f, &y)| {
                    // Still while planted.
                    let f = if (4..=6).contains(&f) { 4.0 } else { f as f32 };
                    Vec3::new(0.5 + 0.05 * f, y, 0.1 * f)
                })
                .collect(),
            contacts: heights.iter().map(|&y| y == 0.0).collect(),
            legs: 1,
        }
    }

    #[test]
    fn regression_a_closing_foot_lifting_off_after_a_turning_stance_does_not_slide() {
        // The body turns 0.2 rad a frame, through the stance (frames 4 to 6) too. The
        // correction, held while the foot stood, was turned afresh by the heading still to
        // come at the next swing's first frame: it swung across by the stance's turn as the
        // foot lifted off 0.1 over the ground, sliding it 0.35 at frame 7, where its share of
        // the correction (1.89 across) is 0.13. It now turns on over the swing by its frames'
        // lift.
        let before = one_leg_run();
        let mut run = before.clone();
        // The loop's motion: the body's whole turn, so the closing leaves the turn as it is.
        let motion = Pose {
            translation: Vec3::ZERO,
            rotation: Quat::from_rotation_y(2.0),
        };
        run.close_loop(10, &motion, false, 0.0);
        let moved = |f: usize| {
            let d = run.foot(f, 0) - before.foot(f, 0);
            Vec3::new(d.x, 0.0, d.z)
        };
        let delta = motion.transform_point(before.foot(0, 0)) - before.foot(10, 0);
        let across = Vec3::new(delta.x, 0.0, delta.z).length();
        // Frame 7's share of the lift of every swing frame (1 to 3 and 7 to 10).
        let share = 0.1 / 1.5;
        let jump = (moved(7) - moved(6)).length();
        assert!(
            jump <= 1.5 * share * across,
            "{jump} vs {} ({} then {})",
            share * across,
            moved(6),
            moved(7)
        );
        // And the loop still closes: the last frame's foot is the first's, moved on.
        let closed = motion.transform_point(run.foot(0, 0));
        assert!((run.foot(10, 0) - closed).length() < 1e-5);
    }

    #[test]
    fn regression_closing_a_loop_keeps_planted_feet_on_the_ground() {
        // The correction up or down (frame 10 is higher than frame 0) was spread over the
        // swings and held through the stance between them, and turned with the body's lean:
        // the planted foot stood above the ground.
        let mut run = one_leg_run();
        run.close_loop(10, &Pose::IDENTITY, false, 0.0);
        for f in 4..=6 {
            assert_eq!(run.foot(f, 0).y, 0.0, "frame {f}: {}", run.foot(f, 0));
        }
        // Still planted in one place, and the loop closed.
        assert_eq!(run.foot(4, 0), run.foot(6, 0));
        assert!(run.foot(10, 0).distance(run.foot(0, 0)) < 1e-5);
    }

    #[test]
    fn regression_a_foot_landing_at_frame_0_is_landing_at_the_cut() {
        // Lifted at frame 0 (landing) and planted at the cut: the loop was closed for the
        // body and across but not up or down, the cut's foot left on the ground below frame
        // 0's (the default walker 4's walk missed its loop by 0.08 rad at a knee).
        let mut run = one_leg_run();
        run.close_loop(4, &Pose::IDENTITY, false, 0.0);
        assert!(
            run.foot(4, 0).distance(run.foot(0, 0)) < 1e-5,
            "{} against {}",
            run.foot(4, 0),
            run.foot(0, 0)
        );
        assert!(!run.planted(4, 0));
    }

    #[test]
    fn holding_the_seam_keeps_a_foot_down_until_the_cut() {
        // Planted at frame 0 and lifting off two frames before the cut: held down instead.
        let mut run = one_leg_run();
        run.contacts[0] = true;
        run.feet[0].y = 0.0;
        let (stance, lifted) = (run.foot(6, 0), run.foot(7, 0));
        run.close_loop(8, &Pose::IDENTITY, true, 0.0);
        assert!(run.planted(7, 0) && run.planted(8, 0));
        assert_ne!(run.foot(7, 0), lifted);
        assert_eq!(run.foot(7, 0).y, 0.0);
        assert_eq!(run.foot(7, 0), run.foot(6, 0));
        assert_ne!(
            run.foot(6, 0),
            stance,
            "the stance takes the loop's correction"
        );
    }

    #[test]
    fn ground_slide_measures_a_foot_moving_on_the_ground() {
        let mut run = one_leg_run();
        assert_eq!(run.ground_slide(run.frames(), 1e-3), 0.0);
        // Frame 3 brought down to the ground: 3 to 4 moves across on it.
        run.feet[3].y = 0.0;
        let d = run.foot(4, 0) - run.foot(3, 0);
        let expected = glam::Vec2::new(d.x, d.z).length();
        assert!((run.ground_slide(run.frames(), 1e-3) - expected).abs() < 1e-6);
    }
}
