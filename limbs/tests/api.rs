//! Integration tests through the public API only, including the seed's three failure cases as
//! named regression tests.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use creature_limbs::glam::Vec3;
use creature_limbs::{
    Body, CreatureKind, HeadEnd, Limb, LimbKind, LimbsError, Plan, PlanOptions, Repair, Side,
    Socket, WalkerLayout, plan,
};
use support::reference::seed_walker;
use support::{SplitMix, legs_overlap, margin_of, straight_body, walker_body};

fn walker(body: &Body, options: &PlanOptions, seed: u64) -> Plan {
    plan(body, CreatureKind::Walker, options, &mut SplitMix(seed)).unwrap()
}

/// The socket point a side limb attaches to.
fn socket_point(body: &Body, limb: &Limb) -> Vec3 {
    let b = &body.bones[limb.bone];
    match limb.socket {
        Socket::Left => b.left,
        Socket::Right => b.right,
        Socket::Top | Socket::Tip => b.top,
        other => unreachable!("a socket this test does not know: {other:?}"),
    }
}

#[test]
fn a_four_legged_walker_is_stable_and_mirrored() {
    // Hips and chest, facing +Z (the head is the last bone): left sockets on +X.
    let body = walker_body(12);
    let options = PlanOptions::DEFAULT;
    for seed in 0..20 {
        let p = walker(&body, &options, seed);
        assert_eq!(p.leg_pairs(), 2, "seed {seed}: {p:?}");
        assert_eq!(p.layout, Some(WalkerLayout::TwoWide));
        let margin = p.stability_margin.unwrap();
        assert!(
            margin >= options.min_margin * body.length,
            "seed {seed}: {margin}"
        );
        // The margin is what the public support polygon code measures for these feet.
        let bones: Vec<usize> = p.limbs_of(LimbKind::Leg).map(|l| l.bone).collect();
        assert!((margin - margin_of(&body, &options, &bones)).abs() < 1e-5);
        assert!(!legs_overlap(&p), "seed {seed}");
        assert!(p.knee.is_some());
        for (i, limb) in p.limbs.iter().enumerate() {
            let twin = &p.limbs[limb.mirror.unwrap()];
            assert_eq!(twin.mirror, Some(i));
            assert_eq!(twin.bone, limb.bone);
            assert_ne!(twin.side, limb.side);
            // The body's mid-plane is x = 0: twins' sockets and feet are reflections across it.
            let mirror = Vec3::new(-1.0, 1.0, 1.0);
            let (a, b) = (socket_point(&body, limb), socket_point(&body, twin));
            assert!((a * mirror - b).length() < 1e-6, "{a} {b}");
            if let (Some(fa), Some(fb)) = (limb.foot, twin.foot) {
                assert!((fa * mirror - fb).length() < 1e-6, "{fa} {fb}");
            }
            // The creature faces +Z, so its left is +X.
            if limb.side == Side::Left {
                assert!(a.x > 0.0);
            }
        }
    }
}

#[test]
fn the_hip_and_chest_body_gets_two_wide_pairs() {
    let body = walker_body(12);
    let p = walker(&body, &PlanOptions::DEFAULT, 3);
    assert_eq!(p.layout, Some(WalkerLayout::TwoWide));
    assert!(p.leg_pairs() >= 2);
}

#[test]
fn a_long_low_body_gets_many_pairs() {
    // A centipede: 14 bones, 0.3 above the ground, length 4.5 > 3 x 0.3.
    let body = straight_body(&[0.5; 14], &[0.3; 14], 0.3, HeadEnd::Last);
    let p = walker(&body, &PlanOptions::DEFAULT, 1);
    assert_eq!(p.layout, Some(WalkerLayout::Fill));
    assert!(p.leg_pairs() >= 4, "{}", p.leg_pairs());
    assert!(!legs_overlap(&p));
}

