//! The camera of [conventions](crate::conventions): `look_at` plus a perspective or orthographic
//! projection, set up once per frame in `f32` (no libm on a microcontroller).
//!
//! The camera computes `tan` with its own series rather than a fast approximation
//! (micromath's trade a few parts in a thousand for speed): a camera error would
//! shift the whole picture, not just a few pixels, so it is accurate to `f32`.

mod fit;

pub use fit::{FIT_FILL, FIT_FOV_DEG, FIT_VIEW_DIRECTION};

use crate::mesh::Viewpoint;
use crate::{CameraProblem, Error};

/// How eye space maps to the screen.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Projection {
    /// Perspective with this vertical field of view in degrees, in (0, 180).
    Perspective {
        /// Vertical field of view, degrees.
        fov_y_deg: f32,
    },
    /// Orthographic: the screen shows `half_height` world units above and below the
    /// view axis.
    Orthographic {
        /// Half the visible height, world units.
        half_height: f32,
    },
}

/// A validated camera: `look_at(eye, target, up)`, a projection and the near and far
/// distances.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Camera {
    eye: [f32; 3],
    target: [f32; 3],
    /// Eye-space axes in world space: right, up, forward.
    right: [f32; 3],
    up: [f32; 3],
    forward: [f32; 3],
    projection: Projection,
    near: f32,
    far: f32,
}

pub(crate) fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Square root to full `f32` precision, 0 for non-positive or non-finite input:
/// micromath's fast estimate (no libm on the target), then Newton steps.
pub(crate) fn sqrt(x: f32) -> f32 {
    if x <= 0.0 || !x.is_finite() {
        return 0.0;
    }
    let mut y = micromath::F32Ext::sqrt(x);
    if y.is_nan() || y <= 0.0 {
        y = x;
    }
    for _ in 0..3 {
        y = 0.5 * (y + x / y);
    }
    y
}

/// `v / |v|`, or `None` for a zero (or non-finite) vector.
fn normalize(v: [f32; 3]) -> Option<[f32; 3]> {
    // A component above 1.8e19 overflows the square (a view 1e35 long was called
    // `EyeAtTarget`) and one below 1e-19 underflows it: then divide by the largest
    // component first. Otherwise unchanged, so that cameras keep their exact vectors.
    let d = dot(v, v);
    let v = if d.is_finite() && d >= f32::MIN_POSITIVE {
        v
    } else {
        let m = v.iter().fold(0.0f32, |m, c| m.max(c.abs()));
        if !(m > 0.0 && m.is_finite()) {
            return None;
        }
        [v[0] / m, v[1] / m, v[2] / m]
    };
    let len = sqrt(dot(v, v));
    if len > 0.0 && len.is_finite() {
        Some([v[0] / len, v[1] / len, v[2] / len])
    } else {
        None
    }
}

/// `tan(x)` for `0 < x < pi/2`, from the Taylor series of sin and cos on a halved
/// angle and the double-angle formulas: accurate to a few `f32` ulps.
pub(crate) fn tan(x: f32) -> f32 {
    let h = f64::from(x) * 0.5;
    let h2 = h * h;
    // Terms up to h^13 / 13!: |h| < pi/4 keeps the error below 1e-13.
    let mut sin = 0.0f64;
    let mut cos = 0.0f64;
    let mut term_s = h;
    let mut term_c = 1.0f64;
    for k in 0..7 {
        sin += term_s;
        cos += term_c;
        let n = f64::from(2 * k + 2);
        term_s *= -h2 / (n * (n + 1.0));
        term_c *= -h2 / ((n - 1.0) * n);
    }
    let (s, c) = (2.0 * sin * cos, cos * cos - sin * sin);
    (s / c) as f32
}

impl Camera {
    /// A camera at `eye` looking at `target`, with `up` (usually `[0, 1, 0]`) giving
    /// the screen's up direction. Rejects, as `Error::BadCamera`, non-finite values,
    /// `eye == target`, `up` parallel to the view, a field of view outside (0, 180),
    /// a non-positive half-height, `near <= 0` and `far <= near`.
    pub fn new(
        eye: [f32; 3],
        target: [f32; 3],
        up: [f32; 3],
        projection: Projection,
        near: f32,
        far: f32,
    ) -> Result<Self, Error> {
        let bad = |p| Err(Error::BadCamera(p));
        let param = match projection {
            Projection::Perspective { fov_y_deg } => fov_y_deg,
            Projection::Orthographic { half_height } => half_height,
        };
        let all = eye
            .iter()
            .chain(&target)
            .chain(&up)
            .chain([&param, &near, &far]);
        if !all.into_iter().all(|v| v.is_finite()) {
            return bad(CameraProblem::NonFinite);
        }
        match projection {
            Projection::Perspective { fov_y_deg } if !(fov_y_deg > 0.0 && fov_y_deg < 180.0) => {
                return bad(CameraProblem::FovOutOfRange)
            }
            Projection::Orthographic { half_height } if half_height <= 0.0 => {
                return bad(CameraProblem::HalfHeightNotPositive)
            }
            _ => {}
        }
        if near <= 0.0 {
            return bad(CameraProblem::NearNotPositive);
        }
        if far <= near {
            return bad(CameraProblem::FarNotBeyondNear);
        }
        let Some(forward) = normalize(sub(target, eye)) else {
            return bad(CameraProblem::EyeAtTarget);
        };
        let Some(right) = normalize(cross(forward, up)) else {
            return bad(CameraProblem::UpParallelToView);
        };
        let up = cross(right, forward);
        Ok(Self {
            eye,
            target,
            right,
            up,
            forward,
            projection,
            near,
            far,
        })
    }

