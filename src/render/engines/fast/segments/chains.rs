//! Counts carried along chains of drawn edges, seeded by point tests; then each
//! drawn edge's pieces.

use super::contours::{not_hiding, NotHiding};
use super::exact::{covers_nearer, orient, plane_minus, side, Pt};
use super::{fans_at, Crossing, Run, Scene, SegmentStats, SegmentWorkspace};
use crate::Error;

/// A vertex whose count is not known yet.
const UNKNOWN: i16 = i16::MIN;

impl Scene<'_, '_> {
    /// The triangles of drawn faces that `keep` takes, not around `v`, that cover
    /// `v` (moved) and are strictly nearer there.
    fn covering(&self, v: u16, keep: impl Fn(u16) -> bool, asked: &mut u32) -> i16 {
        let pv = self.p(v);
        let mut count = 0;
        for f in 0..self.mesh.face_count() as u16 {
            if !keep(f) || !self.drawn(f) {
                continue;
            }
            let corners = self.corners(f);
            for k in 1..corners.len().saturating_sub(1) {
                let t = self.fan(corners, k);
                if t.contains(&v) {
                    continue;
                }
                *asked += 1;
                let t = t.map(|c| self.p(c));
                let area = orient(t[0], t[1], t[2]);
                if area != 0 && covers_nearer(t, area, pv) {
                    count += 1;
                }
            }
        }
        count
    }

