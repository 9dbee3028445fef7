//! `generate`: the 3D seed's pipeline — blended pill body, FFD, body scale, auto-rig, skinning,
//! spine bend, head, limbs, ground clearance.

use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;

use glam::{Affine3A, Quat, Vec3};
use rand_core::Rng;

use creature_autorig::{RigOptions, RootAt, rig};
use creature_ffd::{Axis, Lattice};
use creature_gait::{GaitOptions, Leg, LimbKind as GaitLimb};
use creature_limbs::{Body, CreatureKind, HeadEnd, LimbKind, Side, SpineBone, plan};
use creature_skin::{Blend, nearest_k, skin_positions};

use super::accessories::{BackRow, add_back_row};
use super::body::{BASE_RADIUS, base_body, centre_of_volume, pill_triangles, volume_and_centre};
use super::clip::MAX_LEG_TURN_RATE;
use super::colour::{Colouring, body_surface};
use super::extremities::Proportions;
use super::gait::{
    mean_leg_size, swing_time_for_joints, walk_speed_limit, walker_gaits, walking_legs,
};
use super::head::{self, Shape};
use super::limbs::{
    Bind, LegChain, LimbNames, LimbStyle, MeshBuilder, Mount, WingSize, add_limb, leg_knees,
    limb_shape, socket_point,
};
use super::wings::Tone;
use super::{GaitSetup, Kind, Params};
use crate::Error;
use crate::d3::{Clip, Creature, Joint, Mesh, Part, Quality, Skeleton};
use crate::math::{asin, cos, powf, sin};
use crate::rng::{rng_for, uniform};
use crate::span::Span;
use rand_pcg::Pcg64Mcg;

/// The lattice slices at the head's end that narrow into a neck: the first `neck_width` × as
/// wide and high as the body's broadest, the next ones less so, back to the body's own along
/// a parabola (narrow for most of the neck, widening into the shoulders).
const NECK_SLICES: usize = 4;

/// FFD lattice divisions: 3×3 control points per slice, 11 slices along the body (the seed's).
const DIVISIONS: [usize; 3] = [2, 2, 10];

/// Generates a 3D creature from `seed` the 3D seed's way (thesis §4.1–4.2): a pill body shaped
/// by three of nine profiles blended with random weights, an FFD 3×3×11 lattice with randomly
/// scaled slices at monotonic positions, a body scale, an auto-rig (root at the centre for
/// walkers and fliers, at the head for swimmers), nearest-4-bone skinning, the neck and tail
/// bent (walkers and fliers), a head sphere, limbs planned on the rig's sockets and built as
/// meshes skinned to their own bones, the ground at `y = 0` under everything, the walkers'
/// gait set-up, and (with [`Params::clips`]) the kind's baked clips.
///
/// Same seed and params, same creature, bit for bit.
///
/// ```
/// use creature::d3::{generate, Kind, Params};
///
/// let walker = generate(7, &Params::DEFAULT.with_kind(Kind::Walker))?;
/// assert!(walker.quality.stability_margin.unwrap_or(-1.0) > 0.0);
/// assert!(walker.quality.min_height >= 0.0);
/// let mesh = &walker.mesh;
/// assert_eq!(mesh.positions.len(), mesh.weights.len());
/// assert!(mesh.indices.iter().flatten().all(|&i| (i as usize) < mesh.positions.len()));
/// # Ok::<(), creature::Error>(())
/// ```
///
/// # Errors
/// A parameter error from [`Params::validate`]; [`Error::Degenerate`] if the lattice would
/// fold; the sub-crates' errors (rig, skin, limbs, gait) wrapped. With the default parameters
/// (any kind) these do not happen for any seed the sweep has tried; limb options at the far
/// end of their ranges can ask for more than a body allows (a `min_margin` of 1 with a
/// `sweep` of 100 leaves no stable layout:
/// [`LimbsError::NoStableLayout`](crate::limbs::LimbsError::NoStableLayout) wrapped in
/// [`Error::Limbs`]).
pub fn generate(seed: u64, params: &Params) -> Result<Creature, Error> {
    params.validate()?;
    let mut rng = rng_for(seed);
    let spec = KindSpec::of(params.kind, &mut rng);
    generate_kind(&mut rng, params, spec)
}

/// What a creature kind changes in the pipeline: one entry of [`KINDS`] per kind, so a new
/// kind is mostly one new entry (plus its limbs in `creature-limbs` and its clips).
#[derive(Debug, Clone, Copy)]
pub(crate) struct KindSpec {
    /// The limb planner's kind (which limbs, where), also the creature's [`Creature::kind`].
    pub(crate) limbs: CreatureKind,
    /// Where the rig's root joint goes: the body's centre, or the head for a swimmer, whose
    /// body bends from the head back.
    pub(crate) root: RootAt,
    /// The FFD slices' random ranges (width, height, step) from the parameters.
    pub(crate) slices: fn(&Params) -> [Span; 3],
    /// Whether the neck and tail are bent at random, and a head sphere put on the neck tip.
    pub(crate) neck_and_head: bool,
    /// Whether the limbs are registered with the gait controller (walkers).
    pub(crate) walks: bool,
    /// Whether it lies on its belly (slitherers): no clearance under the body, more rings
    /// along it (it bends all along), and a speed by its length.
    pub(crate) crawls: bool,
}

/// The shared slice ranges of walkers and fliers.
fn body_slices(p: &Params) -> [Span; 3] {
    [p.slice_width, p.slice_height, p.slice_step]
}

/// The swimmers' own slice ranges (long, flat bodies).
fn swimmer_slices(p: &Params) -> [Span; 3] {
    [
        p.swimmer_slice_width,
        p.swimmer_slice_height,
        p.swimmer_slice_step,
    ]
}

/// The slitherers' own slice ranges (long, thin bodies).
fn slitherer_slices(p: &Params) -> [Span; 3] {
    [
        p.slitherer_slice_width,
        p.slitherer_slice_height,
        p.slitherer_slice_step,
    ]
}

/// Every kind; [`Kind::Random`] draws from the first [`RANDOM_KINDS`], in this order.
pub(crate) const KINDS: [KindSpec; 4] = [
    KindSpec {
        limbs: CreatureKind::Walker,
        root: RootAt::Centre,
        slices: body_slices,
        neck_and_head: true,
        walks: true,
        crawls: false,
    },
    KindSpec {
        limbs: CreatureKind::Flier,
        root: RootAt::Centre,
        slices: body_slices,
        neck_and_head: true,
        walks: false,
        crawls: false,
    },
    KindSpec {
        limbs: CreatureKind::Swimmer,
        root: RootAt::Head,
        slices: swimmer_slices,
        neck_and_head: false,
        walks: false,
        crawls: false,
    },
    KindSpec {
        limbs: CreatureKind::Slitherer,
        root: RootAt::Head,
        slices: slitherer_slices,
        neck_and_head: false,
        walks: false,
        crawls: true,
    },
];

/// How many of [`KINDS`] (the first) [`Kind::Random`] draws from: walkers, fliers and
/// swimmers, as it always has (a seed's random creature stays the one it was).
const RANDOM_KINDS: usize = 3;

/// A slitherer's rings along its body per ring of [`Params::rings`].
const CRAWLER_RINGS: u32 = 2;

/// A slitherer's spine bones per bone of [`Params::bone_length`] (and of the most of
/// [`Params::spine_bones`], up to [`MAX_CRAWLER_BONES`]): it bends all along, each joint a
/// little.
const CRAWLER_BONES: u32 = 2;

/// The most spine bones a slitherer's doubling gives (the most [`Params::spine_bones`]
/// allows).
const MAX_CRAWLER_BONES: u32 = 60;

/// A slitherer's speed per metre of its length, times its speed factor (m/s): at the default
/// factors, about half a body length a second.
const CRAWL_SPEED: f32 = 0.5;

impl KindSpec {
    /// The entry of `kind`; [`Kind::Random`] draws one of the first [`RANDOM_KINDS`] of
    /// [`KINDS`] uniformly.
    fn of(kind: Kind, rng: &mut impl Rng) -> &'static Self {
        match kind {
            Kind::Walker => &KINDS[0],
            Kind::Flier => &KINDS[1],
            Kind::Swimmer => &KINDS[2],
            Kind::Slitherer => &KINDS[3],
            Kind::Random => {
                let pick = (uniform(rng) * RANDOM_KINDS as f32) as usize;
                &KINDS[pick.min(RANDOM_KINDS - 1)]
            }
        }
    }
}

