//! The 2D pipeline: skeleton → metaballs → outline → mesh → UVs and depth → skin weights →
//! texture.

use alloc::vec::Vec;
use core::cell::RefCell;

use glam::{Vec2, Vec3};

use creature_march::{
    MarchOptions, MeshOptions, Ring, TileField, contains_each, trace_field, triangulate,
};
use creature_metaball::{
    Ball2, BlockSampler, CoverOptions, Falloff, Field2, ISO_LEVEL, MULTIPLIER_RANGE,
    cover_segment_with,
};
use creature_skin::{Influences, from_contributions, report};

use super::Params;
use super::skeleton_from_seed;
use super::texture::{self, TextureOptions};
use crate::Error;
use crate::d2::{Ball, Creature, Mesh, Quality, Skeleton};

/// The most bones a skeleton may have (glTF joints are indexed with 16 bits; far beyond any
/// generated creature).
pub const MAX_BONES: usize = 4096;

/// Generates a 2D creature from `seed`: the seed's skeleton generator ([`skeleton`](crate::d2::skeleton),
/// fed by `Pcg64Mcg::seed_from_u64(seed)`), then [`build`]. Same seed and params, same
/// creature, bit for bit.
///
/// ```
/// use creature::d2::{generate, Params};
///
/// let creature = generate(7, &Params::DEFAULT)?;
/// assert!(creature.mesh.indices.len() > 50);
/// assert!(creature.quality.min_angle >= 20.0);
/// assert_eq!(creature, generate(7, &Params::DEFAULT)?); // deterministic
/// let texture = creature.texture.as_ref().map(|t| t.width);
/// assert_eq!(texture, Some(256));
/// # Ok::<(), creature::Error>(())
/// ```
///
/// # Errors
/// As [`build`], and the errors of [`Params::validate`].
pub fn generate(seed: u64, params: &Params) -> Result<Creature, Error> {
    let skeleton = skeleton_from_seed(seed, params)?;
    let mut creature = build_with_seed(&skeleton, params, seed)?;
    creature.seed = seed;
    Ok(creature)
}

/// The metaball field as `creature-march` samples it: whole 8 × 8 tiles of grid nodes at once
/// through a [`BlockSampler`] ([`Field2::sample_block`]'s separable, culled path, each
/// ball's row and column factors reused between tiles), single points through
/// [`Field2::value`].
struct TiledField<'a>(RefCell<BlockSampler<'a>>);

impl<'a> TiledField<'a> {
    fn new(field: &'a Field2) -> Self {
        Self(RefCell::new(field.block_sampler()))
    }
}

impl TileField for TiledField<'_> {
    fn value(&self, p: Vec2) -> f32 {
        self.0.borrow().field().value(p)
    }

    fn prefers_tiles(&self) -> bool {
        true
    }

    fn sample_tile(&self, first: [i32; 2], step: f32, out: &mut [f32; creature_march::TILE_NODES]) {
        let size = creature_march::TILE_SIZE;
        let origin = creature_march::node_point(first, step);
        let sampled = self
            .0
            .borrow_mut()
            .sample_block(origin, step, size, size, out);
        if sampled.is_err() {
            // Only for a non-finite origin or step, which the tracer never passes: outside.
            out.fill(f32::NAN);
        }
    }

    fn tile_inside(&self, first: [i32; 2], step: f32, iso: f32) -> bool {
        let size = creature_march::TILE_SIZE;
        let origin = creature_march::node_point(first, step);
        // Through the sampler: the bound comes from the factors its tiles share. A block the
        // sampler cannot prove (an error) is simply not proven inside: the trace then samples
        // its nodes one by one, so the answer is conservative, not a lost error.
        self.0
            .borrow_mut()
            .block_is_at_least(origin, step, size, size, iso)
            .unwrap_or(false)
    }
}

/// Builds a creature from any skeleton (generated, or made by hand as the thesis suggests):
///
/// 1. **Metaballs** — each bone with a thickness is covered from itself to its parent by
///    [`cover_segment_with`] (ids = the parent: the segment moves with it); the last ball stops
///    half a step short of a parent that has its own balls (the seed's last-ball rule); colours
///    are lerped from the bone's to the parent's along the segment. With
///    [`Params::connect_sockets`], the link from a thickness-0 socket bone to its parent is
///    covered with its first child's thickness, so limbs stay attached.
/// 2. **Outline** — [`trace_field`] of the culled field with every ball centre as a hint, at
///    [`Params::outline_step`], the grid sampled 8 × 8 nodes at a time
///    ([`Field2::sample_block`]). It must be one piece ([`Error::Detached`] otherwise) that
///    holds every ball centre ([`Error::BallOutside`] otherwise).
/// 3. **Mesh** — [`triangulate`] with interior points and refinement to
///    [`Params::min_angle`]; UVs from the outline's box, `z = (y − min_y) / height`.
/// 4. **Skin weights** — the field's top-4 bone shares at each vertex, through
///    [`from_contributions`].
/// 5. **Texture and normal map** — [`render_texture`](super::render_texture) when [`Params::texture`] is set.
///
/// ```
/// use creature::d2::{build, skeleton_from_seed, Params};
///
/// let params = Params::DEFAULT.with_texture(false);
/// let mut skeleton = skeleton_from_seed(3, &params)?;
/// for bone in &mut skeleton.bones {
///     bone.thickness *= 1.2; // a chunkier variant of creature 3
/// }
/// let creature = build(&skeleton, &params)?;
/// assert!(creature.texture.is_none());
/// assert!(creature.quality.max_weight_sum_error <= 1e-6);
/// # Ok::<(), creature::Error>(())
/// ```
///
/// # Errors
/// - the errors of [`Params::validate`];
/// - [`Error::BadParent`], [`Error::NonFinite`], [`Error::OutOfRange`],
///   [`Error::TooManyBones`] or [`Error::EmptySkeleton`] for a bad skeleton;
/// - [`Error::Detached`] or [`Error::BallOutside`] when the outline does not hold every ball;
/// - the wrapped errors of the metaball, march and skin stages.
pub fn build(skeleton: &Skeleton, params: &Params) -> Result<Creature, Error> {
    build_with_seed(skeleton, params, 0)
}

