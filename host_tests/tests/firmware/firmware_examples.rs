//! The firmware examples' frames, rendered on the host with the same code: the scene,
//! engine and baseline modules are the `pbuffer-scenes` crate's (`examples/scenes`,
//! which the firmware builds too), suzanne is parsed by the same converter
//! (`pbuffer_scenes::obj`) that the firmware's build.rs runs, and the fast engine's constants and planarity bits are
//! made as build.rs makes them (`BakedMesh::bake`, `pbuffer::order::planar_faces`, here
//! at run time). The instrument-panel demo's frames come from the same `instrument`
//! module through `host_tests::firmware`. Prints one line per frame,
//!
//! ```text
//! frame EXAMPLE N hash=HEX
//! ```
//!
//! which `scripts/firmware` compares with the lines the firmware prints under QEMU
//! (any difference fails it). Writes nothing to disk.

use pbuffer_scenes::{obj, painter, plain, scenes};

use host_tests::firmware::{arm, bake_shape, instances, instrument, ArmDemo, Bake, Demo};
use pbuffer::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use pbuffer::render::{storage_rows, Contour, Crossing, SegmentLists, Segments, MAX_GRID_CELLS};
use pbuffer::{packed_len, Capacity, DrawMode, PackedFramebuffer, Pattern};
use scenes::{fnv1a64, panel, suzanne, View};

/// A scene: its mesh arrays, size and cameras.
struct Example {
    name: &'static str,
    vertices: Vec<[f32; 3]>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
    frames: u32,
    view: fn(u32) -> View,
}

fn suzanne_scene() -> Example {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/embedded/models/suzanne.obj"
    );
    let text = std::fs::read_to_string(path).expect("read the examples' suzanne.obj");
    let m = obj::parse(&text, "suzanne.obj").expect("parses");
    Example {
        name: "suzanne",
        vertices: m.vertices,
        indices: m.indices,
        offsets: m.offsets,
        frames: suzanne::FRAMES,
        view: suzanne::view,
    }
}

fn panel_scene() -> Example {
    Example {
        name: "panel",
        vertices: panel::VERTICES.to_vec(),
        indices: panel::INDICES.to_vec(),
        offsets: panel::OFFSETS.to_vec(),
        frames: panel::FRAMES,
        view: panel::view,
    }
}

fn edges<'s>(mesh: &Mesh<'_>, store: &'s mut [MeshEdge]) -> EdgeAdjacency<'s> {
    let mut weld = vec![0u32; mesh.vertices().len()];
    let mut scratch = vec![HalfEdgeRecord::EMPTY; mesh.indices().len()];
    EdgeAdjacency::build(mesh, 30.0, &mut weld, &mut scratch, store).expect("adjacency")
}

fn print(name: &str, n: u32, bytes: &[u8]) -> u32 {
    println!("frame {name} {n} hash={:016x}", fnv1a64(bytes));
    bytes.iter().map(|b| b.count_ones()).sum()
}

