//! Suzanne at 400 x 240 (`suzanne`'s scene, 8 frames) on a Sharp memory LCD
//! (LS027B7DH01) through the `sharp-memory-display` crate: its `DrawTarget` (seen as an
//! embedded-graphics 0.8 one by `panels::Sharp`) over an SPI bus. Under QEMU the bus is
//! a recorder (`panels::Tap`): each frame line's hash is the FNV-1a 64 of the bytes the
//! driver's `flush_buffer` wrote, which the host test `panel_bus.rs` decodes back into
//! the frame. Both ways from the renderer to the bus are measured and printed as
//!
//! ```text
//! bus EXAMPLE N bytes=B writes=W solid_render=I direct_render=I direct_flush=I copy_render=I copy_copy=I copy_flush=I
//! ```
//!
//! the frame line counting the documented way (direct): render into the driver's
//! buffer and flush it to the bus.
#![no_std]
#![no_main]

use core::cell::RefCell;
use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use panic_semihosting as _;
use pbuffer::mesh::Mesh;
use pbuffer::render::BakedMesh;
use pbuffer::{packed_len, DrawMode, PackedFramebuffer};
use pbuffer_examples::panels::{self, NoPin, Record, Sharp, Tap};
use pbuffer_examples::scenes::{self, fnv1a64, suzanne as scene, FastEngine, SuzanneFastBuffers};
use pbuffer_examples::{fw, suzanne};

const NAME: &str = "suzanne-sharp";
type Fb = PackedFramebuffer<
    { scene::WIDTH },
    { scene::HEIGHT },
    { packed_len(scene::WIDTH, scene::HEIGHT) },
>;

static mut FB: Fb = Fb::new();
static mut BUFFERS: SuzanneFastBuffers = SuzanneFastBuffers::new();
static mut ENGINE: FastEngine = FastEngine::new();
/// The bus record: a frame is a command byte, 240 lines of 52 bytes and a trailer byte
/// (12,482 bytes in 242 writes).
static mut BUS: [u8; 12_800] = [0; 12_800];
static mut ENDS: [u32; 256] = [0; 256];

#[entry]
fn main() -> ! {
    fw::paint_stack();
    let mut counter = fw::Counter::new();
    // SAFETY: main runs once; these are its only references to the statics.
    let (fb, buffers, engine, bus, ends) = unsafe {
        (
            &mut *addr_of_mut!(FB),
            &mut *addr_of_mut!(BUFFERS),
            &mut *addr_of_mut!(ENGINE),
            &mut *addr_of_mut!(BUS),
            &mut *addr_of_mut!(ENDS),
        )
    };
    let record = RefCell::new(Record::new(bus, ends));
    let mut display = panels::sharp_display(Tap(&record), NoPin, NoPin);
    display.clear();
    let baked = Mesh::new(&suzanne::VERTICES, &suzanne::INDICES, &suzanne::OFFSETS)
        .and_then(|mesh| mesh.with_planar_faces(&suzanne::PLANAR))
        .and_then(|mesh| BakedMesh::new(mesh, &suzanne::SUZANNE_PLANES, &suzanne::SUZANNE_EDGES))
        .unwrap_or_else(|e| fw::fail(NAME, &e));
    let boot = fw::stack_peak();
    fw::run(NAME, scene::FRAMES, boot, &mut counter, |n, c| {
        let view = scene::view(n);
        // Direct through `fill_solid` (pbuffer's `FillSolid` sink): for comparison.
        let (r, solid_render) = c.count(|| {
            display.clear_buffer();
            panels::render_fill_solid(
                engine,
                &baked,
                &view,
                &mut buffers.workspace(),
                &mut Sharp(&mut display),
            )
        });
        r.unwrap_or_else(|e| fw::fail(NAME, &e));
        record.borrow_mut().clear();
        display.flush_buffer();
        let solid = fnv1a64(record.borrow().bytes().get(1..).unwrap_or_default());
        // Direct: spans into the driver's buffer (`Pixels` sink), then its flush.
        let (r, direct_render) = c.count(|| {
            display.clear_buffer();
            panels::render_direct(
                engine,
                &baked,
                &view,
                &mut buffers.workspace(),
                &mut Sharp(&mut display),
            )
        });
        r.unwrap_or_else(|e| fw::fail(NAME, &e));
        record.borrow_mut().clear();
        let ((), direct_flush) = c.count(|| display.flush_buffer());
        // The first byte is the write command with the VCOM bit, which the driver
        // toggles at every flush: the two ways must agree on the bytes after it.
        let (hash, lines, bytes, writes, lost) = {
            let rec = record.borrow();
            let lines = fnv1a64(rec.bytes().get(1..).unwrap_or_default());
            (
                fnv1a64(rec.bytes()),
                lines,
                rec.bytes().len(),
                rec.ends().len(),
                rec.lost(),
            )
        };
        // Copy: our packed framebuffer, its lit pixels into the driver's, then its flush.
        let (r, copy_render) = c.count(|| {
            fb.clear();
            scenes::render_fast(
                engine,
                &baked,
                &view,
                DrawMode::Dashed,
                &mut buffers.workspace(),
                fb,
            )
        });
        r.unwrap_or_else(|e| fw::fail(NAME, &e));
        let (r, copy_copy) = c.count(|| {
            display.clear_buffer();
            panels::copy_frame(fb, &mut Sharp(&mut display))
        });
        r.unwrap_or_else(|e| fw::fail(NAME, &e));
        record.borrow_mut().clear();
        let ((), copy_flush) = c.count(|| display.flush_buffer());
        let copied = fnv1a64(record.borrow().bytes().get(1..).unwrap_or_default());
        if lost != 0 || record.borrow().lost() != 0 || copied != lines || solid != lines {
            fw::fail(
                NAME,
                &"the two ways wrote different bus bytes (or the record overflowed)",
            );
        }
        hprintln!(
            "bus {} {} bytes={} writes={} solid_render={} direct_render={} direct_flush={} copy_render={} copy_copy={} copy_flush={}",
            NAME,
            n,
            bytes,
            writes,
            solid_render,
            direct_render,
            direct_flush,
            copy_render,
            copy_copy,
            copy_flush
        );
        (hash, direct_render + direct_flush)
    })
}
