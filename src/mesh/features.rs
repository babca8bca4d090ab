//! What an edge is (boundary, crease, ...) and whether a view draws it.

use core::f32::consts::{FRAC_PI_2, PI};

use super::{dot, Mesh, Viewpoint};

/// What an edge is, independent of the view.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EdgeKind {
    /// Used by exactly one face: always drawn.
    Boundary,
    /// Used by three or more faces: always drawn.
    NonManifold,
    /// Two faces whose non-zero normals are more than the crease angle apart:
    /// always drawn.
    Crease,
    /// Two faces with non-zero normals, not a crease: drawn when it is a
    /// silhouette.
    Smooth,
    /// Two faces, at least one with a zero normal: never a crease nor a silhouette.
    Inert,
}

/// One edge of the welded mesh: a pair of welded vertices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MeshEdge {
    /// The lower end: the lowest vertex index at its position.
    pub a: u32,
    /// The higher end: the lowest vertex index at its position; `a < b`.
    pub b: u32,
    /// The two lowest-numbered faces using the edge; `faces[1] == faces[0]` when
    /// only one face does.
    pub faces: [u32; 2],
    /// How many distinct faces use the edge (a face that runs along it twice
    /// counts once).
    pub face_count: u32,
    /// What the edge is.
    pub kind: EdgeKind,
}

impl MeshEdge {
    /// A placeholder to fill the caller's edge buffer with, such as
    /// `[MeshEdge::EMPTY; N]` in a `static`.
    pub const EMPTY: Self = Self {
        a: 0,
        b: 0,
        faces: [0; 2],
        face_count: 0,
        kind: EdgeKind::Boundary,
    };

    /// Is the edge drawn in this view? Boundary, non-manifold and crease edges
    /// always are; a smooth edge when exactly one of its two faces faces the
    /// viewpoint (a silhouette); an inert edge never.
    pub fn is_feature(&self, mesh: &Mesh<'_>, view: &Viewpoint) -> bool {
        match self.kind {
            EdgeKind::Boundary | EdgeKind::NonManifold | EdgeKind::Crease => true,
            EdgeKind::Inert => false,
            EdgeKind::Smooth => {
                let [f, g] = self.faces;
                mesh.faces_viewpoint(f as usize, view) != mesh.faces_viewpoint(g as usize, view)
            }
        }
    }
}

impl Default for MeshEdge {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// Is `face` one of `edge`'s own faces: does it have the edge's two welded
/// positions as consecutive corners (either way round, closing pair included)?
///
/// This is how to find the faces of a non-manifold edge beyond the two in
/// [`MeshEdge::faces`]. Positions are compared bit for bit, as the weld does, so
/// no weld buffer is needed and the answer agrees with [`EdgeAdjacency`]
/// exactly. False when `face` is out of range or `edge` names no vertex of
/// `mesh`.
///
/// [`EdgeAdjacency`]: super::EdgeAdjacency
pub fn face_owns_edge(mesh: &Mesh<'_>, edge: &MeshEdge, face: usize) -> bool {
    let (Some(a), Some(b)) = (mesh.position_bits(edge.a), mesh.position_bits(edge.b)) else {
        return false;
    };
    if a == b {
        return false;
    }
    let corners = mesh.face(face);
    let Some(mut previous) = corners.last().and_then(|&i| mesh.position_bits(i)) else {
        return false;
    };
    corners.iter().any(|&i| {
        let Some(current) = mesh.position_bits(i) else {
            return false;
        };
        let hit = (previous == a && current == b) || (previous == b && current == a);
        previous = current;
        hit
    })
}

/// The kind of an edge used by `face_count` distinct faces, the first two being
/// `faces`. `crease_cos` is the cosine of the crease angle.
pub(super) fn classify(
    mesh: &Mesh<'_>,
    faces: [u32; 2],
    face_count: u32,
    crease_cos: f32,
) -> EdgeKind {
    match face_count {
        0 | 1 => EdgeKind::Boundary,
        2 => {
            let [f, g] = faces.map(|f| scaled(mesh.face_normal(f as usize)));
            match (f, g) {
                (Some(n1), Some(n2)) if is_crease(&n1, &n2, crease_cos) => EdgeKind::Crease,
                (Some(_), Some(_)) => EdgeKind::Smooth,
                _ => EdgeKind::Inert,
            }
        }
        _ => EdgeKind::NonManifold,
    }
}

/// `n` divided by its largest component magnitude, so that its length lies in
/// `[1, sqrt 3]` and the squares in [`is_crease`] cannot overflow; `None` for a
/// zero normal, or one that overflowed (which only coordinates beyond ~1e19 make).
fn scaled(n: [f32; 3]) -> Option<[f32; 3]> {
    if !n.iter().all(|c| c.is_finite()) {
        return None;
    }
    let largest = n.iter().fold(0.0f32, |m, c| m.max(c.abs()));
    if largest > 0.0 {
        Some(n.map(|c| c / largest))
    } else {
        None
    }
}

/// Is the angle between the normals greater than the crease angle, whose cosine
/// is `c`? That is `n1 . n2 < c |n1| |n2|`, decided in f32 on the squares, so that
/// no square root (and no approximate one) is taken:
/// with `d = n1 . n2` and `m = |n1|^2 |n2|^2`, for `c >= 0` it holds when `d < 0`
/// or `d^2 < c^2 m`; for `c < 0` when `d < 0` and `d^2 > c^2 m`.
fn is_crease(n1: &[f32; 3], n2: &[f32; 3], c: f32) -> bool {
    let d = dot(n1, n2);
    let m = dot(n1, n1) * dot(n2, n2);
    let threshold = c * c * m;
    if c >= 0.0 {
        d < 0.0 || d * d < threshold
    } else {
        d < 0.0 && d * d > threshold
    }
}

/// Cosine of an angle in degrees, clamped to `[0, 180]` (the range of angles
/// between two normals, so nothing is lost), accurate to about 1e-7.
///
/// Not `micromath`'s cosine: its error of about 1e-3 would move the crease
/// threshold by a tenth of a degree.
pub(crate) fn cos_degrees(degrees: f32) -> f32 {
    let x = degrees.clamp(0.0, 180.0) * (PI / 180.0);
    // cos x = -cos(pi - x) folds the angle onto [0, pi/2], where the Taylor series
    // to the x^14 term is within f32 rounding.
    let (y, sign) = if x > FRAC_PI_2 {
        (PI - x, -1.0)
    } else {
        (x, 1.0)
    };
    let y2 = y * y;
    // Horner form of 1 - y^2/(1*2) (1 - y^2/(3*4) (1 - ...)).
    let mut c = 1.0f32;
    for k in (1..=7u8).rev() {
        let odd = f32::from(2 * k - 1);
        let even = f32::from(2 * k);
        c = 1.0 - y2 / (odd * even) * c;
    }
    sign * c
}
