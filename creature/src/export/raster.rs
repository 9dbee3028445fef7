//! A small anti-aliased 2D rasteriser for the 2D preview: polygons filled (even-odd or
//! non-zero) with a colour or a texture, lines stroked as filled quads, discs as polygons.
//!
//! Coverage is exact across each pixel horizontally and sampled on [`SUB`] rows vertically;
//! colours are blended source-over in premultiplied alpha. Every step is IEEE arithmetic
//! (and the crate's `sin`/`cos`), so a build with the `libm` feature draws the same bytes on
//! every platform.

use alloc::vec;
use alloc::vec::Vec;

use glam::{Vec2, Vec4};

use crate::image::Image;

/// Sample rows per pixel row.
const SUB: usize = 5;

/// How a filled shape decides what is inside.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Rule {
    /// Inside where a ray crosses the boundary an odd number of times (holes in rings).
    EvenOdd,
    /// Inside where the boundary winds round a nonzero number of times (overlapping pieces
    /// unite).
    NonZero,
}

/// What a shape is painted with.
pub(super) enum Paint<'a> {
    /// One colour, straight-alpha RGBA.
    Solid([u8; 4]),
    /// A straight-alpha texture, stretched so that texel `(i, j)`'s centre lands at
    /// `origin + (i + ½, j + ½) × scale` (canvas pixels), sampled bilinearly with its edge
    /// texels repeated beyond it.
    Texture {
        image: &'a Image,
        origin: Vec2,
        scale: Vec2,
    },
}

/// A polygon's directed edges, collected for one fill.
#[derive(Default)]
pub(super) struct Shape {
    /// `(top, bottom, x at top, dx/dy, winding)`: `top < bottom`; winding +1 for an edge
    /// going down, −1 going up.
    edges: Vec<(f32, f32, f32, f32, i32)>,
}

impl Shape {
    pub(super) fn new() -> Self {
        Self::default()
    }

    /// Adds the closed polygon through `points` (the last joined back to the first).
    pub(super) fn polygon(&mut self, points: &[Vec2]) {
        let Some(&last) = points.last() else {
            return;
        };
        let mut a = last;
        for &b in points {
            self.edge(a, b);
            a = b;
        }
    }

    fn edge(&mut self, a: Vec2, b: Vec2) {
        if !(a.is_finite() && b.is_finite()) || a.y == b.y {
            return;
        }
        let (top, bottom, winding) = if a.y < b.y { (a, b, 1) } else { (b, a, -1) };
        // An edge whose slope overflows (a subnormal rise, or a run past `f32::MAX`) is taken
        // as vertical: it keeps the windings right, and a rise that short spans no sample row.
        let slope = (bottom.x - top.x) / (bottom.y - top.y);
        let slope = if slope.is_finite() { slope } else { 0.0 };
        self.edges.push((top.y, bottom.y, top.x, slope, winding));
    }

    /// Adds a stroke of `width` along the segment from `a` to `b` (square ends at the points:
    /// no cap), turned so its winding adds to the others' under [`Rule::NonZero`].
    pub(super) fn segment(&mut self, a: Vec2, b: Vec2, width: f32) {
        let d = b - a;
        let length = d.length();
        if !(length > 0.0) {
            return;
        }
        // `n` is a → b turned a quarter clockwise on the canvas (y down): the quad a − n,
        // b − n, b + n, a + n runs clockwise for every segment, as `circle` does.
        let n = Vec2::new(-d.y, d.x) * (0.5 * width / length);
        self.polygon(&[a - n, b - n, b + n, a + n]);
    }

    /// Adds a disc of `radius` about `centre` as a polygon fine enough that it is round to
    /// within a tenth of a pixel, wound as [`segment`](Self::segment)'s quads.
    pub(super) fn disc(&mut self, centre: Vec2, radius: f32) {
        if !(radius > 0.0) {
            return;
        }
        let points: Vec<Vec2> = circle(centre, radius).collect();
        self.polygon(&points);
    }

