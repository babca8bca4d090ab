//! Edges, their kinds and feature edges on small known meshes.

use super::*;
use crate::mesh::features::cos_degrees;
use crate::EdgeProblem;

#[test]
fn quad_cube_has_twelve_creases_and_is_closed() {
    let indices = quad_indices();
    let mesh = Mesh::new(&CUBE, &indices, &QUAD_OFFSETS).unwrap();
    assert_eq!(mesh.face_count(), 6);
    assert_eq!(mesh.max_face_len(), 4);
    assert_eq!(mesh.face(1), &[4, 5, 7, 6]);
    assert_eq!(mesh.face(6), &[] as &[u32]);
    assert_eq!(mesh.face(usize::MAX), &[] as &[u32]);
    let normals = [
        [0.0, 0.0, -2.0],
        [0.0, 0.0, 2.0],
        [0.0, -2.0, 0.0],
        [0.0, 2.0, 0.0],
        [-2.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
    ];
    for (f, n) in normals.iter().enumerate() {
        assert_eq!(mesh.face_normal(f), *n, "face {f}");
    }
    assert_eq!(mesh.face_normal(6), [0.0; 3]);
    assert_eq!(mesh.face_centroid(1), [0.5, 0.5, 1.0]);
    assert_eq!(mesh.face_centroid(6), [0.0; 3]);

    let mut buffers = Buffers::new();
    let adjacency = buffers.build(&mesh, 30.0);
    let edges = adjacency.edges();
    assert_eq!(edges.len(), 12);
    assert_eq!(count_kind(edges, EdgeKind::Crease), 12);
    assert!(adjacency.is_closed());
    for e in edges {
        assert!(e.a < e.b);
        assert_eq!(e.face_count, 2);
        assert!(e.faces[0] < e.faces[1]);
        assert!(face_owns_edge(&mesh, e, e.faces[0] as usize));
        assert!(face_owns_edge(&mesh, e, e.faces[1] as usize));
    }
    // Sorted by (a, b) and unique.
    assert!(edges
        .windows(2)
        .all(|w| (w[0].a, w[0].b) < (w[1].a, w[1].b)));
    // At 90 degrees and beyond the cube's edges are no creases.
    assert_eq!(
        count_kind(buffers.build(&mesh, 90.0).edges(), EdgeKind::Smooth),
        12
    );
}

#[test]
fn triangulated_cube_has_smooth_diagonals() {
    let indices = triangle_indices();
    let mesh = Mesh::new(&CUBE, &indices, &TRI_OFFSETS).unwrap();
    assert_eq!(mesh.max_face_len(), 3);
    let mut buffers = Buffers::new();
    let adjacency = buffers.build(&mesh, 30.0);
    let edges = adjacency.edges();
    assert_eq!(edges.len(), 18);
    assert_eq!(count_kind(edges, EdgeKind::Crease), 12);
    assert_eq!(count_kind(edges, EdgeKind::Smooth), 6);
    assert!(adjacency.is_closed());
    for e in edges.iter().filter(|e| e.kind == EdgeKind::Smooth) {
        // A diagonal: both triangles come from one quad.
        assert_eq!(e.faces[0] / 2, e.faces[1] / 2);
        assert_eq!(e.faces[0] + 1, e.faces[1]);
    }
}

#[test]
fn silhouettes_of_the_triangulated_cube() {
    let indices = triangle_indices();
    let mesh = Mesh::new(&CUBE, &indices, &TRI_OFFSETS).unwrap();
    let mut buffers = Buffers::new();
    // 100 degrees: the cube's 90-degree edges are smooth, so only silhouettes draw.
    let edges = buffers.build(&mesh, 100.0).edges();
    assert_eq!(count_kind(edges, EdgeKind::Smooth), 18);

    let corner = Viewpoint::Perspective {
        eye: [5.0, 5.0, 5.0],
    };
    let corner_ortho = Viewpoint::Orthographic {
        direction_to_eye: [1.0, 1.0, 1.0],
    };
    let face_on = Viewpoint::Perspective {
        eye: [0.5, 0.5, 5.0],
    };
    let face_on_ortho = Viewpoint::Orthographic {
        direction_to_eye: [0.0, 0.0, 1.0],
    };
    // From a corner: the hexagon between the three near and the three far faces.
    assert_eq!(count_features(&mesh, edges, &corner), 6);
    assert_eq!(count_features(&mesh, edges, &corner_ortho), 6);
    // Face on: the square around the +Z face (the side faces are edge-on: not facing).
    for view in [face_on, face_on_ortho] {
        assert_eq!(count_features(&mesh, edges, &view), 4);
        for e in edges.iter().filter(|e| e.is_feature(&mesh, &view)) {
            assert_eq!(CUBE[e.a as usize][2], 1.0);
            assert_eq!(CUBE[e.b as usize][2], 1.0);
        }
    }
    // Triangles 2 and 3 make the +Z face.
    assert!(mesh.faces_viewpoint(2, &face_on));
    assert!(mesh.faces_viewpoint(3, &face_on_ortho));
    assert!(!mesh.faces_viewpoint(0, &face_on));
    assert!(!mesh.faces_viewpoint(8, &face_on_ortho));
    assert!(!mesh.faces_viewpoint(99, &face_on));

    // At 30 degrees the creases draw whatever the view.
    let edges = buffers.build(&mesh, 30.0).edges();
    assert_eq!(count_features(&mesh, edges, &corner), 12);
    assert_eq!(count_features(&mesh, edges, &face_on), 12);
}

#[test]
fn open_square_has_four_boundary_edges() {
    let vertices = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let indices = [0, 1, 2, 0, 2, 3];
    let mesh = Mesh::new(&vertices, &indices, &[0, 3, 6]).unwrap();
    let mut buffers = Buffers::new();
    let adjacency = buffers.build(&mesh, 30.0);
    let edges = adjacency.edges();
    assert_eq!(edges.len(), 5);
    assert_eq!(count_kind(edges, EdgeKind::Boundary), 4);
    assert_eq!(count_kind(edges, EdgeKind::Smooth), 1);
    assert!(!adjacency.is_closed());
    for e in edges.iter().filter(|e| e.kind == EdgeKind::Boundary) {
        assert_eq!(e.face_count, 1);
        assert_eq!(e.faces[0], e.faces[1]);
    }
    let diagonal = edges.iter().find(|e| e.kind == EdgeKind::Smooth).unwrap();
    assert_eq!((diagonal.a, diagonal.b, diagonal.faces), (0, 2, [0, 1]));
    let view = Viewpoint::Perspective {
        eye: [0.5, 0.5, 3.0],
    };
    assert_eq!(count_features(&mesh, edges, &view), 4);
}

#[test]
fn three_faces_on_one_edge_are_non_manifold() {
    let vertices = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [5.0, 5.0, 5.0],
        [6.0, 5.0, 5.0],
        [5.0, 6.0, 5.0],
    ];
    let indices = [0, 1, 2, 1, 0, 3, 0, 1, 4, 5, 6, 7];
    let mesh = Mesh::new(&vertices, &indices, &[0, 3, 6, 9, 12]).unwrap();
    let mut buffers = Buffers::new();
    let edges = buffers.build(&mesh, 30.0).edges();
    let shared = edges.iter().find(|e| (e.a, e.b) == (0, 1)).unwrap();
    assert_eq!(shared.kind, EdgeKind::NonManifold);
    assert_eq!(shared.face_count, 3);
    assert_eq!(shared.faces, [0, 1]);
    assert!(face_owns_edge(&mesh, shared, 2));
    assert!(!face_owns_edge(&mesh, shared, 3));
    assert!(!face_owns_edge(&mesh, shared, 4));
    assert!(shared.is_feature(
        &mesh,
        &Viewpoint::Orthographic {
            direction_to_eye: [0.0, 0.0, 1.0]
        }
    ));
    assert_eq!(count_kind(edges, EdgeKind::NonManifold), 1);
    assert_eq!(count_kind(edges, EdgeKind::Boundary), 9);
    let bogus = MeshEdge {
        a: 0,
        b: 99,
        ..MeshEdge::EMPTY
    };
    assert!(!face_owns_edge(&mesh, &bogus, 0));
}

