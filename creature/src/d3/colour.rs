//! Colour: a palette per creature (base, belly, accent) in linear RGB, countershading (the back
//! darker than the belly) and a pattern (stripes, spots, bands, a gradient, or plain) from
//! procedural noise on the body's surface, as vertex colours.
//!
//! The body is coloured on its rest-pose surface, before the spine bends: each vertex of the
//! pill has a place along the body (arc length from the tail tip, × the body length), a place
//! around it (surface distance from the back's midline, × the body length, and the angle from
//! it, × π; the same on both sides, so patterns are mirror-symmetric) and how far up it faces
//! (the sine of its angle around the body's axis: 1 on the back, −1 on the belly). Limbs take
//! the body's colour where they join it and blend to their own along their length, so joins
//! have no seam. Faceted meshes (flat normals) get one colour per quad of the body, so
//! stripes and bands have crisp edges along the rings; spots stay in vertex colours.

use alloc::vec::Vec;
use core::f32::consts::{FRAC_PI_2, PI, TAU};

use glam::Vec3;
use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::wings::Tone;
use crate::Error;
use crate::math::{floor_f, powf, sin};
use crate::rng::uniform;
use crate::span::Span;

/// A body pattern: how the accent colour lies on the skin.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Pattern {
    /// No pattern: the base colour, countershaded.
    Plain,
    /// Narrow stripes across the back and flanks, wavy from noise, thinning toward the belly.
    Stripes,
    /// Round spots of varied size on the back and flanks, in three rows a side.
    Spots,
    /// A few wide, even bands right round the body.
    Bands,
    /// The accent fading in toward the head or toward the tail.
    Gradient,
}

impl Pattern {
    /// Every pattern, in the order [`PatternWeights`] draws them.
    pub const ALL: [Self; 5] = [
        Self::Plain,
        Self::Stripes,
        Self::Spots,
        Self::Bands,
        Self::Gradient,
    ];
}

/// Relative weights of the [`Pattern`]s a creature draws from: pattern `p` is drawn with
/// probability `weight(p) / sum of weights`. Each from 0 to 1000, at least one above 0.
///
/// ```
/// use creature::d3::{Params, Pattern, PatternWeights};
///
/// // Only spots.
/// let params = Params::DEFAULT.with_patterns(PatternWeights::only(Pattern::Spots));
/// params.validate()?;
/// // Stripes twice as likely as by default, never plain.
/// let more_stripes = PatternWeights::DEFAULT
///     .with(Pattern::Stripes, 2.0)
///     .with(Pattern::Plain, 0.0);
/// assert_eq!(more_stripes.weight(Pattern::Stripes), 2.0);
/// # Ok::<(), creature::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct PatternWeights {
    /// Weight of [`Pattern::Plain`]. Default 0.5.
    pub plain: f32,
    /// Weight of [`Pattern::Stripes`]. Default 1.
    pub stripes: f32,
    /// Weight of [`Pattern::Spots`]. Default 1.
    pub spots: f32,
    /// Weight of [`Pattern::Bands`]. Default 0.75.
    pub bands: f32,
    /// Weight of [`Pattern::Gradient`]. Default 0.75.
    pub gradient: f32,
}

impl PatternWeights {
    /// The defaults listed on each field: a pattern in nine creatures of ten.
    pub const DEFAULT: Self = Self {
        plain: 0.5,
        stripes: 1.0,
        spots: 1.0,
        bands: 0.75,
        gradient: 0.75,
    };

    /// Weight 1 for `pattern`, 0 for the others: every creature gets `pattern`.
    #[must_use]
    pub const fn only(pattern: Pattern) -> Self {
        let none = Self {
            plain: 0.0,
            stripes: 0.0,
            spots: 0.0,
            bands: 0.0,
            gradient: 0.0,
        };
        none.with(pattern, 1.0)
    }

    /// Sets the weight of `pattern`.
    #[must_use]
    pub const fn with(mut self, pattern: Pattern, weight: f32) -> Self {
        match pattern {
            Pattern::Plain => self.plain = weight,
            Pattern::Stripes => self.stripes = weight,
            Pattern::Spots => self.spots = weight,
            Pattern::Bands => self.bands = weight,
            Pattern::Gradient => self.gradient = weight,
        }
        self
    }

    /// The weight of `pattern`.
    #[must_use]
    pub const fn weight(&self, pattern: Pattern) -> f32 {
        match pattern {
            Pattern::Plain => self.plain,
            Pattern::Stripes => self.stripes,
            Pattern::Spots => self.spots,
            Pattern::Bands => self.bands,
            Pattern::Gradient => self.gradient,
        }
    }

    /// Checks every weight is finite and from 0 to 1000, and one is above 0.
    pub(crate) fn check(&self, what: &'static str) -> Result<(), Error> {
        crate::rng::check_weights(what, &Pattern::ALL.map(|p| self.weight(p)))
    }

    /// The pattern at `u` in `[0, 1)` of the weights' cumulative sum.
    fn pick(&self, u: f32) -> Pattern {
        let weights = Pattern::ALL.map(|p| self.weight(p));
        Pattern::ALL[crate::rng::pick_weighted(&weights, u)]
    }
}

impl Default for PatternWeights {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A creature's colours, in linear RGB, each channel in `[0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Palette {
    /// The body's colour on its flanks (darker on the back with countershading).
    pub base: Vec3,
    /// The belly's colour: the base's hue, lighter and less saturated.
    pub belly: Vec3,
    /// The pattern's colour, also on feet, wings and fins: a darker or lighter shade of the
    /// base, or a complementary or neighbouring hue.
    pub accent: Vec3,
    /// The pattern drawn.
    pub pattern: Pattern,
}

