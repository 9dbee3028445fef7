//! Renders a 4×4 gallery of 3D creatures per kind (seeds 0–15; each cell the three views of
//! `export::preview_3d`) into one image, walkers on top, then fliers, then swimmers.
//!
//! ```sh
//! cargo run --release -p creature --features export --example gallery3d -- creature/gallery3d.png
//! ```
//!
//! Optional second and third arguments: the first seed (default 0) and the cell height in
//! pixels (default 96), e.g. `-- /tmp/sheet.png 100 160` for seeds 100–115 in larger cells.

#![allow(clippy::std_instead_of_core, clippy::std_instead_of_alloc)]

use std::process::ExitCode;

use creature::Image;
use creature::export;
use creature::{d3, generate};

/// Height of one cell (its width is three views), by default.
const CELL: u32 = 96;
const COLUMNS: u32 = 4;
const ROWS_PER_KIND: u32 = 4;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .cloned()
        .unwrap_or_else(|| "creature/gallery3d.png".into());
    let number = |i: usize, default: u64| match args.get(i) {
        None => Ok(default),
        Some(a) => a
            .parse::<u64>()
            .map_err(|e| format!("argument {i} ({a}): {e}")),
    };
    let (first, cell) = match (number(2, 0), number(3, u64::from(CELL))) {
        (Ok(first), Ok(cell)) if (16..=1024).contains(&cell) => (first, cell as u32),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("gallery3d: {e}");
            return ExitCode::FAILURE;
        }
        _ => {
            eprintln!("gallery3d: the cell height runs from 16 to 1024 pixels");
            return ExitCode::FAILURE;
        }
    };
    match run(&path, first, cell) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gallery3d: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(path: &str, first: u64, cell: u32) -> Result<(), String> {
    let kinds = [d3::Kind::Walker, d3::Kind::Flier, d3::Kind::Swimmer];
    let cell_w = 3 * cell;
    let width = COLUMNS * cell_w;
    let height = kinds.len() as u32 * ROWS_PER_KIND * cell;
    let mut gallery = Image {
        width,
        height,
        rgba: vec![255; (width * height * 4) as usize],
    };
    for (k, kind) in kinds.into_iter().enumerate() {
        for i in 0..COLUMNS * ROWS_PER_KIND {
            let seed = first.wrapping_add(u64::from(i));
            let creature = generate(seed, &d3::Params::DEFAULT.with_kind(kind).with_clips(false))
                .map_err(|e| format!("{kind:?} {seed}: {e}"))?;
            let image = export::preview_3d(&creature, cell).map_err(|e| e.to_string())?;
            let column = i % COLUMNS;
            let row = k as u32 * ROWS_PER_KIND + i / COLUMNS;
            for y in 0..image.height {
                for x in 0..image.width {
                    let Some(pixel) = image.pixel(x, y) else {
                        continue;
                    };
                    let gx = column * cell_w + x;
                    let gy = row * cell + y;
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
