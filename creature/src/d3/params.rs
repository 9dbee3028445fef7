//! Parameters of the 3D generator, with the 3D seed's values as defaults.

use creature_limbs::PlanOptions;

use super::accessories::BackWeights;
use super::colour::{ColourParams, PatternWeights};
use super::wings::WingWeights;
use crate::Error;
use crate::span::{IntSpan, Span, count, scalar};

/// Which kind of creature [`generate`](crate::generate) makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub enum Kind {
    /// Walks on legs (maybe with arms); always statically stable.
    Walker,
    /// Flies on buzzing or flapping wings, legs dangling.
    Flier,
    /// Swims with dorsal fins, pectoral fins and a tail.
    Swimmer,
    /// Crawls on its belly without limbs (a snake): a long, thin body of many spine bones,
    /// moving by a wave that travels from head to tail.
    Slitherer,
    /// One of the first three (walker, flier, swimmer), drawn from the seed (each with
    /// probability 1/3; a seed's random creature is the one it always was).
    #[default]
    Random,
}

/// Parameters of [`generate`](crate::generate): the random ranges of the 3D seed (thesis §4.1,
/// "Procedural creature generation", Unity) as defaults, and the mesh resolution.
///
/// Lengths are in metres; the base pill is 2 long and about 0.7 across before the FFD and the
/// body scale. Every range is drawn uniformly (`min + U·(max − min)`).
///
/// ```
/// use creature::Span;
/// use creature::d3::{Kind, Params};
///
/// let params = Params::DEFAULT
///     .with_kind(Kind::Walker)
///     .with_body_scale(Span::new(1.0, 1.5));
/// params.validate()?;
/// assert!(Params::DEFAULT.with_body_scale(Span::new(2.0, 1.0)).validate().is_err());
/// # Ok::<(), creature::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Params {
    /// The creature kind. Default [`Kind::Random`].
    pub kind: Kind,
    /// How many of the nine body profiles are blended, with random weights. From 1 to 9.
    /// Default 3 (the seed's).
    pub profiles: u32,
    /// Rings of the pill along the body (between its two tip vertices). From 4 to 64.
    /// Default 16. A slitherer's long body has twice as many.
    pub rings: u32,
    /// Vertices around each ring. From 3 to 64. Default 10 (low poly).
    pub segments: u32,
    /// Sides of the limb tubes. From 3 to 32. Default 5.
    pub limb_sides: u32,
    /// Flat (per-face) normals, the seed's low-poly look: every triangle gets its own three
    /// vertices. With `false` the mesh is shared and normals are smooth. Default `true`.
    pub flat_normals: bool,
    /// Scale of each FFD slice across the body (x) for walkers and fliers. From 0.1 to 10.
    /// Default 0.7..1.4.
    pub slice_width: Span,
    /// Scale of each FFD slice in height (y) for walkers and fliers. From 0.1 to 10.
    /// Default 0.7..1.4.
    pub slice_height: Span,
    /// Step from one FFD slice to the next along the body (z), as a fraction of the undeformed
    /// step, for walkers and fliers: each slice is the previous one plus this (always positive),
    /// so the body never folds. From 0.05 to 10. Default 0.7..1.5.
    pub slice_step: Span,
    /// Swimmers' slice width (narrower: fish are flat). From 0.1 to 10. Default 0.4..0.8.
    pub swimmer_slice_width: Span,
    /// Swimmers' slice height (taller). From 0.1 to 10. Default 1.0..1.8.
    pub swimmer_slice_height: Span,
    /// Swimmers' slice step (shorter). From 0.05 to 10. Default 0.6..1.1.
    pub swimmer_slice_step: Span,
    /// Slitherers' slice width (thin: a snake's body). From 0.1 to 10. Default 0.22..0.34.
    pub slitherer_slice_width: Span,
    /// Slitherers' slice height. From 0.1 to 10. Default 0.2..0.3.
    pub slitherer_slice_height: Span,
    /// Slitherers' slice step (longer: their bodies are 10 to 20 times as long as they are
    /// wide). From 0.05 to 10. Default 1.3..2.0.
    pub slitherer_slice_step: Span,
    /// Uniform scale of the body. From 0.01 to 100. Default 0.5..2 (the seed's).
    pub body_scale: Span,
    /// Speed factor: the speed is the body scale times this (m/s); it is also the gait's speed
    /// multiplier (above 1: longer, higher steps). A walker walks no faster than its legs can:
    /// at most a Froude number `v² / (g · leg length)` of 1, where animals break into a run; a
    /// larger factor is lowered to that. From 0.01 to 10. Default 0.8..1.25.
    pub speed_factor: Span,
    /// Target spine bone length for the auto-rigger, in metres: longer bodies get more bones.
    /// From 0.01 to 10. Default 0.25.
    pub bone_length: f32,
    /// Spine bones (bounds on the auto-rigger's count). From 5 to 60. Default 5..=24.
    pub spine_bones: IntSpan,
    /// Spine bend budget in degrees (walkers and fliers): the neck and the tail each bend by a
    /// random per-bone angle of at most `spine_bend / bones`, and never more than half of this
    /// in total. From 0 to 200. Default 200 (the seed's: neither passes 100°).
    pub spine_bend: f32,
    /// Head radius (walkers and fliers), × half the body width at the second neck bone (or,
    /// where that is wider, 1.3 × the neck's width under the head): the skull's half-width is
    /// about this (a broad, flat head's more). From 0.1 to 10.
    /// Default 0.9..1.3.
    pub head_size: Span,
    /// How narrow a walker's or flier's neck is: the body's front (the slice of its lattice at
    /// the head's end) is this × as wide and high as the body's broadest slice behind it (or
    /// as its own, if narrower), the next three slices less so, back to the body's own along a
    /// parabola, so the body narrows into a neck under the head. From 0.2 to 1. Default 0.6.
    pub neck_width: f32,
    /// Eye radius, × the head radius (on a swimmer, × the half-width or half-height of its
    /// front, whichever is less). From 0.05 to 0.6. Default 0.2..0.3.
    pub eye_size: Span,
    /// Snout length (a long-snouted head's; a beak is 0.8 of it), × the head radius, past the
    /// skull's front. From 0 to 5. Default 0.6..1.3.
    pub snout_length: Span,
    /// Length of ears, horns, a crest's feathers and mandibles, × the head radius (antennae
    /// twice as long). From 0 to 3. Default 0.5..0.9.
    pub ornament_size: Span,
    /// How likely a head is to have its family's optional ornament (ears or horns, a crest,
    /// an insect's second pair of eyes; an insect always has mandibles and antennae). From 0 to
    /// 1. Default 0.5.
    pub ornament_chance: f32,
    /// Height of the lowest body point above the ground, × body length (the seed's random
    /// capsule collider height). From 0 to 10. Default 0.15..0.6.
    pub ground_clearance: Span,
    /// Options of the limb planner (`creature_limbs::plan`). Default
    /// [`PlanOptions::DEFAULT`].
    pub limbs: PlanOptions,
    /// How much thicker a leg's thigh is than its shin (an arm's upper arm than its forearm):
    /// the thigh's radius × the shin's, drawn once per creature. From 1 to 3. Default 1.35..1.7.
    pub thigh_thickness: Span,
    /// The least span of a flier's wings (flapping or buzzing), tip to tip, × its body length (a wing the
    /// planner drew longer stays longer). From 0.2 to 5. Default 1.3..1.8.
    pub wing_span: Span,
    /// The least area of a flier's wings (flapping or buzzing; both wings, one face) × the volume of its
    /// body and head to the power 2/3: heavier bodies get bigger wings (wider, then longer).
    /// From 0.1 to 10. Default 1.2..2.0.
    pub wing_area: Span,
    /// How likely a flier's flapping wings are to be feathered or a bat's membrane between
    /// finger bones (buzzing wings are always an insect's). Default [`WingWeights::DEFAULT`].
    pub wing_kinds: WingWeights,
    /// Height of the spikes or plates along a walker's back, × the body's half-height at the
    /// spine joint each stands on (drawn once per creature). From 0 to 3. Default 0.5..1.0.
    pub back_ornament_size: Span,
    /// How likely a walker is to wear something on its back (a row of spikes or plates, or a
    /// shell: see [`back_kinds`](Self::back_kinds)). From 0 to 1. Default 0.5.
    pub back_ornament_chance: f32,
    /// What a walker that wears something on its back wears: a row of spikes, a row of plates
    /// or a shell. Default [`BackWeights::DEFAULT`] (each alike).
    pub back_kinds: BackWeights,
    /// A walker's shell's thickness on top of its middle, × 0.8 × the body's radius there
    /// (drawn once per creature). From 0 to 1: at most a body's radius thick, so the shell
    /// stays on the back instead of outweighing the body (thicker ones, up to 2.2 radii, put
    /// bipeds' feet across their midline as the feet moved under the mass). Default 0.5..1.0.
    pub shell_size: Span,
    /// Saturation of the base colour (HSV, sRGB-encoded; the belly gets about a third of it),
    /// from 0 (greys) to 1. Default 0.3..0.75.
    pub saturation: Span,
    /// Countershading: how far the belly goes from the base colour to the light belly colour,
    /// and how much darker the back is (0: one colour all round; 1: belly in the belly colour,
    /// back 30% darker). From 0 to 1. Default 0.6..1.
    pub countershading: Span,
    /// How likely each body pattern is (stripes, spots, bands, a gradient, plain). Default
    /// [`PatternWeights::DEFAULT`].
    pub patterns: PatternWeights,
    /// How likely a two-legged walker is to hop (both feet together, a flight each hop, its
    /// tail swung up against its legs) where others run, from a little above its walking
    /// speed (a Froude number of [`HOP_FROUDE`](crate::d3::HOP_FROUDE)); its `walk` is a walk
    /// all the same, and its clips gain a `hop`. Drawn from a generator of its own: the chance
    /// changes no shape or colour. From 0 to 1. Default 0.5.
    pub hop_chance: f32,
    /// Bake the kind's animation clips into [`Creature::clips`](crate::d3::Creature::clips)
    /// (see [`Creature::bake_clips`](crate::d3::Creature::bake_clips)). Default `true`; turn off
    /// to generate faster and bake later, or never.
    pub clips: bool,
    /// Bake the clips in place ([`Clip::in_place`](crate::d3::Clip::in_place): the root's
    /// horizontal travel removed) for viewers that loop them as they are. Default `false`:
    /// root motion, what engines that move a character by its clips want.
    pub in_place: bool,
}

