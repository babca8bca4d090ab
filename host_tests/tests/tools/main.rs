//! The host tools and the library's advice: the `render` command's outputs and flags,
//! the repository's arm scene,
//! `recommend`, the engines table of `report`, and the documents that describe them.
//!
//! One test binary; each module is one suite (`cargo test -p host_tests --test tools
//! MODULE::`).

mod arm_scene;
mod documents;
mod engines_table;
mod fit_library;
mod recommend;
mod render_cli;
