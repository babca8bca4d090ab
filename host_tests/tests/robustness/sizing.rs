//! Sizing in one step (issue 50, item 3): a user sizing cow.obj read at run time
//! needed five runs, one error each (`V`, `F`, `E`, `FACETS`, `LINES`); the bake
//! printed `V`, `F`, `E` only, and nothing said what a capacity costs in RAM.

use pbuffer::bake::{mesh_to_rust_with, BakeOptions};
use pbuffer::prelude::*;
use pbuffer::{ram, BakedDrawing, Shortfall, Viewport};

/// cow.obj, read as a user reads it (`pbuffer::obj`), kept for the test's run.
fn cow_obj() -> &'static pbuffer::obj::ObjMesh<f32> {
    let path = host_tests::obj::workspace_root().join("../shared/models/cow.obj");
    Box::leak(Box::new(
        pbuffer::obj::read(path).unwrap_or_else(|e| panic!("{e}")),
    ))
}

/// cow.obj's vertices, faces and edges (`E`: its unique edges, half its corners).
type Cow<const FACETS: usize, const LINES: usize> =
    Drawing<'static, 2903, 5804, 8706, FACETS, LINES>;

fn short(what: Capacity, needed: usize, capacity: usize, at_least: bool) -> Shortfall {
    Shortfall {
        what,
        needed,
        capacity,
        at_least,
    }
}

#[test]
fn a_cube_sized_drawing_of_the_cow_names_v_f_and_e_in_one_error() {
    let obj = cow_obj();
    let mesh = obj.mesh().unwrap();
    let error = Drawing::<8, 6, 12>::new().bake(mesh).unwrap_err();
    assert_eq!(
        error.shortfalls().iter().collect::<Vec<_>>(),
        [
            short(Capacity::Vertices, 2903, 8, false),
            short(Capacity::Faces, 5804, 6, false),
            // The unique edges are counted once `V` fits: until then, half the
            // corners (cow.obj's unique edges are exactly that).
            short(Capacity::Edges, 8706, 12, true),
        ]
    );
    assert_eq!(
        error.to_string(),
        "capacities too small: mesh vertices (V): 2903 needed, capacity 8; \
         mesh faces (F): 5804 needed, capacity 6; \
         mesh edges (E): at least 8706 needed, capacity 12"
    );
    // What the error said bakes.
    let mut sized = Box::new(Cow::<1, 1>::new());
    assert_eq!(sized.bake(mesh), Ok(()));
}

#[test]
fn with_v_f_and_e_fitting_too_few_facets_and_lines_are_named_in_one_error() {
    let obj = cow_obj();
    let mesh = obj.mesh().unwrap();
    let camera = Camera::fit(&mesh, 128, 64).unwrap();
    let mut rows = FrameRows::<128, 64>::new();
    let mut display = PackedFramebuffer128x64::new();
    let mut cow = Box::new(Cow::<32, 32>::new());
    cow.bake(mesh).unwrap();
    let error = cow.draw(&camera, &mut rows, &mut display).unwrap_err();
    let viewport = Viewport::new(128, 64).unwrap();
    let needs = cow.measure(&[camera], &mut rows, viewport).unwrap();
    assert!(needs.facets > 32 && needs.lines > 32, "{needs:?}");
    assert_eq!(
        error.shortfalls().iter().collect::<Vec<_>>(),
        [
            short(Capacity::ActiveFacets, needs.facets, 32, false),
            short(Capacity::ActiveLines, needs.lines, 32, false),
        ]
    );
    assert_eq!(
        error.to_string(),
        format!(
            "capacities too small: active facets (FACETS): {} needed, capacity 32; \
             active lines (LINES): {} needed, capacity 32",
            needs.facets, needs.lines
        )
    );
    // The measured needs are the frame's peaks: a drawing with room to spare
    // reports the same.
    let mut ample = Box::new(Cow::<1024, 1024>::new());
    ample.bake(mesh).unwrap();
    let stats = ample.draw(&camera, &mut rows, &mut display).unwrap();
    assert_eq!(
        (stats.peak_faces as usize, stats.peak_edges as usize),
        (needs.facets, needs.lines)
    );
}

