//! Issue 24, item 4: world coordinates far from the origin. Two boxes near
//! (1e7, -2e7, 3e7) seen from a few units away, on a ground quad reaching 1e9 units
//! out, with far = 1000 and with far = 1e10. In `f32` at 3e7 positions are 2 units
//! apart, so the boxes were refused ("coordinate does not fit the fixed-point
//! type"); moved to a local origin in `f64` first (`host_tests::origin`), the scene
//! is drawn: against the f64 reference, no holes, and the fast engine (the
//! default) within its accuracy limits, the ground drawn to its clipped horizon and
//! the boxes in their depth order, the boxes' bottom edges on the ground visible.

use host_tests::frame::{CameraSpec, EngineSpec, MeshData, ModeSpec, ProjectionSpec, RenderSpec};
use host_tests::metrics::{compare_lines, compare_surfaces};
use host_tests::pipeline::render_frame;
use host_tests::reference3d::reference_frame;
use host_tests::shapes;

const BASE: [f64; 3] = [1e7, -2e7, 3e7];

fn at(p: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| BASE[i] + p[i])
}

/// Ground (face 0, reaching 1e9 out), then two boxes standing on it.
fn scene() -> MeshData {
    let mut m = MeshData::default();
    let g = 1e9;
    m.vertices.extend([
        at([-g, 0.0, g]),
        at([g, 0.0, g]),
        at([g, 0.0, -g]),
        at([-g, 0.0, -g]),
    ]);
    m.faces.push(vec![0, 1, 2, 3]);
    shapes::add_box(&mut m, at([0.0, 0.5, 0.0]), [0.5, 0.5, 0.5], 0.0, 0.0);
    shapes::add_box(&mut m, at([1.0, 0.6, -1.6]), [0.5, 0.6, 0.4], 0.5, 0.0);
    m
}

fn camera(far: f64) -> CameraSpec {
    CameraSpec {
        eye: at([3.0, 2.0, 5.0]),
        target: at([0.4, 0.4, -0.6]),
        up: [0.0, 1.0, 0.0],
        projection: ProjectionSpec::Perspective { fov_deg: 50.0 },
        near: 0.1,
        far,
    }
}

fn spec(engine: EngineSpec, mode: ModeSpec) -> RenderSpec {
    RenderSpec {
        engine,
        width: 200,
        height: 120,
        band: 120,
        mode,
        ..RenderSpec::default()
    }
}

#[test]
fn boxes_far_from_the_origin_on_a_ground_reaching_1e9() {
    let m = scene();
    for far in [1000.0, 1e10] {
        let cam = camera(far);
        let rf = reference_frame(&m, &cam, &spec(EngineSpec::ZBuffer, ModeSpec::Surfaces))
            .expect("reference");
        // Ground and both boxes show in the reference.
        let mut seen = std::collections::BTreeSet::new();
        seen.extend(rf.ids.iter().copied().filter(|&i| i != 0));
        assert!(seen.contains(&1) && seen.len() >= 5, "far {far}: {seen:?}");
        let engine = EngineSpec::Fast;
        let what = format!("far {far} {}", engine.name());
        let frame = render_frame(&m, &cam, &spec(engine, ModeSpec::Surfaces))
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        let s = compare_surfaces(&frame, &rf);
        let covered = rf.ids.iter().filter(|&&i| i != 0).count();
        println!(
            "{what}: holes {} wrong {} order {} far {} of {covered}",
            s.holes, s.wrong_faces, s.depth_order, s.far_diffs
        );
        assert_eq!(s.holes, 0, "{what}");
        let far_px = s.wrong_faces + s.depth_order + s.far_diffs;
        assert!(far_px * 2000 <= covered, "{what}: {far_px} far differences");
        let dashed = render_frame(&m, &cam, &spec(engine, ModeSpec::Dashed))
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        let l = compare_lines(&dashed, &rf);
        println!(
            "{what}: misclassified {} of {}, visible missing {:.1} of {:.1}, hidden missing {:.1} of {:.1} (first misclassified at {:?})",
            l.misclassified, l.line_pixels, l.visible_missing, l.visible_len, l.hidden_missing,
            l.hidden_len, l.first_misclassified
        );
        // The second box's bottom edge lies on the ground: the ground is nearest at
        // the pixel centres below it, and was taken as hiding 7 (far 1000) and 10
        // (far 1e10) of its pixels until the line test compared the ground's plane
        // at the edge point itself (2026-11-26): within issue 23's limits now.
        assert!(l.misclassified_fraction() <= 0.005, "{what}");
        assert!(l.visible_missing <= 0.01 * l.visible_len, "{what}");
        assert!(l.hidden_missing <= 0.01 * l.hidden_len, "{what}");
    }
}

/// The exact engines on the same scene: with far = 1000 the ground is cut in `f64`
/// to the view (`host_tests::origin::cut_huge_faces`); with far = 1e10 it still
/// reaches 1e9 inside the view volume, where one fixed-point position scale (26
/// bits for the largest coordinate) cannot also hold the boxes beside the eye, and
/// was refused as `OutOfRange` until the scene was brought within `2^17` near
/// distances along its rays (`host_tests::origin::warp_far_depths`, the same
/// picture). Both: the reference's surfaces and lines.
#[test]
fn exact_engines_draw_boxes_on_a_ground_reaching_1e9_at_far_1000_and_1e10() {
    let m = scene();
    for far in [1000.0, 1e10] {
        let cam = camera(far);
        let rf = reference_frame(&m, &cam, &spec(EngineSpec::ZBuffer, ModeSpec::Surfaces))
            .expect("reference");
        for engine in [
            EngineSpec::ZBuffer,
            EngineSpec::Scanline,
            EngineSpec::CodeFill,
        ] {
            let what = format!("far {far} {}", engine.name());
            let frame = render_frame(&m, &cam, &spec(engine, ModeSpec::Surfaces))
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            let s = compare_surfaces(&frame, &rf);
            println!("{what}: {s:?}");
            assert_eq!([s.holes, s.wrong_faces, s.depth_order], [0, 0, 0], "{what}");
            let dashed = render_frame(&m, &cam, &spec(engine, ModeSpec::Dashed))
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            let l = compare_lines(&dashed, &rf);
            println!(
                "{what}: misclassified {} of {}, visible missing {:.1} of {:.1}, hidden missing {:.1} of {:.1}",
                l.misclassified, l.line_pixels, l.visible_missing, l.visible_len, l.hidden_missing,
                l.hidden_len
            );
            assert!(l.misclassified_fraction() <= 0.005, "{what}");
            assert!(l.visible_missing <= 0.01 * l.visible_len, "{what}");
            assert!(l.hidden_missing <= 0.01 * l.hidden_len, "{what}");
        }
    }
}
