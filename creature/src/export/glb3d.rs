//! glTF 2.0 binary export of a 3D creature (feature `export`).

use alloc::vec;
use alloc::vec::Vec;

use gltf_json as json;

use super::export_error;
use super::gltf::{
    AnimationBuilder, Bin, accessor, check_skinned_mesh, f32_bytes, new_root, push_mesh,
};
use crate::Error;
use crate::d3::Clip;
use crate::d3::Creature;
use crate::terrain::TerrainMesh;

/// A 3D creature as a glTF 2.0 binary (`.glb`): one skinned mesh (positions, unit normals,
/// `COLOR_0` vertex colours, `JOINTS_0` as unsigned shorts, `WEIGHTS_0` as normalised unsigned
/// bytes summing to exactly 255), one node per joint (translations from the rest pose, rest
/// rotations the identity) with inverse bind matrices, and a double-sided material (white base
/// colour times the vertex colours, metallic 0, roughness 0.9). Written with `gltf-json`;
/// checked with the Khronos glTF-Validator by `cargo xtask verify-gltf`. Each clip becomes an
/// animation (linear interpolation) of the root's translation and rotation and its tracks'
/// translations and rotations.
///
/// ```
/// use creature::d3::{generate, Kind, Params};
/// use creature::export;
///
/// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
/// let walk = walker.bake_walk(2.0)?;
/// let glb = export::glb_3d(&walker, &[walk])?;
/// assert_eq!(&glb[0..4], b"glTF");
/// # Ok::<(), creature::Error>(())
/// ```
///
/// # Errors
/// [`Error::Export`] when the mesh is empty, its attributes disagree, an index or joint is out
/// of range, a clip's tracks do not have one value per frame, or encoding fails.
pub fn glb_3d(creature: &Creature, clips: &[Clip]) -> Result<Vec<u8>, Error> {
    scene(creature, clips, None)
}

/// [`glb_3d`] with the ground it walks on: `terrain` (for example
/// [`terrain_mesh`](crate::terrain::terrain_mesh) of the height field a clip was baked on with
/// [`Creature::bake_to`]) as a second mesh node, `terrain`, unskinned, with an earthy
/// single-sided material, so a viewer shows the feet on the ground. The skeleton's root joint
/// sits under a node of its own, `rig`, beside the two meshes (Blender then imports the
/// terrain as an object of its own, not a child of the creature's armature).
///
/// ```
/// use creature::d3::{generate, Kind, Params};
/// use creature::export;
/// use creature::glam::Vec3;
/// use creature::terrain::{terrain, terrain_mesh, TerrainParams};
///
/// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker).with_clips(false))?;
/// let hills = terrain(7, &TerrainParams::DEFAULT)?;
/// let walk = walker.bake_to(&hills, Vec3::new(0.0, 0.0, 2.0) * walker.length, 20.0)?;
/// let glb = export::glb_3d_on_terrain(&walker, &[walk], &terrain_mesh(&hills))?;
/// assert_eq!(&glb[0..4], b"glTF");
/// # Ok::<(), creature::Error>(())
/// ```
///
/// # Errors
/// As [`glb_3d`]; [`Error::Export`] too when the terrain has no triangles, its normals are not
/// one per vertex, a triangle's index is out of range or a position is not finite.
pub fn glb_3d_on_terrain(
    creature: &Creature,
    clips: &[Clip],
    terrain: &TerrainMesh,
) -> Result<Vec<u8>, Error> {
    let n = terrain.positions.len();
    if terrain.triangles.is_empty()
        || terrain.normals.len() != n
        || terrain.triangles.iter().flatten().any(|&i| i as usize >= n)
        || !terrain.positions.iter().all(|p| p.is_finite())
    {
        return Err(export_error(
            "glb",
            "the terrain mesh needs triangles indexing its vertices, finite positions and one normal per vertex",
        ));
    }
    scene(creature, clips, Some(terrain))
}

