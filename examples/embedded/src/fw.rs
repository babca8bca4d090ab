//! The measuring harness: SysTick instruction counts, stack painting, linker-symbol
//! sizes, and the lines `scripts/firmware` gathers:
//!
//! ```text
//! frame EXAMPLE N hash=HEX instructions=COUNT
//! example EXAMPLE ram=BYTES flash=BYTES stack=BYTES
//! ```
//!
//! On the Cortex-M4 (`mps2-an386`) EXAMPLE is the example's name; the other cores add
//! their own suffix ([`SUFFIX`]: `panel-m3` on the Cortex-M3, `mps2-an385`; `panel-m0` on
//! the Cortex-M0, `microbit`), so that one run's lines stay apart.

use core::ptr::{addr_of, read_volatile, write_volatile};

use cortex_m::peripheral::{syst::SystClkSource, SYST};
use cortex_m_semihosting::{debug, hprintln};

use pbuffer::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};

extern "C" {
    static __stext: u8;
    static __etext: u8;
    static __srodata: u8;
    static __erodata: u8;
    static __sdata: u8;
    static __edata: u8;
    static __sbss: u8;
    static __ebss: u8;
    static _stack_start: u8;
}

/// What the board's frame lines add to the example's name (build.rs sets `fw_board`).
#[cfg(fw_board = "mps2-an386")]
pub const SUFFIX: &str = "";
/// What the board's frame lines add to the example's name (build.rs sets `fw_board`).
#[cfg(fw_board = "mps2-an385")]
pub const SUFFIX: &str = "-m3";
/// What the board's frame lines add to the example's name (build.rs sets `fw_board`).
#[cfg(fw_board = "microbit")]
pub const SUFFIX: &str = "-m0";

/// Instructions a SysTick tick (core clock) under `-icount shift=0`, where QEMU's clock
/// advances 1 ns an instruction: the fraction (numerator, denominator) of 1 GHz over the
/// board's SysTick clock. The mps2 boards clock the core at 25 MHz: 40 instructions a tick.
#[cfg(any(fw_board = "mps2-an386", fw_board = "mps2-an385"))]
const PER_TICK: (u32, u32) = (40, 1);
/// Instructions a SysTick tick (core clock) under `-icount shift=0`, where QEMU's clock
/// advances 1 ns an instruction: the fraction (numerator, denominator) of 1 GHz over the
/// board's SysTick clock. The micro:bit's nRF51 runs at 16 MHz: 62.5 instructions a tick.
#[cfg(fw_board = "microbit")]
const PER_TICK: (u32, u32) = (125, 2);

/// Bytes of stack painted below the current stack pointer.
const PAINT: usize = 64 * 1024;
const MARK: u32 = 0xdead_beef;

fn addr(p: *const u8) -> usize {
    p as usize
}

/// Static RAM (.data + .bss) and flash (.text + .rodata + .data's initial values,
/// copied from flash at reset) from the linker's symbols.
pub fn sizes() -> (usize, usize) {
    let data = addr(addr_of!(__edata)) - addr(addr_of!(__sdata));
    let ram = data + addr(addr_of!(__ebss)) - addr(addr_of!(__sbss));
    let flash = addr(addr_of!(__etext)) - addr(addr_of!(__stext)) + addr(addr_of!(__erodata))
        - addr(addr_of!(__srodata))
        + data;
    (ram, flash)
}

fn stack_top() -> usize {
    addr(addr_of!(_stack_start))
}

/// The lowest address painted.
fn paint_floor() -> usize {
    let ebss = addr(addr_of!(__ebss));
    (stack_top() - PAINT).max(ebss)
}

/// Paints the free stack below the current frame with a marker.
#[inline(never)]
pub fn paint_stack() {
    let sp = cortex_m::register::msp::read() as usize;
    let mut p = paint_floor();
    while p + 4 < sp - 128 {
        // SAFETY: unused stack between the end of .bss and below the live frames.
        unsafe { write_volatile(p as *mut u32, MARK) };
        p += 4;
    }
}

/// Peak stack use since [`paint_stack`]: from the top of the stack down to the
/// lowest word that no longer holds the marker.
#[inline(never)]
pub fn stack_peak() -> usize {
    let mut p = paint_floor();
    // SAFETY: reads of the painted stack region.
    while p < stack_top() && unsafe { read_volatile(p as *const u32) } == MARK {
        p += 4;
    }
    stack_top() - p
}

/// SysTick on the core clock, free running: with `-icount shift=0` it advances once per
/// 40 instructions on the mps2 boards (docs/firmware.md), once per 62.5 on the
/// micro:bit ([`PER_TICK`]).
pub struct Counter {
    syst: SYST,
}

