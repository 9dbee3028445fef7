//! The rigging algorithm: head and tail, the medial line, joints and sockets.

use alloc::borrow::Cow;
use alloc::vec;
use alloc::vec::Vec;

use glam::{Vec3, Vec3A, Vec4};

use crate::error::AutorigError;
use crate::options::{RigOptions, RootAt};
use crate::skeleton::{Joint, Rig, Socket};

/// The fraction of the body's Z extent, at each end, whose vertices' centre anchors the centre
/// line at that end.
const END_DEPTH: f32 = 0.1;

/// How far below an exact half the tail side's bone share must fall to round up: a symmetric
/// body with an odd bone count gives its extra bone to the head side, whatever the rounding.
const CENTRE_SHADE: f32 = 0.01;

/// The largest accepted coordinate magnitude: lengths and squared distances between points
/// within this bound stay far from `f32` overflow.
pub const MAX_COORDINATE: f32 = 1.0e15;

/// Fits a skeleton to a body mesh: the seed's head and tail, a spine along the body's medial
/// line, and limb sockets on every spine bone but the first and last.
///
/// The body must run along Z with the head towards +Z, Y up, in a right-handed frame, so the
/// creature's left is +X and its right −X (glTF's convention; see the crate's conventions).
///
/// 1. **Head and tail** (the 3D seed's rule): the two farthest-apart vertices lying within
///    [`centre_tolerance`](RigOptions::centre_tolerance) times the larger of the body's X and Y
///    extents of its centre line in X and Y; the one further forward (+Z) is the head. The
///    seed's centre line runs along Z through the bounding-box centre; a tilted or bent body
///    can carry its tips away from that line, so a vertex also counts at each end if it is
///    that close to the Z line through the centre of the rearmost or frontmost tenth of the
///    body (its vertices' centroid, weighted from 1 at the very end to 0 a tenth in). In such
///    thin tubes the farthest-apart pair is the pair of Z extremes (up to the tubes' width),
///    and that is what is taken. If the tubes hold no vertex, they are doubled until they do.
/// 2. **Medial line** (beyond the seed): the vertices are cut into slabs across the
///    tail-to-head axis, and the centroid of each slab's vertices is a point of the medial
///    line, which runs from the tail vertex through those centroids to the head vertex. A bent
///    body thus gets a spine inside it, not a chord through the air.
/// 3. **Joints**: the bone count is the medial line's length over
///    [`bone_length`](RigOptions::bone_length), rounded and clamped to
///    `min_bones..=max_bones`; joints are spread evenly along the line. With
///    [`RootAt::Centre`] the root is the medial point level with the bounding-box centre and
///    the bones run out to the head and tail; with [`RootAt::Head`] the root is the head and the
///    bones run back to the tail.
/// 4. **Sockets**: for each spine bone but the first and last, among the vertices beside the
///    bone (between the planes square to it through its two ends; failing any, those around
///    it), the ones furthest out towards its left (+X), right (−X) and top (+Y) sides — the
///    sides taken square to the bone, so a bent or rotated body gets sockets square to its
///    spine; of equally far-out vertices, the one level with the bone's middle — with the
///    left–right distance as the bone's width and the height of the bone's midpoint above the
///    lowest of those vertices as its clearance.
///
/// Only vertices used by a triangle count as the body; with no triangles, every vertex does
/// (a point cloud). The result is deterministic, and its joints lie inside the body's bounding
/// box.
///
/// ```
/// use creature_autorig::{glam::Vec3, rig, RigOptions, RootAt};
///
/// // A capsule-like body: 9 rings of 8 vertices along Z, from the tail (-2) to the head (+2).
/// let mut positions = vec![Vec3::new(0.0, 0.0, -2.0), Vec3::new(0.0, 0.0, 2.0)];
/// for ring in 1..=9 {
///     let z = -2.0 + 0.4 * ring as f32;
///     for k in 0..8 {
///         let a = k as f32 * core::f32::consts::FRAC_PI_4;
///         positions.push(Vec3::new(0.5 * a.cos(), 0.5 * a.sin(), z));
///     }
/// }
/// let body = rig(&positions, &[], &RigOptions::default().with_bone_length(0.5))?;
/// assert_eq!(body.joints[body.head].position, Vec3::new(0.0, 0.0, 2.0));
/// assert_eq!(body.joints[body.tail].position, Vec3::new(0.0, 0.0, -2.0));
/// assert_eq!(body.spine.len(), 9); // 4 / 0.5 = 8 bones
/// assert_eq!(body.sockets.len(), 6); // every bone but the first and last
/// for socket in &body.sockets {
///     assert!((socket.width - 1.0).abs() < 1e-5); // the diameter
///     // The creature's left is +X (right-handed, Y up, facing +Z), its right −X.
///     assert!(socket.left.x > 0.0 && socket.right.x < 0.0 && socket.top.y > 0.0);
/// }
///
/// // Swimmers: rooted at the head.
/// let swimmer = rig(&positions, &[], &RigOptions::default().with_root(RootAt::Head))?;
/// assert_eq!(swimmer.root(), Some(swimmer.head));
/// # Ok::<(), creature_autorig::AutorigError>(())
/// ```
///
/// # Errors
/// - [`AutorigError::InvalidOption`] / [`AutorigError::InvalidBoneCount`] for bad options;
/// - [`AutorigError::NoVertices`] if there are no vertices (or no triangle uses any);
/// - [`AutorigError::NonFinite`] / [`AutorigError::CoordinateTooLarge`] for a bad vertex;
/// - [`AutorigError::IndexOutOfRange`] for a triangle naming a missing vertex;
/// - [`AutorigError::AllCoincident`], [`AutorigError::Collinear`] or [`AutorigError::NoLengthAlongZ`] when
///   the body has no head–tail axis or no cross-section, or is so short that its joints
///   coincide (then its bones could not all get their sockets).
pub fn rig(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    options: &RigOptions,
) -> Result<Rig, AutorigError> {
    options.validate()?;
    let body = Body::new(positions, triangles)?;
    let (tail_point, head_point) = body.tips(options.centre_tolerance)?;
    // `tips` returns indices into `points`.
    let (tail, head) = (body.points[tail_point], body.points[head_point]);
    let chord = head - tail;
    let length = chord.length();
    let axis = chord / length;
    body.check_cross_section(tail, axis, length)?;

    let slabs = Slabs::new(&body, tail, axis, length);
    let line = if options.follow_medial_line {
        slabs.medial_line(tail, head, axis)
    } else {
        MedialLine::new(vec![tail, head], axis, tail)
    };

    // Joint positions along the line, tail to head.
    let arc = line.length();
    let bones = bone_count(arc, options);
    // `centre`: the spine point that becomes the root (counted from the tail).
    let (positions_along, centre): (Vec<f32>, usize) = match options.root {
        RootAt::Head => (
            (0..=bones).map(|i| arc * i as f32 / bones as f32).collect(),
            bones,
        ),
        RootAt::Centre => {
            let centre_s = (body.centre - tail).dot(axis).clamp(0.0, length);
            let centre_arc = line.arc_at_axis(centre_s);
            // A symmetric body with an odd bone count lands on x.5 exactly, where rounding
            // error would pick either side; shade it so the head side gets the extra bone.
            let share = bones as f32 * centre_arc / arc - CENTRE_SHADE;
            let tail_bones = round_to_usize(share).clamp(1, bones - 1);
            let head_bones = bones - tail_bones;
            let mut along: Vec<f32> = (0..=tail_bones)
                .map(|i| centre_arc * i as f32 / tail_bones as f32)
                .collect();
            along.extend(
                (1..=head_bones)
                    .map(|i| centre_arc + (arc - centre_arc) * i as f32 / head_bones as f32),
            );
            (along, tail_bones)
        }
    };
    let mut points: Vec<Vec3> = positions_along
        .iter()
        .map(|&a| line.at_arc(a).clamp(body.min, body.max))
        .collect();
    // The tips are the tip vertices themselves.
    if let Some(first) = points.first_mut() {
        *first = tail;
    }
    if let Some(last) = points.last_mut() {
        *last = head;
    }

    let (joints, spine) = link(&points, centre);
    // One spine entry per point: `bones + 1` of them, and `validate` keeps `bones >= 2`.
    debug_assert!(spine.len() >= 3);
    let (tail_joint, head_joint) = (spine[0], spine[spine.len() - 1]);
    let sockets = sockets(&slabs, &joints, &spine, axis, tail)?;
    Ok(Rig {
        joints,
        spine,
        sockets,
        head: head_joint,
        tail: tail_joint,
    })
}

