//! The report's run: native renders and error measures, then the callgrind jobs.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use pbuffer::recommend::{recommend, ErrorBound, Recommendation, SceneBounds};

use crate::reference3d::vector::{dot, norm, sub};
use pbuffer::Viewport;

use super::errors::{depth_complexity, measure, Errors};
use super::{configs, job_key, load_scene, scene_names, sizes, Config, ENGINES};
use crate::frame::{CameraSpec, ProjectionSpec, RenderSpec};
use crate::pipeline::render_frame;
use crate::reference3d::reference_frame;
use crate::setup::EXCLUDED;
use crate::shapes;
use crate::tools::callgrind::callgrind_with;
use crate::tools::progress::Progress;

/// One rendered combination.
#[derive(Clone, Debug)]
pub struct Row {
    pub scene: String,
    pub size: (usize, usize),
    pub config: Config,
    pub errors: Errors,
    pub code_bits: u64,
    pub working_ram: u64,
    /// Instructions per frame (callgrind), when measured.
    pub ir: Option<u64>,
    /// One of the settings recommended for this scene (not part of the sweep).
    pub recommended_only: bool,
    /// Engines with depth: pixels whose face differs from the code-fill engine's
    /// (full-precision depth) at the same S and band.
    pub diff_vs_codefill: Option<usize>,
}

/// The recommendation for one scene at one size, and what it was computed from.
#[derive(Clone, Debug)]
pub struct SceneCheck {
    pub scene: String,
    pub size: (usize, usize),
    pub bounds: SceneBounds,
    pub rec: Recommendation,
    /// Depth complexity per the reference.
    pub layers: usize,
}

/// Everything a run produced.
#[derive(Clone, Debug, Default)]
pub struct Results {
    pub rows: Vec<Row>,
    pub checks: Vec<SceneCheck>,
    /// Scenes skipped, with the reason.
    pub skipped: Vec<String>,
    /// Why instruction counts are missing, if they are.
    pub no_counts: Option<String>,
    pub seconds_errors: f64,
    pub seconds_counts: f64,
}

/// The error bound the report checks the recommendation against.
pub const BOUND: ErrorBound = ErrorBound { edge_px: 0.25 };

/// The scene bounds of a mesh seen by `cam`: largest coordinate of the vertices and
/// the eye, bounding radius, the distances drawn, smallest gap radius / 1000,
/// and the depth complexity measured by the reference.
pub fn scene_bounds(mesh: &crate::frame::MeshData, cam: &CameraSpec, layers: usize) -> SceneBounds {
    let max_coordinate = mesh
        .vertices
        .iter()
        .flatten()
        .chain(cam.eye.iter())
        .fold(0.0f64, |m, c| m.max(c.abs()));
    let (_, radius) = shapes::all_vertex_bounds(mesh);
    // The distances drawn: the vertices' along the view, within near..far (depth is
    // scaled to them).
    let dir = sub(cam.target, cam.eye);
    let len = norm(dir).max(f64::MIN_POSITIVE);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in &mesh.vertices {
        let d = (dot(sub(*v, cam.eye), dir) / len).clamp(cam.near, cam.far);
        (lo, hi) = (lo.min(d), hi.max(d));
    }
    if lo >= hi {
        (lo, hi) = (cam.near, cam.far);
    }
    let b = SceneBounds::perspective(max_coordinate as f32, radius as f32, lo as f32, hi as f32)
        .with_max_layers(layers as u32);
    SceneBounds {
        orthographic: matches!(cam.projection, ProjectionSpec::Orthographic { .. }),
        ..b
    }
}

/// The code-fill engine whose code width the recommendation's code words describe
/// (the most faces over one pixel): the scan-line engine. In a depth order the code
/// is as wide as the fragments active on a row, which `recommend` does not model.
pub fn recommended_code_engine() -> usize {
    ENGINES
        .iter()
        .position(|e| e.0 == pbuffer_engine_scanline())
        .unwrap_or(0)
}

fn pbuffer_engine_scanline() -> crate::frame::EngineSpec {
    crate::frame::EngineSpec::Scanline
}

/// The configurations the recommendation gives: scan-line code fill at its S (and at
/// S = 8, the floor of what S controls), the Z-buffer at its S and depth bits (and at
/// 32 bits, the comparison for its depth check).
pub fn recommended_configs(rec: &Recommendation) -> Vec<Config> {
    let zbuffer = ENGINES.iter().position(|e| e.2);
    let code = Config {
        engine: recommended_code_engine(),
        ..Config::DEFAULT
    };
    let mut v = vec![
        Config {
            subpixel: rec.subpixel_bits,
            ..code
        },
        Config {
            subpixel: 8,
            ..code
        },
    ];
    v.dedup();
    if let Some(e) = zbuffer {
        for bits in [rec.depth_bits, 32] {
            let c = Config {
                engine: e,
                subpixel: rec.subpixel_bits,
                depth_bits: Some(bits),
                band: None,
            };
            if !v.contains(&c) {
                v.push(c);
            }
        }
    }
    v
}

fn stat(stats: &[(String, u64)], k: &str) -> u64 {
    stats.iter().find(|(n, _)| n == k).map_or(0, |s| s.1)
}

