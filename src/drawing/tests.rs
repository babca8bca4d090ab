//! The short API's sizes: each short parameter named, and all of them at once.

use super::*;

/// A square: 4 vertices, 1 face, 4 edges (half its 4 corners: 2).
fn square() -> Mesh<'static> {
    const V: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    Mesh::new(&V, &[0, 1, 2, 3], &[0, 4]).unwrap()
}

fn short(what: Capacity, needed: usize, capacity: usize) -> Result<(), Error> {
    Err(Error::CapacityExceeded {
        what,
        needed,
        capacity,
    })
}

#[test]
fn bake_names_the_parameter_that_is_short() {
    let v = Drawing::<3, 1, 4>::new().bake(square());
    assert_eq!(v, short(Capacity::Vertices, 4, 3));
    let f = Drawing::<4, 0, 4>::new().bake(square());
    assert_eq!(f, short(Capacity::Faces, 1, 0));
    let e = Drawing::<4, 1, 3>::new().bake(square());
    assert_eq!(e, short(Capacity::Edges, 4, 3));
    assert_eq!(Drawing::<4, 1, 4>::new().bake(square()), Ok(()));
}

#[test]
fn bake_names_every_parameter_that_is_short_at_once() {
    let all = Drawing::<3, 0, 1>::new().bake(square()).unwrap_err();
    let mut expected = Shortfalls::new();
    expected.check(Capacity::Vertices, 4, 3);
    expected.check(Capacity::Faces, 1, 0);
    // Half the corners, a lower bound until the unique edges are counted.
    expected.check_at_least(Capacity::Edges, 2, 1, true);
    assert_eq!(all, Error::CapacitiesExceeded(expected));
    let rows = FrameRows::<8, 1>::new().fit(Viewport {
        width: 64,
        height: 64,
    });
    let mut expected = Shortfalls::new();
    expected.check(Capacity::RowWidth, 64, 8);
    expected.check(Capacity::Rows, 64, 1);
    expected.check(Capacity::LineMasks, 4, 1);
    assert_eq!(rows, Err(Error::CapacitiesExceeded(expected)));
}