/// The fast-engine examples, the scan-line examples, the painter and the plain f32
/// baseline on one scene, exactly as the firmware binaries run them (buffer sizes
/// included). `$edges` is the baked edge count the fast buffers are sized for.
macro_rules! run_scene {
    (
        $s:expr, $w:expr, $h:expr, $v:expr, $f:expr,
        fast: $fast_engine:ty, $fast_buffers:ty, $edges:expr, [$(($fast:expr, $fast_mode:expr)),*],
        scanline: $engine:ty, $buffers:ty, [$(($example:expr, $mode:expr)),*]
    ) => {{
        const N: usize = packed_len($w, $h);
        let s: &Example = $s;
        // As the firmware: the scan-line examples take the mesh and its edge list; the
        // fast ones its planarity bits, face planes and compact edge list, made as
        // build.rs makes them and checked by `BakedMesh::new`.
        let bake = Bake::new(&s.vertices, &s.indices, &s.offsets);
        let (mesh, adjacency, baked) = (bake.plain_mesh(), bake.adjacency(), bake.baked());
        assert_eq!(bake.baked_edges(), $edges, "the fast buffers' edge count");
        let mut fast_engine = Box::new(<$fast_engine>::new());
        $(
            let mut b = Box::new(<$fast_buffers>::new());
            let (mut facets, mut lines) = (0, 0);
            for n in 0..s.frames {
                let mut fb = Box::new(PackedFramebuffer::<{ $w }, { $h }, N>::new());
                let view = (s.view)(n);
                let mut ws = b.workspace();
                let stats = scenes::render_fast(&mut fast_engine, &baked, &view, $fast_mode, &mut ws, &mut *fb)
                    .expect("renders");
                assert!(stats.feature_edges > 0);
                (facets, lines) = (stats.peak_faces.max(facets), stats.peak_edges.max(lines));
                let lit = print($fast, n, fb.as_bytes());
                assert!(lit > 100, "{} {n}: {lit} pixels", $fast);
            }
            println!("peaks {}: {facets} facets, {lines} lines", $fast);
        )*
        let mut engine = Box::new(<$engine>::new());
        $(
            let mut b = Box::new(<$buffers>::new());
            for n in 0..s.frames {
                let mut fb = Box::new(PackedFramebuffer::<{ $w }, { $h }, N>::new());
                let view = (s.view)(n);
                let mut ws = b.workspace();
                let stats = scenes::render(&mut engine, &mesh, &adjacency, &view, $mode, &mut ws, &mut *fb)
                    .expect("renders");
                assert!(stats.feature_edges > 0);
                let lit = print($example, n, fb.as_bytes());
                assert!(lit > 100, "{} {n}: {lit} pixels", $example);
            }
        )*
        let mut p = Box::new(painter::PainterBuffers::<{ $v }, { $f }>::new());
        p.prepare(&mesh);
        let mut plain = Box::new(plain::PlainBuffers::<{ $w * $h }, N, { $v }, { $f }>::new());
        plain.prepare(&mesh);
        for n in 0..s.frames {
            let view = (s.view)(n);
            let mut fb = Box::new(PackedFramebuffer::<{ $w }, { $h }, N>::new());
            p.render(&mesh, &view, &mut *fb).expect("painter");
            print(&format!("{}-painter", s.name), n, fb.as_bytes());
            plain.render(&mesh, adjacency.edges(), adjacency.is_closed(), &view, $w, $h, &Pattern::PAPER);
            print(&format!("{}-plainf32", s.name), n, &plain.frame);
        }
    }};
}

/// What one frame of hidden lines by the segment needs of the list `what`
/// (contours, crossings or grid entries): the frame drawn again with no room in
/// that list and plenty in the others; 0 when it needs none.
fn segment_need<K, const FACETS: usize, const LINES: usize>(
    engine: &mut pbuffer::render::FastRenderer<fixed::types::extra::U4, FACETS, LINES>,
    baked: &pbuffer::render::BakedMesh<'_>,
    view: &View,
    mut ws: pbuffer::render::FastWorkspace<'_>,
    fb: &mut K,
    what: Capacity,
) -> usize
where
    K: pbuffer::SpanSink<
        Color = embedded_graphics::pixelcolor::BinaryColor,
        Error = std::convert::Infallible,
    >,
{
    const PLENTY: usize = 1 << 15;
    let room = |w: Capacity| if w == what { 0 } else { PLENTY };
    let mut contours = vec![Contour::default(); room(Capacity::ContourEdges)];
    let mut stamps = vec![0u16; contours.len()];
    let mut crossings = vec![Crossing::default(); room(Capacity::Crossings)];
    let mut cells = vec![0u16; MAX_GRID_CELLS + 1];
    let mut entries = vec![0u16; room(Capacity::GridEntries)];
    let lists = SegmentLists::new(
        &mut contours,
        &mut stamps,
        &mut crossings,
        &mut cells,
        &mut entries,
    )
    .expect("the lists");
    let work = ws.segments.take().expect("segment storage").work;
    let mut ws = pbuffer::render::FastWorkspace {
        segments: Some(Segments { lists, work }),
        ..ws
    };
    match scenes::render_fast(engine, baked, view, DrawMode::Dashed, &mut ws, fb) {
        Ok(_) => 0,
        Err(pbuffer::Error::CapacityExceeded {
            what: w, needed, ..
        }) if w == what => needed,
        Err(e) => panic!("{what:?}: {e:?}"),
    }
}

