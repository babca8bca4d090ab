//! The independent f64 reference scan converter: the judge of every rasterizer test.
//!
//! It decides coverage of pixel centres by the rule of `CONVENTIONS.md`, from
//! exact edge tests only (no scanline DDA, no division):
//!
//! A pixel centre `P = (px, py)` is covered iff the point `P' = P + (e, e^2)`, for an
//! infinitesimal `e > 0`, is inside the polygon (even-odd, or non-zero winding).
//! `P'` never lies on a line through `P`, so it is never on the boundary, and the
//! crossings of the leftward horizontal ray from `P'` with the edges are counted:
//!
//! * A horizontal edge (`a.y == b.y`) is never crossed (the ray is at `py + e^2`).
//! * An edge with `lo.y < hi.y` (its end points sorted by y) is crossed iff
//!   `lo.y < py + e^2 < hi.y`, i.e. iff `lo.y <= py < hi.y` (half-open).
//! * The crossing is left of `P'` iff `x_edge(py + e^2) < px + e`. With
//!   `d = hi - lo` (`d.y > 0`) and `c(P) = d.x (py - lo.y) - d.y (px - lo.x)` we have
//!   `x_edge(y) - x = c / d.y`, and `c(P') = c(P) - d.y e + d.x e^2`, whose sign is
//!   `sign(c(P))` when `c(P) != 0` and negative when `c(P) == 0`. So the crossing is
//!   left of `P'` iff `c(P) <= 0`: only the exact sign of one 2x2 determinant is needed.
//! * Winding: an edge crossed going down (`a.y < b.y`) counts +1, going up -1.
//!
//! ## Exactness of the f64 evaluation
//! If every coordinate involved (vertices and pixel centres) is an integer multiple of
//! `2^-T` with magnitude `<= 2^M` and `M + T <= 25`, then the differences are integers
//! (in units of `2^-T`) of at most `2^(M+T+1) <= 2^26`, their products are integers of at
//! most `2^52`, so both products are exact in f64 and the rounded difference of two exact
//! values has the exact sign. Pixel centres need `T >= 1`. Examples: vertices snapped to
//! `1/2^8` with `|v| <= 2^17` px, or snapped to `1/2^4` with `|v| <= 2^21` px.
//! Outside that range (unsnapped f64 input, huge coordinates) the determinant is
//! evaluated exactly in integer arithmetic (i128, and 256-bit products when needed).
//! The range check is done once per polygon (see [`Polygon`]).

use std::cmp::Ordering;

/// A point `(x, y)` in pixels.
pub type Point = (f64, f64);

/// Fill rule of the reference (independent of the library's `FillRule`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Rule {
    /// Odd number of crossings to the left.
    EvenOdd,
    /// Non-zero signed crossing count (winding number).
    NonZero,
}

impl Rule {
    /// Both rules, for loops in tests.
    pub const ALL: [Rule; 2] = [Rule::EvenOdd, Rule::NonZero];

    /// Whether a point with this winding number (signed crossing count) is inside.
    pub fn inside(self, winding: i32) -> bool {
        match self {
            Rule::EvenOdd => winding & 1 != 0,
            Rule::NonZero => winding != 0,
        }
    }
}

/// The largest `M + T` for which plain f64 evaluation is exact (see module docs).
const EXACT_BITS: i32 = 25;

/// Whether all `values` are multiples of `2^-T` (some `T >= 1`) with magnitude `<= 2^M`
/// and `M + T <= EXACT_BITS`, so that the f64 determinant is exact (see module docs).
fn fast_path_is_exact(values: impl Iterator<Item = f64>) -> bool {
    let mut max_abs = 1.0f64;
    let mut t = 1i32;
    for v in values {
        if !v.is_finite() {
            return false;
        }
        max_abs = max_abs.max(v.abs());
        // Raise t until v * 2^t is an integer (multiplying by a power of two is exact).
        while t <= EXACT_BITS && (v * pow2(t)).fract() != 0.0 {
            t += 1;
        }
        if t > EXACT_BITS {
            return false;
        }
    }
    let m = max_abs.log2().ceil() as i32;
    // log2 of a power of two is exact, so `m` is the least M with max_abs <= 2^M.
    m + t <= EXACT_BITS
}

