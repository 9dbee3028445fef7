//! The creature workspace's fuzz targets, as a library: one module per target, each with its
//! `Input` (decoded by `arbitrary` from libFuzzer's bytes) and its `run`, which calls the
//! entry points and asserts what their docs promise. `fuzz_targets/*.rs` only forward to
//! these, so `examples/corpus.rs` can build the regression inputs from the same types.
//!
//! Every input carries a `valid` flag: when set, the floats are mapped into the documented
//! ranges (so the interesting paths run); when clear, they are used as they come (NaN,
//! infinities, `f32::MAX`), and the only promise checked is "a typed error or a finite
//! result, never a panic".

// Test code: a failed check is a panic, which is how libFuzzer sees a crash.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::std_instead_of_core,
    clippy::std_instead_of_alloc,
    clippy::cast_possible_truncation,
    missing_docs
)]

pub mod autorig;
pub mod encode;
pub mod export;
pub mod ffd;
pub mod gait;
pub mod generate_2d;
pub mod generate_3d;
pub mod limbs;
pub mod march_grid;
pub mod march_trace;
pub mod metaball_2d;
pub mod metaball_3d;
pub mod skin;
pub mod triangulate;

/// Maps `raw`'s bits uniformly onto `[lo, hi]` (every bit pattern, NaN included, lands inside).
#[must_use]
pub fn map(raw: f32, lo: f32, hi: f32) -> f32 {
    let t = f64::from(raw.to_bits()) / f64::from(u32::MAX);
    let v = f64::from(lo) + (f64::from(hi) - f64::from(lo)) * t;
    (v as f32).clamp(lo, hi)
}

/// `map(raw, lo, hi)` for a valid-range input, `raw` itself otherwise.
#[must_use]
pub fn pick(valid: bool, raw: f32, lo: f32, hi: f32) -> f32 {
    if valid { map(raw, lo, hi) } else { raw }
}

/// Three floats through [`pick`].
#[must_use]
pub fn pick3(valid: bool, raw: [f32; 3], lo: f32, hi: f32) -> glam::Vec3 {
    glam::Vec3::new(
        pick(valid, raw[0], lo, hi),
        pick(valid, raw[1], lo, hi),
        pick(valid, raw[2], lo, hi),
    )
}

/// Two floats through [`pick`].
#[must_use]
pub fn pick2(valid: bool, raw: [f32; 2], lo: f32, hi: f32) -> glam::Vec2 {
    glam::Vec2::new(pick(valid, raw[0], lo, hi), pick(valid, raw[1], lo, hi))
}

/// Asserts that a GLB file is well formed at the container level: the `glTF` magic, version
/// 2, the header's length equal to the byte count, and chunks (JSON first) that tile the rest
/// exactly, each 4-byte aligned. The JSON chunk must parse as UTF-8 starting with `{`.
pub fn check_glb(bytes: &[u8]) {
    assert!(bytes.len() >= 20, "GLB of {} bytes", bytes.len());
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    assert_eq!(&bytes[0..4], b"glTF", "GLB magic");
    assert_eq!(word(4), 2, "GLB version");
    assert_eq!(word(8), bytes.len(), "GLB header length");
    let mut at = 12;
    let mut first = true;
    while at < bytes.len() {
        assert!(at + 8 <= bytes.len(), "truncated GLB chunk header at {at}");
        let (len, kind) = (word(at), word(at + 4));
        assert_eq!(len % 4, 0, "GLB chunk length {len} not 4-aligned");
        assert!(at + 8 + len <= bytes.len(), "GLB chunk past the end");
        if first {
            assert_eq!(kind, 0x4E4F_534A, "first GLB chunk is not JSON");
            let json = std::str::from_utf8(&bytes[at + 8..at + 8 + len]).expect("JSON chunk UTF-8");
            assert!(
                json.starts_with('{'),
                "JSON chunk: {}",
                &json[..json.len().min(40)]
            );
            first = false;
        } else {
            assert_eq!(kind, 0x004E_4942, "second GLB chunk is not BIN");
        }
        at += 8 + len;
    }
    assert!(!first, "GLB without a JSON chunk");
}

/// Decodes a PNG with the `png` crate and returns its size and RGBA8 pixels, asserting the
/// decoder accepts it and the pixel buffer has the declared size.
#[must_use]
pub fn decode_png(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().expect("PNG header decodes");
    let (w, h) = (reader.info().width, reader.info().height);
    let mut buf = vec![0; reader.output_buffer_size().expect("PNG buffer size")];
    let info = reader.next_frame(&mut buf).expect("PNG frame decodes");
    assert_eq!((info.width, info.height), (w, h));
    assert_eq!(info.color_type, png::ColorType::Rgba, "PNG is RGBA");
    assert_eq!(
        info.bit_depth,
        png::BitDepth::Eight,
        "PNG is 8 bits per channel"
    );
    buf.truncate(info.buffer_size());
    assert_eq!(buf.len(), w as usize * h as usize * 4, "PNG pixel count");
    (w, h, buf)
}

/// Asserts a 2D/3D creature image is consistent: `rgba` holds `width × height` pixels.
pub fn check_image(image: &creature::Image) {
    assert_eq!(
        image.rgba.len() as u64,
        u64::from(image.width) * u64::from(image.height) * 4,
        "image {}x{} with {} bytes",
        image.width,
        image.height,
        image.rgba.len()
    );
}

/// Asserts a glTF-style skin vertex: weights finite, non-negative, summing to 1 within 1e-5,
/// and every joint with a positive weight below `joints`.
pub fn check_weights(weights: [f32; 4], joint_ids: [u16; 4], joints: usize) {
    let sum: f32 = weights.iter().sum();
    assert!(
        weights.iter().all(|w| w.is_finite() && *w >= 0.0) && (sum - 1.0).abs() <= 1e-5,
        "weights {weights:?} (sum {sum})"
    );
    for (w, j) in weights.iter().zip(joint_ids) {
        assert!(
            *w == 0.0 || usize::from(j) < joints,
            "joint {j} of {joints} with weight {w}"
        );
    }
}

/// A `Span` of the facade's params: `[a, b]` as they come for an extreme input, else both
/// mapped into `[lo, hi]` and ordered.
#[must_use]
pub fn span(extreme: bool, a: f32, b: f32, lo: f32, hi: f32) -> creature::Span {
    if extreme {
        creature::Span::new(a, b)
    } else {
        let (a, b) = (map(a, lo, hi), map(b, lo, hi));
        creature::Span::new(a.min(b), a.max(b))
    }
}
