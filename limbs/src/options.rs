//! Tuning of the planner.

use crate::LimbsError;

/// How [`plan`](crate::plan) sizes, spaces and checks limbs.
///
/// Sizes marked "× body length" are fractions of [`Body::length`](crate::Body::length); ranges
/// are `[min, max]` and a value is drawn uniformly between them from the caller's generator.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct PlanOptions {
    /// Half the stretch of body a leg (or arm) sweeps while walking, per unit of its length:
    /// a leg of length `L` on a bone at `along = a` sweeps `[a - sweep·L, a + sweep·L]`. Two
    /// limbs on the same side never sweep overlapping stretches, so a long leg blocks more
    /// bones than a short one. Default `0.5` (a stride as long as the leg). Range `[0, 100]`.
    pub sweep: f32,
    /// Radius of a foot's contact patch per unit of leg length, used for the support polygon.
    /// Default `0.15`. Range `[0.001, 100]`.
    pub foot_radius: f32,
    /// Smallest stability margin accepted for a walker, × body length; the planner repairs
    /// any layout below it. Default `0.02`. Range `(0, 100]`.
    pub min_margin: f32,
    /// Shortest walking leg, × body length: bones lower than this are not given legs, and a
    /// body too low everywhere is lifted. Default `0.08`. Range `[0, 100]`.
    pub min_leg_length: f32,
    /// A walker whose length exceeds this many times its height (mean clearance) is "long":
    /// it gets as many leg pairs as fit. Default `3.0` (the seed's). Range `[0, 1e6]`.
    pub long_body_ratio: f32,
    /// A walker whose narrowest bone is at least this fraction of its widest is "nearly
    /// uniform": it gets as many leg pairs as fit. Default `0.75` (the seed's). Range `[0, 1]`.
    pub uniform_width_ratio: f32,
    /// A second leg pair goes on the next widest free bone when it is at least this fraction
    /// of the widest. Default `0.75` (the seed's). Range `[0, 1]`.
    pub second_pair_ratio: f32,
    /// A single pair on the widest bone is kept (a biped) when that bone is within this many
    /// bones of the middle. Default `2` (the seed's).
    pub central_bones: usize,
    /// Multiplies the chance of arms, which is the fraction of bones free between the head
    /// and the first bone a leg blocks. `0` never adds arms. Default `1.0`. Range `[0, 100]`.
    pub arm_chance: f32,
    /// Arm length range, × the height of its socket above the ground (arms never reach the
    /// ground). Default `[0.4, 0.8]`. Range within `[0, 1]`.
    pub arm_length: [f32; 2],
    /// Most leg pairs a flier draws (it draws 1 to this many). Default `8` (the seed's).
    pub max_flier_leg_pairs: usize,
    /// Flier leg length range, × body length. More pairs make short legs likelier. Default
    /// `[0.08, 0.4]`. Range within `[0, 100]`.
    pub flier_leg_length: [f32; 2],
    /// Buzzing (insect) wing size range, × body length. Default `[0.3, 0.6]`.
    pub buzzing_wing_size: [f32; 2],
    /// Flapping (bird) wing size range, × body length. Default `[0.5, 1.0]`.
    pub flapping_wing_size: [f32; 2],
    /// Per-axis stretch range for randomly scaled parts (buzzing wings, fins, tails): each of
    /// x, y, z is the size times a factor drawn from this range. Default `[0.7, 1.3]`.
    pub stretch: [f32; 2],
    /// Number of dorsal fins a swimmer draws. Default `[0, 3]`.
    pub dorsal_fins: [usize; 2],
    /// Number of pectoral fin pairs a swimmer draws. Default `[0, 2]`.
    pub pectoral_pairs: [usize; 2],
    /// Fin size range, × body length. Default `[0.1, 0.25]`.
    pub fin_size: [f32; 2],
    /// Tail size range, × body length. Default `[0.2, 0.45]`.
    pub tail_size: [f32; 2],
}

impl PlanOptions {
    /// The defaults documented on each field.
    pub const DEFAULT: Self = Self {
        sweep: 0.5,
        foot_radius: 0.15,
        min_margin: 0.02,
        min_leg_length: 0.08,
        long_body_ratio: 3.0,
        uniform_width_ratio: 0.75,
        second_pair_ratio: 0.75,
        central_bones: 2,
        arm_chance: 1.0,
        arm_length: [0.4, 0.8],
        max_flier_leg_pairs: 8,
        flier_leg_length: [0.08, 0.4],
        buzzing_wing_size: [0.3, 0.6],
        flapping_wing_size: [0.5, 1.0],
        stretch: [0.7, 1.3],
        dorsal_fins: [0, 3],
        pectoral_pairs: [0, 2],
        fin_size: [0.1, 0.25],
        tail_size: [0.2, 0.45],
    };