/// The pipeline for one kind, stage by stage. The stages draw from `rng` in this order, so
/// the order is part of the output (the goldens pin it).
fn generate_kind(rng: &mut Pcg64Mcg, params: &Params, spec: &KindSpec) -> Result<Creature, Error> {
    let crawler;
    let params = if spec.crawls {
        crawler = Params {
            rings: params.rings.saturating_mul(CRAWLER_RINGS),
            bone_length: params.bone_length / CRAWLER_BONES as f32,
            spine_bones: crate::span::IntSpan::new(
                params.spine_bones.min,
                params
                    .spine_bones
                    .max
                    .saturating_mul(CRAWLER_BONES)
                    .min(MAX_CRAWLER_BONES)
                    .max(params.spine_bones.max),
            ),
            ..*params
        };
        &crawler
    } else {
        params
    };
    let body = shape_body(rng, params, spec)?;
    // Where each body vertex lies on the rest-pose surface, before the spine bends.
    let surface = body_surface(
        &body.positions,
        params.rings as usize,
        params.segments as usize,
    );
    let mut rigged = rig_and_bend(rng, params, spec, body)?;
    // Salted by kind, so a seed's walker and flier (alike up to here) differ in colour.
    let salt = match spec.limbs {
        CreatureKind::Walker => 1,
        CreatureKind::Flier => 2,
        CreatureKind::Swimmer => 3,
        _ => 4,
    };
    let colouring = Colouring::draw(rng, &params.colours(), salt);
    let paint = colouring.paint_body(
        &surface,
        &rigged.triangles,
        params.segments as usize,
        params.flat_normals,
    );
    let mut mesh = skin_body(&rigged, &paint.vertices);
    let head_size = params.head_size.at(uniform(rng));
    let head = Shape::draw(&mut colouring.head_rng(), params);
    let face = if spec.neck_and_head {
        add_head(&mut mesh, &rigged.rig, head_size, &head, &colouring)?
    } else {
        // A snake's head is shorter than a fish's: its face nearer the tip.
        let behind = if spec.crawls { 0.05 } else { 0.1 };
        add_fish_face(&mut mesh, &rigged.rig, params, &head, &colouring, behind)
    };
    // Measured before anything else joins the head's joint.
    let neck = face
        .as_ref()
        .filter(|_| spec.neck_and_head)
        .and_then(|face| measure_neck(&mesh, rigged.positions.len(), &rigged.rig.spine, face));
    // A walker's back row, from a generator of its own, on the body's skin (before the limbs:
    // the feet stand under the body with its row).
    let (back, back_kind) = if spec.walks {
        let row = BackRow::draw(&mut colouring.back_rng(), params);
        let pieces = add_back_row(
            &mut mesh,
            rigged.positions.len(),
            &surface,
            &rigged.rig,
            &row,
            colouring.palette.accent,
        );
        (pieces, row.kind.filter(|_| pieces > 0))
    } else {
        (0, None)
    };
    // A crawler's belly lies on the ground (the draw is made all the same: one order of
    // draws for every kind).
    let clearance = params.ground_clearance.at(uniform(rng));
    let ground = ground_under(
        &mesh,
        if spec.crawls { 0.0 } else { clearance } * rigged.length,
    );
    let proportions = Proportions::draw(&mut colouring.limb_rng(), params);
    let mut limbs = add_limbs(
        rng,
        params,
        spec,
        &rigged,
        &mut mesh,
        ground,
        &colouring,
        &proportions,
    )?;
    let offset = stand_on_ground(
        &mut mesh,
        &mut rigged.rig,
        &mut limbs.joints,
        ground,
        &limbs.plan,
    );
    let mut speed_factor = rigged.speed_factor;
    let gait = if spec.walks {
        let setup;
        // Drawn for every walker (one order of draws), taken by bipeds.
        let hops = uniform(&mut colouring.gait_rng()) < params.hop_chance;
        (setup, speed_factor) = gait_setup(
            &limbs.chains,
            Vec3::Y * offset,
            rigged.body_scale,
            (speed_factor, hops),
        )?;
        Some(setup)
    } else {
        None
    };
    let joints = limbs.joints;
    if joints.len() > usize::from(u16::MAX) {
        return Err(Error::TooManyBones {
            bones: joints.len(),
            max: usize::from(u16::MAX),
        });
    }
    let mesh = finish_mesh(mesh, params.flat_normals, paint.faces.as_deref());
    let mut quality = measure(
        &mesh,
        &limbs.plan,
        rigged.fold_min_determinant,
        rigged.length,
        rigged.bend_degrees,
    );
    quality.belly_contrast = paint.contrast;
    quality.eyes_in_view = face.map_or(0, |f| f.eyes_in_view());
    quality.back_ornaments = back;
    quality.back_kind = back_kind;
    quality.neck_to_head_and_body = neck;
    quality.wing_kind = limbs
        .plan
        .limbs_of(LimbKind::FlappingWing)
        .next()
        .map(|_| proportions.wing_kind);
    [
        quality.thigh_to_shin_radius,
        quality.wing_span_to_body_length,
        quality.wing_area_to_body_volume,
    ] = measure_limbs(&mesh, &joints, &limbs.plan, rigged.length);
    let mut creature = Creature {
        kind: spec.limbs,
        mesh,
        skeleton: Skeleton { joints },
        rig: rigged.rig,
        plan: limbs.plan,
        ground_offset: offset,
        profiles: rigged.profiles,
        body_scale: rigged.body_scale,
        speed: if spec.crawls {
            CRAWL_SPEED * rigged.length * speed_factor
        } else {
            rigged.body_scale * speed_factor
        },
        gait,
        clips: Vec::new(),
        length: rigged.length,
        palette: colouring.palette,
        quality,
    };
    if params.clips {
        creature.clips = creature.bake_clips()?;
        if params.in_place {
            creature.clips = creature.clips.into_iter().map(Clip::in_place).collect();
        }
    }
    Ok(creature)
}

/// The body before rigging: blended profiles on one pill topology, deformed by the FFD
/// lattice and scaled.
struct ShapedBody {
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    profiles: Vec<(usize, f32)>,
    fold_min_determinant: f32,
    body_scale: f32,
    speed_factor: f32,
}

/// Stages 1–3: base body (blended profiles on one pill), FFD (slices scaled at random across,
/// placed at monotonic steps along the body), body scale and speed.
fn shape_body(rng: &mut Pcg64Mcg, params: &Params, spec: &KindSpec) -> Result<ShapedBody, Error> {
    let (rings, segments) = (params.rings as usize, params.segments as usize);
    let (mut positions, profiles) = base_body(rng, params.profiles as usize, rings, segments);
    let triangles = pill_triangles(rings, segments);

    let [width, height, step] = (spec.slices)(params);
    let mut lattice = Lattice::around(&positions, DIVISIONS, 0.05 * BASE_RADIUS)?;
    let slices = lattice.slice_count(Axis::U);
    // The pill's head tip is its last vertex; the lattice's slices run along z (`U`), from
    // the head's end or the tail's.
    let head_first = match (positions.first(), positions.last()) {
        (Some(tail), Some(head)) => head.z < tail.z,
        _ => false,
    };
    let mut scales: Vec<Vec3> = (0..slices)
        .map(|_| Vec3::new(width.at(uniform(rng)), height.at(uniform(rng)), 1.0))
        .collect();
    if spec.neck_and_head {
        // A neck under the head (see [`NECK_SLICES`]): its slices no wider or higher than
        // the body's broadest behind them, then narrowed.
        let from_head = |k: usize| if head_first { k } else { slices - 1 - k };
        debug_assert!(slices > NECK_SLICES, "a lattice longer than its neck");
        let broadest = (0..slices)
            .filter(|&k| from_head(k) >= NECK_SLICES)
            .fold(Vec3::Z, |m, k| m.max(scales[k]));
        let w = params.neck_width;
        for (k, s) in scales.iter_mut().enumerate() {
            if from_head(k) < NECK_SLICES {
                let t = from_head(k) as f32 / NECK_SLICES as f32;
                let neck = w + (1.0 - w) * t * t;
                *s = s.min(broadest) * Vec3::new(neck, neck, 1.0);
            }
        }
    }
    for (k, s) in scales.into_iter().enumerate() {
        lattice.scale_slice(Axis::U, k, s)?;
    }
    let base_gap = lattice.axes()[2].length() / DIVISIONS[2] as f32;
    let gaps: Vec<f32> = (0..DIVISIONS[2])
        .map(|_| base_gap * step.at(uniform(rng)))
        .collect();
    lattice.distribute_slices(Axis::U, &gaps)?;
    let fold = lattice.fold_report(8);
    if fold.folds() {
        return Err(Error::Degenerate {
            what: "body lattice (it folds)",
        });
    }
    lattice.try_deform_in_place(&mut positions)?;

    let body_scale = params.body_scale.at(uniform(rng));
    let speed_factor = params.speed_factor.at(uniform(rng));
    for p in &mut positions {
        *p *= body_scale;
    }
    Ok(ShapedBody {
        positions,
        triangles,
        profiles,
        fold_min_determinant: fold.min_determinant,
        body_scale,
        speed_factor,
    })
}

/// The rigged body: the auto-rig (bent), its skin weights, and what the later stages measure.
struct RiggedBody {
    rig: creature_autorig::Rig,
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    influences: Vec<creature_skin::Influences>,
    length: f32,
    bend_degrees: [f32; 2],
    profiles: Vec<(usize, f32)>,
    fold_min_determinant: f32,
    body_scale: f32,
    speed_factor: f32,
}

