//! The fast engine's contract: baked data checked, errors with their sizes, and a
//! small frame drawn exactly once per pixel.

extern crate std;
use std::vec;
use std::vec::Vec;

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::BinaryColor;
use fixed::types::extra::{U4, U7};

use super::*;
use crate::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use crate::render::{DrawMode, SolidPalette};
use crate::Capacity;
use crate::{packed_len, Dashes, FillSolid, PackedFramebuffer, Pattern, Projection};

/// A unit square in the z = 0 plane as two triangles sharing the diagonal 0-2.
const SQUARE: [[f32; 3]; 4] = [[-1., -1., 0.], [1., -1., 0.], [1., 1., 0.], [-1., 1., 0.]];
const TRIS: [u32; 6] = [0, 1, 2, 0, 2, 3];
const OFFSETS: [u32; 3] = [0, 3, 6];

struct Baked {
    planes: Vec<FacePlane>,
    edges: Vec<CompactEdge>,
}

fn bake(mesh: &Mesh<'_>) -> Baked {
    let mut weld = vec![0u32; mesh.vertices().len()];
    let mut scratch = vec![HalfEdgeRecord::EMPTY; mesh.indices().len()];
    let mut store = vec![MeshEdge::EMPTY; mesh.indices().len()];
    let adjacency = EdgeAdjacency::build(mesh, 30.0, &mut weld, &mut scratch, &mut store).unwrap();
    let mut planes = vec![FacePlane::default(); mesh.face_count()];
    let mut edges = vec![CompactEdge::default(); adjacency.edges().len()];
    BakedMesh::bake(mesh, &adjacency, &mut planes, &mut edges).unwrap();
    Baked { planes, edges }
}

struct Buffers {
    vertices: Vec<FastVertex>,
    facing: Vec<u32>,
    face_links: Vec<u16>,
    line_links: Vec<u16>,
    heads: Vec<u16>,
    row: Vec<u32>,
    masks: Vec<u32>,
    slopes: Vec<u16>,
}

impl Buffers {
    fn new(vertices: usize, faces: usize, edges: usize, w: usize, h: usize) -> Self {
        Self {
            vertices: vec![FastVertex::ZERO; vertices],
            facing: vec![0; faces.div_ceil(32)],
            face_links: vec![0; faces],
            line_links: vec![0; edges],
            heads: vec![0; 2 * h],
            row: vec![0; w],
            masks: vec![0; 2 * w.div_ceil(32)],
            slopes: vec![0; faces],
        }
    }

    fn workspace(&mut self) -> FastWorkspace<'_> {
        FastWorkspace {
            vertices: &mut self.vertices,
            facing: &mut self.facing,
            face_links: &mut self.face_links,
            line_links: &mut self.line_links,
            heads: &mut self.heads,
            row: &mut self.row,
            masks: &mut self.masks,
            pool: &mut [],
            ids: &mut [],
            slopes: &mut self.slopes,
            phases: &mut [],
            segments: None,
        }
    }
}

fn camera() -> Camera {
    looking_down_z(1.5)
}

/// An orthographic camera on the z axis, 4 units out, seeing `half_height` above
/// and below the origin.
fn looking_down_z(half_height: f32) -> Camera {
    Camera::new(
        [0., 0., 4.],
        [0., 0., 0.],
        [0., 1., 0.],
        Projection::Orthographic { half_height },
        0.1,
        10.0,
    )
    .unwrap()
}

fn settings(mode: DrawMode) -> Settings {
    Settings {
        mode,
        cull: Cull::Off,
        pattern: Pattern::PAPER,
        dashes: Dashes::Screen,
        lines: crate::render::LineVisibility::ByPixel,
    }
}

