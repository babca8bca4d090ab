//! The line pass: each feature edge is clipped, projected and drawn one pixel per
//! pixel centre along its major axis; each pixel takes the visibility of the edge
//! point there. Results go into two bit masks per band row (visible, hidden).

use heapless::Vec;

mod bend;
mod covering;

pub(crate) use bend::Bend;
pub(crate) use covering::FaceChunks;

use super::transform::{DepthGrid, ProjectedVertex, ScreenVertex};
use super::{bit, face_polygon, FrameCtx};
use crate::mesh::{face_owns_edge, EdgeAdjacency, EdgeKind, Mesh, MeshEdge};
use crate::render::band::IdBand;
use crate::render::depth::coverage::covers;
use crate::render::depth::fan::FaceView;
use crate::render::depth::plane::DepthPlane;
use crate::scan::edge::div_rem_euclid;
use covering::covered_nearer;

/// Visible and hidden line pixels of one band, bit-packed: bit `k` of word `w` of a
/// row is pixel `32w + k`.
#[derive(Debug)]
pub(crate) struct LineMasks<'s> {
    /// `rows * row_words` visible words, then as many hidden words.
    pub words: &'s mut [u32],
    pub row_words: usize,
    pub rows: u16,
}

impl LineMasks<'_> {
    /// Clears the first `rows` rows of both masks.
    pub fn reset(&mut self, rows: u16) {
        self.rows = rows;
        let n = 2 * self.row_words * usize::from(rows);
        self.words.iter_mut().take(n).for_each(|w| *w = 0);
    }

    /// Marks pixel `x` of band row `row`.
    pub fn set(&mut self, x: u16, row: u16, hidden: bool) {
        let (x, row) = (usize::from(x), usize::from(row));
        let plane = if hidden {
            self.row_words * usize::from(self.rows)
        } else {
            0
        };
        if let Some(w) = self.words.get_mut(plane + row * self.row_words + x / 32) {
            *w |= 1 << (x % 32);
        }
    }

    /// The visible and hidden words of band row `row`.
    pub fn row(&self, row: u16) -> (&[u32], &[u32]) {
        let n = self.row_words;
        let start = usize::from(row) * n;
        let hidden = n * usize::from(self.rows) + start;
        (
            self.words.get(start..start + n).unwrap_or(&[]),
            self.words.get(hidden..hidden + n).unwrap_or(&[]),
        )
    }
}

/// A band as the frame loop's line pass and composition see it: its face ids (own
/// rows and apron) and its line masks.
#[derive(Debug)]
pub(crate) struct Band<'s> {
    /// The face ids, filled by the engine's pass.
    pub ids: IdBand<'s>,
    /// The line pixels of the band's own rows, drawn by the line pass.
    pub lines: LineMasks<'s>,
}

/// One pixel of a projected edge, with the edge point it stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct EdgePixel {
    pub x: u16,
    pub y: u16,
    /// The edge point, in half sub-pixel units (`2^-(S+1)` px).
    pub px: i64,
    pub py: i64,
    /// Its nearness.
    pub q: u32,
    /// How far its nearness may be from the true one through the clip grid's
    /// rounding ([`DepthGrid`]).
    pub slack: u32,
}

impl EdgePixel {
    /// The pixel with its nearness uncertainty on the frame's depth `grid`.
    pub fn with_slack(self, grid: &DepthGrid) -> Self {
        Self {
            slack: grid.slack(self.q),
            ..self
        }
    }
}

