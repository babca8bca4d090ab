//! Active feature lines: each is walked one pixel per pixel centre along its major
//! axis (the pixels of `render::lines::walk_segment`, exactly), row by row, and each
//! pixel is tested against the finished row: hidden when the face nearest at the
//! pixel centre is nearer than the line's depth there by more than a margin (one
//! pixel of the line's own depth slope, one depth unit, and a share of a pixel of
//! the nearer face's steepest slope) and is not one of the line's own faces. The
//! pixel centre lies up to half a pixel from the edge point it stands for, and a
//! face beside a sliver own face, or around an end, covers the centre there without
//! covering the edge point: so a face with a corner at one of the line's ends hides
//! the pixel only when its polygon covers the edge point itself (tested exactly,
//! only for these few).
//!
//! Most pixels are decided with one compare (in front of the face at the centre
//! by more than the line's bias), and most of the others with a second: behind
//! the face the line found last, known apart from its ends, by more than the
//! most the rules can move the depth. Only the rest (about a quarter of
//! suzanne's line pixels) go through the rules.
//!
//! With dashes along the edges ([`super::dash`]) a hidden pixel in a gap is also
//! marked in a third mask, the gaps, which the row's output takes away.

use heapless::Vec;

use super::dash::{DashPhase, Dashing};
pub(super) use super::dash::{GapMask, Gaps, NoGaps};
use super::float_int::{to_i32, to_u32};
use super::segments::{Crossing, PLACE_BITS};
use super::step::Stepper;
use super::view::FastVertex;
use crate::camera::sqrt;

/// The margin's share of the nearer face's slope, in quarter pixels.
const SLOPE_MARGIN: u32 = 1;

/// One feature line crossing the current row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct ActiveLine {
    /// Row ids (`0xFFFF - face`) of its own faces.
    own: [u16; 2],
    /// The positions of its edge's ends as the vertex cache has them
    /// ([`FastVertex::key`]: an end outside matches no corner inside), which
    /// the faces around them share.
    ends: [u32; 2],
    /// Current and last centre index along the major axis, and the step (+-1).
    k: i16,
    last: i16,
    dir: i8,
    x_major: bool,
    /// Minor coordinate at centre `k`.
    v: Stepper,
    /// Depth at centre `k` (16.16) and per step.
    d: u32,
    dd: i32,
    bias: u32,
    /// The row id of the last face the depth test looked up (0 at first), and
    /// what it found: the face's depth step along the line's minor axis when it
    /// is drawn as one plane, else its margin; and whether it is known to be
    /// apart from the line's ends.
    near: u16,
    near_plane: bool,
    near_apart: bool,
    /// Whether `near` is known to touch an end with every corner inside: its
    /// corners need not be matched with the ends again.
    near_touches: bool,
    near_value: u32,
    /// `u32::MAX` until `near` is known apart, then a margin beyond which the
    /// face is nearer at every edge point of the pixel (see
    /// [`sure`](Self::sure)): such pixels skip the rules.
    near_sure: u32,
    /// Hidden lines by the segment: the next boundary of the line's pieces in
    /// the walk's direction (an index into the frame's boundaries), the first
    /// and end of its boundaries, and whether the piece walked now is hidden.
    piece: u16,
    piece_first: u16,
    piece_end: u16,
    piece_hidden: bool,
}

/// What the line test knows of the face nearest at a pixel.
pub(super) trait FaceSlopes {
    /// The face's depth change a pixel right and a row down (16.16), when it is
    /// drawn this row as one plane.
    fn gradient(&self, face: u16) -> Option<(i32, i32)>;
    /// The face's steepest depth change a pixel, in whole depth units.
    fn slope(&self, face: u16) -> u16;
}

/// A face nearer than a line's pixel, seen from the line's ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Beside {
    /// No corner of the face is at an end of the line: it hides the pixel.
    Apart,
    /// A corner is at an end and another is outside the frame (no exact test):
    /// it hides every pixel, as a face apart does.
    Clipped,
    /// A corner is at an end, and the face covers the edge point: it hides it.
    Covers,
    /// A corner is at an end, and the face does not cover the edge point.
    Misses,
}

/// What the line pass does with a pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum LineTest {
    /// Every pixel visible (wireframe).
    None,
    /// Tested against the row.
    Row,
    /// Hidden where its pieces say (hidden lines by the segment).
    Pieces,
}

