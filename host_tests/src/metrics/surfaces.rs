//! Surface metrics (a)-(d): the library's face ids against the reference's.

use super::scene::SurfaceMetrics;
use crate::frame::Frame;
use crate::reference::distance_to_segment;
use crate::reference3d::RefFrame;

/// Offsets (di, dj) with max(|di|, |dj|) <= k.
fn square(k: isize) -> Vec<(isize, isize)> {
    (-k..=k)
        .flat_map(|dj| (-k..=k).map(move |di| (di, dj)))
        .collect()
}

/// The pixels the reference covers more than 1 px from every projected edge: the
/// base of the approximate engine's limit on face-id differences away from edges.
pub fn covered_away(rf: &RefFrame) -> usize {
    let near = near_edge_mask(rf, 1.0);
    rf.ids
        .iter()
        .zip(&near)
        .filter(|(&id, &n)| id != 0 && !n)
        .count()
}

/// Pixels whose centre is within `r` px of an edge of a drawn face's projected polygon.
pub fn near_edge_mask(rf: &RefFrame, r: f64) -> Vec<bool> {
    let (w, h) = (rf.width, rf.height);
    let mut mask = vec![false; w * h];
    for face in rf.faces.iter().filter(|f| f.drawn) {
        let n = face.screen.len();
        for k in 0..n {
            let (a, b) = (face.screen[k], face.screen[(k + 1) % n]);
            let ylo = a.1.min(b.1) - r;
            let yhi = a.1.max(b.1) + r;
            let j0 = (ylo - 0.5).ceil().max(0.0);
            let j1 = (yhi - 0.5).floor().min(h as f64 - 1.0);
            if j0 > j1 {
                continue;
            }
            for j in j0 as usize..=j1 as usize {
                let yc = j as f64 + 0.5;
                // x range of the segment's points with y in [yc - r, yc + r], grown by r.
                let (xlo, xhi) = if a.1 == b.1 {
                    (a.0.min(b.0), a.0.max(b.0))
                } else {
                    let t = |y: f64| ((y - a.1) / (b.1 - a.1)).clamp(0.0, 1.0);
                    let (ta, tb) = (t(yc - r), t(yc + r));
                    let xa = a.0 + ta * (b.0 - a.0);
                    let xb = a.0 + tb * (b.0 - a.0);
                    (xa.min(xb), xa.max(xb))
                };
                let i0 = (xlo - r - 0.5).ceil().max(0.0);
                let i1 = (xhi + r - 0.5).floor().min(w as f64 - 1.0);
                if i0 > i1 {
                    continue;
                }
                for i in i0 as usize..=i1 as usize {
                    let k = j * w + i;
                    if !mask[k] && distance_to_segment((i as f64 + 0.5, yc), a, b) <= r {
                        mask[k] = true;
                    }
                }
            }
        }
    }
    mask
}

/// Surface metrics (a)-(d) of the library `ids` against the reference.
pub fn compare_surfaces(frame: &Frame, rf: &RefFrame) -> SurfaceMetrics {
    let (w, h) = (rf.width, rf.height);
    assert_eq!((frame.width, frame.height), (w, h), "frame size");
    assert_eq!(frame.ids.len(), w * h, "ids size");
    let near = near_edge_mask(rf, 1.0);
    let d1 = square(1);
    let d2 = square(2);
    let nb = |i: usize, j: usize, d: &[(isize, isize)]| -> Vec<usize> {
        d.iter()
            .filter_map(|&(di, dj)| {
                let (x, y) = (i as isize + di, j as isize + dj);
                (x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h)
                    .then(|| y as usize * w + x as usize)
            })
            .collect()
    };
    let mut m = SurfaceMetrics {
        pixels: w * h,
        ref_covered: rf.ids.iter().filter(|&&i| i != 0).count(),
        lib_covered: frame.ids.iter().filter(|&&i| i != 0).count(),
        ..SurfaceMetrics::default()
    };
    let note = |slot: &mut Option<(usize, usize)>, i, j| {
        if slot.is_none() {
            *slot = Some((i, j));
        }
    };
    for j in 0..h {
        for i in 0..w {
            let k = j * w + i;
            let (lib, r) = (frame.ids[k], rf.ids[k]);
            let (cx, cy) = (i as f64 + 0.5, j as f64 + 0.5);
            if lib == 0 {
                if r != 0 && nb(i, j, &d1).iter().all(|&q| rf.ids[q] != 0) {
                    m.holes += 1;
                    note(&mut m.first[0], i, j);
                }
            } else {
                let f = lib as usize - 1;
                let wrong = f >= rf.faces.len() || {
                    let b = rf.faces[f].bbox;
                    rf.faces[f].screen.is_empty()
                        || cx < b[0] - 1.0
                        || cx > b[2] + 1.0
                        || cy < b[1] - 1.0
                        || cy > b[3] + 1.0
                        || rf.face_distance(f, cx, cy) > 1.0
                };
                if wrong {
                    m.wrong_faces += 1;
                    note(&mut m.first[1], i, j);
                }
                if f < rf.faces.len() && !rf.faces[f].drawn {
                    m.culled_face_pixels += 1;
                }
                if lib != r && f < rf.faces.len() {
                    let behind_everywhere = nb(i, j, &d2).iter().all(|&q| {
                        let (qx, qy) = ((q % w) as f64 + 0.5, (q / w) as f64 + 0.5);
                        rf.ids[q] != 0
                            && rf.ids[q] != lib
                            && rf
                                .face_depth(f, qx, qy)
                                .is_some_and(|d| d > rf.depth[q] * (1.0 + 1e-9))
                    });
                    if behind_everywhere {
                        m.depth_order += 1;
                        note(&mut m.first[2], i, j);
                    }
                }
            }
            if lib != r {
                if near[k] {
                    m.near_diffs += 1;
                } else {
                    m.far_diffs += 1;
                    note(&mut m.first[3], i, j);
                }
            }
        }
    }
    m
}

