//! Procedural limb meshes skinned to their own bones: tapered two-segment tubes for legs and
//! arms (two-bone IK with the plan's knee direction), thin membranes on bone chains for wings,
//! fins and tails.

use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;
use core::f32::consts::{PI, TAU};

use glam::Vec3;

use creature_gait::{GaitOptions, solve_two_bone};
use creature_limbs::{Knee, Limb, LimbKind, Side, Socket};

use super::extremities::{ANKLE, Foot, add_foot, add_hand, ankle_height, centre_foot};
use super::wings::{self, Tone, WingFrame, WingKind};
use crate::Error;
use crate::d3::{Joint, Part};
use crate::math::{cos, sin};

/// A growing skinned mesh: positions, colours, triangles, four joints and weights per vertex.
#[derive(Debug, Default)]
pub(crate) struct MeshBuilder {
    pub(crate) positions: Vec<Vec3>,
    pub(crate) colours: Vec<Vec3>,
    pub(crate) indices: Vec<[u32; 3]>,
    pub(crate) joints: Vec<[u16; 4]>,
    pub(crate) weights: Vec<[f32; 4]>,
}

/// The joints a vertex follows and their weights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Bind {
    joints: [u16; 4],
    weights: [f32; 4],
}

impl Bind {
    pub(crate) fn one(joint: u16) -> Self {
        Self {
            joints: [joint, 0, 0, 0],
            weights: [1.0, 0.0, 0.0, 0.0],
        }
    }

    pub(crate) fn from_arrays(joints: [u16; 4], weights: [f32; 4]) -> Self {
        Self { joints, weights }
    }
}

impl MeshBuilder {
    /// Back to its first `vertices` vertices and `triangles` triangles.
    pub(crate) fn truncate(&mut self, vertices: usize, triangles: usize) {
        self.positions.truncate(vertices);
        self.colours.truncate(vertices);
        self.joints.truncate(vertices);
        self.weights.truncate(vertices);
        self.indices.truncate(triangles);
    }

    /// The joint vertex `v` is bound to most (the first of equal weights).
    pub(crate) fn dominant(&self, v: usize) -> usize {
        let (js, ws) = (&self.joints[v], &self.weights[v]);
        let k = (1..4).fold(0, |k, i| if ws[i] > ws[k] { i } else { k });
        usize::from(js[k])
    }

    /// How wide (along `x`, across the body) the first `vertices` vertices bound most to
    /// `joint` reach, from the leftmost to the rightmost; `None` without one.
    pub(crate) fn width_across(&self, vertices: usize, joint: usize) -> Option<f32> {
        self.x_extent(
            (0..vertices.min(self.positions.len())).filter(|&v| self.dominant(v) == joint),
        )
    }

    /// How wide (along `x`) `vertices` reach, from the leftmost to the rightmost; `None`
    /// without one.
    pub(crate) fn x_extent(&self, vertices: impl Iterator<Item = usize>) -> Option<f32> {
        let (lo, hi) = vertices
            .map(|v| self.positions[v].x)
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            });
        (hi >= lo).then_some(hi - lo)
    }

    pub(crate) fn vertex(&mut self, p: Vec3, colour: Vec3, bind: Bind) -> u32 {
        let index = self.positions.len() as u32;
        self.positions.push(p);
        self.colours.push(colour);
        self.joints.push(bind.joints);
        self.weights.push(bind.weights);
        index
    }

    /// A closed tube through `centres` with radii `radii` and one bind per ring, cross-sections
    /// square to `axis` (one frame for the whole tube, so a vertical leg's foot ring is flat on
    /// the ground), capped at both ends.
    pub(crate) fn tube(
        &mut self,
        centres: &[Vec3],
        radii: &[f32],
        binds: &[Bind],
        axis: Vec3,
        sides: usize,
        colour: Vec3,
    ) {
        let axis = axis.try_normalize().unwrap_or(Vec3::NEG_Y);
        let e1 = axis.any_orthonormal_vector();
        let e2 = axis.cross(e1);
        let first = self.positions.len() as u32;
        let rings = centres.len().min(radii.len()).min(binds.len());
        if rings < 2 || sides < 3 {
            return;
        }
        for ((&c, &r), &b) in centres.iter().zip(radii).zip(binds).take(rings) {
            for j in 0..sides {
                let a = TAU * j as f32 / sides as f32;
                self.vertex(c + (e1 * cos(a) + e2 * sin(a)) * r, colour, b);
            }
        }
        let v = |i: usize, j: usize| first + (i * sides + j % sides) as u32;
        for i in 0..rings - 1 {
            for j in 0..sides {
                self.indices.push([v(i, j), v(i, j + 1), v(i + 1, j + 1)]);
                self.indices.push([v(i, j), v(i + 1, j + 1), v(i + 1, j)]);
            }
        }
        let start = self.vertex(centres[0], colour, binds[0]);
        let end = self.vertex(centres[rings - 1], colour, binds[rings - 1]);
        for j in 0..sides {
            self.indices.push([start, v(0, j + 1), v(0, j)]);
            self.indices
                .push([end, v(rings - 1, j), v(rings - 1, j + 1)]);
        }
    }

    /// A thin two-sided membrane from `origin` along `along` (length `length`), `width` wide
    /// across `across`, on a chain of `chain.len()` joints evenly spaced along it.
    pub(crate) fn membrane(&mut self, shape: Membrane, chain: &[u16], colour: Vec3) {
        let Membrane {
            origin,
            along,
            across,
            length,
            width,
            outline,
        } = shape;
        let n = chain.len();
        if n == 0 {
            return;
        }
        let normal = along.cross(across).normalize_or_zero();
        let thickness = 0.02 * length;
        for (side, offset) in [
            (1.0f32, normal * thickness * 0.5),
            (-1.0, -normal * thickness * 0.5),
        ] {
            let first = self.positions.len() as u32;
            // The chord's middle at `t` along (0 the root, 1 the tip).
            let middle = |t: f32| {
                origin + offset + along * (length * t) + across * (width * outline.sweep(t))
            };
            for (k, &joint) in chain.iter().enumerate() {
                let t = k as f32 / n as f32;
                let half = width * outline.half_chord(t);
                let bind = Bind::one(joint);
                self.vertex(middle(t) - across * half, colour, bind);
                self.vertex(middle(t) + across * half, colour, bind);
            }
            let last = Bind::one(chain[n - 1]);
            let tip = if outline == Outline::Forked {
                // A notch a third of the way from the last station to the end, between two
                // lobes at the end as wide as the chord there.
                let t = (n - 1) as f32 / n as f32;
                self.vertex(middle(t + (1.0 - t) / 3.0), colour, last)
            } else {
                self.vertex(middle(1.0), colour, last)
            };
            let v = |k: usize, plus: bool| first + (2 * k + usize::from(plus)) as u32;
            let mut push = |t: [u32; 3]| {
                if side > 0.0 {
                    self.indices.push(t);
                } else {
                    self.indices.push([t[0], t[2], t[1]]);
                }
            };
            for k in 0..n - 1 {
                push([v(k, false), v(k + 1, false), v(k + 1, true)]);
                push([v(k, false), v(k + 1, true), v(k, true)]);
            }
            if outline == Outline::Forked {
                let lobe = width * outline.half_chord(1.0);
                let minus = self.vertex(middle(1.0) - across * lobe, colour, last);
                let plus = self.vertex(middle(1.0) + across * lobe, colour, last);
                let mut push = |t: [u32; 3]| {
                    if side > 0.0 {
                        self.indices.push(t);
                    } else {
                        self.indices.push([t[0], t[2], t[1]]);
                    }
                };
                push([v(n - 1, false), minus, tip]);
                push([v(n - 1, false), tip, v(n - 1, true)]);
                push([tip, plus, v(n - 1, true)]);
            } else {
                push([v(n - 1, false), tip, v(n - 1, true)]);
            }
        }
    }
}