/// Rounds a non-negative finite value to the nearest integer.
fn round_to_usize(x: f32) -> usize {
    // Non-negative, so truncation of x + 0.5 rounds half up.
    (x.max(0.0) + 0.5) as usize
}

fn bone_count(arc: f32, options: &RigOptions) -> usize {
    let wanted = arc / options.bone_length;
    let wanted = if wanted.is_finite() {
        round_to_usize(wanted.min(RigOptions::MAX_BONES as f32))
    } else {
        options.max_bones
    };
    wanted.clamp(options.min_bones, options.max_bones)
}

/// The validated body: the surface vertices and their bounding box.
struct Body<'a> {
    /// The surface vertices' positions, in mesh index order: the mesh's own positions when
    /// every vertex is on the surface (the usual case), else a copy of those that are.
    points: Cow<'a, [Vec3]>,
    /// The mesh index of each of `points`, or `None` when point `i` is vertex `i`.
    ids: Option<Vec<u32>>,
    min: Vec3,
    max: Vec3,
    centre: Vec3,
}

impl<'a> Body<'a> {
    fn new(positions: &'a [Vec3], triangles: &[[u32; 3]]) -> Result<Self, AutorigError> {
        // One pass: validate every vertex and take the bounding box of them all.
        let limit = Vec3A::splat(MAX_COORDINATE);
        let mut min = Vec3A::INFINITY;
        let mut max = Vec3A::NEG_INFINITY;
        for (index, &p) in positions.iter().enumerate() {
            let q = Vec3A::from(p);
            // False for NaN too.
            if !q.abs().cmple(limit).all() {
                if !p.is_finite() {
                    return Err(AutorigError::NonFinite { index });
                }
                let value = p
                    .to_array()
                    .into_iter()
                    .find(|v| v.abs() > MAX_COORDINATE)
                    .unwrap_or(p.x);
                return Err(AutorigError::CoordinateTooLarge { index, value });
            }
            min = min.min(q);
            max = max.max(q);
        }
        let (mut min, mut max) = (Vec3::from(min), Vec3::from(max));
        let (points, ids) = if triangles.is_empty() {
            (Cow::Borrowed(positions), None)
        } else {
            let n = positions.len();
            let mut used = vec![false; n];
            for (triangle, tri) in triangles.iter().enumerate() {
                let [a, b, c] = tri.map(|i| i as usize);
                if a < n && b < n && c < n {
                    used[a] = true;
                    used[b] = true;
                    used[c] = true;
                } else {
                    let index = tri
                        .iter()
                        .copied()
                        .find(|&i| i as usize >= n)
                        .unwrap_or(tri[0]);
                    return Err(AutorigError::IndexOutOfRange {
                        triangle,
                        index,
                        vertices: n,
                    });
                }
            }
            if used.iter().all(|&u| u) {
                (Cow::Borrowed(positions), None)
            } else {
                let (points, ids): (Vec<Vec3>, Vec<u32>) = positions
                    .iter()
                    .zip(&used)
                    .enumerate()
                    .filter(|(_, (_, u))| **u)
                    .map(|(i, (&p, _))| (p, u32::try_from(i).unwrap_or(u32::MAX)))
                    .unzip();
                // The box of the vertices that count (at least the three of the first
                // triangle, all in range).
                let start = points[0];
                (min, max) = points
                    .iter()
                    .fold((start, start), |(lo, hi), &p| (lo.min(p), hi.max(p)));
                (Cow::Owned(points), Some(ids))
            }
        };
        if points.is_empty() {
            return Err(AutorigError::NoVertices);
        }
        if min == max {
            return Err(AutorigError::AllCoincident);
        }
        Ok(Self {
            points,
            ids,
            min,
            max,
            centre: (min + max) * 0.5,
        })
    }

