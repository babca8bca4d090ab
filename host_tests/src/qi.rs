//! A host prototype of hidden lines decided by the segment (quantitative
//! invisibility, Appel 1967), on the fast engine's snapped vertices: the line
//! classification the design brief `LINE-VISIBILITY.md` proposes. The library's
//! stage (`pbuffer::render::engines::fast::segments`, `LineVisibility::BySegment`)
//! was ported from it; it stays as the sweep's independent cross-check
//! (`segment_lines_sweep`), written plainly with maps and every triangle tested.
//! The predicates' unit tests are the library's.
//!
//! Every test is a sign of an integer expression on the vertex cache's snapped
//! screen positions (`2^-S` px) and nearness (16.16, larger nearer; 24 bits of it
//! here): 2-D orientations in `i64`, depth at a crossing compared by
//! cross-multiplied orientations. A point exactly on a line is moved by
//! `(+e, +e^2)` (the conventions' rule for pixel centres), the same for every line
//! through it, so a crossing at a vertex is counted once along a chain.
//!
//! For a drawn edge `e = a-b`: `QI(e, 0+) = QI*(a) + L(e, a)`, where `QI*(v)`
//! counts the drawn faces not around `v` that cover `v` and are strictly nearer,
//! and `L(e, v)` the faces around `v` (not `e`'s own) that cover `e` next to `v`
//! and are nearer there. Along `e` the count changes only where `e` passes a
//! nearer contour edge (one whose drawn faces, other than `e`'s own, do not lie
//! one on each side of it on screen), by the faces of that edge. At `b`,
//! `QI*(b) = QI(e, 1-) - L(e, b)`, which seeds the next edges of the chain. Each
//! connected set of drawn edges is seeded once by a point test; where two paths
//! reach a vertex with different counts the point test decides (a re-seed).
//!
//! Piercings (an edge passing through a triangle) are found by testing every
//! triangle, in `f64`. Not handled (the frame keeps the fast engine's lines,
//! counted as a fallback): vertices outside near..far or the guard box.

use std::collections::{HashMap, VecDeque};

use pbuffer::mesh::{EdgeAdjacency, EdgeKind, Mesh};
use pbuffer::render::FastVertex;

/// Counts of one frame's classification.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QiCounts {
    /// Drawn (feature) edges.
    pub drawn: u64,
    /// Contour edges.
    pub contours: u64,
    /// (drawn, contour) pairs whose screen boxes overlap.
    pub box_pairs: u64,
    /// Pairs that cross on the screen.
    pub crossings: u64,
    /// Crossings where the contour is nearer.
    pub nearer: u64,
    /// Chains seeded by a point test.
    pub seeds: u64,
    /// Vertices reached with two different counts, decided again by a point test.
    pub reseeds: u64,
    /// Counts that went below zero (an inconsistency).
    pub negative: u64,
    /// Frames left to the per-pixel test (a vertex outside near..far).
    pub fallback: u64,
    /// Faces asked by point tests.
    pub point_faces: u64,
    /// Lines passing through a triangle.
    pub piercings: u64,
    /// Drawn edges whose count at the midpoint was checked against every
    /// triangle, and those where the two differ.
    pub checked: u64,
    pub mismatched: u64,
}

impl QiCounts {
    /// Takes `o` out of `self`.
    pub fn sub(&mut self, o: &QiCounts) {
        let mut neg = *o;
        for f in [
            &mut neg.drawn,
            &mut neg.contours,
            &mut neg.box_pairs,
            &mut neg.crossings,
            &mut neg.nearer,
            &mut neg.seeds,
            &mut neg.reseeds,
            &mut neg.negative,
            &mut neg.fallback,
            &mut neg.point_faces,
            &mut neg.piercings,
            &mut neg.checked,
            &mut neg.mismatched,
        ] {
            *f = f.wrapping_neg();
        }
        self.add(&neg);
    }

