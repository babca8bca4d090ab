//! Numerical stability and robustness: hard depth cases, random scenes and meshes
//! (fuzzing), hostile input to the pipeline, and no engine hanging or running far slower
//! than the Z-buffer.
//!
//! One test binary; each module is one suite (`cargo test -p host_tests --test robustness
//! MODULE::`).

mod capacity;
mod engine_time;
mod fuzz_codes;
mod fuzz_properties;
mod fuzzgen;
mod render_robustness;
mod sizing;
mod stab;
mod stability;
mod stability_depth;
