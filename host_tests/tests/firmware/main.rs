//! The firmware's code on the host: the smallest example's cube, the examples' frames
//! (whose hashes scripts/firmware compares with the M4's) and the driver examples' bus
//! bytes.
//!
//! One test binary; each module is one suite (`cargo test -p host_tests --test firmware
//! MODULE::`).

mod firmware_cube;
mod firmware_examples;
mod panel_bus;
