//! Paper 003's three coding schemes on the host (`render --scheme`): the occlusion
//! graph of one view derived from the library's own coverage, codes built for it with
//! the library's searches, and the frame drawn by `SchemeRenderer` (schemes 1 and 2)
//! or by the code-fill engine (scheme 3, the default).
//!
//! The graph of a view: at each pixel, the drawn faces covering its centre (each face
//! scan-converted alone by the library, so coverage is exactly the engines'), nearest
//! first (the Z-buffer's visible face first, the rest by the f64 reference's depth at
//! the centre). Each distinct chain is a path; a chain that is an ordered part of a
//! longer one is dropped. Scenes without a consistent order (interpenetration) give
//! two chains that order a pair differently: the library's `OrderConflict`.

use std::collections::HashMap;
use std::fmt;
use std::time::Instant;

use fixed::types::extra::{LeEqU32, U0, U1, U10, U11, U12, U2, U3, U4, U5, U6, U7, U8, U9};
use pbuffer::codes::{
    coset_path_codes, find_combination_codes, level_node_codes, CombinationScheme, ExtendedHamming,
    OcclusionGraph, PathScheme,
};
use pbuffer::mesh::Mesh;
use pbuffer::render::{SchemeCoding, SchemeRenderer, ScreenSegments};
use pbuffer::{Error, MonoPalette, SchemeViolation};

use crate::frame::{CameraSpec, CullSpec, EngineSpec, Frame, MeshData, ModeSpec, RenderSpec};
use crate::pipeline::render_frame;
use crate::reference3d::reference_frame;
use crate::setup::{
    camera, AdjacencyStorage, Collect, FrameInputs, IdBuffers, Measured, MeshArrays, PackedFrame,
    SceneStorage, EDGES, POLY,
};

/// Code width capacity on the host: the library's largest.
pub const WIDTH: usize = 128;
/// Colour-table rows on the host (32 bytes each).
pub const TABLE: usize = 1 << 13;
/// Candidate codes the scheme-1 search may try per width before giving up on it and
/// trying one bit more (about a second per width on a graph of a hundred paths).
pub const SEARCH_TRIALS: u64 = 20_000;

/// Which of the paper's schemes draws the frame (`--scheme`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SchemeSpec {
    /// Scheme 3: weight-1 codes in a BSP tree's depth order, priority encoder (the
    /// code-fill engine as it is).
    #[default]
    Priority,
    /// Scheme 1: combination codes and a colour table, for this view's graph.
    Combination,
    /// Scheme 2: extended-Hamming node codes, a code per path, a colour table.
    Path,
}

impl SchemeSpec {
    /// Every scheme, in the order the `--scheme` help lists them.
    pub const ALL: [SchemeSpec; 3] = [
        SchemeSpec::Combination,
        SchemeSpec::Path,
        SchemeSpec::Priority,
    ];

    /// The scheme's `--scheme` name.
    pub fn name(self) -> &'static str {
        match self {
            SchemeSpec::Combination => "combination",
            SchemeSpec::Path => "path",
            SchemeSpec::Priority => "priority",
        }
    }

    /// The scheme named `name`.
    pub fn by_name(name: &str) -> Option<SchemeSpec> {
        SchemeSpec::ALL.into_iter().find(|s| s.name() == name)
    }
}

/// Why a scheme frame was not drawn: the library refused (a named condition), or the
/// host could not set up the view.
#[derive(Debug, Clone, PartialEq)]
pub enum SchemeError {
    /// The library's error: `Error::Scheme(..)` names the violated condition.
    Library(Error),
    /// A host problem (mesh, camera).
    Host(String),
}

impl fmt::Display for SchemeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SchemeError::Library(e) => write!(f, "{e}"),
            SchemeError::Host(e) => f.write_str(e),
        }
    }
}

impl From<Error> for SchemeError {
    fn from(e: Error) -> Self {
        SchemeError::Library(e)
    }
}

impl From<String> for SchemeError {
    fn from(e: String) -> Self {
        SchemeError::Host(e)
    }
}

/// The occlusion graph of one view, and the path (screen segment) of each pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewGraph {
    pub width: usize,
    pub height: usize,
    /// Faces of the mesh (the graph's surfaces).
    pub faces: usize,
    /// The paths, each nearest face first.
    pub paths: Vec<Vec<u16>>,
    /// Per pixel (row-major): a path holding the pixel's chain (0 where none covers).
    pub pixel_path: Vec<usize>,
    /// Pixels whose centre some drawn face covers.
    pub covered: usize,
}

