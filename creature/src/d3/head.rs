//! The head: a shape family drawn per creature (round, long snout, beak, broad and flat,
//! insect), a pair of eyes (two pairs on some insects) with a dark lid rim, a light sclera and a
//! dark pupil, a mouth line, and on some heads ears, horns, a crest, mandibles or antennae; all
//! rigid, bound to the `head` joint. Swimmers get a fish face instead: eyes and a mouth on the
//! body's front, bound as the body's skin is there, so the head is the body's front.
//!
//! Every part is a closed tube of elliptic rings in its own frame; the eyes and the mouth
//! colour each band between two rings in one colour on vertices of its own, so a pupil stays
//! one crisp colour with flat normals and with smooth ones alike.

use alloc::vec::Vec;

use glam::Vec3;
use rand_core::Rng;

use super::colour::Colouring;
use super::limbs::{Bind, MeshBuilder};
use super::params::Params;
use crate::math::{cos, sin, sqrt};
use crate::rng::uniform;

/// The head's shape families, drawn uniformly per creature.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Family {
    /// A round skull, eyes facing forward, a mouth line under them; ears on some.
    Round,
    /// A skull with a long, tapering, lowered snout, eyes on the sides; ears or horns on some.
    Snout,
    /// A round skull with a pointed beak in a horn colour, eyes on the sides; a crest on some.
    Beak,
    /// A broad, flat head with a wide mouth and eyes on top (a frog's, a salamander's); horns
    /// on some.
    Flat,
    /// A small skull with big eyes on the sides (a second, small pair on some), mandibles and
    /// antennae.
    Insect,
}

/// Every family, in the order they are drawn.
pub(crate) const FAMILIES: [Family; 5] = [
    Family::Round,
    Family::Snout,
    Family::Beak,
    Family::Flat,
    Family::Insect,
];

/// Segments around the skull and snout (the old head sphere's).
const SKULL_SEGMENTS: usize = 8;
/// Rings of the skull between its two tips.
const SKULL_RINGS: usize = 5;
/// Segments around an eye.
const EYE_SEGMENTS: usize = 8;
/// Segments around a mouth line (a flat lens: its sides show).
const LIP_SEGMENTS: usize = 6;
/// Segments around a horn, ear, mandible or antenna.
const HORN_SEGMENTS: usize = 5;

/// The sclera's colour: an off-white, light on any skin.
const SCLERA: Vec3 = Vec3::new(0.95, 0.93, 0.84);
/// The pupil's colour.
const PUPIL: Vec3 = Vec3::new(0.03, 0.03, 0.04);

/// A head's frame: its centre, and its forward, side and up directions (`side × up =
/// forward`, right-handed).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    pub(crate) centre: Vec3,
    pub(crate) forward: Vec3,
    pub(crate) side: Vec3,
    pub(crate) up: Vec3,
}

impl Frame {
    /// The frame at `centre` looking along `forward`, its up as near world up as it can be.
    pub(crate) fn new(centre: Vec3, forward: Vec3) -> Self {
        let forward = forward.normalize_or(Vec3::Z);
        let side = Vec3::Y.cross(forward).normalize_or(Vec3::X);
        let up = forward.cross(side);
        Self {
            centre,
            forward,
            side,
            up,
        }
    }

    /// The direction `(x, y, z)` in the frame (x to the side, y up, z forward).
    pub(crate) fn dir(&self, x: f32, y: f32, z: f32) -> Vec3 {
        self.side * x + self.up * y + self.forward * z
    }

    /// The point `(x, y, z)` of the frame.
    pub(crate) fn at(&self, x: f32, y: f32, z: f32) -> Vec3 {
        self.centre + self.dir(x, y, z)
    }
}

/// One ring of a tube: its centre and its half-extents along the tube's two cross axes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ring {
    pub(crate) centre: Vec3,
    pub(crate) rx: f32,
    pub(crate) ry: f32,
}

/// A closed tube: the `back` tip, `rings` (ellipses across `x` and `y`, with `x × y` pointing
/// toward `front`), the `front` tip, `segments` around.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tube<'a> {
    pub(crate) back: Vec3,
    pub(crate) rings: &'a [Ring],
    pub(crate) front: Vec3,
    pub(crate) x: Vec3,
    pub(crate) y: Vec3,
    pub(crate) segments: usize,
}

/// How a tube is coloured: `paint(band, up)` for a vertex facing `up` (its direction from its
/// ring's centre · the head's up) in band `band` (0 the back fan, `k` between rings `k − 1`
/// and `k`, `rings.len()` the front fan). `banded`: every band on vertices of its own, in one
/// colour each (the vertex's `up` is then the band's middle's); else the vertices are shared
/// and each ring takes the band it closes.
pub(crate) struct Paint<'a> {
    pub(crate) banded: bool,
    pub(crate) up: Vec3,
    pub(crate) paint: &'a dyn Fn(usize, f32) -> Vec3,
}

