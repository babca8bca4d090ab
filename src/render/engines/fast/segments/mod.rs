//! Hidden lines by the segment (quantitative invisibility, Appel 1967): the line
//! modes' visibility decided per drawn edge at object precision, on the vertex
//! cache's snapped points, with no face filled.
//!
//! The unit is a face's fan triangle (a face is drawn as the parity of its fan).
//! For a drawn edge `a-b`, its count at `a` is `QI*(a) + L(a)`: `QI*(v)` counts
//! the drawn triangles not around `v` that cover `v` and are strictly nearer, and
//! `L(v)` those around `v` (not the edge's own faces') that cover the edge next to
//! `v` and are nearer there. Along the edge the count changes only where it
//! passes behind a nearer *contour* (a triangle side whose drawn triangles do not
//! lie one on each side of it on screen), by the triangles there; so each edge
//! is a list of crossings ([`contours`]), and its count at `b` less `L(b)` is
//! `QI*(b)`, which seeds the next edges at `b` ([`chains`]). Each connected set of
//! drawn edges is seeded once by a point test; where two paths reach a vertex
//! with different counts, a point test decides (a re-seed, counted).
//!
//! Every decision is the sign of an integer expression ([`exact`]); a point on a
//! line is moved by the same rule in every test, so a crossing at a vertex is
//! counted once along a chain. Only where a crossing lies along the edge is
//! rounded (it places a pixel).
//!
//! Where an edge passes through a triangle in depth ([`piercings`]), the
//! triangle starts or stops hiding it: the mesh's baked pairs are decided each
//! frame.
//!
//! Not handled (the frame is left to the per-pixel test, and counted): a drawn
//! edge or a contour with an end outside near..far or the guard box.

mod chains;
mod contours;
pub(crate) mod exact;
mod piercings;
mod sides;
mod source;
mod vertex_faces;

use crate::bits::bit;
use crate::mesh::Mesh;
use crate::{Capacity, Error};

use super::edge::CompactEdge;
use super::view::FastVertex;
use exact::Pt;
pub use piercings::{Piercing, PIERCING_MARGIN};
pub use source::SegmentSource;
pub use vertex_faces::VertexFaces;

/// The most faces that do not hide one drawn edge: its own and those beyond an
/// own face collapsed on screen across an outline.
pub const MAX_NOT_HIDING: usize = 8;

/// The most triangles on one side (a non-manifold edge's faces and a folded
/// face's two).
pub const MAX_SIDE_TRIANGLES: usize = 4;

/// The most cells of the contour grid (cells of `2^g` pixels, `g` the least from
/// 4 up that fits).
pub const MAX_GRID_CELLS: usize = 512;

/// Extra fraction bits of a crossing's place along its edge's major axis (in
/// `2^-(S+1)` px): [`Run`] boundaries are in `2^-(S+1+PLACE_BITS)` px.
pub(crate) const PLACE_BITS: u32 = 4;

/// A contour: a triangle side (welded ends, `a < b`), its screen box, and its
/// drawn triangles' faces with the side of `a`-`b` each lies on (`+1` left, `-1`
/// right).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Contour {
    a: u16,
    b: u16,
    /// Least screen `x`, `y` of its ends (`2^-S` px): most crossing candidates
    /// are told apart by the box alone, without the vertex cache.
    lo: [i16; 2],
    /// Greatest screen `x`, `y` of its ends.
    hi: [i16; 2],
    faces: [u16; MAX_SIDE_TRIANGLES],
    sides: [i8; MAX_SIDE_TRIANGLES],
    count: u8,
}

/// A crossing of a drawn edge with a nearer contour: its place along the edge's
/// major axis (`2^-(S+1+PLACE_BITS)` px) and the change of the count past it.
/// After the counts are known, a list of the places where the edge turns
/// between visible and hidden.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Crossing {
    place: i32,
    delta: i16,
}

impl Crossing {
    /// Its place along the major axis, `2^-(S+1+PLACE_BITS)` px.
    #[inline(always)]
    pub(crate) fn place(&self) -> i32 {
        self.place
    }
}

