//! One polygon edge as an exact integer DDA, and the edge table that holds them.
//!
//! Units: "half-units" of the sub-pixel grid, `u = 2^-(S+1)` px, so that pixel
//! centres are integers: column i is sampled at `(2i+1)·h` with `h = 2^S`, row j at
//! `(2j+1)·h`, and one pixel is `p = 2h`.
//!
//! The edge from top `(x0, y0)` to bottom `(x1, y1)` (`y0 < y1`) crosses row j when
//! `y0 <= py < y1` (the `+e^2` nudge of the convention makes the top end inclusive),
//! at `x = x0 + (py - y0)·dx/dy`. The crossing counts for pixel i when `x <= (2i+1)·h`
//! (the `+e` nudge makes equality count), so the first pixel right of the crossing is
//! `c = ceil((x - h) / p)`. With `x = X + R/dy`, `0 <= R < dy`:
//! `c = (X + h - 1 + [R > 0]) >> (S + 1)`. Stepping one row adds `p·dx/dy` to `x`,
//! split into a quotient and a remainder: one add, one compare, no division.
//!
//! Bounds inside the guard band (`|coord| <= 2^14` px, S <= 12): coordinates are at
//! most `2^(15+S) <= 2^27` half-units, so `|dx|, dy <= 2^28`; set-up products
//! `t·dx < dy·|dx| <= 2^56` and `p·dx <= 2^41` fit `i64`; the stepping state
//! (`e <= 2^28`, `r < dy <= 2^28`, `|qs| <= |dx| + 1` when the edge spans two or more
//! rows, which forces `dy > p`) fits `i32` with two bits to spare.

use heapless::Vec;

use crate::scan::RowRange;
use crate::Viewport;

/// An edge in half-units, top end first, with its winding direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct EdgeLine {
    pub x0: i64,
    pub y0: i64,
    pub x1: i64,
    pub y1: i64,
    /// +1 when the polygon's edge runs downward, -1 upward.
    pub winding: i8,
}

/// What clipping an edge to the viewport leaves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Clipped {
    /// Nothing in the viewport's rows, or wholly right of the viewport: no crossing
    /// there can count for a visible pixel.
    Gone,
    /// Wholly left of the viewport: it counts for every pixel of its rows, so it
    /// becomes a vertical edge at x = 0.
    Left(RowRange),
    /// Crosses the viewport somewhere: rows to walk.
    Rows(RowRange),
}

impl EdgeLine {
    /// The edge from `a` to `b` (half-units), or `None` when horizontal.
    pub fn new(a: (i64, i64), b: (i64, i64)) -> Option<Self> {
        let ((x0, y0), (x1, y1), winding) = match a.1.cmp(&b.1) {
            core::cmp::Ordering::Less => (a, b, 1),
            core::cmp::Ordering::Greater => (b, a, -1),
            core::cmp::Ordering::Equal => return None,
        };
        Some(Self {
            x0,
            y0,
            x1,
            y1,
            winding,
        })
    }

    /// Clips the edge to `rows` (inside the viewport) and the viewport's columns
    /// (`s` = sub-pixel bits).
    pub fn clip(&self, s: u32, viewport: Viewport, rows: RowRange) -> Clipped {
        let h = 1i64 << s;
        // First row whose sample is at or below y: ceil((y - h) / p).
        let row = |y: i64| (y + h - 1) >> (s + 1);
        let first = row(self.y0).max(i64::from(rows.first));
        let end = row(self.y1).min(i64::from(rows.end));
        if first >= end {
            return Clipped::Gone;
        }
        // The range is inside [0, height], height <= 8192: the casts are exact.
        let rows = RowRange {
            first: first as i32,
            end: end as i32,
        };
        let right_of_last_centre = (2 * i64::from(viewport.width) - 1) * h;
        if self.x0.min(self.x1) > right_of_last_centre {
            Clipped::Gone
        } else if self.x0.max(self.x1) <= h {
            Clipped::Left(rows)
        } else {
            Clipped::Rows(rows)
        }
    }

    /// The exact crossing index at row `j`, clamped to `[0, width]`, evaluated
    /// directly in 128-bit arithmetic: valid for any 32-bit input coordinates.
    pub fn crossing_at(&self, s: u32, j: i32, width: u16) -> u16 {
        let h = 1i128 << s;
        let dx = i128::from(self.x1) - i128::from(self.x0);
        let dy = i128::from(self.y1) - i128::from(self.y0);
        let t = (2 * i128::from(j) + 1) * h - i128::from(self.y0);
        let num = t * dx;
        // dy > 0 by construction (the edge is not horizontal): the checks cannot fail,
        // they only spare the division its panic path.
        let x = i128::from(self.x0) + num.checked_div_euclid(dy).unwrap_or(0);
        let up = i128::from(num.checked_rem_euclid(dy).unwrap_or(0) != 0);
        let c = (x + h - 1 + up) >> (s + 1);
        c.clamp(0, i128::from(width)) as u16
    }
}

