//! Deterministic random scenes for the rasterizer tests: polygons and watertight meshes.
//!
//! Vertices are generated as raw fixed-point integers `k` (value `k / 2^S`), so the
//! library (`ScreenPoint::from_bits`) and the reference (`k as f64 / 2^S`, exact) see the
//! very same vertices. The generator is a self-contained SplitMix64, seeded explicitly:
//! host_tests' only one (`scenes` draws the polygon test scene and the benchmark
//! triangles with it too).

use std::f64::consts::TAU;

/// SplitMix64 (Steele, Lea, Flood 2014): small, fast, good enough for test scenes.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator with a fixed seed.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` with 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform integer in `0..n` (`n > 0`).
    pub fn below(&mut self, n: u64) -> u64 {
        ((u128::from(self.next_u64()) * u128::from(n)) >> 64) as u64
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// Log-uniform in `[lo, hi]` (`0 < lo <= hi`).
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }

    /// One element of a non-empty slice.
    pub fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[self.below(xs.len() as u64) as usize]
    }
}

/// Raw fixed-point value `k` nearest to `v * 2^s` (ties away from zero; only used for
/// generated geometry, whose rounding mode is irrelevant because the result is exact).
pub fn snap_raw(v: f64, s: u32) -> i32 {
    let r = (v * f64::from(1u32 << s)).round();
    assert!(
        r.abs() < 2_147_483_647.0,
        "snap_raw: {v} out of i32 range at S={s}"
    );
    r as i32
}

/// The exact f64 value of a raw fixed-point coordinate.
pub fn raw_to_f64(k: i32, s: u32) -> f64 {
    f64::from(k) / f64::from(1u32 << s)
}

/// A polygon with vertices on the `1/2^S` grid.
#[derive(Clone, Debug, PartialEq)]
pub struct RawPolygon {
    /// Sub-pixel bits.
    pub s: u32,
    /// Raw vertices (value = raw / 2^S).
    pub pts: Vec<(i32, i32)>,
}

impl RawPolygon {
    /// The exact vertex values as f64.
    pub fn to_f64(&self) -> Vec<(f64, f64)> {
        self.pts
            .iter()
            .map(|&(x, y)| (raw_to_f64(x, self.s), raw_to_f64(y, self.s)))
            .collect()
    }
}

/// Shapes of random polygons.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// Three random points.
    Triangle,
    /// Four random points (convex, concave or bowtie).
    Quad,
    /// A simple star-shaped polygon, 5..16 vertices at sorted angles, random radii.
    Concave,
    /// 4..12 random points in a box: usually self-intersecting.
    SelfIntersecting,
    /// 3..10 points of a coarse lattice (a few pixels, step 1/2 px or 1 px): repeated
    /// vertices, collinear and overlapping edges, edges through centres.
    Lattice,
}

impl Shape {
    /// All shapes.
    pub const ALL: [Shape; 5] = [
        Shape::Triangle,
        Shape::Quad,
        Shape::Concave,
        Shape::SelfIntersecting,
        Shape::Lattice,
    ];
}

/// A snapped point near `(x, y)`. With probability 1/4 the point is put on the half-pixel
/// lattice (pixel centres and pixel corners), which provokes exact ties with pixel centres.
fn point(rng: &mut Rng, s: u32, x: f64, y: f64, tie_bias: bool) -> (i32, i32) {
    if tie_bias && s >= 1 && rng.chance(0.25) {
        let (hx, hy) = ((x * 2.0).round() / 2.0, (y * 2.0).round() / 2.0);
        (snap_raw(hx, s), snap_raw(hy, s))
    } else {
        (snap_raw(x, s), snap_raw(y, s))
    }
}

/// A random polygon of `shape` on a `width x height` frame, with a size log-distributed
/// from 1 px to the full frame, centred anywhere in the frame extended by half its size
/// (so some polygons are clipped by the frame borders).
pub fn polygon(rng: &mut Rng, shape: Shape, s: u32, width: u32, height: u32) -> RawPolygon {
    let full = f64::from(width.max(height));
    let size = rng.log_uniform(1.0, full);
    let cx = rng.range(-size / 2.0, f64::from(width) + size / 2.0);
    let cy = rng.range(-size / 2.0, f64::from(height) + size / 2.0);
    let tie_bias = rng.chance(0.5);
    let random_in_box = |rng: &mut Rng| {
        let x = cx + rng.range(-0.5, 0.5) * size;
        let y = cy + rng.range(-0.5, 0.5) * size;
        point(rng, s, x, y, tie_bias)
    };
    let pts = match shape {
        Shape::Triangle => (0..3).map(|_| random_in_box(rng)).collect(),
        Shape::Quad => (0..4).map(|_| random_in_box(rng)).collect(),
        Shape::SelfIntersecting => {
            let n = 4 + rng.below(9);
            (0..n).map(|_| random_in_box(rng)).collect()
        }
        Shape::Lattice => {
            let n = 3 + rng.below(8);
            let step = if s >= 1 && rng.chance(0.5) { 0.5 } else { 1.0 };
            let cells = 1 + rng.below(6);
            let origin = ((cx - size / 2.0).floor(), (cy - size / 2.0).floor());
            (0..n)
                .map(|_| {
                    let x = origin.0 + step * rng.below(cells + 1) as f64;
                    let y = origin.1 + step * rng.below(cells + 1) as f64;
                    (snap_raw(x, s), snap_raw(y, s))
                })
                .collect()
        }
        Shape::Concave => {
            let n = 5 + rng.below(12) as usize;
            let mut angles: Vec<f64> = (0..n).map(|_| rng.range(0.0, TAU)).collect();
            angles.sort_by(f64::total_cmp);
            let reverse = rng.chance(0.5);
            let mut pts: Vec<(i32, i32)> = angles
                .iter()
                .map(|&t| {
                    let r = size / 2.0 * rng.range(0.2, 1.0);
                    point(rng, s, cx + r * t.cos(), cy + r * t.sin(), tie_bias)
                })
                .collect();
            if reverse {
                pts.reverse();
            }
            pts
        }
    };
    RawPolygon { s, pts }
}

