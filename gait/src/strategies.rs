//! Proptest strategies for this crate's inputs (feature `proptest`).
//!
//! Valid inputs ([`leg_layout`], [`height_field`], [`motion_sequence`], [`two_bone`],
//! [`flap_params`], [`swim_params`]) and
//! adversarial ones for the error paths ([`bad_leg`], [`bad_time_step`], [`non_finite_vec3`]),
//! so a downstream property suite can generate creatures and the motions that drive them the
//! way this crate's own suite does.
//!
//! ```
//! use creature_gait::{Controller, GaitOptions, strategies};
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::deterministic();
//! runner.run(&strategies::leg_layout(), |legs| {
//!     let controller = Controller::new(&legs, &GaitOptions::DEFAULT);
//!     proptest::prop_assert!(controller.is_ok());
//!     Ok(())
//! }).unwrap();
//! ```

use alloc::vec::Vec;

use glam::{Vec2, Vec3};
use proptest::prelude::*;

use crate::{FlapParams, HeightField, Leg, SwimParams, WingKind};

/// A finite point with every coordinate in `[-range, range]`.
pub fn vec3_in(range: f32) -> impl Strategy<Value = Vec3> {
    (-range..=range, -range..=range, -range..=range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A valid, plausible leg layout: 1 to 6 left/right pairs spaced along Z (body origin at hip
/// height), leg lengths 0.2 to 2 m per pair, rest feet under the hips; sometimes a centre leg.
/// Always accepted by [`Controller::new`](crate::Controller::new).
pub fn leg_layout() -> impl Strategy<Value = Vec<Leg>> {
    (
        prop::collection::vec((0.2f32..2.0, 0.3f32..0.6), 1..=6),
        any::<bool>(),
    )
        .prop_map(|(pairs, centre)| {
            let mut legs = Vec::new();
            let mut z = 0.0f32;
            let mut height = 0.0f32;
            for &(length, _) in &pairs {
                height = height.max(0.8 * length);
            }
            for (length, spread) in pairs {
                for side in [1.0f32, -1.0] {
                    let hip = Vec3::new(spread * length * 0.6 * side, 0.0, z);
                    let rest = Vec3::new(spread * length * side, -height.min(0.9 * length), z);
                    legs.push(Leg::new(hip, rest, 0.5 * length, 0.5 * length));
                }
                z -= 0.9 * length;
            }
            if centre {
                legs.push(Leg::new(
                    Vec3::new(0.0, 0.0, z),
                    Vec3::new(0.0, -0.5, z),
                    0.4,
                    0.4,
                ));
            }
            legs
        })
}

/// A valid height field around the origin: 40 × 40 m, cell 0.5 to 2 m, heights within
/// `± amplitude` from a random lattice.
pub fn height_field(amplitude: f32) -> impl Strategy<Value = HeightField> {
    (0.5f32..2.0, prop::collection::vec(-1.0f32..1.0, 16)).prop_filter_map(
        "rejected field",
        move |(cell, lattice)| {
            let count = (40.0 / cell) as usize + 1;
            HeightField::from_fn(Vec2::splat(-20.0), cell, count, count, |x, z| {
                let i = (((x + 20.0) / 10.0) as usize).min(3);
                let j = (((z + 20.0) / 10.0) as usize).min(3);
                amplitude * lattice[j * 4 + i] * 0.5
                    + 0.5 * amplitude * (x * 0.7).sin() * (z * 0.4).cos()
            })
            .ok()
        },
    )
}

/// One step of a motion sequence: time step, forward speed (body space) and yaw rate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionStep {
    /// Seconds, in `[1/240, 1/20]`.
    pub dt: f32,
    /// Forward speed in m/s, in `[-1, 4]` (negative walks backwards).
    pub speed: f32,
    /// Sideways speed in m/s, in `[-1, 1]`.
    pub strafe: f32,
    /// Yaw rate in rad/s, in `[-3, 3]`.
    pub yaw_rate: f32,
    /// How many frames this step lasts, 1 to 120.
    pub frames: u32,
}

/// A sequence of `1..=max_len` motion steps (each held for up to 2 s): random walking,
/// strafing, turning and stopping, with variable time steps.
pub fn motion_sequence(max_len: usize) -> impl Strategy<Value = Vec<MotionStep>> {
    let step = (
        1.0f32 / 240.0..1.0 / 20.0,
        prop_oneof![Just(0.0f32), -1.0f32..4.0],
        prop_oneof![Just(0.0f32), -1.0f32..1.0],
        prop_oneof![Just(0.0f32), -3.0f32..3.0],
        1u32..=120,
    )
        .prop_map(|(dt, speed, strafe, yaw_rate, frames)| MotionStep {
            dt,
            speed,
            strafe,
            yaw_rate,
            frames,
        });
    prop::collection::vec(step, 1..=max_len.max(1))
}

/// A two-bone problem `(root, target, upper, lower, pole)` with any finite target, lengths
/// 0.05 to 3 m and a pole not parallel to the chain.
pub fn two_bone() -> impl Strategy<Value = (Vec3, Vec3, f32, f32, Vec3)> {
    (
        vec3_in(10.0),
        vec3_in(10.0),
        0.05f32..3.0,
        0.05f32..3.0,
        vec3_in(1.0),
    )
        .prop_filter(
            "pole parallel to the chain",
            |(root, target, _, _, pole)| {
                let d = *target - *root;
                d.length() > 1e-3
                    && pole.length() > 0.1
                    && d.normalize().cross(pole.normalize()).length() > 0.1
            },
        )
}

/// A float that is NaN or infinite.
pub fn non_finite_f32() -> impl Strategy<Value = f32> {
    prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY)]
}

