//! The `report` command: speed against error. A fixed set of scenes rendered at
//! 400x240 and 128x64 across the knobs that trade speed for accuracy (sub-pixel bits
//! S, depth bits, engine, band height), one knob at a time from the default
//! settings plus a grid of S x depth bits on two scenes. For each combination:
//! error against the f64 reference ([`errors`]) and cost (instructions per frame
//! under callgrind, working RAM). Also the depth-precision table ([`depth`]) and the
//! check of [`pbuffer::recommend`] on every scene. Writes `report/speed-vs-error.md`
//! ([`write`]) and `report/speed-vs-error.svg` ([`plot`]).

pub mod depth;
pub mod engines;
pub mod errors;
pub mod plot;
pub mod run;
pub mod write;

use std::path::PathBuf;

use crate::frame::{EngineSpec, ModeSpec, RenderSpec};
use crate::obj::{load_obj, workspace_root};
use crate::shapes::{self, Framing, Scene};

/// Engines of the report: the spec, its name, whether it has a depth buffer, whether
/// it draws in bands of rows (the fast engine has no bands: its buffer is one row).
/// Adding an engine to the report is one line here.
pub const ENGINES: &[(EngineSpec, &str, bool, bool)] = &[
    (EngineSpec::CodeFill, "codefill", false, true),
    (
        EngineSpec::CodeFillCrossings,
        "codefill-crossings",
        false,
        true,
    ),
    (EngineSpec::Scanline, "scanline", false, true),
    (EngineSpec::ZBuffer, "zbuffer", true, true),
    (EngineSpec::Fast, "fast", false, false),
];

/// Index into [`ENGINES`] of the default engine (`render`'s: the fast engine).
pub const FAST: usize = 4;
/// Index into [`ENGINES`] of code fill in depth order, the exact engine whose S
/// sweep runs to 8.
pub const CODEFILL: usize = 0;
// The two indices name the engines they say, or the build fails.
const _: () = assert!(matches!(ENGINES[FAST].0, EngineSpec::Fast));
const _: () = assert!(matches!(ENGINES[CODEFILL].0, EngineSpec::CodeFill));

/// Depth bits the Z-buffer engine offers (`Depth` is implemented for `u16` and `u32`
/// only: there is no 24-bit sample).
pub const DEPTH_BITS: [u32; 2] = [16, 32];
/// Sub-pixel bits of the sweep (the fast engine stops at 6: `SubpixelTooFine` beyond).
pub const SUBPIXEL: [u32; 5] = [0, 2, 4, 6, 8];
/// The most sub-pixel bits the fast engine takes.
pub const FAST_MAX_SUBPIXEL: u32 = 6;
/// Frame sizes: a 400 x 240 memory LCD and a 128 x 64 OLED.
pub const SIZES: [(usize, usize); 2] = [(400, 240), (128, 64)];
/// Band height of the banded rows (the other is the full frame).
pub const BAND: usize = 8;

/// Procedural scenes of the report (`shapes::all_scenes` names).
pub const PROCEDURAL: [&str; 6] = ["boxes", "torus", "gear", "frame", "cyclic", "coplanar"];
/// Models from `../shared/models/`, skipped with a message when absent.
pub const MODELS: [&str; 7] = [
    "suzanne", "beetle", "woody", "teapot", "fandisk", "cow", "spot",
];
/// Scenes of the S x depth-bits grid.
pub const GRID_SCENES: [&str; 2] = ["coplanar", "suzanne"];
/// `--quick`: these scenes, one size, fewer combinations.
pub const QUICK_SCENES: [&str; 3] = ["boxes", "coplanar", "suzanne"];

/// One combination of the knobs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Config {
    /// Index into [`ENGINES`].
    pub engine: usize,
    pub subpixel: u32,
    /// Depth bits (engines with depth only).
    pub depth_bits: Option<u32>,
    /// Band rows (`None`: the full frame).
    pub band: Option<usize>,
}

impl Config {
    /// The default settings, `render`'s: the fast engine, S = 4 (it has no bands).
    pub const DEFAULT: Config = Config {
        engine: FAST,
        subpixel: 4,
        depth_bits: None,
        band: None,
    };

    pub fn engine_name(&self) -> &'static str {
        ENGINES[self.engine].1
    }

    /// `codefill S4`, `zbuffer S4 d16 b8`.
    pub fn label(&self) -> String {
        let mut s = format!("{} S{}", self.engine_name(), self.subpixel);
        if let Some(d) = self.depth_bits {
            s += &format!(" d{d}");
        }
        if let Some(b) = self.band {
            s += &format!(" b{b}");
        }
        s
    }

    /// The key of a child job: the label with `_` for spaces.
    pub fn key(&self) -> String {
        self.label().replace(' ', "_")
    }

    pub fn from_key(key: &str) -> Option<Self> {
        let mut parts = key.split('_');
        let name = parts.next()?;
        let engine = ENGINES.iter().position(|e| e.1 == name)?;
        let mut c = Config {
            engine,
            ..Config::DEFAULT
        };
        for p in parts {
            if let Some(v) = p.strip_prefix('S') {
                c.subpixel = v.parse().ok()?;
            } else if let Some(v) = p.strip_prefix('d') {
                c.depth_bits = Some(v.parse().ok()?);
            } else if let Some(v) = p.strip_prefix('b') {
                c.band = Some(v.parse().ok()?);
            } else {
                return None;
            }
        }
        Some(c)
    }

    /// The render settings of this combination at `size` (dashed hidden lines).
    pub fn spec(&self, (width, height): (usize, usize)) -> RenderSpec {
        RenderSpec {
            engine: ENGINES[self.engine].0,
            width,
            height,
            mode: ModeSpec::Dashed,
            subpixel: self.subpixel,
            depth_bits: self.depth_bits.unwrap_or(32),
            band: self.band.unwrap_or(height),
            ..RenderSpec::default()
        }
    }
}

