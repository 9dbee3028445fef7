//! The facade's `export::image_png` on arbitrary images: a consistent image encodes to a PNG
//! that decodes to the same size and pixels; an inconsistent one (size and data disagree,
//! sizes whose byte count overflows) is a typed error.

use arbitrary::Arbitrary;
use creature::{Error, Image, export};

use crate::decode_png;

#[derive(Debug, Clone, Arbitrary)]
pub struct Input {
    pub valid: bool,
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
}

pub fn run(input: &Input) {
    let image = if input.valid {
        let (w, h) = (1 + input.width % 64, 1 + input.height % 64);
        let len = (w * h * 4) as usize;
        let rgba = (0..len)
            .map(|i| {
                input
                    .rgba
                    .get(i % input.rgba.len().max(1))
                    .copied()
                    .unwrap_or(0)
            })
            .collect();
        Image {
            width: w,
            height: h,
            rgba,
        }
    } else {
        Image {
            width: input.width,
            height: input.height,
            rgba: input.rgba.clone(),
        }
    };
    let consistent =
        u128::from(image.width) * u128::from(image.height) * 4 == image.rgba.len() as u128;
    match export::image_png(&image) {
        Ok(png) => {
            assert!(
                consistent,
                "image_png accepted a {}x{} image with {} bytes",
                image.width,
                image.height,
                image.rgba.len()
            );
            assert!(export::image_png(&image).unwrap() == png, "determinism");
            let (w, h, pixels) = decode_png(&png);
            assert_eq!((w, h), (image.width, image.height));
            assert!(pixels == image.rgba, "decoded pixels differ");
        }
        Err(e) => {
            assert!(matches!(e, Error::Export { .. }), "{e:?}");
            // A consistent non-empty image that fits a PNG must encode.
            assert!(
                !consistent || image.width == 0 || image.height == 0,
                "image_png refused a consistent {}x{} image: {e:?}",
                image.width,
                image.height
            );
        }
    }
}
