//! The exact predicates of hidden lines by the segment: signs of integer
//! expressions on the vertex cache's snapped points.
//!
//! Bounds: `x`, `y` are 16-bit (`2^-S` px), so a difference is below `2^16` and
//! an orientation below `2^33`; nearness is the cache's 16.16 depth less its 8
//! lowest bits (below `2^24`). A nearness times an orientation is below `2^57`
//! and every sum below is of at most four such terms: `i64` holds them all.

use super::super::view::FastVertex;

/// A snapped point: screen `x`, `y` (`2^-S` px), nearness `d` (24 bits, larger
/// nearer), and the vertex it is ([`NOT_A_VERTEX`] for another point): its rank
/// in the symbolic perturbation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Pt {
    pub x: i32,
    pub y: i32,
    pub d: i32,
    pub id: u16,
}

/// The id of a point that is no vertex.
pub(crate) const NOT_A_VERTEX: u16 = u16::MAX;

impl Pt {
    /// Vertex `id` as the cache has it.
    #[inline(always)]
    pub fn of(v: FastVertex, id: u16) -> Self {
        Self {
            x: i32::from(v.x),
            y: i32::from(v.y),
            d: (v.d >> 8) as i32,
            id,
        }
    }
}

/// Twice the signed area of `p`, `q`, `r` (positive: `r` left of `p`-`q` in
/// these axes, y down).
#[inline(always)]
pub(crate) fn orient(p: Pt, q: Pt, r: Pt) -> i64 {
    i64::from(q.x - p.x) * i64::from(r.y - p.y) - i64::from(q.y - p.y) * i64::from(r.x - p.x)
}

/// The side of `r` of the line `p`-`q` (+1 left, -1 right), never 0 unless
/// `p == q` and no rule applies. Three vertices on one line are told apart by
/// simulation of simplicity (vertex `i` moved by its own infinitesimals, lower
/// ids more), the same way in every test; a point that is no vertex is moved by
/// `(+e, +e^2)`, the conventions' nudge.
#[inline(always)]
pub(crate) fn side(p: Pt, q: Pt, r: Pt) -> i32 {
    side_with(orient(p, q, r), p, q, r)
}

/// [`side`] with `o = orient(p, q, r)` known.
#[inline(always)]
pub(crate) fn side_with(o: i64, p: Pt, q: Pt, r: Pt) -> i32 {
    if o != 0 {
        return o.signum() as i32;
    }
    tie(p, q, r)
}

/// [`side`] where the orientation is 0. Out of line: rare.
#[inline(never)]
fn tie(p: Pt, q: Pt, r: Pt) -> i32 {
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
/// [`side`] (vertex `i`'s x moved by `e^(2^(2i))`, its y by `e^(2^(2i+1))`): with
/// `i < j < k` their ids in order, the first non-zero of `y_j - y_k`, `x_k - x_j`,
/// `y_k - y_i`, else -1, times the parity of the order.
fn perturbed(p: Pt, q: Pt, r: Pt) -> i32 {
    let (mut i, mut j, mut k) = (p, q, r);
    let mut parity = 1;
    for _ in 0..2 {
        if i.id > j.id {
            core::mem::swap(&mut i, &mut j);
            parity = -parity;
        }
        if j.id > k.id {
            core::mem::swap(&mut j, &mut k);
            parity = -parity;
        }
    }
    let terms = [j.y - k.y, k.x - j.x, k.y - i.y];
    let s = terms.iter().find(|t| **t != 0).map_or(-1, |t| t.signum());
    s * parity
}

/// Is `r` (moved as [`side`] moves it) inside triangle `t` (of twice-area
/// `area`, not 0), and is the triangle's plane strictly nearer than `r` there?
#[inline(always)]
pub(crate) fn covers_nearer(t: [Pt; 3], area: i64, r: Pt) -> bool {
    let s = area.signum() as i32;
    s * side(t[0], t[1], r) > 0
        && s * side(t[1], t[2], r) > 0
        && s * side(t[2], t[0], r) > 0
        && plane_minus(t, area, r) > 0
}

/// The sign of the nearness of the plane of `t` (twice-area `area`, not 0) at
/// `r`'s screen point, less `r`'s own (positive: the plane is nearer; the
/// plane extrapolated outside the triangle).
#[inline(always)]
pub(crate) fn plane_minus(t: [Pt; 3], area: i64, r: Pt) -> i32 {
    let w0 = orient(t[1], t[2], r);
    let w1 = orient(t[2], t[0], r);
    let w2 = orient(t[0], t[1], r);
    let n = i64::from(t[0].d) * w0 + i64::from(t[1].d) * w1 + i64::from(t[2].d) * w2
        - i64::from(r.d) * area;
    (n.signum() * area.signum()) as i32
}

/// The sign of the nearness of segment `a`-`b` less that of `p`-`q` where the
/// two cross on screen (they must): with `o1`, `o2` the orientations of `a`, `b`
/// to `p`-`q` and `o3`, `o4` of `p`, `q` to `a`-`b`, the segment's nearness there
/// is `(b.d o1 - a.d o2) / (o1 - o2)` and the other's `-(q.d o3 - p.d o4) / (o1 -
/// o2)`, so one cross-multiplied sum decides.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn segment_minus(a: Pt, b: Pt, p: Pt, q: Pt, o1: i64, o2: i64, o3: i64, o4: i64) -> i32 {
    let num = i64::from(b.d) * o1 - i64::from(a.d) * o2 + i64::from(q.d) * o3 - i64::from(p.d) * o4;
    (num.signum() * (o1 - o2).signum()) as i32
}

#[cfg(test)]
mod tests;
