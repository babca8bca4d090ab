//! The frames on real panel drivers (`panel-ssd1306`, `suzanne-sharp`): the `ssd1306`
//! crate's buffered `DrawTarget` (128 x 64, I2C) and the `sharp-memory-display` crate's
//! (400 x 240, LS027B7DH01, SPI). `no_std`; shared with the host test
//! `host_tests/tests/firmware/panel_bus.rs` (through this crate), so the host drives the very
//! same code against `embedded-hal-mock` buses.
//!
//! A frame reaches the driver's buffer in one of three ways, measured by the examples:
//!
//! - **direct, `Pixels`** (the documented way, the fastest on both panels): the
//!   renderer's spans and row masks go straight into the driver's buffer through its
//!   `DrawTarget`, as `draw_iter` calls of their lit pixels ([`render_direct`]);
//! - **direct, `fill_solid`**: the same through pbuffer's `FillSolid` sink, one
//!   `fill_solid` a span ([`render_fill_solid`]);
//! - **copy**: the frame is drawn into pbuffer's `PackedFramebuffer` and its lit pixels
//!   are then copied into the driver's buffer ([`copy_frame`]).
//!
//! Every way, the driver's `flush` then writes the same bytes to the bus.

use core::cell::RefCell;
use core::convert::Infallible;

use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::{DrawTarget, OriginDimensions, Point, Size};
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;
use embedded_graphics_core_03 as eg03;
use pbuffer::render::{BakedMesh, FastRenderer, FastWorkspace};
use pbuffer::{DrawMode, Error, FillSolid, PackedFramebuffer, Span, SpanSink, Stats, Viewport};

use crate::scenes::{self, View};

/// The bytes a driver wrote to its bus, kept in lent memory: the bytes in order and
/// where each write (an I2C write, an SPI `write` call) ended.
#[derive(Debug)]
pub struct Record<'a> {
    bytes: &'a mut [u8],
    len: usize,
    ends: &'a mut [u32],
    writes: usize,
    lost: usize,
}

impl<'a> Record<'a> {
    /// An empty record into `bytes` (the bus bytes) and `ends` (one entry a write).
    pub fn new(bytes: &'a mut [u8], ends: &'a mut [u32]) -> Self {
        Self {
            bytes,
            len: 0,
            ends,
            writes: 0,
            lost: 0,
        }
    }

    /// Forgets what was recorded.
    pub fn clear(&mut self) {
        self.len = 0;
        self.writes = 0;
        self.lost = 0;
    }

    /// The bytes written since the last [`clear`](Self::clear), in order.
    pub fn bytes(&self) -> &[u8] {
        self.bytes.get(..self.len).unwrap_or_default()
    }

    /// Where each write ended (offsets into [`bytes`](Self::bytes)).
    pub fn ends(&self) -> &[u32] {
        self.ends.get(..self.writes).unwrap_or_default()
    }

    /// Bytes or writes that did not fit the lent memory (0 when the record is whole).
    pub fn lost(&self) -> usize {
        self.lost
    }

    fn write(&mut self, bytes: &[u8]) {
        let end = self.len + bytes.len();
        match self.bytes.get_mut(self.len..end) {
            Some(slot) => {
                slot.copy_from_slice(bytes);
                self.len = end;
            }
            None => self.lost += bytes.len(),
        }
        match self.ends.get_mut(self.writes) {
            Some(slot) => {
                *slot = self.len as u32;
                self.writes += 1;
            }
            None => self.lost += 1,
        }
    }
}

/// A bus that records what is written to it: an embedded-hal 1.0 I2C bus (the
/// `ssd1306` crate's) and an embedded-hal 0.2 SPI bus (the `sharp-memory-display`
/// crate's). I2C addresses are not recorded: only the bytes each write carries.
#[derive(Debug, Clone, Copy)]
pub struct Tap<'r, 'a>(pub &'r RefCell<Record<'a>>);

impl embedded_hal::i2c::ErrorType for Tap<'_, '_> {
    type Error = Infallible;
}

impl embedded_hal::i2c::I2c for Tap<'_, '_> {
    fn transaction(
        &mut self,
        _address: u8,
        operations: &mut [embedded_hal::i2c::Operation<'_>],
    ) -> Result<(), Infallible> {
        for op in operations {
            if let embedded_hal::i2c::Operation::Write(bytes) = op {
                self.0.borrow_mut().write(bytes);
            }
        }
        Ok(())
    }
}

impl embedded_hal_02::blocking::spi::Write<u8> for Tap<'_, '_> {
    type Error = Infallible;

    fn write(&mut self, words: &[u8]) -> Result<(), Infallible> {
        self.0.borrow_mut().write(words);
        Ok(())
    }
}

/// An output pin that goes nowhere (the Sharp display's chip select and DISP pins
/// under QEMU).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoPin;

impl embedded_hal_02::digital::v2::OutputPin for NoPin {
    type Error = Infallible;

    fn set_low(&mut self) -> Result<(), Infallible> {
        Ok(())
    }

