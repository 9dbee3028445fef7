//! Integration tests through the public API only.

// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use approx::assert_abs_diff_eq;
use creature_ffd::glam::{Mat3, Vec3};
use creature_ffd::{Axis, FfdError, InverseOptions, Lattice, MAX_COORDINATE, OutsidePolicy};

use support::reference;

/// The creature body's lattice, shaped by a fixed pattern of slice scales and gaps.
fn shaped_body() -> Lattice {
    let mut lattice = Lattice::new(
        Vec3::new(-0.5, -0.4, -2.0),
        [Vec3::X, Vec3::Y * 0.8, Vec3::Z * 4.0],
        [2, 2, 10],
    )
    .unwrap();
    for k in 0..11 {
        let f = k as f32;
        let scale = Vec3::new(
            0.6 + 0.1 * (f * 1.3).sin(),
            0.9 + 0.3 * (f * 0.7).cos(),
            1.0,
        );
        lattice.scale_slice(Axis::U, k, scale).unwrap();
    }
    let gaps: Vec<f32> = (0..10).map(|q| 0.3 + 0.05 * (q % 4) as f32).collect();
    lattice.distribute_slices(Axis::U, &gaps).unwrap();
    lattice
}

fn sample_points(lattice: &Lattice, count: usize) -> Vec<Vec3> {
    (0..count)
        .map(|i| {
            let a = i as f32;
            let local = Vec3::new(
                (a * 0.618_034).fract(),
                (a * 0.414_213_5).fract(),
                (a * 0.732_050_8).fract(),
            );
            lattice.world_coords(local)
        })
        .collect()
}

#[test]
fn deform_agrees_with_the_reference_implementation() {
    let lattice = shaped_body();
    for p in sample_points(&lattice, 500) {
        let expected = reference::deform(
            lattice.origin(),
            lattice.axes(),
            lattice.divisions(),
            lattice.control_points(),
            p,
        );
        assert_abs_diff_eq!(lattice.deform(p), expected, epsilon = 2e-5);
    }
}

#[test]
fn deform_agrees_with_the_reference_on_an_oblique_lattice() {
    let axes = [
        Vec3::new(3.0, 0.5, 0.0),
        Vec3::new(-0.5, 2.0, 0.6),
        Vec3::new(0.2, -0.3, 5.0),
    ];
    let mut lattice = Lattice::new(Vec3::new(10.0, -4.0, 2.0), axes, [3, 1, 4]).unwrap();
    lattice
        .set_control_point([2, 1, 3], Vec3::new(11.0, -1.0, 7.0))
        .unwrap();
    lattice
        .set_control_point([0, 0, 0], Vec3::new(9.0, -4.5, 2.5))
        .unwrap();
    for local in [
        Vec3::splat(0.5),
        Vec3::new(0.1, 0.9, 0.3),
        Vec3::new(1.2, -0.1, 0.5),
    ] {
        let p = lattice.world_coords(local);
        let expected = reference::deform(
            lattice.origin(),
            lattice.axes(),
            lattice.divisions(),
            lattice.control_points(),
            p,
        );
        assert_abs_diff_eq!(lattice.deform(p), expected, epsilon = 1e-4);
    }
}

#[test]
fn batch_matches_single_points_bit_for_bit() {
    let lattice = shaped_body();
    let points = sample_points(&lattice, 1000);
    let mut batch = points.clone();
    lattice.deform_in_place(&mut batch);
    for (p, q) in points.iter().zip(&batch) {
        assert_eq!(
            lattice.deform(*p).to_array().map(f32::to_bits),
            q.to_array().map(f32::to_bits)
        );
    }
    let mut checked = points.clone();
    lattice.try_deform_in_place(&mut checked).unwrap();
    assert_eq!(checked, batch);
}

#[test]
fn undeformed_body_lattice_is_the_exact_identity() {
    let body = [Vec3::new(-1.0, 0.0, -3.0), Vec3::new(1.0, 2.0, 3.0)];
    let lattice = Lattice::around(&body, [2, 2, 10], 0.25).unwrap();
    for p in sample_points(&lattice, 200) {
        assert_eq!(lattice.deform(p), p);
    }
}

