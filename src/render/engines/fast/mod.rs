//! The fast engine: a scan-line Z-buffer one row high, for microcontrollers.
//!
//! Per mesh, on the host ([`BakedMesh::bake`], in a `build.rs`): face normals and
//! centroids and the compact edge list, kept in flash. Per frame: an `f32`
//! transform of each vertex into an 8-byte cache entry (16-bit screen x, y with S
//! sub-pixel bits, and a depth scaled to the depth range the frame draws); facing
//! bits; faces and feature lines linked into per-row lists (back faces that no ray
//! reaches, away from an open mesh's holes, left out: see `holes`). Per row: each active
//! facet (a face; a bent convex quad split at its diagonal, one plane a side; or a
//! fan triangle of another bent face), in the order of its face index, fills its
//! span into one row of `u32`s, `depth << 16 | (0xFFFF - face)`, with one
//! unsigned compare a pixel; then each active feature line's pixels in the row are
//! tested against the finished row; then the row goes out as spans. Integer work
//! per pixel and per row, edges stepped in 16.16 fixed point, no 64-bit division
//! anywhere in a frame. Working memory grows with one row and the active facets
//! and lines, not with the frame.
//!
//! # What it bends ([conventions](crate::conventions), "Approximate engines")
//! It keeps the fill rule (pixel centres, top-left, even-odd, watertight shared
//! edges), the tie rule (equal depth: the lower face index wins) and the outputs.
//! It bends, measured against the f64 reference in `BENCHMARKS.md`:
//! - **Depth is 16 bits** in the row (of the frame's own nearness range), and a
//!   face's depth is one plane in 16.16 fixed point set up in `f32`: faces closer
//!   than a depth unit, or crossing, may swap over a few pixels. A facet drawn
//!   after one of lower face index takes a pixel only when nearer by its tie (one
//!   depth unit plus a sixteenth of its depth change a pixel, at most 128 units).
//! - **Edge crossings in 16.16**: an edge's crossing of each row is stepped from
//!   its top end with a slope rounded to `2^-16` px (set up in `f32`), within about
//!   `2^-11` px of the exact crossing; every face that shares the edge steps the
//!   same integers, so fills stay watertight.
//! - **A line pixel is tested against the face nearest at its pixel centre**, not
//!   the face over the edge point; the edge's own two faces never hide it, and
//!   another face hides it only when nearer by more than one pixel of the line's
//!   own depth slope plus one depth unit (instead of "strictly nearer"): nearer at
//!   the edge point itself when the face is drawn as one plane (its depth moved
//!   there from the centre along its plane), at the centre by a further quarter
//!   pixel of its steepest slope when it is drawn as several. A steep line whose
//!   next column toward the edge point shows no face is an outline there, never
//!   hidden.
//!   A non-manifold edge's third and later faces are not its own here.
//! - **A bent face** (not planar, [`Mesh::with_planar_faces`]) is drawn as its fan
//!   triangles, each with its own plane (their union is the polygon's even-odd
//!   coverage when they all turn the same way on screen; a convex quad's two are
//!   one facet split at its diagonal, the same pixels). A bent face whose fan
//!   folds over on screen, or that is clipped, is drawn as its polygon with the
//!   plane of its largest fan triangle. Faces of unknown planarity are taken as
//!   planar.
//! - **Snapping in `f32`**: vertices are projected and rounded to the 2^-S grid in
//!   `f32`, so a vertex may land one grid step from the exact engines' snap.
//!
//! [`Mesh::with_planar_faces`]: crate::mesh::Mesh::with_planar_faces

mod active;
mod baked;
mod clip;
mod dash;
mod depth_row;
mod edge;
mod facets;
mod float_int;
mod holes;
mod lines;
mod needs;
mod planes;
mod polygon;
mod row_out;
mod segments;
mod step;
mod view;
mod views;

use core::marker::PhantomData;
use core::mem::{align_of, size_of};

use fixed::types::extra::LeEqU32;
use heapless::Vec;