#[test]
fn a_slitherer_gets_no_limbs_and_draws_nothing() {
    struct Counting(u64);
    impl creature_limbs::rand_core::TryRng for Counting {
        type Error = core::convert::Infallible;
        fn try_next_u32(&mut self) -> Result<u32, Self::Error> {
            self.0 += 1;
            Ok(0)
        }
        fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
            self.0 += 1;
            Ok(0)
        }
        fn try_fill_bytes(&mut self, dest: &mut [u8]) -> Result<(), Self::Error> {
            self.0 += 1;
            dest.fill(0);
            Ok(())
        }
    }
    let body = straight_body(&[0.3; 16], &[0.2; 16], 0.1, HeadEnd::Last);
    let mut rng = Counting(0);
    let p = plan(
        &body,
        CreatureKind::Slitherer,
        &PlanOptions::DEFAULT,
        &mut rng,
    )
    .unwrap();
    assert!(p.limbs.is_empty(), "{p:?}");
    assert_eq!(p.kind, CreatureKind::Slitherer);
    assert_eq!(rng.0, 0, "a plan without limbs draws nothing");
}

#[test]
fn walking_legs_reach_the_ground() {
    let body = walker_body(9);
    let p = walker(&body, &PlanOptions::DEFAULT, 11);
    for leg in p.limbs_of(LimbKind::Leg) {
        let b = &body.bones[leg.bone];
        let socket = match leg.socket {
            Socket::Left => b.left,
            _ => b.right,
        };
        let foot = leg.foot.unwrap();
        assert!((socket.y - leg.length - foot.y).abs() < 1e-5);
        assert!((foot.y - (b.ground() - p.lift)).abs() < 1e-5);
    }
}

/// Seed failure 1: "If a very large pair of legs is added to the front or back of the creature
/// to start with, it may overlap all available slots. This can leave the creature unbalanced
/// with no free spaces to add more legs to correct."
#[test]
fn regression_large_first_pair_covering_every_slot_is_moved() {
    // The head bone is the widest and stands 6 high: its legs sweep the whole body. The centre
    // of mass is 19% of the body length behind that bone.
    let body = straight_body(
        &[0.4, 0.4, 0.4, 0.4, 0.4, 1.0],
        &[1.0, 1.0, 1.0, 1.0, 1.0, 6.0],
        0.5,
        HeadEnd::Last,
    );
    let options = PlanOptions::DEFAULT;
    let required = options.min_margin * body.length;
    // The seed: one pair at the head end, nothing else fits, and it tips over, with the
    // default (leg-size-independent) feet.
    let seed = seed_walker(&body, options.sweep);
    assert_eq!(seed, vec![5]);
    let offset = body.center_of_mass().y - body.bones[5].along;
    assert!(offset.abs() > 0.18 * body.length, "{offset}");
    assert!(margin_of(&body, &options, &seed) < 0.0);
    // Ours: the layout is rebuilt without the covering pair, from pairs that straddle the
    // centre of mass, and stands on feet of the default size.
    for seed in 0..10 {
        let p = walker(&body, &options, seed);
        assert_eq!(p.layout, Some(WalkerLayout::Rebuilt), "{p:?}");
        assert!(
            p.repairs.contains(&Repair::DroppedPair { bone: 5 }),
            "{:?}",
            p.repairs
        );
        assert!(p.limbs_of(LimbKind::Leg).all(|l| l.bone != 5));
        assert!(p.leg_pairs() >= 2);
        for leg in p.limbs_of(LimbKind::Leg) {
            assert!(
                p.repairs.contains(&Repair::AddedPair { bone: leg.bone }),
                "{:?}",
                p.repairs
            );
        }
        assert_eq!(p.lift, 0.0, "stability never comes from lifting");
        assert!(!p.repairs.iter().any(|r| matches!(r, Repair::Lifted { .. })));
        let margin = p.stability_margin.unwrap();
        assert!(margin >= required, "{margin}");
        let bones: Vec<usize> = p.limbs_of(LimbKind::Leg).map(|l| l.bone).collect();
        assert!((margin - margin_of(&body, &options, &bones)).abs() < 1e-5);
        assert!(!legs_overlap(&p));
    }
}