#[test]
fn shaped_body_does_not_fold_and_inverts() {
    let lattice = shaped_body();
    let report = lattice.fold_report(12);
    assert!(!report.folds(), "{report:?}");
    assert!(report.min_determinant > 0.0);
    for p in sample_points(&lattice, 50) {
        let back = lattice.inverse(lattice.deform(p)).unwrap();
        assert_abs_diff_eq!(back, p, epsilon = 1e-3);
    }
}

#[test]
fn normals_stay_perpendicular_to_deformed_tangents() {
    let lattice = shaped_body();
    let p = lattice.world_coords(Vec3::new(0.3, 0.6, 0.4));
    let n = Vec3::new(0.0, 1.0, 0.0);
    // Two tangents of the plane y = const through p.
    let j = lattice.jacobian(p);
    let deformed_n = lattice.deform_normal(p, n).unwrap();
    for tangent in [Vec3::X, Vec3::Z] {
        let deformed_tangent = j * tangent;
        assert_abs_diff_eq!(deformed_n.dot(deformed_tangent), 0.0, epsilon = 1e-5);
    }
    assert_ne!(j, Mat3::IDENTITY);
}

#[test]
fn outside_policy_is_selectable() {
    let mut lattice = shaped_body();
    let outside = lattice.world_coords(Vec3::new(0.5, 0.5, 1.3));
    assert_ne!(lattice.deform(outside), outside);
    lattice.set_outside_policy(OutsidePolicy::Unchanged);
    assert_eq!(lattice.deform(outside), outside);
    assert_eq!(lattice.jacobian(outside), Mat3::IDENTITY);
}

#[test]
fn inverse_options_are_honoured() {
    let lattice = shaped_body();
    let q = lattice.deform(lattice.world_coords(Vec3::splat(0.5)));
    let strict = InverseOptions::default()
        .with_tolerance(0.0)
        .with_max_iterations(1);
    assert!(matches!(
        lattice.inverse_with(q, &strict),
        Err(FfdError::NoConvergence { .. })
    ));
    let loose = InverseOptions::default().with_tolerance(1e-2);
    assert!(lattice.inverse_with(q, &loose).is_ok());
}

#[test]
fn errors_describe_the_fix() {
    let err = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::X, Vec3::Z], [1, 1, 1]).unwrap_err();
    assert!(err.to_string().contains("independent"), "{err}");
    let err = Lattice::around(&[], [1, 1, 1], 1.0).unwrap_err();
    assert_eq!(
        err.to_string(),
        "no points were given: pass at least one point"
    );
    let boxed: Box<dyn core::error::Error> = Box::new(err);
    assert!(!boxed.to_string().is_empty());
}

/// Regression: a property once compared `deform` at a lattice corner *in world space* with the
/// corner's control point and failed by 8e-4 on a lattice 0.23 long and 54 wide, 16 units from
/// the origin. The Bernstein sum was right; the world-to-local round trip of a badly
/// conditioned frame was not exact (s off by ~1e-5, amplified by control points moved tens of
/// units). Corners are exact in local coordinates, and the world-space error stays within the
/// frame's conditioning.
#[test]
fn regression_thin_lattice_corner_is_exact_in_local_coordinates() {
    let axes = [
        Vec3::new(-0.070_951_715, 0.126_406_12, -0.174_403_95),
        Vec3::new(-3.539_714_3, -53.389_41, -8.700_844),
        Vec3::new(-15.342_998_5, -1.762_149_9, 5.907_195_6),
    ];
    let origin = Vec3::new(0.0, 0.0, -16.347_67);
    let mut lattice = Lattice::new(origin, axes, [5, 1, 2]).unwrap();
    let cells = [axes[0] / 5.0, axes[1], axes[2] / 2.0];
    let mut n = 0.0f32;
    for k in 0..=2 {
        for j in 0..=1 {
            for i in 0..=5 {
                n += 1.0;
                let shift = cells[0] * (0.3 * (n * 1.7).sin())
                    + cells[1] * (0.3 * (n * 2.3).cos())
                    + cells[2] * (0.3 * (n * 0.9).sin());
                let p = lattice.control_point([i, j, k]).unwrap();
                lattice.set_control_point([i, j, k], p + shift).unwrap();
            }
        }
    }
    let corner = lattice.control_point([0, 1, 2]).unwrap();
    let local = Vec3::new(0.0, 1.0, 1.0);
    let diagonal = axes.iter().map(|a| a.length()).sum::<f32>();
    assert!(lattice.deform_local(local).distance(corner) <= 1e-6 * diagonal);
    // Through world space the frame's conditioning shows, but stays small.
    let world = lattice.deform(lattice.world_coords(local));
    assert!(
        world.distance(corner) <= 1e-4 * diagonal,
        "{world} vs {corner}"
    );
}

