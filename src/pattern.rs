//! The P-buffer's filtering pattern (Yuan and Sun's P-buffer paper): a small bit pattern
//! repeated over
//! the screen. A hidden edge pixel at (x, y) is drawn where the bit at
//! (x mod width, y mod height) is 1.

/// A `width` x `height` bit pattern, at most 32 x 32, bit-packed one `u32` per row:
/// bit `x` of `rows[y]` is the value at (x, y).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pattern {
    rows: [u32; 32],
    width: u8,
    height: u8,
}

impl Default for Pattern {
    fn default() -> Self {
        Self::PAPER
    }
}

/// `rotate_left` for an 8-bit row held in a `u32`.
const fn rot8(bits: u32, by: u32) -> u32 {
    ((bits << (by % 8)) | (bits >> ((8 - by % 8) % 8))) & 0xFF
}

// Indexing: y < 8 on a [u32; 32] (a const fn cannot use `get_mut`).
#[allow(clippy::indexing_slicing)]
const fn rotated_rows(base: u32, step: u32) -> [u32; 32] {
    let mut rows = [0u32; 32];
    let mut y = 0;
    while y < 8 {
        rows[y] = rot8(base, step * y as u32);
        y += 1;
    }
    rows
}

impl Pattern {
    /// The default, in the spirit of the paper's 8x8 pattern (its Fig. 3(a) is lost
    /// in the text we have): four on, four off in every row, each row shifted two
    /// bits from the last, so that horizontal, vertical and both diagonal lines are
    /// all broken into dashes (a chess board passes or blocks whole diagonals).
    pub const PAPER: Pattern = Pattern {
        rows: rotated_rows(0xF0, 2),
        width: 8,
        height: 8,
    };

    /// A 2 x 2 chess board: dots on horizontal and vertical lines, and the paper's
    /// counter-example: a diagonal line is wholly passed or wholly blocked.
    pub const CHECKER: Pattern = {
        let mut rows = [0u32; 32];
        rows[0] = 0b01;
        rows[1] = 0b10;
        Pattern {
            rows,
            width: 2,
            height: 2,
        }
    };

    /// Sparse dots: one pixel in two along rows and columns of a 4x4 tile; hidden
    /// lines come out dotted.
    pub const DOTS: Pattern = {
        let mut rows = [0u32; 32];
        rows[0] = 0b0101;
        rows[1] = 0b1010;
        rows[2] = 0b0000;
        rows[3] = 0b0000;
        Pattern {
            rows,
            width: 4,
            height: 4,
        }
    };

    /// Long dashes: 6 on, 2 off, shifted three bits per row (8x8).
    pub const LONG_DASH: Pattern = Pattern {
        rows: rotated_rows(0x3F, 3),
        width: 8,
        height: 8,
    };

    /// Every bit set: hidden lines drawn solid (a wireframe with depth).
    pub const SOLID: Pattern = {
        let mut rows = [0u32; 32];
        rows[0] = 1;
        Pattern {
            rows,
            width: 1,
            height: 1,
        }
    };

    /// The stock patterns by name: `paper`, `checker`, `dots`, `long-dash`, `solid`.
    pub fn by_name(name: &str) -> Option<Pattern> {
        match name {
            "paper" => Some(Self::PAPER),
            "checker" => Some(Self::CHECKER),
            "dots" => Some(Self::DOTS),
            "long-dash" => Some(Self::LONG_DASH),
            "solid" => Some(Self::SOLID),
            _ => None,
        }
    }

    /// A pattern from rows (bit x of `rows[y]` is the value at (x, y)); `None` unless
    /// `1 <= width, height <= 32` and `rows.len() == height`. Bits at or beyond
    /// `width` are ignored.
    pub fn new(width: u8, height: u8, rows: &[u32]) -> Option<Pattern> {
        if !(1..=32).contains(&width) || !(1..=32).contains(&height) {
            return None;
        }
        if rows.len() != usize::from(height) {
            return None;
        }
        let mask = u32::MAX >> (32 - u32::from(width));
        let mut packed = [0u32; 32];
        for (dst, src) in packed.iter_mut().zip(rows) {
            *dst = src & mask;
        }
        Some(Pattern {
            rows: packed,
            width,
            height,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u8 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u8 {
        self.height
    }

    /// The value at screen pixel (x, y): true passes a hidden edge pixel.
    pub fn passes(&self, x: u32, y: u32) -> bool {
        let row = self.row_bits(y);
        (row >> modulo(x, u32::from(self.width.max(1)))) & 1 == 1
    }

    fn row_bits(&self, y: u32) -> u32 {
        let h = u32::from(self.height.max(1));
        self.rows.get(modulo(y, h) as usize).copied().unwrap_or(0)
    }

    /// Whether the width divides 32 (1 to 32 pixels: a power of two), so
    /// that one word holds a row's repeats at any multiple of 32.
    pub fn divides_word(&self) -> bool {
        self.width.is_power_of_two()
    }

    /// Screen row `y`'s pattern, replicated over the 32 pixels starting at `x0`
    /// (`x0` a multiple of 32): bit k is the value at (x0 + k, y). One shift-or per
    /// doubling when the width divides 32, a bit at a time otherwise.
    pub fn word(&self, x0: u32, y: u32) -> u32 {
        let w = u32::from(self.width.max(1));
        let row = self.row_bits(y);
        if self.divides_word() {
            let mut word = row;
            let mut span = w;
            while span < 32 {
                word |= word << span;
                span *= 2;
            }
            word
        } else {
            (0..32).fold(0u32, |acc, k| acc | (((row >> ((x0 + k) % w)) & 1) << k))
        }
    }
}

/// `a % m` (`m > 0`), a mask for a power of two: a Cortex-M0 has no divide
/// instruction, and its division call took 3 % of the panel's frame.
fn modulo(a: u32, m: u32) -> u32 {
    if m.is_power_of_two() {
        a & (m - 1)
    } else {
        a % m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_replicate_the_pattern_exactly() {
        let odd = Pattern::new(5, 3, &[0b10110, 0b00001, 0b11111]).unwrap();
        for p in [
            Pattern::PAPER,
            Pattern::CHECKER,
            Pattern::DOTS,
            Pattern::LONG_DASH,
            odd,
        ] {
            for y in 0..40 {
                for x0 in [0, 32, 64, 96] {
                    let w = p.word(x0, y);
                    for k in 0..32 {
                        assert_eq!(
                            (w >> k) & 1 == 1,
                            p.passes(x0 + k, y),
                            "{p:?} at {},{y}",
                            x0 + k
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn paper_pattern_dashes_rows_columns_and_diagonals() {
        let p = Pattern::PAPER;
        for c in 0..8u32 {
            let count = |f: &dyn Fn(u32) -> (u32, u32)| {
                (0..8)
                    .filter(|&t| {
                        let (x, y) = f(t);
                        p.passes(x, y)
                    })
                    .count()
            };
            for line in [
                count(&|t| (t, c)),         // horizontal
                count(&|t| (c, t)),         // vertical
                count(&|t| (t + c, t)),     // diagonal
                count(&|t| (c + 8 - t, t)), // anti-diagonal
            ] {
                assert!(
                    line > 0 && line < 8,
                    "every line is broken, never erased: {line}"
                );
            }
        }
    }

    #[test]
    fn bad_sizes_are_refused() {
        assert!(Pattern::new(0, 1, &[1]).is_none());
        assert!(Pattern::new(33, 1, &[1]).is_none());
        assert!(Pattern::new(2, 2, &[1]).is_none());
        assert_eq!(Pattern::by_name("nope"), None);
    }
}
