//! The rays: a pixel's covering faces kept nearest first and closed under ties
//! ([`Candidates`]), the trace through the tree, a tile's face list and the walk
//! along it, and the exhaustive pass in index order for the pixels the pruned
//! trace cannot decide.

use heapless::Vec;

use super::{Cast, TILE_FACES};
use crate::render::depth::coverage::covers_centre;
use crate::render::depth::fan::fan_depth_at;
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::{face_polygon, FrameCtx};
use crate::Error;

/// Depth of the trace stack. A median split halves the faces at each level, so a
/// tree over at most 65 535 faces is at most 16 levels deep below the root and the
/// depth-first stack holds at most one entry per level plus one.
const STACK: usize = 40;

/// Covering faces a trace keeps (the nearest ones, within ties of each other). More
/// than this at one pixel sends the pixel to the exhaustive pass.
const CANDIDATES: usize = 8;

/// A covering face met by a ray.
#[derive(Debug, Clone, Copy)]
pub(super) struct Hit {
    pub(super) face: u16,
    pub(super) entry: u32,
    pub(super) q: u32,
    pub(super) tie: u32,
}

/// The nearest covering faces of one ray, nearest first, kept closed under ties.
pub(super) struct Candidates {
    hits: Vec<Hit, CANDIDATES>,
    /// Faces below `floor` cannot change the pixel (if the floor is final).
    pub(super) floor: i64,
    /// The largest nearness bound of anything set aside (pruned or dropped); -1 none.
    pub(super) lost: i64,
}

impl Candidates {
    pub(super) fn new() -> Self {
        Self {
            hits: Vec::new(),
            floor: i64::MIN,
            lost: -1,
        }
    }

    /// Sets aside something whose nearness is at most `bound`.
    pub(super) fn lose(&mut self, bound: u32) {
        self.lost = self.lost.max(i64::from(bound));
    }

    pub(super) fn insert(&mut self, hit: Hit) {
        if self.hits.is_full() {
            match self.hits.last() {
                Some(last) if last.q >= hit.q => {
                    self.lose(hit.q);
                    return;
                }
                _ => {
                    if let Some(last) = self.hits.pop() {
                        self.lose(last.q);
                    }
                }
            }
        }
        let at = self
            .hits
            .iter()
            .position(|h| h.q < hit.q)
            .unwrap_or(self.hits.len());
        let _ = self.hits.insert(at, hit);
        // The tie-closed prefix and its floor; the rest is set aside.
        let (mut floor, mut len) = (i64::MAX, 0);
        for h in &self.hits {
            let q = i64::from(h.q);
            if len > 0 && q < floor {
                break;
            }
            floor = floor.min(q - i64::from(h.tie));
            len += 1;
        }
        while self.hits.len() > len {
            if let Some(h) = self.hits.pop() {
                self.lose(h.q);
            }
        }
        self.floor = floor;
    }

    /// The Z-buffer's rule over the kept faces: in index order, a later face wins
    /// when nearer by more than its tie.
    pub(super) fn winner(&self) -> Option<Hit> {
        let mut by_face = self.hits.clone();
        by_face.sort_unstable_by_key(|h| h.face);
        fold(by_face.iter().copied())
    }
}

/// The Z-buffer's decision over covering faces given in index order.
pub(super) fn fold(hits: impl Iterator<Item = Hit>) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for h in hits {
        if best.is_none_or(|b| h.q > b.q.saturating_add(h.tie)) {
            best = Some(h);
        }
    }
    best
}

