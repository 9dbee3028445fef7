//! The CPU texture and normal map of a 2D creature (the seed rendered them on the GPU).
//!
//! Both are rendered ball by ball over the *culled* field: each ball touches only the pixels
//! within its cutoff radius, and its Gaussian splits into a row factor times a column factor,
//! so a ball costs one `exp` per row and column it reaches — not one per pixel (the seed's
//! approach cost about 19 million `exp` per creature). Per pixel the pass accumulates the field
//! sum, its gradient, and the field-weighted colour and texture weights (`Σ f_i a_i / Σ f_i`).

use alloc::vec;
use alloc::vec::Vec;

use glam::Vec2;

use creature_metaball::{DEFAULT_EPSILON, Falloff, SEED_BLOBBINESS};

use crate::types::Ball2d;
use crate::{Error, math, noise};

/// An RGBA8 image, rows top to bottom, 4 bytes per pixel.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 4` bytes, row-major, row 0 at the top.
    pub rgba: Vec<u8>,
}

impl Image {
    /// The pixel at `(x, y)` (row `y` from the top), `None` outside the image.
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 4;
        let p = self.rgba.get(i..i + 4)?;
        Some([p[0], p[1], p[2], p[3]])
    }
}

/// Options of [`render`].
///
/// ```
/// use creature::TextureOptions;
///
/// let options = TextureOptions::DEFAULT.with_size(128);
/// assert_eq!(options.depth_shading, 0.75);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct TextureOptions {
    /// Width and height in pixels, from 1 to 4096. Default 256.
    pub size: u32,
    /// Brightness as a fraction of the field sum, from 0 to 4. Default 0.75 (the seed's).
    pub depth_shading: f32,
    /// The normal map treats the creature as the height field `normal_relief × field` (world
    /// units), from 0 to 1000. Default 12.
    pub normal_relief: f32,
    /// Seed of the base textures' noise. Default 0.
    pub noise_seed: u32,
}

impl TextureOptions {
    /// The defaults.
    pub const DEFAULT: Self = Self {
        size: 256,
        depth_shading: 0.75,
        normal_relief: 12.0,
        noise_seed: 0,
    };

    /// Sets [`size`](Self::size).
    #[must_use]
    pub const fn with_size(mut self, size: u32) -> Self {
        self.size = size;
        self
    }
    /// Sets [`depth_shading`](Self::depth_shading).
    #[must_use]
    pub const fn with_depth_shading(mut self, depth_shading: f32) -> Self {
        self.depth_shading = depth_shading;
        self
    }
    /// Sets [`normal_relief`](Self::normal_relief).
    #[must_use]
    pub const fn with_normal_relief(mut self, normal_relief: f32) -> Self {
        self.normal_relief = normal_relief;
        self
    }
    /// Sets [`noise_seed`](Self::noise_seed).
    #[must_use]
    pub const fn with_noise_seed(mut self, noise_seed: u32) -> Self {
        self.noise_seed = noise_seed;
        self
    }

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] or [`Error::NonFinite`] naming the first bad field.
    pub fn validate(&self) -> Result<(), Error> {
        if self.size == 0 || self.size > 4096 {
            return Err(Error::OutOfRange {
                what: "texture_size",
                value: self.size as f32,
                min: 1.0,
                max: 4096.0,
            });
        }
        for (what, value, max) in [
            ("depth_shading", self.depth_shading, 4.0),
            ("normal_relief", self.normal_relief, 1000.0),
        ] {
            if !value.is_finite() {
                return Err(Error::NonFinite { what });
            }
            if !(value >= 0.0 && value <= max) {
                return Err(Error::OutOfRange {
                    what,
                    value,
                    min: 0.0,
                    max,
                });
            }
        }
        Ok(())
    }
}

