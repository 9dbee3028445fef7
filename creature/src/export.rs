//! Exporters (feature `export`): a preview PNG, an SVG of the outline and mesh, and a skinned
//! glTF 2.0 binary (`.glb`) with the texture and normal map embedded.
//!
//! Every function returns the file's bytes or text; writing it is the caller's business.
//!
//! ```
//! use creature::{export, generate_2d, Params2d};
//!
//! let creature = generate_2d(7, &Params2d::DEFAULT.with_texture_size(64))?;
//! let glb = export::glb(&creature)?;
//! assert_eq!(&glb[..4], b"glTF");
//! let png = export::preview_png(&creature, &export::PreviewOptions::DEFAULT)?;
//! assert_eq!(&png[1..4], b"PNG");
//! let svg = export::svg(&creature);
//! assert!(svg.starts_with("<svg"));
//! # Ok::<(), creature::Error>(())
//! ```

use alloc::collections::BTreeMap;
use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec;
use alloc::vec::Vec;
use core::fmt::Write as _;

use glam::{Mat4, Vec2, Vec3};
use gltf_json as json;
use json::validation::{Checked, USize64};
use tiny_skia::{
    Color, FillRule, FilterQuality, IntSize, Paint, PathBuilder, Pattern, Pixmap, SpreadMode,
    Stroke, Transform,
};

use crate::Error;
use crate::texture::Image;
use crate::types::Creature2d;

pub use crate::export3d::glb_3d;

pub(crate) fn export_error(format: &'static str, message: impl ToString) -> Error {
    Error::Export {
        format,
        message: message.to_string(),
    }
}

/// Encodes an [`Image`] as an 8-bit RGBA PNG.
///
/// # Errors
/// [`Error::Export`] when the image's size and data disagree or the encoder fails.
pub fn image_png(image: &Image) -> Result<Vec<u8>, Error> {
    let expected = image.width as usize * image.height as usize * 4;
    if image.rgba.len() != expected || image.width == 0 || image.height == 0 {
        return Err(export_error("png", "image size and data length disagree"));
    }
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, image.width, image.height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(|e| export_error("png", e))?;
        writer
            .write_image_data(&image.rgba)
            .map_err(|e| export_error("png", e))?;
        writer.finish().map_err(|e| export_error("png", e))?;
    }
    Ok(out)
}

