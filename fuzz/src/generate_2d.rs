//! The facade's `creature::generate_2d` with arbitrary `d2::Params` fields (in range, with
//! the texture and resolution bounded, or extreme), and its exporters `glb_2d`, `svg_2d`,
//! `preview_2d`, `preview_2d_png` and `image_png`: a finite creature with skin weights summing
//! to 1, a well-formed GLB and the same bytes for the same input, previews whose longer side is
//! the size asked for, PNGs that decode to the declared size.

use arbitrary::Arbitrary;
use creature::IntSpan;
use creature::d2;
use creature::export::{self, PreviewOptions};

use crate::{check_glb, check_image, check_weights, decode_png, map, span};

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub seed: u64,
    pub extreme: bool,
    pub texture: bool,
    pub texture_size: u16,
    pub preview_size: u16,
    /// textured, mesh, outline, bones, eyes.
    pub preview_flags: u8,
    pub tweaks: Vec<(u8, f32, f32)>,
}

#[must_use]
pub fn params(input: &Input) -> d2::Params {
    let x = input.extreme;
    let mut p = d2::Params::DEFAULT
        .with_texture(input.texture)
        .with_texture_size(if x {
            u32::from(input.texture_size)
        } else {
            1 + u32::from(input.texture_size % 64)
        });
    let int = |a: f32, lo: u32, hi: u32| {
        if x {
            a.to_bits()
        } else {
            lo + a.to_bits() % (hi - lo + 1)
        }
    };
    let one = |a: f32, lo: f32, hi: f32| if x { a } else { map(a, lo, hi) };
    for &(field, a, b) in input.tweaks.iter().take(6) {
        match field % 16 {
            0 => {
                let (lo, hi) = (int(a, 2, 8), int(b, 2, 8));
                p.spine_bones = IntSpan::new(lo.min(hi), if x { hi } else { lo.max(hi) });
            }
            1 => p.spine_thickness = span(x, a, b, 1.0, 1000.0),
            2 => p.spine_length = span(x, a, b, 1.0, 10_000.0),
            3 => p.spine_multiplier = span(x, a, b, 1.0, 1.6),
            4 => p.limb_probability = one(a, 0.0, 1.0),
            5 => p.limb_length = span(x, a, b, 1.0, 10_000.0),
            6 => p.limb_thickness = span(x, a, b, 1.0, 1000.0),
            7 => p.socket_offset = one(a, 0.0, 4.0),
            8 => p.eye_size = span(x, a, b, 0.0, 1.0),
            9 => p.outline_step = one(a, 0.5, 100.0),
            10 => p.simplify = one(a, 0.0, 0.5),
            11 => p.interior_spacing = one(a, 1.0, 1000.0),
            12 => p.interior_clearance = one(a, 0.0, 2.0),
            13 => p.min_angle = one(a, 0.0, 33.0),
            14 => p.depth_shading = one(a, 0.0, 4.0),
            _ => p.normal_relief = one(a, 0.0, 1000.0),
        }
    }
    p
}

pub fn run(input: &Input) {
    let params = params(input);
    if params.validate().is_ok() {
        // Textures past 128 px are valid but slow to render and encode (past 256, seconds).
        if params.texture && params.texture_size > 128 {
            return;
        }
        // Bound one execution: thick spines over long segments at a fine outline step are
        // valid but take seconds (the sweep and tests cover the defaults).
        let long =
            params.spine_length.max * params.spine_bones.max as f32 + params.limb_length.max * 16.0;
        if long / params.outline_step > 500.0 || (long / params.interior_spacing).powi(2) > 10_000.0
        {
            return;
        }
    }
    let Ok(c) = d2::generate(input.seed, &params) else {
        return;
    };
    let m = &c.mesh;
    let n = m.positions.len();
    assert!(
        m.positions.iter().all(|p| p.is_finite()) && m.uvs.iter().all(|u| u.is_finite()),
        "non-finite mesh"
    );
    assert!(
        m.indices.iter().flatten().all(|&i| (i as usize) < n),
        "index out of range"
    );
    assert!(m.outline_len <= n);
    for (w, j) in m.weights.iter().zip(&m.joints) {
        check_weights(*w, *j, c.bones.len());
    }
    assert!(
        c.bones
            .iter()
            .all(|b| b.position.is_finite() && b.offset.is_finite() && b.rotation.is_finite())
    );
    assert!(c.outline.iter().flatten().all(|p| p.is_finite()));
    for image in [&c.texture, &c.normal_map].into_iter().flatten() {
        check_image(image);
    }
    let glb = export::glb_2d(&c).expect("glb_2d of a generated creature");
    check_glb(&glb);
    let svg = export::svg_2d(&c);
    assert!(
        svg.contains("<svg") && svg.trim_end().ends_with("</svg>"),
        "SVG"
    );
    let again = d2::generate(input.seed, &params).expect("the same seed and params generate again");
    assert!(
        export::glb_2d(&again).unwrap() == glb,
        "determinism: GLB bytes differ"
    );
    assert!(export::svg_2d(&again) == svg, "determinism: SVG differs");
    let f = input.preview_flags;
    let size = if input.extreme {
        u32::from(input.preview_size)
    } else {
        16 + u32::from(input.preview_size % 112)
    };
    let options = PreviewOptions::DEFAULT
        .with_size(size)
        .with_textured(f & 1 != 0)
        .with_mesh(f & 2 != 0)
        .with_outline(f & 4 != 0)
        .with_bones(f & 8 != 0)
        .with_eyes(f & 16 != 0);
    if !(16..=1024).contains(&size) {
        assert!(
            size > 1024 || export::preview_2d(&c, &options).is_err(),
            "size {size} accepted"
        );
        return;
    }
    // Sizes in range past 128 px (extreme flavour) must be accepted too, but are slow to draw,
    // and so are creatures of more than 300 triangles (hairlines cost per segment; it is the
    // same drawing code at any count): the facade's tests draw both.
    if size > 128 || m.indices.len() > 300 {
        return;
    }
    // One of the two per input (drawing is most of the time): their pictures are the same.
    let (w, h) = if f & 32 == 0 {
        let image = export::preview_2d(&c, &options).expect("preview_2d in range");
        check_image(&image);
        (image.width, image.height)
    } else {
        let png = export::preview_2d_png(&c, &options).expect("preview_2d_png in range");
        let (w, h, _) = decode_png(&png);
        (w, h)
    };
    assert_eq!(w.max(h), size, "the longer side is the size: {w}x{h}");
}
