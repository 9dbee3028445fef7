//! The CPU texture and normal map of a 2D creature (the seed rendered them on the GPU).
//!
//! Both are rendered ball by ball over the *culled* field: each ball touches only the pixels
//! within its cutoff radius, and its Gaussian splits into a row factor times a column factor,
//! so a ball costs one `exp` per row and column it reaches — not one per pixel (the seed's
//! approach cost about 19 million `exp` per creature). Per pixel the pass accumulates the field
//! sum, its gradient, and the field-weighted colour and texture weights (`Σ f_i a_i / Σ f_i`).
//!
//! Four rows at a time: the balls' runs on those rows add into seven planes (a multiply and
//! an add per plane and texel, four texels per vector), then each row is finished over the
//! columns some ball reaches only (normals and coverage, the base textures where the creature
//! is, the albedo, all in loops the compiler vectorises); the rest of a row is transparent
//! black with a flat normal. The hot loops avoid what keeps the compiler from vectorising:
//! float-to-integer conversions (bytes and floors come from adding `1.5 · 2²³`), `exp` calls
//! (a polynomial instead), NaN-aware `min`/`max`, and overlapping slices (the seven planes
//! are separate parameters of one function).

use alloc::vec;
use alloc::vec::Vec;
use core::ops::Range;

use glam::Vec2;

use creature_metaball::{DEFAULT_EPSILON, Falloff, SEED_BLOBBINESS};

use super::noise;
use crate::d2::Ball;
use crate::image::Image;
use crate::math::{max, min};
use crate::{Error, math};

/// Options of [`render_texture`].
///
/// ```
/// use creature::d2::TextureOptions;
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
///   first-order distance `(field − 1) / |∇field|`, and never 0 for a pixel holding a ball's
///   centre (each ball's disk is inside, so a part thinner than a pixel, between pixel
///   centres, still shows);
/// - the normal of the height field `normal_relief × field`, `n = normalize(−r ∂F/∂x,
///   −r ∂F/∂y, 1)`, encoded as `n · 0.5 + 0.5` (+x right, +y up: glTF's convention);
/// - channels are rounded to the nearest byte (ties to even).
///
/// ```
/// use creature::glam::{Vec2, Vec3};
/// use creature::metaball::Ball2;
/// use creature::d2::{render_texture, Ball, TextureOptions};
///
/// let ball = Ball {
///     ball: Ball2::new(Vec2::ZERO, 10.0, 0),
///     colour: Vec3::new(0.9, 0.5, 0.2),
///     texture_weights: Vec2::new(1.0, 0.0),
/// };
/// let bounds = (Vec2::splat(-12.0), Vec2::splat(12.0));
/// let (albedo, normals) = render_texture(&[ball], bounds, &TextureOptions::DEFAULT.with_size(32))?;
/// assert_eq!(albedo.pixel(16, 16).map(|p| p[3]), Some(255)); // the centre is inside
/// assert_eq!(albedo.pixel(0, 0).map(|p| p[3]), Some(0)); // a corner is not
/// assert!(normals.pixel(2, 16).is_some_and(|n| n[0] < 128)); // left rim leans left
/// # Ok::<(), creature::Error>(())
/// ```
///
/// # Errors
/// Invalid options; [`Error::NonFinite`] or [`Error::Degenerate`] for a non-finite or empty
/// box; [`Error::Metaball`] for an invalid ball.
pub fn render_texture(
    balls: &[Ball],
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
    // reuses); only the columns some ball reaches are summed, finished and cleared.
    let mut planes = Planes::new(BAND_ROWS.min(n), n);
    for first in (0..n).step_by(BAND_ROWS) {
        let rows = first..(first + BAND_ROWS).min(n);
        footprints.splat(&mut planes, rows.clone());
        finisher.rows(&planes, rows, &footprints.centres);
        planes.clear();
    }
    Ok(finisher.images())
}

/// Rows of the image summed and finished at a time.
const BAND_ROWS: usize = 4;

/// The least coverage of a texel holding a ball's centre: one step of alpha.
const MIN_COVERAGE: f32 = 1.0 / 255.0;

