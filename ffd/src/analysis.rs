//! Jacobians, normal transformation, fold detection and inversion.

use alloc::vec::Vec;
use glam::{Mat3, Vec3, Vec3A};

use crate::bernstein::Basis;
use crate::error::FfdError;
use crate::lattice::{Lattice, MAX_DIVISIONS, OutsidePolicy, is_inside};

/// Determinants with an absolute value at or below this count as singular.
pub const SINGULAR_DETERMINANT: f32 = 1e-6;

/// What [`Lattice::fold_report`] found on its sample grid.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FoldReport {
    /// The smallest Jacobian determinant seen. 1 for an undeformed lattice; at or below 0 where
    /// the deformation folds space over itself (turns it inside out).
    pub min_determinant: f32,
    /// Local `(s, t, u)` of the sample with the smallest determinant.
    pub min_at: Vec3,
    /// The largest Jacobian determinant seen (a volume growth factor).
    pub max_determinant: f32,
    /// Samples taken: `samples_per_axis³`.
    pub samples: usize,
    /// Samples whose determinant is at or below 0.
    pub folded_samples: usize,
}

impl FoldReport {
    /// Whether any sample folded (determinant at or below 0).
    #[must_use]
    pub fn folds(&self) -> bool {
        self.folded_samples > 0
    }
}

/// Limits for [`Lattice::inverse_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct InverseOptions {
    /// Newton iterations at most. Default 32.
    pub max_iterations: u32,
    /// Accepted distance between the deformed guess and the target, as a fraction of the
    /// lattice's diagonal length. Default `1e-5`.
    pub tolerance: f32,
}

impl InverseOptions {
    /// The defaults: 32 iterations, tolerance `1e-5` of the lattice's diagonal.
    pub const DEFAULT: Self = Self {
        max_iterations: 32,
        tolerance: 1e-5,
    };

    /// Sets [`InverseOptions::max_iterations`].
    #[must_use]
    pub const fn with_max_iterations(mut self, max_iterations: u32) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// Sets [`InverseOptions::tolerance`].
    #[must_use]
    pub const fn with_tolerance(mut self, tolerance: f32) -> Self {
        self.tolerance = tolerance;
        self
    }
}

impl Default for InverseOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Most samples per axis [`Lattice::fold_report`] takes (so at most 256³ evaluations).
pub const MAX_FOLD_SAMPLES: usize = 256;

impl Lattice {
    /// The Jacobian `∂deform/∂p` at world point `p`: the identity for an undeformed lattice,
    /// outside the lattice under [`OutsidePolicy::Unchanged`], and at a non-finite `p` (which
    /// [`Lattice::deform`] passes through unchanged).
    ///
    /// ```
    /// use creature_ffd::{glam::{Mat3, Vec3}, Lattice};
    ///
    /// let mut lattice = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], [1, 1, 1])?;
    /// // Stretch the whole lattice 2x along x: move the four x = 1 corners.
    /// for j in 0..2 {
    ///     for k in 0..2 {
    ///         lattice.set_control_point([1, j, k], Vec3::new(2.0, j as f32, k as f32))?;
    ///     }
    /// }
    /// let j = lattice.jacobian(Vec3::splat(0.5));
    /// assert!(j.abs_diff_eq(Mat3::from_diagonal(Vec3::new(2.0, 1.0, 1.0)), 1e-6));
    /// # Ok::<(), creature_ffd::FfdError>(())
    /// ```
    #[must_use]
    pub fn jacobian(&self, p: Vec3) -> Mat3 {
        if !p.is_finite() {
            return Mat3::IDENTITY;
        }
        let local = self.local_coords(p);
        if self.outside_policy() == OutsidePolicy::Unchanged && !is_inside(local) {
            return Mat3::IDENTITY;
        }
        self.jacobian_local(local)
    }

