//! Parsing and validation of the arguments into [`Options`]: clap reads the flags
//! ([`Flags`]), then the defaults and the checks across flags.

use std::path::Path;

use super::errors::one_line;
use super::flags::Flags;
use super::options::Options;
use crate::frame::{EngineSpec, ProjectionSpec, RenderSpec};
use crate::schemes::SchemeSpec;

/// Parses the arguments (without the program name) as the flags `T` of the command
/// `name`; an error is one line ([`one_line`]).
pub fn parse_flags<T, I, S>(name: &str, args: I) -> Result<T, String>
where
    T: clap::Parser,
    I: IntoIterator<Item = S>,
    S: AsRef<str>,
{
    let argv =
        std::iter::once(name.to_string()).chain(args.into_iter().map(|s| s.as_ref().to_string()));
    T::try_parse_from(argv).map_err(|e| one_line(&e))
}

/// Parses the arguments of `render` (without the program name).
pub fn parse_args<I, S>(args: I) -> Result<Options, String>
where
    I: IntoIterator<Item = S>,
    S: AsRef<str>,
{
    options(parse_flags::<Flags, _, _>("render", args)?)
}

/// The options of parsed flags: the defaults of what was not given, then the checks
/// across flags.
fn options(f: Flags) -> Result<Options, String> {
    if let (Some(first), Some(second)) = (&f.scene, f.more_scenes.first()) {
        return Err(format!(
            "{}: a second scene (already have {}); one SCENE.obj at most",
            second.display(),
            first.display()
        ));
    }
    let d = Options::default();
    let (width, height) = f.size.unwrap_or((d.spec.width, d.spec.height));
    let spec = RenderSpec {
        engine: f.engine.unwrap_or(d.spec.engine),
        width,
        height,
        crease_deg: f.crease.unwrap_or(d.spec.crease_deg),
        cull: f.cull.unwrap_or(d.spec.cull),
        mode: f.mode.unwrap_or(d.spec.mode),
        subpixel: f.subpixel.unwrap_or(d.spec.subpixel),
        depth_bits: f.depth_bits.unwrap_or(d.spec.depth_bits),
        // Set by `check` once the height is known.
        band: d.spec.band,
        pattern: f.pattern.unwrap_or(d.spec.pattern),
        dashes: f.dashes.unwrap_or(d.spec.dashes),
        lines: f.line_test.unwrap_or(d.spec.lines),
    };
    // The last of --fov and --ortho given wins (they override each other in clap).
    let projection = match (f.fov, f.ortho) {
        (Some(fov_deg), None) => Some(ProjectionSpec::Perspective { fov_deg }),
        (None, Some(half_height)) => Some(ProjectionSpec::Orthographic { half_height }),
        (None, None) => None,
        (Some(_), Some(_)) => unreachable!("--fov and --ortho override each other"),
    };
    check(Options {
        scene: f.scene,
        fit: f.fit,
        eye: f.eye,
        target: f.target,
        up: f.up,
        projection,
        near: f.near,
        far: f.far,
        spec,
        engine_given: f.engine.is_some(),
        depth_bits_given: f.depth_bits.is_some(),
        scheme: f.scheme.unwrap_or(d.scheme),
        band: f.band,
        out: f.out,
        look: f.look.unwrap_or(d.look),
        scale: f.scale.unwrap_or(d.scale),
        ids: f.ids,
        lines: f.lines,
        grey: f.grey,
        dump_obj: f.dump_obj,
        stats: f.stats,
        hash: f.hash,
        pick: f.pick,
        help: f.help,
    })
}

/// The default engine, the band, and the checks across flags.
fn check(mut o: Options) -> Result<Options, String> {
    // The default engine is the fast one; a flag only an exact engine has picks the
    // code-fill engine instead.
    if !o.engine_given
        && (o.scheme != SchemeSpec::Priority
            || o.spec.subpixel > pbuffer::render::FAST_MAX_SUBPIXEL_BITS
            || o.depth_bits_given)
    {
        o.spec.engine = EngineSpec::CodeFill;
    }
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
    if o.spec.dashes != pbuffer::Dashes::Screen && o.spec.engine != EngineSpec::Fast {
        return Err(format!(
            "--dashes: dashes along the edges are drawn by the fast engine; --engine {} \
             dashes by the screen pattern only",
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
    png_name("--out", o.out.as_deref())?;
    png_name("--grey", o.grey.as_deref())?;
    Ok(o)
}

/// A PNG output must end in `.png` (any case).
fn png_name(flag: &str, path: Option<&Path>) -> Result<(), String> {
    let Some(p) = path else { return Ok(()) };
    let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("");
    if ext.eq_ignore_ascii_case("png") {
        Ok(())
    } else {
        Err(format!("{flag}: `{}` does not end in .png", p.display()))
    }
}