    /// A perspective camera at `eye` looking at `target` with a vertical field of
    /// view of `fov_y_deg` degrees: `+y` is up on the screen, the near plane at a
    /// hundredth of the eye's distance to the target and the far plane at a
    /// hundred times it. The errors of [`new`](Self::new); looking straight up or
    /// down is `UpParallelToView` (use [`new`](Self::new) with another `up`).
    pub fn look_at(eye: [f32; 3], target: [f32; 3], fov_y_deg: f32) -> Result<Self, Error> {
        let view = sub(target, eye);
        // |view| scaled by its largest component, so that no square overflows.
        let m = view.iter().fold(0.0f32, |m, c| m.max(c.abs()));
        // Eye at target: any distance lets `new` name the first problem.
        let distance = if m > 0.0 && m.is_finite() {
            m * sqrt(dot(view.map(|c| c / m), view.map(|c| c / m)))
        } else {
            1.0
        };
        let projection = Projection::Perspective { fov_y_deg };
        Self::new(
            eye,
            target,
            [0.0, 1.0, 0.0],
            projection,
            distance / 100.0,
            distance * 100.0,
        )
    }

    /// The eye position.
    pub fn eye(&self) -> [f32; 3] {
        self.eye
    }

    /// The projection.
    pub fn projection(&self) -> Projection {
        self.projection
    }

    /// Near and far distances.
    pub fn near_far(&self) -> (f32, f32) {
        (self.near, self.far)
    }

    /// Where faces are seen from, for facing tests and silhouettes.
    pub fn viewpoint(&self) -> Viewpoint {
        match self.projection {
            Projection::Perspective { .. } => Viewpoint::Perspective { eye: self.eye },
            Projection::Orthographic { .. } => Viewpoint::Orthographic {
                direction_to_eye: sub(self.eye, self.target),
            },
        }
    }

    /// Rows of the affine map from a world position `p` to clip coordinates
    /// `(xc, yc, zc)`, each `row . (p - eye)`: `x_ndc = xc / wc`, `y_ndc = yc / wc`,
    /// `zc` the distance in front of the eye, and `wc = zc` under perspective, 1 under
    /// an orthographic projection.
    pub(crate) fn clip_rows(&self, aspect: f32) -> [[f32; 3]; 3] {
        let (px, py) = match self.projection {
            Projection::Perspective { fov_y_deg } => {
                let t = tan(fov_y_deg * (core::f32::consts::PI / 360.0));
                (1.0 / (t * aspect), 1.0 / t)
            }
            Projection::Orthographic { half_height } => {
                (1.0 / (half_height * aspect), 1.0 / half_height)
            }
        };
        let scale = |v: [f32; 3], k: f32| [v[0] * k, v[1] * k, v[2] * k];
        [scale(self.right, px), scale(self.up, py), self.forward]
    }