    /// Sets [`sweep`](Self::sweep).
    #[must_use]
    pub const fn with_sweep(mut self, sweep: f32) -> Self {
        self.sweep = sweep;
        self
    }

    /// Sets [`foot_radius`](Self::foot_radius).
    #[must_use]
    pub const fn with_foot_radius(mut self, foot_radius: f32) -> Self {
        self.foot_radius = foot_radius;
        self
    }

    /// Sets [`min_margin`](Self::min_margin).
    #[must_use]
    pub const fn with_min_margin(mut self, min_margin: f32) -> Self {
        self.min_margin = min_margin;
        self
    }

    /// Sets [`min_leg_length`](Self::min_leg_length).
    #[must_use]
    pub const fn with_min_leg_length(mut self, min_leg_length: f32) -> Self {
        self.min_leg_length = min_leg_length;
        self
    }

    /// Sets [`long_body_ratio`](Self::long_body_ratio).
    #[must_use]
    pub const fn with_long_body_ratio(mut self, ratio: f32) -> Self {
        self.long_body_ratio = ratio;
        self
    }

    /// Sets [`uniform_width_ratio`](Self::uniform_width_ratio).
    #[must_use]
    pub const fn with_uniform_width_ratio(mut self, ratio: f32) -> Self {
        self.uniform_width_ratio = ratio;
        self
    }

    /// Sets [`second_pair_ratio`](Self::second_pair_ratio).
    #[must_use]
    pub const fn with_second_pair_ratio(mut self, ratio: f32) -> Self {
        self.second_pair_ratio = ratio;
        self
    }

    /// Sets [`central_bones`](Self::central_bones).
    #[must_use]
    pub const fn with_central_bones(mut self, bones: usize) -> Self {
        self.central_bones = bones;
        self
    }

    /// Sets [`arm_chance`](Self::arm_chance).
    #[must_use]
    pub const fn with_arm_chance(mut self, chance: f32) -> Self {
        self.arm_chance = chance;
        self
    }

    /// Sets [`arm_length`](Self::arm_length).
    #[must_use]
    pub const fn with_arm_length(mut self, range: [f32; 2]) -> Self {
        self.arm_length = range;
        self
    }

    /// Sets [`max_flier_leg_pairs`](Self::max_flier_leg_pairs).
    #[must_use]
    pub const fn with_max_flier_leg_pairs(mut self, pairs: usize) -> Self {
        self.max_flier_leg_pairs = pairs;
        self
    }

    /// Sets [`flier_leg_length`](Self::flier_leg_length).
    #[must_use]
    pub const fn with_flier_leg_length(mut self, range: [f32; 2]) -> Self {
        self.flier_leg_length = range;
        self
    }

    /// Sets [`buzzing_wing_size`](Self::buzzing_wing_size).
    #[must_use]
    pub const fn with_buzzing_wing_size(mut self, range: [f32; 2]) -> Self {
        self.buzzing_wing_size = range;
        self
    }

    /// Sets [`flapping_wing_size`](Self::flapping_wing_size).
    #[must_use]
    pub const fn with_flapping_wing_size(mut self, range: [f32; 2]) -> Self {
        self.flapping_wing_size = range;
        self
    }

    /// Sets [`stretch`](Self::stretch).
    #[must_use]
    pub const fn with_stretch(mut self, range: [f32; 2]) -> Self {
        self.stretch = range;
        self
    }

    /// Sets [`dorsal_fins`](Self::dorsal_fins).
    #[must_use]
    pub const fn with_dorsal_fins(mut self, range: [usize; 2]) -> Self {
        self.dorsal_fins = range;
        self
    }

    /// Sets [`pectoral_pairs`](Self::pectoral_pairs).
    #[must_use]
    pub const fn with_pectoral_pairs(mut self, range: [usize; 2]) -> Self {
        self.pectoral_pairs = range;
        self
    }

    /// Sets [`fin_size`](Self::fin_size).
    #[must_use]
    pub const fn with_fin_size(mut self, range: [f32; 2]) -> Self {
        self.fin_size = range;
        self
    }

