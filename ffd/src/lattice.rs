//! The lattice type: construction, control points and deformation.

use alloc::vec::Vec;

use glam::{Vec3, Vec3A};

use crate::bernstein::Binomials;
use crate::error::FfdError;
use crate::math;

/// The largest number of divisions along one axis (the Bernstein degree).
///
/// Bases of higher degree lose most of their precision in `f32`, and no body needs them.
pub const MAX_DIVISIONS: usize = 32;

/// Layers of at most this many control points take the precomputed-weights path.
const SMALL_LAYER: usize = 9;

/// Lattices with at most this many slices along U (and small layers) take the fast path.
const SMALL_DEPTH: usize = 16;

/// Smallest accepted `|S · (T × U)| / (|S| |T| |U|)`: below it the lattice counts as flat.
pub const MIN_VOLUME_RATIO: f32 = 1e-6;

/// The largest magnitude of any coordinate of a lattice corner or control point.
///
/// With every grid and control point within `±1e15`, a control point's offset from its grid
/// position is at most `2e15` per coordinate, and the Bernstein sum inside the lattice (weights
/// in `[0, 1]` summing to 1) keeps every deformed point within about `3e15`: far from `f32`'s
/// range, so [`Lattice::deform`] is finite everywhere inside. Closer to `f32::MAX` the offsets
/// and their sums overflowed (regression: a slice moved to `−f32::MAX` gave NaN inside, where
/// its weight is 0). The same bound as `creature-skin`'s and `creature-autorig`'s.
pub const MAX_COORDINATE: f32 = 1.0e15;

/// What [`Lattice::deform`] does with a point whose local `(s, t, u)` lies outside `[0, 1]^3`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum OutsidePolicy {
    /// Evaluate the Bernstein polynomial anyway (Sederberg and Parry's definition). The
    /// deformation stays smooth across the lattice's faces, but grows polynomially with distance:
    /// a point far outside can overflow (see [`Lattice::try_deform`]).
    #[default]
    Extrapolate,
    /// Return outside points unchanged. Points inside still deform; if boundary control points
    /// moved, the result jumps at the lattice's faces.
    Unchanged,
}

/// One of the lattice's three edge directions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Axis {
    /// The first edge vector, S, indexed by `i`, local coordinate `s`.
    S,
    /// The second edge vector, T, indexed by `j`, local coordinate `t`.
    T,
    /// The third edge vector, U, indexed by `k`, local coordinate `u`.
    U,
}

impl Axis {
    /// The three axes in order S, T, U.
    pub const ALL: [Axis; 3] = [Axis::S, Axis::T, Axis::U];

    /// 0 for S, 1 for T, 2 for U: the position in `[i, j, k]`, `divisions` and `axes`.
    #[must_use]
    #[inline]
    pub const fn index(self) -> usize {
        match self {
            Axis::S => 0,
            Axis::T => 1,
            Axis::U => 2,
        }
    }
}

/// A Sederberg–Parry free-form deformation lattice.
///
/// The lattice spans the parallelepiped `origin + s S + t T + u U` for `s, t, u` in `[0, 1]`,
/// split into `divisions = [l, m, n]` cells per axis, with `(l+1)(m+1)(n+1)` control points that
/// start on the grid `origin + i/l S + j/m T + k/n U`. Moving control points deforms space: a
/// point with local coordinates `(s, t, u)` goes to the trivariate Bernstein sum
/// `Σ B_i^l(s) B_j^m(t) B_k^n(u) P_ijk`.
///
/// The sum is evaluated as `p + Σ B (P_ijk − grid_ijk)`, which is the same polynomial (Bernstein
/// bases reproduce linear functions) but makes an undeformed lattice the identity bit for bit and
/// keeps rounding error proportional to the deformation, not to the coordinates.
///
/// ```
/// use creature_ffd::{glam::Vec3, Lattice};
///
/// let mut lattice = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], [1, 1, 1])?;
/// // Pull the top-right-front corner outwards.
/// lattice.set_control_point([1, 1, 1], Vec3::splat(2.0))?;
/// let moved = lattice.deform(Vec3::splat(0.5));
/// assert!(moved.x > 0.5);
/// // Corners go exactly where their control points are.
/// assert_eq!(lattice.deform(Vec3::ZERO), Vec3::ZERO);
/// # Ok::<(), creature_ffd::FfdError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Lattice {
    origin: Vec3,
    axes: [Vec3; 3],
    divisions: [usize; 3],
    /// Rows of the inverse frame: `dual[a] · (p - origin)` is local coordinate `a`.
    dual: [Vec3A; 3],
    binomials: [Binomials; 3],
    /// Control points as set, in storage order (`i` fastest, then `j`, then `k`).
    points: Vec<Vec3>,
    /// `points[idx] - grid(idx)`, what the Bernstein sum actually weighs.
    offsets: Vec<Vec3A>,
    outside: OutsidePolicy,
    /// False while every offset is known to be zero: deformation is then the identity.
    deformed: bool,
}

