//! The visibility engines. Each decides which face a pixel shows (and so which
//! feature-edge pixels are hidden); the parts they share stay in `render/`: the
//! transform and clipping, the depth geometry (`depth/`), the id band, the line
//! pass, composition and the id-filling frame loop (`idpass`).
//!
//! | type (short alias) | `render --engine` | what it is for, when to choose it |
//! |---|---|---|
//! | [`FastRenderer`] ([`Fast`]) | `fast` (the default) | A scan-line Z-buffer one row
//! high, 16-bit depth, per-mesh constants baked on the host ([`BakedMesh`]): the
//! microcontroller engine, integer work per pixel and memory that grows with one row;
//! approximate within the bounds its module states (line pixels tested at pixel centres,
//! 16.16 edge steps). |
//! | [`ZBufferRenderer`] ([`ZBuffer`]) | `zbuffer` | The depth buffer of Yuan and Sun's
//! P-buffer paper (16- or 32-bit samples, [`Depth`]) in bands of rows: exact, the frame the
//! Warnock and ray-casting engines reproduce; the only engine with anti-aliased grey output
//! ([`render_grey`](ZBufferRenderer::render_grey)). Memory grows with the band. |
//! | [`CodeFillRenderer`] ([`CodeFill`]) | `codefill`, `codefill-crossings`, `scanline` |
//! The modulo-2 surface-filling paper's surface codes, one row at a time, no depth buffer:
//! in a depth order ([`Visibility::Order`], e.g. a BSP tree's; rows bit-sliced or as a
//! crossing list, [`RowCodes`]) or with planes compared where faces overlap
//! ([`Visibility::Planes`], the scan-line method: the Z-buffer's 32-bit frame). Exact, in
//! memory that grows with a row. |
//! | [`PainterRenderer`] ([`Painter`]) | `painter`, `bsp`, `newell` | List priority:
//! polygons painted far to near with no depth test, by farthest depth
//! ([`PaintOrder::FarthestDepth`], wrong on cyclic overlap and interpenetration, kept to
//! show that) or in a depth order made elsewhere (a BSP tree walked per view, Newell's sort). |
//! | [`SchemeRenderer`] ([`Scheme`]) | `codefill --scheme combination` or `path` | The
//! modulo-2 surface-filling paper's schemes 1 and 2: face codes and a colour table made
//! once ([`SchemeCoding`]) for a fixed scene whose occlusion graph is known; no depth per frame. |
//! | [`WarnockRenderer`] ([`Warnock`]) | `warnock` | Warnock's area subdivision on a
//! bounded stack in lent storage, down to pixels decided as the Z-buffer decides them: the
//! Z-buffer's 32-bit frame without a depth buffer, at several times its instructions. |
//! | [`RaycastRenderer`] ([`Raycast`]) | `raycast` | One fixed-point ray per pixel centre
//! through a bounding-volume hierarchy built per frame in lent storage: the Z-buffer's
//! 32-bit frame without a depth buffer, at several times its instructions. |
//!
//! The aliases fix S to 4 sub-pixel bits ([`U4`], the default of [`Drawing`]) and
//! the capacities the examples and tests use for one clipped face (16 vertices, so
//! 16 scan-converter edges) and for the code-fill engine's code (one word, 32 faces
//! over a pixel); what is left to size grows with the mesh.
//!
//! [`Drawing`]: crate::Drawing

/// `Default` for an engine's renderer: its `const fn new()`. Every renderer is
/// generic over the sub-pixel bits `Frac` (held by a `PhantomData<Frac>` field) and
/// some `usize` capacities, starts from empty working memory, and derives `Debug`;
/// what `new` fills in differs per engine, so each writes its own `new` and names its
/// capacities here: `default_is_new!(ZBufferRenderer<EDGES, POLY>);`.
macro_rules! default_is_new {
    ($renderer:ident<$($capacity:ident),+>) => {
        impl<Frac: ::fixed::types::extra::LeEqU32, $(const $capacity: usize),+> Default
            for $renderer<Frac, $($capacity),+>
        {
            fn default() -> Self {
                Self::new()
            }
        }
    };
}