fn build_with_seed(skeleton: &Skeleton, params: &Params, seed: u64) -> Result<Creature, Error> {
    params.validate()?;
    validate_skeleton(skeleton)?;
    let balls = cover(skeleton, params)?;
    let plain: Vec<Ball2> = balls.iter().map(|b| b.ball).collect();
    let field = Field2::new(&plain, Falloff::SEED)?;

    // Outline.
    let hints: Vec<Vec2> = plain.iter().map(|b| b.center).collect();
    let mut rings = trace_field(
        &TiledField::new(&field),
        &hints,
        params.outline_step,
        ISO_LEVEL,
        &MarchOptions::DEFAULT,
    )?;
    let outer = rings.iter().filter(|r| !r.hole).count();
    if outer != 1 {
        return Err(Error::Detached { components: outer });
    }
    // Outer ring first, holes after (a hole's parent is then 0).
    crate::sort::sort_by(&mut rings, &mut |a, b| a.hole.cmp(&b.hole));
    for r in &mut rings {
        if r.hole {
            r.parent = Some(0);
        }
    }
    let inside = contains_each(&rings, &hints);
    if let Some(index) = inside.iter().position(|&held| !held) {
        let b = plain[index];
        return Err(Error::BallOutside {
            ball: index,
            bone: b.id as usize,
            center: b.center,
        });
    }
    let outline_points: usize = rings.iter().map(|r| r.points.len()).sum();
    let (min, max) = rings
        .first()
        .and_then(Ring::bounds)
        .ok_or(Error::Degenerate { what: "outline" })?;
    let extent = max - min;
    if !(extent.x > 0.0 && extent.y > 0.0) {
        return Err(Error::Degenerate { what: "outline" });
    }

    // Mesh.
    let options = MeshOptions::DEFAULT
        .with_interior_spacing(params.interior_spacing)
        .with_clearance(params.interior_clearance)
        .with_min_angle(params.min_angle)
        .with_simplify(params.simplify);
    let mesh = triangulate(&rings, &options)?;
    if mesh.triangles.is_empty() {
        return Err(Error::Degenerate { what: "mesh" });
    }
    let positions: Vec<Vec3> = mesh
        .positions
        .iter()
        .map(|p| p.extend((p.y - min.y) / extent.y))
        .collect();
    let uvs: Vec<Vec2> = mesh
        .positions
        .iter()
        .map(|p| Vec2::new((p.x - min.x) / extent.x, (max.y - p.y) / extent.y))
        .collect();

    // Skin weights: the top-4 bone shares of the field. Quality of the outline: the
    // first-order distance of its vertices from the iso line, from the same pass over the
    // balls at each of them.
    let mut influences: Vec<Influences> = Vec::with_capacity(mesh.positions.len());
    let mut outline_error = 0.0f32;
    for (k, &p) in mesh.positions.iter().enumerate() {
        let shares = if k < mesh.outline_len {
            let (v, g, shares) = field.value_gradient_and_shares(p, 4);
            let slope = g.length();
            if slope > 0.0 {
                outline_error = outline_error.max((v - ISO_LEVEL).abs() / slope);
            }
            shares
        } else {
            field.shares(p, 4)
        };
        let inf = if shares.is_empty() {
            Influences::single(nearest_bone(&plain, p))
        } else {
            from_contributions(shares.iter().map(|s| (s.id, s.weight)), 4)?
        };
        influences.push(inf);
    }
    let skin = report(&influences);

    let (texture, normal_map) = if params.texture {
        let options = TextureOptions::DEFAULT
            .with_size(params.texture_size)
            .with_depth_shading(params.depth_shading)
            .with_normal_relief(params.normal_relief)
            .with_noise_seed((seed ^ (seed >> 32)) as u32);
        let (t, n) = texture::render_texture(&balls, (min, max), &options)?;
        (Some(t), Some(n))
    } else {
        (None, None)
    };

    Ok(Creature {
        seed: 0,
        bones: skeleton.bones.clone(),
        eyes: skeleton.eyes.clone(),
        balls,
        outline: rings.into_iter().map(|r| r.points).collect(),
        bounds: (min, max),
        mesh: Mesh {
            positions,
            uvs,
            indices: mesh.triangles,
            joints: influences.iter().map(|i| i.joints).collect(),
            weights: influences.iter().map(|i| i.weights).collect(),
            outline_len: mesh.outline_len,
        },
        texture,
        normal_map,
        quality: Quality {
            min_angle: mesh.quality.min_angle,
            triangles_below_limit: mesh.quality.below_limit,
            refinement_complete: mesh.quality.refinement_complete,
            max_weight_sum_error: skin.max_weight_sum_error,
            outline_points,
            outline_error,
        },
    })
}

