//! The flags of `report` (clap derive).

use std::path::PathBuf;

use clap::{ArgAction, Parser};

use super::values;
use crate::obj::workspace_root;

const AFTER_HELP: &str = "\
The binary re-executes itself as `report --child KEY` under callgrind (one frame a job).
Progress (`scene i of n`, `job i of n`, elapsed seconds) goes to stderr once a pass has
run 3 s.
exit status: 0 ok, 1 a check failed or a scene was skipped, 2 bad flags";

/// The flags of `report`.
#[derive(Debug, Parser)]
#[command(
    name = "report",
    about = "Speed against error: renders the report's scenes across sub-pixel bits, depth\n\
             bits, engine and band height, measures the error against the f64 reference and\n\
             the instructions per frame under callgrind, and checks `pbuffer::recommend`.",
    after_help = AFTER_HELP,
    disable_help_flag = true,
    disable_version_flag = true,
    args_override_self = true
)]
pub struct ReportFlags {
    /// `engines`: every engine on every scene, written to engines.md
    /// (without it: speed-vs-error.md and its two plots)
    #[arg(value_name = "engines", value_parser = values::engines_word, verbatim_doc_comment)]
    pub engines: Option<bool>,
    /// Smoke test: fewer scenes at 128x64, written to target/report-quick/
    #[arg(long, verbatim_doc_comment)]
    pub quick: bool,
    /// Callgrind jobs at a time
    #[arg(long, value_name = "N", value_parser = values::count, default_value = "2",
          allow_hyphen_values = true, verbatim_doc_comment)]
    pub jobs: usize,
    /// No instruction counts (no callgrind): the error columns only
    #[arg(long, verbatim_doc_comment)]
    pub no_counts: bool,
    /// Output directory (default report/, or target/report-quick/ with --quick,
    /// in the workspace root)
    #[arg(long, value_name = "DIR", value_parser = values::file, allow_hyphen_values = true,
          verbatim_doc_comment)]
    pub out: Option<PathBuf>,
    /// Print this help
    #[arg(short = 'h', long, action = ArgAction::SetTrue)]
    pub help: bool,
}

impl ReportFlags {
    /// Is it `report engines`?
    pub fn is_engines(&self) -> bool {
        self.engines == Some(true)
    }

    /// Are instruction counts measured (no `--no-counts`)?
    pub fn counts(&self) -> bool {
        !self.no_counts
    }

    /// The output directory: `--out`, else `report/` (`target/report-quick/` with
    /// `--quick`) in the workspace root.
    pub fn out_dir(&self) -> PathBuf {
        match &self.out {
            Some(d) => d.clone(),
            None if self.quick => workspace_root().join("target/report-quick"),
            None => workspace_root().join("report"),
        }
    }
}