    /// The mesh index of surface point `i`.
    #[inline]
    fn id(&self, i: usize) -> u32 {
        match &self.ids {
            // One id per point.
            Some(ids) => ids[i],
            None => u32::try_from(i).unwrap_or(u32::MAX),
        }
    }

    /// The seed's tail and head points (indices into `points`): the Z extremes inside the tube
    /// around the seed's centre line (along Z through the bounding-box centre) or, at each end,
    /// the tube around the Z line through the centre of that end (the centroid of the vertices
    /// within a tenth of the body's length of it, weighted from 1 at the very end down to 0 a
    /// tenth in).
    fn tips(&self, tolerance: f32) -> Result<(usize, usize), AutorigError> {
        let extent = self.max - self.min;
        if !(extent.z > 0.0) {
            return Err(AutorigError::NoLengthAlongZ);
        }
        // The centres (in X and Y) of the rearmost and frontmost tenth of the body.
        let inv_depth = 1.0 / (END_DEPTH * extent.z);
        // Weighted by a tent in Z (1 at the extreme, 0 at `depth` in), so a ring of vertices
        // that only partly reaches into the end barely counts and cannot pull its centre aside.
        // Each end's weighted sum of positions, and its total weight in `w`.
        let mut ends = [Vec4::ZERO; 2];
        for &p in self.points.iter() {
            let point = p.extend(1.0);
            for (end, distance_in) in ends.iter_mut().zip([p.z - self.min.z, self.max.z - p.z]) {
                let w = (1.0 - distance_in * inv_depth).max(0.0);
                *end += point * w;
            }
        }
        let [rear, front] = ends.map(|end| {
            if end.w > 0.0 {
                end.truncate() / end.w
            } else {
                self.centre
            }
        });
        let full = extent.x.max(extent.y);
        let mut half_width = tolerance * full;
        loop {
            let near = |p: Vec3, c: Vec3| {
                (p.x - c.x).abs() <= half_width && (p.y - c.y).abs() <= half_width
            };
            let mut tail: Option<(f32, usize)> = None;
            let mut head: Option<(f32, usize)> = None;
            for (i, &p) in self.points.iter().enumerate() {
                // Strict comparisons: ties keep the lower index. The cheap test on Z first:
                // few vertices beat the extremes found so far.
                let lower = tail.is_none_or(|(z, _)| p.z < z);
                let higher = head.is_none_or(|(z, _)| p.z > z);
                if !(lower || higher) {
                    continue;
                }
                let on_axis = near(p, self.centre);
                if lower && (on_axis || near(p, rear)) {
                    tail = Some((p.z, i));
                }
                if higher && (on_axis || near(p, front)) {
                    head = Some((p.z, i));
                }
            }
            if let (Some((tz, t)), Some((hz, h))) = (tail, head)
                && hz > tz
            {
                return Ok((t, h));
            }
            if half_width >= 2.0 * full {
                // Every vertex is inside both tubes and still no two Zs differ: cannot happen
                // when extent.z > 0, but never loop forever.
                return Err(AutorigError::NoLengthAlongZ);
            }
            half_width = (half_width * 2.0).max(f32::MIN_POSITIVE);
        }
    }