/// Where a body vertex lies on the rest-pose surface (see the module docs).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct SurfacePoint {
    /// Arc length from the tail tip, × the body length: 0 at the tail, 1 at the head.
    pub(crate) along: f32,
    /// Surface distance from the back's midline around the body, × the body length.
    pub(crate) around: f32,
    /// The angle from the back's midline around the body, × π: 0 on the back, 1 on the
    /// belly's midline.
    pub(crate) across: f32,
    /// Sine of the angle around the body's axis: 1 on the back, −1 on the belly.
    pub(crate) up: f32,
}

impl SurfacePoint {
    /// The mean of some places (a face's middle).
    fn mean(points: impl Iterator<Item = Self>) -> Self {
        let (mut sum, mut n) = (Self::default(), 0.0f32);
        for p in points {
            sum.along += p.along;
            sum.around += p.around;
            sum.across += p.across;
            sum.up += p.up;
            n += 1.0;
        }
        let n = n.max(1.0);
        Self {
            along: sum.along / n,
            around: sum.around / n,
            across: sum.across / n,
            up: sum.up / n,
        }
    }
}

/// The surface places of the pill's vertices (tail tip, `rings` rings of `segments`, head
/// tip; see `body::pill_triangles`) at `positions`, the body before the spine bends. Any other
/// vertex count gives every vertex the middle of the flank.
pub(crate) fn body_surface(positions: &[Vec3], rings: usize, segments: usize) -> Vec<SurfacePoint> {
    let flank = SurfacePoint {
        along: 0.5,
        around: 0.0,
        across: 0.5,
        up: 0.0,
    };
    if rings == 0 || segments == 0 || positions.len() != 2 + rings * segments {
        return alloc::vec![flank; positions.len()];
    }
    // Per ring: the arc length of its centre from the tail tip, and its mean radius.
    let per = 1.0 / segments as f32;
    let mut rings_at = Vec::with_capacity(rings);
    let (mut previous, mut total) = (positions[0], 0.0f32);
    for ring in positions[1..1 + rings * segments].chunks_exact(segments) {
        let centre = ring.iter().copied().sum::<Vec3>() * per;
        total += previous.distance(centre);
        previous = centre;
        let radius = ring.iter().map(|p| p.distance(centre)).sum::<f32>() * per;
        rings_at.push((total, radius));
    }
    total += previous.distance(positions[positions.len() - 1]);
    let length = total.max(1e-6);
    // Per segment: the angle from the back's midline and the sine. The pill's vertex `j`
    // sits at angle `a` around the axis (x = cos, y = sin): the back's midline is at π/2,
    // the belly's at 3π/2.
    let columns: Vec<(f32, f32)> = (0..segments)
        .map(|j| {
            let a = TAU * j as f32 / segments as f32;
            let from_back = a - FRAC_PI_2;
            let from_back = if from_back > PI {
                from_back - TAU
            } else {
                from_back
            };
            (from_back.abs(), sin(a))
        })
        .collect();
    let mut out = Vec::with_capacity(positions.len());
    out.push(SurfacePoint {
        along: 0.0,
        around: 0.0,
        across: 0.5,
        up: 0.0,
    });
    for &(arc, radius) in &rings_at {
        let along = arc / length;
        let around = radius / length;
        out.extend(columns.iter().map(|&(angle, up)| SurfacePoint {
            along,
            around: angle * around,
            across: angle * (1.0 / PI),
            up,
        }));
    }
    out.push(SurfacePoint {
        along: 1.0,
        around: 0.0,
        across: 0.5,
        up: 0.0,
    });
    out
}

/// The colour parameters of [`Params`](crate::d3::Params), checked by its `validate`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ColourParams {
    pub(crate) saturation: Span,
    pub(crate) countershading: Span,
    pub(crate) patterns: PatternWeights,
    /// The body's rings: patterns are kept coarse enough for the mesh to show them.
    pub(crate) rings: usize,
}

/// The body's colours from [`Colouring::paint_body`].
#[derive(Debug, Clone, Default)]
pub(crate) struct BodyPaint {
    /// One per body vertex.
    pub(crate) vertices: Vec<Vec3>,
    /// One per body triangle, for a faceted mesh (not for spots).
    pub(crate) faces: Option<Vec<Vec3>>,
    /// The colours' back–belly contrast, as shown: the faces' (by the mean of their corners'
    /// facing) when there are faces, else the vertices' (see [`Quality::belly_contrast`](
    /// crate::d3::Quality::belly_contrast)).
    pub(crate) contrast: f32,
}

/// Everything that colours one creature, drawn once from its seed.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Colouring {
    pub(crate) palette: Palette,
    /// Countershading strength in `[0, 1]`.
    countershade: f32,
    /// The legs' and arms' colour away from the body.
    limb: Vec3,
    /// Wings' and fins' colour away from the body.
    membrane: Vec3,
    /// Whether the accent is lighter than the base.
    light_accent: bool,
    /// The colour of feet and hands on some creatures (the accent when it is a shade of the
    /// base, else a dark base).
    socks: Option<Vec3>,
    /// The pattern's shape: its frequency along the body (per body length), a second
    /// frequency or size, a phase, how wavy or slanted it is, and its noise seed.
    frequency: f32,
    width: f32,
    phase: f32,
    wave: f32,
    slant: f32,
    noise: u32,
    /// The seed of the colouring's own generator, for [`Colouring::head_rng`].
    seed: u64,
}