impl ScreenSegments for ViewGraph {
    fn path(&self, x: u16, y: u16) -> usize {
        let at = usize::from(y) * self.width + usize::from(x);
        self.pixel_path.get(at).copied().unwrap_or(0)
    }
}

/// The graph of `mesh` seen by `cam` at `spec`'s size, sub-pixel bits and culling.
pub fn view_graph(
    mesh: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
) -> Result<ViewGraph, String> {
    let (w, h) = (spec.width, spec.height);
    let surfaces = RenderSpec {
        engine: EngineSpec::ZBuffer,
        mode: ModeSpec::Surfaces,
        band: h,
        ..spec.clone()
    };
    let nearest = render_frame(mesh, cam, &surfaces)?.ids;
    // Each drawn face alone, with every vertex kept: the fixed-point view depends on
    // the extent of the positions, so coverage is exactly as in the whole frame.
    let alone = RenderSpec {
        cull: CullSpec::Off,
        ..surfaces.clone()
    };
    let mut chains: Vec<Vec<u16>> = vec![Vec::new(); w * h];
    for f in drawn_faces(mesh, cam, spec)? {
        let single = MeshData {
            vertices: mesh.vertices.clone(),
            faces: vec![mesh.faces[f].clone()],
        };
        let ids = render_frame(&single, cam, &alone)?.ids;
        for (chain, _) in chains.iter_mut().zip(&ids).filter(|(_, &id)| id != 0) {
            chain.push(f as u16);
        }
    }
    let reference = reference_frame(mesh, cam, spec)?;
    for (at, chain) in chains.iter_mut().enumerate().filter(|(_, c)| c.len() > 1) {
        let (sx, sy) = ((at % w) as f64 + 0.5, (at / w) as f64 + 0.5);
        let depth = |f: u16| {
            reference
                .face_depth(usize::from(f), sx, sy)
                .unwrap_or(f64::MAX)
        };
        chain.sort_by(|&a, &b| depth(a).total_cmp(&depth(b)).then(a.cmp(&b)));
        // The Z-buffer's visible face first: the frame must match it.
        if let Some(k) = chain.iter().position(|&f| u32::from(f) + 1 == nearest[at]) {
            let f = chain.remove(k);
            chain.insert(0, f);
        }
    }
    Ok(paths_of(w, h, mesh.faces.len(), &chains))
}

/// The faces the library draws in this view (not culled), by its own test.
fn drawn_faces(mesh: &MeshData, cam: &CameraSpec, spec: &RenderSpec) -> Result<Vec<usize>, String> {
    let arrays = MeshArrays::new(mesh);
    let lib = Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets)
        .map_err(|e| format!("mesh: {e}"))?;
    let mut storage = AdjacencyStorage::new(&arrays);
    let adjacency = storage.build(&lib, spec.crease_deg)?;
    let cull = match spec.cull {
        CullSpec::On => true,
        CullSpec::Off => false,
        CullSpec::Auto => adjacency.is_closed(),
    };
    let view = camera(cam)?.viewpoint();
    Ok((0..lib.face_count())
        .filter(|&f| !cull || lib.faces_viewpoint(f, &view))
        .collect())
}

/// The maximal chains as paths, and each pixel's path.
fn paths_of(w: usize, h: usize, faces: usize, chains: &[Vec<u16>]) -> ViewGraph {
    let mut distinct: Vec<&Vec<u16>> = chains.iter().filter(|c| !c.is_empty()).collect();
    distinct.sort_by(|a, b| b.len().cmp(&a.len()).then(a.cmp(b)));
    distinct.dedup();
    let mut paths: Vec<Vec<u16>> = Vec::new();
    let mut path_of: HashMap<&[u16], usize> = HashMap::new();
    for chain in distinct {
        let holder = paths.iter().position(|p| ordered_part(chain, p));
        let index = holder.unwrap_or_else(|| {
            paths.push(chain.clone());
            paths.len() - 1
        });
        path_of.insert(chain, index);
    }
    let pixel_path = chains
        .iter()
        .map(|c| path_of.get(c.as_slice()).copied().unwrap_or(0))
        .collect();
    ViewGraph {
        width: w,
        height: h,
        faces,
        paths,
        pixel_path,
        covered: chains.iter().filter(|c| !c.is_empty()).count(),
    }
}

/// Whether `part` is `whole` with some faces left out, in the same order.
fn ordered_part(part: &[u16], whole: &[u16]) -> bool {
    let mut rest = whole.iter();
    part.iter().all(|f| rest.any(|g| g == f))
}

