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
        Self { words: [0; WORDS] }
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
    /// clearing those words; runs are cut at `limit` (pixels from `limit` on are dropped).
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
                    // Shifting brought zeros in at the top: a run reaching bit 31 stays open.
                    let ones = (!bits).trailing_zeros();
                    if pos + ones >= 32 {
                        break;
                    }
                    let x1 = (base + (pos + ones) as usize).min(limit);
                    if start < x1 {
                        run(start, x1)?;
                    }
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
            let x1 = (end * 32).min(limit);
            if start < x1 {
                run(start, x1)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A xorshift generator, so the tests need no dependency.
    fn words(seed: &mut u64) -> u32 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 16) as u32
    }

    #[test]
    fn prefix_xor_equals_bit_by_bit_running_xor() {
        let mut seed = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..10_000 {
            let w = words(&mut seed) & words(&mut seed);
            let mut expected = 0u32;
            let mut parity = 0u32;
            for k in 0..32 {
                parity ^= (w >> k) & 1;
                expected |= parity << k;
            }
            assert_eq!(prefix_xor(w), expected, "word {w:#010x}");
        }
    }

    #[test]
    fn fill_and_drain_give_the_runs_between_toggles_across_words() {
        let mut seed = 0x1234_5678_9ABC_DEF1;
        for _ in 0..2_000 {
            let mut row = CodeRow::<4>::new();
            let mut flags = [false; 128];
            for _ in 0..(words(&mut seed) % 9) {
                let x = (words(&mut seed) % 128) as usize;
                row.toggle(x);
                flags[x] = !flags[x];
            }
            let limit = 100 + (words(&mut seed) % 29) as usize;
            let mut expected = [false; 128];
            let mut parity = false;
            for x in 0..128 {
                parity ^= flags[x];
                expected[x] = parity && x < limit;
            }
            row.fill(0, 4);
            let mut got = [false; 128];
            let mut last_end = None;
            row.drain_runs(0, 4, limit, |x0, x1| {
                assert!(x0 < x1 && x1 <= limit, "run {x0}..{x1} beyond {limit}");
                assert_ne!(
                    last_end,
                    Some(x0),
                    "runs that touch must be joined: {flags:?} limit {limit}"
                );
                last_end = Some(x1);
                got[x0..x1].iter_mut().for_each(|p| *p = true);
                Ok::<(), ()>(())
            })
            .unwrap();
            assert_eq!(got, expected);
            assert_eq!(row, CodeRow::new(), "drain leaves the row cleared");
        }
    }
}
