//! The 3-D renderers: a mesh and a camera in, spans out.
//!
//! Per frame (shared): transform every vertex once (fixed point), mark drawn faces
//! and the view's feature edges. Then a visibility engine fills the face ids of a
//! band of rows: [`ZBufferRenderer`] (the P-buffer paper's depth buffer, in bands) or
//! [`CodeFillRenderer`] (the modulo-2 surface-filling paper's surface codes, one row at a time, no
//! depth buffer) or [`SchemeRenderer`] (the modulo-2 surface-filling paper's schemes 1 and
//! 2: codes made once
//! for a fixed scene, decoded by a colour table). The line pass draws the feature
//! edges that reach the band into a visible and a hidden mask (the P-buffer pattern
//! decides hidden pixels), and composition turns each row into spans.
//!
//! The engines live in `render/engines/`, whose module doc tables every engine: its
//! type, its `render --engine` name and when to choose it. Each has a short alias
//! with S = 4 sub-pixel bits and only the capacities that grow with the mesh left to
//! size: [`Fast`], [`ZBuffer`], [`CodeFill`], [`Painter`], [`Scheme`], [`Warnock`],
//! [`Raycast`].

mod band;
mod compose;
mod depth;
mod engines;
mod idpass;
mod lines;
mod pick;
mod transform;
#[cfg(test)]
mod two_squares;

use embedded_graphics_core::pixelcolor::BinaryColor;
use heapless::Vec;

pub use compose::{FrameProbe, MonoPalette, Palette, SolidPalette};
pub use engines::fast_renderer_bytes;
#[doc(hidden)]
pub use engines::span_kernel_twin_mismatches;
pub(crate) use engines::{faces_view, FaceViews, InstanceViews, OneMesh};
pub use engines::{
    BakedMesh, BakedSource, BvhNode, CodeFill, CodeFillRenderer, CodeWorkspace, CompactEdge,
    Contour, Crossing, DashPhase, Depth, DepthOrder, FacePlane, Fast, FastRenderer, FastVertex,
    FastWorkspace, FrameNeeds, GreyPalette, GreyShades, OneSegment, PaintOrder, Painter,
    PainterRenderer, Piercing, RayFace, Raycast, RaycastFigures, RaycastRenderer, RaycastSizes,
    RaycastStorage, RowCodes, Run, Scheme, SchemeCoding, SchemeRenderer, ScreenSegments,
    SegmentLines, SegmentLists, SegmentSource, SegmentStats, SegmentWorkspace, Segments, SmallFace,
    VertexFaces, Visibility, Warnock, WarnockArea, WarnockFace, WarnockRenderer, WarnockSizes,
    WarnockStorage, ZBuffer, ZBufferRenderer, FAST_MAX_SUBPIXEL_BITS, MAX_CHECKED_FACES,
    MAX_CORNERS, MAX_FAST_FACES, MAX_GRID_CELLS, MAX_HOLES, MAX_NOT_HIDING, MAX_SIDE_TRIANGLES,
    NO_HOLE, PIERCING_MARGIN,
};
pub use idpass::IdWorkspace;
pub use pick::{pick, Pick, PickWorkspace, PickedEdge};
pub use transform::{ClipVertex, ProjectedVertex, ScreenVertex};

use crate::bits::{bit, set_bit};
use crate::mesh::{Mesh, Viewpoint};
use crate::Capacity;
// The engines check their buffers with it as `super::need`.
pub(crate) use crate::error::need;
use crate::{Error, Pattern, Viewport};
use band::IdBand;
use idpass::FrameInput;
use transform::FixedView;

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

/// How the fast engine decides which parts of a line are hidden in the line
/// modes ([`DrawMode::HiddenRemoved`], [`DrawMode::Dashed`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum LineVisibility {
    /// By the segment, at object precision: each drawn edge is cut where it
    /// passes behind a nearer contour, and no face is filled
    /// ([`SegmentLines`]). Needs the mesh's [`VertexFaces`] and the lent
    /// [`FastWorkspace::segments`]; without them, and in a frame with a line or
    /// contour end outside the guard box or near..far, the per-pixel test draws.
    BySegment,
    /// By the pixel (the default while the segment test is slower on the
    /// Cortex-M4, `BENCHMARKS.md`): every face is filled into a row depth buffer
    /// and each line pixel is tested against it. The other engines always test by
    /// the pixel.
    #[default]
    ByPixel,
}

/// How hidden lines are dashed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Dashes {
    /// By the P-buffer's screen pattern ([`Settings::pattern`]): a hidden pixel is
    /// drawn where the pattern's bit at its screen position is 1, so dashes change
    /// length with a line's slope.
    #[default]
    Screen,
    /// As a drawing office dashes them: `dash` pixels on, `gap` pixels off,
    /// measured along each edge (Euclidean length) from the same end of the edge
    /// in every frame, so the dashes do not crawl as the model turns. The pattern
    /// is not used. Drawn by the fast engine ([`FastRenderer`]); the other engines
    /// draw [`Dashes::Screen`]. A `gap` of 0 draws hidden lines solid.
    Along {
        /// Pixels of a dash.
        dash: u8,
        /// Pixels of a gap.
        gap: u8,
    },
}