impl Lattice {
    /// A lattice with corner `origin`, edge vectors `axes = [S, T, U]` (any parallelepiped, not
    /// only axis-aligned) and `divisions = [l, m, n]`, its control points on the undeformed grid.
    ///
    /// # Errors
    /// [`FfdError::NonFinite`] for a NaN or infinite origin or axis,
    /// [`FfdError::ZeroDivisions`] / [`FfdError::TooManyDivisions`] for divisions outside
    /// `1..=MAX_DIVISIONS`, [`FfdError::DegenerateAxes`] when the axes span (almost) no
    /// volume (see [`MIN_VOLUME_RATIO`]), and [`FfdError::CoordinateTooLarge`] when a corner of
    /// the lattice lies beyond ±[`MAX_COORDINATE`].
    ///
    /// ```
    /// use creature_ffd::{glam::Vec3, FfdError, Lattice};
    ///
    /// // A sheared lattice is fine...
    /// let lattice = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::new(0.5, 1.0, 0.0), Vec3::Z], [2, 2, 10])?;
    /// assert_eq!(lattice.control_point_count(), 3 * 3 * 11);
    /// // ...a flat one is not.
    /// let flat = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::X + Vec3::Y], [1, 1, 1]);
    /// assert!(matches!(flat, Err(FfdError::DegenerateAxes { .. })));
    /// # Ok::<(), FfdError>(())
    /// ```
    pub fn new(origin: Vec3, axes: [Vec3; 3], divisions: [usize; 3]) -> Result<Self, FfdError> {
        if !origin.is_finite() {
            return Err(FfdError::NonFinite {
                what: "origin",
                index: None,
            });
        }
        for (index, axis) in axes.iter().enumerate() {
            if !axis.is_finite() {
                return Err(FfdError::NonFinite {
                    what: "axis",
                    index: Some(index),
                });
            }
        }
        for (axis, &d) in divisions.iter().enumerate() {
            if d == 0 {
                return Err(FfdError::ZeroDivisions { axis });
            }
            if d > MAX_DIVISIONS {
                return Err(FfdError::TooManyDivisions {
                    axis,
                    divisions: d,
                    max: MAX_DIVISIONS,
                });
            }
        }
        let [s, t, u] = axes;
        let volume = s.dot(t.cross(u));
        let lengths = s.length() * t.length() * u.length();
        let volume_ratio = if lengths > 0.0 && lengths.is_finite() {
            math::abs(volume) / lengths
        } else {
            0.0
        };
        if !(volume_ratio >= MIN_VOLUME_RATIO) || !volume.is_finite() {
            return Err(FfdError::DegenerateAxes { volume_ratio });
        }
        // Every grid point is a convex combination of the corners.
        for corner in 0..8 {
            let mut p = origin;
            for (a, axis) in axes.iter().enumerate() {
                if corner & (1 << a) != 0 {
                    p += *axis;
                }
            }
            check_coordinates("lattice corner", corner, p)?;
        }
        let tu = t.cross(u);
        let us = u.cross(s);
        let st = s.cross(t);
        let dual = [
            Vec3A::from(tu / tu.dot(s)),
            Vec3A::from(us / us.dot(t)),
            Vec3A::from(st / st.dot(u)),
        ];
        // Axes so short that their products are subnormal pass the ratio above on rounding
        // noise, but their dual basis overflows.
        if !dual.iter().all(|d| d.is_finite()) {
            return Err(FfdError::DegenerateAxes { volume_ratio });
        }
        let [l, m, n] = divisions;
        let count = (l + 1) * (m + 1) * (n + 1);
        let mut lattice = Self {
            origin,
            axes,
            divisions,
            dual,
            binomials: [Binomials::new(l), Binomials::new(m), Binomials::new(n)],
            points: Vec::with_capacity(count),
            offsets: alloc::vec![Vec3A::ZERO; count],
            outside: OutsidePolicy::default(),
            deformed: false,
        };
        for k in 0..=n {
            for j in 0..=m {
                for i in 0..=l {
                    let p = lattice.grid([i, j, k]);
                    lattice.points.push(p);
                }
            }
        }
        Ok(lattice)
    }