/// A vector with at least one NaN or infinite coordinate.
pub fn non_finite_vec3() -> impl Strategy<Value = Vec3> {
    (0usize..3, non_finite_f32(), vec3_in(10.0)).prop_map(|(axis, bad, mut v)| {
        v[axis] = bad;
        v
    })
}

/// A time step [`Controller::update`](crate::Controller::update) must reject: negative, NaN,
/// infinite or beyond [`MAX_TIME_STEP`](crate::MAX_TIME_STEP).
pub fn bad_time_step() -> impl Strategy<Value = f32> {
    prop_oneof![non_finite_f32(), -1000.0f32..-1e-6, 1001.0f32..1e9]
}

/// A leg [`Leg::validate`] must reject: a non-finite position or pole, a segment or size that
/// is zero or negative, or a zero pole.
pub fn bad_leg() -> impl Strategy<Value = Leg> {
    let base = Leg::new(
        Vec3::new(0.2, 0.0, 0.0),
        Vec3::new(0.3, -0.8, 0.0),
        0.5,
        0.5,
    );
    prop_oneof![
        non_finite_vec3().prop_map(move |v| Leg { hip: v, ..base }),
        non_finite_vec3().prop_map(move |v| Leg { rest: v, ..base }),
        non_finite_vec3().prop_map(move |v| base.with_pole(v)),
        (-1.0f32..=0.0).prop_map(move |v| Leg { upper: v, ..base }),
        (-1.0f32..=0.0).prop_map(move |v| Leg { lower: v, ..base }),
        (-1.0f32..=0.0).prop_map(move |v| base.with_size(v)),
        Just(base.with_pole(Vec3::ZERO)),
    ]
}

/// Valid [`FlapParams`] (either wing kind, every field in its range), accepted by
/// [`FlapParams::validate`].
pub fn flap_params() -> impl Strategy<Value = FlapParams> {
    (
        any::<bool>(),
        0.1f32..60.0,
        0.0f32..1.5,
        -1.5f32..1.5,
        0.0f32..1.0,
        0.05f32..5.0,
        0.05f32..20.0,
    )
        .prop_map(|(buzz, frequency, amplitude, bias, bob, idle, fade)| {
            let kind = if buzz {
                WingKind::Buzzing
            } else {
                WingKind::Flapping
            };
            FlapParams::DEFAULT
                .with_kind(kind)
                .with_frequency(frequency)
                .with_amplitude(amplitude)
                .with_bias(bias)
                .with_bob(bob)
                .with_idle_frequency(idle)
                .with_bob_fade_speed(fade)
        })
}

/// Valid [`SwimParams`] (every field in its range), accepted by [`SwimParams::validate`].
pub fn swim_params() -> impl Strategy<Value = SwimParams> {
    (
        0.1f32..10.0,
        0.0f32..1.5,
        0.0f32..3.0,
        0.0f32..4.0,
        0.0f32..0.5,
        0.05f32..3.0,
        0.05f32..10.0,
    )
        .prop_map(
            |(frequency, amplitude, wavelength, gain, idle_amplitude, idle, full)| {
                SwimParams::DEFAULT
                    .with_wiggle(frequency, amplitude)
                    .with_wave(wavelength, gain)
                    .with_idle(idle, idle_amplitude)
                    .with_full_speed(full)
            },
        )
}
