//! Procedural motions of fliers and swimmers (3D seed, sections 4.3.1 and 4.3.2): wing
//! flapping with the flier's up-and-down bob ([`FlapParams`]), and the swimmer's head wiggle,
//! travelling body wave and idle sway ([`SwimParams`]). Plain data in, angles and offsets out:
//! pure functions of time and speed, no state, no allocation.
//!
//! The seed drives the rest of these bodies with damped transforms; here that is
//! [`Chain`](crate::Chain) (a flier's tail half, fins, dangling legs) or, for a swimmer's whole
//! body, the closed-form travelling wave of [`SwimParams::bone_yaw`].
//!
//! Time `t` is in seconds. Outputs are periodic in `t` (period `1 / frequency`) up to f32
//! rounding of `frequency · t`, which grows with `t`: for long runs, wrap `t` by a common
//! multiple of the periods (e.g. `t % 1000.0` for frequencies in steps of 0.001 Hz).

use core::f32::consts::FRAC_PI_2;

use glam::{Quat, Vec3};

use crate::error::{GaitError, in_range};
use crate::math::{quat_yxz, sin_turns};

/// How a flier's wings beat (3D seed, 4.3.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum WingKind {
    /// Bird- or bat-like wings: slow beats; the body bobs in time with them, also in flight.
    #[default]
    Flapping,
    /// Insect-like wings: fast beats ("buzzing"); the body bobs slowly while hovering and stops
    /// bobbing when it flies forward.
    Buzzing,
}

/// Which side a wing (or fin) is on: `Left` is body +X, `Right` is −X (+Z forward, +Y up).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Body +X.
    Left,
    /// Body −X.
    Right,
}

/// The parameters of a flier's wing beat and body bob.
///
/// The wing angle is `bias + amplitude · sin(2π · frequency · t)` (radians, positive up). With
/// [`WingKind::Flapping`] the body bobs in time with the beat, `−bob · sin(2π · frequency · t)`:
/// highest when the wings are lowest, at the end of the downstroke, whatever the speed. With
/// [`WingKind::Buzzing`] it bobs at `idle_frequency`, fading out linearly as the speed rises to
/// `bob_fade_speed`.
///
/// ```
/// use creature_gait::{FlapParams, Side, WingKind};
///
/// let bird = FlapParams::FLAPPING.with_amplitude(0.7);
/// bird.validate()?;
/// for frame in 0..120 {
///     let t = frame as f32 / 60.0;
///     let angle = bird.wing_angle(t); // rotate each wing's root bone by this, about +Z
///     let left = bird.wing_rotation(t, Side::Left);
///     let lift = bird.body_bob(t, 3.0); // add to the body's height (metres)
///     assert!(angle.abs() <= bird.bias.abs() + bird.amplitude + 1e-6);
///     assert!(lift.abs() <= bird.bob + 1e-6 && left.is_normalized());
/// }
/// // An insect stops bobbing once it flies forward.
/// let fly = FlapParams::BUZZING;
/// assert_eq!(fly.body_bob(0.3, fly.bob_fade_speed), 0.0);
/// assert_eq!(fly.kind, WingKind::Buzzing);
/// # Ok::<(), creature_gait::GaitError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FlapParams {
    /// Flapping or buzzing. Default [`WingKind::Flapping`].
    pub kind: WingKind,
    /// Wing beats per second, `(0, 200]`. Default 2.5 (buzzing: 30).
    pub frequency: f32,
    /// Wing angle amplitude about the mean, radians, `[0, π/2]`. Default 0.6 (buzzing: 0.35).
    pub amplitude: f32,
    /// Mean wing angle (dihedral), radians, positive up, `[−π/2, π/2]`. Default 0.1
    /// (buzzing: 0.2).
    pub bias: f32,
    /// Amplitude of the body's up-and-down bob, metres, `[0, 10]`. Default 0.05
    /// (buzzing: 0.03).
    pub bob: f32,
    /// Bob rate of buzzing wings, cycles per second, `(0, 100]` (flapping wings bob at
    /// `frequency`). Default 0.8.
    pub idle_frequency: f32,
    /// Speed (m/s) at which a buzzing flier has stopped bobbing, `(0, 1000]`. Default 0.5.
    pub bob_fade_speed: f32,
}