    /// The axis-aligned lattice enclosing `points`, grown by `padding` (world units) on every
    /// side. A flat point set (all in one plane) needs `padding > 0`.
    ///
    /// # Errors
    /// [`FfdError::NoPoints`] for an empty slice, [`FfdError::NonFinite`] naming the first
    /// non-finite point, [`FfdError::InvalidPadding`] for a negative or non-finite padding,
    /// [`FfdError::TooLarge`] when the padded box overflows `f32`, and the
    /// errors of [`Lattice::new`] (a flat box is [`FfdError::DegenerateAxes`]).
    ///
    /// ```
    /// use creature_ffd::{glam::Vec3, Lattice};
    ///
    /// let body = [Vec3::new(-1.0, 0.0, -3.0), Vec3::new(1.0, 2.0, 3.0)];
    /// let lattice = Lattice::around(&body, [2, 2, 10], 0.1)?;
    /// assert_eq!(lattice.origin(), Vec3::new(-1.1, -0.1, -3.1));
    /// # Ok::<(), creature_ffd::FfdError>(())
    /// ```
    pub fn around(points: &[Vec3], divisions: [usize; 3], padding: f32) -> Result<Self, FfdError> {
        if !(padding >= 0.0) || !padding.is_finite() {
            return Err(FfdError::InvalidPadding { value: padding });
        }
        let (min, max) = bounds(points)?;
        let min = min - Vec3::splat(padding);
        let extent = max + Vec3::splat(padding) - min;
        if !min.is_finite() || !extent.is_finite() {
            return Err(FfdError::TooLarge);
        }
        Self::new(
            min,
            [
                Vec3::new(extent.x, 0.0, 0.0),
                Vec3::new(0.0, extent.y, 0.0),
                Vec3::new(0.0, 0.0, extent.z),
            ],
            divisions,
        )
    }

    /// The same lattice with another policy for points outside it.
    #[must_use]
    pub fn with_outside_policy(mut self, policy: OutsidePolicy) -> Self {
        self.outside = policy;
        self
    }

    /// Sets the policy for points outside the lattice.
    pub fn set_outside_policy(&mut self, policy: OutsidePolicy) {
        self.outside = policy;
    }

    /// The policy for points outside the lattice ([`OutsidePolicy::Extrapolate`] by default).
    #[must_use]
    pub fn outside_policy(&self) -> OutsidePolicy {
        self.outside
    }

    /// The lattice's corner `P0`.
    #[must_use]
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// The edge vectors `[S, T, U]`.
    #[must_use]
    pub fn axes(&self) -> [Vec3; 3] {
        self.axes
    }

    /// The divisions `[l, m, n]`; control point indices run from 0 to these, inclusive.
    #[must_use]
    pub fn divisions(&self) -> [usize; 3] {
        self.divisions
    }

    /// Number of control points, `(l+1)(m+1)(n+1)`.
    #[must_use]
    pub fn control_point_count(&self) -> usize {
        self.points.len()
    }

    /// Storage position of control point `[i, j, k]` in [`Lattice::control_points`]
    /// (`i` fastest, then `j`, then `k`), or `None` when out of range.
    #[must_use]
    pub fn index_of(&self, [i, j, k]: [usize; 3]) -> Option<usize> {
        let [l, m, n] = self.divisions;
        (i <= l && j <= m && k <= n).then(|| (k * (m + 1) + j) * (l + 1) + i)
    }

    /// Control point `[i, j, k]`, or `None` when the index is out of range.
    #[must_use]
    pub fn control_point(&self, index: [usize; 3]) -> Option<Vec3> {
        self.index_of(index).map(|idx| self.points[idx])
    }

    /// Where control point `[i, j, k]` sits on the undeformed grid, or `None` when out of range.
    #[must_use]
    pub fn grid_point(&self, index: [usize; 3]) -> Option<Vec3> {
        self.index_of(index).map(|_| self.grid(index))
    }

    /// All control points in storage order (see [`Lattice::index_of`]).
    #[must_use]
    pub fn control_points(&self) -> &[Vec3] {
        &self.points
    }

    /// Moves control point `[i, j, k]` to `p`.
    ///
    /// # Errors
    /// [`FfdError::IndexOutOfRange`] for an index past the divisions, [`FfdError::NonFinite`]
    /// for a NaN or infinite `p` and [`FfdError::CoordinateTooLarge`] for a coordinate beyond
    /// ±[`MAX_COORDINATE`]; the lattice is unchanged then.
    pub fn set_control_point(&mut self, index: [usize; 3], p: Vec3) -> Result<(), FfdError> {
        let idx = self.index_of(index).ok_or(FfdError::IndexOutOfRange {
            index,
            divisions: self.divisions,
        })?;
        if !p.is_finite() {
            return Err(FfdError::NonFinite {
                what: "control point",
                index: Some(idx),
            });
        }
        check_coordinates("control point", idx, p)?;
        self.write(idx, index, p);
        Ok(())
    }