    /// Adds a stroke of `width` along `points`, closed back to the first when `closed`, with
    /// a disc at each point so that turns have no notch.
    pub(super) fn polyline(&mut self, points: &[Vec2], closed: bool, width: f32) {
        for pair in points.windows(2) {
            self.segment(pair[0], pair[1], width);
        }
        if closed && let (Some(&first), Some(&last)) = (points.first(), points.last()) {
            self.segment(last, first, width);
        }
        let joints = if closed {
            points
        } else {
            points.get(1..points.len().saturating_sub(1)).unwrap_or(&[])
        };
        for &p in joints {
            self.disc(p, 0.5 * width);
        }
    }
}

/// Points round a circle, clockwise on the canvas (y down), as a stroke's quads: as many as keep
/// each chord within a tenth of a pixel of the arc (at least 8, at most 256).
fn circle(centre: Vec2, radius: f32) -> impl Iterator<Item = Vec2> {
    // A chord of angle θ sags r (1 − cos(θ/2)) ≈ r θ² / 8: θ = √(0.8 / r).
    let n = (core::f32::consts::TAU / crate::math::sqrt(0.8 / radius)).clamp(8.0, 256.0) as usize;
    (0..n).map(move |k| {
        let angle = core::f32::consts::TAU * k as f32 / n as f32;
        centre + Vec2::new(crate::math::cos(angle), crate::math::sin(angle)) * radius
    })
}

/// A canvas of premultiplied RGBA bytes (blended in `f32`, stored as tiny-skia stores them:
/// 4 bytes a pixel).
pub(super) struct Canvas {
    width: usize,
    height: usize,
    pixels: Vec<[u8; 4]>,
    /// Each pixel's coverage in the row being filled, and the sample rows' crossings.
    coverage: Vec<f32>,
    crossings: Vec<(f32, i32)>,
}

impl Canvas {
    /// A canvas of `width × height` pixels filled with `background` (straight-alpha RGBA).
    pub(super) fn new(width: u32, height: u32, background: [u8; 4]) -> Self {
        let (width, height) = (width as usize, height as usize);
        Self {
            width,
            height,
            pixels: vec![bytes(premultiply(background)); width * height],
            coverage: vec![0.0; width + 1],
            crossings: Vec::new(),
        }
    }

    /// Paints `shape`'s inside (by `rule`) with `paint`, blended over what is there.
    pub(super) fn fill(&mut self, shape: &mut Shape, rule: Rule, paint: &Paint<'_>) {
        let edges = &mut shape.edges;
        if edges.is_empty() || self.width == 0 {
            return;
        }
        edges.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        let colour = match paint {
            Paint::Solid(rgba) => Some(premultiply(*rgba)),
            Paint::Texture { .. } => None,
        };
        let top = edges[0].0.max(0.0);
        let bottom = edges.iter().map(|e| e.1).fold(f32::NEG_INFINITY, f32::max);
        // Non-negative and finite here: `as usize` is the floor.
        let first = (top as usize).min(self.height);
        let last = if bottom > 0.0 {
            (bottom.ceil() as usize).min(self.height)
        } else {
            0
        };
        let mut active: Vec<usize> = Vec::new();
        let mut next = 0;
        let share = 1.0 / SUB as f32;
        for row in first..last {
            self.coverage.fill(0.0);
            let (mut lo, mut hi) = (self.width, 0);
            for s in 0..SUB {
                let y = row as f32 + (s as f32 + 0.5) * share;
                while next < edges.len() && edges[next].0 <= y {
                    active.push(next);
                    next += 1;
                }
                active.retain(|&e| edges[e].1 > y);
                self.crossings.clear();
                for &e in &active {
                    let (t, _, x, slope, winding) = edges[e];
                    if t <= y {
                        self.crossings.push((x + (y - t) * slope, winding));
                    }
                }
                self.crossings.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
                let mut inside = 0;
                for k in 0..self.crossings.len() {
                    let (x, winding) = self.crossings[k];
                    inside = match rule {
                        Rule::EvenOdd => inside ^ 1,
                        Rule::NonZero => inside + winding,
                    };
                    if inside != 0
                        && let Some(&(end, _)) = self.crossings.get(k + 1)
                    {
                        let span = span(&mut self.coverage, x, end, share);
                        if let Some((a, b)) = span {
                            lo = lo.min(a);
                            hi = hi.max(b);
                        }
                    }
                }
            }
            for x in lo..hi.min(self.width) {
                let c = self.coverage[x].min(1.0);
                if c <= 0.0 {
                    continue;
                }
                let source = match (colour, paint) {
                    (Some(colour), _) => colour,
                    (
                        None,
                        Paint::Texture {
                            image,
                            origin,
                            scale,
                        },
                    ) => sample(
                        image,
                        (Vec2::new(x as f32 + 0.5, row as f32 + 0.5) - *origin) / *scale,
                    ),
                    (None, Paint::Solid(_)) => continue,
                };
                let pixel = &mut self.pixels[row * self.width + x];
                let s = source * c;
                let d = Vec4::from(pixel.map(f32::from)) / 255.0;
                *pixel = bytes(s + d * (1.0 - s.w));
            }
        }
    }

