//! The code-fill engine of the modulo-2 surface-filling paper: visibility one row at a
//! time, no depth buffer.
//!
//! Faces become active at their first row (they are sorted by it) and their edges
//! join one active edge list. On each row the crossings are taken left to right and
//! each toggles its face in the row's surface code: a face entering takes the
//! lowest free bit, a face leaving frees it. The running code is, at every pixel,
//! the set of faces covering it (even-odd per face, so a face covers exactly the
//! pixels the span core fills for it), and the code is only as wide as the most
//! faces covering one pixel. A run of pixels covered by one face needs no depth at
//! all. Where the code holds two or more faces, the scan-line method of notes 004
//! decides: their planes are compared at the run's ends and the run is split where
//! one overtakes another. The result is the Z-buffer engine's picture with 32-bit
//! depth (the nearest face at each pixel centre, ties to the lower face index) in
//! memory that grows with a row.

mod active;
mod resolve;
mod row;
mod sliced;

use core::marker::PhantomData;

use embedded_graphics_core::pixelcolor::PixelColor;
use fixed::types::extra::LeEqU32;
use heapless::Vec;

use crate::camera::Camera;
use crate::geometry::Subpixel;
use crate::mesh::{EdgeAdjacency, Mesh};
pub use crate::order::DepthOrder;
use crate::render::band::IdBand;
use crate::render::compose::{Flat, FrameProbe, Palette};
use crate::render::depth::plane::RowPlane;
use crate::render::idpass::{render_ids, FrameInput, IdPass, IdWorkspace};
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::{bit, index_polygon, need, FrameCtx, Settings, Stats};
use crate::Capacity;
use crate::{Error, SpanSink};
use active::{ActiveEdge, ActiveEdges};

/// Storage the caller lends the code-fill engine for one frame. Sizes: `vertices`
/// at least the mesh's vertex count; `drawn` faces / 32 words; `features` edges /
/// 32 words; `order` one entry per face drawn; `ids` width x
/// [`storage_rows`](crate::render::storage_rows); `lines` 2 x ceil(width / 32) x band
/// rows. The band height follows from `ids.len() / width` as for the Z-buffer.
#[derive(Debug)]
pub struct CodeWorkspace<'s> {
    /// The per-frame vertex cache.
    pub vertices: &'s mut [ProjectedVertex],
    /// One bit per face: drawn in this view (not culled).
    pub drawn: &'s mut [u32],
    /// One bit per mesh edge: a feature edge in this view not yet drawn (scratch:
    /// the line pass clears an edge's bit after the last band it reaches).
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

/// How the code-fill engine keeps a row's surface codes (both give the same frame).
#[derive(Debug)]
pub enum RowCodes<'s> {
    /// The row's crossings in order, each toggling its face: work grows with the
    /// edges on a row, and the code is as wide as the most faces over one pixel.
    /// The default ([`CodeFillRenderer::render`]).
    Crossings,
    /// Every crossed pixel's code in machine words (a running XOR a word at a time
    /// over the pixels crossed): no sort; the code is as wide as the faces active
    /// on a row. The buffer holds width x ceil(active faces / 32) words, then
    /// ceil(width / 32) (a bit per pixel); [`CodeFillRenderer::bit_sliced_len`]
    /// gives the length for a full code.
    BitSliced(&'s mut [u32]),
}

/// How the code-fill engine finds the nearest face where faces overlap.
#[derive(Debug, Clone, Copy)]
pub enum Visibility<'o> {
    /// The scan-line method of notes 004: where the code holds two or more faces,
    /// their planes are compared at the run's ends and the run is split where one
    /// overtakes another. Needs no order; the code is as wide as the most faces
    /// over one pixel.
    Planes,
    /// A front-to-back order of the mesh's faces, or of fragments of them (a BSP
    /// tree's): the faces active on a row take weight-1 codes in that order, and the
    /// lowest bit set in a pixel's code names its nearest face (the priority encoder
    /// of the modulo-2 surface-filling paper, scheme 3). No depth is compared at all; the
    /// code is as wide as
    /// the faces active on one row.
    Order(DepthOrder<'o>),
}

/// What the fill pass scans, and how it reports it.
#[derive(Debug, Clone, Copy)]
struct Surfaces<'a> {
    mesh: &'a Mesh<'a>,
    /// Empty: surface = face.
    source: &'a [u16],
    /// Empty: no order (planes).
    rank: &'a [u32],
}

