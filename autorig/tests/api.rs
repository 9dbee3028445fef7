//! Integration tests through the public API only: capsules, straight, rotated, bent and scaled.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use approx::assert_abs_diff_eq;
use creature_autorig::glam::{Quat, Vec3};
use creature_autorig::{AutorigError, Rig, RigOptions, RootAt, rig};

use support::capsule_mesh;

const RADIUS: f32 = 0.5;
const LENGTH: f32 = 4.0;

fn capsule() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    capsule_mesh(RADIUS, LENGTH, 31, 16)
}

/// Structural checks every rig must pass.
fn check(rig: &Rig, positions: &[Vec3]) {
    assert!(rig.is_tree());
    assert_eq!(rig.spine.len(), rig.joints.len());
    assert_eq!(rig.spine.first(), Some(&rig.tail));
    assert_eq!(rig.spine.last(), Some(&rig.head));
    let (min, max) = positions
        .iter()
        .fold((positions[0], positions[0]), |(a, b), &p| {
            (a.min(p), b.max(p))
        });
    for j in &rig.joints {
        assert!(
            j.position.cmpge(min).all() && j.position.cmple(max).all(),
            "{}",
            j.position
        );
    }
    assert_eq!(rig.sockets.len(), rig.spine.len() - 3);
    for s in &rig.sockets {
        assert_eq!(positions[s.left_vertex as usize], s.left);
        assert_eq!(positions[s.right_vertex as usize], s.right);
        assert_eq!(positions[s.top_vertex as usize], s.top);
        assert!(s.width.is_finite() && s.clearance.is_finite());
    }
}

#[test]
fn a_capsule_along_z_gets_its_tips_and_symmetric_sockets() {
    let (positions, triangles) = capsule();
    let rig = rig(&positions, &triangles, &RigOptions::default()).unwrap();
    check(&rig, &positions);
    assert_eq!(rig.joints[rig.head].position, Vec3::new(0.0, 0.0, 2.0));
    assert_eq!(rig.joints[rig.tail].position, Vec3::new(0.0, 0.0, -2.0));
    // 4 / 0.4 = 10 bones, rooted at the centre.
    assert_eq!(rig.spine.len(), 11);
    assert_eq!(rig.root(), Some(0));
    assert_abs_diff_eq!(rig.joints[0].position, Vec3::ZERO, epsilon = 1e-5);
    for j in &rig.joints {
        assert_abs_diff_eq!(j.position.x, 0.0, epsilon = 1e-5);
        assert_abs_diff_eq!(j.position.y, 0.0, epsilon = 1e-5);
    }
    for s in &rig.sockets {
        // Mirror images across x = 0, top straight up, the width the diameter.
        assert_abs_diff_eq!(s.left, s.right * Vec3::new(-1.0, 1.0, 1.0), epsilon = 1e-5);
        // The creature's left is +X, its right −X (right-handed, Y up, +Z forward).
        assert!(s.left.x > 0.0 && 0.0 > s.right.x, "{s:?}");
        assert_abs_diff_eq!(s.top.x, 0.0, epsilon = 1e-5);
        assert!(s.top.y > 0.0);
        assert_abs_diff_eq!(s.width, 2.0 * RADIUS, epsilon = 0.05 * RADIUS);
        assert_abs_diff_eq!(s.clearance, RADIUS, epsilon = 0.05 * RADIUS);
        // The socket sits beside its bone.
        let bone = rig.spine_bones()[s.bone];
        let lo = bone[0].z.min(bone[1].z);
        let hi = bone[0].z.max(bone[1].z);
        assert!(s.right.z >= lo - 1e-5 && s.right.z <= hi + 1e-5);
    }
    // Sockets run from the tail forwards, skipping the first and last bones.
    let bones: Vec<usize> = rig.sockets.iter().map(|s| s.bone).collect();
    assert_eq!(bones, (1..9).collect::<Vec<_>>());
}

#[test]
fn a_swimmer_is_rooted_at_the_head() {
    let (positions, triangles) = capsule();
    let options = RigOptions::default().with_root(RootAt::Head);
    let rig = rig(&positions, &triangles, &options).unwrap();
    check(&rig, &positions);
    assert_eq!(rig.root(), Some(rig.head));
    // A chain: every joint has at most one child.
    for j in 0..rig.joints.len() {
        assert!(rig.children(j).count() <= 1);
    }
    // Segments for skinning: one per joint but the tail tip, in joint order.
    assert_eq!(rig.bone_segments().len(), rig.joints.len() - 1);
}

#[test]
fn bone_count_grows_with_length_within_limits() {
    let (positions, triangles) = capsule();
    let count =
        |options: RigOptions| rig(&positions, &triangles, &options).unwrap().spine.len() - 1;
    assert_eq!(count(RigOptions::default().with_bone_length(1.0)), 4);
    assert_eq!(count(RigOptions::default().with_bone_length(0.2)), 20);
    assert_eq!(count(RigOptions::default().with_bone_length(0.01)), 24);
    assert_eq!(count(RigOptions::default().with_bone_length(100.0)), 3);
    assert_eq!(
        count(
            RigOptions::default()
                .with_bone_length(100.0)
                .with_bone_count(2, 5)
        ),
        2
    );
}