impl FlapParams {
    /// Flapping wings (bird, bat), the defaults listed on each field.
    pub const FLAPPING: Self = Self {
        kind: WingKind::Flapping,
        frequency: 2.5,
        amplitude: 0.6,
        bias: 0.1,
        bob: 0.05,
        idle_frequency: 0.8,
        bob_fade_speed: 0.5,
    };

    /// Buzzing wings (insect): fast, small beats and a slow hover bob.
    pub const BUZZING: Self = Self {
        kind: WingKind::Buzzing,
        frequency: 30.0,
        amplitude: 0.35,
        bias: 0.2,
        bob: 0.03,
        idle_frequency: 0.8,
        bob_fade_speed: 0.5,
    };

    /// The default, [`FlapParams::FLAPPING`].
    pub const DEFAULT: Self = Self::FLAPPING;

    /// Sets [`kind`](Self::kind).
    #[must_use]
    pub const fn with_kind(mut self, kind: WingKind) -> Self {
        self.kind = kind;
        self
    }
    /// Sets [`frequency`](Self::frequency).
    #[must_use]
    pub const fn with_frequency(mut self, value: f32) -> Self {
        self.frequency = value;
        self
    }
    /// Sets [`amplitude`](Self::amplitude).
    #[must_use]
    pub const fn with_amplitude(mut self, value: f32) -> Self {
        self.amplitude = value;
        self
    }
    /// Sets [`bias`](Self::bias).
    #[must_use]
    pub const fn with_bias(mut self, value: f32) -> Self {
        self.bias = value;
        self
    }
    /// Sets [`bob`](Self::bob).
    #[must_use]
    pub const fn with_bob(mut self, value: f32) -> Self {
        self.bob = value;
        self
    }
    /// Sets [`idle_frequency`](Self::idle_frequency).
    #[must_use]
    pub const fn with_idle_frequency(mut self, value: f32) -> Self {
        self.idle_frequency = value;
        self
    }
    /// Sets [`bob_fade_speed`](Self::bob_fade_speed).
    #[must_use]
    pub const fn with_bob_fade_speed(mut self, value: f32) -> Self {
        self.bob_fade_speed = value;
        self
    }

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`GaitError::OutOfRange`] naming the first bad field (NaN included).
    pub fn validate(&self) -> Result<(), GaitError> {
        let tiny = f32::MIN_POSITIVE;
        in_range(self.frequency, "flap frequency", tiny, 200.0)?;
        in_range(self.amplitude, "flap amplitude", 0.0, FRAC_PI_2)?;
        in_range(self.bias, "flap bias", -FRAC_PI_2, FRAC_PI_2)?;
        in_range(self.bob, "flap bob", 0.0, 10.0)?;
        in_range(self.idle_frequency, "flap idle frequency", tiny, 100.0)?;
        in_range(self.bob_fade_speed, "flap bob fade speed", tiny, 1000.0)?;
        Ok(())
    }

    /// The wing angle at time `t`, radians, positive up: `bias + amplitude · sin(2π f t)`.
    /// Within `|bias| + amplitude`; 0 for a non-finite result.
    #[must_use]
    pub fn wing_angle(&self, t: f32) -> f32 {
        finite_or_zero(self.bias + self.amplitude * sin_turns(self.frequency * t))
    }

    /// The wing's root rotation at time `t` in body space: a turn about the body's forward
    /// axis (+Z) that lifts the wing's tip when the angle is positive, on either side.
    #[must_use]
    pub fn wing_rotation(&self, t: f32, side: Side) -> Quat {
        let angle = self.wing_angle(t);
        let signed = match side {
            Side::Left => angle,
            Side::Right => -angle,
        };
        quat_yxz(0.0, 0.0, signed)
    }

    /// The body's vertical offset (metres) at time `t` while moving at `speed` (m/s): in time
    /// with the beat for flapping wings (any speed); a slow bob fading out with speed for
    /// buzzing wings. Within `bob`; 0 for non-finite input.
    #[must_use]
    pub fn body_bob(&self, t: f32, speed: f32) -> f32 {
        let value = match self.kind {
            WingKind::Flapping => -self.bob * sin_turns(self.frequency * t),
            WingKind::Buzzing => {
                let fade = (1.0 - abs_speed(speed) / self.bob_fade_speed).clamp(0.0, 1.0);
                self.bob * fade * sin_turns(self.idle_frequency * t)
            }
        };
        finite_or_zero(value)
    }

    /// The body's bob as an offset vector (world +Y).
    #[must_use]
    pub fn body_offset(&self, t: f32, speed: f32) -> Vec3 {
        Vec3::Y * self.body_bob(t, speed)
    }
}

