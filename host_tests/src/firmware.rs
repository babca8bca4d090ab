//! The firmware examples' scene code on the host: the `pbuffer-scenes` crate's `scenes`
//! and `instrument` modules (`examples/scenes`, which the firmware builds too), so the
//! host draws the firmware's frames with the very same code; [`Bake`], a mesh made
//! ready as build.rs makes the firmware's; and [`Demo`], the instrument-panel demo
//! ready to draw, for the frame-hash test, the `instrument` PNG writer and the
//! `instrument-window` simulator window.

use pbuffer::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use pbuffer::render::{BakedMesh, CompactEdge, FacePlane, Piercing, VertexFaces};
use pbuffer::Error;

use crate::image::Look;

pub use pbuffer_scenes::{arm, instances, instrument, scenes, shapes};

use instrument::Frame;
use scenes::{panel, PanelFastBuffers, PanelFastEngine};

/// A mesh made ready as `examples/embedded/build.rs` makes the firmware's meshes, at
/// run time: its edge list (crease angle 30 degrees), which faces are planar, and the
/// fast engine's constants (`BakedMesh::bake`), and the tables of hidden lines by the
/// segment (`VertexFaces::bake`, `Piercing::bake`, as `pbuffer::bake::mesh_to_rust`
/// writes them). The one set-up of every firmware frame on the host (the demo,
/// `bench --firmware`, the firmware tests).
#[derive(Debug, Clone)]
pub struct Bake {
    vertices: Vec<[f32; 3]>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
    edges: Vec<MeshEdge>,
    planar: Vec<u32>,
    planes: Vec<FacePlane>,
    compact: Vec<CompactEdge>,
    weld: Vec<u16>,
    around_starts: Vec<u16>,
    around_faces: Vec<u16>,
    irregular: Vec<u32>,
    piercings: Vec<Piercing>,
}

impl Bake {
    /// Bakes the mesh of these arrays (panics on a mesh the firmware could not take).
    pub fn new(vertices: &[[f32; 3]], indices: &[u32], offsets: &[u32]) -> Self {
        let mesh = Mesh::new(vertices, indices, offsets).expect("mesh");
        let mut weld = vec![0u32; vertices.len()];
        let mut scratch = vec![HalfEdgeRecord::EMPTY; indices.len()];
        let mut store = vec![MeshEdge::EMPTY; indices.len()];
        let adjacency = EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut store)
            .expect("adjacency");
        let mut planar = vec![0u32; pbuffer::mesh::planar_words(mesh.face_count())];
        pbuffer::order::planar_faces(&mesh, &mut planar).expect("sized");
        let mut planes = vec![FacePlane::default(); mesh.face_count()];
        let mut compact = vec![CompactEdge::EMPTY; adjacency.edges().len()];
        BakedMesh::bake(&mesh, &adjacency, &mut planes, &mut compact).expect("bakes");
        let edges = adjacency.edges().to_vec();
        // As the bake does (`pbuffer::bake::mesh_to_rust`): the faces around each
        // vertex, and the piercing pairs of the compact edge list.
        let (mut weld16, mut around_starts, mut around_faces) = (
            vec![0u16; vertices.len()],
            vec![0u16; vertices.len() + 1],
            vec![0u16; indices.len()],
        );
        let mut irregular = vec![0u32; vertices.len().div_ceil(32)];
        VertexFaces::bake(
            &mesh,
            &mut weld16,
            &mut around_starts,
            &mut around_faces,
            &mut irregular,
        )
        .expect("the faces around each vertex");
        let mut piercings = vec![Piercing::default(); compact.len() * 4 + 16];
        let n = loop {
            match Piercing::bake(&mesh, &compact, &mut piercings) {
                Ok(n) => break n,
                Err(Error::CapacityExceeded { needed, .. }) => {
                    piercings.resize(needed, Piercing::default())
                }
                Err(e) => panic!("the piercing pairs: {e:?}"),
            }
        };
        piercings.truncate(n);
        Self {
            vertices: vertices.to_vec(),
            indices: indices.to_vec(),
            offsets: offsets.to_vec(),
            edges,
            planar,
            planes,
            compact,
            weld: weld16,
            around_starts,
            around_faces,
            irregular,
            piercings,
        }
    }

    /// The panel bracket (`scenes::panel`'s arrays).
    pub fn panel() -> Self {
        Self::new(&panel::VERTICES, &panel::INDICES, &panel::OFFSETS)
    }

    /// The mesh without its planarity bits (as the scan-line examples keep it).
    pub fn plain_mesh(&self) -> Mesh<'_> {
        Mesh::new(&self.vertices, &self.indices, &self.offsets).expect("mesh")
    }

    /// The mesh with its planarity bits (as the fast examples keep it).
    pub fn mesh(&self) -> Mesh<'_> {
        self.plain_mesh()
            .with_planar_faces(&self.planar)
            .expect("planar bits")
    }

    /// The edge list, as the scan-line firmware takes it (`EdgeAdjacency::from_edges`).
    pub fn adjacency(&self) -> EdgeAdjacency<'_> {
        EdgeAdjacency::from_edges(&self.plain_mesh(), &self.edges).expect("the edge list")
    }

    /// Edges of the fast engine's compact list (what its buffers are sized for).
    pub fn baked_edges(&self) -> usize {
        self.compact.len()
    }

    /// The baked mesh, checked by `BakedMesh::new` as the firmware checks it at boot.
    pub fn baked(&self) -> BakedMesh<'_> {
        BakedMesh::new(self.mesh(), &self.planes, &self.compact).expect("the baked mesh")
    }

    /// The faces around each vertex (`{NAME}_VERTEX_FACES` of the bake).
    pub fn vertex_faces(&self) -> VertexFaces<'_> {
        VertexFaces {
            weld: &self.weld,
            starts: &self.around_starts,
            faces: &self.around_faces,
            irregular: &self.irregular,
        }
    }

    /// The piercing pairs (`{NAME}_PIERCINGS` of the bake).
    pub fn piercings(&self) -> &[Piercing] {
        &self.piercings
    }

    /// The baked mesh with the tables of hidden lines by the segment, as the
    /// `*-segments` firmware examples check it at boot
    /// (`.with_vertex_faces(..)`, `.with_piercings(..)`).
    pub fn baked_segments(&self) -> BakedMesh<'_> {
        self.baked()
            .with_vertex_faces(self.vertex_faces())
            .and_then(|b| b.with_piercings(&self.piercings))
            .expect("the segment tables")
    }
}

