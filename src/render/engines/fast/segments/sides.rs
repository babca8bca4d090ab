//! The sides of a frame's fan triangles: the faces on an edge, which faces do not
//! hide a drawn edge, and a side's record of the drawn triangles on it (a contour
//! where they do not cancel).

use heapless::Vec;

use super::exact::orient;
use super::{Contour, Scene, MAX_NOT_HIDING, MAX_SIDE_TRIANGLES};
use crate::render::engines::fast::edge::CompactEdge;
use crate::{Capacity, Error};

/// The faces that do not hide one drawn edge.
pub(super) type NotHiding = Vec<u16, MAX_NOT_HIDING>;

/// The faces on an edge, into `out`: two (or one) from the edge list, every one
/// of a non-manifold edge from the faces around its end. (Written in place: a
/// returned list is copied byte by byte on the M4.)
pub(super) fn edge_faces(
    scene: &Scene<'_, '_>,
    e: &CompactEdge,
    out: &mut NotHiding,
) -> Result<(), Error> {
    out.clear();
    let full = |needed| Error::CapacityExceeded {
        what: Capacity::NotHidingFaces,
        needed,
        capacity: MAX_NOT_HIDING,
    };
    if e.kind != crate::mesh::EdgeKind::NonManifold {
        let [f, g] = e.faces;
        out.push(f).map_err(|_| full(1))?;
        if g != f {
            out.push(g).map_err(|_| full(2))?;
        }
        return Ok(());
    }
    for &f in scene.around.around(e.a) {
        if out.contains(&f) {
            continue;
        }
        let c = scene.corners(f);
        let has = (0..c.len()).any(|i| {
            let (p, q) = (scene.corner(c, i), scene.corner(c, (i + 1) % c.len()));
            (p.min(q), p.max(q)) == (e.a, e.b)
        });
        if has {
            let needed = out.len() + 1;
            out.push(f).map_err(|_| full(needed))?;
        }
    }
    Ok(())
}

/// Writes into `c` the drawn triangles of `faces` on side `p`-`q` (`p < q`),
/// each with the side of it that counts (`+1` left, `-1` right): the side it
/// lies on, turned where the triangle winds against its face (a face covers
/// where its fan's winding, taken in the face's own sense, is not 0), and
/// returns their sum: a contour when they do not cancel. `folds` gets the sum
/// of the sides they lie on (not 0: the face folds on screen there). (Written
/// in place: a returned record is copied byte by byte on the M4.)
pub(super) fn side_record(
    scene: &Scene<'_, '_>,
    p: u16,
    q: u16,
    faces: &[u16],
    c: &mut Contour,
    folds: &mut i32,
) -> Result<i32, Error> {
    let (pp, pq) = (scene.p(p), scene.p(q));
    *c = Contour {
        a: p,
        b: q,
        lo: [pp.x.min(pq.x) as i16, pp.y.min(pq.y) as i16],
        hi: [pp.x.max(pq.x) as i16, pp.y.max(pq.y) as i16],
        ..Contour::default()
    };
    let mut sum = 0;
    *folds = 0;
    for (i, &f) in faces.iter().enumerate() {
        if faces.get(..i).is_some_and(|before| before.contains(&f)) || !scene.drawn(f) {
            continue;
        }
        let corners = scene.corners(f);
        let n = corners.len();
        let at = |k: usize| scene.corner(corners, k);
        let is = |u: u16, v: u16| u != v && (u.min(v), u.max(v)) == (p, q);
        // The third corners of the fan triangles on the side, each with `+1`
        // where its triangle runs from `p` to `q`: a polygon side's one, a
        // diagonal's two (c0-ci, between triangles i - 1 and i).
        let from_p = |u: u16| if u == p { 1i8 } else { -1 };
        let mut thirds = [None; 2];
        for i in (0..n).filter(|_| n >= 3) {
            let (u, v) = (at(i), at((i + 1) % n));
            if is(u, v) {
                let r = if i == 0 {
                    at(2)
                } else if i == n - 1 {
                    at(n - 2)
                } else {
                    at(0)
                };
                thirds[0] = Some((r, from_p(u)));
            } else if (2..n.saturating_sub(1)).contains(&i) && is(at(0), u) {
                thirds = [
                    Some((at(i - 1), from_p(u))),
                    Some((at(i + 1), from_p(at(0)))),
                ];
            }
        }
        let mut winding = None;
        for (r, dir) in thirds.into_iter().flatten() {
            let s = orient(pp, pq, scene.p(r)).signum() as i8;
            if s == 0 {
                continue;
            }
            *folds += i32::from(s);
            // The triangle's area has the sign `s * dir`; it counts with the
            // sign of the face's: so its side counts as `dir` times the face's.
            // (A triangle is its own face: `s`, without its winding.)
            let counted = if n == 3 {
                s
            } else {
                dir * *winding.get_or_insert_with(|| scene.winding(corners))
            };
            sum += i32::from(counted);
            let (Some(fs), Some(ss)) = (
                c.faces.get_mut(usize::from(c.count)),
                c.sides.get_mut(usize::from(c.count)),
            ) else {
                return Err(Error::CapacityExceeded {
                    what: Capacity::SideTriangles,
                    needed: usize::from(c.count) + 1,
                    capacity: MAX_SIDE_TRIANGLES,
                });
            };
            *fs = f;
            *ss = counted;
            c.count += 1;
        }
    }
    Ok(sum)
}

