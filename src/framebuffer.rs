//! A packed 1-bit-per-pixel framebuffer, the fast path for monochrome panels.

use core::convert::Infallible;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::BinaryColor;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

use crate::{Span, SpanSink, Viewport};

/// Bytes needed by a `width` x `height` [`PackedFramebuffer`]: `ceil(width / 8) * height`.
pub const fn packed_len(width: usize, height: usize) -> usize {
    width.div_ceil(8) * height
}

/// A `W` x `H` monochrome framebuffer, one bit per pixel, `N = packed_len(W, H)` bytes.
///
/// Layout: row-major, MSB first. Row y starts at byte `y * ceil(W / 8)`; pixel x of
/// that row is bit `7 - x % 8` of byte `x / 8`; a set bit is [`BinaryColor::On`].
/// This is the line format of Sharp memory LCDs (LS013B7DH03, LS027B7DH01: each line
/// is sent as `ceil(W/8)` such bytes after its address; some drivers shift them out
/// LSB first and reverse the bits themselves) and of embedded-graphics'
/// `ImageRaw<BinaryColor>`. SSD1306 and SH1106 controllers take *vertical page* bytes
/// instead (8 rows per byte, LSB on top): [`PackedFramebuffer::page_byte`] converts.
///
/// Spans are written as a masked first byte, one slice fill for the whole bytes (a
/// word-wide `memset`) and a masked last byte: never pixel by pixel.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct PackedFramebuffer<const W: usize, const H: usize, const N: usize> {
    bytes: [u8; N],
}

impl<const W: usize, const H: usize, const N: usize> Default for PackedFramebuffer<W, H, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const W: usize, const H: usize, const N: usize> PackedFramebuffer<W, H, N> {
    /// Bytes per row.
    pub const STRIDE: usize = W.div_ceil(8);

    /// Compile-time check of the size parameters.
    const VALID: () = {
        assert!(N == packed_len(W, H), "N must equal packed_len(W, H)");
        assert!(W <= crate::MAX_VIEWPORT as usize && H <= crate::MAX_VIEWPORT as usize);
    };

    /// A framebuffer with every pixel off.
    pub const fn new() -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::VALID;
        Self { bytes: [0; N] }
    }

    /// The packed bytes, row-major, MSB first (see the type's docs).
    pub const fn as_bytes(&self) -> &[u8; N] {
        &self.bytes
    }

    /// Turns every pixel off.
    pub fn clear(&mut self) {
        self.bytes = [0; N];
    }

    /// True when pixel (x, y) is on; false outside the framebuffer.
    pub fn pixel(&self, x: u32, y: u32) -> bool {
        let (x, y) = (x as usize, y as usize);
        x < W
            && y < H
            && self
                .bytes
                .get(y * Self::STRIDE + x / 8)
                .is_some_and(|b| b & (0x80 >> (x % 8)) != 0)
    }

    /// Byte `column` of page `page` in SSD1306/SH1106 order: bit k is pixel
    /// (column, 8 * page + k); pixels below the framebuffer read as off.
    pub fn page_byte(&self, page: u32, column: u32) -> u8 {
        (0..8).fold(0u8, |acc, k| {
            acc | (u8::from(self.pixel(column, page * 8 + k)) << k)
        })
    }

    /// Sets or clears `x0..x1` on row `y`; the caller keeps the run inside the buffer.
    fn write_run(&mut self, y: usize, x0: usize, x1: usize, on: bool) {
        let row = y * Self::STRIDE;
        let (first, last) = (row + x0 / 8, row + (x1 - 1) / 8);
        let head = 0xFFu8 >> (x0 % 8);
        let tail = 0xFFu8 << (7 - (x1 - 1) % 8);
        let apply = |b: &mut u8, mask: u8| {
            if on {
                *b |= mask;
            } else {
                *b &= !mask;
            }
        };
        if first == last {
            if let Some(b) = self.bytes.get_mut(first) {
                apply(b, head & tail);
            }
            return;
        }
        if let Some(b) = self.bytes.get_mut(first) {
            apply(b, head);
        }
        if let Some(mid) = self.bytes.get_mut(first + 1..last) {
            mid.fill(if on { 0xFF } else { 0 });
        }
        if let Some(b) = self.bytes.get_mut(last) {
            apply(b, tail);
        }
    }
}

