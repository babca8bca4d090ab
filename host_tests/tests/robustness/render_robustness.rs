//! The 3-D pipeline on hostile input: random meshes (degenerate faces, coincident and
//! far-flung vertices, concave and non-planar polygons), cameras inside the mesh, near
//! planes through it, grazing and tiny views, every mode, band and precision. Each
//! frame must come back `Ok` or as a precise `Err`, never panic, and never write a
//! span outside the frame or the same pixel twice.

use std::collections::HashSet;
use std::convert::Infallible;

use embedded_graphics::pixelcolor::BinaryColor;
use fixed::types::extra::U4;
use host_tests::frame::MeshData;
use host_tests::random::Rng;
use host_tests::setup::MeshArrays;
use pbuffer::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use pbuffer::render::{storage_rows, ProjectedVertex};
use pbuffer::{
    Camera, Cull, Dashes, DrawMode, MonoPalette, Pattern, Projection, Settings, Span, SpanSink,
    Viewport, Workspace, ZBufferRenderer,
};

/// Checks every span: inside the viewport, no pixel twice in one frame.
struct Strict {
    viewport: Viewport,
    seen: HashSet<(u16, u16)>,
}

impl SpanSink for Strict {
    type Color = BinaryColor;
    type Error = Infallible;
    fn viewport(&self) -> Viewport {
        self.viewport
    }
    fn fill_span(&mut self, span: Span, _: BinaryColor) -> Result<(), Infallible> {
        assert!(span.x0() < span.x1() && span.x1() <= self.viewport.width);
        assert!(span.y() < self.viewport.height);
        for x in span.x0()..span.x1() {
            assert!(
                self.seen.insert((x, span.y())),
                "pixel {x},{} written twice",
                span.y()
            );
        }
        Ok(())
    }
}

fn coordinate(rng: &mut Rng) -> f64 {
    match rng.below(40) {
        0..=3 => rng.range(-1e5, 1e5),
        4..=7 => rng.range(-1e-3, 1e-3),
        8 => 0.0,
        _ => rng.range(-2.0, 2.0),
    }
}

fn random_mesh(rng: &mut Rng) -> MeshData {
    let n = 3 + rng.below(40) as usize;
    let mut m = MeshData::default();
    for _ in 0..n {
        let v = [coordinate(rng), coordinate(rng), coordinate(rng)];
        // Some exact duplicates, for welding and degenerate faces.
        if rng.chance(0.005) && !m.vertices.is_empty() {
            let k = rng.below(m.vertices.len() as u64) as usize;
            m.vertices.push(m.vertices[k]);
        } else {
            m.vertices.push(v);
        }
    }
    for _ in 0..1 + rng.below(60) {
        let k = 3 + rng.below(5.min(n as u64 - 2)) as usize;
        let mut face: Vec<u32> = Vec::new();
        while face.len() < k {
            // Distinct indices (repeats are `Mesh::new`'s own tests' business).
            let v = rng.below(n as u64) as u32;
            if !face.contains(&v) {
                face.push(v);
            }
        }
        m.faces.push(face);
    }
    m
}

