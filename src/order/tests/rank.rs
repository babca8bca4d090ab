//! The walk: coplanar fragments rank by source face id.

use super::*;

/// Two squares in the plane z = 0 overlapping on [1,2] x [0,2]: `a` faces +z, `b`
/// faces -z; and a triangle above both (z = 1) so the tree has more than one node.
/// Returns the mesh with `a` at face id `a_id` (0 or 1), `b` at the other.
fn coplanar_scene(a_id: usize) -> ([[f32; 3]; 11], [u32; 11], [u32; 4]) {
    let vertices = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 2.0, 0.0],
        [0.0, 2.0, 0.0],
        [1.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [3.0, 2.0, 0.0],
        [1.0, 2.0, 0.0],
        [0.5, 0.5, 1.0],
        [2.5, 0.5, 1.0],
        [1.5, 1.8, 1.0],
    ];
    let a = [0, 1, 2, 3]; // counter-clockwise from +z
    let b = [4, 7, 6, 5]; // clockwise from +z: faces -z
    let (first, second) = if a_id == 0 { (a, b) } else { (b, a) };
    let mut indices = [0u32; 11];
    indices[..4].copy_from_slice(&first);
    indices[4..8].copy_from_slice(&second);
    indices[8..].copy_from_slice(&[8, 9, 10]);
    (vertices, indices, [0, 4, 8, 11])
}

#[test]
fn coplanar_faces_rank_by_source_id_whatever_the_input_order() {
    for a_id in [0, 1] {
        let (vertices, indices, offsets) = coplanar_scene(a_id);
        let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
        let mut store = Store::new();
        let tree = BspTree::build(&mesh, store.storage()).unwrap();
        for node in tree.nodes() {
            let sources = &tree.source()[node.fragments()];
            assert!(sources.windows(2).all(|w| w[0] < w[1]), "{sources:?}");
        }
        for eye in [[1.5f32, 1.0, 3.0], [1.5, 1.0, -3.0], [-2.0, 5.0, 0.5]] {
            for view in [
                Viewpoint::Perspective { eye },
                Viewpoint::Orthographic {
                    direction_to_eye: eye,
                },
            ] {
                let mut rank = [0u32; 512];
                let rank = ranks(&tree, &view, &mut rank);
                // Every fragment of face 0 ranks before every fragment of face 1: they
                // share one node, and face 0 wins the tie on the overlap.
                let of = |s: u16| {
                    (0..tree.fragment_count())
                        .filter(move |&f| tree.source()[f] == s)
                        .map(|f| rank[f])
                };
                let worst_0 = of(0).max().unwrap();
                let best_1 = of(1).min().unwrap();
                assert_eq!(best_1, worst_0 + 1, "a_id {a_id}, view {view:?}");
            }
        }
    }
}
