//! The scene's own rules: capacities named, errors instead of frames, and
//! feature edges classified per instance.

extern crate std;

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::BinaryColor;

use super::{Pose, SceneDrawing};
use crate::{Camera, Capacity, Drawing, Error, FrameRows, Mesh, Projection};

/// A unit square in the z = 0 plane, facing +z: open, four boundary edges.
const SQUARE: [[f32; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];

fn square() -> Mesh<'static> {
    Mesh::new(&SQUARE, &[0, 1, 2, 3], &[0, 4]).unwrap()
}

fn camera() -> Camera {
    let fov = Projection::Perspective { fov_y_deg: 60.0 };
    Camera::new(
        [1.0, 0.5, 3.0],
        [1.0, 0.5, 0.0],
        [0.0, 1.0, 0.0],
        fov,
        0.1,
        100.0,
    )
    .unwrap()
}

fn short(what: Capacity, needed: usize, capacity: usize) -> Error {
    Error::CapacityExceeded {
        what,
        needed,
        capacity,
    }
}

#[test]
fn add_names_the_parameter_that_is_short_and_keeps_the_scene() {
    let mut baked = Drawing::<4, 1, 4>::new();
    baked.bake(square()).unwrap();
    let one = baked.baked().unwrap();
    // Two squares: 8 vertices, 2 faces, 8 edges, 8 corners + 2 faces + 1 = 11.
    let at = Pose::IDENTITY;
    let mut n = SceneDrawing::<1, 8, 2, 8, 11>::new();
    assert_eq!(n.add(one, at), Ok(0));
    assert_eq!(n.add(one, at), Err(short(Capacity::Instances, 2, 1)));
    assert_eq!(n.len(), 1);
    let mut v = SceneDrawing::<2, 7, 2, 8, 11>::new();
    v.add(one, at).unwrap();
    assert_eq!(v.add(one, at), Err(short(Capacity::Vertices, 8, 7)));
    let mut c = SceneDrawing::<2, 8, 2, 8, 10>::new();
    c.add(one, at).unwrap();
    assert_eq!(c.add(one, at), Err(short(Capacity::SceneCorners, 11, 10)));
    assert_eq!(c.len(), 1);
    let mut display = MockDisplay::<BinaryColor>::new();
    let stats = c.draw(&camera(), &mut FrameRows::<64, 64>::new(), &mut display);
    assert_eq!(stats.map(|s| s.feature_edges), Ok(4));
}

#[test]
fn an_empty_scene_or_a_pose_out_of_range_draws_no_frame() {
    let mut baked = Drawing::<4, 1, 4>::new();
    baked.bake(square()).unwrap();
    let mut scene = SceneDrawing::<2, 8, 2, 8, 11>::new();
    let mut rows = FrameRows::<64, 64>::new();
    let mut display = MockDisplay::<BinaryColor>::new();
    let drawn = scene.draw(&camera(), &mut rows, &mut display);
    assert_eq!(drawn.err(), Some(Error::NothingBaked));
    scene.add(baked.baked().unwrap(), Pose::IDENTITY).unwrap();
    scene.add(baked.baked().unwrap(), Pose::IDENTITY).unwrap();
    let drawn = scene.draw(&camera(), &mut rows, &mut display);
    assert!(drawn.is_ok());
    *scene.pose_mut(1).unwrap() = Pose::from_degrees([f32::NAN, 0.0, 0.0], [1.0, 0.0, 0.0]);
    let drawn = scene.draw(&camera(), &mut rows, &mut display);
    // Instance 1's first vertex is the union's vertex 4.
    assert_eq!(drawn.err(), Some(Error::NonFiniteVertex { vertex: 4 }));
    assert!(scene.pose_mut(2).is_none());
}

#[test]
fn a_crease_never_joins_two_instances_even_where_their_vertices_coincide() {
    // Two squares side by side share an edge bit for bit. Baked as one mesh the
    // shared edge welds and lies between coplanar faces: no line. As two
    // instances each square keeps its four boundary edges.
    let both: [[f32; 3]; 8] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    let union = Mesh::new(&both, &[0, 1, 2, 3, 4, 5, 6, 7], &[0, 4, 8]).unwrap();
    let mut welded = Drawing::<8, 2, 8>::new();
    welded.bake(union).unwrap();
    let mut rows = FrameRows::<64, 64>::new();
    let mut display = MockDisplay::<BinaryColor>::new();
    let one = welded.draw(&camera(), &mut rows, &mut display).unwrap();
    assert_eq!(one.feature_edges, 6);

    let mut baked = Drawing::<4, 1, 4>::new();
    baked.bake(square()).unwrap();
    let mut scene = SceneDrawing::<2, 8, 2, 8, 11>::new();
    scene.add(baked.baked().unwrap(), Pose::IDENTITY).unwrap();
    let beside = Pose::translation([1.0, 0.0, 0.0]);
    scene.add(baked.baked().unwrap(), beside).unwrap();
    let mut display = MockDisplay::<BinaryColor>::new();
    let two = scene.draw(&camera(), &mut rows, &mut display).unwrap();
    assert_eq!(two.feature_edges, 8);
    // The shared edge is drawn: the column x = 1 in world lies at the frame's
    // centre column, lit between the squares' top and bottom.
    let lit = |d: &MockDisplay<BinaryColor>, x: i32, y: i32| {
        d.get_pixel(embedded_graphics::prelude::Point::new(x, y)) == Some(BinaryColor::On)
    };
    let middle_rows = 24..40;
    assert!(middle_rows
        .clone()
        .all(|y| lit(&display, 32, y) || lit(&display, 31, y)));
}
