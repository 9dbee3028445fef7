//! The planner: the seed's algorithms for walkers, fliers and swimmers, plus the repairs that
//! keep walkers non-overlapping, long-legged enough and stable.

use alloc::vec::Vec;

use glam::{Vec2, Vec3};
use rand_core::Rng;

use crate::random::{below, between, coin, count, unit};
use crate::support::{convex_hull, support_margin};
use crate::{
    Body, CreatureKind, Knee, Limb, LimbKind, LimbsError, Plan, PlanOptions, Repair, Side, Socket,
    Span, WalkerLayout,
};

/// Most first bones the walker's relocation repair tries (the widest ones), bounding its cost.
const RELOCATION_TRIES: usize = 8;

/// Plans the limbs of a creature of `kind` on `body`, drawing every random choice from `rng`.
///
/// - **Walkers** follow the seed: on a long body (length > `long_body_ratio` × mean clearance)
///   or a nearly uniform one (narrowest ≥ `uniform_width_ratio` × widest), as many
///   non-overlapping leg pairs as fit; otherwise a pair on the widest bone, then a second pair on
///   the next widest free bone if it is similar in width, else nothing more when the widest
///   bone is central (a biped), else a balancing pair nearest the opposite end; then arms,
///   likelier the more room there is between the head and the first blocked bone, halfway
///   there. Beyond the seed, overlap is measured with each leg's own sweep (so a large leg
///   blocks more than a small one), bones too low for a leg are skipped (or the body lifted),
///   and the layout is repaired until it is statically stable: the plan's
///   [`stability_margin`](Plan::stability_margin) is at least `min_margin × body length`.
/// - **Fliers**: buzzing wings on the top socket of a random front-half bone (scaled at random
///   per axis) or flapping wings on the middle bone's sides (scaled uniformly); 1 to
///   `max_flier_leg_pairs` hanging leg pairs, shorter on average the more there are, packed from
///   a front-half bone or spread evenly along the body.
/// - **Swimmers**: a random number of dorsal fins on free top sockets and pectoral fin pairs on
///   free side sockets, none overlapping another of its kind, and a tail at the tail tip.
///
/// The same body, options and generator state give the same plan, bit for bit. The number and
/// order of draws from `rng` is part of the output: changing it is a breaking change.
///
/// # Errors
///
/// Anything [`Body::validate`] or [`PlanOptions::validate`] reports.
///
/// # Example
///
/// ```
/// use creature_limbs::{plan, Body, CreatureKind, HeadEnd, LimbKind, PlanOptions, SpineBone};
/// use creature_limbs::glam::Vec3;
/// use creature_limbs::rand_core::{Infallible, TryRng};
///
/// // Any rand_core 0.10 generator works; here a tiny counter-based one.
/// struct Counter(u64);
/// impl TryRng for Counter {
///     type Error = Infallible;
///     fn try_next_u32(&mut self) -> Result<u32, Infallible> {
///         self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
///         Ok((self.0 >> 32) as u32)
///     }
///     fn try_next_u64(&mut self) -> Result<u64, Infallible> {
///         Ok(u64::from(self.try_next_u32()?) << 32 | u64::from(self.try_next_u32()?))
///     }
///     fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
///         for b in dst { *b = self.try_next_u32()? as u8; }
///         Ok(())
///     }
/// }
///
/// // A four-bone body, 1 unit above the ground, wider at the hips.
/// let bones = [0.3, 0.5, 0.35, 0.3].iter().enumerate().map(|(i, &w)| {
///     let z = i as f32 * 0.5;
///     SpineBone::from_sockets(z, Vec3::new(-w / 2.0, 1.0, z), Vec3::new(w / 2.0, 1.0, z),
///         Vec3::new(0.0, 1.0 + w / 2.0, z), 1.0)
/// }).collect();
/// let body = Body::new(bones, 2.5, HeadEnd::Last);
/// let plan = plan(&body, CreatureKind::Walker, &PlanOptions::DEFAULT, &mut Counter(42))?;
/// assert!(plan.leg_pairs() >= 1);
/// assert!(plan.stability_margin.is_some_and(|m| m > 0.0));
/// for leg in plan.limbs_of(LimbKind::Leg) {
///     assert!(leg.foot.is_some());
/// }
/// # Ok::<(), creature_limbs::LimbsError>(())
/// ```
pub fn plan<R: Rng + ?Sized>(
    body: &Body,
    kind: CreatureKind,
    options: &PlanOptions,
    rng: &mut R,
) -> Result<Plan, LimbsError> {
    body.validate()?;
    options.validate()?;
    let ctx = Ctx { body, options };
    let mut out = Plan {
        kind,
        limbs: Vec::new(),
        knee: None,
        lift: 0.0,
        layout: None,
        stability_margin: None,
        center_of_mass: body.center_of_mass(),
        support: Vec::new(),
        repairs: Vec::new(),
    };
    match kind {
        CreatureKind::Walker => ctx.walker(&mut out, rng),
        CreatureKind::Flier => ctx.flier(&mut out, rng),
        CreatureKind::Swimmer => ctx.swimmer(&mut out, rng),
    }
    Ok(out)
}

