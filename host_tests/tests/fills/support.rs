//! Shared helpers of the 2-D rasterizer suites of this binary (`use crate::support;`).
#![allow(dead_code)] // each suite uses a different subset of the helpers

use std::convert::Infallible;

use embedded_graphics::pixelcolor::BinaryColor;
use fixed::types::extra::{LeEqU32, U0, U1, U10, U11, U12, U2, U3, U4, U5, U6, U7, U8, U9};
use host_tests::random::RawPolygon;
use host_tests::reference::Rule;
use pbuffer::{Error, FillRule, ScanConverter, ScreenPoint, Span, SpanSink, Viewport, XorFiller};

/// Edge capacity used by the random tests (polygons have at most 16 vertices).
pub const EDGES: usize = 64;
/// Row words of the XOR filler: 32 * 32 = 1024 px, enough for 1000x1000.
pub const WORDS: usize = 32;

/// A span sink that counts coverage per pixel. It asserts the span contract: every span
/// lies inside the viewport (`x0 < x1 <= width`, `y < height`) and no pixel is written
/// twice within one polygon (polygons are delimited by [`CountSink::begin_polygon`]).
pub struct CountSink {
    pub width: u16,
    pub height: u16,
    /// Coverage count per pixel, row-major, over all polygons since the last clear.
    pub counts: Vec<u32>,
    /// Id of the polygon that last wrote each pixel.
    stamp: Vec<u32>,
    polygon: u32,
    /// Spans received, and `flush` calls.
    pub spans: usize,
    pub flushes: usize,
}

impl CountSink {
    pub fn new(width: u16, height: u16) -> Self {
        let n = usize::from(width) * usize::from(height);
        CountSink {
            width,
            height,
            counts: vec![0; n],
            stamp: vec![0; n],
            polygon: 1,
            spans: 0,
            flushes: 0,
        }
    }

    /// Starts a new polygon: writes after this may touch pixels of earlier polygons once.
    pub fn begin_polygon(&mut self) {
        self.polygon += 1;
    }

    /// Forgets all coverage.
    pub fn clear(&mut self) {
        self.counts.iter_mut().for_each(|c| *c = 0);
        self.begin_polygon();
        self.spans = 0;
        self.flushes = 0;
    }

    /// Pixels with a non-zero count.
    pub fn covered(&self) -> Vec<bool> {
        self.counts.iter().map(|&c| c > 0).collect()
    }

    pub fn covered_count(&self) -> usize {
        self.counts.iter().filter(|&&c| c > 0).count()
    }
}

impl SpanSink for CountSink {
    type Color = BinaryColor;
    type Error = Infallible;

    fn viewport(&self) -> Viewport {
        Viewport {
            width: self.width,
            height: self.height,
        }
    }

    fn fill_span(&mut self, span: Span, color: BinaryColor) -> Result<(), Infallible> {
        assert_eq!(color, BinaryColor::On, "span of an unexpected colour");
        assert!(
            span.x0() < span.x1() && span.x1() <= self.width && span.y() < self.height,
            "span {span:?} outside the {}x{} viewport",
            self.width,
            self.height
        );
        self.spans += 1;
        let row = usize::from(span.y()) * usize::from(self.width);
        for x in span.x0()..span.x1() {
            let i = row + usize::from(x);
            assert_ne!(
                self.stamp[i],
                self.polygon,
                "pixel ({x}, {}) written twice by one polygon",
                span.y()
            );
            self.stamp[i] = self.polygon;
            self.counts[i] += 1;
        }
        Ok(())
    }

    fn flush(&mut self) -> Result<(), Infallible> {
        self.flushes += 1;
        Ok(())
    }
}

pub fn fill_rule(rule: Rule) -> FillRule {
    match rule {
        Rule::EvenOdd => FillRule::EvenOdd,
        Rule::NonZero => FillRule::NonZero,
    }
}

/// Which filler draws a polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filler {
    Scan(Rule),
    Xor,
}

/// Library points from raw fixed-point values, `S` chosen at run time.
pub fn points<F: LeEqU32>(raw: &[(i32, i32)]) -> Vec<ScreenPoint<F>> {
    raw.iter()
        .map(|&(x, y)| ScreenPoint::<F>::from_bits(x, y))
        .collect()
}