    /// Adds `o` into `self`.
    pub fn add(&mut self, o: &QiCounts) {
        for (a, b) in [
            (&mut self.drawn, o.drawn),
            (&mut self.contours, o.contours),
            (&mut self.box_pairs, o.box_pairs),
            (&mut self.crossings, o.crossings),
            (&mut self.nearer, o.nearer),
            (&mut self.seeds, o.seeds),
            (&mut self.reseeds, o.reseeds),
            (&mut self.negative, o.negative),
            (&mut self.fallback, o.fallback),
            (&mut self.point_faces, o.point_faces),
            (&mut self.piercings, o.piercings),
            (&mut self.checked, o.checked),
            (&mut self.mismatched, o.mismatched),
        ] {
            *a = a.wrapping_add(b);
        }
    }
}

/// A triangle edge: its welded ends and, for each triangle on it, the triangle
/// and its third corner.
type TriangleEdge = (u32, u32, Vec<(u32, u32)>);

/// The per-mesh part (a bake's work): welded ids, the faces' fan triangles
/// (each face is drawn as the parity of its fan triangles; here each triangle
/// counts), the edges of those triangles with the triangles on them, and the
/// triangles around each welded vertex.
pub struct QiMesh {
    /// Fan triangles: face and welded corners.
    tris: Vec<(u32, [u32; 3])>,
    /// Mesh edges (the drawn lines' candidates): welded ends, kind, every face.
    edges: Vec<(u32, u32, EdgeKind, Vec<u32>)>,
    /// Every triangle edge (mesh edges and fan diagonals): welded ends and, for
    /// each triangle on it, the triangle and its third corner.
    sides: Vec<TriangleEdge>,
    /// Where each triangle edge is in `sides`.
    side_index: HashMap<(u32, u32), usize>,
    /// The faces on each welded side (the faces of a mesh edge).
    users: HashMap<(u32, u32), Vec<u32>>,
    /// Welded corners of each face.
    corners: Vec<Vec<u32>>,
    /// Each face's first fan triangle in `tris` (its triangles are consecutive).
    face_tris: Vec<u32>,
    /// Triangles around each welded vertex (CSR).
    around_start: Vec<u32>,
    around: Vec<u32>,
}

impl QiMesh {
    /// The per-mesh data of `mesh` with its edges `adjacency`.
    pub fn new(mesh: &Mesh<'_>, adjacency: &EdgeAdjacency<'_>) -> Self {
        let verts = mesh.vertices();
        let mut first: HashMap<[u32; 3], u32> = HashMap::new();
        let weld: Vec<u32> = verts
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let key = p.map(|c| if c == 0.0 { 0 } else { c.to_bits() });
                *first.entry(key).or_insert(i as u32)
            })
            .collect();
        let mut tris = Vec::new();
        let mut users: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
        let mut corners = Vec::new();
        let mut face_tris = Vec::new();
        for f in 0..mesh.face_count() {
            let c: Vec<u32> = mesh.face(f).iter().map(|&i| weld[i as usize]).collect();
            corners.push(c.clone());
            face_tris.push(tris.len() as u32);
            for i in 1..c.len().saturating_sub(1) {
                tris.push((f as u32, [c[0], c[i], c[i + 1]]));
            }
            for i in 0..c.len() {
                let (p, q) = (c[i], c[(i + 1) % c.len()]);
                if p == q {
                    continue;
                }
                let list = users.entry((p.min(q), p.max(q))).or_default();
                if !list.contains(&(f as u32)) {
                    list.push(f as u32);
                }
            }
        }
        let edges = adjacency
            .edges()
            .iter()
            .map(|e| {
                let list = users.get(&(e.a, e.b)).cloned().unwrap_or_default();
                (e.a, e.b, e.kind, list)
            })
            .collect();
        let mut on: HashMap<(u32, u32), Vec<(u32, u32)>> = HashMap::new();
        for (t, (_, c)) in tris.iter().enumerate() {
            for i in 0..3 {
                let (p, q, r) = (c[i], c[(i + 1) % 3], c[(i + 2) % 3]);
                if p == q || q == r || r == p {
                    continue;
                }
                on.entry((p.min(q), p.max(q)))
                    .or_default()
                    .push((t as u32, r));
            }
        }
        let mut sides: Vec<TriangleEdge> = on.into_iter().map(|((a, b), l)| (a, b, l)).collect();
        sides.sort_by_key(|x| (x.0, x.1));
        let side_index = sides
            .iter()
            .enumerate()
            .map(|(i, x)| ((x.0, x.1), i))
            .collect();
        let n = verts.len();
        let mut count = vec![0u32; n + 1];
        for (_, c) in &tris {
            for &v in c {
                count[v as usize + 1] += 1;
            }
        }
        for i in 0..n {
            count[i + 1] += count[i];
        }
        let mut around = vec![0u32; count[n] as usize];
        let mut fill = count.clone();
        for (t, (_, c)) in tris.iter().enumerate() {
            for &v in c {
                around[fill[v as usize] as usize] = t as u32;
                fill[v as usize] += 1;
            }
        }
        Self {
            tris,
            edges,
            sides,
            side_index,
            users,
            corners,
            face_tris,
            around_start: count,
            around,
        }
    }

    fn around(&self, v: u32) -> &[u32] {
        let (s, e) = (
            self.around_start[v as usize] as usize,
            self.around_start[v as usize + 1] as usize,
        );
        &self.around[s..e]
    }
}

