//! The robot-arm panel demo: a 128 x 64, 1-bpp display showing a base, two links
//! and a gripper, four rigid parts each baked once ([`parts`]) and posed every
//! frame by its joint angles, drawn by pbuffer's `SceneDrawing` (the fast engine,
//! mutual hiding, hidden lines dashed), with the joint angles as embedded-graphics
//! text in the top-left corner.
//!
//! `no_std`, shared by the firmware example `arm` (which draws the parts baked by
//! its build.rs) and the host (`host_tests::firmware::ArmDemo`, which bakes the
//! same arrays at run time: the frame-hash test, the `arm` PNG writer and the
//! `instrument-window --demo arm` simulator window).

use embedded_graphics::mono_font::{iso_8859_1::FONT_4X6, MonoTextStyleBuilder};
use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use pbuffer::render::BakedMesh;
use pbuffer::{packed_len, Camera, Error, FrameRows, PackedFramebuffer, Pose, SceneDrawing, Stats};

use crate::shapes::{Axis, Shape, BOX, PRISM};

/// Display width in pixels.
pub const WIDTH: usize = 128;
/// Display height in pixels.
pub const HEIGHT: usize = 64;
/// Frames of the animation (the firmware draws them all once).
pub const FRAMES: u32 = 8;

/// The demo's framebuffer: 128 x 64, packed, 1 bit per pixel.
pub type Frame = PackedFramebuffer<WIDTH, HEIGHT, { packed_len(WIDTH, HEIGHT) }>;

/// Vertices, corners and faces + 1 of a part of a box and a prism (base, links).
const BP: [usize; 3] = [BOX[0] + PRISM[0], BOX[1] + PRISM[1], BOX[2] + PRISM[2] + 1];
/// The same of three boxes (the gripper).
const B3: [usize; 3] = [3 * BOX[0], 3 * BOX[1], 3 * BOX[2] + 1];

/// The base, a link: a box and a prism.
pub type BoxPrism = Shape<{ BP[0] }, { BP[1] }, { BP[2] }>;
/// The gripper: a palm and two fingers.
pub type Gripper = Shape<{ B3[0] }, { B3[1] }, { B3[2] }>;

/// The base (fixed): a disc on the floor and a pillar; the shoulder sits on it.
pub fn base() -> BoxPrism {
    Shape::new()
        .prism(Axis::Y, [0.0, 0.175, 0.0], 1.1, 0.175)
        .cuboid([-0.35, 0.35, -0.35], [0.35, 1.1, 0.35])
}

/// The upper link, from its shoulder joint (the origin) along +x: a hub about z
/// and a beam of `UPPER` length.
pub fn upper() -> BoxPrism {
    Shape::new()
        .prism(Axis::Z, [0.0; 3], 0.32, 0.3)
        .cuboid([0.0, -0.2, -0.2], [UPPER, 0.2, 0.2])
}

/// The forearm, from its elbow joint (the origin) along +x.
pub fn forearm() -> BoxPrism {
    Shape::new()
        .prism(Axis::Z, [0.0; 3], 0.24, 0.25)
        .cuboid([0.0, -0.14, -0.14], [FOREARM, 0.14, 0.14])
}

/// The gripper, from its wrist joint (the origin) along +x: a palm and two fingers.
pub fn gripper() -> Gripper {
    Shape::new()
        .cuboid([0.0, -0.3, -0.15], [0.2, 0.3, 0.15])
        .cuboid([0.2, 0.12, -0.08], [0.6, 0.24, 0.08])
        .cuboid([0.2, -0.24, -0.08], [0.6, -0.12, 0.08])
}

/// Length of the upper link and of the forearm; the shoulder's height.
const UPPER: f32 = 2.0;
const FOREARM: f32 = 1.5;
const SHOULDER: f32 = 1.25;

/// The parts' sizes over all four: vertices, faces, edges (each part's own, as
/// baked at 30 degrees: 36 each) and corners + faces + 1.
pub const V: usize = 3 * BP[0] + B3[0];
/// See [`V`].
pub const F: usize = 3 * (BP[2] - 1) + B3[2] - 1;
/// See [`V`].
pub const E: usize = 4 * 36;
/// See [`V`].
pub const C: usize = 3 * BP[1] + B3[1] + F + 1;

/// The arm's scene: four instances.
pub type ArmScene<'m> = SceneDrawing<'m, 4, V, F, E, C>;
/// The rows the arm's frame needs.
pub type ArmRows = FrameRows<WIDTH, HEIGHT>;

