//! Hidden lines dashed along each edge (`Dashes::Along`, `--dashes`), fast engine:
//! a long straight edge behind a square is drawn in dashes and gaps of the given
//! lengths measured along the edge from its anchor end (vertex 0, the edge's end
//! `a`), in every frame: the camera moved, the view turned so the edge is steep,
//! or zoomed so the anchor end is clipped far off screen. The `--lines` image
//! still has every hidden pixel (before the dashes), and a frame dashed by the
//! screen pattern does not pass the test.
//! `cargo test --release -p host_tests --test frames dashes_along::`.

use host_tests::frame::{
    CameraSpec, EngineSpec, Frame, MeshData, ModeSpec, ProjectionSpec, RenderSpec,
};
use host_tests::pipeline::render_frame;
use pbuffer::Dashes;

const W: usize = 200;
const H: usize = 120;

/// A triangle at z = -1 whose long edge A-B (vertices 0 and 1) runs behind a
/// square at z = 0; its other two edges stay clear of the square.
fn scene() -> MeshData {
    MeshData {
        vertices: vec![
            [-2.5, -1.5, -1.0], // A: the anchor end
            [2.5, 1.0, -1.0],   // B
            [-2.5, 3.0, -1.0],  // C
            [-1.8, -3.0, 0.0],
            [1.8, -3.0, 0.0],
            [1.8, 1.1, 0.0],
            [-1.8, 1.1, 0.0],
        ],
        faces: vec![vec![0, 1, 2], vec![3, 4, 5, 6]],
    }
}

/// Orthographic views down -z: centred at `target`, `half_height` world units
/// above and below, `up` on screen.
fn view(target: [f64; 2], half_height: f64, up: [f64; 3]) -> CameraSpec {
    CameraSpec {
        eye: [target[0], target[1], 5.0],
        target: [target[0], target[1], 0.0],
        up,
        projection: ProjectionSpec::Orthographic { half_height },
        near: 0.1,
        far: 100.0,
    }
}

/// Screen position of world point `p` (CONVENTIONS.md, orthographic).
fn screen(cam: &CameraSpec, p: [f64; 3]) -> (f64, f64) {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let unit = |a: [f64; 3]| {
        let l = dot(a, a).sqrt();
        a.map(|c| c / l)
    };
    let f = unit(sub(cam.target, cam.eye));
    let s = unit(cross(f, cam.up));
    let u = cross(s, f);
    let d = sub(p, cam.eye);
    let ProjectionSpec::Orthographic { half_height: h } = cam.projection else {
        unreachable!("orthographic views only")
    };
    let aspect = W as f64 / H as f64;
    let (xn, yn) = (dot(s, d) / (h * aspect), dot(u, d) / h);
    ((xn + 1.0) * W as f64 / 2.0, (1.0 - yn) * H as f64 / 2.0)
}

fn frame(cam: &CameraSpec, dashes: Dashes) -> Frame {
    let spec = RenderSpec {
        engine: EngineSpec::Fast,
        width: W,
        height: H,
        band: H,
        mode: ModeSpec::Dashed,
        dashes,
        ..RenderSpec::default()
    };
    render_frame(&scene(), cam, &spec).expect("frame")
}

fn drawn(f: &Frame, x: usize, y: usize) -> bool {
    let stride = W.div_ceil(8);
    f.packed[y * stride + x / 8] & (0x80 >> (x % 8)) != 0
}

/// Hidden pixels of A-B (every class-2 pixel of the `--lines` image) and, for
/// each, its distance along the edge from A (the major-axis distance of its
/// centre times sqrt(1 + slope^2), as the stepper measures it) and whether the
/// picture draws it.
fn hidden_along(f: &Frame, cam: &CameraSpec) -> Vec<(f64, bool)> {
    let (a, b) = (
        screen(cam, scene().vertices[0]),
        screen(cam, scene().vertices[1]),
    );
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len = dx.hypot(dy);
    let mut out = Vec::new();
    for y in 0..H {
        for x in 0..W {
            if f.lines[y * W + x] != 2 {
                continue;
            }
            let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
            let dist = if dx.abs() >= dy.abs() {
                (cx - a.0) / dx * len
            } else {
                (cy - a.1) / dy * len
            };
            out.push((dist, drawn(f, x, y)));
        }
    }
    out
}