impl Colouring {
    /// Draws a creature's colouring. Takes exactly three 32-bit draws from `rng` (the stream
    /// the rest of the pipeline shares) and seeds its own generator from them, so the colours
    /// can change without changing any shape.
    /// `salt` tells apart creatures whose streams are alike up to here (the kinds of one seed).
    pub(crate) fn draw(rng: &mut impl Rng, params: &ColourParams, salt: u64) -> Self {
        let key = [rng.next_u32(), rng.next_u32(), rng.next_u32()];
        let seed = (u64::from(key[0]) << 32 | u64::from(key[1]))
            ^ u64::from(key[2]).rotate_left(17)
            ^ salt.wrapping_mul(0x9e37_79b9_7f4a_7c15);
        let mut own = Pcg64Mcg::seed_from_u64(seed);
        let mut u = || uniform(&mut own);

        // Mostly the hues of animals: earth (reds, browns, ochres), then greens and olives,
        // then cool blues and greys; one creature in six any hue at all.
        let (family, within) = (u(), u());
        let hue = if family < 0.45 {
            0.02 + 0.12 * within
        } else if family < 0.7 {
            0.17 + 0.2 * within
        } else if family < 0.83 {
            0.5 + 0.14 * within
        } else {
            within
        };
        let saturation = params.saturation.at(u());
        let value = 0.38 + 0.3 * u();
        let base = hsv(hue, saturation, value);
        let belly = hsv(
            hue + 0.04 * (u() - 0.5),
            0.35 * saturation,
            (value + 0.28 + 0.1 * u()).min(0.97),
        );
        // Darker or lighter than the base by a quarter of the value scale, whichever fits.
        let shifted_value = if value > 0.55 {
            value - 0.27
        } else {
            value + 0.27
        };
        let (mode, spread) = (u(), u() - 0.5);
        let shade = mode < 0.55;
        let dark = hsv(
            hue + 0.06 * spread,
            (1.2 * saturation + 0.1).min(1.0),
            0.3 * value,
        );
        let pale = hsv(hue, 0.2 * saturation, 0.95);
        let accent = if mode < 0.35 {
            // A dark shade: tiger stripes, a dark saddle.
            dark
        } else if mode < 0.55 {
            // A pale shade: fawn spots, white bands.
            pale
        } else if mode < 0.8 {
            // The complementary hue (give or take a twelfth of the wheel).
            hsv(hue + 0.5 + 0.16 * spread, saturation, shifted_value)
        } else {
            // A neighbouring hue, a tenth of the wheel or so either way.
            let step = if spread < 0.0 { -0.12 } else { 0.12 } + 0.08 * spread;
            hsv(hue + step, saturation, shifted_value)
        };
        // Too close to the base in lightness to be seen (a dark shade on a dark base): the
        // pale or dark shade, whichever is farther from the base.
        let accent = if contrast(accent, base) >= MIN_CONTRAST {
            accent
        } else if contrast(pale, base) >= contrast(dark, base) {
            pale
        } else {
            dark
        };
        // An accent lighter than the base must not outshine the belly on the back: the belly
        // a cream then, unless it is well lighter than the accent.
        let lighter = luminance(accent) > luminance(base);
        let belly = if lighter && luminance(belly) < 1.4 * luminance(accent) + 0.05 {
            hsv(hue, 0.15 * saturation, 0.97)
        } else {
            belly
        };
        let pattern = params.patterns.pick(u());
        let countershade = params.countershading.at(u());
        let socks = (u() < 0.3).then_some(if shade { accent } else { base * 0.35 });
        let limb = base * 0.85;
        let membrane = accent.lerp(belly, 0.45);

        // The finest a pattern may be: one period over at least three rings.
        let finest = (params.rings as f32 + 1.0) / 3.0;
        let (frequency, width) = match pattern {
            Pattern::Stripes => ((5.0 + 5.0 * u()).min(finest), 0.3 + 0.15 * u()),
            // Cells along the body, and the spots' radius × the cell.
            Pattern::Spots => ((3.0 + 2.0 * u()).min(finest), 0.32 + 0.1 * u()),
            Pattern::Bands => ((2.0 + 3.0 * u()).min(finest), 0.28 + 0.14 * u()),
            // Where the fade starts along the body, and its length.
            Pattern::Gradient => (0.2 + 0.3 * u(), 0.35 + 0.3 * u()),
            Pattern::Plain => (1.0, 0.0),
        };
        Self {
            palette: Palette {
                base,
                belly,
                accent,
                pattern,
            },
            countershade,
            light_accent: lighter,
            limb,
            membrane,
            socks,
            frequency,
            width,
            phase: u(),
            wave: 0.15 + 0.25 * u(),
            slant: u() - 0.5,
            noise: own.next_u32(),
            seed,
        }
    }

    /// A generator of its own for the head's shape, seeded from the colouring's seed: the head
    /// draws nothing from the pipeline's stream, so it can change without changing the body,
    /// the limbs or the colours.
    pub(crate) fn head_rng(&self) -> Pcg64Mcg {
        Pcg64Mcg::seed_from_u64(self.seed ^ 0x4ead_4ead_4ead_4ead)
    }

    /// A generator of its own for the limbs' proportions (feet, thighs, wings), as
    /// [`head_rng`](Self::head_rng) is for the head.
    pub(crate) fn limb_rng(&self) -> Pcg64Mcg {
        Pcg64Mcg::seed_from_u64(self.seed ^ 0x1146_1146_1146_1146)
    }