    /// Rejects bodies whose vertices all lie on the tail–head line.
    fn check_cross_section(&self, tail: Vec3, axis: Vec3, length: f32) -> Result<(), AutorigError> {
        let tolerance = 1e-6 * length;
        let off_axis = self.points.iter().any(|&p| {
            let rel = p - tail;
            (rel - axis * rel.dot(axis)).length() > tolerance
        });
        if off_axis {
            Ok(())
        } else {
            Err(AutorigError::Collinear)
        }
    }
}

/// The most slabs: one per 8 vertices, up to this many.
const MAX_SLABS: usize = 64;

/// The surface vertices sorted into slabs across the tail–head axis, with their positions and
/// axis parameters stored in slab order so that slab scans read memory in sequence.
struct Slabs {
    /// Slab `k` holds sorted entries `starts[k]..starts[k + 1]`.
    starts: Vec<usize>,
    /// Mesh index of each sorted entry.
    order: Vec<u32>,
    /// Position of each sorted entry.
    points: Vec<Vec3>,
    /// Axis parameter (distance along the tail–head axis from the tail) of each sorted entry.
    along: Vec<f32>,
    /// Axis length covered by each slab.
    width: f32,
    /// `1 / width`.
    inv_width: f32,
}

impl Slabs {
    fn new(body: &Body<'_>, tail: Vec3, axis: Vec3, length: f32) -> Self {
        let n = body.points.len();
        let count = (n / 8).clamp(4, MAX_SLABS);
        let width = length / count as f32;
        let inv_width = count as f32 / length;
        let last = (count - 1) as f32;
        // Each vertex's axis parameter and slab. (Clamped to 0..=count - 1 as floats, so the
        // truncation is a floor and the slab fits a byte.)
        let along: Vec<f32> = body.points.iter().map(|&p| (p - tail).dot(axis)).collect();
        let slab: Vec<u8> = along
            .iter()
            .map(|&a| (a * inv_width).max(0.0).min(last) as u8)
            .collect();
        // Counting sort, stable, so vertex order within a slab is index order. Tables indexed
        // by a byte need no bounds checks.
        let mut next = [0usize; 256];
        for &k in &slab {
            next[usize::from(k)] += 1;
        }
        let mut starts = Vec::with_capacity(count + 1);
        let mut start = 0;
        for size in next.iter_mut().take(count) {
            starts.push(start);
            (start, *size) = (start + *size, start);
        }
        starts.push(start);
        let (mut order, mut points, mut sorted) =
            (vec![0u32; n], vec![Vec3::ZERO; n], vec![0.0; n]);
        for (i, ((&p, &a), &k)) in body.points.iter().zip(&along).zip(&slab).enumerate() {
            let at = next[usize::from(k)];
            next[usize::from(k)] += 1;
            // `at` < `n`: the counting sort hands out each of `0..n` once.
            order[at] = body.id(i);
            points[at] = p;
            sorted[at] = a;
        }
        Self {
            starts,
            order,
            points,
            along: sorted,
            width,
            inv_width,
        }
    }