/// Hidden pixels drawn where the distance from the anchor falls in a dash, and
/// left out in a gap, except within `slack` px of where a dash starts or ends;
/// returns the pixels checked and those that disagree.
fn check(px: &[(f64, bool)], dash: f64, gap: f64, slack: f64) -> (usize, usize) {
    let period = dash + gap;
    let mut bad = 0;
    let mut checked = 0;
    for &(dist, on) in px {
        let phase = dist.rem_euclid(period);
        let near_edge = phase < slack || (phase - dash).abs() < slack || period - phase < slack;
        if near_edge {
            continue;
        }
        checked += 1;
        if on != (phase < dash) {
            bad += 1;
        }
    }
    (checked, bad)
}

/// The frames: fitted; moved and zoomed a little (the dashes must not crawl);
/// turned a quarter so A-B is steep; zoomed so far in that A is beyond the
/// engine's guard box (the line is clipped, the anchor is A's projection).
fn views() -> Vec<(&'static str, CameraSpec)> {
    vec![
        ("fitted", view([0.0, 0.0], 3.2, [0.0, 1.0, 0.0])),
        ("moved", view([0.137, -0.071], 3.05, [0.0, 1.0, 0.0])),
        ("turned", view([0.05, 0.0], 3.2, [0.03, 1.0, 0.0])),
        ("steep", view([0.0, 0.1], 4.0, [-1.0, 0.0, 0.0])),
        ("clipped", view([0.6, 0.05], 0.004, [0.0, 1.0, 0.0])),
    ]
}

#[test]
fn hidden_pixels_are_dashed_along_the_edge_from_its_anchor_in_every_frame() {
    for (dash, gap) in [(12u8, 3u8), (5, 4)] {
        for (name, cam) in views() {
            let f = frame(&cam, Dashes::Along { dash, gap });
            let px = hidden_along(&f, &cam);
            assert!(px.len() >= 40, "{name}: {} hidden pixels", px.len());
            let (checked, bad) = check(&px, f64::from(dash), f64::from(gap), 1.0);
            assert!(checked >= px.len() / 2, "{name}: {checked} of {}", px.len());
            assert_eq!(bad, 0, "{name} {dash},{gap}: {bad} of {checked} pixels");
            // Gaps there are, and runs of them: some hidden pixels are left out.
            let off = px.iter().filter(|p| !p.1).count();
            assert!(
                off * 10 >= px.len(),
                "{name}: {off} of {} left out",
                px.len()
            );
        }
    }
}

#[test]
fn the_lines_image_keeps_every_hidden_pixel_and_visible_lines_stay_solid() {
    for (name, cam) in views() {
        let screen = frame(&cam, Dashes::Screen);
        let along = frame(&cam, Dashes::ISO);
        assert_eq!(screen.lines, along.lines, "{name}");
        assert_eq!(screen.ids, along.ids, "{name}");
        for y in 0..H {
            for x in 0..W {
                let class = along.lines[y * W + x];
                let drawn = drawn(&along, x, y);
                // Visible pixels drawn, pixels of no line not drawn.
                if class != 2 {
                    assert_eq!(drawn, class == 1, "{name} ({x}, {y})");
                }
            }
        }
    }
}

#[test]
fn the_screen_pattern_fails_the_along_the_edge_test() {
    // The test above can fail: the same hidden pixels dashed by the screen
    // pattern do not follow the edge's dashes.
    let cam = &views()[0].1;
    let f = frame(cam, Dashes::Screen);
    let px = hidden_along(&f, cam);
    let (checked, bad) = check(&px, 12.0, 3.0, 1.0);
    assert!(bad * 5 > checked, "{bad} of {checked}");
}

#[test]
fn the_dash_at_the_anchor_end_starts_at_the_anchor_as_the_camera_moves() {
    // The anchor A itself lies in front of the square: zoomed and moved so that
    // A's first dashes fall behind it, the first hidden pixels from A are on a
    // dash exactly as far from A in every frame (no crawl with the view).
    for (target, hh) in [
        ([-1.9, -1.0], 0.9),
        ([-1.93, -1.03], 0.85),
        ([-1.88, -0.98], 0.95),
    ] {
        let cam = view(target, hh, [0.0, 1.0, 0.0]);
        let f = frame(&cam, Dashes::ISO);
        let px = hidden_along(&f, &cam);
        let (checked, bad) = check(&px, 12.0, 3.0, 1.0);
        assert!(checked >= 20, "{target:?}: {checked}");
        assert_eq!(bad, 0, "{target:?}: {bad} of {checked}");
    }
}
