//! Nearest-k binding: each vertex takes the `k` bones whose segments are closest to it.

use alloc::vec::Vec;

use glam::{Vec3, Vec4};

use crate::error::SkinError;
use crate::influences::{Influences, MAX_INFLUENCES};
use crate::math;

/// The most bones [`nearest_k`] accepts: every bone index must fit a `u16` joint index.
pub const MAX_BONES: usize = 1 << 16;

/// The largest accepted coordinate magnitude for vertices and bone ends. Squared distances
/// between points within this bound stay far from `f32` overflow.
pub const MAX_COORDINATE: f32 = 1.0e15;

/// How a bone's weight falls off with its distance `d` from the vertex.
///
/// The default is [`Falloff::Smooth`] with `spread = 1`: bones more than twice as far as the
/// nearest get nothing, so turning the head never drags the tail. Inverse-distance weights never
/// reach zero: every one of the `k` nearest bones keeps some pull, however far (the seed's
/// behaviour).
///
/// Both kernels compare each candidate bone with the nearest one (distance `d_min`), so they
/// are scale-free: scaling a whole model leaves the weights unchanged. Both are continuous in
/// the vertex position, and the nearest bone always has the largest weight (bones at nearly the
/// same distance may tie with it exactly, and equal weights are listed by joint index).
///
/// A vertex lying exactly on a bone (`d_min = 0`) gets weight 1 on that bone; if it lies on
/// several (the joint between two bones), they share equally.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Falloff {
    /// Inverse-distance power: `w ∝ 1 / d^power`, evaluated as `(d_min² / d²)^(power / 2)` so
    /// that nothing overflows as `d → 0`. `power = 2` (inverse square) takes no `powf`.
    InverseDistance {
        /// The exponent, finite and greater than zero. Larger values give sharper bends.
        power: f32,
    },
    /// A smooth kernel with compact support: with `r = d / d_min`, `w = (1 − ((r − 1) / spread)²)²`
    /// for `r < 1 + spread`, else 0. Bones more than `1 + spread` times as far as the nearest get
    /// exactly zero, so far-off bones never tug at a vertex; the weight is continuously
    /// differentiable in the vertex position wherever `d_min > 0`.
    Smooth {
        /// How much farther than the nearest bone another bone may be and still count, as a
        /// multiple of the nearest distance; finite and greater than zero.
        spread: f32,
    },
}

impl Falloff {
    /// The smooth kernel with `spread = 1`, the default.
    pub const DEFAULT: Self = Self::Smooth { spread: 1.0 };

    fn validate(self) -> Result<(), SkinError> {
        let (what, value) = match self {
            Self::InverseDistance { power } => ("power", power),
            Self::Smooth { spread } => ("spread", spread),
        };
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(SkinError::InvalidFalloff { what, value })
        }
    }

    /// Unnormalised weights, four lanes at once, from the squared distances to a bone and to
    /// the nearest one (`d_sq >= nearest_sq`). Lanes where `nearest_sq` is 0 come out NaN or
    /// infinite: the caller replaces them.
    #[inline]
    fn weights(self, nearest_sq: Vec4, d_sq: Vec4) -> Vec4 {
        match self {
            Self::InverseDistance { power } => {
                let ratio = nearest_sq / d_sq;
                if power == 2.0 {
                    ratio
                } else if power == 1.0 {
                    ratio.sqrt()
                } else {
                    Vec4::from_array(ratio.to_array().map(|r| math::powf(r, 0.5 * power)))
                }
            }
            Self::Smooth { spread } => {
                let r = (d_sq / nearest_sq).sqrt();
                let t = (r - Vec4::ONE) / Vec4::splat(spread);
                let s = Vec4::ONE - t * t;
                Vec4::select(t.cmpge(Vec4::ONE), Vec4::ZERO, s * s)
            }
        }
    }
}

