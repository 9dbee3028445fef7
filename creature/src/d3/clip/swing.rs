//! Swings retimed so that a leg's joints turn at an even rate through them.
//!
//! The gait moves a swinging foot along a smooth arc in time with the body, so its knee does
//! most of its bending where the foot drops onto the ground at the end: a fast walker's knee
//! unfolded through 60° between two frames. The clip keeps every swing's path, its lift-off
//! and its landing, and spreads the joints' turn evenly over the swing's frames.

use alloc::vec::Vec;

use glam::Vec3;

use creature_gait::{Leg, LimbKind, Pose};

use super::gait_run::GaitRun;

/// The feet of `run` (world space, frame-major, `legs` per frame like [`GaitRun::feet`]) with
/// each walking leg's swings retimed: the frames of a swing whose foot is well off the ground
/// (not planted, and higher than twice `ground`) keep the path their foot takes in the body's
/// frame (`bodies`, per frame), from where it rises through that height to where it comes
/// down through it, and are spaced along it by equal turns of the leg's joints (see
/// [`joint_turn`]) rather than by time. The frames nearer the ground, the lift-off and the
/// landing, stay as the gait made them.
pub(super) fn even_swings(run: &GaitRun, bodies: &[Pose], legs: &[Leg], ground: f32) -> Vec<Vec3> {
    let mut feet = run.feet.clone();
    let frames = run.frames().min(bodies.len());
    let band = 2.0 * ground;
    let high = |f: usize, i: usize| !run.planted(f, i) && run.foot(f, i).y > band;
    for (i, leg) in legs.iter().enumerate() {
        if leg.kind != LimbKind::Leg {
            continue;
        }
        let mut f = 1;
        while f + 1 < frames {
            if !high(f, i) || high(f - 1, i) {
                f += 1;
                continue;
            }
            // Frames `f ..= last` are high, `f - 1` and `last + 1` are not.
            let mut last = f;
            while last + 1 < frames && high(last + 1, i) {
                last += 1;
            }
            if last + 1 < frames {
                let swing = Swing {
                    leg,
                    index: i,
                    legs: run.legs,
                    band,
                };
                swing.retime(&mut feet, bodies, f..=last);
            }
            f = last + 2;
        }
    }
    feet
}

/// One leg's swing being retimed (see [`even_swings`]).
struct Swing<'a> {
    leg: &'a Leg,
    /// The leg's index, and how many legs each frame of the feet holds.
    index: usize,
    legs: usize,
    /// The height the retimed part of the swing stays above.
    band: f32,
}

