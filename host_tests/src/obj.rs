//! Wavefront OBJ loader for the `render` command, following ../shared/CONVENTIONS.md.
//!
//! Only two statements carry geometry:
//!
//! * `v x y z` — a vertex. The three coordinates must be finite numbers (Rust `f64`
//!   syntax: `1`, `-0.5`, `1e-3`; `nan`, `inf` and values that overflow to infinity are
//!   rejected). Up to three more numbers may follow and are ignored: the optional
//!   weight `w` of the OBJ specification, or the per-vertex colour `r g b` that MeshLab
//!   and others write. They must be finite numbers too; a seventh number or any
//!   non-number is an error.
//! * `f a b c ...` — a face of three or more vertex references. Each reference is
//!   `a`, `a/t`, `a//n` or `a/t/n`; only the first number (the vertex) is used, the
//!   others must be empty or integers. A positive index is 1-based and may name any
//!   vertex of the file (forward references are allowed, checked at the end of the
//!   file); a negative index counts back from the last `v` read before this line
//!   (`-1` is that vertex). Index 0, or an index that names no vertex, is an error.
//!
//! Faces are kept as written (no triangulation); face index = 0-based position of the
//! `f` line. Every other statement (`vn`, `vt`, `o`, `g`, `s`, `l`, `usemtl`, `mtllib`,
//! ...) is ignored, as are blank lines and comments (`#` to the end of a line, also after
//! a statement). Keywords are case-sensitive. Line continuation with `\` is not
//! supported. Invalid UTF-8 is replaced by U+FFFD, so it is only an error inside a `v` or
//! `f` line. A file without faces is an error.
//!
//! Errors are one line, `FILE:LINE: what is wrong` (`FILE:-: ...` for problems of the
//! whole file); nothing here panics.

use std::path::{Path, PathBuf};

use crate::frame::MeshData;

/// Reads and parses an OBJ file. The file name in error messages is `path` as given.
pub fn load_obj(path: &Path) -> Result<MeshData, String> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| format!("{name}:-: cannot read the file: {e}"))?;
    parse_obj(&String::from_utf8_lossy(&bytes), &name)
}

/// A face reference whose positive index is checked once the whole file is read.
struct Pending {
    line: usize,
    /// Largest positive 1-based index of the face (0 if none).
    max_positive: u64,
}

/// Parses OBJ text; `file_name` is used in error messages only.
pub fn parse_obj(text: &str, file_name: &str) -> Result<MeshData, String> {
    let mut mesh = MeshData::default();
    let mut pending: Vec<Pending> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line_no = i + 1;
        let err = |what: String| format!("{file_name}:{line_no}: {what}");
        let content = raw.split('#').next().unwrap_or("");
        let mut tokens = content.split_whitespace();
        match tokens.next() {
            Some("v") => {
                let v = parse_vertex(tokens).map_err(err)?;
                mesh.vertices.push(v);
            }
            Some("f") => {
                let known = mesh.vertices.len() as u64;
                let (face, max_positive) = parse_face(tokens, known).map_err(err)?;
                if max_positive > known {
                    pending.push(Pending {
                        line: line_no,
                        max_positive,
                    });
                }
                mesh.faces.push(face);
            }
            _ => {}
        }
    }
    let total = mesh.vertices.len() as u64;
    if let Some(p) = pending.iter().find(|p| p.max_positive > total) {
        return Err(format!(
            "{file_name}:{}: vertex index {} out of range (the file has {total} vertices)",
            p.line, p.max_positive
        ));
    }
    if mesh.faces.is_empty() {
        return Err(format!("{file_name}:-: no faces (no `f` lines)"));
    }
    Ok(mesh)
}

fn parse_number(tok: &str) -> Result<f64, String> {
    let x: f64 = tok
        .parse()
        .map_err(|_| format!("`{tok}` is not a number in a `v` line"))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("`{tok}` is not a finite number in a `v` line"))
    }
}

fn parse_vertex<'a>(tokens: impl Iterator<Item = &'a str>) -> Result<[f64; 3], String> {
    let mut xyz = [0.0; 3];
    let mut n = 0usize;
    for tok in tokens {
        let x = parse_number(tok)?;
        if n < 3 {
            xyz[n] = x;
        } else if n >= 6 {
            return Err(format!(
                "a `v` line has at most 6 numbers (x y z, then w or r g b), found `{tok}` as the 7th"
            ));
        }
        n += 1;
    }
    if n < 3 {
        return Err(format!("a `v` line needs 3 numbers (x y z), found {n}"));
    }
    Ok(xyz)
}

