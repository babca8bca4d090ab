//! `bench --firmware [--m4 FILE]`: the firmware examples' frames counted on the host
//! (callgrind), set against the counts the same frames took on the emulated Cortex-M4.
//!
//! The scene, engine and baseline modules are the firmware's own (`pbuffer-scenes`,
//! as in `host_tests/tests/firmware/firmware_examples.rs`), and each frame's measured region
//! is what the firmware's SysTick counter brackets: clear + transform + draw (the
//! mesh, its edge list, planarity bits and the fast engine's baked constants are made
//! before, as the firmware has them in flash). `FILE` is the `frame EXAMPLE N hash=HEX instructions=COUNT` lines of
//! `scripts/firmware` (it keeps them in `target/firmware-frames.txt`, the default).
//! A frame whose hash differs from the firmware's is reported and fails the run:
//! the ratio is only meaningful for the same picture.

use std::collections::HashMap;
use std::process::ExitCode;

use fixed::types::extra::U4;
use host_tests::firmware::Bake;
use host_tests::measure::measured_region;
use host_tests::tools::callgrind::{measure_all, thousands};
use pbuffer::mesh::{EdgeAdjacency, Mesh};
use pbuffer::render::{BakedMesh, FastRenderer, FastWorkspace};
use pbuffer::{packed_len, CodeFillRenderer, CodeWorkspace, DrawMode, PackedFramebuffer, Pattern};

use pbuffer_scenes::scenes::{self, fnv1a64, panel, suzanne, View};
use pbuffer_scenes::{obj, painter, plain};

/// The examples in `scripts/firmware`'s order.
const EXAMPLES: [&str; 9] = [
    "suzanne",
    "surfaces",
    "panel",
    "suzanne-scanline",
    "panel-scanline",
    "suzanne-painter",
    "suzanne-plainf32",
    "panel-painter",
    "panel-plainf32",
];

/// Where `scripts/firmware` keeps its frame lines.
pub const DEFAULT_M4: &str = "target/firmware-frames.txt";

/// A scene's mesh arrays.
struct Arrays {
    vertices: Vec<[f32; 3]>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
}

fn arrays(scene: &str) -> Arrays {
    if scene == "suzanne" {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../examples/embedded/models/suzanne.obj"
        );
        let text = std::fs::read_to_string(path).expect("read the examples' suzanne.obj");
        let m = obj::parse(&text, "suzanne.obj").expect("parses");
        Arrays {
            vertices: m.vertices,
            indices: m.indices,
            offsets: m.offsets,
        }
    } else {
        Arrays {
            vertices: panel::VERTICES.to_vec(),
            indices: panel::INDICES.to_vec(),
            offsets: panel::OFFSETS.to_vec(),
        }
    }
}

/// The scene an example draws: `"suzanne"` or `"panel"`.
fn scene_of(example: &str) -> &'static str {
    if example.starts_with("panel") {
        "panel"
    } else {
        "suzanne"
    }
}

/// Frames of an example's scene.
fn frames(example: &str) -> u32 {
    match scene_of(example) {
        "panel" => panel::FRAMES,
        _ => suzanne::FRAMES,
    }
}

/// Draws frame `n` of `example`, counting only what the firmware counts when
/// `measure` is set; returns the frame's bytes.
fn draw(example: &str, n: u32, measure: bool) -> Vec<u8> {
    let scene = scene_of(example);
    let a = arrays(scene);
    // As build.rs makes them: the edge list, the planarity bits and the fast engine's
    // constants (the firmware checks them once at boot, outside the frames). The
    // suzanne and the (fast) panel firmware keep the planarity with the mesh, the other
    // panel examples none.
    let bake = Bake::new(&a.vertices, &a.indices, &a.offsets);
    let mesh = if scene == "suzanne" || example == "panel" {
        bake.mesh()
    } else {
        bake.plain_mesh()
    };
    let (edges, baked) = (bake.adjacency(), bake.baked());
    let run = |f: &mut dyn FnMut()| {
        if measure {
            measured_region(f);
        } else {
            f();
        }
    };
    match scene {
        "suzanne" => frame::<400, 240, { packed_len(400, 240) }>(
            example,
            (&mesh, &edges, &baked, &suzanne::view(n)),
            run,
        ),
        _ => frame::<128, 64, { packed_len(128, 64) }>(
            example,
            (&mesh, &edges, &baked, &panel::view(n)),
            run,
        ),
    }
}

