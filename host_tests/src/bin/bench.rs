//! `bench`: instruction counts (valgrind callgrind) for filling triangles and polygons
//! into a 400 x 240 1-bpp framebuffer, pbuffer against embedded-graphics.
//!
//! ```text
//! cargo run --release -p host_tests --bin bench [-- --markdown] [-- --jobs N]
//! cargo run --release -p host_tests --bin bench -- --scene3d [--markdown]
//! ```
//!
//! `--scene3d` runs the 3-D section instead: Suzanne at 400 x 240 with dashed hidden
//! lines, the library's `ZBufferRenderer` (band heights 8, 32, 240; only the `render`
//! call measured) against the plain f32 P-buffer baseline (`host_tests::baseline`;
//! only the frame measured, welding and adjacency done beforehand), in the same run.
//!
//! The binary re-executes itself under `valgrind --tool=callgrind` once per measurement
//! (`--child ID`), with collection switched on only inside [`measured_region`], and reads
//! the instruction total (Ir) from the callgrind output. Scene setup, vertex conversion
//! and framebuffer allocation happen outside the measured region.
//!
//! Variants:
//! * (a) `span`: pbuffer `ScanConverter` -> `PackedFramebuffer` (SpanSink, word-wide spans)
//! * (b) `xor`: pbuffer `XorFiller` -> `PackedFramebuffer`
//! * (c1) `eg-packed`: embedded-graphics 0.8 `Triangle` + `PrimitiveStyle::with_fill`
//!   -> `PackedFramebuffer` (e-g calls `fill_solid` once per scanline)
//! * (c2) `eg-naive`: the same into [`NaiveFramebuffer`], which implements only `draw_iter`
//!
//! Besides the counts it checks, natively, that (a) and (b) set exactly the same pixels
//! (exit status 1 otherwise) and reports how many pixels embedded-graphics sets
//! differently (its triangle rule is not the top-left rule of CONVENTIONS.md).
//!
//! Without valgrind the checks still run; the instruction counts are skipped (exit 2).

use std::convert::Infallible;
use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, ExitCode};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Triangle};
use fixed::types::extra::U4;
use host_tests::image::{count_diff, count_set, packed_pixel};
use host_tests::scenes::{
    bench_triangles, int_triangle_to_screen, large_polygons, sized_triangles, to_screen,
    IntTriangle, HEIGHT, WIDTH,
};
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

/// Everything between entry and exit of this function is counted (`--toggle-collect`).
#[inline(never)]
fn measured_region(f: &mut dyn FnMut()) {
    f();
}

/// A plain packed 1-bpp framebuffer (same layout as `PackedFramebuffer`) that implements
/// only `DrawTarget::draw_iter`: every primitive reaches it pixel by pixel, as it does
/// on most simple display drivers.
pub struct NaiveFramebuffer {
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

// ---------------------------------------------------------------- callgrind plumbing

fn tool_version(cmd: &str, arg: &str) -> Option<String> {
    let out = Command::new(cmd).arg(arg).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into())
}

struct Measured {
    ir: u64,
    /// Pixels set in the frame, as reported by the child.
    pixels: usize,
}

fn callgrind(exe: &Path, dir: &Path, id: &str) -> Result<Measured, String> {
    let out_file = dir.join(format!("{}.callgrind", id.replace('/', "_")));
    let out = Command::new("valgrind")
        .arg("--tool=callgrind")
        .arg(format!("--callgrind-out-file={}", out_file.display()))
        .arg("--collect-atstart=no")
        .arg("--toggle-collect=*measured_region*")
        .arg(exe)
        .arg("--child")
        .arg(id)
        .output()
        .map_err(|e| format!("cannot run valgrind: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "valgrind run for {id} failed ({}):\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    let stdout = String::from_utf8_lossy(&out.stdout);
    let pixels = stdout
        .lines()
        .find_map(|l| l.strip_prefix("pixels="))
        .and_then(|v| v.trim().parse().ok())
        .ok_or_else(|| format!("child {id} printed no pixel count: {stdout}"))?;
    let text = std::fs::read_to_string(&out_file)
        .map_err(|e| format!("cannot read {}: {e}", out_file.display()))?;
    let total = |key: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(key))
            .and_then(|v| v.split_whitespace().next())
            .and_then(|v| v.parse::<u64>().ok())
    };
    let ir = total("totals:")
        .or_else(|| total("summary:"))
        .ok_or_else(|| format!("no totals in {}", out_file.display()))?;
    std::fs::remove_file(&out_file).ok();
    Ok(Measured { ir, pixels })
}