    /// The picture as straight-alpha RGBA bytes.
    pub(super) fn into_image(self) -> Image {
        let mut rgba = Vec::with_capacity(self.pixels.len() * 4);
        for &[r, g, b, a] in &self.pixels {
            let straight = |c: u8| {
                if a == 0 {
                    0
                } else {
                    // Rounded; at most 255 for `c ≤ a` (premultiplied), clamped all the same.
                    ((u16::from(c) * 255 + u16::from(a) / 2) / u16::from(a)).min(255) as u8
                }
            };
            rgba.extend_from_slice(&[straight(r), straight(g), straight(b), a]);
        }
        Image {
            width: self.width as u32,
            height: self.height as u32,
            rgba,
        }
    }
}

/// Adds `share` × the length of `[from, to)` inside each pixel to `coverage` (one row's
/// pixels, the last entry a spare past the right edge); returns the pixels touched.
fn span(coverage: &mut [f32], from: f32, to: f32, share: f32) -> Option<(usize, usize)> {
    let width = coverage.len() - 1;
    let (from, to) = (from.max(0.0), to.min(width as f32));
    if !(from < to) {
        return None;
    }
    // Non-negative and below `width` here: `as usize` is the floor.
    let (a, b) = (from as usize, (to as usize).min(width - 1));
    if a == b {
        coverage[a] += (to - from) * share;
    } else {
        coverage[a] += (a as f32 + 1.0 - from) * share;
        for c in &mut coverage[a + 1..b] {
            *c += share;
        }
        coverage[b] += (to - b as f32) * share;
    }
    Some((a, b + 1))
}

/// Premultiplied `[0, 1]` as bytes (rounded).
fn bytes(v: Vec4) -> [u8; 4] {
    // Clamped to [0, 255] first (a NaN to 0): the rounded value fits a byte.
    let byte = |v: f32| crate::math::round_non_negative(v.clamp(0.0, 1.0) * 255.0) as u8;
    [byte(v.x), byte(v.y), byte(v.z), byte(v.w)]
}

/// Straight-alpha RGBA bytes as premultiplied `[0, 1]`.
fn premultiply([r, g, b, a]: [u8; 4]) -> Vec4 {
    let a = f32::from(a) / 255.0;
    Vec4::new(
        f32::from(r) / 255.0 * a,
        f32::from(g) / 255.0 * a,
        f32::from(b) / 255.0 * a,
        a,
    )
}

