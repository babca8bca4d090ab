//! The instrument-panel demo (`pbuffer_scenes::instrument`) on an ESP32-C3 with an SSD1306
//! 128 x 64 OLED on I2C0 (GPIO5 SDA, GPIO6 SCL, 400 kHz), as on the Pico
//! (`../pico-ssd1306`): each frame drawn into the demo's packed frame, its lit pixels
//! copied into the `ssd1306` crate's buffer and flushed; one turn is 36 frames.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use esp_hal::clock::CpuClock;
use esp_hal::i2c::master::{Config, I2c};
use esp_hal::time::Rate;
use pbuffer_scenes::instrument::Frame;
use pbuffer_scenes::panels;
use pbuffer_scenes::scenes::{PanelFastBuffers, PanelFastEngine};

// The application descriptor the ESP-IDF second-stage boot loader checks.
esp_bootloader_esp_idf::esp_app_desc!();

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

/// The panel bracket's statics and fast-engine constants, baked by build.rs
/// (`PANEL_...`, `panel_baked()`; the bake's sizes and edge list are not used here).
#[allow(dead_code)]
mod part {
    include!(concat!(env!("OUT_DIR"), "/panel.rs"));
}

static mut FB: Frame = Frame::new();
static mut BUFFERS: PanelFastBuffers = PanelFastBuffers::new();
static mut ENGINE: PanelFastEngine = PanelFastEngine::new();

#[esp_hal::main]
fn main() -> ! {
    // 160 MHz.
    let p = esp_hal::init(esp_hal::Config::default().with_cpu_clock(CpuClock::max()));
    let i2c = I2c::new(
        p.I2C0,
        Config::default().with_frequency(Rate::from_khz(400)),
    )
    .unwrap()
    .with_sda(p.GPIO5)
    .with_scl(p.GPIO6);
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