/// Stages 4–5: the auto-rig (root by kind), the neck and tail bent where the kind has them,
/// and nearest-4-bone skin weights on the bent body.
fn rig_and_bend(
    rng: &mut Pcg64Mcg,
    params: &Params,
    spec: &KindSpec,
    body: ShapedBody,
) -> Result<RiggedBody, Error> {
    let ShapedBody {
        mut positions,
        triangles,
        profiles,
        fold_min_determinant,
        body_scale,
        speed_factor,
    } = body;
    let options = RigOptions::DEFAULT
        .with_root(spec.root)
        .with_bone_length(params.bone_length * body_scale)
        .with_bone_count(
            params.spine_bones.min as usize,
            params.spine_bones.max as usize,
        );
    let mut body_rig = rig(&positions, &triangles, &options)?;
    let mut bend_degrees = [0.0f32; 2];
    if spec.neck_and_head {
        bend_degrees = bend_spine(rng, params, &mut body_rig, &mut positions)?;
    }
    let influences = spine_influences(&body_rig, &positions)?;
    let length = body_rig.spine_length();
    Ok(RiggedBody {
        rig: body_rig,
        positions,
        triangles,
        influences,
        length,
        bend_degrees,
        profiles,
        fold_min_determinant,
        body_scale,
        speed_factor,
    })
}

/// Body weights along the spine: each vertex goes to its nearest point on the spine polyline,
/// and its weight moves linearly from one bone to the next between the bones' midpoints (two
/// bones at most, the bend spread over whole bones), so the skin bends like a tube however thick
/// the body is against its bones. (Nearest-bone weights share a thick body's far vertices among
/// up to four bones all along it, which tears the skin when the spine waves.)
fn spine_influences(
    body: &creature_autorig::Rig,
    positions: &[Vec3],
) -> Result<Vec<creature_skin::Influences>, Error> {
    let spine = &body.spine;
    let root = root_on_spine(body)?;
    let points: Vec<Vec3> = spine.iter().map(|&j| body.joints[j].position).collect();
    let bones = points.len().saturating_sub(1);
    if bones == 0 {
        return Ok(
            alloc::vec![creature_skin::Influences::single(spine[0] as u16); positions.len()],
        );
    }
    // The joint that moves polyline bone `i` (points `i` to `i + 1`): the end nearer the root.
    let carrier = |i: usize| (if i >= root { spine[i] } else { spine[i + 1] }) as u16;
    let mut start = Vec::with_capacity(bones + 1);
    let mut arc = 0.0f32;
    for i in 0..bones {
        start.push(arc);
        arc += points[i].distance(points[i + 1]);
    }
    start.push(arc);
    let middle = |i: usize| 0.5 * (start[i] + start[i + 1]);
    // Each joint's bisecting plane: normal along the spine (the mean of its two bones'
    // directions; the end bone's at the tips).
    let direction = |i: usize| (points[i + 1] - points[i]).normalize_or(Vec3::Z);
    let normals: Vec<Vec3> = (0..=bones)
        .map(|k| match k {
            0 => direction(0),
            k if k == bones => direction(bones - 1),
            k => (direction(k - 1) + direction(k)).normalize_or(direction(k)),
        })
        .collect();
    let influences = positions
        .iter()
        .map(|&v| {
            // Arc length along the spine, from the planes that bisect it at its joints: the
            // vertex's signed distances to the two planes around it split its bone. (The
            // nearest point on a bent polyline jumps on the inside of each bend.)
            let h = |k: usize| (v - points[k]).dot(normals[k]);
            let s = match (1..=bones).find(|&k| h(k) < 0.0) {
                // Before the first plane's far side: past the tail tip, or on bone `k - 1`.
                Some(1) if h(0) < 0.0 => h(0),
                Some(k) => {
                    let (a, b) = (h(k - 1), -h(k));
                    start[k - 1] + (start[k] - start[k - 1]) * (a / (a + b).max(1e-30))
                }
                None => start[bones] + h(bones),
            };
            // `u`: `k` at bone `k`'s middle, linear in arc length between middles (and past
            // the end bones at their own lengths).
            let u = match (0..bones).rev().find(|&i| middle(i) <= s) {
                None => (s - middle(0)) / (start[1] - start[0]).max(1e-12),
                Some(k) if k + 1 >= bones => {
                    k as f32 + (s - middle(k)) / (start[k + 1] - start[k]).max(1e-12)
                }
                Some(k) => k as f32 + (s - middle(k)) / (middle(k + 1) - middle(k)).max(1e-12),
            };
            // Uniform quadratic B-spline weights over the three bones nearest `u`: the bend
            // spreads over two bones' length, smoothly. Bones past either end fold into it.
            let u = u.clamp(-1.0, bones as f32);
            let j = crate::math::floor_f(u + 0.5);
            let g = u + 0.5 - j;
            let mut inf = creature_skin::Influences::NONE;
            let mut slots = 0;
            for (d, w) in [
                (-1.0f32, 0.5 * (1.0 - g) * (1.0 - g)),
                (0.0, 0.5 + g - g * g),
                (1.0, 0.5 * g * g),
            ] {
                let bone = (j + d).clamp(0.0, (bones - 1) as f32) as usize;
                let joint = carrier(bone);
                match inf.joints[..slots].iter().position(|&x| x == joint) {
                    // The three terms sum to 1 exactly, not always in `f32`: a joint holding
                    // all three got 1.0000001 (regression:
                    // `regression_folded_body_weights_stay_within_one`).
                    Some(k) => inf.weights[k] = (inf.weights[k] + w).min(1.0),
                    None => {
                        inf.joints[slots] = joint;
                        inf.weights[slots] = w;
                        slots += 1;
                    }
                }
            }
            inf
        })
        .collect();
    Ok(influences)
}

/// Stage 6: the body's vertices, coloured and bound by their skin weights, into the mesh.
fn skin_body(body: &RiggedBody, colours: &[Vec3]) -> MeshBuilder {
    let mut mesh = MeshBuilder::default();
    for ((p, inf), &colour) in body.positions.iter().zip(&body.influences).zip(colours) {
        mesh.vertex(*p, colour, Bind::from_arrays(inf.joints, inf.weights));
    }
    mesh.indices.extend_from_slice(&body.triangles);
    mesh
}

/// Stage 7: the ground, `clearance` below the lowest vertex of the body (and head).
fn ground_under(mesh: &MeshBuilder, clearance: f32) -> f32 {
    let body_min_y = mesh
        .positions
        .iter()
        .map(|p| p.y)
        .fold(f32::INFINITY, f32::min);
    body_min_y - clearance
}

/// The limbs as built: the plan, the whole skeleton (spine then limb joints), and the legs'
/// and arms' chains (plan index, kind, chain).
struct BuiltLimbs {
    plan: creature_limbs::Plan,
    joints: Vec<Joint>,
    chains: Vec<(usize, LimbKind, LegChain)>,
}