impl Default for FlapParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The parameters of a swimmer's motion (3D seed, 4.3.2): while moving, the head wiggles left
/// and right and the wiggle travels down the body to the tail as a wave that grows toward the
/// tail; when idle, the whole body sways slightly.
///
/// Bone `u` (0 at the head, 1 at the tail tip) turns about the body's up axis by
/// `w · amplitude · (1 + (tail_gain − 1) · u) · sin(2π (frequency · t − wavelength · u))`
/// plus `(1 − w) · idle_amplitude · sin(2π (idle_frequency · t − wavelength · u / 2))`, where
/// `w = min(speed / full_speed, 1)` blends from idle to swimming.
///
/// ```
/// use creature_gait::SwimParams;
///
/// let fish = SwimParams::DEFAULT.with_wave(1.0, 1.2);
/// fish.validate()?;
/// let bones = 8;
/// let mut yaws = [0.0f32; 8];
/// for frame in 0..60 {
///     let t = frame as f32 / 60.0;
///     // Each spine bone's turn about the body's up axis, head first.
///     fish.bone_yaws(t, 1.5, &mut yaws);
///     assert!(yaws.iter().all(|y| y.abs() <= fish.max_yaw() + 1e-6));
/// }
/// // At rest only the gentle idle sway is left.
/// assert!(fish.head_yaw(0.4, 0.0).abs() <= fish.idle_amplitude + 1e-6);
/// # let _ = bones;
/// # Ok::<(), creature_gait::GaitError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct SwimParams {
    /// Head wiggles (and body waves) per second while swimming, `(0, 100]`. Default 1.2.
    pub frequency: f32,
    /// Head yaw amplitude while swimming, radians, `[0, π/2]`. Default 0.25.
    pub amplitude: f32,
    /// Waves along the body from head to tail (the phase lag of the tail behind the head, in
    /// cycles), `[0, 10]`. Default 1.
    pub wavelength: f32,
    /// The tail's amplitude as a multiple of the head's (linear along the body), `[0, 10]`.
    /// Default 1.5.
    pub tail_gain: f32,
    /// Idle sway amplitude, radians, `[0, π/2]`. Default 0.06.
    pub idle_amplitude: f32,
    /// Idle sways per second, `(0, 100]`. Default 0.3.
    pub idle_frequency: f32,
    /// Speed (m/s) from which the swimming motion is fully on (below it, it blends with the
    /// idle sway), `(0, 1000]`. Default 0.5.
    pub full_speed: f32,
}

impl SwimParams {
    /// The defaults listed on each field.
    pub const DEFAULT: Self = Self {
        frequency: 1.2,
        amplitude: 0.25,
        wavelength: 1.0,
        tail_gain: 1.5,
        idle_amplitude: 0.06,
        idle_frequency: 0.3,
        full_speed: 0.5,
    };

