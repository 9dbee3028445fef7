//! Deterministic procedural noise for the base textures: integer hashing, value noise and
//! cellular (Worley) noise from small hashed lattice tables, looked up point by point or row
//! by row (the texture pass's fast path). No float transcendental functions.

use alloc::vec::Vec;

use glam::Vec2;

/// `floor` for the moderate magnitudes used here (core has no float `floor` without `std`).
#[inline]
pub(crate) fn floor_i(x: f32) -> i32 {
    let i = x as i32;
    if (i as f32) > x { i - 1 } else { i }
}

/// A 32-bit integer hash of a lattice point (a murmur3-style finaliser).
#[inline]
fn hash(x: i32, y: i32, seed: u32) -> u32 {
    let mut h = (x as u32).wrapping_mul(0x8da6_b343)
        ^ (y as u32).wrapping_mul(0xd816_3841)
        ^ seed.wrapping_mul(0xcb1a_b31f);
    h ^= h >> 16;
    h = h.wrapping_mul(0x85eb_ca6b);
    h ^= h >> 13;
    h = h.wrapping_mul(0xc2b2_ae35);
    h ^ (h >> 16)
}

/// A hash as a float in `[0, 1)`.
#[inline]
fn unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

#[inline]
fn smooth(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
}

/// Value noise in `[0, 1)`: hashed lattice values, smoothly interpolated (the reference the
/// tables are tested against).
#[cfg(test)]
pub(crate) fn value(p: Vec2, seed: u32) -> f32 {
    let (ix, iy) = (floor_i(p.x), floor_i(p.y));
    let (fx, fy) = (smooth(p.x - ix as f32), smooth(p.y - iy as f32));
    let a = unit(hash(ix, iy, seed));
    let b = unit(hash(ix + 1, iy, seed));
    let c = unit(hash(ix, iy + 1, seed));
    let d = unit(hash(ix + 1, iy + 1, seed));
    let bottom = a + (b - a) * fx;
    let top = c + (d - c) * fx;
    bottom + (top - bottom) * fy
}

/// Cellular noise: squared distances to the nearest and second-nearest jittered cell points (the
/// reference [`CellTable`] is tested against).
#[cfg(test)]
pub(crate) fn cells(p: Vec2, seed: u32) -> (f32, f32) {
    let (ix, iy) = (floor_i(p.x), floor_i(p.y));
    let mut d1 = f32::MAX;
    let mut d2 = f32::MAX;
    for dy in -1..=1 {
        for dx in -1..=1 {
            let (cx, cy) = (ix + dx, iy + dy);
            let h = hash(cx, cy, seed);
            let jitter = Vec2::new(unit(h), unit(h.rotate_left(13) ^ 0x5bd1_e995));
            let d = (Vec2::new(cx as f32, cy as f32) + jitter).distance_squared(p);
            if d < d1 {
                d2 = d1;
                d1 = d;
            } else if d < d2 {
                d2 = d;
            }
        }
    }
    (Vec2::new(d1, 0.0).length(), Vec2::new(d2, 0.0).length())
}

/// Value noise over `[0, 1]²` scaled by `scale`, its lattice values hashed once into a table:
/// the same values as [`value`] at `p * scale`, without hashing per sample.
pub(crate) struct ValueTable {
    scale: Vec2,
    columns: usize,
    values: Vec<f32>,
}

impl ValueTable {
    pub(crate) fn new(scale: Vec2, seed: u32) -> Self {
        let columns = scale.x as usize + 3;
        let rows = scale.y as usize + 3;
        let mut values = Vec::with_capacity(columns * rows);
        for y in 0..rows {
            for x in 0..columns {
                values.push(unit(hash(x as i32, y as i32, seed)));
            }
        }
        Self {
            scale,
            columns,
            values,
        }
    }

