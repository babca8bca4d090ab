//! Scan conversion of screen-space polygons into spans: the span core.
//!
//! Coverage follows [conventions](crate::conventions) exactly: pixel (i, j) is covered when its
//! centre, nudged by `(+e, +e^2)`, is inside the polygon (even-odd, or non-zero
//! winding as an option). This is the top-left rule, and it makes shared edges
//! watertight. Every decision is integer arithmetic on the snapped vertices; see
//! [`edge`](self) for the DDA and the bounds that keep it from overflowing.

pub(crate) mod edge;
mod walk;
mod xor;

use embedded_graphics_core::pixelcolor::PixelColor;
use fixed::types::extra::LeEqU32;

pub use edge::EdgeTable;
pub(crate) use walk::{Crossing, PolygonWalker};
pub use xor::{prefix_xor, CodeRow, XorFiller};

use crate::{Error, ScreenPoint, Span, SpanSink};

/// Which points count as inside a polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FillRule {
    /// An odd number of boundary crossings to the left (the modulo-2 rule).
    #[default]
    EvenOdd,
    /// A non-zero sum of edge directions to the left.
    NonZero,
}

/// Rows `first..end` of the viewport.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct RowRange {
    pub first: i32,
    pub end: i32,
}

impl RowRange {
    pub fn contains(&self, row: i32) -> bool {
        self.first <= row && row < self.end
    }
}

/// A scan-line polygon filler with room for `EDGES` edges: an edge table, an active
/// edge list and one row of crossings, all fixed-size. Spans go to a [`SpanSink`].
///
/// ```
/// use embedded_graphics::pixelcolor::BinaryColor;
/// use fixed::types::extra::U4;
/// use pbuffer::{packed_len, FillRule, PackedFramebuffer, ScanConverter, ScreenPoint};
///
/// let mut fb = PackedFramebuffer::<16, 8, { packed_len(16, 8) }>::new();
/// let triangle = [
///     ScreenPoint::<U4>::from_f32(1.0, 1.0)?,
///     ScreenPoint::from_f32(15.0, 1.0)?,
///     ScreenPoint::from_f32(1.0, 7.0)?,
/// ];
/// let mut filler = ScanConverter::<8>::new();
/// filler.fill(&triangle, FillRule::EvenOdd, BinaryColor::On, &mut fb)?;
/// assert!(fb.pixel(1, 1) && !fb.pixel(14, 6));
/// # Ok::<(), pbuffer::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct ScanConverter<const EDGES: usize> {
    walker: PolygonWalker<EDGES>,
}

impl<const EDGES: usize> Default for ScanConverter<EDGES> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const EDGES: usize> ScanConverter<EDGES> {
    /// Empty working memory.
    pub const fn new() -> Self {
        Self {
            walker: PolygonWalker::new(),
        }
    }

    /// Fills the polygon `points` (3 or more vertices, closed implicitly) with
    /// `color` under `rule`, sending one span per covered run to `sink`.
    ///
    /// Errors, before anything is drawn: fewer than 3 vertices, more than `EDGES`
    /// edges crossing the viewport's rows. A zero-area polygon draws nothing.
    pub fn fill<Frac: LeEqU32, K: SpanSink>(
        &mut self,
        points: &[ScreenPoint<Frac>],
        rule: FillRule,
        color: K::Color,
        sink: &mut K,
    ) -> Result<(), Error<K::Error>> {
        let viewport = sink.viewport();
        self.fill_rows(points, rule, 0..viewport.height, color, sink)
    }

    /// Like [`fill`](Self::fill), but only for the rows `rows` (clamped to the
    /// viewport): the edges are set up at the first row of the window, so a renderer
    /// that works in bands of rows walks each band's edges only. `needed` in a
    /// `CapacityExceeded` error counts the edges that cross the window.
    pub fn fill_rows<Frac: LeEqU32, K: SpanSink>(
        &mut self,
        points: &[ScreenPoint<Frac>],
        rule: FillRule,
        rows: core::ops::Range<u16>,
        color: K::Color,
        sink: &mut K,
    ) -> Result<(), Error<K::Error>> {
        let viewport = sink.viewport();
        let window = RowRange {
            first: i32::from(rows.start),
            end: i32::from(rows.end.min(viewport.height)),
        };
        self.walker
            .begin(points, viewport, window)
            .map_err(Error::widen)?;
        while let Some((y, crossings)) = self.walker.next_row(points, true) {
            emit_row(y, crossings, rule, viewport.width, color, sink).map_err(Error::Target)?;
        }
        sink.flush().map_err(Error::Target)
    }
}

/// Collects one row's runs of one colour and sends them to a sink, joining runs
/// that touch so each maximal run is one span.
#[derive(Debug)]
pub(crate) struct RowRuns<C> {
    y: u16,
    color: C,
    pending: Option<(u16, u16)>,
}

impl<C: PixelColor> RowRuns<C> {
    pub fn new(y: u16, color: C) -> Self {
        Self {
            y,
            color,
            pending: None,
        }
    }

    /// Adds the run `x0..x1`; empty runs are ignored.
    #[inline]
    pub fn push<K: SpanSink<Color = C>>(
        &mut self,
        x0: u16,
        x1: u16,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        if x0 >= x1 {
            return Ok(());
        }
        match self.pending {
            Some((a, b)) if b == x0 => self.pending = Some((a, x1)),
            Some((a, b)) => {
                sink.fill_span(Span::new(self.y, a, b), self.color)?;
                self.pending = Some((x0, x1));
            }
            None => self.pending = Some((x0, x1)),
        }
        Ok(())
    }

    /// Sends the last run.
    pub fn finish<K: SpanSink<Color = C>>(self, sink: &mut K) -> Result<(), K::Error> {
        match self.pending {
            Some((a, b)) => sink.fill_span(Span::new(self.y, a, b), self.color),
            None => Ok(()),
        }
    }
}

/// Turns a row's sorted crossings into spans under `rule`.
fn emit_row<K: SpanSink>(
    y: u16,
    crossings: &[Crossing],
    rule: FillRule,
    width: u16,
    color: K::Color,
    sink: &mut K,
) -> Result<(), K::Error> {
    let mut runs = RowRuns::new(y, color);
    let mut start = 0;
    match rule {
        FillRule::EvenOdd => {
            let mut inside = false;
            for c in crossings {
                if inside {
                    runs.push(start, c.x, sink)?;
                } else {
                    start = c.x;
                }
                inside = !inside;
            }
            if inside {
                runs.push(start, width, sink)?;
            }
        }
        FillRule::NonZero => {
            let mut winding: i32 = 0;
            for c in crossings {
                let was_inside = winding != 0;
                winding += i32::from(c.winding);
                match (was_inside, winding != 0) {
                    (false, true) => start = c.x,
                    (true, false) => runs.push(start, c.x, sink)?,
                    _ => {}
                }
            }
            if winding != 0 {
                runs.push(start, width, sink)?;
            }
        }
    }
    runs.finish(sink)
}