impl<const W: usize, const H: usize, const N: usize> OriginDimensions
    for PackedFramebuffer<W, H, N>
{
    fn size(&self) -> Size {
        Size::new(W as u32, H as u32)
    }
}

impl<const W: usize, const H: usize, const N: usize> DrawTarget for PackedFramebuffer<W, H, N> {
    type Color = BinaryColor;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<BinaryColor>>,
    {
        for Pixel(p, color) in pixels {
            if let (Ok(x), Ok(y)) = (usize::try_from(p.x), usize::try_from(p.y)) {
                if x < W && y < H {
                    self.write_run(y, x, x + 1, color.is_on());
                }
            }
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: BinaryColor) -> Result<(), Infallible> {
        let area = area.intersection(&self.bounding_box());
        if let Some(br) = area.bottom_right() {
            // Inside the bounding box, so non-negative and below W, H.
            let (x0, x1) = (area.top_left.x as usize, br.x as usize + 1);
            for y in area.top_left.y as usize..=br.y as usize {
                self.write_run(y, x0, x1, color.is_on());
            }
        }
        Ok(())
    }

    fn clear(&mut self, color: BinaryColor) -> Result<(), Infallible> {
        let fill = if color.is_on() { 0xFF } else { 0 };
        self.bytes = [fill; N];
        // Keep the padding bits of each row off, so that hashes see only pixels.
        if W % 8 != 0 {
            let pad = 0xFFu8 >> (W % 8);
            for row in self.bytes.chunks_exact_mut(Self::STRIDE) {
                if let Some(b) = row.last_mut() {
                    *b &= !pad;
                }
            }
        }
        Ok(())
    }
}

/// Sets (`on`) or clears the pixels of one packed row (`row`: MSB-first bytes, the
/// [`PackedFramebuffer`] layout, `width` pixels) where `mask` has a bit (bit `k` of
/// word `w` is pixel `32w + k`; bits at or past `width` are ignored): four bytes a
/// word, the word's bits reversed. Returns the words that had a pixel.
pub fn write_mask(row: &mut [u8], width: usize, mask: &[u32], on: bool) -> u32 {
    let mut words = 0;
    for (k, (chunk, &word)) in row.chunks_mut(4).zip(mask).enumerate() {
        let left = width.saturating_sub(32 * k);
        let word = if left < 32 {
            word & ((1u32 << left) - 1)
        } else {
            word
        };
        if word == 0 {
            continue;
        }
        words += 1;
        let bits = word.reverse_bits();
        if let Ok(four) = <&mut [u8; 4]>::try_from(&mut *chunk) {
            // A whole word: one load and one store (about a third of the
            // byte-by-byte instructions on the Cortex-M4).
            let old = u32::from_be_bytes(*four);
            *four = if on { old | bits } else { old & !bits }.to_be_bytes();
            continue;
        }
        for (b, m) in chunk.iter_mut().zip(bits.to_be_bytes()) {
            if on {
                *b |= m;
            } else {
                *b &= !m;
            }
        }
    }
    words
}

impl<const W: usize, const H: usize, const N: usize> SpanSink for PackedFramebuffer<W, H, N> {
    type Color = BinaryColor;
    type Error = Infallible;

    fn viewport(&self) -> Viewport {
        // W, H <= MAX_VIEWPORT, checked at compile time in `new`.
        Viewport {
            width: W as u16,
            height: H as u16,
        }
    }

    fn fill_span(&mut self, span: Span, color: BinaryColor) -> Result<(), Infallible> {
        let (y, x0, x1) = (span.y().into(), span.x0().into(), span.x1().into());
        if x1 <= W && y < H {
            self.write_run(y, x0, x1, color.is_on());
        }
        Ok(())
    }

