//! Everything the command line says, with the defaults of an empty command line.

use std::path::PathBuf;

use super::look::Look;
use crate::frame::{EngineSpec, ProjectionSpec, RenderSpec};
use crate::schemes::SchemeSpec;

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
    /// Whether `--engine` was given (else the fast engine, or the code-fill engine
    /// for a flag only the exact engines have).
    pub engine_given: bool,
    /// Whether `--depth-bits` was given.
    pub depth_bits_given: bool,
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
            stats: false,
            hash: false,
            pick: None,
            help: false,
        }
    }
}
