//! A local origin for scenes far from the world's origin (issue 24, item 4): OBJ
//! coordinates are read in `f64`, and a scene seen from an eye far from the origin
//! compared with the view's size (geographic or CAD world coordinates) is moved, in
//! `f64`, so that the eye is the origin (the target moved with it), before anything
//! becomes `f32` or fixed point. The picture is the same (the
//! camera sees the same scene); only the rounding is local. A perspective scene
//! that still reaches very far from the eye is then brought nearer along its rays
//! ([`warp_far_depths`]), with the same picture. The library documents
//! the same practice for meshes it is handed (README, "World coordinates far from
//! the origin").

use crate::frame::{CameraSpec, MeshData, ProjectionSpec};
use crate::reference3d::vector::{cross, dot, norm, sub};

/// How far (in multiples of the eye's distance to its target) the eye may lie from
/// the origin before the scene is moved: 64 costs `f32` six of its 24 bits there.
const FAR_FACTOR: f64 = 64.0;

/// The origin to move the scene to, when it needs one: the eye, when it lies more
/// than `FAR_FACTOR` times its distance to the target from the world's origin.
/// Under perspective the precision a frame needs falls with the distance from the
/// eye, and positions relative to the eye in `f32` keep exactly that: a box a few
/// units away gets 2^-20 of a unit, a ground corner 1e9 away 2^7. (The centre of
/// the drawn geometry's bounding box would do for a scene of one size; a ground
/// reaching 1e9 inside far pulls that centre 1e9 away from the boxes beside the
/// eye.) `None` when the scene is near enough (it is left as it is, bit for bit).
pub fn local_origin(cam: &CameraSpec) -> Option<[f64; 3]> {
    let view = norm(sub(cam.target, cam.eye));
    let far = cam.eye.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    (far > FAR_FACTOR * view && cam.eye.iter().all(|c| c.is_finite())).then_some(cam.eye)
}

/// The scene moved to its local origin (see [`local_origin`]) and its huge faces
/// cut (see [`cut_huge_faces`]), or `None` when it stays as it is.
pub fn localised(mesh: &MeshData, cam: &CameraSpec, aspect: f64) -> Option<(MeshData, CameraSpec)> {
    let origin = local_origin(cam);
    let (mut moved, mut cam) = (mesh.clone(), *cam);
    if let Some(o) = origin {
        let shift = |p: [f64; 3]| std::array::from_fn(|i| p[i] - o[i]);
        moved.vertices.iter_mut().for_each(|v| *v = shift(*v));
        (cam.eye, cam.target) = (shift(cam.eye), shift(cam.target));
    }
    let cut = cut_huge_faces(&mut moved, &cam, aspect);
    let warped = warp_far_depths(&mut moved, &mut cam);
    (origin.is_some() || cut || warped).then_some((moved, cam))
}

/// Brings a perspective scene that still reaches farther than [`HUGE`] near
/// distances from the eye (a ground inside a far plane of 1e10) within `2 HUGE`
/// near distances, with the same picture: every point `p` at depth `z` in front of
/// the eye (along the view axis) moves along its own ray from the eye to
/// `eye + (p - eye) / (1 + z / Z)`, `Z = 2 HUGE near`, and near and far with it.
/// This map is projective (planes stay planes, edges stay straight), keeps every
/// ray from the eye and the order of depths along it, and adds the constant `1 / Z`
/// to nearness `1 / z`: what each pixel sees, the facing of every face and the
/// silhouettes are the same, and the fixed-point engines' depth (affine in
/// nearness, fitted to the drawn range) steps as before. What it does not keep is
/// angles: a crease within about `z / Z` radians of the crease angle may change
/// kind. True when the scene was warped. (Points behind the eye lie within
/// `HUGE` near distances after `cut_huge_faces`, where the factor stays below 2.)
pub fn warp_far_depths(mesh: &mut MeshData, cam: &mut CameraSpec) -> bool {
    if !matches!(cam.projection, ProjectionSpec::Perspective { .. }) {
        return false;
    }
    let Some(fwd) = unit(sub(cam.target, cam.eye)) else {
        return false;
    };
    let mut used = vec![false; mesh.vertices.len()];
    mesh.faces
        .iter()
        .flatten()
        .for_each(|&v| used[v as usize] = true);
    let reach = |p: &[f64; 3]| norm(sub(*p, cam.eye));
    let huge = mesh
        .vertices
        .iter()
        .zip(&used)
        .any(|(p, &u)| u && reach(p) > HUGE * cam.near);
    if !huge {
        return false;
    }
    let z0 = 2.0 * HUGE * cam.near;
    let eye = cam.eye;
    let warp = |p: [f64; 3]| -> [f64; 3] {
        let d = sub(p, eye);
        let k = 1.0 / (1.0 + dot(fwd, d) / z0).max(0.5);
        std::array::from_fn(|i| eye[i] + k * d[i])
    };
    mesh.vertices.iter_mut().for_each(|p| *p = warp(*p));
    cam.target = warp(cam.target);
    let depth = |z: f64| z / (1.0 + z / z0);
    (cam.near, cam.far) = (depth(cam.near), depth(cam.far));
    true
}