/// Review finding: stability was bought with foot size (a foot radius proportional to leg
/// length), so long legs alone made a lone pair far from the centre of mass "stable".
#[test]
fn regression_long_legs_do_not_make_a_lone_pair_stable() {
    // One pair on bone 5 of six, the centre of mass well behind it. With legs 1 or 100 long,
    // the margin of that lone pair is the same, and negative.
    let widths = [0.4, 0.4, 0.4, 0.4, 0.4, 1.0];
    let short = straight_body(&widths, &[1.0; 6], 0.5, HeadEnd::Last);
    let tall = straight_body(&widths, &[100.0; 6], 0.5, HeadEnd::Last);
    let options = PlanOptions::DEFAULT;
    let (a, b) = (
        margin_of(&short, &options, &[5]),
        margin_of(&tall, &options, &[5]),
    );
    assert_eq!(a, b);
    assert!(a < 0.0);
    // So the planner never settles for it: the tall walker's legs cover each other, and it
    // stands on several pairs or not at all.
    let p = walker(&short, &options, 1);
    assert!(p.leg_pairs() >= 2);
    match plan(&tall, CreatureKind::Walker, &options, &mut SplitMix(1)) {
        Ok(p) => assert!(p.leg_pairs() >= 2 && p.stability_margin.unwrap() > 0.0),
        Err(e) => assert!(matches!(e, LimbsError::NoStableLayout { .. }), "{e}"),
    }
}

/// The seed's biped rule ("stick with one pair of legs" when the widest bone is within two
/// bones of the centre) only stands when the mass is really over the feet: a widest bone two
/// bones off-centre gets a balancing pair.
#[test]
fn an_off_centre_biped_gets_a_balancing_pair() {
    let body = straight_body(
        &[0.3, 0.3, 0.3, 0.3, 0.3, 0.9, 0.5, 0.3, 0.3],
        &[2.0; 9],
        0.4,
        HeadEnd::Last,
    );
    let options = PlanOptions::DEFAULT.with_arm_chance(0.0);
    // The widest bone (5) is within two bones of the middle (4), but the lone pair tips.
    assert!(margin_of(&body, &options, &[5]) < options.min_margin * body.length);
    let p = walker(&body, &options, 0);
    assert_eq!(p.layout, Some(WalkerLayout::Balanced), "{p:?}");
    assert!(p.leg_pairs() >= 2);
    assert!(p.limbs_of(LimbKind::Leg).any(|l| l.bone == 5));
    assert!(
        p.repairs
            .iter()
            .any(|r| matches!(r, Repair::AddedPair { .. }))
    );
    assert!(p.stability_margin.unwrap() >= options.min_margin * body.length);
}

/// Review finding: the old last-resort repair replaced every pair with one, on any bone, without
/// recording the dropped pairs, and could leave legs below `min_leg_length`.
#[test]
fn regression_rebuilt_layouts_use_only_tall_enough_bones_and_say_so() {
    // Bone 4 is the widest and tallest (its legs cover all others); bones 0 and 1 are too low
    // for legs. Only bones 2, 3 and 4 may carry legs.
    let body = straight_body(
        &[0.4, 0.4, 0.4, 0.4, 1.0],
        &[0.05, 0.05, 1.0, 1.0, 5.0],
        0.5,
        HeadEnd::Last,
    );
    let options = PlanOptions::DEFAULT;
    let min = options.min_leg_length * body.length;
    for seed in 0..10 {
        match plan(&body, CreatureKind::Walker, &options, &mut SplitMix(seed)) {
            Ok(p) => {
                for leg in p.limbs_of(LimbKind::Leg) {
                    assert!(leg.bone >= 2 && leg.length >= min, "{p:?}");
                }
                assert!(p.repairs.contains(&Repair::SkippedLowBone {
                    bone: 0,
                    leg_length: 0.05
                }));
                let legs: Vec<usize> = p.limbs_of(LimbKind::Leg).map(|l| l.bone).collect();
                for r in &p.repairs {
                    match *r {
                        Repair::AddedPair { bone } => assert!(legs.contains(&bone)),
                        Repair::DroppedPair { bone } => assert!(!legs.contains(&bone)),
                        _ => {}
                    }
                }
                assert!(p.stability_margin.unwrap() >= options.min_margin * body.length);
            }
            Err(e) => assert!(matches!(e, LimbsError::NoStableLayout { .. }), "{e}"),
        }
    }
}

