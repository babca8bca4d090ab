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
    /// One bit a welded vertex: its faces do not make one fan of sides shared
    /// in pairs (two sheets meet there, a face has it twice, or it is on the
    /// mesh's boundary), so hidden lines by the segment look at it closely.
    pub irregular: &'a [u32],
}

impl<'a> VertexFaces<'a> {
    /// No vertex has a face (a placeholder).
    pub const EMPTY: VertexFaces<'static> = VertexFaces {
        weld: &[],
        starts: &[],
        faces: &[],
        irregular: &[],
    };

    /// Writes the welded ids of `mesh`'s vertices into `weld` (one a vertex),
    /// the faces around each into `starts` (one more) and `faces` (one a face
    /// corner), the irregular vertices into `irregular` (a bit a vertex), and
    /// returns them. Too small a buffer is `CapacityExceeded`; more vertices,
    /// faces or corners than 16 bits name is `TooManyFaces`.
    pub fn bake(
        mesh: &Mesh<'_>,
        weld: &'a mut [u16],
        starts: &'a mut [u16],
        faces: &'a mut [u16],
        irregular: &'a mut [u32],
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
        crate::error::need(Capacity::Vertices, n.div_ceil(32), irregular.len())?;
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
        let irregular = irregular.get_mut(..n.div_ceil(32)).unwrap_or_default();
        irregular.fill(0);
        let table = VertexFaces {
            weld,
            starts,
            faces,
            irregular: &[],
        };
        for v in 0..n as u16 {
            if !table.one_fan(mesh, v) {
                crate::bits::set_bit(irregular, usize::from(v), true);
            }
        }
        Ok(VertexFaces {
            weld,
            starts,
            faces,
            irregular,
        })
    }

    /// Do the faces around welded vertex `v` make one closed fan: each has `v`
    /// once, each neighbour is on exactly two of them, and walking from face to
    /// face across those sides visits them all?
    fn one_fan(&self, mesh: &Mesh<'_>, v: u16) -> bool {
        let around = self.around(v);
        // The neighbours of `v` in face `f`: before and after it.
        let sides = |f: u16| -> Option<[u16; 2]> {
            let c = mesh.face(usize::from(f));
            let n = c.len();
            let mut at = c.iter().enumerate().filter(|(_, &x)| self.welded(x) == v);
            let (k, _) = at.next()?;
            if at.next().is_some() {
                return None;
            }
            let w = |i: usize| self.welded(c.get(i % n).copied().unwrap_or(0));
            Some([w(k + n - 1), w(k + 1)])
        };
        let Some(&first) = around.first() else {
            return true;
        };
        let count = |u: u16| {
            around
                .iter()
                .filter(|&&g| sides(g).is_some_and(|s| s.contains(&u)))
                .count()
        };
        for &f in around {
            match sides(f) {
                Some([p, q]) if p != q && count(p) == 2 && count(q) == 2 => {}
                _ => return false,
            }
        }
        // Walk across the `after` sides.
        let (mut f, mut steps) = (first, 0);
        loop {
            let Some([_, next]) = sides(f) else {
                return false;
            };
            let Some(&g) = around
                .iter()
                .find(|&&g| g != f && sides(g).is_some_and(|s| s.contains(&next)))
            else {
                return false;
            };
            steps += 1;
            f = g;
            if f == first || steps > around.len() {
                break;
            }
        }
        f == first && steps == around.len()
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

    /// Is welded vertex `v` irregular?
    #[inline(always)]
    pub fn is_irregular(&self, v: u16) -> bool {
        crate::bits::bit(self.irregular, usize::from(v))
    }

    /// Vertex `v`'s welded id.
    #[inline(always)]
    pub fn welded(&self, v: u32) -> u16 {
        self.weld.get(v as usize).copied().unwrap_or(v as u16)
    }
}