/// Renders every combination natively and measures its error.
pub fn errors_pass(quick: bool, res: &mut Results) {
    let t = Instant::now();
    let names = scene_names(quick);
    let progress = Progress::new("report: errors", "scene", names.len());
    for name in names {
        let scene = match load_scene(name) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("report: {name} skipped: {e}");
                res.skipped.push(format!("{name}: {e}"));
                progress.step();
                continue;
            }
        };
        for size in sizes(quick) {
            let cam = scene.camera(size.0, size.1, false);
            let base = RenderSpec {
                width: size.0,
                height: size.1,
                band: size.1,
                ..RenderSpec::default()
            };
            let tr = Instant::now();
            let rf = match reference_frame(&scene.mesh, &cam, &base) {
                Ok(r) => r,
                Err(e) => {
                    res.skipped
                        .push(format!("{name} {}x{}: reference: {e}", size.0, size.1));
                    continue;
                }
            };
            let layers = depth_complexity(&rf);
            // The coplanar scene is built of overlapping coplanar faces.
            let bounds =
                scene_bounds(&scene.mesh, &cam, layers).with_coplanar_overlaps(name == "coplanar");
            let viewport = Viewport {
                width: size.0 as u16,
                height: size.1 as u16,
            };
            let rec = recommend(&bounds, viewport, &BOUND);
            res.checks.push(SceneCheck {
                scene: name.into(),
                size,
                bounds,
                rec,
                layers,
            });
            let sweep = configs(name, quick);
            let mut all = sweep.clone();
            for c in recommended_configs(&rec) {
                if !all.contains(&c) {
                    all.push(c);
                }
            }
            eprint!(
                "report: {name} {}x{} (reference {:.1} s) ",
                size.0,
                size.1,
                tr.elapsed().as_secs_f64()
            );
            let mut codefill_ids: Vec<(Config, Vec<u32>)> = Vec::new();
            for config in all {
                match render_frame(&scene.mesh, &cam, &config.spec(size)) {
                    Ok(frame) => res.rows.push(Row {
                        diff_vs_codefill: if config.depth_bits.is_some() {
                            let cf = Config {
                                depth_bits: None,
                                engine: super::CODEFILL,
                                ..config
                            };
                            let ids = match codefill_ids.iter().find(|c| c.0 == cf) {
                                Some(c) => Some(c.1.clone()),
                                None => render_frame(&scene.mesh, &cam, &cf.spec(size))
                                    .ok()
                                    .map(|f| f.ids),
                            };
                            ids.map(|ids| {
                                let d = ids.iter().zip(&frame.ids).filter(|(a, b)| a != b).count();
                                codefill_ids.push((cf, ids));
                                d
                            })
                        } else {
                            if config.engine == super::CODEFILL {
                                codefill_ids.push((config, frame.ids.clone()));
                            }
                            None
                        },
                        scene: name.into(),
                        size,
                        config,
                        errors: measure(&frame, &rf),
                        code_bits: stat(&frame.stats, "code_bits"),
                        working_ram: stat(&frame.stats, "working_ram_bytes"),
                        ir: None,
                        recommended_only: !sweep.contains(&config),
                    }),
                    Err(e) => res.skipped.push(format!(
                        "{name} {}x{} {}: {e}",
                        size.0,
                        size.1,
                        config.label()
                    )),
                }
                eprint!(".");
            }
            eprintln!();
        }
        progress.step();
    }
    res.seconds_errors = t.elapsed().as_secs_f64();
}

/// Counts the instructions of every row under callgrind, `jobs` at a time.
pub fn counts_pass(res: &mut Results, jobs: usize) {
    let t = Instant::now();
    let valgrind = crate::tools::callgrind::tool_version("valgrind", "--version");
    if valgrind.is_none() {
        res.no_counts = Some("valgrind is not installed: no instruction counts".into());
        return;
    }
    let keys: Vec<String> = res
        .rows
        .iter()
        .map(|r| job_key(&r.scene, r.size, &r.config))
        .collect();
    let exe = match std::env::current_exe() {
        Ok(e) => e,
        Err(e) => {
            res.no_counts = Some(format!("cannot find the report binary: {e}"));
            return;
        }
    };
    let dir = std::env::temp_dir().join(format!("pbuffer-report-{}", std::process::id()));
    if let Err(e) = std::fs::create_dir_all(&dir) {
        res.no_counts = Some(format!("cannot create {}: {e}", dir.display()));
        return;
    }
    let out = run_jobs(&exe, &dir, &keys, jobs);
    std::fs::remove_dir_all(&dir).ok();
    let mut failed = Vec::new();
    for (row, r) in res.rows.iter_mut().zip(out) {
        match r {
            Ok(ir) => row.ir = Some(ir),
            Err(e) => failed.push(e),
        }
    }
    if let Some(first) = failed.first() {
        res.no_counts = Some(format!(
            "{} jobs failed under callgrind; first: {first}",
            failed.len()
        ));
    }
    res.seconds_counts = t.elapsed().as_secs_f64();
}

/// Runs the report's callgrind jobs (`report --child KEY`), `jobs` at a time, their
/// output files in `dir`; the instructions of each, in the order of `keys`.
pub fn run_jobs(exe: &Path, dir: &Path, keys: &[String], jobs: usize) -> Vec<Result<u64, String>> {
    let next = AtomicUsize::new(0);
    let progress = Progress::new("report: callgrind", "job", keys.len());
    let results: Mutex<Vec<Option<Result<u64, String>>>> =
        Mutex::new((0..keys.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..jobs.max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= keys.len() {
                    break;
                }
                let r = callgrind_with(exe, dir, &keys[i], &EXCLUDED).map(|m| m.ir);
                progress.step();
                results.lock().expect("no panic holds the lock")[i] = Some(r);
            });
        }
    });
    results
        .into_inner()
        .expect("no panic holds the lock")
        .into_iter()
        .map(|r| r.unwrap_or_else(|| Err("job did not run".into())))
        .collect()
}
