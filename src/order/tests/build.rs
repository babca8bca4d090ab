//! The build: cycles and interpenetration split, capacities and sizes.

use super::*;
use crate::Capacity;

#[test]
fn cyclic_sticks_are_split_and_rays_see_the_nearest_first() {
    let (vertices, indices, offsets) = sticks();
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let mut store = Store::new();
    let tree = BspTree::build(&mesh, store.storage()).unwrap();
    assert!(
        tree.fragment_count() > 3,
        "a cycle needs a split, got {} fragments",
        tree.fragment_count()
    );
    assert_eq!(tree.splits(), tree.fragment_count() - 3);
    let mut checked = 0;
    for eye in [
        [0.0, 0.0, 5.0],
        [0.3, -0.2, 3.0],
        [0.0, 0.0, -4.0],
        [2.0, 1.0, 1.5],
    ] {
        checked += check_grid(&tree, eye, -1.4, 1.4, 0.0, 40);
    }
    assert!(checked > 1000, "only {checked} rays met a fragment");
}

/// Corners of a box: vertex `x + 2y + 4z` at `(x ? hi : lo, ...)`.
fn box_corners(lo: [f32; 3], hi: [f32; 3]) -> [[f32; 3]; 8] {
    core::array::from_fn(|k| {
        [
            if k & 1 == 0 { lo[0] } else { hi[0] },
            if k & 2 == 0 { lo[1] } else { hi[1] },
            if k & 4 == 0 { lo[2] } else { hi[2] },
        ]
    })
}

