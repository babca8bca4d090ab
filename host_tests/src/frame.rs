//! The host-side contract between the library pipeline, the f64 reference, the tests
//! and the `render` command: a mesh, a camera, render settings in; a frame out.

/// A mesh on the host: f64 positions and faces of 3 or more 0-based vertex indices
/// (face index = position in `faces`), counter-clockwise seen from the front.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshData {
    /// Vertex positions.
    pub vertices: Vec<[f64; 3]>,
    /// Faces as 0-based vertex indices.
    pub faces: Vec<Vec<u32>>,
}

/// Projection of a camera, as CONVENTIONS.md defines it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProjectionSpec {
    /// Vertical field of view in degrees.
    Perspective { fov_deg: f64 },
    /// Orthographic with this half-height in world units.
    Orthographic { half_height: f64 },
}

/// A camera: `look_at(eye, target, up)` plus projection and clip distances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraSpec {
    pub eye: [f64; 3],
    pub target: [f64; 3],
    pub up: [f64; 3],
    pub projection: ProjectionSpec,
    pub near: f64,
    pub far: f64,
}

impl Default for CameraSpec {
    fn default() -> Self {
        Self {
            eye: [0.0, 0.0, 5.0],
            target: [0.0; 3],
            up: [0.0, 1.0, 0.0],
            projection: ProjectionSpec::Perspective { fov_deg: 45.0 },
            near: 0.1,
            far: 1000.0,
        }
    }
}

/// Back-face culling.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CullSpec {
    On,
    Off,
    /// On when the mesh is closed (every edge shared by exactly two faces).
    #[default]
    Auto,
}

/// What is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ModeSpec {
    /// All feature edges solid, nothing hidden.
    Wireframe,
    /// Visible feature edges only.
    Hidden,
    /// Visible feature edges solid, hidden ones through the pattern.
    #[default]
    Dashed,
    /// Faces filled, no lines.
    Surfaces,
    /// Faces filled, plus dashed lines.
    SurfacesDashed,
}

/// Visibility engine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EngineSpec {
    /// Modulo-2 surface codes per row in a BSP tree's depth order (weight-1 codes,
    /// priority encoder), no depth buffer; every pixel's code in words
    /// (`RowCodes::BitSliced`), the faster representation in depth order.
    #[default]
    CodeFill,
    /// The same engine with the row's crossings in order (`RowCodes::Crossings`).
    CodeFillCrossings,
    /// The code-fill engine without an order: planes compared where faces overlap
    /// (the scan-line method of notes 004).
    Scanline,
    /// Depth buffer in bands.
    ZBuffer,
    /// The painter's algorithm: faces sorted by farthest depth, painted far to near,
    /// no splitting (fails on cyclic overlap and interpenetration, by design).
    Painter,
    /// A BSP tree built once for the mesh, walked per view; its fragments painted far
    /// to near.
    Bsp,
    /// Warnock's area subdivision: areas split down to pixels, each decided as the
    /// Z-buffer (32-bit depth) decides it.
    Warnock,
    /// One fixed-point ray per pixel centre through a bounding-volume hierarchy built
    /// per frame.
    Raycast,
    /// Newell's list priority for each view (depth sort, Newell's tests, shuffles,
    /// splits), the fragments painted far to near.
    Newell,
    /// The fast engine for microcontrollers: a scan-line Z-buffer one row high, 16-bit
    /// depth, per-mesh constants baked; approximate (`pbuffer::render::FastRenderer`).
    Fast,
}

impl EngineSpec {
    /// Every engine, in the order the `--engine` help lists them.
    pub const ALL: [EngineSpec; 10] = [
        EngineSpec::CodeFill,
        EngineSpec::CodeFillCrossings,
        EngineSpec::Scanline,
        EngineSpec::ZBuffer,
        EngineSpec::Painter,
        EngineSpec::Bsp,
        EngineSpec::Warnock,
        EngineSpec::Raycast,
        EngineSpec::Newell,
        EngineSpec::Fast,
    ];

    /// The engine's `--engine` name.
    pub fn name(self) -> &'static str {
        match self {
            EngineSpec::CodeFill => "codefill",
            EngineSpec::CodeFillCrossings => "codefill-crossings",
            EngineSpec::Scanline => "scanline",
            EngineSpec::ZBuffer => "zbuffer",
            EngineSpec::Painter => "painter",
            EngineSpec::Bsp => "bsp",
            EngineSpec::Warnock => "warnock",
            EngineSpec::Raycast => "raycast",
            EngineSpec::Newell => "newell",
            EngineSpec::Fast => "fast",
        }
    }

    /// The engine named `name`.
    pub fn by_name(name: &str) -> Option<EngineSpec> {
        EngineSpec::ALL.into_iter().find(|e| e.name() == name)
    }
}

/// Render settings.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderSpec {
    pub engine: EngineSpec,
    pub width: usize,
    pub height: usize,
    pub crease_deg: f64,
    pub cull: CullSpec,
    pub mode: ModeSpec,
    /// Sub-pixel bits S.
    pub subpixel: u32,
    /// Depth bits, 16 or 32.
    pub depth_bits: u32,
    /// Band height in rows (`height` = one full-frame band).
    pub band: usize,
    /// Pattern name (see `pbuffer::Pattern::by_name`).
    pub pattern: String,
    /// How hidden lines are dashed (the fast engine draws dashes along the edges;
    /// the others the pattern).
    pub dashes: pbuffer::Dashes,
    /// How the fast engine finds hidden lines.
    pub lines: pbuffer::render::LineVisibility,
}

impl Default for RenderSpec {
    fn default() -> Self {
        Self {
            engine: EngineSpec::CodeFill,
            width: 400,
            height: 240,
            crease_deg: 30.0,
            cull: CullSpec::Auto,
            mode: ModeSpec::Dashed,
            subpixel: 4,
            depth_bits: 32,
            band: 240,
            pattern: "paper".into(),
            dashes: pbuffer::Dashes::Screen,
            lines: pbuffer::render::LineVisibility::ByPixel,
        }
    }
}

/// One rendered frame, row-major, `width * height` entries each.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Frame {
    pub width: usize,
    pub height: usize,
    /// 1 + index of the face visible at each pixel, 0 where none (the `--ids` image).
    pub ids: Vec<u32>,
    /// 0 no feature edge, 1 visible-edge pixel, 2 hidden-edge pixel before the pattern;
    /// 1 wins where both meet (the `--lines` image).
    pub lines: Vec<u8>,
    /// The 1-bpp picture, packed row-major MSB first (`PackedFramebuffer` layout).
    pub packed: Vec<u8>,
    /// Figures: faces, faces_drawn, feature_edges, spans, working_ram_bytes, ...
    pub stats: Vec<(String, u64)>,
    /// The world distance one depth step stands for at the nearest and farthest
    /// drawn distance (`depth_step_near`, `depth_step_far`); 0 where not reported.
    pub depth_step: [f64; 2],
}

impl Frame {
    /// The figure named `name`, 0 when absent.
    pub fn stat(&self, name: &str) -> u64 {
        self.stats
            .iter()
            .find(|(n, _)| n == name)
            .map_or(0, |(_, v)| *v)
    }

    /// Sets (or adds) the figure named `name`.
    pub fn set_stat(&mut self, name: &str, value: u64) {
        match self.stats.iter_mut().find(|(n, _)| n == name) {
            Some((_, v)) => *v = value,
            None => self.stats.push((name.into(), value)),
        }
    }
}
