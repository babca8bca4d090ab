//! Rays in f64 that check a ranking: the nearest fragment a ray meets ranks first.

use super::*;

pub(super) use crate::vector::cross;
use crate::vector::sub;

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Where a ray meets a polygon (even-odd over its fan triangles, two-sided).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Hit {
    Miss,
    At(f64),
    /// Within 1e-9 (barycentric) of a fan triangle's edge: too close to call.
    Edge,
}

fn hit(mesh: &Mesh<'_>, f: usize, origin: [f64; 3], dir: [f64; 3]) -> Hit {
    let corners = mesh.face(f);
    let p = |i: u32| mesh.vertices()[i as usize].map(f64::from);
    let p0 = p(corners[0]);
    let (mut inside, mut depth) = (false, 0.0);
    for pair in corners[1..].windows(2) {
        let (e1, e2) = (sub(p(pair[0]), p0), sub(p(pair[1]), p0));
        let h = cross(dir, e2);
        let a = dot3(e1, h);
        if a.abs() < 1e-14 {
            continue;
        }
        let s = sub(origin, p0);
        let u = dot3(s, h) / a;
        let q = cross(s, e1);
        let v = dot3(dir, q) / a;
        let t = dot3(e2, q) / a;
        let eps = 1e-9;
        if [u, v, 1.0 - u - v].iter().any(|c| c.abs() <= eps) && u > -eps && v > -eps {
            return Hit::Edge;
        }
        if u > 0.0 && v > 0.0 && u + v < 1.0 && t > 0.0 {
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

/// Outcome of one ray: `Ok(true)` checked, `Ok(false)` skipped (edge or a tie
/// within 1e-9), `Err(..)` the ray property fails.
fn ray_ok(
    tree: &BspTree<'_>,
    rank: &[u32],
    origin: [f64; 3],
    dir: [f64; 3],
) -> Result<bool, (usize, usize)> {
    let mesh = tree.fragments();
    let mut nearest: Option<(f64, usize)> = None;
    let mut first: Option<(u32, f64, usize)> = None;
    for (f, &r) in rank.iter().enumerate().take(tree.fragment_count()) {
        match hit(&mesh, f, origin, dir) {
            Hit::Miss => {}
            Hit::Edge => return Ok(false),
            Hit::At(t) => {
                if nearest.is_none_or(|(tn, _)| t < tn) {
                    nearest = Some((t, f));
                }
                if first.is_none_or(|(best, _, _)| r < best) {
                    first = Some((r, t, f));
                }
            }
        }
    }
    match (nearest, first) {
        (Some((tn, fnear)), Some((_, tf, ffirst))) if fnear != ffirst => {
            if (tf - tn).abs() <= 1e-9 * (1.0 + tn) {
                Ok(false)
            } else {
                Err((fnear, ffirst))
            }
        }
        (Some(_), _) => Ok(true),
        _ => Ok(false),
    }
}

/// Ranks for `view` and checks that they are a permutation.
pub(super) fn ranks<'r>(tree: &BspTree<'_>, view: &Viewpoint, rank: &'r mut [u32]) -> &'r [u32] {
    let mut stack = [0u32; 512];
    rank.fill(u32::MAX);
    tree.rank_front_to_back(view, &mut stack, rank).unwrap();
    let rank = &rank[..tree.fragment_count()];
    let mut seen = [false; 512];
    for &r in rank {
        assert!(!seen[r as usize], "rank {r} given twice");
        seen[r as usize] = true;
    }
    rank
}

/// Shoots an `n x n` grid of rays from `eye` (perspective) through points of the
/// square `[lo, hi]^2` at height `z`, and orthographic rays along `-dir` through
/// the same points. Returns how many rays were checked.
pub(super) fn check_grid(
    tree: &BspTree<'_>,
    eye: [f64; 3],
    lo: f64,
    hi: f64,
    z: f64,
    n: usize,
) -> usize {
    let mut rank = [0u32; 512];
    let mut checked = 0;
    let ortho_dir = eye;
    let views = [
        Viewpoint::Perspective {
            eye: eye.map(|c| c as f32),
        },
        Viewpoint::Orthographic {
            direction_to_eye: ortho_dir.map(|c| c as f32),
        },
    ];
    for (v, view) in views.iter().enumerate() {
        let eye32 = eye.map(|c| f64::from(c as f32));
        let rank = ranks(tree, view, &mut rank);
        for i in 0..n {
            for j in 0..n {
                // Irrational-ish offsets keep the rays off the scene's edges.
                let x = lo + (hi - lo) * (i as f64 + 0.5123) / n as f64;
                let y = lo + (hi - lo) * (j as f64 + 0.4871) / n as f64;
                let target = [x, y, z];
                let (origin, dir) = if v == 0 {
                    (eye32, sub(target, eye32))
                } else {
                    let d = ortho_dir.map(|c| f64::from(c as f32));
                    (
                        [x + 100.0 * d[0], y + 100.0 * d[1], z + 100.0 * d[2]],
                        d.map(|c| -c),
                    )
                };
                match ray_ok(tree, rank, origin, dir) {
                    Ok(true) => checked += 1,
                    Ok(false) => {}
                    Err((near, first)) => panic!(
                        "view {view:?}, ray through {target:?}: fragment {near} is nearest but {first} ranks first"
                    ),
                }
            }
        }
    }
    checked
}
