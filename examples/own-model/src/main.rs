//! Draws the baked bracket at 64 x 64 and prints it as text (`#` lines, `.` blank).

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::Point;
use pbuffer::FrameRows;
use pbuffer_own_model::{draw, Bracket};

fn main() -> Result<(), pbuffer::Error> {
    let mut display = MockDisplay::<BinaryColor>::new();
    let stats = draw(
        &mut Bracket::new(),
        &mut FrameRows::<64, 64>::new(),
        &mut display,
    )?;
    for y in 0..64 {
        let row: String = (0..64)
            .map(|x| match display.get_pixel(Point::new(x, y)) {
                Some(BinaryColor::On) => '#',
                _ => '.',
            })
            .collect();
        println!("{row}");
    }
    println!(
        "{} faces drawn, {} feature edges",
        stats.faces_drawn, stats.feature_edges
    );
    Ok(())
}
