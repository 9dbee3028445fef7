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
//!
//! The parts: `footprints` (each ball's texels, column and row factors), `splat` (the band of
//! seven planes the footprints add into), `finish` (normals, coverage, base textures and
//! albedo, row by row, into the images) and `noise` (the procedural base textures).

use glam::Vec2;

use crate::Error;
use crate::d2::Ball;
use crate::image::Image;

mod finish;
mod footprints;
mod noise;
mod splat;

use finish::Finisher;
use footprints::Footprints;
use splat::Planes;

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

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec::Vec;
    use creature_metaball::{Ball2, Falloff};
    use glam::Vec3;

    fn ball(x: f32, y: f32, r: f32, colour: Vec3) -> Ball {
        Ball {
            ball: Ball2::new(Vec2::new(x, y), r, 0),
            colour,
            texture_weights: Vec2::new(0.5, 0.5),
        }
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
