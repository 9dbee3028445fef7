//! Wings by kind: a flier's flapping wings are feathered (coverts, flight feathers with
//! serrated, dark-tipped ends) or a bat's membrane stretched between finger bones and scalloped
//! between their tips, drawn per creature by [`WingWeights`]; buzzing wings are an insect's
//! pale membrane with dark veins.
//!
//! A wing is a flat, two-sided surface (a [`Planform`]) laid out in unit coordinates: `t` along
//! the wing (0 its root, 1 its tip) and `s` across it (× its width, positive toward the leading
//! edge). Chord lines run from the leading edge back; each band between two points of a chord
//! and each panel between two chord lines has a [`Tone`], so a finger or a vein is a crisp
//! strip of panels on vertices of its own. A vertex is skinned to the two chain joints around
//! its `t`, so the wing bends smoothly as the chain flaps.

use alloc::vec::Vec;
use core::f32::consts::{FRAC_PI_2, PI};

use glam::{Vec2, Vec3};

use super::limbs::{Bind, MeshBuilder};
use crate::Error;
use crate::math::{asin, sin, sqrt};

/// What a flier's flapping wings are made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum WingKind {
    /// A bird's: coverts in the body's colour over the front, flight feathers behind, their
    /// serrated ends tipped in a contrasting shade.
    Feathered,
    /// A bat's: a membrane stretched between three finger bones fanning from the wrist,
    /// scalloped between the fingers' tips, with a dark arm along the leading edge.
    Bat,
}

impl WingKind {
    /// Every kind, in the order [`WingWeights`] draws them.
    pub const ALL: [Self; 2] = [Self::Feathered, Self::Bat];
}

/// Relative weights of the [`WingKind`]s a flier with flapping wings draws from: kind `k` is
/// drawn with probability `weight(k) / sum of weights`. Each from 0 to 1000, at least one above
/// 0. (Buzzing wings are always an insect's membrane.)
///
/// ```
/// use creature::d3::{Params, WingKind, WingWeights};
///
/// // Only bat wings.
/// let params = Params::DEFAULT.with_wing_kinds(WingWeights::only(WingKind::Bat));
/// params.validate()?;
/// assert_eq!(WingWeights::DEFAULT.weight(WingKind::Feathered), 1.0);
/// # Ok::<(), creature::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct WingWeights {
    /// Weight of [`WingKind::Feathered`]. Default 1.
    pub feathered: f32,
    /// Weight of [`WingKind::Bat`]. Default 1.
    pub bat: f32,
}

impl WingWeights {
    /// The defaults listed on each field: feathered and bat wings alike.
    pub const DEFAULT: Self = Self {
        feathered: 1.0,
        bat: 1.0,
    };

    /// Weight 1 for `kind`, 0 for the others: every flapping wing is `kind`.
    #[must_use]
    pub const fn only(kind: WingKind) -> Self {
        let none = Self {
            feathered: 0.0,
            bat: 0.0,
        };
        none.with(kind, 1.0)
    }

    /// Sets the weight of `kind`.
    #[must_use]
    pub const fn with(mut self, kind: WingKind, weight: f32) -> Self {
        match kind {
            WingKind::Feathered => self.feathered = weight,
            WingKind::Bat => self.bat = weight,
        }
        self
    }

    /// The weight of `kind`.
    #[must_use]
    pub const fn weight(&self, kind: WingKind) -> f32 {
        match kind {
            WingKind::Feathered => self.feathered,
            WingKind::Bat => self.bat,
        }
    }

    /// Checks every weight is finite and from 0 to 1000, and one is above 0.
    pub(crate) fn check(&self, what: &'static str) -> Result<(), Error> {
        crate::rng::check_weights(what, &WingKind::ALL.map(|k| self.weight(k)))
    }

    /// The kind at `u` in `[0, 1)` of the weights' cumulative sum.
    pub(crate) fn pick(&self, u: f32) -> WingKind {
        let weights = WingKind::ALL.map(|k| self.weight(k));
        WingKind::ALL[crate::rng::pick_weighted(&weights, u)]
    }
}

impl Default for WingWeights {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// How a wing's panel is coloured, from the membrane colour where it is (see
/// [`Colouring::wing_tone`](super::colour::Colouring::wing_tone)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Tone {
    /// The membrane's colour.
    Skin,
    /// A bone or vein: a strong shade of it.
    Bone,
    /// An insect's membrane: pale.
    Pale,
    /// Coverts: toward the body's colour.
    Covert,
    /// Feathers' tips: a contrasting shade.
    Tip,
}

