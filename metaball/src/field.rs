//! Fields: the sum of a set of balls' falloffs, culled through a uniform grid.

use alloc::vec::Vec;
use core::ops::{Add, Mul};

use glam::{Vec2, Vec3};

use crate::ball::validate_ball;
use crate::grid::{Core, FactorCache};
use crate::{Ball2, Ball3, Falloff, ISO_LEVEL, MetaballError};

/// The default culling epsilon: a ball is skipped where it contributes less than `1e-4`
/// (a ten-thousandth of the iso level).
pub const DEFAULT_EPSILON: f32 = 1e-4;

/// Accepted culling epsilons.
pub const EPSILON_RANGE: (f32, f32) = (1e-12, 0.1);

/// The most balls one field may hold: `u32::MAX`, as balls are indexed by `u32` (on 32-bit
/// targets memory runs out long before).
pub const MAX_FIELD_BALLS: usize = u32::MAX as usize;

/// Largest `width × height` that [`Field2::sample_grid`] fills.
pub const MAX_GRID_SAMPLES: usize = 1 << 24;

/// How a field evaluates its balls.
///
/// ```
/// use creature_metaball::{Falloff, FieldOptions};
///
/// let options = FieldOptions::DEFAULT
///     .with_falloff(Falloff::WYVILL)
///     .with_epsilon(1e-6);
/// assert_eq!(FieldOptions::default().falloff, Falloff::SEED);
/// assert_eq!(options.epsilon, 1e-6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FieldOptions {
    /// The falloff of every ball. Default: [`Falloff::SEED`].
    pub falloff: Falloff,
    /// Culling epsilon: each ball is skipped beyond the radius where its contribution drops
    /// below this ([`Falloff::cutoff_radius`]), so a culled value differs from the exact
    /// all-balls sum by at most `epsilon × ball count` (see [`Field2::error_bound`]). In
    /// [`EPSILON_RANGE`]. Ignored by [`Falloff::Wyvill`], whose support ends at `R` (culling is
    /// exact). Default: [`DEFAULT_EPSILON`] (`1e-4`).
    pub epsilon: f32,
    /// Edge of the grid's square (cubic) cells, or `None` to use the median cutoff radius.
    /// The grid never exceeds `16 n + 1024` cells nor `64 n + 4096` ball entries for `n` balls:
    /// a smaller size is doubled until it fits. Default: `None`.
    pub cell_size: Option<f32>,
}

impl FieldOptions {
    /// The seeds' falloff, epsilon `1e-4`, automatic cell size.
    pub const DEFAULT: Self = Self {
        falloff: Falloff::SEED,
        epsilon: DEFAULT_EPSILON,
        cell_size: None,
    };

    /// Sets [`falloff`](Self::falloff).
    #[must_use]
    pub const fn with_falloff(mut self, falloff: Falloff) -> Self {
        self.falloff = falloff;
        self
    }

    /// Sets [`epsilon`](Self::epsilon).
    #[must_use]
    pub const fn with_epsilon(mut self, epsilon: f32) -> Self {
        self.epsilon = epsilon;
        self
    }

    /// Sets [`cell_size`](Self::cell_size) (`None` for automatic).
    #[must_use]
    pub const fn with_cell_size(mut self, cell_size: Option<f32>) -> Self {
        self.cell_size = cell_size;
        self
    }

    /// Checks the falloff, the epsilon and the cell size.
    ///
    /// # Errors
    /// [`MetaballError::NonFinite`], [`MetaballError::NotPositive`] or
    /// [`MetaballError::OutOfRange`] naming the option.
    pub fn validate(&self) -> Result<(), MetaballError> {
        self.falloff.validate()?;
        check_epsilon(self.epsilon)?;
        if let Some(size) = self.cell_size {
            if !size.is_finite() {
                return Err(MetaballError::NonFinite {
                    what: "cell size",
                    index: 0,
                });
            }
            if !(size > 0.0) {
                return Err(MetaballError::NotPositive {
                    what: "cell size",
                    index: 0,
                    value: size,
                });
            }
        }
        Ok(())
    }
}

/// Checks a culling epsilon against [`EPSILON_RANGE`].
pub(crate) fn check_epsilon(e: f32) -> Result<(), MetaballError> {
    if !e.is_finite() {
        return Err(MetaballError::NonFinite {
            what: "epsilon",
            index: 0,
        });
    }
    let (min, max) = EPSILON_RANGE;
    if !(e >= min && e <= max) {
        return Err(MetaballError::OutOfRange {
            what: "epsilon",
            index: 0,
            value: e,
            min,
            max,
        });
    }
    Ok(())
}

impl Default for FieldOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// One id's share of the field at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Share {
    /// The [`Ball2::id`] / [`Ball3::id`] the share belongs to.
    pub id: u32,
    /// Its weight, in `(0, 1]`; the weights of one [`Shares`] sum to 1.
    pub weight: f32,
}

/// The top-k [`Share`]s at a point, largest weight first (ties: smaller id first). Stored inline
/// up to 4, the glTF skinning limit.
pub type Shares = smallvec::SmallVec<[Share; 4]>;