pub use baked::{BakedMesh, BakedSource, FacePlane, MAX_FAST_FACES};
pub use edge::{CompactEdge, MAX_HOLES, NO_HOLE};
pub use facets::twin_mismatches as span_kernel_twin_mismatches;
pub use facets::MAX_CORNERS;
pub use holes::MAX_CHECKED_FACES;
pub use needs::FrameNeeds;
pub use segments::{
    Contour, Crossing, Piercing, Run, SegmentLines, SegmentLists, SegmentSource, SegmentStats,
    SegmentWorkspace, Segments, VertexFaces, MAX_GRID_CELLS, MAX_NOT_HIDING, MAX_SIDE_TRIANGLES,
    PIERCING_MARGIN,
};
pub use view::FastVertex;
pub(crate) use views::{FaceViews, InstanceViews, OneMesh};

use crate::bits::{bit, set_bit};
use crate::camera::{dot, Camera};
use crate::error::need;
use crate::mesh::{EdgeKind, Viewpoint};
use crate::render::compose::{FrameProbe, Palette};
use crate::render::depth::coverage::contains;
use crate::render::{Cull, Settings, Stats};
use crate::{Error, SpanSink, Viewport};
use active::ActiveFacets;
use clip::{clip_polygon, clip_segment};
pub use dash::DashPhase;
use dash::{line_masks, Dashing};
use depth_row::clear_row;
use facets::{facet, ClipPolygon, CornerSource, Corners, Facet};
use holes::HoleBoxes;
use lines::{line_row, ActiveLine, Beside, FaceSlopes, GapMask, LineTest, NoGaps};
use polygon::{convex, folds, turns_away};
use row_out::{emit_row, FaceRow, Shades};
use view::{guard_px, ScreenMap};

/// The most sub-pixel bits the fast engine takes (its screen coordinates are 16
/// bits and its steppers 32).
pub const FAST_MAX_SUBPIXEL_BITS: u32 = 6;

/// End of a per-row list.
const NONE: u16 = 0xFFFF;

/// Storage the caller lends for one frame of the fast engine. Sizes: `vertices` >=
/// the mesh's vertices; `facing` >= faces / 32 words; `face_links` >= faces;
/// `line_links` >= edges; `heads` >= 2 x height; `row` >= width; `masks` >= 2 x
/// ceil(width / 32) (3 x with [`Dashes::Along`](crate::render::Dashes::Along)); `pool`
/// holds the corners of the frame's clipped faces (0 when nothing is clipped; at
/// most 65,535 are used); `slopes` >= faces; `ids` >= width when a [`FrameProbe`]
/// looks at the rows, else it may be empty; `phases` >= `LINES` with
/// [`Dashes::Along`](crate::render::Dashes::Along), else it may be empty.
/// [`FastWorkspace::bytes`] sums them.
#[derive(Debug)]
pub struct FastWorkspace<'s> {
    /// The per-frame vertex cache.
    pub vertices: &'s mut [FastVertex],
    /// One bit per face: faces the eye.
    pub facing: &'s mut [u32],
    /// Per-row lists of faces: the next face in the list of the same row.
    pub face_links: &'s mut [u16],
    /// Per-row lists of feature lines: the next edge in the same row's list.
    pub line_links: &'s mut [u16],
    /// The first face, then the first line, of each row's list.
    pub heads: &'s mut [u16],
    /// The row: nearest face entries.
    pub row: &'s mut [u32],
    /// The row's visible then hidden line masks (then the gaps of dashes along
    /// the edges).
    pub masks: &'s mut [u32],
    /// Corners of clipped faces.
    pub pool: &'s mut [FastVertex],
    /// Face ids of the row (1 + face, 0 none) for a probe.
    pub ids: &'s mut [u16],
    /// Each face's steepest depth slope this frame (for the line test's margin).
    pub slopes: &'s mut [u16],
    /// The active lines' dash phases, one for each of the engine's `LINES`, with
    /// [`Dashes::Along`](crate::render::Dashes::Along); else it may be empty.
    pub phases: &'s mut [DashPhase],
    /// Storage for hidden lines by the segment
    /// ([`LineVisibility::BySegment`](crate::render::LineVisibility)); `None`:
    /// the line modes test by the pixel.
    pub segments: Option<Segments<'s>>,
}

impl FastWorkspace<'_> {
    /// Bytes of all the lent buffers.
    pub fn bytes(&self) -> usize {
        use core::mem::size_of_val;
        size_of_val(self.vertices)
            + size_of_val(self.facing)
            + size_of_val(self.face_links)
            + size_of_val(self.line_links)
            + size_of_val(self.heads)
            + size_of_val(self.row)
            + size_of_val(self.masks)
            + size_of_val(self.pool)
            + size_of_val(self.ids)
            + size_of_val(self.slopes)
            + size_of_val(self.phases)
            + self
                .segments
                .as_ref()
                .map_or(0, |s| s.lists.bytes() + s.work.bytes())
    }
}