impl Dashes {
    /// ISO 128 hidden line (line type 02, dashed) for lines one pixel wide:
    /// dashes of 12 line widths, gaps of 3.
    pub const ISO: Self = Self::Along { dash: 12, gap: 3 };
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
    /// How hidden lines are dashed: by the pattern (the default) or along each edge.
    pub dashes: Dashes,
    /// How the fast engine finds hidden lines (the other engines test by the
    /// pixel).
    pub lines: LineVisibility,
}

/// Rows of depth and id storage for bands of `band_rows` rows in a frame `height`
/// high: the band plus a one-row apron above and below, or the whole frame.
pub fn storage_rows(band_rows: u16, height: u16) -> u16 {
    IdBand::rows_needed(band_rows.max(1), height)
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
    /// One bit per mesh edge: a feature edge in this view not yet drawn (scratch:
    /// the line pass clears an edge's bit after the last band it reaches).
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
#[derive(Debug, Clone, Copy, PartialEq, Default)]
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
    /// Bands rendered (the fast engine: one a row, so the frame's height).
    pub bands: u32,
    /// Rows per band (the fast engine: 1).
    pub band_rows: u32,
    /// Bytes of depth samples: the Z-buffer engine's per band, the fast engine's
    /// row (4 a pixel); 0 for the engines without a depth buffer.
    pub depth_buffer_bytes: u32,
    /// Code-fill engine: bits of the widest surface code a row needed (the most
    /// faces covering one pixel). Schemes engine: the scheme's code width. 0 for
    /// the others.
    pub code_bits: u32,
    /// The most faces active on one row, which is what the engine's active-face
    /// table must hold. Fast engine ([`FastRenderer`], [`Drawing`](crate::Drawing)):
    /// the peak of active *facets* (a face, or a bent face's fan triangle), the
    /// `FACETS` that draws this frame ([`Capacity::ActiveFacets`]).
    /// Code-fill engine: the peak of active faces, its `FACES`
    /// ([`Capacity::ActiveFaces`]). 0 for the others.
    pub peak_faces: u32,
    /// The most edges active on one row. Fast engine: the peak of active feature
    /// *lines*, the `LINES` that draws this frame
    /// ([`Capacity::ActiveLines`]). Code-fill engine:
    /// the peak of active polygon edges, its `EDGES`
    /// ([`Capacity::ActiveEdges`]). 0 for the others.
    pub peak_edges: u32,
    /// The world distance one step of the stored depth stands for at the nearest
    /// drawn distance (depth is scaled to the distances the frame draws, not to
    /// near and far): surfaces closer together than this there may tie. Filled by
    /// the fast and Z-buffer engines, 0 for the others.
    pub depth_step_near: f32,
    /// The same at the farthest drawn distance (larger under perspective).
    pub depth_step_far: f32,
    /// Fast engine, hidden lines by the segment: the stage's counts (all 0 when
    /// the per-pixel test drew the lines).
    pub segments: SegmentStats,
}

/// One frame's fixed inputs, shared by the band passes.
struct FrameCtx<'f, 'm> {
    mesh: &'f Mesh<'m>,
    /// The world positions the vertex cache was made from.
    positions: &'f [[f32; 3]],
    settings: &'f Settings,
    view: FixedView,
    s: u32,
    viewport: Viewport,
    viewpoint: Viewpoint,
}

impl FrameCtx<'_, '_> {
    /// Clip coordinates of vertex `v` of the cache `vertices` (`None` for an index
    /// past either, which a validated mesh does not have).
    fn clip_of(&self, vertices: &[ProjectedVertex], v: u32) -> Option<ClipVertex> {
        let p = vertices.get(v as usize)?;
        let position = self.positions.get(v as usize)?;
        Some(p.clip(&self.view, *position))
    }
}

/// Rows per band that `samples` lent id (and depth) samples and `line_words` lent
/// line words hold in `viewport`: the whole frame, or the band plus a one-row apron
/// above and below. Too little for one row is `CapacityExceeded` with what one row
/// needs.
fn band_rows(viewport: Viewport, samples: usize, line_words: usize) -> Result<u16, Error> {
    let (width, height) = (viewport.width, viewport.height);
    let row_words = usize::from(width).div_ceil(32);
    let w = usize::from(width).max(1);
    let stored = (samples / w).min(usize::from(u16::MAX)) as u16;
    let rows = if stored >= height {
        height
    } else {
        stored.saturating_sub(2)
    }
    .min((line_words / (2 * row_words).max(1)).min(usize::from(height)) as u16);
    if height > 0 && rows == 0 {
        need(
            Capacity::BandSamples,
            usize::from(IdBand::rows_needed(1, height)) * w,
            samples,
        )?;
        need(Capacity::BandLineWords, 2 * row_words, line_words)?;
    }
    Ok(rows)
}

