//! Property tests of the invariants the crate promises, driven by its public strategies.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use creature_limbs::{
    Body, CreatureKind, Limb, LimbKind, Plan, PlanOptions, Side, Socket, plan, strategies,
};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use support::{SplitMix, legs_overlap};

fn all_finite(p: &Plan) -> bool {
    p.lift.is_finite()
        && p.center_of_mass.is_finite()
        && p.stability_margin.is_none_or(f32::is_finite)
        && p.support.iter().all(|v| v.is_finite())
        && p.limbs.iter().all(|l| {
            l.scale.is_finite()
                && l.length.is_finite()
                && l.length >= 0.0
                && l.foot.is_none_or(|f| f.is_finite())
                && l.span.start.is_finite()
                && l.span.end.is_finite()
                && l.span.start <= l.span.end
        })
}

fn check_mirrors(p: &Plan) -> Result<(), TestCaseError> {
    for (i, limb) in p.limbs.iter().enumerate() {
        let Some(j) = limb.mirror else {
            prop_assert!(matches!(limb.kind, LimbKind::DorsalFin | LimbKind::Tail));
            prop_assert_eq!(limb.side, Side::Center);
            continue;
        };
        let twin: &Limb = &p.limbs[j];
        prop_assert_eq!(twin.mirror, Some(i));
        prop_assert_eq!(twin.kind, limb.kind);
        prop_assert_eq!(twin.bone, limb.bone);
        prop_assert_eq!(twin.variant, limb.variant);
        prop_assert_eq!(twin.span, limb.span);
        prop_assert!(
            (limb.side, twin.side) == (Side::Left, Side::Right)
                || (limb.side, twin.side) == (Side::Right, Side::Left)
        );
        if limb.socket != Socket::Top {
            // Side sockets follow the side.
            let expected = if limb.side == Side::Left {
                Socket::Left
            } else {
                Socket::Right
            };
            prop_assert_eq!(limb.socket, expected);
        }
        if !(p.kind == CreatureKind::Walker && limb.kind == LimbKind::Leg) {
            // Walking legs may differ in length on a tilted bone (each reaches the ground).
            prop_assert_eq!(twin.scale, limb.scale);
        }
    }
    Ok(())
}

