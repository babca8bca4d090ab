//! Newell's depth sort (`pbuffer::order::NewellOrder`), sorted per frame and rendered
//! by the code-fill engine through `CodeFillRenderer::render_with`
//! (`Visibility::Order`, `host_tests::newell::render_newell_frame`), against the
//! independent f64 reference (`reference3d`), by the metrics and limits of
//! `pipeline_vs_reference`: surfaces must have no holes, no wrong faces, no
//! depth-order errors and no face-id differences away from edges; lines must stay
//! within the misclassified / missing limits. Each scene runs with bit-sliced rows
//! (full frame) and with crossings (8-row bands).
//! One report line per scene, plus the sort's figures:
//! `cargo test --release -p host_tests --test newell_order -- --nocapture`.

use std::path::PathBuf;
use std::time::Instant;

use host_tests::frame::{CameraSpec, EngineSpec, MeshData, ModeSpec, RenderSpec};
use host_tests::metrics::{compare, SceneMetrics};
use host_tests::newell::render_newell_frame;
use host_tests::reference3d::reference_frame;
use host_tests::shapes;

/// Renders `mesh` in Newell's order and compares it with the reference; returns
/// the report lines and the failures.
fn run_scene(
    name: &str,
    mesh: &MeshData,
    cam: &CameraSpec,
    width: usize,
    height: usize,
) -> (Vec<String>, Vec<String>) {
    let (mut report, mut failures) = (Vec::new(), Vec::new());
    let base = RenderSpec {
        width,
        height,
        band: height,
        subpixel: 4,
        depth_bits: 32,
        ..RenderSpec::default()
    };
    let t = Instant::now();
    let rf = match reference_frame(mesh, cam, &base) {
        Ok(r) => r,
        Err(e) => {
            failures.push(format!("{name}: reference failed: {e}"));
            return (report, failures);
        }
    };
    let ref_ms = t.elapsed().as_secs_f64() * 1e3;
    for mode in [ModeSpec::Surfaces, ModeSpec::Dashed] {
        for (engine, band) in [
            (EngineSpec::CodeFill, height),
            (EngineSpec::CodeFillCrossings, 8),
        ] {
            let spec = RenderSpec {
                engine,
                mode,
                band,
                ..base.clone()
            };
            let label = format!(
                "{name} {width}x{height} {} newell-{} band {band}",
                if mode == ModeSpec::Surfaces {
                    "surf"
                } else {
                    "dash"
                },
                engine.name(),
            );
            let t = Instant::now();
            let frame = match render_newell_frame(mesh, cam, &spec) {
                Ok(f) => f,
                Err(e) => {
                    failures.push(format!("{label}: library failed: {e}"));
                    continue;
                }
            };
            let lib_ms = t.elapsed().as_secs_f64() * 1e3;
            assert_eq!(frame.ids.len(), width * height);
            let surfaces = mode == ModeSpec::Surfaces;
            let mut m: SceneMetrics = compare(&label, &frame, &rf, surfaces, !surfaces);
            m.lib_ms = lib_ms;
            m.ref_ms = ref_ms;
            report.push(m.to_string());
            let stat = |k: &str| {
                frame
                    .stats
                    .iter()
                    .find(|(n, _)| n == k)
                    .map_or(0, |s| s.1)
            };
            if surfaces && engine == EngineSpec::CodeFill {
                report.push(format!(
                    "  newell: {} faces drawn -> {} fragments, {} splits, {} shuffles, \
                     {} unresolved, sort {} us, order {} bytes",
                    stat("faces_drawn"),
                    stat("newell_fragments"),
                    stat("newell_splits"),
                    stat("newell_shuffles"),
                    stat("newell_unresolved"),
                    stat("newell_sort_us"),
                    stat("newell_bytes"),
                ));
            }
            if let Err(e) = m.check() {
                failures.push(format!("{e} [camera {cam:?}]"));
            }
        }
    }
    (report, failures)
}

fn finish(report: &[String], failures: &[String]) {
    for l in report {
        println!("{l}");
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn procedural_scenes_match_reference() {
    let (mut report, mut failures) = (Vec::new(), Vec::new());
    for scene in shapes::all_scenes() {
        for (w, h, ortho) in [(400, 240, false), (128, 64, false), (400, 240, true)] {
            let cam = scene.camera(w, h, ortho);
            let name = format!("{}{}", scene.name, if ortho { " ortho" } else { "" });
            let (r, f) = run_scene(&name, &scene.mesh, &cam, w, h);
            report.extend(r);
            failures.extend(f);
        }
    }
    finish(&report, &failures);
}

fn models_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/models")
}

#[test]
fn models_match_reference() {
    let dir = models_dir();
    if !dir.is_dir() {
        println!(
            "note: {} not found; model comparisons skipped",
            dir.display()
        );
        return;
    }
    let (mut report, mut failures) = (Vec::new(), Vec::new());
    for name in ["suzanne", "woody", "beetle"] {
        let path = dir.join(format!("{name}.obj"));
        if !path.is_file() {
            println!("note: {} not found; skipped", path.display());
            continue;
        }
        let mesh = match host_tests::obj::load_obj(&path) {
            Ok(m) => m,
            Err(e) => {
                failures.push(format!("{name}: cannot load: {e}"));
                continue;
            }
        };
        for (w, h) in [(400, 240), (128, 64)] {
            let cam = host_tests::fit::fit_camera(&mesh, w, h);
            let (r, f) = run_scene(name, &mesh, &cam, w, h);
            report.extend(r);
            failures.extend(f);
        }
    }
    finish(&report, &failures);
}
