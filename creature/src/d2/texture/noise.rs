//! Deterministic procedural noise for the base textures: integer hashing, value noise and
//! cellular (Worley) noise from small hashed lattice tables, looked up point by point or row
//! by row (the texture pass's fast path). No float transcendental functions.

use alloc::vec::Vec;

use glam::Vec2;

use crate::math::{max, min};

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

    /// The table interpolated in x at the points `xs` (each clamped to `[0, 1]`), lattice row
    /// by lattice row: [`Expanded::row`] then only interpolates in y, a contiguous run the
    /// compiler vectorises.
    pub(crate) fn expand(&self, xs: &[f32]) -> Expanded {
        // Each point's lattice column (at most `scale.x`, so it and the next are in the table)
        // and smoothed weight, then row by row a plain lerp.
        let weights: Vec<(usize, f32)> = xs
            .iter()
            .map(|&x| {
                let q = x.clamp(0.0, 1.0) * self.scale.x;
                let ix = q as usize;
                (ix, smooth(q - ix as f32))
            })
            .collect();
        let rows = self.values.len() / self.columns.max(1);
        let mut values = Vec::with_capacity(rows * xs.len());
        for lattice in self.values.chunks_exact(self.columns) {
            values.extend(weights.iter().map(|&(ix, fx)| {
                let (a, b) = (lattice[ix], lattice[ix + 1]);
                a + (b - a) * fx
            }));
        }
        Expanded {
            scale_y: self.scale.y,
            width: xs.len(),
            values,
        }
    }
}

/// A [`ValueTable`] interpolated in x at fixed points (see [`ValueTable::expand`]).
pub(crate) struct Expanded {
    scale_y: f32,
    width: usize,
    values: Vec<f32>,
}

impl Expanded {
    /// The two x-interpolated lattice rows around height `y` (clamped to `[0, 1]`) and the
    /// weight of the upper one: the noise at point `i` is `a[i] + (b[i] − a[i]) · w`.
    #[inline]
    pub(crate) fn row(&self, y: f32) -> (&[f32], &[f32], f32) {
        let q = y.clamp(0.0, 1.0) * self.scale_y;
        let iy = q as usize;
        let w = smooth(q - iy as f32);
        // `iy` is at most `scale_y`: it and the next row are in the table.
        let start = iy * self.width;
        let (a, b) = (
            &self.values[start..start + self.width],
            &self.values[start + self.width..start + 2 * self.width],
        );
        (a, b, w)
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
    fn row(&self, y: f32, out: &mut CellRow) {
        let q = y.clamp(0.0, 1.0) * self.scale;
        let iy = q as usize + 1;
        out.x.clear();
        out.dy2.clear();
        for column in 0..self.columns {
            let mut x = [0.0; 3];
            let mut dy2 = [f32::MAX; 3];
            // Rows up to `scale + 2`, of the `scale + 4` stored.
            for (k, row) in (iy - 1..=iy + 1).enumerate() {
                let point = self.points[row * self.columns + column];
                x[k] = point.x;
                dy2[k] = (point.y - q) * (point.y - q);
            }
            out.x.push(x);
            out.dy2.push(dy2);
        }
    }

    /// The 9 candidate feature points (x, squared y distance) of the points whose x falls in
    /// lattice column `ix − 1` (stored as `ix`, from 1 to `scale + 1`), on a row made by
    /// [`Self::row`].
    #[inline]
    fn candidates(row: &CellRow, ix: usize) -> ([f32; 9], [f32; 9]) {
        let mut xs = [0.0; 9];
        let mut dy2s = [f32::MAX; 9];
        let (x, dy2) = (&row.x[ix - 1..=ix + 1], &row.dy2[ix - 1..=ix + 1]);
        for ((x, dy2), (xs, dy2s)) in x
            .iter()
            .zip(dy2)
            .zip(xs.chunks_exact_mut(3).zip(dy2s.chunks_exact_mut(3)))
        {
            xs.copy_from_slice(x);
            dy2s.copy_from_slice(dy2);
        }
        (xs, dy2s)
    }
}

/// One row of [`CellTable`]'s candidate feature points (see [`CellTable::row`]).
#[derive(Default)]
struct CellRow {
    x: Vec<[f32; 3]>,
    dy2: Vec<[f32; 3]>,
}

/// The centre of the wood texture's rings (below the square frame, so the rings arc).
const WOOD_CENTRE: Vec2 = Vec2::new(0.5, -0.35);

/// The lattice tables of the base textures.
struct Tables {
    warp: ValueTable,
    grain: ValueTable,
    cells: CellTable,
    frost: ValueTable,
}

impl Tables {
    fn new(seed: u32) -> Self {
        Self {
            warp: ValueTable::new(Vec2::splat(5.0), seed),
            grain: ValueTable::new(Vec2::new(60.0, 6.0), seed ^ 0x9e37_79b9),
            cells: CellTable::new(7.0, seed ^ 0x7f4a_7c15),
            frost: ValueTable::new(Vec2::splat(24.0), seed ^ 0x2545_f491),
        }
    }

