//! A small software rasteriser: a 3D creature from three views (side, front, top) with flat
//! shading and a depth buffer.

use alloc::vec;

use glam::{Vec2, Vec3};

use crate::Error;
use crate::d3::Creature;
use crate::d3::colour::linear_to_srgb;
use crate::image::Image;

/// Background colour of [`preview_3d`] images.
pub const PREVIEW_BACKGROUND: [u8; 4] = [236, 236, 232, 255];
const GROUND: [u8; 4] = [120, 110, 100, 255];

/// Renders `creature` from three orthographic views side by side, each `size` pixels square:
/// from its right side (the head to the right), from the front, and from above (the head up).
/// Faces are flat-shaded with a fixed light, their vertex colours (linear, as glTF's
/// `COLOR_0`) sRGB-encoded and interpolated across each face as a viewer shows them; the ground (`y = 0`) is a
/// line in the first two views. Encode with [`export::image_png`](crate::export) (feature
/// `export`).
///
/// ```
/// use creature::d3::{generate, Kind, Params};
/// use creature::export::{preview_3d, PREVIEW_BACKGROUND};
///
/// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
/// let image = preview_3d(&walker, 64)?;
/// assert_eq!((image.width, image.height), (192, 64));
/// assert!(image.rgba.chunks(4).any(|p| p != PREVIEW_BACKGROUND));
/// # Ok::<(), creature::Error>(())
/// ```
///
/// # Errors
/// [`Error::OutOfRange`] for a `size` outside 16 to 4096.
pub fn preview_3d(creature: &Creature, size: u32) -> Result<Image, Error> {
    if !(16..=4096).contains(&size) {
        return Err(Error::OutOfRange {
            what: "size",
            value: size as f32,
            min: 16.0,
            max: 4096.0,
        });
    }
    let (w, h) = (size as usize * 3, size as usize);
    let mut rgba = vec![0u8; w * h * 4];
    for px in rgba.chunks_exact_mut(4) {
        px.copy_from_slice(&PREVIEW_BACKGROUND);
    }
    let mut depth = vec![f32::NEG_INFINITY; w * h];
    let mesh = &creature.mesh;
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for p in &mesh.positions {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    lo = lo.min(Vec3::new(lo.x, 0.0, lo.z));
    if !lo.is_finite() || !hi.is_finite() {
        return Ok(Image {
            width: w as u32,
            height: h as u32,
            rgba,
        });
    }
    let extent = (hi - lo).max_element().max(1e-6);
    let scale = 0.85 * size as f32 / extent;
    let light = Vec3::new(-0.4, 0.8, 0.45).normalize();
    // (screen x, screen y, depth toward the viewer) for each view.
    let views: [fn(Vec3) -> Vec3; 3] = [
        |p| Vec3::new(p.z, p.y, -p.x),
        |p| Vec3::new(p.x, p.y, p.z),
        |p| Vec3::new(-p.x, p.z, p.y),
    ];
    for (v, view) in views.iter().enumerate() {
        let (a, b) = (view(lo), view(hi));
        let centre = Vec2::new(0.5 * (a.x + b.x), 0.5 * (a.y + b.y));
        let origin = Vec2::new(
            (v * size as usize) as f32 + 0.5 * size as f32,
            0.5 * h as f32,
        );
        let to_screen = |p: Vec3| {
            let q = view(p);
            Vec3::new(
                origin.x + (q.x - centre.x) * scale,
                origin.y - (q.y - centre.y) * scale,
                q.z,
            )
        };
        if v < 2 {
            let y = to_screen(Vec3::ZERO).y + 0.5;
            if y >= 0.0 && (y as usize) < h {
                let row = y as usize;
                for x in v * size as usize..(v + 1) * size as usize {
                    let i = (row * w + x) * 4;
                    if let Some(px) = rgba.get_mut(i..i + 4) {
                        px.copy_from_slice(&GROUND);
                    }
                }
            }
        }
        let x_range = (v * size as usize, (v + 1) * size as usize);
        for t in &mesh.indices {
            let Some(p) = t
                .iter()
                .map(|&i| mesh.positions.get(i as usize).copied())
                .collect::<Option<alloc::vec::Vec<Vec3>>>()
            else {
                continue;
            };
            let normal = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
            let shade = 0.35 + 0.65 * normal.dot(light).abs();
            // Linear vertex colours, sRGB-encoded as a viewer shows them, shaded, and
            // interpolated across the face.
            let colours = t.map(|i| {
                let c = mesh
                    .colours
                    .get(i as usize)
                    .copied()
                    .unwrap_or(Vec3::splat(0.5));
                Vec3::new(
                    linear_to_srgb(c.x),
                    linear_to_srgb(c.y),
                    linear_to_srgb(c.z),
                ) * (shade * 255.0)
            });
            let s = [to_screen(p[0]), to_screen(p[1]), to_screen(p[2])];
            raster(&s, x_range, (w, h), &mut depth, &mut rgba, colours);
        }
    }
    Ok(Image {
        width: w as u32,
        height: h as u32,
        rgba,
    })
}

fn edge(a: Vec3, b: Vec3, x: f32, y: f32) -> f32 {
    (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x)
}

fn raster(
    s: &[Vec3; 3],
    x_range: (usize, usize),
    (w, h): (usize, usize),
    depth: &mut [f32],
    rgba: &mut [u8],
    colours: [Vec3; 3],
) {
    let area = edge(s[0], s[1], s[2].x, s[2].y);
    if !(area.abs() > 1e-12) {
        return;
    }
    let lo_x = s.iter().map(|p| p.x).fold(f32::INFINITY, f32::min);
    let hi_x = s.iter().map(|p| p.x).fold(f32::NEG_INFINITY, f32::max);
    let lo_y = s.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
    let hi_y = s.iter().map(|p| p.y).fold(f32::NEG_INFINITY, f32::max);
    if !(hi_x >= x_range.0 as f32 && lo_x < x_range.1 as f32 && hi_y >= 0.0 && lo_y < h as f32) {
        return;
    }
    // Non-negative here, so `as usize` rounds down.
    let min_x = (lo_x.max(x_range.0 as f32) as usize).max(x_range.0);
    let max_x = (hi_x.max(0.0) as usize).min(x_range.1.saturating_sub(1));
    let min_y = lo_y.max(0.0) as usize;
    let max_y = (hi_y.max(0.0) as usize).min(h.saturating_sub(1));
    if min_x > max_x || min_y > max_y {
        return;
    }
    for y in min_y..=max_y {
        for x in min_x..=max_x {
            let (fx, fy) = (x as f32 + 0.5, y as f32 + 0.5);
            let w0 = edge(s[1], s[2], fx, fy) / area;
            let w1 = edge(s[2], s[0], fx, fy) / area;
            let w2 = 1.0 - w0 - w1;
            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                continue;
            }
            let z = w0 * s[0].z + w1 * s[1].z + w2 * s[2].z;
            let i = y * w + x;
            if let Some(d) = depth.get_mut(i)
                && z > *d
            {
                *d = z;
                let c = (colours[0] * w0 + colours[1] * w1 + colours[2] * w2)
                    .clamp(Vec3::ZERO, Vec3::splat(255.0));
                if let Some(px) = rgba.get_mut(i * 4..i * 4 + 4) {
                    px.copy_from_slice(&[c.x as u8, c.y as u8, c.z as u8, 255]);
                }
            }
        }
    }
}
