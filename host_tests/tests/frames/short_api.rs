//! The short API (`pbuffer::prelude`: `Drawing`, `FrameRows`, `Camera::look_at`)
//! draws exactly what the long form draws: the fast engine with a workspace sized
//! by hand, the mesh baked as a `build.rs` bakes it. The README quotes the crate
//! doctest that draws the cube, and the smallest firmware example runs its lines.

use pbuffer::mesh::{EdgeAdjacency, HalfEdgeRecord, MeshEdge};
use pbuffer::prelude::*;
use pbuffer::render::{BakedMesh, CompactEdge, FacePlane, FastRenderer, MonoPalette};
use pbuffer::subpixel::U4;
use pbuffer::{packed_len, PackedFramebuffer, Stats, CREASE_DEG};

use host_tests::fast::FastBuffers;
use host_tests::setup::MeshArrays;

type Frame = PackedFramebuffer<128, 64, { packed_len(128, 64) }>;

const CORNERS: [[f32; 3]; 8] = [
    [-1., -1., -1.],
    [1., -1., -1.],
    [1., 1., -1.],
    [-1., 1., -1.],
    [-1., -1., 1.],
    [1., -1., 1.],
    [1., 1., 1.],
    [-1., 1., 1.],
];
const QUADS: [u32; 24] = [
    0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 2, 3, 7, 6, 1, 2, 6, 5, 0, 4, 7, 3,
];
const STARTS: [u32; 7] = [0, 4, 8, 12, 16, 20, 24];

/// The long form: adjacency, baking, a hand-sized workspace, `FastRenderer`.
fn long_form(mesh: Mesh<'_>, camera: &Camera, settings: &Settings, fb: &mut Frame) -> Stats {
    let (v, i) = (mesh.vertices().len(), mesh.indices().len());
    let mut weld = vec![0u32; v];
    let mut scratch = vec![HalfEdgeRecord::EMPTY; i];
    let mut store = vec![MeshEdge::EMPTY; i];
    let adjacency = EdgeAdjacency::build(&mesh, CREASE_DEG, &mut weld, &mut scratch, &mut store)
        .expect("edges");
    let mut planes = vec![FacePlane::default(); mesh.face_count()];
    let mut edges = vec![CompactEdge::default(); adjacency.edges().len()];
    BakedMesh::bake(&mesh, &adjacency, &mut planes, &mut edges).expect("bakes");
    let baked = BakedMesh::new(mesh, &planes, &edges).expect("checks");
    let mut buffers = FastBuffers::new(v, mesh.face_count(), edges.len(), 128, 64, 64);
    let mut ws = buffers.workspace();
    ws.ids = &mut [];
    ws.phases = &mut [];
    let mut engine = Box::new(FastRenderer::<U4, 128, 128>::new());
    let palette = MonoPalette::default();
    let mut sink = pbuffer::FillSolid::new(fb).expect("fits");
    engine
        .render(
            &baked,
            camera,
            settings,
            &mut ws,
            &palette,
            &mut sink,
            &mut (),
        )
        .expect("renders")
}

/// Flat arrays of an OBJ model (f32 positions, indices, face starts).
fn flat(name: &str) -> MeshArrays {
    let path = host_tests::obj::workspace_root()
        .join("../shared/models")
        .join(name);
    MeshArrays::new(&host_tests::obj::load_obj(&path).expect("model"))
}

#[test]
fn the_cube_drawn_short_is_the_cube_drawn_long() {
    let mesh = Mesh::new(&CORNERS, &QUADS, &STARTS).unwrap();
    let mut cube = Drawing::<8, 6, 12>::new();
    cube.bake(mesh).unwrap();
    let camera = Camera::look_at([2.5, 2.0, 4.0], [0.0; 3], 40.0).unwrap();
    let mut short = Frame::new();
    let stats = cube
        .draw(&camera, &mut FrameRows::<128, 64>::new(), &mut short)
        .unwrap();
    let mut long = Frame::new();
    let want = long_form(mesh, &camera, &Settings::default(), &mut long);
    assert_eq!((stats.faces_drawn, stats.feature_edges), (3, 12));
    assert_eq!(stats, want);
    assert_eq!(short.as_bytes(), long.as_bytes());
    // With room to spare, the same frame (the cube is still closed: culled).
    let mut roomy = Drawing::<10, 8, 16>::new();
    roomy.bake(mesh).unwrap();
    let mut spare = Frame::new();
    let again = roomy
        .draw(&camera, &mut FrameRows::<200, 70>::new(), &mut spare)
        .unwrap();
    assert_eq!((again, spare.as_bytes()), (want, long.as_bytes()));
}

