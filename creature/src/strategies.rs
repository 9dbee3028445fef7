//! Proptest strategies for this crate's inputs (feature `proptest`).
//!
//! Valid inputs ([`params_2d`], [`params`], [`params_of_kind`], [`seed`]) vary every range
//! inside its documented bounds — within a moderate sub-box of each (small textures, a few
//! dozen bones at most) so that one generation stays around a millisecond and a property can
//! run dozens of cases. Adversarial ones ([`bad_params_2d`], [`bad_params`]) break exactly one
//! field (a range with `min > max`, a NaN or infinity, a zero count or a value out of range),
//! so the generators must answer with an [`Error`](crate::Error), never a panic.
//!
//! ```
//! use creature::{generate_2d, strategies};
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::deterministic();
//! runner.run(&(strategies::seed(), strategies::bad_params_2d()), |(seed, params)| {
//!     prop_assert!(generate_2d(seed, &params).is_err());
//!     Ok(())
//! }).unwrap();
//! ```

use proptest::prelude::*;

use crate::d3::{
    BackKind, BackWeights, Kind, Params, Pattern, PatternWeights, WingKind, WingWeights,
};
use crate::{IntSpan, Span, d2};

/// Any seed.
pub fn seed() -> impl Strategy<Value = u64> {
    any::<u64>()
}

/// A [`Span`] with `lo <= min <= max <= hi` (`min == max` included).
pub fn span(lo: f32, hi: f32) -> impl Strategy<Value = Span> {
    (lo..=hi, lo..=hi).prop_map(|(a, b)| Span::new(a.min(b), a.max(b)))
}

/// An [`IntSpan`] with `lo <= min <= max <= hi`.
pub fn int_span(lo: u32, hi: u32) -> impl Strategy<Value = IntSpan> {
    (lo..=hi, lo..=hi).prop_map(|(a, b)| IntSpan::new(a.min(b), a.max(b)))
}

/// Valid 2D parameters: every field drawn inside its documented range (see [`d2::Params`]),
/// kept to a moderate box so generation stays fast — spine 2 to 8 bones, limbs 2 to 5,
/// lengths and thicknesses around the seed's, outline step 3 to 8, texture 8 to 64 pixels.
/// [`connect_sockets`](d2::Params::connect_sockets) stays on (off, a detached limb is a
/// documented [`Error::Detached`](crate::Error::Detached)). Always passes
/// [`d2::Params::validate`].
pub fn params_2d() -> impl Strategy<Value = d2::Params> {
    let spine = (
        int_span(2, 8),
        span(5.0, 50.0),
        span(20.0, 120.0),
        span(1.0, 1.6),
    );
    let limbs = (
        0.0f32..=1.0,
        int_span(2, 5),
        span(20.0, 100.0),
        span(3.0, 20.0),
        span(1.0, 1.6),
        0.0f32..=4.0,
    );
    let eyes = (int_span(0, 8), span(0.0, 1.0));
    let mesh = (
        3.0f32..=8.0,
        0.0f32..=0.5,
        10.0f32..=40.0,
        0.0f32..=1.5,
        0.0f32..=30.0,
    );
    let texture = (any::<bool>(), 8u32..=64, 0.0f32..=4.0, 0.0f32..=50.0);
    (spine, limbs, eyes, mesh, texture).prop_map(
        |(
            (spine_bones, spine_thickness, spine_length, spine_multiplier),
            (limb_probability, limb_bones, limb_length, limb_thickness, limb_multiplier, socket),
            (eye_count, eye_size),
            (outline_step, simplify, interior_spacing, clearance, min_angle),
            (texture, texture_size, depth_shading, normal_relief),
        )| {
            d2::Params::DEFAULT
                .with_spine_bones(spine_bones)
                .with_spine_thickness(spine_thickness)
                .with_spine_length(spine_length)
                .with_spine_multiplier(spine_multiplier)
                .with_limb_probability(limb_probability)
                .with_limb_bones(limb_bones)
                .with_limb_length(limb_length)
                .with_limb_thickness(limb_thickness)
                .with_limb_multiplier(limb_multiplier)
                .with_socket_offset(socket)
                .with_eye_count(eye_count)
                .with_eye_size(eye_size)
                .with_outline_step(outline_step)
                // A fraction of the step: `simplify` must not exceed it.
                .with_simplify(simplify * outline_step)
                .with_interior_spacing(interior_spacing)
                .with_interior_clearance(clearance)
                .with_min_angle(min_angle)
                .with_texture(texture)
                .with_texture_size(texture_size)
                .with_depth_shading(depth_shading)
                .with_normal_relief(normal_relief)
        },
    )
}

/// One of [`Kind::Walker`], [`Kind::Flier`], [`Kind::Swimmer`], [`Kind::Slitherer`] and
/// [`Kind::Random`].
pub fn kind() -> impl Strategy<Value = Kind> {
    prop_oneof![
        Just(Kind::Walker),
        Just(Kind::Flier),
        Just(Kind::Swimmer),
        Just(Kind::Slitherer),
        Just(Kind::Random),
    ]
}

