//! Per-point queries of a reference frame: face depth along a ray, coverage, visibility.

use super::coverage::{covers, distance_to_polygon};
use super::vector::{add, cross, dot, scale, sub, V3};
use super::{RefFrame, DEPTH_EPS, HIDE_EPS, TILE};

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
    pub(super) fn edge_point(&self, a: V3, b: V3, s: f64) -> V3 {
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