/// A membrane's outline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Outline {
    /// Narrow at the root and the tip, widest midway (wings, pectoral fins, a rounded tail
    /// fin).
    Rounded,
    /// Widest at the root, narrowing to a tip swept back against `across` (a shark's dorsal
    /// fin).
    Swept,
    /// Fanning out from a narrow root to two lobes at the end with a notch between them (a
    /// forked tail fin).
    Forked,
}

impl Outline {
    /// Half the chord at `t` along (0 the root, 1 the tip), × the membrane's width.
    fn half_chord(self, t: f32) -> f32 {
        match self {
            Self::Rounded => 0.5 * (0.4 + 0.6 * sin(PI * t)),
            Self::Swept => 0.5 * (1.0 - 0.75 * t),
            Self::Forked => 0.5 * (0.35 + 0.65 * t),
        }
    }

    /// How far the chord's middle at `t` along lies along `across`, × the width.
    fn sweep(self, t: f32) -> f32 {
        match self {
            Self::Swept => -0.35 * t,
            Self::Rounded | Self::Forked => 0.0,
        }
    }
}

/// A membrane's shape: from `origin` along `along` (unit) for `length`, `width` wide across
/// `across` (unit, square to `along`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Membrane {
    pub(crate) origin: Vec3,
    pub(crate) along: Vec3,
    pub(crate) across: Vec3,
    pub(crate) length: f32,
    pub(crate) width: f32,
    pub(crate) outline: Outline,
}

/// How limbs look: the plan's knee direction, tube sides, colour, the creature's feet and
/// thigh thickness, its flapping wings' least size, and whether normals are flat (the foot is
/// centred on its joint as the delivered mesh has its vertices).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LimbStyle {
    pub(crate) knee: Option<Knee>,
    pub(crate) sides: usize,
    pub(crate) colour: Vec3,
    pub(crate) foot: Foot,
    /// Thigh (upper arm) radius × shin (forearm) radius.
    pub(crate) thigh: f32,
    pub(crate) wing: WingSize,
    /// What its flapping wings are made of.
    pub(crate) wing_kind: WingKind,
    /// A tail fin's outline.
    pub(crate) tail_fin: Outline,
    pub(crate) flat: bool,
}

/// The least size of a flier's wings (flapping or buzzing): their span tip to tip (metres) and their area
/// (both wings, one face; square metres).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct WingSize {
    pub(crate) span: f32,
    pub(crate) area: f32,
}

/// A limb as built: a leg's or arm's chain, its vertices to colour as horn (hooves, claws),
/// and a wing's tone per vertex (empty for other limbs).
#[derive(Debug, Clone)]
pub(crate) struct BuiltLimb {
    pub(crate) chain: Option<LegChain>,
    pub(crate) horn: core::ops::Range<usize>,
    pub(crate) tones: Vec<Tone>,
}

/// Where a limb attaches: the socket's point on the bent, grounded body.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mount {
    /// The socket point.
    pub(crate) point: Vec3,
    /// The spine joint that carries it.
    pub(crate) joint: usize,
    /// The body's width there.
    pub(crate) width: f32,
    /// The spine's centre there (the socket joint's position): side limbs point away from it
    /// along X, whatever side the socket was labelled.
    pub(crate) centre: Vec3,
}

