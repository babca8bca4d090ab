//! Modulo-2 edge-flag filling (the modulo-2 surface-filling paper's filler, with a
//! one-surface code).
//!
//! Each crossing XORs a flag into a bit-packed row; a running XOR, a word at a time,
//! fills between flags. No sorting of crossings is needed: the XOR is order-free.
//! It computes the even-odd rule, and gives exactly the pixels of
//! [`ScanConverter`](crate::ScanConverter) with [`FillRule::EvenOdd`](crate::FillRule).

mod row;

pub use row::{prefix_xor, CodeRow};

use fixed::types::extra::LeEqU32;

use super::{PolygonWalker, RowRuns};
use crate::Capacity;
use crate::{Error, ScreenPoint, SpanSink};

/// An even-odd polygon filler that uses a modulo-2 code row instead of sorted
/// crossings: room for `EDGES` edges and rows of up to `32 * WORDS` pixels.
///
/// ```
/// use embedded_graphics::pixelcolor::BinaryColor;
/// use fixed::types::extra::U0;
/// use pbuffer::{packed_len, PackedFramebuffer, ScreenPoint, XorFiller};
///
/// let mut fb = PackedFramebuffer::<64, 8, { packed_len(64, 8) }>::new();
/// let quad = [(0, 0), (40, 0), (40, 4), (0, 4)].map(|(x, y)| ScreenPoint::<U0>::from_bits(x, y));
/// XorFiller::<8, 2>::new().fill(&quad, BinaryColor::On, &mut fb)?;
/// assert_eq!(fb.as_bytes().iter().map(|b| b.count_ones()).sum::<u32>(), 160);
/// # Ok::<(), pbuffer::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct XorFiller<const EDGES: usize, const WORDS: usize> {
    walker: PolygonWalker<EDGES>,
    row: CodeRow<WORDS>,
}

impl<const EDGES: usize, const WORDS: usize> Default for XorFiller<EDGES, WORDS> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const EDGES: usize, const WORDS: usize> XorFiller<EDGES, WORDS> {
    /// Empty working memory.
    pub const fn new() -> Self {
        Self {
            walker: PolygonWalker::new(),
            row: CodeRow::new(),
        }
    }

    /// Fills the polygon `points` with `color` under the even-odd rule.
    ///
    /// Errors, before anything is drawn: fewer than 3 vertices, more than `EDGES`
    /// edges crossing the viewport's rows, a viewport wider than `32 * WORDS`.
    pub fn fill<Frac: LeEqU32, K: SpanSink>(
        &mut self,
        points: &[ScreenPoint<Frac>],
        color: K::Color,
        sink: &mut K,
    ) -> Result<(), Error<K::Error>> {
        let viewport = sink.viewport();
        let width = usize::from(viewport.width);
        let words = width.div_ceil(32);
        if words > WORDS {
            return Err(Error::CapacityExceeded {
                what: Capacity::RowWords,
                needed: words,
                capacity: WORDS,
            });
        }
        let window = crate::scan::RowRange {
            first: 0,
            end: i32::from(viewport.height),
        };
        self.walker
            .begin(points, viewport, window)
            .map_err(Error::widen)?;
        while let Some((y, crossings)) = self.walker.next_row(points, false) {
            let mut first = words;
            let mut last = 0;
            let mut toggled = 0usize;
            // A crossing at x = width counts for no pixel of the row: skip it.
            for x in crossings
                .iter()
                .map(|c| usize::from(c.x))
                .filter(|&x| x < width)
            {
                self.row.toggle(x);
                first = first.min(x / 32);
                last = last.max(x / 32);
                toggled += 1;
            }
            if toggled == 0 {
                continue;
            }
            // An odd count means the last run is closed beyond the right edge.
            let end = if toggled % 2 == 1 { words } else { last + 1 };
            self.row.fill(first, end);
            let mut runs = RowRuns::new(y, color);
            self.row
                .drain_runs(first, end, width, |x0, x1| {
                    runs.push(x0 as u16, x1 as u16, sink)
                })
                .map_err(Error::Target)?;
            runs.finish(sink).map_err(Error::Target)?;
        }
        sink.flush().map_err(Error::Target)
    }
}
