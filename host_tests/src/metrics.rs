//! Comparison of a library [`Frame`] with the f64 [`RefFrame`], by the definitions of the
//! issue. "Every pixel within r px" of a pixel means the pixels at Chebyshev distance
//! <= r, inside the frame (r = 1: the 3x3 block, r = 2: the 5x5 block); distances from a
//! pixel centre to geometry (a polygon, an edge, a sample) are Euclidean. (With the
//! 4-neighbourhood, a pixel centre 0.02 px inside a sliver at a concave silhouette corner,
//! legitimately lost to S = 4 snapping, counts as a hole: cow 400x240, pixel (157, 146).)
//!
//! Surfaces (the `ids` image):
//! * (a) holes: the library shows no face at a pixel, the reference shows one there and
//!   at every pixel within 1 px.
//! * (b) wrong faces: the library's face at a pixel, per the reference geometry (its
//!   near/far-clipped projected polygon), neither covers the pixel centre nor comes within
//!   1 px of it (a face index past the mesh or a face clipped away entirely counts too).
//! * (c) depth-order errors: the library's face `f` differs from the reference's and lies
//!   behind the reference's visible surface at every pixel centre within 2 px: at each
//!   such centre the reference shows a face other than `f`, and `f`'s depth along that
//!   ray (its plane extended, clamped to its depth range) exceeds the reference depth by
//!   more than a relative 1e-9.
//! * (d) face-id differences at pixels more than 1 px from every projected edge of every
//!   drawn face (edges of the near/far-clipped polygons); differences within 1 px of an
//!   edge are counted as near-edge differences and only reported.
//!
//! Lines (the `lines` image against the reference's dense samples):
//! * (e) misclassified: library line pixels (1 or 2) that have reference samples within
//!   1 px and whose class (visible/hidden) is opposite to every one of them, except
//!   pixels with, within 1.5 px, a visibility change (a sample whose neighbour on the same
//!   edge has the other class) or samples of two or more edges. Reported as a fraction of
//!   all library line pixels; limit 0.5 %. Pixels with no sample within 1 px are strays,
//!   reported only.
//! * (f) missing: the fraction of the reference's visible (hidden) projected edge length,
//!   on screen, with no visible (hidden) library line pixel centre within 1.5 px; limit
//!   1 % each. Hidden samples with a visible reference sample within 1 px are left out
//!   of the hidden length (and reported as `hidden_excepted`): where both meet, 1 wins in
//!   the lines image, so a hidden line running along or across a visible one cannot show
//!   there (the reference's own lines image fails (f) without this at 128x64).

use std::fmt;

use crate::frame::Frame;
use crate::reference::distance_to_segment;
use crate::reference3d::RefFrame;

/// Limit of (e), the misclassified fraction.
pub const MISCLASSIFIED_LIMIT: f64 = 0.005;
/// Limit of (f), the missing fraction of visible and of hidden length.
pub const MISSING_LIMIT: f64 = 0.01;
/// Hidden samples with a visible sample this close are left out of (f) ("1 wins").
pub const HIDDEN_EXCEPT_RADIUS: f64 = 1.0;

/// Surface counts of one scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceMetrics {
    pub pixels: usize,
    /// Pixels with a face: reference, library.
    pub ref_covered: usize,
    pub lib_covered: usize,
    /// (a), (b), (c), (d).
    pub holes: usize,
    pub wrong_faces: usize,
    pub depth_order: usize,
    pub far_diffs: usize,
    /// Face-id differences within 1 px of a projected edge (reported, not failed).
    pub near_diffs: usize,
    /// Library pixels showing a face the reference culls (reported).
    pub culled_face_pixels: usize,
    /// First pixel (x, y) of (a), (b), (c), (d), for reproduction.
    pub first: [Option<(usize, usize)>; 4],
}

