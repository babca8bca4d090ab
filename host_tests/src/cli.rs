//! Command-line flags of the `render` command: parsing and validation only (no I/O).
//!
//! Every error is one line that names the flag (or the argument) and what is wrong.
//! Flags take their value as the next argument or after `=` (`--size 128x64` or
//! `--size=128x64`); a repeated flag overrides the earlier one.

use std::path::PathBuf;

use crate::fit::fit_camera;
use crate::frame::{
    CameraSpec, CullSpec, EngineSpec, MeshData, ModeSpec, ProjectionSpec, RenderSpec,
};
use crate::schemes::SchemeSpec;

/// The usage text printed by `--help` and after a usage error.
pub const USAGE: &str = "\
usage: render [SCENE.obj] [flags]
  SCENE.obj            Wavefront OBJ (v and f lines); without it: ../shared/models/suzanne.obj
                       (or a built-in cube), written to docs/render.png, stats printed;
                       scene:NAME renders a procedural test scene (cube, boxes, icosphere,
                       torus, gear, frame, cyclic, coplanar)
camera (default: --fit)
  --fit                frame the whole model from the front-right, above (perspective 30 deg)
  --eye X,Y,Z          eye position (excludes --fit); --target X,Y,Z (0,0,0); --up X,Y,Z (0,1,0)
  --fov DEG            perspective, vertical field of view in (0, 180) (default 45)
  --ortho HALF_HEIGHT  orthographic projection with this half-height
  --near N --far F     clip distances, 0 < near < far (default 0.1, 1000; fitted with --fit)
rendering
  --size WxH           frame size in pixels, 1..=8192 each (default 400x240)
  --crease DEG         crease angle in [0, 180] (default 30)
  --cull on|off|auto   back-face culling (default auto: on for closed meshes)
  --mode M             wireframe | hidden | dashed | surfaces | surfaces+dashed (default dashed)
  --engine E           codefill | codefill-crossings | scanline | zbuffer | painter | bsp |
                       warnock | raycast | newell (default codefill)
  --scheme S           with --engine codefill, paper 003's surface codes: priority (scheme 3:
                       weight-1 codes in a BSP depth order, the default) | combination
                       (scheme 1) | path (scheme 2): codes and colour table built for this
                       view's occlusion graph; a view without a consistent depth order is
                       refused with the condition it breaks (exit 1)
  --subpixel S         sub-pixel bits 0..=12 (default 4)
  --depth-bits 16|32   depth precision (default 32)
  --band ROWS          rows per depth band, 1..=height (default: the height)
  --pattern NAME       hidden-line pattern: paper | checker | dots | long-dash | solid (paper)
outputs
  --out FILE.png       the picture as a display shows it (default docs/render.png without SCENE)
  --look L             lcd-white (memory LCD, default) | lcd-green | lcd-blue | oled-white | oled-blue | paper
  --scale N            PNG pixels per frame pixel, 1..=16 (default 3; a faint pixel grid from 3 up)
  --ids FILE.pgm       P5 16-bit: 1 + visible face id, 0 = none (at most 65535 faces)
  --lines FILE.pgm     P5 8-bit: 0 none, 1 visible edge, 2 hidden edge
  --grey FILE.png      8-bit grey picture, face edges anti-aliased (Z-buffer engine, subpixel >= 2)
  --stats              print `name: value` figures (default when no other output is asked for)
  --hash               print `hash: HEX`, FNV-1a 64 of the packed 1-bpp frame
  --pick X,Y           print what is under pixel (X, Y): `pick_face: F` (0-based, or none) and
                       one `pick_edge: A B in_front K` per feature edge drawn through it
                       (vertex indices A B, K = faces in front of it there, 0 = visible)
exit status: 0 ok, 2 bad input (file, OBJ, flag or value), 1 rendering failed";

/// Largest frame side accepted.
pub const MAX_SIDE: usize = 8192;

/// The colour scheme of the PNG.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Look {
    #[default]
    LcdWhite,
    LcdGreen,
    LcdBlue,
    OledWhite,
    OledBlue,
    /// Black ink on white paper, no pixel grid.
    Paper,
}

