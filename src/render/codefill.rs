//! The code-fill engine of paper 003: visibility one row at a time, no depth buffer.
//!
//! Faces are taken in order of their first row. While a face is active it holds
//! one bit of the row's surface code (a bit is reused once its face ends), and each
//! of its edges crossing a row XORs that bit in at the crossing: the running XOR
//! from the left is, at every pixel, the set of faces covering it (even-odd per
//! face, so a face covers exactly the pixels the span core fills for it). A run of
//! pixels covered by one face needs no depth at all. Where the code holds two or
//! more faces, the scan-line method of notes 004 decides: their planes are compared
//! at the run's ends and the run is split where one overtakes another. The result
//! is the Z-buffer engine's picture with 32-bit depth (the nearest face at each
//! pixel centre, ties to the lower face index) in memory that grows with a row.

use core::marker::PhantomData;

use embedded_graphics_core::pixelcolor::PixelColor;
use fixed::types::extra::LeEqU32;
use heapless::Vec;

use super::compose::{self, FrameProbe, Palette};
use super::lines::{line_pass, LineMasks};
use super::transform::{ProjectedVertex, ScreenVertex};
use super::zband::{DepthPlane, IdBand, RowPlane};
use super::{begin_frame, bit, face_polygon, need, FrameCtx, Settings, Stats};
use crate::camera::Camera;
use crate::geometry::Subpixel;
use crate::mesh::{EdgeAdjacency, Mesh};
use crate::scan::edge::{Edge, EdgeLine};
use crate::scan::RowRange;
use crate::{Error, SpanSink};

/// Storage the caller lends the code-fill engine for one frame. Sizes: `vertices`
/// at least the mesh's vertex count; `drawn` faces / 32 words; `features` edges /
/// 32 words; `order` one entry per face drawn; `ids` width x
/// [`storage_rows`](super::storage_rows); `lines` 2 x ceil(width / 32) x band
/// rows. The band height follows from `ids.len() / width` as for the Z-buffer.
#[derive(Debug)]
pub struct CodeWorkspace<'s> {
    /// The per-frame vertex cache.
    pub vertices: &'s mut [ProjectedVertex],
    /// One bit per face: drawn in this view (not culled).
    pub drawn: &'s mut [u32],
    /// One bit per mesh edge: a feature edge in this view.
    pub features: &'s mut [u32],
    /// Drawn faces sorted by first row (`row << 16 | face`).
    pub order: &'s mut [u32],
    /// Face ids of the band (0 none, else 1 + face).
    pub ids: &'s mut [u16],
    /// Line masks of the band.
    pub lines: &'s mut [u32],
}

impl CodeWorkspace<'_> {
    /// Bytes of all the lent buffers.
    pub fn bytes(&self) -> usize {
        use core::mem::size_of_val;
        size_of_val(self.vertices)
            + size_of_val(self.drawn)
            + size_of_val(self.features)
            + size_of_val(self.order)
            + size_of_val(self.ids)
            + size_of_val(self.lines)
    }
}

/// A face holding a bit of the code.
#[derive(Debug, Clone, Copy, Default)]
struct ActiveFace {
    /// 1 + face index.
    id: u16,
    /// The row after its last.
    end: i32,
    plane: RowPlane,
}

/// An edge of an active face.
#[derive(Debug, Clone, Copy)]
struct ActiveEdge {
    edge: Edge,
    /// The crossing on the current row (`u16::MAX` before the edge's first row).
    x: u16,
    /// The face's bit.
    slot: u16,
}

/// The code-fill renderer with S = `Frac` sub-pixel bits, a surface code of
/// `32 x WORDS` bits (the most faces active on one row), room for `EDGES` active
/// edges and `POLY` vertices per clipped face.
#[derive(Debug)]
pub struct CodeFillRenderer<
    Frac: LeEqU32,
    const WORDS: usize,
    const EDGES: usize,
    const POLY: usize,
> {
    /// Active faces by bit: bit `k` is `faces[k / 32][k % 32]`.
    faces: [[ActiveFace; 32]; WORDS],
    /// Bits held by active faces.
    used: [u32; WORDS],
    active: usize,
    edges: Vec<ActiveEdge, EDGES>,
    /// The running code of the current row.
    code: [u32; WORDS],
    /// Next entry of the face order to activate, and the next row to scan.
    next_face: usize,
    row: u16,
    /// The most faces active at once this frame.
    widest: usize,
    _frac: PhantomData<Frac>,
}

