//! The BSP tree's depth order, checked against f64 ray casting (independent of the
//! tree): for every ray from the eye, the nearest fragment it meets ranks first among
//! the fragments it meets. Random triangle soups (seeded), perspective and
//! orthographic eyes; the fragments tile their source faces and lie in their planes.
//! Plus the test models: fragment counts, depth and build time, printed
//! (`cargo test --release -p host_tests --test bsp_order -- --nocapture`).

use std::collections::HashMap;
use std::path::Path;
use std::time::Instant;

use host_tests::frame::MeshData;
use host_tests::obj::load_obj;
use host_tests::random::Rng;
use pbuffer::order::{
    work_bound, BspNode, BspOptions, BspSizes, BspStorage, BspTree, PLANE_TOLERANCE,
};
use pbuffer::{Error, Mesh, Viewpoint};

/// Owned storage for a build.
struct Owned {
    vertices: Vec<[f32; 3]>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
    source: Vec<u16>,
    nodes: Vec<BspNode>,
    seams: Vec<[u32; 2]>,
    work: Vec<u32>,
}

impl Owned {
    fn new(s: BspSizes) -> Self {
        Self {
            vertices: vec![[0.0; 3]; s.vertices],
            indices: vec![0; s.indices],
            offsets: vec![0; s.offsets],
            source: vec![0; s.source],
            nodes: vec![BspNode::EMPTY; s.nodes],
            seams: vec![[0; 2]; s.seams],
            work: vec![0; s.work],
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

/// CSR slices of a mesh.
struct Csr {
    vertices: Vec<[f32; 3]>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
}

impl Csr {
    fn from_data(data: &MeshData) -> Self {
        let mut offsets = vec![0u32];
        let mut indices = Vec::new();
        for face in &data.faces {
            indices.extend_from_slice(face);
            offsets.push(indices.len() as u32);
        }
        let vertices = data.vertices.iter().map(|v| v.map(|c| c as f32)).collect();
        Self {
            vertices,
            indices,
            offsets,
        }
    }

    fn mesh(&self) -> Mesh<'_> {
        Mesh::new(&self.vertices, &self.indices, &self.offsets).unwrap()
    }

    /// Storage sized by `BspSizes::for_mesh` for a growing split budget, until the
    /// build fits; returns the storage and the budget that fitted.
    fn storage_that_fits(&self) -> (Owned, usize) {
        let mesh = self.mesh();
        let faces = mesh.face_count();
        let mut splits = faces / 2 + 8;
        loop {
            let sizes = BspSizes::for_mesh(self.vertices.len(), faces, self.indices.len(), splits);
            let mut owned = Owned::new(sizes);
            match BspTree::build(&mesh, owned.storage()) {
                Ok(_) => return (owned, splits),
                Err(Error::CapacityExceeded { .. }) => splits *= 2,
                Err(e) => panic!("build failed: {e}"),
            }
        }
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn pos(mesh: &Mesh<'_>, i: u32) -> [f64; 3] {
    mesh.vertices()[i as usize].map(f64::from)
}

/// Newell normal (twice the area vector) of a face, in f64.
fn area_vector(mesh: &Mesh<'_>, f: usize) -> [f64; 3] {
    let c = mesh.face(f);
    let p0 = pos(mesh, c[0]);
    c[1..].windows(2).fold([0.0; 3], |n, w| {
        add(n, cross(sub(pos(mesh, w[0]), p0), sub(pos(mesh, w[1]), p0)))
    })
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Hit {
    Miss,
    At(f64),
    Edge,
}

/// Ray (unit `dir`) against a fragment polygon: even-odd over its fan triangles,
/// two-sided; `Edge` within 1e-9 (barycentric) of a fan triangle's edge.
fn hit(mesh: &Mesh<'_>, f: usize, origin: [f64; 3], dir: [f64; 3]) -> Hit {
    let c = mesh.face(f);
    let p0 = pos(mesh, c[0]);
    let (mut inside, mut depth) = (false, 0.0);
    for w in c[1..].windows(2) {
        let (e1, e2) = (sub(pos(mesh, w[0]), p0), sub(pos(mesh, w[1]), p0));
        let h = cross(dir, e2);
        let a = dot(e1, h);
        if a.abs() < 1e-14 {
            continue;
        }
        let s = sub(origin, p0);
        let u = dot(s, h) / a;
        let q = cross(s, e1);
        let v = dot(dir, q) / a;
        let t = dot(e2, q) / a;
        let eps = 1e-9;
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

#[derive(Debug, Default)]
struct Tally {
    rays: usize,
    checked: usize,
    missed: usize,
    edge: usize,
    ties: usize,
    failures: Vec<String>,
}

/// Checks one ray: the nearest hit fragment has the lowest rank among hit fragments,
/// unless the two are within `tie` of each other along the ray (counted as a tie).
fn check_ray(
    tree: &BspTree<'_>,
    rank: &[u32],
    origin: [f64; 3],
    dir: [f64; 3],
    tie: f64,
    t: &mut Tally,
) {
    let mesh = tree.fragments();
    t.rays += 1;
    let mut nearest: Option<(f64, usize)> = None;
    let mut first: Option<(u32, f64, usize)> = None;
    for (f, &r) in rank.iter().enumerate().take(tree.fragment_count()) {
        match hit(&mesh, f, origin, dir) {
            Hit::Miss => {}
            Hit::Edge => {
                t.edge += 1;
                return;
            }
            Hit::At(d) => {
                if nearest.is_none_or(|(n, _)| d < n) {
                    nearest = Some((d, f));
                }
                if first.is_none_or(|(best, _, _)| r < best) {
                    first = Some((r, d, f));
                }
            }
        }
    }
    match (nearest, first) {
        (Some((dn, fnear)), Some((_, df, ffirst))) => {
            if fnear == ffirst {
                t.checked += 1;
            } else if df - dn <= tie {
                t.ties += 1;
            } else {
                t.failures.push(format!(
                    "ray {origin:?} -> {dir:?}: fragment {fnear} (rank {}, depth {dn}) is nearest, \
                     fragment {ffirst} (rank {}, depth {df}) ranks first",
                    rank[fnear], rank[ffirst]
                ));
            }
        }
        _ => t.missed += 1,
    }
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = norm(v);
    v.map(|c| c / n)
}

fn random_direction(rng: &mut Rng) -> [f64; 3] {
    loop {
        let v = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let n = norm(v);
        if n > 0.1 && n <= 1.0 {
            return v.map(|c| c / n);
        }
    }
}

/// A soup of `n` random triangles in `[-1, 1]^3`, sizes 0.2 to 1.5.
fn soup(rng: &mut Rng, n: usize) -> MeshData {
    let mut data = MeshData::default();
    for f in 0..n {
        let centre = [
            rng.range(-0.8, 0.8),
            rng.range(-0.8, 0.8),
            rng.range(-0.8, 0.8),
        ];
        let size = rng.range(0.2, 1.5);
        for _ in 0..3 {
            let d = random_direction(rng);
            let r = size * rng.range(0.3, 1.0);
            data.vertices.push(add(centre, d.map(|c| c * r)));
        }
        let k = 3 * f as u32;
        data.faces.push(vec![k, k + 1, k + 2]);
    }
    data
}

/// The plane of a polygon: unit normal and a point.
fn plane_of(points: &[[f64; 3]]) -> Option<([f64; 3], [f64; 3])> {
    let p0 = points[0];
    let n = points[1..]
        .windows(2)
        .fold([0.0; 3], |n, w| add(n, cross(sub(w[0], p0), sub(w[1], p0))));
    (norm(n) > 1e-12).then(|| (unit(n), p0))
}

/// Fragments tile their source faces: their area vectors sum to the face's, within
/// `1e-6` relative or the rounding of split points to f32 (`f32::EPSILON * scale *
/// perimeter`, for slivers); and each lies in its face's plane (within twice the
/// build's tolerance), or between its corners' offsets from that plane when the
/// face is not planar. Returns the largest area error relative to the face's area.
fn check_tiling(source_mesh: &Mesh<'_>, tree: &BspTree<'_>, scale: f64) -> f64 {
    let fragments = tree.fragments();
    let mut sums = vec![[0.0f64; 3]; source_mesh.face_count()];
    for f in 0..tree.fragment_count() {
        let s = tree.source()[f] as usize;
        sums[s] = add(sums[s], area_vector(&fragments, f));
        let corners: Vec<[f64; 3]> = source_mesh
            .face(s)
            .iter()
            .map(|&i| pos(source_mesh, i))
            .collect();
        // Within the slab of the face's corners about its plane (a face that is not
        // planar is kept whole, so its fragments lie between its corners' offsets).
        if let Some((n, p0)) = plane_of(&corners) {
            let offset = |p: [f64; 3]| dot(n, sub(p, p0));
            let lo = corners.iter().map(|&p| offset(p)).fold(f64::MAX, f64::min);
            let hi = corners.iter().map(|&p| offset(p)).fold(f64::MIN, f64::max);
            let slack = 2.0 * PLANE_TOLERANCE * scale;
            assert!(
                fragments.face(f).iter().all(|&i| {
                    let o = offset(pos(&fragments, i));
                    o >= lo - slack && o <= hi + slack
                }),
                "fragment {f} does not lie in face {s}'s slab"
            );
        }
    }
    let mut worst = (0.0f64, 0.0f64);
    for (s, sum) in sums.iter().enumerate() {
        let n = area_vector(source_mesh, s);
        let c = source_mesh.face(s);
        let perimeter: f64 = (0..c.len())
            .map(|k| {
                norm(sub(
                    pos(source_mesh, c[(k + 1) % c.len()]),
                    pos(source_mesh, c[k]),
                ))
            })
            .sum();
        let err = norm(sub(*sum, n));
        let rounding = perimeter * scale * f64::from(f32::EPSILON);
        assert!(
            err <= (1e-6 * norm(n)).max(rounding),
            "face {s}: area vectors {sum:?} != {n:?}"
        );
        if norm(n) > 0.0 {
            worst.0 = worst.0.max(err / norm(n));
        }
        worst.1 = worst
            .1
            .max(err / (perimeter * scale * f64::from(f32::EPSILON)));
    }
    assert!(worst.1 <= 1.0);
    worst.0
}

/// Position bits of a vertex (welding: bit-identical positions are one vertex).
fn bits(mesh: &Mesh<'_>, i: u32) -> [u32; 3] {
    mesh.vertices()[i as usize].map(f32::to_bits)
}

/// Directed edges of a mesh's faces, by position bits, with their multiplicity.
fn half_edges(mesh: &Mesh<'_>) -> HashMap<([u32; 3], [u32; 3]), usize> {
    let mut map = HashMap::new();
    for f in 0..mesh.face_count() {
        let c = mesh.face(f);
        for k in 0..c.len() {
            let (a, b) = (bits(mesh, c[k]), bits(mesh, c[(k + 1) % c.len()]));
            if a != b {
                *map.entry((a, b)).or_insert(0) += 1;
            }
        }
    }
    map
}

/// Is `p` on segment `u`-`v` (within `eps`, as a distance)?
fn on_segment(p: [f64; 3], u: [f64; 3], v: [f64; 3], eps: f64) -> bool {
    let d = sub(v, u);
    let len2 = dot(d, d);
    if len2 == 0.0 {
        return norm(sub(p, u)) <= eps;
    }
    let t = (dot(sub(p, u), d) / len2).clamp(0.0, 1.0);
    norm(sub(p, add(u, d.map(|c| c * t)))) <= eps
}

/// The fragments are watertight: every fragment edge has an opposite half-edge among
/// the fragments (same welded ends, other direction), except where it lies on an
/// edge of its source face that has no opposite half-edge among the mesh's faces (a
/// boundary, or a seam with the faces wound alike). Returns (edges, exempt).
fn check_watertight(source_mesh: &Mesh<'_>, tree: &BspTree<'_>, scale: f64) -> (usize, usize) {
    let fragments = tree.fragments();
    let mesh_halves = half_edges(source_mesh);
    let halves = half_edges(&fragments);
    let eps = 1e-5 * scale;
    let (mut edges, mut exempt) = (0, 0);
    for f in 0..tree.fragment_count() {
        let c = fragments.face(f);
        for k in 0..c.len() {
            let (a, b) = (c[k], c[(k + 1) % c.len()]);
            let (ba, bb) = (bits(&fragments, a), bits(&fragments, b));
            if ba == bb {
                continue;
            }
            edges += 1;
            if halves.contains_key(&(bb, ba)) {
                continue;
            }
            let s = tree.source()[f] as usize;
            let sc = source_mesh.face(s);
            let (pa, pb) = (pos(&fragments, a), pos(&fragments, b));
            let on_open_edge = (0..sc.len()).any(|j| {
                let (u, v) = (sc[j], sc[(j + 1) % sc.len()]);
                let (bu, bv) = (bits(source_mesh, u), bits(source_mesh, v));
                let (pu, pv) = (pos(source_mesh, u), pos(source_mesh, v));
                !mesh_halves.contains_key(&(bv, bu))
                    && on_segment(pa, pu, pv, eps)
                    && on_segment(pb, pu, pv, eps)
            });
            assert!(
                on_open_edge,
                "fragment {f} (face {s}): edge {a}-{b} {pa:?} -> {pb:?} has no opposite half"
            );
            exempt += 1;
        }
    }
    (edges, exempt)
}

/// A target for a ray: a random point of a random face (three times in four, so
/// most rays meet something), else a random point of the box `lo..hi`.
fn target(rng: &mut Rng, mesh: &Mesh<'_>, lo: [f64; 3], hi: [f64; 3]) -> [f64; 3] {
    if rng.below(4) == 0 {
        return core::array::from_fn(|k| rng.range(lo[k], hi[k]));
    }
    let c = mesh.face(rng.below(mesh.face_count() as u64) as usize);
    let i = 1 + rng.below(c.len() as u64 - 2) as usize;
    let (a, b) = (rng.unit(), rng.unit());
    let (a, b) = if a + b > 1.0 {
        (1.0 - a, 1.0 - b)
    } else {
        (a, b)
    };
    let p0 = pos(mesh, c[0]);
    let e1 = sub(pos(mesh, c[i]), p0);
    let e2 = sub(pos(mesh, c[i + 1]), p0);
    core::array::from_fn(|k| p0[k] + a * e1[k] + b * e2[k])
}

#[test]
fn random_soups_rank_the_nearest_fragment_first() {
    let mut rng = Rng::new(0xB5B5_0001);
    let mut total = Tally::default();
    let (mut faces, mut fragments, mut worst_area) = (0usize, 0usize, 0.0f64);
    let (mut seam_edges, mut open_edges) = (0usize, 0usize);
    for scene in 0..200 {
        let n = 10 + rng.below(21) as usize;
        let csr = Csr::from_data(&soup(&mut rng, n));
        let mesh = csr.mesh();
        let (mut owned, _) = csr.storage_that_fits();
        let tree = BspTree::build(&mesh, owned.storage()).unwrap();
        faces += n;
        fragments += tree.fragment_count();
        assert!(
            tree.work_peak() <= work_bound(tree.fragment_count(), tree.fragments().indices().len())
        );
        worst_area = worst_area.max(check_tiling(&mesh, &tree, 1.0));
        let (edges, exempt) = check_watertight(&mesh, &tree, 1.0);
        seam_edges += edges;
        open_edges += exempt;
        let mut stack = vec![0u32; tree.depth()];
        let mut rank = vec![u32::MAX; tree.fragment_count()];
        for e in 0..4 {
            let (view, eye) = if e % 2 == 0 {
                // Outside the soup (e = 0) or inside it (e = 2).
                let r = if e == 0 {
                    rng.range(2.0, 5.0)
                } else {
                    rng.range(0.0, 0.8)
                };
                let eye = random_direction(&mut rng).map(|c| c * r);
                (
                    Viewpoint::Perspective {
                        eye: eye.map(|c| c as f32),
                    },
                    Some(eye),
                )
            } else {
                let d = random_direction(&mut rng);
                (
                    Viewpoint::Orthographic {
                        direction_to_eye: d.map(|c| c as f32),
                    },
                    None,
                )
            };
            rank.fill(u32::MAX);
            tree.rank_front_to_back(&view, &mut stack, &mut rank)
                .unwrap();
            let mut sorted = rank.clone();
            sorted.sort_unstable();
            assert!(
                sorted.iter().enumerate().all(|(i, &r)| r as usize == i),
                "not a permutation"
            );
            for _ in 0..50 {
                let target = target(&mut rng, &mesh, [-1.0; 3], [1.0; 3]);
                let (origin, dir) = match (view, eye) {
                    (Viewpoint::Perspective { eye: e32 }, Some(_)) => {
                        let o = e32.map(f64::from);
                        (o, unit(sub(target, o)))
                    }
                    (Viewpoint::Orthographic { direction_to_eye }, _) => {
                        let d = unit(direction_to_eye.map(f64::from));
                        (add(target, d.map(|c| 100.0 * c)), d.map(|c| -c))
                    }
                    _ => unreachable!(),
                };
                check_ray(&tree, &rank, origin, dir, 1e-9, &mut total);
            }
        }
        assert!(
            total.failures.is_empty(),
            "scene {scene}: {:#?}",
            total.failures
        );
    }
    println!(
        "soups: {faces} triangles -> {fragments} fragments ({:.2}x); rays {}: {} checked, \
         {} missed, {} near an edge, {} ties (<= 1e-9); worst area error {worst_area:.2e} relative",
        fragments as f64 / faces as f64,
        total.rays,
        total.checked,
        total.missed,
        total.edge,
        total.ties
    );
    println!(
        "soups: {seam_edges} fragment edges, {} with an opposite half, {open_edges} on open mesh edges",
        seam_edges - open_edges
    );
    assert!(
        fragments > faces + faces / 2,
        "soups this dense must split a lot"
    );
    assert!(total.checked > total.rays / 2, "{total:?}");
}

#[test]
fn models_build_with_reasonable_sizes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/models");
    let mut rng = Rng::new(7);
    for name in [
        "suzanne", "beetle", "woody", "teapot", "cow", "spot", "fandisk",
    ] {
        let path = dir.join(format!("{name}.obj"));
        let Ok(data) = load_obj(&path) else {
            println!("{name}: not found at {}, skipped", path.display());
            continue;
        };
        let csr = Csr::from_data(&data);
        let mesh = csr.mesh();
        let (mut owned, _) = csr.storage_that_fits();
        let start = Instant::now();
        let tree = BspTree::build(&mesh, owned.storage()).unwrap();
        let time = start.elapsed();
        let (faces, fragments) = (mesh.face_count(), tree.fragment_count());
        let index_count = tree.fragments().indices().len();
        println!(
            "{name:8}: {faces:6} faces -> {fragments:6} fragments ({:.2}x), {} splits, {} nodes, \
             depth {}, {} split points, work peak {} words, build {:.1} ms",
            fragments as f64 / faces as f64,
            tree.splits(),
            tree.node_count(),
            tree.depth(),
            tree.fragments().vertices().len() - mesh.vertices().len(),
            tree.work_peak(),
            time.as_secs_f64() * 1e3
        );
        assert!(tree.work_peak() <= work_bound(fragments, index_count));
        // The documented sizes, for the splits this mesh needs, suffice.
        let sizes = BspSizes::for_mesh(
            mesh.vertices().len(),
            faces,
            mesh.indices().len(),
            tree.splits(),
        );
        let mut exact = Owned::new(sizes);
        let again = BspTree::build(&mesh, exact.storage()).expect("for_mesh sizes");
        assert_eq!(again.fragment_count(), fragments);

        // A sample of rays from three eyes around the model.
        let mut tally = Tally::default();
        let (lo, hi) = data
            .vertices
            .iter()
            .fold(([f64::MAX; 3], [f64::MIN; 3]), |(lo, hi), v| {
                (
                    core::array::from_fn(|k| lo[k].min(v[k])),
                    core::array::from_fn(|k| hi[k].max(v[k])),
                )
            });
        let centre: [f64; 3] = core::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
        let radius = norm(sub(hi, lo));
        let scale = data
            .vertices
            .iter()
            .flatten()
            .fold(0.0f64, |m, c| m.max(c.abs()));
        let area_error = check_tiling(&mesh, &tree, scale);
        let (edges, exempt) = check_watertight(&mesh, &tree, scale);
        println!(
            "          watertight: {edges} fragment edges, {exempt} on open mesh edges; \
             kept {} bytes",
            std::mem::size_of_val(tree.fragments().vertices())
                + std::mem::size_of_val(tree.fragments().indices())
                + std::mem::size_of_val(tree.fragments().face_offsets())
                + std::mem::size_of_val(tree.source())
                + std::mem::size_of_val(tree.nodes())
        );
        let mut stack = vec![0u32; tree.depth()];
        let mut rank = vec![0u32; fragments];
        for _ in 0..3 {
            let eye = add(centre, random_direction(&mut rng).map(|c| c * 1.5 * radius));
            let e32 = eye.map(|c| c as f32);
            tree.rank_front_to_back(&Viewpoint::Perspective { eye: e32 }, &mut stack, &mut rank)
                .unwrap();
            let o = e32.map(f64::from);
            for _ in 0..40 {
                let target = target(&mut rng, &mesh, lo, hi);
                check_ray(
                    &tree,
                    &rank,
                    o,
                    unit(sub(target, o)),
                    1e-7 * radius,
                    &mut tally,
                );
            }
        }
        println!("          worst area error {area_error:.2e} relative; rays: {tally:?}");
        assert!(tally.failures.is_empty(), "{name}: {:#?}", tally.failures);
    }
}

/// Fragments and depth for a few splitter choices (`--ignored --nocapture`).
#[test]
#[ignore]
fn splitter_options_sweep() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/models");
    for name in ["suzanne", "beetle", "teapot", "cow", "spot", "fandisk"] {
        let Ok(data) = load_obj(&dir.join(format!("{name}.obj"))) else {
            continue;
        };
        let csr = Csr::from_data(&data);
        let mesh = csr.mesh();
        let sizes = BspSizes::for_mesh(
            mesh.vertices().len(),
            mesh.face_count(),
            mesh.indices().len(),
            8 * mesh.face_count(),
        );
        let mut owned = Owned::new(sizes);
        for candidates in [1u16, 4, 8, 16, 32] {
            for split_weight in [1u32, 4, 8, 32] {
                let start = Instant::now();
                let options = BspOptions {
                    candidates,
                    split_weight,
                };
                let tree = BspTree::build_with(&mesh, owned.storage(), options).unwrap();
                println!(
                    "{name:8} K {candidates:2} w {split_weight:2}: {:.2}x fragments, depth {:4}, {:6.1} ms",
                    tree.fragment_count() as f64 / mesh.face_count() as f64,
                    tree.depth(),
                    start.elapsed().as_secs_f64() * 1e3
                );
            }
        }
    }
}
