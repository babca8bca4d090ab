//! A camera that frames a whole mesh: the default view of the `render` command.
//!
//! The eye looks at the centre of the bounding box from the front-right and a little
//! above, along (1, 0.8, 1.3) (normalized; +Y up, the model's front towards +Z as most
//! OBJ exports have it), with a perspective of 30 degrees vertical field of view.
//!
//! Distance: the bounding sphere (centre = bounding-box centre, radius = farthest
//! vertex) filling 80 % of the narrower field of view is the first guess, but a sphere
//! is loose around long or flat models (Suzanne would fill 40 % of the height). So the
//! distance is then solved exactly for the vertices: the smallest distance at which
//! every vertex projects within 80 % of the half-width and half-height from the centre
//! (|x_ndc|, |y_ndc| <= 0.8, both fields of view). Along a fixed view direction a
//! vertex's eye-space x and y do not change with the distance and its depth grows by
//! it, so this is one bound per vertex, no iteration.
//!
//! Near and far bracket the vertices' depths with a margin of a quarter of the radius
//! (near kept > 0 and at least half the nearest depth) for depth precision.
//!
//! The library offers the same rule to users as `pbuffer::Camera::fit` (its
//! constants are these, in `f32`); the host computes it in `f64`, as the reference
//! does everything, so the `render` command's frames are those of the f64 rule, and
//! `tests/tools/fit_library.rs` holds the two cameras to agree within f32 rounding.

use crate::frame::{CameraSpec, MeshData, ProjectionSpec};

/// Direction from the target to the eye (not normalized).
pub const VIEW_DIRECTION: [f64; 3] = [1.0, 0.8, 1.3];
/// Vertical field of view of the fitted camera, degrees.
pub const FIT_FOV_DEG: f64 = 30.0;
/// Fraction of the narrower field of view the bounding sphere fills.
pub const FILL: f64 = 0.8;

/// The vertices used by faces (all vertices if no face uses any).
fn used_vertices(mesh: &MeshData) -> Vec<[f64; 3]> {
    let mut seen = vec![false; mesh.vertices.len()];
    for f in &mesh.faces {
        for &i in f {
            if let Some(s) = seen.get_mut(i as usize) {
                *s = true;
            }
        }
    }
    let v: Vec<[f64; 3]> = mesh
        .vertices
        .iter()
        .zip(&seen)
        .filter(|(_, &s)| s)
        .map(|(p, _)| *p)
        .collect();
    if v.is_empty() {
        mesh.vertices.clone()
    } else {
        v
    }
}

/// Bounding-box centre and bounding-sphere radius (about that centre) of the vertices
/// used by faces (all vertices if no face uses any). An empty mesh gives (origin, 1);
/// a radius of zero becomes 1.
pub fn used_vertex_bounds(mesh: &MeshData) -> ([f64; 3], f64) {
    let used = used_vertices(mesh);
    if used.is_empty() {
        return ([0.0; 3], 1.0);
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &used {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let c = [
        0.5 * (lo[0] + hi[0]),
        0.5 * (lo[1] + hi[1]),
        0.5 * (lo[2] + hi[2]),
    ];
    let r = used
        .iter()
        .map(|p| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt())
        .fold(0.0, f64::max);
    (c, if r > 0.0 && r.is_finite() { r } else { 1.0 })
}

/// The fitted camera for a `width x height` frame (see the module documentation).
pub fn fit_camera(mesh: &MeshData, width: usize, height: usize) -> CameraSpec {
    let (c, r) = used_vertex_bounds(mesh);
    let aspect = if width > 0 && height > 0 {
        width as f64 / height as f64
    } else {
        1.0
    };
    let tan_v = (FIT_FOV_DEG.to_radians() / 2.0).tan();
    let [dx, dy, dz] = VIEW_DIRECTION;
    let n = (dx * dx + dy * dy + dz * dz).sqrt();
    // Unit vectors of the view: `back` from the target to the eye, `s` right, `u` up.
    let back = [dx / n, dy / n, dz / n];
    let f = [-back[0], -back[1], -back[2]];
    let s = normalize(cross(f, [0.0, 1.0, 0.0]));
    let u = cross(s, f);
    // First guess: the bounding sphere fills FILL of the narrower field of view.
    let tan_half = tan_v * aspect.min(1.0);
    let mut distance = r / (FILL * tan_half).atan().sin();
    // Then the exact distance for the vertices themselves: a vertex at offset p - c has
    // eye-space x = s.(p - c), y = u.(p - c), depth = distance + f.(p - c), none of
    // which depend on the distance but the depth; |x| <= FILL * depth * tan * aspect
    // and |y| <= FILL * depth * tan give a lower bound on the distance per vertex.
    let pts = used_vertices(mesh);
    if !pts.is_empty() {
        let mut need = f64::NEG_INFINITY;
        let mut min_off = f64::INFINITY;
        for p in &pts {
            let d = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
            let (x, y, z) = (dot(s, d), dot(u, d), dot(f, d));
            need = need
                .max(x.abs() / (FILL * tan_v * aspect) - z)
                .max(y.abs() / (FILL * tan_v) - z);
            min_off = min_off.min(z);
        }
        // Keep every vertex well in front of the eye.
        let fitted = need.max(0.05 * r - min_off);
        if fitted.is_finite() && fitted > 0.0 {
            distance = fitted;
        }
    }
    let eye = [
        c[0] + distance * back[0],
        c[1] + distance * back[1],
        c[2] + distance * back[2],
    ];
    // Near and far bracket the vertices (and stay inside the bounding sphere's range).
    let (mut lo, mut hi) = (distance - r, distance + r);
    if !pts.is_empty() {
        let depths = pts
            .iter()
            .map(|p| dot(f, [p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]]));
        let (a, b) = depths.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), z| {
            (a.min(z), b.max(z))
        });
        lo = a;
        hi = b;
    }
    let margin = 0.25 * r;
    let near = (lo - margin).max(0.5 * lo).max(1e-6 * distance);
    CameraSpec {
        eye,
        target: c,
        up: [0.0, 1.0, 0.0],
        projection: ProjectionSpec::Perspective {
            fov_deg: FIT_FOV_DEG,
        },
        near,
        far: (hi + margin).max(near * 2.0),
    }
}

