//! Baked on the host by build.rs and baked at run time by `Drawing::bake` from the
//! same OBJ file: the same pixels.

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::BinaryColor;
use pbuffer::{Camera, Drawing, FrameRows};
use pbuffer_own_model::{bracket, draw, Bracket};

#[test]
fn baked_in_build_rs_and_at_run_time_draw_the_same_pixels() {
    let mut flash = MockDisplay::<BinaryColor>::new();
    let stats = draw(
        &mut Bracket::new(),
        &mut FrameRows::<64, 64>::new(),
        &mut flash,
    )
    .unwrap();

    let model = pbuffer::obj::read(concat!(env!("CARGO_MANIFEST_DIR"), "/models/bracket.obj"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mesh = model.mesh().unwrap();
    assert_eq!(
        (model.vertices.len(), mesh.face_count(), model.indices.len()),
        (
            bracket::BRACKET_V,
            bracket::BRACKET_F,
            bracket::BRACKET_CORNERS
        )
    );
    let mut runtime = Drawing::<16, 14, 28>::new();
    runtime.bake(mesh).unwrap();
    let camera = Camera::fit(&mesh, 64, 64).unwrap();
    let mut ram = MockDisplay::<BinaryColor>::new();
    let again = runtime
        .draw(&camera, &mut FrameRows::<64, 64>::new(), &mut ram)
        .unwrap();

    assert_eq!(flash, ram);
    assert_eq!(stats, again);
    // 28 edges, less the 6 between coplanar quads (two inside each cap, one on the
    // bottom and one on the left side); half of the 14 faces face the eye.
    assert_eq!((stats.feature_edges, stats.faces_drawn), (22, 7));
    assert!(
        flash.affected_area().size.width > 32,
        "the fit fills the frame"
    );
}