/// Stage 8: limbs planned on the rig's sockets, each built as joints and a mesh skinned to
/// them, in the creature's `proportions` (wings sized for the body and head as `mesh`
/// has them now).
#[allow(clippy::too_many_arguments)]
fn add_limbs(
    rng: &mut Pcg64Mcg,
    params: &Params,
    spec: &KindSpec,
    body: &RiggedBody,
    mesh: &mut MeshBuilder,
    ground: f32,
    colouring: &Colouring,
    proportions: &Proportions,
) -> Result<BuiltLimbs, Error> {
    let volume = volume_and_centre(&mesh.positions, &mesh.indices).0.max(0.0);
    let wing = WingSize {
        span: proportions.wing_span * body.length,
        area: proportions.wing_area * powf(volume, 2.0 / 3.0),
    };
    let body_rig = &body.rig;
    let positions = &body.positions;
    let (bones, sockets) = limb_body(body_rig, positions, ground, spec.walks);
    let limb_body = Body::new(bones, body.length, HeadEnd::Last);
    let mut limb_plan = plan(&limb_body, spec.limbs, &params.limbs, rng)?;
    // The planner's bones are the distinct sockets: each limb on its rig socket.
    for limb in &mut limb_plan.limbs {
        limb.bone = sockets[limb.bone];
        limb.span.first_bone = sockets[limb.span.first_bone];
        limb.span.last_bone = sockets[limb.span.last_bone];
    }
    let (body_vertices, body_triangles) = (mesh.positions.len(), mesh.indices.len());

    // The limbs as planned, then, while the mesh's real centre of mass is not well inside the
    // feet, again with the feet moved toward it (the limbs move it too): `LIMB_PASSES` at most.
    let mut pass = 0;
    loop {
        let mut names = spine_names(body_rig, spec.neck_and_head);
        let mut joints: Vec<Joint> = body_rig
            .joints
            .iter()
            .zip(&mut names)
            .map(|(j, name)| Joint {
                name: core::mem::take(name),
                position: j.position,
                parent: j.parent,
                part: Part::Spine,
            })
            .collect();
        let tail = &body_rig.joints[body_rig.tail];
        let mut chains = Vec::new();
        let mut limb_names = LimbNames::default();
        // The planner places limbs on the sockets it was given, one per body bone.
        let mut mounts = Vec::with_capacity(limb_plan.limbs.len());
        for limb in &limb_plan.limbs {
            let socket = &body_rig.sockets[limb.bone];
            let point = socket_point(
                limb.socket,
                positions[socket.left_vertex as usize],
                positions[socket.right_vertex as usize],
                positions[socket.top_vertex as usize],
                tail.position,
            )?;
            // A pair on the back (a top socket) grows from either side of the spine, mirrored,
            // even where the ring's top vertex is off the midline (both would grow from it).
            let spine_at = body_rig.joints[socket.joint].position;
            let point = match (limb.socket, limb.side) {
                (creature_limbs::Socket::Top, Side::Left | Side::Right) => {
                    let out = if limb.side == Side::Left { 1.0 } else { -1.0 };
                    let x = spine_at.x + out * (point.x - spine_at.x).abs();
                    Vec3::new(x, point.y, point.z)
                }
                _ => point,
            };
            let joint = if limb.socket == creature_limbs::Socket::Tip {
                // A tail fin hangs on the joint before the tail tip (the rig roots at the centre
                // or the head, so the tip always has one).
                tail.parent.ok_or(Error::Degenerate {
                    what: "rig (its tail tip is the root, so a tail limb has no joint to hang on)",
                })?
            } else {
                socket.joint
            };
            mounts.push(Mount {
                point,
                joint,
                width: body_width(body_rig, socket.bone),
                centre: body_rig.joints[joint].position,
            });
        }
        let knees = leg_knees(&limb_plan, &mounts);
        let mut painted = Vec::with_capacity(limb_plan.limbs.len());
        for (index, (limb, &mount)) in limb_plan.limbs.iter().zip(&mounts).enumerate() {
            let shape = limb_shape(limb.kind)?;
            let first = mesh.positions.len();
            let built = add_limb(
                mesh,
                &mut joints,
                &mut limb_names,
                index,
                limb,
                shape,
                mount,
                LimbStyle {
                    knee: knees[index],
                    sides: params.limb_sides as usize,
                    colour: colouring.palette.base,
                    foot: proportions.foot,
                    thigh: proportions.thigh,
                    wing,
                    wing_kind: proportions.wing_kind,
                    tail_fin: proportions.tail_fin,
                    flat: params.flat_normals,
                },
            );
            let socket = &body_rig.sockets[limb.bone];
            let near = [
                socket.left_vertex,
                socket.right_vertex,
                socket.top_vertex,
                0,
            ];
            painted.push(LimbPaint {
                vertices: first..mesh.positions.len(),
                join: mount.point,
                near,
                membrane: shape.membrane_colour,
                horn: built.horn,
                tones: built.tones,
            });
            if let Some(chain) = built.chain {
                chains.push((index, limb.kind, chain));
            }
        }
        pass += 1;
        // Walkers stand on their feet; fliers' legs dangle where the planner put them.
        if pass == LIMB_PASSES
            || !spec.walks
            || !feet_under_mass(mesh, &mut limb_plan, body.length, pass)
        {
            for limb in &painted {
                colour_limb(mesh, limb, |root, reach| {
                    colouring.limb(root, limb.membrane, reach)
                });
                for colour in mesh.colours.get_mut(limb.horn.clone()).unwrap_or(&mut []) {
                    *colour = HORN;
                }
                // A wing's tones (its vertices are all the limb's).
                debug_assert!(limb.tones.is_empty() || limb.tones.len() == limb.vertices.len());
                let colours = mesh
                    .colours
                    .get_mut(limb.vertices.clone())
                    .unwrap_or(&mut []);
                for (colour, &tone) in colours.iter_mut().zip(&limb.tones) {
                    *colour = colouring.wing_tone(*colour, tone);
                }
            }
            break Ok(BuiltLimbs {
                plan: limb_plan,
                joints,
                chains,
            });
        }
        mesh.truncate(body_vertices, body_triangles);
    }
}

/// A limb to colour once the limbs are final: its vertices, where it joins the body, and the
/// body vertices near the join (its socket's left, right and top vertices, and the tail tip).
struct LimbPaint {
    vertices: core::ops::Range<usize>,
    join: Vec3,
    near: [u32; 4],
    membrane: bool,
    /// Its vertices in [`HORN`] (hooves, claws).
    horn: core::ops::Range<usize>,
    /// A wing's tone per vertex, from its first (empty for other limbs).
    tones: Vec<Tone>,
}

/// The colour of hooves and claws (linear RGB): a dark horn.
const HORN: Vec3 = Vec3::new(0.09, 0.075, 0.06);

/// Colours `limb`'s vertices by `colour(root, reach)`: `root` the colour of the body vertex
/// of `limb.near` nearest the join, `reach` the vertex's distance from the join × the limb's
/// farthest.
fn colour_limb(mesh: &mut MeshBuilder, limb: &LimbPaint, colour: impl Fn(Vec3, f32) -> Vec3) {
    let root = limb
        .near
        .iter()
        .filter_map(|&v| {
            let v = v as usize;
            Some((
                mesh.positions.get(v)?.distance_squared(limb.join),
                *mesh.colours.get(v)?,
            ))
        })
        .fold((f32::INFINITY, None), |best, (d, c)| {
            if d < best.0 { (d, Some(c)) } else { best }
        })
        .1;
    let (Some(root), Some(positions)) = (root, mesh.positions.get(limb.vertices.clone())) else {
        return;
    };
    let extent = positions
        .iter()
        .map(|p| p.distance(limb.join))
        .fold(0.0f32, f32::max)
        .max(1e-6);
    for i in limb.vertices.clone() {
        let reach = mesh.positions[i].distance(limb.join) / extent;
        mesh.colours[i] = colour(root, reach);
    }
}

/// How many times at most the limbs are built, moving the feet toward the centre of mass.
const LIMB_PASSES: usize = 5;

/// How far inside the feet's footprint a walker's centre of mass must be, × body length,
/// before [`feet_under_mass`] leaves the feet where the planner put them.
const STABLE_MARGIN: f32 = 0.03;