/// The storage hidden lines by the segment borrow for one frame.
#[derive(Debug)]
pub struct Segments<'s> {
    /// The per-frame lists, of fixed capacity.
    pub lists: SegmentLists<'s>,
    /// What grows with the mesh.
    pub work: SegmentWorkspace<'s>,
}

/// A drawn edge's pieces: its boundaries in the crossings list, from the low end
/// of its major axis, and whether it is hidden there (each boundary turns it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Run {
    /// First entry in the crossings list.
    pub(crate) first: u16,
    /// Entries.
    pub(crate) len: u16,
    /// Hidden at the low end.
    pub(crate) hidden: bool,
    /// Drawn this frame (else the rest is meaningless).
    pub(crate) drawn: bool,
    /// The count at end `a` (after the stage: only used while it runs).
    start: i16,
    /// The count's change from `a` to `b`.
    total: i16,
    /// End `a` is at the low end of the major axis.
    a_low: bool,
}

impl Run {
    /// No pieces (not drawn): what a `static` of runs starts as (`.bss`).
    pub const EMPTY: Self = Self {
        first: 0,
        len: 0,
        hidden: false,
        drawn: false,
        start: 0,
        total: 0,
        a_low: false,
    };
}

/// Counts of one frame of hidden lines by the segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SegmentStats {
    /// Drawn edges.
    pub drawn: u32,
    /// Contour edges.
    pub contours: u32,
    /// (drawn edge, contour) pairs tested for a crossing.
    pub pair_tests: u32,
    /// Pairs that cross on screen.
    pub crossings: u32,
    /// Crossings where the contour is nearer (kept).
    pub nearer: u32,
    /// Edges passing through a triangle (kept as crossings).
    pub piercings: u32,
    /// Crossings kept (the frame's need of `CROSSINGS`).
    pub kept: u32,
    /// Entries of the contour grid (the frame's need of `CELL_ENTRIES`).
    pub grid_entries: u32,
    /// Boundaries between visible and hidden pieces.
    pub boundaries: u32,
    /// Chains seeded by a point test.
    pub seeds: u32,
    /// Vertices reached with two different counts, decided again by a point test.
    pub reseeds: u32,
    /// Counts below zero (an inconsistency), taken as visible.
    pub negative: u32,
    /// Triangles asked by point tests.
    pub point_triangles: u32,
    /// Frames left to the per-pixel test (an end outside the guard box or
    /// near..far).
    pub fallback: u32,
}

/// The per-frame lists of hidden lines by the segment, with room for `CONTOURS`
/// contour edges, `CROSSINGS` kept crossings and `CELL_ENTRIES` entries of the
/// contour grid (a contour in each cell its box meets); per vertex and per edge,
/// the lent [`SegmentWorkspace`]. All zero: a `static` of it is `.bss`.
#[derive(Debug)]
pub struct SegmentLines<const CONTOURS: usize, const CROSSINGS: usize, const CELL_ENTRIES: usize> {
    contours: [Contour; CONTOURS],
    stamps: [u16; CONTOURS],
    crossings: [Crossing; CROSSINGS],
    cells: [u16; MAX_GRID_CELLS + 1],
    entries: [u16; CELL_ENTRIES],
}

impl<const CONTOURS: usize, const CROSSINGS: usize, const CELL_ENTRIES: usize>
    SegmentLines<CONTOURS, CROSSINGS, CELL_ENTRIES>
{
    /// Empty lists.
    pub const fn new() -> Self {
        Self {
            contours: [Contour {
                a: 0,
                b: 0,
                lo: [0; 2],
                hi: [0; 2],
                faces: [0; MAX_SIDE_TRIANGLES],
                sides: [0; MAX_SIDE_TRIANGLES],
                count: 0,
            }; CONTOURS],
            stamps: [0; CONTOURS],
            crossings: [Crossing { place: 0, delta: 0 }; CROSSINGS],
            cells: [0; MAX_GRID_CELLS + 1],
            entries: [0; CELL_ENTRIES],
        }
    }

    /// The lists as the frame uses them.
    pub fn lists(&mut self) -> SegmentLists<'_> {
        SegmentLists {
            contours: &mut self.contours,
            stamps: &mut self.stamps,
            crossings: &mut self.crossings,
            cells: &mut self.cells,
            entries: &mut self.entries,
        }
    }
}

