//! The finishing pass: each summed row into the images (the normal from the gradient, the
//! coverage of the inside, the base textures where the creature is, the albedo), and the
//! texel encoding (bytes rounded without float-to-integer conversions).

use alloc::vec;
use alloc::vec::Vec;
use core::ops::Range;

use glam::Vec2;

use super::footprints::Centre;
use super::splat::Planes;
use super::{TextureOptions, noise};
use crate::image::Image;
use crate::math::{self, max, min};

/// The normal map's texel where no ball reaches: `(0, 0, 1)` encoded.
const FLAT_NORMAL: [u8; 4] = [128, 128, 255, 255];

/// Turns summed rows into the albedo and normal images.
pub(super) struct Finisher {
    n: usize,
    /// `n`, as the images' width and height.
    size: u32,
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
    pub(super) fn new(n: usize, extent: Vec2, texel: Vec2, options: &TextureOptions) -> Self {
        let side = extent.max_element();
        // Base texture coordinates: the image in a square frame of side `side`.
        let x_scale = texel.x / side;
        let xs: Vec<f32> = (0..n).map(|col| (col as f32 + 0.5) * x_scale).collect();
        Self {
            n,
            size: options.size,
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
    pub(super) fn rows(&mut self, planes: &Planes, rows: Range<usize>, centres: &[Centre]) {
        let n = self.n;
        for (local, row) in rows.enumerate() {
            // The columns some ball reaches (`lo ≥ hi`: none); they are in the image.
            let (lo, hi) = planes.spans[local];
            debug_assert!(lo >= hi || hi <= n, "a span within the image");
            // Where no ball reaches, the albedo is transparent black and the normal flat.
            let defaults = |albedo: &mut [[u8; 4]], normals: &mut [[u8; 4]]| {
                albedo.fill([0; 4]);
                normals.fill(FLAT_NORMAL);
            };
            let (albedo, normals) = (&mut self.albedo_row, &mut self.normal_row);
            if lo < hi {
                defaults(&mut albedo[..lo], &mut normals[..lo]);
                defaults(&mut albedo[hi..], &mut normals[hi..]);
                self.finish(planes, local * n, row, lo..hi, centres);
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
    fn finish<'a>(
        &mut self,
        planes: &'a Planes,
        start: usize,
        row: usize,
        columns: Range<usize>,
        centres: &[Centre],
    ) {
        let (lo, hi) = (columns.start, columns.end);
        let span = start + lo..start + hi;
        let plane = |p: &'a Vec<f32>| &p[span.clone()];
        let (sum, gx, gy) = (plane(&planes.sum), plane(&planes.gx), plane(&planes.gy));
        let (r, g, b, wood) = (
            plane(&planes.r),
            plane(&planes.g),
            plane(&planes.b),
            plane(&planes.wood),
        );
        let normal_row = &mut self.normal_row[lo..hi];
        let albedo_row = &mut self.albedo_row[lo..hi];
        let coverage = &mut self.coverage[lo..hi];
        let base = &mut self.base[lo..hi];
        let ice = &mut self.ice[lo..hi];
        // 1. The normal, and the coverage: at least the least coverage of the texels holding a
        //    ball's centre (see `Centre`; the row's span holds those texels).
        normals(gx, gy, self.relief, normal_row);
        coverages(sum, gx, gy, self.inverse_pixel, coverage);
        let first = centres.partition_point(|c| c.row < row);
        for centre in centres.iter().skip(first).take_while(|c| c.row == row) {
            let coverage = &mut coverage[centre.column - lo];
            *coverage = max(*coverage, centre.least);
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
            let (base, ice) = (&mut base[covered.clone()], &mut ice[covered.clone()]);
            textures.wood_row(&self.noise_row, columns.clone(), base);
            textures.ice_row(&self.noise_row, columns, ice);
            let (coverage, sum, wood) = (
                &coverage[covered.clone()],
                &sum[covered.clone()],
                &wood[covered],
            );
            blend(base, ice, coverage, [sum, wood]);
        }
        // 3. The albedo.
        albedos([r, g, b], base, coverage, self.shading, albedo_row);
    }

    /// The finished albedo and normal map.
    pub(super) fn images(self) -> (Image, Image) {
        let size = self.size;
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
    debug_assert!(
        sum.len() == coverage.len() && gx.len() == coverage.len() && gy.len() == coverage.len(),
        "a value per texel"
    );
    // Fixed-size arrays, so the loops below unroll into vector code.
    let (coverage_chunks, coverage_rest) = coverage.as_chunks_mut::<CHUNK>();
    let (sum_chunks, sum_rest) = sum.as_chunks::<CHUNK>();
    let (gx_chunks, gx_rest) = gx.as_chunks::<CHUNK>();
    let (gy_chunks, gy_rest) = gy.as_chunks::<CHUNK>();
    let chunks = coverage_chunks
        .iter_mut()
        .zip(sum_chunks)
        .zip(gx_chunks.iter().zip(gy_chunks));
    for ((coverage, sum), (gx, gy)) in chunks {
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
    let rest = coverage_rest
        .iter_mut()
        .zip(sum_rest.iter().zip(gx_rest.iter().zip(gy_rest)));
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
        + coverage[first_chunk * CHUNK..]
            .iter()
            .position(|&c| c > 0.0)?;
    let last_start = last_chunk * CHUNK;
    let last = last_start
        + coverage[last_start..(last_start + CHUNK).min(coverage.len())]
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

    #[test]
    fn bytes_round_clamp_and_map_nan_to_zero() {
        assert_eq!(to_byte(f32::NAN), 0);
        assert_eq!(to_byte(-1.0), 0);
        assert_eq!(to_byte(2.0), 255);
        assert_eq!(to_byte(0.5), 128);
        assert_eq!(to_byte(1.0 / 255.0), 1);
    }
}
