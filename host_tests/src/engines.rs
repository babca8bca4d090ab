//! The id-filling engines of issue 7 on the host: painter's list, BSP tree painted
//! far to near, and (added by their own modules) the other classical methods. Each
//! renders with the library exactly as firmware would, through `IdWorkspace`.

use std::time::Instant;

use fixed::types::extra::LeEqU32;
use pbuffer::mesh::Mesh;
use pbuffer::render::{
    BvhNode, IdWorkspace, PaintOrder, PainterRenderer, ProjectedVertex, RayFace, RaycastRenderer,
    RaycastStorage, WarnockArea, WarnockFace, WarnockRenderer, WarnockSizes, WarnockStorage,
};
use pbuffer::{DepthOrder, MonoPalette};

use crate::bsp::with_bsp;
use crate::callgrind::measured_region;
use crate::frame::{CameraSpec, EngineSpec, Frame, MeshData, RenderSpec};
use crate::pipeline::{
    camera, frame, settings, AdjacencyStorage, Collect, MeshArrays, PackedFrame, EDGES, POLY,
};

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
        let (w, h) = (spec.width, spec.height);
        let band = spec.band.clamp(1, h.max(1));
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
}

/// `painter` (faces by farthest depth) and `bsp` (the tree's fragments, walked per
/// view), both painted far to near with no depth test.
pub(crate) fn render_painter<Frac: LeEqU32>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let arrays = MeshArrays::new(data);
    let mesh = Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets)
        .map_err(|e| format!("mesh: {e}"))?;
    if spec.engine == EngineSpec::Painter {
        return paint_with::<Frac>(&arrays, &mesh, None, cam, spec);
    }
    with_bsp(&mesh, |tree, figures| {
        let mut frame = paint_with::<Frac>(&arrays, &mesh, Some(tree), cam, spec)?;
        frame.stats.extend([
            ("bsp_fragments".into(), figures.fragments as u64),
            ("bsp_bytes".into(), figures.kept_bytes as u64),
            ("bsp_build_us".into(), figures.build_us),
        ]);
        let working = frame.stat("working_ram_bytes") + figures.kept_bytes as u64;
        frame.set_stat("working_ram_bytes", working);
        Ok(frame)
    })?
}

fn paint_with<Frac: LeEqU32>(
    arrays: &MeshArrays,
    mesh: &Mesh<'_>,
    tree: Option<&pbuffer::order::BspTree<'_>>,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let mut storage = AdjacencyStorage::new(arrays);
    let build_bytes = storage.build_bytes();
    let adjacency = storage.build(mesh, spec.crease_deg)?;
    let camera = camera(cam)?;
    let settings = settings(spec)?;
    let surfaces = tree.map_or(*mesh, |t| t.fragments());
    let mut buffers = IdBuffers::new(
        spec,
        surfaces.vertices().len(),
        mesh.face_count(),
        adjacency.edges().len(),
    );
    let mut list = vec![0u64; surfaces.face_count()];
    let mut rank = vec![0u32; tree.map_or(0, |t| t.fragment_count())];
    let mut stack = vec![0u32; tree.map_or(0, |t| t.depth())];
    let mut ws = buffers.workspace();
    let lent = ws.bytes()
        + std::mem::size_of_val(adjacency.edges())
        + std::mem::size_of_val(list.as_slice())
        + std::mem::size_of_val(rank.as_slice())
        + std::mem::size_of_val(stack.as_slice());
    let mut renderer = Box::new(PainterRenderer::<Frac, EDGES, POLY>::new());
    let (w, h) = (spec.width, spec.height);
    let mut target = PackedFrame::new(w, h);
    let mut probe = Collect::new(w, h);
    let start = Instant::now();
    let mut result = None;
    measured_region(&mut || {
        let order = match tree {
            Some(t) => {
                if let Err(e) = t.rank_front_to_back(&camera.viewpoint(), &mut stack, &mut rank) {
                    result = Some(Err(e.widen()));
                    return;
                }
                PaintOrder::Order(DepthOrder {
                    surfaces: t.fragments(),
                    source: t.source(),
                    rank: &rank,
                })
            }
            None => PaintOrder::FarthestDepth,
        };
        result = Some(renderer.render(
            mesh,
            &adjacency,
            &camera,
            &settings,
            &mut ws,
            order,
            &mut list,
            &MonoPalette::default(),
            &mut target,
            &mut probe,
        ));
    });
    let stats = result
        .expect("the measured region ran")
        .map_err(|e| format!("render: {e}"))?;
    let time_us = start.elapsed().as_micros() as u64;
    let working = lent + std::mem::size_of::<PainterRenderer<Frac, EDGES, POLY>>();
    Ok(frame(
        w,
        h,
        probe,
        target,
        &stats,
        working,
        build_bytes,
        time_us,
    ))
}