/// The outward direction of a side: +X for the creature's left, −X for its right.
fn outward(side: Side) -> f32 {
    match side {
        Side::Left => 1.0,
        Side::Right => -1.0,
        Side::Center => 0.0,
    }
}

/// Outward from the body at a mount: for side sockets, the side the socket really lies on
/// (robust to a rigger that labels sides the other way); otherwise the plan's side.
fn outward_at(limb: &Limb, mount: &Mount) -> f32 {
    let dx = mount.point.x - mount.centre.x;
    let side_socket = matches!(limb.socket, Socket::Left | Socket::Right);
    match limb.side {
        Side::Center => 0.0,
        _ if side_socket && dx.abs() > 1e-6 => dx.signum(),
        side => outward(side),
    }
}

/// A two-bone limb's radius at its root, its thigh's (its tube narrows to the end): 9% of its
/// length, at most a fifth of the body's width where it attaches.
fn limb_radius(length: f32, body_width: f32) -> f32 {
    (0.09 * length).min(0.2 * body_width).max(1e-3)
}

/// A thigh's (upper arm's) radius × [`limb_radius`].
const THIGH: f32 = 1.0;
/// The size of a foot (its parts are sized by this: a paw is 2.2 long, a hoof 1.7 across) ×
/// the thigh's radius. Small enough that legs whose shins keep apart keep their feet apart.
const FOOT: f32 = 0.6;
/// The size of a hand (a mitt is 1.9 long) × the upper arm's radius.
const HAND: f32 = 0.9;

/// Where along the thigh (upper arm), from the hip, its thickest ring is.
const THIGH_BULGE: f32 = 0.2;

/// A flapping wing's chord, × its length, unless its area asks for more.
const WING_CHORD: f32 = 0.45;
/// The widest a flapping wing's chord gets, × its length: past that it grows longer instead.
const MAX_WING_CHORD: f32 = 0.6;

/// A wing's (flapping or buzzing) length and width: as planned (`planned` long), at least long enough for
/// the span `wing.span` tip to tip (its root `root` from the body's midline, reaching across
/// by `reach` per unit of length) and wide enough (then long enough) for `wing.area` over the
/// two wings, its outline covering `share` of `length × width`.
fn flapping_wing(planned: f32, root: f32, reach: f32, wing: WingSize, share: f32) -> (f32, f32) {
    let share = share.max(f32::MIN_POSITIVE);
    let mut length = planned.max((0.5 * wing.span - root) / reach.max(0.5));
    let mut width = WING_CHORD * length;
    let need = 0.5 * wing.area;
    if share * width * length < need {
        width = need / (share * length);
    }
    if width > MAX_WING_CHORD * length {
        length = crate::math::sqrt(need / (share * MAX_WING_CHORD));
        width = MAX_WING_CHORD * length;
    }
    (length, width)
}

/// Per limb of `plan`, the way its knee bends (`mounts` are the limbs' mounts, in order): the
/// plan's, unless on some side two standing legs are so close along the body that the knee
/// one bends toward the other (a rear leg's forward knee, a front leg's backward one) would
/// reach within [`CROWDED_SHARE`] of the gap between their hips, their radii included, or
/// past where the other's foot goes in its stride (the gait's reach behind or ahead of its
/// rest position). Then every side's knees bend apart: the front leg's forward, the rear
/// leg's backward and those between sideways.
pub(crate) fn leg_knees(plan: &creature_limbs::Plan, mounts: &[Mount]) -> Vec<Option<Knee>> {
    let mut knees = alloc::vec![plan.knee; plan.limbs.len()];
    let toward_front = match plan.knee {
        Some(Knee::Sideways) => return knees,
        Some(Knee::Backward) => false,
        _ => true,
    };
    // Standing legs per side.
    let mut sides: [Vec<SideLeg>; 2] = [Vec::new(), Vec::new()];
    for (index, (limb, mount)) in plan.limbs.iter().zip(mounts).enumerate() {
        let (LimbKind::Leg, Some(foot)) = (limb.kind, limb.foot) else {
            continue;
        };
        let out = outward_at(limb, mount);
        if out == 0.0 {
            continue;
        }
        sides[usize::from(out < 0.0)].push(SideLeg {
            index,
            hip: mount.point.z,
            foot: foot.z,
            size: mount.point.distance(foot),
            radius: limb_radius(limb.length.max(1e-4), mount.width),
        });
    }
    // The knee's distance from the hip–foot line, per unit of that line's length.
    let offset = 0.5 * crate::math::sqrt(KNEE_SLACK * KNEE_SLACK - 1.0);
    // How far the gait takes a foot behind and ahead of its rest position (× the leg's size).
    let reach = GaitOptions::DEFAULT.reach;
    let (behind, ahead) = (reach.evaluate(-1.0), reach.evaluate(1.0));
    let mut crowded = false;
    for legs in &mut sides {
        crate::sort::sort_by(legs, &mut |a, b| {
            b.hip.total_cmp(&a.hip).then(a.index.cmp(&b.index))
        });
        for pair in legs.windows(2) {
            let [front, rear] = pair else { continue };
            let bent = if toward_front { rear } else { front };
            let radii = front.radius + rear.radius;
            crowded |= offset * bent.size + radii > CROWDED_SHARE * (front.hip - rear.hip);
            // In its stride, the front foot at the back of its stance passes behind the rear
            // leg's forward knee (or the rear foot at the front of its swing ahead of the
            // front leg's backward knee): the front shin would sweep through the rear thigh.
            crowded |= if toward_front {
                front.foot - behind * front.size < rear.hip + offset * rear.size + radii
            } else {
                rear.foot + ahead * rear.size > front.hip - offset * front.size - radii
            };
        }
    }
    if crowded {
        for legs in sides.iter().filter(|legs| legs.len() > 1) {
            let last = legs.len() - 1;
            for (rank, leg) in legs.iter().enumerate() {
                knees[leg.index] = Some(match rank {
                    0 => Knee::Forward,
                    r if r == last => Knee::Backward,
                    _ => Knee::Sideways,
                });
            }
        }
    }
    knees
}