impl<const CONTOURS: usize, const CROSSINGS: usize, const CELL_ENTRIES: usize> Default
    for SegmentLines<CONTOURS, CROSSINGS, CELL_ENTRIES>
{
    fn default() -> Self {
        Self::new()
    }
}

/// [`SegmentLines`] lent to one frame.
#[derive(Debug)]
pub struct SegmentLists<'s> {
    contours: &'s mut [Contour],
    stamps: &'s mut [u16],
    crossings: &'s mut [Crossing],
    cells: &'s mut [u16],
    entries: &'s mut [u16],
}

impl<'s> SegmentLists<'s> {
    /// Lists in lent storage: room for `contours.len()` contours (`stamps` as
    /// many), `crossings.len()` crossings, and `entries.len()` grid entries;
    /// `cells` needs [`MAX_GRID_CELLS`] + 1 (else `CapacityExceeded`).
    pub fn new(
        contours: &'s mut [Contour],
        stamps: &'s mut [u16],
        crossings: &'s mut [Crossing],
        cells: &'s mut [u16],
        entries: &'s mut [u16],
    ) -> Result<Self, Error> {
        crate::error::need(Capacity::ContourEdges, contours.len(), stamps.len())?;
        crate::error::need(Capacity::GridEntries, MAX_GRID_CELLS + 1, cells.len())?;
        Ok(Self {
            contours,
            stamps,
            crossings,
            cells,
            entries,
        })
    }

    /// The crossings list (after the stage: the pieces' boundaries).
    pub(crate) fn crossings(&self) -> &[Crossing] {
        self.crossings
    }

    /// Bytes of the lists.
    pub fn bytes(&self) -> usize {
        use core::mem::size_of_val;
        size_of_val(self.contours)
            + size_of_val(self.stamps)
            + size_of_val(self.crossings)
            + size_of_val(self.cells)
            + size_of_val(self.entries)
    }
}

impl SegmentWorkspace<'_> {
    /// Bytes of the lent buffers.
    pub fn bytes(&self) -> usize {
        use core::mem::size_of_val;
        size_of_val(self.runs)
            + size_of_val(self.counts)
            + size_of_val(self.queue)
            + size_of_val(self.starts)
            + size_of_val(self.at)
            + size_of_val(self.marks)
    }
}

/// Storage that grows with the mesh, lent for one frame of hidden lines by the
/// segment. Sizes: `runs` >= edges; `counts`, `queue` >= vertices; `starts` >=
/// vertices + 1; `at` >= 2 x edges; `marks` >= vertices / 32.
#[derive(Debug)]
pub struct SegmentWorkspace<'s> {
    /// Each edge's pieces (read by the line pass).
    pub runs: &'s mut [Run],
    /// Each vertex's count `QI*` (`i16::MIN` until known).
    pub counts: &'s mut [i16],
    /// The chains' queue of vertices.
    pub queue: &'s mut [u16],
    /// Each vertex's first drawn edge in `at`.
    pub starts: &'s mut [u16],
    /// The drawn edges at each vertex.
    pub at: &'s mut [u16],
    /// One bit a vertex: a contour or a folded face touches it.
    pub marks: &'s mut [u32],
}

/// One frame's mesh on screen, as the stage reads it.
#[derive(Clone, Copy)]
pub(crate) struct Scene<'a, 'm> {
    pub mesh: &'a Mesh<'m>,
    pub edges: &'a [CompactEdge],
    pub around: VertexFaces<'a>,
    pub piercings: &'a [Piercing],
    pub cache: &'a [FastVertex],
    pub facing: &'a [u32],
    pub cull: bool,
    pub s: u32,
    pub width: u16,
    pub height: u16,
}

