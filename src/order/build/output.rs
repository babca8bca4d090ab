//! The output of the build: the fragments' slices, the nodes, the split points.

use crate::error::need;
use crate::mesh::{Mesh, MAX_FACES};
use crate::order::bsp::{BspNode, BspTree, NO_NODE};
use crate::order::plane::Plane;
use crate::order::seams::{insert_seam_vertices, Seams};
use crate::Capacity;
use crate::Error;

/// The output slices and how much of each is used (or would be: the write-only
/// ones count on past their capacity so the error can name the exact need).
pub(super) struct Output<'s> {
    pub(super) vertices: &'s mut [[f32; 3]],
    pub(super) vertex_count: usize,
    /// The mesh's vertex count: split points are numbered from here.
    pub(super) base: usize,
    /// `seams[x - base]`: the root segment of split point `x` (see [`Seams`]).
    pub(super) seams: &'s mut [[u32; 2]],
    pub(super) indices: &'s mut [u32],
    pub(super) index_count: usize,
    pub(super) offsets: &'s mut [u32],
    pub(super) source: &'s mut [u16],
    pub(super) fragment_count: usize,
    pub(super) nodes: &'s mut [BspNode],
    pub(super) node_count: usize,
}

impl<'s> Output<'s> {
    pub(super) fn copy_mesh_vertices(&mut self, mesh: &Mesh<'_>) -> Result<(), Error> {
        let from = mesh.vertices();
        let capacity = self.vertices.len();
        let to = self
            .vertices
            .get_mut(..from.len())
            .ok_or(Error::CapacityExceeded {
                what: Capacity::SplitVertices,
                needed: from.len(),
                capacity,
            })?;
        to.copy_from_slice(from);
        self.vertex_count = from.len();
        Ok(())
    }