/// A standing leg on one side of the body, as [`leg_knees`] weighs it: along the body (`z`).
struct SideLeg {
    /// Its index in the plan.
    index: usize,
    /// Its hip's and its rest foot's place along the body.
    hip: f32,
    foot: f32,
    /// Its hip-to-foot distance, and its radius.
    size: f32,
    radius: f32,
}

/// The share of the gap between two neighbouring legs' hips that a knee bent toward the other
/// leg (and the two legs' radii) may take before the knees are bent apart instead.
const CROWDED_SHARE: f32 = 0.75;

/// A leg's two segments together are this many times its hip-to-foot distance, so the knee
/// bends at rest and the gait's strides (up to about 0.7 of that distance behind the rest
/// position, escape steps included) stay within reach.
pub(crate) const KNEE_SLACK: f32 = 1.3;

/// A two-bone leg or arm as built: hip, rest end (foot or hand), segment lengths, knee pole.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LegChain {
    /// The hip joint's index in the skeleton (the knee and foot follow it).
    pub(crate) hip_joint: usize,
    pub(crate) hip: Vec3,
    pub(crate) end: Vec3,
    pub(crate) upper: f32,
    pub(crate) lower: f32,
    pub(crate) pole: Vec3,
}

/// How one limb type is built: a row of [`LIMB_SHAPES`].
#[derive(Clone, Copy)]
pub(crate) struct LimbShape {
    pub(crate) kind: LimbKind,
    /// The first part of its joints' names (`leg` in `leg_l0_knee`).
    name: &'static str,
    /// Drawn in the limb colour (legs, arms) or the lighter membrane colour (wings, fins).
    pub(crate) membrane_colour: bool,
    build: Build,
}

/// The two ways a limb is built.
#[derive(Clone, Copy)]
enum Build {
    /// Hip, knee and foot (or hand) solved by two-bone IK, skinned as a tapered tube; the
    /// gait drives it.
    TwoBone(TwoBone),
    /// A chain of joints carrying a flat membrane (wings, fins, tails).
    Membrane(MembraneShape),
}

/// A two-bone limb's rest pose.
#[derive(Clone, Copy)]
struct TwoBone {
    /// The last part of the three joints' names (`hip`, `knee`, `foot`).
    segments: [&'static str; 3],
    /// Whether the end goes to the plan's foot point when the plan has one (legs that stand).
    to_foot: bool,
    /// The unit direction from the hip to the rest end otherwise, from the outward sign.
    rest_direction: fn(f32) -> Vec3,
    /// The knee's pole, from the plan's knee direction and the outward sign.
    pole: fn(Option<Knee>, f32) -> Vec3,
    /// Whether the thigh bulges (its thickest ring [`THIGH_BULGE`] down it; else at the hip):
    /// not on arms, whose elbows bend far enough to squash a short upper arm's skin.
    bulge: bool,
}

/// A membrane limb's shape.
#[derive(Clone, Copy)]
struct MembraneShape {
    /// The unit direction of the chain, from the outward sign.
    along: fn(f32) -> Vec3,
    /// The membrane's second direction, made square to `along` (`across_fallback` when the two
    /// are parallel).
    across: Vec3,
    across_fallback: Vec3,
    /// Its width, from the limb and its length.
    width: fn(&Limb, f32) -> f32,
    /// Joints along the chain.
    bones: usize,
}

/// A leg's knee: backward or sideways as the plan says, else forward.
fn leg_pole(knee: Option<Knee>, out: f32) -> Vec3 {
    match knee {
        Some(Knee::Backward) => Vec3::NEG_Z,
        Some(Knee::Sideways) if out != 0.0 => Vec3::X * out,
        _ => Vec3::Z,
    }
}

/// One row per limb type: a new type is one more row (and its place in the planner).
pub(crate) const LIMB_SHAPES: [LimbShape; 7] = [
    LimbShape {
        kind: LimbKind::Leg,
        name: "leg",
        membrane_colour: false,
        build: Build::TwoBone(TwoBone {
            segments: ["hip", "knee", "foot"],
            to_foot: true,
            // A flier's dangling leg: down and a little back.
            rest_direction: |out| Vec3::new(0.15 * out, -1.0, -0.35).normalize(),
            pole: leg_pole,
            bulge: true,
        }),
    },
    LimbShape {
        kind: LimbKind::Arm,
        name: "arm",
        membrane_colour: false,
        build: Build::TwoBone(TwoBone {
            segments: ["shoulder", "elbow", "hand"],
            to_foot: false,
            rest_direction: |out| Vec3::new(0.2 * out, -0.5, 1.0).normalize(),
            pole: |_, _| Vec3::new(0.0, -1.0, -0.3),
            bulge: false,
        }),
    },
    LimbShape {
        kind: LimbKind::BuzzingWing,
        name: "wing",
        membrane_colour: true,
        build: Build::Membrane(MembraneShape {
            along: |out| Vec3::new(out, 0.35, -0.25).normalize_or(Vec3::X),
            across: Vec3::Z,
            across_fallback: Vec3::Z,
            width: |limb, length| 0.5 * limb.scale.z.max(0.2 * length),
            bones: 2,
        }),
    },
    LimbShape {
        kind: LimbKind::FlappingWing,
        name: "wing",
        membrane_colour: true,
        build: Build::Membrane(MembraneShape {
            along: |out| Vec3::new(out, 0.05, 0.0).normalize_or(Vec3::X),
            across: Vec3::Z,
            across_fallback: Vec3::Z,
            width: |_, length| 0.45 * length,
            bones: 4,
        }),
    },
    LimbShape {
        kind: LimbKind::DorsalFin,
        name: "fin_dorsal",
        membrane_colour: true,
        build: Build::Membrane(MembraneShape {
            along: |_| Vec3::new(0.0, 1.0, -0.5).normalize(),
            across: Vec3::Z,
            across_fallback: Vec3::Y,
            width: |limb, length| 0.8 * limb.scale.z.max(0.3 * length),
            bones: 3,
        }),
    },
    LimbShape {
        kind: LimbKind::PectoralFin,
        name: "fin_pectoral",
        membrane_colour: true,
        build: Build::Membrane(MembraneShape {
            along: |out| Vec3::new(out, -0.3, -0.3).normalize_or(Vec3::NEG_Y),
            across: Vec3::Z,
            across_fallback: Vec3::Y,
            width: |limb, length| 0.6 * limb.scale.z.max(0.3 * length),
            bones: 3,
        }),
    },
    LimbShape {
        kind: LimbKind::Tail,
        name: "fin_tail",
        membrane_colour: true,
        build: Build::Membrane(MembraneShape {
            along: |_| Vec3::NEG_Z,
            across: Vec3::Y,
            across_fallback: Vec3::Y,
            width: |limb, length| 0.9 * limb.scale.y.max(0.3 * length),
            bones: 4,
        }),
    },
];

/// The row of `kind` in [`LIMB_SHAPES`].
///
/// # Errors
/// [`Error::Unsupported`] for a limb type the table has no row for.
pub(crate) fn limb_shape(kind: LimbKind) -> Result<&'static LimbShape, Error> {
    LIMB_SHAPES
        .iter()
        .find(|s| s.kind == kind)
        .ok_or(Error::Unsupported { what: "limb type" })
}

