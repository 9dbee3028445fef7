//! Shared helpers for the integration tests and benches: the seed's metaball field, a
//! creature-like ball layout, grid sampling, a Hausdorff distance and a plain reference
//! marching squares.

#![allow(dead_code, unreachable_pub)]

pub mod reference;

use creature_march::Ring;
use creature_march::glam::Vec2;

/// The seed's falloff, inside where the sum is at least 1 (a lone ball: its disc of radius R).
#[derive(Debug, Clone)]
pub struct Balls(pub Vec<(Vec2, f32)>);

impl Balls {
    pub fn value(&self, p: Vec2) -> f32 {
        self.0
            .iter()
            .map(|&(c, r)| (0.5 - 0.5 * p.distance_squared(c) / (r * r)).exp())
            .sum()
    }

    pub fn centres(&self) -> Vec<Vec2> {
        self.0.iter().map(|b| b.0).collect()
    }

    /// Cover a bone the seed's way (reference-2d.md §2.4), last-ball rule included.
    pub fn cover(&mut self, from: Vec2, to: Vec2, thickness: f32, m: f32, interior_joint: bool) {
        let radius = thickness * m / (2.0 * (m * m).ln() + 1.0).sqrt();
        let count = (from.distance(to) / (2.97 * thickness) * m).ceil().max(1.0) as usize;
        for i in 0..=count {
            let mut alpha = i as f32 / count as f32;
            if i == count && interior_joint {
                alpha = (i as f32 - 0.5) / count as f32;
            }
            self.0.push((to.lerp(from, alpha), radius));
        }
    }
}

/// Deterministic xorshift32 in [0, 1).
pub struct Rng(pub u32);

impl Rng {
    pub fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        (self.0 >> 8) as f32 / (1u32 << 24) as f32
    }

    pub fn range(&mut self, a: f32, b: f32) -> f32 {
        a + (b - a) * self.next()
    }
}

/// A creature like the seed's median one: a spine of 4 segments along +y (thickness 10–40),
/// limb pairs of 2–3 segments (thickness 5–15) on some spine bones, sockets just outside the
/// body. About 50 balls.
pub fn creature(seed: u32) -> Balls {
    let mut rng = Rng(seed.max(1));
    let mut balls = Balls(Vec::new());
    let mut spine = vec![(Vec2::ZERO, 0.0f32)];
    for i in 1..5 {
        let prev = spine[i - 1].0;
        let t = rng.range(10.0, 40.0);
        let at = prev + Vec2::Y * rng.range(50.0, 100.0);
        balls.cover(prev, at, t, rng.range(1.0, 1.6), i > 1);
        spine.push((at, t));
    }
    for i in 0..spine.len() {
        if rng.next() < 0.5 || i == spine.len() - 1 {
            continue;
        }
        let t_body = spine[i].1.max(spine.get(i + 1).map_or(0.0, |s| s.1));
        let segments = 2 + (rng.next() * 2.0) as usize;
        let lengths: Vec<(f32, f32, f32)> = (0..segments)
            .map(|_| {
                (
                    rng.range(50.0, 80.0),
                    rng.range(5.0, 15.0),
                    rng.range(1.0, 1.6),
                )
            })
            .collect();
        for dir in [-1.0f32, 1.0] {
            let mut at = spine[i].0 + Vec2::X * dir * 1.1 * t_body;
            for (j, &(len, t, m)) in lengths.iter().enumerate() {
                let next = at + Vec2::X * dir * len;
                balls.cover(at, next, t, m, j > 0);
                at = next;
            }
        }
    }
    balls
}

/// Samples `field` on a `width × height` grid of nodes `step × (i0 + x, j0 + y)`.
pub fn sample(
    field: impl Fn(Vec2) -> f32,
    (i0, j0): (i32, i32),
    width: usize,
    height: usize,
    step: f32,
) -> Vec<f32> {
    let mut values = Vec::with_capacity(width * height);
    for y in 0..height {
        for x in 0..width {
            let p = Vec2::new((i0 + x as i32) as f32, (j0 + y as i32) as f32) * step;
            values.push(field(p));
        }
    }
    values
}

/// Grid rings (sample coordinates) mapped to world units.
pub fn to_world(rings: &[Ring], (i0, j0): (i32, i32), step: f32) -> Vec<Ring> {
    rings
        .iter()
        .map(|r| Ring {
            points: r
                .points
                .iter()
                .map(|p| (*p + Vec2::new(i0 as f32, j0 as f32)) * step)
                .collect(),
            ..r.clone()
        })
        .collect()
}

