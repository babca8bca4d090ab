//! The per-face facts area subdivision asks about a clipped, projected polygon: the
//! pixel centres its box can reach, whether it is convex (then covering an area's
//! four corner centres means covering every centre between them), and whether an
//! area's centres all lie strictly outside one of its edges.

use heapless::Vec;

use crate::render::transform::ScreenVertex;

/// An inclusive box of pixel indices: the centres a polygon can cover.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct PixelBox {
    pub x0: u16,
    pub y0: u16,
    pub x1: u16,
    pub y1: u16,
}

impl PixelBox {
    /// The pixels whose centres lie in the polygon's closed bounding box, within a
    /// `width` x `height` frame; `None` when there are none (no centre is covered).
    ///
    /// A covered centre lies in the closed polygon, so in its closed box: pixel `i`
    /// has its centre at `(2i + 1) 2^s` half sub-pixel units and a vertex `x` is at
    /// `2x`, so `i` runs from `ceil((2 x_min - 2^s) / 2^(s+1))` to
    /// `floor((2 x_max - 2^s) / 2^(s+1))`.
    pub fn of(poly: &[ScreenVertex], s: u32, width: u16, height: u16) -> Option<Self> {
        let first = poly.first()?;
        let (mut lx, mut hx, mut ly, mut hy) = (first.x, first.x, first.y, first.y);
        for v in poly {
            lx = lx.min(v.x);
            hx = hx.max(v.x);
            ly = ly.min(v.y);
            hy = hy.max(v.y);
        }
        let (h, d) = (1i64 << s, 1i64 << (s + 1));
        let lo = |c: i32| -((h - 2 * i64::from(c)).div_euclid(d));
        let hi = |c: i32| (2 * i64::from(c) - h).div_euclid(d);
        let (x0, x1) = (lo(lx).max(0), hi(hx).min(i64::from(width) - 1));
        let (y0, y1) = (lo(ly).max(0), hi(hy).min(i64::from(height) - 1));
        if x0 > x1 || y0 > y1 {
            return None;
        }
        // In 0 ..= width - 1 and 0 ..= height - 1 after the clamps.
        Some(Self {
            x0: x0 as u16,
            y0: y0 as u16,
            x1: x1 as u16,
            y1: y1 as u16,
        })
    }

    /// Whether the box shares a pixel with the area `x0 .. x1` x `y0 .. y1`.
    pub fn meets(&self, area: &Rect) -> bool {
        self.x0 < area.x1 && area.x0 <= self.x1 && self.y0 < area.y1 && area.y0 <= self.y1
    }

    /// Whether the box holds every pixel of the area.
    pub fn holds(&self, area: &Rect) -> bool {
        self.x0 <= area.x0 && area.x1 <= self.x1 + 1 && self.y0 <= area.y0 && area.y1 <= self.y1 + 1
    }
}

/// An area of pixels `x0 .. x1` x `y0 .. y1` (never empty).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Rect {
    pub x0: u16,
    pub y0: u16,
    pub x1: u16,
    pub y1: u16,
}

impl Rect {
    /// The centres of the four corner pixels, in half sub-pixel units.
    pub fn corners(&self, s: u32) -> [(i64, i64); 4] {
        let c = |k: u16| (2 * i64::from(k) + 1) << s;
        let (l, r, t, b) = (c(self.x0), c(self.x1 - 1), c(self.y0), c(self.y1 - 1));
        [(l, t), (r, t), (l, b), (r, b)]
    }

    /// Whether the area is one pixel.
    pub fn is_pixel(&self) -> bool {
        self.x1 - self.x0 == 1 && self.y1 - self.y0 == 1
    }
}

/// The orientation of a convex polygon: +1 or -1 (the sign of its edges' cross
/// products in screen coordinates), 0 when it is not convex or has no area.
///
/// Convex here means: consecutive non-zero edges never turn against the polygon's
/// sense (collinear edges may continue, never reverse) and the edges' x and y
/// directions each change sign at most twice around the loop, which excludes
/// star polygons that wind more than once. Such a polygon is simple and equals the
/// intersection of its edges' closed half-planes.
pub(crate) fn convex_orientation<const POLY: usize>(poly: &[ScreenVertex]) -> i8 {
    let mut edges: Vec<(i64, i64), POLY> = Vec::new();
    let mut prev = match poly.last() {
        Some(v) => v,
        None => return 0,
    };
    for v in poly {
        let e = (
            i64::from(v.x) - i64::from(prev.x),
            i64::from(v.y) - i64::from(prev.y),
        );
        prev = v;
        if e != (0, 0) && edges.push(e).is_err() {
            return 0;
        }
    }
    if edges.len() < 3 {
        return 0;
    }
    let mut sense = 0i8;
    let (mut x_changes, mut y_changes) = (0u32, 0u32);
    let (mut last_x, mut last_y) = (0i64, 0i64);
    // Signs of the last non-zero x and y components before the loop starts.
    for e in edges.iter().rev() {
        if last_x == 0 {
            last_x = e.0.signum();
        }
        if last_y == 0 {
            last_y = e.1.signum();
        }
    }
    let mut before = match edges.last() {
        Some(e) => *e,
        None => return 0,
    };
    for &e in &edges {
        // Differences below 2^28 inside the guard band: products below 2^57.
        let cross = before.0 * e.1 - before.1 * e.0;
        let dot = before.0 * e.0 + before.1 * e.1;
        before = e;
        if cross == 0 {
            if dot < 0 {
                return 0;
            }
        } else {
            let c = if cross > 0 { 1 } else { -1 };
            if sense == 0 {
                sense = c;
            } else if sense != c {
                return 0;
            }
        }
        if e.0 != 0 {
            x_changes += u32::from(e.0.signum() != last_x);
            last_x = e.0.signum();
        }
        if e.1 != 0 {
            y_changes += u32::from(e.1.signum() != last_y);
            last_y = e.1.signum();
        }
    }
    if x_changes > 2 || y_changes > 2 {
        return 0;
    }
    sense
}

