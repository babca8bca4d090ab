//! `Camera::fit` framed one mesh; a scene of several posed parts had no fitted
//! camera: `SceneDrawing::fit_camera` frames every instance at its
//! pose, each posed vertex within `FIT_FILL` of the half-width and half-height,
//! as an `f64` projection of the `f64`-posed vertices checks here.

use host_tests::fit::{cross, dot, normalize};
use pbuffer::prelude::*;
use pbuffer::{FIT_FILL, FIT_FOV_DEG, FIT_VIEW_DIRECTION};

const P: [[f32; 3]; 8] = [
    [0., 0., 0.],
    [1., 0., 0.],
    [1., 1., 0.],
    [0., 1., 0.],
    [0., 0., 1.],
    [1., 0., 1.],
    [1., 1., 1.],
    [0., 1., 1.],
];
const I: [u32; 24] = [
    0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 2, 3, 7, 6, 1, 2, 6, 5, 0, 4, 7, 3,
];

/// `pose` applied to `p` in `f64`.
fn posed(pose: &Pose, p: [f32; 3]) -> [f64; 3] {
    let (r, t) = (pose.rotation(), pose.offset());
    core::array::from_fn(|i| {
        (0..3)
            .map(|j| f64::from(r[i][j]) * f64::from(p[j]))
            .sum::<f64>()
            + f64::from(t[i])
    })
}

#[test]
fn a_fitted_scene_camera_keeps_every_posed_vertex_inside_the_frame_margin() {
    let mut cube = Drawing::<8, 6, 12>::new();
    cube.bake(Mesh::new(&P, &I, &[0, 4, 8, 12, 16, 20, 24]).unwrap())
        .unwrap();
    let poses = [
        Pose::translation([-4.0, 0.0, 1.0]),
        Pose::from_degrees([0.0, 30.0, 10.0], [3.0, 2.0, -2.0]),
        Pose::from_degrees([45.0, 0.0, 0.0], [0.5, -3.0, 0.0]),
    ];
    let mut scene = SceneDrawing::<3, 24, 18, 36, 91>::new();
    for pose in poses {
        scene.add(cube.baked().unwrap(), pose).unwrap();
    }
    for (w, h) in [(400u32, 240u32), (128, 64), (64, 128)] {
        let camera = scene.fit_camera(w, h).unwrap();
        let eye = camera.eye().map(f64::from);
        let f = normalize(FIT_VIEW_DIRECTION.map(|c| -f64::from(c)));
        let s = normalize(cross(f, [0.0, 1.0, 0.0]));
        let u = cross(s, f);
        let tan = (f64::from(FIT_FOV_DEG) / 2.0).to_radians().tan();
        let aspect = f64::from(w) / f64::from(h);
        let (near, far) = camera.near_far();
        let mut extent = 0.0f64;
        for pose in &poses {
            for p in P {
                let d = posed(pose, p);
                let d = [d[0] - eye[0], d[1] - eye[1], d[2] - eye[2]];
                let depth = dot(f, d);
                assert!(depth > f64::from(near) && depth < f64::from(far));
                let x = dot(s, d) / (depth * tan * aspect);
                let y = dot(u, d) / (depth * tan);
                extent = extent.max(x.abs()).max(y.abs());
            }
        }
        // Inside the margin, and the fit reaches it (the nearest such distance).
        let fill = f64::from(FIT_FILL);
        assert!(extent <= fill + 1e-4, "{w}x{h}: extent {extent}");
        assert!(extent >= fill - 1e-3, "{w}x{h}: extent {extent}");
    }
    // No instance: nothing to frame.
    let empty = SceneDrawing::<1, 8, 6, 12, 31>::new();
    assert_eq!(empty.fit_camera(64, 64), Err(Error::EmptyMesh));
}
