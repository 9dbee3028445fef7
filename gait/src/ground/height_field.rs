//! [`HeightField`]: a regular grid of heights, bilinear between samples, with exact ray casts
//! (a 2D DDA over the cells, a quadratic per bilinear patch) and a single lookup straight down.

use alloc::vec::Vec;

use glam::{Vec2, Vec3, Vec4};

use super::{Ground, RayHit};
use crate::error::{GaitError, finite, positive};
use crate::math::{abs, sqrt};

/// A regular grid of heights over the XZ plane, bilinear between samples.
///
/// Sample `(i, j)` sits at `x = origin.x + i · cell`, `z = origin.y + j · cell` with height
/// `heights[j · columns + i]`. Outside the grid there is no ground (rays miss). Ray casts are
/// exact: the ray walks the cells it crosses (a 2D DDA) and, in each, solves the quadratic
/// where it meets the bilinear patch; a vertical ray returns the bilinear height itself.
///
/// ```
/// use creature_gait::{Ground, HeightField, glam::{Vec2, Vec3}};
///
/// // 3 × 2 samples, 1 m apart, rising along X.
/// let field = HeightField::new(Vec2::ZERO, 1.0, 3, 2, vec![0.0, 1.0, 2.0, 0.0, 1.0, 2.0])?;
/// assert_eq!(field.height(0.5, 0.5), Some(0.5));
/// let hit = field.cast_ray(Vec3::new(1.5, 5.0, 0.5), Vec3::NEG_Y, 10.0).unwrap();
/// assert_eq!(hit.point.y, 1.5);
/// # Ok::<(), creature_gait::GaitError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct HeightField {
    origin: Vec2,
    cell: f32,
    columns: usize,
    rows: usize,
    heights: Vec<f32>,
    /// `1 / cell`, so a lookup multiplies instead of dividing.
    inv_cell: f32,
    /// `(columns − 1, rows − 1)` as floats: the largest grid coordinates (no conversion per
    /// lookup).
    max_grid: Vec2,
    /// `(columns − 2, rows − 2)`, the last cell's indices, and `columns` as a `u32`, when both
    /// indices are below 2²⁴ (every practical grid): lookups then convert through `i32`,
    /// exactly, and read a cell's four heights with one bounds check; `None` otherwise.
    grid: Option<(i32, i32, u32)>,
}

impl HeightField {
    /// A height field with `columns × rows` samples (X fastest), `cell` metres apart, its first
    /// sample at `(origin.x, origin.y)` in world XZ.
    ///
    /// # Errors
    /// [`GaitError::GridTooSmall`] for fewer than 2 × 2 samples, [`GaitError::WrongLength`]
    /// when `heights.len() != columns · rows`, [`GaitError::NotPositive`] for a cell size that
    /// is not positive, [`GaitError::NonFinite`] for a non-finite origin or height.
    pub fn new(
        origin: Vec2,
        cell: f32,
        columns: usize,
        rows: usize,
        heights: Vec<f32>,
    ) -> Result<Self, GaitError> {
        if columns < 2 || rows < 2 {
            return Err(GaitError::GridTooSmall { columns, rows });
        }
        let expected = columns
            .checked_mul(rows)
            .ok_or(GaitError::GridTooSmall { columns, rows })?;
        if heights.len() != expected {
            return Err(GaitError::WrongLength {
                what: "heights",
                expected,
                found: heights.len(),
            });
        }
        if !origin.is_finite() {
            return Err(GaitError::NonFinite {
                what: "height field origin",
                index: 0,
            });
        }
        positive(cell, "cell size", 0)?;
        for (index, &h) in heights.iter().enumerate() {
            finite(h, "height", index)?;
        }
        // The far corner must be representable.
        let extent =
            origin + Vec2::splat(cell) * Vec2::new((columns - 1) as f32, (rows - 1) as f32);
        if !extent.is_finite() {
            return Err(GaitError::NonFinite {
                what: "height field extent",
                index: 0,
            });
        }
        Ok(Self {
            origin,
            cell,
            columns,
            rows,
            heights,
            inv_cell: 1.0 / cell,
            max_grid: Vec2::new((columns - 1) as f32, (rows - 1) as f32),
            grid: match (i32::try_from(columns - 2), i32::try_from(rows - 2)) {
                (Ok(i), Ok(j)) if i < 1 << 24 && j < 1 << 24 => {
                    Some((i, j, (i + 2).cast_unsigned()))
                }
                _ => None,
            },
        })
    }

