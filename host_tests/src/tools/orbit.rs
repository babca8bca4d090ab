//! The `viewer` window's view state, kept free of SDL so that it is tested by the plain
//! `cargo test`: a camera orbiting the model (yaw, pitch, zoom), the mode and engine
//! switches, and the `render` flags that reproduce the view exactly, which is how the
//! screenshot check (`scripts/simulator-check`) asks `render` for the same frame.

use crate::fit::used_vertex_bounds;
use crate::frame::{
    CameraSpec, CullSpec, EngineSpec, MeshData, ModeSpec, ProjectionSpec, RenderSpec,
};
use crate::image::Look;

/// Degrees turned by one arrow key.
pub const STEP_DEG: f64 = 15.0;
/// Factor of one zoom key.
pub const ZOOM_STEP: f64 = 1.25;
/// Zoom range: far enough out to see the model small, and in until the eye nears it.
pub const ZOOM_RANGE: (f64, f64) = (0.25, 4.0);
/// Largest elevation of the eye above or below the target, degrees: at 90 the view
/// direction would be parallel to the up vector and the camera undefined.
pub const MAX_ELEVATION_DEG: f64 = 85.0;

/// The modes in the order the M key cycles them.
pub const MODES: [ModeSpec; 5] = [
    ModeSpec::Wireframe,
    ModeSpec::Hidden,
    ModeSpec::Dashed,
    ModeSpec::Surfaces,
    ModeSpec::SurfacesDashed,
];

/// A camera orbiting the target of a starting camera.
#[derive(Debug, Clone, PartialEq)]
pub struct Orbit {
    /// The starting camera (the `render` command's camera for the same flags).
    pub base: CameraSpec,
    /// Bounding-sphere centre and radius of the model, for the clip distances.
    pub centre: [f64; 3],
    pub radius: f64,
    /// Turn about the up vector, degrees (positive: the eye moves to the right).
    pub yaw_deg: f64,
    /// Added elevation of the eye, degrees, kept within +-[`MAX_ELEVATION_DEG`].
    pub pitch_deg: f64,
    /// Magnification: the eye's distance (perspective) or the half-height
    /// (orthographic) is divided by it.
    pub zoom: f64,
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn unit(a: [f64; 3]) -> [f64; 3] {
    scale(a, 1.0 / dot(a, a).sqrt())
}

impl Orbit {
    /// Starts at `base` (a camera that `cli::check_camera` accepted) looking at `mesh`.
    pub fn new(base: CameraSpec, mesh: &MeshData) -> Self {
        let (centre, radius) = used_vertex_bounds(mesh);
        Self {
            base,
            centre,
            radius,
            yaw_deg: 0.0,
            pitch_deg: 0.0,
            zoom: 1.0,
        }
    }

    /// Elevation of the starting eye above the target, degrees.
    fn base_elevation_deg(&self) -> f64 {
        let v = unit(sub(self.base.eye, self.base.target));
        dot(v, unit(self.base.up))
            .clamp(-1.0, 1.0)
            .asin()
            .to_degrees()
    }

    /// Turns the eye about the up vector.
    pub fn turn(&mut self, deg: f64) {
        self.yaw_deg = (self.yaw_deg + deg) % 360.0;
    }

    /// Raises (or lowers) the eye; stops short of looking along the up vector.
    pub fn tilt(&mut self, deg: f64) {
        let e0 = self.base_elevation_deg();
        let e = (e0 + self.pitch_deg + deg).clamp(-MAX_ELEVATION_DEG, MAX_ELEVATION_DEG);
        self.pitch_deg = e - e0;
    }

    /// Multiplies the magnification, within [`ZOOM_RANGE`].
    pub fn magnify(&mut self, factor: f64) {
        self.zoom = (self.zoom * factor).clamp(ZOOM_RANGE.0, ZOOM_RANGE.1);
    }

    /// Back to the starting camera.
    pub fn reset(&mut self) {
        (self.yaw_deg, self.pitch_deg, self.zoom) = (0.0, 0.0, 1.0);
    }

