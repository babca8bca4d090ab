//! Properties of the renderer that need its internals.

extern crate std;
use std::vec;
use std::vec::Vec;

use fixed::types::extra::U4;

use super::lines::{edge_on_screen, walk_segment};
use super::transform::FixedView;
use super::two_squares::cube;
use super::*;
use crate::camera::Camera;
use crate::mesh::{EdgeAdjacency, HalfEdgeRecord, MeshEdge};
use crate::{PackedFramebuffer, Projection};

/// Keeps the whole frame's line masks.
struct Masks {
    words: usize,
    visible: Vec<u32>,
    hidden: Vec<u32>,
}

impl FrameProbe for Masks {
    fn row(&mut self, y: u16, _: &[u16], visible: &[u32], hidden: &[u32]) {
        let at = usize::from(y) * self.words;
        self.visible[at..at + self.words].copy_from_slice(visible);
        self.hidden[at..at + self.words].copy_from_slice(hidden);
    }
}

fn icosahedron() -> (Vec<[f32; 3]>, Vec<u32>, Vec<u32>) {
    let t = 1.618_034f32;
    let v = vec![
        [-1., t, 0.],
        [1., t, 0.],
        [-1., -t, 0.],
        [1., -t, 0.],
        [0., -1., t],
        [0., 1., t],
        [0., -1., -t],
        [0., 1., -t],
        [t, 0., -1.],
        [t, 0., 1.],
        [-t, 0., -1.],
        [-t, 0., 1.],
    ];
    let f: [[u32; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    (
        v,
        f.iter().flatten().copied().collect(),
        (0..=20).map(|i| 3 * i).collect(),
    )
}

/// Renders a 96x64 frame with `band` rows per band; returns the picture and masks.
fn render(
    mesh: &Mesh<'_>,
    adj: &EdgeAdjacency<'_>,
    camera: &Camera,
    band: usize,
    mode: DrawMode,
) -> (Vec<u8>, Masks) {
    let mut fb = PackedFramebuffer::<96, 64, { crate::packed_len(96, 64) }>::new();
    let mut vertices = vec![ProjectedVertex::default(); mesh.vertices().len()];
    let (mut drawn, mut features) = (vec![0u32; 1], vec![0u32; 1]);
    let stored = usize::from(storage_rows(band as u16, 64));
    let (mut depth, mut ids) = (vec![0u32; 96 * stored], vec![0u16; 96 * stored]);
    let mut lines = vec![0u32; 2 * 3 * band];
    let mut ws = Workspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        depth: &mut depth,
        ids: &mut ids,
        lines: &mut lines,
    };
    let mut masks = Masks {
        words: 3,
        visible: vec![0; 3 * 64],
        hidden: vec![0; 3 * 64],
    };
    let settings = Settings {
        mode,
        cull: Cull::Auto,
        pattern: Pattern::PAPER,
        dashes: Dashes::Screen,
        lines: LineVisibility::ByPixel,
    };
    let mut renderer = ZBufferRenderer::<U4, 16, 16>::new();
    let stats = renderer
        .render(
            mesh,
            adj,
            camera,
            &settings,
            &mut ws,
            &MonoPalette::default(),
            &mut fb,
            &mut masks,
        )
        .unwrap();
    assert_eq!(stats.band_rows as usize, band);
    (fb.as_bytes().to_vec(), masks)
}

/// The vertex cache keeps a projection or clip coordinates, not both (16 bytes a
/// vertex; it was 28 with both): an inside vertex's clip coordinates are made again
/// from its position, the same integers, and an outside vertex keeps its own and
/// has no projection.
#[test]
fn a_cached_vertex_keeps_its_projection_or_its_clip_coordinates_in_16_bytes() {
    assert_eq!(size_of::<ProjectedVertex>(), 16);
    let projection = Projection::Perspective { fov_y_deg: 40.0 };
    let camera = Camera::new(
        [0.0, 0.0, 6.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        projection,
        0.5,
        20.0,
    );
    let view = FixedView::new(&camera.unwrap(), 25.0, 96, 64, 4).unwrap();
    let (mut inside, mut outside) = (0, 0);
    // A line from behind the eye to beyond the far plane: both clipped.
    for k in 0..=60 {
        let t = k as f32 / 2.0;
        let p = [0.2 * t, 0.1, 8.0 - t];
        let clip = view.clip(p);
        let v = ProjectedVertex::new(&view, p);
        assert_eq!(v.outside(), view.outcode(&clip), "{p:?}");
        assert_eq!(v.clip(&view, p), clip, "{p:?}");
        if v.outside() == 0 {
            assert_eq!(v.screen(), view.project(&clip), "{p:?}");
            inside += 1;
        } else {
            assert_eq!(v.screen(), ScreenVertex::default(), "{p:?}");
            outside += 1;
        }
    }
    assert!(
        inside > 5 && outside > 5,
        "{inside} inside, {outside} outside"
    );
}

/// The k-th of n viewpoints spread over a sphere of radius 6 (golden-angle spiral).
fn viewpoint(k: u32, n: u32) -> Camera {
    let z = 1.0 - 2.0 * (k as f32 + 0.5) / n as f32;
    let r = crate::camera::sqrt(1.0 - z * z);
    let a = k as f32 * 2.399_963;
    let (s, c) = (sin(a), sin(a + core::f32::consts::FRAC_PI_2));
    let eye = [6.0 * r * c, 6.0 * z, 6.0 * r * s];
    let up = if z.abs() > 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let projection = Projection::Perspective { fov_y_deg: 40.0 };
    Camera::new(eye, [0.0; 3], up, projection, 0.5, 20.0).unwrap()
}

#[test]
fn band_height_does_not_change_the_frame() {
    let (v, idx, off) = icosahedron();
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let mut weld = vec![0u32; v.len()];
    let mut scratch = vec![HalfEdgeRecord::default(); idx.len()];
    let mut store = vec![MeshEdge::default(); idx.len()];
    let adj = EdgeAdjacency::build(&mesh, 1.0, &mut weld, &mut scratch, &mut store).unwrap();
    for k in 0..20 {
        let camera = viewpoint(k, 20);
        for mode in [DrawMode::Dashed, DrawMode::SurfacesDashed] {
            let (full, m) = render(&mesh, &adj, &camera, 64, mode);
            assert!(full.iter().any(|b| *b != 0));
            for band in [1, 5, 16] {
                let (banded, mb) = render(&mesh, &adj, &camera, band, mode);
                assert_eq!(banded, full, "view {k}, {mode:?}, band {band}");
                assert_eq!(
                    (mb.visible, mb.hidden),
                    (m.visible.clone(), m.hidden.clone())
                );
            }
        }
    }
}

#[test]
fn convex_solids_never_draw_a_visible_edge_pixel_dashed() {
    let mut checked = 0usize;
    for (name, (v, idx, off)) in [("cube", cube()), ("icosahedron", icosahedron())] {
        let mesh = Mesh::new(&v, &idx, &off).unwrap();
        let mut weld = vec![0u32; v.len()];
        let mut scratch = vec![HalfEdgeRecord::default(); idx.len()];
        let mut store = vec![MeshEdge::default(); idx.len()];
        // Crease 1 degree: every edge of these solids is a feature edge.
        let adj = EdgeAdjacency::build(&mesh, 1.0, &mut weld, &mut scratch, &mut store).unwrap();
        for k in 0..200u32 {
            let camera = viewpoint(k, 200);
            let (_, masks) = render(&mesh, &adj, &camera, 16, DrawMode::Dashed);
            // Walk every visible edge with the renderer's own rasterization.
            let view = FixedView::new(&camera, 1.7, 96, 64, 4).unwrap();
            let cache: Vec<ProjectedVertex> =
                v.iter().map(|p| ProjectedVertex::new(&view, *p)).collect();
            let ctx = FrameCtx {
                mesh: &mesh,
                positions: &v,
                settings: &Settings::default(),
                view,
                s: 4,
                viewport: Viewport {
                    width: 96,
                    height: 64,
                },
                viewpoint: camera.viewpoint(),
            };
            let viewpoint = camera.viewpoint();
            for edge in adj.edges() {
                let own_front = edge
                    .faces
                    .iter()
                    .any(|&f| mesh.faces_viewpoint(f as usize, &viewpoint));
                if !own_front {
                    continue;
                }
                let (a, b) = edge_on_screen(&ctx, &cache, edge).unwrap();
                walk_segment(&a, &b, 4, 96, 0..64, |p| {
                    let i = usize::from(p.y) * 3 + usize::from(p.x) / 32;
                    let on = masks.visible[i] & (1 << (p.x % 32)) != 0;
                    assert!(
                        on,
                        "{name}, view {k}: visible edge {edge:?} judged hidden at {},{}",
                        p.x, p.y
                    );
                    checked += 1;
                });
            }
        }
    }
    assert!(
        checked > 100_000,
        "the scenes exercise enough pixels: {checked}"
    );
}

/// sin for the test's viewpoints, by a short series after range reduction.
fn sin(x: f32) -> f32 {
    let tau = 2.0 * core::f32::consts::PI;
    let mut x = x % tau;
    if x > core::f32::consts::PI {
        x -= tau;
    }
    let (mut s, mut t) = (0.0f32, x);
    for k in 0..12 {
        s += t;
        let n = (2 * k + 2) as f32;
        t *= -x * x / (n * (n + 1.0));
    }
    s
}

/// `n` unit squares stacked along z (z = 0, -0.1, ...), all facing +z.
fn stack(n: u32) -> (Vec<[f32; 3]>, Vec<u32>, Vec<u32>) {
    let mut v = Vec::new();
    for k in 0..n {
        let z = -0.1 * k as f32;
        v.extend([[-1., -1., z], [1., -1., z], [1., 1., z], [-1., 1., z]]);
    }
    (v, (0..4 * n).collect(), (0..=n).map(|f| 4 * f).collect())
}

/// Renders `mesh` head-on at 96x64 with the code-fill engine of `WORDS` code words.
fn code_fill<const WORDS: usize, const EDGES: usize>(mesh: &Mesh<'_>) -> Result<Stats, Error> {
    code_fill_with::<WORDS, EDGES>(mesh, Visibility::Planes, &mut ())
}

/// [`code_fill_rows`] with the crossing list.
fn code_fill_with<const WORDS: usize, const EDGES: usize>(
    mesh: &Mesh<'_>,
    visibility: Visibility<'_>,
    probe: &mut impl FrameProbe,
) -> Result<Stats, Error> {
    code_fill_rows::<WORDS, EDGES>(mesh, RowCodes::Crossings, visibility, probe)
}

/// [`code_fill`] with a row representation, a way to find the nearest face and a
/// probe.
fn code_fill_rows<const WORDS: usize, const EDGES: usize>(
    mesh: &Mesh<'_>,
    codes: RowCodes<'_>,
    visibility: Visibility<'_>,
    probe: &mut impl FrameProbe,
) -> Result<Stats, Error> {
    let mut weld = vec![0u32; mesh.vertices().len()];
    let mut scratch = vec![HalfEdgeRecord::default(); mesh.indices().len()];
    let mut store = vec![MeshEdge::default(); mesh.indices().len()];
    let adj = EdgeAdjacency::build(mesh, 30.0, &mut weld, &mut scratch, &mut store).unwrap();
    let projection = Projection::Perspective { fov_y_deg: 40.0 };
    let camera = Camera::new(
        [0.2, 0.1, 6.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        projection,
        0.5,
        20.0,
    )
    .unwrap();
    let mut fb = PackedFramebuffer::<96, 64, { crate::packed_len(96, 64) }>::new();
    let surfaces = match &visibility {
        Visibility::Order(order) => order.surfaces,
        Visibility::Planes => *mesh,
    };
    let mut vertices = vec![ProjectedVertex::default(); surfaces.vertices().len()];
    let mut drawn = vec![0u32; mesh.face_count().div_ceil(32)];
    let mut features = vec![0u32; adj.edges().len().div_ceil(32)];
    let mut order = vec![0u32; surfaces.face_count()];
    let mut ids = vec![0u16; 96 * 10];
    let mut lines = vec![0u32; 2 * 3 * 8];
    let mut ws = CodeWorkspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        order: &mut order,
        ids: &mut ids,
        lines: &mut lines,
    };
    let settings = Settings::default();
    CodeFillRenderer::<U4, WORDS, 64, EDGES, 16>::new().render_with(
        mesh,
        &adj,
        &camera,
        &settings,
        &mut ws,
        codes,
        visibility,
        &MonoPalette::default(),
        &mut fb,
        probe,
    )
}

/// Every face id of the 96x64 frame.
struct FrameIds(Vec<u16>);

impl FrameProbe for FrameIds {
    fn row(&mut self, y: u16, ids: &[u16], _: &[u32], _: &[u32]) {
        let at = usize::from(y) * 96;
        self.0[at..at + 96].copy_from_slice(ids);
    }
}

#[test]
fn bit_sliced_rows_ignore_what_the_buffer_held_and_leave_it_clear() {
    // Three stacked squares in a depth order that ranks square 1 first: the
    // crossing list's frame is the reference.
    let (v, idx, off) = stack(3);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let order = DepthOrder {
        surfaces: mesh,
        source: &[0, 1, 2],
        rank: &[2, 0, 1],
    };
    let mut want = FrameIds(vec![0; 96 * 64]);
    code_fill_with::<1, 64>(&mesh, Visibility::Order(order), &mut want).unwrap();
    assert!(want.0.contains(&2));
    // A buffer left full of ones by someone else: cleared once by the frame, and
    // by each row as it reads it.
    type Engine = CodeFillRenderer<U4, 1, 64, 64, 16>;
    let len = Engine::bit_sliced_len(96);
    assert_eq!(len, 96 + 3, "a word per pixel, then a bit per pixel");
    let mut words = vec![u32::MAX; len];
    let mut got = FrameIds(vec![0; 96 * 64]);
    let codes = RowCodes::BitSliced(&mut words);
    code_fill_rows::<1, 64>(&mesh, codes, Visibility::Order(order), &mut got).unwrap();
    assert!(got.0 == want.0, "the bit-sliced frame differs");
    assert!(words.iter().all(|&w| w == 0), "left {words:x?}");
    // One word short: the length needed, not a truncated row.
    let mut short = vec![0u32; len - 1];
    let codes = RowCodes::BitSliced(&mut short);
    assert_eq!(
        code_fill_rows::<1, 64>(&mesh, codes, Visibility::Order(order), &mut ()),
        Err(Error::CapacityExceeded {
            what: Capacity::RowCodes,
            needed: len,
            capacity: len - 1
        })
    );
}

/// The face id (0 none, else 1 + face) at pixel (48, 32).
#[derive(Default)]
struct CentreId(u16);

impl FrameProbe for CentreId {
    fn row(&mut self, y: u16, ids: &[u16], _: &[u32], _: &[u32]) {
        if y == 32 {
            self.0 = ids[48];
        }
    }
}

#[test]
fn a_depth_order_decides_the_nearest_face_by_its_lowest_code_bit() {
    // Three squares stacked along z, square 0 nearest: the planes show face 0; an
    // order that ranks square 2 first shows square 2, with no depth compared.
    let (v, idx, off) = stack(3);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let source = [0u16, 1, 2];
    let mut seen = [0u16; 3];
    for (k, rank) in [[0u32, 1, 2], [2, 0, 1], [1, 2, 0]].iter().enumerate() {
        let order = DepthOrder {
            surfaces: mesh,
            source: &source,
            rank,
        };
        let mut centre = CentreId::default();
        let stats = code_fill_with::<1, 64>(&mesh, Visibility::Order(order), &mut centre).unwrap();
        assert_eq!(stats.code_bits, 3, "one bit per face on the row");
        seen[k] = centre.0;
    }
    assert_eq!(seen, [1, 2, 3]);
    let mut centre = CentreId::default();
    code_fill_with::<1, 64>(&mesh, Visibility::Planes, &mut centre).unwrap();
    assert_eq!(centre.0, 1);
}

#[test]
fn a_depth_order_made_for_another_mesh_is_an_error() {
    let (v, idx, off) = stack(3);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    let (v2, idx2, off2) = stack(2);
    let other = Mesh::new(&v2, &idx2, &off2).unwrap();
    let source = [0u16, 1, 2];
    let rank = [0u32, 1, 2];
    let orders = [
        // Vertices of another mesh.
        DepthOrder {
            surfaces: other,
            source: &source[..2],
            rank: &rank[..2],
        },
        // A rank missing.
        DepthOrder {
            surfaces: mesh,
            source: &source,
            rank: &rank[..2],
        },
        // A source face the mesh does not have.
        DepthOrder {
            surfaces: mesh,
            source: &[0, 1, 3],
            rank: &rank,
        },
    ];
    for order in orders {
        let got = code_fill_with::<1, 64>(&mesh, Visibility::Order(order), &mut ());
        assert_eq!(got, Err(Error::DepthOrderMismatch));
    }
}

#[test]
fn a_code_wider_than_compiled_is_an_error_with_the_width_needed() {
    let (v, idx, off) = stack(40);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    // 40 squares over the frame's centre: a 32-bit code is too narrow, 64 bits do.
    assert_eq!(
        code_fill::<1, 256>(&mesh),
        Err(Error::CodeTooWide {
            needed: 40,
            capacity: 32
        })
    );
    let stats = code_fill::<2, 256>(&mesh).unwrap();
    assert_eq!(stats.code_bits, 40);
    assert_eq!(stats.peak_faces, 40);
}

#[test]
fn too_many_active_edges_is_an_error_not_a_truncated_frame() {
    let (v, idx, off) = stack(40);
    let mesh = Mesh::new(&v, &idx, &off).unwrap();
    // Each square's four edges join the active edges when it starts (none is quite
    // horizontal in this view): up to 160.
    match code_fill::<2, 64>(&mesh) {
        Err(Error::CapacityExceeded {
            what: Capacity::ActiveEdges,
            needed,
            capacity,
        }) => {
            assert_eq!(capacity, 64);
            assert!(needed > 64, "needed {needed}");
        }
        other => panic!("expected CapacityExceeded, got {other:?}"),
    }
    let peak = code_fill::<2, 160>(&mesh).unwrap().peak_edges;
    assert!((81..=160).contains(&peak), "peak {peak}");
}