    fn count(&self) -> usize {
        self.starts.len() - 1
    }

    /// The sorted entries of the slabs overlapping `[from, to]` along the axis.
    fn between(&self, from: f32, to: f32) -> core::ops::Range<usize> {
        let last = self.count() - 1;
        let first = ((from * self.inv_width).max(0.0) as usize).min(last);
        let end = ((to * self.inv_width).max(0.0) as usize).min(last);
        // `starts` has `count + 1` entries and `first, end <= count - 1`.
        let (a, b) = (self.starts[first], self.starts[end + 1]);
        if a <= b { a..b } else { 0..0 }
    }

    /// Tail vertex, cross-section centroids, head vertex.
    ///
    /// The centroid for slab `k` weighs the vertices of slabs `k - 1` to `k + 1` by a tent
    /// around the slab's centre (weight 1 there, 0 at 1.5 slab widths), so a ring of vertices
    /// that rounding splits across a slab boundary still counts whole and evenly.
    fn medial_line(&self, tail: Vec3, head: Vec3, axis: Vec3) -> MedialLine {
        let count = self.count();
        let inv_reach = self.inv_width / 1.5;
        // Each slab's weighted sum of positions, and its total weight in `w`. One pass over the
        // vertices in slab order, each adding to the windows of its own slab and the two beside
        // it: every window sums its vertices in the same order as a scan of the window would.
        // Window `k`'s sum is `sums[k + 1]`: every slab then adds to three windows, the first
        // and last slabs to a phantom one beyond the ends as well, which is never read.
        let mut sums = vec![Vec4::ZERO; count + 2];
        for slab in 0..count {
            // `starts` has `count + 1` non-decreasing entries, the last `points.len()`;
            // `sums` has `count + 2`.
            let (from, to) = (self.starts[slab], self.starts[slab + 1]);
            let (ps, ss) = (&self.points[from..to], &self.along[from..to]);
            let window = &mut sums[slab..slab + 3];
            // The centres of slabs `slab - 1`, `slab` and `slab + 1`, as `centre` computes them.
            let k = slab as f32;
            let centres = [k - 0.5, k + 0.5, k + 1.5].map(|c| c * self.width);
            let mut acc = [window[0], window[1], window[2]];
            for (&p, &s) in ps.iter().zip(ss) {
                let point = p.extend(1.0);
                for (sum, c) in acc.iter_mut().zip(centres) {
                    let w = (1.0 - (s - c).abs() * inv_reach).max(0.0);
                    *sum += point * w;
                }
            }
            window.copy_from_slice(&acc);
        }
        let sums = &sums[1..=count];
        let mut points = Vec::with_capacity(count + 2);
        points.push(tail);
        // A slab whose window only grazes a few vertices would add a point wherever those
        // happen to be; a point needs the weight of at least one whole vertex.
        points.extend(
            sums.iter()
                .filter(|sum| sum.w >= 1.0)
                .map(|sum| sum.truncate() / sum.w),
        );
        points.push(head);
        MedialLine::new(points, axis, tail)
    }
}

