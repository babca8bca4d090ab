//! The firmware examples' frames, written once: the scenes and their cameras
//! ([`scenes`]), the two on-chip baselines ([`painter`], [`plain`]), the
//! instrument-panel demo ([`instrument`]), the robot-arm demo ([`arm`]) and the
//! cost of posed instances ([`instances`]) with their procedural parts ([`shapes`]), the frames on panel driver crates
//! (`panels`, feature `panels`) and the OBJ converter (`obj`, feature `std`).
//!
//! `no_std`. The firmware (`examples/embedded`) and the host's checks (`host_tests`)
//! both take this crate as a path dependency, so the host draws the firmware's frames
//! with the very same code, and `examples/embedded/build.rs` converts suzanne with the
//! same `obj` the host tests parse her with.
#![no_std]
#![forbid(unsafe_code)]
// The buffers have a `const fn new` for `static`s; a `Default` would build them on the stack.
#![allow(clippy::new_without_default)]

#[cfg(feature = "std")]
extern crate std;

pub mod arm;
pub mod instances;
pub mod instrument;
#[cfg(feature = "std")]
pub mod obj;
pub mod painter;
#[cfg(feature = "panels")]
pub mod panels;
pub mod plain;
pub mod scenes;
pub mod shapes;
