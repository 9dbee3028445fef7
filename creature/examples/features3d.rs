//! Renders the 3D README's close-up pictures, one per feature (each cell the three views of
//! `export::preview_3d`: side, front, top):
//!
//! - `heads3d.png`: six walkers and two swimmers (seeds 0–5, 0–1): heads, faces and feet;
//! - `wings3d.png`: fliers with feathered wings, bat wings and buzzing insect wings (the first
//!   seeds that have them);
//! - `backs3d.png`: walkers with a row of spikes, a row of plates and a shell (the first seeds
//!   that wear them);
//! - `patterns3d.png`: one walker (seed 3) in each body pattern.
//!
//! ```sh
//! cargo run --release -p creature --features export --example features3d -- creature
//! ```
//!
//! Optional second argument: the cell height in pixels (default 150).

#![allow(clippy::std_instead_of_core, clippy::std_instead_of_alloc)]

use std::process::ExitCode;

use creature::Image;
use creature::d3::{
    self, BackKind, BackWeights, Creature, Kind, Params, Pattern, PatternWeights, WingKind,
    WingWeights,
};
use creature::export;
use creature::limbs::LimbKind;

/// Height of one cell (its width is three views), by default.
const CELL: u32 = 150;
/// Seeds searched for a creature that shows a feature.
const SEARCH: u64 = 200;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let dir = args.get(1).cloned().unwrap_or_else(|| "creature".into());
    let cell = match args.get(2).map(|a| a.parse::<u32>()) {
        None => CELL,
        Some(Ok(c)) if (16..=1024).contains(&c) => c,
        Some(_) => {
            eprintln!("features3d: the cell height runs from 16 to 1024 pixels");
            return ExitCode::FAILURE;
        }
    };
    match run(&dir, cell) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("features3d: {e}");
            ExitCode::FAILURE
        }
    }
}

fn make(seed: u64, params: &Params) -> Result<Creature, String> {
    d3::generate(seed, &params.with_clips(false)).map_err(|e| format!("seed {seed}: {e}"))
}

/// The first creature of `params` from seed 0 up that `shows` the feature (`what`, printed
/// with its seed).
fn first(
    what: &str,
    params: &Params,
    shows: impl Fn(&Creature) -> bool,
) -> Result<Creature, String> {
    for seed in 0..SEARCH {
        let c = make(seed, params)?;
        if shows(&c) {
            println!("{what}: seed {seed}");
            return Ok(c);
        }
    }
    Err(format!("no creature of seeds 0–{SEARCH} shows the feature"))
}

fn run(dir: &str, cell: u32) -> Result<(), String> {
    let walker = Params::DEFAULT.with_kind(Kind::Walker);
    let flier = Params::DEFAULT.with_kind(Kind::Flier);
    let swimmer = Params::DEFAULT.with_kind(Kind::Swimmer);

    let mut heads = Vec::new();
    for seed in 0..6 {
        heads.push(make(seed, &walker)?);
    }
    for seed in 0..2 {
        heads.push(make(seed, &swimmer)?);
    }
    write(dir, "heads3d.png", &heads, 2, cell)?;

    let mut wings = Vec::new();
    for kind in WingKind::ALL {
        let params = flier.with_wing_kinds(WingWeights::only(kind));
        let what = format!("{kind:?} wings");
        wings.push(first(&what, &params, |c| {
            c.quality.wing_kind == Some(kind)
        })?);
    }
    wings.push(first("buzzing wings", &flier, |c| {
        c.plan.limbs_of(LimbKind::BuzzingWing).next().is_some()
    })?);
    // Wings are thin: one flier a row, larger.
    write(dir, "wings3d.png", &wings, 1, cell * 5 / 3)?;

    let mut backs = Vec::new();
    for kind in BackKind::ALL {
        let params = walker.with_back_kinds(BackWeights::only(kind));
        let what = format!("{kind:?} on the back");
        backs.push(first(&what, &params, |c| {
            c.quality.back_kind == Some(kind)
        })?);
    }
    write(dir, "backs3d.png", &backs, 2, cell)?;

    let mut patterns = Vec::new();
    for pattern in Pattern::ALL {
        patterns.push(make(
            3,
            &walker.with_patterns(PatternWeights::only(pattern)),
        )?);
    }
    write(dir, "patterns3d.png", &patterns, 2, cell)
}

/// `creatures` in rows of `columns` cells `cell` high, written as `dir/name`.
fn write(
    dir: &str,
    name: &str,
    creatures: &[Creature],
    columns: u32,
    cell: u32,
) -> Result<(), String> {
    let cell_w = 3 * cell;
    let rows = (creatures.len() as u32).div_ceil(columns);
    let (width, height) = (columns * cell_w, rows * cell);
    let mut sheet = Image {
        width,
        height,
        rgba: vec![255; (width * height * 4) as usize],
    };
    for (i, creature) in creatures.iter().enumerate() {
        let image = export::preview_3d(creature, cell).map_err(|e| e.to_string())?;
        let (column, row) = (i as u32 % columns, i as u32 / columns);
        for y in 0..image.height {
            for x in 0..image.width {
                let Some(pixel) = image.pixel(x, y) else {
                    continue;
                };
                let at = (((row * cell + y) * width + column * cell_w + x) * 4) as usize;
                if let Some(dst) = sheet.rgba.get_mut(at..at + 4) {
                    dst.copy_from_slice(&pixel);
                }
            }
        }
    }
    let png = export::image_png(&sheet).map_err(|e| e.to_string())?;
    let path = format!("{dir}/{name}");
    std::fs::write(&path, png).map_err(|e| format!("{path}: {e}"))?;
    println!("wrote {path} ({width}×{height})");
    Ok(())
}
