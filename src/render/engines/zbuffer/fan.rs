//! Faces that are not planar, in the Z-buffer: [conventions](crate::conventions) gives such
//! a face the
//! depth of the fan triangle `(v0, vi, vi+1)` the ray meets, and the coverage of its
//! projected polygon (even-odd).
//!
//! The polygon is scan-converted as any face is, so its coverage is unchanged; each of
//! its spans is then depth-tested piece by piece: the part inside fan triangle `k`'s
//! projection (its run on the row, from its edges' DDAs: the scan converter's own
//! exact crossing rule) with triangle `k`'s plane. Where fan triangles overlap (the face
//! folds) the pixel
//! keeps the nearest. The parity of the fan triangles is the polygon's coverage, so
//! every pixel of a span lies in at least one of them; the face's single plane
//! ([`DepthPlane::new`]) is only the fallback for a pixel that does not (a fan triangle
//! with a corner outside the view volume is not used: its projection is not the
//! triangle's).

use core::convert::Infallible;

use embedded_graphics_core::pixelcolor::BinaryColor;
use heapless::Vec;

use super::band::{Depth, ZBand};
use crate::mesh::Mesh;
use crate::render::depth::fan::fan_corners;
use crate::render::depth::plane::{DepthPlane, RowPlane};
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::scan::edge::{Edge, EdgeLine};
use crate::scan::RowRange;
use crate::{Span, SpanSink, Viewport, GUARD_BAND_PX};

/// A fan triangle's depth along the rows, its edges (DDAs of the scan converter, set
/// up at the band's first row, each moved on to the row asked for), and its run of
/// pixels on the current row.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FanRow {
    plane: RowPlane,
    /// `first` is the row each DDA stands at (moved on with it).
    edges: [Edge; 3],
    lo: u16,
    hi: u16,
}

impl FanRow {
    /// The triangle `corners` (inside the guard band) with depth `plane`, its edges
    /// set up for `window`.
    fn new(
        corners: &[ScreenVertex; 3],
        plane: RowPlane,
        s: u32,
        viewport: Viewport,
        window: RowRange,
    ) -> Self {
        let half = |v: &ScreenVertex| (2 * i64::from(v.x), 2 * i64::from(v.y));
        let mut edges = [Edge::ZERO; 3];
        for (slot, (a, b)) in edges.iter_mut().zip([(0, 1), (1, 2), (2, 0)]) {
            let (Some(a), Some(b)) = (corners.get(a), corners.get(b)) else {
                continue;
            };
            if let Some(line) = EdgeLine::new(half(a), half(b)) {
                *slot = Edge::new(&line, line.clip(s, viewport, window), s).unwrap_or(Edge::ZERO);
            }
        }
        Self {
            plane,
            edges,
            lo: 0,
            hi: 0,
        }
    }

    /// Sets the run to the pixels of row `y` whose centres lie inside the triangle,
    /// by the scan converter's rule (rows only ever move down).
    fn run(&mut self, y: i32, s: u32, width: u16) {
        let mut found = [i32::from(width); 2];
        let mut n = 0;
        for edge in self.edges.iter_mut() {
            while edge.first < y && edge.first < edge.end {
                edge.step();
                edge.first += 1;
            }
            if edge.first == y && y < edge.end {
                if let Some(slot) = found.get_mut(n) {
                    *slot = edge.crossing(s).clamp(0, i32::from(width));
                }
                n += 1;
            }
        }
        // A row meets a triangle's boundary twice or not at all; an edge wholly right
        // of the viewport was dropped (a crossing at `width`).
        let [a, b] = found;
        (self.lo, self.hi) = if n == 0 {
            (0, 0)
        } else {
            (a.min(b) as u16, a.max(b) as u16)
        };
    }
}

/// The fan triangles of face `f` ([`fan_corners`]) that lie inside the guard band
/// and have an area on screen, set up for the rows `window` of `viewport`, into `out`
/// (room for `POLY - 2`: the face fits `POLY` corners). True when no fan triangle
/// was left out but for having no area (which covers no pixel centre): the face is
/// then wholly in view, its polygon is the one scan-converted, and every pixel of
/// its spans lies in one of them (their parity is its coverage).
pub(crate) fn fan_rows<const POLY: usize>(
    out: &mut Vec<FanRow, POLY>,
    mesh: &Mesh<'_>,
    vertices: &[ProjectedVertex],
    f: usize,
    s: u32,
    viewport: Viewport,
    window: RowRange,
) -> bool {
    out.clear();
    let limit = i64::from(GUARD_BAND_PX) << s;
    let inside = |v: &ScreenVertex| i64::from(v.x).abs() <= limit && i64::from(v.y).abs() <= limit;
    let mut kept = 0;
    for corners in fan_corners(mesh, vertices, f) {
        if !corners.iter().all(inside) {
            continue;
        }
        kept += 1;
        if let Some(plane) = DepthPlane::new(&corners, s) {
            let _ = out.push(FanRow::new(
                &corners,
                plane.row_plane(0),
                s,
                viewport,
                window,
            ));
        }
    }
    kept + 2 == mesh.face(f).len()
}

/// A span sink that depth-tests the spans of one face that is not planar into a
/// [`ZBand`], each pixel with the plane of the fan triangle that holds its centre.
#[derive(Debug)]
pub(crate) struct FanSpans<'b, 'd, 's, 'f, D> {
    pub band: &'b mut ZBand<'d, 's, D>,
    /// The face's fan triangles ([`fan_rows`]).
    pub fans: &'f mut [FanRow],
    /// The face's single plane, for a pixel no fan triangle holds.
    pub fallback: RowPlane,
    /// Every pixel lies in a fan triangle (see [`fan_rows`]): no fallback needed.
    pub complete: bool,
    /// 1 + face index.
    pub id: u16,
    pub viewport: Viewport,
    /// Sub-pixel bits.
    pub s: u32,
    /// The row the fans' runs are for.
    pub row: Option<u16>,
    /// Spans received, for the statistics.
    pub spans: u32,
}

impl<D: Depth> SpanSink for FanSpans<'_, '_, '_, '_, D> {
    type Color = BinaryColor;
    type Error = Infallible;

    fn viewport(&self) -> Viewport {
        self.viewport
    }

    fn fill_span(&mut self, span: Span, _: BinaryColor) -> Result<(), Infallible> {
        self.spans += 1;
        let (y, x0, x1) = (span.y(), span.x0(), span.x0().saturating_add(span.len()));
        if self.row != Some(y) {
            self.row = Some(y);
            for fan in self.fans.iter_mut() {
                fan.run(i32::from(y), self.s, self.viewport.width);
            }
        }
        for fan in self.fans.iter() {
            let (lo, hi) = (fan.lo.max(x0), fan.hi.min(x1));
            if lo < hi {
                fan.plane.depth_test(self.band, y, lo, hi, self.id);
            }
        }
        if self.complete {
            return Ok(());
        }
        // The pixels of the span that no fan triangle holds: walk the span, jumping
        // over the runs that hold the current pixel.
        let mut x = x0;
        while x < x1 {
            let (mut covered, mut next) = (x, x1);
            for fan in self.fans.iter() {
                if fan.lo <= x && x < fan.hi {
                    covered = covered.max(fan.hi);
                } else if fan.lo > x {
                    next = next.min(fan.lo);
                }
            }
            if covered > x {
                x = covered;
            } else {
                self.fallback.depth_test(self.band, y, x, next, self.id);
                x = next;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
#[path = "fan_tests.rs"]
mod tests;
