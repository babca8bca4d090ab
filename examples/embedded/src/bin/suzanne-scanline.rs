//! Suzanne at 400 x 240 with dashed hidden lines, 8 frames of an orbiting camera, into
//! the packed 1-bpp framebuffer, rendered by pbuffer's scan-line code-fill engine
//! (`scenes::Engine`) in 16-row bands: the `suzanne` example's frames before the fast
//! engine, kept to compare.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use panic_semihosting as _;
use pbuffer::mesh::{EdgeAdjacency, Mesh};
use pbuffer::{packed_len, DrawMode, PackedFramebuffer};
use pbuffer_examples::scenes::{self, fnv1a64, suzanne as scene, Engine, SuzanneBuffers};
use pbuffer_examples::{fw, suzanne};

const NAME: &str = "suzanne-scanline";
type Fb = PackedFramebuffer<
    { scene::WIDTH },
    { scene::HEIGHT },
    { packed_len(scene::WIDTH, scene::HEIGHT) },
>;

static mut FB: Fb = Fb::new();
static mut BUFFERS: SuzanneBuffers = SuzanneBuffers::new();
static mut ENGINE: Engine = Engine::new();

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
    // Which faces are planar was found on the host (build.rs) and stays in flash.
    let mesh = Mesh::new(&suzanne::VERTICES, &suzanne::INDICES, &suzanne::OFFSETS)
        .and_then(|mesh| mesh.with_planar_faces(&suzanne::PLANAR))
        .unwrap_or_else(|e| fw::fail(NAME, &e));
    // The edge list was built on the host (build.rs) and stays in flash.
    let edges = EdgeAdjacency::from_edges(&mesh, &suzanne::EDGE_LIST)
        .unwrap_or_else(|e| fw::fail(NAME, &e));
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
