//! The id-filling engines of issue 7 on the host: painter's list, BSP tree painted
//! far to near, and (added by their own modules) the other classical methods. Each
//! renders with the library exactly as firmware would, through `IdWorkspace`.

use fixed::types::extra::LeEqU32;
use pbuffer::render::{
    BvhNode, PaintOrder, PainterRenderer, RayFace, RaycastRenderer, RaycastStorage, WarnockArea,
    WarnockFace, WarnockRenderer, WarnockSizes, WarnockStorage,
};
use pbuffer::MonoPalette;

use crate::bsp::{with_bsp, DepthRanks};
use crate::frame::{CameraSpec, EngineSpec, Frame, MeshData, RenderSpec};
use crate::setup::{FrameInputs, IdBuffers, Measured, SceneStorage};
use crate::setup::{EDGES, POLY};

/// `painter` (faces by farthest depth) and `bsp` (the tree's fragments, walked per
/// view), both painted far to near with no depth test.
pub(crate) fn render_painter<Frac: LeEqU32>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let mut storage = SceneStorage::new(data);
    let scene = storage.scene(cam, spec)?;
    if spec.engine == EngineSpec::Painter {
        return paint_with::<Frac>(&scene, None, spec);
    }
    with_bsp(&scene.mesh, |tree, figures| {
        let mut frame = paint_with::<Frac>(&scene, Some(tree), spec)?;
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
    scene: &FrameInputs<'_>,
    tree: Option<&pbuffer::order::BspTree<'_>>,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let FrameInputs {
        mesh,
        adjacency,
        camera,
        settings,
        build_bytes,
    } = scene;
    let surfaces = tree.map_or(*mesh, |t| t.fragments());
    let mut buffers = IdBuffers::for_mesh(spec, surfaces.vertices().len(), mesh, adjacency);
    let mut list = vec![0u64; surfaces.face_count()];
    let mut ranks = DepthRanks::new(tree);
    let mut ws = buffers.workspace();
    let lent = ws.bytes()
        + std::mem::size_of_val(adjacency.edges())
        + std::mem::size_of_val(list.as_slice())
        + ranks.bytes();
    let mut renderer = Box::new(PainterRenderer::<Frac, EDGES, POLY>::new());
    let measured = Measured::run(spec.width, spec.height, |target, probe| {
        let order = match tree {
            Some(t) => PaintOrder::Order(ranks.order(t, &camera.viewpoint())?),
            None => PaintOrder::FarthestDepth,
        };
        renderer.render(
            mesh,
            adjacency,
            camera,
            settings,
            &mut ws,
            order,
            &mut list,
            &MonoPalette::default(),
            target,
            probe,
        )
    })?;
    let working = lent + std::mem::size_of::<PainterRenderer<Frac, EDGES, POLY>>();
    Ok(measured.frame(working, *build_bytes))
}

/// `warnock`: area subdivision, storage lent at the sizes that always suffice.
pub(crate) fn render_warnock<Frac: LeEqU32>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let mut storage = SceneStorage::new(data);
    let FrameInputs {
        mesh,
        adjacency,
        camera,
        settings,
        build_bytes,
    } = storage.scene(cam, spec)?;
    let mut buffers = IdBuffers::for_mesh(spec, mesh.vertices().len(), &mesh, &adjacency);
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
    let measured = Measured::run(w, h, |target, probe| {
        let storage = WarnockStorage {
            areas: &mut *lend.areas,
            lists: &mut *lend.lists,
            faces: &mut *lend.faces,
        };
        renderer.render(
            &mesh,
            &adjacency,
            &camera,
            &settings,
            &mut ws,
            storage,
            &MonoPalette::default(),
            target,
            probe,
        )
    })?;
    let working = lent + std::mem::size_of::<WarnockRenderer<Frac, POLY>>();
    Ok(measured.frame(working, build_bytes))
}

/// `raycast`: one ray per pixel centre through a bounding-volume hierarchy built per
/// frame in lent storage (counted in the working RAM).
pub(crate) fn render_raycast<Frac: LeEqU32>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    let mut storage = SceneStorage::new(data);
    let FrameInputs {
        mesh,
        adjacency,
        camera,
        settings,
        build_bytes,
    } = storage.scene(cam, spec)?;
    let mut buffers = IdBuffers::for_mesh(spec, mesh.vertices().len(), &mesh, &adjacency);
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
    let measured = Measured::run(spec.width, spec.height, |target, probe| {
        renderer.render(
            &mesh,
            &adjacency,
            &camera,
            &settings,
            &mut ws,
            &mut rays,
            &MonoPalette::default(),
            target,
            probe,
        )
    })?;
    let working = lent + std::mem::size_of::<RaycastRenderer<Frac, POLY>>();
    let figures = renderer.figures();
    let mut frame = measured.frame(working, build_bytes);
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
    let mut storage = SceneStorage::new(data);
    let FrameInputs {
        mesh,
        adjacency,
        camera,
        settings,
        build_bytes,
    } = storage.scene(cam, spec)?;
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
    let mut ids = IdBuffers::for_mesh(spec, fragments.0, &mesh, &adjacency);
    let mut list = vec![0u64; fragments.1];
    let mut ws = ids.workspace();
    let lent = ws.bytes()
        + std::mem::size_of_val(adjacency.edges())
        + std::mem::size_of_val(list.as_slice())
        + order_bytes;
    let mut renderer = Box::new(PainterRenderer::<Frac, EDGES, POLY>::new());
    let mut figures = (0usize, 0usize);
    let measured = Measured::run(spec.width, spec.height, |target, probe| {
        let order = buffers.sort(&mesh, &camera, cull)?;
        figures = (order.splits(), order.shuffles());
        renderer.render(
            &mesh,
            &adjacency,
            &camera,
            &settings,
            &mut ws,
            PaintOrder::Order(order.depth_order()),
            &mut list,
            &MonoPalette::default(),
            target,
            probe,
        )
    })?;
    let working = lent + std::mem::size_of::<PainterRenderer<Frac, EDGES, POLY>>();
    let mut frame = measured.frame(working, build_bytes);
    frame.stats.extend([
        ("newell_fragments".into(), fragments.1 as u64),
        ("newell_splits".into(), figures.0 as u64),
        ("newell_shuffles".into(), figures.1 as u64),
        ("newell_storage_bytes".into(), order_bytes as u64),
    ]);
    Ok(frame)
}