impl Surfaces<'_> {
    fn source(&self, s: usize) -> usize {
        self.source.get(s).map_or(s, |&f| usize::from(f))
    }

    fn rank(&self, s: usize) -> u32 {
        self.rank.get(s).copied().unwrap_or(0)
    }
}

/// A face on the rows it covers.
#[derive(Debug, Clone, Copy, Default)]
struct ActiveFace {
    /// 1 + face index.
    id: u16,
    /// Its bit in the current row's code while inside the face: [`NO_BIT`] when
    /// outside, [`OVER`] when inside without a bit (the code is full).
    bit: u16,
    /// Depth order: its place among the row's faces (its weight-1 code), and its
    /// rank in the frame's front-to-back order.
    pos: u16,
    rank: u32,
    /// Its source face is not planar and may fold in this view (see
    /// `coverage::folded`): its fragments can overlap on screen, and the face covers
    /// a pixel only where an odd number of them do.
    fold: bool,
    /// Planes: how far its fan triangles may leave `plane`
    /// ([`bend`](crate::render::depth::fan::bend)),
    /// 0 for a planar face (see `resolve_overlap`).
    bend: u32,
    /// The row after its last.
    end: i32,
    plane: RowPlane,
}

const NO_BIT: u16 = u16::MAX;
/// Faces whose fold test the engine remembers (see `fold_of`).
const FOLD_MEMO: usize = 32;
const OVER: u16 = u16::MAX - 1;

/// The code-fill renderer with S = `Frac` sub-pixel bits, a surface code of
/// `32 x WORDS` bits (at least the most faces covering one pixel), room for
/// `FACES` faces and `EDGES` edges active on one row, and `POLY` vertices per
/// clipped face.
#[derive(Debug)]
pub struct CodeFillRenderer<
    Frac: LeEqU32,
    const WORDS: usize,
    const FACES: usize,
    const EDGES: usize,
    const POLY: usize,
> {
    /// Active face table; `live` indexes the entries in use, `free` the others.
    faces: [ActiveFace; FACES],
    live: Vec<u16, FACES>,
    free: Vec<u16, FACES>,
    edges: ActiveEdges<EDGES>,
    /// The running code of the current row, and which face holds each bit.
    code: [u32; WORDS],
    owner: [[u16; 32]; WORDS],
    /// Faces inside at the current crossing (bits set, plus any beyond the code).
    inside: usize,
    /// This frame has a depth order: codes are weight-1 in that order.
    priority: bool,
    /// Recent fold tests: `(1 + face) << 1 | fold`, 0 for none, by face index.
    fold_memo: [u32; FOLD_MEMO],
    /// Next entry of the face order to activate, and the next row to scan.
    next_face: usize,
    row: u16,
    /// The most faces covering one pixel, and active on one row, this frame.
    widest: usize,
    peak_faces: usize,
    peak_edges: usize,
    _frac: PhantomData<Frac>,
}

default_is_new!(CodeFillRenderer<WORDS, FACES, EDGES, POLY>);

/// No face (id 0), all zero: what an empty slot holds (so that a `static` engine
/// lands in `.bss`, not in `.data`, which costs its size in flash too; a face writes
/// its slot whole in `add_surface` before anything reads it), and what a lookup that
/// misses gets.
const NO_FACE: ActiveFace = ActiveFace {
    id: 0,
    bit: 0,
    pos: 0,
    rank: 0,
    fold: false,
    bend: 0,
    end: 0,
    plane: RowPlane::ZERO,
};