/// Valid weights of `all`'s kinds, built from `only` and `with`: each from 0 to 1000 (often
/// 0), at least one above 0.
fn weights<K, W>(
    all: &'static [K],
    only: fn(K) -> W,
    with: fn(W, K, f32) -> W,
) -> impl Strategy<Value = W>
where
    K: Copy + PartialEq + core::fmt::Debug + 'static,
    W: core::fmt::Debug,
{
    let weight = prop_oneof![Just(0.0f32), 0.0f32..=1000.0];
    (
        proptest::collection::vec(weight, all.len()),
        proptest::sample::select(all),
        0.001f32..=1000.0,
    )
        .prop_map(move |(weights, kept, floor)| {
            let mut w = with(only(kept), kept, floor);
            for (&k, weight) in all.iter().zip(weights) {
                if k != kept {
                    w = with(w, k, weight);
                }
            }
            w
        })
}

/// Valid pattern weights: each from 0 to 1000 (often 0), at least one above 0.
pub fn pattern_weights() -> impl Strategy<Value = PatternWeights> {
    weights(&Pattern::ALL, PatternWeights::only, PatternWeights::with)
}

/// Valid wing-kind weights: each from 0 to 1000 (often 0), at least one above 0.
pub fn wing_weights() -> impl Strategy<Value = WingWeights> {
    weights(&WingKind::ALL, WingWeights::only, WingWeights::with)
}

/// Valid back-kind weights: each from 0 to 1000 (often 0), at least one above 0.
pub fn back_weights() -> impl Strategy<Value = BackWeights> {
    weights(&BackKind::ALL, BackWeights::only, BackWeights::with)
}

/// Valid 3D parameters of the given kind: every field drawn inside its documented range (see
/// [`Params`]), kept to a moderate box so generation stays fast — up to 24 rings and 16
/// segments, slice scales 0.3 to 3 (a slitherer's 0.15 to 1 across, 0.5 to 3 along), body scale 0.1 to 10, bones 0.1 to 0.5 long, at most 40
/// spine bones; colours, the head's eyes, snout and ornaments, the limbs' proportions
/// ([`Params::thigh_thickness`], [`Params::wing_span`], [`Params::wing_area`]) and the back's
/// ornaments over their whole ranges. The limb planner keeps its defaults. Always passes [`Params::validate`].
pub fn params_of_kind(kind: Kind) -> impl Strategy<Value = Params> {
    let mesh = (1u32..=9, 4u32..=24, 3u32..=16, 3u32..=8, any::<bool>());
    let slices = (
        span(0.3, 3.0),
        span(0.3, 3.0),
        span(0.3, 3.0),
        span(0.3, 3.0),
        span(0.3, 3.0),
        span(0.3, 3.0),
        span(0.15, 1.0),
        span(0.15, 1.0),
        span(0.5, 3.0),
    );
    let body = (
        span(0.1, 10.0),
        span(0.1, 5.0),
        0.1f32..=0.5,
        int_span(5, 40),
        0.0f32..=200.0,
        span(0.5, 2.0),
        span(0.0, 1.0),
        any::<bool>(),
    );
    let colours = (span(0.0, 1.0), span(0.0, 1.0), pattern_weights());
    let head = (
        span(0.05, 0.6),
        span(0.0, 5.0),
        span(0.0, 3.0),
        0.0f32..=1.0,
        0.2f32..=1.0,
    );
    let limbs = (
        span(1.0, 3.0),
        span(0.2, 5.0),
        span(0.1, 10.0),
        span(0.0, 3.0),
        0.0f32..=1.0,
        (wing_weights(), back_weights(), span(0.0, 1.0), 0.0f32..=1.0),
    );
    (mesh, slices, body, colours, head, limbs).prop_map(
        move |(
            (profiles, rings, segments, limb_sides, flat),
            (
                width,
                height,
                step,
                swim_width,
                swim_height,
                swim_step,
                slither_width,
                slither_height,
                slither_step,
            ),
            (scale, speed, bone_length, spine_bones, bend, head, clearance, clips),
            (saturation, countershading, patterns),
            (eye_size, snout_length, ornament_size, ornament_chance, neck_width),
            (
                thigh_thickness,
                wing_span,
                wing_area,
                back_size,
                back_chance,
                (wings, backs, shell, hop_chance),
            ),
        )| {
            Params::DEFAULT
                .with_kind(kind)
                .with_profiles(profiles)
                .with_resolution(rings, segments)
                .with_limb_sides(limb_sides)
                .with_flat_normals(flat)
                .with_slices(width, height, step)
                .with_swimmer_slices(swim_width, swim_height, swim_step)
                .with_slitherer_slices(slither_width, slither_height, slither_step)
                .with_body_scale(scale)
                .with_speed_factor(speed)
                .with_bone_length(bone_length)
                .with_spine_bones(spine_bones)
                .with_spine_bend(bend)
                .with_head_size(head)
                .with_neck_width(neck_width)
                .with_ground_clearance(clearance)
                .with_saturation(saturation)
                .with_countershading(countershading)
                .with_patterns(patterns)
                .with_eye_size(eye_size)
                .with_snout_length(snout_length)
                .with_ornaments(ornament_size, ornament_chance)
                .with_thigh_thickness(thigh_thickness)
                .with_back_ornaments(back_size, back_chance)
                .with_wings(wing_span, wing_area)
                .with_wing_kinds(wings)
                .with_back_kinds(backs)
                .with_shell_size(shell)
                .with_hop_chance(hop_chance)
                .with_clips(clips)
        },
    )
}

