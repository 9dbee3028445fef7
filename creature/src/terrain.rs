//! Procedural terrain: rolling hills on an overall slope, cut into steps, as a
//! [`HeightField`] any gait controller walks on (it is a
//! [`Ground`](crate::gait::Ground)).
//!
//! ```
//! use creature::terrain::{terrain, TerrainParams};
//! use creature::gait::Ground;
//! use creature::glam::Vec3;
//!
//! let ground = terrain(7, &TerrainParams::DEFAULT)?;
//! let hit = ground.cast_ray(Vec3::new(1.0, 50.0, 2.0), Vec3::NEG_Y, 100.0).expect("on the terrain");
//! assert!(hit.point.y.is_finite());
//! // Same seed and parameters, same terrain.
//! assert_eq!(ground, terrain(7, &TerrainParams::DEFAULT)?);
//! # Ok::<(), creature::Error>(())
//! ```

use alloc::vec::Vec;
use core::f32::consts::TAU;

use glam::Vec2;

use crate::Error;
use crate::gait::HeightField;
use crate::math::{cos, sin, sqrt};
use crate::rng::{rng_for, uniform};
use crate::span::{count, scalar};

/// What [`terrain`] makes: the ground's extent and resolution, its hills, its slope and its
/// steps. Every field has a default and a documented range ([`validate`](Self::validate)).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct TerrainParams {
    /// The side of the square of ground, metres, centred on the origin. `(0, 10000]`.
    /// Default 40.
    pub size: f32,
    /// Samples per side of the height field. `[2, 2049]`. Default 161 (a sample every 0.25 m
    /// at the default size).
    pub samples: u32,
    /// The hills' height from trough to crest, metres. `[0, 1000]`. Default 1.5.
    pub hill_height: f32,
    /// The typical distance between neighbouring hilltops, metres. `[0.01, 10000]`. Default 10.
    pub hill_spacing: f32,
    /// The incline of the overall slope, degrees, toward a direction drawn from the seed.
    /// `[0, 45]`. Default 8.
    pub slope_degrees: f32,
    /// The height of each step, metres (0: no steps). `[0, 100]`. Default 0.2.
    pub step_height: f32,
    /// The distance between neighbouring step edges, metres, across lines drawn from the seed.
    /// `[0.01, 10000]`. Default 4.
    pub step_spacing: f32,
}

impl TerrainParams {
    /// The defaults listed on each field.
    pub const DEFAULT: Self = Self {
        size: 40.0,
        samples: 161,
        hill_height: 1.5,
        hill_spacing: 10.0,
        slope_degrees: 8.0,
        step_height: 0.2,
        step_spacing: 4.0,
    };

    /// Sets [`size`](Self::size) and [`samples`](Self::samples).
    #[must_use]
    pub const fn with_extent(mut self, size: f32, samples: u32) -> Self {
        self.size = size;
        self.samples = samples;
        self
    }

    /// Sets [`hill_height`](Self::hill_height) and [`hill_spacing`](Self::hill_spacing).
    #[must_use]
    pub const fn with_hills(mut self, height: f32, spacing: f32) -> Self {
        self.hill_height = height;
        self.hill_spacing = spacing;
        self
    }

    /// Sets [`slope_degrees`](Self::slope_degrees).
    #[must_use]
    pub const fn with_slope(mut self, degrees: f32) -> Self {
        self.slope_degrees = degrees;
        self
    }

    /// Sets [`step_height`](Self::step_height) and [`step_spacing`](Self::step_spacing).
    #[must_use]
    pub const fn with_steps(mut self, height: f32, spacing: f32) -> Self {
        self.step_height = height;
        self.step_spacing = spacing;
        self
    }

