//! The scenes of the firmware examples: cameras per frame, the bracket mesh, the
//! renderer configuration and the one call that draws a frame. `no_std`; shared with
//! the host test `host_tests/tests/firmware/firmware_examples.rs` (through this crate), so
//! the host renders the very same frames with the very same code.

use core::convert::Infallible;

use fixed::types::extra::U4;
use pbuffer::mesh::{EdgeAdjacency, Mesh};
use pbuffer::render::{
    BakedMesh, FastRenderer, FastVertex, FastWorkspace, ProjectedVertex, Run, SegmentLines,
    SegmentWorkspace, Segments,
};
use pbuffer::{
    Camera, CodeFillRenderer, CodeWorkspace, Cull, Dashes, DrawMode, Error, MonoPalette, Pattern,
    Projection, Settings, SpanSink, Stats,
};

/// The scan-line engine of the `*-scanline` examples: the code-fill engine (no depth
/// buffer), S = 4 sub-pixel bits, a 32-bit surface code (suzanne needs 9 bits),
/// room for 128 faces and 384 edges active on one row (the suzanne frames need up
/// to 258 edges) and 16 vertices per clipped face.
pub type Engine = CodeFillRenderer<U4, 1, 128, 384, 16>;
/// The panel's scan-line engine: the same, with room for the bracket's 16 faces and
/// 64 edges.
pub type PanelEngine = CodeFillRenderer<U4, 1, 16, 64, 16>;

/// The default engine of the examples: the fast engine (a scan-line Z-buffer one row
/// high), S = 4 sub-pixel bits, room for 100 facets and 84 feature lines active on
/// one row (suzanne's 8 frames need up to 82 and 70, with her back faces away from
/// the holes skipped; 92 facets when every back face was drawn).
pub type FastEngine = FastRenderer<U4, 100, 84>;
/// The panel's fast engine: room for every one of the bracket's 16 (planar) faces and
/// 36 edges at once, so no view can run out.
pub type PanelFastEngine = FastRenderer<U4, 16, { panel::EDGES }>;
/// Corners of clipped faces the fast examples have room for (their frames clip none).
pub const FAST_POOL: usize = 64;

/// A perspective camera looking at `target`, `up` = +Y.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    pub eye: [f32; 3],
    pub target: [f32; 3],
    pub fov_deg: f32,
    pub near: f32,
    pub far: f32,
}

impl View {
    /// The library camera.
    pub fn camera(&self) -> Result<Camera, Error> {
        Camera::new(
            self.eye,
            self.target,
            [0.0, 1.0, 0.0],
            Projection::Perspective {
                fov_y_deg: self.fov_deg,
            },
            self.near,
            self.far,
        )
    }
}

/// Suzanne at 400 x 240: the eye orbits the model's centre, 15 degrees a frame.
pub mod suzanne {
    use super::View;
    pub const WIDTH: usize = 400;
    pub const HEIGHT: usize = 240;
    /// Rows per band (18 stored rows with the apron).
    pub const BAND: usize = 16;
    pub const FRAMES: u32 = 8;
    const TARGET: [f32; 3] = [-2.49, 1.25, 4.1];
    /// `TARGET + (5 sin t, 1.2, 5 cos t)` for t = -45, -30, ..., 60 degrees.
    const EYES: [[f32; 3]; FRAMES as usize] = [
        [-6.0255, 2.45, 7.6355],
        [-4.99, 2.45, 8.4301],
        [-3.7841, 2.45, 8.9296],
        [-2.49, 2.45, 9.1],
        [-1.1959, 2.45, 8.9296],
        [0.01, 2.45, 8.4301],
        [1.0455, 2.45, 7.6355],
        [1.8401, 2.45, 6.6],
    ];
    /// The camera of frame `n`.
    pub fn view(n: u32) -> View {
        View {
            eye: EYES[n as usize % EYES.len()],
            target: TARGET,
            fov_deg: 35.0,
            near: 1.0,
            far: 20.0,
        }
    }
}

/// The 128 x 64 instrument panel: an L-bracket with a hexagonal boss, turning.
pub mod panel {
    use super::View;
    pub const WIDTH: usize = 128;
    pub const HEIGHT: usize = 64;
    /// Rows per band (10 stored rows with the apron).
    pub const BAND: usize = 8;
    pub const FRAMES: u32 = 4;
    const TARGET: [f32; 3] = [1.5, 0.7, 0.0];
    /// `(1.5 + 6 sin t, 4, 6 cos t)` for t = 20, 45, 70, 95 degrees.
    const EYES: [[f32; 3]; FRAMES as usize] = [
        [3.5521, 4.0, 5.6382],
        [5.7426, 4.0, 4.2426],
        [7.1382, 4.0, 2.0521],
        [7.4772, 4.0, -0.5229],
    ];
    /// The camera of frame `n`.
    pub fn view(n: u32) -> View {
        View {
            eye: EYES[n as usize % EYES.len()],
            target: TARGET,
            fov_deg: 35.0,
            near: 1.0,
            far: 30.0,
        }
    }