impl MeshBuilder {
    /// Adds `tube`, every vertex bound by `bind`.
    pub(crate) fn head_tube(&mut self, tube: Tube<'_>, paint: &Paint<'_>, bind: Bind) {
        let Tube {
            back,
            rings,
            front,
            x,
            y,
            segments,
        } = tube;
        let n = rings.len();
        if n == 0 || segments < 3 {
            return;
        }
        let angle = |j: usize| core::f32::consts::TAU * (j % segments) as f32 / segments as f32;
        let offset = |r: &Ring, j: usize| {
            let a = angle(j);
            x * (r.rx * cos(a)) + y * (r.ry * sin(a))
        };
        let facing = |d: Vec3| d.normalize_or_zero().dot(paint.up);
        let tip_up = |tip: Vec3, r: &Ring| facing(tip - r.centre);
        // Writes ring `r` (band `band`), returns its first vertex.
        let ring = |mesh: &mut Self, r: &Ring, band: usize, band_up: Option<f32>| {
            let first = mesh.positions.len() as u32;
            for j in 0..segments {
                let d = offset(r, j);
                let colour = (paint.paint)(band, band_up.unwrap_or_else(|| facing(d)));
                mesh.vertex(r.centre + d, colour, bind);
            }
            first
        };
        let v = |first: u32, j: usize| first + (j % segments) as u32;
        if paint.banded {
            let band_up = |a: Vec3, b: Vec3| facing(0.5 * (a + b) - (back + front) * 0.5);
            // Back fan.
            let up = band_up(back, rings[0].centre);
            let tip = self.vertex(back, (paint.paint)(0, up), bind);
            let first = ring(self, &rings[0], 0, Some(up));
            for j in 0..segments {
                self.indices.push([tip, v(first, j + 1), v(first, j)]);
            }
            for k in 1..n {
                let up = band_up(rings[k - 1].centre, rings[k].centre);
                let a = ring(self, &rings[k - 1], k, Some(up));
                let b = ring(self, &rings[k], k, Some(up));
                for j in 0..segments {
                    self.indices.push([v(a, j), v(a, j + 1), v(b, j + 1)]);
                    self.indices.push([v(a, j), v(b, j + 1), v(b, j)]);
                }
            }
            let up = band_up(rings[n - 1].centre, front);
            let last = ring(self, &rings[n - 1], n, Some(up));
            let tip = self.vertex(front, (paint.paint)(n, up), bind);
            for j in 0..segments {
                self.indices.push([tip, v(last, j), v(last, j + 1)]);
            }
        } else {
            let tip = self.vertex(back, (paint.paint)(0, tip_up(back, &rings[0])), bind);
            let firsts: Vec<u32> = rings
                .iter()
                .enumerate()
                .map(|(k, r)| ring(self, r, k + 1, None))
                .collect();
            let end = self.vertex(front, (paint.paint)(n, tip_up(front, &rings[n - 1])), bind);
            for j in 0..segments {
                self.indices
                    .push([tip, v(firsts[0], j + 1), v(firsts[0], j)]);
                self.indices
                    .push([end, v(firsts[n - 1], j), v(firsts[n - 1], j + 1)]);
            }
            for w in firsts.windows(2) {
                let (a, b) = (w[0], w[1]);
                for j in 0..segments {
                    self.indices.push([v(a, j), v(a, j + 1), v(b, j + 1)]);
                    self.indices.push([v(a, j), v(b, j + 1), v(b, j)]);
                }
            }
        }
    }
}

/// Two unit vectors square to `axis` and to each other, `x × y = axis`, `x` level when it can
/// be.
pub(crate) fn cross_axes(axis: Vec3) -> (Vec3, Vec3) {
    let axis = axis.normalize_or(Vec3::Z);
    let x = Vec3::Y.cross(axis).try_normalize().unwrap_or(Vec3::X);
    (x, axis.cross(x))
}

/// An eye on a surface at `point` with outward `normal`, its pupil looking along `gaze`:
/// radius `radius`, a dark `lid` rim, the sclera, a pupil `pupil` × the radius across.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Eye {
    pub(crate) point: Vec3,
    pub(crate) normal: Vec3,
    pub(crate) gaze: Vec3,
    pub(crate) radius: f32,
    pub(crate) pupil: f32,
}

impl Eye {
    /// The way the pupil faces: the normal turned toward the gaze.
    fn axis(&self) -> Vec3 {
        (self.normal + self.gaze).normalize_or(self.normal)
    }
}

