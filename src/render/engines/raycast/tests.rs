//! The ray-casting engine on small scenes: pictures, ties, capacity, and the
//! Z-buffer's frame on a scene deep enough for a many-level hierarchy.

extern crate std;
use std::string::String;
use std::vec;
use std::vec::Vec;

use fixed::types::extra::U4;

use super::trace::{fold, Candidates, Hit};
use super::*;
use crate::mesh::{HalfEdgeRecord, MeshEdge};
use crate::render::{Cull, DrawMode, MonoPalette, Workspace, ZBufferRenderer};
use crate::Capacity;
use crate::{Dashes, Pattern, Projection, Span, Viewport};
use embedded_graphics_core::pixelcolor::BinaryColor;

/// A target of any size that keeps nothing (the probe sees the ids).
struct Blank(Viewport);

impl SpanSink for Blank {
    type Color = BinaryColor;
    type Error = core::convert::Infallible;
    fn viewport(&self) -> Viewport {
        self.0
    }
    fn fill_span(&mut self, _: Span, _: BinaryColor) -> Result<(), Self::Error> {
        Ok(())
    }
}

const W: usize = 16;
const H: usize = 8;

/// Every row's face ids.
struct Ids {
    width: usize,
    ids: Vec<u16>,
}

impl FrameProbe for Ids {
    fn row(&mut self, y: u16, ids: &[u16], _: &[u32], _: &[u32]) {
        let at = usize::from(y) * self.width;
        self.ids[at..at + self.width].copy_from_slice(&ids[..self.width]);
    }
}

/// A mesh of quads and triangles given as vertex lists.
struct Scene {
    v: Vec<[f32; 3]>,
    idx: Vec<u32>,
    off: Vec<u32>,
}

impl Scene {
    fn new(faces: &[&[[f32; 3]]]) -> Self {
        let (mut v, mut idx, mut off) = (Vec::new(), Vec::new(), vec![0]);
        for f in faces {
            for p in *f {
                idx.push(v.len() as u32);
                v.push(*p);
            }
            off.push(idx.len() as u32);
        }
        Self { v, idx, off }
    }
}

