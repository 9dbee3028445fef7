//! 3D previews: three views with something drawn in each. With `CREATURE_PREVIEW_DIR` set,
//! writes `walker-N.png`, `flier-N.png` and `swimmer-N.png` there to look at.

#![cfg(feature = "export")]
#![allow(clippy::unwrap_used)]

use creature::{d3, export, generate};

#[test]
fn every_view_shows_the_creature() {
    let dir = std::env::var_os("CREATURE_PREVIEW_DIR");
    for (name, kind) in [
        ("walker", d3::Kind::Walker),
        ("flier", d3::Kind::Flier),
        ("swimmer", d3::Kind::Swimmer),
    ] {
        for seed in 0..4 {
            let c = generate(seed, &d3::Params::DEFAULT.with_kind(kind)).unwrap();
            let image = export::preview_3d(&c, 96).unwrap();
            assert_eq!((image.width, image.height), (288, 96));
            for view in 0..3 {
                let drawn = (0..96u32)
                    .flat_map(|y| (view * 96..(view + 1) * 96).map(move |x| (x, y)))
                    .filter(|&(x, y)| image.pixel(x, y) != Some(export::PREVIEW_BACKGROUND))
                    .count();
                assert!(drawn > 200, "{name} {seed} view {view}: {drawn} pixels");
            }
            if let Some(dir) = &dir {
                let png = creature::export::image_png(&image).unwrap();
                std::fs::write(
                    std::path::Path::new(dir).join(format!("{name}-{seed}.png")),
                    png,
                )
                .unwrap();
                // A posed frame of each clip, to look at.
                for clip in &c.clips {
                    let mut posed = c.clone();
                    posed.mesh.positions = c.posed_positions(clip, clip.frames / 3).unwrap();
                    let image = export::preview_3d(&posed, 96).unwrap();
                    let png = creature::export::image_png(&image).unwrap();
                    let file = format!("{name}-{seed}-{}.png", clip.name);
                    std::fs::write(std::path::Path::new(dir).join(file), png).unwrap();
                }
            }
        }
    }
    assert!(export::preview_3d(&generate(0, &d3::Params::DEFAULT).unwrap(), 8).is_err());
}

/// The preview shows the mesh's vertex colours: painted red, the creature comes out red;
/// painted blue, blue.
#[test]
fn the_preview_shows_the_vertex_colours() {
    let c = generate(3, &d3::Params::DEFAULT.with_kind(d3::Kind::Walker)).unwrap();
    for (paint, channel) in [(creature::glam::Vec3::X, 0), (creature::glam::Vec3::Z, 2)] {
        let mut painted = c.clone();
        painted.mesh.colours.iter_mut().for_each(|v| *v = paint);
        let image = export::preview_3d(&painted, 96).unwrap();
        let drawn: Vec<&[u8]> = image
            .rgba
            .chunks(4)
            // Not the background, nor the ground line.
            .filter(|p| *p != export::PREVIEW_BACKGROUND && *p != [120, 110, 100, 255])
            .collect();
        assert!(drawn.len() > 500, "{} pixels", drawn.len());
        for p in drawn {
            let others = (0..3)
                .filter(|&k| k != channel)
                .map(|k| p[k])
                .max()
                .unwrap();
            assert!(p[channel] > 60 && others == 0, "{p:?} painted {paint}");
        }
    }
}
