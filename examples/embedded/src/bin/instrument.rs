//! The instrument-panel demo on a 128 x 64, 1-bpp display (`pbuffer_examples::instrument`):
//! the panel bracket turning in a 64 x 64 pane, hidden lines dashed, drawn by pbuffer's
//! fast engine from the constants build.rs baked, beside embedded-graphics text (the
//! part's label and its turn angle) and a bar. 36 frames, one whole turn; each frame's
//! count covers all of it: clearing, the 3-D pane and the text.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use panic_semihosting as _;
use pbuffer::mesh::Mesh;
use pbuffer::render::BakedMesh;
use pbuffer_examples::instrument::{self, Frame};
use pbuffer_examples::scenes::{fnv1a64, panel as scene, PanelFastBuffers, PanelFastEngine};
use pbuffer_examples::{fw, panel_baked};

const NAME: &str = "instrument";

static mut FB: Frame = Frame::new();
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
    // As the `panel` example: the bracket's planarity bits, face planes and compact
    // edge list were made on the host (build.rs); `BakedMesh::new` checks them once.
    let baked = Mesh::new(&scene::VERTICES, &scene::INDICES, &scene::OFFSETS)
        .and_then(|mesh| mesh.with_planar_faces(&panel_baked::PLANAR))
        .and_then(|mesh| {
            BakedMesh::new(mesh, &panel_baked::PANEL_PLANES, &panel_baked::PANEL_EDGES)
        })
        .unwrap_or_else(|e| fw::fail(NAME, &e));
    let boot = fw::stack_peak();
    fw::run(NAME, instrument::FRAMES, boot, &mut counter, |n, c| {
        let (r, instructions) = c.count(|| instrument::draw(engine, &baked, buffers, n, fb));
        let _stats = r.unwrap_or_else(|e| fw::fail(NAME, &e));
        #[cfg(feature = "defmt")]
        defmt::info!("{} frame {}: {}", NAME, n, _stats);
        (fnv1a64(fb.as_bytes()), instructions)
    })
}
