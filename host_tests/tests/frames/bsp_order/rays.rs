//! Ray casting against the fragments: the nearest hit must rank first.

use pbuffer::order::BspTree;
use pbuffer::Mesh;

use super::geometry::{cross, dot, pos, sub};

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Hit {
    Miss,
    At(f64),
    Edge,
}

/// Ray (unit `dir`) against a fragment polygon: even-odd over its fan triangles,
/// two-sided; `Edge` within 1e-9 (barycentric) of a fan triangle's edge.
pub(super) fn hit(mesh: &Mesh<'_>, f: usize, origin: [f64; 3], dir: [f64; 3]) -> Hit {
    let c = mesh.face(f);
    let p0 = pos(mesh, c[0]);
    let (mut inside, mut depth) = (false, 0.0);
    for w in c[1..].windows(2) {
        let (e1, e2) = (sub(pos(mesh, w[0]), p0), sub(pos(mesh, w[1]), p0));
        let h = cross(dir, e2);
        let a = dot(e1, h);
        if a.abs() < 1e-14 {
            continue;
        }
        let s = sub(origin, p0);
        let u = dot(s, h) / a;
        let q = cross(s, e1);
        let v = dot(dir, q) / a;
        let t = dot(e2, q) / a;
        let eps = 1e-9;
        if t > 0.0 && u > -eps && v > -eps && u + v < 1.0 + eps {
            if u < eps || v < eps || u + v > 1.0 - eps {
                return Hit::Edge;
            }
            inside = !inside;
            depth = t;
        }
    }
    if inside {
        Hit::At(depth)
    } else {
        Hit::Miss
    }
}

#[derive(Debug, Default)]
pub(super) struct Tally {
    pub(super) rays: usize,
    pub(super) checked: usize,
    pub(super) missed: usize,
    pub(super) edge: usize,
    pub(super) ties: usize,
    pub(super) failures: Vec<String>,
}

/// Checks one ray: the nearest hit fragment has the lowest rank among hit fragments,
/// unless the two are within `tie` of each other along the ray (counted as a tie).
pub(super) fn check_ray(
    tree: &BspTree<'_>,
    rank: &[u32],
    origin: [f64; 3],
    dir: [f64; 3],
    tie: f64,
    t: &mut Tally,
) {
    let mesh = tree.fragments();
    t.rays += 1;
    let mut nearest: Option<(f64, usize)> = None;
    let mut first: Option<(u32, f64, usize)> = None;
    for (f, &r) in rank.iter().enumerate().take(tree.fragment_count()) {
        match hit(&mesh, f, origin, dir) {
            Hit::Miss => {}
            Hit::Edge => {
                t.edge += 1;
                return;
            }
            Hit::At(d) => {
                if nearest.is_none_or(|(n, _)| d < n) {
                    nearest = Some((d, f));
                }
                if first.is_none_or(|(best, _, _)| r < best) {
                    first = Some((r, d, f));
                }
            }
        }
    }
    match (nearest, first) {
        (Some((dn, fnear)), Some((_, df, ffirst))) => {
            if fnear == ffirst {
                t.checked += 1;
            } else if df - dn <= tie {
                t.ties += 1;
            } else {
                t.failures.push(format!(
                    "ray {origin:?} -> {dir:?}: fragment {fnear} (rank {}, depth {dn}) is nearest, \
                     fragment {ffirst} (rank {}, depth {df}) ranks first",
                    rank[fnear], rank[ffirst]
                ));
            }
        }
        _ => t.missed += 1,
    }
}
