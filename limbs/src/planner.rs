//! The planner: the seed's algorithms for walkers, fliers and swimmers, plus the repairs that
//! keep walkers non-overlapping, long-legged enough and stable.

use alloc::vec::Vec;

use glam::{Vec2, Vec3};
use rand_core::Rng;

use crate::random::{below, between, coin, count, unit};
use crate::sort::sort_by;
use crate::support::{convex_hull, support_margin};
use crate::{
    Body, CreatureKind, Knee, Limb, LimbKind, LimbsError, Plan, PlanOptions, Repair, Side, Socket,
    Span, WalkerLayout,
};

/// How many first bones (the widest) and how many one- or two-pair bases (the most stable) the
/// walker's rebuild tries, bounding its cost.
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
///   blocks more than a small one), bones too low for a leg of `min_leg_length` are skipped
///   (or, when every bone is, the body is lifted), and the layout is checked for static
///   stability: the centre of mass must lie at least `min_margin × body length` inside the
///   feet's convex hull grown by the fixed foot radius `foot_radius × body length`. A layout
///   short of that gets balancing pairs; if none is enough, the layout is rebuilt from other
///   bones; and as a last resort, the strides are shortened until pairs that stand fit (a
///   short spine under long legs). Every step uses only bones tall enough for legs and never
///   overlaps sweeps; every change is listed in [`Plan::repairs`] and [`Plan::layout`] names
///   the final layout.
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
/// Anything [`Body::validate`] or [`PlanOptions::validate`] reports; for walkers,
/// [`LimbsError::NoStableLayout`] when no layout can stand: even legs on every bone, with the
/// body lifted until each is tall enough for them, leave the centre of mass outside the support
/// region or inside by less than the required margin (e.g. a `min_margin` wider than the body;
/// a heavy end too low for legs is lifted instead, [`Repair::LiftedToStand`]). The planner
/// never returns a walker that does not stand.
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
///     // Facing +Z (the head is the last bone): the left socket is on +X.
///     SpineBone::from_sockets(z, Vec3::new(w / 2.0, 1.0, z), Vec3::new(-w / 2.0, 1.0, z),
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
    let ctx = Ctx {
        body,
        options,
        com: body.center_of_mass(),
        foot_radius: options.foot_radius * body.length,
        sweep: options.sweep,
    };
    let mut out = Plan {
        kind,
        limbs: Vec::new(),
        knee: None,
        lift: 0.0,
        layout: None,
        stability_margin: None,
        center_of_mass: ctx.com,
        support: Vec::new(),
        repairs: Vec::new(),
    };
    match kind {
        CreatureKind::Walker => ctx.walker(&mut out, rng)?,
        CreatureKind::Flier => ctx.flier(&mut out, rng),
        CreatureKind::Swimmer => ctx.swimmer(&mut out, rng),
        // No limbs: it moves by bending its body.
        CreatureKind::Slitherer => {}
    }
    Ok(out)
}

#[derive(Clone, Copy)]
struct Ctx<'a> {
    body: &'a Body,
    options: &'a PlanOptions,
    /// The body's centre of mass in the ground plane.
    com: Vec2,
    /// Every foot's contact radius, in body units.
    foot_radius: f32,
    /// Half a walking leg's (or arm's) sweep per unit of its length: `options.sweep`, unless
    /// the walker's last repair shortened the strides.
    sweep: f32,
}