/// Adds `eye`: a low dome sunk a little into the surface, rim, sclera and pupil in bands.
fn add_eye(mesh: &mut MeshBuilder, eye: Eye, lid: Vec3, up: Vec3, bind: Bind) {
    let axis = eye.axis();
    let (x, y) = cross_axes(axis);
    let r = eye.radius;
    let at = |h: f32| eye.point + axis * (h * r);
    let rings = [
        Ring {
            centre: at(-0.2),
            rx: r,
            ry: r,
        },
        Ring {
            centre: at(0.12),
            rx: 0.97 * r,
            ry: 0.97 * r,
        },
        Ring {
            centre: at(0.42),
            rx: eye.pupil * r,
            ry: eye.pupil * r,
        },
    ];
    let paint = |band: usize, _: f32| match band {
        0 | 1 => lid,
        2 => SCLERA,
        _ => PUPIL,
    };
    mesh.head_tube(
        Tube {
            back: at(-0.6),
            rings: &rings,
            front: at(0.52),
            x,
            y,
            segments: EYE_SEGMENTS,
        },
        &Paint {
            banded: true,
            up,
            paint: &paint,
        },
        bind,
    );
}

/// A cone from `base` (radius `radius`, sunk a little inside along `-axis`) to `base + axis`,
/// in one colour.
pub(crate) fn add_cone(
    mesh: &mut MeshBuilder,
    base: Vec3,
    axis: Vec3,
    radius: f32,
    colour: Vec3,
    bind: Bind,
) {
    if axis.length_squared() <= 1e-12 {
        // No length (an `ornament_size` of 0): nothing to add.
        return;
    }
    let (x, y) = cross_axes(axis);
    let dir = axis.normalize_or(Vec3::Y);
    let rings = [
        Ring {
            centre: base,
            rx: radius,
            ry: radius,
        },
        Ring {
            centre: base + axis * 0.5,
            rx: 0.55 * radius,
            ry: 0.55 * radius,
        },
    ];
    let paint = |_: usize, _: f32| colour;
    mesh.head_tube(
        Tube {
            back: base - dir * radius,
            rings: &rings,
            front: base + axis,
            x,
            y,
            segments: HORN_SEGMENTS,
        },
        &Paint {
            banded: false,
            up: Vec3::Y,
            paint: &paint,
        },
        bind,
    );
}

/// The head's random shape, drawn from its own generator.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Shape {
    pub(crate) family: Family,
    /// The skull's half-extents × the head radius: across, up, along.
    skull: Vec3,
    /// Snout or beak length × the head radius.
    snout: f32,
    /// Eye radius × the head radius.
    eye: f32,
    /// Ears, horns, crest, mandibles: length × the head radius (antennae twice).
    ornament: f32,
    /// Whether the optional ornament (ears, horns, crest, the insect's second pair of eyes)
    /// is there.
    extra: bool,
    /// A second draw for details: which horn colour, ears or horns.
    detail: f32,
}

impl Shape {
    /// Draws a head from `rng`: a family, then its proportions within `params`' ranges.
    pub(crate) fn draw(rng: &mut impl Rng, params: &Params) -> Self {
        let pick = (uniform(rng) * FAMILIES.len() as f32) as usize;
        let family = FAMILIES[pick.min(FAMILIES.len() - 1)];
        let jitter = uniform(rng);
        let skull = match family {
            Family::Round => Vec3::new(1.0, 0.95, 0.95),
            Family::Snout => Vec3::new(0.85, 0.85, 0.9),
            Family::Beak => Vec3::new(0.9, 0.95, 0.9),
            Family::Flat => Vec3::new(1.25, 0.6, 0.95),
            Family::Insect => Vec3::new(0.85, 0.8, 0.8),
        } * (0.92 + 0.16 * jitter);
        Self {
            family,
            skull,
            snout: params.snout_length.at(uniform(rng)),
            eye: params.eye_size.at(uniform(rng)),
            ornament: params.ornament_size.at(uniform(rng)),
            extra: uniform(rng) < params.ornament_chance,
            detail: uniform(rng),
        }
    }

    /// The skull's half-width × the head radius.
    pub(crate) fn across(&self) -> f32 {
        self.skull.x
    }
}

/// Where a head goes: the neck tip, the direction the neck points, the head radius (half the
/// body width there × the head size), and the joint it is bound to.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mount {
    pub(crate) tip: Vec3,
    pub(crate) forward: Vec3,
    pub(crate) radius: f32,
    pub(crate) joint: u16,
}