fn distance_to_segment(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

fn distance_to_rings(p: Vec2, rings: &[Ring]) -> f32 {
    rings
        .iter()
        .flat_map(|r| {
            let n = r.points.len();
            (0..n).map(move |i| distance_to_segment(p, r.points[i], r.points[(i + 1) % n]))
        })
        .fold(f32::INFINITY, f32::min)
}

/// Symmetric Hausdorff distance between two sets of polylines (vertex to polyline).
pub fn hausdorff(a: &[Ring], b: &[Ring]) -> f32 {
    let one = |x: &[Ring], y: &[Ring]| {
        x.iter()
            .flat_map(|r| r.points.iter())
            .map(|&p| distance_to_rings(p, y))
            .fold(0.0, f32::max)
    };
    one(a, b).max(one(b, a))
}

/// Whether a ring has no two non-adjacent edges meeting (a quadratic check, independent of the
/// crate's sweep).
pub fn is_simple(ring: &Ring) -> bool {
    let p = &ring.points;
    let n = p.len();
    let orient = |a: Vec2, b: Vec2, c: Vec2| (b - a).perp_dot(c - a) as f64;
    for i in 0..n {
        for j in i + 1..n {
            if j == i + 1 || (i == 0 && j == n - 1) {
                continue;
            }
            let (a, b, c, d) = (p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]);
            let (o1, o2) = (orient(a, b, c), orient(a, b, d));
            let (o3, o4) = (orient(c, d, a), orient(c, d, b));
            if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
                return false;
            }
        }
    }
    true
}

/// `creature-metaball`'s `Field2` as a [`TileField`](creature_march::TileField) that fills
/// each tile through a `BlockSampler` (`Field2::sample_block`'s separable fast path, reusing
/// each ball's row and column factors between tiles): the newtype the README shows. Make a
/// new one per trace, as for a new field: its cache belongs to one grid spacing.
pub struct TiledField<'a>(core::cell::RefCell<creature_metaball::BlockSampler<'a>>);

impl<'a> TiledField<'a> {
    pub fn new(field: &'a creature_metaball::Field2) -> Self {
        Self(core::cell::RefCell::new(field.block_sampler()))
    }
}

impl creature_march::TileField for TiledField<'_> {
    fn value(&self, p: Vec2) -> f32 {
        self.0.borrow().field().value(p)
    }

    fn prefers_tiles(&self) -> bool {
        true
    }

    fn sample_tile(&self, first: [i32; 2], step: f32, out: &mut [f32; creature_march::TILE_NODES]) {
        use creature_march::{TILE_SIZE, node_point};
        let origin = node_point(first, step);
        if self
            .0
            .borrow_mut()
            .sample_block(origin, step, TILE_SIZE, TILE_SIZE, out)
            .is_err()
        {
            // Only for a non-finite origin or step, which the tracer never passes: outside.
            out.fill(f32::NAN);
        }
    }

    fn tile_inside(&self, first: [i32; 2], step: f32, iso: f32) -> bool {
        use creature_march::{TILE_SIZE, node_point};
        let origin = node_point(first, step);
        self.0
            .borrow_mut()
            .block_is_at_least(origin, step, TILE_SIZE, TILE_SIZE, iso)
            .unwrap_or(false)
    }
}

/// `Field2` filling each tile with a plain `Field2::sample_block` call (no cache): the same
/// samples as [`TiledField`], bit for bit.
pub struct UncachedTiledField<'a>(pub &'a creature_metaball::Field2);

impl creature_march::TileField for UncachedTiledField<'_> {
    fn value(&self, p: Vec2) -> f32 {
        self.0.value(p)
    }

    fn prefers_tiles(&self) -> bool {
        true
    }

    fn sample_tile(&self, first: [i32; 2], step: f32, out: &mut [f32; creature_march::TILE_NODES]) {
        use creature_march::{TILE_SIZE, node_point};
        let origin = node_point(first, step);
        if self
            .0
            .sample_block(origin, step, TILE_SIZE, TILE_SIZE, out)
            .is_err()
        {
            out.fill(f32::NAN);
        }
    }
}

/// A point-by-point field that asks to be read tile by tile (with the default `sample_tile`,
/// 64 `value` calls): the same samples as the closure, so the same rings, bit for bit.
pub struct PreferTiles<F>(pub F);

impl<F: Fn(Vec2) -> f32> PreferTiles<F> {
    /// `trace` of the closure, tile by tile (through `trace_field`, default options).
    pub fn trace(
        self,
        hints: &[Vec2],
        step: f32,
        iso: f32,
    ) -> Result<Vec<Ring>, creature_march::MarchError> {
        creature_march::trace_field(
            &self,
            hints,
            step,
            iso,
            &creature_march::MarchOptions::DEFAULT,
        )
    }
}

impl<F: Fn(Vec2) -> f32> creature_march::TileField for PreferTiles<F> {
    fn value(&self, p: Vec2) -> f32 {
        (self.0)(p)
    }

    fn prefers_tiles(&self) -> bool {
        true
    }
}