/// The dot product.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The cross product.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a` scaled to unit length.
pub fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(s: f64, o: [f64; 3]) -> MeshData {
        let mut m = MeshData::default();
        for i in 0..8 {
            m.vertices.push([
                o[0] + s * f64::from(i & 1),
                o[1] + s * f64::from((i >> 1) & 1),
                o[2] + s * f64::from((i >> 2) & 1),
            ]);
        }
        m.faces = vec![vec![0, 2, 3, 1]];
        m.faces.push(vec![4, 5, 7, 6]);
        m
    }

    fn project(cam: &CameraSpec, p: [f64; 3], w: f64, h: f64) -> (f64, f64, f64) {
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let norm = |a: [f64; 3]| {
            let l = dot(a, a).sqrt();
            [a[0] / l, a[1] / l, a[2] / l]
        };
        let f = norm(sub(cam.target, cam.eye));
        let s = norm(cross(f, cam.up));
        let u = cross(s, f);
        let d = sub(p, cam.eye);
        let (x, y, z) = (dot(s, d), dot(u, d), -dot(f, d));
        let ProjectionSpec::Perspective { fov_deg } = cam.projection else {
            unreachable!()
        };
        let t = (fov_deg.to_radians() / 2.0).tan();
        let (xn, yn) = (x / (-z * t * w / h), y / (-z * t));
        ((xn + 1.0) * w / 2.0, (1.0 - yn) * h / 2.0, -z)
    }

    #[test]
    fn whole_model_in_frame_and_depth_range() {
        for (w, h) in [(400usize, 240usize), (128, 128), (100, 300)] {
            for m in [cube(2.0, [10.0, -3.0, 5.0]), cube(0.001, [0.0; 3])] {
                let cam = fit_camera(&m, w, h);
                assert!(cam.near > 0.0 && cam.far > cam.near);
                let mut extent = 0.0f64;
                for &p in &m.vertices {
                    let (x, y, z) = project(&cam, p, w as f64, h as f64);
                    assert!(z > cam.near && z < cam.far, "depth {z} in {cam:?}");
                    let (xn, yn) = (2.0 * x / w as f64 - 1.0, 1.0 - 2.0 * y / h as f64);
                    extent = extent.max(xn.abs()).max(yn.abs());
                }
                // The farthest vertex from the centre is at 80 % of the half-frame.
                assert!((extent - FILL).abs() < 1e-9, "extent {extent}");
            }
        }
    }

    #[test]
    fn degenerate_meshes_give_a_valid_camera() {
        let mut m = MeshData::default();
        let cam = fit_camera(&m, 400, 240);
        assert!(cam.near > 0.0 && cam.far > cam.near && cam.eye != cam.target);
        m.vertices = vec![[1.0, 2.0, 3.0]; 3];
        m.faces = vec![vec![0, 1, 2]];
        let cam = fit_camera(&m, 400, 240);
        assert_eq!(cam.target, [1.0, 2.0, 3.0]);
        assert!(cam.near > 0.0 && cam.far > cam.near);
    }
}