    /// Terrain sized to `creature`, as the `generate` example's `--terrain` makes it: a square
    /// 24 body lengths wide (193 samples a side), hills half its length high and six lengths
    /// apart on a 12° slope, and steps three lengths apart, a fifth of its gait's shortest leg
    /// high (a slitherer's 1.5% of its length, about a third of its body's thickness; a tenth
    /// of its length for another creature without a gait).
    ///
    /// ```
    /// use creature::d3::{generate, Kind, Params};
    /// use creature::terrain::{terrain, TerrainParams};
    ///
    /// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker).with_clips(false))?;
    /// let params = TerrainParams::for_creature(&walker);
    /// assert_eq!(params.size, 24.0 * walker.length);
    /// let ground = terrain(3, &params)?;
    /// assert_eq!(ground.columns(), 193);
    /// # Ok::<(), creature::Error>(())
    /// ```
    #[must_use]
    pub fn for_creature(creature: &crate::d3::Creature) -> Self {
        let length = creature.length;
        let crawls = creature.kind == creature_limbs::CreatureKind::Slitherer;
        let lying = if crawls { 0.015 } else { 0.1 };
        let step = creature.gait.as_ref().map_or(lying * length, |gait| {
            0.2 * gait
                .legs
                .iter()
                .map(|l| l.size)
                .fold(f32::INFINITY, f32::min)
        });
        Self::DEFAULT
            .with_extent(24.0 * length, 193)
            .with_hills(0.5 * length, 6.0 * length)
            .with_slope(12.0)
            .with_steps(step, 3.0 * length)
    }

    /// Checks every field against its documented range; [`terrain`] calls this first.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] naming the field.
    pub fn validate(&self) -> Result<(), Error> {
        scalar("terrain size", self.size, 1e-3, 10_000.0)?;
        count("terrain samples", self.samples, 2, 2049)?;
        scalar("hill height", self.hill_height, 0.0, 1000.0)?;
        scalar("hill spacing", self.hill_spacing, 0.01, 10_000.0)?;
        scalar("slope degrees", self.slope_degrees, 0.0, 45.0)?;
        scalar("step height", self.step_height, 0.0, 100.0)?;
        scalar("step spacing", self.step_spacing, 0.01, 10_000.0)?;
        Ok(())
    }
}

impl Default for TerrainParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Waves summed into the hills.
const HILL_WAVES: usize = 6;

/// The terrain of `seed` and `params`: a height field over the square of side
/// [`size`](TerrainParams::size) centred on the origin, its height at `(x, z)`
///
/// `hills(x, z) + tan(slope) · (x, z)·u + step_height · ⌊(x, z)·v / step_spacing⌋`
///
/// with `u` and `v` unit directions drawn from the seed, and the hills a sum of
/// six sine waves of random directions and phases, wavelengths about twice the hill
/// spacing (the longest first, the amplitudes falling with the wavelength), scaled so that
/// their crest-to-trough height over the terrain is about `hill_height` (at most). A step is a
/// one-sample ramp in the height field (heights are bilinear between samples). Deterministic:
/// the same seed and parameters give the same heights, bit for bit.
///
/// # Errors
/// [`TerrainParams::validate`]'s; [`Error::Gait`] if the height field cannot hold the grid.
pub fn terrain(seed: u64, params: &TerrainParams) -> Result<HeightField, Error> {
    params.validate()?;
    let mut rng = rng_for(seed);
    let mut direction = || {
        let a = TAU * uniform(&mut rng);
        Vec2::new(cos(a), sin(a))
    };
    let slope_direction = direction();
    let step_direction = direction();
    // The waves: direction × wave number, phase and amplitude (the amplitudes sum to half the
    // hill height, so the sum spans at most the hill height).
    let mut waves = [(Vec2::ZERO, 0.0f32, 0.0f32); HILL_WAVES];
    let mut total = 0.0;
    for (k, wave) in waves.iter_mut().enumerate() {
        let wavelength = 2.0 * params.hill_spacing / (1.0 + 0.6 * k as f32);
        let number = TAU / wavelength;
        let amplitude = 1.0 / (1.0 + k as f32);
        *wave = (direction() * number, 0.0, amplitude);
        total += amplitude;
    }
    for wave in &mut waves {
        wave.1 = TAU * uniform(&mut rng);
        wave.2 *= 0.5 * params.hill_height / total;
    }
    let slope = params.slope_degrees.to_radians();
    let rise = sin(slope) / cos(slope);
    let samples = params.samples as usize;
    let cell = params.size / (samples - 1) as f32;
    let half = 0.5 * params.size;
    let height = |x: f32, z: f32| {
        let p = Vec2::new(x, z);
        let mut h = rise * p.dot(slope_direction);
        for &(wave, phase, amplitude) in &waves {
            h += amplitude * sin(p.dot(wave) + phase);
        }
        if params.step_height > 0.0 {
            let along = p.dot(step_direction) / params.step_spacing;
            h += params.step_height * floor(along);
        }
        h
    };
    Ok(HeightField::from_fn(
        Vec2::splat(-half),
        cell,
        samples,
        samples,
        height,
    )?)
}