/// A random polygon with vertices far away: 3..=8 vertices at log-distributed distances
/// from 1 px up to `max_px` around a centre inside the frame (sorted angles half of the
/// time, so that the polygon often covers the frame; random order otherwise), so that long
/// edges from far beyond the guard band cross the frame.
pub fn far_polygon(rng: &mut Rng, s: u32, width: u32, height: u32, max_px: f64) -> RawPolygon {
    let c = (
        rng.range(0.0, f64::from(width)),
        rng.range(0.0, f64::from(height)),
    );
    let n = 3 + rng.below(6) as usize;
    let mut angles: Vec<f64> = (0..n).map(|_| rng.range(0.0, TAU)).collect();
    if rng.chance(0.5) {
        angles.sort_by(f64::total_cmp);
    }
    let pts = angles
        .iter()
        .map(|&t| {
            let r = rng.log_uniform(1.0, max_px);
            let x = (c.0 + r * t.cos()).clamp(-max_px, max_px);
            let y = (c.1 + r * t.sin()).clamp(-max_px, max_px);
            point(rng, s, x, y, true)
        })
        .collect();
    RawPolygon { s, pts }
}

/// A random polygon given in full f64 precision (not snapped), for the snapping-error test.
pub fn unsnapped_polygon(rng: &mut Rng, shape: Shape, width: u32, height: u32) -> Vec<(f64, f64)> {
    // A polygon of the given shape with integer vertices, each moved by a uniform random
    // offset in [-0.5, 0.5)^2: 53-bit random fractions, never on any 1/2^S grid in practice.
    let p = polygon(rng, shape, 0, width, height);
    p.pts
        .iter()
        .map(|&(x, y)| {
            (
                f64::from(x) + rng.range(-0.5, 0.5),
                f64::from(y) + rng.range(-0.5, 0.5),
            )
        })
        .collect()
}

/// A triangle mesh on the `1/2^S` grid whose triangles all have the same (positive)
/// orientation, and its outer boundary in the same rotational sense: every point is covered
/// by exactly |winding number of the boundary| triangles.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// Sub-pixel bits.
    pub s: u32,
    /// Raw vertices.
    pub vertices: Vec<(i32, i32)>,
    /// Vertex indices of the triangles.
    pub triangles: Vec<[usize; 3]>,
    /// Vertex indices of the outer boundary, in order.
    pub boundary: Vec<usize>,
}

impl Mesh {
    /// The f64 vertices of triangle `t`.
    pub fn triangle_f64(&self, t: usize) -> [(f64, f64); 3] {
        self.triangles[t].map(|i| self.vertex_f64(i))
    }

    /// The raw vertices of triangle `t`.
    pub fn triangle_raw(&self, t: usize) -> [(i32, i32); 3] {
        self.triangles[t].map(|i| self.vertices[i])
    }

    /// One vertex as exact f64.
    pub fn vertex_f64(&self, i: usize) -> (f64, f64) {
        let (x, y) = self.vertices[i];
        (raw_to_f64(x, self.s), raw_to_f64(y, self.s))
    }

    /// The outer boundary as exact f64 polygon.
    pub fn boundary_f64(&self) -> Vec<(f64, f64)> {
        self.boundary.iter().map(|&i| self.vertex_f64(i)).collect()
    }
}

