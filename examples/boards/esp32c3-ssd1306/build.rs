//! Bakes the instrument demo's part, the panel bracket (`pbuffer_scenes::scenes::panel`),
//! into `static`s in flash with `pbuffer::bake` (its edge list, planarity bits and the fast
//! engine's constants), as `examples/embedded/build.rs` does: `$OUT_DIR/panel.rs`
//! (`PANEL_...`). esp-hal brings the memory layout (`linkall.x`).
use std::{env, fs, path::PathBuf};

use pbuffer::mesh::Mesh;
use pbuffer_scenes::scenes::panel;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    println!("cargo:rerun-if-changed=build.rs");
    let mesh = Mesh::new(&panel::VERTICES, &panel::INDICES, &panel::OFFSETS)
        .expect("the panel is a valid mesh");
    let source = pbuffer::bake::mesh_to_rust(&mesh, "PANEL", "pbuffer_scenes::scenes::panel")
        .unwrap_or_else(|e| panic!("{e}"));
    fs::write(out.join("panel.rs"), source).expect("write panel.rs");
}
