//! Shared helpers of the numerical stability suite (`stability*.rs`): render a scene
//! with every engine, compare it with the f64 reference, and print one frame hash per
//! rendering so that `scripts/debug-release-check` can diff a debug (overflow checks
//! on) run against a release run.
#![allow(dead_code)] // each stability file uses a different subset

use host_tests::frame::{
    CameraSpec, CullSpec, EngineSpec, Frame, MeshData, ModeSpec, ProjectionSpec, RenderSpec,
};
use host_tests::metrics::{compare_lines, compare_surfaces, SurfaceMetrics};
use host_tests::pipeline::render_frame;
use host_tests::reference3d::{reference_frame, RefFrame};

/// A world-space segment.
pub type Segment = ([f64; 3], [f64; 3]);

/// One way of rendering: engine, band height (0 = the full frame), depth bits.
#[derive(Clone, Copy, Debug)]
pub struct Config {
    pub engine: EngineSpec,
    pub band: usize,
    pub depth_bits: u32,
}

impl Config {
    pub fn label(&self) -> String {
        let engine = self.engine.name();
        let band = if self.band == 0 {
            "full".to_string()
        } else {
            format!("band{}", self.band)
        };
        format!("{engine}-{band}-d{}", self.depth_bits)
    }
}

/// Code fill (both row representations), scan-line and the 32-bit Z-buffer: the engines that
/// must match the reference on every case of the suite.
pub const EXACT: [Config; 5] = [
    Config {
        engine: EngineSpec::CodeFill,
        band: 0,
        depth_bits: 32,
    },
    Config {
        engine: EngineSpec::Scanline,
        band: 0,
        depth_bits: 32,
    },
    Config {
        engine: EngineSpec::CodeFillCrossings,
        band: 8,
        depth_bits: 32,
    },
    Config {
        engine: EngineSpec::ZBuffer,
        band: 0,
        depth_bits: 32,
    },
    Config {
        engine: EngineSpec::ZBuffer,
        band: 8,
        depth_bits: 32,
    },
];

/// The 16-bit Z-buffer in bands, checked apart where its depth precision matters.
pub const Z16: Config = Config {
    engine: EngineSpec::ZBuffer,
    band: 8,
    depth_bits: 16,
};

/// The fast engine (16-bit depth in its row; approximate, issue 23), full frame.
pub const FAST: Config = Config {
    engine: EngineSpec::Fast,
    band: 0,
    depth_bits: 16,
};

/// Warnock's subdivision and the ray caster, full frame, 32-bit nearness.
pub const SUBDIVIDING: [Config; 2] = [
    Config {
        engine: EngineSpec::Warnock,
        band: 0,
        depth_bits: 32,
    },
    Config {
        engine: EngineSpec::Raycast,
        band: 0,
        depth_bits: 32,
    },
];

/// Every configuration.
pub fn all() -> Vec<Config> {
    let mut v = EXACT.to_vec();
    v.push(Z16);
    v
}

/// FNV-1a over the ids, the lines and the packed picture: equal hashes, equal frames.
pub fn hash(frame: &Frame) -> u64 {
    let ids = frame.ids.iter().flat_map(|id| id.to_le_bytes());
    let bytes: Vec<u8> = ids
        .chain(frame.lines.iter().copied())
        .chain(frame.packed.iter().copied())
        .collect();
    host_tests::image::fnv1a64(&bytes)
}

/// A render spec of `w x h` at S = 4 in `mode` for `config`.
pub fn spec(config: Config, mode: ModeSpec, w: usize, h: usize) -> RenderSpec {
    RenderSpec {
        engine: config.engine,
        width: w,
        height: h,
        band: if config.band == 0 { h } else { config.band },
        depth_bits: config.depth_bits,
        subpixel: 4,
        mode,
        cull: CullSpec::Off,
        ..RenderSpec::default()
    }
}

/// Renders with the library twice (the two runs must give the same frame) and prints
/// the frame's hash as `HASH <case> <config> <mode> <hash>` for the debug/release diff.
pub fn render(case: &str, mesh: &MeshData, cam: &CameraSpec, spec: &RenderSpec) -> Frame {
    let config = Config {
        engine: spec.engine,
        band: if spec.band == spec.height {
            0
        } else {
            spec.band
        },
        depth_bits: spec.depth_bits,
    };
    let label = format!("{case} {} {:?}", config.label(), spec.mode);
    let frame = render_frame(mesh, cam, spec).unwrap_or_else(|e| panic!("{label}: {e}"));
    let again = render_frame(mesh, cam, spec).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert!(
        frame.ids == again.ids && frame.packed == again.packed,
        "{label}: two runs differ"
    );
    println!("HASH {label} {:016x}", hash(&frame));
    frame
}