impl Default for TextureOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Renders the albedo texture and the tangent-space normal map of `balls` over the box
/// `bounds = (min, max)` (the outline's box: pixel `(0, 0)` is its top-left corner, y up in
/// the world, rows top to bottom in the image), with the seed falloff culled at
/// `creature_metaball::DEFAULT_EPSILON`:
///
/// - colour and texture weights are the field-weighted averages of the balls';
/// - albedo = colour × (wood-like and ice-like base textures, blended by the texture weights)
///   × `depth_shading` × field sum, clamped; the base textures are procedural (value noise
///   rings and cellular noise) in a square frame, so they are not stretched;
/// - alpha is the pixel's coverage of the inside (`field ≥ 1`), anti-aliased with the
///   first-order distance `(field − 1) / |∇field|`;
/// - the normal of the height field `normal_relief × field`, `n = normalize(−r ∂F/∂x,
///   −r ∂F/∂y, 1)`, encoded as `n · 0.5 + 0.5` (+x right, +y up: glTF's convention).
///
/// ```
/// use creature::glam::{Vec2, Vec3};
/// use creature::metaball::Ball2;
/// use creature::{texture, Ball2d, TextureOptions};
///
/// let ball = Ball2d {
///     ball: Ball2::new(Vec2::ZERO, 10.0, 0),
///     colour: Vec3::new(0.9, 0.5, 0.2),
///     texture_weights: Vec2::new(1.0, 0.0),
/// };
/// let bounds = (Vec2::splat(-12.0), Vec2::splat(12.0));
/// let (albedo, normals) = texture::render(&[ball], bounds, &TextureOptions::DEFAULT.with_size(32))?;
/// assert_eq!(albedo.pixel(16, 16).map(|p| p[3]), Some(255)); // the centre is inside
/// assert_eq!(albedo.pixel(0, 0).map(|p| p[3]), Some(0)); // a corner is not
/// assert!(normals.pixel(2, 16).is_some_and(|n| n[0] < 128)); // left rim leans left
/// # Ok::<(), creature::Error>(())
/// ```
///
/// # Errors
/// Invalid options; [`Error::NonFinite`] or [`Error::Degenerate`] for a non-finite or empty
/// box; [`Error::Metaball`] for an invalid ball.
pub fn render(
    balls: &[Ball2d],
    bounds: (Vec2, Vec2),
    options: &TextureOptions,
) -> Result<(Image, Image), Error> {
    options.validate()?;
    let (min, max) = bounds;
    if !min.is_finite() || !max.is_finite() {
        return Err(Error::NonFinite {
            what: "texture bounds",
        });
    }
    let extent = max - min;
    if !(extent.x > 0.0 && extent.y > 0.0) {
        return Err(Error::Degenerate {
            what: "texture box",
        });
    }
    for b in balls {
        b.ball.validate()?;
        if !b.colour.is_finite() || !b.texture_weights.is_finite() {
            return Err(Error::NonFinite {
                what: "ball attribute",
            });
        }
    }
    let n = options.size as usize;
    let texel = extent / n as f32;
    let footprints = Footprints::new(balls, bounds, texel, n);
    let mut finisher = Finisher::new(n, extent, texel, options);
    // Band by band: the sums of a few rows stay in the cache (and in memory the allocator
    // reuses), and the base textures' rows are made once.
    let mut planes = Planes::new(BAND_ROWS.min(n) * n);
    for first in (0..n).step_by(BAND_ROWS) {
        let rows = first..(first + BAND_ROWS).min(n);
        planes.clear();
        footprints.splat(&mut planes, rows.clone(), n);
        finisher.rows(&planes, rows);
    }
    Ok(finisher.images())
}

/// Rows of the image summed and finished at a time.
const BAND_ROWS: usize = 16;

/// One ball's footprint on the image: the pixels within its cutoff circle, the seed falloff
/// split into x and y factors, `f = e^(−B) · exp(B dx² / R²) · exp(B dy² / R²)`.
struct Footprint {
    centre: Vec2,
    /// `B / R²` (negative).
    k: f32,
    cutoff2: f32,
    columns: (usize, usize),
    rows: (usize, usize),
    /// Where the ball's column factors start in [`Footprints::fx`].
    offset: usize,
    colour: [f32; 3],
    wood: f32,
}

/// Every ball's footprint, and their column factors: per column of a footprint, the x factor
/// `fx` and `2k dx fx`, so each pixel adds f = fx·fy, ∂f/∂x = (2k dx fx)·fy,
/// ∂f/∂y = fx·(2k dy fy), and f times the colour and wood weight.
struct Footprints {
    balls: Vec<Footprint>,
    fx: Vec<f32>,
    fx_dx: Vec<f32>,
    min: Vec2,
    max: Vec2,
    texel: Vec2,
}