/// Line counts of one scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LineMetrics {
    /// Library line pixels (1 or 2).
    pub line_pixels: usize,
    /// (e) count, and the excepted pixels that would otherwise count.
    pub misclassified: usize,
    pub excepted: usize,
    /// Library line pixels with no reference sample within 1 px.
    pub stray: usize,
    /// (f): reference visible / hidden length on screen (px) and the missing parts.
    pub visible_len: f64,
    pub visible_missing: f64,
    pub hidden_len: f64,
    pub hidden_missing: f64,
    /// Hidden length left out because a visible sample lies within 1 px.
    pub hidden_excepted: f64,
    /// First misclassified pixel, first visible / hidden sample point missing.
    pub first_misclassified: Option<(usize, usize)>,
    pub first_visible_missing: Option<(f64, f64)>,
    pub first_hidden_missing: Option<(f64, f64)>,
}

impl LineMetrics {
    pub fn misclassified_fraction(&self) -> f64 {
        self.misclassified as f64 / (self.line_pixels.max(1)) as f64
    }
    pub fn visible_missing_fraction(&self) -> f64 {
        if self.visible_len > 0.0 {
            self.visible_missing / self.visible_len
        } else {
            0.0
        }
    }
    pub fn hidden_missing_fraction(&self) -> f64 {
        if self.hidden_len > 0.0 {
            self.hidden_missing / self.hidden_len
        } else {
            0.0
        }
    }
}

/// The metrics of one scene (one line of the report).
#[derive(Clone, Debug, Default)]
pub struct SceneMetrics {
    pub scene: String,
    pub surfaces: Option<SurfaceMetrics>,
    pub lines: Option<LineMetrics>,
    /// Milliseconds spent in the library and in the reference.
    pub lib_ms: f64,
    pub ref_ms: f64,
}

impl SceneMetrics {
    /// `Err` with the reasons when (a)-(d) are not 0 or a line limit is exceeded.
    pub fn check(&self) -> Result<(), String> {
        let mut why = Vec::new();
        if let Some(s) = &self.surfaces {
            let names = ["holes", "wrong faces", "depth-order errors", "far id diffs"];
            let counts = [s.holes, s.wrong_faces, s.depth_order, s.far_diffs];
            for k in 0..4 {
                if counts[k] > 0 {
                    why.push(format!(
                        "{} {} (first at pixel {:?})",
                        counts[k], names[k], s.first[k]
                    ));
                }
            }
        }
        if let Some(l) = &self.lines {
            if l.misclassified_fraction() > MISCLASSIFIED_LIMIT {
                why.push(format!(
                    "misclassified line pixels {:.3}% (first at {:?})",
                    100.0 * l.misclassified_fraction(),
                    l.first_misclassified
                ));
            }
            if l.visible_missing_fraction() > MISSING_LIMIT {
                why.push(format!(
                    "visible length missing {:.3}% (first near {:?})",
                    100.0 * l.visible_missing_fraction(),
                    l.first_visible_missing
                ));
            }
            if l.hidden_missing_fraction() > MISSING_LIMIT {
                why.push(format!(
                    "hidden length missing {:.3}% (first near {:?})",
                    100.0 * l.hidden_missing_fraction(),
                    l.first_hidden_missing
                ));
            }
        }
        if why.is_empty() {
            Ok(())
        } else {
            Err(format!("{}: {}", self.scene, why.join("; ")))
        }
    }
}

impl fmt::Display for SceneMetrics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:<36}", self.scene)?;
        if let Some(s) = &self.surfaces {
            write!(
                f,
                " | px ref {:>6} lib {:>6} | holes {} wrong {} depth {} far-diff {} | near-diff {:>4} culled {}",
                s.ref_covered,
                s.lib_covered,
                s.holes,
                s.wrong_faces,
                s.depth_order,
                s.far_diffs,
                s.near_diffs,
                s.culled_face_pixels
            )?;
        }
        if let Some(l) = &self.lines {
            write!(
                f,
                " | lines {:>5} misclass {} ({:.3}%) exc {} stray {} | vis {:.0}px miss {:.3}% hid {:.0}px miss {:.3}% (exc {:.0}px)",
                l.line_pixels,
                l.misclassified,
                100.0 * l.misclassified_fraction(),
                l.excepted,
                l.stray,
                l.visible_len,
                100.0 * l.visible_missing_fraction(),
                l.hidden_len,
                100.0 * l.hidden_missing_fraction(),
                l.hidden_excepted
            )?;
        }
        write!(f, " | lib {:.0} ms ref {:.0} ms", self.lib_ms, self.ref_ms)
    }
}

