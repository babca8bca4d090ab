//! List-priority engines: polygons painted far to near into the band's face ids,
//! each nearer one over the ones before, with no depth test at all. The list is
//! the painter's sort by farthest depth (no splitting: it fails where faces
//! overlap cyclically or interpenetrate, and is kept to show that), or a depth
//! order made elsewhere (a BSP tree walked for the view, Newell's sort).

use core::marker::PhantomData;
use core::ops::Range;

use embedded_graphics_core::pixelcolor::{BinaryColor, PixelColor};
use fixed::types::extra::LeEqU32;
use heapless::Vec;

use super::codefill::DepthOrder;
use crate::camera::Camera;
use crate::geometry::Subpixel;
use crate::mesh::{EdgeAdjacency, Mesh};
use crate::render::band::IdBand;
use crate::render::compose::{Flat, FrameProbe, Palette};
use crate::render::depth::coverage::{covers_centre, fragments_may_overlap};
use crate::render::idpass::{render_ids, FrameInput, IdPass, IdWorkspace};
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::{bit, index_polygon, need, FrameCtx, Settings, Stats};
use crate::Capacity;
use crate::{Error, FillRule, ScanConverter, ScreenPoint, Span, SpanSink, Viewport};

/// The list a [`PainterRenderer`] paints.
#[derive(Debug, Clone, Copy)]
pub enum PaintOrder<'o> {
    /// The painter's algorithm: the mesh's faces sorted by their farthest point,
    /// farthest first; on equal keys the lower face index is painted last (wins).
    FarthestDepth,
    /// A depth order's surfaces, highest rank (farthest) first; on equal ranks the
    /// lower surface index is painted last.
    Order(DepthOrder<'o>),
}

/// Paints a list of polygons far to near: S = `Frac` sub-pixel bits, room for
/// `EDGES` polygon edges in the scan converter and `POLY` vertices per clipped
/// polygon. `list` (lent to [`render`](Self::render)) holds one `u64` per surface.
#[derive(Debug)]
pub struct PainterRenderer<Frac: LeEqU32, const EDGES: usize, const POLY: usize> {
    scan: ScanConverter<EDGES>,
    _frac: PhantomData<Frac>,
}

default_is_new!(PainterRenderer<EDGES, POLY>);

impl<Frac: LeEqU32, const EDGES: usize, const POLY: usize> PainterRenderer<Frac, EDGES, POLY> {
    /// Empty working memory.
    pub const fn new() -> Self {
        Self {
            scan: ScanConverter::new(),
            _frac: PhantomData,
        }
    }

