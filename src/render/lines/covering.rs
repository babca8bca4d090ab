//! The line test's search for a face that covers an edge point, where neither
//! pixel centre's nearest face holds it: every drawn face whose screen box holds
//! the point is asked, found through the boxes of chunks of consecutive faces, so
//! that a pixel reads a few chunks' faces instead of the whole mesh.

use heapless::Vec;

use super::{across_collapsed_own_face, owns, touches, view, Bend, EdgePixel, REACH_COVERING};
use crate::mesh::MeshEdge;
use crate::render::depth::coverage::covers;
use crate::render::depth::plane::DepthPlane;
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::{bit, face_polygon, FrameCtx};

/// Chunks of consecutive faces the search keeps a box of. Meshes are written
/// surface by surface, so a chunk is mostly one patch of the screen. 128 records of
/// six bytes are 768 bytes of the frame loop's stack (the micro:bit runs an exact
/// engine in 16 KiB of RAM). On the teapot from `render`'s view (50 faces a chunk)
/// a search reads 279 faces' first corners and 62 faces' boxes, against 456 boxes
/// with 64 chunks and no corner test; 256 chunks would read 233 first corners for
/// 1.5 KiB.
const CHUNKS: usize = 128;

/// A chunk's box in cells of `2^shift` half sub-pixel units, saturated to `u8`
/// (min x, min y, max x, max y), and the widest and highest box of one of its faces
/// (cells).
type CellBox = [u8; 6];

/// The box of no face: holds no point.
const EMPTY: CellBox = [u8::MAX, u8::MAX, 0, 0, 0, 0];

/// The box of a face cut by the view volume (asked by its polygon): holds every
/// point.
const ALL: CellBox = [0, 0, u8::MAX, u8::MAX, u8::MAX, u8::MAX];

/// The screen boxes of chunks of consecutive drawn faces, set up on the frame's
/// first search (most frames make none): a chunk's box holds the box of each of its
/// drawn faces, so a chunk whose box misses the point has no face that
/// [`box_holds`] it, and skipping it changes no answer.
#[derive(Debug)]
pub(crate) struct FaceChunks {
    /// Faces a chunk spans; 0 until set up.
    size: usize,
    /// Cell size: half sub-pixel units a cell, as a power of two, the frame's
    /// width and height in at most 256 cells.
    shift: u32,
    /// The chunks' boxes, in face order.
    boxes: [CellBox; CHUNKS],
}

impl FaceChunks {
    /// No boxes yet: the first search of the frame sets them up.
    pub const fn new() -> Self {
        Self {
            size: 0,
            shift: 0,
            boxes: [EMPTY; CHUNKS],
        }
    }

    /// Sets the boxes up from the frame's projected `vertices` and `drawn` faces,
    /// the first `count` faces of the mesh.
    fn set_up(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        count: usize,
    ) {
        let size = count.div_ceil(CHUNKS).max(1);
        self.size = size;
        let side = u32::from(ctx.viewport.width.max(ctx.viewport.height)).saturating_sub(1);
        self.shift = ctx.s + 1 + (32 - side.leading_zeros()).saturating_sub(8);
        let shift = self.shift;
        for (c, chunk) in self.boxes.iter_mut().enumerate() {
            let mut b = EMPTY;
            for f in (c * size..(c + 1) * size).take_while(|&f| f < count) {
                if !bit(drawn, f) {
                    continue;
                }
                b = match face_box(ctx, vertices, f) {
                    Some([lx, ly, hx, hy]) => {
                        let ([lx, ly], [hx, hy]) = (
                            [cell(lx, shift), cell(ly, shift)],
                            [cell(hx, shift), cell(hy, shift)],
                        );
                        [
                            b[0].min(lx),
                            b[1].min(ly),
                            b[2].max(hx),
                            b[3].max(hy),
                            b[4].max(hx.saturating_sub(lx)),
                            b[5].max(hy.saturating_sub(ly)),
                        ]
                    }
                    None => ALL,
                };
            }
            *chunk = b;
        }
    }
}

/// The cell holding half sub-pixel coordinate `v` (units of `2^-(s+1)` px),
/// cells of `2^shift` units, saturated to `u8`: flooring and saturating keep
/// order, so a box that holds a point holds it still in cells.
#[inline]
fn cell(v: i64, shift: u32) -> u8 {
    (v >> shift.min(63)).clamp(0, i64::from(u8::MAX)) as u8
}

/// Face `f`'s corners' screen box in half sub-pixel units (min x, min y, max x,
/// max y), or `None` when a corner is outside the view volume.
fn face_box(ctx: &FrameCtx<'_, '_>, vertices: &[ProjectedVertex], f: usize) -> Option<[i64; 4]> {
    let (mut lo, mut hi) = ([i64::MAX; 2], [i64::MIN; 2]);
    for &v in ctx.mesh.face(f) {
        let p = vertices
            .get(v as usize)
            .and_then(ProjectedVertex::projection)?;
        let (x, y) = (2 * i64::from(p.x), 2 * i64::from(p.y));
        lo = [lo[0].min(x), lo[1].min(y)];
        hi = [hi[0].max(x), hi[1].max(y)];
    }
    Some([lo[0], lo[1], hi[0], hi[1]])
}

