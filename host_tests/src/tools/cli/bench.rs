//! The flags of `bench` (clap derive).

use clap::{ArgAction, Parser};

use super::values;

const AFTER_HELP: &str = "\
Without --scene3d, --ram or --firmware: triangles and polygons filled into a 400x240
1-bpp framebuffer, pbuffer against embedded-graphics. Given more than one, --firmware
runs, else --ram, else --scene3d. The binary re-executes itself as `bench --child ID`
under callgrind (one measurement a job). Progress (`scene i of n`, `job i of n`, elapsed
seconds) goes to stderr once a pass has run 3 s.
exit status: 0 ok, 1 a check failed, 2 bad flags or nothing measured (no valgrind)";

/// The flags of `bench`.
#[derive(Debug, Parser)]
#[command(
    name = "bench",
    about = "Instruction counts (valgrind callgrind) of pbuffer's fills, 3-D scenes and \
             firmware frames.",
    after_help = AFTER_HELP,
    disable_help_flag = true,
    disable_version_flag = true,
    args_override_self = true
)]
pub struct BenchFlags {
    /// Markdown tables (as in BENCHMARKS.md) instead of aligned text
    #[arg(long, verbatim_doc_comment)]
    pub markdown: bool,
    /// The 3-D section: three models at two sizes with dashed hidden lines, the
    /// library's engines against the plain f32 P-buffer baseline
    #[arg(long, verbatim_doc_comment)]
    pub scene3d: bool,
    /// The 3-D scenes' working RAM part by part (native, no callgrind)
    #[arg(long, verbatim_doc_comment)]
    pub ram: bool,
    /// The firmware examples' frames on the host against the emulated Cortex-M4's
    /// counts of the same frames (after ./scripts/firmware)
    #[arg(long, verbatim_doc_comment)]
    pub firmware: bool,
    /// The Cortex-M4 counts of --firmware (default target/firmware-frames.txt)
    #[arg(long, value_name = "FILE", value_parser = values::text, allow_hyphen_values = true,
          verbatim_doc_comment)]
    pub m4: Option<String>,
    /// Callgrind jobs at a time (default: the number of cores)
    #[arg(long, value_name = "N", value_parser = values::count, allow_hyphen_values = true,
          verbatim_doc_comment)]
    pub jobs: Option<usize>,
    /// Print this help
    #[arg(short = 'h', long, action = ArgAction::SetTrue)]
    pub help: bool,
}