/// The shared start of a frame of `input` in `viewport`: checks the lent per-frame
/// storage, transforms every vertex of `input.positions` (the mesh's vertices, or a
/// depth order's fragment vertices, which begin with them) into `vertices`, marks the
/// drawn faces (`drawn`) and this view's feature edges (`features`), and counts them
/// in `stats`.
fn begin_frame<'f, 'm>(
    input: &FrameInput<'f, 'm>,
    viewport: Viewport,
    vertices: &mut [ProjectedVertex],
    drawn: &mut [u32],
    features: &mut [u32],
    stats: &mut Stats,
) -> Result<FrameCtx<'f, 'm>, Error> {
    let FrameInput {
        mesh,
        positions,
        edges,
        camera,
        settings,
        s,
    } = *input;
    let faces = mesh.face_count();
    need(
        Capacity::Vertices,
        positions.len().max(mesh.vertices().len()),
        vertices.len(),
    )?;
    need(Capacity::FaceBits, faces.div_ceil(32), drawn.len())?;
    need(
        Capacity::EdgeBits,
        edges.edges().len().div_ceil(32),
        features.len(),
    )?;
    let max_abs = positions
        .iter()
        .flatten()
        .fold(0.0f32, |m, c| m.max(c.abs()));
    let mut view = FixedView::new(camera, max_abs, viewport.width, viewport.height, s)?;
    // Clip coordinates first, the depth range from them, then the projection: each
    // vertex is transformed once.
    for (slot, p) in vertices.iter_mut().zip(positions) {
        *slot = ProjectedVertex::unprojected(&view, *p);
    }
    let cached = vertices.get(..positions.len()).unwrap_or_default();
    view.fit_depth(cached.iter().map(ProjectedVertex::clip_z));
    (stats.depth_step_near, stats.depth_step_far) = view.depth_steps(32);
    for slot in vertices.iter_mut().take(positions.len()) {
        slot.project(&view);
    }
    let viewpoint = camera.viewpoint();
    let cull = match settings.cull {
        Cull::On => true,
        Cull::Off => false,
        Cull::Auto => edges.is_closed(),
    };
    stats.faces = faces as u32;
    for f in 0..faces {
        let on = !cull || mesh.faces_viewpoint(f, &viewpoint);
        set_bit(drawn, f, on);
        let common = mesh.face(f).iter().fold(0xFF, |acc, &v| {
            acc & vertices.get(v as usize).map_or(0, ProjectedVertex::outside)
        });
        if on && common == 0 {
            stats.faces_drawn += 1;
        }
    }
    for (e, edge) in edges.edges().iter().enumerate() {
        let feature = edge.is_feature(mesh, &viewpoint);
        set_bit(features, e, feature);
        stats.feature_edges += u32::from(feature);
    }
    Ok(FrameCtx {
        mesh,
        positions,
        settings,
        view,
        s,
        viewport,
        viewpoint,
    })
}

/// Face `f` clipped and projected into `out`; false when nothing of it is in view.
fn face_polygon<const POLY: usize>(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    f: usize,
    out: &mut Vec<ScreenVertex, POLY>,
) -> Result<bool, Error> {
    index_polygon(ctx, vertices, ctx.mesh.face(f), out)
}

/// The polygon with vertex indices `idx` (into `vertices`) clipped and projected
/// into `out`; false when nothing of it is in view.
fn index_polygon<const POLY: usize>(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    idx: &[u32],
    out: &mut Vec<ScreenVertex, POLY>,
) -> Result<bool, Error> {
    out.clear();
    let (mut any, mut all) = (0u8, 0xFFu8);
    for &v in idx {
        let o = vertices
            .get(v as usize)
            .map_or(0xFF, ProjectedVertex::outside);
        any |= o;
        all &= o;
    }
    if all != 0 {
        return Ok(false);
    }
    if any == 0 {
        need(Capacity::FaceCorners, idx.len(), POLY)?;
        for &v in idx {
            if let Some(p) = vertices.get(v as usize) {
                let _ = out.push(p.screen());
            }
        }
        return Ok(true);
    }
    let mut clip: Vec<ClipVertex, POLY> = Vec::new();
    need(Capacity::FaceCorners, idx.len(), POLY)?;
    for &v in idx {
        if let Some(c) = ctx.clip_of(vertices, v) {
            let _ = clip.push(c);
        }
    }
    ctx.view.clip_polygon(&mut clip, any)?;
    for c in &clip {
        let _ = out.push(ctx.view.project(c));
    }
    Ok(out.len() >= 3)
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
