//! The fast engine on the host: the mesh baked as firmware bakes it in `build.rs`
//! (`BakedMesh::bake`, outside the frame), then one frame drawn by `FastRenderer`
//! with its lent storage sized for the mesh and the frame.

use fixed::types::extra::LeEqU32;
use std::cell::Cell;

use pbuffer::render::Cull;
use pbuffer::render::{
    BakedMesh, CompactEdge, Contour, Crossing, DashPhase, FacePlane, FastRenderer, FastVertex,
    FastWorkspace, Piercing, Run, SegmentLists, SegmentWorkspace, Segments, VertexFaces,
    MAX_GRID_CELLS, NO_HOLE,
};
use pbuffer::{Dashes, MonoPalette};

use crate::frame::{CameraSpec, Frame, MeshData, RenderSpec};
use crate::qi::{QiCounts, QiFrame, QiMesh};
use crate::setup::{FrameInputs, Measured, SceneStorage};

/// Active facets and lines the host engine has room for.
pub const FACETS: usize = 4096;
pub const LINES: usize = 4096;

thread_local! {
    /// Set by [`with_segment_lines`]: the line pixels are classified again by the
    /// segment prototype ([`crate::qi`]), and its counts summed here.
    static SEGMENT_LINES: Cell<bool> = const { Cell::new(false) };
    static SEGMENT_COUNTS: Cell<QiCounts> = const { Cell::new(QiCounts {
        drawn: 0, contours: 0, box_pairs: 0, crossings: 0, nearer: 0, seeds: 0,
        reseeds: 0, negative: 0, fallback: 0, point_faces: 0, piercings: 0, checked: 0, mismatched: 0,
    }) };
    /// Set by [`with_every_back_face`]: the baked holes' labels are dropped.
    static EVERY_BACK_FACE: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f` with the fast engine drawing every back face (its mesh baked
/// without hole labels), on this thread: to check that skipping the back faces
/// away from the holes changes no pixel.
pub fn with_every_back_face<T>(f: impl FnOnce() -> T) -> T {
    EVERY_BACK_FACE.with(|c| c.set(true));
    let out = f();
    EVERY_BACK_FACE.with(|c| c.set(false));
    out
}

/// Runs `f` with the fast engine's line pixels classified by the segment
/// prototype ([`crate::qi`]) on this thread; returns what `f` returns and the
/// prototype's counts summed over its frames.
pub fn with_segment_lines<T>(f: impl FnOnce() -> T) -> (T, QiCounts) {
    SEGMENT_LINES.with(|c| c.set(true));
    SEGMENT_COUNTS.with(|c| c.set(QiCounts::default()));
    let out = f();
    SEGMENT_LINES.with(|c| c.set(false));
    (out, SEGMENT_COUNTS.with(Cell::get))
}

/// The fast engine's per-mesh constants, owned.
pub struct Baked {
    pub planes: Vec<FacePlane>,
    pub edges: Vec<CompactEdge>,
}

impl Baked {
    /// Bakes `scene`'s mesh and edge list.
    pub fn new(scene: &FrameInputs<'_>) -> Result<Self, String> {
        let mut planes = vec![FacePlane::default(); scene.mesh.face_count()];
        let mut edges = vec![CompactEdge::default(); scene.adjacency.edges().len()];
        BakedMesh::bake(&scene.mesh, &scene.adjacency, &mut planes, &mut edges)
            .map_err(|e| format!("bake: {e}"))?;
        Ok(Self { planes, edges })
    }
}

/// Lent buffers of a fast frame.
pub struct FastBuffers {
    pub vertices: Vec<FastVertex>,
    pub facing: Vec<u32>,
    pub face_links: Vec<u16>,
    pub line_links: Vec<u16>,
    pub heads: Vec<u16>,
    pub row: Vec<u32>,
    pub masks: Vec<u32>,
    pub pool: Vec<FastVertex>,
    pub ids: Vec<u16>,
    pub slopes: Vec<u16>,
    pub phases: Vec<DashPhase>,
    pub segments: SegmentBuffers,
}

/// Lent buffers of hidden lines by the segment, sized for any host frame.
pub struct SegmentBuffers {
    pub contours: Vec<Contour>,
    pub stamps: Vec<u16>,
    pub crossings: Vec<Crossing>,
    pub cells: Vec<u16>,
    pub entries: Vec<u16>,
    pub runs: Vec<Run>,
    pub counts: Vec<i16>,
    pub queue: Vec<u16>,
    pub starts: Vec<u16>,
    pub at: Vec<u16>,
    pub marks: Vec<u32>,
}

impl SegmentBuffers {
    /// Room for a mesh of `vertices`, `faces` and `edges`: every side a contour,
    /// and up to 65,535 crossings and grid entries.
    pub fn new(vertices: usize, faces: usize, edges: usize) -> Self {
        let contours = edges + 2 * faces;
        Self {
            contours: vec![Contour::default(); contours],
            stamps: vec![0; contours],
            crossings: vec![Crossing::default(); 65_535],
            cells: vec![0; MAX_GRID_CELLS + 1],
            entries: vec![0; 65_535],
            runs: vec![Run::default(); edges],
            counts: vec![0; vertices],
            queue: vec![0; vertices],
            starts: vec![0; vertices + 1],
            at: vec![0; 2 * edges],
            marks: vec![0; vertices.div_ceil(32)],
        }
    }

    pub fn segments(&mut self) -> Segments<'_> {
        Segments {
            lists: SegmentLists::new(
                &mut self.contours,
                &mut self.stamps,
                &mut self.crossings,
                &mut self.cells,
                &mut self.entries,
            )
            .expect("sized"),
            work: SegmentWorkspace {
                runs: &mut self.runs,
                counts: &mut self.counts,
                queue: &mut self.queue,
                starts: &mut self.starts,
                at: &mut self.at,
                marks: &mut self.marks,
            },
        }
    }
}

impl FastBuffers {
    /// Sized for `mesh` at `w` x `h`, with `pool` clipped corners.
    pub fn new(
        vertices: usize,
        faces: usize,
        edges: usize,
        w: usize,
        h: usize,
        pool: usize,
    ) -> Self {
        Self {
            vertices: vec![FastVertex::default(); vertices],
            facing: vec![0; faces.div_ceil(32)],
            face_links: vec![0; faces],
            line_links: vec![0; edges],
            heads: vec![0; 2 * h],
            row: vec![0; w],
            // Visible, hidden and the gaps of dashes along the edges.
            masks: vec![0; 3 * w.div_ceil(32)],
            pool: vec![FastVertex::default(); pool],
            ids: vec![0; w],
            slopes: vec![0; faces],
            // Room for the dash phases of `LINES` lines (engines with fewer use
            // a part).
            phases: vec![DashPhase::SCREEN; LINES],
            segments: SegmentBuffers::new(vertices, faces, edges),
        }
    }

    pub fn workspace(&mut self) -> FastWorkspace<'_> {
        FastWorkspace {
            vertices: &mut self.vertices,
            facing: &mut self.facing,
            face_links: &mut self.face_links,
            line_links: &mut self.line_links,
            heads: &mut self.heads,
            row: &mut self.row,
            masks: &mut self.masks,
            pool: &mut self.pool,
            ids: &mut self.ids,
            slopes: &mut self.slopes,
            phases: &mut self.phases,
            segments: Some(self.segments.segments()),
        }
    }
}

/// `fast`: one frame of the fast engine.
pub(crate) fn render_fast<Frac: LeEqU32>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let mut storage = SceneStorage::new(data);
    let scene = storage.scene(cam, spec)?;
    let mut baked = Baked::new(&scene)?;
    if EVERY_BACK_FACE.with(Cell::get) {
        for e in &mut baked.edges {
            e.hole = NO_HOLE;
        }
    }
    let mut weld = vec![0u16; scene.mesh.vertices().len()];
    let mut starts = vec![0u16; scene.mesh.vertices().len() + 1];
    let mut around = vec![0u16; scene.mesh.indices().len()];
    let mut irregular = vec![0u32; scene.mesh.vertices().len().div_ceil(32)];
    let faces_around = VertexFaces::bake(
        &scene.mesh,
        &mut weld,
        &mut starts,
        &mut around,
        &mut irregular,
    )
    .map_err(|e| format!("vertex faces: {e}"))?;
    let mut pairs = vec![Piercing::default(); 1 << 16];
    let n = Piercing::bake(&scene.mesh, &baked.edges, &mut pairs)
        .map_err(|e| format!("piercings: {e}"))?;
    pairs.truncate(n);
    let mesh = BakedMesh::new(scene.mesh, &baked.planes, &baked.edges)
        .and_then(|m| m.with_vertex_faces(faces_around))
        .and_then(|m| m.with_piercings(&pairs))
        .map_err(|e| format!("baked mesh: {e}"))?;
    let (w, h) = (spec.width, spec.height);
    // Room for every face clipped, with six cut corners each.
    let pool = scene.mesh.indices().len() + 6 * scene.mesh.face_count();
    let mut buffers = FastBuffers::new(
        scene.mesh.vertices().len(),
        scene.mesh.face_count(),
        baked.edges.len(),
        w,
        h,
        pool,
    );
    let mut ws = buffers.workspace();
    let mut renderer = Box::new(FastRenderer::<Frac, FACETS, LINES>::new());
    let measured = Measured::run(w, h, |target, probe| {
        renderer.render(
            &mesh,
            &scene.camera,
            &scene.settings,
            &mut ws,
            &MonoPalette::default(),
            target,
            probe,
        )
    })?;
    // Working RAM: the lent buffers (the pool and ids at what this frame needs:
    // none clipped here is 0; the gap mask and the dash phases only with dashes
    // along the edges) and the active lists at this frame's peaks.
    let stats = measured.stats;
    let along = matches!(scene.settings.dashes, Dashes::Along { .. });
    let unused = if along {
        0
    } else {
        std::mem::size_of_val(ws.phases) + 4 * w.div_ceil(32)
    };
    // The segment storage at this frame's need when the segment path drew (its
    // lists at their peaks, the mesh-sized part whole), else none.
    let segments = ws
        .segments
        .as_ref()
        .map_or(0, |s| s.lists.bytes() + s.work.bytes());
    let seg = &stats.segments;
    let segment_need = match &ws.segments {
        Some(s) if seg.drawn > 0 => {
            use std::mem::size_of;
            s.work.bytes()
                + seg.contours as usize * (size_of::<Contour>() + size_of::<u16>())
                + seg.kept as usize * size_of::<Crossing>()
                + (seg.grid_entries as usize + MAX_GRID_CELLS + 1) * size_of::<u16>()
        }
        _ => 0,
    };
    let lent = ws.bytes()
        - std::mem::size_of_val(ws.pool)
        - std::mem::size_of_val(ws.ids)
        - unused
        - segments
        + segment_need;
    let working = lent
        + FastRenderer::<Frac, FACETS, LINES>::bytes_for(
            stats.peak_faces as usize,
            stats.peak_edges as usize,
        );
    let mut frame = measured.frame(working, scene.build_bytes);
    if SEGMENT_LINES.with(Cell::get) {
        let cull = match scene.settings.cull {
            Cull::On => true,
            Cull::Off => false,
            Cull::Auto => scene.adjacency.is_closed(),
        };
        let qmesh = QiMesh::new(&scene.mesh, &scene.adjacency);
        let qf = QiFrame {
            mesh: &qmesh,
            cache: &buffers.vertices,
            facing: &buffers.facing,
            cull,
            s: Frac::U32,
            width: w,
            height: h,
        };
        let mut lines = vec![0u8; w * h];
        let mut counts = QiCounts::default();
        if qf
            .classify(
                &mut lines,
                &mut counts,
                std::env::var_os("PBUFFER_SEGMENT_CHECK").is_some(),
            )
            .is_some()
        {
            frame.lines = lines;
        }
        SEGMENT_COUNTS.with(|c| {
            let mut all = c.get();
            all.add(&counts);
            c.set(all);
        });
    }
    Ok(frame)
}
