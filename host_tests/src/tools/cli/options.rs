//! Everything the command line says, with the defaults of an empty command line.

use std::path::PathBuf;

use crate::frame::{EngineSpec, ProjectionSpec, RenderSpec};
use crate::image::Look;
use crate::schemes::SchemeSpec;

/// Everything the command line says.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// The scene: an OBJ file or `scene:NAME` (none: the repository's models/suzanne.obj).
    pub scene: Option<PathBuf>,
    /// `--fit`: frame the whole model.
    pub fit: bool,
    /// `--eye X,Y,Z`.
    pub eye: Option<[f64; 3]>,
    /// `--target X,Y,Z`.
    pub target: Option<[f64; 3]>,
    /// `--up X,Y,Z`.
    pub up: Option<[f64; 3]>,
    /// `--fov DEG` or `--ortho HALF_HEIGHT`, the last given.
    pub projection: Option<ProjectionSpec>,
    /// `--near N`.
    pub near: Option<f64>,
    /// `--far F`.
    pub far: Option<f64>,
    /// The frame: size, crease, culling, mode, engine, sub-pixel and depth bits,
    /// band, pattern, dashes.
    pub spec: RenderSpec,
    /// Whether `--engine` was given (else the fast engine, or the code-fill engine
    /// for a flag only the exact engines have).
    pub engine_given: bool,
    /// Whether `--depth-bits` was given.
    pub depth_bits_given: bool,
    /// `--scheme`: the surface codes of the code-fill engine.
    pub scheme: SchemeSpec,
    /// `--band` as given (the default is the height, known after `--size`).
    pub band: Option<usize>,
    /// `--out FILE.png`: the picture.
    pub out: Option<PathBuf>,
    /// `--look L`: the colours of the PNG.
    pub look: Look,
    /// `--scale N`: PNG pixels per frame pixel.
    pub scale: usize,
    /// `--ids FILE.pgm`: the face-id image.
    pub ids: Option<PathBuf>,
    /// `--lines FILE.pgm`: the line-class image.
    pub lines: Option<PathBuf>,
    /// `--grey`: the anti-aliased grey picture (`host_tests::grey`).
    pub grey: Option<PathBuf>,
    /// `--dump-obj`: the posed union of a scene (or the model) as one OBJ.
    pub dump_obj: Option<PathBuf>,
    /// `--stats`: print the figures.
    pub stats: bool,
    /// `--hash`: print the frame's hash.
    pub hash: bool,
    /// `--pick X,Y`: the pixel to pick.
    pub pick: Option<(u16, u16)>,
    /// `-h`, `--help`: print the help and nothing else.
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
            spec: RenderSpec {
                engine: EngineSpec::Fast,
                ..RenderSpec::default()
            },
            engine_given: false,
            depth_bits_given: false,
            scheme: SchemeSpec::default(),
            band: None,
            out: None,
            look: Look::default(),
            scale: 3,
            ids: None,
            lines: None,
            grey: None,
            dump_obj: None,
            stats: false,
            hash: false,
            pick: None,
            help: false,
        }
    }
}