/// Runs the jobs under callgrind, `jobs` at a time.
fn measure_all(ids: &[String], jobs: usize) -> Result<Vec<Measured>, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let dir = std::env::temp_dir().join(format!("pbuffer-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<Measured, String>>>> =
        Mutex::new((0..ids.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..jobs.max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= ids.len() {
                    break;
                }
                let r = callgrind(&exe, &dir, &ids[i]);
                eprint!(".");
                results.lock().unwrap()[i] = Some(r);
            });
        }
    });
    eprintln!();
    std::fs::remove_dir_all(&dir).ok();
    results
        .into_inner()
        .unwrap()
        .into_iter()
        .map(|r| r.expect("every job ran"))
        .collect()
}

fn job_id(set: Set, v: Variant) -> String {
    format!("{}/{}", set.key(), v.key())
}

fn child(id: &str) -> ExitCode {
    if let Some(name) = id.strip_prefix("scene3d/") {
        return match scene3d::child(name) {
            Ok(bytes) => {
                println!("pixels={}", count_set(&bytes, WIDTH, HEIGHT));
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("bench: {e}");
                ExitCode::from(2)
            }
        };
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

// ---------------------------------------------------------------- tables

struct Table {
    title: String,
    header: Vec<&'static str>,
    rows: Vec<Vec<String>>,
}

impl Table {
    fn text(&self) -> String {
        let n = self.header.len();
        let mut w: Vec<usize> = self.header.iter().map(|h| h.len()).collect();
        for r in &self.rows {
            for (i, c) in r.iter().enumerate() {
                w[i] = w[i].max(c.len());
            }
        }
        let line = |cells: Vec<&str>| {
            let mut s = String::from(" ");
            for (i, c) in cells.iter().enumerate() {
                if i == 0 {
                    let _ = write!(s, " {:<w$}", c, w = w[i]);
                } else {
                    let _ = write!(s, "  {:>w$}", c, w = w[i]);
                }
            }
            s.push('\n');
            s
        };
        let mut s = format!("{}\n", self.title);
        s += &line(self.header.clone());
        s += &format!(
            "  {}\n",
            "-".repeat(w.iter().sum::<usize>() + 2 * (n - 1) + 1)
        );
        for r in &self.rows {
            s += &line(r.iter().map(String::as_str).collect());
        }
        s
    }

    fn markdown(&self) -> String {
        let mut s = format!("### {}\n\n| {} |\n|", self.title, self.header.join(" | "));
        for i in 0..self.header.len() {
            s += if i == 0 { ":---|" } else { "---:|" };
        }
        s.push('\n');
        for r in &self.rows {
            s += &format!("| {} |\n", r.join(" | "));
        }
        s
    }
}

fn thousands(n: u64) -> String {
    let d = n.to_string();
    let mut groups: Vec<&str> = d
        .as_bytes()
        .rchunks(3)
        .map(|g| std::str::from_utf8(g).expect("ASCII digits"))
        .collect();
    groups.reverse();
    groups.join(",")
}

fn ratio(a: u64, b: u64) -> String {
    if b == 0 {
        "-".into()
    } else {
        format!("{:.2}", a as f64 / b as f64)
    }
}

// ---------------------------------------------------------------- 3-D scene (--scene3d)

/// The 3-D benchmark: Suzanne (../shared/models/suzanne.obj), fitted camera, 400 x 240,
/// dashed hidden lines, S = 4, 32-bit depth, the `paper` pattern.
mod scene3d {
    use super::{measured_region, Frame as Packed400x240};
    use fixed::types::extra::U4;
    use host_tests::baseline::{prepare_baseline, render_prepared};
    use host_tests::fit::fit_camera;
    use host_tests::frame::{CameraSpec, MeshData, RenderSpec};
    use host_tests::obj::load_obj;
    use host_tests::pipeline::{render_frame, MeshArrays};
    use pbuffer::mesh::Mesh;
    use pbuffer::render::ProjectedVertex;
    use pbuffer::{MonoPalette, Workspace, ZBufferRenderer};
    use std::path::PathBuf;

    /// Band heights measured.
    pub const BANDS: [usize; 3] = [8, 32, 240];

    pub fn model_path() -> PathBuf {
        let manifest = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        manifest
            .parent()
            .unwrap_or(manifest)
            .join("../shared/models/suzanne.obj")
    }

    pub fn scene() -> Result<(MeshData, CameraSpec), String> {
        let mesh = load_obj(&model_path())?;
        let cam = fit_camera(&mesh, 400, 240);
        Ok((mesh, cam))
    }

    pub fn spec(band: usize) -> RenderSpec {
        RenderSpec {
            band,
            ..RenderSpec::default()
        }
    }

    /// The library's frame through `host_tests::pipeline::render_frame` (for the
    /// figures and the checks, not measured).
    pub fn library_frame(band: usize) -> Result<host_tests::frame::Frame, String> {
        let (mesh, cam) = scene()?;
        render_frame(&mesh, &cam, &spec(band))
    }

    /// The library as firmware calls it: mesh, adjacency, camera and workspace set up
    /// beforehand; only `ZBufferRenderer::render` into a `PackedFramebuffer<400, 240>`
    /// (no probe) is inside the measured region. Returns the packed frame.
    pub fn pbuffer_measured(band: usize) -> Result<Vec<u8>, String> {
        let (data, cam) = scene()?;
        let spec = spec(band);
        let arrays = MeshArrays::new(&data);
        let mesh = Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets)
            .map_err(|e| format!("mesh: {e}"))?;
        let mut storage = host_tests::pipeline::AdjacencyStorage::new(&arrays);
        let adjacency = storage.build(&mesh, spec.crease_deg)?;
        let camera = host_tests::pipeline::camera(&cam)?;
        let settings = host_tests::pipeline::settings(&spec)?;
        let (w, band) = (spec.width, spec.band);
        let row_words = w.div_ceil(32);
        let mut vertices = vec![ProjectedVertex::default(); arrays.vertices.len()];
        let mut drawn = vec![0u32; mesh.face_count().div_ceil(32)];
        let mut features = vec![0u32; adjacency.edges().len().div_ceil(32)];
        let stored = usize::from(pbuffer::render::storage_rows(
            band as u16,
            spec.height as u16,
        ));
        let mut depth = vec![0u32; w * stored];
        let mut ids = vec![0u16; w * stored];
        let mut lines = vec![0u32; 2 * row_words * band];
        let mut ws = Workspace {
            vertices: &mut vertices,
            drawn: &mut drawn,
            features: &mut features,
            depth: &mut depth,
            ids: &mut ids,
            lines: &mut lines,
        };
        let mut renderer = Box::new(ZBufferRenderer::<U4, 512, 512>::new());
        let mut fb = Box::new(Packed400x240::new());
        let palette = MonoPalette::default();
        let mut result = Ok(());
        measured_region(&mut || {
            result = renderer
                .render(
                    &mesh,
                    &adjacency,
                    &camera,
                    &settings,
                    &mut ws,
                    &palette,
                    &mut *fb,
                    &mut (),
                )
                .map(|_| ())
                .map_err(|e| format!("render: {e}"));
        });
        result?;
        Ok(fb.as_bytes().to_vec())
    }

    /// The f32 baseline: welding, adjacency and normals beforehand; the frame
    /// (buffers initialized, faces, edges, packing) inside the measured region.
    pub fn baseline_measured() -> Result<Vec<u8>, String> {
        let (mesh, cam) = scene()?;
        let spec = spec(240);
        let prep = prepare_baseline(&mesh);
        let mut frame = None;
        measured_region(&mut || {
            frame = Some(render_prepared(&mesh, &prep, &cam, &spec));
        });
        Ok(frame.ok_or("no frame")?.packed)
    }

    /// Runs child job `name` (`pb8`, `pb32`, `pb240`, `baseline`); returns the frame.
    pub fn child(name: &str) -> Result<Vec<u8>, String> {
        match name {
            "baseline" => baseline_measured(),
            _ => {
                let band = name
                    .strip_prefix("pb")
                    .and_then(|b| b.parse().ok())
                    .filter(|b| BANDS.contains(b))
                    .ok_or_else(|| format!("bad scene3d job {name:?}"))?;
                pbuffer_measured(band)
            }
        }
    }
}

/// `bench --scene3d`: the 3-D section alone.
fn run_scene3d(markdown: bool, jobs: usize) -> ExitCode {
    let mut failures = Vec::new();
    let stat = |f: &host_tests::frame::Frame, k: &str| {
        f.stats.iter().find(|(n, _)| n == k).map_or(0, |s| s.1)
    };
    // Native frames and figures.
    let mut lib_frames = Vec::new();
    for &b in &scene3d::BANDS {
        match scene3d::library_frame(b) {
            Ok(f) => lib_frames.push((b, f)),
            Err(e) => {
                eprintln!("bench: {}: {e}", scene3d::model_path().display());
                return ExitCode::from(2);
            }
        }
    }
    let mut natives = Vec::new();
    for &b in &scene3d::BANDS {
        match scene3d::pbuffer_measured(b) {
            Ok(bytes) => natives.push((format!("pb{b}"), bytes)),
            Err(e) => {
                eprintln!("bench: {e}");
                return ExitCode::from(2);
            }
        }
    }
    match scene3d::baseline_measured() {
        Ok(bytes) => natives.push(("baseline".into(), bytes)),
        Err(e) => {
            eprintln!("bench: {e}");
            return ExitCode::from(2);
        }
    }
    let reference = &lib_frames[lib_frames.len() - 1].1.packed;
    for (name, bytes) in &natives[..scene3d::BANDS.len()] {
        if bytes != reference {
            failures.push(format!(
                "{name}: the measured library frame differs from render_frame's in {} px",
                count_diff(bytes, reference, WIDTH, HEIGHT)
            ));
        }
    }
    for (b, f) in &lib_frames {
        if &f.packed != reference {
            failures.push(format!(
                "band {b}: the frame differs from the full-frame band in {} px",
                count_diff(&f.packed, reference, WIDTH, HEIGHT)
            ));
        }
    }
    let base_bytes = &natives[natives.len() - 1].1;

    // Instruction counts.
    let valgrind = tool_version("valgrind", "--version");
    let mut ids: Vec<String> = vec![job_id(Set::Bench, Variant::Empty)];
    ids.extend(natives.iter().map(|(n, _)| format!("scene3d/{n}")));
    let measured = match &valgrind {
        Some(_) => match measure_all(&ids, jobs) {
            Ok(m) => Some(m),
            Err(e) => {
                eprintln!("bench: {e}");
                return ExitCode::from(2);
            }
        },
        None => None,
    };
    if let Some(m) = &measured {
        for (i, (name, bytes)) in natives.iter().enumerate() {
            let px = count_set(bytes, WIDTH, HEIGHT);
            if m[i + 1].pixels != px {
                failures.push(format!(
                    "scene3d/{name}: under valgrind {} pixels set, natively {px}",
                    m[i + 1].pixels
                ));
            }
        }
    }

    let full = &lib_frames[lib_frames.len() - 1].1;
    let rustc = tool_version("rustc", "--version").unwrap_or_else(|| "rustc: unknown".into());
    let machine = format!(
        "{}; {}; {} ({})",
        valgrind.as_deref().unwrap_or("valgrind: not found"),
        rustc,
        cpu_model(),
        std::env::consts::ARCH,
    );
    let mut out = report_header(
        "cargo run --release -p host_tests --bin bench -- --scene3d",
        "--markdown",
        &machine,
        markdown,
    );
    let title = format!(
        "Suzanne ({} faces, {} feature edges in this view), fitted camera, 400 x 240 1-bpp, dashed hidden lines, S = 4, 32-bit depth",
        stat(full, "faces"),
        stat(full, "feature_edges")
    );
    let mut rows = Vec::new();
    let base_ir = measured.as_ref().map(|m| m[natives.len()].ir);
    for (i, (name, bytes)) in natives.iter().enumerate() {
        let (label, depth_bytes, ram) = if name == "baseline" {
            (
                "f32 P-buffer baseline (paper, full frame)".to_string(),
                (WIDTH * HEIGHT * 4) as u64,
                // depth f32 + ids u32 + picture u8 + lines u8 per pixel
                (WIDTH * HEIGHT * 10) as u64,
            )
        } else {
            let b: usize = name[2..].parse().unwrap_or(0);
            let f = &lib_frames.iter().find(|(x, _)| *x == b).expect("band").1;
            (
                format!("pbuffer ZBufferRenderer, band {b} rows"),
                stat(f, "depth_buffer_bytes"),
                stat(f, "working_ram_bytes"),
            )
        };
        let ir = measured.as_ref().map(|m| m[i + 1].ir);
        rows.push(vec![
            label,
            ir.map_or("-".into(), thousands),
            thousands(depth_bytes),
            thousands(ram),
            thousands(count_set(bytes, WIDTH, HEIGHT) as u64),
            match (ir, base_ir) {
                (Some(a), Some(b)) => ratio(a, b),
                _ => "-".into(),
            },
        ]);
    }
    let table = Table {
        title,
        header: vec![
            "renderer",
            "instructions (Ir) / frame",
            "depth buffer bytes",
            "working RAM bytes",
            "pixels set",
            "ratio vs baseline",
        ],
        rows,
    };
    out += &if markdown {
        table.markdown()
    } else {
        table.text()
    };
    out.push('\n');
    let checks = vec![
        format!(
            "library frame identical at band heights 8, 32 and 240, and identical to render_frame's: {}",
            if failures.is_empty() { "yes" } else { "NO" }
        ),
        format!(
            "pbuffer vs f32 baseline: {} of {} pixels differ (the baseline is f32, unsnapped, fan-union coverage)",
            count_diff(reference, base_bytes, WIDTH, HEIGHT),
            WIDTH * HEIGHT
        ),
        format!(
            "library spans per frame: {}; bands: {} / {} / {}",
            stat(full, "spans"),
            stat(&lib_frames[0].1, "bands"),
            stat(&lib_frames[1].1, "bands"),
            stat(full, "bands")
        ),
        match &measured {
            Some(m) => format!("measurement overhead (empty region): {} Ir", m[0].ir),
            None => "valgrind not found: instruction counts skipped".into(),
        },
    ];
    finish_report(out, &checks, &failures, markdown, measured.is_some())
}

// ---------------------------------------------------------------- main

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [flag, id] = args.as_slice() {
        if flag == "--child" {
            return child(id);
        }
    }
    let mut markdown = false;
    let mut scene3d = false;
    let mut jobs = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--markdown" => markdown = true,
            "--scene3d" => scene3d = true,
            "--jobs" => match it.next().and_then(|j| j.parse().ok()) {
                Some(j) => jobs = j,
                None => {
                    eprintln!("bench: --jobs needs a number");
                    return ExitCode::from(2);
                }
            },
            "-h" | "--help" => {
                println!("usage: bench [--markdown] [--scene3d] [--jobs N]");
                return ExitCode::SUCCESS;
            }
            other => {
                eprintln!(
                    "bench: unknown argument {other:?}\nusage: bench [--markdown] [--scene3d] [--jobs N]"
                );
                return ExitCode::from(2);
            }
        }
    }
    if cfg!(debug_assertions) {
        eprintln!("bench: warning: debug build; run with --release for meaningful counts");
    }
    if scene3d {
        return run_scene3d(markdown, jobs);
    }

    // ---- native checks
    let bench = bench_triangles();
    let check = check_triangles(&bench);
    let mut failures = Vec::new();
    if check.span_xor_diff != 0 {
        failures.push(format!(
            "bench set: span and XOR paths differ in {} pixels (first: triangle {:?}, {} px)",
            check.span_xor_diff,
            check.first_span_xor.unwrap().0,
            check.first_span_xor.unwrap().1
        ));
    }
    let mut frames: Vec<(Set, Variant, Vec<u8>)> = Vec::new();
    let large = large_polygons();
    let mut sets = vec![Set::Bench];
    sets.extend((0..large.len()).map(Set::Large));
    sets.extend(SCALE_SIZES.iter().map(|&s| Set::Scale(s)));
    for &set in &sets {
        let sh = shapes(set);
        let variants: &[Variant] = match sh {
            Shapes::Triangles(_) => &Variant::ALL,
            Shapes::Polygons(_) => &[Variant::Span, Variant::Xor],
        };
        for &v in variants {
            frames.push((set, v, execute(v, &sh)));
        }
    }
    let frame = |set: Set, v: Variant| -> &[u8] {
        &frames
            .iter()
            .find(|(s, w, _)| *s == set && *w == v)
            .expect("frame")
            .2
    };
    let pixels = |set: Set, v: Variant| count_set(frame(set, v), WIDTH, HEIGHT);
    for &set in &sets {
        let d = count_diff(
            frame(set, Variant::Span),
            frame(set, Variant::Xor),
            WIDTH,
            HEIGHT,
        );
        if d != 0 {
            let (a, b) = (frame(set, Variant::Span), frame(set, Variant::Xor));
            let first = (0..HEIGHT)
                .flat_map(|y| (0..WIDTH).map(move |x| (x, y)))
                .find(|&(x, y)| packed_pixel(a, WIDTH, x, y) != packed_pixel(b, WIDTH, x, y));
            failures.push(format!(
                "{}: span and XOR frames differ in {d} pixels (first at {first:?})",
                set.key()
            ));
        }
        if !matches!(set, Set::Large(_)) {
            let d = count_diff(
                frame(set, Variant::EgPacked),
                frame(set, Variant::EgNaive),
                WIDTH,
                HEIGHT,
            );
            if d != 0 {
                failures.push(format!(
                    "{}: e-g into PackedFramebuffer and into the naive framebuffer differ in {d} pixels",
                    set.key()
                ));
            }
        }
    }

    // ---- instruction counts
    let valgrind = tool_version("valgrind", "--version");
    let mut ids: Vec<String> = vec![job_id(Set::Bench, Variant::Empty)];
    for (set, v, _) in &frames {
        ids.push(job_id(*set, *v));
    }
    let measured = match &valgrind {
        Some(_) => match measure_all(&ids, jobs) {
            Ok(m) => Some(m),
            Err(e) => {
                eprintln!("bench: {e}");
                return ExitCode::from(2);
            }
        },
        None => None,
    };
    let ir = |set: Set, v: Variant| -> u64 {
        let id = job_id(set, v);
        let i = ids.iter().position(|x| *x == id).expect("job");
        let m = &measured.as_ref().expect("measured")[i];
        m.ir
    };
    if let Some(m) = &measured {
        for (i, id) in ids.iter().enumerate().skip(1) {
            let (set, v) = (frames[i - 1].0, frames[i - 1].1);
            if m[i].pixels != pixels(set, v) {
                failures.push(format!(
                    "{id}: under valgrind {} pixels set, natively {}",
                    m[i].pixels,
                    pixels(set, v)
                ));
            }
        }
    }

    // ---- report
    let rustc = tool_version("rustc", "--version").unwrap_or_else(|| "rustc: unknown".into());
    let machine = format!(
        "{}; {}; {} ({}, {} cores)",
        valgrind.as_deref().unwrap_or("valgrind: not found"),
        rustc,
        cpu_model(),
        std::env::consts::ARCH,
        std::thread::available_parallelism().map_or(1, |n| n.get()),
    );
    let mut out = report_header(
        "cargo run --release -p host_tests --bin bench",
        "-- --markdown",
        &machine,
        markdown,
    );
    let tri_note = format!(
        "{} triangles (300 of 2-10 px, 60 of 20-60 px, 12 of 100-240 px), integer pixel-centre vertices, 400 x 240 1-bpp, S = 4",
        bench.len()
    );
    let mut tables = Vec::new();
    if measured.is_some() {
        let base = ir(Set::Bench, Variant::Span);
        let n = bench.len() as u64;
        let rows = Variant::ALL
            .iter()
            .map(|&v| {
                let i = ir(Set::Bench, v);
                let drawn = if matches!(v, Variant::EgPacked | Variant::EgNaive) {
                    check.eg_pixels
                } else {
                    check.pb_pixels
                } as u64;
                vec![
                    v.label().to_string(),
                    thousands(i),
                    thousands(i / n),
                    format!("{:.1}", i as f64 / drawn as f64),
                    thousands(pixels(Set::Bench, v) as u64),
                    ratio(i, base),
                ]
            })
            .collect();
        tables.push(Table {
            title: format!("Fill the fixed triangle set: {tri_note}"),
            header: vec![
                "variant",
                "instructions (Ir)",
                "Ir / triangle",
                "Ir / pixel drawn",
                "pixels set",
                "ratio vs (a)",
            ],
            rows,
        });

        let rows = large
            .iter()
            .enumerate()
            .map(|(i, (name, pts))| {
                let (a, b) = (
                    ir(Set::Large(i), Variant::Span),
                    ir(Set::Large(i), Variant::Xor),
                );
                vec![
                    name.to_string(),
                    pts.len().to_string(),
                    thousands(pixels(Set::Large(i), Variant::Span) as u64),
                    thousands(a),
                    thousands(b),
                    format!(
                        "{:.1}",
                        a as f64 / pixels(Set::Large(i), Variant::Span).max(1) as f64
                    ),
                    format!(
                        "{:.1}",
                        b as f64 / pixels(Set::Large(i), Variant::Span).max(1) as f64
                    ),
                    ratio(b, a),
                ]
            })
            .collect();
        tables.push(Table {
            title: "(d) Large polygons, one fill each (even-odd, 1/16-px vertices)".into(),
            header: vec![
                "polygon",
                "vertices",
                "pixels",
                "(a) span Ir",
                "(b) XOR Ir",
                "(a) Ir/px",
                "(b) Ir/px",
                "XOR / span",
            ],
            rows,
        });

        let rows = SCALE_SIZES
            .iter()
            .map(|&s| {
                let set = Set::Scale(s);
                let per = |v| ir(set, v) / SCALE_COUNT as u64;
                let c = check_triangles(match &shapes(set) {
                    Shapes::Triangles(t) => t,
                    Shapes::Polygons(_) => unreachable!(),
                });
                vec![
                    format!("{s} px"),
                    format!("{:.0}", c.pb_pixels as f64 / SCALE_COUNT as f64),
                    thousands(per(Variant::Span)),
                    thousands(per(Variant::Xor)),
                    ratio(per(Variant::Xor), per(Variant::Span)),
                    thousands(per(Variant::EgPacked)),
                    thousands(per(Variant::EgNaive)),
                    ratio(per(Variant::EgPacked), per(Variant::Span)),
                ]
            })
            .collect();
        tables.push(Table {
            title: format!(
                "(d) Scaling with triangle size: {SCALE_COUNT} triangles per size (vertices on a circle of that diameter), Ir per triangle"
            ),
            header: vec![
                "size",
                "px / tri",
                "(a) span",
                "(b) XOR",
                "XOR / span",
                "(c1) e-g packed",
                "(c2) e-g naive",
                "(c1) / (a)",
            ],
            rows,
        });
    }
    for t in &tables {
        out += &if markdown { t.markdown() } else { t.text() };
        out.push('\n');
    }

    let mut checks = vec![
        format!(
            "span == XOR, triangle by triangle and frame by frame on every set: {}",
            if check.span_xor_diff == 0 && failures.is_empty() {
                "yes"
            } else {
                "NO"
            }
        ),
        format!(
            "e-g vs pbuffer on the {} bench triangles drawn one at a time: pbuffer {} px, e-g {} px; e-g sets {} px pbuffer does not and misses {} px pbuffer sets; {} of {} triangles differ",
            check.triangles,
            check.pb_pixels,
            check.eg_pixels,
            check.eg_extra,
            check.eg_missing,
            check.eg_tris_differing,
            check.triangles
        ),
        format!(
            "e-g into PackedFramebuffer == e-g into the naive framebuffer: {}",
            if failures.iter().any(|f| f.contains("naive")) {
                "NO"
            } else {
                "yes"
            }
        ),
    ];
    if let Some(m) = &measured {
        checks.push(format!(
            "measurement overhead (empty region): {} Ir",
            m[0].ir
        ));
    } else {
        checks.push("valgrind not found: instruction counts skipped".into());
    }
    finish_report(out, &checks, &failures, markdown, measured.is_some())
}

/// The first lines of a report: the command that makes it (with `markdown_flag` in
/// markdown) and the machine.
fn report_header(command: &str, markdown_flag: &str, machine: &str, markdown: bool) -> String {
    if markdown {
        format!("Generated by `{command} {markdown_flag}`.\n\nMachine: {machine}.\n\n")
    } else {
        format!("pbuffer bench ({command})\nmachine: {machine}\n\n")
    }
}

/// Prints a report with its checks and failures; the exit status is 1 on a failure,
/// 2 when nothing could be measured (no valgrind), else success.
fn finish_report(
    mut out: String,
    checks: &[String],
    failures: &[String],
    markdown: bool,
    measured: bool,
) -> ExitCode {
    let (heading, bullet) = if markdown {
        ("### Checks\n\n", "- ")
    } else {
        ("checks:\n", "  ")
    };
    out += heading;
    for c in checks {
        let _ = writeln!(out, "{bullet}{c}");
    }
    for f in failures {
        let _ = writeln!(out, "{bullet}FAILURE: {f}");
    }
    print!("{out}");
    if !failures.is_empty() {
        ExitCode::from(1)
    } else if !measured {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    }
}
