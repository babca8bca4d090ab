//! Procedural test scenes for the 3-D pipeline: closed meshes (but the open `cyclic`
//! sticks), faces counter-clockwise seen from outside, and a three-quarter camera that
//! sees each whole.

use crate::fit::fit_camera;
use crate::frame::{CameraSpec, MeshData, ProjectionSpec};

/// A named scene: a mesh and how its camera is chosen. The one scene type of the
/// inputs: the procedural scenes here, and the models `report` loads.
#[derive(Clone, Debug)]
pub struct Scene {
    pub name: String,
    pub mesh: MeshData,
    pub framing: Framing,
}

/// How a [`Scene`]'s default camera is chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Framing {
    /// The procedural scenes' three-quarter view ([`three_quarter_camera`]).
    ThreeQuarter,
    /// A model's view, as `render --fit` frames it ([`fit_camera`], perspective).
    Fit,
}

impl Scene {
    /// A procedural scene (three-quarter view).
    fn procedural(name: &str, mesh: MeshData) -> Self {
        Scene {
            name: name.into(),
            mesh,
            framing: Framing::ThreeQuarter,
        }
    }

    /// The default camera of this scene; `ortho` asks the three-quarter view for an
    /// orthographic projection (a fitted model's view is always perspective).
    pub fn camera(&self, width: usize, height: usize, ortho: bool) -> CameraSpec {
        match self.framing {
            Framing::ThreeQuarter => three_quarter_camera(&self.mesh, width, height, ortho),
            Framing::Fit => fit_camera(&self.mesh, width, height),
        }
    }
}

/// All procedural scenes.
pub fn all_scenes() -> Vec<Scene> {
    vec![
        Scene::procedural("cube", cube()),
        Scene::procedural("boxes", boxes()),
        Scene::procedural("icosphere", icosphere(2)),
        Scene::procedural("torus", torus(24, 12, 1.0, 0.4)),
        Scene::procedural("gear", gear(12, 0.8, 1.0, 0.3)),
        Scene::procedural("frame", frame()),
        Scene::procedural("cyclic", cyclic_sticks()),
        Scene::procedural("coplanar", coplanar_boxes()),
    ]
}

/// A camera looking at the bounding-box centre from the front-right, above, along
/// (1, 0.7, 1.6); the bounding sphere fills 90 % of the vertical (or, if narrower,
/// horizontal) field of view of 40 degrees; orthographic: half-height = 1.1 radius
/// (scaled up when the frame is taller than wide). Near/far bracket the sphere.
pub fn three_quarter_camera(
    mesh: &MeshData,
    width: usize,
    height: usize,
    ortho: bool,
) -> CameraSpec {
    let (c, r) = all_vertex_bounds(mesh);
    let aspect = width as f64 / height.max(1) as f64;
    let dir = [1.0f64, 0.7, 1.6];
    let n = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
    let fov = 40.0f64;
    let tan_half = (fov.to_radians() / 2.0).tan() * aspect.min(1.0);
    let dist = r / (0.9 * tan_half).atan().sin();
    let eye = [
        c[0] + dist * dir[0] / n,
        c[1] + dist * dir[1] / n,
        c[2] + dist * dir[2] / n,
    ];
    CameraSpec {
        eye,
        target: c,
        up: [0.0, 1.0, 0.0],
        projection: if ortho {
            ProjectionSpec::Orthographic {
                half_height: 1.1 * r / aspect.min(1.0),
            }
        } else {
            ProjectionSpec::Perspective { fov_deg: fov }
        },
        near: (dist - 1.5 * r).max(1e-3 * dist),
        far: dist + 1.5 * r,
    }
}

/// Bounding-box centre and the radius of the sphere about it holding all vertices.
pub fn all_vertex_bounds(mesh: &MeshData) -> ([f64; 3], f64) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &mesh.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if mesh.vertices.is_empty() {
        return ([0.0; 3], 1.0);
    }
    let c = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    let r = mesh
        .vertices
        .iter()
        .map(|p| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt())
        .fold(0.0, f64::max);
    (c, if r > 0.0 { r } else { 1.0 })
}

