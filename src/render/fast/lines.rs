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

use super::step::Stepper;
use super::view::FastVertex;

/// The margin's share of the nearer face's slope, in quarter pixels.
const SLOPE_MARGIN: u32 = 1;

/// One feature line crossing the current row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct ActiveLine {
    /// Row ids (`0xFFFF - face`) of its own faces.
    own: [u16; 2],
    /// Its ends' snapped screen positions (`x`, `y`), as the vertex cache has them.
    ends: [(i16, i16); 2],
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
}

/// What the line pass does with a pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum LineTest {
    /// Every pixel visible (wireframe).
    None,
    /// Tested against the row.
    Row,
}

impl ActiveLine {
    /// The line between `a` and `b` (snapped screen points) with own faces
    /// `faces`; `None` when it has no pixel centre.
    /// `ends` are the edge's vertices' cache positions (which the faces around its
    /// ends share).
    pub fn new(
        a: FastVertex,
        b: FastVertex,
        faces: [u16; 2],
        ends: [(i16, i16); 2],
        s: u32,
    ) -> Option<Self> {
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
        let d = (d0 + c * per) as u32;
        let dd = (per * p as f32) as i32 * dir;
        Some(Self {
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
        })
    }

    /// Draws the line's pixels in row `y` into the visible and hidden masks
    /// (`row` is the finished row of face entries); returns false once the line
    /// has no pixel left.
    #[allow(clippy::too_many_arguments)]
    pub fn row(
        &mut self,
        y: i32,
        s: u32,
        test: LineTest,
        row: &[u32],
        slopes: &[u16],
        beside: &impl Fn(u16, &[(i16, i16); 2], (i32, i32)) -> bool,
        visible: &mut [u32],
        hidden: &mut [u32],
    ) -> bool {
        loop {
            let k = i32::from(self.k);
            let m = self.v.q >> (s + 1);
            let (px, py) = if self.x_major { (k, m) } else { (m, k) };
            if py > y {
                return true;
            }
            if py == y && px >= 0 {
                if let Some(&cell) = row.get(px as usize) {
                    let hide = test == LineTest::Row && {
                        let id = cell as u16;
                        let depth = cell & 0xFFFF_0000;
                        depth > self.d.saturating_add(self.bias)
                            && id != self.own[0]
                            && id != self.own[1]
                            && {
                                let slope = slopes.get(usize::from(0xFFFF - id)).copied();
                                let slope = u32::from(slope.unwrap_or(0));
                                depth
                                    > self.d.saturating_add(
                                        self.bias.saturating_add((SLOPE_MARGIN * slope) << 14),
                                    )
                            }
                            && {
                                let c = (2 * k + 1) << s;
                                let e = if self.x_major {
                                    (c, self.v.q)
                                } else {
                                    (self.v.q, c)
                                };
                                !beside(0xFFFF - id, &self.ends, e)
                            }
                    };
                    let mask = if hide { &mut *hidden } else { &mut *visible };
                    let x = px as usize;
                    if let Some(w) = mask.get_mut(x / 32) {
                        *w |= 1 << (x % 32);
                    }
                }
            }
            if self.k == self.last {
                return false;
            }
            self.k += i16::from(self.dir);
            self.d = self.d.wrapping_add(self.dd as u32);
            if self.dir > 0 {
                self.v.forward();
            } else {
                self.v.back();
            }
        }
    }
}
