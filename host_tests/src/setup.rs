//! The library's engines set up on the host, once for every engine: the mesh, its
//! edge adjacency, camera and settings ([`Scene`], built in [`SceneStorage`]), the lent
//! buffers of a frame ([`IdBuffers`]) and one frame drawn in the measured region
//! ([`Measured`]).

use std::time::Instant;

use pbuffer::mesh::{EdgeAdjacency, Mesh};
use pbuffer::render::{IdWorkspace, ProjectedVertex};
use pbuffer::{Camera, CodeWorkspace, Settings, Stats, Workspace};

use crate::callgrind::measured_region;
use crate::frame::{CameraSpec, Frame, MeshData, RenderSpec};
use crate::pipeline::{
    camera, frame, settings, AdjacencyStorage, Collect, MeshArrays, PackedFrame,
};

/// The owned storage behind a [`Scene`]: the mesh's arrays, its faces' planarity
/// and its adjacency's.
pub struct SceneStorage {
    pub arrays: MeshArrays,
    /// Which faces are planar ([`pbuffer::order::planar_faces`]), kept with the mesh
    /// ([`Mesh::with_planar_faces`]) as firmware keeps them: part of the mesh, made
    /// once (by the first `scene`), not of a frame.
    pub planar: Vec<u32>,
    planar_made: bool,
    pub adjacency: AdjacencyStorage,
}

impl SceneStorage {
    /// Storage for `data`.
    pub fn new(data: &MeshData) -> Self {
        let arrays = MeshArrays::new(data);
        let adjacency = AdjacencyStorage::new(&arrays);
        let planar = vec![0; pbuffer::mesh::planar_words(arrays.offsets.len().saturating_sub(1))];
        Self {
            arrays,
            planar,
            planar_made: false,
            adjacency,
        }
    }

    /// The library mesh (its faces' planarity kept), its adjacency (crease angle
    /// `spec.crease_deg`), the camera of `cam` and the settings of `spec`, in that
    /// order (the first error is returned).
    pub fn scene(&mut self, cam: &CameraSpec, spec: &RenderSpec) -> Result<Scene<'_>, String> {
        let arrays = &self.arrays;
        let mesh = Mesh::new(&arrays.vertices, &arrays.indices, &arrays.offsets)
            .map_err(|e| format!("mesh: {e}"))?;
        if !self.planar_made {
            pbuffer::order::planar_faces(&mesh, &mut self.planar)
                .map_err(|e| format!("mesh: {e}"))?;
            self.planar_made = true;
        }
        let mesh = mesh
            .with_planar_faces(&self.planar)
            .map_err(|e| format!("mesh: {e}"))?;
        let build_bytes = self.adjacency.build_bytes();
        let adjacency = self.adjacency.build(&mesh, spec.crease_deg)?;
        Ok(Scene {
            mesh,
            adjacency,
            camera: camera(cam)?,
            settings: settings(spec)?,
            build_bytes,
        })
    }
}

/// What every engine renders from: the mesh, its adjacency, the camera, the settings.
pub struct Scene<'s> {
    pub mesh: Mesh<'s>,
    pub adjacency: EdgeAdjacency<'s>,
    pub camera: Camera,
    pub settings: Settings,
    /// Bytes of the adjacency storage needed only while building it (weld map,
    /// half-edge records): once per mesh, reported apart from the working RAM.
    pub build_bytes: usize,
}

/// Lent buffers of an id-filling frame, sized for `vertices` vertex positions.
pub(crate) struct IdBuffers {
    pub vertices: Vec<ProjectedVertex>,
    pub drawn: Vec<u32>,
    pub features: Vec<u32>,
    pub ids: Vec<u16>,
    pub lines: Vec<u32>,
}

impl IdBuffers {
    pub fn new(spec: &RenderSpec, vertices: usize, faces: usize, edges: usize) -> Self {
        let band = spec.band.clamp(1, spec.height.max(1));
        Self::sized(spec.width, spec.height, band, vertices, faces, edges)
    }

    /// Buffers for drawing `vertices` vertex positions of `mesh`, with its `adjacency`.
    pub fn for_mesh(
        spec: &RenderSpec,
        vertices: usize,
        mesh: &Mesh<'_>,
        adjacency: &EdgeAdjacency<'_>,
    ) -> Self {
        Self::new(spec, vertices, mesh.face_count(), adjacency.edges().len())
    }

    /// Buffers for a `w` x `h` frame drawn in bands of `band` rows.
    pub fn sized(
        w: usize,
        h: usize,
        band: usize,
        vertices: usize,
        faces: usize,
        edges: usize,
    ) -> Self {
        let stored = usize::from(pbuffer::render::storage_rows(band as u16, h as u16));
        Self {
            vertices: vec![ProjectedVertex::default(); vertices],
            drawn: vec![0; faces.div_ceil(32)],
            features: vec![0; edges.div_ceil(32)],
            ids: vec![0; w * stored],
            lines: vec![0; 2 * w.div_ceil(32) * band],
        }
    }

    pub fn workspace(&mut self) -> IdWorkspace<'_> {
        IdWorkspace {
            vertices: &mut self.vertices,
            drawn: &mut self.drawn,
            features: &mut self.features,
            ids: &mut self.ids,
            lines: &mut self.lines,
        }
    }

    /// The Z-buffer's workspace: these buffers and `depth` (one per id).
    pub fn depth_workspace<'a, D>(&'a mut self, depth: &'a mut [D]) -> Workspace<'a, D> {
        Workspace {
            vertices: &mut self.vertices,
            drawn: &mut self.drawn,
            features: &mut self.features,
            depth,
            ids: &mut self.ids,
            lines: &mut self.lines,
        }
    }

    /// The code-fill engine's workspace: these buffers and `order` (one per surface).
    pub fn code_workspace<'a>(&'a mut self, order: &'a mut [u32]) -> CodeWorkspace<'a> {
        CodeWorkspace {
            vertices: &mut self.vertices,
            drawn: &mut self.drawn,
            features: &mut self.features,
            order,
            ids: &mut self.ids,
            lines: &mut self.lines,
        }
    }
}

/// One frame drawn: the target, the probe's images, the stats and the time it took.
pub(crate) struct Measured {
    pub target: PackedFrame,
    pub probe: Collect,
    pub stats: Stats,
    pub time_us: u64,
}

impl Measured {
    /// Draws once with `draw` into a new `w` x `h` target and probe, inside
    /// [`measured_region`] (only `draw` is counted).
    pub fn run(
        w: usize,
        h: usize,
        mut draw: impl FnMut(&mut PackedFrame, &mut Collect) -> Result<Stats, pbuffer::Error>,
    ) -> Result<Self, String> {
        let mut target = PackedFrame::new(w, h);
        let mut probe = Collect::new(w, h);
        let start = Instant::now();
        let mut result = None;
        measured_region(&mut || {
            result = Some(draw(&mut target, &mut probe));
        });
        let stats = result
            .expect("the measured region ran")
            .map_err(|e| format!("render: {e}"))?;
        let time_us = start.elapsed().as_micros() as u64;
        Ok(Self {
            target,
            probe,
            stats,
            time_us,
        })
    }

    /// The frame and its `--stats` figures (see [`frame`]).
    pub fn frame(self, working: usize, build_bytes: usize) -> Frame {
        let (w, h) = (self.target.width, self.target.height);
        frame(
            w,
            h,
            self.probe,
            self.target,
            &self.stats,
            working,
            build_bytes,
            self.time_us,
        )
    }
}
