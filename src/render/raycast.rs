//! Ray casting: one ray per pixel centre, through a bounding-volume hierarchy over
//! the drawn faces' screen boxes, built once per frame in lent storage.
//!
//! After projection the ray through a pixel centre is the line of constant screen
//! (x, y), along which nearness `q` is affine: the ray meets a face where the face
//! covers the centre ([`covers_centre`], the scan converter's decision) and at the
//! face's plane nearness there, the very value the Z-buffer stores. The cast is
//! exact in fixed point, and it decides each pixel exactly as the Z-buffer does
//! (32-bit depth): of the covering faces taken in index order, a later face wins
//! only when nearer by more than its tie.
//!
//! Pruning without losing that rule: the faces that can matter at a pixel are the
//! set H of the nearest covering faces closed under "within a tie": walking the
//! covering faces nearest first, a face joins H while its nearness reaches
//! `floor(H) = min over H of (q - tie)`. Every face of H beats every face below the
//! floor and none of those can beat a face of H, so the index-order rule over H alone
//! gives the Z-buffer's answer. The trace visits nodes nearest first and prunes a
//! node whose largest nearness is below the current floor; since the floor of a
//! partial H can end higher than the final one, the largest bound set aside is
//! remembered, and when it reaches the final floor the pixel is decided again by an
//! exhaustive pass in index order (counted in [`RaycastFigures::fallbacks`]).
//!
//! Coherence: rays are cast in 8x8 tiles. One walk of the tree lists the faces
//! whose boxes meet the tile, sorted by their largest nearness; each pixel walks
//! that list until a face's bound falls below the floor (then the floor is final).
//! A tile meeting more faces than the list holds is traced pixel by pixel through
//! the tree, nearest child first, the previous pixel's face tried first.

use core::marker::PhantomData;

use embedded_graphics_core::pixelcolor::PixelColor;
use fixed::types::extra::LeEqU32;
use heapless::Vec;

use super::compose::{FrameProbe, Palette};
use super::coverage::covers_centre;
use super::idpass::{render_ids, FrameInput, IdPass, IdWorkspace};
use super::transform::{ProjectedVertex, ScreenVertex};
use super::zband::{DepthPlane, IdBand, RowPlane};
use super::{bit, face_polygon, need, FrameCtx, Settings, Stats};
use crate::camera::Camera;
use crate::geometry::Subpixel;
use crate::mesh::{EdgeAdjacency, Mesh};
use crate::{Error, SpanSink};

/// Most faces in a leaf of the hierarchy.
const LEAF: usize = 4;

/// Depth of the trace stack. A median split halves the faces at each level, so a
/// tree over at most 65 535 faces is at most 16 levels deep below the root and the
/// depth-first stack holds at most one entry per level plus one.
const STACK: usize = 40;

/// Pixels on a side of the tiles traced together: one walk of the tree lists the
/// faces that meet the tile, and each pixel of the tile walks that list.
const TILE: u16 = 8;

/// Most faces a tile's list holds; a tile meeting more is traced pixel by pixel.
const TILE_FACES: usize = 48;

/// Covering faces a trace keeps (the nearest ones, within ties of each other). More
/// than this at one pixel sends the pixel to the exhaustive pass.
const CANDIDATES: usize = 8;

/// One node of the bounding-volume hierarchy: the pixel centres its faces' boxes
/// reach (inclusive, clamped to the frame) and their largest nearness.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BvhNode {
    x0: u16,
    y0: u16,
    x1: u16,
    y1: u16,
    /// The largest nearness of any face below.
    q_max: u32,
    /// Inner node: the first of its two children (the second follows it). Leaf: the
    /// first of its faces in [`RaycastStorage::faces`].
    index: u32,
    /// 0 for an inner node, else the leaf's face count.
    count: u32,
}

impl BvhNode {
    fn contains(&self, x: u16, y: u16) -> bool {
        self.x0 <= x && x <= self.x1 && self.y0 <= y && y <= self.y1
    }
}

/// One drawn face as the rays see it: the pixel centres its box reaches, its depth
/// plane, and whether its polygon is clipped (then the polygon is clipped again at
/// each test; an unclipped face's polygon is read from the vertex cache through the
/// mesh's indices, which costs a copy of a few vertices).
///
/// Measured (400x240, fitted camera): suzanne makes 51 thousand coverage tests a
/// frame and teapot 94 thousand, with no clipped face in either
/// ([`RaycastFigures::clipped_faces`]); a cache of clipped polygons would cost
/// `POLY` screen vertices per face for the rare near-plane cut, so they are
/// recomputed, and unclipped ones are only the mesh's indices into the vertex cache.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RayFace {
    plane: RowPlane,
    x0: u16,
    y0: u16,
    x1: u16,
    y1: u16,
    face: u16,
    clipped: bool,
}

