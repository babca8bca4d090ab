//! `pbuffer::render::pick` on the host: what is under chosen pixels.

use fixed::types::extra::U4;
use pbuffer::mesh::Mesh;
use pbuffer::render::{pick, Pick, PickWorkspace, PickedEdge, ProjectedVertex};
use pbuffer::Viewport;

use crate::frame::{CameraSpec, MeshData, RenderSpec};
use crate::pipeline::{camera, settings, AdjacencyStorage, MeshArrays, POLY};

/// One picked pixel: the library's answer, each edge with its end positions.
#[derive(Clone, Debug)]
pub struct Picked {
    pub x: u16,
    pub y: u16,
    pub pick: Pick,
    pub edges: Vec<(PickedEdge, [[f32; 3]; 2])>,
}

/// Picks every pixel of `pixels` at S = 4 (the only sub-pixel setting picking is
/// offered at on the host).
pub fn pick_pixels(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    pixels: &[(u16, u16)],
) -> Result<Vec<Picked>, String> {
    let arrays = MeshArrays::new(data);
    let mesh = Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets)
        .map_err(|e| format!("mesh: {e}"))?;
    let mut storage = AdjacencyStorage::new(&arrays);
    let adjacency = storage.build(&mesh, spec.crease_deg)?;
    let camera = camera(cam)?;
    let settings = settings(spec)?;
    let viewport = Viewport::new(spec.width as u32, spec.height as u32)
        .map_err(|e| format!("viewport: {e}"))?;
    let mut vertices = vec![ProjectedVertex::default(); arrays.vertices.len()];
    let mut drawn = vec![0u32; mesh.face_count().div_ceil(32)];
    let mut features = vec![0u32; adjacency.edges().len().div_ceil(32)];
    let mut out = vec![PickedEdge::default(); 64];
    let mut result = Vec::new();
    for &(x, y) in pixels {
        let ws = PickWorkspace {
            vertices: &mut vertices,
            drawn: &mut drawn,
            features: &mut features,
        };
        let p = pick::<U4, POLY>(
            &mesh,
            &adjacency,
            &camera,
            &settings,
            viewport,
            (x, y),
            ws,
            &mut out,
        )
        .map_err(|e| format!("pick ({x}, {y}): {e}"))?;
        let edges = out[..p.edges]
            .iter()
            .map(|pe| {
                let e = adjacency.edges()[pe.edge as usize];
                (
                    *pe,
                    [arrays.vertices[e.a as usize], arrays.vertices[e.b as usize]],
                )
            })
            .collect();
        result.push(Picked {
            x,
            y,
            pick: p,
            edges,
        });
    }
    Ok(result)
}
