//! The plain data a 2D creature is made of.

use alloc::vec::Vec;

use glam::{Vec2, Vec3};

use crate::image::Image;

/// What a bone is for; decides whether it animates and how the pipeline covers it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum BoneKind {
    /// The skeleton's root, at the tail tip (no thickness).
    Root,
    /// A spine bone between the root and the head.
    Spine,
    /// The last spine bone: carries the eyes, owns no balls, does not animate.
    Head,
    /// The invisible first bone of a limb, at its socket just outside the body.
    Socket,
    /// A visible limb segment.
    Limb,
}

/// One bone of a 2D skeleton, at rest. Bones are stored parents first.
///
/// A bone's thickness, multiplier, colour and texture weight describe the segment from its
/// parent to itself; the balls covering that segment belong to the parent (they move with it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bone {
    /// The parent's index (always smaller than this bone's), `None` for the root.
    pub parent: Option<usize>,
    /// Rest position relative to the parent's, in the parent's frame (world units).
    pub offset: Vec2,
    /// Rest position in the creature's frame (y up).
    pub position: Vec2,
    /// Rest rotation relative to the parent, radians, counter-clockwise (0: the seed's
    /// skeletons are straight at rest).
    pub rotation: f32,
    /// Thickness of the segment from the parent to this bone; 0 gives it no balls.
    pub thickness: f32,
    /// Smoothness multiplier of that segment, from 1 (beads) to 1.6 (a smooth tube).
    pub multiplier: f32,
    /// Linear RGB colour, each channel in `[0, 1]`.
    pub colour: Vec3,
    /// Texture weights: `x` for the wood-like base texture, `y` for the ice-like one (sum 1).
    pub texture_weights: Vec2,
    /// What the bone is.
    pub kind: BoneKind,
}

impl Bone {
    /// Whether [`Creature::idle_rotations`] moves this bone (every bone but the root and the
    /// head, as in the seed).
    #[must_use]
    pub fn animated(&self) -> bool {
        !matches!(self.kind, BoneKind::Root | BoneKind::Head)
    }
}

/// An eye: a sprite on the head, not part of the mesh (drawn by the exporters).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Eye {
    /// Centre in the creature's frame.
    pub position: Vec2,
    /// Radius.
    pub radius: f32,
    /// The bone it rides on (the head).
    pub bone: usize,
}

/// A skeleton plus its eyes: the input of [`build`](crate::d2::build).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Skeleton {
    /// Bones, parents first; index 0 is the root.
    pub bones: Vec<Bone>,
    /// Eyes on the head.
    pub eyes: Vec<Eye>,
}

/// One metaball of a creature, with the attributes the texture blends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ball {
    /// The ball (centre, radius, owning bone as `id`).
    pub ball: creature_metaball::Ball2,
    /// Linear RGB colour.
    pub colour: Vec3,
    /// Texture weights (wood, ice).
    pub texture_weights: Vec2,
}

/// A skinned 2D triangle mesh, glTF-ready.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Vertex positions: `x, y` in the creature's frame and `z = (y − min_y) / height` of the
    /// outline's box, in `[0, 1]`, so higher parts draw on top.
    pub positions: Vec<Vec3>,
    /// Texture coordinates in the outline's box, glTF convention: `u = (x − min_x) / width`,
    /// `v = (max_y − y) / height` (row 0 of [`Creature::texture`] is the top).
    pub uvs: Vec<Vec2>,
    /// Triangles, counter-clockwise seen from +z.
    pub indices: Vec<[u32; 3]>,
    /// Up to four joints (bone indices) per vertex; unused slots are 0 with weight 0.
    pub joints: Vec<[u16; 4]>,
    /// The joints' weights, largest first, summing to 1.
    pub weights: Vec<[f32; 4]>,
    /// How many leading vertices lie on the outline.
    pub outline_len: usize,
}

/// Measured quality of a creature.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct Quality {
    /// Smallest triangle angle, degrees.
    pub min_angle: f32,
    /// Triangles below [`Params::min_angle`](crate::d2::Params::min_angle).
    pub triangles_below_limit: usize,
    /// Whether Delaunay refinement reached the angle limit everywhere.
    pub refinement_complete: bool,
    /// Largest `|Σ weights − 1|` over the vertices.
    pub max_weight_sum_error: f32,
    /// Points of the traced outline (before simplification).
    pub outline_points: usize,
    /// Largest distance of an outline vertex from the iso line, measured as
    /// `|field − 1| / |∇field|` (a first-order estimate), world units.
    pub outline_error: f32,
}

