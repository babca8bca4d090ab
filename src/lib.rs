//! # pbuffer
//!
//! A `#![no_std]`, allocation-free, fixed-point hidden-line and hidden-surface
//! renderer for embedded displays: a mesh and a camera go in, a line drawing with
//! dashed hidden lines (or filled surfaces) comes out as horizontal spans drawn
//! into any embedded-graphics
//! [`DrawTarget`](embedded_graphics_core::draw_target::DrawTarget).
//!
//! A cube with dashed hidden lines:
//!
//! ```
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor};
//! use pbuffer::prelude::*;
//!
//! const CORNERS: [[f32; 3]; 8] = [[-1., -1., -1.], [1., -1., -1.], [1., 1., -1.], [-1., 1., -1.],
//!     [-1., -1., 1.], [1., -1., 1.], [1., 1., 1.], [-1., 1., 1.]];
//! const QUADS: [u32; 24] = [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 2, 3, 7, 6, 1, 2, 6, 5, 0, 4, 7, 3];
//! let mesh = Mesh::new(&CORNERS, &QUADS, &[0, 4, 8, 12, 16, 20, 24])?;
//! let mut cube = Drawing::<8, 6, 12>::new(); // vertices, faces, edges
//! cube.bake(mesh)?;
//! let camera = Camera::look_at([3.0, 2.5, 4.0], [0.0; 3], 40.0)?;
//! let mut display = MockDisplay::<BinaryColor>::new(); // 64 x 64; fails on overdraw
//! let stats = cube.draw(&camera, &mut FrameRows::<64, 64>::new(), &mut display)?;
//! assert_eq!((stats.faces_drawn, stats.feature_edges), (3, 12)); // 9 edges seen, 3 dashed
//! # Ok::<(), pbuffer::Error>(())
//! ```
//!
//! The flow is one way, one stage a module:
//! 1. [`mesh`]: a validated [`Mesh`] (vertices, polygon faces), its edges
//!    ([`EdgeAdjacency`]) and their kinds: the feature edges a view draws.
//! 2. [`camera`]: [`Camera`], the eye, projection and near and far planes.
//! 3. Projection and clipping (`render`'s transform): vertices to fixed-point
//!    screen positions with S sub-pixel bits ([`subpixel`]), faces clipped at the
//!    near plane.
//! 4. Visibility, by one of the engines of [`render`] (the fast engine by default;
//!    the Z-buffer, the modulo-2 code-fill buffer, painter, BSP, Newell, Warnock,
//!    ray casting, coding schemes), with the depth orders of [`order`] and the
//!    codes of [`codes`].
//! 5. Lines: each feature edge's pixels, visible solid and hidden through the
//!    P-buffer [`Pattern`].
//! 6. Composition: palettes ([`render::MonoPalette`], grey levels) give each run its
//!    colour.
//! 7. Spans: half-open `(y, x0..x1)` runs of one colour into a [`SpanSink`]:
//!    [`FillSolid`], [`ContiguousRows`] or the packed 1-bpp [`PackedFramebuffer`].
//!
//! Under the 3-D flow is the exact 2-D span core: [`ScreenPoint`]s ->
//! [`ScanConverter`] (edge table, active edges, sorted crossings) or [`XorFiller`]
//! (modulo-2 code row) -> [`Span`]s, decided by the pixel-centre, top-left rule.
//!
//! No input panics: bad input is an [`Error`]. Nothing is allocated: capacities are
//! const generics. What a frame means, pixel by pixel, is in [`conventions`].
//!
//! ## The papers
//! - Xiaobu Yuan and Hanqiu Sun, *P-Buffer: Hidden-line rendering with a dynamic
//!   p-buffer*, Computers & Graphics 24(3), 359-366, 2000: the pattern buffer that
//!   dashes hidden lines ([`Pattern`]).
//! - A paper on hidden-surface removal with *a new linear surface-filling algorithm*
//!   (our copy has lost its title page; cited here as "the modulo-2 surface-filling
//!   paper"): surface codes combined by XOR into a scan line, and three coding
//!   schemes ([`codes`], the code-fill engine, [`XorFiller`]).
//! - Michael Laszlo, *Computer Graphics: Hidden Surface Removal*, lecture notes, 2002,
//!   and Mousumi Dutt, *Visible Surface Detection*, lecture notes: the Z-buffer,
//!   Newell-Newell-Sancha depth sort, Warnock subdivision, BSP trees, the scan-line
//!   method, ray casting ([`order`] and the engines of [`render`]).
#![cfg_attr(not(feature = "std"), no_std)]
// Unsafe only in the fenced assembly span kernels (render::engines::fast::facets::kernel).
#![deny(unsafe_code)]
#![deny(missing_docs, missing_debug_implementations)]
// Panic-freedom made visible: no unchecked index, unwrap, expect or panic outside
// tests. Each allowed index carries its bound proof where it is allowed.
#![cfg_attr(
    not(test),
    deny(
        clippy::indexing_slicing,
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic
    )
)]
#![warn(
    clippy::cast_lossless,
    clippy::semicolon_if_nothing_returned,
    clippy::doc_markdown,
    clippy::redundant_closure_for_method_calls,
    trivial_numeric_casts,
    unused_qualifications
)]

