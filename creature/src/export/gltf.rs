//! glTF 2.0 scaffolding both exporters share: the binary buffer, accessors, float bytes.

use alloc::format;
use alloc::vec::Vec;

use glam::Vec3;
use gltf_json as json;
use json::accessor::{ComponentType as C, Type as T};
use json::buffer::Target;
use json::validation::{Checked, USize64};

use super::export_error;
use crate::Error;

/// A new document naming this crate and version as its generator.
pub(crate) fn new_root() -> json::Root {
    json::Root {
        asset: json::Asset {
            generator: Some(format!("creature {}", env!("CARGO_PKG_VERSION"))),
            ..json::Asset::default()
        },
        ..json::Root::default()
    }
}

/// The creature's one mesh: a single triangle primitive with `attributes`, `indices` and
/// `material`.
pub(crate) fn push_mesh(
    root: &mut json::Root,
    attributes: &[(json::mesh::Semantic, json::Index<json::Accessor>)],
    indices: json::Index<json::Accessor>,
    material: json::Index<json::Material>,
) -> json::Index<json::Mesh> {
    let attributes = attributes
        .iter()
        .map(|(semantic, index)| (Checked::Valid(semantic.clone()), *index))
        .collect();
    root.push(json::Mesh {
        name: Some("creature".into()),
        primitives: alloc::vec![json::mesh::Primitive {
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
    })
}

/// The checks every skinned mesh passes before export: `vertices` vertices (none missing from
/// an attribute: the caller compares the lengths in `attributes_agree`), triangles indexing
/// them, and a skeleton of 1 to 65,535 joints.
pub(crate) fn check_skinned_mesh(
    vertices: usize,
    attributes_agree: bool,
    indices: &[[u32; 3]],
    joints: usize,
) -> Result<(), Error> {
    if vertices == 0 || indices.is_empty() || !attributes_agree {
        return Err(export_error(
            "glb",
            "the mesh is empty or its attributes disagree",
        ));
    }
    if joints == 0 || joints > usize::from(u16::MAX) {
        return Err(export_error("glb", "the skeleton is empty or too large"));
    }
    if indices.iter().flatten().any(|&i| i as usize >= vertices) {
        return Err(export_error("glb", "a triangle index is out of range"));
    }
    Ok(())
}

/// Binary buffer under construction: 4-byte aligned views.
pub(crate) struct Bin {
    pub(crate) data: Vec<u8>,
    pub(crate) views: Vec<json::buffer::View>,
}

impl Bin {
    pub(crate) fn new() -> Self {
        Self {
            data: Vec::new(),
            views: Vec::new(),
        }
    }

    /// A vertex attribute of `count` float vectors of type `type_`.
    pub(crate) fn floats(
        &mut self,
        root: &mut json::Root,
        values: impl IntoIterator<Item = f32>,
        count: usize,
        type_: T,
    ) -> json::Index<json::Accessor> {
        let view = self.push(&f32_bytes(values), Some(Target::ArrayBuffer));
        root.push(accessor(view, count, C::F32, type_, false, None))
    }

    /// The positions, with their bounds (glTF requires them).
    pub(crate) fn positions(
        &mut self,
        root: &mut json::Root,
        positions: &[Vec3],
    ) -> json::Index<json::Accessor> {
        let mut lo = [f32::MAX; 3];
        let mut hi = [f32::MIN; 3];
        for p in positions {
            for (k, v) in p.to_array().into_iter().enumerate() {
                lo[k] = lo[k].min(v);
                hi[k] = hi[k].max(v);
            }
        }
        let view = self.push(
            &f32_bytes(positions.iter().flat_map(|p| p.to_array())),
            Some(Target::ArrayBuffer),
        );
        root.push(accessor(
            view,
            positions.len(),
            C::F32,
            T::Vec3,
            false,
            Some((lo.to_vec(), hi.to_vec())),
        ))
    }

    /// `JOINTS_0` as unsigned shorts and `WEIGHTS_0` as normalised unsigned bytes summing to
    /// exactly 255; a joint whose weight rounds to 0 is written as 0 (glTF: unused slots are 0).
    pub(crate) fn skin(
        &mut self,
        root: &mut json::Root,
        joints: &[[u16; 4]],
        weights: &[[f32; 4]],
    ) -> (json::Index<json::Accessor>, json::Index<json::Accessor>) {
        let n = joints.len();
        let mut joint_bytes = Vec::with_capacity(n * 8);
        let mut weight_bytes = Vec::with_capacity(n * 4);
        for (joints, weights) in joints.iter().zip(weights) {
            let inf = creature_skin::Influences {
                joints: *joints,
                weights: *weights,
            };
            for (j, w) in joints.iter().zip(inf.quantize_u8()) {
                let j = if w == 0 { 0 } else { *j };
                joint_bytes.extend_from_slice(&j.to_le_bytes());
                weight_bytes.push(w);
            }
        }
        let view = self.push(&joint_bytes, Some(Target::ArrayBuffer));
        let joints = root.push(accessor(view, n, C::U16, T::Vec4, false, None));
        let view = self.push(&weight_bytes, Some(Target::ArrayBuffer));
        let weights = root.push(accessor(view, n, C::U8, T::Vec4, true, None));
        (joints, weights)
    }

    /// The triangles as 32-bit indices.
    pub(crate) fn indices(
        &mut self,
        root: &mut json::Root,
        triangles: &[[u32; 3]],
    ) -> json::Index<json::Accessor> {
        let bytes: Vec<u8> = triangles
            .iter()
            .flatten()
            .flat_map(|i| i.to_le_bytes())
            .collect();
        let view = self.push(&bytes, Some(Target::ElementArrayBuffer));
        root.push(accessor(
            view,
            triangles.len() * 3,
            C::U32,
            T::Scalar,
            false,
            None,
        ))
    }

    /// The document and this buffer as a `.glb` file: header, JSON chunk, binary chunk.
    pub(crate) fn into_glb(mut self, mut root: json::Root) -> Result<Vec<u8>, Error> {
        while !self.data.len().is_multiple_of(4) {
            self.data.push(0);
        }
        root.buffers.push(json::Buffer {
            byte_length: USize64::from(self.data.len()),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
        root.buffer_views = self.views;

        let mut text = serde_json::to_vec(&root).map_err(|e| export_error("glb", e))?;
        while !text.len().is_multiple_of(4) {
            text.push(b' ');
        }
        let total = 12 + 8 + text.len() + 8 + self.data.len();
        let total = u32::try_from(total).map_err(|_| export_error("glb", "file over 4 GiB"))?;
        let mut out = Vec::with_capacity(total as usize);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&total.to_le_bytes());
        out.extend_from_slice(&(text.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&text);
        out.extend_from_slice(&(self.data.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&self.data);
        Ok(out)
    }

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

/// One glTF animation being built: a time accessor (one key per frame at `fps`) shared by its
/// samplers, one linear sampler and one channel per animated node property.
pub(crate) struct AnimationBuilder {
    input: json::Index<json::Accessor>,
    frames: usize,
    samplers: Vec<json::animation::Sampler>,
    channels: Vec<json::animation::Channel>,
}

impl AnimationBuilder {
    /// An animation of `frames` keys (at least 2) at `fps` (finite, > 0), its time accessor
    /// pushed into `root` and `bin`.
    pub(crate) fn new(
        root: &mut json::Root,
        bin: &mut Bin,
        frames: usize,
        fps: f32,
    ) -> Result<Self, Error> {
        if frames < 2 || !(fps > 0.0) || !fps.is_finite() {
            return Err(bad_track());
        }
        let times: Vec<f32> = (0..frames).map(|f| f as f32 / fps).collect();
        let view = bin.push(&f32_bytes(times.iter().copied()), None);
        let last = times.last().copied().unwrap_or(0.0);
        let input = root.push(accessor(
            view,
            frames,
            C::F32,
            T::Scalar,
            false,
            Some((alloc::vec![0.0], alloc::vec![last])),
        ));
        Ok(Self {
            input,
            frames,
            samplers: Vec::new(),
            channels: Vec::new(),
        })
    }

    /// Animates `property` of node `node` with `values`: one finite value per frame (`Vec3`
    /// translations or `Vec4` rotations, flattened).
    pub(crate) fn channel(
        &mut self,
        root: &mut json::Root,
        bin: &mut Bin,
        node: u32,
        property: json::animation::Property,
        values: Vec<f32>,
    ) -> Result<(), Error> {
        let type_ = if property == json::animation::Property::Rotation {
            T::Vec4
        } else {
            T::Vec3
        };
        let width = if type_ == T::Vec4 { 4 } else { 3 };
        if values.len() != self.frames * width || !values.iter().all(|v| v.is_finite()) {
            return Err(bad_track());
        }
        let view = bin.push(&f32_bytes(values), None);
        let output = root.push(accessor(view, self.frames, C::F32, type_, false, None));
        self.samplers.push(json::animation::Sampler {
            input: self.input,
            interpolation: Checked::Valid(json::animation::Interpolation::Linear),
            output,
            extensions: None,
            extras: Default::default(),
        });
        self.channels.push(json::animation::Channel {
            sampler: json::Index::new(self.samplers.len() as u32 - 1),
            target: json::animation::Target {
                node: json::Index::new(node),
                path: Checked::Valid(property),
                extensions: None,
                extras: Default::default(),
            },
            extensions: None,
            extras: Default::default(),
        });
        Ok(())
    }

    /// The animation, named `name`.
    pub(crate) fn finish(self, name: &str) -> json::Animation {
        json::Animation {
            name: Some(name.into()),
            channels: self.channels,
            samplers: self.samplers,
            extensions: None,
            extras: Default::default(),
        }
    }
}

/// The error for a clip whose tracks do not fit its frames.
fn bad_track() -> Error {
    export_error("glb", "a clip's tracks do not have one value per frame")
}