/// A short spine under long legs: only one pair fits at full stride, and the mass lies between
/// the bones. As a last resort the strides are shortened so both pairs fit.
#[test]
fn a_short_spine_under_long_legs_takes_shorter_strides() {
    // Two equal bones 0.3 apart whose 2-long legs sweep ±1 around them.
    let body = straight_body(&[0.5, 0.5], &[2.0, 2.0], 0.3, HeadEnd::Last);
    let options = PlanOptions::DEFAULT;
    // Either pair alone tips: the mass is 0.15 from its feet, the foot radius 0.045.
    assert!(margin_of(&body, &options, &[0]) < 0.0);
    let p = walker(&body, &options, 0);
    assert_eq!(p.leg_pairs(), 2);
    assert_eq!(p.layout, Some(WalkerLayout::Rebuilt));
    let stride = p
        .repairs
        .iter()
        .find_map(|r| match *r {
            Repair::ShortenedStride { sweep } => Some(sweep),
            _ => None,
        })
        .unwrap();
    assert!(stride < options.sweep && stride > 0.07, "{stride}");
    assert!(!legs_overlap(&p));
    for leg in p.limbs_of(LimbKind::Leg) {
        assert!((leg.span.end - leg.span.start - 2.0 * stride * 2.0).abs() < 1e-5);
    }
    assert!(p.stability_margin.unwrap() >= options.min_margin * body.length);
}

/// When no layout can stand, the planner says so instead of returning a walker that tips.
#[test]
fn a_walker_that_cannot_stand_is_an_error() {
    // Asking for a margin no layout can give (40% of the body length, on a body 0.6 wide).
    let body = straight_body(&[0.6, 0.6, 0.6], &[1.0, 1.0, 1.0], 0.5, HeadEnd::Last);
    let options = PlanOptions::DEFAULT.with_min_margin(0.4);
    let err = plan(&body, CreatureKind::Walker, &options, &mut SplitMix(0)).unwrap_err();
    match err {
        LimbsError::NoStableLayout { margin, required } => {
            assert!(margin < required);
            assert_eq!(required, options.min_margin * body.length);
        }
        other => panic!("{other}"),
    }
}

/// A heavy end too low for legs: the mass lies beyond every bone that can carry legs, so no
/// layout on those bones stands (this was `NoStableLayout`). The planner lifts the body until
/// the heavy end can carry legs too, and it stands.
#[test]
fn a_heavy_end_too_low_for_legs_is_lifted_to_stand() {
    let body = straight_body(&[0.3, 0.3, 2.0], &[1.0, 1.0, 0.01], 0.5, HeadEnd::Last);
    let options = PlanOptions::DEFAULT;
    let min_len = options.min_leg_length * body.length;
    assert!(margin_of(&body, &options, &[0, 1]) < options.min_margin * body.length);
    let p = walker(&body, &options, 0);
    assert!(p.stability_margin.unwrap() >= options.min_margin * body.length);
    assert_eq!(p.layout, Some(WalkerLayout::Rebuilt));
    assert!(
        p.repairs.contains(&Repair::LiftedToStand { by: p.lift }),
        "{:?}",
        p.repairs
    );
    assert!(
        !p.repairs
            .iter()
            .any(|r| matches!(r, Repair::Lifted { .. } | Repair::SkippedLowBone { .. })),
        "{:?}",
        p.repairs
    );
    // Every bone is now tall enough for legs; the heavy end carries a pair.
    assert!(p.lift > 0.0 && p.lift < min_len);
    assert!(p.limbs_of(LimbKind::Leg).any(|l| l.bone == 2));
    for leg in p.limbs_of(LimbKind::Leg) {
        assert!(leg.length >= min_len, "{leg:?}");
    }
    // Allowing shorter legs lets the heavy end carry legs without that repair.
    let p = walker(&body, &options.with_min_leg_length(0.001), 0);
    assert!(p.stability_margin.unwrap() >= options.min_margin * body.length);
    assert!(
        !p.repairs
            .iter()
            .any(|r| matches!(r, Repair::LiftedToStand { .. }))
    );
}

