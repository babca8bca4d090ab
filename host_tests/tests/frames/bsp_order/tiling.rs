//! The fragments tile their source faces (area, planes) and are watertight.

use std::collections::HashMap;

use pbuffer::order::{BspTree, PLANE_TOLERANCE};
use pbuffer::Mesh;

use super::geometry::{add, area_vector, dot, norm, plane_of, pos, sub};

/// Fragments tile their source faces: their area vectors sum to the face's, within
/// `1e-6` relative or the rounding of split points to f32 (`f32::EPSILON * scale *
/// perimeter`, for slivers); and each lies in its face's plane (within twice the
/// build's tolerance), or between its corners' offsets from that plane when the
/// face is not planar. Returns the largest area error relative to the face's area.
pub(super) fn check_tiling(source_mesh: &Mesh<'_>, tree: &BspTree<'_>, scale: f64) -> f64 {
    let fragments = tree.fragments();
    let mut sums = vec![[0.0f64; 3]; source_mesh.face_count()];
    for f in 0..tree.fragment_count() {
        let s = tree.source()[f] as usize;
        sums[s] = add(sums[s], area_vector(&fragments, f));
        let corners: Vec<[f64; 3]> = source_mesh
            .face(s)
            .iter()
            .map(|&i| pos(source_mesh, i))
            .collect();
        // Within the slab of the face's corners about its plane (a face that is not
        // planar is kept whole, so its fragments lie between its corners' offsets).
        if let Some((n, p0)) = plane_of(&corners) {
            let offset = |p: [f64; 3]| dot(n, sub(p, p0));
            let lo = corners.iter().map(|&p| offset(p)).fold(f64::MAX, f64::min);
            let hi = corners.iter().map(|&p| offset(p)).fold(f64::MIN, f64::max);
            let slack = 2.0 * PLANE_TOLERANCE * scale;
            assert!(
                fragments.face(f).iter().all(|&i| {
                    let o = offset(pos(&fragments, i));
                    o >= lo - slack && o <= hi + slack
                }),
                "fragment {f} does not lie in face {s}'s slab"
            );
        }
    }
    let mut worst = (0.0f64, 0.0f64);
    for (s, sum) in sums.iter().enumerate() {
        let n = area_vector(source_mesh, s);
        let c = source_mesh.face(s);
        let perimeter: f64 = (0..c.len())
            .map(|k| {
                norm(sub(
                    pos(source_mesh, c[(k + 1) % c.len()]),
                    pos(source_mesh, c[k]),
                ))
            })
            .sum();
        let err = norm(sub(*sum, n));
        let rounding = perimeter * scale * f64::from(f32::EPSILON);
        assert!(
            err <= (1e-6 * norm(n)).max(rounding),
            "face {s}: area vectors {sum:?} != {n:?}"
        );
        if norm(n) > 0.0 {
            worst.0 = worst.0.max(err / norm(n));
        }
        worst.1 = worst
            .1
            .max(err / (perimeter * scale * f64::from(f32::EPSILON)));
    }
    assert!(worst.1 <= 1.0);
    worst.0
}

/// Position bits of a vertex (welding: bit-identical positions are one vertex).
pub(super) fn bits(mesh: &Mesh<'_>, i: u32) -> [u32; 3] {
    mesh.vertices()[i as usize].map(f32::to_bits)
}

/// Directed edges of a mesh's faces, by position bits, with their multiplicity.
pub(super) fn half_edges(mesh: &Mesh<'_>) -> HashMap<([u32; 3], [u32; 3]), usize> {
    let mut map = HashMap::new();
    for f in 0..mesh.face_count() {
        let c = mesh.face(f);
        for k in 0..c.len() {
            let (a, b) = (bits(mesh, c[k]), bits(mesh, c[(k + 1) % c.len()]));
            if a != b {
                *map.entry((a, b)).or_insert(0) += 1;
            }
        }
    }
    map
}

/// Is `p` on segment `u`-`v` (within `eps`, as a distance)?
pub(super) fn on_segment(p: [f64; 3], u: [f64; 3], v: [f64; 3], eps: f64) -> bool {
    let d = sub(v, u);
    let len2 = dot(d, d);
    if len2 == 0.0 {
        return norm(sub(p, u)) <= eps;
    }
    let t = (dot(sub(p, u), d) / len2).clamp(0.0, 1.0);
    norm(sub(p, add(u, d.map(|c| c * t)))) <= eps
}

/// The fragments are watertight: every fragment edge has an opposite half-edge among
/// the fragments (same welded ends, other direction), except where it lies on an
/// edge of its source face that has no opposite half-edge among the mesh's faces (a
/// boundary, or a seam with the faces wound alike). Returns (edges, exempt).
pub(super) fn check_watertight(
    source_mesh: &Mesh<'_>,
    tree: &BspTree<'_>,
    scale: f64,
) -> (usize, usize) {
    let fragments = tree.fragments();
    let mesh_halves = half_edges(source_mesh);
    let halves = half_edges(&fragments);
    let eps = 1e-5 * scale;
    let (mut edges, mut exempt) = (0, 0);
    for f in 0..tree.fragment_count() {
        let c = fragments.face(f);
        for k in 0..c.len() {
            let (a, b) = (c[k], c[(k + 1) % c.len()]);
            let (ba, bb) = (bits(&fragments, a), bits(&fragments, b));
            if ba == bb {
                continue;
            }
            edges += 1;
            if halves.contains_key(&(bb, ba)) {
                continue;
            }
            let s = tree.source()[f] as usize;
            let sc = source_mesh.face(s);
            let (pa, pb) = (pos(&fragments, a), pos(&fragments, b));
            let on_open_edge = (0..sc.len()).any(|j| {
                let (u, v) = (sc[j], sc[(j + 1) % sc.len()]);
                let (bu, bv) = (bits(source_mesh, u), bits(source_mesh, v));
                let (pu, pv) = (pos(source_mesh, u), pos(source_mesh, v));
                !mesh_halves.contains_key(&(bv, bu))
                    && on_segment(pa, pu, pv, eps)
                    && on_segment(pb, pu, pv, eps)
            });
            assert!(
                on_open_edge,
                "fragment {f} (face {s}): edge {a}-{b} {pa:?} -> {pb:?} has no opposite half"
            );
            exempt += 1;
        }
    }
    (edges, exempt)
}