    /// Sets [`frequency`](Self::frequency) and [`amplitude`](Self::amplitude).
    #[must_use]
    pub const fn with_wiggle(mut self, frequency: f32, amplitude: f32) -> Self {
        self.frequency = frequency;
        self.amplitude = amplitude;
        self
    }
    /// Sets [`wavelength`](Self::wavelength) and [`tail_gain`](Self::tail_gain).
    #[must_use]
    pub const fn with_wave(mut self, wavelength: f32, tail_gain: f32) -> Self {
        self.wavelength = wavelength;
        self.tail_gain = tail_gain;
        self
    }
    /// Sets [`idle_frequency`](Self::idle_frequency) and
    /// [`idle_amplitude`](Self::idle_amplitude).
    #[must_use]
    pub const fn with_idle(mut self, frequency: f32, amplitude: f32) -> Self {
        self.idle_frequency = frequency;
        self.idle_amplitude = amplitude;
        self
    }
    /// Sets [`full_speed`](Self::full_speed).
    #[must_use]
    pub const fn with_full_speed(mut self, value: f32) -> Self {
        self.full_speed = value;
        self
    }

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`GaitError::OutOfRange`] naming the first bad field (NaN included).
    pub fn validate(&self) -> Result<(), GaitError> {
        let tiny = f32::MIN_POSITIVE;
        in_range(self.frequency, "swim frequency", tiny, 100.0)?;
        in_range(self.amplitude, "swim amplitude", 0.0, FRAC_PI_2)?;
        in_range(self.wavelength, "swim wavelength", 0.0, 10.0)?;
        in_range(self.tail_gain, "swim tail gain", 0.0, 10.0)?;
        in_range(self.idle_amplitude, "swim idle amplitude", 0.0, FRAC_PI_2)?;
        in_range(self.idle_frequency, "swim idle frequency", tiny, 100.0)?;
        in_range(self.full_speed, "swim full speed", tiny, 1000.0)?;
        Ok(())
    }

    /// The largest yaw any bone can reach: `max(amplitude · max(1, tail_gain),
    /// idle_amplitude)`.
    #[must_use]
    pub fn max_yaw(&self) -> f32 {
        (self.amplitude * self.tail_gain.max(1.0)).max(self.idle_amplitude)
    }

    /// How much of the swimming motion (vs the idle sway) is on at `speed`: `0..=1`.
    #[must_use]
    pub fn swim_weight(&self, speed: f32) -> f32 {
        finite_or_zero((abs_speed(speed) / self.full_speed).clamp(0.0, 1.0))
    }

    /// The yaw (radians, about the body's up axis, positive toward +X) of the bone at `u`
    /// along the body (0 head, 1 tail tip; clamped) at time `t` and `speed` (m/s). Within
    /// [`max_yaw`](Self::max_yaw); 0 for a non-finite result.
    #[must_use]
    pub fn bone_yaw(&self, t: f32, speed: f32, u: f32) -> f32 {
        let u = if u.is_nan() { 0.0 } else { u.clamp(0.0, 1.0) };
        let w = self.swim_weight(speed);
        let gain = 1.0 + (self.tail_gain - 1.0) * u;
        let swim = self.amplitude * gain * sin_turns(self.frequency * t - self.wavelength * u);
        let idle =
            self.idle_amplitude * sin_turns(self.idle_frequency * t - 0.5 * self.wavelength * u);
        finite_or_zero(w * swim + (1.0 - w) * idle)
    }

    /// The head's yaw: [`bone_yaw`](Self::bone_yaw) at `u = 0`. Moving the head is what the
    /// seed's damped body turns into a swim.
    #[must_use]
    pub fn head_yaw(&self, t: f32, speed: f32) -> f32 {
        self.bone_yaw(t, speed, 0.0)
    }

    /// Fills `yaws` with the yaw of each of `yaws.len()` bones spaced evenly from the head
    /// (`u = 0`) to the tail tip (`u = 1`); a single bone is the head.
    pub fn bone_yaws(&self, t: f32, speed: f32, yaws: &mut [f32]) {
        let last = yaws.len().saturating_sub(1).max(1) as f32;
        for (k, yaw) in yaws.iter_mut().enumerate() {
            *yaw = self.bone_yaw(t, speed, k as f32 / last);
        }
    }

    /// A bone's yaw as a rotation about the body's up axis (+Y).
    #[must_use]
    pub fn bone_rotation(&self, t: f32, speed: f32, u: f32) -> Quat {
        quat_yxz(self.bone_yaw(t, speed, u), 0.0, 0.0)
    }
}

impl Default for SwimParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

fn finite_or_zero(x: f32) -> f32 {
    if x.is_finite() { x } else { 0.0 }
}

