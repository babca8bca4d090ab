//! `pick(x, y)` against the f64 reference: the visible face at every sampled pixel
//! away from edges is the reference's, and each feature edge under a pixel has as many
//! faces in front of it as the reference counts at that edge's point nearest the
//! pixel centre (counted tolerance: the library tests the snapped edge point, the
//! reference the exact one). Report: `cargo test --release -p host_tests --test frames pick::
//! -- --nocapture`.

use host_tests::fit::fit_camera;
use host_tests::frame::{CameraSpec, MeshData, ModeSpec, RenderSpec};
use host_tests::metrics::near_edge_mask;
use host_tests::obj::{load_obj, workspace_root};
use host_tests::pick::pick_pixels;
use host_tests::reference3d::{reference_frame, RefFrame};
use host_tests::shapes;

/// Reference faces in front of edge `e` at its sample nearest (x + 0.5, y + 0.5).
fn ref_in_front(rf: &RefFrame, e: usize, x: u16, y: u16) -> Option<usize> {
    let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
    let s = rf
        .samples
        .iter()
        .filter(|s| s.edge as usize == e)
        .min_by(|a, b| {
            let d = |s: &&host_tests::reference3d::LineSample| (s.x - cx).hypot(s.y - cy);
            d(a).total_cmp(&d(b))
        })?;
    let own = &rf.edges[e].faces;
    Some(
        (0..rf.faces.len())
            .filter(|&f| rf.faces[f].drawn && !own.contains(&(f as u32)))
            .filter(|&f| rf.face_covers(f, s.x, s.y))
            .filter(|&f| {
                rf.face_depth(f, s.x, s.y)
                    .is_some_and(|d| d < s.depth * (1.0 - 1e-9))
            })
            .count(),
    )
}

/// Counts for one scene: (pixels away from edges, face mismatches there, picked edges,
/// edges whose count of faces in front differs, edges whose visibility differs).
fn check(name: &str, mesh: &MeshData, cam: &CameraSpec) -> [usize; 5] {
    let spec = RenderSpec {
        width: 128,
        height: 64,
        band: 64,
        mode: ModeSpec::Dashed,
        ..RenderSpec::default()
    };
    let rf = reference_frame(mesh, cam, &spec).expect("reference");
    let near = near_edge_mask(&rf, 1.0);
    let pixels: Vec<(u16, u16)> = (0..64u16)
        .flat_map(|y| (0..128u16).map(move |x| (x, y)))
        .filter(|(x, y)| (x + 2 * y) % 3 == 0)
        .collect();
    let picked = pick_pixels(mesh, cam, &spec, &pixels).expect("pick");
    let key = |p: [f32; 3]| p.map(f32::to_bits);
    let mut counts = [0usize; 5];
    for p in &picked {
        let i = usize::from(p.y) * 128 + usize::from(p.x);
        if !near[i] {
            counts[0] += 1;
            let lib = p.pick.face.map_or(0, |f| u32::from(f) + 1);
            if lib != rf.ids[i] {
                counts[1] += 1;
            }
        }
        for (pe, ends) in &p.edges {
            counts[2] += 1;
            let ends = [key(ends[0]), key(ends[1])];
            let Some(e) = rf.edges.iter().position(|re| {
                let r = [key(re.a.map(|c| c as f32)), key(re.b.map(|c| c as f32))];
                r == ends || r == [ends[1], ends[0]]
            }) else {
                counts[3] += 1;
                counts[4] += 1;
                continue;
            };
            let Some(n) = ref_in_front(&rf, e, p.x, p.y) else {
                counts[3] += 1;
                counts[4] += 1;
                continue;
            };
            counts[3] += usize::from(n != usize::from(pe.faces_in_front));
            counts[4] += usize::from((n == 0) != (pe.faces_in_front == 0));
        }
    }
    println!(
        "{name:>10}: {} px away from edges, {} face mismatches; {} edges picked, {} depth counts differ, {} visibilities differ",
        counts[0], counts[1], counts[2], counts[3], counts[4]
    );
    counts
}

#[test]
fn picking_matches_the_reference() {
    let mut scenes: Vec<(String, MeshData, CameraSpec)> = shapes::all_scenes()
        .into_iter()
        .map(|s| {
            let cam = s.camera(128, 64, false);
            (s.name.to_string(), s.mesh, cam)
        })
        .collect();
    let path = workspace_root().join("../shared/models/suzanne.obj");
    let m = load_obj(&path)
        .unwrap_or_else(|e| panic!("{e}: the shared models are part of the test set"));
    let cam = fit_camera(&m, 128, 64);
    scenes.push(("suzanne".into(), m, cam));
    let mut total = [0usize; 5];
    for (name, mesh, cam) in &scenes {
        let c = check(name, mesh, cam);
        for (t, v) in total.iter_mut().zip(c) {
            *t += v;
        }
        // Away from edges the visible face is exact, as for the Z-buffer engine.
        assert_eq!(c[1], 0, "{name}: picked faces differ from the reference");
    }
    // Measured: 0.59 % and 1.71 % (1,699 edges). Hidden lines under other parts exist
    // in these scenes: the test is not empty.
    assert!(total[2] > 500, "too few edges picked: {}", total[2]);
    let depth_pct = 100.0 * total[3] as f64 / total[2] as f64;
    let vis_pct = 100.0 * total[4] as f64 / total[2] as f64;
    println!(
        "all: depth counts differ on {depth_pct:.2}% of picked edges, visibility on {vis_pct:.2}%"
    );
    assert!(
        vis_pct <= 1.0,
        "visibility differs on {vis_pct:.2}% of picked edges"
    );
    assert!(
        depth_pct <= 2.5,
        "depth counts differ on {depth_pct:.2}% of picked edges"
    );
}