    /// Puts every control point back on the undeformed grid.
    pub fn reset(&mut self) {
        let [l, m, n] = self.divisions;
        for k in 0..=n {
            for j in 0..=m {
                for i in 0..=l {
                    let idx = (k * (m + 1) + j) * (l + 1) + i;
                    self.points[idx] = self.grid([i, j, k]);
                    self.offsets[idx] = Vec3A::ZERO;
                }
            }
        }
        self.deformed = false;
    }

    /// Whether any control point has been moved since construction or [`Lattice::reset`].
    #[must_use]
    pub fn is_deformed(&self) -> bool {
        self.deformed
    }

    /// Local coordinates `(s, t, u)` of `p` by the cross-product formulas, e.g.
    /// `s = (T × U) · (p − P0) / ((T × U) · S)`. Inside the lattice each lies in `[0, 1]`.
    ///
    /// ```
    /// use creature_ffd::{glam::Vec3, Lattice};
    ///
    /// let lattice = Lattice::new(Vec3::ONE, [Vec3::X * 2.0, Vec3::Y * 4.0, Vec3::Z], [1, 1, 1])?;
    /// assert_eq!(lattice.local_coords(Vec3::new(2.0, 2.0, 1.5)), Vec3::new(0.5, 0.25, 0.5));
    /// # Ok::<(), creature_ffd::FfdError>(())
    /// ```
    #[must_use]
    #[inline]
    pub fn local_coords(&self, p: Vec3) -> Vec3 {
        let d = Vec3A::from(p - self.origin);
        Vec3::new(
            self.dual[0].dot(d),
            self.dual[1].dot(d),
            self.dual[2].dot(d),
        )
    }

    /// The undeformed world position of local coordinates `(s, t, u)`.
    #[must_use]
    #[inline]
    pub fn world_coords(&self, local: Vec3) -> Vec3 {
        self.origin + self.axes[0] * local.x + self.axes[1] * local.y + self.axes[2] * local.z
    }

    /// Whether `p`'s local coordinates all lie in `[0, 1]`.
    #[must_use]
    pub fn contains(&self, p: Vec3) -> bool {
        is_inside(self.local_coords(p))
    }

    /// The deformed position of `p`: the trivariate Bernstein sum over the control points.
    ///
    /// Points outside the lattice follow the [`OutsidePolicy`]. An undeformed lattice returns
    /// `p` exactly. A non-finite `p` is returned unchanged. Inside the lattice the result is
    /// always finite (control points are kept within ±[`MAX_COORDINATE`]). With
    /// [`OutsidePolicy::Extrapolate`], a
    /// point so far outside that the Bernstein polynomial overflows `f32` (local coordinates
    /// beyond roughly ±10^(38/degree)) comes back non-finite (NaN or infinite): use
    /// [`Lattice::try_deform`] to have both cases reported as errors, or
    /// [`OutsidePolicy::Unchanged`].
    #[must_use]
    #[inline]
    pub fn deform(&self, p: Vec3) -> Vec3 {
        if !self.deformed {
            return p;
        }
        match self.local_if_moved(p) {
            Some(local) => Vec3::from(Vec3A::from(p) + self.displacement(local)),
            None => p,
        }
    }

    /// [`Lattice::deform`] that rejects a non-finite `p` and a non-finite result.
    ///
    /// # Errors
    /// [`FfdError::NonFinite`] for a NaN or infinite `p`, [`FfdError::NonFiniteResult`] when the
    /// deformed point overflows.
    pub fn try_deform(&self, p: Vec3) -> Result<Vec3, FfdError> {
        if !p.is_finite() {
            return Err(FfdError::NonFinite {
                what: "point",
                index: None,
            });
        }
        let q = self.deform(p);
        if q.is_finite() {
            Ok(q)
        } else {
            Err(FfdError::NonFiniteResult { index: 0 })
        }
    }

    /// Deforms every point in place; each result is bit-identical to [`Lattice::deform`].
    pub fn deform_in_place(&self, points: &mut [Vec3]) {
        if !self.deformed {
            return;
        }
        const BATCH: usize = 8;
        let mut chunks = points.chunks_exact_mut(BATCH);
        for chunk in &mut chunks {
            let mut locals = [Vec3::ZERO; BATCH];
            let mut moved = [false; BATCH];
            for (q, p) in chunk.iter().enumerate() {
                if let Some(local) = self.local_if_moved(*p) {
                    locals[q] = local;
                    moved[q] = true;
                }
            }
            let displacements = self.displacements(&locals);
            for ((p, d), moved) in chunk.iter_mut().zip(displacements).zip(moved) {
                if moved {
                    *p = Vec3::from(Vec3A::from(*p) + d);
                }
            }
        }
        for p in chunks.into_remainder() {
            *p = self.deform(*p);
        }
    }

