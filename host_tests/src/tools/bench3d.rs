//! The 3-D section of `bench` (`bench --scene3d`): instructions per frame, working RAM
//! and depth-buffer bytes of the library's two visibility engines against the plain
//! f32 P-buffer baseline ([`crate::baseline`]), for every model of [`MODELS`] at every
//! size of [`SIZES`], dashed hidden lines, S = 4, the `paper` pattern, the camera of
//! `render --fit` ([`fit_camera`]).
//!
//! Library rows render into a `PackedFramebuffer<W, H, N>` with no probe, the way
//! firmware calls them: mesh, edge adjacency, camera and the lent buffers are built
//! before the measured region, only the `render` call is inside. The baseline's
//! welding, adjacency and normals are built beforehand; its frame (buffers
//! initialized, faces, edges, packing) is measured.
//!
//! Working RAM is every byte a library renderer needs beyond the framebuffer and the
//! caller's mesh arrays: the lent workspace (`bytes()`), the mesh's edge list and the
//! renderer struct. The adjacency build's weld map and half-edge records are needed
//! once per mesh, not per frame, and are not counted.

use std::convert::Infallible;
use std::mem::{size_of, size_of_val};
use std::path::PathBuf;

use fixed::types::extra::U4;
use pbuffer::order::BspTree;
use pbuffer::render::{Depth, RowCodes};
use pbuffer::{
    packed_len, CodeFillRenderer, Error, MonoPalette, PackedFramebuffer, Stats, Visibility,
    ZBufferRenderer,
};

use crate::baseline::{prepare_baseline, render_prepared};
use crate::bsp::{with_bsp, DepthRanks};
use crate::fit::fit_camera;
use crate::frame::{CameraSpec, MeshData, RenderSpec};
use crate::image::count_set;
use crate::measure::measured_region;
use crate::obj::load_obj;
use crate::setup::{FrameInputs, IdBuffers, SceneStorage};

mod ram;
mod report;
pub use ram::run as run_ram;
pub use report::run;

/// Models, from `../shared/models/` (relative to the workspace root).
pub const MODELS: [&str; 3] = ["suzanne", "beetle", "fandisk"];
/// The calibration job: an empty measured region.
const EMPTY: &str = "empty";
/// Frame sizes: a 400 x 240 memory LCD and a 128 x 64 OLED.
pub const SIZES: [(usize, usize); 2] = [(400, 240), (128, 64)];

/// Vertices of a clipped face (a triangle clipped by six planes has at most nine).
const POLY: usize = 64;
/// Code-fill capacities as firmware would compile them: a 128-bit surface code, 256
/// faces and 1024 edges active on one row.
const CODE_WORDS: usize = 4;
/// In a depth order the code is as wide as the faces active on a row: 512 bits.
const ORDER_WORDS: usize = 16;
const ACTIVE_FACES: usize = 256;
const ACTIVE_EDGES: usize = 1024;
/// Roomier (active faces, active edges), tried in order when the firmware capacities
/// refuse a frame, to report what it needed.
const ROOMIER: [(usize, usize); 4] = [(512, 2048), (1024, 4096), (2048, 8192), (4096, 16384)];
/// Scan-converter edges per face for the Z-buffer engine.
const FACE_EDGES: usize = 64;

/// A visibility engine of the table.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Engine {
    /// The code-fill engine in a BSP tree's depth order (weight-1 codes), bit-sliced
    /// rows (`RowCodes::BitSliced`).
    CodeFill,
    /// The same with the crossing list (`RowCodes::Crossings`).
    CodeFillCrossings,
    /// The code-fill engine without an order: planes where faces overlap.
    Scanline,
    ZBuffer16,
    ZBuffer32,
    /// The f32 baseline of `crate::baseline` (always full frame).
    Baseline,
}

/// A row of the table: an engine and its band height (`None`: one full-frame band).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Renderer {
    pub engine: Engine,
    pub band: Option<usize>,
}

impl Renderer {
    /// The rows of each table, in order; the last is the baseline.
    pub const ALL: [Renderer; 9] = [
        Renderer::new(Engine::CodeFill, None),
        Renderer::new(Engine::CodeFill, Some(8)),
        Renderer::new(Engine::CodeFillCrossings, None),
        Renderer::new(Engine::CodeFillCrossings, Some(8)),
        Renderer::new(Engine::Scanline, None),
        Renderer::new(Engine::Scanline, Some(8)),
        Renderer::new(Engine::ZBuffer32, None),
        Renderer::new(Engine::ZBuffer16, Some(8)),
        Renderer::new(Engine::Baseline, None),
    ];

