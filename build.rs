//! Picks the facet-row span kernels: the assembly ones (`src/render/engines/fast/facets/kernel.s`)
//! for targets with Thumb-2 and the DSP extension, the portable Rust twin elsewhere.
//!
//! The choice is made here, from the target's name, because a stable compiler does not
//! report Arm's `thumb2` and `dsp` target features to `cfg` (`rustc --print cfg --target
//! thumbv7em-none-eabihf` lists none), although every `thumbv7em` core (Cortex-M4, M7) has
//! them. Sets `cfg(pbuffer_dsp_kernels)` for `thumbv7em-*` targets and for any Arm target
//! whose reported features include both (a nightly build with `-C target-cpu=cortex-m33`,
//! say). `PBUFFER_NO_KERNELS=1` in the environment turns the kernels off (the twin
//! everywhere), to measure what they save.
use std::env;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(pbuffer_dsp_kernels)");
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-env-changed=PBUFFER_NO_KERNELS");

    let target = env::var("TARGET").unwrap_or_default();
    let arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let features = env::var("CARGO_CFG_TARGET_FEATURE").unwrap_or_default();
    let has = |f: &str| features.split(',').any(|x| x == f);
    let dsp = target.starts_with("thumbv7em") || (arch == "arm" && has("thumb2") && has("dsp"));
    let off = env::var_os("PBUFFER_NO_KERNELS").is_some_and(|v| !v.is_empty() && v != "0");
    if dsp && !off {
        println!("cargo::rustc-cfg=pbuffer_dsp_kernels");
    }
}