/// The texel holding a ball's centre, and a lower bound on its coverage.
///
/// Each ball alone reaches the iso-level out to its radius `R` (the seed falloff is 1 there),
/// so its disk is inside the creature. The disk's centre lies in the texel, which therefore
/// holds at least a quarter disk of radius `min(R, tx/2, ty/2)`: that area over the texel's
/// is its least coverage (and at least [`MIN_COVERAGE`]). The first-order coverage already
/// exceeds it unless the ball is thin next to a texel; then it is what keeps a part thinner
/// than a texel, lying between texel centres, from vanishing from the texture.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Centre {
    row: usize,
    column: usize,
    least: f32,
}

/// One ball's footprint on the image: the texels within its cutoff circle, the seed falloff
/// split into x and y factors, `f = e^(−B) · exp(B dx² / R²) · exp(B dy² / R²)`.
struct Footprint {
    /// The first row of the footprint, and where its runs start in [`Footprints::runs`] (one
    /// per row).
    first_row: usize,
    runs: Range<usize>,
    colour: [f32; 3],
    wood: f32,
}

/// One row of a footprint: the texels whose centres lie within the cutoff circle (the culled
/// field's support), from image column `column`, their column factors from `factors` in
/// [`Footprints::fx`], and the row factors `fy` and `2k dy fy`.
#[derive(Clone, Copy)]
struct Run {
    column: usize,
    factors: usize,
    len: usize,
    fy: f32,
    fy_dy: f32,
}

/// Every ball's footprint, and their column factors: per column of a footprint, the x factor
/// `fx` at the texel's centre and `2k dx fx`, so each texel adds f = fx·fy,
/// ∂f/∂x = (2k dx fx)·fy, ∂f/∂y = fx·(2k dy fy), and f times the colour and wood weight;
/// and the texels holding the balls' centres, by row.
struct Footprints {
    balls: Vec<Footprint>,
    runs: Vec<Run>,
    fx: Vec<f32>,
    fx_dx: Vec<f32>,
    centres: Vec<Centre>,
    n: usize,
}

impl Footprints {
    // Out of line (like `splat`, `Planes::clear` and `Finisher::rows`) so that profiles name
    // the stages; each runs once per render or band.
    #[inline(never)]
    fn new(balls: &[Ball], (min, max): (Vec2, Vec2), texel: Vec2, n: usize) -> Self {
        // Room for every footprint's columns and rows at once (at most the box of the cutoff
        // circle each), so the tables do not grow step by step.
        let (columns, rows) = balls.iter().fold((0, 0), |(columns, rows), b| {
            let diameter = 2.0 * Falloff::SEED.cutoff_radius(b.ball.radius, DEFAULT_EPSILON);
            let span = |texel: f32| math::ceil_non_negative(diameter / texel).saturating_add(2);
            (columns + span(texel.x).min(n), rows + span(texel.y).min(n))
        });
        let mut out = Self {
            balls: Vec::with_capacity(balls.len()),
            runs: Vec::with_capacity(rows),
            fx: Vec::with_capacity(columns),
            fx_dx: Vec::with_capacity(columns),
            centres: Vec::with_capacity(balls.len()),
            n,
        };
        let peak = math::exp(-SEED_BLOBBINESS);
        let inverse = texel.recip();
        let n_f = n as f32;
        let mut scratch = RowScratch::default();
        let quarter_disk = core::f32::consts::FRAC_PI_4 / (texel.x * texel.y);
        let half = texel.min_element() * 0.5;
        for b in balls {
            let centre = b.ball.center;
            let (column, row) = (
                noise::floor_i((centre.x - min.x) / texel.x),
                noise::floor_i((max.y - centre.y) / texel.y),
            );
            if let (Ok(column @ 0..), Ok(row @ 0..)) =
                (usize::try_from(column), usize::try_from(row))
                && column < n
                && row < n
            {
                let r = b.ball.radius.min(half);
                out.centres.push(Centre {
                    row,
                    column,
                    least: (r * r * quarter_disk).max(MIN_COVERAGE),
                });
            }
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
            // Column and row factors, each in a loop of its own (they vectorise).
            let offset = out.fx.len();
            let x = move |c: i32| min.x + (c as f32 + 0.5) * texel.x - centre.x;
            // Exclusive ranges: inclusive ones do not vectorise.
            let (c0, c1) = (columns.0 as i32, columns.1 as i32);
            out.fx
                .extend((c0..c1 + 1).map(move |c| math::exp_poly(k * x(c) * x(c))));
            let fx = out.fx.get(offset..).unwrap_or_default();
            out.fx_dx.extend(
                (c0..c1 + 1)
                    .zip(fx)
                    .map(move |(c, &fx)| fx * x(c) * 2.0 * k),
            );
            let y = move |r: i32| max.y - (r as f32 + 0.5) * texel.y - centre.y;
            let (r0, r1) = (rows.0 as i32, rows.1 as i32);
            let cutoff2 = cutoff * cutoff;
            // The columns whose centres are within the cutoff circle on each row, as floats
            // (from `first` to `last`, none if `first > last`), intersected with `columns`.
            let (c0f, c1f) = (c0 as f32, c1 as f32);
            let half = move |y: f32| math::sqrt(math::max(cutoff2 - y * y, 0.0));
            // Clamped next to the image first, where `ceil_f` and `floor_f` are exact.
            let column =
                move |x: f32| math::min(math::max((x - min.x) * inverse.x - 0.5, -1.0), n_f);
            scratch.first.clear();
            scratch.first.extend((r0..r1 + 1).map(move |r| {
                let first = math::ceil_f(column(centre.x - half(y(r))));
                if y(r) * y(r) <= cutoff2 {
                    math::max(first, c0f)
                } else {
                    f32::MAX
                }
            }));
            scratch.last.clear();
            scratch.last.extend(
                (r0..r1 + 1)
                    .map(move |r| math::min(math::floor_f(column(centre.x + half(y(r)))), c1f)),
            );
            scratch.fy.clear();
            scratch
                .fy
                .extend((r0..r1 + 1).map(move |r| peak * math::exp_poly(k * y(r) * y(r))));
            let first_run = out.runs.len();
            let rows_f = scratch.first.iter().zip(&scratch.last);
            for ((r, (&first, &last)), &fy) in (r0..r1 + 1).zip(rows_f).zip(&scratch.fy) {
                out.runs.push(if first <= last {
                    // Whole numbers from c0 to c1.
                    let (a, z) = (first as usize, last as usize);
                    Run {
                        column: a,
                        factors: offset + a - columns.0,
                        len: z + 1 - a,
                        fy,
                        fy_dy: fy * y(r) * 2.0 * k,
                    }
                } else {
                    Run {
                        column: 0,
                        factors: 0,
                        len: 0,
                        fy: 0.0,
                        fy_dy: 0.0,
                    }
                });
            }
            out.balls.push(Footprint {
                first_row: rows.0,
                runs: first_run..out.runs.len(),
                colour: b.colour.to_array(),
                wood: b.texture_weights.x,
            });
        }
        out.centres.sort_unstable_by_key(|c| (c.row, c.column));
        out
    }

