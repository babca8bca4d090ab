//! A 128 x 64 instrument-panel picture (an SSD1306-sized frame): an L-bracket with a
//! hexagonal boss, hidden lines dashed, 4 frames of a turning camera, rendered by
//! pbuffer's fast engine (`scenes::PanelFastEngine`, a scan-line Z-buffer one row high)
//! from the constants build.rs baked, into the packed 1-bpp framebuffer.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use panic_semihosting as _;
use pbuffer::mesh::Mesh;
use pbuffer::render::BakedMesh;
use pbuffer::{packed_len, DrawMode, PackedFramebuffer};
use pbuffer_examples::scenes::{self, fnv1a64, panel as scene, PanelFastBuffers, PanelFastEngine};
use pbuffer_examples::{fw, panel_baked};

const NAME: &str = "panel";
type Fb = PackedFramebuffer<
    { scene::WIDTH },
    { scene::HEIGHT },
    { packed_len(scene::WIDTH, scene::HEIGHT) },
>;

static mut FB: Fb = Fb::new();
static mut BUFFERS: PanelFastBuffers = PanelFastBuffers::new();
static mut ENGINE: PanelFastEngine = PanelFastEngine::new();

#[entry]
fn main() -> ! {
    fw::paint_stack();
    let mut counter = fw::Counter::new();
    // SAFETY: main runs once; these are its only references to the statics.
    let (fb, buffers, engine) = unsafe {
        (
            &mut *addr_of_mut!(FB),
            &mut *addr_of_mut!(BUFFERS),
            &mut *addr_of_mut!(ENGINE),
        )
    };
    // Which faces are planar, the face planes and the compact edge list were made on
    // the host (build.rs) and stay in flash; `BakedMesh::new` checks them once.
    let baked = Mesh::new(&scene::VERTICES, &scene::INDICES, &scene::OFFSETS)
        .and_then(|mesh| mesh.with_planar_faces(&panel_baked::PLANAR))
        .and_then(|mesh| {
            BakedMesh::new(mesh, &panel_baked::PANEL_PLANES, &panel_baked::PANEL_EDGES)
        })
        .unwrap_or_else(|e| fw::fail(NAME, &e));
    let boot = fw::stack_peak();
    fw::run(NAME, scene::FRAMES, boot, &mut counter, |n, c| {
        let view = scene::view(n);
        let (r, instructions) = c.count(|| {
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
        let _stats = r.unwrap_or_else(|e| fw::fail(NAME, &e));
        #[cfg(feature = "defmt")]
        defmt::info!("{} frame {}: {}", NAME, n, _stats);
        (fnv1a64(fb.as_bytes()), instructions)
    })
}