/// Appends a box of half extents `h` centred at `c`, rotated by `yaw` about Y and then
/// `pitch` about X (radians); 6 quads, counter-clockwise from outside.
pub fn add_box(m: &mut MeshData, c: [f64; 3], h: [f64; 3], yaw: f64, pitch: f64) {
    let base = m.vertices.len() as u32;
    let (sy, cy) = yaw.sin_cos();
    let (sp, cp) = pitch.sin_cos();
    for k in 0..8 {
        let p = [
            if k & 1 != 0 { h[0] } else { -h[0] },
            if k & 2 != 0 { h[1] } else { -h[1] },
            if k & 4 != 0 { h[2] } else { -h[2] },
        ];
        // yaw about Y
        let q = [cy * p[0] + sy * p[2], p[1], -sy * p[0] + cy * p[2]];
        // pitch about X
        let r = [q[0], cp * q[1] - sp * q[2], sp * q[1] + cp * q[2]];
        m.vertices.push([c[0] + r[0], c[1] + r[1], c[2] + r[2]]);
    }
    for f in [
        [0, 4, 6, 2], // -x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // -y
        [2, 6, 7, 3], // +y
        [0, 2, 3, 1], // -z
        [4, 5, 7, 6], // +z
    ] {
        m.faces.push(f.iter().map(|&i| base + i).collect());
    }
}

/// The unit cube [-1, 1]^3 as 6 quads.
pub fn cube() -> MeshData {
    let mut m = MeshData::default();
    add_box(&mut m, [0.0; 3], [1.0; 3], 0.0, 0.0);
    m
}

/// Boxes in front of boxes: a floor slab, axis-aligned and rotated boxes, two of them
/// interpenetrating, one partly hidden behind another.
pub fn boxes() -> MeshData {
    let mut m = MeshData::default();
    add_box(&mut m, [0.0, -1.1, 0.0], [2.6, 0.1, 2.1], 0.0, 0.0);
    add_box(&mut m, [-1.0, -0.3, 0.6], [0.6, 0.7, 0.5], 0.0, 0.0);
    add_box(&mut m, [-0.4, -0.5, 0.9], [0.5, 0.45, 0.55], 0.5, 0.0); // into the previous
    add_box(&mut m, [1.2, 0.1, -0.9], [0.7, 1.1, 0.6], -0.3, 0.0); // behind
    add_box(&mut m, [0.9, -0.55, 1.1], [0.35, 0.3, 0.35], 0.9, 0.35);
    add_box(&mut m, [-1.5, 0.2, -1.3], [0.45, 0.95, 0.45], 0.2, 0.0);
    m
}

/// Three sticks (flat quads, both sides seen) that overlap cyclically when seen
/// from +z: each lies over the next and under the previous, so no order of the
/// three faces is right everywhere.
pub fn cyclic_sticks() -> MeshData {
    let mut m = MeshData::default();
    for k in 0..3 {
        let a = k as f64 * std::f64::consts::TAU / 3.0;
        let (s, c) = a.sin_cos();
        let rot = |x: f64, y: f64| [c * x - s * y, s * x + c * y];
        let base = m.vertices.len() as u32;
        // Along x from -1.4 to 1.4, 0.35 off the centre, falling 0.5 in z.
        for (x, y) in [(-1.4, -0.55), (1.4, -0.55), (1.4, -0.2), (-1.4, -0.2)] {
            let [px, py] = rot(x, y);
            m.vertices.push([px, py, -0.18 * x]);
        }
        m.faces.push((base..base + 4).collect());
    }
    m
}

/// Two boxes side by side whose top faces lie in one plane and overlap, on a
/// slab whose top is coplanar with neither: coplanar faces need a deterministic
/// winner (the lower face index, CONVENTIONS.md).
pub fn coplanar_boxes() -> MeshData {
    let mut m = MeshData::default();
    add_box(&mut m, [0.0, -1.1, 0.0], [1.6, 0.1, 1.4], 0.0, 0.0);
    add_box(&mut m, [-0.35, -0.4, 0.0], [0.6, 0.6, 0.6], 0.0, 0.0);
    add_box(&mut m, [0.35, -0.4, 0.3], [0.6, 0.6, 0.5], 0.0, 0.0);
    m
}

