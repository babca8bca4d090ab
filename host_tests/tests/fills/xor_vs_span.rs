//! The modulo-2 edge-flag filler (`XorFiller`) draws exactly the pixels the scan converter
//! draws under the even-odd rule, and both equal the f64 reference, for random polygons.

use crate::support;

use host_tests::random::{polygon, Rng, Shape};
use host_tests::reference::{Polygon, Rule};
use support::{check, minimize, render, Filler};

/// Compares XorFiller, ScanConverter(EvenOdd) and the reference on `count` polygons.
fn compare(seed: u64, count: usize, width: u16, height: u16) {
    let mut rng = Rng::new(seed);
    let mut failures = Vec::new();
    let mut pixels = 0usize;
    let reference = |p: &host_tests::random::RawPolygon| {
        Polygon::new(&p.to_f64(), f64::from(width.max(height))).rasterize(
            Rule::EvenOdd,
            u32::from(width),
            u32::from(height),
        )
    };
    for _ in 0..count {
        let s = rng.pick(&[0, 4, 8]);
        let shape = rng.pick(&Shape::ALL);
        let p = polygon(&mut rng, shape, s, u32::from(width), u32::from(height));
        let expected = reference(&p);
        pixels += expected.len();
        if let Err(msg) = check(&p, Filler::Xor, width, height, &expected) {
            let small = minimize(&p, |q| {
                check(q, Filler::Xor, width, height, &reference(q)).is_err()
            });
            let small_msg = check(&small, Filler::Xor, width, height, &reference(&small))
                .err()
                .unwrap_or_default();
            failures.push(format!("{shape:?}: {msg}\n    minimal: {small_msg}"));
            continue;
        }
        // Same pixels as the scan converter (which span_vs_reference checks in depth).
        let xor = render(&p, Filler::Xor, width, height);
        let scan =
            std::panic::catch_unwind(|| render(&p, Filler::Scan(Rule::EvenOdd), width, height));
        if scan.as_ref().map_or(true, |scan| *scan != xor) {
            failures.push(format!(
                "XorFiller and ScanConverter(EvenOdd) differ: S={} {:?}",
                p.s, p.pts
            ));
        }
    }
    println!(
        "XorFiller on {width}x{height}: {count} polygons, {pixels} pixels compared, {} failures",
        failures.len()
    );
    assert!(
        failures.is_empty(),
        "{} of {count} polygons differ; first ones:\n{}",
        failures.len(),
        failures
            .iter()
            .take(5)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

#[test]
fn xor_filler_equals_even_odd_scan_converter_and_reference_on_64x64() {
    compare(0x0e0e_0064, 60_000, 64, 64);
}

#[test]
fn xor_filler_equals_even_odd_scan_converter_and_reference_on_400x240() {
    compare(0x0e0e_0400, 6_000, 400, 240);
}

/// Widths that are not a multiple of the 32-bit row word, and 1-pixel frames.
#[test]
fn xor_filler_equals_reference_on_odd_widths() {
    for (i, (w, h)) in [(1, 1), (31, 7), (33, 9), (63, 5), (65, 12), (97, 3)]
        .into_iter()
        .enumerate()
    {
        compare(0x0e0e_0001 + i as u64, 2_000, w, h);
    }
}