    fn set_high(&mut self) -> Result<(), Infallible> {
        Ok(())
    }
}

/// The SSD1306 driver in buffered graphics mode on an I2C bus (address 0x3C).
pub type Ssd1306Display<I2C> = ssd1306::Ssd1306<
    ssd1306::prelude::I2CInterface<I2C>,
    ssd1306::size::DisplaySize128x64,
    ssd1306::mode::BufferedGraphicsMode<ssd1306::size::DisplaySize128x64>,
>;

/// A 128 x 64 SSD1306 on `i2c`, not rotated, in buffered graphics mode (call its
/// `init` before the first flush).
pub fn ssd1306_display<I2C: embedded_hal::i2c::I2c>(i2c: I2C) -> Ssd1306Display<I2C> {
    ssd1306::Ssd1306::new(
        ssd1306::I2CDisplayInterface::new(i2c),
        ssd1306::size::DisplaySize128x64,
        ssd1306::prelude::DisplayRotation::Rotate0,
    )
    .into_buffered_graphics_mode()
}

/// The Sharp memory LCD driver (LS027B7DH01, 400 x 240).
pub type SharpDisplay<SPI, CS, DISP> = sharp_memory_display::MemoryDisplay<SPI, CS, DISP>;

/// A Sharp LS027B7DH01 on `spi` with chip select `cs` and display-enable `disp`,
/// enabled, its buffer cleared to off (a set bit is `BinaryColor::On`).
pub fn sharp_display<SPI, CS, DISP, E>(spi: SPI, cs: CS, disp: DISP) -> SharpDisplay<SPI, CS, DISP>
where
    SPI: embedded_hal_02::blocking::spi::Write<u8, Error = E>,
    CS: embedded_hal_02::digital::v2::OutputPin,
    DISP: embedded_hal_02::digital::v2::OutputPin,
{
    let mut display = sharp_memory_display::MemoryDisplay::new(spi, cs, disp);
    display.set_clear_state(eg03::pixelcolor::BinaryColor::Off);
    display.enable();
    display.clear_buffer();
    display
}

/// The Sharp driver seen as an embedded-graphics 0.8 `DrawTarget`: the driver is
/// written for embedded-graphics 0.7 (`embedded-graphics-core` 0.3), pbuffer for 0.8
/// (core 0.4). Pixels and `fill_solid` go through to the driver's own `DrawTarget`.
#[derive(Debug)]
pub struct Sharp<'d, D>(pub &'d mut D);

impl<D: eg03::geometry::OriginDimensions> OriginDimensions for Sharp<'_, D> {
    fn size(&self) -> Size {
        let s = self.0.size();
        Size::new(s.width, s.height)
    }
}

fn color03(c: BinaryColor) -> eg03::pixelcolor::BinaryColor {
    eg03::pixelcolor::BinaryColor::from(c.is_on())
}

impl<D> DrawTarget for Sharp<'_, D>
where
    D: eg03::draw_target::DrawTarget<Color = eg03::pixelcolor::BinaryColor>
        + eg03::geometry::OriginDimensions,
{
    type Color = BinaryColor;
    type Error = D::Error;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), D::Error>
    where
        I: IntoIterator<Item = Pixel<BinaryColor>>,
    {
        self.0.draw_iter(
            pixels
                .into_iter()
                .map(|Pixel(p, c)| eg03::Pixel(eg03::geometry::Point::new(p.x, p.y), color03(c))),
        )
    }

    fn fill_solid(&mut self, area: &Rectangle, color: BinaryColor) -> Result<(), D::Error> {
        let area = eg03::primitives::Rectangle::new(
            eg03::geometry::Point::new(area.top_left.x, area.top_left.y),
            eg03::geometry::Size::new(area.size.width, area.size.height),
        );
        self.0.fill_solid(&area, color03(color))
    }
}

/// A span sink that hands a driver's `DrawTarget` pixels, not rectangles: a span is
/// one `draw_iter` of its pixels, a row's mask (`SpanSink::fill_mask`) one `draw_iter`
/// of its set bits. For drivers that set pixel by pixel anyway (both here do), it
/// skips what `fill_solid`'s default path costs a span.
#[derive(Debug)]
pub struct Pixels<'d, D> {
    target: &'d mut D,
    viewport: Viewport,
}

impl<'d, D: DrawTarget<Color = BinaryColor>> Pixels<'d, D> {
    /// Wraps a driver's draw target of `width` x `height` pixels.
    pub fn new(target: &'d mut D, width: u16, height: u16) -> Self {
        Self {
            target,
            viewport: Viewport { width, height },
        }
    }
}

