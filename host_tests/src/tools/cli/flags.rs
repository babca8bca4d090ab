//! The flags of `render` as clap reads them (derive): one field per flag, its value
//! parsed and checked on its own ([`super::values`]); [`super::parse_args`] then applies
//! the defaults and the checks across flags to make the [`super::Options`].
//!
//! The doc comment of each field is its `--help` text, kept verbatim (line breaks as
//! written).

use std::path::PathBuf;

use clap::{ArgAction, Parser};

use super::values;
use crate::frame::{CullSpec, EngineSpec, ModeSpec};
use crate::image::Look;
use crate::schemes::SchemeSpec;

const CAMERA: &str = "Camera (default: --fit)";
const RENDERING: &str = "Rendering";
const OUTPUTS: &str = "Outputs";

/// The text after the flags in `--help`.
const AFTER_HELP: &str = "\
Values follow the flag as the next argument or after `=` (--size 128x64 or --size=128x64);
a repeated flag overrides the earlier one; every error is one line naming the flag.
exit status: 0 ok, 2 bad input (file, OBJ, flag or value), 1 rendering failed";

/// The flags of `render`, each value checked on its own.
#[derive(Debug, Parser)]
#[command(
    name = "render",
    about = "Draws a Wavefront OBJ model as a line drawing (dashed hidden lines by default)\n\
             through pbuffer's 3-D pipeline.",
    after_help = AFTER_HELP,
    disable_help_flag = true,
    disable_version_flag = true,
    args_override_self = true
)]
pub struct Flags {
    /// Wavefront OBJ (v and f lines); without it: the repository's
    /// models/suzanne.obj, written to target/render.png, stats printed;
    /// scene:NAME renders a procedural test scene (cube, boxes, icosphere,
    /// torus, gear, frame, cyclic, coplanar); a .scene file lists posed
    /// parts, one a line: PATH [tx ty tz [rx ry rz]] (path relative to the
    /// file; degrees about the part's origin, x then y then z, then moved)
    #[arg(value_name = "SCENE.obj", value_parser = values::scene, verbatim_doc_comment)]
    pub scene: Option<PathBuf>,
    /// Scenes after the first (refused with a message that names them).
    #[arg(value_name = "MORE", value_parser = values::scene, hide = true)]
    pub more_scenes: Vec<PathBuf>,

