//! Everything that turns a creature into something to look at or to load elsewhere: previews
//! (images) and files (glTF 2.0 binaries, SVG, PNG).
//!
//! [`preview_3d`] works everywhere (it is the crate's own rasteriser, `no_std`); the rest needs
//! the `export` feature (`std`, with `gltf-json` and `png`; the 2D preview is drawn by the
//! crate's own anti-aliased rasteriser). Every function
//! returns the file's bytes, text or pixels; writing them is the caller's business.
//!
//! | | 2D ([`d2::Creature`](crate::d2::Creature)) | 3D ([`d3::Creature`](crate::d3::Creature)) |
//! | --- | --- | --- |
//! | glTF 2.0 binary (`.glb`) | [`glb_2d`] | [`glb_3d`] (with clips) |
//! | preview image | [`preview_2d`], [`preview_2d_png`] | [`preview_3d`] |
//! | vector drawing | [`svg_2d`] | |
//! | any [`Image`] as PNG | [`image_png`] | [`image_png`] |
//!
//! ```
//! # #[cfg(feature = "export")] {
//! use creature::{d2, export, generate_2d};
//!
//! let creature = generate_2d(7, &d2::Params::DEFAULT.with_texture_size(64))?;
//! let glb = export::glb_2d(&creature)?;
//! assert_eq!(&glb[..4], b"glTF");
//! let png = export::preview_2d_png(&creature, &export::PreviewOptions::DEFAULT)?;
//! assert_eq!(&png[1..4], b"PNG");
//! let svg = export::svg_2d(&creature);
//! assert!(svg.starts_with("<svg"));
//! # }
//! # Ok::<(), creature::Error>(())
//! ```

#[cfg(feature = "export")]
use alloc::string::ToString;
#[cfg(feature = "export")]
use alloc::vec::Vec;

#[cfg(feature = "export")]
use crate::Error;
#[cfg(feature = "export")]
use crate::image::Image;

#[cfg(feature = "export")]
mod glb2d;
#[cfg(feature = "export")]
mod glb3d;
#[cfg(feature = "export")]
mod gltf;
#[cfg(feature = "export")]
mod preview2d;
mod preview3d;
#[cfg(feature = "export")]
mod raster;
#[cfg(feature = "export")]
mod svg;

#[cfg(feature = "export")]
#[cfg_attr(docsrs, doc(cfg(feature = "export")))]
pub use glb2d::glb_2d;
#[cfg(feature = "export")]
#[cfg_attr(docsrs, doc(cfg(feature = "export")))]
pub use glb3d::{glb_3d, glb_3d_on_terrain};
#[cfg(feature = "export")]
#[cfg_attr(docsrs, doc(cfg(feature = "export")))]
pub use preview2d::{PreviewOptions, preview_2d, preview_2d_png};
pub use preview3d::{PREVIEW_BACKGROUND, preview_3d};
#[cfg(feature = "export")]
#[cfg_attr(docsrs, doc(cfg(feature = "export")))]
pub use svg::svg_2d;

#[cfg(feature = "export")]
pub(crate) fn export_error(format: &'static str, message: impl ToString) -> Error {
    Error::Export {
        format,
        message: message.to_string(),
    }
}

/// Encodes an [`Image`] as an 8-bit RGBA PNG.
///
/// # Errors
/// [`Error::Export`] when the image's size and data disagree or the encoder fails.
#[cfg(feature = "export")]
#[cfg_attr(docsrs, doc(cfg(feature = "export")))]
pub fn image_png(image: &Image) -> Result<Vec<u8>, Error> {
    // Checked: a size whose byte count overflows `usize` is not this data's size.
    let expected = (image.width as usize)
        .checked_mul(image.height as usize)
        .and_then(|pixels| pixels.checked_mul(4));
    if expected != Some(image.rgba.len()) || image.width == 0 || image.height == 0 {
        return Err(export_error("png", "image size and data length disagree"));
    }
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, image.width, image.height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(|e| export_error("png", e))?;
        writer
            .write_image_data(&image.rgba)
            .map_err(|e| export_error("png", e))?;
        writer.finish().map_err(|e| export_error("png", e))?;
    }
    Ok(out)
}