impl Swing<'_> {
    /// Retimes the high frames `frames` (the frames either side are not high) in `feet`.
    fn retime(&self, feet: &mut [Vec3], bodies: &[Pose], frames: core::ops::RangeInclusive<usize>) {
        let (first, last) = (*frames.start(), *frames.end());
        let foot = |f: usize| feet[f * self.legs + self.index];
        let local = |f: usize| bodies[f].inverse_transform_point(foot(f));
        // Where (in the body's frame) and when (in frames) the foot rises through the band and
        // comes down through it.
        let crossing = |low: usize, high: usize| {
            let (a, b) = (foot(low).y, foot(high).y);
            let s = if b > a {
                ((self.band - a) / (b - a)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (local(low).lerp(local(high), s), s)
        };
        let (rise, s_in) = crossing(first - 1, first);
        let (fall, s_out) = crossing(last + 1, last);
        let (begin, finish) = ((first - 1) as f32 + s_in, (last + 1) as f32 - s_out);
        let mut path = Vec::with_capacity(last - first + 3);
        path.push(rise);
        path.extend(frames.clone().map(local));
        path.push(fall);
        let mut turned = Vec::with_capacity(path.len());
        let mut total = 0.0f32;
        turned.push(0.0);
        for pair in path.windows(2) {
            total += joint_turn(self.leg, pair[0], pair[1]);
            turned.push(total);
        }
        if !(total > 0.0 && total.is_finite() && finish > begin) {
            return;
        }
        let mut segment = 0;
        for f in frames {
            let want = total * ((f as f32 - begin) / (finish - begin)).clamp(0.0, 1.0);
            while segment + 2 < turned.len() && turned[segment + 1] < want {
                segment += 1;
            }
            let (a, b) = (turned[segment], turned[segment + 1]);
            let t = if b > a {
                ((want - a) / (b - a)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let at = bodies[f].transform_point(path[segment].lerp(path[segment + 1], t));
            // The path is the body's: a body lurching between two frames (a biped shifting
            // onto its other foot) can carry a point of it down to the ground, where the gait's
            // own frame (high, as every retimed frame is) stays.
            if at.y > self.band {
                feet[f * self.legs + self.index] = at;
            }
        }
    }
}

/// How far a two-bone leg's joints turn (radians) as its foot moves from `a` to `b` (body
/// space): the knee's change of bend plus the angle the hip-to-foot direction turns through.
fn joint_turn(leg: &Leg, a: Vec3, b: Vec3) -> f32 {
    let (u, l) = (leg.upper, leg.lower);
    let bend = |p: Vec3| {
        let d = (p - leg.hip).length().clamp((u - l).abs(), u + l);
        let cos = ((u * u + l * l - d * d) / (2.0 * u * l)).clamp(-1.0, 1.0);
        core::f32::consts::FRAC_PI_2 - crate::math::asin(cos)
    };
    let (da, db) = (a - leg.hip, b - leg.hip);
    let direction = match (da.try_normalize(), db.try_normalize()) {
        (Some(x), Some(y)) => super::kinematics::angle_between_vectors(x, y),
        _ => 0.0,
    };
    (bend(a) - bend(b)).abs() + direction
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    /// One leg (hip 1 up, segments 0.7) under a still body, stepping from `z = −0.4` to `0.4`
    /// over frames 1 to 9 along an arc 0.5 high, in time: up quickly, across, and down at the
    /// end in one frame; planted before and after.
    fn quick_landing() -> (GaitRun, Vec<Pose>, Leg) {
        let leg = Leg::new(Vec3::Y, Vec3::ZERO, 0.7, 0.7);
        let mut feet = Vec::new();
        let mut contacts = Vec::new();
        for f in 0..12 {
            let t = ((f as f32 - 1.0) / 8.0).clamp(0.0, 1.0);
            let height = if (2..9).contains(&f) { 0.5 } else { 0.0 };
            feet.push(Vec3::new(0.0, height, -0.4 + 0.8 * t));
            contacts.push(height == 0.0);
        }
        let bodies = alloc::vec![
            Pose {
                translation: Vec3::ZERO,
                rotation: Quat::IDENTITY,
            };
            12
        ];
        let run = GaitRun {
            bodies: bodies.clone(),
            feet,
            contacts,
            legs: 1,
        };
        (run, bodies, leg)
    }

    /// The joints' turn between consecutive frames of `feet` (one leg, a still body).
    fn turns(leg: &Leg, feet: &[Vec3]) -> Vec<f32> {
        feet.windows(2)
            .map(|w| joint_turn(leg, w[0], w[1]))
            .collect()
    }

    #[test]
    fn a_swing_is_spread_evenly_over_its_frames_and_keeps_its_ends() {
        let (run, bodies, leg) = quick_landing();
        let before = turns(&leg, &run.feet);
        let after_feet = even_swings(&run, &bodies, core::slice::from_ref(&leg), 0.01);
        let after = turns(&leg, &after_feet);
        let most = |t: &[f32]| t.iter().copied().fold(0.0, f32::max);
        // The landing's drop was the swing's sharpest turn; spread, no frame turns more than
        // the swing's share per frame (and the lift-off and landing frames stay).
        assert!(
            most(&after) < 0.6 * most(&before),
            "{after:?} vs {before:?}"
        );
        for f in [0, 1, 9, 10, 11] {
            assert_eq!(after_feet[f], run.feet[f], "frame {f}");
        }
        // Every retimed frame is on the swing's path (at its height, between its ends).
        for foot in &after_feet[2..9] {
            assert!(foot.y > 0.02 && foot.z >= -0.4 && foot.z <= 0.4, "{foot}");
        }
    }

    #[test]
    fn a_foot_never_off_the_ground_is_left_alone() {
        let (mut run, bodies, leg) = quick_landing();
        for foot in &mut run.feet {
            foot.y = 0.0;
        }
        let feet = even_swings(&run, &bodies, core::slice::from_ref(&leg), 0.01);
        assert_eq!(feet, run.feet);
    }
}
