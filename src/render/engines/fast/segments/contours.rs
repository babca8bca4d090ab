//! Contour edges, their screen grid, and each drawn edge's crossings with the
//! nearer ones.

use super::exact::{orient, segment_minus, side_with, Pt};
use super::piercings::pierce;
use super::sides::{edge_between, edge_faces, not_hiding, side_record, NotHiding};
use super::{
    place_between, turn, Contour, Crossing, Run, Scene, SegmentLists, SegmentStats, MAX_GRID_CELLS,
};
use crate::bits::set_bit;
use crate::{Capacity, Error};

/// Finds the frame's contours into `out`: the mesh's edges and its faces' fan
/// diagonals whose drawn triangles do not lie one on each side. `None`: a
/// contour has an end outside.
pub(super) fn find(
    scene: &Scene<'_, '_>,
    out: &mut [Contour],
    marks: &mut [u32],
) -> Result<Option<usize>, Error> {
    let mut n = 0usize;
    marks.fill(0);
    let mut spare = Contour::default();
    // The record of side `p`-`q` in the next slot (in `spare` once the list is
    // full, to count the need): `Some(true)` a contour, kept; `None` a contour
    // with an end outside.
    let mut record =
        |p: u16, q: u16, faces: &[u16], n: &mut usize, marks: &mut [u32], folds: &mut i32| {
            let slot = match out.get_mut(*n) {
                Some(slot) => slot,
                None => &mut spare,
            };
            if side_record(scene, p, q, faces, slot, folds)? == 0 {
                return Ok::<_, Error>(Some(false));
            }
            if !scene.inside(p) || !scene.inside(q) {
                return Ok(None);
            }
            set_bit(marks, usize::from(p), true);
            set_bit(marks, usize::from(q), true);
            *n += 1;
            Ok(Some(true))
        };
    let mut faces = NotHiding::new();
    let mut folds = 0;
    for e in scene.edges {
        edge_faces(scene, e, &mut faces)?;
        if record(e.a, e.b, &faces, &mut n, marks, &mut folds)?.is_none() {
            return Ok(None);
        }
    }
    for f in 0..scene.mesh.face_count() as u16 {
        let corners = scene.corners(f);
        for i in 2..corners.len().saturating_sub(1) {
            let t = scene.fan(corners, i);
            let (p, q) = (t[0].min(t[1]), t[0].max(t[1]));
            let Some(contour) = record(p, q, &[f], &mut n, marks, &mut folds)? else {
                return Ok(None);
            };
            if contour || folds != 0 {
                // A fold: every corner of the face sees it.
                for k in 0..corners.len() {
                    set_bit(marks, usize::from(scene.corner(corners, k)), true);
                }
            }
        }
    }
    if n > out.len() {
        return Err(Error::CapacityExceeded {
            what: Capacity::ContourEdges,
            needed: n,
            capacity: out.len(),
        });
    }
    Ok(Some(n))
}

/// The contour grid: cells of `2^shift` sub-pixel units, `cols` x `rows`, each
/// cell's contours in `lists.entries` from `lists.cells`.
pub(super) struct Grid {
    shift: u32,
    cols: i32,
    rows: i32,
}

impl Grid {
    /// The cells' range of a screen box (clamped to the grid, so that boxes off
    /// the frame meet in its border cells).
    fn range(&self, lo: (i32, i32), hi: (i32, i32)) -> (i32, i32, i32, i32) {
        let cell = |v: i32, n: i32| (v >> self.shift).clamp(0, n - 1);
        (
            cell(lo.0, self.cols),
            cell(hi.0, self.cols),
            cell(lo.1, self.rows),
            cell(hi.1, self.rows),
        )
    }

