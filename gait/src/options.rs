//! [`GaitOptions`]: every tunable of the controller, with documented defaults.

use glam::Vec3;

use crate::curve::{HeightCurve, ReachCurve};
use crate::error::{GaitError, finite3, in_range};
use crate::gaits::GaitSpeeds;

/// Tunables of a [`Controller`](crate::Controller). Lengths marked "× size" are fractions of
/// each leg's [`size`](crate::Leg::size) (or, for body-wide values, of the mean leg size).
///
/// ```
/// use creature_gait::{GaitOptions, HeightCurve};
///
/// let options = GaitOptions::DEFAULT
///     .with_height_curve(HeightCurve::Parabola)
///     .with_step_height(0.2)
///     .with_overshoot(0.6);
/// options.validate()?;
/// # Ok::<(), creature_gait::GaitError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct GaitOptions {
    /// Allowed stray of a planted foot by direction, × size. Default [`ReachCurve::DEFAULT`]
    /// (0.45 back, 0.3 forward).
    pub reach: ReachCurve,
    /// Lift profile of a step. Default [`HeightCurve::Sine`].
    pub height_curve: HeightCurve,
    /// Peak lift of a step, × size, in `[0, 2]`. Default 0.15.
    pub step_height: f32,
    /// Overshoot ahead of the rest position along the motion, as a fraction of the reach in
    /// that direction, in `[0, 1]`. Default 0.5.
    pub overshoot: f32,
    /// Speed (× size per second) at which the overshoot reaches its full length; slower motion
    /// overshoots proportionally less. `(0, 100]`. Default 1.
    pub overshoot_speed: f32,
    /// The creature's speed multiplier (3D seed): above 1 it lengthens and raises steps for a
    /// running gait; at or below 1 it changes nothing. `(0, 10]`. Default 1.
    pub speed_multiplier: f32,
    /// Angle (radians) a planted foot may turn about the body's up axis, seen from the body's
    /// origin, away from its rest direction before it steps (turning in place), `(0, π]`.
    /// Default 0.5.
    pub max_turn_angle: f32,
    /// A foot further than this many times its reach steps whatever its group (escape
    /// distance), `[1, 10]`. Default 1.5.
    pub escape_factor: f32,
    /// When a group takes its turn, its other legs that trail behind their rest position
    /// (against the motion) by more than this fraction of their reach step with it, `[0, 1]` (1 = only legs past their reach). Default 0.5.
    pub group_join: f32,
    /// Progress per second of a step when the body does not move (the seed's fixed rate),
    /// `(0, 1000]`. Default 4 (a quarter-second step).
    pub settle_rate: f32,
    /// When the body is still, a planted foot further than this (× size) from its rest
    /// position steps back to it, restoring the neutral pose, `[0, 10]`. Default 0.1.
    pub settle_distance: f32,
    /// Speed (× mean size per second) under which the body counts as still, `[0, 10]`.
    /// Default 0.02.
    pub still_speed: f32,
    /// The ground ray starts this far above the rest position (× size), `(0, 10]`. Default 1.
    pub cast_height: f32,
    /// The ground ray reaches this far below the rest position (× size), `(0, 10]`. Default 1.
    pub cast_depth: f32,
    /// Body bob as a fraction of the feet's average height offset, `[0, 2]`. Default 0.5.
    pub bob_gain: f32,
    /// Largest body bob, × mean size, `[0, 2]`. Default 0.2.
    pub bob_limit: f32,
    /// Body sway/roll/pitch as a fraction of the feet's average angle offsets, `[0, 2]`.
    /// Default 0.5.
    pub sway_gain: f32,
    /// Largest sway, roll or pitch angle, radians, `[0, π/2]`. Default 0.3. The sway is held
    /// further to what keeps every walking foot at rest on its side of the body's midline: at
    /// most the narrowest foot's distance from it over the farthest foot's distance ahead or
    /// behind the body's origin.
    pub sway_limit: f32,
    /// Time constant of the bob and sway damping, seconds, `[0, 10]` (0 = no damping).
    /// Default 0.1.
    pub reaction_time: f32,
    /// Hip roll per radian of height slope between a foot and its partner, `[0, 4]`.
    /// Default 1.
    pub hip_roll_gain: f32,
    /// Largest hip roll, radians, `[0, π/2]`. Default 0.35.
    pub hip_roll_limit: f32,
    /// Seconds of yaw rate the head looks ahead into a turn, `[0, 10]`. Default 0.4.
    pub look_ahead: f32,
    /// Largest head yaw and pitch, radians, `[0, π]`. Default 1.
    pub look_limit: f32,
    /// Time constant of the head's smoothing, seconds, `[0, 10]`. Default 0.15.
    pub look_time: f32,
    /// Upward pitch of the head's gaze (so it does not stare at the ground), radians,
    /// `[−π/2, π/2]`. Default 0.1.
    pub look_pitch: f32,
    /// Idle breathing: body rise amplitude, × mean size, `[0, 1]`. Default 0.01.
    pub breathe_amplitude: f32,
    /// Idle breathing (and arm idle) rate, cycles per second, `[0, 100]`. Default 0.25.
    pub breathe_rate: f32,
    /// Idle motion of arms' hands, × size, `[0, 1]`. Default 0.03.
    pub arm_idle_amplitude: f32,
    /// Seconds a [`Controller::blend_to`](crate::Controller::blend_to) ramp takes from 0 to 1,
    /// `[0, 100]`. Default 0.3.
    pub blend_time: f32,
    /// Centre of mass in body space, for the stability margin. Default zero.
    pub centre_of_mass: Vec3,
    /// The fraction of a step's swing, at its start and at its end, in which the foot moves
    /// only up (lift-off) or down (landing) while it is near the ground, `[0, 0.45]`: feet that
    /// neither scuff nor skid. The target stops following the motion when the landing starts.
    /// Default 0.15.
    pub plant_fraction: f32,
    /// A planted leg steps at once (out of its group's turn) when its foot comes this close to
    /// the body's midline, as a fraction of its rest position's distance from it, `[0, 1]`:
    /// feet never cross to the other side when a long body turns in place. Step targets stay no
    /// closer to the midline than halfway from the margin to the rest position. Default 0.5.
    pub midline_margin: f32,
    /// How far apart, along the body, the feet of two walking legs on the same side land, ×
    /// the mean of the two legs' sizes, `[0, 1]`: a step's target stays that far behind the
    /// foot (or the step target) of a leg whose rest position is ahead, and ahead of one whose
    /// rest position is behind, so that a rear foot does not land on or past a front foot that
    /// trails, and the legs never pass through each other. At most half the two rest
    /// positions' distance along the body, and a target is never moved further than its reach
    /// from the rest position. A planted foot that trails to within three quarters of that
    /// of the foot behind it (or of where that lands) steps at once, out of turn, if another
    /// foot stays down: a long front leg can stride back past where a short hind leg can
    /// land. 0 turns it off. Default 0.25.
    pub foot_spacing: f32,
    /// The shortest a step's swing takes (seconds), `(0, 10]`; a leg of size `s` under 1 takes
    /// `min_swing_time × √s` at least (a pendulum's time: a small leg swings faster). However fast its rest position moves (the outer feet of a long body turning in
    /// place), a foot is in the air that long, so it visibly lifts and lands rather than jump
    /// along the ground in an update or two. Default 0.1.
    pub min_swing_time: f32,
    /// Gaits by speed: `Some` to change between walk, trot and run at these speeds (see
    /// [`Gait`](crate::Gait)), starting (and [reset](crate::Controller::reset)) in the gait
    /// they give standing still; `None` (default) to walk in one pattern at every speed (a
    /// hopper, see [`hop`](Self::hop), to hop at every speed).
    pub gaits: Option<GaitSpeeds>,
    /// Hopping: `true` to hop instead of trotting and running, every walking leg in one group
    /// (both feet of a biped together, as a kangaroo or a sparrow), a flight phase each hop
    /// (see [`Gait::Hop`](crate::Gait::Hop)). With [`gaits`](Self::gaits) set, a hopper walks
    /// below the trot's speed and hops from there; without, it hops at every speed. Legs whose
    /// [`group`](crate::Leg::group) the caller set keep their groups. Default `false`.
    pub hop: bool,
}

