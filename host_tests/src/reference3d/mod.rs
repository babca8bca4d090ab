//! The independent f64 reference of the 3-D hidden-line pipeline (ray casting per pixel
//! centre), following ../shared/CONVENTIONS.md. It shares nothing with the library but
//! the exact 2x2 determinant sign of [`crate::reference::exact`].
//!
//! * Camera: `look_at`, perspective (vertical fov, aspect = W/H) or orthographic
//!   (half-height), near/far, `sx = (x_ndc + 1) W/2`, `sy = (1 - y_ndc) H/2`.
//! * Faces drawn: all, minus back faces when culling is on (auto: on for closed meshes).
//!   Facing: world-space Newell normal `n`, `n . (eye - centroid) > 0` (centroid = mean
//!   of the vertices); orthographic: `n . (eye - target) > 0`.
//! * Surfaces: every drawn face is clipped to `near <= -z <= far` in eye space and
//!   projected; a pixel centre is covered by the even-odd, top-left-rule test of
//!   [`covers`]; the nearest covering face along the ray wins (depth = eye-space `-z`),
//!   equal depth (relative 1e-12) goes to the lower face index.
//! * Lines: feature edges (welded by bit-identical positions; boundary, non-manifold,
//!   crease, silhouette) clipped to near/far, projected, one pixel per centre along the
//!   major axis; each pixel takes the object-space visibility of the edge point at that
//!   centre. Dense samples (every <= 0.25 px of projected length) feed the line metrics.
//!
//! Projected polygon vertices are rounded to multiples of 2^-40 px (about 1e-12 px, below
//! the f64 noise of the projection itself) so that the exact determinant fallback never
//! meets an exponent range it cannot hold; coverage is decided exactly on those values.
mod camera;
mod clip;
mod coverage;
mod depth;
mod render;
#[cfg(test)]
mod tests;
pub(crate) mod vector;

pub use camera::Camera;
pub use coverage::{boundary_distance, covers, distance_to_polygon, orient_sign};
pub use render::reference_frame;
pub use vector::{newell_normal, V3};

/// One face as the reference sees it.
#[derive(Clone, Debug)]
pub struct RefFace {
    /// World-space Newell normal.
    pub normal: V3,
    pub facing: bool,
    /// Drawn (not culled).
    pub drawn: bool,
    /// Eye-space vertices (unclipped).
    pub eye: Vec<V3>,
    /// Screen polygon of the near/far-clipped face (empty if nothing is left).
    pub screen: Vec<(f64, f64)>,
    /// Bounding box of `screen`: min x, min y, max x, max y.
    pub bbox: [f64; 4],
    /// Planar face: eye-space normal n and n.centroid.
    plane: Option<(V3, f64)>,
    /// Depth range of the clipped polygon.
    wmin: f64,
    wmax: f64,
}

/// Kind of a feature edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeKind {
    Boundary,
    NonManifold,
    Crease,
    Silhouette,
    /// A crease that is also a silhouette.
    CreaseSilhouette,
}

/// A welded edge of the mesh.
#[derive(Clone, Debug)]
pub struct RefEdge {
    /// World positions of the two welded vertices.
    pub a: V3,
    pub b: V3,
    /// Faces using the edge (with repetition if a face uses it twice).
    pub faces: Vec<u32>,
    /// `Some` for a feature edge.
    pub kind: Option<EdgeKind>,
}

/// A dense sample of a feature edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineSample {
    pub x: f64,
    pub y: f64,
    /// Projected length this sample stands for (px).
    pub weight: f64,
    pub visible: bool,
    /// Index into [`RefFrame::edges`].
    pub edge: u32,
    /// Eye-space depth of the edge point.
    pub depth: f64,
}

/// The reference frame and the geometry the metrics need.
#[derive(Clone, Debug)]
pub struct RefFrame {
    pub width: usize,
    pub height: usize,
    /// 1 + face index of the visible face per pixel, 0 none (row-major).
    pub ids: Vec<u32>,
    /// Eye-space depth -z of the visible surface per pixel (infinity where none).
    pub depth: Vec<f64>,
    /// 0 none, 1 visible edge, 2 hidden edge (1 wins); all 1 in wireframe mode.
    pub lines: Vec<u8>,
    /// Dense samples, ordered by edge and along each edge.
    pub samples: Vec<LineSample>,
    /// Number of feature edges of the mesh (before clipping).
    pub feature_edges: usize,
    /// Number of faces drawn (after culling).
    pub faces_drawn: usize,
    pub closed: bool,
    pub culling: bool,
    pub camera: Camera,
    pub faces: Vec<RefFace>,
    pub edges: Vec<RefEdge>,
    /// Tiles of `TILE` px over [-TILE, W + TILE) x [-TILE, H + TILE): drawn faces whose
    /// screen bounding box meets the tile.
    tiles: Vec<Vec<u32>>,
    tiles_x: usize,
    tiles_y: usize,
}

const TILE: usize = 8;
/// Spacing of the dense samples along the projected edge (px).
pub const SAMPLE_STEP: f64 = 0.25;
/// Relative depth difference below which depths are equal.
const DEPTH_EPS: f64 = 1e-12;
/// Relative depth margin by which a face must be nearer than an edge point to hide it.
const HIDE_EPS: f64 = 1e-9;
