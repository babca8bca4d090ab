//! The 4 frames of `panel` (128 x 64, the L-bracket, hidden lines dashed) with hidden
//! lines decided by the segment (`LineVisibility::BySegment` with the segment tables
//! build.rs baked, `PANEL_VERTEX_FACES` and `PANEL_PIERCINGS`, and the lent
//! `scenes::PanelSegmentBuffers`) instead of the per-pixel test, rendered by pbuffer's
//! fast engine (`scenes::PanelFastEngine`) into the packed 1-bpp framebuffer.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use panic_semihosting as _;
use pbuffer::mesh::Mesh;
use pbuffer::render::BakedMesh;
use pbuffer::{packed_len, DrawMode, PackedFramebuffer};
use pbuffer_examples::scenes::{
    self, fnv1a64, panel as scene, PanelFastBuffers, PanelFastEngine, PanelSegmentBuffers,
};
use pbuffer_examples::{fw, panel_baked};

const NAME: &str = "panel-segments";
type Fb = PackedFramebuffer<
    { scene::WIDTH },
    { scene::HEIGHT },
    { packed_len(scene::WIDTH, scene::HEIGHT) },
>;

static mut FB: Fb = Fb::new();
static mut BUFFERS: PanelFastBuffers = PanelFastBuffers::new();
static mut ENGINE: PanelFastEngine = PanelFastEngine::new();
static mut SEGMENTS: PanelSegmentBuffers = PanelSegmentBuffers::new();

#[entry]
fn main() -> ! {
    fw::paint_stack();
    let mut counter = fw::Counter::new();
    // SAFETY: main runs once; these are its only references to the statics.
    let (fb, buffers, engine, segments) = unsafe {
        (
            &mut *addr_of_mut!(FB),
            &mut *addr_of_mut!(BUFFERS),
            &mut *addr_of_mut!(ENGINE),
            &mut *addr_of_mut!(SEGMENTS),
        )
    };
    // Which faces are planar, the face planes, the compact edge list, the faces around
    // each vertex and the piercing pairs were made on the host (build.rs) and stay in
    // flash; `BakedMesh::new`, `with_vertex_faces` and `with_piercings` check them once.
    let baked = Mesh::new(&scene::VERTICES, &scene::INDICES, &scene::OFFSETS)
        .and_then(|mesh| mesh.with_planar_faces(&panel_baked::PLANAR))
        .and_then(|mesh| {
            BakedMesh::new(mesh, &panel_baked::PANEL_PLANES, &panel_baked::PANEL_EDGES)
        })
        .and_then(|baked| baked.with_vertex_faces(panel_baked::PANEL_VERTEX_FACES))
        .and_then(|baked| baked.with_piercings(&panel_baked::PANEL_PIERCINGS))
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
                &mut buffers.workspace_with(segments),
                fb,
            )
        });
        let _stats = r.unwrap_or_else(|e| fw::fail(NAME, &e));
        #[cfg(feature = "defmt")]
        defmt::info!("{} frame {}: {}", NAME, n, _stats);
        (fnv1a64(fb.as_bytes()), instructions)
    })
}
