//! `report -- engines`: every visibility engine on every scene, in one table.
//! Instructions per frame (callgrind), working RAM, face-id mismatches near and away
//! from edges against the f64 reference, and where each engine breaks, with why.
//! Writes `report/engines.md`.

use std::fmt::Write as _;

use super::errors::{measure, Errors};
use super::{load_scene, MODELS, PROCEDURAL};
use crate::frame::{EngineSpec, ModeSpec, RenderSpec};
use crate::pipeline::render_frame;
use crate::reference3d::reference_frame;
use crate::tools::callgrind::thousands;

/// Scenes of `--quick` (and of the CI test).
pub const QUICK_SCENES: [&str; 4] = ["cube", "boxes", "cyclic", "suzanne"];

/// One engine on one scene.
#[derive(Clone, Debug)]
pub struct EngineRow {
    pub scene: String,
    pub size: (usize, usize),
    pub engine: EngineSpec,
    /// `Err` when the engine could not render the scene (capacity, etc.).
    pub errors: Result<Errors, String>,
    pub working_ram: u64,
    pub time_us: u64,
    pub ir: Option<u64>,
}

impl EngineRow {
    /// Whether the frame has the defects the metrics forbid: holes, wrong faces,
    /// depth-order errors or face-id differences away from edges.
    pub fn breaks(&self) -> bool {
        match &self.errors {
            Ok(e) => e.far_diffs + e.holes + e.wrong_faces + e.depth_order > 0,
            Err(_) => true,
        }
    }
}

/// Why `engine` is expected to fail on `scene`, when it is: the scenes each method
/// is not meant for. Any other failure is a defect (the test fails on it).
pub fn expected_failure(engine: EngineSpec, scene: &str) -> Option<&'static str> {
    match engine {
        EngineSpec::Painter => match scene {
            "cube" | "icosphere" => None,
            "coplanar" => Some("overlapping coplanar faces tie in depth, but the painter orders them by their farthest points (different boxes), not by the lower face index the conventions ask for"),
            "cyclic" => Some("three sticks overlap cyclically: no order of whole faces is right, and the painter does not split"),
            "boxes" | "frame" | "gear" | "torus" => Some("sorting by the farthest point misorders faces whose depth ranges overlap (a near face with a far corner is painted before a face it hides); no Newell tests, no splitting"),
            _ => Some("a model's faces overlap in depth range everywhere: the farthest point is not an order"),
        },
        EngineSpec::Newell => (scene == "suzanne").then_some("suzanne's quads are not planar; Newell's plane-side tests treat each as its plane within its own thickness, so where a face passes through another's bulge the order is wrong at a few pixels"),
        EngineSpec::Bsp => {
            (scene == "suzanne").then_some("suzanne's quads are not planar: the tree orders their fan triangles, and where such a face folds on screen the painter paints its fragments only where its polygon covers; along a fan diagonal the seams' snapped split points leave a pixel or two where that and the fragments' parity (what the code fill counts) disagree")
        }
        EngineSpec::Fast => (scene == "suzanne").then_some("approximate (16-bit depth, a tie of a sixteenth of a pixel's depth change): at 128x64 one pixel 0.09 px from an edge shows the face that meets the visible one there, which lies behind it (the engines_table test bounds it at one pixel)"),
        _ => None,
    }
}

/// The scene names of a run.
pub fn scene_names(quick: bool) -> Vec<&'static str> {
    if quick {
        QUICK_SCENES.to_vec()
    } else {
        ["cube", "icosphere"]
            .into_iter()
            .chain(PROCEDURAL)
            .chain(MODELS)
            .collect()
    }
}

/// The render settings of one engine: dashed hidden lines, S = 4, full frame.
pub fn spec(engine: EngineSpec, (width, height): (usize, usize)) -> RenderSpec {
    RenderSpec {
        engine,
        width,
        height,
        band: height,
        mode: ModeSpec::Dashed,
        ..RenderSpec::default()
    }
}