    // VERTICES, INDICES, OFFSETS and EDGES: shared with build.rs.
    include!("panel_mesh.rs");
}

/// A zero vertex, for `static` buffers.
pub const ZERO_VERTEX: ProjectedVertex = ProjectedVertex::ZERO;

/// Words of a bitset of `n` bits.
pub const fn words(n: usize) -> usize {
    n.div_ceil(32)
}

/// The lent working memory of one scene: `V` vertices, `F` faces (`FW` face-bit
/// words), `EW` edge-bit words, `ST` id samples (width x (band + 2)), `LW` line
/// words (2 x ceil(width / 32) x band). Zero-initialised, so a `static` of it is
/// `.bss`.
#[derive(Debug)]
pub struct Buffers<
    const V: usize,
    const F: usize,
    const FW: usize,
    const EW: usize,
    const ST: usize,
    const LW: usize,
> {
    pub vertices: [ProjectedVertex; V],
    pub drawn: [u32; FW],
    pub features: [u32; EW],
    pub order: [u32; F],
    pub ids: [u16; ST],
    pub lines: [u32; LW],
}

impl<
        const V: usize,
        const F: usize,
        const FW: usize,
        const EW: usize,
        const ST: usize,
        const LW: usize,
    > Buffers<V, F, FW, EW, ST, LW>
{
    /// All zero.
    pub const fn new() -> Self {
        Self {
            vertices: [ZERO_VERTEX; V],
            drawn: [0; FW],
            features: [0; EW],
            order: [0; F],
            ids: [0; ST],
            lines: [0; LW],
        }
    }

    /// The workspace the renderer borrows.
    pub fn workspace(&mut self) -> CodeWorkspace<'_> {
        CodeWorkspace {
            vertices: &mut self.vertices,
            drawn: &mut self.drawn,
            features: &mut self.features,
            order: &mut self.order,
            ids: &mut self.ids,
            lines: &mut self.lines,
        }
    }
}

/// Buffers for suzanne (507 vertices, 500 faces, <= 1024 edges) at 400 x 240 in
/// 16-row bands.
pub type SuzanneBuffers = Buffers<
    507,
    500,
    { words(500) },
    { words(1024) },
    { suzanne::WIDTH * (suzanne::BAND + 2) },
    { 2 * words(suzanne::WIDTH) * suzanne::BAND },
>;
/// Buffers for the panel part at 128 x 64 in 8-row bands.
pub type PanelBuffers = Buffers<
    24,
    16,
    1,
    { words(panel::EDGES) },
    { panel::WIDTH * (panel::BAND + 2) },
    { 2 * words(panel::WIDTH) * panel::BAND },
>;

/// The lent working memory of the fast engine for one scene: `V` vertices, `F` faces
/// (`FW` facing words), `E` baked edges, `H2` list heads (2 x height), `W` row
/// entries (width), `MW` mask words (2 x ceil(width / 32)), `P` clipped corners. No
/// probe ids (the examples draw without a probe). Zero-initialised, so a `static` of
/// it is `.bss`.
#[derive(Debug)]
pub struct FastBuffers<
    const V: usize,
    const F: usize,
    const FW: usize,
    const E: usize,
    const H2: usize,
    const W: usize,
    const MW: usize,
    const P: usize,
> {
    pub vertices: [FastVertex; V],
    pub facing: [u32; FW],
    pub face_links: [u16; F],
    pub line_links: [u16; E],
    pub heads: [u16; H2],
    pub row: [u32; W],
    pub masks: [u32; MW],
    pub pool: [FastVertex; P],
    pub slopes: [u16; F],
}