/// Valid 3D parameters of any [`kind`]; see [`params_of_kind`].
pub fn params() -> impl Strategy<Value = Params> {
    kind().prop_flat_map(params_of_kind)
}

/// A float that is NaN or ±infinity.
pub fn non_finite_f32() -> impl Strategy<Value = f32> {
    prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY)]
}

/// Valid [`params_2d`] with exactly one field broken: a range with `min > max`, a NaN or
/// infinite value, a zero count (spine or limb bones, texture size) or a value out of range
/// (`simplify` above `outline_step`, a multiplier below 1). [`d2::Params::validate`] — and so
/// [`generate_2d`](crate::generate_2d) — rejects every one.
pub fn bad_params_2d() -> impl Strategy<Value = d2::Params> {
    (params_2d(), non_finite_f32(), 0usize..10).prop_map(|(p, bad, which)| {
        let swap = |s: Span| {
            if s.min < s.max {
                Span::new(s.max, s.min)
            } else {
                Span::new(s.min + 1.0, s.min)
            }
        };
        match which {
            0 => p.with_spine_length(swap(p.spine_length)),
            1 => p.with_limb_thickness(swap(p.limb_thickness)),
            2 => p.with_spine_bones(IntSpan::new(p.spine_bones.max + 1, p.spine_bones.min)),
            3 => p.with_spine_thickness(Span::new(bad, p.spine_thickness.max)),
            4 => p.with_outline_step(bad),
            5 => p.with_limb_probability(bad),
            6 => p.with_spine_bones(IntSpan::new(0, p.spine_bones.max)),
            7 => p.with_limb_bones(IntSpan::new(0, 0)),
            8 => p.with_texture_size(0),
            _ => p.with_simplify(p.outline_step * 1.5),
        }
    })
}

/// Valid [`params`] with exactly one field broken: a range with `min > max`, a NaN or
/// infinite value, a zero count (profiles, rings, segments, limb sides, spine bones), a value
/// out of range (a colour range outside 0 to 1, an eye size above 0.6, a negative pattern
/// weight) or every pattern, wing-kind or back-kind weight 0. [`Params::validate`] — and so [`generate`](crate::generate) — rejects every one.
pub fn bad_params() -> impl Strategy<Value = Params> {
    (params(), non_finite_f32(), 0usize..24).prop_map(|(p, bad, which)| {
        let swap = |s: Span| {
            if s.min < s.max {
                Span::new(s.max, s.min)
            } else {
                Span::new(s.min + 0.1, s.min)
            }
        };
        match which {
            0 => p.with_body_scale(swap(p.body_scale)),
            1 => p.with_slices(p.slice_width, p.slice_height, swap(p.slice_step)),
            2 => p.with_body_scale(Span::new(p.body_scale.min, bad)),
            3 => p.with_bone_length(bad),
            4 => p.with_spine_bend(bad),
            5 => p.with_profiles(0),
            6 => p.with_resolution(0, p.segments),
            7 => p.with_resolution(p.rings, 0),
            8 => p.with_limb_sides(0),
            9 => p.with_saturation(Span::new(p.saturation.min, 1.5)),
            10 => p.with_countershading(swap(p.countershading)),
            11 => p.with_patterns(p.patterns.with(Pattern::Spots, bad)),
            12 => p.with_patterns(PatternWeights::only(Pattern::Bands).with(Pattern::Bands, -1.0)),
            13 => p.with_eye_size(Span::new(p.eye_size.min, 0.7)),
            14 => p.with_snout_length(swap(p.snout_length)),
            15 => p.with_ornaments(p.ornament_size, bad),
            16 => p.with_back_ornaments(p.back_ornament_size, bad),
            17 => p.with_wing_kinds(WingWeights::only(WingKind::Bat).with(WingKind::Bat, 0.0)),
            18 => p.with_back_kinds(p.back_kinds.with(BackKind::Shell, bad)),
            19 => {
                p.with_back_kinds(BackWeights::only(BackKind::Spikes).with(BackKind::Spikes, 0.0))
            }
            20 => p.with_shell_size(swap(p.shell_size)),
            21 => p.with_neck_width(bad),
            22 => p.with_hop_chance(bad),
            _ => p.with_spine_bones(IntSpan::new(0, 0)),
        }
    })
}