    /// A height field sampled from `height(x, z)` on the grid. Non-finite samples are an error.
    ///
    /// # Errors
    /// As [`HeightField::new`].
    pub fn from_fn(
        origin: Vec2,
        cell: f32,
        columns: usize,
        rows: usize,
        height: impl Fn(f32, f32) -> f32,
    ) -> Result<Self, GaitError> {
        let mut heights = Vec::with_capacity(columns.saturating_mul(rows).min(1 << 24));
        for j in 0..rows {
            for i in 0..columns {
                heights.push(height(
                    origin.x + i as f32 * cell,
                    origin.y + j as f32 * cell,
                ));
            }
        }
        Self::new(origin, cell, columns, rows, heights)
    }

    /// World XZ of sample `(0, 0)`.
    #[must_use]
    pub const fn origin(&self) -> Vec2 {
        self.origin
    }

    /// Distance between neighbouring samples, in metres.
    #[must_use]
    pub const fn cell(&self) -> f32 {
        self.cell
    }

    /// Samples along X.
    #[must_use]
    pub const fn columns(&self) -> usize {
        self.columns
    }

    /// Samples along Z.
    #[must_use]
    pub const fn rows(&self) -> usize {
        self.rows
    }

    /// The samples, X fastest.
    #[must_use]
    pub fn heights(&self) -> &[f32] {
        &self.heights
    }

    /// World XZ of the far corner (sample `(columns − 1, rows − 1)`).
    #[must_use]
    pub fn max_corner(&self) -> Vec2 {
        self.origin
            + Vec2::new(
                (self.columns - 1) as f32 * self.cell,
                (self.rows - 1) as f32 * self.cell,
            )
    }

    #[inline]
    fn sample(&self, i: usize, j: usize) -> f32 {
        self.heights[j * self.columns + i]
    }

    /// The cell holding grid coordinates `(gx, gz)` (in cells from the origin) and the local
    /// coordinates inside it, or `None` outside the grid.
    #[inline(always)]
    fn locate(&self, x: f32, z: f32) -> Option<(usize, usize, f32, f32)> {
        let gx = (x - self.origin.x) * self.inv_cell;
        let gz = (z - self.origin.y) * self.inv_cell;
        if !(gx >= 0.0 && gx <= self.max_grid.x && gz >= 0.0 && gz <= self.max_grid.y) {
            return None;
        }
        // Non-negative here, so truncation is the floor (no libm call).
        if let Some((last_i, last_j, _)) = self.grid {
            // Below 2²⁴ here: `i32` conversions both ways are exact and cheaper than `usize`'s.
            let i = (gx as i32).min(last_i);
            let j = (gz as i32).min(last_j);
            return Some((i as usize, j as usize, gx - i as f32, gz - j as f32));
        }
        let i = (gx as usize).min(self.columns - 2);
        let j = (gz as usize).min(self.rows - 2);
        Some((i, j, gx - i as f32, gz - j as f32))
    }

    /// Bilinear coefficients `[a, b, c, d]` of cell `(i, j)`: `h = a + b u + c v + d u v`.
    #[inline(always)]
    fn patch(&self, i: usize, j: usize) -> [f32; 4] {
        if let Some((_, _, columns)) = self.grid {
            // Both rows in one slice of `columns + 2` samples: one bounds check (never failing
            // for a located cell); `columns` below 2³² makes the four reads provably inside it.
            let c = columns as usize;
            let k = j * c + i;
            if let Some(q) = self.heights.get(k..k + c + 2) {
                let (h00, h10, h01, h11) = (q[0], q[1], q[c], q[c + 1]);
                return [h00, h10 - h00, h01 - h00, h00 - h10 - h01 + h11];
            }
        }
        // Two rows of two samples: two bounds checks (never failing for a located cell).
        let k = j * self.columns + i;
        let (h00, h10) = match self.heights.get(k..k + 2) {
            Some(&[a, b]) => (a, b),
            _ => (self.sample(i, j), self.sample(i + 1, j)),
        };
        let k = k + self.columns;
        let (h01, h11) = match self.heights.get(k..k + 2) {
            Some(&[a, b]) => (a, b),
            _ => (self.sample(i, j + 1), self.sample(i + 1, j + 1)),
        };
        [h00, h10 - h00, h01 - h00, h00 - h10 - h01 + h11]
    }

    /// The bilinear height at world `(x, z)`, or `None` outside the grid.
    #[must_use]
    pub fn height(&self, x: f32, z: f32) -> Option<f32> {
        let (i, j, u, v) = self.locate(x, z)?;
        let [a, b, c, d] = self.patch(i, j);
        Some(a + b * u + c * v + d * u * v)
    }

