//! Meshes borrowed from the caller, validated once; edge adjacency and feature edges.
//!
//! A [`Mesh`] is three slices in compressed-row form: vertex positions, the vertex
//! indices of every face one after the other, and where each face starts. It is
//! checked once in [`Mesh::new`], so the renderer never meets a bad index or a NaN.
//! [`EdgeAdjacency`] then finds the mesh's unique edges (vertices welded by
//! bit-identical position) and what kind each one is; [`MeshEdge::is_feature`]
//! says which of them a line drawing shows from a given [`Viewpoint`].

mod adjacency;
mod features;
#[cfg(test)]
mod tests;

pub use adjacency::{EdgeAdjacency, HalfEdgeRecord};
pub use features::{face_owns_edge, EdgeKind, MeshEdge};

use crate::bits::bit;
use crate::Capacity;
use crate::Error;

/// Most faces a mesh may have: face ids are 16-bit in the renderer's id buffers.
pub const MAX_FACES: usize = 65_535;

/// A validated mesh borrowing the caller's slices.
///
/// Face `f` is `indices[face_offsets[f] as usize..face_offsets[f + 1] as usize]`
/// (CSR form): `face_offsets.len() == faces + 1`, `face_offsets[0] == 0`, the
/// offsets never decrease and the last one is `indices.len()`. Faces wind
/// counter-clockwise seen from their front.
#[derive(Debug, Clone, Copy)]
pub struct Mesh<'a> {
    vertices: &'a [[f32; 3]],
    indices: &'a [u32],
    face_offsets: &'a [u32],
    /// Kept from validation: the renderer sizes its per-face buffers by it.
    max_face_len: usize,
    /// Which faces are planar, one bit a face, when the caller keeps them
    /// ([`Mesh::with_planar_faces`]).
    planar: Option<&'a [u32]>,
}

/// Where the eye is, for facing tests.
///
/// A face faces the eye when `n . (eye - centroid) > 0` (perspective), or when
/// its normal points toward +Z in eye space (orthographic), that is
/// `n . direction_to_eye > 0` with `direction_to_eye = eye - target`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Viewpoint {
    /// A perspective camera at `eye` (world space).
    Perspective {
        /// The eye position.
        eye: [f32; 3],
    },
    /// An orthographic camera looking along `-direction_to_eye`.
    Orthographic {
        /// Any positive multiple of `eye - target`.
        direction_to_eye: [f32; 3],
    },
}

impl<'a> Mesh<'a> {
    /// Validates the slices once and reports the first problem found, checking in
    /// this order:
    ///
    /// 1. the offsets, face by face: [`Error::BadFaceOffsets`] names the first face
    ///    whose range is wrong (face 0 when the offsets are empty or do not start at
    ///    0; the last face when they do not end at `indices.len()`);
    /// 2. the face count: none is [`Error::EmptyMesh`], more than [`MAX_FACES`] is
    ///    [`Error::TooManyFaces`];
    /// 3. every vertex, in order: [`Error::NonFiniteVertex`];
    /// 4. every face, in order: [`Error::DegenerateFace`] when it has fewer than 3
    ///    indices, then its indices ([`Error::IndexOutOfRange`] with the first bad
    ///    index).
    ///
    /// As in [conventions](crate::conventions), a face needs 3 valid indices, nothing more:
    /// a face whose
    /// positions repeat (`f 1 2 1`) or lie on a line is valid, with a zero normal, so
    /// it covers no pixel and makes no crease or silhouette.
    pub fn new(
        vertices: &'a [[f32; 3]],
        indices: &'a [u32],
        face_offsets: &'a [u32],
    ) -> Result<Self, Error> {
        check_offsets(indices.len(), face_offsets)?;
        let faces = face_offsets.len().saturating_sub(1);
        if faces == 0 {
            return Err(Error::EmptyMesh);
        }
        if faces > MAX_FACES {
            return Err(Error::TooManyFaces {
                faces,
                max: MAX_FACES,
            });
        }
        if let Some(vertex) = vertices
            .iter()
            .position(|v| !v.iter().all(|c| c.is_finite()))
        {
            return Err(Error::NonFiniteVertex { vertex });
        }
        let mut mesh = Self {
            vertices,
            indices,
            face_offsets,
            max_face_len: 0,
            planar: None,
        };
        for face in 0..faces {
            let corners = mesh.face(face);
            if corners.len() < 3 {
                return Err(Error::DegenerateFace { face });
            }
            if let Some(&index) = corners.iter().find(|&&i| mesh.position_bits(i).is_none()) {
                return Err(Error::IndexOutOfRange { face, index });
            }
            mesh.max_face_len = mesh.max_face_len.max(corners.len());
        }
        Ok(mesh)
    }