/// Draws the two-triangle square filled into `sink` (`width` x 64), seen
/// orthographically from (`eye_x`, 0, 4) at 16 px a unit: both faces drawn.
fn draw_square<K: SpanSink<Color = BinaryColor>>(sink: &mut K, width: usize, eye_x: f32)
where
    K::Error: core::fmt::Debug,
{
    let mesh = Mesh::new(&SQUARE, &TRIS, &OFFSETS).unwrap();
    let b = bake(&mesh);
    let baked = BakedMesh::new(mesh, &b.planes, &b.edges).unwrap();
    let mut buffers = Buffers::new(4, 2, b.edges.len(), width, 64);
    let palette = SolidPalette {
        line: BinaryColor::On,
        face: Some(BinaryColor::On),
    };
    let camera = Camera::new(
        [eye_x, 0., 4.],
        [eye_x, 0., 0.],
        [0., 1., 0.],
        Projection::Orthographic { half_height: 2.0 },
        0.1,
        10.0,
    )
    .unwrap();
    let stats = FastRenderer::<U4, 8, 8>::new()
        .render(
            &baked,
            &camera,
            &settings(DrawMode::Surfaces),
            &mut buffers.workspace(),
            &palette,
            sink,
            &mut (),
        )
        .unwrap();
    assert_eq!(stats.faces_drawn, 2);
}

/// Exactly the pixels in `columns` x [16, 48) of a `width` x 64 frame are `lit`.
fn lit_exactly(width: i32, columns: core::ops::Range<i32>, lit: impl Fn(i32, i32) -> bool) {
    for y in 0..64 {
        for x in 0..width {
            let inside = columns.contains(&x) && (16..48).contains(&y);
            assert_eq!(lit(x, y), inside, "pixel ({x}, {y})");
        }
    }
}

#[test]
fn two_triangles_fill_their_square_once_with_no_gap_on_the_diagonal() {
    // MockDisplay panics on a pixel drawn twice: each pixel is one span's.
    let mut display = MockDisplay::<BinaryColor>::new();
    draw_square(&mut FillSolid::new(&mut display).unwrap(), 64, 0.0);
    // 16 px a unit: the square covers exactly the centres in [16, 48) x [16, 48).
    lit_exactly(64, 16..48, |x, y| {
        let p = embedded_graphics::prelude::Point::new(x, y);
        display.get_pixel(p).is_some()
    });
}

/// The surface modes scan a row's words for runs only within the columns the
/// frame's faces can reach: a square in the third and fourth words of a 128-pixel
/// row (columns 80 to 111) comes out whole, and the words before it empty.
#[test]
fn a_square_right_of_the_first_words_is_filled_whole() {
    let mut frame = PackedFramebuffer::<128, 64, { packed_len(128, 64) }>::new();
    draw_square(&mut frame, 128, -2.0);
    lit_exactly(128, 80..112, |x, y| frame.pixel(x as u32, y as u32));
}

#[test]
fn baked_planes_that_are_not_the_faces_own_are_refused() {
    let mesh = Mesh::new(&SQUARE, &TRIS, &OFFSETS).unwrap();
    let mut b = bake(&mesh);
    assert!(BakedMesh::new(mesh, &b.planes, &b.edges).is_ok());
    b.planes[1].normal[2] += 1.0;
    assert_eq!(
        BakedMesh::new(mesh, &b.planes, &b.edges).unwrap_err(),
        Error::BadFacePlanes { face: 1 }
    );
    assert_eq!(
        BakedMesh::new(mesh, &b.planes[..1], &b.edges).unwrap_err(),
        Error::BadFacePlanes { face: 1 }
    );
    b.planes[1].normal[2] -= 1.0;
    b.edges[0].faces = [0, 7];
    assert!(matches!(
        BakedMesh::new(mesh, &b.planes, &b.edges).unwrap_err(),
        Error::BadEdgeList { edge: 0, .. }
    ));
}

