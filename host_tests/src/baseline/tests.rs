//! Unit tests of the baseline: a cube in front and three-quarter views, clipping, pattern.

use super::*;
use crate::frame::{CameraSpec, CullSpec, MeshData, ModeSpec, ProjectionSpec, RenderSpec};

fn cube() -> MeshData {
    let mut m = MeshData::default();
    for i in 0..8 {
        m.vertices.push([
            f64::from(i & 1) * 2.0 - 1.0,
            f64::from((i >> 1) & 1) * 2.0 - 1.0,
            f64::from((i >> 2) & 1) * 2.0 - 1.0,
        ]);
    }
    // CCW seen from outside.
    m.faces = vec![
        vec![0, 2, 3, 1], // -z
        vec![4, 5, 7, 6], // +z
        vec![0, 1, 5, 4], // -y
        vec![2, 6, 7, 3], // +y
        vec![0, 4, 6, 2], // -x
        vec![1, 3, 7, 5], // +x
    ];
    m
}

fn spec(mode: ModeSpec) -> RenderSpec {
    RenderSpec {
        width: 120,
        height: 80,
        mode,
        ..RenderSpec::default()
    }
}

#[test]
fn cube_front_view() {
    let cam = CameraSpec {
        eye: [0.0, 0.0, 6.0],
        ..CameraSpec::default()
    };
    let f = render_baseline(&cube(), &cam, &spec(ModeSpec::Dashed));
    let stat = |k: &str| f.stats.iter().find(|(n, _)| n == k).map(|s| s.1);
    assert_eq!(stat("faces"), Some(6));
    assert_eq!(stat("closed"), Some(1));
    // Only the front face is visible from straight ahead; it covers the centre.
    assert_eq!(f.ids[40 * 120 + 60], 2);
    assert_eq!(stat("faces_drawn"), Some(1));
    // The silhouette is the front square's outline: 4 edges, all visible.
    assert_eq!(stat("feature_edges"), Some(12));
    assert!(f.lines.contains(&1));
    let set: u32 = f.packed.iter().map(|b| b.count_ones()).sum();
    assert!(set > 100, "{set}");
}

#[test]
fn hidden_edges_are_dashed_three_quarter() {
    let cam = CameraSpec {
        eye: [4.0, 3.0, 5.0],
        projection: ProjectionSpec::Perspective { fov_deg: 45.0 },
        ..CameraSpec::default()
    };
    let mut s = spec(ModeSpec::Dashed);
    s.cull = CullSpec::Off;
    let f = render_baseline(&cube(), &cam, &s);
    let hidden = f.lines.iter().filter(|&&l| l == 2).count();
    let visible = f.lines.iter().filter(|&&l| l == 1).count();
    assert!(hidden > 20 && visible > 100, "{hidden} {visible}");
    // Every visible line pixel is set; hidden ones only where the pattern passes.
    let p = PatternTable::by_name("paper").unwrap();
    let stride = 120usize.div_ceil(8);
    for y in 0..80 {
        for x in 0..120 {
            let on = f.packed[y * stride + x / 8] >> (7 - x % 8) & 1 != 0;
            match f.lines[y * 120 + x] {
                1 => assert!(on),
                2 => assert_eq!(on, p.value(x, y) != 0),
                _ => assert!(!on),
            }
        }
    }
    let h = render_baseline(&cube(), &cam, &spec(ModeSpec::Hidden));
    let set: u32 = h.packed.iter().map(|b| b.count_ones()).sum();
    assert_eq!(set as usize, h.lines.iter().filter(|&&l| l == 1).count());
}

#[test]
fn near_plane_clips_instead_of_dropping() {
    // Eye inside the cube's slab: near plane cuts faces.
    let cam = CameraSpec {
        eye: [0.0, 0.0, 1.5],
        near: 1.0,
        ..CameraSpec::default()
    };
    let mut s = spec(ModeSpec::Dashed);
    s.cull = CullSpec::Off;
    let f = render_baseline(&cube(), &cam, &s);
    assert!(f.ids.iter().filter(|&&i| i != 0).count() > 1000);
}

#[test]
fn paper_pattern_table_matches_the_library() {
    let t = PatternTable::by_name("paper").unwrap();
    let p = pbuffer::Pattern::PAPER;
    for y in 0..20 {
        for x in 0..20 {
            assert_eq!(t.value(x, y) != 0, p.passes(x as u32, y as u32));
        }
    }
    assert!(PatternTable::by_name("nope").is_none());
}