fn walker_checks(body: &Body, options: &PlanOptions, p: &Plan) -> Result<(), TestCaseError> {
    prop_assert!(p.leg_pairs() >= 1);
    prop_assert!(!legs_overlap(p), "{:?}", p);
    let margin = p.stability_margin.unwrap();
    prop_assert!(margin > 0.0);
    prop_assert!(
        margin >= options.min_margin * body.length * 0.999,
        "margin {} below {}",
        margin,
        options.min_margin * body.length
    );
    prop_assert!(p.lift >= 0.0);
    for leg in p.limbs_of(LimbKind::Leg) {
        let b = &body.bones[leg.bone];
        let socket = if leg.socket == Socket::Left {
            b.left
        } else {
            b.right
        };
        let foot = leg.foot.unwrap();
        let ground = b.ground() - p.lift;
        let tol = 1e-4 * (1.0 + socket.y.abs() + leg.length);
        prop_assert!(
            (foot.y - ground).abs() <= tol,
            "foot {} ground {}",
            foot.y,
            ground
        );
        prop_assert!((socket.y - leg.length - foot.y).abs() <= tol);
        prop_assert!(leg.span.first_bone <= leg.bone && leg.bone <= leg.span.last_bone);
    }
    let arms: Vec<_> = p.limbs_of(LimbKind::Arm).collect();
    prop_assert!(arms.is_empty() || arms.len() == 2);
    for arm in &arms {
        for leg in p.limbs_of(LimbKind::Leg) {
            prop_assert!(!arm.span.overlaps(&leg.span));
            prop_assert_ne!(arm.bone, leg.bone);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 256,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/properties.txt",
        ))),
        ..ProptestConfig::default()
    })]

    #[test]
    fn walkers_stand_without_overlap_and_reach_the_ground(
        body in strategies::body(),
        seed in any::<u64>(),
    ) {
        let options = PlanOptions::DEFAULT;
        let p = plan(&body, CreatureKind::Walker, &options, &mut SplitMix(seed)).unwrap();
        prop_assert!(all_finite(&p));
        walker_checks(&body, &options, &p)?;
        check_mirrors(&p)?;
    }

    #[test]
    fn walkers_stand_under_any_valid_options(
        body in strategies::body(),
        options in strategies::options(),
        seed in any::<u64>(),
    ) {
        let p = plan(&body, CreatureKind::Walker, &options, &mut SplitMix(seed)).unwrap();
        prop_assert!(all_finite(&p));
        walker_checks(&body, &options, &p)?;
    }

    #[test]
    fn fliers_have_one_wing_pair_and_bounded_legs(
        body in strategies::body(),
        seed in any::<u64>(),
    ) {
        let p = plan(&body, CreatureKind::Flier, &PlanOptions::DEFAULT, &mut SplitMix(seed)).unwrap();
        prop_assert!(all_finite(&p));
        check_mirrors(&p)?;
        let wings = p.limbs_of(LimbKind::BuzzingWing).count() + p.limbs_of(LimbKind::FlappingWing).count();
        prop_assert_eq!(wings, 2);
        prop_assert!(p.leg_pairs() <= 8);
        let flapping_bone = p.limbs_of(LimbKind::FlappingWing).next().map(|w| w.bone);
        let free_bones = body.bones.len() - usize::from(flapping_bone.is_some());
        if free_bones > 0 {
            prop_assert!(p.leg_pairs() >= 1);
        }
        prop_assert!(!legs_overlap(&p));
        for leg in p.limbs_of(LimbKind::Leg) {
            prop_assert!(Some(leg.bone) != flapping_bone);
        }
        prop_assert!(p.stability_margin.is_none());
    }

    #[test]
    fn swimmers_have_a_tail_and_non_overlapping_fins(
        body in strategies::body(),
        seed in any::<u64>(),
    ) {
        let p = plan(&body, CreatureKind::Swimmer, &PlanOptions::DEFAULT, &mut SplitMix(seed)).unwrap();
        prop_assert!(all_finite(&p));
        check_mirrors(&p)?;
        prop_assert_eq!(p.limbs_of(LimbKind::Tail).count(), 1);
        let dorsal: Vec<_> = p.limbs_of(LimbKind::DorsalFin).collect();
        prop_assert!(dorsal.len() <= 3);
        let pectoral: Vec<_> = p.limbs_of(LimbKind::PectoralFin).filter(|l| l.side == Side::Left).collect();
        prop_assert!(pectoral.len() <= 2);
        for group in [&dorsal, &pectoral] {
            for (i, a) in group.iter().enumerate() {
                for b in &group[i + 1..] {
                    prop_assert!(a.bone != b.bone && !a.span.overlaps(&b.span));
                }
            }
        }
    }

    #[test]
    fn the_same_seed_gives_the_same_plan(
        body in strategies::body(),
        kind in strategies::creature_kind(),
        options in strategies::options(),
        seed in any::<u64>(),
    ) {
        let a = plan(&body, kind, &options, &mut SplitMix(seed)).unwrap();
        let b = plan(&body, kind, &options, &mut SplitMix(seed)).unwrap();
        prop_assert_eq!(a, b);
    }

    #[test]
    fn invalid_bodies_are_errors(
        body in strategies::invalid_body(),
        kind in strategies::creature_kind(),
    ) {
        prop_assert!(body.validate().is_err());
        prop_assert!(plan(&body, kind, &PlanOptions::DEFAULT, &mut SplitMix(0)).is_err());
    }

    #[test]
    fn invalid_options_are_errors(
        body in strategies::body(),
        options in strategies::invalid_options(),
        kind in strategies::creature_kind(),
    ) {
        prop_assert!(plan(&body, kind, &options, &mut SplitMix(0)).is_err());
    }
}