/// A snapped point: x, y (`2^-S` px) and nearness (24 bits).
#[derive(Clone, Copy, Debug)]
struct P {
    x: i64,
    y: i64,
    d: i64,
    /// The welded vertex it is ([`NOT_A_VERTEX`] for other points): its rank in
    /// the symbolic perturbation.
    id: u32,
}

/// The id of a point that is no vertex.
const NOT_A_VERTEX: u32 = u32::MAX;

fn pt(v: &FastVertex, id: u32) -> P {
    P {
        x: i64::from(v.x),
        y: i64::from(v.y),
        d: i64::from(v.d >> 8),
        id,
    }
}

fn orient(p: P, q: P, r: P) -> i64 {
    (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x)
}

/// The side of `r` of the line `p`-`q` (+1 left in these axes, -1 right). Where
/// the three lie on one line and all are vertices, every vertex is moved by its
/// own infinitesimal (simulation of simplicity: vertex `i`'s x by `e^(2^(2i))`, its
/// y by `e^(2^(2i+1))`, lower ids moved more), so that coincident vertices are
/// told apart the same way in every test; a point that is no vertex is moved by
/// `(+e, +e^2)` (the conventions' nudge). 0 only when `p == q` and no rule applies.
fn side(p: P, q: P, r: P) -> i64 {
    let o = orient(p, q, r);
    if o != 0 {
        return o.signum();
    }
    if p.id != NOT_A_VERTEX && q.id != NOT_A_VERTEX && r.id != NOT_A_VERTEX {
        return perturbed(p, q, r);
    }
    // orient(p, q, r + (e, e^2)) = (qx - px) e^2 - (qy - py) e.
    if q.y != p.y {
        -(q.y - p.y).signum()
    } else {
        (q.x - p.x).signum()
    }
}

/// The sign of a zero orientation of three vertices under the perturbation of
/// [`side`]: with `i < j < k` their ids in order, the first non-zero of
/// `y_j - y_k`, `x_k - x_j`, `y_k - y_i` (the factors of the three largest
/// infinitesimals), else -1 (the factor of `e_i2 e_j1`), times the parity of the
/// order.
fn perturbed(p: P, q: P, r: P) -> i64 {
    let mut v = [p, q, r];
    let mut parity = 1;
    for a in 0..2 {
        for b in 0..2 - a {
            if v[b].id > v[b + 1].id {
                v.swap(b, b + 1);
                parity = -parity;
            }
        }
    }
    let [i, j, k] = v;
    let terms = [j.y - k.y, k.x - j.x, k.y - i.y];
    let s = terms.iter().find(|t| **t != 0).map_or(-1, |t| t.signum());
    s * parity
}

/// Whether `r` (moved) lies inside triangle `t`, and the sign of the plane's
/// nearness at `r` minus `r.d` (the plane extrapolated when outside).
fn in_triangle(t: [P; 3], r: P) -> (bool, i64) {
    let area = orient(t[0], t[1], t[2]);
    if area == 0 {
        return (false, 0);
    }
    let s = area.signum();
    let inside = (0..3).all(|i| s * side(t[i], t[(i + 1) % 3], r) > 0);
    (inside, nearer_plane(t, area, r))
}