impl RayFace {
    fn contains(&self, x: u16, y: u16) -> bool {
        self.x0 <= x && x <= self.x1 && self.y0 <= y && y <= self.y1
    }
}

/// Lengths of the slices of a [`RaycastStorage`] for a mesh of some face count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RaycastSizes {
    /// Nodes of the hierarchy: at most 2 faces - 1.
    pub nodes: usize,
    /// Face records: one per face (the drawn ones are kept, in the tree's order).
    pub faces: usize,
}

/// Storage the caller lends a [`RaycastRenderer`] for one frame: the hierarchy and
/// its face records (which are also the tree's face order; there is no separate
/// index array). See [`RaycastStorage::sizes`].
#[derive(Debug)]
pub struct RaycastStorage<'s> {
    /// The hierarchy's nodes, the root first.
    pub nodes: &'s mut [BvhNode],
    /// The drawn faces, in the order the leaves reference.
    pub faces: &'s mut [RayFace],
}

impl RaycastStorage<'_> {
    /// What a mesh of `faces` faces needs.
    pub const fn sizes(faces: usize) -> RaycastSizes {
        let nodes = 2 * faces;
        RaycastSizes {
            nodes: if nodes > 1 { nodes - 1 } else { 1 },
            faces,
        }
    }

    /// Bytes of the lent slices.
    pub fn bytes(&self) -> usize {
        size_of_val(self.nodes) + size_of_val(self.faces)
    }
}

/// Figures of the last frame a [`RaycastRenderer`] drew.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RaycastFigures {
    /// Faces in the hierarchy (drawn, in view, able to cover a pixel centre).
    pub faces: u32,
    /// Nodes of the hierarchy.
    pub nodes: u32,
    /// Pixels the pruned trace could not decide alone (the exhaustive pass did).
    pub fallbacks: u32,
    /// Coverage tests made (faces whose box held the pixel centre).
    pub face_tests: u64,
    /// Faces of the hierarchy whose polygon is clipped (cut again at each test).
    pub clipped_faces: u32,
    /// Pixels traced through the tree one by one (their tile met too many faces
    /// to list); the others walked their tile's face list.
    pub tree_pixels: u64,
}

/// The ray-casting engine: S = `Frac` sub-pixel bits, `POLY` vertices per clipped
/// polygon. Each frame builds a bounding-volume hierarchy over the drawn faces in a
/// lent [`RaycastStorage`], then casts one ray per pixel centre of each band.
#[derive(Debug)]
pub struct RaycastRenderer<Frac, const POLY: usize> {
    figures: RaycastFigures,
    _frac: PhantomData<Frac>,
}

impl<Frac: LeEqU32, const POLY: usize> Default for RaycastRenderer<Frac, POLY> {
    fn default() -> Self {
        Self::new()
    }
}

impl<Frac: LeEqU32, const POLY: usize> RaycastRenderer<Frac, POLY> {
    /// A renderer that has drawn nothing yet.
    pub const fn new() -> Self {
        Self {
            figures: RaycastFigures {
                faces: 0,
                nodes: 0,
                fallbacks: 0,
                face_tests: 0,
                tree_pixels: 0,
                clipped_faces: 0,
            },
            _frac: PhantomData,
        }
    }

    /// Figures of the last frame.
    pub fn figures(&self) -> RaycastFigures {
        self.figures
    }

    /// Renders `mesh` seen by `camera` into `sink`. `storage` must hold
    /// [`RaycastStorage::sizes`] of the mesh's face count, else
    /// [`Error::CapacityExceeded`] with the length needed.
    #[allow(clippy::too_many_arguments)]
    pub fn render<K: SpanSink, P: Palette<Color = K::Color>, R: FrameProbe>(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &EdgeAdjacency<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut IdWorkspace<'_>,
        storage: &mut RaycastStorage<'_>,
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>>
    where
        K::Color: PixelColor,
    {
        let sizes = RaycastStorage::sizes(mesh.face_count());
        need(sizes.faces, storage.faces.len()).map_err(Error::widen)?;
        need(sizes.nodes, storage.nodes.len()).map_err(Error::widen)?;
        let input = FrameInput {
            mesh,
            positions: mesh.vertices(),
            edges,
            camera,
            settings,
            s: Subpixel::<Frac>::BITS,
        };
        let mut pass = Cast::<POLY> {
            nodes: storage.nodes,
            faces: storage.faces,
            node_count: 0,
            face_count: 0,
            figures: RaycastFigures::default(),
        };
        let stats = render_ids::<POLY, _, _, _, _>(&mut pass, &input, ws, palette, sink, probe);
        self.figures = pass.figures;
        stats
    }
}

/// A covering face met by a ray.
#[derive(Debug, Clone, Copy)]
struct Hit {
    face: u16,
    entry: u32,
    q: u32,
    tie: u32,
}

/// The nearest covering faces of one ray, nearest first, kept closed under ties.
struct Candidates {
    hits: Vec<Hit, CANDIDATES>,
    /// Faces below `floor` cannot change the pixel (if the floor is final).
    floor: i64,
    /// The largest nearness bound of anything set aside (pruned or dropped); -1 none.
    lost: i64,
}

impl Candidates {
    fn new() -> Self {
        Self {
            hits: Vec::new(),
            floor: i64::MIN,
            lost: -1,
        }
    }