/// The instrument-panel demo with its engine and lent buffers (the firmware's sizes).
#[derive(Debug)]
pub struct Demo {
    bake: Bake,
    engine: Box<PanelFastEngine>,
    buffers: Box<PanelFastBuffers>,
}

impl Demo {
    /// A demo ready to draw.
    pub fn new() -> Self {
        Self {
            bake: Bake::panel(),
            engine: Box::new(PanelFastEngine::new()),
            buffers: Box::new(PanelFastBuffers::new()),
        }
    }

    /// Frame `n` (`instrument::draw`, as the firmware draws it).
    pub fn frame(&mut self, n: u32) -> Box<Frame> {
        let mut fb = Box::new(Frame::new());
        instrument::draw(
            &mut self.engine,
            &self.bake.baked(),
            &mut self.buffers,
            n,
            &mut fb,
        )
        .expect("the demo frame draws");
        fb
    }
}

impl Default for Demo {
    fn default() -> Self {
        Self::new()
    }
}

/// A procedural part's arrays made ready as build.rs bakes them.
pub fn bake_shape<const V: usize, const I: usize, const O: usize>(
    shape: &shapes::Shape<V, I, O>,
) -> Bake {
    assert!(shape.is_full(), "the shape's sizes");
    Bake::new(&shape.vertices, &shape.indices, &shape.offsets)
}

/// The robot-arm demo (`arm`): its four parts baked as build.rs bakes them.
#[derive(Debug)]
pub struct ArmDemo {
    parts: [Bake; 4],
}

impl ArmDemo {
    /// The parts baked: base, upper link, forearm, gripper.
    pub fn new() -> Self {
        Self {
            parts: [
                bake_shape(&arm::base()),
                bake_shape(&arm::upper()),
                bake_shape(&arm::forearm()),
                bake_shape(&arm::gripper()),
            ],
        }
    }