    /// The Jacobian `∂deform/∂p` at local coordinates `(s, t, u)` (extrapolating outside).
    #[must_use]
    pub fn jacobian_local(&self, local: Vec3) -> Mat3 {
        if !self.is_deformed() {
            return Mat3::IDENTITY;
        }
        let [l, m, n] = self.divisions();
        let binomials = self.binomials();
        let mut b: [Basis; 3] = [[0.0; MAX_DIVISIONS + 1]; 3];
        let mut d: [Basis; 3] = [[0.0; MAX_DIVISIONS + 1]; 3];
        for (axis, x) in local.to_array().into_iter().enumerate() {
            binomials[axis].eval(x, &mut b[axis]);
            binomials[axis].eval_derivative(x, &mut d[axis]);
        }
        // Partial derivatives of the displacement with respect to s, t and u.
        let (mut ds, mut dt, mut du) = (Vec3A::ZERO, Vec3A::ZERO, Vec3A::ZERO);
        let offsets = self.offsets();
        let mut idx = 0;
        for k in 0..=n {
            for j in 0..=m {
                for i in 0..=l {
                    let o = offsets[idx];
                    idx += 1;
                    ds += o * (d[0][i] * b[1][j] * b[2][k]);
                    dt += o * (b[0][i] * d[1][j] * b[2][k]);
                    du += o * (b[0][i] * b[1][j] * d[2][k]);
                }
            }
        }
        let [gs, gt, gu] = *self.dual();
        // J = I + [∂D/∂s ∂D/∂t ∂D/∂u] · [∇s ∇t ∇u]ᵀ
        let partials = Mat3::from_cols(ds.into(), dt.into(), du.into());
        let gradients = Mat3::from_cols(gs.into(), gt.into(), gu.into()).transpose();
        Mat3::IDENTITY + partials * gradients
    }

    /// Transforms a surface normal at world point `p` by the inverse transpose of the Jacobian,
    /// and normalises it. A zero normal stays zero.
    ///
    /// # Errors
    /// [`FfdError::NonFinite`] for a non-finite `p` or `normal`,
    /// [`FfdError::SingularJacobian`] where the deformation crushes space (determinant within
    /// [`SINGULAR_DETERMINANT`] of 0), and [`FfdError::NonFiniteResult`] where the Jacobian
    /// itself overflows `f32` (a lattice stretched by more than about 1e38). A huge or tiny
    /// Jacobian or normal is otherwise fine: where `J⁻ᵀ · normal` or the determinant leaves the
    /// `f32` range, the product is redone in `f64`.
    ///
    /// ```
    /// use creature_ffd::{glam::Vec3, Lattice};
    ///
    /// let mut lattice = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], [1, 1, 1])?;
    /// for j in 0..2 {
    ///     for k in 0..2 {
    ///         lattice.set_control_point([1, j, k], Vec3::new(2.0, j as f32, k as f32))?;
    ///     }
    /// }
    /// // A 45° normal in the xy plane tilts towards y when x is stretched.
    /// let n = lattice.deform_normal(Vec3::splat(0.5), Vec3::new(1.0, 1.0, 0.0))?;
    /// assert!(n.y > n.x && n.is_normalized());
    /// # Ok::<(), creature_ffd::FfdError>(())
    /// ```
    pub fn deform_normal(&self, p: Vec3, normal: Vec3) -> Result<Vec3, FfdError> {
        if !p.is_finite() {
            return Err(FfdError::NonFinite {
                what: "point",
                index: None,
            });
        }
        if !normal.is_finite() {
            return Err(FfdError::NonFinite {
                what: "normal",
                index: None,
            });
        }
        let j = self.jacobian(p);
        if !j.is_finite() {
            return Err(FfdError::NonFiniteResult { index: 0 });
        }
        let determinant = j.determinant();
        if determinant.is_finite() {
            if !(crate::math::abs(determinant) > SINGULAR_DETERMINANT) {
                return Err(FfdError::SingularJacobian {
                    local: self.local_coords(p),
                    determinant,
                });
            }
            let n = crate::math::normalize_or(j.inverse().transpose() * normal, Vec3::ZERO);
            if n != Vec3::ZERO || normal == Vec3::ZERO {
                return Ok(n);
            }
        }
        // The determinant or the product left the f32 range (a huge Jacobian, a huge normal):
        // redo it in f64, where no product of finite f32 values overflows or underflows.
        cofactor_normal(j, normal).map_err(|determinant| FfdError::SingularJacobian {
            local: self.local_coords(p),
            determinant,
        })
    }

