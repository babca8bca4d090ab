//! Error of one library frame against the f64 reference, by the definitions of
//! [`crate::metrics`], plus what the report adds:
//!
//! * face-id mismatches near edges (within 1 px of a projected edge) and away from
//!   them, as counts and as a percentage of the pixels the reference covers;
//! * edge displacement: at every pixel whose face differs from the reference's,
//!   the distance from its centre to the nearest exact (f64, unsnapped) edge of the
//!   two faces: either face's projected boundary, or the line where the two faces
//!   are at equal depth (where they interpenetrate). A centre changes face only when
//!   such an edge moved across it, so this is a lower bound of how far that edge
//!   moved (mean and maximum). For an intersection line the move comes from depth
//!   error, and grazing intersections magnify it;
//! * visible/hidden line misclassification (% of line pixels) and the missing
//!   visible and hidden length (% of the reference's length);
//! * depth-order errors, holes, wrong faces;
//! * the scene's depth complexity (most drawn faces covering one pixel centre, per
//!   the reference) next to the code bits the code-fill engine needed.

use crate::frame::Frame;
use crate::metrics::{compare_lines, compare_surfaces};
use crate::reference3d::{boundary_distance, RefFrame};

/// The error columns of one frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Errors {
    /// Pixels the reference covers.
    pub ref_covered: usize,
    pub near_diffs: usize,
    pub far_diffs: usize,
    pub holes: usize,
    pub wrong_faces: usize,
    pub depth_order: usize,
    /// Edge displacement (px) over the mismatched pixels: sum, count, maximum.
    pub edge_sum: f64,
    pub edge_count: usize,
    pub edge_max: f64,
    pub line_pixels: usize,
    pub misclassified: usize,
    pub visible_len: f64,
    pub visible_missing: f64,
    pub hidden_len: f64,
    pub hidden_missing: f64,
}

impl Errors {
    /// Face-id mismatches (near and far) per 100 pixels the reference covers.
    pub fn mismatch_pct(&self) -> f64 {
        pct(
            (self.near_diffs + self.far_diffs) as f64,
            self.ref_covered as f64,
        )
    }
    pub fn near_pct(&self) -> f64 {
        pct(self.near_diffs as f64, self.ref_covered as f64)
    }
    pub fn far_pct(&self) -> f64 {
        pct(self.far_diffs as f64, self.ref_covered as f64)
    }
    pub fn edge_mean(&self) -> f64 {
        if self.edge_count == 0 {
            0.0
        } else {
            self.edge_sum / self.edge_count as f64
        }
    }
    pub fn misclassified_pct(&self) -> f64 {
        pct(self.misclassified as f64, self.line_pixels as f64)
    }
    pub fn visible_missing_pct(&self) -> f64 {
        pct(self.visible_missing, self.visible_len)
    }
    pub fn hidden_missing_pct(&self) -> f64 {
        pct(self.hidden_missing, self.hidden_len)
    }

    /// Sums of several frames (the maximum of the maxima).
    pub fn add(&mut self, o: &Errors) {
        self.ref_covered += o.ref_covered;
        self.near_diffs += o.near_diffs;
        self.far_diffs += o.far_diffs;
        self.holes += o.holes;
        self.wrong_faces += o.wrong_faces;
        self.depth_order += o.depth_order;
        self.edge_sum += o.edge_sum;
        self.edge_count += o.edge_count;
        self.edge_max = self.edge_max.max(o.edge_max);
        self.line_pixels += o.line_pixels;
        self.misclassified += o.misclassified;
        self.visible_len += o.visible_len;
        self.visible_missing += o.visible_missing;
        self.hidden_len += o.hidden_len;
        self.hidden_missing += o.hidden_missing;
    }
}

fn pct(a: f64, b: f64) -> f64 {
    if b > 0.0 {
        100.0 * a / b
    } else {
        0.0
    }
}

