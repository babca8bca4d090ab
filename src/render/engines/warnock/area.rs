//! One area of the subdivision decided from its candidates: which of its parent's
//! candidates stay, whether one face that covers the whole area is nearest all over
//! it, and at a single pixel the Z-buffer's decision; then the area's ids filled.

use heapless::Vec;

use super::geom::{outside_an_edge, Rect};
use super::WarnockFace;
use crate::render::band::IdBand;
use crate::render::depth::coverage::covers_centre;
use crate::render::depth::fan::fan_depth_at;
use crate::render::face_polygon;
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::FrameCtx;
use crate::Error;

/// What deciding one area needs.
pub(super) struct Areas<'a, 'b, 's, const POLY: usize> {
    /// The frame.
    pub(super) ctx: &'a FrameCtx<'a, 'a>,
    /// The vertex cache, that a polygon of more than four corners is rebuilt from.
    pub(super) vertices: &'a [ProjectedVertex],
    /// The frame's drawn faces in view; the candidate lists hold their slots.
    pub(super) faces: &'a [WarnockFace],
    /// The band whose ids the decided areas fill.
    pub(super) band: &'b mut IdBand<'s>,
    /// The clipped polygon of the face last asked about.
    pub(super) poly: Vec<ScreenVertex, POLY>,
    /// The face whose polygon `poly` holds.
    pub(super) poly_of: Option<u16>,
    /// Id runs written, for `Stats::spans`.
    pub(super) runs: u32,
}