    /// Bins the first `n` contours of `lists` by their boxes.
    pub(super) fn build(
        scene: &Scene<'_, '_>,
        lists: &mut SegmentLists<'_>,
        n: usize,
        stats: &mut SegmentStats,
    ) -> Result<Self, Error> {
        let (w, h) = (i32::from(scene.width), i32::from(scene.height));
        let mut px = 4;
        while ((w + (1 << px) - 1) >> px) * ((h + (1 << px) - 1) >> px) > MAX_GRID_CELLS as i32 {
            px += 1;
        }
        let grid = Grid {
            shift: px + scene.s,
            cols: ((w + (1 << px) - 1) >> px).max(1),
            rows: ((h + (1 << px) - 1) >> px).max(1),
        };
        let cells = (grid.cols * grid.rows) as usize;
        let starts = lists.cells.get_mut(..=cells).unwrap_or_default();
        starts.fill(0);
        let contours = lists.contours.get(..n).unwrap_or_default();
        let boxes = |c: &Contour| grid.range(c.lo_i32(), c.hi_i32());
        for c in contours {
            let (x0, x1, y0, y1) = boxes(c);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    if let Some(s) = starts.get_mut((y * grid.cols + x) as usize + 1) {
                        *s += 1;
                    }
                }
            }
        }
        let mut total = 0usize;
        for s in starts.iter_mut() {
            total += usize::from(*s);
            *s = total as u16;
        }
        stats.grid_entries += total as u32;
        crate::error::need(Capacity::GridEntries, total, lists.entries.len())?;
        if total > usize::from(u16::MAX) {
            return Err(Error::CapacityExceeded {
                what: Capacity::GridEntries,
                needed: total,
                capacity: usize::from(u16::MAX),
            });
        }
        for (i, c) in contours.iter().enumerate().rev() {
            let (x0, x1, y0, y1) = boxes(c);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    if let Some(s) = starts.get_mut((y * grid.cols + x) as usize + 1) {
                        *s -= 1;
                        if let Some(slot) = lists.entries.get_mut(usize::from(*s)) {
                            *slot = i as u16;
                        }
                    }
                }
            }
        }
        for i in 0..cells {
            let next = starts.get(i + 1).copied().unwrap_or(0);
            if let Some(s) = starts.get_mut(i) {
                *s = next;
            }
        }
        if let Some(s) = starts.get_mut(cells) {
            *s = total as u16;
        }
        Ok(grid)
    }
}

/// One drawn edge's crossing test: its ends, its major axis, its faces that do
/// not hide it.
struct Line<'o> {
    a: Pt,
    b: Pt,
    lo: (i32, i32),
    hi: (i32, i32),
    x_major: bool,
    own: &'o [u16],
}

