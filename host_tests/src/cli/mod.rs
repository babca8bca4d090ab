//! Command-line flags of the `render` command: parsing and validation only (no I/O).
//!
//! Every error is one line that names the flag (or the argument) and what is wrong.
//! Flags take their value as the next argument or after `=` (`--size 128x64` or
//! `--size=128x64`); a repeated flag overrides the earlier one.
mod camera;
mod look;
mod options;
mod parse;
#[cfg(test)]
mod tests;

pub use camera::check_camera;
pub use look::Look;
pub use options::Options;
pub use parse::parse_args;

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
  --engine E           fast | codefill | codefill-crossings | scanline | zbuffer | painter |
                       bsp | warnock | raycast | newell (default fast: 16-bit depth, lines
                       tested at pixel centres; codefill when --scheme, --depth-bits or
                       --subpixel above 6 asks for an exact engine)
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