/// What a built head reports: its frame, its skull's half-extents (across, up, along the
/// frame; a swimmer's face has no skull of its own, zero) and its eyes.
#[derive(Debug, Clone)]
pub(crate) struct Built {
    pub(crate) frame: Frame,
    pub(crate) skull: Vec3,
    pub(crate) eyes: Vec<Eye>,
}

impl Built {
    /// Whether `p` is inside the skull.
    pub(crate) fn in_skull(&self, p: Vec3) -> bool {
        let d = p - self.frame.centre;
        let q = Vec3::new(
            d.dot(self.frame.side),
            d.dot(self.frame.up),
            d.dot(self.frame.forward),
        ) / self.skull.max(Vec3::splat(f32::MIN_POSITIVE));
        q.length_squared() < 1.0
    }

    /// How many eyes face the front or a side view: their pupils (see [`Eye::axis`]) more
    /// than a little toward the front (`+z`, where the previews' front view looks from) or
    /// mostly toward a side.
    pub(crate) fn eyes_in_view(&self) -> u32 {
        let facing = |e: &&Eye| {
            let axis = e.axis();
            axis.z > 0.3 || axis.dot(self.frame.side).abs() > 0.5
        };
        self.eyes.iter().filter(facing).count() as u32
    }
}

/// Builds the head of `shape` on `mount`: the skull overlapping the neck tip (its back inside
/// the neck), snout or beak, the mouth line, eyes and ornaments, all bound to `mount.joint`.
pub(crate) fn add_head(
    mesh: &mut MeshBuilder,
    mount: Mount,
    shape: &Shape,
    colouring: &Colouring,
) -> Built {
    let r = mount.radius;
    let s = shape.skull * r;
    // The skull's back three-quarters of its half-length inside the neck.
    let frame = Frame::new(mount.tip, mount.forward);
    let frame = Frame {
        centre: mount.tip + frame.forward * (0.25 * s.z),
        ..frame
    };
    let bind = Bind::one(mount.joint);
    let skin = |_: usize, up: f32| colouring.head(up);
    let base = colouring.palette.base;
    let lid = base * 0.4;
    let mouth = base * 0.22;

    // The skull, an ellipsoid.
    let rings: Vec<Ring> = (0..SKULL_RINGS)
        .map(|i| {
            let phi = core::f32::consts::PI * (i + 1) as f32 / (SKULL_RINGS + 1) as f32;
            Ring {
                centre: frame.at(0.0, 0.0, -cos(phi) * s.z),
                rx: sin(phi) * s.x,
                ry: sin(phi) * s.y,
            }
        })
        .collect();
    along(
        mesh,
        &frame,
        (
            [frame.at(0.0, 0.0, -s.z), frame.at(0.0, 0.0, s.z)],
            SKULL_SEGMENTS,
        ),
        &rings,
        &skin,
        bind,
    );

    let snout_length = shape.snout * r;
    match shape.family {
        Family::Snout => {
            // A tapering snout from inside the skull, lowered, its mouth line on both sides.
            let (z0, y0) = (0.2 * s.z, -0.25 * s.y);
            let ring = |t: f32, scale: f32| Ring {
                centre: frame.at(0.0, y0 - 0.15 * s.y * t, z0 + (s.z - z0 + snout_length) * t),
                rx: 0.62 * s.x * scale,
                ry: 0.55 * s.y * scale,
            };
            let rings = [ring(0.0, 1.0), ring(0.5, 0.8), ring(0.9, 0.62)];
            let tip = rings[2].centre + frame.forward * (0.5 * rings[2].ry);
            // The mouth a third of the way down the snout, on both sides.
            let muzzle = Muzzle {
                back: frame.at(0.0, y0, z0 - 0.5 * s.z),
                rings: &rings,
                tip,
                drop: 0.3,
                widen: 1.04,
                thickness: 0.06 * r,
            };
            muzzle.add(mesh, &frame, &skin, mouth, bind);
        }
        Family::Beak => {
            // A cone from inside the skull, its tip hooked down, in a horn colour.
            let colour = [
                Vec3::new(0.93, 0.7, 0.2),
                Vec3::new(0.3, 0.27, 0.25),
                Vec3::new(0.88, 0.82, 0.66),
            ][((shape.detail * 3.0) as usize).min(2)];
            let length = 0.8 * snout_length;
            let (z0, y0) = (0.45 * s.z, -0.12 * s.y);
            let rings = [
                Ring {
                    centre: frame.at(0.0, y0, z0),
                    rx: 0.5 * s.x,
                    ry: 0.42 * s.y,
                },
                Ring {
                    centre: frame.at(0.0, y0 - 0.05 * length, s.z + 0.45 * length),
                    rx: 0.25 * s.x,
                    ry: 0.22 * s.y,
                },
            ];
            let tip = frame.at(0.0, y0 - 0.25 * length, s.z + length);
            let paint = |_: usize, up: f32| colour * (0.9 + 0.1 * up);
            // The mouth along the beak's middle.
            let muzzle = Muzzle {
                back: frame.at(0.0, y0, z0 - 0.4 * s.z),
                rings: &rings,
                tip,
                drop: 0.0,
                widen: 1.04,
                thickness: 0.04 * r,
            };
            muzzle.add(mesh, &frame, &paint, mouth, bind);
        }
        _ => {
            // A mouth line across the skull's lower front.
            let low = match shape.family {
                Family::Flat => -0.2,
                Family::Insect => -0.45,
                _ => -0.4,
            };
            let lips = Lips {
                low,
                bulge: 1.05,
                from: 0.05,
                thickness: 0.05 * r,
                colour: mouth,
            };
            lips.on_ellipsoid(mesh, &frame, s, bind);
        }
    }

    // Eyes: a direction in the frame per family (x to the side, mirrored), placed on the skull.
    let (eye_dir, gaze, pupil) = match shape.family {
        Family::Round => (Vec3::new(0.48, 0.32, 0.82), 0.6, 0.5),
        Family::Snout => (Vec3::new(0.72, 0.5, 0.5), 0.3, 0.5),
        Family::Beak => (Vec3::new(0.8, 0.35, 0.5), 0.2, 0.55),
        Family::Flat => (Vec3::new(0.95, 0.22, 0.35), 0.3, 0.5),
        Family::Insect => (Vec3::new(0.85, 0.2, 0.45), 0.2, 0.7),
    };
    let mut eyes = Vec::new();
    let mut pair = |dir: Vec3, radius: f32, pupil: f32| {
        for sign in [1.0f32, -1.0] {
            let d = Vec3::new(sign * dir.x, dir.y, dir.z);
            let mut eye = on_skull(&frame, s, d, radius, pupil, gaze);
            if shape.family == Family::Flat {
                // A frog's eyes bulge out of its flat head.
                eye.point += eye.normal * (0.35 * radius);
            }
            add_eye(mesh, eye, lid, frame.up, bind);
            eyes.push(eye);
        }
    };
    pair(eye_dir, shape.eye * r, pupil);
    if shape.family == Family::Insect && shape.extra {
        pair(Vec3::new(0.3, 0.6, 0.75), 0.5 * shape.eye * r, 0.6);
    }

    // Ornaments.
    let length = shape.ornament * r;
    let accent = colouring.palette.accent;
    let horn = if shape.detail < 0.5 {
        Vec3::new(0.86, 0.8, 0.64)
    } else {
        Vec3::new(0.26, 0.22, 0.2)
    };
    for sign in [1.0f32, -1.0] {
        let place = |x: f32, y: f32, z: f32| {
            // On the skull (a unit direction scaled by its half-extents), sunk a little.
            let d = Vec3::new(sign * x, y, z).normalize_or(Vec3::Y);
            frame.at(0.9 * d.x * s.x, 0.9 * d.y * s.y, 0.9 * d.z * s.z)
        };
        match shape.family {
            Family::Round | Family::Snout if shape.extra && shape.detail < 0.6 => {
                // Ears, up and out.
                let base = place(0.55, 0.8, -0.25);
                let axis = frame.dir(sign * 0.45, 1.0, -0.2).normalize_or(frame.up) * length;
                add_cone(mesh, base, axis, 0.32 * r, base_skin(colouring), bind);
            }
            Family::Snout | Family::Flat if shape.extra => {
                // Horns, up, out and back.
                let base = place(0.45, 0.85, 0.1);
                let axis = frame.dir(sign * 0.5, 1.0, -0.35).normalize_or(frame.up) * length;
                add_cone(mesh, base, axis, 0.16 * r, horn, bind);
            }
            Family::Beak if shape.extra && sign > 0.0 => {
                // A crest of three feathers along the top.
                for (k, z) in [0.25f32, -0.05, -0.35].into_iter().enumerate() {
                    let base = frame.at(0.0, 0.85 * s.y * sqrt(1.0 - z * z), z * s.z);
                    let tilt = frame
                        .dir(0.0, 1.0, -0.5 - 0.3 * k as f32)
                        .normalize_or(frame.up);
                    add_cone(
                        mesh,
                        base,
                        tilt * (length * (1.0 - 0.2 * k as f32)),
                        0.1 * r,
                        accent,
                        bind,
                    );
                }
            }
            Family::Insect => {
                // Mandibles, forward and in, and antennae, up and forward.
                let base = frame.at(sign * 0.35 * s.x, -0.55 * s.y, 0.7 * s.z);
                let axis = frame
                    .dir(-sign * 0.35, -0.15, 1.0)
                    .normalize_or(frame.forward);
                add_cone(mesh, base, axis * (0.6 * length), 0.14 * r, lid, bind);
                let base = place(0.3, 0.75, 0.55);
                let axis = frame.dir(sign * 0.35, 1.0, 0.7).normalize_or(frame.up);
                add_cone(mesh, base, axis * (2.0 * length), 0.06 * r, lid, bind);
            }
            _ => {}
        }
    }
    Built {
        frame,
        skull: s,
        eyes,
    }
}

