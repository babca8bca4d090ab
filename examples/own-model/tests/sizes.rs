//! The sizes the bake emits fit the bracket: `Bracket`, sized by `BRACKET_FACETS`
//! and `BRACKET_LINES`, draws every view the bake sized them for (64 x 64, 24
//! directions around the model), and one of those views needs each in full.

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::BinaryColor;
use pbuffer::bake::BakeOptions;
use pbuffer::FrameRows;
use pbuffer_own_model::{bracket, Bracket};

#[test]
fn the_bracket_alias_draws_every_view_the_bake_sized_it_for() {
    let mesh = bracket::bracket_baked().unwrap();
    let views = BakeOptions {
        width: 64,
        height: 64,
        ..Default::default()
    };
    let mut drawing = Bracket::with_mesh(mesh).unwrap();
    let (mut facets, mut lines) = (0, 0);
    for camera in views.cameras(mesh.mesh()).unwrap() {
        let mut display = MockDisplay::<BinaryColor>::new();
        let stats = drawing
            .draw(&camera, &mut FrameRows::<64, 64>::new(), &mut display)
            .unwrap_or_else(|e| panic!("{e}"));
        facets = facets.max(stats.peak_faces as usize);
        lines = lines.max(stats.peak_edges as usize);
    }
    assert_eq!(
        (facets, lines),
        (bracket::BRACKET_FACETS, bracket::BRACKET_LINES)
    );
    // Its RAM, as the README's table gives it for a 64-bit host.
    assert_eq!(
        Bracket::RAM_BYTES,
        pbuffer::ram::baked_drawing_bytes(
            bracket::BRACKET_V,
            bracket::BRACKET_F,
            bracket::BRACKET_E,
            bracket::BRACKET_FACETS,
            bracket::BRACKET_LINES
        )
    );
}