    /// A generator of its own for the back's ornaments, as [`head_rng`](Self::head_rng) is
    /// for the head.
    pub(crate) fn back_rng(&self) -> Pcg64Mcg {
        Pcg64Mcg::seed_from_u64(self.seed ^ 0xbac4_bac4_bac4_bac4)
    }

    /// A generator of its own for the gait's style (whether a biped hops), as
    /// [`head_rng`](Self::head_rng) is for the head.
    pub(crate) fn gait_rng(&self) -> Pcg64Mcg {
        Pcg64Mcg::seed_from_u64(self.seed ^ 0x6a17_6a17_6a17_6a17)
    }

    /// How far toward the belly colour the skin facing `up` (1 back, −1 belly) goes, and how
    /// much darker it is.
    fn countershading(&self, up: f32) -> (f32, f32) {
        (
            self.countershade * smoothstep(0.2, -0.6, up),
            0.35 * self.countershade * up.max(0.0),
        )
    }

    /// The countershaded skin facing `up` without a pattern.
    fn plain(&self, up: f32) -> Vec3 {
        let (toward_belly, darken) = self.countershading(up);
        self.palette.base.lerp(self.palette.belly, toward_belly) * (1.0 - darken)
    }

    /// The countershaded skin facing `up`: without a pattern, and in the accent (countershaded
    /// by half, so bands and gradients lighten on the belly too, and a pale pattern does not
    /// turn tartan over the back's facets).
    fn shaded(&self, up: f32) -> (Vec3, Vec3) {
        let (toward_belly, darken) = self.countershading(up);
        let p = &self.palette;
        (
            self.plain(up),
            p.accent.lerp(p.belly, 0.5 * toward_belly) * (1.0 - 0.5 * darken),
        )
    }

    /// How much of the accent the pattern puts at `s`, in `[0, 1]`.
    fn pattern(&self, s: SurfacePoint) -> f32 {
        // Patterns on the back and flanks fade out on the belly.
        let topside = smoothstep(-0.75, -0.1, s.up);
        match self.palette.pattern {
            Pattern::Plain => 0.0,
            Pattern::Stripes => {
                let warp =
                    self.wave * (value_noise(3.0 * s.along, 3.0 * s.around, self.noise) - 0.5);
                let x =
                    self.frequency * (s.along + 0.4 * self.slant * s.around) + warp + self.phase;
                // Stripes thin and fade toward the belly.
                let half = self.width * (0.5 + 0.5 * topside);
                topside * (1.0 - smoothstep(half - 0.08, half + 0.08, triangle(x)))
            }
            Pattern::Spots => {
                let cells = self.frequency;
                // Three rows of cells from the back's midline to the belly's, whatever the
                // body's girth (spots a vertex or two across, on a thin body too), the first
                // centred on the back (its spots mirrored into one); alternate rows shifted
                // half a cell along, so spots do not line up.
                let (cy_f, y) = split(3.0 * s.across + 0.5);
                let row = cy_f as i32;
                let (cx_f, x) = split(cells * s.along + self.phase + 0.5 * (row & 1) as f32);
                let cell = (cx_f as i32, row);
                let h = hash(cell.0, cell.1, self.noise);
                // Two cells in three hold a spot, its centre kept inside the cell.
                if unit(h) >= 0.67 {
                    return 0.0;
                }
                let centre = (
                    0.5 + 0.3 * (unit(hash(cell.0, cell.1, self.noise ^ 0x9e37_79b9)) - 0.5),
                    0.5 + 0.3 * (unit(hash(cell.0, cell.1, self.noise ^ 0x85eb_ca6b)) - 0.5),
                );
                let radius = self.width * (0.7 + 0.45 * unit(h.rotate_left(11)));
                let (dx, dy) = (x - centre.0, y - centre.1);
                let d = crate::math::sqrt(dx * dx + dy * dy);
                topside * (1.0 - smoothstep(radius - 0.06, radius + 0.06, d))
            }
            Pattern::Bands => {
                let x = self.frequency * s.along + self.phase;
                1.0 - smoothstep(self.width - 0.06, self.width + 0.06, triangle(x))
            }
            Pattern::Gradient => {
                let t = if self.phase < 0.5 {
                    s.along
                } else {
                    1.0 - s.along
                };
                smoothstep(self.frequency, self.frequency + self.width, t)
            }
        }
    }

    /// The body's colour at `s`.
    pub(crate) fn skin(&self, s: SurfacePoint) -> Vec3 {
        let amount = self.pattern(s);
        if amount <= 0.0 {
            return clamp01(self.plain(s.up));
        }
        self.patterned(s, amount, self.shaded(s.up))
    }

    /// The skin at `s` given the plain and accent colours there (see
    /// [`shaded`](Self::shaded)).
    fn skin_in(&self, s: SurfacePoint, shade: (Vec3, Vec3)) -> Vec3 {
        let amount = self.pattern(s);
        if amount > 0.0 {
            self.patterned(s, amount, shade)
        } else {
            clamp01(shade.0)
        }
    }

    /// The skin at `s` with the pattern's `amount` (above 0) of the accent, given the plain
    /// and accent colours there (see [`shaded`](Self::shaded)).
    fn patterned(&self, s: SurfacePoint, amount: f32, (shaded, accent): (Vec3, Vec3)) -> Vec3 {
        // Light spots thin out along the spine (the pattern that covers it most: a spot on
        // the midline is mirrored into a broad one), so they never make the back as light as
        // the belly.
        let thinned = if self.light_accent && self.palette.pattern == Pattern::Spots {
            1.0 - 0.5 * self.countershade * s.up.max(0.0)
        } else {
            1.0
        };
        clamp01(shaded.lerp(accent, amount * thinned))
    }