    /// The camera of the current view. At rest it is `base` itself, bit for bit, so the
    /// first frame is the one `render` draws for the same flags.
    pub fn camera(&self) -> CameraSpec {
        if self.yaw_deg == 0.0 && self.pitch_deg == 0.0 && self.zoom == 1.0 {
            return self.base;
        }
        let b = &self.base;
        let u = unit(b.up);
        let v = sub(b.eye, b.target);
        let dist = dot(v, v).sqrt();
        // The eye's horizontal direction (perpendicular to up), turned by the yaw, then
        // raised to the new elevation; `check_camera` ruled out v parallel to up.
        let h = unit(sub(v, scale(u, dot(v, u))));
        let (sy, cy) = self.yaw_deg.to_radians().sin_cos();
        let h = add(scale(h, cy), scale(cross(u, h), sy));
        let e = (self.base_elevation_deg() + self.pitch_deg).to_radians();
        let mut c = *b;
        let (dist, projection) = match b.projection {
            ProjectionSpec::Perspective { .. } => (dist / self.zoom, b.projection),
            ProjectionSpec::Orthographic { half_height } => (
                dist,
                ProjectionSpec::Orthographic {
                    half_height: half_height / self.zoom,
                },
            ),
        };
        let dir = add(scale(h, e.cos()), scale(u, e.sin()));
        c.eye = add(b.target, scale(dir, dist));
        c.projection = projection;
        // Clip distances around the model's bounding sphere as seen from the new eye,
        // with the quarter-radius margin of `fit`; near stays > 0 when the eye is inside.
        let dc = sub(self.centre, c.eye);
        let dc = dot(dc, dc).sqrt();
        let margin = 1.25 * self.radius;
        c.far = dc + margin;
        c.near = (dc - margin).max(0.01 * c.far);
        c
    }
}

/// Next mode in [`MODES`] after `m`.
pub fn next_mode(m: ModeSpec) -> ModeSpec {
    let i = MODES.iter().position(|&x| x == m).unwrap_or(0);
    MODES[(i + 1) % MODES.len()]
}

/// The next engine: code fill, code fill with bit-sliced rows, scan-line, Z-buffer.
pub fn other_engine(e: EngineSpec) -> EngineSpec {
    let all = EngineSpec::ALL;
    let at = all.iter().position(|&x| x == e).unwrap_or(0);
    all[(at + 1) % all.len()]
}

/// The `--mode` value of a mode.
pub fn mode_name(m: ModeSpec) -> &'static str {
    match m {
        ModeSpec::Wireframe => "wireframe",
        ModeSpec::Hidden => "hidden",
        ModeSpec::Dashed => "dashed",
        ModeSpec::Surfaces => "surfaces",
        ModeSpec::SurfacesDashed => "surfaces+dashed",
    }
}

/// The `--engine` value of an engine.
pub fn engine_name(e: EngineSpec) -> &'static str {
    e.name()
}

fn look_name(l: Look) -> &'static str {
    match l {
        Look::LcdWhite => "lcd-white",
        Look::LcdGreen => "lcd-green",
        Look::LcdBlue => "lcd-blue",
        Look::OledWhite => "oled-white",
        Look::OledBlue => "oled-blue",
        Look::Paper => "paper",
    }
}

