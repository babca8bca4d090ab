//! The Z-buffer engine of Yuan and Sun's P-buffer paper, in bands of rows.
//!
//! Per band: depth-test the faces that reach the band (each face's edges are set up
//! at the band's first row), then the shared line pass and composition.

use core::marker::PhantomData;
use core::mem::size_of;

use embedded_graphics_core::pixelcolor::{BinaryColor, PixelColor};
use fixed::types::extra::LeEqU32;
use heapless::Vec;

mod abuffer;
mod band;
mod fan;

pub use abuffer::{GreyPalette, GreyShades, SmallFace};
pub use band::Depth;

use abuffer::{GreyCompose, GREY_MIN_BITS};
use band::{FaceSpans, ZBand};
use fan::{fan_rows, FanRow, FanSpans};

use crate::camera::Camera;
use crate::geometry::Subpixel;
use crate::mesh::{EdgeAdjacency, Mesh};
use crate::render::band::IdBand;
use crate::render::compose::{self, Compose, FrameProbe, Palette};
use crate::render::depth::fan::takes_fan_depth;
use crate::render::depth::plane::DepthPlane;
use crate::render::idpass::{render_ids, FrameInput, IdPass, IdWorkspace};
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::{bit, face_polygon, FrameCtx, Settings, Stats, Workspace};
use crate::scan::RowRange;
use crate::{Error, FillRule, ScanConverter, ScreenPoint, SpanSink};

/// The Z-buffer + P-buffer renderer with S = `Frac` sub-pixel bits, room for
/// `EDGES` polygon edges in the scan converter and `POLY` vertices per clipped face.
///
/// A face of more than three corners that is not planar takes the depth of each
/// pixel from its fan triangle `(v0, vi, vi+1)` that holds the pixel centre
/// ([conventions](crate::conventions)) in the depth test; drawing one sets up its fan
/// triangles on the
/// stack, about 150 bytes for each of `POLY`. The hidden-line test, shared by every
/// engine, asks such a face's fan triangle where its single plane cannot decide.
#[derive(Debug)]
pub struct ZBufferRenderer<Frac: LeEqU32, const EDGES: usize, const POLY: usize> {
    scan: ScanConverter<EDGES>,
    _frac: PhantomData<Frac>,
}

default_is_new!(ZBufferRenderer<EDGES, POLY>);

impl<Frac: LeEqU32, const EDGES: usize, const POLY: usize> ZBufferRenderer<Frac, EDGES, POLY> {
    /// Empty working memory.
    pub const fn new() -> Self {
        Self {
            scan: ScanConverter::new(),
            _frac: PhantomData,
        }
    }

