//! The library's 3-D pipeline on the host: `MeshData` and specs in, a `Frame` out.

use embedded_graphics::pixelcolor::BinaryColor;
use fixed::types::extra::{LeEqU32, U0, U1, U10, U11, U12, U2, U3, U4, U5, U6, U7, U8, U9};
use pbuffer::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use pbuffer::order::BspTree;
use pbuffer::render::{Depth, FrameProbe, RowCodes};
use pbuffer::{
    Camera, CodeFillRenderer, Cull, DrawMode, MonoPalette, Pattern, Projection, Settings, Span,
    SpanSink, Stats, Viewport, Visibility, ZBufferRenderer,
};

use crate::bsp::{with_bsp, BspFigures, DepthRanks};
use crate::frame::{
    CameraSpec, CullSpec, EngineSpec, Frame, MeshData, ModeSpec, ProjectionSpec, RenderSpec,
};
use crate::setup::{IdBuffers, Measured, Scene, SceneStorage};

/// Scan-converter edge capacity and clipped-polygon capacity used on the host.
pub(crate) const EDGES: usize = 512;
pub(crate) const POLY: usize = 512;
/// Code-fill engine on the host: active faces and edges. The code is 128 bits (4
/// words), as on firmware; a frame that needs more is rendered again with 1024.
pub const ACTIVE_FACES: usize = 2048;
pub const ACTIVE_EDGES: usize = 8192;

/// The host-only work inside the measured region of [`render_frame`] (the probe that
/// collects the `--ids`/`--lines` images and the per-pixel host span sink): callgrind
/// patterns that `report` passes as extra `--toggle-collect` options, so that
/// collection is off while they run and the count is the library's own work.
pub const EXCLUDED: [&str; 3] = [
    "*pipeline::Collect as*FrameProbe*row*",
    "*render::engines::fast::frame::probe_ids*",
    "*pipeline::PackedFrame as*SpanSink*fill_span*",
];

/// A packed 1-bpp frame of any size (the `PackedFramebuffer` layout), as a span sink.
#[derive(Debug)]
pub struct PackedFrame {
    pub width: usize,
    pub height: usize,
    pub bytes: Vec<u8>,
    pub spans: u64,
}

impl PackedFrame {
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            bytes: vec![0; width.div_ceil(8) * height],
            spans: 0,
        }
    }
}

impl SpanSink for PackedFrame {
    type Color = BinaryColor;
    type Error = std::convert::Infallible;

    fn viewport(&self) -> Viewport {
        Viewport {
            width: self.width as u16,
            height: self.height as u16,
        }
    }

    /// As `PackedFramebuffer` does it (counted: it is the firmware's work too).
    fn fill_mask(&mut self, y: u16, mask: &[u32], color: BinaryColor) -> Result<u32, Self::Error> {
        let stride = self.width.div_ceil(8);
        let y = usize::from(y);
        let Some(row) = self.bytes.get_mut(y * stride..(y + 1) * stride) else {
            return Ok(0);
        };
        let words = pbuffer::write_mask(row, self.width, mask, color.is_on());
        self.spans += u64::from(words);
        Ok(words)
    }

    fn fill_span(&mut self, span: Span, color: BinaryColor) -> Result<(), Self::Error> {
        self.spans += 1;
        let stride = self.width.div_ceil(8);
        for x in span.x0()..span.x1() {
            let i = usize::from(span.y()) * stride + usize::from(x) / 8;
            let m = 0x80u8 >> (x % 8);
            if color.is_on() {
                self.bytes[i] |= m;
            } else {
                self.bytes[i] &= !m;
            }
        }
        Ok(())
    }
}

/// Collects the `--ids` and `--lines` images.
pub(crate) struct Collect {
    width: usize,
    ids: Vec<u32>,
    lines: Vec<u8>,
}

impl Collect {
    /// Empty images of `width` x `height`.
    pub(crate) fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            ids: vec![0; width * height],
            lines: vec![0; width * height],
        }
    }
}

impl FrameProbe for Collect {
    /// Never inlined: `report` leaves it out of the instruction count
    /// (`--toggle-collect` on its symbol, see [`EXCLUDED`]).
    #[inline(never)]
    fn row(&mut self, y: u16, ids: &[u16], visible: &[u32], hidden: &[u32]) {
        let base = usize::from(y) * self.width;
        for (x, &id) in ids.iter().enumerate().take(self.width) {
            self.ids[base + x] = u32::from(id);
            let bit = |w: &[u32]| w.get(x / 32).is_some_and(|w| w & (1 << (x % 32)) != 0);
            self.lines[base + x] = if bit(visible) {
                1
            } else if bit(hidden) {
                2
            } else {
                0
            };
        }
    }
}

