//! The 2D preview: the creature at rest drawn with tiny-skia.

use alloc::vec::Vec;

use glam::{Vec2, Vec3};
use tiny_skia::{
    Color, FillRule, FilterQuality, IntSize, Paint, PathBuilder, Pattern, Pixmap, SpreadMode,
    Stroke, Transform,
};

use super::{export_error, image_png};
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

    fn point(&self, p: Vec2) -> (f32, f32) {
        (
            self.margin + (p.x - self.min.x) * self.scale,
            self.margin + (self.max.y - p.y) * self.scale,
        )
    }
}

fn premultiplied(image: &Image) -> Option<Pixmap> {
    let mut data = image.rgba.clone();
    for px in data.chunks_exact_mut(4) {
        let a = u16::from(px[3]);
        for c in &mut px[..3] {
            *c = ((u16::from(*c) * a + 127) / 255) as u8;
        }
    }
    Pixmap::from_vec(data, IntSize::from_wh(image.width, image.height)?)
}

/// Renders a preview of the creature at rest: its texture (or flat colours) inside the
/// outline, and optionally the mesh, outline, bones and eyes, as PNG bytes.
///
/// # Errors
/// [`Error::OutOfRange`] for a size outside 16–8192; [`Error::Export`] if drawing or encoding
/// fails.
pub fn preview_2d_png(
    creature: &crate::d2::Creature,
    options: &PreviewOptions,
) -> Result<Vec<u8>, Error> {
    let pixmap = preview(creature, options)?;
    let mut rgba = Vec::with_capacity(pixmap.data().len());
    for px in pixmap.pixels() {
        let c = px.demultiply();
        rgba.extend_from_slice(&[c.red(), c.green(), c.blue(), c.alpha()]);
    }
    image_png(&Image {
        width: pixmap.width(),
        height: pixmap.height(),
        rgba,
    })
}

/// [`preview_2d_png`]'s picture as a straight-alpha RGBA [`Image`], for composing galleries.
///
/// # Errors
/// As [`preview_2d_png`].
pub fn preview_2d(
    creature: &crate::d2::Creature,
    options: &PreviewOptions,
) -> Result<Image, Error> {
    let pixmap = preview(creature, options)?;
    let mut rgba = Vec::with_capacity(pixmap.data().len());
    for px in pixmap.pixels() {
        let c = px.demultiply();
        rgba.extend_from_slice(&[c.red(), c.green(), c.blue(), c.alpha()]);
    }
    Ok(Image {
        width: pixmap.width(),
        height: pixmap.height(),
        rgba,
    })
}

