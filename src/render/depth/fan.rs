//! The fan triangles `(v0, vi, vi+1)` of a face that is not planar, whose depth
//! [conventions](crate::conventions) gives such a face at a point: which faces take it
//! ([`takes_fan_depth`]), how far they leave the face's single plane ([`bend`]), and
//! their depth at a point ([`fan_depth_at`], [`triangle_at`]).

use super::coverage::polygon_contains;
use super::plane::{exact_at, half_units, plane_through, DepthPlane, STEP_BITS};
use crate::mesh::Mesh;
use crate::order::is_planar;
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::GUARD_BAND_PX;

/// Nearness units added to a bend for the rounding of the fixed-point planes.
pub(crate) const ROUNDING: u32 = 16;

/// A face as the line test sees it: its index, its polygon on screen and single
/// plane, and what its fan triangles are made of.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FaceView<'a> {
    pub mesh: &'a Mesh<'a>,
    pub vertices: &'a [ProjectedVertex],
    pub f: usize,
    pub poly: &'a [ScreenVertex],
    pub plane: &'a DepthPlane,
}

/// Does face `f`, on screen `poly` with single plane `plane`, take its depth from its
/// fan triangles (more than three corners, not planar by [`is_planar`])? Only where
/// the plane leaves some corner ([`bend`]) by more than the rounding and more than the
/// plane's change of depth over one pixel. A smaller bend is left to the plane, a
/// trade measured in `host_tests/tests/frames/non_planar_faces.rs`: on the twisted quads
/// 1 + 171 depth-order and far pixels of 378,765 against 2 + 157 with fan depth for
/// every face not planar, on suzanne 2 + 0 against 1 + 0, and the Z-buffer draws
/// suzanne in 13 % fewer instructions. The (f64) planarity test, asked last, keeps a
/// planar face whose snapped vertices bend it (coarse sub-pixel precision) on its
/// plane, as every engine that has one plane per face draws it.
pub(crate) fn takes_fan_depth(
    mesh: &Mesh<'_>,
    f: usize,
    poly: &[ScreenVertex],
    plane: &DepthPlane,
) -> bool {
    mesh.face(f).len() > 3 && poly.len() > 3 && bends(poly, plane) && !is_planar(mesh, f)
}

/// Whether `plane` leaves a corner of `poly` by more than the rounding and its change of
/// depth over one pixel (out of line: asked of quads only, kept out of the loops that
/// draw triangles).
#[inline(never)]
fn bends(poly: &[ScreenVertex], plane: &DepthPlane) -> bool {
    bend(poly, plane) > ROUNDING.max(plane.change_per_pixel())
}

/// The fan triangles `(v0, vk, vk+1)` of face `f` on screen, those with every corner
/// inside the view volume (others project to something else than the triangle).
pub(crate) fn fan_corners<'a>(
    mesh: &'a Mesh<'_>,
    vertices: &'a [ProjectedVertex],
    f: usize,
) -> impl Iterator<Item = [ScreenVertex; 3]> + 'a {
    let corner = move |v: &u32| {
        vertices
            .get(*v as usize)
            .and_then(ProjectedVertex::projection)
    };
    let face = mesh.face(f);
    let v0 = face.first().and_then(corner);
    face.get(1..)
        .unwrap_or(&[])
        .windows(2)
        .filter_map(move |pair| match pair {
            [a, b] => Some([v0?, corner(a)?, corner(b)?]),
            _ => None,
        })
}

/// Nearness at the centre of pixel (`x`, `y`) of face `f`, not planar: that of the
/// nearest of its fan triangles (those the Z-buffer's `fan_rows` keeps) that holds the centre,
/// evaluated there from the triangle's corners; `None` when none does (the face's
/// single plane decides then). A centre exactly on a fan triangle's edge counts for
/// it here (on the diagonal both triangles, whose planes meet there, are asked). For
/// the few pixels where the single plane cannot decide.
#[inline(never)]
pub(crate) fn fan_depth_at(
    mesh: &Mesh<'_>,
    vertices: &[ProjectedVertex],
    f: usize,
    s: u32,
    (x, y): (u16, u16),
) -> Option<u32> {
    let limit = i64::from(GUARD_BAND_PX) << s;
    let inside = |v: &ScreenVertex| i64::from(v.x).abs() <= limit && i64::from(v.y).abs() <= limit;
    let centre = |k: u16| (2 * i64::from(k) + 1) << s;
    let (cx, cy) = (centre(x), centre(y));
    fan_corners(mesh, vertices, f)
        .filter(|corners| corners.iter().all(inside) && polygon_contains(corners, cx, cy))
        .filter_map(|corners| clamped_at(&corners, cx, cy))
        .max()
}

/// Nearness of the triangle's plane at (`x`, `y`) (half sub-pixel units, a point
/// inside it), clamped to its corners' range (which holds it but for the rounding);
/// `None` when it has no area on screen.
fn clamped_at(corners: &[ScreenVertex; 3], x: i64, y: i64) -> Option<u32> {
    let q = triangle_at(corners, x, y)?;
    let (lo, hi) = corners
        .iter()
        .fold((u32::MAX, 0), |(lo, hi), v| (lo.min(v.q), hi.max(v.q)));
    Some(q.clamp(i64::from(lo), i64::from(hi)) as u32)
}

/// The largest difference of nearness between a corner of `poly` and `plane` there
/// (the plane unclamped: clamped to the vertices' range at a corner, it could meet
/// the corner there and still leave the fan triangle between).
pub(crate) fn bend(poly: &[ScreenVertex], plane: &DepthPlane) -> u32 {
    poly.iter()
        .map(|c| {
            let q = plane.unclamped(2 * i64::from(c.x), 2 * i64::from(c.y));
            let d = q.abs_diff(i64::from(c.q) << STEP_BITS) >> STEP_BITS;
            u32::try_from(d).unwrap_or(u32::MAX)
        })
        .max()
        .unwrap_or(0)
}

/// Nearness at (`x`, `y`) (half sub-pixel units) of the plane through a triangle's
/// corners, `None` when it has no area on screen.
pub(crate) fn triangle_at([v0, v1, v2]: &[ScreenVertex; 3], x: i64, y: i64) -> Option<i64> {
    let (x0, y0, q0) = half_units(v0);
    let coefficients = plane_through(v0, v1, v2);
    (coefficients.2 != 0).then(|| exact_at(q0, coefficients, x - x0, y - y0))
}