/// `|speed|`, with NaN as 0 (a motion of unknown speed idles).
fn abs_speed(speed: f32) -> f32 {
    if speed.is_nan() {
        0.0
    } else {
        crate::math::abs(speed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid_and_setters_set() {
        assert!(FlapParams::FLAPPING.validate().is_ok());
        assert!(FlapParams::BUZZING.validate().is_ok());
        assert_eq!(FlapParams::default(), FlapParams::FLAPPING);
        assert!(SwimParams::default().validate().is_ok());
        let f = FlapParams::DEFAULT.with_frequency(4.0).with_bob(0.1);
        assert_eq!((f.frequency, f.bob), (4.0, 0.1));
        assert!(matches!(
            FlapParams::DEFAULT.with_amplitude(f32::NAN).validate(),
            Err(GaitError::OutOfRange {
                what: "flap amplitude",
                ..
            })
        ));
        assert!(SwimParams::DEFAULT.with_full_speed(0.0).validate().is_err());
    }

    #[test]
    fn wings_beat_up_and_down_and_buzz_faster() {
        let bird = FlapParams::FLAPPING;
        // A quarter period in: top of the beat.
        let top = bird.wing_angle(0.25 / bird.frequency);
        assert!((top - (bird.bias + bird.amplitude)).abs() < 1e-5);
        let bottom = bird.wing_angle(0.75 / bird.frequency);
        assert!((bottom - (bird.bias - bird.amplitude)).abs() < 1e-5);
        assert!(FlapParams::BUZZING.frequency > 5.0 * bird.frequency);
        // Both wings lift their tips: left (+X) and right (−X).
        let t = 0.25 / bird.frequency;
        let left_tip = bird.wing_rotation(t, Side::Left) * Vec3::X;
        let right_tip = bird.wing_rotation(t, Side::Right) * Vec3::NEG_X;
        assert!(left_tip.y > 0.5 && right_tip.y > 0.5);
        assert!((left_tip.x + right_tip.x).abs() < 1e-6);
    }

    #[test]
    fn flapping_bob_keeps_time_with_the_wings_and_buzzing_bob_fades_with_speed() {
        let bird = FlapParams::FLAPPING;
        let low = 0.75 / bird.frequency; // wings lowest
        assert!((bird.body_bob(low, 0.0) - bird.bob).abs() < 1e-6);
        assert_eq!(bird.body_bob(low, 0.0), bird.body_bob(low, 20.0));
        let fly = FlapParams::BUZZING;
        let t = 0.25 / fly.idle_frequency;
        assert!((fly.body_bob(t, 0.0) - fly.bob).abs() < 1e-6);
        let half = fly.body_bob(t, 0.5 * fly.bob_fade_speed);
        assert!((half - 0.5 * fly.bob).abs() < 1e-6);
        assert_eq!(fly.body_bob(t, 2.0 * fly.bob_fade_speed), 0.0);
        assert_eq!(fly.body_bob(f32::NAN, 0.0), 0.0);
        assert_eq!(fly.body_offset(t, 0.0).y, fly.body_bob(t, 0.0));
    }

    #[test]
    fn the_swim_wave_travels_from_head_to_tail_and_grows() {
        let fish = SwimParams::DEFAULT;
        let speed = fish.full_speed;
        // The tail repeats the head's motion `wavelength` cycles later (one cycle: same time).
        let lag = 0.3 / fish.frequency;
        let mid = fish.bone_yaw(lag, speed, 0.3 / fish.wavelength);
        let head_earlier = fish.head_yaw(0.0, speed);
        let gain = 1.0 + (fish.tail_gain - 1.0) * 0.3;
        assert!(
            (mid - gain * head_earlier).abs() < 1e-5,
            "{mid} vs {head_earlier}"
        );
        // The tail swings wider than the head.
        let peak = |u: f32| {
            (0..200)
                .map(|k| {
                    fish.bone_yaw(k as f32 / 200.0 / fish.frequency, speed, u)
                        .abs()
                })
                .fold(0.0, f32::max)
        };
        assert!(peak(1.0) > 1.4 * peak(0.0));
        assert!((peak(1.0) - fish.max_yaw()).abs() < 1e-2);
    }

    #[test]
    fn an_idle_swimmer_only_sways() {
        let fish = SwimParams::DEFAULT;
        for k in 0..100 {
            let t = k as f32 * 0.07;
            let y = fish.bone_yaw(t, 0.0, 0.5);
            assert!(y.abs() <= fish.idle_amplitude + 1e-6);
        }
        assert_eq!(fish.swim_weight(0.0), 0.0);
        assert_eq!(fish.swim_weight(-10.0), 1.0);
        let mut yaws = [1.0f32; 5];
        fish.bone_yaws(0.2, 0.0, &mut yaws);
        assert_eq!(yaws[0], fish.head_yaw(0.2, 0.0));
        assert_eq!(yaws[4], fish.bone_yaw(0.2, 0.0, 1.0));
        fish.bone_yaws(0.2, 0.0, &mut []);
        let q = fish.bone_rotation(0.2, 1.0, 0.5);
        assert!(q.is_normalized());
    }
}
