//! Fixed, deterministic scenes for the `render` command and the `bench` harness.
//!
//! Everything here is generated from fixed seeds by [`Rng`] (the SplitMix64 of
//! [`crate::random`], which the tests' random scenes use too), so the scenes are the same
//! on every machine and in every run (no `rand` dependency).
//!
//! * [`test_scene`]: the polygon test scene on 400 x 240 (triangles of 1 to 200 px, a
//!   concave comb, a self-intersecting star drawn with both fill rules, thin needles, a
//!   fan, polygons clipped by the viewport and one reaching far beyond the guard band).
//! * [`bench_triangles`]: the fixed benchmark set of triangles on 400 x 240 with integer
//!   pixel-centre vertices (so that embedded-graphics can draw the same triangles).
//! * [`sized_triangles`]: triangles of one size, for the scaling table.
//! * [`large_polygons`]: a few large polygons, where the XOR fill is expected to shine.
//!
//! Fractional vertices are multiples of 1/16, so that snapping to the 1/2^S grid for any
//! S >= 4 changes nothing.

use fixed::types::extra::LeEqU32;
use pbuffer::{FillRule, ScreenPoint};

use crate::random::Rng;

/// Width of all scenes, in pixels.
pub const WIDTH: usize = 400;
/// Height of all scenes, in pixels.
pub const HEIGHT: usize = 240;

/// Rounds to the nearest multiple of 1/16.
pub fn q16(v: f64) -> f64 {
    (v * 16.0).round() / 16.0
}

/// One polygon of a scene: vertices in pixel units (pixel (i, j) covers
/// [i, i+1) x [j, j+1), centre at (i + 0.5, j + 0.5)), a fill rule and a colour.
#[derive(Clone, Debug)]
pub struct ScenePolygon {
    /// What kind of test this polygon is ("triangle", "star", ...), for the report.
    pub kind: &'static str,
    /// Vertices, all multiples of 1/16.
    pub points: Vec<(f64, f64)>,
    /// Fill rule the polygon is meant to be drawn with.
    pub rule: FillRule,
    /// `true`: draw with `BinaryColor::On`; `false`: draw with `Off` (cuts a hole into
    /// what was drawn before it).
    pub on: bool,
}

impl ScenePolygon {
    fn new(kind: &'static str, points: Vec<(f64, f64)>, rule: FillRule, on: bool) -> Self {
        let points = points.into_iter().map(|(x, y)| (q16(x), q16(y))).collect();
        Self {
            kind,
            points,
            rule,
            on,
        }
    }
}

/// Converts pixel-unit vertices to fixed-point screen points with `Frac` fractional bits.
///
/// Panics if a vertex does not fit the fixed-point type (scene vertices always fit).
pub fn to_screen<Frac: LeEqU32>(points: &[(f64, f64)]) -> Vec<ScreenPoint<Frac>> {
    points
        .iter()
        .map(|&(x, y)| {
            ScreenPoint::<Frac>::from_f64(x, y)
                .unwrap_or_else(|e| panic!("vertex ({x}, {y}) does not fit: {e:?}"))
        })
        .collect()
}

/// Regular star polygon {n/k} (self-intersecting for k > 1), first vertex straight up.
pub fn star(cx: f64, cy: f64, r: f64, n: usize, k: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * ((i * k) % n) as f64 / n as f64;
            (cx + r * a.sin(), cy - r * a.cos())
        })
        .collect()
}

/// Regular n-gon, or a spiky star when `r_inner` differs from `r` (2n vertices then).
pub fn spiky(cx: f64, cy: f64, r: f64, r_inner: f64, n: usize) -> Vec<(f64, f64)> {
    let m = if r_inner == r { n } else { 2 * n };
    (0..m)
        .map(|i| {
            let rr = if i % 2 == 1 && m != n { r_inner } else { r };
            let a = std::f64::consts::TAU * i as f64 / m as f64;
            (cx + rr * a.sin(), cy - rr * a.cos())
        })
        .collect()
}

/// A comb: a bar along the top with `teeth` teeth hanging down, spanning [x0, x1] x [y0, y1].
pub fn comb(x0: f64, y0: f64, x1: f64, y1: f64, teeth: usize, bar: f64) -> Vec<(f64, f64)> {
    let pitch = (x1 - x0) / (2 * teeth - 1) as f64;
    let mut p = vec![(x0, y0), (x1, y0)];
    // Walk back along the bottom from right to left, tooth by tooth.
    for t in (0..teeth).rev() {
        let tx1 = x0 + (2 * t + 1) as f64 * pitch;
        let tx0 = x0 + (2 * t) as f64 * pitch;
        p.push((tx1, y1));
        p.push((tx0, y1));
        if t > 0 {
            p.push((tx0, y0 + bar));
            p.push((tx0 - pitch, y0 + bar));
        }
    }
    p
}

