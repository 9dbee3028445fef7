//! Renders `gaits3d.png`, the README's strips of frames per gait: the first two- and
//! four-legged walkers and the first with six legs or more (from seed 0 up) that do not hop,
//! each in its looping `walk` (a trot's pattern) and its `run` (`Creature::bake_run_loop`), and
//! the first biped that hops in its `walk` and its `hop`, eight consecutive frames (30 a
//! second) from the side; then slitherers 0 and 3 in their `slither`,
//! eight frames spread over one body wave, from above. Each frame's root travel is taken off
//! so the body stays in place.
//!
//! ```sh
//! cargo run --release -p creature --features export --example gaits3d -- creature/gaits3d.png
//! ```
//!
//! Optional second argument: the frame height in pixels (default 120).

#![allow(clippy::std_instead_of_core, clippy::std_instead_of_alloc)]

use std::process::ExitCode;

use creature::Image;
use creature::d3::{self, Clip, Creature, Kind, Params};
use creature::export;
use creature::gait::LimbKind;
use creature::glam::Vec3;

/// Height (and width) of one frame, by default.
const FRAME: u32 = 120;
/// Frames per strip.
const FRAMES: usize = 8;
/// Seeds searched for a walker with a leg count.
const SEARCH: u64 = 2000;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .cloned()
        .unwrap_or_else(|| "creature/gaits3d.png".into());
    let size = match args.get(2).map(|a| a.parse::<u32>()) {
        None => FRAME,
        Some(Ok(s)) if (16..=1024).contains(&s) => s,
        Some(_) => {
            eprintln!("gaits3d: the frame height runs from 16 to 1024 pixels");
            return ExitCode::FAILURE;
        }
    };
    match run(&path, size) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gaits3d: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The first walker from seed 0 up with `legs` walking legs, or at least that many if `more`,
/// that hops if `hops` (and does not if not).
fn walker(legs: usize, more: bool, hops: bool) -> Result<(u64, Creature), String> {
    let params = Params::DEFAULT.with_kind(Kind::Walker);
    for seed in 0..SEARCH {
        let c = d3::generate(seed, &params).map_err(|e| format!("seed {seed}: {e}"))?;
        let count = c.gait.as_ref().map_or(0, |g| {
            g.legs.iter().filter(|l| l.kind == LimbKind::Leg).count()
        });
        let hopper = c.gait.as_ref().is_some_and(|g| g.options.hop);
        if (count == legs || (more && count > legs)) && hopper == hops {
            return Ok((seed, c));
        }
    }
    Err(format!("no walker with {legs} legs in seeds 0 to {SEARCH}"))
}

fn run(path: &str, size: u32) -> Result<(), String> {
    let side = size as usize;
    let width = side * FRAMES;
    let mut rgba = Vec::new();
    let mut rows = 0;
    for (legs, more, hops) in [
        (2, false, false),
        (4, false, false),
        (6, true, false),
        (2, false, true),
    ] {
        let (seed, c) = walker(legs, more, hops)?;
        let legs = c.gait.as_ref().map_or(0, |g| {
            g.legs.iter().filter(|l| l.kind == LimbKind::Leg).count()
        });
        let walk = c
            .clips
            .iter()
            .find(|clip| clip.name == "walk")
            .cloned()
            .ok_or_else(|| format!("seed {seed}: no walk"))?;
        let run = if hops {
            c.bake_hop_loop()
        } else {
            c.bake_run_loop()
        }
        .map_err(|e| format!("seed {seed}: {e}"))?;
        for clip in [&walk, &run] {
            println!("row {rows}: seed {seed}, {legs} legs, {}", clip.name);
            rgba.extend(strip(&c, clip, (0..FRAMES).collect(), (SIDE, size))?);
            rows += 1;
        }
    }
    for seed in [0, 3] {
        let params = Params::DEFAULT.with_kind(Kind::Slitherer);
        let c = d3::generate(seed, &params).map_err(|e| format!("seed {seed}: {e}"))?;
        let slither = c
            .clips
            .iter()
            .find(|clip| clip.name == "slither")
            .ok_or_else(|| format!("slitherer {seed}: no slither"))?;
        println!("row {rows}: slitherer {seed}, slither");
        let spread = (0..FRAMES)
            .map(|k| k * (slither.frames - 1) / FRAMES)
            .collect();
        rgba.extend(strip(&c, slither, spread, (TOP, size))?);
        rows += 1;
    }
    let sheet = Image {
        width: width as u32,
        height: (side * rows) as u32,
        rgba,
    };
    let png = export::image_png(&sheet).map_err(|e| e.to_string())?;
    std::fs::write(path, png).map_err(|e| format!("{path}: {e}"))?;
    println!("wrote {path}");
    Ok(())
}

/// The side and top views of `preview_3d`'s three.
const SIDE: usize = 0;
const TOP: usize = 2;

/// One strip: `frames` of `c`'s `clip`, each in `view` (of `preview_3d`'s three) `size`
/// pixels square, all at one scale (every frame's bounds), side by side.
fn strip(
    c: &Creature,
    clip: &Clip,
    frames: Vec<usize>,
    (view, size): (usize, u32),
) -> Result<Vec<u8>, String> {
    let side = size as usize;
    let width = side * frames.len();
    let mut row = vec![0u8; width * side * 4];
    let posed: Vec<Vec<Vec3>> = frames
        .iter()
        .map(|&k| in_place(c, clip, k))
        .collect::<Result<_, _>>()
        .map_err(|e| e.to_string())?;
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for p in posed.iter().flatten() {
        (lo, hi) = (lo.min(*p), hi.max(*p));
    }
    for (k, positions) in posed.into_iter().enumerate() {
        let image = frame(c, positions, (lo, hi), size).map_err(|e| e.to_string())?;
        for y in 0..side {
            let from = (y * image.width as usize + view * side) * 4;
            let to = (y * width + k * side) * 4;
            row[to..to + side * 4].copy_from_slice(&image.rgba[from..from + side * 4]);
        }
    }
    Ok(row)
}

/// Frame `k` of `clip` skinned, the root's horizontal travel taken off.
fn in_place(c: &Creature, clip: &Clip, k: usize) -> Result<Vec<Vec3>, creature::Error> {
    let mut positions = c.posed_positions(clip, k)?;
    let root = clip.root_translation.get(k).copied().unwrap_or_default();
    for p in &mut positions {
        p.x -= root.x;
        p.z -= root.z;
    }
    Ok(positions)
}

/// `c` with its mesh at `positions`, in `preview_3d`'s three views, scaled to `bounds` (two
/// vertices no triangle uses, at its corners, so every frame of a strip has the same scale).
fn frame(
    c: &Creature,
    mut positions: Vec<Vec3>,
    bounds: (Vec3, Vec3),
    size: u32,
) -> Result<Image, creature::Error> {
    let mut posed = c.clone();
    positions.extend([bounds.0, bounds.1]);
    let last = *posed.mesh.joints.last().unwrap_or(&[0u16; 4]);
    let weights = *posed.mesh.weights.last().unwrap_or(&[1.0, 0.0, 0.0, 0.0]);
    for _ in 0..2 {
        posed.mesh.normals.push(Vec3::Y);
        posed.mesh.colours.push(Default::default());
        posed.mesh.joints.push(last);
        posed.mesh.weights.push(weights);
    }
    posed.mesh.positions = positions;
    export::preview_3d(&posed, size)
}
