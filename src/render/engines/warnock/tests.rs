//! Area subdivision against the Z-buffer and against pictures drawn by hand.

extern crate std;
use std::string::String;
use std::vec;
use std::vec::Vec;

use fixed::types::extra::U4;

use super::*;
use crate::mesh::{HalfEdgeRecord, MeshEdge};
use crate::render::{storage_rows, Cull, DrawMode, MonoPalette, Workspace, ZBufferRenderer};
use crate::{Dashes, PackedFramebuffer, Pattern, Projection};

const W: usize = 96;
const H: usize = 64;

/// Keeps the whole frame's face ids.
struct Ids(Vec<u16>);

impl FrameProbe for Ids {
    fn row(&mut self, y: u16, ids: &[u16], _: &[u32], _: &[u32]) {
        let at = usize::from(y) * W;
        self.0[at..at + W].copy_from_slice(ids);
    }
}

type Lists = (Vec<[f32; 3]>, Vec<u32>, Vec<u32>);

/// Quads given by corners (x0, y0, x1, y1) at depth z, in face order.
fn quads(q: &[([f32; 4], f32)]) -> Lists {
    let mut v = Vec::new();
    for &([x0, y0, x1, y1], z) in q {
        v.extend([[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]]);
    }
    let n = q.len() as u32;
    (v, (0..4 * n).collect(), (0..=n).map(|f| 4 * f).collect())
}

fn camera(eye: [f32; 3]) -> Camera {
    let projection = Projection::Perspective { fov_y_deg: 40.0 };
    Camera::new(eye, [0.0; 3], [0.0, 1.0, 0.0], projection, 0.5, 20.0).unwrap()
}

fn adjacency<'s>(mesh: &Mesh<'_>, store: &'s mut [MeshEdge]) -> EdgeAdjacency<'s> {
    let mut weld = vec![0u32; mesh.vertices().len()];
    let mut scratch = vec![HalfEdgeRecord::default(); mesh.indices().len()];
    EdgeAdjacency::build(mesh, 30.0, &mut weld, &mut scratch, store).unwrap()
}

fn settings() -> Settings {
    Settings {
        mode: DrawMode::Surfaces,
        cull: Cull::Off,
        pattern: Pattern::PAPER,
        dashes: Dashes::Screen,
        lines: crate::render::LineVisibility::ByPixel,
    }
}

/// Sizes of the storage lent to area subdivision.
#[derive(Clone, Copy)]
struct Lend {
    areas: usize,
    lists: usize,
    faces: usize,
}

impl Lend {
    fn enough(faces: usize, band: usize) -> Self {
        let s = WarnockSizes::for_frame(faces, W as u16, H as u16, band as u16);
        Self {
            areas: s.areas,
            lists: s.lists,
            faces: s.faces,
        }
    }
}

/// Renders with area subdivision at 96x64 in bands of `band` rows.
fn warnock(mesh: &Mesh<'_>, eye: [f32; 3], band: usize, lend: Lend) -> Result<Vec<u16>, Error> {
    let mut store = vec![MeshEdge::default(); mesh.indices().len()];
    let adj = adjacency(mesh, &mut store);
    let mut fb = PackedFramebuffer::<W, H, { crate::packed_len(W, H) }>::new();
    let mut vertices = vec![ProjectedVertex::default(); mesh.vertices().len()];
    let mut drawn = vec![0u32; mesh.face_count().div_ceil(32)];
    let mut features = vec![0u32; adj.edges().len().div_ceil(32)];
    let stored = usize::from(storage_rows(band as u16, H as u16));
    let mut ids = vec![0u16; W * stored];
    let mut lines = vec![0u32; 2 * 3 * band];
    let mut ws = IdWorkspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        ids: &mut ids,
        lines: &mut lines,
    };
    let mut areas = vec![WarnockArea::default(); lend.areas];
    let mut lists = vec![0u16; lend.lists];
    let mut faces = vec![WarnockFace::default(); lend.faces];
    let storage = WarnockStorage {
        areas: &mut areas,
        lists: &mut lists,
        faces: &mut faces,
    };
    let mut probe = Ids(vec![0; W * H]);
    WarnockRenderer::<U4, 16>::new().render(
        mesh,
        &adj,
        &camera(eye),
        &settings(),
        &mut ws,
        storage,
        &MonoPalette::default(),
        &mut fb,
        &mut probe,
    )?;
    Ok(probe.0)
}

