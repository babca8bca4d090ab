//! Bakes `models/bracket.obj` into flash statics (`$OUT_DIR/bracket.rs`): the mesh,
//! its edges, planarity bits and the fast engine's constants, and their sizes.
fn main() {
    let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    pbuffer::bake::obj_to_rust("models/bracket.obj", "BRACKET", out.join("bracket.rs"))
        .unwrap_or_else(|e| panic!("{e}"));
}
