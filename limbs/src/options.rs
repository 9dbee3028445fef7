//! Tuning of the planner.

use crate::{LimbsError, MAX_BONES};

/// How [`plan`](crate::plan) sizes, spaces and checks limbs.
///
/// Sizes marked "× body length" are fractions of [`Body::length`](crate::Body::length); a
/// `[min, max]` pair is a range a value is drawn from uniformly with the caller's generator, and
/// needs `min <= max`. Every field documents its valid range; [`validate`](Self::validate) (and
/// so [`plan`](crate::plan)) rejects anything outside it, and NaN or infinity anywhere, with
/// [`LimbsError::InvalidOption`](crate::LimbsError::InvalidOption).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct PlanOptions {
    /// Half the stretch of body a leg (or arm) sweeps while walking, per unit of its length:
    /// a leg of length `L` on a bone at `along = a` sweeps `[a - sweep·L, a + sweep·L]`. Two
    /// limbs on the same side never sweep overlapping stretches, so a long leg blocks more
    /// bones than a short one. Default `0.5` (a stride as long as the leg). Range `[0, 100]`.
    pub sweep: f32,
    /// Radius of each foot's contact patch, × body length: a walker's support region is the
    /// convex hull of its feet grown by this much. It does not depend on the legs' size, so
    /// long legs do not buy stability: a walker stands only when its centre of mass really lies
    /// over its feet. A single pair (a biped) stands only when the centre of mass lies within
    /// `foot_radius - min_margin` (× body length) of the segment between its feet, that is
    /// when its legs are under the middle of its mass. Default `0.05`. Range `[0, 0.25]`.
    pub foot_radius: f32,
    /// Smallest stability margin accepted for a walker, × body length; the planner repairs
    /// any layout below it, or returns
    /// [`LimbsError::NoStableLayout`](crate::LimbsError::NoStableLayout) when no layout of its
    /// legs reaches it. Default `0.02`. Range `(0, 1]`.
    pub min_margin: f32,
    /// Shortest walking leg, × body length: bones lower than this are not given legs, and a
    /// body too low everywhere is lifted until its highest bone's legs are this long. Default
    /// `0.08`. Range `[0.001, 100]`.
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
    /// A single pair on the widest bone is tried as a biped (before any balancing pair) when
    /// that bone is within this many bones of the middle; it is kept only if it stands (see
    /// [`foot_radius`](Self::foot_radius)). Default `2` (the seed's). Range
    /// `[0, MAX_BONES]` ([`MAX_BONES`](crate::MAX_BONES) = 64).
    pub central_bones: usize,
    /// Multiplies the chance of arms, which is the fraction of bones free between the head
    /// and the first bone a leg blocks. `0` never adds arms. Default `1.0`. Range `[0, 100]`.
    pub arm_chance: f32,
    /// Arm length range, × the height of its socket above the ground (arms never reach the
    /// ground). Default `[0.4, 0.8]`. Range within `[0, 1]`.
    pub arm_length: [f32; 2],
    /// Shortest arm, × body length: drawn arms shorter than this (a low socket, a small draw,
    /// or too little room beside the legs) are left out and reported as
    /// [`Repair::DroppedArms`](crate::Repair::DroppedArms). Default `0.05`. Range
    /// `[0.001, 100]`.
    pub min_arm_length: f32,
    /// Most leg pairs a flier draws (it draws 1 to this many; `0` gives fliers no legs).
    /// Default `8` (the seed's). Range `[0, 64]`.
    pub max_flier_leg_pairs: usize,
    /// Flier leg length range, × body length. More pairs make short legs likelier. Default
    /// `[0.08, 0.4]`. Range within `[0.001, 100]`.
    pub flier_leg_length: [f32; 2],
    /// Buzzing (insect) wing size range, × body length. Default `[0.3, 0.6]`. Range within
    /// `[0.001, 100]`.
    pub buzzing_wing_size: [f32; 2],
    /// Flapping (bird) wing size range, × body length. Default `[0.5, 1.0]`. Range within
    /// `[0.001, 100]`.
    pub flapping_wing_size: [f32; 2],
    /// Per-axis stretch range for randomly scaled parts (buzzing wings, fins, tails): each of
    /// x, y, z is the size times a factor drawn from this range. Default `[0.7, 1.3]`. Range
    /// within `[0.001, 100]`.
    pub stretch: [f32; 2],
    /// Number of dorsal fins a swimmer draws. Default `[0, 3]`. Range within `[0, 64]`.
    pub dorsal_fins: [usize; 2],
    /// Number of pectoral fin pairs a swimmer draws. Default `[0, 2]`. Range within `[0, 64]`.
    pub pectoral_pairs: [usize; 2],
    /// Fin size range, × body length. Default `[0.1, 0.25]`. Range within `[0.001, 100]`.
    pub fin_size: [f32; 2],
    /// Tail size range, × body length. Default `[0.2, 0.45]`. Range within `[0.001, 100]`.
    pub tail_size: [f32; 2],
}