/// The combinations for one scene: one knob at a time from [`Config::DEFAULT`]
/// (every S the fast engine takes, and every S of code fill in depth order, the exact
/// engine; every engine, at each depth for one with depth; the 8-row band for each
/// engine with bands), plus, on the grid scenes, every S x depth bits of the Z-buffer.
pub fn configs(scene: &str, quick: bool) -> Vec<Config> {
    let d = Config::DEFAULT;
    let mut v = Vec::new();
    let subpixel: &[u32] = if quick { &[0, 4, 8] } else { &SUBPIXEL };
    for &s in subpixel.iter().filter(|&&s| s <= FAST_MAX_SUBPIXEL) {
        v.push(Config { subpixel: s, ..d });
    }
    for &s in subpixel {
        v.push(Config {
            engine: CODEFILL,
            subpixel: s,
            ..d
        });
    }
    for (e, &(_, _, depth, banded)) in ENGINES.iter().enumerate() {
        let depths: Vec<Option<u32>> = if depth {
            DEPTH_BITS.iter().rev().map(|&b| Some(b)).collect()
        } else {
            vec![None]
        };
        for depth_bits in depths {
            let bands: &[Option<usize>] = if banded { &[None, Some(BAND)] } else { &[None] };
            for &band in bands {
                if quick && band.is_some() && e != CODEFILL {
                    continue;
                }
                v.push(Config {
                    engine: e,
                    depth_bits,
                    band,
                    ..d
                });
            }
        }
    }
    if GRID_SCENES.contains(&scene) && !quick {
        for (e, _) in ENGINES.iter().enumerate().filter(|x| x.1 .2) {
            for &s in &SUBPIXEL {
                for &b in &DEPTH_BITS {
                    v.push(Config {
                        engine: e,
                        subpixel: s,
                        depth_bits: Some(b),
                        band: None,
                    });
                }
            }
        }
    }
    let mut seen = std::collections::HashSet::new();
    v.retain(|c| seen.insert(*c));
    v
}

/// `../shared/models/` relative to the workspace root.
pub fn models_dir() -> PathBuf {
    workspace_root().join("../shared/models")
}

/// Loads scene `name` (procedural or model); `Err` with the reason when absent.
pub fn load_scene(name: &str) -> Result<Scene, String> {
    if let Some(s) = shapes::all_scenes().into_iter().find(|s| s.name == name) {
        return Ok(s);
    }
    let path = models_dir().join(format!("{name}.obj"));
    if !path.is_file() {
        return Err(format!("{} not found", path.display()));
    }
    Ok(Scene {
        name: name.into(),
        mesh: load_obj(&path)?,
        framing: Framing::Fit,
    })
}

/// The scene names of a run.
pub fn scene_names(quick: bool) -> Vec<&'static str> {
    if quick {
        QUICK_SCENES.to_vec()
    } else {
        PROCEDURAL.iter().chain(MODELS.iter()).copied().collect()
    }
}

/// The sizes of a run.
pub fn sizes(quick: bool) -> Vec<(usize, usize)> {
    if quick {
        vec![SIZES[1]]
    } else {
        SIZES.to_vec()
    }
}

/// A child job's key: `scene|WxH|config`.
pub fn job_key(scene: &str, (w, h): (usize, usize), c: &Config) -> String {
    format!("{scene}|{w}x{h}|{}", c.key())
}

/// Runs child job `key` (inside callgrind): renders the frame; returns the pixels
/// set (printed as `pixels=N` for the harness).
pub fn child(key: &str) -> Result<usize, String> {
    if key.starts_with("engines|") {
        return engines::child(key);
    }
    let mut parts = key.split('|');
    let (Some(scene), Some(size), Some(config)) = (parts.next(), parts.next(), parts.next()) else {
        return Err(format!("bad job key {key:?}"));
    };
    let (w, h) = size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .ok_or_else(|| format!("bad size in {key:?}"))?;
    let config = Config::from_key(config).ok_or_else(|| format!("bad config in {key:?}"))?;
    let scene = load_scene(scene)?;
    let frame = crate::pipeline::render_frame(
        &scene.mesh,
        &scene.camera(w, h, false),
        &config.spec((w, h)),
    )?;
    Ok(crate::image::count_set(&frame.packed, w, h))
}