/// Offsets (di, dj) with max(|di|, |dj|) <= k.
fn square(k: isize) -> Vec<(isize, isize)> {
    (-k..=k)
        .flat_map(|dj| (-k..=k).map(move |di| (di, dj)))
        .collect()
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

/// A grid of 1-px cells over [-3, W + 3) x [-3, H + 3) holding sample indices.
struct SampleGrid {
    w: usize,
    h: usize,
    cells: Vec<Vec<u32>>,
}

const PAD: f64 = 3.0;

impl SampleGrid {
    fn new(rf: &RefFrame) -> Self {
        let w = rf.width + 2 * PAD as usize;
        let h = rf.height + 2 * PAD as usize;
        let mut cells = vec![Vec::new(); w * h];
        for (k, s) in rf.samples.iter().enumerate() {
            let (x, y) = ((s.x + PAD).floor(), (s.y + PAD).floor());
            if x >= 0.0 && y >= 0.0 && x < w as f64 && y < h as f64 {
                cells[y as usize * w + x as usize].push(k as u32);
            }
        }
        SampleGrid { w, h, cells }
    }

    /// Samples within `r` of (x, y).
    fn near<'a>(
        &'a self,
        rf: &'a RefFrame,
        x: f64,
        y: f64,
        r: f64,
    ) -> impl Iterator<Item = usize> + 'a {
        let x0 = (x - r + PAD).floor().max(0.0) as usize;
        let x1 = ((x + r + PAD).floor().max(-1.0) as isize).min(self.w as isize - 1);
        let y0 = (y - r + PAD).floor().max(0.0) as usize;
        let y1 = ((y + r + PAD).floor().max(-1.0) as isize).min(self.h as isize - 1);
        (y0 as isize..=y1)
            .flat_map(move |cy| (x0 as isize..=x1).map(move |cx| (cx, cy)))
            .flat_map(move |(cx, cy)| self.cells[cy as usize * self.w + cx as usize].iter())
            .map(|&k| k as usize)
            .filter(move |&k| {
                let s = &rf.samples[k];
                (s.x - x).powi(2) + (s.y - y).powi(2) <= r * r
            })
    }
}

