//! Accessories on a walker's back: a row of spikes or of plates along its spine, or a shell
//! over the middle of its back, drawn per creature from a generator of its own (so it changes
//! nothing else). Each piece of a row is rigid on the spine joint it stands on; a shell is the
//! skin of the back it covers lifted into a dome, each of its vertices skinned as the skin
//! under it, so it bends with the body.
//!
//! A piece stands on the top of the body's skin at its joint (the highest body vertex bound
//! mostly to that joint), sunk a little into it, leaning back; its height is
//! [`Params::back_ornament_size`] × the body's half-height there, so a row tapers with the
//! body toward the tail and the neck. Pieces keep apart: a joint closer to the last piece than
//! half that piece's height is skipped, and so is a piece under 1% of the spine's length. Only joints where the spine runs within 37° of level
//! carry one (a raised neck does not), and never the head's, its carrier or the tail's tip.

use alloc::vec::Vec;
use core::f32::consts::PI;

use glam::Vec3;
use rand_core::Rng;

use super::colour::SurfacePoint;
use super::head::{Paint, Ring, Tube, add_cone};
use super::limbs::{Bind, MeshBuilder};
use super::params::Params;
use crate::Error;
use crate::math::sin;
use crate::rng::uniform;

/// What a walker wears on its back.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum BackKind {
    /// A row of cones leaning back.
    Spikes,
    /// A row of flat upright plates, thin across the body and broad along it.
    Plates,
    /// A domed shell over the middle of the back, in plates of two shades with a dark rim.
    Shell,
}

impl BackKind {
    /// Every kind, in the order [`BackWeights`] draws them.
    pub const ALL: [Self; 3] = [Self::Spikes, Self::Plates, Self::Shell];
}

/// Relative weights of the [`BackKind`]s a walker that wears something on its back draws from
/// (see [`Params::back_ornament_chance`]): kind `k` is drawn with probability
/// `weight(k) / sum of weights`. Each from 0 to 1000, at least one above 0.
///
/// ```
/// use creature::d3::{BackKind, BackWeights, Params};
///
/// // Every walker in a shell.
/// let params = Params::DEFAULT
///     .with_back_ornaments(Params::DEFAULT.back_ornament_size, 1.0)
///     .with_back_kinds(BackWeights::only(BackKind::Shell));
/// params.validate()?;
/// # Ok::<(), creature::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct BackWeights {
    /// Weight of [`BackKind::Spikes`]. Default 1.
    pub spikes: f32,
    /// Weight of [`BackKind::Plates`]. Default 1.
    pub plates: f32,
    /// Weight of [`BackKind::Shell`]. Default 1.
    pub shell: f32,
}

impl BackWeights {
    /// The defaults listed on each field: every kind alike.
    pub const DEFAULT: Self = Self {
        spikes: 1.0,
        plates: 1.0,
        shell: 1.0,
    };

    /// Weight 1 for `kind`, 0 for the others.
    #[must_use]
    pub const fn only(kind: BackKind) -> Self {
        let none = Self {
            spikes: 0.0,
            plates: 0.0,
            shell: 0.0,
        };
        none.with(kind, 1.0)
    }

    /// Sets the weight of `kind`.
    #[must_use]
    pub const fn with(mut self, kind: BackKind, weight: f32) -> Self {
        match kind {
            BackKind::Spikes => self.spikes = weight,
            BackKind::Plates => self.plates = weight,
            BackKind::Shell => self.shell = weight,
        }
        self
    }

    /// The weight of `kind`.
    #[must_use]
    pub const fn weight(&self, kind: BackKind) -> f32 {
        match kind {
            BackKind::Spikes => self.spikes,
            BackKind::Plates => self.plates,
            BackKind::Shell => self.shell,
        }
    }

    /// Checks every weight is finite and from 0 to 1000, and one is above 0.
    pub(crate) fn check(&self, what: &'static str) -> Result<(), Error> {
        crate::rng::check_weights(what, &BackKind::ALL.map(|k| self.weight(k)))
    }

    /// The kind at `u` in `[0, 1)` of the weights' cumulative sum.
    fn pick(&self, u: f32) -> BackKind {
        BackKind::ALL[crate::rng::pick_weighted(&BackKind::ALL.map(|k| self.weight(k)), u)]
    }
}