/// The most points a chord line has (a planform's bands plus one).
const MAX_POINTS: usize = 5;

/// A wing's flat outline and its tones in unit coordinates (see the module's docs).
#[derive(Debug, Clone)]
pub(crate) struct Planform {
    /// Chord lines from the root to the tip, each `points` points `(t, s)` from the leading
    /// edge back.
    chords: Vec<[Vec2; MAX_POINTS]>,
    points: usize,
    /// Per panel (between chord `k` and `k + 1`) and band, its tone.
    tones: Vec<[Tone; MAX_POINTS - 1]>,
}

impl Planform {
    fn new(bands: usize) -> Self {
        debug_assert!((1..MAX_POINTS).contains(&bands));
        Self {
            chords: Vec::new(),
            points: bands + 1,
            tones: Vec::new(),
        }
    }

    /// Adds a chord line from `(t_lead, s_lead)` to `(t_trail, s_trail)` with points at the
    /// fractions `splits` of the way back (the first 0, the last 1), and the tones of the panel
    /// from the line before to it.
    fn push(&mut self, lead: Vec2, trail: Vec2, splits: &[f32], tones: &[Tone]) {
        let mut line = [Vec2::ZERO; MAX_POINTS];
        for (p, &f) in line.iter_mut().zip(splits) {
            *p = lead.lerp(trail, f);
        }
        if !self.chords.is_empty() {
            let mut row = [Tone::Skin; MAX_POINTS - 1];
            for (r, &t) in row.iter_mut().zip(tones) {
                *r = t;
            }
            self.tones.push(row);
        }
        self.chords.push(line);
    }

    /// The outline's area in unit coordinates: a wing `length` long and `width` wide covers
    /// `length × width ×` this (one face).
    pub(crate) fn area(&self) -> f32 {
        let mut area = 0.0;
        for pair in self.chords.windows(2) {
            for b in 0..self.points - 1 {
                let [a, c] = [pair[0][b], pair[1][b + 1]];
                let (b0, d) = (pair[0][b + 1], pair[1][b]);
                // A quad's area: half the cross product of its diagonals.
                area += 0.5 * (c - a).perp_dot(d - b0).abs();
            }
        }
        area
    }

    /// Its chord lines (tests).
    #[cfg(test)]
    pub(crate) fn chords(&self) -> impl Iterator<Item = &[Vec2]> {
        self.chords.iter().map(|c| &c[..self.points])
    }

    /// The panels in `tone` (tests): their count.
    #[cfg(test)]
    pub(crate) fn panels_in(&self, tone: Tone) -> usize {
        self.tones
            .iter()
            .map(|row| {
                row[..self.points - 1]
                    .iter()
                    .filter(|&&t| t == tone)
                    .count()
            })
            .sum()
    }
}

/// A feathered wing: coverts over the front 45% of the chord, flight feathers behind them
/// with tips in a contrasting shade over the last quarter; eight short secondaries along the
/// inner 55% and five long primaries out to the tip, each with a blunt end reaching back past
/// the notches on either side (the primaries' notches deep, so they spread like fingers).
pub(crate) fn feathered() -> Planform {
    const SPLITS: [f32; 4] = [0.0, 0.45, 0.75, 1.0];
    const TONES: [Tone; 3] = [Tone::Covert, Tone::Skin, Tone::Tip];
    // Feathers: (from, to, count, how far a tip reaches back, how far a notch comes in).
    const GROUPS: [(f32, f32, usize, f32, f32); 2] =
        [(0.0, 0.55, 8, 0.04, 0.0), (0.55, 1.0, 5, 0.2, 0.05)];
    // A feather's end: from a third of the way along it to two thirds.
    const END: [f32; 2] = [0.3, 0.7];
    let lead = |t: f32| 0.42 - 0.36 * t * t * t * t;
    let trail = |t: f32| -0.5 + 0.34 * t;
    let mut p = Planform::new(3);
    let mut line = |t: f32, back: f32| {
        p.push(
            Vec2::new(t, lead(t)),
            Vec2::new(t, trail(t) - back),
            &SPLITS,
            &TONES,
        );
    };
    line(0.0, 0.0);
    for (from, to, count, reach, notch) in GROUPS {
        let step = (to - from) / count as f32;
        for k in 0..count {
            for f in END {
                line(from + step * (k as f32 + f), reach);
            }
            // The group's last notch exactly at its end (the tip's at 1).
            let t = if k + 1 == count {
                to
            } else {
                from + step * (k as f32 + 1.0)
            };
            line(t, if t < 1.0 { -notch } else { 0.0 });
        }
    }
    p
}

