//! Unit tests of the reference: coverage, cameras, pixels, depth order, edges, clipping.

use super::*;
use crate::frame::{CameraSpec, CullSpec, MeshData, ProjectionSpec, RenderSpec};

fn spec(w: usize, h: usize) -> RenderSpec {
    RenderSpec {
        width: w,
        height: h,
        band: h,
        ..RenderSpec::default()
    }
}

/// Orthographic camera looking down -Z with half-height h (x, y map linearly).
fn ortho(h: f64) -> CameraSpec {
    CameraSpec {
        eye: [0.0, 0.0, 10.0],
        target: [0.0, 0.0, 0.0],
        projection: ProjectionSpec::Orthographic { half_height: h },
        ..CameraSpec::default()
    }
}

#[test]
fn covers_agrees_with_the_2d_reference() {
    let mut state = 99u64;
    let mut next = |k: u64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state % k
    };
    for _ in 0..300 {
        let n = 3 + next(5) as usize;
        let pts: Vec<(f64, f64)> = (0..n)
            .map(|_| (next(80) as f64 / 4.0, next(80) as f64 / 4.0))
            .collect();
        let poly = crate::reference::Polygon::new(&pts, 20.0);
        for j in 0..20 {
            for i in 0..20 {
                let p = (i as f64 + 0.5, j as f64 + 0.5);
                assert_eq!(
                    covers(&pts, p),
                    poly.covered(crate::reference::Rule::EvenOdd, p.0, p.1)
                );
            }
        }
    }
}

#[test]
fn rejects_degenerate_cameras() {
    let s = spec(8, 8);
    let m = MeshData {
        vertices: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        faces: vec![vec![0, 1, 2]],
    };
    let bad = [
        CameraSpec {
            eye: [0.0; 3],
            ..CameraSpec::default()
        },
        CameraSpec {
            up: [0.0, 0.0, 1.0],
            ..CameraSpec::default()
        },
        CameraSpec {
            projection: ProjectionSpec::Perspective { fov_deg: 180.0 },
            ..CameraSpec::default()
        },
        CameraSpec {
            projection: ProjectionSpec::Perspective { fov_deg: 0.0 },
            ..CameraSpec::default()
        },
        CameraSpec {
            near: 0.0,
            ..CameraSpec::default()
        },
        CameraSpec {
            far: 0.1,
            ..CameraSpec::default()
        },
        CameraSpec {
            projection: ProjectionSpec::Orthographic { half_height: 0.0 },
            ..CameraSpec::default()
        },
    ];
    for c in bad {
        assert!(reference_frame(&m, &c, &s).is_err(), "{c:?}");
    }
    assert!(reference_frame(&m, &CameraSpec::default(), &s).is_ok());
}

/// A unit square in z = 0 seen orthographically with half-height 4 on an 8x8 frame:
/// 1 world unit = 1 px, the square [0,1]^2 covers screen x in [4, 5], y in [3, 4]:
/// exactly pixel (4, 3). Enlarged to [-1.5, 1.5] x [-0.5, 2.5] (screen x 2.5..5.5,
/// y 1.5..4.5) it covers columns 2..=4 and rows 1..=3 by the top-left rule.
#[test]
fn single_quad_covers_expected_pixels() {
    let s = spec(8, 8);
    let quad = |x0: f64, y0: f64, x1: f64, y1: f64| MeshData {
        vertices: vec![[x0, y0, 0.0], [x1, y0, 0.0], [x1, y1, 0.0], [x0, y1, 0.0]],
        faces: vec![vec![0, 1, 2, 3]],
    };
    let r = reference_frame(&quad(0.0, 0.0, 1.0, 1.0), &ortho(4.0), &s).unwrap();
    let on: Vec<usize> = (0..64).filter(|&k| r.ids[k] != 0).collect();
    assert_eq!(on, vec![3 * 8 + 4]);
    assert_eq!(r.depth[3 * 8 + 4], 10.0);
    let r = reference_frame(&quad(-1.5, -0.5, 1.5, 2.5), &ortho(4.0), &s).unwrap();
    let mut expect = Vec::new();
    for j in 1..=3 {
        for i in 2..=4 {
            expect.push(j * 8 + i);
        }
    }
    let on: Vec<usize> = (0..64).filter(|&k| r.ids[k] != 0).collect();
    assert_eq!(on, expect);
    // An open quad: 4 boundary edges, no culling.
    assert_eq!(r.feature_edges, 4);
    assert!(!r.culling);
    // Back side: the same quad wound clockwise is still drawn (not closed, no culling).
    let mut m = quad(-1.5, -0.5, 1.5, 2.5);
    m.faces[0].reverse();
    let r2 = reference_frame(&m, &ortho(4.0), &s).unwrap();
    assert_eq!(r2.ids, r.ids);
    // With culling on it disappears.
    let s_on = RenderSpec {
        cull: CullSpec::On,
        ..s.clone()
    };
    let r3 = reference_frame(&m, &ortho(4.0), &s_on).unwrap();
    assert!(r3.ids.iter().all(|&i| i == 0));
}