    const fn new(engine: Engine, band: Option<usize>) -> Self {
        Self { engine, band }
    }

    fn key(self) -> String {
        let engine = match self.engine {
            Engine::CodeFill => "codefill",
            Engine::CodeFillCrossings => "codefill-crossings",
            Engine::Scanline => "scanline",
            Engine::ZBuffer16 => "zbuffer16",
            Engine::ZBuffer32 => "zbuffer32",
            Engine::Baseline => "baseline",
        };
        match self.band {
            Some(b) => format!("{engine}-b{b}"),
            None => engine.into(),
        }
    }

    fn label(self) -> String {
        let engine = match self.engine {
            Engine::CodeFill => format!(
                "CodeFillRenderer<U4, {ORDER_WORDS}, {ACTIVE_FACES}, {ACTIVE_EDGES}, {POLY}>, BSP order, bit-sliced rows"
            ),
            Engine::CodeFillCrossings => format!(
                "CodeFillRenderer<U4, {ORDER_WORDS}, {ACTIVE_FACES}, {ACTIVE_EDGES}, {POLY}>, BSP order, crossings"
            ),
            Engine::Scanline => format!(
                "CodeFillRenderer<U4, {CODE_WORDS}, {ACTIVE_FACES}, {ACTIVE_EDGES}, {POLY}>, planes"
            ),
            Engine::ZBuffer16 => format!("ZBufferRenderer<U4, {FACE_EDGES}, {POLY}>, u16 depth"),
            Engine::ZBuffer32 => format!("ZBufferRenderer<U4, {FACE_EDGES}, {POLY}>, u32 depth"),
            Engine::Baseline => "f32 P-buffer baseline (paper)".into(),
        };
        match self.band {
            Some(b) => format!("{engine}, band {b} rows"),
            None => format!("{engine}, full frame"),
        }
    }
}

/// One measurement: a renderer drawing a model at a size.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
struct Job {
    model: &'static str,
    size: (usize, usize),
    renderer: Renderer,
}

impl Job {
    fn key(&self) -> String {
        let (w, h) = self.size;
        format!("{}/{w}x{h}/{}", self.model, self.renderer.key())
    }

    fn from_key(key: &str) -> Option<Self> {
        let mut parts = key.split('/');
        let (model, size, renderer) = (parts.next()?, parts.next()?, parts.next()?);
        let model = MODELS.into_iter().find(|m| *m == model)?;
        let size = SIZES
            .into_iter()
            .find(|(w, h)| format!("{w}x{h}") == size)?;
        let renderer = Renderer::ALL.into_iter().find(|r| r.key() == renderer)?;
        Some(Self {
            model,
            size,
            renderer,
        })
    }
}

/// A model's mesh and the fitted camera for one size.
struct View {
    data: MeshData,
    camera: CameraSpec,
    size: (usize, usize),
}

impl View {
    fn load(model: &str, size: (usize, usize)) -> Result<Self, String> {
        let manifest = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let path: PathBuf = manifest
            .parent()
            .unwrap_or(manifest)
            .join(format!("../shared/models/{model}.obj"));
        let data = load_obj(&path)?;
        let camera = fit_camera(&data, size.0, size.1);
        Ok(Self { data, camera, size })
    }

    fn spec(&self) -> RenderSpec {
        RenderSpec {
            width: self.size.0,
            height: self.size.1,
            band: self.size.1,
            ..RenderSpec::default()
        }
    }
}

/// One frame drawn and what it needed.
struct Drawn {
    bytes: Vec<u8>,
    stats: Stats,
    working_ram: usize,
    depth_bytes: usize,
}

/// Why a library renderer refused a frame.
enum Refusal {
    Library(Error<Infallible>),
    Setup(String),
}

type Outcome = Result<Drawn, Refusal>;

/// Draws `renderer`'s frame of `view`, only the frame itself in the measured region.
/// `rung` picks a [`ROOMIER`] code-fill capacity instead of the firmware one.
fn draw(view: &View, renderer: Renderer, rung: Option<usize>) -> Outcome {
    match view.size {
        (400, 240) => draw_sized::<400, 240, { packed_len(400, 240) }>(view, renderer, rung),
        (128, 64) => draw_sized::<128, 64, { packed_len(128, 64) }>(view, renderer, rung),
        (w, h) => Err(Refusal::Setup(format!("no framebuffer type for {w} x {h}"))),
    }
}