/// Moves the planned feet (along the body) under the mesh's centre of mass (body, head and
/// limbs, by volume) when it is less than [`STABLE_MARGIN`] inside the convex hull of what
/// touches the ground; true when it moved them. The footprint grows toward the mass: with the
/// mass ahead, the front feet step forward (a heavy head's legs splay forward), with it behind,
/// the hind feet back, and the other feet follow by what those cannot reach; a single pair
/// goes under it. No foot moves more than its leg's length. From the third pass on (`pass` 2),
/// the whole stance moves toward the mass (its feet's centre toward right below it, no foot
/// more than twice its leg's length), only as far as puts the mass [`STABLE_MARGIN`] inside
/// the feet: a stance moved all the way under a mass far ahead raked every leg forward, the
/// hind feet under the front hips, and a side's legs passed through each other.
fn feet_under_mass(
    mesh: &MeshBuilder,
    plan: &mut creature_limbs::Plan,
    length: f32,
    pass: usize,
) -> bool {
    let (mut front, mut back) = (f32::NEG_INFINITY, f32::INFINITY);
    for foot in plan.limbs.iter().filter_map(|l| l.foot) {
        front = front.max(foot.z);
        back = back.min(foot.z);
    }
    if !(front >= back) {
        return false;
    }
    let Some((centre, margin)) = standing(&mesh.positions, &mesh.indices, length) else {
        return false;
    };
    if margin.is_some_and(|m| m >= STABLE_MARGIN * length) {
        return false;
    }
    let want = STABLE_MARGIN * length;
    if pass >= 2 {
        // Growing the footprint was not enough (an odd layout, or a mass far off): the whole
        // stance goes toward the mass, its feet's centre toward right below it.
        let (mut sum, mut n) = (glam::Vec2::ZERO, 0.0f32);
        for foot in plan.limbs.iter().filter_map(|l| l.foot) {
            sum += glam::Vec2::new(foot.x, foot.z);
            n += 1.0;
        }
        let mass = glam::Vec2::new(centre.x, centre.z);
        let full = mass - sum / n;
        // Each foot's move by a share `t` of the full shift, no more than twice its leg's
        // length; across the body only the feet on the mass's side move (outward), so the
        // stance widens toward a mass off to one side instead of carrying a foot across the
        // midline.
        let middle = sum.x / n;
        let shift = |limb: &creature_limbs::Limb, t: f32| {
            let s = (full * t).clamp_length_max(2.0 * limb.length);
            let toward = limb.foot.is_some_and(|f| (f.x - middle) * full.x > 0.0);
            glam::Vec2::new(if toward { s.x } else { 0.0 }, s.y)
        };
        let moved = |t: f32| {
            plan.limbs.iter().filter_map(move |limb| {
                let s = shift(limb, t);
                limb.foot.map(|f| glam::Vec2::new(f.x + s.x, f.z + s.y))
            })
        };
        // Only as far as puts the mass `want` inside the feet (their points: the footprint
        // around them is larger), so the legs rake no more than they must.
        let mut points: Vec<glam::Vec2> = Vec::with_capacity(plan.limbs.len());
        let mut hull = Vec::new();
        let mut enough = |t: f32| {
            points.clear();
            points.extend(moved(t));
            creature_gait::support_margin(&mut points, &mut hull, mass).is_some_and(|m| m >= want)
        };
        let t = if enough(1.0) {
            let (mut low, mut high) = (0.0f32, 1.0f32);
            for _ in 0..12 {
                let mid = 0.5 * (low + high);
                if enough(mid) {
                    high = mid;
                } else {
                    low = mid;
                }
            }
            high
        } else {
            1.0
        };
        let shifts: Vec<glam::Vec2> = plan.limbs.iter().map(|limb| shift(limb, t)).collect();
        for (limb, s) in plan.limbs.iter_mut().zip(shifts) {
            if let Some(foot) = limb.foot.as_mut() {
                foot.x += s.x;
                foot.z += s.y;
            }
        }
        return true;
    }
    // How far the front feet must go forward (or the hind feet back) to have the mass
    // `want` inside them.
    let ahead = (centre.z + want - front).max(0.0);
    let behind = (centre.z - want - back).min(0.0);
    // A pair steps together: a foot whose mirror is at the front (back) is a front (hind)
    // foot too, so a lopsided pair does not leave one foot behind under the next pair's.
    let at = |limb: &creature_limbs::Limb, edge: f32| {
        let near =
            |l: &creature_limbs::Limb| l.foot.is_some_and(|f| (f.z - edge).abs() <= 1e-3 * length);
        near(limb)
            || limb
                .mirror
                .and_then(|m| plan.limbs.get(m))
                .is_some_and(near)
    };
    let ends: Vec<(bool, bool)> = plan
        .limbs
        .iter()
        .map(|l| (at(l, front), at(l, back)))
        .collect();
    for (limb, &(is_front, is_back)) in plan.limbs.iter_mut().zip(&ends) {
        let reach = limb.length;
        let Some(foot) = limb.foot.as_mut() else {
            continue;
        };
        let shift = if front - back < want {
            // One pair (or feet nearly abreast): under the mass.
            centre.z - foot.z
        } else if is_front {
            ahead
        } else if is_back {
            behind
        } else {
            // What the front (or hind) feet cannot reach, the rest of the stance follows.
            (ahead - reach).max(0.0) + (behind + reach).min(0.0)
        };
        foot.z += shift.clamp(-reach, reach);
    }
    true
}

/// The root's place on the rig's spine (rigs built by `rig` root on it).
fn root_on_spine(body: &creature_autorig::Rig) -> Result<usize, Error> {
    body.root()
        .and_then(|r| body.spine.iter().position(|&j| j == r))
        .ok_or(Error::Degenerate {
            what: "rig (its root is not on the spine)",
        })
}

/// How a mesh stands: its centre of volume, and that centre's margin inside the convex hull
/// of the vertices on the ground (within 0.5% of `length` of the lowest), as
/// `creature_gait::support_margin` gives it. `None` when the mesh encloses no volume.
fn standing(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    length: f32,
) -> Option<(Vec3, Option<f32>)> {
    let centre = centre_of_volume(positions, triangles)?;
    let lowest = positions.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
    let mut contacts: Vec<glam::Vec2> = positions
        .iter()
        .filter(|p| p.y <= lowest + 0.005 * length)
        .map(|p| glam::Vec2::new(p.x, p.z))
        .collect();
    let margin = creature_gait::support_margin(
        &mut contacts,
        &mut Vec::new(),
        glam::Vec2::new(centre.x, centre.z),
    );
    Some((centre, margin))
}

/// The spine joints' names, by joint index (see [`Joint::name`]): `spine_0` at the root,
/// `spine_k` toward the head end, whose joint before the tip is `head` on kinds with a head and
/// whose tip is `head_end`; `tail_k` toward the tail end (`spine_k` when the root is at the head
/// end), whose tip is `tail_end`.
fn spine_names(body: &creature_autorig::Rig, has_head: bool) -> Vec<String> {
    let mut names = alloc::vec![String::new(); body.joints.len()];
    let spine = &body.spine;
    let Ok(c) = root_on_spine(body) else {
        // Rigs built by `rig` root on their spine; name by index otherwise.
        for (i, name) in names.iter_mut().enumerate() {
            *name = format!("spine_{i}");
        }
        return names;
    };
    let n = spine.len();
    let hind = if c == n - 1 { "spine" } else { "tail" };
    for (k, &j) in spine.iter().enumerate() {
        names[j] = if k == c {
            "spine_0".into()
        } else if k > c && k == n - 1 {
            "head_end".into()
        } else if k > c && k == n - 2 && has_head {
            "head".into()
        } else if k > c {
            format!("spine_{}", k - c)
        } else if k == 0 {
            "tail_end".into()
        } else {
            format!("{hind}_{}", c - k)
        };
    }
    // Joints off the spine (none in rigs built by `rig`).
    for (i, name) in names.iter_mut().enumerate() {
        if name.is_empty() {
            *name = format!("joint_{i}");
        }
    }
    names
}

/// Stage 9: the ground to `y = 0` (the plan's lift applied) and nothing under it; moves the
/// mesh, the skeleton and the rig. Returns the vertical offset applied.
fn stand_on_ground(
    mesh: &mut MeshBuilder,
    body_rig: &mut creature_autorig::Rig,
    joints: &mut [Joint],
    ground: f32,
    limb_plan: &creature_limbs::Plan,
) -> f32 {
    let mut offset = -(ground - limb_plan.lift);
    let lowest = mesh
        .positions
        .iter()
        .map(|p| p.y + offset)
        .fold(f32::INFINITY, f32::min);
    if lowest < 0.0 {
        offset -= lowest;
    }
    let shift = Vec3::Y * offset;
    for p in &mut mesh.positions {
        *p += shift;
    }
    for j in joints {
        j.position += shift;
    }
    for j in &mut body_rig.joints {
        j.position += shift;
    }
    for s in &mut body_rig.sockets {
        s.left += shift;
        s.right += shift;
        s.top += shift;
    }
    offset
}

/// Stage 10 (walkers): the legs and arms registered for the gait controller, checked by
/// building one, so a creature never carries a set-up the controller rejects; its swings long
/// enough for the joints (see `swing_time_for_joints`). With the speed factor it walks at:
/// `speed_factor`, the drawn one, at most what its legs walk (see `walk_speed_limit`).
fn gait_setup(
    chains: &[(usize, LimbKind, LegChain)],
    shift: Vec3,
    body_scale: f32,
    (speed_factor, hops): (f32, bool),
) -> Result<(GaitSetup, f32), Error> {
    let mut legs = Vec::with_capacity(chains.len());
    let mut limbs = Vec::with_capacity(chains.len());
    let mut hip_joints = Vec::with_capacity(chains.len());
    for (index, limb_kind, c) in chains {
        let gait_kind = if *limb_kind == LimbKind::Arm {
            GaitLimb::Arm
        } else {
            GaitLimb::Leg
        };
        legs.push(
            Leg::new(c.hip + shift, c.end + shift, c.upper, c.lower)
                .with_pole(c.pole)
                .with_size(c.hip.distance(c.end).max(1e-3))
                .with_kind(gait_kind),
        );
        limbs.push(*index);
        hip_joints.push(c.hip_joint);
    }
    let speed_factor = mean_leg_size(&legs).map_or(speed_factor, |leg| {
        speed_factor.min(walk_speed_limit(leg) / body_scale)
    });
    let mut options = GaitOptions::DEFAULT
        .with_speed_multiplier(speed_factor)
        .with_gaits(walker_gaits(&legs, hops));
    options.hop = hops && walking_legs(&legs) == 2;
    options.min_swing_time = swing_time_for_joints(&legs, &options, MAX_LEG_TURN_RATE);
    let setup = GaitSetup {
        legs,
        limbs,
        hip_joints,
        options,
    };
    setup.controller()?;
    Ok((setup, speed_factor))
}

