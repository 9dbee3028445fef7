//! A block's candidate balls: the union of the bit sets of the culling cells under it.

use super::{Core, Entry};

impl Core<2> {
    /// The candidate balls of the block from `origin` to `far`, in ball order: those whose
    /// bits are set in any of the cells under it (every ball whose padded cutoff box meets the
    /// block), gathered in `seen` (zeros on entry); `None` when the grid keeps no bits or the
    /// block covers more than [`MAX_BLOCK_CELLS`] cells. A field of at most 64 balls keeps its
    /// one word in a register, not in `seen`.
    #[inline]
    pub(super) fn bit_candidates<'s>(
        &'s self,
        origin: [f32; 2],
        far: [f32; 2],
        seen: &'s mut [u64; BIT_WORDS],
    ) -> Option<BitBalls<'s, 2>> {
        let words = self.words;
        if words == 0 {
            return None;
        }
        let width = self.dims[0];
        let (x0, x1) = (self.clamp_axis(0, origin[0]), self.clamp_axis(0, far[0]));
        let (y0, y1) = (self.clamp_axis(1, origin[1]), self.clamp_axis(1, far[1]));
        if (x1 - x0 + 1) * (y1 - y0 + 1) > MAX_BLOCK_CELLS {
            return None;
        }
        if words == 1 {
            let mut bits = 0;
            for y in y0..=y1 {
                let row = y * width;
                for x in x0..=x1 {
                    bits |= self.bits[row + x];
                }
            }
            // The one word, already loaded: no words left to read.
            return Some(BitBalls {
                words: &[],
                base: 64,
                bits,
                balls: &self.balls,
            });
        }
        for y in y0..=y1 {
            let row = y * width;
            for x in x0..=x1 {
                let at = (row + x) * words;
                for (w, word) in seen.iter_mut().enumerate().take(words) {
                    *word |= self.bits[at + w];
                }
            }
        }
        Some(BitBalls {
            words: &seen[..words],
            base: 0,
            bits: 0,
            balls: &self.balls,
        })
    }
}

/// 2D fields of up to `64 ×` this many balls keep a bit set of balls per culling cell.
pub(super) const BIT_WORDS: usize = 4;

/// The balls whose bits are set in `words` (bit `i % 64` of word `i / 64` for ball `i`), in
/// ball order.
pub(super) struct BitBalls<'a, const D: usize> {
    pub(super) words: &'a [u64],
    /// 64 more than the index of the first ball of the word in `bits`.
    pub(super) base: usize,
    /// What is left of the current word.
    pub(super) bits: u64,
    pub(super) balls: &'a [Entry<D>],
}

impl<'a, const D: usize> Iterator for BitBalls<'a, D> {
    type Item = &'a Entry<D>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        while self.bits == 0 {
            let (&first, rest) = self.words.split_first()?;
            self.bits = first;
            self.words = rest;
            self.base += 64;
        }
        let i = self.base - 64 + self.bits.trailing_zeros() as usize;
        self.bits &= self.bits - 1;
        // Only the bits of balls are ever set.
        Some(&self.balls[i])
    }
}

/// A block spanning more culling cells than this visits every ball instead of merging the
/// cells' lists.
pub(super) const MAX_BLOCK_CELLS: usize = 16;
