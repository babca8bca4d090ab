//! The smallest firmware example's scene, apart from the firmware (`main.rs`) so the
//! host builds it too: `host_tests/tests/firmware/firmware_cube.rs` takes this crate as a path
//! dependency and checks the cube's hash against the one the M4 checks.
#![no_std]
#![forbid(unsafe_code)]

pub mod cube;
