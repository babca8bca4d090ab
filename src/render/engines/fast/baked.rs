//! Per-mesh constants of the fast engine, made once on the host (in a `build.rs`)
//! and kept in flash: each face's Newell normal and centroid, and the compact edge
//! list (two vertex and two face indices and the edge's kind). A frame then
//! computes nothing that depends only on the mesh.

use core::fmt;

use super::edge::{CompactEdge, MAX_HOLES, NO_HOLE};
use super::holes::label_holes;
use crate::error::need;
use crate::mesh::{EdgeAdjacency, EdgeKind, Mesh};
use crate::Capacity;
use crate::{EdgeProblem, Error};

/// The most faces and vertices the fast engine names: face ids are 16 bits
/// (`0xFFFF` is "no face").
pub const MAX_FAST_FACES: usize = 0xFFFF;

/// A face's Newell normal and centroid, exactly as [`Mesh::face_normal`] and
/// [`Mesh::face_centroid`] compute them (so the facing test gives the same answer
/// as the exact engines').
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FacePlane {
    /// Newell normal (not normalized).
    pub normal: [f32; 3],
    /// Mean of the face's corners.
    pub centroid: [f32; 3],
}

/// A mesh with its per-mesh constants, checked once: what the fast engine draws.
#[derive(Debug, Clone, Copy)]
pub struct BakedMesh<'a> {
    mesh: Mesh<'a>,
    planes: &'a [FacePlane],
    edges: &'a [CompactEdge],
    closed: bool,
    around: super::VertexFaces<'a>,
    piercings: &'a [super::Piercing],
}

impl<'a> BakedMesh<'a> {
    /// Writes the per-mesh constants of `mesh` (whose edge list is `adjacency`) into
    /// `planes` (one per face) and `edges` (one per edge of `adjacency`), with the
    /// boundary edges labelled by hole when the mesh with its holes capped is
    /// nowhere inside-out (checked along rays from both sides of every face; the
    /// cost grows with faces squared, so meshes of up to
    /// [`MAX_CHECKED_FACES`](super::MAX_CHECKED_FACES) faces are checked). Run on the
    /// host, in a `build.rs`; [`BakedSource`] prints the result as Rust statics.
    /// Too small a buffer is `CapacityExceeded`; more than [`MAX_FAST_FACES`] faces or
    /// vertices is `TooManyFaces`.
    pub fn bake(
        mesh: &Mesh<'_>,
        adjacency: &EdgeAdjacency<'_>,
        planes: &mut [FacePlane],
        edges: &mut [CompactEdge],
    ) -> Result<(), Error> {
        check_counts(mesh)?;
        let faces = mesh.face_count();
        let all = adjacency.edges();
        need(Capacity::Faces, faces, planes.len())?;
        need(Capacity::Edges, all.len(), edges.len())?;
        for (f, slot) in planes.iter_mut().enumerate().take(faces) {
            *slot = FacePlane {
                normal: mesh.face_normal(f),
                centroid: mesh.face_centroid(f),
            };
        }
        for (e, slot) in all.iter().zip(edges.iter_mut()) {
            // check_counts bounds both indices by 0xFFFF.
            *slot = CompactEdge {
                a: e.a as u16,
                b: e.b as u16,
                faces: [e.faces[0] as u16, e.faces[1] as u16],
                kind: e.kind,
                hole: NO_HOLE,
            };
        }
        if let Some(baked) = edges.get_mut(..all.len()) {
            label_holes(mesh, baked);
        }
        Ok(())
    }

