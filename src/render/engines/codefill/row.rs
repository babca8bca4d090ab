//! The row scan of the code-fill engine: faces activated at their first row, the
//! crossings of the row taken in order, each toggling its face in the surface code.

use heapless::Vec;

use fixed::types::extra::LeEqU32;

use super::active::ActiveEdge;
use super::resolve::RowFaces;
use super::{ActiveFace, CodeFillRenderer, Surfaces, FOLD_MEMO, NO_BIT, OVER};
use crate::render::depth::coverage::{fragments_may_overlap, has_area};
use crate::render::depth::fan::bend;
use crate::render::depth::fan::takes_fan_depth;
use crate::render::depth::plane::{DepthPlane, RowPlane};
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::{index_polygon, FrameCtx};
use crate::scan::edge::{Edge, EdgeLine};
use crate::scan::RowRange;
use crate::Capacity;
use crate::Error;

impl<
        Frac: LeEqU32,
        const WORDS: usize,
        const FACES: usize,
        const EDGES: usize,
        const POLY: usize,
    > CodeFillRenderer<Frac, WORDS, FACES, EDGES, POLY>
{
    /// Fills `out` with the face ids of row `y` (rows come in order); returns the
    /// runs of one face resolved.
    pub(super) fn scan_row(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        fill: &Surfaces<'_>,
        vertices: &[ProjectedVertex],
        order: &[u32],
        y: u16,
        out: &mut [u16],
    ) -> Result<u32, Error> {
        self.enter_row(ctx, fill, vertices, order, y)?;
        let faces = RowFaces::new(ctx, fill, vertices, y);
        // (Bit-sliced rows give every live face its place themselves.)
        if self.priority {
            self.assign_priority_bits();
        }
        let width = out.len() as u16;
        let row = i32::from(y);
        self.edges.move_to_row(row, ctx.s, width);
        self.code = [0; WORDS];
        self.inside = 0;
        let (mut xa, mut runs) = (0u16, 0u32);
        let mut k = 0;
        while let Some(&ActiveEdge { x, .. }) = self.edges.get(k) {
            // The edges crossing at x (edges not begun yet only hold their place).
            let mut end = k;
            while self.edges.get(end).is_some_and(|e| e.x == x) {
                end += 1;
            }
            let live = |e: &ActiveEdge| e.edge.first <= row;
            if (k..end).any(|j| self.edges.get(j).is_some_and(live)) {
                if x != xa {
                    runs += self.resolve(&faces, xa, x, out);
                    xa = x;
                }
                // Faces leaving first, so that one entering at the same place can
                // take the bit: the code is then as wide as the most faces over one
                // pixel.
                for j in k..end {
                    let Some(&e) = self.edges.get(j) else { break };
                    let inside = self
                        .faces
                        .get(usize::from(e.face))
                        .is_some_and(|f| f.bit != NO_BIT);
                    if live(&e) && inside {
                        self.toggle(usize::from(e.face));
                        if let Some(e) = self.edges.get_mut(j) {
                            e.mark = true;
                        }
                    }
                }
                // Then the faces entering; two crossings of one face here (a face
                // narrower than a pixel on this row) cancel instead of taking a bit
                // for nothing.
                for j in k..end {
                    let Some(&e) = self.edges.get(j) else { break };
                    if !live(&e) || e.mark {
                        continue;
                    }
                    let twin = (j + 1..end).find(|&t| {
                        self.edges
                            .get(t)
                            .is_some_and(|o| o.face == e.face && live(o) && !o.mark)
                    });
                    match twin.and_then(|t| self.edges.get_mut(t)) {
                        Some(other) => other.mark = true,
                        None => self.toggle(usize::from(e.face)),
                    }
                }
                for j in k..end {
                    if let Some(e) = self.edges.get_mut(j) {
                        e.mark = false;
                    }
                }
            }
            k = end.max(k + 1);
        }
        if xa < width {
            runs += self.resolve(&faces, xa, width, out);
        }
        self.step_row();
        Ok(runs)
    }

    /// Brings the active faces and edges to row `y` (rows come in order; a gap, none
    /// in practice, is walked through) and activates the faces that start there.
    pub(super) fn enter_row(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        fill: &Surfaces<'_>,
        vertices: &[ProjectedVertex],
        order: &[u32],
        y: u16,
    ) -> Result<(), Error> {
        while self.row < y {
            self.activate(ctx, fill, vertices, order, self.row)?;
            self.step_row();
        }
        self.activate(ctx, fill, vertices, order, y)?;
        self.peak_faces = self.peak_faces.max(self.live.len());
        self.peak_edges = self.peak_edges.max(self.edges.len());
        Ok(())
    }

    /// Depth order: the faces active on the row take weight-1 codes in their order
    /// (the live list is kept sorted by rank), so the lowest bit set in a pixel's
    /// code names its nearest face. The code is as wide as the faces on the row.
    fn assign_priority_bits(&mut self) {
        self.widest = self.widest.max(self.live.len());
        for (bit, &slot) in self.live.iter().enumerate() {
            if let Some(face) = self.faces.get_mut(usize::from(slot)) {
                face.pos = if bit < Self::CODE_BITS {
                    bit as u16
                } else {
                    OVER
                };
            }
            if let Some(owner) = self
                .owner
                .get_mut(bit / 32)
                .and_then(|o| o.get_mut(bit % 32))
            {
                *owner = slot;
            }
        }
    }

    /// Face `f` enters or leaves at the current crossing.
    // Indexing: k comes from enumerating `code` (k < WORDS) and b = trailing_ones of
    // a word that is not all ones (b < 32).
    #[allow(clippy::indexing_slicing)]
    pub(super) fn toggle(&mut self, f: usize) {
        let Some(face) = self.faces.get_mut(f) else {
            return;
        };
        if face.bit == NO_BIT && self.priority {
            face.bit = face.pos;
            if let Some(word) = self.code.get_mut(usize::from(face.pos / 32)) {
                *word |= 1 << (face.pos % 32);
            }
            self.inside += 1;
        } else if face.bit == NO_BIT {
            let free = self
                .code
                .iter()
                .enumerate()
                .find(|(_, w)| **w != u32::MAX)
                .map(|(k, w)| (k, w.trailing_ones() as usize));
            face.bit = match free {
                Some((k, b)) => {
                    self.code[k] |= 1 << b;
                    self.owner[k][b] = f as u16;
                    (32 * k + b) as u16
                }
                None => OVER,
            };
            self.inside += 1;
            self.widest = self.widest.max(self.inside);
        } else {
            if let Some(word) = self.code.get_mut(usize::from(face.bit / 32)) {
                *word &= !(1 << (face.bit % 32));
            }
            face.bit = NO_BIT;
            self.inside -= 1;
        }
    }

    /// Whether the fragments of mesh face `source` may overlap in this view
    /// ([`fragments_may_overlap`]), remembered for the face's other fragments: a
    /// face's fragments start on nearby rows, so a few slots (by face index) catch
    /// most of them.
    fn fold_of(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        source: usize,
        vertices: &[ProjectedVertex],
    ) -> bool {
        let key = (source as u32 + 1) << 1;
        let slot = self.fold_memo.get_mut(source % FOLD_MEMO);
        if let Some(&seen) = slot.as_deref() {
            if seen & !1 == key {
                return seen & 1 == 1;
            }
        }
        let fold = fragments_may_overlap(ctx.mesh, source, vertices);
        if let Some(seen) = slot {
            *seen = key | u32::from(fold);
        }
        fold
    }

    /// Moves every active edge and face past the current row, dropping those that
    /// end there.
    pub(super) fn step_row(&mut self) {
        let next = i32::from(self.row) + 1;
        self.edges.step(next);
        let mut k = 0;
        while let Some(&f) = self.live.get(k) {
            let Some(face) = self.faces.get_mut(usize::from(f)) else {
                break;
            };
            // A face cut by the frame's right side can end a row inside.
            face.bit = NO_BIT;
            if face.end <= next {
                if self.priority {
                    // Keeps the rank order.
                    self.live.remove(k);
                } else {
                    self.live.swap_remove(k);
                }
                let _ = self.free.push(f);
            } else {
                if !self.priority {
                    face.plane.step();
                }
                k += 1;
            }
        }
        self.row += 1;
    }

    /// Activates the faces whose first row is `y`: their edges join the active
    /// edges.
    pub(super) fn activate(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        fill: &Surfaces<'_>,
        vertices: &[ProjectedVertex],
        order: &[u32],
        y: u16,
    ) -> Result<(), Error> {
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        while let Some(&key) = order.get(self.next_face) {
            if key >> 16 > u32::from(y) {
                break;
            }
            self.next_face += 1;
            let f = (key & 0xFFFF) as usize;
            if !index_polygon(ctx, vertices, fill.mesh.face(f), &mut poly)? {
                continue;
            }
            let mut face = ActiveFace {
                id: (fill.source(f) + 1) as u16,
                bit: NO_BIT,
                pos: NO_BIT,
                rank: fill.rank(f),
                fold: false,
                bend: 0,
                end: 0,
                plane: RowPlane::ZERO,
            };
            if self.priority {
                // A depth order compares no depths: no plane.
                if !has_area(&poly) {
                    continue;
                }
                face.fold = self.fold_of(ctx, fill.source(f), vertices);
            } else {
                let Some(plane) = DepthPlane::new(&poly, ctx.s) else {
                    continue;
                };
                face.plane = plane.row_plane(y);
                // A face that is not planar takes its depth from the fan triangle
                // that holds the pixel (CONVENTIONS.md): `resolve_overlap` asks it
                // where the plane's bend could change the answer. Clipped, the
                // corners left bound nothing: it is always asked.
                if takes_fan_depth(fill.mesh, f, &poly, &plane) {
                    let corners = fill.mesh.face(f);
                    let seen =
                        |v: &u32| vertices.get(*v as usize).is_some_and(|p| p.outside() == 0);
                    face.bend = if corners.iter().all(seen) {
                        bend(&poly, &plane)
                    } else {
                        u32::MAX
                    };
                }
            }
            self.add_surface(ctx, &poly, y, face)?;
        }
        Ok(())
    }

    /// Activates `face`, whose polygon is `poly` and first row `y`: its edges join
    /// the active edges; nothing when none crosses a pixel centre's row.
    fn add_surface(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        poly: &[ScreenVertex],
        y: u16,
        mut face: ActiveFace,
    ) -> Result<(), Error> {
        let Some(&slot) = self.free.last() else {
            return Err(Error::CapacityExceeded {
                what: Capacity::ActiveFaces,
                needed: self.live.len() + 1,
                capacity: FACES,
            });
        };
        let rows = RowRange {
            first: i32::from(y),
            end: i32::from(ctx.viewport.height),
        };
        let half = |v: &ScreenVertex| (2 * i64::from(v.x), 2 * i64::from(v.y));
        let mut end = i32::from(y);
        let mut added = 0;
        for (a, b) in poly.iter().zip(poly.iter().cycle().skip(1)) {
            let Some(line) = EdgeLine::new(half(a), half(b)) else {
                continue;
            };
            let Some(edge) = Edge::new(&line, line.clip(ctx.s, ctx.viewport, rows), ctx.s) else {
                continue;
            };
            end = end.max(edge.end);
            let width = ctx.viewport.width;
            if self.edges.insert(edge, slot, ctx.s, width).is_err() {
                return Err(Error::CapacityExceeded {
                    what: Capacity::ActiveEdges,
                    needed: self.edges.len() + poly.len() - added,
                    capacity: EDGES,
                });
            }
            added += 1;
        }
        if added == 0 {
            return Ok(());
        }
        face.end = end;
        let rank = face.rank;
        if let Some(held) = self.faces.get_mut(usize::from(slot)) {
            *held = face;
        }
        self.free.pop();
        if self.priority {
            let faces = &self.faces;
            let at = self
                .live
                .partition_point(|&s| faces.get(usize::from(s)).map_or(0, |f| f.rank) < rank);
            let _ = self.live.insert(at, slot);
        } else {
            let _ = self.live.push(slot);
        }
        Ok(())
    }
}