impl Scene<'_, '_> {
    /// Vertex `v` as a point.
    #[inline(always)]
    fn p(&self, v: u16) -> Pt {
        Pt::of(
            self.cache.get(usize::from(v)).copied().unwrap_or_default(),
            v,
        )
    }

    #[inline(always)]
    fn inside(&self, v: u16) -> bool {
        self.cache
            .get(usize::from(v))
            .is_some_and(FastVertex::inside)
    }

    #[inline(always)]
    fn facing(&self, f: u16) -> bool {
        bit(self.facing, usize::from(f))
    }

    /// Is face `f` drawn (not culled)?
    #[inline(always)]
    fn drawn(&self, f: u16) -> bool {
        !self.cull || self.facing(f)
    }

    /// Face `f`'s corners.
    #[inline(always)]
    fn corners(&self, f: u16) -> &[u32] {
        self.mesh.face(usize::from(f))
    }

    /// Fan triangle `i` of a face with `corners`, in welded ids.
    #[inline(always)]
    fn fan(&self, corners: &[u32], i: usize) -> [u16; 3] {
        let c = |k: usize| self.around.welded(corners.get(k).copied().unwrap_or(0));
        [c(0), c(i), c(i + 1)]
    }

    /// The sense a face with `corners` winds in on screen: the sign of its fan's
    /// area (`+1` for none). A fan triangle counts as covering with its own
    /// area's sign times this: for a simple polygon, once inside and not at all
    /// outside, however its fan overlaps.
    fn winding(&self, corners: &[u32]) -> i8 {
        let at = |k: usize| {
            let v = corners.get(k).copied().unwrap_or(0);
            self.cache.get(v as usize).copied().unwrap_or_default()
        };
        let p0 = at(0);
        let mut total = 0i64;
        for i in 1..corners.len().saturating_sub(1) {
            total += super::polygon::turn(p0, at(i), at(i + 1));
        }
        if total < 0 {
            -1
        } else {
            1
        }
    }

    /// How a fan triangle of a face with `corners`, of twice-area `area` (not
    /// 0), counts where it covers: `+1`, or `-1` where it winds against its face.
    #[inline(always)]
    fn counts_as(&self, corners: &[u32], area: i64) -> i16 {
        if corners.len() == 3 {
            1
        } else {
            i16::from(self.winding(corners)) * area.signum() as i16
        }
    }

    /// Corner `k` of a face with `corners`, welded.
    #[inline(always)]
    fn corner(&self, corners: &[u32], k: usize) -> u16 {
        self.around.welded(corners.get(k).copied().unwrap_or(0))
    }

    /// May edge `e` be an outline, whose faces that do not hide it reach beyond
    /// its own ([`sides::not_hiding`])? A boundary or non-manifold edge, or
    /// one between a face that faces the eye and one that does not (by the
    /// faces' planes: snapping may still lay both on one side of it on screen,
    /// so it need not be a contour).
    #[inline(always)]
    fn may_be_outline(&self, e: &CompactEdge) -> bool {
        use crate::mesh::EdgeKind;
        match e.kind {
            EdgeKind::Boundary | EdgeKind::NonManifold => true,
            _ => e.faces[0] == e.faces[1] || self.facing(e.faces[0]) != self.facing(e.faces[1]),
        }
    }

    /// Is edge `e` drawn in this view (a feature edge)?
    fn is_drawn(&self, e: &CompactEdge) -> bool {
        use crate::mesh::EdgeKind;
        match e.kind {
            EdgeKind::Boundary | EdgeKind::NonManifold | EdgeKind::Crease => true,
            EdgeKind::Smooth => self.facing(e.faces[0]) != self.facing(e.faces[1]),
            EdgeKind::Inert => false,
        }
    }
}

