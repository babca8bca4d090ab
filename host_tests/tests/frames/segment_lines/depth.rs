//! Hidden lines by the segment where depth decides: faces 1e-4 apart far from
//! the eye, random views (no negative count), and boxes in contact seen at a
//! grazing angle (ignored: a known fault).

use super::*;

/// The pair of `nearly_parallel_faces_1e_minus_4_apart_at_depth_100`
/// (robustness): a far quad at z = -100 and a nearer one 1e-4 in front of it,
/// tilted by about 1e-6 rad, overlapping; eye at the origin looking along -z.
fn parallel_pair(gap: f64, nearer_first: bool) -> MeshData {
    let depth = 100.0;
    let mut m = MeshData::default();
    let s = depth * 0.2;
    let (z_far, z_near) = (-depth, -depth + gap);
    let t = gap * 0.25 / s;
    let far = [
        [-s, -s, z_far],
        [s * 0.5, -s, z_far],
        [s * 0.5, s, z_far],
        [-s, s, z_far],
    ];
    let near = [
        [-s * 0.5, -s * 0.5, z_near - t * s],
        [s, -s * 0.5, z_near + t * s],
        [s, s * 0.5, z_near + t * s],
        [-s * 0.5, s * 0.5, z_near - t * s],
    ];
    let quads = if nearer_first {
        [near, far]
    } else {
        [far, near]
    };
    for q in quads {
        let base = m.vertices.len() as u32;
        m.vertices.extend(q);
        m.faces.push((base..base + 4).collect());
    }
    m
}

/// The pair of line_test's `edges_1e_4_behind_a_tilted_face_far_from_the_eye_are_hidden`:
/// a square of half-size 20 at z = 0 and a larger square over it, 1e-4 in front of
/// its corner (-20, -20) and rising 1e-3 a unit along x and y.
fn tilted_pair(nearer_first: bool) -> MeshData {
    let (gap, slope, h) = (1e-4, 1e-3, 20.0);
    let z = |x: f64, y: f64| gap + slope * ((x + h) + (y + h));
    let square = [[-h, -h, 0.0], [h, -h, 0.0], [h, h, 0.0], [-h, h, 0.0]];
    let over =
        [(-25.0, -25.0), (45.0, -25.0), (45.0, 45.0), (-25.0, 45.0)].map(|(x, y)| [x, y, z(x, y)]);
    let quads = if nearer_first {
        [over, square]
    } else {
        [square, over]
    };
    let mut m = MeshData::default();
    for q in quads {
        let base = m.vertices.len() as u32;
        m.vertices.extend(q);
        m.faces.push((base..base + 4).collect());
    }
    m
}