/// A polyline from the tail to the head, with its axis parameters and arc lengths.
struct MedialLine {
    points: Vec<Vec3>,
    /// Axis parameter of each point, non-decreasing.
    along_axis: Vec<f32>,
    /// Arc length at each point, from the tail.
    arc: Vec<f32>,
}

impl MedialLine {
    fn new(points: Vec<Vec3>, axis: Vec3, tail: Vec3) -> Self {
        let mut along_axis = Vec::with_capacity(points.len());
        let mut arc = Vec::with_capacity(points.len());
        let mut previous: Option<(Vec3, f32, f32)> = None;
        for &p in &points {
            let s = (p - tail).dot(axis);
            let (s, a) = match previous {
                // Slab centroids are ordered along the axis up to rounding; keep it monotone.
                Some((q, ps, pa)) => (s.max(ps), pa + q.distance(p)),
                None => (s, 0.0),
            };
            along_axis.push(s);
            arc.push(a);
            previous = Some((p, s, a));
        }
        Self {
            points,
            along_axis,
            arc,
        }
    }

    /// Never empty: the line has at least its tail and head points.
    fn length(&self) -> f32 {
        self.arc[self.arc.len() - 1]
    }

    /// The point at arc length `a`.
    fn at_arc(&self, a: f32) -> Vec3 {
        let k = self.arc.partition_point(|&x| x < a);
        match (k.checked_sub(1), self.points.get(k)) {
            (Some(j), Some(&p)) => {
                let (a0, a1) = (self.arc[j], self.arc[k]);
                let q = self.points[j];
                if a1 > a0 {
                    q.lerp(p, ((a - a0) / (a1 - a0)).clamp(0.0, 1.0))
                } else {
                    p
                }
            }
            (None, Some(&p)) => p,
            // Beyond the last point (the line has at least its tail and head points).
            _ => self.points[self.points.len() - 1],
        }
    }

    /// The arc length where the line reaches axis parameter `s`.
    fn arc_at_axis(&self, s: f32) -> f32 {
        let k = self.along_axis.partition_point(|&x| x < s);
        match (k.checked_sub(1), self.along_axis.get(k)) {
            (Some(j), Some(&s1)) => {
                let s0 = self.along_axis[j];
                let (a0, a1) = (self.arc[j], self.arc[k]);
                if s1 > s0 {
                    a0 + (a1 - a0) * ((s - s0) / (s1 - s0)).clamp(0.0, 1.0)
                } else {
                    a1
                }
            }
            (None, _) => 0.0,
            (Some(_), None) => self.length(),
        }
    }
}

