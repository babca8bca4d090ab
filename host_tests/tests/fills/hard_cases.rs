//! Hand-computed edge cases of coverage, range and errors. Every expected picture is
//! derived in the comments from the rule of CONVENTIONS.md (a centre counts iff the centre
//! moved by (+e, +e^2) is inside) and is also checked against the f64 reference.

use crate::support;

use embedded_graphics::pixelcolor::BinaryColor;
use fixed::types::extra::{U0, U12, U4, U8};
use host_tests::random::RawPolygon;
use host_tests::reference::{Polygon, Rule};
use pbuffer::{
    packed_len, Capacity, Error, FillRule, PackedFramebuffer, ScanConverter, ScreenPoint,
    XorFiller, GUARD_BAND_PX,
};
use support::{fill_raw, CountSink, Filler};

type Pixels = Vec<(usize, usize)>;

/// Raw value of `v` px at `s` sub-pixel bits (exact: `v` must be on the grid).
fn raw(v: f64, s: u32) -> i32 {
    let r = v * f64::from(1u32 << s);
    assert_eq!(r.fract(), 0.0, "{v} is not on the 1/2^{s} grid");
    r as i32
}

fn raw_pts(s: u32, pts: &[(f64, f64)]) -> Vec<(i32, i32)> {
    pts.iter().map(|&(x, y)| (raw(x, s), raw(y, s))).collect()
}

fn pixel_list(covered: &[bool], width: u16) -> Pixels {
    let w = usize::from(width);
    covered
        .iter()
        .enumerate()
        .filter(|(_, &c)| c)
        .map(|(i, _)| (i % w, i / w))
        .collect()
}

/// The library's pixels (each drawn at most once, checked by the sink).
fn library(s: u32, raw: &[(i32, i32)], filler: Filler, width: u16, height: u16) -> Pixels {
    let mut sink = CountSink::new(width, height);
    fill_raw(s, raw, filler, &mut sink).expect("fill");
    pixel_list(&sink.covered(), width)
}

fn reference(s: u32, raw: &[(i32, i32)], rule: Rule, width: u16, height: u16) -> Pixels {
    let p = RawPolygon {
        s,
        pts: raw.to_vec(),
    };
    let img = Polygon::new(&p.to_f64(), f64::from(width.max(height))).rasterize(
        rule,
        u32::from(width),
        u32::from(height),
    );
    pixel_list(&img, width)
}

/// Asserts that the reference, the scan converter (both rules) and the XOR filler all
/// draw exactly `expected` for the polygon `pts` (exact values on the 1/2^s grid).
fn assert_draws(s: u32, pts: &[(f64, f64)], width: u16, height: u16, expected: &[(usize, usize)]) {
    let r = raw_pts(s, pts);
    let mut expected = expected.to_vec();
    expected.sort_by_key(|&(x, y)| (y, x));
    for rule in Rule::ALL {
        same(
            &reference(s, &r, rule, width, height),
            &expected,
            &format!("reference {rule:?}, S={s} {pts:?}"),
        );
        same(
            &library(s, &r, Filler::Scan(rule), width, height),
            &expected,
            &format!("ScanConverter {rule:?}, S={s} {pts:?}"),
        );
    }
    if width <= 1024 {
        same(
            &library(s, &r, Filler::Xor, width, height),
            &expected,
            &format!("XorFiller, S={s} {pts:?}"),
        );
    }
}

/// Asserts two pixel lists are equal, printing only the first differences.
fn same(got: &[(usize, usize)], want: &[(usize, usize)], what: &str) {
    if got != want {
        let extra: Vec<_> = got.iter().filter(|p| !want.contains(p)).take(10).collect();
        let missing: Vec<_> = want.iter().filter(|p| !got.contains(p)).take(10).collect();
        panic!(
            "{what}: {} pixels instead of {}; extra {extra:?}, missing {missing:?}",
            got.len(),
            want.len()
        );
    }
}

/// Asserts the library equals the reference (no hand-computed picture).
fn assert_matches_reference(s: u32, r: &[(i32, i32)], width: u16, height: u16) -> usize {
    let want = reference(s, r, Rule::EvenOdd, width, height);
    for filler in [
        Filler::Scan(Rule::EvenOdd),
        Filler::Scan(Rule::NonZero),
        Filler::Xor,
    ] {
        same(
            &library(s, r, filler, width, height),
            &want,
            &format!("{filler:?}, S={s} raw {r:?}"),
        );
    }
    want.len()
}

fn all_pixels(width: usize, height: usize) -> Pixels {
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .collect()
}