impl Params {
    /// The defaults listed on each field.
    pub const DEFAULT: Self = Self {
        kind: Kind::Random,
        profiles: 3,
        rings: 16,
        segments: 10,
        limb_sides: 5,
        flat_normals: true,
        slice_width: Span::new(0.7, 1.4),
        slice_height: Span::new(0.7, 1.4),
        slice_step: Span::new(0.7, 1.5),
        swimmer_slice_width: Span::new(0.4, 0.8),
        swimmer_slice_height: Span::new(1.0, 1.8),
        swimmer_slice_step: Span::new(0.6, 1.1),
        slitherer_slice_width: Span::new(0.22, 0.34),
        slitherer_slice_height: Span::new(0.2, 0.3),
        slitherer_slice_step: Span::new(1.3, 2.0),
        body_scale: Span::new(0.5, 2.0),
        speed_factor: Span::new(0.8, 1.25),
        bone_length: 0.25,
        spine_bones: IntSpan::new(5, 24),
        spine_bend: 200.0,
        head_size: Span::new(0.9, 1.3),
        neck_width: 0.6,
        eye_size: Span::new(0.2, 0.3),
        snout_length: Span::new(0.6, 1.3),
        ornament_size: Span::new(0.5, 0.9),
        ornament_chance: 0.5,
        ground_clearance: Span::new(0.15, 0.6),
        limbs: PlanOptions::DEFAULT,
        thigh_thickness: Span::new(1.35, 1.7),
        wing_span: Span::new(1.3, 1.8),
        wing_area: Span::new(1.2, 2.0),
        wing_kinds: WingWeights::DEFAULT,
        back_ornament_size: Span::new(0.5, 1.0),
        back_ornament_chance: 0.5,
        back_kinds: BackWeights::DEFAULT,
        shell_size: Span::new(0.5, 1.0),
        saturation: Span::new(0.3, 0.75),
        countershading: Span::new(0.6, 1.0),
        patterns: PatternWeights::DEFAULT,
        hop_chance: 0.5,
        clips: true,
        in_place: false,
    };

