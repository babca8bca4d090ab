//! A bit-packed row for modulo-2 (XOR) edge-flag filling.

/// One row of `WORDS` 32-bit words, one bit per pixel: bit `k` of word `w` is pixel
/// `32w + k`. Edge crossings toggle bits; a running XOR from left to right then
/// leaves bit x set exactly when an odd number of crossings lie at or left of x.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CodeRow<const WORDS: usize> {
    words: [u32; WORDS],
}

impl<const WORDS: usize> Default for CodeRow<WORDS> {
    fn default() -> Self {
        Self::new()
    }
}

/// Prefix XOR inside a word, from bit 0 upward: bit k becomes the XOR of bits 0..=k.
#[inline(always)]
pub const fn prefix_xor(mut w: u32) -> u32 {
    w ^= w << 1;
    w ^= w << 2;
    w ^= w << 4;
    w ^= w << 8;
    w ^= w << 16;
    w
}

impl<const WORDS: usize> CodeRow<WORDS> {
    /// Number of pixels the row holds.
    pub const PIXELS: usize = WORDS * 32;

    /// A cleared row.
    pub const fn new() -> Self {
        Self {
            words: [0; WORDS],
        }
    }

    /// Flips the flag of pixel `x`; pixels beyond the row are ignored (a crossing
    /// there counts for no pixel of the row).
    #[inline(always)]
    pub fn toggle(&mut self, x: usize) {
        if let Some(w) = self.words.get_mut(x / 32) {
            *w ^= 1 << (x % 32);
        }
    }

    /// Runs the XOR fill over words `first..end` (the words left of `first` must be
    /// zero), a word at a time: a parallel prefix XOR inside the word and the carry
    /// (the parity so far) from the word before.
    #[inline]
    pub fn fill(&mut self, first: usize, end: usize) {
        let mut carry = 0u32;
        for w in self.words.get_mut(first..end).into_iter().flatten() {
            let filled = prefix_xor(*w) ^ carry.wrapping_neg();
            carry = filled >> 31;
            *w = filled;
        }
    }

    /// Calls `run(x0, x1)` for each maximal run of set pixels in words `first..end`,
    /// clearing those words; runs are cut at `limit`.
    #[inline]
    pub fn drain_runs<E>(
        &mut self,
        first: usize,
        end: usize,
        limit: usize,
        mut run: impl FnMut(usize, usize) -> Result<(), E>,
    ) -> Result<(), E> {
        let mut open: Option<usize> = None;
        let words = self.words.get_mut(first..end).into_iter().flatten();
        for (i, w) in words.enumerate() {
            let base = (first + i) * 32;
            let mut bits = core::mem::take(w);
            let mut pos = 0u32;
            // Walk alternating runs of ones and zeros inside the word.
            while pos < 32 {
                if let Some(start) = open {
                    let ones = (!bits).trailing_zeros();
                    if ones >= 32 {
                        break;
                    }
                    let x1 = base + (pos + ones) as usize;
                    run(start, x1.min(limit))?;
                    open = None;
                    bits >>= ones;
                    pos += ones;
                } else {
                    if bits == 0 {
                        break;
                    }
                    let zeros = bits.trailing_zeros();
                    open = Some(base + (pos + zeros) as usize);
                    bits >>= zeros;
                    pos += zeros;
                }
            }
        }
        if let Some(start) = open {
            run(start, (end * 32).min(limit))?;
        }
        Ok(())
    }
}