impl Look {
    /// Off and on colours (RGB) of the look, shared by `render`'s PNG and the `viewer`
    /// window so that a screenshot of one can be compared with the other.
    pub fn colours(self) -> ([u8; 3], [u8; 3]) {
        match self {
            // A reflective memory LCD: grey-green glass, near-black pixels.
            Look::LcdWhite => ([214, 219, 205], [38, 42, 48]),
            Look::LcdGreen => ([120, 185, 50], [32, 32, 32]),
            Look::LcdBlue => ([70, 80, 230], [230, 230, 255]),
            Look::OledWhite => ([20, 20, 20], [255, 255, 255]),
            Look::OledBlue => ([0, 20, 40], [0, 210, 255]),
            Look::Paper => ([255, 255, 255], [0, 0, 0]),
        }
    }
}

/// Everything the command line says.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    pub scene: Option<PathBuf>,
    pub fit: bool,
    pub eye: Option<[f64; 3]>,
    pub target: Option<[f64; 3]>,
    pub up: Option<[f64; 3]>,
    pub projection: Option<ProjectionSpec>,
    pub near: Option<f64>,
    pub far: Option<f64>,
    pub spec: RenderSpec,
    /// `--scheme`: the surface codes of the code-fill engine.
    pub scheme: SchemeSpec,
    /// `--band` as given (the default is the height, known after `--size`).
    pub band: Option<usize>,
    pub out: Option<PathBuf>,
    pub look: Look,
    pub scale: usize,
    pub ids: Option<PathBuf>,
    pub lines: Option<PathBuf>,
    /// `--grey`: the anti-aliased grey picture (`host_tests::grey`).
    pub grey: Option<PathBuf>,
    pub stats: bool,
    pub hash: bool,
    /// `--pick X,Y`: the pixel to pick.
    pub pick: Option<(u16, u16)>,
    pub help: bool,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            scene: None,
            fit: false,
            eye: None,
            target: None,
            up: None,
            projection: None,
            near: None,
            far: None,
            spec: RenderSpec::default(),
            scheme: SchemeSpec::default(),
            band: None,
            out: None,
            look: Look::default(),
            scale: 3,
            ids: None,
            lines: None,
            grey: None,
            stats: false,
            hash: false,
            pick: None,
            help: false,
        }
    }
}

fn finite(flag: &str, s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("{flag}: `{s}` is not a finite number")),
    }
}

fn vec3(flag: &str, s: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!(
            "{flag}: `{s}` is not X,Y,Z (three numbers, commas)"
        ));
    }
    let mut v = [0.0; 3];
    for (k, p) in parts.iter().enumerate() {
        v[k] = finite(flag, p)
            .map_err(|_| format!("{flag}: `{s}` is not X,Y,Z (`{p}` is not a finite number)"))?;
    }
    Ok(v)
}

fn int_in(flag: &str, s: &str, lo: usize, hi: usize) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if (lo..=hi).contains(&n) => Ok(n),
        _ => Err(format!("{flag}: `{s}` is not an integer in {lo}..={hi}")),
    }
}

fn size(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("--size: `{s}` is not WxH with W and H in 1..={MAX_SIDE}");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w = int_in("--size", w, 1, MAX_SIDE).map_err(|_| bad())?;
    let h = int_in("--size", h, 1, MAX_SIDE).map_err(|_| bad())?;
    Ok((w, h))
}

/// Flags that take a value.
const VALUED: [&str; 24] = [
    "--size",
    "--eye",
    "--target",
    "--up",
    "--fov",
    "--ortho",
    "--near",
    "--far",
    "--crease",
    "--cull",
    "--mode",
    "--engine",
    "--scheme",
    "--subpixel",
    "--depth-bits",
    "--band",
    "--pattern",
    "--out",
    "--ids",
    "--lines",
    "--grey",
    "--look",
    "--scale",
    "--pick",
];

