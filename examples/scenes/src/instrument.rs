//! The instrument-panel demo: a 128 x 64, 1-bpp display (an SSD1306- or memory-LCD-sized
//! frame) as a part preview would show it. On the left, a 64 x 64 pane with the panel
//! bracket (`scenes::panel`) turning, drawn by pbuffer's fast engine with dashed hidden
//! lines; on the right, embedded-graphics text and primitives: the part's label, the turn
//! angle as a number, and a bar that fills as the part turns.
//!
//! `no_std`, shared by the firmware example `instrument` and the host (the frame-hash
//! test `host_tests/tests/firmware/firmware_examples.rs`, the `instrument` PNG writer and the
//! simulator window `instrument-window` reach it through `host_tests::firmware`), so
//! every one of them draws the very same frames with the very same code.

use core::convert::Infallible;

use embedded_graphics::mono_font::{ascii::FONT_6X10, iso_8859_1::FONT_10X20, MonoTextStyle};
use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Line, PrimitiveStyle, Rectangle};
use embedded_graphics::text::{Alignment, Baseline, Text, TextStyleBuilder};
use micromath::F32Ext;
use pbuffer::render::BakedMesh;
use pbuffer::{packed_len, DrawMode, Error, PackedFramebuffer, Span, SpanSink, Stats, Viewport};

use crate::scenes::{self, PanelFastBuffers, PanelFastEngine, View};

/// Display width in pixels.
pub const WIDTH: usize = 128;
/// Display height in pixels.
pub const HEIGHT: usize = 64;
/// The 3-D pane: the left `PANE` x `HEIGHT` pixels (a whole number of 32-pixel words).
pub const PANE: usize = 64;
/// Frames of one whole turn (the firmware draws them all once).
pub const FRAMES: u32 = 36;
/// Degrees the part turns from one frame to the next.
pub const STEP_DEG: u32 = 360 / FRAMES;

/// The demo's framebuffer: 128 x 64, packed, 1 bit per pixel (1,024 bytes).
pub type Frame = PackedFramebuffer<WIDTH, HEIGHT, { packed_len(WIDTH, HEIGHT) }>;

/// The point the camera looks at: the bracket's middle.
const TARGET: [f32; 3] = [1.5, 0.9, 0.0];
/// The eye's distance from `TARGET` in the ground plane, and its height above it.
const RADIUS: f32 = 6.2;
const RISE: f32 = 3.6;

/// The part's turn in frame `n`, in degrees: 0, 10, ..., 350, then again.
pub fn turn_deg(n: u32) -> u32 {
    (n % FRAMES) * STEP_DEG
}

/// The camera of frame `n`: the eye circles the part (the part seems to turn the other
/// way), looking down at it. The sine and cosine are micromath's, in software, so the
/// firmware and the host compute the same bits.
pub fn view(n: u32) -> View {
    let t = (turn_deg(n) as f32 + 30.0) * (core::f32::consts::PI / 180.0);
    let (s, c) = (F32Ext::sin(t), F32Ext::cos(t));
    View {
        eye: [
            TARGET[0] + RADIUS * s,
            TARGET[1] + RISE,
            TARGET[2] + RADIUS * c,
        ],
        target: TARGET,
        fov_deg: 40.0,
        near: 1.0,
        far: 30.0,
    }
}

/// The left pane of a [`Frame`] as a span sink: the 3-D view's viewport is `PANE` x
/// `HEIGHT`, and its rows go straight into the frame's rows (the pane starts at x = 0).
#[derive(Debug)]
pub struct Pane<'a>(pub &'a mut Frame);

impl SpanSink for Pane<'_> {
    type Color = BinaryColor;
    type Error = Infallible;

    fn viewport(&self) -> Viewport {
        Viewport {
            width: PANE as u16,
            height: HEIGHT as u16,
        }
    }

    fn fill_span(&mut self, span: Span, color: BinaryColor) -> Result<(), Infallible> {
        // The engine clips its spans to the viewport: inside the pane.
        self.0.fill_span(span, color)
    }

    fn fill_mask(&mut self, y: u16, mask: &[u32], color: BinaryColor) -> Result<u32, Infallible> {
        // The pane's words only: the frame's further words are the text's side.
        let words = mask.get(..PANE / 32).unwrap_or(mask);
        self.0.fill_mask(y, words, color)
    }
}

