//! Host-side checks for pbuffer. Two parts, and imports go one way, from the tools to
//! the library part (`scripts/import-circles host_tests/src` checks it):
//!
//! **The library part**, what the tests judge frames with:
//! - references, written from CONVENTIONS.md and never from the fixed-point code:
//!   [`reference`] (2-D coverage, f64), [`reference3d`] (3-D frames by ray casting);
//! - inputs: [`frame`] (the contract: meshes, cameras and frames every part shares),
//!   [`obj`], [`shapes`] (procedural 3-D scenes), [`scenes`] (fixed 2-D scenes),
//!   [`random`] (the one PRNG and the random polygons and meshes), [`fit`] (a camera
//!   that frames a mesh), [`origin`] (a local origin for far scenes);
//! - drivers, the library run on the host: [`pipeline`] (the one render call),
//!   [`setup`] (the one scene set-up), [`engines`], [`fast`], [`bsp`], [`newell`],
//!   [`schemes`], [`grey`], [`pick`], [`firmware`] (the firmware's own frames),
//!   [`baseline`] (the plain f32 P-buffer), [`measure`] (the measured region);
//! - metrics: [`metrics`] (a frame against the reference), [`image`] (PNGs and hashes).
//!
//! **The tools** ([`tools`]): the command-line flags, `bench`'s 3-D section, `report`,
//! the callgrind harness, progress lines and the viewer's view state. The binaries
//! (`render`, `report`, `bench`, `polygons`, `instrument`, `viewer`,
//! `instrument-window`) are in `src/bin/`.

// The library part: references.
pub mod reference;
pub mod reference3d;

// Inputs.
pub mod fit;
pub mod frame;
pub mod obj;
pub mod origin;
pub mod random;
pub mod scenes;
pub mod shapes;

// Drivers.
pub mod baseline;
pub mod bsp;
pub mod engines;
pub mod fast;
pub mod firmware;
pub mod grey;
pub mod measure;
pub mod newell;
pub mod pick;
pub mod pipeline;
pub mod posed;
pub mod qi;
pub mod schemes;
pub mod setup;

// Metrics.
pub mod image;
pub mod metrics;

// The tools.
pub mod tools;
