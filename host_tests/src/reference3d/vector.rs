//! 3-vector arithmetic of the reference: [`V3`], its helpers and the Newell normal.

/// A 3-vector.
pub type V3 = [f64; 3];

pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub(crate) fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub(crate) fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// A position's weld key: its bit patterns with -0.0 read as 0.0 (CONVENTIONS.md;
/// `+ 0.0` turns -0.0 into 0.0 and leaves every other value alone).
pub(super) fn weld_key(p: &V3) -> [u64; 3] {
    p.map(|c| (c + 0.0).to_bits())
}

/// Newell normal of a polygon (not normalized; zero for degenerate polygons).
pub fn newell_normal(pts: &[V3]) -> V3 {
    let n = pts.len();
    let mut r = [0.0; 3];
    // Offsets from the first corner: a face in a plane of constant x, y or z then
    // gets exactly zero in the other components (raw coordinates leave a rounding
    // residue that can make an edge-on face of an axis view face the eye or not).
    let o = pts.first().copied().unwrap_or([0.0; 3]);
    for i in 0..n {
        let (a, b) = (sub(pts[i], o), sub(pts[(i + 1) % n], o));
        r[0] += (a[1] - b[1]) * (a[2] + b[2]);
        r[1] += (a[2] - b[2]) * (a[0] + b[0]);
        r[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    r
}