    /// Four bytes a word: the word's bits reversed are the row's MSB-first bytes.
    fn fill_mask(&mut self, y: u16, mask: &[u32], color: BinaryColor) -> Result<u32, Infallible> {
        let y = usize::from(y);
        if y >= H {
            return Ok(0);
        }
        let row = self
            .bytes
            .get_mut(y * Self::STRIDE..(y + 1) * Self::STRIDE)
            .unwrap_or_default();
        Ok(write_mask(row, W, mask, color.is_on()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics_core::geometry::Point;

    type Fb = PackedFramebuffer<21, 3, { packed_len(21, 3) }>;

    #[test]
    fn every_run_sets_exactly_its_pixels_msb_first() {
        for x0 in 0..21 {
            for x1 in x0 + 1..=21 {
                let mut fb = Fb::new();
                fb.write_run(1, x0, x1, true);
                for y in 0..3 {
                    for x in 0..24 {
                        let want = y == 1 && (x0..x1).contains(&(x as usize));
                        assert_eq!(fb.pixel(x, y), want, "run {x0}..{x1} pixel {x},{y}");
                    }
                }
                fb.write_run(1, x0, x1, false);
                assert_eq!(fb, Fb::new(), "clearing run {x0}..{x1}");
            }
        }
    }

    /// A 70-pixel row (two whole words and a tail of 6 pixels in a third):
    /// the mask's pixels, set and cleared, over a row of other pixels, exactly
    /// as pixel by pixel; bits past the width touch nothing.
    #[test]
    fn a_mask_sets_and_clears_exactly_its_pixels_whole_words_and_tail() {
        type Wide = PackedFramebuffer<70, 1, { packed_len(70, 1) }>;
        let mut seed = 0x9E37_79B9u32;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            seed
        };
        for round in 0..200 {
            let mut fb = Wide::new();
            let mut want = [false; 70];
            for (x, w) in want.iter_mut().enumerate() {
                *w = next() & 1 == 1;
                fb.write_run(0, x, x + 1, *w);
            }
            let mask = [next(), next(), next()];
            let on = round % 2 == 0;
            let words = fb.fill_mask(0, &mask, BinaryColor::from(on)).unwrap();
            let mut had = [false; 3];
            for (x, w) in want.iter_mut().enumerate() {
                if mask[x / 32] >> (x % 32) & 1 == 1 {
                    *w = on;
                    had[x / 32] = true;
                }
            }
            for (x, &w) in want.iter().enumerate() {
                assert_eq!(fb.pixel(x as u32, 0), w, "round {round} pixel {x}");
            }
            // The padding bits of the row's last byte stay off.
            assert_eq!(fb.bytes[8] & 0x03, 0, "round {round}");
            assert_eq!(words, had.iter().filter(|&&h| h).count() as u32);
        }
    }

    #[test]
    fn byte_layout_is_row_major_msb_first() {
        let mut fb = Fb::new();
        fb.draw_iter([
            Pixel(Point::new(0, 0), BinaryColor::On),
            Pixel(Point::new(9, 2), BinaryColor::On),
        ])
        .unwrap();
        assert_eq!(fb.as_bytes()[0], 0x80);
        assert_eq!(fb.as_bytes()[2 * 3 + 1], 0x40);
        assert_eq!(fb.as_bytes().iter().map(|b| b.count_ones()).sum::<u32>(), 2);
    }

    #[test]
    fn clear_on_leaves_row_padding_off_and_page_bytes_read_columns() {
        let mut fb = Fb::new();
        DrawTarget::clear(&mut fb, BinaryColor::On).unwrap();
        assert_eq!(
            fb.as_bytes()[2],
            0b1111_1000,
            "21 px: 5 bits of the third byte"
        );
        assert_eq!(
            fb.page_byte(0, 20),
            0b0000_0111,
            "3 rows on, rows 3..8 absent"
        );
        assert_eq!(fb.page_byte(0, 21), 0);
    }

    #[test]
    fn fill_solid_clips_to_the_buffer() {
        let mut fb = Fb::new();
        let area = Rectangle::new(Point::new(-5, -5), Size::new(100, 100));
        fb.fill_solid(&area, BinaryColor::On).unwrap();
        let mut full = Fb::new();
        DrawTarget::clear(&mut full, BinaryColor::On).unwrap();
        assert_eq!(fb, full);
    }
}
