//! Writes the committed seed corpus: for every target a few seeds, and for each finding of
//! issue 17 the input that reproduces it under that target. Each file is decoded back with
//! `arbitrary`, printed, and run through its target (catching the panic), so the output says
//! which regression inputs still fail.
//!
//! `cargo run --example corpus` (from `fuzz/`); review the `git diff` of `corpus/`.

#![allow(clippy::unwrap_used, clippy::std_instead_of_core, missing_docs)]

use arbitrary::{Arbitrary, Unstructured};
use creature_fuzz::encode::Enc;
use std::fmt::Debug;
use std::path::Path;

fn write<T: for<'a> Arbitrary<'a> + Debug>(target: &str, name: &str, bytes: &[u8], run: fn(&T)) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus")
        .join(target);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join(name), bytes).unwrap();
    let input = T::arbitrary_take_rest(Unstructured::new(bytes)).unwrap();
    let text = format!("{input:?}");
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run(&input)));
    println!(
        "{target}/{name}: {} -- {}",
        if outcome.is_ok() { "passes" } else { "FAILS" },
        &text[..text.len().min(400)]
    );
}

/// Seeds: a few pseudo-random byte strings, valid flavour (first byte odd) and arbitrary.
fn seeds<T: for<'a> Arbitrary<'a> + Debug>(target: &str, run: fn(&T)) {
    let mut state = 0x2545_f491_4f6c_dd1d_u64 ^ target.len() as u64;
    for (i, first) in [1u8, 1, 0].into_iter().enumerate() {
        let mut bytes = vec![first];
        for _ in 0..255 {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            bytes.push((state >> 56) as u8);
        }
        write::<T>(target, &format!("seed-{i}"), &bytes, run);
    }
}

