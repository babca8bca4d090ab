//! The library's 3-D pipeline on the host: `MeshData` and specs in, a `Frame` out.

use fixed::types::extra::{LeEqU32, U0, U1, U10, U11, U12, U2, U3, U4, U5, U6, U7, U8, U9};
use pbuffer::order::BspTree;
use pbuffer::render::{Depth, RowCodes};
use pbuffer::{CodeFillRenderer, MonoPalette, Visibility, ZBufferRenderer};

use crate::bsp::{with_bsp, BspFigures, DepthRanks};
use crate::frame::{CameraSpec, EngineSpec, Frame, MeshData, RenderSpec};
use crate::setup::{
    FrameInputs, IdBuffers, Measured, SceneStorage, ACTIVE_EDGES, ACTIVE_FACES, EDGES, POLY,
};

/// Renders with the library exactly as firmware would (fixed point, banded).
pub fn render_frame(mesh: &MeshData, cam: &CameraSpec, spec: &RenderSpec) -> Result<Frame, String> {
    // Far from the origin, or with huge faces: moved to a local origin and cut in
    // f64 first (the same picture).
    let aspect = spec.width as f64 / spec.height.max(1) as f64;
    if let Some((mesh, cam)) = crate::origin::localised(mesh, cam, aspect) {
        return render_local(&mesh, &cam, spec, false);
    }
    render_local(mesh, cam, spec, false)
}

/// The scan-line method (`spec.engine` must be `scanline`) with bit-sliced rows
/// (`RowCodes::BitSliced`) in place of the crossings: not an engine of its own, since
/// both row representations must draw the same frame; this draws the other one to
/// check it (the fuzz property of `fuzz_properties.rs` compares them on random scenes).
pub fn render_scanline_bit_sliced(
    mesh: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<Frame, String> {
    if spec.engine != EngineSpec::Scanline {
        return Err(format!(
            "bit-sliced rows of --engine {}",
            spec.engine.name()
        ));
    }
    let aspect = spec.width as f64 / spec.height.max(1) as f64;
    if let Some((mesh, cam)) = crate::origin::localised(mesh, cam, aspect) {
        return render_local(&mesh, &cam, spec, true);
    }
    render_local(mesh, cam, spec, true)
}

/// `sliced`: the scan-line method with bit-sliced rows.
fn render_local(
    mesh: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    sliced: bool,
) -> Result<Frame, String> {
    match spec.subpixel {
        0 => render_s::<U0>(mesh, cam, spec, sliced),
        1 => render_s::<U1>(mesh, cam, spec, sliced),
        2 => render_s::<U2>(mesh, cam, spec, sliced),
        3 => render_s::<U3>(mesh, cam, spec, sliced),
        4 => render_s::<U4>(mesh, cam, spec, sliced),
        5 => render_s::<U5>(mesh, cam, spec, sliced),
        6 => render_s::<U6>(mesh, cam, spec, sliced),
        7 => render_s::<U7>(mesh, cam, spec, sliced),
        8 => render_s::<U8>(mesh, cam, spec, sliced),
        9 => render_s::<U9>(mesh, cam, spec, sliced),
        10 => render_s::<U10>(mesh, cam, spec, sliced),
        11 => render_s::<U11>(mesh, cam, spec, sliced),
        12 => render_s::<U12>(mesh, cam, spec, sliced),
        s => Err(format!("--subpixel {s}: must be 0 to 12")),
    }
}

fn render_s<Frac: LeEqU32>(
    mesh: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    sliced: bool,
) -> Result<Frame, String> {
    if matches!(
        spec.engine,
        EngineSpec::CodeFill | EngineSpec::CodeFillCrossings | EngineSpec::Scanline
    ) {
        return match render_code::<Frac, 4>(mesh, cam, spec, sliced) {
            Err(e) if e.contains("surface code") => {
                render_code::<Frac, 32>(mesh, cam, spec, sliced)
            }
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
    let FrameInputs {
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

/// The code-fill engine: no depth buffer; ids for the band and its apron. `codefill`
/// and `codefill-crossings` render in the depth order of a BSP tree built once for the
/// mesh (its build is timed apart, its storage counted in the working RAM);
/// `scanline` compares planes where faces overlap (`sliced`: with bit-sliced rows).
fn render_code<Frac: LeEqU32, const WORDS: usize>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    sliced: bool,
) -> Result<Frame, String> {
    let mut storage = SceneStorage::new(data);
    let scene = storage.scene(cam, spec)?;
    if spec.engine == EngineSpec::Scanline {
        return render_code_with::<Frac, WORDS>(&scene, None, spec, sliced);
    }
    match with_bsp(&scene.mesh, |tree, figures| {
        render_code_with::<Frac, WORDS>(&scene, Some((tree, figures)), spec, false)
    }) {
        Ok(frame) => frame,
        // A mesh whose tree would need more fragments than face ids can name: the
        // same engine without an order (planes where faces overlap), said aloud.
        Err(e) => {
            eprintln!("note: {e}; rendering with --engine scanline instead");
            let mut frame = render_code_with::<Frac, WORDS>(&scene, None, spec, false)?;
            frame.stats.push(("depth_order_fallback".into(), 1));
            Ok(frame)
        }
    }
}

fn render_code_with<Frac: LeEqU32, const WORDS: usize>(
    scene: &FrameInputs<'_>,
    bsp: Option<(&BspTree<'_>, BspFigures)>,
    spec: &RenderSpec,
    sliced_planes: bool,
) -> Result<Frame, String> {
    let FrameInputs {
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
    let sliced = spec.engine == EngineSpec::CodeFill || sliced_planes;
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