#[test]
fn sliver_below_a_thousandth_of_a_pixel_covers_a_centre_on_its_top_edge() {
    // Top edge y = 0.5 from x = 0.375 to 0.625, apex 1/256 below: area 0.25/256/2 = 4.9e-4.
    // The centre (0.5, 0.5) lies on the top edge: covered.
    assert_draws(
        8,
        &[(0.375, 0.5), (0.625, 0.5), (0.5, 0.5 + 1.0 / 256.0)],
        4,
        4,
        &[(0, 0)],
    );
}

#[test]
fn sliver_below_a_thousandth_of_a_pixel_misses_a_centre_on_its_bottom_edge() {
    // The same sliver mirrored above y = 0.5: the centre is on its bottom edge: not covered.
    assert_draws(
        8,
        &[(0.375, 0.5), (0.625, 0.5), (0.5, 0.5 - 1.0 / 256.0)],
        4,
        4,
        &[],
    );
}

#[test]
fn horizontal_needle_10000_px_long_covers_its_row_across_the_screen() {
    // Top edge on the row of centres y = 20.5 from x = -4999.75 to 5000.25; the third vertex
    // 1/256 below the left end. Just below y = 20.5 the needle spans the whole screen.
    let pts = [
        (-4999.75, 20.5),
        (5000.25, 20.5),
        (-4999.75, 20.5 + 1.0 / 256.0),
    ];
    let row: Pixels = (0..400).map(|x| (x, 20)).collect();
    assert_draws(8, &pts, 400, 240, &row);
}

#[test]
fn diagonal_needle_10000_px_long_covers_the_centres_on_its_left_edge() {
    // Edge A->B on the line y = x through the centres (i+.5, i+.5); C is 1/256 right of A,
    // so the needle lies right of y = x: the perturbed centres are inside. Length 10 000 px.
    let pts = [
        (-3535.5, -3535.5),
        (3535.5, 3535.5),
        (-3535.5 + 1.0 / 256.0, -3535.5),
    ];
    let diagonal: Pixels = (0..64).map(|i| (i, i)).collect();
    assert_draws(8, &pts, 64, 64, &diagonal);
}

#[test]
fn three_equal_vertices_draw_nothing() {
    assert_draws(4, &[(2.5, 2.5); 3], 8, 8, &[]);
    assert_draws(0, &[(3.0, 3.0); 3], 8, 8, &[]);
}

#[test]
fn collinear_vertices_draw_nothing() {
    // On a line through pixel centres, in a back-and-forth order too.
    assert_draws(4, &[(0.5, 0.5), (10.5, 5.5), (4.5, 2.5)], 16, 16, &[]);
    assert_draws(
        0,
        &[(0.0, 0.0), (8.0, 8.0), (3.0, 3.0), (12.0, 12.0)],
        16,
        16,
        &[],
    );
    assert_draws(4, &[(1.5, 3.5), (9.5, 3.5), (4.5, 3.5)], 16, 16, &[]);
}

#[test]
fn vertex_above_the_screen_is_clipped_like_the_reference() {
    // Apex at y = -50; base on y = 20: rows 0..=19 are drawn, nothing below.
    let r = raw_pts(4, &[(10.0, -50.0), (30.0, 20.0), (-5.0, 20.0)]);
    let n = assert_matches_reference(4, &r, 64, 64);
    let got = library(4, &r, Filler::Scan(Rule::EvenOdd), 64, 64);
    assert!(n > 0 && got.iter().all(|&(_, y)| y < 20));
    assert!(got.contains(&(10, 0)) && got.contains(&(10, 19)) && got.contains(&(0, 19)));
}

#[test]
fn full_screen_triangle_fills_every_pixel_of_400x240_once() {
    // (400, 240) satisfies (x+10)/1010 + (y+10)/610 = 0.82 < 1: the screen is inside.
    assert_draws(
        4,
        &[(-10.0, -10.0), (1000.0, -10.0), (-10.0, 600.0)],
        400,
        240,
        &all_pixels(400, 240),
    );
    // Through the packed framebuffer's own sink: every byte full.
    let mut fb = PackedFramebuffer::<400, 240, { packed_len(400, 240) }>::new();
    let tri =
        [(-10, -10), (1000, -10), (-10, 600)].map(|(x, y)| ScreenPoint::<U0>::from_bits(x, y));
    ScanConverter::<8>::new()
        .fill(&tri, FillRule::EvenOdd, BinaryColor::On, &mut fb)
        .expect("fill");
    assert!(fb.as_bytes().iter().all(|&b| b == 0xff));
}

