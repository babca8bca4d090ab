//! Active facets: the faces (a bent convex quad split at its diagonal, or the fan
//! triangles of another bent face) that cross the current row, each with its depth
//! plane(s), and the row they fill.
//!
//! A facet whose corners fall monotonically in y from one top corner to one bottom
//! corner (every triangle, every convex polygon) keeps two edge steppers, one per
//! chain: each row is one span between their crossings (for a split quad, two, at
//! the diagonal's crossing). Any other polygon is filled by the even-odd rule from
//! all its edges' crossings, made afresh each row (rare: concave faces). The row is
//! `u32`s, `depth << 16 | (0xFFFF - face)`, and the facets come in face order, so
//! one unsigned compare a pixel takes the nearer face, and within the tie the lower
//! index.

use heapless::Vec;

use super::clip::CLIP_CORNERS;
use super::depth_row::run;
use super::planes::{det, plane, plane_through, steepest, tie};
use super::step::{crossing, row_at, EdgeStep};
use super::view::FastVertex;
use crate::Capacity;
use crate::Error;

mod kernel;

pub use kernel::twin_mismatches;

/// Most corners of a face the fast engine draws without clipping; more is
/// `CapacityExceeded` (for the even-odd path's crossings).
pub const MAX_CORNERS: usize = 64;

/// Where a facet's corners are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Corners {
    /// Corners of the mesh face, through the vertex cache.
    Face,
    /// Fan triangle `(c0, ck, ck+1)` of the face.
    Fan(u8),
    /// Clipped corners from `start` in the clip pool (the facet knows how many).
    Pool { start: u16 },
}

/// How a facet's row span is filled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Layout {
    /// All of it with the first plane.
    First,
    /// All of it with the second plane (a split quad's triangle `c0 c2 c3`).
    Second,
    /// Split at the diagonal, the first plane's triangle on the left.
    FirstLeft,
    /// Split at the diagonal, the first plane's triangle on the right.
    FirstRight,
}

/// One facet crossing the current row, 104 bytes: a face, or one fan triangle of
/// a bent face, or a bent convex quad split at its diagonal `c0 c2` into two
/// triangles with a plane each (so that a bent quad is one facet, not two).
///
/// `repr(C)`: the span kernels of `kernel` (assembly on the Cortex-M4) read and
/// step the first fields at their `offset_of!` offsets, each stepped pair
/// (`x, dx`; `drow, b`) with one double-word load.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C)]
pub(super) struct Facet {
    /// Monotone: the two chains' current edges (`left` walks corners forward,
    /// `right` backward; either may be the left one on screen). Both are spent
    /// at the facet's first row until it is reached, and hold x = 0 (no span).
    pub left: EdgeStep,
    pub right: EdgeStep,
    /// A split quad's diagonal `c0 c2`, while `layout` splits.
    diag: EdgeStep,
    /// Depth at column 0 of the current row and per row down, then per pixel
    /// right (16.16, wrapping): the first plane, then the second.
    drow: u32,
    b: i32,
    drow2: u32,
    b2: i32,
    a: i32,
    a2: i32,
    /// Depths this close to the nearest so far are a tie (16.16).
    tie: u32,
    /// Rows before this keep the layout and the chains: the fast path.
    until: i32,
    /// Its last row.
    pub last: i32,
    /// The steepest depth change per pixel, whole depth units (for the line test).
    slope: u16,
    face: u16,
    corners: Corners,
    /// The chains' lower corners' local indices, the bottom corner, the corners.
    at: [u8; 2],
    top: u8,
    bottom: u8,
    n: u8,
    monotone: bool,
    split: bool,
    layout: Layout,
    /// Corner positions (`2^-S` px) of a facet of up to four corners, so that
    /// moving a chain on reads no mesh data.
    pts: [(i16, i16); 4],
}

/// Reads corner `i` of a facet.
pub(super) trait CornerSource {
    fn corner(&self, facet_corners: Corners, face: u16, i: usize) -> FastVertex;
}

