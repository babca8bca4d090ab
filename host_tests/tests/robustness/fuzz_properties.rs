//! Fuzzing as property tests, through the library API (errors are `pbuffer::Error`
//! values): seeded generators feed NaN, infinities, 1e35, i32 extremes, subnormals,
//! repeated and out-of-range indices, degenerate faces and degenerate cameras into
//! mesh + camera -> frame (code fill with both row representations, the Z-buffer with
//! 16- and 32-bit depth, and code fill in the depth order of a BSP tree built for the
//! case). Properties:
//! - invalid input gives exactly the documented error (`NonFiniteVertex`,
//!   `IndexOutOfRange`, `DegenerateFace`, `BadFaceOffsets`, `EmptyMesh`,
//!   `BadCamera(problem)`), computed by an independent oracle (`fuzzgen`);
//! - valid input never panics and never sends a span outside the target (a recording
//!   sink counts them as failures); its only errors are `OutOfRange` (a scene scale
//!   fixed point cannot hold), `CapacityExceeded` and `CodeTooWide` (compiled
//!   capacities, deliberately small here so that both occur);
//! - code fill's two row representations give the same picture.
//!
//! Case counts are fixed; `cargo test --release -p host_tests --test robustness fuzz_properties::
//! -- --nocapture` prints them with the CPU time. The 2-D fillers and the GF(2)
//! coding schemes are fuzzed in `fuzz_fillers.rs` and `fuzz_codes.rs`.

use crate::fuzzgen;

use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

use fixed::types::extra::{LeEqU32, U0, U12, U4};
use fuzzgen::{finite, panic_message, raw_camera, raw_mesh, wild, RawCamera, RawMesh, Recorder};
use host_tests::bsp::BspBuffers;
use host_tests::fast::FastBuffers;
use host_tests::random::Rng;
use pbuffer::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use pbuffer::order::BspSizes;
use pbuffer::render::{
    storage_rows, BakedMesh, CompactEdge, Depth, FacePlane, FastRenderer, LineVisibility, Piercing,
    ProjectedVertex, RowCodes, VertexFaces,
};
use pbuffer::{
    Camera, CodeFillRenderer, CodeWorkspace, Cull, Dashes, DepthOrder, DrawMode, Error,
    MonoPalette, Pattern, Settings, Stats, Visibility, Workspace, ZBufferRenderer,
};

/// Mesh + camera cases of the render property; `PBUFFER_FUZZ_SCENES` asks for
/// more (`scripts/fuzz-million` runs 10^6) and `PBUFFER_FUZZ_SEED` for other ones.
const RENDER_CASES: usize = 30_000;

fn render_cases() -> (usize, u64) {
    let var = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<u64>().ok());
    let cases = var("PBUFFER_FUZZ_SCENES").map_or(RENDER_CASES, |n| n as usize);
    (cases, var("PBUFFER_FUZZ_SEED").unwrap_or(0xF022_0000_0002))
}

/// `PBUFFER_FUZZ_ONLY=38470,40884`: render only these cases (each still derived from
/// the seed and its index, every case before it generated and skipped) and print
/// their jobs; to reproduce a failure of a long run.
fn only_cases() -> Option<Vec<usize>> {
    let list = std::env::var("PBUFFER_FUZZ_ONLY").ok()?;
    Some(
        list.split(',')
            .filter_map(|c| c.trim().replace('_', "").parse().ok())
            .collect(),
    )
}

/// Mesh + camera cases of the error property.
const ERROR_CASES: usize = 200_000;

/// The engines.
#[derive(Clone, Copy, Debug)]
enum Engine {
    Crossings,
    BitSliced,
    /// Crossings in a BSP tree's depth order (the tree built for the case).
    Ordered,
    Z16,
    Z32,
    /// The fast engine (the default), its mesh baked for the case.
    Fast,
    /// The fast engine with hidden lines by the segment (its vertex faces and
    /// piercing pairs baked too).
    FastSegments,
}

/// What one frame needs besides mesh and camera.
struct Job<'a> {
    mesh: &'a Mesh<'a>,
    edges: &'a EdgeAdjacency<'a>,
    camera: &'a Camera,
    settings: Settings,
    w: u16,
    h: u16,
    band: u16,
    /// Shorten the vertex cache by one (a `CapacityExceeded` on purpose).
    short: bool,
}

/// Code fill with a 32-bit code (so that 33 faces over a pixel, or on a row with
/// bit-sliced rows, are `CodeTooWide`), 64 active faces and 256 active edges.
type Code<F> = CodeFillRenderer<F, 1, 64, 256, 64>;

