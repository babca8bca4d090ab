//! The library's 3-D pipeline (`host_tests::pipeline::render_frame`: fixed point, both
//! engines) against the independent f64 reference (`reference3d`), by the metrics of
//! `host_tests::metrics`: surfaces (ids, mode `surfaces`) must have no holes, no wrong
//! faces, no depth-order errors and no face-id differences away from edges; lines
//! (mode `dashed`) must stay within the misclassified / missing limits. Each scene runs
//! with the code-fill engine (full frame, and 8-row bands with bit-sliced rows) and the
//! Z-buffer engine (a full-frame band with 32-bit depth, and 8-row bands with 16-bit
//! depth), Warnock's area subdivision and the ray-casting engine (each a full-frame
//! band and 8-row bands).
//! One report line per scene: `cargo test --release -p host_tests --test
//! pipeline_vs_reference -- --nocapture`.

use std::path::PathBuf;
use std::time::Instant;

use host_tests::frame::{CameraSpec, EngineSpec, MeshData, ModeSpec, RenderSpec};
use host_tests::metrics::{compare, snapping_bound, unexplained_diffs, SceneMetrics};
use host_tests::pipeline::render_frame;
use host_tests::reference3d::reference_frame;
use host_tests::shapes;

/// Renders `mesh` with the library and compares it with the reference for both modes
/// and both band heights; returns the report lines and the failures.
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
        for (engine, band, depth_bits) in [
            (EngineSpec::CodeFill, height, 32),
            (EngineSpec::Scanline, height, 32),
            (EngineSpec::CodeFillCrossings, 8, 32),
            (EngineSpec::ZBuffer, height, 32),
            (EngineSpec::ZBuffer, 8, 16),
            (EngineSpec::Warnock, height, 32),
            (EngineSpec::Warnock, 8, 32),
            (EngineSpec::Raycast, height, 32),
            (EngineSpec::Raycast, 8, 32),
        ] {
            let spec = RenderSpec {
                engine,
                mode,
                band,
                depth_bits,
                ..base.clone()
            };
            let label = format!(
                "{name} {width}x{height} {} {} band {band}{}",
                if mode == ModeSpec::Surfaces {
                    "surf"
                } else {
                    "dash"
                },
                engine.name(),
                if engine == EngineSpec::ZBuffer {
                    format!(" depth {depth_bits}")
                } else {
                    String::new()
                }
            );
            let t = Instant::now();
            let frame = match render_frame(mesh, cam, &spec) {
                Ok(f) => f,
                Err(e) => {
                    failures.push(format!("{label}: library failed: {e}"));
                    continue;
                }
            };
            let lib_ms = t.elapsed().as_secs_f64() * 1e3;
            if (frame.width, frame.height) != (width, height)
                || frame.ids.len() != width * height
                || frame.lines.len() != width * height
            {
                failures.push(format!("{label}: frame has the wrong size"));
                continue;
            }
            let surfaces = mode == ModeSpec::Surfaces;
            let mut m: SceneMetrics = compare(&label, &frame, &rf, surfaces, !surfaces);
            m.lib_ms = lib_ms;
            m.ref_ms = ref_ms;
            report.push(m.to_string());
            let stat = |k: &str| frame.stats.iter().find(|(n, _)| n == k).map(|s| s.1);
            // The counts agree exactly on every scene here (they were only printed
            // before; `feature_edges.rs` covers more views with a tolerance).
            if stat("feature_edges") != Some(rf.feature_edges as u64) {
                failures.push(format!(
                    "{label}: feature edges: library {:?}, reference {}",
                    stat("feature_edges"),
                    rf.feature_edges
                ));
            }
            if stat("faces_drawn") != Some(rf.faces_drawn as u64) {
                failures.push(format!(
                    "{label}: faces drawn: library {:?}, reference {}",
                    stat("faces_drawn"),
                    rf.faces_drawn
                ));
            }
            if let Err(e) = m.check() {
                failures.push(format!("{e} [camera {cam:?}]"));
            }
            if surfaces {
                // The exact rule: every differing pixel lies within the snapping bound
                // of an edge of its two faces, or on their intersection.
                let (n, first) = unexplained_diffs(&frame, &rf, snapping_bound(spec.subpixel));
                println!("{label}: unexplained {n} first {first:?}");
                if n > 0 {
                    failures.push(format!(
                        "{label}: {n} face-id differences off every edge (first at {first:?})"
                    ));
                }
            }
        }
    }
    (report, failures)
}

// Beetle at 400x240 missed 1.18 % of the reference's hidden-edge length here (limit
// 1 %), tolerated as a known deviation until 2026-11-22: creases of a sliver seen
// edge-on, drawn visible because their own face was nearest at the pixel centres
// although another face passed in front of the edge points half a pixel off. The line
// test now asks the face beside after the edge's own face: 0.56 % to 0.60 %.

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
    assert!(
        dir.is_dir(),
        "{} not found: {}",
        dir.display(),
        "the shared models are part of the test set"
    );
    let (mut report, mut failures) = (Vec::new(), Vec::new());
    for name in [
        "suzanne", "fandisk", "beetle", "cow", "spot", "teapot", "woody",
    ] {
        let path = dir.join(format!("{name}.obj"));
        assert!(
            path.is_file(),
            "{} not found: {}",
            path.display(),
            "the shared models are part of the test set"
        );
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
