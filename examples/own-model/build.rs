//! Bakes `models/bracket.obj` into flash statics (`$OUT_DIR/bracket.rs`): the mesh,
//! its edges, planarity bits and the fast engine's constants, and their sizes,
//! with `BRACKET_FACETS` and `BRACKET_LINES` for the 64 x 64 frames this example
//! draws (24 directions around the model at the fitted camera's elevation).
fn main() {
    let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let views = pbuffer::bake::BakeOptions {
        width: 64,
        height: 64,
        ..Default::default()
    };
    pbuffer::bake::obj_to_rust_with(
        "models/bracket.obj",
        "BRACKET",
        out.join("bracket.rs"),
        &views,
    )
    .unwrap_or_else(|e| panic!("{e}"));
}