fn render_code<F: LeEqU32>(job: &Job, sliced: bool, sink: &mut Recorder) -> Result<Stats, Error> {
    render_code_in::<F>(job, sliced, None, sink)
}

/// Code fill in the depth order of a BSP tree built into storage for up to two
/// splits per face (more is `CapacityExceeded`, an allowed outcome).
fn render_ordered<F: LeEqU32>(job: &Job, sink: &mut Recorder) -> Result<Stats, Error> {
    let mesh = job.mesh;
    let sizes = BspSizes::for_mesh(
        mesh.vertices().len(),
        mesh.face_count(),
        mesh.indices().len(),
        2 * mesh.face_count() + 8,
    );
    let mut buffers = BspBuffers::new(sizes);
    let tree = buffers.build(mesh)?;
    let mut rank = vec![0u32; tree.fragment_count()];
    let mut stack = vec![0u32; tree.depth()];
    tree.rank_front_to_back(&job.camera.viewpoint(), &mut stack, &mut rank)?;
    let order = DepthOrder {
        surfaces: tree.fragments(),
        source: tree.source(),
        rank: &rank,
    };
    render_code_in::<F>(job, false, Some(order), sink)
}

fn render_code_in<F: LeEqU32>(
    job: &Job,
    sliced: bool,
    depth_order: Option<DepthOrder<'_>>,
    sink: &mut Recorder,
) -> Result<Stats, Error> {
    let (w, band) = (usize::from(job.w), usize::from(job.band));
    let stored = usize::from(storage_rows(job.band, job.h));
    let surfaces = depth_order.map_or(*job.mesh, |o| o.surfaces);
    let n = surfaces.vertices().len() - usize::from(job.short);
    let mut vertices = vec![ProjectedVertex::default(); n];
    let mut drawn = vec![0u32; job.mesh.face_count().div_ceil(32)];
    let mut features = vec![0u32; job.edges.edges().len().div_ceil(32)];
    let mut order = vec![0u32; surfaces.face_count()];
    let mut ids = vec![0u16; w * stored];
    let mut lines = vec![0u32; 2 * w.div_ceil(32) * band];
    let mut ws = CodeWorkspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        order: &mut order,
        ids: &mut ids,
        lines: &mut lines,
    };
    let mut words = vec![0u32; Code::<F>::bit_sliced_len(w)];
    let codes = if sliced {
        RowCodes::BitSliced(&mut words)
    } else {
        RowCodes::Crossings
    };
    // Boxed: the engine's tables are too large for a test thread's stack.
    let mut engine = Box::new(Code::<F>::new());
    let visibility = depth_order.map_or(Visibility::Planes, Visibility::Order);
    engine.render_with(
        job.mesh,
        job.edges,
        job.camera,
        &job.settings,
        &mut ws,
        codes,
        visibility,
        &MonoPalette::default(),
        sink,
        &mut (),
    )
}

fn render_z<F: LeEqU32, D: Depth>(job: &Job, sink: &mut Recorder) -> Result<Stats, Error> {
    let (w, band) = (usize::from(job.w), usize::from(job.band));
    let stored = usize::from(storage_rows(job.band, job.h));
    let n = job.mesh.vertices().len() - usize::from(job.short);
    let mut vertices = vec![ProjectedVertex::default(); n];
    let mut drawn = vec![0u32; job.mesh.face_count().div_ceil(32)];
    let mut features = vec![0u32; job.edges.edges().len().div_ceil(32)];
    let mut depth = vec![D::default(); w * stored];
    let mut ids = vec![0u16; w * stored];
    let mut lines = vec![0u32; 2 * w.div_ceil(32) * band];
    let mut ws = Workspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        depth: &mut depth,
        ids: &mut ids,
        lines: &mut lines,
    };
    let mut engine = Box::new(ZBufferRenderer::<F, 64, 64>::new());
    engine.render(
        job.mesh,
        job.edges,
        job.camera,
        &job.settings,
        &mut ws,
        &MonoPalette::default(),
        sink,
        &mut (),
    )
}

fn render_s<F: LeEqU32>(job: &Job, engine: Engine, sink: &mut Recorder) -> Result<Stats, Error> {
    match engine {
        Engine::Crossings => render_code::<F>(job, false, sink),
        Engine::BitSliced => render_code::<F>(job, true, sink),
        Engine::Ordered => render_ordered::<F>(job, sink),
        Engine::Z16 => render_z::<F, u16>(job, sink),
        Engine::Z32 => render_z::<F, u32>(job, sink),
        Engine::Fast => render_fast::<F>(job, sink, false),
        Engine::FastSegments => render_fast::<F>(job, sink, true),
    }
}