/// Fan triangle `i` (1 ..= n - 2) of a face with `corners`.
#[inline(always)]
pub(crate) fn fan(corners: &[u32], i: usize) -> [u16; 3] {
    let c = |k: usize| corners.get(k).copied().unwrap_or(0) as u16;
    [c(0), c(i), c(i + 1)]
}

/// Where the point `num / (num - other)` of the way from `ua` to `ub` (major-axis
/// coordinates, `2^-S` px) lies, in `2^-(S+1+PLACE_BITS)` px: the two are
/// shifted to 24 bits and divided in `f32`, since the place only puts a pixel.
#[inline(always)]
pub(crate) fn place_between(ua: i32, ub: i32, num: i64, other: i64) -> i32 {
    let span = (num - other).unsigned_abs();
    let shift = (64 - span.leading_zeros()).saturating_sub(24);
    let (n, d) = (num >> shift, (num >> shift) - (other >> shift));
    let t = if d == 0 {
        0.0
    } else {
        // Both below 2^25 in magnitude: through `i32`, no 64-bit conversion call.
        (n as i32 as f32 / d as i32 as f32).clamp(0.0, 1.0)
    };
    let scale = 1 << (1 + PLACE_BITS);
    ua * scale + super::float_int::to_i32(((ub - ua) * scale) as f32 * t)
}

/// Triangle `t` turned to start at its corner `j` (0, 1 or 2).
#[inline(always)]
pub(crate) fn turn(t: [u16; 3], j: usize) -> [u16; 3] {
    let [a, b, c] = t;
    match j {
        0 => [a, b, c],
        1 => [b, c, a],
        _ => [c, a, b],
    }
}

/// The fan triangles (their `i`) of a face with `corners` that have corner `k`.
#[inline(always)]
pub(crate) fn fans_at(n: usize, k: usize) -> core::ops::Range<usize> {
    if k == 0 {
        1..n.saturating_sub(1)
    } else {
        k.saturating_sub(1).max(1)..k.min(n.saturating_sub(2)) + 1
    }
}

/// Classifies the drawn edges of `scene` into `ws.runs` (their pieces in
/// `lists.crossings`). `Ok(false)`: the frame is not handled (an end outside),
/// and the caller draws it with the per-pixel test.
pub(crate) fn classify(
    scene: &Scene<'_, '_>,
    lists: &mut SegmentLists<'_>,
    ws: &mut SegmentWorkspace<'_>,
    stats: &mut SegmentStats,
) -> Result<bool, Error> {
    let vertices = scene.mesh.vertices().len();
    let edges = scene.edges.len();
    crate::error::need(Capacity::Edges, edges, ws.runs.len())?;
    crate::error::need(Capacity::Vertices, vertices, ws.counts.len())?;
    crate::error::need(Capacity::Vertices, vertices, ws.queue.len())?;
    crate::error::need(Capacity::Vertices, vertices + 1, ws.starts.len())?;
    crate::error::need(Capacity::Edges, 2 * edges, ws.at.len())?;
    crate::error::need(Capacity::Vertices, vertices.div_ceil(32), ws.marks.len())?;
    // Drawn edges.
    let mut drawn = 0u32;
    for (e, run) in scene.edges.iter().zip(ws.runs.iter_mut()) {
        *run = Run::default();
        if scene.is_drawn(e) {
            if !scene.inside(e.a) || !scene.inside(e.b) {
                stats.fallback += 1;
                return Ok(false);
            }
            run.drawn = true;
            run.start = i16::MIN;
            drawn += 1;
        }
    }
    stats.drawn += drawn;
    let Some(contour_count) = contours::find(scene, lists.contours, ws.marks)? else {
        stats.fallback += 1;
        return Ok(false);
    };
    stats.contours += contour_count as u32;
    let grid = contours::Grid::build(scene, lists, contour_count, stats)?;
    contours::cross_all(scene, lists, &grid, contour_count, ws.runs, stats)?;
    chains::propagate(scene, ws, stats)?;
    chains::pieces(lists.crossings, ws.runs, stats);
    Ok(true)
}