    /// Sets [`kind`](Self::kind).
    #[must_use]
    pub const fn with_kind(mut self, kind: Kind) -> Self {
        self.kind = kind;
        self
    }

    /// Sets [`profiles`](Self::profiles).
    #[must_use]
    pub const fn with_profiles(mut self, profiles: u32) -> Self {
        self.profiles = profiles;
        self
    }

    /// Sets [`rings`](Self::rings) and [`segments`](Self::segments).
    #[must_use]
    pub const fn with_resolution(mut self, rings: u32, segments: u32) -> Self {
        self.rings = rings;
        self.segments = segments;
        self
    }

    /// Sets [`limb_sides`](Self::limb_sides).
    #[must_use]
    pub const fn with_limb_sides(mut self, sides: u32) -> Self {
        self.limb_sides = sides;
        self
    }

    /// Sets [`flat_normals`](Self::flat_normals).
    #[must_use]
    pub const fn with_flat_normals(mut self, flat: bool) -> Self {
        self.flat_normals = flat;
        self
    }

    /// Sets [`slice_width`](Self::slice_width), [`slice_height`](Self::slice_height) and
    /// [`slice_step`](Self::slice_step) (walkers and fliers).
    #[must_use]
    pub const fn with_slices(mut self, width: Span, height: Span, step: Span) -> Self {
        self.slice_width = width;
        self.slice_height = height;
        self.slice_step = step;
        self
    }

