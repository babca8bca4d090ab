// The panel bracket's mesh arrays: `include!`d by `scenes.rs` (its `panel` module, for the
// firmware and the host tests) and by `build.rs` (which bakes the fast engine's constants
// and the planarity bits from them), so both read the same arrays.

/// An L profile (x, y) extruded over z in [-1, 1] (vertices 0-11), and a hexagonal
/// boss of radius 0.45 on its foot, y in [0.6, 1.4] (vertices 12-23).
pub const VERTICES: [[f32; 3]; 24] = [
    [0.0, 0.0, -1.0],
    [3.0, 0.0, -1.0],
    [3.0, 0.6, -1.0],
    [0.6, 0.6, -1.0],
    [0.6, 2.0, -1.0],
    [0.0, 2.0, -1.0],
    [0.0, 0.0, 1.0],
    [3.0, 0.0, 1.0],
    [3.0, 0.6, 1.0],
    [0.6, 0.6, 1.0],
    [0.6, 2.0, 1.0],
    [0.0, 2.0, 1.0],
    // boss, bottom ring (angle 0, 60, ..., 300 degrees in the x-z plane)
    [2.25, 0.6, 0.0],
    [2.025, 0.6, 0.3897114],
    [1.575, 0.6, 0.3897114],
    [1.35, 0.6, 0.0],
    [1.575, 0.6, -0.3897114],
    [2.025, 0.6, -0.3897114],
    // top ring
    [2.25, 1.4, 0.0],
    [2.025, 1.4, 0.3897114],
    [1.575, 1.4, 0.3897114],
    [1.35, 1.4, 0.0],
    [1.575, 1.4, -0.3897114],
    [2.025, 1.4, -0.3897114],
];
/// Faces, counter-clockwise from outside: L front, L back, 6 L sides, boss
/// top, bottom and 6 sides.
pub const INDICES: [u32; 72] = [
    6, 7, 8, 9, 10, 11, // front (z = 1), concave
    5, 4, 3, 2, 1, 0, // back
    0, 1, 7, 6, //
    1, 2, 8, 7, //
    2, 3, 9, 8, //
    3, 4, 10, 9, //
    4, 5, 11, 10, //
    5, 0, 6, 11, //
    23, 22, 21, 20, 19, 18, // boss top
    12, 13, 14, 15, 16, 17, // boss bottom
    13, 12, 18, 19, //
    14, 13, 19, 20, //
    15, 14, 20, 21, //
    16, 15, 21, 22, //
    17, 16, 22, 23, //
    12, 17, 23, 18, //
];
pub const OFFSETS: [u32; 17] = [
    0, 6, 12, 16, 20, 24, 28, 32, 36, 42, 48, 52, 56, 60, 64, 68, 72,
];
/// Unique edges: 18 of the L, 18 of the boss.
pub const EDGES: usize = 36;