impl Default for Falloff {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Options for [`nearest_k_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct NearestOptions {
    /// Influences per vertex, 1 to [`MAX_INFLUENCES`]. Default 4 (the glTF limit, and the seed's
    /// choice).
    pub k: usize,
    /// How weights fall off with distance. Default [`Falloff::Smooth`] with spread 1.
    pub falloff: Falloff,
}

impl NearestOptions {
    /// `k = 4`, smooth falloff with spread 1.
    pub const DEFAULT: Self = Self {
        k: MAX_INFLUENCES,
        falloff: Falloff::DEFAULT,
    };

    /// Sets [`k`](Self::k).
    #[must_use]
    pub const fn with_k(mut self, k: usize) -> Self {
        self.k = k;
        self
    }

    /// Sets [`falloff`](Self::falloff).
    #[must_use]
    pub const fn with_falloff(mut self, falloff: Falloff) -> Self {
        self.falloff = falloff;
        self
    }
}

impl Default for NearestOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Binds each vertex to its `k` nearest bones with the default falloff ([`Falloff::DEFAULT`]).
///
/// Shorthand for [`nearest_k_with`] with `NearestOptions::DEFAULT.with_k(k)`; see there.
///
/// ```
/// use creature_skin::{glam::Vec3, nearest_k};
///
/// // A two-bone spine along +Z.
/// let bones = [[Vec3::ZERO, Vec3::Z], [Vec3::Z, Vec3::Z * 2.0]];
/// let vertices = [Vec3::new(0.3, 0.0, 0.2), Vec3::new(0.0, 0.3, 1.0), Vec3::new(0.0, 0.0, 1.5)];
/// let influences = nearest_k(&vertices, &bones, 4)?;
/// assert_eq!(influences[0].joints[0], 0);                // nearest to the first bone
/// assert!((influences[1].weights[0] - 0.5).abs() < 1e-6); // at the joint: half and half
/// assert_eq!(influences[2].weights, [1.0, 0.0, 0.0, 0.0]); // on the second bone: all of it
/// # Ok::<(), creature_skin::SkinError>(())
/// ```
///
/// # Errors
/// As [`nearest_k_with`].
pub fn nearest_k(
    vertices: &[Vec3],
    bones: &[[Vec3; 2]],
    k: usize,
) -> Result<Vec<Influences>, SkinError> {
    nearest_k_with(vertices, bones, &NearestOptions::DEFAULT.with_k(k))
}

/// Binds each vertex to its `options.k` nearest bones (the 3D seed's rule), with weights from
/// `options.falloff`, normalised to sum 1.
///
/// A bone is the segment from `bone[0]` (head) to `bone[1]` (tail); a bone with both ends equal
/// is a point. Distance is to the segment ([`distance_to_bone`]), not to its head. Bones at equal
/// distance are ranked by index, smallest first, so the result is deterministic. Joint index `i`
/// in the output is `bones[i]`.
///
/// Returns one [`Influences`] per vertex, in order; no vertices give an empty list.
///
/// # Errors
/// - [`SkinError::InvalidInfluenceCount`] if `k` is 0 or more than [`MAX_INFLUENCES`];
/// - [`SkinError::InvalidFalloff`] for a falloff parameter that is not finite and positive;
/// - [`SkinError::NoBones`] / [`SkinError::TooManyBones`] for 0 or more than [`MAX_BONES`]
///   bones;
/// - [`SkinError::NonFinite`] / [`SkinError::CoordinateTooLarge`] for a vertex or bone end
///   that is not finite or beyond [`MAX_COORDINATE`].
pub fn nearest_k_with(
    vertices: &[Vec3],
    bones: &[[Vec3; 2]],
    options: &NearestOptions,
) -> Result<Vec<Influences>, SkinError> {
    let k = options.k;
    if k == 0 || k > MAX_INFLUENCES {
        return Err(SkinError::InvalidInfluenceCount { k });
    }
    options.falloff.validate()?;
    if bones.is_empty() {
        return Err(SkinError::NoBones);
    }
    if bones.len() > MAX_BONES {
        return Err(SkinError::TooManyBones { count: bones.len() });
    }
    for (index, bone) in bones.iter().enumerate() {
        check_point("bone", index, bone[0])?;
        check_point("bone", index, bone[1])?;
    }
    for (index, &v) in vertices.iter().enumerate() {
        check_point("vertex", index, v)?;
    }

    let segments: Vec<Segment> = bones.iter().map(|b| Segment::new(b[0], b[1])).collect();
    Ok(bind_all(vertices, &segments, k, options.falloff))
}

/// Distance from `point` to the bone segment `bone[0]`–`bone[1]` (to the point itself when the
/// two ends coincide).
///
/// ```
/// use creature_skin::{distance_to_bone, glam::Vec3};
///
/// let bone = [Vec3::ZERO, Vec3::Z * 2.0];
/// assert_eq!(distance_to_bone(Vec3::new(0.5, 0.0, 1.0), bone), 0.5); // beside the middle
/// assert_eq!(distance_to_bone(Vec3::new(0.0, 0.0, 3.0), bone), 1.0); // past the tail
/// ```
#[must_use]
pub fn distance_to_bone(point: Vec3, bone: [Vec3; 2]) -> f32 {
    // The same lane code as `nearest_k`, so the two agree to the last bit.
    let p = [
        Vec4::splat(point.x),
        Vec4::splat(point.y),
        Vec4::splat(point.z),
    ];
    math::sqrt(Segment::new(bone[0], bone[1]).distance_sq(&p).x)
}

fn check_point(what: &'static str, index: usize, p: Vec3) -> Result<(), SkinError> {
    if !p.is_finite() {
        return Err(SkinError::NonFinite { what, index });
    }
    for value in p.to_array() {
        if value.abs() > MAX_COORDINATE {
            return Err(SkinError::CoordinateTooLarge { what, index, value });
        }
    }
    Ok(())
}

/// A bone prepared for distance queries: every component splatted across four lanes, so four
/// vertices are measured against it at once.
#[derive(Clone, Copy)]
struct Segment {
    head: [Vec4; 3],
    axis: [Vec4; 3],
    /// `1 / |axis|²` rounded up so that `|axis|² · inv_len_sq >= 1` exactly, or 0 for a point
    /// bone (or one too short to square).
    inv_len_sq: Vec4,
}

impl Segment {
    fn new(head: Vec3, tail: Vec3) -> Self {
        let split = |v: Vec3| [Vec4::splat(v.x), Vec4::splat(v.y), Vec4::splat(v.z)];
        let axis = split(tail - head);
        // The same operations as the projection in `distance_sq`, so that a point exactly on
        // the tail projects to exactly this value.
        let [ax, ay, az] = axis;
        let len_sq = (ax * ax + ay * ay + az * az).x;
        let mut inv = 1.0 / len_sq;
        if inv.is_finite() && len_sq * inv < 1.0 {
            inv = inv.next_up();
        }
        Self {
            head: split(head),
            axis,
            inv_len_sq: Vec4::splat(if inv.is_finite() { inv } else { 0.0 }),
        }
    }

    /// Squared distances from four points (coordinates by lane) to the segment.
    ///
    /// Exactly zero for a point on either end: at the head the projection parameter is exactly
    /// 0; at the tail `p − head` is exactly `axis` (the same subtraction) and its projection
    /// exactly `|axis|²`, which `inv_len_sq` (rounded up) takes to at least 1, clamped to
    /// exactly 1.
    #[inline]
    fn distance_sq(&self, p: &[Vec4; 3]) -> Vec4 {
        let [ax, ay, az] = self.axis;
        let rx = p[0] - self.head[0];
        let ry = p[1] - self.head[1];
        let rz = p[2] - self.head[2];
        let dot = rx * ax + ry * ay + rz * az;
        let t = (dot * self.inv_len_sq).max(Vec4::ZERO).min(Vec4::ONE);
        let dx = rx - ax * t;
        let dy = ry - ay * t;
        let dz = rz - az * t;
        dx * dx + dy * dy + dz * dz
    }
}

/// Binds `vertices` four at a time (the last block padded by repeating its last vertex).
fn bind_all(
    vertices: &[Vec3],
    segments: &[Segment],
    k: usize,
    falloff: Falloff,
) -> Vec<Influences> {
    let used = k.min(segments.len()).min(MAX_INFLUENCES);
    let mut out = Vec::with_capacity(vertices.len());
    for block in vertices.chunks(4) {
        // Chunks are never empty; a short last block repeats its last vertex in the spare lanes.
        let last = block[block.len() - 1];
        let lane = |i: usize| block.get(i).copied().unwrap_or(last);
        let (a, b, c, d) = (lane(0), lane(1), lane(2), lane(3));
        let p = [
            Vec4::new(a.x, b.x, c.x, d.x),
            Vec4::new(a.y, b.y, c.y, d.y),
            Vec4::new(a.z, b.z, c.z, d.z),
        ];
        let nearest = nearest_block(&p, segments);
        let weights = weigh_block(&nearest, used, falloff);
        let settled = settle_block(weights, nearest.ids);
        out.extend(settled.iter().take(block.len()));
    }
    out
}

/// The four nearest bones of each of four lanes, nearest first: squared distances and bone
/// indices, slot by slot.
struct Nearest {
    /// Squared distance, `[slot]` by lane; infinite in slots past the bone count.
    d_sq: [Vec4; MAX_INFLUENCES],
    /// Bone index (a whole number, exact in `f32`), `[slot]` by lane.
    ids: [Vec4; MAX_INFLUENCES],
}

/// Bits of a sort key that carry the bone index: a `f32` widened to `f64` leaves the low 29
/// bits of the mantissa zero, and bone indices fit in 16 (`MAX_BONES` is `2^16`).
const ID_BITS: u64 = 0xffff;

/// The best four bones for each of four lanes, nearest first; the best `k` are the first `k`.
///
/// Each (squared distance, bone) pair is packed into one `f64` sort key: the distance widened
/// exactly to `f64`, the bone index in the mantissa's low bits, which the widening leaves zero.
/// For non-negative keys the `f64` order is the order of (distance, index), exactly: ties keep
/// the lower bone index, and nothing is rounded. Four sorted slots per lane take each new key
/// by a min/max insertion network, branch-free.
fn nearest_block(p: &[Vec4; 3], segments: &[Segment]) -> Nearest {
    let mut slots = [[f64::INFINITY; 4]; MAX_INFLUENCES];
    for (index, segment) in segments.iter().enumerate() {
        let d = segment.distance_sq(p).to_array();
        // Bone counts are validated to fit 16 bits; squared distances are finite and >= 0.
        let id = index as u64 & ID_BITS;
        let mut key: [f64; 4] =
            core::array::from_fn(|l| f64::from_bits(f64::from(d[l]).to_bits() | id));
        for slot in &mut slots {
            let low: [f64; 4] =
                core::array::from_fn(|l| if key[l] < slot[l] { key[l] } else { slot[l] });
            let high: [f64; 4] =
                core::array::from_fn(|l| if key[l] < slot[l] { slot[l] } else { key[l] });
            *slot = low;
            key = high;
        }
    }
    Nearest {
        d_sq: slots.map(|slot| {
            // Clearing the index bits gives back the widened distance, which narrows exactly.
            Vec4::from_array(slot.map(|key| f64::from_bits(key.to_bits() & !ID_BITS) as f32))
        }),
        // The low 16 bits are the index (0 for the infinite padding).
        ids: slots.map(|slot| Vec4::from_array(slot.map(|key| (key.to_bits() & ID_BITS) as f32))),
    }
}

/// Normalised weights, `[slot]` by lane, for the first `used` slots of `nearest` (the rest 0).
///
/// Each lane's weights come from `falloff` (a lane whose nearest bone is at distance zero gives
/// weight 1 to every bone at distance zero and 0 to the rest), divided by their sum.
fn weigh_block(nearest: &Nearest, used: usize, falloff: Falloff) -> [Vec4; MAX_INFLUENCES] {
    let nearest_sq = nearest.d_sq[0];
    let on_bone = nearest_sq.cmple(Vec4::ZERO);
    let mut weights = [Vec4::ZERO; MAX_INFLUENCES];
    for (w, &d_sq) in weights.iter_mut().zip(&nearest.d_sq).take(used) {
        // On-bone lanes divide 0 by 0 here; the select below replaces them.
        let off = falloff.weights(nearest_sq, d_sq);
        let on = Vec4::select(d_sq.cmple(Vec4::ZERO), Vec4::ONE, Vec4::ZERO);
        *w = Vec4::select(on_bone, on, off);
    }
    let [w0, w1, w2, w3] = weights;
    // The same order of additions as summing one vertex's four weights.
    let sum = w0 + w1 + w2 + w3;
    // The nearest bone's weight is 1, so the sum is at least 1; never divide by zero anyway.
    let divisor = Vec4::select(sum.cmpgt(Vec4::ZERO), sum, Vec4::ONE);
    weights.map(|w| w / divisor)
}

/// Influences for four lanes from their divided weights and bone ids, `[slot]` by lane: what
/// [`settle`] makes of each lane, computed for all four at once, with [`settle`] itself only for
/// a lane that is not in canonical order already.
fn settle_block(weights: [Vec4; MAX_INFLUENCES], ids: [Vec4; MAX_INFLUENCES]) -> [Influences; 4] {
    let zero = Vec4::ZERO;
    // Empty slots name joint 0.
    let ids: [Vec4; MAX_INFLUENCES] =
        core::array::from_fn(|s| Vec4::select(weights[s].cmpgt(zero), ids[s], zero));
    // The same test as `settle`'s, lane by lane.
    let in_order = |a: usize, b: usize| {
        let (wa, wb, ja, jb) = (weights[a], weights[b], ids[a], ids[b]);
        wa.cmpgt(wb) | (wa.cmpeq(wb) & (ja.cmplt(jb) | wb.cmple(zero)))
    };
    let canonical = (in_order(0, 1) & in_order(1, 2) & in_order(2, 3)).bitmask();
    let [w0, w1, w2, w3] = weights;
    // The rounding residue, as in `settle`.
    let first = Vec4::ONE - (w1 + w2 + w3);
    let w0 = Vec4::select(w0.cmpgt(w1) & first.cmpgt(w1), first, w0);
    let settled_w = [w0, w1, w2, w3].map(|w| w.to_array());
    let divided_w0 = weights[0].to_array();
    // Ids are whole numbers below 65536: the cast is exact.
    let ids = ids.map(|j| j.to_array().map(|j| j as u16));
    core::array::from_fn(|lane| {
        let mut inf = Influences {
            joints: core::array::from_fn(|s| ids[s][lane]),
            weights: core::array::from_fn(|s| settled_w[s][lane]),
        };
        if canonical & (1 << lane) == 0 {
            inf.weights[0] = divided_w0[lane];
            settle(&mut inf);
        }
        inf
    })
}

/// Scales the weights to sum 1, then sorts them, clears empty slots and puts the rounding
/// residue on an untied largest weight (see [`settle`]). No positive weight gives
/// [`Influences::NONE`].
pub(crate) fn normalise(inf: &mut Influences) {
    let sum: f32 = inf.weights.iter().sum();
    if !(sum > 0.0) {
        *inf = Influences::NONE;
        return;
    }
    for w in &mut inf.weights {
        *w /= sum;
    }
    settle(inf);
}

/// Puts divided weights in canonical order (sorted by weight, largest first, equal weights by
/// joint index; empty slots on joint 0) and the rounding residue on a largest weight that has
/// no tie.
fn settle(inf: &mut Influences) {
    // Usually already canonical (the kernels are monotone and the bones come nearest first).
    let [j0, j1, j2, j3] = inf.joints;
    let [w0, w1, w2, w3] = inf.weights;
    let in_order =
        |wa: f32, ja: u16, wb: f32, jb: u16| wa > wb || (wa == wb && (ja < jb || wb <= 0.0));
    let canonical = in_order(w0, j0, w1, j1)
        && in_order(w1, j1, w2, j2)
        && in_order(w2, j2, w3, j3)
        && inf
            .joints
            .iter()
            .zip(inf.weights.iter())
            .all(|(&j, &w)| w > 0.0 || j == 0);
    if !canonical {
        inf.canonicalise();
    }
    // Put the rounding residue on the largest weight when it stands alone at the top and stays
    // there: tied weights stay exactly equal (so the lower joint index keeps its place by
    // right, and a nearer bone is never outweighed by a tied farther one). The sum is within a
    // few ulps of 1 either way.
    let rest: f32 = inf.weights[1..].iter().sum();
    let first = 1.0 - rest;
    if inf.weights[0] > inf.weights[1] && first > inf.weights[1] {
        inf.weights[0] = first;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_is_to_the_segment_not_the_head() {
        let bone = [Vec3::ZERO, Vec3::new(0.0, 0.0, 4.0)];
        assert_eq!(distance_to_bone(Vec3::new(1.0, 0.0, 3.0), bone), 1.0);
        assert_eq!(distance_to_bone(Vec3::new(0.0, 0.0, -2.0), bone), 2.0);
        // A point bone.
        assert_eq!(
            distance_to_bone(Vec3::new(3.0, 4.0, 0.0), [Vec3::ZERO; 2]),
            5.0
        );
    }

    /// Regression: a vertex exactly on a bone's tail came out at a distance of ~1e-7 (the
    /// projection parameter rounded below 1), so it took weights of 1e-14 from other bones.
    #[test]
    fn a_vertex_on_a_bone_end_is_at_distance_zero() {
        let bone = [Vec3::new(0.1, 0.7, -2.0), Vec3::new(0.3, 1e-3, 2.0)];
        assert_eq!(distance_to_bone(bone[0], bone), 0.0);
        assert_eq!(distance_to_bone(bone[1], bone), 0.0);
        // The capsule's tip: `1.96 * (1 / 1.96)` rounds to 0.99999994.
        let bones = [[Vec3::Z * 0.6, Vec3::Z * 2.0], [Vec3::ZERO, Vec3::Z * 0.6]];
        assert_eq!(
            nearest_k(&[Vec3::Z * 2.0], &bones, 4).unwrap()[0],
            Influences::single(0)
        );
    }

    #[test]
    fn the_reciprocal_length_is_rounded_up() {
        // |axis|² · inv_len_sq must reach 1 so that a point on the tail projects to t = 1.
        let mut x = 0.013_f32;
        for _ in 0..2000 {
            let s = Segment::new(
                Vec3::new(0.3, -1.0, 2.0),
                Vec3::new(0.3 + x, -1.0 + x * 0.7, 2.0),
            );
            let [ax, ay, az] = s.axis;
            let len_sq = (ax * ax + ay * ay + az * az).x;
            assert!(len_sq * s.inv_len_sq.x >= 1.0, "{x}");
            assert_eq!(
                s.distance_sq(&[
                    Vec4::splat(0.3 + x),
                    Vec4::splat(-1.0 + x * 0.7),
                    Vec4::splat(2.0)
                ])
                .x,
                0.0,
                "{x}"
            );
            x *= 1.0071;
        }
        // A point bone, and one too short to square, measure from the head.
        let point = Segment::new(Vec3::ONE, Vec3::ONE);
        assert_eq!(point.inv_len_sq, Vec4::ZERO);
        let p = [Vec4::splat(1.0), Vec4::splat(1.0), Vec4::splat(4.0)];
        assert_eq!(point.distance_sq(&p).x, 9.0);
    }

    const INVERSE_SQUARE: NearestOptions =
        NearestOptions::DEFAULT.with_falloff(Falloff::InverseDistance { power: 2.0 });

    #[test]
    fn inverse_square_weights_follow_the_distances() {
        let bones = [
            [Vec3::new(-1.0, 0.0, 0.0), Vec3::new(-1.0, 0.0, 1.0)],
            [Vec3::new(2.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 1.0)],
        ];
        let options = INVERSE_SQUARE.with_k(2);
        let inf = nearest_k_with(&[Vec3::new(0.0, 0.0, 0.5)], &bones, &options).unwrap()[0];
        // d = 1 and 2: weights 1 and 1/4, normalised to 0.8 and 0.2.
        assert_eq!(inf.joints, [0, 1, 0, 0]);
        assert!((inf.weights[0] - 0.8).abs() < 1e-6);
        assert!((inf.weights[1] - 0.2).abs() < 1e-6);
    }

    #[test]
    fn k_limits_the_influences() {
        let bones: Vec<[Vec3; 2]> = (0..6)
            .map(|i| [Vec3::new(i as f32, 0.0, 0.0), Vec3::new(i as f32, 1.0, 0.0)])
            .collect();
        for k in 1..=4 {
            let options = INVERSE_SQUARE.with_k(k);
            let inf = nearest_k_with(&[Vec3::new(2.2, 0.5, 0.3)], &bones, &options).unwrap()[0];
            assert_eq!(inf.count(), k);
            assert_eq!(inf.joints[0], 2);
        }
        let inf = nearest_k(&[Vec3::new(2.2, 0.5, 0.3)], &bones, 1).unwrap()[0];
        assert_eq!(inf, Influences::single(2));
    }

    #[test]
    fn vertex_on_a_bone_takes_it_whole() {
        let bones = [[Vec3::ZERO, Vec3::Z], [Vec3::X, Vec3::X + Vec3::Z]];
        let inf = nearest_k(&[Vec3::new(0.0, 0.0, 0.25)], &bones, 4).unwrap()[0];
        assert_eq!(inf, Influences::single(0));
        let smooth = NearestOptions::DEFAULT.with_falloff(Falloff::Smooth { spread: 10.0 });
        let inf = nearest_k_with(&[Vec3::new(1.0, 0.0, 0.25)], &bones, &smooth).unwrap()[0];
        assert_eq!(inf, Influences::single(1));
    }

    /// Regression: two equal weights, 0.5 and 0.5 after division, became 0.49999997 and 0.5
    /// when the rounding residue went to the first slot, leaving the pair unsorted.
    #[test]
    fn equal_weights_stay_sorted_after_normalising() {
        let bones = [
            [Vec3::Z * -2.0, Vec3::Z * -0.6],
            [Vec3::Z * -0.6, Vec3::Z * 0.6],
            [Vec3::Z * 0.6, Vec3::Z * 2.0],
        ];
        let v = Vec3::new(0.5 * 0.382_683_4, 0.5 * 0.923_879_5, -0.6);
        for options in [NearestOptions::DEFAULT, INVERSE_SQUARE] {
            let inf = nearest_k_with(&[v], &bones, &options).unwrap()[0];
            assert!(inf.weights.windows(2).all(|p| p[0] >= p[1]), "{inf:?}");
            assert!((inf.weight_sum() - 1.0).abs() < 1e-6);
        }
        let mut inf = Influences {
            joints: [0, 1, 0, 0],
            weights: [0.3, 0.3, 0.0, 0.0],
        };
        normalise(&mut inf);
        assert!(inf.weights[0] >= inf.weights[1], "{inf:?}");
    }

    /// Regression: bones at nearly equal distances get exactly equal smooth weights
    /// (`1 − t²` rounds to 1), and they came out nearest first, bone 1 before bone 0, against
    /// the documented order (equal weights by joint index, smallest first).
    #[test]
    fn equal_weights_are_ordered_by_joint_index() {
        let bones = [
            [
                Vec3::new(-1.000_01, 0.0, 0.0),
                Vec3::new(-1.000_01, 0.0, 1.0),
            ],
            [Vec3::new(1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 1.0)],
        ];
        let inf = nearest_k(&[Vec3::new(0.0, 0.0, 0.5)], &bones, 4).unwrap()[0];
        assert_eq!(inf.weights, [0.5, 0.5, 0.0, 0.0]);
        assert_eq!(inf.joints, [0, 1, 0, 0]);
    }

    #[test]
    fn vertex_on_a_shared_joint_splits_evenly() {
        let bones = [[Vec3::ZERO, Vec3::Z], [Vec3::Z, Vec3::Z * 2.0]];
        let inf = nearest_k(&[Vec3::Z], &bones, 4).unwrap()[0];
        assert_eq!(inf.joints, [0, 1, 0, 0]);
        assert_eq!(inf.weights, [0.5, 0.5, 0.0, 0.0]);
    }

    #[test]
    fn smooth_falloff_ignores_far_bones() {
        let bones = [
            [Vec3::new(-1.0, 0.0, 0.0), Vec3::new(-1.0, 0.0, 1.0)],
            [Vec3::new(1.5, 0.0, 0.0), Vec3::new(1.5, 0.0, 1.0)],
            [Vec3::new(5.0, 0.0, 0.0), Vec3::new(5.0, 0.0, 1.0)],
        ];
        let options = NearestOptions::DEFAULT.with_falloff(Falloff::Smooth { spread: 1.0 });
        let inf = nearest_k_with(&[Vec3::new(0.0, 0.0, 0.5)], &bones, &options).unwrap()[0];
        // d = 1, 1.5, 5: the third is beyond 2 × the nearest and gets nothing.
        assert_eq!(inf.count(), 2);
        assert_eq!(inf.joints[..2], [0, 1]);
        // r = 1.5, t = 0.5: (1 − 0.25)² = 0.5625 against 1.
        assert!((inf.weights[1] - 0.5625 / 1.5625).abs() < 1e-6);
    }

    #[test]
    fn other_powers_use_powf() {
        let bones = [
            [Vec3::new(-1.0, 0.0, 0.0), Vec3::new(-1.0, 0.0, 1.0)],
            [Vec3::new(3.0, 0.0, 0.0), Vec3::new(3.0, 0.0, 1.0)],
        ];
        for (power, expected) in [(1.0, 1.0 / 3.0), (3.0, 1.0 / 27.0), (0.5, 0.577_350_3)] {
            let options = NearestOptions::DEFAULT.with_falloff(Falloff::InverseDistance { power });
            let inf = nearest_k_with(&[Vec3::new(0.0, 0.0, 0.5)], &bones, &options).unwrap()[0];
            let got = inf.weights[1] / inf.weights[0];
            assert!((got - expected).abs() < 1e-5, "power {power}: {got}");
        }
    }

    #[test]
    fn bad_input_is_an_error() {
        let bone = [[Vec3::ZERO, Vec3::Z]];
        let v = [Vec3::ZERO];
        assert_eq!(
            nearest_k(&v, &bone, 0),
            Err(SkinError::InvalidInfluenceCount { k: 0 })
        );
        assert_eq!(
            nearest_k(&v, &bone, 5),
            Err(SkinError::InvalidInfluenceCount { k: 5 })
        );
        assert_eq!(nearest_k(&v, &[], 4), Err(SkinError::NoBones));
        assert_eq!(
            nearest_k(&[Vec3::ZERO, Vec3::NAN], &bone, 4),
            Err(SkinError::NonFinite {
                what: "vertex",
                index: 1
            })
        );
        assert_eq!(
            nearest_k(&v, &[[Vec3::ZERO, Vec3::INFINITY]], 4),
            Err(SkinError::NonFinite {
                what: "bone",
                index: 0
            })
        );
        assert_eq!(
            nearest_k(&[Vec3::new(0.0, 2e15, 0.0)], &bone, 4),
            Err(SkinError::CoordinateTooLarge {
                what: "vertex",
                index: 0,
                value: 2e15
            })
        );
        let many = alloc::vec![[Vec3::ZERO, Vec3::Z]; MAX_BONES + 1];
        assert_eq!(
            nearest_k(&v, &many, 4),
            Err(SkinError::TooManyBones {
                count: MAX_BONES + 1
            })
        );
        let bad = NearestOptions::DEFAULT.with_falloff(Falloff::Smooth { spread: f32::NAN });
        assert!(matches!(
            nearest_k_with(&v, &bone, &bad),
            Err(SkinError::InvalidFalloff { what: "spread", .. })
        ));
    }

    #[test]
    fn the_largest_bone_count_is_accepted() {
        let many = alloc::vec![[Vec3::ZERO, Vec3::Z]; MAX_BONES];
        let inf = nearest_k(&[Vec3::X], &many, 4).unwrap()[0];
        // All tie: the four lowest indices share.
        assert_eq!(inf.joints, [0, 1, 2, 3]);
        assert!((inf.weight_sum() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn extreme_but_valid_coordinates_stay_finite() {
        let bones = [
            [Vec3::splat(-1e15), Vec3::splat(1e15)],
            [Vec3::ZERO, Vec3::X],
        ];
        let inf = nearest_k(
            &[Vec3::new(1e15, -1e15, 1e15), Vec3::splat(1e-30)],
            &bones,
            4,
        )
        .unwrap();
        for i in inf {
            assert!(i.weights.iter().all(|w| w.is_finite()));
            assert!((i.weight_sum() - 1.0).abs() < 1e-6);
        }
    }
}
