//! Which points a projected polygon covers. There are exactly two point rules, both
//! even-odd, and they differ only on the boundary:
//! - **top-left** ([`covers`], [`covers_centre`]): the fill rule of
//!   [conventions](crate::conventions), the same answer as the scan converter's rows
//!   (`scan::edge`) one point at a time. Pixel coverage: whether a face covers a
//!   sample, for the engines that sample rather than scan (area subdivision, ray
//!   casting, the painter's, the A-buffer), picking, and the exact engines' line test
//!   (does a face cover a line pixel's edge point).
//! - **boundary inside** ([`contains`], [`polygon_contains`]): a point on an edge
//!   counts as inside. Points on lines and fan selection: which fan triangles of a
//!   bent face hold a point the face covers (the fan depth at a centre, the line
//!   test's bend), and the fast engine's exact test of an edge point against a face
//!   that touches the line's end.
//!
//! Beside them, tests of a face's projection as a whole: whether its fragments may
//! overlap ([`folded`], [`fragments_may_overlap`]) and whether it has an area
//! ([`has_area`]).

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

/// Whether the centre of pixel (`i`, `j`) is covered by `poly` at `s` sub-pixel bits
/// (the top-left rule, [`covers`]).
pub(crate) fn covers_centre(poly: &[ScreenVertex], s: u32, i: i64, j: i64) -> bool {
    let h = 1i64 << s;
    covers(poly, (2 * i + 1) * h, (2 * j + 1) * h)
}

/// Whether point (`x`, `y`), in half sub-pixel units (`2^-(S+1)` px), is inside
/// `poly` by the even-odd rule, a point on an edge counting as inside: [`contains`]
/// of its corners.
///
/// Its callers ask about corners in the view volume (within `GUARD_BAND_PX / 2` =
/// 2^13 px of the origin, and a unit of rounding; S at most 12: 2^26 half-units) and
/// points in the frame (`MAX_VIEWPORT` = 2^13 px): all of them fit 32 bits as they
/// are, and their differences too (below 2^28).
pub(crate) fn polygon_contains(poly: &[ScreenVertex], x: i64, y: i64) -> bool {
    contains(
        poly.iter()
            .map(|v| (v.x.wrapping_mul(2), v.y.wrapping_mul(2))),
        (x as i32, y as i32),
    )
}

