//! What a posed instance costs: `N` copies of a small part (the arm's forearm, a
//! beam and a hub: 24 vertices, 16 faces) in a grid, drawn as one mesh baked once
//! (the union of the copies, `BakedDrawing`) and as `N` instances of the part baked
//! once (`SceneDrawing`), for `N` in [`COUNTS`]. Both draw the same frame, bit for
//! bit (the scene's frame is its union's); the difference in instructions is what
//! the instances cost per frame (posing each vertex, the eye brought into each
//! instance's space, the facing tests on the baked planes).
//!
//! Shared by the firmware example `instances` (the unions baked by its build.rs)
//! and the host's frame-hash test (the same arrays baked at run time).

use pbuffer::render::BakedMesh;
use pbuffer::{BakedDrawing, Camera, Error, FrameRows, Pose, SceneDrawing, Stats};

use crate::arm::{self, BoxPrism, Frame, HEIGHT, WIDTH};
use crate::shapes::Shape;

/// The instance counts measured.
pub const COUNTS: [usize; 3] = [1, 4, 16];
/// The most instances.
pub const MOST: usize = 16;
/// Frames per count (the camera turns a little from one to the next).
pub const FRAMES: u32 = 4;

/// The part: the arm's forearm.
pub fn part() -> BoxPrism {
    arm::forearm()
}

/// Vertices, corners, faces and edges of one part (its edges as baked).
const PART: [usize; 4] = [24, 72, 16, 36];
/// Room for the most instances, as one mesh or as instances.
pub const V: usize = MOST * PART[0];
/// See [`V`].
pub const F: usize = MOST * PART[2];
/// See [`V`].
pub const E: usize = MOST * PART[3];
/// See [`V`]: corners, faces and one more, as the scene keeps them.
pub const C: usize = MOST * PART[1] + F + 1;
/// Facets and lines on one row: room for a row across the widest grid.
pub const FACETS: usize = 128;
/// See [`FACETS`].
pub const LINES: usize = 128;

/// The union of `N` copies as one mesh.
pub type Grid<const VN: usize, const IN: usize, const ON: usize> = Shape<VN, IN, ON>;
/// One mesh of up to [`MOST`] copies, drawn by the fast engine.
pub type UnionDrawing<'m> = BakedDrawing<'m, V, F, E, FACETS, LINES>;
/// Up to [`MOST`] instances of the part.
pub type InstanceScene<'m> = SceneDrawing<'m, MOST, V, F, E, C, FACETS, LINES>;
/// The rows of a frame.
pub type Rows = FrameRows<WIDTH, HEIGHT>;

/// Copies on a side of the grid of `n` (1, 2 or 4).
fn side(n: usize) -> usize {
    match n {
        0 | 1 => 1,
        2..=4 => 2,
        _ => 4,
    }
}

/// Where copy `k` of `n` sits: rows along z, the beams along x.
pub fn pose(k: usize, n: usize) -> Pose {
    let s = side(n);
    let (col, row) = ((k % s) as f32, (k / s) as f32);
    Pose::translation([col * 2.25, 0.0, row * 1.0])
}

/// The union of the first `n` copies (`VN` = 24 n vertices, `IN` = 72 n corners,
/// `ON` = 16 n + 1 offsets).
pub fn grid<const VN: usize, const IN: usize, const ON: usize>(n: usize) -> Grid<VN, IN, ON> {
    let one = part();
    (0..n).fold(Shape::new(), |g, k| g.posed(&one, &pose(k, n)))
}

/// The camera of frame `f` for `n` copies: looking at the grid's middle from the
/// front and above, far enough to see it whole, turning 5 degrees a frame.
pub fn camera(n: usize, f: u32) -> Result<Camera, Error> {
    let s = side(n) as f32;
    let mid = [(s - 1.0) * 1.125 + 0.75, 0.0, (s - 1.0) * 0.5];
    let reach = 2.2 + 2.0 * s;
    let t = (f as f32 * 5.0 - 25.0) * (core::f32::consts::PI / 180.0);
    let (sin, cos) = (micromath::F32Ext::sin(t), micromath::F32Ext::cos(t));
    let eye = [
        mid[0] + reach * sin,
        mid[1] + 0.8 * reach,
        mid[2] + reach * cos,
    ];
    Camera::look_at(eye, mid, 40.0)
}

/// Sets the scene to `n` instances of `part` at their grid poses.
pub fn set_instances<'m>(
    scene: &mut InstanceScene<'m>,
    part: BakedMesh<'m>,
    n: usize,
) -> Result<(), Error> {
    scene.clear();
    for k in 0..n {
        scene.add(part, pose(k, n))?;
    }
    Ok(())
}

/// Frame `f` of the union of `n` copies (set with `set_mesh`) into `fb`.
pub fn draw_union(
    drawing: &mut UnionDrawing<'_>,
    rows: &mut Rows,
    n: usize,
    f: u32,
    fb: &mut Frame,
) -> Result<Stats, Error> {
    fb.clear();
    drawing.draw(&camera(n, f)?, rows, fb)
}

/// Frame `f` of `n` instances (set with [`set_instances`]) into `fb`.
pub fn draw_scene(
    scene: &mut InstanceScene<'_>,
    rows: &mut Rows,
    n: usize,
    f: u32,
    fb: &mut Frame,
) -> Result<Stats, Error> {
    fb.clear();
    scene.draw(&camera(n, f)?, rows, fb)
}