    /// Sets aside something whose nearness is at most `bound`.
    fn lose(&mut self, bound: u32) {
        self.lost = self.lost.max(i64::from(bound));
    }

    fn insert(&mut self, hit: Hit) {
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
    fn winner(&self) -> Option<Hit> {
        let mut by_face = self.hits.clone();
        by_face.sort_unstable_by_key(|h| h.face);
        fold(by_face.iter().copied())
    }
}

/// The Z-buffer's decision over covering faces given in index order.
fn fold(hits: impl Iterator<Item = Hit>) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for h in hits {
        if best.is_none_or(|b| h.q > b.q.saturating_add(h.tie)) {
            best = Some(h);
        }
    }
    best
}

/// One frame's casting.
struct Cast<'a, const POLY: usize> {
    nodes: &'a mut [BvhNode],
    faces: &'a mut [RayFace],
    node_count: usize,
    face_count: usize,
    figures: RaycastFigures,
}

/// The pixel centres inside the bounding box of `poly`, clamped to a `w` x `h`
/// frame: (x0, y0, x1, y1) inclusive, `None` when it holds none. Centre i is at
/// `(2i + 1) 2^s` half sub-pixel units; a polygon never covers a centre outside its
/// closed box.
fn centre_box(poly: &[ScreenVertex], s: u32, w: u16, h: u16) -> Option<[u16; 4]> {
    let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
    for v in poly {
        x0 = x0.min(i64::from(v.x));
        y0 = y0.min(i64::from(v.y));
        x1 = x1.max(i64::from(v.x));
        y1 = y1.max(i64::from(v.y));
    }
    let half = 1i64 << s;
    // First centre at or right of m, last centre at or left of m.
    let lo = |m: i64| ((2 * m + half - 1) >> (s + 1)).max(0);
    let hi = |m: i64, n: u16| ((2 * m - half) >> (s + 1)).min(i64::from(n) - 1);
    let (c0, c1, r0, r1) = (lo(x0), hi(x1, w), lo(y0), hi(y1, h));
    (c0 <= c1 && r0 <= r1).then_some([c0 as u16, r0 as u16, c1 as u16, r1 as u16])
}

