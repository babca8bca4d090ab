//! Test scenes shared by several topics, and the no-std maths they need.

/// Three sticks (long planar quads) over the triangle of corners at 90, 210 and 330
/// degrees: stick `i` runs from corner `i` (height -0.3) to corner `i + 1` (height
/// +0.3), extended by 0.4 beyond both, so each stick lies over the next one where
/// they cross and under the previous one: a cycle no face order can draw.
pub(super) fn sticks() -> ([[f32; 3]; 12], [u32; 12], [u32; 4]) {
    let corner = |i: usize| {
        let a = (90.0f64 + 120.0 * i as f64).to_radians();
        [cos(a), sin(a)]
    };
    let mut vertices = [[0.0f32; 3]; 12];
    for i in 0..3 {
        let (p, q) = (corner(i), corner((i + 1) % 3));
        let d = [q[0] - p[0], q[1] - p[1]];
        let len = (d[0] * d[0] + d[1] * d[1]).sqrt_approx();
        let (u, w) = ([d[0] / len, d[1] / len], 0.08);
        let perp = [-u[1], u[0]];
        let at = |s: f64, side: f64| {
            // s: distance along the stick from p; height linear in s.
            let z = -0.3 + 0.6 * s / len;
            [
                (p[0] + u[0] * s + perp[0] * side * w) as f32,
                (p[1] + u[1] * s + perp[1] * side * w) as f32,
                z as f32,
            ]
        };
        // Counter-clockwise seen from +z.
        vertices[4 * i] = at(-0.4, -1.0);
        vertices[4 * i + 1] = at(len + 0.4, -1.0);
        vertices[4 * i + 2] = at(len + 0.4, 1.0);
        vertices[4 * i + 3] = at(-0.4, 1.0);
    }
    let indices = core::array::from_fn(|k| k as u32);
    (vertices, indices, [0, 4, 8, 12])
}

/// Small no-std trigonometry for the test scenes (Taylor series, |a| <= 2 pi).
fn sin(a: f64) -> f64 {
    let pi = core::f64::consts::PI;
    let mut x = a % (2.0 * pi);
    if x > pi {
        x -= 2.0 * pi;
    } else if x < -pi {
        x += 2.0 * pi;
    }
    let (mut term, mut sum) = (x, x);
    for k in 1..20 {
        term *= -x * x / (f64::from(2 * k) * f64::from(2 * k + 1));
        sum += term;
    }
    sum
}

fn cos(a: f64) -> f64 {
    sin(a + core::f64::consts::FRAC_PI_2)
}

trait SqrtApprox {
    fn sqrt_approx(self) -> Self;
}

impl SqrtApprox for f64 {
    fn sqrt_approx(self) -> f64 {
        let mut x = if self > 1.0 { self } else { 1.0 };
        for _ in 0..60 {
            x = 0.5 * (x + self / x);
        }
        x
    }
}