/// Seed failure 2: "if spine bending results in the thickest part of the creature being very
/// close to the ground, then very tiny legs may be attached".
#[test]
fn regression_tiny_legs_under_a_low_body_are_avoided() {
    // The widest bone sits 0.02 above the ground (minimum leg: 0.08 x 2.8 = 0.22).
    let body = straight_body(
        &[0.4, 0.5, 1.0, 0.5, 0.4, 0.4],
        &[1.5, 1.4, 0.02, 1.4, 1.5, 1.5],
        0.4,
        HeadEnd::Last,
    );
    let options = PlanOptions::DEFAULT;
    let seed = seed_walker(&body, options.sweep);
    assert_eq!(seed[0], 2, "the seed puts its first pair on the low bone");
    let p = walker(&body, &options, 2);
    assert!(p.repairs.contains(&Repair::SkippedLowBone {
        bone: 2,
        leg_length: 0.02
    }));
    let min = options.min_leg_length * body.length;
    for leg in p.limbs_of(LimbKind::Leg) {
        assert!(leg.length >= min, "{} < {min}", leg.length);
        assert_ne!(leg.bone, 2);
    }
    assert!(p.stability_margin.unwrap() > 0.0);
}

/// Seed failure 2, everywhere: a body lying on the ground is lifted instead.
#[test]
fn regression_a_body_on_the_ground_is_lifted() {
    let body = straight_body(&[0.5; 5], &[0.0; 5], 0.5, HeadEnd::First);
    let p = walker(&body, &PlanOptions::DEFAULT, 9);
    assert!(p.lift > 0.0);
    assert!(p.repairs.contains(&Repair::Lifted { by: p.lift }));
    for leg in p.limbs_of(LimbKind::Leg) {
        assert!(leg.length >= 0.08 * body.length);
    }
    assert!(p.stability_margin.unwrap() >= 0.02 * body.length);
}

/// Seed failure 3: "it does not account for the size of legs when adding them [...] A large
/// pair could conceivably be added to the first available bone next to the small legs and
/// overlap them."
#[test]
fn regression_large_legs_are_not_placed_over_small_ones() {
    // Bone 1 is widest with short legs; bone 2 is nearly as wide with long legs whose sweep
    // covers bone 1.
    let body = straight_body(
        &[0.3, 1.0, 0.9, 0.3, 0.3, 0.3],
        &[3.0, 0.6, 4.0, 3.0, 3.0, 3.0],
        1.0,
        HeadEnd::Last,
    );
    let options = PlanOptions::DEFAULT;
    // The seed marks only bone 1 and then puts the long legs on bone 2, over the short ones.
    let seed = seed_walker(&body, options.sweep);
    assert_eq!(seed, vec![1, 2]);
    let (a, b) = (&body.bones[1], &body.bones[2]);
    assert!((a.along - b.along).abs() < options.sweep * (a.clearance + b.clearance));
    // Ours measures both legs' sweeps: nothing on bone 2, and no overlap anywhere.
    let p = walker(&body, &options, 4);
    assert!(p.limbs_of(LimbKind::Leg).all(|l| l.bone != 2));
    assert!(!legs_overlap(&p));
    assert!(p.stability_margin.unwrap() > 0.0);
}

#[test]
fn a_biped_keeps_one_central_pair_when_it_stands() {
    // Widest in the middle, narrow elsewhere: the centre of mass is over the middle bone.
    let body = straight_body(
        &[0.2, 0.3, 1.0, 0.3, 0.2],
        &[2.0, 2.0, 2.0, 2.0, 2.0],
        0.3,
        HeadEnd::Last,
    );
    let p = walker(&body, &PlanOptions::DEFAULT.with_arm_chance(0.0), 0);
    assert_eq!(p.layout, Some(WalkerLayout::Biped));
    assert_eq!(p.leg_pairs(), 1);
    assert!(p.repairs.is_empty(), "{:?}", p.repairs);
    assert!(p.stability_margin.unwrap() > 0.0);
}