impl GaitOptions {
    /// The defaults listed on each field.
    pub const DEFAULT: Self = Self {
        reach: ReachCurve::DEFAULT,
        height_curve: HeightCurve::DEFAULT,
        step_height: 0.15,
        overshoot: 0.5,
        overshoot_speed: 1.0,
        speed_multiplier: 1.0,
        max_turn_angle: 0.5,
        escape_factor: 1.5,
        group_join: 0.5,
        settle_rate: 4.0,
        settle_distance: 0.1,
        still_speed: 0.02,
        cast_height: 1.0,
        cast_depth: 1.0,
        bob_gain: 0.5,
        bob_limit: 0.2,
        sway_gain: 0.5,
        sway_limit: 0.3,
        reaction_time: 0.1,
        hip_roll_gain: 1.0,
        hip_roll_limit: 0.35,
        look_ahead: 0.4,
        look_limit: 1.0,
        look_time: 0.15,
        look_pitch: 0.1,
        breathe_amplitude: 0.01,
        breathe_rate: 0.25,
        arm_idle_amplitude: 0.03,
        blend_time: 0.3,
        centre_of_mass: Vec3::ZERO,
        plant_fraction: 0.15,
        midline_margin: 0.5,
        foot_spacing: 0.25,
        min_swing_time: 0.1,
        gaits: None,
        hop: false,
    };