/// The mesh, its edges, the mesh baked for the fast engine and the camera of one frame.
type FrameScene<'a, 'm, 'e> = (
    &'a Mesh<'m>,
    &'a EdgeAdjacency<'e>,
    &'a BakedMesh<'m>,
    &'a View,
);

fn frame<const W: usize, const H: usize, const N: usize>(
    example: &str,
    scene: FrameScene<'_, '_, '_>,
    run: impl Fn(&mut dyn FnMut()),
) -> Vec<u8> {
    let mut fb = Box::new(PackedFramebuffer::<W, H, N>::new());
    let mode = if example == "surfaces" {
        DrawMode::SurfacesDashed
    } else {
        DrawMode::Dashed
    };
    match example {
        "suzanne" | "surfaces" => fast_frame(
            &mut scenes::FastEngine::new(),
            &mut scenes::SuzanneFastBuffers::new().workspace(),
            scene,
            mode,
            &mut *fb,
            run,
        ),
        "panel" => fast_frame(
            &mut scenes::PanelFastEngine::new(),
            &mut scenes::PanelFastBuffers::new().workspace(),
            scene,
            mode,
            &mut *fb,
            run,
        ),
        "suzanne-scanline" => engine_frame(
            &mut scenes::Engine::new(),
            &mut scenes::SuzanneBuffers::new().workspace(),
            scene,
            mode,
            &mut *fb,
            run,
        ),
        "panel-scanline" => engine_frame(
            &mut scenes::PanelEngine::new(),
            &mut scenes::PanelBuffers::new().workspace(),
            scene,
            mode,
            &mut *fb,
            run,
        ),
        "suzanne-painter" => painter_frame(
            &mut painter::PainterBuffers::<507, 500>::new(),
            scene,
            &mut *fb,
            run,
        ),
        "panel-painter" => painter_frame(
            &mut painter::PainterBuffers::<24, 16>::new(),
            scene,
            &mut *fb,
            run,
        ),
        "suzanne-plainf32" => {
            return plain_frame::<W, H, N, { 400 * 240 }, 507, 500>(scene, run);
        }
        _ => return plain_frame::<W, H, N, { 128 * 64 }, 24, 16>(scene, run),
    }
    fb.as_bytes().to_vec()
}

/// One fast-engine frame as the firmware draws it: clear, then `scenes::render_fast`.
fn fast_frame<const W: usize, const H: usize, const N: usize, const F: usize, const L: usize>(
    engine: &mut FastRenderer<U4, F, L>,
    ws: &mut FastWorkspace<'_>,
    (_, _, baked, view): FrameScene<'_, '_, '_>,
    mode: DrawMode,
    fb: &mut PackedFramebuffer<W, H, N>,
    run: impl Fn(&mut dyn FnMut()),
) {
    run(&mut || {
        fb.clear();
        scenes::render_fast(engine, baked, view, mode, ws, fb).expect("renders");
    });
}

/// One scan-line frame as the firmware draws it: clear, then `scenes::render`.
fn engine_frame<const W: usize, const H: usize, const N: usize, const F: usize, const E: usize>(
    engine: &mut CodeFillRenderer<U4, 1, F, E, 16>,
    ws: &mut CodeWorkspace<'_>,
    (mesh, edges, _, view): FrameScene<'_, '_, '_>,
    mode: DrawMode,
    fb: &mut PackedFramebuffer<W, H, N>,
    run: impl Fn(&mut dyn FnMut()),
) {
    run(&mut || {
        fb.clear();
        scenes::render(engine, mesh, edges, view, mode, ws, fb).expect("renders");
    });
}

/// One frame of the embedded-graphics painter baseline: clear, then paint.
fn painter_frame<const W: usize, const H: usize, const N: usize, const V: usize, const F: usize>(
    p: &mut painter::PainterBuffers<V, F>,
    (mesh, _, _, view): FrameScene<'_, '_, '_>,
    fb: &mut PackedFramebuffer<W, H, N>,
    run: impl Fn(&mut dyn FnMut()),
) {
    p.prepare(mesh);
    run(&mut || {
        fb.clear();
        p.render(mesh, view, fb).expect("painter");
    });
}

/// One frame of the plain f32 P-buffer baseline (it clears its own buffers).
fn plain_frame<
    const W: usize,
    const H: usize,
    const N: usize,
    const P: usize,
    const V: usize,
    const F: usize,