impl<
        const V: usize,
        const F: usize,
        const FW: usize,
        const E: usize,
        const H2: usize,
        const W: usize,
        const MW: usize,
        const P: usize,
    > FastBuffers<V, F, FW, E, H2, W, MW, P>
{
    /// All zero.
    pub const fn new() -> Self {
        Self {
            vertices: [FastVertex::ZERO; V],
            facing: [0; FW],
            face_links: [0; F],
            line_links: [0; E],
            heads: [0; H2],
            row: [0; W],
            masks: [0; MW],
            pool: [FastVertex::ZERO; P],
            slopes: [0; F],
        }
    }

    /// The workspace the fast engine borrows.
    pub fn workspace(&mut self) -> FastWorkspace<'_> {
        FastWorkspace {
            vertices: &mut self.vertices,
            facing: &mut self.facing,
            face_links: &mut self.face_links,
            line_links: &mut self.line_links,
            heads: &mut self.heads,
            row: &mut self.row,
            masks: &mut self.masks,
            pool: &mut self.pool,
            ids: &mut [],
            slopes: &mut self.slopes,
            phases: &mut [],
            segments: None,
        }
    }

    /// The workspace the fast engine borrows, with `seg`'s storage for hidden lines
    /// by the segment (`segments: Some(..)`: the `*-segments` examples).
    pub fn workspace_with<
        'a,
        const SV: usize,
        const SV1: usize,
        const SVW: usize,
        const SE: usize,
        const SE2: usize,
        const CONTOURS: usize,
        const CROSSINGS: usize,
        const ENTRIES: usize,
    >(
        &'a mut self,
        seg: &'a mut SegmentBuffers<SV, SV1, SVW, SE, SE2, CONTOURS, CROSSINGS, ENTRIES>,
    ) -> FastWorkspace<'a> {
        FastWorkspace {
            segments: Some(seg.segments()),
            ..self.workspace()
        }
    }
}

/// The lent storage of hidden lines by the segment for one scene: the per-frame
/// lists (`CONTOURS` contour edges, `CROSSINGS` kept crossings, `ENTRIES` entries
/// of the contour grid) and the mesh-sized workspace for `V` vertices (`V1` =
/// `V` + 1, `VW` = ceil(`V` / 32)) and `E` baked edges (`E2` = 2 x `E`). Zero-initialised, so a `static`
/// of it is `.bss`.
#[derive(Debug)]
pub struct SegmentBuffers<
    const V: usize,
    const V1: usize,
    const VW: usize,
    const E: usize,
    const E2: usize,
    const CONTOURS: usize,
    const CROSSINGS: usize,
    const ENTRIES: usize,
> {
    pub lines: SegmentLines<CONTOURS, CROSSINGS, ENTRIES>,
    pub runs: [Run; E],
    pub counts: [i16; V],
    pub queue: [u16; V],
    pub starts: [u16; V1],
    pub at: [u16; E2],
    pub marks: [u32; VW],
}

impl<
        const V: usize,
        const V1: usize,
        const VW: usize,
        const E: usize,
        const E2: usize,
        const CONTOURS: usize,
        const CROSSINGS: usize,
        const ENTRIES: usize,
    > SegmentBuffers<V, V1, VW, E, E2, CONTOURS, CROSSINGS, ENTRIES>
{
    /// All zero.
    pub const fn new() -> Self {
        Self {
            lines: SegmentLines::new(),
            runs: [Run::EMPTY; E],
            counts: [0; V],
            queue: [0; V],
            starts: [0; V1],
            at: [0; E2],
            marks: [0; VW],
        }
    }

    /// The storage as a frame borrows it (`FastWorkspace::segments`).
    pub fn segments(&mut self) -> Segments<'_> {
        Segments {
            lists: self.lines.lists(),
            work: SegmentWorkspace {
                runs: &mut self.runs,
                counts: &mut self.counts,
                queue: &mut self.queue,
                starts: &mut self.starts,
                at: &mut self.at,
                marks: &mut self.marks,
            },
        }
    }
}

impl<
        const V: usize,
        const V1: usize,
        const VW: usize,
        const E: usize,
        const E2: usize,
        const CONTOURS: usize,
        const CROSSINGS: usize,
        const ENTRIES: usize,
    > Default for SegmentBuffers<V, V1, VW, E, E2, CONTOURS, CROSSINGS, ENTRIES>
{
    fn default() -> Self {
        Self::new()
    }
}

/// Suzanne's baked edges (`suzanne::SUZANNE_EDGES.len()`, checked by the host test).
pub const SUZANNE_EDGES: usize = 1005;

/// Fast-engine buffers for suzanne (507 vertices, 500 faces, its baked edges) at
/// 400 x 240.
pub type SuzanneFastBuffers = FastBuffers<
    507,
    500,
    { words(500) },
    SUZANNE_EDGES,
    { 2 * suzanne::HEIGHT },
    { suzanne::WIDTH },
    { 2 * words(suzanne::WIDTH) },
    FAST_POOL,
>;
/// Fast-engine buffers for the panel part at 128 x 64.
pub type PanelFastBuffers = FastBuffers<
    24,
    16,
    1,
    { panel::EDGES },
    { 2 * panel::HEIGHT },
    { panel::WIDTH },
    { 2 * words(panel::WIDTH) },
    FAST_POOL,
>;