    /// Sets [`gaits`](Self::gaits): change gait by speed at `speeds`.
    #[must_use]
    pub const fn with_gaits(mut self, speeds: GaitSpeeds) -> Self {
        self.gaits = Some(speeds);
        self
    }

    /// Sets [`hop`](Self::hop): hop instead of trotting and running (or at every speed
    /// without [`gaits`](Self::gaits)).
    #[must_use]
    pub const fn with_hop(mut self, hop: bool) -> Self {
        self.hop = hop;
        self
    }

    /// Sets [`reach`](Self::reach).
    #[must_use]
    pub const fn with_reach(mut self, reach: ReachCurve) -> Self {
        self.reach = reach;
        self
    }
    /// Sets [`height_curve`](Self::height_curve).
    #[must_use]
    pub const fn with_height_curve(mut self, curve: HeightCurve) -> Self {
        self.height_curve = curve;
        self
    }
    /// Sets [`step_height`](Self::step_height).
    #[must_use]
    pub const fn with_step_height(mut self, value: f32) -> Self {
        self.step_height = value;
        self
    }
    /// Sets [`overshoot`](Self::overshoot).
    #[must_use]
    pub const fn with_overshoot(mut self, value: f32) -> Self {
        self.overshoot = value;
        self
    }
    /// Sets [`overshoot_speed`](Self::overshoot_speed).
    #[must_use]
    pub const fn with_overshoot_speed(mut self, value: f32) -> Self {
        self.overshoot_speed = value;
        self
    }
    /// Sets [`speed_multiplier`](Self::speed_multiplier).
    #[must_use]
    pub const fn with_speed_multiplier(mut self, value: f32) -> Self {
        self.speed_multiplier = value;
        self
    }
    /// Sets [`plant_fraction`](Self::plant_fraction).
    #[must_use]
    pub const fn with_plant_fraction(mut self, value: f32) -> Self {
        self.plant_fraction = value;
        self
    }

    /// Sets [`midline_margin`](Self::midline_margin).
    #[must_use]
    pub const fn with_midline_margin(mut self, value: f32) -> Self {
        self.midline_margin = value;
        self
    }

    /// Sets [`foot_spacing`](Self::foot_spacing).
    #[must_use]
    pub const fn with_foot_spacing(mut self, value: f32) -> Self {
        self.foot_spacing = value;
        self
    }

    /// Sets [`min_swing_time`](Self::min_swing_time).
    #[must_use]
    pub const fn with_min_swing_time(mut self, value: f32) -> Self {
        self.min_swing_time = value;
        self
    }

