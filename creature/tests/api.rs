//! Integration tests through the public API: determinism, bad parameters, bad skeletons,
//! detached parts, texture and animation helpers.

#![cfg(feature = "std")]
#![allow(clippy::unwrap_used)]

mod support;

use creature::glam::Vec2;
use creature::{Error, IntSpan, Span, d2, generate_2d};

#[test]
fn same_seed_same_creature_bit_for_bit() {
    for seed in [0, 5, 77, 123_456_789] {
        let a = generate_2d(seed, &d2::Params::DEFAULT).unwrap();
        let b = generate_2d(seed, &d2::Params::DEFAULT).unwrap();
        assert_eq!(a, b);
        let bits = |c: &creature::d2::Creature| -> Vec<u32> {
            c.mesh
                .positions
                .iter()
                .flat_map(|p| p.to_array())
                .map(f32::to_bits)
                .collect()
        };
        assert_eq!(bits(&a), bits(&b));
        assert_eq!(a.seed, seed);
    }
    let a = generate_2d(1, &d2::Params::DEFAULT).unwrap();
    let b = generate_2d(2, &d2::Params::DEFAULT).unwrap();
    assert_ne!(a.mesh.positions, b.mesh.positions);
}

#[test]
fn generated_creatures_are_valid() {
    for seed in 0..12 {
        let c = generate_2d(seed, &d2::Params::DEFAULT).unwrap();
        let problems = support::check(&c);
        assert!(problems.is_empty(), "seed {seed}: {problems:?}");
        assert!(c.quality.max_weight_sum_error <= 1e-6);
        assert!(c.quality.outline_error < 2.5, "{}", c.quality.outline_error);
        let (min, max) = c.bounds;
        for uv in &c.mesh.uvs {
            assert!((-1e-6..=1.0 + 1e-6).contains(&uv.x) && (-1e-6..=1.0 + 1e-6).contains(&uv.y));
        }
        assert!(max.x > min.x && max.y > min.y);
        // The head carries the eyes; bones without children (limb tips, a limbless head) own
        // no balls: a segment's balls belong to its parent.
        let head = c
            .bones
            .iter()
            .position(|b| b.kind == d2::BoneKind::Head)
            .unwrap();
        assert!(c.eyes.iter().all(|e| e.bone == head));
        for (i, _) in c.bones.iter().enumerate() {
            if !c.bones.iter().any(|b| b.parent == Some(i)) {
                assert!(c.balls.iter().all(|b| b.ball.id as usize != i));
            }
        }
    }
}

#[test]
fn higher_vertices_are_drawn_on_top() {
    let c = generate_2d(9, &d2::Params::DEFAULT.with_texture(false)).unwrap();
    let (min, max) = c.bounds;
    for p in &c.mesh.positions {
        let expected = (p.y - min.y) / (max.y - min.y);
        assert!((p.z - expected).abs() < 1e-6);
    }
}

fn expect_err(params: d2::Params, what: &str) {
    match generate_2d(1, &params) {
        Err(Error::NonFinite { what: w })
        | Err(Error::OutOfRange { what: w, .. })
        | Err(Error::EmptyRange { what: w, .. }) => assert_eq!(w, what),
        other => panic!("{what}: expected a parameter error, got {other:?}"),
    }
}

#[test]
fn bad_params_are_errors() {
    let d = d2::Params::DEFAULT;
    expect_err(
        d.with_spine_thickness(Span::new(-10.0, 40.0)),
        "spine_thickness",
    );
    expect_err(d.with_spine_length(Span::new(100.0, 50.0)), "spine_length");
    expect_err(d.with_limb_length(Span::new(f32::NAN, 80.0)), "limb_length");
    expect_err(
        d.with_limb_thickness(Span::new(5.0, f32::INFINITY)),
        "limb_thickness",
    );
    expect_err(
        d.with_spine_multiplier(Span::new(0.5, 1.6)),
        "spine_multiplier",
    );
    expect_err(
        d.with_limb_multiplier(Span::new(1.2, 1.1)),
        "limb_multiplier",
    );
    expect_err(d.with_spine_bones(IntSpan::new(6, 3)), "spine_bones");
    expect_err(d.with_spine_bones(IntSpan::new(0, 3)), "spine_bones");
    expect_err(d.with_limb_bones(IntSpan::new(1, 4)), "limb_bones");
    expect_err(d.with_eye_count(IntSpan::new(3, 1)), "eye_count");
    expect_err(d.with_eye_size(Span::new(-0.5, 1.0)), "eye_size");
    expect_err(d.with_limb_probability(1.5), "limb_probability");
    expect_err(d.with_limb_probability(f32::NAN), "limb_probability");
    expect_err(d.with_socket_offset(-1.0), "socket_offset");
    expect_err(d.with_texture_size(0), "texture_size");
    expect_err(d.with_texture_size(100_000), "texture_size");
    expect_err(d.with_outline_step(0.0), "outline_step");
    expect_err(d.with_outline_step(f32::NEG_INFINITY), "outline_step");
    expect_err(d.with_simplify(-1.0), "simplify");
    expect_err(d.with_interior_spacing(f32::NAN), "interior_spacing");
    expect_err(d.with_min_angle(40.0), "min_angle");
    expect_err(d.with_depth_shading(-0.1), "depth_shading");
    expect_err(d.with_normal_relief(f32::INFINITY), "normal_relief");
    // Errors have messages that say what to do.
    let e = generate_2d(1, &d.with_spine_length(Span::new(100.0, 50.0))).unwrap_err();
    assert!(e.to_string().contains("spine_length"));
}

