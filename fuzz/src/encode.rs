//! The inverse of `arbitrary`'s decoding for the shapes the inputs use (integers and floats
//! little-endian, `bool` as a byte, `Option` as a flag byte then the value, `Vec` as a `1`
//! byte before each element and a final `0`), so `examples/corpus.rs` can write the bytes of
//! a chosen input. Every written file is decoded back and compared, so a mismatch with
//! `arbitrary` is caught there, not silently.

/// Bytes being built, field after field, in declaration order.
#[derive(Debug, Default)]
pub struct Enc(pub Vec<u8>);

impl Enc {
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
    pub fn u8(&mut self, v: u8) -> &mut Self {
        self.0.push(v);
        self
    }
    pub fn u16(&mut self, v: u16) -> &mut Self {
        self.0.extend(v.to_le_bytes());
        self
    }
    pub fn u32(&mut self, v: u32) -> &mut Self {
        self.0.extend(v.to_le_bytes());
        self
    }
    pub fn u64(&mut self, v: u64) -> &mut Self {
        self.0.extend(v.to_le_bytes());
        self
    }
    pub fn bool(&mut self, v: bool) -> &mut Self {
        self.u8(u8::from(v))
    }
    pub fn f32(&mut self, v: f32) -> &mut Self {
        self.u32(v.to_bits())
    }
    pub fn f32s(&mut self, v: &[f32]) -> &mut Self {
        for x in v {
            self.f32(*x);
        }
        self
    }
    /// An `Option`: the flag byte, then the value when `Some`.
    pub fn opt(&mut self, v: Option<impl FnOnce(&mut Self)>) -> &mut Self {
        match v {
            Some(f) => {
                self.u8(1);
                f(self);
            }
            None => {
                self.u8(0);
            }
        }
        self
    }
    /// A `Vec` of `items`, each written by `f`.
    pub fn vec<T>(&mut self, items: &[T], mut f: impl FnMut(&mut Self, &T)) -> &mut Self {
        for item in items {
            self.u8(1);
            f(self, item);
        }
        self.u8(0)
    }
    #[must_use]
    pub fn bytes(&self) -> Vec<u8> {
        self.0.clone()
    }
}
