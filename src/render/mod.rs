//! The hidden-line renderer of paper 000: a fixed-point Z-buffer, in bands of rows,
//! plus the P-buffer's pattern for hidden lines.
//!
//! Per frame: transform every vertex once (fixed point), mark drawn faces and the
//! view's feature edges. Per band of rows: depth-test the faces that reach the band
//! (each face's edges are set up at the band's first row), draw the feature edges
//! that reach it into a visible and a hidden mask, then compose each row into spans.

mod compose;
mod lines;
mod transform;
mod zband;

use core::marker::PhantomData;
use core::mem::size_of;

use embedded_graphics_core::pixelcolor::{BinaryColor, PixelColor};
use fixed::types::extra::LeEqU32;
use heapless::Vec;

pub use compose::{FrameProbe, MonoPalette, Palette, SolidPalette};
pub use transform::{ClipVertex, ProjectedVertex, ScreenVertex};
pub use zband::Depth;

use crate::camera::Camera;
use crate::geometry::Subpixel;
use crate::mesh::{face_owns_edge, EdgeAdjacency, EdgeKind, Mesh, MeshEdge, Viewpoint};
use crate::{Error, FillRule, Pattern, ScanConverter, ScreenPoint, SpanSink, Viewport};
use lines::{polygon_contains, walk_segment, LineMasks};
use transform::FixedView;
use zband::{DepthPlane, FaceSpans, ZBand};

/// What a frame shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum DrawMode {
    /// Every feature edge solid; nothing is hidden (no depth test at all).
    Wireframe,
    /// Visible feature edges only.
    HiddenRemoved,
    /// Visible feature edges solid, hidden ones through the pattern.
    #[default]
    Dashed,
    /// Faces filled by the palette, no lines.
    Surfaces,
    /// Faces filled, plus dashed lines.
    SurfacesDashed,
}

impl DrawMode {
    fn needs_depth(self) -> bool {
        self != DrawMode::Wireframe
    }
    fn draws_lines(self) -> bool {
        self != DrawMode::Surfaces
    }
    fn draws_faces(self) -> bool {
        matches!(self, DrawMode::Surfaces | DrawMode::SurfacesDashed)
    }
}

/// Back-face culling.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Cull {
    /// Faces that do not face the eye are not drawn.
    On,
    /// Every face is drawn.
    Off,
    /// On when the mesh is closed (every edge shared by exactly two faces).
    #[default]
    Auto,
}

/// How to draw a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Settings {
    /// What is drawn.
    pub mode: DrawMode,
    /// Back-face culling.
    pub cull: Cull,
    /// The P-buffer pattern for hidden lines.
    pub pattern: Pattern,
}

/// Storage the caller lends for one frame. Sizes: `vertices` >= the mesh's vertex
/// count; `drawn` >= faces / 32 words; `features` >= edges / 32 words; `depth` and
/// `ids` >= width x band rows; `lines` >= 2 x ceil(width / 32) x band rows. The band
/// height is `depth.len() / width` (a full frame when it reaches the height).
#[derive(Debug)]
pub struct Workspace<'s, D> {
    /// The per-frame vertex cache.
    pub vertices: &'s mut [ProjectedVertex],
    /// One bit per face: drawn in this view (not culled).
    pub drawn: &'s mut [u32],
    /// One bit per mesh edge: a feature edge in this view.
    pub features: &'s mut [u32],
    /// Depth of the band.
    pub depth: &'s mut [D],
    /// Face ids of the band (0 none, else 1 + face).
    pub ids: &'s mut [u16],
    /// Line masks of the band.
    pub lines: &'s mut [u32],
}

impl<D> Workspace<'_, D> {
    /// Bytes of all the lent buffers.
    pub fn bytes(&self) -> usize {
        use core::mem::size_of_val;
        size_of_val(self.vertices)
            + size_of_val(self.drawn)
            + size_of_val(self.features)
            + size_of_val(self.depth)
            + size_of_val(self.ids)
            + size_of_val(self.lines)
    }
}

