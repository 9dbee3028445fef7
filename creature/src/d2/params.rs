//! Parameters of the 2D generator, with the seed's values as defaults.

use crate::Error;
use crate::span::{IntSpan, Span, scalar};

/// Parameters of [`generate_2d`](crate::generate_2d): the skeleton's random ranges (the 2D
/// seed's, reference §2.3, as defaults), the outline, mesh and texture settings.
///
/// Lengths are in the seed's units (pixels of an 800×800 view); a default creature measures
/// about 200–500 units across.
///
/// ```
/// use creature::Span;
/// use creature::d2::Params;
///
/// let params = Params::DEFAULT
///     .with_spine_thickness(Span::new(20.0, 30.0))
///     .with_texture_size(128);
/// params.validate()?;
/// assert!(Params::DEFAULT.with_texture_size(0).validate().is_err());
/// # Ok::<(), creature::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Params {
    /// Spine bones, the root (the tail tip, no thickness) included; the last is the head.
    /// From 2 to 64. Default 3..=6 (the seed's: 2 to 5 visible segments).
    pub spine_bones: IntSpan,
    /// Spine thickness (the covering balls' thickness `T`). From 1 to 1000. Default 10..40.
    pub spine_thickness: Span,
    /// Spine segment length. From 1 to 10,000. Default 50..100.
    pub spine_length: Span,
    /// Spine smoothness multiplier `m` (1: beads, 1.6: a smooth tube). From 1 to 1.6.
    /// Default 1..1.6.
    pub spine_multiplier: Span,
    /// Probability that a spine bone (the root, i.e. the tail tip, included) gets a mirrored
    /// limb pair. From 0 to 1. Default 0.5.
    pub limb_probability: f32,
    /// Bones per limb side, the first being the invisible socket joint (so 2 gives one visible
    /// segment). From 2 to 16. Default 2..=4.
    pub limb_bones: IntSpan,
    /// Limb segment length. From 1 to 10,000. Default 50..80.
    pub limb_length: Span,
    /// Limb thickness. From 1 to 1000. Default 5..15.
    pub limb_thickness: Span,
    /// Limb smoothness multiplier. From 1 to 1.6. Default 1..1.6.
    pub limb_multiplier: Span,
    /// The socket joint sits this many spine thicknesses out from the spine (the larger of the
    /// two spine segments meeting there). From 0 to 4. Default 1.1 (the seed's).
    pub socket_offset: f32,
    /// Cover the link from the spine to each socket joint with the limb's thickness, so every
    /// limb stays attached to the body (the seed left it empty and silently dropped the 1% of
    /// limbs that ended up detached). Default `true`; with `false`, a detached limb is an
    /// [`Error::Detached`].
    pub connect_sockets: bool,
    /// Eyes on the head. From 0 to 32. Default 1..=7 (drawn as `floor(1 + 7U)`, uniformly, as
    /// the seed does: the range's ends are as likely as the rest).
    pub eye_count: IntSpan,
    /// Eye radius as a fraction of the head's thickness. From 0 to 1. Default 0.5..1.
    pub eye_size: Span,
    /// Outline sampling step of the contour-following marching squares. From 0.5 to 100.
    /// Default 5 (the seed's `interval`).
    pub outline_step: f32,
    /// Ring points within this distance of the line through their neighbours are dropped
    /// before meshing (fewer, better triangles). From 0 to `outline_step`. Default 0.5.
    pub simplify: f32,
    /// Spacing of the interior mesh points (sheared lattice). From 1 to 1000. Default 20 (the
    /// seed's).
    pub interior_spacing: f32,
    /// Interior points closer than `interior_clearance × interior_spacing` to the (simplified)
    /// outline are left out; refinement grades the band between them and the outline. From 0
    /// to 2. Default 0.8: on the seed's creatures this gives about the fewest vertices at the
    /// same minimum angle (207 against 221 with `creature-march`'s default 0.5, on average
    /// over seeds 0–15; 1.0 gives 200 but more refinement work), so the mesh, its skinning and
    /// its refinement cost less.
    pub interior_clearance: f32,
    /// Delaunay refinement's minimum triangle angle, degrees. From 0 to 33. Default 20.
    pub min_angle: f32,
    /// Render the texture and normal map. Default `true`.
    pub texture: bool,
    /// Texture and normal-map size in pixels (square). From 1 to 4096. Default 256 (the seed's).
    pub texture_size: u32,
    /// Depth shading: the texture's brightness is this fraction of the field sum. From 0 to 4.
    /// Default 0.75 (the seed's).
    pub depth_shading: f32,
    /// Height of the normal map's relief: the surface is `z = normal_relief × field`, in world
    /// units. From 0 to 1000. Default 12.
    pub normal_relief: f32,
}