/// Floor quotient and non-negative remainder for `d > 0`; in 32 bits when both
/// operands fit (one hardware divide on a Cortex-M4 instead of a 64-bit library call).
#[inline]
pub(crate) fn div_rem_euclid(n: i64, d: i64) -> (i64, i64) {
    if let (Ok(n32), Ok(d32)) = (i32::try_from(n), i32::try_from(d)) {
        let (q, r) = (
            n32.checked_div_euclid(d32).unwrap_or(0),
            n32.checked_rem_euclid(d32).unwrap_or(0),
        );
        return (i64::from(q), i64::from(r));
    }
    (
        n.checked_div_euclid(d).unwrap_or(0),
        n.checked_rem_euclid(d).unwrap_or(0),
    )
}

/// The stepping state of one edge inside the guard band (all 32-bit).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Edge {
    /// First row (inclusive) and last row (exclusive) the edge crosses.
    pub first: i32,
    pub end: i32,
    /// `X + h - 1`, where `X = floor(x)` at the current row.
    e: i32,
    /// Remainder of x, `0 <= r < dy`.
    r: i32,
    /// Per-row step of `e` and `r`.
    qs: i32,
    rs: i32,
    dy: i32,
    /// +1 downward, -1 upward.
    pub winding: i8,
}

impl Edge {
    /// An edge crossing no row.
    pub const ZERO: Self = Self {
        first: 0,
        end: 0,
        e: 0,
        r: 0,
        qs: 0,
        rs: 0,
        dy: 1,
        winding: 0,
    };

    /// All zero: room for an edge not set up yet, so that a `static` holding such
    /// rooms lands in `.bss` (not in `.data`, which costs flash too). It crosses no
    /// row either, and stepping it divides by nothing.
    pub(crate) const UNSET: Self = Self {
        dy: 0,
        ..Self::ZERO
    };

    /// Sets up the DDA at the first visible row. Only for edges whose endpoints lie
    /// inside the guard band (see the module docs for why nothing overflows).
    pub fn new(line: &EdgeLine, clipped: Clipped, s: u32) -> Option<Self> {
        let (rows, left) = match clipped {
            Clipped::Gone => return None,
            Clipped::Left(rows) => (rows, true),
            Clipped::Rows(rows) => (rows, false),
        };
        let mut edge = Self {
            first: rows.first,
            end: rows.end,
            winding: line.winding,
            dy: 1,
            ..Self::default()
        };
        if left {
            // e = 0, r = 0, no step: the crossing stays at column 0.
            return Some(edge);
        }
        let h = 1i64 << s;
        let dx = line.x1 - line.x0;
        let dy = line.y1 - line.y0;
        let t = (2 * i64::from(rows.first) + 1) * h - line.y0;
        let num = t * dx;
        // dy > 0 (not horizontal): `checked_` only spares the divisions a panic path.
        let (q, r) = div_rem_euclid(num, dy);
        edge.e = (line.x0 + q + h - 1) as i32;
        edge.r = r as i32;
        edge.dy = dy as i32;
        if rows.end - rows.first > 1 {
            let (qs, rs) = div_rem_euclid(2 * h * dx, dy);
            edge.qs = qs as i32;
            edge.rs = rs as i32;
        }
        Some(edge)
    }

    /// The first pixel right of the crossing on the current row (may lie outside
    /// the viewport; the caller clamps).
    #[inline(always)]
    pub fn crossing(&self, s: u32) -> i32 {
        (self.e + i32::from(self.r != 0)) >> (s + 1)
    }

    /// Moves to the next row.
    #[inline(always)]
    pub fn step(&mut self) {
        self.e += self.qs;
        self.r += self.rs;
        if self.r >= self.dy {
            self.r -= self.dy;
            self.e += 1;
        }
    }
}

/// The edges of one polygon, sorted by first row: the scan-line method's edge table.
#[derive(Debug, Clone)]
pub struct EdgeTable<const N: usize> {
    pub(crate) edges: Vec<Edge, N>,
}

impl<const N: usize> Default for EdgeTable<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> EdgeTable<N> {
    /// An empty table.
    pub const fn new() -> Self {
        Self { edges: Vec::new() }
    }

    /// Number of edges held.
    pub fn len(&self) -> usize {
        self.edges.len()
    }

    /// True when no edge is held.
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty()
    }
}
