//! The "plain" baseline: the P-buffer algorithm of Yuan & Sun (Computers & Graphics
//! 24(3), 2000, appendix pseudocode; ../shared/seeds/000_535f0dd2467ca08a.txt) written
//! the obvious way in `f32`, to measure the library against.
//!
//! * A full-frame `f32` depth buffer (and a face-id buffer, needed for `--ids` and for
//!   "other than the edge's own faces"), a byte per pixel for the picture.
//! * Faces are rasterized as fan triangles with `f32` edge functions over their bounding
//!   box (top-left rule on pixel centres, incremental along a row), depth interpolated
//!   as a plane in screen space (normalized so that 0 = near, 1 = far; `1/z` under
//!   perspective, which is affine in screen space).
//! * Feature edges (boundary, non-manifold, crease, silhouette; vertices welded by
//!   bit-identical coordinates) are drawn with an `f32` DDA, one pixel per centre along
//!   the major axis, depth interpolated along the line.
//! * Each pixel goes through the paper's `this_Algorithm`: a nearer interior pixel
//!   updates the depth buffer and clears the picture where the pattern blocks; a
//!   boundary (edge) pixel is drawn when it is not behind, and where
//!   `value_Pattern(x, y) = pattern[x % l][y % l]` passes when it is.
//!
//! Deliberate simplifications against ../shared/CONVENTIONS.md (the baseline need not be
//! exact): coverage of a face is the union of its fan triangles, not their parity
//! (identical for convex faces); `f32` everywhere, no snapping; an edge pixel is hidden
//! when the depth there is nearer by more than 2^-14 of the near-far range and the face
//! there is not one of the edge's own faces (the paper has no such test; without it
//! silhouettes self-hide); edge pixels do not write depth, so all faces are processed
//! before all edges, which gives the same picture as the paper's object order.
//! Camera conventions, clipping (near/far, polygons clipped, never dropped whole),
//! culling and feature-edge rules are those of CONVENTIONS.md.
//!
//! Surfaces modes (not part of the paper): visible faces are set pixels, edges clear them.

use std::collections::HashMap;

use crate::frame::{CameraSpec, CullSpec, Frame, MeshData, ModeSpec, ProjectionSpec, RenderSpec};

/// The pattern as the paper keeps it: `pattern[x % l][y % l]`, a table of 0/1
/// (`l` x `l'` for a `l` x `l'` pattern), filled from the library's `Pattern` of the
/// same name.
pub struct PatternTable {
    w: usize,
    h: usize,
    /// `bits[x * h + y]`.
    bits: Vec<u8>,
}

impl PatternTable {
    /// The table of the library pattern `name` (`None` if the library has none).
    pub fn by_name(name: &str) -> Option<Self> {
        let p = pbuffer::Pattern::by_name(name)?;
        let (w, h) = (
            usize::from(p.width()).max(1),
            usize::from(p.height()).max(1),
        );
        let mut bits = vec![0u8; w * h];
        for x in 0..w {
            for y in 0..h {
                bits[x * h + y] = u8::from(p.passes(x as u32, y as u32));
            }
        }
        Some(Self { w, h, bits })
    }

    /// The paper's `value_Pattern(x, y)`: 1 = pass, 0 = block.
    #[inline]
    pub fn value(&self, x: usize, y: usize) -> u8 {
        self.bits[(x % self.w) * self.h + y % self.h]
    }
}

