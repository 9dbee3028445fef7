//! `creature-metaball` in 3D: `Field3` from arbitrary balls and options; the culled `value`
//! against `value_exact` within `error_bound`, `contains`, gradients and `shares`.

use arbitrary::Arbitrary;
use creature_metaball::{Ball3, Field3};

use crate::metaball_2d::{FieldIn, check_value, options};
use crate::{pick, pick3};

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub field: FieldIn,
    pub z: Vec<f32>,
    pub k: u8,
    pub points: Vec<[f32; 3]>,
}

fn build(input: &Input) -> Option<Field3> {
    let f = &input.field;
    let balls: Vec<Ball3> = f
        .balls
        .iter()
        .take(64)
        .enumerate()
        .map(|(i, (c, r))| {
            let z = input.z.get(i).copied().unwrap_or(0.0);
            Ball3::new(
                pick3(f.valid, [c[0], c[1], z], -100.0, 100.0),
                pick(f.valid, *r, 0.1, 50.0),
                i as u32 % 7,
            )
        })
        .collect();
    let field = Field3::with_options(&balls, &options(f));
    if f.valid && !balls.is_empty() {
        assert!(field.is_ok(), "valid balls rejected: {field:?}");
    }
    field.ok()
}

pub fn run(input: &Input) {
    let Some(field) = build(input) else {
        return;
    };
    let again = build(input).unwrap();
    let bound = field.error_bound();
    assert!(bound.is_finite() && bound >= 0.0);
    let k = usize::from(input.k % 6);
    for p in input.points.iter().take(32) {
        let p = pick3(input.field.valid, *p, -150.0, 150.0);
        if !p.is_finite() {
            continue;
        }
        let value = field.value(p);
        assert_eq!(
            value.to_bits(),
            again.value(p).to_bits(),
            "determinism at {p}"
        );
        check_value(value, field.value_exact(p), bound, field.contains(p), &p);
        let (vg, gradient) = field.value_and_gradient(p);
        assert_eq!(
            vg.to_bits(),
            value.to_bits(),
            "value_and_gradient's value at {p}"
        );
        assert!(
            gradient.is_finite() && field.gradient(p).is_finite(),
            "gradient {gradient} at {p}"
        );
        assert!(field.gradient_exact(p).is_finite());
        let shares = field.shares(p, k);
        if value == 0.0 || k == 0 {
            assert!(shares.is_empty());
        } else {
            let sum: f32 = shares.iter().map(|s| s.weight).sum();
            assert!(
                shares.len() <= k && (sum - 1.0).abs() <= 1e-5,
                "shares {shares:?} at {p}"
            );
        }
    }
}