/// The library mesh's borrowed arrays, built from `MeshData`.
pub struct MeshArrays {
    pub vertices: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
    pub offsets: Vec<u32>,
}

impl MeshArrays {
    pub fn new(mesh: &MeshData) -> Self {
        let vertices = mesh.vertices.iter().map(|v| v.map(|c| c as f32)).collect();
        let mut indices = Vec::new();
        let mut offsets = vec![0u32];
        for f in &mesh.faces {
            indices.extend_from_slice(f);
            offsets.push(indices.len() as u32);
        }
        Self {
            vertices,
            indices,
            offsets,
        }
    }
}

/// Storage for building a mesh's edge adjacency: the weld map and half-edge records
/// (needed only while building) and the edge list (kept for rendering).
pub struct AdjacencyStorage {
    pub weld: Vec<u32>,
    pub scratch: Vec<HalfEdgeRecord>,
    pub edges: Vec<MeshEdge>,
}

impl AdjacencyStorage {
    /// Storage large enough for `arrays`.
    pub fn new(arrays: &MeshArrays) -> Self {
        Self {
            weld: vec![0; arrays.vertices.len()],
            scratch: vec![HalfEdgeRecord::default(); arrays.indices.len()],
            edges: vec![MeshEdge::default(); arrays.indices.len()],
        }
    }

    /// Builds the adjacency of `mesh` with crease angle `crease_deg`.
    pub fn build<'s>(
        &'s mut self,
        mesh: &Mesh<'_>,
        crease_deg: f64,
    ) -> Result<EdgeAdjacency<'s>, String> {
        EdgeAdjacency::build(
            mesh,
            crease_deg as f32,
            &mut self.weld,
            &mut self.scratch,
            &mut self.edges,
        )
        .map_err(|e| format!("adjacency: {e}"))
    }

    /// Bytes of the storage needed only while building (weld map, half-edge records).
    pub fn build_bytes(&self) -> usize {
        std::mem::size_of_val(self.weld.as_slice()) + std::mem::size_of_val(self.scratch.as_slice())
    }
}

/// The library camera of a `CameraSpec`.
pub fn camera(spec: &CameraSpec) -> Result<Camera, String> {
    let f = |v: [f64; 3]| v.map(|c| c as f32);
    let projection = match spec.projection {
        ProjectionSpec::Perspective { fov_deg } => Projection::Perspective {
            fov_y_deg: fov_deg as f32,
        },
        ProjectionSpec::Orthographic { half_height } => Projection::Orthographic {
            half_height: half_height as f32,
        },
    };
    Camera::new(
        f(spec.eye),
        f(spec.target),
        f(spec.up),
        projection,
        spec.near as f32,
        spec.far as f32,
    )
    .map_err(|e| format!("camera: {e}"))
}

/// The library settings of a `RenderSpec`.
pub fn settings(spec: &RenderSpec) -> Result<Settings, String> {
    let pattern = Pattern::by_name(&spec.pattern)
        .ok_or_else(|| format!("--pattern {}: unknown", spec.pattern))?;
    Ok(Settings {
        mode: match spec.mode {
            ModeSpec::Wireframe => DrawMode::Wireframe,
            ModeSpec::Hidden => DrawMode::HiddenRemoved,
            ModeSpec::Dashed => DrawMode::Dashed,
            ModeSpec::Surfaces => DrawMode::Surfaces,
            ModeSpec::SurfacesDashed => DrawMode::SurfacesDashed,
        },
        cull: match spec.cull {
            CullSpec::On => Cull::On,
            CullSpec::Off => Cull::Off,
            CullSpec::Auto => Cull::Auto,
        },
        pattern,
        dashes: spec.dashes,
    })
}

/// Renders with the library exactly as firmware would (fixed point, banded).
pub fn render_frame(mesh: &MeshData, cam: &CameraSpec, spec: &RenderSpec) -> Result<Frame, String> {
    // Far from the origin, or with huge faces: moved to a local origin and cut in
    // f64 first (the same picture).
    let aspect = spec.width as f64 / spec.height.max(1) as f64;
    if let Some((mesh, cam)) = crate::origin::localised(mesh, cam, aspect) {
        return render_local(&mesh, &cam, spec);
    }
    render_local(mesh, cam, spec)
}