type V3 = [f32; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V3, b: V3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn normalize(a: V3) -> V3 {
    let l = dot(a, a).sqrt();
    if l > 0.0 {
        [a[0] / l, a[1] / l, a[2] / l]
    } else {
        [0.0; 3]
    }
}
fn to32(p: [f64; 3]) -> V3 {
    [p[0] as f32, p[1] as f32, p[2] as f32]
}

/// The camera in f32: eye-space transform and projection to (sx, sy, depth in [0, 1]).
struct Cam {
    eye: V3,
    s: V3,
    u: V3,
    f: V3,
    persp: bool,
    /// Perspective: tan(fov / 2); orthographic: the half-height.
    t: f32,
    aspect: f32,
    near: f32,
    far: f32,
    w: f32,
    h: f32,
}

impl Cam {
    fn new(c: &CameraSpec, width: usize, height: usize) -> Self {
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
    fn to_eye(&self, p: V3) -> V3 {
        let d = sub(p, self.eye);
        [dot(self.s, d), dot(self.u, d), dot(self.f, d)]
    }
    /// Screen x, y and normalized depth (0 near, 1 far) of an eye-space point with
    /// near <= distance <= far.
    fn project(&self, e: V3) -> [f32; 3] {
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
fn clip_polygon(poly: &[V3], near: f32, far: f32, out: &mut Vec<V3>, tmp: &mut Vec<V3>) {
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

/// The buffers of the paper plus the id buffer.
struct Buffers {
    w: usize,
    h: usize,
    depth: Vec<f32>,
    ids: Vec<u32>,
    frame: Vec<u8>,
    lines: Vec<u8>,
}

/// Rasterizes one screen triangle (x, y, depth) as an interior of face `id`.
fn raster_triangle(
    b: &mut Buffers,
    tri: [[f32; 3]; 3],
    id: u32,
    pattern: &PatternTable,
    erase: bool,
) {
    let [p0, mut p1, mut p2] = tri;
    let area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
    if area == 0.0 || !area.is_finite() {
        return;
    }
    if area < 0.0 {
        std::mem::swap(&mut p1, &mut p2);
    }
    let area = area.abs();
    let min_x = p0[0].min(p1[0]).min(p2[0]);
    let max_x = p0[0].max(p1[0]).max(p2[0]);
    let min_y = p0[1].min(p1[1]).min(p2[1]);
    let max_y = p0[1].max(p1[1]).max(p2[1]);
    // Pixel centres i + 0.5 in [min, max].
    let x0 = ((min_x - 0.5).ceil().max(0.0)) as usize;
    let x1 = ((max_x - 0.5).floor().min(b.w as f32 - 1.0)) as isize;
    let y0 = ((min_y - 0.5).ceil().max(0.0)) as usize;
    let y1 = ((max_y - 0.5).floor().min(b.h as f32 - 1.0)) as isize;
    if x1 < x0 as isize || y1 < y0 as isize {
        return;
    }
    let (x1, y1) = (x1 as usize, y1 as usize);
    // Edge function of a -> b, positive inside; (A, B, C): E = A x + B y + C.
    let edge = |a: [f32; 3], c: [f32; 3]| {
        let (dx, dy) = (c[0] - a[0], c[1] - a[1]);
        let top_left = dy < 0.0 || (dy == 0.0 && dx > 0.0);
        (-dy, dx, dy * a[0] - dx * a[1], top_left)
    };
    let e = [edge(p1, p2), edge(p2, p0), edge(p0, p1)];
    // Depth plane: d = d0 * w0 + d1 * w1 + d2 * w2 with w the normalized edge values.
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
        let row = y * b.w;
        for x in x0..=x1 {
            if inside(w0, e[0].3) && inside(w1, e[1].3) && inside(w2, e[2].3) {
                let i = row + x;
                // The paper's this_Algorithm for an interior pixel (nearer = smaller d).
                if d < b.depth[i] {
                    b.depth[i] = d;
                    b.ids[i] = id + 1;
                    if erase && pattern.value(x, y) == 0 {
                        b.frame[i] = 0;
                    }
                }
            }
            w0 += e[0].0;
            w1 += e[1].0;
            w2 += e[2].0;
            d += ddx;
        }
    }
}

/// Face data prepared once per frame.
struct Prepared<'a> {
    normals: &'a [V3],
    facing: Vec<bool>,
}

fn newell(verts: &[V3], face: &[u32]) -> V3 {
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

/// A welded edge and the faces that use it.
struct Edge {
    a: u32,
    b: u32,
    faces: Vec<u32>,
}

/// What does not depend on the view: f32 vertices, Newell normals, welded edges with
/// their faces, closedness. Built once per mesh (as firmware would keep it).
pub struct BaselineMesh {
    verts: Vec<V3>,
    normals: Vec<V3>,
    edges: Vec<Edge>,
    closed: bool,
}

/// Prepares `mesh` for [`render_prepared`]. Faces with an invalid index are skipped.
pub fn prepare_baseline(mesh: &MeshData) -> BaselineMesh {
    let verts: Vec<V3> = mesh.vertices.iter().map(|&p| to32(p)).collect();
    let nv = verts.len() as u32;
    let mut weld_of: HashMap<[u64; 3], u32> = HashMap::with_capacity(mesh.vertices.len());
    let weld: Vec<u32> = mesh
        .vertices
        .iter()
        .enumerate()
        .map(|(i, p)| {
            *weld_of
                .entry([p[0].to_bits(), p[1].to_bits(), p[2].to_bits()])
                .or_insert(i as u32)
        })
        .collect();
    let mut edge_of: HashMap<(u32, u32), usize> = HashMap::new();
    let mut edges: Vec<Edge> = Vec::new();
    let mut normals = Vec::with_capacity(mesh.faces.len());
    for (fi, f) in mesh.faces.iter().enumerate() {
        if f.iter().any(|&v| v >= nv) {
            normals.push([0.0; 3]);
            continue;
        }
        normals.push(newell(&verts, f));
        for k in 0..f.len() {
            let (a, c) = (weld[f[k] as usize], weld[f[(k + 1) % f.len()] as usize]);
            if a == c {
                continue;
            }
            let key = (a.min(c), a.max(c));
            let e = *edge_of.entry(key).or_insert_with(|| {
                edges.push(Edge {
                    a: key.0,
                    b: key.1,
                    faces: Vec::new(),
                });
                edges.len() - 1
            });
            if edges[e].faces.last() != Some(&(fi as u32)) {
                edges[e].faces.push(fi as u32);
            }
        }
    }
    let closed = edges.iter().all(|e| e.faces.len() == 2);
    BaselineMesh {
        verts,
        normals,
        edges,
        closed,
    }
}

/// Renders `mesh` the way the paper does (see the module documentation). Invalid
/// vertex indices are skipped; a degenerate camera draws nothing.
pub fn render_baseline(mesh: &MeshData, camera: &CameraSpec, spec: &RenderSpec) -> Frame {
    render_prepared(mesh, &prepare_baseline(mesh), camera, spec)
}

/// [`render_baseline`] with the view-independent part done beforehand.
pub fn render_prepared(
    mesh: &MeshData,
    pm: &BaselineMesh,
    camera: &CameraSpec,
    spec: &RenderSpec,
) -> Frame {
    let (w, h) = (spec.width, spec.height);
    let mut b = Buffers {
        w,
        h,
        depth: vec![f32::INFINITY; w * h],
        ids: vec![0; w * h],
        frame: vec![0; w * h],
        lines: vec![0; w * h],
    };
    let pattern = PatternTable::by_name(&spec.pattern)
        .or_else(|| PatternTable::by_name("paper"))
        .unwrap_or(PatternTable {
            w: 1,
            h: 1,
            bits: vec![1],
        });
    let cam = Cam::new(camera, w.max(1), h.max(1));
    let verts = &pm.verts;
    let nv = verts.len() as u32;
    let faces: Vec<&Vec<u32>> = mesh.faces.iter().collect();
    let edges = &pm.edges;
    let closed = pm.closed;
    let cull = match spec.cull {
        CullSpec::On => true,
        CullSpec::Off => false,
        CullSpec::Auto => closed,
    };

    // Facing, per view.
    let facing: Vec<bool> = faces
        .iter()
        .zip(&pm.normals)
        .map(|(f, &n)| {
            if f.is_empty() || f.iter().any(|&v| v >= nv) {
                return false;
            }
            if cam.persp {
                let mut c = [0.0f32; 3];
                for &v in f.iter() {
                    let p = verts[v as usize];
                    c = [c[0] + p[0], c[1] + p[1], c[2] + p[2]];
                }
                let k = 1.0 / f.len() as f32;
                dot(n, sub(cam.eye, [c[0] * k, c[1] * k, c[2] * k])) > 0.0
            } else {
                dot(n, cam.f) < 0.0
            }
        })
        .collect();
    let prep = Prepared {
        normals: &pm.normals,
        facing,
    };

    // Pass 1: faces (interiors).
    let eye_v: Vec<V3> = verts.iter().map(|&p| cam.to_eye(p)).collect();
    let surfaces = matches!(spec.mode, ModeSpec::Surfaces | ModeSpec::SurfacesDashed);
    let mut poly: Vec<V3> = Vec::new();
    let (mut clipped, mut tmp) = (Vec::new(), Vec::new());
    let mut scr: Vec<[f32; 3]> = Vec::new();
    let mut faces_drawn = 0u64;
    for (fi, f) in faces.iter().enumerate() {
        if f.len() < 3 || f.iter().any(|&v| v >= nv) || (cull && !prep.facing[fi]) {
            continue;
        }
        faces_drawn += 1;
        poly.clear();
        poly.extend(f.iter().map(|&v| eye_v[v as usize]));
        let src: &[V3] = if poly.iter().all(|p| p[2] >= cam.near && p[2] <= cam.far) {
            &poly
        } else {
            clip_polygon(&poly, cam.near, cam.far, &mut clipped, &mut tmp);
            &clipped
        };
        if src.len() < 3 {
            continue;
        }
        scr.clear();
        scr.extend(src.iter().map(|&p| cam.project(p)));
        for k in 1..scr.len() - 1 {
            raster_triangle(
                &mut b,
                [scr[0], scr[k], scr[k + 1]],
                fi as u32,
                &pattern,
                false,
            );
        }
    }
    if surfaces {
        for (px, id) in b.frame.iter_mut().zip(&b.ids) {
            *px = u8::from(*id != 0);
        }
    }

    // Pass 2: feature edges through the P-buffer test.
    let cos_crease = (spec.crease_deg.to_radians() as f32).cos();
    let eps = 1.0f32 / 16384.0;
    let mut feature_edges = 0u64;
    for e in edges {
        let feature = match e.faces.as_slice() {
            [f0, f1] => {
                let (n0, n1) = (prep.normals[*f0 as usize], prep.normals[*f1 as usize]);
                let (l0, l1) = (dot(n0, n0).sqrt(), dot(n1, n1).sqrt());
                if l0 == 0.0 || l1 == 0.0 {
                    false
                } else {
                    dot(n0, n1) < cos_crease * l0 * l1
                        || prep.facing[*f0 as usize] != prep.facing[*f1 as usize]
                }
            }
            _ => true,
        };
        if !feature {
            continue;
        }
        feature_edges += 1;
        // Clip the segment to near/far in eye space.
        let (mut p, mut q) = (eye_v[e.a as usize], eye_v[e.b as usize]);
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
        if !ok {
            continue;
        }
        let (s0, s1) = (cam.project(p), cam.project(q));
        draw_edge(&mut b, s0, s1, &e.faces, &pattern, spec.mode, eps);
    }

    // Pack.
    let stride = w.div_ceil(8);
    let mut packed = vec![0u8; stride * h];
    for y in 0..h {
        for x in 0..w {
            if b.frame[y * w + x] != 0 {
                packed[y * stride + x / 8] |= 0x80 >> (x % 8);
            }
        }
    }
    let depth_bytes = (w * h * std::mem::size_of::<f32>()) as u64;
    let stats = vec![
        ("faces".to_string(), faces.len() as u64),
        ("faces_drawn".to_string(), faces_drawn),
        ("feature_edges".to_string(), feature_edges),
        ("closed".to_string(), u64::from(closed)),
        ("culled".to_string(), u64::from(cull)),
        ("depth_buffer_bytes".to_string(), depth_bytes),
        (
            "working_ram_bytes".to_string(),
            depth_bytes + (w * h * 4 + w * h * 2) as u64,
        ),
    ];
    Frame {
        width: w,
        height: h,
        ids: b.ids,
        lines: b.lines,
        packed,
        stats,
    }
}

/// DDA along a screen segment: one pixel per centre along the major axis; each pixel
/// goes through the paper's boundary-pixel test.
fn draw_edge(
    b: &mut Buffers,
    s0: [f32; 3],
    s1: [f32; 3],
    own: &[u32],
    pattern: &PatternTable,
    mode: ModeSpec,
    eps: f32,
) {
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
    let limit = if x_major { b.w } else { b.h } as f32;
    let lo = ((a0.min(a1) - 0.5).ceil().max(0.0)) as isize;
    let hi = ((a0.max(a1) - 0.5).floor().min(limit - 1.0)) as isize;
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
    let other_limit = if x_major { b.h } else { b.w };
    let erase_on = matches!(mode, ModeSpec::Surfaces | ModeSpec::SurfacesDashed);
    for a in lo..=hi {
        let mf = m.floor();
        m += dminor;
        let dd_here = d;
        d += dd;
        if mf < 0.0 || mf >= other_limit as f32 {
            continue;
        }
        let (x, y) = if x_major {
            (a as usize, mf as usize)
        } else {
            (mf as usize, a as usize)
        };
        let i = y * b.w + x;
        let id = b.ids[i];
        let hidden = b.depth[i] < dd_here - eps && !(id != 0 && own.contains(&(id - 1)));
        let draw = match mode {
            ModeSpec::Wireframe => true,
            ModeSpec::Hidden | ModeSpec::Surfaces => !hidden,
            ModeSpec::Dashed | ModeSpec::SurfacesDashed => !hidden || pattern.value(x, y) != 0,
        };
        if hidden {
            if b.lines[i] == 0 {
                b.lines[i] = 2;
            }
        } else {
            b.lines[i] = 1;
        }
        if mode == ModeSpec::Surfaces {
            continue;
        }
        if draw {
            b.frame[i] = u8::from(!erase_on);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> MeshData {
        let mut m = MeshData::default();
        for i in 0..8 {
            m.vertices.push([
                f64::from(i & 1) * 2.0 - 1.0,
                f64::from((i >> 1) & 1) * 2.0 - 1.0,
                f64::from((i >> 2) & 1) * 2.0 - 1.0,
            ]);
        }
        // CCW seen from outside.
        m.faces = vec![
            vec![0, 2, 3, 1], // -z
            vec![4, 5, 7, 6], // +z
            vec![0, 1, 5, 4], // -y
            vec![2, 6, 7, 3], // +y
            vec![0, 4, 6, 2], // -x
            vec![1, 3, 7, 5], // +x
        ];
        m
    }

    fn spec(mode: ModeSpec) -> RenderSpec {
        RenderSpec {
            width: 120,
            height: 80,
            mode,
            ..RenderSpec::default()
        }
    }

    #[test]
    fn cube_front_view() {
        let cam = CameraSpec {
            eye: [0.0, 0.0, 6.0],
            ..CameraSpec::default()
        };
        let f = render_baseline(&cube(), &cam, &spec(ModeSpec::Dashed));
        let stat = |k: &str| f.stats.iter().find(|(n, _)| n == k).map(|s| s.1);
        assert_eq!(stat("faces"), Some(6));
        assert_eq!(stat("closed"), Some(1));
        // Only the front face is visible from straight ahead; it covers the centre.
        assert_eq!(f.ids[40 * 120 + 60], 2);
        assert_eq!(stat("faces_drawn"), Some(1));
        // The silhouette is the front square's outline: 4 edges, all visible.
        assert_eq!(stat("feature_edges"), Some(12));
        assert!(f.lines.contains(&1));
        let set: u32 = f.packed.iter().map(|b| b.count_ones()).sum();
        assert!(set > 100, "{set}");
    }

    #[test]
    fn hidden_edges_are_dashed_three_quarter() {
        let cam = CameraSpec {
            eye: [4.0, 3.0, 5.0],
            projection: ProjectionSpec::Perspective { fov_deg: 45.0 },
            ..CameraSpec::default()
        };
        let mut s = spec(ModeSpec::Dashed);
        s.cull = CullSpec::Off;
        let f = render_baseline(&cube(), &cam, &s);
        let hidden = f.lines.iter().filter(|&&l| l == 2).count();
        let visible = f.lines.iter().filter(|&&l| l == 1).count();
        assert!(hidden > 20 && visible > 100, "{hidden} {visible}");
        // Every visible line pixel is set; hidden ones only where the pattern passes.
        let p = PatternTable::by_name("paper").unwrap();
        let stride = 120usize.div_ceil(8);
        for y in 0..80 {
            for x in 0..120 {
                let on = f.packed[y * stride + x / 8] >> (7 - x % 8) & 1 != 0;
                match f.lines[y * 120 + x] {
                    1 => assert!(on),
                    2 => assert_eq!(on, p.value(x, y) != 0),
                    _ => assert!(!on),
                }
            }
        }
        let h = render_baseline(&cube(), &cam, &spec(ModeSpec::Hidden));
        let set: u32 = h.packed.iter().map(|b| b.count_ones()).sum();
        assert_eq!(set as usize, h.lines.iter().filter(|&&l| l == 1).count());
    }

    #[test]
    fn near_plane_clips_instead_of_dropping() {
        // Eye inside the cube's slab: near plane cuts faces.
        let cam = CameraSpec {
            eye: [0.0, 0.0, 1.5],
            near: 1.0,
            ..CameraSpec::default()
        };
        let mut s = spec(ModeSpec::Dashed);
        s.cull = CullSpec::Off;
        let f = render_baseline(&cube(), &cam, &s);
        assert!(f.ids.iter().filter(|&&i| i != 0).count() > 1000);
    }

    #[test]
    fn paper_pattern_table_matches_the_library() {
        let t = PatternTable::by_name("paper").unwrap();
        let p = pbuffer::Pattern::PAPER;
        for y in 0..20 {
            for x in 0..20 {
                assert_eq!(t.value(x, y) != 0, p.passes(x as u32, y as u32));
            }
        }
        assert!(PatternTable::by_name("nope").is_none());
    }
}
