//! `polygons`: draws the polygon test scene (`host_tests::scenes::test_scene`) into a packed
//! 400 x 240 1-bpp framebuffer twice, once through the span path (`ScanConverter`) and
//! once through the XOR path (`XorFiller`), checks that both frames are byte-identical,
//! writes the picture as a PNG and prints the figures of the frame.
//!
//! ```text
//! cargo run --release -p host_tests --bin polygons -- [--out FILE.png] [--hash]
//!     [--scale N] [--frames N]
//! ```
//!
//! Exit status: 0 when both paths succeed and agree, 1 when they disagree or a fill
//! fails, 2 on a usage or I/O error.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use embedded_graphics::pixelcolor::BinaryColor;
use fixed::types::extra::U4;
use host_tests::image::{
    count_diff, count_set, fnv1a64, packed_pixel, write_packed_png, write_rgb_png,
};
use host_tests::scenes::{test_scene, to_screen, ScenePolygon, HEIGHT, WIDTH};
use pbuffer::{
    packed_len, FillRule, PackedFramebuffer, ScanConverter, ScreenPoint, Span, SpanSink, Viewport,
    XorFiller,
};

/// Sub-pixel bits of the vertices.
type Frac = U4;
const SUBPIXEL_BITS: u32 = 4;
type Frame = PackedFramebuffer<400, 240, { packed_len(400, 240) }>;
/// Edge capacity: the largest polygon of the scene has 16 vertices.
type Spans = ScanConverter<64>;
/// 13 words of 32 bits cover a 400-pixel row.
type Xor = XorFiller<64, 13>;

const USAGE: &str = "\
usage: polygons [--out FILE.png] [--hash] [--scale N] [--frames N]
  --out FILE.png  where to write the picture (default: docs/scene.png in the workspace)
  --hash          print only the FNV-1a 64 hash of the frame (hex); the PNG is written
                  only when --out is given too
  --scale N       PNG pixels per frame pixel (default 2)
  --frames N      frames per path for the timing (default 200; 0 skips the timing)";

struct Args {
    out: Option<PathBuf>,
    hash_only: bool,
    scale: usize,
    frames: u32,
}

fn parse_args() -> Result<Args, String> {
    let mut a = Args {
        out: None,
        hash_only: false,
        scale: 2,
        frames: 200,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        match arg.as_str() {
            "--out" => a.out = Some(PathBuf::from(value("--out")?)),
            "--hash" => a.hash_only = true,
            "--scale" => {
                a.scale = value("--scale")?
                    .parse()
                    .ok()
                    .filter(|&s| (1..=16).contains(&s))
                    .ok_or("--scale needs an integer in 1..=16")?
            }
            "--frames" => {
                a.frames = value("--frames")?
                    .parse()
                    .map_err(|_| "--frames needs a non-negative integer")?
            }
            "-h" | "--help" => {
                println!("{USAGE}");
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument {other:?}")),
        }
    }
    Ok(a)
}

/// A span sink that counts what goes through it.
struct Counting<'a, K> {
    inner: &'a mut K,
    spans: u64,
    span_pixels: u64,
}

impl<'a, K: SpanSink> Counting<'a, K> {
    fn new(inner: &'a mut K) -> Self {
        Self {
            inner,
            spans: 0,
            span_pixels: 0,
        }
    }
}