/// Lattices too deep (17+ slices) or too wide (layers over 9 points) for the fast kernel take
/// the general one; both must match the plain sum.
#[test]
fn general_kernel_agrees_with_the_reference() {
    for divisions in [[2, 2, 20], [4, 4, 3], [1, 9, 2]] {
        let mut lattice = Lattice::new(
            Vec3::new(1.0, 2.0, -3.0),
            [Vec3::X * 2.0, Vec3::Y * 1.5, Vec3::Z * 5.0],
            divisions,
        )
        .unwrap();
        let [l, m, n] = divisions;
        let mut seed = 0.0f32;
        for k in 0..=n {
            for j in 0..=m {
                for i in 0..=l {
                    seed += 1.0;
                    let p = lattice.control_point([i, j, k]).unwrap();
                    let wobble =
                        Vec3::new((seed * 1.1).sin(), (seed * 0.7).cos(), (seed * 1.9).sin());
                    lattice
                        .set_control_point([i, j, k], p + wobble * 0.1)
                        .unwrap();
                }
            }
        }
        let points = sample_points(&lattice, 64);
        let mut batch = points.clone();
        lattice.deform_in_place(&mut batch);
        for (p, q) in points.iter().zip(&batch) {
            let expected = reference::deform(
                lattice.origin(),
                lattice.axes(),
                lattice.divisions(),
                lattice.control_points(),
                *p,
            );
            assert_abs_diff_eq!(*q, expected, epsilon = 1e-4);
            assert_eq!(lattice.deform(*p), *q);
        }
    }
}

/// Issue 17, finding 8: a tiny normal came out of `deform_normal` 0.992 long (its squared
/// length underflowed), though the docs promise a unit normal.
#[test]
fn regression_deform_normal_is_unit_for_tiny_and_huge_normals() {
    let lattice = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], [1, 1, 1]).unwrap();
    for normal in [
        Vec3::new(2e-22, 0.0, 0.0),
        Vec3::new(1e-30, -3e-31, 2e-30),
        Vec3::new(3e37, -2e38, 1e38),
    ] {
        let n = lattice.deform_normal(Vec3::splat(0.5), normal).unwrap();
        assert!(n.is_normalized(), "{normal} -> {n} ({})", n.length());
        assert!(n.dot(normal.signum()) > 0.0 || normal.x.signum() == n.x.signum());
    }
    assert_eq!(
        lattice.deform_normal(Vec3::splat(0.5), Vec3::ZERO).unwrap(),
        Vec3::ZERO
    );
}

