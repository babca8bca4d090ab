//! Parsing and validation of the arguments into [`Options`].

use std::path::PathBuf;

use super::look::Look;
use super::options::Options;
use super::MAX_SIDE;
use crate::frame::{CullSpec, EngineSpec, ModeSpec, ProjectionSpec};
use crate::schemes::SchemeSpec;

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
                o.engine_given = true;
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
                o.depth_bits_given = true;
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
    // The default engine is the fast one; a flag only an exact engine has picks the
    // code-fill engine instead.
    if !o.engine_given
        && (o.scheme != SchemeSpec::Priority
            || o.spec.subpixel > pbuffer::render::FAST_MAX_SUBPIXEL_BITS
            || o.depth_bits_given)
    {
        o.spec.engine = EngineSpec::CodeFill;
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