/// Faces 1e-4 apart at depth 100, in both face orders: (a) the nearly parallel
/// pair (eye at the origin, near 1, far 1000, fov 60, 160x120); (b) the tilted
/// pair (eye (3, 5, 100), near 0.1, far 1000, fov 60, 160x120). Cull off.
///
/// Rule: a point is hidden only by a face strictly nearer there (equal depth
/// does not hide), whatever the faces' order. Expected: the farther quad's
/// edges inside the overlap hidden (in the tilted pair, including the corner
/// where the gap is only 1e-4), outside visible; the nearer quad's edges
/// visible everywhere; the same classification in both face orders.
#[test]
fn faces_1e_4_apart_at_depth_100_both_orders() {
    let parallel_cam = CameraSpec {
        eye: [0.0, 0.0, 0.0],
        target: [0.0, 0.0, -1.0],
        up: [0.0, 1.0, 0.0],
        projection: ProjectionSpec::Perspective { fov_deg: 60.0 },
        near: 1.0,
        far: 1000.0,
    };
    let tilted_cam = CameraSpec {
        eye: [3.0, 5.0, 100.0],
        target: [0.0, 0.0, 0.0],
        up: [0.0, 1.0, 0.0],
        projection: ProjectionSpec::Perspective { fov_deg: 60.0 },
        near: 0.1,
        far: 1000.0,
    };
    let mut failures = Vec::new();
    for nearer_first in [true, false] {
        failures.extend(check_by_segment(
            &format!("parallel 1e-4 at 100, nearer first {nearer_first}"),
            &parallel_pair(1e-4, nearer_first),
            &parallel_cam,
            (160, 120),
            CullSpec::Off,
        ));
        failures.extend(check_by_segment(
            &format!("tilted 1e-4 at 100, nearer first {nearer_first}"),
            &tilted_pair(nearer_first),
            &tilted_cam,
            (160, 120),
            CullSpec::Off,
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Property: across random views (seeded; six each, perspective and
/// orthographic, 160x120) of the torus (24 x 12) and the `boxes` scene, culled,
/// the segment path classifies every frame (no fallback) and no count of
/// quantitative invisibility goes below zero (`segment_negative_counts == 0`):
/// a negative count means a chain crossed a contour it should not have, or
/// missed one. The comparisons are printed, not checked.
#[test]
fn random_views_have_no_negative_counts() {
    let mut rng = Rng::new(0x5e6_1e5);
    let mut failures = Vec::new();
    for (name, m) in [("torus", torus(24, 12, 1.0, 0.4)), ("boxes", boxes())] {
        let base = three_quarter_camera(&m, 160, 120, false);
        let d = [0, 1, 2].map(|k| base.eye[k] - base.target[k]);
        let dist = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        for k in 0..6 {
            // A direction on the sphere away from the poles (the up vector is +y).
            let (dir, ortho) = loop {
                let v = [0, 1, 2].map(|_| rng.range(-1.0, 1.0));
                let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                if n > 0.2 && n <= 1.0 && (v[1] / n).abs() < 0.9 {
                    break (v.map(|c| c / n), rng.chance(0.5));
                }
            };
            let mut cam = base;
            cam.eye = [0, 1, 2].map(|i| base.target[i] + dist * dir[i]);
            if ortho {
                cam = CameraSpec {
                    projection: three_quarter_camera(&m, 160, 120, true).projection,
                    ..cam
                };
            }
            let label = format!(
                "{name} random view {k} {}",
                if ortho { "ortho" } else { "persp" }
            );
            let spec = fast_spec((160, 120), CullSpec::Auto, LineVisibility::BySegment);
            let frame = render_frame(&m, &cam, &spec).unwrap();
            let rf = reference_frame(&m, &cam, &spec).unwrap();
            println!("{}", compare(&label, &frame, &rf, false, true));
            let per_pixel = render_frame(
                &m,
                &cam,
                &fast_spec((160, 120), CullSpec::Auto, LineVisibility::ByPixel),
            )
            .unwrap();
            println!(
                "{}",
                compare(&format!("{label} by-pixel"), &per_pixel, &rf, false, true)
            );
            println!("{label}: {}", segment_figures(&frame));
            if frame.stat("segment_drawn_edges") == 0
                || frame.stat("segment_fallback") != 0
                || frame.stat("segment_negative_counts") != 0
            {
                failures.push(format!("{label}: {}", segment_figures(&frame)));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Boxes standing on a slab, seen low: the `boxes` scene (a slab whose top is
/// y = -1, boxes whose bottoms lie exactly in that plane) from just above the
/// slab's top, eye (-7.32, -0.486, -8.73) (0.51 above the top plane, about 3
/// degrees), looking at the origin, 160x120, fov 40, culled; found by
/// `random_views_have_no_negative_counts` (its boxes view 0). And the same
/// view of the slab with only the first box on it.
///
/// Rule: an edge in a face's plane is not hidden by it (equal depth does not
/// hide). Expected: the boxes' bottom edges on the near side (on the slab's
/// top face, in front of the eye) visible, as the reference and the per-pixel
/// test draw them.
#[test]
#[ignore = "library: the segment path hides the box bottom edges that lie in the slab's \
            top plane (x = -1.6 and z = 0.1 at y = -1, on screen rows 74-75): measured \
            2026-11-29, boxes: visible length missing 3.145 % (limit 1 %), one box: \
            3.837 % (21 px drawn hidden where the reference and by-pixel draw them \
            visible; segment_piercings = 4 with no edge through a face); by-pixel 0.000 %"]
fn boxes_standing_on_a_slab_seen_at_a_grazing_angle() {
    let cam = CameraSpec {
        eye: [-7.321715426291396, -0.4860187943081847, -8.733992731452078],
        target: [0.0, 0.0, 0.0],
        up: [0.0, 1.0, 0.0],
        projection: ProjectionSpec::Perspective { fov_deg: 40.0 },
        near: 6.080709890046433,
        far: 16.733878432785257,
    };
    let mut one_box = MeshData::default();
    add_box(&mut one_box, [0.0, -1.1, 0.0], [2.6, 0.1, 2.1], 0.0, 0.0);
    add_box(&mut one_box, [-1.0, -0.3, 0.6], [0.6, 0.7, 0.5], 0.0, 0.0);
    let mut failures = Vec::new();
    for (label, m) in [("boxes on slab", boxes()), ("one box on slab", one_box)] {
        failures.extend(check_by_segment(
            label,
            &m,
            &cam,
            (160, 120),
            CullSpec::Auto,
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
