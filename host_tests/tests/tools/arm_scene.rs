//! The repository's robot-arm scene (`models/arm.scene`, README "Several moving
//! parts"): its part files are the robot-arm demo's procedural parts
//! (`examples/scenes/src/arm.rs`), vertex for vertex, and `render` draws it.
//!
//! `PBUFFER_WRITE_MODELS=1 cargo test --release -p host_tests --test tools arm_scene::`
//! writes the part files again from the demo's code.

use std::process::Command;

use host_tests::firmware::{arm, shapes::Shape};
use host_tests::obj::{load_obj, workspace_root};
use host_tests::posed::load_scene_file;

/// A part as OBJ text: each coordinate the shortest decimal of its `f32`, so that
/// reading it back gives the same bits.
fn obj_text<const V: usize, const I: usize, const O: usize>(
    name: &str,
    shape: &Shape<V, I, O>,
) -> String {
    assert!(shape.is_full(), "{name}: the part's sizes");
    let mut text = format!(
        "# The robot-arm demo's part `{name}()` (examples/scenes/src/arm.rs) in its own space,\n\
         # written by host_tests' arm_scene test (PBUFFER_WRITE_MODELS=1).\n"
    );
    for v in &shape.vertices {
        text += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for w in shape.offsets.windows(2) {
        let corners: Vec<String> = shape.indices[w[0] as usize..w[1] as usize]
            .iter()
            .map(|i| (i + 1).to_string())
            .collect();
        text += &format!("f {}\n", corners.join(" "));
    }
    text
}

#[test]
fn part_files_are_the_demos_parts() {
    let parts = [
        ("base", obj_text("base", &arm::base())),
        ("upper", obj_text("upper", &arm::upper())),
        ("forearm", obj_text("forearm", &arm::forearm())),
        ("gripper", obj_text("gripper", &arm::gripper())),
    ];
    let write = std::env::var_os("PBUFFER_WRITE_MODELS").is_some();
    for (name, text) in parts {
        let path = workspace_root().join(format!("models/arm-{name}.obj"));
        if write {
            std::fs::write(&path, &text).unwrap();
        }
        let file = std::fs::read_to_string(&path).unwrap_or_else(|e| {
            panic!("{}: {e} (PBUFFER_WRITE_MODELS=1 writes it)", path.display())
        });
        assert_eq!(file, text, "{} is not the demo's part", path.display());
        load_obj(&path).unwrap();
    }
}

#[test]
fn the_readme_scene_renders() {
    let scene = workspace_root().join("models/arm.scene");
    let parts = load_scene_file(&scene).unwrap();
    assert_eq!(parts.len(), 4);
    let out = Command::new(env!("CARGO_BIN_EXE_render"))
        .args([scene.to_str().unwrap(), "--size", "128x64", "--hash"])
        .output()
        .expect("run render");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