    /// Sets the swimmers' [`swimmer_slice_width`](Self::swimmer_slice_width),
    /// [`swimmer_slice_height`](Self::swimmer_slice_height) and
    /// [`swimmer_slice_step`](Self::swimmer_slice_step).
    #[must_use]
    pub const fn with_swimmer_slices(mut self, width: Span, height: Span, step: Span) -> Self {
        self.swimmer_slice_width = width;
        self.swimmer_slice_height = height;
        self.swimmer_slice_step = step;
        self
    }

    /// Sets the slitherers' [`slitherer_slice_width`](Self::slitherer_slice_width),
    /// [`slitherer_slice_height`](Self::slitherer_slice_height) and
    /// [`slitherer_slice_step`](Self::slitherer_slice_step).
    #[must_use]
    pub const fn with_slitherer_slices(mut self, width: Span, height: Span, step: Span) -> Self {
        self.slitherer_slice_width = width;
        self.slitherer_slice_height = height;
        self.slitherer_slice_step = step;
        self
    }

    /// Sets [`body_scale`](Self::body_scale).
    #[must_use]
    pub const fn with_body_scale(mut self, scale: Span) -> Self {
        self.body_scale = scale;
        self
    }

    /// Sets [`speed_factor`](Self::speed_factor).
    #[must_use]
    pub const fn with_speed_factor(mut self, factor: Span) -> Self {
        self.speed_factor = factor;
        self
    }

    /// Sets [`bone_length`](Self::bone_length).
    #[must_use]
    pub const fn with_bone_length(mut self, length: f32) -> Self {
        self.bone_length = length;
        self
    }

    /// Sets [`spine_bones`](Self::spine_bones).
    #[must_use]
    pub const fn with_spine_bones(mut self, bones: IntSpan) -> Self {
        self.spine_bones = bones;
        self
    }

    /// Sets [`spine_bend`](Self::spine_bend).
    #[must_use]
    pub const fn with_spine_bend(mut self, degrees: f32) -> Self {
        self.spine_bend = degrees;
        self
    }

    /// Sets [`head_size`](Self::head_size).
    #[must_use]
    pub const fn with_head_size(mut self, size: Span) -> Self {
        self.head_size = size;
        self
    }

    /// Sets [`neck_width`](Self::neck_width).
    #[must_use]
    pub const fn with_neck_width(mut self, neck_width: f32) -> Self {
        self.neck_width = neck_width;
        self
    }

    /// Sets [`eye_size`](Self::eye_size).
    #[must_use]
    pub const fn with_eye_size(mut self, size: Span) -> Self {
        self.eye_size = size;
        self
    }

    /// Sets [`snout_length`](Self::snout_length).
    #[must_use]
    pub const fn with_snout_length(mut self, length: Span) -> Self {
        self.snout_length = length;
        self
    }