/// A generated 2D creature: plain data, ready to draw, skin or export.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Creature {
    /// The seed it was generated from (0 for [`build`](crate::d2::build)).
    pub seed: u64,
    /// Bones, parents first; joint `i` of the mesh is bone `i`.
    pub bones: Vec<Bone>,
    /// Eyes on the head.
    pub eyes: Vec<Eye>,
    /// The metaballs the shape, weights and texture come from.
    pub balls: Vec<Ball>,
    /// The outline: outer ring first (counter-clockwise), then holes (clockwise).
    pub outline: Vec<Vec<Vec2>>,
    /// The outline's bounding box `(min, max)`: the UV and texture frame.
    pub bounds: (Vec2, Vec2),
    /// The skinned mesh.
    pub mesh: Mesh,
    /// Albedo texture (RGBA8, row 0 at the top), if [`Params::texture`](crate::d2::Params::texture).
    pub texture: Option<Image>,
    /// Tangent-space normal map (`n · 0.5 + 0.5`), same size as the texture.
    pub normal_map: Option<Image>,
    /// Measured quality.
    pub quality: Quality,
}

impl Creature {
    /// The seed's idle wiggle: each bone's rotation (radians, relative to its rest rotation)
    /// at time `t` seconds: `sin(t (i / 0.23 + 1) / 10)` for bone `i`, 0 for the root and the
    /// head.
    ///
    /// ```
    /// # fn main() -> Result<(), creature::Error> {
    /// let creature = creature::generate_2d(7, &creature::d2::Params::DEFAULT.with_texture(false))?;
    /// let pose = creature.idle_rotations(1.5);
    /// assert_eq!(pose.len(), creature.bones.len());
    /// assert_eq!(pose[0], 0.0);
    /// # Ok(()) }
    /// ```
    #[must_use]
    pub fn idle_rotations(&self, t: f32) -> Vec<f32> {
        idle_rotations(&self.bones, t)
    }

    /// The idle wiggle made to loop: as [`idle_rotations`](Self::idle_rotations), with each
    /// bone's frequency rounded to a whole number of cycles in [`IDLE_LOOP_SECONDS`] (at least
    /// one), so that the wiggle at `t` and at `t + IDLE_LOOP_SECONDS` are the same: within 3.1%
    /// of the seed's frequencies (bone 3's; the higher bones' less). The 2D `.glb` bakes it as
    /// its `idle` animation.
    ///
    /// ```
    /// # fn main() -> Result<(), creature::Error> {
    /// use creature::d2::IDLE_LOOP_SECONDS;
    ///
    /// let creature = creature::generate_2d(7, &creature::d2::Params::DEFAULT.with_texture(false))?;
    /// let (start, end) = (creature.idle_loop_rotations(0.5), creature.idle_loop_rotations(0.5 + IDLE_LOOP_SECONDS));
    /// for (a, b) in start.iter().zip(&end) {
    ///     assert!((a - b).abs() < 1e-3);
    /// }
    /// # Ok(()) }
    /// ```
    #[must_use]
    pub fn idle_loop_rotations(&self, t: f32) -> Vec<f32> {
        wiggle(&self.bones, t, |frequency| {
            let cycle = core::f32::consts::TAU / IDLE_LOOP_SECONDS;
            crate::math::round_non_negative(frequency / cycle).max(1) as f32 * cycle
        })
    }

    /// World transforms of the bones posed with `rotations` (radians, added to each bone's
    /// rest rotation), as `(position, angle)`; missing rotations count as 0.
    #[must_use]
    pub fn pose(&self, rotations: &[f32]) -> Vec<(Vec2, f32)> {
        let mut out: Vec<(Vec2, f32)> = Vec::with_capacity(self.bones.len());
        for (i, bone) in self.bones.iter().enumerate() {
            let local = bone.rotation + rotations.get(i).copied().unwrap_or(0.0);
            let local = if local.is_finite() { local } else { 0.0 };
            let world = match bone.parent.and_then(|p| out.get(p)) {
                Some(&(pos, angle)) => (
                    pos + Vec2::from_angle(angle).rotate(bone.offset),
                    angle + local,
                ),
                None => (bone.position, local),
            };
            out.push(world);
        }
        out
    }