#[test]
fn full_screen_triangle_fills_every_pixel_of_1000x1000_once() {
    assert_draws(
        8,
        &[(-1.0, -1.0), (3000.0, -1.0), (-1.0, 3000.0)],
        1000,
        1000,
        &all_pixels(1000, 1000),
    );
}

#[test]
fn two_triangles_on_the_screen_corners_tile_the_screen() {
    // Split on the diagonal (0,0)-(400,240): every pixel exactly once (the sink checks).
    let mut sink = CountSink::new(400, 240);
    for tri in [
        [(0, 0), (400, 0), (400, 240)],
        [(0, 0), (400, 240), (0, 240)],
    ] {
        fill_raw(0, &tri, Filler::Scan(Rule::EvenOdd), &mut sink).expect("fill");
    }
    assert!(sink.counts.iter().all(|&c| c == 1));
}

#[test]
fn quad_split_on_its_diagonal_with_vertices_on_pixel_centres_draws_15_plus_10_pixels() {
    // Square of centres (0.5, 0.5)..(5.5, 5.5): pixels 0..5 x 0..5 (right and bottom edges
    // excluded). Split on A-C, the diagonal is the left edge of the upper-right triangle
    // (row j: pixels j..=4, 5+4+3+2+1 = 15) and the right edge of the lower-left one
    // (row j: pixels 0..j, 0+1+2+3+4 = 10). Split on B-D the same holds with 15 above it.
    let (a, b, c, d) = ((0.5, 0.5), (5.5, 0.5), (5.5, 5.5), (0.5, 5.5));
    let upper_right: Pixels = all_pixels(5, 5)
        .into_iter()
        .filter(|&(x, y)| x >= y)
        .collect();
    let lower_left: Pixels = all_pixels(5, 5)
        .into_iter()
        .filter(|&(x, y)| x < y)
        .collect();
    assert_eq!((upper_right.len(), lower_left.len()), (15, 10));
    assert_draws(4, &[a, b, c], 8, 8, &upper_right);
    assert_draws(4, &[a, c, d], 8, 8, &lower_left);
    let upper_left: Pixels = all_pixels(5, 5)
        .into_iter()
        .filter(|&(x, y)| x + y <= 4)
        .collect();
    let lower_right: Pixels = all_pixels(5, 5)
        .into_iter()
        .filter(|&(x, y)| x + y >= 5)
        .collect();
    assert_eq!((upper_left.len(), lower_right.len()), (15, 10));
    assert_draws(4, &[a, b, d], 8, 8, &upper_left);
    assert_draws(4, &[b, c, d], 8, 8, &lower_right);
}

#[test]
fn vertices_a_quarter_subpixel_off_a_centre_snap_onto_it() {
    // S is at most 12, so 0.5 - 2^-14 (= 2047.75 / 2^12) is not representable: from_f64
    // rounds it to 2048 / 2^12 = 0.5, a pixel centre. The snapped right triangle
    // (0.5,0.5) (4.5,0.5) (0.5,4.5) has its top and left edges on centres (covered) and its
    // hypotenuse x + y = 5 through the centres with i + j = 4 (excluded): i + j <= 3, 10 px.
    let d = 0.5f64.powi(14);
    let pts = [(0.5 - d, 0.5 - d), (4.5, 0.5 - d), (0.5 - d, 4.5)]
        .map(|(x, y)| ScreenPoint::<U12>::from_f64(x, y).expect("in range"));
    assert!(pts
        .iter()
        .all(|p| p.x.to_bits() % 2048 == 0 && p.y.to_bits() % 2048 == 0));
    let r: Vec<(i32, i32)> = pts.iter().map(|p| (p.x.to_bits(), p.y.to_bits())).collect();
    let expected: Pixels = all_pixels(5, 5)
        .into_iter()
        .filter(|&(x, y)| x + y <= 3)
        .collect();
    assert_eq!(library(12, &r, Filler::Scan(Rule::EvenOdd), 8, 8).len(), 10);
    assert_draws(12, &[(0.5, 0.5), (4.5, 0.5), (0.5, 4.5)], 8, 8, &expected);
}