    /// [`Lattice::deform_in_place`] that first checks every input is finite and then that every
    /// result is.
    ///
    /// # Errors
    /// [`FfdError::NonFinite`] naming the first non-finite input (nothing is written then), and
    /// [`FfdError::NonFiniteResult`] naming the first point that overflowed (points before it
    /// are already deformed).
    pub fn try_deform_in_place(&self, points: &mut [Vec3]) -> Result<(), FfdError> {
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
            return Err(FfdError::NonFinite {
                what: "point",
                index: Some(index),
            });
        }
        for (index, p) in points.iter_mut().enumerate() {
            let q = self.deform(*p);
            if !q.is_finite() {
                return Err(FfdError::NonFiniteResult { index });
            }
            *p = q;
        }
        Ok(())
    }

    /// The deformed position of local coordinates `(s, t, u)`, ignoring the outside policy.
    #[must_use]
    pub fn deform_local(&self, local: Vec3) -> Vec3 {
        let p = self.world_coords(local);
        if !self.deformed {
            return p;
        }
        Vec3::from(Vec3A::from(p) + self.displacement(local))
    }

    /// `Σ B_i(s) B_j(t) B_k(u) (P_ijk − grid_ijk)` at one point.
    #[inline]
    pub(crate) fn displacement(&self, local: Vec3) -> Vec3A {
        let [d] = self.displacements(&[local]);
        d
    }

    /// The displacement at `N` points at once. Every point goes through exactly the same
    /// arithmetic whatever `N` is (so batches are bit-identical to single points); interleaving
    /// independent points only gives the processor more to do in parallel.
    #[inline]
    fn displacements<const N: usize>(&self, locals: &[Vec3; N]) -> [Vec3A; N] {
        let [l, m, n] = self.divisions;
        let row = l + 1;
        let layer = row * (m + 1);
        let mut out = [Vec3A::ZERO; N];
        if l == 2 && m == 2 && n < SMALL_DEPTH {
            // The body lattice's 3×3 cross-sections, with every size known at compile time.
            let mut bu = [[0.0f32; SMALL_DEPTH]; N];
            let mut weights = [[Vec3A::ZERO; 9]; N];
            for q in 0..N {
                let bs = quadratic_basis(locals[q].x);
                let bt = quadratic_basis(locals[q].y);
                self.binomials[2].eval(locals[q].z, &mut bu[q]);
                for j in 0..3 {
                    for i in 0..3 {
                        weights[q][j * 3 + i] = Vec3A::splat(bt[j] * bs[i]);
                    }
                }
            }
            for (k, layer_offsets) in self.offsets.chunks_exact(9).enumerate().take(n + 1) {
                let mut sums = [Vec3A::ZERO; N];
                for (c, d) in layer_offsets.iter().enumerate() {
                    for q in 0..N {
                        sums[q] += *d * weights[q][c];
                    }
                }
                for q in 0..N {
                    out[q] += sums[q] * bu[q][k];
                }
            }
            return out;
        }
        if layer <= SMALL_LAYER && n < SMALL_DEPTH {
            // Common case (the body's 3×3 cross-sections): weigh each layer with the products
            // B_i(s) B_j(t), splatted once and reused by every layer, then sum the layers with
            // B_k(u).
            let mut weights = [[Vec3A::ZERO; SMALL_LAYER]; N];
            let mut bu = [[0.0f32; SMALL_DEPTH]; N];
            for q in 0..N {
                let mut bs = [0.0f32; SMALL_LAYER];
                let mut bt = [0.0f32; SMALL_LAYER];
                self.binomials[0].eval(locals[q].x, &mut bs);
                self.binomials[1].eval(locals[q].y, &mut bt);
                self.binomials[2].eval(locals[q].z, &mut bu[q]);
                for (j, wt) in bt.iter().take(m + 1).enumerate() {
                    for (i, ws) in bs.iter().take(row).enumerate() {
                        weights[q][j * row + i] = Vec3A::splat(*wt * *ws);
                    }
                }
            }
            for (k, layer_offsets) in self.offsets.chunks_exact(layer).enumerate().take(n + 1) {
                let mut sums = [Vec3A::ZERO; N];
                for (c, d) in layer_offsets.iter().enumerate() {
                    for q in 0..N {
                        sums[q] += *d * weights[q][c];
                    }
                }
                for q in 0..N {
                    out[q] += sums[q] * bu[q][k];
                }
            }
            return out;
        }
        for q in 0..N {
            let mut bs = [0.0f32; MAX_DIVISIONS + 1];
            let mut bt = [0.0f32; MAX_DIVISIONS + 1];
            let mut bu = [0.0f32; MAX_DIVISIONS + 1];
            self.binomials[0].eval(locals[q].x, &mut bs);
            self.binomials[1].eval(locals[q].y, &mut bt);
            self.binomials[2].eval(locals[q].z, &mut bu);
            let mut total = Vec3A::ZERO;
            for (wu, layer_offsets) in bu[..=n].iter().zip(self.offsets.chunks_exact(layer)) {
                let mut plane = Vec3A::ZERO;
                for (wt, row_offsets) in bt[..=m].iter().zip(layer_offsets.chunks_exact(row)) {
                    let mut line = Vec3A::ZERO;
                    for (ws, d) in bs[..=l].iter().zip(row_offsets) {
                        line += *d * *ws;
                    }
                    plane += line * *wt;
                }
                total += plane * *wu;
            }
            out[q] = total;
        }
        out
    }

    /// Local coordinates of `p` if [`Lattice::deform`] moves it (finite, and inside unless the
    /// policy extrapolates).
    #[inline]
    fn local_if_moved(&self, p: Vec3) -> Option<Vec3> {
        if !p.is_finite() {
            return None;
        }
        let local = self.local_coords(p);
        if self.outside == OutsidePolicy::Unchanged && !is_inside(local) {
            return None;
        }
        Some(local)
    }

    /// Control point offsets from the grid, in storage order.
    pub(crate) fn offsets(&self) -> &[Vec3A] {
        &self.offsets
    }

    /// The dual frame: `dual[a] · (p − origin)` is local coordinate `a`.
    pub(crate) fn dual(&self) -> &[Vec3A; 3] {
        &self.dual
    }

    pub(crate) fn binomials(&self) -> &[Binomials; 3] {
        &self.binomials
    }

    /// Undeformed grid position of an in-range index.
    pub(crate) fn grid(&self, [i, j, k]: [usize; 3]) -> Vec3 {
        let [l, m, n] = self.divisions;
        self.world_coords(Vec3::new(
            i as f32 / l as f32,
            j as f32 / m as f32,
            k as f32 / n as f32,
        ))
    }

    /// Writes a validated, finite control point at an in-range index.
    pub(crate) fn write(&mut self, idx: usize, index: [usize; 3], p: Vec3) {
        let offset = Vec3A::from(p - self.grid(index));
        self.points[idx] = p;
        self.offsets[idx] = offset;
        if offset != Vec3A::ZERO {
            self.deformed = true;
        }
    }
}

