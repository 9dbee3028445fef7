//! Covers a two-bone limb with balls the 2D seed's way, builds its field and prints it as
//! ASCII art: `#` inside (`value ≥ 1`), `+`, `:` and `.` for the falloff outside, digits for
//! the bone (id) with the largest share inside, on request.
//!
//! Run: `cargo run -p creature-metaball --example field -- [--owners]`

use creature_metaball::glam::Vec2;
use creature_metaball::{
    CoverOptions, Falloff, Field2, ISO_LEVEL, MetaballError, cover_segment, cover_segment_with,
};

fn main() -> Result<(), MetaballError> {
    let owners = std::env::args().any(|a| a == "--owners");

    // Shoulder → elbow → hand; each bone covered from its child end to its parent joint, the
    // forearm's last ball kept half a step short of the shared elbow (interior joint).
    let shoulder = Vec2::new(0.0, 60.0);
    let elbow = Vec2::new(70.0, 20.0);
    let hand = Vec2::new(130.0, 50.0);
    let mut balls = cover_segment(elbow, shoulder, 14.0, 1.5, 0)?;
    let joint = CoverOptions::DEFAULT.with_interior_joint(true);
    balls.extend(cover_segment_with(hand, elbow, 9.0, 1.2, 1, &joint)?);
    let field = Field2::new(&balls, Falloff::SEED)?;

    // One character per 2.5 × 5 units (terminal cells are about twice as tall as wide).
    let (min, max) = field.bounds();
    let (step_x, step_y) = (2.5, 5.0);
    let columns = ((max.x - min.x) / step_x).ceil().min(120.0) as usize;
    let rows = ((max.y - min.y) / step_y).ceil().min(60.0) as usize;
    // `sample_grid` takes one step for both axes; sample at the finer one and skip rows.
    let per_row = (step_y / step_x) as usize;
    let samples = field.sample_grid(min, step_x, columns, rows * per_row)?;

    println!(
        "{} balls (upper arm {}, forearm {}), error bound {:.1e}, grid {:?}",
        balls.len(),
        balls.iter().filter(|b| b.id == 0).count(),
        balls.iter().filter(|b| b.id == 1).count(),
        field.error_bound(),
        field.grid_stats(),
    );
    // Top row first, so y points up.
    for row in (0..rows).rev() {
        let line: String = (0..columns)
            .map(|column| {
                let value = samples[row * per_row * columns + column];
                if value >= ISO_LEVEL {
                    if owners {
                        let p = min + Vec2::new(column as f32 * step_x, row as f32 * step_y);
                        let top = field.shares(p, 1);
                        top.first()
                            .and_then(|s| char::from_digit(s.id % 10, 10))
                            .unwrap_or('#')
                    } else {
                        '#'
                    }
                } else if value >= 0.5 {
                    '+'
                } else if value >= 0.1 {
                    ':'
                } else if value >= 0.01 {
                    '.'
                } else {
                    ' '
                }
            })
            .collect();
        println!("{}", line.trim_end());
    }
    Ok(())
}
