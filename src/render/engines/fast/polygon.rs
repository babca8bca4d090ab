//! Screen-space tests of a face's snapped corners: which way a corner turns,
//! whether a quad is convex or a fan folds over. (Whether a polygon holds a point
//! is the shared `render::depth::coverage::contains`.)

use super::view::FastVertex;

/// Is the polygon `pts` strictly convex on screen: do all its corners turn the
/// same way, none straight? Then each of its diagonals lies inside it and splits
/// it into two triangles on either side, and its rows beyond a diagonal's belong
/// to one of them.
pub(super) fn convex(pts: &[FastVertex]) -> bool {
    let n = pts.len();
    let (mut pos, mut neg) = (0, 0);
    for i in 0..n {
        let at = |k: usize| pts.get(k % n).copied().unwrap_or_default();
        let cross = turn(at(i), at(i + 1), at(i + 2));
        pos += usize::from(cross > 0);
        neg += usize::from(cross < 0);
    }
    pos == n || neg == n
}

/// The cross product `(p - o) x (q - o)` of screen points: positive when `o, p, q`
/// turn one way, negative the other, 0 on a line. 16-bit coordinates: the products
/// fit `i64` exactly.
pub(super) fn turn(o: FastVertex, p: FastVertex, q: FastVertex) -> i64 {
    let (ax, ay) = (
        i32::from(p.x) - i32::from(o.x),
        i32::from(p.y) - i32::from(o.y),
    );
    let (bx, by) = (
        i32::from(q.x) - i32::from(o.x),
        i32::from(q.y) - i32::from(o.y),
    );
    i64::from(ax) * i64::from(by) - i64::from(bx) * i64::from(ay)
}

/// Does every fan triangle `(c0, ck, ck+1)` of the face with cached corners
/// `corners` turn the way a back face turns on screen (clockwise with y up),
/// none edge-on? A bent face whose Newell normal faces away may still have a fan
/// triangle that faces the eye: that one is front surface.
pub(super) fn turns_away(corners: &[u32], cache: &[FastVertex]) -> bool {
    let at = |v: &u32| cache.get(*v as usize).copied().unwrap_or_default();
    let Some(p0) = corners.first().map(at) else {
        return false;
    };
    corners
        .get(1..)
        .unwrap_or(&[])
        .windows(2)
        .all(|w| matches!(w, [p, q] if turn(p0, at(p), at(q)) > 0))
}

/// Does the fan of `pts` fold over on screen: do its triangles `(p0, pk, pk+1)` not
/// all turn the same way? Then they overlap, and their union is not the polygon's
/// even-odd coverage: such a face is drawn as its polygon with one plane.
pub(super) fn folds(pts: &[FastVertex]) -> bool {
    let Some(&p0) = pts.first() else {
        return false;
    };
    let (mut pos, mut neg) = (false, false);
    for w in pts.get(1..).unwrap_or(&[]).windows(2) {
        if let [p, q] = *w {
            let cross = turn(p0, p, q);
            pos |= cross > 0;
            neg |= cross < 0;
        }
    }
    pos && neg
}