#[test]
fn arms_go_between_the_head_and_the_legs() {
    // A biped with its legs mid-body and room between them and the head.
    let body = straight_body(
        &[0.3, 0.3, 0.3, 0.5, 1.0, 0.5, 0.3, 0.3, 0.3, 0.3],
        &[2.5; 10],
        0.6,
        HeadEnd::Last,
    );
    let options = PlanOptions::DEFAULT.with_arm_chance(100.0);
    let p = walker(&body, &options, 8);
    let arms: Vec<_> = p.limbs_of(LimbKind::Arm).collect();
    assert_eq!(arms.len(), 2, "{p:?}");
    for arm in &arms {
        assert!(arm.foot.is_none());
        for leg in p.limbs_of(LimbKind::Leg) {
            assert!(!arm.span.overlaps(&leg.span));
        }
        // Shorter than its socket's height: it never reaches the ground.
        assert!(arm.length <= body.bones[arm.bone].clearance + p.lift);
    }
    // No arms when the chance is zero.
    let p = walker(&body, &options.with_arm_chance(0.0), 8);
    assert_eq!(p.limbs_of(LimbKind::Arm).count(), 0);
}

/// Review finding: an arm's length is a drawn fraction of its socket's height, so a draw of 0
/// (or a low socket) gave zero-length arms. They are now left out, and the plan says so.
#[test]
fn regression_zero_length_arms_are_dropped() {
    let body = straight_body(
        &[0.3, 0.3, 0.3, 0.5, 1.0, 0.5, 0.3, 0.3, 0.3, 0.3],
        &[2.5; 10],
        0.6,
        HeadEnd::Last,
    );
    let options = PlanOptions::DEFAULT
        .with_arm_chance(100.0)
        .with_arm_length([0.0, 0.0]);
    let p = walker(&body, &options, 8);
    assert_eq!(p.limbs_of(LimbKind::Arm).count(), 0);
    assert!(p.repairs.contains(&Repair::DroppedArms { length: 0.0 }));
    // Arms that are drawn long enough are kept, at least `min_arm_length` long.
    let options = options.with_arm_length([0.5, 0.5]);
    let p = walker(&body, &options, 8);
    for arm in p.limbs_of(LimbKind::Arm) {
        assert!(arm.length >= options.min_arm_length * body.length);
    }
    assert_eq!(p.limbs_of(LimbKind::Arm).count(), 2);
}

#[test]
fn fliers_get_one_wing_pair_and_up_to_eight_leg_pairs() {
    let body = walker_body(10);
    let mut saw = [false; 2];
    for seed in 0..40 {
        let p = plan(
            &body,
            CreatureKind::Flier,
            &PlanOptions::DEFAULT,
            &mut SplitMix(seed),
        )
        .unwrap();
        let buzzing: Vec<_> = p.limbs_of(LimbKind::BuzzingWing).collect();
        let flapping: Vec<_> = p.limbs_of(LimbKind::FlappingWing).collect();
        assert_eq!(buzzing.len() + flapping.len(), 2);
        if let Some(w) = buzzing.first() {
            saw[0] = true;
            assert_eq!(w.socket, Socket::Top);
            assert!(body.head_rank(w.bone) < body.bones.len().div_ceil(2));
        }
        if let Some(w) = flapping.first() {
            saw[1] = true;
            assert_eq!(w.scale.x, w.scale.y);
            assert_eq!(w.bone, body.from_head((body.bones.len() - 1) / 2));
            for leg in p.limbs_of(LimbKind::Leg) {
                assert_ne!(leg.bone, w.bone);
            }
        }
        assert!((1..=8).contains(&p.leg_pairs()));
        assert!(!legs_overlap(&p));
        assert!(p.stability_margin.is_none());
    }
    assert_eq!(saw, [true, true]);
}