    /// The noise at `p` (clamped into `[0, 1]²`): the reference [`Self::at_row`] is tested
    /// against.
    #[cfg(test)]
    pub(crate) fn at(&self, p: Vec2) -> f32 {
        let q = p.clamp(Vec2::ZERO, Vec2::ONE) * self.scale;
        let (ix, iy) = (q.x as usize, q.y as usize);
        let (fx, fy) = (smooth(q.x - ix as f32), smooth(q.y - iy as f32));
        let i = iy * self.columns + ix;
        let get = |i: usize| self.values.get(i).copied().unwrap_or(0.0);
        let (a, b) = (get(i), get(i + 1));
        let (c, d) = (get(i + self.columns), get(i + self.columns + 1));
        let bottom = a + (b - a) * fx;
        let top = c + (d - c) * fx;
        bottom + (top - bottom) * fy
    }

    /// One row of the noise at height `y` (clamped to `[0, 1]`, like [`Self::at`]): the two
    /// lattice rows around it interpolated in y, so [`Self::at_row`] only interpolates in x.
    pub(crate) fn row(&self, y: f32, out: &mut Vec<f32>) {
        let q = y.clamp(0.0, 1.0) * self.scale.y;
        let iy = q as usize;
        let fy = smooth(q - iy as f32);
        let start = iy * self.columns;
        out.clear();
        let (Some(bottom), Some(top)) = (
            self.values.get(start..start + self.columns),
            self.values
                .get(start + self.columns..start + 2 * self.columns),
        ) else {
            out.resize(self.columns, 0.0);
            return;
        };
        out.extend(bottom.iter().zip(top).map(|(&a, &c)| a + (c - a) * fy));
    }

    /// The noise at `x` (clamped to `[0, 1]`) on a row made by [`Self::row`]: equal to
    /// [`Self::at`] up to rounding.
    #[inline]
    pub(crate) fn at_row(&self, row: &[f32], x: f32) -> f32 {
        let q = x.clamp(0.0, 1.0) * self.scale.x;
        let ix = q as usize;
        let fx = smooth(q - ix as f32);
        match row.get(ix..ix + 2) {
            Some(&[a, b]) => a + (b - a) * fx,
            _ => 0.0,
        }
    }
}

/// Cellular noise over `[0, 1]²` scaled by `scale`, its jittered points hashed once.
pub(crate) struct CellTable {
    scale: f32,
    columns: usize,
    points: Vec<Vec2>,
}

impl CellTable {
    pub(crate) fn new(scale: f32, seed: u32) -> Self {
        // Cells −1 ..= scale + 1, stored from 0.
        let columns = scale as usize + 4;
        let mut points = Vec::with_capacity(columns * columns);
        for y in 0..columns {
            for x in 0..columns {
                let (cx, cy) = (x as i32 - 1, y as i32 - 1);
                let h = hash(cx, cy, seed);
                let jitter = Vec2::new(unit(h), unit(h.rotate_left(13) ^ 0x5bd1_e995));
                points.push(Vec2::new(cx as f32, cy as f32) + jitter);
            }
        }
        Self {
            scale,
            columns,
            points,
        }
    }

    /// Squared distances (in lattice cells) to the nearest and second-nearest point from `p`
    /// (clamped into `[0, 1]²`): the reference [`Self::at_row`] is tested against.
    #[cfg(test)]
    pub(crate) fn at(&self, p: Vec2) -> (f32, f32) {
        let q = p.clamp(Vec2::ZERO, Vec2::ONE) * self.scale;
        let (ix, iy) = (q.x as usize + 1, q.y as usize + 1);
        let mut d1 = f32::MAX;
        let mut d2 = f32::MAX;
        for y in iy - 1..=iy + 1 {
            for x in ix - 1..=ix + 1 {
                let Some(point) = self.points.get(y * self.columns + x) else {
                    continue;
                };
                let d = point.distance_squared(q);
                if d < d1 {
                    d2 = d1;
                    d1 = d;
                } else if d < d2 {
                    d2 = d;
                }
            }
        }
        (d1, d2)
    }