    /// The unit surface normal at world `(x, z)`, or `None` outside the grid.
    #[must_use]
    pub fn normal(&self, x: f32, z: f32) -> Option<Vec3> {
        let (i, j, u, v) = self.locate(x, z)?;
        Some(self.patch_normal(i, j, u, v))
    }

    #[inline]
    fn patch_normal(&self, i: usize, j: usize, u: f32, v: f32) -> Vec3 {
        self.patch_normal_of(self.patch(i, j), u, v)
    }

    #[inline(always)]
    fn patch_normal_of(&self, [_, b, c, d]: [f32; 4], u: f32, v: f32) -> Vec3 {
        let dx = (b + d * v) * self.inv_cell;
        let dz = (c + d * u) * self.inv_cell;
        // (−dx, 1, −dz) normalised; its length is at least 1, so only overflow needs care.
        let len2 = 1.0 + dx * dx + dz * dz;
        if len2.is_finite() {
            let inv = 1.0 / sqrt(len2);
            Vec3::new(-dx * inv, inv, -dz * inv)
        } else {
            Vec3::new(-dx, 1.0, -dz).normalize_or(Vec3::Y)
        }
    }

    /// A vertical ray down from `origin` at speed `down` (> 0) per unit of distance: the
    /// bilinear height under it and the patch's normal.
    #[inline(always)]
    fn vertical(&self, origin: Vec3, down: f32, max_distance: f32) -> Option<RayHit> {
        let (patch, u, v, h, distance) = self.under(origin, down, max_distance)?;
        Some(RayHit {
            point: Vec3::new(origin.x, h, origin.z),
            normal: self.patch_normal_of(patch, u, v),
            distance,
        })
    }

    /// The surface under `origin` for [`vertical`](Self::vertical): the cell's bilinear
    /// coefficients, the local coordinates, the height and the distance, or `None` for no hit.
    #[inline(always)]
    fn under(
        &self,
        origin: Vec3,
        down: f32,
        max_distance: f32,
    ) -> Option<([f32; 4], f32, f32, f32, f32)> {
        let (i, j, u, v) = self.locate(origin.x, origin.z)?;
        let patch = self.patch(i, j);
        let [a, b, c, d] = patch;
        let h = a + b * u + c * v + d * u * v;
        if origin.y < h {
            return None;
        }
        // Dividing by exactly 1 (every straight-down cast) changes nothing: skip it.
        let rise = origin.y - h;
        let distance = if down == 1.0 { rise } else { rise / down };
        if !(distance <= max_distance) {
            return None;
        }
        Some((patch, u, v, h, distance))
    }

    /// The first downward crossing of the ray with cell `(i, j)`'s patch for `t` in
    /// `[t0, t1]`.
    fn cross_cell(
        &self,
        i: usize,
        j: usize,
        origin: Vec3,
        direction: Vec3,
        t0: f32,
        t1: f32,
    ) -> Option<f32> {
        let [a, b, c, d] = self.patch(i, j);
        // Re-base at the cell entry for conditioning: s = t − t0.
        let p = origin + direction * t0;
        let u0 = (p.x - self.origin.x) / self.cell - i as f32;
        let v0 = (p.z - self.origin.y) / self.cell - j as f32;
        let du = direction.x / self.cell;
        let dv = direction.z / self.cell;
        // f(s) = ray height − surface height = k0 + k1 s + k2 s².
        let k0 = p.y - (a + b * u0 + c * v0 + d * u0 * v0);
        let k1 = direction.y - (b * du + c * dv + d * (u0 * dv + v0 * du));
        let k2 = -d * du * dv;
        let len = t1 - t0;
        let slope = |s: f32| k1 + 2.0 * k2 * s;
        let accept = |s: f32| s >= 0.0 && s <= len && slope(s) < 0.0;
        let scale = abs(k1) + abs(k0) / len.max(1e-12);
        if abs(k2) * len <= 1e-7 * scale.max(1e-30) {
            // Linear.
            if k1 == 0.0 {
                return None;
            }
            let s = -k0 / k1;
            return accept(s).then_some(t0 + s);
        }
        let disc = k1 * k1 - 4.0 * k2 * k0;
        if disc < 0.0 {
            return None;
        }
        let root = sqrt(disc);
        let q = -0.5 * (k1 + if k1 >= 0.0 { root } else { -root });
        let (mut r1, mut r2) = if q == 0.0 {
            (0.0, 0.0)
        } else {
            (q / k2, k0 / q)
        };
        if r1 > r2 {
            core::mem::swap(&mut r1, &mut r2);
        }
        if accept(r1) {
            Some(t0 + r1)
        } else if accept(r2) {
            Some(t0 + r2)
        } else {
            None
        }
    }
}

