//! A 128 x 64 instrument-panel picture (an SSD1306-sized frame): an L-bracket with a
//! hexagonal boss, hidden lines dashed, 4 frames of a turning camera, rendered by
//! pbuffer's scan-line code-fill engine (`scenes::PanelEngine`) in 8-row bands into the
//! packed 1-bpp framebuffer: the `panel` example's frames before the fast engine, kept
//! to compare.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use panic_semihosting as _;
use pbuffer::mesh::{Mesh, MeshEdge};
use pbuffer::{packed_len, DrawMode, PackedFramebuffer};
use pbuffer_examples::fw;
use pbuffer_examples::scenes::{self, fnv1a64, panel as scene, PanelBuffers, PanelEngine};

const NAME: &str = "panel-scanline";
type Fb = PackedFramebuffer<
    { scene::WIDTH },
    { scene::HEIGHT },
    { packed_len(scene::WIDTH, scene::HEIGHT) },
>;

static mut FB: Fb = Fb::new();
static mut BUFFERS: PanelBuffers = PanelBuffers::new();
static mut EDGES: [MeshEdge; scene::EDGES] = [MeshEdge::EMPTY; scene::EDGES];
static mut ENGINE: PanelEngine = PanelEngine::new();

#[entry]
fn main() -> ! {
    fw::paint_stack();
    let mut counter = fw::Counter::new();
    // SAFETY: main runs once; these are its only references to the statics.
    let (fb, buffers, store, engine) = unsafe {
        (
            &mut *addr_of_mut!(FB),
            &mut *addr_of_mut!(BUFFERS),
            &mut *addr_of_mut!(EDGES),
            &mut *addr_of_mut!(ENGINE),
        )
    };
    let mesh = Mesh::new(&scene::VERTICES, &scene::INDICES, &scene::OFFSETS)
        .unwrap_or_else(|e| fw::fail(NAME, &e));
    let edges =
        fw::build_edges::<{ scene::VERTICES.len() }, { scene::INDICES.len() }>(NAME, &mesh, store);
    let boot = fw::stack_peak();
    fw::run(NAME, scene::FRAMES, boot, &mut counter, |n, c| {
        let view = scene::view(n);
        let (r, instructions) = c.count(|| {
            fb.clear();
            scenes::render(
                engine,
                &mesh,
                &edges,
                &view,
                DrawMode::Dashed,
                &mut buffers.workspace(),
                fb,
            )
        });
        let _stats = r.unwrap_or_else(|e| fw::fail(NAME, &e));
        #[cfg(feature = "defmt")]
        defmt::info!("{} frame {}: {}", NAME, n, _stats);
        (fnv1a64(fb.as_bytes()), instructions)
    })
}