/// Regression for two bugs this body found: the tilted tips fell outside a tube around a Z line
/// through the body's centre (the head became a cap vertex), and a ring split across a slab
/// boundary by rounding pulled the medial line sideways (socket widths came out 13% short).
#[test]
fn a_slightly_rotated_capsule_still_rigs() {
    let (positions, triangles) = capsule();
    let turn = Quat::from_rotation_y(0.08) * Quat::from_rotation_x(-0.06);
    let turned: Vec<Vec3> = positions.iter().map(|&p| turn * p).collect();
    let rig = rig(&turned, &triangles, &RigOptions::default()).unwrap();
    check(&rig, &turned);
    assert_eq!(rig.joints[rig.head].position, turned[1]);
    assert_eq!(rig.joints[rig.tail].position, turned[0]);
    for s in &rig.sockets {
        assert_abs_diff_eq!(s.width, 2.0 * RADIUS, epsilon = 0.08 * RADIUS);
    }
}

#[test]
fn a_bent_body_gets_a_spine_inside_it() {
    // FFD-like bend: the middle raised by 0.8 (more than the radius), the tips in place.
    let bend = |z: f32| 0.8 * (1.0 - (z / 2.0) * (z / 2.0));
    let (positions, triangles) = capsule();
    let bent: Vec<Vec3> = positions
        .iter()
        .map(|&p| Vec3::new(p.x, p.y + bend(p.z), p.z))
        .collect();
    let rig = rig(&bent, &triangles, &RigOptions::default()).unwrap();
    check(&rig, &bent);
    assert_eq!(rig.joints[rig.head].position, Vec3::new(0.0, 0.0, 2.0));
    assert_eq!(rig.joints[rig.tail].position, Vec3::new(0.0, 0.0, -2.0));
    for j in &rig.joints {
        let centre = Vec3::new(0.0, bend(j.position.z), j.position.z);
        assert!(
            j.position.distance(centre) < 0.5 * RADIUS,
            "{} is off the medial line",
            j.position
        );
    }
    for s in &rig.sockets {
        assert_abs_diff_eq!(s.width, 2.0 * RADIUS, epsilon = 0.1 * RADIUS);
        assert!(s.top.y > bend(s.top.z));
    }
    // The seed's straight chord runs through the air under the hump.
    let straight = creature_autorig::rig(
        &bent,
        &triangles,
        &RigOptions::default().with_follow_medial_line(false),
    )
    .unwrap();
    let middle = straight.joints[0].position;
    assert!(middle.distance(Vec3::new(0.0, bend(middle.z), middle.z)) > RADIUS);
}

#[test]
fn scaling_the_body_scales_the_rig() {
    let (positions, triangles) = capsule();
    let reference = rig(&positions, &triangles, &RigOptions::default()).unwrap();
    for scale in [0.5f32, 2.0] {
        let scaled: Vec<Vec3> = positions.iter().map(|&p| p * scale).collect();
        // Same bone length relative to the body: the same rig, scaled.
        let options = RigOptions::default().with_bone_length(0.4 * scale);
        let rig = rig(&scaled, &triangles, &options).unwrap();
        check(&rig, &scaled);
        assert_eq!(rig.joints.len(), reference.joints.len());
        for (a, b) in rig.joints.iter().zip(&reference.joints) {
            assert_abs_diff_eq!(a.position, b.position * scale, epsilon = 1e-5 * scale);
            assert_eq!(a.parent, b.parent);
        }
        for (a, b) in rig.sockets.iter().zip(&reference.sockets) {
            assert_eq!(a.left_vertex, b.left_vertex);
            assert_abs_diff_eq!(a.width, b.width * scale, epsilon = 1e-5 * scale);
        }
        // Same absolute bone length: the bone count follows the body's size.
        let absolute = creature_autorig::rig(&scaled, &triangles, &RigOptions::default()).unwrap();
        let bones = absolute.spine.len() - 1;
        assert_eq!(bones, if scale < 1.0 { 5 } else { 20 });
    }
}

#[test]
fn vertices_no_triangle_uses_are_ignored() {
    let (mut positions, triangles) = capsule();
    let plain = rig(&positions, &triangles, &RigOptions::default()).unwrap();
    positions.push(Vec3::new(0.0, 0.0, 50.0));
    let with_stray = rig(&positions, &triangles, &RigOptions::default()).unwrap();
    assert_eq!(plain, with_stray);
    // Without triangles it is a point cloud, and the stray point becomes the head.
    let cloud = rig(&positions, &[], &RigOptions::default()).unwrap();
    assert_eq!(cloud.joints[cloud.head].position, Vec3::new(0.0, 0.0, 50.0));
}