#[test]
fn too_little_lent_storage_or_room_is_an_error_with_the_size_needed() {
    let mesh = Mesh::new(&SQUARE, &TRIS, &OFFSETS).unwrap();
    let b = bake(&mesh);
    let baked = BakedMesh::new(mesh, &b.planes, &b.edges).unwrap();
    let mut fb = PackedFramebuffer::<16, 16, { packed_len(16, 16) }>::new();
    let palette = SolidPalette {
        line: BinaryColor::On,
        face: Some(BinaryColor::On),
    };
    let s = settings(DrawMode::SurfacesDashed);
    // Three vertex slots for four vertices.
    let mut short = Buffers::new(3, 2, b.edges.len(), 16, 16);
    let r = FastRenderer::<U4, 8, 8>::new().render(
        &baked,
        &camera(),
        &s,
        &mut short.workspace(),
        &palette,
        &mut fb,
        &mut (),
    );
    assert_eq!(
        r.unwrap_err(),
        Error::CapacityExceeded {
            what: Capacity::Vertices,
            needed: 4,
            capacity: 3
        }
    );
    // Room for one active facet where the square's two are active together.
    let mut ok = Buffers::new(4, 2, b.edges.len(), 16, 16);
    let r = FastRenderer::<U4, 1, 8>::new().render(
        &baked,
        &camera(),
        &s,
        &mut ok.workspace(),
        &palette,
        &mut fb,
        &mut (),
    );
    assert_eq!(
        r.unwrap_err(),
        Error::CapacityExceeded {
            what: Capacity::ActiveFacets,
            needed: 2,
            capacity: 1
        }
    );
    // Seven sub-pixel bits do not fit the 16-bit screen coordinates.
    let r = FastRenderer::<U7, 8, 8>::new().render(
        &baked,
        &camera(),
        &s,
        &mut ok.workspace(),
        &palette,
        &mut fb,
        &mut (),
    );
    assert_eq!(r.unwrap_err(), Error::SubpixelTooFine { bits: 7, max: 6 });
}

/// A regression test: a steep line entering the frame from above was drawn with
/// the pixels of its rows above the frame, one row a pixel, from row 0 down (its
/// walk started at its first centre, above the frame, one step a row).
#[test]
fn a_steep_line_entering_from_above_keeps_its_columns() {
    // Screen (16 px a unit, origin at the centre): the apex (32, -16) is above the
    // 64 x 64 frame; the sides run to (40, 48) and (24, 48).
    let corners = [[0., 3., 0.], [0.5, -1., 0.], [-0.5, -1., 0.]];
    let mesh = Mesh::new(&corners, &[0, 1, 2], &[0, 3]).unwrap();
    let b = bake(&mesh);
    let baked = BakedMesh::new(mesh, &b.planes, &b.edges).unwrap();
    let mut buffers = Buffers::new(3, 1, b.edges.len(), 64, 64);
    let mut display = MockDisplay::<BinaryColor>::new();
    let camera = looking_down_z(2.0);
    FastRenderer::<U4, 8, 8>::new()
        .render(
            &baked,
            &camera,
            &settings(DrawMode::Wireframe),
            &mut buffers.workspace(),
            &SolidPalette {
                line: BinaryColor::On,
                face: None,
            },
            &mut FillSolid::new(&mut display).unwrap(),
            &mut (),
        )
        .unwrap();
    // At the centre of row r the sides are at x = 32 +- (r + 16.5) / 8: each row
    // has the pixel of each side's crossing (floor), and nothing else.
    for y in 0..40 {
        let off = (f64::from(y) + 16.5) / 8.0;
        let want = [(32.0 - off).floor() as i32, (32.0 + off).floor() as i32];
        let on: Vec<i32> = (0..64)
            .filter(|&x| {
                let p = embedded_graphics::prelude::Point::new(x, y);
                display.get_pixel(p).is_some()
            })
            .collect();
        assert_eq!(on, want, "row {y}");
    }
}

