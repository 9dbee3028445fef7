//! Deterministic procedural noise for the base textures: integer hashing, value noise and
//! cellular (Worley) noise. No tables, no float transcendental functions.

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

/// Cellular noise: distances to the nearest and second-nearest jittered cell points (the
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

    /// The noise at `p` (clamped into `[0, 1]²`).
    #[inline]
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

    /// Distances to the nearest and second-nearest point from `p` (clamped into `[0, 1]²`).
    #[inline]
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
        (Vec2::new(d1, 0.0).length(), Vec2::new(d2, 0.0).length())
    }
}

/// The procedural base textures of one render, tables built once.
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
    /// fine grain.
    pub(crate) fn wood(&self, p: Vec2) -> f32 {
        let centre = Vec2::new(0.5, -0.35);
        let r = (p - centre).length() * 14.0 + self.warp.at(p) * 0.9;
        let t = r - floor_i(r) as f32;
        // A soft triangle wave: dark thin rings on light wood.
        let ring = smooth((2.0 * t - 1.0).abs());
        0.58 + 0.3 * ring + 0.12 * self.grain.at(p)
    }

    /// The ice-like base texture at `p`, in roughly `[0.62, 1]`: pale cells with bright cracks
    /// between them and a faint frost.
    pub(crate) fn ice(&self, p: Vec2) -> f32 {
        let (d1, d2) = self.cells.at(p);
        let edge = (d2 - d1).min(0.25) * 4.0; // 0 on a crack, 1 inside a cell
        let crack = 1.0 - smooth(edge);
        0.62 + 0.1 * d1.min(1.0) + 0.2 * crack + 0.08 * self.frost.at(p)
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