/// Bends the neck and the tail of a centre-rooted rig: each bone by the same random angle, at
/// most `spine_bend / bones` degrees and at most half the budget over the whole chain. Moves
/// the joints, sockets and vertices (linear blend skinning with nearest-4 weights). Returns
/// the neck's and tail's total bends in degrees.
fn bend_spine(
    rng: &mut impl Rng,
    params: &Params,
    body: &mut creature_autorig::Rig,
    positions: &mut [Vec3],
) -> Result<[f32; 2], Error> {
    let spine = body.spine.clone();
    let bones = spine.len().saturating_sub(1);
    // The rig roots on its spine (at the centre, for the kinds that bend).
    let c = root_on_spine(body)?;
    if bones == 0 {
        return Ok([0.0; 2]);
    }
    let per_bone_cap = params.spine_bend / bones as f32;
    // Rotating joints: neck spine[c+1..bones], tail spine[1..c].
    let neck_joints = bones.saturating_sub(c + 1);
    let tail_joints = c.saturating_sub(1);
    let half = params.spine_bend * 0.5;
    let cap = |n: usize| {
        if n == 0 {
            0.0
        } else {
            per_bone_cap.min(half / n as f32)
        }
    };
    let neck_angle = uniform(rng) * cap(neck_joints);
    let tail_sign = if uniform(rng) < 0.5 { -1.0 } else { 1.0 };
    let tail_angle = uniform(rng) * cap(tail_joints);

    let rest: Vec<Vec3> = body.joints.iter().map(|j| j.position).collect();
    let mut transforms = alloc::vec![Affine3A::IDENTITY; rest.len()];
    let rotate_about = |pivot: Vec3, degrees: f32| {
        Affine3A::from_translation(pivot)
            * Affine3A::from_quat(Quat::from_rotation_x(degrees.to_radians()))
            * Affine3A::from_translation(-pivot)
    };
    // Neck: head up is a rotation of −angle about X.
    let mut previous = Affine3A::IDENTITY;
    for &j in spine.iter().take(bones).skip(c + 1) {
        previous *= rotate_about(rest[j], -neck_angle);
        transforms[j] = previous;
    }
    previous = Affine3A::IDENTITY;
    for &j in spine.iter().take(c).skip(1).rev() {
        previous *= rotate_about(rest[j], tail_sign * tail_angle);
        transforms[j] = previous;
    }
    // Vertices by linear blend skinning on the straight rig's weights.
    let influences = nearest_k(positions, &body.bone_segments(), 4)?;
    let bone_joints: Vec<usize> = body.bones().into_iter().map(|(j, _)| j).collect();
    let per_segment: Vec<Affine3A> = bone_joints.iter().map(|&j| transforms[j]).collect();
    let rest_positions = positions.to_vec();
    skin_positions(
        &rest_positions,
        &influences,
        &per_segment,
        Blend::Linear,
        positions,
    )?;
    // Joints: moved by their parent's transform.
    for (i, joint) in body.joints.iter_mut().enumerate() {
        if let Some(p) = joint.parent {
            joint.position = transforms[p].transform_point3(rest[i]);
        }
    }
    // Socket vertices index the rigged mesh's positions.
    for s in &mut body.sockets {
        let (l, r) = (
            positions[s.left_vertex as usize],
            positions[s.right_vertex as usize],
        );
        s.left = l;
        s.right = r;
        s.top = positions[s.top_vertex as usize];
        s.width = l.distance(r);
    }
    Ok([
        neck_angle * neck_joints as f32,
        tail_angle * tail_joints as f32,
    ])
}

/// The body's width at spine bone `bone`: its socket's; if that has no width (a coarse
/// cross-section, e.g. 3 segments, can have a single vertex beside a bone), the widest of its
/// neighbours', else the widest socket's, else the base body's.
fn body_width(body: &creature_autorig::Rig, bone: usize) -> f32 {
    let widest = |reach: usize| {
        body.sockets
            .iter()
            .filter(|s| s.bone.abs_diff(bone) <= reach)
            .map(|s| s.width)
            .filter(|w| w.is_finite())
            .fold(0.0f32, f32::max)
    };
    let floor = 1e-3 * body.spine_length().max(1e-6);
    [widest(0), widest(1), widest(usize::MAX)]
        .into_iter()
        .find(|&w| w > floor)
        .unwrap_or(2.0 * BASE_RADIUS)
}

/// The least width of a head (at `head_size` 1) × the neck's under it.
const HEAD_OVER_NECK: f32 = 1.3;

/// The head of `shape` on the neck tip, bound to the `head` joint (the last neck bone's).
fn add_head(
    mesh: &mut MeshBuilder,
    body: &creature_autorig::Rig,
    size: f32,
    shape: &Shape,
    colouring: &Colouring,
) -> Result<Option<head::Built>, Error> {
    let spine = &body.spine;
    let n = spine.len();
    if n < 2 {
        return Ok(None);
    }
    let pos = |j: usize| body.joints[j].position;
    let tip = pos(spine[n - 1]);
    let carrier = spine[n - 2];
    let centre_index = root_on_spine(body)?;
    // The body's width at the second neck bone counted from the root, or, where the neck
    // under the head is wider, [`HEAD_OVER_NECK`] × that: a head wider than its neck.
    let width = body_width(body, centre_index + 1).max(HEAD_OVER_NECK * body_width(body, n - 2));
    // And at least [`HEAD_OVER_NECK`] × as wide as the neck's skin as built (the bone's before
    // the head's), whatever the head's size and shape.
    let neck_skin = n
        .checked_sub(3)
        .and_then(|k| mesh.width_across(mesh.positions.len(), spine[k]))
        .unwrap_or(0.0);
    let radius = (0.5 * width * size).max(0.5 * HEAD_OVER_NECK * neck_skin / shape.across());
    // The head held nearer level than the neck: a neck raised by `p` (in the body's YZ plane,
    // past upright on a neck bent back) pitches it by 0.3 `p`, at most 20° down or 25° up.
    let neck = (tip - pos(carrier)).normalize_or(Vec3::Z);
    let raised = asin(neck.y.clamp(-1.0, 1.0));
    let raised = if neck.z < 0.0 {
        core::f32::consts::PI.copysign(raised) - raised
    } else {
        raised
    };
    let pitch = (0.3 * raised).clamp(-0.35, 0.44);
    let mount = head::Mount {
        tip,
        forward: Vec3::new(0.0, sin(pitch), cos(pitch)),
        radius,
        joint: carrier as u16,
    };
    Ok(Some(head::add_head(mesh, mount, shape, colouring)))
}

/// A swimmer's (or slitherer's) face on its body's front (the first `body_vertices` of
/// `mesh`, the pill's: tail tip, rings, head tip), on the ring `behind` × the body's length
/// behind its front (a snake's, less than a tenth: its eyes lower on its sides), each part
/// bound as the body vertex nearest it.
fn add_fish_face(
    mesh: &mut MeshBuilder,
    body: &creature_autorig::Rig,
    params: &Params,
    shape: &Shape,
    colouring: &Colouring,
    behind: f32,
) -> Option<head::Built> {
    let (rings, segments) = (params.rings as usize, params.segments as usize);
    let body_vertices = 2 + rings * segments;
    let spine = &body.spine;
    let n = spine.len();
    if n < 2 || rings < 2 || mesh.positions.len() < body_vertices {
        return None;
    }
    let tip = body.joints[body.head].position;
    let forward = (tip - body.joints[spine[n - 2]].position).normalize_or(Vec3::Z);
    // The body as it is now, for the face to find its place and binds on.
    let positions: Vec<Vec3> = mesh.positions[..body_vertices].to_vec();
    let binds: Vec<Bind> = (0..body_vertices)
        .map(|v| Bind::from_arrays(mesh.joints[v], mesh.weights[v]))
        .collect();
    let front = positions
        .iter()
        .copied()
        .max_by(|a, b| a.dot(forward).total_cmp(&b.dot(forward)))?;
    let length = body.spine_length();
    // The ring about `behind` the body's length behind the front.
    let ring_at = |i: usize| {
        let ring = &positions[1 + i * segments..1 + (i + 1) * segments];
        let centre = ring.iter().copied().sum::<Vec3>() / segments as f32;
        (centre, ring)
    };
    let target = front.dot(forward) - behind * length;
    let i = (0..rings).min_by(|&a, &b| {
        let d = |i: usize| (ring_at(i).0.dot(forward) - target).abs();
        d(a).total_cmp(&d(b))
    })?;
    let (centre, ring) = ring_at(i);
    let frame = head::Frame::new(centre, forward);
    let (half_width, half_height) = ring.iter().fold((0.0f32, 0.0f32), |(w, h), &p| {
        let d = p - centre;
        (w.max(d.dot(frame.side).abs()), h.max(d.dot(frame.up).abs()))
    });
    let front = head::FishFront {
        tip: front,
        forward,
        ring_centre: centre,
        half_width,
        half_height,
        // A snake's eyes lower on the sides of its head than a fish's.
        eyes_at: if behind < 0.1 {
            (0.92, 0.4)
        } else {
            (0.8, 0.6)
        },
    };
    let nearest = |p: Vec3| {
        let v = positions
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.distance_squared(p).total_cmp(&b.1.distance_squared(p)))
            .map_or(0, |(v, _)| v);
        binds[v]
    };
    Some(head::add_fish_face(mesh, front, shape, colouring, nearest))
}

/// How far (× the spine's length) a walker's socket's side vertices must be on their own sides
/// of the midline for the planner to see it (see [`limb_body`]).
const SIDED_SOCKET_MARGIN: f32 = 0.005;