    /// Renders `mesh` seen by `camera` into `sink`, painting `order`'s list.
    /// `list.len()` must reach the surfaces' count (the mesh's faces for
    /// [`PaintOrder::FarthestDepth`]), else [`Error::CapacityExceeded`]; an order made
    /// for another mesh is [`Error::DepthOrderMismatch`].
    #[allow(clippy::too_many_arguments)]
    pub fn render<K: SpanSink, P: Palette<Color = K::Color>, R: FrameProbe>(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &EdgeAdjacency<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut IdWorkspace<'_>,
        order: PaintOrder<'_>,
        list: &mut [u64],
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>>
    where
        K::Color: PixelColor,
    {
        let (surfaces, source, rank) = match order {
            PaintOrder::FarthestDepth => (*mesh, None, None),
            PaintOrder::Order(o) => {
                if !o.fits(mesh) {
                    return Err(Error::DepthOrderMismatch);
                }
                (o.surfaces, Some(o.source), Some(o.rank))
            }
        };
        need(Capacity::DepthOrder, surfaces.face_count(), list.len()).map_err(Error::widen)?;
        let input = FrameInput {
            mesh,
            positions: surfaces.vertices(),
            edges,
            camera,
            settings,
            s: Subpixel::<Frac>::BITS,
        };
        let mut pass = Paint::<Frac, EDGES, POLY> {
            scan: &mut self.scan,
            _frac: PhantomData,
            surfaces,
            source,
            rank,
            list,
            len: 0,
        };
        render_ids::<POLY, _, _, _, _>(&mut pass, &input, ws, &mut Flat(palette), sink, probe)
    }
}

/// One frame's painting.
struct Paint<'a, 'o, Frac, const EDGES: usize, const POLY: usize> {
    scan: &'a mut ScanConverter<EDGES>,
    _frac: PhantomData<Frac>,
    surfaces: Mesh<'o>,
    source: Option<&'o [u16]>,
    rank: Option<&'o [u32]>,
    /// `(key << 32) | !surface`, sorted ascending: the painting order.
    list: &'a mut [u64],
    len: usize,
}

impl<Frac, const EDGES: usize, const POLY: usize> Paint<'_, '_, Frac, EDGES, POLY> {
    fn source(&self, k: usize) -> usize {
        self.source
            .and_then(|s| s.get(k))
            .map_or(k, |&f| usize::from(f))
    }
}

impl<Frac: LeEqU32, const EDGES: usize, const POLY: usize> IdPass
    for Paint<'_, '_, Frac, EDGES, POLY>
{
    fn begin(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
    ) -> Result<(), Error> {
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        let mut len = 0;
        for k in 0..self.surfaces.face_count() {
            if !bit(drawn, self.source(k)) {
                continue;
            }
            let key = match self.rank {
                // Highest rank first.
                Some(rank) => !rank.get(k).copied().unwrap_or(0),
                // The farthest point: the least nearness of the clipped polygon.
                None => {
                    if !index_polygon(ctx, vertices, self.surfaces.face(k), &mut poly)? {
                        continue;
                    }
                    poly.iter().map(|v| v.q).min().unwrap_or(0)
                }
            };
            if let Some(slot) = self.list.get_mut(len) {
                // Within a key, the higher surface index first: the lower paints last.
                *slot = (u64::from(key) << 32) | u64::from(!(k as u32));
                len += 1;
            }
        }
        self.len = len;
        if let Some(list) = self.list.get_mut(..len) {
            crate::sort::sort_by_key(list, |&e| e);
        }
        Ok(())
    }

    fn fill(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        _drawn: &[u32],
        band: &mut IdBand<'_>,
        _fresh: u16,
    ) -> Result<u32, Error> {
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        let mut points: Vec<ScreenPoint<Frac>, POLY> = Vec::new();
        let mut whole: Vec<ScreenVertex, POLY> = Vec::new();
        let rows = band.first..band.first + band.held;
        let mut spans = 0;
        for i in 0..self.len {
            let Some(&entry) = self.list.get(i) else {
                break;
            };
            let k = !(entry as u32) as usize;
            if !index_polygon(ctx, vertices, self.surfaces.face(k), &mut poly)? {
                continue;
            }
            if !reaches(&poly, ctx.s, &rows) {
                continue;
            }
            let source = self.source(k);
            let id = (source + 1) as u16;
            // A depth order's fragments of a face that may fold here are painted only
            // where the face's polygon covers (its parity), not in their overlap.
            let clip_to_face = self.source.is_some()
                && fragments_may_overlap(ctx.mesh, source, vertices)
                && index_polygon(ctx, vertices, ctx.mesh.face(source), &mut whole)?;
            points.clear();
            for v in &poly {
                let _ = points.push(ScreenPoint::from_bits(v.x, v.y));
            }
            let mut sink = IdSpans {
                band: &mut *band,
                id,
                viewport: ctx.viewport,
                spans: 0,
                within: clip_to_face.then_some((whole.as_slice(), ctx.s)),
            };
            self.scan
                .fill_rows(
                    &points,
                    FillRule::EvenOdd,
                    rows.clone(),
                    BinaryColor::On,
                    &mut sink,
                )
                .map_err(|e| match e {
                    Error::Target(never) => match never {},
                    other => other.widen(),
                })?;
            spans += sink.spans;
        }
        Ok(spans)
    }
}

/// Whether a polygon can cover a pixel centre in `rows`.
pub(super) fn reaches(poly: &[ScreenVertex], s: u32, rows: &Range<u16>) -> bool {
    let h = 1i32 << s;
    let (lo, hi) = poly.iter().fold((i32::MAX, i32::MIN), |(lo, hi), v| {
        (lo.min(v.y), hi.max(v.y))
    });
    let (first, last) = ((lo - h) >> s, (hi + h) >> s);
    last >= i32::from(rows.start) && first < i32::from(rows.end)
}

/// A span sink that writes one id over a band's ids (only at pixel centres the
/// polygon `within` covers, when given, with its sub-pixel bits).
struct IdSpans<'b, 's, 'w> {
    band: &'b mut IdBand<'s>,
    id: u16,
    viewport: Viewport,
    spans: u32,
    within: Option<(&'w [ScreenVertex], u32)>,
}

impl SpanSink for IdSpans<'_, '_, '_> {
    type Color = BinaryColor;
    type Error = core::convert::Infallible;

