//! The welded vertices and the faces around each, baked once per mesh: what
//! hidden lines by the segment ask of the topology ([`super::chains`]).

use crate::mesh::Mesh;
use crate::sort::sort_by_key;
use crate::{Capacity, Error};

/// The mesh's welded vertices (the lowest id at each position, compared bit for
/// bit as [`EdgeAdjacency`](crate::mesh::EdgeAdjacency) welds) and the faces
/// around each: welded vertex `v`'s faces are `faces[starts[v]..starts[v + 1]]`
/// (a face once for each of its corners there). Baked by [`VertexFaces::bake`]:
/// `weld` one entry a vertex, `starts` one more, `faces` one a face corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VertexFaces<'a> {
    /// Each vertex's welded id.
    pub weld: &'a [u16],
    /// Where each welded vertex's faces start in `faces`, and the end.
    pub starts: &'a [u16],
    /// The faces, vertex by vertex.
    pub faces: &'a [u16],
}

impl<'a> VertexFaces<'a> {
    /// No vertex has a face (a placeholder).
    pub const EMPTY: VertexFaces<'static> = VertexFaces {
        weld: &[],
        starts: &[],
        faces: &[],
    };

    /// Writes the welded ids of `mesh`'s vertices into `weld` (at least the
    /// vertices), the faces around each into `starts` (at least the vertices +
    /// 1) and `faces` (at least the face corners), and returns them. Too small a
    /// buffer is `CapacityExceeded`; more vertices, faces or corners than 16 bits
    /// name is `TooManyFaces`.
    pub fn bake(
        mesh: &Mesh<'_>,
        weld: &'a mut [u16],
        starts: &'a mut [u16],
        faces: &'a mut [u16],
    ) -> Result<VertexFaces<'a>, Error> {
        let n = mesh.vertices().len();
        let corners = mesh.indices().len();
        let most = usize::from(u16::MAX);
        if corners > most || n > most || mesh.face_count() > most {
            return Err(Error::TooManyFaces {
                faces: mesh.face_count(),
                max: most,
            });
        }
        crate::error::need(Capacity::Vertices, n, weld.len())?;
        crate::error::need(Capacity::VertexFaces, n + 1, starts.len())?;
        crate::error::need(Capacity::VertexFaces, corners, faces.len())?;
        let weld = weld.get_mut(..n).unwrap_or_default();
        let starts = starts.get_mut(..=n).unwrap_or_default();
        // Ids sorted by position, then id: each run's first is its lowest.
        let order = starts.get_mut(..n).unwrap_or_default();
        for (i, slot) in order.iter_mut().enumerate() {
            *slot = i as u16;
        }
        sort_by_key(order, |&v| (mesh.position_bits(u32::from(v)), v));
        let mut first = 0u16;
        for (i, &v) in order.iter().enumerate() {
            let prev = i.checked_sub(1).and_then(|p| order.get(p)).copied();
            let same = prev.is_some_and(|p| {
                mesh.position_bits(u32::from(p)) == mesh.position_bits(u32::from(v))
            });
            if !same {
                first = v;
            }
            if let Some(w) = weld.get_mut(usize::from(v)) {
                *w = first;
            }
        }
        let welded = |v: u32| weld.get(v as usize).copied().unwrap_or(0);
        starts.fill(0);
        for &v in mesh.indices() {
            if let Some(s) = starts.get_mut(usize::from(welded(v)) + 1) {
                *s += 1;
            }
        }
        for i in 0..n {
            let before = starts.get(i).copied().unwrap_or(0);
            if let Some(s) = starts.get_mut(i + 1) {
                *s += before;
            }
        }
        // Filled from each vertex's end down, so faces come in ascending order.
        for f in (0..mesh.face_count()).rev() {
            for &v in mesh.face(f).iter().rev() {
                if let Some(s) = starts.get_mut(usize::from(welded(v)) + 1) {
                    *s -= 1;
                    if let Some(slot) = faces.get_mut(usize::from(*s)) {
                        *slot = f as u16;
                    }
                }
            }
        }
        // Each vertex's start is now one entry up: moved down into place.
        for i in 0..n {
            let next = starts.get(i + 1).copied().unwrap_or(0);
            if let Some(s) = starts.get_mut(i) {
                *s = next;
            }
        }
        if let Some(s) = starts.get_mut(n) {
            *s = corners as u16;
        }
        let faces = faces.get(..corners).unwrap_or_default();
        Ok(VertexFaces {
            weld,
            starts,
            faces,
        })
    }

    /// The faces around welded vertex `v`.
    #[inline(always)]
    pub fn around(&self, v: u16) -> &'a [u16] {
        let v = usize::from(v);
        match (self.starts.get(v), self.starts.get(v + 1)) {
            (Some(&s), Some(&e)) => self
                .faces
                .get(usize::from(s)..usize::from(e))
                .unwrap_or(&[]),
            _ => &[],
        }
    }

    /// Vertex `v`'s welded id.
    #[inline(always)]
    pub fn welded(&self, v: u32) -> u16 {
        self.weld.get(v as usize).copied().unwrap_or(v as u16)
    }
}