/// The error of `frame` (dashed mode: ids and lines) against `rf`.
pub fn measure(frame: &Frame, rf: &RefFrame) -> Errors {
    let s = compare_surfaces(frame, rf);
    let l = compare_lines(frame, rf);
    let mut e = Errors {
        ref_covered: s.ref_covered,
        near_diffs: s.near_diffs,
        far_diffs: s.far_diffs,
        holes: s.holes,
        wrong_faces: s.wrong_faces,
        depth_order: s.depth_order,
        line_pixels: l.line_pixels,
        misclassified: l.misclassified,
        visible_len: l.visible_len,
        visible_missing: l.visible_missing,
        hidden_len: l.hidden_len,
        hidden_missing: l.hidden_missing,
        ..Errors::default()
    };
    let w = rf.width;
    for (k, (&lib, &r)) in frame.ids.iter().zip(&rf.ids).enumerate() {
        if lib == r {
            continue;
        }
        let p = ((k % w) as f64 + 0.5, (k / w) as f64 + 0.5);
        let d = [lib, r]
            .iter()
            .filter(|&&id| id != 0 && (id as usize) <= rf.faces.len())
            .map(|&id| &rf.faces[id as usize - 1].screen)
            .filter(|poly| poly.len() >= 2)
            .map(|poly| boundary_distance(poly, p))
            .fold(f64::INFINITY, f64::min)
            .min(intersection_distance(rf, lib, r, p));
        if d.is_finite() {
            e.edge_sum += d;
            e.edge_count += 1;
            e.edge_max = e.edge_max.max(d);
        }
    }
    e
}

/// Screen distance from `p` to the line where faces `a` and `b` (1 + index; 0 is
/// none) are at equal depth, their planes extended: `|g| / |grad g|` for
/// `g = 1/d_a - 1/d_b`, affine in screen space for planar faces (gradient from
/// samples half a pixel away). Infinite when either is none.
fn intersection_distance(rf: &RefFrame, a: u32, b: u32, p: (f64, f64)) -> f64 {
    let n = rf.faces.len();
    if a == 0 || b == 0 || a as usize > n || b as usize > n {
        return f64::INFINITY;
    }
    let (fa, fb) = (a as usize - 1, b as usize - 1);
    let g = |x: f64, y: f64| -> Option<f64> {
        Some(1.0 / rf.face_depth(fa, x, y)? - 1.0 / rf.face_depth(fb, x, y)?)
    };
    let (Some(g0), Some(gx), Some(gy)) = (g(p.0, p.1), g(p.0 + 0.5, p.1), g(p.0, p.1 + 0.5)) else {
        return f64::INFINITY;
    };
    let grad = (2.0 * (gx - g0)).hypot(2.0 * (gy - g0));
    if g0 == 0.0 {
        0.0
    } else if grad > 0.0 {
        g0.abs() / grad
    } else {
        f64::INFINITY
    }
}

/// The most drawn faces covering one pixel centre, per the reference.
pub fn depth_complexity(rf: &RefFrame) -> usize {
    let (w, h) = (rf.width, rf.height);
    let mut count = vec![0u32; w * h];
    for (f, face) in rf.faces.iter().enumerate() {
        if !face.drawn || face.screen.is_empty() {
            continue;
        }
        let b = face.bbox;
        let i0 = (b[0] - 0.5).ceil().max(0.0) as usize;
        let j0 = (b[1] - 0.5).ceil().max(0.0) as usize;
        let i1 = ((b[2] - 0.5).floor()).min(w as f64 - 1.0);
        let j1 = ((b[3] - 0.5).floor()).min(h as f64 - 1.0);
        if i1 < 0.0 || j1 < 0.0 {
            continue;
        }
        for j in j0..=j1 as usize {
            for i in i0..=i1 as usize {
                if rf.face_covers(f, i as f64 + 0.5, j as f64 + 0.5) {
                    count[j * w + i] += 1;
                }
            }
        }
    }
    count.into_iter().max().unwrap_or(0) as usize
}