    /// The mesh of slices that [`new`](Self::new) accepted before with the same
    /// indices and face starts, and reported `max_face_len` for, unchecked: a
    /// scene assembles its union once and poses its positions every frame
    /// (checking that they are finite as it goes).
    pub(crate) fn assembled(
        vertices: &'a [[f32; 3]],
        indices: &'a [u32],
        face_offsets: &'a [u32],
        max_face_len: usize,
        planar: &'a [u32],
    ) -> Self {
        Self {
            vertices,
            indices,
            face_offsets,
            max_face_len,
            planar: Some(planar),
        }
    }

    /// This mesh, with which of its faces are planar kept in `bits` (bit `f % 32` of
    /// word `f / 32` set for a planar face), as [`order::planar_faces`] fills them:
    /// the renderers then read a bit where they would test a face with more than
    /// three corners in every frame (a test in `f64`, in software on a Cortex-M4).
    /// Firmware can make the bits on the host and keep them in flash.
    ///
    /// `bits` needs [`planar_words`]`(face_count)` words, else
    /// [`Error::CapacityExceeded`] with the words needed; words beyond them are not
    /// read. That the bits belong to this mesh is not checked: bits of another mesh
    /// give its faces the wrong depth rule (a fan triangle's or the single plane's),
    /// never a panic.
    ///
    /// [`order::planar_faces`]: crate::order::planar_faces
    pub fn with_planar_faces(self, bits: &'a [u32]) -> Result<Self, Error> {
        let needed = planar_words(self.face_count());
        if bits.len() < needed {
            return Err(Error::CapacityExceeded {
                what: Capacity::FaceBits,
                needed,
                capacity: bits.len(),
            });
        }
        Ok(Self {
            planar: Some(bits),
            ..self
        })
    }

    /// Whether face `f` is planar, from the bits kept by [`Mesh::with_planar_faces`];
    /// `None` when none are kept.
    pub(crate) fn kept_planarity(&self, f: usize) -> Option<bool> {
        self.planar.map(|bits| bit(bits, f))
    }