/// A perspective quad facing the camera: fov 90 at distance 1, so the screen half-
/// height (H/2 = 4 px) equals 1 world unit at z = 0.
#[test]
fn perspective_quad_maps_like_ortho_at_unit_distance() {
    let s = spec(8, 8);
    let cam = CameraSpec {
        eye: [0.0, 0.0, 1.0],
        projection: ProjectionSpec::Perspective { fov_deg: 90.0 },
        ..CameraSpec::default()
    };
    let m = MeshData {
        vertices: vec![
            [0.0, 0.0, 0.0],
            [0.25, 0.0, 0.0],
            [0.25, 0.25, 0.0],
            [0.0, 0.25, 0.0],
        ],
        faces: vec![vec![0, 1, 2, 3]],
    };
    let r = reference_frame(&m, &cam, &s).unwrap();
    let on: Vec<usize> = (0..64).filter(|&k| r.ids[k] != 0).collect();
    assert_eq!(on, vec![3 * 8 + 4]);
    assert!((r.depth[3 * 8 + 4] - 1.0).abs() < 1e-12);
}

/// An axis-aligned box from its corners (`shapes::add_box` without rotation).
fn boxm(lo: V3, hi: V3, m: &mut MeshData) {
    let centre = [0, 1, 2].map(|i| (lo[i] + hi[i]) / 2.0);
    let half = [0, 1, 2].map(|i| (hi[i] - lo[i]) / 2.0);
    crate::shapes::add_box(m, centre, half, 0.0, 0.0);
}