impl<'a, const POLY: usize> Areas<'a, '_, '_, POLY> {
    /// The face in candidate slot `slot`.
    fn face(&self, slot: u16) -> Option<&'a WarnockFace> {
        self.faces.get(usize::from(slot))
    }

    /// Puts the clipped polygon of `face` in `self.poly`: kept, copied from the
    /// face's small polygon, or rebuilt from the vertex cache.
    fn polygon(&mut self, face: &WarnockFace) -> Result<bool, Error> {
        if self.poly_of == Some(face.face) {
            return Ok(true);
        }
        self.poly_of = None;
        let n = usize::from(face.small_len);
        if let Some(small) = face.small.get(..n).filter(|_| n > 0) {
            self.poly.clear();
            for v in small {
                let _ = self.poly.push(*v);
            }
        } else if !face_polygon(
            self.ctx,
            self.vertices,
            usize::from(face.face),
            &mut self.poly,
        )? {
            return Ok(false);
        }
        self.poly_of = Some(face.face);
        Ok(true)
    }

    /// Whether the face in `slot` may cover a centre of the area.
    pub(super) fn candidate(
        &mut self,
        slot: u16,
        rect: &Rect,
        corners: &[(i64, i64); 4],
    ) -> Result<bool, Error> {
        let Some(face) = self.face(slot) else {
            return Ok(false);
        };
        if !face.pixels.meets(rect) {
            return Ok(false);
        }
        if face.sense == 0 || !self.polygon(face)? {
            return Ok(true);
        }
        Ok(!outside_an_edge(&self.poly, face.sense, corners))
    }

    /// Whether the face covers every centre of the area: convex and covering the
    /// four corner centres (its covered set is convex, so it holds their hull).
    fn surrounds(&mut self, face: &WarnockFace, rect: &Rect) -> Result<bool, Error> {
        if face.sense == 0 || !face.pixels.holds(rect) || !self.polygon(face)? {
            return Ok(false);
        }
        let s = self.ctx.s;
        let (l, r) = (i64::from(rect.x0), i64::from(rect.x1 - 1));
        let (t, b) = (i64::from(rect.y0), i64::from(rect.y1 - 1));
        Ok([(l, t), (r, t), (l, b), (r, b)]
            .iter()
            .all(|&(i, j)| covers_centre(&self.poly, s, i, j)))
    }

    /// Decides the area from its candidates `list` (slots in increasing face
    /// index); false when it must be split.
    pub(super) fn decide(
        &mut self,
        list: &[u16],
        rect: &Rect,
        corners: &[(i64, i64); 4],
    ) -> Result<bool, Error> {
        let range = |face: &WarnockFace| {
            let (lo, hi) = corners.iter().fold((u32::MAX, 0), |(lo, hi), &(x, y)| {
                let q = face.plane.at(x, y);
                (lo.min(q), hi.max(q))
            });
            (lo.saturating_sub(face.bend), hi.saturating_add(face.bend))
        };
        match list {
            [] => return Ok(true),
            [only] => {
                let Some(face) = self.face(*only) else {
                    return Ok(true);
                };
                if self.surrounds(face, rect)? {
                    self.fill(rect, face.face);
                } else {
                    self.fill_covered(face, rect)?;
                }
                return Ok(true);
            }
            _ => {}
        }
        for (k, &slot) in list.iter().enumerate() {
            let Some(face) = self.face(slot) else {
                continue;
            };
            if !self.surrounds(face, rect)? {
                continue;
            }
            let (nearest, _) = range(face);
            // Z-buffer order: an earlier face loses to this one where this one is
            // nearer by more than this one's tie; a later one never wins where it
            // is not nearer by more than its own tie.
            let wins = list.iter().enumerate().all(|(m, &other)| {
                if m == k {
                    return true;
                }
                let Some(other) = self.face(other) else {
                    return true;
                };
                let (_, farthest) = range(other);
                if m < k {
                    nearest > farthest.saturating_add(face.tie)
                } else {
                    farthest <= nearest.saturating_add(other.tie)
                }
            });
            if wins {
                self.fill(rect, face.face);
                return Ok(true);
            }
        }
        if !rect.is_pixel() {
            return Ok(false);
        }
        // One pixel: the Z-buffer's decision.
        let (i, j) = (i64::from(rect.x0), i64::from(rect.y0));
        let [(x, y), ..] = *corners;
        let mut best: Option<(u16, u32)> = None;
        for &slot in list {
            let Some(face) = self.face(slot) else {
                continue;
            };
            if !self.polygon(face)? || !covers_centre(&self.poly, self.ctx.s, i, j) {
                continue;
            }
            let q = (face.bend > 0)
                .then(|| {
                    fan_depth_at(
                        self.ctx.mesh,
                        self.vertices,
                        usize::from(face.face),
                        self.ctx.s,
                        (rect.x0, rect.y0),
                    )
                })
                .flatten()
                .unwrap_or_else(|| face.plane.at(x, y));
            if best.is_none_or(|(_, near)| q > near.saturating_add(face.tie)) {
                best = Some((face.face, q));
            }
        }
        if let Some((f, _)) = best {
            self.fill(rect, f);
        }
        Ok(true)
    }

    /// The area shows `face`.
    fn fill(&mut self, rect: &Rect, face: u16) {
        let id = face.wrapping_add(1);
        for y in rect.y0..rect.y1 {
            if let Some(start) = self.band.index(rect.x0, y) {
                let end = start + usize::from(rect.x1 - rect.x0);
                if let Some(ids) = self.band.ids.get_mut(start..end) {
                    ids.fill(id);
                    self.runs += 1;
                }
            }
        }
    }

    /// Each centre of the area that `face` covers shows it.
    fn fill_covered(&mut self, face: &WarnockFace, rect: &Rect) -> Result<(), Error> {
        if !self.polygon(face)? {
            return Ok(());
        }
        let id = face.face.wrapping_add(1);
        let s = self.ctx.s;
        for y in rect.y0..rect.y1 {
            let mut run = false;
            for x in rect.x0..rect.x1 {
                let covered = covers_centre(&self.poly, s, i64::from(x), i64::from(y));
                if covered {
                    if let Some(slot) = self.band.index(x, y).and_then(|k| self.band.ids.get_mut(k))
                    {
                        *slot = id;
                    }
                    self.runs += u32::from(!run);
                }
                run = covered;
            }
        }
        Ok(())
    }
}