impl Params {
    /// The seed's values; see each field.
    pub const DEFAULT: Self = Self {
        spine_bones: IntSpan::new(3, 6),
        spine_thickness: Span::new(10.0, 40.0),
        spine_length: Span::new(50.0, 100.0),
        spine_multiplier: Span::new(1.0, 1.6),
        limb_probability: 0.5,
        limb_bones: IntSpan::new(2, 4),
        limb_length: Span::new(50.0, 80.0),
        limb_thickness: Span::new(5.0, 15.0),
        limb_multiplier: Span::new(1.0, 1.6),
        socket_offset: 1.1,
        connect_sockets: true,
        eye_count: IntSpan::new(1, 7),
        eye_size: Span::new(0.5, 1.0),
        outline_step: 5.0,
        simplify: 0.5,
        interior_spacing: 20.0,
        interior_clearance: 0.8,
        min_angle: 20.0,
        texture: true,
        texture_size: 256,
        depth_shading: 0.75,
        normal_relief: 12.0,
    };

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`Error::NonFinite`], [`Error::OutOfRange`] or [`Error::EmptyRange`] naming the first
    /// bad field.
    pub fn validate(&self) -> Result<(), Error> {
        self.spine_bones.check("spine_bones", 2, 64)?;
        self.spine_thickness.check("spine_thickness", 1.0, 1000.0)?;
        self.spine_length.check("spine_length", 1.0, 10_000.0)?;
        self.spine_multiplier.check("spine_multiplier", 1.0, 1.6)?;
        scalar("limb_probability", self.limb_probability, 0.0, 1.0)?;
        self.limb_bones.check("limb_bones", 2, 16)?;
        self.limb_length.check("limb_length", 1.0, 10_000.0)?;
        self.limb_thickness.check("limb_thickness", 1.0, 1000.0)?;
        self.limb_multiplier.check("limb_multiplier", 1.0, 1.6)?;
        scalar("socket_offset", self.socket_offset, 0.0, 4.0)?;
        self.eye_count.check("eye_count", 0, 32)?;
        self.eye_size.check("eye_size", 0.0, 1.0)?;
        scalar("outline_step", self.outline_step, 0.5, 100.0)?;
        scalar("simplify", self.simplify, 0.0, self.outline_step)?;
        scalar("interior_spacing", self.interior_spacing, 1.0, 1000.0)?;
        scalar("interior_clearance", self.interior_clearance, 0.0, 2.0)?;
        scalar("min_angle", self.min_angle, 0.0, 33.0)?;
        if self.texture_size == 0 || self.texture_size > 4096 {
            return Err(Error::OutOfRange {
                what: "texture_size",
                value: self.texture_size as f32,
                min: 1.0,
                max: 4096.0,
            });
        }
        scalar("depth_shading", self.depth_shading, 0.0, 4.0)?;
        scalar("normal_relief", self.normal_relief, 0.0, 1000.0)?;
        Ok(())
    }

    /// Sets [`spine_bones`](Self::spine_bones).
    #[must_use]
    pub const fn with_spine_bones(mut self, v: IntSpan) -> Self {
        self.spine_bones = v;
        self
    }
    /// Sets [`spine_thickness`](Self::spine_thickness).
    #[must_use]
    pub const fn with_spine_thickness(mut self, v: Span) -> Self {
        self.spine_thickness = v;
        self
    }
    /// Sets [`spine_length`](Self::spine_length).
    #[must_use]
    pub const fn with_spine_length(mut self, v: Span) -> Self {
        self.spine_length = v;
        self
    }
    /// Sets [`spine_multiplier`](Self::spine_multiplier).
    #[must_use]
    pub const fn with_spine_multiplier(mut self, v: Span) -> Self {
        self.spine_multiplier = v;
        self
    }
    /// Sets [`limb_probability`](Self::limb_probability).
    #[must_use]
    pub const fn with_limb_probability(mut self, v: f32) -> Self {
        self.limb_probability = v;
        self
    }
    /// Sets [`limb_bones`](Self::limb_bones).
    #[must_use]
    pub const fn with_limb_bones(mut self, v: IntSpan) -> Self {
        self.limb_bones = v;
        self
    }
    /// Sets [`limb_length`](Self::limb_length).
    #[must_use]
    pub const fn with_limb_length(mut self, v: Span) -> Self {
        self.limb_length = v;
        self
    }
    /// Sets [`limb_thickness`](Self::limb_thickness).
    #[must_use]
    pub const fn with_limb_thickness(mut self, v: Span) -> Self {
        self.limb_thickness = v;
        self
    }
    /// Sets [`limb_multiplier`](Self::limb_multiplier).
    #[must_use]
    pub const fn with_limb_multiplier(mut self, v: Span) -> Self {
        self.limb_multiplier = v;
        self
    }
    /// Sets [`socket_offset`](Self::socket_offset).
    #[must_use]
    pub const fn with_socket_offset(mut self, v: f32) -> Self {
        self.socket_offset = v;
        self
    }
    /// Sets [`connect_sockets`](Self::connect_sockets).
    #[must_use]
    pub const fn with_connect_sockets(mut self, v: bool) -> Self {
        self.connect_sockets = v;
        self
    }
    /// Sets [`eye_count`](Self::eye_count).
    #[must_use]
    pub const fn with_eye_count(mut self, v: IntSpan) -> Self {
        self.eye_count = v;
        self
    }
    /// Sets [`eye_size`](Self::eye_size).
    #[must_use]
    pub const fn with_eye_size(mut self, v: Span) -> Self {
        self.eye_size = v;
        self
    }
    /// Sets [`outline_step`](Self::outline_step).
    #[must_use]
    pub const fn with_outline_step(mut self, v: f32) -> Self {
        self.outline_step = v;
        self
    }
    /// Sets [`simplify`](Self::simplify).
    #[must_use]
    pub const fn with_simplify(mut self, v: f32) -> Self {
        self.simplify = v;
        self
    }
    /// Sets [`interior_clearance`](Self::interior_clearance).
    #[must_use]
    pub const fn with_interior_clearance(mut self, v: f32) -> Self {
        self.interior_clearance = v;
        self
    }

    /// Sets [`interior_spacing`](Self::interior_spacing).
    #[must_use]
    pub const fn with_interior_spacing(mut self, v: f32) -> Self {
        self.interior_spacing = v;
        self
    }
    /// Sets [`min_angle`](Self::min_angle).
    #[must_use]
    pub const fn with_min_angle(mut self, v: f32) -> Self {
        self.min_angle = v;
        self
    }
    /// Sets [`texture`](Self::texture).
    #[must_use]
    pub const fn with_texture(mut self, v: bool) -> Self {
        self.texture = v;
        self
    }
    /// Sets [`texture_size`](Self::texture_size).
    #[must_use]
    pub const fn with_texture_size(mut self, v: u32) -> Self {
        self.texture_size = v;
        self
    }
    /// Sets [`depth_shading`](Self::depth_shading).
    #[must_use]
    pub const fn with_depth_shading(mut self, v: f32) -> Self {
        self.depth_shading = v;
        self
    }
    /// Sets [`normal_relief`](Self::normal_relief).
    #[must_use]
    pub const fn with_normal_relief(mut self, v: f32) -> Self {
        self.normal_relief = v;
        self
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

    #[test]
    fn defaults_are_valid() {
        assert_eq!(Params::default().validate(), Ok(()));
    }

    #[test]
    fn int_span_draws_the_seed_way() {
        let s = IntSpan::new(3, 6);
        assert_eq!(s.at(0.0), 3);
        assert_eq!(s.at(0.16), 3);
        assert_eq!(s.at(0.17), 4);
        assert_eq!(s.at(0.999_999), 6);
        assert_eq!(IntSpan::new(4, 4).at(0.7), 4);
    }

    #[test]
    fn bad_spans_are_named() {
        let p = Params::DEFAULT.with_spine_length(Span::new(90.0, 50.0));
        assert!(matches!(
            p.validate(),
            Err(Error::EmptyRange {
                what: "spine_length",
                ..
            })
        ));
        let p = Params::DEFAULT.with_limb_thickness(Span::new(f32::NAN, 5.0));
        assert_eq!(
            p.validate(),
            Err(Error::NonFinite {
                what: "limb_thickness"
            })
        );
    }
}
