//! The grey coverage mode: sub-sample masks, resolution at shared edges, pictures.

extern crate std;
use std::string::String;
use std::vec;
use std::vec::Vec;

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics_core::pixelcolor::{Gray4, Gray8};
use fixed::types::extra::{U1, U4};

use super::*;
use crate::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use crate::render::{Cull, ProjectedVertex, Settings, Workspace, ZBufferRenderer};
use crate::{Camera, Dashes, FillSolid, Pattern, Projection};

fn v(x: i32, y: i32) -> ScreenVertex {
    ScreenVertex { x, y, q: 1 << 30 }
}

/// Pixels at S = 4: vertex coordinates are sixteenths.
fn px(p: f64) -> i32 {
    (p * 16.0) as i32
}

fn mask(poly: &[ScreenVertex], i: i64, j: i64) -> u16 {
    pixel_mask(poly, &bounds(poly), 4, i, j)
}

/// A vertical edge through the middle of pixel 2 leaves its two right columns of
/// sub-samples: 8 of 16.
#[test]
fn a_half_plane_through_the_middle_covers_half() {
    let rect = [
        v(px(2.5), 0),
        v(px(10.0), 0),
        v(px(10.0), px(10.0)),
        v(px(2.5), px(10.0)),
    ];
    assert_eq!(mask(&rect, 2, 3), 0xCCCC);
    assert_eq!(mask(&rect, 2, 3).count_ones(), 8);
    assert_eq!(mask(&rect, 1, 3), 0);
    assert_eq!(mask(&rect, 3, 3), 0xFFFF);
    // A horizontal edge a quarter into the pixel: three rows of four.
    let low = [
        v(0, px(5.25)),
        v(px(10.0), px(5.25)),
        v(px(10.0), px(9.0)),
        v(0, px(9.0)),
    ];
    assert_eq!(mask(&low, 4, 5), 0xFFF0);
}

/// Two triangles sharing the diagonal x + y = 8 through pixel (2, 5), whose four
/// sub-samples with a + b = 3 lie exactly on it: each sub-sample is covered once,
/// the shared ones by the triangle to the right of the edge (top-left rule).
#[test]
fn abutting_faces_split_the_sub_samples() {
    let upper = [v(0, 0), v(px(8.0), 0), v(0, px(8.0))];
    let lower = [v(px(8.0), 0), v(px(8.0), px(8.0)), v(0, px(8.0))];
    for (i, j) in [(2, 5), (3, 4), (0, 7), (5, 2), (4, 4)] {
        let (a, b) = (mask(&upper, i, j), mask(&lower, i, j));
        assert_eq!(a & b, 0, "pixel ({i}, {j}) covered twice");
        assert_eq!(a | b, 0xFFFF, "pixel ({i}, {j}) has a hole");
    }
    assert_eq!(mask(&upper, 2, 5).count_ones(), 6);
    assert_eq!(mask(&lower, 2, 5).count_ones(), 10);
}

/// Depth decides a sub-sample covered twice; within the tie the lower index keeps it.
#[test]
fn the_nearest_face_takes_a_shared_sub_sample() {
    let square = |q: u32| {
        let s = [(0, 0), (64, 0), (64, 64), (0, 64)].map(|(x, y)| ScreenVertex { x, y, q });
        (s, DepthPlane::new(&s, 4).unwrap())
    };
    let ((_, far), (_, near)) = (square(1 << 20), square(1 << 28));
    let c = |plane, level| Candidate {
        mask: 0xFFFF,
        plane,
        level,
    };
    assert_eq!(resolve(&[c(far, 10), c(near, 200)], 4, 1, 1, 0), 16 * 200);
    assert_eq!(resolve(&[c(near, 200), c(far, 10)], 4, 1, 1, 0), 16 * 200);
    // Equal depth: the first (lower face index) wins.
    assert_eq!(resolve(&[c(near, 30), c(near, 200)], 4, 1, 1, 0), 16 * 30);
    // Half covered, half background.
    let half = Candidate {
        mask: 0x00FF,
        ..c(near, 200)
    };
    assert_eq!(resolve(&[half], 4, 1, 1, 40), 8 * 200 + 8 * 40);
}

