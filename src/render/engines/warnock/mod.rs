//! Warnock's area subdivision (notes 002 and 004) with an explicit, bounded stack:
//! an area of the band is filled at once when nothing or one face decides it, and
//! split in four (or two) otherwise, down to single pixels, which are decided
//! exactly as the Z-buffer decides them.
//!
//! Per frame, every drawn face in view is clipped and projected once, and its depth
//! plane, tie, pixel box and convexity are kept in lent storage ([`WarnockFace`]);
//! the plane (two divisions) because every decision needs it. The clipped polygon
//! is kept inline when it has at most four vertices (most faces: 48 bytes a face);
//! a larger one is rebuilt from the vertex cache when a coverage test needs it
//! (keeping every polygon would lend `faces x POLY` screen vertices). Measured by
//! callgrind on suzanne at 400x240 (500 quads, one band): rebuilding every polygon
//! from the vertex cache took 61.5 M instructions a frame, the inline polygons
//! (and keeping the last one built) 48.8 M, for 24 kB more lent storage; the
//! Z-buffer takes 11.0 M.
//!
//! An area popped from the stack holds the candidates of its parent: those whose
//! pixel box meets it, and, for a convex candidate, those not wholly outside one of
//! its edges, stay. Then, with candidates sorted by face index:
//! - none: the area shows no face (its ids stay 0);
//! - one: each pixel centre it covers shows it (all of them, without a test, when it
//!   is convex and covers the four corner centres);
//! - a convex candidate covering the four corner centres (so every centre between
//!   them) that is nearer than every other candidate, at every centre of the area,
//!   by more than the tie the Z-buffer would apply: the area shows it. Depth bounds
//!   come from the corner centres, where an affine depth, clamped, has its extremes;
//! - one pixel: the candidates covering its centre are compared in increasing face
//!   index, a later one winning only when nearer by more than its tie, exactly the
//!   Z-buffer's rule, so the frame is the Z-buffer's (32-bit depth) pixel for pixel
//!   (a face that is not planar takes the depth of its fan triangle that holds the
//!   centre, evaluated from the triangle's corners, and its depth bounds over an
//!   area widen by how far its plane leaves its corners; where two faces cross,
//!   that evaluation can round apart from the Z-buffer's fan planes);
//! - else: the area is split at its middle in x and y (only along a side longer than
//!   one pixel) and the parts are pushed.
//!
//! Storage bounds (see [`WarnockSizes`]): with `L = ceil(log2(max(width, rows)))`
//! for a band of `rows` held rows, every split at least halves the longer side (a
//! side of `n` becomes at most `ceil(n / 2)`), so an area at depth `L` is one pixel.
//! Depth first, the stack holds at most three unvisited siblings at each depth
//! 1 .. L plus the four children just pushed: `3 L + 1` areas. The candidate lists
//! live in one lent slice used as a stack: the band's faces first, then one list per
//! depth on the path being visited (each a subset of the one before), so at most
//! `faces x (L + 2)` entries.

mod area;
mod geom;
#[cfg(test)]
mod tests;

use core::marker::PhantomData;

use embedded_graphics_core::pixelcolor::PixelColor;
use fixed::types::extra::LeEqU32;
use heapless::Vec;

use crate::camera::Camera;
use crate::geometry::Subpixel;
use crate::mesh::{EdgeAdjacency, Mesh};
use crate::render::band::IdBand;
use crate::render::compose::{Flat, FrameProbe, Palette};
use crate::render::depth::fan::takes_fan_depth;
use crate::render::depth::fan::{bend, ROUNDING};
use crate::render::depth::plane::DepthPlane;
use crate::render::idpass::{render_ids, FrameInput, IdPass, IdWorkspace};
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::{bit, face_polygon, need, FrameCtx, Settings, Stats};
use crate::Capacity;
use crate::{Error, SpanSink};
use area::Areas;
use geom::{convex_orientation, PixelBox, Rect};

/// One drawn face in view, as area subdivision asks about it: kept for a frame in
/// [`WarnockStorage::faces`].
#[derive(Debug, Clone, Copy, Default)]
pub struct WarnockFace {
    plane: DepthPlane,
    tie: u32,
    /// How far the face's fan triangles may leave its plane: 0 for a planar face;
    /// for one that is not ([`takes_fan_depth`]), its [`bend`] and the rounding,
    /// `u32::MAX` when clipped (its corners then bound nothing).
    bend: u32,
    /// The mesh face (0-based; a mesh has at most 65 535 faces).
    face: u16,
    /// +1 or -1 for a convex polygon, 0 otherwise.
    sense: i8,
    pixels: PixelBox,
    /// The clipped polygon when it has at most 4 vertices (`small_len` of them),
    /// else `small_len` is 0 and it is rebuilt when needed.
    small: [ScreenVertex; 4],
    small_len: u8,
}

