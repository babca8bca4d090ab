//! Renders a reference frame: welding, face set-up, feature edges, surfaces, lines.

use std::collections::HashMap;

use super::camera::Camera;
use super::clip::{clip_polygon, clip_segment, clip_to_rect};
use super::coverage::{covers, quantize};
use super::vector::{add, cross, dot, newell_normal, norm, scale, sub, weld_key, V3};
use super::{EdgeKind, LineSample, RefEdge, RefFace, RefFrame, DEPTH_EPS, SAMPLE_STEP, TILE};
use crate::frame::{CameraSpec, CullSpec, MeshData, ModeSpec, RenderSpec};

/// Renders the reference frame of `mesh` seen by `camera` with `spec` (size, crease
/// angle, culling, mode; sub-pixel bits, depth bits, band and pattern do not apply).
pub fn reference_frame(
    mesh: &MeshData,
    camera: &CameraSpec,
    spec: &RenderSpec,
) -> Result<RefFrame, String> {
    let (width, height) = (spec.width, spec.height);
    let cam = Camera::new(camera, width, height)?;
    if !(spec.crease_deg.is_finite()) {
        return Err("crease angle must be finite".into());
    }
    for (k, v) in mesh.vertices.iter().enumerate() {
        if !v.iter().all(|c| c.is_finite()) {
            return Err(format!("vertex {k} is not finite"));
        }
    }
    for (k, f) in mesh.faces.iter().enumerate() {
        if f.len() < 3 {
            return Err(format!("face {k} has fewer than 3 vertices"));
        }
        if f.iter().any(|&i| i as usize >= mesh.vertices.len()) {
            return Err(format!("face {k} has a vertex index out of range"));
        }
    }

    // Welding and edges.
    let mut weld: HashMap<[u64; 3], u32> = HashMap::new();
    let welded: Vec<u32> = mesh
        .vertices
        .iter()
        .map(|p| {
            let n = weld.len() as u32;
            *weld.entry(weld_key(p)).or_insert(n)
        })
        .collect();
    let mut edge_index: HashMap<(u32, u32), usize> = HashMap::new();
    let mut edges: Vec<RefEdge> = Vec::new();
    for (fi, f) in mesh.faces.iter().enumerate() {
        let n = f.len();
        for k in 0..n {
            let (i, j) = (f[k] as usize, f[(k + 1) % n] as usize);
            let (wi, wj) = (welded[i], welded[j]);
            if wi == wj {
                continue; // a degenerate edge of a face (repeated vertex): no edge
            }
            let key = (wi.min(wj), wi.max(wj));
            let idx = *edge_index.entry(key).or_insert_with(|| {
                let (a, b) = if wi < wj { (i, j) } else { (j, i) };
                edges.push(RefEdge {
                    a: mesh.vertices[a],
                    b: mesh.vertices[b],
                    faces: Vec::new(),
                    kind: None,
                });
                edges.len() - 1
            });
            edges[idx].faces.push(fi as u32);
        }
    }
    let closed = edges.iter().all(|e| e.faces.len() == 2);
    let culling = match spec.cull {
        CullSpec::On => true,
        CullSpec::Off => false,
        CullSpec::Auto => closed,
    };

    // Faces.
    let eye_vertices: Vec<V3> = mesh.vertices.iter().map(|&p| cam.to_eye(p)).collect();
    let mut faces = Vec::with_capacity(mesh.faces.len());
    for f in &mesh.faces {
        let world: Vec<V3> = f.iter().map(|&i| mesh.vertices[i as usize]).collect();
        let normal = newell_normal(&world);
        let centroid = scale(
            world.iter().fold([0.0; 3], |acc, &p| add(acc, p)),
            1.0 / world.len() as f64,
        );
        let facing = cam.facing(normal, centroid);
        let drawn = !culling || facing;
        let eye: Vec<V3> = f.iter().map(|&i| eye_vertices[i as usize]).collect();
        let clipped = clip_polygon(&eye, cam.near, cam.far);
        let screen: Vec<(f64, f64)> = clipped
            .iter()
            .map(|&p| {
                let (x, y) = cam.project(p);
                (quantize(x), quantize(y))
            })
            .collect();
        let mut bbox = [f64::INFINITY, f64::INFINITY, -f64::INFINITY, -f64::INFINITY];
        for &(x, y) in &screen {
            bbox = [
                bbox[0].min(x),
                bbox[1].min(y),
                bbox[2].max(x),
                bbox[3].max(y),
            ];
        }
        let wmin = clipped.iter().map(|p| -p[2]).fold(f64::INFINITY, f64::min);
        let wmax = clipped.iter().map(|p| -p[2]).fold(-f64::INFINITY, f64::max);
        // Plane (eye space) if planar within 1e-9 of the face's size.
        let ne = newell_normal(&eye);
        let ln = norm(ne);
        let ce = scale(
            eye.iter().fold([0.0; 3], |acc, &p| add(acc, p)),
            1.0 / eye.len() as f64,
        );
        let size = eye.iter().map(|&p| norm(sub(p, ce))).fold(0.0, f64::max);
        let plane = if ln > 0.0 && ln.is_finite() {
            let nu = scale(ne, 1.0 / ln);
            let planar = eye.len() == 3
                || eye
                    .iter()
                    .all(|&p| dot(nu, sub(p, ce)).abs() <= 1e-9 * size);
            planar.then_some((nu, dot(nu, ce)))
        } else {
            None
        };
        faces.push(RefFace {
            normal,
            facing,
            drawn,
            eye,
            screen,
            bbox,
            plane,
            wmin,
            wmax,
        });
    }
    let faces_drawn = faces.iter().filter(|f| f.drawn).count();

    // Feature edges.
    let crease_rad = spec.crease_deg.to_radians();
    for e in &mut edges {
        e.kind = match e.faces.len() {
            1 => Some(EdgeKind::Boundary),
            2 => {
                let (f, g) = (&faces[e.faces[0] as usize], &faces[e.faces[1] as usize]);
                if f.normal == [0.0; 3] || g.normal == [0.0; 3] {
                    None
                } else {
                    let angle = norm(cross(f.normal, g.normal)).atan2(dot(f.normal, g.normal));
                    let crease = angle > crease_rad;
                    let silhouette = f.facing != g.facing;
                    match (crease, silhouette) {
                        (true, true) => Some(EdgeKind::CreaseSilhouette),
                        (true, false) => Some(EdgeKind::Crease),
                        (false, true) => Some(EdgeKind::Silhouette),
                        (false, false) => None,
                    }
                }
            }
            _ => Some(EdgeKind::NonManifold),
        };
    }
    let feature_edges = edges.iter().filter(|e| e.kind.is_some()).count();

    // Tiles.
    let tiles_x = width.div_ceil(TILE) + 2;
    let tiles_y = height.div_ceil(TILE) + 2;
    let mut tiles = vec![Vec::new(); tiles_x * tiles_y];
    for (fi, face) in faces.iter().enumerate() {
        if !face.drawn || face.screen.is_empty() {
            continue;
        }
        let b = face.bbox;
        let t = |v: f64, n: usize| {
            ((v + TILE as f64) / TILE as f64)
                .floor()
                .clamp(0.0, (n - 1) as f64) as usize
        };
        if b[2] < -(TILE as f64) || b[3] < -(TILE as f64) {
            continue;
        }
        if b[0] >= (width + TILE) as f64 || b[1] >= (height + TILE) as f64 {
            continue;
        }
        for ty in t(b[1], tiles_y)..=t(b[3], tiles_y) {
            for tx in t(b[0], tiles_x)..=t(b[2], tiles_x) {
                tiles[ty * tiles_x + tx].push(fi as u32);
            }
        }
    }

    let mut rf = RefFrame {
        width,
        height,
        ids: vec![0; width * height],
        depth: vec![f64::INFINITY; width * height],
        lines: vec![0; width * height],
        samples: Vec::new(),
        feature_edges,
        faces_drawn,
        closed,
        culling,
        camera: cam,
        faces,
        edges,
        tiles,
        tiles_x,
        tiles_y,
    };

    // Surfaces.
    for fi in 0..rf.faces.len() {
        let face = &rf.faces[fi];
        if !face.drawn || face.screen.is_empty() {
            continue;
        }
        let b = face.bbox;
        let i0 = (b[0] - 0.5).ceil().max(0.0);
        let i1 = (b[2] - 0.5).floor().min(width as f64 - 1.0);
        let j0 = (b[1] - 0.5).ceil().max(0.0);
        let j1 = (b[3] - 0.5).floor().min(height as f64 - 1.0);
        if i0 > i1 || j0 > j1 {
            continue;
        }
        for j in j0 as usize..=j1 as usize {
            for i in i0 as usize..=i1 as usize {
                let (px, py) = (i as f64 + 0.5, j as f64 + 0.5);
                if !covers(&rf.faces[fi].screen, (px, py)) {
                    continue;
                }
                let Some(w) = rf.face_depth(fi, px, py) else {
                    continue;
                };
                let k = j * width + i;
                if w < rf.depth[k] * (1.0 - DEPTH_EPS) {
                    rf.depth[k] = w;
                    rf.ids[k] = fi as u32 + 1;
                }
            }
        }
    }

    // Lines and samples.
    let wire = spec.mode == ModeSpec::Wireframe;
    let (wf, hf) = (width as f64, height as f64);
    for ei in 0..rf.edges.len() {
        if rf.edges[ei].kind.is_none() {
            continue;
        }
        let (a, b) = (
            rf.camera.to_eye(rf.edges[ei].a),
            rf.camera.to_eye(rf.edges[ei].b),
        );
        let Some((t0, t1)) = clip_segment(a, b, rf.camera.near, rf.camera.far) else {
            continue;
        };
        let (ca, cb) = (add(a, scale(sub(b, a), t0)), add(a, scale(sub(b, a), t1)));
        let p0 = rf.camera.project(ca);
        let p1 = rf.camera.project(cb);
        let (dx, dy) = (p1.0 - p0.0, p1.1 - p0.1);
        let own = rf.edges[ei].faces.clone();
        let visible_at = |rf: &RefFrame, s: f64, x: f64, y: f64| {
            let p = rf.edge_point(ca, cb, s);
            rf.point_visible(x, y, -p[2], &own)
        };
        // Pixels: one per centre along the major axis, closed interval of the segment.
        let x_major = dx.abs() >= dy.abs();
        let (lo, hi, len_major) = if x_major {
            (p0.0.min(p1.0), p0.0.max(p1.0), wf)
        } else {
            (p0.1.min(p1.1), p0.1.max(p1.1), hf)
        };
        if dx != 0.0 || dy != 0.0 {
            let c0 = (lo - 0.5).ceil().max(0.0);
            let c1 = (hi - 0.5).floor().min(len_major - 1.0);
            let mut c = c0;
            while c <= c1 {
                let m = c + 0.5;
                let (s, x, y) = if x_major {
                    let s = (m - p0.0) / dx;
                    (s, m, p0.1 + s * dy)
                } else {
                    let s = (m - p0.1) / dy;
                    (s, p0.0 + s * dx, m)
                };
                let (i, j) = (x.floor(), y.floor());
                if i >= 0.0 && j >= 0.0 && i < wf && j < hf {
                    let k = j as usize * width + i as usize;
                    let vis = wire || visible_at(&rf, s.clamp(0.0, 1.0), x, y);
                    if vis {
                        rf.lines[k] = 1;
                    } else if rf.lines[k] == 0 {
                        rf.lines[k] = 2;
                    }
                }
                c += 1.0;
            }
        }
        // Samples: the part of the segment within the screen grown by 2 px.
        let Some((s0, s1)) = clip_to_rect(p0, p1, [-2.0, -2.0, wf + 2.0, hf + 2.0]) else {
            continue;
        };
        let len = (dx * dx + dy * dy).sqrt() * (s1 - s0);
        let n = ((len / SAMPLE_STEP).ceil() as usize).max(1);
        let step = len / n as f64;
        for k in 0..=n {
            let s = s0 + (s1 - s0) * k as f64 / n as f64;
            let (x, y) = (p0.0 + s * dx, p0.1 + s * dy);
            let p = rf.edge_point(ca, cb, s);
            let visible = wire || visible_at(&rf, s, x, y);
            let weight = if k == 0 || k == n { step / 2.0 } else { step };
            rf.samples.push(LineSample {
                x,
                y,
                weight,
                visible,
                edge: ei as u32,
                depth: -p[2],
            });
        }
    }
    Ok(rf)
}

impl RefFrame {
    /// The reference as a library-style `Frame` (ids and lines; no picture), for
    /// self-comparison of the metrics.
    pub fn to_frame(&self) -> crate::frame::Frame {
        crate::frame::Frame {
            width: self.width,
            height: self.height,
            ids: self.ids.clone(),
            lines: self.lines.clone(),
            packed: Vec::new(),
            stats: vec![
                ("faces".into(), self.faces.len() as u64),
                ("faces_drawn".into(), self.faces_drawn as u64),
                ("feature_edges".into(), self.feature_edges as u64),
            ],
            depth_step: [0.0; 2],
        }
    }
}
