//! Puts the board's memory layout where cortex-m-rt's link.x finds it (as `memory.x`:
//! the repository's `memory.x` for the mps2 boards, `memory-microbit.x` for
//! `thumbv6m-none-eabi`), tells `fw` the board (`cfg(fw_board = ...)`: `mps2-an386` for
//! `thumbv7em-none-eabihf`, `mps2-an385` for `thumbv7m-none-eabi`, `microbit` for
//! `thumbv6m-none-eabi`), and bakes the
//! firmware's meshes into `static`s kept in flash with `pbuffer::bake` (the edge list
//! at 30 degrees, which faces are planar, the fast engine's per-mesh constants):
//! `models/suzanne.obj` into `$OUT_DIR/suzanne.rs` (`SUZANNE_...`), and the panel
//! bracket (`pbuffer_scenes::scenes::panel`) into `$OUT_DIR/panel.rs` (`PANEL_...`), the
//! robot arm's procedural parts (`pbuffer_scenes::arm`) into `$OUT_DIR/arm.rs`
//! (`ARM_BASE_...`, `ARM_UPPER_...`, `ARM_FOREARM_...`, `ARM_GRIPPER_...`) and the
//! instance grids as one mesh each (`pbuffer_scenes::instances::grid`) into
//! `$OUT_DIR/grids.rs` (`GRID1_...`, `GRID4_...`, `GRID16_...`).
use std::{env, fs, path::PathBuf};

use pbuffer::mesh::Mesh;
use pbuffer_scenes::scenes::panel;
use pbuffer_scenes::shapes::Shape;
use pbuffer_scenes::{arm, instances};

/// The Rust source of a procedural part's statics.
fn shape_to_rust<const V: usize, const I: usize, const O: usize>(
    shape: &Shape<V, I, O>,
    name: &str,
    origin: &str,
) -> String {
    assert!(shape.is_full(), "{name}: the shape's sizes");
    let mesh = Mesh::new(&shape.vertices, &shape.indices, &shape.offsets)
        .unwrap_or_else(|e| panic!("{name}: {e:?}"));
    pbuffer::bake::mesh_to_rust(&mesh, name, origin).unwrap_or_else(|e| panic!("{e}"))
}

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap());
    let target = env::var("TARGET").unwrap_or_default();
    let (memory, board) = match target.as_str() {
        "thumbv6m-none-eabi" => ("memory-microbit.x", "microbit"),
        "thumbv7m-none-eabi" => ("../../memory.x", "mps2-an385"),
        _ => ("../../memory.x", "mps2-an386"),
    };
    fs::copy(memory, out.join("memory.x")).unwrap_or_else(|e| panic!("copy {memory}: {e}"));
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo::rustc-check-cfg=cfg(fw_board, values(\"mps2-an386\", \"mps2-an385\", \"microbit\"))");
    println!("cargo:rustc-cfg=fw_board=\"{board}\"");
    for f in ["../../memory.x", "memory-microbit.x", "build.rs"] {
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

    let arm = [
        shape_to_rust(&arm::base(), "ARM_BASE", "pbuffer_scenes::arm::base"),
        shape_to_rust(&arm::upper(), "ARM_UPPER", "pbuffer_scenes::arm::upper"),
        shape_to_rust(
            &arm::forearm(),
            "ARM_FOREARM",
            "pbuffer_scenes::arm::forearm",
        ),
        shape_to_rust(
            &arm::gripper(),
            "ARM_GRIPPER",
            "pbuffer_scenes::arm::gripper",
        ),
    ];
    fs::write(out.join("arm.rs"), arm.concat()).expect("write arm.rs");
    let origin = "pbuffer_scenes::instances::grid";
    let grids = [
        shape_to_rust(&instances::grid::<24, 72, 17>(1), "GRID1", origin),
        shape_to_rust(&instances::grid::<96, 288, 65>(4), "GRID4", origin),
        shape_to_rust(&instances::grid::<384, 1152, 257>(16), "GRID16", origin),
    ];
    fs::write(out.join("grids.rs"), grids.concat()).expect("write grids.rs");
}
