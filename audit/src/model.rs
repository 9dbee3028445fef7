//! A skinned, animated glTF model read back from a `.glb`: what a viewer loads.

use glam::{Mat4, Quat, Vec3};

use crate::AuditError;
use crate::geometry::Terrain;

/// One node of the file: its name, parent and rest transform.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    /// The node's name (empty when it has none).
    pub name: String,
    /// The parent node.
    pub parent: Option<usize>,
    /// Rest translation.
    pub translation: Vec3,
    /// Rest rotation.
    pub rotation: Quat,
    /// Rest scale.
    pub scale: Vec3,
}

/// The animated values of one channel, one per key.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// A translation per key.
    Translation(Vec<Vec3>),
    /// A rotation per key.
    Rotation(Vec<Quat>),
    /// A scale per key.
    Scale(Vec<Vec3>),
}

/// One animation channel: a node's property over time (linear interpolation).
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// The animated node.
    pub node: usize,
    /// Key times in seconds, increasing.
    pub times: Vec<f32>,
    /// The values at the keys.
    pub values: Values,
}

/// One animation.
#[derive(Debug, Clone, PartialEq)]
pub struct Clip {
    /// The animation's name.
    pub name: String,
    /// Its channels.
    pub channels: Vec<Channel>,
}

impl Clip {
    /// The key times of the channel with the most keys: the frames the audit poses.
    #[must_use]
    pub fn frame_times(&self) -> &[f32] {
        self.channels
            .iter()
            .map(|c| c.times.as_slice())
            .max_by_key(|t| t.len())
            .unwrap_or(&[])
    }
}

/// A skinned mesh with its skeleton and animations, as a glTF viewer sees it: the first mesh
/// primitive that has a skin.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// Bind-pose vertex positions.
    pub positions: Vec<Vec3>,
    /// Triangles.
    pub triangles: Vec<[u32; 3]>,
    /// Up to four joints per vertex, as indices into [`Model::skin`].
    pub joints: Vec<[u16; 4]>,
    /// Their weights (as stored: normalised bytes read back as fractions).
    pub weights: Vec<[f32; 4]>,
    /// Every node of the file.
    pub nodes: Vec<Node>,
    /// The skin's joints (node indices), in the order the vertices index them.
    pub skin: Vec<usize>,
    /// The skin's inverse bind matrices, one per joint.
    pub inverse_bind: Vec<Mat4>,
    /// The animations.
    pub clips: Vec<Clip>,
    /// The ground the creature walks on when the file carries one: the triangles of an
    /// unskinned mesh on a node named `terrain` (as `creature`'s `glb_3d_on_terrain` writes
    /// it), in world space. `None`: the plane `y = 0`.
    pub terrain: Option<Terrain>,
}

impl Model {
    /// Reads a binary glTF (`.glb`) file's skinned mesh, nodes and animations.
    ///
    /// # Errors
    /// [`AuditError::Gltf`] when the file does not parse, [`AuditError::Unsupported`] when it
    /// has no skinned triangle mesh or its data is not what a skinned mesh needs.
    pub fn from_glb(bytes: &[u8]) -> Result<Self, AuditError> {
        let gltf = gltf::Gltf::from_slice(bytes).map_err(|e| AuditError::Gltf(e.to_string()))?;
        let blob = gltf.blob.as_deref();
        let buffer = |b: gltf::Buffer<'_>| match b.source() {
            gltf::buffer::Source::Bin => blob,
            gltf::buffer::Source::Uri(_) => None,
        };
        let unsupported = |what: &'static str| AuditError::Unsupported { what };

        let mut nodes: Vec<Node> = gltf
            .nodes()
            .map(|n| {
                let (t, r, s) = n.transform().decomposed();
                Node {
                    name: n.name().unwrap_or("").to_owned(),
                    parent: None,
                    translation: Vec3::from_array(t),
                    rotation: Quat::from_array(r),
                    scale: Vec3::from_array(s),
                }
            })
            .collect();
        for n in gltf.nodes() {
            for c in n.children() {
                nodes[c.index()].parent = Some(n.index());
            }
        }

