//! The rig's data: joints, the spine, and sockets.

use alloc::vec::Vec;

use glam::Vec3;

/// One joint of the skeleton.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// Rest position, in the mesh's frame.
    pub position: Vec3,
    /// The parent joint's index, `None` for the root.
    pub parent: Option<usize>,
}

/// An attachment point set for one spine bone: where limbs, wings and fins go.
///
/// The sides are the creature's own: the frame is right-handed with +Y up and +Z forward (glTF's
/// convention), so the creature's left is +X and its right −X. `left` is the bone's +X side,
/// `right` its −X side and `top` its +Y side, each taken square to the bone (see the crate's
/// conventions). Each point is a mesh vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Socket {
    /// The spine bone, counted from the tail: it runs from joint `spine[bone]` to
    /// `spine[bone + 1]` of [`Rig::spine`].
    pub bone: usize,
    /// The joint that carries the bone (its end nearer the root): attach limbs to it.
    pub joint: usize,
    /// The surface point on the bone's +X side: the creature's left.
    pub left: Vec3,
    /// The surface point on the bone's −X side: the creature's right.
    pub right: Vec3,
    /// The surface point on the bone's +Y side.
    pub top: Vec3,
    /// Index of the [`left`](Self::left) vertex in the mesh.
    pub left_vertex: u32,
    /// Index of the [`right`](Self::right) vertex in the mesh.
    pub right_vertex: u32,
    /// Index of the [`top`](Self::top) vertex in the mesh.
    pub top_vertex: u32,
    /// The body's width at the bone: the distance from `left` to `right`.
    pub width: f32,
    /// Height of the bone's midpoint above the lowest body point near the bone (along Y): how
    /// far below the spine the belly reaches there.
    pub clearance: f32,
}

/// A skeleton fitted to a body mesh by [`rig`](crate::rig).
///
/// The joints form one tree (exactly one root). The spine is a chain from the tail tip to the
/// head tip; for rigs built by [`rig`](crate::rig), every joint is on the spine, the root is
/// joint 0, and the two tips (which have no children) are the last joints.
#[derive(Debug, Clone, PartialEq)]
pub struct Rig {
    /// Every joint; parents are indices into this list.
    pub joints: Vec<Joint>,
    /// The spine's joints in order from the tail tip to the head tip; consecutive entries are
    /// one spine bone.
    pub spine: Vec<usize>,
    /// One socket set per spine bone except the first and last, from the tail forwards.
    pub sockets: Vec<Socket>,
    /// The head tip joint (the frontmost spine joint, on the mesh surface).
    pub head: usize,
    /// The tail tip joint (the rearmost spine joint, on the mesh surface).
    pub tail: usize,
}

impl Rig {
    /// The root joint: the first joint without a parent (0 for rigs built by
    /// [`rig`](crate::rig)).
    #[must_use]
    pub fn root(&self) -> Option<usize> {
        self.joints.iter().position(|j| j.parent.is_none())
    }

