//! Coverage for grey displays on the host: the library's
//! `ZBufferRenderer::render_grey` into an 8-bit grey frame, and the f64 reference of
//! the same quantity: per pixel, the mean over the 4 x 4 sub-samples at
//! (i + (2a + 1) / 8, j + (2b + 1) / 8) of the grey of the face nearest there
//! (`RefFrame::nearest_face`, unsnapped geometry), or the background.

use std::time::Instant;

use embedded_graphics::pixelcolor::{Gray8, GrayColor};
use fixed::types::extra::{LeEqU32, U10, U11, U12, U2, U3, U4, U5, U6, U7, U8, U9};
use pbuffer::render::Depth;
use pbuffer::{GreyPalette, GreyShades, Span, SpanSink, Viewport, ZBufferRenderer};

use crate::frame::{CameraSpec, MeshData, ProjectionSpec, RenderSpec};
use crate::reference3d::RefFrame;
use crate::setup::{FrameInputs, IdBuffers, SceneStorage};
use crate::setup::{EDGES, POLY};

/// The palette of the host's grey frames: black background, white lines, faces
/// from level 48 (edge-on) to 176 (facing the eye).
pub fn shades() -> GreyShades<Gray8> {
    GreyShades::default()
}

/// An 8-bit grey frame, row-major.
#[derive(Debug, Clone)]
pub struct GreyFrame {
    pub width: usize,
    pub height: usize,
    pub grey: Vec<u8>,
    /// The library's render call (microseconds).
    pub time_us: u64,
}

/// A grey frame cleared to the background, as a span sink.
struct GreySink {
    width: usize,
    height: usize,
    grey: Vec<u8>,
}

impl SpanSink for GreySink {
    type Color = Gray8;
    type Error = std::convert::Infallible;

    fn viewport(&self) -> Viewport {
        Viewport {
            width: self.width as u16,
            height: self.height as u16,
        }
    }

    fn fill_span(&mut self, span: Span, color: Gray8) -> Result<(), Self::Error> {
        let row = usize::from(span.y()) * self.width;
        let (a, b) = (usize::from(span.x0()), usize::from(span.x1()));
        self.grey[row + a..row + b].fill(color.luma());
        Ok(())
    }
}

/// Renders `mesh` with `render_grey` (Z-buffer engine; `spec`'s size, mode, culling,
/// sub-pixel bits 2..=12, depth bits and band).
pub fn render_grey(
    mesh: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    palette: &GreyShades<Gray8>,
) -> Result<GreyFrame, String> {
    match spec.subpixel {
        2 => grey_s::<U2>(mesh, cam, spec, palette),
        3 => grey_s::<U3>(mesh, cam, spec, palette),
        4 => grey_s::<U4>(mesh, cam, spec, palette),
        5 => grey_s::<U5>(mesh, cam, spec, palette),
        6 => grey_s::<U6>(mesh, cam, spec, palette),
        7 => grey_s::<U7>(mesh, cam, spec, palette),
        8 => grey_s::<U8>(mesh, cam, spec, palette),
        9 => grey_s::<U9>(mesh, cam, spec, palette),
        10 => grey_s::<U10>(mesh, cam, spec, palette),
        11 => grey_s::<U11>(mesh, cam, spec, palette),
        12 => grey_s::<U12>(mesh, cam, spec, palette),
        s => Err(format!(
            "needs --subpixel 2 to 12 (sub-samples at eighths of a pixel), not {s}"
        )),
    }
}

fn grey_s<Frac: LeEqU32>(
    mesh: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    palette: &GreyShades<Gray8>,
) -> Result<GreyFrame, String> {
    match spec.depth_bits {
        16 => grey_sd::<Frac, u16>(mesh, cam, spec, palette),
        32 => grey_sd::<Frac, u32>(mesh, cam, spec, palette),
        b => Err(format!("--depth-bits {b}: must be 16 or 32")),
    }
}

fn grey_sd<Frac: LeEqU32, D: Depth>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    palette: &GreyShades<Gray8>,
) -> Result<GreyFrame, String> {
    let mut storage = SceneStorage::new(data);
    let FrameInputs {
        mesh,
        adjacency,
        camera,
        settings,
        ..
    } = storage.scene(cam, spec)?;
    let (w, h) = (spec.width, spec.height);
    let mut buffers = IdBuffers::for_mesh(spec, mesh.vertices().len(), &mesh, &adjacency);
    let mut depth = vec![D::default(); buffers.ids.len()];
    let mut ws = buffers.depth_workspace(&mut depth);
    let mut sink = GreySink {
        width: w,
        height: h,
        grey: vec![palette.background(); w * h],
    };
    let mut renderer = Box::new(ZBufferRenderer::<Frac, EDGES, POLY>::new());
    let start = Instant::now();
    renderer
        .render_grey(
            &mesh,
            &adjacency,
            &camera,
            &settings,
            &mut ws,
            &mut vec![pbuffer::render::SmallFace::default(); mesh.face_count()],
            palette,
            &mut sink,
            &mut (),
        )
        .map_err(|e| e.to_string())?;
    let time_us = start.elapsed().as_micros() as u64;
    Ok(GreyFrame {
        width: w,
        height: h,
        grey: sink.grey,
        time_us,
    })
}

/// The shading of face `f` as the library computes it (|cos| of the angle between
/// its normal and the direction to the eye from its centroid, times 255, truncated),
/// in f64.
pub fn reference_shade(rf: &RefFrame, mesh: &MeshData, cam: &CameraSpec, f: usize) -> u8 {
    let n = rf.faces[f].normal;
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len <= 0.0 {
        return 0;
    }
    let face = &mesh.faces[f];
    let mut c = [0.0; 3];
    for &v in face {
        for (k, ck) in c.iter_mut().enumerate() {
            *ck += mesh.vertices[v as usize][k] / face.len() as f64;
        }
    }
    let d: [f64; 3] = match cam.projection {
        ProjectionSpec::Perspective { .. } => std::array::from_fn(|k| cam.eye[k] - c[k]),
        ProjectionSpec::Orthographic { .. } => std::array::from_fn(|k| cam.eye[k] - cam.target[k]),
    };
    let dl = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if dl <= 0.0 {
        return 0;
    }
    let cos = ((n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / (len * dl))
        .abs()
        .min(1.0);
    (cos * 255.0) as u8
}

/// The reference grey frame of surfaces (no lines): per pixel, the mean over the 16
/// sub-samples of the level of the nearest face there, or the background; rounded.
pub fn reference_grey(
    rf: &RefFrame,
    mesh: &MeshData,
    cam: &CameraSpec,
    palette: &GreyShades<Gray8>,
) -> Vec<u8> {
    let levels: Vec<u8> = (0..rf.faces.len())
        .map(|f| palette.face(f as u16, reference_shade(rf, mesh, cam, f)))
        .collect();
    let background = u32::from(palette.background());
    let mut out = vec![0u8; rf.width * rf.height];
    for j in 0..rf.height {
        for i in 0..rf.width {
            let mut sum = 0u32;
            for b in 0..4 {
                for a in 0..4 {
                    let x = i as f64 + (2 * a + 1) as f64 / 8.0;
                    let y = j as f64 + (2 * b + 1) as f64 / 8.0;
                    sum += rf
                        .nearest_face(x, y)
                        .map_or(background, |f| u32::from(levels[f]));
                }
            }
            out[j * rf.width + i] = ((sum + 8) / 16) as u8;
        }
    }
    out
}
