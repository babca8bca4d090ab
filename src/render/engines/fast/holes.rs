//! Back faces that no ray can reach: skipped.
//!
//! Cap each hole of an open mesh (each loop of boundary edges) with a fan of
//! triangles. When the capped surface is nowhere inside-out (its winding number is
//! never negative), a ray from an eye outside it that meets a back face at `p` has
//! entered the capped solid before `p`: through a front face, which then hides
//! `p`, or through a cap. A cap lies in the convex hull of its loop, so when every
//! vertex is in front of the near plane (so is the eye outside, and no front face
//! is cut away) a back face is seen only where its screen box meets the screen box
//! of a hole's loop; elsewhere it is skipped. "Back" is said of the surface, so a
//! face is skipped only when its Newell normal faces away and each of its fan
//! triangles turns away on screen (a bent quad can have a fan triangle that faces
//! the eye: that part is front surface). Suzanne keeps the back faces around her
//! four holes.
//!
//! The picture is the same up to depth ties: a back face of lower index that won a
//! pixel from the front face beside it at a silhouette (within the tie) no longer
//! does. Measured against drawing every back face (`open_mesh.rs`): where the two
//! differ, the skipping frame agrees with the f64 reference or neither does.
//!
//! The host's [`BakedMesh::bake`](super::BakedMesh::bake) finds the loops and
//! checks the capped surface: its winding number, counted along skewed rays,
//! is at least 0 just off both sides of every face and cap triangle (so for a
//! surface that does not cross itself, everywhere). It labels each boundary
//! edge with its loop; a mesh that fails, or has more than [`MAX_HOLES`] loops or
//! more than [`MAX_CHECKED_FACES`] faces, gets no labels and draws every back face.

use super::edge::{CompactEdge, MAX_HOLES, NO_HOLE};
use super::view::FastVertex;
use crate::mesh::{EdgeKind, Mesh};
use crate::vector::{cross, sub};

/// The most faces whose capped surface `bake` checks (the check costs faces
/// times triangles): a larger mesh draws every back face.
pub const MAX_CHECKED_FACES: usize = 2048;

/// Labels each boundary edge of `mesh` with its loop when the capped surface
/// passes the check; otherwise every edge keeps [`NO_HOLE`].
pub(super) fn label_holes(mesh: &Mesh<'_>, edges: &mut [CompactEdge]) {
    for e in edges.iter_mut() {
        e.hole = NO_HOLE;
    }
    if mesh.face_count() > MAX_CHECKED_FACES
        || edges.iter().any(|e| e.kind == EdgeKind::NonManifold)
        || !edges.iter().any(|e| e.kind == EdgeKind::Boundary)
    {
        return;
    }
    if !find_loops(mesh, edges) || !never_inside_out(mesh, edges) {
        for e in edges.iter_mut() {
            e.hole = NO_HOLE;
        }
    }
}

/// The boundary edge's ends in the direction its face walks them, or `None`.
fn directed(mesh: &Mesh<'_>, e: &CompactEdge) -> Option<(u16, u16)> {
    let positions = mesh.vertices();
    let at = |v: u32| positions.get(v as usize).copied();
    let (pa, pb) = (at(u32::from(e.a))?, at(u32::from(e.b))?);
    let corners = mesh.face(usize::from(e.faces[0]));
    let n = corners.len();
    let (mut forward, mut backward) = (0, 0);
    for i in 0..n {
        let (u, v) = (corners.get(i)?, corners.get((i + 1) % n)?);
        let (pu, pv) = (at(*u)?, at(*v)?);
        // Welded ends: equal positions (`==` reads -0.0 as 0.0).
        forward += usize::from(pu == pa && pv == pb);
        backward += usize::from(pu == pb && pv == pa);
    }
    match (forward, backward) {
        (1, 0) => Some((e.a, e.b)),
        (0, 1) => Some((e.b, e.a)),
        _ => None,
    }
}