/// Builds the joint tree from spine points ordered tail to head, rooted at `points[centre]`;
/// returns the joints and the spine (joint indices, tail to head). The root is joint 0, then the
/// joints towards the head, then those towards the tail, and the tips (which have no children)
/// come last.
fn link(points: &[Vec3], centre: usize) -> (Vec<Joint>, Vec<usize>) {
    let n = points.len().saturating_sub(1);
    let centre = centre.min(n);
    let mut joints = Vec::with_capacity(points.len());
    let mut spine = vec![0usize; points.len()];
    joints.push(Joint {
        position: points[centre],
        parent: None,
    });
    spine[centre] = 0;
    // Each side without its tip, then the tips; a tip that is the root itself is skipped.
    let mut chain = |range: &mut dyn Iterator<Item = usize>, joints: &mut Vec<Joint>| {
        let mut parent = 0;
        for k in range {
            joints.push(Joint {
                position: points[k],
                parent: Some(parent),
            });
            parent = joints.len() - 1;
            spine[k] = parent;
        }
        parent
    };
    let head_parent = chain(&mut (centre + 1..n), &mut joints);
    let tail_parent = chain(&mut (1..centre).rev(), &mut joints);
    if centre < n {
        joints.push(Joint {
            position: points[n],
            parent: Some(head_parent),
        });
        spine[n] = joints.len() - 1;
    }
    if centre > 0 {
        joints.push(Joint {
            position: points[0],
            parent: Some(tail_parent),
        });
        spine[0] = joints.len() - 1;
    }
    (joints, spine)
}

/// The sockets of every spine bone but the first and last.
///
/// # Errors
/// [`AutorigError::NoLengthAlongZ`] when a bone finds no vertex for a socket: a body so short
/// (under about 1e-38 along Z) that its joints coincide in `f32`.
fn sockets(
    slabs: &Slabs,
    joints: &[Joint],
    spine: &[usize],
    axis: Vec3,
    tail: Vec3,
) -> Result<Vec<Socket>, AutorigError> {
    let bones = spine.len().saturating_sub(1);
    let mut out = Vec::with_capacity(bones.saturating_sub(2));
    for bone in 1..bones.saturating_sub(1) {
        // `bone + 1 < spine.len()`, and spine entries are joint indices.
        let (a, b) = (spine[bone], spine[bone + 1]);
        let (ja, jb) = (&joints[a], &joints[b]);
        // The carrying joint is the parent of the other end.
        let joint = if jb.parent == Some(a) { a } else { b };
        let socket = socket_for(slabs, bone, joint, ja.position, jb.position, axis, tail)
            .ok_or(AutorigError::NoLengthAlongZ)?;
        out.push(socket);
    }
    Ok(out)
}

/// The best vertex for each of a socket's three directions, and the lowest Y, over a set of
/// candidates.
#[derive(Clone, Copy)]
struct Extremes {
    /// Best score per direction (left, right, top); −∞ until a candidate is offered.
    score: [f32; 3],
    /// The sorted entry with that score.
    entry: [usize; 3],
    lowest: f32,
}

impl Extremes {
    const EMPTY: Self = Self {
        score: [f32::NEG_INFINITY; 3],
        entry: [usize::MAX; 3],
        lowest: f32::INFINITY,
    };

