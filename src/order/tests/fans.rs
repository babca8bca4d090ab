//! Planes and fans: non-planar and zero-normal faces.

use super::*;

#[test]
fn non_planar_and_zero_normal_faces_build_and_rank() {
    // A twisted quad (one corner lifted: not planar), a zero-normal face (f 1 2 1)
    // and a collinear triangle, over a flat square.
    let vertices = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.5],
        [0.0, 1.0, 0.0],
        [0.5, 0.5, 0.0],
        [2.0, 2.0, 2.0],
        [-1.0, -1.0, -0.2],
        [2.0, -1.0, -0.2],
        [2.0, 2.0, -0.2],
        [-1.0, 2.0, -0.2],
    ];
    let indices = [0, 1, 2, 3, 0, 1, 0, 0, 4, 5, 6, 7, 8, 9];
    let offsets = [0, 4, 7, 10, 14];
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let mut store = Store::new();
    let tree = BspTree::build(&mesh, store.storage()).unwrap();
    // The twisted quad enters as its fan triangles, cut only by other planes.
    assert!(tree.source().contains(&0));
    assert!(tree.fragments().face(0).len() >= 3);
    let mut rank = [0u32; 512];
    for eye in [[0.5f32, 0.3, 3.0], [0.5, 0.5, -3.0], [3.0, 0.1, 0.25]] {
        ranks(&tree, &Viewpoint::Perspective { eye }, &mut rank);
    }
    let checked = check_grid(&tree, [0.4, 0.3, 3.0], -1.0, 2.0, 0.0, 30);
    assert!(checked > 500);
}

#[test]
fn a_twisted_convex_quad_enters_as_its_fan_triangles() {
    // A twisted quad over a flat square: convex in its Newell plane, so it enters as
    // its fan triangles (v0, v1, v2) and (v0, v2, v3), the planes CONVENTIONS.md takes
    // its depth from.
    let vertices = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.5],
        [0.0, 1.0, 0.0],
        [-1.0, -1.0, -0.2],
        [2.0, -1.0, -0.2],
        [2.0, 2.0, -0.2],
        [-1.0, 2.0, -0.2],
    ];
    let indices = [0, 1, 2, 3, 4, 5, 6, 7];
    let offsets = [0, 4, 8];
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let mut store = Store::new();
    let tree = BspTree::build(&mesh, store.storage()).unwrap();
    assert_eq!(tree.fragment_count(), 3);
    assert_eq!(
        tree.splits(),
        1,
        "the second fan triangle counts as a split"
    );
    let mut fan: [&[u32]; 2] = [&[], &[]];
    let pieces = (0..3).filter(|&f| tree.source()[f] == 0);
    for (slot, f) in fan.iter_mut().zip(pieces) {
        *slot = tree.fragments().face(f);
    }
    fan.sort();
    assert_eq!(fan, [&[0, 1, 2][..], &[0, 2, 3][..]]);
}

#[test]
fn a_non_planar_face_that_is_not_convex_stays_whole() {
    // A dart (reflex corner at index 3) with its tip lifted: its fan triangles would
    // overlap, so it keeps its polygon (and its parity coverage) as one fragment.
    let vertices = [
        [0.0, 0.0, 0.0],
        [2.0, 1.0, 0.4],
        [0.0, 2.0, 0.0],
        [0.5, 1.0, 0.0],
        [-1.0, -1.0, -0.2],
        [3.0, -1.0, -0.2],
        [3.0, 3.0, -0.2],
        [-1.0, 3.0, -0.2],
    ];
    let indices = [0, 1, 2, 3, 4, 5, 6, 7];
    let offsets = [0, 4, 8];
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let mut store = Store::new();
    let tree = BspTree::build(&mesh, store.storage()).unwrap();
    assert_eq!(tree.fragment_count(), 2);
    assert_eq!(tree.splits(), 0);
    let f = (0..2).find(|&f| tree.source()[f] == 0).unwrap();
    assert_eq!(tree.fragments().face(f), &[0, 1, 2, 3]);
}

#[test]
fn a_face_through_a_twisted_quads_bulge_ranks_behind_it() {
    // Regression (suzanne's 5 far pixels): the twisted quad's fan surface is at
    // z = 0.425 .. 0.575 over the small square at z = 0.4, but its Newell plane
    // through the centroid is at z = 0.25 there. Ordered as that plane, the square
    // ranked in front of the quad, seen from above; its fan triangles order it right.
    let vertices = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 2.0, 1.0],
        [0.0, 2.0, 0.0],
        [0.85, 0.85, 0.4],
        [1.15, 0.85, 0.4],
        [1.15, 1.15, 0.4],
        [0.85, 1.15, 0.4],
    ];
    let indices = [0, 1, 2, 3, 4, 5, 6, 7];
    let offsets = [0, 4, 8];
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let mut store = Store::new();
    let tree = BspTree::build(&mesh, store.storage()).unwrap();
    let checked = check_grid(&tree, [1.1, 0.9, 3.0], 0.0, 2.0, 0.0, 40);
    assert!(checked > 2000, "{checked}");
}