    /// The baked mesh, checked in one pass: one plane per face, equal bit for bit to
    /// the face's normal and centroid; every edge's ends and faces in range, `a < b`,
    /// and a kind that agrees with its faces, and a hole label on boundary edges
    /// only, below [`MAX_HOLES`], on all of them or none (else `BadEdgeList`).
    /// `closed` is whether every edge has two faces (for `Cull::Auto`). That the
    /// capped surface is nowhere inside-out is the host's check, not redone here.
    pub fn new(
        mesh: Mesh<'a>,
        planes: &'a [FacePlane],
        edges: &'a [CompactEdge],
    ) -> Result<Self, Error> {
        check_counts(&mesh)?;
        let faces = mesh.face_count();
        if planes.len() != faces {
            return Err(Error::BadFacePlanes {
                face: planes.len().min(faces),
            });
        }
        for (f, p) in planes.iter().enumerate() {
            let same = |a: [f32; 3], b: [f32; 3]| a.map(f32::to_bits) == b.map(f32::to_bits);
            if !same(p.normal, mesh.face_normal(f)) || !same(p.centroid, mesh.face_centroid(f)) {
                return Err(Error::BadFacePlanes { face: f });
            }
        }
        let vertices = mesh.vertices().len();
        let mut closed = true;
        // Either every boundary edge names its hole or none does.
        let holes_labelled = edges
            .iter()
            .find(|e| e.kind == EdgeKind::Boundary)
            .is_some_and(|e| e.hole != NO_HOLE);
        for (i, e) in edges.iter().enumerate() {
            let bad = |problem| Err(Error::BadEdgeList { edge: i, problem });
            if usize::from(e.b) >= vertices {
                return bad(EdgeProblem::EndOutOfRange);
            }
            if e.a >= e.b {
                return bad(EdgeProblem::EndsNotAscending);
            }
            if e.faces.iter().any(|&f| usize::from(f) >= faces) {
                return bad(EdgeProblem::FaceOutOfRange);
            }
            let single = e.faces[0] == e.faces[1];
            if single != (e.kind == EdgeKind::Boundary) {
                return bad(EdgeProblem::FacesDisagree);
            }
            closed &= closes(e);
            let labelled = e.hole != NO_HOLE;
            if usize::from(e.hole) >= MAX_HOLES && labelled
                || labelled != (e.kind == EdgeKind::Boundary && holes_labelled)
            {
                return bad(EdgeProblem::HoleLabel);
            }
        }
        Ok(Self {
            mesh,
            planes,
            edges,
            closed,
            around: super::VertexFaces::EMPTY,
            piercings: &[],
        })
    }

    /// The constants [`bake`](Self::bake) wrote here, unchecked: for a caller that
    /// keeps them beside the mesh it baked ([`Drawing`](crate::Drawing)).
    pub(crate) fn baked_here(
        mesh: Mesh<'a>,
        planes: &'a [FacePlane],
        edges: &'a [CompactEdge],
    ) -> Self {
        let closed = edges.iter().all(closes);
        Self {
            mesh,
            planes,
            edges,
            closed,
            around: super::VertexFaces::EMPTY,
            piercings: &[],
        }
    }

    /// This mesh with the faces around each vertex (baked by
    /// [`VertexFaces::bake`](super::VertexFaces::bake) from this mesh), which hidden
    /// lines by the segment need ([`LineVisibility::BySegment`](crate::render::LineVisibility));
    /// without them the line modes use the per-pixel test. A table shorter than
    /// the mesh's vertices + 1 or its corners is `CapacityExceeded`.
    pub fn with_vertex_faces(mut self, around: super::VertexFaces<'a>) -> Result<Self, Error> {
        let mesh = &self.mesh;
        need(Capacity::Vertices, mesh.vertices().len(), around.weld.len())?;
        need(
            Capacity::VertexFaces,
            mesh.vertices().len() + 1,
            around.starts.len(),
        )?;
        need(
            Capacity::VertexFaces,
            mesh.indices().len(),
            around.faces.len(),
        )?;
        self.around = around;
        Ok(self)
    }

