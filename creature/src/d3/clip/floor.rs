//! Nothing under the floor: knees turned so that they never bend through the ground, and how
//! far a joint's ring of vertices reaches.

use glam::Vec3;

use crate::d3::Creature;

impl Creature {
    /// How far the mesh's vertices skinned to `joint` reach from its rest position: for a
    /// knee, the radius of the ring around it.
    pub(super) fn ring_radius(&self, joint: usize) -> f32 {
        let Some(centre) = self.skeleton.joints.get(joint).map(|j| j.position) else {
            return 0.0;
        };
        let mesh = &self.mesh;
        mesh.positions
            .iter()
            .zip(&mesh.joints)
            .zip(&mesh.weights)
            .filter(|((_, js), ws)| {
                js.iter()
                    .zip(ws.iter())
                    .any(|(&j, &w)| usize::from(j) == joint && w > 0.0)
            })
            .map(|((p, _), _)| p.distance(centre))
            .fold(0.0f32, f32::max)
    }
}

/// The knee `middle` of a solved two-bone chain from `root` to `end`, turned about the
/// root–end axis as little as needed so that its height along `up` is at least `floor` (as
/// high as it can go when no turn reaches that): a knee never bends through the ground. The
/// chain's bone lengths and ends are unchanged; a knee already high enough is returned as is.
pub(super) fn knee_above(root: Vec3, middle: Vec3, end: Vec3, up: Vec3, floor: f32) -> Vec3 {
    if up.dot(middle) >= floor {
        return middle;
    }
    let Some(dir) = (end - root).try_normalize() else {
        return middle;
    };
    let centre = root + dir * dir.dot(middle - root);
    let offset = middle - centre;
    let across = offset.length();
    if !(across > 0.0) {
        return middle;
    }
    let b1 = offset / across;
    let b2 = dir.cross(b1);
    // Height of the knee turned by φ: h(φ) = c + across (cos φ u₁ + sin φ u₂).
    let c = up.dot(centre);
    let (u1, u2) = (up.dot(b1), up.dot(b2));
    let m = crate::math::sqrt(u1 * u1 + u2 * u2);
    if !(m > 1e-9) {
        return middle;
    }
    let (u1, u2) = (u1 / m, u2 / m);
    // The turn (cos φ, sin φ) whose height is `floor`, nearest to no turn; the highest knee
    // when even that is too low.
    let k = (floor - c) / (across * m);
    let (cos, sin) = if k >= 1.0 {
        (u1, u2)
    } else {
        let k = k.max(-1.0);
        let w = crate::math::sqrt((1.0 - k * k).max(0.0));
        let a = (k * u1 - w * u2, k * u2 + w * u1);
        let b = (k * u1 + w * u2, k * u2 - w * u1);
        if a.0 >= b.0 { a } else { b }
    };
    centre + across * (cos * b1 + sin * b2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn a_knee_turns_just_above_the_floor_keeping_its_bones() {
        let (root, end) = (Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.2, 1.2));
        // A knee bent down, below y = 0.3.
        let knee = Vec3::new(0.0, 0.1, 0.4);
        let (upper, lower) = (root.distance(knee), end.distance(knee));
        let lifted = knee_above(root, knee, end, Vec3::Y, 0.3);
        assert!((lifted.y - 0.3).abs() < 1e-5, "{lifted}");
        assert!((root.distance(lifted) - upper).abs() < 1e-5);
        assert!((end.distance(lifted) - lower).abs() < 1e-5);
        // The smaller of the two turns: it stays on the side it was (x < 0 or x > 0 are
        // equally near here; either keeps the bones).
        assert_eq!(knee_above(root, knee, end, Vec3::Y, 0.05), knee);
        // Out of reach of any turn: the highest knee.
        let highest = knee_above(root, knee, end, Vec3::Y, 5.0);
        for k in 0..64 {
            let turn = Quat::from_axis_angle((end - root).normalize(), k as f32 * 0.1);
            let other = root + turn * (knee - root);
            assert!(other.y <= highest.y + 1e-5);
        }
    }
}