    /// Sets [`ornament_size`](Self::ornament_size) and
    /// [`ornament_chance`](Self::ornament_chance).
    #[must_use]
    pub const fn with_ornaments(mut self, size: Span, chance: f32) -> Self {
        self.ornament_size = size;
        self.ornament_chance = chance;
        self
    }

    /// Sets [`ground_clearance`](Self::ground_clearance).
    #[must_use]
    pub const fn with_ground_clearance(mut self, clearance: Span) -> Self {
        self.ground_clearance = clearance;
        self
    }

    /// Sets [`limbs`](Self::limbs).
    #[must_use]
    pub const fn with_limbs(mut self, limbs: PlanOptions) -> Self {
        self.limbs = limbs;
        self
    }

    /// Sets [`thigh_thickness`](Self::thigh_thickness).
    #[must_use]
    pub const fn with_thigh_thickness(mut self, thickness: Span) -> Self {
        self.thigh_thickness = thickness;
        self
    }

    /// Sets [`wing_span`](Self::wing_span) and [`wing_area`](Self::wing_area).
    #[must_use]
    pub const fn with_wings(mut self, span: Span, area: Span) -> Self {
        self.wing_span = span;
        self.wing_area = area;
        self
    }

    /// Sets [`back_ornament_size`](Self::back_ornament_size) and
    /// [`back_ornament_chance`](Self::back_ornament_chance).
    #[must_use]
    pub const fn with_back_ornaments(mut self, size: Span, chance: f32) -> Self {
        self.back_ornament_size = size;
        self.back_ornament_chance = chance;
        self
    }

    /// Sets [`hop_chance`](Self::hop_chance).
    #[must_use]
    pub const fn with_hop_chance(mut self, chance: f32) -> Self {
        self.hop_chance = chance;
        self
    }

    /// Sets [`saturation`](Self::saturation).
    #[must_use]
    pub const fn with_saturation(mut self, saturation: Span) -> Self {
        self.saturation = saturation;
        self
    }

    /// Sets [`countershading`](Self::countershading).
    #[must_use]
    pub const fn with_countershading(mut self, countershading: Span) -> Self {
        self.countershading = countershading;
        self
    }

    /// Sets [`shell_size`](Self::shell_size).
    #[must_use]
    pub const fn with_shell_size(mut self, shell_size: Span) -> Self {
        self.shell_size = shell_size;
        self
    }

    /// Sets [`back_kinds`](Self::back_kinds).
    #[must_use]
    pub const fn with_back_kinds(mut self, back_kinds: BackWeights) -> Self {
        self.back_kinds = back_kinds;
        self
    }

    /// Sets [`wing_kinds`](Self::wing_kinds).
    #[must_use]
    pub const fn with_wing_kinds(mut self, wing_kinds: WingWeights) -> Self {
        self.wing_kinds = wing_kinds;
        self
    }

    /// Sets [`patterns`](Self::patterns).
    #[must_use]
    pub const fn with_patterns(mut self, patterns: PatternWeights) -> Self {
        self.patterns = patterns;
        self
    }

    /// The colour fields, for the colouring stage.
    pub(crate) fn colours(&self) -> ColourParams {
        ColourParams {
            saturation: self.saturation,
            countershading: self.countershading,
            patterns: self.patterns,
            rings: self.rings as usize,
        }
    }

    /// Sets [`clips`](Self::clips).
    #[must_use]
    pub const fn with_clips(mut self, clips: bool) -> Self {
        self.clips = clips;
        self
    }

    /// Sets [`in_place`](Self::in_place).
    #[must_use]
    pub const fn with_in_place(mut self, in_place: bool) -> Self {
        self.in_place = in_place;
        self
    }