impl<K: SpanSink> SpanSink for Counting<'_, K> {
    type Color = K::Color;
    type Error = K::Error;
    fn viewport(&self) -> Viewport {
        self.inner.viewport()
    }
    fn fill_span(&mut self, span: Span, color: Self::Color) -> Result<(), Self::Error> {
        self.spans += 1;
        self.span_pixels += u64::from(span.x1().saturating_sub(span.x0()));
        self.inner.fill_span(span, color)
    }
    fn flush(&mut self) -> Result<(), Self::Error> {
        self.inner.flush()
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Path {
    /// ScanConverter for every polygon.
    Span,
    /// XorFiller for even-odd polygons; ScanConverter for non-zero ones (XorFiller
    /// computes parity only).
    Xor,
}

struct Prepared {
    points: Vec<ScreenPoint<Frac>>,
    rule: FillRule,
    color: BinaryColor,
}

fn color(on: bool) -> BinaryColor {
    if on {
        BinaryColor::On
    } else {
        BinaryColor::Off
    }
}

/// Draws the whole scene into `sink` along `path`. Err names the failing polygon.
fn draw<K: SpanSink<Color = BinaryColor>>(
    path: Path,
    scene: &[Prepared],
    sc: &mut Spans,
    xf: &mut Xor,
    sink: &mut K,
) -> Result<(), String>
where
    K::Error: core::fmt::Debug,
{
    for (i, p) in scene.iter().enumerate() {
        let r = if path == Path::Xor && p.rule == FillRule::EvenOdd {
            xf.fill(&p.points, p.color, sink)
        } else {
            sc.fill(&p.points, p.rule, p.color, sink)
        };
        r.map_err(|e| {
            let who = if path == Path::Xor && p.rule == FillRule::EvenOdd {
                "XorFiller"
            } else {
                "ScanConverter"
            };
            format!("{who} failed on polygon #{i}: {e:?}")
        })?;
    }
    Ok(())
}

struct Figures {
    spans: u64,
    span_pixels: u64,
    frame: Box<Frame>,
    us_per_frame: Option<f64>,
}

fn run(path: Path, scene: &[Prepared], frames: u32) -> Result<Figures, String> {
    let mut sc = Spans::new();
    let mut xf = Xor::new();
    let mut frame = Box::new(Frame::new());
    let mut counting = Counting::new(&mut *frame);
    draw(path, scene, &mut sc, &mut xf, &mut counting)?;
    let (spans, span_pixels) = (counting.spans, counting.span_pixels);

    let us_per_frame = if frames == 0 {
        None
    } else {
        // Best of 5 batches, after a warm-up batch.
        let batch = frames.div_ceil(5);
        let mut fb = Box::new(Frame::new());
        let mut best = f64::INFINITY;
        for round in 0..6 {
            let t = Instant::now();
            for _ in 0..batch {
                fb.clear();
                draw(path, scene, &mut sc, &mut xf, &mut *fb)?;
                std::hint::black_box(&mut *fb);
            }
            let us = t.elapsed().as_secs_f64() * 1e6 / f64::from(batch);
            if round > 0 {
                best = best.min(us);
            }
        }
        Some(best)
    };
    Ok(Figures {
        spans,
        span_pixels,
        frame,
        us_per_frame,
    })
}

fn default_out() -> PathBuf {
    let manifest = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .parent()
        .unwrap_or(manifest)
        .join("docs")
        .join("scene.png")
}

fn kinds(scene: &[ScenePolygon]) -> String {
    let mut v: Vec<(&str, usize)> = Vec::new();
    for p in scene {
        match v.iter_mut().find(|(k, _)| *k == p.kind) {
            Some((_, n)) => *n += 1,
            None => v.push((p.kind, 1)),
        }
    }
    v.iter()
        .map(|(k, n)| format!("{n} {k}"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("polygons: {e}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    let scene = test_scene();
    let prepared: Vec<Prepared> = scene
        .iter()
        .map(|p| Prepared {
            points: to_screen::<Frac>(&p.points),
            rule: p.rule,
            color: color(p.on),
        })
        .collect();
    let frames = if args.hash_only { 0 } else { args.frames };

    let results = run(Path::Span, &prepared, frames)
        .and_then(|a| run(Path::Xor, &prepared, frames).map(|b| (a, b)));
    let (a, b) = match results {
        Ok(r) => r,
        Err(e) => {
            eprintln!("polygons: {e}");
            return ExitCode::from(1);
        }
    };

    let (w, h) = (WIDTH, HEIGHT);
    let bytes = a.frame.as_bytes();
    let same = bytes == b.frame.as_bytes();
    let hash = fnv1a64(bytes);
    let out = args.out.clone().unwrap_or_else(default_out);

    if !same {
        let n = count_diff(bytes, b.frame.as_bytes(), w, h);
        eprintln!("polygons: MISMATCH: the span path and the XOR path differ in {n} pixels");
        let mut rgb = Vec::with_capacity(w * h * 3);
        let mut shown = 0;
        for y in 0..h {
            for x in 0..w {
                let (p, q) = (
                    packed_pixel(bytes, w, x, y),
                    packed_pixel(b.frame.as_bytes(), w, x, y),
                );
                if p != q && shown < 20 {
                    eprintln!("  pixel ({x}, {y}): span path {p}, XOR path {q}");
                    shown += 1;
                }
                rgb.extend_from_slice(match (p, q) {
                    (true, true) => &[0, 0, 0],
                    (false, false) => &[255, 255, 255],
                    (true, false) => &[230, 0, 0],
                    (false, true) => &[0, 0, 230],
                });
            }
        }
        let diff = out.with_file_name(format!(
            "{}-mismatch.png",
            out.file_stem().and_then(|s| s.to_str()).unwrap_or("scene")
        ));
        match write_rgb_png(&diff, &rgb, w, h, args.scale) {
            Ok(()) => eprintln!(
                "  wrote {} (black: both, red: span path only, blue: XOR path only)",
                diff.display()
            ),
            Err(e) => eprintln!("  cannot write {}: {e}", diff.display()),
        }
        return ExitCode::from(1);
    }

    if !args.hash_only || args.out.is_some() {
        if let Err(e) = write_packed_png(&out, bytes, w, h, args.scale) {
            eprintln!("polygons: cannot write {}: {e}", out.display());
            return ExitCode::from(2);
        }
    }
    if args.hash_only {
        println!("{hash:016x}");
        return ExitCode::SUCCESS;
    }

    let nonzero = scene.iter().filter(|p| p.rule == FillRule::NonZero).count();
    let set = count_set(bytes, w, h);
    let time = |f: &Figures| {
        f.us_per_frame
            .map_or_else(|| "-".to_string(), |us| format!("{us:.1} us"))
    };
    println!("pbuffer polygons: polygon test scene, {w} x {h}, 1 bpp packed, S = {SUBPIXEL_BITS} sub-pixel bits");
    println!("  polygons      {} ({})", scene.len(), kinds(&scene));
    println!();
    println!("  {:<16}{:>22}{:>22}", "", "span path", "XOR path");
    println!(
        "  {:<16}{:>22}{:>22}",
        "filler", "ScanConverter<64>", "XorFiller<64, 13>"
    );
    println!("  {:<16}{:>22}{:>22}", "spans", a.spans, b.spans);
    println!(
        "  {:<16}{:>22}{:>22}",
        "span pixels", a.span_pixels, b.span_pixels
    );
    println!(
        "  {:<16}{:>22}{:>22}",
        "pixels set",
        set,
        count_set(b.frame.as_bytes(), w, h)
    );
    println!(
        "  {:<16}{:>22}{:>22}",
        "FNV-1a 64",
        format!("{hash:016x}"),
        format!("{:016x}", fnv1a64(b.frame.as_bytes()))
    );
    println!("  {:<16}{:>22}{:>22}", "time / frame", time(&a), time(&b));
    println!();
    if nonzero > 0 {
        println!(
            "  XOR path: {nonzero} non-zero polygon(s) drawn by ScanConverter (XorFiller is even-odd only)"
        );
    }
    println!(
        "  frames identical: yes ({} bytes); wall time is the best of 5 batches of {} frames, clear included",
        bytes.len(),
        args.frames.div_ceil(5)
    );
    println!(
        "  wrote {} ({} x {}, scale {})",
        out.display(),
        w * args.scale,
        h * args.scale,
        args.scale
    );
    ExitCode::SUCCESS
}