impl HeightField {
    /// [`Ground::cast_down_four`] where every ray is over the grid and its cells' indices fit
    /// `i32` (see `grid`): `locate`, `patch` and `under` for four rays, lane for lane; `None`
    /// otherwise.
    #[inline(always)]
    fn four(&self, x: Vec4, y: Vec4, z: Vec4, max_distance: Vec4) -> Option<[Option<f32>; 4]> {
        let (last_i, last_j, columns) = self.grid?;
        // Every sample index below 2²³: the indices below are exact as floats, and 2²³ more
        // than one holds it in its mantissa's low bits.
        if self.heights.len() > BIG as usize {
            return None;
        }
        let inv = Vec4::splat(self.inv_cell);
        let gx = (x - Vec4::splat(self.origin.x)) * inv;
        let gz = (z - Vec4::splat(self.origin.y)) * inv;
        let (top_x, top_z) = (Vec4::splat(self.max_grid.x), Vec4::splat(self.max_grid.y));
        let inside =
            gx.cmpge(Vec4::ZERO) & gx.cmple(top_x) & gz.cmpge(Vec4::ZERO) & gz.cmple(top_z);
        if !inside.all() {
            return None;
        }
        // The cell: each grid coordinate's whole part (non-negative and below 2²³: rounded to a
        // whole number by adding 2²³, then one less where that rounded up; `as i32` exactly),
        // no further than the last cell; `locate`'s as floats, exactly.
        let big = Vec4::splat(BIG as f32);
        let whole = |g: Vec4, last: i32| {
            let near = (g + big) - big;
            let floor = Vec4::select(near.cmpgt(g), near - Vec4::ONE, near);
            floor.min(Vec4::splat(last as f32))
        };
        let (i, j) = (whole(gx, last_i), whole(gz, last_j));
        let (u, v) = (gx - i, gz - j);
        let c = columns as usize;
        let first = j * Vec4::splat(columns as f32) + i + big;
        // 2²³ + k: the float's bits are 2²³'s plus `k`.
        let index = |k: f32| (k.to_bits() - BIG_BITS) as usize;
        let [h00, h10, h01, h11] = if first.cmpeq(Vec4::splat(first.x)).all() {
            // One cell under the four (a sole's rays, mostly): its corners read once.
            let k = index(first.x);
            // Both rows of the cell in one slice (never failing for a located cell).
            let q = self.heights.get(k..k + c + 2)?;
            [q[0], q[1], q[c], q[c + 1]].map(Vec4::splat)
        } else {
            let mut corners = [[0.0f32; 4]; 4];
            for (l, k) in first.to_array().into_iter().enumerate() {
                let k = index(k);
                let q = self.heights.get(k..k + c + 2)?;
                (corners[0][l], corners[1][l]) = (q[0], q[1]);
                (corners[2][l], corners[3][l]) = (q[c], q[c + 1]);
            }
            corners.map(Vec4::from_array)
        };
        let (a, b, cc, d) = (h00, h10 - h00, h01 - h00, h00 - h10 - h01 + h11);
        let h = a + b * u + cc * v + d * u * v;
        // `under`'s checks (the ray starts at or above the height, and reaches it), then
        // `cast_down_point`'s (a finite distance).
        let distance = y - h;
        let hit = !y.cmplt(h) & distance.cmple(max_distance) & distance.is_finite_mask();
        let (hit, h) = (hit.bitmask(), h.to_array());
        Some(core::array::from_fn(|l| {
            (hit & (1 << l) != 0).then_some(h[l])
        }))
    }

    /// [`Ground::cast_down_four`] ray by ray (where [`four`](Self::four) cannot look the
    /// four up together: kept out of line, as it is rarely taken).
    #[cold]
    #[inline(never)]
    fn each_of_four(&self, x: Vec4, y: Vec4, z: Vec4, max_distance: Vec4) -> [Option<f32>; 4] {
        core::array::from_fn(|l| {
            self.cast_down_point(Vec3::new(x[l], y[l], z[l]), max_distance[l])
                .map(|hit| hit.y)
        })
    }