/// Parses the arguments (without the program name).
pub fn parse_args<I, S>(args: I) -> Result<Options, String>
where
    I: IntoIterator<Item = S>,
    S: AsRef<str>,
{
    let mut o = Options::default();
    let args: Vec<String> = args.into_iter().map(|s| s.as_ref().to_string()).collect();
    let mut i = 0;
    while i < args.len() {
        let arg = &args[i];
        i += 1;
        if arg == "--" {
            // Everything after is a scene path.
            for a in &args[i..] {
                set_scene(&mut o, a)?;
            }
            break;
        }
        if !arg.starts_with('-') || arg == "-" {
            set_scene(&mut o, arg)?;
            continue;
        }
        let (flag, inline) = match arg.split_once('=') {
            Some((f, v)) if f.starts_with("--") => (f, Some(v.to_string())),
            _ => (arg.as_str(), None),
        };
        if !VALUED.contains(&flag) {
            if inline.is_some() {
                return Err(format!("{flag}: takes no value"));
            }
            match flag {
                "--fit" => o.fit = true,
                "--stats" => o.stats = true,
                "--hash" => o.hash = true,
                "-h" | "--help" => o.help = true,
                _ => return Err(format!("{flag}: unknown flag (see --help)")),
            }
            continue;
        }
        let v = match inline {
            Some(v) => v,
            None => {
                let v = args
                    .get(i)
                    .ok_or_else(|| format!("{flag}: needs a value"))?
                    .clone();
                i += 1;
                v
            }
        };
        if v.is_empty() {
            return Err(format!("{flag}: needs a value"));
        }
        match flag {
            "--size" => (o.spec.width, o.spec.height) = size(&v)?,
            "--eye" => o.eye = Some(vec3(flag, &v)?),
            "--target" => o.target = Some(vec3(flag, &v)?),
            "--up" => o.up = Some(vec3(flag, &v)?),
            "--fov" => {
                let f = finite(flag, &v)?;
                if !(f > 0.0 && f < 180.0) {
                    return Err(format!("--fov: {v} is not in (0, 180) degrees"));
                }
                o.projection = Some(ProjectionSpec::Perspective { fov_deg: f });
            }
            "--ortho" => {
                let h = finite(flag, &v)?;
                if h <= 0.0 {
                    return Err(format!("--ortho: the half-height {v} is not > 0"));
                }
                o.projection = Some(ProjectionSpec::Orthographic { half_height: h });
            }
            "--near" => o.near = Some(finite(flag, &v)?),
            "--far" => o.far = Some(finite(flag, &v)?),
            "--crease" => {
                let c = finite(flag, &v)?;
                if !(0.0..=180.0).contains(&c) {
                    return Err(format!("--crease: {v} is not in [0, 180] degrees"));
                }
                o.spec.crease_deg = c;
            }
            "--cull" => {
                o.spec.cull = match v.as_str() {
                    "on" => CullSpec::On,
                    "off" => CullSpec::Off,
                    "auto" => CullSpec::Auto,
                    _ => return Err(format!("--cull: `{v}` is not on, off or auto")),
                }
            }
            "--mode" => {
                o.spec.mode = match v.as_str() {
                    "wireframe" => ModeSpec::Wireframe,
                    "hidden" => ModeSpec::Hidden,
                    "dashed" => ModeSpec::Dashed,
                    "surfaces" => ModeSpec::Surfaces,
                    "surfaces+dashed" => ModeSpec::SurfacesDashed,
                    _ => {
                        return Err(format!(
                            "--mode: `{v}` is not wireframe, hidden, dashed, surfaces or surfaces+dashed"
                        ))
                    }
                }
            }
            "--engine" => {
                o.spec.engine = EngineSpec::by_name(&v).ok_or_else(|| {
                    let names: Vec<&str> = EngineSpec::ALL.iter().map(|e| e.name()).collect();
                    format!("--engine: `{v}` is not one of {}", names.join(", "))
                })?
            }
            "--scheme" => {
                o.scheme = SchemeSpec::by_name(&v).ok_or_else(|| {
                    let names: Vec<&str> = SchemeSpec::ALL.iter().map(|s| s.name()).collect();
                    format!("--scheme: `{v}` is not one of {}", names.join(", "))
                })?
            }
            "--subpixel" => o.spec.subpixel = int_in(flag, &v, 0, 12)? as u32,
            "--depth-bits" => {
                o.spec.depth_bits = match v.as_str() {
                    "16" => 16,
                    "32" => 32,
                    _ => return Err(format!("--depth-bits: `{v}` is not 16 or 32")),
                }
            }
            "--band" => o.band = Some(int_in(flag, &v, 1, MAX_SIDE)?),
            "--pattern" => {
                if pbuffer::Pattern::by_name(&v).is_none() {
                    return Err(format!(
                        "--pattern: `{v}` is not a pattern (paper, checker, dots, long-dash, solid)"
                    ));
                }
                o.spec.pattern = v;
            }
            "--out" => o.out = Some(PathBuf::from(v)),
            "--ids" => o.ids = Some(PathBuf::from(v)),
            "--lines" => o.lines = Some(PathBuf::from(v)),
            "--grey" => o.grey = Some(PathBuf::from(v)),
            "--look" => {
                o.look = match v.as_str() {
                    "lcd-white" => Look::LcdWhite,
                    "lcd-green" => Look::LcdGreen,
                    "lcd-blue" => Look::LcdBlue,
                    "oled-white" => Look::OledWhite,
                    "oled-blue" => Look::OledBlue,
                    "paper" => Look::Paper,
                    _ => {
                        return Err(format!(
                            "--look: `{v}` is not lcd-white, lcd-green, lcd-blue, oled-white, oled-blue or paper"
                        ))
                    }
                }
            }
            "--scale" => o.scale = int_in(flag, &v, 1, 16)?,
            "--pick" => {
                let (x, y) = v
                    .split_once(',')
                    .and_then(|(x, y)| Some((x.trim().parse().ok()?, y.trim().parse().ok()?)))
                    .ok_or_else(|| format!("--pick: `{v}` is not X,Y (two pixel indices)"))?;
                o.pick = Some((x, y));
            }
            _ => unreachable!("every valued flag is handled"),
        }
    }
    // Checks across flags.
    if o.fit && o.eye.is_some() {
        return Err("--fit: excludes --eye (the fitted camera chooses the eye)".into());
    }
    if o.scheme != SchemeSpec::Priority && o.spec.engine != EngineSpec::CodeFill {
        return Err(format!(
            "--scheme: {} is drawn by the code-fill engine; --engine {} has no surface codes",
            o.scheme.name(),
            o.spec.engine.name()
        ));
    }
    match o.band {
        Some(b) if b > o.spec.height => {
            return Err(format!(
                "--band: {b} rows is more than the height {}",
                o.spec.height
            ))
        }
        Some(b) => o.spec.band = b,
        None => o.spec.band = o.spec.height,
    }
    if let Some((x, y)) = o.pick {
        if usize::from(x) >= o.spec.width || usize::from(y) >= o.spec.height {
            return Err(format!(
                "--pick: pixel ({x}, {y}) is outside the {}x{} frame",
                o.spec.width, o.spec.height
            ));
        }
    }
    if let Some(out) = &o.out {
        let ext = out.extension().and_then(|e| e.to_str()).unwrap_or("");
        if !ext.eq_ignore_ascii_case("png") {
            return Err(format!("--out: `{}` does not end in .png", out.display()));
        }
    }
    if let Some(grey) = &o.grey {
        let ext = grey.extension().and_then(|e| e.to_str()).unwrap_or("");
        if !ext.eq_ignore_ascii_case("png") {
            return Err(format!("--grey: `{}` does not end in .png", grey.display()));
        }
    }
    Ok(o)
}

