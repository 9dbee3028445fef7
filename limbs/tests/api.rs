//! Integration tests through the public API only, including the seed's three failure cases as
//! named regression tests.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use creature_limbs::glam::Vec2;
use creature_limbs::{
    Body, CreatureKind, HeadEnd, LimbKind, LimbsError, Plan, PlanOptions, Repair, Side, Socket,
    WalkerLayout, plan, support_margin,
};
use support::reference::seed_walker;
use support::{SplitMix, legs_overlap, straight_body, walker_body};

fn walker(body: &Body, options: &PlanOptions, seed: u64) -> Plan {
    plan(body, CreatureKind::Walker, options, &mut SplitMix(seed)).unwrap()
}

/// The seed reference's margin, measured the way the planner measures it.
fn seed_margin(body: &Body, options: &PlanOptions, pairs: &[usize]) -> f32 {
    let mut feet = Vec::new();
    let mut shortest = f32::INFINITY;
    for &p in pairs {
        let b = &body.bones[p];
        feet.push(Vec2::new(b.left.x, b.left.z));
        feet.push(Vec2::new(b.right.x, b.right.z));
        shortest = shortest.min(b.clearance);
    }
    support_margin(&feet, options.foot_radius * shortest, body.center_of_mass())
}

#[test]
fn a_four_legged_walker_is_stable_and_mirrored() {
    let body = walker_body(12);
    for seed in 0..20 {
        let p = walker(&body, &PlanOptions::DEFAULT, seed);
        assert!(p.leg_pairs() >= 1);
        let margin = p.stability_margin.unwrap();
        assert!(margin >= 0.02 * body.length, "seed {seed}: {margin}");
        assert!(!legs_overlap(&p), "seed {seed}");
        assert!(p.knee.is_some());
        for (i, limb) in p.limbs.iter().enumerate() {
            let twin = &p.limbs[limb.mirror.unwrap()];
            assert_eq!(twin.mirror, Some(i));
            assert_eq!(twin.bone, limb.bone);
            assert_ne!(twin.side, limb.side);
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
    // The head bone is the widest and stands 6 high: its legs sweep the whole body.
    let body = straight_body(
        &[0.4, 0.4, 0.4, 0.4, 0.4, 1.0],
        &[1.0, 1.0, 1.0, 1.0, 1.0, 6.0],
        0.5,
        HeadEnd::Last,
    );
    let options = PlanOptions::DEFAULT.with_foot_radius(0.05);
    // The seed: one pair at the head end, nothing else fits, and it tips over.
    let seed = seed_walker(&body, options.sweep);
    assert_eq!(seed, vec![5]);
    assert!(seed_margin(&body, &options, &seed) < 0.0);
    // Ours: the layout is rebuilt from another first bone and stands.
    let p = walker(&body, &options, 5);
    assert!(
        p.repairs
            .iter()
            .any(|r| matches!(r, Repair::MovedFirstPair { from: 5, .. })),
        "{:?}",
        p.repairs
    );
    assert!(p.stability_margin.unwrap() >= options.min_margin * body.length);
    assert!(!legs_overlap(&p));
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
    assert!(p.repairs.iter().any(|r| matches!(r, Repair::Lifted { .. })));
    for leg in p.limbs_of(LimbKind::Leg) {
        assert!(leg.length >= 0.08 * body.length * 0.999);
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
    // Widest in the middle, tall legs (big feet), narrow elsewhere.
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
}