    /// The feature points that can be nearest on the row at height `y` (clamped to
    /// `[0, 1]`): per lattice column, the three candidate rows' x and squared y distance.
    pub(crate) fn row(&self, y: f32, out: &mut CellRow) {
        let q = y.clamp(0.0, 1.0) * self.scale;
        let iy = q as usize + 1;
        out.x.clear();
        out.dy2.clear();
        for column in 0..self.columns {
            let mut x = [0.0; 3];
            let mut dy2 = [f32::MAX; 3];
            for (k, row) in (iy - 1..=iy + 1).enumerate() {
                if let Some(point) = self.points.get(row * self.columns + column) {
                    x[k] = point.x;
                    dy2[k] = (point.y - q) * (point.y - q);
                }
            }
            out.x.push(x);
            out.dy2.push(dy2);
        }
    }

    /// The squared distances to the nearest and second-nearest feature points at `x` (clamped to
    /// `[0, 1]`) on a row made by [`Self::row`]: equal to [`Self::at`]. Branch-free.
    #[inline]
    pub(crate) fn at_row(&self, row: &CellRow, x: f32) -> (f32, f32) {
        let q = x.clamp(0.0, 1.0) * self.scale;
        let ix = q as usize + 1;
        let mut d1 = f32::MAX;
        let mut d2 = f32::MAX;
        if let (Some(xs), Some(dy2s)) = (row.x.get(ix - 1..=ix + 1), row.dy2.get(ix - 1..=ix + 1)) {
            for (xs, dy2s) in xs.iter().zip(dy2s) {
                for (&px, &dy2) in xs.iter().zip(dy2s) {
                    let dx = px - q;
                    let d = dx * dx + dy2;
                    d2 = d2.min(d1.max(d));
                    d1 = d1.min(d);
                }
            }
        }
        (d1, d2)
    }
}

/// One row of [`CellTable`]'s candidate feature points (see [`CellTable::row`]).
#[derive(Default)]
pub(crate) struct CellRow {
    x: Vec<[f32; 3]>,
    dy2: Vec<[f32; 3]>,
}

/// One row of the base textures (see [`BaseTextures::row`]): reused from row to row.
#[derive(Default)]
pub(crate) struct BaseRow {
    y: f32,
    warp: Vec<f32>,
    grain: Vec<f32>,
    frost: Vec<f32>,
    cells: CellRow,
}

/// The procedural base textures of one render, tables built once.
/// The centre of the wood texture's rings (below the square frame, so the rings arc).
const WOOD_CENTRE: Vec2 = Vec2::new(0.5, -0.35);

pub(crate) struct BaseTextures {
    warp: ValueTable,
    grain: ValueTable,
    cells: CellTable,
    frost: ValueTable,
}

impl BaseTextures {
    pub(crate) fn new(seed: u32) -> Self {
        Self {
            warp: ValueTable::new(Vec2::splat(5.0), seed),
            grain: ValueTable::new(Vec2::new(60.0, 6.0), seed ^ 0x9e37_79b9),
            cells: CellTable::new(7.0, seed ^ 0x7f4a_7c15),
            frost: ValueTable::new(Vec2::splat(24.0), seed ^ 0x2545_f491),
        }
    }

    /// The wood-like base texture at `p` (the creature's square frame, `[0, 1]²`), in roughly
    /// `[0.58, 1]`: rings around a point below the creature, warped by value noise, with a
    /// fine grain. The reference [`Self::wood_at`] is tested against.
    #[cfg(test)]
    pub(crate) fn wood(&self, p: Vec2) -> f32 {
        let r = (p - WOOD_CENTRE).length() * 14.0 + self.warp.at(p) * 0.9;
        let t = r - floor_i(r) as f32;
        // A soft triangle wave: dark thin rings on light wood.
        let ring = smooth((2.0 * t - 1.0).abs());
        0.58 + 0.3 * ring + 0.12 * self.grain.at(p)
    }

    /// The ice-like base texture at `p`, in roughly `[0.62, 1]`: pale cells with bright cracks
    /// between them and a faint frost. The reference [`Self::ice_at`] is tested against.
    #[cfg(test)]
    pub(crate) fn ice(&self, p: Vec2) -> f32 {
        let (d1, d2) = self.cells.at(p);
        let edge = (d2 - d1).min(0.25) * 4.0; // 0 on a crack, 1 inside a cell
        let crack = 1.0 - smooth(edge);
        0.62 + 0.1 * d1.min(1.0) + 0.2 * crack + 0.08 * self.frost.at(p)
    }

