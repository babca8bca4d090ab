//! The engines against each other on random scenes.
//!
//! - `scanline` (the code-fill engine comparing planes where faces overlap) against
//!   the Z-buffer: the same frame, pixel for pixel (face ids, line masks and the
//!   packed picture). It resolves overlapping faces from their planes exactly as the
//!   Z-buffer receives them (face order, ties to the lower index), so no tolerance
//!   is owed.
//! - `warnock` (area subdivision) against the Z-buffer: the same frame, pixel for
//!   pixel. Areas are filled only where one face provably wins at every centre by
//!   the Z-buffer's own rule, and single pixels are decided by that rule, so no
//!   tolerance is owed either.
//! - `codefill` (a BSP tree's depth order, weight-1 codes) with both row
//!   representations: the same frame as each other, pixel for pixel. Against the
//!   Z-buffer its face ids differ where two faces are within a tie of each other
//!   (intersection lines, which the BSP cuts in f64 where the Z-buffer compares
//!   snapped planes) and along edges: counted, at most 0.6 % of the covered pixels
//!   over the run (0.42 % measured). Both are compared with the f64 reference on
//!   every scene, and over the run code fill may not have more holes, wrong faces,
//!   depth-order errors or far id differences than the Z-buffer (+2).
//! - `raycast` (one ray per pixel centre through a per-frame bounding-volume
//!   hierarchy) against the Z-buffer (32-bit depth): the same frame, pixel for pixel.
//!   A ray meets a face where `covers_centre` (the scan converter's decision) says so,
//!   at the plane nearness the Z-buffer stores, and decides among the tie-closed
//!   nearest hits by the Z-buffer's rule in index order, so no tolerance is owed.
//!
//! Scenes: random boxes (many interpenetrating), random triangle soups (open,
//! crossing, coplanar pairs), random cameras from every side, perspective and
//! orthographic, random sizes, sub-pixel bits, band heights and culling.

use host_tests::frame::{
    CameraSpec, CullSpec, EngineSpec, Frame, MeshData, ModeSpec, ProjectionSpec, RenderSpec,
};
use host_tests::metrics::compare_surfaces;
use host_tests::pipeline::render_frame;
use host_tests::random::Rng;
use host_tests::reference3d::reference_frame;
use host_tests::shapes::{add_box, all_vertex_bounds};