/// One entry of the explicit stack: an area still to visit and the candidate list
/// of its parent (a range of [`WarnockStorage::lists`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct WarnockArea {
    rect: Rect,
    list: u32,
    len: u32,
}

/// Storage the caller lends to [`WarnockRenderer::render`], besides the
/// [`IdWorkspace`]; [`WarnockSizes::for_frame`] says how much.
#[derive(Debug)]
pub struct WarnockStorage<'s> {
    /// The explicit stack of areas.
    pub areas: &'s mut [WarnockArea],
    /// Candidate lists (indices into `faces`), used as a stack.
    pub lists: &'s mut [u16],
    /// The frame's drawn faces in view.
    pub faces: &'s mut [WarnockFace],
}

impl WarnockStorage<'_> {
    /// Bytes of all the lent buffers.
    pub fn bytes(&self) -> usize {
        use core::mem::size_of_val;
        size_of_val(self.areas) + size_of_val(self.lists) + size_of_val(self.faces)
    }
}

/// Entries of each [`WarnockStorage`] slice that always suffice for a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct WarnockSizes {
    /// Stack entries: `3 L + 1`.
    pub areas: usize,
    /// Candidate list entries: `faces x (L + 2)`.
    pub lists: usize,
    /// Face entries: the mesh's faces.
    pub faces: usize,
}

impl WarnockSizes {
    /// Sizes for a mesh of `faces` faces in a `width` x `height` frame drawn in
    /// bands of `band_rows` rows, where `L = ceil(log2(max(width, held rows)))` and
    /// the held rows are the band plus its apron ([`storage_rows`](crate::render::storage_rows)).
    /// Fewer list entries often do: a frame that needs more stops with
    /// [`Error::CapacityExceeded`] naming this bound.
    pub const fn for_frame(faces: usize, width: u16, height: u16, band_rows: u16) -> Self {
        let band = if band_rows == 0 { 1 } else { band_rows };
        let held = if band >= height { height } else { band + 2 };
        let levels = levels(width, held);
        Self {
            areas: 3 * levels + 1,
            lists: faces * (levels + 2),
            faces,
        }
    }
}

/// `ceil(log2(max(width, rows)))`: the splits from a `width` x `rows` area to one
/// pixel.
const fn levels(width: u16, rows: u16) -> usize {
    let n = if width > rows { width } else { rows };
    if n <= 1 {
        0
    } else {
        (16 - (n - 1).leading_zeros()) as usize
    }
}

/// Warnock's area subdivision with S = `Frac` sub-pixel bits and room for `POLY`
/// vertices per clipped face. It draws the frame of the Z-buffer with 32-bit depth.
#[derive(Debug)]
pub struct WarnockRenderer<Frac: LeEqU32, const POLY: usize> {
    _frac: PhantomData<Frac>,
}

default_is_new!(WarnockRenderer<POLY>);

impl<Frac: LeEqU32, const POLY: usize> WarnockRenderer<Frac, POLY> {
    /// A renderer (it keeps nothing between frames).
    pub const fn new() -> Self {
        Self { _frac: PhantomData }
    }

    /// Renders `mesh` seen by `camera` into `sink`, deciding the visible faces by
    /// area subdivision in `storage`. Too little storage is
    /// [`Error::CapacityExceeded`] with what would do: the faces in view for
    /// `faces`, the bounds of [`WarnockSizes`] for `areas` and `lists`.
    /// `Stats::spans` counts the id runs written (a filled area one per row, a
    /// pixel decided alone one) plus the spans sent to the sink.
    #[allow(clippy::too_many_arguments)]
    pub fn render<K: SpanSink, P: Palette<Color = K::Color>, R: FrameProbe>(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &EdgeAdjacency<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut IdWorkspace<'_>,
        storage: WarnockStorage<'_>,
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>>
    where
        K::Color: PixelColor,
    {
        let input = FrameInput::of_mesh(mesh, edges, camera, settings, Subpixel::<Frac>::BITS);
        let mut pass = Subdivide::<POLY> { storage, count: 0 };
        render_ids::<POLY, _, _, _, _>(&mut pass, &input, ws, &mut Flat(palette), sink, probe)
    }
}

/// One frame's subdivision.
struct Subdivide<'s, const POLY: usize> {
    storage: WarnockStorage<'s>,
    /// Entries of `storage.faces` in use.
    count: usize,
}

