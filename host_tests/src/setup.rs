//! The library's engines set up on the host, once for every engine: the mesh, its
//! edge adjacency, camera and settings ([`FrameInputs`], built in [`SceneStorage`] from the
//! specs by [`camera`] and [`settings`]), the lent buffers of a frame ([`IdBuffers`]),
//! the host's span sink and probe ([`PackedFrame`], `Collect`) and one frame drawn in
//! the measured region ([`Measured`]). [`crate::pipeline`] picks the engine; every
//! driver starts here.

use std::cell::RefCell;
use std::time::Instant;

use embedded_graphics::pixelcolor::BinaryColor;
use pbuffer::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use pbuffer::render::{FrameProbe, IdWorkspace, ProjectedVertex};
use pbuffer::{
    Camera, CodeWorkspace, Cull, DrawMode, Pattern, Projection, Settings, Span, SpanSink, Stats,
    Viewport, Workspace,
};

use crate::frame::{CameraSpec, CullSpec, Frame, MeshData, ModeSpec, ProjectionSpec, RenderSpec};
use crate::measure::measured_region;

/// The owned storage behind a [`FrameInputs`]: the mesh's arrays, its faces' planarity
/// and its adjacency's.
pub struct SceneStorage {
    pub arrays: MeshArrays,
    /// Which faces are planar ([`pbuffer::order::planar_faces`]), kept with the mesh
    /// ([`Mesh::with_planar_faces`]) as firmware keeps them: part of the mesh, made
    /// once (by the first `scene`), not of a frame.
    pub planar: Vec<u32>,
    planar_made: bool,
    pub adjacency: AdjacencyStorage,
}

thread_local! {
    /// The parts of the meshes drawn on this thread, while [`with_parts`] runs.
    static PARTS: RefCell<Option<Vec<PartSize>>> = const { RefCell::new(None) };
}

/// One part of a union mesh: its vertices and faces, which follow the part before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PartSize {
    pub vertices: usize,
    pub faces: usize,
}

/// Runs `f` with every mesh it sets up ([`SceneStorage::new`]) taken as the union of
/// `parts`, one after the other, when the sizes add up to the mesh's: its edges are
/// then made per part (vertices weld only within a part, a crease or silhouette never
/// joins two parts), as `pbuffer::scene` defines a scene's frame. So every engine,
/// handed the union by `render_frame`, draws a scene's lines as the library's
/// `SceneDrawing` does. A mesh of other sizes (a far scene whose huge faces were cut)
/// is one mesh, as before. A thread-local rather than a parameter: every engine of
/// the pipeline starts at `SceneStorage::new`, and a scene is the only caller.
pub fn with_parts<R>(parts: &[PartSize], f: impl FnOnce() -> R) -> R {
    struct Reset;
    impl Drop for Reset {
        fn drop(&mut self) {
            PARTS.with(|p| p.borrow_mut().take());
        }
    }
    PARTS.with(|p| *p.borrow_mut() = Some(parts.to_vec()));
    let _reset = Reset;
    f()
}

impl SceneStorage {
    /// Storage for `data` (as the union of parts inside [`with_parts`]).
    pub fn new(data: &MeshData) -> Self {
        let arrays = MeshArrays::new(data);
        let mut adjacency = AdjacencyStorage::new(&arrays);
        let parts = PARTS.with(|p| p.borrow().clone()).unwrap_or_default();
        let sum = |f: fn(&PartSize) -> usize| parts.iter().map(f).sum::<usize>();
        if sum(|p| p.vertices) == data.vertices.len() && sum(|p| p.faces) == data.faces.len() {
            adjacency.parts = parts;
        }
        let planar = vec![0; pbuffer::mesh::planar_words(arrays.offsets.len().saturating_sub(1))];
        Self {
            arrays,
            planar,
            planar_made: false,
            adjacency,
        }
    }

    /// The library mesh (its faces' planarity kept), its adjacency (crease angle
    /// `spec.crease_deg`), the camera of `cam` and the settings of `spec`, in that
    /// order (the first error is returned).
    pub fn scene(
        &mut self,
        cam: &CameraSpec,
        spec: &RenderSpec,
    ) -> Result<FrameInputs<'_>, String> {
        let arrays = &self.arrays;
        let mesh = Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets)
            .map_err(|e| format!("mesh: {e}"))?;
        if !self.planar_made {
            pbuffer::order::planar_faces(&mesh, &mut self.planar)
                .map_err(|e| format!("mesh: {e}"))?;
            self.planar_made = true;
        }
        let mesh = mesh
            .with_planar_faces(&self.planar)
            .map_err(|e| format!("mesh: {e}"))?;
        let build_bytes = self.adjacency.build_bytes();
        let adjacency = self.adjacency.build(&mesh, spec.crease_deg)?;
        Ok(FrameInputs {
            mesh,
            adjacency,
            camera: camera(cam)?,
            settings: settings(spec)?,
            build_bytes,
        })
    }
}