/// The snapping bound at S sub-pixel bits: a vertex snapped to the `2^-S` grid moves
/// at most `sqrt(2) 2^-(S+1)` px, and so does every edge through it; plus 0.01 px
/// for the clip points' and the projection's rounding.
pub fn snapping_bound(subpixel: u32) -> f64 {
    std::f64::consts::SQRT_2 * 0.5f64.powi(subpixel as i32 + 1) + 0.01
}

/// The exact rule for face-id differences (issue 24, item 5): a pixel where the
/// library's face differs from the reference's is unexplained when its centre lies
/// farther than `bound` (see [`snapping_bound`]) from every edge of the two faces
/// involved (one where the other side shows none) and is not on their intersection
/// (their depths at the centre within one pixel's depth change, the larger of the
/// two faces'). Snapping moves edges by at most the bound, so an exact engine has
/// none; a frame shifted by one pixel has thousands. Returns the count and the
/// first such pixel.
pub fn unexplained_diffs(
    frame: &Frame,
    rf: &RefFrame,
    bound: f64,
) -> (usize, Option<(usize, usize)>) {
    let (w, h) = (rf.width, rf.height);
    let (mut count, mut first) = (0, None);
    let n = rf.faces.len();
    for j in 0..h {
        for i in 0..w {
            let k = j * w + i;
            let (lib, r) = (frame.ids[k], rf.ids[k]);
            if lib == r {
                continue;
            }
            let faces: Vec<usize> = [lib, r]
                .iter()
                .filter(|&&id| id != 0)
                .map(|&id| id as usize - 1)
                .collect();
            let c = (i as f64 + 0.5, j as f64 + 0.5);
            let near_edge = faces.iter().any(|&f| {
                f < n && {
                    let s = &rf.faces[f].screen;
                    (0..s.len())
                        .any(|e| distance_to_segment(c, s[e], s[(e + 1) % s.len()]) <= bound)
                }
            });
            let on_intersection = faces.len() == 2 && faces.iter().all(|&f| f < n) && {
                let depth = |f: usize, x: f64, y: f64| rf.face_depth(f, x, y);
                let (f, g) = (faces[0], faces[1]);
                match (depth(f, c.0, c.1), depth(g, c.0, c.1)) {
                    (Some(df), Some(dg)) => {
                        let change = |f: usize, d: f64| {
                            let dx = depth(f, c.0 + 1.0, c.1).map_or(0.0, |e| (e - d).abs());
                            let dy = depth(f, c.0, c.1 + 1.0).map_or(0.0, |e| (e - d).abs());
                            dx.max(dy)
                        };
                        (df - dg).abs() <= change(f, df).max(change(g, dg))
                    }
                    _ => false,
                }
            };
            if !near_edge && !on_intersection {
                count += 1;
                first.get_or_insert((i, j));
            }
        }
    }
    (count, first)
}