#[test]
fn hostile_meshes_and_cameras_never_panic_or_overdraw() {
    let mut rng = Rng::new(0x0005_EED0_FBAD);
    let (mut rendered, mut rejected) = (0usize, 0usize);
    let mut why = std::collections::BTreeMap::<String, usize>::new();
    for case in 0..4000 {
        let data = random_mesh(&mut rng);
        let arrays = MeshArrays::new(&data);
        let mesh = match Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets) {
            Ok(mesh) => mesh,
            Err(e) => {
                *why.entry(
                    format!("mesh {e:?}")
                        .split_whitespace()
                        .take(2)
                        .collect::<String>(),
                )
                .or_insert(0) += 1;
                rejected += 1;
                continue;
            }
        };
        let mut weld = vec![0u32; arrays.vertices.len()];
        let mut scratch = vec![HalfEdgeRecord::default(); arrays.indices.len()];
        let mut store = vec![MeshEdge::default(); arrays.indices.len()];
        let crease = rng.range(0.0, 180.0) as f32;
        let edges = EdgeAdjacency::build(&mesh, crease, &mut weld, &mut scratch, &mut store)
            .expect("buffers are large enough");
        let p = |rng: &mut Rng| {
            [
                coordinate(rng) as f32,
                coordinate(rng) as f32,
                coordinate(rng) as f32,
            ]
        };
        let projection = if rng.chance(0.3) {
            Projection::Orthographic {
                half_height: rng.log_uniform(1e-3, 1e3) as f32,
            }
        } else {
            Projection::Perspective {
                fov_y_deg: rng.range(1.0, 179.0) as f32,
            }
        };
        let near = rng.log_uniform(1e-4, 10.0) as f32;
        let far = near * rng.log_uniform(1.001, 1e6) as f32;
        let Ok(camera) = Camera::new(p(&mut rng), p(&mut rng), p(&mut rng), projection, near, far)
        else {
            rejected += 1;
            continue;
        };
        let (w, h) = [(1, 1), (3, 97), (64, 40), (128, 64), (400, 240)][rng.below(5) as usize];
        let band = 1 + rng.below(h as u64) as u16;
        let stored = usize::from(storage_rows(band, h));
        let mode = [
            DrawMode::Wireframe,
            DrawMode::HiddenRemoved,
            DrawMode::Dashed,
            DrawMode::Surfaces,
            DrawMode::SurfacesDashed,
        ][rng.below(5) as usize];
        let cull = [Cull::On, Cull::Off, Cull::Auto][rng.below(3) as usize];
        let settings = Settings {
            mode,
            cull,
            pattern: Pattern::PAPER,
            dashes: Dashes::Screen,
            lines: pbuffer::render::LineVisibility::ByPixel,
        };
        let (wu, bu) = (usize::from(w), usize::from(band));
        let mut vertices = vec![ProjectedVertex::default(); arrays.vertices.len()];
        let mut drawn = vec![0u32; mesh.face_count().div_ceil(32)];
        let mut features = vec![0u32; edges.edges().len().div_ceil(32)];
        let mut depth = vec![0u16; wu * stored];
        let mut ids = vec![0u16; wu * stored];
        let mut lines = vec![0u32; 2 * wu.div_ceil(32) * bu];
        let mut ws = Workspace {
            vertices: &mut vertices,
            drawn: &mut drawn,
            features: &mut features,
            depth: &mut depth,
            ids: &mut ids,
            lines: &mut lines,
        };
        let mut sink = Strict {
            viewport: Viewport {
                width: w,
                height: h,
            },
            seen: HashSet::new(),
        };
        let mut renderer = Box::new(ZBufferRenderer::<U4, 64, 64>::new());
        match renderer.render(
            &mesh,
            &edges,
            &camera,
            &settings,
            &mut ws,
            &MonoPalette::default(),
            &mut sink,
            &mut (),
        ) {
            Ok(stats) => {
                rendered += 1;
                assert_eq!(stats.faces as usize, mesh.face_count(), "case {case}");
            }
            Err(e) => {
                // Only precise, expected errors: a face clipped beyond the polygon
                // capacity, or a scene scale fixed point cannot hold.
                let ok = matches!(
                    e,
                    pbuffer::Error::CapacityExceeded { .. } | pbuffer::Error::OutOfRange
                );
                assert!(ok, "case {case}: unexpected error {e:?}");
                *why.entry(
                    format!("render {e:?}")
                        .split_whitespace()
                        .take(2)
                        .collect::<String>(),
                )
                .or_insert(0) += 1;
                rejected += 1;
            }
        }
    }
    println!("{rendered} frames rendered, {rejected} inputs rejected with an error: {why:?}");
    assert!(
        rendered > 2000,
        "the generator must mostly make renderable scenes"
    );
}
