//! Generates creatures. In 3D (the default) writes `creature.glb` (skinned, with the kind's
//! baked clips) and `creature.png` (three views); with `--count N`, N creatures from `--seed`
//! on, files named by kind and seed. In 2D writes `creature.glb`, `creature.png` and
//! `creature.svg`.
//!
//! ```sh
//! cargo run --release --example generate -- --seed 7 --out out/
//! cargo run --release --example generate -- --kind walker --count 16 --out out/
//! cargo run --release --example generate -- --dim 2d --seed 7 --out out/
//! ```
//!
//! Options: `--dim 3d|2d` (default 3d), `--kind walker|flier|swimmer|random` (3D, default
//! random), `--count N` (3D, default 1), `--seed N` (default 0), `--out DIR` (default
//! `out/`), `--texture-size N` (2D, default 256), `--bones` (2D: draw the bones on the PNG).

#![allow(clippy::std_instead_of_core, clippy::std_instead_of_alloc)]

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use creature::export::{self, PreviewOptions};
use creature::{Kind, Params, Params2d, generate, generate_2d, preview_3d};

const USAGE: &str = "usage: generate [--dim 3d|2d] [--kind walker|flier|swimmer|random] \
     [--count N] [--seed N] [--out DIR] [--texture-size N] [--bones]";

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("generate: {e}\n{USAGE}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), String> {
    let mut seed = 0u64;
    let mut out = PathBuf::from("out");
    let mut texture_size = 256u32;
    let mut bones = false;
    let mut three_d = true;
    let mut kind = Kind::Random;
    let mut count = 1u64;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = |name: &str| args.next().ok_or(format!("{name} needs a value"));
        match arg.as_str() {
            "--dim" => {
                three_d = match value("--dim")?.as_str() {
                    "3d" => true,
                    "2d" => false,
                    other => return Err(format!("--dim {other}: use 3d or 2d")),
                };
            }
            "--kind" => {
                kind = match value("--kind")?.as_str() {
                    "walker" => Kind::Walker,
                    "flier" => Kind::Flier,
                    "swimmer" => Kind::Swimmer,
                    "random" => Kind::Random,
                    other => {
                        return Err(format!(
                            "--kind {other}: use walker, flier, swimmer or random"
                        ));
                    }
                };
            }
            "--count" => {
                count = value("--count")?
                    .parse()
                    .map_err(|e| format!("--count: {e}"))?;
                if count == 0 {
                    return Err("--count must be at least 1".into());
                }
            }
            "--seed" => {
                seed = value("--seed")?
                    .parse()
                    .map_err(|e| format!("--seed: {e}"))?;
            }
            "--out" => out = PathBuf::from(value("--out")?),
            "--texture-size" => {
                texture_size = value("--texture-size")?
                    .parse()
                    .map_err(|e| format!("--texture-size: {e}"))?;
            }
            "--bones" => bones = true,
            "-h" | "--help" => {
                println!("{USAGE}");
                return Ok(());
            }
            other => return Err(format!("unknown argument `{other}`")),
        }
    }
    if three_d {
        return run_3d(seed, count, kind, &out);
    }
    let params = Params2d::DEFAULT.with_texture_size(texture_size);
    let start = Instant::now();
    let creature = generate_2d(seed, &params).map_err(|e| e.to_string())?;
    let elapsed = start.elapsed();
    let glb = export::glb(&creature).map_err(|e| e.to_string())?;
    let png = export::preview_png(&creature, &PreviewOptions::DEFAULT.with_bones(bones))
        .map_err(|e| e.to_string())?;
    let svg = export::svg(&creature);
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    for (name, bytes) in [
        ("creature.glb", glb.as_slice()),
        ("creature.png", png.as_slice()),
        ("creature.svg", svg.as_bytes()),
    ] {
        let path = out.join(name);
        std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    println!(
        "seed {seed}: {} bones, {} vertices, {} triangles, min angle {:.1}°, generated in {:.2} ms -> {}",
        creature.bones.len(),
        creature.mesh.positions.len(),
        creature.mesh.indices.len(),
        creature.quality.min_angle,
        elapsed.as_secs_f64() * 1e3,
        out.display()
    );
    Ok(())
}

/// Writes `count` 3D creatures from `first` on, one summary line each.
fn run_3d(first: u64, count: u64, kind: Kind, out: &std::path::Path) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let params = Params::DEFAULT.with_kind(kind);
    for (done, seed) in (first..first.saturating_add(count)).enumerate() {
        let start = Instant::now();
        let creature = generate(seed, &params).map_err(|e| format!("seed {seed}: {e}"))?;
        let elapsed = start.elapsed();
        let clips = &creature.clips;
        let glb = export::glb_3d(&creature, clips).map_err(|e| e.to_string())?;
        let image = preview_3d(&creature, 256).map_err(|e| e.to_string())?;
        let png = export::image_png(&image).map_err(|e| e.to_string())?;
        let kind_name = format!("{:?}", creature.kind).to_lowercase();
        let stem = if count == 1 {
            "creature".to_string()
        } else {
            format!("{kind_name}-{seed}")
        };
        for (ext, bytes) in [("glb", &glb), ("png", &png)] {
            let path = out.join(format!("{stem}.{ext}"));
            std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        }
        let names: Vec<&str> = clips.iter().map(|c| c.name).collect();
        println!(
            "[{}/{count}] seed {seed} {kind_name}: {:.2} m, {} vertices, {} triangles, {} joints, {} limbs, clips {}, generated (clips baked) in {:.2} ms -> {}",
            done + 1,
            creature.length,
            creature.mesh.positions.len(),
            creature.mesh.indices.len(),
            creature.skeleton.joints.len(),
            creature.plan.limbs.len(),
            names.join("/"),
            elapsed.as_secs_f64() * 1e3,
            out.join(format!("{stem}.glb")).display()
        );
    }
    Ok(())
}