/// The smallest lift from `from` at which `legs(lift)` (a leg length that grows with the
/// lift) is at least `min_len` and positive, and whether it got there: `from` when it already
/// is; else the shortfall added, then nudged up an ulp at a time, as rounding can leave the
/// sum just short.
fn lift_until(from: f32, min_len: f32, legs: impl Fn(f32) -> f32) -> (f32, bool) {
    let long_enough = |leg: f32| leg >= min_len && leg > 0.0;
    let now = legs(from);
    if long_enough(now) {
        return (from, true);
    }
    let mut lift = from + (min_len - now).max(0.0);
    let step = (min_len * f32::EPSILON).max(f32::MIN_POSITIVE);
    for _ in 0..64 {
        if long_enough(legs(lift)) {
            return (lift, true);
        }
        lift += step.max(lift * f32::EPSILON);
    }
    (lift, long_enough(legs(lift)))
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

    /// The shorter walking leg on `bone` with the body raised by `lift`: the height of its
    /// lower side socket above the ground.
    fn shortest_leg(&self, bone: usize, lift: f32) -> f32 {
        let (l, r) = self.walking_legs(bone, lift);
        l.min(r)
    }

    /// The sweep of a walking leg pair on `bone`.
    fn pair_span(&self, bone: usize, lift: f32) -> Span {
        let (l, r) = self.walking_legs(bone, lift);
        self.centered_span(bone, self.sweep * l.max(r))
    }

    fn free_for_pair(&self, bone: usize, pairs: &[usize], lift: f32) -> bool {
        let span = self.pair_span(bone, lift);
        pairs
            .iter()
            .all(|&p| p != bone && !span.overlaps(&self.pair_span(p, lift)))
    }

    /// Stability margin of walking pairs on `pairs`: feet under the side sockets, each with
    /// the fixed contact radius `foot_radius × body length` (leg size plays no part).
    fn margin(&self, pairs: &[usize]) -> f32 {
        if pairs.is_empty() {
            return f32::NEG_INFINITY;
        }
        let mut feet: Vec<Vec2> = Vec::with_capacity(pairs.len() * 2);
        for &p in pairs {
            let b = &self.body.bones[p];
            feet.push(Vec2::new(b.left.x, b.left.z));
            feet.push(Vec2::new(b.right.x, b.right.z));
        }
        support_margin(&feet, self.foot_radius, self.com)
    }

    /// The lift that gives the highest bone legs of `min_len` (zero when it already has them),
    /// recorded as a repair when non-zero.
    fn lift_for_min_legs(&self, out: &mut Plan, min_len: f32) -> f32 {
        let tallest = |lift: f32| {
            (0..self.n())
                .map(|i| self.shortest_leg(i, lift))
                .fold(f32::NEG_INFINITY, f32::max)
        };
        let (lift, _) = lift_until(0.0, min_len, tallest);
        if lift > 0.0 {
            out.repairs.push(Repair::Lifted { by: lift });
        }
        lift
    }

    /// The last repair of a walker that cannot stand on the bones tall enough for legs: the
    /// body raised (from `lift`) until every bone's legs are at least `min_len`, and the layout
    /// rebuilt on all bones, with shorter strides if needed. The pairs, margin, sweep and the
    /// whole lift; `None` when every bone was eligible already or it still cannot stand.
    fn lifted_to_stand(
        &self,
        lift: f32,
        min_len: f32,
        eligible: &[bool],
    ) -> Option<(Vec<usize>, f32, f32, f32)> {
        if eligible.iter().all(|&e| e) {
            return None;
        }
        let shortest = |lift: f32| {
            (0..self.n())
                .map(|i| self.shortest_leg(i, lift))
                .fold(f32::INFINITY, f32::min)
        };
        let (full, reached) = lift_until(lift, min_len, shortest);
        if !reached {
            return None;
        }
        let all = alloc::vec![true; self.n()];
        if let Ok((pairs, margin)) = self.rebuild(full, &all) {
            return Some((pairs, margin, self.sweep, full));
        }
        self.shortened_strides(full, &all)
            .ok()
            .map(|(pairs, margin, sweep)| (pairs, margin, sweep, full))
    }

    fn walker<R: Rng + ?Sized>(&self, out: &mut Plan, rng: &mut R) -> Result<(), LimbsError> {
        let o = self.options;
        let body = self.body;
        let n = self.n();
        out.knee = Some(draw_knee(rng));
        let reverse_fill = coin(rng);

        // Tiny legs: lift a body that is too low everywhere; pass over low bones otherwise.
        let min_len = o.min_leg_length * body.length;
        let mut lift = self.lift_for_min_legs(out, min_len);
        let eligible: Vec<bool> = (0..n)
            .map(|i| {
                let leg = self.shortest_leg(i, lift);
                leg >= min_len && leg > 0.0
            })
            .collect();
        for (i, &ok) in eligible.iter().enumerate() {
            if !ok {
                out.repairs.push(Repair::SkippedLowBone {
                    bone: i,
                    leg_length: self.shortest_leg(i, lift),
                });
            }
        }

        // The seed's layout, on eligible bones, with leg-size-aware overlap.
        let (seed_pairs, rule) = self.seed_layout(lift, &eligible, reverse_fill);

        // Repairs: balancing pairs first, then a rebuilt layout, else an error.
        let required = o.min_margin * body.length;
        let mut pairs = seed_pairs.clone();
        let mut margin = self.margin(&pairs);
        let mut rebuilt = false;
        let mut sweep = self.sweep;
        if margin < required {
            let (grown, m) = self.grow(pairs.clone(), lift, &eligible);
            if m >= required {
                pairs = grown;
                margin = m;
            } else {
                if let Ok((p, m2)) = self.rebuild(lift, &eligible) {
                    pairs = p;
                    margin = m2;
                } else {
                    match self.shortened_strides(lift, &eligible) {
                        Ok((p, m2, s)) => {
                            out.repairs.push(Repair::ShortenedStride { sweep: s });
                            pairs = p;
                            margin = m2;
                            sweep = s;
                        }
                        Err(best) => {
                            // Last resort: raise the body until every bone is tall enough.
                            let Some((p, m2, s, full)) =
                                self.lifted_to_stand(lift, min_len, &eligible)
                            else {
                                return Err(LimbsError::NoStableLayout {
                                    margin: best,
                                    required,
                                });
                            };
                            out.repairs.retain(|r| {
                                !matches!(r, Repair::Lifted { .. } | Repair::SkippedLowBone { .. })
                            });
                            out.repairs.push(Repair::LiftedToStand { by: full });
                            if s < self.sweep {
                                out.repairs.push(Repair::ShortenedStride { sweep: s });
                            }
                            pairs = p;
                            margin = m2;
                            sweep = s;
                            lift = full;
                        }
                    }
                }
                rebuilt = true;
            }
        }
        for &p in &seed_pairs {
            if !pairs.contains(&p) {
                out.repairs.push(Repair::DroppedPair { bone: p });
            }
        }
        for &p in &pairs {
            if !seed_pairs.contains(&p) {
                out.repairs.push(Repair::AddedPair { bone: p });
            }
        }
        let layout = if rebuilt {
            WalkerLayout::Rebuilt
        } else {
            match rule {
                WalkerLayout::Biped | WalkerLayout::Balanced if pairs.len() == 1 => {
                    WalkerLayout::Biped
                }
                WalkerLayout::Biped | WalkerLayout::Balanced => WalkerLayout::Balanced,
                other => other,
            }
        };

        // Legs, head to tail, left then right, with the final strides.
        let ctx = Ctx { sweep, ..*self };
        ctx.write_walker(out, pairs, lift, margin, layout, rng);
        Ok(())
    }

    /// Writes a walker's legs, layout, lift, margin and support, then adds arms.
    fn write_walker<R: Rng + ?Sized>(
        &self,
        out: &mut Plan,
        mut pairs: Vec<usize>,
        lift: f32,
        margin: f32,
        layout: WalkerLayout,
        rng: &mut R,
    ) {
        let body = self.body;
        sort_by(&mut pairs, &mut |&a, &b| {
            body.head_rank(a).cmp(&body.head_rank(b))
        });
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

    /// The seed's walker rules on the eligible bones: the pairs and the rule that placed them
    /// (`Balanced` even when no balancing bone was free; the caller settles the final name).
    fn seed_layout(
        &self,
        lift: f32,
        eligible: &[bool],
        reverse_fill: bool,
    ) -> (Vec<usize>, WalkerLayout) {
        let o = self.options;
        let body = self.body;
        let n = self.n();
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
        if long || uniform {
            // As many non-overlapping pairs as fit: interval scheduling by earliest end (or, in
            // the reverse direction, latest start), which places the most pairs.
            let mut order: Vec<usize> = (0..n).filter(|&i| eligible[i]).collect();
            if reverse_fill {
                sort_by(&mut order, &mut |&a, &b| {
                    let (sa, sb) = (self.pair_span(a, lift), self.pair_span(b, lift));
                    sb.start.total_cmp(&sa.start).then(b.cmp(&a))
                });
            } else {
                sort_by(&mut order, &mut |&a, &b| {
                    let (sa, sb) = (self.pair_span(a, lift), self.pair_span(b, lift));
                    sa.end.total_cmp(&sb.end).then(a.cmp(&b))
                });
            }
            for i in order {
                if self.free_for_pair(i, &pairs, lift) {
                    pairs.push(i);
                }
            }
            return (pairs, WalkerLayout::Fill);
        }
        let Some(first) = argmax(n, |i| body.bones[i].width, |i| eligible[i]) else {
            return (pairs, WalkerLayout::Balanced);
        };
        pairs.push(first);
        let next = argmax(
            n,
            |i| body.bones[i].width,
            |i| eligible[i] && self.free_for_pair(i, &pairs, lift),
        );
        if let Some(s) = next
            && body.bones[s].width >= o.second_pair_ratio * body.bones[first].width
        {
            pairs.push(s);
            return (pairs, WalkerLayout::TwoWide);
        }
        let off = (2 * first).abs_diff(n - 1);
        if off <= 2 * o.central_bones {
            return (pairs, WalkerLayout::Biped);
        }
        let opposite = self.along(0) + self.along(n - 1) - self.along(first);
        let balance = argmax(
            n,
            |i| -(self.along(i) - opposite).abs(),
            |i| eligible[i] && self.free_for_pair(i, &pairs, lift),
        );
        if let Some(b) = balance {
            pairs.push(b);
        }
        (pairs, WalkerLayout::Balanced)
    }

    /// Greedily adds the eligible free pair that most raises the margin until the margin is
    /// enough or no pair raises it. Returns the pairs and their margin.
    fn grow(&self, mut pairs: Vec<usize>, lift: f32, eligible: &[bool]) -> (Vec<usize>, f32) {
        let required = self.options.min_margin * self.body.length;
        let mut margin = self.margin(&pairs);
        while margin < required {
            let mut best: Option<(usize, f32)> = None;
            for (i, &ok) in eligible.iter().enumerate() {
                if !ok || !self.free_for_pair(i, &pairs, lift) {
                    continue;
                }
                pairs.push(i);
                let m = self.margin(&pairs);
                pairs.pop();
                if m > margin && best.is_none_or(|(_, bm)| m > bm) {
                    best = Some((i, m));
                }
            }
            let Some((i, m)) = best else { break };
            pairs.push(i);
            margin = m;
        }
        (pairs, margin)
    }

    /// A layout from scratch, for when the seed's layout cannot be made to stand: first from
    /// each of the widest eligible bones, then from the most stable one- and two-pair bases
    /// (every eligible bone and every compatible two bones), each grown with [`Self::grow`].
    /// Only eligible bones and non-overlapping sweeps are used. Returns the first layout that
    /// stands, or the best margin seen.
    fn rebuild(&self, lift: f32, eligible: &[bool]) -> Result<(Vec<usize>, f32), f32> {
        let body = self.body;
        let n = self.n();
        let required = self.options.min_margin * body.length;
        let mut best = f32::NEG_INFINITY;
        let mut firsts: Vec<usize> = (0..n).filter(|&i| eligible[i]).collect();
        sort_by(&mut firsts, &mut |&a, &b| {
            body.bones[b]
                .width
                .total_cmp(&body.bones[a].width)
                .then(a.cmp(&b))
        });
        for &start in firsts.iter().take(RELOCATION_TRIES) {
            let (p, m) = self.grow(alloc::vec![start], lift, eligible);
            if m >= required {
                return Ok((p, m));
            }
            best = best.max(m);
        }
        let mut bases: Vec<(f32, usize, usize)> = Vec::new();
        for i in (0..n).filter(|&i| eligible[i]) {
            bases.push((self.margin(&[i]), i, i));
            for j in (i + 1..n).filter(|&j| eligible[j]) {
                if self.free_for_pair(j, &[i], lift) {
                    bases.push((self.margin(&[i, j]), i, j));
                }
            }
        }
        sort_by(&mut bases, &mut |a, b| {
            b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2))
        });
        for &(_, i, j) in bases.iter().take(RELOCATION_TRIES) {
            let base = if i == j {
                alloc::vec![i]
            } else {
                alloc::vec![i, j]
            };
            let (p, m) = self.grow(base, lift, eligible);
            if m >= required {
                return Ok((p, m));
            }
            best = best.max(m);
        }
        Err(best)
    }

    /// The last resort, when no layout stands at full stride: the longest stride (below
    /// `sweep`) at which [`Self::rebuild`] finds a layout that stands, searched among the
    /// strides at which two eligible bones' sweeps just stop overlapping; failing that, legs
    /// on every eligible bone at the stride where none overlap. Returns the pairs, their margin
    /// and the stride, or, when even every eligible bone together does not stand (so no stride
    /// can help), that best possible margin.
    fn shortened_strides(
        &self,
        lift: f32,
        eligible: &[bool],
    ) -> Result<(Vec<usize>, f32, f32), f32> {
        let required = self.options.min_margin * self.body.length;
        let all: Vec<usize> = (0..self.n()).filter(|&i| eligible[i]).collect();
        let best = self.margin(&all);
        if !(best >= required) {
            return Err(best);
        }
        let leg = |i: usize| {
            let (l, r) = self.walking_legs(i, lift);
            l.max(r)
        };
        // The largest stride at which bones `i` and `j` no longer overlap (with some slack).
        let fit =
            |i: usize, j: usize| (self.along(j) - self.along(i)).abs() / (leg(i) + leg(j)) * 0.999;
        // Neighbours apart means everyone apart: sweeps are intervals centred on the bones.
        let s_all = all
            .windows(2)
            .map(|w| fit(w[0], w[1]))
            .fold(self.sweep, f32::min)
            .max(0.0);
        let mut strides: Vec<f32> = Vec::new();
        for (k, &i) in all.iter().enumerate() {
            for &j in &all[k + 1..] {
                let s = fit(i, j);
                if s > s_all && s < self.sweep {
                    strides.push(s);
                }
            }
        }
        sort_by(&mut strides, &mut |a, b| b.total_cmp(a));
        strides.dedup();
        // Binary search for the longest stride that works (the first success in descending
        // order); every probe is checked, so the answer stands whatever the search assumes.
        let (mut lo, mut hi) = (0, strides.len());
        let mut found = None;
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            let s = strides[mid];
            if let Ok((p, m)) = (Ctx { sweep: s, ..*self }).rebuild(lift, eligible) {
                found = Some((p, m, s));
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        if let Some(f) = found {
            return Ok(f);
        }
        let ctx = Ctx {
            sweep: s_all,
            ..*self
        };
        let apart = all
            .iter()
            .enumerate()
            .all(|(k, &i)| ctx.free_for_pair(i, &all[..k], lift));
        if apart {
            Ok((all, best, s_all))
        } else {
            Err(best)
        }
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
        let min_arm = self.options.min_arm_length * body.length;
        let t = between(rng, self.options.arm_length);
        let mut length = t * self.shortest_leg(bone, lift);
        if !(length >= min_arm && length > 0.0) {
            out.repairs.push(Repair::DroppedArms { length });
            return;
        }
        let a = self.along(bone);
        let room = leg_spans
            .iter()
            .map(|s| if a < s.start { s.start - a } else { a - s.end })
            .fold(f32::INFINITY, f32::min);
        let sweep = self.sweep;
        if sweep * length > room {
            let allowed = room / sweep * 0.999;
            if !(allowed >= min_arm && allowed > 0.0) {
                out.repairs.push(Repair::DroppedArms { length: allowed });
                return;
            }
            length = allowed;
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
        sort_by(&mut bones, &mut |&a, &b| {
            body.head_rank(a).cmp(&body.head_rank(b))
        });
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

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::*;
    use crate::SpineBone;
    use crate::split_mix::SplitMix;

    /// A straight body facing +Z (left on +X), bones 0.5 apart.
    fn body(widths: &[f32], clearances: &[f32]) -> Body {
        let bones = widths
            .iter()
            .zip(clearances)
            .enumerate()
            .map(|(i, (&w, &c))| {
                let z = i as f32 * 0.5;
                SpineBone::from_sockets(
                    z,
                    Vec3::new(w / 2.0, c, z),
                    Vec3::new(-w / 2.0, c, z),
                    Vec3::new(0.0, c + w / 2.0, z),
                    c,
                )
            })
            .collect();
        Body::new(
            bones,
            0.5 * (widths.len() as f32 + 1.0),
            crate::HeadEnd::Last,
        )
    }

    fn ctx<'a>(body: &'a Body, options: &'a PlanOptions) -> Ctx<'a> {
        Ctx {
            body,
            options,
            com: body.center_of_mass(),
            foot_radius: options.foot_radius * body.length,
            sweep: options.sweep,
        }
    }

    #[test]
    fn the_margin_does_not_depend_on_leg_length() {
        let o = PlanOptions::DEFAULT;
        let short = body(&[0.4, 0.4, 1.0], &[0.5, 0.5, 0.5]);
        let tall = body(&[0.4, 0.4, 1.0], &[50.0, 50.0, 50.0]);
        for pairs in [&[2][..], &[0, 2], &[0, 1, 2]] {
            assert_eq!(ctx(&short, &o).margin(pairs), ctx(&tall, &o).margin(pairs));
        }
        // One pair: the foot radius minus the distance to the centre of mass.
        let c = ctx(&short, &o);
        let expected = c.foot_radius - (c.com.y - 1.0).abs();
        assert!((c.margin(&[2]) - expected).abs() < 1e-6);
    }

    #[test]
    fn the_lift_gives_the_highest_bone_exactly_the_minimum_leg() {
        // Awkward floats: 0.1 and 0.3 are not exact in binary.
        let b = body(&[0.5, 0.5, 0.5], &[0.1, 0.3, 0.1]);
        let o = PlanOptions::DEFAULT.with_min_leg_length(0.3);
        let c = ctx(&b, &o);
        let mut out = Plan {
            kind: CreatureKind::Walker,
            limbs: Vec::new(),
            knee: None,
            lift: 0.0,
            layout: None,
            stability_margin: None,
            center_of_mass: c.com,
            support: Vec::new(),
            repairs: Vec::new(),
        };
        let min_len = o.min_leg_length * b.length;
        let lift = c.lift_for_min_legs(&mut out, min_len);
        assert!(lift > 0.0);
        assert!(c.shortest_leg(1, lift) >= min_len);
        assert!(lift < min_len - 0.3 + 1e-5);
        assert_eq!(out.repairs, vec![Repair::Lifted { by: lift }]);
        // Tall enough already: no lift, no repair.
        out.repairs.clear();
        let o = PlanOptions::DEFAULT;
        let c = ctx(&b, &o);
        assert_eq!(c.lift_for_min_legs(&mut out, 0.2), 0.0);
        assert!(out.repairs.is_empty());
    }

    #[test]
    fn a_rebuild_uses_only_eligible_bones() {
        let b = body(&[0.4, 0.4, 0.4, 0.4, 1.0], &[1.0, 1.0, 1.0, 1.0, 6.0]);
        let o = PlanOptions::DEFAULT;
        let c = ctx(&b, &o);
        // Bone 4 would stand alone on the widest bone, but it is not eligible.
        let eligible = [true, true, true, true, false];
        let (pairs, margin) = c.rebuild(0.0, &eligible).unwrap();
        assert!(pairs.iter().all(|&p| p < 4), "{pairs:?}");
        assert!(margin >= o.min_margin * b.length);
        for (k, &p) in pairs.iter().enumerate() {
            assert!(c.free_for_pair(p, &pairs[..k], 0.0));
        }
        // Nothing eligible: nothing stands.
        assert!(c.rebuild(0.0, &[false; 5]).is_err());
    }

    #[test]
    fn shortened_strides_are_as_long_as_possible() {
        // Two bones 0.5 apart with 2-long legs: at the default stride (±1) they overlap.
        let b = body(&[0.5, 0.5], &[2.0, 2.0]);
        let o = PlanOptions::DEFAULT;
        let c = ctx(&b, &o);
        assert!(c.rebuild(0.0, &[true, true]).is_err());
        let (pairs, margin, stride) = c.shortened_strides(0.0, &[true, true]).unwrap();
        assert_eq!(pairs.len(), 2);
        assert!(margin >= o.min_margin * b.length);
        // Just short of the stride at which the sweeps touch: 0.5 / (2 + 2).
        assert!(stride < 0.125 && stride > 0.124, "{stride}");
        // A heavy bone that cannot carry legs: no stride helps.
        let b = body(&[0.3, 0.3, 2.0], &[1.0, 1.0, 1.0]);
        let c = ctx(&b, &o);
        assert!(c.shortened_strides(0.0, &[true, true, false]).is_err());
    }

    #[test]
    fn arms_shorter_than_the_minimum_are_dropped() {
        // Pairs on bones 0 and 4 (sweeping up to z = 3); the head bone 7 is free for arms.
        let b = body(&[1.0, 0.3, 0.3, 0.3, 0.9, 0.3, 0.3, 0.3], &[2.0; 8]);
        let o = PlanOptions::DEFAULT
            .with_arm_chance(100.0)
            .with_arm_length([0.01, 0.01]);
        let p = plan(&b, CreatureKind::Walker, &o, &mut SplitMix(3)).unwrap();
        assert_eq!(p.layout, Some(WalkerLayout::TwoWide));
        assert_eq!(p.limbs_of(LimbKind::Arm).count(), 0);
        assert!(
            p.repairs
                .iter()
                .any(|r| matches!(r, Repair::DroppedArms { length } if *length < 0.05 * b.length))
        );
        // Long enough arms are kept.
        let p = plan(
            &b,
            CreatureKind::Walker,
            &o.with_arm_length([0.5, 0.5]),
            &mut SplitMix(3),
        )
        .unwrap();
        assert_eq!(p.limbs_of(LimbKind::Arm).count(), 2);
    }
}