/// Draws frame `n` into `fb`: clears it, draws the turning bracket into the left pane
/// with the fast engine (hidden lines dashed), then the right side's text and bar.
/// Returns the 3-D drawing's statistics.
pub fn draw(
    engine: &mut PanelFastEngine,
    baked: &BakedMesh<'_>,
    buffers: &mut PanelFastBuffers,
    n: u32,
    fb: &mut Frame,
) -> Result<Stats, Error> {
    fb.clear();
    let stats = scenes::render_fast(
        engine,
        baked,
        &view(n),
        DrawMode::Dashed,
        &mut buffers.workspace(),
        &mut Pane(fb),
    )?;
    match draw_readout(turn_deg(n), fb) {
        Ok(()) => Ok(stats),
        Err(never) => match never {},
    }
}

/// The right side: a rule, the label, the turn angle in large digits and a bar of
/// the turn, on any 1-bpp `DrawTarget` (embedded-graphics' fonts and primitives).
pub fn draw_readout<D: DrawTarget<Color = BinaryColor>>(
    deg: u32,
    target: &mut D,
) -> Result<(), D::Error> {
    let on = PrimitiveStyle::with_stroke(BinaryColor::On, 1);
    let x0 = PANE as i32 + 2;
    let right = WIDTH as i32 - 1;
    Line::new(Point::new(PANE as i32, 0), Point::new(PANE as i32, 63))
        .into_styled(on)
        .draw(target)?;
    let small = MonoTextStyle::new(&FONT_6X10, BinaryColor::On);
    let top = TextStyleBuilder::new().baseline(Baseline::Top).build();
    Text::with_text_style("PART 7", Point::new(x0 + 1, 1), small, top).draw(target)?;
    Line::new(Point::new(x0, 12), Point::new(right, 12))
        .into_styled(on)
        .draw(target)?;
    Text::with_text_style("TURN", Point::new(x0 + 1, 15), small, top).draw(target)?;

    // The angle, right-aligned, with a degree sign (ISO 8859-1 has it).
    let mut buf = [0u8; 6];
    let text = degrees(deg, &mut buf);
    let big = MonoTextStyle::new(&FONT_10X20, BinaryColor::On);
    let flush_right = TextStyleBuilder::new()
        .baseline(Baseline::Top)
        .alignment(Alignment::Right)
        .build();
    Text::with_text_style(text, Point::new(right, 27), big, flush_right).draw(target)?;

    // The bar: an outline, filled as far as the part has turned.
    let bar = Rectangle::new(Point::new(x0, 53), Size::new((right - x0 + 1) as u32, 9));
    bar.into_styled(on).draw(target)?;
    let inner = bar.size.width - 4;
    let filled = inner * deg / 360;
    if filled > 0 {
        Rectangle::new(bar.top_left + Point::new(2, 2), Size::new(filled, 5))
            .into_styled(PrimitiveStyle::with_fill(BinaryColor::On))
            .draw(target)?;
    }
    Ok(())
}

/// `deg` (below 1,000) in decimal and a degree sign, written into `buf`.
fn degrees(deg: u32, buf: &mut [u8; 6]) -> &str {
    let mut len = 0;
    let mut started = false;
    for div in [100, 10, 1] {
        let d = (deg / div) % 10;
        if d != 0 || started || div == 1 {
            buf[len] = b'0' + d as u8;
            len += 1;
            started = true;
        }
    }
    // U+00B0 DEGREE SIGN in UTF-8.
    buf[len] = 0xC2;
    buf[len + 1] = 0xB0;
    core::str::from_utf8(&buf[..len + 2]).unwrap_or("?")
}