/// The fast engine with S = `Frac` sub-pixel bits (at most
/// [`FAST_MAX_SUBPIXEL_BITS`]), room for `FACETS` facets and `LINES` feature lines
/// active on one row (more is `CapacityExceeded`: its row loop only says the table
/// is full; [`FastRenderer::needs`] counts the frame's peak, and the clip pool's,
/// without drawing, and [`FastRenderer::with_true_need`] puts it in the error, as
/// the short API does).
#[derive(Debug)]
pub struct FastRenderer<Frac: LeEqU32, const FACETS: usize, const LINES: usize> {
    facets: ActiveFacets<FACETS>,
    lines: Vec<ActiveLine, LINES>,
    _frac: PhantomData<Frac>,
}

default_is_new!(FastRenderer<FACETS, LINES>);

/// Bytes of a [`FastRenderer`] with room for `facets` facets and `lines` lines
/// (`size_of` of `FastRenderer<_, facets, lines>`, for sizes known at run time).
pub const fn fast_renderer_bytes(facets: usize, lines: usize) -> usize {
    let fields = ActiveFacets::bytes(facets) + crate::bits::vec_bytes::<ActiveLine>(lines);
    crate::bits::padded(
        fields,
        align_of::<FastRenderer<fixed::types::extra::U4, 0, 0>>(),
    )
}

/// The frame's mesh on screen: the baked mesh, the frame's camera and screen, and
/// the vertex cache made with them.
#[derive(Clone, Copy)]
struct OnScreen<'a, 'm> {
    baked: &'a BakedMesh<'m>,
    map: &'a ScreenMap,
    cache: &'a [FastVertex],
}

/// Reads facet corners from the vertex cache or the clip pool.
struct Source<'a, 'm> {
    mesh: &'a crate::mesh::Mesh<'m>,
    cache: &'a [FastVertex],
    pool: &'a [FastVertex],
}

impl CornerSource for Source<'_, '_> {
    #[inline]
    fn corner(&self, corners: Corners, face: u16, i: usize) -> FastVertex {
        let from_face = |i: usize| {
            let v = self.mesh.face(usize::from(face)).get(i).copied();
            v.and_then(|v| self.cache.get(v as usize).copied())
        };
        match corners {
            Corners::Face => from_face(i),
            Corners::Fan(k) => from_face(if i == 0 { 0 } else { usize::from(k) + i - 1 }),
            Corners::Pool { start, .. } => self.pool.get(usize::from(start) + i).copied(),
        }
        .unwrap_or_default()
    }
}

/// Are back faces culled in a frame of `baked` with `settings`?
pub(crate) fn culls(settings: &Settings, baked: &BakedMesh<'_>) -> bool {
    match settings.cull {
        Cull::On => true,
        Cull::Off => false,
        Cull::Auto => baked.is_closed(),
    }
}

/// Does the face with `plane` face `view`? The test of `Mesh::faces_viewpoint`,
/// on the baked normal and centroid.
pub(crate) fn faces_view(plane: &FacePlane, view: &Viewpoint) -> bool {
    let toward = match view {
        Viewpoint::Perspective { eye } => [
            eye[0] - plane.centroid[0],
            eye[1] - plane.centroid[1],
            eye[2] - plane.centroid[2],
        ],
        Viewpoint::Orthographic { direction_to_eye } => *direction_to_eye,
    };
    dot(plane.normal, toward) > 0.0
}

impl<Frac: LeEqU32, const FACETS: usize, const LINES: usize> FastRenderer<Frac, FACETS, LINES> {
    /// Empty working memory.
    pub const fn new() -> Self {
        Self {
            facets: ActiveFacets::new(),
            lines: Vec::new(),
            _frac: PhantomData,
        }
    }

    /// Bytes of this engine's active lists with room for `facets` and `lines`.
    pub const fn bytes_for(facets: usize, lines: usize) -> usize {
        facets * (size_of::<Facet>() + size_of::<u32>() + size_of::<u16>())
            + lines * size_of::<ActiveLine>()
    }
}

mod buckets;
mod frame;
#[cfg(test)]
mod tests;