/// Calls `pixel` for each pixel of segment `a`-`b` in rows `top..end` and columns
/// `0..width`: one pixel per pixel centre along the major axis (end points
/// included), in the row or column that contains the edge point there. Its
/// `slack` is 0: the line test sets it ([`EdgePixel::with_slack`]) where it asks.
pub(crate) fn walk_segment(
    a: &ScreenVertex,
    b: &ScreenVertex,
    s: u32,
    width: u16,
    rows: core::ops::Range<u16>,
    mut pixel: impl FnMut(EdgePixel),
) {
    let h = 1i64 << s;
    let p = 2 * h;
    let (ax, ay, bx, by) = (
        2 * i64::from(a.x),
        2 * i64::from(a.y),
        2 * i64::from(b.x),
        2 * i64::from(b.y),
    );
    let (dx, dy) = (bx - ax, by - ay);
    if dx == 0 && dy == 0 {
        return;
    }
    let x_major = dx.abs() >= dy.abs();
    // Walk along the major axis u, with v the minor axis; (u0, v0) the start.
    let (u0, v0, u1, v1, q0, q1) = match (x_major, if x_major { dx } else { dy } >= 0) {
        (true, true) => (ax, ay, bx, by, a.q, b.q),
        (true, false) => (bx, by, ax, ay, b.q, a.q),
        (false, true) => (ay, ax, by, bx, a.q, b.q),
        (false, false) => (by, bx, ay, ax, b.q, a.q),
    };
    let (du, dv, dq) = (u1 - u0, v1 - v0, i64::from(q1) - i64::from(q0));
    // Pixel centres (2k+1)h in [u0, u1].
    // Floor divisions by the pixel size 2^(S+1) are shifts.
    let k_first = (u0 - h + p - 1) >> (s + 1);
    let k_last = (u1 - h) >> (s + 1);
    let (limit_u, limit_v) = if x_major {
        (
            i64::from(width),
            (i64::from(rows.start), i64::from(rows.end)),
        )
    } else {
        (i64::from(rows.end), (0, i64::from(width)))
    };
    let mut k_lo = k_first.max(0);
    let mut k_hi = k_last.min(limit_u - 1);
    if !x_major {
        k_lo = k_lo.max(i64::from(rows.start));
    }
    // For an x-major edge, narrow the columns to those whose row can be in the band.
    if x_major && dv != 0 {
        let at = |v: i64| u0 + quotient((v - v0) * du, dv);
        let (ua, ub) = (at(limit_v.0 * p), at(limit_v.1 * p));
        let (lo, hi) = (ua.min(ub), ua.max(ub));
        k_lo = k_lo.max(((lo - h) >> (s + 1)) - 1);
        k_hi = k_hi.min(((hi - h) >> (s + 1)) + 1);
    }
    if k_lo > k_hi {
        return;
    }
    // Minor coordinate v and nearness q at the first centre, then carried from
    // centre to centre as quotient and remainder: no division per pixel.
    let c = (2 * k_lo + 1) * h;
    let mut v = Stepper::new(v0 * du + (c - u0) * dv, du, p * dv);
    let mut q = Stepper::new((c - u0) * dq, du, p * dq);
    for k in k_lo..=k_hi {
        let c = (2 * k + 1) * h;
        // The pixel holding the edge point: floor(v / p).
        let m = v.quotient >> (s + 1);
        if m >= limit_v.0 && m < limit_v.1 {
            let (x, y, px, py) = if x_major {
                (k, m, c, v.quotient)
            } else {
                (m, k, v.quotient, c)
            };
            let q = (i64::from(q0) + q.quotient).clamp(0, 1 << 31);
            pixel(EdgePixel {
                x: x as u16,
                y: y as u16,
                px,
                py,
                q: q as u32,
                slack: 0,
            });
        }
        v.advance();
        q.advance();
    }
}

/// `n / d` rounded toward zero (`d != 0`), in 32 bits when both fit: one hardware
/// divide on a Cortex-M4 instead of a 64-bit library call.
fn quotient(n: i64, d: i64) -> i64 {
    if let (Ok(n32), Ok(d32)) = (i32::try_from(n), i32::try_from(d)) {
        return i64::from(n32.checked_div(d32).unwrap_or(0));
    }
    n.checked_div(d).unwrap_or(0)
}

/// `floor(n / d)` for `n` growing by `step` each time, `d > 0`, kept as quotient
/// and remainder so that each step is two adds and a compare.
#[derive(Debug, Clone, Copy)]
struct Stepper {
    quotient: i64,
    remainder: i64,
    step_q: i64,
    step_r: i64,
    d: i64,
}

