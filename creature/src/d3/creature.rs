//! The 3D creature as plain data.

use alloc::vec::Vec;

use glam::{Mat4, Vec3};

use creature_autorig::Rig;
use creature_limbs::{CreatureKind, Plan};

/// A skinned triangle mesh: one for the whole creature (body, head, limbs), one skin.
///
/// Right-handed, +Y up, the creature facing +Z (its left is +X), in metres, the ground at
/// `y = 0`. Triangles are counter-clockwise seen from outside.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals (per face when [`Params::flat_normals`](crate::d3::Params::flat_normals) is on).
    pub normals: Vec<Vec3>,
    /// Linear RGB vertex colours in `[0, 1]`.
    pub colours: Vec<Vec3>,
    /// Triangles as vertex indices.
    pub indices: Vec<[u32; 3]>,
    /// Up to four joints per vertex (indices into [`Skeleton::joints`]).
    pub joints: Vec<[u16; 4]>,
    /// Their weights, summing to 1; unused slots have weight 0.
    pub weights: Vec<[f32; 4]>,
}

/// What part of the creature a joint moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Part {
    /// The spine (from the auto-rigger), which also carries the head.
    Spine,
    /// A limb: the index in [`Creature::plan`]'s `limbs`.
    Limb(usize),
}

/// One joint of the skeleton, in its rest pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// Rest position in model space.
    pub position: Vec3,
    /// Parent joint, `None` for the root.
    pub parent: Option<usize>,
    /// What it moves.
    pub part: Part,
}

/// The creature's skeleton: one tree; the spine joints first (the auto-rigger's order, root
/// first), then each limb's joints. Rest rotations are the identity, so a joint's rest
/// transform is a translation.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Skeleton {
    /// The joints.
    pub joints: Vec<Joint>,
}

impl Skeleton {
    /// The rest translation of each joint relative to its parent (model space for the root).
    #[must_use]
    pub fn rest_translations(&self) -> Vec<Vec3> {
        self.joints
            .iter()
            .map(|j| {
                let parent = j
                    .parent
                    .and_then(|p| self.joints.get(p))
                    .map_or(Vec3::ZERO, |p| p.position);
                j.position - parent
            })
            .collect()
    }

    /// The inverse bind matrices (glTF's): the inverse of each joint's model-space rest
    /// transform.
    #[must_use]
    pub fn inverse_bind_matrices(&self) -> Vec<Mat4> {
        self.joints
            .iter()
            .map(|j| Mat4::from_translation(-j.position))
            .collect()
    }
}

/// Measured quality of a 3D creature: tests assert on these.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Quality {
    /// For walkers, the signed distance from the centre of mass to the edge of the support
    /// region (positive: statically stable), from the limb plan; `None` otherwise.
    pub stability_margin: Option<f32>,
    /// Smallest Jacobian determinant of the body's FFD lattice over a sample grid (above 0:
    /// the body does not fold).
    pub ffd_min_determinant: f32,
    /// Largest `|Σ weights − 1|` over the vertices.
    pub max_weight_sum_error: f32,
    /// Lowest vertex height (the ground is `y = 0`; never below it).
    pub min_height: f32,
    /// Smallest triangle area, × the square of the body length.
    pub min_triangle_area: f32,
    /// Total bend of the neck and of the tail, in degrees (0 for swimmers).
    pub bend_degrees: [f32; 2],
}

/// A generated 3D creature: plain data.
#[derive(Debug, Clone, PartialEq)]
pub struct Creature {
    /// The kind it was generated as (a [`Kind::Random`](crate::d3::Kind::Random) resolved).
    pub kind: CreatureKind,
    /// The skinned mesh.
    pub mesh: Mesh,
    /// The skeleton: spine joints, then limb joints.
    pub skeleton: Skeleton,
    /// The spine rig (bent and grounded) whose joints are the skeleton's first joints.
    pub rig: Rig,
    /// The limb plan (in the body frame before grounding: add [`Creature::ground_offset`] to
    /// its positions).
    pub plan: Plan,
    /// How far the body frame was moved up to put the ground at `y = 0`.
    pub ground_offset: f32,
    /// The body profiles blended (indices 0–8) with their weights.
    pub profiles: Vec<(usize, f32)>,
    /// The uniform body scale drawn.
    pub body_scale: f32,
    /// Movement speed in m/s (the body scale times a random factor).
    pub speed: f32,
    /// Walkers' legs and arms registered for `creature-gait`; `None` for fliers and swimmers.
    pub gait: Option<crate::d3::GaitSetup>,
    /// The kind's baked clips (walkers `idle`, `walk`, `turn`; fliers `hover`, `fly`;
    /// swimmers `idle`, `swim`), empty when [`Params::clips`](crate::d3::Params::clips) is off.
    pub clips: Vec<crate::d3::Clip>,
    /// Body length (the spine's length), in metres.
    pub length: f32,
    /// Quality figures.
    pub quality: Quality,
}
