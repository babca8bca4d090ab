//! The depth-precision table: relative depth error against depth bits and far/near,
//! measured through the library and next to the formula.
//!
//! The Z-buffer stores nearness `q = near / d` (perspective) in `Q1.31`
//! (`src/render/transform.rs`: `q = (near << 31) / z` in clip units) and a sample
//! keeps its top `B` bits (`Depth::from_q`: a 16-bit sample is `q >> 16`,
//! truncated). One step is `2^-(B-1)`, so the stored nearness is low by less than a
//! step and the depth read back, `near / q_stored`, is high by a relative
//! `step / q = 2^-(B-1) d / near`: largest at the far plane, `2^-(B-1) far / near`.
//! Beyond `d = near 2^(B-1)` a sample is 0 and depth is lost altogether.
//!
//! Measured: a mesh of small triangles with one vertex on the view axis at each of
//! 400 distances spaced geometrically from near to far is rendered by the
//! Z-buffer engine; the nearness the library computed for each axis vertex (its
//! vertex cache, the value the depth planes start from) is stored as `Depth` does
//! it, read back and compared with the f64 depth. So the figure includes the
//! library's fixed-point positions and projection rounding as well as the sample
//! width.

use fixed::types::extra::U4;
use pbuffer::mesh::Mesh;
use pbuffer::render::{storage_rows, Depth, ProjectedVertex};
use pbuffer::{Camera, MonoPalette, Projection, Settings, Workspace, ZBufferRenderer};

use crate::frame::MeshData;
use crate::setup::{AdjacencyStorage, MeshArrays, PackedFrame};

/// Far/near ratios of the table.
pub const RATIOS: [f64; 3] = [10.0, 1000.0, 1e5];
/// Samples per ratio.
const SAMPLES: usize = 400;

/// One row of the table.
#[derive(Clone, Debug)]
pub struct DepthRow {
    pub bits: u32,
    pub ratio: f64,
    /// The formula at the far plane: `2^-(B-1) far / near`.
    pub formula_far: f64,
    /// Measured relative error: the maximum and mean over all samples (the maximum
    /// is infinite where a sample reads back 0; the mean leaves those out).
    pub measured_max: f64,
    pub measured_mean: f64,
    /// Samples that read back as 0 (depth lost).
    pub lost: usize,
}

/// Nearness (`Q1.31`) of the axis vertex at each distance, from the library.
fn library_nearness(near: f64, far: f64) -> Result<(Vec<f64>, Vec<u32>), String> {
    let mut mesh = MeshData::default();
    let mut dists = Vec::new();
    for i in 0..SAMPLES {
        // Strictly inside [near, far]; the f32 value is the truth.
        let t = (i as f64 + 0.5) / SAMPLES as f64;
        let d = f64::from((near * (far / near).powf(t)) as f32);
        let e = d * 1e-3;
        let k = mesh.vertices.len() as u32;
        mesh.vertices
            .extend([[0.0, 0.0, -d], [e, 0.0, -d], [0.0, e, -d]]);
        mesh.faces.push(vec![k, k + 1, k + 2]);
        dists.push(d);
    }
    let arrays = MeshArrays::new(&mesh);
    let m = Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets)
        .map_err(|e| format!("mesh: {e}"))?;
    let mut storage = AdjacencyStorage::new(&arrays);
    let adjacency = storage.build(&m, 30.0)?;
    let camera = Camera::new(
        [0.0; 3],
        [0.0, 0.0, -1.0],
        [0.0, 1.0, 0.0],
        Projection::Perspective { fov_y_deg: 45.0 },
        near as f32,
        far as f32,
    )
    .map_err(|e| format!("camera: {e}"))?;
    let (w, h) = (64usize, 64usize);
    let stored = usize::from(storage_rows(h as u16, h as u16));
    let mut vertices = vec![ProjectedVertex::default(); arrays.vertices.len()];
    let mut drawn = vec![0u32; m.face_count().div_ceil(32)];
    let mut features = vec![0u32; adjacency.edges().len().div_ceil(32)];
    let mut depth = vec![0u32; w * stored];
    let mut ids = vec![0u16; w * stored];
    let mut lines = vec![0u32; 2 * w.div_ceil(32) * h];
    let mut ws = Workspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        depth: &mut depth,
        ids: &mut ids,
        lines: &mut lines,
    };
    let mut renderer = Box::new(ZBufferRenderer::<U4, 64, 64>::new());
    let mut target = PackedFrame::new(w, h);
    renderer
        .render(
            &m,
            &adjacency,
            &camera,
            &Settings::default(),
            &mut ws,
            &MonoPalette::default(),
            &mut target,
            &mut (),
        )
        .map_err(|e| format!("render: {e}"))?;
    let q = (0..SAMPLES)
        .map(|i| ws.vertices[3 * i].screen().q)
        .collect();
    Ok((dists, q))
}

/// Relative error of depth read back from nearness `q` (`Q1.31`) stored in `D`.
fn rel_error<D: Depth>(near: f64, d: f64, q: u32) -> f64 {
    let stored = D::from_q(q).to_q();
    if stored == 0 {
        return f64::INFINITY;
    }
    let back = near / (f64::from(stored) / f64::from(1u32 << 31));
    (back - d).abs() / d
}

/// The table: every depth width of the library at every ratio (near = 1).
pub fn table() -> Result<Vec<DepthRow>, String> {
    let mut rows = Vec::new();
    for &ratio in &RATIOS {
        let near = 1.0;
        let (dists, q) = library_nearness(near, ratio)?;
        for bits in [16u32, 32] {
            let errs: Vec<f64> = dists
                .iter()
                .zip(&q)
                .map(|(&d, &q)| {
                    if bits == 16 {
                        rel_error::<u16>(near, d, q)
                    } else {
                        rel_error::<u32>(near, d, q)
                    }
                })
                .collect();
            let finite: Vec<f64> = errs.iter().copied().filter(|e| e.is_finite()).collect();
            rows.push(DepthRow {
                bits,
                ratio,
                formula_far: 2f64.powi(1 - bits as i32) * ratio,
                measured_max: errs.iter().copied().fold(0.0, f64::max),
                measured_mean: finite.iter().sum::<f64>() / finite.len().max(1) as f64,
                lost: errs.len() - finite.len(),
            });
        }
    }
    Ok(rows)
}
