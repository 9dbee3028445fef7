//! The RGBA8 image both generators' pictures come in (textures, normal maps, previews).

use alloc::vec::Vec;

/// An RGBA8 image, rows top to bottom, 4 bytes per pixel.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 4` bytes, row-major, row 0 at the top.
    pub rgba: Vec<u8>,
}

impl Image {
    /// The pixel at `(x, y)` (row `y` from the top), `None` outside the image.
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 4;
        let p = self.rgba.get(i..i + 4)?;
        Some([p[0], p[1], p[2], p[3]])
    }
}
