//! `bench`: instruction counts (valgrind callgrind) for filling triangles and polygons
//! into a 400 x 240 1-bpp framebuffer, pbuffer against embedded-graphics.
//!
//! ```text
//! cargo run --profile figures -p host_tests --bin bench [-- --markdown] [-- --jobs N]
//! cargo run --profile figures -p host_tests --bin bench -- --scene3d [--markdown]
//! cargo run --profile figures -p host_tests --bin bench -- --firmware [--m4 FILE]
//! cargo run --profile figures -p host_tests --bin bench -- --help
//! ```
//!
//! `--firmware` counts the firmware examples' frames on the host and sets them against
//! the emulated Cortex-M4's counts of the same frames (`firmware.rs`).
//!
//! `--scene3d` runs the 3-D section instead (`host_tests::tools::bench3d`): three models at
//! two sizes with dashed hidden lines, the library's code-fill and Z-buffer engines
//! against the plain f32 P-buffer baseline.
//!
//! The binary re-executes itself under `valgrind --tool=callgrind` once per measurement
//! (`--child ID`), with collection switched on only inside `measured_region`, and reads
//! the instruction total (Ir) from the callgrind output (`host_tests::tools::callgrind`). Scene
//! setup, vertex conversion and framebuffer allocation happen outside the measured
//! region.
//!
//! Variants:
//! * (a) `span`: pbuffer `ScanConverter` -> `PackedFramebuffer` (SpanSink, word-wide spans)
//! * (b) `xor`: pbuffer `XorFiller` -> `PackedFramebuffer`
//! * (c1) `eg-packed`: embedded-graphics 0.8 `Triangle` + `PrimitiveStyle::with_fill`
//!   -> `PackedFramebuffer` (e-g calls `fill_solid` once per scanline)
//! * (c2) `eg-naive`: the same into [`fill::NaiveFramebuffer`], which implements only `draw_iter`
//!
//! Besides the counts it checks, natively, that (a) and (b) set exactly the same pixels
//! (exit status 1 otherwise) and reports how many pixels embedded-graphics sets
//! differently (its triangle rule is not the top-left rule of CONVENTIONS.md).
//!
//! Without valgrind the checks still run; the instruction counts are skipped (exit 2).

mod fills_report;
mod firmware;

use std::convert::Infallible;
use std::process::ExitCode;

use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Triangle};
use fixed::types::extra::U4;
use host_tests::image::{count_diff, count_set};
use host_tests::measure::measured_region;
use host_tests::scenes::{
    bench_triangles, int_triangle_to_screen, large_polygons, sized_triangles, to_screen,
    IntTriangle, HEIGHT, WIDTH,
};
use host_tests::tools::cli::{help_text, parse_flags, BenchFlags};
use pbuffer::{packed_len, FillRule, PackedFramebuffer, ScanConverter, ScreenPoint, XorFiller};

type Frac = U4;
const LEN: usize = packed_len(400, 240);
type Frame = PackedFramebuffer<400, 240, LEN>;
/// Row words for 400 pixels: ceil(400 / 32).
const WORDS: usize = 13;
/// Edge capacity for triangles and for the large polygons.
const EDGES_TRI: usize = 64;
const EDGES_POLY: usize = 256;
/// Sizes (circumscribed-circle diameters, px) and count of the scaling sets.
const SCALE_SIZES: [u32; 7] = [4, 8, 16, 32, 64, 128, 232];
const SCALE_COUNT: usize = 64;

/// A plain packed 1-bpp framebuffer (same layout as `PackedFramebuffer`) that implements
/// only `DrawTarget::draw_iter`: every primitive reaches it pixel by pixel, as it does
/// on most simple display drivers.
struct NaiveFramebuffer {
    buf: Box<[u8; LEN]>,
}

impl NaiveFramebuffer {
    fn new() -> Self {
        Self {
            buf: Box::new([0; LEN]),
        }
    }
}

impl OriginDimensions for NaiveFramebuffer {
    fn size(&self) -> Size {
        Size::new(WIDTH as u32, HEIGHT as u32)
    }
}