/// The sign of the plane of `t` at `r` minus `r.d` (larger: the plane nearer).
fn nearer_plane(t: [P; 3], area: i64, r: P) -> i64 {
    let w0 = orient(t[1], t[2], r) as i128;
    let w1 = orient(t[2], t[0], r) as i128;
    let w2 = orient(t[0], t[1], r) as i128;
    let n = i128::from(t[0].d) * w0 + i128::from(t[1].d) * w1 + i128::from(t[2].d) * w2
        - i128::from(r.d) * i128::from(area);
    n.signum() as i64 * area.signum()
}

/// The sign of the nearness of segment `a-b` minus that of `p-q` where they
/// cross on screen (they must cross): with `o1, o2` the orientations of `a`, `b`
/// to `p-q` and `o3, o4` of `p`, `q` to `a-b`, the line's nearness there is
/// `(b.d o1 - a.d o2) / (o1 - o2)` and the contour's `-(q.d o3 - p.d o4) / (o1 - o2)`
/// (`o3 - o4 = -(o1 - o2)`), so one cross-multiplied sum decides.
fn line_minus_contour(a: P, b: P, p: P, q: P) -> i64 {
    let (o1, o2) = (orient(p, q, a), orient(p, q, b));
    let (o3, o4) = (orient(a, b, p), orient(a, b, q));
    let num = i128::from(b.d) * i128::from(o1) - i128::from(a.d) * i128::from(o2)
        + i128::from(q.d) * i128::from(o3)
        - i128::from(p.d) * i128::from(o4);
    num.signum() as i64 * (o1 - o2).signum()
}

/// One frame's inputs.
pub struct QiFrame<'a> {
    pub mesh: &'a QiMesh,
    pub cache: &'a [FastVertex],
    pub facing: &'a [u32],
    pub cull: bool,
    pub s: u32,
    pub width: usize,
    pub height: usize,
}

struct Contour {
    a: u32,
    b: u32,
    /// Drawn triangles' faces and their side (+1 / -1) of `a`-`b`.
    faces: Vec<(u32, i64)>,
    /// Screen box.
    lo: (i64, i64),
    hi: (i64, i64),
}