/// A small box in front of a big box, seen orthographically along -Z (1 unit = 1 px
/// on a 16x16 frame with half-height 8): the front box's +z face covers its pixels,
/// the back box shows around it; the back box's far edges are hidden; the front box's
/// outline is visible.
#[test]
fn box_behind_box() {
    let mut m = MeshData::default();
    boxm([-6.0, -6.0, -4.0], [6.0, 6.0, -2.0], &mut m); // faces 0..6, +z face = 5
    boxm([-2.0, -2.0, 0.0], [2.0, 2.0, 2.0], &mut m); // faces 6..12, +z face = 11
    let s = spec(16, 16);
    let r = reference_frame(&m, &ortho(8.0), &s).unwrap();
    assert!(r.closed && r.culling);
    // Only the two +z faces face the eye.
    assert_eq!(r.faces_drawn, 2);
    // front box: x in [-2, 2] -> screen 6..10, covers columns 6..=9, rows 6..=9.
    for j in 0..16 {
        for i in 0..16 {
            let id = r.ids[j * 16 + i];
            if (6..10).contains(&i) && (6..10).contains(&j) {
                assert_eq!(id, 12, "{i} {j}");
                assert_eq!(r.depth[j * 16 + i], 8.0);
            } else if (2..14).contains(&i) && (2..14).contains(&j) {
                assert_eq!(id, 6, "{i} {j}");
                assert_eq!(r.depth[j * 16 + i], 12.0);
            } else {
                assert_eq!(id, 0, "{i} {j}");
            }
        }
    }
    // All 24 edges are creases (90 degrees); seen along an axis, the side edges
    // project to points and the back outlines coincide with the front outlines.
    assert_eq!(r.feature_edges, 24);
    // The back box's front outline (z = -2) is visible, its back outline (z = -4)
    // lies under its own +z face (not one of its faces) and is hidden: both land on
    // the same pixels, where 1 wins. Check the samples instead.
    let back_far: Vec<&LineSample> = r
        .samples
        .iter()
        .filter(|s| (s.depth - 14.0).abs() < 1e-9)
        .collect();
    assert!(!back_far.is_empty());
    // The outline lies exactly on the boundary of the +z face's projection (screen
    // square 2..14): the top-left rule covers its left (x = 2) and top (y = 2) sides,
    // so those are hidden, and not its right and bottom sides, which stay visible.
    for s in &back_far {
        let inner = |v: f64| v > 2.0 && v < 14.0;
        let on = |v: f64, c: f64| (v - c).abs() < 1e-9;
        if (on(s.x, 2.0) && inner(s.y)) || (on(s.y, 2.0) && inner(s.x)) {
            assert!(!s.visible, "{s:?}");
        } else if on(s.x, 14.0) || on(s.y, 14.0) {
            assert!(s.visible, "{s:?}");
        }
    }
    // The front box's front outline (depth 8) is all visible.
    assert!(r
        .samples
        .iter()
        .filter(|s| (s.depth - 8.0).abs() < 1e-9)
        .all(|s| s.visible));
    // The back box's front outline, where it passes behind... it does not: all visible.
    assert!(r
        .samples
        .iter()
        .filter(|s| (s.depth - 12.0).abs() < 1e-9)
        .all(|s| s.visible));
    // The front box's back outline (depth 10) lies under its own +z face: hidden.
    assert!(r
        .samples
        .iter()
        .filter(|s| (s.depth - 10.0).abs() < 1e-9
            && s.x > 6.1
            && s.x < 9.9
            && s.y > 6.1
            && s.y < 9.9)
        .all(|s| !s.visible));
}

/// Perspective three-quarter view of a box, with a second box partly behind it: some
/// samples of the back box are hidden, and the pixel lines carry 2s.
#[test]
fn hidden_edge_in_perspective() {
    let mut m = MeshData::default();
    boxm([-1.0, -1.0, -1.0], [1.0, 1.0, 1.0], &mut m);
    boxm([-0.5, -0.5, -5.0], [0.5, 0.5, -3.0], &mut m);
    let cam = CameraSpec {
        eye: [0.5, 0.3, 6.0],
        ..CameraSpec::default()
    };
    let r = reference_frame(&m, &cam, &spec(64, 48)).unwrap();
    // The back box is entirely behind the front one: no pixel shows it.
    assert!(r.ids.iter().all(|&i| i == 0 || i <= 6));
    // Its silhouette edges exist and are all hidden.
    let back: Vec<&LineSample> = r.samples.iter().filter(|s| s.edge >= 12).collect();
    assert!(!back.is_empty());
    assert!(back.iter().all(|s| !s.visible));
    assert!(r.lines.contains(&2));
}