/// Parses the references of an `f` line. `known` = vertices read so far. Returns the
/// 0-based indices and the largest positive 1-based index (for the end-of-file check).
fn parse_face<'a>(
    tokens: impl Iterator<Item = &'a str>,
    known: u64,
) -> Result<(Vec<u32>, u64), String> {
    let mut face = Vec::new();
    let mut max_positive = 0u64;
    for tok in tokens {
        let mut parts = tok.split('/');
        let first = parts.next().unwrap_or("");
        let rest: Vec<&str> = parts.collect();
        if rest.len() > 2
            || rest
                .iter()
                .any(|p| !p.is_empty() && p.parse::<i64>().is_err())
        {
            return Err(format!(
                "`{tok}` is not a vertex reference (v, v/t, v//n or v/t/n)"
            ));
        }
        let idx: i64 = first
            .parse()
            .map_err(|_| format!("`{tok}` is not a vertex reference (v, v/t, v//n or v/t/n)"))?;
        let zero_based = if idx > 0 {
            let k = idx.unsigned_abs();
            max_positive = max_positive.max(k);
            k - 1
        } else if idx < 0 {
            let back = idx.unsigned_abs();
            if back > known {
                return Err(format!(
                    "vertex index {idx} out of range ({known} vertices read before this line)"
                ));
            }
            known - back
        } else {
            return Err("vertex index 0 (indices start at 1)".into());
        };
        let i = u32::try_from(zero_based)
            .map_err(|_| format!("vertex index {idx} out of range (more than 2^32 vertices)"))?;
        face.push(i);
    }
    if face.len() < 3 {
        return Err(format!(
            "a face needs at least 3 vertices, found {}",
            face.len()
        ));
    }
    Ok((face, max_positive))
}

/// The workspace root (the parent of `host_tests/`), where `../shared/` and `docs/` are
/// found relative to.
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

