//! The iterative build of the BSP tree: the work stack of fragment sets, splitting.
//!
//! [`run`] drives it: [`output`] holds the output slices, [`stack`] the work stack
//! (the root set, one node split at a time), [`choose`] picks a set's splitter and
//! [`split`] cuts a polygon by its plane.

mod choose;
mod output;
mod split;
mod stack;

use super::bsp::{BspOptions, BspStorage, BspTree, PLANE_TOLERANCE};
use crate::mesh::Mesh;
use crate::Error;
use output::Output;
use stack::Build;

/// Words of a set header on the work stack: `[words, count, link, level]`.
const HEADER: usize = 4;

/// [`BspTree::build_with`]: copies the vertices, pushes the root set, splits sets
/// until none is left, then checks the write-only slices and wraps the result.
pub(super) fn run<'s>(
    mesh: &Mesh<'_>,
    storage: BspStorage<'s>,
    options: BspOptions,
) -> Result<BspTree<'s>, Error> {
    let BspStorage {
        vertices,
        indices,
        offsets,
        source,
        nodes,
        seams,
        work,
    } = storage;
    let tolerance = PLANE_TOLERANCE;
    let mut out = Output {
        vertices,
        vertex_count: 0,
        base: mesh.vertices().len(),
        seams,
        indices,
        index_count: 0,
        offsets,
        source,
        fragment_count: 0,
        nodes,
        node_count: 0,
    };
    let mut build = Build {
        mesh,
        options,
        tolerance_sq: tolerance * tolerance,
        work,
        top: 0,
        peak: 0,
        depth: 0,
    };
    out.copy_mesh_vertices(mesh)?;
    let pieces = build.push_faces()?;
    while build.top > 0 {
        build.split_top(&mut out)?;
    }
    let depth = build.depth;
    out.finish(depth, pieces, build.peak, build.work)
}