    /// The mesh's vertices posed with `rotations` (as [`pose`](Self::pose) takes them), by
    /// linear-blend skinning from the rest pose, as a viewer skins the exported `.glb`: `x, y`
    /// per vertex (a vertex's `z`, its draw order, does not move). A joint index with no bone
    /// (an edited creature) keeps its share of the vertex where it is; a weight that is not
    /// above 0 (or NaN) counts as 0.
    ///
    /// ```
    /// # fn main() -> Result<(), creature::Error> {
    /// let c = creature::generate_2d(7, &creature::d2::Params::DEFAULT.with_texture(false))?;
    /// let rest = c.posed_positions(&[]);
    /// assert_eq!(rest.len(), c.mesh.positions.len());
    /// for (posed, at_rest) in rest.iter().zip(&c.mesh.positions) {
    ///     assert!(posed.distance(at_rest.truncate()) < 1e-4);
    /// }
    /// assert_ne!(rest, c.posed_positions(&c.idle_rotations(2.0)));
    /// # Ok(()) }
    /// ```
    #[must_use]
    pub fn posed_positions(&self, rotations: &[f32]) -> Vec<Vec2> {
        let (rest, now) = (self.pose(&[]), self.pose(rotations));
        let m = &self.mesh;
        m.positions
            .iter()
            .zip(&m.joints)
            .zip(&m.weights)
            .map(|((p, joints), weights)| {
                let v = p.truncate();
                let mut at = Vec2::ZERO;
                for (&j, &w) in joints.iter().zip(weights) {
                    if !(w > 0.0) {
                        continue;
                    }
                    at += w * match (rest.get(usize::from(j)), now.get(usize::from(j))) {
                        (Some(&(p0, a0)), Some(&(p1, a1))) => {
                            p1 + Vec2::from_angle(a1 - a0).rotate(v - p0)
                        }
                        _ => v,
                    };
                }
                at
            })
            .collect()
    }

    /// The eyes' centres posed with `rotations` (as [`pose`](Self::pose) takes them): each
    /// rides its bone. An eye on a bone that does not exist stays where it is.
    #[must_use]
    pub fn posed_eyes(&self, rotations: &[f32]) -> Vec<Vec2> {
        let (rest, now) = (self.pose(&[]), self.pose(rotations));
        self.eyes
            .iter()
            .map(|eye| match (rest.get(eye.bone), now.get(eye.bone)) {
                (Some(&(p0, a0)), Some(&(p1, a1))) => {
                    p1 + Vec2::from_angle(a1 - a0).rotate(eye.position - p0)
                }
                _ => eye.position,
            })
            .collect()
    }
}

/// How long the 2D creature's looping idle wiggle takes to repeat (seconds; see
/// [`Creature::idle_loop_rotations`]).
pub const IDLE_LOOP_SECONDS: f32 = 60.0;

/// The seed's idle wiggle for any bone list (see [`Creature::idle_rotations`]).
#[must_use]
pub(crate) fn idle_rotations(bones: &[Bone], t: f32) -> Vec<f32> {
    wiggle(bones, t, |frequency| frequency)
}

/// The wiggle `sin(t ω)` of every animated bone `i` of `bones`, its angular frequency `ω` the
/// seed's `(i / 0.23 + 1) / 10` (radians per second) through `frequency`; 0 for the others and
/// for a time that is not finite.
fn wiggle(bones: &[Bone], t: f32, frequency: impl Fn(f32) -> f32) -> Vec<f32> {
    bones
        .iter()
        .enumerate()
        .map(|(i, b)| {
            if b.animated() && t.is_finite() {
                crate::math::sin(t * frequency((i as f32 / 0.23 + 1.0) / 10.0))
            } else {
                0.0
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression (review): a joint index with no bone dropped its share of the vertex (pulling
    /// it toward the origin), and a NaN weight made the vertex NaN.
    #[test]
    fn posed_positions_keep_a_missing_bones_share_and_skip_bad_weights() {
        let bone = Bone {
            parent: None,
            offset: Vec2::ZERO,
            position: Vec2::new(1.0, 0.0),
            rotation: 0.0,
            thickness: 1.0,
            multiplier: 1.0,
            colour: Vec3::ONE,
            texture_weights: Vec2::new(0.5, 0.5),
            kind: BoneKind::Root,
        };
        let mut c = Creature {
            bones: alloc::vec![bone],
            ..Creature::default()
        };
        c.mesh.positions = alloc::vec![Vec3::new(2.0, 3.0, 0.5); 2];
        c.mesh.joints = alloc::vec![[0, 7, 0, 0], [0, 0, 0, 0]];
        c.mesh.weights = alloc::vec![[0.5, 0.5, 0.0, 0.0], [1.0, f32::NAN, 0.0, 0.0]];
        let quarter = core::f32::consts::FRAC_PI_2;
        let posed = c.posed_positions(&[quarter]);
        // Bone 0 turns (2, 3) a quarter turn about (1, 0): (-2, 1); bone 7 does not exist.
        let turned = Vec2::new(-2.0, 1.0);
        assert!(posed[0].distance(0.5 * turned + 0.5 * Vec2::new(2.0, 3.0)) < 1e-5);
        assert!(posed[1].distance(turned) < 1e-5, "{}", posed[1]);
    }
}