/// Figures of one frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Stats {
    /// Faces in the mesh.
    pub faces: u32,
    /// Faces drawn: not culled and not wholly outside the view.
    pub faces_drawn: u32,
    /// Feature edges in this view.
    pub feature_edges: u32,
    /// Spans: face spans depth-tested plus spans sent to the sink.
    pub spans: u32,
    /// Bands rendered.
    pub bands: u32,
    /// Rows per band.
    pub band_rows: u32,
    /// Bytes of depth samples per band.
    pub depth_buffer_bytes: u32,
}

/// Set a bit in a bitset.
fn set_bit(bits: &mut [u32], i: usize, on: bool) {
    if let Some(w) = bits.get_mut(i / 32) {
        if on {
            *w |= 1 << (i % 32);
        } else {
            *w &= !(1 << (i % 32));
        }
    }
}

fn bit(bits: &[u32], i: usize) -> bool {
    bits.get(i / 32).is_some_and(|w| w & (1 << (i % 32)) != 0)
}

fn need(needed: usize, capacity: usize) -> Result<(), Error> {
    if needed > capacity {
        return Err(Error::CapacityExceeded { needed, capacity });
    }
    Ok(())
}

/// The Z-buffer + P-buffer renderer with S = `Frac` sub-pixel bits, room for
/// `EDGES` polygon edges in the scan converter and `POLY` vertices per clipped face.
#[derive(Debug)]
pub struct ZBufferRenderer<Frac: LeEqU32, const EDGES: usize, const POLY: usize> {
    scan: ScanConverter<EDGES>,
    _frac: PhantomData<Frac>,
}

impl<Frac: LeEqU32, const EDGES: usize, const POLY: usize> Default
    for ZBufferRenderer<Frac, EDGES, POLY>
{
    fn default() -> Self {
        Self::new()
    }
}