impl DrawTarget for NaiveFramebuffer {
    type Color = BinaryColor;
    type Error = Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<BinaryColor>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            if let (Ok(x), Ok(y)) = (usize::try_from(p.x), usize::try_from(p.y)) {
                if x < WIDTH && y < HEIGHT {
                    let i = y * WIDTH.div_ceil(8) + x / 8;
                    let m = 0x80u8 >> (x % 8);
                    if c.is_on() {
                        self.buf[i] |= m;
                    } else {
                        self.buf[i] &= !m;
                    }
                }
            }
        }
        Ok(())
    }
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Variant {
    Span,
    Xor,
    EgPacked,
    EgNaive,
    /// Calibration: an empty measured region.
    Empty,
}

impl Variant {
    const ALL: [Variant; 4] = [
        Variant::Span,
        Variant::Xor,
        Variant::EgPacked,
        Variant::EgNaive,
    ];
    fn key(self) -> &'static str {
        match self {
            Variant::Span => "span",
            Variant::Xor => "xor",
            Variant::EgPacked => "eg-packed",
            Variant::EgNaive => "eg-naive",
            Variant::Empty => "empty",
        }
    }
    fn label(self) -> &'static str {
        match self {
            Variant::Span => "(a) pbuffer ScanConverter -> PackedFramebuffer",
            Variant::Xor => "(b) pbuffer XorFiller -> PackedFramebuffer",
            Variant::EgPacked => "(c1) e-g Triangle -> PackedFramebuffer (fill_solid)",
            Variant::EgNaive => "(c2) e-g Triangle -> naive fb (draw_iter only)",
            Variant::Empty => "empty region",
        }
    }
    fn from_key(k: &str) -> Option<Self> {
        Variant::ALL
            .into_iter()
            .chain([Variant::Empty])
            .find(|v| v.key() == k)
    }
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Set {
    /// The fixed benchmark set (`scenes::bench_triangles`).
    Bench,
    /// One of `scenes::large_polygons`.
    Large(usize),
    /// `scenes::sized_triangles(size, SCALE_COUNT, ..)`.
    Scale(u32),
}

impl Set {
    fn key(self) -> String {
        match self {
            Set::Bench => "bench".into(),
            Set::Large(i) => format!("large{i}"),
            Set::Scale(s) => format!("scale{s}"),
        }
    }
    fn from_key(k: &str) -> Option<Self> {
        if k == "bench" {
            Some(Set::Bench)
        } else if let Some(i) = k.strip_prefix("large") {
            i.parse().ok().map(Set::Large)
        } else {
            k.strip_prefix("scale")
                .and_then(|s| s.parse().ok())
                .map(Set::Scale)
        }
    }
}

enum Shapes {
    Triangles(Vec<IntTriangle>),
    Polygons(Vec<Vec<(f64, f64)>>),
}

fn shapes(set: Set) -> Shapes {
    match set {
        Set::Bench => Shapes::Triangles(bench_triangles()),
        Set::Large(i) => Shapes::Polygons(vec![large_polygons()[i].1.clone()]),
        Set::Scale(s) => Shapes::Triangles(sized_triangles(
            f64::from(s),
            SCALE_COUNT,
            0x5CA1_E000 + u64::from(s),
        )),
    }
}

fn eg_triangle(t: &IntTriangle) -> Triangle {
    let [a, b, c] = t.map(|(x, y)| Point::new(x, y));
    Triangle::new(a, b, c)
}

fn fill_polys_span<const E: usize>(polys: &[Vec<ScreenPoint<Frac>>], fb: &mut Frame) {
    let mut sc = ScanConverter::<E>::new();
    measured_region(&mut || {
        for p in polys {
            if let Err(e) = sc.fill(p, FillRule::EvenOdd, BinaryColor::On, fb) {
                panic!("ScanConverter failed: {e:?}");
            }
        }
    });
}

