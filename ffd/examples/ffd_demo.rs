//! Shapes a capsule into a creature-like body the way the 3D seed does: a 3×3×11 lattice
//! around it, every cross-section scaled at random, slices spaced by random positive steps.
//! Prints what happened and writes the body as a Wavefront OBJ file.
//!
//! Run: `cargo run --release -p creature-ffd --example ffd_demo -- [seed] [out.obj]`
//! (defaults: seed 7, `target/ffd_demo.obj`).

use core::error::Error;
use core::fmt::Write as _;
use std::time::Instant;

use creature_ffd::glam::Vec3;
use creature_ffd::{Axis, Lattice};

/// A small deterministic generator (SplitMix64), enough for a demo.
struct SplitMix(u64);

impl SplitMix {
    fn next_f32(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }

    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next_f32()
    }
}

/// A capsule ("pill") along Z: radius 0.5, cylinder length 2, with smooth normals.
fn capsule(rings: usize, segments: usize) -> (Vec<Vec3>, Vec<Vec3>, Vec<[u32; 3]>) {
    let (radius, half) = (0.5f32, 1.0f32);
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for r in 0..=rings {
        // Polar angle from the -Z tip to the +Z tip, the cylinder inserted at the equator.
        let v = r as f32 / rings as f32;
        let theta = v * core::f32::consts::PI;
        let offset = if v < 0.5 { -half } else { half };
        for s in 0..segments {
            let phi = s as f32 / segments as f32 * core::f32::consts::TAU;
            let n = Vec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                -theta.cos(),
            );
            positions.push(n * radius + Vec3::Z * offset);
            normals.push(n);
        }
    }
    let mut triangles = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            let a = (r * segments + s) as u32;
            let b = (r * segments + (s + 1) % segments) as u32;
            let c = a + segments as u32;
            let d = b + segments as u32;
            triangles.push([a, c, b]);
            triangles.push([b, c, d]);
        }
    }
    (positions, normals, triangles)
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let seed: u64 = args.next().map(|s| s.parse()).transpose()?.unwrap_or(7);
    let out = args
        .next()
        .unwrap_or_else(|| "target/ffd_demo.obj".to_string());
    let mut rng = SplitMix(seed);

    let (positions, normals, triangles) = capsule(48, 32);
    let start = Instant::now();
    let mut lattice = Lattice::around(&positions, [2, 2, 10], 0.05)?;
    for k in 0..lattice.slice_count(Axis::U) {
        let scale = Vec3::new(rng.range(0.5, 1.6), rng.range(0.5, 1.6), 1.0);
        lattice.scale_slice(Axis::U, k, scale)?;
    }
    let spacing = lattice.axes()[2].length() / 10.0;
    let gaps: Vec<f32> = (0..10).map(|_| spacing * rng.range(0.5, 1.5)).collect();
    lattice.distribute_slices(Axis::U, &gaps)?;
    let shaped = Instant::now();

    let mut deformed = positions.clone();
    lattice.try_deform_in_place(&mut deformed)?;
    let deformed_normals = positions
        .iter()
        .zip(&normals)
        .map(|(&p, &n)| lattice.deform_normal(p, n))
        .collect::<Result<Vec<_>, _>>()?;
    let done = Instant::now();

    let report = lattice.fold_report(16);
    let (min, max) = deformed
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    println!(
        "seed {seed}: {} vertices, {} triangles",
        positions.len(),
        triangles.len()
    );
    println!(
        "lattice 3x3x11 shaped in {:.1} us; vertices and normals deformed in {:.1} us",
        (shaped - start).as_secs_f64() * 1e6,
        (done - shaped).as_secs_f64() * 1e6
    );
    println!(
        "Jacobian determinant on a 16^3 grid: min {:.3}, max {:.3}, folds: {}",
        report.min_determinant,
        report.max_determinant,
        report.folds()
    );
    println!("deformed bounds: {min} .. {max}");

    let mut obj = format!("# creature-ffd demo, seed {seed}\n");
    for p in &deformed {
        writeln!(obj, "v {} {} {}", p.x, p.y, p.z)?;
    }
    for n in &deformed_normals {
        writeln!(obj, "vn {} {} {}", n.x, n.y, n.z)?;
    }
    for [a, b, c] in &triangles {
        let (a, b, c) = (a + 1, b + 1, c + 1);
        writeln!(obj, "f {a}//{a} {b}//{b} {c}//{c}")?;
    }
    std::fs::write(&out, obj)?;
    println!("wrote {out}");
    Ok(())
}
