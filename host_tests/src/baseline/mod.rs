//! The "plain" baseline: the P-buffer algorithm of Yuan & Sun (Computers & Graphics
//! 24(3), 2000, appendix pseudocode; ../shared/seeds/000_535f0dd2467ca08a.txt) written
//! the obvious way in `f32`, to measure the library against.
//!
//! * A full-frame `f32` depth buffer (and a face-id buffer, needed for `--ids` and for
//!   "other than the edge's own faces"), a byte per pixel for the picture.
//! * Faces are rasterized as fan triangles with `f32` edge functions over their bounding
//!   box (top-left rule on pixel centres, incremental along a row), depth interpolated
//!   as a plane in screen space (normalized so that 0 = near, 1 = far; `1/z` under
//!   perspective, which is affine in screen space).
//! * Feature edges (boundary, non-manifold, crease, silhouette; vertices welded by
//!   bit-identical coordinates) are drawn with an `f32` DDA, one pixel per centre along
//!   the major axis, depth interpolated along the line.
//! * Each pixel goes through the paper's `this_Algorithm`: a nearer interior pixel
//!   updates the depth buffer and clears the picture where the pattern blocks; a
//!   boundary (edge) pixel is drawn when it is not behind, and where
//!   `value_Pattern(x, y) = pattern[x % l][y % l]` passes when it is.
//!
//! Deliberate simplifications against ../shared/CONVENTIONS.md (the baseline need not be
//! exact): coverage of a face is the union of its fan triangles, not their parity
//! (identical for convex faces); `f32` everywhere, no snapping; an edge pixel is hidden
//! when the depth there is nearer by more than 2^-14 of the near-far range and the face
//! there is not one of the edge's own faces (the paper has no such test; without it
//! silhouettes self-hide); edge pixels do not write depth, so all faces are processed
//! before all edges, which gives the same picture as the paper's object order.
//! Camera conventions, clipping (near/far, polygons clipped, never dropped whole),
//! culling and feature-edge rules are those of CONVENTIONS.md.
//!
//! Surfaces modes (not part of the paper): visible faces are set pixels, edges clear them.
mod camera;
mod mesh;
mod pattern;
mod raster;
mod render;
#[cfg(test)]
mod tests;
mod vector;

pub use mesh::{prepare_baseline, BaselineMesh};
pub use pattern::PatternTable;
pub use render::{render_baseline, render_prepared};