#[test]
fn swimmers_get_fins_and_one_tail() {
    let body = walker_body(10);
    for seed in 0..30 {
        let p = plan(
            &body,
            CreatureKind::Swimmer,
            &PlanOptions::DEFAULT,
            &mut SplitMix(seed),
        )
        .unwrap();
        let tails: Vec<_> = p.limbs_of(LimbKind::Tail).collect();
        assert_eq!(tails.len(), 1);
        assert_eq!(tails[0].socket, Socket::Tip);
        assert_eq!(tails[0].bone, body.from_head(body.bones.len() - 1));
        let dorsal: Vec<_> = p.limbs_of(LimbKind::DorsalFin).collect();
        assert!(dorsal.len() <= 3);
        for (i, a) in dorsal.iter().enumerate() {
            assert_eq!(a.socket, Socket::Top);
            assert_eq!(a.side, Side::Center);
            for b in &dorsal[i + 1..] {
                assert!(!a.span.overlaps(&b.span));
            }
        }
        assert!(p.limbs_of(LimbKind::PectoralFin).count() <= 4);
        assert!(p.knee.is_none());
    }
}

#[test]
fn the_same_seed_gives_the_same_plan() {
    let body = walker_body(12);
    for kind in [
        CreatureKind::Walker,
        CreatureKind::Flier,
        CreatureKind::Swimmer,
    ] {
        let a = plan(&body, kind, &PlanOptions::DEFAULT, &mut SplitMix(77)).unwrap();
        let b = plan(&body, kind, &PlanOptions::DEFAULT, &mut SplitMix(77)).unwrap();
        assert_eq!(a, b);
    }
}

#[test]
fn a_single_bone_body_is_planned() {
    let body = straight_body(&[0.5], &[0.5], 1.0, HeadEnd::Last);
    for kind in [
        CreatureKind::Walker,
        CreatureKind::Flier,
        CreatureKind::Swimmer,
    ] {
        let p = plan(&body, kind, &PlanOptions::DEFAULT, &mut SplitMix(3)).unwrap();
        if kind == CreatureKind::Walker {
            assert_eq!(p.leg_pairs(), 1);
            assert!(p.stability_margin.unwrap() >= 0.02 * body.length);
        }
    }
}

#[test]
fn bad_input_is_an_error() {
    let mut body = walker_body(4);
    body.bones.clear();
    let err = plan(
        &body,
        CreatureKind::Walker,
        &PlanOptions::DEFAULT,
        &mut SplitMix(0),
    );
    assert_eq!(err, Err(LimbsError::NoBones));

    let mut body = walker_body(4);
    body.bones[2].width = -1.0;
    let err = plan(
        &body,
        CreatureKind::Flier,
        &PlanOptions::DEFAULT,
        &mut SplitMix(0),
    );
    assert!(matches!(err, Err(LimbsError::Negative { bone: 2, .. })));

    let mut body = walker_body(4);
    body.bones[1].clearance = f32::NAN;
    let err = plan(
        &body,
        CreatureKind::Swimmer,
        &PlanOptions::DEFAULT,
        &mut SplitMix(0),
    );
    assert!(matches!(err, Err(LimbsError::NonFinite { bone: 1, .. })));

    let err = plan(
        &walker_body(4),
        CreatureKind::Walker,
        &PlanOptions::DEFAULT.with_sweep(-1.0),
        &mut SplitMix(0),
    );
    assert!(matches!(
        err,
        Err(LimbsError::InvalidOption { name: "sweep", .. })
    ));

    let mut body = walker_body(4);
    body.length = f32::NAN;
    let err = plan(
        &body,
        CreatureKind::Walker,
        &PlanOptions::DEFAULT,
        &mut SplitMix(0),
    )
    .unwrap_err();
    assert!(matches!(err, LimbsError::InvalidLength { .. }));
    // The message is about the body length, not about a bone.
    assert!(!err.to_string().contains("bone"), "{err}");
}