    /// [`Ground::height_bounds`]: the lowest and highest samples at the corners of the cells
    /// the square covers (a bilinear patch lies between its corners), widened by the rounding
    /// of a lookup unless they are equal (a flat patch's lookups are exact); `None` for a
    /// square not inside the grid, a negative or non-finite `half`, or one over more than
    /// [`BOUNDED_CELLS`] cells (casting is then as cheap).
    fn bounds(&self, centre: Vec2, half: f32) -> Option<(f32, f32)> {
        if !(half >= 0.0) {
            return None;
        }
        // The cells of the square's corners, as a lookup finds them (grid coordinates are
        // monotonic in world ones: every point of the square is in a cell between them).
        let (i0, j0, _, _) = self.locate(centre.x - half, centre.y - half)?;
        let (i1, j1, _, _) = self.locate(centre.x + half, centre.y + half)?;
        // Their corners: `across` samples in each of `rows` rows, `columns` apart.
        let (across, rows) = (i1 - i0 + 2, j1 - j0 + 2);
        if (across - 1) * (rows - 1) > BOUNDED_CELLS {
            return None;
        }
        let c = self.columns;
        let first = j0 * c + i0;
        // Inside the grid (both corners were located): one bounds check for the block.
        let block = self.heights.get(first..first + (rows - 1) * c + across)?;
        // The heights are finite: plain comparisons (no NaN handling) find the extremes.
        let (mut lowest, mut highest) = (block[0], block[0]);
        for row in 0..rows {
            for &h in &block[row * c..row * c + across] {
                if h < lowest {
                    lowest = h;
                }
                if h > highest {
                    highest = h;
                }
            }
        }
        Some(pad(lowest, highest))
    }
}

/// Bounds on a lookup's height among samples from `lowest` to `highest`: the same where they
/// are equal (a flat patch's lookups are exact), else widened by the rounding of a lookup
/// `a + b u + c v + d u v` (each of its corner differences and terms rounded: well within 64
/// units of roundoff of the largest height).
#[inline]
fn pad(lowest: f32, highest: f32) -> (f32, f32) {
    if lowest == highest {
        return (lowest, highest);
    }
    let pad = 64.0 * f32::EPSILON * abs(lowest).max(abs(highest)) + f32::MIN_POSITIVE;
    (lowest - pad, highest + pad)
}

/// 2²³: a float at least this large is a whole number, and `BIG + k` (a whole `k` below it)
/// has `BIG`'s bits plus `k` ([`HeightField`]'s four lookups at once).
const BIG: u32 = 1 << 23;

/// The bits of `BIG as f32`.
const BIG_BITS: u32 = (BIG as f32).to_bits();

/// The most cells [`HeightField`]'s [`Ground::height_bounds`] scans (a square over more says
/// nothing).
const BOUNDED_CELLS: usize = 16;

impl Ground for HeightField {
    /// One bilinear lookup (no march): the same hit as `cast_ray` straight down.
    ///
    /// A non-finite `origin.x` or `origin.z` is outside the grid, and the distance found is
    /// `+0` or more (`-0` when `origin.y` is `-0` on a height of `+0`), so a NaN or negative
    /// `max_distance` (below `-0`) finds no hit: the checks of `cast_ray` come down to a finite
    /// `origin.y`.
    #[inline(always)]
    fn cast_down(&self, origin: Vec3, max_distance: f32) -> Option<RayHit> {
        if !origin.y.is_finite() {
            return None;
        }
        self.vertical(origin, 1.0, max_distance)
    }

    /// The bilinear height alone, without the normal: a patch's normal is always valid
    /// (finite and of unit length, or +Y where its slope overflows), so the hit is valid
    /// exactly when its height and distance are finite: when its distance is (a NaN or
    /// infinite `origin.y` or height gives a NaN or infinite distance, or none; and see
    /// [`cast_down`](Self::cast_down) for the other checks).
    #[inline(always)]
    fn cast_down_point(&self, origin: Vec3, max_distance: f32) -> Option<Vec3> {
        let (_, _, _, h, distance) = self.under(origin, 1.0, max_distance)?;
        distance
            .is_finite()
            .then(|| Vec3::new(origin.x, h, origin.z))
    }

    /// The lowest and highest heights at the corners of the cells under the square (see
    /// [`Ground::height_bounds`]); exact where they are equal. `None` where the square is not
    /// inside the grid or covers more than 16 cells.
    #[inline]
    fn height_bounds(&self, centre: Vec2, half: f32) -> Option<(f32, f32)> {
        self.bounds(centre, half)
    }

    /// Four lookups together: the same heights, bit for bit, as four
    /// [`cast_down_point`](Ground::cast_down_point)s (the same operations, lane for lane),
    /// their grid coordinates and bilinear sums four at a time. Where a ray is off the grid, or
    /// the grid is too large for `i32` indices, each ray is looked up alone.
    ///
    /// Inlined into its callers natively (a sole's 16 rays, four at a time, keep the grid's
    /// constants in registers); on WebAssembly, where the module's size counts, one copy.
    #[cfg_attr(not(target_arch = "wasm32"), inline(always))]
    #[cfg_attr(target_arch = "wasm32", inline)]
    fn cast_down_four(&self, x: Vec4, y: Vec4, z: Vec4, max_distance: Vec4) -> [Option<f32>; 4] {
        self.four(x, y, z, max_distance)
            .unwrap_or_else(|| self.each_of_four(x, y, z, max_distance))
    }

