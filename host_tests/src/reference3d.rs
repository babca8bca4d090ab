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

use std::cmp::Ordering;
use std::collections::HashMap;

use crate::frame::{CameraSpec, CullSpec, MeshData, ModeSpec, ProjectionSpec, RenderSpec};
use crate::reference::{distance_to_segment, exact};

/// A 3-vector.
pub type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// Newell normal of a polygon (not normalized; zero for degenerate polygons).
pub fn newell_normal(pts: &[V3]) -> V3 {
    let n = pts.len();
    let mut r = [0.0; 3];
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        r[0] += (a[1] - b[1]) * (a[2] + b[2]);
        r[1] += (a[2] - b[2]) * (a[0] + b[0]);
        r[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    r
}

/// A validated camera for a `width x height` frame.
#[derive(Clone, Debug)]
pub struct Camera {
    pub eye: V3,
    pub target: V3,
    /// Eye-space axes: s (right), u (up), f (forward; eye z = -f.d).
    s: V3,
    u: V3,
    f: V3,
    pub ortho: bool,
    /// Perspective: tan(fov/2); orthographic: half-height.
    k: f64,
    pub aspect: f64,
    pub near: f64,
    pub far: f64,
    pub width: f64,
    pub height: f64,
}

impl Camera {
    /// Validates `spec` (CONVENTIONS: eye != target, up not parallel to the view, fov in
    /// (0, 180), half-height > 0, 0 < near < far, everything finite, frame not empty).
    pub fn new(spec: &CameraSpec, width: usize, height: usize) -> Result<Self, String> {
        if width == 0 || height == 0 {
            return Err(format!("empty frame {width}x{height}"));
        }
        let all = spec
            .eye
            .iter()
            .chain(&spec.target)
            .chain(&spec.up)
            .chain([&spec.near, &spec.far]);
        if !all.clone().all(|v| v.is_finite()) {
            return Err("camera: non-finite value".into());
        }
        let fwd = sub(spec.target, spec.eye);
        let lf = norm(fwd);
        if lf == 0.0 || !lf.is_finite() {
            return Err("camera: eye = target".into());
        }
        let f = scale(fwd, 1.0 / lf);
        let su = cross(f, spec.up);
        let lu = norm(spec.up);
        let ls = norm(su);
        if lu == 0.0 || ls <= 1e-12 * lu {
            return Err("camera: up is parallel to the view direction".into());
        }
        let s = scale(su, 1.0 / ls);
        let u = cross(s, f);
        if spec.near <= 0.0 || spec.far <= spec.near {
            return Err(format!(
                "camera: need 0 < near < far (near {}, far {})",
                spec.near, spec.far
            ));
        }
        let (ortho, k) = match spec.projection {
            ProjectionSpec::Perspective { fov_deg } => {
                if !(fov_deg > 0.0 && fov_deg < 180.0) {
                    return Err(format!("camera: fov {fov_deg} not in (0, 180)"));
                }
                (false, (fov_deg.to_radians() / 2.0).tan())
            }
            ProjectionSpec::Orthographic { half_height } => {
                if !(half_height > 0.0 && half_height.is_finite()) {
                    return Err(format!("camera: half-height {half_height} must be > 0"));
                }
                (true, half_height)
            }
        };
        Ok(Camera {
            eye: spec.eye,
            target: spec.target,
            s,
            u,
            f,
            ortho,
            k,
            aspect: width as f64 / height as f64,
            near: spec.near,
            far: spec.far,
            width: width as f64,
            height: height as f64,
        })
    }

    /// World to eye space: (s.d, u.d, -f.d), d = p - eye.
    pub fn to_eye(&self, p: V3) -> V3 {
        let d = sub(p, self.eye);
        [dot(self.s, d), dot(self.u, d), -dot(self.f, d)]
    }

    /// Eye space (with -z > 0 for perspective) to screen.
    pub fn project(&self, e: V3) -> (f64, f64) {
        let (xn, yn) = if self.ortho {
            (e[0] / (self.k * self.aspect), e[1] / self.k)
        } else {
            let w = -e[2];
            (e[0] / (w * self.k * self.aspect), e[1] / (w * self.k))
        };
        (
            (xn + 1.0) * self.width / 2.0,
            (1.0 - yn) * self.height / 2.0,
        )
    }

    /// The ray through screen point (sx, sy) in eye space: origin `o` and direction `d`
    /// with `d.z = -1`, so the point `o + t d` has depth `-z = t`.
    pub fn ray(&self, sx: f64, sy: f64) -> (V3, V3) {
        let xn = sx * 2.0 / self.width - 1.0;
        let yn = 1.0 - sy * 2.0 / self.height;
        if self.ortho {
            (
                [xn * self.k * self.aspect, yn * self.k, 0.0],
                [0.0, 0.0, -1.0],
            )
        } else {
            ([0.0; 3], [xn * self.k * self.aspect, yn * self.k, -1.0])
        }
    }

    /// Whether a face with world normal `n` and centroid `c` faces the eye.
    pub fn facing(&self, n: V3, c: V3) -> bool {
        if self.ortho {
            dot(n, sub(self.eye, self.target)) > 0.0
        } else {
            dot(n, sub(self.eye, c)) > 0.0
        }
    }
}

/// Rounds to a multiple of 2^-40 (identity for |v| >= 2^12).
fn quantize(v: f64) -> f64 {
    const Q: f64 = (1u64 << 40) as f64;
    (v * Q).round() / Q
}

/// Sign of `(b.x - a.x)(p.y - a.y) - (b.y - a.y)(p.x - a.x)`, exact: an f64 filter with
/// Shewchuk's error bound (3.3e-16, taken as 1e-15), else [`exact::det_sign`].
pub fn orient_sign(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> Ordering {
    let l = (b.0 - a.0) * (p.1 - a.1);
    let r = (b.1 - a.1) * (p.0 - a.0);
    let det = l - r;
    let bound = 1e-15 * (l.abs() + r.abs());
    if det > bound {
        Ordering::Greater
    } else if det < -bound {
        Ordering::Less
    } else {
        exact::det_sign(a, b, p)
    }
}

/// Even-odd coverage of the point `p` by `poly` with the CONVENTIONS boundary rule
/// (the point moved by (+e, +e^2) is inside): the test of `reference::Polygon::winding`.
pub fn covers(poly: &[(f64, f64)], p: (f64, f64)) -> bool {
    let n = poly.len();
    let mut odd = false;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let (lo, hi) = match a.1.partial_cmp(&b.1) {
            Some(Ordering::Less) => (a, b),
            Some(Ordering::Greater) => (b, a),
            _ => continue,
        };
        if lo.1 <= p.1 && p.1 < hi.1 && orient_sign(lo, hi, p) != Ordering::Greater {
            odd = !odd;
        }
    }
    odd
}

/// Distance from `p` to the region of `poly` (0 when covered).
pub fn distance_to_polygon(poly: &[(f64, f64)], p: (f64, f64)) -> f64 {
    if poly.is_empty() {
        return f64::INFINITY;
    }
    if covers(poly, p) {
        return 0.0;
    }
    boundary_distance(poly, p)
}

/// Distance from `p` to the boundary of `poly`.
pub fn boundary_distance(poly: &[(f64, f64)], p: (f64, f64)) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| distance_to_segment(p, poly[i], poly[(i + 1) % n]))
        .fold(f64::INFINITY, f64::min)
}

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

