//! A face that is not planar in the Z-buffer engine: depth from its fan triangles.

extern crate std;
use std::vec;
use std::vec::Vec;

use fixed::types::extra::U4;

use crate::camera::Camera;
use crate::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use crate::render::two_squares::{Frame32, Ids};
use crate::render::{
    storage_rows, Cull, DrawMode, MonoPalette, ProjectedVertex, Settings, Workspace,
    ZBufferRenderer,
};
use crate::{Dashes, Pattern, Projection};

/// The vertices of [`twisted_quad_and_wall`]'s two faces (0..4 and 4..8).
const QUAD_AND_WALL: [[f32; 3]; 8] = [
    [-1.5, -1.5, 0.0],
    [1.5, -1.5, 0.0],
    [1.5, 1.5, 0.0],
    [-1.5, 1.5, 1.0],
    [-1.9, 0.5, 0.5],
    [-0.5, 0.5, 0.5],
    [-0.5, 1.9, 0.5],
    [-1.9, 1.9, 0.5],
];

/// Face 0, a quad twisted about its diagonal v0-v2: fan triangle (v0, v1, v2) lies in
/// z = 0, (v0, v2, v3) rises to z = 1 at v3, in the plane z = (y - x) / 3. Face 1, a
/// square wall at z = 0.5 over the corner v3. Seen from +z (orthographic, 8 px per
/// unit, screen x = 8 (x + 2), y = 8 (2 - y)); the wall is a band of 4 rows of 16 px.
fn twisted_quad_and_wall(band: u16) -> Vec<u16> {
    twisted_quad_and_wall_kept(band, None)
}

/// The same, with the faces' planarity kept in `planar` ([`Mesh::with_planar_faces`]).
fn twisted_quad_and_wall_kept(band: u16, planar: Option<&[u32]>) -> Vec<u16> {
    let v = QUAD_AND_WALL;
    let (idx, off) = ((0..8).collect::<Vec<u32>>(), [0, 4, 8]);
    let mut mesh = Mesh::new(&v, &idx, &off).unwrap();
    if let Some(bits) = planar {
        mesh = mesh.with_planar_faces(bits).unwrap();
    }
    let mut weld = vec![0u32; v.len()];
    let mut scratch = vec![HalfEdgeRecord::default(); idx.len()];
    let mut store = vec![MeshEdge::default(); idx.len()];
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
    let settings = Settings {
        mode: DrawMode::Surfaces,
        cull: Cull::Off,
        pattern: Pattern::PAPER,
        dashes: Dashes::Screen,
        lines: crate::render::LineVisibility::ByPixel,
    };
    let stored = usize::from(storage_rows(band, 32));
    let mut vertices = vec![ProjectedVertex::default(); v.len()];
    let (mut drawn, mut features) = (vec![0u32; 1], vec![0u32; 1]);
    let (mut depth, mut ids) = (vec![0u32; 32 * stored], vec![0u16; 32 * stored]);
    let mut lines = vec![0u32; 2 * usize::from(band)];
    let mut ws = Workspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        depth: &mut depth,
        ids: &mut ids,
        lines: &mut lines,
    };
    let mut probe = Ids(vec![0; 32 * 32]);
    ZBufferRenderer::<U4, 16, 16>::new()
        .render(
            &mesh,
            &adj,
            &camera,
            &settings,
            &mut ws,
            &MonoPalette::default(),
            &mut Frame32::new(),
            &mut probe,
        )
        .unwrap();
    probe.0
}

/// Where the quad's raised fan triangle passes in front of the wall (where z = (y - x)
/// / 3 is 0.5 or more, equal depth going to the quad, the lower face), the quad
/// shows. Its single
/// plane (its first fan triangle's, z = 0, extended) put the wall in front of all of
/// it. Pixels (i, j) with centre x = (i + 0.5) / 8 - 2, y = 2 - (j + 0.5) / 8: the
/// wall covers 1 <= i, j <= 11, the quad i, j >= 4, and the quad is nearer where
/// i + j <= 19. Columns and rows 1..=11 (`#` the quad, `w` the wall):
///
/// ```text
/// w w w w w w w w w w w
/// w w w w w w w w w w w
/// w w w w w w w w w w w
/// w w w # # # # # # # #
/// w w w # # # # # # # #
/// w w w # # # # # # # #
/// w w w # # # # # # # #
/// w w w # # # # # # # #
/// w w w # # # # # # # w
/// w w w # # # # # # w w
/// w w w # # # # # w w w
/// ```
#[test]
fn a_twisted_quad_in_front_of_a_wall_showed_the_wall_through_its_raised_half() {
    for band in [32, 5] {
        let ids = twisted_quad_and_wall(band);
        let at = |i: usize, j: usize| ids[j * 32 + i];
        let mut quad = 0;
        for j in 1..=11 {
            for i in 1..=11 {
                let expect = if i >= 4 && j >= 4 && i + j <= 19 {
                    1
                } else {
                    2
                };
                assert_eq!(at(i, j), expect, "pixel ({i}, {j}), band {band}");
                quad += usize::from(expect == 1);
            }
        }
        assert_eq!(quad, 58);
        // Elsewhere the quad shows whole, whichever fan triangle holds the pixel.
        for (i, j) in [(20, 20), (27, 4), (4, 27), (13, 13)] {
            assert_eq!(at(i, j), 1, "pixel ({i}, {j}), band {band}");
        }
    }
}

/// Planarity kept per mesh is read in place of the test in every frame: the bits
/// `planar_faces` makes (the quad not planar, the wall planar) draw the same frame as
/// none kept, and bits calling the quad planar give it its single plane, which puts
/// the wall in front of its raised half.
#[test]
fn planarity_kept_per_mesh_draws_the_same_frame_and_is_what_is_read() {
    let v = QUAD_AND_WALL;
    let (idx, off) = ((0..8).collect::<Vec<u32>>(), [0, 4, 8]);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let mut bits = [u32::MAX; 2];
    assert_eq!(crate::order::planar_faces(&mesh, &mut bits), Ok(1));
    assert_eq!(
        bits,
        [0b10, u32::MAX],
        "the wall planar, the quad not; word 2 untouched"
    );
    assert_eq!(
        crate::order::planar_faces(&mesh, &mut []),
        Err(crate::Error::CapacityExceeded {
            what: crate::Capacity::FaceBits,
            needed: 1,
            capacity: 0
        })
    );
    assert_eq!(
        mesh.with_planar_faces(&[]).map(|_| ()),
        Err(crate::Error::CapacityExceeded {
            what: crate::Capacity::FaceBits,
            needed: 1,
            capacity: 0
        })
    );
    for band in [32, 5] {
        let tested = twisted_quad_and_wall(band);
        assert_eq!(twisted_quad_and_wall_kept(band, Some(&bits[..1])), tested);
        let wrong = twisted_quad_and_wall_kept(band, Some(&[0b11]));
        // Pixel (5, 5): the raised half in front of the wall, or behind it as a plane.
        assert_eq!(tested[5 * 32 + 5], 1, "band {band}");
        assert_eq!(wrong[5 * 32 + 5], 2, "band {band}");
        let differ = wrong.iter().zip(&tested).filter(|(a, b)| a != b).count();
        assert!(differ >= 20, "band {band}: {differ} pixels differ");
    }
}

/// The stack a face that is not planar needs, per `POLY` (as `ZBufferRenderer` says).
#[test]
fn a_fan_triangle_set_up_for_the_rows_takes_about_150_bytes() {
    let size = size_of::<super::FanRow>();
    assert!((140..=160).contains(&size), "{size}");
}
