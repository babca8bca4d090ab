//! The span kernels checked on the target: random facet-rows through the assembly
//! kernels and their portable Rust twin (`pbuffer::render::span_kernel_twin_mismatches`),
//! on rows of several widths. Prints
//!
//! ```text
//! kernels rows=N mismatches=M
//! ```
//!
//! and exits with failure unless M is 0 (`scripts/firmware` runs it under QEMU).
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _;
use pbuffer::render::span_kernel_twin_mismatches;
// The examples crate: its defmt logger (the `defmt` build check) and memory layout.
use pbuffer_examples as _;

#[entry]
fn main() -> ! {
    let (mut rows, mut bad) = (0u32, 0u32);
    // Narrow rows clip most spans; wide ones hold them.
    for (seed, width) in [(1u32, 1usize), (2, 7), (3, 40), (4, 128), (5, 256)] {
        let rounds = 4000;
        bad += span_kernel_twin_mismatches(seed, rounds, width);
        rows += rounds;
    }
    hprintln!("kernels rows={} mismatches={}", rows, bad);
    debug::exit(if bad == 0 {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {}
}
