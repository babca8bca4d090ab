//! Depth precision follows the scene ([conventions]: "two surfaces close together
//! far from the eye get the precision they need where it exists"): two squares
//! facing the eye, `d` apart at distance `z`, in a frame whose drawn depths run
//! from `z / 2` to `2 z` (a marker triangle at each end). The front square covers
//! a corner of the back one; the back square has the lower index, so a frame that
//! cannot tell the two apart shows it (a tie goes to the lower index) and draws its
//! edges inside the overlap visible.
//!
//! For each `z` of 1, 100 and 10^4 and `d / z` from 10^-2 down to 10^-6 (about four
//! steps of the clip grid at this range, the finest the fixed-point transform keeps;
//! one unit of 32-bit nearness is 7e-10 z here), every exact engine shows the front
//! square over the overlap and hides the back square's edges there, as the f64
//! reference does. The fast engine, whose depth is 16 bits (one unit is 2.3e-5 z
//! here), is held to `d / z` down to 10^-4. Closer than the clip grid (10^-8) the
//! check fails: the self-test.
//!
//! [conventions]: ../../../../shared/CONVENTIONS.md
//! `cargo test --release -p host_tests --test frames depth_precision:: -- --nocapture`.

use host_tests::frame::{
    CameraSpec, CullSpec, EngineSpec, MeshData, ModeSpec, ProjectionSpec, RenderSpec,
};
use host_tests::metrics::compare;
use host_tests::pipeline::render_frame;
use host_tests::reference3d::reference_frame;

const SIZE: (usize, usize) = (160, 120);

/// The two squares `d` apart at distance `z` (back square face 0, front face 1)
/// and the two depth markers (faces 2 and 3).
fn scene(z: f64, d: f64) -> (MeshData, CameraSpec) {
    let mut m = MeshData::default();
    let mut square = |x0: f64, y0: f64, x1: f64, y1: f64, depth: f64| {
        let n = m.vertices.len() as u32;
        m.vertices.extend([
            [x0 * z, y0 * z, depth],
            [x1 * z, y0 * z, depth],
            [x1 * z, y1 * z, depth],
            [x0 * z, y1 * z, depth],
        ]);
        m.faces.push(vec![n, n + 1, n + 2, n + 3]);
    };
    // The eye at (0, 0, z) looks down -z: world depth 0 is distance z.
    square(-0.3, -0.3, 0.1, 0.1, 0.0);
    square(-0.1, -0.1, 0.3, 0.3, d);
    // Markers in the corners, at distances z / 2 and 2 z.
    square(-0.28, 0.18, -0.22, 0.24, 0.5 * z);
    square(0.5, -0.8, 0.6, -0.7, -z);
    let cam = CameraSpec {
        eye: [0.0, 0.0, z],
        target: [0.0, 0.0, 0.0],
        up: [0.0, 1.0, 0.0],
        projection: ProjectionSpec::Perspective { fov_deg: 60.0 },
        near: 0.1 * z.min(1.0),
        far: 100.0 * z,
    };
    (m, cam)
}

/// `Err` with the reasons when `engine` at S (8, or 4 for the fast engine) does
/// not draw the scene as the reference does, or the reference itself does not
/// show the front square over the overlap with the back square's edges hidden.
fn check(engine: EngineSpec, z: f64, d: f64) -> Result<(), String> {
    let (mesh, cam) = scene(z, d);
    let spec = RenderSpec {
        engine,
        width: SIZE.0,
        height: SIZE.1,
        band: SIZE.1,
        mode: ModeSpec::Dashed,
        cull: CullSpec::Off,
        subpixel: if engine == EngineSpec::Fast { 4 } else { 8 },
        ..RenderSpec::default()
    };
    let rf = reference_frame(&mesh, &cam, &spec).map_err(|e| format!("reference: {e}"))?;
    let (w, h) = SIZE;
    // The overlap's centre is the view's centre.
    let centre = (h / 2) * w + w / 2;
    assert_eq!(rf.ids[centre], 2, "the reference shows the front square");
    assert!(
        rf.samples.iter().any(|s| !s.visible),
        "the reference hides lines"
    );
    let frame = render_frame(&mesh, &cam, &spec).map_err(|e| format!("render: {e}"))?;
    let label = format!("{} z {z:e} d/z {:e}", engine.name(), d / z);
    let m = compare(&label, &frame, &rf, true, true);
    println!("{m}");
    if frame.ids[centre] != 2 {
        return Err(format!("{label}: face {} at the centre", frame.ids[centre]));
    }
    m.check()
}

#[test]
fn two_faces_apart_by_a_millionth_of_their_distance_are_told_apart() {
    let mut failures = Vec::new();
    for z in [1.0, 100.0, 1e4] {
        for ratio in [1e-2, 1e-3, 1e-4, 1e-5, 1e-6] {
            for engine in [
                EngineSpec::ZBuffer,
                EngineSpec::Scanline,
                EngineSpec::CodeFill,
                EngineSpec::Warnock,
                EngineSpec::Raycast,
            ] {
                if let Err(e) = check(engine, z, ratio * z) {
                    failures.push(e);
                }
            }
            if ratio >= 1e-4 {
                if let Err(e) = check(EngineSpec::Fast, z, ratio * z) {
                    failures.push(e);
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The check above can fail: 10^-8 of the distance apart, which the reference
/// tells (it hides a point nearer by 10^-9 of its distance) and a sixth of a step
/// of the clip grid, the two squares are not told apart.
#[test]
fn self_test_faces_closer_than_the_clip_grid_fail_the_check() {
    for engine in [EngineSpec::ZBuffer, EngineSpec::Scanline, EngineSpec::Fast] {
        assert!(
            check(engine, 100.0, 1e-6).is_err(),
            "{} told apart faces 1e-8 of their distance apart",
            engine.name()
        );
    }
}
