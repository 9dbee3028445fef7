//! `creature-ffd`: lattices built from arbitrary frames and divisions, moved by
//! `set_control_point` / `translate_slice` / `scale_slice`, then `deform`, `try_deform`,
//! `deform_in_place`, `try_deform_in_place` and `deform_normal` at arbitrary points.

use arbitrary::Arbitrary;
use creature_ffd::{Axis, Lattice, OutsidePolicy};
use glam::Vec3;

use crate::{map, pick3};

#[derive(Debug, Clone, Arbitrary)]
pub struct Move {
    /// 0: `set_control_point`, 1: `translate_slice`, 2: `scale_slice`.
    pub op: u8,
    pub axis: u8,
    pub index: [u8; 3],
    pub value: [f32; 3],
}

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub valid: bool,
    pub extrapolate: bool,
    pub origin: [f32; 3],
    pub axes: [[f32; 3]; 3],
    pub divisions: [u8; 3],
    pub moves: Vec<Move>,
    pub normal: [f32; 3],
    pub points: Vec<[f32; 3]>,
}

fn axis(a: u8) -> Axis {
    match a % 3 {
        0 => Axis::S,
        1 => Axis::T,
        _ => Axis::U,
    }
}

fn build(input: &Input) -> Option<Lattice> {
    let v = input.valid;
    let origin = pick3(v, input.origin, -10.0, 10.0);
    let axes = if v {
        // Diagonal lengths in [0.1, 10] and a shear of at most 0.3 of them: always a valid frame.
        let mut axes = [Vec3::ZERO; 3];
        for (a, raw) in input.axes.iter().enumerate() {
            let len = map(raw[a], 0.1, 10.0);
            let mut e = Vec3::ZERO;
            e[a] = len;
            for b in 0..3 {
                if b != a {
                    e[b] = map(raw[b], -0.1, 0.1) * len;
                }
            }
            axes[a] = e;
        }
        axes
    } else {
        input.axes.map(Vec3::from)
    };
    let divisions = input.divisions.map(|d| {
        if v {
            usize::from(d % 6) + 1
        } else {
            usize::from(d % 40)
        }
    });
    let lattice = Lattice::new(origin, axes, divisions);
    if v {
        assert!(lattice.is_ok(), "valid frame rejected: {lattice:?}");
    }
    let mut lattice = lattice.ok()?;
    if input.extrapolate {
        lattice.set_outside_policy(OutsidePolicy::Extrapolate);
    }
    for m in input.moves.iter().take(16) {
        let before = lattice.clone();
        let value = pick3(v, m.value, -5.0, 5.0);
        let result = match m.op % 3 {
            0 => {
                let index = m.index.map(usize::from);
                let p = if v {
                    let local = Vec3::new(
                        f32::from(m.index[0]) / 255.0,
                        f32::from(m.index[1]) / 255.0,
                        f32::from(m.index[2]) / 255.0,
                    );
                    lattice.world_coords(local) + value * 0.2
                } else {
                    value
                };
                let index = if v {
                    let d = lattice.divisions();
                    [
                        index[0] % (d[0] + 1),
                        index[1] % (d[1] + 1),
                        index[2] % (d[2] + 1),
                    ]
                } else {
                    index
                };
                lattice.set_control_point(index, p)
            }
            1 => lattice.translate_slice(
                axis(m.axis),
                usize::from(m.index[0]),
                value * if v { 0.2 } else { 1.0 },
            ),
            _ => {
                let scale = if v {
                    pick3(v, m.value, 0.5, 2.0)
                } else {
                    value
                };
                lattice.scale_slice(axis(m.axis), usize::from(m.index[0]), scale)
            }
        };
        match result {
            Ok(()) => assert!(
                lattice.control_points().iter().all(|p| p.is_finite()),
                "a move was accepted and left a non-finite control point: {m:?}"
            ),
            // Documented: the lattice is unchanged on error.
            Err(_) => assert_eq!(lattice, before, "a failed move changed the lattice: {m:?}"),
        }
    }
    Some(lattice)
}

pub fn run(input: &Input) {
    let Some(lattice) = build(input) else {
        return;
    };
    // Determinism: the same calls build the same lattice.
    assert_eq!(build(input).as_ref(), Some(&lattice));
    let v = input.valid;
    let points: Vec<Vec3> = input
        .points
        .iter()
        .take(64)
        .map(|p| {
            if v {
                lattice.world_coords(pick3(true, *p, -0.2, 1.2))
            } else {
                Vec3::from(*p)
            }
        })
        .collect();
    let normal = pick3(v, input.normal, -1.0, 1.0);
    let mut batch = points.clone();
    lattice.deform_in_place(&mut batch);
    for (p, batched) in points.iter().zip(&batch) {
        let q = lattice.deform(*p);
        // Documented: each batched result is bit-identical to `deform`.
        assert_eq!(
            q.to_array().map(f32::to_bits),
            batched.to_array().map(f32::to_bits),
            "deform_in_place vs deform at {p}"
        );
        if !lattice.is_deformed() {
            assert_eq!(
                q.to_array().map(f32::to_bits),
                p.to_array().map(f32::to_bits),
                "undeformed lattice moved {p}"
            );
        }
        if !p.is_finite() {
            assert!(lattice.try_deform(*p).is_err());
            continue;
        }
        if lattice.contains(*p) {
            assert!(q.is_finite(), "deform({p}) = {q} inside the lattice");
        }
        match lattice.try_deform(*p) {
            Ok(t) => assert_eq!(
                t.to_array().map(f32::to_bits),
                q.to_array().map(f32::to_bits)
            ),
            Err(e) => assert!(
                !q.is_finite(),
                "try_deform({p}) = {e:?} but deform gives {q}"
            ),
        }
        if let Ok(n) = lattice.deform_normal(*p, normal) {
            if normal == Vec3::ZERO {
                assert_eq!(n, Vec3::ZERO);
            } else {
                assert!(
                    n.is_finite() && n.is_normalized(),
                    "deform_normal({p}, {normal}) = {n}, length {}",
                    n.length()
                );
            }
        }
    }
    let mut checked = points.clone();
    match lattice.try_deform_in_place(&mut checked) {
        Ok(()) => assert!(
            checked
                .iter()
                .zip(&batch)
                .all(|(a, b)| a.is_finite() && a == b)
        ),
        Err(_) => assert!(
            points.iter().any(|p| !p.is_finite()) || batch.iter().any(|p| !p.is_finite()),
            "try_deform_in_place failed on finite points with finite results"
        ),
    }
}
