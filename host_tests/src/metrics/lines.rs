//! Line metrics (e), (f): the library's line pixels against the reference's samples.

use super::scene::LineMetrics;
use super::HIDDEN_EXCEPT_RADIUS;
use crate::frame::Frame;
use crate::reference3d::RefFrame;

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
