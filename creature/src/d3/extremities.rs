//! Feet and hands: what a leg or an arm ends in, drawn per creature (paws, hooves or clawed
//! toes; mitts for hands), and the limbs' proportions (thigh against shin, the wings' span and
//! area), drawn from a generator of their own so they change nothing else.
//!
//! Every part is a closed tube of the head's kind ([`Tube`]), rigid on the end joint. A foot
//! stands on its joint's height (the ground, for a standing leg) and is centred on the joint
//! across the ground, so turning a planted foot with the body's heading does not slide it.

use alloc::vec::Vec;
use core::ops::Range;

use glam::Vec3;
use rand_core::Rng;

use super::head::{Frame, Paint, Ring, Tube};
use super::limbs::{Bind, MeshBuilder, Outline};
use super::params::Params;
use super::wings::WingKind;
use crate::math::sin;
use crate::rng::uniform;

/// What a creature's legs end in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Foot {
    /// A padded oval with four toe nubs in front.
    Paw,
    /// A horn-coloured frustum under a slender ankle.
    Hoof,
    /// Three toes forward and one back, each with a horn-coloured claw.
    Claws,
}

/// Every foot kind, in the order they are drawn.
pub(crate) const FEET: [Foot; 3] = [Foot::Paw, Foot::Hoof, Foot::Claws];

/// A creature's limb proportions, drawn once for all its limbs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Proportions {
    /// What its legs end in.
    pub(crate) foot: Foot,
    /// Thigh (upper arm) radius × shin (forearm) radius.
    pub(crate) thigh: f32,
    /// Wings' span tip to tip (flapping or buzzing), × body length (at least).
    pub(crate) wing_span: f32,
    /// Wings' area (flapping or buzzing; both wings, one face), × the body's volume to the power 2/3
    /// (at least).
    pub(crate) wing_area: f32,
    /// A tail fin's outline: forked or rounded, evenly.
    pub(crate) tail_fin: Outline,
    /// What flapping wings are made of.
    pub(crate) wing_kind: WingKind,
}

impl Proportions {
    /// Draws the proportions from `rng` within `params`' ranges.
    pub(crate) fn draw(rng: &mut impl Rng, params: &Params) -> Self {
        let pick = (uniform(rng) * FEET.len() as f32) as usize;
        Self {
            foot: FEET[pick.min(FEET.len() - 1)],
            thigh: params.thigh_thickness.at(uniform(rng)),
            wing_span: params.wing_span.at(uniform(rng)),
            wing_area: params.wing_area.at(uniform(rng)),
            tail_fin: if uniform(rng) < 0.5 {
                Outline::Forked
            } else {
                Outline::Rounded
            },
            wing_kind: params.wing_kinds.pick(uniform(rng)),
        }
    }
}

/// Segments around a foot's pad or hoof, and around a hand.
const FOOT_SEGMENTS: usize = 8;
/// Segments around a toe, a claw or a thumb.
const TOE_SEGMENTS: usize = 6;

/// How far the ankle ring sits above the foot joint, × the foot's size, per foot kind: just
/// inside the foot's top, so the leg's end cap is hidden in the foot.
pub(crate) fn ankle_height(foot: Foot) -> f32 {
    match foot {
        Foot::Paw => 0.8,
        Foot::Hoof => 0.75,
        Foot::Claws => 0.75,
    }
}

/// The ankle (wrist) ring's radius × the shin radius.
pub(crate) const ANKLE: f32 = 0.6;

/// The lowest `sin` of a ring's vertices (`segments` around, the first at angle 0): a ring
/// centred `-lowest · ry` above a level plane touches it with its lowest vertex.
fn lowest(segments: usize) -> f32 {
    (0..segments)
        .map(|j| sin(core::f32::consts::TAU * j as f32 / segments.max(1) as f32))
        .fold(0.0f32, f32::min)
}

