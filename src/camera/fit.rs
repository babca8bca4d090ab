//! A camera that frames a whole mesh: the `render` command's default view (`--fit`),
//! the same rule in `f32`.
//!
//! The eye looks at the centre of the bounding box along a fixed direction
//! ([`FIT_VIEW_DIRECTION`]: from the front-right and a little above, +Y up, the
//! model's front towards +Z as most OBJ exports have it), with a perspective of
//! [`FIT_FOV_DEG`]. The distance is the smallest at which every vertex used by a face
//! projects within [`FIT_FILL`] of the half-width and half-height from the centre:
//! along a fixed direction a vertex's eye-space x and y do not change with the
//! distance and its depth grows by it, so that is one bound per vertex, no iteration.
//! (When that bound is no use, the bounding sphere filling `FIT_FILL` of the narrower
//! field of view is.) Near and far bracket the vertices' depths with a margin of a
//! quarter of the bounding radius, near kept at least half the nearest depth, for
//! depth precision.
//!
//! The `render` command computes this rule in `f64` on the host; here it is `f32`, so
//! the two cameras agree to `f32` rounding, not bit for bit (a host test holds them
//! to it).

use super::{cross, dot, normalize, sqrt, sub, tan, Camera, Projection};
use crate::mesh::Mesh;
use crate::{CameraProblem, Error};

/// Direction from the target to the eye of [`Camera::fit`] (not normalized).
pub const FIT_VIEW_DIRECTION: [f32; 3] = [1.0, 0.8, 1.3];
/// Vertical field of view of [`Camera::fit`], degrees.
pub const FIT_FOV_DEG: f32 = 30.0;
/// The fraction of the half-width and half-height the fitted mesh reaches.
pub const FIT_FILL: f32 = 0.8;

impl Camera {
    /// The camera that frames `mesh` in a `width` x `height` frame (a zero size is
    /// taken as square): the rule of the `render` command's `--fit`, in `f32`.
    ///
    /// The eye looks at the centre of the bounding box of the vertices the faces use,
    /// along [`FIT_VIEW_DIRECTION`] (from the front-right and a little above, +Y up),
    /// with a [`FIT_FOV_DEG`] perspective, from the smallest distance at which every
    /// such vertex projects within [`FIT_FILL`] of the half-width and half-height.
    /// Near and far bracket the vertices' depths with a margin of a quarter of the
    /// bounding radius (near at least half the nearest depth), for depth precision.
    ///
    /// ```
    /// # use pbuffer::prelude::*;
    /// let corners = [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [10.0, 5.0, 0.0], [0.0, 5.0, 0.0]];
    /// let mesh = Mesh::new(&corners, &[0, 1, 2, 3], &[0, 4])?;
    /// let camera = Camera::fit(&mesh, 128, 64)?;
    /// let (near, far) = camera.near_far();
    /// assert!(0.0 < near && near < far);
    /// # Ok::<(), Error>(())
    /// ```
    pub fn fit(mesh: &Mesh<'_>, width: u32, height: u32) -> Result<Self, Error> {
        Self::fit_along(mesh, width, height, FIT_VIEW_DIRECTION, FIT_FOV_DEG)
    }

    /// [`fit`](Self::fit) seen along `direction_to_eye` (any positive multiple of
    /// eye - target) with a vertical field of view of `fov_y_deg` degrees. A zero or
    /// non-finite direction is `EyeAtTarget`, one along +-Y is `UpParallelToView`,
    /// a field of view outside (0, 180) is `FovOutOfRange`.
    pub fn fit_along(
        mesh: &Mesh<'_>,
        width: u32,
        height: u32,
        direction_to_eye: [f32; 3],
        fov_y_deg: f32,
    ) -> Result<Self, Error> {
        // Every corner of every face: a vertex seen twice changes no minimum or
        // maximum, and a validated mesh has at least one face.
        let used = mesh
            .indices()
            .iter()
            .filter_map(|&i| mesh.vertices().get(i as usize).copied());
        Self::fit_points_along(used, width, height, direction_to_eye, fov_y_deg)
    }