#[test]
fn seams_of_duplicated_vertices_are_welded() {
    // The square of two triangles, the second with its own copies of 0 and 2.
    let vertices = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    let indices = [0, 1, 2, 4, 5, 3];
    let mesh = Mesh::new(&vertices, &indices, &[0, 3, 6]).unwrap();
    let mut buffers = Buffers::new();
    let edges = buffers.build(&mesh, 30.0).edges();
    assert_eq!(edges.len(), 5);
    assert_eq!(count_kind(edges, EdgeKind::Boundary), 4);
    let seam = edges.iter().find(|e| e.kind == EdgeKind::Smooth).unwrap();
    // Named by the lowest id at each position.
    assert_eq!((seam.a, seam.b, seam.face_count), (0, 2, 2));
    assert!(face_owns_edge(&mesh, seam, 1));
    // Sorted vertex ids by position, lowest first within a position.
    assert_eq!(buffers.weld[..6], [0, 4, 3, 1, 2, 5]);

    // A cube with four vertices of its own per face (24 vertices) is still closed.
    let mut split = [[0.0f32; 3]; 24];
    let mut indices = [0u32; 24];
    for (k, &v) in QUADS.iter().flatten().enumerate() {
        split[k] = CUBE[v as usize];
        indices[k] = k as u32;
    }
    let mesh = Mesh::new(&split, &indices, &QUAD_OFFSETS).unwrap();
    let adjacency = buffers.build(&mesh, 30.0);
    assert_eq!(adjacency.edges().len(), 12);
    assert_eq!(count_kind(adjacency.edges(), EdgeKind::Crease), 12);
    assert!(adjacency.is_closed());
}

