//! A buffer too small for a frame says which buffer and how much the frame really
//! needs (issue 40 item 1): `Drawing::draw` used to report one more than the
//! capacity of whichever active table filled first, so that a user with a RAM
//! budget had to bisect `FACETS` and `LINES` by hand. Both short are named in
//! one error (issue 50; `sizing.rs`).

use pbuffer::prelude::*;
use pbuffer::render::{FastRenderer, MonoPalette};
use pbuffer::subpixel::U4;
use pbuffer::{packed_len, DrawingNeeds, PackedFramebuffer, Stats, Viewport, CLIPPED_CORNERS};

use host_tests::fast::FastBuffers;
use host_tests::setup::MeshArrays;

type Frame = PackedFramebuffer<128, 64, { packed_len(128, 64) }>;

/// cow.obj's vertices, faces and corners (2,903, 5,804, 17,412: `E` is half the
/// corners).
type Cow<const FACETS: usize, const LINES: usize> =
    Drawing<'static, 2903, 5804, 8706, FACETS, LINES>;

fn cow_arrays() -> &'static MeshArrays {
    let path = host_tests::obj::workspace_root().join("../shared/models/cow.obj");
    let data = host_tests::obj::load_obj(&path).expect("cow.obj");
    Box::leak(Box::new(MeshArrays::new(&data)))
}

fn cow_mesh() -> Mesh<'static> {
    let a = cow_arrays();
    Mesh::new(&a.vertices, &a.indices, &a.offsets).expect("mesh")
}

fn camera() -> Camera {
    Camera::look_at([6.0, 4.0, 12.0], [0.8, -0.4, 0.0], 40.0).unwrap()
}

/// Draws cow.obj in a 128 x 64 frame with room for `FACETS` and `LINES`.
fn draw<const FACETS: usize, const LINES: usize>() -> Result<Stats, Error> {
    let mut cow = Box::new(Cow::<FACETS, LINES>::new());
    cow.bake(cow_mesh()).expect("bakes");
    let mut fb = Frame::new();
    cow.draw(&camera(), &mut FrameRows::<128, 64>::new(), &mut fb)
}

/// The peaks of cow.obj's frame, as `Stats` reports them with room to spare.
const FACETS_NEEDED: usize = 129;
const LINES_NEEDED: usize = 106;

fn short(what: Capacity, needed: usize, capacity: usize) -> pbuffer::Shortfall {
    pbuffer::Shortfall {
        what,
        needed,
        capacity,
        at_least: false,
    }
}

fn exceeded(what: Capacity, needed: usize, capacity: usize) -> Result<(), Error> {
    Err(Error::CapacityExceeded {
        what,
        needed,
        capacity,
    })
}

#[test]
fn drawing_needed_is_the_real_need_on_cow() {
    let ample = draw::<1024, 1024>().expect("room to spare");
    assert_eq!(
        (ample.peak_faces as usize, ample.peak_edges as usize),
        (FACETS_NEEDED, LINES_NEEDED)
    );
    // The defaults: both tables are short, and one error says by how much each
    // (issue 50: it used to name only the facets, which ran out first).
    assert_eq!(
        draw::<32, 32>()
            .unwrap_err()
            .shortfalls()
            .iter()
            .collect::<Vec<_>>(),
        [
            short(Capacity::ActiveFacets, FACETS_NEEDED, 32),
            short(Capacity::ActiveLines, LINES_NEEDED, 32),
        ]
    );
    // Facets to spare: the lines, with their own peak.
    assert_eq!(
        draw::<1024, 32>().map(drop),
        exceeded(Capacity::ActiveLines, LINES_NEEDED, 32)
    );
    // What the errors said draws the frame, and one less says the same again.
    assert!(draw::<FACETS_NEEDED, LINES_NEEDED>().is_ok());
    assert_eq!(
        draw::<{ FACETS_NEEDED - 1 }, LINES_NEEDED>().map(drop),
        exceeded(Capacity::ActiveFacets, FACETS_NEEDED, FACETS_NEEDED - 1)
    );
    assert_eq!(
        draw::<FACETS_NEEDED, { LINES_NEEDED - 1 }>().map(drop),
        exceeded(Capacity::ActiveLines, LINES_NEEDED, LINES_NEEDED - 1)
    );
}

#[test]
fn capacity_errors_say_the_buffer_in_words() {
    let e = draw::<32, 1024>().unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("active facets (FACETS): {FACETS_NEEDED} needed, capacity 32")
    );
    let e = draw::<32, 32>().unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "capacities too small: active facets (FACETS): {FACETS_NEEDED} needed, \
             capacity 32; active lines (LINES): {LINES_NEEDED} needed, capacity 32"
        )
    );
}

