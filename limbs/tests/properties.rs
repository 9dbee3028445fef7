//! Property tests of the invariants the crate promises, driven by its public strategies.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use creature_limbs::glam::{Vec2, Vec3, Vec3Swizzles};
use creature_limbs::{
    Body, CreatureKind, HeadEnd, Limb, LimbKind, LimbsError, Plan, PlanOptions, Repair, Side,
    Socket, WalkerLayout, plan, strategies,
};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use support::{
    SplitMix, best_possible_margin, legs_overlap, margin_of, tall_enough_bones, walking_legs,
};

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

/// Mirror twins: paired both ways, same kind, bone, variant and span, opposite sides; side
/// limbs on their side's socket; and geometrically, twins' sockets and feet are reflections of
/// each other across the body's mid-plane at their bone (the vertical plane through the bone's
/// centre, square to its left–right direction), with the left one on the creature's left.
fn check_mirrors(body: &Body, p: &Plan) -> Result<(), TestCaseError> {
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
        if limb.side != Side::Left {
            continue;
        }
        // Geometry, in the ground plane: the bone's mid-plane passes through its centre with
        // normal `n` (from its right socket to its left one).
        let b = &body.bones[limb.bone];
        let center = b.center().xz();
        let n = (b.left - b.right).xz().normalize_or_zero();
        let reflect = |v: Vec2| v - 2.0 * (v - center).dot(n) * n;
        let tol = 1e-4 * (1.0 + center.abs().max_element() + b.width);
        if limb.socket != Socket::Top && n != Vec2::ZERO {
            let (l, r) = (b.left.xz(), b.right.xz());
            prop_assert!(reflect(l).distance(r) <= tol, "sockets {} {}", l, r);
        }
        if let (Some(fl), Some(fr)) = (limb.foot, twin.foot) {
            if n != Vec2::ZERO {
                prop_assert!(
                    reflect(fl.xz()).distance(fr.xz()) <= tol,
                    "feet {} {}",
                    fl,
                    fr
                );
                // The left foot is on the creature's left of the mid-plane.
                prop_assert!((fl.xz() - center).dot(n) > 0.0);
            }
            if p.kind == CreatureKind::Walker {
                prop_assert_eq!(fl.y, fr.y);
            }
        }
    }
    Ok(())
}

/// The creature faces its head (the strategies' convention): its left is up × forward.
fn check_body_faces_its_head(body: &Body) -> Result<(), TestCaseError> {
    let forward = if body.head == HeadEnd::Last {
        1.0
    } else {
        -1.0
    };
    let left_dir = Vec3::Y.cross(Vec3::Z * forward);
    for b in &body.bones {
        prop_assert!((b.left - b.right).dot(left_dir) > 0.0);
    }
    Ok(())
}

