//! What posed instances cost (`pbuffer_examples::instances`): `N` copies of the arm's
//! forearm in a grid, for `N` = 1, 4, 16, drawn at 128 x 64 as one mesh (the union,
//! baked by build.rs, drawn by `BakedDrawing`) and as `N` instances of the part baked
//! once (`SceneDrawing`), 4 frames each. Both draw the same frames (equal hashes);
//! each count covers clearing the frame and drawing it. Prints
//! `frame instances-union-N F ...` and `frame instances-scene-N F ...` lines and one
//! `example instances` line (RAM: both drawings' buffers, sized for 16).
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _;
use pbuffer::render::BakedMesh;
use pbuffer::{BakedDrawing, SceneDrawing};
use pbuffer_examples::arm::Frame;
use pbuffer_examples::instances::{self, InstanceScene, Rows, UnionDrawing};
use pbuffer_examples::scenes::fnv1a64;
use pbuffer_examples::{arm_baked, fw, grids};

const NAME: &str = "instances";

static mut FB: Frame = Frame::new();
static mut UNION: UnionDrawing<'static> = BakedDrawing::new();
static mut SCENE: InstanceScene<'static> = SceneDrawing::new();
static mut ROWS: Rows = Rows::new();

fn check(r: Result<BakedMesh<'static>, pbuffer::Error>) -> BakedMesh<'static> {
    r.unwrap_or_else(|e| fw::fail(NAME, &e))
}

#[entry]
fn main() -> ! {
    fw::paint_stack();
    let mut counter = fw::Counter::new();
    // SAFETY: main runs once; these are its only references to the statics.
    let (fb, union, scene, rows) = unsafe {
        (
            &mut *addr_of_mut!(FB),
            &mut *addr_of_mut!(UNION),
            &mut *addr_of_mut!(SCENE),
            &mut *addr_of_mut!(ROWS),
        )
    };
    let part = check(arm_baked::arm_forearm_baked());
    let unions = [
        check(grids::grid1_baked()),
        check(grids::grid4_baked()),
        check(grids::grid16_baked()),
    ];
    for (n, one) in instances::COUNTS.into_iter().zip(unions) {
        union.set_mesh(one).unwrap_or_else(|e| fw::fail(NAME, &e));
        instances::set_instances(scene, part, n).unwrap_or_else(|e| fw::fail(NAME, &e));
        for f in 0..instances::FRAMES {
            let (r, i) = counter.count(|| instances::draw_union(union, rows, n, f, fb));
            r.unwrap_or_else(|e| fw::fail(NAME, &e));
            let hash = fnv1a64(fb.as_bytes());
            hprintln!(
                "frame instances-union-{} {} hash={:016x} instructions={}",
                n,
                f,
                hash,
                i
            );
            let (r, i) = counter.count(|| instances::draw_scene(scene, rows, n, f, fb));
            r.unwrap_or_else(|e| fw::fail(NAME, &e));
            let hash = fnv1a64(fb.as_bytes());
            hprintln!(
                "frame instances-scene-{} {} hash={:016x} instructions={}",
                n,
                f,
                hash,
                i
            );
        }
    }
    let stack = fw::stack_peak();
    let (ram, flash) = fw::sizes();
    hprintln!(
        "example {} ram={} flash={} stack={}",
        NAME,
        ram,
        flash,
        stack
    );
    debug::exit(debug::EXIT_SUCCESS);
    #[allow(clippy::empty_loop)]
    loop {}
}
