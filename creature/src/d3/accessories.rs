//! Accessories on a walker's back: a row of spikes or of plates along its spine, drawn per
//! creature from a generator of its own (so it changes nothing else), each piece rigid on the
//! spine joint it stands on, so the row moves with the body.
//!
//! A piece stands on the top of the body's skin at its joint (the highest body vertex bound
//! mostly to that joint), sunk a little into it, leaning back; its height is
//! [`Params::back_ornament_size`] × the body's half-height there, so a row tapers with the
//! body toward the tail and the neck. Pieces keep apart: a joint closer to the last piece than
//! half that piece's height is skipped. Only joints where the spine runs within 37° of level
//! carry one (a raised neck does not), and never the head's, its carrier or the tail's tip.

use glam::Vec3;
use rand_core::Rng;

use super::head::{Paint, Ring, Tube, add_cone};
use super::limbs::{Bind, MeshBuilder};
use super::params::Params;
use crate::rng::uniform;

/// What a walker wears along its back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum BackKind {
    /// Cones leaning back.
    Spikes,
    /// Flat upright plates, thin across the body and broad along it.
    Plates,
}

/// A creature's back row, drawn once.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BackRow {
    /// What it wears, `None` for a bare back.
    pub(crate) kind: Option<BackKind>,
    /// Height × the body's half-height at the piece's joint.
    size: f32,
    /// In a horn colour (else the palette's accent).
    horn: bool,
}

impl BackRow {
    /// Draws the row from `rng` within `params`' ranges (every value always drawn, so the
    /// chance changes nothing else).
    pub(crate) fn draw(rng: &mut impl Rng, params: &Params) -> Self {
        let has = uniform(rng) < params.back_ornament_chance;
        let kind = if uniform(rng) < 0.5 {
            BackKind::Spikes
        } else {
            BackKind::Plates
        };
        let size = params.back_ornament_size.at(uniform(rng));
        let horn = uniform(rng) < 0.5;
        Self {
            kind: has.then_some(kind),
            size,
            horn,
        }
    }
}

/// The steepest the spine may run at a joint that carries a piece: `|tangent.y|` at most this
/// (37° from level).
const LEVEL: f32 = 0.6;
/// How far a piece's base sinks into the skin, × its height.
const SINK: f32 = 0.12;
/// The least gap between two pieces' joints, × the last piece's height.
const GAP: f32 = 0.5;
/// Segments around a plate (a spike has a horn's).
const SEGMENTS: usize = 6;

/// Adds `row` along the spine of `rig` on the body of `mesh` (its first `body_vertices`
/// vertices), in `accent` or a horn colour; returns how many pieces it added.
pub(crate) fn add_back_row(
    mesh: &mut MeshBuilder,
    body_vertices: usize,
    rig: &creature_autorig::Rig,
    row: &BackRow,
    accent: Vec3,
) -> u32 {
    let Some(kind) = row.kind else {
        return 0;
    };
    if row.size <= 0.0 {
        return 0;
    }
    let colour = if row.horn {
        Vec3::new(0.62, 0.55, 0.42)
    } else {
        accent
    };
    let spine = &rig.spine;
    let n = spine.len();
    let mut placed = 0;
    let mut last: Option<(Vec3, f32)> = None;
    // Not the tail's tip (the spine's first joint), nor the head's carrier and tip (its last
    // two).
    for k in 1..n.saturating_sub(2) {
        let (j, prev, next) = (spine[k], spine[k - 1], spine[k + 1]);
        let at = rig.joints[j].position;
        let tangent = (rig.joints[next].position - rig.joints[prev].position).normalize_or_zero();
        if tangent == Vec3::ZERO || tangent.y.abs() > LEVEL {
            continue;
        }
        // The top of the skin at this joint: the highest body vertex bound mostly to it.
        let top = (0..body_vertices)
            .filter(|&v| most(mesh, v) == j)
            .map(|v| mesh.positions[v])
            .filter(|p| p.y > at.y)
            .max_by(|a, b| a.y.total_cmp(&b.y));
        let Some(top) = top else {
            continue;
        };
        let height = row.size * (top.y - at.y);
        if height <= 0.0 || !height.is_finite() {
            continue;
        }
        if let Some((p, h)) = last
            && p.distance(at) < GAP * h
        {
            continue;
        }
        // Up, leaning back along the spine toward the tail (the creature faces +z).
        let back = Vec3::new(tangent.x, 0.0, tangent.z).normalize_or(Vec3::NEG_Z);
        let back = if back.z > 0.0 { -back } else { back };
        let up = (Vec3::Y + 0.35 * back).normalize_or(Vec3::Y);
        let base = top - up * (SINK * height);
        let bind = Bind::one(j as u16);
        let spacing = rig.joints[next]
            .position
            .distance(at)
            .min(rig.joints[prev].position.distance(at));
        match kind {
            BackKind::Spikes => {
                let radius = (0.3 * height).min(0.45 * spacing);
                add_cone(mesh, base, up * height, radius, colour, bind);
            }
            BackKind::Plates => {
                add_plate(mesh, base, up, back, height, spacing, colour, bind);
            }
        }
        placed += 1;
        last = Some((at, height));
    }
    placed
}

/// The joint body vertex `v` is bound to most.
fn most(mesh: &MeshBuilder, v: usize) -> usize {
    let (js, ws) = (&mesh.joints[v], &mesh.weights[v]);
    let mut best = (0usize, f32::NEG_INFINITY);
    for (&j, &w) in js.iter().zip(ws) {
        if w > best.1 {
            best = (usize::from(j), w);
        }
    }
    best.0
}

/// A plate standing on `base` along `up` for `height`: thin across the body, broad along
/// `back` (at most about `spacing`, so neighbours barely overlap), a rounded diamond.
#[allow(clippy::too_many_arguments)]
fn add_plate(
    mesh: &mut MeshBuilder,
    base: Vec3,
    up: Vec3,
    back: Vec3,
    height: f32,
    spacing: f32,
    colour: Vec3,
    bind: Bind,
) {
    let side = up.cross(back).normalize_or(Vec3::X);
    let along = side.cross(up).normalize_or(back);
    let broad = (0.45 * height).min(0.7 * spacing);
    let thin = 0.08 * height;
    // Across `along` (x) and `side` (y): `along × side` is `up`, the tube's way.
    let ring = |t: f32, width: f32, thick: f32| Ring {
        centre: base + up * (t * height),
        rx: width,
        ry: thick,
    };
    let rings = [
        ring(0.0, 0.45 * broad, thin),
        ring(0.35, broad, 0.8 * thin),
        ring(0.7, 0.7 * broad, 0.5 * thin),
    ];
    let paint = |_: usize, _: f32| colour;
    mesh.head_tube(
        Tube {
            back: base - up * (0.1 * height),
            rings: &rings,
            front: base + up * height,
            x: along,
            y: side,
            segments: SEGMENTS,
        },
        &Paint {
            banded: false,
            up: Vec3::Y,
            paint: &paint,
        },
        bind,
    );
}