    /// Checks every field against its documented range; [`generate`](crate::generate) calls
    /// this first.
    ///
    /// # Errors
    /// [`Error::NonFinite`], [`Error::OutOfRange`] or [`Error::EmptyRange`] naming the field,
    /// [`Error::AllZero`] for [`patterns`](Self::patterns), [`wing_kinds`](Self::wing_kinds)
    /// or [`back_kinds`](Self::back_kinds) with no weight above 0, and
    /// [`Error::Limbs`] for bad [`limbs`](Self::limbs) options.
    pub fn validate(&self) -> Result<(), Error> {
        count("profiles", self.profiles, 1, 9)?;
        count("rings", self.rings, 4, 64)?;
        count("segments", self.segments, 3, 64)?;
        count("limb_sides", self.limb_sides, 3, 32)?;
        self.slice_width.check("slice_width", 0.1, 10.0)?;
        self.slice_height.check("slice_height", 0.1, 10.0)?;
        self.slice_step.check("slice_step", 0.05, 10.0)?;
        self.swimmer_slice_width
            .check("swimmer_slice_width", 0.1, 10.0)?;
        self.swimmer_slice_height
            .check("swimmer_slice_height", 0.1, 10.0)?;
        self.swimmer_slice_step
            .check("swimmer_slice_step", 0.05, 10.0)?;
        self.slitherer_slice_width
            .check("slitherer_slice_width", 0.1, 10.0)?;
        self.slitherer_slice_height
            .check("slitherer_slice_height", 0.1, 10.0)?;
        self.slitherer_slice_step
            .check("slitherer_slice_step", 0.05, 10.0)?;
        self.body_scale.check("body_scale", 0.01, 100.0)?;
        self.speed_factor.check("speed_factor", 0.01, 10.0)?;
        scalar("bone_length", self.bone_length, 0.01, 10.0)?;
        self.spine_bones.check("spine_bones", 5, 60)?;
        scalar("spine_bend", self.spine_bend, 0.0, 200.0)?;
        self.head_size.check("head_size", 0.1, 10.0)?;
        scalar("neck_width", self.neck_width, 0.2, 1.0)?;
        self.eye_size.check("eye_size", 0.05, 0.6)?;
        self.snout_length.check("snout_length", 0.0, 5.0)?;
        self.ornament_size.check("ornament_size", 0.0, 3.0)?;
        scalar("ornament_chance", self.ornament_chance, 0.0, 1.0)?;
        self.ground_clearance.check("ground_clearance", 0.0, 10.0)?;
        self.limbs.validate()?;
        self.thigh_thickness.check("thigh_thickness", 1.0, 3.0)?;
        self.wing_span.check("wing_span", 0.2, 5.0)?;
        self.wing_area.check("wing_area", 0.1, 10.0)?;
        self.wing_kinds.check("wing_kinds")?;
        self.back_ornament_size
            .check("back_ornament_size", 0.0, 3.0)?;
        scalar("back_ornament_chance", self.back_ornament_chance, 0.0, 1.0)?;
        self.back_kinds.check("back_kinds")?;
        self.shell_size.check("shell_size", 0.0, 1.0)?;
        scalar("hop_chance", self.hop_chance, 0.0, 1.0)?;
        self.saturation.check("saturation", 0.0, 1.0)?;
        self.countershading.check("countershading", 0.0, 1.0)?;
        self.patterns.check("patterns")?;
        Ok(())
    }
}

