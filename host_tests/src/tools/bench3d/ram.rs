//! `bench --ram`: where the code-fill engine's working RAM goes, part by part, for
//! the models and sizes of the `--scene3d` tables (same cameras, dashed, S = 4), in
//! full-frame, 8-row and 1-row bands. Native runs, no callgrind: bytes only.
//!
//! Each part is a buffer the frame needs beyond the framebuffer and the caller's
//! mesh arrays (as the `--scene3d` tables count working RAM), twice: as the bench
//! compiles the renderer (its capacities: [`ACTIVE_FACES`] faces and
//! [`ACTIVE_EDGES`] edges active on a row, a code of `32 x WORDS` bits), and as
//! small as this frame allows (the renderer at the frame's `peak_faces`,
//! `peak_edges` and widest code, [`CodeFillRenderer::bytes_for`]; bit-sliced rows at
//! the widest code). The second is what a firmware compiled for exactly this view
//! would lend; it shows which part a smaller design must remove. The last column
//! leaves out the edge list, which depends only on the mesh and the crease angle:
//! firmware can make it on the host and keep it in flash
//! (`EdgeAdjacency::from_edges`, as `examples/embedded` does).

use std::fmt::Write as _;
use std::mem::{size_of, size_of_val};
use std::process::ExitCode;

use fixed::types::extra::U4;
use pbuffer::{BspTree, CodeFillRenderer, Stats};

use super::{
    code_fill, View, ACTIVE_EDGES, ACTIVE_FACES, CODE_WORDS, MODELS, ORDER_WORDS, POLY, SIZES,
};
use crate::bsp::{with_bsp, DepthRanks};
use crate::setup::{IdBuffers, SceneStorage};
use crate::tools::callgrind::thousands;
use crate::tools::progress::Progress;

/// The goal for suzanne at 400 x 240, dashed: working RAM at most 8 KiB.
const GOAL: usize = 8 * 1024;
/// Room for every model's busiest row (fandisk needs more than the firmware's).
const FACES: usize = 4096;
const EDGES: usize = 16384;

/// One breakdown row: the parts in bytes.
#[derive(Debug, Default, Clone, Copy)]
struct Parts {
    vertices: usize,
    bits: usize,
    order: usize,
    ids: usize,
    lines: usize,
    edge_list: usize,
    /// Bit-sliced row codes: as compiled, and at the frame's widest code.
    sliced: (usize, usize),
    /// The BSP tree's kept storage plus the per-view ranks and walk stack.
    tree: usize,
    /// The renderer struct: as compiled, and at the frame's peaks.
    renderer: (usize, usize),
}

impl Parts {
    fn common(&self) -> usize {
        self.vertices + self.bits + self.order + self.ids + self.lines + self.edge_list + self.tree
    }
    fn compiled(&self) -> usize {
        self.common() + self.sliced.0 + self.renderer.0
    }
    fn needed(&self) -> usize {
        self.common() + self.sliced.1 + self.renderer.1
    }
}

