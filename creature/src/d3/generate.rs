//! `generate`: the 3D seed's pipeline — blended pill body, FFD, body scale, auto-rig, skinning,
//! spine bend, head, limbs, ground clearance.

use alloc::vec::Vec;

use glam::{Affine3A, Quat, Vec3};
use rand_core::Rng;

use creature_autorig::{RigOptions, RootAt, rig};
use creature_ffd::{Axis, Lattice};
use creature_gait::{GaitOptions, Leg, LimbKind as GaitLimb};
use creature_limbs::{Body, CreatureKind, HeadEnd, SpineBone, plan};
use creature_skin::{Blend, nearest_k, skin_positions};

use super::body::{BASE_RADIUS, base_body, pill_triangles};
use super::limbs::{Bind, LimbStyle, MeshBuilder, Mount, add_limb, socket_point};
use super::{GaitSetup, Kind, Params};
use crate::Error;
use crate::d3::{Creature, Joint, Mesh, Part, Quality, Skeleton};
use crate::math::{cos, sin};
use crate::rng::{rng_for, uniform};

/// FFD lattice divisions: 3×3 control points per slice, 11 slices along the body (the seed's).
const DIVISIONS: [usize; 3] = [2, 2, 10];
/// Head sphere resolution (rings, segments).
const HEAD_RES: (usize, usize) = (5, 8);

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
/// fold; the sub-crates' errors (rig, skin, limbs) wrapped — with valid params these do not
/// happen for any seed the sweep has tried.
pub fn generate(seed: u64, params: &Params) -> Result<Creature, Error> {
    params.validate()?;
    let mut rng = rng_for(seed);
    let rng = &mut rng;
    let kind = match params.kind {
        Kind::Walker => CreatureKind::Walker,
        Kind::Flier => CreatureKind::Flier,
        Kind::Swimmer => CreatureKind::Swimmer,
        Kind::Random => match (uniform(rng) * 3.0) as u32 {
            0 => CreatureKind::Walker,
            1 => CreatureKind::Flier,
            _ => CreatureKind::Swimmer,
        },
    };
    let swimmer = kind == CreatureKind::Swimmer;

    // 1. Base body: blended profiles on one pill topology.
    let (rings, segments) = (params.rings as usize, params.segments as usize);
    let (mut positions, profiles) = base_body(rng, params.profiles as usize, rings, segments);
    let triangles = pill_triangles(rings, segments);

    // 2. FFD: slices scaled at random across, placed at monotonic steps along the body.
    let (width, height, step) = if swimmer {
        (
            params.swimmer_slice_width,
            params.swimmer_slice_height,
            params.swimmer_slice_step,
        )
    } else {
        (params.slice_width, params.slice_height, params.slice_step)
    };
    let mut lattice = Lattice::around(&positions, DIVISIONS, 0.05 * BASE_RADIUS)?;
    let slices = lattice.slice_count(Axis::U);
    for k in 0..slices {
        let s = Vec3::new(width.at(uniform(rng)), height.at(uniform(rng)), 1.0);
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

    // 3. Body scale and speed.
    let body_scale = params.body_scale.at(uniform(rng));
    let speed_factor = params.speed_factor.at(uniform(rng));
    let speed = body_scale * speed_factor;
    for p in &mut positions {
        *p *= body_scale;
    }

    // 4. Rig and skin.
    let root = if swimmer {
        RootAt::Head
    } else {
        RootAt::Centre
    };
    let options = RigOptions::DEFAULT
        .with_root(root)
        .with_bone_length(params.bone_length * body_scale)
        .with_bone_count(
            params.spine_bones.min as usize,
            params.spine_bones.max as usize,
        );
    let mut body_rig = rig(&positions, &triangles, &options)?;

    // 5. Spine bend (walkers and fliers): neck up, tail up or down, per bone within budget.
    let mut bend_degrees = [0.0f32; 2];
    if !swimmer {
        bend_degrees = bend_spine(rng, params, &mut body_rig, &mut positions)?;
    }
    let segments_now = body_rig.bone_segments();
    let influences = nearest_k(&positions, &segments_now, 4)?;
    let length = body_rig.spine_length();

    // 6. Head sphere on the neck tip (walkers and fliers), scaled by the second neck bone's
    //    width.
    let body_colour = Vec3::new(
        0.25 + 0.6 * uniform(rng),
        0.25 + 0.6 * uniform(rng),
        0.25 + 0.6 * uniform(rng),
    );
    let mut mesh = MeshBuilder::default();
    for (p, inf) in positions.iter().zip(&influences) {
        mesh.vertex(*p, body_colour, Bind::from_arrays(inf.joints, inf.weights));
    }
    mesh.indices.extend_from_slice(&triangles);
    let head_size = params.head_size.at(uniform(rng));
    if !swimmer {
        add_head(&mut mesh, &body_rig, head_size, body_colour);
    }

    // 7. Ground under the body (and head), the seed's random capsule height below it.
    let body_min_y = mesh
        .positions
        .iter()
        .map(|p| p.y)
        .fold(f32::INFINITY, f32::min);
    let ground = body_min_y - params.ground_clearance.at(uniform(rng)) * length;

    // 8. Limbs planned on the sockets.
    let bones = limb_body(&body_rig, &positions, ground);
    let limb_body = Body::new(bones, length, HeadEnd::Last);
    let limb_plan = plan(&limb_body, kind, &params.limbs, rng)?;

    let mut joints: Vec<Joint> = body_rig
        .joints
        .iter()
        .map(|j| Joint {
            position: j.position,
            parent: j.parent,
            part: Part::Spine,
        })
        .collect();
    let tail_tip = body_rig
        .joints
        .get(body_rig.tail)
        .map_or(Vec3::ZERO, |j| j.position);
    let tail_joint = body_rig
        .joints
        .get(body_rig.tail)
        .and_then(|j| j.parent)
        .unwrap_or(0);
    let limb_colour = body_colour * 0.8;
    let membrane_colour = body_colour * 0.5 + Vec3::splat(0.45);
    let mut chains = Vec::new();
    for (index, limb) in limb_plan.limbs.iter().enumerate() {
        let Some(socket) = body_rig.sockets.get(limb.bone) else {
            continue;
        };
        let get = |v: u32| positions.get(v as usize).copied().unwrap_or(Vec3::ZERO);
        let point = socket_point(
            limb.socket,
            get(socket.left_vertex),
            get(socket.right_vertex),
            get(socket.top_vertex),
            tail_tip,
        );
        let joint = if limb.socket == creature_limbs::Socket::Tip {
            tail_joint
        } else {
            socket.joint
        };
        let colour = match limb.kind {
            creature_limbs::LimbKind::Leg | creature_limbs::LimbKind::Arm => limb_colour,
            _ => membrane_colour,
        };
        let chain = add_limb(
            &mut mesh,
            &mut joints,
            index,
            limb,
            Mount {
                point,
                joint,
                width: body_width(&body_rig, socket.bone),
                centre: body_rig.joints.get(joint).map_or(point, |j| j.position),
            },
            LimbStyle {
                knee: limb_plan.knee,
                sides: params.limb_sides as usize,
                colour,
            },
        );
        if let Some(chain) = chain {
            chains.push((index, limb.kind, chain));
        }
    }

    // 9. Ground clearance: the ground to y = 0 (the plan's lift applied), and nothing under it.
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
    for j in &mut joints {
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

    let gait = (kind == CreatureKind::Walker).then(|| {
        let mut legs = Vec::with_capacity(chains.len());
        let mut limbs = Vec::with_capacity(chains.len());
        let mut hip_joints = Vec::with_capacity(chains.len());
        for (index, limb_kind, c) in &chains {
            let gait_kind = if *limb_kind == creature_limbs::LimbKind::Arm {
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
        GaitSetup {
            legs,
            limbs,
            hip_joints,
            options: GaitOptions::DEFAULT.with_speed_multiplier(speed_factor),
        }
    });
    if let Some(setup) = &gait {
        // Validate now, so a creature never carries a set-up the controller rejects.
        setup.controller()?;
    }
    if joints.len() > usize::from(u16::MAX) {
        return Err(Error::TooManyBones {
            bones: joints.len(),
            max: usize::from(u16::MAX),
        });
    }
    let mesh = finish_mesh(mesh, params.flat_normals);
    let quality = measure(
        &mesh,
        &limb_plan,
        fold.min_determinant,
        length,
        bend_degrees,
    );
    let mut creature = Creature {
        kind,
        mesh,
        skeleton: Skeleton { joints },
        rig: body_rig,
        plan: limb_plan,
        ground_offset: offset,
        profiles,
        body_scale,
        speed,
        gait,
        clips: Vec::new(),
        length,
        quality,
    };
    if params.clips {
        creature.clips = creature.bake_clips()?;
    }
    Ok(creature)
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
    let Some(root) = body.root() else {
        return Ok([0.0; 2]);
    };
    let Some(c) = spine.iter().position(|&j| j == root) else {
        return Ok([0.0; 2]);
    };
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
        let pivot = rest.get(j).copied().unwrap_or(Vec3::ZERO);
        previous *= rotate_about(pivot, -neck_angle);
        if let Some(t) = transforms.get_mut(j) {
            *t = previous;
        }
    }
    previous = Affine3A::IDENTITY;
    for &j in spine.iter().take(c).skip(1).rev() {
        let pivot = rest.get(j).copied().unwrap_or(Vec3::ZERO);
        previous *= rotate_about(pivot, tail_sign * tail_angle);
        if let Some(t) = transforms.get_mut(j) {
            *t = previous;
        }
    }
    // Vertices by linear blend skinning on the straight rig's weights.
    let influences = nearest_k(positions, &body.bone_segments(), 4)?;
    let bone_joints: Vec<usize> = body.bones().into_iter().map(|(j, _)| j).collect();
    let per_segment: Vec<Affine3A> = bone_joints
        .iter()
        .map(|&j| transforms.get(j).copied().unwrap_or(Affine3A::IDENTITY))
        .collect();
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
            let t = transforms.get(p).copied().unwrap_or(Affine3A::IDENTITY);
            if let Some(&r) = rest.get(i) {
                joint.position = t.transform_point3(r);
            }
        }
    }
    for s in &mut body.sockets {
        let get = |v: u32| positions.get(v as usize).copied();
        if let (Some(l), Some(r), Some(t)) =
            (get(s.left_vertex), get(s.right_vertex), get(s.top_vertex))
        {
            s.left = l;
            s.right = r;
            s.top = t;
            s.width = l.distance(r);
        }
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

/// A low-poly sphere on the neck tip, bound to the last neck bone's joint.
fn add_head(mesh: &mut MeshBuilder, body: &creature_autorig::Rig, size: f32, colour: Vec3) {
    let spine = &body.spine;
    let n = spine.len();
    if n < 2 {
        return;
    }
    let pos = |j: usize| body.joints.get(j).map_or(Vec3::ZERO, |j| j.position);
    let tip = pos(spine[n - 1]);
    let carrier = spine[n - 2];
    let centre_index = body
        .root()
        .and_then(|r| spine.iter().position(|&j| j == r))
        .unwrap_or(0);
    // The body's width at the second neck bone counted from the root.
    let width = body_width(body, centre_index + 1);
    let radius = 0.5 * width * size;
    let direction = (tip - pos(carrier)).normalize_or(Vec3::Z);
    let centre = tip + direction * (0.5 * radius);
    let (rings, segments) = HEAD_RES;
    let first = mesh.positions.len() as u32;
    let bind = Bind::one(carrier as u16);
    mesh.vertex(centre - Vec3::Z * radius, colour, bind);
    for i in 0..rings {
        let phi = core::f32::consts::PI * (i + 1) as f32 / (rings + 1) as f32;
        let (z, r) = (-cos(phi) * radius, sin(phi) * radius);
        for k in 0..segments {
            let a = core::f32::consts::TAU * k as f32 / segments as f32;
            mesh.vertex(centre + Vec3::new(r * cos(a), r * sin(a), z), colour, bind);
        }
    }
    mesh.vertex(centre + Vec3::Z * radius, colour, bind);
    for t in pill_triangles(rings, segments) {
        mesh.indices.push(t.map(|i| i + first));
    }
}

/// The planner's view of the body: one bone per socket, `along` the arc length at the bone's
/// middle, heights above `ground`.
fn limb_body(body: &creature_autorig::Rig, positions: &[Vec3], ground: f32) -> Vec<SpineBone> {
    let spine_bones = body.spine_bones();
    let mut arc = Vec::with_capacity(spine_bones.len());
    let mut total = 0.0f32;
    for b in &spine_bones {
        let len = b[0].distance(b[1]);
        arc.push(total + 0.5 * len);
        total += len;
    }
    body.sockets
        .iter()
        .map(|s| {
            let get =
                |v: u32, fallback: Vec3| positions.get(v as usize).copied().unwrap_or(fallback);
            let left = get(s.left_vertex, s.left);
            let right = get(s.right_vertex, s.right);
            let top = get(s.top_vertex, s.top);
            let along = arc.get(s.bone).copied().unwrap_or(0.0);
            let clearance = (left.y.min(right.y) - ground).max(0.0);
            SpineBone::from_sockets(along, left, right, top, clearance)
        })
        .collect()
}

/// Normals (flat: every triangle its own vertices), into the public mesh.
fn finish_mesh(b: MeshBuilder, flat: bool) -> Mesh {
    let face_normal = |t: &[u32; 3]| {
        let [a, c, d] = t.map(|i| b.positions.get(i as usize).copied().unwrap_or(Vec3::ZERO));
        (c - a).cross(d - a)
    };
    if flat {
        let mut m = Mesh::default();
        for t in &b.indices {
            let n = face_normal(t).normalize_or(Vec3::Y);
            let base = m.positions.len() as u32;
            for &i in t {
                let i = i as usize;
                m.positions
                    .push(b.positions.get(i).copied().unwrap_or(Vec3::ZERO));
                m.colours
                    .push(b.colours.get(i).copied().unwrap_or(Vec3::ONE));
                m.joints.push(b.joints.get(i).copied().unwrap_or([0; 4]));
                m.weights
                    .push(b.weights.get(i).copied().unwrap_or([1.0, 0.0, 0.0, 0.0]));
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
                if let Some(v) = normals.get_mut(i as usize) {
                    *v += n;
                }
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
            let [a, b, c] = t.map(|i| {
                mesh.positions
                    .get(i as usize)
                    .copied()
                    .unwrap_or(Vec3::ZERO)
            });
            0.5 * (b - a).cross(c - a).length() / scale
        })
        .fold(f32::INFINITY, f32::min);
    Quality {
        stability_margin: limb_plan.stability_margin,
        ffd_min_determinant,
        max_weight_sum_error,
        min_height,
        min_triangle_area,
        bend_degrees,
    }
}
