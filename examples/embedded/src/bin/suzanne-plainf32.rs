//! Baseline (ii) on the suzanne scene: the paper's P-buffer algorithm in plain `f32`
//! (`pbuffer_examples::plain`, full-frame f32 depth buffer), same cameras as `suzanne`.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use panic_semihosting as _;
use pbuffer::mesh::{EdgeAdjacency, Mesh};
use pbuffer::{packed_len, Pattern};
use pbuffer_examples::plain::PlainBuffers;
use pbuffer_examples::scenes::{fnv1a64, suzanne as scene};
use pbuffer_examples::{fw, suzanne};

const NAME: &str = "suzanne-plainf32";
const PIXELS: usize = scene::WIDTH * scene::HEIGHT;
type Buffers = PlainBuffers<PIXELS, { packed_len(scene::WIDTH, scene::HEIGHT) }, 507, 500>;

static mut BUFFERS: Buffers = Buffers::new();

#[entry]
fn main() -> ! {
    fw::paint_stack();
    let mut counter = fw::Counter::new();
    // SAFETY: main runs once; this is its only reference to the static.
    let buffers = unsafe { &mut *addr_of_mut!(BUFFERS) };
    let mesh = Mesh::new(&suzanne::VERTICES, &suzanne::INDICES, &suzanne::OFFSETS)
        .unwrap_or_else(|e| fw::fail(NAME, &e));
    // The edge list was built on the host (build.rs) and stays in flash.
    let edges = EdgeAdjacency::from_edges(&mesh, &suzanne::EDGE_LIST)
        .unwrap_or_else(|e| fw::fail(NAME, &e));
    let cull = edges.is_closed();
    buffers.prepare(&mesh);
    let boot = fw::stack_peak();
    fw::run(NAME, scene::FRAMES, boot, &mut counter, |n, c| {
        let view = scene::view(n);
        let ((), instructions) = c.count(|| {
            buffers.render(
                &mesh,
                edges.edges(),
                cull,
                &view,
                scene::WIDTH,
                scene::HEIGHT,
                &Pattern::PAPER,
            )
        });
        (fnv1a64(&buffers.frame), instructions)
    })
}