/// A fast-engine example drawn with hidden lines by the segment, exactly as its
/// firmware binary draws it (`Bake::baked_segments`, `FastBuffers::workspace_with`):
/// prints its frames, checks that every frame took the segment path, and prints the
/// peak need of each segment list against its capacity.
macro_rules! run_segments {
    (
        $s:expr, $w:expr, $h:expr, $name:expr, $engine:ty, $buffers:ty, $segments:ty,
        ($contours:expr, $crossings:expr, $entries:expr)
    ) => {{
        const N: usize = packed_len($w, $h);
        let s: &Example = $s;
        let bake = Bake::new(&s.vertices, &s.indices, &s.offsets);
        let baked = bake.baked_segments();
        let mut engine = Box::new(<$engine>::new());
        let mut b = Box::new(<$buffers>::new());
        let mut seg = Box::new(<$segments>::new());
        let mut peaks = [0usize; 3];
        let mut pierced = 0;
        for n in 0..s.frames {
            let mut fb = Box::new(PackedFramebuffer::<{ $w }, { $h }, N>::new());
            let view = (s.view)(n);
            let stats = scenes::render_fast(
                &mut engine,
                &baked,
                &view,
                DrawMode::Dashed,
                &mut b.workspace_with(&mut seg),
                &mut *fb,
            )
            .expect("renders");
            let st = stats.segments;
            assert!(
                st.drawn > 0 && st.fallback == 0,
                "{} {n}: not by the segment: {st:?}",
                $name
            );
            let lit = print($name, n, fb.as_bytes());
            assert!(lit > 100, "{} {n}: {lit} pixels", $name);
            println!("segments {} {n}: {st:?}", $name);
            pierced += st.piercings;
            let kinds = [
                Capacity::ContourEdges,
                Capacity::Crossings,
                Capacity::GridEntries,
            ];
            for (peak, what) in peaks.iter_mut().zip(kinds) {
                let mut probe = Box::new(PackedFramebuffer::<{ $w }, { $h }, N>::new());
                let need = segment_need(
                    &mut engine,
                    &baked,
                    &view,
                    b.workspace_with(&mut seg),
                    &mut *probe,
                    what,
                );
                *peak = need.max(*peak);
            }
        }
        let room = [$contours, $crossings, $entries];
        println!(
            "peaks {}: {} / {} contours, {} / {} crossings, {} / {} grid entries, \
             {} piercing pairs baked, {pierced} pierced in all frames",
            $name,
            peaks[0],
            room[0],
            peaks[1],
            room[1],
            peaks[2],
            room[2],
            bake.piercings().len()
        );
        for (peak, room) in peaks.iter().zip(room) {
            assert!(*peak <= room, "{}: {peaks:?} over {room}", $name);
        }
    }};
}