/// A bat's wing: the arm along the leading edge to the wrist at 40% of the length, three
/// fingers fanning from the wrist to the trailing edge, the leading finger on to the tip, and
/// the membrane scalloped between the fingers' tips.
pub(crate) fn bat() -> Planform {
    const SPLITS: [f32; 3] = [0.0, 0.08, 1.0];
    const TONES: [Tone; 2] = [Tone::Bone, Tone::Skin];
    const BONE: [Tone; 2] = [Tone::Bone, Tone::Bone];
    // Half a finger's breadth, along.
    const FINGER: f32 = 0.012;
    // Panels between two fingers.
    const SAMPLES: usize = 5;
    let lead = |t: f32| 0.3 + 0.08 * sin(PI * t) - 0.24 * t * t * t;
    let trail = |t: f32| -0.62 + 0.6 * t;
    // Finger lines and the root's and the tip's: (t at the leading edge, t at the trailing).
    let lines = [
        (0.0, 0.0),
        (0.4, 0.45),
        (0.43, 0.7),
        (0.46, 0.9),
        (1.0, 1.0),
    ];
    let mut p = Planform::new(2);
    let line = |p: &mut Planform, tl: f32, tt: f32, inward: f32, tones: &[Tone]| {
        p.push(
            Vec2::new(tl, lead(tl)),
            Vec2::new(tt, trail(tt) + inward),
            &SPLITS,
            tones,
        );
    };
    line(&mut p, 0.0, 0.0, 0.0, &TONES);
    for pair in lines.windows(2) {
        let ((l0, t0), (l1, t1)) = (pair[0], pair[1]);
        let last = l1 >= 1.0;
        // From past this line's finger (the root has none) to before the next one's (the
        // tip's line is the leading finger's end, the chord there narrow).
        let (l0, t0) = if l0 > 0.0 {
            (l0 + FINGER, t0 + FINGER)
        } else {
            (l0, t0)
        };
        let (l1e, t1e) = if last {
            (1.0, 1.0)
        } else {
            (l1 - FINGER, t1 - FINGER)
        };
        let depth = 0.45 * (t1e - t0);
        for k in 1..=SAMPLES {
            let u = k as f32 / SAMPLES as f32;
            let (tl, tt) = (l0 + (l1e - l0) * u, t0 + (t1e - t0) * u);
            // The trailing edge scallops in between the fingers; at the tip it meets the lead.
            let inward = if last {
                (lead(tt) - 0.04 - trail(tt)) * u * u
            } else {
                depth * sin(PI * u)
            };
            line(&mut p, tl, tt, inward, &TONES);
        }
        if !last {
            // The finger: a strip of bone from its leading end to its trailing one.
            line(&mut p, l1 + FINGER, t1 + FINGER, 0.0, &BONE);
        }
    }
    p
}

/// An insect's wing: a rounded blade, pale, with a dark vein along the leading edge (the
/// costa), one along the middle and three veins across.
pub(crate) fn insect() -> Planform {
    const SPLITS: [f32; 5] = [0.0, 0.08, 0.46, 0.52, 1.0];
    const TONES: [Tone; 4] = [Tone::Bone, Tone::Pale, Tone::Bone, Tone::Pale];
    const BONE: [Tone; 4] = [Tone::Bone; 4];
    // Chord lines round the outline, and the veins across (their middles and half-breadth).
    const SAMPLES: usize = 10;
    const VEINS: [f32; 3] = [0.3, 0.55, 0.78];
    const VEIN: f32 = 0.01;
    // An ellipse's half from t = 0 through its widest (0.45) to the tip, chord 1 at most.
    let (centre, half) = (0.45, 0.55);
    let chord = |t: f32| {
        let x = ((t - centre) / half).clamp(-1.0, 1.0);
        sqrt(1.0 - x * x).max(0.06)
    };
    let mut p = Planform::new(4);
    let line = |p: &mut Planform, t: f32, tones: &[Tone]| {
        let c = chord(t);
        let lead = 0.1 + 0.4 * c;
        p.push(Vec2::new(t, lead), Vec2::new(t, lead - c), &SPLITS, tones);
    };
    // Evenly in the angle round the ellipse, so the tip is round.
    let from = asin(-centre / half);
    let mut veins = VEINS.iter().peekable();
    line(&mut p, 0.0, &TONES);
    for k in 1..=SAMPLES {
        let angle = from + (FRAC_PI_2 - from) * k as f32 / SAMPLES as f32;
        let t = if k == SAMPLES {
            1.0
        } else {
            centre + half * sin(angle)
        };
        while let Some(&&v) = veins.peek() {
            if v + VEIN >= t {
                break;
            }
            line(&mut p, v - VEIN, &TONES);
            line(&mut p, v + VEIN, &BONE);
            veins.next();
        }
        line(&mut p, t, &TONES);
    }
    p
}