/// A foot of `kind` bound by `bind` at `at` (its sole at `at.y`), facing +Z, of size `shin`
/// (a paw is 2.2 long), in `colour`. Returns the vertices to colour as horn (a hoof, claws).
pub(crate) fn add_foot(
    mesh: &mut MeshBuilder,
    kind: Foot,
    at: Vec3,
    shin: f32,
    colour: Vec3,
    bind: Bind,
) -> Range<usize> {
    let frame = Frame::new(at, Vec3::Z);
    let paint = |_: usize, _: f32| colour;
    let paint = Paint {
        banded: false,
        up: Vec3::Y,
        paint: &paint,
    };
    let s = shin;
    // Rings square to a level direction whose lowest vertex is on the sole.
    let level = |segments: usize| -lowest(segments);
    let horn_start;
    match kind {
        Foot::Paw => {
            pad(
                mesh,
                &frame,
                s,
                &[(-0.7, 0.7, 0.4), (0.0, 0.95, 0.55), (0.8, 1.0, 0.45)],
                [(0.35, -1.0), (0.3, 1.2)],
                &paint,
                bind,
            );
            let toe = 0.22;
            let kt = level(TOE_SEGMENTS);
            for x in [-0.6f32, -0.2, 0.2, 0.6] {
                nub(
                    mesh,
                    [
                        frame.at(x * s, kt * toe * s, 0.75 * s),
                        frame.at(x * s, kt * toe * s, 1.1 * s),
                        frame.at(1.1 * x * s, 0.1 * s, 1.45 * s),
                    ],
                    toe * s,
                    (frame.side, frame.up),
                    &paint,
                    bind,
                );
            }
            horn_start = mesh.positions.len();
        }
        Foot::Hoof => {
            horn_start = mesh.positions.len();
            // A vertical frustum: its rings square to the up axis (x across, y forward).
            let ring = |h: f32, rx: f32, ry: f32| Ring {
                centre: frame.at(0.0, h * s, 0.0),
                rx: rx * s,
                ry: ry * s,
            };
            let rings = [ring(0.0, 0.85, 1.0), ring(0.9, 0.7, 0.75)];
            mesh.head_tube(
                Tube {
                    back: frame.at(0.0, 0.0, 0.0),
                    rings: &rings,
                    front: frame.at(0.0, 0.9 * s, 0.0),
                    x: -frame.side,
                    y: frame.forward,
                    segments: FOOT_SEGMENTS,
                },
                &paint,
                bind,
            );
        }
        Foot::Claws => {
            // A heel pad, then the toes and their claws.
            pad(
                mesh,
                &frame,
                s,
                &[(-0.3, 0.65, 0.5), (0.3, 0.7, 0.55)],
                [(0.4, -0.75), (0.4, 0.75)],
                &paint,
                bind,
            );
            // Toes: direction (x, z) in the ground plane and length, × the shin radius.
            let toes = [
                (-0.55f32, 0.84f32, 1.3f32),
                (0.0, 1.0, 1.5),
                (0.55, 0.84, 1.3),
            ];
            let back_toe = (0.0f32, -1.0f32, 0.8f32);
            let kt = level(TOE_SEGMENTS);
            let mut claws = Vec::with_capacity(4);
            for (x, z, length) in toes.into_iter().chain([back_toe]) {
                let dir = frame.dir(x, 0.0, z).normalize_or(frame.forward);
                let r = 0.3 * s;
                let base = at + dir * (0.3 * s);
                let end = at + dir * (length * s);
                let rings = [
                    Ring {
                        centre: base + frame.up * (kt * r),
                        rx: r,
                        ry: r,
                    },
                    Ring {
                        centre: end + frame.up * (kt * 0.7 * r),
                        rx: 0.7 * r,
                        ry: 0.7 * r,
                    },
                ];
                let (x_axis, y_axis) = (frame.up.cross(dir), frame.up);
                mesh.head_tube(
                    Tube {
                        back: base + frame.up * (kt * r) - dir * r,
                        rings: &rings,
                        front: end + frame.up * (kt * 0.7 * r) + dir * (0.3 * r),
                        x: x_axis,
                        y: y_axis,
                        segments: TOE_SEGMENTS,
                    },
                    &paint,
                    bind,
                );
                claws.push((end, dir, r));
            }
            horn_start = mesh.positions.len();
            for (end, dir, r) in claws {
                // A claw from the toe's tip, hooked down to the ground.
                let kc = level(TOE_SEGMENTS);
                let root = end + dir * (0.2 * r) + frame.up * (kc * 0.45 * r);
                nub(
                    mesh,
                    [root - dir * (0.5 * r), root, end + dir * (1.6 * r)],
                    0.45 * r,
                    (frame.up.cross(dir), frame.up),
                    &paint,
                    bind,
                );
            }
        }
    }
    horn_start..mesh.positions.len()
}

