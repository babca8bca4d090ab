//! A cube with dashed hidden lines on 128x64, drawn with the short API: the lines of
//! the crate doctest that the README quotes (`host_tests/tests/frames/short_api.rs` checks
//! that they are the same lines). Shared by the firmware (`main.rs`) and the host test
//! `host_tests/tests/firmware/firmware_cube.rs`, which both check `EXPECTED_CUBE`, so the M4
//! and the host are held to the same bits.

use pbuffer::prelude::*;
use pbuffer::{packed_len, PackedFramebuffer, Stats};

/// The frame.
pub type CubeFrame = PackedFramebuffer<128, 64, { packed_len(128, 64) }>;

#[rustfmt::skip] // the doctest's lines
const CORNERS: [[f32; 3]; 8] = [[-1., -1., -1.], [1., -1., -1.], [1., 1., -1.], [-1., 1., -1.],
    [-1., -1., 1.], [1., -1., 1.], [1., 1., 1.], [-1., 1., 1.]];
#[rustfmt::skip]
const QUADS: [u32; 24] = [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 2, 3, 7, 6, 1, 2, 6, 5, 0, 4, 7, 3];

/// FNV-1a 64 of the frame; both the host test and the firmware check it.
pub const EXPECTED_CUBE: u64 = 0x0549_e202_7963_139b;

/// FNV-1a 64, as `render --hash` computes it.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// Bakes the cube and draws it into `display`.
#[rustfmt::skip] // the doctest's lines, as the README quotes them
pub fn render_cube(display: &mut CubeFrame) -> Result<Stats, Error> {
    let mesh = Mesh::new(&CORNERS, &QUADS, &[0, 4, 8, 12, 16, 20, 24])?;
    let mut cube = Drawing::<8, 6, 12>::new(); // vertices, faces, edges
    cube.bake(mesh)?;
    let camera = Camera::look_at([3.0, 2.5, 4.0], [0.0; 3], 40.0)?;
    cube.draw(&camera, &mut FrameRows::<128, 64>::new(), display)
}