    /// Prepares `row` for the points `(x, y)` of one image row: [`Self::wood_at`] and
    /// [`Self::ice_at`] then cost a few table look-ups and one or two square roots.
    pub(crate) fn row(&self, y: f32, row: &mut BaseRow) {
        row.y = y;
        self.warp.row(y, &mut row.warp);
        self.grain.row(y, &mut row.grain);
        self.frost.row(y, &mut row.frost);
        self.cells.row(y, &mut row.cells);
    }

    /// [`Self::wood`] at `(x, row's y)`, up to rounding.
    #[inline]
    pub(crate) fn wood_at(&self, row: &BaseRow, x: f32) -> f32 {
        let (dx, dy) = (x - WOOD_CENTRE.x, row.y - WOOD_CENTRE.y);
        let r = crate::math::sqrt(dx * dx + dy * dy) * 14.0 + self.warp.at_row(&row.warp, x) * 0.9;
        // r ≥ 0 (a distance plus a value in [0, 1)): truncation is the floor.
        let t = r - (r as i32) as f32;
        let ring = smooth((2.0 * t - 1.0).abs());
        0.58 + 0.3 * ring + 0.12 * self.grain.at_row(&row.grain, x)
    }

    /// [`Self::ice`] at `(x, row's y)`, up to rounding.
    #[inline]
    pub(crate) fn ice_at(&self, row: &BaseRow, x: f32) -> f32 {
        let (d1, d2) = self.cells.at_row(&row.cells, x);
        let edge = (d2 - d1).min(0.25) * 4.0;
        let crack = 1.0 - smooth(edge);
        0.62 + 0.1 * d1.min(1.0) + 0.2 * crack + 0.08 * self.frost.at_row(&row.frost, x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_matches_the_definition() {
        assert_eq!(floor_i(1.5), 1);
        assert_eq!(floor_i(-1.5), -2);
        assert_eq!(floor_i(-2.0), -2);
        assert_eq!(floor_i(0.0), 0);
    }

    #[test]
    fn tables_match_the_hashed_noise() {
        let t = ValueTable::new(Vec2::new(60.0, 6.0), 11);
        let c = CellTable::new(7.0, 11);
        for i in 0..300 {
            let p = Vec2::new((i % 17) as f32 / 16.0, (i / 17) as f32 / 17.6);
            assert!((t.at(p) - value(p * Vec2::new(60.0, 6.0), 11)).abs() < 1e-5);
            let (a, b) = c.at(p);
            let (x, y) = cells(p * 7.0, 11);
            assert!((a - x).abs() < 1e-4 && (b - y).abs() < 1e-4, "{p}");
        }
    }

    #[test]
    fn rows_match_the_point_lookups() {
        let base = BaseTextures::new(5);
        let mut row = BaseRow::default();
        for j in 0..23 {
            let y = j as f32 / 20.0 - 0.05; // a little outside [0, 1] too: clamped alike
            base.row(y, &mut row);
            for i in 0..97 {
                let x = i as f32 / 90.0 - 0.03;
                let p = Vec2::new(x, y);
                assert!((base.wood_at(&row, x) - base.wood(p)).abs() < 1e-4, "{p}");
                assert!((base.ice_at(&row, x) - base.ice(p)).abs() < 1e-4, "{p}");
                let (a, b) = base.cells.at_row(&row.cells, x);
                let (c, d) = base.cells.at(p);
                assert_eq!((a, b), (c, d), "{p}");
            }
        }
    }

    #[test]
    fn noises_stay_in_range_and_vary() {
        let base = BaseTextures::new(3);
        let mut lo = f32::MAX;
        let mut hi = f32::MIN;
        for i in 0..400 {
            let p = Vec2::new((i % 20) as f32 * 0.05, (i / 20) as f32 * 0.05);
            for v in [value(p, 3), base.wood(p), base.ice(p)] {
                assert!(v.is_finite() && (0.0..=1.0).contains(&v), "{v}");
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        assert!(hi - lo > 0.3);
    }
}