impl Counter {
    pub fn new() -> Self {
        let mut syst = cortex_m::Peripherals::take().unwrap().SYST;
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(0x00ff_ffff);
        syst.clear_current();
        syst.enable_counter();
        Self { syst }
    }

    /// Runs `f` and returns its result and the instructions it took (ticks x
    /// [`PER_TICK`], rounded down: 40 x ticks on the mps2 boards, 125 x ticks / 2 on the
    /// micro:bit; at most 2^24 ticks, so the product fits in `u32`).
    pub fn count<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32) {
        self.syst.clear_current();
        let _ = self.syst.has_wrapped(); // clears COUNTFLAG
        let r = f();
        let ticks = 0x00ff_ffff - SYST::get_current();
        assert!(
            !self.syst.has_wrapped(),
            "SysTick wrapped: measure in chunks"
        );
        (r, ticks * PER_TICK.0 / PER_TICK.1)
    }
}

impl Default for Counter {
    fn default() -> Self {
        Self::new()
    }
}

/// Builds the edge adjacency of `mesh` into `store` (crease angle 30 degrees), with
/// the weld map and half-edge records (needed only while building) on the stack.
#[inline(never)]
pub fn build_edges<'s, const VN: usize, const IN: usize>(
    name: &str,
    mesh: &Mesh<'_>,
    store: &'s mut [MeshEdge],
) -> EdgeAdjacency<'s> {
    let mut weld = [0u32; VN];
    let mut scratch = [HalfEdgeRecord::EMPTY; IN];
    EdgeAdjacency::build(mesh, 30.0, &mut weld, &mut scratch, store)
        .unwrap_or_else(|e| fail(name, &e))
}

/// Renders `frames` frames with `draw(n, counter)` (which clears and draws frame `n`,
/// counting its instructions, and returns the frame's bytes and the count), prints a
/// `frame` line for each and the `example` line, and exits QEMU with success.
/// `boot_stack` is the peak stack of the set-up before (printed as a `boot` line).
pub fn run(
    name: &str,
    frames: u32,
    boot_stack: usize,
    counter: &mut Counter,
    mut draw: impl FnMut(u32, &mut Counter) -> (u64, u32),
) -> ! {
    paint_stack();
    for n in 0..frames {
        let (hash, instructions) = draw(n, counter);
        hprintln!(
            "frame {}{} {} hash={:016x} instructions={}",
            name,
            SUFFIX,
            n,
            hash,
            instructions
        );
    }
    let stack = stack_peak();
    let (ram, flash) = sizes();
    hprintln!("boot {}{} stack={}", name, SUFFIX, boot_stack);
    hprintln!(
        "example {}{} ram={} flash={} stack={}",
        name,
        SUFFIX,
        ram,
        flash,
        stack
    );
    debug::exit(debug::EXIT_SUCCESS);
    #[allow(clippy::empty_loop)]
    loop {}
}

/// Reports an error and exits QEMU with failure.
pub fn fail(name: &str, what: &dyn core::fmt::Debug) -> ! {
    hprintln!("FAIL {}{}: {:?}", name, SUFFIX, what);
    debug::exit(debug::EXIT_FAILURE);
    #[allow(clippy::empty_loop)]
    loop {}
}

/// A defmt logger for the `defmt` build check: frames go to semihosting stderr.
#[cfg(feature = "defmt")]
mod logger {
    use core::sync::atomic::{AtomicBool, Ordering};

    #[defmt::global_logger]
    struct Logger;

    static TAKEN: AtomicBool = AtomicBool::new(false);
    static mut ENCODER: defmt::Encoder = defmt::Encoder::new();

    fn write(bytes: &[u8]) {
        if let Ok(mut e) = cortex_m_semihosting::hio::hstderr() {
            let _ = e.write_all(bytes);
        }
    }

    // SAFETY: single core, no interrupts use defmt; `TAKEN` guards re-entry.
    unsafe impl defmt::Logger for Logger {
        fn acquire() {
            if TAKEN.swap(true, Ordering::Acquire) {
                panic!("defmt logger taken reentrantly");
            }
            // SAFETY: exclusive by `TAKEN`.
            unsafe { (*core::ptr::addr_of_mut!(ENCODER)).start_frame(write) }
        }
        unsafe fn flush() {}
        unsafe fn release() {
            (*core::ptr::addr_of_mut!(ENCODER)).end_frame(write);
            TAKEN.store(false, Ordering::Release);
        }
        unsafe fn write(bytes: &[u8]) {
            (*core::ptr::addr_of_mut!(ENCODER)).write(bytes, write);
        }
    }
}
