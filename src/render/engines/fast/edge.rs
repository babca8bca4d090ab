//! The compact edge list's record ([`CompactEdge`]), baked on the host with each
//! boundary edge's hole.

use crate::mesh::EdgeKind;

/// The most holes (boundary loops) a mesh may have for back faces to be skipped.
pub const MAX_HOLES: usize = 16;

/// The label of an edge that bounds no hole (and of every edge of a mesh whose
/// back faces are all drawn).
pub const NO_HOLE: u8 = 0xFF;

/// One edge of the compact edge list: 10 bytes instead of [`MeshEdge`]'s 24.
///
/// [`MeshEdge`]: crate::mesh::MeshEdge
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CompactEdge {
    /// Lower vertex index.
    pub a: u16,
    /// Higher vertex index.
    pub b: u16,
    /// The two lowest-numbered faces using it (equal for a boundary edge).
    pub faces: [u16; 2],
    /// What the edge is.
    pub kind: EdgeKind,
    /// A boundary edge's hole (its loop, below [`MAX_HOLES`]) when the host found
    /// the mesh with its holes capped nowhere inside-out, so that back faces away
    /// from the holes can be skipped; else [`NO_HOLE`].
    pub hole: u8,
}

impl CompactEdge {
    /// A placeholder for lent buffers.
    pub const EMPTY: Self = Self {
        a: 0,
        b: 0,
        faces: [0; 2],
        kind: EdgeKind::Inert,
        hole: NO_HOLE,
    };
}

impl Default for CompactEdge {
    fn default() -> Self {
        Self::EMPTY
    }
}