/// Crease and silhouette: a "roof" of two quads meeting at 90 degrees is a crease;
/// at 20 degrees (within the crease angle) it is not; a closed tetrahedron seen so that
/// exactly one face faces away has silhouette edges.
#[test]
fn crease_and_silhouette_classification() {
    let roof = |h: f64| MeshData {
        vertices: vec![
            [-1.0, 0.0, 0.0],
            [0.0, h, 0.0],
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, -1.0],
            [0.0, h, -1.0],
            [1.0, 0.0, -1.0],
        ],
        faces: vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]],
    };
    let cam = CameraSpec {
        eye: [0.0, 5.0, 5.0],
        target: [0.0, 0.0, -0.5],
        ..CameraSpec::default()
    };
    let s = spec(32, 32);
    // h = 1: faces at 45 degrees each side, 90 between normals -> crease.
    let r = reference_frame(&roof(1.0), &cam, &s).unwrap();
    let ridge: Vec<&RefEdge> = r.edges.iter().filter(|e| e.faces.len() == 2).collect();
    assert_eq!(ridge.len(), 1);
    assert_eq!(ridge[0].kind, Some(EdgeKind::Crease));
    assert_eq!(r.feature_edges, 7);
    // h = tan(10 deg): normals 20 degrees apart -> not drawn.
    let r = reference_frame(&roof(10f64.to_radians().tan()), &cam, &s).unwrap();
    let ridge: Vec<&RefEdge> = r.edges.iter().filter(|e| e.faces.len() == 2).collect();
    assert_eq!(ridge[0].kind, None);
    assert_eq!(r.feature_edges, 6);
    // Crease angle 10 -> drawn again.
    let s10 = RenderSpec {
        crease_deg: 10.0,
        ..s.clone()
    };
    let r = reference_frame(&roof(10f64.to_radians().tan()), &cam, &s10).unwrap();
    assert_eq!(r.feature_edges, 7);
    // Silhouette: a very flat roof seen from the side so one face is a back face.
    let cam_side = CameraSpec {
        eye: [5.0, 0.01, -0.5],
        target: [0.0, 0.0, -0.5],
        ..CameraSpec::default()
    };
    let r = reference_frame(&roof(0.05), &cam_side, &s).unwrap();
    assert!(r.faces[1].facing && !r.faces[0].facing);
    let ridge: Vec<&RefEdge> = r.edges.iter().filter(|e| e.faces.len() == 2).collect();
    assert_eq!(ridge[0].kind, Some(EdgeKind::Silhouette));
    // Welding: the same roof with the ridge vertices duplicated (bit-identical) still
    // has one shared ridge edge.
    let mut m = roof(1.0);
    m.vertices.push([0.0, 1.0, 0.0]);
    m.vertices.push([0.0, 1.0, -1.0]);
    m.faces[1] = vec![6, 2, 5, 7];
    let r = reference_frame(&m, &cam, &s).unwrap();
    assert_eq!(r.edges.iter().filter(|e| e.faces.len() == 2).count(), 1);
}

/// Near-plane clipping: a quad crossing the near plane is cut, not dropped.
#[test]
fn near_clipping_keeps_the_far_part() {
    let m = MeshData {
        vertices: vec![
            [-1.0, -0.2, 1.0],
            [1.0, -0.2, 1.0],
            [1.0, -0.2, -5.0],
            [-1.0, -0.2, -5.0],
        ],
        faces: vec![vec![0, 1, 2, 3]],
    };
    let cam = CameraSpec {
        eye: [0.0, 0.0, 0.5],
        near: 0.3,
        ..CameraSpec::default()
    };
    let r = reference_frame(&m, &cam, &spec(40, 30)).unwrap();
    let n = r.ids.iter().filter(|&&i| i != 0).count();
    assert!(n > 100, "{n}");
    assert!(r
        .depth
        .iter()
        .filter(|d| d.is_finite())
        .all(|&d| (0.3..=5.5).contains(&d)));
}

/// A non-planar quad takes its depth from the fan triangle the ray meets.
#[test]
fn non_planar_quad_depth_from_fan() {
    let m = MeshData {
        vertices: vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 0.0],
        ],
        faces: vec![vec![0, 1, 2, 3]],
    };
    let r = reference_frame(&m, &ortho(2.0), &spec(16, 16)).unwrap();
    // Fan (0,1,2) and (0,2,3); the point (0.5, -0.5) lies in triangle (0,1,2):
    // plane through (-1,-1,0), (1,-1,0), (1,1,1): z = (y + 1) / 2 -> z = 0.25.
    // screen: x = (0.5/2 + 1) * 8 = 10, y = (1 + 0.5/2) * 8 = 10.
    let d = r.face_depth(0, 10.0, 10.0).unwrap();
    assert!((d - (10.0 - 0.25)).abs() < 1e-12, "{d}");
    // (-0.5, 0.5) lies in triangle (0,2,3): plane z = (x + 1) / 2 -> 0.25 too;
    // (0.5, 0.5) is in (0,2,3)? No: in (0,1,2) iff x >= y. (0.6, 0.2) -> (0,1,2): 0.6.
    let (sx, sy) = ((0.6 / 2.0 + 1.0) * 8.0, (1.0 - 0.2 / 2.0) * 8.0);
    let d = r.face_depth(0, sx, sy).unwrap();
    assert!((d - (10.0 - 0.6)).abs() < 1e-12, "{d}");
}