    /// Samples the Jacobian determinant on a `samples_per_axis³` grid spanning the lattice
    /// (corners included) and reports the smallest, where it is, and how many samples fold.
    ///
    /// `samples_per_axis` is clamped to `2..=MAX_FOLD_SAMPLES`. A grid catches folds at least as
    /// wide as its spacing; raise the count for a finer check.
    ///
    /// ```
    /// use creature_ffd::{glam::Vec3, Lattice};
    ///
    /// let mut lattice = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], [1, 1, 2])?;
    /// assert_eq!(lattice.fold_report(5).min_determinant, 1.0);
    /// // Push the middle slice past the last one: the body turns inside out.
    /// for i in 0..2 {
    ///     for j in 0..2 {
    ///         lattice.set_control_point([i, j, 1], Vec3::new(i as f32, j as f32, 2.0))?;
    ///     }
    /// }
    /// assert!(lattice.fold_report(5).folds());
    /// # Ok::<(), creature_ffd::FfdError>(())
    /// ```
    #[must_use]
    pub fn fold_report(&self, samples_per_axis: usize) -> FoldReport {
        let count = samples_per_axis.clamp(2, MAX_FOLD_SAMPLES);
        let step = 1.0 / (count - 1) as f32;
        let mut report = FoldReport {
            min_determinant: f32::INFINITY,
            min_at: Vec3::ZERO,
            max_determinant: f32::NEG_INFINITY,
            samples: count * count * count,
            folded_samples: 0,
        };
        let mut offer = |det: f32, local: Vec3| {
            // NaN cannot arise from finite control points; count it as folded anyway.
            if !(det > 0.0) {
                report.folded_samples += 1;
            }
            if !(det >= report.min_determinant) {
                report.min_determinant = det;
                report.min_at = local;
            }
            if det > report.max_determinant {
                report.max_determinant = det;
            }
        };
        if !self.is_deformed() {
            for a in 0..count {
                for b in 0..count {
                    for c in 0..count {
                        offer(1.0, Vec3::new(a as f32, b as f32, c as f32) * step);
                    }
                }
            }
            return report;
        }
        // The grid is a tensor product, so the Jacobian's partial derivatives are contracted
        // one axis at a time: over `i` once per `a`, over `j` once per `(a, b)`, over `k` per
        // sample (the Bernstein values per axis and sample computed once).
        let [l, m, n] = self.divisions();
        let (ni, nj, nk) = (l + 1, m + 1, n + 1);
        let binomials = self.binomials();
        let tables = |axis: usize, len: usize| {
            let mut values = Vec::with_capacity(count * len);
            let mut slopes = Vec::with_capacity(count * len);
            let (mut b, mut d): (Basis, Basis) =
                ([0.0; MAX_DIVISIONS + 1], [0.0; MAX_DIVISIONS + 1]);
            for a in 0..count {
                let x = a as f32 * step;
                binomials[axis].eval(x, &mut b);
                binomials[axis].eval_derivative(x, &mut d);
                values.extend_from_slice(&b[..len]);
                slopes.extend_from_slice(&d[..len]);
            }
            (values, slopes)
        };
        let (b0, d0) = tables(0, ni);
        let (b1, d1) = tables(1, nj);
        let (b2, d2) = tables(2, nk);
        let offsets = self.offsets();
        let [gs, gt, gu] = *self.dual();
        let gradients = Mat3::from_cols(gs.into(), gt.into(), gu.into()).transpose();
        // Per (j, k): the offsets contracted over i with the s-derivative (`p`) and the values
        // (`q`); per k: those contracted over j (`ps` for ∂/∂s, `qt` for ∂/∂t, `qu` for ∂/∂u).
        let mut p = alloc::vec![Vec3A::ZERO; nj * nk];
        let mut q = alloc::vec![Vec3A::ZERO; nj * nk];
        let (mut ps, mut qt, mut qu) = (
            alloc::vec![Vec3A::ZERO; nk],
            alloc::vec![Vec3A::ZERO; nk],
            alloc::vec![Vec3A::ZERO; nk],
        );
        for a in 0..count {
            let (bs, ds) = (&b0[a * ni..][..ni], &d0[a * ni..][..ni]);
            for ((row, pr), qr) in offsets.chunks_exact(ni).zip(&mut p).zip(&mut q) {
                let (mut x, mut y) = (Vec3A::ZERO, Vec3A::ZERO);
                for ((&o, &d), &b) in row.iter().zip(ds).zip(bs) {
                    x += o * d;
                    y += o * b;
                }
                *pr = x;
                *qr = y;
            }
            for b in 0..count {
                let (bt, dt) = (&b1[b * nj..][..nj], &d1[b * nj..][..nj]);
                for k in 0..nk {
                    let (pk, qk) = (&p[k * nj..][..nj], &q[k * nj..][..nj]);
                    let (mut x, mut y, mut z) = (Vec3A::ZERO, Vec3A::ZERO, Vec3A::ZERO);
                    for j in 0..nj {
                        x += pk[j] * bt[j];
                        y += qk[j] * dt[j];
                        z += qk[j] * bt[j];
                    }
                    ps[k] = x;
                    qt[k] = y;
                    qu[k] = z;
                }
                for c in 0..count {
                    let (bu, du) = (&b2[c * nk..][..nk], &d2[c * nk..][..nk]);
                    let (mut x, mut y, mut z) = (Vec3A::ZERO, Vec3A::ZERO, Vec3A::ZERO);
                    for k in 0..nk {
                        x += ps[k] * bu[k];
                        y += qt[k] * bu[k];
                        z += qu[k] * du[k];
                    }
                    let partials = Mat3::from_cols(x.into(), y.into(), z.into());
                    let det = (Mat3::IDENTITY + partials * gradients).determinant();
                    offer(det, Vec3::new(a as f32, b as f32, c as f32) * step);
                }
            }
        }
        report
    }

