//! The 2D preview: the creature at rest, drawn by the crate's own rasteriser ([`raster`](super::raster)).

use alloc::vec::Vec;

use glam::{Vec2, Vec3};

use super::image_png;
use super::raster::{Canvas, Paint, Rule, Shape};
use crate::Error;
use crate::image::Image;

/// What [`preview_2d_png`] draws.
///
/// ```
/// use creature::export::PreviewOptions;
///
/// let options = PreviewOptions::DEFAULT.with_size(256).with_bones(true);
/// assert!(options.outline);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct PreviewOptions {
    /// The longer side of the image in pixels, margins included; from 16 to 8192. Default 512.
    pub size: u32,
    /// Draw the texture (or, without one, flat colours). Default `true`.
    pub textured: bool,
    /// Draw the mesh's edges. Default `false`.
    pub mesh: bool,
    /// Draw the outline. Default `true`.
    pub outline: bool,
    /// Draw the bones and joints. Default `false`.
    pub bones: bool,
    /// Draw the eyes. Default `true`.
    pub eyes: bool,
    /// Background RGBA. Default opaque white.
    pub background: [u8; 4],
}

impl PreviewOptions {
    /// The defaults.
    pub const DEFAULT: Self = Self {
        size: 512,
        textured: true,
        mesh: false,
        outline: true,
        bones: false,
        eyes: true,
        background: [255, 255, 255, 255],
    };

    /// Sets [`size`](Self::size).
    #[must_use]
    pub const fn with_size(mut self, size: u32) -> Self {
        self.size = size;
        self
    }
    /// Sets [`textured`](Self::textured).
    #[must_use]
    pub const fn with_textured(mut self, textured: bool) -> Self {
        self.textured = textured;
        self
    }
    /// Sets [`mesh`](Self::mesh).
    #[must_use]
    pub const fn with_mesh(mut self, mesh: bool) -> Self {
        self.mesh = mesh;
        self
    }
    /// Sets [`outline`](Self::outline).
    #[must_use]
    pub const fn with_outline(mut self, outline: bool) -> Self {
        self.outline = outline;
        self
    }
    /// Sets [`bones`](Self::bones).
    #[must_use]
    pub const fn with_bones(mut self, bones: bool) -> Self {
        self.bones = bones;
        self
    }
    /// Sets [`eyes`](Self::eyes).
    #[must_use]
    pub const fn with_eyes(mut self, eyes: bool) -> Self {
        self.eyes = eyes;
        self
    }
    /// Sets [`background`](Self::background).
    #[must_use]
    pub const fn with_background(mut self, background: [u8; 4]) -> Self {
        self.background = background;
        self
    }
}

impl Default for PreviewOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The world → image mapping of a preview.
#[derive(Clone, Copy)]
struct View {
    min: Vec2,
    max: Vec2,
    scale: f32,
    margin: f32,
}

impl View {
    fn new(c: &crate::d2::Creature, size: u32) -> (Self, u32, u32) {
        let (min, max) = c.bounds;
        // Eyes and bones may reach past the outline.
        let extent = (max - min).max(Vec2::splat(1e-3));
        let margin = (size as f32 * 0.04).max(2.0);
        let scale = (size as f32 - 2.0 * margin) / extent.max_element();
        // The longer side is `size` exactly; rounding may put it a hair above, which `ceil`
        // would turn into a whole extra pixel.
        let side = |length: f32| {
            (length * scale + 2.0 * margin)
                .ceil()
                .clamp(1.0, size as f32) as u32
        };
        let (w, h) = (side(extent.x), side(extent.y));
        (
            Self {
                min,
                max,
                scale,
                margin,
            },
            w,
            h,
        )
    }

    fn point(&self, p: Vec2) -> Vec2 {
        Vec2::new(
            self.margin + (p.x - self.min.x) * self.scale,
            self.margin + (self.max.y - p.y) * self.scale,
        )
    }
}

/// Renders a preview of the creature at rest: its texture (or flat colours) inside the
/// outline, and optionally the mesh, outline, bones and eyes, as PNG bytes.
///
/// # Errors
/// [`Error::OutOfRange`] for a size outside 16–8192; [`Error::Export`] if encoding fails.
pub fn preview_2d_png(
    creature: &crate::d2::Creature,
    options: &PreviewOptions,
) -> Result<Vec<u8>, Error> {
    image_png(&preview(creature, options)?)
}

