//! The tools: what turns the library's frames into commands, figures and windows. They
//! use the library part of this crate (references, inputs, drivers, metrics); nothing
//! in the library part uses them.
//!
//! - [`cli`]: the flags of `render`, `report` and `bench`;
//! - [`bench3d`]: `bench`'s 3-D section (instructions per frame, working RAM);
//! - [`report`]: `report`, speed against error;
//! - [`callgrind`]: instruction counts from valgrind (the harness of `bench` and `report`);
//! - [`progress`]: progress lines of the long passes on stderr;
//! - [`orbit`]: the `viewer` window's view state.

pub mod bench3d;
pub mod callgrind;
pub mod cli;
pub mod orbit;
pub mod progress;
pub mod report;
