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

/// Rows of depth and id storage for bands of `band_rows` rows in a frame `height`
/// high: the band plus a one-row apron above and below, or the whole frame.
pub fn storage_rows(band_rows: u16, height: u16) -> u16 {
    ZBand::<u32>::rows_needed(band_rows.max(1), height)
}

/// Storage the caller lends for one frame. Sizes: `vertices` >= the mesh's vertex
/// count; `drawn` >= faces / 32 words; `features` >= edges / 32 words; `depth` and
/// `ids` >= width x [`storage_rows`]; `lines` >= 2 x ceil(width / 32) x band rows.
/// The band height follows from `depth.len() / width` (the whole frame when that
/// reaches the height, else two rows fewer: the apron).
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
        // Storage rows: the band's own rows plus a one-row apron above and below,
        // unless one band holds the whole frame.
        let stored = (ws.depth.len().min(ws.ids.len()) / w).min(usize::from(u16::MAX)) as u16;
        let band_rows = if stored >= height {
            height
        } else {
            stored.saturating_sub(2)
        }
        .min((ws.lines.len() / (2 * row_words).max(1)).min(usize::from(height)) as u16);
        need(mesh.vertices().len(), ws.vertices.len()).map_err(Error::widen)?;
        need(faces.div_ceil(32), ws.drawn.len()).map_err(Error::widen)?;
        need(edges.edges().len().div_ceil(32), ws.features.len()).map_err(Error::widen)?;
        if height > 0 && band_rows == 0 {
            let rows = usize::from(ZBand::<D>::rows_needed(1, height));
            need(rows * w, ws.depth.len().min(ws.ids.len())).map_err(Error::widen)?;
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
            depth_buffer_bytes: (usize::from(ZBand::<D>::rows_needed(band_rows, height))
                * w
                * size_of::<D>()) as u32,
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
            first: 0,
            held: 0,
        };
        let mut masks = LineMasks {
            words: lines,
            row_words,
            rows: 0,
        };
        let mut top = 0u16;
        while top < height && band_rows > 0 {
            let rows = band_rows.min(height - top);
            band.reset(top, rows, height);
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
        // Faces are walked over the apron too: the line test looks there.
        let (top, end) = (band.first, band.first + band.held);
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
    let mut cache = FaceCache::<POLY>::new();
    for (e, edge) in edges.edges().iter().enumerate() {
        if !bit(features, e) {
            continue;
        }
        let Some((a, b)) = edge_on_screen(ctx, vertices, edge) else {
            continue;
        };
        let rows = band.top..band.top + band.rows;
        walk_segment(&a, &b, ctx.s, ctx.viewport.width, rows, |px| {
            let hidden = hide && hidden(ctx, vertices, drawn, edge, band, &px, &mut cache);
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

/// The last two faces tested by the line pass: polygon and depth plane.
struct FaceCache<const POLY: usize> {
    slots: [(u16, Vec<ScreenVertex, POLY>, Option<DepthPlane>); 2],
    next: usize,
}

impl<const POLY: usize> FaceCache<POLY> {
    fn new() -> Self {
        Self {
            slots: [(0, Vec::new(), None), (0, Vec::new(), None)],
            next: 0,
        }
    }

    /// Slot of face `id` (1 + index), filled in place when missing: the polygon
    /// buffers are large, so they never move.
    fn get(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        id: u16,
    ) -> &(u16, Vec<ScreenVertex, POLY>, Option<DepthPlane>) {
        let k = match self.slots.iter().position(|slot| slot.0 == id) {
            Some(k) => k,
            None => {
                let k = self.next;
                self.next ^= 1;
                let (cid, poly, plane) = &mut self.slots[k];
                let f = usize::from(id - 1);
                *cid = id;
                *plane = None;
                if bit(drawn, f) && face_polygon(ctx, vertices, f, poly).unwrap_or(false) {
                    *plane = DepthPlane::new(poly, ctx.s);
                }
                k
            }
        };
        &self.slots[k]
    }
}

/// Whether the edge point of `px` is hidden. The face nearest at the pixel centre
/// decides, or, when it does not contain the edge point (up to half a pixel off the
/// centre), the face nearest at the neighbouring centre on that side, if that one
/// contains it. A face that contains the point hides it when nearer by a small
/// margin; the centre's face extended to the point needs a wide one (see [`nearer`]).
fn hidden<D, const POLY: usize>(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    drawn: &[u32],
    edge: &MeshEdge,
    band: &ZBand<'_, D>,
    px: &lines::EdgePixel,
    cache: &mut FaceCache<POLY>,
) -> bool {
    let own = |id: u16| {
        let f = usize::from(id - 1);
        edge.faces[..(edge.face_count.min(2) as usize)]
            .iter()
            .any(|&g| g as usize == f)
            || (edge.kind == EdgeKind::NonManifold && face_owns_edge(ctx.mesh, edge, f))
    };
    let centre = |k: u16| (2 * i64::from(k) + 1) << ctx.s;
    // The neighbour on the side of the edge point (the minor axis of the edge).
    let (dx, dy) = (px.px - centre(px.x), px.py - centre(px.y));
    let step = |d: i64, k: u16| match d.signum() {
        -1 => k.checked_sub(1),
        1 => k.checked_add(1),
        _ => None,
    };
    let beside = if dy != 0 {
        step(dy, px.y).map(|y| band.id(px.x, y))
    } else {
        step(dx, px.x).map(|x| band.id(x, px.y))
    };
    let nearest = band.id(px.x, px.y);
    let mut extended = None;
    for id in [Some(nearest), beside]
        .into_iter()
        .flatten()
        .filter(|&id| id != 0)
    {
        if own(id) {
            return false;
        }
        let (_, poly, plane) = cache.get(ctx, vertices, drawn, id);
        let Some(plane) = *plane else { continue };
        if polygon_contains(poly, px.px, px.py) {
            return nearer(&plane, px, REACH_COVERING);
        }
        // Only the face at the pixel centre is extended to the point; a neighbour
        // counts only where it covers the point.
        if id == nearest {
            extended = Some((plane, id));
        }
    }
    match extended {
        // Extended to the point and sharing a vertex with the edge, it cannot say:
        // beside a vertex every incident face passes close to the edge.
        Some((plane, id)) if !touches(ctx.mesh, edge, usize::from(id - 1)) => {
            nearer(&plane, px, REACH_EXTENDED)
        }
        _ => false,
    }
}

/// True when `plane` is strictly nearer than the edge point, beyond the uncertainty
/// of sampling at pixel centres: the rounding of fixed-point depth, plus `reach`
/// sixteenths of the plane's depth change over one pixel. This also keeps an edge
/// that lies in another face's plane visible: equal depth does not hide.
fn nearer(plane: &DepthPlane, px: &lines::EdgePixel, reach: u64) -> bool {
    let slope = (u64::from(plane.change_per_pixel()) * reach) >> 4;
    let eps = (px.q >> 16).max(1 << 8) + slope.min(1 << 31) as u32;
    plane.at(px.px, px.py) > px.q.saturating_add(eps)
}

/// Depth margins of the line test, in sixteenths of a pixel's depth change along the
/// hiding face. A face that covers the edge point: only the point's snapping is
/// uncertain. A face extended to the point: a grazing face beside a silhouette,
/// extended, passes just in front of its edge. Both were chosen against the f64
/// reference (`host_tests/tests/pipeline_vs_reference.rs`).
const REACH_COVERING: u64 = 1;
const REACH_EXTENDED: u64 = 32;

/// True when face `f` has a vertex at the position of one of `edge`'s ends.
fn touches(mesh: &Mesh<'_>, edge: &MeshEdge, f: usize) -> bool {
    let key = |v: u32| mesh.vertices().get(v as usize).map(|p| p.map(f32::to_bits));
    let ends = [key(edge.a), key(edge.b)];
    mesh.face(f).iter().any(|&v| ends.contains(&key(v)))
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