fn render_local(mesh: &MeshData, cam: &CameraSpec, spec: &RenderSpec) -> Result<Frame, String> {
    match spec.subpixel {
        0 => render_s::<U0>(mesh, cam, spec),
        1 => render_s::<U1>(mesh, cam, spec),
        2 => render_s::<U2>(mesh, cam, spec),
        3 => render_s::<U3>(mesh, cam, spec),
        4 => render_s::<U4>(mesh, cam, spec),
        5 => render_s::<U5>(mesh, cam, spec),
        6 => render_s::<U6>(mesh, cam, spec),
        7 => render_s::<U7>(mesh, cam, spec),
        8 => render_s::<U8>(mesh, cam, spec),
        9 => render_s::<U9>(mesh, cam, spec),
        10 => render_s::<U10>(mesh, cam, spec),
        11 => render_s::<U11>(mesh, cam, spec),
        12 => render_s::<U12>(mesh, cam, spec),
        s => Err(format!("--subpixel {s}: must be 0 to 12")),
    }
}

fn render_s<Frac: LeEqU32>(
    mesh: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    if matches!(
        spec.engine,
        EngineSpec::CodeFill | EngineSpec::CodeFillCrossings | EngineSpec::Scanline
    ) {
        return match render_code::<Frac, 4>(mesh, cam, spec) {
            Err(e) if e.contains("surface code") => render_code::<Frac, 32>(mesh, cam, spec),
            other => other,
        };
    }
    if matches!(spec.engine, EngineSpec::Painter | EngineSpec::Bsp) {
        return crate::engines::render_painter::<Frac>(mesh, cam, spec);
    }
    if spec.engine == EngineSpec::Warnock {
        return crate::engines::render_warnock::<Frac>(mesh, cam, spec);
    }
    if spec.engine == EngineSpec::Newell {
        return crate::engines::render_newell_paint::<Frac>(mesh, cam, spec);
    }
    if spec.engine == EngineSpec::Fast {
        return crate::fast::render_fast::<Frac>(mesh, cam, spec);
    }
    if spec.engine == EngineSpec::Raycast {
        return crate::engines::render_raycast::<Frac>(mesh, cam, spec);
    }
    match spec.depth_bits {
        16 => render_sd::<Frac, u16>(mesh, cam, spec),
        32 => render_sd::<Frac, u32>(mesh, cam, spec),
        b => Err(format!("--depth-bits {b}: must be 16 or 32")),
    }
}

fn render_sd<Frac: LeEqU32, D: Depth>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let mut storage = SceneStorage::new(data);
    let Scene {
        mesh,
        adjacency,
        camera,
        settings,
        build_bytes,
    } = storage.scene(cam, spec)?;
    let mut buffers = IdBuffers::for_mesh(spec, mesh.vertices().len(), &mesh, &adjacency);
    let mut depth = vec![D::default(); buffers.ids.len()];
    let mut ws = buffers.depth_workspace(&mut depth);
    // Per frame: the lent workspace, the mesh's edge list and the renderer. The weld
    // map and half-edge records are needed only while the edge list is built (once
    // per mesh), so they are reported apart.
    let lent = ws.bytes() + std::mem::size_of_val(adjacency.edges());
    let mut renderer = Box::new(ZBufferRenderer::<Frac, EDGES, POLY>::new());
    let measured = Measured::run(spec.width, spec.height, |target, probe| {
        renderer.render(
            &mesh,
            &adjacency,
            &camera,
            &settings,
            &mut ws,
            &MonoPalette::default(),
            target,
            probe,
        )
    })?;
    let working = lent + std::mem::size_of::<ZBufferRenderer<Frac, EDGES, POLY>>();
    Ok(measured.frame(working, build_bytes))
}

/// The frame and its `--stats` figures.
#[allow(clippy::too_many_arguments)]
pub(crate) fn frame(
    w: usize,
    h: usize,
    probe: Collect,
    target: PackedFrame,
    stats: &Stats,
    working: usize,
    build_bytes: usize,
    time_us: u64,
) -> Frame {
    Frame {
        width: w,
        height: h,
        ids: probe.ids,
        lines: probe.lines,
        packed: target.bytes,
        stats: vec![
            ("faces".into(), u64::from(stats.faces)),
            ("faces_drawn".into(), u64::from(stats.faces_drawn)),
            ("feature_edges".into(), u64::from(stats.feature_edges)),
            ("spans".into(), u64::from(stats.spans)),
            ("bands".into(), u64::from(stats.bands)),
            ("band_rows".into(), u64::from(stats.band_rows)),
            (
                "depth_buffer_bytes".into(),
                u64::from(stats.depth_buffer_bytes),
            ),
            ("code_bits".into(), u64::from(stats.code_bits)),
            ("peak_active_faces".into(), u64::from(stats.peak_faces)),
            ("peak_active_edges".into(), u64::from(stats.peak_edges)),
            ("working_ram_bytes".into(), working as u64),
            ("adjacency_build_bytes".into(), build_bytes as u64),
            ("time_us".into(), time_us),
        ],
        depth_step: [stats.depth_step_near, stats.depth_step_far].map(f64::from),
    }
}

