//! The coverage point test of CONVENTIONS.md on one projected polygon: the same
//! answer as the scan converter's rows (`scan::edge`), one point at a time, for the
//! engines that sample rather than scan (area subdivision, ray casting, picking,
//! sub-pixel coverage).

use super::transform::ScreenVertex;

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
        // x0 + (py - y0) (x1 - x0) / (y1 - y0) <= px, with y1 - y0 > 0; products
        // below 2^58 inside the guard band, in 128 bits for any input.
        let lhs = i128::from(py - y0) * i128::from(x1 - x0);
        let rhs = i128::from(px - x0) * i128::from(y1 - y0);
        if lhs <= rhs {
            inside = !inside;
        }
    }
    inside
}

/// Whether the centre of pixel (`i`, `j`) is covered by `poly` at `s` sub-pixel bits.
// For the sampling engines; only the tests use it so far.
#[allow(dead_code)]
pub(crate) fn covers_centre(poly: &[ScreenVertex], s: u32, i: i64, j: i64) -> bool {
    let h = 1i64 << s;
    covers(poly, (2 * i + 1) * h, (2 * j + 1) * h)
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
