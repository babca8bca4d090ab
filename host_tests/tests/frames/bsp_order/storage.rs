//! Owned build storage and CSR meshes: a BSP tree built in storage that fits.

use host_tests::frame::MeshData;
use pbuffer::order::{BspNode, BspSizes, BspStorage, BspTree};
use pbuffer::{Error, Mesh};

/// Owned storage for a build.
pub(super) struct Owned {
    vertices: Vec<[f32; 3]>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
    source: Vec<u16>,
    nodes: Vec<BspNode>,
    seams: Vec<[u32; 2]>,
    work: Vec<u32>,
}

impl Owned {
    pub(super) fn new(s: BspSizes) -> Self {
        Self {
            vertices: vec![[0.0; 3]; s.vertices],
            indices: vec![0; s.indices],
            offsets: vec![0; s.offsets],
            source: vec![0; s.source],
            nodes: vec![BspNode::EMPTY; s.nodes],
            seams: vec![[0; 2]; s.seams],
            work: vec![0; s.work],
        }
    }

    pub(super) fn storage(&mut self) -> BspStorage<'_> {
        BspStorage {
            vertices: &mut self.vertices,
            indices: &mut self.indices,
            offsets: &mut self.offsets,
            source: &mut self.source,
            nodes: &mut self.nodes,
            seams: &mut self.seams,
            work: &mut self.work,
        }
    }
}

/// CSR slices of a mesh.
pub(super) struct Csr {
    vertices: Vec<[f32; 3]>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
}

impl Csr {
    pub(super) fn from_data(data: &MeshData) -> Self {
        let mut offsets = vec![0u32];
        let mut indices = Vec::new();
        for face in &data.faces {
            indices.extend_from_slice(face);
            offsets.push(indices.len() as u32);
        }
        let vertices = data.vertices.iter().map(|v| v.map(|c| c as f32)).collect();
        Self {
            vertices,
            indices,
            offsets,
        }
    }

    pub(super) fn mesh(&self) -> Mesh<'_> {
        Mesh::new(&self.vertices, &self.indices, &self.offsets).unwrap()
    }

    /// Storage sized by `BspSizes::for_mesh` for a growing split budget, until the
    /// build fits; returns the storage and the budget that fitted.
    pub(super) fn storage_that_fits(&self) -> (Owned, usize) {
        let mesh = self.mesh();
        let faces = mesh.face_count();
        let mut splits = faces / 2 + 8;
        loop {
            let sizes = BspSizes::for_mesh(self.vertices.len(), faces, self.indices.len(), splits);
            let mut owned = Owned::new(sizes);
            match BspTree::build(&mesh, owned.storage()) {
                Ok(_) => return (owned, splits),
                Err(Error::CapacityExceeded { .. }) => splits *= 2,
                Err(e) => panic!("build failed: {e}"),
            }
        }
    }
}