/// What the lines' pixels in row `y` are tested against (S = `s` sub-pixel bits):
/// the finished `row` of face entries, what the test knows of its faces' slopes
/// (`faces`), and how a face nearer than a line's pixel lies beside the line's ends
/// (`beside`: face, the line's ends' keys, edge point, and whether the face is
/// known to touch an end with every corner inside, so that only the edge point is
/// left to test).
struct LineRow<'a, F, B> {
    y: i32,
    s: u32,
    test: LineTest,
    row: &'a [u32],
    faces: &'a F,
    beside: &'a B,
    /// The frame's piece boundaries (with [`LineTest::Pieces`]).
    pieces: &'a [Crossing],
}

/// A pixel centre of a line: centre `k` along its major axis, and the line's minor
/// coordinate `q` and depth `d` there.
#[derive(Clone, Copy)]
struct Centre {
    k: i32,
    q: i32,
    d: u32,
}

impl ActiveLine {
    /// The line between `a` and `b` (snapped screen points) with own faces
    /// `faces`; `None` when it has no pixel centre.
    /// `ends`: its edge's ends' keys in the vertex cache (before clipping).
    /// `along`: the frame's dashes along the edges, and the anchor
    /// (`2^-S` px), the unclipped position of the edge's end on `a`'s side;
    /// the line's dash phase comes with it ([`DashPhase::SCREEN`] without `along`).
    pub fn new(
        a: FastVertex,
        b: FastVertex,
        faces: [u16; 2],
        ends: [u32; 2],
        s: u32,
        along: Option<(Dashing, (f32, f32))>,
    ) -> Option<(Self, DashPhase)> {
        let (h, p) = (1i32 << s, 2i32 << s);
        let ((ax, ay), (bx, by)) = (a.half(), b.half());
        let (dx, dy) = (bx - ax, by - ay);
        if dx == 0 && dy == 0 {
            return None;
        }
        let x_major = dx.abs() >= dy.abs();
        // u0 is the end with the smaller major coordinate.
        let forward = if x_major { dx >= 0 } else { dy >= 0 };
        let (s0, s1) = if forward { (a, b) } else { (b, a) };
        let ((x0, y0), (x1, y1)) = (s0.half(), s1.half());
        let (u0, v0, u1, v1) = if x_major {
            (x0, y0, x1, y1)
        } else {
            (y0, x0, y1, x1)
        };
        let (du, dv) = (u1 - u0, v1 - v0);
        let k_first = (u0 + h - 1) >> (s + 1);
        let k_last = (u1 - h) >> (s + 1);
        if k_first > k_last {
            return None;
        }
        // Walk toward growing y: an x-major line going up is walked from its end.
        let back = x_major && dv < 0;
        let (k, last, dir) = if back {
            (k_last, k_first, -1)
        } else {
            (k_first, k_last, 1)
        };
        let v = Stepper::new(u0, v0, du, dv, k - k_first, s);
        // Depth at centre k and per step, from the ends' depths.
        let (d0, d1) = (s0.d as f32, s1.d as f32);
        let per = (d1 - d0) / du as f32;
        let c = ((2 * k + 1) * h - u0) as f32;
        let d = to_u32(d0 + c * per);
        let dd = to_i32(per * p as f32) * dir;
        let phase = match along {
            Some((dashing, (ax, ay))) => {
                let anchor = if x_major { ax } else { ay } / (1u32 << s) as f32;
                let (fu, fv) = (du as f32, dv as f32);
                let ratio = sqrt(fu * fu + fv * fv) / fu;
                // `a` is the end at the smaller major coordinate when `forward`.
                DashPhase::new(dashing, anchor, forward, ratio, k_first)
            }
            None => DashPhase::SCREEN,
        };
        let line = Self {
            own: faces.map(|f| 0xFFFF - f),
            ends,
            k: k as i16,
            last: last as i16,
            dir: dir as i8,
            x_major,
            v,
            d,
            dd,
            bias: dd.unsigned_abs().saturating_add(1 << 16),
            near: 0,
            near_plane: false,
            near_apart: false,
            near_touches: false,
            near_value: 0,
            near_sure: u32::MAX,
            piece: 0,
            piece_first: 0,
            piece_end: 0,
            piece_hidden: false,
        };
        Some((line, phase))
    }

    /// Gives the line its pieces (hidden lines by the segment): boundaries
    /// `first..first + len` of the frame's list, in their edge's major axis from
    /// its low end, and whether it is `hidden` there.
    pub fn with_pieces(&mut self, first: u16, len: u16, hidden: bool) {
        let end = first.saturating_add(len);
        self.piece_first = first;
        self.piece_end = end;
        if self.dir > 0 {
            self.piece = first;
            self.piece_hidden = hidden;
        } else {
            // Walked from the high end: past every boundary.
            self.piece = end;
            self.piece_hidden = hidden ^ (len % 2 == 1);
        }
    }