    fn viewport(&self) -> Viewport {
        self.viewport
    }

    fn fill_span(&mut self, span: Span, _: BinaryColor) -> Result<(), Self::Error> {
        self.spans += 1;
        let Some(start) = self.band.index(span.x0(), span.y()) else {
            return Ok(());
        };
        let end = start + usize::from(span.len());
        let Some(ids) = self.band.ids.get_mut(start..end) else {
            return Ok(());
        };
        match self.within {
            None => ids.fill(self.id),
            Some((poly, s)) => {
                let (x0, y) = (i64::from(span.x0()), i64::from(span.y()));
                for (x, id) in (x0..).zip(ids.iter_mut()) {
                    if covers_centre(poly, s, x, y) {
                        *id = self.id;
                    }
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::vec;
    use std::vec::Vec;

    use fixed::types::extra::U4;

    use super::*;
    use crate::render::two_squares::{count, frame, squares};
    use crate::render::MonoPalette;

    fn paint(v: &[[f32; 3]], idx: &[u32], off: &[u32], list_len: usize) -> Result<Vec<u16>, Error> {
        frame(v, idx, off, |mesh, adj, camera, settings, ws, fb, probe| {
            let mut list = vec![0u64; list_len];
            PainterRenderer::<U4, 16, 16>::new().render(
                mesh,
                adj,
                camera,
                settings,
                ws,
                PaintOrder::FarthestDepth,
                &mut list,
                &MonoPalette::default(),
                fb,
                probe,
            )
        })
    }

    #[test]
    fn the_nearer_square_is_painted_over_the_farther_one() {
        // Face 1 nearer: it shows over the whole overlap (x in [-0.5, 0.5], 8 px).
        let (v, idx, off) = squares(0.0, 1.0);
        let ids = paint(&v, &idx, &off, 2).unwrap();
        assert_eq!((count(&ids, 1), count(&ids, 2)), (8, 16));
        // Face 0 nearer: it shows there instead.
        let (v, idx, off) = squares(1.0, 0.0);
        let ids = paint(&v, &idx, &off, 2).unwrap();
        assert_eq!((count(&ids, 1), count(&ids, 2)), (16, 8));
    }

    #[test]
    fn on_equal_depth_the_lower_face_index_is_painted_last() {
        let (v, idx, off) = squares(0.0, 0.0);
        let ids = paint(&v, &idx, &off, 2).unwrap();
        assert_eq!((count(&ids, 1), count(&ids, 2)), (16, 8));
    }

    #[test]
    fn a_list_shorter_than_the_faces_is_an_error_with_the_size_needed() {
        let (v, idx, off) = squares(0.0, 1.0);
        assert_eq!(
            paint(&v, &idx, &off, 1),
            Err(Error::CapacityExceeded {
                what: Capacity::DepthOrder,
                needed: 2,
                capacity: 1
            })
        );
    }
}