/// `⌊x⌋` without `std` (exact for |x| below 2²³, `x` itself beyond, where every float is a
/// whole number).
fn floor(x: f32) -> f32 {
    if !(x.abs() < 8_388_608.0) {
        return x;
    }
    let whole = x as i32 as f32;
    if whole > x { whole - 1.0 } else { whole }
}

/// The terrain as a triangle mesh (for a viewer or an exporter) that stays within a hundredth
/// of a cell of the height field's bilinear surface, the one the gait walks on: one vertex per
/// sample at its height, smooth normals, and each cell cut into triangles fanned around its
/// middle (four per cell), wound counter-clockwise seen from above.
///
/// A fan is within a sixteenth of the cell's twist (`|h₀₀ − h₁₀ − h₀₁ + h₁₁|`) of the
/// bilinear surface, a quarter of what two triangles per cell show; a cell twisted more than
/// that allows (a step's corner) is first cut into `n × n` smaller cells, fanned each, whose
/// twist is `n²` times less. Along a cell's edges the bilinear surface is straight, so the
/// extra vertices of a cut cell lie exactly on its neighbours' edges and leave no crack.
#[must_use]
pub fn terrain_mesh(field: &HeightField) -> TerrainMesh {
    let (columns, rows) = (field.columns(), field.rows());
    let (origin, cell) = (field.origin(), field.cell());
    let heights = field.heights();
    let at = |i: usize, j: usize| heights[j * columns + i];
    let samples = columns * rows;
    let cells = (columns - 1) * (rows - 1);
    let mut positions = Vec::with_capacity(samples + cells);
    let mut normals = Vec::with_capacity(samples + cells);
    for j in 0..rows {
        for i in 0..columns {
            let x = origin.x + i as f32 * cell;
            let z = origin.y + j as f32 * cell;
            positions.push(glam::Vec3::new(x, at(i, j), z));
            // Central differences inside, one-sided at the edges.
            let (i0, i1) = (i.saturating_sub(1), (i + 1).min(columns - 1));
            let (j0, j1) = (j.saturating_sub(1), (j + 1).min(rows - 1));
            let dx = (at(i1, j) - at(i0, j)) / ((i1 - i0) as f32 * cell);
            let dz = (at(i, j1) - at(i, j0)) / ((j1 - j0) as f32 * cell);
            normals.push(unit_normal(dx, dz));
        }
    }
    let mut triangles = Vec::with_capacity(4 * cells);
    let tolerance = MESH_TOLERANCE * cell;
    for j in 0..rows - 1 {
        for i in 0..columns - 1 {
            let corners = [at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)];
            let [a, b, c, d] = corners;
            let twist = (a - b - c + d).abs();
            // The fewest cuts `n` with twist / (16 n²) within the tolerance.
            let mut n = 1;
            while n < MAX_CUTS && twist > 16.0 * (n * n) as f32 * tolerance {
                n += 1;
            }
            let cell_origin =
                glam::Vec2::new(origin.x + i as f32 * cell, origin.y + j as f32 * cell);
            // The vertices of the cut cell's (n + 1)² grid: its corners are the samples'.
            let v = |i: usize, j: usize| (j * columns + i) as u32;
            let sample = [v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)];
            let first = positions.len();
            let grid = |p: usize, q: usize| -> u32 {
                if (p == 0 || p == n) && (q == 0 || q == n) {
                    return sample[usize::from(p == n) + 2 * usize::from(q == n)];
                }
                let inner = if q == 0 {
                    p - 1
                } else if q < n {
                    (n - 1) + (q - 1) * (n + 1) + p
                } else {
                    (n - 1) + (n - 1) * (n + 1) + p - 1
                };
                (first + inner) as u32
            };
            let bilinear = |u: f32, w: f32| {
                let h = a + (b - a) * u + (c - a) * w + (a - b - c + d) * u * w;
                let slope_x = ((b - a) + (a - b - c + d) * w) / cell;
                let slope_z = ((c - a) + (a - b - c + d) * u) / cell;
                let p = cell_origin + glam::Vec2::new(u, w) * cell;
                (glam::Vec3::new(p.x, h, p.y), unit_normal(slope_x, slope_z))
            };
            let step = 1.0 / n as f32;
            for q in 0..=n {
                for p in 0..=n {
                    if (p == 0 || p == n) && (q == 0 || q == n) {
                        continue;
                    }
                    let (position, normal) = bilinear(p as f32 * step, q as f32 * step);
                    positions.push(position);
                    normals.push(normal);
                }
            }
            for q in 0..n {
                for p in 0..n {
                    let (position, normal) =
                        bilinear((p as f32 + 0.5) * step, (q as f32 + 0.5) * step);
                    let m = positions.len() as u32;
                    positions.push(position);
                    normals.push(normal);
                    let (a, b, c, d) = (
                        grid(p, q),
                        grid(p + 1, q),
                        grid(p, q + 1),
                        grid(p + 1, q + 1),
                    );
                    triangles.extend([[a, m, b], [b, m, d], [d, m, c], [c, m, a]]);
                }
            }
        }
    }
    TerrainMesh {
        positions,
        normals,
        triangles,
    }
}