/// The render tests' cube (side 2 about the origin, faces counter-clockwise seen
/// from outside) without its face at z = 1: a box with one hole.
fn open_box() -> (Vec<[f32; 3]>, Vec<u32>, Vec<u32>) {
    let (vertices, mut indices, _) = crate::render::two_squares::cube();
    // Its second face is the top, [4, 5, 6, 7].
    indices.drain(4..8);
    (vertices, indices, (0..=5).map(|f| 4 * f).collect())
}

/// The labelled edges, as `(a, b, hole)`.
fn labels(edges: &[CompactEdge]) -> Vec<(u16, u16, u8)> {
    edges
        .iter()
        .filter(|e| e.hole != NO_HOLE)
        .map(|e| (e.a, e.b, e.hole))
        .collect()
}

#[test]
fn an_open_box_has_its_rim_labelled_as_one_hole() {
    let (vertices, indices, offsets) = open_box();
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let b = bake(&mesh);
    assert_eq!(
        labels(&b.edges),
        [(4, 5, 0), (4, 7, 0), (5, 6, 0), (6, 7, 0)]
    );
    assert!(BakedMesh::new(mesh, &b.planes, &b.edges).is_ok());
}

#[test]
fn an_inside_out_box_and_a_closed_one_have_no_holes_labelled() {
    let (vertices, mut indices, offsets) = open_box();
    for face in indices.chunks_mut(4) {
        face.reverse();
    }
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    assert_eq!(labels(&bake(&mesh).edges), []);
    let (vertices, indices, offsets) = crate::render::two_squares::cube();
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    assert_eq!(labels(&bake(&mesh).edges), []);
}

#[test]
fn hole_labels_on_some_boundary_edges_or_off_them_are_refused() {
    let (vertices, indices, offsets) = open_box();
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let b = bake(&mesh);
    let rim = b.edges.iter().position(|e| e.hole == 0).unwrap();
    let inner = b.edges.iter().position(|e| e.hole == NO_HOLE).unwrap();
    for (edge, hole) in [(rim, NO_HOLE), (rim, MAX_HOLES as u8), (inner, 0)] {
        let mut edges = b.edges.clone();
        edges[edge].hole = hole;
        assert_eq!(
            BakedMesh::new(mesh, &b.planes, &edges).unwrap_err(),
            Error::BadEdgeList {
                edge: if edge == rim && hole == NO_HOLE {
                    // The first rim edge decides that labels are on.
                    b.edges
                        .iter()
                        .skip(rim + 1)
                        .position(|e| e.hole == 0)
                        .unwrap()
                        + rim
                        + 1
                } else {
                    edge
                },
                problem: crate::EdgeProblem::HoleLabel
            },
            "edge {edge} labelled {hole}"
        );
    }
}

/// [`MonoPalette`](crate::render::MonoPalette) without its word form: the faces'
/// pixels asked one by one; `every_other` keeps the word form for even faces.
struct PixelByPixel {
    mono: crate::render::MonoPalette,
    every_other: bool,
}

impl Palette for PixelByPixel {
    type Color = BinaryColor;
    fn line(&self) -> BinaryColor {
        self.mono.line()
    }
    fn face(&self, face: u16, shade: u8, x: u16, y: u16) -> Option<BinaryColor> {
        self.mono.face(face, shade, x, y)
    }
    fn face_word(
        &self,
        face: u16,
        shade: u8,
        x0: u16,
        y: u16,
    ) -> Option<(u32, BinaryColor, BinaryColor)> {
        (self.every_other && face % 2 == 0)
            .then(|| self.mono.face_word(face, shade, x0, y))
            .flatten()
    }
}

/// A square pyramid seen from the side, so that its four faces have four shades.
const PYRAMID: [[f32; 3]; 5] = [
    [-1., -1., 0.],
    [1., -1., 0.],
    [1., 1., 0.],
    [-1., 1., 0.],
    [0., 0., 1.2],
];
const SIDES: [u32; 12] = [0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4];
const SIDE_OFFSETS: [u32; 5] = [0, 3, 6, 9, 12];