/// One frame's fixed inputs, shared by the band passes.
struct FrameCtx<'f, 'm> {
    mesh: &'f Mesh<'m>,
    view: FixedView,
    s: u32,
    viewport: Viewport,
}

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
        let viewport = sink.viewport();
        let (width, height) = (viewport.width, viewport.height);
        let s = Subpixel::<Frac>::BITS;
        let faces = mesh.face_count();
        let row_words = usize::from(width).div_ceil(32);
        let w = usize::from(width).max(1);
        let band_rows = (ws.depth.len().min(ws.ids.len()) / w)
            .min(ws.lines.len() / (2 * row_words).max(1))
            .min(usize::from(height)) as u16;
        need(mesh.vertices().len(), ws.vertices.len()).map_err(Error::widen)?;
        need(faces.div_ceil(32), ws.drawn.len()).map_err(Error::widen)?;
        need(edges.edges().len().div_ceil(32), ws.features.len()).map_err(Error::widen)?;
        if height > 0 && band_rows == 0 {
            need(w, ws.depth.len().min(ws.ids.len())).map_err(Error::widen)?;
            need(2 * row_words, ws.lines.len()).map_err(Error::widen)?;
        }
        let max_abs = mesh
            .vertices()
            .iter()
            .flatten()
            .fold(0.0f32, |m, c| m.max(c.abs()));
        let view = FixedView::new(camera, max_abs, width, height, s).map_err(Error::widen)?;
        for (slot, p) in ws.vertices.iter_mut().zip(mesh.vertices()) {
            let clip = view.clip(*p);
            let outside = view.outcode(&clip);
            let screen = if outside == 0 {
                view.project(&clip)
            } else {
                ScreenVertex::default()
            };
            *slot = ProjectedVertex {
                clip,
                screen,
                outside,
            };
        }
        let viewpoint = camera.viewpoint();
        let cull = match settings.cull {
            Cull::On => true,
            Cull::Off => false,
            Cull::Auto => edges.is_closed(),
        };
        let mut stats = Stats {
            faces: faces as u32,
            band_rows: u32::from(band_rows),
            depth_buffer_bytes: (usize::from(band_rows) * w * size_of::<D>()) as u32,
            ..Stats::default()
        };
        for f in 0..faces {
            let drawn = !cull || mesh.faces_viewpoint(f, &viewpoint);
            set_bit(ws.drawn, f, drawn);
            let idx = mesh.face(f);
            let common = idx.iter().fold(0xFF, |acc, &v| {
                acc & ws.vertices.get(v as usize).map_or(0, |p| p.outside)
            });
            if drawn && common == 0 {
                stats.faces_drawn += 1;
            }
        }
        for (e, edge) in edges.edges().iter().enumerate() {
            let feature = edge.is_feature(mesh, &viewpoint);
            set_bit(ws.features, e, feature);
            stats.feature_edges += u32::from(feature);
        }
        let ctx = FrameCtx {
            mesh,
            view,
            s,
            viewport,
        };
        let Workspace {
            vertices,
            drawn,
            features,
            depth,
            ids,
            lines,
        } = ws;
        let mut band = ZBand {
            depth,
            ids,
            width,
            top: 0,
            rows: 0,
        };
        let mut masks = LineMasks {
            words: lines,
            row_words,
            rows: 0,
        };
        let mut top = 0u16;
        while top < height && band_rows > 0 {
            let rows = band_rows.min(height - top);
            band.reset(top, rows);
            masks.reset(rows);
            stats.bands += 1;
            if settings.mode.needs_depth() {
                stats.spans += self.depth_pass(&ctx, vertices, drawn, &mut band)?;
            }
            if settings.mode.draws_lines() {
                line_pass::<D, POLY>(
                    &ctx, vertices, drawn, features, edges, settings, &band, &mut masks,
                );
            }
            stats.spans += compose::emit_band(
                &ctx, settings, &band, &masks, drawn, palette, &viewpoint, sink, probe,
            )
            .map_err(Error::Target)?;
            top += rows;
        }
        sink.flush().map_err(Error::Target)?;
        Ok(stats)
    }

    /// Depth-tests every drawn face that reaches the band; returns the spans walked.
    fn depth_pass<D: Depth, T>(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        band: &mut ZBand<'_, D>,
    ) -> Result<u32, Error<T>> {
        let mut spans = 0;
        let (top, end) = (band.top, band.top + band.rows);
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
                lo = lo.min(p.screen.y);
                hi = hi.max(p.screen.y);
                outside |= p.outside;
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
}

/// Face `f` clipped and projected into `out`; false when nothing of it is in view.
fn face_polygon<const POLY: usize>(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    f: usize,
    out: &mut Vec<ScreenVertex, POLY>,
) -> Result<bool, Error> {
    out.clear();
    let idx = ctx.mesh.face(f);
    let (mut any, mut all) = (0u8, 0xFFu8);
    for &v in idx {
        let o = vertices.get(v as usize).map_or(0xFF, |p| p.outside);
        any |= o;
        all &= o;
    }
    if all != 0 {
        return Ok(false);
    }
    if any == 0 {
        need(idx.len(), POLY)?;
        for &v in idx {
            if let Some(p) = vertices.get(v as usize) {
                let _ = out.push(p.screen);
            }
        }
        return Ok(true);
    }
    let mut clip: Vec<ClipVertex, POLY> = Vec::new();
    need(idx.len(), POLY)?;
    for &v in idx {
        if let Some(p) = vertices.get(v as usize) {
            let _ = clip.push(p.clip);
        }
    }
    ctx.view.clip_polygon(&mut clip, any)?;
    for c in &clip {
        let _ = out.push(ctx.view.project(c));
    }
    Ok(out.len() >= 3)
}