    /// This mesh with the (edge, triangle) pairs that may meet, from
    /// [`Piercing::bake`](super::Piercing::bake) on this mesh and its edges: hidden
    /// lines by the segment split the edges where they pass through the
    /// triangles. Pairs out of range are `BadEdgeList` (`FaceOutOfRange`), out of order
    /// `BadEdgeList` (`NotSorted`), naming the pair.
    pub fn with_piercings(mut self, pairs: &'a [super::Piercing]) -> Result<Self, Error> {
        let faces = self.mesh.face_count();
        let mut last = 0;
        for (i, p) in pairs.iter().enumerate() {
            let corners = self.mesh.face(usize::from(p.face)).len();
            let fits = usize::from(p.edge) < self.edges.len()
                && usize::from(p.face) < faces
                && p.fan >= 1
                && usize::from(p.fan) + 1 < corners.max(1);
            let problem = if !fits {
                EdgeProblem::FaceOutOfRange
            } else if p.edge < last {
                EdgeProblem::NotSorted
            } else {
                last = p.edge;
                continue;
            };
            return Err(Error::BadEdgeList { edge: i, problem });
        }
        self.piercings = pairs;
        Ok(self)
    }

    /// The baked piercing pairs (none when not given).
    pub fn piercings(&self) -> &'a [super::Piercing] {
        self.piercings
    }

    /// The faces around each vertex ([`VertexFaces::EMPTY`](super::VertexFaces::EMPTY)
    /// when not given).
    pub fn vertex_faces(&self) -> super::VertexFaces<'a> {
        self.around
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh<'a> {
        &self.mesh
    }

    /// One plane per face.
    pub fn planes(&self) -> &'a [FacePlane] {
        self.planes
    }

    /// The compact edge list.
    pub fn edges(&self) -> &'a [CompactEdge] {
        self.edges
    }

    /// Is every edge used by exactly two faces?
    pub fn is_closed(&self) -> bool {
        self.closed
    }
}

/// Is the edge used by exactly two faces (so that it keeps the mesh closed)?
fn closes(e: &CompactEdge) -> bool {
    e.kind != EdgeKind::Boundary && e.kind != EdgeKind::NonManifold
}

fn check_counts(mesh: &Mesh<'_>) -> Result<(), Error> {
    let most = mesh.face_count().max(mesh.vertices().len());
    if most > MAX_FAST_FACES {
        return Err(Error::TooManyFaces {
            faces: most,
            max: MAX_FAST_FACES,
        });
    }
    Ok(())
}

/// Baked constants printed as Rust source: `pub static {NAME}_PLANES` and
/// `pub static {NAME}_EDGES`, for a `build.rs` to write into `OUT_DIR`.
#[derive(Debug, Clone, Copy)]
pub struct BakedSource<'a> {
    /// Prefix of the statics' names.
    pub name: &'a str,
    /// The planes [`BakedMesh::bake`] wrote.
    pub planes: &'a [FacePlane],
    /// The edges it wrote.
    pub edges: &'a [CompactEdge],
}

impl fmt::Display for BakedSource<'_> {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = self.name;
        writeln!(
            out,
            "/// Face normals and centroids, baked on the host by `BakedMesh::bake`."
        )?;
        writeln!(
            out,
            "pub static {name}_PLANES: [pbuffer::render::FacePlane; {}] = [",
            self.planes.len()
        )?;
        // `{:?}` prints the shortest decimal that reads back to the same f32.
        for p in self.planes {
            writeln!(
                out,
                "    pbuffer::render::FacePlane {{ normal: {:?}, centroid: {:?} }},",
                p.normal, p.centroid
            )?;
        }
        writeln!(out, "];")?;
        writeln!(
            out,
            "/// The compact edge list, baked on the host by `BakedMesh::bake`."
        )?;
        writeln!(
            out,
            "pub static {name}_EDGES: [pbuffer::render::CompactEdge; {}] = [",
            self.edges.len()
        )?;
        for e in self.edges {
            writeln!(
                out,
                "    pbuffer::render::CompactEdge {{ a: {}, b: {}, faces: {:?}, kind: pbuffer::mesh::EdgeKind::{:?}, hole: {} }},",
                e.a, e.b, e.faces, e.kind, e.hole
            )?;
        }
        writeln!(out, "];")
    }
}