    /// Scores a candidate: how far out it is in each direction from `mid` (`side` along the
    /// left direction, so `-side` along the right; `up` along the top), less half its distance
    /// from `mid` along the bone, so that of equally far-out vertices the one level with the
    /// bone's middle wins; ties keep the earlier entry (the lower mesh index within a slab).
    #[inline]
    fn offer(&mut self, entry: usize, side: f32, up: f32, along_bone: f32, y: f32) {
        let penalty = 0.5 * along_bone.abs();
        let scores = [side - penalty, -side - penalty, up - penalty];
        for ((best, at), score) in self.score.iter_mut().zip(&mut self.entry).zip(scores) {
            // Scores are finite, so the first candidate always beats −∞.
            if score > *best {
                *best = score;
                *at = entry;
            }
        }
        if y < self.lowest {
            self.lowest = y;
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn socket_for(
    slabs: &Slabs,
    bone: usize,
    joint: usize,
    from: Vec3,
    to: Vec3,
    axis: Vec3,
    tail: Vec3,
) -> Option<Socket> {
    let mid = (from + to) * 0.5;
    let length = from.distance(to);
    let dir = (to - from).try_normalize().unwrap_or(axis);
    // Square to the bone: left = up × forward (+X for a bone along +Z: right-handed, Y up,
    // facing +Z, the creature's left is +X), right its opposite, top = forward × left.
    let left_dir = Vec3::Y.cross(dir).try_normalize().unwrap_or(Vec3::X);
    let top = dir.cross(left_dir);

    // Candidates: the vertices beside the bone (between the planes square to it through its
    // ends), taken from the axis slabs around it; failing any, all of those slabs' vertices;
    // failing those, every vertex.
    let (s0, s1) = ((from - tail).dot(axis), (to - tail).dot(axis));
    let mut gathered = slabs.between(s0.min(s1) - slabs.width, s0.max(s1) + slabs.width);
    if gathered.is_empty() {
        gathered = 0..slabs.points.len();
    }
    let first = gathered.start;
    let candidates = &slabs.points[gathered];
    let half = 0.5 * length;
    let scan = |beside_only: bool| {
        let mut found = Extremes::EMPTY;
        for (k, &p) in candidates.iter().enumerate() {
            let w = p - mid;
            let along_bone = w.dot(dir);
            if !beside_only || along_bone.abs() <= half {
                found.offer(first + k, w.dot(left_dir), w.dot(top), along_bone, p.y);
            }
        }
        found
    };
    // A coarse ring may have a single vertex beside a short bone, which is then both its
    // left and its right: the socket has no width, and two limbs of a pair would share a
    // point. The slabs' other vertices give it two sides.
    let mut chosen = scan(true);
    if chosen.entry[0] == usize::MAX || chosen.entry[0] == chosen.entry[1] {
        chosen = scan(false);
    }
    let pick = |k: usize| -> Option<(u32, Vec3)> {
        let entry = *chosen.entry.get(k)?;
        Some((*slabs.order.get(entry)?, *slabs.points.get(entry)?))
    };
    let (left_vertex, left) = pick(0)?;
    let (right_vertex, right_point) = pick(1)?;
    let (top_vertex, top_point) = pick(2)?;
    Some(Socket {
        bone,
        joint,
        left,
        right: right_point,
        top: top_point,
        left_vertex,
        right_vertex,
        top_vertex,
        width: left.distance(right_point),
        clearance: (mid.y - chosen.lowest).max(0.0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn link_roots_the_tree_and_puts_the_tips_last() {
        let points: Vec<Vec3> = (0..5).map(|k| Vec3::Z * k as f32).collect();
        // Centre root at point 2.
        let (joints, spine) = link(&points, 2);
        assert_eq!(spine, [4, 2, 0, 1, 3]);
        let parents: Vec<Option<usize>> = joints.iter().map(|j| j.parent).collect();
        assert_eq!(parents, [None, Some(0), Some(0), Some(1), Some(2)]);
        // Head root: a chain from the head back to the tail.
        let (joints, spine) = link(&points, 4);
        assert_eq!(spine, [4, 3, 2, 1, 0]);
        assert_eq!(joints[0].position, Vec3::Z * 4.0);
        assert_eq!(joints[4].parent, Some(3));
    }

    #[test]
    fn bone_count_follows_length_within_limits() {
        let o = RigOptions::DEFAULT
            .with_bone_length(0.5)
            .with_bone_count(3, 10);
        assert_eq!(bone_count(4.0, &o), 8);
        assert_eq!(bone_count(0.1, &o), 3);
        assert_eq!(bone_count(100.0, &o), 10);
    }

    #[test]
    fn medial_line_interpolates_by_arc_and_axis() {
        let line = MedialLine::new(
            alloc::vec![
                Vec3::ZERO,
                Vec3::new(0.0, 1.0, 1.0),
                Vec3::new(0.0, 0.0, 2.0)
            ],
            Vec3::Z,
            Vec3::ZERO,
        );
        let half = line.length() / 2.0;
        assert!(
            line.at_arc(half)
                .abs_diff_eq(Vec3::new(0.0, 1.0, 1.0), 1e-6)
        );
        assert_eq!(line.at_arc(0.0), Vec3::ZERO);
        assert_eq!(line.at_arc(line.length()), Vec3::new(0.0, 0.0, 2.0));
        assert!((line.arc_at_axis(1.0) - half).abs() < 1e-6);
        assert_eq!(line.arc_at_axis(-1.0), 0.0);
    }
}
