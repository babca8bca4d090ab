//! Piercings: where a drawn edge passes through a triangle, the triangle starts
//! or stops hiding it with no contour crossed on screen. Within a rigid mesh the
//! pairs that meet do not depend on the view: [`Piercing::bake`] finds them once
//! (with a margin, so that snapping cannot make a pair it missed), and each frame
//! decides them exactly on the snapped points.

use super::exact::{orient, Pt};
use super::{fan, place_between, Crossing};
use crate::mesh::Mesh;
use crate::render::engines::fast::edge::CompactEdge;
use crate::{Capacity, Error};

/// A mesh edge and a face's fan triangle that may meet: baked by
/// [`Piercing::bake`], sorted by edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Piercing {
    /// The edge's index in the compact edge list.
    pub edge: u16,
    /// The face.
    pub face: u16,
    /// The fan triangle (1 ..= corners - 2).
    pub fan: u8,
}

/// The margin of [`Piercing::bake`], as a share of the mesh's box diagonal.
pub const PIERCING_MARGIN: f64 = 1e-3;

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Coordinate `i` (0, 1, else 2) of `v`.
fn axis(v: V3, i: usize) -> f64 {
    let [x, y, z] = v;
    match i {
        0 => x,
        1 => y,
        _ => z,
    }
}

fn sqrt(x: f64) -> f64 {
    f64::from(crate::camera::sqrt(x as f32))
}

impl Piercing {
    /// Writes into `out` every (edge that can be drawn, fan triangle sharing no
    /// vertex with it) pair of `mesh` that meets, or passes within
    /// [`PIERCING_MARGIN`] of the mesh's size of meeting, sorted by edge; returns
    /// how many. `edges` is the compact edge list. Too small an `out` is
    /// `CapacityExceeded` with the real need. The cost grows with edges times
    /// faces: a bake's work, on the host.
    pub fn bake(
        mesh: &Mesh<'_>,
        edges: &[CompactEdge],
        out: &mut [Piercing],
    ) -> Result<usize, Error> {
        let pos = mesh.vertices();
        let at = |v: u32| -> V3 {
            let p = pos.get(v as usize).copied().unwrap_or_default();
            [f64::from(p[0]), f64::from(p[1]), f64::from(p[2])]
        };
        let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
        for p in pos {
            for ((l, h), &c) in lo.iter_mut().zip(hi.iter_mut()).zip(p) {
                *l = l.min(f64::from(c));
                *h = h.max(f64::from(c));
            }
        }
        let d = sub(hi, lo);
        let eps = PIERCING_MARGIN * sqrt(dot(d, d));
        let mut n = 0usize;
        for (e, edge) in edges.iter().enumerate() {
            if edge.kind == crate::mesh::EdgeKind::Inert {
                continue;
            }
            let (a, b) = (at(u32::from(edge.a)), at(u32::from(edge.b)));
            let (elo, ehi) = (
                [a[0].min(b[0]), a[1].min(b[1]), a[2].min(b[2])],
                [a[0].max(b[0]), a[1].max(b[1]), a[2].max(b[2])],
            );
            for f in 0..mesh.face_count() {
                let corners = mesh.face(f);
                let (pa, pb) = (
                    mesh.position_bits(u32::from(edge.a)),
                    mesh.position_bits(u32::from(edge.b)),
                );
                let touches = corners.iter().any(|&v| {
                    let p = mesh.position_bits(v);
                    p == pa || p == pb
                });
                if touches {
                    continue;
                }
                for k in 1..corners.len().saturating_sub(1) {
                    let t = fan(corners, k).map(|v| at(u32::from(v)));
                    let apart = (0..3).any(|i| {
                        let (l, h) = (axis(elo, i), axis(ehi, i));
                        t.iter().all(|&p| axis(p, i) < l - eps)
                            || t.iter().all(|&p| axis(p, i) > h + eps)
                    });
                    if apart || !meets(a, b, t, eps) {
                        continue;
                    }
                    if let Some(slot) = out.get_mut(n) {
                        *slot = Piercing {
                            edge: e as u16,
                            face: f as u16,
                            fan: k as u8,
                        };
                    }
                    n += 1;
                }
            }
        }
        crate::error::need(Capacity::Piercings, n, out.len())?;
        Ok(n)
    }
}

/// Does segment `a`-`b` meet triangle `t`, or pass within `eps` of it?
fn meets(a: V3, b: V3, t: [V3; 3], eps: f64) -> bool {
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let len = sqrt(dot(n, n));
    if len == 0.0 {
        return false;
    }
    let (sa, sb) = (dot(n, sub(a, t[0])) / len, dot(n, sub(b, t[0])) / len);
    if (sa > eps && sb > eps) || (sa < -eps && sb < -eps) {
        return false;
    }
    let s = if sa == sb {
        0.5
    } else {
        (sa / (sa - sb)).clamp(0.0, 1.0)
    };
    let x = [
        a[0] + s * (b[0] - a[0]),
        a[1] + s * (b[1] - a[1]),
        a[2] + s * (b[2] - a[2]),
    ];
    let [t0, t1, t2] = t;
    [(t0, t1), (t1, t2), (t2, t0)].into_iter().all(|(p, q)| {
        let e = sub(q, p);
        let side = dot(n, cross(e, sub(x, p))) / len;
        side >= -eps * sqrt(dot(e, e))
    })
}

/// Where drawn edge `a`-`b` passes through triangle `t` on screen, in depth:
/// its place along the major axis (`x_major`) and the change of its count (`+1`
/// entering behind it going from `a` to `b`). Exact: the plane's nearness less
/// the edge's is affine along the edge, and so is each barycentric orientation,
/// so the point where the first is 0 is inside when each of the others,
/// cross-multiplied, has the triangle's sign (`i128`: products of `2^59` and
/// `2^34`).
pub(super) fn pierce(a: Pt, b: Pt, t: [Pt; 3], x_major: bool) -> Option<Crossing> {
    let area = orient(t[0], t[1], t[2]);
    if area == 0 {
        return None;
    }
    let sa = area.signum();
    let g = |r: Pt| {
        let w = [
            orient(t[1], t[2], r),
            orient(t[2], t[0], r),
            orient(t[0], t[1], r),
        ];
        let n = i64::from(t[0].d) * w[0] + i64::from(t[1].d) * w[1] + i64::from(t[2].d) * w[2]
            - i64::from(r.d) * area;
        (n * sa, w)
    };
    let ((ga, wa), (gb, wb)) = (g(a), g(b));
    if (ga > 0) == (gb > 0) {
        return None;
    }
    let den = (i128::from(ga) - i128::from(gb)).signum();
    let inside = wa.iter().zip(wb.iter()).all(|(&x, &y)| {
        let w = i128::from(ga) * i128::from(y) - i128::from(gb) * i128::from(x);
        w.signum() * den * i128::from(sa) > 0
    });
    if !inside {
        return None;
    }
    let (ua, ub) = if x_major { (a.x, b.x) } else { (a.y, b.y) };
    Some(Crossing {
        place: place_between(ua, ub, ga, gb),
        delta: if gb > 0 { 1 } else { -1 },
    })
}