/// What a scheme needed for a view.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SchemeFigures {
    /// Paths of the view's graph.
    pub paths: usize,
    /// The most faces on one path.
    pub longest_path: usize,
    /// Code width in bits (scheme 2: the Hamming codeword length).
    pub width: u32,
    /// Colour-table rows.
    pub table_rows: usize,
    /// Scheme 1: widths the search gave up on, undecided, before the one found (0:
    /// the width is the least that works, every narrower one proven impossible).
    pub undecided_widths: u32,
}

/// The schemes drawn through a colour table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TableScheme {
    /// Scheme 1.
    Combination,
    /// Scheme 2.
    Path,
}

/// Builds `scheme`'s codes for `graph` and calls `draw` with them.
///
/// Errors: the library's, naming the condition that fails: `OrderConflict` for
/// chains in different orders, `CyclicOrder` (scheme 2's depth levels),
/// `NoAssignment`/`SearchGaveUp`/`CodeTooWide`, `CapacityExceeded` for a table of more
/// than [`TABLE`] rows or more paths than scheme 2's cosets.
pub fn with_coding<R>(
    graph: &ViewGraph,
    scheme: TableScheme,
    draw: impl FnOnce(&SchemeCoding<'_, WIDTH, TABLE>) -> R,
) -> Result<(R, SchemeFigures), Error> {
    let paths: Vec<&[u16]> = graph.paths.iter().map(Vec::as_slice).collect();
    let occlusion = OcclusionGraph::new(graph.faces, &paths)?;
    let mut figures = SchemeFigures {
        paths: paths.len(),
        longest_path: occlusion.longest_path(),
        ..SchemeFigures::default()
    };
    let mut codes = vec![0u128; graph.faces];
    let mut path_codes = vec![0u128; paths.len()];
    let coding = match scheme {
        TableScheme::Combination => {
            figures.undecided_widths = combination_codes(&occlusion, &mut codes)?;
            let scheme = CombinationScheme::<WIDTH>::new(occlusion, &codes)?;
            Box::new(SchemeCoding::combination(scheme)?)
        }
        TableScheme::Path => {
            let hamming = path_hamming(&occlusion, &mut codes, &mut path_codes)?;
            let scheme = PathScheme::<WIDTH>::new(occlusion, hamming, &codes, &path_codes)?;
            Box::new(SchemeCoding::path(scheme, graph)?)
        }
    };
    figures.width = coding.width();
    figures.table_rows = coding.table().len();
    Ok((draw(&coding), figures))
}

/// Scheme-1 codes of the least width the search reaches: widths from the corollary's
/// bound up, each searched with a budget of [`SEARCH_TRIALS`]; after a width the
/// search gave up on, the next tried is a quarter wider (so a large graph costs a
/// few budgets, not one per bit). Returns how many narrower widths were left
/// undecided (the library's `minimal_combination_codes` stops at the first).
fn combination_codes(graph: &OcclusionGraph<'_>, codes: &mut [u128]) -> Result<u32, Error> {
    let mut undecided = 0;
    let mut last = None;
    let mut width = graph.largest_union().max(1);
    while width <= WIDTH {
        match find_combination_codes::<WIDTH>(graph, width as u32, codes, SEARCH_TRIALS) {
            Ok(()) => return Ok(undecided),
            Err(e @ Error::Scheme(SchemeViolation::SearchGaveUp { .. })) => {
                undecided += 1;
                last = Some(e);
                width += (width / 4).max(1);
            }
            Err(e @ Error::Scheme(SchemeViolation::NoAssignment { .. })) => {
                last = Some(e);
                width += 1;
            }
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or(Error::CodeTooWide {
        needed: graph.largest_union(),
        capacity: WIDTH,
    }))
}

/// The shortest extended Hamming code with a data bit per depth level and a coset
/// per path, its level codes in `data` and coset codes in `path_codes`.
fn path_hamming(
    graph: &OcclusionGraph<'_>,
    data: &mut [u128],
    path_codes: &mut [u128],
) -> Result<ExtendedHamming, Error> {
    let mut last = None;
    for hamming in (3..=7).filter_map(ExtendedHamming::with_order) {
        let built = level_node_codes(graph, hamming, data)
            .and_then(|()| coset_path_codes::<WIDTH>(graph, hamming, data, path_codes));
        match built {
            Ok(()) => return Ok(hamming),
            Err(e @ (Error::CodeTooWide { .. } | Error::CapacityExceeded { .. })) => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or(Error::CodeTooWide {
        needed: 0,
        capacity: WIDTH,
    }))
}

/// The frame of `mesh` drawn with `scheme`, and what the scheme needed: scheme 3 is
/// the code-fill engine (`--engine codefill`); schemes 1 and 2 derive this view's
/// graph and draw with `SchemeRenderer`. Figures `scheme_*` are added to the frame.
pub fn render_scheme(
    mesh: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    scheme: SchemeSpec,
) -> Result<(Frame, SchemeFigures), SchemeError> {
    let scheme = match scheme {
        SchemeSpec::Combination => TableScheme::Combination,
        SchemeSpec::Path => TableScheme::Path,
        SchemeSpec::Priority => {
            let frame = render_frame(mesh, cam, spec)?;
            let figures = SchemeFigures {
                width: frame.stat("code_bits") as u32,
                ..SchemeFigures::default()
            };
            return Ok((frame, figures));
        }
    };
    let start = Instant::now();
    let graph = view_graph(mesh, cam, spec)?;
    let setup_us = start.elapsed().as_micros() as u64;
    let (frame, figures) = with_coding(&graph, scheme, |coding| draw(mesh, cam, spec, coding))?;
    let mut frame = frame?;
    frame.stats.extend([
        ("scheme_paths".into(), figures.paths as u64),
        ("scheme_longest_path".into(), figures.longest_path as u64),
        ("scheme_code_bits".into(), u64::from(figures.width)),
        ("scheme_table_rows".into(), figures.table_rows as u64),
        (
            "scheme_undecided_widths".into(),
            u64::from(figures.undecided_widths),
        ),
        ("scheme_graph_us".into(), setup_us),
    ]);
    Ok((frame, figures))
}

/// `mesh` drawn by `SchemeRenderer` with `coding` (one code per mesh face).
pub fn draw<const W: usize, const E: usize>(
    mesh: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    coding: &SchemeCoding<'_, W, E>,
) -> Result<Frame, SchemeError> {
    match spec.subpixel {
        0 => draw_s::<U0, W, E>(mesh, cam, spec, coding),
        1 => draw_s::<U1, W, E>(mesh, cam, spec, coding),
        2 => draw_s::<U2, W, E>(mesh, cam, spec, coding),
        3 => draw_s::<U3, W, E>(mesh, cam, spec, coding),
        4 => draw_s::<U4, W, E>(mesh, cam, spec, coding),
        5 => draw_s::<U5, W, E>(mesh, cam, spec, coding),
        6 => draw_s::<U6, W, E>(mesh, cam, spec, coding),
        7 => draw_s::<U7, W, E>(mesh, cam, spec, coding),
        8 => draw_s::<U8, W, E>(mesh, cam, spec, coding),
        9 => draw_s::<U9, W, E>(mesh, cam, spec, coding),
        10 => draw_s::<U10, W, E>(mesh, cam, spec, coding),
        11 => draw_s::<U11, W, E>(mesh, cam, spec, coding),
        12 => draw_s::<U12, W, E>(mesh, cam, spec, coding),
        s => Err(SchemeError::Host(format!(
            "--subpixel {s}: must be 0 to 12"
        ))),
    }
}

fn draw_s<Frac: LeEqU32, const W: usize, const E: usize>(
    data: &MeshData,
    cam: &CameraSpec,
    spec: &RenderSpec,
    coding: &SchemeCoding<'_, W, E>,
) -> Result<Frame, SchemeError> {
    let mut storage = SceneStorage::new(data);
    let FrameInputs {
        mesh,
        adjacency,
        camera,
        settings,
        build_bytes,
    } = storage.scene(cam, spec)?;
    let mut buffers = IdBuffers::for_mesh(spec, mesh.vertices().len(), &mesh, &adjacency);
    let (w, h) = (spec.width, spec.height);
    // Codes for the band and its apron: one pass over the faces per band.
    let mut codes = vec![0u128; buffers.ids.len().max(w)];
    let mut ws = buffers.workspace();
    let lent = ws.bytes()
        + std::mem::size_of_val(adjacency.edges())
        + std::mem::size_of_val(codes.as_slice())
        + std::mem::size_of_val(coding);
    let mut renderer = Box::new(SchemeRenderer::<Frac, EDGES, POLY>::new());
    let mut target = PackedFrame::new(w, h);
    let mut probe = Collect::new(w, h);
    let start = Instant::now();
    let stats = renderer
        .render(
            &mesh,
            &adjacency,
            &camera,
            &settings,
            &mut ws,
            coding,
            &mut codes,
            &MonoPalette::default(),
            &mut target,
            &mut probe,
        )
        .map_err(SchemeError::Library)?;
    let time_us = start.elapsed().as_micros() as u64;
    let working = lent + std::mem::size_of::<SchemeRenderer<Frac, EDGES, POLY>>();
    let measured = Measured {
        target,
        probe,
        stats,
        time_us,
    };
    Ok(measured.frame(working, build_bytes))
}
