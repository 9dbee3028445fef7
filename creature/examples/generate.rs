//! Generates creatures. In 3D (the default) writes `creature.glb` (skinned, with the kind's
//! baked clips) and `creature.png` (three views); in 2D writes `creature.glb`, `creature.png`
//! and `creature.svg`. With `--count N`, N creatures from `--seed` on, generated on all cores
//! (`--threads` to choose) behind a progress bar, files named by kind and seed
//! (`walker-42.glb`; 2D: `creature-42.glb`), one summary line each and a total at the end.
//!
//! ```sh
//! cargo run --release --example generate -- --seed 7 --out out/
//! cargo run --release --example generate -- --kind walker --count 16 --out out/
//! cargo run --release --example generate -- --kind walker --in-place --seed 7 --out out/
//! cargo run --release --example generate -- --kind walker --terrain 3 --seed 7 --out out/
//! cargo run --release --example generate -- --kind flier --terrain 3 --seed 7 --out out/
//! cargo run --release --example generate -- --dim 2d --seed 7 --out out/
//! cargo run --release --example generate -- --help
//! ```
//!
//! Options: `--dim 3d|2d` (default 3d), `--kind walker|flier|swimmer|slitherer|random` (3D,
//! default random: one of the first three), `--count N` (default 1), `--seed N` (default 0), `--out DIR` (default `out/`),
//! `--texture-size N` (2D, default 256), `--bones` (2D: draw the bones on the PNG),
//! `--in-place` (3D), `--terrain SEED` (3D: a walk, flight, swim or crawl over procedural terrain,
//! the terrain in the file), `--body-scale X`, `--head-size X`, `--snout-length X`,
//! `--neck-width X` (3D: that parameter fixed at X, as the web playground sets it),
//! `--threads N` (default: every core), `--dry-run` (generate and encode, write
//! nothing).

#![allow(clippy::std_instead_of_core, clippy::std_instead_of_alloc)]

use std::fmt;
use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use clap::{CommandFactory, Parser, ValueEnum};
use creature::export::{self, PreviewOptions};
use creature::glam;
use creature::terrain::{TerrainParams, terrain, terrain_mesh};
use creature::{d2, d3, generate, generate_2d};
use indicatif::{ProgressBar, ProgressState, ProgressStyle};
use rayon::prelude::*;

/// Procedural creatures from a seed: animated `.glb` and preview `.png` (2D: also `.svg`).
#[derive(Debug, Parser)]
#[command(name = "generate")]
struct Args {
    /// 3D skinned creatures with baked clips, or 2D metaball creatures.
    #[arg(long, value_enum, default_value_t = Dim::ThreeD)]
    dim: Dim,
    /// The 3D kind; `random` draws a walker, flier or swimmer from each seed.
    #[arg(long, value_enum, default_value_t = KindArg::Random)]
    kind: KindArg,
    /// How many creatures, seeds `--seed` to `--seed + N - 1`; more than one names the files
    /// by kind and seed.
    #[arg(long, default_value_t = 1, value_name = "N",
          value_parser = clap::value_parser!(u64).range(1..))]
    count: u64,
    /// The (first) seed.
    #[arg(long, default_value_t = 0, value_name = "N")]
    seed: u64,
    /// Output directory, created if missing.
    #[arg(long, default_value = "out", value_name = "DIR")]
    out: PathBuf,
    /// 2D: the texture's side in pixels.
    #[arg(long, default_value_t = 256, value_name = "N")]
    texture_size: u32,
    /// 2D: draw the bones on the preview PNG.
    #[arg(long)]
    bones: bool,
    /// 3D: bake the clips in place (the root's horizontal travel removed), for viewers that
    /// loop them as they are; the default keeps root motion, as engines want it.
    #[arg(long)]
    in_place: bool,
    /// 3D: instead of the flat-ground clips, bake a walker's `walk_to` (a flier's `fly_to`:
    /// take-off, flight and landing; a swimmer's `swim_to`) from the origin to a point 10 body
    /// lengths away over procedural terrain drawn from this seed (hills, a 12° slope, steps),
    /// and put the terrain in the `.glb` as a second node.
    #[arg(long, value_name = "SEED")]
    terrain: Option<u64>,
    /// 3D: every creature's body scale (`Params::body_scale` fixed at this value; default: a
    /// random scale from 0.5 to 2).
    #[arg(long, value_name = "X")]
    body_scale: Option<f32>,
    /// 3D: the head's size (`Params::head_size` fixed at this value).
    #[arg(long, value_name = "X")]
    head_size: Option<f32>,
    /// 3D: the snout's length (`Params::snout_length` fixed at this value).
    #[arg(long, value_name = "X")]
    snout_length: Option<f32>,
    /// 3D: how narrow the neck is (`Params::neck_width`).
    #[arg(long, value_name = "X")]
    neck_width: Option<f32>,
    /// Worker threads for `--count` (default: every core, or `RAYON_NUM_THREADS`).
    #[arg(long, value_name = "N")]
    threads: Option<NonZeroUsize>,
    /// Generate and encode every file, but write nothing.
    #[arg(long)]
    dry_run: bool,
}

