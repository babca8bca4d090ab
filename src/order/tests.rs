//! Unit tests of the BSP tree (core only: no std here).

use super::*;
use crate::mesh::{Mesh, Viewpoint};
use crate::Error;

/// Storage big enough for the small scenes here.
struct Store {
    vertices: [[f32; 3]; 256],
    indices: [u32; 2048],
    offsets: [u32; 512],
    source: [u16; 512],
    nodes: [BspNode; 512],
    seams: [[u32; 2]; 256],
    work: [u32; 8192],
}

impl Store {
    fn new() -> Self {
        Self {
            vertices: [[0.0; 3]; 256],
            indices: [0; 2048],
            offsets: [0; 512],
            source: [0; 512],
            nodes: [BspNode::EMPTY; 512],
            seams: [[0; 2]; 256],
            work: [0; 8192],
        }
    }

    fn storage(&mut self) -> BspStorage<'_> {
        BspStorage {
            vertices: &mut self.vertices,
            indices: &mut self.indices,
            offsets: &mut self.offsets,
            source: &mut self.source,
            nodes: &mut self.nodes,
            seams: &mut self.seams,
            work: &mut self.work,
        }
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Where a ray meets a polygon (even-odd over its fan triangles, two-sided).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Hit {
    Miss,
    At(f64),
    /// Within 1e-9 (barycentric) of a fan triangle's edge: too close to call.
    Edge,
}

fn hit(mesh: &Mesh<'_>, f: usize, origin: [f64; 3], dir: [f64; 3]) -> Hit {
    let corners = mesh.face(f);
    let p = |i: u32| mesh.vertices()[i as usize].map(f64::from);
    let p0 = p(corners[0]);
    let (mut inside, mut depth) = (false, 0.0);
    for pair in corners[1..].windows(2) {
        let (e1, e2) = (sub(p(pair[0]), p0), sub(p(pair[1]), p0));
        let h = cross(dir, e2);
        let a = dot3(e1, h);
        if a.abs() < 1e-14 {
            continue;
        }
        let s = sub(origin, p0);
        let u = dot3(s, h) / a;
        let q = cross(s, e1);
        let v = dot3(dir, q) / a;
        let t = dot3(e2, q) / a;
        let eps = 1e-9;
        if [u, v, 1.0 - u - v].iter().any(|c| c.abs() <= eps) && u > -eps && v > -eps {
            return Hit::Edge;
        }
        if u > 0.0 && v > 0.0 && u + v < 1.0 && t > 0.0 {
            inside = !inside;
            depth = t;
        }
    }
    if inside {
        Hit::At(depth)
    } else {
        Hit::Miss
    }
}

/// Outcome of one ray: `Ok(true)` checked, `Ok(false)` skipped (edge or a tie
/// within 1e-9), `Err(..)` the ray property fails.
fn ray_ok(
    tree: &BspTree<'_>,
    rank: &[u32],
    origin: [f64; 3],
    dir: [f64; 3],
) -> Result<bool, (usize, usize)> {
    let mesh = tree.fragments();
    let mut nearest: Option<(f64, usize)> = None;
    let mut first: Option<(u32, f64, usize)> = None;
    for (f, &r) in rank.iter().enumerate().take(tree.fragment_count()) {
        match hit(&mesh, f, origin, dir) {
            Hit::Miss => {}
            Hit::Edge => return Ok(false),
            Hit::At(t) => {
                if nearest.is_none_or(|(tn, _)| t < tn) {
                    nearest = Some((t, f));
                }
                if first.is_none_or(|(best, _, _)| r < best) {
                    first = Some((r, t, f));
                }
            }
        }
    }
    match (nearest, first) {
        (Some((tn, fnear)), Some((_, tf, ffirst))) if fnear != ffirst => {
            if (tf - tn).abs() <= 1e-9 * (1.0 + tn) {
                Ok(false)
            } else {
                Err((fnear, ffirst))
            }
        }
        (Some(_), _) => Ok(true),
        _ => Ok(false),
    }
}

/// Ranks for `view` and checks that they are a permutation.
fn ranks<'r>(tree: &BspTree<'_>, view: &Viewpoint, rank: &'r mut [u32]) -> &'r [u32] {
    let mut stack = [0u32; 512];
    rank.fill(u32::MAX);
    tree.rank_front_to_back(view, &mut stack, rank).unwrap();
    let rank = &rank[..tree.fragment_count()];
    let mut seen = [false; 512];
    for &r in rank {
        assert!(!seen[r as usize], "rank {r} given twice");
        seen[r as usize] = true;
    }
    rank
}

/// Shoots an `n x n` grid of rays from `eye` (perspective) through points of the
/// square `[lo, hi]^2` at height `z`, and orthographic rays along `-dir` through
/// the same points. Returns how many rays were checked.
fn check_grid(tree: &BspTree<'_>, eye: [f64; 3], lo: f64, hi: f64, z: f64, n: usize) -> usize {
    let mut rank = [0u32; 512];
    let mut checked = 0;
    let ortho_dir = eye;
    let views = [
        Viewpoint::Perspective {
            eye: eye.map(|c| c as f32),
        },
        Viewpoint::Orthographic {
            direction_to_eye: ortho_dir.map(|c| c as f32),
        },
    ];
    for (v, view) in views.iter().enumerate() {
        let eye32 = eye.map(|c| f64::from(c as f32));
        let rank = ranks(tree, view, &mut rank);
        for i in 0..n {
            for j in 0..n {
                // Irrational-ish offsets keep the rays off the scene's edges.
                let x = lo + (hi - lo) * (i as f64 + 0.5123) / n as f64;
                let y = lo + (hi - lo) * (j as f64 + 0.4871) / n as f64;
                let target = [x, y, z];
                let (origin, dir) = if v == 0 {
                    (eye32, sub(target, eye32))
                } else {
                    let d = ortho_dir.map(|c| f64::from(c as f32));
                    (
                        [x + 100.0 * d[0], y + 100.0 * d[1], z + 100.0 * d[2]],
                        d.map(|c| -c),
                    )
                };
                match ray_ok(tree, rank, origin, dir) {
                    Ok(true) => checked += 1,
                    Ok(false) => {}
                    Err((near, first)) => panic!(
                        "view {view:?}, ray through {target:?}: fragment {near} is nearest but {first} ranks first"
                    ),
                }
            }
        }
    }
    checked
}

/// Three sticks (long planar quads) over the triangle of corners at 90, 210 and 330
/// degrees: stick `i` runs from corner `i` (height -0.3) to corner `i + 1` (height
/// +0.3), extended by 0.4 beyond both, so each stick lies over the next one where
/// they cross and under the previous one: a cycle no face order can draw.
fn sticks() -> ([[f32; 3]; 12], [u32; 12], [u32; 4]) {
    let corner = |i: usize| {
        let a = (90.0f64 + 120.0 * i as f64).to_radians();
        [cos(a), sin(a)]
    };
    let mut vertices = [[0.0f32; 3]; 12];
    for i in 0..3 {
        let (p, q) = (corner(i), corner((i + 1) % 3));
        let d = [q[0] - p[0], q[1] - p[1]];
        let len = (d[0] * d[0] + d[1] * d[1]).sqrt_approx();
        let (u, w) = ([d[0] / len, d[1] / len], 0.08);
        let perp = [-u[1], u[0]];
        let at = |s: f64, side: f64| {
            // s: distance along the stick from p; height linear in s.
            let z = -0.3 + 0.6 * s / len;
            [
                (p[0] + u[0] * s + perp[0] * side * w) as f32,
                (p[1] + u[1] * s + perp[1] * side * w) as f32,
                z as f32,
            ]
        };
        // Counter-clockwise seen from +z.
        vertices[4 * i] = at(-0.4, -1.0);
        vertices[4 * i + 1] = at(len + 0.4, -1.0);
        vertices[4 * i + 2] = at(len + 0.4, 1.0);
        vertices[4 * i + 3] = at(-0.4, 1.0);
    }
    let indices = core::array::from_fn(|k| k as u32);
    (vertices, indices, [0, 4, 8, 12])
}

/// Small no-std trigonometry for the test scenes (Taylor series, |a| <= 2 pi).
fn sin(a: f64) -> f64 {
    let pi = core::f64::consts::PI;
    let mut x = a % (2.0 * pi);
    if x > pi {
        x -= 2.0 * pi;
    } else if x < -pi {
        x += 2.0 * pi;
    }
    let (mut term, mut sum) = (x, x);
    for k in 1..20 {
        term *= -x * x / (f64::from(2 * k) * f64::from(2 * k + 1));
        sum += term;
    }
    sum
}

fn cos(a: f64) -> f64 {
    sin(a + core::f64::consts::FRAC_PI_2)
}

trait SqrtApprox {
    fn sqrt_approx(self) -> Self;
}

impl SqrtApprox for f64 {
    fn sqrt_approx(self) -> f64 {
        let mut x = if self > 1.0 { self } else { 1.0 };
        for _ in 0..60 {
            x = 0.5 * (x + self / x);
        }
        x
    }
}

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
    let exceeded = |needed, capacity| Err(Error::CapacityExceeded { needed, capacity });
    let mut s = store.storage();
    s.nodes = &mut core::mem::take(&mut s.nodes)[..nodes - 1];
    assert_eq!(
        BspTree::build(&mesh, s).map(|_| ()),
        exceeded(nodes, nodes - 1)
    );
    let mut s = store.storage();
    s.offsets = &mut core::mem::take(&mut s.offsets)[..f];
    assert_eq!(BspTree::build(&mesh, s).map(|_| ()), exceeded(f + 1, f));
    let mut s = store.storage();
    s.source = &mut core::mem::take(&mut s.source)[..2];
    assert_eq!(BspTree::build(&mesh, s).map(|_| ()), exceeded(f, 2));
    let mut s = store.storage();
    s.indices = &mut core::mem::take(&mut s.indices)[..index_count - 1];
    assert_eq!(
        BspTree::build(&mesh, s).map(|_| ()),
        exceeded(index_count, index_count - 1)
    );
    let mut s = store.storage();
    s.nodes = &mut [];
    s.indices = &mut [];
    assert_eq!(BspTree::build(&mesh, s).map(|_| ()), exceeded(nodes, 0));

    // Lower bounds: the slices the build reads back.
    for capacity in [0, 11, 12, vertex_count - 1] {
        let mut s = store.storage();
        s.vertices = &mut core::mem::take(&mut s.vertices)[..capacity];
        match BspTree::build(&mesh, s) {
            Err(Error::CapacityExceeded {
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
        exceeded(depth, depth - 1)
    );
    assert_eq!(
        tree.rank_front_to_back(&view, &mut stack, &mut rank[..f - 1]),
        exceeded(f, f - 1)
    );
    assert_eq!(
        tree.rank_front_to_back(&view, &mut [], &mut []),
        exceeded(depth, 0)
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