fn preview(c: &crate::d2::Creature, options: &PreviewOptions) -> Result<Pixmap, Error> {
    if !(16..=8192).contains(&options.size) {
        return Err(Error::OutOfRange {
            what: "preview size",
            value: options.size as f32,
            min: 16.0,
            max: 8192.0,
        });
    }
    let (view, w, h) = View::new(c, options.size);
    let mut pixmap = Pixmap::new(w, h).ok_or_else(|| export_error("png", "empty image"))?;
    let [r, g, b, a] = options.background;
    pixmap.fill(Color::from_rgba8(r, g, b, a));

    let mut outline = PathBuilder::new();
    for ring in &c.outline {
        for (i, &p) in ring.iter().enumerate() {
            let (x, y) = view.point(p);
            if i == 0 {
                outline.move_to(x, y);
            } else {
                outline.line_to(x, y);
            }
        }
        outline.close();
    }
    let outline = outline.finish();

    if options.textured
        && let Some(path) = &outline
    {
        {
            let texture = c.texture.as_ref().and_then(premultiplied);
            let mut paint = Paint {
                anti_alias: true,
                ..Paint::default()
            };
            match &texture {
                Some(t) => {
                    let (min, max) = c.bounds;
                    let sx = (max.x - min.x) / t.width() as f32 * view.scale;
                    let sy = (max.y - min.y) / t.height() as f32 * view.scale;
                    paint.shader = Pattern::new(
                        t.as_ref(),
                        SpreadMode::Pad,
                        FilterQuality::Bilinear,
                        1.0,
                        Transform::from_row(sx, 0.0, 0.0, sy, view.margin, view.margin),
                    );
                }
                None => {
                    let n = c.balls.len().max(1) as f32;
                    let mean = c.balls.iter().map(|b| b.colour).sum::<Vec3>() / n;
                    let [r, g, b] = mean.to_array().map(|v| (v.clamp(0.0, 1.0) * 255.0) as u8);
                    paint.set_color_rgba8(r, g, b, 255);
                }
            }
            pixmap.fill_path(path, &paint, FillRule::EvenOdd, Transform::identity(), None);
        }
    }

    let line = |pixmap: &mut Pixmap, path: &tiny_skia::Path, rgba: [u8; 4], width: f32| {
        let mut paint = Paint {
            anti_alias: true,
            ..Paint::default()
        };
        paint.set_color_rgba8(rgba[0], rgba[1], rgba[2], rgba[3]);
        let stroke = Stroke {
            width,
            ..Stroke::default()
        };
        pixmap.stroke_path(path, &paint, &stroke, Transform::identity(), None);
    };
    let width = (options.size as f32 / 512.0).max(0.5);

    if options.mesh {
        let mut pb = PathBuilder::new();
        for t in &c.mesh.indices {
            let pts: Vec<(f32, f32)> = t
                .iter()
                .filter_map(|&i| c.mesh.positions.get(i as usize))
                .map(|p| view.point(p.truncate()))
                .collect();
            if let [a, b, d] = pts[..] {
                pb.move_to(a.0, a.1);
                pb.line_to(b.0, b.1);
                pb.line_to(d.0, d.1);
                pb.close();
            }
        }
        if let Some(path) = pb.finish() {
            line(&mut pixmap, &path, [20, 20, 20, 90], width * 0.6);
        }
    }
    if options.outline
        && let Some(path) = &outline
    {
        line(&mut pixmap, path, [25, 25, 25, 255], width * 1.5);
    }
    if options.bones {
        let mut pb = PathBuilder::new();
        for bone in &c.bones {
            if let Some(parent) = bone.parent.and_then(|p| c.bones.get(p)) {
                let (x0, y0) = view.point(parent.position);
                let (x1, y1) = view.point(bone.position);
                pb.move_to(x0, y0);
                pb.line_to(x1, y1);
            }
        }
        if let Some(path) = pb.finish() {
            line(&mut pixmap, &path, [200, 30, 30, 255], width * 1.5);
        }
        for bone in &c.bones {
            let (x, y) = view.point(bone.position);
            if let Some(dot) = PathBuilder::from_circle(x, y, width * 2.5) {
                let mut paint = Paint::default();
                paint.set_color_rgba8(200, 30, 30, 255);
                paint.anti_alias = true;
                pixmap.fill_path(&dot, &paint, FillRule::Winding, Transform::identity(), None);
            }
        }
    }
    if options.eyes {
        for eye in &c.eyes {
            let (x, y) = view.point(eye.position);
            let r = eye.radius * view.scale;
            for (radius, rgba) in [(r, [250, 250, 250, 255]), (r * 0.5, [15, 15, 15, 255])] {
                if let Some(disc) = PathBuilder::from_circle(x, y, radius.max(0.5)) {
                    let mut paint = Paint::default();
                    paint.set_color_rgba8(rgba[0], rgba[1], rgba[2], rgba[3]);
                    paint.anti_alias = true;
                    pixmap.fill_path(
                        &disc,
                        &paint,
                        FillRule::Winding,
                        Transform::identity(),
                        None,
                    );
                }
            }
            if let Some(disc) = PathBuilder::from_circle(x, y, r.max(0.5)) {
                line(&mut pixmap, &disc, [15, 15, 15, 255], width);
            }
        }
    }
    Ok(pixmap)
}