/// `--dim`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Dim {
    /// Skinned, animated 3D creatures (walkers, fliers, swimmers).
    #[value(name = "3d")]
    ThreeD,
    /// 2D metaball creatures.
    #[value(name = "2d")]
    TwoD,
}

/// `--kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum KindArg {
    /// Walks on legs (maybe with arms).
    Walker,
    /// Flies on buzzing or flapping wings.
    Flier,
    /// Swims with fins and a tail.
    Swimmer,
    /// Crawls on its belly without limbs (a snake).
    Slitherer,
    /// One of walker, flier and swimmer, drawn from the seed.
    Random,
}

impl From<KindArg> for d3::Kind {
    fn from(kind: KindArg) -> Self {
        match kind {
            KindArg::Walker => d3::Kind::Walker,
            KindArg::Flier => d3::Kind::Flier,
            KindArg::Swimmer => d3::Kind::Swimmer,
            KindArg::Slitherer => d3::Kind::Slitherer,
            KindArg::Random => d3::Kind::Random,
        }
    }
}

/// What every seed of one run shares.
struct Job<'a> {
    dim: Dim,
    params: d3::Params,
    params_2d: d2::Params,
    bones: bool,
    terrain: Option<u64>,
    out: &'a Path,
    /// One creature: files are `creature.*`, not named by seed.
    single: bool,
    write: bool,
}

impl Job<'_> {
    /// The file stem of one creature: `creature` alone, else `{prefix}-{seed}`.
    fn stem(&self, prefix: &str, seed: u64) -> String {
        if self.single {
            "creature".to_string()
        } else {
            format!("{prefix}-{seed}")
        }
    }
}

fn main() -> ExitCode {
    let args = Args::parse();
    let Some(end) = args.seed.checked_add(args.count - 1) else {
        Args::command()
            .error(
                clap::error::ErrorKind::ValueValidation,
                format!(
                    "--seed {} with --count {} goes past the last seed {}",
                    args.seed,
                    args.count,
                    u64::MAX
                ),
            )
            .exit()
    };
    match run(&args, end) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("generate: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The 3D parameters `args` ask for: the defaults, with each value given fixed.
fn params_3d(args: &Args) -> d3::Params {
    let mut params = d3::Params::DEFAULT
        .with_kind(args.kind.into())
        .with_in_place(args.in_place)
        .with_clips(args.terrain.is_none());
    if let Some(s) = args.body_scale {
        params = params.with_body_scale(creature::Span::new(s, s));
    }
    if let Some(s) = args.head_size {
        params = params.with_head_size(creature::Span::new(s, s));
    }
    if let Some(s) = args.snout_length {
        params = params.with_snout_length(creature::Span::new(s, s));
    }
    if let Some(w) = args.neck_width {
        params = params.with_neck_width(w);
    }
    params
}

/// Generates seeds `args.seed..=end`; `Ok(false)` if some seeds failed (each was reported).
fn run(args: &Args, end: u64) -> Result<bool, String> {
    if !args.dry_run {
        std::fs::create_dir_all(&args.out).map_err(|e| format!("{}: {e}", args.out.display()))?;
    }
    let job = Job {
        dim: args.dim,
        params: params_3d(args),
        params_2d: d2::Params::DEFAULT.with_texture_size(args.texture_size),
        bones: args.bones,
        terrain: args.terrain,
        out: &args.out,
        single: args.count == 1,
        write: !args.dry_run,
    };
    if job.single {
        let line = make(args.seed, &job)?;
        println!("{line}");
        return Ok(true);
    }

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.map_or(0, NonZeroUsize::get))
        .build()
        .map_err(|e| format!("thread pool: {e}"))?;
    let threads = pool.current_num_threads();
    let bar = ProgressBar::new(args.count).with_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} {rate} ETA {eta}")
            .map_err(|e| format!("progress bar: {e}"))?
            .with_key("rate", |state: &ProgressState, w: &mut dyn fmt::Write| {
                // A failed write only loses this frame's text.
                let _ = write!(w, "{:.0} creatures/s", state.per_sec());
            })
            .progress_chars("=> "),
    );
    let failed = AtomicUsize::new(0);
    let start = Instant::now();
    pool.install(|| {
        (args.seed..=end).into_par_iter().for_each(|seed| {
            // `suspend` clears the bar, prints, and redraws it: lines never tear, and they are
            // printed even when the bar is hidden (standard error not a terminal).
            match make(seed, &job) {
                Ok(line) => bar.suspend(|| println!("{line}")),
                Err(e) => {
                    failed.fetch_add(1, Ordering::Relaxed);
                    bar.suspend(|| eprintln!("generate: {e}"));
                }
            }
            bar.inc(1);
        });
    });
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();
    let failed = failed.into_inner();
    println!(
        "{} creatures{} in {wall:.2} s: {:.1} creatures/s on {threads} thread{} -> {}{}",
        args.count,
        if failed == 0 {
            String::new()
        } else {
            format!(" ({failed} failed)")
        },
        args.count as f64 / wall,
        if threads == 1 { "" } else { "s" },
        args.out.display(),
        if args.dry_run {
            " (dry run, nothing written)"
        } else {
            ""
        },
    );
    Ok(failed == 0)
}