fn pow2(t: i32) -> f64 {
    f64::from_bits(((1023 + t) as u64) << 52)
}

/// The sign of `c = (b.x - a.x)(p.y - a.y) - (b.y - a.y)(p.x - a.x)`, evaluated
/// exactly: in f64 when `fast` (caller guarantees the range), else in integers.
pub fn det_sign(fast: bool, a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> Ordering {
    if fast {
        let c = (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
        c.partial_cmp(&0.0).expect("finite")
    } else {
        exact::det_sign(a, b, p)
    }
}

/// A polygon prepared for reference queries: its edges, and whether the f64 fast path
/// is exact for all pixel centres of a `width x height` frame.
#[derive(Clone, Debug)]
pub struct Polygon {
    pts: Vec<(f64, f64)>,
    fast: bool,
}

impl Polygon {
    /// Prepares `pts` for queries at pixel centres within `[0, extent]^2`.
    pub fn new(pts: &[(f64, f64)], extent: f64) -> Self {
        assert!(
            pts.iter().all(|p| p.0.is_finite() && p.1.is_finite()),
            "reference: non-finite vertex"
        );
        let fast = fast_path_is_exact(pts.iter().flat_map(|p| [p.0, p.1]).chain([extent, 0.5]));
        Polygon {
            pts: pts.to_vec(),
            fast,
        }
    }

    /// Whether the exact-f64 fast path is in use (for documentation in tests).
    pub fn uses_fast_path(&self) -> bool {
        self.fast
    }

    /// The same polygon evaluated with integer arithmetic only (to cross-check the paths).
    pub fn with_integer_arithmetic(mut self) -> Self {
        self.fast = false;
        self
    }

    /// The edges `(a, b)` in order, closing edge included.
    fn edges(&self) -> impl Iterator<Item = ((f64, f64), (f64, f64))> + '_ {
        let n = self.pts.len();
        (0..n).map(move |i| (self.pts[i], self.pts[(i + 1) % n]))
    }

    /// Signed number of crossings left of `P' = (px + e, py + e^2)`: the winding number
    /// (+1 per downward edge, -1 per upward edge).
    pub fn winding(&self, px: f64, py: f64) -> i32 {
        let mut w = 0;
        for (a, b) in self.edges() {
            if let Some((lo, hi, dir)) = spans_row(a, b, py) {
                if det_sign(self.fast, lo, hi, (px, py)) != Ordering::Greater {
                    w += dir;
                }
            }
        }
        w
    }

    /// Coverage of one point (a pixel centre) under `rule`.
    pub fn covered(&self, rule: Rule, px: f64, py: f64) -> bool {
        rule.inside(self.winding(px, py))
    }

    /// Winding numbers of all pixel centres of a `width x height` frame, row-major.
    ///
    /// Row-wise, but decided by the same exact test as [`Polygon::winding`]: for each edge
    /// spanning the row, "`c(P) <= 0`" is monotone in `px` (c decreases as px grows), so a
    /// binary search with the exact test finds the first pixel from which on the edge
    /// counts; a difference array accumulates the signed counts.
    pub fn winding_map(&self, width: u32, height: u32) -> Vec<i32> {
        let (w, h) = (width as usize, height as usize);
        let mut out = vec![0i32; w * h];
        let mut diff = vec![0i32; w + 1];
        for j in 0..h {
            let py = j as f64 + 0.5;
            diff.iter_mut().for_each(|d| *d = 0);
            for (a, b) in self.edges() {
                if let Some((lo, hi, dir)) = spans_row(a, b, py) {
                    let counts = |i: usize| {
                        det_sign(self.fast, lo, hi, (i as f64 + 0.5, py)) != Ordering::Greater
                    };
                    // First i in [0, w] with counts(i) (w if none).
                    let (mut l, mut r) = (0usize, w);
                    while l < r {
                        let mid = (l + r) / 2;
                        if counts(mid) {
                            r = mid;
                        } else {
                            l = mid + 1;
                        }
                    }
                    diff[l] += dir;
                }
            }
            let mut acc = 0;
            for i in 0..w {
                acc += diff[i];
                out[j * w + i] = acc;
            }
        }
        out
    }

    /// Coverage of all pixel centres of a `width x height` frame, row-major.
    pub fn rasterize(&self, rule: Rule, width: u32, height: u32) -> Vec<bool> {
        self.winding_map(width, height)
            .into_iter()
            .map(|w| rule.inside(w))
            .collect()
    }
}

/// For an edge `a -> b` and a row at `py`: `Some((lo, hi, dir))` if the perturbed ray
/// at `py + e^2` crosses it (`lo.y <= py < hi.y`), with `dir` = +1 going down, -1 up.
fn spans_row(a: Point, b: Point, py: f64) -> Option<(Point, Point, i32)> {
    let (lo, hi, dir) = match a.1.partial_cmp(&b.1)? {
        Ordering::Less => (a, b, 1),
        Ordering::Greater => (b, a, -1),
        Ordering::Equal => return None,
    };
    (lo.1 <= py && py < hi.1).then_some((lo, hi, dir))
}

/// Whether the point `(px, py)` (a pixel centre) is covered by `poly` under `rule`.
pub fn covered(poly: &[(f64, f64)], rule: Rule, px: f64, py: f64) -> bool {
    Polygon::new(poly, px.abs().max(py.abs())).covered(rule, px, py)
}

/// Coverage of every pixel centre of a `width x height` frame, row-major
/// (`index = y * width + x`).
pub fn rasterize(poly: &[(f64, f64)], rule: Rule, width: u32, height: u32) -> Vec<bool> {
    Polygon::new(poly, f64::from(width.max(height))).rasterize(rule, width, height)
}

/// Winding numbers of every pixel centre of a `width x height` frame, row-major.
pub fn winding_map(poly: &[(f64, f64)], width: u32, height: u32) -> Vec<i32> {
    Polygon::new(poly, f64::from(width.max(height))).winding_map(width, height)
}

/// Euclidean distance from `p` to the segment `a b` (f64, approximate; for error bounds).
pub fn distance_to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (qx, qy) = (a.0 + t * dx, a.1 + t * dy);
    ((p.0 - qx).powi(2) + (p.1 - qy).powi(2)).sqrt()
}