/// [`preview_2d_png`]'s picture as a straight-alpha RGBA [`Image`], for composing galleries.
///
/// # Errors
/// As [`preview_2d_png`].
pub fn preview_2d(
    creature: &crate::d2::Creature,
    options: &PreviewOptions,
) -> Result<Image, Error> {
    preview(creature, options)
}

fn preview(c: &crate::d2::Creature, options: &PreviewOptions) -> Result<Image, Error> {
    if !(16..=8192).contains(&options.size) {
        return Err(Error::OutOfRange {
            what: "preview size",
            value: options.size as f32,
            min: 16.0,
            max: 8192.0,
        });
    }
    let (view, w, h) = View::new(c, options.size);
    let mut canvas = Canvas::new(w, h, options.background);
    let rings: Vec<Vec<Vec2>> = c
        .outline
        .iter()
        .map(|ring| ring.iter().map(|&p| view.point(p)).collect())
        .collect();

    if options.textured {
        let mut body = Shape::new();
        for ring in &rings {
            body.polygon(ring);
        }
        let paint = match &c.texture {
            Some(t) if t.width > 0 && t.height > 0 => {
                let (min, max) = c.bounds;
                Paint::Texture {
                    image: t,
                    origin: Vec2::splat(view.margin),
                    scale: Vec2::new(
                        (max.x - min.x) / t.width as f32 * view.scale,
                        (max.y - min.y) / t.height as f32 * view.scale,
                    ),
                }
            }
            _ => {
                let n = c.balls.len().max(1) as f32;
                let mean = c.balls.iter().map(|b| b.colour).sum::<Vec3>() / n;
                let [r, g, b] = mean.to_array().map(|v| (v.clamp(0.0, 1.0) * 255.0) as u8);
                Paint::Solid([r, g, b, 255])
            }
        };
        canvas.fill(&mut body, Rule::EvenOdd, &paint);
    }

    let width = (options.size as f32 / 512.0).max(0.5);
    if options.mesh {
        let mut edges = Shape::new();
        for t in &c.mesh.indices {
            let pts: Vec<Vec2> = t
                .iter()
                .filter_map(|&i| c.mesh.positions.get(i as usize))
                .map(|p| view.point(p.truncate()))
                .collect();
            if let [a, b, d] = pts[..] {
                for (from, to) in [(a, b), (b, d), (d, a)] {
                    edges.segment(from, to, width * 0.6);
                }
            }
        }
        canvas.fill(&mut edges, Rule::NonZero, &Paint::Solid([20, 20, 20, 90]));
    }
    if options.outline {
        let mut outline = Shape::new();
        for ring in &rings {
            outline.polyline(ring, true, width * 1.5);
        }
        canvas.fill(
            &mut outline,
            Rule::NonZero,
            &Paint::Solid([25, 25, 25, 255]),
        );
    }
    if options.bones {
        let red = Paint::Solid([200, 30, 30, 255]);
        let mut sticks = Shape::new();
        for bone in &c.bones {
            if let Some(parent) = bone.parent.and_then(|p| c.bones.get(p)) {
                let (a, b) = (view.point(parent.position), view.point(bone.position));
                sticks.segment(a, b, width * 1.5);
            }
        }
        canvas.fill(&mut sticks, Rule::NonZero, &red);
        let mut dots = Shape::new();
        for bone in &c.bones {
            dots.disc(view.point(bone.position), width * 2.5);
        }
        canvas.fill(&mut dots, Rule::NonZero, &red);
    }
    if options.eyes {
        for eye in &c.eyes {
            let centre = view.point(eye.position);
            let r = (eye.radius * view.scale).max(0.5);
            for (radius, rgba) in [(r, [250, 250, 250, 255]), (r * 0.5, [15, 15, 15, 255])] {
                let mut disc = Shape::new();
                disc.disc(centre, radius.max(0.5));
                canvas.fill(&mut disc, Rule::NonZero, &Paint::Solid(rgba));
            }
            // The eye's rim: a ring `width` wide on its edge.
            let mut rim = Shape::new();
            rim.disc(centre, r + 0.5 * width);
            rim.disc(centre, (r - 0.5 * width).max(0.0));
            canvas.fill(&mut rim, Rule::EvenOdd, &Paint::Solid([15, 15, 15, 255]));
        }
    }
    Ok(canvas.into_image())
}