    /// The children of `joint`, in index order.
    pub fn children(&self, joint: usize) -> impl Iterator<Item = usize> + '_ {
        self.joints
            .iter()
            .enumerate()
            .filter(move |(_, j)| j.parent == Some(joint))
            .map(|(i, _)| i)
    }

    /// The spine bones as segments from the tail forwards: `[spine[b], spine[b + 1]]`'s
    /// positions.
    #[must_use]
    pub fn spine_bones(&self) -> Vec<[Vec3; 2]> {
        self.spine
            .windows(2)
            .filter_map(|w| {
                Some([
                    self.joints.get(w[0])?.position,
                    self.joints.get(w[1])?.position,
                ])
            })
            .collect()
    }

    /// The spine's length: the sum of its bones' lengths.
    #[must_use]
    pub fn spine_length(&self) -> f32 {
        self.spine_bones().iter().map(|b| b[0].distance(b[1])).sum()
    }

    /// Each deforming joint with the segment it moves, for skinning: one `(joint, [from, to])`
    /// per joint that has children, in joint order.
    ///
    /// A joint with one child moves the bone from itself to that child. A joint with two or more
    /// children (the centre root) moves the stretch between its first two children, which passes
    /// through it. Joints without children (the tips) move no segment of their own.
    #[must_use]
    pub fn bones(&self) -> Vec<(usize, [Vec3; 2])> {
        let mut out = Vec::with_capacity(self.joints.len());
        for (index, joint) in self.joints.iter().enumerate() {
            let mut children = self.children(index);
            let Some(first) = children.next().and_then(|c| self.joints.get(c)) else {
                continue;
            };
            let segment = match children.next().and_then(|c| self.joints.get(c)) {
                Some(second) => [first.position, second.position],
                None => [joint.position, first.position],
            };
            out.push((index, segment));
        }
        out
    }

    /// The segments of [`bones`](Self::bones) alone, ready for `creature_skin::nearest_k`.
    ///
    /// For rigs built by [`rig`](crate::rig) the joints without children come last, so segment
    /// `i` belongs to joint `i` and the skinning joint indices need no remapping. For an edited
    /// rig, pair them up through [`bones`](Self::bones).
    ///
    /// ```
    /// use creature_autorig::{glam::Vec3, rig, RigOptions};
    ///
    /// // A diamond along Z: tips at ±2, a waist of four vertices.
    /// let positions = [
    ///     Vec3::new(0.0, 0.0, -2.0), Vec3::new(0.0, 0.0, 2.0),
    ///     Vec3::new(0.5, 0.0, 0.0), Vec3::new(0.0, 0.5, 0.0),
    ///     Vec3::new(-0.5, 0.0, 0.0), Vec3::new(0.0, -0.5, 0.0),
    /// ];
    /// let triangles = [
    ///     [0, 3, 2], [0, 4, 3], [0, 5, 4], [0, 2, 5],
    ///     [1, 2, 3], [1, 3, 4], [1, 4, 5], [1, 5, 2],
    /// ];
    /// let rig = rig(&positions, &triangles, &RigOptions::default())?;
    /// let segments = rig.bone_segments();
    /// for (i, (joint, segment)) in rig.bones().into_iter().enumerate() {
    ///     assert_eq!(joint, i);
    ///     assert_eq!(segment, segments[i]);
    /// }
    /// # Ok::<(), creature_autorig::AutorigError>(())
    /// ```
    #[must_use]
    pub fn bone_segments(&self) -> Vec<[Vec3; 2]> {
        self.bones().into_iter().map(|(_, s)| s).collect()
    }

    /// True when the joints form exactly one tree: one root, every parent index in range, and
    /// no cycles.
    #[must_use]
    pub fn is_tree(&self) -> bool {
        let roots = self.joints.iter().filter(|j| j.parent.is_none()).count();
        if roots != 1 {
            return false;
        }
        // Every joint must reach the root within `len` steps.
        self.joints.iter().all(|start| {
            let mut current = *start;
            for _ in 0..self.joints.len() {
                match current.parent {
                    None => return true,
                    Some(p) => match self.joints.get(p) {
                        Some(&next) => current = next,
                        None => return false,
                    },
                }
            }
            false
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chain() -> Rig {
        // Root in the middle, two joints each way.
        let joints = alloc::vec![
            Joint {
                position: Vec3::ZERO,
                parent: None
            },
            Joint {
                position: Vec3::Z,
                parent: Some(0)
            },
            Joint {
                position: -Vec3::Z,
                parent: Some(0)
            },
            Joint {
                position: Vec3::Z * 2.0,
                parent: Some(1)
            },
            Joint {
                position: -Vec3::Z * 2.0,
                parent: Some(2)
            },
        ];
        Rig {
            joints,
            spine: alloc::vec![4, 2, 0, 1, 3],
            sockets: Vec::new(),
            head: 3,
            tail: 4,
        }
    }

    #[test]
    fn bones_pair_joints_with_the_segments_they_move() {
        let rig = chain();
        assert_eq!(
            rig.bones(),
            alloc::vec![
                (0, [Vec3::Z, -Vec3::Z]),
                (1, [Vec3::Z, Vec3::Z * 2.0]),
                (2, [-Vec3::Z, -Vec3::Z * 2.0]),
            ]
        );
        assert_eq!(rig.bone_segments().len(), 3);
        assert_eq!(rig.spine_bones().len(), 4);
        assert_eq!(rig.spine_length(), 4.0);
        assert_eq!(rig.root(), Some(0));
        assert_eq!(rig.children(0).collect::<Vec<_>>(), [1, 2]);
    }

    #[test]
    fn tree_check_finds_cycles_and_extra_roots() {
        let mut rig = chain();
        assert!(rig.is_tree());
        rig.joints[0].parent = Some(3);
        assert!(!rig.is_tree());
        rig.joints[0].parent = None;
        rig.joints[4].parent = None;
        assert!(!rig.is_tree());
        rig.joints[4].parent = Some(40);
        assert!(!rig.is_tree());
    }
}