    /// Frame `n` (`arm::draw`, as the firmware draws it; the scene assembled anew,
    /// as the firmware assembles it once: the frame depends only on the poses).
    pub fn frame(&self, n: u32) -> Box<Frame> {
        let mut scene: Box<arm::ArmScene<'_>> = Box::new(pbuffer::SceneDrawing::new());
        arm::add_parts(&mut scene, self.parts.each_ref().map(Bake::baked)).expect("the parts");
        let mut rows = Box::new(arm::ArmRows::new());
        let mut fb = Box::new(Frame::new());
        arm::draw(&mut scene, &mut rows, n, &mut fb).expect("the arm frame draws");
        fb
    }
}

impl Default for ArmDemo {
    fn default() -> Self {
        Self::new()
    }
}

/// Which 128 x 64 panel demo: the instrument panel or the robot arm (the `instrument`
/// PNG writer's and the `instrument-window`'s `--demo`).
#[derive(Debug)]
pub enum PanelDemo {
    Instrument(Box<Demo>),
    Arm(Box<ArmDemo>),
}

impl PanelDemo {
    /// `instrument` or `arm`.
    pub fn named(name: &str) -> Result<Self, String> {
        match name {
            "instrument" => Ok(Self::Instrument(Box::default())),
            "arm" => Ok(Self::Arm(Box::default())),
            other => Err(format!("no demo '{other}' (instrument | arm)")),
        }
    }

    /// Its name, as the firmware example's.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Instrument(_) => "instrument",
            Self::Arm(_) => "arm",
        }
    }

    /// Frames of its animation.
    pub fn frames(&self) -> u32 {
        match self {
            Self::Instrument(_) => instrument::FRAMES,
            Self::Arm(_) => arm::FRAMES,
        }
    }

    /// Frame `n`.
    pub fn frame(&mut self, n: u32) -> Box<Frame> {
        match self {
            Self::Instrument(d) => d.frame(n),
            Self::Arm(d) => d.frame(n),
        }
    }
}

/// The colour between frames in [`frames_rgb`].
const BEZEL: [u8; 3] = [64, 64, 64];

/// Frames side by side as RGB (row-major, 3 bytes a pixel) in `look`, each pixel a
/// `scale x scale` block, `gap` pixels of a dark grey bezel between frames (before
/// scaling). As `render` draws its PNG: from scale 3 up (not for `paper`) the last row
/// and column of each block are a shade towards the glass, a faint pixel grid; at
/// scale 1 and 2 the picture is pixel for pixel the simulator window's (no spacing).
/// Returns the RGB bytes, width and height.
pub fn frames_rgb(
    frames: &[&Frame],
    look: Look,
    scale: usize,
    gap: usize,
) -> (Vec<u8>, usize, usize) {
    let (fw, fh) = (instrument::WIDTH, instrument::HEIGHT);
    let w = (frames.len() * fw + frames.len().saturating_sub(1) * gap) * scale;
    let h = fh * scale;
    let (off, on) = look.colours();
    let mix = |a: [u8; 3], b: [u8; 3], t: f32| -> [u8; 3] {
        std::array::from_fn(|k| (f32::from(a[k]) * (1.0 - t) + f32::from(b[k]) * t).round() as u8)
    };
    let grid = scale >= 3 && look != Look::Paper;
    let (on_edge, off_edge) = (mix(on, off, 0.3), mix(off, [0, 0, 0], 0.06));
    let mut rgb = Vec::with_capacity(w * h * 3);
    for y in 0..h {
        for x in 0..w {
            let (col, sx, sy) = (x / scale, x % scale, y % scale);
            let (k, fx) = (col / (fw + gap), col % (fw + gap));
            let lit = fx < fw && frames[k].pixel(fx as u32, (y / scale) as u32);
            let edge = grid && fx < fw && (sx == scale - 1 || sy == scale - 1);
            if fx >= fw {
                rgb.extend_from_slice(&BEZEL);
                continue;
            }
            rgb.extend_from_slice(&match (lit, edge) {
                (true, false) => on,
                (true, true) => on_edge,
                (false, false) => off,
                (false, true) => off_edge,
            });
        }
    }
    (rgb, w, h)
}