/// A wing's place: from `origin` along `along` (unit) for `length`, `width` wide across
/// `across` (unit, square to `along`, toward the leading edge).
#[derive(Debug, Clone, Copy)]
pub(crate) struct WingFrame {
    pub(crate) origin: Vec3,
    pub(crate) along: Vec3,
    pub(crate) across: Vec3,
    pub(crate) length: f32,
    pub(crate) width: f32,
}

/// The bind of a vertex at `t` along a wing on `chain` (joints evenly spaced from `t = 0`):
/// the two joints around it, by how near; past the last joint, the last.
fn bind_at(chain: &[u16], t: f32) -> Bind {
    let n = chain.len();
    let x = (t * n as f32).max(0.0);
    // Truncation is the floor for x ≥ 0.
    let k = x as usize;
    if k + 1 >= n {
        return Bind::one(chain[n - 1]);
    }
    let f = x - k as f32;
    if f == 0.0 {
        return Bind::one(chain[k]);
    }
    Bind::from_arrays([chain[k], chain[k + 1], 0, 0], [1.0 - f, f, 0.0, 0.0])
}

impl MeshBuilder {
    /// A thin two-sided wing of `planform` in `frame` on `chain` (its joints evenly spaced from
    /// the root), in `colour`; returns each new vertex's tone, in order.
    pub(crate) fn wing(
        &mut self,
        frame: WingFrame,
        planform: &Planform,
        chain: &[u16],
        colour: Vec3,
    ) -> Vec<Tone> {
        let mut tones = Vec::new();
        if chain.is_empty() || planform.chords.len() < 2 {
            return tones;
        }
        let WingFrame {
            origin,
            along,
            across,
            length,
            width,
        } = frame;
        let normal = along.cross(across).normalize_or_zero();
        let thickness = 0.02 * length;
        for side in [1.0f32, -1.0] {
            let offset = normal * (0.5 * thickness * side);
            for b in 0..planform.points - 1 {
                // The vertices of band `b` on the last chord line: (leading, trailing).
                let mut at: Option<(u32, u32)> = None;
                for (k, pair) in planform.chords.windows(2).enumerate() {
                    let tone = planform.tones[k][b];
                    let mut vertex = |q: Vec2| {
                        tones.push(tone);
                        let p = origin + offset + along * (length * q.x) + across * (width * q.y);
                        self.vertex(p, colour, bind_at(chain, q.x))
                    };
                    let shared = k > 0 && planform.tones[k - 1][b] == tone;
                    let (lead0, trail0) = match at {
                        Some(v) if shared => v,
                        _ => (vertex(pair[0][b]), vertex(pair[0][b + 1])),
                    };
                    let (lead1, trail1) = (vertex(pair[1][b]), vertex(pair[1][b + 1]));
                    at = Some((lead1, trail1));
                    let mut push = |t: [u32; 3]| {
                        self.indices
                            .push(if side > 0.0 { t } else { [t[0], t[2], t[1]] });
                    };
                    push([trail0, trail1, lead1]);
                    push([trail0, lead1, lead0]);
                }
            }
        }
        tones
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all() -> [(&'static str, Planform); 3] {
        [
            ("feathered", feathered()),
            ("bat", bat()),
            ("insect", insect()),
        ]
    }

    #[test]
    fn planforms_run_root_to_tip_and_lead_to_trail_with_no_fold() {
        for (name, p) in all() {
            let chords: Vec<&[Vec2]> = p.chords().collect();
            assert_eq!(chords.first().map(|c| c[0].x), Some(0.0), "{name}");
            assert!(
                chords.last().is_some_and(|c| c.iter().all(|q| q.x == 1.0)),
                "{name}"
            );
            for c in &chords {
                for pair in c.windows(2) {
                    assert!(pair[1].y < pair[0].y, "{name}: points go back: {c:?}");
                }
            }
            for pair in chords.windows(2) {
                for (a, b) in pair[0].iter().zip(pair[1]) {
                    assert!(
                        b.x > a.x,
                        "{name}: each point moves toward the tip: {pair:?}"
                    );
                }
            }
            assert!(
                p.area() > 0.3 && p.area() < 1.0,
                "{name}: area {}",
                p.area()
            );
        }
    }

    #[test]
    fn a_wing_mesh_covers_its_planforms_area_on_each_face() {
        for (name, p) in all() {
            let mut mesh = MeshBuilder::default();
            let frame = WingFrame {
                origin: Vec3::new(0.1, 0.2, 0.3),
                along: Vec3::X,
                across: Vec3::Z,
                length: 2.0,
                width: 0.8,
            };
            let tones = mesh.wing(frame, &p, &[0, 1, 2, 3], Vec3::ONE);
            assert_eq!(tones.len(), mesh.positions.len(), "{name}");
            let faces: f32 = mesh
                .indices
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
                    0.5 * (b - a).cross(c - a).length()
                })
                .sum();
            let expected = 2.0 * 0.8 * p.area();
            assert!(
                (0.5 * faces - expected).abs() < 1e-4 * expected,
                "{name}: {} against {expected}",
                0.5 * faces
            );
            // The first face's triangles face the way it is offset (along × across, −Y).
            let n = mesh.indices.len() / 2;
            for t in &mesh.indices[..n] {
                let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
                assert!((b - a).cross(c - a).y < 0.0 || (b - a).cross(c - a).length() == 0.0);
            }
        }
    }