/// The planner's view of the body: one bone per distinct socket, `along` the arc length along
/// the spine where the socket is (its side vertices' middle), heights above `ground`; and, for
/// each of the planner's bones, the rig's socket it stands for.
///
/// A coarse body (few rings under many bones) gives several bones the same side vertices as
/// their socket, a ring away from the bone's middle: limbs planned on two of them, apart along
/// the spine as the planner would see them by their bones, would grow from one point, or closer
/// than their sweeps allow, and pass through each other. Of the bones sharing a side vertex (or
/// not further along the spine) the planner sees only one, the one whose middle is nearest to
/// its socket. For a walker (`sided`), it sees only sockets whose side vertices are on their
/// own sides of the midline by [`SIDED_SOCKET_MARGIN`] (all of them if none is).
fn limb_body(
    body: &creature_autorig::Rig,
    positions: &[Vec3],
    ground: f32,
    sided: bool,
) -> (Vec<SpineBone>, Vec<usize>) {
    let spine_bones = body.spine_bones();
    let mut arc = Vec::with_capacity(spine_bones.len());
    let mut total = 0.0f32;
    for b in &spine_bones {
        let len = b[0].distance(b[1]);
        arc.push(total + 0.5 * len);
        total += len;
    }
    // Arc length along the spine of the point on it nearest to `p`.
    let arc_of = |p: Vec3| {
        let mut best = (f32::INFINITY, 0.0f32);
        let mut start = 0.0f32;
        for b in &spine_bones {
            let d = b[1] - b[0];
            let len = d.length();
            let t = if len > 0.0 {
                ((p - b[0]).dot(d) / (len * len)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let distance = p.distance_squared(b[0] + t * d);
            if distance < best.0 {
                best = (distance, start + t * len);
            }
            start += len;
        }
        best.1
    };
    let mut bones: Vec<SpineBone> = Vec::with_capacity(body.sockets.len());
    let mut kept: Vec<usize> = Vec::with_capacity(body.sockets.len());
    // A walker's limbs stand on the body's sides: a socket whose "left" vertex is not left of
    // the midline (a pointed end, a narrow bent neck) would plant a foot on or across it.
    let margin = SIDED_SOCKET_MARGIN * body.spine_length();
    let beside = |s: &creature_autorig::Socket| {
        positions[s.left_vertex as usize].x > margin
            && positions[s.right_vertex as usize].x < -margin
    };
    let sided = sided && body.sockets.iter().any(beside);
    for (index, s) in body.sockets.iter().enumerate() {
        if sided && !beside(s) {
            continue;
        }
        let left = positions[s.left_vertex as usize];
        let right = positions[s.right_vertex as usize];
        let top = positions[s.top_vertex as usize];
        let along = arc_of(0.5 * (left + right));
        let clearance = (left.y.min(right.y) - ground).max(0.0);
        let bone = SpineBone::from_sockets(along, left, right, top, clearance);
        let n = bones.len();
        let conflict = n > 0 && {
            let other = &body.sockets[kept[n - 1]];
            other.left_vertex == s.left_vertex
                || other.right_vertex == s.right_vertex
                || bones[n - 1].along >= along
        };
        if !conflict {
            bones.push(bone);
            kept.push(index);
            continue;
        }
        // One place on the body: the bone whose middle is nearer to it stands for it, as long
        // as the bones stay in order along the spine.
        let in_order = n < 2 || bones[n - 2].along < along;
        let nearer = (arc[s.bone] - along).abs()
            < (arc[body.sockets[kept[n - 1]].bone] - bones[n - 1].along).abs();
        if in_order && nearer {
            bones[n - 1] = bone;
            kept[n - 1] = index;
        }
    }
    (bones, kept)
}

/// Normals (flat: every triangle its own vertices; with `face_colours`, in one colour:
/// `face_colours[i]` for the first triangles, its first corner's for the rest), into the
/// public mesh.
fn finish_mesh(b: MeshBuilder, flat: bool, face_colours: Option<&[Vec3]>) -> Mesh {
    let face_normal = |t: &[u32; 3]| {
        let [a, c, d] = t.map(|i| b.positions[i as usize]);
        (c - a).cross(d - a)
    };
    if flat {
        // Three vertices per triangle, each list allocated once.
        let (triangles, vertices) = (b.indices.len(), 3 * b.indices.len());
        let mut m = Mesh {
            positions: Vec::with_capacity(vertices),
            normals: Vec::with_capacity(vertices),
            colours: Vec::with_capacity(vertices),
            indices: Vec::with_capacity(triangles),
            joints: Vec::with_capacity(vertices),
            weights: Vec::with_capacity(vertices),
        };
        for (k, t) in b.indices.iter().enumerate() {
            let n = face_normal(t).normalize_or(Vec3::Y);
            let base = m.positions.len() as u32;
            let colour =
                face_colours.map(|faces| faces.get(k).copied().unwrap_or(b.colours[t[0] as usize]));
            for &i in t {
                let i = i as usize;
                m.positions.push(b.positions[i]);
                m.colours.push(colour.unwrap_or(b.colours[i]));
                m.joints.push(b.joints[i]);
                m.weights.push(b.weights[i]);
                m.normals.push(n);
            }
            m.indices.push([base, base + 1, base + 2]);
        }
        m
    } else {
        let mut normals = alloc::vec![Vec3::ZERO; b.positions.len()];
        for t in &b.indices {
            let n = face_normal(t);
            for &i in t {
                normals[i as usize] += n;
            }
        }
        Mesh {
            normals: normals.iter().map(|n| n.normalize_or(Vec3::Y)).collect(),
            positions: b.positions,
            colours: b.colours,
            indices: b.indices,
            joints: b.joints,
            weights: b.weights,
        }
    }
}

fn measure(
    mesh: &Mesh,
    limb_plan: &creature_limbs::Plan,
    ffd_min_determinant: f32,
    length: f32,
    bend_degrees: [f32; 2],
) -> Quality {
    let max_weight_sum_error = mesh
        .weights
        .iter()
        .map(|w| (w.iter().sum::<f32>() - 1.0).abs())
        .fold(0.0f32, f32::max);
    let min_height = mesh
        .positions
        .iter()
        .map(|p| p.y)
        .fold(f32::INFINITY, f32::min);
    let scale = (length * length).max(f32::MIN_POSITIVE);
    let min_triangle_area = mesh
        .indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            0.5 * (b - a).cross(c - a).length() / scale
        })
        .fold(f32::INFINITY, f32::min);
    // Walkers: the mesh's centre of volume against the hull of what touches the ground.
    let stands = limb_plan.kind == CreatureKind::Walker;
    let stability_margin = stands
        .then(|| standing(&mesh.positions, &mesh.indices, length))
        .flatten()
        .and_then(|(_, margin)| margin);
    Quality {
        stability_margin,
        ffd_min_determinant,
        max_weight_sum_error,
        min_height,
        min_triangle_area,
        bend_degrees,
        belly_contrast: 0.0,
        eyes_in_view: 0,
        thigh_to_shin_radius: None,
        wing_span_to_body_length: None,
        wing_area_to_body_volume: None,
        back_ornaments: 0,
        back_kind: None,
        wing_kind: None,
        neck_to_head_and_body: None,
    }
}

/// The limbs' proportions as delivered (see [`Quality`]): the least thigh-over-shin radius of
/// the legs, and the wings' (flapping or buzzing) span over the body length and area over the body's
/// volume to the power 2/3; measured on `mesh` by each vertex's most weighted joint.
/// The neck's width over the narrower of the head's and the body's, across the body (`x`) as
/// the front view shows them (see [`Quality::neck_to_head_and_body`]), of `mesh` (the body's
/// skin its first `body_vertices` vertices, the head's parts after them) on the rig's `spine`
/// (tail to head: the head's joint the last but one) under `head`; `None` without a joint
/// between the body's widest and the head, or without head parts.
fn measure_neck(
    mesh: &MeshBuilder,
    body_vertices: usize,
    spine: &[usize],
    head: &head::Built,
) -> Option<f32> {
    let n = spine.len();
    if n < 3 {
        return None;
    }
    let carrier = spine[n - 2];
    // The body's width at each joint short of the head: the skin bound to it most, from its
    // leftmost vertex to its rightmost.
    let widths: Vec<Option<f32>> = spine[..n - 2]
        .iter()
        .map(|&j| mesh.width_across(body_vertices, j))
        .collect();
    // The widest joint short of the head, then the narrowest from it to the head: the
    // joints' skin, and the head's carrier's where it shows outside the skull.
    let (widest, body) = widths
        .iter()
        .enumerate()
        .filter_map(|(k, w)| Some((k, (*w)?)))
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    let body_end = body_vertices.min(mesh.positions.len());
    let shown = mesh.x_extent(
        (0..body_end).filter(|&v| mesh.dominant(v) == carrier && !head.in_skull(mesh.positions[v])),
    );
    let neck = widths[widest..]
        .iter()
        .flatten()
        .copied()
        .chain(shown)
        .min_by(f32::total_cmp)?;
    // The head's: its parts' (skull, face and ornaments) from the leftmost to the rightmost.
    let head = mesh
        .x_extent((body_vertices..mesh.positions.len()).filter(|&v| mesh.dominant(v) == carrier))?;
    Some(neck / body.min(head).max(f32::MIN_POSITIVE))
}