/// What [`preview_png`] draws.
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
    fn new(c: &Creature2d, size: u32) -> (Self, u32, u32) {
        let (min, max) = c.bounds;
        // Eyes and bones may reach past the outline.
        let extent = (max - min).max(Vec2::splat(1e-3));
        let margin = (size as f32 * 0.04).max(2.0);
        let scale = (size as f32 - 2.0 * margin) / extent.max_element();
        let w = (extent.x * scale + 2.0 * margin).ceil().max(1.0) as u32;
        let h = (extent.y * scale + 2.0 * margin).ceil().max(1.0) as u32;
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
pub fn preview_png(creature: &Creature2d, options: &PreviewOptions) -> Result<Vec<u8>, Error> {
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

/// [`preview_png`]'s picture as a straight-alpha RGBA [`Image`], for composing galleries.
///
/// # Errors
/// As [`preview_png`].
pub fn preview_image(creature: &Creature2d, options: &PreviewOptions) -> Result<Image, Error> {
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

fn preview(c: &Creature2d, options: &PreviewOptions) -> Result<Pixmap, Error> {
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

/// An SVG drawing of the outline (filled with the balls' mean colour), the mesh's edges, the
/// bones and the eyes, in world units (y up, flipped for SVG).
#[must_use]
pub fn svg(creature: &Creature2d) -> String {
    let (min, max) = creature.bounds;
    let pad = (max - min).max_element() * 0.05;
    let (x0, y0) = (min.x - pad, -max.y - pad);
    let (w, h) = (max.x - min.x + 2.0 * pad, max.y - min.y + 2.0 * pad);
    let n = creature.balls.len().max(1) as f32;
    let mean = creature.balls.iter().map(|b| b.colour).sum::<Vec3>() / n;
    let [r, g, b] = mean.to_array().map(|v| (v.clamp(0.0, 1.0) * 255.0) as u8);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{x0:.2} {y0:.2} {w:.2} {h:.2}" width="{:.0}" height="{:.0}">"#,
        w.max(1.0),
        h.max(1.0)
    );
    let _ = writeln!(s, r#"<g transform="scale(1,-1)">"#);
    let mut d = String::new();
    for ring in &creature.outline {
        for (i, p) in ring.iter().enumerate() {
            let _ = write!(
                d,
                "{}{:.2},{:.2} ",
                if i == 0 { "M" } else { "L" },
                p.x,
                p.y
            );
        }
        d.push_str("Z ");
    }
    let _ = writeln!(
        s,
        r#"<path d="{}" fill="rgb({r},{g},{b})" fill-rule="evenodd" stroke="none"/>"#,
        d.trim_end()
    );
    let mut m = String::new();
    for t in &creature.mesh.indices {
        let pts: Vec<Vec3> = t
            .iter()
            .filter_map(|&i| creature.mesh.positions.get(i as usize).copied())
            .collect();
        if let [a, b, c] = pts[..] {
            let _ = write!(
                m,
                "M{:.2},{:.2} L{:.2},{:.2} L{:.2},{:.2} Z ",
                a.x, a.y, b.x, b.y, c.x, c.y
            );
        }
    }
    let _ = writeln!(
        s,
        r#"<path d="{}" fill="none" stroke="black" stroke-opacity="0.35" stroke-width="0.4"/>"#,
        m.trim_end()
    );
    let _ = writeln!(
        s,
        r#"<path d="{}" fill="none" stroke="black" stroke-width="1.2"/>"#,
        d.trim_end()
    );
    for bone in &creature.bones {
        if let Some(parent) = bone.parent.and_then(|p| creature.bones.get(p)) {
            let _ = writeln!(
                s,
                r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="rgb(200,30,30)" stroke-width="1.5"/>"#,
                parent.position.x, parent.position.y, bone.position.x, bone.position.y
            );
        }
    }
    for eye in &creature.eyes {
        let _ = writeln!(
            s,
            r#"<circle cx="{:.2}" cy="{:.2}" r="{:.2}" fill="white" stroke="black"/><circle cx="{:.2}" cy="{:.2}" r="{:.2}" fill="black"/>"#,
            eye.position.x,
            eye.position.y,
            eye.radius,
            eye.position.x,
            eye.position.y,
            eye.radius * 0.5
        );
    }
    s.push_str("</g>\n</svg>\n");
    s
}

/// Binary buffer under construction: 4-byte aligned views.
pub(crate) struct Bin {
    pub(crate) data: Vec<u8>,
    pub(crate) views: Vec<json::buffer::View>,
}

impl Bin {
    pub(crate) fn push(
        &mut self,
        bytes: &[u8],
        target: Option<json::buffer::Target>,
    ) -> json::Index<json::buffer::View> {
        while !self.data.len().is_multiple_of(4) {
            self.data.push(0);
        }
        let offset = self.data.len();
        self.data.extend_from_slice(bytes);
        self.views.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: target.map(Checked::Valid),
            extensions: None,
            extras: Default::default(),
        });
        json::Index::new(self.views.len() as u32 - 1)
    }
}

pub(crate) fn accessor(
    view: json::Index<json::buffer::View>,
    count: usize,
    component: json::accessor::ComponentType,
    type_: json::accessor::Type,
    normalized: bool,
    bounds: Option<(Vec<f32>, Vec<f32>)>,
) -> json::Accessor {
    let (min, max) = match bounds {
        Some((lo, hi)) => (Some(json::Value::from(lo)), Some(json::Value::from(hi))),
        None => (None, None),
    };
    json::Accessor {
        buffer_view: Some(view),
        byte_offset: None,
        count: USize64::from(count),
        component_type: Checked::Valid(json::accessor::GenericComponentType(component)),
        extensions: None,
        extras: Default::default(),
        type_: Checked::Valid(type_),
        min,
        max,
        name: None,
        normalized,
        sparse: None,
    }
}

pub(crate) fn f32_bytes(values: impl IntoIterator<Item = f32>) -> Vec<u8> {
    values.into_iter().flat_map(f32::to_le_bytes).collect()
}

/// The creature as a glTF 2.0 binary (`.glb`): one skinned mesh (positions with the depth z,
/// normals +z, tangents +x, UVs, `JOINTS_0` as unsigned shorts, `WEIGHTS_0` as normalised
/// unsigned bytes summing to exactly 255), a joint node per bone (translations from the rest
/// offsets) with inverse bind matrices, and a material with the texture and normal map
/// embedded as PNG (metallic 0, roughness 0.9, as the seed). Written with `gltf-json`; checked
/// with the Khronos glTF-Validator by `cargo xtask verify-gltf`.
///
/// # Errors
/// [`Error::Export`] when the mesh is empty or too large, or encoding fails.
pub fn glb(creature: &Creature2d) -> Result<Vec<u8>, Error> {
    let m = &creature.mesh;
    let n = m.positions.len();
    if n == 0
        || m.indices.is_empty()
        || m.uvs.len() != n
        || m.joints.len() != n
        || m.weights.len() != n
    {
        return Err(export_error(
            "glb",
            "the mesh is empty or its attributes disagree",
        ));
    }
    if creature.bones.is_empty() || creature.bones.len() > usize::from(u16::MAX) {
        return Err(export_error("glb", "the skeleton is empty or too large"));
    }
    if m.indices.iter().flatten().any(|&i| i as usize >= n) {
        return Err(export_error("glb", "a triangle index is out of range"));
    }
    use json::accessor::{ComponentType as C, Type as T};
    use json::buffer::Target;
    let mut bin = Bin {
        data: Vec::new(),
        views: Vec::new(),
    };
    let mut root = json::Root {
        asset: json::Asset {
            generator: Some(format!("creature {}", env!("CARGO_PKG_VERSION"))),
            ..json::Asset::default()
        },
        ..json::Root::default()
    };

    // Vertex attributes.
    let mut lo = [f32::MAX; 3];
    let mut hi = [f32::MIN; 3];
    for p in &m.positions {
        for (k, v) in p.to_array().into_iter().enumerate() {
            lo[k] = lo[k].min(v);
            hi[k] = hi[k].max(v);
        }
    }
    let view = bin.push(
        &f32_bytes(m.positions.iter().flat_map(|p| p.to_array())),
        Some(Target::ArrayBuffer),
    );
    let positions = root.push(accessor(
        view,
        n,
        C::F32,
        T::Vec3,
        false,
        Some((lo.to_vec(), hi.to_vec())),
    ));
    let view = bin.push(
        &f32_bytes((0..n).flat_map(|_| [0.0, 0.0, 1.0])),
        Some(Target::ArrayBuffer),
    );
    let normals = root.push(accessor(view, n, C::F32, T::Vec3, false, None));
    let view = bin.push(
        &f32_bytes((0..n).flat_map(|_| [1.0, 0.0, 0.0, 1.0])),
        Some(Target::ArrayBuffer),
    );
    let tangents = root.push(accessor(view, n, C::F32, T::Vec4, false, None));
    let view = bin.push(
        &f32_bytes(m.uvs.iter().flat_map(|p| p.to_array())),
        Some(Target::ArrayBuffer),
    );
    let uvs = root.push(accessor(view, n, C::F32, T::Vec2, false, None));
    let mut joint_bytes = Vec::with_capacity(n * 8);
    let mut weight_bytes = Vec::with_capacity(n * 4);
    for (joints, weights) in m.joints.iter().zip(&m.weights) {
        let inf = creature_skin::Influences {
            joints: *joints,
            weights: *weights,
        };
        let q = inf.quantize_u8();
        for (j, w) in joints.iter().zip(q) {
            // A joint whose weight rounds to 0 is reset to 0 (glTF: unused slots are 0).
            let j = if w == 0 { 0 } else { *j };
            joint_bytes.extend_from_slice(&j.to_le_bytes());
            weight_bytes.push(w);
        }
    }
    let view = bin.push(&joint_bytes, Some(Target::ArrayBuffer));
    let joints = root.push(accessor(view, n, C::U16, T::Vec4, false, None));
    let view = bin.push(&weight_bytes, Some(Target::ArrayBuffer));
    let weights = root.push(accessor(view, n, C::U8, T::Vec4, true, None));
    let index_bytes: Vec<u8> = m
        .indices
        .iter()
        .flatten()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let view = bin.push(&index_bytes, Some(Target::ElementArrayBuffer));
    let indices = root.push(accessor(
        view,
        m.indices.len() * 3,
        C::U32,
        T::Scalar,
        false,
        None,
    ));

    // Material with the embedded textures.
    let sampler = root.push(json::texture::Sampler {
        mag_filter: Some(Checked::Valid(json::texture::MagFilter::Linear)),
        min_filter: Some(Checked::Valid(json::texture::MinFilter::Linear)),
        wrap_s: Checked::Valid(json::texture::WrappingMode::ClampToEdge),
        wrap_t: Checked::Valid(json::texture::WrappingMode::ClampToEdge),
        ..Default::default()
    });
    let texture_index = |root: &mut json::Root,
                         bin: &mut Bin,
                         image: &Image,
                         name: &str|
     -> Result<json::Index<json::Texture>, Error> {
        let png = image_png(image)?;
        let view = bin.push(&png, None);
        let image = root.push(json::Image {
            buffer_view: Some(view),
            mime_type: Some(json::image::MimeType("image/png".into())),
            name: Some(name.into()),
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
        Ok(root.push(json::Texture {
            name: Some(name.into()),
            sampler: Some(sampler),
            source: image,
            extensions: None,
            extras: Default::default(),
        }))
    };
    let mut material = json::Material {
        name: Some("creature".into()),
        double_sided: true,
        ..Default::default()
    };
    material.pbr_metallic_roughness.metallic_factor = json::material::StrengthFactor(0.0);
    material.pbr_metallic_roughness.roughness_factor = json::material::StrengthFactor(0.9);
    if let Some(t) = &creature.texture {
        let index = texture_index(&mut root, &mut bin, t, "albedo")?;
        material.pbr_metallic_roughness.base_color_texture = Some(json::texture::Info {
            index,
            tex_coord: 0,
            extensions: None,
            extras: Default::default(),
        });
    }
    if let Some(t) = &creature.normal_map {
        let index = texture_index(&mut root, &mut bin, t, "normals")?;
        material.normal_texture = Some(json::material::NormalTexture {
            index,
            scale: 1.0,
            tex_coord: 0,
            extensions: None,
            extras: Default::default(),
        });
    }
    let material = root.push(material);

    let mut attributes = BTreeMap::new();
    for (semantic, index) in [
        (json::mesh::Semantic::Positions, positions),
        (json::mesh::Semantic::Normals, normals),
        (json::mesh::Semantic::Tangents, tangents),
        (json::mesh::Semantic::TexCoords(0), uvs),
        (json::mesh::Semantic::Joints(0), joints),
        (json::mesh::Semantic::Weights(0), weights),
    ] {
        attributes.insert(Checked::Valid(semantic), index);
    }
    let mesh = root.push(json::Mesh {
        name: Some("creature".into()),
        primitives: vec![json::mesh::Primitive {
            attributes,
            indices: Some(indices),
            material: Some(material),
            mode: Checked::Valid(json::mesh::Mode::Triangles),
            targets: None,
            extensions: None,
            extras: Default::default(),
        }],
        weights: None,
        extensions: None,
        extras: Default::default(),
    });

    // Joints: one node per bone, children listed on their parents.
    let first_joint = root.nodes.len() as u32;
    let mut children: Vec<Vec<json::Index<json::Node>>> = vec![Vec::new(); creature.bones.len()];
    for (i, bone) in creature.bones.iter().enumerate() {
        if let Some(list) = bone.parent.and_then(|p| children.get_mut(p)) {
            list.push(json::Index::new(first_joint + i as u32));
        }
    }
    let mut inverse_bind = Vec::with_capacity(creature.bones.len() * 64);
    for (i, bone) in creature.bones.iter().enumerate() {
        let list = core::mem::take(&mut children[i]);
        let rotation = (bone.rotation != 0.0).then(|| {
            let q = glam::Quat::from_rotation_z(bone.rotation);
            json::scene::UnitQuaternion(q.to_array())
        });
        root.push(json::Node {
            children: (!list.is_empty()).then_some(list),
            name: Some(format!("bone{i}")),
            translation: Some([bone.offset.x, bone.offset.y, 0.0]),
            rotation,
            ..Default::default()
        });
        // The rest skeleton is a pure translation when no bone is rotated; in general the
        // inverse of the bone's rest world transform.
        let world = rest_world(creature, i);
        inverse_bind.extend(f32_bytes(world.inverse().to_cols_array()));
    }
    let view = bin.push(&inverse_bind, None);
    let ibm = root.push(accessor(
        view,
        creature.bones.len(),
        C::F32,
        T::Mat4,
        false,
        None,
    ));
    let skin = root.push(json::Skin {
        inverse_bind_matrices: Some(ibm),
        joints: (0..creature.bones.len() as u32)
            .map(|i| json::Index::new(first_joint + i))
            .collect(),
        skeleton: Some(json::Index::new(first_joint)),
        name: Some("skeleton".into()),
        extensions: None,
        extras: Default::default(),
    });
    let mesh_node = root.push(json::Node {
        mesh: Some(mesh),
        skin: Some(skin),
        name: Some("creature".into()),
        ..Default::default()
    });
    let scene = root.push(json::Scene {
        name: Some("creature".into()),
        nodes: vec![json::Index::new(first_joint), mesh_node],
        extensions: None,
        extras: Default::default(),
    });
    root.scene = Some(scene);

    while !bin.data.len().is_multiple_of(4) {
        bin.data.push(0);
    }
    root.buffers.push(json::Buffer {
        byte_length: USize64::from(bin.data.len()),
        name: None,
        uri: None,
        extensions: None,
        extras: Default::default(),
    });
    root.buffer_views = bin.views;

    let mut text = serde_json::to_vec(&root).map_err(|e| export_error("glb", e))?;
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let total = 12 + 8 + text.len() + 8 + bin.data.len();
    let total = u32::try_from(total).map_err(|_| export_error("glb", "file over 4 GiB"))?;
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    out.extend_from_slice(&(bin.data.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin.data);
    Ok(out)
}

/// A bone's rest world transform (translation and z rotation down the chain).
fn rest_world(creature: &Creature2d, bone: usize) -> Mat4 {
    let mut chain = Vec::new();
    let mut at = Some(bone);
    while let Some(i) = at {
        if chain.len() > creature.bones.len() {
            break;
        }
        chain.push(i);
        at = creature.bones.get(i).and_then(|b| b.parent);
    }
    let mut world = Mat4::IDENTITY;
    for &i in chain.iter().rev() {
        if let Some(b) = creature.bones.get(i) {
            world = world
                * Mat4::from_translation(b.offset.extend(0.0))
                * Mat4::from_rotation_z(b.rotation);
        }
    }
    world
}