    /// Frame the whole model from the front-right, above
    /// (perspective 30 deg)
    #[arg(long, help_heading = CAMERA, verbatim_doc_comment)]
    pub fit: bool,
    /// Eye position (excludes --fit)
    #[arg(long, value_name = "X,Y,Z", value_parser = values::vec3, allow_hyphen_values = true,
          help_heading = CAMERA, verbatim_doc_comment)]
    pub eye: Option<[f64; 3]>,
    /// The point looked at (default 0,0,0)
    #[arg(long, value_name = "X,Y,Z", value_parser = values::vec3, allow_hyphen_values = true,
          help_heading = CAMERA, verbatim_doc_comment)]
    pub target: Option<[f64; 3]>,
    /// Up direction (default 0,1,0)
    #[arg(long, value_name = "X,Y,Z", value_parser = values::vec3, allow_hyphen_values = true,
          help_heading = CAMERA, verbatim_doc_comment)]
    pub up: Option<[f64; 3]>,
    /// Perspective, vertical field of view in (0, 180) (default 45)
    #[arg(long, value_name = "DEG", value_parser = values::fov, allow_hyphen_values = true,
          overrides_with = "ortho", help_heading = CAMERA, verbatim_doc_comment)]
    pub fov: Option<f64>,
    /// Orthographic projection with this half-height (> 0)
    #[arg(long, value_name = "HALF_HEIGHT", value_parser = values::half_height,
          allow_hyphen_values = true, overrides_with = "fov", help_heading = CAMERA, verbatim_doc_comment)]
    pub ortho: Option<f64>,
    /// Near clip distance, 0 < near < far
    /// (default 0.1; fitted with --fit)
    #[arg(long, value_name = "N", value_parser = values::finite, allow_hyphen_values = true,
          help_heading = CAMERA, verbatim_doc_comment)]
    pub near: Option<f64>,
    /// Far clip distance (default 1000; fitted with --fit)
    #[arg(long, value_name = "F", value_parser = values::finite, allow_hyphen_values = true,
          help_heading = CAMERA, verbatim_doc_comment)]
    pub far: Option<f64>,

    /// Frame size in pixels, 1..=8192 each (default 400x240)
    #[arg(long, value_name = "WxH", value_parser = values::size, allow_hyphen_values = true,
          help_heading = RENDERING, verbatim_doc_comment)]
    pub size: Option<(usize, usize)>,
    /// Crease angle in [0, 180] (default 30)
    #[arg(long, value_name = "DEG", value_parser = values::crease, allow_hyphen_values = true,
          help_heading = RENDERING, verbatim_doc_comment)]
    pub crease: Option<f64>,
    /// Back-face culling: on | off | auto
    /// (default auto: on for closed meshes)
    #[arg(long, value_name = "on|off|auto", value_parser = values::cull,
          allow_hyphen_values = true, help_heading = RENDERING, verbatim_doc_comment)]
    pub cull: Option<CullSpec>,
    /// wireframe | hidden | dashed | surfaces | surfaces+dashed
    /// (default dashed)
    #[arg(long, value_name = "M", value_parser = values::mode, allow_hyphen_values = true,
          help_heading = RENDERING, verbatim_doc_comment)]
    pub mode: Option<ModeSpec>,
    /// fast | codefill | codefill-crossings | scanline | zbuffer | painter |
    /// bsp | warnock | raycast | newell (default fast: 16-bit depth, lines
    /// tested at pixel centres; codefill when --scheme, --depth-bits or
    /// --subpixel above 6 asks for an exact engine)
    #[arg(long, value_name = "E", value_parser = values::engine, allow_hyphen_values = true,
          help_heading = RENDERING, verbatim_doc_comment)]
    pub engine: Option<EngineSpec>,
    /// With --engine codefill, paper 003's surface codes: priority (scheme 3:
    /// weight-1 codes in a BSP depth order, the default) | combination
    /// (scheme 1) | path (scheme 2): codes and colour table built for this
    /// view's occlusion graph; a view without a consistent depth order is
    /// refused with the condition it breaks (exit 1)
    #[arg(long, value_name = "S", value_parser = values::scheme, allow_hyphen_values = true,
          help_heading = RENDERING, verbatim_doc_comment)]
    pub scheme: Option<SchemeSpec>,
    /// Sub-pixel bits 0..=12 (default 4)
    #[arg(long, value_name = "S", value_parser = values::subpixel, allow_hyphen_values = true,
          help_heading = RENDERING, verbatim_doc_comment)]
    pub subpixel: Option<u32>,
    /// Depth precision: 16 | 32 (default 32)
    #[arg(long, value_name = "16|32", value_parser = values::depth_bits,
          allow_hyphen_values = true, help_heading = RENDERING, verbatim_doc_comment)]
    pub depth_bits: Option<u32>,
    /// Rows per depth band, 1..=height (default: the height)
    #[arg(long, value_name = "ROWS", value_parser = values::band, allow_hyphen_values = true,
          help_heading = RENDERING, verbatim_doc_comment)]
    pub band: Option<usize>,
    /// Hidden-line pattern: paper | checker | dots | long-dash | solid
    /// (default paper)
    #[arg(long, value_name = "NAME", value_parser = values::pattern, allow_hyphen_values = true,
          help_heading = RENDERING, verbatim_doc_comment)]
    pub pattern: Option<String>,
    /// How hidden lines are dashed: screen (by --pattern, the default) |
    /// iso (ISO 128: dashes of 12 px, gaps of 3, measured along each edge
    /// from the same end in every frame) | DASH,GAP (pixels along the edge,
    /// 1..=255 each); along the edges with the fast engine only
    #[arg(long, value_name = "screen|iso|DASH,GAP", value_parser = values::dashes,
          allow_hyphen_values = true, help_heading = RENDERING, verbatim_doc_comment)]
    pub dashes: Option<pbuffer::Dashes>,
    /// How the fast engine finds hidden lines in the line modes: pixel (every
    /// face filled into a row depth buffer, each line pixel tested against it:
    /// the default) | segment (by the segment, at object precision, no face
    /// filled)
    #[arg(long = "line-test", value_name = "segment|pixel", value_parser = values::line_test,
          help_heading = RENDERING, verbatim_doc_comment)]
    pub line_test: Option<pbuffer::render::LineVisibility>,

    /// The picture as a display shows it
    /// (default target/render.png without SCENE)
    #[arg(long, value_name = "FILE.png", value_parser = values::file, allow_hyphen_values = true,
          help_heading = OUTPUTS, verbatim_doc_comment)]
    pub out: Option<PathBuf>,
    /// lcd-white (memory LCD, default) | lcd-green | lcd-blue | oled-white |
    /// oled-blue | paper
    #[arg(long, value_name = "L", value_parser = values::look, allow_hyphen_values = true,
          help_heading = OUTPUTS, verbatim_doc_comment)]
    pub look: Option<Look>,
    /// PNG pixels per frame pixel, 1..=16
    /// (default 3; a faint pixel grid from 3 up)
    #[arg(long, value_name = "N", value_parser = values::scale, allow_hyphen_values = true,
          help_heading = OUTPUTS, verbatim_doc_comment)]
    pub scale: Option<usize>,
    /// P5 16-bit: 1 + visible face id, 0 = none (at most 65535 faces)
    #[arg(long, value_name = "FILE.pgm", value_parser = values::file, allow_hyphen_values = true,
          help_heading = OUTPUTS, verbatim_doc_comment)]
    pub ids: Option<PathBuf>,
    /// P5 8-bit: 0 none, 1 visible edge, 2 hidden edge
    #[arg(long, value_name = "FILE.pgm", value_parser = values::file, allow_hyphen_values = true,
          help_heading = OUTPUTS, verbatim_doc_comment)]
    pub lines: Option<PathBuf>,
    /// The scene's posed parts as one OBJ (world space,
    /// faces in part order: the union its frame means)
    #[arg(long = "dump-obj", value_name = "FILE.obj", value_parser = values::file,
          allow_hyphen_values = true, help_heading = OUTPUTS, verbatim_doc_comment)]
    pub dump_obj: Option<PathBuf>,
    /// 8-bit grey picture, face edges anti-aliased
    /// (Z-buffer engine, subpixel >= 2)
    #[arg(long, value_name = "FILE.png", value_parser = values::file, allow_hyphen_values = true,
          help_heading = OUTPUTS, verbatim_doc_comment)]
    pub grey: Option<PathBuf>,
    /// Print `name: value` figures
    /// (default when no other output is asked for)
    #[arg(long, help_heading = OUTPUTS, verbatim_doc_comment)]
    pub stats: bool,
    /// Print `hash: HEX`, FNV-1a 64 of the packed 1-bpp frame
    #[arg(long, help_heading = OUTPUTS, verbatim_doc_comment)]
    pub hash: bool,
    /// Print what is under pixel (X, Y): `pick_face: F` (0-based, or none) and
    /// one `pick_edge: A B in_front K` per feature edge drawn through it
    /// (vertex indices A B, K = faces in front of it there, 0 = visible)
    #[arg(long, value_name = "X,Y", value_parser = values::pixel, allow_hyphen_values = true,
          help_heading = OUTPUTS, verbatim_doc_comment)]
    pub pick: Option<(u16, u16)>,

    /// Print this help
    #[arg(short = 'h', long, action = ArgAction::SetTrue)]
    pub help: bool,
}
