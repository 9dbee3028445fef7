//! Intent: the head's smoothed look-at, toward a target or where the body turns.

use glam::{Quat, Vec2, Vec3, Vec3A};

use super::{Controller, transform_a};
use crate::leg::Pose;
use crate::math::{Roots, atan2, clamp_sym, quat_yxz};

impl Controller {
    pub(super) fn intend(&mut self, pose: &Pose, angular_velocity: Vec3) {
        let o = &self.options;
        let (yaw_t, pitch_t) = match self.look_target {
            Some(target) => {
                let local = pose.inverse_transform_point(target) - self.head;
                let flat = Vec2::new(local.x, local.z).norm();
                if local.length_squared() > 1e-12 {
                    (atan2(local.x, local.z), atan2(local.y, flat))
                } else {
                    (0.0, o.look_pitch)
                }
            }
            None => (angular_velocity.y * o.look_ahead, o.look_pitch),
        };
        let yaw_t = clamp_sym(yaw_t, o.look_limit);
        let pitch_t = clamp_sym(pitch_t, o.look_limit);
        let k = self.look_k;
        let look = &mut self.look;
        look.yaw = clamp_sym(look.yaw + (yaw_t - look.yaw) * k, o.look_limit);
        look.pitch = clamp_sym(look.pitch + (pitch_t - look.pitch) * k, o.look_limit);
        // A settled gaze (same angles and blend as the last update) keeps its rotation.
        let key = [
            look.yaw.to_bits(),
            look.pitch.to_bits(),
            self.blend.to_bits(),
        ];
        let local = match self.look_cache {
            Some((cached, local)) if cached == key => local,
            _ => {
                let full = quat_yxz(look.yaw, -look.pitch, 0.0);
                look.rotation = if self.blend == 1.0 {
                    full.unit()
                } else {
                    Quat::IDENTITY.slerp(full, self.blend).unit()
                };
                let local = Vec3A::from(self.head + full * Vec3::Z * (2.0 * self.mean_size));
                self.look_cache = Some((key, local));
                local
            }
        };
        look.target = transform_a(pose, local);
    }
}

#[cfg(test)]
mod tests {
    use alloc::vec::Vec;

    use glam::{Quat, Vec3};

    use crate::ground::Plane;
    use crate::{Controller, GaitOptions, Leg, Pose};

    fn quadruped(options: &GaitOptions) -> Controller {
        let legs: Vec<Leg> = [(0.2, 0.4), (-0.2, 0.4), (0.2, -0.4), (-0.2, -0.4)]
            .iter()
            .map(|&(x, z)| Leg::new(Vec3::new(x, 0.0, z), Vec3::new(1.2 * x, -0.8, z), 0.5, 0.5))
            .collect();
        Controller::new(&legs, options).unwrap()
    }

    fn walk(c: &mut Controller, from: usize, frames: usize) {
        let dt = 1.0 / 60.0;
        for f in from..from + frames {
            let pose = Pose::new(Vec3::new(0.0, 0.8, f as f32 * dt), Quat::IDENTITY);
            c.update(dt, pose, Vec3::Z, Vec3::ZERO, &Plane::GROUND)
                .unwrap();
        }
    }

    #[test]
    fn a_settled_gaze_follows_a_new_head_position() {
        // The look-at keeps its rotation while its angles stand still; moving the head must
        // still move the gaze's target.
        let mut late = quadruped(&GaitOptions::DEFAULT);
        walk(&mut late, 0, 600);
        late.set_head(Vec3::new(0.0, 0.3, 0.6)).unwrap();
        walk(&mut late, 600, 1);
        let mut early = quadruped(&GaitOptions::DEFAULT);
        early.set_head(Vec3::new(0.0, 0.3, 0.6)).unwrap();
        walk(&mut early, 0, 601);
        assert_eq!(late.look(), early.look());
    }

    #[test]
    fn a_reset_recomputes_an_instant_gaze() {
        // With no smoothing the gaze's angles are the same before and after a reset, which
        // sets its rotation to identity: the next update must compute it again.
        let options = GaitOptions::DEFAULT.with_look(0.4, 1.0, 0.0);
        let mut walked = quadruped(&options);
        walk(&mut walked, 0, 120);
        let pose = Pose::new(Vec3::new(0.0, 0.8, 2.0), Quat::IDENTITY);
        walked.reset(pose, &Plane::GROUND).unwrap();
        walk(&mut walked, 120, 1);
        let mut fresh = quadruped(&options);
        fresh.reset(pose, &Plane::GROUND).unwrap();
        walk(&mut fresh, 120, 1);
        assert_eq!(walked.look(), fresh.look());
        assert_ne!(walked.look().rotation, Quat::IDENTITY);
    }
}