/// Clips a polygon (eye space) to `near <= -z <= far`. The intersection point of an edge
/// is computed from its end points in a canonical order, so that two faces sharing the
/// edge get bit-identical points (watertight).
fn clip_polygon(poly: &[V3], near: f64, far: f64) -> Vec<V3> {
    let keep_near = |p: &V3| -p[2] >= near;
    let keep_far = |p: &V3| -p[2] <= far;
    let a = clip_plane(poly, keep_near, near);
    clip_plane(&a, keep_far, far)
}

fn clip_plane(poly: &[V3], keep: impl Fn(&V3) -> bool, w: f64) -> Vec<V3> {
    let n = poly.len();
    let mut out = Vec::with_capacity(n + 2);
    for i in 0..n {
        let (p, q) = (poly[i], poly[(i + 1) % n]);
        let (kp, kq) = (keep(&p), keep(&q));
        if kp {
            out.push(p);
        }
        if kp != kq {
            out.push(intersect_w(p, q, w));
        }
    }
    out
}

/// The point of segment p q at depth -z = w, computed in a canonical order of p and q.
fn intersect_w(p: V3, q: V3, w: f64) -> V3 {
    let key = |v: &V3| v.map(f64::to_bits);
    let (a, b) = if key(&p) <= key(&q) { (p, q) } else { (q, p) };
    let (wa, wb) = (-a[2], -b[2]);
    let t = (w - wa) / (wb - wa);
    let mut r = add(a, scale(sub(b, a), t));
    r[2] = -w;
    r
}

/// Segment a b (eye space) clipped to near <= -z <= far: parameter range.
fn clip_segment(a: V3, b: V3, near: f64, far: f64) -> Option<(f64, f64)> {
    let (wa, wb) = (-a[2], -b[2]);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (lim, sign) in [(near, 1.0), (far, -1.0)] {
        // keep sign * (w - lim) >= 0
        let fa = sign * (wa - lim);
        let fb = sign * (wb - lim);
        if fa < 0.0 && fb < 0.0 {
            return None;
        }
        if fa < 0.0 {
            t0 = t0.max(fa / (fa - fb));
        } else if fb < 0.0 {
            t1 = t1.min(fa / (fa - fb));
        }
    }
    (t0 <= t1).then_some((t0, t1))
}

impl RefFrame {
    /// Depth (eye-space -z) of face `f` along the ray through screen point (sx, sy): the
    /// plane of a planar face, or the fan triangle (v0, vi, vi+1) the ray meets (the
    /// nearest if several do, the least outside if none does) of a non-planar one. The
    /// plane is extended beyond the polygon; the result is clamped to the depth range
    /// of the clipped polygon. `None` for an edge-on plane or a fully clipped face.
    pub fn face_depth(&self, f: usize, sx: f64, sy: f64) -> Option<f64> {
        let face = &self.faces[f];
        if face.screen.is_empty() {
            return None;
        }
        let (o, d) = self.camera.ray(sx, sy);
        let w = if let Some((n, nc)) = face.plane {
            let nd = dot(n, d);
            if nd == 0.0 {
                return None;
            }
            (nc - dot(n, o)) / nd
        } else {
            fan_depth(&face.eye, o, d)?
        };
        if !w.is_finite() {
            return None;
        }
        Some(w.clamp(face.wmin, face.wmax))
    }

    /// Whether face `f`'s projected (clipped) polygon covers the point.
    pub fn face_covers(&self, f: usize, sx: f64, sy: f64) -> bool {
        let face = &self.faces[f];
        !face.screen.is_empty()
            && sx >= face.bbox[0]
            && sx <= face.bbox[2]
            && sy >= face.bbox[1]
            && sy <= face.bbox[3]
            && covers(&face.screen, (sx, sy))
    }