    #[test]
    fn a_feathered_wing_has_a_serrated_trailing_edge_and_three_tones() {
        let p = feathered();
        let trail: Vec<f32> = p.chords().map(|c| c[c.len() - 1].y).collect();
        // A feather's tip reaches back past the notches on either side.
        let tips = trail
            .windows(3)
            .filter(|w| w[1] < w[0] && w[1] < w[2])
            .count();
        assert_eq!(tips, 13);
        for tone in [Tone::Covert, Tone::Skin, Tone::Tip] {
            assert_eq!(p.panels_in(tone), 39, "{tone:?}");
        }
    }

    #[test]
    fn a_bat_wing_has_three_fingers_and_scallops_between_their_tips() {
        let p = bat();
        // A finger is a panel of bone right across the chord.
        let fingers = p
            .tones
            .iter()
            .filter(|row| row[..2].iter().all(|&t| t == Tone::Bone))
            .count();
        assert_eq!(fingers, 3);
        // Between two fingers the trailing edge comes in past the line joining their tips.
        let chords: Vec<&[Vec2]> = p.chords().collect();
        let trail = |k: usize| chords[k][2];
        let mid = trail(8);
        let (a, b) = (trail(6), trail(11));
        let chordline = a.y + (b.y - a.y) * (mid.x - a.x) / (b.x - a.x);
        assert!(mid.y > chordline + 0.02, "{mid:?} against {a:?}–{b:?}");
    }

    #[test]
    fn an_insect_wing_has_veins_along_and_across() {
        let p = insect();
        let across = p
            .tones
            .iter()
            .filter(|row| row.iter().all(|&t| t == Tone::Bone))
            .count();
        assert_eq!(across, 3);
        assert!(p.panels_in(Tone::Pale) > 0);
    }

    #[test]
    fn a_vertex_is_bound_to_the_joints_around_it() {
        let chain = [4, 5, 6, 7];
        assert_eq!(bind_at(&chain, 0.0), Bind::one(4));
        assert_eq!(
            bind_at(&chain, 0.375),
            Bind::from_arrays([5, 6, 0, 0], [0.5, 0.5, 0.0, 0.0])
        );
        assert_eq!(bind_at(&chain, 0.9), Bind::one(7));
    }

    #[test]
    fn weights_pick_only_weighted_kinds() {
        let bat = WingWeights::only(WingKind::Bat);
        for u in [0.0, 0.3, 0.999_999] {
            assert_eq!(bat.pick(u), WingKind::Bat);
        }
        assert_eq!(WingWeights::DEFAULT.pick(0.2), WingKind::Feathered);
        assert_eq!(WingWeights::DEFAULT.pick(0.7), WingKind::Bat);
        let none = WingWeights::only(WingKind::Bat).with(WingKind::Bat, 0.0);
        assert_eq!(none.check("w"), Err(Error::AllZero { what: "w" }));
        assert!(
            WingWeights::DEFAULT
                .with(WingKind::Bat, f32::NAN)
                .check("w")
                .is_err()
        );
    }
}