/// How far [`terrain_mesh`] may draw the terrain from its bilinear surface, × the cell size.
const MESH_TOLERANCE: f32 = 0.01;

/// The most cuts along a side [`terrain_mesh`] makes in one cell (a cliff within a cell is
/// drawn as a steep ramp whichever way it is cut).
const MAX_CUTS: usize = 8;

/// The unit normal of a surface rising `dx` along X and `dz` along Z.
fn unit_normal(dx: f32, dz: f32) -> glam::Vec3 {
    let n = glam::Vec3::new(-dx, 1.0, -dz);
    n / sqrt(n.length_squared())
}

/// A terrain's triangle mesh (see [`terrain_mesh`]).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct TerrainMesh {
    /// One vertex per height sample, X fastest; then, cell by cell (X fastest), the inner
    /// vertices of a cut cell's grid and the middles of its fans.
    pub positions: Vec<glam::Vec3>,
    /// Unit normals, one per vertex.
    pub normals: Vec<glam::Vec3>,
    /// Triangles, counter-clockwise seen from above (their normals point up).
    pub triangles: Vec<[u32; 3]>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_rounds_down_on_both_sides_of_zero() {
        for (x, f) in [
            (0.0, 0.0),
            (0.5, 0.0),
            (1.0, 1.0),
            (-0.5, -1.0),
            (-1.0, -1.0),
            (-2.5, -3.0),
        ] {
            assert_eq!(floor(x), f, "{x}");
        }
        assert_eq!(floor(1e9), 1e9);
        assert!(floor(f32::NAN).is_nan());
    }

    #[test]
    fn the_mesh_faces_up_and_follows_the_bilinear_surface() {
        let params = TerrainParams::DEFAULT.with_extent(10.0, 11);
        for field in [
            terrain(3, &params).unwrap(),
            terrain(4, &params.with_steps(0.8, 2.0)).unwrap(),
        ] {
            let mesh = terrain_mesh(&field);
            assert_eq!(
                mesh.positions[..121],
                {
                    let mut samples = Vec::new();
                    for j in 0..11 {
                        for i in 0..11 {
                            let (x, z) = (-5.0 + i as f32, -5.0 + j as f32);
                            samples.push(glam::Vec3::new(x, field.heights()[j * 11 + i], z));
                        }
                    }
                    samples
                }[..]
            );
            assert!(mesh.triangles.len() >= 400);
            for p in &mesh.positions {
                let h = field.height(p.x, p.z).unwrap();
                assert!((p.y - h).abs() < 1e-4, "{p}: {h}");
            }
            for n in &mesh.normals {
                assert!(n.y > 0.0 && (n.length() - 1.0).abs() < 1e-5, "{n}");
            }
            // Inside every triangle, within the tolerance of the bilinear surface.
            for t in &mesh.triangles {
                let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
                assert!((b - a).cross(c - a).y > 0.0, "{t:?}");
                for (u, v) in [
                    (1.0 / 3.0, 1.0 / 3.0),
                    (0.5, 0.25),
                    (0.25, 0.5),
                    (0.25, 0.25),
                ] {
                    let p = a + u * (b - a) + v * (c - a);
                    let h = field.height(p.x, p.z).unwrap();
                    assert!(
                        (p.y - h).abs() <= MESH_TOLERANCE * field.cell() + 1e-5,
                        "{p}: {h}"
                    );
                }
            }
        }
    }
}
