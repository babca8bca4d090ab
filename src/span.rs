//! Spans, the core abstraction: half-open runs `(y, x0..x1)` of one colour, and
//! the sinks that take them.

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, Point, Size};
use embedded_graphics_core::pixelcolor::PixelColor;
use embedded_graphics_core::primitives::Rectangle;
use heapless::Vec;

use crate::{Error, Viewport};

/// A run of pixels `x0..x1` on row `y`, already clipped to its viewport:
/// `x0 < x1 <= width` and `y < height`. Only the rasterizers make spans.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Span {
    y: u16,
    x0: u16,
    x1: u16,
}

impl Span {
    /// A span; the caller guarantees `x0 < x1` inside the viewport.
    pub(crate) const fn new(y: u16, x0: u16, x1: u16) -> Self {
        Self { y, x0, x1 }
    }

    /// The row.
    pub const fn y(&self) -> u16 {
        self.y
    }

    /// The first pixel of the run.
    pub const fn x0(&self) -> u16 {
        self.x0
    }

    /// One past the last pixel of the run.
    pub const fn x1(&self) -> u16 {
        self.x1
    }

    /// Number of pixels, at least 1.
    pub const fn len(&self) -> u16 {
        self.x1 - self.x0
    }

    /// Always false: a span holds at least one pixel.
    pub const fn is_empty(&self) -> bool {
        false
    }

    /// The span as a one-row rectangle.
    pub fn to_rectangle(&self) -> Rectangle {
        Rectangle::new(
            Point::new(i32::from(self.x0), i32::from(self.y)),
            Size::new(u32::from(self.len()), 1),
        )
    }
}

/// Where spans go. Every span handed to a sink lies inside [`SpanSink::viewport`].
pub trait SpanSink {
    /// The colour of a span.
    type Color: PixelColor;
    /// The sink's own error.
    type Error;

    /// The pixel rectangle spans are clipped to.
    fn viewport(&self) -> Viewport;

    /// Takes one span of one colour.
    fn fill_span(&mut self, span: Span, color: Self::Color) -> Result<(), Self::Error>;

    /// Takes the pixels of row `y` set in `mask` (bit `k` of word `w` is pixel
    /// `32w + k`; bits at or past the viewport's width are ignored), all of one
    /// colour. By default each run of set bits is one [`fill_span`](Self::fill_span);
    /// a sink that keeps packed rows can take the words whole. Returns the spans
    /// (or words) written.
    fn fill_mask(&mut self, y: u16, mask: &[u32], color: Self::Color) -> Result<u32, Self::Error> {
        let width = usize::from(self.viewport().width);
        let mut spans = 0;
        let mut run: Option<(usize, usize)> = None;
        for (k, &word) in mask.iter().enumerate() {
            let mut bits = word;
            while bits != 0 {
                let start = bits.trailing_zeros();
                let ones = (!(bits >> start)).trailing_zeros();
                let x0 = 32 * k + start as usize;
                let x1 = (x0 + ones as usize).min(width);
                if x0 >= width {
                    break;
                }
                run = match run {
                    Some((a, b)) if b == x0 => Some((a, x1)),
                    Some((a, b)) => {
                        self.fill_span(Span::new(y, a as u16, b as u16), color)?;
                        spans += 1;
                        Some((x0, x1))
                    }
                    None => Some((x0, x1)),
                };
                bits = if start + ones >= 32 {
                    0
                } else {
                    bits & !(((1u32 << ones) - 1) << start)
                };
            }
        }
        if let Some((a, b)) = run {
            self.fill_span(Span::new(y, a as u16, b as u16), color)?;
            spans += 1;
        }
        Ok(spans)
    }

