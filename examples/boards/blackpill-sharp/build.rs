//! Puts `memory.x` where cortex-m-rt's `link.x` finds it and bakes suzanne
//! (`../../embedded/models/suzanne.obj`, the QEMU examples' model) into `static`s in
//! flash with `pbuffer::bake` (her edge list, planarity bits and the fast engine's
//! constants), as `examples/embedded/build.rs` does: `$OUT_DIR/suzanne.rs` (`SUZANNE_...`).
use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("copy memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");

    pbuffer::bake::obj_to_rust(
        "../../embedded/models/suzanne.obj",
        "SUZANNE",
        out.join("suzanne.rs"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
}
