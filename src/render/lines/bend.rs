//! The hidden-line test's depth of a face that is not planar.
//! [conventions](crate::conventions) gives
//! such a face the depth of its fan triangle `(v0, vi, vi+1)` at the point; the line
//! test holds one plane per face (the largest fan triangle's, [`DepthPlane::new`]).
//! Within a fan triangle the difference between its plane and the face's is linear,
//! so it is largest at a corner: over the whole face the fan depth stays within the
//! largest corner difference, the face's [`Bend`], of the single plane. Only an edge
//! point nearer to the plane than that asks for the depth of the fan triangle that
//! holds it, evaluated there from the triangle's corners (a plane set up and kept
//! would cost a hundred bytes of a small stack, for a question seldom asked).
//!
//! [`DepthPlane::new`]: crate::render::depth::plane::DepthPlane::new

use super::{margin, EdgePixel};
use crate::render::depth::coverage::polygon_contains;
use crate::render::depth::fan::{bend, fan_corners, triangle_at, FaceView, ROUNDING};

/// How far a face's fan triangles leave its single plane, found when first asked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Bend {
    /// The largest difference of nearness between a fan triangle's corner and the
    /// face's plane there; 0 for a triangle, which has no other plane; `None` until
    /// asked.
    off: Option<u32>,
}

impl Bend {
    /// No bend: the single plane decides.
    pub const NONE: Self = Self { off: Some(0) };

    /// The bend of a face of `corners` corners in the mesh: none for a triangle,
    /// else found when first asked.
    pub fn of(corners: usize) -> Self {
        Self {
            off: (corners <= 3).then_some(0),
        }
    }

    /// True when `face` is nearer than the edge point of `px` by the margin of
    /// `reach` ([`margin`]). Where the fan triangles' depth could decide otherwise
    /// than the single plane, the nearest fan triangle holding (`x`, `y`) (half
    /// sub-pixel units) decides; the single plane when none holds it.
    #[inline]
    pub fn nearer(
        &mut self,
        face: &FaceView<'_>,
        px: &EdgePixel,
        (x, y): (i64, i64),
        reach: u64,
    ) -> bool {
        let q = face.plane.at(px.px, px.py);
        let limit = px.q.saturating_add(margin(face.plane, px, reach));
        // Both the plane (clamped) and the fan triangles stay within the vertices'
        // range: most points are decided before the bend is asked.
        let gap = q.abs_diff(limit);
        if gap > face.plane.span().saturating_add(ROUNDING) {
            return q > limit;
        }
        let off = self.off(face);
        if off == 0 || gap > off.saturating_add(ROUNDING) {
            return q > limit;
        }
        match fan_at(face, x, y, (px.px, px.py)) {
            Some(fan) => fan > i64::from(limit),
            None => q > limit,
        }
    }

    /// The largest difference between a corner's nearness and the plane there.
    /// The polygon's vertices hold every fan triangle's corners that are in view (a
    /// fan triangle with a corner out of the view volume is never asked,
    /// [`fan_corners`]), and points on its edges, which are fan triangles' edges: a
    /// bound, if a loose one where clipped.
    #[inline(never)]
    fn off(&mut self, face: &FaceView<'_>) -> u32 {
        *self.off.get_or_insert_with(|| bend(face.poly, face.plane))
    }
}

/// Nearness at (`px`, `py`) of the face's nearest fan triangle among those whose
/// projection holds (`x`, `y`) (several where the face folds on screen, or on the
/// diagonal between two); `None` when none holds it. Half sub-pixel units.
#[inline(never)]
fn fan_at(face: &FaceView<'_>, x: i64, y: i64, (px, py): (i64, i64)) -> Option<i64> {
    fan_corners(face.mesh, face.vertices, face.f)
        .filter(|corners| polygon_contains(corners, x, y))
        .filter_map(|corners| triangle_at(&corners, px, py))
        .max()
}
