//! Creatures, grounds and a simulation loop shared by the integration tests and the bench.
#![allow(dead_code)]

use creature_gait::glam::{Quat, Vec2, Vec3};
use creature_gait::{Controller, GaitError, GaitOptions, Ground, HeightField, Leg, Pose};

/// A creature with `pairs` leg pairs of leg length `length`, spaced along Z; body origin at hip
/// height, rest feet under the hips, slightly outward.
pub(crate) fn creature_legs(pairs: usize, length: f32) -> Vec<Leg> {
    let height = 0.8 * length;
    let spacing = 0.9 * length;
    let mut legs = Vec::new();
    for k in 0..pairs {
        let z = (k as f32 - (pairs as f32 - 1.0) * 0.5) * spacing;
        for side in [1.0f32, -1.0] {
            legs.push(
                Leg::new(
                    Vec3::new(0.25 * length * side, 0.0, z),
                    Vec3::new(0.35 * length * side, -height, z),
                    0.5 * length,
                    0.5 * length,
                )
                .with_pole(Vec3::Z),
            );
        }
    }
    legs
}

/// A deterministic random height field (value noise from an LCG) around the origin: 80 × 80 m,
/// bumps up to ± `amplitude`.
pub(crate) fn random_terrain(seed: u32, amplitude: f32) -> HeightField {
    let mut state = seed;
    let mut next = move || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1u32 << 24) as f32
    };
    let coarse: Vec<f32> = (0..21 * 21).map(|_| next() * 2.0 - 1.0).collect();
    HeightField::from_fn(Vec2::new(-40.0, -40.0), 0.5, 161, 161, |x, z| {
        // Bilinear interpolation of a 4 m lattice of random values, plus a little fine noise.
        let gx = ((x + 40.0) / 4.0).clamp(0.0, 19.999);
        let gz = ((z + 40.0) / 4.0).clamp(0.0, 19.999);
        let (i, j) = (gx as usize, gz as usize);
        let (u, v) = (gx - i as f32, gz - j as f32);
        let h = |a: usize, b: usize| coarse[b * 21 + a];
        let value = h(i, j) * (1.0 - u) * (1.0 - v)
            + h(i + 1, j) * u * (1.0 - v)
            + h(i, j + 1) * (1.0 - u) * v
            + h(i + 1, j + 1) * u * v;
        amplitude * value + 0.02 * amplitude * ((x * 3.1).sin() + (z * 2.3).cos())
    })
    .unwrap()
}

/// What a simulation measured, worst over all frames.
#[derive(Debug, Default, Clone)]
pub(crate) struct Figures {
    pub(crate) frames: usize,
    pub(crate) max_skate: f32,
    pub(crate) max_ground_gap: f32,
    pub(crate) max_overstretch: f32,
    pub(crate) opposite_overlaps: usize,
    pub(crate) escapes: u32,
    pub(crate) steps: Vec<u32>,
    pub(crate) max_in_air: usize,
    pub(crate) min_margin: f32,
}

/// Body motion of one frame: position, yaw, velocity, yaw rate.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    pub(crate) position: Vec3,
    pub(crate) yaw: f32,
    pub(crate) velocity: Vec3,
    pub(crate) yaw_rate: f32,
}

/// Drives `controller` along `frames` (at `dt`) over `ground`, with the body height put at
/// `ride` above the ground under the body (if any), and records the figures.
pub(crate) fn run(
    controller: &mut Controller,
    ground: &impl Ground,
    height_at: impl Fn(f32, f32) -> f32,
    ride: f32,
    dt: f32,
    frames: impl IntoIterator<Item = Frame>,
) -> Result<Figures, GaitError> {
    let mut figures = Figures {
        min_margin: f32::INFINITY,
        ..Figures::default()
    };
    let rests: Vec<Vec3> = controller.legs().iter().map(|l| l.rest).collect();
    for frame in frames {
        // Ride at the mean ground height under the rest feet, as a game would.
        let rotation = Quat::from_rotation_y(frame.yaw);
        let mean = rests
            .iter()
            .map(|r| {
                let p = frame.position + rotation * *r;
                height_at(p.x, p.z)
            })
            .sum::<f32>()
            / rests.len() as f32;
        let pose = Pose::new(
            Vec3::new(frame.position.x, mean + ride, frame.position.z),
            rotation,
        );
        controller.update(
            dt,
            pose,
            frame.velocity,
            Vec3::new(0.0, frame.yaw_rate, 0.0),
            ground,
        )?;
        figures.frames += 1;
        let m = controller.metrics();
        figures.max_skate = figures.max_skate.max(m.max_skate);
        figures.max_overstretch = figures.max_overstretch.max(m.max_overstretch);
        figures.max_in_air = figures.max_in_air.max(m.legs_in_air);
        if let Some(margin) = m.stability_margin {
            figures.min_margin = figures.min_margin.min(margin);
        }
        let states = controller.leg_states();
        for (i, s) in states.iter().enumerate() {
            if s.planted && s.grounded {
                let gap = (s.foot.y - height_at(s.foot.x, s.foot.z)).abs();
                figures.max_ground_gap = figures.max_ground_gap.max(gap);
            }
            if let Some(j) = controller.partner(i) {
                let o = &states[j];
                if i < j && s.stepping && o.stepping && !s.is_escaping() && !o.is_escaping() {
                    figures.opposite_overlaps += 1;
                }
            }
        }
    }
    figures.steps = controller.leg_states().iter().map(|s| s.steps).collect();
    figures.escapes = controller.leg_states().iter().map(|s| s.escapes).sum();
    Ok(figures)
}

/// Straight walk along +Z at `speed` for `distance` metres.
pub(crate) fn straight(speed: f32, distance: f32, dt: f32) -> impl Iterator<Item = Frame> {
    let frames = (distance / (speed * dt)).ceil() as usize;
    (0..=frames).map(move |k| Frame {
        position: Vec3::new(0.0, 0.0, -10.0 + speed * dt * k as f32),
        yaw: 0.0,
        velocity: Vec3::new(0.0, 0.0, speed),
        yaw_rate: 0.0,
    })
}

/// Default options, shared.
pub(crate) fn options() -> GaitOptions {
    GaitOptions::DEFAULT
}