/// Draws `baked` in `mode` with `palette` into `sink` (room for 8 facets and 8
/// lines, buffers for a 70 x 64 frame).
fn draw_frame<P: Palette<Color = BinaryColor>, K: SpanSink<Color = BinaryColor>>(
    baked: &BakedMesh<'_>,
    camera: &Camera,
    mode: DrawMode,
    palette: &P,
    sink: &mut K,
) -> Stats
where
    K::Error: core::fmt::Debug,
{
    let faces = baked.mesh().face_count();
    let mut buffers = Buffers::new(
        baked.mesh().vertices().len(),
        faces,
        baked.edges().len(),
        70,
        64,
    );
    FastRenderer::<U4, 8, 8>::new()
        .render(
            baked,
            camera,
            &settings(mode),
            &mut buffers.workspace(),
            palette,
            sink,
            &mut (),
        )
        .unwrap()
}

#[test]
fn surfaces_written_a_word_at_a_time_are_the_pixels_asked_one_by_one() {
    let mesh = Mesh::new(&PYRAMID, &SIDES, &SIDE_OFFSETS).unwrap();
    let b = bake(&mesh);
    let baked = BakedMesh::new(mesh, &b.planes, &b.edges).unwrap();
    let camera = Camera::new(
        [1.5, -2.5, 3.],
        [0., 0., 0.3],
        [0., 0., 1.],
        Projection::Perspective { fov_y_deg: 40.0 },
        0.1,
        20.0,
    )
    .unwrap();
    let mono = crate::render::MonoPalette::default();
    let one_by_one = PixelByPixel {
        mono,
        every_other: false,
    };
    let mixed = PixelByPixel {
        mono,
        every_other: true,
    };
    let solid = SolidPalette {
        line: BinaryColor::On,
        face: Some(BinaryColor::On),
    };
    type Fb = PackedFramebuffer<70, 64, { packed_len(70, 64) }>;
    let on = |fb: &Fb| {
        (0..64)
            .flat_map(|y| (0..70).map(move |x| (x, y)))
            .filter(|&(x, y)| fb.pixel(x, y))
            .count()
    };
    for mode in [DrawMode::Surfaces, DrawMode::SurfacesDashed] {
        let (mut words, mut pixels, mut half, mut full) =
            (Fb::new(), Fb::new(), Fb::new(), Fb::new());
        let stats = draw_frame(&baked, &camera, mode, &mono, &mut words);
        draw_frame(&baked, &camera, mode, &one_by_one, &mut pixels);
        draw_frame(&baked, &camera, mode, &mixed, &mut half);
        draw_frame(&baked, &camera, mode, &solid, &mut full);
        assert_eq!(stats.faces_drawn, 4, "{mode:?}");
        // The faces are dithered: fewer pixels on than with every face solid.
        assert!(on(&words) > 100 && on(&full) > on(&words) + 100, "{mode:?}");
        assert_eq!(words, pixels, "{mode:?}: word form against pixel by pixel");
        assert_eq!(words, half, "{mode:?}: word form for every other face");
        // Each pixel drawn once (MockDisplay fails on a pixel drawn twice).
        let mut display = MockDisplay::<BinaryColor>::new();
        draw_frame(
            &baked,
            &camera,
            mode,
            &mixed,
            &mut FillSolid::new(&mut display).unwrap(),
        );
    }
}

#[test]
fn the_mono_palette_word_is_its_pixels() {
    let mono = crate::render::MonoPalette::default();
    for shade in [0u8, 31, 32, 100, 200, 254, 255] {
        for y in 0..8u16 {
            for x0 in 0..40u16 {
                let (word, a, b) = mono.face_word(3, shade, x0, y).unwrap();
                for k in 0..32u16 {
                    let want = mono.face(3, shade, x0 + k, y).unwrap();
                    let got = if word >> k & 1 == 1 { a } else { b };
                    assert_eq!(got, want, "shade {shade} row {y} x0 {x0} bit {k}");
                }
            }
        }
    }
}
