//! The value parsers of the flags (clap `value_parser`s): each turns one argument into
//! its value or into what is wrong with it, without the flag's name, which
//! [`super::errors::one_line`] puts in front (`--size: ` + the message).
//!
//! Every parser refuses an empty value (`--out=`) with `needs a value`, as a missing
//! value is refused.

use std::path::PathBuf;

use super::MAX_SIDE;
use crate::frame::{CullSpec, EngineSpec, ModeSpec};
use crate::image::Look;
use crate::schemes::SchemeSpec;

/// What a parser says about an empty value.
pub const NEEDS_A_VALUE: &str = "needs a value";

fn given(s: &str) -> Result<&str, String> {
    if s.is_empty() {
        Err(NEEDS_A_VALUE.into())
    } else {
        Ok(s)
    }
}

/// A finite number (`inf` and `NaN` are refused).
pub fn finite(s: &str) -> Result<f64, String> {
    let s = given(s)?;
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("`{s}` is not a finite number")),
    }
}

/// `X,Y,Z`: three finite numbers separated by commas.
pub fn vec3(s: &str) -> Result<[f64; 3], String> {
    let s = given(s)?;
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("`{s}` is not X,Y,Z (three numbers, commas)"));
    }
    let mut v = [0.0; 3];
    for (k, p) in parts.iter().enumerate() {
        v[k] =
            finite(p).map_err(|_| format!("`{s}` is not X,Y,Z (`{p}` is not a finite number)"))?;
    }
    Ok(v)
}

fn int_in(s: &str, lo: usize, hi: usize) -> Result<usize, String> {
    let s = given(s)?;
    match s.trim().parse::<usize>() {
        Ok(n) if (lo..=hi).contains(&n) => Ok(n),
        _ => Err(format!("`{s}` is not an integer in {lo}..={hi}")),
    }
}

/// `--size WxH`, each side in `1..=MAX_SIDE`.
pub fn size(s: &str) -> Result<(usize, usize), String> {
    let s = given(s)?;
    let bad = || format!("`{s}` is not WxH with W and H in 1..={MAX_SIDE}");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w = int_in(w, 1, MAX_SIDE).map_err(|_| bad())?;
    let h = int_in(h, 1, MAX_SIDE).map_err(|_| bad())?;
    Ok((w, h))
}

/// `--fov DEG`: a finite angle in (0, 180) degrees.
pub fn fov(s: &str) -> Result<f64, String> {
    let f = finite(s)?;
    if f > 0.0 && f < 180.0 {
        Ok(f)
    } else {
        Err(format!("{s} is not in (0, 180) degrees"))
    }
}

/// `--ortho HALF_HEIGHT`: a finite half-height above 0.
pub fn half_height(s: &str) -> Result<f64, String> {
    let h = finite(s)?;
    if h > 0.0 {
        Ok(h)
    } else {
        Err(format!("the half-height {s} is not > 0"))
    }
}

/// `--crease DEG`: a finite angle in [0, 180] degrees.
pub fn crease(s: &str) -> Result<f64, String> {
    let c = finite(s)?;
    if (0.0..=180.0).contains(&c) {
        Ok(c)
    } else {
        Err(format!("{s} is not in [0, 180] degrees"))
    }
}

/// `--subpixel S`: sub-pixel bits in `0..=12`.
pub fn subpixel(s: &str) -> Result<u32, String> {
    // At most 12: the conversion cannot fail.
    int_in(s, 0, 12).map(|n| n as u32)
}

/// `--band ROWS`: rows per band in `1..=MAX_SIDE` (the height is checked later).
pub fn band(s: &str) -> Result<usize, String> {
    int_in(s, 1, MAX_SIDE)
}

/// `--scale N`: PNG pixels per frame pixel in `1..=16`.
pub fn scale(s: &str) -> Result<usize, String> {
    int_in(s, 1, 16)
}

/// `--depth-bits 16|32`.
pub fn depth_bits(s: &str) -> Result<u32, String> {
    match given(s)? {
        "16" => Ok(16),
        "32" => Ok(32),
        _ => Err(format!("`{s}` is not 16 or 32")),
    }
}

/// `--cull on|off|auto`.
pub fn cull(s: &str) -> Result<CullSpec, String> {
    match given(s)? {
        "on" => Ok(CullSpec::On),
        "off" => Ok(CullSpec::Off),
        "auto" => Ok(CullSpec::Auto),
        _ => Err(format!("`{s}` is not on, off or auto")),
    }
}