    /// The drawn face nearest to the eye along the ray through screen point (sx, sy)
    /// among those whose projected polygon covers it (lower index on equal depth), as
    /// the surfaces pass decides at pixel centres: the visible face at any point, for
    /// sub-sample coverage.
    pub fn nearest_face(&self, sx: f64, sy: f64) -> Option<usize> {
        let tx = ((sx + TILE as f64) / TILE as f64).floor();
        let ty = ((sy + TILE as f64) / TILE as f64).floor();
        let all: Vec<u32>;
        let faces: &[u32] =
            if tx < 0.0 || ty < 0.0 || tx >= self.tiles_x as f64 || ty >= self.tiles_y as f64 {
                all = (0..self.faces.len() as u32)
                    .filter(|&f| self.faces[f as usize].drawn)
                    .collect();
                &all
            } else {
                &self.tiles[ty as usize * self.tiles_x + tx as usize]
            };
        let mut best: Option<(usize, f64)> = None;
        for &f in faces {
            let f = f as usize;
            if !self.face_covers(f, sx, sy) {
                continue;
            }
            let Some(w) = self.face_depth(f, sx, sy) else {
                continue;
            };
            if best.is_none_or(|(_, bw)| w < bw * (1.0 - DEPTH_EPS)) {
                best = Some((f, w));
            }
        }
        best.map(|(f, _)| f)
    }

    /// Distance from the point to face `f`'s projected polygon (0 inside, infinity when
    /// nothing of the face is left after clipping).
    pub fn face_distance(&self, f: usize, sx: f64, sy: f64) -> f64 {
        distance_to_polygon(&self.faces[f].screen, (sx, sy))
    }

    /// Whether the edge point projected at (sx, sy), at depth `w`, is visible: no drawn
    /// face other than `own` covers the point and is strictly nearer there.
    pub fn point_visible(&self, sx: f64, sy: f64, w: f64, own: &[u32]) -> bool {
        let tx = ((sx + TILE as f64) / TILE as f64).floor();
        let ty = ((sy + TILE as f64) / TILE as f64).floor();
        if tx < 0.0 || ty < 0.0 || tx >= self.tiles_x as f64 || ty >= self.tiles_y as f64 {
            // Outside the tiled area: test every drawn face.
            return !(0..self.faces.len())
                .any(|f| self.faces[f].drawn && self.hides(f, sx, sy, w, own));
        }
        let tile = &self.tiles[ty as usize * self.tiles_x + tx as usize];
        !tile.iter().any(|&f| self.hides(f as usize, sx, sy, w, own))
    }

    fn hides(&self, f: usize, sx: f64, sy: f64, w: f64, own: &[u32]) -> bool {
        if own.contains(&(f as u32)) {
            return false;
        }
        let b = self.faces[f].bbox;
        if self.faces[f].screen.is_empty() || sx < b[0] || sx > b[2] || sy < b[1] || sy > b[3] {
            return false;
        }
        match self.face_depth(f, sx, sy) {
            Some(d) if d < w * (1.0 - HIDE_EPS) => covers(&self.faces[f].screen, (sx, sy)),
            _ => false,
        }
    }

    /// Eye-space point of feature edge `e` at screen parameter `s` (0..1) of its
    /// clipped projected segment `(a, b)` (eye space): perspective-correct.
    fn edge_point(&self, a: V3, b: V3, s: f64) -> V3 {
        let t = if self.camera.ortho {
            s
        } else {
            let (wa, wb) = (-a[2], -b[2]);
            s * wa / (s * wa + (1.0 - s) * wb)
        };
        add(a, scale(sub(b, a), t))
    }
}

/// Depth along the ray o + t d of the fan triangle (v0, vi, vi+1) the ray meets.
fn fan_depth(eye: &[V3], o: V3, d: V3) -> Option<f64> {
    let mut best_inside: Option<f64> = None;
    let mut best_outside: Option<(f64, f64)> = None; // (min barycentric, t)
    for i in 1..eye.len().saturating_sub(1) {
        let (a, b, c) = (eye[0], eye[i], eye[i + 1]);
        let (e1, e2) = (sub(b, a), sub(c, a));
        let p = cross(d, e2);
        let det = dot(e1, p);
        if det == 0.0 || !det.is_finite() {
            continue;
        }
        let inv = 1.0 / det;
        let tv = sub(o, a);
        let u = dot(tv, p) * inv;
        let q = cross(tv, e1);
        let v = dot(d, q) * inv;
        let t = dot(e2, q) * inv;
        let m = u.min(v).min(1.0 - u - v);
        if m >= -1e-12 {
            best_inside = Some(best_inside.map_or(t, |b: f64| b.min(t)));
        } else if best_outside.is_none_or(|(bm, _)| m > bm) {
            best_outside = Some((m, t));
        }
    }
    best_inside.or(best_outside.map(|(_, t)| t))
}