/// The `.glb` of [`glb_3d`], with `terrain` (checked) as a second mesh node if given.
fn scene(
    creature: &Creature,
    clips: &[Clip],
    terrain: Option<&TerrainMesh>,
) -> Result<Vec<u8>, Error> {
    let m = &creature.mesh;
    let n = m.positions.len();
    let joint_count = creature.skeleton.joints.len();
    let agree =
        m.normals.len() == n && m.colours.len() == n && m.joints.len() == n && m.weights.len() == n;
    check_skinned_mesh(n, agree, &m.indices, joint_count)?;
    if m.joints
        .iter()
        .flatten()
        .any(|&j| usize::from(j) >= joint_count)
    {
        return Err(export_error("glb", "a vertex joint is out of range"));
    }
    let Some(root_joint) = creature
        .skeleton
        .joints
        .iter()
        .position(|j| j.parent.is_none())
    else {
        return Err(export_error("glb", "the skeleton has no root"));
    };
    use json::accessor::{ComponentType as C, Type as T};

    let mut bin = Bin::new();
    let mut root = new_root();

    let positions = bin.positions(&mut root, &m.positions);
    let normals = bin.floats(
        &mut root,
        m.normals
            .iter()
            .flat_map(|v| v.normalize_or(glam::Vec3::Y).to_array()),
        n,
        T::Vec3,
    );
    let colours = bin.floats(
        &mut root,
        m.colours
            .iter()
            .flat_map(|c| c.clamp(glam::Vec3::ZERO, glam::Vec3::ONE).to_array()),
        n,
        T::Vec3,
    );
    let (joints, weights) = bin.skin(&mut root, &m.joints, &m.weights);
    let indices = bin.indices(&mut root, &m.indices);

    let mut material = json::Material {
        name: Some("creature".into()),
        double_sided: true,
        ..Default::default()
    };
    material.pbr_metallic_roughness.metallic_factor = json::material::StrengthFactor(0.0);
    material.pbr_metallic_roughness.roughness_factor = json::material::StrengthFactor(0.9);
    let material = root.push(material);

    let mesh = push_mesh(
        &mut root,
        &[
            (json::mesh::Semantic::Positions, positions),
            (json::mesh::Semantic::Normals, normals),
            (json::mesh::Semantic::Colors(0), colours),
            (json::mesh::Semantic::Joints(0), joints),
            (json::mesh::Semantic::Weights(0), weights),
        ],
        indices,
        material,
    );

    // Joints: one node per joint, children listed on their parents.
    let first_joint = root.nodes.len() as u32;
    let mut children: Vec<Vec<json::Index<json::Node>>> = vec![Vec::new(); joint_count];
    for (i, joint) in creature.skeleton.joints.iter().enumerate() {
        if let Some(list) = joint.parent.and_then(|p| children.get_mut(p)) {
            list.push(json::Index::new(first_joint + i as u32));
        }
    }
    let translations = creature.skeleton.rest_translations();
    for ((t, list), joint) in translations
        .iter()
        .zip(&mut children)
        .zip(&creature.skeleton.joints)
    {
        let list = core::mem::take(list);
        root.push(json::Node {
            children: (!list.is_empty()).then_some(list),
            name: Some(joint.name.clone()),
            translation: Some(t.to_array()),
            ..Default::default()
        });
    }
    let inverse_bind: Vec<u8> = creature
        .skeleton
        .inverse_bind_matrices()
        .iter()
        .flat_map(|m| f32_bytes(m.to_cols_array()))
        .collect();
    let view = bin.push(&inverse_bind, None);
    let ibm = root.push(accessor(view, joint_count, C::F32, T::Mat4, false, None));
    let root_node = json::Index::new(first_joint + root_joint as u32);
    let skin = root.push(json::Skin {
        inverse_bind_matrices: Some(ibm),
        joints: (0..joint_count as u32)
            .map(|i| json::Index::new(first_joint + i))
            .collect(),
        skeleton: Some(root_node),
        name: Some("skeleton".into()),
        extensions: None,
        extras: Default::default(),
    });
    for clip in clips {
        let animation = animation(&mut root, &mut bin, clip, first_joint, root_joint)?;
        root.animations.push(animation);
    }
    let mesh_node = root.push(json::Node {
        mesh: Some(mesh),
        skin: Some(skin),
        name: Some("creature".into()),
        ..Default::default()
    });
    let nodes = match terrain {
        None => vec![root_node, mesh_node],
        Some(terrain) => {
            // The skeleton under a node of its own: with its root joint at the scene's top,
            // Blender's importer made the whole scene the armature and the terrain its child.
            let rig = root.push(json::Node {
                children: Some(vec![root_node]),
                name: Some("rig".into()),
                ..Default::default()
            });
            vec![rig, mesh_node, terrain_node(&mut root, &mut bin, terrain)]
        }
    };
    let scene = root.push(json::Scene {
        name: Some("creature".into()),
        nodes,
        extensions: None,
        extras: Default::default(),
    });
    root.scene = Some(scene);

    bin.into_glb(root)
}