/// The reference of a `w x h` frame.
pub fn reference(mesh: &MeshData, cam: &CameraSpec, w: usize, h: usize) -> RefFrame {
    let base = spec(EXACT[0], ModeSpec::Surfaces, w, h);
    reference_frame(mesh, cam, &base).expect("reference")
}

/// The surface metrics of `config` against `rf`.
pub fn surfaces(
    case: &str,
    mesh: &MeshData,
    cam: &CameraSpec,
    rf: &RefFrame,
    config: Config,
) -> (Frame, SurfaceMetrics) {
    let s = spec(config, ModeSpec::Surfaces, rf.width, rf.height);
    let frame = render(case, mesh, cam, &s);
    let m = compare_surfaces(&frame, rf);
    (frame, m)
}

/// Asserts (a)-(d) of the surface metrics are 0: no holes, no wrong faces, no
/// depth-order errors, no face-id differences away from edges.
pub fn assert_exact(what: &str, m: &SurfaceMetrics) {
    let counts = [m.holes, m.wrong_faces, m.depth_order, m.far_diffs];
    assert_eq!(
        counts, [0; 4],
        "{what}: [holes, wrong faces, depth-order errors, far id diffs] (first at {:?})",
        m.first
    );
}

/// The whole check of a case: for every configuration in `configs`, surfaces match
/// the reference exactly ((a)-(d) = 0), the scan-line engine and the 32-bit Z-buffer
/// give the same ids pixel for pixel, and so do the two row representations of code
/// fill in depth order, and the dashed line
/// drawing renders (hash printed) within the line limits of the metrics. Returns the
/// library's surface frame of the first configuration and the reference.
pub fn check_case(
    case: &str,
    mesh: &MeshData,
    cam: &CameraSpec,
    w: usize,
    h: usize,
    configs: &[Config],
) -> (Frame, RefFrame) {
    check(case, mesh, cam, (w, h), configs, &[], true)
}

/// `check_case` with two exceptions: face-id differences within 1 px of one of
/// `crossings` (world segments where faces interpenetrate: the reference's edges do
/// not include them) are allowed, and lines are checked only when `lines`.
pub fn check(
    case: &str,
    mesh: &MeshData,
    cam: &CameraSpec,
    (w, h): (usize, usize),
    configs: &[Config],
    crossings: &[Segment],
    lines: bool,
) -> (Frame, RefFrame) {
    let rf = reference(mesh, cam, w, h);
    assert!(
        rf.ids.iter().any(|&i| i != 0),
        "{case}: the reference must see something, or the case tests nothing"
    );
    let view = host_tests::reference3d::Camera::new(cam, w, h).expect("camera");
    let segments: Vec<_> = crossings
        .iter()
        .map(|&(a, b)| (view.project(view.to_eye(a)), view.project(view.to_eye(b))))
        .collect();
    let near = host_tests::metrics::near_edge_mask(&rf, 1.0);
    let mut first: Option<Frame> = None;
    let mut first_ordered: Option<(Frame, String)> = None;
    let mut first_compared: Option<(Frame, String)> = None;
    for &config in configs {
        let (frame, mut m) = surfaces(case, mesh, cam, &rf, config);
        if !segments.is_empty() {
            for k in (0..frame.ids.len()).filter(|&k| frame.ids[k] != rf.ids[k] && !near[k]) {
                let p = ((k % w) as f64 + 0.5, (k / w) as f64 + 0.5);
                let d = segments
                    .iter()
                    .map(|&(a, b)| host_tests::reference::distance_to_segment(p, a, b))
                    .fold(f64::INFINITY, f64::min);
                if d <= 1.0 {
                    m.far_diffs -= 1;
                }
            }
        }
        assert_exact(&format!("{case} {}", config.label()), &m);
        // Frames that must be the same pixel for pixel: the engines comparing depths
        // (scan-line, 32-bit Z-buffer) with each other, and the depth-order engines
        // (both row representations) with each other.
        let ordered = matches!(
            config.engine,
            EngineSpec::CodeFill | EngineSpec::CodeFillCrossings
        );
        let same = if ordered {
            &mut first_ordered
        } else {
            &mut first_compared
        };
        if let Some((f, label)) = same.as_ref() {
            if config.depth_bits == 32 {
                assert!(
                    f.ids == frame.ids,
                    "{case}: {} differs from {label} ({} pixels)",
                    config.label(),
                    f.ids.iter().zip(&frame.ids).filter(|(a, b)| a != b).count()
                );
            }
        } else {
            *same = Some((frame.clone(), config.label()));
        }
        if first.is_none() {
            first = Some(frame);
        }
        let dashed = render(case, mesh, cam, &spec(config, ModeSpec::Dashed, w, h));
        let l = compare_lines(&dashed, &rf);
        assert!(
            !lines || l.misclassified_fraction() <= host_tests::metrics::MISCLASSIFIED_LIMIT,
            "{case} {}: {} of {} line pixels misclassified (first at {:?})",
            config.label(),
            l.misclassified,
            l.line_pixels,
            l.first_misclassified
        );
        // Line length missing (issue 24, item 5: never asserted here before).
        let limit = host_tests::metrics::MISSING_LIMIT;
        assert!(
            !lines
                || (l.visible_missing_fraction() <= limit && l.hidden_missing_fraction() <= limit),
            "{case} {}: visible {:.1} of {:.1} and hidden {:.1} of {:.1} missing (first at {:?}, {:?})",
            config.label(),
            l.visible_missing,
            l.visible_len,
            l.hidden_missing,
            l.hidden_len,
            l.first_visible_missing,
            l.first_hidden_missing
        );
    }
    (first.expect("at least one configuration"), rf)
}