fn nearest_bone(balls: &[Ball2], p: Vec2) -> u16 {
    let mut best = (f32::MAX, 0u32);
    for b in balls {
        let d = b.center.distance_squared(p) / (b.radius * b.radius);
        if d < best.0 {
            best = (d, b.id);
        }
    }
    // Ball ids are bone indices, and `validate_skeleton` caps the bones at `MAX_BONES`.
    debug_assert!(best.1 < MAX_BONES as u32);
    best.1 as u16
}

fn validate_skeleton(skeleton: &Skeleton) -> Result<(), Error> {
    let bones = &skeleton.bones;
    if bones.is_empty() {
        return Err(Error::EmptySkeleton);
    }
    if bones.len() > MAX_BONES {
        return Err(Error::TooManyBones {
            bones: bones.len(),
            max: MAX_BONES,
        });
    }
    for (i, b) in bones.iter().enumerate() {
        match (i, b.parent) {
            (0, None) => {}
            (0, Some(p)) => {
                return Err(Error::BadParent {
                    bone: 0,
                    parent: Some(p),
                });
            }
            (_, Some(p)) if p < i => {}
            (_, parent) => return Err(Error::BadParent { bone: i, parent }),
        }
        if !(b.offset.is_finite()
            && b.position.is_finite()
            && b.rotation.is_finite()
            && b.thickness.is_finite()
            && b.multiplier.is_finite()
            && b.colour.is_finite()
            && b.texture_weights.is_finite())
        {
            return Err(Error::NonFinite { what: "bone" });
        }
        if !(b.thickness >= 0.0 && b.thickness <= 1000.0) {
            return Err(Error::OutOfRange {
                what: "bone thickness",
                value: b.thickness,
                min: 0.0,
                max: 1000.0,
            });
        }
        let (lo, hi) = MULTIPLIER_RANGE;
        if b.thickness > 0.0 && !(b.multiplier >= lo && b.multiplier <= hi) {
            return Err(Error::OutOfRange {
                what: "bone multiplier",
                value: b.multiplier,
                min: lo,
                max: hi,
            });
        }
    }
    for e in &skeleton.eyes {
        if !(e.position.is_finite() && e.radius.is_finite()) {
            return Err(Error::NonFinite { what: "eye" });
        }
    }
    if !bones.iter().skip(1).any(|b| b.thickness > 0.0) {
        return Err(Error::EmptySkeleton);
    }
    Ok(())
}

/// Covers every bone with balls (see [`build`]).
fn cover(skeleton: &Skeleton, params: &Params) -> Result<Vec<Ball>, Error> {
    let bones = &skeleton.bones;
    let mut out: Vec<Ball> = Vec::new();
    for (i, bone) in bones.iter().enumerate() {
        let Some(p) = bone.parent else { continue };
        // `validate_skeleton`: parents come first, and there are at most `MAX_BONES` bones.
        let parent = &bones[p];
        let id = p as u32;
        let (thickness, multiplier, colour, interior, parent_colour) = if bone.thickness > 0.0 {
            let parent_has_balls = parent.parent.is_some() && parent.thickness > 0.0;
            (
                bone.thickness,
                bone.multiplier,
                bone.colour,
                parent_has_balls,
                (parent.thickness > 0.0).then_some(parent.colour),
            )
        } else if params.connect_sockets {
            // A socket: cover the link to the parent with the first child's thickness.
            let child = bones
                .iter()
                .skip(i + 1)
                .find(|c| c.parent == Some(i) && c.thickness > 0.0);
            match child {
                Some(c) => (c.thickness, c.multiplier, c.colour, false, None),
                None => continue,
            }
        } else {
            continue;
        };
        let options = CoverOptions::DEFAULT.with_interior_joint(interior);
        let covering = cover_segment_with(
            bone.position,
            parent.position,
            thickness,
            multiplier,
            id,
            &options,
        )?;
        let length = bone.position.distance(parent.position);
        for ball in covering {
            let alpha = if length > 0.0 {
                (ball.center.distance(bone.position) / length).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let colour = match parent_colour {
                Some(pc) => colour.lerp(pc, alpha),
                None => colour,
            };
            out.push(Ball {
                ball,
                colour,
                texture_weights: bone.texture_weights,
            });
        }
    }
    if out.is_empty() {
        return Err(Error::EmptySkeleton);
    }
    Ok(out)
}