/// Writes into `out` the facet with corners `pts` (of face `face`, found again
/// through `corners`) at `row`; false when it has no row at or after `row`.
///
/// `split`: `pts` is a convex quad, drawn as its triangles `c0 c1 c2` and
/// `c0 c2 c3`, each with its own plane.
pub(super) fn facet(
    out: &mut Facet,
    pts: &[FastVertex],
    face: u16,
    corners: Corners,
    row: i32,
    s: u32,
    split: bool,
) -> bool {
    let n = pts.len();
    // Triangles and quads, nearly every facet, without the general loops.
    let (top, bottom, ymin, ymax, monotone) = match *pts {
        [p0, p1, p2] => small_shape([p0, p1, p2, p2], false),
        [p0, p1, p2, p3] => small_shape([p0, p1, p2, p3], true),
        _ => polygon_shape(pts),
    };
    let end = row_at(2 * ymax, s);
    if row >= end || ymin == ymax {
        return false;
    }
    let split = split && n == 4;
    let ((a, b, drow), (a2, b2, drow2)) = match *pts {
        [p0, p1, p2, p3] if split => (
            plane_through(p0, p1, p2, det(p0, p1, p2), row, s),
            plane_through(p0, p2, p3, det(p0, p2, p3), row, s),
        ),
        [p0, p1, p2] => {
            let one = plane_through(p0, p1, p2, det(p0, p1, p2), row, s);
            (one, one)
        }
        [p0, p1, p2, p3] => {
            // The fan triangle of larger area, the first on a tie (as `plane`).
            let (d1, d2) = (det(p0, p1, p2), det(p0, p2, p3));
            let one = if d2.abs() > d1.abs() {
                plane_through(p0, p2, p3, d2, row, s)
            } else {
                plane_through(p0, p1, p2, d1, row, s)
            };
            (one, one)
        }
        _ => {
            let one = plane(pts, row, s);
            (one, one)
        }
    };
    let first = row_at(2 * ymin, s);
    // One plane twice unless split: its tie and slope once.
    let (tie, slope) = if split {
        (tie(a, b).max(tie(a2, b2)), steepest([a, b, a2, b2]))
    } else {
        (tie(a, b), steepest([a, b, 0, 0]))
    };
    *out = Facet {
        // Chains are set up on the first row.
        left: EdgeStep::spent(first),
        right: EdgeStep::spent(first),
        diag: EdgeStep::spent(first),
        until: first,
        a,
        b,
        drow,
        a2,
        b2,
        drow2,
        tie,
        slope,
        last: end - 1,
        face,
        corners,
        at: [top as u8; 2],
        top: top as u8,
        bottom: bottom as u8,
        n: n as u8,
        monotone,
        split,
        layout: Layout::First,
        pts: {
            let mut q = [(0i16, 0i16); 4];
            for (q, p) in q.iter_mut().zip(pts) {
                *q = (p.x, p.y);
            }
            q
        },
    };
    // A facet of up to four corners at its first row sets its chains up now,
    // from its own corners (a clipped one may start above its first row: its
    // chains wait, spent, for it).
    if monotone && n <= out.pts.len() && row >= first {
        out.next_edge(&OwnCorners, 0, row, s);
        out.next_edge(&OwnCorners, 1, row, s);
        out.lay_out(row, s);
    }
    true
}

/// Top and bottom corners (the first of equal ones), their y, and whether it is
/// monotone in y, of a triangle (`pts[3]` unused) or a quad.
#[inline(always)]
fn small_shape(pts: [FastVertex; 4], quad: bool) -> (usize, usize, i32, i32, bool) {
    let [y0, y1, y2, y3] = pts.map(|p| i32::from(p.y));
    let (mut top, mut bottom, mut ymin, mut ymax) = (0, 0, y0, y0);
    for (i, y) in [(1, y1), (2, y2), (3, y3)] {
        if i == 3 && !quad {
            break;
        }
        if y < ymin {
            (ymin, top) = (y, i);
        }
        if y > ymax {
            (ymax, bottom) = (y, i);
        }
    }
    // A quad has two local minima exactly when its opposite corners are both
    // above (or both below) the other two.
    let monotone = !quad || !(y0.max(y2) < y1.min(y3) || y1.max(y3) < y0.min(y2));
    (top, bottom, ymin, ymax, monotone)
}

