//! Command-line flags of the `render`, `report` and `bench` commands: parsing and
//! validation only (no I/O), with clap (derive).
//!
//! Every error is one line that names the flag (or the argument) and what is wrong
//! ([`one_line`]); the commands print it and exit with status 2.
//! Flags take their value as the next argument or after `=` (`--size 128x64` or
//! `--size=128x64`); a repeated flag overrides the earlier one.
mod bench;
mod camera;
mod errors;
mod flags;
mod options;
mod parse;
mod report;
#[cfg(test)]
mod tests;
mod values;

use clap::CommandFactory;

pub use bench::BenchFlags;
pub use camera::check_camera;
pub use errors::one_line;
pub use flags::Flags;
pub use options::Options;
pub use parse::{parse_args, parse_flags};
pub use report::ReportFlags;
/// `--look NAME` parsed (lcd-white, lcd-green, lcd-blue, oled-white, oled-blue, paper).
pub use values::look as parse_look;

/// The `--help` text of the flags `T`: every flag with its values and default.
pub fn help_text<T: CommandFactory>() -> String {
    T::command().render_help().to_string()
}

/// The text `render --help` prints.
pub fn help() -> String {
    help_text::<Flags>()
}

/// Largest frame side accepted.
pub const MAX_SIDE: usize = 8192;