fn measure_limbs(
    mesh: &Mesh,
    joints: &[Joint],
    limb_plan: &creature_limbs::Plan,
    length: f32,
) -> [Option<f32>; 3] {
    let dominant: Vec<usize> = mesh
        .joints
        .iter()
        .zip(&mesh.weights)
        .map(|(j, w)| {
            let k = (0..4).fold(0, |k, i| if w[i] > w[k] { i } else { k });
            usize::from(j[k])
        })
        .collect();
    // The farthest a vertex bound to `joint` is from the segment `a`–`b`.
    let radius = |joint: usize, a: Vec3, b: Vec3| {
        mesh.positions
            .iter()
            .zip(&dominant)
            .filter(|&(_, &d)| d == joint)
            .map(|(&p, _)| segment_distance(p, a, b))
            .fold(0.0f32, f32::max)
    };
    let mut thigh_to_shin: Option<f32> = None;
    let mut wing_joints = Vec::new();
    for (index, limb) in limb_plan.limbs.iter().enumerate() {
        let chain: Vec<usize> = (0..joints.len())
            .filter(|&j| joints[j].part == Part::Limb(index))
            .collect();
        match (limb.kind, chain.as_slice()) {
            (LimbKind::Leg, &[hip, knee, foot]) => {
                let at = |j: usize| joints[j].position;
                let thigh = radius(hip, at(hip), at(knee));
                let shin = radius(knee, at(knee), at(foot)).max(f32::MIN_POSITIVE);
                let ratio = thigh / shin;
                thigh_to_shin = Some(thigh_to_shin.map_or(ratio, |r| r.min(ratio)));
            }
            (LimbKind::FlappingWing | LimbKind::BuzzingWing, _) => wing_joints.extend(chain),
            _ => {}
        }
    }
    if wing_joints.is_empty() {
        return [thigh_to_shin, None, None];
    }
    let in_wing = |v: u32| {
        dominant
            .get(v as usize)
            .is_some_and(|d| wing_joints.contains(d))
    };
    let (lo, hi) = (0..mesh.positions.len() as u32)
        .filter(|&v| in_wing(v))
        .map(|v| mesh.positions[v as usize].x)
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
    let span = (hi - lo) / length.max(f32::MIN_POSITIVE);
    let faces: f32 = mesh
        .indices
        .iter()
        .filter(|t| t.iter().all(|&v| in_wing(v)))
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            0.5 * (b - a).cross(c - a).length()
        })
        .sum();
    let on_spine = |v: u32| {
        dominant
            .get(v as usize)
            .and_then(|&j| joints.get(j))
            .is_some_and(|j| j.part == Part::Spine)
    };
    let body: Vec<[u32; 3]> = mesh
        .indices
        .iter()
        .filter(|t| t.iter().all(|&v| on_spine(v)))
        .copied()
        .collect();
    let volume = volume_and_centre(&mesh.positions, &body).0.max(0.0);
    let area = 0.5 * faces / powf(volume, 2.0 / 3.0).max(f32::MIN_POSITIVE);
    [thigh_to_shin, Some(span), Some(area)]
}

/// The distance from `p` to the segment `a`–`b`.
fn segment_distance(p: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared().max(f32::MIN_POSITIVE)).clamp(0.0, 1.0);
    p.distance(a + ab * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A new kind is one entry: here a swimmer's body, fins and tail with a walker's neck and
    /// head (rooted at the centre, neck and tail bent), made by nothing but this table entry.
    const HEADED_SWIMMER: KindSpec = KindSpec {
        limbs: CreatureKind::Swimmer,
        root: RootAt::Centre,
        slices: swimmer_slices,
        neck_and_head: true,
        walks: false,
        crawls: false,
    };

    #[test]
    fn a_new_kind_is_one_table_entry() {
        let mut bent = false;
        for seed in 0..6 {
            let headed = generate_kind(&mut rng_for(seed), &Params::DEFAULT, &HEADED_SWIMMER)
                .expect("a valid kind entry generates");
            assert_eq!(headed.kind, CreatureKind::Swimmer);
            assert!(headed.gait.is_none());
            assert!(headed.quality.min_height >= 0.0);
            assert!(headed.mesh.positions.iter().all(|p| p.is_finite()));
            assert!(headed.clips.iter().any(|c| c.name == "swim"));
            // Rooted at the centre, where the plain swimmer roots at its head.
            let head_tip = |c: &Creature| c.rig.spine.last().copied();
            let plain = generate_kind(&mut rng_for(seed), &Params::DEFAULT, &KINDS[2])
                .expect("swimmers generate");
            assert_eq!(plain.rig.root(), head_tip(&plain));
            assert_ne!(headed.rig.root(), head_tip(&headed));
            bent |= headed.quality.bend_degrees[0] > 0.0;
        }
        assert!(bent, "the entry's neck_and_head bends the neck");
    }

    #[test]
    fn colours_follow_the_palette_on_body_and_limbs() {
        use crate::Span;
        use crate::d3::{Pattern, PatternWeights};
        let params = Params::DEFAULT
            .with_kind(Kind::Walker)
            .with_clips(false)
            .with_flat_normals(false);
        // The body's vertices come first: tail tip, 16 rings of 10, head tip.
        let body = 2 + 16 * 10;
        let flank =
            |c: &Creature| -> Vec<Vec3> { (0..16).map(|i| c.mesh.colours[1 + 10 * i]).collect() };
        let luminance = |c: Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722));
        for seed in 0..8 {
            let c = generate(seed, &params).expect("walkers generate");
            assert!(
                c.quality.belly_contrast >= 0.1,
                "seed {seed}: {:?}",
                c.quality
            );

            // Plain and no countershading: the base colour all over the body.
            let plain = generate(
                seed,
                &params
                    .with_patterns(PatternWeights::only(Pattern::Plain))
                    .with_countershading(Span::new(0.0, 0.0)),
            )
            .expect("walkers generate");
            assert!(plain.quality.belly_contrast.abs() < 1e-6);
            for colour in &plain.mesh.colours[..body] {
                assert!(
                    (*colour - plain.palette.base).length() < 1e-6,
                    "seed {seed}"
                );
            }

            // Stripes: the flank changes colour along the body.
            let striped = generate(
                seed,
                &params.with_patterns(PatternWeights::only(Pattern::Stripes)),
            )
            .expect("walkers generate");
            assert_eq!(striped.palette.pattern, Pattern::Stripes);
            let l: Vec<f32> = flank(&striped).into_iter().map(luminance).collect();
            let (lo, hi) = l
                .iter()
                .fold((f32::MAX, f32::MIN), |(a, b), &x| (a.min(x), b.max(x)));
            assert!(hi - lo > 0.05, "seed {seed}: flank {l:?}");

            // Each limb starts in the colour of the body where it joins it: its vertex nearest
            // the body's nearest vertex is within a hair of that colour.
            for limb in 0..c.plan.limbs.len() {
                let joints: Vec<u16> = c
                    .skeleton
                    .joints
                    .iter()
                    .enumerate()
                    .filter(|(_, j)| j.part == Part::Limb(limb))
                    .map(|(i, _)| i as u16)
                    .collect();
                let limb_vertices: Vec<usize> = (body..c.mesh.positions.len())
                    .filter(|&v| joints.contains(&c.mesh.joints[v][0]))
                    .collect();
                let (mut best, mut pair) = (f32::INFINITY, (0, 0));
                for &v in &limb_vertices {
                    for b in 0..body {
                        let d = c.mesh.positions[v].distance(c.mesh.positions[b]);
                        if d < best {
                            (best, pair) = (d, (v, b));
                        }
                    }
                }
                let seam = (c.mesh.colours[pair.0] - c.mesh.colours[pair.1]).length();
                assert!(seam < 0.15, "seed {seed} limb {limb}: seam {seam}");
            }
        }
    }

    #[test]
    fn random_draws_every_kind_of_the_table_but_the_slitherer() {
        let mut seen = [false; KINDS.len()];
        for seed in 0..64 {
            let spec = KindSpec::of(Kind::Random, &mut rng_for(seed));
            let i = KINDS
                .iter()
                .position(|k| k.limbs == spec.limbs)
                .expect("drawn from the table");
            seen[i] = true;
        }
        let mut expected = [true; KINDS.len()];
        expected[RANDOM_KINDS..].fill(false);
        assert_eq!(seen, expected);
        assert_eq!(KINDS[RANDOM_KINDS].limbs, CreatureKind::Slitherer);
    }
}
