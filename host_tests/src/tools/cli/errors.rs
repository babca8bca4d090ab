//! clap's errors as the one line the commands print: the flag first, then what is
//! wrong (`--size: `abc` is not WxH ...`), without clap's usage and tips.

use std::error::Error as _;

use clap::error::{ContextKind, ContextValue, ErrorKind};

use super::values::NEEDS_A_VALUE;

/// The flag an error is about: `--size` of clap's `--size <WxH>`, `--stats` of
/// `--stats=1`; empty when clap names none.
fn flag(e: &clap::Error) -> String {
    match e.get(ContextKind::InvalidArg) {
        Some(ContextValue::String(s)) => s.split([' ', '=']).next().unwrap_or_default().to_string(),
        _ => String::new(),
    }
}

fn context_str(e: &clap::Error, kind: ContextKind) -> Option<&str> {
    match e.get(kind) {
        Some(ContextValue::String(s)) => Some(s),
        _ => None,
    }
}

/// The first line of clap's own message, without its `error: ` prefix.
fn clap_line(e: &clap::Error) -> String {
    let text = e.to_string();
    let line = text.lines().next().unwrap_or_default();
    line.strip_prefix("error: ").unwrap_or(line).to_string()
}

/// One line for a parse error: the flag (a positional argument's value), then what is
/// wrong with it.
///
/// A value the flag's parser refuses gives the parser's message (see
/// [`super::values`]); a missing value `FLAG: needs a value`; an unknown flag
/// `FLAG: unknown flag (see --help)` (with clap's suggestion when it has one); a value
/// given to a flag that takes none `FLAG: takes no value`. Anything else is the first
/// line of clap's message.
pub fn one_line(e: &clap::Error) -> String {
    let mut flag = flag(e);
    if !flag.starts_with('-') {
        // A positional argument: name it by its value, not clap's placeholder.
        if let Some(v) = context_str(e, ContextKind::InvalidValue) {
            flag = v.to_string();
        }
    }
    match e.kind() {
        ErrorKind::ValueValidation => match e.source() {
            Some(why) => format!("{flag}: {why}"),
            None => clap_line(e),
        },
        ErrorKind::InvalidValue if context_str(e, ContextKind::InvalidValue) == Some("") => {
            format!("{flag}: {NEEDS_A_VALUE}")
        }
        ErrorKind::UnknownArgument => match context_str(e, ContextKind::SuggestedArg) {
            Some(s) => format!("{flag}: unknown flag (did you mean {s}? see --help)"),
            None => format!("{flag}: unknown flag (see --help)"),
        },
        ErrorKind::TooManyValues if flag.starts_with('-') => format!("{flag}: takes no value"),
        _ => clap_line(e),
    }
}