    /// The wood-like base texture at `p` (the creature's square frame, `[0, 1]²`), in roughly
    /// `[0.58, 1]`: rings around a point below the creature, warped by value noise, with a
    /// fine grain. The reference [`BaseTextures::wood_row`] is tested against.
    #[cfg(test)]
    fn wood(&self, p: Vec2) -> f32 {
        let r = (p - WOOD_CENTRE).length() * 14.0 + self.warp.at(p) * 0.9;
        let t = r - floor_i(r) as f32;
        // A soft triangle wave: dark thin rings on light wood.
        let ring = smooth((2.0 * t - 1.0).abs());
        0.58 + 0.3 * ring + 0.12 * self.grain.at(p)
    }

    /// The ice-like base texture at `p`, in roughly `[0.62, 1]`: pale cells with bright cracks
    /// between them and a faint frost. The reference [`BaseTextures::ice_row`] is tested
    /// against.
    #[cfg(test)]
    fn ice(&self, p: Vec2) -> f32 {
        let (d1, d2) = self.cells.at(p);
        let edge = (d2 - d1).min(0.25) * 4.0; // 0 on a crack, 1 inside a cell
        let crack = 1.0 - smooth(edge);
        0.62 + 0.1 * d1.min(1.0) + 0.2 * crack + 0.08 * self.frost.at(p)
    }
}

/// The procedural base textures of one render at fixed x coordinates (the image's columns):
/// the value noise interpolated in x once per render ([`ValueTable::expand`]), the cellular
/// noise's columns grouped by lattice cell, so a row costs a few vector operations per point.
pub(crate) struct BaseTextures {
    cells: CellTable,
    warp: Expanded,
    grain: Expanded,
    frost: Expanded,
    /// Per point: the squared x distance to the wood's centre.
    wood_dx2: Vec<f32>,
    /// Per point: x in cellular-noise cells (clamped into the frame).
    cell_x: Vec<f32>,
    /// Runs of points in one lattice column: the run's end and the column (stored from 1).
    cell_runs: Vec<(usize, usize)>,
}

/// One row of the base textures (see [`BaseTextures::row`]): reused from row to row.
#[derive(Default)]
pub(crate) struct BaseRow {
    y: f32,
    cells: CellRow,
}

impl BaseTextures {
    /// The base textures of seed `seed` at the points whose x (in the square frame) are `xs`.
    pub(crate) fn new(seed: u32, xs: &[f32]) -> Self {
        let tables = Tables::new(seed);
        let cell_x: Vec<f32> = xs
            .iter()
            .map(|&x| x.clamp(0.0, 1.0) * tables.cells.scale)
            .collect();
        let mut cell_runs: Vec<(usize, usize)> = Vec::new();
        for (i, &q) in cell_x.iter().enumerate() {
            let ix = q as usize + 1;
            match cell_runs.last_mut() {
                Some((end, last)) if *last == ix => *end = i + 1,
                _ => cell_runs.push((i + 1, ix)),
            }
        }
        Self {
            warp: tables.warp.expand(xs),
            grain: tables.grain.expand(xs),
            frost: tables.frost.expand(xs),
            wood_dx2: xs
                .iter()
                .map(|&x| (x - WOOD_CENTRE.x) * (x - WOOD_CENTRE.x))
                .collect(),
            cell_x,
            cell_runs,
            cells: tables.cells,
        }
    }

    /// Prepares `row` for the points `(x, y)` of one image row.
    pub(crate) fn row(&self, y: f32, row: &mut BaseRow) {
        row.y = y;
        self.cells.row(y, &mut row.cells);
    }