/// `render` flags (without the scene) that give exactly this camera, settings and look:
/// f64 values are written with `{}`, the shortest text that parses back to the same bits.
pub fn render_flags(cam: &CameraSpec, spec: &RenderSpec, look: Look, scale: usize) -> Vec<String> {
    let v3 = |v: [f64; 3]| format!("{},{},{}", v[0], v[1], v[2]);
    let mut f: Vec<String> = vec![
        format!("--size={}x{}", spec.width, spec.height),
        format!("--eye={}", v3(cam.eye)),
        format!("--target={}", v3(cam.target)),
        format!("--up={}", v3(cam.up)),
        match cam.projection {
            ProjectionSpec::Perspective { fov_deg } => format!("--fov={fov_deg}"),
            ProjectionSpec::Orthographic { half_height } => format!("--ortho={half_height}"),
        },
        format!("--near={}", cam.near),
        format!("--far={}", cam.far),
        format!("--crease={}", spec.crease_deg),
        format!("--mode={}", mode_name(spec.mode)),
        format!("--engine={}", engine_name(spec.engine)),
        format!("--subpixel={}", spec.subpixel),
        format!("--depth-bits={}", spec.depth_bits),
        format!("--band={}", spec.band),
        format!("--pattern={}", spec.pattern),
        format!("--look={}", look_name(look)),
        format!("--scale={scale}"),
    ];
    f.push(
        match spec.cull {
            CullSpec::On => "--cull=on",
            CullSpec::Off => "--cull=off",
            CullSpec::Auto => "--cull=auto",
        }
        .into(),
    );
    f
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obj::builtin_cube;
    use crate::tools::cli::parse_args;

    fn start(args: &[&str]) -> (Orbit, RenderSpec, Look, usize) {
        let o = parse_args(args.iter().copied()).unwrap();
        let mesh = builtin_cube();
        (
            Orbit::new(o.camera(&mesh).unwrap(), &mesh),
            o.spec,
            o.look,
            o.scale,
        )
    }

    /// What `render` makes of the flags: its camera and settings.
    fn reparsed(
        orbit: &Orbit,
        spec: &RenderSpec,
        look: Look,
        s: usize,
    ) -> (CameraSpec, RenderSpec, Look, usize) {
        let o = parse_args(render_flags(&orbit.camera(), spec, look, s)).unwrap();
        (o.camera(&builtin_cube()).unwrap(), o.spec, o.look, o.scale)
    }

    #[test]
    fn at_rest_the_camera_is_the_starting_one() {
        let (orbit, ..) = start(&["--size", "128x64"]);
        assert_eq!(orbit.camera(), orbit.base);
    }

    #[test]
    fn flags_give_render_the_same_view() {
        for args in [
            &["--size", "400x240"][..],
            &[
                "--mode", "hidden", "--engine", "zbuffer", "--look", "paper", "--scale", "2",
            ],
            &[
                "--eye", "3,1,4", "--ortho", "1.5", "--cull", "off", "--band", "16",
            ],
        ] {
            let (mut orbit, mut spec, look, s) = start(args);
            for _ in 0..3 {
                let want = (orbit.camera(), spec.clone(), look, s);
                assert_eq!(reparsed(&orbit, &spec, look, s), want, "{args:?}");
                orbit.turn(STEP_DEG);
                orbit.tilt(-STEP_DEG);
                orbit.magnify(ZOOM_STEP);
                spec.mode = next_mode(spec.mode);
                spec.engine = other_engine(spec.engine);
            }
        }
    }

    #[test]
    fn orbit_keeps_distance_and_stops_before_the_pole() {
        let (mut orbit, ..) = start(&[]);
        let d0 = sub(orbit.base.eye, orbit.base.target);
        orbit.turn(90.0);
        let c = orbit.camera();
        let d = sub(c.eye, c.target);
        assert!((dot(d, d) - dot(d0, d0)).abs() < 1e-9 * dot(d0, d0));
        assert!(c.near > 0.0 && c.far > c.near);
        for _ in 0..20 {
            orbit.tilt(STEP_DEG);
        }
        let e = orbit.base_elevation_deg() + orbit.pitch_deg;
        assert!((e - MAX_ELEVATION_DEG).abs() < 1e-9);
        assert!(crate::tools::cli::check_camera(&orbit.camera()).is_ok());
        for _ in 0..20 {
            orbit.magnify(ZOOM_STEP);
        }
        assert_eq!(orbit.zoom, ZOOM_RANGE.1);
        orbit.reset();
        assert_eq!(orbit.camera(), orbit.base);
    }

    #[test]
    fn m_cycles_every_mode() {
        let mut m = ModeSpec::Dashed;
        let mut seen = vec![];
        for _ in 0..MODES.len() {
            m = next_mode(m);
            seen.push(m);
        }
        assert_eq!(m, ModeSpec::Dashed);
        assert!(MODES.iter().all(|x| seen.contains(x)));
    }
}
