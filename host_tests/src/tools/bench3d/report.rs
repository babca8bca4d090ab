//! `bench --scene3d`: every frame drawn and checked natively, then the callgrind jobs,
//! then one table per (model, size).

use std::process::ExitCode;

use super::{draw, refusal_text, Drawn, Engine, Job, Outcome, Refusal, Renderer, View};
use super::{CODE_WORDS, EMPTY, MODELS, POLY, ROOMIER, SIZES};
use crate::frame::{EngineSpec, RenderSpec};
use crate::image::{count_diff, count_set};
use crate::pipeline::render_frame;
use crate::tools::callgrind::{
    cpu_model, finish_report, measure_all, ratio, report_header, thousands, tool_version, Measured,
    Table,
};
use crate::tools::progress::Progress;

/// A table row after the native run.
struct Row {
    job: Job,
    outcome: Outcome,
    /// When the firmware capacities refused the frame: the first roomier (active
    /// faces, active edges) that drew it, and that frame.
    roomier: Option<((usize, usize), Drawn)>,
}

impl Row {
    /// The frame this row drew, with the firmware or the roomier capacities.
    fn drawn(&self) -> Option<&Drawn> {
        self.outcome
            .as_ref()
            .ok()
            .or(self.roomier.as_ref().map(|r| &r.1))
    }
}

/// Draws every renderer's frame of `view` natively.
fn draw_rows(view: &View, model: &'static str) -> Vec<Row> {
    Renderer::ALL
        .iter()
        .map(|&renderer| {
            let outcome = draw(view, renderer, None);
            let refused = matches!(outcome, Err(Refusal::Library(_)));
            let roomier = (refused
                && matches!(
                    renderer.engine,
                    Engine::CodeFill | Engine::CodeFillCrossings | Engine::Scanline
                ))
            .then(|| {
                (0..ROOMIER.len())
                    .find_map(|i| draw(view, renderer, Some(i)).ok().map(|d| (ROOMIER[i], d)))
            })
            .flatten();
            Row {
                job: Job {
                    model,
                    size: view.size,
                    renderer,
                },
                outcome,
                roomier,
            }
        })
        .collect()
}

/// Checks that every library frame of a view is the same picture (and render_frame's),
/// and tells how far the baseline is from it.
fn check_rows(view: &View, rows: &[Row], failures: &mut Vec<String>) -> Result<String, String> {
    let (w, h) = view.size;
    // Two pictures: in a BSP tree's depth order, and with depths compared (scan-line,
    // Z-buffer), each render_frame's for its engine.
    let spec = |engine| RenderSpec {
        engine,
        ..view.spec()
    };
    let ordered = render_frame(&view.data, &view.camera, &spec(EngineSpec::CodeFill))?.packed;
    let compared = render_frame(&view.data, &view.camera, &spec(EngineSpec::Scanline))?.packed;
    let mut library = 0;
    for row in rows {
        let Some(d) = row.drawn() else { continue };
        if row.job.renderer.engine == Engine::Baseline {
            continue;
        }
        library += 1;
        let reference = match row.job.renderer.engine {
            Engine::CodeFill | Engine::CodeFillCrossings => &ordered,
            _ => &compared,
        };
        if d.bytes != *reference {
            failures.push(format!(
                "{}: the frame differs from render_frame's in {} px",
                row.job.key(),
                count_diff(&d.bytes, reference, w, h)
            ));
        }
    }
    let baseline = rows
        .iter()
        .find(|r| r.job.renderer.engine == Engine::Baseline)
        .and_then(Row::drawn)
        .map_or(0, |d| count_diff(&d.bytes, &compared, w, h));
    let between = count_diff(&ordered, &compared, w, h);
    Ok(format!(
        "{} {w} x {h}: {library} library frames identical to render_frame's for their engine (depth order / depths compared, which differ in {between} px): {}; f32 baseline differs from the depth-compared frame in {baseline} of {} px",
        rows[0].job.model,
        if failures.iter().any(|f| f.starts_with(&format!("{}/{w}x{h}/", rows[0].job.model))) {
            "NO"
        } else {
            "yes"
        },
        w * h
    ))
}