/// Line metrics (e), (f) of the library `lines` against the reference samples.
pub fn compare_lines(frame: &Frame, rf: &RefFrame) -> LineMetrics {
    let (w, h) = (rf.width, rf.height);
    assert_eq!((frame.width, frame.height), (w, h), "frame size");
    assert_eq!(frame.lines.len(), w * h, "lines size");
    let grid = SampleGrid::new(rf);
    let n = rf.samples.len();
    let change: Vec<bool> = (0..n)
        .map(|k| {
            let s = &rf.samples[k];
            let differs =
                |o: usize| rf.samples[o].edge == s.edge && rf.samples[o].visible != s.visible;
            (k > 0 && differs(k - 1)) || (k + 1 < n && differs(k + 1))
        })
        .collect();
    let mut m = LineMetrics::default();
    for j in 0..h {
        for i in 0..w {
            let v = frame.lines[j * w + i];
            if v == 0 {
                continue;
            }
            m.line_pixels += 1;
            let visible = v == 1;
            let (cx, cy) = (i as f64 + 0.5, j as f64 + 0.5);
            let mut any = false;
            let mut all_opposite = true;
            for k in grid.near(rf, cx, cy, 1.0) {
                any = true;
                if rf.samples[k].visible == visible {
                    all_opposite = false;
                    break;
                }
            }
            if !any {
                m.stray += 1;
                continue;
            }
            if !all_opposite {
                continue;
            }
            let mut edge = None;
            let excepted = grid.near(rf, cx, cy, 1.5).any(|k| {
                let e = rf.samples[k].edge;
                let other = *edge.get_or_insert(e) != e;
                change[k] || other
            });
            if excepted {
                m.excepted += 1;
            } else {
                m.misclassified += 1;
                if m.first_misclassified.is_none() {
                    m.first_misclassified = Some((i, j));
                }
            }
        }
    }
    let has_line_near = |x: f64, y: f64, want: u8| {
        let i0 = (x - 2.0).floor().max(0.0) as usize;
        let i1 = ((x + 1.5).floor().max(-1.0) as isize).min(w as isize - 1);
        let j0 = (y - 2.0).floor().max(0.0) as usize;
        let j1 = ((y + 1.5).floor().max(-1.0) as isize).min(h as isize - 1);
        (j0 as isize..=j1).any(|j| {
            (i0 as isize..=i1).any(|i| {
                let (cx, cy) = (i as f64 + 0.5, j as f64 + 0.5);
                frame.lines[j as usize * w + i as usize] == want
                    && (cx - x).powi(2) + (cy - y).powi(2) <= 1.5 * 1.5
            })
        })
    };
    for s in &rf.samples {
        if !(s.x >= 0.0 && s.y >= 0.0 && s.x < w as f64 && s.y < h as f64) {
            continue;
        }
        if !s.visible
            && grid
                .near(rf, s.x, s.y, HIDDEN_EXCEPT_RADIUS)
                .any(|k| rf.samples[k].visible)
        {
            m.hidden_excepted += s.weight;
            continue;
        }
        let want = if s.visible { 1 } else { 2 };
        let found = has_line_near(s.x, s.y, want);
        if s.visible {
            m.visible_len += s.weight;
            if !found {
                m.visible_missing += s.weight;
                m.first_visible_missing.get_or_insert((s.x, s.y));
            }
        } else {
            m.hidden_len += s.weight;
            if !found {
                m.hidden_missing += s.weight;
                m.first_hidden_missing.get_or_insert((s.x, s.y));
            }
        }
    }
    m
}

