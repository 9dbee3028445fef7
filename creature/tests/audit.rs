//! The audit of delivered creatures: each 3D kind's creatures exported to `.glb`, read back and
//! played as a viewer does (`creature-audit`). Runs `CREATURE_AUDIT_SEEDS` seeds per kind
//! (default 12 in a debug build; `cargo xtask sweep` runs 10,000 in release), from seed
//! `CREATURE_AUDIT_FIRST_SEED` (default 0), and prints, per check, how many creatures fail it.
//! Every check is enforced for every kind: each must hold on every seed.

#![allow(clippy::unwrap_used, clippy::std_instead_of_alloc)]

mod tally;

use creature::Span;
use creature::d3::{self, Kind};
use creature::export::glb_3d;
use creature_audit::{Check, Limits, audit_glb};
use tally::{Tally, listed};

fn seeds() -> u64 {
    std::env::var("CREATURE_AUDIT_SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(12)
}

/// The first seed audited: `CREATURE_AUDIT_FIRST_SEED`, 0 by default.
fn first_seed() -> u64 {
    std::env::var("CREATURE_AUDIT_FIRST_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0)
}

fn run(kind: Kind, enforced: &[Check]) {
    let n = seeds();
    let first = first_seed();
    let params = d3::Params::DEFAULT.with_kind(kind);
    let mut tally = Tally::default();
    for seed in first..first + n {
        let c = d3::generate(seed, &params).unwrap();
        tally.add(&format!("seed {seed}"), &c);
    }
    if let Err(e) = tally.finish(&format!("{kind:?}"), enforced) {
        panic!("{e}");
    }
}

#[test]
fn audit_walkers() {
    run(Kind::Walker, &Check::ALL);
}

#[test]
fn regression_turning_walkers_keep_planted_feet_down_and_still() {
    // Seed 5003: closing the turn's loop held a planted foot 6% of the body length up (the
    // correction between two swings at different heights, held through the stance). 5004: the
    // correction made while a foot was only lifting off slid it along the ground. 5005: a foot
    // landing exactly at the midline margin stepped again at once, dragged around the turn.
    walkers_pass(
        &[5003, 5004, 5005],
        &[Check::FootInAir, Check::FootNeverDown, Check::FootSlides],
    );
}

#[test]
fn audit_fliers() {
    run(Kind::Flier, &Check::ALL);
}

#[test]
fn audit_swimmers() {
    run(Kind::Swimmer, &Check::ALL);
}

#[test]
fn audit_slitherers() {
    run(Kind::Slitherer, &Check::ALL);
}

/// The belly checks fail where they should. A slitherer's `slither` (which passes, and by
/// which the audit knows it for a slitherer) frozen in its first frame's shape while its root
/// still travels (a body gliding along in its S, as a fish's wave would carry it) slides its
/// belly sideways; raised by 2% of its length, its body is off the ground.
#[test]
fn the_belly_checks_fail_a_gliding_or_a_floating_slitherer() {
    let c = d3::generate(3, &d3::Params::DEFAULT.with_kind(Kind::Slitherer)).unwrap();
    let slither = c
        .clips
        .iter()
        .find(|clip| clip.name == "slither")
        .unwrap()
        .clone();
    let audit = |clip: d3::Clip| {
        let mut c = c.clone();
        c.clips = vec![clip];
        audit_glb(&glb_3d(&c, &c.clips).unwrap(), &Limits::DEFAULT).unwrap()
    };
    let report = audit(slither.clone());
    assert!(report.slitherer);
    assert!(report.passes(), "{}", listed(&report));
    let mut gliding = slither.clone();
    let first = gliding.root_rotation[0];
    gliding.root_rotation.fill(first);
    for track in &mut gliding.tracks {
        let first = track.rotations[0];
        track.rotations.fill(first);
    }
    let report = audit(gliding);
    assert!(report.fails(Check::BellySlides), "{}", listed(&report));
    let mut floating = slither;
    for t in &mut floating.root_translation {
        t.y += 0.02 * c.length;
    }
    let report = audit(floating);
    assert!(report.fails(Check::OffGround), "{}", listed(&report));
}

/// Slitherers crawling over terrain to a point 10 body lengths away (`slither_to`, as
/// `--terrain` exports it) hold every check on that terrain: the belly on it, never in it,
/// never sliding sideways.
#[test]
fn slithers_over_terrain_pass_the_audit_on_the_terrain() {
    let params = d3::Params::DEFAULT
        .with_kind(Kind::Slitherer)
        .with_clips(false);
    for seed in [3, 7, 12, 40] {
        let report = terrain_report(&params, seed);
        assert!(report.slitherer);
        assert!(report.passes(), "seed {seed}: {}", listed(&report));
    }
}

/// The walkers the regressions were found on: before bodies narrowed into a neck, without
/// one, as then.
const REGRESSION_WALKER: d3::Params = d3::Params::DEFAULT
    .with_neck_width(1.0)
    .with_kind(Kind::Walker);

/// Fails if any of `seeds`' walkers ([`REGRESSION_WALKER`]) fails any of `checks`.
fn walkers_pass(seeds: &[u64], checks: &[Check]) {
    for &seed in seeds {
        passes(seed, &REGRESSION_WALKER, checks);
    }
}

#[test]
fn regression_bent_knees_and_elbows_do_not_pinch_their_skin() {
    // The knee (elbow) ring was bound half and half to the two bones: linear blend skinning
    // shrank it to 0.79 of its size as the joint bent (seeds 98, 5024: knees; 5144: elbow).
    walkers_pass(&[98, 5024, 5144], &[Check::Squash, Check::Stretch]);
}

#[test]
fn regression_a_full_turn_closing_its_loop_does_not_flick_a_leg() {
    // Closing a turn's loop turned each foot's correction with the body the shortest way
    // round: past half a turn it flipped to the other side of the body, and the leg with it
    // (53° in one key at seed 5174's hip).
    walkers_pass(&[157, 297, 5174], &[Check::KeyTurn, Check::AngularSpeed]);
}

#[test]
fn regression_a_long_walker_turns_no_faster_than_its_feet_follow() {
    // Turning at a quarter turn a second whatever its length, a 5 m walker's front feet swept
    // round at 3.7 m/s (it walks at 2): carried past the midline between two frames.
    let c = d3::generate(5887, &REGRESSION_WALKER).unwrap();
    let turn = c.clips.iter().find(|k| k.name == "turn").unwrap();
    assert!(turn.duration() > 6.0, "{} s", turn.duration());
    walkers_pass(&[5887, 5634, 5616], &[Check::FeetCross]);
}

#[test]
fn regression_a_narrow_walker_does_not_sway_its_rear_feet_across() {
    // The body's sway (the planted feet's mean angle about its origin) turned a long body with
    // rear hips near the midline 5° while a rear foot trailed far behind: in the body's frame
    // the foot crossed the midline at the start of `walk` (seeds 6904, 1600, 8794).
    walkers_pass(&[6904, 1600, 8794], &[Check::FeetCross]);
}

#[test]
fn regression_feet_on_a_side_keep_apart_along_the_body() {
    // A rear foot's step, overshooting ahead of its rest position, landed beside (or past) the
    // front foot still planted behind its own, and the front leg swung through the rear one
    // (seeds 7988, 5190: `walk`); closing a turn's loop brought two feet on a side together
    // (4235, 4570, 6857).
    walkers_pass(&[7988, 5190, 4235, 4570, 6857], &[Check::LegsIntersect]);
}

#[test]
fn regression_a_quick_swing_turns_its_knee_no_faster_than_a_joint_may() {
    // A short swing (a loop's closing correction, or a foot swung out sideways and back) bent
    // the knee 46° between two keys, 24 rad/s (seeds 1311, 5897, 6550 in `turn`).
    walkers_pass(&[1311, 5897, 6550], &[Check::KeyTurn, Check::AngularSpeed]);
}

#[test]
fn regression_a_long_walker_turning_lifts_its_outer_feet() {
    // The outer feet of a 5 m walker turning in place stepped in an update or two (their rest
    // positions move fast): the foot jumped 0.22 m along the ground (seed 8370, `turn`).
    walkers_pass(&[8370], &[Check::FootSlides]);
}

#[test]
fn regression_sideways_knees_of_an_upright_leg_are_not_flipped_across_the_body() {
    // A knee's pole was flipped whenever, square to the leg, it dipped at all: the left leg of
    // seed 87 (nearly upright, knees bending sideways) had its knee turned in, toward the right
    // leg, and the two legs passed through each other in the turn.
    walkers_pass(&[87, 477, 785], &[Check::LegsIntersect]);
    let c = d3::generate(87, &REGRESSION_WALKER).unwrap();
    let legs = &c.gait.as_ref().unwrap().legs;
    assert!(legs[0].pole.x > 0.0 && legs[1].pole.x < 0.0, "{legs:?}");
}

/// Fails if the creature of `seed` and `params` fails any of `checks`.
fn passes(seed: u64, params: &d3::Params, checks: &[Check]) {
    let c = d3::generate(seed, params).unwrap();
    let report = audit_glb(&glb_3d(&c, &c.clips).unwrap(), &Limits::DEFAULT).unwrap();
    for &check in checks {
        assert!(!report.fails(check), "seed {seed}: {}", listed(&report));
    }
}

/// A creature's params as the params property drew them: its kind, mesh (profiles, rings,
/// segments, limb sides, flat normals), `(width, height, step)` of its slices, its body
/// scale, speed factor, bone length, spine bones, bend, head size and clearance.
#[allow(clippy::too_many_arguments)]
fn drawn(
    kind: Kind,
    mesh: (u32, u32, u32, u32, bool),
    slices: [(f32, f32); 3],
    scale: (f32, f32),
    speed: (f32, f32),
    bone_length: f32,
    spine_bones: (u32, u32),
    spine_bend: f32,
    head: (f32, f32),
    clearance: (f32, f32),
) -> d3::Params {
    use creature::{IntSpan, Span};
    let span = |(a, b): (f32, f32)| Span::new(a, b);
    let (profiles, rings, segments, sides, flat) = mesh;
    // Found before bodies narrowed into a neck: without one, as then.
    d3::Params::DEFAULT
        .with_neck_width(1.0)
        .with_kind(kind)
        .with_profiles(profiles)
        .with_resolution(rings, segments)
        .with_limb_sides(sides)
        .with_flat_normals(flat)
        .with_slices(span(slices[0]), span(slices[1]), span(slices[2]))
        .with_body_scale(span(scale))
        .with_speed_factor(span(speed))
        .with_bone_length(bone_length)
        .with_spine_bones(IntSpan::new(spine_bones.0, spine_bones.1))
        .with_spine_bend(spine_bend)
        .with_head_size(span(head))
        .with_ground_clearance(span(clearance))
}

#[test]
fn regression_a_fast_fliers_dangling_legs_do_not_whirl() {
    // A fast flier's short dangling legs were springs damped against the air at a tenth of
    // critical, stiffened to trail behind at 17 m/s: the bob rang them, and a hip whirled
    // round (up to 180° between two keys of `fly`). They are now simulated flying with the
    // body, trailing in their rest direction and damped at 0.7 of critical.
    let params = drawn(
        Kind::Flier,
        (4, 14, 4, 3, true),
        [
            (0.994_159_3, 1.039_162_8),
            (0.606_776_5, 1.339_082_8),
            (0.695_626_2, 1.422_667_4),
        ],
        (2.455_140_6, 6.808_189_4),
        (1.718_118_1, 4.711_306_6),
        0.369_513_54,
        (26, 37),
        178.213,
        (1.634_431, 1.977_957_4),
        (0.050_255_79, 0.471_187_5),
    );
    passes(
        17_832_793_757_359_882_385,
        &params,
        &[Check::KeyTurn, Check::AngularSpeed],
    );
}

#[test]
fn regression_a_coarse_fliers_tail_bends_within_its_skin() {
    // On a coarse mesh (2 profiles, 4 rings) no vertex was mostly weighted to some tail
    // joints, so they had no bend limit: one swung 55° in `hover` and stretched the skin to
    // 1.54 of its rest length. Such a joint takes its nearest spine neighbour's thickness.
    let params = drawn(
        Kind::Flier,
        (2, 4, 9, 3, true),
        [
            (2.013_578, 2.413_838_6),
            (0.769_067, 1.785_924_8),
            (0.341_956_38, 2.615_084_2),
        ],
        (4.441_711, 9.789_626),
        (0.444_320_14, 2.797_783_4),
        0.246_018,
        (20, 33),
        39.219_963,
        (0.777_901_1, 1.729_058_7),
        (0.373_015_46, 0.830_393_5),
    );
    passes(
        8_069_181_287_398_322_298,
        &params,
        &[Check::Stretch, Check::Squash],
    );
}

#[test]
fn regression_a_walker_asked_to_walk_faster_than_its_legs_can_walks_at_their_limit() {
    // A big walker drawn a speed factor of up to 4 was asked to walk at 28 m/s on 18.6 m legs
    // (a Froude number v² / (g · leg) of 4.3, where animals run): its swings were so quick that
    // a knee unfolded 58° between two keys of `walk`. A walk now goes at most at Froude 1.
    let params = drawn(
        Kind::Walker,
        (3, 4, 3, 3, false),
        [
            (1.710_644_4, 1.858_802_3),
            (1.435_134_3, 2.042_423),
            (1.312_088_7, 1.798_883_1),
        ],
        (7.252_962_6, 7.837_54),
        (1.405_083_1, 4.135_769_4),
        0.285_187_57,
        (24, 26),
        23.989_475,
        (0.823_052_3, 1.612_167_8),
        (0.346_899_8, 0.720_121_86),
    );
    let seed = 9_095_166_373_788_020_810;
    passes(seed, &params, &[Check::KeyTurn, Check::AngularSpeed]);
    let walker = d3::generate(seed, &params).unwrap();
    let gait = walker.gait.as_ref().unwrap();
    let legs: Vec<f32> = gait
        .legs
        .iter()
        .filter(|l| l.kind == creature::gait::LimbKind::Leg)
        .map(|l| l.size)
        .collect();
    let leg = legs.iter().sum::<f32>() / legs.len() as f32;
    let froude = walker.speed * walker.speed / (9.81 * leg);
    assert!(froude <= 1.0 + 1e-4, "walks at Froude {froude}");
}

#[test]
fn regression_a_turning_walkers_foot_lifting_off_near_the_midline_stays_on_its_side() {
    // A 14.3 m walker on 11 m legs whose hips are 0.6 m off the midline, turning in place: a
    // front foot near the midline lifted off as the body's lean swung back and was carried
    // 0.66 m across the midline in the body's frame (`turn` frame 73). A lifted foot now moves
    // out as it rises.
    let params = drawn(
        Kind::Walker,
        (5, 16, 6, 3, true),
        [
            (0.840_060_35, 1.352_365_1),
            (2.267_752_2, 2.470_356),
            (2.668_757_4, 2.962_468_6),
        ],
        (1.314_283_5, 6.148_751_3),
        (1.285_855, 2.323_904_8),
        0.176_331_7,
        (32, 35),
        160.727_87,
        (1.434_576_2, 1.927_977),
        (0.360_950_1, 0.914_356_95),
    );
    passes(
        3_991_390_260_638_037_947,
        &params,
        &[Check::FeetCross, Check::FootSlides],
    );
}

#[test]
fn regression_a_swimmers_fluttering_fin_stays_above_the_ground() {
    // A swimmer at rest on the ground with a pectoral fin hanging down to it: the fin's
    // flutter in `idle` dipped its tip 1.9% of the body length below the ground. Its clips are
    // now raised by the most any vertex dips in any frame.
    use creature::d3::{Pattern, PatternWeights};
    use creature::{IntSpan, Span};
    let params = d3::Params::DEFAULT
        .with_neck_width(1.0)
        .with_kind(Kind::Swimmer)
        .with_profiles(8)
        .with_resolution(13, 3)
        .with_limb_sides(5)
        .with_flat_normals(true)
        .with_swimmer_slices(
            Span::new(0.349_509_92, 1.847_776_4),
            Span::new(1.030_298_6, 1.665_015_9),
            Span::new(0.415_306_93, 1.444_092_6),
        )
        .with_body_scale(Span::new(0.717_793_2, 3.079_842_8))
        .with_speed_factor(Span::new(0.482_403_67, 0.933_012_25))
        .with_bone_length(0.442_698_7)
        .with_spine_bones(IntSpan::new(9, 26))
        .with_spine_bend(54.071_384)
        .with_head_size(Span::new(0.567_758_9, 1.459_022_9))
        .with_ground_clearance(Span::new(0.003_512_616_7, 0.295_456_05))
        .with_saturation(Span::new(0.383_618_68, 0.928_629_16))
        .with_countershading(Span::new(0.265_450_84, 0.701_300_74))
        .with_patterns(
            PatternWeights::only(Pattern::Stripes)
                .with(Pattern::Stripes, 531.121_34)
                .with(Pattern::Plain, 327.247_68),
        );
    passes(4_640_276_320_221_147_182, &params, &[Check::BelowGround]);
}

#[test]
fn regression_a_pair_of_legs_does_not_share_one_point_of_a_coarse_body() {
    // A body of 3 segments around had a single vertex beside a short spine bone: the rig made
    // it the socket's left and its right, and the pair's right leg was built on the left at
    // the very point of the left one (the two legs inside each other at rest). A socket with
    // one vertex beside its bone takes its sides from the slabs around it.
    let params = drawn(
        Kind::Walker,
        (1, 8, 3, 7, false),
        [
            (1.498_884_2, 2.870_209),
            (0.665_157_85, 1.455_821_8),
            (0.767_983_6, 1.667_125),
        ],
        (4.520_921, 8.719_804),
        (0.313_174_13, 3.403_623_3),
        0.123_322_91,
        (9, 25),
        134.962_13,
        (0.962_679_4, 1.301_479_7),
        (0.153_853_67, 0.380_899_22),
    );
    let seed = 13_377_572_734_828_355_716;
    let c = d3::generate(seed, &params).unwrap();
    let gait = c.gait.as_ref().unwrap();
    for (i, a) in gait.legs.iter().enumerate() {
        for b in &gait.legs[i + 1..] {
            assert!(
                a.hip.distance(b.hip) > 0.01 * c.length,
                "{:?} {:?}",
                a.hip,
                b.hip
            );
        }
    }
    passes(seed, &params, &[Check::LegsIntersect]);
}

#[test]
fn regression_crowded_legs_bend_their_knees_apart() {
    // Two legs on a side close together along the body, all knees forward: the rear knee
    // reached into the front leg as it swung (seeds 88 and 6318 in `walk`; at params drawn
    // by the property, knees poked a whole body length forward past the front hip). Such
    // sides bend their knees apart: the front leg's forward, the rear one's backward.
    walkers_pass(&[88, 6318], &[Check::LegsIntersect]);
    let params = drawn(
        Kind::Walker,
        (9, 7, 13, 7, true),
        [
            (1.644_481_4, 2.560_728_3),
            (1.591_648_7, 2.237_061_5),
            (0.414_549_23, 0.579_102_16),
        ],
        (6.433_948, 9.544_270_5),
        (2.748_151_5, 3.769_874_8),
        0.268_293_23,
        (10, 11),
        81.042_71,
        (1.421_913, 1.813_046_6),
        (0.495_726_64, 0.605_670_9),
    );
    passes(10_405_529_381_658_842_790, &params, &[Check::LegsIntersect]);
}

#[test]
fn regression_skin_whose_joints_jump_along_the_spine_bends_within_its_limit() {
    // Where the spine rises into the neck, a vertex high on the back is nearest joints three
    // further along it than its neighbour below: the edge between them was stretched by the
    // bends of all the joints between (1° each in `turn`) to 1.38 of its rest length. Each
    // joint of such a span takes its share of the limit.
    let params = drawn(
        Kind::Walker,
        (5, 20, 11, 5, true),
        [
            (1.571_468_2, 1.927_732_1),
            (1.333_315_5, 2.446_952),
            (0.782_679_3, 1.052_295_4),
        ],
        (2.749_542_5, 3.476_217),
        (1.627_416_4, 1.703_324_6),
        0.467_015_36,
        (25, 26),
        102.378_02,
        (1.113_410_6, 1.504_087_7),
        (0.516_531_65, 0.519_780_46),
    );
    passes(
        914_156_467_985_218_874,
        &params,
        &[Check::Stretch, Check::Squash],
    );
}

#[test]
fn regression_a_sideways_knee_bends_about_its_hinge() {
    // The hip turned its thigh the shortest way from rest, which twisted it as the leg swung:
    // a sideways knee then turned about a wandering axis, through 47° between two keys of
    // `walk` (24 rad/s), though the leg's bend hardly changed (a small, fast walker: the
    // facade's property case 722 over valid params).
    let params = drawn(
        Kind::Walker,
        (6, 10, 13, 3, false),
        [
            (0.891_477_47, 2.021_170_4),
            (0.323_322_77, 0.495_552_18),
            (0.860_478_9, 1.081_391_8),
        ],
        (0.114_449_31, 0.160_834_8),
        (4.447_129_2, 4.485_049),
        0.364_939_15,
        (29, 36),
        97.44526,
        (1.649_839_4, 1.832_287_4),
        (0.067_177, 0.741_246_5),
    );
    let checks = [Check::KeyTurn, Check::AngularSpeed];
    passes(17_446_813_456_853_714_282, &params, &checks);
}

#[test]
fn regression_a_fast_walkers_knee_unfolds_evenly_through_its_swing() {
    // A 19 m walker at 17 m/s (the facade's property case 1221 over valid params): its foot
    // dropped from high in the swing onto the ground at the end, and the knee unfolded 63°
    // between two keys of `walk`; the swing's frames are now spaced by the joints' turn.
    let params = drawn(
        Kind::Random,
        (4, 21, 11, 5, true),
        [
            (1.276_099_6, 2.971_592_7),
            (0.680_393_34, 1.390_769_7),
            (1.115_497_4, 1.980_858_7),
        ],
        (5.636_702_5, 6.711_443_4),
        (2.775_828_6, 2.826_998_5),
        0.333_442_84,
        (34, 35),
        104.19234,
        (1.953_637_4, 1.999_920_7),
        (0.080_476_07, 0.329_559_86),
    );
    let checks = [Check::KeyTurn, Check::AngularSpeed];
    passes(10_072_698_522_228_869_427, &params, &checks);
}

#[test]
fn regression_a_long_stride_bends_crowded_knees_apart() {
    // Legs as long as the body on hips 0.75 of it apart, all knees forward (the facade's
    // property case 818 over valid params): the hips were far enough apart at rest, but at the
    // back of its stance the front foot passed behind the rear leg's forward knee, and the
    // front shin swept through the rear thigh in `walk`.
    let params = drawn(
        Kind::Walker,
        (5, 6, 9, 8, false),
        [
            (1.015_512_7, 2.449_571_4),
            (1.755_314_7, 2.887_926_8),
            (0.756_334_2, 2.912_366),
        ],
        (0.238_220_69, 3.803_444),
        (2.464_702_8, 4.955_887_3),
        0.240_171_18,
        (39, 39),
        57.680_603,
        (0.595_136_34, 0.828_786_6),
        (0.605_272_5, 0.837_489_37),
    );
    passes(13_341_310_954_036_717_780, &params, &[Check::LegsIntersect]);
}

#[test]
fn regression_a_limited_swing_frame_that_would_touch_the_ground_moves_only_as_far_as_it_must() {
    // An 8.9 m eight-legged walker (property case 1866 over valid params, head fields drawn):
    // the frame before a rear foot landed, its rate-limited knee lowered the sole under the
    // ground, and the frame went back to the gait's pose whole: the knee turned 73° between
    // two keys of `walk`. Such a frame now blends from the limited pose toward the gait's
    // only as far as keeps the sole clear of the ground.
    let params = drawn(
        Kind::Walker,
        (6, 22, 12, 3, false),
        [
            (0.979_103_2, 1.424_793_5),
            (1.465_426_4, 1.940_351_4),
            (0.947_793_54, 2.526_943_4),
        ],
        (1.714_868_3, 5.781_369_7),
        (0.768_233_3, 4.482_866),
        0.200_448_23,
        (28, 30),
        127.710_31,
        (0.569_013_24, 0.917_463_2),
        (0.022_081_522, 0.083_563_19),
    )
    .with_eye_size(creature::Span::new(0.282_893_78, 0.324_411_2))
    .with_snout_length(creature::Span::new(0.320_417_43, 1.413_983_2))
    .with_ornaments(creature::Span::new(1.348_072_9, 2.514_043), 0.112_624_206);
    passes(
        17_310_549_602_782_747_354,
        &params,
        &[Check::KeyTurn, Check::FootSlides, Check::BelowGround],
    );
}

/// A walk over procedural terrain, as `--terrain` bakes and exports it (hills half the body's
/// length high, a 12° slope, steps a fifth of the shortest leg high), audited on the terrain
/// the file carries; a [`REGRESSION_WALKER`], as its regressions were found on.
fn terrain_walk_report(seed: u64) -> creature_audit::Report {
    terrain_report(&REGRESSION_WALKER.with_clips(false), seed)
}

/// The audit of creature `seed` of `params` going over terrain to a point 10 body lengths
/// away, as `--terrain` exports it, measured on that terrain (a walker's fails on the plane
/// y = 0).
fn terrain_report(params: &d3::Params, seed: u64) -> creature_audit::Report {
    use creature::terrain::{TerrainParams, terrain, terrain_mesh};
    let c = d3::generate(seed, params).unwrap();
    let params = TerrainParams::for_creature(&c);
    let field = terrain(seed, &params).unwrap();
    let target = creature::glam::Vec3::new(6.0, 0.0, 8.0) * c.length;
    let clip = c.bake_to(&field, target, 120.0).unwrap();
    let glb = creature::export::glb_3d_on_terrain(&c, &[clip], &terrain_mesh(&field)).unwrap();
    let mut model = creature_audit::Model::from_glb(&glb).unwrap();
    assert!(model.terrain.is_some());
    let report = creature_audit::audit(&model, &Limits::DEFAULT).unwrap();
    if c.gait.is_some() {
        // Measured on the plane y = 0 instead, the same walk is over and under the ground.
        model.terrain = None;
        let flat = creature_audit::audit(&model, &Limits::DEFAULT).unwrap();
        assert!(flat.fails(Check::BelowGround) || flat.fails(Check::FootNeverDown));
    }
    report
}

/// The audit on terrain (a walk to a point 10 body lengths away over hills, a slope and
/// steps, as `--terrain` exports it) holds every check, as on flat ground. Regressions: the
/// head, turned on its own joint to look at the target and wrenched round to it on arrival,
/// stretched the neck's skin to 1.78× and squashed it to 0.31×; a sole tilted to the ground's
/// normal under its middle dipped up to 2.7% of the body's length into a step's edge, and
/// tilted 55° between two keys crossing one; an arm's elbow flipped between two keys.
#[test]
fn walks_over_terrain_pass_the_audit_on_the_terrain() {
    // 107: a sole raised for ground beyond its rim stood in the air; 170: an elbow flicked
    // 88° between two keys as the hand passed its pole.
    for seed in [3, 7, 12, 107, 170] {
        let report = terrain_walk_report(seed);
        assert!(report.walker);
        assert!(report.passes(), "seed {seed}: {}", listed(&report));
    }
}

/// Toed feet (a rear toe or claw reaching a seventh of a body length behind the ankle) on
/// terrain walks stay out of the ground and land without skidding. Regressions: the sole was
/// raised for the ground under sixteen rim samples, and a step's crest passing between two of
/// them left a toe up to 1.2% of the body's length in it (seeds 106, 110; 31 of seeds
/// 100-199 failed); raised for every sole vertex, a stepping foot's toe caught the crest its
/// sole would rest on before the step ended and skidded 1.6% over it (seed 100).
#[test]
fn toed_soles_stay_out_of_step_crests_on_terrain_walks() {
    for seed in [100, 106, 110] {
        let report = terrain_walk_report(seed);
        assert!(report.walker);
        assert!(report.passes(), "seed {seed}: {}", listed(&report));
    }
}

#[test]
fn regression_legs_on_a_coarse_body_grow_from_their_own_sockets() {
    // Four rings under up to 33 spine bones: several bones took the same ring's vertices as
    // their sockets, and the planner, which saw the bones' middles 10 m apart, put two pairs
    // of legs on one ring: ten legs grew from six points and two of them passed through each
    // other at rest (0.025 of the body length). The planner now sees each socket where it is,
    // once.
    let params = drawn(
        Kind::Random,
        (2, 4, 6, 6, false),
        [
            (0.616_603_7, 1.541_992_9),
            (1.005_354_9, 2.073_105_6),
            (2.779_494_3, 2.852_187_4),
        ],
        (7.240_580_6, 9.536_671),
        (3.111_096_9, 3.124_008_4),
        0.331_744_22,
        (10, 33),
        65.0615,
        (0.503_178_54, 1.336_021_2),
        (0.073_901_66, 0.749_087_9),
    )
    .with_eye_size(Span::new(0.174_666_51, 0.192_548))
    .with_snout_length(Span::new(1.527_606_8, 4.519_441))
    .with_ornaments(Span::new(1.097_268_7, 1.812_374_2), 0.096_638_404);
    let seed = 3_328_320_640_590_428_760;
    let c = d3::generate(seed, &params).unwrap();
    let hips: Vec<_> = c
        .skeleton
        .joints
        .iter()
        .filter(|j| j.name.starts_with("leg_") && j.name.ends_with("_hip"))
        .map(|j| j.position)
        .collect();
    assert!(hips.len() >= 2);
    for (a, p) in hips.iter().enumerate() {
        for q in &hips[a + 1..] {
            assert!(p.distance(*q) > 0.01 * c.length, "two hips at {p}");
        }
    }
    passes(seed, &params, &[Check::LegsIntersect]);
}

#[test]
fn regression_a_lopsided_front_pair_steps_forward_together() {
    // A heavy head ahead of the feet: the front feet step forward under it. Only the front-most
    // foot did, and its mirror, a little behind it, stayed, under the hind pair's knees: the
    // right legs passed through each other in `walk` and `turn` (0.054 and 0.061 of the body
    // length). A pair now steps together.
    let params = drawn(
        Kind::Random,
        (3, 6, 15, 3, false),
        [
            (1.423_797_6, 2.454_077_5),
            (0.323_339_58, 1.559_009_2),
            (0.350_691_85, 1.310_309_8),
        ],
        (6.716_143, 6.868_582),
        (2.681_01, 3.116_035_5),
        0.250_626_83,
        (16, 31),
        119.682_67,
        (0.706_489_6, 1.648_291_5),
        (0.601_043_6, 0.622_355_46),
    )
    .with_eye_size(Span::new(0.462_305_13, 0.585_680_5))
    .with_snout_length(Span::new(4.043_108_5, 4.650_486))
    .with_ornaments(Span::new(0.162_090_94, 2.487_76), 0.085_426_98);
    passes(9_794_981_786_070_673_381, &params, &[Check::LegsIntersect]);
}

#[test]
fn regression_a_retimed_swing_stays_above_the_ground_when_the_body_lurches() {
    // A wide biped turning shifts its body onto its stance foot between two frames (0.9 m on
    // a 20 m walker); the swing, retimed along its path in the body's frame, was carried down
    // with it: the swinging foot went 0.028 of the body length under the ground in `turn`.
    // A retimed frame that would come down to the ground keeps the gait's own.
    let params = drawn(
        Kind::Walker,
        (9, 9, 11, 3, true),
        [
            (2.703_210_8, 2.943_948_7),
            (0.339_541_58, 0.731_376_1),
            (0.416_009_9, 2.441_887_1),
        ],
        (4.193_389, 8.083_549_5),
        (0.293_502_48, 2.352_748_2),
        0.157_278_69,
        (23, 40),
        19.542_784,
        (0.921_866_06, 1.177_133_2),
        (0.030_366_527, 0.460_567_8),
    )
    .with_eye_size(Span::new(0.428_844_6, 0.504_285_7))
    .with_snout_length(Span::new(2.824_727_8, 3.347_311_3))
    .with_ornaments(Span::new(1.179_151_4, 1.838_340_6), 0.215_361_06);
    passes(7_689_786_250_423_442_917, &params, &[Check::BelowGround]);
}

#[test]
fn regression_a_foot_lifting_off_behind_a_rising_body_does_not_flick_its_knee() {
    // A fast walker's rear foot lifted off as the body rose in its bob: the leg, nearly
    // straight at the end of its stance, was pulled straight in the air, then bent again, its
    // knee turning 39° between two keys of `walk` (20.6 rad/s). A foot in the air now stops
    // softly short of a straight leg.
    let params = drawn(
        Kind::Walker,
        (5, 12, 3, 6, false),
        [
            (0.395_800_83, 1.607_863_9),
            (1.936_680_8, 2.311_951_4),
            (1.525_831_6, 1.750_294_6),
        ],
        (0.693_888_07, 3.704_585),
        (3.442_911_1, 3.719_795_2),
        0.251_549_15,
        (23, 34),
        33.982_647,
        (1.087_947_1, 1.747_150_3),
        (0.200_450_14, 0.250_805_5),
    )
    .with_eye_size(Span::new(0.209_969_45, 0.249_091_2))
    .with_snout_length(Span::new(2.395_431_5, 3.641_475_2))
    .with_ornaments(Span::new(0.693_299_6, 1.167_318_5), 0.132_839_84);
    passes(
        1_957_023_710_239_692_180,
        &params,
        &[Check::KeyTurn, Check::AngularSpeed],
    );
}

#[test]
fn regression_a_walkers_legs_stand_on_its_sides() {
    // A socket near a pointed end (or on a narrow, bent neck) has its "left" vertex on the
    // midline or past it: a pair of legs grew from one point on the midline, and stood through
    // each other at rest (0.033 of the body length), and a "left" foot stood right of the
    // midline. A walker's limbs now go only on sockets whose sides are its sides.
    let pointed = drawn(
        Kind::Walker,
        (3, 4, 6, 5, true),
        [
            (0.444_557_6, 0.535_536_2),
            (1.016_834_4, 1.180_852_5),
            (0.885_604_8, 2.334_824),
        ],
        (7.988_452, 9.883_803),
        (3.825_549_8, 3.917_542),
        0.129_191_18,
        (34, 40),
        158.052_86,
        (0.634_932_8, 1.168_202_2),
        (0.606_042_44, 0.635_191_6),
    )
    .with_eye_size(Span::new(0.445_613_24, 0.555_924_3))
    .with_snout_length(Span::new(0.017_155_867, 3.390_631_4))
    .with_ornaments(Span::new(1.158_044_3, 2.632_665_2), 0.014_055_995);
    let narrow = drawn(
        Kind::Walker,
        (1, 13, 11, 5, false),
        [
            (0.959_071_5, 1.831_038_6),
            (0.832_827_87, 2.914_273_7),
            (0.519_394_3, 0.880_000_95),
        ],
        (3.059_110_4, 9.564_991),
        (2.863_166, 3.442_652_5),
        0.285_698_56,
        (9, 17),
        152.486_79,
        (1.009_275, 1.815_916_5),
        (0.383_933_6, 0.402_652_77),
    )
    .with_eye_size(Span::new(0.368_042_53, 0.518_224_95))
    .with_snout_length(Span::new(1.059_300_8, 3.696_033_5))
    .with_ornaments(Span::new(1.559_793_6, 1.686_687_4), 0.674_563_94);
    for (seed, params) in [
        (5_287_661_177_873_974_911, pointed),
        (7_150_111_178_774_173_641, narrow),
    ] {
        let c = d3::generate(seed, &params).unwrap();
        for j in c
            .skeleton
            .joints
            .iter()
            .filter(|j| j.name.ends_with("_foot"))
        {
            let side = if j.name.contains("_l") { 1.0 } else { -1.0 };
            assert!(
                j.position.x * side > 0.0,
                "seed {seed}: {} at {}",
                j.name,
                j.position
            );
        }
        passes(seed, &params, &[Check::FeetCross, Check::LegsIntersect]);
    }
}

#[test]
fn regression_a_body_of_odd_rings_stands_on_its_legs_midline() {
    // Found by the audit over valid params (case 2773): a ring of 3 segments started beside
    // the body, so the body was wider on one side and its spine stood 1 m (12% of its length)
    // off the midline its legs are mirrored about; in the body's frame a right foot lifting
    // off in `turn` crossed it. Every ring is now symmetric about the midline.
    let params = drawn(
        Kind::Walker,
        (7, 10, 3, 4, false),
        [
            (2.716_044_7, 2.821_567_3),
            (0.754_861_1, 2.307_473_7),
            (0.374_761_4, 0.720_983_2),
        ],
        (5.398_502_3, 8.137_73),
        (4.138_1, 4.346_852_3),
        0.437_313_26,
        (21, 27),
        69.007_32,
        (1.471_515_8, 1.853_493_7),
        (0.661_944_87, 0.997_731_2),
    )
    .with_eye_size(Span::new(0.088_975_07, 0.584_538_9))
    .with_snout_length(Span::new(2.558_503, 4.968_017_6))
    .with_ornaments(Span::new(0.374_553_8, 1.966_423), 0.129_422_25);
    let seed = 4_642_089_095_425_433_596;
    let c = d3::generate(seed, &params).unwrap();
    for joint in c
        .skeleton
        .joints
        .iter()
        .filter(|j| j.name.starts_with("spine"))
    {
        assert!(
            joint.position.x.abs() < 1e-4 * c.length,
            "{} at x = {}",
            joint.name,
            joint.position.x
        );
    }
    passes(seed, &params, &[Check::FeetCross]);
}

#[test]
fn regression_a_tall_narrow_walker_does_not_sway_its_feet_across() {
    // Found by the audit over valid params (case 5001): a 27 m walker on 26 m legs with front
    // hips 0.61 m off the midline, 17 m ahead of its origin. Turning in place, the sway (up to
    // 0.3 rad) turned the body 3.6° in a key, carrying a planted front foot 1 m across the
    // body's frame and over the midline. The gait now sways no further than keeps the feet at
    // rest on their sides.
    let params = drawn(
        Kind::Walker,
        (2, 24, 4, 8, false),
        [
            (0.328_505_25, 1.395_186_5),
            (2.162_314_4, 2.836_322_5),
            (2.140_524, 2.659_603_6),
        ],
        (5.450_493, 6.547_758_6),
        (0.144_784_02, 0.652_867_44),
        0.298_312_28,
        (21, 31),
        132.852_16,
        (0.729_697_7, 1.776_309_7),
        (0.045_260_19, 0.806_076_17),
    )
    .with_eye_size(Span::new(0.068_981_096, 0.599_020_9))
    .with_snout_length(Span::new(0.444_855, 1.867_586_1))
    .with_ornaments(Span::new(0.589_865_5, 1.130_940_8), 0.468_370_74);
    passes(14_018_834_416_006_655_849, &params, &[Check::FeetCross]);
}

#[test]
fn regression_legs_on_a_fliers_tail_do_not_whirl() {
    // Found by the audit over valid params (case 2067, once its rings of 11 were symmetric): a
    // flier's hind legs hang from its tail, whose damped chain the tracks hold to its skin's
    // bend limits; the legs hung from the tail as it was simulated, not as the tracks turn it,
    // so a hip whirled through the tail's swing (72° between two keys of `hover`). A chain
    // hanging from another now hangs from it as its tracks turn it.
    let params = drawn(
        Kind::Flier,
        (2, 15, 11, 4, true),
        [
            (1.926_589_3, 2.056_185),
            (2.435_380_2, 2.946_805_2),
            (1.027_310_8, 1.409_368_9),
        ],
        (0.215_320_53, 1.541_805_6),
        (0.730_527_76, 4.733_236_3),
        0.160_564_82,
        (22, 38),
        55.271_187,
        (1.002_684_4, 1.151_605_5),
        (0.116_262_645, 0.514_046_67),
    )
    .with_eye_size(Span::new(0.065_051_86, 0.433_630_2))
    .with_snout_length(Span::new(2.557_860_1, 4.205_465))
    .with_ornaments(Span::new(1.549_262_2, 1.848_271_4), 0.140_088_66);
    let seed = 18_041_021_384_657_769_040;
    assert!(a_leg_hangs_from_the_tail(
        &d3::generate(seed, &params).unwrap()
    ));
    passes(seed, &params, &[Check::KeyTurn, Check::AngularSpeed]);
}

/// Whether a leg's hip hangs from a tail joint of `c`.
fn a_leg_hangs_from_the_tail(c: &d3::Creature) -> bool {
    let tail = |j: Option<usize>| j.is_some_and(|j| c.skeleton.joints[j].name.starts_with("tail"));
    c.skeleton
        .joints
        .iter()
        .any(|j| j.name.ends_with("_hip") && tail(j.parent))
}

#[test]
fn regression_a_heavy_headed_walker_rakes_its_legs_no_further_than_it_must() {
    // Found by the audit over valid params (case 1229): a walker whose centre of mass is 6 m
    // ahead of its front hips (a heavy head on a long neck). With its front feet forward as far
    // as they reach it still tipped, so its whole stance went under the mass, the feet's centre
    // right below it: every foot 6.4 m ahead of its hip (3.2 m up), the hind feet under the
    // front hips, and the legs of a side passed through each other. The stance now moves only
    // as far as puts the mass inside the feet.
    let params = drawn(
        Kind::Walker,
        (7, 16, 12, 3, false),
        [
            (2.455_258_6, 2.595_328_6),
            (0.642_411_77, 1.336_081_7),
            (0.357_616_66, 2.121_498_8),
        ],
        (0.567_409_75, 6.925_729_8),
        (0.989_464_9, 1.304_557_1),
        0.376_482_67,
        (8, 11),
        39.207_535,
        (1.487_182_5, 1.710_061),
        (0.003_151_273_6, 0.743_861_5),
    )
    .with_eye_size(Span::new(0.207_330_05, 0.509_561_5))
    .with_snout_length(Span::new(2.343_797_4, 3.894_768_7))
    .with_ornaments(Span::new(0.135_239_94, 2.359_578_6), 0.855_954_23);
    passes(
        6_648_856_961_646_856_361,
        &params,
        &[Check::LegsIntersect, Check::Tips, Check::FeetCross],
    );
}

#[test]
fn regression_legs_on_a_fliers_long_tail_turn_no_faster_than_a_leg_may() {
    // Found by the audit over valid params (case 14805 of 20,000): a flier whose hind legs hang
    // from the end of a 12-joint tail. The tail's joints each bend little, but together they
    // swing its end round fast, and the hips, hanging from it, turned 55° between two keys
    // of `hover` (29 rad/s). The chains' joints now turn no faster than a leg's may, round the
    // clip's loop.
    let params = drawn(
        Kind::Random,
        (1, 24, 6, 4, true),
        [
            (1.067_235_4, 1.371_128_7),
            (0.792_939_9, 2.324_391_1),
            (1.325_594, 2.758_476_3),
        ],
        (0.163_732_7, 0.311_202_76),
        (1.585_937, 3.050_422_7),
        0.172_719_63,
        (15, 39),
        42.234_51,
        (1.312_135_1, 1.879_967_5),
        (0.331_440_33, 0.567_984_9),
    )
    .with_eye_size(Span::new(0.184_983_63, 0.359_926_88))
    .with_snout_length(Span::new(2.152_501_3, 4.507_331))
    .with_ornaments(Span::new(1.464_800_6, 1.749_664_4), 0.738_865_44);
    let seed = 10_211_869_299_900_184_870;
    let c = d3::generate(seed, &params).unwrap();
    assert_eq!(c.kind, creature::limbs::CreatureKind::Flier);
    assert!(a_leg_hangs_from_the_tail(&c));
    passes(seed, &params, &[Check::KeyTurn, Check::AngularSpeed]);
}

#[test]
fn regression_a_narrow_walker_turns_slower_rather_than_pass_its_front_legs_through_each_other() {
    // Found by the audit over valid params (case 11542 of 20,000): a walker on long legs (1.8 m
    // under a 1.5 m body) whose front feet stand 0.7 m apart. Turning in place at its full
    // rate, its front legs passed through each other (1% of the body length deep) while one
    // foot bore the body. A turn whose legs pass through each other is now tried slower.
    let params = drawn(
        Kind::Walker,
        (6, 5, 8, 8, true),
        [
            (2.021_461_7, 2.783_694),
            (1.342_532_2, 2.024_165_9),
            (1.255_227_1, 2.139_709_2),
        ],
        (0.444_005_13, 0.499_152_1),
        (2.222_739_2, 3.547_838_7),
        0.352_325_9,
        (9, 12),
        166.684_98,
        (0.705_612_24, 1.543_471),
        (0.546_669_5, 0.864_212_16),
    )
    .with_eye_size(Span::new(0.145_306_74, 0.347_324_04))
    .with_snout_length(Span::new(1.230_476_1, 1.394_398_7))
    .with_ornaments(Span::new(0.795_256_56, 2.069_260_1), 0.772_013_4);
    passes(13_725_262_081_713_939_660, &params, &Check::ALL);
}

#[test]
fn regression_a_long_front_leg_steps_before_the_hind_foot_lands_on_it() {
    // Found by the audit over valid params (case 9734 of 20,000): a walker whose front legs
    // (8.1 m) are twice as long as its hind legs and nearer the midline, their hips 1.25 m
    // apart, walking at 6.8 m/s. A front foot trailed past where the hind leg could land, the
    // hind foot came down beside it, and the legs of a side passed through each other (5% of
    // the body length deep) in `walk`. A foot trailing onto a hind foot of its side now steps
    // first (the gait's `foot_spacing`).
    let params = drawn(
        Kind::Walker,
        (1, 8, 10, 5, false),
        [
            (1.113_769_2, 2.674_89),
            (2.894_423_7, 2.950_510_7),
            (0.388_631_6, 0.523_296_5),
        ],
        (0.754_380_46, 4.758_433_3),
        (4.422_318, 4.898_66),
        0.410_137_6,
        (10, 40),
        35.732_452,
        (0.992_747_2, 1.047_531_1),
        (0.445_376_84, 0.541_037_4),
    )
    .with_eye_size(Span::new(0.315_415_5, 0.372_528_2))
    .with_snout_length(Span::new(2.230_136_2, 3.719_821_7))
    .with_ornaments(Span::new(0.751_980_3, 1.985_458_4), 0.938_962_34);
    passes(7_361_394_951_656_852_688, &params, &Check::ALL);
}

/// Fliers and swimmers over terrain (a flight from landed to landed, a swim over a seabed of
/// hills, a slope and steps to a point 10 body lengths away, as `--terrain` exports them)
/// hold every check on that terrain: nothing in the ground, no joint whipping. Seeds 0 to
/// `CREATURE_TERRAIN_SEEDS - 1` (default 6) of each kind.
#[test]
fn flights_and_swims_over_terrain_pass_the_audit_on_the_terrain() {
    let seeds = std::env::var("CREATURE_TERRAIN_SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(6u64);
    for kind in [Kind::Flier, Kind::Swimmer] {
        let params = d3::Params::DEFAULT.with_kind(kind).with_clips(false);
        let failed: Vec<String> = (0..seeds)
            .filter_map(|seed| {
                let report = terrain_report(&params, seed);
                (!report.passes()).then(|| format!("seed {seed}: {}", listed(&report)))
            })
            .collect();
        eprintln!("{kind:?} over terrain: {} of {seeds} fail", failed.len());
        assert!(failed.is_empty(), "{kind:?}: {failed:#?}");
    }
}

/// Walker `seed` (default params, no baked clips) driven live by the animator on flat ground
/// to a point 4 body lengths aside and 6 ahead, and to one 1 aside and 5 behind (it turns
/// round on the spot as it sets off), each as `bake_to` records it.
fn live_walks(seed: u64) -> d3::Creature {
    use creature::gait::Plane;
    use creature::glam::Vec3;
    let params = d3::Params::DEFAULT
        .with_kind(Kind::Walker)
        .with_clips(false);
    let mut c = d3::generate(seed, &params).unwrap();
    c.clips = [Vec3::new(4.0, 0.0, 6.0), Vec3::new(-1.0, 0.0, -5.0)]
        .into_iter()
        .map(|to| c.bake_to(&Plane::GROUND, to * c.length, 120.0).unwrap())
        .collect();
    c
}

/// Live walks (see [`live_walks`]) hold every check of the audit, as the baked clips do: a
/// tenth as many seeds as the audit's (`CREATURE_AUDIT_SEEDS`, at least 12), from its first.
#[test]
fn audit_live_walks() {
    let mut tally = Tally::default();
    let first = first_seed();
    for seed in first..first + (seeds() / 10).max(12) {
        tally.add(&format!("seed {seed}"), &live_walks(seed));
    }
    if let Err(e) = tally.finish("live walks", &Check::ALL) {
        panic!("{e}");
    }
}

#[test]
fn regression_a_step_begun_as_the_last_one_ends_turns_the_sole_on_from_its_landing() {
    // A foot whose step ended and whose next began in the same update (walkers turning round
    // as they set off) turned its sole back to the yaw it had lifted off with two steps
    // before: 47° to 52° in one key (seeds 543, 1094, 1412).
    for seed in [543, 1094, 1412] {
        let c = live_walks(seed);
        let report = audit_glb(&glb_3d(&c, &c.clips).unwrap(), &Limits::DEFAULT).unwrap();
        for check in [Check::KeyTurn, Check::AngularSpeed] {
            assert!(!report.fails(check), "seed {seed}: {}", listed(&report));
        }
    }
}

/// Walkers' `run` ([`d3::Creature::bake_run_loop`]; a hopper's hops at the run's speed) holds
/// every check of the audit, and at most one in a thousand two- and four-legged walkers never
/// has every foot off the ground in it (3 of 9,901 of the first 10,000): as many seeds as the
/// audit's (`CREATURE_AUDIT_SEEDS`, at least 24; the sweep's 10,000), from its first.
#[test]
fn run_clips_hold_the_audit_and_fly() {
    use creature::gait::LimbKind;
    let params = d3::Params::DEFAULT
        .with_kind(Kind::Walker)
        .with_clips(false);
    let first = first_seed();
    let (mut count, mut failed) = (0, Vec::new());
    let (mut two_groups, mut grounded) = (0, Vec::new());
    for seed in first..first + seeds().max(24) {
        let mut c = d3::generate(seed, &params).unwrap();
        let run = c.bake_run_loop().unwrap();
        let setup = c.gait.as_ref().unwrap();
        let walking: Vec<usize> = (0..setup.legs.len())
            .filter(|&i| setup.legs[i].kind == LimbKind::Leg)
            .collect();
        if walking.len() == 2 || walking.len() == 4 {
            let flying = run
                .contacts
                .iter()
                .filter(|frame| walking.iter().all(|&i| !frame[i]))
                .count();
            two_groups += 1;
            if flying == 0 {
                grounded.push(seed);
            }
        }
        c.clips = vec![run];
        let report = audit_glb(&glb_3d(&c, &c.clips).unwrap(), &Limits::DEFAULT).unwrap();
        if !report.passes() {
            failed.push(format!("seed {seed}: {}", listed(&report)));
        }
        count += 1;
    }
    eprintln!(
        "run clips: {count} audited, {} failed; of {two_groups} on two or four legs, {} never all up: {grounded:?}",
        failed.len(),
        grounded.len()
    );
    assert!(failed.is_empty(), "{failed:#?}");
    assert!(
        grounded.len() * 1000 <= two_groups,
        "never all up: {grounded:?}"
    );
}

#[test]
fn regression_small_fast_runners_turn_their_joints_no_faster_than_the_audit_allows() {
    // Seeds 1714 and 6651: small quadrupeds whose runs took five frames a stride at 30 fps,
    // a hip or a foot turning 21.5 and 20.3 rad/s in a swing, past the audit's 20. Their runs
    // are baked again with longer swings.
    for seed in [1714, 6651] {
        let mut c = d3::generate(seed, &d3::Params::DEFAULT.with_kind(Kind::Walker)).unwrap();
        c.clips.retain(|clip| clip.name == "run");
        assert_eq!(c.clips.len(), 1, "seed {seed}: a run");
        let report = audit_glb(&glb_3d(&c, &c.clips).unwrap(), &Limits::DEFAULT).unwrap();
        assert!(report.passes(), "seed {seed}: {}", listed(&report));
    }
}

/// Every hopping biped's `hop` (`Creature::bake_hop_loop`; every biped made to hop) holds every
/// check of the audit of delivered creatures, and has a flight each hop (frames with both feet
/// off the ground), over as many seeds as the audit's (`CREATURE_AUDIT_SEEDS`), from its first.
#[test]
fn hop_clips_hold_the_audit_and_fly() {
    use creature::gait::LimbKind;
    let params = d3::Params::DEFAULT
        .with_kind(Kind::Walker)
        .with_clips(false)
        .with_hop_chance(1.0);
    let first = first_seed();
    let (mut count, mut failed) = (0, Vec::new());
    for seed in first..first + seeds() {
        let mut c = d3::generate(seed, &params).unwrap();
        let setup = c.gait.as_ref().unwrap();
        let walking = setup
            .legs
            .iter()
            .filter(|l| l.kind == LimbKind::Leg)
            .count();
        assert_eq!(
            setup.options.hop,
            walking == 2,
            "seed {seed}: bipeds hop, no others"
        );
        if walking != 2 {
            assert!(
                c.bake_hop_loop().is_err(),
                "seed {seed}: {walking} legs hop"
            );
            continue;
        }
        let hop = c.bake_hop_loop().unwrap();
        let flying = hop
            .contacts
            .iter()
            .filter(|frame| {
                frame
                    .iter()
                    .zip(&setup.legs)
                    .all(|(&down, l)| l.kind != LimbKind::Leg || !down)
            })
            .count();
        c.clips = vec![hop];
        let report = audit_glb(&glb_3d(&c, &c.clips).unwrap(), &Limits::DEFAULT).unwrap();
        let fails: Vec<Check> = Check::ALL
            .into_iter()
            .filter(|&k| report.fails(k))
            .collect();
        if !fails.is_empty() || flying == 0 {
            eprintln!("seed {seed}: flying {flying} {}", listed(&report));
            failed.push(seed);
        }
        count += 1;
    }
    eprintln!(
        "hop clips: {count} audited, {} failed: {failed:?}",
        failed.len()
    );
    assert!(count > 0 && failed.is_empty(), "{failed:?}");
}

/// Regression: a hopper's tail swung on the spine joints its legs hang from (biped 802's hips
/// hang from its first tail joint), moving its legs off where the gait put its feet: a landing
/// foot 0.0098 body lengths under the ground. The tail now swings only behind every limb.
#[test]
fn regression_a_hoppers_tail_swings_behind_its_legs_only() {
    let params = d3::Params::DEFAULT
        .with_kind(Kind::Walker)
        .with_clips(false)
        .with_hop_chance(1.0);
    let mut c = d3::generate(802, &params).unwrap();
    c.clips = vec![c.bake_hop_loop().unwrap()];
    let report = audit_glb(&glb_3d(&c, &c.clips).unwrap(), &Limits::DEFAULT).unwrap();
    assert!(
        Check::ALL.into_iter().all(|k| !report.fails(k)),
        "{}",
        listed(&report)
    );
}