#[test]
fn vertices_one_subpixel_off_a_centre_at_12_bits_are_exact() {
    let d = 0.5f64.powi(12);
    // Moved up-left by 2^-12: centres of row 0 / column 0 now strictly inside; the
    // hypotenuse x + y = 5 - d still excludes i + j = 4: the same 10 pixels.
    let ten: Pixels = all_pixels(5, 5)
        .into_iter()
        .filter(|&(x, y)| x + y <= 3)
        .collect();
    assert_draws(
        12,
        &[(0.5 - d, 0.5 - d), (4.5, 0.5 - d), (0.5 - d, 4.5)],
        8,
        8,
        &ten,
    );
    // Moved down-right by 2^-12: row 0 and column 0 drop out, the hypotenuse x + y = 5 + d
    // now includes i + j = 4: i, j >= 1 and i + j <= 4, 6 pixels.
    let six: Pixels = all_pixels(5, 5)
        .into_iter()
        .filter(|&(x, y)| x >= 1 && y >= 1 && x + y <= 4)
        .collect();
    assert_eq!(six.len(), 6);
    assert_draws(
        12,
        &[(0.5 + d, 0.5 + d), (4.5, 0.5 + d), (0.5 + d, 4.5)],
        8,
        8,
        &six,
    );
}

#[test]
fn tiny_triangle_3_16_px_across_covers_the_centre_only_when_the_rule_says_so() {
    // Right triangle with legs 3/16 and corner o = c - (k, m)/16 around the centre c=(5.5,5.5).
    // In triangle coordinates the centre is (k, m)/16; moved by (+e, +e^2) it is inside iff
    // k >= 0, m >= 0 and k + m < 3 (k + m = 3 is the hypotenuse, left by the move).
    let mut covered = 0;
    for k in -2..=4i32 {
        for m in -2..=4i32 {
            let o = (5.5 - f64::from(k) / 16.0, 5.5 - f64::from(m) / 16.0);
            let tri = [o, (o.0 + 3.0 / 16.0, o.1), (o.0, o.1 + 3.0 / 16.0)];
            let inside = k >= 0 && m >= 0 && k + m < 3;
            covered += usize::from(inside);
            assert_draws(4, &tri, 12, 12, if inside { &[(5, 5)] } else { &[] });
        }
    }
    assert_eq!(covered, 6);
}

/// Triangles reaching just inside and just outside the guard band, and far beyond it,
/// must give the reference's pixels (the fast path and the wide path agree).
#[test]
fn guard_band_edges_inside_and_outside_match_the_reference() {
    let g = f64::from(GUARD_BAND_PX);
    for s in [0u32, 4, 8] {
        let q = 0.5f64.powi(s as i32);
        for delta in [0.0, q] {
            let far = g + delta;
            // Long edges crossing the 64x64 screen at odd slopes, vertices at +-far.
            let cases = [
                [(-far, 10.0 + q), (far, 30.0 + 3.0 * q), (20.0, far)],
                [(far, -far), (-far, 40.0), (5.0 + q, 5.0)],
                [
                    (-far, -far),
                    (far, -far + 67.0 * q),
                    (31.0 + q, 33.0 + 2.0 * q),
                ],
                [(q, -far), (far, far), (-far, q)],
            ];
            for tri in cases {
                let r = raw_pts(s, &tri);
                let n = assert_matches_reference(s, &r, 64, 64);
                assert!(n > 0, "case {tri:?} should reach the screen");
                let beyond = r.iter().any(|&(x, y)| {
                    x.unsigned_abs().max(y.unsigned_abs()) > (GUARD_BAND_PX as u32) << s
                });
                assert_eq!(beyond, delta > 0.0);
            }
        }
    }
}

#[test]
fn huge_coordinates_at_8_bits_match_the_reference() {
    let h = 4_194_304.0; // 2^22 px, raw 2^30
    for tri in [
        [(-h, 10.5), (h, 30.5 + 1.0 / 256.0), (20.0, h)],
        [(-h, -h), (h, -h + 67.0 / 256.0), (31.0 + 1.0 / 256.0, 33.5)],
        [(h, -h), (-h, h + 1.0 / 256.0), (h, h)],
    ] {
        assert!(assert_matches_reference(8, &raw_pts(8, &tri), 64, 64) > 0);
    }
    // Covering the whole screen from far away.
    assert_draws(
        8,
        &[(-h, -h), (h + h / 2.0, -h), (-h, h + h / 2.0)],
        64,
        64,
        &all_pixels(64, 64),
    );
}

#[test]
fn coordinates_near_the_i32_limit_at_0_bits_match_the_reference() {
    let (max, min) = (i32::MAX, i32::MIN);
    for r in [
        vec![(min, 10), (max, 31), (20, max)],
        vec![(min, min), (max, min + 67), (31, 33)],
        vec![(max, min), (min, max), (max, max)],
        vec![(min, 3), (max, 4), (max, 5), (min, 6)],
    ] {
        assert!(assert_matches_reference(0, &r, 64, 64) > 0, "{r:?}");
    }
    // The whole i32 square, and a triangle whose far edge x + y = 2^31 + 100 passes
    // beyond the screen: both cover every pixel.
    let (lo, hi) = (-2_147_483_648.0, 2_147_483_647.0);
    assert_draws(
        0,
        &[(lo, lo), (hi, lo), (hi, hi), (lo, hi)],
        64,
        64,
        &all_pixels(64, 64),
    );
    assert_draws(
        0,
        &[(lo, lo), (hi, 100.0), (100.0, hi)],
        64,
        64,
        &all_pixels(64, 64),
    );
}