/// The fast engine with room for 64 active facets and 64 lines (more is
/// `CapacityExceeded`), a clip pool for every face cut by six planes; with
/// `by_segment`, hidden lines by the segment (room for 4,096 piercing pairs).
fn render_fast<F: LeEqU32>(
    job: &Job,
    sink: &mut Recorder,
    by_segment: bool,
) -> Result<Stats, Error> {
    let mesh = job.mesh;
    let mut planes = vec![FacePlane::default(); mesh.face_count()];
    let mut edges = vec![CompactEdge::default(); job.edges.edges().len()];
    BakedMesh::bake(mesh, job.edges, &mut planes, &mut edges)?;
    let mut baked = BakedMesh::new(*mesh, &planes, &edges)?;
    let nv = mesh.vertices().len();
    let (mut weld, mut starts) = (vec![0u16; nv], vec![0u16; nv + 1]);
    let mut around = vec![0u16; mesh.indices().len()];
    let mut irregular = vec![0u32; nv.div_ceil(32)];
    let mut pairs = vec![Piercing::default(); if by_segment { 4096 } else { 0 }];
    let mut settings = job.settings;
    if by_segment {
        let faces = VertexFaces::bake(mesh, &mut weld, &mut starts, &mut around, &mut irregular)?;
        let n = Piercing::bake(mesh, &edges, &mut pairs)?;
        baked = baked
            .with_vertex_faces(faces)?
            .with_piercings(pairs.get(..n).unwrap_or_default())?;
        settings.lines = LineVisibility::BySegment;
    }
    let n = mesh.vertices().len() - usize::from(job.short);
    let pool = mesh.indices().len() + 6 * mesh.face_count();
    let (w, h) = (usize::from(job.w), usize::from(job.h));
    let mut buffers = FastBuffers::new(n, mesh.face_count(), edges.len(), w, h, pool);
    let mut engine = Box::new(FastRenderer::<F, 64, 64>::new());
    engine.render(
        &baked,
        job.camera,
        &settings,
        &mut buffers.workspace(),
        &MonoPalette::default(),
        sink,
        &mut (),
    )
}

/// Renders `job` with `engine` at S = `s` (0, 4 or 12) into a fresh recording sink.
fn render(job: &Job, engine: Engine, s: u32) -> (Result<Stats, Error>, Recorder) {
    let mut sink = Recorder::new(job.w, job.h);
    let r = match s {
        0 => render_s::<U0>(job, engine, &mut sink),
        4 => render_s::<U4>(job, engine, &mut sink),
        _ => render_s::<U12>(job, engine, &mut sink),
    };
    (r, sink)
}

fn library_mesh(m: &RawMesh) -> Result<Mesh<'_>, Error> {
    Mesh::new(&m.vertices, &m.indices, &m.offsets)
}

fn library_camera(c: &RawCamera) -> Result<Camera, Error> {
    Camera::new(c.eye, c.target, c.up, c.projection, c.near, c.far)
}

/// Invalid meshes and cameras give exactly the documented error; valid ones `Ok`.
#[test]
fn bad_meshes_and_cameras_give_the_precise_error() {
    let t = Instant::now();
    let mut rng = Rng::new(0xF022_0000_0001);
    let mut seen = BTreeMap::<String, usize>::new();
    let mut failures = Vec::new();
    for case in 0..ERROR_CASES {
        let m = raw_mesh(&mut rng, 0.5, wild);
        let got = catch_unwind(|| library_mesh(&m).err());
        match got {
            Ok(got) if got == m.expected => {}
            Ok(got) => failures.push(format!(
                "mesh case {case}: got {got:?}, want {:?}: {m:?}",
                m.expected
            )),
            Err(e) => failures.push(format!(
                "mesh case {case}: panic {}: {m:?}",
                panic_message(&*e)
            )),
        }
        let c = raw_camera(&mut rng, 0.3);
        let got = catch_unwind(|| library_camera(&c).err());
        match got {
            Ok(got) if got == c.expected => {}
            Ok(got) => failures.push(format!(
                "camera case {case}: got {got:?}, want {:?}: {c:?}",
                c.expected
            )),
            Err(e) => failures.push(format!(
                "camera case {case}: panic {}: {c:?}",
                panic_message(&*e)
            )),
        }
        for e in [m.expected, c.expected] {
            let k = format!("{e:?}")
                .split(['(', ' '])
                .next()
                .unwrap_or("")
                .to_string();
            *seen.entry(k).or_insert(0) += 1;
        }
    }
    println!(
        "fuzz errors: {ERROR_CASES} meshes + {ERROR_CASES} cameras in {:.2} s: {seen:?}",
        t.elapsed().as_secs_f64()
    );
    assert!(
        failures.is_empty(),
        "{} failures, first: {:#?}",
        failures.len(),
        &failures[..failures.len().min(5)]
    );
    for k in ["None", "Some"] {
        assert!(seen.get(k).copied().unwrap_or(0) > 1000, "{k}: {seen:?}");
    }
}