/// Renders every engine on every scene and measures it against the reference.
pub fn errors_pass(
    scenes: &[&str],
    size: (usize, usize),
    engines: &[EngineSpec],
) -> (Vec<EngineRow>, Vec<String>) {
    let (mut rows, mut skipped) = (Vec::new(), Vec::new());
    let progress = crate::tools::progress::Progress::new("report: engines", "scene", scenes.len());
    for &name in scenes {
        let scene = match load_scene(name) {
            Ok(s) => s,
            Err(e) => {
                skipped.push(format!("{name}: {e}"));
                progress.step();
                continue;
            }
        };
        let cam = scene.camera(size.0, size.1, false);
        let rf = match reference_frame(&scene.mesh, &cam, &spec(EngineSpec::ZBuffer, size)) {
            Ok(r) => r,
            Err(e) => {
                skipped.push(format!("{name}: reference: {e}"));
                progress.step();
                continue;
            }
        };
        for &engine in engines {
            let frame = render_frame(&scene.mesh, &cam, &spec(engine, size));
            let (errors, working_ram, time_us) = match frame {
                Ok(f) => (
                    Ok(measure(&f, &rf)),
                    f.stat("working_ram_bytes"),
                    f.stat("time_us"),
                ),
                Err(e) => (Err(e), 0, 0),
            };
            rows.push(EngineRow {
                scene: name.into(),
                size,
                engine,
                errors,
                working_ram,
                time_us,
                ir: None,
            });
        }
        progress.step();
    }
    (rows, skipped)
}

/// The callgrind child key of a row.
pub fn job_key(r: &EngineRow) -> String {
    format!(
        "engines|{}|{}x{}|{}",
        r.scene,
        r.size.0,
        r.size.1,
        r.engine.name()
    )
}

/// Runs child job `engines|scene|WxH|engine`; returns the pixels set.
pub fn child(key: &str) -> Result<usize, String> {
    let parts: Vec<&str> = key.split('|').collect();
    let [_, scene, size, engine] = parts[..] else {
        return Err(format!("bad job key {key:?}"));
    };
    let (w, h) = size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .ok_or_else(|| format!("bad size in {key:?}"))?;
    let engine = EngineSpec::by_name(engine).ok_or_else(|| format!("bad engine in {key:?}"))?;
    let scene = load_scene(scene)?;
    let frame = render_frame(
        &scene.mesh,
        &scene.camera(w, h, false),
        &spec(engine, (w, h)),
    )?;
    Ok(crate::image::count_set(&frame.packed, w, h))
}