/// `--mode M`: one of the five drawing modes.
pub fn mode(s: &str) -> Result<ModeSpec, String> {
    match given(s)? {
        "wireframe" => Ok(ModeSpec::Wireframe),
        "hidden" => Ok(ModeSpec::Hidden),
        "dashed" => Ok(ModeSpec::Dashed),
        "surfaces" => Ok(ModeSpec::Surfaces),
        "surfaces+dashed" => Ok(ModeSpec::SurfacesDashed),
        _ => Err(format!(
            "`{s}` is not wireframe, hidden, dashed, surfaces or surfaces+dashed"
        )),
    }
}

/// `--engine E`: an engine by its name ([`EngineSpec::name`]).
pub fn engine(s: &str) -> Result<EngineSpec, String> {
    EngineSpec::by_name(given(s)?).ok_or_else(|| {
        let names: Vec<&str> = EngineSpec::ALL.iter().map(|e| e.name()).collect();
        format!("`{s}` is not one of {}", names.join(", "))
    })
}

/// `--scheme S`: a surface-code scheme by its name ([`SchemeSpec::name`]).
pub fn scheme(s: &str) -> Result<SchemeSpec, String> {
    SchemeSpec::by_name(given(s)?).ok_or_else(|| {
        let names: Vec<&str> = SchemeSpec::ALL.iter().map(|s| s.name()).collect();
        format!("`{s}` is not one of {}", names.join(", "))
    })
}

/// `--pattern NAME`: a hidden-line pattern the library knows (`pbuffer::Pattern::by_name`).
pub fn pattern(s: &str) -> Result<String, String> {
    match pbuffer::Pattern::by_name(given(s)?) {
        Some(_) => Ok(s.to_string()),
        None => Err(format!(
            "`{s}` is not a pattern (paper, checker, dots, long-dash, solid)"
        )),
    }
}

/// `--line-test segment|pixel`: how the fast engine finds hidden lines.
pub fn line_test(s: &str) -> Result<pbuffer::render::LineVisibility, String> {
    match given(s)? {
        "segment" => Ok(pbuffer::render::LineVisibility::BySegment),
        "pixel" => Ok(pbuffer::render::LineVisibility::ByPixel),
        _ => Err(format!("`{s}` is not segment or pixel")),
    }
}

/// `--dashes screen|iso|DASH,GAP`: how hidden lines are dashed.
pub fn dashes(s: &str) -> Result<pbuffer::Dashes, String> {
    match given(s)? {
        "screen" => Ok(pbuffer::Dashes::Screen),
        "iso" => Ok(pbuffer::Dashes::ISO),
        v => v
            .split_once(',')
            .and_then(|(d, g)| {
                let len = |t: &str| t.trim().parse::<u8>().ok().filter(|&n| n > 0);
                Some(pbuffer::Dashes::Along {
                    dash: len(d)?,
                    gap: len(g)?,
                })
            })
            .ok_or_else(|| {
                format!("`{s}` is not screen, iso or DASH,GAP (two lengths in pixels, 1..=255)")
            }),
    }
}

/// `--look L`: the colour scheme of the PNG.
pub fn look(s: &str) -> Result<Look, String> {
    match given(s)? {
        "lcd-white" => Ok(Look::LcdWhite),
        "lcd-green" => Ok(Look::LcdGreen),
        "lcd-blue" => Ok(Look::LcdBlue),
        "oled-white" => Ok(Look::OledWhite),
        "oled-blue" => Ok(Look::OledBlue),
        "paper" => Ok(Look::Paper),
        _ => Err(format!(
            "`{s}` is not lcd-white, lcd-green, lcd-blue, oled-white, oled-blue or paper"
        )),
    }
}

/// `--pick X,Y`: two pixel indices (the frame is checked later).
pub fn pixel(s: &str) -> Result<(u16, u16), String> {
    given(s)?
        .split_once(',')
        .and_then(|(x, y)| Some((x.trim().parse().ok()?, y.trim().parse().ok()?)))
        .ok_or_else(|| format!("`{s}` is not X,Y (two pixel indices)"))
}

/// An output file (`--out`, `--ids`, ...): any non-empty path.
pub fn file(s: &str) -> Result<PathBuf, String> {
    given(s).map(PathBuf::from)
}

/// A count (`--jobs N` of `report` and `bench`): a whole number, 0 included.
pub fn count(s: &str) -> Result<usize, String> {
    let s = given(s)?;
    s.trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a whole number"))
}

/// The scene argument: any path (an empty one fails later as unreadable).
pub fn scene(s: &str) -> Result<PathBuf, String> {
    Ok(PathBuf::from(s))
}

/// Any non-empty text (`bench --m4 FILE`).
pub fn text(s: &str) -> Result<String, String> {
    given(s).map(str::to_string)
}

/// `report`'s one word, `engines`.
pub fn engines_word(s: &str) -> Result<bool, String> {
    match s {
        "engines" => Ok(true),
        _ => Err("unknown argument: neither a flag nor `engines` (see --help)".into()),
    }
}