/// Random boxes, some inside others.
fn boxes(rng: &mut Rng) -> MeshData {
    let mut m = MeshData::default();
    for _ in 0..1 + rng.below(6) {
        let c = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let h = [
            rng.range(0.1, 0.8),
            rng.range(0.1, 0.8),
            rng.range(0.1, 0.8),
        ];
        add_box(&mut m, c, h, rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
    }
    m
}

/// A soup of random triangles and quads; some share a plane with the one before.
fn soup(rng: &mut Rng) -> MeshData {
    let mut m = MeshData::default();
    let point = |rng: &mut Rng| {
        [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ]
    };
    for _ in 0..2 + rng.below(25) {
        let base = m.vertices.len() as u32;
        let n = if rng.chance(0.3) { 4 } else { 3 };
        if n == 4 || m.vertices.len() < 3 || !rng.chance(0.2) {
            let (a, b, c) = (point(rng), point(rng), point(rng));
            m.vertices.extend([a, b, c]);
            if n == 4 {
                // Planar: the fourth vertex is a + c - b.
                m.vertices
                    .push([a[0] + c[0] - b[0], a[1] + c[1] - b[1], a[2] + c[2] - b[2]]);
            }
        } else {
            // Coplanar with the previous triangle: affine combinations of its vertices.
            let k = m.vertices.len();
            let (a, b, c) = (m.vertices[k - 3], m.vertices[k - 2], m.vertices[k - 1]);
            for _ in 0..3 {
                let (u, v) = (rng.range(-0.5, 1.0), rng.range(-0.5, 1.0));
                m.vertices
                    .push([0, 1, 2].map(|i| a[i] + u * (b[i] - a[i]) + v * (c[i] - a[i])));
            }
        }
        m.faces.push((base..base + n).collect());
    }
    m
}

fn camera(rng: &mut Rng, mesh: &MeshData, w: usize, h: usize) -> CameraSpec {
    let (c, r) = all_vertex_bounds(mesh);
    let dir = loop {
        let d = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        // Not along the up vector (a degenerate look-at).
        if len > 0.2 && (d[1] / len).abs() < 0.95 {
            break d.map(|x| x / len);
        }
    };
    let dist = r * rng.range(1.2, 4.0);
    let projection = if rng.chance(0.3) {
        ProjectionSpec::Orthographic {
            half_height: r * rng.range(0.5, 1.5) * (h as f64 / w as f64).max(1.0),
        }
    } else {
        ProjectionSpec::Perspective {
            fov_deg: rng.range(20.0, 90.0),
        }
    };
    CameraSpec {
        eye: [0, 1, 2].map(|i| c[i] + dir[i] * dist),
        target: [0, 1, 2].map(|i| c[i] + rng.range(-0.3, 0.3) * r),
        up: [0.0, 1.0, 0.0],
        projection,
        // Sometimes the near plane cuts the scene.
        near: if rng.chance(0.3) { dist * 0.8 } else { 0.05 },
        far: dist + 3.0 * r,
    }
}

fn differing(a: &Frame, b: &Frame) -> (usize, usize, usize) {
    let ids = a.ids.iter().zip(&b.ids).filter(|(x, y)| x != y).count();
    let lines = a.lines.iter().zip(&b.lines).filter(|(x, y)| x != y).count();
    let bytes = a
        .packed
        .iter()
        .zip(&b.packed)
        .filter(|(x, y)| x != y)
        .count();
    (ids, lines, bytes)
}

/// A random scene and its render settings (the same draws for every engine).
struct Case {
    mesh: MeshData,
    cam: CameraSpec,
    spec: RenderSpec,
}

fn scenes() -> Vec<Case> {
    let mut rng = Rng::new(0x5eed_c0de);
    (0..300)
        .map(|k| {
            let mesh = if k % 2 == 0 {
                boxes(&mut rng)
            } else {
                soup(&mut rng)
            };
            let (w, h) = (8 + rng.below(300) as usize, 8 + rng.below(200) as usize);
            let cam = camera(&mut rng, &mesh, w, h);
            let spec = RenderSpec {
                width: w,
                height: h,
                subpixel: rng.below(9) as u32,
                band: if rng.chance(0.5) {
                    h
                } else {
                    1 + rng.below(h as u64) as usize
                },
                cull: *[CullSpec::On, CullSpec::Off, CullSpec::Auto]
                    .get(rng.below(3) as usize)
                    .unwrap(),
                mode: if rng.chance(0.5) {
                    ModeSpec::Dashed
                } else {
                    ModeSpec::SurfacesDashed
                },
                depth_bits: 32,
                ..RenderSpec::default()
            };
            Case { mesh, cam, spec }
        })
        .collect()
}

fn with_engine(spec: &RenderSpec, engine: EngineSpec) -> RenderSpec {
    RenderSpec {
        engine,
        ..spec.clone()
    }
}

fn stat(f: &Frame, name: &str) -> u64 {
    f.stats.iter().find(|s| s.0 == name).map_or(0, |s| s.1)
}

/// Renders every random scene with `engine` and with `base`; the frames must be the
/// same pixel for pixel (face ids, line masks and the packed picture), or both
/// engines must fail alike. `seen` sees each frame of `engine`. At least 290 scenes
/// render and they cover more than 500,000 face pixels.
fn assert_same_frames(base: EngineSpec, engine: EngineSpec, mut seen: impl FnMut(&Frame)) {
    let mut failures = Vec::new();
    let (mut rendered, mut covered) = (0, 0usize);
    for (k, sc) in scenes().iter().enumerate() {
        let b = render_frame(&sc.mesh, &sc.cam, &with_engine(&sc.spec, base));
        let e = render_frame(&sc.mesh, &sc.cam, &with_engine(&sc.spec, engine));
        match (b, e) {
            (Ok(b), Ok(e)) => {
                rendered += 1;
                covered += b.ids.iter().filter(|&&id| id != 0).count();
                seen(&e);
                let d = differing(&b, &e);
                if d != (0, 0, 0) {
                    let spec = &sc.spec;
                    failures.push(format!(
                        "scene {k} ({}x{}, S {}, band {}, {:?}): {} ids, {} line pixels, {} bytes differ",
                        spec.width, spec.height, spec.subpixel, spec.band, spec.cull, d.0, d.1, d.2
                    ));
                }
            }
            (Err(a), Err(b)) if a == b => {}
            (b, e) => failures.push(format!(
                "scene {k}: the engines disagree on failing: {:?} / {:?}",
                b.err(),
                e.err()
            )),
        }
    }
    println!(
        "{} against {}: {rendered} scenes, {covered} face pixels",
        engine.name(),
        base.name()
    );
    assert!(rendered >= 290, "only {rendered} scenes rendered");
    assert!(
        covered > 500_000,
        "the scenes cover too little: {covered} pixels"
    );
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn scanline_draws_the_z_buffer_frame_on_random_scenes() {
    let mut widest = 0u64;
    assert_same_frames(EngineSpec::ZBuffer, EngineSpec::Scanline, |f| {
        widest = widest.max(stat(f, "code_bits"));
    });
    println!("widest code {widest} bits");
}

#[test]
fn warnock_draws_the_z_buffer_frame_on_random_scenes() {
    assert_same_frames(EngineSpec::ZBuffer, EngineSpec::Warnock, |_| {});
}

/// The Z-buffer's holes, wrong faces, depth-order errors and far id differences
/// against the f64 reference over the 300 seeded scenes, as measured (2026-11-26):
/// pixels at intersections and slivers the 32-bit plane compare decides otherwise.
const Z_BUFFER_AGAINST_REFERENCE: [usize; 4] = [7, 0, 1, 178];

#[test]
fn code_fill_in_depth_order_is_as_faithful_as_the_z_buffer_on_random_scenes() {
    let mut failures = Vec::new();
    let (mut rendered, mut covered, mut differ, mut widest) = (0, 0usize, 0usize, 0u64);
    // Holes, wrong faces, depth-order errors, far id differences against the f64
    // reference: Z-buffer, code fill.
    let (mut zc, mut cc) = ([0usize; 4], [0usize; 4]);
    for (k, sc) in scenes().iter().enumerate() {
        let z = render_frame(
            &sc.mesh,
            &sc.cam,
            &with_engine(&sc.spec, EngineSpec::ZBuffer),
        );
        let c = render_frame(
            &sc.mesh,
            &sc.cam,
            &with_engine(&sc.spec, EngineSpec::CodeFill),
        );
        let s = render_frame(
            &sc.mesh,
            &sc.cam,
            &with_engine(&sc.spec, EngineSpec::CodeFillCrossings),
        );
        match (z, c, s) {
            (Ok(z), Ok(c), Ok(s)) => {
                rendered += 1;
                covered += z.ids.iter().filter(|&&id| id != 0).count();
                widest = widest.max(stat(&c, "code_bits"));
                let same = differing(&c, &s);
                if same != (0, 0, 0) {
                    failures.push(format!(
                        "scene {k}: crossings and bit-sliced rows differ: {same:?}"
                    ));
                }
                differ += differing(&z, &c).0;
                let surfaces = RenderSpec {
                    mode: ModeSpec::Surfaces,
                    ..sc.spec.clone()
                };
                let rf = reference_frame(&sc.mesh, &sc.cam, &surfaces).expect("reference");
                for (frame, counts) in [(&z, &mut zc), (&c, &mut cc)] {
                    let m = compare_surfaces(frame, &rf);
                    let got = [m.holes, m.wrong_faces, m.depth_order, m.far_diffs];
                    for (t, g) in counts.iter_mut().zip(got) {
                        *t += g;
                    }
                }
            }
            (Err(a), Err(b), Err(_)) if a == b => {}
            (z, c, s) => failures.push(format!(
                "scene {k}: the engines disagree on failing: {:?} / {:?} / {:?}",
                z.err(),
                c.err(),
                s.err()
            )),
        }
    }
    let fraction = differ as f64 / covered.max(1) as f64;
    println!(
        "{rendered} scenes, {covered} face pixels, {differ} ids differ from the Z-buffer ({:.3} %), widest code {widest} bits",
        100.0 * fraction
    );
    println!("against the reference (holes, wrong faces, depth order, far diffs): Z-buffer {zc:?}, code fill {cc:?}");
    assert!(rendered >= 290, "only {rendered} scenes rendered");
    for (k, name) in ["holes", "wrong faces", "depth-order errors", "far id diffs"]
        .iter()
        .enumerate()
    {
        // The Z-buffer is the engine the others must equal: its own errors are
        // bounded by what it makes today (seeded scenes), so a regression in it
        // cannot pass through every engine that copies it.
        if zc[k] > Z_BUFFER_AGAINST_REFERENCE[k] {
            failures.push(format!(
                "{name}: Z-buffer {} against the reference, over its bound {}",
                zc[k], Z_BUFFER_AGAINST_REFERENCE[k]
            ));
        }
        if cc[k] > zc[k] + 2 {
            failures.push(format!(
                "{name}: code fill {} against Z-buffer {}",
                cc[k], zc[k]
            ));
        }
    }
    assert!(fraction <= 0.006, "{differ} of {covered} ids differ");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The BSP order painted far to near (`bsp`) and the same order as weight-1 codes
/// (`codefill`): the nearest fragment at a pixel is the last painted and the lowest
/// set code bit alike, so the frames are identical.
#[test]
fn painting_a_bsp_order_draws_the_code_fill_frame_on_random_scenes() {
    assert_same_frames(EngineSpec::CodeFill, EngineSpec::Bsp, |_| {});
}

#[test]
fn raycast_draws_the_z_buffer_frame_on_random_scenes() {
    let (mut fallbacks, mut tests) = (0u64, 0u64);
    assert_same_frames(EngineSpec::ZBuffer, EngineSpec::Raycast, |f| {
        fallbacks += stat(f, "ray_fallbacks");
        tests += stat(f, "ray_face_tests");
    });
    println!("{tests} ray-face tests, {fallbacks} pixels decided exhaustively");
}