/// A mitt on the hand joint at `at`, along `forward` (the forearm's direction), its thumb
/// toward `inward`, of size `forearm` (the mitt is 1.9 long).
pub(crate) fn add_hand(
    mesh: &mut MeshBuilder,
    at: Vec3,
    forward: Vec3,
    inward: Vec3,
    forearm: f32,
    colour: Vec3,
    bind: Bind,
) {
    let frame = Frame::new(at, forward);
    let s = forearm;
    let paint = |_: usize, _: f32| colour;
    let paint = Paint {
        banded: false,
        up: Vec3::Y,
        paint: &paint,
    };
    let ring = |z: f32, rx: f32, ry: f32| Ring {
        centre: frame.at(0.0, 0.0, z * s),
        rx: rx * s,
        ry: ry * s,
    };
    let rings = [ring(0.1, 0.75, 0.5), ring(0.9, 0.95, 0.45)];
    mesh.head_tube(
        Tube {
            back: frame.at(0.0, 0.0, -0.3 * s),
            rings: &rings,
            front: frame.at(0.0, -0.1 * s, 1.6 * s),
            x: frame.side,
            y: frame.up,
            segments: FOOT_SEGMENTS,
        },
        &paint,
        bind,
    );
    // The thumb, out of the palm's inner side.
    let inward = (inward - frame.forward * inward.dot(frame.forward)).normalize_or(frame.side);
    let base = frame.at(0.0, 0.0, 0.5 * s) + inward * (0.55 * s);
    let dir = (inward + frame.forward).normalize_or(frame.forward);
    nub(
        mesh,
        [base - dir * (0.3 * s), base, base + dir * (0.6 * s)],
        0.25 * s,
        super::head::cross_axes(dir),
        &paint,
        bind,
    );
}

/// A foot's pad along `frame`'s forward axis, sized by `s`: `rings` of `(z, rx, ry)` standing
/// on the sole (each ring's lowest vertex on it), from the tip `ends[0]` to the tip `ends[1]`,
/// each `(height, z)`.
#[allow(clippy::too_many_arguments)]
fn pad(
    mesh: &mut MeshBuilder,
    frame: &Frame,
    s: f32,
    rings: &[(f32, f32, f32)],
    ends: [(f32, f32); 2],
    paint: &Paint<'_>,
    bind: Bind,
) {
    let k = -lowest(FOOT_SEGMENTS);
    let rings: Vec<Ring> = rings
        .iter()
        .map(|&(z, rx, ry)| Ring {
            centre: frame.at(0.0, k * ry * s, z * s),
            rx: rx * s,
            ry: ry * s,
        })
        .collect();
    let tip = |(h, z): (f32, f32)| frame.at(0.0, h * s, z * s);
    mesh.head_tube(
        Tube {
            back: tip(ends[0]),
            rings: &rings,
            front: tip(ends[1]),
            x: frame.side,
            y: frame.up,
            segments: FOOT_SEGMENTS,
        },
        paint,
        bind,
    );
}

/// A toe, claw or thumb: a tube from `back` through one round ring of `radius` at `centre`
/// (across `axes`, whose cross product points toward `front`) to `front`.
fn nub(
    mesh: &mut MeshBuilder,
    [back, centre, front]: [Vec3; 3],
    radius: f32,
    (x, y): (Vec3, Vec3),
    paint: &Paint<'_>,
    bind: Bind,
) {
    let rings = [Ring {
        centre,
        rx: radius,
        ry: radius,
    }];
    mesh.head_tube(
        Tube {
            back,
            rings: &rings,
            front,
            x,
            y,
            segments: TOE_SEGMENTS,
        },
        paint,
        bind,
    );
}

/// Moves the foot's vertices `shape` across the ground so that the mean of the vertices bound
/// to `joint` among `vertices` (the limb's; with `flat` normals, counted once per triangle
/// corner of `triangles`, as the delivered mesh has them) is right above `at`: a planted foot
/// turning about its joint then keeps its centre still.
pub(crate) fn centre_foot(
    mesh: &mut MeshBuilder,
    vertices: Range<usize>,
    triangles: Range<usize>,
    shape: Range<usize>,
    joint: u16,
    at: Vec3,
    flat: bool,
) {
    let start = vertices.start;
    let mut count = alloc::vec![u32::from(!flat); vertices.len()];
    if flat {
        for t in mesh.indices.get(triangles).unwrap_or(&[]) {
            for &i in t {
                if let Some(c) = (i as usize)
                    .checked_sub(start)
                    .and_then(|k| count.get_mut(k))
                {
                    *c += 1;
                }
            }
        }
    }
    let bound = |i: usize| mesh.joints[i][0] == joint && mesh.weights[i][0] >= 1.0;
    let (mut sum, mut n, mut moved) = (Vec3::ZERO, 0.0f32, 0.0f32);
    for (k, i) in vertices.clone().enumerate() {
        if bound(i) {
            let c = count[k] as f32;
            sum += mesh.positions[i] * c;
            n += c;
            if shape.contains(&i) {
                moved += c;
            }
        }
    }
    if n <= 0.0 || moved <= 0.0 {
        return;
    }
    let mut shift = (at - sum / n) * (n / moved);
    shift.y = 0.0;
    for i in shape {
        if let Some(p) = mesh.positions.get_mut(i) {
            *p += shift;
        }
    }
}