/// The terrain as an unskinned mesh node: positions, unit normals and triangles, with an
/// earthy material.
fn terrain_node(
    root: &mut json::Root,
    bin: &mut Bin,
    terrain: &TerrainMesh,
) -> json::Index<json::Node> {
    use json::accessor::Type as T;
    let positions = bin.positions(root, &terrain.positions);
    let normals = bin.floats(
        root,
        terrain
            .normals
            .iter()
            .flat_map(|v| v.normalize_or(glam::Vec3::Y).to_array()),
        terrain.normals.len(),
        T::Vec3,
    );
    let indices = bin.indices(root, &terrain.triangles);
    let mut material = json::Material {
        name: Some("terrain".into()),
        ..Default::default()
    };
    material.pbr_metallic_roughness.base_color_factor =
        json::material::PbrBaseColorFactor([0.42, 0.37, 0.28, 1.0]);
    material.pbr_metallic_roughness.metallic_factor = json::material::StrengthFactor(0.0);
    material.pbr_metallic_roughness.roughness_factor = json::material::StrengthFactor(1.0);
    let material = root.push(material);
    let mesh = push_mesh(
        root,
        &[
            (json::mesh::Semantic::Positions, positions),
            (json::mesh::Semantic::Normals, normals),
        ],
        indices,
        material,
    );
    if let Some(pushed) = root.meshes.get_mut(mesh.value()) {
        pushed.name = Some("terrain".into());
    }
    root.push(json::Node {
        mesh: Some(mesh),
        name: Some("terrain".into()),
        ..Default::default()
    })
}

/// One clip as a glTF animation (see [`AnimationBuilder`]): the root's translation and
/// rotation, and each track's.
fn animation(
    root: &mut json::Root,
    bin: &mut Bin,
    clip: &Clip,
    first_joint: u32,
    root_joint: usize,
) -> Result<json::Animation, Error> {
    use json::animation::Property;
    let mut animation = AnimationBuilder::new(root, bin, clip.frames, clip.fps)?;
    let node = |joint: usize| first_joint + joint as u32;
    let vec3s = |v: &[glam::Vec3]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<f32>>();
    let quats = |q: &[glam::Quat]| {
        q.iter()
            .flat_map(|q| q.normalize().to_array())
            .collect::<Vec<f32>>()
    };
    let at = node(root_joint);
    animation.channel(
        root,
        bin,
        at,
        Property::Translation,
        vec3s(&clip.root_translation),
    )?;
    animation.channel(
        root,
        bin,
        at,
        Property::Rotation,
        quats(&clip.root_rotation),
    )?;
    for track in &clip.tracks {
        let at = node(track.joint);
        if let Some(t) = &track.translations {
            animation.channel(root, bin, at, Property::Translation, vec3s(t))?;
        }
        animation.channel(root, bin, at, Property::Rotation, quats(&track.rotations))?;
    }
    Ok(animation.finish(clip.name))
}