/// Looking down -z from z = 5, orthographic: x in [-2, 2] spans the 16 columns,
/// y in [-1, 1] the 8 rows (one pixel is 0.25 world units).
fn camera() -> Camera {
    let projection = Projection::Orthographic { half_height: 1.0 };
    Camera::new(
        [0.0, 0.0, 5.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        projection,
        0.5,
        20.0,
    )
    .unwrap()
}

fn square(x0: f32, y0: f32, x1: f32, y1: f32, z: impl Fn(f32, f32) -> f32) -> Vec<[f32; 3]> {
    [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
        .iter()
        .map(|&[x, y]| [x, y, z(x, y)])
        .collect()
}

enum Engine {
    Raycast,
    ZBuffer,
}

/// A frame `w` x `h` pixels, drawn in bands of `band` rows.
#[derive(Clone, Copy)]
struct Frame {
    w: usize,
    h: usize,
    band: usize,
}

/// Renders `scene` (culling off, surfaces) at `w` x `h` in bands of `band` rows;
/// returns every pixel's id and the engine's figures.
fn render(
    scene: &Scene,
    camera: &Camera,
    w: usize,
    h: usize,
    band: usize,
    engine: Engine,
) -> Result<(Vec<u16>, RaycastFigures), Error> {
    let mesh = Mesh::new(&scene.v, &scene.idx, &scene.off)?;
    let mut weld = vec![0u32; scene.v.len()];
    let mut scratch = vec![HalfEdgeRecord::default(); scene.idx.len()];
    let mut store = vec![MeshEdge::default(); scene.idx.len()];
    let adj = EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut store)?;
    let sizes = RaycastStorage::sizes(mesh.face_count());
    let mut nodes = vec![BvhNode::default(); sizes.nodes];
    let mut faces = vec![RayFace::default(); sizes.faces];
    let storage = RaycastStorage {
        nodes: &mut nodes,
        faces: &mut faces,
    };
    render_with(&mesh, &adj, camera, Frame { w, h, band }, engine, storage)
}

/// [`render`] of a built mesh, the ray-casting engine in `storage`.
fn render_with(
    mesh: &Mesh<'_>,
    adj: &EdgeAdjacency<'_>,
    camera: &Camera,
    frame: Frame,
    engine: Engine,
    mut storage: RaycastStorage<'_>,
) -> Result<(Vec<u16>, RaycastFigures), Error> {
    let Frame { w, h, band } = frame;
    let settings = Settings {
        mode: DrawMode::Surfaces,
        cull: Cull::Off,
        pattern: Pattern::PAPER,
        dashes: Dashes::Screen,
        lines: crate::render::LineVisibility::ByPixel,
    };
    let mut target = Blank(Viewport {
        width: w as u16,
        height: h as u16,
    });
    let mut probe = Ids {
        width: w,
        ids: vec![0; w * h],
    };
    let mut vertices = vec![ProjectedVertex::default(); mesh.vertices().len()];
    let mut drawn = vec![0u32; mesh.face_count().div_ceil(32)];
    let mut features = vec![0u32; adj.edges().len().div_ceil(32)];
    let stored = usize::from(crate::render::storage_rows(band as u16, h as u16));
    let mut ids = vec![0u16; w * stored];
    let mut lines = vec![0u32; 2 * w.div_ceil(32) * band];
    let figures = match engine {
        Engine::Raycast => {
            let mut ws = IdWorkspace {
                vertices: &mut vertices,
                drawn: &mut drawn,
                features: &mut features,
                ids: &mut ids,
                lines: &mut lines,
            };
            let mut r = RaycastRenderer::<U4, 16>::new();
            r.render(
                mesh,
                adj,
                camera,
                &settings,
                &mut ws,
                &mut storage,
                &MonoPalette::default(),
                &mut target,
                &mut probe,
            )
            .map_err(Error::widen)?;
            r.figures()
        }
        Engine::ZBuffer => {
            let mut depth = vec![0u32; w * stored];
            let mut ws = Workspace {
                vertices: &mut vertices,
                drawn: &mut drawn,
                features: &mut features,
                depth: &mut depth,
                ids: &mut ids,
                lines: &mut lines,
            };
            ZBufferRenderer::<U4, 64, 16>::new()
                .render(
                    mesh,
                    adj,
                    camera,
                    &settings,
                    &mut ws,
                    &MonoPalette::default(),
                    &mut target,
                    &mut probe,
                )
                .map_err(Error::widen)?;
            RaycastFigures::default()
        }
    };
    Ok((probe.ids, figures))
}

fn picture(ids: &[u16], w: usize) -> Vec<String> {
    ids.chunks(w)
        .map(|row| {
            row.iter()
                .map(|&id| match id {
                    0 => '.',
                    n => char::from_digit(u32::from(n - 1) % 36, 36).unwrap(),
                })
                .collect()
        })
        .collect()
}

/// Face 0 (z = 0) and the nearer face 1 (z = 1) overlap: face 1 shows there.
#[test]
fn the_nearer_of_two_overlapping_faces_is_visible() {
    let far = square(-1.5, -0.5, 0.5, 0.5, |_, _| 0.0);
    let near = square(-0.5, -0.75, 1.5, 0.25, |_, _| 1.0);
    let expected = [
        "................",
        "................",
        "..00000000......",
        "..000011111111..",
        "..000011111111..",
        "..000011111111..",
        "......11111111..",
        "................",
    ];
    for faces in [[&far[..], &near[..]], [&near[..], &far[..]]] {
        let scene = Scene::new(&faces);
        for band in [1, 3, H] {
            let (ids, fig) = render(&scene, &camera(), W, H, band, Engine::Raycast).unwrap();
            let mut want: Vec<String> = expected.iter().map(|r| String::from(*r)).collect();
            if core::ptr::eq(faces[0], &near[..]) {
                // Faces swapped: the ids swap with them.
                want = want
                    .iter()
                    .map(|r| {
                        r.chars()
                            .map(|c| match c {
                                '0' => '1',
                                '1' => '0',
                                c => c,
                            })
                            .collect()
                    })
                    .collect();
            }
            assert_eq!(picture(&ids, W), want, "band {band}");
            assert_eq!((fig.faces, fig.fallbacks), (2, 0));
        }
    }
}

/// Two faces in one plane (flat, then tilted): where they overlap the lower index
/// wins, whichever face that is, as with the Z-buffer.
#[test]
fn coplanar_faces_tie_to_the_lower_index() {
    type Plane = fn(f32, f32) -> f32;
    let planes: [Plane; 2] = [|_, _| 0.0, |x, y| 0.3 * x - 0.2 * y];
    for z in planes {
        let a = square(-1.5, -0.5, 0.5, 0.5, z);
        let b = square(-0.5, -0.75, 1.5, 0.25, z);
        for (faces, first) in [([&a[..], &b[..]], 'a'), ([&b[..], &a[..]], 'b')] {
            let scene = Scene::new(&faces);
            let (ids, _) = render(&scene, &camera(), W, H, H, Engine::Raycast).unwrap();
            let (zids, _) = render(&scene, &camera(), W, H, H, Engine::ZBuffer).unwrap();
            assert_eq!(ids, zids);
            // Columns 6..10 of rows 3..6 are covered by both.
            for y in 3..6 {
                for x in 6..10 {
                    assert_eq!(ids[y * W + x], 1, "{first} first, pixel ({x}, {y})");
                }
            }
            // Row 3: the first face (id 1) holds its own columns and the overlap.
            let row3 = if first == 'a' {
                "..000000001111.."
            } else {
                "..111100000000.."
            };
            assert_eq!(picture(&ids, W)[3], row3, "{first} first");
        }
    }
}

/// Too little storage is `CapacityExceeded` with the length needed.
#[test]
fn too_little_storage_is_an_error_with_the_size_needed() {
    let a = square(-1.5, -0.5, 0.5, 0.5, |_, _| 0.0);
    let b = square(-0.5, -0.75, 1.5, 0.25, |_, _| 1.0);
    let c = square(-1.0, -1.0, 1.0, 1.0, |_, _| 0.5);
    let scene = Scene::new(&[&a, &b, &c]);
    let mesh = Mesh::new(&scene.v, &scene.idx, &scene.off).unwrap();
    let mut weld = vec![0u32; scene.v.len()];
    let mut scratch = vec![HalfEdgeRecord::default(); scene.idx.len()];
    let mut store = vec![MeshEdge::default(); scene.idx.len()];
    let adj = EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut store).unwrap();
    let sizes = RaycastStorage::sizes(3);
    assert_eq!(sizes, RaycastSizes { nodes: 5, faces: 3 });
    let cam = camera();
    let run = |nodes: usize, faces: usize| {
        let mut n = vec![BvhNode::default(); nodes];
        let mut f = vec![RayFace::default(); faces];
        let storage = RaycastStorage {
            nodes: &mut n,
            faces: &mut f,
        };
        let frame = Frame {
            w: W,
            h: H,
            band: H,
        };
        render_with(&mesh, &adj, &cam, frame, Engine::Raycast, storage).map(|r| r.0)
    };
    assert_eq!(
        run(5, 2).unwrap_err(),
        Error::CapacityExceeded {
            what: Capacity::RaycastFaces,
            needed: 3,
            capacity: 2
        }
    );
    assert_eq!(
        run(4, 3).unwrap_err(),
        Error::CapacityExceeded {
            what: Capacity::BvhNodes,
            needed: 5,
            capacity: 4
        }
    );
    let ids = run(5, 3).unwrap();
    assert!(ids.contains(&1) && ids.contains(&2) && ids.contains(&3));
}

