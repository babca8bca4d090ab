//! Baseline (ii): the paper's P-buffer algorithm written the plain way in `f32`, a
//! `no_std` port of `host_tests/src/baseline/` (dashed mode only): a full-frame `f32`
//! depth buffer and a face-id buffer, faces rasterized as fan triangles with `f32` edge
//! functions over their bounding box, feature edges drawn with an `f32` DDA, each pixel
//! through the paper's test, the pattern looked up per pixel. The view-independent
//! edge list comes from the library's `EdgeAdjacency` (built once at boot, as the host
//! baseline builds its own once per mesh). Shared with the host test through this crate.

use pbuffer::mesh::{Mesh, MeshEdge};
use pbuffer::Pattern;

use crate::scenes::View;

pub type V3 = [f32; 3];

pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn dot(a: V3, b: V3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
/// Square root: micromath's estimate, refined by two Newton steps (deterministic on
/// every target: only IEEE basic operations).
pub fn sqrt(x: f32) -> f32 {
    if x <= 0.0 {
        return 0.0;
    }
    let mut y = micromath::F32Ext::sqrt(x);
    y = 0.5 * (y + x / y);
    0.5 * (y + x / y)
}
fn normalize(a: V3) -> V3 {
    let l = sqrt(dot(a, a));
    if l > 0.0 {
        [a[0] / l, a[1] / l, a[2] / l]
    } else {
        [0.0; 3]
    }
}
/// `floor` as an integer (saturating).
pub fn floor_i(x: f32) -> i32 {
    let i = x as i32;
    if (i as f32) > x {
        i - 1
    } else {
        i
    }
}
fn ceil_i(x: f32) -> i32 {
    -floor_i(-x)
}

/// The camera in `f32`: eye space and projection to (sx, sy, depth 0 near .. 1 far).
#[derive(Debug, Clone, Copy)]
pub struct Cam {
    pub eye: V3,
    s: V3,
    u: V3,
    f: V3,
    t: f32,
    aspect: f32,
    pub near: f32,
    pub far: f32,
    w: f32,
    h: f32,
}

impl Cam {
    pub fn new(v: &View, width: usize, height: usize) -> Self {
        let f = normalize(sub(v.target, v.eye));
        let s = normalize(cross(f, [0.0, 1.0, 0.0]));
        let u = cross(s, f);
        Cam {
            eye: v.eye,
            s,
            u,
            f,
            t: micromath::F32Ext::tan(v.fov_deg * (core::f32::consts::PI / 360.0)),
            aspect: width as f32 / height as f32,
            near: v.near,
            far: v.far,
            w: width as f32,
            h: height as f32,
        }
    }
    /// Eye space as (x, y, distance along the view direction).
    pub fn eye_space(&self, p: V3) -> V3 {
        let d = sub(p, self.eye);
        [dot(self.s, d), dot(self.u, d), dot(self.f, d)]
    }
    /// Screen x, y and normalized depth of an eye-space point within near..far.
    pub fn project(&self, e: V3) -> V3 {
        let k = 1.0 / (e[2] * self.t);
        let d = (1.0 / self.near - 1.0 / e[2]) / (1.0 / self.near - 1.0 / self.far);
        let (xn, yn) = (e[0] * k / self.aspect, e[1] * k);
        [(xn + 1.0) * self.w * 0.5, (1.0 - yn) * self.h * 0.5, d]
    }
}

/// Newell normal of face `f`.
pub fn newell(mesh: &Mesh<'_>, f: usize) -> V3 {
    let (verts, face) = (mesh.vertices(), mesh.face(f));
    let mut n = [0.0f32; 3];
    for k in 0..face.len() {
        let a = verts[face[k] as usize];
        let b = verts[face[(k + 1) % face.len()] as usize];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

/// Does face `f` (normal `n`) face the eye (perspective: n . (eye - centroid) > 0)?
pub fn facing(mesh: &Mesh<'_>, f: usize, n: V3, eye: V3) -> bool {
    let face = mesh.face(f);
    let mut c = [0.0f32; 3];
    for &v in face {
        let p = mesh.vertices()[v as usize];
        c = [c[0] + p[0], c[1] + p[1], c[2] + p[2]];
    }
    let k = 1.0 / face.len() as f32;
    dot(n, sub(eye, [c[0] * k, c[1] * k, c[2] * k])) > 0.0
}

const MAXP: usize = 24;

/// Clips an eye-space polygon to near <= distance <= far; returns the vertex count.
fn clip_polygon(poly: &mut [V3; MAXP], mut n: usize, near: f32, far: f32) -> usize {
    let mut tmp = [[0.0f32; 3]; MAXP];
    for (plane, keep_ge) in [(near, true), (far, false)] {
        let inside = |p: &V3| {
            if keep_ge {
                p[2] >= plane
            } else {
                p[2] <= plane
            }
        };
        if poly[..n].iter().all(inside) {
            continue;
        }
        let mut m = 0;
        for i in 0..n {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let (ia, ib) = (inside(&a), inside(&b));
            if ia && m < MAXP {
                tmp[m] = a;
                m += 1;
            }
            if ia != ib && m < MAXP {
                let t = (plane - a[2]) / (b[2] - a[2]);
                tmp[m] = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), plane];
                m += 1;
            }
        }
        poly[..m].copy_from_slice(&tmp[..m]);
        n = m;
        if n == 0 {
            return 0;
        }
    }
    n
}

/// The baseline's buffers: `P` = width x height pixels, `NB` packed frame bytes, `V`
/// vertices, `F` faces. Zero-initialised (a `static` of it is `.bss`).
#[derive(Debug)]
pub struct PlainBuffers<const P: usize, const NB: usize, const V: usize, const F: usize> {
    pub depth: [f32; P],
    pub ids: [u16; P],
    /// The picture, packed 1 bpp row-major MSB first (the `PackedFramebuffer` layout).
    pub frame: [u8; NB],
    pub eye_v: [V3; V],
    pub normals: [V3; F],
    pub facing: [bool; F],
}

impl<const P: usize, const NB: usize, const V: usize, const F: usize> PlainBuffers<P, NB, V, F> {
    pub const fn new() -> Self {
        Self {
            depth: [0.0; P],
            ids: [0; P],
            frame: [0; NB],
            eye_v: [[0.0; 3]; V],
            normals: [[0.0; 3]; F],
            facing: [false; F],
        }
    }

    /// View-independent set-up, once per mesh: the Newell normals.
    pub fn prepare(&mut self, mesh: &Mesh<'_>) {
        for (f, n) in self.normals.iter_mut().enumerate().take(mesh.face_count()) {
            *n = newell(mesh, f);
        }
    }

    /// Renders one frame (clear included) with dashed hidden lines, culling faces
    /// when `cull`.
    #[allow(clippy::too_many_arguments)]
    pub fn render(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &[MeshEdge],
        cull: bool,
        view: &View,
        width: usize,
        height: usize,
        pattern: &Pattern,
    ) {
        let cam = Cam::new(view, width, height);
        self.depth.fill(f32::INFINITY);
        self.ids.fill(0);
        self.frame.fill(0);
        for (e, &p) in self.eye_v.iter_mut().zip(mesh.vertices()) {
            *e = cam.eye_space(p);
        }
        for f in 0..mesh.face_count() {
            self.facing[f] = facing(mesh, f, self.normals[f], cam.eye);
        }
        let mut r = Raster {
            w: width,
            h: height,
            stride: width.div_ceil(8),
            depth: &mut self.depth,
            ids: &mut self.ids,
            frame: &mut self.frame,
        };
        // Pass 1: faces.
        let mut poly = [[0.0f32; 3]; MAXP];
        for f in 0..mesh.face_count() {
            if cull && !self.facing[f] {
                continue;
            }
            let face = mesh.face(f);
            let mut n = face.len().min(MAXP);
            for (slot, &v) in poly.iter_mut().zip(face) {
                *slot = self.eye_v[v as usize];
            }
            if !poly[..n]
                .iter()
                .all(|p| p[2] >= cam.near && p[2] <= cam.far)
            {
                n = clip_polygon(&mut poly, n, cam.near, cam.far);
            }
            if n < 3 {
                continue;
            }
            let mut scr = [[0.0f32; 3]; MAXP];
            for k in 0..n {
                scr[k] = cam.project(poly[k]);
            }
            for k in 1..n - 1 {
                r.triangle([scr[0], scr[k], scr[k + 1]], f as u16);
            }
        }
        // Pass 2: feature edges through the P-buffer test.
        let cos_crease = 0.866_025_4_f32; // cos 30 degrees
        for e in edges {
            let feature = if e.face_count == 2 {
                let (f0, f1) = (e.faces[0] as usize, e.faces[1] as usize);
                let (n0, n1) = (self.normals[f0], self.normals[f1]);
                let (l0, l1) = (sqrt(dot(n0, n0)), sqrt(dot(n1, n1)));
                l0 != 0.0
                    && l1 != 0.0
                    && (dot(n0, n1) < cos_crease * l0 * l1 || self.facing[f0] != self.facing[f1])
            } else {
                true
            };
            if !feature {
                continue;
            }
            let (mut p, mut q) = (self.eye_v[e.a as usize], self.eye_v[e.b as usize]);
            let mut ok = true;
            for (plane, keep_ge) in [(cam.near, true), (cam.far, false)] {
                let ins = |v: &V3| {
                    if keep_ge {
                        v[2] >= plane
                    } else {
                        v[2] <= plane
                    }
                };
                match (ins(&p), ins(&q)) {
                    (true, true) => {}
                    (false, false) => ok = false,
                    (ip, _) => {
                        let t = (plane - p[2]) / (q[2] - p[2]);
                        let m = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), plane];
                        if ip {
                            q = m;
                        } else {
                            p = m;
                        }
                    }
                }
            }
            if ok {
                r.edge(cam.project(p), cam.project(q), e.faces, pattern);
            }
        }
    }
}