impl Line<'_> {
    /// The crossing with contour `c` when the contour is nearer there and the
    /// count changes: its place and the change.
    #[inline(always)]
    fn cross(
        &self,
        scene: &Scene<'_, '_>,
        c: &Contour,
        stats: &mut SegmentStats,
    ) -> Option<Crossing> {
        let (a, b) = (self.a, self.b);
        if !self.box_meets(c.lo_i32(), c.hi_i32()) {
            return None;
        }
        if c.a == a.id || c.a == b.id || c.b == a.id || c.b == b.id {
            return None;
        }
        let (p, q) = (scene.p(c.a), scene.p(c.b));
        stats.pair_tests += 1;
        let (o1, o2, o3, o4, s2) = self.straddle(p, q)?;
        stats.crossings += 1;
        if segment_minus(a, b, p, q, o1, o2, o3, o4) >= 0 {
            return None;
        }
        stats.nearer += 1;
        let mut plus = 0i16;
        for (f, s) in c.faces.iter().zip(c.sides).take(usize::from(c.count)) {
            if !self.own.contains(f) {
                plus += i16::from(s);
            }
        }
        if plus == 0 {
            return None;
        }
        Some(Crossing {
            place: self.place(o1, o2),
            delta: if s2 > 0 { plus } else { -plus },
        })
    }

    /// Do `p`-`q` and the edge cross on screen (the test of [`cross`](Self::cross))?
    fn meets(&self, p: Pt, q: Pt) -> bool {
        let (lo, hi) = ((p.x.min(q.x), p.y.min(q.y)), (p.x.max(q.x), p.y.max(q.y)));
        self.box_meets(lo, hi) && self.straddle(p, q).is_some()
    }

    /// Does the screen box `lo`..`hi` meet the edge's?
    #[inline(always)]
    fn box_meets(&self, lo: (i32, i32), hi: (i32, i32)) -> bool {
        hi.0 >= self.lo.0 && lo.0 <= self.hi.0 && hi.1 >= self.lo.1 && lo.1 <= self.hi.1
    }

    /// Where `p`-`q` and the edge cross on screen (each pair of ends on the two
    /// sides of the other segment, moved as [`side_with`] moves them): the
    /// orientations of `a`, `b` to `p`-`q` and of `p`, `q` to `a`-`b`, and the
    /// side of `b`.
    #[inline(always)]
    fn straddle(&self, p: Pt, q: Pt) -> Option<(i64, i64, i64, i64, i32)> {
        let (a, b) = (self.a, self.b);
        let (o1, o2) = (orient(p, q, a), orient(p, q, b));
        let s2 = side_with(o2, p, q, b);
        if side_with(o1, p, q, a) == s2 {
            return None;
        }
        let (o3, o4) = (orient(a, b, p), orient(a, b, q));
        if side_with(o3, a, b, p) == side_with(o4, a, b, q) {
            return None;
        }
        Some((o1, o2, o3, o4, s2))
    }

    /// Where `a + (b - a) o1 / (o1 - o2)` lies along the major axis, in
    /// `2^-(S+1+PLACE_BITS)` px (rounded in `f32`: it only places a pixel).
    fn place(&self, o1: i64, o2: i64) -> i32 {
        let (ua, ub) = if self.x_major {
            (self.a.x, self.b.x)
        } else {
            (self.a.y, self.b.y)
        };
        place_between(ua, ub, o1, o2)
    }
}

