//! Clipping: polygons and segments to the near/far slab, segments to a screen rectangle.

use super::vector::{add, scale, sub, weld_key, V3};

/// Clips a polygon (eye space) to `near <= -z <= far`. The intersection point of an edge
/// is computed from its end points in a canonical order, so that two faces sharing the
/// edge get bit-identical points (watertight).
pub(super) fn clip_polygon(poly: &[V3], near: f64, far: f64) -> Vec<V3> {
    let keep_near = |p: &V3| -p[2] >= near;
    let keep_far = |p: &V3| -p[2] <= far;
    let a = clip_plane(poly, keep_near, near);
    clip_plane(&a, keep_far, far)
}

fn clip_plane(poly: &[V3], keep: impl Fn(&V3) -> bool, w: f64) -> Vec<V3> {
    let n = poly.len();
    let mut out = Vec::with_capacity(n + 2);
    for i in 0..n {
        let (p, q) = (poly[i], poly[(i + 1) % n]);
        let (kp, kq) = (keep(&p), keep(&q));
        if kp {
            out.push(p);
        }
        if kp != kq {
            out.push(intersect_w(p, q, w));
        }
    }
    out
}

/// The point of segment p q at depth -z = w, computed in a canonical order of p and q.
fn intersect_w(p: V3, q: V3, w: f64) -> V3 {
    let (a, b) = if weld_key(&p) <= weld_key(&q) {
        (p, q)
    } else {
        (q, p)
    };
    let (wa, wb) = (-a[2], -b[2]);
    let t = (w - wa) / (wb - wa);
    let mut r = add(a, scale(sub(b, a), t));
    r[2] = -w;
    r
}

/// Segment a b (eye space) clipped to near <= -z <= far: parameter range.
pub(super) fn clip_segment(a: V3, b: V3, near: f64, far: f64) -> Option<(f64, f64)> {
    let (wa, wb) = (-a[2], -b[2]);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (lim, sign) in [(near, 1.0), (far, -1.0)] {
        // keep sign * (w - lim) >= 0
        let fa = sign * (wa - lim);
        let fb = sign * (wb - lim);
        if fa < 0.0 && fb < 0.0 {
            return None;
        }
        if fa < 0.0 {
            t0 = t0.max(fa / (fa - fb));
        } else if fb < 0.0 {
            t1 = t1.min(fa / (fa - fb));
        }
    }
    (t0 <= t1).then_some((t0, t1))
}

/// Liang-Barsky: parameter range of segment p0 p1 inside rect [x0, y0, x1, y1].
pub(super) fn clip_to_rect(p0: (f64, f64), p1: (f64, f64), r: [f64; 4]) -> Option<(f64, f64)> {
    let (dx, dy) = (p1.0 - p0.0, p1.1 - p0.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, p0.0 - r[0]),
        (dx, r[2] - p0.0),
        (-dy, p0.1 - r[1]),
        (dy, r[3] - p0.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 <= t1).then_some((t0, t1))
}
