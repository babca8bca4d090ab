//! Screen-space polygons: exact orientation, even-odd coverage, distances, rounding.

use std::cmp::Ordering;

use crate::reference::{distance_to_segment, exact};

/// Rounds to a multiple of 2^-40 (identity for |v| >= 2^12).
pub(super) fn quantize(v: f64) -> f64 {
    const Q: f64 = (1u64 << 40) as f64;
    (v * Q).round() / Q
}

/// Sign of `(b.x - a.x)(p.y - a.y) - (b.y - a.y)(p.x - a.x)`, exact: an f64 filter with
/// Shewchuk's error bound (3.3e-16, taken as 1e-15), else [`exact::det_sign`].
pub fn orient_sign(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> Ordering {
    let l = (b.0 - a.0) * (p.1 - a.1);
    let r = (b.1 - a.1) * (p.0 - a.0);
    let det = l - r;
    let bound = 1e-15 * (l.abs() + r.abs());
    if det > bound {
        Ordering::Greater
    } else if det < -bound {
        Ordering::Less
    } else {
        exact::det_sign(a, b, p)
    }
}

/// Even-odd coverage of the point `p` by `poly` with the CONVENTIONS boundary rule
/// (the point moved by (+e, +e^2) is inside): the test of `reference::Polygon::winding`.
pub fn covers(poly: &[(f64, f64)], p: (f64, f64)) -> bool {
    let n = poly.len();
    let mut odd = false;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let (lo, hi) = match a.1.partial_cmp(&b.1) {
            Some(Ordering::Less) => (a, b),
            Some(Ordering::Greater) => (b, a),
            _ => continue,
        };
        if lo.1 <= p.1 && p.1 < hi.1 && orient_sign(lo, hi, p) != Ordering::Greater {
            odd = !odd;
        }
    }
    odd
}

/// Distance from `p` to the region of `poly` (0 when covered).
pub fn distance_to_polygon(poly: &[(f64, f64)], p: (f64, f64)) -> f64 {
    if poly.is_empty() {
        return f64::INFINITY;
    }
    if covers(poly, p) {
        return 0.0;
    }
    boundary_distance(poly, p)
}

/// Distance from `p` to the boundary of `poly`.
pub fn boundary_distance(poly: &[(f64, f64)], p: (f64, f64)) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| distance_to_segment(p, poly[i], poly[(i + 1) % n]))
        .fold(f64::INFINITY, f64::min)
}