fn fill_polys_xor<const E: usize>(polys: &[Vec<ScreenPoint<Frac>>], fb: &mut Frame) {
    let mut xf = XorFiller::<E, WORDS>::new();
    measured_region(&mut || {
        for p in polys {
            if let Err(e) = xf.fill(p, BinaryColor::On, fb) {
                panic!("XorFiller failed: {e:?}");
            }
        }
    });
}

/// Draws `shapes` with `variant` inside the measured region; returns the frame bytes.
fn execute(variant: Variant, shapes: &Shapes) -> Vec<u8> {
    let mut fb = Box::new(Frame::new());
    match (variant, shapes) {
        (Variant::Empty, _) => measured_region(&mut || {}),
        (Variant::Span | Variant::Xor, Shapes::Triangles(t)) => {
            let tris: Vec<[ScreenPoint<Frac>; 3]> =
                t.iter().map(int_triangle_to_screen::<Frac>).collect();
            if variant == Variant::Span {
                let mut sc = ScanConverter::<EDGES_TRI>::new();
                measured_region(&mut || {
                    for p in &tris {
                        if let Err(e) = sc.fill(p, FillRule::EvenOdd, BinaryColor::On, &mut *fb) {
                            panic!("ScanConverter failed: {e:?}");
                        }
                    }
                });
            } else {
                let mut xf = XorFiller::<EDGES_TRI, WORDS>::new();
                measured_region(&mut || {
                    for p in &tris {
                        if let Err(e) = xf.fill(p, BinaryColor::On, &mut *fb) {
                            panic!("XorFiller failed: {e:?}");
                        }
                    }
                });
            }
        }
        (Variant::Span | Variant::Xor, Shapes::Polygons(p)) => {
            let polys: Vec<Vec<ScreenPoint<Frac>>> =
                p.iter().map(|p| to_screen::<Frac>(p)).collect();
            if variant == Variant::Span {
                fill_polys_span::<EDGES_POLY>(&polys, &mut fb);
            } else {
                fill_polys_xor::<EDGES_POLY>(&polys, &mut fb);
            }
        }
        (Variant::EgPacked, Shapes::Triangles(t)) => {
            let style = PrimitiveStyle::with_fill(BinaryColor::On);
            let tris: Vec<_> = t
                .iter()
                .map(|t| eg_triangle(t).into_styled(style))
                .collect();
            measured_region(&mut || {
                for t in &tris {
                    let Ok(()) = t.draw(&mut *fb);
                }
            });
        }
        (Variant::EgNaive, Shapes::Triangles(t)) => {
            let style = PrimitiveStyle::with_fill(BinaryColor::On);
            let tris: Vec<_> = t
                .iter()
                .map(|t| eg_triangle(t).into_styled(style))
                .collect();
            let mut naive = NaiveFramebuffer::new();
            measured_region(&mut || {
                for t in &tris {
                    let Ok(()) = t.draw(&mut naive);
                }
            });
            return naive.buf.to_vec();
        }
        (Variant::EgPacked | Variant::EgNaive, Shapes::Polygons(_)) => {
            panic!("embedded-graphics has no polygon fill")
        }
    }
    fb.as_bytes().to_vec()
}

/// Per-triangle comparison of pbuffer (span, xor) and embedded-graphics.
#[derive(Default, Debug)]
struct TriangleCheck {
    triangles: usize,
    /// Pixels summed over triangles drawn one at a time.
    pb_pixels: usize,
    eg_pixels: usize,
    /// Pixels where the span and XOR paths differ (must be 0).
    span_xor_diff: usize,
    /// Pixels set by e-g but not by pbuffer, and the other way round.
    eg_extra: usize,
    eg_missing: usize,
    /// Triangles where e-g and pbuffer differ.
    eg_tris_differing: usize,
    /// First triangle where span and XOR differ.
    first_span_xor: Option<(IntTriangle, usize)>,
}

