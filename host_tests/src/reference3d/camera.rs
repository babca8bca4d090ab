//! The reference camera: validation, world to eye space, projection, rays, facing.

use super::vector::{cross, dot, norm, scale, sub, V3};
use crate::frame::{CameraSpec, ProjectionSpec};

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