impl<const POLY: usize> Cast<'_, POLY> {
    /// Face record `k` met by the ray through the centre of pixel (x, y), if it
    /// covers the centre.
    fn hit(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        k: usize,
        x: u16,
        y: u16,
        poly: &mut Vec<ScreenVertex, POLY>,
    ) -> Result<Option<Hit>, Error> {
        let Some(&rf) = self.faces.get(k) else {
            return Ok(None);
        };
        if !rf.contains(x, y) {
            return Ok(None);
        }
        self.figures.face_tests += 1;
        let f = usize::from(rf.face);
        if rf.clipped {
            if !face_polygon(ctx, vertices, f, poly)? {
                return Ok(None);
            }
        } else {
            poly.clear();
            for &v in ctx.mesh.face(f) {
                if let Some(p) = vertices.get(v as usize) {
                    let _ = poly.push(p.screen());
                }
            }
        }
        if !covers_centre(poly, ctx.s, i64::from(x), i64::from(y)) {
            return Ok(None);
        }
        Ok(Some(Hit {
            face: rf.face,
            entry: k as u32,
            q: rf
                .bent
                .then(|| fan_depth_at(ctx.mesh, vertices, f, ctx.s, (x, y)))
                .flatten()
                .unwrap_or_else(|| rf.plane.at_xy(x, y)),
            tie: rf.plane.tie,
        }))
    }

    /// The visible face at pixel (x, y): its record, or `None`. `hint` (the
    /// previous pixel's face record) is tried first: its nearness prunes the most.
    pub(super) fn trace(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        x: u16,
        y: u16,
        hint: Option<u32>,
        poly: &mut Vec<ScreenVertex, POLY>,
    ) -> Result<Option<Hit>, Error> {
        let mut c = Candidates::new();
        if let Some(k) = hint {
            if let Some(h) = self.hit(ctx, vertices, k as usize, x, y, poly)? {
                c.insert(h);
            }
        }
        let mut stack: Vec<u32, STACK> = Vec::new();
        if self.node_count > 0 {
            let _ = stack.push(0);
        }
        while let Some(i) = stack.pop() {
            let Some(&node) = self.nodes.get(i as usize) else {
                continue;
            };
            if !node.contains(x, y) {
                continue;
            }
            if i64::from(node.q_max) < c.floor {
                c.lose(node.q_max);
                continue;
            }
            if node.count == 0 {
                let (a, b) = (node.index, node.index + 1);
                let q = |n: u32| self.nodes.get(n as usize).map_or(0, |n| n.q_max);
                // The nearer child is popped first.
                let (far, near) = if q(a) >= q(b) { (b, a) } else { (a, b) };
                for child in [far, near] {
                    if stack.push(child).is_err() {
                        // Deeper than a median split can make: decide exhaustively.
                        c.lose(u32::MAX);
                    }
                }
                continue;
            }
            for k in node.index..node.index + node.count {
                if Some(k) == hint {
                    continue;
                }
                let bound = self.faces.get(k as usize).map_or(0, |f| f.plane.max_q());
                if i64::from(bound) < c.floor {
                    c.lose(bound);
                    continue;
                }
                if let Some(h) = self.hit(ctx, vertices, k as usize, x, y, poly)? {
                    c.insert(h);
                }
            }
        }
        if c.lost >= c.floor && !c.hits.is_empty() {
            self.figures.fallbacks += 1;
            return self.exhaustive(ctx, vertices, x, y, poly);
        }
        Ok(c.winner())
    }

    /// The face records whose boxes meet the tile `[x0, y0, x1, y1]` (inclusive),
    /// nearest bound first, into `out`; false when they do not fit (the tile's
    /// pixels are then traced through the tree one by one).
    pub(super) fn tile_faces(&self, tile: [u16; 4], out: &mut Vec<u32, TILE_FACES>) -> bool {
        let [x0, y0, x1, y1] = tile;
        let meets = |a: [u16; 4]| a[0] <= x1 && x0 <= a[2] && a[1] <= y1 && y0 <= a[3];
        out.clear();
        let mut stack: Vec<u32, STACK> = Vec::new();
        if self.node_count > 0 {
            let _ = stack.push(0);
        }
        while let Some(i) = stack.pop() {
            let Some(node) = self.nodes.get(i as usize) else {
                continue;
            };
            if !meets([node.x0, node.y0, node.x1, node.y1]) {
                continue;
            }
            if node.count == 0 {
                if stack.push(node.index).is_err() || stack.push(node.index + 1).is_err() {
                    return false;
                }
                continue;
            }
            for k in node.index..node.index + node.count {
                let Some(f) = self.faces.get(k as usize) else {
                    continue;
                };
                if meets([f.x0, f.y0, f.x1, f.y1]) && out.push(k).is_err() {
                    return false;
                }
            }
        }
        let bound = |k: &u32| self.faces.get(*k as usize).map_or(0, |f| f.plane.max_q());
        out.sort_unstable_by_key(|k| core::cmp::Reverse(bound(k)));
        true
    }

    /// [`trace`](Self::trace) over a tile's face list (nearest bound first): the
    /// first face whose bound is below the floor ends the walk, so the floor is final
    /// and only an overflow of the kept hits can leave the pixel undecided.
    pub(super) fn trace_list(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        x: u16,
        y: u16,
        list: &[u32],
        poly: &mut Vec<ScreenVertex, POLY>,
    ) -> Result<Option<Hit>, Error> {
        let mut c = Candidates::new();
        for &k in list {
            let bound = self.faces.get(k as usize).map_or(0, |f| f.plane.max_q());
            if i64::from(bound) < c.floor {
                c.lose(bound);
                break;
            }
            if let Some(h) = self.hit(ctx, vertices, k as usize, x, y, poly)? {
                c.insert(h);
            }
        }
        if c.lost >= c.floor && !c.hits.is_empty() {
            self.figures.fallbacks += 1;
            return self.exhaustive(ctx, vertices, x, y, poly);
        }
        Ok(c.winner())
    }

    /// The Z-buffer's decision at pixel (x, y) over every face record, taken in
    /// index order by repeated scans (no storage; only for the rare pixel the
    /// pruned trace cannot decide).
    fn exhaustive(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        x: u16,
        y: u16,
        poly: &mut Vec<ScreenVertex, POLY>,
    ) -> Result<Option<Hit>, Error> {
        let mut best: Option<Hit> = None;
        let mut after: Option<u16> = None;
        loop {
            // The covering face of least index above `after`.
            let mut next: Option<Hit> = None;
            for k in 0..self.face_count {
                let Some(face) = self.faces.get(k).map(|f| f.face) else {
                    break;
                };
                if after.is_some_and(|a| face <= a) || next.is_some_and(|n| face >= n.face) {
                    continue;
                }
                if let Some(h) = self.hit(ctx, vertices, k, x, y, poly)? {
                    next = Some(h);
                }
            }
            let Some(h) = next else {
                return Ok(best);
            };
            after = Some(h.face);
            best = fold(best.into_iter().chain(core::iter::once(h)));
        }
    }
}