/// `warnock`: area subdivision, storage lent at the sizes that always suffice.
pub(crate) fn render_warnock<Frac: LeEqU32>(
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
    let mut buffers = IdBuffers::new(
        spec,
        mesh.vertices().len(),
        mesh.face_count(),
        adjacency.edges().len(),
    );
    let (w, h) = (spec.width, spec.height);
    let band = spec.band.clamp(1, h.max(1));
    let sizes = WarnockSizes::for_frame(mesh.face_count(), w as u16, h as u16, band as u16);
    let mut areas = vec![WarnockArea::default(); sizes.areas];
    let mut lists = vec![0u16; sizes.lists];
    let mut faces = vec![WarnockFace::default(); sizes.faces];
    let mut ws = buffers.workspace();
    let lend = WarnockStorage {
        areas: &mut areas,
        lists: &mut lists,
        faces: &mut faces,
    };
    let lent = ws.bytes() + lend.bytes() + std::mem::size_of_val(adjacency.edges());
    let mut renderer = WarnockRenderer::<Frac, POLY>::new();
    let mut target = PackedFrame::new(w, h);
    let mut probe = Collect::new(w, h);
    let start = Instant::now();
    let mut result = None;
    measured_region(&mut || {
        let storage = WarnockStorage {
            areas: &mut *lend.areas,
            lists: &mut *lend.lists,
            faces: &mut *lend.faces,
        };
        result = Some(renderer.render(
            &mesh,
            &adjacency,
            &camera,
            &settings,
            &mut ws,
            storage,
            &MonoPalette::default(),
            &mut target,
            &mut probe,
        ));
    });
    let stats = result
        .expect("the measured region ran")
        .map_err(|e| format!("render: {e}"))?;
    let time_us = start.elapsed().as_micros() as u64;
    let working = lent + std::mem::size_of::<WarnockRenderer<Frac, POLY>>();
    Ok(frame(
        w,
        h,
        probe,
        target,
        &stats,
        working,
        build_bytes,
        time_us,
    ))
}

/// `raycast`: one ray per pixel centre through a bounding-volume hierarchy built per
/// frame in lent storage (counted in the working RAM).
pub(crate) fn render_raycast<Frac: LeEqU32>(
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
    let mut buffers = IdBuffers::new(
        spec,
        mesh.vertices().len(),
        mesh.face_count(),
        adjacency.edges().len(),
    );
    let sizes = RaycastStorage::sizes(mesh.face_count());
    let mut nodes = vec![BvhNode::default(); sizes.nodes];
    let mut faces = vec![RayFace::default(); sizes.faces];
    let mut ws = buffers.workspace();
    let mut rays = RaycastStorage {
        nodes: &mut nodes,
        faces: &mut faces,
    };
    let lent = ws.bytes() + std::mem::size_of_val(adjacency.edges()) + rays.bytes();
    let mut renderer = Box::new(RaycastRenderer::<Frac, POLY>::new());
    let (w, h) = (spec.width, spec.height);
    let mut target = PackedFrame::new(w, h);
    let mut probe = Collect::new(w, h);
    let start = Instant::now();
    let mut result = None;
    measured_region(&mut || {
        result = Some(renderer.render(
            &mesh,
            &adjacency,
            &camera,
            &settings,
            &mut ws,
            &mut rays,
            &MonoPalette::default(),
            &mut target,
            &mut probe,
        ));
    });
    let stats = result
        .expect("the measured region ran")
        .map_err(|e| format!("render: {e}"))?;
    let time_us = start.elapsed().as_micros() as u64;
    let working = lent + std::mem::size_of::<RaycastRenderer<Frac, POLY>>();
    let figures = renderer.figures();
    let mut frame = frame(w, h, probe, target, &stats, working, build_bytes, time_us);
    frame.stats.extend([
        ("bvh_faces".into(), u64::from(figures.faces)),
        ("bvh_nodes".into(), u64::from(figures.nodes)),
        ("ray_face_tests".into(), figures.face_tests),
        ("ray_fallbacks".into(), u64::from(figures.fallbacks)),
        ("ray_tree_pixels".into(), figures.tree_pixels),
        ("ray_clipped_faces".into(), u64::from(figures.clipped_faces)),
    ]);
    Ok(frame)
}

