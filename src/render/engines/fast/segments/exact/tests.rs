//! The predicates' signs against `f64` on random cases.

use super::*;

/// A small deterministic generator (xorshift).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn range(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.next() % (hi - lo + 1) as u64) as i32
    }
}

fn random_point(rng: &mut Rng) -> Pt {
    Pt {
        x: rng.range(-32_000, 32_000),
        y: rng.range(-32_000, 32_000),
        d: rng.range(0, (1 << 24) - 1),
        id: NOT_A_VERTEX,
    }
}

/// The depth order at a crossing agrees with f64 on 20,000 random crossings,
/// at the bounds' extremes of position and nearness.
#[test]
fn the_depth_order_at_a_crossing_agrees_with_f64() {
    let mut rng = Rng(49);
    let mut tested = 0;
    while tested < 20_000 {
        let [a, b, p, q] = [0; 4].map(|_| random_point(&mut rng));
        let (o1, o2) = (orient(p, q, a), orient(p, q, b));
        let (o3, o4) = (orient(a, b, p), orient(a, b, q));
        if o1.signum() * o2.signum() >= 0 || o3.signum() * o4.signum() >= 0 {
            continue;
        }
        let t = o1 as f64 / (o1 - o2) as f64;
        let s = o3 as f64 / (o3 - o4) as f64;
        let de = f64::from(a.d) + t * f64::from(b.d - a.d);
        let dc = f64::from(p.d) + s * f64::from(q.d - p.d);
        if (de - dc).abs() < 1e-3 {
            continue;
        }
        tested += 1;
        assert_eq!(
            segment_minus(a, b, p, q, o1, o2, o3, o4),
            if de > dc { 1 } else { -1 },
            "{a:?}-{b:?} x {p:?}-{q:?}"
        );
    }
}

/// The plane test agrees with f64 at random points, inside the triangle and
/// beyond it.
#[test]
fn the_plane_test_agrees_with_f64() {
    let mut rng = Rng(50);
    let mut tested = 0;
    while tested < 20_000 {
        let t = [0; 3].map(|_| random_point(&mut rng));
        let r = random_point(&mut rng);
        let area = orient(t[0], t[1], t[2]);
        if area == 0 {
            continue;
        }
        let w = [
            orient(t[1], t[2], r) as f64 / area as f64,
            orient(t[2], t[0], r) as f64 / area as f64,
            orient(t[0], t[1], r) as f64 / area as f64,
        ];
        let plane = w[0] * f64::from(t[0].d) + w[1] * f64::from(t[1].d) + w[2] * f64::from(t[2].d);
        if (plane - f64::from(r.d)).abs() < 1e-3 * (1.0 + plane.abs()) {
            continue;
        }
        tested += 1;
        let expected = if plane > f64::from(r.d) { 1 } else { -1 };
        assert_eq!(plane_minus(t, area, r), expected, "{t:?} at {r:?}");
    }
}

/// A point on a line is moved by (+e, +e^2): left of a line going right (y
/// grows downward), right of a line going down.
#[test]
fn a_point_on_a_line_takes_the_side_of_its_nudge() {
    let p = |x, y| Pt {
        x,
        y,
        d: 0,
        id: NOT_A_VERTEX,
    };
    assert_eq!(side(p(0, 0), p(10, 0), p(5, 0)), 1);
    assert_eq!(side(p(10, 0), p(0, 0), p(5, 0)), -1);
    assert_eq!(side(p(0, 0), p(0, 10), p(0, 5)), -1);
    assert_eq!(side(p(0, 0), p(10, 0), p(5, 1)), 1);
}

fn v(x: i32, y: i32, id: u16) -> Pt {
    Pt { x, y, d: 0, id }
}

/// The perturbed side is antisymmetric, never zero, and agrees with the exact
/// one where that is not zero, for collinear and coincident vertices.
#[test]
fn the_perturbed_side_is_a_consistent_orientation() {
    let cases = [
        [v(0, 0, 3), v(10, 0, 1), v(5, 0, 2)],
        [v(0, 0, 3), v(0, 0, 1), v(5, 5, 2)],
        [v(2, 2, 0), v(2, 2, 1), v(2, 2, 2)],
        [v(0, 0, 0), v(4, 4, 5), v(8, 8, 9)],
        [v(1, 0, 0), v(4, 4, 5), v(8, 8, 9)],
    ];
    for [a, b, c] in cases {
        let s = side(a, b, c);
        assert_ne!(s, 0);
        assert_eq!(side(b, a, c), -s, "swap");
        assert_eq!(side(b, c, a), s, "rotation");
        assert_eq!(side(a, c, b), -s, "swap");
        let o = orient(a, b, c);
        if o != 0 {
            assert_eq!(i64::from(s), o.signum());
        }
    }
}

/// A chain through a vertex that coincides with a vertex of a crossing chain
/// is crossed exactly once, as if the two were apart.
#[test]
fn coincident_vertices_are_crossed_once_along_a_chain() {
    let (a, m, b) = (v(0, -10, 0), v(0, 0, 1), v(0, 10, 2));
    let (p, n, q) = (v(-10, 0, 3), v(0, 0, 4), v(10, 0, 5));
    let crosses = |e0: Pt, e1: Pt, c0: Pt, c1: Pt| {
        side(c0, c1, e0) != side(c0, c1, e1) && side(e0, e1, c0) != side(e0, e1, c1)
    };
    let total: usize = [(a, m), (m, b)]
        .iter()
        .flat_map(|e| [(p, n), (n, q)].map(|c| (*e, c)))
        .filter(|((e0, e1), (c0, c1))| crosses(*e0, *e1, *c0, *c1))
        .count();
    assert_eq!(total, 1);
}