    /// The wood-like texture ([`Tables::wood`] up to rounding) at the points `range` of `row`,
    /// into `out` (one value per point of `range`).
    pub(crate) fn wood_row(&self, row: &BaseRow, range: core::ops::Range<usize>, out: &mut [f32]) {
        let (wa, wb, ww) = self.warp.row(row.y);
        let (ga, gb, gw) = self.grain.row(row.y);
        let dy = row.y - WOOD_CENTRE.y;
        let dy2 = dy * dy;
        let (wa, wb) = (&wa[range.clone()], &wb[range.clone()]);
        let (ga, gb) = (&ga[range.clone()], &gb[range.clone()]);
        let dx2 = &self.wood_dx2[range];
        let points = wa.iter().zip(wb).zip(ga.iter().zip(gb)).zip(dx2).zip(out);
        for ((((&wa, &wb), (&ga, &gb)), &dx2), out) in points {
            let warp = wa + (wb - wa) * ww;
            let r = crate::math::sqrt(dx2 + dy2) * 14.0 + warp * 0.9;
            // 0 ≤ r < 30 (a distance in the frame ×14 plus a value in [0, 1)).
            let t = r - crate::math::floor_f(r);
            let ring = smooth((2.0 * t - 1.0).abs());
            *out = 0.58 + 0.3 * ring + 0.12 * (ga + (gb - ga) * gw);
        }
    }

    /// The ice-like texture ([`Tables::ice`] up to rounding) at the points `range` of `row`,
    /// into `out` (one value per point of `range`): lattice column by lattice column, each
    /// point against the column's 9 candidate feature points.
    pub(crate) fn ice_row(&self, row: &BaseRow, range: core::ops::Range<usize>, out: &mut [f32]) {
        let (fa, fb, fw) = self.frost.row(row.y);
        let mut start = 0;
        for &(end, ix) in &self.cell_runs {
            let run = start.max(range.start)..end.min(range.end);
            start = end;
            if run.is_empty() {
                continue;
            }
            let (xs, dy2s) = CellTable::candidates(&row.cells, ix);
            let local = run.start - range.start..run.end - range.start;
            let (q, fa, fb) = (&self.cell_x[run.clone()], &fa[run.clone()], &fb[run]);
            let out = &mut out[local];
            for (((&q, &fa), &fb), out) in q.iter().zip(fa).zip(fb).zip(out) {
                let mut d1 = f32::MAX;
                let mut d2 = f32::MAX;
                for (&px, &dy2) in xs.iter().zip(&dy2s) {
                    let dx = px - q;
                    let d = dx * dx + dy2;
                    d2 = min(d2, max(d1, d));
                    d1 = min(d1, d);
                }
                let edge = min(d2 - d1, 0.25) * 4.0; // 0 on a crack, 1 inside a cell
                let crack = 1.0 - smooth(edge);
                *out = 0.62 + 0.1 * min(d1, 1.0) + 0.2 * crack + 0.08 * (fa + (fb - fa) * fw);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

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
        // A little outside [0, 1] too: clamped alike.
        let xs: Vec<f32> = (0..97).map(|i| i as f32 / 90.0 - 0.03).collect();
        let tables = Tables::new(5);
        let base = BaseTextures::new(5, &xs);
        let expanded = tables.grain.expand(&xs);
        let mut row = BaseRow::default();
        let (mut wood, mut ice) = (vec![0.0; xs.len()], vec![0.0; xs.len()]);
        for j in 0..23 {
            let y = j as f32 / 20.0 - 0.05;
            base.row(y, &mut row);
            base.wood_row(&row, 0..xs.len(), &mut wood);
            // A part of the row too: runs of cells cut at both ends.
            base.ice_row(&row, 0..xs.len(), &mut ice);
            let mut part = vec![0.0; 50];
            base.ice_row(&row, 20..70, &mut part);
            assert_eq!(&part[..], &ice[20..70]);
            let (a, b, w) = expanded.row(y);
            for (i, &x) in xs.iter().enumerate() {
                let p = Vec2::new(x, y);
                assert!((wood[i] - tables.wood(p)).abs() < 1e-4, "{p}");
                assert!((ice[i] - tables.ice(p)).abs() < 1e-4, "{p}");
                assert!(
                    (a[i] + (b[i] - a[i]) * w - tables.grain.at(p)).abs() < 1e-5,
                    "{p}"
                );
            }
        }
    }

    #[test]
    fn noises_stay_in_range_and_vary() {
        let base = Tables::new(3);
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