/// Prints the breakdown (a markdown table with `markdown`).
pub fn run(markdown: bool) -> ExitCode {
    let mut out = String::new();
    let mut failed = false;
    let progress = Progress::new("bench --ram", "scene", MODELS.len() * SIZES.len());
    for model in MODELS {
        for size in SIZES {
            let view = match View::load(model, size) {
                Ok(v) => v,
                Err(e) => {
                    eprintln!("bench --ram: {model}: {e}");
                    return ExitCode::FAILURE;
                }
            };
            let (w, h) = size;
            let _ = writeln!(out, "\n### {model} at {w} x {h}\n");
            if markdown {
                let _ = writeln!(
                    out,
                    "| engine, band | vertex cache | face + edge bits | order | ids rows | line rows | edge list | row codes | tree + ranks | renderer | total | total at the frame's needs | the same, edge list in flash |"
                );
                let _ = writeln!(
                    out,
                    "|:---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
                );
            }
            for ordered in [false, true] {
                for band in [h, 8, 1] {
                    match breakdown(&view, ordered, band) {
                        Ok((parts, stats)) => {
                            row(&mut out, markdown, ordered, band, h, &parts, &stats)
                        }
                        Err(e) => {
                            failed = true;
                            let _ = writeln!(out, "{model} {w}x{h} band {band}: {e}");
                        }
                    }
                }
            }
            progress.step();
        }
    }
    println!("{out}");
    // Record sizes, from the renderer's own accounting (a record plus its list slots).
    type One = CodeFillRenderer<U4, 1, 1, 1, POLY>;
    let face = One::bytes_for(1, 0) - One::bytes_for(0, 0);
    let edge = One::bytes_for(0, 1) - One::bytes_for(0, 0);
    println!(
        "records: active face {face} B, active edge {edge} B, mesh edge {} B, vertex cache entry {} B",
        size_of::<pbuffer::MeshEdge>(),
        size_of::<pbuffer::render::ProjectedVertex>()
    );
    println!("goal (issue 4): suzanne 400 x 240 dashed, code fill, working RAM <= {GOAL} bytes");
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

fn row(
    out: &mut String,
    markdown: bool,
    ordered: bool,
    band: usize,
    h: usize,
    p: &Parts,
    stats: &Stats,
) {
    let engine = if ordered {
        "BSP order, bit-sliced"
    } else {
        "planes (scan-line), crossings"
    };
    let band = if band == h {
        "full frame".to_string()
    } else {
        format!("{band} rows")
    };
    let n = |v: usize| thousands(v as u64);
    let pair = |(a, b): (usize, usize)| {
        if a == b {
            n(a)
        } else {
            format!("{} ({})", n(a), n(b))
        }
    };
    let needs = format!(
        "{} ({} faces, {} edges, {} bits)",
        n(p.needed()),
        stats.peak_faces,
        stats.peak_edges,
        stats.code_bits
    );
    let cells = [
        format!("{engine}, {band}"),
        n(p.vertices),
        n(p.bits),
        n(p.order),
        n(p.ids),
        n(p.lines),
        n(p.edge_list),
        pair(p.sliced),
        n(p.tree),
        pair(p.renderer),
        n(p.compiled()),
        needs,
        n(p.needed() - p.edge_list),
    ];
    if markdown {
        let _ = writeln!(out, "| {} |", cells.join(" | "));
    } else {
        let _ = writeln!(out, "{}", cells.join("  "));
    }
}

/// Draws the view once with the code-fill engine (planes, or a BSP tree's order with
/// bit-sliced rows) in bands of `band` rows and returns its parts and stats.
fn breakdown(view: &View, ordered: bool, band: usize) -> Result<(Parts, Stats), String> {
    match view.size {
        (400, 240) => sized::<400, 240, { pbuffer::packed_len(400, 240) }>(view, ordered, band),
        (128, 64) => sized::<128, 64, { pbuffer::packed_len(128, 64) }>(view, ordered, band),
        (w, h) => Err(format!("no framebuffer type for {w} x {h}")),
    }
}

fn sized<const W: usize, const H: usize, const N: usize>(
    view: &View,
    ordered: bool,
    band: usize,
) -> Result<(Parts, Stats), String> {
    let mut storage = SceneStorage::new(&view.data);
    let scene = storage.scene(&view.camera, &view.spec())?;
    let measure = |tree: Option<(&BspTree<'_>, usize)>| -> Result<(Parts, Stats), String> {
        // The frame as `--scene3d` draws it, with room for every model's busiest row.
        let drawn = match tree {
            Some(_) => code_fill::<W, H, N, ORDER_WORDS, FACES, EDGES>(&scene, tree, band, true),
            None => code_fill::<W, H, N, CODE_WORDS, FACES, EDGES>(&scene, None, band, false),
        }
        .map_err(|e| e.to_string())?;
        let stats = drawn.stats;
        // The same buffers, sized as `code_fill` sizes them, taken apart.
        let surfaces = tree.map_or(scene.mesh, |(t, _)| t.fragments());
        let faces = scene.mesh.face_count();
        let edges = scene.adjacency.edges().len();
        let buffers = IdBuffers::sized(W, H, band, surfaces.vertices().len(), faces, edges);
        let mut parts = Parts {
            vertices: size_of_val(buffers.vertices.as_slice()),
            bits: size_of_val(buffers.drawn.as_slice()) + size_of_val(buffers.features.as_slice()),
            order: surfaces.face_count() * size_of::<u32>(),
            ids: size_of_val(buffers.ids.as_slice()),
            lines: size_of_val(buffers.lines.as_slice()),
            edge_list: size_of_val(scene.adjacency.edges()),
            tree: tree.map_or(0, |(_, kept)| kept) + DepthRanks::new(tree.map(|(t, _)| t)).bytes(),
            ..Parts::default()
        };
        let code_words = (stats.code_bits as usize).div_ceil(32).max(1);
        let (peak_faces, peak_edges) = (stats.peak_faces as usize, stats.peak_edges as usize);
        // `bytes_for` of a one-word code, plus each further word's code and owners.
        let per_word = size_of::<u32>() + 32 * size_of::<u16>();
        let needed = CodeFillRenderer::<U4, 1, 1, 1, POLY>::bytes_for(peak_faces, peak_edges)
            + (code_words - 1) * per_word;
        // As compiled by `bench --scene3d` (a frame that needs more is refused there
        // and drawn by a roomier rung; its table says which), and as `code_fill` just
        // compiled it, with room for every model.
        let (compiled, roomy) = if ordered {
            (
                size_of::<CodeFillRenderer<U4, ORDER_WORDS, ACTIVE_FACES, ACTIVE_EDGES, POLY>>(),
                size_of::<CodeFillRenderer<U4, ORDER_WORDS, FACES, EDGES, POLY>>(),
            )
        } else {
            (
                size_of::<CodeFillRenderer<U4, CODE_WORDS, ACTIVE_FACES, ACTIVE_EDGES, POLY>>(),
                size_of::<CodeFillRenderer<U4, CODE_WORDS, FACES, EDGES, POLY>>(),
            )
        };
        parts.renderer = (compiled, needed);
        if ordered {
            let compiled = CodeFillRenderer::<U4, ORDER_WORDS, 1, 1, POLY>::bit_sliced_len(W);
            let needed = W * code_words + W.div_ceil(32);
            parts.sliced = (4 * compiled, 4 * needed);
        }
        // The parts add up to the working RAM `code_fill` counted.
        let sum = parts.compiled() - compiled + roomy;
        if sum != drawn.working_ram {
            return Err(format!(
                "the parts add up to {sum} bytes, code_fill counted {}",
                drawn.working_ram
            ));
        }
        Ok((parts, stats))
    };
    if ordered {
        with_bsp(&scene.mesh, |tree, figures| {
            measure(Some((tree, figures.kept_bytes)))
        })?
    } else {
        measure(None)
    }
}