        let (node, mesh) = gltf
            .nodes()
            .find_map(|n| Some((n.clone(), n.mesh()?)).filter(|_| n.skin().is_some()))
            .ok_or(unsupported("no node with a skinned mesh"))?;
        let skin = node.skin().ok_or(unsupported("no skin"))?;
        let primitive = mesh
            .primitives()
            .find(|p| p.mode() == gltf::mesh::Mode::Triangles)
            .ok_or(unsupported("no triangle primitive"))?;
        let reader = primitive.reader(buffer);
        let positions: Vec<Vec3> = reader
            .read_positions()
            .ok_or(unsupported("no positions"))?
            .map(Vec3::from_array)
            .collect();
        let flat: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..positions.len() as u32).collect(),
        };
        if !flat.len().is_multiple_of(3) || flat.iter().any(|&i| i as usize >= positions.len()) {
            return Err(unsupported("triangle indices"));
        }
        let triangles = flat.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
        let joints: Vec<[u16; 4]> = reader
            .read_joints(0)
            .ok_or(unsupported("no JOINTS_0"))?
            .into_u16()
            .collect();
        let weights: Vec<[f32; 4]> = reader
            .read_weights(0)
            .ok_or(unsupported("no WEIGHTS_0"))?
            .into_f32()
            .collect();
        let skin_joints: Vec<usize> = skin.joints().map(|j| j.index()).collect();
        let inverse_bind: Vec<Mat4> = match skin.reader(buffer).read_inverse_bind_matrices() {
            Some(m) => m.map(|m| Mat4::from_cols_array_2d(&m)).collect(),
            None => vec![Mat4::IDENTITY; skin_joints.len()],
        };
        if joints.len() != positions.len()
            || weights.len() != positions.len()
            || inverse_bind.len() != skin_joints.len()
            || joints
                .iter()
                .flatten()
                .any(|&j| usize::from(j) >= skin_joints.len())
        {
            return Err(unsupported("skin attributes"));
        }

        let mut clips = Vec::new();
        for animation in gltf.animations() {
            let mut channels = Vec::new();
            for channel in animation.channels() {
                let reader = channel.reader(buffer);
                let times: Vec<f32> = reader
                    .read_inputs()
                    .ok_or(unsupported("animation times"))?
                    .collect();
                use gltf::animation::util::ReadOutputs;
                let values = match reader
                    .read_outputs()
                    .ok_or(unsupported("animation values"))?
                {
                    ReadOutputs::Translations(v) => {
                        Values::Translation(v.map(Vec3::from_array).collect())
                    }
                    ReadOutputs::Rotations(r) => {
                        Values::Rotation(r.into_f32().map(Quat::from_array).collect())
                    }
                    ReadOutputs::Scales(v) => Values::Scale(v.map(Vec3::from_array).collect()),
                    ReadOutputs::MorphTargetWeights(_) => continue,
                };
                let len = match &values {
                    Values::Translation(v) | Values::Scale(v) => v.len(),
                    Values::Rotation(r) => r.len(),
                };
                if channel.sampler().interpolation() != gltf::animation::Interpolation::Linear
                    && channel.sampler().interpolation() != gltf::animation::Interpolation::Step
                {
                    return Err(unsupported("cubic spline animation"));
                }
                if len != times.len() || times.is_empty() {
                    return Err(unsupported("animation keys"));
                }
                channels.push(Channel {
                    node: channel.target().node().index(),
                    times,
                    values,
                });
            }
            clips.push(Clip {
                name: animation.name().unwrap_or("").to_owned(),
                channels,
            });
        }
        let terrain = match gltf
            .nodes()
            .find(|n| n.name() == Some("terrain") && n.skin().is_none())
            .and_then(|n| Some((n.index(), n.mesh()?)))
        {
            None => None,
            Some((index, mesh)) => {
                let world = world_matrix(&nodes, index);
                let mut positions = Vec::new();
                let mut triangles = Vec::new();
                for primitive in mesh
                    .primitives()
                    .filter(|p| p.mode() == gltf::mesh::Mode::Triangles)
                {
                    let reader = primitive.reader(buffer);
                    let first = positions.len() as u32;
                    let Some(read) = reader.read_positions() else {
                        continue;
                    };
                    positions.extend(read.map(|p| world.transform_point3(Vec3::from_array(p))));
                    let count = positions.len() as u32 - first;
                    let flat: Vec<u32> = match reader.read_indices() {
                        Some(i) => i.into_u32().collect(),
                        None => (0..count).collect(),
                    };
                    if !flat.len().is_multiple_of(3) || flat.iter().any(|&i| i >= count) {
                        return Err(unsupported("terrain triangle indices"));
                    }
                    triangles.extend(
                        flat.chunks_exact(3)
                            .map(|t| [first + t[0], first + t[1], first + t[2]]),
                    );
                }
                Some(
                    Terrain::new(positions, triangles)
                        .ok_or(unsupported("a terrain mesh with no area seen from above"))?,
                )
            }
        };
        Ok(Self {
            positions,
            triangles,
            joints,
            weights,
            nodes,
            skin: skin_joints,
            inverse_bind,
            clips,
            terrain,
        })
    }

    /// The index in [`Model::skin`] of the joint named `name`.
    #[must_use]
    pub fn joint(&self, name: &str) -> Option<usize> {
        self.skin.iter().position(|&n| self.nodes[n].name == name)
    }

    /// The name of skin joint `j`.
    #[must_use]
    pub fn joint_name(&self, j: usize) -> &str {
        &self.nodes[self.skin[j]].name
    }
}

/// Node `index`'s rest transform in the world (its parents' composed).
fn world_matrix(nodes: &[Node], index: usize) -> Mat4 {
    let mut m = Mat4::IDENTITY;
    let mut at = Some(index);
    // A file's hierarchy is a forest; the bound guards a malformed cycle.
    for _ in 0..nodes.len() {
        let Some(i) = at else { break };
        let n = &nodes[i];
        m = Mat4::from_scale_rotation_translation(n.scale, n.rotation, n.translation) * m;
        at = n.parent;
    }
    m
}