/// What every engine renders from: the mesh, its adjacency, the camera, the settings.
pub struct FrameInputs<'s> {
    pub mesh: Mesh<'s>,
    pub adjacency: EdgeAdjacency<'s>,
    pub camera: Camera,
    pub settings: Settings,
    /// Bytes of the adjacency storage needed only while building it (weld map,
    /// half-edge records): once per mesh, reported apart from the working RAM.
    pub build_bytes: usize,
}

/// Lent buffers of an id-filling frame, sized for `vertices` vertex positions.
pub(crate) struct IdBuffers {
    pub vertices: Vec<ProjectedVertex>,
    pub drawn: Vec<u32>,
    pub features: Vec<u32>,
    pub ids: Vec<u16>,
    pub lines: Vec<u32>,
}

impl IdBuffers {
    pub fn new(spec: &RenderSpec, vertices: usize, faces: usize, edges: usize) -> Self {
        let band = spec.band.clamp(1, spec.height.max(1));
        Self::sized(spec.width, spec.height, band, vertices, faces, edges)
    }

    /// Buffers for drawing `vertices` vertex positions of `mesh`, with its `adjacency`.
    pub fn for_mesh(
        spec: &RenderSpec,
        vertices: usize,
        mesh: &Mesh<'_>,
        adjacency: &EdgeAdjacency<'_>,
    ) -> Self {
        Self::new(spec, vertices, mesh.face_count(), adjacency.edges().len())
    }

    /// Buffers for a `w` x `h` frame drawn in bands of `band` rows.
    pub fn sized(
        w: usize,
        h: usize,
        band: usize,
        vertices: usize,
        faces: usize,
        edges: usize,
    ) -> Self {
        let stored = usize::from(pbuffer::render::storage_rows(band as u16, h as u16));
        Self {
            vertices: vec![ProjectedVertex::default(); vertices],
            drawn: vec![0; faces.div_ceil(32)],
            features: vec![0; edges.div_ceil(32)],
            ids: vec![0; w * stored],
            lines: vec![0; 2 * w.div_ceil(32) * band],
        }
    }

    pub fn workspace(&mut self) -> IdWorkspace<'_> {
        IdWorkspace {
            vertices: &mut self.vertices,
            drawn: &mut self.drawn,
            features: &mut self.features,
            ids: &mut self.ids,
            lines: &mut self.lines,
        }
    }

    /// The Z-buffer's workspace: these buffers and `depth` (one per id).
    pub fn depth_workspace<'a, D>(&'a mut self, depth: &'a mut [D]) -> Workspace<'a, D> {
        Workspace {
            vertices: &mut self.vertices,
            drawn: &mut self.drawn,
            features: &mut self.features,
            depth,
            ids: &mut self.ids,
            lines: &mut self.lines,
        }
    }

    /// The code-fill engine's workspace: these buffers and `order` (one per surface).
    pub fn code_workspace<'a>(&'a mut self, order: &'a mut [u32]) -> CodeWorkspace<'a> {
        CodeWorkspace {
            vertices: &mut self.vertices,
            drawn: &mut self.drawn,
            features: &mut self.features,
            order,
            ids: &mut self.ids,
            lines: &mut self.lines,
        }
    }
}

/// One frame drawn: the target, the probe's images, the stats and the time it took.
pub(crate) struct Measured {
    pub target: PackedFrame,
    pub probe: Collect,
    pub stats: Stats,
    pub time_us: u64,
}

impl Measured {
    /// Draws once with `draw` into a new `w` x `h` target and probe, inside
    /// [`measured_region`] (only `draw` is counted).
    pub fn run(
        w: usize,
        h: usize,
        mut draw: impl FnMut(&mut PackedFrame, &mut Collect) -> Result<Stats, pbuffer::Error>,
    ) -> Result<Self, String> {
        let mut target = PackedFrame::new(w, h);
        let mut probe = Collect::new(w, h);
        let start = Instant::now();
        let mut result = None;
        measured_region(&mut || {
            result = Some(draw(&mut target, &mut probe));
        });
        let stats = result
            .expect("the measured region ran")
            .map_err(|e| format!("render: {e}"))?;
        let time_us = start.elapsed().as_micros() as u64;
        Ok(Self {
            target,
            probe,
            stats,
            time_us,
        })
    }