fn set_scene(o: &mut Options, a: &str) -> Result<(), String> {
    if let Some(s) = &o.scene {
        return Err(format!(
            "{a}: a second scene (already have {}); one SCENE.obj at most",
            s.display()
        ));
    }
    o.scene = Some(PathBuf::from(a));
    Ok(())
}

impl Options {
    /// Is the camera fitted to the mesh (`--fit`, or no `--eye`)?
    pub fn fits(&self) -> bool {
        self.fit || self.eye.is_none()
    }

    /// The camera for `mesh`: fitted (then `--target`, `--up`, `--fov`/`--ortho`,
    /// `--near`, `--far` override the fitted values) or from the flags with the
    /// defaults of [`CameraSpec`]. Degenerate cameras are errors naming the flags.
    pub fn camera(&self, mesh: &MeshData) -> Result<CameraSpec, String> {
        let mut c = if self.fits() {
            fit_camera(mesh, self.spec.width, self.spec.height)
        } else {
            CameraSpec {
                eye: self.eye.unwrap_or(CameraSpec::default().eye),
                target: [0.0; 3],
                ..CameraSpec::default()
            }
        };
        if let Some(t) = self.target {
            c.target = t;
        }
        if let Some(u) = self.up {
            c.up = u;
        }
        if let Some(p) = self.projection {
            c.projection = p;
        }
        if let Some(n) = self.near {
            c.near = n;
        }
        if let Some(f) = self.far {
            c.far = f;
        }
        check_camera(&c)?;
        Ok(c)
    }
}

