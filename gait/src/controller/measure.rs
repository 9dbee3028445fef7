//! The figures of [`Controller::metrics`]: skate, overstretch, legs in the air and the
//! stability margin, measured when asked rather than every update.

use alloc::vec::Vec;

use glam::Vec2;

use super::{Controller, transform_a};
use crate::leg::LimbKind;
use crate::math::sqrt;
use crate::metrics::{GaitMetrics, support_margin};

impl Controller {
    /// Skate, overstretch, legs in the air and the stability margin of the state the last
    /// update left (see [`Controller::metrics`]).
    pub(super) fn measure(&self) -> GaitMetrics {
        let mut skate = 0.0f32;
        let mut over = 0.0f32;
        let mut in_air = 0usize;
        let mut support: Vec<Vec2> = Vec::with_capacity(self.legs.len());
        for (leg, state) in self.legs.iter().zip(&self.states) {
            if leg.kind != LimbKind::Leg {
                continue;
            }
            // Squared distances: the square root (monotonic) is taken of the largest only.
            if state.prev_planted && state.planted {
                skate = skate.max(state.foot.distance_squared(state.prev_foot));
            }
            if state.stepping || !state.grounded {
                in_air += 1;
            } else {
                support.push(Vec2::new(state.foot.x, state.foot.z));
                let reach = leg.length();
                let d2 = state.foot.distance_squared(state.joints.root);
                if d2 > reach * reach {
                    over = over.max(sqrt(d2) - reach);
                }
            }
        }
        let com = transform_a(&self.pose, self.centre_of_mass);
        let mut hull = Vec::with_capacity(support.len() + 1);
        GaitMetrics {
            max_skate: sqrt(skate),
            max_overstretch: over.max(0.0),
            legs_in_air: in_air,
            stability_margin: support_margin(&mut support, &mut hull, Vec2::new(com.x, com.z)),
            ..self.metrics
        }
    }
}