/// Valid meshes (extreme but finite coordinates, repeated indices, zero-area faces)
/// under valid cameras: no panic, no span outside the target, only the allowed
/// errors; the two code-fill row representations agree.
#[test]
fn valid_scenes_never_panic_or_write_outside_the_target() {
    let t = Instant::now();
    let (cases, seed) = render_cases();
    let only = only_cases();
    let mut rng = Rng::new(seed);
    let mut outcomes = BTreeMap::<String, usize>::new();
    let mut failures = Vec::new();
    let mut frames = 0usize;
    let mut valid = 0usize;
    for case in 0..cases {
        let coordinate: fn(&mut Rng) -> f32 = if rng.chance(0.5) {
            finite
        } else {
            |r| r.range(-2.0, 2.0) as f32
        };
        let mut m = raw_mesh(&mut rng, 0.0, coordinate);
        let mut c = raw_camera(&mut rng, 0.0);
        // Stacks of faces over one pixel: now and then 40 copies of one triangle, so
        // that a 32-bit code is too narrow.
        if rng.chance(0.05) {
            for _ in 0..40 {
                m.indices
                    .extend([0, 1, 2].map(|i| i % m.vertices.len() as u32));
                m.offsets.push(m.indices.len() as u32);
            }
        }
        if c.expected.is_some() {
            c = raw_camera(&mut rng, 0.0);
        }
        let (Ok(mesh), Ok(camera)) = (library_mesh(&m), library_camera(&c)) else {
            *outcomes.entry("setup rejected".into()).or_insert(0) += 1;
            continue;
        };
        let mut weld = vec![0u32; m.vertices.len()];
        let mut scratch = vec![HalfEdgeRecord::default(); m.indices.len()];
        let mut store = vec![MeshEdge::default(); m.indices.len()];
        let crease = rng.range(0.0, 180.0) as f32;
        let Ok(edges) = EdgeAdjacency::build(&mesh, crease, &mut weld, &mut scratch, &mut store)
        else {
            failures.push(format!("case {case}: adjacency failed with enough storage"));
            continue;
        };
        valid += 1;
        let (w, h) = [(1, 1), (7, 3), (64, 40), (128, 64), (400, 240)][rng.below(5) as usize];
        let job = Job {
            mesh: &mesh,
            edges: &edges,
            camera: &camera,
            settings: Settings {
                mode: [
                    DrawMode::Wireframe,
                    DrawMode::HiddenRemoved,
                    DrawMode::Dashed,
                    DrawMode::Surfaces,
                    DrawMode::SurfacesDashed,
                ][rng.below(5) as usize],
                cull: [Cull::On, Cull::Off, Cull::Auto][rng.below(3) as usize],
                pattern: Pattern::PAPER,
                dashes: Dashes::Screen,
                lines: pbuffer::render::LineVisibility::ByPixel,
            },
            w,
            h,
            band: 1 + rng.below(u64::from(h)) as u16,
            short: rng.chance(0.03),
        };
        let s = [0, 4, 12][rng.below(3) as usize];
        if let Some(only) = &only {
            if !only.contains(&case) {
                continue;
            }
            println!(
                "case {case}: {w}x{h} band {} short {} S={s} {:?} {:?} crease {crease}: {m:?} {c:?}",
                job.band, job.short, job.settings.mode, job.settings.cull
            );
        }
        let mut sliced_vs_crossings: Vec<Option<u64>> = Vec::new();
        for engine in [
            Engine::Crossings,
            Engine::BitSliced,
            Engine::Ordered,
            Engine::Z16,
            Engine::Z32,
            Engine::Fast,
            Engine::FastSegments,
        ] {
            frames += 1;
            let r = catch_unwind(AssertUnwindSafe(|| render(&job, engine, s)));
            let (result, sink) = match r {
                Ok(r) => r,
                Err(e) => {
                    failures.push(format!(
                        "case {case} {engine:?} S={s}: panic {}: {m:?} {c:?}",
                        panic_message(&*e)
                    ));
                    continue;
                }
            };
            if !sink.outside.is_empty() {
                failures.push(format!(
                    "case {case} {engine:?} S={s}: spans outside {w}x{h}: {:?}",
                    &sink.outside[..sink.outside.len().min(3)]
                ));
            }
            // The segment path drew (not left to the per-pixel test).
            if let (Engine::FastSegments, Ok(stats)) = (engine, &result) {
                if stats.segments.drawn > 0 && stats.segments.fallback == 0 {
                    *outcomes
                        .entry("FastSegments by segment".into())
                        .or_insert(0) += 1;
                }
            }
            let key = match &result {
                Ok(_) => "Ok".to_string(),
                Err(e) => format!("{e:?}")
                    .split([' ', '(', '{'])
                    .next()
                    .unwrap_or("")
                    .to_string(),
            };
            let allowed = match result {
                Ok(_) => true,
                Err(Error::CapacityExceeded {
                    needed, capacity, ..
                }) => needed > capacity,
                Err(Error::CodeTooWide { needed, capacity }) => needed > capacity && capacity == 32,
                Err(Error::OutOfRange) => true,
                // More fragments than face ids can name.
                Err(Error::TooManyFaces { faces, max }) => {
                    matches!(
                        engine,
                        Engine::Ordered | Engine::Fast | Engine::FastSegments
                    ) && faces > max
                }
                // The fast engine keeps at most 6 sub-pixel bits (S = 12 asks 12).
                Err(Error::SubpixelTooFine { bits, max }) => {
                    matches!(engine, Engine::Fast | Engine::FastSegments) && bits > max
                }
                Err(_) => false,
            };
            if job.short
                && !matches!(
                    result,
                    Err(Error::CapacityExceeded { .. })
                        | Err(Error::OutOfRange)
                        | Err(Error::SubpixelTooFine { .. })
                )
            {
                failures.push(format!(
                    "case {case} {engine:?}: short vertex cache gave {result:?}"
                ));
            } else if !allowed {
                failures.push(format!(
                    "case {case} {engine:?} S={s}: unexpected {result:?}: {m:?} {c:?}"
                ));
            }
            *outcomes.entry(format!("{engine:?} {key}")).or_insert(0) += 1;
            if matches!(engine, Engine::Crossings | Engine::BitSliced) {
                sliced_vs_crossings.push(result.is_ok().then_some(sink.pixels));
            }
        }
        if let [Some(a), Some(b)] = sliced_vs_crossings[..] {
            if a != b {
                failures.push(format!(
                    "case {case}: crossings drew {a} px, bit-sliced {b} px: {m:?} {c:?}"
                ));
            }
        }
    }
    println!(
        "fuzz render: {cases} scenes (seed {seed:#x}), {valid} valid, {frames} frames in {:.2} s: {outcomes:?}",
        t.elapsed().as_secs_f64()
    );
    assert!(
        failures.is_empty(),
        "{} failures, first: {:#?}",
        failures.len(),
        &failures[..failures.len().min(5)]
    );
    if only.is_some() {
        return;
    }
    for k in [
        "Z32 Ok",
        "Crossings CodeTooWide",
        "Z16 CapacityExceeded",
        "Ordered Ok",
        "Ordered CodeTooWide",
        "Fast Ok",
        "FastSegments by segment",
    ] {
        assert!(
            outcomes.get(k).copied().unwrap_or(0) > 0,
            "{k} never happened: {outcomes:?}"
        );
    }
}

/// Regression (found by `bad_meshes_and_cameras_give_the_precise_error`): a view
/// 1e35 long overflowed the square in `normalize` and was rejected as
/// `BadCamera(EyeAtTarget)`; one 1e-30 long underflowed it. Both are cameras.
#[test]
fn camera_looking_1e35_or_1e_minus_30_away_is_not_eye_at_target() {
    for d in [1e35f32, 1e-30] {
        let c = Camera::new(
            [0.0; 3],
            [0.0, 0.0, -d],
            [0.0, 1.0, 0.0],
            pbuffer::Projection::Perspective { fov_y_deg: 60.0 },
            0.1,
            100.0,
        );
        assert!(c.is_ok(), "view {d} long: {c:?}");
    }
    let up = Camera::new(
        [0.0; 3],
        [0.0, 0.0, -1.0],
        [0.0, 1e35, 0.0],
        pbuffer::Projection::Perspective { fov_y_deg: 60.0 },
        0.1,
        100.0,
    );
    assert!(up.is_ok(), "up 1e35 long: {up:?}");
}
