//! A user's own model, the whole path: `models/bracket.obj` baked by `build.rs`
//! (`pbuffer::bake::obj_to_rust`) into `static`s, drawn by the short API
//! ([`BakedDrawing`], sized by the generated constants) with a camera fitted to the
//! mesh ([`Camera::fit`]). Nothing is baked, parsed or allocated at run time.
#![no_std]
#![forbid(unsafe_code)]

use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::DrawTarget;
use pbuffer::prelude::*;

/// The bracket as `build.rs` baked it: `BRACKET_V`, `BRACKET_F`, `BRACKET_E`,
/// `BRACKET_FACETS`, `BRACKET_LINES`, the statics and `bracket_baked()`.
pub mod bracket {
    include!(concat!(env!("OUT_DIR"), "/bracket.rs"));
}

/// The short API for the baked bracket: every buffer sized by the bake, `FACETS`
/// and `LINES` for the bake's views (64 x 64, around the model).
pub type Bracket = BakedDrawing<
    'static,
    { bracket::BRACKET_V },
    { bracket::BRACKET_F },
    { bracket::BRACKET_E },
    { bracket::BRACKET_FACETS },
    { bracket::BRACKET_LINES },
>;

/// Draws the bracket into `target` (up to `W` x `H`), its camera fitted to the mesh
/// and the target's size.
pub fn draw<D: DrawTarget<Color = BinaryColor>, const W: usize, const H: usize>(
    drawing: &mut Bracket,
    rows: &mut FrameRows<W, H>,
    target: &mut D,
) -> Result<Stats, Error<D::Error>> {
    let mesh = bracket::bracket_baked().map_err(Error::widen)?;
    let size = target.bounding_box().size;
    let camera = Camera::fit(mesh.mesh(), size.width, size.height).map_err(Error::widen)?;
    drawing.set_mesh(mesh).map_err(Error::widen)?;
    drawing.draw(&camera, rows, target)
}