/// The skin colour of ears: the head's on its flank.
fn base_skin(colouring: &Colouring) -> Vec3 {
    colouring.head(0.3)
}

/// The eye on the skull of half-extents `s` in `frame` in direction `d` (frame coordinates):
/// the point where the ray from the centre meets the skull, its outward normal, a gaze turned
/// `gaze` toward the front.
fn on_skull(frame: &Frame, s: Vec3, d: Vec3, radius: f32, pupil: f32, gaze: f32) -> Eye {
    let d = d.normalize_or(Vec3::Z);
    let q = Vec3::new(d.x / s.x, d.y / s.y, d.z / s.z);
    let t = 1.0 / sqrt(q.dot(q).max(1e-12));
    let p = d * t;
    let n = Vec3::new(p.x / (s.x * s.x), p.y / (s.y * s.y), p.z / (s.z * s.z));
    let normal = frame.dir(n.x, n.y, n.z).normalize_or(frame.forward);
    Eye {
        point: frame.at(p.x, p.y, p.z),
        normal,
        gaze: frame.forward * gaze,
        radius,
        pupil,
    }
}

/// A closed tube along the head (its rings across `frame`'s side and up) from `ends[0]` to
/// `ends[1]`, `segments` around, vertices shared, coloured by `paint(band, up)` (see [`Paint`]).
fn along(
    mesh: &mut MeshBuilder,
    frame: &Frame,
    (ends, segments): ([Vec3; 2], usize),
    rings: &[Ring],
    paint: &dyn Fn(usize, f32) -> Vec3,
    bind: Bind,
) {
    let tube = Tube {
        back: ends[0],
        rings,
        front: ends[1],
        x: frame.side,
        y: frame.up,
        segments,
    };
    let paint = Paint {
        banded: false,
        up: frame.up,
        paint,
    };
    mesh.head_tube(tube, &paint, bind);
}