/// The polygon test scene on [`WIDTH`] x [`HEIGHT`]. Polygons are drawn in order; the
/// order matters because some polygons are drawn in the background colour.
pub fn test_scene() -> Vec<ScenePolygon> {
    let mut s = Vec::new();
    let mut rng = Rng::new(0x5EED_0001);

    // Left half: 40 random triangles, sizes log-uniform in 1..200 px, drawn largest first;
    // every third one in the background colour so that it cuts into the larger ones.
    let mut tris: Vec<(f64, Vec<(f64, f64)>)> = (0..40)
        .map(|_| {
            let size = (200f64.ln() * rng.unit()).exp();
            let (cx, cy) = (rng.range(0.0, 200.0), rng.range(0.0, 240.0));
            let mut p: Vec<(f64, f64)> = (0..3)
                .map(|_| {
                    let a = rng.range(0.0, std::f64::consts::TAU);
                    (cx + 0.5 * size * a.cos(), cy + 0.5 * size * a.sin())
                })
                .collect();
            // Keep the left half to itself (x < 200); edges of the frame may clip it.
            let max_x = p.iter().map(|q| q.0).fold(f64::MIN, f64::max);
            if max_x > 199.5 {
                p.iter_mut().for_each(|q| q.0 -= max_x - 199.5);
            }
            (size, p)
        })
        .collect();
    tris.sort_by(|a, b| b.0.total_cmp(&a.0));
    for (i, (_, p)) in tris.into_iter().enumerate() {
        s.push(ScenePolygon::new(
            "triangle",
            p,
            FillRule::EvenOdd,
            i % 3 != 2,
        ));
    }

    // A concave comb (4 teeth), with one slanted side.
    let mut c = comb(206.25, 10.5, 270.75, 98.25, 4, 22.0);
    c[1].0 += 6.0; // slant the right end of the bar
    s.push(ScenePolygon::new(
        "concave comb",
        c,
        FillRule::EvenOdd,
        true,
    ));

    // Self-intersecting pentagram {5/2}: even-odd leaves the centre empty, non-zero fills it.
    s.push(ScenePolygon::new(
        "star even-odd",
        star(340.3, 62.2, 50.0, 5, 2),
        FillRule::EvenOdd,
        true,
    ));
    s.push(ScenePolygon::new(
        "star non-zero",
        star(340.3, 178.7, 50.0, 5, 2),
        FillRule::NonZero,
        true,
    ));

    // Row of tiny triangles, 1 to 12 px, with fractional vertices.
    let mut x = 206.3;
    for size in [1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 6.0, 8.0, 12.0] {
        let p = vec![
            (x, 118.0 + size),
            (x + size * 0.5, 118.1),
            (x + size, 118.0 + size * 0.8),
        ];
        s.push(ScenePolygon::new(
            "tiny triangle",
            p,
            FillRule::EvenOdd,
            true,
        ));
        x += size + 3.0;
    }

    // A fan of 16 triangles around one centre, alternately on and off (a pinwheel).
    let (fx, fy, fr) = (240.4, 180.3, 44.0);
    for i in 0..16 {
        let a0 = std::f64::consts::TAU * i as f64 / 16.0;
        let a1 = std::f64::consts::TAU * (i + 1) as f64 / 16.0;
        let p = vec![
            (fx, fy),
            (fx + fr * a0.cos(), fy + fr * a0.sin()),
            (fx + fr * a1.cos(), fy + fr * a1.sin()),
        ];
        s.push(ScenePolygon::new(
            "fan triangle",
            p,
            FillRule::EvenOdd,
            i % 2 == 0,
        ));
    }

    // Thin needles: one nearly vertical, one nearly horizontal, a fraction of a pixel wide.
    s.push(ScenePolygon::new(
        "needle",
        vec![(288.5, 8.0), (291.25, 228.0), (292.0, 227.5)],
        FillRule::EvenOdd,
        true,
    ));
    s.push(ScenePolygon::new(
        "needle",
        vec![(201.0, 238.0), (398.0, 230.5), (398.0, 230.9375)],
        FillRule::EvenOdd,
        true,
    ));

    // Clipped by the viewport: across the left edge, across the top-right corner.
    s.push(ScenePolygon::new(
        "clipped",
        vec![(-30.0, 200.0), (25.5, 236.0), (-10.0, 250.0)],
        FillRule::EvenOdd,
        true,
    ));
    s.push(ScenePolygon::new(
        "clipped",
        vec![(296.0, -15.0), (330.0, 2.0), (312.0, 11.5)],
        FillRule::EvenOdd,
        true,
    ));
    // Far beyond the guard band (16384 px): a corner of it fills the top-right corner of
    // the frame (x > ~378, y < ~14), with a slanted left edge and a nearly flat bottom.
    s.push(ScenePolygon::new(
        "beyond guard band",
        vec![(378.5, -20000.0), (30000.0, 4.25), (377.75, 14.5)],
        FillRule::EvenOdd,
        true,
    ));
    s
}