impl<const POLY: usize> IdPass for Subdivide<'_, POLY> {
    fn begin(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
    ) -> Result<(), Error> {
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        let (width, height) = (ctx.viewport.width, ctx.viewport.height);
        let mut count = 0;
        for f in 0..ctx.mesh.face_count() {
            if !bit(drawn, f) || !face_polygon(ctx, vertices, f, &mut poly)? {
                continue;
            }
            let Some(pixels) = PixelBox::of(&poly, ctx.s, width, height) else {
                continue;
            };
            let Some(plane) = DepthPlane::new(&poly, ctx.s) else {
                continue;
            };
            // A face that is not planar takes its fan triangle's depth at a pixel
            // (CONVENTIONS.md): an area's depth bounds widen by its bend.
            let bend = if !takes_fan_depth(ctx.mesh, f, &poly, &plane) {
                0
            } else if ctx
                .mesh
                .face(f)
                .iter()
                .all(|&v| vertices.get(v as usize).is_some_and(|p| p.outside() == 0))
            {
                bend(&poly, &plane).saturating_add(ROUNDING)
            } else {
                u32::MAX
            };
            let mut small = [ScreenVertex::default(); 4];
            let small_len = if poly.len() <= small.len() {
                for (to, from) in small.iter_mut().zip(poly.iter()) {
                    *to = *from;
                }
                poly.len() as u8
            } else {
                0
            };
            if let Some(slot) = self.storage.faces.get_mut(count) {
                *slot = WarnockFace {
                    small,
                    small_len,
                    plane,
                    tie: plane.tie(),
                    bend,
                    // Below MAX_FACES = 65 535.
                    face: f as u16,
                    sense: convex_orientation::<POLY>(&poly),
                    pixels,
                };
            }
            count += 1;
        }
        need(Capacity::WarnockFaces, count, self.storage.faces.len())?;
        self.count = count;
        Ok(())
    }

    fn fill(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        _drawn: &[u32],
        band: &mut IdBand<'_>,
        _fresh: u16,
    ) -> Result<u32, Error> {
        if band.held == 0 || band.width == 0 {
            return Ok(0);
        }
        let root = Rect {
            x0: 0,
            y0: band.first,
            x1: band.width,
            y1: band.first + band.held,
        };
        let levels = levels(band.width, band.held);
        let WarnockStorage {
            areas,
            lists,
            faces,
        } = &mut self.storage;
        let faces = faces.get(..self.count).unwrap_or(&[]);
        need(Capacity::WarnockAreas, 3 * levels + 1, areas.len())?;
        let (list_bound, list_cap) = (self.count * (levels + 2), lists.len());
        let list_full = || Error::CapacityExceeded {
            what: Capacity::WarnockLists,
            needed: list_bound,
            capacity: list_cap,
        };
        // The band's faces: the root's parent list.
        let mut len = 0usize;
        for (k, face) in faces.iter().enumerate() {
            if face.pixels.meets(&root) {
                *lists.get_mut(len).ok_or_else(list_full)? = k as u16;
                len += 1;
            }
        }
        let mut sub = Areas::<POLY> {
            ctx,
            vertices,
            faces,
            band,
            poly: Vec::new(),
            poly_of: None,
            runs: 0,
        };
        let mut top = 0usize;
        push(
            areas,
            &mut top,
            WarnockArea {
                rect: root,
                list: 0,
                len: len as u32,
            },
        );
        while top > 0 {
            top -= 1;
            let Some(&area) = areas.get(top) else { break };
            let rect = area.rect;
            // The area's own list goes right after its parent's: everything above
            // belonged to areas already finished (depth first).
            let start = area.list as usize + area.len as usize;
            let corners = rect.corners(ctx.s);
            let mut n = 0usize;
            for k in 0..area.len as usize {
                let Some(&slot) = lists.get(area.list as usize + k) else {
                    break;
                };
                if !sub.candidate(slot, &rect, &corners)? {
                    continue;
                }
                *lists.get_mut(start + n).ok_or_else(list_full)? = slot;
                n += 1;
            }
            let list = lists.get(start..start + n).unwrap_or(&[]);
            if sub.decide(list, &rect, &corners)? {
                continue;
            }
            // Split at the middle of each side longer than one pixel.
            let (w, h) = (rect.x1 - rect.x0, rect.y1 - rect.y0);
            let xs = if w > 1 { rect.x0 + w / 2 } else { rect.x1 };
            let ys = if h > 1 { rect.y0 + h / 2 } else { rect.y1 };
            for (x0, x1) in [(xs, rect.x1), (rect.x0, xs)] {
                for (y0, y1) in [(ys, rect.y1), (rect.y0, ys)] {
                    if x0 < x1 && y0 < y1 {
                        let child = WarnockArea {
                            rect: Rect { x0, y0, x1, y1 },
                            list: start as u32,
                            len: n as u32,
                        };
                        push(areas, &mut top, child);
                    }
                }
            }
        }
        Ok(sub.runs)
    }
}

/// Puts `area` on the stack (within the bound checked at the band's start).
fn push(areas: &mut [WarnockArea], top: &mut usize, area: WarnockArea) {
    if let Some(slot) = areas.get_mut(*top) {
        *slot = area;
        *top += 1;
    }
}