    /// The vertex positions.
    pub fn vertices(&self) -> &'a [[f32; 3]] {
        self.vertices
    }

    /// The vertex indices of all faces, one face after the other.
    pub fn indices(&self) -> &'a [u32] {
        self.indices
    }

    /// The face offsets (CSR form), one more than the faces.
    pub fn face_offsets(&self) -> &'a [u32] {
        self.face_offsets
    }

    /// Number of faces, at least 1 and at most [`MAX_FACES`].
    pub fn face_count(&self) -> usize {
        self.face_offsets.len().saturating_sub(1)
    }

    /// Vertex indices of face `f` (empty slice when out of range).
    pub fn face(&self, f: usize) -> &'a [u32] {
        let range = f.checked_add(1).and_then(|next| {
            let start = *self.face_offsets.get(f)? as usize;
            let end = *self.face_offsets.get(next)? as usize;
            self.indices.get(start..end)
        });
        range.unwrap_or(&[])
    }

    /// Largest number of vertices of one face.
    pub fn max_face_len(&self) -> usize {
        self.max_face_len
    }

    /// Newell normal of face `f`: twice its area vector, pointing to the side from
    /// which it winds counter-clockwise. Not normalized; zero for a face of zero
    /// area and for `f` out of range.
    ///
    /// It is summed as the fan `(p_i - p_0) x (p_(i+1) - p_0)`, the same vector as
    /// Newell's `p_i x p_(i+1)` for any polygon, planar or not, but rounded relative
    /// to the face rather than to the origin, so that a small face far from the
    /// origin keeps its normal and an exactly collinear triangle gets exactly zero.
    pub fn face_normal(&self, f: usize) -> [f32; 3] {
        let mut corners = self
            .face(f)
            .iter()
            .filter_map(|&i| self.vertices.get(i as usize));
        let Some(origin) = corners.next() else {
            return [0.0; 3];
        };
        let mut normal = [0.0; 3];
        let mut previous: Option<[f32; 3]> = None;
        for p in corners {
            let d = sub(p, origin);
            if let Some(q) = previous {
                normal = add(&normal, &cross(&q, &d));
            }
            previous = Some(d);
        }
        normal
    }

    /// Mean of face `f`'s vertices (the origin when `f` is out of range).
    pub fn face_centroid(&self, f: usize) -> [f32; 3] {
        let mut corners = self
            .face(f)
            .iter()
            .filter_map(|&i| self.vertices.get(i as usize));
        let Some(origin) = corners.next() else {
            return [0.0; 3];
        };
        // Offsets from the first vertex keep the sum small for a face far from the origin.
        let mut sum = [0.0f32; 3];
        let mut count = 1.0f32;
        for p in corners {
            sum = add(&sum, &sub(p, origin));
            count += 1.0;
        }
        add(origin, &sum.map(|c| c / count))
    }

    /// Does face `f` face the viewpoint? False for a zero normal and for `f` out of
    /// range; see [`Viewpoint`] for the test.
    pub fn faces_viewpoint(&self, f: usize, view: &Viewpoint) -> bool {
        let toward_eye = match view {
            Viewpoint::Perspective { eye } => sub(eye, &self.face_centroid(f)),
            Viewpoint::Orthographic { direction_to_eye } => *direction_to_eye,
        };
        dot(&self.face_normal(f), &toward_eye) > 0.0
    }

    /// The bit patterns of vertex `i`'s coordinates: equal exactly when the
    /// positions weld. `None` when there is no such vertex.
    pub(crate) fn position_bits(&self, i: u32) -> Option<[u32; 3]> {
        self.vertices.get(i as usize).map(weld_bits)
    }
}

/// The weld key of a position: its coordinates' bit patterns, with `-0.0` written
/// as `0.0` ([conventions](crate::conventions): they weld; a mirrored model's seam has both).
pub(crate) fn weld_bits(p: &[f32; 3]) -> [u32; 3] {
    // Adding +0.0 turns -0.0 into +0.0 and leaves every other value alone.
    p.map(|c| (c + 0.0).to_bits())
}

/// Words of face bits a mesh of `faces` faces needs for
/// [`Mesh::with_planar_faces`]: one bit a face.
pub const fn planar_words(faces: usize) -> usize {
    faces.div_ceil(32)
}

/// Checks the CSR offsets against the index count; see [`Mesh::new`].
fn check_offsets(index_count: usize, offsets: &[u32]) -> Result<(), Error> {
    if offsets.first() != Some(&0) {
        return Err(Error::BadFaceOffsets { face: 0 });
    }
    for (face, pair) in offsets.windows(2).enumerate() {
        if let [start, end] = *pair {
            if end < start || end as usize > index_count {
                return Err(Error::BadFaceOffsets { face });
            }
        }
    }
    if offsets.last().map(|&end| end as usize) != Some(index_count) {
        return Err(Error::BadFaceOffsets {
            face: offsets.len().saturating_sub(2),
        });
    }
    Ok(())
}

fn add(a: &[f32; 3], b: &[f32; 3]) -> [f32; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: &[f32; 3], b: &[f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: &[f32; 3], b: &[f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: &[f32; 3], b: &[f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