/// Labels the boundary edges loop by loop, each walked in its faces' direction;
/// false when a boundary vertex does not have exactly one boundary edge out and
/// one in, or there are more than [`MAX_HOLES`] loops.
fn find_loops(mesh: &Mesh<'_>, edges: &mut [CompactEdge]) -> bool {
    let boundary = |e: &CompactEdge| e.kind == EdgeKind::Boundary;
    let mut holes = 0usize;
    for start in 0..edges.len() {
        let Some(first) = edges.get(start).copied() else {
            return false;
        };
        if !boundary(&first) || first.hole != NO_HOLE {
            continue;
        }
        if holes == MAX_HOLES {
            return false;
        }
        let Some((origin, mut to)) = directed(mesh, &first) else {
            return false;
        };
        if let Some(e) = edges.get_mut(start) {
            e.hole = holes as u8;
        }
        while to != origin {
            // Exactly one boundary edge leaves `to`, and it is not labelled yet.
            let mut next = None;
            for (i, e) in edges.iter().enumerate() {
                if boundary(e) && (e.a == to || e.b == to) {
                    match directed(mesh, e) {
                        Some((from, _)) if from != to => {}
                        Some((_, end)) if next.is_none() && e.hole == NO_HOLE => {
                            next = Some((i, end));
                        }
                        _ => return false,
                    }
                }
            }
            let Some((i, end)) = next else {
                return false;
            };
            if let Some(e) = edges.get_mut(i) {
                e.hole = holes as u8;
            }
            to = end;
        }
        holes += 1;
    }
    // Every loop closed at its origin; a vertex with a second edge out was refused.
    true
}

/// A triangle of the capped surface, corners in `f64`.
type Tri = [[f64; 3]; 3];

/// Every triangle of the capped surface: the faces' fans, and each loop's cap,
/// a fan from its first corner walked against the loop (so it closes the
/// surface with the faces' orientation), given to `visit` until it returns false.
fn each_triangle(mesh: &Mesh<'_>, edges: &[CompactEdge], mut visit: impl FnMut(Tri) -> bool) {
    let positions = mesh.vertices();
    let at = |v: u32| {
        positions
            .get(v as usize)
            .map_or([0.0; 3], |p| p.map(f64::from))
    };
    for f in 0..mesh.face_count() {
        let corners = mesh.face(f);
        let Some(&c0) = corners.first() else {
            continue;
        };
        for w in corners.get(1..).unwrap_or(&[]).windows(2) {
            if let [b, c] = *w {
                if !visit([at(c0), at(b), at(c)]) {
                    return;
                }
            }
        }
    }
    for hole in 0..MAX_HOLES as u8 {
        let mut loop_edges = edges.iter().filter(|e| e.hole == hole);
        let Some(first) = loop_edges.next() else {
            return;
        };
        let Some((origin, mut to)) = directed(mesh, first) else {
            return;
        };
        // The cap walks the loop backward: triangle (origin, next, this).
        while to != origin {
            let Some((_, end)) = edges
                .iter()
                .filter(|e| e.hole == hole)
                .filter_map(|e| directed(mesh, e))
                .find(|&(from, _)| from == to)
            else {
                return;
            };
            if end != origin
                && !visit([at(u32::from(origin)), at(u32::from(end)), at(u32::from(to))])
            {
                return;
            }
            to = end;
        }
    }
}

/// Rays are skewed off the axes, so that they rarely graze the edges of
/// axis-aligned models; a sample whose every ray grazes fails the check.
const SKEWS: [(f64, f64); 3] = [(0.1234, 0.0567), (-0.0891, 0.1423), (0.0345, -0.1111)];

/// Is the capped surface's winding number at least 0 just off both sides of each
/// of its triangles?
fn never_inside_out(mesh: &Mesh<'_>, edges: &[CompactEdge]) -> bool {
    let mut scale = 0.0f64;
    each_triangle(mesh, edges, |t| {
        for p in t {
            scale = p.iter().fold(scale, |m, c| m.max(c.abs()));
        }
        true
    });
    let scale = scale.max(f64::MIN_POSITIVE);
    let mut ok = true;
    each_triangle(mesh, edges, |t| {
        let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
        let norm = n.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        if norm <= 1e-12 * scale * scale {
            // A degenerate triangle bounds no region.
            return true;
        }
        let [a, b, d] = t;
        let c = [
            (a[0] + b[0] + d[0]) / 3.0,
            (a[1] + b[1] + d[1]) / 3.0,
            (a[2] + b[2] + d[2]) / 3.0,
        ];
        let reach = t
            .iter()
            .flat_map(|p| sub(*p, c))
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let off = 1e-4 * reach / norm;
        for side in [1.0, -1.0] {
            let k = side * off;
            let x = [c[0] + k * n[0], c[1] + k * n[1], c[2] + k * n[2]];
            match winding(mesh, edges, x, scale) {
                Some(w) if w >= 0 => {}
                _ => {
                    ok = false;
                    return false;
                }
            }
        }
        true
    });
    ok
}