/// `newell`: Newell's depth sort for this frame's view (shuffles, splits, inside the
/// measured frame), its fragments painted far to near. The lent storage is first
/// grown until the sort fits (outside the frame), then the frame sorts again into it.
pub(crate) fn render_newell_paint<Frac: LeEqU32>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    use pbuffer::order::NewellSizes;
    let arrays = MeshArrays::new(data);
    let mesh = Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets)
        .map_err(|e| format!("mesh: {e}"))?;
    let mut storage = AdjacencyStorage::new(&arrays);
    let build_bytes = storage.build_bytes();
    let adjacency = storage.build(&mesh, spec.crease_deg)?;
    let camera = camera(cam)?;
    let settings = settings(spec)?;
    let cull = crate::newell::culls(spec, adjacency.is_closed());
    let mut splits = mesh.face_count() / 4 + 16;
    let (mut buffers, fragments) = loop {
        let sizes = NewellSizes::for_mesh(
            mesh.vertices().len(),
            mesh.face_count(),
            mesh.indices().len(),
            splits,
        );
        let mut b = crate::newell::NewellBuffers::new(sizes);
        match b.sort(&mesh, &camera, cull) {
            Ok(order) => {
                let n = (order.fragments().vertices().len(), order.fragment_count());
                break (b, n);
            }
            Err(pbuffer::Error::CapacityExceeded { .. }) if splits < 1 << 24 => {
                splits = 2 * splits + 64
            }
            Err(e) => return Err(format!("Newell sort: {e}")),
        }
    };
    let order_bytes = buffers.bytes();
    let mut ids = IdBuffers::new(
        spec,
        fragments.0,
        mesh.face_count(),
        adjacency.edges().len(),
    );
    let mut list = vec![0u64; fragments.1];
    let mut ws = ids.workspace();
    let lent = ws.bytes()
        + std::mem::size_of_val(adjacency.edges())
        + std::mem::size_of_val(list.as_slice())
        + order_bytes;
    let mut renderer = Box::new(PainterRenderer::<Frac, EDGES, POLY>::new());
    let (w, h) = (spec.width, spec.height);
    let mut target = PackedFrame::new(w, h);
    let mut probe = Collect::new(w, h);
    let start = Instant::now();
    let mut result = None;
    let mut figures = (0usize, 0usize);
    measured_region(&mut || {
        let order = match buffers.sort(&mesh, &camera, cull) {
            Ok(o) => o,
            Err(e) => {
                result = Some(Err(e.widen()));
                return;
            }
        };
        figures = (order.splits(), order.shuffles());
        result = Some(renderer.render(
            &mesh,
            &adjacency,
            &camera,
            &settings,
            &mut ws,
            PaintOrder::Order(order.depth_order()),
            &mut list,
            &MonoPalette::default(),
            &mut target,
            &mut probe,
        ));
    });
    let stats = result
        .expect("the measured region ran")
        .map_err(|e| format!("render: {e}"))?;
    let time_us = start.elapsed().as_micros() as u64;
    let working = lent + std::mem::size_of::<PainterRenderer<Frac, EDGES, POLY>>();
    let mut frame = frame(w, h, probe, target, &stats, working, build_bytes, time_us);
    frame.stats.extend([
        ("newell_fragments".into(), fragments.1 as u64),
        ("newell_splits".into(), figures.0 as u64),
        ("newell_shuffles".into(), figures.1 as u64),
        ("newell_storage_bytes".into(), order_bytes as u64),
    ]);
    Ok(frame)
}
