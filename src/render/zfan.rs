//! Faces that are not planar, in the Z-buffer: CONVENTIONS.md gives such a face the
//! depth of the fan triangle `(v0, vi, vi+1)` the ray meets, and the coverage of its
//! projected polygon (even-odd).
//!
//! The polygon is scan-converted as any face is, so its coverage is unchanged; each of
//! its spans is then depth-tested piece by piece: the part inside fan triangle `k`'s
//! projection (its run on the row, by the scan converter's own exact crossing rule)
//! with triangle `k`'s plane. Where fan triangles overlap (the face folds) the pixel
//! keeps the nearest. The parity of the fan triangles is the polygon's coverage, so
//! every pixel of a span lies in at least one of them; the face's single plane
//! ([`DepthPlane::new`]) is only the fallback for a pixel that does not (a fan triangle
//! with a corner outside the view volume is not used: its projection is not the
//! triangle's).

use core::convert::Infallible;

use embedded_graphics_core::pixelcolor::BinaryColor;
use heapless::Vec;

use super::transform::{ProjectedVertex, ScreenVertex};
use super::zband::{Depth, DepthPlane, RowPlane, ZBand};
use crate::mesh::Mesh;
use crate::order::is_planar;
use crate::scan::edge::{div_rem_euclid, EdgeLine};
use crate::{Span, SpanSink, Viewport};

/// Does face `f` take its depth from its fan triangles (more than three corners, not
/// planar by [`is_planar`])? A triangle is never asked the (f64) planarity test.
pub(crate) fn takes_fan_depth(mesh: &Mesh<'_>, f: usize) -> bool {
    mesh.face(f).len() > 3 && !is_planar(mesh, f)
}

/// The fan triangles `(v0, vk, vk+1)` of face `f` on screen, those with every corner
/// inside the view volume (others project to something else than the triangle).
pub(crate) fn fan_corners<'a>(
    mesh: &'a Mesh<'_>,
    vertices: &'a [ProjectedVertex],
    f: usize,
) -> impl Iterator<Item = [ScreenVertex; 3]> + 'a {
    let corner = move |v: &u32| {
        vertices
            .get(*v as usize)
            .filter(|p| p.outside == 0)
            .map(|p| p.screen)
    };
    let face = mesh.face(f);
    let v0 = face.first().and_then(corner);
    face.get(1..)
        .unwrap_or(&[])
        .windows(2)
        .filter_map(move |pair| match pair {
            [a, b] => Some([v0?, corner(a)?, corner(b)?]),
            _ => None,
        })
}

/// The pixels `lo..hi` of row `j` whose centres lie inside the triangle `t`, by the
/// scan converter's rule (see `scan::edge`), clamped to `0..width`.
pub(crate) fn triangle_run(t: &[ScreenVertex; 3], s: u32, j: u16, width: u16) -> (u16, u16) {
    let h = 1i64 << s;
    let py = (2 * i64::from(j) + 1) * h;
    let half = |v: &ScreenVertex| (2 * i64::from(v.x), 2 * i64::from(v.y));
    let mut found = [0u16; 2];
    let mut n = 0;
    for (a, b) in [(0, 1), (1, 2), (2, 0)] {
        let (Some(a), Some(b)) = (t.get(a), t.get(b)) else {
            continue;
        };
        let Some(line) = EdgeLine::new(half(a), half(b)) else {
            continue;
        };
        if !(line.y0 <= py && py < line.y1) {
            continue;
        }
        // The first pixel right of the crossing, as the DDA's set-up computes it;
        // exactly (128-bit) beyond 64 bits, which the guard band never reaches.
        let (dx, dy) = (line.x1 - line.x0, line.y1 - line.y0);
        let c = match (py - line.y0).checked_mul(dx) {
            Some(num) => {
                let (q, r) = div_rem_euclid(num, dy);
                let c = (line.x0 + q + h - 1 + i64::from(r != 0)) >> (s + 1);
                c.clamp(0, i64::from(width)) as u16
            }
            None => line.crossing_at(s, i32::from(j), width),
        };
        if let Some(slot) = found.get_mut(n) {
            *slot = c;
        }
        n += 1;
    }
    // A row meets a triangle's boundary twice or not at all.
    match (n, found) {
        (2, [a, b]) => (a.min(b), a.max(b)),
        _ => (0, 0),
    }
}

/// A fan triangle's depth along the rows, and its run on the current row.
#[derive(Debug, Clone, Copy)]
struct FanRow {
    corners: [ScreenVertex; 3],
    plane: RowPlane,
    lo: u16,
    hi: u16,
}

/// A span sink that depth-tests the spans of one face that is not planar into a
/// [`ZBand`], each pixel with the plane of the fan triangle that holds its centre.
#[derive(Debug)]
pub(crate) struct FanSpans<'b, 's, D, const POLY: usize> {
    band: &'b mut ZBand<'s, D>,
    fans: Vec<FanRow, POLY>,
    /// The face's single plane, for a pixel no fan triangle holds.
    fallback: RowPlane,
    /// 1 + face index.
    id: u16,
    viewport: Viewport,
    s: u32,
    /// The row the fans' runs are for.
    row: Option<u16>,
    /// Spans received, for the statistics.
    pub spans: u32,
}

impl<'b, 's, D: Depth, const POLY: usize> FanSpans<'b, 's, D, POLY> {
    /// A sink for face `f` (the fan triangles of [`fan_corners`] that have an area on
    /// screen), with its single plane `fallback`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        band: &'b mut ZBand<'s, D>,
        mesh: &Mesh<'_>,
        vertices: &[ProjectedVertex],
        f: usize,
        fallback: &DepthPlane,
        viewport: Viewport,
        s: u32,
    ) -> Self {
        let mut fans = Vec::new();
        for corners in fan_corners(mesh, vertices, f) {
            if let Some(plane) = DepthPlane::new(&corners, s) {
                // The face fits `POLY` corners, so its fan triangles fit.
                let _ = fans.push(FanRow {
                    corners,
                    plane: plane.row_plane(0),
                    lo: 0,
                    hi: 0,
                });
            }
        }
        Self {
            band,
            fans,
            fallback: fallback.row_plane(0),
            id: (f + 1) as u16,
            viewport,
            s,
            row: None,
            spans: 0,
        }
    }
}

impl<D: Depth, const POLY: usize> SpanSink for FanSpans<'_, '_, D, POLY> {
    type Color = BinaryColor;
    type Error = Infallible;

    fn viewport(&self) -> Viewport {
        self.viewport
    }

    fn fill_span(&mut self, span: Span, _: BinaryColor) -> Result<(), Infallible> {
        self.spans += 1;
        let (y, x0, x1) = (span.y(), span.x0(), span.x0() + span.len());
        if self.row != Some(y) {
            self.row = Some(y);
            for fan in self.fans.iter_mut() {
                (fan.lo, fan.hi) = triangle_run(&fan.corners, self.s, y, self.viewport.width);
            }
        }
        for fan in &self.fans {
            let (lo, hi) = (fan.lo.max(x0), fan.hi.min(x1));
            if lo < hi {
                fan.plane.depth_test(self.band, y, lo, hi, self.id);
            }
        }
        // The pixels of the span that no fan triangle holds: walk the span, jumping
        // over the runs that hold the current pixel.
        let mut x = x0;
        while x < x1 {
            let (mut covered, mut next) = (x, x1);
            for fan in &self.fans {
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
#[path = "zfan_tests.rs"]
mod tests;