/// Renders with the Z-buffer (32-bit depth) at 96x64 in bands of `band` rows.
fn zbuffer(mesh: &Mesh<'_>, eye: [f32; 3], band: usize) -> Vec<u16> {
    let mut store = vec![MeshEdge::default(); mesh.indices().len()];
    let adj = adjacency(mesh, &mut store);
    let mut fb = PackedFramebuffer::<W, H, { crate::packed_len(W, H) }>::new();
    let mut vertices = vec![ProjectedVertex::default(); mesh.vertices().len()];
    let mut drawn = vec![0u32; mesh.face_count().div_ceil(32)];
    let mut features = vec![0u32; adj.edges().len().div_ceil(32)];
    let stored = usize::from(storage_rows(band as u16, H as u16));
    let (mut depth, mut ids) = (vec![0u32; W * stored], vec![0u16; W * stored]);
    let mut lines = vec![0u32; 2 * 3 * band];
    let mut ws = Workspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        depth: &mut depth,
        ids: &mut ids,
        lines: &mut lines,
    };
    let mut probe = Ids(vec![0; W * H]);
    ZBufferRenderer::<U4, 64, 16>::new()
        .render(
            mesh,
            &adj,
            &camera(eye),
            &settings(),
            &mut ws,
            &MonoPalette::default(),
            &mut fb,
            &mut probe,
        )
        .unwrap();
    probe.0
}

/// Every 4th column and row of the ids as characters: '.' none, 'a' face 0, ...
fn ascii(ids: &[u16]) -> String {
    let mut s = String::new();
    for y in (0..H).step_by(4) {
        for x in (0..W).step_by(4) {
            s.push(match ids[y * W + x] {
                0 => '.',
                id => char::from(b'a' + (id - 1) as u8),
            });
        }
        s.push('\n');
    }
    s
}

#[test]
fn the_nearer_of_two_overlapping_squares_shows() {
    // Face 0 far and large, face 1 nearer and overlapping its upper right.
    let (v, idx, off) = quads(&[([-1.5, -1.0, 0.5, 1.0], 0.0), ([-0.5, -0.2, 1.5, 1.4], 0.5)]);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let eye = [0.0, 0.0, 6.0];
    let ids = warnock(&mesh, eye, H, Lend::enough(2, H)).unwrap();
    let picture = ascii(&ids);
    std::println!("{picture}");
    let expected = "\
........................
........................
........................
..........bbbbbbbb......
..........bbbbbbbb......
.......aaabbbbbbbb......
.......aaabbbbbbbb......
.......aaabbbbbbbb......
.......aaabbbbbbbb......
.......aaaaaaa..........
.......aaaaaaa..........
.......aaaaaaa..........
........................
........................
........................
........................
";
    assert_eq!(picture, expected);
    assert_eq!(ids, zbuffer(&mesh, eye, H));
    // Swapped depths: face 0 in front.
    let (v, idx, off) = quads(&[([-1.5, -1.0, 0.5, 1.0], 0.5), ([-0.5, -0.2, 1.5, 1.4], 0.0)]);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let ids = warnock(&mesh, eye, H, Lend::enough(2, H)).unwrap();
    assert_eq!(ids, zbuffer(&mesh, eye, H));
    let count = |id: u16| ids.iter().filter(|&&i| i == id).count();
    assert!(count(1) > count(2) && count(2) > 0, "{}", ascii(&ids));
}

#[test]
fn coplanar_faces_tie_to_the_lower_index() {
    let (v, idx, off) = quads(&[([-1.0, -1.0, 0.5, 0.5], 0.0), ([-0.5, -0.5, 1.0, 1.0], 0.0)]);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    // Head on, both faces have the same nearness everywhere: the overlap must show
    // face 0 at every pixel, also where face 0's edges cross face 1 (decided pixel
    // by pixel, as no face wins a whole area there).
    for eye in [[0.0, 0.0, 6.0], [0.3, 0.2, 6.0]] {
        let ids = warnock(&mesh, eye, H, Lend::enough(2, H)).unwrap();
        assert_eq!(ids, zbuffer(&mesh, eye, H), "{}", ascii(&ids));
        // The overlap shows face 0: its centre pixel.
        let centre = ids[32 * W + 48];
        assert_eq!(centre, 1, "{}", ascii(&ids));
    }
    // Two coplanar dents (concave quads), head on: neither ever covers a whole area,
    // so every pixel of the overlap is decided alone, by the tie rule.
    let dart = |dx: f32, dy: f32| {
        [[-1.5, -1.0], [0.0, -0.3], [1.5, -1.0], [0.0, 1.2]].map(|[x, y]| [x + dx, y + dy, 0.0])
    };
    let v: Vec<[f32; 3]> = dart(0.0, 0.0).into_iter().chain(dart(0.4, 0.3)).collect();
    let (idx, off): (Vec<u32>, Vec<u32>) = ((0..8).collect(), vec![0, 4, 8]);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let eye = [0.0, 0.0, 6.0];
    let ids = warnock(&mesh, eye, H, Lend::enough(2, H)).unwrap();
    assert_eq!(ids, zbuffer(&mesh, eye, H), "{}", ascii(&ids));
    assert_eq!(ids[32 * W + 48], 1, "{}", ascii(&ids));
}