/// Instruction counts of every row (callgrind, `jobs` at a time); `Err` says why
/// there are none.
pub fn counts_pass(rows: &mut [EngineRow], jobs: usize) -> Result<(), String> {
    crate::tools::callgrind::tool_version("valgrind", "--version")
        .ok_or("valgrind is not installed: no instruction counts")?;
    let exe = std::env::current_exe().map_err(|e| format!("cannot find the report binary: {e}"))?;
    let dir = std::env::temp_dir().join(format!("pbuffer-engines-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let keys: Vec<String> = rows.iter().map(job_key).collect();
    let out = super::run::run_jobs(&exe, &dir, &keys, jobs);
    std::fs::remove_dir_all(&dir).ok();
    let mut failed = Vec::new();
    for (row, r) in rows.iter_mut().zip(out) {
        match r {
            Ok(ir) => row.ir = Some(ir),
            Err(e) => failed.push(e),
        }
    }
    match failed.first() {
        Some(first) => Err(format!("{} jobs failed; first: {first}", failed.len())),
        None => Ok(()),
    }
}

/// One-line description of each engine, for the table's legend.
pub fn describe(engine: EngineSpec) -> &'static str {
    match engine {
        EngineSpec::CodeFill => {
            "modulo-2 surface codes per row in a BSP order, priority encoder, bit-sliced rows"
        }
        EngineSpec::CodeFillCrossings => "the same with a sorted crossing list per row",
        EngineSpec::Scanline => {
            "surface codes, planes compared only where the code shows overlap (notes 004)"
        }
        EngineSpec::ZBuffer => "depth buffer (32-bit here), the whole frame",
        EngineSpec::Painter => "faces sorted by farthest depth, painted far to near, no splitting",
        EngineSpec::Bsp => "BSP tree built once, walked per view, fragments painted far to near",
        EngineSpec::Newell => "Newell's depth sort per view (z-extent, x/y extents, plane sides, projection overlap), shuffle and split; fragments painted far to near",
        EngineSpec::Raycast => "one fixed-point ray per pixel centre through a per-frame BVH of screen boxes",
        EngineSpec::Warnock => "area subdivision (explicit bounded stack), leaves at one pixel decided by the Z-buffer's rule",
        #[allow(unreachable_patterns)]
        _ => "",
    }
}

/// The markdown document.
pub fn markdown(
    rows: &[EngineRow],
    skipped: &[String],
    command: &str,
    seconds: f64,
    counts: &Result<(), String>,
) -> String {
    let mut s = String::from("# Every engine on every scene\n\n");
    let _ = writeln!(s, "Generated by `{command}` in {seconds:.0} s. Dashed hidden lines, S = 4, full-frame band, against the f64 reference renderer (`host_tests/src/reference3d/`). *near* = face-id mismatches within 1 px of a projected edge, *far* = away from edges (must be 0 where an engine is meant to work); *holes*, *wrong*, *order* = holes, wrong faces and depth-order errors (`host_tests/src/metrics/`). Instructions: callgrind, the library's frame only (tree builds done once per mesh are outside; per-view work such as a BSP walk or a depth sort is inside). RAM: the working RAM of the frame (lent buffers, engine state, and a BSP tree's kept storage).\n");
    if let Err(why) = counts {
        let _ = writeln!(s, "**Instruction counts incomplete: {why}.**\n");
    }
    for k in skipped {
        let _ = writeln!(s, "- skipped: {k}");
    }
    let mut engines: Vec<EngineSpec> = Vec::new();
    for r in rows {
        if !engines.contains(&r.engine) {
            engines.push(r.engine);
        }
    }
    s += "\n| engine | method |\n|---|---|\n";
    for e in &engines {
        let _ = writeln!(s, "| `{}` | {} |", e.name(), describe(*e));
    }
    // Summary per engine.
    s += "\n## Summary over the scenes\n\n| engine | instructions (mean) | RAM (max) | near | far | holes | wrong | order | scenes broken |\n|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for e in &engines {
        let mine: Vec<&EngineRow> = rows.iter().filter(|r| r.engine == *e).collect();
        let irs: Vec<u64> = mine.iter().filter_map(|r| r.ir).collect();
        let mean = if irs.len() == mine.len() && !irs.is_empty() {
            thousands(irs.iter().sum::<u64>() / irs.len() as u64)
        } else {
            "-".into()
        };
        let mut sum = Errors::default();
        for r in &mine {
            if let Ok(x) = &r.errors {
                sum.add(x);
            }
        }
        let broken: Vec<&str> = mine
            .iter()
            .filter(|r| r.breaks())
            .map(|r| r.scene.as_str())
            .collect();
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} | {} | {} | {} | {} |",
            e.name(),
            mean,
            thousands(mine.iter().map(|r| r.working_ram).max().unwrap_or(0)),
            sum.near_diffs,
            sum.far_diffs,
            sum.holes,
            sum.wrong_faces,
            sum.depth_order,
            if broken.is_empty() {
                "none".to_string()
            } else {
                broken.join(", ")
            }
        );
    }
    // Per scene.
    let mut scenes: Vec<&str> = Vec::new();
    for r in rows {
        if !scenes.contains(&r.scene.as_str()) {
            scenes.push(&r.scene);
        }
    }
    for sc in &scenes {
        let size = rows
            .iter()
            .find(|r| r.scene == *sc)
            .map_or((0, 0), |r| r.size);
        let _ = writeln!(s, "\n## {sc} ({}x{})\n\n| engine | instructions | RAM | time (us, native) | near | far | holes | wrong | order |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|", size.0, size.1);
        for r in rows.iter().filter(|r| r.scene == *sc) {
            match &r.errors {
                Ok(e) => {
                    let _ = writeln!(
                        s,
                        "| `{}` | {} | {} | {} | {} | {}{} | {} | {} | {} |",
                        r.engine.name(),
                        r.ir.map_or("-".into(), thousands),
                        thousands(r.working_ram),
                        r.time_us,
                        e.near_diffs,
                        e.far_diffs,
                        if r.breaks() { " **x**" } else { "" },
                        e.holes,
                        e.wrong_faces,
                        e.depth_order
                    );
                }
                Err(why) => {
                    let _ = writeln!(s, "| `{}` | failed: {why} | | | | | | | |", r.engine.name());
                }
            }
        }
    }
    // Where each engine breaks.
    s += "\n## Where each engine breaks, and why\n\n";
    let mut any = false;
    for r in rows.iter().filter(|r| r.breaks()) {
        any = true;
        let why = expected_failure(r.engine, &r.scene).unwrap_or("**not expected: a defect**");
        let detail = match &r.errors {
            Ok(e) => format!(
                "{} far, {} holes, {} wrong, {} order of {} covered px",
                e.far_diffs, e.holes, e.wrong_faces, e.depth_order, e.ref_covered
            ),
            Err(e) => format!("failed: {e}"),
        };
        let _ = writeln!(s, "- `{}` on {}: {detail}. {why}", r.engine.name(), r.scene);
    }
    if !any {
        s += "No engine breaks on these scenes.\n";
    }
    s
}