fn fill_typed<F: LeEqU32>(
    raw: &[(i32, i32)],
    filler: Filler,
    sink: &mut CountSink,
) -> Result<(), Error> {
    let pts = points::<F>(raw);
    sink.begin_polygon();
    match filler {
        Filler::Scan(rule) => {
            ScanConverter::<EDGES>::new().fill(&pts, fill_rule(rule), BinaryColor::On, sink)
        }
        Filler::Xor => XorFiller::<EDGES, WORDS>::new().fill(&pts, BinaryColor::On, sink),
    }
}

/// Draws the raw polygon with `s` sub-pixel bits (0..=12) into `sink`.
pub fn fill_raw(
    s: u32,
    raw: &[(i32, i32)],
    filler: Filler,
    sink: &mut CountSink,
) -> Result<(), Error> {
    match s {
        0 => fill_typed::<U0>(raw, filler, sink),
        1 => fill_typed::<U1>(raw, filler, sink),
        2 => fill_typed::<U2>(raw, filler, sink),
        3 => fill_typed::<U3>(raw, filler, sink),
        4 => fill_typed::<U4>(raw, filler, sink),
        5 => fill_typed::<U5>(raw, filler, sink),
        6 => fill_typed::<U6>(raw, filler, sink),
        7 => fill_typed::<U7>(raw, filler, sink),
        8 => fill_typed::<U8>(raw, filler, sink),
        9 => fill_typed::<U9>(raw, filler, sink),
        10 => fill_typed::<U10>(raw, filler, sink),
        11 => fill_typed::<U11>(raw, filler, sink),
        12 => fill_typed::<U12>(raw, filler, sink),
        _ => panic!("S = {s} is not supported"),
    }
}

/// The pixels one filler draws for one polygon on a fresh `width x height` frame.
pub fn render(p: &RawPolygon, filler: Filler, width: u16, height: u16) -> Vec<bool> {
    let mut sink = CountSink::new(width, height);
    fill_raw(p.s, &p.pts, filler, &mut sink).expect("fill failed");
    assert_eq!(
        sink.flushes, 1,
        "flush must be called once at the end of the polygon"
    );
    sink.covered()
}

/// Draws `p` with `filler` and compares with `expected`; `Err(description)` on any
/// difference or panic (the sink's contract assertions panic).
pub fn check(
    p: &RawPolygon,
    filler: Filler,
    width: u16,
    height: u16,
    expected: &[bool],
) -> Result<(), String> {
    let got = std::panic::catch_unwind(|| render(p, filler, width, height));
    match got {
        Ok(got) => {
            let diffs = differences(expected, &got, width);
            if diffs.is_empty() {
                Ok(())
            } else {
                Err(describe(p, filler, width, height, &diffs))
            }
        }
        Err(e) => {
            let msg = e
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(format!(
                "{} -- panicked: {msg}",
                describe(p, filler, width, height, &[])
            ))
        }
    }
}

/// `(x, y, expected, got)` of every pixel where two pictures differ.
pub fn differences(expected: &[bool], got: &[bool], width: u16) -> Vec<(usize, usize, bool, bool)> {
    let w = usize::from(width);
    expected
        .iter()
        .zip(got)
        .enumerate()
        .filter(|(_, (e, g))| e != g)
        .map(|(i, (&e, &g))| (i % w, i / w, e, g))
        .collect()
}

/// A reproducible description of a failing case, for the report to the lead.
pub fn describe(
    p: &RawPolygon,
    filler: Filler,
    width: u16,
    height: u16,
    diffs: &[(usize, usize, bool, bool)],
) -> String {
    let shown: Vec<String> = diffs
        .iter()
        .take(8)
        .map(|(x, y, e, g)| format!("({x},{y}) expected {} got {}", u8::from(*e), u8::from(*g)))
        .collect();
    format!(
        "S={} raw vertices {:?} (= {:?}) filler {:?} viewport {}x{}: {} differing pixels: {}",
        p.s,
        p.pts,
        p.to_f64(),
        filler,
        width,
        height,
        diffs.len(),
        shown.join(", ")
    )
}

/// Greedily shrinks a failing polygon by dropping vertices while `fails` still holds
/// (moving vertices would change the exact ties that may be the cause).
pub fn minimize(p: &RawPolygon, fails: impl Fn(&RawPolygon) -> bool) -> RawPolygon {
    let mut best = p.clone();
    loop {
        let mut improved = false;
        for i in 0..best.pts.len() {
            if best.pts.len() <= 3 {
                break;
            }
            let mut q = best.clone();
            q.pts.remove(i);
            if fails(&q) {
                best = q;
                improved = true;
                break;
            }
        }
        if !improved {
            return best;
        }
    }
}
