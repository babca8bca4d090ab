//! One baseline frame: facing and culling, faces then feature edges, packing, stats.

use super::camera::{clip_polygon, Cam};
use super::mesh::{prepare_baseline, BaselineMesh};
use super::pattern::PatternTable;
use super::raster::{draw_edge, raster_triangle, Buffers};
use super::vector::{dot, sub, V3};
use crate::frame::{CameraSpec, CullSpec, Frame, MeshData, ModeSpec, RenderSpec};

/// Face data prepared once per frame.
struct Prepared<'a> {
    normals: &'a [V3],
    facing: Vec<bool>,
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
        depth_step: [0.0; 2],
    }
}