/// A triangle with integer vertices: pixel-centre coordinates. For pbuffer the vertex
/// `(x, y)` is the point `(x + 0.5, y + 0.5)`; for embedded-graphics it is `Point(x, y)`.
pub type IntTriangle = [(i32, i32); 3];

/// Twice the signed area of an integer triangle.
pub fn area2(t: &IntTriangle) -> i64 {
    let [(ax, ay), (bx, by), (cx, cy)] = t.map(|(x, y)| (i64::from(x), i64::from(y)));
    (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
}

/// Converts an integer pixel-centre triangle to fixed-point screen points
/// (vertex (x, y) -> (x + 0.5, y + 0.5)).
pub fn int_triangle_to_screen<Frac: LeEqU32>(t: &IntTriangle) -> [ScreenPoint<Frac>; 3] {
    t.map(|(x, y)| {
        ScreenPoint::<Frac>::from_f64(f64::from(x) + 0.5, f64::from(y) + 0.5)
            .expect("integer vertex fits")
    })
}

fn random_int_triangle(rng: &mut Rng, size: f64) -> IntTriangle {
    // Vertices on a circle of diameter `size` whose centre keeps the circle on screen
    // where possible; then clamped to the screen. Zero-area triangles are redrawn.
    loop {
        let r = 0.5 * size;
        let cx = rng.range(r.min(199.5), (399.0 - r).max(199.5));
        let cy = rng.range(r.min(119.5), (239.0 - r).max(119.5));
        let t: IntTriangle = [0, 1, 2].map(|_| {
            let a = rng.range(0.0, std::f64::consts::TAU);
            (
                ((cx + r * a.cos()).round() as i32).clamp(0, WIDTH as i32 - 1),
                ((cy + r * a.sin()).round() as i32).clamp(0, HEIGHT as i32 - 1),
            )
        });
        if area2(&t) != 0 {
            return t;
        }
    }
}

/// The fixed benchmark set on 400 x 240: 300 small triangles (2-10 px), 60 medium
/// (20-60 px) and 12 large (100-240 px), shuffled by size class, all on screen, none of
/// zero area, with integer pixel-centre vertices.
pub fn bench_triangles() -> Vec<IntTriangle> {
    let mut rng = Rng::new(0xBE4C_0002);
    let mut v = Vec::new();
    for (count, lo, hi) in [(300, 2.0, 10.0), (60, 20.0, 60.0), (12, 100.0, 240.0)] {
        for _ in 0..count {
            let size = rng.range(lo, hi);
            v.push(random_int_triangle(&mut rng, size));
        }
    }
    // Interleave the classes deterministically (Fisher-Yates with the same generator).
    for i in (1..v.len()).rev() {
        let j = rng.below(i as u64 + 1) as usize;
        v.swap(i, j);
    }
    v
}

/// `count` triangles whose vertices lie on a circle of diameter `size` (<= 239 px),
/// placed at random on screen: for the scaling table.
pub fn sized_triangles(size: f64, count: usize, seed: u64) -> Vec<IntTriangle> {
    let mut rng = Rng::new(seed);
    (0..count)
        .map(|_| random_int_triangle(&mut rng, size))
        .collect()
}

/// A few large polygons covering much of the 400 x 240 screen (even-odd, fractional
/// vertices): a big triangle, a 64-gon, a 32-tooth comb, a pentagram and a 100-point star.
pub fn large_polygons() -> Vec<(&'static str, Vec<(f64, f64)>)> {
    let q = |p: Vec<(f64, f64)>| p.into_iter().map(|(x, y)| (q16(x), q16(y))).collect();
    vec![
        (
            "triangle 400x240",
            q(vec![(-0.5, 0.25), (399.75, 10.5), (120.25, 239.75)]),
        ),
        ("64-gon r=118", q(spiky(200.3, 120.2, 118.0, 118.0, 64))),
        (
            "comb, 32 teeth",
            q(comb(2.25, 2.5, 397.75, 237.5, 32, 20.0)),
        ),
        ("pentagram r=120", q(star(200.3, 126.2, 120.0, 5, 2))),
        ("star, 100 points", q(spiky(200.3, 120.2, 118.0, 70.0, 100))),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deterministic() {
        assert_eq!(bench_triangles(), bench_triangles());
        assert_eq!(format!("{:?}", test_scene()), format!("{:?}", test_scene()));
    }

    #[test]
    fn bench_set_on_screen_and_nondegenerate() {
        let t = bench_triangles();
        assert_eq!(t.len(), 372);
        for tri in &t {
            assert_ne!(area2(tri), 0);
            for &(x, y) in tri {
                assert!((0..WIDTH as i32).contains(&x) && (0..HEIGHT as i32).contains(&y));
            }
        }
    }

    #[test]
    fn comb_is_closed_and_simple_shape() {
        let c = comb(0.0, 0.0, 70.0, 50.0, 4, 10.0);
        assert_eq!(c.len(), 2 + 4 * 2 + 3 * 2);
        assert_eq!(c.last().copied(), Some((0.0, 50.0)));
    }
}
