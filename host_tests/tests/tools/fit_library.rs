//! `pbuffer::Camera::fit` is the `render` command's `--fit` rule (`host_tests::fit`,
//! in f64) in f32: the same constants, and cameras equal within f32 rounding.

use host_tests::fit::{fit_camera, used_vertex_bounds, FILL, FIT_FOV_DEG, VIEW_DIRECTION};
use host_tests::frame::MeshData;

/// Two faces of a cube of side `s` at `o`.
fn cube(s: f64, o: [f64; 3]) -> MeshData {
    let vertices = (0..8)
        .map(|i| {
            [
                o[0] + s * f64::from(i & 1),
                o[1] + s * f64::from((i >> 1) & 1),
                o[2] + s * f64::from((i >> 2) & 1),
            ]
        })
        .collect();
    let faces = vec![vec![0, 2, 3, 1], vec![4, 5, 7, 6]];
    MeshData { vertices, faces }
}

#[test]
fn the_library_fit_is_this_rule_in_f32() {
    assert_eq!(
        VIEW_DIRECTION.map(|c| c as f32),
        pbuffer::FIT_VIEW_DIRECTION
    );
    assert_eq!(FIT_FOV_DEG as f32, pbuffer::FIT_FOV_DEG);
    assert_eq!(FILL as f32, pbuffer::FIT_FILL);
    let root = host_tests::obj::workspace_root().join("../shared/models");
    let mut models = vec![cube(2.0, [10.0, -3.0, 5.0]), cube(0.001, [0.0; 3])];
    for name in ["suzanne.obj", "teapot.obj", "fandisk.obj"] {
        if let Ok(m) = host_tests::obj::load_obj(&root.join(name)) {
            models.push(m);
        }
    }
    for m in &models {
        let arrays = host_tests::setup::MeshArrays::new(m);
        let mesh =
            pbuffer::Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets).expect("mesh");
        for (w, h) in [(400u32, 240u32), (128, 128), (100, 300)] {
            let host = fit_camera(m, w as usize, h as usize);
            let lib = pbuffer::Camera::fit(&mesh, w, h).expect("fits");
            let (_, r) = used_vertex_bounds(m);
            let close = |a: f32, b: f64, what: &str| {
                assert!(
                    (f64::from(a) - b).abs() <= 1e-5 * (r + b.abs()),
                    "{what}: {a} vs {b}"
                );
            };
            for k in 0..3 {
                close(lib.eye()[k], host.eye[k], "eye");
            }
            let (near, far) = lib.near_far();
            close(near, host.near, "near");
            close(far, host.far, "far");
        }
    }
}