/// Draws the feature edges that reach the band into the masks.
#[allow(clippy::too_many_arguments)]
fn line_pass<D: Depth, const POLY: usize>(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    drawn: &[u32],
    features: &[u32],
    edges: &EdgeAdjacency<'_>,
    settings: &Settings,
    band: &ZBand<'_, D>,
    masks: &mut LineMasks<'_>,
) {
    let hide = settings.mode.needs_depth();
    // The last face tested for covering an edge point, with its polygon and plane.
    let mut cached: (u16, Vec<ScreenVertex, POLY>, Option<DepthPlane>) = (0, Vec::new(), None);
    for (e, edge) in edges.edges().iter().enumerate() {
        if !bit(features, e) {
            continue;
        }
        let Some((a, b)) = edge_on_screen(ctx, vertices, edge) else {
            continue;
        };
        let rows = band.top..band.top + band.rows;
        walk_segment(&a, &b, ctx.s, ctx.viewport.width, rows, |px| {
            let hidden = hide
                && band.index(px.x, px.y).is_some_and(|i| {
                    let id = band.ids.get(i).copied().unwrap_or(0);
                    id != 0 && hides(ctx, vertices, drawn, edge, id, &px, &mut cached)
                });
            masks.set(px.x, px.y - band.top, hidden);
        });
    }
}

/// The edge clipped to the view and projected, or `None` when it is out of view.
fn edge_on_screen(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    edge: &MeshEdge,
) -> Option<(ScreenVertex, ScreenVertex)> {
    let (pa, pb) = (
        vertices.get(edge.a as usize)?,
        vertices.get(edge.b as usize)?,
    );
    if pa.outside & pb.outside != 0 {
        return None;
    }
    if pa.outside | pb.outside == 0 {
        return Some((pa.screen, pb.screen));
    }
    let (first, last) = ctx
        .view
        .clip_segment(pa.clip, pb.clip, pa.outside | pb.outside)?;
    Some((ctx.view.project(&first), ctx.view.project(&last)))
}

/// True when face `id - 1`, the nearest at the pixel's centre, hides the edge point:
/// it is not one of the edge's own faces, covers the point and is strictly nearer.
fn hides<const POLY: usize>(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    drawn: &[u32],
    edge: &MeshEdge,
    id: u16,
    px: &lines::EdgePixel,
    cached: &mut (u16, Vec<ScreenVertex, POLY>, Option<DepthPlane>),
) -> bool {
    let f = usize::from(id - 1);
    let own = edge.faces[..(edge.face_count.min(2) as usize)]
        .iter()
        .any(|&g| g as usize == f);
    if own || (edge.kind == EdgeKind::NonManifold && face_owns_edge(ctx.mesh, edge, f)) {
        return false;
    }
    if cached.0 != id {
        // Refill the cache in place: the polygon buffer is large, never move it.
        let (cid, poly, plane) = cached;
        *cid = id;
        *plane = None;
        if bit(drawn, f) && face_polygon(ctx, vertices, f, poly).unwrap_or(false) {
            *plane = DepthPlane::new(poly, ctx.s);
        }
    }
    let (_, poly, Some(plane)) = &*cached else {
        return false;
    };
    if !polygon_contains(poly, px.px, px.py) {
        return false;
    }
    // "Strictly nearer", beyond the rounding of fixed-point depth.
    let eps = (px.q >> 16).max(1 << 8);
    plane.at(px.px, px.py) > px.q.saturating_add(eps)
}

impl Viewpoint {
    /// Unit direction from a point toward the eye (for shading).
    pub(crate) fn direction_from(&self, p: [f32; 3]) -> [f32; 3] {
        let d = match *self {
            Viewpoint::Perspective { eye } => [eye[0] - p[0], eye[1] - p[1], eye[2] - p[2]],
            Viewpoint::Orthographic { direction_to_eye } => direction_to_eye,
        };
        let len = crate::camera::sqrt(crate::camera::dot(d, d));
        if len > 0.0 {
            [d[0] / len, d[1] / len, d[2] / len]
        } else {
            [0.0; 3]
        }
    }
}

/// Lines `On`, faces dithered around `Off`.
impl Default for MonoPalette {
    fn default() -> Self {
        MonoPalette {
            line: BinaryColor::On,
        }
    }
}

#[cfg(test)]
mod tests;