    /// The body's colours: per vertex (at its place on the surface), and for a `faceted`
    /// mesh (flat normals) per triangle too (see [`body_faces`](Self::body_faces)), the
    /// vertices then taking the colour of a face they belong to (so limbs join the colour
    /// shown, and the measured contrast is that of the faces).
    pub(crate) fn paint_body(
        &self,
        surface: &[SurfacePoint],
        triangles: &[[u32; 3]],
        segments: usize,
        faceted: bool,
    ) -> BodyPaint {
        let up = |i: u32| surface.get(i as usize).map_or(0.0, |s| s.up);
        if faceted && self.palette.pattern != Pattern::Spots {
            let (faces, vertices) = self.body_faces(surface, triangles, segments);
            let facing = triangles
                .iter()
                .map(|t| (up(t[0]) + up(t[1]) + up(t[2])) / 3.0);
            BodyPaint {
                contrast: belly_contrast(faces.iter().copied().zip(facing)),
                vertices,
                faces: Some(faces),
            }
        } else {
            let vertices = self.body_vertices(surface, segments);
            BodyPaint {
                contrast: belly_contrast(
                    vertices.iter().copied().zip(surface.iter().map(|s| s.up)),
                ),
                vertices,
                faces: None,
            }
        }
    }

    /// The skin at each vertex of the pill: `surface` as [`body_surface`] gives it, its rings'
    /// vertices sharing their columns' plain and accent colours.
    fn body_vertices(&self, surface: &[SurfacePoint], segments: usize) -> Vec<Vec3> {
        if segments == 0 || surface.len() < 2 + segments {
            return surface.iter().map(|&s| self.skin(s)).collect();
        }
        let shades: Vec<(Vec3, Vec3)> = surface[1..=segments]
            .iter()
            .map(|s| self.shaded(s.up))
            .collect();
        let last = surface.len() - 1;
        surface
            .iter()
            .enumerate()
            .map(|(k, &s)| {
                if k == 0 || k == last {
                    return self.skin(s);
                }
                self.skin_in(s, shades[(k - 1) % segments])
            })
            .collect()
    }

    /// One colour per triangle of the body (`triangles`, the pill's: a fan at each tip, two
    /// triangles per quad between rings), for faceted meshes: the skin's at the middle of the
    /// triangle's quad (at the tips, of the triangle), so each quad is one colour and a
    /// pattern's edges follow the rings and segments rather than zigzag across the quads'
    /// diagonals. Not for spots: on the default body a spot is a quad or two across, so it
    /// stays in vertex colours, round and soft where one colour per quad would square it.
    /// Also one colour per vertex: that of a face it belongs to.
    fn body_faces(
        &self,
        surface: &[SurfacePoint],
        triangles: &[[u32; 3]],
        segments: usize,
    ) -> (Vec<Vec3>, Vec<Vec3>) {
        let at = |i: u32| surface.get(i as usize).copied().unwrap_or_default();
        let by_triangle = |t: &[u32; 3]| self.skin(SurfacePoint::mean(t.iter().map(|&i| at(i))));
        let rings = surface.len().saturating_sub(2) / segments.max(1);
        if segments == 0 || rings == 0 || triangles.len() != 2 * rings * segments {
            // Not the pill's layout: a colour per triangle, each vertex its first face's
            // (backwards, so the first face is written last).
            let faces: Vec<Vec3> = triangles.iter().map(by_triangle).collect();
            let mut vertices = alloc::vec![self.palette.base; surface.len()];
            for (t, &colour) in triangles.iter().zip(&faces).rev() {
                for &i in t {
                    if let Some(v) = vertices.get_mut(i as usize) {
                        *v = colour;
                    }
                }
            }
            return (faces, vertices);
        }
        // The quads between columns `j` and `j + 1` all face the same way: their plain and
        // accent colours once per column.
        // Column `j`'s neighbour around the ring.
        let next = |j: usize| if j + 1 == segments { 0 } else { j + 1 };
        let v = |i: usize, j: usize| 1 + i * segments + j;
        let shades: Vec<(Vec3, Vec3)> = (0..segments)
            .map(|j| self.shaded(0.5 * (at(v(0, j) as u32).up + at(v(0, next(j)) as u32).up)))
            .collect();
        let mut out = Vec::with_capacity(triangles.len());
        // The tail's fan, the quads ring by ring (two triangles each), the head's fan.
        out.extend(triangles[..segments].iter().map(by_triangle));
        for i in 0..rings - 1 {
            for (j, &shade) in shades.iter().enumerate() {
                // The quad's middle: halfway along between its rings, halfway around between
                // its columns (as the mean of its corners).
                let (a, b) = (surface[v(i, j)], surface[v(i, next(j))]);
                let (c, d) = (surface[v(i + 1, j)], surface[v(i + 1, next(j))]);
                let middle = SurfacePoint {
                    along: 0.5 * (a.along + c.along),
                    around: 0.25 * (a.around + b.around + c.around + d.around),
                    across: 0.5 * (a.across + b.across),
                    up: 0.5 * (a.up + b.up),
                };
                out.extend([self.skin_in(middle, shade); 2]);
            }
        }
        out.extend(
            triangles[triangles.len() - segments..]
                .iter()
                .map(by_triangle),
        );
        // Vertex (i, j): the quad it is the first corner of (of the ring before, on the last
        // ring; with one ring, the tail's fan); the tips, their fans' first.
        let quad = |i: usize, j: usize| out[segments + 2 * (i * segments + j)];
        let mut vertices = Vec::with_capacity(surface.len());
        vertices.push(out[0]);
        for i in 0..rings {
            vertices.extend((0..segments).map(|j| match i {
                _ if rings == 1 => out[j],
                i if i + 1 < rings => quad(i, j),
                i => quad(i - 1, j),
            }));
        }
        vertices.push(out[out.len() - segments]);
        (out, vertices)
    }