/// A snout or a beak along the head: a tube from `back` through `rings` to `tip`, and a mouth
/// line along it, `drop` × each ring's half-height below its centre, `widen` × as wide as the
/// ring's ellipse there (a little over 1 to show), `thickness` high.
struct Muzzle<'a> {
    back: Vec3,
    rings: &'a [Ring],
    tip: Vec3,
    drop: f32,
    widen: f32,
    thickness: f32,
}

impl Muzzle<'_> {
    /// Adds the muzzle coloured by `paint` (see [`Paint`]) and its mouth line in `mouth`.
    fn add(
        &self,
        mesh: &mut MeshBuilder,
        frame: &Frame,
        paint: &dyn Fn(usize, f32) -> Vec3,
        mouth: Vec3,
        bind: Bind,
    ) {
        let ends = ([self.back, self.tip], SKULL_SEGMENTS);
        along(mesh, frame, ends, self.rings, paint, bind);
        // The ellipse's half-width at `drop` below its middle, widened.
        let across = self.widen * sqrt((1.0 - self.drop * self.drop).max(0.0));
        let lips: Vec<Ring> = self
            .rings
            .iter()
            .map(|q| Ring {
                centre: q.centre - frame.up * (self.drop * q.ry),
                rx: across * q.rx,
                ry: self.thickness,
            })
            .collect();
        let last = self.rings.last().map_or(0.0, |q| q.ry);
        let front = self.tip - frame.up * (self.drop * last);
        add_lips(mesh, frame, &lips, front, mouth, bind);
    }
}

/// A mouth line: a flat dark tube through `rings` (across the head's side and up), closed at
/// `front`, its back tip inside the head.
fn add_lips(
    mesh: &mut MeshBuilder,
    frame: &Frame,
    rings: &[Ring],
    front: Vec3,
    colour: Vec3,
    bind: Bind,
) {
    let Some(first) = rings.first() else {
        return;
    };
    let paint = |_: usize, _: f32| colour;
    along(
        mesh,
        frame,
        (
            [first.centre - frame.forward * (0.3 * first.rx), front],
            LIP_SEGMENTS,
        ),
        rings,
        &paint,
        bind,
    );
}