#[test]
fn bad_skeletons_are_errors() {
    let params = d2::Params::DEFAULT.with_texture(false);
    let good = d2::skeleton_from_seed(4, &params).unwrap();
    assert!(d2::build(&good, &params).is_ok());

    let mut s = good.clone();
    s.bones[2].parent = Some(5);
    assert_eq!(
        d2::build(&s, &params),
        Err(Error::BadParent {
            bone: 2,
            parent: Some(5)
        })
    );
    let mut s = good.clone();
    s.bones[1].position.x = f32::NAN;
    assert!(matches!(
        d2::build(&s, &params),
        Err(Error::NonFinite { .. })
    ));
    let mut s = good.clone();
    s.bones[1].multiplier = 3.0;
    assert!(matches!(
        d2::build(&s, &params),
        Err(Error::OutOfRange { .. })
    ));
    let mut s = good.clone();
    for b in &mut s.bones {
        b.thickness = 0.0;
    }
    assert_eq!(d2::build(&s, &params), Err(Error::EmptySkeleton));
    let mut s = good;
    s.bones.clear();
    assert_eq!(d2::build(&s, &params), Err(Error::EmptySkeleton));
}

#[test]
fn a_detached_limb_is_an_error_never_dropped() {
    // Without the socket links, a thin limb far from a thick spine floats free.
    let params = d2::Params::DEFAULT
        .with_texture(false)
        .with_connect_sockets(false)
        .with_limb_probability(1.0)
        .with_spine_thickness(Span::new(35.0, 40.0))
        .with_limb_thickness(Span::new(5.0, 6.0))
        .with_socket_offset(3.0);
    let err = generate_2d(3, &params).unwrap_err();
    assert!(
        matches!(err, Error::Detached { components } if components > 1),
        "{err:?}"
    );
    // With them (the default), the same skeleton stays in one piece.
    let c = generate_2d(3, &params.with_connect_sockets(true)).unwrap();
    assert!(support::check(&c).is_empty());
}

#[test]
fn texture_and_normal_map() {
    let c = generate_2d(11, &d2::Params::DEFAULT.with_texture_size(96)).unwrap();
    let t = c.texture.as_ref().unwrap();
    let n = c.normal_map.as_ref().unwrap();
    assert_eq!((t.width, t.height, t.rgba.len()), (96, 96, 96 * 96 * 4));
    assert_eq!(n.rgba.len(), t.rgba.len());
    let inside = t.rgba.chunks_exact(4).filter(|p| p[3] == 255).count();
    assert!(inside > 96 * 96 / 10, "{inside}");
    // Decoded normals have unit length and face the viewer.
    for p in n.rgba.chunks_exact(4) {
        let v = Vec2::new(f32::from(p[0]) / 127.5 - 1.0, f32::from(p[1]) / 127.5 - 1.0);
        let z = f32::from(p[2]) / 127.5 - 1.0;
        assert!(z > 0.0);
        assert!(((v.length_squared() + z * z).sqrt() - 1.0).abs() < 0.02);
    }
    let none = generate_2d(11, &d2::Params::DEFAULT.with_texture(false)).unwrap();
    assert!(none.texture.is_none() && none.normal_map.is_none());
    assert_eq!(none.mesh, c.mesh);
}

#[test]
fn idle_animation_and_pose() {
    let c = generate_2d(8, &d2::Params::DEFAULT.with_texture(false)).unwrap();
    let at_zero = c.idle_rotations(0.0);
    assert!(at_zero.iter().all(|&r| r == 0.0));
    let later = c.idle_rotations(3.0);
    assert_eq!(later.len(), c.bones.len());
    for (b, r) in c.bones.iter().zip(&later) {
        assert!(r.abs() <= 1.0);
        if matches!(b.kind, d2::BoneKind::Root | d2::BoneKind::Head) {
            assert_eq!(*r, 0.0);
        }
    }
    assert!(later.iter().any(|&r| r != 0.0));
    // The rest pose reproduces the rest positions.
    for (b, (p, a)) in c.bones.iter().zip(c.pose(&[])) {
        assert!(b.position.distance(p) < 1e-3);
        assert_eq!(a, 0.0);
    }
    assert!(c.idle_rotations(f32::NAN).iter().all(|&r| r == 0.0));
}
