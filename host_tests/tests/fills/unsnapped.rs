//! Snapping error: polygons given at full f64 precision are snapped by the library
//! (`ScreenPoint::from_f64`, round to nearest) to the 1/2^S grid. Compared with the
//! reference on the *unsnapped* geometry, a pixel may differ only if its centre lies within
//! the snapping distance of a true edge.
//!
//! Bound: each vertex moves by at most 2^-(S+1) per coordinate, i.e. by at most
//! d = sqrt(2) * 2^-(S+1). Moving the vertices linearly from the true to the snapped
//! positions moves every point of every edge by at most d, and a pixel centre changes
//! sides only when an edge passes over it; so a differing centre is within d of a true edge.

use crate::support;

use fixed::types::extra::{LeEqU32, U0, U12, U2, U4, U8};
use host_tests::random::{unsnapped_polygon, RawPolygon, Rng, Shape};
use host_tests::reference::{distance_to_boundary, Polygon, Rule};
use pbuffer::ScreenPoint;
use support::{check, differences, fill_raw, CountSink, Filler};

/// The library's snapping of `pts` to `F`, as raw values.
fn snap<F: LeEqU32>(pts: &[(f64, f64)]) -> Vec<(i32, i32)> {
    pts.iter()
        .map(|&(x, y)| {
            let p = ScreenPoint::<F>::from_f64(x, y).expect("in range");
            (p.x.to_bits(), p.y.to_bits())
        })
        .collect()
}

fn snap_dyn(s: u32, pts: &[(f64, f64)]) -> Vec<(i32, i32)> {
    match s {
        0 => snap::<U0>(pts),
        2 => snap::<U2>(pts),
        4 => snap::<U4>(pts),
        8 => snap::<U8>(pts),
        12 => snap::<U12>(pts),
        _ => unreachable!(),
    }
}

/// Per-S statistics.
#[derive(Default)]
struct Stats {
    polygons: usize,
    pixels: usize,
    differing: usize,
    max_distance: f64,
}

fn run(s: u32, seed: u64, count: usize, width: u16, height: u16) -> Stats {
    let bound = std::f64::consts::SQRT_2 * 0.5f64.powi(s as i32 + 1);
    let slack = 1e-9; // the distance itself is computed in f64
    let mut rng = Rng::new(seed);
    let mut stats = Stats::default();
    for _ in 0..count {
        let shape = rng.pick(&Shape::ALL);
        let rule = rng.pick(&Rule::ALL);
        let true_pts = unsnapped_polygon(&mut rng, shape, u32::from(width), u32::from(height));
        let raw = snap_dyn(s, &true_pts);
        let snapped = RawPolygon {
            s,
            pts: raw.clone(),
        };
        // from_f64 rounds to the nearest grid value.
        for (&(x, y), &(sx, sy)) in true_pts.iter().zip(&snapped.to_f64()) {
            let half = 0.5f64.powi(s as i32 + 1);
            assert!(
                (x - sx).abs() <= half && (y - sy).abs() <= half,
                "from_f64({x}, {y}) = ({sx}, {sy}) at S={s}"
            );
        }
        // On the snapped vertices the library is exact.
        let extent = f64::from(width.max(height));
        let on_snapped = Polygon::new(&snapped.to_f64(), extent).rasterize(
            rule,
            u32::from(width),
            u32::from(height),
        );
        if let Err(msg) = check(&snapped, Filler::Scan(rule), width, height, &on_snapped) {
            panic!("library differs from the reference on snapped vertices: {msg}");
        }
        // Against the true geometry, only pixels near a true edge may differ.
        let truth =
            Polygon::new(&true_pts, extent).rasterize(rule, u32::from(width), u32::from(height));
        let mut sink = CountSink::new(width, height);
        fill_raw(s, &raw, Filler::Scan(rule), &mut sink).expect("fill");
        for (x, y, want, got) in differences(&truth, &sink.covered(), width) {
            let d = distance_to_boundary(&true_pts, (x as f64 + 0.5, y as f64 + 0.5));
            assert!(
                d <= bound + slack,
                "S={s} {rule:?}: pixel ({x},{y}) is {} (truth {}) but its centre is {d} px from the \
                 true boundary (bound {bound}); true vertices {true_pts:?}, snapped {raw:?}",
                u8::from(got),
                u8::from(want)
            );
            stats.max_distance = stats.max_distance.max(d);
            stats.differing += 1;
        }
        stats.polygons += 1;
        stats.pixels += truth.len();
    }
    println!(
        "S={s:2}: {} polygons, {} pixels, {} differ from the unsnapped truth ({:.2e}), farthest {:.4} px from a true edge (bound {bound:.4})",
        stats.polygons,
        stats.pixels,
        stats.differing,
        stats.differing as f64 / stats.pixels as f64,
        stats.max_distance
    );
    stats
}

#[test]
fn snapping_errors_stay_within_the_snapping_distance_of_true_edges() {
    let mut totals = Vec::new();
    for s in [0, 2, 4, 8, 12] {
        let stats = run(s, 0xdead_0000 + u64::from(s), 10_000, 64, 64);
        totals.push((s, stats.differing));
    }
    // More sub-pixel bits, fewer errors: S=0 must err somewhere in 10000 random polygons,
    // and S=12 much less often than S=0.
    let (d0, d12) = (totals[0].1, totals[4].1);
    assert!(
        d0 > 0,
        "S=0 snapping must change some pixels of random polygons"
    );
    assert!(
        d12 * 20 < d0,
        "S=12 ({d12}) should err far less often than S=0 ({d0})"
    );
}

#[test]
fn snapping_errors_on_400x240_stay_within_bound() {
    for s in [0, 4, 8] {
        run(s, 0xbeef_0000 + u64::from(s), 1_000, 400, 240);
    }
}