/// `image` (straight alpha) sampled bilinearly at texel coordinates `at` (texel `(i, j)`'s
/// centre at `(i + ½, j + ½)`), premultiplied; edge texels repeat beyond the edges.
fn sample(image: &Image, at: Vec2) -> Vec4 {
    let (w, h) = (image.width as usize, image.height as usize);
    if w == 0 || h == 0 || !at.is_finite() {
        return Vec4::ZERO;
    }
    let max = Vec2::new((w - 1) as f32, (h - 1) as f32);
    let p = (at - 0.5).clamp(Vec2::ZERO, max);
    // Non-negative here: `as usize` is the floor.
    let (i, j) = (p.x as usize, p.y as usize);
    let (u, v) = (p.x - i as f32, p.y - j as f32);
    let texel = |i: usize, j: usize| {
        let k = (j.min(h - 1) * w + i.min(w - 1)) * 4;
        image
            .rgba
            .get(k..k + 4)
            .map_or(Vec4::ZERO, |t| premultiply([t[0], t[1], t[2], t[3]]))
    };
    let top = texel(i, j).lerp(texel(i + 1, j), u);
    let bottom = texel(i, j + 1).lerp(texel(i + 1, j + 1), u);
    top.lerp(bottom, v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn alpha_sum(canvas: Canvas) -> f32 {
        canvas.pixels.iter().map(|p| f32::from(p[3]) / 255.0).sum()
    }

    #[test]
    fn a_filled_square_covers_its_area() {
        let mut canvas = Canvas::new(20, 20, [0, 0, 0, 0]);
        let mut shape = Shape::new();
        shape.polygon(&[
            Vec2::new(2.25, 3.5),
            Vec2::new(12.25, 3.5),
            Vec2::new(12.25, 13.5),
            Vec2::new(2.25, 13.5),
        ]);
        canvas.fill(&mut shape, Rule::NonZero, &Paint::Solid([255, 0, 0, 255]));
        assert!((alpha_sum(canvas) - 100.0).abs() < 0.5);
    }

    /// The area of the polygon `circle` makes (shoelace).
    fn polygon_area(centre: Vec2, radius: f32) -> f32 {
        let points: Vec<Vec2> = circle(centre, radius).collect();
        let mut twice = 0.0;
        for (k, &a) in points.iter().enumerate() {
            twice += a.perp_dot(points[(k + 1) % points.len()]);
        }
        0.5 * twice.abs()
    }

    #[test]
    fn a_disc_covers_its_area_and_even_odd_rings_have_holes() {
        let centre = Vec2::new(20.25, 19.75);
        let mut canvas = Canvas::new(40, 40, [0, 0, 0, 0]);
        let mut shape = Shape::new();
        shape.disc(centre, 10.0);
        canvas.fill(&mut shape, Rule::NonZero, &Paint::Solid([0, 0, 255, 255]));
        let area = polygon_area(centre, 10.0);
        assert!((alpha_sum(canvas) - area).abs() < 0.005 * area);
        // Round to within a tenth of a pixel: the polygon is within 2% of the circle.
        assert!((area / (core::f32::consts::PI * 100.0) - 1.0).abs() < 0.02);

        let mut canvas = Canvas::new(40, 40, [0, 0, 0, 0]);
        let mut shape = Shape::new();
        shape.disc(centre, 10.0);
        shape.disc(centre, 5.0);
        canvas.fill(&mut shape, Rule::EvenOdd, &Paint::Solid([0, 0, 255, 255]));
        let ring = area - polygon_area(centre, 5.0);
        assert!((alpha_sum(canvas) - ring).abs() < 0.005 * ring);
    }

    #[test]
    fn overlapping_strokes_unite_under_non_zero() {
        // Two crossing strokes: their crossing painted once, not twice.
        let mut canvas = Canvas::new(30, 30, [0, 0, 0, 0]);
        let mut shape = Shape::new();
        shape.segment(Vec2::new(5.0, 15.0), Vec2::new(25.0, 15.0), 2.0);
        shape.segment(Vec2::new(15.0, 25.0), Vec2::new(15.0, 5.0), 2.0);
        canvas.fill(&mut shape, Rule::NonZero, &Paint::Solid([0, 0, 0, 128]));
        let max = canvas.pixels.iter().map(|p| p[3]).max();
        assert_eq!(max, Some(128));
    }

    #[test]
    fn a_texture_is_sampled_at_texel_centres() {
        let image = Image {
            width: 2,
            height: 1,
            rgba: vec![255, 0, 0, 255, 0, 0, 255, 255],
        };
        assert_eq!(
            sample(&image, Vec2::new(0.5, 0.5)),
            Vec4::new(1.0, 0.0, 0.0, 1.0)
        );
        assert_eq!(
            sample(&image, Vec2::new(1.0, 0.5)),
            Vec4::new(0.5, 0.0, 0.5, 1.0)
        );
        assert_eq!(
            sample(&image, Vec2::new(9.0, 0.5)),
            Vec4::new(0.0, 0.0, 1.0, 1.0)
        );
    }
}