#[test]
fn negative_zero_welds_with_zero() {
    // CONVENTIONS.md: -0.0 is read as 0.0 for welding (a mirrored model's seam
    // writes both), so the two triangles share their diagonal.
    let vertices = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [-0.0, 0.0, 0.0],
    ];
    let indices = [0, 1, 2, 4, 2, 3];
    let mesh = Mesh::new(&vertices, &indices, &[0, 3, 6]).unwrap();
    let mut buffers = Buffers::new();
    let edges = buffers.build(&mesh, 30.0).edges();
    assert_eq!(edges.len(), 5);
    assert_eq!(count_kind(edges, EdgeKind::Boundary), 4);
    // A face with 0 and -0 as two corners is still a valid face: only fewer than
    // three corners make one degenerate.
    assert!(Mesh::new(&vertices, &[0, 4, 1], &[0, 3]).is_ok());
}

#[test]
fn zero_normal_faces_make_inert_edges() {
    // Face 0 is three distinct collinear points: valid, but its normal is zero.
    let vertices = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let indices = [0, 1, 2, 1, 0, 3];
    let mesh = Mesh::new(&vertices, &indices, &[0, 3, 6]).unwrap();
    assert_eq!(mesh.face_normal(0), [0.0; 3]);
    let mut buffers = Buffers::new();
    let edges = buffers.build(&mesh, 30.0).edges();
    let shared = edges.iter().find(|e| (e.a, e.b) == (0, 1)).unwrap();
    assert_eq!(shared.kind, EdgeKind::Inert);
    assert_eq!(count_kind(edges, EdgeKind::Inert), 1);
    for view in [
        Viewpoint::Perspective {
            eye: [0.0, 0.0, 5.0],
        },
        Viewpoint::Orthographic {
            direction_to_eye: [0.0, 1.0, 0.0],
        },
    ] {
        assert!(!shared.is_feature(&mesh, &view));
        assert!(!mesh.faces_viewpoint(0, &view));
    }
}

#[test]
fn crease_angle_is_exact_around_the_threshold() {
    assert!((cos_degrees(0.0) - 1.0).abs() < 1e-7);
    assert!((cos_degrees(30.0) - 0.866_025_4).abs() < 1e-6);
    assert!((cos_degrees(60.0) - 0.5).abs() < 1e-6);
    assert!(cos_degrees(90.0).abs() < 1e-6);
    assert!((cos_degrees(120.0) + 0.5).abs() < 1e-6);
    assert!((cos_degrees(180.0) + 1.0).abs() < 1e-7);
    assert_eq!(cos_degrees(-10.0), cos_degrees(0.0));
    assert_eq!(cos_degrees(400.0), cos_degrees(180.0));

    // A hinge along the x axis whose faces' normals are 45 degrees apart...
    let vertices = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 1.0],
    ];
    let indices = [0, 1, 2, 1, 0, 3];
    let mesh = Mesh::new(&vertices, &indices, &[0, 3, 6]).unwrap();
    let mut buffers = Buffers::new();
    let kind = |buffers: &mut Buffers, deg: f32| {
        let edges = buffers.build(&mesh, deg).edges();
        edges.iter().find(|e| (e.a, e.b) == (0, 1)).unwrap().kind
    };
    assert_eq!(kind(&mut buffers, 30.0), EdgeKind::Crease);
    assert_eq!(kind(&mut buffers, 44.9), EdgeKind::Crease);
    assert_eq!(kind(&mut buffers, 45.1), EdgeKind::Smooth);
    assert_eq!(kind(&mut buffers, 0.0), EdgeKind::Crease);
    assert_eq!(kind(&mut buffers, 180.0), EdgeKind::Smooth);
    // ...and a fold of 135 degrees between the normals (obtuse: cos < 0).
    let vertices = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 1.0, -1.0],
    ];
    let mesh = Mesh::new(&vertices, &indices, &[0, 3, 6]).unwrap();
    let kind = |buffers: &mut Buffers, deg: f32| {
        let edges = buffers.build(&mesh, deg).edges();
        edges.iter().find(|e| (e.a, e.b) == (0, 1)).unwrap().kind
    };
    assert_eq!(kind(&mut buffers, 134.9), EdgeKind::Crease);
    assert_eq!(kind(&mut buffers, 135.1), EdgeKind::Smooth);
    // Coplanar faces are never creases, not even at 0 degrees.
    let vertices = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
    ];
    let mesh = Mesh::new(&vertices, &indices, &[0, 3, 6]).unwrap();
    let edges = buffers.build(&mesh, 0.0).edges();
    assert_eq!(count_kind(edges, EdgeKind::Smooth), 1);
}