    /// Whether the deformation folds over anywhere on a `samples_per_axis³` grid: shorthand for
    /// `self.fold_report(samples_per_axis).folds()`.
    #[must_use]
    pub fn folds(&self, samples_per_axis: usize) -> bool {
        self.fold_report(samples_per_axis).folds()
    }

    /// The undeformed point that [`Lattice::deform`] maps to `q`, by damped Newton iteration
    /// with the default [`InverseOptions`].
    ///
    /// # Errors
    /// See [`Lattice::inverse_with`].
    ///
    /// ```
    /// use creature_ffd::{glam::Vec3, Lattice};
    ///
    /// let mut lattice = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], [2, 2, 2])?;
    /// lattice.set_control_point([1, 1, 1], Vec3::new(0.6, 0.55, 0.5))?;
    /// let p = Vec3::new(0.3, 0.4, 0.7);
    /// let back = lattice.inverse(lattice.deform(p))?;
    /// assert!(back.distance(p) < 1e-4);
    /// # Ok::<(), creature_ffd::FfdError>(())
    /// ```
    pub fn inverse(&self, q: Vec3) -> Result<Vec3, FfdError> {
        self.inverse_with(q, &InverseOptions::DEFAULT)
    }

    /// [`Lattice::inverse`] with explicit limits.
    ///
    /// # Errors
    /// [`FfdError::NonFinite`] for a non-finite `q` or tolerance, [`FfdError::SingularJacobian`]
    /// when an iterate lands where the deformation is crushed, and [`FfdError::NoConvergence`]
    /// with the best residual when the limit is reached (a `q` outside the deformed lattice's
    /// reach, or a folded lattice with several preimages).
    pub fn inverse_with(&self, q: Vec3, options: &InverseOptions) -> Result<Vec3, FfdError> {
        if !q.is_finite() {
            return Err(FfdError::NonFinite {
                what: "point",
                index: None,
            });
        }
        if !options.tolerance.is_finite() {
            return Err(FfdError::NonFinite {
                what: "tolerance",
                index: None,
            });
        }
        if !self.is_deformed() {
            return Ok(q);
        }
        let [s, t, u] = self.axes();
        let tolerance = options.tolerance * (s + t + u).length();
        let mut p = q;
        let mut residual = self.deform(p) - q;
        let mut error = residual.length();
        for iteration in 0..options.max_iterations {
            if error <= tolerance {
                return Ok(p);
            }
            let j = self.jacobian(p);
            let determinant = j.determinant();
            if !(crate::math::abs(determinant) > SINGULAR_DETERMINANT) {
                return Err(FfdError::SingularJacobian {
                    local: self.local_coords(p),
                    determinant,
                });
            }
            let step = j.inverse() * residual;
            // Backtrack until the residual shrinks (at most 10 halvings).
            let mut scale = 1.0;
            let mut improved = false;
            for _ in 0..10 {
                let candidate = p - step * scale;
                let r = self.deform(candidate) - q;
                let e = r.length();
                if e < error {
                    p = candidate;
                    residual = r;
                    error = e;
                    improved = true;
                    break;
                }
                scale *= 0.5;
            }
            if !improved {
                return Err(FfdError::NoConvergence {
                    target: q,
                    residual: error,
                    iterations: iteration + 1,
                });
            }
        }
        if error <= tolerance {
            Ok(p)
        } else {
            Err(FfdError::NoConvergence {
                target: q,
                residual: error,
                iterations: options.max_iterations,
            })
        }
    }
}

