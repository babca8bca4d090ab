//! The `render` command as a user meets it: the built binary run on temporary files.
//! Every bad input exits with status 2 and one line on stderr naming the file and line
//! or the flag; the PGM and PNG outputs have the right headers and sizes; `--hash` and
//! `--stats` print `name: value` lines.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const TETRA: &str = "\
# a closed tetrahedron, counter-clockwise from outside
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
";

struct Dir(PathBuf);

impl Dir {
    fn new(name: &str) -> Self {
        let d =
            std::env::temp_dir().join(format!("pbuffer-render-cli-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        Dir(d)
    }
    fn file(&self, name: &str, text: &str) -> PathBuf {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }
    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

fn render(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_render"))
        .args(args)
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("run render")
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Asserts exit status 2 and exactly one stderr line that contains `needle`.
fn fails_with(out: &Output, needle: &str) -> String {
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "stderr: {err}");
    assert_eq!(err.lines().count(), 1, "one line: {err:?}");
    assert!(err.contains(needle), "{needle:?} not in {err:?}");
    assert!(
        !err.contains("panicked") && !err.contains("backtrace"),
        "{err}"
    );
    assert!(out.stdout.is_empty(), "nothing on stdout");
    err
}

#[test]
fn obj_errors_name_file_and_line() {
    let d = Dir::new("obj");
    let cases: [(&str, String, &str); 9] = [
        ("nan.obj", format!("{TETRA}v nan 0 0\n"), ":10: "),
        ("inf.obj", "v 0 0 inf\n".to_string(), ":1: "),
        ("garbage-v.obj", "v 0 0\n".to_string(), ":1: "),
        ("garbage-f.obj", format!("{TETRA}f 1 2 three\n"), ":10: "),
        ("zero.obj", format!("{TETRA}f 0 1 2\n"), ":10: "),
        ("range.obj", format!("{TETRA}f 1 2 5\n"), ":10: "),
        ("negative.obj", format!("{TETRA}f -1 -2 -5\n"), ":10: "),
        ("two.obj", format!("{TETRA}f 1 2\n"), ":10: "),
        (
            "nofaces.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\n".to_string(),
            ":-: ",
        ),
    ];
    for (name, text, line) in cases {
        let p = d.file(name, &text);
        let out = render(&[s(&p), "--hash"]);
        let err = fails_with(&out, &format!("{}{line}", s(&p)));
        assert!(err.starts_with("render: "), "{err}");
    }
}

#[test]
fn unreadable_file() {
    let d = Dir::new("unreadable");
    let missing = d.path("missing.obj");
    fails_with(
        &render(&[s(&missing)]),
        &format!("{}:-: cannot read", s(&missing)),
    );
    // A directory is not a readable OBJ file either.
    fails_with(&render(&[s(&d.0)]), ":-: cannot read");
}

#[test]
fn flag_errors_name_the_flag() {
    let d = Dir::new("flags");
    let p = d.file("t.obj", TETRA);
    for (args, flag) in [
        (&["--size", "0x10"][..], "--size"),
        (&["--size", "abc"], "--size"),
        (&["--eye", "1,2"], "--eye"),
        (&["--eye", "nan,0,0"], "--eye"),
        (&["--fov", "0"], "--fov"),
        (&["--ortho", "0"], "--ortho"),
        (&["--near", "-1"], "--near"),
        (&["--eye", "0,0,5", "--near", "2", "--far", "1"], "--far"),
        (&["--eye", "0,0,5", "--target", "0,0,5"], "--eye"),
        (&["--eye", "0,5,0"], "--up"),
        (&["--crease", "-5"], "--crease"),
        (&["--cull", "sometimes"], "--cull"),
        (&["--mode", "solid"], "--mode"),
        (&["--engine", "phong"], "--engine"),
        (&["--subpixel", "13"], "--subpixel"),
        (&["--depth-bits", "8"], "--depth-bits"),
        (&["--band", "0"], "--band"),
        (&["--band", "241"], "--band"),
        (&["--pattern", "zigzag"], "--pattern"),
        (&["--scale", "99"], "--scale"),
        (&["--out", "x.bmp"], "--out"),
        (&["--ids"], "--ids"),
        (&["--nonsense"], "--nonsense"),
        (&["--fit", "--eye", "1,1,1"], "--fit"),
    ] {
        let mut a = vec![s(&p)];
        a.extend_from_slice(args);
        fails_with(&render(&a), flag);
    }
    fails_with(&render(&[s(&p), s(&p)]), "second scene");
}

#[test]
fn unwritable_output() {
    let d = Dir::new("unwritable");
    let p = d.file("t.obj", TETRA);
    // A path below a regular file cannot be created.
    let below = d.path("t.obj/x.pgm");
    fails_with(&render(&[s(&p), "--lines", s(&below)]), "--lines");
}

#[test]
fn out_into_a_missing_directory_is_refused_not_created() {
    let d = Dir::new("missing-dir");
    let p = d.file("t.obj", TETRA);
    for flag in ["--out", "--ids", "--lines", "--grey"] {
        let missing = d.path("no/such/dir");
        let target = missing.join("x.png");
        let err = fails_with(&render(&[s(&p), flag, s(&target)]), flag);
        assert!(
            err.contains(s(&missing)),
            "{err:?} does not name the directory"
        );
        assert!(!d.path("no").exists(), "{flag} created the directories");
    }
}

#[test]
fn the_main_command_writes_outside_the_tracked_tree() {
    // `render` without a scene writes target/render.png (git ignores target/), never
    // a tracked file in docs/.
    let out = render(&["--size", "32x16"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let wrote = text
        .lines()
        .find_map(|l| l.strip_prefix("wrote: "))
        .expect("a wrote: line");
    let root = host_tests::obj::workspace_root();
    assert_eq!(Path::new(wrote), root.join("target").join("render.png"));
}

#[test]
fn too_many_faces_for_ids() {
    let d = Dir::new("ids-limit");
    let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for _ in 0..65_536 {
        text += "f 1 2 3\n";
    }
    let p = d.file("big.obj", &text);
    let ids = d.path("ids.pgm");
    fails_with(&render(&[s(&p), "--ids", s(&ids)]), "65536 faces");
    assert!(!ids.exists());
}

fn pgm(bytes: &[u8]) -> (String, &[u8]) {
    // Header: three whitespace-terminated fields after "P5", then one whitespace byte.
    let mut fields = 0;
    let mut i = 2;
    assert_eq!(&bytes[..2], b"P5");
    while fields < 3 {
        while bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        while !bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        fields += 1;
    }
    let header = String::from_utf8(bytes[..i].to_vec()).unwrap();
    (header, &bytes[i + 1..])
}

#[test]
fn pgm_outputs_and_hash() {
    let d = Dir::new("pgm");
    let p = d.file("t.obj", TETRA);
    let (ids, lines, png) = (d.path("ids.pgm"), d.path("lines.pgm"), d.path("t.png"));
    let out = render(&[
        s(&p),
        "--size",
        "64x48",
        "--ids",
        s(&ids),
        "--lines",
        s(&lines),
        "--out",
        s(&png),
        "--scale",
        "2",
        "--hash",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    // --hash alone prints one line `hash: ` + 16 lower-case hex digits.
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    let hex = stdout
        .trim_end()
        .strip_prefix("hash: ")
        .expect("hash: prefix");
    assert_eq!(hex.len(), 16);
    assert!(hex
        .chars()
        .all(|c| c.is_ascii_hexdigit() && !c.is_ascii_uppercase()));

    let bytes = std::fs::read(&ids).unwrap();
    let (header, data) = pgm(&bytes);
    assert_eq!(header, "P5\n64 48\n65535");
    assert_eq!(data.len(), 64 * 48 * 2);
    let samples: Vec<u16> = data
        .chunks_exact(2)
        .map(|c| u16::from_be_bytes([c[0], c[1]]))
        .collect();
    assert!(
        samples.iter().all(|&v| v <= 4),
        "ids are 0 or 1 + face index"
    );
    assert!(samples.iter().any(|&v| v != 0), "the tetrahedron is seen");

    let bytes = std::fs::read(&lines).unwrap();
    let (header, data) = pgm(&bytes);
    assert_eq!(header, "P5\n64 48\n255");
    assert_eq!(data.len(), 64 * 48);
    assert!(data.iter().all(|&v| v <= 2));
    assert!(data.contains(&1));

    let dec = png::Decoder::new(std::fs::File::open(&png).unwrap());
    let info = dec.read_info().unwrap();
    let (w, h) = (info.info().width, info.info().height);
    assert_eq!((w, h), (64 * 2, 48 * 2));

    // The same frame again: the same hash.
    let again = render(&[s(&p), "--size", "64x48", "--hash"]);
    assert_eq!(String::from_utf8(again.stdout).unwrap(), stdout);
}

#[test]
fn stats_lines() {
    let d = Dir::new("stats");
    let p = d.file("t.obj", TETRA);
    let out = render(&[s(&p), "--stats", "--size=80x60", "--mode", "hidden"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    let mut names = Vec::new();
    for l in stdout.lines() {
        let (k, v) = l
            .split_once(": ")
            .unwrap_or_else(|| panic!("not name: value: {l:?}"));
        assert!(!k.is_empty() && !v.is_empty() && !k.contains(' '), "{l:?}");
        names.push(k.to_string());
    }
    for k in [
        "faces",
        "faces_drawn",
        "feature_edges",
        "spans",
        "working_ram_bytes",
        "time_us",
    ] {
        assert!(names.iter().any(|n| n == k), "{k} missing in {stdout}");
    }
    assert!(stdout.contains("faces: 4\n"), "{stdout}");
}

#[test]
fn help_exits_zero() {
    let out = render(&["--help"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stdout).contains("--mode"));
}

/// Regression: `Mesh::new` rejected faces whose positions repeat, so `render` refused
/// OBJ files that CONVENTIONS.md calls valid (a face needs 3 valid indices). Such a
/// face has a zero normal: it covers nothing, and only its one real edge is drawn
/// (a boundary).
#[test]
fn a_face_with_a_repeated_vertex_renders_as_the_conventions_allow() {
    let dir = Dir::new("repeated");
    let obj = dir.file(
        "repeated.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 2\n",
    );
    let ids = dir.path("ids.pgm");
    let out = render(&[s(&obj), "--stats", "--ids", s(&ids), "--cull", "off"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("faces: 2"), "{stdout}");
    assert!(stdout.contains("feature_edges: 4"), "{stdout}");
    // No pixel shows face 1 (the collapsed one): its id, 2, never appears.
    let bytes = std::fs::read(&ids).unwrap();
    let (_, samples) = pgm(&bytes);
    assert!(samples
        .chunks(2)
        .all(|s| u16::from_be_bytes([s[0], s[1]]) != 2));
    assert!(samples
        .chunks(2)
        .any(|s| u16::from_be_bytes([s[0], s[1]]) == 1));
}

/// `--scheme`: schemes 1 and 2 draw the view they can order (the code width among the
/// figures), and a view without a consistent order exits 1 naming the condition.
#[test]
fn scheme_flag_draws_or_names_the_broken_condition() {
    let out = render(&[
        "scene:cube",
        "--scheme",
        "path",
        "--size",
        "128x64",
        "--stats",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("scheme_code_bits: 8"), "{text}");
    let out = render(&["scene:boxes", "--scheme", "combination", "--size", "128x64"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("order their shared surfaces differently"),
        "{err}"
    );
}

/// `--grey` looks at most 64 faces at a pixel: the teapot at 128x64 has more under
/// some pixels. The error names the flag, like every other (it said "render: render:
/// capacity ...", naming neither the flag nor the output).
#[test]
fn grey_past_its_faces_at_a_pixel_names_the_flag() {
    let d = Dir::new("grey-capacity");
    let teapot = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/models/teapot.obj");
    let grey = d.path("grey.png");
    let args = [s(&teapot), "--size", "128x64", "--mode", "surfaces"];
    let err = fails_with(
        &render(&[&args[..], &["--grey", s(&grey)]].concat()),
        "--grey: ",
    );
    assert!(
        err.contains("A-buffer faces at a pixel: 65 needed, capacity 64"),
        "{err}"
    );
    assert!(!err.contains("render: render:"), "{err}");
}

/// `*` matches any run of characters, as callgrind's `--toggle-collect` does.
fn glob(pattern: &str, text: &str) -> bool {
    let parts: Vec<&str> = pattern.split('*').collect();
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !text.starts_with(first) || !text[first.len()..].ends_with(last) {
        return false;
    }
    let mut rest = &text[first.len()..text.len() - last.len()];
    for part in &parts[1..parts.len() - 1] {
        match rest.find(part) {
            Some(i) => rest = &rest[i + part.len()..],
            None => return false,
        }
    }
    parts.len() > 1 || text == pattern
}

/// The report's callgrind counts leave out the host-only work by function name
/// (`pipeline::EXCLUDED`): a move or rename that leaves a pattern matching nothing
/// would silently count that work. Every pattern must name a function of the
/// `report` binary.
#[test]
fn every_callgrind_exclusion_names_a_function_of_the_report_binary() {
    let out = Command::new("nm")
        .arg("-C")
        .arg(env!("CARGO_BIN_EXE_report"))
        .output()
        .expect("nm (binutils) runs");
    assert!(out.status.success(), "nm failed");
    let symbols = String::from_utf8_lossy(&out.stdout);
    let names: Vec<&str> = symbols
        .lines()
        .filter_map(|l| l.splitn(3, ' ').nth(2))
        .collect();
    assert!(
        names.len() > 1000,
        "{} symbols: is the binary stripped?",
        names.len()
    );
    for pattern in host_tests::setup::EXCLUDED {
        let hits = names.iter().filter(|n| glob(pattern, n)).count();
        assert!(hits > 0, "no function of `report` matches {pattern:?}");
    }
    assert!(glob("*a::B as*C*d*", "<x::a::B as y::C>::d"));
    assert!(!glob("*a::B as*C*d*", "<x::a::B as y::E>::f"));
}

/// A scene of two tetrahedra, the second turned and moved.
const TWO_TETRA: &str = "\
# parts: PATH [tx ty tz [rx ry rz]]
tetra.obj
tetra.obj   1.5 0 0   0 90 30   # beside the first
";

#[test]
fn a_scene_renders_and_its_dumped_union_renders_the_same() {
    let d = Dir::new("scene");
    d.file("tetra.obj", TETRA);
    let scene = d.file("two.scene", TWO_TETRA);
    let (ids, lines, union) = (d.path("ids.pgm"), d.path("lines.pgm"), d.path("union.obj"));
    let (ids2, lines2) = (d.path("ids2.pgm"), d.path("lines2.pgm"));
    let camera = [
        "--eye",
        "1,2,4",
        "--target",
        "0.8,0.3,0.3",
        "--size",
        "96x64",
    ];
    let mut args = vec![s(&scene), "--ids", s(&ids), "--lines", s(&lines)];
    args.extend(["--dump-obj", s(&union), "--stats"]);
    args.extend(camera);
    let out = render(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stats = String::from_utf8_lossy(&out.stdout);
    assert!(stats.contains("faces: 8\n"), "{stats}");
    let dumped = std::fs::read_to_string(&union).unwrap();
    assert_eq!(dumped.lines().filter(|l| l.starts_with("v ")).count(), 8);
    assert!(
        dumped.contains("\nf 5 7 6\n"),
        "faces in part order: {dumped}"
    );
    // The union as one OBJ: the same face ids and line pixels.
    let mut again = vec![s(&union), "--ids", s(&ids2), "--lines", s(&lines2)];
    again.extend(camera);
    let out = render(&again);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let read = |p: &Path| std::fs::read(p).unwrap();
    let ids = read(&ids);
    assert_eq!(ids, read(&ids2), "--ids");
    assert_eq!(read(&lines), read(&lines2), "--lines");
    // Both parts are seen: face ids of the second (5..8, stored 1 + id) occur.
    let (_, samples) = pgm(&ids);
    let seen = |f: u16| {
        samples
            .chunks(2)
            .any(|s| u16::from_be_bytes([s[0], s[1]]) == f + 1)
    };
    assert!(seen(0) || seen(1) || seen(2) || seen(3));
    assert!((4..8).any(seen));
}

#[test]
fn a_bad_scene_line_exits_2_naming_file_and_line() {
    let d = Dir::new("bad-scene");
    d.file("tetra.obj", TETRA);
    for (text, line, what) in [
        ("tetra.obj\ntetra.obj 1 2\n", 2, "found 2 numbers"),
        (
            "# ok\ntetra.obj 0 0 0 x 0 0\n",
            2,
            "`x` is not a finite number",
        ),
        ("tetra.obj\n\nmissing.obj 1 0 0\n", 3, "part missing.obj"),
    ] {
        let scene = d.file("bad.scene", text);
        let out = render(&[s(&scene)]);
        let needle = format!("{}:{line}: ", s(&scene));
        let err = fails_with(&out, &needle);
        assert!(err.contains(what), "{err}");
    }
    // A part's own OBJ error names the part's file and line too.
    d.file("broken.obj", "v 0 0 0\nv 1 0\nf 1 2 3\n");
    let scene = d.file("broken.scene", "broken.obj\n");
    let err = fails_with(&render(&[s(&scene)]), &format!("{}:1: ", s(&scene)));
    assert!(err.contains("broken.obj:2:"), "{err}");
}

#[test]
fn pick_and_stats_work_on_a_scene_as_on_one_mesh() {
    let d = Dir::new("scene-pick");
    d.file("tetra.obj", TETRA);
    let scene = d.file("two.scene", TWO_TETRA);
    let out = render(&[
        s(&scene),
        "--pick",
        "48,32",
        "--eye",
        "1,2,4",
        "--size",
        "96x64",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("pick_face: "), "{text}");
}