/// Six quads, counter-clockwise from outside: -Z, +Z, -Y, +Y, -X, +X.
const BOX_QUADS: [[u32; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

#[test]
fn interpenetrating_boxes_are_cut_along_their_intersection() {
    // Box A = [0,2]^3; box B = [1,3] x [0.5,1.5]^2 pokes out through A's +X face.
    let mut vertices = [[0.0f32; 3]; 16];
    vertices[..8].copy_from_slice(&box_corners([0.0; 3], [2.0; 3]));
    vertices[8..].copy_from_slice(&box_corners([1.0, 0.5, 0.5], [3.0, 1.5, 1.5]));
    let mut indices = [0u32; 48];
    for (f, quad) in BOX_QUADS.iter().chain(BOX_QUADS.iter()).enumerate() {
        let shift = if f < 6 { 0 } else { 8 };
        for (k, &i) in quad.iter().enumerate() {
            indices[4 * f + k] = i + shift;
        }
    }
    let offsets: [u32; 13] = core::array::from_fn(|f| 4 * f as u32);
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let mut store = Store::new();
    let tree = BspTree::build(&mesh, store.storage()).unwrap();
    assert!(tree.fragment_count() > 12);

    // B's four side faces (-Z, +Z, -Y, +Y: ids 6..10) each meet A's +X face (x = 2)
    // along a segment of the line x = 2, c = 0.5 or 1.5: some plane through that
    // line cuts one of the two, leaving split points on it.
    let fragments = tree.fragments();
    let split_points = &fragments.vertices()[16..];
    for (axis, value) in [(2, 0.5f32), (2, 1.5), (1, 0.5), (1, 1.5)] {
        assert!(
            split_points
                .iter()
                .any(|p| (p[0] - 2.0).abs() < 1e-6 && (p[axis] - value).abs() < 1e-6),
            "no split point on the line x = 2, axis {axis} = {value}"
        );
    }
    let mut checked = 0;
    for eye in [
        [5.0, 1.3, 4.0],
        [4.0, -3.0, 1.2],
        [-3.0, 4.0, 5.0],
        [2.6, 1.1, 0.9],
    ] {
        // Rays through the plane z = 1 (inside both boxes) and across the boxes.
        checked += check_grid(&tree, eye, -0.5, 3.5, 1.0, 40);
    }
    assert!(checked > 2000, "only {checked} rays met a fragment");
}

#[test]
fn capacity_errors_name_the_need_and_never_panic() {
    let (vertices, indices, offsets) = sticks();
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let mut full = Store::new();
    let tree = BspTree::build(&mesh, full.storage()).unwrap();
    let (f, nodes, depth) = (tree.fragment_count(), tree.node_count(), tree.depth());
    let index_count = tree.fragments().indices().len();
    let vertex_count = tree.fragments().vertices().len();
    let peak = tree.work_peak();
    assert!(peak <= work_bound(f, index_count));
    assert!(vertex_count > 12);

    // Exact needs: the slices only written.
    let mut store = Store::new();
    let exceeded = |what, needed, capacity| {
        Err(Error::CapacityExceeded {
            what,
            needed,
            capacity,
        })
    };
    let mut s = store.storage();
    s.nodes = &mut core::mem::take(&mut s.nodes)[..nodes - 1];
    assert_eq!(
        BspTree::build(&mesh, s).map(|_| ()),
        exceeded(Capacity::BspNodes, nodes, nodes - 1)
    );
    let mut s = store.storage();
    s.offsets = &mut core::mem::take(&mut s.offsets)[..f];
    assert_eq!(
        BspTree::build(&mesh, s).map(|_| ()),
        exceeded(Capacity::FragmentOffsets, f + 1, f)
    );
    let mut s = store.storage();
    s.source = &mut core::mem::take(&mut s.source)[..2];
    assert_eq!(
        BspTree::build(&mesh, s).map(|_| ()),
        exceeded(Capacity::FragmentSources, f, 2)
    );
    let mut s = store.storage();
    s.indices = &mut core::mem::take(&mut s.indices)[..index_count - 1];
    assert_eq!(
        BspTree::build(&mesh, s).map(|_| ()),
        exceeded(Capacity::FragmentIndices, index_count, index_count - 1)
    );
    let mut s = store.storage();
    s.nodes = &mut [];
    s.indices = &mut [];
    assert_eq!(
        BspTree::build(&mesh, s).map(|_| ()),
        exceeded(Capacity::BspNodes, nodes, 0)
    );

    // Lower bounds: the slices the build reads back.
    for capacity in [0, 11, 12, vertex_count - 1] {
        let mut s = store.storage();
        s.vertices = &mut core::mem::take(&mut s.vertices)[..capacity];
        match BspTree::build(&mesh, s) {
            Err(Error::CapacityExceeded {
                what: Capacity::SplitVertices,
                needed,
                capacity: c,
            }) => {
                assert_eq!(c, capacity);
                assert!(needed > capacity && needed <= vertex_count, "{needed}");
            }
            other => panic!("vertices {capacity}: {other:?}"),
        }
    }
    for capacity in [0, 3, 20, peak - 1] {
        let mut s = store.storage();
        s.work = &mut core::mem::take(&mut s.work)[..capacity];
        match BspTree::build(&mesh, s) {
            Err(Error::CapacityExceeded {
                what: Capacity::OrderWork,
                needed,
                capacity: c,
            }) => {
                assert_eq!(c, capacity);
                assert!(needed > capacity && needed <= peak, "{needed}");
            }
            other => panic!("work {capacity}: {other:?}"),
        }
    }
    let mut s = store.storage();
    s.work = &mut core::mem::take(&mut s.work)[..peak];
    assert!(BspTree::build(&mesh, s).is_ok(), "work_peak words suffice");

    // The walk.
    let view = Viewpoint::Perspective {
        eye: [0.0, 0.0, 5.0],
    };
    let (mut stack, mut rank) = ([0u32; 64], [0u32; 64]);
    assert_eq!(
        tree.rank_front_to_back(&view, &mut stack[..depth - 1], &mut rank),
        exceeded(Capacity::BspStack, depth, depth - 1)
    );
    assert_eq!(
        tree.rank_front_to_back(&view, &mut stack, &mut rank[..f - 1]),
        exceeded(Capacity::FragmentRanks, f, f - 1)
    );
    assert_eq!(
        tree.rank_front_to_back(&view, &mut [], &mut []),
        exceeded(Capacity::BspStack, depth, 0)
    );
    assert!(tree
        .rank_front_to_back(&view, &mut stack[..depth], &mut rank[..f])
        .is_ok());
}

#[test]
fn sizes_for_mesh_suffice_for_the_splits_made() {
    let (vertices, indices, offsets) = sticks();
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let mut store = Store::new();
    let tree = BspTree::build(&mesh, store.storage()).unwrap();
    let sizes = BspStorage::sizes_for_mesh(12, 3, 12, tree.splits());
    assert!(tree.fragments().vertices().len() <= sizes.vertices);
    assert!(tree.fragments().indices().len() <= sizes.indices);
    assert!(tree.fragment_count() < sizes.offsets);
    assert!(tree.fragment_count() <= sizes.source);
    assert!(tree.node_count() <= sizes.nodes);
    assert!(tree.work_peak() <= sizes.work);
    let mut small = Store::new();
    let s = small.storage();
    let storage = BspStorage {
        vertices: &mut s.vertices[..sizes.vertices],
        indices: &mut s.indices[..sizes.indices],
        offsets: &mut s.offsets[..sizes.offsets],
        source: &mut s.source[..sizes.source],
        nodes: &mut s.nodes[..sizes.nodes],
        seams: &mut s.seams[..sizes.seams],
        work: &mut s.work[..sizes.work],
    };
    assert_eq!(storage.sizes(), sizes);
    assert!(BspTree::build(&mesh, storage).is_ok());
}
