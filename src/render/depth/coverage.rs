//! The coverage point test of [conventions](crate::conventions) on one projected polygon: the same
//! answer as the scan converter's rows (`scan::edge`), one point at a time, for the
//! engines that sample rather than scan (area subdivision, ray casting, picking,
//! sub-pixel coverage); and [`polygon_contains`], whose boundary counts as inside,
//! for the line test's fan triangles.

use crate::mesh::Mesh;
use crate::order::is_planar;
use crate::render::transform::{ProjectedVertex, ScreenVertex};

/// Whether the point (`px`, `py`), in half sub-pixel units (`2^-(S+1)` px), is
/// inside `poly` under the even-odd rule, a point on the boundary counting when the
/// point moved by (+e, +e^2) is inside.
///
/// An edge from top `(x0, y0)` to bottom `(x1, y1)` crosses the point's row when
/// `y0 <= py < y1`, and the crossing counts when it is at or left of `px`: exactly
/// the scan converter's rule (see `scan::edge`), compared here without division.
pub(crate) fn covers(poly: &[ScreenVertex], px: i64, py: i64) -> bool {
    let mut inside = false;
    let mut prev = match poly.last() {
        Some(v) => v,
        None => return false,
    };
    for v in poly {
        let (a, b) = if prev.y <= v.y { (prev, v) } else { (v, prev) };
        prev = v;
        let (x0, y0, x1, y1) = (
            2 * i64::from(a.x),
            2 * i64::from(a.y),
            2 * i64::from(b.x),
            2 * i64::from(b.y),
        );
        if !(y0 <= py && py < y1) {
            continue;
        }
        // x0 + (py - y0) (x1 - x0) / (y1 - y0) <= px, with y1 - y0 > 0. Inside the
        // guard band every difference fits 32 bits and a 64-bit product does (one
        // multiply on a Cortex-M4); 128 bits for any other input.
        let (a, b, c, d) = (py - y0, x1 - x0, px - x0, y1 - y0);
        let narrow = |v: i64| i32::try_from(v).map(i64::from);
        let left_of = match (narrow(a), narrow(b), narrow(c), narrow(d)) {
            (Ok(a), Ok(b), Ok(c), Ok(d)) => a * b <= c * d,
            _ => i128::from(a) * i128::from(b) <= i128::from(c) * i128::from(d),
        };
        if left_of {
            inside = !inside;
        }
    }
    inside
}

/// Whether the centre of pixel (`i`, `j`) is covered by `poly` at `s` sub-pixel bits.
// For the sampling engines; only the tests use it so far.
/// May the fragments of a face with these corners overlap on screen? A depth order
/// cuts a face that is not planar into fragments (its fan triangles, pieces along
/// cutting chords); their parity always adds up to the face's even-odd coverage
/// ([conventions](crate::conventions)), but an engine that draws each fragment on its own
/// covers their
/// overlap, where the face does not. (A planar face's pieces tile it in any view;
/// [`fragments_may_overlap`] asks this together with planarity.) They cannot overlap when the face
/// projects to a strictly convex polygon, winding once (every turn and every fan
/// triangle `(v0, vk, vk+1)` the same way): its fan triangles and every chord stay
/// inside it. Anything else (a face seen nearly edge-on that folds, a concave
/// projection, a corner clipped away) may.
pub(crate) fn folded(corners: &[u32], vertices: &[ProjectedVertex]) -> bool {
    let n = corners.len();
    if n < 3 {
        return true;
    }
    let at = |k: usize| {
        let p = corners.get(k % n).and_then(|&v| vertices.get(v as usize))?;
        p.projection().map(|s| (i64::from(s.x), i64::from(s.y)))
    };
    let sign = |a: (i64, i64), b: (i64, i64), c: (i64, i64)| {
        ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)).signum()
    };
    // Each corner is read once: (a, b, c) slides along, wrapping to v0 and v1.
    let (Some(v0), Some(v1)) = (at(0), at(1)) else {
        return true;
    };
    let (mut a, mut b) = (v0, v1);
    let mut way = 0;
    for k in 0..n {
        let c = match k + 2 {
            next if next < n => match at(next) {
                Some(c) => c,
                None => return true,
            },
            next if next == n => v0,
            _ => v1,
        };
        let turn = sign(a, b, c);
        let fan = if (1..n - 1).contains(&k) {
            sign(v0, a, b)
        } else {
            turn
        };
        if turn == 0 || fan != turn || (way != 0 && turn != way) {
            return true;
        }
        way = turn;
        (a, b) = (b, c);
    }
    false
}