impl Stepper {
    fn new(n: i64, d: i64, step: i64) -> Self {
        let d = d.max(1);
        let ((quotient, remainder), (step_q, step_r)) =
            (div_rem_euclid(n, d), div_rem_euclid(step, d));
        Self {
            quotient,
            remainder,
            step_q,
            step_r,
            d,
        }
    }

    fn advance(&mut self) {
        self.quotient += self.step_q;
        self.remainder += self.step_r;
        if self.remainder >= self.d {
            self.remainder -= self.d;
            self.quotient += 1;
        }
    }
}

/// Draws the feature edges that reach the band into its line masks. Bands come top
/// to bottom, each below the last: an edge that ends above the next band (or is out
/// of view) leaves `features`, so that later bands do not ask it again. `chunks`
/// is the frame's, kept from band to band (set up on the frame's first search).
pub(crate) fn line_pass<const POLY: usize>(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    drawn: &[u32],
    features: &mut [u32],
    edges: &EdgeAdjacency<'_>,
    chunks: &mut FaceChunks,
    band: &mut Band<'_>,
) {
    let Band {
        ids: band,
        lines: masks,
    } = band;
    let band: &IdBand<'_> = band;
    let hide = ctx.settings.mode.needs_depth();
    let grid = ctx.view.depth_grid();
    // The last face tested for covering an edge point, with its polygon and plane.
    let mut cache = FaceCache::<POLY>::new(chunks);
    let all = edges.edges();
    // Most edges miss a band: rejected by their ends' rows (which hold every row the
    // walk draws) before the clipping and the walk's divisions (a long library call
    // each on a Cortex-M4).
    let next = i32::from(band.top + band.rows);
    let last = next >= i32::from(ctx.viewport.height);
    for (w, word) in features.iter_mut().enumerate() {
        let (mut bits, mut done) = (*word, 0u32);
        while bits != 0 {
            let k = bits.trailing_zeros();
            bits &= bits - 1;
            let Some(edge) = all.get(32 * w + k as usize) else {
                break;
            };
            let Some((a, b)) = edge_on_screen(ctx, vertices, edge) else {
                done |= 1 << k;
                continue;
            };
            let (lo, hi) = (a.y.min(b.y) >> ctx.s, a.y.max(b.y) >> ctx.s);
            if hi < next && !last {
                done |= 1 << k;
            }
            if hi < i32::from(band.top) || lo >= next {
                continue;
            }
            let rows = band.top..band.top + band.rows;
            walk_segment(&a, &b, ctx.s, ctx.viewport.width, rows, |px| {
                let hidden = hide && {
                    let px = px.with_slack(&grid);
                    hidden(ctx, vertices, drawn, edge, band, &px, &mut cache)
                };
                masks.set(px.x, px.y - band.top, hidden);
            });
        }
        // Out of view, or done with after this band.
        *word &= !done;
    }
}

/// The edge clipped to the view and projected, or `None` when it is out of view.
#[inline]
pub(crate) fn edge_on_screen(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    edge: &MeshEdge,
) -> Option<(ScreenVertex, ScreenVertex)> {
    let (pa, pb) = (
        vertices.get(edge.a as usize)?,
        vertices.get(edge.b as usize)?,
    );
    match (pa.projection(), pb.projection()) {
        (Some(a), Some(b)) => Some((a, b)),
        _ => clipped_edge(ctx, vertices, edge, (pa.outside(), pb.outside())),
    }
}

/// [`edge_on_screen`] of an edge with an end outside the view volume (`oa`, `ob`:
/// its ends' outcodes).
// Out of line: inlined into the line pass's band loop it took the M4 image 7.9 KB
// of flash and 544 B of stack, for the few edges that need it.
#[inline(never)]
fn clipped_edge(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    edge: &MeshEdge,
    (oa, ob): (u8, u8),
) -> Option<(ScreenVertex, ScreenVertex)> {
    if oa & ob != 0 {
        return None;
    }
    let (ca, cb) = (
        ctx.clip_of(vertices, edge.a)?,
        ctx.clip_of(vertices, edge.b)?,
    );
    let (first, last) = ctx.view.clip_segment(ca, cb, oa | ob)?;
    Some((ctx.view.project(&first), ctx.view.project(&last)))
}