    /// [`fit_along`](Self::fit_along) framing `points` rather than a mesh's
    /// vertices: every vertex of several parts, each where it stands (a
    /// [`SceneDrawing`](crate::SceneDrawing)'s posed instances, say). A point seen
    /// twice changes nothing; no points is `EmptyMesh`, a non-finite one
    /// `NonFinite`.
    pub fn fit_points_along(
        points: impl Iterator<Item = [f32; 3]> + Clone,
        width: u32,
        height: u32,
        direction_to_eye: [f32; 3],
        fov_y_deg: f32,
    ) -> Result<Self, Error> {
        let bad = |problem| Err(Error::BadCamera(problem));
        if points.clone().next().is_none() {
            return Err(Error::EmptyMesh);
        }
        if points.clone().flatten().any(|c| !c.is_finite()) {
            return Err(Error::NonFinite);
        }
        if !(fov_y_deg > 0.0 && fov_y_deg < 180.0) {
            return bad(CameraProblem::FovOutOfRange);
        }
        let Some(back) = normalize(direction_to_eye) else {
            return bad(CameraProblem::EyeAtTarget);
        };
        let f = back.map(|c| -c);
        let Some(s) = normalize(cross(f, [0.0, 1.0, 0.0])) else {
            return bad(CameraProblem::UpParallelToView);
        };
        let u = cross(s, f);
        let aspect = if width > 0 && height > 0 {
            width as f32 / height as f32
        } else {
            1.0
        };
        let tan_v = tan(fov_y_deg * (core::f32::consts::PI / 360.0));
        let used = || points.clone();
        let (c, r) = bounds(used());
        // The first guess: the bounding sphere fills FIT_FILL of the narrower field
        // of view (sin(atan(x)) = x / sqrt(1 + x^2)).
        let x = FIT_FILL * tan_v * aspect.min(1.0);
        let mut distance = r * sqrt(1.0 + x * x) / x;
        // Then the exact distance for the vertices: |x| <= FILL * depth * tan *
        // aspect and |y| <= FILL * depth * tan, depth = distance + f.(p - c).
        let (mut need, mut min_off) = (f32::NEG_INFINITY, f32::INFINITY);
        for p in used() {
            let d = sub(p, c);
            let (x, y, z) = (dot(s, d), dot(u, d), dot(f, d));
            need = need
                .max(x.abs() / (FIT_FILL * tan_v * aspect) - z)
                .max(y.abs() / (FIT_FILL * tan_v) - z);
            min_off = min_off.min(z);
        }
        // Keep every vertex well in front of the eye.
        let fitted = need.max(0.05 * r - min_off);
        if fitted.is_finite() && fitted > 0.0 {
            distance = fitted;
        }
        let eye = each(c, back, |c, b| c + distance * b);
        let (lo, hi) = used().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
            let z = dot(f, sub(p, eye));
            (lo.min(z), hi.max(z))
        });
        let margin = 0.25 * r;
        let near = (lo - margin).max(0.5 * lo).max(1e-6 * distance);
        let far = (hi + margin).max(near * 2.0);
        let projection = Projection::Perspective { fov_y_deg };
        Self::new(eye, c, [0.0, 1.0, 0.0], projection, near, far)
    }
}

/// Bounding-box centre and bounding-sphere radius (about that centre) of `points`; a
/// radius that is zero or not finite becomes 1.
fn bounds(points: impl Iterator<Item = [f32; 3]> + Clone) -> ([f32; 3], f32) {
    let (lo, hi) = points.clone().fold(
        ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
        |(lo, hi), p| (each(lo, p, f32::min), each(hi, p, f32::max)),
    );
    let c = each(lo, hi, |lo, hi| 0.5 * (lo + hi));
    let r = points.fold(0.0f32, |r, p| r.max(sqrt(dot(sub(p, c), sub(p, c)))));
    (c, if r > 0.0 && r.is_finite() { r } else { 1.0 })
}

/// `op` of `a` and `b` component by component.
fn each(a: [f32; 3], b: [f32; 3], op: impl Fn(f32, f32) -> f32) -> [f32; 3] {
    let ([a0, a1, a2], [b0, b1, b2]) = (a, b);
    [op(a0, b0), op(a1, b1), op(a2, b2)]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A box of side `side` at `origin`, as two opposite quads.
    fn two_quads(side: f32, o: [f32; 3]) -> [[f32; 3]; 8] {
        core::array::from_fn(|i| {
            let bit = |b: usize| ((i >> b) & 1) as f32 * side;
            [o[0] + bit(0), o[1] + bit(1), o[2] + bit(2)]
        })
    }

    #[test]
    fn whole_model_in_frame_at_the_fill() {
        for (w, h) in [(400u32, 240u32), (128, 128), (100, 300)] {
            for corners in [
                two_quads(2.0, [10.0, -3.0, 5.0]),
                two_quads(0.001, [0.0; 3]),
            ] {
                let mesh = Mesh::new(&corners, &[0, 2, 3, 1, 4, 5, 7, 6], &[0, 4, 8]).unwrap();
                let cam = Camera::fit(&mesh, w, h).unwrap();
                let (near, far) = cam.near_far();
                let rows = cam.clip_rows(w as f32 / h as f32);
                let mut extent = 0.0f32;
                for p in corners {
                    let d = sub(p, cam.eye());
                    let depth = dot(rows[2], d);
                    assert!(depth > near && depth < far, "depth {depth}");
                    let (xn, yn) = (dot(rows[0], d) / depth, dot(rows[1], d) / depth);
                    extent = extent.max(xn.abs()).max(yn.abs());
                }
                assert!((extent - FIT_FILL).abs() < 1e-4, "extent {extent}");
            }
        }
    }

    #[test]
    fn degenerate_mesh_and_bad_directions() {
        let p = [[1.0, 2.0, 3.0]; 3];
        let mesh = Mesh::new(&p, &[0, 1, 2], &[0, 3]).unwrap();
        let cam = Camera::fit(&mesh, 0, 0).unwrap();
        assert_eq!(cam.target, [1.0, 2.0, 3.0]);
        let problem = |d, fov| Camera::fit_along(&mesh, 8, 8, d, fov).unwrap_err();
        let bad = Error::BadCamera;
        assert_eq!(problem([0.0; 3], 30.0), bad(CameraProblem::EyeAtTarget));
        assert_eq!(
            problem([0.0, 2.0, 0.0], 30.0),
            bad(CameraProblem::UpParallelToView)
        );
        assert_eq!(problem([1.0; 3], 180.0), bad(CameraProblem::FovOutOfRange));
        assert_eq!(
            problem([1.0; 3], f32::NAN),
            bad(CameraProblem::FovOutOfRange)
        );
    }
}