/// Numbers limbs of one type on one side in the order they are built, for joint names.
#[derive(Debug, Default)]
pub(crate) struct LimbNames {
    seen: Vec<(&'static str, char)>,
}

impl LimbNames {
    /// The next limb's name prefix, e.g. `leg_l0`.
    fn next(&mut self, name: &'static str, side: char) -> String {
        let n = self.seen.iter().filter(|&&s| s == (name, side)).count();
        self.seen.push((name, side));
        format!("{name}_{side}{n}")
    }
}

/// Adds one limb's joints (parent: the mount's joint) and its mesh; joints are appended to
/// `joints`, with the limb's index in the plan in their part and names from `names`. Legs and
/// arms return their chain.
#[allow(clippy::too_many_arguments)]
pub(crate) fn add_limb(
    mesh: &mut MeshBuilder,
    joints: &mut Vec<Joint>,
    names: &mut LimbNames,
    limb_index: usize,
    limb: &Limb,
    shape: &LimbShape,
    mount: Mount,
    style: LimbStyle,
) -> BuiltLimb {
    let LimbStyle {
        knee,
        sides,
        colour,
        foot: foot_kind,
        thigh,
        wing,
        wing_kind,
        tail_fin,
        flat,
    } = style;
    let (first_vertex, first_triangle) = (mesh.positions.len(), mesh.indices.len());
    let out = outward_at(limb, &mount);
    let length = limb.length.max(1e-4);
    let base = joints.len();
    let side = match out {
        o if o > 0.0 => 'l',
        o if o < 0.0 => 'r',
        _ => 'c',
    };
    let prefix = names.next(shape.name, side);
    let mut push_joint = |position: Vec3, parent: usize, segment: &str| -> u16 {
        let index = joints.len();
        joints.push(Joint {
            name: format!("{prefix}_{segment}"),
            position,
            parent: Some(parent),
            part: Part::Limb(limb_index),
        });
        index as u16
    };
    match shape.build {
        Build::TwoBone(bone) => {
            let hip = mount.point;
            let end = match (bone.to_foot, limb.foot) {
                (true, Some(foot)) => foot,
                _ => hip + (bone.rest_direction)(out) * length,
            };
            // The knee bends toward the pole, square to the hip–foot line; a leg slanted far
            // (its foot moved under the mass) bends its knee the other way rather than down
            // toward the ground. Only far: square to a leg that is nearly upright, a level pole
            // dips a little, and a sideways knee flipped for that would point across the body
            // into the other leg.
            let pole = (bone.pole)(knee, out);
            let axis = (end - hip).normalize_or(Vec3::NEG_Y);
            let square = pole - axis * pole.dot(axis);
            let pole = if square.y < -0.5 * square.length() {
                -pole
            } else {
                pole
            };
            let reach = hip.distance(end);
            let segment = KNEE_SLACK * 0.5 * reach.max(1e-4);
            let ik = solve_two_bone(hip, end, segment, segment, pole);
            let [hip_name, knee_name, foot_name] = bone.segments;
            let hip_joint = push_joint(hip, mount.joint, hip_name);
            let knee_joint = push_joint(ik.middle, base, knee_name);
            let foot_joint = push_joint(ik.end, base + 1, foot_name);
            // The thigh's radius; the shin's is `thigh` times less, narrowing through the knee
            // to a slender ankle over the foot (or wrist over the hand).
            let thick = THIGH * limb_radius(length, mount.width);
            let shin = thick / thigh.max(1.0);
            // Feet and hands sized by the thigh, so a slender shin still stands on a foot.
            let foot_size = FOOT * thick;
            let standing = bone.to_foot && limb.foot.is_some();
            // Standing legs have level rings (the foot's flat on the ground however the leg
            // slants); others square to the limb.
            let axis = if standing { Vec3::NEG_Y } else { ik.end - hip };
            let is_leg = shape.kind == LimbKind::Leg;
            let lift = if is_leg { ankle_height(foot_kind) } else { 0.0 } * foot_size;
            let up_shin = (ik.middle - ik.end).normalize_or(Vec3::Y);
            let ankle = ik.end + up_shin * lift.min(0.3 * ik.middle.distance(ik.end));
            // Arms start at their thickest ring (the shoulder's); legs one thigh-bulge down.
            let first = usize::from(!bone.bulge);
            let bulge = if bone.bulge {
                hip.lerp(ik.middle, THIGH_BULGE)
            } else {
                hip
            };
            mesh.tube(
                &[hip, bulge, ik.middle, ankle][first..],
                &[thick, thick, shin, ANKLE * shin][first..],
                &[
                    Bind::one(hip_joint),
                    Bind::one(hip_joint),
                    // The knee ring on the knee joint alone: a ring shared half and half
                    // between two bones shrinks as the knee bends (to 0.79 of its rest size at
                    // 75°, linear blend skinning's pinch); the segments' lengthwise edges take
                    // the bend instead.
                    Bind::one(knee_joint),
                    // The ankle ring on the foot joint: clips keep it level, over the foot.
                    Bind::one(foot_joint),
                ][first..],
                axis,
                sides,
                colour,
            );
            let end_bind = Bind::one(foot_joint);
            let mut horn = mesh.positions.len()..mesh.positions.len();
            if is_leg {
                let shape_start = mesh.positions.len();
                horn = add_foot(mesh, foot_kind, ik.end, foot_size, colour, end_bind);
                centre_foot(
                    mesh,
                    first_vertex..mesh.positions.len(),
                    first_triangle..mesh.indices.len(),
                    shape_start..mesh.positions.len(),
                    foot_joint,
                    ik.end,
                    flat,
                );
            } else {
                let forward = (ik.end - ik.middle).normalize_or(Vec3::NEG_Y);
                let inward = Vec3::X * -out;
                add_hand(
                    mesh,
                    ik.end,
                    forward,
                    inward,
                    HAND * thick,
                    colour,
                    end_bind,
                );
            }
            BuiltLimb {
                chain: Some(LegChain {
                    hip_joint: usize::from(hip_joint),
                    hip,
                    end: ik.end,
                    upper: segment,
                    lower: segment,
                    pole,
                }),
                horn,
                tones: Vec::new(),
            }
        }
        Build::Membrane(m) => {
            let along = (m.along)(out);
            let across = (m.across - along * along.dot(m.across)).normalize_or(m.across_fallback);
            let planform = match (shape.kind, wing_kind) {
                (LimbKind::FlappingWing, WingKind::Feathered) => Some(wings::feathered()),
                (LimbKind::FlappingWing, WingKind::Bat) => Some(wings::bat()),
                (LimbKind::BuzzingWing, _) => Some(wings::insect()),
                _ => None,
            };
            let (length, width) = match &planform {
                Some(p) if matches!(shape.kind, LimbKind::FlappingWing | LimbKind::BuzzingWing) => {
                    let root = (mount.point.x - mount.centre.x).abs();
                    flapping_wing(length, root, along.x.abs(), wing, p.area())
                }
                _ => (length, (m.width)(limb, length)),
            };
            let chain = chain_joints(&mut push_joint, mount, along, length, m.bones, base);
            let tones = if let Some(planform) = &planform {
                let frame = WingFrame {
                    origin: mount.point,
                    along,
                    across,
                    length,
                    width,
                };
                mesh.wing(frame, planform, &chain, colour)
            } else {
                let outline = match shape.kind {
                    LimbKind::DorsalFin => Outline::Swept,
                    LimbKind::Tail => tail_fin,
                    _ => Outline::Rounded,
                };
                mesh.membrane(
                    Membrane {
                        origin: mount.point,
                        along,
                        across,
                        length,
                        width,
                        outline,
                    },
                    &chain,
                    colour,
                );
                Vec::new()
            };
            BuiltLimb {
                chain: None,
                horn: mesh.positions.len()..mesh.positions.len(),
                tones,
            }
        }
    }
}

/// `bones` joints evenly spaced from the mount along `along`, each the parent of the next.
fn chain_joints(
    push_joint: &mut impl FnMut(Vec3, usize, &str) -> u16,
    mount: Mount,
    along: Vec3,
    length: f32,
    bones: usize,
    base: usize,
) -> Vec<u16> {
    (0..bones)
        .map(|k| {
            let parent = if k == 0 { mount.joint } else { base + k - 1 };
            push_joint(
                mount.point + along * (length * k as f32 / bones as f32),
                parent,
                &format!("{}", k + 1),
            )
        })
        .collect()
}

/// The socket point a limb attaches to.
///
/// # Errors
/// [`Error::Unsupported`] for a socket the planner has and this facade does not.
pub(crate) fn socket_point(
    socket: Socket,
    left: Vec3,
    right: Vec3,
    top: Vec3,
    tip: Vec3,
) -> Result<Vec3, Error> {
    match socket {
        Socket::Left => Ok(left),
        Socket::Right => Ok(right),
        Socket::Top => Ok(top),
        Socket::Tip => Ok(tip),
        _ => Err(Error::Unsupported {
            what: "limb socket",
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::d3::extremities::FEET;
    use creature_limbs::Span;

    #[test]
    fn every_limb_type_the_planner_makes_has_one_row() {
        for kind in [
            LimbKind::Leg,
            LimbKind::Arm,
            LimbKind::BuzzingWing,
            LimbKind::FlappingWing,
            LimbKind::DorsalFin,
            LimbKind::PectoralFin,
            LimbKind::Tail,
        ] {
            let rows = LIMB_SHAPES.iter().filter(|s| s.kind == kind).count();
            assert_eq!(rows, 1, "{kind:?}");
            assert!(limb_shape(kind).is_ok());
        }
    }

    fn wing(side: Side) -> Limb {
        Limb {
            kind: LimbKind::FlappingWing,
            variant: 0,
            bone: 0,
            socket: if side == Side::Left {
                Socket::Left
            } else {
                Socket::Right
            },
            side,
            mirror: None,
            scale: Vec3::ONE,
            length: 1.0,
            foot: None,
            span: Span {
                start: 0.0,
                end: 1.0,
                first_bone: 0,
                last_bone: 0,
            },
        }
    }

    fn leg(foot: Vec3) -> Limb {
        Limb {
            kind: LimbKind::Leg,
            foot: Some(foot),
            length: 1.0,
            ..wing(Side::Left)
        }
    }

    /// A leg from `(0.3, 1, 0)` to a foot of `kind` on the ground, its thigh 1.5 × its shin.
    fn build_leg(kind: Foot, flat: bool) -> (MeshBuilder, Vec<Joint>, BuiltLimb) {
        let style = LimbStyle {
            knee: Some(Knee::Forward),
            foot: kind,
            flat,
            ..STYLE
        };
        let limb = leg(Vec3::new(0.45, 0.0, 0.1));
        build_with(&limb, Vec3::new(0.3, 1.0, 0.0), Vec3::Y, style)
    }

    const STYLE: LimbStyle = LimbStyle {
        knee: None,
        sides: 5,
        colour: Vec3::ONE,
        foot: Foot::Paw,
        thigh: 1.5,
        wing: WingSize {
            span: 0.0,
            area: 0.0,
        },
        wing_kind: WingKind::Feathered,
        tail_fin: Outline::Rounded,
        flat: true,
    };

    /// `limb` on a body whose spine joint is at `centre`, mounted at `point`.
    fn build_with(
        limb: &Limb,
        point: Vec3,
        centre: Vec3,
        style: LimbStyle,
    ) -> (MeshBuilder, Vec<Joint>, BuiltLimb) {
        let mut mesh = MeshBuilder::default();
        let mut joints = alloc::vec![Joint {
            name: "spine_0".into(),
            position: centre,
            parent: None,
            part: Part::Spine,
        }];
        let mount = Mount {
            point,
            joint: 0,
            width: 0.6,
            centre,
        };
        let shape = limb_shape(limb.kind).expect("every planner limb type has a row");
        let built = add_limb(
            &mut mesh,
            &mut joints,
            &mut LimbNames::default(),
            0,
            limb,
            shape,
            mount,
            style,
        );
        (mesh, joints, built)
    }

    #[test]
    fn a_leg_has_a_thick_thigh_a_thin_shin_and_a_foot_of_its_kind_on_its_bones() {
        let mut shapes = Vec::new();
        for kind in FEET {
            for flat in [true, false] {
                let (mesh, joints, built) = build_leg(kind, flat);
                assert_eq!(joints.len(), 4, "hip, knee, foot");
                let [hip, knee, foot] = [1u16, 2, 3];
                let at = |j: u16| joints[usize::from(j)].position;
                let (ids, weights) = (&mesh.joints, &mesh.weights);
                let bound = |j: u16| {
                    (0..ids.len()).filter(move |&v| ids[v][0] == j && weights[v][0] == 1.0)
                };
                // Every vertex on one bone.
                assert!(mesh.weights.iter().all(|w| *w == [1.0, 0.0, 0.0, 0.0]));
                // The thigh on the hip, thickest; the shin on the knee; the foot on the foot,
                // on the ground (its sole at the foot joint's height) and below the knee.
                let far = |j: u16, a: Vec3, b: Vec3| {
                    bound(j)
                        .map(|v| {
                            let p = mesh.positions[v];
                            let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                            p.distance(a + (b - a) * t)
                        })
                        .fold(0.0f32, f32::max)
                };
                let thigh = far(hip, at(hip), at(knee));
                let shin = far(knee, at(knee), at(foot));
                assert!((thigh / shin - 1.5).abs() < 1e-3, "{thigh} / {shin}");
                let sole = bound(foot)
                    .map(|v| mesh.positions[v].y)
                    .fold(f32::INFINITY, f32::min);
                assert!(
                    sole.abs() < 1e-5 && at(foot).y.abs() < 1e-6,
                    "sole at {sole}"
                );
                assert!(bound(foot).all(|v| mesh.positions[v].y < at(knee).y));
                // Centred on the foot joint across the ground, as the delivered mesh counts
                // its vertices (once per triangle corner with flat normals).
                let mut count = alloc::vec![usize::from(!flat); mesh.positions.len()];
                if flat {
                    for &i in mesh.indices.iter().flatten() {
                        count[i as usize] += 1;
                    }
                }
                let (sum, n) = bound(foot).fold((Vec3::ZERO, 0.0f32), |(s, n), v| {
                    (s + mesh.positions[v] * count[v] as f32, n + count[v] as f32)
                });
                let off = (sum / n - at(foot)) * Vec3::new(1.0, 0.0, 1.0);
                assert!(off.length() < 1e-5, "{kind:?}: foot centre off by {off}");
                // Hooves and claws in horn, paws not.
                assert_eq!(built.horn.is_empty(), kind == Foot::Paw, "{kind:?}");
                for t in &mesh.indices {
                    let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
                    assert!((b - a).cross(c - a).length() > 1e-7, "{kind:?}");
                }
                if flat {
                    shapes.push(bound(foot).count());
                }
            }
        }
        // The three kinds are three shapes.
        shapes.sort_unstable();
        shapes.dedup();
        assert_eq!(shapes.len(), FEET.len(), "{shapes:?}");
    }

    #[test]
    fn flapping_wings_reach_their_span_and_grow_with_the_area_asked() {
        let share = 0.7;
        let wing =
            |span: f32, area: f32| flapping_wing(0.3, 0.2, 1.0, WingSize { span, area }, share);
        // As planned when that is enough.
        assert_eq!(wing(0.0, 0.0), (0.3, WING_CHORD * 0.3));
        // Long enough for the span: the root 0.2 out, so the tips 1.2 apart.
        let (length, _) = wing(1.2, 0.0);
        assert!((length - 0.4).abs() < 1e-6);
        // More area asked, a wider wing, then a longer one; never less area than asked, and
        // the asked area once it is more than the span's wing has.
        let mut last = 0.0;
        for area in [0.05f32, 0.1, 0.2, 0.4, 0.8, 1.6] {
            let (length, width) = wing(1.2, area);
            let got = 2.0 * share * length * width;
            assert!(got >= area * (1.0 - 1e-5) && got >= last, "{area}: {got}");
            assert!(
                area < 0.2 || (got / area - 1.0).abs() < 1e-5,
                "{area}: {got}"
            );
            assert!(width <= MAX_WING_CHORD * length * (1.0 + 1e-6));
            last = got;
        }
    }

    /// A membrane 2 long along +X, `width` wide across Z, on four joints.
    fn membrane_along_x(width: f32, outline: Outline) -> MeshBuilder {
        let mut mesh = MeshBuilder::default();
        let shape = Membrane {
            origin: Vec3::ZERO,
            along: Vec3::X,
            across: Vec3::Z,
            length: 2.0,
            width,
            outline,
        };
        mesh.membrane(shape, &[0, 1, 2, 3], Vec3::ONE);
        mesh
    }

    #[test]
    fn a_forked_fin_ends_in_two_lobes_and_a_swept_fin_leans_back() {
        let fin = |outline| {
            let mesh = membrane_along_x(1.0, outline);
            // Every triangle has area and faces its side's way (the two faces opposite).
            let normals: Vec<f32> = mesh
                .indices
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
                    let n = (b - a).cross(c - a);
                    assert!(n.length() > 1e-6, "{outline:?}: a sliver");
                    n.y.signum()
                })
                .collect();
            let half = normals.len() / 2;
            assert!(
                normals[..half].iter().all(|&s| s == normals[0]),
                "{outline:?}"
            );
            assert!(
                normals[half..].iter().all(|&s| s == -normals[0]),
                "{outline:?}"
            );
            mesh.positions
        };
        // Forked: the end's two outermost points at the full length, wide apart; the middle
        // of the end short of them (the notch).
        let forked = fin(Outline::Forked);
        let at_end: Vec<Vec3> = forked.iter().copied().filter(|p| p.x > 1.99).collect();
        assert!(at_end.iter().any(|p| p.z > 0.45) && at_end.iter().any(|p| p.z < -0.45));
        let notch = forked
            .iter()
            .filter(|p| p.z.abs() < 1e-6 && p.x > 1.0)
            .map(|p| p.x)
            .fold(0.0f32, f32::max);
        assert!(notch > 1.5 && notch < 1.95, "notch at {notch}");
        // Swept: widest at the root, its tip behind the root along `across`.
        let swept = fin(Outline::Swept);
        let width_at = |x: f32| {
            swept
                .iter()
                .filter(|p| (p.x - x).abs() < 1e-4)
                .map(|p| p.z)
                .fold(f32::NEG_INFINITY, f32::max)
        };
        assert!(width_at(0.0) > width_at(1.0) && width_at(1.0) > width_at(1.5));
        let tip = swept
            .iter()
            .copied()
            .fold(Vec3::ZERO, |m, p| if p.x > m.x { p } else { m });
        assert!(tip.z < -0.3, "tip at {tip}");
    }

    fn build(limb: &Limb, point: Vec3) -> (MeshBuilder, Vec<Joint>) {
        let (mesh, joints, built) = build_with(limb, point, Vec3::ZERO, STYLE);
        assert!(built.chain.is_none(), "wings have no leg chain");
        (mesh, joints)
    }

    #[test]
    fn wings_point_away_from_the_body_whatever_the_side_label() {
        // Labelled left, on the left (+X): out along +X (within the membrane's thickness).
        let (mesh, joints) = build(&wing(Side::Left), Vec3::new(0.3, 0.0, 0.0));
        assert_eq!(joints.len(), 5, "a flapping wing has 4 bones");
        assert!(mesh.positions.iter().all(|p| p.x >= 0.3 - 1e-3));
        // Labelled left but lying on −X (a rigger with the other convention): still outward.
        let (mesh, _) = build(&wing(Side::Left), Vec3::new(-0.3, 0.0, 0.0));
        assert!(mesh.positions.iter().all(|p| p.x <= -0.3 + 1e-3));
        // Every membrane triangle has area, and every vertex one full weight.
        for t in &mesh.indices {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            assert!((b - a).cross(c - a).length() > 1e-6);
        }
        assert!(
            mesh.weights
                .iter()
                .all(|w| (w.iter().sum::<f32>() - 1.0).abs() < 1e-6)
        );
    }
}
