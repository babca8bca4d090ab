//! The view-independent part: `f32` vertices, Newell normals, welded edges, closedness.

use std::collections::HashMap;

use super::vector::{newell, to32, V3};
use crate::frame::MeshData;

/// A welded edge and the faces that use it.
pub(super) struct Edge {
    pub(super) a: u32,
    pub(super) b: u32,
    pub(super) faces: Vec<u32>,
}

/// What does not depend on the view: f32 vertices, Newell normals, welded edges with
/// their faces, closedness. Built once per mesh (as firmware would keep it).
pub struct BaselineMesh {
    pub(super) verts: Vec<V3>,
    pub(super) normals: Vec<V3>,
    pub(super) edges: Vec<Edge>,
    pub(super) closed: bool,
}

/// Prepares `mesh` for [`render_prepared`](super::render_prepared). Faces with an invalid
/// index are skipped.
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
                .entry(p.map(|c| (c + 0.0).to_bits()))
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
