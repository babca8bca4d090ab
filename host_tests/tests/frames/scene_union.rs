//! A scene's frame is the frame of its union mesh (`pbuffer::scene`): several
//! parts at random poses drawn by the library's `SceneDrawing` give, bit for bit,
//! the face ids and line pixels of the same posed geometry baked as one mesh,
//! in every mode, with the fast engine and with the exact Z-buffer.
//! `cargo test --release -p host_tests --test frames scene_union::`.

use host_tests::frame::{CameraSpec, EngineSpec, MeshData, ModeSpec, ProjectionSpec, RenderSpec};
use host_tests::pipeline::render_frame;
use host_tests::posed::{render_scene, union, Part};
use host_tests::random::Rng;
use host_tests::shapes::{boxes, cube, gear, icosphere, torus};
use pbuffer::Pose;

/// The test meshes, each in its own space around its origin.
fn meshes() -> Vec<(&'static str, MeshData)> {
    vec![
        ("cube", cube()),
        ("icosphere", icosphere(1)),
        ("torus", torus(12, 8, 0.6, 0.2)),
        ("gear", gear(8, 0.4, 0.55, 0.2)),
        ("boxes", boxes()),
    ]
}

/// Two to four parts at random poses within a box of side 3 around the origin.
fn random_parts(
    rng: &mut Rng,
    meshes: &[(&'static str, MeshData)],
) -> (Vec<Part>, Vec<&'static str>) {
    let n = 2 + rng.below(3) as usize;
    let (mut parts, mut names) = (Vec::new(), Vec::new());
    for _ in 0..n {
        let (name, mesh) = &meshes[rng.below(meshes.len() as u64) as usize];
        let angle = |rng: &mut Rng| rng.range(-180.0, 180.0) as f32;
        let place = |rng: &mut Rng| rng.range(-1.5, 1.5) as f32;
        let degrees = [angle(rng), angle(rng), angle(rng)];
        let t = [place(rng), place(rng), place(rng)];
        parts.push(Part {
            mesh: mesh.clone(),
            pose: Pose::from_degrees(degrees, t),
        });
        names.push(*name);
    }
    (parts, names)
}

fn camera(rng: &mut Rng, ortho: bool) -> CameraSpec {
    let eye = [
        rng.range(-7.0, 7.0),
        rng.range(1.0, 6.0),
        rng.range(5.0, 8.0),
    ];
    CameraSpec {
        eye,
        target: [0.0, 0.0, 0.0],
        up: [0.0, 1.0, 0.0],
        projection: if ortho {
            ProjectionSpec::Orthographic { half_height: 3.0 }
        } else {
            ProjectionSpec::Perspective { fov_deg: 50.0 }
        },
        near: 0.1,
        far: 100.0,
    }
}

#[test]
fn scene_through_poses_equals_the_union_baked_as_one_mesh() {
    let meshes = meshes();
    let modes = [
        ModeSpec::Dashed,
        ModeSpec::Hidden,
        ModeSpec::Wireframe,
        ModeSpec::SurfacesDashed,
    ];
    let mut compared = 0;
    for seed in 0..24u64 {
        let mut rng = Rng::new(0x5CE4E + seed);
        let (parts, names) = random_parts(&mut rng, &meshes);
        let cam = camera(&mut rng, seed % 3 == 2);
        let posed = union(&parts);
        for engine in [EngineSpec::Fast, EngineSpec::ZBuffer] {
            let mode = modes[seed as usize % modes.len()];
            let spec = RenderSpec {
                engine,
                width: 160,
                height: 120,
                band: 120,
                mode,
                ..RenderSpec::default()
            };
            let scene = render_scene(&parts, &cam, &spec).unwrap();
            let one = render_frame(&posed, &cam, &spec).unwrap();
            let what = format!("seed {seed} {names:?} {engine:?} {mode:?}");
            assert!(scene.lines.iter().any(|&l| l != 0), "{what}: nothing drawn");
            assert_eq!(scene.ids, one.ids, "{what}: face ids");
            assert_eq!(scene.lines, one.lines, "{what}: line pixels");
            assert_eq!(scene.packed, one.packed, "{what}: picture");
            compared += 1;
        }
    }
    assert_eq!(compared, 48);
}

/// The number `name` in a frame's figures.
fn figure(frame: &host_tests::frame::Frame, name: &str) -> u64 {
    let found = frame.stats.iter().find(|(n, _)| n == name);
    found
        .map(|(_, v)| *v)
        .unwrap_or_else(|| panic!("no figure {name}"))
}

/// Two cubes that touch face to face, their corners there equal bit for bit: as one
/// mesh those corners weld and the four edges of the touching square are one edge
/// each; as a scene every engine keeps each cube's edges, as the library does (the
/// exact engines through the union, its edges made part by part).
#[test]
fn touching_parts_keep_their_own_edges_in_every_engine() {
    let parts = vec![
        Part {
            mesh: cube(),
            pose: Pose::IDENTITY,
        },
        Part {
            mesh: cube(),
            pose: Pose::translation([2.0, 0.0, 0.0]),
        },
    ];
    let cam = CameraSpec {
        eye: [4.0, 3.0, 7.0],
        target: [1.0, 0.0, 0.0],
        up: [0.0, 1.0, 0.0],
        projection: ProjectionSpec::Perspective { fov_deg: 50.0 },
        near: 0.1,
        far: 100.0,
    };
    let posed = union(&parts);
    let mut counts = Vec::new();
    for engine in [EngineSpec::Fast, EngineSpec::ZBuffer, EngineSpec::Scanline] {
        let spec = RenderSpec {
            engine,
            width: 160,
            height: 120,
            band: 120,
            ..RenderSpec::default()
        };
        let scene = figure(&render_scene(&parts, &cam, &spec).unwrap(), "feature_edges");
        let one = figure(&render_frame(&posed, &cam, &spec).unwrap(), "feature_edges");
        // 12 edges a cube; welded, the touching square's 4 edges are 4, not 8.
        assert_eq!(
            (scene, one),
            (24, 20),
            "{engine:?}: scene, union as one mesh"
        );
        counts.push(scene);
    }
    assert_eq!(counts, [24, 24, 24]);
}