/// A per-ball value that [`Field2::blend`] / [`Field3::blend`] can interpolate: anything linear
/// (`a + b`, `a * w`) that can say whether it is finite, so that a NaN or infinite attribute is
/// reported as an error instead of leaking into the blend.
///
/// Implemented for `f32`, [`Vec2`], [`Vec3`], [`Vec3A`](glam::Vec3A) and [`Vec4`](glam::Vec4);
/// implement it for your own colour or weight types.
///
/// ```
/// use core::ops::{Add, Mul};
/// use creature_metaball::Attribute;
///
/// #[derive(Clone, Copy)]
/// struct Rgb([f32; 3]);
///
/// impl Add for Rgb {
///     type Output = Self;
///     fn add(self, o: Self) -> Self {
///         Rgb([self.0[0] + o.0[0], self.0[1] + o.0[1], self.0[2] + o.0[2]])
///     }
/// }
/// impl Mul<f32> for Rgb {
///     type Output = Self;
///     fn mul(self, w: f32) -> Self {
///         Rgb(self.0.map(|c| c * w))
///     }
/// }
/// impl Attribute for Rgb {
///     fn is_finite(&self) -> bool {
///         self.0.iter().all(|c| c.is_finite())
///     }
/// }
/// assert!(!Rgb([0.0, f32::NAN, 1.0]).is_finite());
/// ```
pub trait Attribute: Copy + Add<Output = Self> + Mul<f32, Output = Self> {
    /// Whether every component is finite (not NaN, not infinite).
    fn is_finite(&self) -> bool;
}

impl Attribute for f32 {
    fn is_finite(&self) -> bool {
        f32::is_finite(*self)
    }
}

impl Attribute for Vec2 {
    fn is_finite(&self) -> bool {
        Vec2::is_finite(*self)
    }
}

impl Attribute for Vec3 {
    fn is_finite(&self) -> bool {
        Vec3::is_finite(*self)
    }
}

impl Attribute for glam::Vec3A {
    fn is_finite(&self) -> bool {
        glam::Vec3A::is_finite(*self)
    }
}

impl Attribute for glam::Vec4 {
    fn is_finite(&self) -> bool {
        glam::Vec4::is_finite(*self)
    }
}

/// Statistics of a field's culling grid, for diagnostics and tuning.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct GridStats {
    /// Edge of a cell.
    pub cell_size: f32,
    /// Number of cells.
    pub cells: usize,
    /// Ball entries over all cells (a ball is listed in every cell its cutoff box overlaps).
    pub entries: usize,
}

fn check_options_and_count(options: &FieldOptions, count: usize) -> Result<(), MetaballError> {
    options.validate()?;
    if count == 0 {
        return Err(MetaballError::NoBalls);
    }
    if count > MAX_FIELD_BALLS {
        return Err(MetaballError::TooManyFieldBalls {
            count,
            max: MAX_FIELD_BALLS,
        });
    }
    Ok(())
}

fn check_attribute_count(count: usize, found: usize) -> Result<(), MetaballError> {
    if count == found {
        Ok(())
    } else {
        Err(MetaballError::WrongLength {
            what: "attributes",
            expected: count,
            found,
        })
    }
}

fn check_attributes<T: Attribute>(count: usize, attributes: &[T]) -> Result<(), MetaballError> {
    check_attribute_count(count, attributes.len())?;
    match attributes.iter().position(|a| !a.is_finite()) {
        Some(index) => Err(MetaballError::NonFinite {
            what: "attribute",
            index,
        }),
        None => Ok(()),
    }
}

