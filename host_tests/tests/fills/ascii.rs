//! Small pictures as ASCII art, drawn through the embedded-graphics span sinks `FillSolid`
//! and `ContiguousRows` into a `MockDisplay`, which panics on any pixel drawn twice and on
//! any pixel outside its 64x64 area. `#` = drawn, space = untouched. All vertices are
//! integers (S = 0), so every centre (i + 0.5, j + 0.5) is decided by hand from the edges.

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::BinaryColor;
use fixed::types::extra::U0;
use host_tests::reference::{rasterize, Rule};
use pbuffer::{ContiguousRows, FillRule, FillSolid, ScanConverter, ScreenPoint, XorFiller};

fn points(pts: &[(i32, i32)]) -> Vec<ScreenPoint<U0>> {
    pts.iter()
        .map(|&(x, y)| ScreenPoint::from_bits(x, y))
        .collect()
}

/// The reference picture as the same ASCII art, for a second opinion on the hand-made one.
fn reference_pattern(pts: &[(i32, i32)], rule: Rule, pattern: &[&str]) -> Vec<String> {
    let (w, h) = (64u32, 64u32);
    let f: Vec<(f64, f64)> = pts
        .iter()
        .map(|&(x, y)| (f64::from(x), f64::from(y)))
        .collect();
    let img = rasterize(&f, rule, w, h);
    (0..pattern.len())
        .map(|y| {
            (0..pattern[0].len())
                .map(|x| if img[y * w as usize + x] { '#' } else { ' ' })
                .collect()
        })
        .collect()
}

/// Draws `pts` under `rule` through both sinks (and the XOR filler for even-odd) and
/// asserts the picture is `pattern`, which must also be the reference's picture.
fn assert_picture(pts: &[(i32, i32)], rule: Rule, pattern: &[&str]) {
    assert_eq!(
        reference_pattern(pts, rule, pattern),
        pattern,
        "the reference disagrees with the hand-made picture"
    );
    let fill_rule = match rule {
        Rule::EvenOdd => FillRule::EvenOdd,
        Rule::NonZero => FillRule::NonZero,
    };
    let p = points(pts);

    let mut display = MockDisplay::<BinaryColor>::new();
    let mut sink = FillSolid::new(&mut display).expect("64x64 fits");
    ScanConverter::<16>::new()
        .fill(&p, fill_rule, BinaryColor::On, &mut sink)
        .expect("fill");
    display.assert_pattern_with_message(pattern, |f| write!(f, "FillSolid, {rule:?}"));

    let mut display = MockDisplay::<BinaryColor>::new();
    let mut sink = ContiguousRows::new(&mut display).expect("64x64 fits");
    ScanConverter::<16>::new()
        .fill(&p, fill_rule, BinaryColor::On, &mut sink)
        .expect("fill");
    display.assert_pattern_with_message(pattern, |f| write!(f, "ContiguousRows, {rule:?}"));

    if rule == Rule::EvenOdd {
        let mut display = MockDisplay::<BinaryColor>::new();
        let mut sink = ContiguousRows::new(&mut display).expect("64x64 fits");
        XorFiller::<16, 2>::new()
            .fill(&p, BinaryColor::On, &mut sink)
            .expect("fill");
        display.assert_pattern_with_message(pattern, |f| write!(f, "XorFiller"));
    }
}

/// (1,1) (9,1) (1,7): top edge y = 1 and left edge x = 1 lie between centres; the
/// hypotenuse (x-1)/8 + (y-1)/6 = 1 ends row 1 (y = 1.5) at x = 8.33, row 4 at x = 4.33.
#[test]
fn right_triangle() {
    let tri = [(1, 1), (9, 1), (1, 7)];
    let pattern = [
        "          ",
        " #######  ",
        " ######   ",
        " #####    ",
        " ###      ",
        " ##       ",
        " #        ",
        "          ",
    ];
    assert_picture(&tri, Rule::EvenOdd, &pattern);
    assert_picture(&tri, Rule::NonZero, &pattern);
}