/// Whether point `(x, y)` is inside the polygon with corners `corners` (closed: the
/// last joins the first) by the even-odd rule, a point on an edge counting as
/// inside. Half sub-pixel units (`2^-(S+1)` px), where pixel centres are integers.
///
/// Rows are half-open: an edge from `(lx, ly)` to `(hx, hy)`, `ly < hy`, takes part
/// in rows `ly <= y < hy`. The point is inside when it lies on such an edge, else
/// when an odd number of them cross its row strictly right of it. So a point on a
/// horizontal edge, or at a corner with no edge going on to larger y, is decided by
/// the crossings beside it: inside on a polygon's smallest-y side, outside on its
/// largest-y side.
///
/// 32-bit coordinates and differences, 64-bit products (one multiply on a
/// Cortex-M4; 64-bit coordinates cost the fast engine's suzanne frame 0.7 %): exact
/// when every difference of coordinates fits 32 bits, as it does for both callers,
/// [`polygon_contains`] (below 2^28) and the fast engine (16-bit corners, below
/// 2^16 half-units, and edge points on its lines, below 2^17).
pub(crate) fn contains(corners: impl IntoIterator<Item = (i32, i32)>, (x, y): (i32, i32)) -> bool {
    let mut corners = corners.into_iter();
    let Some(first) = corners.next() else {
        return false;
    };
    // Each edge (a, b), the closing one last: the parity does not depend on the
    // order, and neither does the answer on an edge.
    let mut a = first;
    let mut inside = false;
    for b in corners.chain(core::iter::once(first)) {
        let ((ax, ay), (bx, by)) = (a, b);
        if (ay <= y) != (by <= y) {
            // Orientation of the point against the edge, taken upward.
            let (lx, ly, hx, hy) = if ay < by {
                (ax, ay, bx, by)
            } else {
                (bx, by, ax, ay)
            };
            let wide = |a: i32, b: i32| i64::from(a) * i64::from(b);
            let cross = wide(hx.wrapping_sub(lx), y.wrapping_sub(ly))
                - wide(hy.wrapping_sub(ly), x.wrapping_sub(lx));
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

    /// Polygons in half-units: convex both ways round, concave (an L, a notch whose
    /// corner has no edge going on to larger y, a notch from the other side),
    /// crossing itself, with edges through lattice points, and a bare segment.
    const POLYGONS: [&[(i32, i32)]; 9] = [
        &[(0, 0), (8, 2), (3, 9)],
        &[(1, 1), (9, 1), (9, 9), (1, 9)],
        &[(1, 9), (9, 9), (9, 1), (1, 1)],
        &[(0, 0), (10, 0), (10, 4), (4, 4), (4, 10), (0, 10)],
        &[(0, 0), (5, 5), (10, 0), (10, 10), (0, 10)],
        &[(0, 0), (10, 0), (10, 10), (5, 4), (0, 10)],
        &[(0, 0), (10, 10), (10, 0), (0, 10)],
        &[(0, 0), (9, 3), (12, 12), (3, 9)],
        &[(2, 2), (6, 2)],
    ];

    /// Every lattice point of the polygon's box and two beyond it: the points on
    /// its edges and corners, inside and outside.
    fn points(poly: &[(i32, i32)]) -> impl Iterator<Item = (i32, i32)> {
        let (lo, hi) = poly.iter().fold((i32::MAX, i32::MIN), |(lo, hi), &(x, y)| {
            (lo.min(x).min(y), hi.max(x).max(y))
        });
        (lo - 2..=hi + 2).flat_map(move |y| (lo - 2..=hi + 2).map(move |x| (x, y)))
    }

    /// The rule of [`contains`] said the plain way: on an edge that takes part in
    /// the point's row (exactly, in 128 bits) inside, else the parity of the
    /// crossings right of it (the crossing found by division in `f64`, exact enough
    /// for these small coordinates: a crossing off the point is at least 1/16 of a
    /// unit from it).
    fn reference(poly: &[(i32, i32)], (px, py): (i32, i32)) -> bool {
        let n = poly.len();
        let mut crossings = 0;
        for k in 0..n {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            let ((lx, ly), (hx, hy)) = if a.1 < b.1 { (a, b) } else { (b, a) };
            if !(ly <= py && py < hy) {
                continue;
            }
            let on = i128::from(hx - lx) * i128::from(py - ly)
                == i128::from(hy - ly) * i128::from(px - lx);
            if on {
                return true;
            }
            let f = f64::from;
            let at = f(lx) + f(hx - lx) * f(py - ly) / f(hy - ly);
            crossings += usize::from(at > f(px));
        }
        crossings % 2 == 1
    }

    #[test]
    fn contains_agrees_with_the_reference() {
        for poly in POLYGONS {
            for p in points(poly) {
                assert_eq!(
                    contains(poly.iter().copied(), p),
                    reference(poly, p),
                    "{poly:?} {p:?}"
                );
            }
        }
        assert!(!contains([], (0, 0)));
    }

    /// Scaled to the callers' ranges (the fast engine's 16-bit corners, the view
    /// volume's 2^26 half-units around the origin), every answer stays the same:
    /// the 32-bit products are exact there.
    #[test]
    fn contains_is_exact_at_the_callers_bounds() {
        for (scale, offset) in [(1 << 12, -(1 << 15)), (1 << 23, -(1 << 26))] {
            let big = |(x, y): (i32, i32)| (x * scale + offset, y * scale + offset);
            for poly in POLYGONS {
                for p in points(poly) {
                    assert_eq!(
                        contains(poly.iter().map(|&c| big(c)), big(p)),
                        reference(poly, p),
                        "{poly:?} {p:?} x {scale}"
                    );
                }
            }
        }
    }

    /// A point on an edge is inside, but where rows are half-open: on the square's
    /// largest-y side (its edge and corners there) it is outside.
    #[test]
    fn points_on_edges_are_inside_but_on_the_largest_y_side() {
        let square = [v(1, 1), v(5, 1), v(5, 5), v(1, 5)];
        for k in 2..=10 {
            assert_eq!(polygon_contains(&square, 2, k), k < 10, "left ({k})");
            assert_eq!(polygon_contains(&square, 10, k), k < 10, "right ({k})");
            assert!(polygon_contains(&square, k, 2), "top ({k})");
            assert!(!polygon_contains(&square, k, 10), "bottom ({k})");
        }
        assert!(polygon_contains(&square, 6, 6));
        assert!(!polygon_contains(&square, 1, 6));
        assert!(!polygon_contains(&square, 11, 6));
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
