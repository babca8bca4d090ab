//! Suzanne turning on an STM32F411 "Black Pill" with a Sharp LS027B7DH01 400 x 240 memory
//! LCD on SPI1 (PA5 SCK, PA7 MOSI, PA4 chip select, PA3 DISP; 2 MHz): the QEMU example
//! `suzanne-sharp`'s views (`pbuffer_scenes::scenes::suzanne`), drawn by pbuffer's fast
//! engine with dashed hidden lines straight into the `sharp-memory-display` crate's
//! buffer (`panels::render_direct`, the `Pixels` sink), then flushed. The eye swings
//! through the 8 views and back; each flush toggles the panel's VCOM, as the panel needs
//! at least once a second.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use panic_halt as _;
use pbuffer_scenes::panels::{self, Sharp};
use pbuffer_scenes::scenes::{suzanne as scene, FastEngine, SuzanneFastBuffers};
use stm32f4xx_hal::pac::{self, SPI1};
use stm32f4xx_hal::prelude::*;
use stm32f4xx_hal::rcc::Config;

/// Suzanne's statics and fast-engine constants, baked by build.rs (`SUZANNE_...`,
/// `suzanne_baked()`; the bake's sizes and edge list are not used here).
#[allow(dead_code)]
mod suzanne {
    include!(concat!(env!("OUT_DIR"), "/suzanne.rs"));
}

/// Frames of one swing through the views and back.
const SWING: u32 = 2 * scene::FRAMES - 2;

static mut BUFFERS: SuzanneFastBuffers = SuzanneFastBuffers::new();
static mut ENGINE: FastEngine = FastEngine::new();

#[entry]
fn main() -> ! {
    let dp = pac::Peripherals::take().unwrap();
    // 100 MHz from the Black Pill's 25 MHz crystal.
    let mut rcc = dp.RCC.freeze(Config::hse(25.MHz()).sysclk(100.MHz()));
    let gpioa = dp.GPIOA.split(&mut rcc);
    let spi = dp.SPI1.spi(
        (Some(gpioa.pa5), SPI1::NoMiso, Some(gpioa.pa7)),
        sharp_memory_display::MODE,
        2.MHz(),
        &mut rcc,
    );
    let cs = gpioa.pa4.into_push_pull_output();
    let disp = gpioa.pa3.into_push_pull_output();
    let mut display = panels::sharp_display(spi, cs, disp);
    display.clear();

    // SAFETY: main runs once; these are its only references to the statics.
    let (buffers, engine) = unsafe { (&mut *addr_of_mut!(BUFFERS), &mut *addr_of_mut!(ENGINE)) };
    // The baked constants are checked once, at boot.
    let baked = suzanne::suzanne_baked().unwrap();
    let mut n = 0;
    loop {
        // Views 0, 1, ..., 7, 6, ..., 1, then again.
        let k = n % SWING;
        let view = scene::view(k.min(SWING - k));
        display.clear_buffer();
        let drawn = panels::render_direct(
            engine,
            &baked,
            &view,
            &mut buffers.workspace(),
            &mut Sharp(&mut display),
        );
        if drawn.is_err() {
            panic!("suzanne did not fit the buffers");
        }
        display.flush_buffer();
        n = n.wrapping_add(1);
    }
}