/// A small deterministic generator.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((self.0 >> 40) as f32) / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }
}

/// Hundreds of crossing triangles, some coplanar with the one before (ties), in
/// perspective: the Z-buffer's frame, pixel for pixel, in any band height.
#[test]
fn a_deep_soup_draws_the_z_buffer_frame() {
    let mut rng = Lcg(7);
    let mut tris: Vec<Vec<[f32; 3]>> = Vec::new();
    for k in 0..400 {
        let c = [
            rng.range(-1.5, 1.5),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let mut p = || {
            [
                c[0] + rng.range(-0.4, 0.4),
                c[1] + rng.range(-0.4, 0.4),
                c[2] + rng.range(-0.4, 0.4),
            ]
        };
        let t = vec![p(), p(), p()];
        if k % 5 == 4 {
            // Coplanar with the previous triangle, overlapping it.
            let q = tris.last().unwrap().clone();
            let mix = |u: f32, v: f32| {
                [0, 1, 2].map(|i| q[0][i] + u * (q[1][i] - q[0][i]) + v * (q[2][i] - q[0][i]))
            };
            tris.push(vec![mix(0.2, 0.1), mix(1.1, 0.2), mix(0.3, 0.9)]);
        } else {
            tris.push(t);
        }
    }
    let faces: Vec<&[[f32; 3]]> = tris.iter().map(|t| &t[..]).collect();
    let scene = Scene::new(&faces);
    let projection = Projection::Perspective { fov_y_deg: 50.0 };
    let cam = Camera::new(
        [0.5, 0.8, 4.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        projection,
        0.5,
        20.0,
    )
    .unwrap();
    let (zids, _) = render(&scene, &cam, 64, 48, 48, Engine::ZBuffer).unwrap();
    let covered = zids.iter().filter(|&&id| id != 0).count();
    assert!(
        covered > 1000,
        "the soup covers {covered} pixels:\n{}",
        picture(&zids, 64).join("\n")
    );
    for band in [48, 5] {
        let (ids, fig) = render(&scene, &cam, 64, 48, band, Engine::Raycast).unwrap();
        let differ = ids.iter().zip(&zids).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "band {band}: {differ} pixels differ");
        assert!(fig.nodes > 100, "a deep tree: {fig:?}");
        // Both ways of tracing are taken: tile lists and the tree.
        assert!(
            fig.tree_pixels > 0 && fig.tree_pixels < 64 * 48 / 2,
            "{fig:?}"
        );
        // The pruned trace tests far fewer faces than there are faces.
        assert!(fig.face_tests < 64 * 48 * 400 / 20, "{fig:?}");
    }
}

/// The pruning argument on random hit sets: kept in any order (some set aside as a
/// pruned node would be), the tie-closed nearest hits decide as the Z-buffer's rule
/// over every hit in index order, unless the trace reports it cannot tell (then the
/// pixel goes to the exhaustive pass).
#[test]
fn the_tie_closed_nearest_hits_decide_as_all_hits_do() {
    let mut rng = Lcg(11);
    let (mut decided, mut undecided) = (0, 0);
    for _ in 0..20_000 {
        let n = 1 + (rng.next() * 14.0) as usize;
        let mut hits: Vec<Hit> = (0..n)
            .map(|k| Hit {
                face: k as u16,
                entry: k as u32,
                q: 1000 + (rng.next() * 200.0) as u32,
                tie: (rng.next() * 40.0) as u32,
            })
            .collect();
        let want = fold(hits.iter().copied()).map(|h| h.face);
        // Shuffle: the order a trace meets them in.
        for i in (1..n).rev() {
            let j = (rng.next() * (i + 1) as f32) as usize % (i + 1);
            hits.swap(i, j);
        }
        let mut c = Candidates::new();
        for h in &hits {
            // As the trace does: a hit below the current floor is pruned.
            if i64::from(h.q) < c.floor {
                c.lose(h.q);
            } else {
                c.insert(*h);
            }
        }
        if c.lost >= c.floor {
            undecided += 1;
            continue;
        }
        decided += 1;
        assert_eq!(c.winner().map(|h| h.face), want, "{hits:?}");
    }
    std::println!("{decided} decided, {undecided} to the exhaustive pass");
    assert!(
        decided > 10_000 && undecided > 100,
        "{decided} / {undecided}"
    );
}
