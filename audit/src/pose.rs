//! Posing a [`Model`] as a viewer does: node transforms from the animation's channels (linear
//! interpolation, rotations by slerp), world transforms down the node tree, and linear-blend
//! skinning with the joints' world transforms times their inverse bind matrices.

use glam::{Affine3A, Mat4, Quat, Vec3};

use crate::AuditError;
use crate::model::{Channel, Clip, Model, Values};

/// Poses one model, reusing its buffers from frame to frame.
#[derive(Debug)]
pub(crate) struct Poser<'a> {
    model: &'a Model,
    /// Nodes, parents before children.
    order: Vec<usize>,
    translation: Vec<Vec3>,
    rotation: Vec<Quat>,
    scale: Vec<Vec3>,
    world: Vec<Mat4>,
    skinning: Vec<Affine3A>,
    /// The skinned vertex positions of the last posed frame.
    pub(crate) positions: Vec<Vec3>,
}

impl<'a> Poser<'a> {
    pub(crate) fn new(model: &'a Model) -> Result<Self, AuditError> {
        let n = model.nodes.len();
        let mut depth = vec![0usize; n];
        for (i, d) in depth.iter_mut().enumerate() {
            let mut node = i;
            while let Some(p) = model.nodes[node].parent {
                *d += 1;
                if *d > n {
                    return Err(AuditError::Unsupported {
                        what: "a cycle in the node tree",
                    });
                }
                node = p;
            }
        }
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by_key(|&i| depth[i]);
        let mut poser = Self {
            model,
            order,
            translation: model.nodes.iter().map(|n| n.translation).collect(),
            rotation: model.nodes.iter().map(|n| n.rotation).collect(),
            scale: model.nodes.iter().map(|n| n.scale).collect(),
            world: vec![Mat4::IDENTITY; n],
            skinning: vec![Affine3A::IDENTITY; model.skin.len()],
            positions: model.positions.clone(),
        };
        poser.update();
        Ok(poser)
    }

    /// The rest pose (every node at its file transform).
    pub(crate) fn rest(&mut self) {
        for (i, node) in self.model.nodes.iter().enumerate() {
            self.translation[i] = node.translation;
            self.rotation[i] = node.rotation;
            self.scale[i] = node.scale;
        }
        self.update();
    }

    /// `clip` at time `t` (seconds).
    pub(crate) fn at(&mut self, clip: &Clip, t: f32) {
        for (i, node) in self.model.nodes.iter().enumerate() {
            self.translation[i] = node.translation;
            self.rotation[i] = node.rotation;
            self.scale[i] = node.scale;
        }
        for channel in &clip.channels {
            let (k, f) = key(channel, t);
            let node = channel.node;
            match &channel.values {
                Values::Translation(v) => self.translation[node] = lerp(v, k, f),
                Values::Scale(v) => self.scale[node] = lerp(v, k, f),
                Values::Rotation(r) => {
                    let a = r[k];
                    let b = r[(k + 1).min(r.len() - 1)];
                    self.rotation[node] = a.normalize().slerp(b.normalize(), f);
                }
            }
        }
        self.update();
    }

    /// The world transform of skin joint `j` in the last posed frame.
    pub(crate) fn joint_world(&self, j: usize) -> Mat4 {
        self.world[self.model.skin[j]]
    }

    /// Vertex `v`'s skinning (as its position is skinned) applied to its joints' `axes`
    /// (one direction per skin joint, at rest), blended by its weights: a direction along
    /// the body where it is, posed.
    pub(crate) fn blended(&self, v: usize, axes: &[Vec3]) -> Vec3 {
        let model = self.model;
        let mut sum = Vec3::ZERO;
        for (&j, &w) in model.joints[v].iter().zip(&model.weights[v]) {
            let j = usize::from(j);
            if w != 0.0 {
                sum += w * self.skinning[j].transform_vector3(axes[j]);
            }
        }
        sum
    }

    fn update(&mut self) {
        for &i in &self.order {
            let local = Mat4::from_scale_rotation_translation(
                self.scale[i],
                self.rotation[i],
                self.translation[i],
            );
            self.world[i] = match self.model.nodes[i].parent {
                Some(p) => self.world[p] * local,
                None => local,
            };
        }
        for (j, m) in self.skinning.iter_mut().enumerate() {
            let joint = self.model.skin[j];
            *m = Affine3A::from_mat4(self.world[joint] * self.model.inverse_bind[j]);
        }
        let model = self.model;
        for (((out, p), joints), weights) in self
            .positions
            .iter_mut()
            .zip(&model.positions)
            .zip(&model.joints)
            .zip(&model.weights)
        {
            let mut sum = Vec3::ZERO;
            for (&j, &w) in joints.iter().zip(weights) {
                if w != 0.0 {
                    sum += w * self.skinning[usize::from(j)].transform_point3(*p);
                }
            }
            *out = sum;
        }
    }
}

/// The key before `t` and the fraction toward the next.
fn key(channel: &Channel, t: f32) -> (usize, f32) {
    let times = &channel.times;
    let after = times.partition_point(|&k| k <= t);
    if after == 0 {
        return (0, 0.0);
    }
    let k = after - 1;
    if k + 1 >= times.len() {
        return (k, 0.0);
    }
    let span = times[k + 1] - times[k];
    let f = if span > 0.0 {
        ((t - times[k]) / span).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (k, f)
}

fn lerp(v: &[Vec3], k: usize, f: f32) -> Vec3 {
    v[k].lerp(v[(k + 1).min(v.len() - 1)], f)
}