#[cfg(feature = "std")]
pub mod bake;
mod bits;
pub mod camera;
pub mod codes;
mod drawing;
mod error;
mod framebuffer;
mod geometry;
pub mod mesh;
#[cfg(feature = "std")]
pub mod obj;
pub mod order;
mod pattern;
pub mod recommend;
pub mod render;
pub mod scan;
pub mod scene;
mod sort;
mod span;
mod vector;

pub use camera::{Camera, Projection, FIT_FILL, FIT_FOV_DEG, FIT_VIEW_DIRECTION};
pub use codes::SchemeViolation;
pub use drawing::{BakedDrawing, Drawing, DrawingNeeds, FrameRows, CLIPPED_CORNERS, CREASE_DEG};
pub use error::{
    CameraProblem, Capacity, EdgeProblem, Error, Shortfall, Shortfalls, MAX_SHORTFALLS,
};
pub use framebuffer::{packed_len, write_mask, PackedFramebuffer};
pub use geometry::{ScreenPoint, Viewport, GUARD_BAND_PX, MAX_SUBPIXEL_BITS, MAX_VIEWPORT};
pub use mesh::{
    face_owns_edge, EdgeAdjacency, EdgeKind, HalfEdgeRecord, Mesh, MeshEdge, Viewpoint, MAX_FACES,
};
pub use order::{BspNode, BspSizes, BspStorage, BspTree};
pub use pattern::Pattern;
pub use render::{
    CodeFillRenderer, CodeWorkspace, Cull, Dashes, DepthOrder, DrawMode, GreyPalette, GreyShades,
    MonoPalette, Palette, SchemeCoding, SchemeRenderer, Settings, SmallFace, SolidPalette, Stats,
    Visibility, Workspace, ZBufferRenderer,
};
pub use scan::XorFiller;
pub use scan::{FillRule, ScanConverter};
pub use scene::{Pose, SceneDrawing};
pub use span::{ContiguousRows, FillSolid, Span, SpanSink, ROW_SEGMENTS};

/// The RAM of the short API's buffers for sizes known at run time: `const fn`s
/// of the sizes, equal to `size_of` of [`Drawing`], [`BakedDrawing`] and
/// [`FrameRows`] with those parameters (whose `RAM_BYTES` give it at compile time).
pub mod ram {
    pub use crate::drawing::ram::{baked_drawing_bytes, drawing_bytes, frame_rows_bytes};
    pub use crate::render::fast_renderer_bytes;
}

/// The README's Rust blocks, compiled and run as doctests so that the guide cannot
/// drift from the library.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

/// The 2-D modulo-2 filler, now in [`scan`] beside the scan converter whose pixels
/// it gives; these paths stay for one release. (The 3-D code-fill engine is
/// [`render::CodeFillRenderer`].)
pub mod codefill {
    pub use crate::scan::{prefix_xor, CodeRow, XorFiller};
}

/// The sub-pixel precisions S (fractional bits of screen coordinates) the engines
/// take as a type parameter, re-exported from `fixed` so that a user need not
/// depend on it: `U4` is 1/16 pixel, the default of [`Drawing`] and of the
/// aliases in [`render`].
pub mod subpixel {
    pub use fixed::types::extra::{LeEqU32, U0, U1, U2, U3, U4, U5, U6, U7, U8};
}

/// What a frame means, exactly: pixel centres, the fill rule, the camera, feature
/// edges, hidden points, exact and approximate engines, and the `render` command's
/// outputs. Every engine and the f64 reference obey it; the module docs cite its
/// sections. (`docs/CONVENTIONS.md`, the project's shared conventions as of this
/// release; CI checks the copy against the shared original.)
#[doc = include_str!("../docs/CONVENTIONS.md")]
// The shared text, kept verbatim (CI compares it): its formulas are not code spans.
#[allow(clippy::doc_markdown)]
pub mod conventions {}

/// The names one frame needs: `use pbuffer::prelude::*;`.
pub mod prelude {
    pub use crate::{
        packed_len, BakedDrawing, Camera, Capacity, DrawMode, Drawing, Error, FrameRows, Mesh,
        PackedFramebuffer, Pose, SceneDrawing, Settings, Stats,
    };
}