impl Footprints {
    fn new(balls: &[Ball2d], (min, max): (Vec2, Vec2), texel: Vec2, n: usize) -> Self {
        let mut out = Self {
            balls: Vec::with_capacity(balls.len()),
            fx: Vec::new(),
            fx_dx: Vec::new(),
            min,
            max,
            texel,
        };
        for b in balls {
            let centre = b.ball.center;
            let k = SEED_BLOBBINESS / (b.ball.radius * b.ball.radius);
            let cutoff = Falloff::SEED.cutoff_radius(b.ball.radius, DEFAULT_EPSILON);
            let Some(columns) = pixel_range(
                centre.x - cutoff - min.x,
                centre.x + cutoff - min.x,
                texel.x,
                n,
            ) else {
                continue;
            };
            let Some(rows) = pixel_range(
                max.y - centre.y - cutoff,
                max.y - centre.y + cutoff,
                texel.y,
                n,
            ) else {
                continue;
            };
            let offset = out.fx.len();
            for c in columns.0..=columns.1 {
                let dx = min.x + (c as f32 + 0.5) * texel.x - centre.x;
                let fx = math::exp(k * dx * dx);
                out.fx.push(fx);
                out.fx_dx.push(fx * dx * 2.0 * k);
            }
            out.balls.push(Footprint {
                centre,
                k,
                cutoff2: cutoff * cutoff,
                columns,
                rows,
                offset,
                colour: b.colour.to_array(),
                wood: b.texture_weights.x,
            });
        }
        out
    }

    /// Adds every ball's contribution to the image rows `rows` (plane row 0 is `rows.start`).
    fn splat(&self, planes: &mut Planes, rows: core::ops::Range<usize>, n: usize) {
        let peak = math::exp(-SEED_BLOBBINESS);
        for ball in &self.balls {
            let first = ball.rows.0.max(rows.start);
            let last = ball.rows.1.min(rows.end.saturating_sub(1));
            let (c0, c1) = ball.columns;
            let [cr, cg, cb] = ball.colour;
            for row in first..=last {
                let dy = self.max.y - (row as f32 + 0.5) * self.texel.y - ball.centre.y;
                let fy = peak * math::exp(ball.k * dy * dy);
                let fy_dy = fy * dy * 2.0 * ball.k;
                // Only the columns within the cutoff circle (the culled field's support).
                let half = math::sqrt((ball.cutoff2 - dy * dy).max(0.0));
                let Some((a, z)) = pixel_range(
                    ball.centre.x - half - self.min.x,
                    ball.centre.x + half - self.min.x,
                    self.texel.x,
                    n,
                ) else {
                    continue;
                };
                let (a, z) = (a.max(c0), z.min(c1));
                if a > z {
                    continue;
                }
                let factors = ball.offset + a - c0..=ball.offset + z - c0;
                let (Some(fx), Some(fx_dx)) =
                    (self.fx.get(factors.clone()), self.fx_dx.get(factors))
                else {
                    continue;
                };
                // Seven contiguous runs, each `plane += column factor × row factor`: vector
                // adds.
                let start = (row - rows.start) * n;
                let span = start + a..=start + z;
                let p = &mut *planes;
                let runs = [
                    (&mut p.sum, fx, fy),
                    (&mut p.gx, fx_dx, fy),
                    (&mut p.gy, fx, fy_dy),
                    (&mut p.r, fx, fy * cr),
                    (&mut p.g, fx, fy * cg),
                    (&mut p.b, fx, fy * cb),
                    (&mut p.wood, fx, fy * ball.wood),
                ];
                for (plane, columns, factor) in runs {
                    if let Some(out) = plane.get_mut(span.clone()) {
                        for (o, &c) in out.iter_mut().zip(columns) {
                            *o += c * factor;
                        }
                    }
                }
            }
        }
    }
}

