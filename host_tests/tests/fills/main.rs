//! The 2-D span core against the f64 coverage reference: span and XOR paths, exact
//! pixels, watertight meshes, snapping error, hand-computed hard cases,
//! ASCII pictures.
//!
//! One test binary; each module is one suite (`cargo test -p host_tests --test fills
//! MODULE::`).

mod ascii;
mod hard_cases;
mod span_vs_reference;
mod support;
mod unsnapped;
mod watertight;
mod xor_vs_span;