/// A face reaching farther from the eye than `HUGE` near distances: `f32` places
/// its corners there to within `HUGE 2^-24` near distances, which misplaces its
/// plane by as much where it passes the eye.
const HUGE: f64 = 65536.0;

/// Cuts, in `f64`, every face that reaches farther than [`HUGE`] near distances from
/// the eye to the part of it inside a widened view volume: between `near / 2` and
/// `2 far` in front of the eye, and within twice the view's extent sideways (for a
/// frame of aspect `aspect`, width over height). The corners `f32` then sees are
/// where the frame needs them, and every cut edge lies outside the view volume, so
/// none is ever drawn. A cut point of an edge is computed from its lower-numbered
/// end and shared by every face with that edge, so the cut mesh stays welded; faces
/// keep their indices (a face wholly outside is left as it is: the library clips it
/// away). True when any face was cut.
pub fn cut_huge_faces(mesh: &mut MeshData, cam: &CameraSpec, aspect: f64) -> bool {
    let dir = sub(cam.target, cam.eye);
    let (Some(fwd), Some(right)) = (unit(dir), unit(cross(dir, cam.up))) else {
        return false;
    };
    let up = cross(right, fwd);
    let reach = |p: [f64; 3]| norm(sub(p, cam.eye));
    // Planes (n, c): inside where n . (p - eye) + c >= 0.
    let mut planes = vec![(fwd, -0.5 * cam.near), (fwd.map(|c| -c), 2.0 * cam.far)];
    let aspect = aspect.max(1e-6);
    for (axis, extent) in [(right, aspect), (up, 1.0)] {
        for sign in [1.0, -1.0] {
            let lean = axis.map(|c| -sign * c);
            planes.push(match cam.projection {
                ProjectionSpec::Perspective { fov_deg } => {
                    let s = 2.0 * extent * (0.5 * fov_deg.to_radians()).tan();
                    (std::array::from_fn(|i| s * fwd[i] + lean[i]), 0.0)
                }
                ProjectionSpec::Orthographic { half_height } => (lean, 2.0 * extent * half_height),
            });
        }
    }
    let mut cuts = std::collections::HashMap::<(u32, u32, usize), u32>::new();
    let mut any = false;
    for f in 0..mesh.faces.len() {
        let huge = mesh.faces[f]
            .iter()
            .any(|&v| reach(mesh.vertices[v as usize]) > HUGE * cam.near);
        if !huge {
            continue;
        }
        let mut poly = mesh.faces[f].clone();
        for (k, &(n, c)) in planes.iter().enumerate() {
            let side = |v: u32, m: &MeshData| dot(n, sub(m.vertices[v as usize], cam.eye)) + c;
            let inside: Vec<bool> = poly.iter().map(|&v| side(v, mesh) >= 0.0).collect();
            if inside.iter().all(|&i| i) || !inside.iter().any(|&i| i) {
                continue;
            }
            let mut out = Vec::new();
            for i in 0..poly.len() {
                let j = (i + 1) % poly.len();
                let (a, b) = (poly[i], poly[j]);
                if inside[i] {
                    out.push(a);
                }
                if inside[i] != inside[j] {
                    let key = (a.min(b), a.max(b), k);
                    let cut = *cuts.entry(key).or_insert_with(|| {
                        let (p, q) = (key.0, key.1);
                        let (sp, sq) = (side(p, mesh), side(q, mesh));
                        let t = sp / (sp - sq);
                        let (pp, pq) = (mesh.vertices[p as usize], mesh.vertices[q as usize]);
                        mesh.vertices
                            .push(std::array::from_fn(|i| pp[i] + t * (pq[i] - pp[i])));
                        (mesh.vertices.len() - 1) as u32
                    });
                    out.push(cut);
                }
            }
            poly = out;
            any = true;
        }
        mesh.faces[f] = poly;
    }
    if any {
        // Corners no face uses any more would still set the fixed-point scale (the
        // largest coordinate): moved onto a corner in use (they draw nothing).
        let mut used = vec![false; mesh.vertices.len()];
        mesh.faces
            .iter()
            .flatten()
            .for_each(|&v| used[v as usize] = true);
        if let Some(&keep) = mesh.faces.iter().flatten().next() {
            let spot = mesh.vertices[keep as usize];
            for (v, p) in mesh.vertices.iter_mut().enumerate() {
                if !used[v] && reach(*p) > HUGE * cam.near {
                    *p = spot;
                }
            }
        }
    }
    any
}