#[test]
fn rigging_is_deterministic() {
    let (positions, triangles) = capsule();
    let a = rig(&positions, &triangles, &RigOptions::default()).unwrap();
    let b = rig(&positions, &triangles, &RigOptions::default()).unwrap();
    assert_eq!(a, b);
}

#[test]
fn bad_input_is_an_error() {
    let (mut positions, mut triangles) = capsule();
    let options = RigOptions::default();
    assert_eq!(rig(&[], &[], &options), Err(AutorigError::NoVertices));
    assert_eq!(
        rig(&[Vec3::ONE; 5], &[], &options),
        Err(AutorigError::AllCoincident)
    );
    let line: Vec<Vec3> = (0..10)
        .map(|i| Vec3::new(0.1, 0.2, 1.0) * i as f32)
        .collect();
    assert_eq!(rig(&line, &[], &options), Err(AutorigError::Collinear));
    let disc: Vec<Vec3> = (0..10)
        .map(|i| Vec3::new((i as f32).cos(), (i as f32).sin(), 3.0))
        .collect();
    assert_eq!(rig(&disc, &[], &options), Err(AutorigError::NoLengthAlongZ));
    triangles.push([0, 1, 9999]);
    let err = rig(&positions, &triangles, &options).unwrap_err();
    assert_eq!(
        err,
        AutorigError::IndexOutOfRange {
            triangle: triangles.len() - 1,
            index: 9999,
            vertices: positions.len()
        }
    );
    assert!(err.to_string().contains("9999"));
    triangles.pop();
    positions[17].z = f32::NAN;
    assert_eq!(
        rig(&positions, &triangles, &options),
        Err(AutorigError::NonFinite { index: 17 })
    );
    positions[17].z = 1e30;
    assert_eq!(
        rig(&positions, &triangles, &options),
        Err(AutorigError::CoordinateTooLarge {
            index: 17,
            value: 1e30
        })
    );
    assert!(matches!(
        rig(
            &positions,
            &triangles,
            &RigOptions::default().with_bone_length(-1.0)
        ),
        Err(AutorigError::InvalidOption { .. })
    ));
}

/// Regression (found by `the_tips_are_the_capsule_tips`): on a short, squashed, tilted capsule
/// only part of the ring next to a tip fell in the "end tenth", pulling that end's centre
/// sideways until the tip left its tube; a cap vertex became the tail. The seed's own tube (on
/// the Z line through the body's centre) now counts too.
#[test]
fn a_short_tilted_capsule_keeps_its_tips() {
    let (positions, triangles) = capsule_mesh(0.1, 0.4, 8, 11);
    let turn = Quat::from_rotation_y(0.0685);
    let body: Vec<Vec3> = positions
        .iter()
        .map(|&p| turn * Vec3::new(p.x * 1.1, p.y * 0.6, p.z))
        .collect();
    let rig = rig(&body, &triangles, &RigOptions::default()).unwrap();
    check(&rig, &body);
    assert_eq!(rig.joints[rig.tail].position, body[0]);
    assert_eq!(rig.joints[rig.head].position, body[1]);
}

/// A body with nothing beside its middle bones (only its two ends have vertices): their sockets
/// fall back to the vertices around the bone, still mesh vertices, still on the right sides.
#[test]
fn bones_with_no_vertex_beside_them_still_get_sockets() {
    let mut positions = vec![Vec3::new(0.0, 0.0, -2.0), Vec3::new(0.0, 0.0, 2.0)];
    for z in [-1.9f32, 1.9] {
        for k in 0..8 {
            let a = k as f32 * core::f32::consts::FRAC_PI_4;
            positions.push(Vec3::new(0.3 * a.cos(), 0.3 * a.sin(), z));
        }
    }
    let rig = rig(&positions, &[], &RigOptions::default()).unwrap();
    check(&rig, &positions);
    assert_eq!(rig.sockets.len(), 8);
    for s in &rig.sockets {
        // The creature's left is +X, its right −X.
        assert!(s.left.x > 0.0 && 0.0 > s.right.x, "{s:?}");
        assert_abs_diff_eq!(s.width, 0.6, epsilon = 1e-5);
    }
}

/// Issue 17, finding 10: a body 1e-45 across rigged "fine" with four coincident bones and no
/// sockets at all, though every bone but the first and last promises one. A body too small
/// to give its bones a length is an error, as one of 1e-30 already was.
#[test]
fn regression_a_body_too_small_for_its_bones_is_an_error_not_a_rig_without_sockets() {
    let positions = [Vec3::ZERO, Vec3::splat(1e-45)];
    let options = RigOptions::DEFAULT.with_bone_count(4, 4);
    match rig(&positions, &[], &options) {
        Ok(r) => {
            let bones = r.spine.len() - 1;
            assert_eq!(
                r.sockets.len(),
                bones - 2,
                "one socket per inner bone: {r:?}"
            );
        }
        Err(e) => assert!(
            matches!(
                e,
                AutorigError::NoLengthAlongZ
                    | AutorigError::AllCoincident
                    | AutorigError::Collinear
            ),
            "{e:?}"
        ),
    }
}