/// Faces the line pass keeps set up: an edge's pixels meet the same few faces.
const CACHED_FACES: usize = 2;

/// A face the line pass has set up: 1 + its index (0 none), its polygon on screen,
/// its depth plane, and how far its fan triangles bend off that plane.
struct CachedFace<const POLY: usize> {
    id: u16,
    poly: Vec<ScreenVertex, POLY>,
    plane: Option<DepthPlane>,
    bend: Bend,
}

/// The last faces tested by the line pass, and the frame's chunk boxes for the
/// search of a covering face ([`covered_nearer`]).
struct FaceCache<'c, const POLY: usize> {
    slots: [CachedFace<POLY>; CACHED_FACES],
    next: usize,
    chunks: &'c mut FaceChunks,
}

impl<'c, const POLY: usize> FaceCache<'c, POLY> {
    fn new(chunks: &'c mut FaceChunks) -> Self {
        Self {
            slots: [const {
                CachedFace {
                    id: 0,
                    poly: Vec::new(),
                    plane: None,
                    bend: Bend::NONE,
                }
            }; CACHED_FACES],
            next: 0,
            chunks,
        }
    }

    /// Slot of face `id` (1 + index), filled in place when missing: the polygon
    /// buffers are large, so they never move.
    // Indexing: k is a found position or `next`, always < CACHED_FACES.
    #[allow(clippy::indexing_slicing)]
    fn get(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        id: u16,
    ) -> &mut CachedFace<POLY> {
        let k = match self.slots.iter().position(|slot| slot.id == id) {
            Some(k) => k,
            None => {
                let k = self.next;
                self.next = (self.next + 1) % CACHED_FACES;
                let slot = &mut self.slots[k];
                let f = usize::from(id - 1);
                slot.id = id;
                slot.plane = None;
                slot.bend = Bend::NONE;
                if bit(drawn, f) && face_polygon(ctx, vertices, f, &mut slot.poly).unwrap_or(false)
                {
                    slot.plane = DepthPlane::new(&slot.poly, ctx.s);
                    slot.bend = Bend::of(ctx.mesh.face(f).len());
                }
                k
            }
        };
        &mut self.slots[k]
    }
}

/// Whether the edge point of `px` is hidden. The face nearest at the pixel centre
/// decides, or, when it does not contain the edge point (up to half a pixel off the
/// centre) or is one of the edge's own faces, the face nearest at the neighbouring
/// centre on that side, if that one contains it; when neither does, every face that
/// contains it ([`covered_nearer`]). A face hides the point when it contains it and is
/// nearer there by the uncertainty of snapping ([`margin`]), never by its plane
/// extended past its edges ([conventions](crate::conventions): only a face covering
/// the point's projection hides it). A face that is not planar may answer by its fan
/// triangle's depth ([`Bend::nearer`]).
// Out of line: inlined, its three depth tests' temporaries took their own stack.
#[inline(never)]
fn hidden<const POLY: usize>(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    drawn: &[u32],
    edge: &MeshEdge,
    band: &IdBand<'_>,
    px: &EdgePixel,
    cache: &mut FaceCache<'_, POLY>,
) -> bool {
    let own = |id: u16| owns(ctx.mesh, edge, usize::from(id - 1));
    let centre = |k: u16| (2 * i64::from(k) + 1) << ctx.s;
    // The neighbour on the side of the edge point (the minor axis of the edge).
    let (dx, dy) = (px.px - centre(px.x), px.py - centre(px.y));
    let step = |d: i64, k: u16| match d.signum() {
        -1 => k.checked_sub(1),
        1 => k.checked_add(1),
        _ => None,
    };
    let beside = if dy != 0 {
        step(dy, px.y).map(|y| band.id(px.x, y))
    } else {
        step(dx, px.x).map(|x| band.id(x, px.y))
    };
    let nearest = band.id(px.x, px.y);
    // Faces asked that do not hold the edge point: where one of them is not the
    // edge's own, a face that holds it may hide behind it at both centres.
    let mut asked = [0u16; 2];
    let mut after_own = false;
    for (slot_k, id) in [Some(nearest), beside]
        .into_iter()
        .flatten()
        .filter(|&id| id != 0)
        .enumerate()
    {
        if own(id) {
            // The edge's own face at the centre may turn away within the half pixel
            // to the edge point (seen edge-on), and another face, nearest beside, be
            // in front of the point: that one is asked still.
            if id == nearest && beside.is_some_and(|b| b != id) {
                after_own = true;
                continue;
            }
            return false;
        }
        // A face covering the pixel centre contains an edge point at the centre; a
        // triangle (convex, clipped or not) covering both centres contains the edge
        // point between them. Otherwise the polygon is tested.
        let f = usize::from(id - 1);
        let sure = id == nearest
            && (beside.is_none() || (beside == Some(id) && ctx.mesh.face(f).len() == 3));
        let slot = cache.get(ctx, vertices, drawn, id);
        let Some(plane) = slot.plane.as_ref() else {
            continue;
        };
        let face = view(ctx, vertices, f, &slot.poly, plane);
        if sure || covers(&slot.poly, px.px, px.py) {
            if across_collapsed_own_face(ctx, vertices, edge, f, &slot.poly, px) {
                return false;
            }
            return slot.bend.nearer(&face, px, (px.px, px.py), REACH_COVERING);
        }
        if !after_own {
            if let Some(a) = asked.get_mut(slot_k) {
                *a = id;
            }
        }
    }
    asked != [0, 0] && covered_nearer::<POLY>(ctx, vertices, drawn, cache.chunks, edge, px, asked)
}