    /// Called after the last span of a primitive; sinks that batch spans write them out.
    fn flush(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// The viewport of a draw target: `[0, right) x [0, bottom)` of its bounding box.
fn target_viewport<D: Dimensions>(target: &D) -> Result<Viewport, Error> {
    let bb = target.bounding_box();
    let (w, h) = match bb.bottom_right() {
        Some(br) => (
            u32::try_from(br.x.saturating_add(1)).unwrap_or(0),
            u32::try_from(br.y.saturating_add(1)).unwrap_or(0),
        ),
        None => (0, 0),
    };
    Viewport::new(w, h)
}

/// A span sink that draws each span with one [`DrawTarget::fill_solid`] call.
#[derive(Debug)]
pub struct FillSolid<'a, D> {
    target: &'a mut D,
    viewport: Viewport,
}

impl<'a, D: DrawTarget> FillSolid<'a, D> {
    /// Wraps a draw target; fails when its bounding box exceeds the largest viewport.
    pub fn new(target: &'a mut D) -> Result<Self, Error> {
        let viewport = target_viewport(target)?;
        Ok(Self { target, viewport })
    }
}

impl<D: DrawTarget> SpanSink for FillSolid<'_, D> {
    type Color = D::Color;
    type Error = D::Error;

    fn viewport(&self) -> Viewport {
        self.viewport
    }

    fn fill_span(&mut self, span: Span, color: D::Color) -> Result<(), D::Error> {
        self.target.fill_solid(&span.to_rectangle(), color)
    }
}

/// Most colour changes one row run may hold before [`ContiguousRows`] writes it out early.
pub const ROW_SEGMENTS: usize = 16;

/// A span sink that joins touching spans of a row and draws each joined run with one
/// [`DrawTarget::fill_contiguous`] call: one call per row for a convex shape.
#[derive(Debug)]
pub struct ContiguousRows<'a, D: DrawTarget> {
    target: &'a mut D,
    viewport: Viewport,
    /// Row and first pixel of the pending run.
    start: Option<(u16, u16)>,
    /// End pixel and colour of each segment of the pending run, in order.
    segments: Vec<(u16, D::Color), ROW_SEGMENTS>,
}

impl<'a, D: DrawTarget> ContiguousRows<'a, D> {
    /// Wraps a draw target; fails when its bounding box exceeds the largest viewport.
    pub fn new(target: &'a mut D) -> Result<Self, Error> {
        let viewport = target_viewport(target)?;
        Ok(Self {
            target,
            viewport,
            start: None,
            segments: Vec::new(),
        })
    }

    fn write_run(&mut self) -> Result<(), D::Error> {
        let (Some((y, x0)), Some(&(x1, _))) = (self.start.take(), self.segments.last()) else {
            return Ok(());
        };
        let area = Span::new(y, x0, x1).to_rectangle();
        let mut x = x0;
        let segments = &self.segments;
        let colors = segments.iter().flat_map(move |&(end, color)| {
            let n = end.saturating_sub(x);
            x = end;
            core::iter::repeat_n(color, usize::from(n))
        });
        let result = self.target.fill_contiguous(&area, colors);
        self.segments.clear();
        result
    }
}

impl<D: DrawTarget> SpanSink for ContiguousRows<'_, D> {
    type Color = D::Color;
    type Error = D::Error;

    fn viewport(&self) -> Viewport {
        self.viewport
    }

    fn fill_span(&mut self, span: Span, color: D::Color) -> Result<(), D::Error> {
        let touches = matches!(
            (self.start, self.segments.last()),
            (Some((y, _)), Some(&(end, _))) if y == span.y() && end == span.x0()
        );
        if !touches || self.segments.is_full() {
            self.write_run()?;
            self.start = Some((span.y(), span.x0()));
        }
        match self.segments.last_mut() {
            Some(last) if touches && last.1 == color => last.0 = span.x1(),
            _ => {
                // Cannot fail: the run was written out above when full.
                let _ = self.segments.push((span.x1(), color));
            }
        }
        Ok(())
    }

    fn flush(&mut self) -> Result<(), D::Error> {
        self.write_run()
    }
}