    /// The head's colour facing `up`: countershaded, in the body's colour at its head end
    /// (a gradient's end colour; stripes, spots and bands stay on the body).
    pub(crate) fn head(&self, up: f32) -> Vec3 {
        if self.palette.pattern != Pattern::Gradient {
            return clamp01(self.plain(up));
        }
        let (shaded, accent) = self.shaded(up);
        let amount = self.pattern(SurfacePoint {
            along: 1.0,
            around: 0.0,
            across: 0.5,
            up,
        });
        clamp01(shaded.lerp(accent, amount))
    }

    /// A limb's colour at `reach` (0 where it joins the body, 1 at its far end) given the
    /// body's colour `root` at the join: the body's colour blending into the limb's own
    /// (legs and arms a darker base, with accent feet or hands on some creatures; wings and
    /// fins a pale accent).
    pub(crate) fn limb(&self, root: Vec3, membrane: bool, reach: f32) -> Vec3 {
        let c = if membrane {
            root.lerp(self.membrane, smoothstep(0.05, 0.5, reach))
        } else {
            let c = root.lerp(self.limb, smoothstep(0.1, 0.6, reach));
            match self.socks {
                Some(socks) => c.lerp(socks, smoothstep(0.72, 0.85, reach)),
                None => c,
            }
        };
        clamp01(c)
    }
}

impl Colouring {
    /// A wing's colour in `tone`, from its membrane colour `c` there: bones and veins a strong
    /// shade of it, an insect's membrane pale, coverts toward the body's base colour, and
    /// feathers' tips a contrasting shade (darker on a light wing, lighter on a dark one).
    pub(crate) fn wing_tone(&self, c: Vec3, tone: Tone) -> Vec3 {
        let shade = |amount: f32| {
            if luminance(c) > 0.12 {
                c * (1.0 - amount)
            } else {
                c.lerp(Vec3::ONE, 0.6 * amount)
            }
        };
        clamp01(match tone {
            Tone::Skin => c,
            Tone::Bone => shade(0.6),
            Tone::Pale => c.lerp(Vec3::splat(0.85), 0.6),
            Tone::Covert => c.lerp(self.palette.base, 0.7),
            Tone::Tip => shade(0.5),
        })
    }
}

/// The least luminance contrast (see [`contrast`]) between the accent and the base.
const MIN_CONTRAST: f32 = 2.5;

/// The luminance contrast of two colours: the lighter's relative luminance plus 0.05 over the
/// darker's plus 0.05 (WCAG's ratio; 1 for equal luminance, 21 for black on white).
fn contrast(a: Vec3, b: Vec3) -> f32 {
    let (la, lb) = (luminance(a) + 0.05, luminance(b) + 0.05);
    la.max(lb) / la.min(lb)
}

/// Relative luminance of a linear RGB colour (Rec. 709 weights).
#[must_use]
pub(crate) fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// The mean luminance of the colours facing down (`up < −0.5`) minus that of those facing up
/// (`up > 0.5`), of `(colour, up)` pairs; 0 when either set is empty.
fn belly_contrast(colours: impl Iterator<Item = (Vec3, f32)>) -> f32 {
    let (mut back, mut belly) = ((0.0f32, 0u32), (0.0f32, 0u32));
    for (c, up) in colours {
        if up > 0.5 {
            back = (back.0 + luminance(c), back.1 + 1);
        } else if up < -0.5 {
            belly = (belly.0 + luminance(c), belly.1 + 1);
        }
    }
    if back.1 == 0 || belly.1 == 0 {
        return 0.0;
    }
    belly.0 / belly.1 as f32 - back.0 / back.1 as f32
}

/// An sRGB-encoded channel in `[0, 1]` to linear.
#[must_use]
pub(crate) fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.040_45 {
        c / 12.92
    } else {
        powf((c + 0.055) / 1.055, 2.4)
    }
}

/// A linear channel to sRGB encoding, clamped to `[0, 1]` (NaN gives 0).
#[must_use]
pub(crate) fn linear_to_srgb(c: f32) -> f32 {
    let c = if c > 0.0 { c.min(1.0) } else { 0.0 };
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * powf(c, 1.0 / 2.4) - 0.055
    }
}

/// Hue (turns, any value), saturation and value of an sRGB colour, as linear RGB.
fn hsv(hue: f32, saturation: f32, value: f32) -> Vec3 {
    let h = (hue - floor_f(hue)) * 6.0;
    let (s, v) = (saturation.clamp(0.0, 1.0), value.clamp(0.0, 1.0));
    let channel = |n: f32| {
        let k = n + h;
        let k = if k >= 6.0 { k - 6.0 } else { k };
        v - v * s * k.min(4.0 - k).clamp(0.0, 1.0)
    };
    clamp01(Vec3::new(
        srgb_to_linear(channel(5.0)),
        srgb_to_linear(channel(3.0)),
        srgb_to_linear(channel(1.0)),
    ))
}

fn clamp01(c: Vec3) -> Vec3 {
    c.clamp(Vec3::ZERO, Vec3::ONE)
}

/// 0 below `a`, 1 above `b` (or the other way round when `a > b`), smooth between.
fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// A triangle wave of period 1: 0 at whole numbers, 1 halfway between.
fn triangle(x: f32) -> f32 {
    2.0 * (x - floor_f(x) - 0.5).abs()
}

