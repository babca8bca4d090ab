//! The library's Newell depth sort on the host: storage grown until the sort fits
//! (the `newell` engine itself is `engines::render_newell_paint`).

use std::time::Instant;

use pbuffer::mesh::Mesh;
use pbuffer::order::{NewellOrder, NewellSizes, NewellStorage};
use pbuffer::{Camera, Error};

use crate::frame::{CullSpec, RenderSpec};

/// One sort's figures.
#[derive(Clone, Copy, Debug, Default)]
pub struct NewellFigures {
    /// Bytes the order keeps for rendering (fragment vertices, indices, offsets,
    /// sources and ranks).
    pub kept_bytes: usize,
    /// Bytes of all the lent storage (the sizes that fitted).
    pub storage_bytes: usize,
    pub fragments: usize,
    pub drawn: usize,
    pub splits: usize,
    pub shuffles: usize,
    pub unresolved: usize,
    /// Time of the sort that fitted.
    pub sort_us: u64,
}

/// Owned storage for one sort, sized by [`NewellSizes`].
pub struct NewellBuffers {
    vertices: Vec<[f32; 3]>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
    source: Vec<u16>,
    rank: Vec<u32>,
    seams: Vec<[u32; 2]>,
    boxes: Vec<[f32; 6]>,
    work: Vec<u32>,
}

impl NewellBuffers {
    /// Buffers of exactly these sizes.
    pub fn new(sizes: NewellSizes) -> Self {
        Self {
            vertices: vec![[0f32; 3]; sizes.vertices],
            indices: vec![0u32; sizes.indices],
            offsets: vec![0u32; sizes.offsets],
            source: vec![0u16; sizes.source],
            rank: vec![0u32; sizes.rank],
            seams: vec![[0u32; 2]; sizes.seams],
            boxes: vec![[0f32; 6]; sizes.boxes],
            work: vec![0u32; sizes.work],
        }
    }

    /// Bytes of all the buffers.
    pub fn bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(self.vertices.as_slice())
            + size_of_val(self.indices.as_slice())
            + size_of_val(self.offsets.as_slice())
            + size_of_val(self.source.as_slice())
            + size_of_val(self.rank.as_slice())
            + size_of_val(self.seams.as_slice())
            + size_of_val(self.boxes.as_slice())
            + size_of_val(self.work.as_slice())
    }

    /// Sorts `mesh` for `camera` into these buffers.
    pub fn sort(
        &mut self,
        mesh: &Mesh<'_>,
        camera: &Camera,
        cull: bool,
    ) -> Result<NewellOrder<'_>, Error> {
        NewellOrder::sort(
            mesh,
            camera,
            cull,
            NewellStorage {
                vertices: &mut self.vertices,
                indices: &mut self.indices,
                offsets: &mut self.offsets,
                source: &mut self.source,
                rank: &mut self.rank,
                seams: &mut self.seams,
                boxes: &mut self.boxes,
                work: &mut self.work,
            },
        )
    }
}

/// Sorts `mesh` for the view of `camera` (growing the lent storage from a guess of
/// one split per 4 faces until it fits) and hands the order to `f`. `cull`: leave
/// out the faces that do not face the eye, as the renderer does
/// (`Cull::Auto` = the mesh is closed).
pub fn with_newell<R>(
    mesh: &Mesh<'_>,
    camera: &Camera,
    cull: bool,
    f: impl FnOnce(&NewellOrder<'_>, NewellFigures) -> R,
) -> Result<R, String> {
    let mut splits = mesh.face_count() / 4 + 16;
    for _ in 0..16 {
        let sizes = NewellSizes::for_mesh(
            mesh.vertices().len(),
            mesh.face_count(),
            mesh.indices().len(),
            splits,
        );
        let mut buffers = NewellBuffers::new(sizes);
        let storage_bytes = buffers.bytes();
        let start = Instant::now();
        let sorted = buffers.sort(mesh, camera, cull);
        let sort_us = start.elapsed().as_micros() as u64;
        match sorted {
            Ok(order) => {
                let frags = order.fragments();
                let kept_bytes = std::mem::size_of_val(frags.vertices())
                    + std::mem::size_of_val(frags.indices())
                    + std::mem::size_of_val(frags.face_offsets())
                    + std::mem::size_of_val(order.source())
                    + std::mem::size_of_val(order.rank());
                let figures = NewellFigures {
                    kept_bytes,
                    storage_bytes,
                    fragments: order.fragment_count(),
                    drawn: order.drawn(),
                    splits: order.splits(),
                    shuffles: order.shuffles(),
                    unresolved: order.unresolved(),
                    sort_us,
                };
                return Ok(f(&order, figures));
            }
            Err(Error::CapacityExceeded { .. }) => splits = 2 * splits + 64,
            Err(e) => return Err(format!("Newell sort: {e}")),
        }
    }
    Err("Newell sort: storage for 2^16 times the first guess of splits was not enough".into())
}

/// The culling the renderer applies for `spec` (auto: closed meshes).
pub fn culls(spec: &RenderSpec, closed: bool) -> bool {
    match spec.cull {
        CullSpec::On => true,
        CullSpec::Off => false,
        CullSpec::Auto => closed,
    }
}