/// `bench --scene3d`: the 3-D section alone.
pub fn run(markdown: bool, jobs: usize) -> ExitCode {
    let mut failures = Vec::new();
    let mut checks = Vec::new();
    let mut sections: Vec<Vec<Row>> = Vec::new();
    let progress = Progress::new("bench: 3-D", "scene", MODELS.len() * SIZES.len());
    for model in MODELS {
        for size in SIZES {
            let view = match View::load(model, size) {
                Ok(v) => v,
                Err(e) => {
                    eprintln!("bench: {model}: {e}");
                    return ExitCode::from(2);
                }
            };
            let rows = draw_rows(&view, model);
            for row in &rows {
                if let Err(Refusal::Setup(e)) = &row.outcome {
                    eprintln!("bench: {}: {e}", row.job.key());
                    return ExitCode::from(2);
                }
            }
            match check_rows(&view, &rows, &mut failures) {
                Ok(c) => checks.push(c),
                Err(e) => {
                    eprintln!("bench: {model}: {e}");
                    return ExitCode::from(2);
                }
            }
            sections.push(rows);
            progress.step();
        }
    }

    // Instruction counts, for the frames the firmware capacities drew.
    let valgrind = tool_version("valgrind", "--version");
    let mut ids = vec![format!("scene3d/{EMPTY}")];
    for row in sections.iter().flatten() {
        if row.outcome.is_ok() {
            ids.push(format!("scene3d/{}", row.job.key()));
        }
    }
    let measured = match &valgrind {
        Some(_) => match measure_all(&ids, jobs) {
            Ok(m) => Some(m),
            Err(e) => {
                eprintln!("bench: {e}");
                return ExitCode::from(2);
            }
        },
        None => None,
    };
    let ir_of = |job: &Job| -> Option<&Measured> {
        let id = format!("scene3d/{}", job.key());
        let i = ids.iter().position(|x| *x == id)?;
        measured.as_ref().map(|m| &m[i])
    };
    for row in sections.iter().flatten() {
        let (Some(m), Ok(d)) = (ir_of(&row.job), &row.outcome) else {
            continue;
        };
        let px = count_set(&d.bytes, row.job.size.0, row.job.size.1);
        if m.pixels != px {
            failures.push(format!(
                "{}: under valgrind {} pixels set, natively {px}",
                row.job.key(),
                m.pixels
            ));
        }
    }

    let rustc = tool_version("rustc", "--version").unwrap_or_else(|| "rustc: unknown".into());
    let machine = format!(
        "{}; {}; {} ({})",
        valgrind.as_deref().unwrap_or("valgrind: not found"),
        rustc,
        cpu_model(),
        std::env::consts::ARCH,
    );
    let mut out = report_header(
        "cargo run --profile figures -p host_tests --bin bench -- --scene3d",
        "--markdown",
        &machine,
        markdown,
    );
    for rows in &sections {
        let table = section_table(rows, &ir_of);
        out += &if markdown {
            table.markdown()
        } else {
            table.text()
        };
        out.push('\n');
    }
    checks.push(match &measured {
        Some(m) => format!("measurement overhead (empty region): {} Ir", m[0].ir),
        None => "valgrind not found: instruction counts skipped".into(),
    });
    finish_report(out, &checks, &failures, markdown, measured.is_some())
}

/// The table of one (model, size).
fn section_table<'m>(rows: &[Row], ir_of: &dyn Fn(&Job) -> Option<&'m Measured>) -> Table {
    let first = &rows[0].job;
    let (w, h) = first.size;
    let stats = rows
        .iter()
        .filter(|r| r.job.renderer.engine == Engine::CodeFill)
        .find_map(Row::drawn)
        .map(|d| d.stats)
        .unwrap_or_default();
    let base_ir = rows
        .iter()
        .find(|r| r.job.renderer.engine == Engine::Baseline)
        .and_then(|r| ir_of(&r.job))
        .map(|m| m.ir);
    let body = rows
        .iter()
        .map(|row| {
            let ir = row.outcome.as_ref().ok().and(ir_of(&row.job)).map(|m| m.ir);
            let (ir_cell, ram) = match (&row.outcome, &row.roomier) {
                (Ok(d), _) => (ir.map_or("-".into(), thousands), thousands(d.working_ram as u64)),
                (Err(r), Some(((faces, edges), d))) => (
                    format!(
                        "{}; draws with CodeFillRenderer<U4, {CODE_WORDS}, {faces}, {edges}, {POLY}>",
                        refusal_text(r)
                    ),
                    format!("({})", thousands(d.working_ram as u64)),
                ),
                (Err(r), None) => (refusal_text(r), "-".into()),
            };
            vec![
                row.job.renderer.label(),
                ir_cell,
                row.drawn()
                    .map_or("-".into(), |d| thousands(d.depth_bytes as u64)),
                ram,
                match (ir, base_ir) {
                    (Some(a), Some(b)) => ratio(a, b),
                    _ => "-".into(),
                },
            ]
        })
        .collect();
    Table {
        title: format!(
            "{} at {w} x {h}: {} faces ({} drawn), {} feature edges in this view, widest code {} bits",
            first.model, stats.faces, stats.faces_drawn, stats.feature_edges, stats.code_bits
        ),
        header: vec![
            "renderer",
            "instructions (Ir) / frame",
            "depth buffer bytes",
            "working RAM bytes",
            "ratio vs baseline",
        ],
        rows: body,
    }
}
