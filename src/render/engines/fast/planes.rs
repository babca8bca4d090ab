//! The depth plane of a facet: its steps per pixel and per row and its depth at
//! column 0 of a row (16.16), set up in `f32` from three snapped corners, and the
//! tie and steepest slope made from it.

use super::float_int::to_i32;
use super::view::FastVertex;

/// Depths closer than a facet's tie are a tie, which the lower face index wins:
/// coplanar faces get planes through different snapped corners, each up to
/// `2^-(S+1)` px from its exact place, so their depths differ by up to about a
/// sixteenth of a pixel's depth change (at S = 4), plus rounding: the tie is one
/// depth unit plus `(|a| + |b|) / 16`, rounded up to whole depth units (so that
/// the pixel loop makes the stored entry from the compared one with one add).
pub(super) fn tie(a: i32, b: i32) -> u32 {
    let slope = (a.unsigned_abs() >> 4).saturating_add(b.unsigned_abs() >> 4);
    let units = (1u32 << 16).saturating_add(slope).saturating_add(0xFFFF) & 0xFFFF_0000;
    units.min(MAX_TIE)
}

/// The steepest of depth steps `steps` (16.16), in whole depth units (saturating).
pub(super) fn steepest(steps: [i32; 4]) -> u16 {
    let most = steps.iter().fold(0, |m, v| v.unsigned_abs().max(m)) >> 16;
    most.min(u32::from(u16::MAX)) as u16
}

/// The largest tie, 128 depth units: half the margin kept free below and above
/// the frame's depths (`view::MARGIN`), so that `depth - tie` never wraps.
const MAX_TIE: u32 = 128 << 16;

/// The depth plane through the fan triangle of largest screen area: steps per
/// pixel and per row, and the depth at the centre of column 0 of `row`.
pub(super) fn plane(pts: &[FastVertex], row: i32, s: u32) -> (i32, i32, u32) {
    let Some(&v0) = pts.first() else {
        return (0, 0, 0);
    };
    let (mut best, mut tri) = (0.0f32, (v0, v0));
    for w in pts.get(1..).unwrap_or(&[]).windows(2) {
        if let [p, q] = *w {
            let det = det(v0, p, q);
            if det.abs() > best.abs() {
                (best, tri) = (det, (p, q));
            }
        }
    }
    plane_through(v0, tri.0, tri.1, best, row, s)
}

/// Twice the signed screen area of the triangle `v0 p q` (`2^-2S` px^2), in `f32`.
#[inline(always)]
pub(super) fn det(v0: FastVertex, p: FastVertex, q: FastVertex) -> f32 {
    let (x0, y0) = (f32::from(v0.x), f32::from(v0.y));
    (f32::from(p.x) - x0) * (f32::from(q.y) - y0) - (f32::from(q.x) - x0) * (f32::from(p.y) - y0)
}

/// The plane through the triangle `v0 p q` of [`det`] `det` (flat when 0): see
/// [`plane`].
#[inline(always)]
pub(super) fn plane_through(
    v0: FastVertex,
    p: FastVertex,
    q: FastVertex,
    det: f32,
    row: i32,
    s: u32,
) -> (i32, i32, u32) {
    let (x0, y0) = (f32::from(v0.x), f32::from(v0.y));
    let xa = i32::from(v0.x) >> s;
    let ya = i32::from(v0.y) >> s;
    if det == 0.0 {
        return (0, 0, v0.d);
    }
    let (dx1, dy1) = (f32::from(p.x) - x0, f32::from(p.y) - y0);
    let (dx2, dy2) = (f32::from(q.x) - x0, f32::from(q.y) - y0);
    // Depth differences as f32: 16.16 values below 2^32, so the difference is exact
    // to 2^-8 of a depth unit.
    let dd1 = p.d as f32 - v0.d as f32;
    let dd2 = q.d as f32 - v0.d as f32;
    let inv = 1.0 / det;
    let unit = (1u32 << s) as f32;
    let a_sub = (dd1 * dy2 - dd2 * dy1) * inv;
    let b_sub = (dd2 * dx1 - dd1 * dx2) * inv;
    // From corner 0 to the centre of its pixel, in 2^-S px.
    let ox = (xa as f32 + 0.5) * unit - x0;
    let oy = (ya as f32 + 0.5) * unit - y0;
    let c = v0.d.wrapping_add(to_i32(a_sub * ox + b_sub * oy) as u32);
    let (a, b) = (to_i32(a_sub * unit), to_i32(b_sub * unit));
    let drow = c
        .wrapping_add(b.wrapping_mul(row - ya) as u32)
        .wrapping_sub(a.wrapping_mul(xa) as u32);
    (a, b, drow)
}