impl Default for Params {
    fn default() -> Self {
        Self::DEFAULT
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::d3::{BackKind, Pattern, WingKind};

    #[test]
    fn defaults_are_valid() {
        assert_eq!(Params::DEFAULT.validate(), Ok(()));
        assert_eq!(Params::default(), Params::DEFAULT);
    }

    #[test]
    fn bad_values_name_the_field() {
        let e = Params::DEFAULT.with_profiles(0).validate();
        assert!(matches!(
            e,
            Err(Error::OutOfRange {
                what: "profiles",
                ..
            })
        ));
        let e = Params::DEFAULT
            .with_body_scale(Span::new(f32::NAN, 1.0))
            .validate();
        assert_eq!(e, Err(Error::NonFinite { what: "body_scale" }));
        let e = Params::DEFAULT
            .with_spine_bones(IntSpan::new(10, 6))
            .validate();
        assert!(matches!(
            e,
            Err(Error::EmptyRange {
                what: "spine_bones",
                ..
            })
        ));
        let e = Params::DEFAULT.with_spine_bend(f32::INFINITY).validate();
        assert_eq!(e, Err(Error::NonFinite { what: "spine_bend" }));
        let e = Params::DEFAULT
            .with_limbs(PlanOptions::DEFAULT.with_sweep(-1.0))
            .validate();
        assert!(matches!(e, Err(Error::Limbs(_))));
        let e = Params::DEFAULT
            .with_saturation(Span::new(0.5, 1.5))
            .validate();
        assert!(matches!(
            e,
            Err(Error::OutOfRange {
                what: "saturation",
                ..
            })
        ));
        let e = Params::DEFAULT
            .with_countershading(Span::new(0.9, 0.1))
            .validate();
        assert!(matches!(
            e,
            Err(Error::EmptyRange {
                what: "countershading",
                ..
            })
        ));
        let e = Params::DEFAULT
            .with_eye_size(Span::new(0.01, 0.2))
            .validate();
        assert!(matches!(
            e,
            Err(Error::OutOfRange {
                what: "eye_size",
                ..
            })
        ));
        let e = Params::DEFAULT
            .with_snout_length(Span::new(1.0, 0.5))
            .validate();
        assert!(matches!(
            e,
            Err(Error::EmptyRange {
                what: "snout_length",
                ..
            })
        ));
        let e = Params::DEFAULT
            .with_ornaments(Span::new(0.5, 0.9), f32::NAN)
            .validate();
        assert_eq!(
            e,
            Err(Error::NonFinite {
                what: "ornament_chance"
            })
        );
        let e = Params::DEFAULT
            .with_ornaments(Span::new(0.5, 9.0), 0.5)
            .validate();
        assert!(matches!(
            e,
            Err(Error::OutOfRange {
                what: "ornament_size",
                ..
            })
        ));
        let e = Params::DEFAULT
            .with_thigh_thickness(Span::new(0.8, 1.5))
            .validate();
        assert!(matches!(
            e,
            Err(Error::OutOfRange {
                what: "thigh_thickness",
                ..
            })
        ));
        let e = Params::DEFAULT
            .with_wings(Span::new(1.8, 1.3), Span::new(1.5, 2.5))
            .validate();
        assert!(matches!(
            e,
            Err(Error::EmptyRange {
                what: "wing_span",
                ..
            })
        ));
        let e = Params::DEFAULT
            .with_wings(Span::new(1.3, 1.8), Span::new(f32::NAN, 2.5))
            .validate();
        assert_eq!(e, Err(Error::NonFinite { what: "wing_area" }));
        let e = Params::DEFAULT
            .with_back_ornaments(Span::new(0.5, 3.5), 0.5)
            .validate();
        assert!(matches!(
            e,
            Err(Error::OutOfRange {
                what: "back_ornament_size",
                ..
            })
        ));
        let e = Params::DEFAULT
            .with_back_ornaments(Span::new(0.5, 1.0), f32::NAN)
            .validate();
        assert_eq!(
            e,
            Err(Error::NonFinite {
                what: "back_ornament_chance"
            })
        );
        let none = PatternWeights::only(Pattern::Spots).with(Pattern::Spots, 0.0);
        let e = Params::DEFAULT.with_patterns(none).validate();
        assert_eq!(e, Err(Error::AllZero { what: "patterns" }));
        let e = Params::DEFAULT
            .with_patterns(PatternWeights::DEFAULT.with(Pattern::Bands, f32::NAN))
            .validate();
        assert_eq!(e, Err(Error::NonFinite { what: "patterns" }));
        let e = Params::DEFAULT
            .with_shell_size(Span::new(0.5, 1.5))
            .validate();
        assert!(matches!(
            e,
            Err(Error::OutOfRange {
                what: "shell_size",
                ..
            })
        ));
        let none = BackWeights::only(BackKind::Shell).with(BackKind::Shell, 0.0);
        let e = Params::DEFAULT.with_back_kinds(none).validate();
        assert_eq!(e, Err(Error::AllZero { what: "back_kinds" }));
        let none = WingWeights::only(WingKind::Bat).with(WingKind::Bat, 0.0);
        let e = Params::DEFAULT.with_wing_kinds(none).validate();
        assert_eq!(e, Err(Error::AllZero { what: "wing_kinds" }));
        let e = Params::DEFAULT
            .with_wing_kinds(WingWeights::DEFAULT.with(WingKind::Feathered, -1.0))
            .validate();
        assert!(matches!(
            e,
            Err(Error::OutOfRange {
                what: "wing_kinds",
                ..
            })
        ));
    }
}
