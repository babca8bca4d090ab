//! The library's BSP tree on the host: storage grown until the build fits.

use std::time::Instant;

use pbuffer::mesh::{Mesh, Viewpoint};
use pbuffer::order::{BspNode, BspSizes, BspStorage, BspTree};
use pbuffer::{DepthOrder, Error};

/// A built tree's figures.
#[derive(Clone, Copy, Debug, Default)]
pub struct BspFigures {
    /// Bytes the tree keeps for rendering (fragment vertices, indices, offsets,
    /// sources and nodes; not the build's work words).
    pub kept_bytes: usize,
    /// Bytes of the build's work words actually used.
    pub work_bytes: usize,
    pub fragments: usize,
    pub splits: usize,
    pub depth: usize,
    pub build_us: u64,
}

/// Owned storage for one BSP build, sized by [`BspSizes`].
pub struct BspBuffers {
    vertices: Vec<[f32; 3]>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
    source: Vec<u16>,
    nodes: Vec<BspNode>,
    seams: Vec<[u32; 2]>,
    work: Vec<u32>,
}

impl BspBuffers {
    /// Buffers of exactly these sizes.
    pub fn new(sizes: BspSizes) -> Self {
        Self {
            vertices: vec![[0f32; 3]; sizes.vertices],
            indices: vec![0u32; sizes.indices],
            offsets: vec![0u32; sizes.offsets],
            source: vec![0u16; sizes.source],
            nodes: vec![BspNode::default(); sizes.nodes],
            seams: vec![[0u32; 2]; sizes.seams],
            work: vec![0u32; sizes.work],
        }
    }

    /// Builds the tree of `mesh` into these buffers.
    pub fn build(&mut self, mesh: &Mesh<'_>) -> Result<BspTree<'_>, Error> {
        BspTree::build(
            mesh,
            BspStorage {
                vertices: &mut self.vertices,
                indices: &mut self.indices,
                offsets: &mut self.offsets,
                source: &mut self.source,
                nodes: &mut self.nodes,
                seams: &mut self.seams,
                work: &mut self.work,
            },
        )
    }
}

/// Builds the BSP tree of `mesh` (growing the lent storage from a guess of one split
/// per face until it fits) and hands it to `f`.
pub fn with_bsp<R>(
    mesh: &Mesh<'_>,
    f: impl FnOnce(&BspTree<'_>, BspFigures) -> R,
) -> Result<R, String> {
    let mut splits = mesh.face_count();
    for _ in 0..12 {
        let sizes = BspSizes::for_mesh(
            mesh.vertices().len(),
            mesh.face_count(),
            mesh.indices().len(),
            splits,
        );
        let mut buffers = BspBuffers::new(sizes);
        let start = Instant::now();
        let built = buffers.build(mesh);
        let build_us = start.elapsed().as_micros() as u64;
        match built {
            Ok(tree) => {
                let frags = tree.fragments();
                let kept_bytes = std::mem::size_of_val(frags.vertices())
                    + std::mem::size_of_val(frags.indices())
                    + std::mem::size_of_val(frags.face_offsets())
                    + std::mem::size_of_val(tree.source())
                    + std::mem::size_of_val(tree.nodes());
                let figures = BspFigures {
                    kept_bytes,
                    work_bytes: 4 * tree.work_peak(),
                    fragments: tree.fragment_count(),
                    splits: tree.splits(),
                    depth: tree.depth(),
                    build_us,
                };
                return Ok(f(&tree, figures));
            }
            Err(Error::CapacityExceeded { .. }) => splits = 2 * splits + 64,
            Err(e) => return Err(format!("BSP tree: {e}")),
        }
    }
    Err("BSP tree: storage for 4096 splits per face was not enough".into())
}

/// The per-view walk of a BSP tree (or of none): one rank per fragment and the walk's
/// stack.
pub struct DepthRanks {
    pub rank: Vec<u32>,
    pub stack: Vec<u32>,
}

impl DepthRanks {
    /// Storage for walking `tree` (empty with no tree).
    pub fn new(tree: Option<&BspTree<'_>>) -> Self {
        Self {
            rank: vec![0u32; tree.map_or(0, |t| t.fragment_count())],
            stack: vec![0u32; tree.map_or(0, |t| t.depth())],
        }
    }

    /// Bytes of the ranks and the stack.
    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.rank.as_slice()) + std::mem::size_of_val(self.stack.as_slice())
    }

    /// Ranks `tree`'s fragments for `view`, nearest first: the order to draw them in.
    pub fn order<'a>(
        &'a mut self,
        tree: &'a BspTree<'_>,
        view: &Viewpoint,
    ) -> Result<DepthOrder<'a>, Error> {
        tree.rank_front_to_back(view, &mut self.stack, &mut self.rank)?;
        Ok(DepthOrder {
            surfaces: tree.fragments(),
            source: tree.source(),
            rank: &self.rank,
        })
    }
}