struct Raster<'b> {
    w: usize,
    h: usize,
    stride: usize,
    depth: &'b mut [f32],
    ids: &'b mut [u16],
    frame: &'b mut [u8],
}

impl Raster<'_> {
    /// One screen triangle as interior pixels of face `id` (the paper's interior test).
    fn triangle(&mut self, tri: [V3; 3], id: u16) {
        let [p0, mut p1, mut p2] = tri;
        let area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
        if area == 0.0 || !area.is_finite() {
            return;
        }
        if area < 0.0 {
            core::mem::swap(&mut p1, &mut p2);
        }
        let area = area.abs();
        let min_x = p0[0].min(p1[0]).min(p2[0]);
        let max_x = p0[0].max(p1[0]).max(p2[0]);
        let min_y = p0[1].min(p1[1]).min(p2[1]);
        let max_y = p0[1].max(p1[1]).max(p2[1]);
        let x0 = ceil_i(min_x - 0.5).max(0);
        let x1 = floor_i(max_x - 0.5).min(self.w as i32 - 1);
        let y0 = ceil_i(min_y - 0.5).max(0);
        let y1 = floor_i(max_y - 0.5).min(self.h as i32 - 1);
        if x1 < x0 || y1 < y0 {
            return;
        }
        let edge = |a: V3, c: V3| {
            let (dx, dy) = (c[0] - a[0], c[1] - a[1]);
            let top_left = dy < 0.0 || (dy == 0.0 && dx > 0.0);
            (-dy, dx, dy * a[0] - dx * a[1], top_left)
        };
        let e = [edge(p1, p2), edge(p2, p0), edge(p0, p1)];
        let inv = 1.0 / area;
        let (da, db, dc) = (p0[2], p1[2], p2[2]);
        let ddx = (e[0].0 * da + e[1].0 * db + e[2].0 * dc) * inv;
        let ddy = (e[0].1 * da + e[1].1 * db + e[2].1 * dc) * inv;
        let dd0 = (e[0].2 * da + e[1].2 * db + e[2].2 * dc) * inv;
        let inside = |v: f32, tl: bool| v > 0.0 || (v == 0.0 && tl);
        for y in y0..=y1 {
            let cy = y as f32 + 0.5;
            let cx = x0 as f32 + 0.5;
            let mut w0 = e[0].0 * cx + e[0].1 * cy + e[0].2;
            let mut w1 = e[1].0 * cx + e[1].1 * cy + e[1].2;
            let mut w2 = e[2].0 * cx + e[2].1 * cy + e[2].2;
            let mut d = dd0 + ddx * cx + ddy * cy;
            let row = y as usize * self.w;
            for x in x0..=x1 {
                if inside(w0, e[0].3) && inside(w1, e[1].3) && inside(w2, e[2].3) {
                    let i = row + x as usize;
                    if d < self.depth[i] {
                        self.depth[i] = d;
                        self.ids[i] = id + 1;
                    }
                }
                w0 += e[0].0;
                w1 += e[1].0;
                w2 += e[2].0;
                d += ddx;
            }
        }
    }

    /// DDA along a screen segment, one pixel per centre along the major axis; each
    /// pixel goes through the paper's boundary-pixel test and the pattern.
    fn edge(&mut self, s0: V3, s1: V3, own: [u32; 2], pattern: &Pattern) {
        let eps = 1.0f32 / 16384.0;
        let (dx, dy) = (s1[0] - s0[0], s1[1] - s0[1]);
        let x_major = dx.abs() >= dy.abs();
        let (a0, a1, len) = if x_major {
            (s0[0], s1[0], dx)
        } else {
            (s0[1], s1[1], dy)
        };
        if len == 0.0 || !len.is_finite() {
            return;
        }
        let limit = if x_major { self.w } else { self.h } as i32;
        let lo = ceil_i(a0.min(a1) - 0.5).max(0);
        let hi = floor_i(a0.max(a1) - 0.5).min(limit - 1);
        if hi < lo {
            return;
        }
        let (minor0, dminor) = if x_major {
            (s0[1], dy / dx)
        } else {
            (s0[0], dx / dy)
        };
        let dd = (s1[2] - s0[2]) / len;
        let start = lo as f32 + 0.5 - a0;
        let mut m = minor0 + start * dminor;
        let mut d = s0[2] + start * dd;
        let other = if x_major { self.h } else { self.w } as i32;
        for a in lo..=hi {
            let mf = floor_i(m);
            m += dminor;
            let here = d;
            d += dd;
            if mf < 0 || mf >= other {
                continue;
            }
            let (x, y) = if x_major {
                (a as usize, mf as usize)
            } else {
                (mf as usize, a as usize)
            };
            let i = y * self.w + x;
            let id = self.ids[i];
            let mine = id != 0 && (u32::from(id - 1) == own[0] || u32::from(id - 1) == own[1]);
            let hidden = self.depth[i] < here - eps && !mine;
            // The paper's value_Pattern(x, y), looked up per pixel.
            if !hidden || pattern.passes(x as u32, y as u32) {
                self.frame[y * self.stride + x / 8] |= 0x80 >> (x % 8);
            }
        }
    }
}