impl<const POLY: usize> Cast<'_, POLY> {
    /// Builds the hierarchy over the first `n` face records: breadth first, each
    /// node's faces split at the median of their box centres along the wider axis,
    /// the children appended to the node array (which is the work queue: no stack,
    /// no recursion).
    fn build(&mut self, n: usize) -> Result<(), Error> {
        self.node_count = 0;
        if n == 0 {
            return Ok(());
        }
        need(2 * n - 1, self.nodes.len())?;
        let root = BvhNode {
            count: n as u32,
            ..BvhNode::default()
        };
        if let Some(slot) = self.nodes.get_mut(0) {
            *slot = root;
        }
        let mut next = 1;
        let mut i = 0;
        while i < next {
            let Some(&node) = self.nodes.get(i) else {
                break;
            };
            let (first, count) = (node.index as usize, node.count as usize);
            let Some(faces) = self.faces.get_mut(first..first + count) else {
                break;
            };
            let mut b = BvhNode {
                x0: u16::MAX,
                y0: u16::MAX,
                ..node
            };
            let (mut cx0, mut cy0, mut cx1, mut cy1) = (u32::MAX, u32::MAX, 0, 0);
            for f in faces.iter() {
                b.x0 = b.x0.min(f.x0);
                b.y0 = b.y0.min(f.y0);
                b.x1 = b.x1.max(f.x1);
                b.y1 = b.y1.max(f.y1);
                b.q_max = b.q_max.max(f.plane.max_q());
                let (cx, cy) = (
                    u32::from(f.x0) + u32::from(f.x1),
                    u32::from(f.y0) + u32::from(f.y1),
                );
                cx0 = cx0.min(cx);
                cx1 = cx1.max(cx);
                cy0 = cy0.min(cy);
                cy1 = cy1.max(cy);
            }
            if count > LEAF && next + 2 <= self.nodes.len() {
                let mid = count / 2;
                if cx1 - cx0 >= cy1 - cy0 {
                    faces.select_nth_unstable_by_key(mid, |f| u32::from(f.x0) + u32::from(f.x1));
                } else {
                    faces.select_nth_unstable_by_key(mid, |f| u32::from(f.y0) + u32::from(f.y1));
                }
                let left = BvhNode {
                    index: node.index,
                    count: mid as u32,
                    ..BvhNode::default()
                };
                let right = BvhNode {
                    index: node.index + mid as u32,
                    count: (count - mid) as u32,
                    ..BvhNode::default()
                };
                if let Some([l, r]) = self.nodes.get_mut(next..next + 2) {
                    (*l, *r) = (left, right);
                }
                b.index = next as u32;
                b.count = 0;
                next += 2;
            }
            if let Some(slot) = self.nodes.get_mut(i) {
                *slot = b;
            }
            i += 1;
        }
        self.node_count = next;
        Ok(())
    }

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
                    let _ = poly.push(p.screen);
                }
            }
        }
        if !covers_centre(poly, ctx.s, i64::from(x), i64::from(y)) {
            return Ok(None);
        }
        Ok(Some(Hit {
            face: rf.face,
            entry: k as u32,
            q: rf.plane.at_xy(x, y),
            tie: rf.plane.tie,
        }))
    }

    /// The visible face at pixel (x, y): its record, or `None`. `hint` (the
    /// previous pixel's face record) is tried first: its nearness prunes the most.
    fn trace(
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
    fn tile_faces(&self, tile: [u16; 4], out: &mut Vec<u32, TILE_FACES>) -> bool {
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
    fn trace_list(
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

impl<const POLY: usize> IdPass for Cast<'_, POLY> {
    fn begin(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
    ) -> Result<(), Error> {
        let (w, h) = (ctx.viewport.width, ctx.viewport.height);
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        let mut n = 0;
        for f in 0..ctx.mesh.face_count() {
            if !bit(drawn, f) || !face_polygon(ctx, vertices, f, &mut poly)? {
                continue;
            }
            let Some(plane) = DepthPlane::new(&poly, ctx.s) else {
                continue;
            };
            let Some([x0, y0, x1, y1]) = centre_box(&poly, ctx.s, w, h) else {
                continue;
            };
            let clipped = ctx
                .mesh
                .face(f)
                .iter()
                .any(|&v| vertices.get(v as usize).is_none_or(|p| p.outside != 0));
            let capacity = self.faces.len();
            let slot = self.faces.get_mut(n).ok_or(Error::CapacityExceeded {
                needed: n + 1,
                capacity,
            })?;
            *slot = RayFace {
                plane: plane.row_plane(0),
                x0,
                y0,
                x1,
                y1,
                face: f as u16,
                clipped,
            };
            n += 1;
            self.figures.clipped_faces += u32::from(clipped);
        }
        self.face_count = n;
        self.build(n)?;
        self.figures.faces = n as u32;
        self.figures.nodes = self.node_count as u32;
        Ok(())
    }

    fn fill(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        _drawn: &[u32],
        band: &mut IdBand<'_>,
    ) -> Result<u32, Error> {
        let Some(&root) = self.nodes.first().filter(|_| self.node_count > 0) else {
            return Ok(0);
        };
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        let mut list: Vec<u32, TILE_FACES> = Vec::new();
        let rows = band.first.max(root.y0)..(band.first + band.held).min(root.y1 + 1);
        let mut ty = rows.start;
        while ty < rows.end {
            let ty1 = (ty + TILE).min(rows.end) - 1;
            let mut tx = root.x0;
            while tx <= root.x1 {
                let tx1 = (tx + TILE - 1).min(root.x1);
                let listed = self.tile_faces([tx, ty, tx1, ty1], &mut list);
                for y in ty..=ty1 {
                    let mut hint = None;
                    for x in tx..=tx1 {
                        let hit = if listed {
                            self.trace_list(ctx, vertices, x, y, &list, &mut poly)?
                        } else {
                            self.figures.tree_pixels += 1;
                            self.trace(ctx, vertices, x, y, hint, &mut poly)?
                        };
                        hint = hit.map(|h| h.entry);
                        if let Some(slot) = band.row_mut(y).and_then(|r| r.get_mut(usize::from(x)))
                        {
                            *slot = hit.map_or(0, |h| h.face + 1);
                        }
                    }
                }
                tx = tx1 + 1;
            }
            ty = ty1 + 1;
        }
        // Runs of one face along the rows, for the statistics.
        let mut runs = 0;
        for y in rows {
            let mut last = 0;
            for &id in band.row(y) {
                runs += u32::from(id != 0 && id != last);
                last = id;
            }
        }
        Ok(runs)
    }
}

#[cfg(test)]
mod tests;
