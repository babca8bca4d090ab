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
/// surface by surface, so a chunk is mostly one small patch of the screen
/// (teapot: 99 faces a chunk, a pixel reads the faces of a few); 64 boxes of
/// four `i16` are 512 bytes of stack.
const CHUNKS: usize = 64;

/// A box in whole pixels (min x, min y, max x, max y), saturated to `i16`.
type PixelBox = [i16; 4];

/// The box of no face: holds no point.
const EMPTY: PixelBox = [i16::MAX, i16::MAX, i16::MIN, i16::MIN];

/// The box of a face cut by the view volume (asked by its polygon): holds every
/// point.
const ALL: PixelBox = [i16::MIN, i16::MIN, i16::MAX, i16::MAX];

/// The screen boxes of chunks of consecutive drawn faces, set up on the frame's
/// first search (most frames make none): a chunk's box holds the box of each of its
/// drawn faces, so a chunk whose box misses the point has no face that
/// [`box_holds`] it, and skipping it changes no answer.
#[derive(Debug)]
pub(crate) struct FaceChunks {
    /// Faces a chunk spans; 0 until set up.
    size: usize,
    /// The chunks' boxes, in face order.
    boxes: [PixelBox; CHUNKS],
}

impl FaceChunks {
    /// No boxes yet: the first search of the frame sets them up.
    pub const fn new() -> Self {
        Self {
            size: 0,
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
        for (c, chunk) in self.boxes.iter_mut().enumerate() {
            let mut b = EMPTY;
            for f in (c * size..(c + 1) * size).take_while(|&f| f < count) {
                if !bit(drawn, f) {
                    continue;
                }
                b = match face_box(ctx, vertices, f) {
                    Some([lx, ly, hx, hy]) => {
                        let p = |v: i64| pixel(v, ctx.s);
                        [
                            b[0].min(p(lx)),
                            b[1].min(p(ly)),
                            b[2].max(p(hx)),
                            b[3].max(p(hy)),
                        ]
                    }
                    None => ALL,
                };
            }
            *chunk = b;
        }
    }
}

/// The pixel holding half sub-pixel coordinate `v` (units of `2^-(s+1)` px),
/// saturated to `i16`: flooring and saturating keep order, so a box that holds a
/// point holds it still in pixels.
fn pixel(v: i64, s: u32) -> i16 {
    (v >> (s + 1)).clamp(i64::from(i16::MIN), i64::from(i16::MAX)) as i16
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
/// but only in the chunks whose box holds it ([`FaceChunks`]). Not rare on large
/// meshes: before the chunks, asking every face took the teapot's Z-buffer frame
/// from 29 M to 989 M instructions (`cargo run --profile figures -p host_tests
/// --bin report -- engines`, BENCHMARKS.md).
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
    let (x, y) = (pixel(px.px, ctx.s), pixel(px.py, ctx.s));
    let size = chunks.size;
    for (c, b) in chunks.boxes.iter().enumerate() {
        if x < b[0] || y < b[1] || x > b[2] || y > b[3] {
            continue;
        }
        for f in (c * size..(c + 1) * size).take_while(|&f| f < count) {
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