/// `x` as its whole part and its fraction.
fn split(x: f32) -> (f32, f32) {
    let whole = floor_f(x);
    (whole, x - whole)
}

/// A 32-bit hash of a lattice cell and a seed (a multiply–xorshift finaliser).
fn hash(x: i32, y: i32, seed: u32) -> u32 {
    let mut h = seed
        ^ (x as u32).wrapping_mul(0x27d4_eb2d)
        ^ (y as u32).wrapping_mul(0x1656_67b1).rotate_left(16);
    h ^= h >> 15;
    h = h.wrapping_mul(0x85eb_ca6b);
    h ^= h >> 13;
    h = h.wrapping_mul(0xc2b2_ae35);
    h ^ (h >> 16)
}

/// A hash as a number in `[0, 1)`.
fn unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Smooth value noise in `[0, 1]` on the unit lattice.
fn value_noise(x: f32, y: f32, seed: u32) -> f32 {
    let (cx, fx) = split(x);
    let (cy, fy) = split(y);
    let (ix, iy) = (cx as i32, cy as i32);
    let corner = |dx: i32, dy: i32| unit(hash(ix.wrapping_add(dx), iy.wrapping_add(dy), seed));
    let [a, b, c, d] = [corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1)];
    let (sx, sy) = (fx * fx * (3.0 - 2.0 * fx), fy * fy * (3.0 - 2.0 * fy));
    let bottom = a + (b - a) * sx;
    let top = c + (d - c) * sx;
    bottom + (top - bottom) * sy
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::rng_for;

    fn params() -> ColourParams {
        ColourParams {
            saturation: Span::new(0.3, 0.75),
            countershading: Span::new(0.6, 1.0),
            patterns: PatternWeights::DEFAULT,
            rings: 16,
        }
    }

    fn in_unit_cube(c: Vec3) -> bool {
        c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0
    }

    #[test]
    fn bellies_are_lighter_than_backs_and_accents_stand_out() {
        for seed in 0..500 {
            let c = Colouring::draw(&mut rng_for(seed), &params(), 0);
            let p = c.palette;
            assert!(in_unit_cube(p.base) && in_unit_cube(p.belly) && in_unit_cube(p.accent));
            let back = c.shaded(1.0).0;
            let belly = c.shaded(-1.0).0;
            assert!(
                luminance(belly) - luminance(back) >= 0.1,
                "seed {seed}: back {back} belly {belly}"
            );
            let ratio = contrast(p.accent, p.base);
            assert!(
                ratio >= MIN_CONTRAST,
                "seed {seed}: base {} accent {}: {ratio}",
                p.base,
                p.accent
            );
        }
    }

    #[test]
    fn srgb_round_trips() {
        for i in 0..=100 {
            let c = i as f32 / 100.0;
            assert!((linear_to_srgb(srgb_to_linear(c)) - c).abs() < 1e-4, "{c}");
        }
        assert_eq!(linear_to_srgb(f32::NAN), 0.0);
        assert!((linear_to_srgb(2.0) - 1.0).abs() < 1e-6);
        let red = hsv(0.0, 1.0, 1.0);
        assert!((red - Vec3::X).length() < 1e-6, "{red}");
        let green = hsv(1.0 / 3.0, 1.0, 1.0);
        assert!((green - Vec3::Y).length() < 1e-5, "{green}");
    }

    #[test]
    fn weights_pick_only_weighted_patterns() {
        for p in Pattern::ALL {
            let only = PatternWeights::only(p);
            for i in 0..100 {
                assert_eq!(only.pick(i as f32 / 100.0), p);
            }
        }
        let two = PatternWeights::only(Pattern::Spots).with(Pattern::Bands, 3.0);
        let bands = (0..100)
            .filter(|&i| two.pick(i as f32 / 100.0) == Pattern::Bands)
            .count();
        assert_eq!(bands, 75);
        assert!(PatternWeights::DEFAULT.check("patterns").is_ok());
        let none = PatternWeights::only(Pattern::Plain).with(Pattern::Plain, 0.0);
        assert_eq!(
            none.check("patterns"),
            Err(Error::AllZero { what: "patterns" })
        );
        assert!(matches!(
            PatternWeights::DEFAULT
                .with(Pattern::Spots, -1.0)
                .check("patterns"),
            Err(Error::OutOfRange { .. })
        ));
        assert_eq!(
            PatternWeights::DEFAULT
                .with(Pattern::Bands, f32::NAN)
                .check("patterns"),
            Err(Error::NonFinite { what: "patterns" })
        );
    }

    /// A body's surface: 16 rings of 10 along a unit-radius tube 4 long.
    fn tube() -> Vec<SurfacePoint> {
        let (rings, segments) = (16, 10);
        let mut p = alloc::vec![Vec3::new(0.0, 0.0, -2.0)];
        for i in 0..rings {
            let z = -2.0 + 4.0 * (i + 1) as f32 / (rings + 1) as f32;
            for j in 0..segments {
                let a = TAU * j as f32 / segments as f32;
                p.push(Vec3::new(crate::math::cos(a), sin(a), z));
            }
        }
        p.push(Vec3::new(0.0, 0.0, 2.0));
        body_surface(&p, rings, segments)
    }

    #[test]
    fn surface_places_run_tail_to_head_and_back_to_belly() {
        let s = tube();
        assert_eq!(s.len(), 2 + 160);
        assert_eq!(s[0].along, 0.0);
        assert_eq!(s[161].along, 1.0);
        for w in s.windows(2) {
            assert!(w[1].along >= w[0].along);
        }
        // Ring 0, vertex 0 faces sideways; vertex 2.5 would be the back (π/2 of 10 steps).
        assert!(s[1].up.abs() < 1e-6);
        let top = s[1..11].iter().map(|p| p.up).fold(f32::MIN, f32::max);
        assert!(top > 0.9);
        // Mirror-symmetric: vertex j and 5 − j (mirrored about the back) alike.
        for j in 0..=5 {
            assert!((s[1 + j].around - s[1 + (5 + 10 - j) % 10].around).abs() < 1e-6);
        }
        // Not a pill: everything on the flank.
        assert!(
            body_surface(&[Vec3::ZERO; 5], 16, 10)
                .iter()
                .all(|p| p.up == 0.0)
        );
    }

    #[test]
    fn patterns_vary_along_the_body_and_plain_does_not() {
        let surface = tube();
        for pattern in Pattern::ALL {
            let params = ColourParams {
                patterns: PatternWeights::only(pattern),
                ..params()
            };
            for seed in 0..40 {
                let c = Colouring::draw(&mut rng_for(seed), &params, 0);
                assert_eq!(c.palette.pattern, pattern);
                // The flank's vertices along the body (vertex 0 of each ring).
                let amounts: Vec<f32> = (0..16).map(|i| c.pattern(surface[1 + 10 * i])).collect();
                let (lo, hi) = amounts
                    .iter()
                    .fold((f32::MAX, f32::MIN), |(a, b), &x| (a.min(x), b.max(x)));
                if pattern == Pattern::Plain {
                    assert_eq!(hi, 0.0);
                } else if pattern != Pattern::Spots {
                    assert!(hi - lo > 0.5, "{pattern:?} seed {seed}: {amounts:?}");
                }
                // Spots: somewhere on the back and flanks.
                if pattern == Pattern::Spots {
                    let any = surface
                        .iter()
                        .filter(|s| s.up > -0.5)
                        .map(|&s| c.pattern(s))
                        .fold(0.0f32, f32::max);
                    let count = surface.iter().filter(|&&s| c.pattern(s) > 0.5).count();
                    assert!(any > 0.5 && count >= 4, "spots seed {seed}: {count}");
                }
                for &s in &surface {
                    assert!(in_unit_cube(c.skin(s)));
                }
            }
        }
    }

    #[test]
    fn faceted_bodies_colour_each_quad_once() {
        let surface = tube();
        let triangles = crate::d3::body::pill_triangles(16, 10);
        for pattern in Pattern::ALL {
            let params = ColourParams {
                patterns: PatternWeights::only(pattern),
                ..params()
            };
            let c = Colouring::draw(&mut rng_for(11), &params, 0);
            let paint = c.paint_body(&surface, &triangles, 10, true);
            let smooth = c.paint_body(&surface, &triangles, 10, false);
            assert!(smooth.faces.is_none());
            assert_eq!(smooth.vertices.len(), surface.len());
            for (k, &s) in surface.iter().enumerate() {
                assert_eq!(smooth.vertices[k], c.skin(s), "{pattern:?} vertex {k}");
            }
            let Some(faces) = paint.faces else {
                assert_eq!(pattern, Pattern::Spots, "only spots stay in vertex colours");
                assert_eq!(paint.vertices, smooth.vertices);
                continue;
            };
            assert_eq!(faces.len(), triangles.len());
            // The two triangles of a quad alike, in the skin's colour at the quad's middle.
            for q in 0..15 * 10 {
                let (a, b) = (10 + 2 * q, 11 + 2 * q);
                assert_eq!(faces[a], faces[b], "{pattern:?} quad {q}");
                let corners = [
                    triangles[a][0],
                    triangles[a][1],
                    triangles[a][2],
                    triangles[b][2],
                ];
                let middle = SurfacePoint::mean(corners.iter().map(|&i| surface[i as usize]));
                assert!(
                    (faces[a] - c.skin(middle)).length() < 1e-5,
                    "{pattern:?} quad {q}"
                );
            }
            // Each vertex in the colour of one of its faces.
            for (v, colour) in paint.vertices.iter().enumerate() {
                assert!(
                    triangles
                        .iter()
                        .zip(&faces)
                        .any(|(t, f)| t.contains(&(v as u32)) && f == colour),
                    "{pattern:?} vertex {v}"
                );
            }
        }
    }

    #[test]
    fn same_seed_same_colours() {
        let surface = tube();
        for seed in 0..20 {
            let a = Colouring::draw(&mut rng_for(seed), &params(), 0);
            let b = Colouring::draw(&mut rng_for(seed), &params(), 0);
            assert_eq!(a.palette, b.palette);
            for &s in &surface {
                assert_eq!(
                    a.skin(s).to_array().map(f32::to_bits),
                    b.skin(s).to_array().map(f32::to_bits)
                );
            }
        }
        let a = Colouring::draw(&mut rng_for(1), &params(), 0);
        let b = Colouring::draw(&mut rng_for(2), &params(), 0);
        assert_ne!(a.palette, b.palette);
    }

    #[test]
    fn limbs_start_in_the_body_colour() {
        let c = Colouring::draw(&mut rng_for(3), &params(), 0);
        let root = Vec3::new(0.2, 0.3, 0.4);
        for membrane in [false, true] {
            assert_eq!(c.limb(root, membrane, 0.0), root);
            assert!(in_unit_cube(c.limb(root, membrane, 1.0)));
            assert_ne!(c.limb(root, membrane, 1.0), root);
        }
    }
}