/// The degree-2 Bernstein basis `[(1 − x)², 2x(1 − x), x²]`, with the same operations in the
/// same order as the general evaluation, so it gives the same bits.
#[inline]
fn quadratic_basis(x: f32) -> [f32; 3] {
    let y = 1.0 - x;
    [y * y, 2.0 * x * y, x * x]
}

/// [`FfdError::CoordinateTooLarge`] naming the first coordinate of `p` (finite) beyond
/// ±[`MAX_COORDINATE`]; `index` is the point's.
pub(crate) fn check_coordinates(what: &'static str, index: usize, p: Vec3) -> Result<(), FfdError> {
    match p
        .to_array()
        .into_iter()
        .find(|c| !(math::abs(*c) <= MAX_COORDINATE))
    {
        Some(value) => Err(FfdError::CoordinateTooLarge { what, index, value }),
        None => Ok(()),
    }
}

/// Whether local coordinates lie in the closed unit cube.
#[inline]
pub(crate) fn is_inside(local: Vec3) -> bool {
    local.cmpge(Vec3::ZERO).all() && local.cmple(Vec3::ONE).all()
}

/// The axis-aligned bounds of a non-empty, finite point set.
fn bounds(points: &[Vec3]) -> Result<(Vec3, Vec3), FfdError> {
    let first = *points.first().ok_or(FfdError::NoPoints)?;
    let mut min = first;
    let mut max = first;
    for (index, p) in points.iter().enumerate() {
        if !p.is_finite() {
            return Err(FfdError::NonFinite {
                what: "point",
                index: Some(index),
            });
        }
        min = min.min(*p);
        max = max.max(*p);
    }
    Ok((min, max))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit(divisions: [usize; 3]) -> Lattice {
        Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], divisions).unwrap()
    }

    #[test]
    fn grid_starts_undeformed() {
        let lattice = unit([2, 2, 10]);
        assert_eq!(lattice.control_point_count(), 99);
        assert_eq!(lattice.control_point([2, 2, 10]), Some(Vec3::ONE));
        assert_eq!(
            lattice.control_point([1, 0, 5]),
            Some(Vec3::new(0.5, 0.0, 0.5))
        );
        assert_eq!(lattice.control_point([3, 0, 0]), None);
        assert!(!lattice.is_deformed());
    }

    #[test]
    fn storage_order_is_i_fastest() {
        let lattice = unit([1, 2, 3]);
        assert_eq!(lattice.index_of([1, 0, 0]), Some(1));
        assert_eq!(lattice.index_of([0, 1, 0]), Some(2));
        assert_eq!(lattice.index_of([0, 0, 1]), Some(6));
        assert_eq!(lattice.index_of([1, 2, 3]), Some(23));
    }

    #[test]
    fn rejects_bad_construction() {
        let axes = [Vec3::X, Vec3::Y, Vec3::Z];
        assert_eq!(
            Lattice::new(Vec3::NAN, axes, [1, 1, 1]),
            Err(FfdError::NonFinite {
                what: "origin",
                index: None
            })
        );
        assert_eq!(
            Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::INFINITY, Vec3::Z], [1, 1, 1]),
            Err(FfdError::NonFinite {
                what: "axis",
                index: Some(1)
            })
        );
        assert_eq!(
            Lattice::new(Vec3::ZERO, axes, [1, 0, 1]),
            Err(FfdError::ZeroDivisions { axis: 1 })
        );
        assert!(matches!(
            Lattice::new(Vec3::ZERO, axes, [1, 1, MAX_DIVISIONS + 1]),
            Err(FfdError::TooManyDivisions { axis: 2, .. })
        ));
        assert!(matches!(
            Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::ZERO, Vec3::Z], [1, 1, 1]),
            Err(FfdError::DegenerateAxes { .. })
        ));
        assert!(matches!(
            Lattice::new(
                Vec3::ZERO,
                [Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1e-9)],
                [1, 1, 1]
            ),
            Err(FfdError::DegenerateAxes { .. })
        ));
    }

    #[test]
    fn around_points_spanning_more_than_f32_is_an_error() {
        let far = [Vec3::splat(-3e38), Vec3::splat(3e38)];
        assert_eq!(
            Lattice::around(&far, [1, 1, 1], 0.0),
            Err(FfdError::TooLarge)
        );
        assert_eq!(
            Lattice::around(&[Vec3::ZERO], [1, 1, 1], f32::MAX),
            Err(FfdError::TooLarge)
        );
    }

    #[test]
    fn huge_axes_overflowing_the_volume_are_degenerate_not_nan() {
        let big = Vec3::splat(f32::MAX);
        let result = Lattice::new(Vec3::ZERO, [big, big * Vec3::Y, big * Vec3::Z], [1, 1, 1]);
        assert!(matches!(result, Err(FfdError::DegenerateAxes { .. })));
    }

    #[test]
    fn around_checks_its_input() {
        assert_eq!(
            Lattice::around(&[], [1, 1, 1], 0.0),
            Err(FfdError::NoPoints)
        );
        assert_eq!(
            Lattice::around(&[Vec3::ZERO, Vec3::NAN], [1, 1, 1], 0.0),
            Err(FfdError::NonFinite {
                what: "point",
                index: Some(1)
            })
        );
        assert!(matches!(
            Lattice::around(&[Vec3::ZERO], [1, 1, 1], -1.0),
            Err(FfdError::InvalidPadding { .. })
        ));
        assert!(matches!(
            Lattice::around(&[Vec3::ZERO, Vec3::X], [1, 1, 1], 0.0),
            Err(FfdError::DegenerateAxes { .. })
        ));
        let lattice = Lattice::around(&[Vec3::ZERO], [1, 1, 1], 0.5).unwrap();
        assert_eq!(lattice.origin(), Vec3::splat(-0.5));
        assert!(lattice.contains(Vec3::ZERO));
    }

    #[test]
    fn set_control_point_validates() {
        let mut lattice = unit([1, 1, 1]);
        assert_eq!(
            lattice.set_control_point([2, 0, 0], Vec3::ZERO),
            Err(FfdError::IndexOutOfRange {
                index: [2, 0, 0],
                divisions: [1, 1, 1]
            })
        );
        assert!(lattice.set_control_point([1, 0, 0], Vec3::NAN).is_err());
        assert!(!lattice.is_deformed());
        lattice
            .set_control_point([1, 0, 0], Vec3::new(2.0, 0.0, 0.0))
            .unwrap();
        assert!(lattice.is_deformed());
        assert_eq!(lattice.deform(Vec3::X), Vec3::new(2.0, 0.0, 0.0));
        lattice.reset();
        assert!(!lattice.is_deformed());
        assert_eq!(lattice.control_point([1, 0, 0]), Some(Vec3::X));
    }

    #[test]
    fn deform_matches_a_hand_computed_sum() {
        // One division per axis: trilinear interpolation. Move corner [1,1,1] by (1,0,0).
        let mut lattice = unit([1, 1, 1]);
        lattice
            .set_control_point([1, 1, 1], Vec3::new(2.0, 1.0, 1.0))
            .unwrap();
        let p = Vec3::new(0.5, 0.5, 0.5);
        // Weight of the corner is 0.125.
        assert_eq!(lattice.deform(p), Vec3::new(0.625, 0.5, 0.5));
    }

    #[test]
    fn outside_policy_unchanged_keeps_outside_points() {
        let mut lattice = unit([1, 1, 1]).with_outside_policy(OutsidePolicy::Unchanged);
        lattice
            .set_control_point([1, 1, 1], Vec3::splat(2.0))
            .unwrap();
        let outside = Vec3::new(1.5, 0.5, 0.5);
        assert_eq!(lattice.deform(outside), outside);
        lattice.set_outside_policy(OutsidePolicy::Extrapolate);
        assert_ne!(lattice.deform(outside), outside);
    }

    #[test]
    fn non_finite_points_pass_through_or_error() {
        let mut lattice = unit([1, 1, 1]);
        lattice
            .set_control_point([1, 1, 1], Vec3::splat(2.0))
            .unwrap();
        assert!(lattice.deform(Vec3::NAN).is_nan());
        assert!(matches!(
            lattice.try_deform(Vec3::NAN),
            Err(FfdError::NonFinite { .. })
        ));
        let mut pts = [Vec3::ZERO, Vec3::INFINITY];
        assert_eq!(
            lattice.try_deform_in_place(&mut pts),
            Err(FfdError::NonFinite {
                what: "point",
                index: Some(1)
            })
        );
        assert_eq!(pts[0], Vec3::ZERO);
    }

    #[test]
    fn far_points_overflow_into_an_error() {
        let mut lattice = unit([2, 2, 10]);
        lattice
            .set_control_point([1, 1, 5], Vec3::splat(0.7))
            .unwrap();
        let far = Vec3::splat(1e30);
        assert_eq!(
            lattice.try_deform(far),
            Err(FfdError::NonFiniteResult { index: 0 })
        );
    }

    #[test]
    fn batches_with_skipped_points_match_single_points() {
        let mut lattice = unit([2, 2, 10]).with_outside_policy(OutsidePolicy::Unchanged);
        lattice
            .set_control_point([1, 1, 5], Vec3::new(0.7, 0.4, 0.5))
            .unwrap();
        let points = [
            Vec3::splat(0.5),
            Vec3::new(2.0, 0.5, 0.5),
            Vec3::NAN,
            Vec3::new(0.1, 0.9, 0.4),
            Vec3::new(0.3, 0.2, 0.6),
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(0.6, 0.6, 0.45),
        ];
        let mut batch = points;
        lattice.deform_in_place(&mut batch);
        for (p, q) in points.iter().zip(&batch) {
            let single = lattice.deform(*p);
            assert!(
                single == *q || (single.is_nan() && q.is_nan()),
                "{p}: {single} vs {q}"
            );
        }
        assert_eq!(batch[1], points[1]);
        assert_ne!(batch[0], points[0]);
    }

    #[test]
    fn large_layers_take_the_general_path_and_agree_with_trilinear_math() {
        // 4x4 layers exceed the small-layer path: a 1-division-in-u lattice with one moved
        // corner still interpolates that corner exactly.
        let mut lattice = unit([3, 3, 1]);
        lattice
            .set_control_point([3, 3, 1], Vec3::splat(1.5))
            .unwrap();
        assert_eq!(lattice.deform(Vec3::ONE), Vec3::splat(1.5));
        assert_eq!(lattice.deform(Vec3::ZERO), Vec3::ZERO);
    }

    #[test]
    fn quadratic_basis_matches_the_general_evaluation_bit_for_bit() {
        let general = crate::bernstein::Binomials::new(2);
        for step in -20..=40 {
            let x = step as f32 * 0.037;
            let mut out = [0.0f32; 3];
            general.eval(x, &mut out);
            assert_eq!(
                quadratic_basis(x).map(f32::to_bits),
                out.map(f32::to_bits),
                "x = {x}"
            );
        }
    }
}
