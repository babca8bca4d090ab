//! Baseline (i) on the panel scene: the embedded-graphics painter's algorithm
//! (`pbuffer_examples::painter`), same cameras and frame as the `panel` example.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use panic_semihosting as _;
use pbuffer::mesh::Mesh;
use pbuffer::{packed_len, PackedFramebuffer};
use pbuffer_examples::fw;
use pbuffer_examples::painter::PainterBuffers;
use pbuffer_examples::scenes::{fnv1a64, panel as scene};

const NAME: &str = "panel-painter";
type Fb = PackedFramebuffer<
    { scene::WIDTH },
    { scene::HEIGHT },
    { packed_len(scene::WIDTH, scene::HEIGHT) },
>;

static mut FB: Fb = Fb::new();
static mut BUFFERS: PainterBuffers<24, 16> = PainterBuffers::new();

#[entry]
fn main() -> ! {
    fw::paint_stack();
    let mut counter = fw::Counter::new();
    // SAFETY: main runs once; these are its only references to the statics.
    let (fb, buffers) = unsafe { (&mut *addr_of_mut!(FB), &mut *addr_of_mut!(BUFFERS)) };
    let mesh = Mesh::new(&scene::VERTICES, &scene::INDICES, &scene::OFFSETS)
        .unwrap_or_else(|e| fw::fail(NAME, &e));
    buffers.prepare(&mesh);
    let boot = fw::stack_peak();
    fw::run(NAME, scene::FRAMES, boot, &mut counter, |n, c| {
        let view = scene::view(n);
        let (r, instructions) = c.count(|| {
            fb.clear();
            buffers.render(&mesh, &view, fb)
        });
        r.unwrap_or_else(|e| fw::fail(NAME, &e));
        (fnv1a64(fb.as_bytes()), instructions)
    })
}