    /// Adds every ball's contribution to the image rows `rows` (plane row 0 is `rows.start`)
    /// and widens the rows' spans to the columns it reaches (and to the texels holding the
    /// balls' centres).
    #[inline(never)]
    fn splat(&self, planes: &mut Planes, rows: Range<usize>) {
        let n = self.n;
        for centre in self.centres.iter().filter(|c| rows.contains(&c.row)) {
            if let Some(span) = planes.spans.get_mut(centre.row - rows.start) {
                span.0 = span.0.min(centre.column);
                span.1 = span.1.max(centre.column + 1);
            }
        }
        for ball in &self.balls {
            let Some(runs) = self.runs.get(ball.runs.clone()) else {
                continue;
            };
            // The ball's runs on these rows.
            let skip = rows.start.saturating_sub(ball.first_row);
            let first = ball.first_row.max(rows.start);
            let [cr, cg, cb] = ball.colour;
            for (local, run) in (first - rows.start..rows.len()).zip(runs.iter().skip(skip)) {
                if run.len == 0 {
                    continue;
                }
                let factors = run.factors..run.factors + run.len;
                let (Some(fx), Some(fx_dx)) =
                    (self.fx.get(factors.clone()), self.fx_dx.get(factors))
                else {
                    continue;
                };
                if let Some(span) = planes.spans.get_mut(local) {
                    span.0 = span.0.min(run.column);
                    span.1 = span.1.max(run.column + run.len);
                }
                let fy = run.fy;
                // Seven contiguous runs in one loop, `plane += column factor × row factor`:
                // vector multiply-adds.
                let start = local * n + run.column;
                let span = start..start + run.len;
                let p = &mut *planes;
                let (Some(sum), Some(gx), Some(gy), Some(r), Some(g), Some(b), Some(wood)) = (
                    p.sum.get_mut(span.clone()),
                    p.gx.get_mut(span.clone()),
                    p.gy.get_mut(span.clone()),
                    p.r.get_mut(span.clone()),
                    p.g.get_mut(span.clone()),
                    p.b.get_mut(span.clone()),
                    p.wood.get_mut(span),
                ) else {
                    continue;
                };
                accumulate(
                    [sum, gx, gy, r, g, b, wood],
                    (fx, fx_dx),
                    [fy, fy, run.fy_dy, fy * cr, fy * cg, fy * cb, fy * ball.wood],
                );
            }
        }
    }
}

