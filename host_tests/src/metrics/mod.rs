//! Comparison of a library [`Frame`] with the f64 [`RefFrame`], by the definitions of the
//! issue. "Every pixel within r px" of a pixel means the pixels at Chebyshev distance
//! <= r, inside the frame (r = 1: the 3x3 block, r = 2: the 5x5 block); distances from a
//! pixel centre to geometry (a polygon, an edge, a sample) are Euclidean. (With the
//! 4-neighbourhood, a pixel centre 0.02 px inside a sliver at a concave silhouette corner,
//! legitimately lost to S = 4 snapping, counts as a hole: cow 400x240, pixel (157, 146).)
//!
//! Surfaces (the `ids` image):
//! * (a) holes: the library shows no face at a pixel, the reference shows one there and
//!   at every pixel within 1 px.
//! * (b) wrong faces: the library's face at a pixel, per the reference geometry (its
//!   near/far-clipped projected polygon), neither covers the pixel centre nor comes within
//!   1 px of it (a face index past the mesh or a face clipped away entirely counts too).
//! * (c) depth-order errors: the library's face `f` differs from the reference's and lies
//!   behind the reference's visible surface at every pixel centre within 2 px: at each
//!   such centre the reference shows a face other than `f`, and `f`'s depth along that
//!   ray (its plane extended, clamped to its depth range) exceeds the reference depth by
//!   more than a relative 1e-9.
//! * (d) face-id differences at pixels more than 1 px from every projected edge of every
//!   drawn face (edges of the near/far-clipped polygons); differences within 1 px of an
//!   edge are counted as near-edge differences and only reported.
//!
//! Lines (the `lines` image against the reference's dense samples):
//! * (e) misclassified: library line pixels (1 or 2) that have reference samples within
//!   1 px and whose class (visible/hidden) is opposite to every one of them, except
//!   pixels with, within 1.5 px, a visibility change (a sample whose neighbour on the same
//!   edge has the other class) or samples of two or more edges. Reported as a fraction of
//!   all library line pixels; limit 0.5 %. Pixels with no sample within 1 px are strays,
//!   reported only.
//! * (f) missing: the fraction of the reference's visible (hidden) projected edge length,
//!   on screen, with no visible (hidden) library line pixel centre within 1.5 px; limit
//!   1 % each. Hidden samples with a visible reference sample within 1 px are left out
//!   of the hidden length (and reported as `hidden_excepted`): where both meet, 1 wins in
//!   the lines image, so a hidden line running along or across a visible one cannot show
//!   there (the reference's own lines image fails (f) without this at 128x64).
mod lines;
mod scene;
mod surfaces;
#[cfg(test)]
mod tests;

use crate::frame::Frame;
use crate::reference3d::RefFrame;

pub use lines::compare_lines;
pub use scene::{LineMetrics, SceneMetrics, SurfaceMetrics};
pub use surfaces::{
    compare_surfaces, covered_away, near_edge_mask, snapping_bound, unexplained_diffs,
};

/// Limit of (e), the misclassified fraction.
pub const MISCLASSIFIED_LIMIT: f64 = 0.005;
/// Limit of (f), the missing fraction of visible and of hidden length.
pub const MISSING_LIMIT: f64 = 0.01;
/// Limit of the stray fraction: line pixels with no reference edge sample within
/// 1 px (a line drawn where no feature edge is).
pub const STRAY_LIMIT: f64 = 0.005;
/// Hidden samples with a visible sample this close are left out of (f) ("1 wins").
pub const HIDDEN_EXCEPT_RADIUS: f64 = 1.0;

/// Both comparisons (as the mode asks: `surfaces` for the ids, `lines` for the lines).
pub fn compare(
    scene: &str,
    frame: &Frame,
    rf: &RefFrame,
    surfaces: bool,
    lines: bool,
) -> SceneMetrics {
    SceneMetrics {
        scene: scene.to_string(),
        surfaces: surfaces.then(|| compare_surfaces(frame, rf)),
        lines: lines.then(|| compare_lines(frame, rf)),
        lib_ms: 0.0,
        ref_ms: 0.0,
    }
}
