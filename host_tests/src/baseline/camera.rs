//! The `f32` camera (eye space, projection to screen and depth) and near/far clipping.

use super::vector::{cross, dot, normalize, sub, to32, V3};
use crate::frame::{CameraSpec, ProjectionSpec};

/// The camera in f32: eye-space transform and projection to (sx, sy, depth in [0, 1]).
pub(super) struct Cam {
    pub(super) eye: V3,
    pub(super) s: V3,
    pub(super) u: V3,
    pub(super) f: V3,
    pub(super) persp: bool,
    /// Perspective: tan(fov / 2); orthographic: the half-height.
    pub(super) t: f32,
    pub(super) aspect: f32,
    pub(super) near: f32,
    pub(super) far: f32,
    pub(super) w: f32,
    pub(super) h: f32,
}

impl Cam {
    pub(super) fn new(c: &CameraSpec, width: usize, height: usize) -> Self {
        let eye = to32(c.eye);
        let f = normalize(sub(to32(c.target), eye));
        let s = normalize(cross(f, to32(c.up)));
        let u = cross(s, f);
        let (persp, t) = match c.projection {
            ProjectionSpec::Perspective { fov_deg } => {
                (true, (fov_deg.to_radians() as f32 / 2.0).tan())
            }
            ProjectionSpec::Orthographic { half_height } => (false, half_height as f32),
        };
        Cam {
            eye,
            s,
            u,
            f,
            persp,
            t,
            aspect: width as f32 / height as f32,
            near: c.near as f32,
            far: c.far as f32,
            w: width as f32,
            h: height as f32,
        }
    }
    /// Eye space as (x, y, distance along the view direction).
    pub(super) fn to_eye(&self, p: V3) -> V3 {
        let d = sub(p, self.eye);
        [dot(self.s, d), dot(self.u, d), dot(self.f, d)]
    }
    /// Screen x, y and normalized depth (0 near, 1 far) of an eye-space point with
    /// near <= distance <= far.
    pub(super) fn project(&self, e: V3) -> [f32; 3] {
        let (xn, yn, d) = if self.persp {
            let k = 1.0 / (e[2] * self.t);
            let inv = (1.0 / self.near - 1.0 / e[2]) / (1.0 / self.near - 1.0 / self.far);
            (e[0] * k / self.aspect, e[1] * k, inv)
        } else {
            (
                e[0] / (self.t * self.aspect),
                e[1] / self.t,
                (e[2] - self.near) / (self.far - self.near),
            )
        };
        [(xn + 1.0) * self.w * 0.5, (1.0 - yn) * self.h * 0.5, d]
    }
}

/// Clips an eye-space polygon to near <= distance <= far (Sutherland-Hodgman).
pub(super) fn clip_polygon(poly: &[V3], near: f32, far: f32, out: &mut Vec<V3>, tmp: &mut Vec<V3>) {
    out.clear();
    out.extend_from_slice(poly);
    for (plane, keep_ge) in [(near, true), (far, false)] {
        let inside = |p: &V3| {
            if keep_ge {
                p[2] >= plane
            } else {
                p[2] <= plane
            }
        };
        if out.iter().all(inside) {
            continue;
        }
        tmp.clear();
        for i in 0..out.len() {
            let a = out[i];
            let b = out[(i + 1) % out.len()];
            let (ia, ib) = (inside(&a), inside(&b));
            if ia {
                tmp.push(a);
            }
            if ia != ib {
                let t = (plane - a[2]) / (b[2] - a[2]);
                tmp.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), plane]);
            }
        }
        std::mem::swap(out, tmp);
        if out.is_empty() {
            return;
        }
    }
}
