//! Wavefront OBJ loader for the `render` command: the library's reader
//! (`pbuffer::obj`, which follows ../shared/CONVENTIONS.md and says what it accepts)
//! with the positions kept in f64 for the reference, and the faces as lists.
//!
//! Errors are one line, `FILE:LINE: what is wrong` (`FILE:-: ...` for problems of the
//! whole file); nothing here panics.

use std::path::{Path, PathBuf};

use crate::frame::MeshData;

/// Reads and parses an OBJ file. The file name in error messages is `path` as given.
pub fn load_obj(path: &Path) -> Result<MeshData, String> {
    pbuffer::obj::read_f64(path)
        .map(mesh_data)
        .map_err(|e| e.to_string())
}

/// Parses OBJ text; `file_name` is used in error messages only.
pub fn parse_obj(text: &str, file_name: &str) -> Result<MeshData, String> {
    pbuffer::obj::parse_f64(text, file_name)
        .map(mesh_data)
        .map_err(|e| e.to_string())
}

/// The host's layout: the faces as lists.
fn mesh_data(m: pbuffer::obj::ObjMesh<f64>) -> MeshData {
    let faces = m.faces().map(<[u32]>::to_vec).collect();
    MeshData {
        vertices: m.vertices,
        faces,
    }
}

/// The workspace root (the parent of `host_tests/`), where `models/`, `docs/` and (for
/// the tests) `../shared/` are found relative to.
pub fn workspace_root() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().unwrap_or(manifest).to_path_buf()
}

/// A 2 x 2 x 2 cube centred on the origin, faces counter-clockwise from outside.
pub fn builtin_cube() -> MeshData {
    let vertices = (0..8)
        .map(|i| {
            [
                f64::from(i & 1) * 2.0 - 1.0,
                f64::from((i >> 1) & 1) * 2.0 - 1.0,
                f64::from((i >> 2) & 1) * 2.0 - 1.0,
            ]
        })
        .collect();
    let faces = vec![
        vec![0, 2, 3, 1],
        vec![4, 5, 7, 6],
        vec![0, 1, 5, 4],
        vec![2, 6, 7, 3],
        vec![0, 4, 6, 2],
        vec![1, 3, 7, 5],
    ];
    MeshData { vertices, faces }
}

/// The default model of the `render` and `viewer` commands: the repository's
/// `models/suzanne.obj`, found from the workspace root wherever the command runs.
pub fn default_model() -> PathBuf {
    workspace_root().join("models").join("suzanne.obj")
}

/// The scene of the `render` and `viewer` commands and the name to report it by: the
/// given file, else [`default_model`], so both commands show the same default. A
/// default model that cannot be read is an error, as any other file.
pub fn load_scene(path: Option<&Path>) -> Result<(MeshData, String), String> {
    match path {
        Some(p) if p.to_string_lossy().starts_with("scene:") => {
            let name = p.to_string_lossy()["scene:".len()..].to_string();
            let scenes = crate::shapes::all_scenes();
            let names: Vec<&str> = scenes.iter().map(|s| s.name.as_str()).collect();
            scenes
                .iter()
                .find(|s| s.name == name)
                .map(|s| (s.mesh.clone(), format!("scene:{name}")))
                .ok_or_else(|| {
                    format!(
                        "scene:{name}: no such procedural scene (have {})",
                        names.join(", ")
                    )
                })
        }
        Some(p) => Ok((load_obj(p)?, p.display().to_string())),
        None => {
            let p = default_model();
            let mesh = load_obj(&p).map_err(|e| format!("{e} (the default model)"))?;
            Ok((mesh, p.display().to_string()))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // The parser's own tests are the library's (src/obj/tests.rs).
    #[test]
    fn faces_as_lists_and_errors_as_lines() {
        let m = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf -1 -2 -3\n", "t.obj").unwrap();
        assert_eq!(m.faces, vec![vec![0, 1, 2], vec![2, 1, 0]]);
        assert_eq!(m.vertices[1], [1.0, 0.0, 0.0]);
        let e = parse_obj("v 0 0 0\n", "t.obj").unwrap_err();
        assert_eq!(e, "t.obj:-: no faces (no `f` lines)");
        let e = load_obj(Path::new("/nonexistent/dir/x.obj")).unwrap_err();
        assert!(
            e.starts_with("/nonexistent/dir/x.obj:-: cannot read"),
            "{e}"
        );
    }

    #[test]
    fn shared_models_load() {
        let root = workspace_root().join("../shared/models");
        for (name, faces) in [("suzanne.obj", 500), ("fandisk.obj", 12946)] {
            let p = root.join(name);
            if p.exists() {
                let m = load_obj(&p).unwrap();
                assert_eq!(m.faces.len(), faces, "{name}");
            }
        }
    }
}