    /// The frame and its `--stats` figures (see [`frame`]).
    pub fn frame(self, working: usize, build_bytes: usize) -> Frame {
        let (w, h) = (self.target.width, self.target.height);
        frame(
            w,
            h,
            self.probe,
            self.target,
            &self.stats,
            working,
            build_bytes,
            self.time_us,
        )
    }
}

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
    "*setup::Collect as*FrameProbe*row*",
    "*render::engines::fast::frame::probe_ids*",
    "*setup::PackedFrame as*SpanSink*fill_span*",
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
/// (needed only while building) and the edge list (kept for rendering); and the parts
/// whose edges are made one by one (none: one mesh).
pub struct AdjacencyStorage {
    pub weld: Vec<u32>,
    pub scratch: Vec<HalfEdgeRecord>,
    pub edges: Vec<MeshEdge>,
    pub parts: Vec<PartSize>,
}

impl AdjacencyStorage {
    /// Storage large enough for `arrays`.
    pub fn new(arrays: &MeshArrays) -> Self {
        Self {
            weld: vec![0; arrays.vertices.len()],
            scratch: vec![HalfEdgeRecord::default(); arrays.indices.len()],
            edges: vec![MeshEdge::default(); arrays.indices.len()],
            parts: Vec::new(),
        }
    }

    /// Builds the adjacency of `mesh` with crease angle `crease_deg`: of each part
    /// alone, the lists joined (`EdgeAdjacency::from_edges`), when it has parts.
    pub fn build<'s>(
        &'s mut self,
        mesh: &Mesh<'_>,
        crease_deg: f64,
    ) -> Result<EdgeAdjacency<'s>, String> {
        if self.parts.len() > 1 {
            return self.build_parts(mesh, crease_deg);
        }
        EdgeAdjacency::build(
            mesh,
            crease_deg as f32,
            &mut self.weld,
            &mut self.scratch,
            &mut self.edges,
        )
        .map_err(|e| format!("adjacency: {e}"))
    }

    /// [`build`](Self::build) part by part: each part's faces and vertices as a mesh
    /// of their own, its edges shifted to the union's numbers. The parts' vertices
    /// come one after the other, so the joined list stays sorted by its ends.
    fn build_parts<'s>(
        &'s mut self,
        mesh: &Mesh<'_>,
        crease_deg: f64,
    ) -> Result<EdgeAdjacency<'s>, String> {
        let (all, offsets) = (mesh.indices(), mesh.face_offsets());
        let (mut v0, mut f0, mut count) = (0usize, 0usize, 0usize);
        for part in &self.parts {
            let (c0, c1) = (offsets[f0] as usize, offsets[f0 + part.faces] as usize);
            let vertices = &mesh.vertices()[v0..v0 + part.vertices];
            let indices: Vec<u32> = all[c0..c1].iter().map(|&i| i - v0 as u32).collect();
            let starts: Vec<u32> = offsets[f0..=f0 + part.faces]
                .iter()
                .map(|&o| o - c0 as u32)
                .collect();
            let one = Mesh::new(vertices, &indices, &starts).map_err(|e| format!("part: {e}"))?;
            let (weld, scratch) = (&mut self.weld[..part.vertices], &mut self.scratch);
            let edges = &mut self.edges[count..];
            let built = EdgeAdjacency::build(&one, crease_deg as f32, weld, scratch, edges)
                .map_err(|e| format!("adjacency: {e}"))?;
            let made = built.edges().len();
            for e in &mut self.edges[count..count + made] {
                (e.a, e.b) = (e.a + v0 as u32, e.b + v0 as u32);
                e.faces = e.faces.map(|f| f + f0 as u32);
            }
            (v0, f0, count) = (v0 + part.vertices, f0 + part.faces, count + made);
        }
        EdgeAdjacency::from_edges(mesh, &self.edges[..count]).map_err(|e| format!("adjacency: {e}"))
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
        lines: spec.lines,
    })
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
        ]
        .into_iter()
        .chain(segment_stats(&stats.segments))
        .collect(),
        depth_step: [stats.depth_step_near, stats.depth_step_far].map(f64::from),
    }
}

/// The `--stats` figures of hidden lines by the segment (none when the
/// per-pixel test drew the lines).
fn segment_stats(s: &pbuffer::render::SegmentStats) -> Vec<(String, u64)> {
    if s.drawn == 0 && s.fallback == 0 {
        return Vec::new();
    }
    [
        ("segment_drawn_edges", s.drawn),
        ("segment_contours", s.contours),
        ("segment_pair_tests", s.pair_tests),
        ("segment_crossings", s.crossings),
        ("segment_nearer_crossings", s.nearer),
        ("segment_piercings", s.piercings),
        ("segment_kept_crossings", s.kept),
        ("segment_grid_entries", s.grid_entries),
        ("segment_boundaries", s.boundaries),
        ("segment_seeds", s.seeds),
        ("segment_reseeds", s.reseeds),
        ("segment_negative_counts", s.negative),
        ("segment_point_triangles", s.point_triangles),
        ("segment_fallback", s.fallback),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), u64::from(v)))
    .collect()
}