    /// Sets [`max_turn_angle`](Self::max_turn_angle).
    #[must_use]
    pub const fn with_max_turn_angle(mut self, value: f32) -> Self {
        self.max_turn_angle = value;
        self
    }
    /// Sets [`escape_factor`](Self::escape_factor).
    #[must_use]
    pub const fn with_escape_factor(mut self, value: f32) -> Self {
        self.escape_factor = value;
        self
    }
    /// Sets [`group_join`](Self::group_join).
    #[must_use]
    pub const fn with_group_join(mut self, value: f32) -> Self {
        self.group_join = value;
        self
    }
    /// Sets [`settle_rate`](Self::settle_rate).
    #[must_use]
    pub const fn with_settle_rate(mut self, value: f32) -> Self {
        self.settle_rate = value;
        self
    }
    /// Sets [`settle_distance`](Self::settle_distance).
    #[must_use]
    pub const fn with_settle_distance(mut self, value: f32) -> Self {
        self.settle_distance = value;
        self
    }
    /// Sets [`still_speed`](Self::still_speed).
    #[must_use]
    pub const fn with_still_speed(mut self, value: f32) -> Self {
        self.still_speed = value;
        self
    }
    /// Sets [`cast_height`](Self::cast_height) and [`cast_depth`](Self::cast_depth).
    #[must_use]
    pub const fn with_cast(mut self, height: f32, depth: f32) -> Self {
        self.cast_height = height;
        self.cast_depth = depth;
        self
    }
    /// Sets [`bob_gain`](Self::bob_gain) and [`bob_limit`](Self::bob_limit).
    #[must_use]
    pub const fn with_bob(mut self, gain: f32, limit: f32) -> Self {
        self.bob_gain = gain;
        self.bob_limit = limit;
        self
    }
    /// Sets [`sway_gain`](Self::sway_gain) and [`sway_limit`](Self::sway_limit).
    #[must_use]
    pub const fn with_sway(mut self, gain: f32, limit: f32) -> Self {
        self.sway_gain = gain;
        self.sway_limit = limit;
        self
    }
    /// Sets [`reaction_time`](Self::reaction_time).
    #[must_use]
    pub const fn with_reaction_time(mut self, value: f32) -> Self {
        self.reaction_time = value;
        self
    }
    /// Sets [`hip_roll_gain`](Self::hip_roll_gain) and [`hip_roll_limit`](Self::hip_roll_limit).
    #[must_use]
    pub const fn with_hip_roll(mut self, gain: f32, limit: f32) -> Self {
        self.hip_roll_gain = gain;
        self.hip_roll_limit = limit;
        self
    }
    /// Sets the head's [`look_ahead`](Self::look_ahead), [`look_limit`](Self::look_limit) and
    /// [`look_time`](Self::look_time).
    #[must_use]
    pub const fn with_look(mut self, ahead: f32, limit: f32, time: f32) -> Self {
        self.look_ahead = ahead;
        self.look_limit = limit;
        self.look_time = time;
        self
    }
    /// Sets [`look_pitch`](Self::look_pitch).
    #[must_use]
    pub const fn with_look_pitch(mut self, value: f32) -> Self {
        self.look_pitch = value;
        self
    }
    /// Sets [`breathe_amplitude`](Self::breathe_amplitude) and
    /// [`breathe_rate`](Self::breathe_rate).
    #[must_use]
    pub const fn with_breathing(mut self, amplitude: f32, rate: f32) -> Self {
        self.breathe_amplitude = amplitude;
        self.breathe_rate = rate;
        self
    }
    /// Sets [`arm_idle_amplitude`](Self::arm_idle_amplitude).
    #[must_use]
    pub const fn with_arm_idle_amplitude(mut self, value: f32) -> Self {
        self.arm_idle_amplitude = value;
        self
    }
    /// Sets [`blend_time`](Self::blend_time).
    #[must_use]
    pub const fn with_blend_time(mut self, value: f32) -> Self {
        self.blend_time = value;
        self
    }
    /// Sets [`centre_of_mass`](Self::centre_of_mass).
    #[must_use]
    pub const fn with_centre_of_mass(mut self, value: Vec3) -> Self {
        self.centre_of_mass = value;
        self
    }

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`GaitError::OutOfRange`] naming the first bad field, or [`GaitError::NonFinite`] for
    /// a non-finite centre of mass.
    pub fn validate(&self) -> Result<(), GaitError> {
        use core::f32::consts::{FRAC_PI_2, PI};
        let tiny = f32::MIN_POSITIVE;
        in_range(self.step_height, "step height", 0.0, 2.0)?;
        in_range(self.plant_fraction, "plant fraction", 0.0, 0.45)?;
        in_range(self.midline_margin, "midline margin", 0.0, 1.0)?;
        in_range(self.foot_spacing, "foot spacing", 0.0, 1.0)?;
        in_range(self.min_swing_time, "min swing time", tiny, 10.0)?;
        in_range(self.overshoot, "overshoot", 0.0, 1.0)?;
        in_range(self.overshoot_speed, "overshoot speed", tiny, 100.0)?;
        in_range(self.speed_multiplier, "speed multiplier", tiny, 10.0)?;
        in_range(self.max_turn_angle, "max turn angle", tiny, PI)?;
        in_range(self.escape_factor, "escape factor", 1.0, 10.0)?;
        in_range(self.group_join, "group join", 0.0, 1.0)?;
        in_range(self.settle_rate, "settle rate", tiny, 1000.0)?;
        in_range(self.settle_distance, "settle distance", 0.0, 10.0)?;
        in_range(self.still_speed, "still speed", 0.0, 10.0)?;
        in_range(self.cast_height, "cast height", tiny, 10.0)?;
        in_range(self.cast_depth, "cast depth", tiny, 10.0)?;
        in_range(self.bob_gain, "bob gain", 0.0, 2.0)?;
        in_range(self.bob_limit, "bob limit", 0.0, 2.0)?;
        in_range(self.sway_gain, "sway gain", 0.0, 2.0)?;
        in_range(self.sway_limit, "sway limit", 0.0, FRAC_PI_2)?;
        in_range(self.reaction_time, "reaction time", 0.0, 10.0)?;
        in_range(self.hip_roll_gain, "hip roll gain", 0.0, 4.0)?;
        in_range(self.hip_roll_limit, "hip roll limit", 0.0, FRAC_PI_2)?;
        in_range(self.look_ahead, "look ahead", 0.0, 10.0)?;
        in_range(self.look_limit, "look limit", 0.0, PI)?;
        in_range(self.look_time, "look time", 0.0, 10.0)?;
        in_range(self.look_pitch, "look pitch", -FRAC_PI_2, FRAC_PI_2)?;
        in_range(self.breathe_amplitude, "breathe amplitude", 0.0, 1.0)?;
        in_range(self.breathe_rate, "breathe rate", 0.0, 100.0)?;
        in_range(self.arm_idle_amplitude, "arm idle amplitude", 0.0, 1.0)?;
        in_range(self.blend_time, "blend time", 0.0, 100.0)?;
        finite3(self.centre_of_mass, "centre of mass", 0)?;
        if let Some(speeds) = &self.gaits {
            speeds.validate()?;
        }
        Ok(())
    }
}

impl Default for GaitOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_setters_set() {
        assert!(GaitOptions::DEFAULT.validate().is_ok());
        assert_eq!(GaitOptions::default(), GaitOptions::DEFAULT);
        let o = GaitOptions::DEFAULT
            .with_bob(0.3, 0.1)
            .with_escape_factor(2.0);
        assert_eq!((o.bob_gain, o.bob_limit, o.escape_factor), (0.3, 0.1, 2.0));
    }

    #[test]
    fn out_of_range_fields_are_named() {
        let e = GaitOptions::DEFAULT.with_overshoot(f32::NAN).validate();
        assert!(matches!(
            e,
            Err(GaitError::OutOfRange {
                what: "overshoot",
                ..
            })
        ));
        let e = GaitOptions::DEFAULT.with_escape_factor(0.5).validate();
        assert!(matches!(
            e,
            Err(GaitError::OutOfRange {
                what: "escape factor",
                ..
            })
        ));
        let e = GaitOptions::DEFAULT
            .with_centre_of_mass(Vec3::INFINITY)
            .validate();
        assert!(matches!(e, Err(GaitError::NonFinite { .. })));
    }
}