/// Faces (1 + index) seen in a frame's ids, and how many pixels each.
pub fn face_pixels(frame: &Frame) -> std::collections::BTreeMap<u32, usize> {
    let mut m = std::collections::BTreeMap::new();
    for &id in &frame.ids {
        if id != 0 {
            *m.entry(id).or_insert(0) += 1;
        }
    }
    m
}

/// An orthographic camera looking down -Z from (0, 0, 10) at the origin with
/// half-height `half`: at `n x n` pixels, world (x, y) is screen
/// ((x / half + 1) n / 2, (1 - y / half) n / 2).
pub fn ortho_front(half: f64) -> CameraSpec {
    CameraSpec {
        eye: [0.0, 0.0, 10.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        projection: ProjectionSpec::Orthographic { half_height: half },
        near: 1.0,
        far: 100.0,
    }
}

/// A perspective camera at `eye` looking at `target`, fov 60, near/far as given.
pub fn persp(eye: [f64; 3], target: [f64; 3], near: f64, far: f64) -> CameraSpec {
    CameraSpec {
        eye,
        target,
        up: [0.0, 1.0, 0.0],
        projection: ProjectionSpec::Perspective { fov_deg: 60.0 },
        near,
        far,
    }
}

/// A mesh from vertex positions and faces.
pub fn mesh(vertices: &[[f64; 3]], faces: &[&[u32]]) -> MeshData {
    MeshData {
        vertices: vertices.to_vec(),
        faces: faces.iter().map(|f| f.to_vec()).collect(),
    }
}

/// Appends a quad (counter-clockwise seen from +Z when `a, b, c, d` go that way).
pub fn quad(m: &mut MeshData, corners: [[f64; 3]; 4]) {
    let base = m.vertices.len() as u32;
    m.vertices.extend_from_slice(&corners);
    m.faces.push((base..base + 4).collect());
}

/// A backdrop quad at z = `z` covering [-s, s]^2, facing +Z.
pub fn backdrop(m: &mut MeshData, s: f64, z: f64) {
    quad(m, [[-s, -s, z], [s, -s, z], [s, s, z], [-s, s, z]]);
}

/// Rounds `v` to the library's per-frame position grid for a scene whose largest
/// coordinate (eye included) is `magnitude`: 26 bits of `i32` hold the largest,
/// so the step is 2^(ceil(log2 magnitude) - 26) world units.
pub fn frame_grid(v: f64, magnitude: f64) -> f64 {
    let step = 2f64.powi(magnitude.log2().ceil() as i32 - 26);
    (v / step).round() * step
}
