//! The scan converter draws exactly the pixels of the f64 reference, for random polygons
//! (triangles, quads, concave and self-intersecting polygons, both fill rules) whose
//! vertices are snapped to the 1/2^S grid, S in {0, 4, 8}: 0 differing pixels.
//!
//! The counting sink also asserts that no span leaves the viewport and that no pixel is
//! written twice by one polygon.

use crate::support;

use host_tests::random::{far_polygon, polygon, RawPolygon, Rng, Shape};
use host_tests::reference::{Polygon, Rule};
use support::{check, minimize, Filler};

/// Totals of one batch.
struct Batch {
    polygons: usize,
    /// Polygons that cover at least one pixel.
    nonempty: usize,
    pixels: usize,
    failures: Vec<String>,
}

/// The reference coverage of `p` under `rule` on a `width x height` frame.
fn reference(p: &RawPolygon, rule: Rule, width: u16, height: u16) -> Vec<bool> {
    Polygon::new(&p.to_f64(), f64::from(width.max(height))).rasterize(
        rule,
        u32::from(width),
        u32::from(height),
    )
}

/// Compares `count` random polygons with the reference under both rules.
/// `frame` picks the frame size of each polygon.
fn compare(
    seed: u64,
    count: usize,
    s_values: &[u32],
    frame: impl Fn(&mut Rng) -> (u16, u16),
) -> Batch {
    compare_with(seed, count, s_values, frame, |rng, s, w, h| {
        let shape = rng.pick(&Shape::ALL);
        (format!("{shape:?}"), polygon(rng, shape, s, w, h))
    })
}

/// Like [`compare`], with polygons from `make(rng, s, width, height) -> (label, polygon)`.
fn compare_with(
    seed: u64,
    count: usize,
    s_values: &[u32],
    frame: impl Fn(&mut Rng) -> (u16, u16),
    make: impl Fn(&mut Rng, u32, u32, u32) -> (String, RawPolygon),
) -> Batch {
    let mut rng = Rng::new(seed);
    let mut batch = Batch {
        polygons: 0,
        nonempty: 0,
        pixels: 0,
        failures: Vec::new(),
    };
    for _ in 0..count {
        let (w, h) = frame(&mut rng);
        let s = rng.pick(s_values);
        let (shape, p) = make(&mut rng, s, u32::from(w), u32::from(h));
        let wind =
            Polygon::new(&p.to_f64(), f64::from(w.max(h))).winding_map(u32::from(w), u32::from(h));
        for rule in Rule::ALL {
            let expected: Vec<bool> = wind.iter().map(|&n| rule.inside(n)).collect();
            if let Err(msg) = check(&p, Filler::Scan(rule), w, h, &expected) {
                let small = minimize(&p, |q| {
                    check(q, Filler::Scan(rule), w, h, &reference(q, rule, w, h)).is_err()
                });
                let small_msg = check(
                    &small,
                    Filler::Scan(rule),
                    w,
                    h,
                    &reference(&small, rule, w, h),
                )
                .err()
                .unwrap_or_default();
                batch
                    .failures
                    .push(format!("{shape}: {msg}\n    minimal: {small_msg}"));
            }
            batch.pixels += expected.len();
        }
        batch.polygons += 1;
        batch.nonempty += usize::from(wind.iter().any(|&n| n != 0));
    }
    batch
}

fn report(name: &str, batch: &Batch) {
    println!(
        "{name}: {} polygons ({} reach the frame) x 2 rules, {} pixels compared, {} failures",
        batch.polygons,
        batch.nonempty,
        batch.pixels,
        batch.failures.len()
    );
    assert!(
        batch.failures.is_empty(),
        "{name}: {} of {} polygon/rule pairs differ from the reference; first ones:\n{}",
        batch.failures.len(),
        2 * batch.polygons,
        batch
            .failures
            .iter()
            .take(5)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

#[test]
fn random_polygons_with_integer_vertices_match_reference_on_64x64() {
    let b = compare(0x5eed_0000, 60_000, &[0], |_| (64, 64));
    report("S=0, 64x64", &b);
}

#[test]
fn random_polygons_with_4_subpixel_bits_match_reference_on_64x64() {
    let b = compare(0x5eed_0004, 60_000, &[4], |_| (64, 64));
    report("S=4, 64x64", &b);
}

#[test]
fn random_polygons_with_8_subpixel_bits_match_reference_on_64x64() {
    let b = compare(0x5eed_0008, 60_000, &[8], |_| (64, 64));
    report("S=8, 64x64", &b);
}

#[test]
fn random_polygons_match_reference_on_400x240() {
    let b = compare(0x5eed_0400, 12_000, &[0, 4, 8], |_| (400, 240));
    report("S in {0,4,8}, 400x240", &b);
}

/// Frames of 1..=24 px per side, where most polygons cross the borders.
#[test]
fn random_polygons_match_reference_on_tiny_frames() {
    let b = compare(0x5eed_0001, 20_000, &[0, 1, 4, 8, 12], |rng| {
        (1 + rng.below(24) as u16, 1 + rng.below(24) as u16)
    });
    report("tiny frames", &b);
}

/// Vertices far beyond the guard band (up to the i32 raw limit: 2^30.9 px at S=0, 2^22.9 px
/// at S=8), with long edges crossing the frame; the reference evaluates them exactly.
#[test]
fn random_polygons_beyond_the_guard_band_match_reference() {
    let b = compare_with(
        0x5eed_fa00,
        20_000,
        &[0, 4, 8],
        |rng| {
            if rng.chance(0.8) {
                (64, 64)
            } else {
                (400, 240)
            }
        },
        |rng, s, w, h| {
            let max_px = rng.pick(&[2e4, 1e6, 2f64.powf(30.9 - f64::from(s))]);
            (
                format!("far polygon up to {max_px:.0} px"),
                far_polygon(rng, s, w, h, max_px),
            )
        },
    );
    report("beyond the guard band", &b);
}

/// Minimal polygons that tell a correct tie rule from one that treats a centre exactly on
/// an edge the other way (found by flipping the reference's `c <= 0` test to `c < 0` and
/// letting the random comparison above shrink its failures). Each must match exactly.
#[test]
fn centres_exactly_on_edges_follow_the_top_left_rule() {
    // (S, raw vertices, width, height)
    type Case = (u32, [(i32, i32); 3], u16, u16);
    let cases: [Case; 8] = [
        (1, [(1, 17), (3, 12), (10, 11)], 5, 15),
        (1, [(37, 1), (39, 0), (38, 2)], 19, 1),
        (12, [(17436, 64818), (13679, 61104), (14336, 63488)], 4, 17),
        (4, [(888, 720), (872, 768), (888, 760)], 64, 64),
        (4, [(288, 656), (272, 640), (288, 616)], 64, 64),
        (4, [(888, 488), (1428, 536), (856, 432)], 64, 64),
        (8, [(9984, 6528), (9472, 5504), (8439, 5028)], 64, 64),
        (8, [(2176, 14720), (2304, 14848), (2304, 14720)], 64, 64),
    ];
    for (s, pts, w, h) in cases {
        let p = RawPolygon {
            s,
            pts: pts.to_vec(),
        };
        for rule in Rule::ALL {
            let expected = reference(&p, rule, w, h);
            if let Err(msg) = check(&p, Filler::Scan(rule), w, h, &expected) {
                panic!("{msg}");
            }
            if let Err(msg) = check(&p, Filler::Xor, w, h, &reference(&p, Rule::EvenOdd, w, h)) {
                panic!("{msg}");
            }
        }
    }
}