    /// Is the line hidden at centre `k`, by its pieces? Moves the line's place
    /// among them (centres come in the walk's order).
    #[inline(always)]
    fn piece_hidden(&mut self, k: i32, pieces: &[Crossing], s: u32) -> bool {
        let c = ((2 * k + 1) << s) << PLACE_BITS;
        if self.dir > 0 {
            while self.piece < self.piece_end
                && pieces
                    .get(usize::from(self.piece))
                    .is_some_and(|b| b.place() < c)
            {
                self.piece += 1;
                self.piece_hidden = !self.piece_hidden;
            }
        } else {
            while self.piece > self.piece_first
                && pieces
                    .get(usize::from(self.piece) - 1)
                    .is_some_and(|b| b.place() >= c)
            {
                self.piece -= 1;
                self.piece_hidden = !self.piece_hidden;
            }
        }
        self.piece_hidden
    }

    /// The last row the line is active in when made active at row `y`: where
    /// [`row`](Self::row) returns false. Off the hot path: for counting a frame's
    /// peak of active lines after an overflow.
    pub fn end_row(&self, y: i32, s: u32) -> i32 {
        let last = i32::from(self.last);
        if !self.x_major {
            // One centre a row: the last centre's row, or at once if above.
            return last.max(y);
        }
        // The row of the last centre, stepped as `row` steps it.
        let mut v = self.v;
        for _ in 0..(last - i32::from(self.k)).unsigned_abs() {
            if self.dir > 0 {
                v.forward();
            } else {
                v.back();
            }
        }
        (v.q >> (s + 1)).max(y)
    }

    /// Draws the line's pixels in row `at.y` into the visible and hidden masks, and
    /// its hidden pixels in the gaps of its dashes into `gaps`.
    /// Returns false once the line has no pixel left.
    #[inline(always)]
    fn row<F: FaceSlopes, B: Fn(u16, [u32; 2], (i32, i32), bool) -> Beside>(
        &mut self,
        at: &LineRow<'_, F, B>,
        visible: &mut [u32],
        hidden: &mut [u32],
        gaps: &mut impl Gaps,
    ) -> bool {
        let (y, sh) = (at.y, at.s + 1);
        let last = i32::from(self.last);
        if !self.x_major {
            // One pixel a row: centre k is row k. A clipped line made at row 0 may
            // start above the frame: walked down to the row first.
            while i32::from(self.k) < y {
                if i32::from(self.k) == last {
                    return false;
                }
                self.next_row();
            }
            let k = i32::from(self.k);
            if k > y {
                return true;
            }
            let (q, d) = (self.v.q, self.d);
            self.pixel(q >> sh, Centre { k, q, d }, at, visible, hidden, gaps);
            if k == last {
                return false;
            }
            self.next_row();
            return true;
        }
        let mut k = i32::from(self.k);
        let (mut v, mut d) = (self.v, self.d);
        // Read once: the pixels write the record's face cache.
        let (forward, dd) = (self.dir > 0, self.dd as u32);
        let more = loop {
            let py = v.q >> sh;
            if py > y {
                break true;
            }
            if py == y {
                let c = Centre { k, q: v.q, d };
                self.pixel(k, c, at, visible, hidden, gaps);
            }
            if k == last {
                break false;
            }
            d = d.wrapping_add(dd);
            if forward {
                k += 1;
                v.forward();
            } else {
                k -= 1;
                v.back();
            }
        };
        (self.k, self.v, self.d) = (k as i16, v, d);
        more
    }

    /// A steep line one centre (one row) on.
    #[inline(always)]
    fn next_row(&mut self) {
        self.k += 1;
        self.d = self.d.wrapping_add(self.dd as u32);
        self.v.forward();
    }

