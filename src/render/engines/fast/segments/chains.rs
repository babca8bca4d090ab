//! Counts carried along chains of drawn edges, seeded by point tests; then each
//! drawn edge's pieces.

use super::exact::{covers_nearer, orient, plane_minus, side, Pt};
use super::sides::{not_hiding, NotHiding};
use super::{fans_at, turn, Crossing, Run, Scene, SegmentStats, SegmentWorkspace};
use crate::bits::bit;
use crate::Error;

/// A vertex whose count is not known yet.
const UNKNOWN: i16 = i16::MIN;

impl Scene<'_, '_> {
    /// The triangles of the drawn ones of `faces`, not around `v`, that cover `v`
    /// (moved) and are strictly nearer there.
    fn covering(&self, v: u16, faces: impl Iterator<Item = u16>, asked: &mut u32) -> i16 {
        let pv = self.p(v);
        let mut count = 0;
        for f in faces {
            if !self.drawn(f) {
                continue;
            }
            let corners = self.corners(f);
            for k in 1..corners.len().saturating_sub(1) {
                let t = self.fan(corners, k);
                let pt = t.map(|c| self.p(c));
                // Most triangles are far from the point: their box tells.
                let outside = |coord: fn(&Pt) -> i32| {
                    let (lo, hi) = pt
                        .iter()
                        .map(coord)
                        .fold((i32::MAX, i32::MIN), |(l, h), x| (l.min(x), h.max(x)));
                    coord(&pv) < lo || coord(&pv) > hi
                };
                if outside(|p| p.x) || outside(|p| p.y) || t.contains(&v) {
                    continue;
                }
                *asked += 1;
                let t = pt;
                let area = orient(t[0], t[1], t[2]);
                if area != 0 && covers_nearer(t, area, pv) {
                    count += self.counts_as(corners, area);
                }
            }
        }
        count
    }

    /// `QI*(v)`, by a point test over every drawn triangle.
    fn point(&self, v: u16, stats: &mut SegmentStats) -> i16 {
        let faces = 0..self.mesh.face_count() as u16;
        self.covering(v, faces, &mut stats.point_triangles)
    }

    /// The count at `v` of edge `v`-`b` (faces `own` not hiding it) less `QI*(v)`:
    /// the triangles around `v` (not of `own`) that cover the edge next to `v`
    /// and are nearer there, less those of `own` not around `v` that cover `v`
    /// (counted in `QI*(v)`, but not over this edge).
    fn at_end(&self, v: u16, b: u16, own: &NotHiding) -> i16 {
        let pb = self.p(b);
        let mut count = 0;
        let around = self.around.around(v);
        for (i, &f) in around.iter().enumerate() {
            let again = i > 0 && around.get(i - 1) == Some(&f);
            if again || own.contains(&f) || !self.drawn(f) {
                continue;
            }
            let corners = self.corners(f);
            let n = corners.len();
            for k in (0..n).filter(|&k| self.corner(corners, k) == v) {
                for i in fans_at(n, k) {
                    let t = self.fan(corners, i);
                    let j = t.iter().position(|&c| c == v).unwrap_or(0);
                    let (pv, pu, pw): (Pt, Pt, Pt) = {
                        let [x, y, z] = turn(t, j);
                        (self.p(x), self.p(y), self.p(z))
                    };
                    let area = orient(pv, pu, pw);
                    if area == 0 {
                        continue;
                    }
                    let s = area.signum() as i32;
                    if s * side(pv, pu, pb) > 0
                        && s * side(pw, pv, pb) > 0
                        && plane_minus([pv, pu, pw], area, pb) > 0
                    {
                        count += self.counts_as(corners, area);
                    }
                }
            }
        }
        let mut unused = 0;
        count - self.covering(v, own.iter().copied(), &mut unused)
    }
}