/// Whether face `f` is one of `edge`'s own faces (for a non-manifold edge, any
/// face that uses it).
#[inline]
pub(crate) fn owns(mesh: &Mesh<'_>, edge: &MeshEdge, f: usize) -> bool {
    edge.faces
        .iter()
        .take(edge.face_count.min(2) as usize)
        .any(|&g| g as usize == f)
        || (edge.kind == EdgeKind::NonManifold && face_owns_edge(mesh, edge, f))
}

/// Face `f` with its polygon and plane, for [`Bend::nearer`].
fn view<'a>(
    ctx: &'a FrameCtx<'_, '_>,
    vertices: &'a [ProjectedVertex],
    f: usize,
    poly: &'a [ScreenVertex],
    plane: &'a DepthPlane,
) -> FaceView<'a> {
    FaceView {
        mesh: ctx.mesh,
        vertices,
        f,
        poly,
        plane,
    }
}

/// The margin of [`Bend::nearer`] (a face strictly nearer than the edge point by
/// more than the uncertainty of snapping; equal depth does not hide): the clip
/// grid's uncertainty of the edge point's nearness plus `reach` times the plane's
/// [`snap_change`](DepthPlane::snap_change).
pub(crate) fn margin(plane: &DepthPlane, px: &EdgePixel, reach: u64) -> u32 {
    let slope = u64::from(plane.snap_change()) * reach;
    px.slack.saturating_add(slope.min(1 << 31) as u32)
}

/// Depth margin of the line test, in [`snap_change`](DepthPlane::snap_change)s of
/// the hiding face: a face that covers the edge point is uncertain only by the
/// snapping of its corners and the edge's.
pub(crate) const REACH_COVERING: u64 = 1;

/// How close, in half sub-pixel units, a face's side must pass to an edge point for
/// snapping to have put it across: two units, as far as snapping moves the side and
/// the point together along an axis. (One unit left the open cylinder's silhouette
/// of the random-view sweep's view 16 at 4.6 % of its line pixels misclassified
/// instead of 1.1 %; two let 9.8 px of suzanne's hidden length go missing from
/// sixteen sides instead of 5.4, out of 50,452.)
const SNAP_REACH: i64 = 2;

/// True when face `f` has a vertex at the position of one of `edge`'s ends: such a
/// face passes through the edge's end, and where it folds over the edge on screen
/// (around a silhouette's end) its depth there differs from the edge's by less than
/// the snapping of both can tell (measured on suzanne from sixteen sides, where
/// asking these faces too misses 10.8 px of visible length instead of 3.0 px).
fn touches(mesh: &Mesh<'_>, edge: &MeshEdge, f: usize) -> bool {
    let key = |v: u32| mesh.position_bits(v);
    let ends = [key(edge.a), key(edge.b)];
    mesh.face(f).iter().any(|&v| ends.contains(&key(v)))
}