#[test]
fn a_prebuilt_edge_list_is_taken_back_as_built() {
    let indices = triangle_indices();
    let mesh = Mesh::new(&CUBE, &indices, &TRI_OFFSETS).unwrap();
    let mut buffers = Buffers::new();
    let built = buffers.build(&mesh, 30.0).edges();
    // As firmware keeps it: a copy made elsewhere (a `static` in flash).
    let mut copy = [MeshEdge::EMPTY; 64];
    copy[..built.len()].copy_from_slice(built);
    let taken = EdgeAdjacency::from_edges(&mesh, &copy[..built.len()]).unwrap();
    assert_eq!(taken.edges(), built);
    assert!(taken.is_closed());
    // The empty list is a (useless) valid list.
    assert!(EdgeAdjacency::from_edges(&mesh, &[]).is_ok());
}

#[test]
fn a_prebuilt_edge_list_that_does_not_fit_names_its_first_bad_edge() {
    let indices = quad_indices();
    let mesh = Mesh::new(&CUBE, &indices, &QUAD_OFFSETS).unwrap();
    let mut buffers = Buffers::new();
    let built = buffers.build(&mesh, 30.0).edges();
    let n = built.len();
    let mut list = [MeshEdge::EMPTY; 64];
    let check = |list: &[MeshEdge], edge: usize, problem| check_on(&mesh, list, edge, problem);
    type Break = fn(&mut MeshEdge);
    let cases: [(usize, Break, EdgeProblem); 9] = [
        (3, |e| e.b = 8, EdgeProblem::EndOutOfRange),
        (3, |e| e.a = e.b, EdgeProblem::EndsNotAscending),
        (
            0,
            |e| core::mem::swap(&mut e.a, &mut e.b),
            EdgeProblem::EndsNotAscending,
        ),
        (5, |e| e.faces[1] = 6, EdgeProblem::FaceOutOfRange),
        (5, |e| e.face_count = 0, EdgeProblem::FacesDisagree),
        (5, |e| e.faces.reverse(), EdgeProblem::FacesDisagree),
        (
            5,
            |e| e.kind = EdgeKind::Boundary,
            EdgeProblem::FacesDisagree,
        ),
        (5, |e| e.face_count = 3, EdgeProblem::FacesDisagree),
        (5, |e| e.face_count = 1, EdgeProblem::FacesDisagree),
    ];
    for (k, break_it, problem) in cases {
        list[..n].copy_from_slice(built);
        break_it(&mut list[k]);
        check(&list[..n], k, problem);
    }
    // Out of order, and a repeated edge: the later one is named.
    list[..n].copy_from_slice(built);
    list.swap(6, 7);
    check(&list[..n], 7, EdgeProblem::NotSorted);
    list[..n].copy_from_slice(built);
    list[7] = list[6];
    check(&list[..n], 7, EdgeProblem::NotSorted);
    // A list for a bigger mesh: its first edge, (0, 1) of faces 0 and 2, names a
    // face this two-face mesh does not have.
    let small = Mesh::new(&CUBE[..4], &[0, 1, 3, 0, 3, 2], &[0, 3, 6]).unwrap();
    assert_eq!((built[0].a, built[0].b, built[0].faces), (0, 1, [0, 2]));
    check_on(&small, built, 0, EdgeProblem::FaceOutOfRange);
}

/// `list` is refused for `mesh` at `edge` for `problem`.
fn check_on(mesh: &Mesh<'_>, list: &[MeshEdge], edge: usize, problem: EdgeProblem) {
    assert_eq!(
        EdgeAdjacency::from_edges(mesh, list).map(|a| a.edges().len()),
        Err(Error::BadEdgeList { edge, problem }),
        "{problem:?}"
    );
}