/// Each drawn edge's crossings with nearer contours (from the grid) and with
/// the plain sides of its own faces' triangles (across which the count changes by
/// the triangle beyond), sorted along the edge, into `lists.crossings`; each
/// drawn edge's `first`, `len`, `total` and `a_low` in `runs`.
pub(super) fn cross_all(
    scene: &Scene<'_, '_>,
    lists: &mut SegmentLists<'_>,
    grid: &Grid,
    contours: usize,
    runs: &mut [Run],
    stats: &mut SegmentStats,
) -> Result<(), Error> {
    let stamps = lists.stamps.get_mut(..contours).unwrap_or_default();
    stamps.fill(0);
    let mut stamp = 0u16;
    let mut used = 0usize;
    let capacity = lists.crossings.len();
    let mut short = false;
    let mut pairs = scene.piercings;
    let (mut own, mut faces) = (NotHiding::new(), NotHiding::new());
    let mut side = Contour::default();
    let mut folds = 0;
    for (index, (e, run)) in scene.edges.iter().zip(runs.iter_mut()).enumerate() {
        // The edge's piercing pairs (sorted by edge).
        let skip = pairs.partition_point(|p| usize::from(p.edge) < index);
        pairs = pairs.get(skip..).unwrap_or_default();
        let mine = pairs.partition_point(|p| usize::from(p.edge) == index);
        let (own_pairs, rest) = pairs.split_at(mine.min(pairs.len()));
        pairs = rest;
        if !run.drawn {
            continue;
        }
        if stamp == u16::MAX {
            stamps.fill(0);
            stamp = 0;
        }
        stamp += 1;
        not_hiding(scene, e, &mut own)?;
        let (a, b) = (scene.p(e.a), scene.p(e.b));
        let line = Line {
            a,
            b,
            lo: (a.x.min(b.x), a.y.min(b.y)),
            hi: (a.x.max(b.x), a.y.max(b.y)),
            x_major: (b.x - a.x).abs() >= (b.y - a.y).abs(),
            own: &own,
        };
        let first = used;
        let mut add = |c: Crossing, used: &mut usize| {
            if let Some(slot) = lists.crossings.get_mut(*used) {
                *slot = c;
            } else {
                short = true;
            }
            *used += 1;
        };
        let (x0, x1, y0, y1) = grid.range(line.lo, line.hi);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let cell = (y * grid.cols + x) as usize;
                let (s, t) = (
                    lists.cells.get(cell).copied().unwrap_or(0),
                    lists.cells.get(cell + 1).copied().unwrap_or(0),
                );
                for &i in lists
                    .entries
                    .get(usize::from(s)..usize::from(t))
                    .unwrap_or(&[])
                {
                    let Some(mark) = stamps.get_mut(usize::from(i)) else {
                        continue;
                    };
                    if *mark == stamp {
                        continue;
                    }
                    *mark = stamp;
                    if let Some(c) = lists.contours.get(usize::from(i)) {
                        if let Some(x) = line.cross(scene, c, stats) {
                            add(x, &mut used);
                        }
                    }
                }
            }
        }
        // The plain sides of the own faces' triangles away from the edge.
        for &f in own.iter() {
            let corners = scene.corners(f);
            for k in 1..corners.len().saturating_sub(1) {
                let t = scene.fan(corners, k);
                for j in 0..3 {
                    let [x, y, _] = turn(t, j);
                    let (u, v) = (x.min(y), x.max(y));
                    if u == v || u == e.a || u == e.b || v == e.a || v == e.b {
                        continue;
                    }
                    // Most never cross the edge on screen: tested first.
                    if !line.meets(scene.p(u), scene.p(v)) {
                        continue;
                    }
                    let diagonal = j == 2 && k + 2 < corners.len() || j == 0 && k > 1;
                    let sum = if diagonal {
                        side_record(scene, u, v, &[f], &mut side, &mut folds)?
                    } else {
                        match edge_between(scene.edges, u, v) {
                            Some(m) => {
                                edge_faces(scene, m, &mut faces)?;
                                side_record(scene, u, v, &faces, &mut side, &mut folds)?
                            }
                            None => side_record(scene, u, v, &[f], &mut side, &mut folds)?,
                        }
                    };
                    if sum != 0 {
                        continue;
                    }
                    if let Some(x) = line.cross(scene, &side, stats) {
                        add(x, &mut used);
                    }
                }
            }
        }
        for p in own_pairs {
            if own.contains(&p.face) || !scene.drawn(p.face) {
                continue;
            }
            let corners = scene.corners(p.face);
            let t = scene.fan(corners, usize::from(p.fan)).map(|v| scene.p(v));
            if let Some(mut x) = pierce(a, b, t, line.x_major) {
                stats.piercings += 1;
                x.delta *= scene.counts_as(corners, orient(t[0], t[1], t[2]));
                add(x, &mut used);
            }
        }
        if short {
            continue;
        }
        let list = lists.crossings.get_mut(first..used).unwrap_or_default();
        // Insertion sort: a few crossings an edge.
        for i in 1..list.len() {
            let mut j = i;
            while j > 0 {
                match (list.get(j - 1), list.get(j)) {
                    (Some(x), Some(y)) if x.place > y.place => list.swap(j - 1, j),
                    _ => break,
                }
                j -= 1;
            }
        }
        // Changes from the low end up; the total from `a` to `b`.
        run.a_low = if line.x_major { a.x <= b.x } else { a.y <= b.y };
        let sum: i16 = list.iter().map(|c| c.delta).sum();
        if !run.a_low {
            for c in list.iter_mut() {
                c.delta = -c.delta;
            }
        }
        run.first = first as u16;
        run.len = (used - first) as u16;
        run.total = sum;
    }
    stats.kept += used as u32;
    if short || used > usize::from(u16::MAX) {
        return Err(Error::CapacityExceeded {
            what: Capacity::Crossings,
            needed: used,
            capacity: capacity.min(usize::from(u16::MAX)),
        });
    }
    Ok(())
}