/// [`small_shape`] of any polygon.
fn polygon_shape(pts: &[FastVertex]) -> (usize, usize, i32, i32, bool) {
    let (mut top, mut bottom, mut ymin, mut ymax) = (0usize, 0usize, i32::MAX, i32::MIN);
    for (i, p) in pts.iter().enumerate() {
        let y = i32::from(p.y);
        if y < ymin {
            (ymin, top) = (y, i);
        }
        if y > ymax {
            (ymax, bottom) = (y, i);
        }
    }
    // Every triangle is monotone in y.
    let monotone = pts.len() == 3 || local_minima(pts) <= 1;
    (top, bottom, ymin, ymax, monotone)
}

/// Local minima of y around the cycle of `pts` (flat runs skipped): 1 when the
/// polygon is monotone in y.
fn local_minima(pts: &[FastVertex]) -> u32 {
    let (mut minima, mut last_dir, mut first_dir) = (0u32, 0i32, 0i32);
    let Some(last) = pts.last() else {
        return 0;
    };
    let mut prev = i32::from(last.y);
    for p in pts {
        let y = i32::from(p.y);
        let dir = (y - prev).signum();
        if dir != 0 {
            if last_dir < 0 && dir > 0 {
                minima += 1;
            }
            if first_dir == 0 {
                first_dir = dir;
            }
            last_dir = dir;
        }
        prev = y;
    }
    if last_dir < 0 && first_dir > 0 {
        minima += 1;
    }
    minima
}

/// The corner source of a facet that keeps its own corners (up to four): never
/// asked.
struct OwnCorners;

impl CornerSource for OwnCorners {
    fn corner(&self, _: Corners, _: u16, _: usize) -> FastVertex {
        FastVertex::ZERO
    }
}

impl Facet {
    /// A placeholder for a free slot.
    pub const EMPTY: Self = Self {
        left: EdgeStep::spent(0),
        right: EdgeStep::spent(0),
        diag: EdgeStep::spent(0),
        until: 0,
        a: 0,
        b: 0,
        drow: 0,
        a2: 0,
        b2: 0,
        drow2: 0,
        tie: 0,
        slope: 0,
        last: -1,
        face: 0,
        corners: Corners::Face,
        at: [0; 2],
        top: 0,
        bottom: 0,
        n: 0,
        monotone: true,
        split: false,
        layout: Layout::First,
        pts: [(0, 0); 4],
    };

    /// The steepest depth change per pixel, in whole depth units (saturating).
    pub fn slope(&self) -> u16 {
        self.slope
    }

    /// The face it belongs to.
    pub fn face(&self) -> u16 {
        self.face
    }

    /// Its depth change a pixel right and a row down (16.16) when it has one plane.
    pub fn gradient(&self) -> Option<(i32, i32)> {
        (!self.split).then_some((self.a, self.b))
    }

    /// True when both chains and the layout hold row `y`: the fast path.
    #[inline(always)]
    pub fn holds(&self, y: i32) -> bool {
        y < self.until
    }

    /// The layout of row `y` (the chains set up for it), and the row it holds
    /// until.
    fn lay_out(&mut self, y: i32, s: u32) {
        let mut until = self.left.end.min(self.right.end);
        if self.split {
            let [p0, p1, p2, _] = self.pts.map(|(x, y)| (2 * i32::from(x), 2 * i32::from(y)));
            let (first, end) = (row_at(p0.1.min(p2.1), s), row_at(p0.1.max(p2.1), s));
            // Beyond the diagonal's rows, the triangle with the corner there.
            let apex = |corner: u8| {
                if corner == 1 {
                    Layout::First
                } else {
                    Layout::Second
                }
            };
            if y < first {
                self.layout = apex(self.top);
                until = until.min(first);
            } else if y < end {
                if !matches!(self.layout, Layout::FirstLeft | Layout::FirstRight) {
                    self.diag = EdgeStep::new(p0, p2, y, s).unwrap_or(EdgeStep::spent(y));
                    // Corner 1 left of the diagonal (y down): the first triangle is.
                    let cross = i64::from(p2.0 - p0.0) * i64::from(p1.1 - p0.1)
                        - i64::from(p2.1 - p0.1) * i64::from(p1.0 - p0.0);
                    self.layout = if (cross > 0) == (p2.1 > p0.1) {
                        Layout::FirstLeft
                    } else {
                        Layout::FirstRight
                    };
                }
                until = until.min(end);
            } else {
                self.layout = apex(self.bottom);
            }
        }
        self.until = until;
    }

    /// Both planes one row down.
    #[inline(always)]
    pub(super) fn step_planes(&mut self) {
        self.drow = self.drow.wrapping_add(self.b as u32);
        self.drow2 = self.drow2.wrapping_add(self.b2 as u32);
    }