/// The scene of the `render` and `viewer` commands and the name to report it by: the
/// given file, else `../shared/models/suzanne.obj` (from the workspace root), else the
/// built-in cube when that file is missing, so both commands show the same default.
pub fn load_scene(path: Option<&Path>) -> Result<(MeshData, String), String> {
    let default_model = workspace_root().join("../shared/models/suzanne.obj");
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
        None if default_model.exists() => Ok((
            load_obj(&default_model)?,
            default_model.display().to_string(),
        )),
        None => Ok((builtin_cube(), "built-in cube".to_string())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ok(text: &str) -> MeshData {
        parse_obj(text, "t.obj").unwrap_or_else(|e| panic!("{e}"))
    }

    fn err(text: &str) -> String {
        match parse_obj(text, "t.obj") {
            Ok(m) => panic!("accepted: {m:?}"),
            Err(e) => {
                assert!(!e.contains('\n'), "one line: {e}");
                e
            }
        }
    }

    const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

    #[test]
    fn triangle_and_quad() {
        let m = ok("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 3\n");
        assert_eq!(m.vertices.len(), 4);
        assert_eq!(m.vertices[2], [1.0, 1.0, 0.0]);
        assert_eq!(m.faces, vec![vec![0, 1, 2, 3], vec![0, 1, 2]]);
    }

    #[test]
    fn number_syntax() {
        let m = ok("v -1.5 +2 3e-2\nv .5 1E3 -0\nv 1 1 1\nf 1 2 3\n");
        assert_eq!(m.vertices[0], [-1.5, 2.0, 0.03]);
        assert_eq!(m.vertices[1], [0.5, 1000.0, -0.0]);
    }

    #[test]
    fn extra_numbers_w_and_colour_ignored() {
        let m = ok("v 1 2 3 1.0\nv 1 2 3 0.5 0.5 0.5\nv 0 0 0\nf 1 2 3\n");
        assert_eq!(m.vertices[0], [1.0, 2.0, 3.0]);
        assert_eq!(m.vertices[1], [1.0, 2.0, 3.0]);
        let e = err("v 1 2 3 4 5 6 7\nv 0 0 0\nv 1 1 1\nf 1 2 3\n");
        assert!(e.starts_with("t.obj:1: ") && e.contains("7th"), "{e}");
        let e = err("v 1 2 3 nan\nv 0 0 0\nv 1 1 1\nf 1 2 3\n");
        assert!(e.starts_with("t.obj:1: "), "{e}");
    }

    #[test]
    fn slash_forms_take_the_first_number() {
        let m = ok(&format!("{TRI}vt 0 0\nvn 0 0 1\nf 1/1 2/1/1 3//1\n"));
        assert_eq!(m.faces, vec![vec![0, 1, 2]]);
    }

    #[test]
    fn negative_indices_count_back_from_the_last_v_before_the_line() {
        let m = ok(&format!(
            "{TRI}f -3 -2 -1\nv 5 5 5\nf -1 -2 -3\nf -4/1/1 1 -1//2\n"
        ));
        assert_eq!(m.faces[0], vec![0, 1, 2]);
        assert_eq!(m.faces[1], vec![3, 2, 1]);
        assert_eq!(m.faces[2], vec![0, 0, 3]);
    }

    #[test]
    fn forward_positive_reference_allowed_if_the_file_has_it() {
        let m = ok("v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n");
        assert_eq!(m.faces, vec![vec![0, 1, 2]]);
        let e = err("v 0 0 0\nf 1 2 4\nv 1 0 0\nv 0 1 0\n");
        assert!(
            e.starts_with("t.obj:2: ") && e.contains("out of range"),
            "{e}"
        );
    }

    #[test]
    fn unknown_statements_comments_blank_lines_crlf() {
        let m = ok(concat!(
            "# comment\r\n\r\nmtllib x.mtl\r\no thing\r\ng group\r\ns off\r\n",
            "usemtl m\r\nv 0 0 0 # inline\r\nv 1 0 0\r\nv 0 1 0\r\nvn 0 0 1\r\n",
            "vt 0.5 0.5\r\nl 1 2\r\np 1\r\nvp 1 2\r\nf 1 2 3 # tri\r\nvertex 1 2\r\nF 9 9\r\n",
            "\tf\t1 2 3\n"
        ));
        assert_eq!(m.vertices.len(), 3);
        assert_eq!(m.faces.len(), 2);
    }

    #[test]
    fn errors_in_v_lines() {
        for (text, what) in [
            ("v 1 2\n", "needs 3 numbers"),
            ("v\n", "needs 3 numbers"),
            ("v 1 2 x\n", "not a number"),
            ("v 1,0 2 3\n", "not a number"),
            ("v nan 0 0\n", "not a finite number"),
            ("v 0 NaN 0\n", "not a finite number"),
            ("v 0 0 inf\n", "not a finite number"),
            ("v 0 0 -infinity\n", "not a finite number"),
            ("v 1e400 0 0\n", "not a finite number"),
        ] {
            let e = err(&format!("# header\n{text}v 0 0 0\nf 1 1 1\n"));
            assert!(
                e.starts_with("t.obj:2: ") && e.contains(what),
                "{text:?}: {e}"
            );
        }
    }

    #[test]
    fn errors_in_f_lines() {
        for (line, what) in [
            ("f 1 2 0", "index 0"),
            ("f 1 2 4", "out of range"),
            ("f 1 2 -4", "out of range"),
            ("f 1 2", "at least 3"),
            ("f 1", "at least 3"),
            ("f", "at least 3"),
            ("f 1 2 x", "not a vertex reference"),
            ("f 1 2 3.0", "not a vertex reference"),
            ("f 1 2 /3", "not a vertex reference"),
            ("f 1 2 3/a", "not a vertex reference"),
            ("f 1 2 3/1/1/1", "not a vertex reference"),
            ("f 1 2 99999999999999999999", "not a vertex reference"),
            ("f 1 2 4294967297", "out of range"),
        ] {
            let e = err(&format!("{TRI}{line}\n"));
            assert!(
                e.starts_with("t.obj:4: ") && e.contains(what),
                "{line:?}: {e}"
            );
        }
    }

    #[test]
    fn negative_index_before_any_vertex() {
        let e = err("f -1 -2 -3\nv 0 0 0\n");
        assert!(
            e.starts_with("t.obj:1: ") && e.contains("0 vertices read"),
            "{e}"
        );
    }

    #[test]
    fn no_faces() {
        assert_eq!(err(""), "t.obj:-: no faces (no `f` lines)");
        assert_eq!(err(TRI), "t.obj:-: no faces (no `f` lines)");
        assert!(err("# nothing\n\n").starts_with("t.obj:-: no faces"));
    }

    #[test]
    fn first_error_wins_and_names_its_line() {
        let e = err(&format!("{TRI}f 1 2 3\nv 1 1 q\nf 0 1 2\n"));
        assert!(e.starts_with("t.obj:5: "), "{e}");
    }

    #[test]
    fn unreadable_file() {
        let p = std::path::PathBuf::from("/nonexistent/dir/x.obj");
        let e = load_obj(&p).unwrap_err();
        assert!(
            e.starts_with("/nonexistent/dir/x.obj:-: cannot read"),
            "{e}"
        );
    }

    #[test]
    fn load_from_disk_and_invalid_utf8() {
        let dir = std::env::temp_dir().join(format!("pbuffer-obj-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("a.obj");
        std::fs::write(&p, b"# caf\xe9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(load_obj(&p).unwrap().faces.len(), 1);
        std::fs::write(&p, b"v 0 0 \xff\n").unwrap();
        let e = load_obj(&p).unwrap_err();
        assert!(e.contains("a.obj:1: "), "{e}");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn shared_models_load() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/models");
        for (name, faces) in [("suzanne.obj", 500), ("fandisk.obj", 12946)] {
            let p = root.join(name);
            if p.exists() {
                let m = load_obj(&p).unwrap();
                assert_eq!(m.faces.len(), faces, "{name}");
            }
        }
    }
}