impl QiFrame<'_> {
    fn p(&self, v: u32) -> P {
        pt(&self.cache[v as usize], v)
    }

    fn drawn(&self, f: u32) -> bool {
        !self.cull || self.facing(f)
    }

    fn facing(&self, f: u32) -> bool {
        self.facing[f as usize / 32] >> (f % 32) & 1 == 1
    }

    fn tri(&self, t: u32) -> (u32, [P; 3]) {
        let (f, c) = self.mesh.tris[t as usize];
        (f, c.map(|v| self.p(v)))
    }

    /// The faces that do not hide drawn edge `a-b` with faces `own`: its own,
    /// and, where it is an outline (a boundary or a silhouette), the faces beyond
    /// an own face collapsed on screen: across a side of it within one snapping
    /// step of the edge (the conventions' "Where snapping moves a face's side
    /// across an outline").
    fn not_hiding(&self, a: u32, b: u32, own: &[u32]) -> Vec<u32> {
        let mut out = own.to_vec();
        let outline = match own {
            [_] => true,
            [f, g] => self.facing(*f) != self.facing(*g),
            _ => false,
        };
        if !outline {
            return out;
        }
        let (pa, pb) = (self.p(a), self.p(b));
        let len2 = (pb.x - pa.x).pow(2) + (pb.y - pa.y).pow(2);
        let near = |v: u32| {
            let o = orient(pa, pb, self.p(v));
            o * o <= len2
        };
        for &f in own {
            let c = &self.mesh.corners[f as usize];
            for i in 0..c.len() {
                let (p, q) = (c[i], c[(i + 1) % c.len()]);
                if (p.min(q), p.max(q)) == (a.min(b), a.max(b)) || !near(p) || !near(q) {
                    continue;
                }
                for &g in self
                    .mesh
                    .users
                    .get(&(p.min(q), p.max(q)))
                    .into_iter()
                    .flatten()
                {
                    if !out.contains(&g) {
                        out.push(g);
                    }
                }
            }
        }
        out
    }

    /// The triangles around `v` (of faces not in `own`) covering `e = v-b` next
    /// to `v` and strictly nearer there.
    fn local(&self, v: u32, b: u32, own: &[u32]) -> i64 {
        let pb = self.p(b);
        let mut count = 0;
        for &t in self.mesh.around(v) {
            let (f, c) = self.mesh.tris[t as usize];
            if own.contains(&f) || !self.drawn(f) {
                continue;
            }
            let k = c.iter().position(|&x| x == v).unwrap_or(0);
            let (pv, pu, pw) = (self.p(c[k]), self.p(c[(k + 1) % 3]), self.p(c[(k + 2) % 3]));
            let area = orient(pv, pu, pw);
            if area == 0 {
                continue;
            }
            let s = area.signum();
            if s * side(pv, pu, pb) > 0
                && s * side(pw, pv, pb) > 0
                && nearer_plane([pv, pu, pw], area, pb) > 0
            {
                count += 1;
            }
        }
        count
    }

    /// The triangles of the faces `own` not around `v` that cover `v` (moved) and
    /// are strictly nearer there: counted in `QI*(v)`, but not over a line that
    /// `own` are the faces of.
    fn own_apart(&self, v: u32, own: &[u32]) -> i64 {
        self.covering(v, |f| own.contains(&f)).0
    }

    /// `QI*(v)`: the drawn triangles not around `v` that cover `v` (moved) and
    /// are strictly nearer there.
    fn point(&self, v: u32, counts: &mut QiCounts) -> i64 {
        let (count, asked) = self.covering(v, |_| true);
        counts.point_faces += asked;
        count
    }

    /// The drawn triangles of faces that `keep` takes, not around `v`, that cover
    /// `v` (moved) and are strictly nearer there; and how many were asked.
    fn covering(&self, v: u32, keep: impl Fn(u32) -> bool) -> (i64, u64) {
        let pv = self.p(v);
        let (mut count, mut asked) = (0, 0);
        for (t, (f, c)) in self.mesh.tris.iter().enumerate() {
            if !keep(*f) || !self.drawn(*f) || c.contains(&v) {
                continue;
            }
            asked += 1;
            let (_, tp) = self.tri(t as u32);
            let (inside, n) = in_triangle(tp, pv);
            if inside && n > 0 {
                count += 1;
            }
        }
        (count, asked)
    }

    /// The count at the point `a + (b - a) num / den` of edge `a-b` by testing
    /// every drawn triangle of a face not in `own` (a check of the chains).
    pub fn brute(&self, a: u32, b: u32, own: &[u32], num: i64, den: i64) -> i64 {
        let scale = |p: P| P {
            x: p.x * den,
            y: p.y * den,
            d: p.d * den,
            id: p.id,
        };
        let (pa, pb) = (self.p(a), self.p(b));
        let r = P {
            x: pa.x * (den - num) + pb.x * num,
            y: pa.y * (den - num) + pb.y * num,
            d: pa.d * (den - num) + pb.d * num,
            id: NOT_A_VERTEX,
        };
        let mut count = 0;
        for t in 0..self.mesh.tris.len() as u32 {
            let (f, tp) = self.tri(t);
            if !self.drawn(f) || own.contains(&f) {
                continue;
            }
            let (inside, n) = in_triangle(tp.map(scale), r);
            if inside && n > 0 {
                count += 1;
            }
        }
        count
    }

    /// Classifies every drawn edge's pixels into `lines` (1 visible, 2 hidden; 1
    /// wins), or returns `None` when the frame is not handled.
    pub fn classify(&self, lines: &mut [u8], counts: &mut QiCounts, check: bool) -> Option<()> {
        let m = self.mesh;
        // Drawn edges and contours.
        let on = |v: u32| self.cache[v as usize].x != i16::MIN;
        let mut drawn: Vec<usize> = Vec::new();
        for (k, (a, b, kind, fs)) in m.edges.iter().enumerate() {
            let feature = match kind {
                EdgeKind::Boundary | EdgeKind::NonManifold | EdgeKind::Crease => true,
                EdgeKind::Smooth => fs.len() == 2 && self.facing(fs[0]) != self.facing(fs[1]),
                EdgeKind::Inert => false,
            };
            if feature {
                if !on(*a) || !on(*b) {
                    counts.fallback += 1;
                    return None;
                }
                drawn.push(k);
            }
        }
        let mut contours: Vec<Contour> = Vec::new();
        for (a, b, list) in &m.sides {
            let (pa, pb) = (self.p(*a), self.p(*b));
            let mut sides = Vec::new();
            let mut sum = 0;
            for &(t, r) in list {
                let f = m.tris[t as usize].0;
                if self.drawn(f) {
                    let s = orient(pa, pb, self.p(r)).signum();
                    if s != 0 {
                        sides.push((f, s));
                        sum += s;
                    }
                }
            }
            // Triangles one on each side (or none with area): not a contour.
            if sum == 0 {
                continue;
            }
            if !on(*a) || !on(*b) {
                counts.fallback += 1;
                return None;
            }
            contours.push(Contour {
                a: *a,
                b: *b,
                faces: sides,
                lo: (pa.x.min(pb.x), pa.y.min(pb.y)),
                hi: (pa.x.max(pb.x), pa.y.max(pb.y)),
            });
        }
        counts.drawn += drawn.len() as u64;
        counts.contours += contours.len() as u64;
        // Each drawn edge's faces that do not hide it, decided once.
        let owners: Vec<Vec<u32>> = drawn
            .iter()
            .map(|&k| {
                let (a, b, _, own) = &m.edges[k];
                self.not_hiding(*a, *b, own)
            })
            .collect();

        // Each drawn edge: its crossings (t, delta) sorted.
        let mut events: Vec<Vec<(f64, i64)>> = Vec::with_capacity(drawn.len());
        for (&k, own) in drawn.iter().zip(&owners) {
            let (a, b, _, _) = &m.edges[k];
            let (pa, pb) = (self.p(*a), self.p(*b));
            let lo = (pa.x.min(pb.x), pa.y.min(pb.y));
            let hi = (pa.x.max(pb.x), pa.y.max(pb.y));
            let mut list = Vec::new();
            // The contours, and the plain edges of the line's own faces'
            // triangles: across those the count changes by the triangle on the
            // other side (an own face counts nowhere on its line).
            let mut extra: Vec<Contour> = Vec::new();
            for &f in own.iter() {
                let first = m.face_tris[f as usize] as usize;
                let count = m.corners[f as usize].len().saturating_sub(2);
                for (_, c) in &m.tris[first..first + count] {
                    for i in 0..3 {
                        let (p, q) = (c[i].min(c[(i + 1) % 3]), c[i].max(c[(i + 1) % 3]));
                        let Some(&si) = m.side_index.get(&(p, q)) else {
                            continue;
                        };
                        let (_, _, users) = &m.sides[si];
                        let (pp, pq) = (self.p(p), self.p(q));
                        let mut sides = Vec::new();
                        let mut sum = 0;
                        for &(t, r) in users {
                            let g = m.tris[t as usize].0;
                            if self.drawn(g) {
                                let sg = orient(pp, pq, self.p(r)).signum();
                                if sg != 0 {
                                    sides.push((g, sg));
                                    sum += sg;
                                }
                            }
                        }
                        if sum != 0 || extra.iter().any(|x| x.a == p && x.b == q) {
                            continue; // a contour: in the list already
                        }
                        extra.push(Contour {
                            a: p,
                            b: q,
                            faces: sides,
                            lo: (pp.x.min(pq.x), pp.y.min(pq.y)),
                            hi: (pp.x.max(pq.x), pp.y.max(pq.y)),
                        });
                    }
                }
            }
            for c in contours.iter().chain(extra.iter()) {
                if c.a == *a || c.a == *b || c.b == *a || c.b == *b {
                    continue;
                }
                if c.hi.0 < lo.0 || c.lo.0 > hi.0 || c.hi.1 < lo.1 || c.lo.1 > hi.1 {
                    continue;
                }
                counts.box_pairs += 1;
                let (pp, pq) = (self.p(c.a), self.p(c.b));
                let (s1, s2) = (side(pp, pq, pa), side(pp, pq, pb));
                if s1 == s2 {
                    continue;
                }
                let (s3, s4) = (side(pa, pb, pp), side(pa, pb, pq));
                if s3 == s4 {
                    continue;
                }
                counts.crossings += 1;
                // The contour hides where it is strictly nearer.
                if line_minus_contour(pa, pb, pp, pq) >= 0 {
                    continue;
                }
                let (o1, o2) = (orient(pp, pq, pa), orient(pp, pq, pb));
                counts.nearer += 1;
                let plus: i64 = c
                    .faces
                    .iter()
                    .filter(|(f, _)| !own.contains(f))
                    .map(|(_, s)| *s)
                    .sum();
                if plus == 0 {
                    continue;
                }
                // Entering the + side adds the faces there minus those on the -.
                let delta = if s2 > 0 { plus } else { -plus };
                let t = if o1 == o2 {
                    0.0
                } else {
                    o1 as f64 / (o1 - o2) as f64
                };
                list.push((t.clamp(0.0, 1.0), delta));
            }
            // Piercings: where the line passes through a triangle's plane
            // inside it, the triangle starts or stops hiding it (tested against
            // every triangle here; the target would take the pairs a bake
            // found).
            for (ti, (f, c)) in m.tris.iter().enumerate() {
                if own.contains(f) || !self.drawn(*f) || c.contains(a) || c.contains(b) {
                    continue;
                }
                let (_, tp) = self.tri(ti as u32);
                let tlo = (
                    tp[0].x.min(tp[1].x).min(tp[2].x),
                    tp[0].y.min(tp[1].y).min(tp[2].y),
                );
                let thi = (
                    tp[0].x.max(tp[1].x).max(tp[2].x),
                    tp[0].y.max(tp[1].y).max(tp[2].y),
                );
                if thi.0 < lo.0 || tlo.0 > hi.0 || thi.1 < lo.1 || tlo.1 > hi.1 {
                    continue;
                }
                let area = orient(tp[0], tp[1], tp[2]);
                if area == 0 {
                    continue;
                }
                let g = |r: P| {
                    let w0 = orient(tp[1], tp[2], r) as f64;
                    let w1 = orient(tp[2], tp[0], r) as f64;
                    let w2 = orient(tp[0], tp[1], r) as f64;
                    (tp[0].d as f64 * w0 + tp[1].d as f64 * w1 + tp[2].d as f64 * w2) / area as f64
                        - r.d as f64
                };
                let (g0, g1) = (g(pa), g(pb));
                if (g0 > 0.0) == (g1 > 0.0) {
                    continue;
                }
                let t = g0 / (g0 - g1);
                let x = pa.x as f64 + t * (pb.x - pa.x) as f64;
                let y = pa.y as f64 + t * (pb.y - pa.y) as f64;
                let sgn = |p: P, q: P| {
                    ((q.x - p.x) as f64 * (y - p.y as f64) - (q.y - p.y) as f64 * (x - p.x as f64))
                        * area.signum() as f64
                };
                if sgn(tp[0], tp[1]) > 0.0 && sgn(tp[1], tp[2]) > 0.0 && sgn(tp[2], tp[0]) > 0.0 {
                    counts.piercings += 1;
                    list.push((t, if g1 > 0.0 { 1 } else { -1 }));
                }
            }
            list.sort_by(|x, y| x.0.total_cmp(&y.0));
            events.push(list);
        }

        // Chains: welded vertex -> drawn edges.
        let mut at: HashMap<u32, Vec<usize>> = HashMap::new();
        for (i, &k) in drawn.iter().enumerate() {
            let (a, b, _, _) = &m.edges[k];
            at.entry(*a).or_default().push(i);
            at.entry(*b).or_default().push(i);
        }
        let mut star: HashMap<u32, i64> = HashMap::new();
        let mut start_qi: Vec<Option<i64>> = vec![None; drawn.len()];
        let mut queue: VecDeque<u32> = VecDeque::new();
        for i in 0..drawn.len() {
            if start_qi[i].is_some() {
                continue;
            }
            let v0 = m.edges[drawn[i]].0;
            if let std::collections::hash_map::Entry::Vacant(e) = star.entry(v0) {
                counts.seeds += 1;
                e.insert(self.point(v0, counts));
                queue.push_back(v0);
            }
            while let Some(v) = queue.pop_front() {
                let qv = star[&v];
                for &i in &at[&v] {
                    let (a, b, _, _) = &m.edges[drawn[i]];
                    let own = &owners[i];
                    let forward = *a == v;
                    if forward && start_qi[i].is_some() {
                        continue;
                    }
                    let w = if forward { *b } else { *a };
                    if !forward {
                        // Reached from its far end: walk it backwards.
                        if start_qi[i].is_some() {
                            continue;
                        }
                    }
                    let l0 = self.local(v, w, own) - self.own_apart(v, own);
                    let mut q = qv + l0;
                    let total: i64 = events[i].iter().map(|e| e.1).sum();
                    let (qa, qend) = if forward {
                        (q, q + total)
                    } else {
                        // q is the count next to b, at the end of the list.
                        let qa = q - total;
                        (qa, qa)
                    };
                    let end_q = if forward { qend } else { qa };
                    q = end_q;
                    start_qi[i] = Some(qa);
                    let lw = self.local(w, v, own) - self.own_apart(w, own);
                    let qw = q - lw;
                    match star.get(&w) {
                        None => {
                            star.insert(w, qw);
                            queue.push_back(w);
                        }
                        Some(&old) if old != qw => {
                            counts.reseeds += 1;
                            let fresh = self.point(w, counts);
                            star.insert(w, fresh);
                        }
                        _ => {}
                    }
                }
            }
        }

        if check {
            for (i, &k) in drawn.iter().enumerate() {
                let (a, b, _, _) = &m.edges[k];
                let own = &owners[i];
                let q0 = start_qi[i].unwrap_or(0);
                let mid = q0
                    + events[i]
                        .iter()
                        .filter(|e| e.0 < 0.5)
                        .map(|e| e.1)
                        .sum::<i64>();
                counts.checked += 1;
                if mid != self.brute(*a, *b, own, 1, 2) {
                    counts.mismatched += 1;
                }
            }
        }

        // Pixels.
        for (i, &k) in drawn.iter().enumerate() {
            let (a, b, _, _) = &m.edges[k];
            let q0 = start_qi[i].unwrap_or(0);
            let ev = &events[i];
            let (pa, pb) = (self.p(*a), self.p(*b));
            // The count after each crossing, so a pixel looks its piece up.
            let after: Vec<i64> = ev
                .iter()
                .scan(q0, |q, e| {
                    *q += e.1;
                    Some(*q)
                })
                .collect();
            walk(pa, pb, self.s, self.width, self.height, |x, y, t| {
                let passed = ev.partition_point(|e| e.0 < t);
                let q = if passed == 0 { q0 } else { after[passed - 1] };
                if q < 0 {
                    counts.negative += 1;
                }
                let cell = &mut lines[y * self.width + x];
                let class = if q <= 0 { 1 } else { 2 };
                if *cell == 0 || class == 1 {
                    *cell = class;
                }
            });
        }
        Some(())
    }
}