    /// Row `y` when a chain has run out: moves the chains on (or fills a polygon
    /// that is not monotone by the even-odd rule), then steps a row. Returns the
    /// spans filled.
    #[inline(never)]
    pub fn fill_row_slow<C: CornerSource>(
        &mut self,
        src: &C,
        y: i32,
        s: u32,
        row: &mut [u32],
    ) -> Result<u32, Error> {
        if self.monotone {
            if self.left.end <= y {
                self.next_edge(src, 0, y, s);
            }
            if self.right.end <= y {
                self.next_edge(src, 1, y, s);
            }
            self.lay_out(y, s);
            if self.holds(y) {
                return Ok(self.fill_span_row(row));
            }
            // Before the first row (a clipped facet) or after the last: no span.
            self.step_planes();
            return Ok(0);
        }
        let spans = self.fill_even_odd(src, y, s, row)?;
        self.step_planes();
        Ok(spans)
    }

    /// Moves chain `c` (0 forward, 1 backward) on to the edge that holds row `y`,
    /// or leaves it spent at the bottom corner.
    #[inline(always)]
    fn next_edge<C: CornerSource>(&mut self, src: &C, c: usize, y: i32, s: u32) {
        let n = usize::from(self.n);
        let bottom = usize::from(self.bottom);
        let (mut at, mut edge) = if c == 0 {
            (usize::from(self.at[0]), self.left)
        } else {
            (usize::from(self.at[1]), self.right)
        };
        // Rows end at the bottom corner; a chain that reached it stays spent (the
        // top corner is never the bottom one).
        while edge.end <= y && at != bottom {
            let to = match c {
                0 if at + 1 == n => 0,
                0 => at + 1,
                _ if at == 0 => n - 1,
                _ => at - 1,
            };
            let (a, b) = if n <= self.pts.len() {
                let half = |i: usize| {
                    let (x, y) = self.pts.get(i).copied().unwrap_or_default();
                    (2 * i32::from(x), 2 * i32::from(y))
                };
                (half(at), half(to))
            } else {
                (
                    src.corner(self.corners, self.face, at).half(),
                    src.corner(self.corners, self.face, to).half(),
                )
            };
            at = to;
            edge = EdgeStep::new(a, b, y, s).unwrap_or(EdgeStep::spent(y));
            if to == bottom {
                break;
            }
        }
        if c == 0 {
            (self.at[0], self.left) = (at as u8, edge);
        } else {
            (self.at[1], self.right) = (at as u8, edge);
        }
    }

    /// The even-odd fill of a polygon that is not monotone in y: every edge's
    /// crossing of the row, made afresh, sorted, filled in pairs.
    #[inline(never)]
    fn fill_even_odd<C: CornerSource>(
        &self,
        src: &C,
        y: i32,
        s: u32,
        row: &mut [u32],
    ) -> Result<u32, Error> {
        let mut spans = 0;
        let mut xs: Vec<i32, MAX_CORNERS> = Vec::new();
        let n = usize::from(self.n);
        for i in 0..n {
            let a = src.corner(self.corners, self.face, i).half();
            let b = src.corner(self.corners, self.face, (i + 1) % n).half();
            if let Some(x) = crossing(a, b, y, s) {
                xs.push(x).map_err(|_| Error::CapacityExceeded {
                    what: Capacity::FaceCorners,
                    needed: n,
                    capacity: MAX_CORNERS,
                })?;
            }
        }
        // Insertion sort: a few crossings, and no panic path (the library sort
        // keeps one for an order that is not total).
        for i in 1..xs.len() {
            let mut j = i;
            while j > 0 && xs.get(j - 1) > xs.get(j) {
                if let Some(pair) = xs.get_mut(j - 1..=j) {
                    pair.reverse();
                }
                j -= 1;
            }
        }
        for pair in xs.chunks_exact(2) {
            if let [x0, x1] = *pair {
                let id = 0xFFFF - u32::from(self.face);
                spans += run(row, x0, x1, self.drow, self.a, id, self.tie);
            }
        }
        Ok(spans)
    }
}

/// Corners of a clipped polygon kept for the frame.
pub(super) type ClipPolygon = Vec<FastVertex, CLIP_CORNERS>;