/// A mesh in the plane z = 0 seen face-on by an orthographic camera on +Z with
/// half-height 32 on a 64 x 64 target: world (x, y) is screen (x + 32, 32 - y).
fn picture<C, const N: usize>(
    v: &[[f32; 3]],
    faces: &[[u32; N]],
    palette: &GreyShades<C>,
    mode: DrawMode,
) -> MockDisplay<C>
where
    C: GrayColor + From<Gray8> + PixelColor,
    Gray8: From<C>,
{
    let idx: Vec<u32> = faces.iter().flatten().copied().collect();
    let off: Vec<u32> = (0..=faces.len() as u32).map(|f| N as u32 * f).collect();
    let mesh = Mesh::new(v, &idx, &off).unwrap();
    let mut weld = vec![0u32; v.len()];
    let mut scratch = vec![HalfEdgeRecord::default(); idx.len()];
    let mut store = vec![MeshEdge::default(); idx.len()];
    let adj = EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut store).unwrap();
    let camera = Camera::new(
        [0.0, 0.0, 5.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        Projection::Orthographic { half_height: 32.0 },
        0.5,
        20.0,
    )
    .unwrap();
    let settings = Settings {
        mode,
        cull: Cull::Off,
        pattern: Pattern::default(),
        dashes: Dashes::Screen,
        lines: crate::render::LineVisibility::ByPixel,
    };
    let (w, band) = (64usize, 7u16);
    let mut vertices = vec![ProjectedVertex::default(); v.len()];
    let mut drawn = vec![0u32; 1];
    let mut features = vec![0u32; adj.edges().len().div_ceil(32)];
    let stored = usize::from(crate::render::storage_rows(band, 64));
    let mut depth = vec![0u32; w * stored];
    let mut ids = vec![0u16; w * stored];
    let mut lines = vec![0u32; 2 * 2 * usize::from(band)];
    let mut ws = Workspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        depth: &mut depth,
        ids: &mut ids,
        lines: &mut lines,
    };
    let mut display = MockDisplay::new();
    let mut sink = FillSolid::new(&mut display).unwrap();
    let mut renderer = ZBufferRenderer::<U4, 64, 16>::new();
    renderer
        .render_grey(
            &mesh,
            &adj,
            &camera,
            &settings,
            &mut ws,
            &mut [SmallFace::default(); 64],
            palette,
            &mut sink,
            &mut (),
        )
        .unwrap();
    display
}

fn flat<C: GrayColor + From<Gray8>>(level: u8) -> GreyShades<C> {
    GreyShades {
        background: C::BLACK,
        line: C::WHITE,
        dark: Gray8::new(level).into(),
        light: Gray8::new(level).into(),
    }
}

fn luma(d: &MockDisplay<Gray8>, x: i32, y: i32) -> Option<u8> {
    d.get_pixel(embedded_graphics::prelude::Point::new(x, y))
        .map(|c| c.luma())
}

/// A square of two triangles, x in [-10.5, 9.5] and y in [-10.25, 9.75] (screen x
/// [21.5, 41.5], y [22.25, 42.25]): no pixel along the shared diagonal shows the
/// background, and the border pixels hold exactly their sub-sample coverage.
#[test]
fn a_shared_edge_lets_no_background_through() {
    let v = [
        [-10.5, -10.25, 0.0],
        [9.5, -10.25, 0.0],
        [9.5, 9.75, 0.0],
        [-10.5, 9.75, 0.0],
    ];
    let d = picture(
        &v,
        &[[0, 1, 2], [0, 2, 3]],
        &flat::<Gray8>(200),
        DrawMode::Surfaces,
    );
    for y in 23..42 {
        for x in 22..41 {
            assert_eq!(luma(&d, x, y), Some(200), "({x}, {y})");
        }
    }
    // Left and right edges at half a pixel: 8/16; top at a quarter: 12/16; bottom
    // at a quarter: 4/16; the top left corner 6/16.
    assert_eq!(luma(&d, 21, 30), Some(100));
    assert_eq!(luma(&d, 41, 30), Some(100));
    assert_eq!(luma(&d, 30, 22), Some(150));
    assert_eq!(luma(&d, 30, 42), Some(50));
    assert_eq!(luma(&d, 21, 22), Some(75));
    // Beside the square: background where a neighbour is a face, else untouched.
    assert_eq!(luma(&d, 20, 30), Some(0));
    assert_eq!(luma(&d, 19, 30), None);
}

