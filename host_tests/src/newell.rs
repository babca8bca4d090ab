//! The library's Newell depth sort on the host: storage grown until the sort fits,
//! and a frame rendered by the code-fill engine in that order (`Visibility::Order`),
//! as `pipeline` renders in a BSP tree's order.

use std::time::Instant;

use fixed::types::extra::{LeEqU32, U0, U1, U10, U11, U12, U2, U3, U4, U5, U6, U7, U8, U9};
use pbuffer::mesh::Mesh;
use pbuffer::order::{NewellOrder, NewellSizes, NewellStorage};
use pbuffer::render::{FrameProbe, ProjectedVertex, RowCodes};
use pbuffer::{Camera, CodeFillRenderer, CodeWorkspace, Error, MonoPalette, Visibility};

use crate::frame::{CameraSpec, CullSpec, EngineSpec, Frame, MeshData, RenderSpec};
use crate::pipeline::{
    camera, settings, AdjacencyStorage, MeshArrays, PackedFrame, ACTIVE_EDGES, ACTIVE_FACES,
};

/// One sort's figures.
#[derive(Clone, Copy, Debug, Default)]
pub struct NewellFigures {
    /// Bytes the order keeps for rendering (fragment vertices, indices, offsets,
    /// sources and ranks).
    pub kept_bytes: usize,
    /// Bytes of all the lent storage (the sizes that fitted).
    pub storage_bytes: usize,
    pub fragments: usize,
    pub drawn: usize,
    pub splits: usize,
    pub shuffles: usize,
    pub unresolved: usize,
    /// Time of the sort that fitted.
    pub sort_us: u64,
}

/// Owned storage for one sort, sized by [`NewellSizes`].
pub struct NewellBuffers {
    vertices: Vec<[f32; 3]>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
    source: Vec<u16>,
    rank: Vec<u32>,
    seams: Vec<[u32; 2]>,
    boxes: Vec<[f32; 6]>,
    work: Vec<u32>,
}

impl NewellBuffers {
    /// Buffers of exactly these sizes.
    pub fn new(sizes: NewellSizes) -> Self {
        Self {
            vertices: vec![[0f32; 3]; sizes.vertices],
            indices: vec![0u32; sizes.indices],
            offsets: vec![0u32; sizes.offsets],
            source: vec![0u16; sizes.source],
            rank: vec![0u32; sizes.rank],
            seams: vec![[0u32; 2]; sizes.seams],
            boxes: vec![[0f32; 6]; sizes.boxes],
            work: vec![0u32; sizes.work],
        }
    }

    /// Bytes of all the buffers.
    pub fn bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(self.vertices.as_slice())
            + size_of_val(self.indices.as_slice())
            + size_of_val(self.offsets.as_slice())
            + size_of_val(self.source.as_slice())
            + size_of_val(self.rank.as_slice())
            + size_of_val(self.seams.as_slice())
            + size_of_val(self.boxes.as_slice())
            + size_of_val(self.work.as_slice())
    }

    /// Sorts `mesh` for `camera` into these buffers.
    pub fn sort(
        &mut self,
        mesh: &Mesh<'_>,
        camera: &Camera,
        cull: bool,
    ) -> Result<NewellOrder<'_>, Error> {
        NewellOrder::sort(
            mesh,
            camera,
            cull,
            NewellStorage {
                vertices: &mut self.vertices,
                indices: &mut self.indices,
                offsets: &mut self.offsets,
                source: &mut self.source,
                rank: &mut self.rank,
                seams: &mut self.seams,
                boxes: &mut self.boxes,
                work: &mut self.work,
            },
        )
    }
}