/// Where a swimmer's face goes: the body's front `tip`, the `forward` direction, and the body's
/// cross-section `behind` it (its ring's centre and half-extents across and up).
#[derive(Debug, Clone, Copy)]
pub(crate) struct FishFront {
    pub(crate) tip: Vec3,
    pub(crate) forward: Vec3,
    pub(crate) ring_centre: Vec3,
    pub(crate) half_width: f32,
    pub(crate) half_height: f32,
    /// Where up the sides the eyes sit: the cosine and sine of their angle on the ellipse.
    pub(crate) eyes_at: (f32, f32),
}

/// A swimmer's face on the body's front: a pair of eyes on the sides of the ring behind the
/// tip and a mouth line across the tip, each bound like the body vertex nearest it (`bind_at`).
pub(crate) fn add_fish_face(
    mesh: &mut MeshBuilder,
    front: FishFront,
    shape: &Shape,
    colouring: &Colouring,
    bind_at: impl Fn(Vec3) -> Bind,
) -> Built {
    let frame = Frame::new(front.ring_centre, front.forward);
    let (w, h) = (front.half_width.max(1e-4), front.half_height.max(1e-4));
    let size = w.min(h);
    let base = colouring.palette.base;
    let mut eyes = Vec::new();
    // Eyes up the side of the ellipse (a fish's a third of the way; its normal there, facing
    // out).
    let (c, s) = front.eyes_at;
    for sign in [1.0f32, -1.0] {
        let point = frame.at(sign * w * c, h * s, 0.0);
        let normal = frame
            .dir(sign * c / w, s / h, 0.0)
            .normalize_or(frame.side * sign);
        let eye = Eye {
            point,
            normal,
            gaze: frame.forward * 0.25,
            radius: shape.eye * 1.15 * h,
            pupil: 0.55,
        };
        add_eye(mesh, eye, base * 0.4, frame.up, bind_at(point));
        eyes.push(eye);
    }
    // The mouth: a line across the nose, a little below the middle, the nose taken for half
    // an ellipsoid from the ring to the tip.
    let depth = (front.tip - front.ring_centre).dot(frame.forward).max(1e-4);
    let lips = Lips {
        low: -0.22,
        bulge: 1.2,
        from: 0.2,
        thickness: 0.08 * size,
        colour: base * 0.22,
    };
    let mouth_at = frame.at(0.0, -0.22 * h, depth);
    lips.on_ellipsoid(mesh, &frame, Vec3::new(w, h, depth), bind_at(mouth_at));
    Built {
        frame,
        skull: Vec3::ZERO,
        eyes,
    }
}

/// A mouth line on an ellipsoid: a thin dark lens `bulge` × as wide as the ellipsoid at height
/// `low` × its half-height, from `from` × its half-length in front of its centre to its front.
struct Lips {
    low: f32,
    bulge: f32,
    from: f32,
    thickness: f32,
    colour: Vec3,
}