/// Generates one creature, encodes (and writes) its files; returns its summary line.
fn make(seed: u64, job: &Job<'_>) -> Result<String, String> {
    match job.dim {
        Dim::ThreeD => make_3d(seed, job),
        Dim::TwoD => make_2d(seed, job),
    }
}

fn make_3d(seed: u64, job: &Job<'_>) -> Result<String, String> {
    let err = |e: creature::Error| format!("seed {seed}: {e}");
    let start = Instant::now();
    let creature = generate(seed, &job.params).map_err(err)?;
    let elapsed = start.elapsed();
    let to;
    let (clips, glb) = match job.terrain {
        None => (
            &creature.clips[..],
            export::glb_3d(&creature, &creature.clips).map_err(err)?,
        ),
        Some(terrain_seed) => {
            let (clip, ground) = over_terrain(&creature, terrain_seed).map_err(err)?;
            to = [if job.params.in_place {
                clip.in_place()
            } else {
                clip
            }];
            let glb =
                export::glb_3d_on_terrain(&creature, &to, &terrain_mesh(&ground)).map_err(err)?;
            (&to[..], glb)
        }
    };
    let image = export::preview_3d(&creature, 256).map_err(err)?;
    let png = export::image_png(&image).map_err(err)?;
    let kind = format!("{:?}", creature.kind).to_lowercase();
    let glb_path = write(
        job,
        &job.stem(&kind, seed),
        &[("glb", glb.as_slice()), ("png", png.as_slice())],
    )?;
    let names: Vec<&str> = clips.iter().map(|c| c.name).collect();
    Ok(format!(
        "seed {seed} {kind}: {:.2} m, {} vertices, {} triangles, {} joints, {} limbs, clips {}, generated (clips baked) in {:.2} ms -> {}",
        creature.length,
        creature.mesh.positions.len(),
        creature.mesh.indices.len(),
        creature.skeleton.joints.len(),
        creature.plan.limbs.len(),
        names.join("/"),
        elapsed.as_secs_f64() * 1e3,
        glb_path.display()
    ))
}

/// `--terrain`: terrain from `seed` sized to `creature` (`TerrainParams::for_creature`: hills
/// half its length high, a 12° slope, steps a fifth of its gait's shortest limb high, or a
/// tenth of its length without a gait), and its walk, flight or swim from the origin to a point 10 body lengths away over it.
fn over_terrain(
    creature: &d3::Creature,
    seed: u64,
) -> Result<(d3::Clip, creature::gait::HeightField), creature::Error> {
    let length = creature.length;
    let params = TerrainParams::for_creature(creature);
    let ground = terrain(seed, &params)?;
    let clip = creature.bake_to(&ground, glam::Vec3::new(6.0, 0.0, 8.0) * length, 120.0)?;
    Ok((clip, ground))
}

fn make_2d(seed: u64, job: &Job<'_>) -> Result<String, String> {
    let err = |e: creature::Error| format!("seed {seed}: {e}");
    let start = Instant::now();
    let creature = generate_2d(seed, &job.params_2d).map_err(err)?;
    let elapsed = start.elapsed();
    let glb = export::glb_2d(&creature).map_err(err)?;
    let png = export::preview_2d_png(&creature, &PreviewOptions::DEFAULT.with_bones(job.bones))
        .map_err(err)?;
    let svg = export::svg_2d(&creature);
    let glb_path = write(
        job,
        &job.stem("creature", seed),
        &[
            ("glb", glb.as_slice()),
            ("png", png.as_slice()),
            ("svg", svg.as_bytes()),
        ],
    )?;
    Ok(format!(
        "seed {seed}: {} bones, {} vertices, {} triangles, min angle {:.1}°, generated in {:.2} ms -> {}",
        creature.bones.len(),
        creature.mesh.positions.len(),
        creature.mesh.indices.len(),
        creature.quality.min_angle,
        elapsed.as_secs_f64() * 1e3,
        glb_path.display()
    ))
}

/// Writes `{stem}.{ext}` for each file (unless a dry run); returns the first file's path.
fn write(job: &Job<'_>, stem: &str, files: &[(&str, &[u8])]) -> Result<PathBuf, String> {
    let mut first = None;
    for &(ext, bytes) in files {
        let path = job.out.join(format!("{stem}.{ext}"));
        if job.write {
            std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        }
        first.get_or_insert(path);
    }
    first.ok_or_else(|| "no file to write".to_string())
}