    /// Marks the line's pixel at centre `c`, in column `x` of `at.row` (none
    /// outside it), visible or hidden, and hidden in a gap.
    #[inline(always)]
    fn pixel<F: FaceSlopes, B: Fn(u16, [u32; 2], (i32, i32), bool) -> Beside>(
        &mut self,
        x: i32,
        c: Centre,
        at: &LineRow<'_, F, B>,
        visible: &mut [u32],
        hidden: &mut [u32],
        gaps: &mut impl Gaps,
    ) {
        let Some(&cell) = at.row.get(x as usize) else {
            return;
        };
        // Most pixels are in front of the face there: one compare. Most of the
        // others are behind the face the last one was, known apart from the
        // line's ends: one compare more, with a margin that covers what the
        // rules move the depth by (then only a steep line's next column is
        // looked at, as in `hidden_by`): 1,800 of suzanne's 3,070 pixels a frame
        // that pass the first. Kept inline: out of line, the rules' call cost
        // more than the margin saved.
        if at.test == LineTest::Pieces {
            let hide = self.piece_hidden(c.k, at.pieces, at.s);
            let mask = if hide { hidden } else { visible };
            let x = x as usize;
            if let Some(w) = mask.get_mut(x / 32) {
                *w |= 1 << (x % 32);
            }
            if hide {
                gaps.mark(c.k, x);
            }
            return;
        }
        let hide = at.test == LineTest::Row
            && cell & 0xFFFF_0000 > c.d.saturating_add(self.bias)
            && if cell as u16 == self.near
                && cell & 0xFFFF_0000 > c.d.saturating_add(self.near_sure)
            {
                self.x_major || next_shows_face(at.row, x, c.q, at.s)
            } else {
                !self.owns(cell) && self.hidden_by(cell, x, c, at)
            };
        let mask = if hide { hidden } else { visible };
        let x = x as usize;
        if let Some(w) = mask.get_mut(x / 32) {
            *w |= 1 << (x % 32);
        }
        if hide {
            gaps.mark(c.k, x);
        }
    }

    /// Does the face of entry `cell` (column `x`) of `at.row`, nearer than the
    /// line's depth at centre `c` by more than its bias, hide the line's pixel
    /// there, when it is not one of the line's own faces? Not within a share of its
    /// own slope, and not when it only touches the line at an end (tested exactly).
    #[inline(always)]
    fn hidden_by<F: FaceSlopes, B: Fn(u16, [u32; 2], (i32, i32), bool) -> Beside>(
        &mut self,
        cell: u32,
        x: i32,
        c: Centre,
        at: &LineRow<'_, F, B>,
    ) -> bool {
        let (Centre { k, q, d }, row, s) = (c, at.row, at.s);
        let face = 0xFFFF - cell as u16;
        if !self.nearer_at_edge(cell, d, q, s, at.faces) {
            return false;
        }
        // A steep line's edge point lies between its pixel's centre and the next
        // column's, in the same row.
        if !self.x_major && !next_shows_face(row, x, q, s) {
            return false;
        }
        // Most hidden pixels are behind a face that does not touch the line's ends:
        // the last face found so is kept.
        // (The depth test just looked the face up: it is `near`.)
        self.near_apart || self.hides_near_ends(face, k, q, s, at.beside)
    }

    /// Is the face of entry `cell` one of the line's own faces (never hiding it)?
    #[inline(always)]
    fn owns(&self, cell: u32) -> bool {
        let id = cell as u16;
        id == self.own[0] || id == self.own[1]
    }

    /// A margin beyond which the face `near` is nearer than the line at every
    /// edge point of a pixel whose centre it holds: what
    /// [`nearer_at_edge`](Self::nearer_at_edge) compares with, plus the most
    /// its plane can move the depth from the centre to the edge point (half
    /// a pixel of its gradient), less the middle of the stored unit.
    fn sure(&self) -> u32 {
        if self.near_plane {
            let half = (self.near_value as i32).unsigned_abs().saturating_add(1) >> 1;
            self.bias.saturating_add(half).saturating_sub(0x8000)
        } else {
            self.near_value
        }
    }