fn check_triangles(tris: &[IntTriangle]) -> TriangleCheck {
    let mut c = TriangleCheck {
        triangles: tris.len(),
        ..Default::default()
    };
    let mut sc = ScanConverter::<EDGES_TRI>::new();
    let mut xf = XorFiller::<EDGES_TRI, WORDS>::new();
    let style = PrimitiveStyle::with_fill(BinaryColor::On);
    let (mut a, mut b, mut e) = (
        Box::new(Frame::new()),
        Box::new(Frame::new()),
        Box::new(Frame::new()),
    );
    for t in tris {
        a.clear();
        b.clear();
        e.clear();
        let p = int_triangle_to_screen::<Frac>(t);
        sc.fill(&p, FillRule::EvenOdd, BinaryColor::On, &mut *a)
            .expect("ScanConverter");
        xf.fill(&p, BinaryColor::On, &mut *b).expect("XorFiller");
        let Ok(()) = eg_triangle(t).into_styled(style).draw(&mut *e);
        let (a, b, e) = (a.as_bytes(), b.as_bytes(), e.as_bytes());
        let sx = count_diff(a, b, WIDTH, HEIGHT);
        if sx > 0 && c.first_span_xor.is_none() {
            c.first_span_xor = Some((*t, sx));
        }
        c.span_xor_diff += sx;
        c.pb_pixels += count_set(a, WIDTH, HEIGHT);
        c.eg_pixels += count_set(e, WIDTH, HEIGHT);
        let extra: Vec<u8> = e.iter().zip(a).map(|(e, a)| e & !a).collect();
        let missing: Vec<u8> = e.iter().zip(a).map(|(e, a)| !e & a).collect();
        let (x, m) = (
            count_set(&extra, WIDTH, HEIGHT),
            count_set(&missing, WIDTH, HEIGHT),
        );
        c.eg_extra += x;
        c.eg_missing += m;
        c.eg_tris_differing += usize::from(x + m > 0);
    }
    c
}

fn job_id(set: Set, v: Variant) -> String {
    format!("{}/{}", set.key(), v.key())
}

/// Prints a 3-D child job's pixels (or its error, exit 2).
fn pixels_or_error(r: Result<usize, String>) -> ExitCode {
    match r {
        Ok(pixels) => {
            println!("pixels={pixels}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("bench: {e}");
            ExitCode::from(2)
        }
    }
}

/// Runs one job under callgrind: prints the pixels set in its frame.
fn child(id: &str) -> ExitCode {
    if let Some(key) = id.strip_prefix("fw/") {
        return pixels_or_error(firmware::child(key));
    }
    if let Some(name) = id.strip_prefix("scene3d/") {
        return pixels_or_error(host_tests::tools::bench3d::child(name));
    }
    let parsed = id
        .split_once('/')
        .and_then(|(s, v)| Some((Set::from_key(s)?, Variant::from_key(v)?)));
    let Some((set, variant)) = parsed else {
        eprintln!("bench: bad child id {id:?}");
        return ExitCode::from(2);
    };
    let bytes = execute(variant, &shapes(set));
    println!("pixels={}", count_set(&bytes, WIDTH, HEIGHT));
    ExitCode::SUCCESS
}

// ---------------------------------------------------------------- main

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [flag, id] = args.as_slice() {
        if flag == "--child" {
            return child(id);
        }
    }
    let flags: BenchFlags = match parse_flags("bench", &args) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("bench: {e}");
            return ExitCode::from(2);
        }
    };
    if flags.help {
        print!("{}", help_text::<BenchFlags>());
        return ExitCode::SUCCESS;
    }
    let jobs = flags
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let markdown = flags.markdown;
    if cfg!(debug_assertions) {
        eprintln!("bench: warning: debug build; run with --release for meaningful counts");
    }
    if flags.firmware {
        return firmware::run(flags.m4.as_deref().unwrap_or(firmware::DEFAULT_M4), jobs);
    }
    if flags.ram {
        return host_tests::tools::bench3d::run_ram(markdown);
    }
    if flags.scene3d {
        return host_tests::tools::bench3d::run(markdown, jobs);
    }

    fills_report::run(markdown, jobs)
}