#[test]
fn firmware_example_frames() {
    // Large buffers: run on a thread with room for them.
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(|| {
            let suz = suzanne_scene();
            let probe = Mesh::new(&suz.vertices, &suz.indices, &suz.offsets).expect("mesh");
            let m = obj::ObjMesh {
                vertices: suz.vertices.clone(),
                indices: suz.indices.clone(),
                offsets: suz.offsets.clone(),
            };
            let mut store = vec![MeshEdge::EMPTY; suz.indices.len()];
            // The converter's edge count sizes the firmware's edge store exactly.
            assert_eq!(
                edges(&probe, &mut store).edges().len(),
                obj::unique_edges(&m)
            );
            assert!(
                obj::unique_edges(&m) <= 1024,
                "SuzanneBuffers holds 1024 edge bits"
            );
            assert_eq!((suz.vertices.len(), probe.face_count()), (507, 500));
            let pan = panel_scene();
            let pm = obj::ObjMesh {
                vertices: pan.vertices.clone(),
                indices: pan.indices.clone(),
                offsets: pan.offsets.clone(),
            };
            assert_eq!(obj::unique_edges(&pm), panel::EDGES);
            // The buffers hold a band plus its apron.
            assert_eq!(
                usize::from(storage_rows(suzanne::BAND as u16, 240)),
                suzanne::BAND + 2
            );
            assert_eq!(
                usize::from(storage_rows(panel::BAND as u16, 64)),
                panel::BAND + 2
            );
            run_scene!(
                &suz,
                400,
                240,
                507,
                500,
                fast: scenes::FastEngine,
                scenes::SuzanneFastBuffers,
                scenes::SUZANNE_EDGES,
                [
                    ("suzanne", DrawMode::Dashed),
                    ("surfaces", DrawMode::SurfacesDashed)
                ],
                scanline: scenes::Engine,
                scenes::SuzanneBuffers,
                [("suzanne-scanline", DrawMode::Dashed)]
            );
            run_scene!(
                &pan,
                128,
                64,
                24,
                16,
                fast: scenes::PanelFastEngine,
                scenes::PanelFastBuffers,
                panel::EDGES,
                [("panel", DrawMode::Dashed)],
                scanline: scenes::PanelEngine,
                scenes::PanelBuffers,
                [("panel-scanline", DrawMode::Dashed)]
            );
            // Hidden lines by the segment: the same frames with the segment tables.
            run_segments!(
                &suz,
                400,
                240,
                "suzanne-segments",
                scenes::FastEngine,
                scenes::SuzanneFastBuffers,
                scenes::SuzanneSegmentBuffers,
                (
                    scenes::SUZANNE_CONTOURS,
                    scenes::SUZANNE_CROSSINGS,
                    scenes::SUZANNE_GRID_ENTRIES
                )
            );
            run_segments!(
                &pan,
                128,
                64,
                "panel-segments",
                scenes::PanelFastEngine,
                scenes::PanelFastBuffers,
                scenes::PanelSegmentBuffers,
                (
                    scenes::PANEL_CONTOURS,
                    scenes::PANEL_CROSSINGS,
                    scenes::PANEL_GRID_ENTRIES
                )
            );
            // The instrument-panel demo: the bracket in its pane beside the text.
            let mut demo = Demo::new();
            for n in 0..instrument::FRAMES {
                let fb = demo.frame(n);
                let lit = print("instrument", n, fb.as_bytes());
                assert!(lit > 300, "instrument {n}: {lit} pixels");
            }
            // In the same test: a second test's progress dot would land at the start
            // of a frame line that scripts/firmware greps for.
            scene_example_frames();
        })
        .expect("spawn")
        .join()
        .expect("the frames render");
}

/// The robot-arm demo (four posed parts, `SceneDrawing`) and the instances example:
/// each grid as one mesh and as instances, the same frame.
fn scene_example_frames() {
    let demo = ArmDemo::new();
    for n in 0..arm::FRAMES {
        let fb = demo.frame(n);
        let lit = print("arm", n, fb.as_bytes());
        assert!(lit > 300, "arm {n}: {lit} pixels");
    }
    let part = bake_shape(&instances::part());
    let grids = [
        bake_shape(&instances::grid::<24, 72, 17>(1)),
        bake_shape(&instances::grid::<96, 288, 65>(4)),
        bake_shape(&instances::grid::<384, 1152, 257>(16)),
    ];
    let mut union: Box<instances::UnionDrawing<'_>> = Box::new(pbuffer::BakedDrawing::new());
    let mut scene: Box<instances::InstanceScene<'_>> = Box::new(pbuffer::SceneDrawing::new());
    let mut rows = Box::new(instances::Rows::new());
    for (n, grid) in instances::COUNTS.into_iter().zip(&grids) {
        union.set_mesh(grid.baked()).expect("the grid");
        instances::set_instances(&mut scene, part.baked(), n).expect("the instances");
        for f in 0..instances::FRAMES {
            let mut fb = Box::new(arm::Frame::new());
            instances::draw_union(&mut union, &mut rows, n, f, &mut fb).expect("union");
            let one = print(&format!("instances-union-{n}"), f, fb.as_bytes());
            let union_bytes = fb.as_bytes().to_vec();
            instances::draw_scene(&mut scene, &mut rows, n, f, &mut fb).expect("scene");
            print(&format!("instances-scene-{n}"), f, fb.as_bytes());
            assert!(one > 100, "instances {n} {f}: {one} pixels");
            assert_eq!(union_bytes, fb.as_bytes(), "{n} instances, frame {f}");
        }
    }
}