/// Sorts `mesh` for the view of `camera` (growing the lent storage from a guess of
/// one split per 4 faces until it fits) and hands the order to `f`. `cull`: leave
/// out the faces that do not face the eye, as the renderer does
/// (`Cull::Auto` = the mesh is closed).
pub fn with_newell<R>(
    mesh: &Mesh<'_>,
    camera: &Camera,
    cull: bool,
    f: impl FnOnce(&NewellOrder<'_>, NewellFigures) -> R,
) -> Result<R, String> {
    let mut splits = mesh.face_count() / 4 + 16;
    for _ in 0..16 {
        let sizes = NewellSizes::for_mesh(
            mesh.vertices().len(),
            mesh.face_count(),
            mesh.indices().len(),
            splits,
        );
        let mut buffers = NewellBuffers::new(sizes);
        let storage_bytes = buffers.bytes();
        let start = Instant::now();
        let sorted = buffers.sort(mesh, camera, cull);
        let sort_us = start.elapsed().as_micros() as u64;
        match sorted {
            Ok(order) => {
                let frags = order.fragments();
                let kept_bytes = std::mem::size_of_val(frags.vertices())
                    + std::mem::size_of_val(frags.indices())
                    + std::mem::size_of_val(frags.face_offsets())
                    + std::mem::size_of_val(order.source())
                    + std::mem::size_of_val(order.rank());
                let figures = NewellFigures {
                    kept_bytes,
                    storage_bytes,
                    fragments: order.fragment_count(),
                    drawn: order.drawn(),
                    splits: order.splits(),
                    shuffles: order.shuffles(),
                    unresolved: order.unresolved(),
                    sort_us,
                };
                return Ok(f(&order, figures));
            }
            Err(Error::CapacityExceeded { .. }) => splits = 2 * splits + 64,
            Err(e) => return Err(format!("Newell sort: {e}")),
        }
    }
    Err("Newell sort: storage for 2^16 times the first guess of splits was not enough".into())
}

/// The culling the renderer applies for `spec` (auto: closed meshes).
pub fn culls(spec: &RenderSpec, closed: bool) -> bool {
    match spec.cull {
        CullSpec::On => true,
        CullSpec::Off => false,
        CullSpec::Auto => closed,
    }
}

/// Renders with the code-fill engine in Newell's depth order, sorted for this
/// frame's view (the sort is inside the timed frame): bit-sliced rows for
/// `EngineSpec::CodeFill`, crossings otherwise. The frame's stats add
/// `newell_fragments`, `newell_splits`, `newell_shuffles`, `newell_unresolved`,
/// `newell_bytes` and `newell_sort_us`.
pub fn render_newell_frame(
    mesh: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
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
    match render_newell::<Frac, 4>(mesh, cam, spec) {
        Err(e) if e.contains("surface code") => render_newell::<Frac, 32>(mesh, cam, spec),
        other => other,
    }
}

fn render_newell<Frac: LeEqU32, const WORDS: usize>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let arrays = MeshArrays::new(data);
    let mesh = Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets)
        .map_err(|e| format!("mesh: {e}"))?;
    let mut storage = AdjacencyStorage::new(&arrays);
    let build_bytes = storage.build_bytes();
    let adjacency = storage.build(&mesh, spec.crease_deg)?;
    let camera = camera(cam)?;
    let settings = settings(spec)?;
    let cull = culls(spec, adjacency.is_closed());
    let (w, h) = (spec.width, spec.height);
    let band = spec.band.clamp(1, h.max(1));
    let row_words = w.div_ceil(32);
    let start = Instant::now();
    with_newell(&mesh, &camera, cull, |order, figures| {
        let surfaces = order.fragments();
        let mut vertices = vec![ProjectedVertex::default(); surfaces.vertices().len()];
        let mut drawn = vec![0u32; mesh.face_count().div_ceil(32)];
        let mut features = vec![0u32; adjacency.edges().len().div_ceil(32)];
        let mut order_words = vec![0u32; surfaces.face_count()];
        let stored = usize::from(pbuffer::render::storage_rows(band as u16, h as u16));
        let mut ids = vec![0u16; w * stored];
        let mut lines = vec![0u32; 2 * row_words * band];
        let mut ws = CodeWorkspace {
            vertices: &mut vertices,
            drawn: &mut drawn,
            features: &mut features,
            order: &mut order_words,
            ids: &mut ids,
            lines: &mut lines,
        };
        type Engine<F, const W: usize> = CodeFillRenderer<F, W, ACTIVE_FACES, ACTIVE_EDGES, 512>;
        let mut renderer = Box::new(Engine::<Frac, WORDS>::new());
        let mut target = PackedFrame::new(w, h);
        let mut probe = Collect::new(w, h);
        let sliced = spec.engine == EngineSpec::CodeFill;
        let mut words = vec![0u32; if sliced { w * WORDS } else { 0 }];
        let codes = if sliced {
            RowCodes::BitSliced(&mut words)
        } else {
            RowCodes::Crossings
        };
        let stats = renderer
            .render_with(
                &mesh,
                &adjacency,
                &camera,
                &settings,
                &mut ws,
                codes,
                Visibility::Order(order.depth_order()),
                &MonoPalette::default(),
                &mut target,
                &mut probe,
            )
            .map_err(|e| format!("render: {e}"))?;
        let time_us = start.elapsed().as_micros() as u64;
        let lent = ws.bytes()
            + std::mem::size_of_val(adjacency.edges())
            + std::mem::size_of_val(words.as_slice())
            + figures.storage_bytes;
        let working = lent
            + Engine::<Frac, WORDS>::bytes_for(
                stats.peak_faces as usize,
                stats.peak_edges as usize,
            );
        let mut stats_list: Vec<(String, u64)> = vec![
            ("faces".into(), u64::from(stats.faces)),
            ("faces_drawn".into(), u64::from(stats.faces_drawn)),
            ("feature_edges".into(), u64::from(stats.feature_edges)),
            ("spans".into(), u64::from(stats.spans)),
            ("bands".into(), u64::from(stats.bands)),
            ("band_rows".into(), u64::from(stats.band_rows)),
            ("code_bits".into(), u64::from(stats.code_bits)),
            ("peak_active_faces".into(), u64::from(stats.peak_faces)),
            ("peak_active_edges".into(), u64::from(stats.peak_edges)),
            ("working_ram_bytes".into(), working as u64),
            ("adjacency_build_bytes".into(), build_bytes as u64),
            ("time_us".into(), time_us),
        ];
        stats_list.extend([
            ("newell_fragments".into(), figures.fragments as u64),
            ("newell_splits".into(), figures.splits as u64),
            ("newell_shuffles".into(), figures.shuffles as u64),
            ("newell_unresolved".into(), figures.unresolved as u64),
            ("newell_bytes".into(), figures.kept_bytes as u64),
            ("newell_sort_us".into(), figures.sort_us),
        ]);
        Ok(Frame {
            width: w,
            height: h,
            ids: probe.ids,
            lines: probe.lines,
            packed: target.bytes,
            stats: stats_list,
        })
    })?
}

/// Collects the `--ids` and `--lines` images (as `pipeline`'s probe does).
struct Collect {
    width: usize,
    ids: Vec<u32>,
    lines: Vec<u8>,
}

impl Collect {
    fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            ids: vec![0; width * height],
            lines: vec![0; width * height],
        }
    }
}

impl FrameProbe for Collect {
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