/// Face `f`'s first corner on screen, `None` when it has none or it is out of
/// view. Where the face's box holds a point, this corner's cell is no farther from
/// the point's on an axis than the box is wide (or high) in cells.
#[inline]
fn first_corner(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    f: usize,
) -> Option<ScreenVertex> {
    let &v = ctx.mesh.face(f).first()?;
    vertices.get(v as usize)?.projection()
}

/// False when face `f`'s corners are all in view and their screen box misses the
/// edge point of `px`; true otherwise (a clipped face is asked by its polygon).
fn box_holds(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    f: usize,
    px: &EdgePixel,
) -> bool {
    face_box(ctx, vertices, f)
        .is_none_or(|[lx, ly, hx, hy]| (lx..=hx).contains(&px.px) && (ly..=hy).contains(&px.py))
}

/// Whether a drawn face other than the edge's own and those already asked
/// (`asked`) covers the edge point of `px` and is nearer there: the exact answer
/// where the faces nearest at the two pixel centres beside the point do not hold
/// it (a face beside a silhouette, seen at the centre, ends before the edge).
/// Every drawn face whose corners' box holds the point is asked, in face order,
/// found through the chunks' boxes ([`FaceChunks`]): the same faces and answers as
/// a scan of every face. Not rare on large meshes (1,220 of the teapot's line
/// pixels from `render`'s view): scanning every face took the teapot's Z-buffer
/// frame from 29 M to 989 M instructions, the chunks to 71 M; the exact engines'
/// mean over the 15 scenes from about 150 M to 18-48 M (Z-buffer 9.7 M before the
/// search; `cargo run --profile figures -p host_tests --bin report -- engines`,
/// BENCHMARKS.md "Every hidden-surface method").
#[inline(never)]
pub(super) fn covered_nearer<const POLY: usize>(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    drawn: &[u32],
    chunks: &mut FaceChunks,
    edge: &MeshEdge,
    px: &EdgePixel,
    asked: [u16; 2],
) -> bool {
    let count = ctx.mesh.face_count().min(usize::from(u16::MAX));
    if chunks.size == 0 {
        chunks.set_up(ctx, vertices, drawn, count);
    }
    let (x, y) = (cell(px.px, chunks.shift), cell(px.py, chunks.shift));
    let (size, shift) = (chunks.size, chunks.shift);
    for (c, &[lx, ly, hx, hy, rx, ry]) in chunks.boxes.iter().enumerate() {
        if x < lx || y < ly || x > hx || y > hy {
            continue;
        }
        for f in c * size..((c + 1) * size).min(count) {
            if !bit(drawn, f) {
                continue;
            }
            // Most faces of a chunk lie away from the point: one corner tells.
            if let Some(p) = first_corner(ctx, vertices, f) {
                let (cx, cy) = (
                    cell(2 * i64::from(p.x), shift),
                    cell(2 * i64::from(p.y), shift),
                );
                if cx.abs_diff(x) > rx || cy.abs_diff(y) > ry {
                    continue;
                }
            }
            if face_hides::<POLY>(ctx, vertices, drawn, edge, px, asked, f) {
                return true;
            }
        }
    }
    false
}

/// Whether face `f`, drawn, not `edge`'s own nor touching its ends nor among
/// `asked`, its box holding the edge point of `px`, covers the point and is nearer
/// there.
fn face_hides<const POLY: usize>(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    drawn: &[u32],
    edge: &MeshEdge,
    px: &EdgePixel,
    asked: [u16; 2],
    f: usize,
) -> bool {
    let id = (f + 1) as u16;
    if !bit(drawn, f)
        || asked.contains(&id)
        || !box_holds(ctx, vertices, f, px)
        || owns(ctx.mesh, edge, f)
        || touches(ctx.mesh, edge, f)
    {
        return false;
    }
    // Set up here, not in the cache: the faces at the two centres stay there for
    // the next pixels, and a face that does not cover the point needs no plane.
    let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
    if !face_polygon(ctx, vertices, f, &mut poly).unwrap_or(false)
        || !covers(&poly, px.px, px.py)
        || across_collapsed_own_face(ctx, vertices, edge, f, &poly, px)
    {
        return false;
    }
    let Some(plane) = DepthPlane::new(&poly, ctx.s) else {
        return false;
    };
    let mut bend = Bend::of(ctx.mesh.face(f).len());
    bend.nearer(
        &view(ctx, vertices, f, &poly, &plane),
        px,
        (px.px, px.py),
        REACH_COVERING,
    )
}