    /// Renders `mesh` seen by `camera` into `sink`, whose viewport is the frame.
    /// Colours come from `palette`; `probe` sees each finished row's face ids and line
    /// masks (for the `--ids` and `--lines` outputs; `&mut ()` ignores them).
    #[allow(clippy::too_many_arguments)]
    pub fn render<D: Depth, K: SpanSink, P: Palette<Color = K::Color>, R: FrameProbe>(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &EdgeAdjacency<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut Workspace<'_, D>,
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>>
    where
        K::Color: PixelColor,
    {
        let input = FrameInput::of_mesh(mesh, edges, camera, settings, Subpixel::<Frac>::BITS);
        self.render_with(&input, ws, &mut compose::Flat(palette), sink, probe)
    }

    /// Renders like [`render`](Self::render) for a grey-scale target (`Gray4`,
    /// `Gray8`, ...), anti-aliasing the edges of faces: where a pixel's 3 x 3
    /// neighbourhood holds more than one face, the pixel's grey is the mean over a
    /// 4 x 4 grid of sub-samples of the grey of the face nearest at each sub-sample
    /// (or the background), an A-buffer of 16-bit coverage masks (see
    /// [`GreyPalette`]). Feature-edge lines stay solid in the line colour; modes
    /// without faces draw the lines only. Pixels no face reaches are left untouched:
    /// clear the target to the palette's background first.
    ///
    /// Needs S >= 2 sub-pixel bits, so that the sub-samples (at odd eighths of a
    /// pixel) lie on the half sub-pixel grid of the coverage test:
    /// [`Error::SubpixelTooCoarse`] otherwise. `small` holds a band's faces less than
    /// three pixels wide or high (found by bounding box, since the face ids may not
    /// show them); more in one band than `small.len()` is
    /// [`Error::CapacityExceeded`] with the count (the mesh's face count always
    /// suffices).
    #[allow(clippy::too_many_arguments)]
    pub fn render_grey<D: Depth, K: SpanSink, G: GreyPalette<Color = K::Color>, R: FrameProbe>(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &EdgeAdjacency<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut Workspace<'_, D>,
        small: &mut [SmallFace],
        palette: &G,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>>
    where
        K::Color: PixelColor,
    {
        let s = Subpixel::<Frac>::BITS;
        if s < GREY_MIN_BITS {
            return Err(Error::SubpixelTooCoarse {
                bits: s,
                needed: GREY_MIN_BITS,
            });
        }
        let mut grey = GreyCompose::<G, POLY>::new(palette, small);
        let input = FrameInput::of_mesh(mesh, edges, camera, settings, s);
        self.render_with(&input, ws, &mut grey, sink, probe)
    }

    /// The frame of `input`: the shared band loop ([`render_ids`]) with this
    /// engine's depth pass, and `composer` turning each finished band into spans.
    fn render_with<D: Depth, K: SpanSink, C: Compose<K>, R: FrameProbe>(
        &mut self,
        input: &FrameInput<'_, '_>,
        ws: &mut Workspace<'_, D>,
        composer: &mut C,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>> {
        let Workspace {
            vertices,
            drawn,
            features,
            depth,
            ids,
            lines,
        } = ws;
        let mut ids = IdWorkspace {
            vertices,
            drawn,
            features,
            ids,
            lines,
        };
        let mut pass = DepthPass {
            engine: self,
            depth,
        };
        render_ids::<POLY, _, _, _, _>(&mut pass, input, &mut ids, composer, sink, probe)
    }

    /// Depth-tests every drawn face that reaches the band; returns the spans walked.
    fn depth_pass<D: Depth, T>(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        band: &mut ZBand<'_, '_, D>,
    ) -> Result<u32, Error<T>> {
        let mut spans = 0;
        // Faces are walked over the apron too: the line test looks there.
        let (top, end) = (band.ids.first, band.ids.first + band.ids.held);
        let h = 1i32 << ctx.s;
        let reaches = |lo: i32, hi: i32| {
            let (first, last) = ((lo - h) >> ctx.s, (hi + h) >> ctx.s);
            last >= i32::from(top) && first < i32::from(end)
        };
        // Reused for every face: a heapless vector moved by value copies its capacity.
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        let mut points: Vec<ScreenPoint<Frac>, POLY> = Vec::new();
        for f in 0..ctx.mesh.face_count() {
            if !bit(drawn, f) {
                continue;
            }
            // Rows the face can reach, from the vertex cache: most faces miss the band.
            let (mut lo, mut hi, mut outside) = (i32::MAX, i32::MIN, 0u8);
            for &v in ctx.mesh.face(f) {
                let p = vertices
                    .get(v as usize)
                    .map_or(ProjectedVertex::default(), |p| *p);
                let y = p.screen().y;
                (lo, hi) = (lo.min(y), hi.max(y));
                outside |= p.outside();
            }
            if outside == 0 && !reaches(lo, hi) {
                continue;
            }
            if !face_polygon(ctx, vertices, f, &mut poly).map_err(Error::widen)? {
                continue;
            }
            if outside != 0 {
                let (lo, hi) = poly.iter().fold((i32::MAX, i32::MIN), |(lo, hi), v| {
                    (lo.min(v.y), hi.max(v.y))
                });
                if !reaches(lo, hi) {
                    continue;
                }
            }
            let Some(plane) = DepthPlane::new(&poly, ctx.s) else {
                continue;
            };
            points.clear();
            for v in &poly {
                let _ = points.push(ScreenPoint::from_bits(v.x, v.y));
            }
            // A face clipped to three corners keeps its single plane: it was a
            // triangle, or (one clipping plane) it kept one corner, so that every fan
            // triangle has a corner cut away (see `fan`).
            if takes_fan_depth(ctx.mesh, f, &poly, &plane) {
                spans += self.fan_face(ctx, vertices, f, &points, &plane, band)?;
                continue;
            }
            let mut sink = FaceSpans {
                band: &mut *band,
                plane,
                id: (f + 1) as u16,
                viewport: ctx.viewport,
                spans: 0,
            };
            self.scan
                .fill_rows(
                    &points,
                    FillRule::EvenOdd,
                    top..end,
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

    /// Depth-tests face `f`, not planar, whose clipped polygon is `points` and whose
    /// single plane is `plane`: each pixel of the polygon's spans takes its depth from
    /// the fan triangle that holds its centre (see [`FanSpans`]). Out of line, so the
    /// fan triangles' storage is on the stack only while such a face is drawn.
    #[inline(never)]
    fn fan_face<D: Depth, T>(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        f: usize,
        points: &[ScreenPoint<Frac>],
        plane: &DepthPlane,
        band: &mut ZBand<'_, '_, D>,
    ) -> Result<u32, Error<T>> {
        let rows = band.ids.first..band.ids.first + band.ids.held;
        let window = RowRange {
            first: i32::from(rows.start),
            end: i32::from(rows.end),
        };
        let mut fans: Vec<FanRow, POLY> = Vec::new();
        let complete = fan_rows(
            &mut fans,
            ctx.mesh,
            vertices,
            f,
            ctx.s,
            ctx.viewport,
            window,
        );
        let mut sink = FanSpans {
            band,
            fans: &mut fans,
            fallback: plane.row_plane(0),
            complete,
            id: (f + 1) as u16,
            viewport: ctx.viewport,
            s: ctx.s,
            row: None,
            spans: 0,
        };
        self.scan
            .fill_rows(points, FillRule::EvenOdd, rows, BinaryColor::On, &mut sink)
            .map_err(|e| match e {
                Error::Target(never) => match never {},
                other => other.widen(),
            })?;
        Ok(sink.spans)
    }
}

/// One frame's depth pass: the engine and the depth band the caller lent.
struct DepthPass<'e, 'd, Frac: LeEqU32, D, const EDGES: usize, const POLY: usize> {
    engine: &'e mut ZBufferRenderer<Frac, EDGES, POLY>,
    depth: &'d mut [D],
}

impl<Frac: LeEqU32, D: Depth, const EDGES: usize, const POLY: usize> IdPass
    for DepthPass<'_, '_, Frac, D, EDGES, POLY>
{
    fn begin(
        &mut self,
        _: &FrameCtx<'_, '_>,
        _: &[ProjectedVertex],
        _: &[u32],
    ) -> Result<(), Error> {
        Ok(())
    }

    fn samples(&self) -> usize {
        self.depth.len()
    }

    fn frame_stats(&self, ctx: &FrameCtx<'_, '_>, band_rows: u16, stats: &mut Stats) {
        let viewport = ctx.viewport;
        let rows = usize::from(IdBand::rows_needed(band_rows, viewport.height));
        let w = usize::from(viewport.width).max(1);
        stats.depth_buffer_bytes = (rows * w * size_of::<D>()) as u32;
        (stats.depth_step_near, stats.depth_step_far) = ctx.view.depth_steps(D::BITS);
    }

    fn fill(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        band: &mut IdBand<'_>,
        _fresh: u16,
    ) -> Result<u32, Error> {
        // The band's ids join the depth for the pass (a pixel without a face takes
        // any face's depth, so depth is never cleared), then go back to the loop.
        let width = band.width;
        let ids = core::mem::replace(band, IdBand::new(&mut [], width));
        let mut zband = ZBand {
            depth: &mut *self.depth,
            ids,
        };
        let spans = self.engine.depth_pass(ctx, vertices, drawn, &mut zband);
        *band = zband.ids;
        spans
    }
}