fn draw_sized<const W: usize, const H: usize, const N: usize>(
    view: &View,
    renderer: Renderer,
    rung: Option<usize>,
) -> Outcome {
    let spec = view.spec();
    if renderer.engine == Engine::Baseline {
        let prepared = prepare_baseline(&view.data);
        let mut frame = None;
        measured_region(&mut || {
            frame = Some(render_prepared(&view.data, &prepared, &view.camera, &spec));
        });
        return Ok(Drawn {
            bytes: frame.map(|f| f.packed).unwrap_or_default(),
            stats: Stats::default(),
            // f32 depth, u32 id, picture byte and lines byte per pixel.
            working_ram: W * H * 10,
            depth_bytes: W * H * 4,
        });
    }
    // What firmware keeps per mesh and per view, built before the measured region.
    let mut storage = SceneStorage::new(&view.data);
    let scene = storage.scene(&view.camera, &spec).map_err(Refusal::Setup)?;
    let band = renderer.band.unwrap_or(H);
    match renderer.engine {
        Engine::ZBuffer16 => z_buffer::<W, H, N, u16>(&scene, band).map_err(Refusal::Library),
        Engine::ZBuffer32 => z_buffer::<W, H, N, u32>(&scene, band).map_err(Refusal::Library),
        Engine::Scanline => code_fill_rung::<W, H, N, CODE_WORDS>(&scene, None, band, false, rung),
        _ => {
            let sliced = renderer.engine == Engine::CodeFill;
            // The tree is built once per mesh, before the measured region; its kept
            // storage counts as working RAM.
            with_bsp(&scene.mesh, |tree, figures| {
                code_fill_rung::<W, H, N, ORDER_WORDS>(
                    &scene,
                    Some((tree, figures.kept_bytes)),
                    band,
                    sliced,
                    rung,
                )
            })
            .map_err(Refusal::Setup)?
        }
    }
}