impl Lips {
    /// Adds the line on the ellipsoid of half-extents `s` (across, up, along) at `frame`'s
    /// centre.
    fn on_ellipsoid(&self, mesh: &mut MeshBuilder, frame: &Frame, s: Vec3, bind: Bind) {
        let low = self.low.clamp(-0.95, 0.95);
        let y = low * s.y;
        let z_max = s.z * sqrt(1.0 - low * low);
        let rings: Vec<Ring> = [0.0f32, 0.55, 0.88]
            .iter()
            .map(|&t| {
                let z = z_max * (self.from + (1.0 - self.from) * t);
                let half = sqrt((1.0 - low * low - (z / s.z) * (z / s.z)).max(0.0));
                Ring {
                    centre: frame.at(0.0, y, z),
                    rx: self.bulge * s.x * half,
                    ry: self.thickness,
                }
            })
            .collect();
        add_lips(
            mesh,
            frame,
            &rings,
            frame.at(0.0, y, 1.04 * z_max),
            self.colour,
            bind,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::rng_for;

    fn colouring(seed: u64) -> Colouring {
        Colouring::draw(&mut rng_for(seed), &Params::DEFAULT.colours(), 1)
    }

    /// A head of `family` (ornaments on) on a neck tip at `(0, 1, 1)` pointing forward and a
    /// little up, bound to joint 3.
    fn head(family: Family, seed: u64) -> (MeshBuilder, Built, Mount) {
        let mut shape = Shape::draw(&mut rng_for(seed), &Params::DEFAULT);
        shape.family = family;
        shape.extra = true;
        let mount = Mount {
            tip: Vec3::new(0.0, 1.0, 1.0),
            forward: Vec3::new(0.0, 0.3, 1.0).normalize(),
            radius: 0.2,
            joint: 3,
        };
        let mut mesh = MeshBuilder::default();
        let built = add_head(&mut mesh, mount, &shape, &colouring(seed));
        (mesh, built, mount)
    }

    #[test]
    fn every_family_is_drawn() {
        let mut seen = [false; FAMILIES.len()];
        for seed in 0..64 {
            let shape = Shape::draw(&mut rng_for(seed), &Params::DEFAULT);
            let i = FAMILIES.iter().position(|&f| f == shape.family);
            seen[i.expect("a family of the table")] = true;
        }
        assert_eq!(seen, [true; FAMILIES.len()]);
    }

    #[test]
    fn eyes_are_a_symmetric_pair_on_the_skull_facing_out() {
        for (k, &family) in FAMILIES.iter().enumerate() {
            let (_, built, _) = head(family, k as u64);
            let f = built.frame;
            let expected = if family == Family::Insect { 4 } else { 2 };
            assert_eq!(built.eyes.len(), expected, "{family:?}");
            for pair in built.eyes.chunks(2) {
                let [a, b] = [pair[0], pair[1]].map(|e| e.point - f.centre);
                // Mirror images across the midline plane (side = 0).
                assert!((a.dot(f.side) + b.dot(f.side)).abs() < 1e-5, "{family:?}");
                assert!(a.dot(f.side).abs() > 0.01, "{family:?}: apart");
                assert!((a.dot(f.up) - b.dot(f.up)).abs() < 1e-5, "{family:?}");
                assert!(
                    (a.dot(f.forward) - b.dot(f.forward)).abs() < 1e-5,
                    "{family:?}"
                );
            }
            for e in &built.eyes {
                // On the outside, facing out, and toward the front or a side view.
                assert!(e.normal.dot(e.point - f.centre) > 0.0, "{family:?}");
                let (front, side) = (e.normal.dot(f.forward), e.normal.dot(f.side).abs());
                assert!(front > 0.2 || side > 0.5, "{family:?}: {front} {side}");
                assert!(e.radius > 0.0 && e.pupil > 0.0 && e.pupil < 1.0);
            }
        }
    }

    #[test]
    fn the_head_is_rigid_on_its_joint_and_its_eyes_contrast() {
        for (k, &family) in FAMILIES.iter().enumerate() {
            let (mesh, built, mount) = head(family, 10 + k as u64);
            let n = mesh.positions.len();
            assert!(n > 0);
            assert!(mesh.positions.iter().all(|p| p.is_finite()));
            assert!(mesh.indices.iter().flatten().all(|&i| (i as usize) < n));
            assert!(mesh.joints.iter().all(|j| j[0] == mount.joint));
            assert!(mesh.weights.iter().all(|w| *w == [1.0, 0.0, 0.0, 0.0]));
            // Sclera and pupil present, far apart in lightness.
            assert!(mesh.colours.contains(&SCLERA) && mesh.colours.contains(&PUPIL));
            // The skull's back sits inside the neck, behind the tip: no ball on a stick.
            let behind = mesh
                .positions
                .iter()
                .map(|p| (*p - mount.tip).dot(built.frame.forward))
                .fold(f32::INFINITY, f32::min);
            assert!(behind < -0.3 * mount.radius, "{family:?}: {behind}");
            // Every triangle has an area (no degenerate bands).
            for t in &mesh.indices {
                let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
                assert!((b - a).cross(c - a).length() > 1e-10, "{family:?}");
            }
        }
    }

    #[test]
    fn a_fish_face_sits_on_the_front() {
        let shape = Shape::draw(&mut rng_for(5), &Params::DEFAULT);
        let front = FishFront {
            tip: Vec3::new(0.0, 0.5, 2.0),
            forward: Vec3::Z,
            ring_centre: Vec3::new(0.0, 0.5, 1.7),
            half_width: 0.15,
            half_height: 0.3,
            eyes_at: (0.8, 0.6),
        };
        let mut mesh = MeshBuilder::default();
        let built = add_fish_face(&mut mesh, front, &shape, &colouring(5), |_| Bind::one(7));
        assert_eq!(built.eyes.len(), 2);
        let [a, b] = [built.eyes[0].point, built.eyes[1].point];
        assert!((a.x + b.x).abs() < 1e-6 && (a.y - b.y).abs() < 1e-6);
        for e in &built.eyes {
            assert!(e.normal.x.abs() > 0.5, "a fish's eyes look to the sides");
        }
        assert!(mesh.joints.iter().all(|j| j[0] == 7));
        assert!(mesh.positions.iter().all(|p| p.is_finite() && p.z < 2.2));
    }
}