/// Rejects the degenerate cameras of CONVENTIONS.md with a message naming the flags.
pub fn check_camera(c: &CameraSpec) -> Result<(), String> {
    let d = [
        c.target[0] - c.eye[0],
        c.target[1] - c.eye[1],
        c.target[2] - c.eye[2],
    ];
    let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if len(d) == 0.0 {
        return Err("--eye/--target: the eye is at the target (no view direction)".into());
    }
    let x = [
        d[1] * c.up[2] - d[2] * c.up[1],
        d[2] * c.up[0] - d[0] * c.up[2],
        d[0] * c.up[1] - d[1] * c.up[0],
    ];
    if len(c.up) == 0.0 || len(x) <= 1e-12 * len(d) * len(c.up) {
        return Err("--up: the up vector is zero or parallel to the view direction".into());
    }
    if let ProjectionSpec::Perspective { fov_deg } = c.projection {
        if !(fov_deg > 0.0 && fov_deg < 180.0) {
            return Err(format!("--fov: {fov_deg} is not in (0, 180) degrees"));
        }
    }
    // Written so that NaN fails too.
    if c.near.is_nan() || c.near <= 0.0 {
        return Err(format!("--near: {} is not > 0", c.near));
    }
    if c.far.is_nan() || c.far <= c.near {
        return Err(format!(
            "--far: {} is not greater than near ({})",
            c.far, c.near
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(args: &[&str]) -> Result<Options, String> {
        parse_args(args.iter().copied())
    }

    fn cube() -> MeshData {
        MeshData {
            vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            faces: vec![vec![0, 1, 2]],
        }
    }

    #[test]
    fn defaults() {
        let o = p(&[]).unwrap();
        assert_eq!(o.spec, RenderSpec::default());
        assert!(o.fits() && o.scene.is_none() && !o.stats && !o.hash);
        assert_eq!(o.spec.band, 240);
    }

    #[test]
    fn all_flags() {
        let o = p(&[
            "m.obj",
            "--size",
            "128x64",
            "--eye=1,2,3",
            "--target",
            "0,0.5,0",
            "--up",
            "0,0,1",
            "--fov",
            "60",
            "--near",
            "0.5",
            "--far",
            "50",
            "--crease",
            "45",
            "--cull",
            "off",
            "--mode",
            "surfaces+dashed",
            "--engine",
            "zbuffer",
            "--subpixel",
            "8",
            "--depth-bits",
            "16",
            "--band",
            "8",
            "--pattern",
            "dots",
            "--out",
            "a.png",
            "--ids",
            "i.pgm",
            "--lines",
            "l.pgm",
            "--stats",
            "--hash",
            "--look",
            "oled-blue",
            "--scale",
            "2",
        ])
        .unwrap();
        assert_eq!(o.scene, Some(PathBuf::from("m.obj")));
        assert_eq!((o.spec.width, o.spec.height, o.spec.band), (128, 64, 8));
        assert_eq!(o.eye, Some([1.0, 2.0, 3.0]));
        assert_eq!(o.spec.cull, CullSpec::Off);
        assert_eq!(o.spec.mode, ModeSpec::SurfacesDashed);
        assert_eq!((o.spec.subpixel, o.spec.depth_bits), (8, 16));
        assert_eq!(o.spec.pattern, "dots");
        assert_eq!(o.scheme, SchemeSpec::Priority);
        assert!(o.stats && o.hash && !o.fits());
        let c = o.camera(&cube()).unwrap();
        assert_eq!(c.up, [0.0, 0.0, 1.0]);
        assert_eq!(c.projection, ProjectionSpec::Perspective { fov_deg: 60.0 });
        assert_eq!((c.near, c.far), (0.5, 50.0));
        let o = p(&["--scheme", "combination"]).unwrap();
        assert_eq!(o.scheme, SchemeSpec::Combination);
        let o = p(&["--engine=codefill", "--scheme=path"]).unwrap();
        assert_eq!(o.scheme, SchemeSpec::Path);
        let o = p(&["--ortho", "2", "--eye", "0,0,5"]).unwrap();
        let c = o.camera(&cube()).unwrap();
        assert_eq!(
            c.projection,
            ProjectionSpec::Orthographic { half_height: 2.0 }
        );
        assert_eq!(c.target, [0.0; 3]);
    }

    #[test]
    fn errors_name_the_flag() {
        for (args, flag) in [
            (&["--size", "0x10"][..], "--size"),
            (&["--size", "400"], "--size"),
            (&["--size", "9000x10"], "--size"),
            (&["--eye", "1,2"], "--eye"),
            (&["--eye", "1,nan,2"], "--eye"),
            (&["--target", "a,b,c"], "--target"),
            (&["--fov", "180"], "--fov"),
            (&["--fov", "inf"], "--fov"),
            (&["--ortho", "-1"], "--ortho"),
            (&["--near", "x"], "--near"),
            (&["--crease", "200"], "--crease"),
            (&["--cull", "maybe"], "--cull"),
            (&["--mode", "solid"], "--mode"),
            (&["--engine", "phong"], "--engine"),
            (&["--scheme", "gray"], "--scheme"),
            (&["--scheme", "path", "--engine", "zbuffer"], "--scheme"),
            (&["--subpixel", "13"], "--subpixel"),
            (&["--depth-bits", "24"], "--depth-bits"),
            (&["--band", "0"], "--band"),
            (&["--band", "300"], "--band"),
            (&["--scale", "0"], "--scale"),
            (&["--pick", "400,0"], "--pick"),
            (&["--pick", "3"], "--pick"),
            (&["--look", "crt"], "--look"),
            (&["--pattern", "zigzag"], "--pattern"),
            (&["--out", "a.jpg"], "--out"),
            (&["--grey", "a.pgm"], "--grey"),
            (&["--out"], "--out"),
            (&["--frobnicate"], "--frobnicate"),
            (&["--stats=1"], "--stats"),
            (&["--fit", "--eye", "1,1,1"], "--fit"),
            (&["a.obj", "b.obj"], "b.obj"),
        ] {
            let e = p(args).unwrap_err();
            assert!(e.starts_with(flag) && !e.contains('\n'), "{args:?}: {e}");
        }
    }

    #[test]
    fn degenerate_cameras() {
        let m = cube();
        for (args, flag) in [
            (&["--eye", "1,1,1", "--target", "1,1,1"][..], "--eye"),
            (&["--eye", "0,5,0"], "--up"),
            (&["--eye", "0,0,5", "--up", "0,0,0"], "--up"),
            (&["--eye", "0,0,5", "--near", "0"], "--near"),
            (&["--eye", "0,0,5", "--near", "2", "--far", "1"], "--far"),
            (&["--near", "-1"], "--near"),
        ] {
            let e = p(args).unwrap().camera(&m).unwrap_err();
            assert!(e.starts_with(flag), "{args:?}: {e}");
        }
    }
}
