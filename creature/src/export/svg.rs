//! The 2D outline, mesh, bones and eyes as SVG text.

use alloc::string::String;
use alloc::vec::Vec;
use core::fmt::Write as _;

use glam::Vec3;

/// An SVG drawing of the outline (filled with the balls' mean colour), the mesh's edges, the
/// bones and the eyes, in world units (y up, flipped for SVG).
#[must_use]
pub fn svg_2d(creature: &crate::d2::Creature) -> String {
    let (min, max) = creature.bounds;
    let pad = (max - min).max_element() * 0.05;
    let (x0, y0) = (min.x - pad, -max.y - pad);
    let (w, h) = (max.x - min.x + 2.0 * pad, max.y - min.y + 2.0 * pad);
    let n = creature.balls.len().max(1) as f32;
    let mean = creature.balls.iter().map(|b| b.colour).sum::<Vec3>() / n;
    let [r, g, b] = mean.to_array().map(|v| (v.clamp(0.0, 1.0) * 255.0) as u8);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{x0:.2} {y0:.2} {w:.2} {h:.2}" width="{:.0}" height="{:.0}">"#,
        w.max(1.0),
        h.max(1.0)
    );
    let _ = writeln!(s, r#"<g transform="scale(1,-1)">"#);
    let mut d = String::new();
    for ring in &creature.outline {
        for (i, p) in ring.iter().enumerate() {
            let _ = write!(
                d,
                "{}{:.2},{:.2} ",
                if i == 0 { "M" } else { "L" },
                p.x,
                p.y
            );
        }
        d.push_str("Z ");
    }
    let _ = writeln!(
        s,
        r#"<path d="{}" fill="rgb({r},{g},{b})" fill-rule="evenodd" stroke="none"/>"#,
        d.trim_end()
    );
    let mut m = String::new();
    for t in &creature.mesh.indices {
        let pts: Vec<Vec3> = t
            .iter()
            .filter_map(|&i| creature.mesh.positions.get(i as usize).copied())
            .collect();
        if let [a, b, c] = pts[..] {
            let _ = write!(
                m,
                "M{:.2},{:.2} L{:.2},{:.2} L{:.2},{:.2} Z ",
                a.x, a.y, b.x, b.y, c.x, c.y
            );
        }
    }
    let _ = writeln!(
        s,
        r#"<path d="{}" fill="none" stroke="black" stroke-opacity="0.35" stroke-width="0.4"/>"#,
        m.trim_end()
    );
    let _ = writeln!(
        s,
        r#"<path d="{}" fill="none" stroke="black" stroke-width="1.2"/>"#,
        d.trim_end()
    );
    for bone in &creature.bones {
        if let Some(parent) = bone.parent.and_then(|p| creature.bones.get(p)) {
            let _ = writeln!(
                s,
                r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="rgb(200,30,30)" stroke-width="1.5"/>"#,
                parent.position.x, parent.position.y, bone.position.x, bone.position.y
            );
        }
    }
    for eye in &creature.eyes {
        let _ = writeln!(
            s,
            r#"<circle cx="{:.2}" cy="{:.2}" r="{:.2}" fill="white" stroke="black"/><circle cx="{:.2}" cy="{:.2}" r="{:.2}" fill="black"/>"#,
            eye.position.x,
            eye.position.y,
            eye.radius,
            eye.position.x,
            eye.position.y,
            eye.radius * 0.5
        );
    }
    s.push_str("</g>\n</svg>\n");
    s
}