impl<
        Frac: LeEqU32,
        const WORDS: usize,
        const FACES: usize,
        const EDGES: usize,
        const POLY: usize,
    > CodeFillRenderer<Frac, WORDS, FACES, EDGES, POLY>
{
    /// Bits of the surface code.
    pub const CODE_BITS: usize = 32 * WORDS;

    /// Bytes of an engine with this code width and room for `faces` active faces
    /// and `edges` active edges (with `stats.peak_faces` and `stats.peak_edges`:
    /// the engine a frame needed).
    pub const fn bytes_for(faces: usize, edges: usize) -> usize {
        use core::mem::size_of;
        faces * (size_of::<ActiveFace>() + 2 * size_of::<u16>())
            + edges * (size_of::<ActiveEdge>() + 2 * size_of::<u16>())
            + WORDS * (size_of::<u32>() + 32 * size_of::<u16>())
            + FOLD_MEMO * size_of::<u32>()
            + 4 * size_of::<usize>()
    }

    /// Words of a [`RowCodes::BitSliced`] buffer for rows `width` pixels wide and
    /// codes of up to [`Self::CODE_BITS`] bits.
    pub const fn bit_sliced_len(width: usize) -> usize {
        width * WORDS + width.div_ceil(32)
    }

    /// Empty working memory.
    pub const fn new() -> Self {
        Self {
            faces: [NO_FACE; FACES],
            live: Vec::new(),
            free: Vec::new(),
            edges: ActiveEdges::new(),
            code: [0; WORDS],
            owner: [[0; 32]; WORDS],
            inside: 0,
            priority: false,
            fold_memo: [0; FOLD_MEMO],
            next_face: 0,
            row: 0,
            widest: 0,
            peak_faces: 0,
            peak_edges: 0,
            _frac: PhantomData,
        }
    }

    /// Renders `mesh` seen by `camera` into `sink`, whose viewport is the frame:
    /// the same frame as [`ZBufferRenderer`](super::ZBufferRenderer) with 32-bit
    /// depth. Fails with [`Error::CodeTooWide`] when more than [`Self::CODE_BITS`]
    /// faces cover one pixel, with the width the whole frame needs (the target then
    /// holds the bands drawn before; so after any error).
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
        let codes = RowCodes::Crossings;
        self.render_rows(
            mesh, edges, camera, settings, ws, codes, palette, sink, probe,
        )
    }

    /// [`render`](Self::render) with the row representation `codes`.
    #[allow(clippy::too_many_arguments)]
    pub fn render_rows<K: SpanSink, P: Palette<Color = K::Color>, R: FrameProbe>(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &EdgeAdjacency<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut CodeWorkspace<'_>,
        codes: RowCodes<'_>,
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>>
    where
        K::Color: PixelColor,
    {
        let visibility = Visibility::Planes;
        self.render_with(
            mesh, edges, camera, settings, ws, codes, visibility, palette, sink, probe,
        )
    }

    /// [`render`](Self::render) with the row representation `codes` and the way
    /// `visibility` finds the nearest face. With [`Visibility::Order`] the frame is
    /// the order's picture: the nearest face in that order at each pixel centre
    /// (for a BSP tree's order, the nearest face; ties between coplanar faces go to
    /// the lower face index). `ws.vertices` then holds one entry per vertex of the
    /// order's surfaces and `ws.order` one per surface drawn. An order made for
    /// another mesh is [`Error::DepthOrderMismatch`]; a row with more faces than
    /// [`Self::CODE_BITS`] is [`Error::CodeTooWide`].
    #[allow(clippy::too_many_arguments)]
    pub fn render_with<K: SpanSink, P: Palette<Color = K::Color>, R: FrameProbe>(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &EdgeAdjacency<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut CodeWorkspace<'_>,
        mut codes: RowCodes<'_>,
        visibility: Visibility<'_>,
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>>
    where
        K::Color: PixelColor,
    {
        let fill = match &visibility {
            Visibility::Planes => Surfaces {
                mesh,
                source: &[],
                rank: &[],
            },
            Visibility::Order(order) => {
                if !order.fits(mesh) {
                    return Err(Error::DepthOrderMismatch);
                }
                Surfaces {
                    mesh: &order.surfaces,
                    source: order.source,
                    rank: order.rank,
                }
            }
        };
        self.priority = matches!(visibility, Visibility::Order(_));
        self.begin();
        if let RowCodes::BitSliced(words) = &mut codes {
            // Each row leaves the buffer as it found it: all zero.
            words.fill(0);
        }
        let input = FrameInput {
            mesh,
            positions: fill.mesh.vertices(),
            edges,
            camera,
            settings,
            s: Subpixel::<Frac>::BITS,
        };
        let CodeWorkspace {
            vertices,
            drawn,
            features,
            order,
            ids,
            lines,
        } = ws;
        let mut ids = IdWorkspace {
            vertices,
            drawn,
            features,
            ids,
            lines,
        };
        let mut pass = RowPass {
            engine: self,
            fill,
            order,
            faces: 0,
            codes,
        };
        render_ids::<POLY, _, _, _, _>(&mut pass, &input, &mut ids, &mut Flat(palette), sink, probe)
    }

    /// Sorts the drawn faces that reach the frame's rows by first row into `order`;
    /// returns how many there are.
    fn order_faces(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        fill: &Surfaces<'_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        order: &mut [u32],
    ) -> Result<usize, Error> {
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        let mut count = 0;
        for f in 0..fill.mesh.face_count() {
            if !bit(drawn, fill.source(f)) {
                continue;
            }
            let idx = fill.mesh.face(f);
            let outside = idx.iter().fold(0, |acc, &v| {
                acc | vertices
                    .get(v as usize)
                    .map_or(0xFF, ProjectedVertex::outside)
            });
            let rows = if outside == 0 {
                let ys = idx
                    .iter()
                    .filter_map(|&v| vertices.get(v as usize).map(|p| p.screen().y));
                row_span(ctx.s, ys)
            } else if index_polygon(ctx, vertices, idx, &mut poly)? {
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
        need(Capacity::DepthOrder, count, order.len())?;
        if let Some(order) = order.get_mut(..count) {
            crate::sort::sort_by_key(order, |&k| k);
        }
        Ok(count)
    }

    /// Forgets the last frame's active faces and edges.
    fn begin(&mut self) {
        self.live.clear();
        self.free.clear();
        for k in (0..FACES).rev() {
            let _ = self.free.push(k as u16);
        }
        self.edges.clear();
        self.next_face = 0;
        self.fold_memo = [0; FOLD_MEMO];
        self.row = 0;
        self.widest = 0;
        self.peak_faces = 0;
        self.peak_edges = 0;
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

/// One frame's rows: the engine, the surfaces it fills, the faces in order of
/// their first row, and the row representation.
struct RowPass<
    'e,
    's,
    'w,
    Frac: LeEqU32,
    const WORDS: usize,
    const FACES: usize,
    const EDGES: usize,
    const POLY: usize,
> {
    engine: &'e mut CodeFillRenderer<Frac, WORDS, FACES, EDGES, POLY>,
    fill: Surfaces<'s>,
    order: &'w mut [u32],
    faces: usize,
    codes: RowCodes<'w>,
}

impl<
        Frac: LeEqU32,
        const WORDS: usize,
        const FACES: usize,
        const EDGES: usize,
        const POLY: usize,
    > IdPass for RowPass<'_, '_, '_, Frac, WORDS, FACES, EDGES, POLY>
{
    fn begin(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
    ) -> Result<(), Error> {
        self.faces = self
            .engine
            .order_faces(ctx, &self.fill, vertices, drawn, self.order)?;
        Ok(())
    }

    /// Rows are scanned in order, once each: the apron a band shares with the next
    /// is kept.
    fn keeps_rows(&self) -> bool {
        true
    }

    fn fill(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        _: &[u32],
        band: &mut IdBand<'_>,
        fresh: u16,
    ) -> Result<u32, Error> {
        let order = self.order.get(..self.faces).unwrap_or(&[]);
        let mut spans = 0;
        for y in fresh..band.first + band.held {
            let Some(out) = band.row_mut(y) else { continue };
            if self.faces == 0 {
                out.fill(0);
                continue;
            }
            spans += match &mut self.codes {
                RowCodes::Crossings => self
                    .engine
                    .scan_row(ctx, &self.fill, vertices, order, y, out),
                RowCodes::BitSliced(words) => self
                    .engine
                    .scan_row_sliced(ctx, &self.fill, vertices, order, y, out, words),
            }?;
        }
        Ok(spans)
    }

    fn finish(&self, stats: &mut Stats) -> Result<(), Error> {
        let engine = &*self.engine;
        stats.code_bits = engine.widest as u32;
        stats.peak_faces = engine.peak_faces as u32;
        stats.peak_edges = engine.peak_edges as u32;
        if engine.widest > CodeFillRenderer::<Frac, WORDS, FACES, EDGES, POLY>::CODE_BITS {
            return Err(Error::CodeTooWide {
                needed: engine.widest,
                capacity: CodeFillRenderer::<Frac, WORDS, FACES, EDGES, POLY>::CODE_BITS,
            });
        }
        Ok(())
    }
}