/// Distance from `p` to the nearest edge of the closed polygon `poly`.
pub fn distance_to_boundary(poly: &[(f64, f64)], p: (f64, f64)) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| distance_to_segment(p, poly[i], poly[(i + 1) % n]))
        .fold(f64::INFINITY, f64::min)
}

/// Exact determinant sign for arbitrary finite f64 input (integer arithmetic).
pub mod exact {
    use std::cmp::Ordering;

    /// `v = m * 2^e` exactly, `m` odd (or zero).
    fn decompose(v: f64) -> (i64, i32) {
        assert!(v.is_finite(), "reference: non-finite coordinate");
        if v == 0.0 {
            return (0, 0);
        }
        let bits = v.to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i32;
        let frac = (bits & ((1u64 << 52) - 1)) as i64;
        let (mut m, mut e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1i64 << 52), exp - 1075)
        };
        let tz = m.trailing_zeros();
        m >>= tz;
        e += tz as i32;
        (if bits >> 63 == 1 { -m } else { m }, e)
    }

    /// Sign of `(b.x - a.x)(p.y - a.y) - (b.y - a.y)(p.x - a.x)`, exactly.
    pub fn det_sign(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> Ordering {
        let vals = [a.0, a.1, b.0, b.1, p.0, p.1].map(decompose);
        let emin = vals
            .iter()
            .filter(|v| v.0 != 0)
            .map(|v| v.1)
            .min()
            .unwrap_or(0);
        // Each value as an integer in units of 2^emin; must fit in 125 bits so that
        // differences fit in i128.
        let scaled = vals.map(|(m, e)| {
            let shift = (e - emin) as u32;
            let bits = 64 - m.unsigned_abs().leading_zeros();
            assert!(
                m == 0 || bits + shift <= 125,
                "reference: coordinate range too wide for exact path"
            );
            i128::from(m) << shift
        });
        let [ax, ay, bx, by, px, py] = scaled;
        sign_of_product_difference(bx - ax, py - ay, by - ay, px - ax)
    }

    /// Sign of `p*q - r*s` for `|p|, |q|, |r|, |s| < 2^126`, exactly.
    pub fn sign_of_product_difference(p: i128, q: i128, r: i128, s: i128) -> Ordering {
        if let (Some(x), Some(y)) = (p.checked_mul(q), r.checked_mul(s)) {
            if let Some(d) = x.checked_sub(y) {
                return d.cmp(&0);
            }
        }
        let lhs = (
            p.signum() * q.signum(),
            mul_u128(p.unsigned_abs(), q.unsigned_abs()),
        );
        let rhs = (
            r.signum() * s.signum(),
            mul_u128(r.unsigned_abs(), s.unsigned_abs()),
        );
        compare_signed(lhs, rhs)
    }

    /// Compares `s1 * m1` with `s2 * m2` (signs in {-1, 0, 1}, magnitudes as (hi, lo)).
    fn compare_signed(l: (i128, (u128, u128)), r: (i128, (u128, u128))) -> Ordering {
        let (sl, ml) = (if l.1 == (0, 0) { 0 } else { l.0 }, l.1);
        let (sr, mr) = (if r.1 == (0, 0) { 0 } else { r.0 }, r.1);
        match sl.cmp(&sr) {
            Ordering::Equal => match sl {
                0 => Ordering::Equal,
                1 => ml.cmp(&mr),
                _ => mr.cmp(&ml),
            },
            o => o,
        }
    }

    /// Full 256-bit product `a * b` as `(hi, lo)`.
    pub fn mul_u128(a: u128, b: u128) -> (u128, u128) {
        let mask = u128::from(u64::MAX);
        let (a1, a0) = (a >> 64, a & mask);
        let (b1, b0) = (b >> 64, b & mask);
        let p00 = a0 * b0;
        let p01 = a0 * b1;
        let p10 = a1 * b0;
        let p11 = a1 * b1;
        // middle column: high half of p00 plus low halves of p01 and p10 (< 3 * 2^64)
        let mid = (p00 >> 64) + (p01 & mask) + (p10 & mask);
        let lo = (p00 & mask) | (mid << 64);
        let hi = p11 + (p01 >> 64) + (p10 >> 64) + (mid >> 64);
        (hi, lo)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mul_u128_matches_known_products() {
        let m = u128::MAX;
        // (2^128 - 1)^2 = 2^256 - 2^129 + 1
        assert_eq!(exact::mul_u128(m, m), (m - 1, 1));
        assert_eq!(exact::mul_u128(1 << 64, 1 << 64), (1, 0));
        assert_eq!(exact::mul_u128(12345, 67890), (0, 12345 * 67890));
        let a = (1u128 << 100) + 3;
        // (2^100 + 3)^2 = 2^200 + 6 * 2^100 + 9
        assert_eq!(exact::mul_u128(a, a), (1 << 72, (6u128 << 100) + 9));
    }

    #[test]
    fn wide_products_compare_exactly() {
        let t = 1i128 << 100;
        // t*t - (t+1)(t-1) = 1
        assert_eq!(
            exact::sign_of_product_difference(t, t, t + 1, t - 1),
            Ordering::Greater
        );
        assert_eq!(
            exact::sign_of_product_difference(t + 1, t - 1, t, t),
            Ordering::Less
        );
        assert_eq!(
            exact::sign_of_product_difference(-t, t, t, -t),
            Ordering::Equal
        );
        assert_eq!(
            exact::sign_of_product_difference(-t, t, -t - 1, t - 1),
            Ordering::Less
        );
        assert_eq!(
            exact::sign_of_product_difference(0, t, -t, t),
            Ordering::Greater
        );
    }

    #[test]
    fn exact_and_fast_paths_agree_on_snapped_values() {
        let mut state = 0x1234_5678_9abc_def0u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 33) as i64 % 2048 - 1024) as f64 / 16.0
        };
        for _ in 0..100_000 {
            let (a, b, p) = ((next(), next()), (next(), next()), (next(), next()));
            assert_eq!(
                det_sign(true, a, b, p),
                exact::det_sign(a, b, p),
                "{a:?} {b:?} {p:?}"
            );
        }
    }

    #[test]
    fn exact_path_sees_differences_f64_would_round_away() {
        // c = (2^30)(2^-30) - (1 + 2^-52)*1 ... a case where naive f64 loses the sign:
        let a = (0.0, 0.0);
        let b = (1.0 + f64::EPSILON, 1.0);
        let p = (1.0, 1.0 - f64::EPSILON / 2.0);
        // c = b.x * p.y - b.y * p.x = (1+eps)(1-eps/2) - 1 = eps/2 - eps^2/2 > 0
        assert_eq!(exact::det_sign(a, b, p), Ordering::Greater);
        // huge coordinates with fractional pixel centres
        let a = (-(2f64.powi(40)), 0.5);
        let b = (2f64.powi(40), 1.5);
        // the line passes x = 0 at y = 1.0; the point (0.5, 1.0) is right of it (downward edge)
        assert_eq!(exact::det_sign(a, b, (0.5, 1.0)), Ordering::Less);
        assert_eq!(exact::det_sign(a, b, (0.0, 1.0)), Ordering::Equal);
        assert_eq!(exact::det_sign(a, b, (-0.5, 1.0)), Ordering::Greater);
    }

    #[test]
    fn fast_path_range_check() {
        assert!(Polygon::new(&[(0.0, 0.0), (100.25, 3.0), (5.0, 7.5)], 64.0).uses_fast_path());
        assert!(!Polygon::new(&[(0.0, 0.0), (0.1, 3.0), (5.0, 7.5)], 64.0).uses_fast_path());
        assert!(!Polygon::new(
            &[(0.0, 0.0), (2f64.powi(22), 3.0), (5.0, 7.5 + 1.0 / 256.0)],
            64.0
        )
        .uses_fast_path());
        assert!(Polygon::new(
            &[(0.0, 0.0), (2f64.powi(17), 3.0), (5.0, 7.5 + 1.0 / 256.0)],
            64.0
        )
        .uses_fast_path());
    }

    /// The unit square with corners on pixel centres (1.5, 1.5)..(2.5, 2.5) covers only
    /// pixel (1, 1): left and top edges are in, right and bottom edges out.
    #[test]
    fn unit_square_on_pixel_centres_covers_its_top_left_pixel() {
        let sq = [(1.5, 1.5), (2.5, 1.5), (2.5, 2.5), (1.5, 2.5)];
        for rule in Rule::ALL {
            let img = rasterize(&sq, rule, 5, 5);
            let on: Vec<usize> = (0..25).filter(|&i| img[i]).collect();
            assert_eq!(on, vec![5 + 1]);
            // both orientations
            let mut rev = sq;
            rev.reverse();
            assert_eq!(rasterize(&rev, rule, 5, 5), img);
        }
    }

    #[test]
    fn quad_split_on_diagonal_draws_each_pixel_once() {
        // 5x5 pixel centres square from (0.5,0.5) to (4.5,4.5), split on the diagonal.
        let a = [(0.5, 0.5), (4.5, 0.5), (4.5, 4.5)];
        let b = [(0.5, 0.5), (4.5, 4.5), (0.5, 4.5)];
        let ra = rasterize(&a, Rule::EvenOdd, 5, 5);
        let rb = rasterize(&b, Rule::EvenOdd, 5, 5);
        let quad = rasterize(
            &[(0.5, 0.5), (4.5, 0.5), (4.5, 4.5), (0.5, 4.5)],
            Rule::EvenOdd,
            5,
            5,
        );
        for i in 0..25 {
            assert!(!(ra[i] && rb[i]), "pixel {i} drawn twice");
            assert_eq!(ra[i] || rb[i], quad[i]);
        }
        // The quad covers x in 0..4, y in 0..4 = 16 pixels; the upper-right triangle (with the
        // diagonal, which is its left edge) gets 4+3+2+1 = 10, the lower-left 3+2+1 = 6.
        assert_eq!(quad.iter().filter(|&&c| c).count(), 16);
        assert_eq!(ra.iter().filter(|&&c| c).count(), 10);
        assert_eq!(rb.iter().filter(|&&c| c).count(), 6);
    }

    #[test]
    fn pentagram_has_a_hole_under_even_odd_only() {
        let pts: Vec<(f64, f64)> = (0..5)
            .map(|k| {
                let t = std::f64::consts::PI * (0.5 + 0.8 * k as f64);
                (
                    (16.0 + 14.0 * t.cos()).round(),
                    (16.0 - 14.0 * t.sin()).round(),
                )
            })
            .collect();
        assert!(!covered(&pts, Rule::EvenOdd, 16.5, 16.5));
        assert!(covered(&pts, Rule::NonZero, 16.5, 16.5));
        assert_eq!(winding_map(&pts, 32, 32)[16 * 32 + 16].abs(), 2);
    }

    #[test]
    fn degenerate_polygons_cover_nothing() {
        let line = [(0.5, 0.5), (3.5, 3.5), (2.5, 2.5), (6.5, 6.5)];
        let point = [(2.5, 2.5); 3];
        for rule in Rule::ALL {
            assert!(rasterize(&line, rule, 8, 8).iter().all(|&c| !c));
            assert!(rasterize(&point, rule, 8, 8).iter().all(|&c| !c));
        }
    }

    #[test]
    fn integer_path_agrees_with_f64_where_f64_is_clearly_right() {
        // Unsnapped values: whenever the f64 determinant is far from zero relative to its
        // rounding error, the exact sign must agree with it.
        let mut state = 7u64;
        let mut unit = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut checked = 0;
        for _ in 0..200_000 {
            let mut v = || 100.0 * unit() - 20.0;
            let (a, b, p) = ((v(), v()), (v(), v()), (v(), v()));
            let (l, r) = ((b.0 - a.0) * (p.1 - a.1), (b.1 - a.1) * (p.0 - a.0));
            if (l - r).abs() > 1e-9 * (l.abs() + r.abs()) {
                assert_eq!(exact::det_sign(a, b, p), (l - r).partial_cmp(&0.0).unwrap());
                checked += 1;
            }
        }
        assert!(checked > 190_000);
    }

    #[test]
    fn integer_path_rasterizes_like_the_f64_path_on_snapped_polygons() {
        let pts = [
            (0.5, 0.5),
            (30.25, 3.5),
            (12.0, 29.5),
            (2.5, 17.0),
            (20.5, 9.75),
        ];
        let fast = Polygon::new(&pts, 32.0);
        assert!(fast.uses_fast_path());
        let slow = fast.clone().with_integer_arithmetic();
        assert_eq!(fast.winding_map(32, 32), slow.winding_map(32, 32));
    }

    #[test]
    fn row_wise_map_agrees_with_point_queries() {
        let mut state = 42u64;
        let mut next = |k: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % k
        };
        for _ in 0..500 {
            let n = 3 + next(6) as usize;
            let s = [1.0, 2.0, 16.0][next(3) as usize];
            let pts: Vec<(f64, f64)> = (0..n)
                .map(|_| {
                    (
                        (next(24 * s as u64) as f64) / s - 2.0,
                        (next(24 * s as u64) as f64) / s - 2.0,
                    )
                })
                .collect();
            let poly = Polygon::new(&pts, 20.0);
            let map = poly.winding_map(20, 20);
            for j in 0..20 {
                for i in 0..20 {
                    assert_eq!(
                        map[j * 20 + i],
                        poly.winding(i as f64 + 0.5, j as f64 + 0.5),
                        "{pts:?} {i} {j}"
                    );
                }
            }
        }
    }
}
