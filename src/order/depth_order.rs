//! A front-to-back order of a mesh's surfaces ([`DepthOrder`]): what a BSP tree or
//! Newell's sort makes and the code-fill engine's priority scheme draws.

use crate::mesh::Mesh;

/// Surfaces in a front-to-back order: the fill pass scans `surfaces` (the mesh's
/// faces or fragments of them) and reports each as its source face.
#[derive(Debug, Clone, Copy)]
pub struct DepthOrder<'o> {
    /// The surfaces: their vertices begin with the mesh's vertices, bit for bit
    /// (so the mesh's indices still hold), followed by any new ones.
    pub surfaces: Mesh<'o>,
    /// `source[s]`: the mesh face surface `s` lies in.
    pub source: &'o [u16],
    /// `rank[s]`: surface `s`'s place front to back (lower is nearer; equal ranks
    /// go by surface index).
    pub rank: &'o [u32],
}

impl DepthOrder<'_> {
    /// Whether this order was made for `mesh`: its vertices begin with the mesh's,
    /// every surface has a source face of the mesh and a rank.
    pub(crate) fn fits(&self, mesh: &Mesh<'_>) -> bool {
        let n = self.surfaces.face_count();
        let v = mesh.vertices();
        self.source.len() >= n
            && self.rank.len() >= n
            && self.surfaces.vertices().get(..v.len()).is_some_and(|head| {
                head.iter()
                    .zip(v)
                    .all(|(a, b)| a.map(f32::to_bits) == b.map(f32::to_bits))
            })
            && self
                .source
                .iter()
                .take(n)
                .all(|&f| usize::from(f) < mesh.face_count())
    }
}