/// An axis-aligned concave "C": [1,9)x[1,8) minus the notch [4,9)x[3,6).
#[test]
fn concave_c_shape() {
    let c = [
        (1, 1),
        (9, 1),
        (9, 3),
        (4, 3),
        (4, 6),
        (9, 6),
        (9, 8),
        (1, 8),
    ];
    let pattern = [
        "          ",
        " ######## ",
        " ######## ",
        " ###      ",
        " ###      ",
        " ###      ",
        " ######## ",
        " ######## ",
        "          ",
    ];
    assert_picture(&c, Rule::EvenOdd, &pattern);
    assert_picture(&c, Rule::NonZero, &pattern);
}

/// A bowtie: its two lobes wind in opposite directions (+1 and -1), so both rules fill
/// both lobes. Row 3 (y = 3.5): the diagonals cross it at x = 4.33 and x = 5.67.
#[test]
fn self_intersecting_bowtie_is_the_same_under_both_rules() {
    let bowtie = [(1, 1), (9, 7), (9, 1), (1, 7)];
    let pattern = [
        "          ",
        " #      # ",
        " ##    ## ",
        " ###  ### ",
        " ###  ### ",
        " ##    ## ",
        " #      # ",
        "          ",
    ];
    assert_picture(&bowtie, Rule::EvenOdd, &pattern);
    assert_picture(&bowtie, Rule::NonZero, &pattern);
}

/// A boundary that loops over itself: the overlap [3,7)x[3,5) winds twice, a hole under
/// even-odd, filled under non-zero.
#[test]
fn overlapping_loop_has_a_hole_under_even_odd_only() {
    let lp = [
        (1, 1),
        (7, 1),
        (7, 5),
        (3, 5),
        (3, 3),
        (9, 3),
        (9, 7),
        (1, 7),
    ];
    assert_picture(
        &lp,
        Rule::EvenOdd,
        &[
            "          ",
            " ######   ",
            " ######   ",
            " ##    ## ",
            " ##    ## ",
            " ######## ",
            " ######## ",
            "          ",
        ],
    );
    assert_picture(
        &lp,
        Rule::NonZero,
        &[
            "          ",
            " ######   ",
            " ######   ",
            " ######## ",
            " ######## ",
            " ######## ",
            " ######## ",
            "          ",
        ],
    );
}

/// Pentagram (10,1) (4,18) (19,7) (1,7) (16,18): the inner pentagon winds twice, a hole
/// under even-odd. Row 12 (y = 12.5) is not mirror-symmetric: two edges cross it exactly
/// at the centres x = 8.5 and x = 11.5, and a crossing at a centre counts as left of it,
/// so pixel 8 lies outside (2 crossings) and pixel 11 inside (3 crossings).
#[test]
fn pentagram_has_a_hole_under_even_odd_but_not_under_non_zero() {
    let star = [(10, 1), (4, 18), (19, 7), (1, 7), (16, 18)];
    let (top, bottom) = (
        [
            "                    ",
            "                    ",
            "         ##         ",
            "         ##         ",
            "         ##         ",
            "        ####        ",
            "        ####        ",
        ],
        [
            "     ####  ####     ",
            "     ##      ##     ",
            "     #        #     ",
            "    #          #    ",
            "                    ",
        ],
    );
    let even_odd_middle = [
        "  ######    ######  ",
        "   ####      ####   ",
        "    ###      ###    ",
        "      #      #      ",
        "      #      #      ",
        "      ##   ###      ",
        "      ########      ",
    ];
    let non_zero_middle = [
        "  ################  ",
        "   ##############   ",
        "    ############    ",
        "      ########      ",
        "      ########      ",
        "      ########      ",
        "      ########      ",
    ];
    let even_odd: Vec<&str> = top
        .iter()
        .chain(&even_odd_middle)
        .chain(&bottom)
        .copied()
        .collect();
    let non_zero: Vec<&str> = top
        .iter()
        .chain(&non_zero_middle)
        .chain(&bottom)
        .copied()
        .collect();
    assert_picture(&star, Rule::EvenOdd, &even_odd);
    assert_picture(&star, Rule::NonZero, &non_zero);
}