/// True when `edge` is an [`outline`] and face `f` borders one of its own faces
/// along a side that passes within [`SNAP_REACH`] of the edge point of `px` on
/// screen: the own face between that side and the edge is seen edge-on, collapsed
/// to less than snapping can tell, and `f` covers the point only because snapping
/// moved its side across the outline (a face beside a silhouette of a smooth open
/// surface: the cup's side). Such a face does not hide the point. At a crease the
/// face beyond may really fold over the edge, and is asked as any other.
fn across_collapsed_own_face(
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    edge: &MeshEdge,
    f: usize,
    poly: &[ScreenVertex],
    px: &EdgePixel,
) -> bool {
    // Most points lie well inside the face that hides them: its polygon on screen
    // answers first, with no look at the mesh.
    let sides = poly.iter().zip(poly.iter().cycle().skip(1));
    if !sides
        .into_iter()
        .any(|(a, b)| near_segment(a, b, px.px, px.py, SNAP_REACH))
    {
        return false;
    }
    let mesh = ctx.mesh;
    let key = |v: u32| mesh.position_bits(v);
    let corners = mesh.face(f);
    let owns = |g: usize, a: u32, b: u32| {
        let face = mesh.face(g);
        face.iter().any(|&v| key(v) == key(a)) && face.iter().any(|&v| key(v) == key(b))
    };
    let own_faces = edge.faces.iter().take(edge.face_count.min(2) as usize);
    let sides = corners.iter().zip(corners.iter().cycle().skip(1));
    for (&a, &b) in sides {
        if !own_faces.clone().any(|&g| owns(g as usize, a, b)) {
            continue;
        }
        let ends = (vertices.get(a as usize), vertices.get(b as usize));
        let (Some(pa), Some(pb)) = (
            ends.0.and_then(ProjectedVertex::projection),
            ends.1.and_then(ProjectedVertex::projection),
        ) else {
            continue;
        };
        if near_segment(&pa, &pb, px.px, px.py, SNAP_REACH) {
            return outline(ctx, edge);
        }
    }
    false
}

/// Whether `edge` is an outline of its surface: a boundary, or a silhouette (one
/// face turned to the eye, the other away). Only there does the surface fold on
/// screen so that a face beyond the edge's own can reach across it.
fn outline(ctx: &FrameCtx<'_, '_>, edge: &MeshEdge) -> bool {
    match edge.face_count {
        1 => true,
        2 => {
            let [f, g] = edge.faces;
            ctx.mesh.faces_viewpoint(f as usize, &ctx.viewpoint)
                != ctx.mesh.faces_viewpoint(g as usize, &ctx.viewpoint)
        }
        _ => false,
    }
}

/// Whether point (`x`, `y`) (half sub-pixel units) lies within `reach` of segment
/// `a`-`b` on screen. Screen coordinates stay below 2^28 half units, so the cross
/// product fits 64 bits; its square is compared with the segment's in `f32` (the
/// same bits on the host and the target; a 128-bit square is a long library call
/// on a Cortex-M4).
fn near_segment(a: &ScreenVertex, b: &ScreenVertex, x: i64, y: i64, reach: i64) -> bool {
    let (ax, ay) = (2 * i64::from(a.x), 2 * i64::from(a.y));
    let (bx, by) = (2 * i64::from(b.x), 2 * i64::from(b.y));
    let inside_box = x >= ax.min(bx) - reach
        && x <= ax.max(bx) + reach
        && y >= ay.min(by) - reach
        && y <= ay.max(by) + reach;
    if !inside_box {
        return false;
    }
    let (dx, dy) = (bx - ax, by - ay);
    let cross = dx
        .saturating_mul(y - ay)
        .saturating_sub(dy.saturating_mul(x - ax));
    let (c, r, fx, fy) = (cross as f32, reach as f32, dx as f32, dy as f32);
    c * c <= r * r * (fx * fx + fy * fy)
}
