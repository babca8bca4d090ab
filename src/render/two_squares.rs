//! Test scenes shared by the engines' unit tests: two unit-high squares overlapping
//! in x, seen from +z (orthographic, 32 x 32 px over [-2, 2]^2), drawn into a packed
//! framebuffer with a probe that keeps the frame's face ids; and a cube ([`cube`]).

extern crate std;
use core::convert::Infallible;
use std::vec;
use std::vec::Vec;

use super::compose::FrameProbe;
use super::idpass::IdWorkspace;
use super::transform::ProjectedVertex;
use super::{Cull, DrawMode, Settings, Stats};
use crate::camera::Camera;
use crate::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use crate::{Dashes, Error, PackedFramebuffer, Pattern, Projection};

/// The frame buffer the scene is drawn into.
pub(super) type Frame32 = PackedFramebuffer<32, 32, { crate::packed_len(32, 32) }>;

/// Keeps the frame's face ids.
pub(super) struct Ids(pub Vec<u16>);

impl FrameProbe for Ids {
    fn row(&mut self, y: u16, ids: &[u16], _: &[u32], _: &[u32]) {
        let at = usize::from(y) * 32;
        self.0[at..at + 32].copy_from_slice(ids);
    }
}

/// Face 0 at depth `z0`, x in [-1.5, 0.5]; face 1 at depth `z1`, x in [-0.5, 1.5].
pub(super) fn squares(z0: f32, z1: f32) -> (Vec<[f32; 3]>, Vec<u32>, Vec<u32>) {
    let sq = |x0: f32, z: f32| {
        [
            [x0, -1.0, z],
            [x0 + 2.0, -1.0, z],
            [x0 + 2.0, 1.0, z],
            [x0, 1.0, z],
        ]
    };
    let v: Vec<[f32; 3]> = sq(-1.5, z0).into_iter().chain(sq(-0.5, z1)).collect();
    (v, (0..8).collect(), vec![0, 4, 8])
}

/// Pixels of row 16 showing face `id` (1 + index) in columns 0..32: 8 px per unit.
pub(super) fn count(ids: &[u16], id: u16) -> usize {
    ids[16 * 32..17 * 32].iter().filter(|&&i| i == id).count()
}

/// Everything an engine's `render` takes for the mesh `(v, idx, off)` in this view
/// (surfaces, no culling), lent to `draw`; returns the frame's face ids.
pub(super) fn frame(
    v: &[[f32; 3]],
    idx: &[u32],
    off: &[u32],
    draw: impl FnOnce(
        &Mesh<'_>,
        &EdgeAdjacency<'_>,
        &Camera,
        &Settings,
        &mut IdWorkspace<'_>,
        &mut Frame32,
        &mut Ids,
    ) -> Result<Stats, Error<Infallible>>,
) -> Result<Vec<u16>, Error> {
    let mesh = Mesh::new(v, idx, off).unwrap();
    let mut weld = vec![0u32; v.len()];
    let mut scratch = vec![HalfEdgeRecord::default(); idx.len()];
    let mut store = vec![MeshEdge::default(); idx.len()];
    let adj = EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut store).unwrap();
    let camera = Camera::new(
        [0.0, 0.0, 5.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        Projection::Orthographic { half_height: 2.0 },
        0.5,
        20.0,
    )
    .unwrap();
    let settings = Settings {
        mode: DrawMode::Surfaces,
        cull: Cull::Off,
        pattern: Pattern::PAPER,
        dashes: Dashes::Screen,
        lines: crate::render::LineVisibility::ByPixel,
    };
    let mut vertices = vec![ProjectedVertex::default(); v.len()];
    let (mut drawn, mut features) = (vec![0u32; 1], vec![0u32; 1]);
    let (mut ids, mut lines) = (vec![0u16; 32 * 32], vec![0u32; 2 * 32]);
    let mut ws = IdWorkspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        ids: &mut ids,
        lines: &mut lines,
    };
    let mut fb = Frame32::new();
    let mut probe = Ids(vec![0; 32 * 32]);
    draw(
        &mesh, &adj, &camera, &settings, &mut ws, &mut fb, &mut probe,
    )
    .map_err(|e| match e {
        Error::Target(never) => match never {},
        other => other.widen(),
    })?;
    Ok(probe.0)
}

/// The cube [-1, 1]^3, faces wound outward: vertices, corners and offsets.
pub(crate) fn cube() -> (Vec<[f32; 3]>, Vec<u32>, Vec<u32>) {
    let v = vec![
        [-1., -1., -1.],
        [1., -1., -1.],
        [1., 1., -1.],
        [-1., 1., -1.],
        [-1., -1., 1.],
        [1., -1., 1.],
        [1., 1., 1.],
        [-1., 1., 1.],
    ];
    let idx = vec![
        0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 3, 7, 6, 2, 0, 4, 7, 3, 1, 2, 6, 5,
    ];
    (v, idx, (0..=6).map(|f| 4 * f).collect())
}
