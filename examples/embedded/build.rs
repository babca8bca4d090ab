//! Puts the repository's memory.x where cortex-m-rt's link.x finds it, and bakes the
//! firmware's meshes into `static`s kept in flash with `pbuffer::bake` (the edge list
//! at 30 degrees, which faces are planar, the fast engine's per-mesh constants):
//! `models/suzanne.obj` into `$OUT_DIR/suzanne.rs` (`SUZANNE_...`), and the panel
//! bracket (`pbuffer_scenes::scenes::panel`) into `$OUT_DIR/panel.rs` (`PANEL_...`).
use std::{env, fs, path::PathBuf};

use pbuffer::mesh::Mesh;
use pbuffer_scenes::scenes::panel;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap());
    fs::copy("../../memory.x", out.join("memory.x")).expect("copy ../../memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    for f in ["../../memory.x", "build.rs"] {
        println!("cargo:rerun-if-changed={f}");
    }

    // defmt's sections (not loaded: nothing in flash or RAM) need defmt.x: the
    // `defmt` feature's, and sharp-memory-display's, which always depends on defmt.
    println!("cargo:rustc-link-arg=-Tdefmt.x");

    pbuffer::bake::obj_to_rust("models/suzanne.obj", "SUZANNE", out.join("suzanne.rs"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mesh = Mesh::new(&panel::VERTICES, &panel::INDICES, &panel::OFFSETS)
        .expect("the panel is a valid mesh");
    let source = pbuffer::bake::mesh_to_rust(&mesh, "PANEL", "pbuffer_scenes::scenes::panel")
        .unwrap_or_else(|e| panic!("{e}"));
    fs::write(out.join("panel.rs"), source).expect("write panel.rs");
}
