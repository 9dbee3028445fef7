//! Renders 16 creatures (seeds 0–15) into one 4×4 image: `cargo xtask gallery` writes
//! `creature/gallery.png` with it.
//!
//! ```sh
//! cargo run --release -p creature --features export --example gallery -- creature/gallery.png
//! ```

#![allow(clippy::std_instead_of_core, clippy::std_instead_of_alloc)]

use std::process::ExitCode;

use creature::Image;
use creature::export::{self, PreviewOptions};
use creature::{d2, generate_2d};

const CELL: u32 = 256;
const COLUMNS: u32 = 4;

fn main() -> ExitCode {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "creature/gallery.png".into());
    match run(&path) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gallery: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(path: &str) -> Result<(), String> {
    let size = CELL * COLUMNS;
    let mut sheet = Image {
        width: size,
        height: size,
        rgba: vec![255; (size * size * 4) as usize],
    };
    let options = PreviewOptions::DEFAULT.with_size(CELL);
    for seed in 0..16u32 {
        let creature =
            generate_2d(u64::from(seed), &d2::Params::DEFAULT).map_err(|e| e.to_string())?;
        let image = export::preview_2d(&creature, &options).map_err(|e| e.to_string())?;
        // Centre the preview in its cell.
        let (cx, cy) = ((seed % COLUMNS) * CELL, (seed / COLUMNS) * CELL);
        let (ox, oy) = (
            (CELL - image.width.min(CELL)) / 2,
            (CELL - image.height.min(CELL)) / 2,
        );
        for y in 0..image.height.min(CELL) {
            for x in 0..image.width.min(CELL) {
                let src = ((y * image.width + x) * 4) as usize;
                let dst = (((cy + oy + y) * size + cx + ox + x) * 4) as usize;
                sheet.rgba[dst..dst + 4].copy_from_slice(&image.rgba[src..src + 4]);
            }
        }
    }
    let png = export::image_png(&sheet).map_err(|e| e.to_string())?;
    std::fs::write(path, png).map_err(|e| format!("{path}: {e}"))?;
    println!("gallery: 16 creatures (seeds 0-15) -> {path}");
    Ok(())
}