fn main() {
    use creature_fuzz as f;
    seeds::<f::ffd::Input>("ffd", f::ffd::run);
    seeds::<f::metaball_2d::Input>("metaball_2d", f::metaball_2d::run);
    seeds::<f::metaball_3d::Input>("metaball_3d", f::metaball_3d::run);
    seeds::<f::march_grid::Input>("march_grid", f::march_grid::run);
    seeds::<f::march_trace::Input>("march_trace", f::march_trace::run);
    seeds::<f::triangulate::Input>("triangulate", f::triangulate::run);
    seeds::<f::autorig::Input>("autorig", f::autorig::run);
    seeds::<f::skin::Input>("skin", f::skin::run);
    seeds::<f::limbs::Input>("limbs", f::limbs::run);
    seeds::<f::gait::Input>("gait", f::gait::run);
    seeds::<f::generate_3d::Input>("generate_3d", f::generate_3d::run);
    seeds::<f::generate_2d::Input>("generate_2d", f::generate_2d::run);
    seeds::<f::export::Input>("image_png", f::export::run);

    // Findings 1, 3 and 12: triangulate (raw rings, default options unless said).
    let tri = |rings: &[Vec<[f32; 2]>], spacing: f32, min_angle: f32| {
        let mut e = Enc::new();
        e.bool(false)
            .f32(spacing)
            .f32(0.5)
            .f32(min_angle)
            .u16(u16::MAX)
            .f32(0.0);
        e.f32s(&[0.0, 0.0]).f32(1.0);
        e.vec(rings, |e, r| {
            e.bool(false).u8(0).vec(r, |e, p| {
                e.f32s(p);
            });
        });
        e.bytes()
    };
    let t = f::triangulate::run;
    write::<f::triangulate::Input>(
        "triangulate",
        "issue17-finding1-thin-ring",
        &tri(
            &[vec![[3.0, 6.0], [0.0, 3.0], [-100.0, -100.0]]],
            20.0,
            20.0,
        ),
        t,
    );
    write::<f::triangulate::Input>(
        "triangulate",
        "issue17-finding1-thin-ring-2",
        &tri(
            &[vec![
                [-8.0, -8.0],
                [3.0, 3.0],
                [-100.0, -99.957_275],
                [-100.0, -100.0],
            ]],
            20.0,
            20.0,
        ),
        t,
    );
    let square = |s: f32| vec![[0.0, 0.0], [s, 0.0], [s, s], [0.0, s]];
    write::<f::triangulate::Input>(
        "triangulate",
        "issue17-finding3-tiny-spacing",
        &tri(&[square(10.0)], 1e-30, 20.0),
        t,
    );
    write::<f::triangulate::Input>(
        "triangulate",
        "issue17-finding3-dense-spacing",
        &tri(&[square(100.0)], 1e-3, 20.0),
        t,
    );
    write::<f::triangulate::Input>(
        "triangulate",
        "issue17-finding12-min-angle-at-f32-max",
        &tri(&[vec![[0.0, 0.0], [1e19, 0.0], [0.0, f32::MAX]]], 0.0, 0.0),
        t,
    );

    // Findings 2 and 11: metaball_2d (raw field).
    let field = |balls: &[([f32; 2], f32)],
                 blobbiness: f32,
                 cell: Option<f32>,
                 block: ([f32; 2], f32, [u8; 2]),
                 points: &[[f32; 2]]| {
        let mut e = Enc::new();
        e.bool(false).u8(0).f32s(&[blobbiness, 0.0]).f32(1e-4);
        e.opt(cell.map(|c| {
            move |e: &mut Enc| {
                e.f32(c);
            }
        }));
        e.vec(balls, |e, (c, r)| {
            e.f32s(c).f32(*r);
        });
        e.u8(2)
            .f32s(&block.0)
            .f32(block.1)
            .u8(block.2[0])
            .u8(block.2[1])
            .f32(1.0);
        e.vec(points, |e, p| {
            e.f32s(p);
        });
        e.bytes()
    };
    let m = f::metaball_2d::run;
    let tiny = [([-10000.0, -9998.779], 1e-5), ([-10000.0, -9998.781], 1e-5)];
    write::<f::metaball_2d::Input>(
        "metaball_2d",
        "issue17-finding2-cell-size-misses-a-ball",
        &field(
            &tiny,
            -0.5,
            Some(1.0),
            ([0.0, 0.0], 1.0, [0, 0]),
            &[tiny[0].0, tiny[1].0],
        ),
        m,
    );
    let pair = [
        ([0.992_217_9, 0.0], 0.531_799_14),
        ([0.725_490_2, 1.0], 0.531_799_14),
    ];
    write::<f::metaball_2d::Input>(
        "metaball_2d",
        "issue17-finding11-sample-block-tolerance",
        &field(
            &pair,
            -33.255_486,
            None,
            ([0.337_255, 0.337_255], 0.584_729_43, [8, 8]),
            &[],
        ),
        m,
    );

    // Later finding (`new-`): a Wyvill ball of radius 1.0003113 culled the point on its rim
    // where `d² = R²` rounds to `q = 1 − 2⁻²⁴` (culled 0, exact about 2e-22, bound 0).
    let r = 1.000_311_3_f32;
    let mut e = Enc::new();
    e.bool(false).u8(1).f32s(&[1.0, 0.0]).f32(1e-4);
    e.opt(Some(|e: &mut Enc| {
        e.f32(7.4e-10);
    }));
    e.vec(&[([0.0f32, 0.0], r)], |e, (c, r)| {
        e.f32s(c).f32(*r);
    });
    e.vec(&[0.0f32], |e, z| {
        e.f32(*z);
    });
    e.u8(1);
    e.vec(&[[0.0, 0.0, r], [r, 0.0, 0.0], [0.0, -r, 0.0]], |e, p| {
        e.f32s(p);
    });
    write::<f::metaball_3d::Input>(
        "metaball_3d",
        "new-wyvill-rim-culled",
        &e.bytes(),
        f::metaball_3d::run,
    );

    // Finding 4: image_png with a size whose byte count overflows.
    let mut e = Enc::new();
    e.bool(false)
        .u32(1 << 31)
        .u32(1 << 31)
        .vec::<u8>(&[], |_, _| {});
    write::<f::export::Input>(
        "image_png",
        "issue17-finding4-size-overflow",
        &e.bytes(),
        f::export::run,
    );

    // Findings 5 and 6: gait (raw legs, chains, ground and steps).
    let quadruped: Vec<([f32; 3], [f32; 3], f32, f32)> =
        [(-0.3, -0.5), (0.3, -0.5), (-0.3, 0.5), (0.3, 0.5)]
            .iter()
            .map(|&(x, z)| ([x, 0.8, z], [x, 0.0, z], 0.5, 0.5))
            .collect();
    let gait = |legs: &[([f32; 3], [f32; 3], f32, f32)],
                chains: &[([f32; 3], [f32; 3], u8, f32)],
                heights: &[f32],
                steps: &[[f32; 4]]| {
        let mut e = Enc::new();
        e.bool(false);
        e.vec(legs, |e, (h, r, u, l)| {
            e.f32s(h).f32s(r).f32(*u).f32(*l);
        });
        e.vec(chains, |e, (r, d, s, l)| {
            e.f32s(r).f32s(d).u8(*s).f32(*l);
        });
        e.vec(heights, |e, h| {
            e.f32(*h);
        });
        e.f32s(&[0.0, 1.0, 0.0]);
        e.vec(steps, |e, q| {
            e.f32(1.0 / 30.0)
                .f32s(&[0.0, 0.8, 0.0])
                .f32s(q)
                .f32s(&[0.0; 3])
                .f32s(&[0.0; 3]);
        });
        e.bytes()
    };
    let g = f::gait::run;
    let identity = [0.0, 0.0, 0.0, 1.0];
    write::<f::gait::Input>(
        "gait",
        "issue17-finding5-huge-quaternion",
        &gait(
            &quadruped,
            &[],
            &[0.0],
            &[identity, [-3.226_371_5e19, -1.0, -1.0, -1.0]],
        ),
        g,
    );
    let mut long = quadruped.clone();
    long[0].2 = f32::MAX;
    write::<f::gait::Input>(
        "gait",
        "issue17-finding6-leg-length-f32-max",
        &gait(&long, &[], &[0.0], &[identity, identity]),
        g,
    );
    let mut far = quadruped.clone();
    far[0].0[2] = 1e30;
    write::<f::gait::Input>(
        "gait",
        "issue17-finding6-hip-1e30",
        &gait(&far, &[], &[0.0], &[identity, identity]),
        g,
    );
    write::<f::gait::Input>(
        "gait",
        "issue17-finding6-chain-f32-max",
        &gait(
            &quadruped,
            &[([0.0; 3], [0.0, 0.0, -1.0], 3, f32::MAX)],
            &[0.0],
            &[identity, identity],
        ),
        g,
    );
    write::<f::gait::Input>(
        "gait",
        "issue17-finding6-ground-1e30-away",
        &gait(&quadruped, &[], &[-1e30], &[identity, identity, identity]),
        g,
    );

    // Findings 7 and 8: ffd (raw lattice).
    let ffd = |axes: f32,
               divisions: [u8; 3],
               moves: &[(u8, u8, [u8; 3], [f32; 3])],
               normal: [f32; 3],
               points: &[[f32; 3]]| {
        let mut e = Enc::new();
        e.bool(false).bool(false).f32s(&[0.0; 3]);
        e.f32s(&[axes, 0.0, 0.0, 0.0, axes, 0.0, 0.0, 0.0, axes]);
        e.u8(divisions[0]).u8(divisions[1]).u8(divisions[2]);
        e.vec(moves, |e, (op, axis, index, value)| {
            e.u8(*op)
                .u8(*axis)
                .u8(index[0])
                .u8(index[1])
                .u8(index[2])
                .f32s(value);
        });
        e.f32s(&normal);
        e.vec(points, |e, p| {
            e.f32s(p);
        });
        e.bytes()
    };
    write::<f::ffd::Input>(
        "ffd",
        "issue17-finding7-control-point-near-minus-max",
        &ffd(
            10.0,
            [1, 2, 13],
            &[(1, 2, [13, 0, 0], [0.0, -f32::MAX, 1.748_592_4])],
            [0.0, 1.0, 0.0],
            &[[9.621_613_5, 9.026_454, 9.019]],
        ),
        f::ffd::run,
    );
    write::<f::ffd::Input>(
        "ffd",
        "issue17-finding8-tiny-normal",
        &ffd(1.0, [1, 1, 1], &[], [2e-22, 0.0, 0.0], &[[0.5; 3]]),
        f::ffd::run,
    );

    // Finding 8 (skin): linear skin_normals with an extreme scale.
    let skin = |scale: f32, normal: [f32; 3]| {
        let mut e = Enc::new();
        e.bool(false).bool(false).u8(1).bool(false).f32(1.0);
        e.vec(&[([0.0f32, 0.0, 0.0], [0.0f32, 0.0, 1.0])], |e, (a, b)| {
            e.f32s(a).f32s(b);
        });
        // Columns (s, 0, 0), (0, 2s, 0), (0, 0, s), translation 0.
        e.vec(&[()], |e, ()| {
            e.f32s(&[scale, 0.0, 0.0, 0.0])
                .f32s(&[2.0 * scale, 0.0, 0.0])
                .f32s(&[0.0, 0.0, scale])
                .f32s(&[0.0, 0.0]);
        });
        e.vec::<u8>(&[], |_, _| {});
        e.vec(&[normal], |e, n| {
            e.f32s(&[0.0, 0.0, 0.5]).f32s(n);
        });
        e.bytes()
    };
    write::<f::skin::Input>(
        "skin",
        "issue17-finding8-normal-scale-1e15",
        &skin(1e15, [0.3, -0.5, 0.8]),
        f::skin::run,
    );
    write::<f::skin::Input>(
        "skin",
        "issue17-finding8-tiny-normal-scale-1e12",
        &skin(1e12, [2e-22, 0.0, 1e-22]),
        f::skin::run,
    );

    // Finding 9: generate_2d's preview one pixel too large (seed 0, 16 px texture, size 89).
    let mut e = Enc::new();
    e.u64(0)
        .bool(false)
        .bool(true)
        .u16(15)
        .u16(73)
        .u8(0)
        .vec::<u8>(&[], |_, _| {});
    write::<f::generate_2d::Input>(
        "generate_2d",
        "issue17-finding9-preview-size-89",
        &e.bytes(),
        f::generate_2d::run,
    );

    // Finding 10: autorig on a body 1e-45 across with 4 bones.
    let mut e = Enc::new();
    e.bool(false)
        .bool(false)
        .bool(true)
        .f32(0.25)
        .f32(0.4)
        .u16(4)
        .u16(4);
    e.vec::<u8>(&[], |_, _| {});
    e.vec(&[[0.0f32; 3], [1e-45; 3]], |e, p| {
        e.f32s(p);
    });
    write::<f::autorig::Input>(
        "autorig",
        "issue17-finding10-tiny-body",
        &e.bytes(),
        f::autorig::run,
    );

    // generate's docs: extreme valid limb options (min_margin 1, sweep 100) give a typed error.
    let mut e = Enc::new();
    e.u64(0).u8(0).bool(true).bool(false).bool(true).u8(0);
    e.vec(&[(15u8, 1.0f32, 100.0f32)], |e, (f, a, b)| {
        e.u8(*f).f32(*a).f32(*b);
    });
    write::<f::generate_3d::Input>(
        "generate_3d",
        "issue17-generate-no-stable-layout",
        &e.bytes(),
        f::generate_3d::run,
    );
}
