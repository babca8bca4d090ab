//! A cube with dashed hidden lines on 128x64, rendered by `ZBufferRenderer` in 8-row
//! bands: shared by the firmware (`main.rs`) and the host test
//! `host_tests/tests/firmware_cube.rs`, which both check `EXPECTED_CUBE`, so the M4
//! and the host are held to the same bits.

use pbuffer::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use pbuffer::render::{storage_rows, ProjectedVertex};
use pbuffer::{
    packed_len, Camera, Cull, Dashes, DrawMode, Error, MonoPalette, PackedFramebuffer, Pattern,
    Projection, Settings, Stats, Workspace, ZBufferRenderer,
};

/// The frame.
pub type CubeFrame = PackedFramebuffer<128, 64, { packed_len(128, 64) }>;

const VERTICES: [[f32; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];
/// Six quads, counter-clockwise seen from outside.
const INDICES: [u32; 24] = [
    0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 3, 7, 6, 2, 0, 4, 7, 3, 1, 2, 6, 5,
];
const OFFSETS: [u32; 7] = [0, 4, 8, 12, 16, 20, 24];
const BAND: u16 = 8;
const STORED: usize = 128 * 10; // storage_rows(8, 64) = 10 rows: the band and its apron

/// FNV-1a 64 of the frame; both the host test and the firmware check it.
pub const EXPECTED_CUBE: u64 = 0x0549_e202_7963_139b;

/// FNV-1a 64, as `render --hash` computes it.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// Renders the cube seen from eye `eye` into `fb`.
pub fn render_cube(fb: &mut CubeFrame, eye: [f32; 3]) -> Result<Stats, Error> {
    debug_assert_eq!(usize::from(storage_rows(BAND, 64)) * 128, STORED);
    let mesh = Mesh::new(&VERTICES, &INDICES, &OFFSETS)?;
    let mut weld = [0u32; 8];
    let mut scratch = [HalfEdgeRecord::EMPTY; 24];
    let mut store = [MeshEdge::EMPTY; 24];
    let edges = EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut store)?;
    let projection = Projection::Perspective { fov_y_deg: 40.0 };
    let camera = Camera::new(eye, [0.0; 3], [0.0, 1.0, 0.0], projection, 0.5, 20.0)?;
    let mut vertices = [ProjectedVertex::default(); 8];
    let (mut drawn, mut features) = ([0u32; 1], [0u32; 1]);
    let mut depth = [0u32; STORED];
    let mut ids = [0u16; STORED];
    let mut lines = [0u32; 2 * 4 * BAND as usize];
    let mut ws = Workspace {
        vertices: &mut vertices,
        drawn: &mut drawn,
        features: &mut features,
        depth: &mut depth,
        ids: &mut ids,
        lines: &mut lines,
    };
    let settings = Settings {
        mode: DrawMode::Dashed,
        cull: Cull::Auto,
        pattern: Pattern::PAPER,
        dashes: Dashes::Screen,
    };
    let mut renderer = ZBufferRenderer::<fixed::types::extra::U4, 16, 16>::new();
    renderer.render(
        &mesh,
        &edges,
        &camera,
        &settings,
        &mut ws,
        &MonoPalette::default(),
        fb,
        &mut (),
    )
}
