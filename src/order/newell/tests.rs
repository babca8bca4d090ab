//! Unit tests of Newell's depth sort (core only: no std here). Every order is
//! checked by rays in f64: along each ray, the nearest fragment it meets has the
//! lowest rank of those it meets (coplanar ones: the lower face index).

use super::*;
use crate::camera::{Camera, Projection};
use crate::mesh::Mesh;
use crate::Capacity;
use crate::Error;

const V: usize = 512;
const I: usize = 8192;
const F: usize = 1024;

/// Storage big enough for the small scenes here.
struct Store {
    vertices: [[f32; 3]; V],
    indices: [u32; I],
    offsets: [u32; F + 1],
    source: [u16; F],
    rank: [u32; F],
    seams: [[u32; 2]; V],
    boxes: [[f32; 6]; F],
    work: [u32; 3 * F],
}

impl Store {
    fn new() -> Self {
        Self {
            vertices: [[0.0; 3]; V],
            indices: [0; I],
            offsets: [0; F + 1],
            source: [0; F],
            rank: [0; F],
            seams: [[0; 2]; V],
            boxes: [[0.0; 6]; F],
            work: [0; 3 * F],
        }
    }

    fn storage(&mut self) -> NewellStorage<'_> {
        NewellStorage {
            vertices: &mut self.vertices,
            indices: &mut self.indices,
            offsets: &mut self.offsets,
            source: &mut self.source,
            rank: &mut self.rank,
            seams: &mut self.seams,
            boxes: &mut self.boxes,
            work: &mut self.work,
        }
    }
}

/// A small mesh built in fixed arrays.
struct Build {
    vertices: [[f32; 3]; 64],
    nv: usize,
    indices: [u32; 256],
    ni: usize,
    offsets: [u32; 64],
    nf: usize,
}

impl Build {
    fn new() -> Self {
        Self {
            vertices: [[0.0; 3]; 64],
            nv: 0,
            indices: [0; 256],
            ni: 0,
            offsets: [0; 64],
            nf: 0,
        }
    }

    fn vertex(&mut self, p: [f64; 3]) -> u32 {
        self.vertices[self.nv] = p.map(|c| c as f32);
        self.nv += 1;
        (self.nv - 1) as u32
    }

    fn face(&mut self, idx: &[u32]) {
        for &i in idx {
            self.indices[self.ni] = i;
            self.ni += 1;
        }
        self.nf += 1;
        self.offsets[self.nf] = self.ni as u32;
    }

    fn quad(&mut self, corners: [[f64; 3]; 4]) {
        let v = corners.map(|p| self.vertex(p));
        self.face(&v);
    }

    /// A box: centre, half sizes, rotation (rows), outward faces wound
    /// counter-clockwise.
    fn cuboid(&mut self, c: [f64; 3], h: [f64; 3], r: [[f64; 3]; 3]) {
        let base = self.nv as u32;
        for i in 0..8 {
            let local = [
                if i & 1 == 0 { -h[0] } else { h[0] },
                if i & 2 == 0 { -h[1] } else { h[1] },
                if i & 4 == 0 { -h[2] } else { h[2] },
            ];
            let p = core::array::from_fn(|k| c[k] + dot3(r[k], local));
            self.vertex(p);
        }
        for f in [
            [0, 4, 6, 2],
            [1, 3, 7, 5],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 2, 3, 1],
            [4, 5, 7, 6],
        ] {
            self.face(&f.map(|k| base + k));
        }
    }

    fn mesh(&self) -> Mesh<'_> {
        Mesh::new(
            &self.vertices[..self.nv],
            &self.indices[..self.ni],
            &self.offsets[..=self.nf],
        )
        .unwrap()
    }
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Product of rotations about x (cos, sin) then y (cos, sin).
fn rotation(x: (f64, f64), y: (f64, f64)) -> [[f64; 3]; 3] {
    let rx = [[1.0, 0.0, 0.0], [0.0, x.0, -x.1], [0.0, x.1, x.0]];
    let ry = [[y.0, 0.0, y.1], [0.0, 1.0, 0.0], [-y.1, 0.0, y.0]];
    core::array::from_fn(|i| core::array::from_fn(|j| (0..3).map(|k| ry[i][k] * rx[k][j]).sum()))
}