/// Gives every drawn edge its count at end `a` (`runs[e].start`): chains from
/// point-tested seeds, the counts at each vertex carried over and checked.
pub(super) fn propagate(
    scene: &Scene<'_, '_>,
    ws: &mut SegmentWorkspace<'_>,
    stats: &mut SegmentStats,
) -> Result<(), Error> {
    let n = scene.mesh.vertices().len();
    let marks: &[u32] = ws.marks;
    let counts = ws.counts.get_mut(..n).unwrap_or_default();
    counts.fill(UNKNOWN);
    // The drawn edges at each vertex.
    let starts = ws.starts.get_mut(..=n).unwrap_or_default();
    starts.fill(0);
    for (e, run) in scene.edges.iter().zip(ws.runs.iter()) {
        if run.drawn {
            for v in [e.a, e.b] {
                if let Some(s) = starts.get_mut(usize::from(v) + 1) {
                    *s += 1;
                }
            }
        }
    }
    let mut total = 0u16;
    for s in starts.iter_mut() {
        total += *s;
        *s = total;
    }
    for (i, (e, run)) in scene.edges.iter().zip(ws.runs.iter()).enumerate().rev() {
        if run.drawn {
            for v in [e.a, e.b] {
                if let Some(s) = starts.get_mut(usize::from(v) + 1) {
                    *s -= 1;
                    if let Some(slot) = ws.at.get_mut(usize::from(*s)) {
                        *slot = i as u16;
                    }
                }
            }
        }
    }
    for i in 0..n {
        let next = starts.get(i + 1).copied().unwrap_or(0);
        if let Some(s) = starts.get_mut(i) {
            *s = next;
        }
    }
    if let Some(s) = starts.get_mut(n) {
        *s = total;
    }
    for seed in 0..scene.edges.len() {
        let Some(run) = ws.runs.get(seed) else { break };
        if !run.drawn || run.known() {
            continue;
        }
        let v0 = scene.edges.get(seed).map_or(0, |e| e.a);
        let (mut head, mut tail) = (0usize, 0usize);
        let mut own = NotHiding::new();
        if counts.get(usize::from(v0)) == Some(&UNKNOWN) {
            stats.seeds += 1;
            if let Some(c) = counts.get_mut(usize::from(v0)) {
                *c = scene.point(v0, stats);
            }
            if let Some(q) = ws.queue.get_mut(tail) {
                *q = v0;
                tail += 1;
            }
        }
        while head < tail {
            let v = ws.queue.get(head).copied().unwrap_or(0);
            head += 1;
            let qv = counts.get(usize::from(v)).copied().unwrap_or(0);
            let (s, t) = (
                starts.get(usize::from(v)).copied().unwrap_or(0),
                starts.get(usize::from(v) + 1).copied().unwrap_or(0),
            );
            for slot in s..t {
                let i = usize::from(ws.at.get(usize::from(slot)).copied().unwrap_or(0));
                let (Some(e), Some(run)) = (scene.edges.get(i), ws.runs.get_mut(i)) else {
                    continue;
                };
                if run.known() {
                    continue;
                }
                let forward = e.a == v;
                let w = if forward { e.b } else { e.a };
                // The terms at an end are 0 where no contour or fold touches the
                // vertex and its fan is regular (its triangles tile a disk once),
                // unless the edge may be an outline: then faces beyond its own
                // may not hide it, and one of them may cover the end.
                let outline = scene.may_be_outline(e);
                let folded = [v, w]
                    .map(|x| outline || bit(marks, usize::from(x)) || scene.around.is_irregular(x));
                if folded[0] || folded[1] {
                    not_hiding(scene, e, &mut own)?;
                }
                let end = |x: u16, y: u16, marked: bool| {
                    if marked {
                        scene.at_end(x, y, &own)
                    } else {
                        0
                    }
                };
                let q = qv + end(v, w, folded[0]);
                let qa = if forward { q } else { q - run.total };
                run.start = qa;
                let at_w = if forward { qa + run.total } else { qa };
                let qw = at_w - end(w, v, folded[1]);
                let Some(cw) = counts.get_mut(usize::from(w)) else {
                    continue;
                };
                if *cw == UNKNOWN {
                    *cw = qw;
                    if let Some(q) = ws.queue.get_mut(tail) {
                        *q = w;
                        tail += 1;
                    }
                } else if *cw != qw {
                    stats.reseeds += 1;
                    *cw = scene.point(w, stats);
                }
            }
        }
    }
    Ok(())
}

impl Run {
    /// Has the chains' walk given it its count?
    fn known(&self) -> bool {
        self.start != UNKNOWN
    }
}

/// Turns each drawn edge's crossings into its pieces: the places where its
/// count turns between 0 (visible) and more (hidden), from its low end, written
/// over its crossings.
pub(super) fn pieces(crossings: &mut [Crossing], runs: &mut [Run], stats: &mut SegmentStats) {
    for run in runs.iter_mut().filter(|r| r.drawn) {
        let (first, len) = (usize::from(run.first), usize::from(run.len));
        let list = crossings.get_mut(first..first + len).unwrap_or_default();
        let mut q = if run.a_low {
            run.start
        } else {
            run.start + run.total
        };
        let low = q > 0;
        let mut hidden = low;
        let mut kept = 0usize;
        for i in 0..list.len() {
            let c = list.get(i).copied().unwrap_or_default();
            q += c.delta;
            if q < 0 {
                stats.negative += 1;
            }
            if (q > 0) != hidden {
                hidden = q > 0;
                if let Some(slot) = list.get_mut(kept) {
                    slot.place = c.place;
                }
                kept += 1;
            }
        }
        run.hidden = low;
        run.len = kept as u16;
        stats.boundaries += kept as u32;
    }
}
