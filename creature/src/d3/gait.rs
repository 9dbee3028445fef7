//! Gait set-up of a 3D walker: its legs and arms registered with `creature-gait`.

use alloc::vec::Vec;

use creature_gait::{Controller, GaitOptions, Leg};

use crate::Error;

/// A walker's legs and arms as `creature-gait` takes them (body space = the creature's model
/// space at rest, the ground at `y = 0`), with the gait options, ready for a [`Controller`].
///
/// ```
/// use creature::d3::{generate, Kind, Params};
/// use creature::gait::{Plane, Pose, glam::Vec3};
///
/// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
/// let setup = walker.gait.as_ref().expect("walkers have a gait set-up");
/// let mut controller = setup.controller()?;
/// let ground = Plane::horizontal(0.0);
/// let velocity = Vec3::Z * walker.speed;
/// let mut position = Vec3::ZERO;
/// for _ in 0..30 {
///     position += velocity / 30.0;
///     controller.update(1.0 / 30.0, Pose::from_yaw(position, 0.0), velocity, Vec3::ZERO, &ground)?;
/// }
/// assert!(controller.metrics().max_skate <= 1e-3 * walker.length);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct GaitSetup {
    /// The legs and arms, hips and rest feet (hands) where the mesh has them.
    pub legs: Vec<Leg>,
    /// For each of [`legs`](Self::legs), its index in the creature's limb plan.
    pub limbs: Vec<usize>,
    /// For each of [`legs`](Self::legs), its hip joint in the skeleton; the knee and the foot
    /// are the next two joints.
    pub hip_joints: Vec<usize>,
    /// Gait options: the defaults, with the creature's speed factor as the speed multiplier.
    pub options: GaitOptions,
}

impl GaitSetup {
    /// A fresh controller for these legs.
    ///
    /// # Errors
    /// [`Error::Gait`] if `creature-gait` rejects the legs or options (an edited set-up).
    pub fn controller(&self) -> Result<Controller, Error> {
        Ok(Controller::new(&self.legs, &self.options)?)
    }
}