    /// Sets [`tail_size`](Self::tail_size).
    #[must_use]
    pub const fn with_tail_size(mut self, range: [f32; 2]) -> Self {
        self.tail_size = range;
        self
    }

    /// Checks every field against its documented range.
    ///
    /// # Errors
    ///
    /// [`LimbsError::InvalidOption`] naming the first bad field.
    pub fn validate(&self) -> Result<(), LimbsError> {
        scalar("sweep", self.sweep, 0.0, 100.0, true)?;
        scalar("foot_radius", self.foot_radius, 0.001, 100.0, true)?;
        scalar("min_margin", self.min_margin, 0.0, 100.0, false)?;
        scalar("min_leg_length", self.min_leg_length, 0.0, 100.0, true)?;
        scalar("long_body_ratio", self.long_body_ratio, 0.0, 1.0e6, true)?;
        scalar(
            "uniform_width_ratio",
            self.uniform_width_ratio,
            0.0,
            1.0,
            true,
        )?;
        scalar("second_pair_ratio", self.second_pair_ratio, 0.0, 1.0, true)?;
        scalar("arm_chance", self.arm_chance, 0.0, 100.0, true)?;
        range("arm_length", self.arm_length, 0.0, 1.0)?;
        range("flier_leg_length", self.flier_leg_length, 0.0, 100.0)?;
        range("buzzing_wing_size", self.buzzing_wing_size, 0.0, 100.0)?;
        range("flapping_wing_size", self.flapping_wing_size, 0.0, 100.0)?;
        range("stretch", self.stretch, 0.0, 100.0)?;
        range("fin_size", self.fin_size, 0.0, 100.0)?;
        range("tail_size", self.tail_size, 0.0, 100.0)?;
        if self.dorsal_fins[0] > self.dorsal_fins[1] || self.dorsal_fins[1] > 64 {
            return Err(LimbsError::InvalidOption {
                name: "dorsal_fins",
                value: self.dorsal_fins[0] as f32,
            });
        }
        if self.pectoral_pairs[0] > self.pectoral_pairs[1] || self.pectoral_pairs[1] > 64 {
            return Err(LimbsError::InvalidOption {
                name: "pectoral_pairs",
                value: self.pectoral_pairs[0] as f32,
            });
        }
        if self.max_flier_leg_pairs > 64 {
            return Err(LimbsError::InvalidOption {
                name: "max_flier_leg_pairs",
                value: self.max_flier_leg_pairs as f32,
            });
        }
        Ok(())
    }
}

impl Default for PlanOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// `value` finite and in `[min, max]` (or `(min, max]` when `zero_ok` is false).
fn scalar(
    name: &'static str,
    value: f32,
    min: f32,
    max: f32,
    zero_ok: bool,
) -> Result<(), LimbsError> {
    let low_ok = if zero_ok { value >= min } else { value > min };
    if value.is_finite() && low_ok && value <= max {
        Ok(())
    } else {
        Err(LimbsError::InvalidOption { name, value })
    }
}

fn range(name: &'static str, [lo, hi]: [f32; 2], min: f32, max: f32) -> Result<(), LimbsError> {
    scalar(name, lo, min, max, true)?;
    scalar(name, hi, min, max, true)?;
    if lo > hi {
        return Err(LimbsError::InvalidOption { name, value: lo });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_setters_set() {
        assert_eq!(PlanOptions::default().validate(), Ok(()));
        let o = PlanOptions::DEFAULT
            .with_sweep(0.3)
            .with_dorsal_fins([1, 2]);
        assert_eq!(o.sweep, 0.3);
        assert_eq!(o.dorsal_fins, [1, 2]);
    }

    #[test]
    fn bad_options_are_named() {
        let o = PlanOptions::DEFAULT.with_foot_radius(0.0);
        assert!(matches!(
            o.validate(),
            Err(LimbsError::InvalidOption {
                name: "foot_radius",
                ..
            })
        ));
        let o = PlanOptions::DEFAULT.with_fin_size([0.5, 0.1]);
        assert!(matches!(
            o.validate(),
            Err(LimbsError::InvalidOption {
                name: "fin_size",
                ..
            })
        ));
        let o = PlanOptions::DEFAULT.with_sweep(f32::NAN);
        assert!(o.validate().is_err());
    }
}
