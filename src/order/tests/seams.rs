//! Split points: seams shared across nodes, pieces that tile a cut face.

use super::*;

#[test]
fn a_split_edge_gives_its_point_to_the_neighbour_across_it() {
    // A folded quad: triangle T0 (face 1) in z = 0 and T1 (face 2) tilted up, sharing
    // the diagonal (0,0,0)-(2,2,0); and a small panel C (face 0) in the plane x = 1.5,
    // in front of T1's plane. The root is T1 (no split); then C cuts T0, and its
    // plane crosses the diagonal at (1.5, 1.5, 0). T1 is in another node: only the
    // seam insertion can give it that point.
    let vertices = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 2.0, 0.0],
        [0.0, 2.0, 1.0],
        [1.5, 0.2, -0.2],
        [1.5, 1.0, -0.2],
        [1.5, 1.0, 0.3],
        [1.5, 0.2, 0.3],
    ];
    let indices = [4, 5, 6, 7, 0, 1, 2, 0, 2, 3];
    let offsets = [0, 4, 7, 10];
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let mut store = Store::new();
    let tree = BspTree::build(&mesh, store.storage()).unwrap();
    let fragments = tree.fragments();
    let p = [1.5f32, 1.5, 0.0];
    let has_p = |f: usize| {
        fragments
            .face(f)
            .iter()
            .any(|&i| fragments.vertices()[i as usize] == p)
    };
    let of = |s: u16| (0..tree.fragment_count()).filter(move |&f| tree.source()[f] == s);
    assert_eq!(of(2).count(), 1, "T1 is not cut");
    assert_eq!(of(1).count(), 2, "T0 is cut in two");
    assert!(of(1).all(has_p), "both halves of T0 hold the split point");
    let t1 = of(2).next().unwrap();
    assert!(
        has_p(t1),
        "T1 holds the split point: {:?}",
        fragments.face(t1)
    );
    // In order along the shared edge: T1 = (0, 0, 0), P, (2, 2, 0), (0, 2, 1).
    let corners: [[f32; 3]; 4] =
        core::array::from_fn(|k| fragments.vertices()[fragments.face(t1)[k] as usize]);
    assert_eq!(corners, [vertices[0], p, vertices[2], vertices[3]]);
}

#[test]
fn a_saddle_cut_four_times_is_tiled_by_its_pieces() {
    // A square near z = 0.5 (face 0, tilted so that the saddle's plane z = 0.5 cuts it
    // too and it wins the tie as the root) and a saddle quad (face 1) whose corners
    // alternate below and above it: the cut crosses the quad four times.
    let vertices = [
        [-1.0, -1.0, 0.45],
        [2.0, -1.0, 0.6],
        [2.0, 2.0, 0.6],
        [-1.0, 2.0, 0.45],
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 1.0],
    ];
    let indices = [0, 1, 2, 3, 4, 5, 6, 7];
    let offsets = [0, 4, 8];
    let mesh = Mesh::new(&vertices, &indices, &offsets).unwrap();
    let mut store = Store::new();
    let tree = BspTree::build(&mesh, store.storage()).unwrap();
    let fragments = tree.fragments();
    let newell = |corners: &[u32], v: &[[f32; 3]]| {
        let mut n = [0.0f64; 3];
        for k in 0..corners.len() {
            let a = v[corners[k] as usize].map(f64::from);
            let b = v[corners[(k + 1) % corners.len()] as usize].map(f64::from);
            let c = cross(a, b);
            n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
        }
        n
    };
    let whole = newell(mesh.face(1), mesh.vertices());
    let mut sum = [0.0f64; 3];
    let mut pieces = 0;
    for f in 0..tree.fragment_count() {
        if tree.source()[f] == 1 {
            pieces += 1;
            let n = newell(fragments.face(f), fragments.vertices());
            sum = [sum[0] + n[0], sum[1] + n[1], sum[2] + n[2]];
        }
    }
    assert_eq!(pieces, 3, "one front piece, two back pieces");
    for k in 0..3 {
        assert!((sum[k] - whole[k]).abs() < 1e-6, "{sum:?} != {whole:?}");
    }
    // Every edge between two split points (here a chord: they lie on different
    // sides of the saddle) has its opposite among the pieces.
    let saddle = || (0..tree.fragment_count()).filter(|&f| tree.source()[f] == 1);
    let edge = |f: usize, k: usize| {
        let c = fragments.face(f);
        (c[k], c[(k + 1) % c.len()])
    };
    for f in saddle() {
        for k in 0..fragments.face(f).len() {
            let (a, b) = edge(f, k);
            if a >= 8 && b >= 8 {
                let opposite =
                    saddle().any(|g| (0..fragments.face(g).len()).any(|j| edge(g, j) == (b, a)));
                assert!(opposite, "fragment {f}: chord {a}-{b} has no opposite");
            }
        }
    }
}
