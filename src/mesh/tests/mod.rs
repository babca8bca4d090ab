//! Unit tests of meshes, adjacency and feature edges (core only: no std here).

mod edges;
mod input;

use super::*;

/// Unit cube corners: vertex `x + 2y + 4z` is at `(x, y, z)`.
const CUBE: [[f32; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [1.0, 1.0, 1.0],
];

/// Six quads, counter-clockwise from outside: -Z, +Z, -Y, +Y, -X, +X.
const QUADS: [[u32; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

const QUAD_OFFSETS: [u32; 7] = [0, 4, 8, 12, 16, 20, 24];
const TRI_OFFSETS: [u32; 13] = [0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 33, 36];

fn quad_indices() -> [u32; 24] {
    let mut out = [0; 24];
    for (slot, &i) in out.iter_mut().zip(QUADS.iter().flatten()) {
        *slot = i;
    }
    out
}

/// Each quad `[a, b, c, d]` as `[a, b, c]`, `[a, c, d]`: diagonal a-c.
fn triangle_indices() -> [u32; 36] {
    let mut out = [0; 36];
    for (q, [a, b, c, d]) in QUADS.iter().enumerate() {
        out[q * 6..q * 6 + 6].copy_from_slice(&[*a, *b, *c, *a, *c, *d]);
    }
    out
}

/// Storage for up to 64 vertices and 64 corners.
struct Buffers {
    weld: [u32; 64],
    scratch: [HalfEdgeRecord; 64],
    out: [MeshEdge; 64],
}

impl Buffers {
    fn new() -> Self {
        Self {
            weld: [0; 64],
            scratch: [HalfEdgeRecord::EMPTY; 64],
            out: [MeshEdge::EMPTY; 64],
        }
    }

    fn build(&mut self, mesh: &Mesh<'_>, crease_deg: f32) -> EdgeAdjacency<'_> {
        EdgeAdjacency::build(
            mesh,
            crease_deg,
            &mut self.weld,
            &mut self.scratch,
            &mut self.out,
        )
        .expect("buffers are large enough")
    }
}

fn count_kind(edges: &[MeshEdge], kind: EdgeKind) -> usize {
    edges.iter().filter(|e| e.kind == kind).count()
}

fn count_features(mesh: &Mesh<'_>, edges: &[MeshEdge], view: &Viewpoint) -> usize {
    edges.iter().filter(|e| e.is_feature(mesh, view)).count()
}
