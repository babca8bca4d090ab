//! The instrument-panel demo (`pbuffer_scenes::instrument`) on a Raspberry Pi Pico with an
//! SSD1306 128 x 64 OLED on I2C0 (GP4 SDA, GP5 SCL, 400 kHz): the panel bracket turning
//! in a 64 x 64 pane, hidden lines dashed, beside its label, turn angle and a bar. Each
//! frame is drawn into the demo's packed frame, its lit pixels copied into the `ssd1306`
//! crate's buffer (`panels::copy_frame`) and flushed over I2C; one turn is 36 frames,
//! and the loop runs as fast as the bus takes the frames.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use panic_halt as _;
use pbuffer_scenes::instrument::Frame;
use pbuffer_scenes::panels;
use pbuffer_scenes::scenes::{PanelFastBuffers, PanelFastEngine};
use rp2040_hal::fugit::RateExtU32;
use rp2040_hal::gpio::{FunctionI2C, Pin, PullUp};
use rp2040_hal::{self as hal, pac, Clock};

/// The second-stage boot loader for the Pico's W25Q080 flash, first in flash (memory.x).
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal.
const XTAL_FREQ_HZ: u32 = 12_000_000;

/// The panel bracket's statics and fast-engine constants, baked by build.rs
/// (`PANEL_...`, `panel_baked()`; the bake's sizes and edge list are not used here).
#[allow(dead_code)]
mod part {
    include!(concat!(env!("OUT_DIR"), "/panel.rs"));
}

static mut FB: Frame = Frame::new();
static mut BUFFERS: PanelFastBuffers = PanelFastBuffers::new();
static mut ENGINE: PanelFastEngine = PanelFastEngine::new();

#[hal::entry]
fn main() -> ! {
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    // 125 MHz system clock from the 12 MHz crystal.
    let clocks = hal::clocks::init_clocks_and_plls(
        XTAL_FREQ_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .ok()
    .unwrap();
    let sio = hal::Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let sda: Pin<_, FunctionI2C, PullUp> = pins.gpio4.reconfigure();
    let scl: Pin<_, FunctionI2C, PullUp> = pins.gpio5.reconfigure();
    let i2c = hal::I2C::i2c0(
        pac.I2C0,
        sda,
        scl,
        400.kHz(),
        &mut pac.RESETS,
        clocks.system_clock.freq(),
    );
    let mut display = panels::ssd1306_display(i2c);
    // SAFETY: main runs once; these are its only references to the statics.
    let (fb, buffers, engine) = unsafe {
        (
            &mut *addr_of_mut!(FB),
            &mut *addr_of_mut!(BUFFERS),
            &mut *addr_of_mut!(ENGINE),
        )
    };
    // The baked constants are checked once, at boot.
    let baked = part::panel_baked().unwrap();
    panels::run_instrument_ssd1306(&mut display, engine, &baked, buffers, fb)
}