/// Segment storage for suzanne (507 vertices, her baked edges): room for
/// [`SUZANNE_CONTOURS`] contours, [`SUZANNE_CROSSINGS`] crossings and
/// [`SUZANNE_GRID_ENTRIES`] grid entries.
pub type SuzanneSegmentBuffers = SegmentBuffers<
    507,
    508,
    { words(507) },
    SUZANNE_EDGES,
    { 2 * SUZANNE_EDGES },
    SUZANNE_CONTOURS,
    SUZANNE_CROSSINGS,
    SUZANNE_GRID_ENTRIES,
>;
/// Contour edges suzanne's segment storage holds (her 8 frames need up to 271:
/// `cargo test --release -p host_tests --test firmware firmware_example_frames --
/// --nocapture` prints the peaks).
pub const SUZANNE_CONTOURS: usize = 512;
/// Crossings suzanne's segment storage holds (her 8 frames need up to 266).
pub const SUZANNE_CROSSINGS: usize = 768;
/// Contour-grid entries suzanne's segment storage holds (her 8 frames need up to
/// 479).
pub const SUZANNE_GRID_ENTRIES: usize = 1024;

/// Segment storage for the panel part (24 vertices, its 36 edges): room for
/// [`PANEL_CONTOURS`] contours, [`PANEL_CROSSINGS`] crossings and
/// [`PANEL_GRID_ENTRIES`] grid entries.
pub type PanelSegmentBuffers = SegmentBuffers<
    24,
    25,
    1,
    { panel::EDGES },
    { 2 * panel::EDGES },
    PANEL_CONTOURS,
    PANEL_CROSSINGS,
    PANEL_GRID_ENTRIES,
>;
/// Contour edges the panel's segment storage holds (its 4 frames need up to 18).
pub const PANEL_CONTOURS: usize = 32;
/// Crossings the panel's segment storage holds (its 4 frames need up to 13).
pub const PANEL_CROSSINGS: usize = 32;
/// Contour-grid entries the panel's segment storage holds (its 4 frames need up to
/// 36).
pub const PANEL_GRID_ENTRIES: usize = 64;

/// Draws one frame of `baked` seen from `view` into `sink` with the fast engine:
/// `mode` with culling on for closed meshes and the paper's pattern.
pub fn render_fast<
    K: SpanSink<Color = embedded_graphics::pixelcolor::BinaryColor, Error = Infallible>,
    const FACETS: usize,
    const LINES: usize,
>(
    engine: &mut FastRenderer<U4, FACETS, LINES>,
    baked: &BakedMesh<'_>,
    view: &View,
    mode: DrawMode,
    ws: &mut FastWorkspace<'_>,
    sink: &mut K,
) -> Result<Stats, Error> {
    render_fast_to(engine, baked, view, mode, ws, sink)
}

/// [`render_fast`] into a sink that can fail: a panel driver's draw target (the
/// `panels` examples).
pub fn render_fast_to<
    K: SpanSink<Color = embedded_graphics::pixelcolor::BinaryColor>,
    const FACETS: usize,
    const LINES: usize,
>(
    engine: &mut FastRenderer<U4, FACETS, LINES>,
    baked: &BakedMesh<'_>,
    view: &View,
    mode: DrawMode,
    ws: &mut FastWorkspace<'_>,
    sink: &mut K,
) -> Result<Stats, Error<K::Error>> {
    let camera = view.camera().map_err(Error::widen)?;
    engine.render(
        baked,
        &camera,
        &settings(mode),
        ws,
        &MonoPalette::default(),
        sink,
        &mut (),
    )
}

/// The examples' settings: `mode`, culling on for closed meshes, the paper's pattern.
fn settings(mode: DrawMode) -> Settings {
    Settings {
        mode,
        cull: Cull::Auto,
        pattern: Pattern::PAPER,
        dashes: Dashes::Screen,
        lines: pbuffer::render::LineVisibility::BySegment,
    }
}

/// Draws one frame of `mesh` seen from `view` into `sink` with pbuffer's engine:
/// `mode` with culling on for closed meshes and the paper's pattern.
pub fn render<
    K: SpanSink<Color = embedded_graphics::pixelcolor::BinaryColor, Error = Infallible>,
    const FACES: usize,
    const EDGES: usize,
>(
    engine: &mut CodeFillRenderer<U4, 1, FACES, EDGES, 16>,
    mesh: &Mesh<'_>,
    edges: &EdgeAdjacency<'_>,
    view: &View,
    mode: DrawMode,
    ws: &mut CodeWorkspace<'_>,
    sink: &mut K,
) -> Result<Stats, Error> {
    let camera = view.camera()?;
    engine.render(
        mesh,
        edges,
        &camera,
        &settings(mode),
        ws,
        &MonoPalette::default(),
        sink,
        &mut (),
    )
}

/// FNV-1a 64, as `render --hash` computes it.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}
