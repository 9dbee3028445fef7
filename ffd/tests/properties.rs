//! Property tests of the invariants the crate promises, driven by its public strategies.

use creature_ffd::glam::{Mat3, Vec3};
use creature_ffd::{FfdError, Lattice, strategies};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;

mod support;

use support::reference;

/// Tolerance for a lattice: a small fraction of its diagonal.
fn tolerance(lattice: &Lattice, fraction: f32) -> f32 {
    let [s, t, u] = lattice.axes();
    fraction * (s.length() + t.length() + u.length())
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
    fn undeformed_lattice_is_the_identity(
        lattice in strategies::lattice(),
        local in strategies::local_point(),
    ) {
        let p = lattice.world_coords(local);
        // Bit for bit through the crate (offsets from the grid are all zero).
        prop_assert_eq!(lattice.deform(p), p);
        let mut batch = [p; 5];
        lattice.deform_in_place(&mut batch);
        prop_assert_eq!(batch, [p; 5]);
        // And the paper's identity itself: the plain Bernstein sum over the undeformed grid
        // reproduces the point (linear precision), within rounding.
        let summed = reference::deform(
            lattice.origin(),
            lattice.axes(),
            lattice.divisions(),
            lattice.control_points(),
            p,
        );
        let slack = tolerance(&lattice, 1e-5) + 1e-5 * p.length();
        prop_assert!(summed.distance(p) <= slack, "{} vs {}", summed, p);
    }

    #[test]
    fn an_affine_map_of_the_control_points_maps_points_the_same_way(
        lattice in strategies::lattice(),
        local in strategies::local_point(),
        linear in prop::array::uniform9(-0.5f32..0.5),
        shift in strategies::vec3_in(10.0),
    ) {
        let matrix = Mat3::IDENTITY + Mat3::from_cols_array(&linear);
        let map = |p: Vec3| matrix * p + shift;
        let mut moved = lattice.clone();
        let [l, m, n] = lattice.divisions();
        for k in 0..=n {
            for j in 0..=m {
                for i in 0..=l {
                    let p = lattice.control_point([i, j, k]).unwrap();
                    moved.set_control_point([i, j, k], map(p)).unwrap();
                }
            }
        }
        let p = lattice.world_coords(local);
        let expected = map(p);
        let got = moved.deform(p);
        let scale = tolerance(&lattice, 2e-5) + 2e-5 * (p.length() + shift.length());
        prop_assert!(got.distance(expected) <= scale, "{} vs {}", got, expected);
    }

    #[test]
    fn corners_go_to_their_control_points(lattice in strategies::deformed_lattice(0.3), corner in 0usize..8) {
        let [l, m, n] = lattice.divisions();
        let index = [
            if corner & 1 == 0 { 0 } else { l },
            if corner & 2 == 0 { 0 } else { m },
            if corner & 4 == 0 { 0 } else { n },
        ];
        let local = Vec3::new((corner & 1) as f32, ((corner >> 1) & 1) as f32, ((corner >> 2) & 1) as f32);
        // In local coordinates: going through world space would add the frame's conditioning
        // (a thin, long lattice amplifies rounding in `local_coords`) to what is tested here.
        let expected = lattice.control_point(index).unwrap();
        let got = lattice.deform_local(local);
        prop_assert!(got.distance(expected) <= tolerance(&lattice, 1e-5), "{} vs {}", got, expected);
    }

    #[test]
    fn batch_equals_per_point(
        lattice in strategies::deformed_lattice(0.3),
        locals in prop::collection::vec(strategies::local_point(), 1..40),
    ) {
        let points: Vec<Vec3> = locals.iter().map(|&l| lattice.world_coords(l)).collect();
        let mut batch = points.clone();
        lattice.deform_in_place(&mut batch);
        for (p, q) in points.iter().zip(&batch) {
            prop_assert_eq!(lattice.deform(*p), *q);
        }
    }

    #[test]
    fn inverse_undoes_mild_deformations(
        lattice in strategies::deformed_lattice(0.1),
        local in strategies::local_point(),
    ) {
        let p = lattice.world_coords(local);
        let back = lattice.inverse(lattice.deform(p));
        prop_assert!(back.is_ok(), "{:?}", back);
        let back = back.unwrap();
        prop_assert!(back.distance(p) <= tolerance(&lattice, 1e-4), "{} vs {}", back, p);
    }

    #[test]
    fn deformed_points_and_normals_are_finite(
        lattice in strategies::deformed_lattice(0.1),
        local in strategies::local_point(),
    ) {
        let p = lattice.world_coords(local);
        prop_assert!(lattice.deform(p).is_finite());
        let n = lattice.deform_normal(p, Vec3::Y).unwrap();
        prop_assert!(n.is_finite());
        prop_assert!((n.length() - 1.0).abs() < 1e-4);
    }

    #[test]
    fn seed_style_bodies_never_fold(lattice in strategies::body_lattice()) {
        let report = lattice.fold_report(6);
        prop_assert!(!report.folds(), "{:?}", report);
    }

    /// Swapping an end slice with any other slice reverses the lattice's direction at that
    /// end, so the Jacobian determinant there is negative. (Swapping two *interior* slices of
    /// a high-degree lattice need not fold: the Bernstein sum smooths a small inversion away;
    /// see the unit test `interior_swap_can_be_smoothed_away`.)
    #[test]
    fn swapping_an_end_slice_is_detected_as_a_fold(
        lattice in strategies::lattice(),
        axis in 0usize..3,
        other in 1usize..=32,
        end_is_last in any::<bool>(),
    ) {
        let divisions = lattice.divisions();
        let last = divisions[axis];
        let other = 1 + (other - 1) % last; // 1..=last
        let (a, b) = if end_is_last { (last, last - other) } else { (0, other) };
        let mut swapped = lattice.clone();
        let [l, m, n] = divisions;
        for k in 0..=n {
            for j in 0..=m {
                for i in 0..=l {
                    let mut index = [i, j, k];
                    if index[axis] != a {
                        continue;
                    }
                    let p = lattice.control_point(index).unwrap();
                    index[axis] = b;
                    let q = lattice.control_point(index).unwrap();
                    swapped.set_control_point(index, p).unwrap();
                    index[axis] = a;
                    swapped.set_control_point(index, q).unwrap();
                }
            }
        }
        prop_assert!(swapped.folds(2), "{:?}", swapped.fold_report(2));
    }

    #[test]
    fn non_finite_origins_are_rejected(origin in strategies::non_finite_vec3(), (_, axes) in strategies::frame()) {
        prop_assert_eq!(
            Lattice::new(origin, axes, [1, 1, 1]),
            Err(FfdError::NonFinite { what: "origin", index: None })
        );
    }

    #[test]
    fn degenerate_axes_are_rejected(axes in strategies::degenerate_axes()) {
        let is_degenerate_error = matches!(Lattice::new(Vec3::ZERO, axes, [1, 1, 1]), Err(FfdError::DegenerateAxes { .. }));
        prop_assert!(is_degenerate_error);
    }

    #[test]
    fn bad_divisions_are_rejected(divisions in strategies::bad_divisions()) {
        let result = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], divisions);
        let is_divisions_error = matches!(
            result,
            Err(FfdError::ZeroDivisions { .. } | FfdError::TooManyDivisions { .. })
        );
        prop_assert!(is_divisions_error);
    }

    #[test]
    fn non_finite_points_never_become_errors_silently(
        lattice in strategies::deformed_lattice(0.2),
        bad in strategies::non_finite_vec3(),
    ) {
        let is_non_finite = matches!(lattice.try_deform(bad), Err(FfdError::NonFinite { .. }));
        prop_assert!(is_non_finite);
        let mut points = [lattice.origin(), bad];
        let is_non_finite = matches!(lattice.try_deform_in_place(&mut points), Err(FfdError::NonFinite { index: Some(1), .. }));
        prop_assert!(is_non_finite);
        prop_assert!(lattice.inverse(bad).is_err());
    }
}

/// `default` cases, or `PROPTEST_CASES` when set (for longer soaks).
fn cases_or_env(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}