    /// Is the face of row entry `cell` nearer than the line (depth `d` at the edge
    /// point with minor coordinate `q`) by more than the line's bias: at the edge
    /// point itself for a face drawn as one plane (its depth moved there from the
    /// pixel centre along its plane), at the centre by a share of its steepest
    /// slope more for one drawn as several?
    #[inline(always)]
    fn nearer_at_edge(
        &mut self,
        cell: u32,
        d: u32,
        q: i32,
        s: u32,
        slopes: &impl FaceSlopes,
    ) -> bool {
        let (id, face) = (cell as u16, 0xFFFF - cell as u16);
        if id != self.near {
            // Hidden pixels mostly lie behind the face the last one did: its
            // look-up is kept.
            (self.near_plane, self.near_value) = match slopes.gradient(face) {
                Some((a, b)) => (true, if self.x_major { b } else { a } as u32),
                None => {
                    let slope = u32::from(slopes.slope(face));
                    (
                        false,
                        self.bias.saturating_add((SLOPE_MARGIN * slope) << 14),
                    )
                }
            };
            self.near = id;
            self.near_apart = false;
            self.near_touches = false;
            self.near_sure = u32::MAX;
        }
        if self.near_plane {
            // The middle of the stored unit at the centre, moved along the minor
            // axis to the edge point.
            let off = edge_offset(q, s);
            let grad = self.near_value as i32;
            let at = i64::from(cell & 0xFFFF_0000)
                + 0x8000
                + ((i64::from(grad) * i64::from(off)) >> (s + 1));
            at > i64::from(d) + i64::from(self.bias)
        } else {
            cell & 0xFFFF_0000 > d.saturating_add(self.near_value)
        }
    }

    /// [`hidden_by`](Self::hidden_by) for a face not known to be apart from the
    /// line's ends: asks `beside`, and keeps the face when it is apart.
    #[inline(never)]
    fn hides_near_ends(
        &mut self,
        face: u16,
        k: i32,
        q: i32,
        s: u32,
        beside: &impl Fn(u16, [u32; 2], (i32, i32), bool) -> Beside,
    ) -> bool {
        let c = (2 * k + 1) << s;
        let e = if self.x_major { (c, q) } else { (q, c) };
        // Only the edge point changes from pixel to pixel: a face that touches
        // an end keeps that known (the panel's M4 frame 1.4 % fewer
        // instructions; suzanne's faces are small, and the face found last
        // seldom stays).
        let answer = beside(face, self.ends, e, self.near_touches);
        self.near_touches = matches!(answer, Beside::Covers | Beside::Misses);
        match answer {
            Beside::Apart | Beside::Clipped => {
                self.near_apart = true;
                self.near_sure = self.sure();
                true
            }
            Beside::Covers => true,
            Beside::Misses => false,
        }
    }
}

/// Does the column next to `x` of `row`, on the side of the edge point (minor
/// coordinate `q`) of a steep line's pixel, show a face? When the edge point is
/// off the pixel's centre and that column shows none, the line is an outline
/// there and the face at the centre ends before the edge point (a silhouette
/// seen beside the next face of a convex surface): not hidden.
#[inline(always)]
fn next_shows_face(row: &[u32], x: i32, q: i32, s: u32) -> bool {
    let off = edge_offset(q, s);
    off == 0
        || row
            .get((x + off.signum()) as usize)
            .is_some_and(|&n| n != 0)
}

/// From the centre of the pixel holding minor coordinate `q` to `q` itself, in
/// half-units (`2^-(S+1)` px). Computed where it is needed (twice for a few
/// pixels): computing it once up front and passing it cost suzanne's frame 1.5 %.
#[inline(always)]
fn edge_offset(q: i32, s: u32) -> i32 {
    q - (((q >> (s + 1)) << 1) + 1) * (1i32 << s)
}

/// Draws every active line's pixels in row `y` into the masks, and drops the
/// lines that end; `row` is the finished row of face entries. Out of line: the row
/// loop's values stay in its registers.
// Its parameters stay apart, not in a `LineRow`: as references of their own they
// tell the compiler that the row, the faces and the masks do not overlap (passed in
// a `LineRow`, suzanne's M4 frame took 3 % more instructions).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(super) fn line_row<const LINES: usize>(
    lines: &mut Vec<ActiveLine, LINES>,
    y: i32,
    s: u32,
    test: LineTest,
    row: &[u32],
    faces: &impl FaceSlopes,
    beside: &impl Fn(u16, [u32; 2], (i32, i32), bool) -> Beside,
    pieces: &[Crossing],
    visible: &mut [u32],
    hidden: &mut [u32],
    mut gaps: impl Gaps,
) {
    let at = LineRow {
        y,
        s,
        test,
        row,
        faces,
        beside,
        pieces,
    };
    let mut i = 0;
    while let Some(line) = lines.get_mut(i) {
        gaps.line(i);
        if line.row(&at, visible, hidden, &mut gaps) {
            i += 1;
        } else {
            gaps.remove(i, lines.len() - 1);
            // The last line takes its place: swapped, not moved (a move is a call
            // to `memmove` for the 72 bytes).
            let n = lines.len();
            if let Some([one, .., last]) = lines.get_mut(i..n) {
                core::mem::swap(one, last);
            }
            lines.pop();
        }
    }
}
