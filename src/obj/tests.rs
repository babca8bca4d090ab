//! The reader against the conventions, line by line.
use super::*;
use std::path::PathBuf;

/// The faces as lists, to compare with literals.
fn faces(m: &ObjMesh<f64>) -> Vec<Vec<u32>> {
    m.faces().map(<[u32]>::to_vec).collect()
}

fn ok(text: &str) -> ObjMesh<f64> {
    parse_f64(text, "t.obj").unwrap_or_else(|e| panic!("{e}"))
}

fn err(text: &str) -> String {
    match parse_f64(text, "t.obj") {
        Ok(m) => panic!("accepted: {m:?}"),
        Err(e) => {
            let e = e.to_string();
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
    assert_eq!(faces(&m), vec![vec![0, 1, 2, 3], vec![0, 1, 2]]);
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
    assert_eq!(faces(&m), vec![vec![0, 1, 2]]);
}

#[test]
fn negative_indices_count_back_from_the_last_v_before_the_line() {
    let m = ok(&format!(
        "{TRI}f -3 -2 -1\nv 5 5 5\nf -1 -2 -3\nf -4/1/1 1 -1//2\n"
    ));
    assert_eq!(faces(&m)[0], vec![0, 1, 2]);
    assert_eq!(faces(&m)[1], vec![3, 2, 1]);
    assert_eq!(faces(&m)[2], vec![0, 0, 3]);
}

#[test]
fn forward_positive_reference_allowed_if_the_file_has_it() {
    let m = ok("v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n");
    assert_eq!(faces(&m), vec![vec![0, 1, 2]]);
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
    assert_eq!(m.face_count(), 2);
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
    let p = PathBuf::from("/nonexistent/dir/x.obj");
    let e = read_f64(&p).unwrap_err().to_string();
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
    assert_eq!(read_f64(&p).unwrap().face_count(), 1);
    std::fs::write(&p, b"v 0 0 \xff\n").unwrap();
    let e = read_f64(&p).unwrap_err().to_string();
    assert!(e.contains("a.obj:1: "), "{e}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn shared_models_load() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/models");
    for (name, faces) in [("suzanne.obj", 500), ("fandisk.obj", 12946)] {
        let p = root.join(name);
        if p.exists() {
            let m = read_f64(&p).unwrap();
            assert_eq!(m.face_count(), faces, "{name}");
        }
    }
}

#[test]
fn f32_positions_round_and_reject_overflow() {
    let m = parse("v 0.1 1 2\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj").unwrap();
    assert_eq!(m.vertices[0], [0.1f32, 1.0, 2.0]);
    assert_eq!(m.indices, vec![0, 1, 2]);
    assert_eq!(m.offsets, vec![0, 3]);
    assert_eq!(m.mesh().unwrap().face_count(), 1);
    let e = parse("v 1e39 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj").unwrap_err();
    assert_eq!(e.line, Some(1));
    assert_eq!(e.problem, ObjProblem::OutOfF32Range("1e39".into()));
    // The f64 reader keeps it.
    assert!(parse_f64("v 1e39 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj").is_ok());
}

#[test]
fn error_variants_name_the_problem() {
    let problem = |text: &str| parse(text, "t.obj").unwrap_err().problem;
    assert_eq!(problem("v 0 0 0\nf 1 1 0\n"), ObjProblem::IndexZero);
    assert_eq!(problem("v 0 0 0\nf 1 1\n"), ObjProblem::ShortFace(2));
    assert_eq!(
        problem("v 0 0 0\nf 1 1 -2\n"),
        ObjProblem::NegativeOutOfRange {
            index: -2,
            known: 1
        }
    );
    assert_eq!(
        problem("v 0 0 0\nf 1 1 7\n"),
        ObjProblem::IndexOutOfRange {
            index: 7,
            vertices: 1
        }
    );
    assert_eq!(problem("v 0 0 0\n"), ObjProblem::NoFaces);
}