/// The pixels whose centres `(i + 0.5) · texel` lie in `[lo, hi]`, clamped to the image.
fn pixel_range(lo: f32, hi: f32, texel: f32, n: usize) -> Option<(usize, usize)> {
    let top = n as f32 - 1.0;
    let a = (lo / texel - 0.5).clamp(-1.0, n as f32);
    let b = (hi / texel - 0.5).clamp(-1.0, n as f32);
    if !(b >= 0.0 && a <= top) {
        return None;
    }
    let first = (-noise::floor_i(-a)).max(0) as usize;
    let last = (noise::floor_i(b).max(0) as usize).min(n - 1);
    (first <= last).then_some((first, last))
}

/// Per-pixel sums, one plane each (so rows are contiguous runs the compiler vectorises):
/// field, gradient x and y, colour r, g, b (field-weighted) and wood weight (field-weighted).
struct Planes {
    sum: Vec<f32>,
    gx: Vec<f32>,
    gy: Vec<f32>,
    r: Vec<f32>,
    g: Vec<f32>,
    b: Vec<f32>,
    wood: Vec<f32>,
}

impl Planes {
    fn new(len: usize) -> Self {
        Self {
            sum: vec![0.0; len],
            gx: vec![0.0; len],
            gy: vec![0.0; len],
            r: vec![0.0; len],
            g: vec![0.0; len],
            b: vec![0.0; len],
            wood: vec![0.0; len],
        }
    }

    fn clear(&mut self) {
        for plane in [
            &mut self.sum,
            &mut self.gx,
            &mut self.gy,
            &mut self.r,
            &mut self.g,
            &mut self.b,
            &mut self.wood,
        ] {
            plane.fill(0.0);
        }
    }
}

/// Turns summed rows into the albedo and normal images.
struct Finisher {
    n: usize,
    albedo: Vec<u8>,
    normals: Vec<u8>,
    extent: Vec2,
    texel: Vec2,
    side: f32,
    inverse_pixel: f32,
    relief: f32,
    shading: f32,
    base_textures: noise::BaseTextures,
    noise_row: noise::BaseRow,
    coverage: Vec<f32>,
    base: Vec<f32>,
}

impl Finisher {
    fn new(n: usize, extent: Vec2, texel: Vec2, options: &TextureOptions) -> Self {
        Self {
            n,
            albedo: vec![0u8; n * n * 4],
            normals: vec![0u8; n * n * 4],
            extent,
            texel,
            side: extent.max_element(),
            inverse_pixel: 1.0 / texel.max_element(),
            relief: options.normal_relief,
            shading: options.depth_shading,
            base_textures: noise::BaseTextures::new(options.noise_seed),
            noise_row: noise::BaseRow::default(),
            coverage: vec![0.0; n],
            base: vec![1.0; n],
        }
    }

