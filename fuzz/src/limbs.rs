//! `creature-limbs`: `plan` for walkers, fliers and swimmers on arbitrary spines (sockets,
//! widths, clearances) with arbitrary options and seeds. A plan is finite everywhere, its
//! limbs sit on existing bones, mirrors pair up, and the same seed gives the same plan.

use arbitrary::Arbitrary;
use creature_limbs::rand_core::{Infallible, TryRng};
use creature_limbs::{Body, CreatureKind, HeadEnd, PlanOptions, SpineBone, plan};
use glam::Vec3;

use crate::{map, pick};

/// A small deterministic generator (an LCG), as the planner's docs use.
pub struct Lcg(pub u64);

impl TryRng for Lcg {
    type Error = Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        Ok((self.0 >> 32) as u32)
    }
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        Ok(u64::from(self.try_next_u32()?) << 32 | u64::from(self.try_next_u32()?))
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        for b in dst {
            *b = self.try_next_u32()? as u8;
        }
        Ok(())
    }
}

#[derive(Debug, Clone, Arbitrary)]
pub struct BoneIn {
    pub gap: f32,
    pub width: f32,
    pub height: f32,
    pub clearance: f32,
}

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub valid: bool,
    pub kind: u8,
    pub head_last: bool,
    pub seed: u64,
    /// Option field number and value, applied in order.
    pub tweaks: Vec<(u8, f32)>,
    pub bones: Vec<BoneIn>,
}

fn options(input: &Input) -> PlanOptions {
    let v = input.valid;
    let mut o = PlanOptions::DEFAULT;
    for &(field, raw) in input.tweaks.iter().take(8) {
        match field % 12 {
            0 => o.sweep = pick(v, raw, 0.0, 100.0),
            1 => o.foot_radius = pick(v, raw, 0.0, 0.25),
            2 => o.min_margin = pick(v, raw, 1e-4, 1.0),
            3 => o.min_leg_length = pick(v, raw, 0.001, 100.0),
            4 => o.long_body_ratio = pick(v, raw, 0.0, 1e6),
            5 => o.uniform_width_ratio = pick(v, raw, 0.0, 1.0),
            6 => o.arm_chance = pick(v, raw, 0.0, 100.0),
            7 => o.central_bones = raw.to_bits() as usize % 70,
            8 => o.max_flier_leg_pairs = raw.to_bits() as usize % 70,
            9 => o.fin_size = [pick(v, raw, 0.001, 1.0), pick(v, raw, 0.001, 1.0) * 1.5],
            10 => o.stretch = [pick(v, raw, 0.001, 2.0), pick(v, raw, 0.001, 2.0) * 2.0],
            _ => o.second_pair_ratio = pick(v, raw, 0.0, 1.0),
        }
    }
    o
}

fn body(input: &Input) -> Body {
    let v = input.valid;
    let mut along = 0.0;
    let bones: Vec<SpineBone> = input
        .bones
        .iter()
        .take(70)
        .map(|b| {
            if v {
                along += map(b.gap, 0.05, 1.0);
                let w = map(b.width, 0.05, 2.0);
                let y = map(b.height, 0.1, 3.0);
                SpineBone::from_sockets(
                    along,
                    Vec3::new(w / 2.0, y, along),
                    Vec3::new(-w / 2.0, y, along),
                    Vec3::new(0.0, y + w / 2.0, along),
                    map(b.clearance, 0.05, 3.0),
                )
            } else {
                along = b.gap;
                SpineBone::from_sockets(
                    b.gap,
                    Vec3::new(b.width, b.height, b.gap),
                    Vec3::new(-b.width, b.height, b.gap),
                    Vec3::new(0.0, b.height + b.width, b.gap),
                    b.clearance,
                )
            }
        })
        .collect();
    let length = if v { along + 0.5 } else { along };
    Body::new(
        bones,
        length,
        if input.head_last {
            HeadEnd::Last
        } else {
            HeadEnd::First
        },
    )
}

pub fn run(input: &Input) {
    let body = body(input);
    let options = options(input);
    let kind = match input.kind % 3 {
        0 => CreatureKind::Walker,
        1 => CreatureKind::Flier,
        _ => CreatureKind::Swimmer,
    };
    let result = plan(&body, kind, &options, &mut Lcg(input.seed));
    assert_eq!(
        format!("{:?}", plan(&body, kind, &options, &mut Lcg(input.seed))),
        format!("{result:?}"),
        "determinism"
    );
    let Ok(p) = result else {
        return;
    };
    let n = body.bones.len();
    assert!(p.lift.is_finite() && p.center_of_mass.is_finite(), "{p:?}");
    assert!(
        p.stability_margin.is_none_or(f32::is_finite),
        "margin {:?}",
        p.stability_margin
    );
    assert!(p.support.iter().all(|s| s.is_finite()));
    for (i, limb) in p.limbs.iter().enumerate() {
        assert!(limb.bone < n, "limb {i} on bone {} of {n}", limb.bone);
        assert!(
            limb.scale.is_finite() && limb.length.is_finite(),
            "limb {i}: {limb:?}"
        );
        assert!(
            limb.foot.is_none_or(|f| f.is_finite()),
            "limb {i}: {limb:?}"
        );
        assert!(limb.span.start.is_finite() && limb.span.end.is_finite());
        if let Some(m) = limb.mirror {
            assert!(
                m < p.limbs.len() && p.limbs[m].mirror == Some(i),
                "mirror of {i} is {m}"
            );
        }
    }
}