impl PlanOptions {
    /// The defaults documented on each field.
    pub const DEFAULT: Self = Self {
        sweep: 0.5,
        foot_radius: 0.05,
        min_margin: 0.02,
        min_leg_length: 0.08,
        long_body_ratio: 3.0,
        uniform_width_ratio: 0.75,
        second_pair_ratio: 0.75,
        central_bones: 2,
        arm_chance: 1.0,
        arm_length: [0.4, 0.8],
        min_arm_length: 0.05,
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

    /// Sets [`min_arm_length`](Self::min_arm_length).
    #[must_use]
    pub const fn with_min_arm_length(mut self, min_arm_length: f32) -> Self {
        self.min_arm_length = min_arm_length;
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
        scalar("foot_radius", self.foot_radius, 0.0, 0.25, true)?;
        scalar("min_margin", self.min_margin, 0.0, 1.0, false)?;
        scalar("min_leg_length", self.min_leg_length, MIN_SIZE, 100.0, true)?;
        scalar("long_body_ratio", self.long_body_ratio, 0.0, 1.0e6, true)?;
        scalar(
            "uniform_width_ratio",
            self.uniform_width_ratio,
            0.0,
            1.0,
            true,
        )?;
        scalar("second_pair_ratio", self.second_pair_ratio, 0.0, 1.0, true)?;
        count("central_bones", self.central_bones, MAX_BONES)?;
        scalar("arm_chance", self.arm_chance, 0.0, 100.0, true)?;
        range("arm_length", self.arm_length, 0.0, 1.0)?;
        scalar("min_arm_length", self.min_arm_length, MIN_SIZE, 100.0, true)?;
        count("max_flier_leg_pairs", self.max_flier_leg_pairs, MAX_COUNT)?;
        range("flier_leg_length", self.flier_leg_length, MIN_SIZE, 100.0)?;
        range("buzzing_wing_size", self.buzzing_wing_size, MIN_SIZE, 100.0)?;
        range(
            "flapping_wing_size",
            self.flapping_wing_size,
            MIN_SIZE,
            100.0,
        )?;
        range("stretch", self.stretch, MIN_SIZE, 100.0)?;
        count_range("dorsal_fins", self.dorsal_fins)?;
        count_range("pectoral_pairs", self.pectoral_pairs)?;
        range("fin_size", self.fin_size, MIN_SIZE, 100.0)?;
        range("tail_size", self.tail_size, MIN_SIZE, 100.0)?;
        Ok(())
    }
}

/// The smallest size option: parts never shrink to nothing.
const MIN_SIZE: f32 = 0.001;

/// The largest count option (fins, fin pairs, flier leg pairs).
const MAX_COUNT: usize = 64;

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

fn count(name: &'static str, value: usize, max: usize) -> Result<(), LimbsError> {
    if value <= max {
        Ok(())
    } else {
        Err(LimbsError::InvalidOption {
            name,
            value: value as f32,
        })
    }
}

fn count_range(name: &'static str, [lo, hi]: [usize; 2]) -> Result<(), LimbsError> {
    count(name, hi, MAX_COUNT)?;
    if lo > hi {
        return Err(LimbsError::InvalidOption {
            name,
            value: lo as f32,
        });
    }
    Ok(())
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
    fn every_field_rejects_values_outside_its_documented_range() {
        let d = PlanOptions::DEFAULT;
        let cases: [(&str, PlanOptions); 24] = [
            ("sweep", d.with_sweep(-0.1)),
            ("sweep", d.with_sweep(100.5)),
            ("foot_radius", d.with_foot_radius(0.3)),
            ("foot_radius", d.with_foot_radius(-0.01)),
            ("min_margin", d.with_min_margin(0.0)),
            ("min_margin", d.with_min_margin(1.5)),
            ("min_leg_length", d.with_min_leg_length(0.0)),
            ("long_body_ratio", d.with_long_body_ratio(2.0e6)),
            ("uniform_width_ratio", d.with_uniform_width_ratio(1.5)),
            ("second_pair_ratio", d.with_second_pair_ratio(-1.0)),
            ("central_bones", d.with_central_bones(MAX_BONES + 1)),
            ("arm_chance", d.with_arm_chance(101.0)),
            ("arm_length", d.with_arm_length([0.5, 1.1])),
            ("min_arm_length", d.with_min_arm_length(0.0)),
            ("max_flier_leg_pairs", d.with_max_flier_leg_pairs(65)),
            ("flier_leg_length", d.with_flier_leg_length([0.0, 0.2])),
            ("buzzing_wing_size", d.with_buzzing_wing_size([0.3, 101.0])),
            ("flapping_wing_size", d.with_flapping_wing_size([0.0, 1.0])),
            ("stretch", d.with_stretch([1.3, 0.7])),
            ("dorsal_fins", d.with_dorsal_fins([3, 1])),
            ("dorsal_fins", d.with_dorsal_fins([0, 65])),
            ("pectoral_pairs", d.with_pectoral_pairs([0, 65])),
            ("fin_size", d.with_fin_size([0.5, 0.1])),
            ("tail_size", d.with_tail_size([f32::NAN, 0.4])),
        ];
        for (name, o) in cases {
            match o.validate() {
                Err(LimbsError::InvalidOption { name: got, .. }) => assert_eq!(got, name),
                other => panic!("{name}: {other:?}"),
            }
        }
        // The ends of each range are valid.
        let edges = d
            .with_sweep(100.0)
            .with_foot_radius(0.0)
            .with_min_margin(1.0)
            .with_min_leg_length(0.001)
            .with_central_bones(MAX_BONES)
            .with_arm_length([0.0, 1.0])
            .with_max_flier_leg_pairs(64)
            .with_stretch([0.001, 100.0])
            .with_dorsal_fins([64, 64]);
        assert_eq!(edges.validate(), Ok(()));
        assert!(d.with_sweep(f32::NAN).validate().is_err());
    }
}