/// Issue 17, finding 7: a slice moved to near −f32::MAX made `deform` return NaN (where the
/// slice's weight is 0, `−∞ · 0`) or −∞ inside the lattice: the offsets from the grid and their
/// Bernstein sum overflowed. Control points beyond `MAX_COORDINATE` are now refused, and inside
/// the lattice every deformed point is finite.
#[test]
fn regression_control_points_near_f32_max_never_give_nan_inside() {
    let mut lattice = Lattice::new(
        Vec3::ZERO,
        [Vec3::X * 10.0, Vec3::Y * 10.0, Vec3::Z * 10.0],
        [1, 2, 13],
    )
    .unwrap();
    let before = lattice.clone();
    let result = lattice.translate_slice(Axis::U, 13, Vec3::new(0.0, -f32::MAX, 1.748_592_4));
    if result.is_ok() {
        // Inside points, half of them on the face u = 0 where slice 13 weighs exactly 0.
        let bad: Vec<(Vec3, Vec3)> = (0..500)
            .map(|i| {
                let a = i as f32;
                let u = if i % 2 == 0 { 0.0 } else { (a * 0.732).fract() };
                let p =
                    lattice.world_coords(Vec3::new((a * 0.618).fract(), (a * 0.4142).fract(), u));
                (p, lattice.deform(p))
            })
            .filter(|(_, q)| !q.is_finite())
            .collect();
        let nan = bad.iter().find(|(_, q)| q.is_nan());
        assert!(
            bad.is_empty(),
            "{} of 500 inside points deform to non-finite, e.g. {:?}; NaN e.g. {nan:?}",
            bad.len(),
            bad[0]
        );
    }
    assert_eq!(lattice, before);
    assert!(matches!(
        result,
        Err(FfdError::CoordinateTooLarge {
            what: "control point",
            value,
            ..
        }) if value == -f32::MAX
    ));
    // The largest accepted moves, every way: inside points stay finite.
    for offset in [
        Vec3::new(0.0, -MAX_COORDINATE, 0.0),
        Vec3::new(MAX_COORDINATE, -MAX_COORDINATE, MAX_COORDINATE) * 0.999,
    ] {
        let mut lattice = before.clone();
        lattice.translate_slice(Axis::U, 13, offset).unwrap();
        lattice.translate_slice(Axis::U, 0, -offset).unwrap();
        lattice
            .set_control_point([1, 1, 6], Vec3::splat(-MAX_COORDINATE))
            .unwrap();
        for i in 0..500 {
            let a = i as f32;
            let u = if i % 2 == 0 { 0.0 } else { (a * 0.732).fract() };
            let p = lattice.world_coords(Vec3::new((a * 0.618).fract(), (a * 0.4142).fract(), u));
            assert!(lattice.try_deform(p).is_ok(), "{offset} {p}");
        }
    }
    // Lattices and control points past the bound are refused.
    assert!(matches!(
        Lattice::new(
            Vec3::splat(1e15),
            [Vec3::X * 1e9, Vec3::Y, Vec3::Z],
            [1, 1, 1]
        ),
        Err(FfdError::CoordinateTooLarge {
            what: "lattice corner",
            index: 1,
            ..
        })
    ));
    let mut lattice = before.clone();
    assert!(matches!(
        lattice.set_control_point([0, 0, 0], Vec3::new(0.0, 0.0, 2e15)),
        Err(FfdError::CoordinateTooLarge { value: 2e15, .. })
    ));
    assert!(lattice.scale_slice(Axis::U, 1, Vec3::splat(1e15)).is_err());
    assert!(lattice.distribute_slices(Axis::U, &[1e14; 13]).is_err());
    assert_eq!(lattice, before);
}

#[test]
fn regression_axes_with_subnormal_products_are_degenerate() {
    // Found by the fuzz smoke: axes about 4.65e-15 long passed the volume check on rounding
    // noise (their products are subnormal) while the dual basis overflowed to inf and NaN.
    let a = -4.653358e-15;
    let axes = [
        Vec3::new(-4.6532873e-15, a, a),
        Vec3::splat(a),
        Vec3::new(a, 1.539667e-38, -1.7763568e-15),
    ];
    let result = Lattice::new(Vec3::new(3e-45, 2.511e-42, 0.0), axes, [7, 7, 7]);
    assert!(
        matches!(result, Err(FfdError::DegenerateAxes { .. })),
        "{:?}",
        result.map(|l| l.divisions())
    );
}