/// The winding number of the capped surface at `x`, counted along the first of
/// the skewed rays that grazes no triangle; `None` when every one grazes.
fn winding(mesh: &Mesh<'_>, edges: &[CompactEdge], x: [f64; 3], scale: f64) -> Option<i32> {
    'ray: for (sx, sy) in SKEWS {
        // Sheared so that the ray runs along +z: (x - sx z, y - sy z, z).
        let shear = |p: [f64; 3]| [p[0] - sx * p[2], p[1] - sy * p[2], p[2]];
        let o = shear(x);
        let (mut w, mut grazed) = (0i32, false);
        let tiny = 1e-12 * scale * scale;
        each_triangle(mesh, edges, |t| {
            let [a, b, c] = t.map(shear);
            let d = [orient(a, b, o), orient(b, c, o), orient(c, a, o)];
            let area = d[0] + d[1] + d[2];
            if d.iter().all(|v| *v > tiny) || d.iter().all(|v| *v < -tiny) {
                // The ray's line crosses the inside: where is the plane?
                let z = (d[1] * a[2] + d[2] * b[2] + d[0] * c[2]) / area;
                if (z - o[2]).abs() <= 1e-9 * scale {
                    grazed = true;
                    return false;
                }
                if z > o[2] {
                    // Counter-clockwise in xy: the normal leans along the ray, which
                    // leaves through it.
                    w += if area > 0.0 { 1 } else { -1 };
                }
            } else if d.iter().any(|v| v.abs() <= tiny)
                && !(d.iter().any(|v| *v > tiny) && d.iter().any(|v| *v < -tiny))
            {
                grazed = true;
                return false;
            }
            true
        });
        if grazed {
            continue 'ray;
        }
        return Some(w);
    }
    None
}

/// Twice the signed area of `a b p` in xy: positive counter-clockwise.
fn orient(a: [f64; 3], b: [f64; 3], p: [f64; 3]) -> f64 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

/// Each hole's screen box in a frame (half sub-pixel units, a pixel wider on
/// every side): a back face whose box meets none is skipped.
#[derive(Debug, Clone, Copy)]
pub(super) struct HoleBoxes {
    boxes: [[i32; 4]; MAX_HOLES],
    count: usize,
}

impl HoleBoxes {
    /// The holes' boxes from the vertex cache, or `None` (every back face drawn)
    /// when the mesh has no labelled holes or a vertex is not inside (near plane,
    /// far plane, guard box).
    pub fn new(edges: &[CompactEdge], vertices: &[FastVertex], s: u32) -> Option<Self> {
        if vertices.iter().any(|v| !v.inside()) {
            return None;
        }
        let mut boxes = Self {
            boxes: [[i32::MAX, i32::MIN, i32::MAX, i32::MIN]; MAX_HOLES],
            count: 0,
        };
        let margin = 2 << s;
        for e in edges {
            let Some(b) = boxes.boxes.get_mut(usize::from(e.hole)) else {
                continue;
            };
            boxes.count = boxes.count.max(usize::from(e.hole) + 1);
            for v in [e.a, e.b] {
                let (x, y) = vertices
                    .get(usize::from(v))
                    .copied()
                    .unwrap_or_default()
                    .half();
                *b = [
                    b[0].min(x - margin),
                    b[1].max(x + margin),
                    b[2].min(y - margin),
                    b[3].max(y + margin),
                ];
            }
        }
        (boxes.count > 0).then_some(boxes)
    }

    /// Does the box `left..=right`, `top..=bottom` (half units) meet a hole's?
    #[inline(always)]
    pub fn meets(&self, left: i32, right: i32, top: i32, bottom: i32) -> bool {
        self.boxes
            .get(..self.count)
            .unwrap_or(&[])
            .iter()
            .any(|b| left <= b[1] && right >= b[0] && top <= b[3] && bottom >= b[2])
    }
}