/// `plane += column factor × row factor` for seven planes at once (field, gradient x and y,
/// colour r, g, b and wood weight; the gradient x's column factors are `fx_dx`, the others'
/// `fx`): one pass of vector multiply-adds.
#[inline]
fn accumulate(planes: [&mut [f32]; 7], (fx, fx_dx): (&[f32], &[f32]), factors: [f32; 7]) {
    let [sum, gx, gy, r, g, b, wood] = planes;
    sum_7(sum, gx, gy, r, g, b, wood, fx, fx_dx, factors);
}

/// [`accumulate`]'s loop: the planes as separate parameters, so the compiler knows they do
/// not overlap (no run-time overlap checks before each run).
#[allow(clippy::too_many_arguments)]
#[inline(never)] // inlined, the compiler loses that the planes do not overlap
fn sum_7(
    sum: &mut [f32],
    gx: &mut [f32],
    gy: &mut [f32],
    r: &mut [f32],
    g: &mut [f32],
    b: &mut [f32],
    wood: &mut [f32],
    fx: &[f32],
    fx_dx: &[f32],
    [f_sum, f_gx, f_gy, f_r, f_g, f_b, f_wood]: [f32; 7],
) {
    let texels = sum
        .iter_mut()
        .zip(gx.iter_mut().zip(gy.iter_mut()))
        .zip(r.iter_mut().zip(g.iter_mut()))
        .zip(b.iter_mut().zip(wood.iter_mut()))
        .zip(fx.iter().zip(fx_dx));
    for ((((sum, (gx, gy)), (r, g)), (b, wood)), (&fx, &fx_dx)) in texels {
        *sum += fx * f_sum;
        *gx += fx_dx * f_gx;
        *gy += fx * f_gy;
        *r += fx * f_r;
        *g += fx * f_g;
        *b += fx * f_b;
        *wood += fx * f_wood;
    }
}

/// Per row of a footprint, before they become [`Run`]s: the first and last column and the row
/// factor (reused from ball to ball).
#[derive(Default)]
struct RowScratch {
    first: Vec<f32>,
    last: Vec<f32>,
    fy: Vec<f32>,
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

/// Per-texel sums of a band of rows, one plane each (so rows are contiguous runs the compiler
/// vectorises): field, gradient x and y, colour r, g, b (field-weighted) and wood weight
/// (field-weighted); and per row the columns some ball reaches. Outside a row's span every
/// sum is 0.
struct Planes {
    n: usize,
    sum: Vec<f32>,
    gx: Vec<f32>,
    gy: Vec<f32>,
    r: Vec<f32>,
    g: Vec<f32>,
    b: Vec<f32>,
    wood: Vec<f32>,
    /// Per row: the columns `start..end` some ball reaches (`start ≥ end`: none).
    spans: Vec<(usize, usize)>,
}

impl Planes {
    fn new(rows: usize, n: usize) -> Self {
        let len = rows * n;
        // Planes of different lengths (by 80 bytes each), so that the same texel of two planes
        // is unlikely to sit at the same address modulo 4 KiB, which would make the
        // processor treat a load from one as depending on a store to the other.
        let plane = |k: usize| vec![0.0; len + 20 * k];
        Self {
            n,
            sum: plane(0),
            gx: plane(1),
            gy: plane(2),
            r: plane(3),
            g: plane(4),
            b: plane(5),
            wood: plane(6),
            spans: vec![(n, 0); rows],
        }
    }