/// [`code_fill`] with the firmware capacities or a [`ROOMIER`] rung.
fn code_fill_rung<const W: usize, const H: usize, const N: usize, const WORDS: usize>(
    scene: &FrameInputs<'_>,
    bsp: Option<(&BspTree<'_>, usize)>,
    band: usize,
    sliced: bool,
    rung: Option<usize>,
) -> Outcome {
    let (s, b) = (sliced, band);
    let drawn = match rung {
        None => code_fill::<W, H, N, WORDS, ACTIVE_FACES, ACTIVE_EDGES>(scene, bsp, b, s),
        Some(0) => {
            code_fill::<W, H, N, WORDS, { ROOMIER[0].0 }, { ROOMIER[0].1 }>(scene, bsp, b, s)
        }
        Some(1) => {
            code_fill::<W, H, N, WORDS, { ROOMIER[1].0 }, { ROOMIER[1].1 }>(scene, bsp, b, s)
        }
        Some(2) => {
            code_fill::<W, H, N, WORDS, { ROOMIER[2].0 }, { ROOMIER[2].1 }>(scene, bsp, b, s)
        }
        Some(_) => {
            code_fill::<W, H, N, WORDS, { ROOMIER[3].0 }, { ROOMIER[3].1 }>(scene, bsp, b, s)
        }
    };
    drawn.map_err(Refusal::Library)
}

fn code_fill<
    const W: usize,
    const H: usize,
    const N: usize,
    const WORDS: usize,
    const FACES: usize,
    const EDGES: usize,
>(
    scene: &FrameInputs<'_>,
    bsp: Option<(&BspTree<'_>, usize)>,
    band: usize,
    sliced: bool,
) -> Result<Drawn, Error<Infallible>> {
    type Engine<const C: usize, const F: usize, const E: usize> =
        CodeFillRenderer<U4, C, F, E, POLY>;
    // Bit-sliced rows: every pixel's code, up to WORDS words, and a bit per pixel.
    let sliced_len = Engine::<WORDS, FACES, EDGES>::bit_sliced_len(W);
    let mut words = vec![0u32; if sliced { sliced_len } else { 0 }];
    let faces = scene.mesh.face_count();
    let surfaces = bsp.map_or(scene.mesh, |(tree, _)| tree.fragments());
    let edges = scene.adjacency.edges().len();
    let mut buffers = IdBuffers::sized(W, H, band, surfaces.vertices().len(), faces, edges);
    let mut order = vec![0u32; surfaces.face_count()];
    let mut ranks = DepthRanks::new(bsp.map(|(tree, _)| tree));
    let mut ws = buffers.code_workspace(&mut order);
    let working_ram = ws.bytes()
        + size_of_val(scene.adjacency.edges())
        + size_of::<Engine<WORDS, FACES, EDGES>>()
        + size_of_val(words.as_slice())
        + bsp.map_or(0, |(_, kept)| kept)
        + ranks.bytes();
    let mut renderer = Box::new(Engine::<WORDS, FACES, EDGES>::new());
    let mut fb = Box::new(PackedFramebuffer::<W, H, N>::new());
    let palette = MonoPalette::default();
    let mut result = None;
    measured_region(&mut || {
        let codes = if sliced {
            RowCodes::BitSliced(&mut words)
        } else {
            RowCodes::Crossings
        };
        let visibility = match bsp {
            Some((tree, _)) => match ranks.order(tree, &scene.camera.viewpoint()) {
                Ok(order) => Visibility::Order(order),
                Err(e) => {
                    result = Some(Err(e.widen()));
                    return;
                }
            },
            None => Visibility::Planes,
        };
        result = Some(renderer.render_with(
            &scene.mesh,
            &scene.adjacency,
            &scene.camera,
            &scene.settings,
            &mut ws,
            codes,
            visibility,
            &palette,
            &mut *fb,
            &mut (),
        ));
    });
    let stats = result.expect("the measured region ran")?;
    Ok(Drawn {
        bytes: fb.as_bytes().to_vec(),
        stats,
        working_ram,
        depth_bytes: 0,
    })
}

fn z_buffer<const W: usize, const H: usize, const N: usize, D: Depth>(
    scene: &FrameInputs<'_>,
    band: usize,
) -> Result<Drawn, Error<Infallible>> {
    type Engine = ZBufferRenderer<U4, FACE_EDGES, POLY>;
    let (faces, edges) = (scene.mesh.face_count(), scene.adjacency.edges().len());
    let vertices = scene.mesh.vertices().len();
    let mut buffers = IdBuffers::sized(W, H, band, vertices, faces, edges);
    let mut depth = vec![D::default(); buffers.ids.len()];
    let mut ws = buffers.depth_workspace(&mut depth);
    let working_ram = ws.bytes() + size_of_val(scene.adjacency.edges()) + size_of::<Engine>();
    let mut renderer = Box::new(Engine::new());
    let mut fb = Box::new(PackedFramebuffer::<W, H, N>::new());
    let palette = MonoPalette::default();
    let mut result = None;
    measured_region(&mut || {
        result = Some(renderer.render(
            &scene.mesh,
            &scene.adjacency,
            &scene.camera,
            &scene.settings,
            &mut ws,
            &palette,
            &mut *fb,
            &mut (),
        ));
    });
    let stats = result.expect("the measured region ran")?;
    Ok(Drawn {
        bytes: fb.as_bytes().to_vec(),
        stats,
        working_ram,
        depth_bytes: stats.depth_buffer_bytes as usize,
    })
}

/// Runs child job `key` (`MODEL/WxH/RENDERER`); returns the pixels set in its frame.
pub fn child(key: &str) -> Result<usize, String> {
    if key == EMPTY {
        measured_region(&mut || {});
        return Ok(0);
    }
    let job = Job::from_key(key).ok_or_else(|| format!("bad scene3d job {key:?}"))?;
    let view = View::load(job.model, job.size)?;
    match draw(&view, job.renderer, None) {
        Ok(d) => Ok(count_set(&d.bytes, job.size.0, job.size.1)),
        Err(r) => Err(format!("{key}: {}", refusal_text(&r))),
    }
}

fn refusal_text(r: &Refusal) -> String {
    match r {
        Refusal::Library(Error::CodeTooWide { needed, capacity }) => {
            format!("CodeTooWide (needs {needed} bits, has {capacity})")
        }
        Refusal::Library(Error::CapacityExceeded {
            what,
            needed,
            capacity,
        }) => {
            format!("CapacityExceeded ({what}: {needed} > {capacity})")
        }
        Refusal::Library(e) => format!("{e}"),
        Refusal::Setup(e) => e.clone(),
    }
}