#[test]
fn fewer_than_three_vertices_is_an_error_that_draws_nothing() {
    let pts = [(1, 1), (60, 3), (30, 50)].map(|(x, y)| ScreenPoint::<U0>::from_bits(x, y));
    for n in 0..3 {
        let mut sink = CountSink::new(64, 64);
        let e = ScanConverter::<8>::new().fill(
            &pts[..n],
            FillRule::EvenOdd,
            BinaryColor::On,
            &mut sink,
        );
        assert_eq!(e, Err(Error::TooFewVertices { found: n }));
        let e = XorFiller::<8, 2>::new().fill(&pts[..n], BinaryColor::On, &mut sink);
        assert_eq!(e, Err(Error::TooFewVertices { found: n }));
        assert_eq!(sink.spans, 0);
    }
}

/// A 10-pointed star around (32, 32): 10 edges, none horizontal, all within the screen.
fn star() -> Vec<ScreenPoint<U4>> {
    (0..10)
        .map(|k| {
            let t = std::f64::consts::TAU * (f64::from(k) + 0.25) / 10.0;
            let r = if k % 2 == 0 { 25.0 } else { 9.0 };
            ScreenPoint::<U4>::from_f64(32.0 + r * t.cos(), 32.0 + r * t.sin()).expect("finite")
        })
        .collect()
}

#[test]
fn too_many_edges_is_a_capacity_error_with_the_needed_count_and_draws_nothing() {
    let pts = star();
    assert!((0..10).all(|i| pts[i].y != pts[(i + 1) % 10].y));
    let mut sink = CountSink::new(64, 64);
    let e = ScanConverter::<4>::new().fill(&pts, FillRule::EvenOdd, BinaryColor::On, &mut sink);
    assert_eq!(
        e,
        Err(Error::CapacityExceeded {
            what: Capacity::ActiveEdges,
            needed: 10,
            capacity: 4
        })
    );
    let e = XorFiller::<9, 2>::new().fill(&pts, BinaryColor::On, &mut sink);
    assert_eq!(
        e,
        Err(Error::CapacityExceeded {
            what: Capacity::ActiveEdges,
            needed: 10,
            capacity: 9
        })
    );
    assert_eq!(sink.spans, 0);
    // With room for 10 edges it draws.
    ScanConverter::<10>::new()
        .fill(&pts, FillRule::EvenOdd, BinaryColor::On, &mut sink)
        .expect("fits");
    assert!(sink.spans > 0);
}

#[test]
fn xor_row_buffer_narrower_than_the_viewport_is_a_capacity_error() {
    let pts = star();
    let mut sink = CountSink::new(64, 64);
    let e = XorFiller::<16, 1>::new().fill(&pts, BinaryColor::On, &mut sink);
    assert_eq!(
        e,
        Err(Error::CapacityExceeded {
            what: Capacity::RowWords,
            needed: 2,
            capacity: 1
        })
    );
    assert_eq!(sink.spans, 0);
}

#[test]
fn non_finite_and_out_of_range_coordinates_are_rejected() {
    for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(ScreenPoint::<U4>::from_f64(v, 1.0), Err(Error::NonFinite));
        assert_eq!(ScreenPoint::<U4>::from_f64(1.0, v), Err(Error::NonFinite));
        assert_eq!(
            ScreenPoint::<U4>::from_f32(v as f32, 1.0),
            Err(Error::NonFinite)
        );
    }
    // Raw values must fit i32: 2^31 px at S=0, 2^23 px at S=8.
    assert_eq!(
        ScreenPoint::<U0>::from_f64(2_147_483_648.0, 0.0),
        Err(Error::OutOfRange)
    );
    assert_eq!(
        ScreenPoint::<U8>::from_f64(0.0, -8_388_609.0),
        Err(Error::OutOfRange)
    );
    assert_eq!(
        ScreenPoint::<U0>::from_f64(-2_147_483_648.0, 2_147_483_647.0)
            .map(|p| (p.x.to_bits(), p.y.to_bits())),
        Ok((i32::MIN, i32::MAX))
    );
}