/// Renders the reference frame of `mesh` seen by `camera` with `spec` (size, crease
/// angle, culling, mode; sub-pixel bits, depth bits, band and pattern do not apply).
pub fn reference_frame(
    mesh: &MeshData,
    camera: &CameraSpec,
    spec: &RenderSpec,
) -> Result<RefFrame, String> {
    let (width, height) = (spec.width, spec.height);
    let cam = Camera::new(camera, width, height)?;
    if !(spec.crease_deg.is_finite()) {
        return Err("crease angle must be finite".into());
    }
    for (k, v) in mesh.vertices.iter().enumerate() {
        if !v.iter().all(|c| c.is_finite()) {
            return Err(format!("vertex {k} is not finite"));
        }
    }
    for (k, f) in mesh.faces.iter().enumerate() {
        if f.len() < 3 {
            return Err(format!("face {k} has fewer than 3 vertices"));
        }
        if f.iter().any(|&i| i as usize >= mesh.vertices.len()) {
            return Err(format!("face {k} has a vertex index out of range"));
        }
    }

    // Welding and edges.
    let mut weld: HashMap<[u64; 3], u32> = HashMap::new();
    let welded: Vec<u32> = mesh
        .vertices
        .iter()
        .map(|p| {
            let n = weld.len() as u32;
            *weld.entry(p.map(f64::to_bits)).or_insert(n)
        })
        .collect();
    let mut edge_index: HashMap<(u32, u32), usize> = HashMap::new();
    let mut edges: Vec<RefEdge> = Vec::new();
    for (fi, f) in mesh.faces.iter().enumerate() {
        let n = f.len();
        for k in 0..n {
            let (i, j) = (f[k] as usize, f[(k + 1) % n] as usize);
            let (wi, wj) = (welded[i], welded[j]);
            if wi == wj {
                continue; // a degenerate edge of a face (repeated vertex): no edge
            }
            let key = (wi.min(wj), wi.max(wj));
            let idx = *edge_index.entry(key).or_insert_with(|| {
                let (a, b) = if wi < wj { (i, j) } else { (j, i) };
                edges.push(RefEdge {
                    a: mesh.vertices[a],
                    b: mesh.vertices[b],
                    faces: Vec::new(),
                    kind: None,
                });
                edges.len() - 1
            });
            edges[idx].faces.push(fi as u32);
        }
    }
    let closed = edges.iter().all(|e| e.faces.len() == 2);
    let culling = match spec.cull {
        CullSpec::On => true,
        CullSpec::Off => false,
        CullSpec::Auto => closed,
    };

    // Faces.
    let eye_vertices: Vec<V3> = mesh.vertices.iter().map(|&p| cam.to_eye(p)).collect();
    let mut faces = Vec::with_capacity(mesh.faces.len());
    for f in &mesh.faces {
        let world: Vec<V3> = f.iter().map(|&i| mesh.vertices[i as usize]).collect();
        let normal = newell_normal(&world);
        let centroid = scale(
            world.iter().fold([0.0; 3], |acc, &p| add(acc, p)),
            1.0 / world.len() as f64,
        );
        let facing = cam.facing(normal, centroid);
        let drawn = !culling || facing;
        let eye: Vec<V3> = f.iter().map(|&i| eye_vertices[i as usize]).collect();
        let clipped = clip_polygon(&eye, cam.near, cam.far);
        let screen: Vec<(f64, f64)> = clipped
            .iter()
            .map(|&p| {
                let (x, y) = cam.project(p);
                (quantize(x), quantize(y))
            })
            .collect();
        let mut bbox = [f64::INFINITY, f64::INFINITY, -f64::INFINITY, -f64::INFINITY];
        for &(x, y) in &screen {
            bbox = [
                bbox[0].min(x),
                bbox[1].min(y),
                bbox[2].max(x),
                bbox[3].max(y),
            ];
        }
        let wmin = clipped.iter().map(|p| -p[2]).fold(f64::INFINITY, f64::min);
        let wmax = clipped.iter().map(|p| -p[2]).fold(-f64::INFINITY, f64::max);
        // Plane (eye space) if planar within 1e-9 of the face's size.
        let ne = newell_normal(&eye);
        let ln = norm(ne);
        let ce = scale(
            eye.iter().fold([0.0; 3], |acc, &p| add(acc, p)),
            1.0 / eye.len() as f64,
        );
        let size = eye.iter().map(|&p| norm(sub(p, ce))).fold(0.0, f64::max);
        let plane = if ln > 0.0 && ln.is_finite() {
            let nu = scale(ne, 1.0 / ln);
            let planar = eye.len() == 3
                || eye
                    .iter()
                    .all(|&p| dot(nu, sub(p, ce)).abs() <= 1e-9 * size);
            planar.then_some((nu, dot(nu, ce)))
        } else {
            None
        };
        faces.push(RefFace {
            normal,
            facing,
            drawn,
            eye,
            screen,
            bbox,
            plane,
            wmin,
            wmax,
        });
    }
    let faces_drawn = faces.iter().filter(|f| f.drawn).count();

    // Feature edges.
    let crease_rad = spec.crease_deg.to_radians();
    for e in &mut edges {
        e.kind = match e.faces.len() {
            1 => Some(EdgeKind::Boundary),
            2 => {
                let (f, g) = (&faces[e.faces[0] as usize], &faces[e.faces[1] as usize]);
                if f.normal == [0.0; 3] || g.normal == [0.0; 3] {
                    None
                } else {
                    let angle = norm(cross(f.normal, g.normal)).atan2(dot(f.normal, g.normal));
                    let crease = angle > crease_rad;
                    let silhouette = f.facing != g.facing;
                    match (crease, silhouette) {
                        (true, true) => Some(EdgeKind::CreaseSilhouette),
                        (true, false) => Some(EdgeKind::Crease),
                        (false, true) => Some(EdgeKind::Silhouette),
                        (false, false) => None,
                    }
                }
            }
            _ => Some(EdgeKind::NonManifold),
        };
    }
    let feature_edges = edges.iter().filter(|e| e.kind.is_some()).count();

    // Tiles.
    let tiles_x = width.div_ceil(TILE) + 2;
    let tiles_y = height.div_ceil(TILE) + 2;
    let mut tiles = vec![Vec::new(); tiles_x * tiles_y];
    for (fi, face) in faces.iter().enumerate() {
        if !face.drawn || face.screen.is_empty() {
            continue;
        }
        let b = face.bbox;
        let t = |v: f64, n: usize| {
            ((v + TILE as f64) / TILE as f64)
                .floor()
                .clamp(0.0, (n - 1) as f64) as usize
        };
        if b[2] < -(TILE as f64) || b[3] < -(TILE as f64) {
            continue;
        }
        if b[0] >= (width + TILE) as f64 || b[1] >= (height + TILE) as f64 {
            continue;
        }
        for ty in t(b[1], tiles_y)..=t(b[3], tiles_y) {
            for tx in t(b[0], tiles_x)..=t(b[2], tiles_x) {
                tiles[ty * tiles_x + tx].push(fi as u32);
            }
        }
    }

    let mut rf = RefFrame {
        width,
        height,
        ids: vec![0; width * height],
        depth: vec![f64::INFINITY; width * height],
        lines: vec![0; width * height],
        samples: Vec::new(),
        feature_edges,
        faces_drawn,
        closed,
        culling,
        camera: cam,
        faces,
        edges,
        tiles,
        tiles_x,
        tiles_y,
    };

    // Surfaces.
    for fi in 0..rf.faces.len() {
        let face = &rf.faces[fi];
        if !face.drawn || face.screen.is_empty() {
            continue;
        }
        let b = face.bbox;
        let i0 = (b[0] - 0.5).ceil().max(0.0);
        let i1 = (b[2] - 0.5).floor().min(width as f64 - 1.0);
        let j0 = (b[1] - 0.5).ceil().max(0.0);
        let j1 = (b[3] - 0.5).floor().min(height as f64 - 1.0);
        if i0 > i1 || j0 > j1 {
            continue;
        }
        for j in j0 as usize..=j1 as usize {
            for i in i0 as usize..=i1 as usize {
                let (px, py) = (i as f64 + 0.5, j as f64 + 0.5);
                if !covers(&rf.faces[fi].screen, (px, py)) {
                    continue;
                }
                let Some(w) = rf.face_depth(fi, px, py) else {
                    continue;
                };
                let k = j * width + i;
                if w < rf.depth[k] * (1.0 - DEPTH_EPS) {
                    rf.depth[k] = w;
                    rf.ids[k] = fi as u32 + 1;
                }
            }
        }
    }

    // Lines and samples.
    let wire = spec.mode == ModeSpec::Wireframe;
    let (wf, hf) = (width as f64, height as f64);
    for ei in 0..rf.edges.len() {
        if rf.edges[ei].kind.is_none() {
            continue;
        }
        let (a, b) = (
            rf.camera.to_eye(rf.edges[ei].a),
            rf.camera.to_eye(rf.edges[ei].b),
        );
        let Some((t0, t1)) = clip_segment(a, b, rf.camera.near, rf.camera.far) else {
            continue;
        };
        let (ca, cb) = (add(a, scale(sub(b, a), t0)), add(a, scale(sub(b, a), t1)));
        let p0 = rf.camera.project(ca);
        let p1 = rf.camera.project(cb);
        let (dx, dy) = (p1.0 - p0.0, p1.1 - p0.1);
        let own = rf.edges[ei].faces.clone();
        let visible_at = |rf: &RefFrame, s: f64, x: f64, y: f64| {
            let p = rf.edge_point(ca, cb, s);
            rf.point_visible(x, y, -p[2], &own)
        };
        // Pixels: one per centre along the major axis, closed interval of the segment.
        let x_major = dx.abs() >= dy.abs();
        let (lo, hi, len_major) = if x_major {
            (p0.0.min(p1.0), p0.0.max(p1.0), wf)
        } else {
            (p0.1.min(p1.1), p0.1.max(p1.1), hf)
        };
        if dx != 0.0 || dy != 0.0 {
            let c0 = (lo - 0.5).ceil().max(0.0);
            let c1 = (hi - 0.5).floor().min(len_major - 1.0);
            let mut c = c0;
            while c <= c1 {
                let m = c + 0.5;
                let (s, x, y) = if x_major {
                    let s = (m - p0.0) / dx;
                    (s, m, p0.1 + s * dy)
                } else {
                    let s = (m - p0.1) / dy;
                    (s, p0.0 + s * dx, m)
                };
                let (i, j) = (x.floor(), y.floor());
                if i >= 0.0 && j >= 0.0 && i < wf && j < hf {
                    let k = j as usize * width + i as usize;
                    let vis = wire || visible_at(&rf, s.clamp(0.0, 1.0), x, y);
                    if vis {
                        rf.lines[k] = 1;
                    } else if rf.lines[k] == 0 {
                        rf.lines[k] = 2;
                    }
                }
                c += 1.0;
            }
        }
        // Samples: the part of the segment within the screen grown by 2 px.
        let Some((s0, s1)) = clip_to_rect(p0, p1, [-2.0, -2.0, wf + 2.0, hf + 2.0]) else {
            continue;
        };
        let len = (dx * dx + dy * dy).sqrt() * (s1 - s0);
        let n = ((len / SAMPLE_STEP).ceil() as usize).max(1);
        let step = len / n as f64;
        for k in 0..=n {
            let s = s0 + (s1 - s0) * k as f64 / n as f64;
            let (x, y) = (p0.0 + s * dx, p0.1 + s * dy);
            let p = rf.edge_point(ca, cb, s);
            let visible = wire || visible_at(&rf, s, x, y);
            let weight = if k == 0 || k == n { step / 2.0 } else { step };
            rf.samples.push(LineSample {
                x,
                y,
                weight,
                visible,
                edge: ei as u32,
                depth: -p[2],
            });
        }
    }
    Ok(rf)
}