    /// `QI*(v)`, by a point test over every drawn triangle.
    fn point(&self, v: u16, stats: &mut SegmentStats) -> i16 {
        self.covering(v, |_| true, &mut stats.point_triangles)
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
                    let (pv, pu, pw): (Pt, Pt, Pt) =
                        (self.p(t[j]), self.p(t[(j + 1) % 3]), self.p(t[(j + 2) % 3]));
                    let area = orient(pv, pu, pw);
                    if area == 0 {
                        continue;
                    }
                    let s = area.signum() as i32;
                    if s * side(pv, pu, pb) > 0
                        && s * side(pw, pv, pb) > 0
                        && plane_minus([pv, pu, pw], area, pb) > 0
                    {
                        count += 1;
                    }
                }
            }
        }
        let mut unused = 0;
        count - self.covering(v, |f| own.contains(&f), &mut unused)
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
    let mut known = 0usize;
    for seed in 0..scene.edges.len() {
        let Some(run) = ws.runs.get(seed) else { break };
        if !run.drawn || run.known() {
            continue;
        }
        let v0 = scene.edges.get(seed).map_or(0, |e| e.a);
        let (mut head, mut tail) = (0usize, 0usize);
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
                let own = not_hiding(scene, e)?;
                let q = qv + scene.at_end(v, w, &own);
                let qa = if forward { q } else { q - run.total };
                run.start = qa;
                known += 1;
                let at_w = if forward { qa + run.total } else { qa };
                let qw = at_w - scene.at_end(w, v, &own);
                let Some(cw) = counts.get_mut(usize::from(w)) else {
                    continue;
                };
                if *cw == UNKNOWN {
                    *cw = qw;
                    #[cfg(feature = "std")]
                    if std::env::var_os("SEG_DEBUG").is_some() {
                        let mut unused = 0;
                        let pw = scene.covering(w, |_| true, &mut unused);
                        let pv = scene.covering(v, |_| true, &mut unused);
                        if pw != qw && pv == qv {
                            std::eprintln!(
                                "edge {i} {v}->{w}: qv {qv} at_end(v) {} total {} at_end(w) {} qw {qw} point(w) {pw} own {own:?} events {}",
                                scene.at_end(v, w, &own), run.total, scene.at_end(w, v, &own), run.len
                            );
                        }
                    }
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
        // An edge whose start vertex was known but not queued (reached, then
        // re-seeded): walked from its own start next round.
        if let Some(run) = ws.runs.get_mut(seed) {
            if !run.known() {
                let q = counts.get(usize::from(v0)).copied().unwrap_or(0);
                let own = scene.edges.get(seed).map(|e| not_hiding(scene, e));
                if let Some(Ok(own)) = own {
                    let w = scene.edges.get(seed).map_or(0, |e| e.b);
                    run.start = q + scene.at_end(v0, w, &own);
                    known += 1;
                }
            }
        }
    }
    let _ = known;
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
pub(super) fn pieces(
    _scene: &Scene<'_, '_>,
    crossings: &mut [Crossing],
    runs: &mut [Run],
    stats: &mut SegmentStats,
) {
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

#[cfg(feature = "std")]
extern crate std;

#[cfg(feature = "std")]
pub(crate) fn debug_runs(scene: &Scene<'_, '_>, runs: &[Run], crossings: &[Crossing]) {
    let mut bad = 0;
    for (i, r) in runs.iter().enumerate().filter(|(_, r)| r.drawn) {
        let e = scene.edges[i];
        let own = not_hiding(scene, &e).unwrap();
        let (a, b) = (scene.p(e.a), scene.p(e.b));
        let m = Pt {
            x: a.x + b.x,
            y: a.y + b.y,
            d: a.d + b.d,
            id: super::exact::NOT_A_VERTEX,
        };
        let mut brute = 0;
        for f in 0..scene.mesh.face_count() as u16 {
            if own.contains(&f) || !scene.drawn(f) {
                continue;
            }
            let c = scene.corners(f);
            for k in 1..c.len() - 1 {
                let t = scene.fan(c, k).map(|v| {
                    let p = scene.p(v);
                    Pt {
                        x: 2 * p.x,
                        y: 2 * p.y,
                        d: 2 * p.d,
                        id: p.id,
                    }
                });
                let area = orient(t[0], t[1], t[2]);
                if area != 0 && covers_nearer(t, area, m) {
                    brute += 1;
                }
            }
        }
        let list = &crossings[usize::from(r.first)..usize::from(r.first) + usize::from(r.len)];
        let mid_place = if (b.x - a.x).abs() >= (b.y - a.y).abs() {
            a.x + b.x
        } else {
            a.y + b.y
        } << super::PLACE_BITS;
        let low = if r.a_low { r.start } else { r.start + r.total };
        let mid = low
            + list
                .iter()
                .filter(|c| c.place < mid_place)
                .map(|c| c.delta)
                .sum::<i16>();
        if mid != brute {
            bad += 1;
            if std::env::var("SEG_EDGE")
                .ok()
                .and_then(|v| v.parse::<usize>().ok())
                == Some(i)
            {
                for num in [
                    1i32, 4, 8, 12, 15, 16, 30, 31, 62, 63, 127, 255, 511, 1023, 1024,
                ] {
                    let den = 1024;
                    let m = Pt {
                        x: a.x * (den - num) + b.x * num,
                        y: a.y * (den - num) + b.y * num,
                        d: 0,
                        id: super::exact::NOT_A_VERTEX,
                    };
                    let md = (i64::from(a.d) * i64::from(den - num)
                        + i64::from(b.d) * i64::from(num))
                        / i64::from(den);
                    let mut list = std::vec::Vec::new();
                    for f in 0..scene.mesh.face_count() as u16 {
                        if own.contains(&f) || !scene.drawn(f) {
                            continue;
                        }
                        let c = scene.corners(f);
                        for k in 1..c.len() - 1 {
                            let t = scene.fan(c, k).map(|v| {
                                let p = scene.p(v);
                                Pt {
                                    x: den * p.x,
                                    y: den * p.y,
                                    d: p.d,
                                    id: p.id,
                                }
                            });
                            let area = orient(t[0], t[1], t[2]);
                            if area != 0 && covers_nearer(t, area, Pt { d: md as i32, ..m }) {
                                list.push((f, k));
                            }
                        }
                    }
                    std::eprintln!("  at {num}/1024: {list:?}");
                }
                let pv = scene.p(e.b);
                std::eprintln!("  b = {pv:?}, a = {:?}", scene.p(e.a));
                for f in [202u16, 236, 238] {
                    let c = scene.corners(f);
                    for k in 1..c.len() - 1 {
                        let t = scene.fan(c, k);
                        let tp = t.map(|v| scene.p(v));
                        let area = orient(tp[0], tp[1], tp[2]);
                        std::eprintln!(
                            "  face {f} tri {k} {t:?}: {tp:?} covers b {}",
                            area != 0 && covers_nearer(tp, area, pv)
                        );
                    }
                }
                // Every fan triangle side that crosses the edge.
                for f in 0..scene.mesh.face_count() as u16 {
                    let c = scene.corners(f);
                    for k in 1..c.len() - 1 {
                        let t = scene.fan(c, k);
                        for j in 0..3 {
                            let (u, w) = (t[j].min(t[(j + 1) % 3]), t[j].max(t[(j + 1) % 3]));
                            if u == e.a || u == e.b || w == e.a || w == e.b {
                                continue;
                            }
                            let (p, q) = (scene.p(u), scene.p(w));
                            let (o1, o2) = (orient(p, q, a), orient(p, q, b));
                            let (o3, o4) = (orient(a, b, p), orient(a, b, q));
                            if super::exact::side_with(o1, p, q, a)
                                == super::exact::side_with(o2, p, q, b)
                            {
                                continue;
                            }
                            if super::exact::side_with(o3, a, b, p)
                                == super::exact::side_with(o4, a, b, q)
                            {
                                continue;
                            }
                            let nearer =
                                super::exact::segment_minus(a, b, p, q, o1, o2, o3, o4) < 0;
                            let r = t[(j + 2) % 3];
                            let sg = orient(p, q, scene.p(r)).signum();
                            std::eprintln!("  side {u}-{w} of face {f} tri {k}: third {r} sign {sg} nearer {nearer} t {:.3}", o1 as f64 / (o1 - o2) as f64);
                        }
                    }
                }
            }
            if bad < 15 {
                std::eprintln!("edge {i} ({}-{}): start {} total {} mid {mid} brute {brute} own {own:?} {list:?}", e.a, e.b, r.start, r.total);
            }
        }
    }
    std::eprintln!("{bad} edges mismatched at the midpoint");
}