struct Ctx<'a> {
    body: &'a Body,
    options: &'a PlanOptions,
}

fn draw_knee<R: Rng + ?Sized>(rng: &mut R) -> Knee {
    match below(rng, 3) {
        0 => Knee::Forward,
        1 => Knee::Backward,
        _ => Knee::Sideways,
    }
}

/// Per-axis stretch factors.
fn stretch<R: Rng + ?Sized>(rng: &mut R, range: [f32; 2]) -> Vec3 {
    let x = between(rng, range);
    let y = between(rng, range);
    let z = between(rng, range);
    Vec3::new(x, y, z)
}

impl Ctx<'_> {
    fn n(&self) -> usize {
        self.body.bones.len()
    }

    fn along(&self, bone: usize) -> f32 {
        self.body.bones[bone].along
    }

    /// The stretch `[start, end]` with the bones inside it; `bone` must lie inside.
    fn span(&self, bone: usize, start: f32, end: f32) -> Span {
        let bones = &self.body.bones;
        let mut first = bone;
        while first > 0 && bones[first - 1].along >= start {
            first -= 1;
        }
        let mut last = bone;
        while last + 1 < bones.len() && bones[last + 1].along <= end {
            last += 1;
        }
        Span {
            start,
            end,
            first_bone: first,
            last_bone: last,
        }
    }

    fn centered_span(&self, bone: usize, half: f32) -> Span {
        let a = self.along(bone);
        self.span(bone, a - half, a + half)
    }

    /// Lengths of the left and right walking legs on `bone` with the body raised by `lift`.
    fn walking_legs(&self, bone: usize, lift: f32) -> (f32, f32) {
        let b = &self.body.bones[bone];
        let ground = b.ground();
        (b.left.y - ground + lift, b.right.y - ground + lift)
    }

    /// The sweep of a walking leg pair on `bone`.
    fn pair_span(&self, bone: usize, lift: f32) -> Span {
        let (l, r) = self.walking_legs(bone, lift);
        self.centered_span(bone, self.options.sweep * l.max(r))
    }

    fn free_for_pair(&self, bone: usize, pairs: &[usize], lift: f32) -> bool {
        let span = self.pair_span(bone, lift);
        pairs
            .iter()
            .all(|&p| p != bone && !span.overlaps(&self.pair_span(p, lift)))
    }

    /// Stability margin of walking pairs on `pairs`.
    fn margin(&self, pairs: &[usize], lift: f32) -> f32 {
        let mut feet: Vec<Vec2> = Vec::with_capacity(pairs.len() * 2);
        let mut shortest = f32::INFINITY;
        for &p in pairs {
            let b = &self.body.bones[p];
            feet.push(Vec2::new(b.left.x, b.left.z));
            feet.push(Vec2::new(b.right.x, b.right.z));
            let (l, r) = self.walking_legs(p, lift);
            shortest = shortest.min(l.min(r));
        }
        if feet.is_empty() {
            return f32::NEG_INFINITY;
        }
        support_margin(
            &feet,
            self.options.foot_radius * shortest,
            self.body.center_of_mass(),
        )
    }

    fn walker<R: Rng + ?Sized>(&self, out: &mut Plan, rng: &mut R) {
        let o = self.options;
        let body = self.body;
        let n = self.n();
        out.knee = Some(draw_knee(rng));
        let reverse_fill = coin(rng);

        // Tiny legs: lift a body that is too low everywhere; skip low bones otherwise.
        let min_len = o.min_leg_length * body.length;
        let (highest, max_clear) =
            body.bones
                .iter()
                .enumerate()
                .fold((0, f32::NEG_INFINITY), |(bi, bc), (i, b)| {
                    if b.clearance > bc {
                        (i, b.clearance)
                    } else {
                        (bi, bc)
                    }
                });
        let mut lift = 0.0;
        let threshold = if max_clear < min_len {
            lift = min_len - max_clear;
            out.repairs.push(Repair::Lifted { by: lift });
            max_clear
        } else {
            min_len
        };
        let eligible: Vec<bool> = body
            .bones
            .iter()
            .enumerate()
            .map(|(i, b)| i == highest || b.clearance >= threshold)
            .collect();

        let widest = body.bones.iter().map(|b| b.width).fold(0.0f32, f32::max);
        let narrowest = body
            .bones
            .iter()
            .map(|b| b.width)
            .fold(f32::INFINITY, f32::min);
        let height = body.bones.iter().map(|b| b.clearance).sum::<f32>() / n as f32 + lift;
        let long = body.length > o.long_body_ratio * height;
        let uniform = narrowest >= o.uniform_width_ratio * widest;

        let mut pairs: Vec<usize> = Vec::new();
        let layout = if long || uniform {
            // As many non-overlapping pairs as fit: interval scheduling by earliest end (or, in
            // the reverse direction, latest start), which places the most pairs.
            let mut order: Vec<usize> = (0..n).filter(|&i| eligible[i]).collect();
            if reverse_fill {
                order.sort_by(|&a, &b| {
                    let (sa, sb) = (self.pair_span(a, lift), self.pair_span(b, lift));
                    sb.start.total_cmp(&sa.start).then(b.cmp(&a))
                });
            } else {
                order.sort_by(|&a, &b| {
                    let (sa, sb) = (self.pair_span(a, lift), self.pair_span(b, lift));
                    sa.end.total_cmp(&sb.end).then(a.cmp(&b))
                });
            }
            for i in order {
                if self.free_for_pair(i, &pairs, lift) {
                    pairs.push(i);
                }
            }
            WalkerLayout::Fill
        } else {
            let widest_any = argmax(n, |i| body.bones[i].width, |_| true);
            let first = argmax(n, |i| body.bones[i].width, |i| eligible[i]);
            if let (Some(w), Some(f)) = (widest_any, first)
                && w != f
            {
                out.repairs.push(Repair::SkippedLowBone {
                    bone: w,
                    leg_length: body.bones[w].clearance + lift,
                });
            }
            let Some(first) = first else {
                // Unreachable: the highest bone is always eligible. Fall back to it anyway.
                pairs.push(highest);
                return self.finish_walker(out, pairs, lift, &eligible, WalkerLayout::Biped, rng);
            };
            pairs.push(first);
            let next = argmax(
                n,
                |i| body.bones[i].width,
                |i| eligible[i] && self.free_for_pair(i, &pairs, lift),
            );
            let first_width = body.bones[first].width;
            match next {
                Some(s) if body.bones[s].width >= o.second_pair_ratio * first_width => {
                    pairs.push(s);
                    WalkerLayout::TwoWide
                }
                _ => {
                    let off = (2 * first).abs_diff(n - 1);
                    if off <= 2 * o.central_bones {
                        WalkerLayout::Biped
                    } else {
                        let opposite = self.along(0) + self.along(n - 1) - self.along(first);
                        let balance = argmax(
                            n,
                            |i| -(self.along(i) - opposite).abs(),
                            |i| eligible[i] && self.free_for_pair(i, &pairs, lift),
                        );
                        if let Some(b) = balance {
                            pairs.push(b);
                        }
                        WalkerLayout::Balanced
                    }
                }
            }
        };
        self.finish_walker(out, pairs, lift, &eligible, layout, rng);
    }

    /// Repairs the layout until stable, adds arms, and writes the walker's plan.
    fn finish_walker<R: Rng + ?Sized>(
        &self,
        out: &mut Plan,
        mut pairs: Vec<usize>,
        mut lift: f32,
        eligible: &[bool],
        layout: WalkerLayout,
        rng: &mut R,
    ) {
        let body = self.body;
        let n = self.n();
        let required = self.options.min_margin * body.length;
        // Extra pairs obey the tiny-leg rule too.
        let mut margin = self.margin(&pairs, lift);

        // 1. One more pair, as long as it helps.
        if margin < required {
            let (p, m, added) = self.grow(pairs.clone(), lift, eligible);
            if m > margin {
                for &a in &added {
                    out.repairs.push(Repair::AddedPair { bone: a });
                }
                pairs = p;
                margin = m;
            }
        }
        // 2. Another first bone (the first pair blocked every slot that could balance it).
        if margin < required {
            let from = pairs.first().copied().unwrap_or(0);
            let mut widest: Vec<usize> = (0..n).filter(|&i| eligible[i] && i != from).collect();
            widest.sort_by(|&a, &b| {
                body.bones[b]
                    .width
                    .total_cmp(&body.bones[a].width)
                    .then(a.cmp(&b))
            });
            for &start in widest.iter().take(RELOCATION_TRIES) {
                let (p, m, _) = self.grow(alloc::vec![start], lift, eligible);
                if m >= required {
                    out.repairs.push(Repair::MovedFirstPair { from, to: start });
                    pairs = p;
                    margin = m;
                    break;
                }
            }
        }
        // 3. Lift the body so one pair under the centre of mass has feet big enough to stand.
        if margin < required {
            let com = body.center_of_mass();
            let dist = |i: usize| {
                let b = &body.bones[i];
                let feet = [
                    Vec2::new(b.left.x, b.left.z),
                    Vec2::new(b.right.x, b.right.z),
                ];
                -crate::support::signed_distance(&convex_hull(&feet), com)
            };
            let best = argmax(n, |i| -dist(i), |_| true).unwrap_or(0);
            let (l, r) = self.walking_legs(best, 0.0);
            let shortest = l.min(r);
            let foot = self.options.foot_radius;
            let mut new_lift = lift.max((dist(best) + required) / foot - shortest);
            pairs = alloc::vec![best];
            // Guard against rounding: nudge until the measured margin clears the bar.
            for _ in 0..8 {
                margin = self.margin(&pairs, new_lift);
                if margin >= required {
                    break;
                }
                new_lift += (required - margin) / foot + required * 1e-3;
            }
            out.repairs.push(Repair::Lifted {
                by: new_lift - lift,
            });
            lift = new_lift;
        }

        // Legs, head to tail, left then right.
        pairs.sort_by_key(|&p| body.head_rank(p));
        for &p in &pairs {
            let b = &body.bones[p];
            let (l, r) = self.walking_legs(p, lift);
            let span = self.pair_span(p, lift);
            let floor = b.ground() - lift;
            let idx = out.limbs.len();
            for (socket, side, point, len, mirror) in [
                (Socket::Left, Side::Left, b.left, l, idx + 1),
                (Socket::Right, Side::Right, b.right, r, idx),
            ] {
                out.limbs.push(Limb {
                    kind: LimbKind::Leg,
                    variant: 0,
                    bone: p,
                    socket,
                    side,
                    mirror: Some(mirror),
                    scale: Vec3::splat(len),
                    length: len,
                    foot: Some(Vec3::new(point.x, floor, point.z)),
                    span,
                });
            }
        }
        out.layout = Some(layout);
        out.lift = lift;
        out.stability_margin = Some(margin);
        let feet: Vec<Vec2> = out
            .limbs
            .iter()
            .filter_map(|l| l.foot.map(|f| Vec2::new(f.x, f.z)))
            .collect();
        out.support = convex_hull(&feet);

        self.arms(out, &pairs, lift, rng);
    }

    /// Greedily adds the pair that most raises the margin until the margin is enough or no pair
    /// raises it. Returns the pairs, their margin and the bones added.
    fn grow(
        &self,
        mut pairs: Vec<usize>,
        lift: f32,
        eligible: &[bool],
    ) -> (Vec<usize>, f32, Vec<usize>) {
        let required = self.options.min_margin * self.body.length;
        let mut margin = self.margin(&pairs, lift);
        let mut added = Vec::new();
        while margin < required {
            let mut best: Option<(usize, f32)> = None;
            for (i, &ok) in eligible.iter().enumerate() {
                if !ok || !self.free_for_pair(i, &pairs, lift) {
                    continue;
                }
                pairs.push(i);
                let m = self.margin(&pairs, lift);
                pairs.pop();
                if m > margin && best.is_none_or(|(_, bm)| m > bm) {
                    best = Some((i, m));
                }
            }
            let Some((i, m)) = best else { break };
            pairs.push(i);
            added.push(i);
            margin = m;
        }
        (pairs, margin, added)
    }

    /// Arms, sometimes: halfway between the head and the first bone a leg blocks.
    fn arms<R: Rng + ?Sized>(&self, out: &mut Plan, pairs: &[usize], lift: f32, rng: &mut R) {
        let body = self.body;
        let n = self.n();
        let leg_spans: Vec<Span> = pairs.iter().map(|&p| self.pair_span(p, lift)).collect();
        let blocked = |i: usize| {
            let a = self.along(i);
            pairs.contains(&i) || leg_spans.iter().any(|s| s.start <= a && a <= s.end)
        };
        let free = (0..n).take_while(|&k| !blocked(body.from_head(k))).count();
        let chance = (self.options.arm_chance * free as f32 / n as f32).min(1.0);
        let draw = unit(rng);
        if free == 0 || !(draw < chance) {
            return;
        }
        let head_along = self.along(body.from_head(0));
        let stop_along = if free < n {
            self.along(body.from_head(free))
        } else {
            self.along(body.from_head(n - 1))
        };
        let target = (head_along + stop_along) * 0.5;
        let Some(bone) = argmax(
            n,
            |i| -(self.along(i) - target).abs(),
            |i| body.head_rank(i) < free,
        ) else {
            return;
        };
        let t = between(rng, self.options.arm_length);
        let (l, r) = self.walking_legs(bone, lift);
        let mut length = t * l.min(r);
        let a = self.along(bone);
        let room = leg_spans
            .iter()
            .map(|s| if a < s.start { s.start - a } else { a - s.end })
            .fold(f32::INFINITY, f32::min);
        let sweep = self.options.sweep;
        if sweep * length > room {
            length = room / sweep * 0.999;
            if length < self.options.min_leg_length * body.length || !(length > 0.0) {
                out.repairs.push(Repair::DroppedArms);
                return;
            }
            out.repairs.push(Repair::ShortenedArms { length });
        }
        let span = self.centered_span(bone, sweep * length);
        let idx = out.limbs.len();
        for (socket, side, mirror) in [
            (Socket::Left, Side::Left, idx + 1),
            (Socket::Right, Side::Right, idx),
        ] {
            out.limbs.push(Limb {
                kind: LimbKind::Arm,
                variant: 0,
                bone,
                socket,
                side,
                mirror: Some(mirror),
                scale: Vec3::splat(length),
                length,
                foot: None,
                span,
            });
        }
    }

    fn flier<R: Rng + ?Sized>(&self, out: &mut Plan, rng: &mut R) {
        let o = self.options;
        let body = self.body;
        let n = self.n();
        let len = body.length;
        out.knee = Some(draw_knee(rng));
        let front = n.div_ceil(2);

        // Wings.
        let buzzing = coin(rng);
        let mut wing_bone_sides: Option<usize> = None;
        if buzzing {
            let variant = u8::from(coin(rng));
            let size = between(rng, o.buzzing_wing_size) * len;
            let scale = stretch(rng, o.stretch) * size;
            let bone = body.from_head(below(rng, front));
            let span = self.centered_span(bone, 0.5 * scale.z);
            self.push_pair(
                out,
                LimbKind::BuzzingWing,
                variant,
                bone,
                true,
                scale,
                scale.x,
                span,
            );
        } else {
            let size = between(rng, o.flapping_wing_size) * len;
            let bone = body.from_head((n - 1) / 2);
            let span = self.centered_span(bone, 0.5 * size);
            wing_bone_sides = Some(bone);
            self.push_pair(
                out,
                LimbKind::FlappingWing,
                0,
                bone,
                false,
                Vec3::splat(size),
                size,
                span,
            );
        }

        // Legs.
        let drawn = if o.max_flier_leg_pairs == 0 {
            0
        } else {
            count(rng, [1, o.max_flier_leg_pairs])
        };
        let packed = coin(rng);
        let u = unit(rng);
        let mut t = u;
        for _ in 0..(drawn.saturating_sub(1) / 2) {
            t *= u;
        }
        let [lo, hi] = o.flier_leg_length;
        let mut leg = (lo + (hi - lo) * t) * len;
        let available: Vec<usize> = (0..n)
            .map(|k| body.from_head(k))
            .filter(|&i| Some(i) != wing_bone_sides)
            .collect();
        let sweep = o.sweep;
        let mut bones: Vec<usize> = Vec::new();
        if drawn > 0 && !available.is_empty() {
            if packed {
                let front_bones: Vec<usize> = available
                    .iter()
                    .copied()
                    .filter(|&i| body.head_rank(i) < front)
                    .collect();
                let pool = if front_bones.is_empty() {
                    &available
                } else {
                    &front_bones
                };
                let first = pool[below(rng, pool.len())];
                bones.push(first);
                let half = sweep * leg;
                while bones.len() < drawn {
                    let next = available.iter().copied().find(|&i| {
                        let s = self.centered_span(i, half);
                        bones
                            .iter()
                            .all(|&b| b != i && !s.overlaps(&self.centered_span(b, half)))
                    });
                    match next {
                        Some(i) => bones.push(i),
                        None => break,
                    }
                }
            } else {
                let m = available.len();
                let mut c = drawn.min(m);
                loop {
                    bones.clear();
                    if c <= 1 {
                        bones.push(available[(m - 1) / 2]);
                        break;
                    }
                    for j in 0..c {
                        let k = (2 * j * (m - 1) + (c - 1)) / (2 * (c - 1));
                        bones.push(available[k.min(m - 1)]);
                    }
                    let gap = bones
                        .windows(2)
                        .map(|w| (self.along(w[0]) - self.along(w[1])).abs())
                        .fold(f32::INFINITY, f32::min);
                    if 2.0 * sweep * leg <= gap {
                        break;
                    }
                    let allowed = gap / (2.0 * sweep) * 0.999;
                    if allowed >= lo * len && allowed > 0.0 {
                        leg = allowed;
                        out.repairs.push(Repair::ShortenedLegs { length: leg });
                        break;
                    }
                    c -= 1;
                }
            }
        }
        if bones.len() < drawn {
            out.repairs.push(Repair::FewerThanDrawn {
                kind: LimbKind::Leg,
                drawn,
                placed: bones.len(),
            });
        }
        bones.sort_by_key(|&b| body.head_rank(b));
        for &bone in &bones {
            let b = &body.bones[bone];
            let span = self.centered_span(bone, sweep * leg);
            let idx = out.limbs.len();
            for (socket, side, point, mirror) in [
                (Socket::Left, Side::Left, b.left, idx + 1),
                (Socket::Right, Side::Right, b.right, idx),
            ] {
                out.limbs.push(Limb {
                    kind: LimbKind::Leg,
                    variant: 0,
                    bone,
                    socket,
                    side,
                    mirror: Some(mirror),
                    scale: Vec3::splat(leg),
                    length: leg,
                    foot: Some(point - Vec3::Y * leg),
                    span,
                });
            }
        }
    }

    /// Pushes a left/right pair; `top` puts both on the top socket.
    #[allow(clippy::too_many_arguments)]
    fn push_pair(
        &self,
        out: &mut Plan,
        kind: LimbKind,
        variant: u8,
        bone: usize,
        top: bool,
        scale: Vec3,
        length: f32,
        span: Span,
    ) {
        let idx = out.limbs.len();
        for (socket, side, mirror) in [
            (Socket::Left, Side::Left, idx + 1),
            (Socket::Right, Side::Right, idx),
        ] {
            out.limbs.push(Limb {
                kind,
                variant,
                bone,
                socket: if top { Socket::Top } else { socket },
                side,
                mirror: Some(mirror),
                scale,
                length,
                foot: None,
                span,
            });
        }
    }

    fn swimmer<R: Rng + ?Sized>(&self, out: &mut Plan, rng: &mut R) {
        let o = self.options;
        let body = self.body;
        let n = self.n();
        let len = body.length;

        // Dorsal fins on free top sockets, no two overlapping.
        let drawn = count(rng, o.dorsal_fins);
        let mut spans: Vec<(usize, Span)> = Vec::new();
        for _ in 0..drawn {
            let variant = u8::from(coin(rng));
            let scale = stretch(rng, o.stretch) * (between(rng, o.fin_size) * len);
            let free = self.free_bones(&spans, 0.5 * scale.z);
            if free.is_empty() {
                break;
            }
            let bone = free[below(rng, free.len())];
            let span = self.centered_span(bone, 0.5 * scale.z);
            spans.push((bone, span));
            out.limbs.push(Limb {
                kind: LimbKind::DorsalFin,
                variant,
                bone,
                socket: Socket::Top,
                side: Side::Center,
                mirror: None,
                scale,
                length: scale.y,
                foot: None,
                span,
            });
        }
        if spans.len() < drawn {
            out.repairs.push(Repair::FewerThanDrawn {
                kind: LimbKind::DorsalFin,
                drawn,
                placed: spans.len(),
            });
        }

        // Pectoral fin pairs on free side sockets.
        let drawn = count(rng, o.pectoral_pairs);
        let mut spans: Vec<(usize, Span)> = Vec::new();
        for _ in 0..drawn {
            let variant = u8::from(coin(rng));
            let scale = stretch(rng, o.stretch) * (between(rng, o.fin_size) * len);
            let free = self.free_bones(&spans, 0.5 * scale.z);
            if free.is_empty() {
                break;
            }
            let bone = free[below(rng, free.len())];
            let span = self.centered_span(bone, 0.5 * scale.z);
            spans.push((bone, span));
            self.push_pair(
                out,
                LimbKind::PectoralFin,
                variant,
                bone,
                false,
                scale,
                scale.x,
                span,
            );
        }
        if spans.len() < drawn {
            out.repairs.push(Repair::FewerThanDrawn {
                kind: LimbKind::PectoralFin,
                drawn,
                placed: spans.len(),
            });
        }

        // The tail, at the tail tip, reaching away from the head.
        let variant = u8::from(coin(rng));
        let scale = stretch(rng, o.stretch) * (between(rng, o.tail_size) * len);
        let bone = body.from_head(n - 1);
        let a = self.along(bone);
        let head_is_ahead = self.along(body.from_head(0)) >= a;
        let span = if head_is_ahead {
            self.span(bone, a - scale.z, a)
        } else {
            self.span(bone, a, a + scale.z)
        };
        out.limbs.push(Limb {
            kind: LimbKind::Tail,
            variant,
            bone,
            socket: Socket::Tip,
            side: Side::Center,
            mirror: None,
            scale,
            length: scale.z,
            foot: None,
            span,
        });
    }

    /// Bones, in index order, where a part of half-footprint `half` overlaps none of `taken`.
    fn free_bones(&self, taken: &[(usize, Span)], half: f32) -> Vec<usize> {
        (0..self.n())
            .filter(|&i| {
                let s = self.centered_span(i, half);
                taken.iter().all(|(b, t)| *b != i && !s.overlaps(t))
            })
            .collect()
    }
}

/// The index in `0..n` passing `keep` with the largest `key` (the lowest index on ties).
fn argmax(n: usize, key: impl Fn(usize) -> f32, keep: impl Fn(usize) -> bool) -> Option<usize> {
    let mut best: Option<(usize, f32)> = None;
    for i in 0..n {
        if !keep(i) {
            continue;
        }
        let k = key(i);
        if best.is_none_or(|(_, bk)| k > bk) {
            best = Some((i, k));
        }
    }
    best.map(|(i, _)| i)
}