    fn cast_ray(&self, origin: Vec3, direction: Vec3, max_distance: f32) -> Option<RayHit> {
        if !(origin.is_finite() && direction.is_finite() && max_distance >= 0.0) {
            return None;
        }
        if direction.x == 0.0 && direction.z == 0.0 {
            // Vertical: the bilinear height itself.
            if !(direction.y < 0.0) {
                return None;
            }
            return self.vertical(origin, -direction.y, max_distance);
        }
        // Clip the ray against the grid's XZ box (slabs).
        let lo = self.origin;
        let hi = self.max_corner();
        let mut t_in = 0.0f32;
        let mut t_out = max_distance;
        for (o, dir, min, max) in [
            (origin.x, direction.x, lo.x, hi.x),
            (origin.z, direction.z, lo.y, hi.y),
        ] {
            if dir == 0.0 {
                if o < min || o > max {
                    return None;
                }
            } else {
                let a = (min - o) / dir;
                let b = (max - o) / dir;
                t_in = t_in.max(a.min(b));
                t_out = t_out.min(a.max(b));
            }
        }
        if !(t_in <= t_out) {
            return None;
        }
        // 2D DDA through the cells from t_in to t_out.
        let start = origin + direction * t_in;
        let gx = ((start.x - lo.x) / self.cell).clamp(0.0, (self.columns - 1) as f32);
        let gz = ((start.z - lo.y) / self.cell).clamp(0.0, (self.rows - 1) as f32);
        let mut i = (gx as usize).min(self.columns - 2);
        let mut j = (gz as usize).min(self.rows - 2);
        let step_i: isize = if direction.x > 0.0 { 1 } else { -1 };
        let step_j: isize = if direction.z > 0.0 { 1 } else { -1 };
        let boundary = |index: usize, step: isize, o: f32, dir: f32, lo: f32| -> f32 {
            if dir == 0.0 {
                return f32::INFINITY;
            }
            let edge = if step > 0 { index + 1 } else { index };
            (lo + edge as f32 * self.cell - o) / dir
        };
        let mut t = t_in;
        let max_steps = self.columns + self.rows + 2;
        for _ in 0..max_steps {
            let next_x = boundary(i, step_i, origin.x, direction.x, lo.x);
            let next_z = boundary(j, step_j, origin.z, direction.z, lo.y);
            let t_next = next_x.min(next_z).min(t_out).max(t);
            if let Some(hit_t) = self.cross_cell(i, j, origin, direction, t, t_next) {
                let point = origin + direction * hit_t;
                let (u, v) = (
                    ((point.x - lo.x) / self.cell - i as f32).clamp(0.0, 1.0),
                    ((point.z - lo.y) / self.cell - j as f32).clamp(0.0, 1.0),
                );
                return Some(RayHit {
                    point,
                    normal: self.patch_normal(i, j, u, v),
                    distance: hit_t,
                });
            }
            if t_next >= t_out {
                return None;
            }
            t = t_next;
            if next_x <= next_z {
                let ni = i as isize + step_i;
                if ni < 0 || ni as usize > self.columns - 2 {
                    return None;
                }
                i = ni as usize;
            } else {
                let nj = j as isize + step_j;
                if nj < 0 || nj as usize > self.rows - 2 {
                    return None;
                }
                j = nj as usize;
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::*;

    fn bumpy() -> HeightField {
        HeightField::from_fn(Vec2::new(-5.0, -5.0), 0.5, 21, 21, |x, z| {
            0.3 * crate::math::sin(x * 1.3) * crate::math::cos(z * 0.9) + 0.05 * x
        })
        .unwrap()
    }

    #[test]
    fn four_lookups_in_one_cell_are_four_lookups() {
        // Four rays round a point (a sole's rim: mostly in one cell, which is read once), at
        // points all over a bumpy grid, its edges included: the heights of four single casts.
        let f = bumpy();
        let (mut one_cell, mut several) = (0, 0);
        for k in 0..400 {
            let t = k as f32;
            let (cx, cz) = (-5.0 + 0.025 * t, 5.0 - 0.0251 * t);
            let r = 0.004 * (k % 40) as f32;
            let x = Vec4::new(cx + r, cx - r, cx, cx + 0.5 * r).min(Vec4::splat(5.0));
            let z = Vec4::new(cz, cz + r, cz - r, cz - 0.5 * r).max(Vec4::splat(-5.0));
            let (y, max) = (Vec4::splat(2.0), Vec4::splat(5.0));
            let four = f.cast_down_four(x, y, z, max).map(|h| h.map(f32::to_bits));
            let one: [Option<u32>; 4] = core::array::from_fn(|l| {
                f.cast_down_point(Vec3::new(x[l], y[l], z[l]), max[l])
                    .map(|h| h.y.to_bits())
            });
            assert_eq!(four, one, "{k}");
            let cells: [(usize, usize); 4] = core::array::from_fn(|l| {
                let (i, j, _, _) = f.locate(x[l], z[l]).unwrap();
                (i, j)
            });
            if cells.iter().all(|&c| c == cells[0]) {
                one_cell += 1;
            } else {
                several += 1;
            }
        }
        assert!(
            one_cell > 100 && several > 10,
            "{one_cell} in one cell, {several} not"
        );
    }

    #[test]
    fn four_lookups_on_a_grid_too_large_for_float_indices_are_four_lookups() {
        // 2,900² samples, more than 2²³: each ray is looked up alone (the same heights).
        let n = 2_900;
        let heights = (0..n * n).map(|k| (k % 7) as f32 * 0.1).collect();
        let f = HeightField::new(Vec2::ZERO, 0.5, n, n, heights).unwrap();
        let x = Vec4::new(0.3, 700.2, 1_449.4, 1_000.0);
        let z = Vec4::new(0.2, 1_200.7, 1_449.5, -1.0);
        let (y, max) = (Vec4::splat(2.0), Vec4::splat(5.0));
        let four = f.cast_down_four(x, y, z, max);
        let one: [Option<f32>; 4] = core::array::from_fn(|l| {
            f.cast_down_point(Vec3::new(x[l], y[l], z[l]), max[l])
                .map(|h| h.y)
        });
        assert_eq!(four, one);
        assert!(four[..3].iter().all(Option::is_some) && four[3].is_none());
    }

    #[test]
    fn height_field_rejects_bad_grids() {
        assert_eq!(
            HeightField::new(Vec2::ZERO, 1.0, 1, 3, vec![0.0; 3]),
            Err(GaitError::GridTooSmall {
                columns: 1,
                rows: 3
            })
        );
        assert!(matches!(
            HeightField::new(Vec2::ZERO, 1.0, 2, 2, vec![0.0; 3]),
            Err(GaitError::WrongLength { .. })
        ));
        assert!(matches!(
            HeightField::new(Vec2::ZERO, 0.0, 2, 2, vec![0.0; 4]),
            Err(GaitError::NotPositive { .. })
        ));
        assert!(matches!(
            HeightField::new(Vec2::ZERO, 1.0, 2, 2, vec![0.0, f32::NAN, 0.0, 0.0]),
            Err(GaitError::NonFinite { index: 1, .. })
        ));
    }

    #[test]
    fn bilinear_height_matches_samples_and_midpoints() {
        let f = HeightField::new(Vec2::ZERO, 2.0, 2, 2, vec![0.0, 1.0, 2.0, 5.0]).unwrap();
        assert_eq!(f.height(0.0, 0.0), Some(0.0));
        assert_eq!(f.height(2.0, 2.0), Some(5.0));
        assert_eq!(f.height(1.0, 1.0), Some(2.0));
        assert_eq!(f.height(2.1, 1.0), None);
    }

    #[test]
    fn vertical_ray_returns_the_bilinear_height() {
        let f = bumpy();
        for k in 0..50 {
            let x = -4.9 + k as f32 * 0.19;
            let z = 4.7 - k as f32 * 0.17;
            let hit = f.cast_ray(Vec3::new(x, 5.0, z), Vec3::NEG_Y, 20.0).unwrap();
            assert_eq!(hit.point.y, f.height(x, z).unwrap());
            assert_eq!((hit.point.x, hit.point.z), (x, z));
        }
    }

    #[test]
    fn slanted_rays_land_on_the_surface() {
        let f = bumpy();
        let mut hits = 0;
        for k in 0..200 {
            let a = k as f32 * 0.37;
            let origin = Vec3::new(
                -4.0 + (k % 17) as f32 * 0.5,
                3.0,
                -4.0 + (k % 13) as f32 * 0.6,
            );
            let direction = Vec3::new(crate::math::cos(a), -1.5, crate::math::sin(a)).normalize();
            if let Some(hit) = f.cast_ray(origin, direction, 20.0) {
                hits += 1;
                let h = f.height(hit.point.x, hit.point.z).unwrap();
                assert!((hit.point.y - h).abs() < 1e-4, "{} vs {h}", hit.point.y);
                assert!((origin + direction * hit.distance).distance(hit.point) < 1e-4);
                // Nothing above the surface was skipped: sample the ray before the hit.
                for q in 1..40 {
                    let p = origin + direction * (hit.distance * q as f32 / 40.0 - 1e-3);
                    if let Some(h) = f.height(p.x, p.z) {
                        assert!(p.y >= h - 1e-3, "ray passed below the surface at {p}");
                    }
                }
            }
        }
        assert!(hits > 150, "{hits}");
    }

    #[test]
    fn cast_down_point_is_the_point_of_valid_hits_only() {
        let f = bumpy();
        for k in 0..50 {
            let origin = Vec3::new(
                -4.9 + k as f32 * 0.19,
                5.0 - 0.2 * k as f32,
                4.7 - k as f32 * 0.17,
            );
            let hit = f.cast_down(origin, 20.0);
            assert_eq!(f.cast_down_point(origin, 20.0), hit.map(|h| h.point));
        }
        // A hit 6e38 below: its distance overflows to infinity, which no valid hit has.
        let steep = HeightField::new(Vec2::ZERO, 1.0, 2, 2, vec![-3e38, 0.0, 0.0, 0.0]).unwrap();
        let origin = Vec3::new(0.0, 3e38, 0.0);
        let hit = steep.cast_down(origin, f32::INFINITY).unwrap();
        assert!(!hit.is_valid());
        assert_eq!(steep.cast_down_point(origin, f32::INFINITY), None);
    }

    #[test]
    fn cast_down_checks_as_cast_ray_does() {
        // Non-finite coordinates, signed zeros on a zero height, and NaN, negative and infinite
        // lengths: `cast_down` finds what `cast_ray` straight down finds, and `cast_down_point`
        // the point of its valid hits, though they check less up front.
        let flat = HeightField::new(Vec2::ZERO, 1.0, 2, 2, vec![0.0; 4]).unwrap();
        let steep = HeightField::new(Vec2::ZERO, 1.0, 2, 2, vec![-3e38, 0.0, 0.0, 0.0]).unwrap();
        let odd = [
            0.0,
            -0.0,
            0.5,
            3e38,
            -3e38,
            f32::INFINITY,
            -f32::INFINITY,
            f32::NAN,
        ];
        let lengths = [
            20.0,
            0.0,
            -0.0,
            -1.0,
            f32::INFINITY,
            -f32::INFINITY,
            f32::NAN,
        ];
        for field in [&flat, &steep] {
            for (x, y, z) in odd
                .iter()
                .flat_map(|&x| odd.iter().flat_map(move |&y| [(x, y, 0.25), (0.25, y, x)]))
            {
                for max in lengths {
                    let origin = Vec3::new(x, y, z);
                    let down = field.cast_down(origin, max);
                    assert_eq!(
                        down,
                        field.cast_ray(origin, Vec3::NEG_Y, max),
                        "{origin} {max}"
                    );
                    let valid = down.filter(RayHit::is_valid).map(|h| h.point);
                    assert_eq!(field.cast_down_point(origin, max), valid, "{origin} {max}");
                }
            }
        }
    }

    #[test]
    fn rays_outside_or_below_miss() {
        let f = bumpy();
        assert!(
            f.cast_ray(Vec3::new(50.0, 5.0, 0.0), Vec3::NEG_Y, 20.0)
                .is_none()
        );
        assert!(
            f.cast_ray(Vec3::new(0.0, -5.0, 0.0), Vec3::NEG_Y, 20.0)
                .is_none()
        );
        assert!(
            f.cast_ray(Vec3::new(0.0, 5.0, 0.0), Vec3::NEG_Y, 1.0)
                .is_none()
        );
        assert!(
            f.cast_ray(Vec3::new(0.0, 5.0, 0.0), Vec3::Y, 10.0)
                .is_none()
        );
    }

    #[test]
    fn ray_from_outside_the_grid_enters_it() {
        let f = HeightField::new(Vec2::ZERO, 1.0, 3, 3, vec![0.0; 9]).unwrap();
        let hit = f
            .cast_ray(
                Vec3::new(-1.0, 1.0, 1.0),
                Vec3::new(1.0, -0.5, 0.0).normalize(),
                10.0,
            )
            .unwrap();
        assert!((hit.point - Vec3::new(1.0, 0.0, 1.0)).length() < 1e-5);
    }
}
