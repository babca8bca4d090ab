//! The library's BSP tree on the host: storage grown until the build fits.

use std::time::Instant;

use pbuffer::mesh::Mesh;
use pbuffer::order::{BspNode, BspSizes, BspStorage, BspTree};
use pbuffer::Error;

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
        let mut vertices = vec![[0f32; 3]; sizes.vertices];
        let mut indices = vec![0u32; sizes.indices];
        let mut offsets = vec![0u32; sizes.offsets];
        let mut source = vec![0u16; sizes.source];
        let mut nodes = vec![BspNode::default(); sizes.nodes];
        let mut seams = vec![[0u32; 2]; sizes.seams];
        let mut work = vec![0u32; sizes.work];
        let start = Instant::now();
        let built = BspTree::build(
            mesh,
            BspStorage {
                vertices: &mut vertices,
                indices: &mut indices,
                offsets: &mut offsets,
                source: &mut source,
                nodes: &mut nodes,
                seams: &mut seams,
                work: &mut work,
            },
        );
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