/// The joint angles of frame `n`, in degrees: base yaw, shoulder, elbow, wrist.
pub fn joints(n: u32) -> [i32; 4] {
    let k = (n % FRAMES) as i32;
    [-35 + 8 * k, 45 - 4 * k, -80 + 8 * k, -30 + 7 * k]
}

/// The poses of the four parts for `joints`: each link carried by the one before
/// (`Pose::then`), the base fixed.
pub fn poses(joints: [i32; 4]) -> [Pose; 4] {
    let [yaw, shoulder, elbow, wrist] = joints.map(|d| d as f32);
    let turret = Pose::from_degrees([0.0, yaw, 0.0], [0.0, SHOULDER, 0.0]);
    let upper = Pose::from_degrees([0.0, 0.0, shoulder], [0.0; 3]).then(&turret);
    let forearm = Pose::from_degrees([0.0, 0.0, elbow], [UPPER, 0.0, 0.0]).then(&upper);
    let gripper = Pose::from_degrees([0.0, 0.0, wrist], [FOREARM, 0.0, 0.0]).then(&forearm);
    [Pose::IDENTITY, upper, forearm, gripper]
}

/// The camera: fixed, above and in front, the arm on the right of the screen.
pub fn camera() -> Result<Camera, Error> {
    Camera::look_at([0.4, 3.6, 6.4], [1.1, 1.5, 0.0], 34.0)
}

/// Adds the four baked parts (base, upper link, forearm, gripper) at frame 0's poses.
pub fn add_parts<'m>(scene: &mut ArmScene<'m>, parts: [BakedMesh<'m>; 4]) -> Result<(), Error> {
    for (mesh, pose) in parts.into_iter().zip(poses(joints(0))) {
        scene.add(mesh, pose)?;
    }
    Ok(())
}

/// Draws frame `n` into `fb`: clears it, poses the parts by [`joints`]`(n)`, draws
/// the scene (dashed hidden lines) and the angles. Returns the 3-D statistics.
pub fn draw(
    scene: &mut ArmScene<'_>,
    rows: &mut ArmRows,
    n: u32,
    fb: &mut Frame,
) -> Result<Stats, Error> {
    fb.clear();
    let angles = joints(n);
    for (k, pose) in poses(angles).into_iter().enumerate() {
        if let Some(p) = scene.pose_mut(k) {
            *p = pose;
        }
    }
    let stats = scene.draw(&camera()?, rows, fb)?;
    match draw_angles(angles, fb) {
        Ok(()) => Ok(stats),
        Err(never) => match never {},
    }
}

/// The joint angles, one a line (`BASE -40°`), on a cleared background so the
/// drawing never runs through the text.
pub fn draw_angles<D: DrawTarget<Color = BinaryColor>>(
    joints: [i32; 4],
    target: &mut D,
) -> Result<(), D::Error> {
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_4X6)
        .text_color(BinaryColor::On)
        .background_color(BinaryColor::Off)
        .build();
    for (k, (name, deg)) in ["BASE", "SHLD", "ELBW", "WRST"]
        .into_iter()
        .zip(joints)
        .enumerate()
    {
        let mut buf = [0u8; 12];
        let text = line(name, deg, &mut buf);
        let at = Point::new(1, 1 + 7 * k as i32);
        Text::with_baseline(text, at, style, Baseline::Top).draw(target)?;
    }
    Ok(())
}

/// `NAME` and `deg` (within +-999) right-aligned in 4 places and a degree sign.
fn line<'b>(name: &str, deg: i32, buf: &'b mut [u8; 12]) -> &'b str {
    let mut len = 0;
    for &b in name.as_bytes().iter().take(4) {
        buf[len] = b;
        len += 1;
    }
    let digits = deg.unsigned_abs().min(999);
    let mut field = [b' '; 4];
    let mut at = 3;
    let mut rest = digits;
    loop {
        field[at] = b'0' + (rest % 10) as u8;
        rest /= 10;
        if rest == 0 || at == 0 {
            break;
        }
        at -= 1;
    }
    if deg < 0 && at > 0 {
        field[at - 1] = b'-';
    }
    for b in field {
        buf[len] = b;
        len += 1;
    }
    // U+00B0 DEGREE SIGN in UTF-8.
    buf[len] = 0xC2;
    buf[len + 1] = 0xB0;
    core::str::from_utf8(&buf[..len + 2]).unwrap_or("?")
}