/// Liang-Barsky: parameter range of segment p0 p1 inside rect [x0, y0, x1, y1].
fn clip_to_rect(p0: (f64, f64), p1: (f64, f64), r: [f64; 4]) -> Option<(f64, f64)> {
    let (dx, dy) = (p1.0 - p0.0, p1.1 - p0.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, p0.0 - r[0]),
        (dx, r[2] - p0.0),
        (-dy, p0.1 - r[1]),
        (dy, r[3] - p0.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 <= t1).then_some((t0, t1))
}

impl RefFrame {
    /// The reference as a library-style `Frame` (ids and lines; no picture), for
    /// self-comparison of the metrics.
    pub fn to_frame(&self) -> crate::frame::Frame {
        crate::frame::Frame {
            width: self.width,
            height: self.height,
            ids: self.ids.clone(),
            lines: self.lines.clone(),
            packed: Vec::new(),
            stats: vec![
                ("faces".into(), self.faces.len() as u64),
                ("faces_drawn".into(), self.faces_drawn as u64),
                ("feature_edges".into(), self.feature_edges as u64),
            ],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(w: usize, h: usize) -> RenderSpec {
        RenderSpec {
            width: w,
            height: h,
            band: h,
            ..RenderSpec::default()
        }
    }

    /// Orthographic camera looking down -Z with half-height h (x, y map linearly).
    fn ortho(h: f64) -> CameraSpec {
        CameraSpec {
            eye: [0.0, 0.0, 10.0],
            target: [0.0, 0.0, 0.0],
            projection: ProjectionSpec::Orthographic { half_height: h },
            ..CameraSpec::default()
        }
    }

    #[test]
    fn covers_agrees_with_the_2d_reference() {
        let mut state = 99u64;
        let mut next = |k: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % k
        };
        for _ in 0..300 {
            let n = 3 + next(5) as usize;
            let pts: Vec<(f64, f64)> = (0..n)
                .map(|_| (next(80) as f64 / 4.0, next(80) as f64 / 4.0))
                .collect();
            let poly = crate::reference::Polygon::new(&pts, 20.0);
            for j in 0..20 {
                for i in 0..20 {
                    let p = (i as f64 + 0.5, j as f64 + 0.5);
                    assert_eq!(
                        covers(&pts, p),
                        poly.covered(crate::reference::Rule::EvenOdd, p.0, p.1)
                    );
                }
            }
        }
    }

    #[test]
    fn rejects_degenerate_cameras() {
        let s = spec(8, 8);
        let m = MeshData {
            vertices: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            faces: vec![vec![0, 1, 2]],
        };
        let bad = [
            CameraSpec {
                eye: [0.0; 3],
                ..CameraSpec::default()
            },
            CameraSpec {
                up: [0.0, 0.0, 1.0],
                ..CameraSpec::default()
            },
            CameraSpec {
                projection: ProjectionSpec::Perspective { fov_deg: 180.0 },
                ..CameraSpec::default()
            },
            CameraSpec {
                projection: ProjectionSpec::Perspective { fov_deg: 0.0 },
                ..CameraSpec::default()
            },
            CameraSpec {
                near: 0.0,
                ..CameraSpec::default()
            },
            CameraSpec {
                far: 0.1,
                ..CameraSpec::default()
            },
            CameraSpec {
                projection: ProjectionSpec::Orthographic { half_height: 0.0 },
                ..CameraSpec::default()
            },
        ];
        for c in bad {
            assert!(reference_frame(&m, &c, &s).is_err(), "{c:?}");
        }
        assert!(reference_frame(&m, &CameraSpec::default(), &s).is_ok());
    }

    /// A unit square in z = 0 seen orthographically with half-height 4 on an 8x8 frame:
    /// 1 world unit = 1 px, the square [0,1]^2 covers screen x in [4, 5], y in [3, 4]:
    /// exactly pixel (4, 3). Enlarged to [-1.5, 1.5] x [-0.5, 2.5] (screen x 2.5..5.5,
    /// y 1.5..4.5) it covers columns 2..=4 and rows 1..=3 by the top-left rule.
    #[test]
    fn single_quad_covers_expected_pixels() {
        let s = spec(8, 8);
        let quad = |x0: f64, y0: f64, x1: f64, y1: f64| MeshData {
            vertices: vec![[x0, y0, 0.0], [x1, y0, 0.0], [x1, y1, 0.0], [x0, y1, 0.0]],
            faces: vec![vec![0, 1, 2, 3]],
        };
        let r = reference_frame(&quad(0.0, 0.0, 1.0, 1.0), &ortho(4.0), &s).unwrap();
        let on: Vec<usize> = (0..64).filter(|&k| r.ids[k] != 0).collect();
        assert_eq!(on, vec![3 * 8 + 4]);
        assert_eq!(r.depth[3 * 8 + 4], 10.0);
        let r = reference_frame(&quad(-1.5, -0.5, 1.5, 2.5), &ortho(4.0), &s).unwrap();
        let mut expect = Vec::new();
        for j in 1..=3 {
            for i in 2..=4 {
                expect.push(j * 8 + i);
            }
        }
        let on: Vec<usize> = (0..64).filter(|&k| r.ids[k] != 0).collect();
        assert_eq!(on, expect);
        // An open quad: 4 boundary edges, no culling.
        assert_eq!(r.feature_edges, 4);
        assert!(!r.culling);
        // Back side: the same quad wound clockwise is still drawn (not closed, no culling).
        let mut m = quad(-1.5, -0.5, 1.5, 2.5);
        m.faces[0].reverse();
        let r2 = reference_frame(&m, &ortho(4.0), &s).unwrap();
        assert_eq!(r2.ids, r.ids);
        // With culling on it disappears.
        let s_on = RenderSpec {
            cull: CullSpec::On,
            ..s.clone()
        };
        let r3 = reference_frame(&m, &ortho(4.0), &s_on).unwrap();
        assert!(r3.ids.iter().all(|&i| i == 0));
    }

    /// A perspective quad facing the camera: fov 90 at distance 1, so the screen half-
    /// height (H/2 = 4 px) equals 1 world unit at z = 0.
    #[test]
    fn perspective_quad_maps_like_ortho_at_unit_distance() {
        let s = spec(8, 8);
        let cam = CameraSpec {
            eye: [0.0, 0.0, 1.0],
            projection: ProjectionSpec::Perspective { fov_deg: 90.0 },
            ..CameraSpec::default()
        };
        let m = MeshData {
            vertices: vec![
                [0.0, 0.0, 0.0],
                [0.25, 0.0, 0.0],
                [0.25, 0.25, 0.0],
                [0.0, 0.25, 0.0],
            ],
            faces: vec![vec![0, 1, 2, 3]],
        };
        let r = reference_frame(&m, &cam, &s).unwrap();
        let on: Vec<usize> = (0..64).filter(|&k| r.ids[k] != 0).collect();
        assert_eq!(on, vec![3 * 8 + 4]);
        assert!((r.depth[3 * 8 + 4] - 1.0).abs() < 1e-12);
    }

    /// An axis-aligned box from its corners (`shapes::add_box` without rotation).
    fn boxm(lo: V3, hi: V3, m: &mut MeshData) {
        let centre = [0, 1, 2].map(|i| (lo[i] + hi[i]) / 2.0);
        let half = [0, 1, 2].map(|i| (hi[i] - lo[i]) / 2.0);
        crate::shapes::add_box(m, centre, half, 0.0, 0.0);
    }

    /// A small box in front of a big box, seen orthographically along -Z (1 unit = 1 px
    /// on a 16x16 frame with half-height 8): the front box's +z face covers its pixels,
    /// the back box shows around it; the back box's far edges are hidden; the front box's
    /// outline is visible.
    #[test]
    fn box_behind_box() {
        let mut m = MeshData::default();
        boxm([-6.0, -6.0, -4.0], [6.0, 6.0, -2.0], &mut m); // faces 0..6, +z face = 5
        boxm([-2.0, -2.0, 0.0], [2.0, 2.0, 2.0], &mut m); // faces 6..12, +z face = 11
        let s = spec(16, 16);
        let r = reference_frame(&m, &ortho(8.0), &s).unwrap();
        assert!(r.closed && r.culling);
        // Only the two +z faces face the eye.
        assert_eq!(r.faces_drawn, 2);
        // front box: x in [-2, 2] -> screen 6..10, covers columns 6..=9, rows 6..=9.
        for j in 0..16 {
            for i in 0..16 {
                let id = r.ids[j * 16 + i];
                if (6..10).contains(&i) && (6..10).contains(&j) {
                    assert_eq!(id, 12, "{i} {j}");
                    assert_eq!(r.depth[j * 16 + i], 8.0);
                } else if (2..14).contains(&i) && (2..14).contains(&j) {
                    assert_eq!(id, 6, "{i} {j}");
                    assert_eq!(r.depth[j * 16 + i], 12.0);
                } else {
                    assert_eq!(id, 0, "{i} {j}");
                }
            }
        }
        // All 24 edges are creases (90 degrees); seen along an axis, the side edges
        // project to points and the back outlines coincide with the front outlines.
        assert_eq!(r.feature_edges, 24);
        // The back box's front outline (z = -2) is visible, its back outline (z = -4)
        // lies under its own +z face (not one of its faces) and is hidden: both land on
        // the same pixels, where 1 wins. Check the samples instead.
        let back_far: Vec<&LineSample> = r
            .samples
            .iter()
            .filter(|s| (s.depth - 14.0).abs() < 1e-9)
            .collect();
        assert!(!back_far.is_empty());
        // The outline lies exactly on the boundary of the +z face's projection (screen
        // square 2..14): the top-left rule covers its left (x = 2) and top (y = 2) sides,
        // so those are hidden, and not its right and bottom sides, which stay visible.
        for s in &back_far {
            let inner = |v: f64| v > 2.0 && v < 14.0;
            let on = |v: f64, c: f64| (v - c).abs() < 1e-9;
            if (on(s.x, 2.0) && inner(s.y)) || (on(s.y, 2.0) && inner(s.x)) {
                assert!(!s.visible, "{s:?}");
            } else if on(s.x, 14.0) || on(s.y, 14.0) {
                assert!(s.visible, "{s:?}");
            }
        }
        // The front box's front outline (depth 8) is all visible.
        assert!(r
            .samples
            .iter()
            .filter(|s| (s.depth - 8.0).abs() < 1e-9)
            .all(|s| s.visible));
        // The back box's front outline, where it passes behind... it does not: all visible.
        assert!(r
            .samples
            .iter()
            .filter(|s| (s.depth - 12.0).abs() < 1e-9)
            .all(|s| s.visible));
        // The front box's back outline (depth 10) lies under its own +z face: hidden.
        assert!(r
            .samples
            .iter()
            .filter(|s| (s.depth - 10.0).abs() < 1e-9
                && s.x > 6.1
                && s.x < 9.9
                && s.y > 6.1
                && s.y < 9.9)
            .all(|s| !s.visible));
    }

    /// Perspective three-quarter view of a box, with a second box partly behind it: some
    /// samples of the back box are hidden, and the pixel lines carry 2s.
    #[test]
    fn hidden_edge_in_perspective() {
        let mut m = MeshData::default();
        boxm([-1.0, -1.0, -1.0], [1.0, 1.0, 1.0], &mut m);
        boxm([-0.5, -0.5, -5.0], [0.5, 0.5, -3.0], &mut m);
        let cam = CameraSpec {
            eye: [0.5, 0.3, 6.0],
            ..CameraSpec::default()
        };
        let r = reference_frame(&m, &cam, &spec(64, 48)).unwrap();
        // The back box is entirely behind the front one: no pixel shows it.
        assert!(r.ids.iter().all(|&i| i == 0 || i <= 6));
        // Its silhouette edges exist and are all hidden.
        let back: Vec<&LineSample> = r.samples.iter().filter(|s| s.edge >= 12).collect();
        assert!(!back.is_empty());
        assert!(back.iter().all(|s| !s.visible));
        assert!(r.lines.contains(&2));
    }

    /// Crease and silhouette: a "roof" of two quads meeting at 90 degrees is a crease;
    /// at 20 degrees (within the crease angle) it is not; a closed tetrahedron seen so that
    /// exactly one face faces away has silhouette edges.
    #[test]
    fn crease_and_silhouette_classification() {
        let roof = |h: f64| MeshData {
            vertices: vec![
                [-1.0, 0.0, 0.0],
                [0.0, h, 0.0],
                [1.0, 0.0, 0.0],
                [-1.0, 0.0, -1.0],
                [0.0, h, -1.0],
                [1.0, 0.0, -1.0],
            ],
            faces: vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]],
        };
        let cam = CameraSpec {
            eye: [0.0, 5.0, 5.0],
            target: [0.0, 0.0, -0.5],
            ..CameraSpec::default()
        };
        let s = spec(32, 32);
        // h = 1: faces at 45 degrees each side, 90 between normals -> crease.
        let r = reference_frame(&roof(1.0), &cam, &s).unwrap();
        let ridge: Vec<&RefEdge> = r.edges.iter().filter(|e| e.faces.len() == 2).collect();
        assert_eq!(ridge.len(), 1);
        assert_eq!(ridge[0].kind, Some(EdgeKind::Crease));
        assert_eq!(r.feature_edges, 7);
        // h = tan(10 deg): normals 20 degrees apart -> not drawn.
        let r = reference_frame(&roof(10f64.to_radians().tan()), &cam, &s).unwrap();
        let ridge: Vec<&RefEdge> = r.edges.iter().filter(|e| e.faces.len() == 2).collect();
        assert_eq!(ridge[0].kind, None);
        assert_eq!(r.feature_edges, 6);
        // Crease angle 10 -> drawn again.
        let s10 = RenderSpec {
            crease_deg: 10.0,
            ..s.clone()
        };
        let r = reference_frame(&roof(10f64.to_radians().tan()), &cam, &s10).unwrap();
        assert_eq!(r.feature_edges, 7);
        // Silhouette: a very flat roof seen from the side so one face is a back face.
        let cam_side = CameraSpec {
            eye: [5.0, 0.01, -0.5],
            target: [0.0, 0.0, -0.5],
            ..CameraSpec::default()
        };
        let r = reference_frame(&roof(0.05), &cam_side, &s).unwrap();
        assert!(r.faces[1].facing && !r.faces[0].facing);
        let ridge: Vec<&RefEdge> = r.edges.iter().filter(|e| e.faces.len() == 2).collect();
        assert_eq!(ridge[0].kind, Some(EdgeKind::Silhouette));
        // Welding: the same roof with the ridge vertices duplicated (bit-identical) still
        // has one shared ridge edge.
        let mut m = roof(1.0);
        m.vertices.push([0.0, 1.0, 0.0]);
        m.vertices.push([0.0, 1.0, -1.0]);
        m.faces[1] = vec![6, 2, 5, 7];
        let r = reference_frame(&m, &cam, &s).unwrap();
        assert_eq!(r.edges.iter().filter(|e| e.faces.len() == 2).count(), 1);
    }

    /// Near-plane clipping: a quad crossing the near plane is cut, not dropped.
    #[test]
    fn near_clipping_keeps_the_far_part() {
        let m = MeshData {
            vertices: vec![
                [-1.0, -0.2, 1.0],
                [1.0, -0.2, 1.0],
                [1.0, -0.2, -5.0],
                [-1.0, -0.2, -5.0],
            ],
            faces: vec![vec![0, 1, 2, 3]],
        };
        let cam = CameraSpec {
            eye: [0.0, 0.0, 0.5],
            near: 0.3,
            ..CameraSpec::default()
        };
        let r = reference_frame(&m, &cam, &spec(40, 30)).unwrap();
        let n = r.ids.iter().filter(|&&i| i != 0).count();
        assert!(n > 100, "{n}");
        assert!(r
            .depth
            .iter()
            .filter(|d| d.is_finite())
            .all(|&d| (0.3..=5.5).contains(&d)));
    }

    /// A non-planar quad takes its depth from the fan triangle the ray meets.
    #[test]
    fn non_planar_quad_depth_from_fan() {
        let m = MeshData {
            vertices: vec![
                [-1.0, -1.0, 0.0],
                [1.0, -1.0, 0.0],
                [1.0, 1.0, 1.0],
                [-1.0, 1.0, 0.0],
            ],
            faces: vec![vec![0, 1, 2, 3]],
        };
        let r = reference_frame(&m, &ortho(2.0), &spec(16, 16)).unwrap();
        // Fan (0,1,2) and (0,2,3); the point (0.5, -0.5) lies in triangle (0,1,2):
        // plane through (-1,-1,0), (1,-1,0), (1,1,1): z = (y + 1) / 2 -> z = 0.25.
        // screen: x = (0.5/2 + 1) * 8 = 10, y = (1 + 0.5/2) * 8 = 10.
        let d = r.face_depth(0, 10.0, 10.0).unwrap();
        assert!((d - (10.0 - 0.25)).abs() < 1e-12, "{d}");
        // (-0.5, 0.5) lies in triangle (0,2,3): plane z = (x + 1) / 2 -> 0.25 too;
        // (0.5, 0.5) is in (0,2,3)? No: in (0,1,2) iff x >= y. (0.6, 0.2) -> (0,1,2): 0.6.
        let (sx, sy) = ((0.6 / 2.0 + 1.0) * 8.0, (1.0 - 0.2 / 2.0) * 8.0);
        let d = r.face_depth(0, sx, sy).unwrap();
        assert!((d - (10.0 - 0.6)).abs() < 1e-12, "{d}");
    }
}
