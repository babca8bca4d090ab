//! Steppers: a line's minor coordinate at each pixel centre of its major axis,
//! exactly, as a floor quotient and a remainder (the scheme of `scan::edge`) set
//! up with 32-bit divisions only; and a polygon edge's crossing of each row in
//! 16.16 px, set up in `f32` (see [`EdgeStep`]).
//!
//! Units are half sub-pixels, `2^-(S+1)` px, where pixel centres are the odd
//! multiples of `h = 2^S`; one pixel is `p = 2h`. Inside the guard box
//! (`|coord| <= G` px, `G = guard_px(S)`) a coordinate is at most `B = G 2^(S+1)`
//! half-units: `|du|, |dv| <= 2B <= 2^17`, so `r0 dv < p 2B <= 2^(S+18)` and
//! `n sr < n du <= (2B)^2 / p + 2B <= 2^(S+3) G^2 + 2B`, below `2^30` for every
//! S <= 6 (see `view::guard_px`): no 64-bit product, no 64-bit division.

use super::float_int::to_i32;

/// `(floor(a / d), a mod d)` for `d > 0`.
pub(super) fn div_floor(a: i32, d: i32) -> (i32, i32) {
    let d = d.max(1);
    let (q, r) = (a / d, a % d);
    if r < 0 {
        (q - 1, r + d)
    } else {
        (q, r)
    }
}

/// `floor(v0 + (c_k - u0) dv / du)` for the centres `c_k = (2k + 1) h`, kept as
/// quotient `q` and remainder `r` (`0 <= r < du`) and stepped by one centre.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct Stepper {
    pub q: i32,
    r: i32,
    sq: i32,
    sr: i32,
    d: i32,
}

impl Stepper {
    /// The stepper of the segment from `(u0, v0)` with `du > 0`, `dv`, at centre
    /// `k_first + n`, where `k_first` is the first centre at or after `u0`.
    pub fn new(u0: i32, v0: i32, du: i32, dv: i32, n: i32, s: u32) -> Self {
        let h = 1i32 << s;
        let p = 2 * h;
        let k_first = (u0 + h - 1) >> (s + 1);
        let r0 = (2 * k_first + 1) * h - u0;
        let (q0, r0) = div_floor(r0 * dv, du);
        let (sq, sr) = div_floor(p * dv, du);
        // Starting at the first centre (the usual case) needs no third division.
        let (tq, tr) = if n == 0 {
            (0, r0)
        } else {
            div_floor(r0 + n * sr, du)
        };
        Self {
            q: v0 + q0 + n * sq + tq,
            r: tr,
            sq,
            sr,
            d: du.max(1),
        }
    }

    /// One centre forward.
    #[inline(always)]
    pub fn forward(&mut self) {
        self.q += self.sq;
        self.r += self.sr;
        if self.r >= self.d {
            self.r -= self.d;
            self.q += 1;
        }
    }

    /// One centre back.
    #[inline(always)]
    pub fn back(&mut self) {
        self.q -= self.sq;
        self.r -= self.sr;
        if self.r < 0 {
            self.r += self.d;
            self.q -= 1;
        }
    }
}

/// First row whose centre is at or below `y` (half-units): `ceil((y - h) / p)`.
#[inline(always)]
pub(super) fn row_at(y: i32, s: u32) -> i32 {
    (y + (1 << s) - 1) >> (s + 1)
}

/// One polygon edge stepped row by row in 16.16 px: `x` is the edge's crossing of
/// the current row's centre plus `0x7FFF`, so `x >> 16` is the first pixel whose
/// centre is right of (or on) the crossing: the top-left rule. Set up in `f32`
/// from the edge's top end only, with one division, so every face that shares the
/// edge steps the very same integers (watertight). The crossing is within about
/// `2^-11` px of the exact one (the slope rounded to `2^-16` px a row, the start
/// rounded in `f32`): a pixel centre closer than that to an edge may fall on the
/// other side of it.
///
/// `repr(C)`, `x` then `dx`: the span kernels step it with one double-word load.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[repr(C)]
pub(super) struct EdgeStep {
    pub x: i32,
    pub dx: i32,
    /// The row after its last.
    pub end: i32,
}

impl EdgeStep {
    /// The edge from `a` to `b` (half-units, either order) at `row`, or `None` when
    /// no row centre at or after `row` lies in its rows (`top <= yc < bottom`).
    pub fn new(a: (i32, i32), b: (i32, i32), row: i32, s: u32) -> Option<Self> {
        let ((x0, y0), (x1, y1)) = if a.1 <= b.1 { (a, b) } else { (b, a) };
        let (first, end) = (row_at(y0, s), row_at(y1, s));
        let row = row.max(first);
        if row >= end {
            return None;
        }
        // Half-units to 16.16 px: 2^(15 - S). Coordinates inside the guard box are
        // at most 4,096 px, 2^28 in 16.16: sums of two fit i32.
        let sh = 15 - s;
        let k = (x1 - x0) as f32 / (y1 - y0) as f32;
        let down = ((2 * first + 1) << s) - y0;
        let start = to_i32(down as f32 * k * (1u32 << sh) as f32);
        // An edge of one row never steps, so a slope beyond i32 (saturated) is unused.
        let dx = to_i32(k * 65536.0);
        let x = (x0 << sh)
            .wrapping_add(start)
            .wrapping_add(0x7FFF)
            .wrapping_add(dx.wrapping_mul(row - first));
        Some(Self { x, dx, end })
    }

    /// A spent edge whose rows ended before `end`, at pixel 0.
    pub const fn spent(end: i32) -> Self {
        Self { x: 0, dx: 0, end }
    }

    /// The first pixel at or right of the crossing.
    #[inline(always)]
    pub fn pixel(&self) -> i32 {
        self.x >> 16
    }

    /// One row down.
    #[inline(always)]
    pub fn next_row(&mut self) {
        self.x = self.x.wrapping_add(self.dx);
    }
}

/// The crossing pixel of edge `a`-`b` at `row`, or `None` when the row is not in
/// its rows: [`EdgeStep::new`] then [`EdgeStep::pixel`], with no state kept.
pub(super) fn crossing(a: (i32, i32), b: (i32, i32), row: i32, s: u32) -> Option<i32> {
    let ((_, y0), (_, y1)) = if a.1 <= b.1 { (a, b) } else { (b, a) };
    if row < row_at(y0, s) || row >= row_at(y1, s) {
        return None;
    }
    EdgeStep::new(a, b, row, s).map(|e| e.pixel())
}