/// An icosphere of radius 1 (subdivision level `level`: 20 * 4^level triangles).
pub fn icosphere(level: u32) -> MeshData {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut v: Vec<[f64; 3]> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let unit = |p: [f64; 3]| {
        let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        [p[0] / l, p[1] / l, p[2] / l]
    };
    for p in &mut v {
        *p = unit(*p);
    }
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..level {
        let mut mid = std::collections::HashMap::new();
        let mut midpoint = |a: u32, b: u32, v: &mut Vec<[f64; 3]>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (v[a as usize], v[b as usize]);
                v.push(unit([p[0] + q[0], p[1] + q[1], p[2] + q[2]]));
                v.len() as u32 - 1
            })
        };
        let mut nf = Vec::with_capacity(f.len() * 4);
        for [a, b, c] in f {
            let ab = midpoint(a, b, &mut v);
            let bc = midpoint(b, c, &mut v);
            let ca = midpoint(c, a, &mut v);
            nf.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = nf;
    }
    MeshData {
        vertices: v,
        faces: f.into_iter().map(|t| t.to_vec()).collect(),
    }
}

/// A torus around the Y axis: `nu` segments around, `nv` around the tube; quads.
pub fn torus(nu: u32, nv: u32, big_r: f64, small_r: f64) -> MeshData {
    let mut m = MeshData::default();
    for i in 0..nu {
        let u = std::f64::consts::TAU * f64::from(i) / f64::from(nu);
        for j in 0..nv {
            let v = std::f64::consts::TAU * f64::from(j) / f64::from(nv);
            let rr = big_r + small_r * v.cos();
            m.vertices
                .push([rr * u.cos(), small_r * v.sin(), -rr * u.sin()]);
        }
    }
    let idx = |i: u32, j: u32| (i % nu) * nv + (j % nv);
    for i in 0..nu {
        for j in 0..nv {
            // u runs counter-clockwise seen from +Y, v outward-up: (u, v) -> outward normal
            m.faces.push(vec![
                idx(i, j),
                idx(i + 1, j),
                idx(i + 1, j + 1),
                idx(i, j + 1),
            ]);
        }
    }
    m
}

/// An open cylinder around the Y axis (no caps): `n` quads (or, `split`, two
/// triangles each) of radius `r` from y = 0 to y = `h`, their fronts outward.
/// Open, so both sides are drawn.
pub fn open_cylinder(n: u32, r: f64, h: f64, split: bool) -> MeshData {
    cup(n, r, r, h, split)
}

/// A cup: an open cone frustum around the Y axis (no caps), radius `r_bottom` at
/// y = 0 and `r_top` at y = `h`, `n` quads (or, `split`, two triangles each), their
/// fronts outward. Both rims are boundary edges; open, so both sides are drawn.
pub fn cup(n: u32, r_bottom: f64, r_top: f64, h: f64, split: bool) -> MeshData {
    let mut m = MeshData::default();
    for i in 0..n {
        let u = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        m.vertices
            .push([r_bottom * u.cos(), 0.0, -r_bottom * u.sin()]);
        m.vertices.push([r_top * u.cos(), h, -r_top * u.sin()]);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        if split {
            m.faces.push(vec![2 * i, 2 * j, 2 * j + 1]);
            m.faces.push(vec![2 * i, 2 * j + 1, 2 * i + 1]);
        } else {
            m.faces.push(vec![2 * i, 2 * j, 2 * j + 1, 2 * i + 1]);
        }
    }
    m
}

/// A gear: a profile of `teeth` trapezoid teeth between radii `r_root` and `r_tip`,
/// extruded along Z by `thickness`; the two caps are single concave n-gons.
pub fn gear(teeth: u32, r_root: f64, r_tip: f64, thickness: f64) -> MeshData {
    let mut profile = Vec::new();
    for k in 0..teeth {
        let a0 = std::f64::consts::TAU * f64::from(k) / f64::from(teeth);
        let step = std::f64::consts::TAU / f64::from(teeth);
        for (frac, r) in [(0.0, r_root), (0.2, r_tip), (0.45, r_tip), (0.65, r_root)] {
            let a = a0 + frac * step;
            profile.push([r * a.cos(), r * a.sin()]);
        }
    }
    let n = profile.len() as u32;
    let h = thickness / 2.0;
    let mut m = MeshData::default();
    for p in &profile {
        m.vertices.push([p[0], p[1], h]); // front: 0..n
    }
    for p in &profile {
        m.vertices.push([p[0], p[1], -h]); // back: n..2n
    }
    // The profile is counter-clockwise seen from +Z.
    m.faces.push((0..n).collect());
    m.faces.push((0..n).rev().map(|i| n + i).collect());
    for i in 0..n {
        let j = (i + 1) % n;
        m.faces.push(vec![n + i, n + j, j, i]);
    }
    m
}

