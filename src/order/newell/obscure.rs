//! Newell's tests (1 to 6): may one fragment, painted before another, cover a part
//! of it that is nearer? The planes with their thickness bands, the side counts, the
//! separating-axis test of the projections, and whether a plane cuts a fragment.

use super::sort::Sorter;
use crate::order::plane::{vertex, Plane, Record, Side};

impl Sorter<'_, '_, '_> {
    /// The plane of fragment `f`'s surface and the face's own thickness about it:
    /// the largest distance of its vertices (0 for a planar face or a fan triangle,
    /// in the units of [`Plane::distance`]).
    pub(super) fn banded(&self, f: usize) -> (Plane, f64) {
        let plane = self.plane(f);
        if Record::fan(self.surface(f)) != 0 {
            return (plane, 0.0);
        }
        let corners = self.mesh.face(self.face(f));
        let band = corners.iter().fold(0.0f64, |b, &i| {
            b.max(plane.distance(vertex(self.mesh.vertices(), i)).abs())
        });
        (plane, band)
    }

    /// How many vertices of fragment `f` lie in front of and behind `plane`, beyond
    /// the tolerance and beyond `band` (a face that is not planar is known no better
    /// than its thickness: a vertex within it counts as on the plane).
    fn sides(&self, f: usize, (plane, band): &(Plane, f64)) -> (usize, usize) {
        let mut sides = (0, 0);
        for &i in self.idx(f) {
            let p = vertex(self.vertices, i);
            let s = plane.distance(p);
            if s.abs() <= *band {
                continue;
            }
            match plane.side_of(s, p) {
                Side::Front => sides.0 += 1,
                Side::Back => sides.1 += 1,
                Side::On => {}
            }
        }
        sides
    }

    /// May P, painted before Q, cover a part of Q that is nearer? (True unless one
    /// of Newell's tests proves otherwise; coplanar overlapping polygons: when P's
    /// face index is the lower one.)
    pub(super) fn may_obscure(&self, p: usize, q: usize) -> bool {
        let (bp, bq) = (self.extent(p), self.extent(q));
        // 1: P wholly beyond Q.
        if bp[4] > bq[5] {
            return false;
        }
        // 2 and 3: disjoint (or touching) screen extents.
        if bp[1] <= bq[0] || bq[1] <= bp[0] || bp[3] <= bq[2] || bq[3] <= bp[2] {
            return false;
        }
        let (fp, fq) = (self.face(p), self.face(q));
        if fp == fq {
            // Pieces of one face do not overlap (fan triangles do where the face
            // folds on screen, and the renderer covers that by the polygon's parity).
            return false;
        }
        let (plane_p, plane_q) = (self.banded(p), self.banded(q));
        let (p_by_q, q_by_p) = (self.sides(p, &plane_q), self.sides(q, &plane_p));
        if p_by_q == (0, 0) && q_by_p == (0, 0) {
            // Coplanar: the lower face index is nearer where they overlap.
            return fp < fq && self.projections_overlap(p, q);
        }
        // 4: P wholly on the far side of Q's plane (Q edge-on covers nothing).
        let far = match self.view.eye_side(&plane_q.0) {
            Side::Front => p_by_q.0 == 0,
            Side::Back => p_by_q.1 == 0,
            Side::On => true,
        };
        // 5: Q wholly on the near side of P's plane.
        let near = match self.view.eye_side(&plane_p.0) {
            Side::Front => q_by_p.1 == 0,
            Side::Back => q_by_p.0 == 0,
            Side::On => true,
        };
        // 6: the projections overlap.
        !far && !near && self.projections_overlap(p, q)
    }

    /// Do the projections of fragments `p` and `q` overlap? False when an edge
    /// direction of either separates them (touching counts as apart: no pixel
    /// centre is covered by both); true when a vertex is at or behind the eye.
    fn projections_overlap(&self, p: usize, q: usize) -> bool {
        self.separated(p, q) != Some(true)
    }

    fn separated(&self, p: usize, q: usize) -> Option<bool> {
        let (a, b) = (self.idx(p), self.idx(q));
        let screen = |i: u32| self.view.screen(vertex(self.vertices, i));
        let interval = |poly: &[u32], axis: [f64; 2]| -> Option<(f64, f64)> {
            let mut range = (f64::INFINITY, f64::NEG_INFINITY);
            for &i in poly {
                let [x, y] = screen(i)?;
                let t = axis[0] * x + axis[1] * y;
                range = (range.0.min(t), range.1.max(t));
            }
            Some(range)
        };
        for poly in [a, b] {
            for (k, &u) in poly.iter().enumerate() {
                let v = poly.get(k + 1).or(poly.first()).copied().unwrap_or(u);
                let (pu, pv) = (screen(u)?, screen(v)?);
                let axis = [pu[1] - pv[1], pv[0] - pu[0]];
                if axis == [0.0, 0.0] {
                    continue;
                }
                let (ia, ib) = (interval(a, axis)?, interval(b, axis)?);
                if ia.1 <= ib.0 || ib.1 <= ia.0 {
                    return Some(true);
                }
            }
        }
        Some(false)
    }

    /// Does fragment `f` have vertices on both sides of `plane` (beyond the
    /// tolerance)?
    pub(super) fn straddles(&self, f: usize, plane: &(Plane, f64)) -> bool {
        let (front, back) = self.sides(f, plane);
        front > 0 && back > 0
    }
}