fn unit(a: [f64; 3]) -> Option<[f64; 3]> {
    let len = norm(a);
    (len > 0.0 && len.is_finite()).then(|| a.map(|c| c / len))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam(eye: [f64; 3], target: [f64; 3]) -> CameraSpec {
        CameraSpec {
            eye,
            target,
            up: [0.0, 1.0, 0.0],
            projection: ProjectionSpec::Perspective { fov_deg: 40.0 },
            near: 0.1,
            far: 1000.0,
        }
    }

    fn box_at(c: [f64; 3]) -> MeshData {
        MeshData {
            vertices: vec![
                [c[0] - 1.0, c[1] - 1.0, c[2]],
                [c[0] + 1.0, c[1] - 1.0, c[2]],
                [c[0] + 1.0, c[1] + 1.0, c[2]],
            ],
            faces: vec![vec![0, 1, 2]],
        }
    }

    #[test]
    fn a_scene_near_the_origin_stays_put() {
        let m = box_at([3.0, 0.0, 0.0]);
        let view = cam([3.0, 0.0, 10.0], [3.0, 0.0, 0.0]);
        assert_eq!(local_origin(&view), None);
        assert!(
            localised(&m, &view, 1.0).is_none(),
            "nothing huge to cut either"
        );
    }

    #[test]
    fn a_scene_far_away_moves_so_that_the_eye_is_the_origin() {
        let c = [1e7, -2e7, 3e7];
        let m = box_at(c);
        let eye = [c[0], c[1], c[2] + 10.0];
        let (moved, cam) = localised(&m, &cam(eye, c), 1.0).expect("moved");
        assert_eq!(moved.vertices[0], [-1.0, -1.0, -10.0]);
        assert_eq!(cam.eye, [0.0; 3]);
        assert_eq!(cam.target, [0.0, 0.0, -10.0]);
    }

    #[test]
    fn a_far_reaching_scene_is_warped_along_its_rays_with_the_same_picture() {
        let mut m = MeshData {
            vertices: vec![
                [-1e9, -1.0, -1e9],
                [1e9, -1.0, -1e9],
                [0.0, -1.0, -2.0],
                [0.5, 0.0, -3.0],
            ],
            faces: vec![vec![0, 1, 2], vec![0, 1, 3]],
        };
        let before = m.clone();
        let mut view = cam([0.0; 3], [0.0, 0.0, -1.0]);
        view.far = 1e10;
        assert!(warp_far_depths(&mut m, &mut view));
        let z0 = 2.0 * HUGE * 0.1;
        for (p, q) in before.vertices.iter().zip(&m.vertices) {
            // Same ray from the eye (the origin), same order of depths, within Z.
            let k = q[2] / p[2];
            assert!(k > 0.0 && k <= 1.0, "{p:?} -> {q:?}");
            assert!((q[0] - k * p[0]).abs() <= 1e-9 * p[0].abs().max(1.0));
            assert!(-q[2] < z0);
        }
        assert!(-m.vertices[2][2] < -m.vertices[3][2]);
        assert!(view.far < z0 && (view.near - 0.1).abs() < 1e-6);
        // A scene within reach is left as it is.
        let mut near = before.clone();
        near.vertices.truncate(4);
        near.vertices[0] = [-1.0, -1.0, -5.0];
        near.vertices[1] = [1.0, -1.0, -5.0];
        assert!(!warp_far_depths(
            &mut near,
            &mut cam([0.0; 3], [0.0, 0.0, -1.0])
        ));
    }
}
