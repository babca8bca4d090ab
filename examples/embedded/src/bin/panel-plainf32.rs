//! Baseline (ii) on the panel scene: the paper's P-buffer algorithm in plain `f32`
//! (`pbuffer_examples::plain`, full-frame f32 depth buffer), same cameras as `panel`.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use panic_semihosting as _;
use pbuffer::mesh::{Mesh, MeshEdge};
use pbuffer::{packed_len, Pattern};
use pbuffer_examples::fw;
use pbuffer_examples::plain::PlainBuffers;
use pbuffer_examples::scenes::{fnv1a64, panel as scene};

const NAME: &str = "panel-plainf32";
const PIXELS: usize = scene::WIDTH * scene::HEIGHT;
type Buffers = PlainBuffers<PIXELS, { packed_len(scene::WIDTH, scene::HEIGHT) }, 24, 16>;

static mut BUFFERS: Buffers = Buffers::new();
static mut EDGES: [MeshEdge; scene::EDGES] = [MeshEdge::EMPTY; scene::EDGES];

#[entry]
fn main() -> ! {
    fw::paint_stack();
    let mut counter = fw::Counter::new();
    // SAFETY: main runs once; these are its only references to the statics.
    let (buffers, store) = unsafe { (&mut *addr_of_mut!(BUFFERS), &mut *addr_of_mut!(EDGES)) };
    let mesh = Mesh::new(&scene::VERTICES, &scene::INDICES, &scene::OFFSETS)
        .unwrap_or_else(|e| fw::fail(NAME, &e));
    let edges = fw::build_edges::<24, { scene::INDICES.len() }>(NAME, &mesh, store);
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
