//! Findings of an independent reference (issue 24) kept as named scenes: an open
//! cylinder seen from above into its mouth, culling off. Its outer silhouette is
//! plainly visible; a face that shares only a vertex with a silhouette edge must not
//! hide it. Every exact engine and the fast one, dashed, against the f64 reference
//! within the line limits (the fast engine was at 21.9 % misclassified, orthographic,
//! until a steep line beside an empty column was taken as an outline there).
//! Also: the fast engine's skipping of back faces away from the holes changes no
//! pixel.
//! `cargo test --release -p host_tests --test frames open_mesh:: -- --nocapture`.

use host_tests::fast::with_every_back_face;
use host_tests::frame::{CameraSpec, CullSpec, EngineSpec, ModeSpec, ProjectionSpec, RenderSpec};
use host_tests::metrics::compare;
use host_tests::pipeline::render_frame;
use host_tests::reference3d::reference_frame;
use host_tests::shapes::open_cylinder;
use host_tests::tools::orbit::Orbit;
use host_tests::tools::report::load_scene;

/// Into the mouth from above and to the side, both projections. (Views whose
/// direction makes a face edge-on to within a tenth of a degree are avoided: there
/// the snapped corners of that sliver decide, in f32 as in f64, and the two may
/// round apart.)
fn views() -> Vec<(&'static str, CameraSpec)> {
    let cam = |projection| CameraSpec {
        eye: [0.5, 4.0, 2.5],
        target: [0.0, 1.5, 0.0],
        up: [0.0, 1.0, 0.0],
        projection,
        near: 0.1,
        far: 100.0,
    };
    vec![
        (
            "perspective",
            cam(ProjectionSpec::Perspective { fov_deg: 40.0 }),
        ),
        (
            "orthographic",
            cam(ProjectionSpec::Orthographic { half_height: 1.5 }),
        ),
    ]
}

#[test]
fn open_cylinder_silhouette_is_not_hidden_by_a_face_beside_it() {
    let mut failures = Vec::new();
    for (view, cam) in views() {
        for split in [false, true] {
            // Before the fix the right silhouette was dashed from end to end: 21.9 %
            // of the line pixels misclassified (orthographic, quads) in every engine.
            let mesh = open_cylinder(48, 0.5, 3.0, split);
            let base = RenderSpec {
                width: 400,
                height: 240,
                band: 240,
                mode: ModeSpec::Dashed,
                cull: CullSpec::Off,
                ..RenderSpec::default()
            };
            let rf = reference_frame(&mesh, &cam, &base).unwrap();
            for engine in [
                EngineSpec::Fast,
                EngineSpec::CodeFill,
                EngineSpec::Scanline,
                EngineSpec::ZBuffer,
                EngineSpec::Warnock,
                EngineSpec::Raycast,
            ] {
                let spec = RenderSpec {
                    engine,
                    ..base.clone()
                };
                let frame = render_frame(&mesh, &cam, &spec).unwrap();
                let faces = if split { "triangles" } else { "quads" };
                let label = format!("cylinder {faces} {view} {}", engine.name());
                let m = compare(&label, &frame, &rf, false, true);
                println!("{m}");
                if let Err(e) = m.check() {
                    failures.push(e);
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The fast engine skips a back face whose screen box meets no hole's (the mesh
/// with its holes capped checked nowhere inside-out when baked, every fan triangle
/// turned away on screen). Drawing every back face instead, from 12 views around
/// each open mesh (suzanne with her four holes, woody, the open cylinder), at both
/// sizes, dashed: wherever a face id or a line pixel differs, the frame that drew
/// every back face is not the one that agrees with the f64 reference (measured,
/// 2026-11-26: on suzanne, 127 differing ids agree with the reference only when
/// skipped, 22 with neither, 0 only when drawn: a back face of lower index won a
/// depth tie at a silhouette). And faces are skipped: fewer drawn on suzanne.
#[test]
fn back_faces_away_from_the_holes_are_skipped_and_no_pixel_gets_worse() {
    let mut meshes: Vec<(String, host_tests::frame::MeshData)> = ["suzanne", "woody"]
        .into_iter()
        .map(|name| {
            let scene = load_scene(name).unwrap_or_else(|e| panic!("{name}: {e}"));
            (name.to_string(), scene.mesh)
        })
        .collect();
    meshes.push(("open cylinder".into(), open_cylinder(48, 0.5, 3.0, false)));
    let (mut frames, mut fewer, mut differ) = (0, 0, 0);
    let mut failures = Vec::new();
    for (name, mesh) in &meshes {
        for size in [(400, 240), (128, 64)] {
            let spec = RenderSpec {
                cull: CullSpec::Off,
                ..host_tests::tools::report::engines::spec(EngineSpec::Fast, size)
            };
            let mut orbit = Orbit::new(host_tests::fit::fit_camera(mesh, size.0, size.1), mesh);
            for view in 0..12 {
                orbit.turn(30.0);
                orbit.tilt(if view % 2 == 0 { 25.0 } else { -25.0 });
                let cam = orbit.camera();
                let skipped = render_frame(mesh, &cam, &spec).unwrap();
                let every = with_every_back_face(|| render_frame(mesh, &cam, &spec)).unwrap();
                let exact = RenderSpec {
                    engine: EngineSpec::ZBuffer,
                    ..spec.clone()
                };
                let rf = reference_frame(mesh, &cam, &exact).unwrap();
                let worse = |a: &[u32], b: &[u32], r: &[u32]| {
                    let diff = a.iter().zip(b).filter(|(a, b)| a != b).count();
                    let worse = (0..r.len())
                        .filter(|&i| a[i] != b[i] && b[i] == r[i])
                        .count();
                    (diff, worse)
                };
                let (ids, ids_worse) = worse(&skipped.ids, &every.ids, &rf.ids);
                let wide = |v: &[u8]| v.iter().map(|&p| u32::from(p)).collect::<Vec<_>>();
                let (lines, lines_worse) =
                    worse(&wide(&skipped.lines), &wide(&every.lines), &wide(&rf.lines));
                let drawn = (skipped.stat("faces_drawn"), every.stat("faces_drawn"));
                frames += 1;
                fewer += usize::from(drawn.0 < drawn.1);
                differ += ids + lines;
                let at = format!("{name} {}x{} view {view}", size.0, size.1);
                if ids_worse + lines_worse > 0 {
                    failures.push(format!(
                        "{at}: {ids_worse} ids and {lines_worse} line pixels agree with the reference only with every back face"
                    ));
                }
                if name == "suzanne" && drawn.0 >= drawn.1 {
                    failures.push(format!("{at}: no back face skipped ({} drawn)", drawn.0));
                }
            }
        }
    }
    println!("{frames} frames, {fewer} with back faces skipped, {differ} pixels differ");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