impl<Frac: LeEqU32, const WORDS: usize, const EDGES: usize, const POLY: usize> Default
    for CodeFillRenderer<Frac, WORDS, EDGES, POLY>
{
    fn default() -> Self {
        Self::new()
    }
}

const NO_FACE: ActiveFace = ActiveFace {
    id: 0,
    end: 0,
    plane: RowPlane::ZERO,
};

impl<Frac: LeEqU32, const WORDS: usize, const EDGES: usize, const POLY: usize>
    CodeFillRenderer<Frac, WORDS, EDGES, POLY>
{
    /// Bits of the surface code.
    pub const CODE_BITS: usize = 32 * WORDS;

    /// Empty working memory.
    pub const fn new() -> Self {
        Self {
            faces: [[NO_FACE; 32]; WORDS],
            used: [0; WORDS],
            active: 0,
            edges: Vec::new(),
            code: [0; WORDS],
            next_face: 0,
            row: 0,
            widest: 0,
            _frac: PhantomData,
        }
    }

    /// Renders `mesh` seen by `camera` into `sink`, whose viewport is the frame:
    /// the same frame as [`ZBufferRenderer`](super::ZBufferRenderer) with 32-bit
    /// depth. Fails with [`Error::CodeTooWide`] when more than [`Self::CODE_BITS`]
    /// faces are active on one row (the row where that first happens says how many).
    #[allow(clippy::too_many_arguments)]
    pub fn render<K: SpanSink, P: Palette<Color = K::Color>, R: FrameProbe>(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &EdgeAdjacency<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut CodeWorkspace<'_>,
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>>
    where
        K::Color: PixelColor,
    {
        let viewport = sink.viewport();
        let (width, height) = (viewport.width, viewport.height);
        let s = Subpixel::<Frac>::BITS;
        let row_words = usize::from(width).div_ceil(32);
        let w = usize::from(width).max(1);
        let stored = (ws.ids.len() / w).min(usize::from(u16::MAX)) as u16;
        let band_rows = if stored >= height {
            height
        } else {
            stored.saturating_sub(2)
        }
        .min((ws.lines.len() / (2 * row_words).max(1)).min(usize::from(height)) as u16);
        if height > 0 && band_rows == 0 {
            let rows = usize::from(IdBand::rows_needed(1, height));
            need(rows * w, ws.ids.len()).map_err(Error::widen)?;
            need(2 * row_words, ws.lines.len()).map_err(Error::widen)?;
        }
        let mut stats = Stats {
            band_rows: u32::from(band_rows),
            ..Stats::default()
        };
        let ctx = begin_frame(
            mesh,
            edges,
            camera,
            settings,
            viewport,
            s,
            ws.vertices,
            ws.drawn,
            ws.features,
            &mut stats,
        )
        .map_err(Error::widen)?;
        let CodeWorkspace {
            vertices,
            drawn,
            features,
            order,
            ids,
            lines,
        } = ws;
        let faces = if settings.mode.needs_depth() {
            self.order_faces(&ctx, vertices, drawn, order)
                .map_err(Error::widen)?
        } else {
            0
        };
        let order = order.get(..faces).unwrap_or(&[]);
        self.begin();
        let mut band = IdBand::new(ids, width);
        let mut masks = LineMasks {
            words: lines,
            row_words,
            rows: 0,
        };
        let mut top = 0u16;
        while top < height && band_rows > 0 {
            let rows = band_rows.min(height - top);
            let fresh = band.advance(top, rows, height);
            masks.reset(rows);
            stats.bands += 1;
            for y in fresh..band.first + band.held {
                let Some(out) = band.row_mut(y) else { continue };
                if faces == 0 {
                    out.fill(0);
                    continue;
                }
                stats.spans += self
                    .scan_row(&ctx, vertices, order, y, out)
                    .map_err(Error::widen)?;
            }
            if settings.mode.draws_lines() {
                line_pass::<POLY>(
                    &ctx, vertices, drawn, features, edges, settings, &band, &mut masks,
                );
            }
            stats.spans += compose::emit_band(
                &ctx, settings, &band, &masks, drawn, palette, sink, probe,
            )
            .map_err(Error::Target)?;
            top += rows;
        }
        stats.code_bits = self.widest as u32;
        sink.flush().map_err(Error::Target)?;
        Ok(stats)
    }

    /// Sorts the drawn faces that reach the frame's rows by first row into `order`;
    /// returns how many there are.
    fn order_faces(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        order: &mut [u32],
    ) -> Result<usize, Error> {
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        let mut count = 0;
        for f in 0..ctx.mesh.face_count() {
            if !bit(drawn, f) {
                continue;
            }
            let idx = ctx.mesh.face(f);
            let outside = idx.iter().fold(0, |acc, &v| {
                acc | vertices.get(v as usize).map_or(0xFF, |p| p.outside)
            });
            let rows = if outside == 0 {
                let ys = idx
                    .iter()
                    .filter_map(|&v| vertices.get(v as usize).map(|p| p.screen.y));
                row_span(ctx.s, ys)
            } else if face_polygon(ctx, vertices, f, &mut poly)? {
                row_span(ctx.s, poly.iter().map(|v| v.y))
            } else {
                None
            };
            let Some((first, end)) = rows else { continue };
            if end <= 0 || first >= i32::from(ctx.viewport.height) {
                continue;
            }
            if let Some(slot) = order.get_mut(count) {
                *slot = (first.max(0) as u32) << 16 | f as u32;
            }
            count += 1;
        }
        need(count, order.len())?;
        if let Some(order) = order.get_mut(..count) {
            crate::sort::sort_by_key(order, |&k| k);
        }
        Ok(count)
    }

    /// Forgets the last frame's active faces and edges.
    fn begin(&mut self) {
        self.used = [0; WORDS];
        self.active = 0;
        self.edges.clear();
        self.next_face = 0;
        self.row = 0;
        self.widest = 0;
    }

    /// Fills `out` with the face ids of row `y` (rows come in order); returns the
    /// runs of one face resolved.
    fn scan_row(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        order: &[u32],
        y: u16,
        out: &mut [u16],
    ) -> Result<u32, Error> {
        // Rows are scanned in order; a gap (none in practice) is walked through.
        while self.row < y {
            self.activate(ctx, vertices, order, self.row)?;
            self.step_row();
        }
        self.activate(ctx, vertices, order, y)?;
        let width = out.len() as u16;
        for e in self.edges.iter_mut() {
            e.x = if e.edge.first > i32::from(y) {
                u16::MAX
            } else {
                e.edge.crossing(ctx.s).clamp(0, i32::from(width)) as u16
            };
        }
        insertion_sort_by_x(&mut self.edges);
        self.code = [0; WORDS];
        let mut count = 0u32;
        let (mut xa, mut runs) = (0u16, 0u32);
        for i in 0..self.edges.len() {
            let Some(&ActiveEdge { x, slot, .. }) = self.edges.get(i) else {
                break;
            };
            if x > width {
                break;
            }
            if x != xa {
                runs += self.resolve(count, y, xa, x, out);
                xa = x;
            }
            if let Some(word) = self.code.get_mut(usize::from(slot / 32)) {
                let mask = 1 << (slot % 32);
                *word ^= mask;
                if *word & mask != 0 {
                    count += 1;
                } else {
                    count -= 1;
                }
            }
        }
        if xa < width {
            runs += self.resolve(count, y, xa, width, out);
        }
        self.step_row();
        Ok(runs)
    }

    /// Moves every active edge and face past the current row, dropping those that
    /// end there.
    fn step_row(&mut self) {
        let next = i32::from(self.row) + 1;
        for e in self.edges.iter_mut() {
            if e.edge.first < next {
                e.edge.step();
            }
        }
        self.edges.retain(|e| e.edge.end > next);
        for (faces, used) in self.faces.iter_mut().zip(self.used.iter_mut()) {
            let mut bits = *used;
            while bits != 0 {
                let b = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let Some(face) = faces.get_mut(b) else { continue };
                if face.end <= next {
                    *used &= !(1 << b);
                    self.active -= 1;
                } else {
                    face.plane.step();
                }
            }
        }
        self.row += 1;
    }

    /// Activates the faces whose first row is `y`: each takes the lowest free bit,
    /// and its edges join the active edges.
    fn activate(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
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
            if !face_polygon(ctx, vertices, f, &mut poly)? {
                continue;
            }
            let Some(plane) = DepthPlane::new(&poly, ctx.s) else {
                continue;
            };
            let slot = self
                .used
                .iter()
                .enumerate()
                .find(|(_, w)| **w != u32::MAX)
                .map(|(k, w)| 32 * k + w.trailing_ones() as usize)
                .ok_or(Error::CodeTooWide {
                    needed: self.active + 1,
                    capacity: Self::CODE_BITS,
                })?;
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
                let Some(edge) = Edge::new(&line, line.clip(ctx.s, ctx.viewport, rows), ctx.s)
                else {
                    continue;
                };
                end = end.max(edge.end);
                let active = ActiveEdge {
                    edge,
                    x: u16::MAX,
                    slot: slot as u16,
                };
                if self.edges.push(active).is_err() {
                    return Err(Error::CapacityExceeded {
                        needed: self.edges.len() + poly.len() - added,
                        capacity: EDGES,
                    });
                }
                added += 1;
            }
            if added == 0 {
                continue;
            }
            if let (Some(word), Some(face)) = (
                self.used.get_mut(slot / 32),
                self.faces.get_mut(slot / 32).and_then(|w| w.get_mut(slot % 32)),
            ) {
                *word |= 1 << (slot % 32);
                *face = ActiveFace {
                    id: (f + 1) as u16,
                    end,
                    plane: plane.row_plane(y),
                };
            }
            self.active += 1;
            self.widest = self.widest.max(self.active);
        }
        Ok(())
    }

    /// The face holding bit `slot`.
    fn face(&self, slot: usize) -> ActiveFace {
        self.faces
            .get(slot / 32)
            .and_then(|w| w.get(slot % 32))
            .copied()
            .unwrap_or(NO_FACE)
    }

    /// Writes the ids of pixels `xa .. xb` of the current row, where the code holds
    /// `count` faces; returns the runs written.
    fn resolve(&self, count: u32, _y: u16, xa: u16, xb: u16, out: &mut [u16]) -> u32 {
        let Some(run) = out.get_mut(usize::from(xa)..usize::from(xb)) else {
            return 0;
        };
        match count {
            0 => {
                run.fill(0);
                1
            }
            1 => {
                let slot = self
                    .code
                    .iter()
                    .enumerate()
                    .find(|(_, w)| **w != 0)
                    .map_or(0, |(k, w)| 32 * k + w.trailing_zeros() as usize);
                run.fill(self.face(slot).id);
                1
            }
            _ => self.resolve_overlap(xa, xb, out),
        }
    }

    /// The scan-line method on a run covered by two or more faces: the nearest at
    /// the run's start wins until another overtakes it (found by bisection: two
    /// planes along a row cross at most once).
    fn resolve_overlap(&self, xa: u16, xb: u16, out: &mut [u16]) -> u32 {
        let beats = |c: &ActiveFace, w: &ActiveFace, x: u16| {
            let (qc, qw) = (c.plane.at(x), w.plane.at(x));
            qc > qw || (qc == qw && c.id < w.id)
        };
        let mut runs = 0;
        let mut x = xa;
        while x < xb {
            let mut winner = NO_FACE;
            self.each_covering(|face| {
                if winner.id == 0 || beats(face, &winner, x) {
                    winner = *face;
                }
            });
            let last = xb - 1;
            let mut end = xb;
            self.each_covering(|face| {
                if face.id != winner.id && last > x && beats(face, &winner, last) {
                    let (mut lo, mut hi) = (x, last);
                    while hi - lo > 1 {
                        let mid = lo + (hi - lo) / 2;
                        if beats(face, &winner, mid) {
                            hi = mid;
                        } else {
                            lo = mid;
                        }
                    }
                    end = end.min(hi);
                }
            });
            if let Some(run) = out.get_mut(usize::from(x)..usize::from(end)) {
                run.fill(winner.id);
            }
            runs += 1;
            x = end;
        }
        runs
    }

    /// Calls `f` on each face whose bit is set in the code.
    fn each_covering(&self, mut f: impl FnMut(&ActiveFace)) {
        for (faces, &word) in self.faces.iter().zip(self.code.iter()) {
            let mut bits = word;
            while bits != 0 {
                let b = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                if let Some(face) = faces.get(b) {
                    f(face);
                }
            }
        }
    }
}

/// Insertion sort by crossing: the order changes little from row to row.
fn insertion_sort_by_x(edges: &mut [ActiveEdge]) {
    for i in 1..edges.len() {
        let mut j = i;
        while j > 0 && edges[j - 1].x > edges[j].x {
            edges.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// First row and the row after the last that a polygon with these vertex y
/// coordinates (sub-pixel units) can cover; `None` when it covers no row centre.
fn row_span(s: u32, ys: impl Iterator<Item = i32>) -> Option<(i32, i32)> {
    let (lo, hi) = ys.fold((i32::MAX, i32::MIN), |(lo, hi), y| (lo.min(y), hi.max(y)));
    if lo > hi {
        return None;
    }
    let h = 1i64 << s;
    // As `EdgeLine::clip`: the first row whose centre is at or below y.
    let row = |y: i32| ((2 * i64::from(y) + h - 1) >> (s + 1)) as i32;
    let (first, end) = (row(lo), row(hi));
    (first < end).then_some((first, end))
}