/// A box with a square through-hole along Z (a picture frame): outer half size 1,
/// inner 0.5, half thickness 0.3; 16 quads.
pub fn frame() -> MeshData {
    let (o, i, t) = (1.0, 0.5, 0.3);
    let mut m = MeshData::default();
    // Square corners counter-clockwise seen from +Z.
    let sq = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
    // 0..4 outer front, 4..8 inner front, 8..12 outer back, 12..16 inner back
    for (s, z) in [(o, t), (i, t), (o, -t), (i, -t)] {
        for c in sq {
            m.vertices.push([s * c[0], s * c[1], z]);
        }
    }
    for k in 0..4u32 {
        let l = (k + 1) % 4;
        // front ring (+Z): outer k, outer l, inner l, inner k
        m.faces.push(vec![k, l, 4 + l, 4 + k]);
        // back ring (-Z): reversed
        m.faces.push(vec![8 + k, 12 + k, 12 + l, 8 + l]);
        // outer side: facing outward
        m.faces.push(vec![8 + k, 8 + l, l, k]);
        // inner side: facing the hole's axis
        m.faces.push(vec![12 + k, 4 + k, 4 + l, 12 + l]);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// Closed, consistently oriented (every directed edge once, its reverse once), and
    /// outward (positive signed volume).
    fn check_closed_outward(m: &MeshData) {
        let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
        for f in &m.faces {
            for k in 0..f.len() {
                *directed.entry((f[k], f[(k + 1) % f.len()])).or_default() += 1;
            }
        }
        for (&(a, b), &c) in &directed {
            assert_eq!(c, 1, "edge {a}-{b} used {c} times in one direction");
            assert_eq!(directed.get(&(b, a)), Some(&1), "edge {a}-{b} has no twin");
        }
        // Signed volume by the divergence theorem over fan triangles.
        let mut vol = 0.0;
        for f in &m.faces {
            let p0 = m.vertices[f[0] as usize];
            for k in 1..f.len() - 1 {
                let (a, b) = (m.vertices[f[k] as usize], m.vertices[f[k + 1] as usize]);
                vol += p0[0] * (a[1] * b[2] - a[2] * b[1]) - p0[1] * (a[0] * b[2] - a[2] * b[0])
                    + p0[2] * (a[0] * b[1] - a[1] * b[0]);
            }
        }
        assert!(vol > 0.0, "volume {vol}");
    }

    #[test]
    fn scenes_are_closed_and_outward() {
        for s in all_scenes() {
            if s.name == "cyclic" {
                // Three open sticks, seen from both sides: nothing to close.
                assert_eq!(s.mesh.faces.len(), 3);
            } else if s.name == "boxes" || s.name == "coplanar" {
                // several closed boxes: check each box (24 faces each... 6 faces each)
                for b in 0..s.mesh.faces.len() / 6 {
                    let mut m = s.mesh.clone();
                    m.faces = m.faces[b * 6..b * 6 + 6].to_vec();
                    check_closed_outward(&m);
                }
            } else {
                check_closed_outward(&s.mesh);
            }
        }
        assert_eq!(icosphere(2).faces.len(), 320);
        assert_eq!(torus(24, 12, 1.0, 0.4).faces.len(), 288);
        assert_eq!(frame().faces.len(), 16);
    }

    #[test]
    fn cameras_see_every_vertex() {
        use crate::reference3d::Camera;
        for s in all_scenes() {
            for (w, h) in [(400, 240), (128, 64), (64, 128)] {
                for ortho in [false, true] {
                    let spec = s.camera(w, h, ortho);
                    let cam = Camera::new(&spec, w, h).unwrap();
                    for &p in &s.mesh.vertices {
                        let e = cam.to_eye(p);
                        assert!(-e[2] > spec.near && -e[2] < spec.far);
                        let (x, y) = cam.project(e);
                        assert!(
                            x > 0.0 && x < w as f64 && y > 0.0 && y < h as f64,
                            "{}",
                            s.name
                        );
                    }
                }
            }
        }
    }
}
