//! f64 vector arithmetic on mesh vertices: positions, area vectors, planes.

use pbuffer::Mesh;

pub(super) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(super) fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(super) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(super) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(super) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

pub(super) fn pos(mesh: &Mesh<'_>, i: u32) -> [f64; 3] {
    mesh.vertices()[i as usize].map(f64::from)
}

/// Newell normal (twice the area vector) of a face, in f64.
pub(super) fn area_vector(mesh: &Mesh<'_>, f: usize) -> [f64; 3] {
    let c = mesh.face(f);
    let p0 = pos(mesh, c[0]);
    c[1..].windows(2).fold([0.0; 3], |n, w| {
        add(n, cross(sub(pos(mesh, w[0]), p0), sub(pos(mesh, w[1]), p0)))
    })
}

pub(super) fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = norm(v);
    v.map(|c| c / n)
}

/// The plane of a polygon: unit normal and a point.
pub(super) fn plane_of(points: &[[f64; 3]]) -> Option<([f64; 3], [f64; 3])> {
    let p0 = points[0];
    let n = points[1..]
        .windows(2)
        .fold([0.0; 3], |n, w| add(n, cross(sub(w[0], p0), sub(w[1], p0))));
    (norm(n) > 1e-12).then(|| (unit(n), p0))
}