impl<D: DrawTarget<Color = BinaryColor>> SpanSink for Pixels<'_, D> {
    type Color = BinaryColor;
    type Error = D::Error;

    fn viewport(&self) -> Viewport {
        self.viewport
    }

    fn fill_span(&mut self, span: Span, color: BinaryColor) -> Result<(), D::Error> {
        let y = i32::from(span.y());
        self.target.draw_iter(
            (span.x0()..span.x1()).map(move |x| Pixel(Point::new(i32::from(x), y), color)),
        )
    }

    fn fill_mask(&mut self, y: u16, mask: &[u32], color: BinaryColor) -> Result<u32, D::Error> {
        let width = u32::from(self.viewport.width);
        let y = i32::from(y);
        let words = mask.iter().filter(|&&w| w != 0).count() as u32;
        let lit = mask.iter().enumerate().flat_map(move |(k, &word)| {
            let base = 32 * k as u32;
            let mut bits = word;
            core::iter::from_fn(move || {
                let b = bits.trailing_zeros();
                (bits != 0).then(|| {
                    bits &= bits - 1;
                    base + b
                })
            })
            .filter(move |&x| x < width)
            .map(move |x| Pixel(Point::new(x as i32, y), color))
        });
        self.target.draw_iter(lit)?;
        Ok(words)
    }
}

/// Way **direct**, with `fill_solid` a span (embedded-graphics' usual path: pbuffer's
/// `FillSolid` sink): draws frame `view` of `baked` (dashed hidden lines, the
/// examples' settings) straight into `target`, a driver's `DrawTarget`. The caller
/// clears the driver's buffer first.
pub fn render_fill_solid<D, const FACETS: usize, const LINES: usize>(
    engine: &mut FastRenderer<fixed::types::extra::U4, FACETS, LINES>,
    baked: &BakedMesh<'_>,
    view: &View,
    ws: &mut FastWorkspace<'_>,
    target: &mut D,
) -> Result<Stats, Error<D::Error>>
where
    D: DrawTarget<Color = BinaryColor>,
{
    let mut sink = FillSolid::new(target).map_err(Error::widen)?;
    scenes::render_fast_to(engine, baked, view, DrawMode::Dashed, ws, &mut sink)
}

/// Way **direct**: draws frame `view` of `baked` (dashed hidden lines, the examples'
/// settings) straight into `target`, a driver's `DrawTarget`, through the [`Pixels`]
/// sink. The caller clears the driver's buffer first.
pub fn render_direct<D, const FACETS: usize, const LINES: usize>(
    engine: &mut FastRenderer<fixed::types::extra::U4, FACETS, LINES>,
    baked: &BakedMesh<'_>,
    view: &View,
    ws: &mut FastWorkspace<'_>,
    target: &mut D,
) -> Result<Stats, Error<D::Error>>
where
    D: DrawTarget<Color = BinaryColor>,
{
    let size = target.bounding_box().size;
    let (width, height) = (
        u16::try_from(size.width).map_err(|_| Error::OutOfRange)?,
        u16::try_from(size.height).map_err(|_| Error::OutOfRange)?,
    );
    let mut sink = Pixels::new(target, width, height);
    scenes::render_fast_to(engine, baked, view, DrawMode::Dashed, ws, &mut sink)
}

/// Way **copy**, its second half: copies the lit pixels of the finished frame `fb`
/// into `target`, a driver's `DrawTarget` whose buffer the caller has cleared (one
/// `draw_iter` call; bytes with no lit pixel are skipped).
pub fn copy_frame<D, const W: usize, const H: usize, const N: usize>(
    fb: &PackedFramebuffer<W, H, N>,
    target: &mut D,
) -> Result<(), D::Error>
where
    D: DrawTarget<Color = BinaryColor>,
{
    let stride = W.div_ceil(8);
    let lit = fb
        .as_bytes()
        .chunks_exact(stride)
        .enumerate()
        .flat_map(move |(y, row)| {
            row.iter()
                .enumerate()
                .filter(|&(_, &b)| b != 0)
                .flat_map(move |(i, &b)| {
                    (0..8).filter(move |k| b & (0x80 >> k) != 0).map(move |k| {
                        Pixel(Point::new((8 * i + k) as i32, y as i32), BinaryColor::On)
                    })
                })
        });
    target.draw_iter(lit)
}

/// The instrument demo on an SSD1306 for ever (the board examples' main loop): the
/// display initialised, then each frame drawn into `fb`, its lit pixels copied into
/// the driver's cleared buffer and flushed; one turn is
/// [`FRAMES`](crate::instrument::FRAMES) frames. A fault of the display or the
/// engine stops it with a panic, which a board reports as it can.
pub fn run_instrument_ssd1306<I2C: embedded_hal::i2c::I2c>(
    display: &mut Ssd1306Display<I2C>,
    engine: &mut crate::scenes::PanelFastEngine,
    baked: &BakedMesh<'_>,
    buffers: &mut crate::scenes::PanelFastBuffers,
    fb: &mut crate::instrument::Frame,
) -> ! {
    use ssd1306::mode::DisplayConfig;
    display.init().unwrap();
    let mut n = 0;
    loop {
        crate::instrument::draw(engine, baked, buffers, n, fb).unwrap();
        display.clear_buffer();
        copy_frame(fb, display).unwrap();
        display.flush().unwrap();
        n = (n + 1) % crate::instrument::FRAMES;
    }
}
