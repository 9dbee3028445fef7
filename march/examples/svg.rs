//! Traces and meshes a creature-like metaball field and writes an SVG of the mesh and its
//! outline.
//!
//! Run: `cargo run -p creature-march --features mesh --example svg -- creature.svg`
//! (without a path the SVG goes to standard output).

use core::fmt::Write as _;

use creature_march::glam::Vec2;
use creature_march::{MeshOptions, trace, triangulate};

fn main() -> Result<(), Box<dyn core::error::Error>> {
    // A spine along +y and a pair of legs, covered by the seed's metaballs.
    let mut balls: Vec<(Vec2, f32)> = Vec::new();
    let mut bone = |from: Vec2, to: Vec2, thickness: f32| {
        let count = (from.distance(to) / (2.97 * thickness) * 1.4).ceil() as usize;
        let radius = thickness * 1.4 / (2.0 * (1.4f32 * 1.4).ln() + 1.0).sqrt();
        for i in 0..=count {
            balls.push((from.lerp(to, i as f32 / count as f32), radius));
        }
    };
    bone(Vec2::ZERO, Vec2::new(0.0, 160.0), 28.0);
    bone(Vec2::new(0.0, 160.0), Vec2::new(0.0, 220.0), 18.0);
    for dir in [-1.0f32, 1.0] {
        bone(
            Vec2::new(dir * 40.0, 60.0),
            Vec2::new(dir * 110.0, 40.0),
            9.0,
        );
        bone(
            Vec2::new(dir * 110.0, 40.0),
            Vec2::new(dir * 130.0, -20.0),
            7.0,
        );
    }
    let field = |p: Vec2| -> f32 {
        balls
            .iter()
            .map(|&(c, r)| (0.5 - 0.5 * p.distance_squared(c) / (r * r)).exp())
            .sum()
    };
    let hints: Vec<Vec2> = balls.iter().map(|b| b.0).collect();
    let rings = trace(field, &hints, 5.0, 1.0)?;
    let mesh = triangulate(&rings, &MeshOptions::DEFAULT)?;

    let svg = render(&rings, &mesh)?;
    match std::env::args().nth(1) {
        Some(path) => {
            std::fs::write(&path, svg)?;
            eprintln!(
                "wrote {path}: {} rings, {} vertices, {} triangles, min angle {:.1}°",
                rings.len(),
                mesh.positions.len(),
                mesh.triangles.len(),
                mesh.quality.min_angle
            );
        }
        None => print!("{svg}"),
    }
    Ok(())
}

fn render(
    rings: &[creature_march::Ring],
    mesh: &creature_march::Mesh2,
) -> Result<String, core::fmt::Error> {
    let lo = mesh.positions.iter().fold(Vec2::MAX, |a, &p| a.min(p)) - Vec2::splat(10.0);
    let hi = mesh.positions.iter().fold(Vec2::MIN, |a, &p| a.max(p)) + Vec2::splat(10.0);
    let size = hi - lo;
    let mut s = String::new();
    // Flip y: SVG's y points down, ours up.
    writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{} {} {} {}">"#,
        lo.x, -hi.y, size.x, size.y
    )?;
    writeln!(s, r#"<g transform="scale(1,-1)">"#)?;
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        writeln!(
            s,
            r##"<polygon points="{},{} {},{} {},{}" fill="#cfe3f5" stroke="#3b6c99" stroke-width="0.4"/>"##,
            a.x, a.y, b.x, b.y, c.x, c.y
        )?;
    }
    for r in rings {
        let points: Vec<String> = r
            .points
            .iter()
            .map(|p| format!("{},{}", p.x, p.y))
            .collect();
        let colour = if r.hole { "#c0392b" } else { "#1d3b57" };
        writeln!(
            s,
            r#"<polygon points="{}" fill="none" stroke="{colour}" stroke-width="1.2"/>"#,
            points.join(" ")
        )?;
    }
    writeln!(s, "</g>\n</svg>")?;
    Ok(s)
}
