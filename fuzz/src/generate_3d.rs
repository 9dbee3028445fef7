//! The facade's `creature::generate` (3D) with arbitrary `d3::Params` fields, in range (with
//! the resolution bounded so an execution stays fast) or extreme (NaN, infinities, huge), and
//! its exporters `glb_3d`, `preview_3d` and `image_png`. A creature is finite (mesh, skeleton,
//! clips, quality), its skin weights sum to 1 on existing joints, its GLB is well formed and
//! the same seed and params give the same bytes; previews decode to their declared size.

use arbitrary::Arbitrary;
use creature::d3::{self, Kind};
use creature::{IntSpan, export};

use crate::{check_glb, check_image, check_weights, decode_png, map, span};

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub seed: u64,
    pub kind: u8,
    pub extreme: bool,
    pub clips: bool,
    pub flat_normals: bool,
    pub preview: u8,
    /// Field number and two values (a span's ends, or one value).
    pub tweaks: Vec<(u8, f32, f32)>,
}

#[must_use]
pub fn params(input: &Input) -> d3::Params {
    let x = input.extreme;
    let mut p = d3::Params::DEFAULT
        .with_kind(match input.kind % 4 {
            0 => Kind::Walker,
            1 => Kind::Flier,
            2 => Kind::Swimmer,
            _ => Kind::Random,
        })
        // Coarse by default: an execution must stay within a few tens of milliseconds.
        .with_resolution(8, 6);
    p.clips = input.clips;
    p.flat_normals = input.flat_normals;
    p.spine_bones = IntSpan::new(5, 12);
    p.limb_sides = 3;
    let int = |a: f32, lo: u32, hi: u32| {
        if x {
            a.to_bits()
        } else {
            lo + a.to_bits() % (hi - lo + 1)
        }
    };
    for &(field, a, b) in input.tweaks.iter().take(6) {
        match field % 16 {
            0 => p.profiles = int(a, 1, 9),
            1 => p.rings = int(a, 4, 20),
            2 => p.segments = int(a, 3, 16),
            3 => p.limb_sides = int(a, 3, 8),
            4 => p.slice_width = span(x, a, b, 0.1, 10.0),
            5 => p.slice_height = span(x, a, b, 0.1, 10.0),
            6 => p.slice_step = span(x, a, b, 0.05, 10.0),
            7 => p.swimmer_slice_width = span(x, a, b, 0.1, 10.0),
            8 => p.body_scale = span(x, a, b, 0.01, 100.0),
            9 => p.speed_factor = span(x, a, b, 0.01, 10.0),
            10 => p.bone_length = if x { a } else { map(a, 0.01, 10.0) },
            11 => {
                let (lo, hi) = (int(a, 5, 16), int(b, 5, 16));
                p.spine_bones = IntSpan::new(lo.min(hi), if x { hi } else { lo.max(hi) });
            }
            12 => p.spine_bend = if x { a } else { map(a, 0.0, 200.0) },
            13 => p.head_size = span(x, a, b, 0.1, 10.0),
            14 => p.ground_clearance = span(x, a, b, 0.0, 10.0),
            _ => {
                p.limbs.min_margin = if x { a } else { map(a, 1e-4, 1.0) };
                p.limbs.sweep = if x { b } else { map(b, 0.0, 100.0) };
            }
        }
    }
    p
}

pub fn run(input: &Input) {
    let params = params(input);
    let Ok(c) = d3::generate(input.seed, &params) else {
        return;
    };
    let m = &c.mesh;
    let n = m.positions.len();
    assert!(
        m.positions
            .iter()
            .chain(&m.normals)
            .chain(&m.colours)
            .all(|v| v.is_finite()),
        "non-finite mesh"
    );
    assert!(
        m.normals.len() == n && m.colours.len() == n && m.joints.len() == n && m.weights.len() == n
    );
    assert!(
        m.indices.iter().flatten().all(|&i| (i as usize) < n),
        "index out of range"
    );
    let joints = c.skeleton.joints.len();
    assert!(
        c.skeleton
            .joints
            .iter()
            .all(|j| j.position.is_finite() && j.parent.is_none_or(|p| p < joints))
    );
    for (w, j) in m.weights.iter().zip(&m.joints) {
        check_weights(*w, *j, joints);
    }
    let q = &c.quality;
    assert!(
        q.ffd_min_determinant.is_finite()
            && q.max_weight_sum_error.is_finite()
            && q.min_height.is_finite()
            && q.min_triangle_area.is_finite()
            && q.bend_degrees.iter().all(|d| d.is_finite())
            && q.stability_margin.is_none_or(f32::is_finite),
        "quality {q:?}"
    );
    assert!(
        c.ground_offset.is_finite()
            && c.body_scale.is_finite()
            && c.speed.is_finite()
            && c.length.is_finite()
    );
    for clip in &c.clips {
        assert!(
            clip.root_translation.iter().all(|t| t.is_finite())
                && clip.root_rotation.iter().all(|r| r.is_finite()),
            "clip {}",
            clip.name
        );
        for track in &clip.tracks {
            assert!(
                track.joint < joints
                    && track
                        .rotations
                        .iter()
                        .all(|r| r.is_finite() && r.is_normalized()),
                "clip {}",
                clip.name
            );
            assert!(track.translations.iter().flatten().all(|t| t.is_finite()));
        }
    }
    let glb = export::glb_3d(&c, &c.clips).expect("glb_3d of a generated creature");
    check_glb(&glb);
    let again = d3::generate(input.seed, &params).expect("the same seed and params generate again");
    assert!(
        export::glb_3d(&again, &again.clips).unwrap() == glb,
        "determinism: the GLB bytes differ"
    );
    let size = 16 + u32::from(input.preview % 64);
    let image = export::preview_3d(&c, size).expect("preview_3d in range");
    check_image(&image);
    assert_eq!((image.width, image.height), (3 * size, size));
    let png = export::image_png(&image).expect("image_png of a preview");
    let (w, h, pixels) = decode_png(&png);
    assert_eq!((w, h), (image.width, image.height));
    assert!(pixels == image.rgba, "PNG pixels differ from the image");
}