/// A small triangle on a 4-bit target: the summed coverage is its area, the
/// interior is full, and the picture is pinned.
#[test]
fn a_gray4_triangle() {
    // Screen (34.3, 36.6), (42.9, 38.2), (36.1, 29.4).
    let v = [[2.3, -4.6, 0.0], [10.9, -6.2, 0.0], [4.1, 2.6, 0.0]];
    let d = picture(&v, &[[0, 1, 2]], &flat::<Gray4>(255), DrawMode::Surfaces);
    let mut sum = 0u32;
    let mut rows = String::new();
    for y in 28..40 {
        for x in 33..45 {
            let p = d.get_pixel(embedded_graphics::prelude::Point::new(x, y));
            sum += p.map_or(0, |c| u32::from(c.luma()));
            rows.push(p.map_or('.', |c| {
                char::from_digit(u32::from(c.luma()), 16)
                    .unwrap()
                    .to_ascii_uppercase()
            }));
        }
        rows.push('\n');
    }
    // Shoelace area of the screen triangle.
    let (a, b, c) = ((34.3, 36.6), (42.9, 38.2), (36.1, 29.4));
    let area: f64 = ((b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)) / 2.0;
    let covered = f64::from(sum) / 15.0;
    assert!(
        (covered - area.abs()).abs() < 0.03 * area.abs(),
        "coverage {covered} against area {}\n{rows}",
        area.abs()
    );
    let expected = "\
............
..030.......
..3E10......
.07FB00.....
.0AFF80.....
.0EFFF50....
.3FFFFE20...
07FFFFFC00..
08CFFFFF80..
0000468BE6..
.....00001..
............
";
    assert_eq!(rows, expected, "\n{rows}");
}

/// Lines stay solid over the grey faces.
#[test]
fn lines_stay_solid() {
    let v = [[-10.0, -10.0, 0.0], [10.0, -10.0, 0.0], [0.0, 10.0, 0.0]];
    let d = picture(
        &v,
        &[[0, 1, 2]],
        &flat::<Gray8>(100),
        DrawMode::SurfacesDashed,
    );
    // The bottom edge y = -10 (screen 42) is a boundary edge: a solid white row.
    for x in 23..41 {
        assert_eq!(luma(&d, x, 42), Some(255), "({x}, 42)");
    }
}

/// Too few sub-pixel bits is an error, not a wrong picture.
#[test]
fn one_sub_pixel_bit_is_too_few() {
    let v = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let (idx, off) = ([0u32, 1, 2], [0u32, 3]);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let (mut weld, mut scratch, mut store) = (
        [0u32; 3],
        [HalfEdgeRecord::default(); 3],
        [MeshEdge::default(); 3],
    );
    let adj = EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut store).unwrap();
    let camera = Camera::new(
        [0.0, 0.0, 5.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        Projection::Orthographic { half_height: 2.0 },
        0.5,
        20.0,
    )
    .unwrap();
    let (mut vertices, mut drawn, mut features) =
        ([ProjectedVertex::default(); 3], [0u32; 1], [0u32; 1]);
    let (mut depth, mut ids, mut lines) = ([0u16; 64 * 64], [0u16; 64 * 64], [0u32; 256]);
    let mut ws = Workspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        depth: &mut depth,
        ids: &mut ids,
        lines: &mut lines,
    };
    let mut display = MockDisplay::<Gray8>::new();
    let mut sink = FillSolid::new(&mut display).unwrap();
    let result = ZBufferRenderer::<U1, 16, 16>::new().render_grey(
        &mesh,
        &adj,
        &camera,
        &Settings::default(),
        &mut ws,
        &mut [SmallFace::default(); 4],
        &GreyShades::<Gray8>::default(),
        &mut sink,
        &mut (),
    );
    assert_eq!(
        result,
        Err(Error::SubpixelTooCoarse {
            bits: 1,
            needed: GREY_MIN_BITS
        })
    );
}