    /// Finishes the image rows `rows` from their sums (plane row 0 is `rows.start`), each in
    /// three passes: normals and coverage (branch-free, vectorised), the base textures where
    /// the creature is (scalar), then the albedo (vectorised).
    fn rows(&mut self, planes: &Planes, rows: core::ops::Range<usize>) {
        let n = self.n;
        let (relief, shading, inverse_pixel) = (self.relief, self.shading, self.inverse_pixel);
        // Base texture coordinates: the image in a square frame of side `side`.
        let x_scale = self.texel.x / self.side;
        let sums = planes
            .sum
            .chunks_exact(n)
            .zip(planes.gx.chunks_exact(n).zip(planes.gy.chunks_exact(n)))
            .zip(planes.r.chunks_exact(n).zip(planes.g.chunks_exact(n)))
            .zip(planes.b.chunks_exact(n).zip(planes.wood.chunks_exact(n)));
        let images = self
            .albedo
            .chunks_exact_mut(4 * n)
            .zip(self.normals.chunks_exact_mut(4 * n))
            .skip(rows.start);
        for (row, ((((sum, (gx, gy)), (r, g)), (b, wood)), (albedo_row, normal_row))) in
            rows.zip(sums.zip(images))
        {
            // 1. The normal of the height field `relief × field` (flat where no ball reaches):
            //    (−relief ∂F/∂x, −relief ∂F/∂y, 1) is at least 1 long, so only an infinite one
            //    cannot be normalised. And the coverage of the inside, `field ≥ 1`, anti-aliased
            //    with the first-order distance (field − 1) / |∇field| (0 where no ball reaches).
            let pixels = sum
                .iter()
                .zip(gx.iter().zip(gy))
                .zip(normal_row.chunks_exact_mut(4).zip(&mut self.coverage));
            for ((&sum, (&gx, &gy)), (normal_px, coverage)) in pixels {
                let (nx, ny) = (-relief * gx, -relief * gy);
                let length2 = nx * nx + ny * ny + 1.0;
                let finite = length2 < f32::INFINITY;
                let inverse = if finite {
                    1.0 / math::sqrt(length2)
                } else {
                    0.0
                };
                let (nx, ny, nz) = if finite {
                    (nx * inverse, ny * inverse, inverse)
                } else {
                    (0.0, 0.0, 1.0)
                };
                normal_px.copy_from_slice(&[
                    to_byte(nx * 0.5 + 0.5),
                    to_byte(ny * 0.5 + 0.5),
                    to_byte(nz * 0.5 + 0.5),
                    255,
                ]);
                let slope = math::sqrt(gx * gx + gy * gy).max(1e-6);
                *coverage = ((sum - 1.0) / slope * inverse_pixel + 0.5).clamp(0.0, 1.0);
            }
            // 2. The base textures only where the creature is (or its anti-aliased rim);
            //    outside, the colour is kept (without detail) so filtering at the rim does not
            //    bleed black.
            let y = (self.extent.y - (row as f32 + 0.5) * self.texel.y) / self.side;
            let mut noise_ready = false;
            let pixels = self
                .coverage
                .iter()
                .zip(sum.iter().zip(wood))
                .zip(&mut self.base);
            for (col, ((&coverage, (&sum, &wood)), base)) in pixels.enumerate() {
                if !(coverage > 0.0) {
                    *base = 1.0;
                    continue;
                }
                if !noise_ready {
                    self.base_textures.row(y, &mut self.noise_row);
                    noise_ready = true;
                }
                let x = (col as f32 + 0.5) * x_scale;
                let wood = (wood / sum).clamp(0.0, 1.0);
                let mut mix = 0.0;
                if wood > 1e-3 {
                    mix += wood * self.base_textures.wood_at(&self.noise_row, x);
                }
                if wood < 1.0 - 1e-3 {
                    mix += (1.0 - wood) * self.base_textures.ice_at(&self.noise_row, x);
                }
                *base = mix;
            }
            // 3. Albedo: the field-weighted colour (colour sums / field) × base × shading ×
            //    field, that is the colour sums × base × shading.
            let pixels = r
                .iter()
                .zip(g.iter().zip(b))
                .zip(self.base.iter().zip(&self.coverage))
                .zip(albedo_row.chunks_exact_mut(4));
            for (((&r, (&g, &b)), (&base, &coverage)), albedo_px) in pixels {
                let k = base * shading;
                albedo_px.copy_from_slice(&[
                    to_byte(r * k),
                    to_byte(g * k),
                    to_byte(b * k),
                    to_byte(coverage),
                ]);
            }
        }
    }

    /// The finished albedo and normal map.
    fn images(self) -> (Image, Image) {
        let size = u32::try_from(self.n).unwrap_or(u32::MAX);
        (
            Image {
                width: size,
                height: size,
                rgba: self.albedo,
            },
            Image {
                width: size,
                height: size,
                rgba: self.normals,
            },
        )
    }
}

/// `[0, 1]` to a byte, rounded; NaN gives 0 (`max` returns the number, not the NaN).
#[inline]
#[allow(clippy::manual_clamp)] // `clamp` keeps a NaN; `max` then `min` turn it into 0
fn to_byte(v: f32) -> u8 {
    (v.max(0.0).min(1.0) * 255.0 + 0.5) as u8
}

#[cfg(test)]
mod tests {
    use super::*;
    use creature_metaball::Ball2;
    use glam::Vec3;

    fn ball(x: f32, y: f32, r: f32, colour: Vec3) -> Ball2d {
        Ball2d {
            ball: Ball2::new(Vec2::new(x, y), r, 0),
            colour,
            texture_weights: Vec2::new(0.5, 0.5),
        }
    }

    #[test]
    fn bytes_round_clamp_and_map_nan_to_zero() {
        assert_eq!(to_byte(f32::NAN), 0);
        assert_eq!(to_byte(-1.0), 0);
        assert_eq!(to_byte(2.0), 255);
        assert_eq!(to_byte(0.5), 128);
        assert_eq!(to_byte(1.0 / 255.0), 1);
    }