impl Contour {
    /// Least screen `x`, `y`.
    #[inline(always)]
    pub(super) fn lo_i32(&self) -> (i32, i32) {
        (i32::from(self.lo[0]), i32::from(self.lo[1]))
    }

    /// Greatest screen `x`, `y`.
    #[inline(always)]
    pub(super) fn hi_i32(&self) -> (i32, i32) {
        (i32::from(self.hi[0]), i32::from(self.hi[1]))
    }
}

/// The edge `p`-`q` (`p < q`) of the mesh's edge list.
pub(super) fn edge_between(edges: &[CompactEdge], p: u16, q: u16) -> Option<&CompactEdge> {
    let i = edges.partition_point(|e| (e.a, e.b) < (p, q));
    match edges.get(i) {
        Some(e) if (e.a, e.b) == (p, q) => Some(e),
        _ => edges.iter().find(|e| (e.a, e.b) == (p, q)),
    }
}

/// The faces that do not hide drawn edge `e`: its own, and where it is an
/// outline (a boundary, or between a face that faces the eye and one that does
/// not), the faces beyond an own face's side that snapping laid within one step
/// of the edge (the conventions' "Where snapping moves a face's side across an
/// outline").
pub(super) fn not_hiding(
    scene: &Scene<'_, '_>,
    e: &CompactEdge,
    out: &mut NotHiding,
) -> Result<(), Error> {
    edge_faces(scene, e, out)?;
    let full = |needed| Error::CapacityExceeded {
        what: Capacity::NotHidingFaces,
        needed,
        capacity: MAX_NOT_HIDING,
    };
    let outline = match out.as_slice() {
        [_] => true,
        [f, g] => scene.facing(*f) != scene.facing(*g),
        _ => false,
    };
    if !outline {
        return Ok(());
    }
    let (pa, pb) = (scene.p(e.a), scene.p(e.b));
    let len2 = i64::from(pb.x - pa.x).pow(2) + i64::from(pb.y - pa.y).pow(2);
    let near = |v: u16| {
        let o = orient(pa, pb, scene.p(v));
        o.unsigned_abs() < 1 << 20 && o * o <= len2
    };
    let mut beyond_faces = NotHiding::new();
    for own in 0..out.len() {
        let Some(&f) = out.get(own) else { break };
        let c = scene.corners(f);
        for i in 0..c.len() {
            let (p, q) = (scene.corner(c, i), scene.corner(c, (i + 1) % c.len()));
            let (p, q) = (p.min(q), p.max(q));
            if (p, q) == (e.a, e.b) || !near(p) || !near(q) {
                continue;
            }
            if let Some(beyond) = edge_between(scene.edges, p, q) {
                edge_faces(scene, beyond, &mut beyond_faces)?;
                for &h in &beyond_faces {
                    if !out.contains(&h) {
                        let needed = out.len() + 1;
                        out.push(h).map_err(|_| full(needed))?;
                    }
                }
            }
        }
    }
    Ok(())
}
