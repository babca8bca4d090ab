//! The harness of the `bench` binary: instruction counts (Ir) from valgrind callgrind.
//!
//! The binary re-executes itself under `valgrind --tool=callgrind` once per job
//! (`bench --child ID`), with collection switched on only inside [`measured_region`](crate::measure::measured_region)
//! (`--toggle-collect=*measured_region*`); the child prints `pixels=N` for the frame
//! it drew, and the parent reads the instruction total from the callgrind output.
//! Also the report tables and their common header and checks.

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, ExitCode};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use crate::tools::progress::Progress;

/// The first line `cmd arg` prints (`--version`), or `None` when it cannot run.
pub fn tool_version(cmd: &str, arg: &str) -> Option<String> {
    let out = Command::new(cmd).arg(arg).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// The CPU named in `/proc/cpuinfo`, for the report header.
pub fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into())
}

/// What one child job reported.
pub struct Measured {
    /// Instructions executed inside `measured_region`.
    pub ir: u64,
    /// Pixels set in the frame, as reported by the child.
    pub pixels: usize,
}

/// Runs child job `id` of `exe` under callgrind, its output file in `dir`.
pub fn callgrind(exe: &Path, dir: &Path, id: &str) -> Result<Measured, String> {
    callgrind_with(exe, dir, id, &[])
}

/// [`callgrind`] with extra `--toggle-collect` patterns: functions called inside
/// [`measured_region`] whose instructions are left out (collection toggles off on
/// entry and back on at exit).
pub fn callgrind_with(
    exe: &Path,
    dir: &Path,
    id: &str,
    excluded: &[&str],
) -> Result<Measured, String> {
    let out_file = dir.join(format!("{}.callgrind", id.replace('/', "_")));
    let out = Command::new("valgrind")
        .arg("--tool=callgrind")
        .arg(format!("--callgrind-out-file={}", out_file.display()))
        .arg("--collect-atstart=no")
        .arg("--toggle-collect=*measured_region*")
        .args(excluded.iter().map(|p| format!("--toggle-collect={p}")))
        .arg(exe)
        .arg("--child")
        .arg(id)
        .output()
        .map_err(|e| format!("cannot run valgrind: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "valgrind run for {id} failed ({}):\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    let stdout = String::from_utf8_lossy(&out.stdout);
    let pixels = stdout
        .lines()
        .find_map(|l| l.strip_prefix("pixels="))
        .and_then(|v| v.trim().parse().ok())
        .ok_or_else(|| format!("child {id} printed no pixel count: {stdout}"))?;
    let text = std::fs::read_to_string(&out_file)
        .map_err(|e| format!("cannot read {}: {e}", out_file.display()))?;
    let total = |key: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(key))
            .and_then(|v| v.split_whitespace().next())
            .and_then(|v| v.parse::<u64>().ok())
    };
    let ir = total("totals:")
        .or_else(|| total("summary:"))
        .ok_or_else(|| format!("no totals in {}", out_file.display()))?;
    std::fs::remove_file(&out_file).ok();
    Ok(Measured { ir, pixels })
}

/// Runs the jobs under callgrind, `jobs` at a time.
pub fn measure_all(ids: &[String], jobs: usize) -> Result<Vec<Measured>, String> {
    measure_all_with(ids, jobs, &[])
}

/// [`measure_all`] with the extra patterns of [`callgrind_with`].
pub fn measure_all_with(
    ids: &[String],
    jobs: usize,
    excluded: &[&str],
) -> Result<Vec<Measured>, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let dir = std::env::temp_dir().join(format!("pbuffer-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let next = AtomicUsize::new(0);
    let progress = Progress::new("bench: callgrind", "job", ids.len());
    let results: Mutex<Vec<Option<Result<Measured, String>>>> =
        Mutex::new((0..ids.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..jobs.max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= ids.len() {
                    break;
                }
                let r = callgrind_with(&exe, &dir, &ids[i], excluded);
                progress.step();
                results.lock().unwrap()[i] = Some(r);
            });
        }
    });
    std::fs::remove_dir_all(&dir).ok();
    results
        .into_inner()
        .unwrap()
        .into_iter()
        .map(|r| r.expect("every job ran"))
        .collect()
}

/// A report table, printed as aligned text or as markdown.
pub struct Table {
    pub title: String,
    pub header: Vec<&'static str>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    pub fn text(&self) -> String {
        let n = self.header.len();
        let mut w: Vec<usize> = self.header.iter().map(|h| h.len()).collect();
        for r in &self.rows {
            for (i, c) in r.iter().enumerate() {
                w[i] = w[i].max(c.len());
            }
        }
        let line = |cells: Vec<&str>| {
            let mut s = String::from(" ");
            for (i, c) in cells.iter().enumerate() {
                if i == 0 {
                    let _ = write!(s, " {:<w$}", c, w = w[i]);
                } else {
                    let _ = write!(s, "  {:>w$}", c, w = w[i]);
                }
            }
            s.push('\n');
            s
        };
        let mut s = format!("{}\n", self.title);
        s += &line(self.header.clone());
        s += &format!(
            "  {}\n",
            "-".repeat(w.iter().sum::<usize>() + 2 * (n - 1) + 1)
        );
        for r in &self.rows {
            s += &line(r.iter().map(String::as_str).collect());
        }
        s
    }

    pub fn markdown(&self) -> String {
        let mut s = format!("### {}\n\n| {} |\n|", self.title, self.header.join(" | "));
        for i in 0..self.header.len() {
            s += if i == 0 { ":---|" } else { "---:|" };
        }
        s.push('\n');
        for r in &self.rows {
            s += &format!("| {} |\n", r.join(" | "));
        }
        s
    }
}

/// `n` with thousands separators: 1,234,567.
pub fn thousands(n: u64) -> String {
    let d = n.to_string();
    let mut groups: Vec<&str> = d
        .as_bytes()
        .rchunks(3)
        .map(|g| std::str::from_utf8(g).expect("ASCII digits"))
        .collect();
    groups.reverse();
    groups.join(",")
}

/// `a / b` to two decimals (`-` when `b` is 0).
pub fn ratio(a: u64, b: u64) -> String {
    if b == 0 {
        "-".into()
    } else {
        format!("{:.2}", a as f64 / b as f64)
    }
}

/// The first lines of a report: the command that makes it (with `markdown_flag` in
/// markdown) and the machine.
pub fn report_header(command: &str, markdown_flag: &str, machine: &str, markdown: bool) -> String {
    if markdown {
        format!("Generated by `{command} {markdown_flag}`.\n\nMachine: {machine}.\n\n")
    } else {
        format!("pbuffer bench ({command})\nmachine: {machine}\n\n")
    }
}

/// Prints a report with its checks and failures; the exit status is 1 on a failure,
/// 2 when nothing could be measured (no valgrind), else success.
pub fn finish_report(
    mut out: String,
    checks: &[String],
    failures: &[String],
    markdown: bool,
    measured: bool,
) -> ExitCode {
    let (heading, bullet) = if markdown {
        ("### Checks\n\n", "- ")
    } else {
        ("checks:\n", "  ")
    };
    out += heading;
    for c in checks {
        let _ = writeln!(out, "{bullet}{c}");
    }
    for f in failures {
        let _ = writeln!(out, "{bullet}FAILURE: {f}");
    }
    print!("{out}");
    if !failures.is_empty() {
        ExitCode::from(1)
    } else if !measured {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    }
}