    #[test]
    fn pixel_range_clamps_and_rejects() {
        assert_eq!(pixel_range(-5.0, 5.0, 1.0, 10), Some((0, 4)));
        assert_eq!(pixel_range(2.4, 3.6, 1.0, 10), Some((2, 3)));
        assert_eq!(pixel_range(20.0, 30.0, 1.0, 10), None);
        assert_eq!(pixel_range(-30.0, -20.0, 1.0, 10), None);
        assert_eq!(pixel_range(5.0, 100.0, 1.0, 10), Some((5, 9)));
    }

    #[test]
    fn field_sum_matches_the_exact_field() {
        use creature_metaball::Field2;
        let balls = [ball(0.0, 0.0, 10.0, Vec3::X), ball(14.0, 3.0, 7.0, Vec3::Y)];
        let bounds = (Vec2::new(-15.0, -12.0), Vec2::new(25.0, 14.0));
        let (albedo, _) = render(&balls, bounds, &TextureOptions::DEFAULT.with_size(40)).unwrap();
        let plain: Vec<Ball2> = balls.iter().map(|b| b.ball).collect();
        let field = Field2::new(&plain, Falloff::SEED).unwrap();
        let texel = (bounds.1 - bounds.0) / 40.0;
        for row in 0..40 {
            for col in 0..40 {
                let p = Vec2::new(
                    bounds.0.x + (col as f32 + 0.5) * texel.x,
                    bounds.1.y - (row as f32 + 0.5) * texel.y,
                );
                let alpha = albedo.pixel(col, row).unwrap()[3];
                let v = field.value_exact(p);
                // The edge is anti-aliased over about a pixel.
                if v > 1.05 {
                    assert!(alpha > 128, "inside at {p}");
                }
                if v > 1.2 {
                    assert_eq!(alpha, 255, "inside at {p}");
                }
                if v < 0.95 {
                    assert!(alpha < 128, "outside at {p}");
                }
                if v < 0.8 {
                    assert_eq!(alpha, 0, "outside at {p}");
                }
            }
        }
    }

    #[test]
    fn colours_blend_by_field_share() {
        let balls = [
            ball(-10.0, 0.0, 8.0, Vec3::X),
            ball(10.0, 0.0, 8.0, Vec3::Z),
        ];
        let bounds = (Vec2::new(-20.0, -10.0), Vec2::new(20.0, 10.0));
        let options = TextureOptions::DEFAULT.with_size(40);
        let (albedo, normals) = render(&balls, bounds, &options).unwrap();
        let left = albedo.pixel(10, 20).unwrap();
        let right = albedo.pixel(30, 20).unwrap();
        assert!(left[0] > left[2] && right[2] > right[0]);
        // Normals lean outwards on each side and are unit length once decoded.
        let decode =
            |p: [u8; 4]| Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32) / 127.5 - Vec3::ONE;
        let l = decode(normals.pixel(2, 20).unwrap());
        let r = decode(normals.pixel(37, 20).unwrap());
        assert!(l.x < -0.1 && r.x > 0.1, "{l} {r}");
        for p in normals.rgba.chunks_exact(4) {
            let n = decode([p[0], p[1], p[2], p[3]]);
            assert!((n.length() - 1.0).abs() < 0.02, "{n}");
        }
    }

    #[test]
    fn bad_input_is_an_error() {
        let balls = [ball(0.0, 0.0, 5.0, Vec3::ONE)];
        let bounds = (Vec2::ZERO, Vec2::ONE);
        assert!(render(&balls, bounds, &TextureOptions::DEFAULT.with_size(0)).is_err());
        assert!(render(&balls, (Vec2::ONE, Vec2::ONE), &TextureOptions::DEFAULT).is_err());
        assert!(
            render(
                &balls,
                (Vec2::ZERO, Vec2::splat(f32::NAN)),
                &TextureOptions::DEFAULT
            )
            .is_err()
        );
        let bad = [ball(0.0, 0.0, -5.0, Vec3::ONE)];
        assert!(render(&bad, bounds, &TextureOptions::DEFAULT).is_err());
    }
}