/// One pixel per pixel centre along the major axis (`render::lines::walk_segment`'s
/// pixels): calls `pixel(x, y, t)` with `t` the edge point's parameter from `a`.
fn walk(a: P, b: P, s: u32, width: usize, height: usize, mut pixel: impl FnMut(usize, usize, f64)) {
    let h = 1i64 << s;
    let p = 2 * h;
    let (ax, ay, bx, by) = (2 * a.x, 2 * a.y, 2 * b.x, 2 * b.y);
    let (dx, dy) = (bx - ax, by - ay);
    if dx == 0 && dy == 0 {
        return;
    }
    let x_major = dx.abs() >= dy.abs();
    let (ua, va, ub, vb) = if x_major {
        (ax, ay, bx, by)
    } else {
        (ay, ax, by, bx)
    };
    let (u0, u1) = (ua.min(ub), ua.max(ub));
    let k_first = (u0 - h + p - 1).div_euclid(p);
    let k_last = (u1 - h).div_euclid(p);
    let du = ub - ua;
    for k in k_first..=k_last {
        let c = (2 * k + 1) * h;
        // v at c: va + (c - ua) dv / du, floored to a pixel.
        let num = va * du + (c - ua) * (vb - va);
        let v = if du > 0 {
            num.div_euclid(du)
        } else {
            (-num).div_euclid(-du)
        };
        let m = v.div_euclid(p);
        let (x, y) = if x_major { (k, m) } else { (m, k) };
        if x < 0 || y < 0 || x >= width as i64 || y >= height as i64 {
            continue;
        }
        let t = (c - ua) as f64 / du as f64;
        pixel(x as usize, y as usize, t);
    }
}
