//! Renders a 4×4 gallery of 3D creatures per kind (seeds 0–15; each cell the three views of
//! `export::preview_3d`) into one image, walkers on top, then fliers, then swimmers.
//!
//! ```sh
//! cargo run --release -p creature --features export --example gallery3d -- creature/gallery3d.png
//! ```

#![allow(clippy::std_instead_of_core, clippy::std_instead_of_alloc)]

use std::process::ExitCode;

use creature::Image;
use creature::export;
use creature::{d3, generate};

/// Height of one cell (its width is three views).
const CELL: u32 = 96;
const COLUMNS: u32 = 4;
const ROWS_PER_KIND: u32 = 4;

fn main() -> ExitCode {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "creature/gallery3d.png".into());
    match run(&path) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gallery3d: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(path: &str) -> Result<(), String> {
    let kinds = [d3::Kind::Walker, d3::Kind::Flier, d3::Kind::Swimmer];
    let cell_w = 3 * CELL;
    let width = COLUMNS * cell_w;
    let height = kinds.len() as u32 * ROWS_PER_KIND * CELL;
    let mut gallery = Image {
        width,
        height,
        rgba: vec![255; (width * height * 4) as usize],
    };
    for (k, kind) in kinds.into_iter().enumerate() {
        for seed in 0..u64::from(COLUMNS * ROWS_PER_KIND) {
            let creature = generate(seed, &d3::Params::DEFAULT.with_kind(kind).with_clips(false))
                .map_err(|e| format!("{kind:?} {seed}: {e}"))?;
            let image = export::preview_3d(&creature, CELL).map_err(|e| e.to_string())?;
            let column = seed as u32 % COLUMNS;
            let row = k as u32 * ROWS_PER_KIND + seed as u32 / COLUMNS;
            for y in 0..image.height {
                for x in 0..image.width {
                    let Some(pixel) = image.pixel(x, y) else {
                        continue;
                    };
                    let gx = column * cell_w + x;
                    let gy = row * CELL + y;
                    let at = ((gy * width + gx) * 4) as usize;
                    if let Some(dst) = gallery.rgba.get_mut(at..at + 4) {
                        dst.copy_from_slice(&pixel);
                    }
                }
            }
        }
    }
    let png = export::image_png(&gallery).map_err(|e| e.to_string())?;
    std::fs::write(path, png).map_err(|e| format!("{path}: {e}"))?;
    println!("wrote {path} ({width}×{height})");
    Ok(())
}