type PackedFramebuffer128x64 =
    pbuffer::PackedFramebuffer<128, 64, { pbuffer::packed_len(128, 64) }>;

/// The number after `= ` on the line `pub const {name}: usize = N;`.
fn constant(source: &str, name: &str) -> usize {
    let head = format!("pub const {name}: usize = ");
    let line = source
        .lines()
        .find_map(|l| l.strip_prefix(head.as_str()))
        .unwrap_or_else(|| panic!("{name} missing"));
    line.trim_end_matches(';').parse().unwrap()
}

#[test]
fn the_bake_emits_facets_and_lines_for_the_views_it_names() {
    let obj = cow_obj();
    let mesh = obj.mesh().unwrap();
    let views = BakeOptions {
        width: 128,
        height: 64,
        views: 16,
    };
    let source = mesh_to_rust_with(&mesh, "COW", "cow.obj", &views).unwrap();
    let (facets, lines) = (
        constant(&source, "COW_FACETS"),
        constant(&source, "COW_LINES"),
    );
    assert_eq!(
        (constant(&source, "COW_V"), constant(&source, "COW_F")),
        (2903, 5804)
    );
    // Each of the 16 views drawn with room to spare peaks at most there, and
    // one of them at each.
    let mut cow = Box::new(Cow::<1024, 1024>::new());
    cow.bake(mesh).unwrap();
    let mut rows = FrameRows::<128, 64>::new();
    let (mut most_facets, mut most_lines) = (0, 0);
    let cameras = views.cameras(&mesh).unwrap();
    assert_eq!(cameras.len(), 16);
    assert_eq!(cameras[0], Camera::fit(&mesh, 128, 64).unwrap());
    for camera in &cameras {
        let mut display = PackedFramebuffer128x64::new();
        let stats = cow.draw(camera, &mut rows, &mut display).unwrap();
        most_facets = most_facets.max(stats.peak_faces as usize);
        most_lines = most_lines.max(stats.peak_edges as usize);
    }
    assert_eq!((most_facets, most_lines), (facets, lines));
    // And the source says which views they hold for.
    assert!(
        source.contains("over 16 views turned about the vertical axis")
            && source.contains("each fitted to a 128 x 64 frame"),
        "{source:.200}"
    );
}

#[test]
fn ram_bytes_are_the_sizes_of_the_types() {
    assert_eq!(
        Cow::<118, 85>::RAM_BYTES,
        ram::drawing_bytes(2903, 5804, 8706, 118, 85)
    );
    assert_eq!(
        Cow::<118, 85>::RAM_BYTES,
        core::mem::size_of::<Cow<118, 85>>()
    );
    type Baked = BakedDrawing<'static, 2903, 5804, 8706, 118, 85>;
    assert_eq!(
        Baked::RAM_BYTES,
        ram::baked_drawing_bytes(2903, 5804, 8706, 118, 85)
    );
    assert_eq!(Baked::RAM_BYTES, core::mem::size_of::<Baked>());
    assert_eq!(
        FrameRows::<400, 240>::RAM_BYTES,
        ram::frame_rows_bytes(400, 240)
    );
    // What the measured needs cost, in one call.
    let obj = cow_obj();
    let mesh = obj.mesh().unwrap();
    let mut cow = Box::new(Cow::<1, 1>::new());
    cow.bake(mesh).unwrap();
    let viewport = Viewport::new(128, 64).unwrap();
    let camera = Camera::fit(&mesh, 128, 64).unwrap();
    let needs = cow
        .measure(&[camera], &mut FrameRows::<128, 64>::new(), viewport)
        .unwrap();
    assert_eq!(
        needs.drawing_bytes(),
        ram::drawing_bytes(2903, 5804, 8706, needs.facets, needs.lines)
    );
    assert_eq!(needs.frame_rows_bytes(), FrameRows::<128, 64>::RAM_BYTES);
}

#[test]
fn naming_every_shortfall_keeps_the_error_as_small_as_it_was() {
    // 48 bytes on a 64-bit host, as before the list: the largest variant is a
    // coding scheme's (a 128-bit code).
    assert_eq!(core::mem::size_of::<Error>(), 48);
    assert!(core::mem::size_of::<pbuffer::Shortfalls>() <= 40);
}
