//! The robot-arm panel demo on a 128 x 64, 1-bpp display (`pbuffer_examples::arm`): a
//! base, two links and a gripper, four procedural parts baked by build.rs, posed every
//! frame by their joint angles and drawn together by pbuffer's `SceneDrawing` (mutual
//! hiding, hidden lines dashed), with the angles as embedded-graphics text. 8 frames,
//! the joints moving; each frame's count covers all of it: clearing, posing, the 3-D
//! drawing and the text.
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use cortex_m_rt::entry;
use panic_semihosting as _;
use pbuffer::SceneDrawing;
use pbuffer_examples::arm::{self, ArmRows, ArmScene, Frame};
use pbuffer_examples::arm_baked as baked;
use pbuffer_examples::fw;
use pbuffer_examples::scenes::fnv1a64;

const NAME: &str = "arm";

static mut FB: Frame = Frame::new();
static mut SCENE: ArmScene<'static> = SceneDrawing::new();
static mut ROWS: ArmRows = ArmRows::new();

#[entry]
fn main() -> ! {
    fw::paint_stack();
    let mut counter = fw::Counter::new();
    // SAFETY: main runs once; these are its only references to the statics.
    let (fb, scene, rows) = unsafe {
        (
            &mut *addr_of_mut!(FB),
            &mut *addr_of_mut!(SCENE),
            &mut *addr_of_mut!(ROWS),
        )
    };
    // The parts' constants were made on the host (build.rs); each `_baked()` checks
    // them once, and the scene assembles its union's fixed parts once.
    let parts = [
        baked::arm_base_baked(),
        baked::arm_upper_baked(),
        baked::arm_forearm_baked(),
        baked::arm_gripper_baked(),
    ];
    let parts = parts.map(|p| p.unwrap_or_else(|e| fw::fail(NAME, &e)));
    arm::add_parts(scene, parts).unwrap_or_else(|e| fw::fail(NAME, &e));
    let boot = fw::stack_peak();
    fw::run(NAME, arm::FRAMES, boot, &mut counter, |n, c| {
        let (r, instructions) = c.count(|| arm::draw(scene, rows, n, fb));
        let _stats = r.unwrap_or_else(|e| fw::fail(NAME, &e));
        #[cfg(feature = "defmt")]
        defmt::info!("{} frame {}: {}", NAME, n, _stats);
        (fnv1a64(fb.as_bytes()), instructions)
    })
}