#[test]
fn measure_tells_every_size_of_a_drawing_at_once() {
    // Tables of one: measuring draws nothing, so they need not fit.
    let mut cow = Box::new(Cow::<1, 1>::new());
    cow.bake(cow_mesh()).expect("bakes");
    let mut rows = FrameRows::<128, 64>::new();
    let viewport = Viewport::new(128, 64).unwrap();
    let needs = cow.measure(&[camera()], &mut rows, viewport).unwrap();
    assert_eq!(
        needs,
        DrawingNeeds {
            vertices: 2903,
            faces: 5804,
            edges: 8706,
            facets: FACETS_NEEDED,
            lines: LINES_NEEDED,
            clipped_corners: 0,
            width: 128,
            height: 64,
        }
    );
    // Several views: the largest need of each.
    let side = Camera::look_at([0.0, 1.0, 14.0], [0.8, -0.4, 0.0], 40.0).unwrap();
    let one = cow.measure(&[side], &mut rows, viewport).unwrap();
    let both = cow.measure(&[camera(), side], &mut rows, viewport).unwrap();
    assert_eq!(both.facets, one.facets.max(FACETS_NEEDED));
    assert_eq!(both.lines, one.lines.max(LINES_NEEDED));
    // The drawing still draws after measuring: its tables of one are too small,
    // and the error names both with the needs measured.
    let mut fb = Frame::new();
    let drawn = cow.draw(&camera(), &mut rows, &mut fb);
    assert_eq!(
        drawn.unwrap_err().shortfalls().iter().collect::<Vec<_>>(),
        [
            short(Capacity::ActiveFacets, FACETS_NEEDED, 1),
            short(Capacity::ActiveLines, LINES_NEEDED, 1),
        ]
    );
}

/// The eye in front of the cow's head: faces cut by the near plane and the
/// screen's edges need 106 clipped corners.
fn close_up() -> Camera {
    Camera::look_at([2.0, 0.0, 2.5], [6.0, 0.0, 0.0], 60.0).unwrap()
}

const CLIPPED_NEEDED: usize = 106;

/// Draws cow.obj in the long form with a clip pool of `pool` corners.
fn draw_with_pool(camera: &Camera, pool: usize) -> Result<Stats, Error> {
    let a = cow_arrays();
    let bake = host_tests::firmware::Bake::new(&a.vertices, &a.indices, &a.offsets);
    let baked = bake.baked();
    let mesh = baked.mesh();
    let (v, edges) = (mesh.vertices().len(), baked.edges());
    let mut buffers = FastBuffers::new(v, mesh.face_count(), edges.len(), 128, 64, pool);
    let mut ws = buffers.workspace();
    ws.ids = &mut [];
    ws.phases = &mut [];
    let mut fb = Frame::new();
    let mut sink = pbuffer::FillSolid::new(&mut fb).expect("fits");
    let mut engine = Box::new(FastRenderer::<U4, 256, 256>::new());
    engine.render(
        &baked,
        camera,
        &Settings::default(),
        &mut ws,
        &MonoPalette::default(),
        &mut sink,
        &mut (),
    )
}

#[test]
fn clipped_corners_needed_is_the_frames_total() {
    let mut cow = Box::new(Cow::<1024, 1024>::new());
    cow.bake(cow_mesh()).expect("bakes");
    let mut rows = FrameRows::<128, 64>::new();
    let viewport = Viewport::new(128, 64).unwrap();
    let needs = cow.measure(&[close_up()], &mut rows, viewport).unwrap();
    assert_eq!(needs.clipped_corners, CLIPPED_NEEDED);
    // A drawing's pool is fixed: the error says what the frame takes.
    let mut fb = Frame::new();
    assert_eq!(
        cow.draw(&close_up(), &mut rows, &mut fb).map(drop),
        exceeded(Capacity::ClippedCorners, CLIPPED_NEEDED, CLIPPED_CORNERS)
    );
    // The long form with that pool draws it; with one corner less its `render`
    // names the pool (its row loop does not count: `FastRenderer::needs` does).
    assert!(draw_with_pool(&close_up(), CLIPPED_NEEDED).is_ok());
    match draw_with_pool(&close_up(), CLIPPED_NEEDED - 1) {
        Err(Error::CapacityExceeded {
            what: Capacity::ClippedCorners,
            needed,
            capacity,
        }) => assert!(needed > capacity && capacity == CLIPPED_NEEDED - 1),
        other => panic!("expected the clip pool to be short: {other:?}"),
    }
}
