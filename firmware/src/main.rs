//! Firmware smoke test for pbuffer on a Cortex-M4 (QEMU `mps2-an386`, run by
//! scripts/thumb-check): fills two polygons into a 128x64 packed framebuffer, then
//! renders a cube with dashed hidden lines (`cube.rs`, the short API's doctest lines),
//! prints the FNV-1a 64 hash of each frame and the instructions each step took, and
//! exits 0 only when both hashes are the ones the host computes for the same scenes
//! (`EXPECTED`, `cube::EXPECTED_CUBE`).
//! A panic or an error exits non-zero (panic-semihosting's `exit` feature).
#![no_std]
#![no_main]

use core::convert::Infallible;

use cortex_m::peripheral::{syst::SystClkSource, SYST};
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use embedded_graphics::pixelcolor::BinaryColor;
use panic_semihosting as _;
use pbuffer::subpixel::U4;
use pbuffer::{packed_len, FillRule, PackedFramebuffer, ScanConverter, ScreenPoint};

use pbuffer_firmware::cube;

/// Bytes of the cube's `Drawing` and of its `FrameRows` on this target
/// (BENCHMARKS.md's figures).
const BUFFER_BYTES: (usize, usize) = (
    core::mem::size_of::<pbuffer::Drawing<'static, 8, 6, 12>>(),
    core::mem::size_of::<pbuffer::FrameRows<128, 64>>(),
);

type Fb = PackedFramebuffer<128, 64, { packed_len(128, 64) }>;
type P = ScreenPoint<U4>; // 4 sub-pixel bits: raw = pixels * 16

/// A pentagram (self-intersecting: even-odd leaves its centre empty), sub-pixel vertices.
const STAR: [P; 5] = [
    P::from_bits(1024, 80),
    P::from_bits(1287, 890),
    P::from_bits(598, 390),
    P::from_bits(1450, 390),
    P::from_bits(761, 890),
];
/// A triangle with a vertex far beyond the guard band: takes the exact wide path.
const WIDE: [P; 3] = [
    P::from_bits(-100_000 * 16, 40 * 16),
    P::from_bits(325, 811),
    P::from_bits(968, 1022),
];

/// FNV-1a 64 of the framebuffer after both fills (1145 pixels set). Computed with pbuffer
/// on the host for the same scene, whose pixels matched host_tests' f64 reference
/// rasterizer (`reference::rasterize`) exactly. The conventions fix every pixel, so a
/// change here means the rasterizer's output changed on the target or everywhere.
const EXPECTED: u64 = 0xb1a6_9344_c4b8_5c2d;

use cube::fnv1a64;

/// Runs `f` and returns the instructions it took: with `-icount shift=0`, SysTick on the
/// core clock advances once per 40 instructions (see docs/firmware.md).
fn count<R>(syst: &mut SYST, f: impl FnOnce() -> R) -> (R, u32) {
    syst.clear_current();
    let _ = syst.has_wrapped(); // clears COUNTFLAG
    let r = f();
    let ticks = 0x00ff_ffff - SYST::get_current();
    assert!(!syst.has_wrapped(), "SysTick wrapped: measure in chunks");
    (r, ticks * 40)
}

fn scene(syst: &mut SYST, fb: &mut Fb) -> Result<(), pbuffer::Error<Infallible>> {
    let mut sc: ScanConverter<16> = ScanConverter::new();
    let (r, n) = count(syst, || {
        sc.fill(&STAR, FillRule::EvenOdd, BinaryColor::On, fb)
    });
    r?;
    hprintln!("pbuffer-firmware: star (even-odd) {} instructions", n);
    let (r, n) = count(syst, || {
        sc.fill(&WIDE, FillRule::NonZero, BinaryColor::On, fb)
    });
    r?;
    hprintln!(
        "pbuffer-firmware: wide triangle (non-zero) {} instructions",
        n
    );
    Ok(())
}

/// Renders the cube and checks its hash against the host's.
fn cube_scene(syst: &mut SYST) -> debug::ExitStatus {
    let mut fb = cube::CubeFrame::new();
    let (r, n) = count(syst, || cube::render_cube(&mut fb));
    match r {
        Ok(stats) => {
            let hash = fnv1a64(fb.as_bytes());
            hprintln!(
                "pbuffer-firmware: cube dashed 128x64 (short API: bake and draw), {} faces drawn, {} feature edges: {} instructions, fnv1a64={:016x}",
                stats.faces_drawn,
                stats.feature_edges,
                n,
                hash
            );
            hprintln!(
                "pbuffer-firmware: cube buffers: Drawing<8, 6, 12> {} bytes, FrameRows<128, 64> {} bytes",
                BUFFER_BYTES.0,
                BUFFER_BYTES.1
            );
            if hash == cube::EXPECTED_CUBE {
                debug::EXIT_SUCCESS
            } else {
                hprintln!(
                    "pbuffer-firmware: FAIL: expected fnv1a64={:016x}",
                    cube::EXPECTED_CUBE
                );
                debug::EXIT_FAILURE
            }
        }
        Err(e) => {
            hprintln!("pbuffer-firmware: FAIL: render error {:?}", e);
            debug::EXIT_FAILURE
        }
    }
}

#[entry]
fn main() -> ! {
    let mut syst = cortex_m::Peripherals::take().unwrap().SYST;
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(0x00ff_ffff);
    syst.enable_counter();

    let mut fb = Fb::new();
    let status = match scene(&mut syst, &mut fb) {
        Ok(()) => {
            let hash = fnv1a64(fb.as_bytes());
            let lit = fb.as_bytes().iter().map(|b| b.count_ones()).sum::<u32>();
            hprintln!(
                "pbuffer-firmware: 128x64 fb, {} pixels set, fnv1a64={:016x}",
                lit,
                hash
            );
            if hash == EXPECTED {
                debug::EXIT_SUCCESS
            } else {
                hprintln!("pbuffer-firmware: FAIL: expected fnv1a64={:016x}", EXPECTED);
                debug::EXIT_FAILURE
            }
        }
        Err(e) => {
            hprintln!("pbuffer-firmware: FAIL: fill error {:?}", e);
            debug::EXIT_FAILURE
        }
    };
    let status = if status == debug::EXIT_SUCCESS {
        cube_scene(&mut syst)
    } else {
        status
    };
    debug::exit(status);
    loop {}
}
