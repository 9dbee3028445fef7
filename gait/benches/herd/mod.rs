//! The bench's workload, shared by `benches/update.rs` and `examples/herd.rs`: hexapods walking
//! in rows over a 401 × 401 height field, one update each per frame.
#![allow(dead_code)]

use creature_gait::glam::{Quat, Vec2, Vec3};
use creature_gait::{Controller, GaitError, GaitOptions, Ground, HeightField, Leg, Pose};

/// Creatures in the bench.
pub(crate) const CREATURES: usize = 1000;
/// The time step, seconds.
pub(crate) const DT: f32 = 1.0 / 60.0;

/// Six legs in three pairs, hips 0.8 m above the rest feet.
pub(crate) fn hexapod() -> Vec<Leg> {
    let mut legs = Vec::new();
    for k in 0..3 {
        let z = 0.9 - 0.9 * k as f32;
        for side in [1.0f32, -1.0] {
            legs.push(Leg::new(
                Vec3::new(0.25 * side, 0.0, z),
                Vec3::new(0.35 * side, -0.8, z),
                0.5,
                0.5,
            ));
        }
    }
    legs
}

/// 200 × 200 m of rolling ground, 0.5 m cells.
pub(crate) fn terrain() -> Result<HeightField, GaitError> {
    HeightField::from_fn(Vec2::splat(-100.0), 0.5, 401, 401, |x, z| {
        0.3 * (x * 0.37).sin() * (z * 0.29).cos() + 0.05 * (x * 2.1 + z * 1.7).sin()
    })
}

/// The creatures, where they are and how fast they walk.
pub(crate) struct Herd {
    pub(crate) controllers: Vec<Controller>,
    pub(crate) positions: Vec<Vec3>,
    pub(crate) velocities: Vec<Vec3>,
}

impl Herd {
    /// `count` hexapods (at most 1,000 fit the field) in rows of 40, walking +Z at 0.5 to
    /// 1.7 m/s over `ground` (its heights from `field`), after a second of warm-up each.
    pub(crate) fn new(
        count: usize,
        ground: &impl Ground,
        field: &HeightField,
    ) -> Result<Self, GaitError> {
        Self::with(count, ground, field, &GaitOptions::DEFAULT, |i| {
            0.5 + (i % 7) as f32 * 0.2
        })
    }

    /// [`new`](Self::new) with `options`, creature `i` at `speed(i)` m/s.
    pub(crate) fn with(
        count: usize,
        ground: &impl Ground,
        field: &HeightField,
        options: &GaitOptions,
        speed: impl Fn(usize) -> f32,
    ) -> Result<Self, GaitError> {
        let legs = hexapod();
        let mut herd = Self {
            controllers: Vec::new(),
            positions: Vec::new(),
            velocities: Vec::new(),
        };
        for i in 0..count {
            let mut p = Vec3::new(
                (i % 40) as f32 * 4.0 - 80.0,
                0.0,
                (i / 40) as f32 * 6.0 - 80.0,
            );
            let velocity = Vec3::new(0.0, 0.0, speed(i));
            let mut c = Controller::new(&legs, options)?;
            for _ in 0..60 {
                p += velocity * DT;
                let y = field.height(p.x, p.z).unwrap_or(0.0) + 0.8;
                c.update(
                    DT,
                    Pose::new(Vec3::new(p.x, y, p.z), Quat::IDENTITY),
                    velocity,
                    Vec3::ZERO,
                    ground,
                )?;
            }
            herd.controllers.push(c);
            herd.positions.push(p);
            herd.velocities.push(velocity);
        }
        Ok(herd)
    }

    /// One frame: every creature moves on (wrapping back before the far edge) and updates.
    pub(crate) fn step(
        &mut self,
        ground: &impl Ground,
        field: &HeightField,
    ) -> Result<(), GaitError> {
        for ((c, p), v) in self
            .controllers
            .iter_mut()
            .zip(&mut self.positions)
            .zip(&self.velocities)
        {
            *p += *v * DT;
            if p.z > 90.0 {
                p.z -= 170.0;
            }
            let y = field.height(p.x, p.z).unwrap_or(0.0) + 0.8;
            let pose = Pose::new(Vec3::new(p.x, y, p.z), Quat::IDENTITY);
            c.update(DT, pose, *v, Vec3::ZERO, ground)?;
        }
        Ok(())
    }
}