/// `J⁻ᵀ · normal`, normalised, computed in `f64` as `sign(det J) · cof(J) · normal` (the
/// cofactor matrix is `det J · J⁻ᵀ`): for a finite `J` and `normal` every product stays within
/// `f64`'s normal range. A zero `normal` gives zero.
///
/// # Errors
/// The `f64` determinant, as `f32`, where it is within [`SINGULAR_DETERMINANT`] of 0 or the
/// product cancels to zero.
fn cofactor_normal(j: Mat3, normal: Vec3) -> Result<Vec3, f32> {
    type D3 = [f64; 3];
    fn d3(v: Vec3) -> D3 {
        [f64::from(v.x), f64::from(v.y), f64::from(v.z)]
    }
    fn cross(a: D3, b: D3) -> D3 {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    let (a, b, c) = (d3(j.x_axis), d3(j.y_axis), d3(j.z_axis));
    let (bc, ca, ab) = (cross(b, c), cross(c, a), cross(a, b));
    let determinant = a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2];
    if !(determinant.abs() > f64::from(SINGULAR_DETERMINANT)) {
        return Err(determinant as f32);
    }
    if normal == Vec3::ZERO {
        return Ok(Vec3::ZERO);
    }
    let n = d3(normal);
    let sign = determinant.signum();
    let v: D3 = core::array::from_fn(|i| sign * (bc[i] * n[0] + ca[i] * n[1] + ab[i] * n[2]));
    // Divided by its largest component, `v` converts to `f32` without overflow, and the
    // largest component (±1) survives it.
    let largest = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(largest > 0.0) {
        return Err(determinant as f32);
    }
    let unit_max = Vec3::new(
        (v[0] / largest) as f32,
        (v[1] / largest) as f32,
        (v[2] / largest) as f32,
    );
    Ok(unit_max.normalize_or(Vec3::ZERO))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit(divisions: [usize; 3]) -> Lattice {
        Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], divisions).unwrap()
    }

    fn bent() -> Lattice {
        let mut lattice = unit([2, 2, 3]);
        lattice
            .set_control_point([1, 1, 1], Vec3::new(0.6, 0.5, 0.35))
            .unwrap();
        lattice
            .set_control_point([2, 2, 3], Vec3::new(1.2, 1.1, 1.0))
            .unwrap();
        lattice
    }

    #[test]
    fn fold_report_agrees_with_the_jacobian_at_every_sample() {
        // The report contracts the grid one axis at a time; `jacobian_local` sums every
        // control point at each sample. Both on a bent, folded and sheared lattice.
        let mut folded = bent();
        folded
            .set_control_point([1, 1, 2], Vec3::new(0.4, 0.6, 1.4))
            .unwrap();
        let mut sheared = Lattice::new(
            Vec3::ONE,
            [Vec3::new(2.0, 0.3, 0.0), Vec3::Y, Vec3::Z],
            [3, 1, 4],
        )
        .unwrap();
        sheared
            .set_control_point([1, 0, 2], Vec3::new(2.0, 0.2, 1.0))
            .unwrap();
        for lattice in [bent(), folded, sheared] {
            for count in [2, 5, 8] {
                let report = lattice.fold_report(count);
                let step = 1.0 / (count - 1) as f32;
                let (mut min, mut max, mut folded) = (f32::INFINITY, f32::NEG_INFINITY, 0);
                for a in 0..count {
                    for b in 0..count {
                        for c in 0..count {
                            let local = Vec3::new(a as f32, b as f32, c as f32) * step;
                            let det = lattice.jacobian_local(local).determinant();
                            min = min.min(det);
                            max = max.max(det);
                            folded += usize::from(!(det > 0.0));
                        }
                    }
                }
                let close = |x: f32, y: f32| (x - y).abs() <= 1e-5 * (1.0 + x.abs());
                assert!(close(report.min_determinant, min), "{report:?} vs {min}");
                assert!(close(report.max_determinant, max), "{report:?} vs {max}");
                assert_eq!(report.folded_samples, folded, "{report:?}");
                assert!(close(
                    lattice.jacobian_local(report.min_at).determinant(),
                    report.min_determinant
                ));
            }
        }
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let lattice = bent();
        let p = Vec3::new(0.3, 0.6, 0.45);
        let j = lattice.jacobian(p);
        let h = 1e-3;
        for (axis, e) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().enumerate() {
            let numeric = (lattice.deform(p + e * h) - lattice.deform(p - e * h)) / (2.0 * h);
            let analytic = j.col(axis);
            assert!(
                numeric.abs_diff_eq(analytic, 5e-3),
                "axis {axis}: {numeric} vs {analytic}"
            );
        }
    }

    #[test]
    fn jacobian_on_a_sheared_frame_matches_finite_differences() {
        let axes = [
            Vec3::new(2.0, 0.3, 0.0),
            Vec3::new(-0.4, 1.5, 0.2),
            Vec3::new(0.1, 0.2, 3.0),
        ];
        let mut lattice = Lattice::new(Vec3::new(1.0, -2.0, 0.5), axes, [2, 3, 2]).unwrap();
        let p = lattice.control_point([1, 2, 1]).unwrap();
        lattice
            .set_control_point([1, 2, 1], p + Vec3::new(0.3, -0.2, 0.4))
            .unwrap();
        let x = lattice.world_coords(Vec3::new(0.4, 0.5, 0.6));
        let j = lattice.jacobian(x);
        let h = 1e-3;
        for (axis, e) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().enumerate() {
            let numeric = (lattice.deform(x + e * h) - lattice.deform(x - e * h)) / (2.0 * h);
            assert!(numeric.abs_diff_eq(j.col(axis), 5e-3), "axis {axis}");
        }
    }

    #[test]
    fn undeformed_lattice_has_identity_jacobian_and_no_folds() {
        let lattice = unit([2, 2, 10]);
        assert_eq!(lattice.jacobian(Vec3::splat(0.5)), Mat3::IDENTITY);
        let report = lattice.fold_report(4);
        assert_eq!(report.min_determinant, 1.0);
        assert_eq!(report.samples, 64);
        assert!(!report.folds());
    }

    #[test]
    fn fold_samples_are_clamped() {
        let lattice = unit([1, 1, 1]);
        assert_eq!(lattice.fold_report(0).samples, 8);
        assert_eq!(
            lattice.fold_report(usize::MAX).samples,
            MAX_FOLD_SAMPLES.pow(3)
        );
    }

    #[test]
    fn crushed_lattice_gives_a_singular_jacobian_error() {
        let mut lattice = unit([1, 1, 1]);
        // Flatten the whole lattice onto z = 0.
        for i in 0..2 {
            for j in 0..2 {
                lattice
                    .set_control_point([i, j, 1], Vec3::new(i as f32, j as f32, 0.0))
                    .unwrap();
            }
        }
        assert!(matches!(
            lattice.deform_normal(Vec3::splat(0.5), Vec3::Z),
            Err(FfdError::SingularJacobian { .. })
        ));
        assert!(lattice.folds(3));
    }

    #[test]
    fn normal_of_undeformed_lattice_is_unchanged() {
        let lattice = unit([2, 2, 2]);
        let n = Vec3::new(0.0, 0.6, 0.8);
        assert_eq!(lattice.deform_normal(Vec3::splat(0.2), n), Ok(n));
        assert!(lattice.deform_normal(Vec3::NAN, n).is_err());
        assert!(lattice.deform_normal(Vec3::ZERO, Vec3::NAN).is_err());
    }

    #[test]
    fn inverse_round_trips_a_bent_lattice() {
        let lattice = bent();
        for p in [
            Vec3::new(0.1, 0.2, 0.3),
            Vec3::new(0.9, 0.8, 0.7),
            Vec3::new(0.5, 0.5, 0.5),
            Vec3::ZERO,
        ] {
            let q = lattice.deform(p);
            let back = lattice.inverse(q).unwrap();
            assert!(back.distance(p) < 1e-4, "{p} -> {q} -> {back}");
        }
    }

    #[test]
    fn inverse_reports_non_convergence() {
        let lattice = bent();
        let options = InverseOptions::DEFAULT.with_max_iterations(0);
        assert!(matches!(
            lattice.inverse_with(Vec3::splat(0.5), &options),
            Err(FfdError::NoConvergence { iterations: 0, .. })
        ));
        assert!(lattice.inverse(Vec3::NAN).is_err());
        let nan_tolerance = InverseOptions::DEFAULT.with_tolerance(f32::NAN);
        assert!(lattice.inverse_with(Vec3::ZERO, &nan_tolerance).is_err());
    }

    #[test]
    fn inverse_of_undeformed_is_exact() {
        let lattice = unit([2, 2, 10]);
        let q = Vec3::new(0.123, 4.5, -6.0);
        assert_eq!(lattice.inverse(q), Ok(q));
    }

    /// Fuzz finding (`fuzz/corpus/ffd/new-deform-normal-zero-for-nonzero-normal`): a large
    /// normal times `J⁻ᵀ` overflowed `J⁻ᵀ · normal` to infinity, and the normalisation fell
    /// back to a zero vector. (The fuzz input moved a slice by 5.8e35, which `MAX_COORDINATE`
    /// now refuses; the same overflow, within it: a unit cube shrunk to half, `J⁻ᵀ = 2 I`,
    /// and a normal near `f32::MAX`.)
    #[test]
    fn regression_deform_normal_unit_when_the_product_overflows() {
        let lattice = stretched(1.0, 0.5);
        let p = Vec3::splat(0.25);
        let normal = Vec3::new(-3.0e38, 6.011_865_6e-16, 1.0e38);
        assert!(!(lattice.jacobian(p).inverse().transpose() * normal).is_finite());
        let n = lattice.deform_normal(p, normal).unwrap();
        assert!(n.is_normalized(), "{n}");
        // The same direction as for the normal scaled into range (exact: a power of two).
        let scaled = lattice.deform_normal(p, normal * 2f32.powi(-70)).unwrap();
        assert!(n.abs_diff_eq(scaled, 1e-6), "{n} vs {scaled}");
    }

    /// A lattice `size` wide whose control points are moved onto the cube `to` wide:
    /// `J = I · to / size`.
    fn stretched(size: f32, to: f32) -> Lattice {
        let mut lattice = Lattice::new(
            Vec3::ZERO,
            [Vec3::X * size, Vec3::Y * size, Vec3::Z * size],
            [1, 1, 1],
        )
        .unwrap();
        for i in 0..2 {
            for j in 0..2 {
                for k in 0..2 {
                    let index = [i, j, k];
                    lattice
                        .set_control_point(index, Vec3::from(index.map(|x| x as f32 * to)))
                        .unwrap();
                }
            }
        }
        lattice
    }

    /// The same bug through the determinant: a lattice 1e-13 wide stretched to a unit cube has
    /// `J = 1e13 · I`, whose `f32` determinant (1e39) overflows, so `J⁻¹` came out zero.
    #[test]
    fn regression_deform_normal_unit_when_the_determinant_overflows() {
        let size = 1e-13;
        let lattice = stretched(size, 1.0);
        let p = Vec3::splat(0.5 * size);
        assert!(lattice.jacobian(p).determinant().is_infinite());
        let n = lattice.deform_normal(p, Vec3::new(1.0, 2.0, 2.0)).unwrap();
        assert!(n.abs_diff_eq(Vec3::new(1.0, 2.0, 2.0) / 3.0, 1e-6), "{n}");
    }

    /// Stretched 1e40 times, the Jacobian itself would overflow `f32` (`deform_normal` then
    /// reports `NonFiniteResult`), but `MAX_COORDINATE` keeps every reachable Jacobian finite:
    /// the thinnest frame `new` accepts (an axis 1.1e-19 long, whose squared length is still
    /// a normal `f32`) with its control points 2e15 apart gives `J ≈ 1.8e34`, and a unit
    /// normal.
    #[test]
    fn deform_normal_unit_at_the_largest_jacobian_within_max_coordinate() {
        let size = 1.1e-19;
        let mut lattice =
            Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z * size], [1, 1, 1]).unwrap();
        lattice
            .translate_slice(crate::Axis::U, 0, Vec3::Z * -1e15)
            .unwrap();
        lattice
            .translate_slice(crate::Axis::U, 1, Vec3::Z * 1e15)
            .unwrap();
        let p = Vec3::new(0.5, 0.5, 0.5 * size);
        assert!(lattice.jacobian(p).is_finite());
        let n = lattice.deform_normal(p, Vec3::new(1.0, 0.0, 1.0)).unwrap();
        assert!(n.is_normalized(), "{n}");
        assert!(Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z * 1e-25], [1, 1, 1]).is_err());
    }
}
