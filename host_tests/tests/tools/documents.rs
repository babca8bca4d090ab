//! The documents a user reads first say what the code does: the default engine they
//! name is `render`'s, their Rust blocks are compiled, and they state the present (no
//! dates or commit hashes: history belongs in git and CHANGELOG.md).

use host_tests::frame::EngineSpec;
use host_tests::obj::workspace_root;
use host_tests::tools::cli::Options;

fn read(rel: &str) -> String {
    let path = workspace_root().join(rel);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The documents checked: the README, the figures, the reports and the examples' guide.
const DOCUMENTS: [&str; 5] = [
    "README.md",
    "BENCHMARKS.md",
    "report/speed-vs-error.md",
    "report/engines.md",
    "examples/embedded/README.md",
];

/// Every engine a document marks "(default)": an engine's name in backticks or bold,
/// perhaps followed by its settings (`**fast S4** (default)`), just before the mark
/// (other defaults, such as `--fit` (default), are left alone).
fn engines_marked_default(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    for (at, _) in text.match_indices("(default)") {
        let before = text[..at].trim_end();
        let Some(quote) = before.chars().last().filter(|c| *c == '`' || *c == '*') else {
            continue;
        };
        let inner = before.trim_end_matches(quote);
        let start = inner.rfind(quote).map_or(0, |i| i + 1);
        let name = inner[start..].split_whitespace().next().unwrap_or("");
        let name = name.trim_matches(['`', '*']);
        if EngineSpec::ALL.iter().any(|e| e.name() == name) {
            found.push(name.to_string());
        }
    }
    found
}

#[test]
fn every_document_names_renders_default_engine() {
    let default = Options::default().spec.engine.name();
    assert_eq!(
        default, "fast",
        "render's default engine changed: update the documents"
    );
    let mut marks = 0;
    for doc in DOCUMENTS {
        for name in engines_marked_default(&read(doc)) {
            marks += 1;
            assert_eq!(name, default, "{doc} marks `{name}` as the default engine");
        }
    }
    let readme = read("README.md");
    assert!(
        readme.contains("**`fast`** (default)"),
        "README's engine table does not mark the default"
    );
    assert!(
        marks >= 2,
        "only {marks} default marks found: the check finds nothing"
    );
    for wrong in ["the `render` default", "`codefill` (default)"] {
        assert!(!readme.contains(wrong), "README says {wrong:?}");
    }
}

#[test]
fn the_default_marker_finder_finds_a_wrong_default() {
    let text = "| `codefill` (default) | `--fit` (default) |\n| **zbuffer S4 d32** (default) |";
    assert_eq!(engines_marked_default(text), ["codefill", "zbuffer"]);
}

/// The fenced blocks of a Markdown text: (info string, body, the text before it).
fn fenced_blocks(text: &str) -> Vec<(String, String, String)> {
    let mut blocks = Vec::new();
    let mut rest = text;
    let mut consumed = 0;
    while let Some(open) = rest.find("```") {
        let after = &rest[open + 3..];
        let Some(eol) = after.find('\n') else { break };
        let info = after[..eol].trim().to_string();
        let body_start = &after[eol + 1..];
        let Some(close) = body_start.find("\n```") else {
            break;
        };
        let before = text[..consumed + open].to_string();
        blocks.push((info, body_start[..close + 1].to_string(), before));
        let used = open + 3 + eol + 1 + close + 4;
        consumed += used;
        rest = &rest[used..];
    }
    blocks
}

#[test]
fn every_rust_block_of_the_readme_is_compiled() {
    // Plain `rust` blocks are doctests: the library includes the README under
    // cfg(doctest). A block that cannot be one (a build script, a file with
    // `include!`) is `rust,ignore` and must be the named file's text, which CI builds.
    let lib = read("src/lib.rs");
    assert!(
        lib.contains("#[cfg(doctest)]") && lib.contains("include_str!(\"../README.md\")"),
        "src/lib.rs no longer compiles the README's blocks"
    );
    let readme = read("README.md");
    let blocks = fenced_blocks(&readme);
    let rust: Vec<_> = blocks.iter().filter(|b| b.0.starts_with("rust")).collect();
    assert!(rust.len() >= 3, "only {} Rust blocks found", rust.len());
    for (info, body, before) in rust {
        if !info.contains("ignore") {
            continue;
        }
        let paragraph = before.trim_end().rsplit("\n\n").next().unwrap_or("");
        let file = paragraph
            .split('`')
            .find(|w| w.starts_with("examples/") && w.ends_with(".rs"))
            .unwrap_or_else(|| panic!("an ignored block names no file before it:\n{body}"));
        let source = read(file);
        assert!(
            source.contains(body.trim()),
            "README's block from {file} is not that file's text:\n{body}"
        );
    }
}

/// A date (2026-11-27) or a word that looks like a commit hash (7 to 12 hex digits,
/// letters and digits both), outside the toolchain's own version line.
fn diary_marks(text: &str) -> Vec<String> {
    let mut marks = Vec::new();
    for line in text.lines().filter(|l| !l.contains("rustc ")) {
        for word in line.split(|c: char| !c.is_ascii_alphanumeric() && c != '-') {
            let date = word.len() == 10
                && word.bytes().enumerate().all(|(i, b)| {
                    if i == 4 || i == 7 {
                        b == b'-'
                    } else {
                        b.is_ascii_digit()
                    }
                });
            let hex = (7..=12).contains(&word.len())
                && word
                    .bytes()
                    .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
                && word.bytes().any(|b| b.is_ascii_digit())
                && word.bytes().any(|b| b.is_ascii_alphabetic());
            if date || hex {
                marks.push(word.to_string());
            }
        }
    }
    marks
}

#[test]
fn readme_and_benchmarks_state_the_present() {
    for doc in ["README.md", "BENCHMARKS.md"] {
        let marks = diary_marks(&read(doc));
        assert!(
            marks.is_empty(),
            "{doc} has dates or commit hashes: {marks:?}"
        );
    }
    assert_eq!(
        diary_marks("measured on 9942a09 (2026-11-26), hash c1c2382bd891f42e"),
        ["9942a09", "2026-11-26"]
    );
}

#[test]
fn readme_starts_with_the_main_job_and_the_tests() {
    let readme = read("README.md");
    let (_, first, _) = fenced_blocks(&readme)
        .into_iter()
        .next()
        .expect("a first block");
    let mut lines = first.lines();
    let main = lines.next().unwrap_or("");
    let tests = lines.next().unwrap_or("");
    assert!(
        main.starts_with("cargo run --release -p host_tests --bin render"),
        "{main}"
    );
    assert!(tests.starts_with("cargo test"), "{tests}");
}