#[test]
fn one_face_over_the_whole_frame_is_one_area() {
    let (v, idx, off) = quads(&[([-20.0, -20.0, 20.0, 20.0], 0.0)]);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let ids = warnock(&mesh, [0.0, 0.0, 6.0], H, Lend::enough(1, H)).unwrap();
    assert!(ids.iter().all(|&id| id == 1));
    // Nothing to split: two list entries do (the band's list and the root's).
    let lend = Lend {
        lists: 2,
        ..Lend::enough(1, H)
    };
    let ids = warnock(&mesh, [0.0, 0.0, 6.0], H, lend).unwrap();
    assert!(ids.iter().all(|&id| id == 1));
}

#[test]
fn a_dented_face_over_the_corners_is_not_taken_as_covering_the_area() {
    // An arrow head (concave quad) in front of a square: its four corners reach
    // far out, its dent leaves the square visible in the middle.
    let v = vec![
        [-1.0f32, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [-2.0, -2.0, 0.5],
        [0.0, -0.1, 0.5],
        [2.0, -2.0, 0.5],
        [0.0, 2.0, 0.5],
    ];
    let idx = vec![0, 1, 2, 3, 4, 5, 6, 7];
    let off = vec![0, 4, 8];
    // The same arrow head so large that it covers the frame's corners: the whole
    // frame is an area whose corner centres it covers.
    let mut large = v.clone();
    for p in &mut large[4..] {
        p[0] *= 10.0;
        p[1] *= 10.0;
    }
    large[5] = [0.0, -0.1, 0.5];
    for v in [&v, &large] {
        let mesh = Mesh::new(v, &idx, &off).unwrap();
        for eye in [[0.0, 0.0, 6.0], [0.4, -0.3, 5.0]] {
            let ids = warnock(&mesh, eye, H, Lend::enough(2, H)).unwrap();
            assert_eq!(ids, zbuffer(&mesh, eye, H), "{}", ascii(&ids));
            assert!(ids.contains(&1) && ids.contains(&2), "{}", ascii(&ids));
        }
    }
}

#[test]
fn too_little_storage_is_an_error_naming_the_size_needed() {
    let (v, idx, off) = quads(&[([-1.5, -1.0, 0.5, 1.0], 0.0), ([-0.5, -0.2, 1.5, 1.4], 0.5)]);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let eye = [0.0, 0.0, 6.0];
    let enough = Lend::enough(2, H);
    let faces = Lend { faces: 1, ..enough };
    assert_eq!(
        warnock(&mesh, eye, H, faces),
        Err(Error::CapacityExceeded {
            what: Capacity::WarnockFaces,
            needed: 2,
            capacity: 1
        })
    );
    // 96 px wide: 7 levels, 22 stack entries, 2 x 9 list entries.
    assert_eq!((enough.areas, enough.lists), (22, 18));
    let areas = Lend {
        areas: 21,
        ..enough
    };
    assert_eq!(
        warnock(&mesh, eye, H, areas),
        Err(Error::CapacityExceeded {
            what: Capacity::WarnockAreas,
            needed: 22,
            capacity: 21
        })
    );
    let lists = Lend { lists: 3, ..enough };
    assert_eq!(
        warnock(&mesh, eye, H, lists),
        Err(Error::CapacityExceeded {
            what: Capacity::WarnockLists,
            needed: 18,
            capacity: 3
        })
    );
    // 8-row bands: 10 rows held, still 7 levels for the width.
    let band = Lend::enough(2, 8);
    assert_eq!((band.areas, band.lists), (22, 18));
    assert_eq!(
        warnock(&mesh, eye, 8, band).unwrap(),
        zbuffer(&mesh, eye, 8)
    );
}

#[test]
fn an_icosahedron_from_many_sides_is_the_z_buffer_frame() {
    let t = 1.618_034f32;
    let v = vec![
        [-1., t, 0.],
        [1., t, 0.],
        [-1., -t, 0.],
        [1., -t, 0.],
        [0., -1., t],
        [0., 1., t],
        [0., -1., -t],
        [0., 1., -t],
        [t, 0., -1.],
        [t, 0., 1.],
        [-t, 0., -1.],
        [-t, 0., 1.],
    ];
    let f: [[u32; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let idx: Vec<u32> = f.iter().flatten().copied().collect();
    let off: Vec<u32> = (0..=20).map(|i| 3 * i).collect();
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    // Culling off: back faces overlap front ones everywhere.
    for k in 0..12 {
        let a = k as f32 * 0.7;
        let eye = [
            4.0 * libm_sin(a),
            1.5 - 0.25 * k as f32,
            4.0 * libm_sin(a + core::f32::consts::FRAC_PI_2),
        ];
        for band in [H, 5] {
            let ids = warnock(&mesh, eye, band, Lend::enough(20, band)).unwrap();
            assert_eq!(ids, zbuffer(&mesh, eye, band), "view {k}, band {band}");
        }
    }
}

/// A sine good enough to place cameras.
fn libm_sin(x: f32) -> f32 {
    let mut x = x % core::f32::consts::TAU;
    if x > core::f32::consts::PI {
        x -= core::f32::consts::TAU;
    }
    x - x * x * x / 6.0 + x * x * x * x * x / 120.0 - x.powi(7) / 5040.0
}
