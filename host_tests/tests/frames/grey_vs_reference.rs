//! The grey coverage mode (`ZBufferRenderer::render_grey`, fixed point, 4 x 4
//! sub-samples at face edges) against the f64 reference of the same quantity
//! (`host_tests::grey::reference_grey`: the nearest face at each of the 16
//! sub-samples of every pixel, unsnapped geometry), mode `surfaces`.
//!
//! Limit, per scene: at least 99 % of the pixels that either frame draws (not
//! background in both) within 1/16 of full scale (16 levels of 255) of the reference.
//! One report line per scene: `cargo test --release -p host_tests --test
//! grey_vs_reference -- --nocapture`.

use std::path::PathBuf;

use host_tests::frame::{CameraSpec, EngineSpec, MeshData, ModeSpec, RenderSpec};
use host_tests::grey::{reference_grey, render_grey, shades};
use host_tests::pipeline::render_frame;
use host_tests::reference3d::reference_frame;
use host_tests::shapes;

/// Largest difference counted as agreeing: 1/16 of full scale.
const TOLERANCE: u8 = 16;
/// Fraction of drawn pixels that must agree.
const MIN_AGREEING: f64 = 0.99;

/// Compares one scene; returns its report line and, when it fails, the failure.
fn run_scene(
    name: &str,
    mesh: &MeshData,
    cam: &CameraSpec,
    w: usize,
    h: usize,
) -> (String, Option<String>) {
    let spec = RenderSpec {
        engine: EngineSpec::ZBuffer,
        width: w,
        height: h,
        band: h,
        mode: ModeSpec::Surfaces,
        subpixel: 4,
        depth_bits: 32,
        ..RenderSpec::default()
    };
    let label = format!("{name} {w}x{h}");
    let palette = shades();
    let rf = match reference_frame(mesh, cam, &spec) {
        Ok(r) => r,
        Err(e) => return (String::new(), Some(format!("{label}: reference: {e}"))),
    };
    let reference = reference_grey(&rf, mesh, cam, &palette);
    let frame = match render_grey(mesh, cam, &spec, &palette) {
        Ok(f) => f,
        Err(e) => return (String::new(), Some(format!("{label}: library: {e}"))),
    };
    // The same frame without coverage, for the cost.
    let flat_us = render_frame(mesh, cam, &spec).map_or(0, |f| f.stat("time_us"));
    let bg = 0u8;
    let (mut drawn, mut agree, mut exact, mut sum, mut worst) = (0usize, 0usize, 0usize, 0u64, 0u8);
    for (&a, &b) in frame.grey.iter().zip(&reference) {
        if a == bg && b == bg {
            continue;
        }
        drawn += 1;
        let d = a.abs_diff(b);
        agree += usize::from(d <= TOLERANCE);
        exact += usize::from(d <= 1);
        sum += u64::from(d);
        worst = worst.max(d);
    }
    let frac = agree as f64 / drawn.max(1) as f64;
    let line = format!(
        "{label}: {drawn} drawn px, {agree} within {TOLERANCE} ({:.3} %), {exact} within 1, \
         mean |diff| {:.3}, max {worst}; grey {} us, flat {} us",
        100.0 * frac,
        sum as f64 / drawn.max(1) as f64,
        frame.time_us,
        flat_us,
    );
    let failure = (drawn == 0 || frac < MIN_AGREEING)
        .then(|| format!("{line}: below {} % [camera {cam:?}]", 100.0 * MIN_AGREEING));
    (line, failure)
}

fn finish(results: Vec<(String, Option<String>)>) {
    let mut failures = Vec::new();
    for (line, failure) in results {
        println!("{line}");
        failures.extend(failure);
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn procedural_scenes_match_reference_grey() {
    let mut results = Vec::new();
    for scene in shapes::all_scenes() {
        for (w, h, ortho) in [(400, 240, false), (128, 64, false), (400, 240, true)] {
            let cam = scene.camera(w, h, ortho);
            let name = format!("{}{}", scene.name, if ortho { " ortho" } else { "" });
            results.push(run_scene(&name, &scene.mesh, &cam, w, h));
        }
    }
    finish(results);
}

fn models_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/models")
}

#[test]
fn suzanne_matches_reference_grey() {
    let path = models_dir().join("suzanne.obj");
    assert!(
        path.is_file(),
        "{} not found: {}",
        path.display(),
        "the shared models are part of the test set"
    );
    let mesh = host_tests::obj::load_obj(&path).expect("suzanne loads");
    let mut results = Vec::new();
    for (w, h) in [(400, 240), (128, 64), (256, 64)] {
        let cam = host_tests::fit::fit_camera(&mesh, w, h);
        results.push(run_scene("suzanne", &mesh, &cam, w, h));
    }
    finish(results);
}