/// Suzanne has holes (back faces away from them skipped) and bent faces; the near
/// views clip faces (the clipped-corner pool); every mode.
#[test]
fn suzanne_drawn_short_is_suzanne_drawn_long_in_every_mode_and_near_view() {
    let arrays = flat("suzanne.obj");
    let mesh = Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets).unwrap();
    // Room for more vertices, faces and edges than suzanne has (507, 500, 1005).
    let mut drawing = Box::new(Drawing::<600, 550, 1100, 128, 128>::new());
    drawing.bake(mesh).unwrap();
    let mut rows = FrameRows::<128, 64>::new();
    let modes = [
        DrawMode::Wireframe,
        DrawMode::HiddenRemoved,
        DrawMode::Dashed,
        DrawMode::Surfaces,
        DrawMode::SurfacesDashed,
    ];
    // Suzanne's box centre; the last eye is inside the box: faces are clipped.
    let centre = [-2.49, 1.25, 4.1];
    let eyes = [[3.0, 1.0, 4.0], [-2.0, 0.5, 1.2], [0.3, 0.2, 0.9]];
    for mode in modes {
        for eye in eyes {
            let eye = [0, 1, 2].map(|k| centre[k] + eye[k]);
            let camera = Camera::look_at(eye, centre, 50.0).unwrap();
            drawing.settings.mode = mode;
            let mut short = Frame::new();
            let stats = drawing.draw(&camera, &mut rows, &mut short).unwrap();
            let mut long = Frame::new();
            let want = long_form(mesh, &camera, &drawing.settings, &mut long);
            assert_eq!(stats, want, "{mode:?} from {eye:?}");
            assert!(stats.faces_drawn > 100, "{mode:?} from {eye:?}: {stats:?}");
            assert_eq!(short.as_bytes(), long.as_bytes(), "{mode:?} from {eye:?}");
        }
    }
}

#[test]
fn a_drawing_starts_with_the_default_settings() {
    assert_eq!(Drawing::<1, 1, 1>::new().settings, Settings::default());
    assert_eq!(Drawing::<1, 1, 1>::new().palette, MonoPalette::default());
}

#[test]
fn too_small_a_drawing_names_the_size_it_needs() {
    let mesh = Mesh::new(&CORNERS, &QUADS, &STARTS).unwrap();
    let short = |what, needed, capacity| {
        Err(Error::CapacityExceeded {
            what,
            needed,
            capacity,
        })
    };
    assert_eq!(
        Drawing::<7, 6, 12>::new().bake(mesh),
        short(Capacity::Vertices, 8, 7)
    );
    assert_eq!(
        Drawing::<8, 5, 12>::new().bake(mesh),
        short(Capacity::Faces, 6, 5)
    );
    assert_eq!(
        Drawing::<8, 6, 11>::new().bake(mesh),
        short(Capacity::Edges, 12, 11)
    );
    // A failed bake leaves nothing to draw.
    let mut cube = Drawing::<8, 6, 12>::new();
    cube.bake(mesh).unwrap();
    let mut too_few = Drawing::<8, 6, 12>::new();
    let camera = Camera::look_at([2.5, 2.0, 4.0], [0.0; 3], 40.0).unwrap();
    let mut fb = Frame::new();
    let mut rows = FrameRows::<128, 64>::new();
    let nothing = too_few.draw(&camera, &mut rows, &mut fb);
    assert_eq!(nothing.map(drop), Err(Error::NothingBaked));
    // Rows narrower, lower, or too low for the line masks of a wide frame.
    let narrow = cube.draw(&camera, &mut FrameRows::<127, 64>::new(), &mut fb);
    assert_eq!(narrow.map(drop), short(Capacity::RowWidth, 128, 127));
    let low = cube.draw(&camera, &mut FrameRows::<128, 63>::new(), &mut fb);
    assert_eq!(low.map(drop), short(Capacity::Rows, 64, 63));
    let mut wide = PackedFramebuffer::<1000, 4, { packed_len(1000, 4) }>::new();
    let masks = cube.draw(&camera, &mut FrameRows::<1000, 4>::new(), &mut wide);
    assert_eq!(masks.map(drop), short(Capacity::LineMasks, 64, 4));
    assert!(
        fb.as_bytes().iter().all(|&b| b == 0),
        "nothing drawn on error"
    );
}

/// The crate doctest's lines (hidden `# ` lines left out).
fn doctest_lines() -> Vec<String> {
    let root = host_tests::obj::workspace_root();
    let lib = std::fs::read_to_string(root.join("src/lib.rs")).unwrap();
    let doc: Vec<&str> = lib
        .lines()
        .take_while(|l| l.starts_with("//!"))
        .map(|l| {
            l.strip_prefix("//! ")
                .unwrap_or(l.trim_start_matches("//!"))
        })
        .collect();
    let open = doc.iter().position(|l| *l == "```").expect("a doctest");
    let len = doc[open + 1..].iter().position(|l| *l == "```").unwrap();
    doc[open + 1..open + 1 + len]
        .iter()
        .filter(|l| !l.starts_with("# "))
        .map(|l| l.to_string())
        .collect()
}

#[test]
fn the_readme_quotes_the_crate_doctest_and_the_firmware_runs_its_lines() {
    let lines = doctest_lines();
    assert!(lines.len() <= 15, "{} lines", lines.len());
    let root = host_tests::obj::workspace_root();
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    // Its hidden lines (`# ...`, compiled but not shown) are left out on both sides.
    let readme: Vec<&str> = readme.lines().filter(|l| !l.starts_with("# ")).collect();
    let readme = readme.join("\n");
    let quoted = format!("```rust\n{}\n```", lines.join("\n"));
    assert!(readme.contains(&quoted), "README does not quote:\n{quoted}");
    // The firmware draws into its framebuffer, not a MockDisplay: every line but
    // the display's, the draw call and the assertion is the same.
    let firmware = std::fs::read_to_string(root.join("firmware/src/cube.rs")).unwrap();
    let firmware: Vec<&str> = firmware.lines().map(str::trim).collect();
    let shared = [
        "const",
        "[-1.",
        "let mesh",
        "let mut cube",
        "cube.bake",
        "let camera",
    ];
    let mut checked = 0;
    for line in lines.iter().map(|l| l.trim()) {
        if shared.iter().any(|s| line.starts_with(s)) {
            assert!(
                firmware.contains(&line),
                "firmware/src/cube.rs lacks `{line}`"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 7);
}