fn walker_checks(body: &Body, options: &PlanOptions, p: &Plan) -> Result<(), TestCaseError> {
    let required = options.min_margin * body.length;
    let min_leg = options.min_leg_length * body.length;
    prop_assert!(p.leg_pairs() >= 1);
    prop_assert!(!legs_overlap(p), "{:?}", p);
    let margin = p.stability_margin.unwrap();
    prop_assert!(margin > 0.0);
    prop_assert!(margin >= required, "margin {} below {}", margin, required);
    // The reported margin is the one the public support polygon code measures for the feet,
    // with a foot radius that does not depend on the legs.
    let bones: Vec<usize> = p
        .limbs_of(LimbKind::Leg)
        .filter(|l| l.side == Side::Left)
        .map(|l| l.bone)
        .collect();
    let measured = margin_of(body, options, &bones);
    prop_assert!(
        (margin - measured).abs() <= 1e-4 * (1.0 + body.length),
        "reported {} measured {}",
        margin,
        measured
    );
    prop_assert!(p.lift >= 0.0);
    for leg in p.limbs_of(LimbKind::Leg) {
        prop_assert!(
            leg.length >= min_leg,
            "leg {} below {}",
            leg.length,
            min_leg
        );
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
    // Layout names match the legs.
    match p.layout.unwrap() {
        WalkerLayout::Biped => prop_assert_eq!(p.leg_pairs(), 1),
        WalkerLayout::TwoWide | WalkerLayout::Balanced => prop_assert!(p.leg_pairs() >= 2),
        WalkerLayout::Fill | WalkerLayout::Rebuilt => {}
        other => prop_assert!(false, "a layout this test does not know: {other:?}"),
    }
    // Repairs are truthful.
    let mut lifted = false;
    for r in &p.repairs {
        match *r {
            Repair::AddedPair { bone } => prop_assert!(bones.contains(&bone), "{:?}", p),
            Repair::DroppedPair { bone } => {
                prop_assert!(!bones.contains(&bone), "{:?}", p);
                prop_assert_eq!(p.layout, Some(WalkerLayout::Rebuilt));
            }
            Repair::SkippedLowBone { bone, leg_length } => {
                prop_assert!(!bones.contains(&bone));
                prop_assert!(leg_length < min_leg || leg_length <= 0.0);
            }
            Repair::Lifted { by } => {
                prop_assert_eq!(by, p.lift);
                lifted = true;
            }
            Repair::LiftedToStand { by } => {
                prop_assert_eq!(by, p.lift);
                prop_assert_eq!(p.layout, Some(WalkerLayout::Rebuilt));
                lifted = true;
                // Only when legs on every bone tall enough without it would not stand; and
                // afterwards every bone is tall enough.
                let (_, tall) = tall_enough_bones(body, options);
                prop_assert!(margin_of(body, options, &tall) < required, "{:?}", p);
                for bone in 0..body.bones.len() {
                    let (l, r) = walking_legs(body, bone, p.lift);
                    prop_assert!(l.min(r) >= min_leg && l.min(r) > 0.0, "{:?}", p);
                }
            }
            Repair::DroppedArms { length } => {
                prop_assert!(!(length >= options.min_arm_length * body.length && length > 0.0));
            }
            _ => {}
        }
    }
    prop_assert_eq!(lifted, p.lift > 0.0);
    let lifts = p
        .repairs
        .iter()
        .filter(|r| matches!(r, Repair::Lifted { .. } | Repair::LiftedToStand { .. }))
        .count();
    prop_assert!(lifts <= 1, "{:?}", p.repairs);
    // Strides: full, unless shortened as the last resort, when no full-stride layout stands.
    let shortened: Vec<f32> = p
        .repairs
        .iter()
        .filter_map(|r| match *r {
            Repair::ShortenedStride { sweep } => Some(sweep),
            _ => None,
        })
        .collect();
    prop_assert!(shortened.len() <= 1);
    let stride = shortened.first().copied().unwrap_or(options.sweep);
    if let Some(&s) = shortened.first() {
        prop_assert!(s >= 0.0 && s < options.sweep);
        prop_assert_eq!(p.layout, Some(WalkerLayout::Rebuilt));
        if body.bones.len() <= 12 {
            let best = best_possible_margin(body, options);
            prop_assert!(
                best < required,
                "strides were shortened, but a full-stride layout with margin {} stands",
                best
            );
        }
    }
    for leg in p.limbs_of(LimbKind::Leg) {
        let (l, r) = walking_legs(body, leg.bone, p.lift);
        let half = stride * l.max(r);
        let a = body.bones[leg.bone].along;
        let tol = 1e-4 * (1.0 + a.abs() + half);
        prop_assert!((leg.span.start - (a - half)).abs() <= tol);
        prop_assert!((leg.span.end - (a + half)).abs() <= tol);
    }
    if p.repairs
        .iter()
        .any(|r| matches!(r, Repair::DroppedPair { .. }))
    {
        prop_assert_eq!(p.layout, Some(WalkerLayout::Rebuilt));
    }
    let arms: Vec<_> = p.limbs_of(LimbKind::Arm).collect();
    prop_assert!(arms.is_empty() || arms.len() == 2);
    for arm in &arms {
        prop_assert!(arm.length >= options.min_arm_length * body.length && arm.length > 0.0);
        let (l, r) = walking_legs(body, arm.bone, p.lift);
        prop_assert!(arm.length <= l.min(r), "an arm never reaches the ground");
        for leg in p.limbs_of(LimbKind::Leg) {
            prop_assert!(!arm.span.overlaps(&leg.span));
            prop_assert_ne!(arm.bone, leg.bone);
        }
    }
    Ok(())
}

/// A walker is either a valid plan, or `NoStableLayout` — and then (for bodies small enough to
/// search exhaustively) no set of legal leg pairs would have stood.
fn check_walker_result(
    body: &Body,
    options: &PlanOptions,
    result: &Result<Plan, LimbsError>,
) -> Result<(), TestCaseError> {
    match result {
        Ok(p) => {
            prop_assert!(all_finite(p));
            walker_checks(body, options, p)?;
            check_mirrors(body, p)?;
        }
        Err(LimbsError::NoStableLayout { margin, required }) => {
            prop_assert!(margin < required);
            prop_assert!(!margin.is_nan());
            // Legs on every bone (any layout's best, at a short enough stride, with the body
            // lifted until every bone is tall enough) would not stand either.
            let all: Vec<usize> = (0..body.bones.len()).collect();
            let best = margin_of(body, options, &all);
            prop_assert!(
                best < *required,
                "the planner gave up, but legs on bones {:?} give margin {} >= {}",
                all,
                best,
                required
            );
        }
        Err(e) => prop_assert!(false, "unexpected error {}", e),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: cases_or_env(256),
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
        check_body_faces_its_head(&body)?;
        let options = PlanOptions::DEFAULT;
        let result = plan(&body, CreatureKind::Walker, &options, &mut SplitMix(seed));
        check_walker_result(&body, &options, &result)?;
    }

    #[test]
    fn walkers_stand_under_any_valid_options(
        body in strategies::body(),
        options in strategies::options(),
        seed in any::<u64>(),
    ) {
        prop_assert_eq!(options.validate(), Ok(()));
        let result = plan(&body, CreatureKind::Walker, &options, &mut SplitMix(seed));
        check_walker_result(&body, &options, &result)?;
    }

    #[test]
    fn fliers_and_swimmers_plan_under_any_valid_options(
        body in strategies::body(),
        options in strategies::options(),
        seed in any::<u64>(),
    ) {
        for kind in [CreatureKind::Flier, CreatureKind::Swimmer] {
            let p = plan(&body, kind, &options, &mut SplitMix(seed)).unwrap();
            prop_assert!(all_finite(&p));
            check_mirrors(&body, &p)?;
            prop_assert!(p.limbs.iter().all(|l| l.length > 0.0), "{:?}", p);
            if kind == CreatureKind::Flier {
                prop_assert!(p.leg_pairs() <= options.max_flier_leg_pairs);
            } else {
                prop_assert!(
                    p.limbs_of(LimbKind::DorsalFin).count() <= options.dorsal_fins[1]
                );
            }
        }
    }

    #[test]
    fn fliers_have_one_wing_pair_and_bounded_legs(
        body in strategies::body(),
        seed in any::<u64>(),
    ) {
        let p = plan(&body, CreatureKind::Flier, &PlanOptions::DEFAULT, &mut SplitMix(seed)).unwrap();
        prop_assert!(all_finite(&p));
        check_mirrors(&body, &p)?;
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
        check_mirrors(&body, &p)?;
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
        let a = plan(&body, kind, &options, &mut SplitMix(seed));
        let b = plan(&body, kind, &options, &mut SplitMix(seed));
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
        let is_invalid_option = matches!(options.validate(), Err(LimbsError::InvalidOption { .. }));
        prop_assert!(is_invalid_option);
        let name_of = |e: LimbsError| match e {
            LimbsError::InvalidOption { name, .. } => Some(name),
            _ => None,
        };
        let expected = name_of(options.validate().unwrap_err());
        let got = plan(&body, kind, &options, &mut SplitMix(0)).err().and_then(name_of);
        prop_assert_eq!(got, expected);
    }
}

/// `NoStableLayout` is a rare outcome for the strategies' bodies under the default options (it
/// needs a very short spine for its legs' strides), not a way out for the planner.
#[test]
fn ordinary_walkers_almost_always_stand() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let strategy = (strategies::body(), any::<u64>());
    let (mut errors, mut rebuilt) = (0usize, 0usize);
    let total = 2000;
    for _ in 0..total {
        let (body, seed) = strategy.new_tree(&mut runner).unwrap().current();
        match plan(
            &body,
            CreatureKind::Walker,
            &PlanOptions::DEFAULT,
            &mut SplitMix(seed),
        ) {
            Ok(p) => rebuilt += usize::from(p.layout == Some(WalkerLayout::Rebuilt)),
            Err(_) => errors += 1,
        }
    }
    println!("errors {errors} / {total}; rebuilt layouts {rebuilt}");
    assert!(
        errors * 20 < total,
        "{errors} of {total} walkers could not stand"
    );
}

/// `default` cases, or `PROPTEST_CASES` when set (for longer soaks).
fn cases_or_env(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}