/// Both comparisons (as the mode asks: `surfaces` for the ids, `lines` for the lines).
pub fn compare(
    scene: &str,
    frame: &Frame,
    rf: &RefFrame,
    surfaces: bool,
    lines: bool,
) -> SceneMetrics {
    SceneMetrics {
        scene: scene.to_string(),
        surfaces: surfaces.then(|| compare_surfaces(frame, rf)),
        lines: lines.then(|| compare_lines(frame, rf)),
        lib_ms: 0.0,
        ref_ms: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::RenderSpec;
    use crate::reference3d::reference_frame;
    use crate::shapes;

    fn refs() -> Vec<(String, RefFrame)> {
        let mut v = Vec::new();
        for s in shapes::all_scenes() {
            for (w, h, ortho) in [(128, 64, false), (200, 120, true)] {
                let spec = RenderSpec {
                    width: w,
                    height: h,
                    band: h,
                    ..RenderSpec::default()
                };
                let cam = s.camera(w, h, ortho);
                v.push((
                    format!("{} {w}x{h}{}", s.name, if ortho { " ortho" } else { "" }),
                    reference_frame(&s.mesh, &cam, &spec).unwrap(),
                ));
            }
        }
        v
    }

    #[test]
    fn reference_against_itself_is_clean() {
        for (name, rf) in refs() {
            let m = compare(&name, &rf.to_frame(), &rf, true, true);
            println!("{m}");
            m.check().unwrap();
            let s = m.surfaces.as_ref().unwrap();
            assert_eq!(s.near_diffs, 0);
            let l = m.lines.as_ref().unwrap();
            assert_eq!(l.misclassified + l.excepted + l.stray, 0, "{name}");
        }
    }

    #[test]
    fn perturbed_frames_fail() {
        for (name, rf) in refs() {
            let (w, h) = (rf.width, rf.height);
            // Shifted ids by 3 px: wrong faces / far diffs.
            let mut f = rf.to_frame();
            for j in 0..h {
                for i in 0..w {
                    f.ids[j * w + i] = if i >= 3 { rf.ids[j * w + i - 3] } else { 0 };
                }
            }
            let s = compare_surfaces(&f, &rf);
            assert!(
                s.holes > 0 && s.wrong_faces > 0 && s.far_diffs > 0,
                "{name} {s:?}"
            );
            // A 4x4 hole in the middle of the object.
            let mut f = rf.to_frame();
            let covered: Vec<usize> = (0..w * h).filter(|&k| rf.ids[k] != 0).collect();
            let c = covered[covered.len() / 2];
            let (ci, cj) = (c % w, c / w);
            for j in cj.saturating_sub(2)..(cj + 2).min(h) {
                for i in ci.saturating_sub(2)..(ci + 2).min(w) {
                    f.ids[j * w + i] = 0;
                }
            }
            let s = compare_surfaces(&f, &rf);
            assert!(s.holes > 0, "{name} {s:?}");
            // Painter's order reversed: the farthest face wins everywhere.
            let mut f = rf.to_frame();
            let mut far = vec![f64::NEG_INFINITY; w * h];
            f.ids.iter_mut().for_each(|i| *i = 0);
            for face in 0..rf.faces.len() {
                if !rf.faces[face].drawn {
                    continue;
                }
                for (k, (fk, id)) in far.iter_mut().zip(f.ids.iter_mut()).enumerate() {
                    let (x, y) = ((k % w) as f64 + 0.5, (k / w) as f64 + 0.5);
                    if rf.face_covers(face, x, y) {
                        let d = rf.face_depth(face, x, y).unwrap();
                        if d > *fk {
                            *fk = d;
                            *id = face as u32 + 1;
                        }
                    }
                }
            }
            let s = compare_surfaces(&f, &rf);
            if name.starts_with("cube") || name.starts_with("icosphere") {
                // convex and culled: no overlap, nothing to get wrong
                assert_eq!(s.depth_order, 0, "{name}");
            } else {
                assert!(s.depth_order > 0, "{name} {s:?}");
            }
            // Lines: all pixels visible, or all hidden, or none.
            let mut f = rf.to_frame();
            let l = &mut f.lines;
            l.iter_mut().filter(|v| **v != 0).for_each(|v| *v = 1);
            let lm = compare_lines(&f, &rf);
            if lm.hidden_len > 10.0 {
                assert!(
                    lm.misclassified_fraction() > MISCLASSIFIED_LIMIT,
                    "{name} {lm:?}"
                );
                assert!(
                    lm.hidden_missing_fraction() > MISSING_LIMIT,
                    "{name} {lm:?}"
                );
            }
            let mut f = rf.to_frame();
            f.lines.iter_mut().filter(|v| **v != 0).for_each(|v| *v = 2);
            let lm = compare_lines(&f, &rf);
            assert!(
                lm.misclassified_fraction() > MISCLASSIFIED_LIMIT,
                "{name} {lm:?}"
            );
            assert!(
                lm.visible_missing_fraction() > MISSING_LIMIT,
                "{name} {lm:?}"
            );
            // Lines shifted by 3 px: fails.
            let mut f = rf.to_frame();
            for j in 0..h {
                for i in 0..w {
                    f.lines[j * w + i] = if j >= 3 { rf.lines[(j - 3) * w + i] } else { 0 };
                }
            }
            let lm = compare_lines(&f, &rf);
            assert!(
                lm.visible_missing_fraction() > MISSING_LIMIT,
                "{name} {lm:?}"
            );
            assert!(lm.stray > 0, "{name} {lm:?}");
        }
    }
}
