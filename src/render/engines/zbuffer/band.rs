//! The banded Z-buffer: depth and face id for `rows` rows of the frame at a time,
//! each face's spans depth-tested with its plane ([`DepthPlane`]).

use core::convert::Infallible;

use embedded_graphics_core::pixelcolor::BinaryColor;

use crate::render::band::IdBand;
use crate::render::depth::plane::{DepthPlane, RowPlane, STEP_BITS};
use crate::{Span, SpanSink, Viewport};

/// A depth sample: 16 or 32 bits of nearness (larger is nearer).
pub trait Depth: Copy + Ord + Default + core::fmt::Debug {
    /// Bits per sample.
    const BITS: u32;
    /// From nearness in `Q1.31` (0 ..= 2^31).
    fn from_q(q: u32) -> Self;
    /// Back to `Q1.31` (the low bits of a 16-bit sample are zero).
    fn to_q(self) -> u32;
}

impl Depth for u16 {
    const BITS: u32 = 16;
    fn from_q(q: u32) -> Self {
        (q >> 16).min(u32::from(u16::MAX)) as u16
    }
    fn to_q(self) -> u32 {
        u32::from(self) << 16
    }
}

impl Depth for u32 {
    const BITS: u32 = 32;
    fn from_q(q: u32) -> Self {
        q
    }
    fn to_q(self) -> u32 {
        self
    }
}

/// The Z-buffer's depth test of a row plane (the plane itself is shared:
/// [`depth::plane`](crate::render::depth::plane)).
impl RowPlane {
    /// Depth-tests pixels `x0..x1` of row `y` of `band` for face `id` with this
    /// plane (made for row 0), the values [`FaceSpans`] would give: nearer by more
    /// than the tie wins, an empty pixel takes any face, and a pixel this face holds
    /// already (from another of its fan triangles) takes the nearer of the two.
    pub fn depth_test<D: Depth>(
        &self,
        band: &mut ZBand<'_, '_, D>,
        y: u16,
        x0: u16,
        x1: u16,
        id: u16,
    ) {
        let Some(start) = band.ids.index(x0, y) else {
            return;
        };
        let len = usize::from(x1.saturating_sub(x0));
        let (Some(depth), Some(ids)) = (
            band.depth.get_mut(start..start + len),
            band.ids.ids.get_mut(start..start + len),
        ) else {
            return;
        };
        // As in `at_xy`, then one add a pixel (no wrap, see `at`).
        let (mut acc, step) = self.start_and_step(x0, y);
        for (d, held) in depth.iter_mut().zip(ids.iter_mut()) {
            let q = D::from_q(self.sample(acc));
            let margin = if *held == id { 0 } else { self.tie };
            if *held == 0 || q.to_q() > d.to_q().saturating_add(margin) {
                *d = q;
                *held = id;
            }
            acc = acc.wrapping_add(step);
        }
    }
}

/// Depth and face ids of one band of rows (see [`IdBand`] for the apron). Faces'
/// spans go in through [`FaceSpans`].
#[derive(Debug)]
pub(crate) struct ZBand<'d, 's, D> {
    pub depth: &'d mut [D],
    pub ids: IdBand<'s>,
}

/// A span sink that depth-tests one face's spans into a [`ZBand`].
#[derive(Debug)]
pub(crate) struct FaceSpans<'b, 'd, 's, D> {
    pub band: &'b mut ZBand<'d, 's, D>,
    pub plane: DepthPlane,
    /// 1 + face index.
    pub id: u16,
    pub viewport: Viewport,
    /// Spans received, for the statistics.
    pub spans: u32,
}

impl<D: Depth> SpanSink for FaceSpans<'_, '_, '_, D> {
    type Color = BinaryColor;
    type Error = Infallible;

    fn viewport(&self) -> Viewport {
        self.viewport
    }

    fn fill_span(&mut self, span: Span, _: BinaryColor) -> Result<(), Infallible> {
        self.spans += 1;
        let Some(start) = self.band.ids.index(span.x0(), span.y()) else {
            return Ok(());
        };
        let len = usize::from(span.len());
        let tie = self.plane.tie();
        // Evaluated at the span's first pixel centre, then one add a pixel.
        let (mut acc, step, (q_min, q_max)) = self.plane.span_start(span.x0(), span.y());
        let (Some(depth), Some(ids)) = (
            self.band.depth.get_mut(start..start + len),
            self.band.ids.ids.get_mut(start..start + len),
        ) else {
            return Ok(());
        };
        for (d, id) in depth.iter_mut().zip(ids.iter_mut()) {
            let q = D::from_q((acc.clamp(q_min, q_max) >> STEP_BITS) as u32);
            // Nearer by more than a tie wins; on a tie the earlier (lower) face stays.
            // An empty pixel (id 0) takes any face, so depth needs no clearing.
            if *id == 0 || q.to_q() > d.to_q().saturating_add(tie) {
                *d = q;
                *id = self.id;
            }
            acc += step;
        }
        Ok(())
    }
}
