//! The 2D creature as a skinned glTF 2.0 binary.

use alloc::format;
use alloc::vec;
use alloc::vec::Vec;

use glam::Mat4;
use gltf_json as json;
use json::validation::Checked;

use super::gltf::{
    AnimationBuilder, Bin, accessor, check_skinned_mesh, f32_bytes, new_root, push_mesh,
};
use super::image_png;
use crate::Error;
use crate::image::Image;

/// The creature as a glTF 2.0 binary (`.glb`): one skinned mesh (positions with the depth z,
/// normals +z, tangents +x, UVs, `JOINTS_0` as unsigned shorts, `WEIGHTS_0` as normalised
/// unsigned bytes summing to exactly 255), a joint node per bone (translations from the rest
/// offsets) with inverse bind matrices, and a material with the texture and normal map
/// embedded as PNG (metallic 0, roughness 0.9, as the seed). Written with `gltf-json`; checked
/// with the Khronos glTF-Validator by `cargo xtask verify-gltf`.
///
/// # Errors
/// [`Error::Export`] when the mesh is empty or too large, or encoding fails.
pub fn glb_2d(creature: &crate::d2::Creature) -> Result<Vec<u8>, Error> {
    let m = &creature.mesh;
    let n = m.positions.len();
    let agree = m.uvs.len() == n && m.joints.len() == n && m.weights.len() == n;
    check_skinned_mesh(n, agree, &m.indices, creature.bones.len())?;
    use json::accessor::{ComponentType as C, Type as T};

    let mut bin = Bin::new();
    let mut root = new_root();

    // Vertex attributes.
    let positions = bin.positions(&mut root, &m.positions);
    let normals = bin.floats(&mut root, (0..n).flat_map(|_| [0.0, 0.0, 1.0]), n, T::Vec3);
    let tangents = bin.floats(
        &mut root,
        (0..n).flat_map(|_| [1.0, 0.0, 0.0, 1.0]),
        n,
        T::Vec4,
    );
    let uvs = bin.floats(
        &mut root,
        m.uvs.iter().flat_map(|p| p.to_array()),
        n,
        T::Vec2,
    );
    let (joints, weights) = bin.skin(&mut root, &m.joints, &m.weights);
    let indices = bin.indices(&mut root, &m.indices);

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

    let mesh = push_mesh(
        &mut root,
        &[
            (json::mesh::Semantic::Positions, positions),
            (json::mesh::Semantic::Normals, normals),
            (json::mesh::Semantic::Tangents, tangents),
            (json::mesh::Semantic::TexCoords(0), uvs),
            (json::mesh::Semantic::Joints(0), joints),
            (json::mesh::Semantic::Weights(0), weights),
        ],
        indices,
        material,
    );

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
    if creature.bones.iter().any(crate::d2::Bone::animated) {
        let idle = idle_animation(&mut root, &mut bin, creature, first_joint)?;
        root.animations.push(idle);
    }

    bin.into_glb(root)
}

/// Keys per second of the 2D creature's `idle` animation.
const IDLE_FPS: f32 = 15.0;

/// The creature's looping idle wiggle ([`Creature::idle_loop_rotations`]) as the `idle`
/// animation: one rotation channel per wiggling bone (at least one), [`IDLE_LOOP_SECONDS`] long at
/// [`IDLE_FPS`], its last key the first again.
///
/// [`Creature::idle_loop_rotations`]: crate::d2::Creature::idle_loop_rotations
/// [`IDLE_LOOP_SECONDS`]: crate::d2::IDLE_LOOP_SECONDS
fn idle_animation(
    root: &mut json::Root,
    bin: &mut Bin,
    creature: &crate::d2::Creature,
    first_joint: u32,
) -> Result<json::Animation, Error> {
    let frames =
        crate::math::round_non_negative(crate::d2::IDLE_LOOP_SECONDS * IDLE_FPS) as usize + 1;
    let poses: Vec<Vec<f32>> = (0..frames)
        .map(|f| creature.idle_loop_rotations(f as f32 / IDLE_FPS))
        .collect();
    let mut animation = AnimationBuilder::new(root, bin, frames, IDLE_FPS)?;
    for (i, bone) in creature.bones.iter().enumerate() {
        if !bone.animated() {
            continue;
        }
        let values = poses
            .iter()
            .flat_map(|pose| {
                let angle = bone.rotation + pose.get(i).copied().unwrap_or(0.0);
                glam::Quat::from_rotation_z(angle).to_array()
            })
            .collect();
        let node = first_joint + i as u32;
        animation.channel(root, bin, node, json::animation::Property::Rotation, values)?;
    }
    Ok(animation.finish("idle"))
}

/// A bone's rest world transform (translation and z rotation down the chain).
fn rest_world(creature: &crate::d2::Creature, bone: usize) -> Mat4 {
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