/// Twice the signed area of the raw triangle `a b c` (exact in i64; raw values < 2^31).
pub fn orientation(a: (i32, i32), b: (i32, i32), c: (i32, i32)) -> i128 {
    let (ax, ay, bx, by, cx, cy) = (
        i128::from(a.0),
        i128::from(a.1),
        i128::from(b.0),
        i128::from(b.1),
        i128::from(c.0),
        i128::from(c.1),
    );
    (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
}

/// A piglit-style triangle fan: centre `c` inside the frame, perimeter vertices stepping a
/// random 0..1 px along a circle of radius `radius` (which may exceed the frame). After
/// snapping, perimeter points that do not turn strictly forward around `c` are dropped, so
/// every triangle `(c, p_i, p_i+1)` has positive orientation and the fan winds once.
pub fn fan(rng: &mut Rng, s: u32, width: u32, height: u32, radius: f64) -> Mesh {
    assert!(radius >= 4.0, "radius must dwarf the snapping error");
    let c = (
        rng.range(0.0, f64::from(width)),
        rng.range(0.0, f64::from(height)),
    );
    let c_raw = point(rng, s, c.0, c.1, true);
    let mut vertices = vec![c_raw];
    let mut angle = rng.range(0.0, TAU);
    let end = angle + TAU;
    let centre = (raw_to_f64(c_raw.0, s), raw_to_f64(c_raw.1, s));
    while angle < end {
        let p = point(
            rng,
            s,
            centre.0 + radius * angle.cos(),
            centre.1 + radius * angle.sin(),
            false,
        );
        let last = *vertices.last().expect("centre");
        if vertices.len() == 1 || orientation(c_raw, last, p) > 0 {
            vertices.push(p);
        }
        angle += rng.unit() / radius;
    }
    // Close the fan: drop last points until the closing triangle turns forward too.
    while vertices.len() > 3 && orientation(c_raw, *vertices.last().expect("v"), vertices[1]) <= 0 {
        vertices.pop();
    }
    let n = vertices.len() - 1;
    assert!(n >= 3, "fan too small");
    let triangles = (1..=n)
        .map(|i| [0, i, if i == n { 1 } else { i + 1 }])
        .collect();
    let boundary = (1..=n).collect();
    Mesh {
        s,
        vertices,
        triangles,
        boundary,
    }
}

/// A jittered triangulated grid of `nx x ny` cells of about `cell` px starting at `origin`,
/// each quad split into two triangles along a random diagonal; all triangles have positive
/// orientation (the jitter is halved until they do).
pub fn grid(rng: &mut Rng, s: u32, origin: (f64, f64), nx: usize, ny: usize, cell: f64) -> Mesh {
    assert!(
        cell * f64::from(1u32 << s) >= 1.5,
        "cells must be wider than the snapping grid"
    );
    let mut jitter = 0.45;
    for _attempt in 0..64 {
        let mut vertices = Vec::with_capacity((nx + 1) * (ny + 1));
        for j in 0..=ny {
            for i in 0..=nx {
                let x = origin.0 + cell * (i as f64 + rng.range(-jitter, jitter));
                let y = origin.1 + cell * (j as f64 + rng.range(-jitter, jitter));
                vertices.push(point(rng, s, x, y, true));
            }
        }
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut triangles = Vec::with_capacity(2 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                if rng.chance(0.5) {
                    triangles.push([a, b, c]);
                    triangles.push([a, c, d]);
                } else {
                    triangles.push([a, b, d]);
                    triangles.push([b, c, d]);
                }
            }
        }
        // y grows downward: (a, b, c) = (top-left, top-right, bottom-right) has orientation > 0.
        let ok = triangles
            .iter()
            .all(|t| orientation(vertices[t[0]], vertices[t[1]], vertices[t[2]]) > 0);
        if ok {
            let mut boundary = Vec::new();
            boundary.extend((0..nx).map(|i| id(i, 0)));
            boundary.extend((0..ny).map(|j| id(nx, j)));
            boundary.extend((1..=nx).rev().map(|i| id(i, ny)));
            boundary.extend((1..=ny).rev().map(|j| id(0, j)));
            return Mesh {
                s,
                vertices,
                triangles,
                boundary,
            };
        }
        jitter /= 2.0;
    }
    panic!("grid: no positively oriented triangulation found");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generators_are_deterministic() {
        let a = polygon(&mut Rng::new(7), Shape::Concave, 4, 64, 64);
        let b = polygon(&mut Rng::new(7), Shape::Concave, 4, 64, 64);
        assert_eq!(a, b);
    }

    #[test]
    fn fan_triangles_turn_forward_and_wind_once() {
        let mut rng = Rng::new(1);
        for s in [0, 4, 8] {
            for _ in 0..50 {
                let r = rng.log_uniform(4.0, 200.0);
                let m = fan(&mut rng, s, 64, 64, r);
                let total: f64 = (0..m.triangles.len())
                    .map(|t| {
                        let [c, p, q] = m.triangle_f64(t);
                        let a1 = (p.1 - c.1).atan2(p.0 - c.0);
                        let a2 = (q.1 - c.1).atan2(q.0 - c.0);
                        assert!(
                            orientation(m.vertices[0], m.triangle_raw(t)[1], m.triangle_raw(t)[2])
                                > 0
                        );
                        (a2 - a1).rem_euclid(TAU)
                    })
                    .sum();
                assert!((total - TAU).abs() < 1e-6, "fan winds {total}");
            }
        }
    }

    #[test]
    fn grid_triangles_have_positive_orientation() {
        let mut rng = Rng::new(2);
        let m = grid(&mut rng, 0, (-3.0, -3.0), 10, 7, 2.0);
        assert_eq!(m.triangles.len(), 140);
        assert_eq!(m.boundary.len(), 34);
    }
}