    /// The split points' root segments, as far as they are made.
    pub(super) fn seams(&self) -> Seams<'_> {
        let vertices: &[[f32; 3]] = self.vertices;
        let roots: &[[u32; 2]] = self.seams;
        let splits = self.vertex_count.saturating_sub(self.base);
        Seams {
            vertices: vertices.get(..self.vertex_count).unwrap_or(vertices),
            base: self.base,
            roots: roots.get(..splits).unwrap_or(roots),
        }
    }

    /// Appends a split point on root segment `root`; `more` further ones are about to
    /// follow (for the error).
    pub(super) fn push_vertex(
        &mut self,
        p: [f32; 3],
        root: [u32; 2],
        more: usize,
    ) -> Result<u32, Error> {
        let capacity = self.vertices.len();
        let slot = self
            .vertices
            .get_mut(self.vertex_count)
            .ok_or(Error::CapacityExceeded {
                what: Capacity::SplitVertices,
                needed: self.vertex_count.saturating_add(more).saturating_add(1),
                capacity,
            })?;
        *slot = p;
        let split = self.vertex_count.saturating_sub(self.base);
        let capacity = self.seams.len();
        let seam = self.seams.get_mut(split).ok_or(Error::CapacityExceeded {
            what: Capacity::SplitSeams,
            needed: split.saturating_add(more).saturating_add(1),
            capacity,
        })?;
        *seam = root;
        let index = u32::try_from(self.vertex_count).map_err(|_| Error::CapacityExceeded {
            what: Capacity::Index32,
            needed: self.vertex_count.saturating_add(1),
            capacity: u32::MAX as usize,
        })?;
        self.vertex_count += 1;
        Ok(index)
    }

    /// Appends a fragment (counting on past the capacity of the write-only slices).
    pub(super) fn emit(&mut self, word: u32, idx: &[u32]) -> Result<(), Error> {
        let start = self.index_count;
        let end = start.saturating_add(idx.len());
        if let Some(to) = self.indices.get_mut(start..end) {
            to.copy_from_slice(idx);
        }
        let f = self.fragment_count;
        if let Some(s) = self.source.get_mut(f) {
            // The face id is below MAX_FACES: it fits 16 bits.
            *s = (word & 0xFFFF) as u16;
        }
        let end_u32 = u32::try_from(end).map_err(|_| Error::CapacityExceeded {
            what: Capacity::Index32,
            needed: end,
            capacity: u32::MAX as usize,
        })?;
        if f == 0 {
            if let Some(o) = self.offsets.first_mut() {
                *o = 0;
            }
        }
        if let Some(o) = self.offsets.get_mut(f.saturating_add(1)) {
            *o = end_u32;
        }
        self.index_count = end;
        self.fragment_count = f.saturating_add(1);
        Ok(())
    }

    /// A new node for `plane`, linked from its parent (`link` = parent * 2 + side).
    pub(super) fn new_node(&mut self, plane: &Plane, link: u32) -> Result<u32, Error> {
        let id = self.node_count;
        let id_u32 = u32::try_from(id).ok().filter(|&n| n < u32::MAX / 2).ok_or(
            Error::CapacityExceeded {
                what: Capacity::Index32,
                needed: id.saturating_add(1),
                capacity: (u32::MAX / 2) as usize,
            },
        )?;
        let first = u32::try_from(self.fragment_count).unwrap_or(u32::MAX);
        if let Some(node) = self.nodes.get_mut(id) {
            *node = BspNode {
                plane: plane.coefficients(),
                first,
                ..BspNode::EMPTY
            };
        }
        if link != NO_NODE {
            if let Some(parent) = self.nodes.get_mut((link / 2) as usize) {
                if link % 2 == 0 {
                    parent.front = id_u32;
                } else {
                    parent.back = id_u32;
                }
            }
        }
        self.node_count = id.saturating_add(1);
        Ok(id_u32)
    }

    /// Closes node `id`: its fragments are those emitted since it was made.
    pub(super) fn close_node(&mut self, id: u32) {
        let fragments = self.fragment_count;
        if let Some(node) = self.nodes.get_mut(id as usize) {
            let count = fragments.saturating_sub(node.first as usize);
            node.count = u32::try_from(count).unwrap_or(u32::MAX);
        }
    }

    /// Makes the fragments watertight: [`insert_seam_vertices`]. Returns the
    /// `work` words used.
    pub(super) fn insert_seam_vertices(&mut self, work: &mut [u32]) -> Result<usize, Error> {
        let vertices: &[[f32; 3]] = self.vertices;
        let roots: &[[u32; 2]] = self.seams;
        let splits = self.vertex_count.saturating_sub(self.base);
        let seams = Seams {
            vertices: vertices.get(..self.vertex_count).unwrap_or(vertices),
            base: self.base,
            roots: roots.get(..splits).unwrap_or(roots),
        };
        let (index_count, words) = insert_seam_vertices(
            seams,
            self.indices,
            self.index_count,
            self.offsets,
            self.fragment_count,
            work,
        )?;
        self.index_count = index_count;
        Ok(words)
    }

    pub(super) fn finish(
        mut self,
        depth: usize,
        pieces: usize,
        work_peak: usize,
        work: &mut [u32],
    ) -> Result<BspTree<'s>, Error> {
        let fragments = self.fragment_count;
        need(Capacity::BspNodes, self.node_count, self.nodes.len())?;
        need(
            Capacity::FragmentOffsets,
            fragments.saturating_add(1),
            self.offsets.len(),
        )?;
        need(Capacity::FragmentSources, fragments, self.source.len())?;
        // Before the seams' split points are inserted: a lower bound.
        need(
            Capacity::FragmentIndices,
            self.index_count,
            self.indices.len(),
        )?;
        if fragments > MAX_FACES {
            return Err(Error::TooManyFaces {
                faces: fragments,
                max: MAX_FACES,
            });
        }
        let sorted_words = self.insert_seam_vertices(work)?;
        let work_peak = work_peak.max(sorted_words);
        let vertices: &'s [[f32; 3]] = self.vertices;
        let indices: &'s [u32] = self.indices;
        let offsets: &'s [u32] = self.offsets;
        let source: &'s [u16] = self.source;
        let nodes: &'s [BspNode] = self.nodes;
        let fragment_mesh = Mesh::new(
            vertices.get(..self.vertex_count).unwrap_or(vertices),
            indices.get(..self.index_count).unwrap_or(indices),
            offsets.get(..=fragments).unwrap_or(offsets),
        )?;
        Ok(BspTree {
            fragments: fragment_mesh,
            source: source.get(..fragments).unwrap_or(source),
            nodes: nodes.get(..self.node_count).unwrap_or(nodes),
            depth,
            pieces,
            work_peak,
        })
    }
}