>(
    (mesh, edges, _, view): FrameScene<'_, '_, '_>,
    run: impl Fn(&mut dyn FnMut()),
) -> Vec<u8> {
    let mut p = Box::new(plain::PlainBuffers::<P, N, V, F>::new());
    p.prepare(mesh);
    let closed = edges.is_closed();
    run(&mut || p.render(mesh, edges.edges(), closed, view, W, H, &Pattern::PAPER));
    p.frame.to_vec()
}

/// Child job `EXAMPLE/N`: draws that frame in the measured region.
pub fn child(key: &str) -> Result<usize, String> {
    let (example, n) = key
        .split_once('/')
        .and_then(|(e, n)| Some((e, n.parse::<u32>().ok()?)))
        .filter(|(e, n)| EXAMPLES.contains(e) && *n < frames(e))
        .ok_or_else(|| format!("bad firmware job {key:?}"))?;
    let bytes = draw(example, n, true);
    Ok(bytes.iter().map(|b| b.count_ones() as usize).sum())
}

/// The firmware's frames: (example, n) to (hash, instructions).
type M4Frames = HashMap<(String, u32), (u64, u64)>;

/// Reads the firmware's frame lines.
fn read_m4(path: &str) -> Result<M4Frames, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut out = HashMap::new();
    for line in text.lines().filter(|l| l.starts_with("frame ")) {
        let f: Vec<&str> = line.split_whitespace().collect();
        let field = |i: usize, key: &str| {
            f.get(i)
                .and_then(|s| s.strip_prefix(key))
                .ok_or_else(|| format!("{path}: bad line {line:?}"))
        };
        let n = f.get(2).and_then(|s| s.parse().ok());
        let hash = u64::from_str_radix(field(3, "hash=")?, 16).ok();
        let ins = field(4, "instructions=")?.parse().ok();
        match (f.get(1), n, hash, ins) {
            (Some(e), Some(n), Some(h), Some(i)) => {
                out.insert((e.to_string(), n), (h, i));
            }
            _ => return Err(format!("{path}: bad line {line:?}")),
        }
    }
    Ok(out)
}

/// Runs every frame under callgrind and prints host Ir against the M4's count.
pub fn run(m4_path: &str, jobs: usize) -> ExitCode {
    let m4 = match read_m4(m4_path) {
        Ok(m) => Some(m),
        Err(e) => {
            eprintln!("bench: no firmware counts ({e}); run ./scripts/firmware first");
            None
        }
    };
    let keys: Vec<(String, u32)> = EXAMPLES
        .iter()
        .flat_map(|e| (0..frames(e)).map(move |n| (e.to_string(), n)))
        .collect();
    let ids: Vec<String> = keys.iter().map(|(e, n)| format!("fw/{e}/{n}")).collect();
    let measured = match measure_all(&ids, jobs) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("bench: {e}");
            return ExitCode::from(2);
        }
    };
    let mut failed = false;
    println!("| example | frames | host Ir / frame (callgrind) | M4 instructions / frame (QEMU) | M4 / host |");
    println!("|:---|---:|---:|---:|---:|");
    for e in EXAMPLES {
        let (mut host, mut arm, mut n_frames, mut all_m4) = (0u64, 0u64, 0u64, true);
        let (mut lo, mut hi) = (f64::MAX, 0f64);
        for ((ex, n), m) in keys.iter().zip(&measured).filter(|((ex, _), _)| ex == e) {
            host += m.ir;
            n_frames += 1;
            let hash = fnv1a64(&draw(ex, *n, false));
            match m4.as_ref().and_then(|t| t.get(&(ex.clone(), *n))) {
                Some(&(h, i)) if h == hash => {
                    arm += i;
                    let r = i as f64 / m.ir as f64;
                    (lo, hi) = (lo.min(r), hi.max(r));
                }
                Some(&(h, _)) => {
                    eprintln!("{ex} {n}: host hash {hash:016x}, firmware {h:016x}");
                    failed = true;
                    all_m4 = false;
                }
                None => all_m4 = false,
            }
        }
        let mean = |t: u64| thousands(t / n_frames.max(1));
        if all_m4 && n_frames > 0 {
            println!(
                "| {e} | {n_frames} | {} | {} | {:.3} ({lo:.3} to {hi:.3}) |",
                mean(host),
                mean(arm),
                arm as f64 / host as f64
            );
        } else {
            println!("| {e} | {n_frames} | {} | - | - |", mean(host));
        }
    }
    if failed {
        eprintln!("bench: firmware frames differ from the host's");
        return ExitCode::from(1);
    }
    ExitCode::SUCCESS
}