/// The code-fill engine: no depth buffer; ids for the band and its apron. `codefill`
/// and `codefill-crossings` render in the depth order of a BSP tree built once for the
/// mesh (its build is timed apart, its storage counted in the working RAM);
/// `scanline` compares planes where faces overlap.
fn render_code<Frac: LeEqU32, const WORDS: usize>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let mut storage = SceneStorage::new(data);
    let scene = storage.scene(cam, spec)?;
    if spec.engine == EngineSpec::Scanline {
        return render_code_with::<Frac, WORDS>(&scene, None, spec);
    }
    match with_bsp(&scene.mesh, |tree, figures| {
        render_code_with::<Frac, WORDS>(&scene, Some((tree, figures)), spec)
    }) {
        Ok(frame) => frame,
        // A mesh whose tree would need more fragments than face ids can name: the
        // same engine without an order (planes where faces overlap), said aloud.
        Err(e) => {
            eprintln!("note: {e}; rendering with --engine scanline instead");
            let mut frame = render_code_with::<Frac, WORDS>(&scene, None, spec)?;
            frame.stats.push(("depth_order_fallback".into(), 1));
            Ok(frame)
        }
    }
}

fn render_code_with<Frac: LeEqU32, const WORDS: usize>(
    scene: &Scene<'_>,
    bsp: Option<(&BspTree<'_>, BspFigures)>,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let Scene {
        mesh,
        adjacency,
        camera,
        settings,
        build_bytes,
    } = scene;
    let w = spec.width;
    let surfaces = bsp.map_or(*mesh, |(tree, _)| tree.fragments());
    let mut buffers = IdBuffers::for_mesh(spec, surfaces.vertices().len(), mesh, adjacency);
    let mut order = vec![0u32; surfaces.face_count()];
    let mut ws = buffers.code_workspace(&mut order);
    let lent = ws.bytes() + std::mem::size_of_val(adjacency.edges());
    type Engine<F, const W: usize> = CodeFillRenderer<F, W, ACTIVE_FACES, ACTIVE_EDGES, POLY>;
    let mut renderer = Box::new(Engine::<Frac, WORDS>::new());
    // Bit-sliced rows: every pixel's code, up to WORDS words, and a bit per pixel.
    let sliced = spec.engine == EngineSpec::CodeFill;
    let mut words = vec![
        0u32;
        if sliced {
            Engine::<Frac, WORDS>::bit_sliced_len(w)
        } else {
            0
        }
    ];
    let codes = if sliced {
        RowCodes::BitSliced(&mut words)
    } else {
        RowCodes::Crossings
    };
    // The depth order: one rank per fragment, and the walk's stack.
    let mut ranks = DepthRanks::new(bsp.map(|(tree, _)| tree));
    let mut codes = Some(codes);
    // The per-frame walk of the tree is part of the frame.
    let measured = Measured::run(w, spec.height, |target, probe| {
        let codes = codes.take().expect("the frame is drawn once");
        let visibility = match bsp {
            Some((tree, _)) => Visibility::Order(ranks.order(tree, &camera.viewpoint())?),
            None => Visibility::Planes,
        };
        renderer.render_with(
            mesh,
            adjacency,
            camera,
            settings,
            &mut ws,
            codes,
            visibility,
            &MonoPalette::default(),
            target,
            probe,
        )
    })?;
    let stats = measured.stats;
    let order_bytes = bsp.map_or(0, |(_, f)| f.kept_bytes) + ranks.bytes();
    let lent = lent + std::mem::size_of_val(words.as_slice()) + order_bytes;
    // The engine this frame needed: its peak active faces and edges, not the host's
    // capacities.
    let working = lent
        + Engine::<Frac, WORDS>::bytes_for(stats.peak_faces as usize, stats.peak_edges as usize);
    let mut frame = measured.frame(working, *build_bytes);
    if let Some((_, f)) = bsp {
        frame.stats.extend([
            ("bsp_fragments".into(), f.fragments as u64),
            ("bsp_splits".into(), f.splits as u64),
            ("bsp_depth".into(), f.depth as u64),
            ("bsp_bytes".into(), f.kept_bytes as u64),
            ("bsp_build_work_bytes".into(), f.work_bytes as u64),
            ("bsp_build_us".into(), f.build_us),
        ]);
    }
    Ok(frame)
}
