//! The 128 x 64 panel picture (`panel`'s scene, 4 frames) on an SSD1306 OLED through the
//! `ssd1306` crate: its buffered graphics mode `DrawTarget` over an I2C bus. Under QEMU
//! the bus is a recorder (`panels::Tap`): each frame line's hash is the FNV-1a 64 of the
//! bytes the driver's `flush` wrote (I2C control bytes included, addresses not), which
//! the host test `panel_bus.rs` decodes back into the frame. Both ways from the
//! renderer to the bus are measured (`panels`: direct, copy) and printed as
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
use pbuffer_examples::panels::{self, Record, Tap};
use pbuffer_examples::scenes::{self, fnv1a64, panel as scene, PanelFastBuffers, PanelFastEngine};
use pbuffer_examples::{fw, panel_baked};
use ssd1306::mode::DisplayConfig;

const NAME: &str = "panel-ssd1306";
type Fb = PackedFramebuffer<
    { scene::WIDTH },
    { scene::HEIGHT },
    { packed_len(scene::WIDTH, scene::HEIGHT) },
>;

static mut FB: Fb = Fb::new();
static mut BUFFERS: PanelFastBuffers = PanelFastBuffers::new();
static mut ENGINE: PanelFastEngine = PanelFastEngine::new();
/// The bus record: a frame is 2 commands and 64 data writes of 17 bytes (1,096 bytes).
static mut BUS: [u8; 2048] = [0; 2048];
static mut ENDS: [u32; 128] = [0; 128];

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
    let mut display = panels::ssd1306_display(Tap(&record));
    display.init().unwrap_or_else(|e| fw::fail(NAME, &e));
    let baked = Mesh::new(&scene::VERTICES, &scene::INDICES, &scene::OFFSETS)
        .and_then(|mesh| mesh.with_planar_faces(&panel_baked::PLANAR))
        .and_then(|mesh| {
            BakedMesh::new(mesh, &panel_baked::PANEL_PLANES, &panel_baked::PANEL_EDGES)
        })
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
                &mut display,
            )
        });
        r.unwrap_or_else(|e| fw::fail(NAME, &e));
        record.borrow_mut().clear();
        display.flush().unwrap_or_else(|e| fw::fail(NAME, &e));
        let solid = fnv1a64(record.borrow().bytes());
        // Direct: spans into the driver's buffer (`Pixels` sink), then its flush.
        let (r, direct_render) = c.count(|| {
            display.clear_buffer();
            panels::render_direct(
                engine,
                &baked,
                &view,
                &mut buffers.workspace(),
                &mut display,
            )
        });
        r.unwrap_or_else(|e| fw::fail(NAME, &e));
        record.borrow_mut().clear();
        let (r, direct_flush) = c.count(|| display.flush());
        r.unwrap_or_else(|e| fw::fail(NAME, &e));
        let (hash, bytes, writes, lost) = {
            let rec = record.borrow();
            (
                fnv1a64(rec.bytes()),
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
            panels::copy_frame(fb, &mut display)
        });
        r.unwrap_or_else(|e| fw::fail(NAME, &e));
        record.borrow_mut().clear();
        let (r, copy_flush) = c.count(|| display.flush());
        r.unwrap_or_else(|e| fw::fail(NAME, &e));
        let copied = fnv1a64(record.borrow().bytes());
        if lost != 0 || record.borrow().lost() != 0 || copied != hash || solid != hash {
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