impl Default for BackWeights {
    fn default() -> Self {
        Self::DEFAULT
    }
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
    /// A shell's thickness on top of its middle, × [`SHELL_HEIGHT`] × the body's radius.
    shell: f32,
}

impl BackRow {
    /// Draws the row from `rng` within `params`' ranges (every value always drawn, so the
    /// chance changes nothing else).
    pub(crate) fn draw(rng: &mut impl Rng, params: &Params) -> Self {
        let has = uniform(rng) < params.back_ornament_chance;
        let kind = params.back_kinds.pick(uniform(rng));
        let size = params.back_ornament_size.at(uniform(rng));
        let horn = uniform(rng) < 0.5;
        let shell = params.shell_size.at(uniform(rng));
        Self {
            kind: has.then_some(kind),
            size,
            horn,
            shell,
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

/// The least height of a piece of a row, × the spine's length (1%): smaller ones are skipped.
const MIN_HEIGHT: f32 = 0.01;

/// Adds `row` along the spine of `rig` on the body of `mesh` (its first `body_vertices`
/// vertices, at `surface` on the body's surface), in `accent` or a horn colour; returns how
/// many pieces it added (a shell is one).
pub(crate) fn add_back_row(
    mesh: &mut MeshBuilder,
    body_vertices: usize,
    surface: &[SurfacePoint],
    rig: &creature_autorig::Rig,
    row: &BackRow,
    accent: Vec3,
) -> u32 {
    let Some(kind) = row.kind else {
        return 0;
    };
    let size = if kind == BackKind::Shell {
        row.shell
    } else {
        row.size
    };
    if size <= 0.0 {
        return 0;
    }
    let colour = if row.horn {
        Vec3::new(0.62, 0.55, 0.42)
    } else {
        accent
    };
    let spikes = match kind {
        BackKind::Shell => {
            return u32::from(add_shell(
                mesh,
                body_vertices,
                surface,
                rig,
                row.size,
                colour,
            ));
        }
        BackKind::Spikes => true,
        BackKind::Plates => false,
    };
    let spine = &rig.spine;
    let n = spine.len();
    let spine_length: f32 = spine
        .windows(2)
        .map(|w| {
            rig.joints[w[0]]
                .position
                .distance(rig.joints[w[1]].position)
        })
        .sum();
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
            .filter(|&v| mesh.dominant(v) == j)
            .map(|v| mesh.positions[v])
            .filter(|p| p.y > at.y)
            .max_by(|a, b| a.y.total_cmp(&b.y));
        let Some(top) = top else {
            continue;
        };
        let height = row.size * (top.y - at.y);
        // A piece too small to see is skipped: on a body pinched to a point its triangles
        // would have no area.
        if !(height > MIN_HEIGHT * spine_length) {
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
        if spikes {
            let radius = (0.3 * height).min(0.45 * spacing);
            add_cone(mesh, base, up * height, radius, colour, bind);
        } else {
            add_plate(mesh, base, up, back, height, spacing, colour, bind);
        }
        placed += 1;
        last = Some((at, height));
    }
    placed
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

/// Where along the body (0 the tail's tip, 1 the head's end of the body) a shell runs.
const SHELL_ALONG: [f32; 2] = [0.25, 0.72];
/// The lowest a shell reaches round the body: skin facing up at least this (the sine of its
/// angle above the body's axis; 0 the flank's middle).
const SHELL_UP: f32 = -0.15;
/// A shell's thickness at the top of its middle, × its size × the body's radius there.
const SHELL_HEIGHT: f32 = 0.8;
/// Rows of plates along a shell.
const SHELL_ROWS: f32 = 4.0;

/// Adds a shell over the back of `mesh`'s body (its first `body_vertices` vertices, at
/// `surface`): the body triangles whose corners all lie in [`SHELL_ALONG`] and face up at
/// least [`SHELL_UP`], lifted off the skin along its normals (most at the top of the middle,
/// `size` ([`Params::shell_size`]) × [`SHELL_HEIGHT`] × the body's radius from its spine
/// joint) over a copy of them
/// on the skin, closed by a dark rim; every vertex skinned as the skin vertex it comes from.
/// Returns whether it added one (a body too coarse for a patch gets none).
fn add_shell(
    mesh: &mut MeshBuilder,
    body_vertices: usize,
    surface: &[SurfacePoint],
    rig: &creature_autorig::Rig,
    size: f32,
    colour: Vec3,
) -> bool {
    let body = body_vertices.min(surface.len()).min(mesh.positions.len());
    let inside = |v: u32| {
        let v = v as usize;
        v < body && {
            let s = surface[v];
            (SHELL_ALONG[0]..=SHELL_ALONG[1]).contains(&s.along) && s.up >= SHELL_UP
        }
    };
    // The skin's normals: area-weighted over the body's triangles.
    let mut normals = alloc::vec![Vec3::ZERO; body];
    let body_triangles: Vec<[u32; 3]> = mesh
        .indices
        .iter()
        .filter(|t| t.iter().all(|&v| (v as usize) < body))
        .copied()
        .collect();
    for t in &body_triangles {
        let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
        let n = (b - a).cross(c - a);
        for &v in t {
            normals[v as usize] += n;
        }
    }
    let patch: Vec<[u32; 3]> = body_triangles
        .iter()
        .filter(|t| t.iter().all(|&v| inside(v)))
        .copied()
        .collect();
    if patch.len() < 4 {
        return false;
    }
    // The patch's vertices' outer and inner copies, by body vertex (`NONE` off the patch).
    const NONE: [u32; 2] = [u32::MAX; 2];
    let mut copy = alloc::vec![NONE; body];
    for t in &patch {
        for &v in t {
            let i = v as usize;
            if copy[i] != NONE {
                continue;
            }
            let p = mesh.positions[i];
            let normal = normals[i].normalize_or(Vec3::Y);
            let bind = Bind::from_arrays(mesh.joints[i], mesh.weights[i]);
            // The body's radius here: how far the skin is from the joint it follows most.
            let radius = rig
                .joints
                .get(mesh.dominant(i))
                .map_or(0.0, |j| p.distance(j.position));
            let s = surface[i];
            let u = (s.along - SHELL_ALONG[0]) / (SHELL_ALONG[1] - SHELL_ALONG[0]);
            let lift = size
                * SHELL_HEIGHT
                * radius
                * (0.3 + 0.7 * sin(PI * u))
                * (0.45 + 0.55 * s.up.max(0.0));
            // Plates: rows along the body, columns round it, in two shades.
            let row = (u * SHELL_ROWS) as i32;
            let column = (s.across * 4.0) as i32;
            let shade = if (row + column) % 2 == 0 { 1.0 } else { 0.72 };
            let outer = mesh.vertex(p + normal * lift, colour * shade, bind);
            let inner = mesh.vertex(p - normal * (0.02 * lift), colour * 0.5, bind);
            copy[i] = [outer, inner];
        }
    }
    // Edges used by one patch triangle: the rim.
    let edges: Vec<(u32, u32)> = patch
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .collect();
    for t in &patch {
        let [a, b, c] = t.map(|v| copy[v as usize]);
        mesh.indices.push([a[0], b[0], c[0]]);
        mesh.indices.push([a[1], c[1], b[1]]);
    }
    // The rim: a dark band from the outer edge down to the inner one, facing out.
    let mut sorted = edges.clone();
    crate::sort::sort_by(&mut sorted, &mut Ord::cmp);
    for &(a, b) in &edges {
        if sorted.binary_search(&(b, a)).is_ok() {
            continue;
        }
        let [a, b] = [copy[a as usize], copy[b as usize]];
        let mut dark = |v: u32| {
            let i = v as usize;
            let bind = Bind::from_arrays(mesh.joints[i], mesh.weights[i]);
            let p = mesh.positions[i];
            mesh.vertex(p, colour * 0.45, bind)
        };
        let (ao, bo, ai, bi) = (dark(a[0]), dark(b[0]), dark(a[1]), dark(b[1]));
        mesh.indices.push([ai, bi, bo]);
        mesh.indices.push([ai, bo, ao]);
    }
    true
}
