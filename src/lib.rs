//! # pbuffer
//!
//! A `#![no_std]`, allocation-free, fixed-point span rasterizer for embedded
//! displays: screen-space polygons become horizontal spans, decided exactly by the
//! pixel-centre, top-left rule of the project's conventions, and drawn through any
//! embedded-graphics [`DrawTarget`](embedded_graphics_core::draw_target::DrawTarget).
//!
//! The flow is one way: [`ScreenPoint`]s (fixed point, S sub-pixel bits) ->
//! [`ScanConverter`] (edge table, active edges, sorted crossings) or [`XorFiller`]
//! (modulo-2 code row) -> [`Span`]s -> a [`SpanSink`]: [`FillSolid`],
//! [`ContiguousRows`] or the packed 1-bpp [`PackedFramebuffer`].
//!
//! No input panics: bad input is an [`Error`]. Nothing is allocated: capacities are
//! const generics.
#![no_std]
#![forbid(unsafe_code)]
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

mod bits;
pub mod camera;
pub mod codefill;
pub mod codes;
mod error;
mod framebuffer;
mod geometry;
pub mod mesh;
pub mod order;
mod pattern;
pub mod recommend;
pub mod render;
pub mod scan;
mod sort;
mod span;
mod vector;

pub use camera::{Camera, Projection};
pub use codefill::XorFiller;
pub use codes::SchemeViolation;
pub use error::{CameraProblem, EdgeProblem, Error};
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
pub use scan::{FillRule, ScanConverter};
pub use span::{ContiguousRows, FillSolid, Span, SpanSink, ROW_SEGMENTS};
