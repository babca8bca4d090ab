//! The paper's pattern table `pattern[x % l][y % l]`, filled from the library's.

/// The pattern as the paper keeps it: `pattern[x % l][y % l]`, a table of 0/1
/// (`l` x `l'` for a `l` x `l'` pattern), filled from the library's `Pattern` of the
/// same name.
pub struct PatternTable {
    pub(super) w: usize,
    pub(super) h: usize,
    /// `bits[x * h + y]`.
    pub(super) bits: Vec<u8>,
}

impl PatternTable {
    /// The table of the library pattern `name` (`None` if the library has none).
    pub fn by_name(name: &str) -> Option<Self> {
        let p = pbuffer::Pattern::by_name(name)?;
        let (w, h) = (
            usize::from(p.width()).max(1),
            usize::from(p.height()).max(1),
        );
        let mut bits = vec![0u8; w * h];
        for x in 0..w {
            for y in 0..h {
                bits[x * h + y] = u8::from(p.passes(x as u32, y as u32));
            }
        }
        Some(Self { w, h, bits })
    }

    /// The paper's `value_Pattern(x, y)`: 1 = pass, 0 = block.
    #[inline]
    pub fn value(&self, x: usize, y: usize) -> u8 {
        self.bits[(x % self.w) * self.h + y % self.h]
    }
}