mod codefill;
mod fast;
mod painter;
mod raycast;
mod scheme;
mod warnock;
mod zbuffer;

pub use codefill::{CodeFillRenderer, CodeWorkspace, DepthOrder, RowCodes, Visibility};
pub use fast::fast_renderer_bytes;
#[doc(hidden)]
pub use fast::span_kernel_twin_mismatches;
pub(crate) use fast::{faces_view, FaceViews, InstanceViews, OneMesh};
pub use fast::{
    BakedMesh, BakedSource, CompactEdge, Contour, Crossing, DashPhase, FacePlane, FastRenderer,
    FastVertex, FastWorkspace, FrameNeeds, Piercing, Run, SegmentLines, SegmentLists,
    SegmentSource, SegmentStats, SegmentWorkspace, Segments, VertexFaces, FAST_MAX_SUBPIXEL_BITS,
    MAX_CHECKED_FACES, MAX_CORNERS, MAX_FAST_FACES, MAX_GRID_CELLS, MAX_HOLES, MAX_NOT_HIDING,
    MAX_SIDE_TRIANGLES, NO_HOLE, PIERCING_MARGIN,
};
pub use painter::{PaintOrder, PainterRenderer};
pub use raycast::{
    BvhNode, RayFace, RaycastFigures, RaycastRenderer, RaycastSizes, RaycastStorage,
};
pub use scheme::{OneSegment, SchemeCoding, SchemeRenderer, ScreenSegments};
pub use warnock::{WarnockArea, WarnockFace, WarnockRenderer, WarnockSizes, WarnockStorage};
pub use zbuffer::{Depth, GreyPalette, GreyShades, SmallFace, ZBufferRenderer};

use crate::subpixel::U4;

/// The fast engine, S = 4: room for `FACETS` facets and `LINES` feature lines
/// active on one row.
pub type Fast<const FACETS: usize, const LINES: usize> = FastRenderer<U4, FACETS, LINES>;

/// The Z-buffer engine, S = 4, faces of up to 16 vertices after clipping.
pub type ZBuffer = ZBufferRenderer<U4, 16, 16>;

/// The code-fill engine, S = 4, a 32-bit surface code (at most 32 faces over one
/// pixel), faces of up to 16 vertices after clipping: room for `FACES` faces and
/// `EDGES` edges active on one row.
pub type CodeFill<const FACES: usize, const EDGES: usize> =
    CodeFillRenderer<U4, 1, FACES, EDGES, 16>;

/// The list-priority (painter's) engine, S = 4, polygons of up to 16 vertices after
/// clipping.
pub type Painter = PainterRenderer<U4, 16, 16>;

/// The schemes 1 and 2 engine, S = 4, faces of up to 16 vertices after clipping.
pub type Scheme = SchemeRenderer<U4, 16, 16>;

/// Warnock's area subdivision, S = 4, faces of up to 16 vertices after clipping.
pub type Warnock = WarnockRenderer<U4, 16>;

/// The ray-casting engine, S = 4, faces of up to 16 vertices after clipping.
pub type Raycast = RaycastRenderer<U4, 16>;

#[cfg(test)]
mod tests {
    use super::*;

    /// Each alias is its renderer's long form with S = 4, made by the same `new`.
    #[test]
    fn the_aliases_are_the_long_forms_with_four_subpixel_bits() {
        let _: FastRenderer<U4, 8, 8> = Fast::<8, 8>::new();
        let _: ZBufferRenderer<U4, 16, 16> = ZBuffer::new();
        let _: CodeFillRenderer<U4, 1, 64, 64, 16> = CodeFill::<64, 64>::new();
        let _: PainterRenderer<U4, 16, 16> = Painter::new();
        let _: SchemeRenderer<U4, 16, 16> = Scheme::new();
        let _: WarnockRenderer<U4, 16> = Warnock::new();
        let _: RaycastRenderer<U4, 16> = Raycast::new();
    }
}
