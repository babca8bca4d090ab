//! `pbuffer::render::pick` on the host: what is under chosen pixels.

use pbuffer::render::{pick, Pick, PickWorkspace, PickedEdge, ProjectedVertex};
use pbuffer::Viewport;

use crate::frame::{CameraSpec, MeshData, RenderSpec};
use crate::setup::POLY;
use crate::setup::{FrameInputs, SceneStorage};

/// One picked pixel: the library's answer, each edge with its end positions.
#[derive(Clone, Debug)]
pub struct Picked {
    pub x: u16,
    pub y: u16,
    pub pick: Pick,
    pub edges: Vec<(PickedEdge, [[f32; 3]; 2])>,
    /// The 0-based vertex indices of each edge's ends (its lowest welded ones).
    pub ends: Vec<[u32; 2]>,
}

/// Picks every pixel of `pixels` at the spec's sub-pixel bits.
pub fn pick_pixels(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    pixels: &[(u16, u16)],
) -> Result<Vec<Picked>, String> {
    use fixed::types::extra::*;
    match spec.subpixel {
        0 => pick_s::<U0>(data, cam, spec, pixels),
        1 => pick_s::<U1>(data, cam, spec, pixels),
        2 => pick_s::<U2>(data, cam, spec, pixels),
        3 => pick_s::<U3>(data, cam, spec, pixels),
        4 => pick_s::<U4>(data, cam, spec, pixels),
        5 => pick_s::<U5>(data, cam, spec, pixels),
        6 => pick_s::<U6>(data, cam, spec, pixels),
        7 => pick_s::<U7>(data, cam, spec, pixels),
        8 => pick_s::<U8>(data, cam, spec, pixels),
        9 => pick_s::<U9>(data, cam, spec, pixels),
        10 => pick_s::<U10>(data, cam, spec, pixels),
        11 => pick_s::<U11>(data, cam, spec, pixels),
        12 => pick_s::<U12>(data, cam, spec, pixels),
        s => Err(format!("--subpixel {s}: must be 0 to 12")),
    }
}

fn pick_s<Frac: fixed::types::extra::LeEqU32>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    pixels: &[(u16, u16)],
) -> Result<Vec<Picked>, String> {
    let mut storage = SceneStorage::new(data);
    let FrameInputs {
        mesh,
        adjacency,
        camera,
        settings,
        ..
    } = storage.scene(cam, spec)?;
    let viewport = Viewport::new(spec.width as u32, spec.height as u32)
        .map_err(|e| format!("viewport: {e}"))?;
    let mut vertices = vec![ProjectedVertex::default(); mesh.vertices().len()];
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
        let p = pick::<Frac, POLY>(
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
        let ends = out[..p.edges]
            .iter()
            .map(|pe| {
                let e = adjacency.edges()[pe.edge as usize];
                [e.a, e.b]
            })
            .collect();
        let edges = out[..p.edges]
            .iter()
            .map(|pe| {
                let e = adjacency.edges()[pe.edge as usize];
                (
                    *pe,
                    [mesh.vertices()[e.a as usize], mesh.vertices()[e.b as usize]],
                )
            })
            .collect();
        result.push(Picked {
            x,
            y,
            pick: p,
            edges,
            ends,
        });
    }
    Ok(result)
}