fn ortho() -> Camera {
    Camera::new(
        [0.0, 0.0, 10.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        Projection::Orthographic { half_height: 4.0 },
        0.1,
        100.0,
    )
    .unwrap()
}

fn perspective(eye: [f32; 3]) -> Camera {
    Camera::new(
        eye,
        [0.0; 3],
        [0.0, 1.0, 0.0],
        Projection::Perspective { fov_y_deg: 60.0 },
        0.1,
        100.0,
    )
    .unwrap()
}

enum Hit {
    Miss,
    At(f64),
    Edge,
}

/// Ray against a fragment: even-odd over its fan triangles, two-sided; `Edge` near
/// a fan triangle's edge.
fn hit(mesh: &Mesh<'_>, f: usize, origin: [f64; 3], dir: [f64; 3]) -> Hit {
    let c = mesh.face(f);
    let pos = |i: u32| mesh.vertices()[i as usize].map(f64::from);
    let p0 = pos(c[0]);
    let (mut inside, mut depth) = (false, 0.0);
    for w in c[1..].windows(2) {
        let (e1, e2) = (sub3(pos(w[0]), p0), sub3(pos(w[1]), p0));
        let h = cross3(dir, e2);
        let a = dot3(e1, h);
        if a.abs() < 1e-14 {
            continue;
        }
        let s = sub3(origin, p0);
        let u = dot3(s, h) / a;
        let q = cross3(s, e1);
        let v = dot3(dir, q) / a;
        let t = dot3(e2, q) / a;
        let eps = 1e-7;
        if t > 0.0 && u > -eps && v > -eps && u + v < 1.0 + eps {
            if u < eps || v < eps || u + v > 1.0 - eps {
                return Hit::Edge;
            }
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

/// Rays through a grid of points of the plane z = 0 (from the eye, or along -z):
/// the nearest fragment met ranks lowest; at equal depth (1e-9) the lower source
/// face must rank lower. Returns (rays that met 2 or more fragments, ties).
fn check_rays(order: &NewellOrder<'_>, eye: Option<[f64; 3]>) -> (usize, usize) {
    let mesh = order.fragments();
    let (mut deep, mut ties) = (0, 0);
    for gy in 0..61 {
        for gx in 0..61 {
            let target = [
                -3.0 + 0.1003 * f64::from(gx),
                -3.0 + 0.0997 * f64::from(gy),
                0.0,
            ];
            let (origin, dir) = match eye {
                Some(e) => (e, sub3(target, e)),
                None => ([target[0], target[1], 50.0], [0.0, 0.0, -1.0]),
            };
            let mut nearest: Option<(f64, usize)> = None;
            let mut first: Option<(u32, f64, usize)> = None;
            let mut hits = 0;
            let mut edge = false;
            for f in 0..order.fragment_count() {
                if order.rank()[f] as usize >= order.drawn() {
                    continue;
                }
                match hit(&mesh, f, origin, dir) {
                    Hit::Miss => {}
                    Hit::Edge => edge = true,
                    Hit::At(d) => {
                        hits += 1;
                        if nearest.is_none_or(|(n, _)| d < n) {
                            nearest = Some((d, f));
                        }
                        let r = order.rank()[f];
                        if first.is_none_or(|(best, _, _)| r < best) {
                            first = Some((r, d, f));
                        }
                    }
                }
            }
            if edge || hits < 2 {
                continue;
            }
            deep += 1;
            let ((dn, fnear), (_, df, ffirst)) = (nearest.unwrap(), first.unwrap());
            let tol = 1e-9 * dn.abs().max(1.0);
            assert!(
                df - dn <= tol,
                "ray to {target:?}: fragment {fnear} (face {}, rank {}, depth {dn}) is \
                 nearest, fragment {ffirst} (face {}, rank {}, depth {df}) ranks first",
                order.source()[fnear],
                order.rank()[fnear],
                order.source()[ffirst],
                order.rank()[ffirst],
            );
            // Every fragment at the nearest depth: the lowest face must rank first.
            let mut at_nearest = 0;
            let mut lowest = u16::MAX;
            for f in 0..order.fragment_count() {
                if order.rank()[f] as usize >= order.drawn() {
                    continue;
                }
                if let Hit::At(d) = hit(&mesh, f, origin, dir) {
                    if d - dn <= tol {
                        at_nearest += 1;
                        lowest = lowest.min(order.source()[f]);
                    }
                }
            }
            if at_nearest > 1 {
                ties += 1;
                assert_eq!(
                    order.source()[ffirst],
                    lowest,
                    "ray to {target:?}: a tie must go to the lower face"
                );
            }
        }
    }
    (deep, ties)
}

/// The ranks are a permutation, the sources in range, and the fragments begin with
/// the mesh's vertices.
fn check_shape(mesh: &Mesh<'_>, order: &NewellOrder<'_>) {
    let n = order.fragment_count();
    let mut seen = [false; F];
    for &r in order.rank() {
        assert!((r as usize) < n && !seen[r as usize], "not a permutation");
        seen[r as usize] = true;
    }
    assert!(order
        .source()
        .iter()
        .all(|&s| (s as usize) < mesh.face_count()));
    let v = mesh.vertices();
    assert_eq!(&order.fragments().vertices()[..v.len()], v);
}

/// Three sticks, each over the next seen from +z (the host's `cyclic_sticks`).
fn sticks() -> Build {
    let mut b = Build::new();
    let (s120, c120) = (0.866_025_403_784_438_6, -0.5);
    for (c, s) in [(1.0, 0.0), (c120, s120), (c120, -s120)] {
        let rot = |x: f64, y: f64| [c * x - s * y, s * x + c * y, -0.18 * x];
        b.quad([
            rot(-1.4, -0.55),
            rot(1.4, -0.55),
            rot(1.4, -0.2),
            rot(-1.4, -0.2),
        ]);
    }
    b
}

#[test]
fn cyclic_overlap_is_split_and_ranked() {
    let b = sticks();
    let mesh = b.mesh();
    let mut store = Store::new();
    for (camera, eye) in [
        (ortho(), None),
        (perspective([0.3, -0.2, 9.0]), Some([0.3, -0.2, 9.0])),
    ] {
        let order = NewellOrder::sort(&mesh, &camera, false, store.storage()).unwrap();
        check_shape(&mesh, &order);
        assert!(order.splits() >= 1, "a cycle needs a split");
        assert!(order.shuffles() >= 1);
        assert_eq!(order.unresolved(), 0);
        assert_eq!(order.drawn(), order.fragment_count());
        let eye = eye.map(|e: [f32; 3]| e.map(f64::from));
        let (deep, _) = check_rays(&order, eye);
        assert!(deep > 20, "the sticks overlap: {deep} rays met two");
    }
}

#[test]
fn cycle_bound_is_an_error() {
    let b = sticks();
    let mesh = b.mesh();
    let mut store = Store::new();
    let options = NewellOptions { max_steps: 1 };
    let got = NewellOrder::sort_with(&mesh, &ortho(), false, store.storage(), options);
    assert!(matches!(got, Err(Error::DepthSortUnsettled { steps: 2 })));
}

fn boxes() -> Build {
    let mut b = Build::new();
    b.cuboid(
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 1.0],
        rotation((0.8, 0.6), (12.0 / 13.0, 5.0 / 13.0)),
    );
    b.cuboid(
        [0.9, 0.6, 0.4],
        [0.9, 0.7, 0.8],
        rotation((5.0 / 13.0, 12.0 / 13.0), (0.6, -0.8)),
    );
    b
}

#[test]
fn interpenetrating_boxes_are_split() {
    let b = boxes();
    let mesh = b.mesh();
    let mut store = Store::new();
    for cull in [true, false] {
        for (camera, eye) in [
            (ortho(), None),
            (perspective([1.0, 2.0, 7.0]), Some([1.0, 2.0, 7.0])),
            (perspective([-3.0, -1.0, 5.0]), Some([-3.0, -1.0, 5.0])),
        ] {
            let order = NewellOrder::sort(&mesh, &camera, cull, store.storage()).unwrap();
            check_shape(&mesh, &order);
            assert!(order.splits() >= 1, "interpenetration needs a split");
            assert_eq!(order.unresolved(), 0);
            if cull {
                assert!(order.drawn() < order.fragment_count());
            }
            let eye = eye.map(|e: [f32; 3]| e.map(f64::from));
            let (deep, _) = check_rays(&order, eye);
            assert!(deep > 100, "{deep} rays met two");
        }
    }
}

#[test]
fn split_fragments_are_watertight() {
    // Every fragment edge has an opposite half-edge (same positions, other
    // direction): the boxes are closed, so T-vertices must have been inserted.
    let b = boxes();
    let mesh = b.mesh();
    let mut store = Store::new();
    let order = NewellOrder::sort(&mesh, &ortho(), false, store.storage()).unwrap();
    let frag = order.fragments();
    let bits = |i: u32| frag.vertices()[i as usize].map(f32::to_bits);
    let mut edges = 0;
    for f in 0..order.fragment_count() {
        let c = frag.face(f);
        for k in 0..c.len() {
            let (a, b) = (bits(c[k]), bits(c[(k + 1) % c.len()]));
            if a == b {
                continue;
            }
            edges += 1;
            let opposite = (0..order.fragment_count()).any(|g| {
                let d = frag.face(g);
                (0..d.len()).any(|m| bits(d[m]) == b && bits(d[(m + 1) % d.len()]) == a)
            });
            assert!(
                opposite,
                "fragment {f}: edge {a:?} -> {b:?} has no opposite"
            );
        }
    }
    assert!(edges > 48);
    assert!(order.fragments().vertices().len() > mesh.vertices().len());
}

#[test]
fn coplanar_overlap_goes_to_the_lower_face() {
    let a = [
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ];
    let b = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 2.0, 0.0],
        [0.0, 2.0, 0.0],
    ];
    let b_reversed = [b[3], b[2], b[1], b[0]];
    // A quad over part of both, not coplanar with them.
    let over = [
        [-2.0, 0.5, 0.3],
        [2.5, 0.5, 0.3],
        [2.5, 0.9, 0.5],
        [-2.0, 0.9, 0.5],
    ];
    let mut store = Store::new();
    for faces in [
        [a, b, over],
        [b, a, over],
        [b_reversed, a, over],
        [over, a, b],
    ] {
        let mut build = Build::new();
        for q in faces {
            build.quad(q);
        }
        let mesh = build.mesh();
        for (camera, eye) in [
            (ortho(), None),
            (perspective([0.5, -0.4, 6.0]), Some([0.5, -0.4, 6.0])),
        ] {
            let order = NewellOrder::sort(&mesh, &camera, false, store.storage()).unwrap();
            check_shape(&mesh, &order);
            let eye = eye.map(|e: [f32; 3]| e.map(f64::from));
            let (_, ties) = check_rays(&order, eye);
            assert!(ties > 20, "the squares overlap: {ties} ties");
        }
    }
}

#[test]
fn too_little_storage_is_capacity_exceeded() {
    let b = sticks();
    let mesh = b.mesh();
    // Sizes for no split: the cycle needs one.
    let sizes = NewellSizes::for_mesh(mesh.vertices().len(), 3, mesh.indices().len(), 0);
    let mut store = Store::new();
    let got = NewellOrder::sort(
        &mesh,
        &ortho(),
        false,
        NewellStorage {
            vertices: &mut store.vertices[..sizes.vertices],
            indices: &mut store.indices[..sizes.indices],
            offsets: &mut store.offsets[..sizes.offsets],
            source: &mut store.source[..sizes.source],
            rank: &mut store.rank[..sizes.rank],
            seams: &mut store.seams[..sizes.seams],
            boxes: &mut store.boxes[..sizes.boxes],
            work: &mut store.work[..sizes.work],
        },
    );
    assert!(
        matches!(got, Err(Error::CapacityExceeded { needed, capacity, .. }) if needed > capacity),
        "{got:?}"
    );
    // The sizes for the splits it makes suffice.
    let splits = NewellOrder::sort(&mesh, &ortho(), false, store.storage())
        .unwrap()
        .splits();
    let sizes = NewellSizes::for_mesh(mesh.vertices().len(), 3, mesh.indices().len(), splits);
    let mut store = Store::new();
    let order = NewellOrder::sort(
        &mesh,
        &ortho(),
        false,
        NewellStorage {
            vertices: &mut store.vertices[..sizes.vertices],
            indices: &mut store.indices[..sizes.indices],
            offsets: &mut store.offsets[..sizes.offsets],
            source: &mut store.source[..sizes.source],
            rank: &mut store.rank[..sizes.rank],
            seams: &mut store.seams[..sizes.seams],
            boxes: &mut store.boxes[..sizes.boxes],
            work: &mut store.work[..sizes.work],
        },
    )
    .unwrap();
    assert_eq!(order.splits(), splits);
    // Rank too short: the exact need, before the result is made.
    let mut store = Store::new();
    let got = NewellOrder::sort(
        &mesh,
        &ortho(),
        false,
        NewellStorage {
            vertices: &mut store.vertices,
            indices: &mut store.indices,
            offsets: &mut store.offsets,
            source: &mut store.source,
            rank: &mut store.rank[..2],
            seams: &mut store.seams,
            boxes: &mut store.boxes,
            work: &mut store.work,
        },
    );
    assert_eq!(
        got.err(),
        Some(Error::CapacityExceeded {
            what: Capacity::FragmentRanks,
            needed: order.fragment_count(),
            capacity: 2
        })
    );
}