/// Do the fragments a depth order made of mesh face `face` possibly overlap on screen
/// in this view, so that the face covers a pixel only where an odd number of them do?
/// Only a face that is not planar can (a triangle never is), and only where it may
/// fold ([`folded`]); the planarity test is the tree's own, asked last (it is f64).
pub(crate) fn fragments_may_overlap(
    mesh: &Mesh<'_>,
    face: usize,
    vertices: &[ProjectedVertex],
) -> bool {
    let corners = mesh.face(face);
    corners.len() > 3 && folded(corners, vertices) && !is_planar(mesh, face)
}

/// Whether some fan triangle `(v0, vk, vk+1)` of `poly` has an area: the test
/// `DepthPlane::new` makes before it sets up a plane (a polygon without one covers
/// no pixel), for an engine that needs no plane.
pub(crate) fn has_area(poly: &[ScreenVertex]) -> bool {
    let Some(v0) = poly.first() else {
        return false;
    };
    let d = |v: &ScreenVertex| {
        (
            i64::from(v.x) - i64::from(v0.x),
            i64::from(v.y) - i64::from(v0.y),
        )
    };
    poly.get(1..).is_some_and(|rest| {
        rest.windows(2).any(|pair| match pair {
            [a, b] => {
                let ((x1, y1), (x2, y2)) = (d(a), d(b));
                x1.wrapping_mul(y2) != x2.wrapping_mul(y1)
            }
            _ => false,
        })
    })
}

pub(crate) fn covers_centre(poly: &[ScreenVertex], s: u32, i: i64, j: i64) -> bool {
    let h = 1i64 << s;
    covers(poly, (2 * i + 1) * h, (2 * j + 1) * h)
}

/// True when point (x, y) (half sub-pixel units) is inside `poly` by the even-odd
/// rule (points exactly on an edge count as inside).
pub(crate) fn polygon_contains(poly: &[ScreenVertex], x: i64, y: i64) -> bool {
    // Each edge (a, b), the closing one first: the parity does not depend on the
    // order, and neither does the answer on an edge.
    let Some(mut a) = poly.last() else {
        return false;
    };
    let mut inside = false;
    for b in poly {
        let (ay, by) = (2 * i64::from(a.y), 2 * i64::from(b.y));
        if (ay <= y) != (by <= y) {
            let (ax, bx) = (2 * i64::from(a.x), 2 * i64::from(b.x));
            // Orientation of the point against the edge, taken upward.
            let (lx, ly, hx, hy) = if ay < by {
                (ax, ay, bx, by)
            } else {
                (bx, by, ax, ay)
            };
            // Inside the guard band every difference is below 2^28 half-units:
            // 32-bit factors with a 64-bit product (one multiply on a Cortex-M4).
            let wide = |a: i64, b: i64| i64::from(a as i32) * i64::from(b as i32);
            let cross = wide(hx - lx, y - ly) - wide(hy - ly, x - lx);
            if cross == 0 {
                return true;
            }
            if cross > 0 {
                inside = !inside;
            }
        }
        a = b;
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: i32, y: i32) -> ScreenVertex {
        ScreenVertex { x, y, q: 0 }
    }

    /// The square [1, 3] x [1, 3] px at S = 0 covers the centres of pixels 1 and 2 in
    /// each direction; two triangles sharing its diagonal cover each centre once.
    #[test]
    fn shared_edges_cover_each_centre_exactly_once() {
        let square = [v(1, 1), v(3, 1), v(3, 3), v(1, 3)];
        let upper = [v(1, 1), v(3, 1), v(3, 3)];
        let lower = [v(1, 1), v(3, 3), v(1, 3)];
        for j in 0..5 {
            for i in 0..5 {
                let inside = (1..3).contains(&i) && (1..3).contains(&j);
                assert_eq!(covers_centre(&square, 0, i, j), inside, "({i}, {j})");
                let n = u8::from(covers_centre(&upper, 0, i, j))
                    + u8::from(covers_centre(&lower, 0, i, j));
                assert_eq!(n, u8::from(inside), "({i}, {j})");
            }
        }
    }

    /// A centre exactly on a left or top edge is covered, on a right or bottom edge
    /// not: the square [0.5, 2.5]^2 px at S = 1 has centres on all four edges.
    #[test]
    fn centres_on_the_boundary_follow_the_top_left_rule() {
        let square = [v(1, 1), v(5, 1), v(5, 5), v(1, 5)];
        assert!(covers_centre(&square, 1, 0, 0));
        assert!(covers_centre(&square, 1, 1, 1));
        assert!(!covers_centre(&square, 1, 2, 1));
        assert!(!covers_centre(&square, 1, 1, 2));
    }
}