    /// Zeroes the rows' spans (all that was summed into) and empties the spans.
    #[inline(never)]
    fn clear(&mut self) {
        let n = self.n;
        for (row, span) in self.spans.iter_mut().enumerate() {
            if span.0 < span.1 {
                let texels = row * n + span.0..row * n + span.1;
                for plane in [
                    &mut self.sum,
                    &mut self.gx,
                    &mut self.gy,
                    &mut self.r,
                    &mut self.g,
                    &mut self.b,
                    &mut self.wood,
                ] {
                    if let Some(texels) = plane.get_mut(texels.clone()) {
                        texels.fill(0.0);
                    }
                }
            }
            *span = (n, 0);
        }
    }
}

/// The normal map's texel where no ball reaches: `(0, 0, 1)` encoded.
const FLAT_NORMAL: [u8; 4] = [128, 128, 255, 255];

/// Turns summed rows into the albedo and normal images.
struct Finisher {
    n: usize,
    /// The images, appended row by row.
    albedo: Vec<u8>,
    normals: Vec<u8>,
    /// One row of each image, finished before it is appended.
    albedo_row: Vec<[u8; 4]>,
    normal_row: Vec<[u8; 4]>,
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
    ice: Vec<f32>,
}

impl Finisher {
    fn new(n: usize, extent: Vec2, texel: Vec2, options: &TextureOptions) -> Self {
        let side = extent.max_element();
        // Base texture coordinates: the image in a square frame of side `side`.
        let x_scale = texel.x / side;
        let xs: Vec<f32> = (0..n).map(|col| (col as f32 + 0.5) * x_scale).collect();
        Self {
            n,
            albedo: Vec::with_capacity(n * n * 4),
            normals: Vec::with_capacity(n * n * 4),
            albedo_row: vec![[0; 4]; n],
            normal_row: vec![[0; 4]; n],
            extent,
            texel,
            side,
            inverse_pixel: 1.0 / texel.max_element(),
            relief: options.normal_relief,
            shading: options.depth_shading,
            base_textures: noise::BaseTextures::new(options.noise_seed, &xs),
            noise_row: noise::BaseRow::default(),
            coverage: vec![0.0; n],
            base: vec![1.0; n],
            ice: vec![0.0; n],
        }
    }

    /// Finishes the image rows `rows` from their sums (plane row 0 is `rows.start`) and
    /// appends them to the images (rows are finished in order, each once).
    #[inline(never)]
    fn rows(&mut self, planes: &Planes, rows: Range<usize>, centres: &[Centre]) {
        let n = self.n;
        for (local, row) in rows.enumerate() {
            let (lo, hi) = planes.spans.get(local).copied().unwrap_or((n, 0));
            let (lo, hi) = (lo.min(n), hi.min(n));
            // Where no ball reaches, the albedo is transparent black and the normal flat.
            let defaults = |albedo: &mut [[u8; 4]], normals: &mut [[u8; 4]]| {
                albedo.fill([0; 4]);
                normals.fill(FLAT_NORMAL);
            };
            let (albedo, normals) = (&mut self.albedo_row, &mut self.normal_row);
            if lo < hi {
                defaults(
                    albedo.get_mut(..lo).unwrap_or_default(),
                    normals.get_mut(..lo).unwrap_or_default(),
                );
                defaults(
                    albedo.get_mut(hi..).unwrap_or_default(),
                    normals.get_mut(hi..).unwrap_or_default(),
                );
                if !self.finish(planes, local * n, row, lo..hi, centres) {
                    let albedo = self.albedo_row.get_mut(lo..hi).unwrap_or_default();
                    let normals = self.normal_row.get_mut(lo..hi).unwrap_or_default();
                    defaults(albedo, normals);
                }
            } else {
                defaults(albedo, normals);
            }
            self.albedo
                .extend_from_slice(self.albedo_row.as_flattened());
            self.normals
                .extend_from_slice(self.normal_row.as_flattened());
        }
    }