/// The methods [`Field2`] and [`Field3`] share, the same code for both: the field's ball,
/// point and vector types vary, the work is `Core<D>`'s. The examples of `shares`, `blend` and
/// `validate_attributes` are passed in (`Field2`'s; `Field3` has none).
macro_rules! shared_field_methods {
    (
        $Field:ident, $Ball:ident, $Vec:ident;
        shares: { $(#[$shares_doc:meta])* }
        blend: { $(#[$blend_doc:meta])* }
        validate_attributes: { $(#[$validate_doc:meta])* }
    ) => {
        impl $Field {
            /// A field of `balls` with `falloff` and the other [`FieldOptions::DEFAULT`]s.
            ///
            /// # Errors
            /// [`MetaballError::NoBalls`] for an empty slice; for a bad ball (non-finite or
            /// out-of-range centre, radius not positive or outside
            /// [`RADIUS_RANGE`](crate::RADIUS_RANGE)) the error names its index; a bad falloff
            /// constant is named too.
            pub fn new(balls: &[$Ball], falloff: Falloff) -> Result<Self, MetaballError> {
                Self::with_options(balls, &FieldOptions::DEFAULT.with_falloff(falloff))
            }

            /// A field of `balls` with `options`.
            ///
            /// # Errors
            /// As [`new`](Self::new), plus a bad epsilon or cell size.
            pub fn with_options(
                balls: &[$Ball],
                options: &FieldOptions,
            ) -> Result<Self, MetaballError> {
                check_options_and_count(options, balls.len())?;
                let mut input = Vec::with_capacity(balls.len());
                for (index, ball) in balls.iter().enumerate() {
                    let center = ball.center.to_array();
                    validate_ball(&center, ball.radius, index)?;
                    input.push((center, ball.radius, ball.id));
                }
                let core = Core::build(
                    &input,
                    options.falloff.kernel(),
                    options.epsilon,
                    options.cell_size,
                );
                Ok(Self {
                    balls: balls.to_vec(),
                    options: *options,
                    core,
                })
            }

            /// The balls, in input order.
            #[must_use]
            pub fn balls(&self) -> &[$Ball] {
                &self.balls
            }

            /// The options the field was built with.
            #[must_use]
            pub fn options(&self) -> &FieldOptions {
                &self.options
            }

            /// The falloff.
            #[must_use]
            pub fn falloff(&self) -> Falloff {
                self.options.falloff
            }

            /// How many balls the field has (at least 1).
            #[must_use]
            pub fn ball_count(&self) -> usize {
                self.core.len()
            }

            /// The culled field value at `p`: the sum over the balls whose cutoff reaches `p`,
            /// in ball order. Within [`error_bound`](Self::error_bound) of
            /// [`value_exact`](Self::value_exact), up to `f32` rounding: for the Gaussian
            /// falloffs (seed, Blinn) each term's `exp` is the crate's own (within `1.5e-7` of
            /// the true `exp`, the same bits on every platform, and what
            /// [`Field2::sample_block`] uses), where `value_exact` uses the platform's.
            /// [`value_and_gradient`](Self::value_and_gradient), [`shares`](Self::shares) and
            /// [`blend`](Self::blend) sum the same terms.
            #[must_use]
            #[inline]
            pub fn value(&self, p: $Vec) -> f32 {
                self.core.value(p.to_array())
            }

            /// The exact field value at `p`: the sum over every ball, no culling, in ball order
            /// (the seeds' computation; O(all balls)).
            #[must_use]
            pub fn value_exact(&self, p: $Vec) -> f32 {
                self.core.value_exact(p.to_array())
            }

            /// Whether `p` is inside: `value(p) ≥ ISO_LEVEL`.
            #[must_use]
            pub fn contains(&self, p: $Vec) -> bool {
                self.value(p) >= ISO_LEVEL
            }

            /// The analytic gradient of the culled field at `p` (it points towards higher
            /// values, i.e. inwards at the iso line).
            #[must_use]
            pub fn gradient(&self, p: $Vec) -> $Vec {
                self.value_and_gradient(p).1
            }

            /// The culled value and analytic gradient together, for the price of one.
            #[must_use]
            pub fn value_and_gradient(&self, p: $Vec) -> (f32, $Vec) {
                let (v, g) = self.core.value_and_gradient(p.to_array());
                (v, $Vec::from_array(g))
            }

            /// The exact analytic gradient over every ball.
            #[must_use]
            pub fn gradient_exact(&self, p: $Vec) -> $Vec {
                $Vec::from_array(self.core.value_and_gradient_exact(p.to_array()).1)
            }

            /// The `k` ids with the largest summed contribution at `p`, largest first, with
            /// their shares renormalised to sum to 1 over the kept ids (as the seed's skinning
            /// does with its top 4). When `k` is at least the number of ids reaching `p`, each
            /// share is exactly the per-id `Σ f_i / D` of the culled field.
            ///
            /// Fewer than `k` entries when fewer ids reach `p` (no padding); empty for `k = 0`
            /// or where the culled field is 0.
            ///
            $(#[$shares_doc])*
            #[must_use]
            pub fn shares(&self, p: $Vec, k: usize) -> Shares {
                self.core.shares(p.to_array(), k)
            }

            /// Blends one attribute per ball (colour, texture weights, anything linear) with
            /// the per-ball shares `f_i(p) / D(p)` of the culled field: `Σ (f_i / Σ f_j) a_i`.
            /// The weights are normalised before they multiply the attributes (in `f64`), so
            /// the blend of finite attributes is their convex combination and cannot overflow
            /// unless an attribute is within rounding of `f32::MAX`.
            ///
            /// `Ok(None)` where no ball reaches `p` (culled value 0).
            ///
            /// Only the attributes of the balls that reach `p` are read, so a sample stays
            /// O(nearby balls), and only those are checked: a NaN or infinite attribute of a
            /// ball that reaches `p` is an error, one of a ball that does not is never read. To
            /// check every attribute once up front, call
            /// [`validate_attributes`](Self::validate_attributes).
            ///
            $(#[$blend_doc])*
            ///
            /// # Errors
            /// - [`MetaballError::WrongLength`] unless there is exactly one attribute per ball;
            /// - [`MetaballError::NonFinite`] (`what: "attribute"`, the ball's index) for a NaN
            ///   or infinite attribute of a ball that reaches `p`;
            /// - [`MetaballError::BlendOverflow`] if the blend of finite attributes is not
            ///   finite.
            pub fn blend<T: Attribute>(
                &self,
                p: $Vec,
                attributes: &[T],
            ) -> Result<Option<T>, MetaballError> {
                check_attribute_count(self.core.len(), attributes.len())?;
                self.core.blend(p.to_array(), attributes)
            }

            /// Checks a whole attribute list for [`blend`](Self::blend) once, in O(balls): one
            /// attribute per ball, every one finite.
            ///
            $(#[$validate_doc])*
            ///
            /// # Errors
            /// [`MetaballError::WrongLength`] or [`MetaballError::NonFinite`] naming the first
            /// non-finite attribute's index.
            pub fn validate_attributes<T: Attribute>(
                &self,
                attributes: &[T],
            ) -> Result<(), MetaballError> {
                check_attributes(self.core.len(), attributes)
            }

            /// The largest possible difference between [`value`](Self::value) and
            /// [`value_exact`](Self::value_exact) anywhere, up to `f32` rounding: the sum over
            /// the balls of the most each can contribute beyond its cutoff, i.e.
            /// `epsilon × ball count` for the exponential falloff and 0 for Wyvill.
            ///
            /// Near the iso line this moves the outline by at most about
            /// `error_bound / |gradient|`: for a lone seed ball of radius `R`, `|∇D| = 1/R`
            /// there.
            #[must_use]
            pub fn error_bound(&self) -> f32 {
                self.core.value_error()
            }

            /// The largest possible length of `gradient(p) − gradient_exact(p)`, up to
            /// rounding: the sum over the balls of the steepest each can be beyond its cutoff.
            #[must_use]
            pub fn gradient_error_bound(&self) -> f32 {
                self.core.gradient_error()
            }

            /// The box `(min, max)` outside which the culled field is exactly 0: every ball's
            /// centre ± its cutoff radius.
            #[must_use]
            pub fn bounds(&self) -> ($Vec, $Vec) {
                let (lo, hi) = self.core.bounds();
                ($Vec::from_array(lo), $Vec::from_array(hi))
            }

            /// The culling grid's statistics.
            #[must_use]
            pub fn grid_stats(&self) -> GridStats {
                GridStats {
                    cell_size: self.core.cell_size(),
                    cells: self.core.cell_count(),
                    entries: self.core.entry_count(),
                }
            }
        }
    };
}

/// A 2D metaball field `D(p) = Σ f_i(p)`, inside where `D(p) ≥ ISO_LEVEL` (1.0).
///
/// Built once from a ball set; then every sample costs O(balls near `p`): each ball is cut off
/// where its contribution drops below [`FieldOptions::epsilon`], and a uniform grid lists, per
/// cell, the balls whose cutoff reaches it. The culled [`value`](Self::value) differs from the
/// exact all-balls [`value_exact`](Self::value_exact) by at most
/// [`error_bound`](Self::error_bound) `= epsilon × ball count` (zero for Wyvill), and the
/// gradient by at most [`gradient_error_bound`](Self::gradient_error_bound). Outside
/// [`bounds`](Self::bounds) the culled field is exactly 0.
///
/// Non-finite sample points are outside every ball: value 0, zero gradient, no shares. No
/// method returns NaN or an infinity: a value whose sum overflows `f32` (an extreme falloff
/// and thousands of coincident balls) saturates to `f32::MAX`, still inside; a gradient
/// component saturates to `±f32::MAX`; [`blend`](Self::blend) reports a non-finite attribute
/// or result as an error.
///
/// ```
/// use creature_metaball::{Ball2, Falloff, Field2, glam::Vec2};
///
/// let balls = [
///     Ball2::new(Vec2::new(0.0, 0.0), 10.0, 0),
///     Ball2::new(Vec2::new(18.0, 0.0), 8.0, 1),
/// ];
/// let field = Field2::new(&balls, Falloff::SEED)?;
/// assert!(field.contains(Vec2::new(9.0, 0.0))); // the two balls have merged
/// assert!(!field.contains(Vec2::new(0.0, 14.0)));
///
/// // The gradient points uphill, towards the centre.
/// assert!(field.gradient(Vec2::new(-5.0, 0.0)).x > 0.0);
///
/// // Top-2 ids and their shares, summing to 1.
/// let shares = field.shares(Vec2::new(4.0, 0.0), 2);
/// assert_eq!(shares[0].id, 0);
/// assert!((shares[0].weight + shares[1].weight - 1.0).abs() < 1e-6);
///
/// // Culled and exact sums agree within the documented bound.
/// let p = Vec2::new(25.0, 3.0);
/// assert!((field.value(p) - field.value_exact(p)).abs() <= field.error_bound());
/// # Ok::<(), creature_metaball::MetaballError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Field2 {
    balls: Vec<Ball2>,
    options: FieldOptions,
    core: Core<2>,
}

shared_field_methods! {
    Field2, Ball2, Vec2;
    shares: {
        /// ```
        /// use creature_metaball::{Ball2, Falloff, Field2, glam::Vec2};
        ///
        /// // Two balls owned by bone 3, one by bone 5.
        /// let balls = [
        ///     Ball2::new(Vec2::new(0.0, 0.0), 5.0, 3),
        ///     Ball2::new(Vec2::new(6.0, 0.0), 5.0, 3),
        ///     Ball2::new(Vec2::new(12.0, 0.0), 5.0, 5),
        /// ];
        /// let field = Field2::new(&balls, Falloff::SEED)?;
        /// let shares = field.shares(Vec2::new(8.0, 0.0), 4);
        /// assert_eq!(shares.len(), 2);
        /// assert_eq!(shares[0].id, 3);
        /// assert!(shares[0].weight > shares[1].weight);
        /// # Ok::<(), creature_metaball::MetaballError>(())
        /// ```
    }
    blend: {
        /// ```
        /// use creature_metaball::{Ball2, Falloff, Field2, glam::{Vec2, Vec3}};
        ///
        /// let balls = [Ball2::new(Vec2::ZERO, 5.0, 0), Ball2::new(Vec2::new(8.0, 0.0), 5.0, 1)];
        /// let colours = [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0)];
        /// let field = Field2::new(&balls, Falloff::SEED)?;
        /// let mid = field.blend(Vec2::new(4.0, 0.0), &colours)?.unwrap_or_default();
        /// assert!((mid.x - 0.5).abs() < 1e-5 && (mid.z - 0.5).abs() < 1e-5);
        /// assert_eq!(field.blend(Vec2::new(1e4, 0.0), &colours)?, None);
        /// # Ok::<(), creature_metaball::MetaballError>(())
        /// ```
    }
    validate_attributes: {
        /// ```
        /// use creature_metaball::{Ball2, Falloff, Field2, MetaballError, glam::Vec2};
        ///
        /// let balls = [Ball2::new(Vec2::ZERO, 5.0, 0), Ball2::new(Vec2::new(1e3, 0.0), 5.0, 1)];
        /// let field = Field2::new(&balls, Falloff::SEED)?;
        /// let bad = [0.5, f32::NAN];
        /// // The far ball does not reach the origin, so blending there never reads its NaN…
        /// assert_eq!(field.blend(Vec2::ZERO, &bad)?, Some(0.5));
        /// // …but the validator finds it.
        /// assert_eq!(
        ///     field.validate_attributes(&bad),
        ///     Err(MetaballError::NonFinite { what: "attribute", index: 1 })
        /// );
        /// # Ok::<(), MetaballError>(())
        /// ```
    }
}

/// The 2D-only methods: combined queries, grid and block sampling, block proofs.
impl Field2 {
    /// [`value_and_gradient`](Self::value_and_gradient) and [`shares`](Self::shares) at `p` in
    /// one pass over the balls that reach it (two for Wyvill's falloff): the same results, bit
    /// for bit, for about the price of one — for a mesh vertex that needs its skin weights and
    /// its distance from the iso line (`|value − 1| / |gradient|`) alike.
    ///
    /// ```
    /// use creature_metaball::{Ball2, Falloff, Field2, glam::Vec2};
    ///
    /// let balls = [Ball2::new(Vec2::ZERO, 5.0, 3), Ball2::new(Vec2::new(6.0, 0.0), 5.0, 5)];
    /// let field = Field2::new(&balls, Falloff::SEED)?;
    /// let p = Vec2::new(2.0, 1.0);
    /// let (value, gradient, shares) = field.value_gradient_and_shares(p, 4);
    /// assert_eq!((value, gradient), field.value_and_gradient(p));
    /// assert_eq!(shares, field.shares(p, 4));
    /// # Ok::<(), creature_metaball::MetaballError>(())
    /// ```
    #[must_use]
    pub fn value_gradient_and_shares(&self, p: Vec2, k: usize) -> (f32, Vec2, Shares) {
        let (v, g, s) = self.core.value_gradient_and_shares(p.to_array(), k);
        (v, Vec2::from_array(g), s)
    }

    /// Samples the culled field on a `width × height` grid with spacing `step`: sample
    /// `row * width + column` is `value(origin + step * (column, row))` (x = column, y = row,
    /// the layout `creature-march`'s `march_grid` reads). Empty if either size is 0.
    ///
    /// Faster than sampling point by point: it runs ball by ball, and for the Gaussian
    /// falloffs (seed, Blinn) splits `exp(−a (dx² + dy²)/R²)` into a row factor times a column
    /// factor, so a ball costs one `exp` per row and column it reaches rather than one per
    /// sample. Each sample sums exactly the balls `value` would, in the same order, so it
    /// differs from `value` by rounding only, within
    /// [`sample_error_bound`](Self::sample_error_bound)` × value`; it is not bit-identical to
    /// `value`. Against [`value_exact`](Self::value_exact) the two bounds add, since
    /// `|sample − exact| ≤ |sample − value| + |value − exact|`: a sample is within
    /// [`error_bound`](Self::error_bound)` + sample_error_bound × value` of the exact sum (up
    /// to the rounding by which `value` itself may differ from `value_exact`). The second term
    /// matters for steep falloffs, whose `sample_error_bound` grows with the exponent at the
    /// cutoff (regression: these docs once said a sample obeys `error_bound` alone; with
    /// blobbiness −76 and epsilon 0.025, three balls, a sample read 94,498.58 where `value`
    /// and `value_exact` read 94,499.73, 1.2e-5 relative, within the `sample_error_bound` of
    /// 3.4e-5 but 15 times `error_bound`). An exponential
    /// falloff so steep that a factor could underflow (`blobbiness + ln(epsilon) < −80`, i.e.
    /// `blobbiness` below about −70.8 at the default epsilon) and [`Falloff::Wyvill`] are not
    /// split: each sample is then `value` itself.
    ///
    /// ```
    /// use creature_metaball::{Ball2, Falloff, Field2, glam::Vec2};
    ///
    /// let field = Field2::new(&[Ball2::new(Vec2::ZERO, 10.0, 0)], Falloff::SEED)?;
    /// let (min, max) = field.bounds();
    /// let samples = field.sample_grid(min, 2.0, 32, 32)?;
    /// assert_eq!(samples.len(), 32 * 32);
    /// assert!(samples.iter().any(|&v| v >= 1.0));
    /// # let _ = max;
    /// # Ok::<(), creature_metaball::MetaballError>(())
    /// ```
    ///
    /// # Errors
    /// [`MetaballError::NonFinite`] for a non-finite origin or step,
    /// [`MetaballError::NotPositive`] for a step ≤ 0, [`MetaballError::OutOfRange`] for more
    /// than [`MAX_GRID_SAMPLES`] samples.
    pub fn sample_grid(
        &self,
        origin: Vec2,
        step: f32,
        width: usize,
        height: usize,
    ) -> Result<Vec<f32>, MetaballError> {
        check_grid(origin, step, width, height)?;
        Ok(self
            .core
            .sample_grid(origin.to_array(), step, width, height))
    }

    /// Samples the culled field on a small `cols × rows` block with spacing `step` into `out`:
    /// `out[row * cols + col]` is the field at `origin + step * (col, row)` (x = column,
    /// y = row, the layout of [`sample_grid`](Self::sample_grid)). Meant for many small
    /// blocks, such as the 8 × 8 node tiles a contour tracer caches: it allocates nothing
    /// (for blocks up to 16 columns wide) and visits only the balls listed by the culling
    /// cells the block overlaps, so a block costs O(balls near it), not O(all balls).
    ///
    /// It uses the separable evaluation of [`sample_grid`](Self::sample_grid) (one `exp` per
    /// ball per row and per column for the Gaussian falloffs), with the row and column
    /// factors of a ball computed together by a branch-free `exp` the compiler vectorises
    /// (within `1.5e-7` relative of the true `exp`; the same bits on every platform, and the
    /// `exp` of [`value`](Self::value)). Against `value` at the same point it sums the same
    /// balls in the same order (so
    /// a sample is 0 exactly where `value` is) and differs only by rounding: within
    /// [`sample_error_bound`](Self::sample_error_bound)` × value` (tested), so within
    /// [`error_bound`](Self::error_bound)` + sample_error_bound × value` of the exact sum, as
    /// for [`sample_grid`](Self::sample_grid). It is **not** bit-identical
    /// to `value`, nor to `sample_grid` (which uses the platform's `exp`). For
    /// [`Falloff::Wyvill`] (no separable form) and the steepest exponential falloffs (as in
    /// [`sample_grid`](Self::sample_grid)) each sample is `value` itself.
    ///
    /// Blocks of at most 8 × 8 take a fixed-width path: the candidate balls are the union of
    /// per-cell bit sets (fields of up to 256 balls), each ball's 16 row and column factors
    /// come from a batched, vectorised `exp`, and a ball whose cutoff provably covers the
    /// whole block is added without per-sample tests; the terms are the same, in the same
    /// order, as a test at every sample.
    ///
    /// ```
    /// use creature_metaball::{Ball2, Falloff, Field2, glam::Vec2};
    ///
    /// let field = Field2::new(&[Ball2::new(Vec2::ZERO, 10.0, 0)], Falloff::SEED)?;
    /// let (origin, step) = (Vec2::new(-8.0, -8.0), 2.0);
    /// let mut tile = [0.0f32; 8 * 8];
    /// field.sample_block(origin, step, 8, 8, &mut tile)?;
    /// for row in 0..8 {
    ///     for col in 0..8 {
    ///         let p = origin + step * Vec2::new(col as f32, row as f32);
    ///         let v = field.value(p);
    ///         assert!((tile[row * 8 + col] - v).abs() <= field.sample_error_bound() * v);
    ///     }
    /// }
    /// # Ok::<(), creature_metaball::MetaballError>(())
    /// ```
    ///
    /// # Errors
    /// As [`sample_grid`](Self::sample_grid), plus [`MetaballError::WrongLength`] when
    /// `out.len()` is not `cols × rows`. On error `out` is left untouched.
    #[inline]
    pub fn sample_block(
        &self,
        origin: Vec2,
        step: f32,
        cols: usize,
        rows: usize,
        out: &mut [f32],
    ) -> Result<(), MetaballError> {
        self.sample_block_with(origin, step, cols, rows, out, None)
    }

    /// [`sample_block`](Self::sample_block) through `cache`, if any (a [`BlockSampler`]'s).
    #[inline]
    fn sample_block_with(
        &self,
        origin: Vec2,
        step: f32,
        cols: usize,
        rows: usize,
        out: &mut [f32],
        cache: Option<&mut FactorCache>,
    ) -> Result<(), MetaballError> {
        check_block(origin, step, cols, rows, out)?;
        self.core
            .sample_block(origin.to_array(), step, cols, rows, out, cache);
        Ok(())
    }

    /// How far, relative, a sample of [`sample_grid`](Self::sample_grid),
    /// [`sample_block`](Self::sample_block) or a [`BlockSampler`] may be from
    /// [`value`](Self::value) at the same point: `|sample − value| ≤ sample_error_bound() ×
    /// value` (so a sample is 0 exactly where `value` is).
    ///
    /// 0 where every sample is `value` itself ([`Falloff::Wyvill`], and exponential falloffs
    /// too steep to split). Otherwise `(7 L + 2 n + 11) · 2⁻²⁴`, from the error analysis of
    /// the split `exp(−a dx²/R²) · exp(−a dy²/R²)` against `value`'s `exp(−a (dx² + dy²)/R²)`:
    /// `L = ln(peak / epsilon)` (at most 80) is the largest exponent of a reaching ball's term,
    /// whose rounding each of the two ways moves the term by `e^{±4uL}` and `e^{±3uL}`; two
    /// `exp`s and two products against one and one add `10.6u`; and `n`, the most balls any
    /// culling cell lists (at most [`ball_count`](Self::ball_count)), bounds the roundings of
    /// the two sums, `2(n − 1)u` (`u = 2⁻²⁴`). For the seed falloff at the default epsilon and
    /// a few balls per cell that is about `5e-6`; for a steep exponential falloff
    /// (`blobbiness = −33`, `L ≈ 42`) about `1.9e-5`. Typical differences are a tenth of it.
    ///
    /// ```
    /// use creature_metaball::{Ball2, Falloff, Field2, glam::Vec2};
    ///
    /// let field = Field2::new(&[Ball2::new(Vec2::ZERO, 10.0, 0)], Falloff::SEED)?;
    /// // L = ln(e^0.5 / 1e-4) ≈ 9.7 and one ball: (7 L + 2 + 11) · 2⁻²⁴.
    /// assert!((field.sample_error_bound() - 4.8e-6).abs() < 1e-7);
    /// let wyvill = Field2::new(&[Ball2::new(Vec2::ZERO, 10.0, 0)], Falloff::WYVILL)?;
    /// assert_eq!(wyvill.sample_error_bound(), 0.0);
    /// # Ok::<(), creature_metaball::MetaballError>(())
    /// ```
    #[must_use]
    pub fn sample_error_bound(&self) -> f32 {
        self.core.sample_error()
    }

    /// Whether every sample of the `cols × rows` block that
    /// [`sample_block`](Self::sample_block) would fill (and [`value`](Self::value) at each of
    /// its points) is certainly at least `level` — `true` only when provably so, `false` when
    /// unsure. For a contour tracer that needs only which nodes are inside (`value ≥ iso`)
    /// somewhere deep inside a body: a block proven inside needs no samples.
    ///
    /// The proof: contributions are never negative, and each ball whose cutoff covers the
    /// whole block contributes at least its value at the block's corner farthest from it; the
    /// sum of those (in `f64`), less a slack for the samples' rounding (`1e-5` plus `ε` per
    /// ball, relative), must reach `level`. It costs one `exp` per nearby ball (it stops as soon
    /// as the sum suffices), a fraction of a block's samples. Blocks well inside one ball, or
    /// inside the overlap of several, pass; blocks near the outline fail.
    ///
    /// ```
    /// use creature_metaball::{Ball2, Falloff, Field2, ISO_LEVEL, glam::Vec2};
    ///
    /// let field = Field2::new(&[Ball2::new(Vec2::ZERO, 40.0, 0)], Falloff::SEED)?;
    /// // An 8 × 8 block around the centre is inside; one straddling the outline is not.
    /// assert!(field.block_is_at_least(Vec2::splat(-7.0), 2.0, 8, 8, ISO_LEVEL)?);
    /// assert!(!field.block_is_at_least(Vec2::new(30.0, -7.0), 2.0, 8, 8, ISO_LEVEL)?);
    /// let mut block = [0.0f32; 64];
    /// field.sample_block(Vec2::splat(-7.0), 2.0, 8, 8, &mut block)?;
    /// assert!(block.iter().all(|&v| v >= ISO_LEVEL));
    /// # Ok::<(), creature_metaball::MetaballError>(())
    /// ```
    ///
    /// # Errors
    /// As [`sample_grid`](Self::sample_grid), and [`MetaballError::NonFinite`] for a NaN
    /// `level`.
    #[inline]
    pub fn block_is_at_least(
        &self,
        origin: Vec2,
        step: f32,
        cols: usize,
        rows: usize,
        level: f32,
    ) -> Result<bool, MetaballError> {
        check_level(origin, step, cols, rows, level)?;
        Ok(self
            .core
            .block_at_least(origin.to_array(), step, cols, rows, level))
    }

    /// A [`BlockSampler`] of this field: [`sample_block`](Self::sample_block) for many
    /// blocks on one grid, reusing work between blocks that share rows or columns.
    #[must_use]
    pub fn block_sampler(&self) -> BlockSampler<'_> {
        BlockSampler {
            field: self,
            cache: FactorCache::default(),
        }
    }
}

/// Samples a [`Field2`] block after block, as [`Field2::sample_block`] does (the same
/// samples, bit for bit), remembering each ball's row and column factors between blocks: a
/// block `8` columns wide whose first column an earlier block on the same grid spacing had
/// (an `8`-row block and its first row, likewise) reuses them instead of evaluating them
/// again. Meant for a contour tracer's 8 × 8 node tiles, which neighbour each other along an
/// outline: on the outline bench's creature, its tiles need about a quarter of the `exp`s.
///
/// The factors are remembered per ball, for one grid spacing: a block with another `step`
/// starts afresh. The cache grows to `32 × balls` factor rows of 8 lanes (about 1 KiB per
/// ball) on first use, and allocates nothing after that. [`Falloff::Wyvill`] and the steepest
/// exponential falloffs (no separable form) are sampled as by
/// [`sample_block`](Field2::sample_block), without the cache.
///
/// ```
/// use creature_metaball::{Ball2, Falloff, Field2, glam::Vec2};
///
/// let balls = [Ball2::new(Vec2::ZERO, 10.0, 0), Ball2::new(Vec2::new(12.0, 3.0), 6.0, 1)];
/// let field = Field2::new(&balls, Falloff::SEED)?;
/// let mut sampler = field.block_sampler();
/// let step = 1.5;
/// // A row of tiles, then the row above it: the second row reuses the column factors.
/// for (i, j) in [(-2, -1), (-1, -1), (0, -1), (-2, 0), (-1, 0), (0, 0)] {
///     let origin = Vec2::new(i as f32, j as f32) * (8.0 * step);
///     let mut cached = [0.0f32; 64];
///     let mut fresh = [0.0f32; 64];
///     sampler.sample_block(origin, step, 8, 8, &mut cached)?;
///     field.sample_block(origin, step, 8, 8, &mut fresh)?;
///     assert_eq!(cached.map(f32::to_bits), fresh.map(f32::to_bits));
/// }
/// # Ok::<(), creature_metaball::MetaballError>(())
/// ```
#[derive(Debug, Clone)]
pub struct BlockSampler<'a> {
    field: &'a Field2,
    cache: FactorCache,
}

impl<'a> BlockSampler<'a> {
    /// The field sampled.
    #[must_use]
    #[inline]
    pub fn field(&self) -> &'a Field2 {
        self.field
    }

    /// [`Field2::block_is_at_least`] for an `8 × 8` block, its bound taken from the block's
    /// row and column factors through the factor cache (which it fills as
    /// [`sample_block`](Self::sample_block) would): a proof that needs no `exp` when the
    /// factors are there already. Other blocks are proven as by `Field2::block_is_at_least`.
    /// Rigorous in the same way: `true` only when every sample is at least `level`.
    ///
    /// ```
    /// use creature_metaball::{Ball2, Falloff, Field2, ISO_LEVEL, glam::Vec2};
    ///
    /// let field = Field2::new(&[Ball2::new(Vec2::ZERO, 40.0, 0)], Falloff::SEED)?;
    /// let mut sampler = field.block_sampler();
    /// let mut block = [0.0f32; 64];
    /// // A block beside the centre, sampled: its row and column factors are remembered ...
    /// sampler.sample_block(Vec2::new(-23.0, -7.0), 2.0, 8, 8, &mut block)?;
    /// // ... and the block to its right, in the same rows, is proven from them.
    /// assert!(sampler.block_is_at_least(Vec2::new(-7.0, -7.0), 2.0, 8, 8, ISO_LEVEL)?);
    /// // One straddling the outline is not.
    /// assert!(!sampler.block_is_at_least(Vec2::new(30.0, -7.0), 2.0, 8, 8, ISO_LEVEL)?);
    /// # Ok::<(), creature_metaball::MetaballError>(())
    /// ```
    ///
    /// # Errors
    /// As [`Field2::block_is_at_least`].
    #[inline]
    pub fn block_is_at_least(
        &mut self,
        origin: Vec2,
        step: f32,
        cols: usize,
        rows: usize,
        level: f32,
    ) -> Result<bool, MetaballError> {
        if cols != 8 || rows != 8 {
            return self
                .field
                .block_is_at_least(origin, step, cols, rows, level);
        }
        check_level(origin, step, cols, rows, level)?;
        Ok(self
            .field
            .core
            .block_at_least_cached(&mut self.cache, origin.to_array(), step, level))
    }

    /// [`Field2::sample_block`], through the factor cache: the same samples, bit for bit.
    ///
    /// # Errors
    /// As [`Field2::sample_block`]. On error `out` is left untouched.
    #[inline]
    pub fn sample_block(
        &mut self,
        origin: Vec2,
        step: f32,
        cols: usize,
        rows: usize,
        out: &mut [f32],
    ) -> Result<(), MetaballError> {
        let cache = Some(&mut self.cache);
        self.field
            .sample_block_with(origin, step, cols, rows, out, cache)
    }
}

/// Checks a block for [`Field2::sample_block`]: a valid grid, and `cols × rows` samples in
/// `out`.
#[inline]
fn check_block(
    origin: Vec2,
    step: f32,
    cols: usize,
    rows: usize,
    out: &[f32],
) -> Result<(), MetaballError> {
    check_grid(origin, step, cols, rows)?;
    let expected = cols * rows;
    if out.len() != expected {
        return Err(MetaballError::WrongLength {
            what: "block samples",
            expected,
            found: out.len(),
        });
    }
    Ok(())
}

/// Checks a sampling grid: finite origin, finite positive step, at most [`MAX_GRID_SAMPLES`]
/// samples.
/// [`check_grid`], and a level that is not NaN.
#[inline]
fn check_level(
    origin: Vec2,
    step: f32,
    cols: usize,
    rows: usize,
    level: f32,
) -> Result<(), MetaballError> {
    check_grid(origin, step, cols, rows)?;
    if level.is_nan() {
        return Err(MetaballError::NonFinite {
            what: "level",
            index: 0,
        });
    }
    Ok(())
}

#[inline]
fn check_grid(origin: Vec2, step: f32, width: usize, height: usize) -> Result<(), MetaballError> {
    if !origin.is_finite() {
        return Err(MetaballError::NonFinite {
            what: "grid origin",
            index: 0,
        });
    }
    if !step.is_finite() {
        return Err(MetaballError::NonFinite {
            what: "grid step",
            index: 0,
        });
    }
    if !(step > 0.0) {
        return Err(MetaballError::NotPositive {
            what: "grid step",
            index: 0,
            value: step,
        });
    }
    let count = width.saturating_mul(height);
    if count > MAX_GRID_SAMPLES {
        return Err(MetaballError::OutOfRange {
            what: "grid sample count",
            index: 0,
            value: count as f32,
            min: 0.0,
            max: MAX_GRID_SAMPLES as f32,
        });
    }
    Ok(())
}

/// A 3D metaball field: [`Field2`] with [`Vec3`] points (a cubic grid culls the balls).
///
/// ```
/// use creature_metaball::{Ball3, Falloff, Field3, glam::Vec3};
///
/// let balls = [
///     Ball3::new(Vec3::ZERO, 1.0, 0),
///     Ball3::new(Vec3::new(1.5, 0.0, 0.0), 1.0, 1),
/// ];
/// let field = Field3::new(&balls, Falloff::SEED)?;
/// assert!(field.contains(Vec3::new(0.75, 0.0, 0.0)));
/// assert!(field.gradient(Vec3::new(0.0, 0.0, 1.0)).z < 0.0);
/// # Ok::<(), creature_metaball::MetaballError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Field3 {
    balls: Vec<Ball3>,
    options: FieldOptions,
    core: Core<3>,
}

shared_field_methods! {
    Field3, Ball3, Vec3;
    shares: {}
    blend: {}
    validate_attributes: {}
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression: more than `u32::MAX` balls was reported as `TooManyBalls`, whose message told
    /// the caller to "use a shorter bone or a larger thickness". Such a slice cannot be
    /// allocated in a test, so the count check is called directly.
    #[cfg(target_pointer_width = "64")]
    #[test]
    fn too_many_field_balls_is_its_own_error() {
        let count = MAX_FIELD_BALLS + 1;
        assert_eq!(
            check_options_and_count(&FieldOptions::DEFAULT, count),
            Err(MetaballError::TooManyFieldBalls {
                count,
                max: MAX_FIELD_BALLS
            })
        );
        assert!(check_options_and_count(&FieldOptions::DEFAULT, MAX_FIELD_BALLS).is_ok());
        assert_eq!(
            check_options_and_count(&FieldOptions::DEFAULT, 0),
            Err(MetaballError::NoBalls)
        );
    }

    #[test]
    fn attributes_are_checked_for_length_and_finiteness() {
        assert!(check_attributes(3, &[1.0f32, 2.0, 3.0]).is_ok());
        assert_eq!(
            check_attributes(3, &[1.0f32, 2.0]),
            Err(MetaballError::WrongLength {
                what: "attributes",
                expected: 3,
                found: 2
            })
        );
        assert_eq!(
            check_attributes(
                3,
                &[Vec3::ONE, Vec3::new(0.0, f32::INFINITY, 0.0), Vec3::NAN]
            ),
            Err(MetaballError::NonFinite {
                what: "attribute",
                index: 1
            })
        );
        assert!(!Attribute::is_finite(&glam::Vec4::new(
            0.0,
            0.0,
            0.0,
            f32::NAN
        )));
        assert!(!Attribute::is_finite(&glam::Vec3A::new(
            f32::NEG_INFINITY,
            0.0,
            0.0
        )));
        assert!(Attribute::is_finite(&Vec2::new(-1.0, 1e30)));
    }
}