    /// True for a perspective camera.
    pub(crate) fn is_perspective(&self) -> bool {
        matches!(self.projection, Projection::Perspective { .. })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_at_is_new_with_y_up_and_planes_a_hundredth_and_a_hundred_times_away() {
        let eye = [3.0, 4.0, 12.0]; // 13 from the origin
        let short = Camera::look_at(eye, [0.0; 3], 40.0).unwrap();
        let fov = Projection::Perspective { fov_y_deg: 40.0 };
        let long = Camera::new(eye, [0.0; 3], [0.0, 1.0, 0.0], fov, 0.13, 1300.0).unwrap();
        assert_eq!(short, long);
    }

    #[test]
    fn look_at_names_the_problem() {
        let bad = |p| Err(Error::BadCamera(p));
        assert_eq!(
            Camera::look_at([1.0; 3], [1.0; 3], 40.0),
            bad(CameraProblem::EyeAtTarget)
        );
        let up = Camera::look_at([0.0, 5.0, 0.0], [0.0; 3], 40.0);
        assert_eq!(up, bad(CameraProblem::UpParallelToView));
        let nan = Camera::look_at([f32::NAN, 0.0, 1.0], [0.0; 3], 40.0);
        assert_eq!(nan, bad(CameraProblem::NonFinite));
        let fov = Camera::look_at([0.0, 0.0, 1.0], [0.0; 3], 180.0);
        assert_eq!(fov, bad(CameraProblem::FovOutOfRange));
        // 1e30 apart: no square overflows, but the far plane (1e32) still fits.
        assert!(Camera::look_at([0.0, 0.0, 1e30], [0.0; 3], 40.0).is_ok());
    }

    #[test]
    fn tan_is_accurate_to_f32() {
        for i in 1..179 {
            let deg = i as f32;
            // Compare at the f32 input itself: near 90 degrees its rounding alone
            // moves tan by more than the tolerance.
            let x = (f64::from(deg).to_radians() * 0.5) as f32;
            let want = libm_free_tan(f64::from(x));
            let got = f64::from(tan(x));
            assert!(
                (got - want).abs() <= 4e-7 * want.abs().max(1.0),
                "tan at {deg}/2 deg"
            );
        }
    }

    /// Reference values by a long series in f64.
    fn libm_free_tan(x: f64) -> f64 {
        libm_free_sin(x) / libm_free_cos(x)
    }
    fn libm_free_sin(x: f64) -> f64 {
        let (mut s, mut t) = (0.0, x);
        for k in 0..30 {
            s += t;
            let n = f64::from(2 * k + 2);
            t *= -x * x / (n * (n + 1.0));
        }
        s
    }
    fn libm_free_cos(x: f64) -> f64 {
        let (mut c, mut t) = (0.0, 1.0);
        for k in 0..30 {
            c += t;
            let n = f64::from(2 * k + 2);
            t *= -x * x / ((n - 1.0) * n);
        }
        c
    }

    #[test]
    fn sqrt_is_accurate_to_f32() {
        for i in 1..2000 {
            let x = i as f32 * 0.731;
            let want = f64::from(x).sqrt();
            assert!((f64::from(sqrt(x)) - want).abs() <= 2e-7 * want, "sqrt {x}");
        }
    }

    #[test]
    fn degenerate_cameras_are_rejected_with_their_reason() {
        let p = Projection::Perspective { fov_y_deg: 45.0 };
        let cam = |eye, target, up, p, n, f| Camera::new(eye, target, up, p, n, f);
        let y = [0.0, 1.0, 0.0];
        let e = [0.0, 0.0, 5.0];
        let o = [0.0; 3];
        let err = |p| Err(Error::BadCamera(p));
        assert_eq!(cam(o, o, y, p, 0.1, 10.0), err(CameraProblem::EyeAtTarget));
        assert_eq!(
            cam([0.0, 5.0, 0.0], o, y, p, 0.1, 10.0),
            err(CameraProblem::UpParallelToView)
        );
        let fov = |d| Projection::Perspective { fov_y_deg: d };
        assert_eq!(
            cam(e, o, y, fov(180.0), 0.1, 10.0),
            err(CameraProblem::FovOutOfRange)
        );
        assert_eq!(
            cam(e, o, y, fov(0.0), 0.1, 10.0),
            err(CameraProblem::FovOutOfRange)
        );
        assert_eq!(
            cam(e, o, y, p, 0.0, 10.0),
            err(CameraProblem::NearNotPositive)
        );
        assert_eq!(
            cam(e, o, y, p, 1.0, 1.0),
            err(CameraProblem::FarNotBeyondNear)
        );
        assert_eq!(
            cam(e, o, y, fov(f32::NAN), 0.1, 10.0),
            err(CameraProblem::NonFinite)
        );
        let ortho = Projection::Orthographic { half_height: 0.0 };
        assert_eq!(
            cam(e, o, y, ortho, 0.1, 10.0),
            err(CameraProblem::HalfHeightNotPositive)
        );
        assert!(cam(e, o, y, p, 0.1, 10.0).is_ok());
    }

    #[test]
    fn look_at_axes_follow_the_conventions() {
        let c = Camera::new(
            [0.0, 0.0, 5.0],
            [0.0; 3],
            [0.0, 1.0, 0.0],
            Projection::Perspective { fov_y_deg: 90.0 },
            0.1,
            100.0,
        )
        .unwrap();
        let rows = c.clip_rows(1.0);
        // A point 1 unit right of the target: x_ndc = 1 / (5 tan 45) = 0.2.
        let d = [1.0, 0.0, -5.0];
        let (xc, zc) = (dot(rows[0], d), dot(rows[2], d));
        assert!((xc / zc - 0.2).abs() < 1e-6 && (zc - 5.0).abs() < 1e-6);
    }
}