    /// Finishes the columns `columns` (some ball reaches them) of image row `row`, whose sums
    /// start at `start` in the planes, into the row buffers, in three passes: normals and
    /// coverage, the base textures where the creature is, then the albedo (all vectorised).
    /// `false` if a buffer is too short (never: then the caller fills in the defaults).
    fn finish<'a>(
        &mut self,
        planes: &'a Planes,
        start: usize,
        row: usize,
        columns: Range<usize>,
        centres: &[Centre],
    ) -> bool {
        let (lo, hi) = (columns.start, columns.end);
        let span = start + lo..start + hi;
        let plane = |p: &'a Vec<f32>| p.get(span.clone());
        let (Some(sum), Some(gx), Some(gy), Some(r), Some(g), Some(b), Some(wood)) = (
            plane(&planes.sum),
            plane(&planes.gx),
            plane(&planes.gy),
            plane(&planes.r),
            plane(&planes.g),
            plane(&planes.b),
            plane(&planes.wood),
        ) else {
            return false;
        };
        let (Some(normal_row), Some(albedo_row)) = (
            self.normal_row.get_mut(lo..hi),
            self.albedo_row.get_mut(lo..hi),
        ) else {
            return false;
        };
        let (Some(coverage), Some(base), Some(ice)) = (
            self.coverage.get_mut(lo..hi),
            self.base.get_mut(lo..hi),
            self.ice.get_mut(lo..hi),
        ) else {
            return false;
        };
        // 1. The normal, and the coverage: at least the least coverage of the texels holding a
        //    ball's centre (see `Centre`).
        normals(gx, gy, self.relief, normal_row);
        coverages(sum, gx, gy, self.inverse_pixel, coverage);
        let first = centres.partition_point(|c| c.row < row);
        for centre in centres.iter().skip(first).take_while(|c| c.row == row) {
            if let Some(coverage) = centre
                .column
                .checked_sub(lo)
                .and_then(|i| coverage.get_mut(i))
            {
                *coverage = max(*coverage, centre.least);
            }
        }
        // 2. The base textures only where the creature is (or its anti-aliased rim); outside,
        //    the colour is kept (without detail, base 1) so filtering at the rim does not bleed
        //    black.
        base.fill(1.0);
        if let Some(covered) = covered(coverage) {
            let y = (self.extent.y - (row as f32 + 0.5) * self.texel.y) / self.side;
            let textures = &self.base_textures;
            textures.row(y, &mut self.noise_row);
            let columns = lo + covered.start..lo + covered.end;
            if let (Some(base), Some(ice), Some(coverage), Some(sum), Some(wood)) = (
                base.get_mut(covered.clone()),
                ice.get_mut(covered.clone()),
                coverage.get(covered.clone()),
                sum.get(covered.clone()),
                wood.get(covered),
            ) {
                textures.wood_row(&self.noise_row, columns.clone(), base);
                textures.ice_row(&self.noise_row, columns, ice);
                blend(base, ice, coverage, [sum, wood]);
            }
        }
        // 3. The albedo.
        albedos([r, g, b], base, coverage, self.shading, albedo_row);
        true
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

/// The normal of the height field `relief × field` from its gradient, as texels (see [`rgba`]):
/// `(−relief ∂F/∂x, −relief ∂F/∂y, 1)` is at least 1 long, so only an infinite one cannot be
/// normalised (it gives the flat normal).
fn normals(gx: &[f32], gy: &[f32], relief: f32, texels: &mut [[u8; 4]]) {
    for ((&gx, &gy), texel) in gx.iter().zip(gy).zip(texels) {
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
        *texel = rgba(nx * 0.5 + 0.5, ny * 0.5 + 0.5, nz * 0.5 + 0.5, 1.0);
    }
}

/// The coverage of the inside, `field ≥ 1`, anti-aliased with the first-order distance
/// `(field − 1) / |∇field|` in texels (`inverse_pixel` is 1 / the texel's larger side):
/// `clamp(distance + 1/2, 0, 1)`.
///
/// Eight texels at a time: when none is within half a texel of the iso-line (compared
/// squared), they are 0 or 1 without a square root and a division.
fn coverages(sum: &[f32], gx: &[f32], gy: &[f32], inverse_pixel: f32, coverage: &mut [f32]) {
    const CHUNK: usize = 8;
    let one = |sum: f32, gx: f32, gy: f32| {
        let slope = max(math::sqrt(gx * gx + gy * gy), 1e-6);
        unit((sum - 1.0) / slope * inverse_pixel + 0.5)
    };
    let chunks = coverage
        .chunks_exact_mut(CHUNK)
        .zip(sum.chunks_exact(CHUNK))
        .zip(gx.chunks_exact(CHUNK).zip(gy.chunks_exact(CHUNK)));
    for ((coverage, sum), (gx, gy)) in chunks {
        // Fixed-size arrays, so the loops below unroll into vector code.
        let (Ok(coverage), Ok(sum), Ok(gx), Ok(gy)) = (
            <&mut [f32; CHUNK]>::try_from(coverage),
            <&[f32; CHUNK]>::try_from(sum),
            <&[f32; CHUNK]>::try_from(gx),
            <&[f32; CHUNK]>::try_from(gy),
        ) else {
            continue;
        };
        let mut rim = [false; CHUNK];
        for (rim, ((&sum, &gx), &gy)) in rim.iter_mut().zip(sum.iter().zip(gx).zip(gy)) {
            let d = (sum - 1.0) * inverse_pixel;
            // |d| / slope < 1/2 (slope at least 1e-6, as above).
            *rim = 4.0 * d * d < max(gx * gx + gy * gy, 1e-12);
        }
        let texels = coverage.iter_mut().zip(sum).zip(gx.iter().zip(gy));
        if rim.contains(&true) {
            for ((coverage, &sum), (&gx, &gy)) in texels {
                *coverage = one(sum, gx, gy);
            }
        } else {
            for ((coverage, &sum), _) in texels {
                *coverage = if sum >= 1.0 { 1.0 } else { 0.0 };
            }
        }
    }
    let done = coverage.len() / CHUNK * CHUNK;
    let rest = coverage
        .iter_mut()
        .zip(sum.iter().zip(gx.iter().zip(gy)))
        .skip(done);
    for (coverage, (&sum, (&gx, &gy))) in rest {
        *coverage = one(sum, gx, gy);
    }
}

/// The texels with a coverage above 0: from the first to the last, `None` if there is none.
/// Eight at a time (vector compares), then texel by texel within the chunk.
fn covered(coverage: &[f32]) -> Option<Range<usize>> {
    const CHUNK: usize = 8;
    let any = |chunk: &[f32]| chunk.iter().fold(false, |any, &c| any | (c > 0.0));
    let first_chunk = coverage.chunks(CHUNK).position(any)?;
    let last_chunk = coverage.chunks(CHUNK).rposition(any)?;
    let first = first_chunk * CHUNK
        + coverage
            .get(first_chunk * CHUNK..)?
            .iter()
            .position(|&c| c > 0.0)?;
    let last_start = last_chunk * CHUNK;
    let last = last_start
        + coverage
            .get(last_start..(last_start + CHUNK).min(coverage.len()))?
            .iter()
            .rposition(|&c| c > 0.0)?;
    Some(first..last + 1)
}

/// The base texture where the texel is covered: the wood-like texture (in `wood`, which it
/// becomes) and the ice-like one blended by the field-weighted wood weight (`wood_sum / sum`);
/// 1 (no detail) where it is not.
fn blend(wood: &mut [f32], ice: &[f32], coverage: &[f32], [sum, wood_sum]: [&[f32]; 2]) {
    let texels = wood
        .iter_mut()
        .zip(ice)
        .zip(coverage.iter().zip(sum.iter().zip(wood_sum)));
    for ((wood, &ice), (&coverage, (&sum, &wood_sum))) in texels {
        let share = unit(wood_sum / sum);
        let mix = ice + (*wood - ice) * share;
        *wood = if coverage > 0.0 { mix } else { 1.0 };
    }
}

/// The albedo, as texels (see [`rgba`]): the field-weighted colour (colour sums / field) × base ×
/// shading × field, that is the colour sums × base × shading; alpha the coverage.
fn albedos(
    [r, g, b]: [&[f32]; 3],
    base: &[f32],
    coverage: &[f32],
    shading: f32,
    texels: &mut [[u8; 4]],
) {
    let texels = r
        .iter()
        .zip(g.iter().zip(b))
        .zip(base.iter().zip(coverage))
        .zip(texels);
    for (((&r, (&g, &b)), (&base, &coverage)), texel) in texels {
        let k = base * shading;
        *texel = rgba(r * k, g * k, b * k, coverage);
    }
}

/// Clamps to `[0, 1]`; NaN gives 0.
#[inline]
fn unit(v: f32) -> f32 {
    min(max(v, 0.0), 1.0)
}

/// `[0, 1]` to a byte, rounded to nearest (ties to even); NaN gives 0.
#[cfg(test)]
fn to_byte(v: f32) -> u8 {
    byte(v) as u8
}

/// [`to_byte`] as a `u32` (a value from 0 to 255).
#[inline]
fn byte(v: f32) -> u32 {
    // `t + 2²³` for `t` in [0, 255] has the exponent of 2²³ and `t` rounded (to nearest, ties
    // to even) as its mantissa: a float add and a bit cast, which vectorise (a float to
    // integer conversion does not without SSE4).
    const TWO_23: f32 = 8_388_608.0;
    (unit(v) * 255.0 + TWO_23).to_bits() - TWO_23.to_bits()
}

/// Four channels in `[0, 1]` as an RGBA8 texel (packed in a `u32` first: shifts and ors
/// that vectorise).
#[inline]
fn rgba(r: f32, g: f32, b: f32, a: f32) -> [u8; 4] {
    (byte(r) | byte(g) << 8 | byte(b) << 16 | byte(a) << 24).to_le_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;
    use creature_metaball::Ball2;
    use glam::Vec3;

    fn ball(x: f32, y: f32, r: f32, colour: Vec3) -> Ball {
        Ball {
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
        let (albedo, _) =
            render_texture(&balls, bounds, &TextureOptions::DEFAULT.with_size(40)).unwrap();
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
        let (albedo, normals) = render_texture(&balls, bounds, &options).unwrap();
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
    fn a_ball_thinner_than_a_texel_between_texel_centres_still_shows() {
        // Texels 10 units wide; a ball of radius 1 at (9, 1): no texel centre within its
        // cutoff circle (4.4), the nearest, (5, 5), is 5.7 away.
        let tiny = [ball(9.0, 1.0, 1.0, Vec3::ONE)];
        let bounds = (Vec2::ZERO, Vec2::splat(40.0));
        let (albedo, _) =
            render_texture(&tiny, bounds, &TextureOptions::DEFAULT.with_size(4)).unwrap();
        // Row 3 from the top holds y in [0, 10]; column 0 holds x in [0, 10].
        let alpha = |x, y| albedo.pixel(x, y).unwrap()[3];
        // A quarter disk of radius 1 in a 10 × 10 texel: 0.79% of it, 2 of 255.
        assert_eq!(alpha(0, 3), 2);
        let others = (0..4).flat_map(|y| (0..4).map(move |x| (x, y)));
        assert!(
            others
                .filter(|&p| p != (0, 3))
                .all(|(x, y)| alpha(x, y) == 0)
        );
        // A ball as wide as the texel: a quarter of a disk of radius 5, 20% of it.
        let wide = [ball(9.0, 1.0, 5.0, Vec3::ONE)];
        let (albedo, _) =
            render_texture(&wide, bounds, &TextureOptions::DEFAULT.with_size(4)).unwrap();
        assert!(albedo.pixel(0, 3).unwrap()[3] >= 50);
    }

    #[test]
    fn balls_much_larger_than_the_image_or_far_outside_it_render_sanely() {
        // A ball 10⁶ times the box (its cutoff circle 10⁸ texels wide): every texel inside,
        // the normals nearly flat.
        let huge = [ball(0.3, -0.2, 1e6, Vec3::ONE)];
        let bounds = (Vec2::splat(-1.0), Vec2::splat(1.0));
        let (albedo, normals) =
            render_texture(&huge, bounds, &TextureOptions::DEFAULT.with_size(64)).unwrap();
        assert!(albedo.rgba.chunks_exact(4).all(|p| p[3] == 255));
        assert!(normals.rgba.chunks_exact(4).all(|p| p[2] >= 254));
        // A ball whose cutoff circle misses the box: transparent, flat.
        let far = [ball(100.0, 0.0, 5.0, Vec3::ONE)];
        let (albedo, normals) =
            render_texture(&far, bounds, &TextureOptions::DEFAULT.with_size(16)).unwrap();
        assert!(albedo.rgba.iter().all(|&b| b == 0));
        assert!(
            normals
                .rgba
                .chunks_exact(4)
                .all(|p| p == [128, 128, 255, 255])
        );
    }

    #[test]
    fn bad_input_is_an_error() {
        let balls = [ball(0.0, 0.0, 5.0, Vec3::ONE)];
        let bounds = (Vec2::ZERO, Vec2::ONE);
        assert!(render_texture(&balls, bounds, &TextureOptions::DEFAULT.with_size(0)).is_err());
        assert!(render_texture(&balls, (Vec2::ONE, Vec2::ONE), &TextureOptions::DEFAULT).is_err());
        assert!(
            render_texture(
                &balls,
                (Vec2::ZERO, Vec2::splat(f32::NAN)),
                &TextureOptions::DEFAULT
            )
            .is_err()
        );
        let bad = [ball(0.0, 0.0, -5.0, Vec3::ONE)];
        assert!(render_texture(&bad, bounds, &TextureOptions::DEFAULT).is_err());
    }
}