/// Whether every point of `points` (half sub-pixel units) lies strictly outside one
/// edge of the convex polygon `poly` of orientation `sense`: then the polygon covers
/// no point in their convex hull (a covered point lies in the closed polygon).
pub(crate) fn outside_an_edge(poly: &[ScreenVertex], sense: i8, points: &[(i64, i64)]) -> bool {
    let mut prev = match poly.last() {
        Some(v) => v,
        None => return true,
    };
    for v in poly {
        let (ax, ay) = (2 * i64::from(prev.x), 2 * i64::from(prev.y));
        let (ex, ey) = (2 * i64::from(v.x) - ax, 2 * i64::from(v.y) - ay);
        prev = v;
        if (ex, ey) == (0, 0) {
            continue;
        }
        // Half-unit coordinates below 2^28 (guard band and centres of the frame):
        // differences below 2^29, products below 2^59.
        let out = points.iter().all(|&(px, py)| {
            let cross = ex * (py - ay) - ey * (px - ax);
            (sense > 0 && cross < 0) || (sense < 0 && cross > 0)
        });
        if out {
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(points: &[(i32, i32)]) -> std::vec::Vec<ScreenVertex> {
        points
            .iter()
            .map(|&(x, y)| ScreenVertex { x, y, q: 0 })
            .collect()
    }

    extern crate std;

    #[test]
    fn convexity_rejects_dents_stars_and_spikes() {
        assert_ne!(convex_orientation::<8>(&poly(&[(0, 0), (4, 0), (0, 4)])), 0);
        assert_ne!(
            convex_orientation::<8>(&poly(&[(0, 0), (2, 0), (4, 0), (4, 4), (0, 4)])),
            0,
            "collinear vertices are still convex"
        );
        // Both senses.
        let a = convex_orientation::<8>(&poly(&[(0, 0), (4, 0), (4, 4), (0, 4)]));
        let b = convex_orientation::<8>(&poly(&[(0, 4), (4, 4), (4, 0), (0, 0)]));
        assert_eq!(a, -b);
        // A dent.
        assert_eq!(
            convex_orientation::<8>(&poly(&[(0, 0), (4, 0), (2, 1), (4, 4), (0, 4)])),
            0
        );
        // A pentagram: every turn the same way, wound twice.
        let star = [(10, 0), (16, 19), (0, 7), (20, 7), (4, 19)];
        assert_eq!(convex_orientation::<8>(&poly(&star)), 0);
        // A spike back along an edge.
        assert_eq!(
            convex_orientation::<8>(&poly(&[(0, 0), (4, 0), (8, 0), (4, 0), (0, 4)])),
            0
        );
        // No area.
        assert_eq!(convex_orientation::<8>(&poly(&[(0, 0), (4, 0), (8, 0)])), 0);
    }

    #[test]
    fn pixel_boxes_hold_exactly_the_centres_in_the_closed_box() {
        // S = 0: the square [1, 3]^2 has centres 1.5 and 2.5 inside.
        let b = PixelBox::of(&poly(&[(1, 1), (3, 1), (3, 3), (1, 3)]), 0, 10, 10).unwrap();
        assert_eq!((b.x0, b.x1, b.y0, b.y1), (1, 2, 1, 2));
        // S = 1: [0.5, 2.5] px reaches centres 0.5, 1.5 and 2.5.
        let b = PixelBox::of(&poly(&[(1, 1), (5, 1), (5, 5), (1, 5)]), 1, 10, 10).unwrap();
        assert_eq!((b.x0, b.x1, b.y0, b.y1), (0, 2, 0, 2));
        // S = 2: [0.25, 0.5] px reaches the centre 0.5 on its closed side.
        let b = PixelBox::of(&poly(&[(1, 1), (2, 1), (2, 2)]), 2, 10, 10).unwrap();
        assert_eq!((b.x0, b.x1, b.y0, b.y1), (0, 0, 0, 0));
        // S = 3: [0.25, 0.375] px lies between two centres: nothing.
        assert!(PixelBox::of(&poly(&[(2, 2), (3, 2), (3, 3)]), 3, 10, 10).is_none());
        // Off the frame.
        assert!(PixelBox::of(&poly(&[(-9, -9), (-5, -9), (-5, -5)]), 0, 10, 10).is_none());
    }
}
