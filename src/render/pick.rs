//! Picking: what is under one pixel. The visible face (the Z-buffer's decision at
//! the pixel centre, without a buffer) and every feature edge drawn through the
//! pixel, hidden ones included, each with the number of drawn faces in front of it
//! there: the paper's use case of choosing a hidden line on a part behind another.

use fixed::types::extra::LeEqU32;
use heapless::Vec;

use super::idpass::FrameInput;
use super::lines::{edge_on_screen, owns, walk_segment, Bend, REACH_COVERING};
use super::transform::{ProjectedVertex, ScreenVertex};
use super::{begin_frame, bit, face_polygon, need, Settings, Stats};
use crate::camera::Camera;
use crate::geometry::Subpixel;
use crate::mesh::{EdgeAdjacency, Mesh};
use crate::render::depth::coverage::{covers, covers_centre};
use crate::render::depth::fan::FaceView;
use crate::render::depth::fan::{fan_depth_at, takes_fan_depth};
use crate::render::depth::plane::DepthPlane;
use crate::Capacity;
use crate::{Error, Viewport};

/// A feature edge drawn through the picked pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PickedEdge {
    /// Index into the adjacency's edges.
    pub edge: u32,
    /// Nearness (`Q1.31`, larger is nearer) of the edge point at this pixel.
    pub nearness: u32,
    /// Drawn faces other than the edge's own that cover the edge point and are
    /// strictly nearer there: 0 for a visible edge, 1 behind one surface, and so on.
    pub faces_in_front: u16,
}

/// What is under one pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pick {
    /// The face visible at the pixel centre, if any.
    pub face: Option<u16>,
    /// How many entries of the caller's edge slice were written.
    pub edges: usize,
}

/// Storage one pick borrows: `vertices` >= the mesh's vertices, `drawn` >= faces / 32
/// words, `features` >= edges / 32 words (as for a frame).
#[derive(Debug)]
pub struct PickWorkspace<'s> {
    /// The vertex cache.
    pub vertices: &'s mut [ProjectedVertex],
    /// One bit per face: drawn in this view.
    pub drawn: &'s mut [u32],
    /// One bit per mesh edge: a feature edge in this view.
    pub features: &'s mut [u32],
}

/// Picks pixel (`x`, `y`) of a frame of size `viewport`, as the renderers with S =
/// `Frac` sub-pixel bits and `POLY` vertices per clipped face would draw it: the
/// visible face, and the feature edges drawn through the pixel into `edges`, nearest
/// first. More edges than `edges.len()` is [`Error::CapacityExceeded`] with the
/// number needed; a pixel outside the viewport is [`Error::OutOfRange`].
#[allow(clippy::too_many_arguments)]
pub fn pick<Frac: LeEqU32, const POLY: usize>(
    mesh: &Mesh<'_>,
    adjacency: &EdgeAdjacency<'_>,
    camera: &Camera,
    settings: &Settings,
    viewport: Viewport,
    (x, y): (u16, u16),
    ws: PickWorkspace<'_>,
    edges: &mut [PickedEdge],
) -> Result<Pick, Error> {
    if x >= viewport.width || y >= viewport.height {
        return Err(Error::OutOfRange);
    }
    let mut stats = Stats::default();
    let s = Subpixel::<Frac>::BITS;
    let input = FrameInput::of_mesh(mesh, adjacency, camera, settings, s);
    let ctx = begin_frame(
        &input,
        viewport,
        ws.vertices,
        ws.drawn,
        ws.features,
        &mut stats,
    )?;
    let vertices: &[ProjectedVertex] = ws.vertices;
    let drawn: &[u32] = ws.drawn;
    let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
    // The visible face: faces in index order, a later one wins only when nearer by
    // more than its tie (the Z-buffer's rule).
    let centre = |k: u16| (2 * i64::from(k) + 1) << s;
    let mut best: Option<(u16, u32)> = None;
    for f in 0..mesh.face_count() {
        if !bit(drawn, f) || !face_polygon(&ctx, vertices, f, &mut poly)? {
            continue;
        }
        if !covers_centre(&poly, s, i64::from(x), i64::from(y)) {
            continue;
        }
        let Some(plane) = DepthPlane::new(&poly, s) else {
            continue;
        };
        // A face that is not planar: its fan triangle's depth, as the engines take it.
        let q = takes_fan_depth(mesh, f, &poly, &plane)
            .then(|| fan_depth_at(mesh, vertices, f, s, (x, y)))
            .flatten()
            .unwrap_or_else(|| plane.at(centre(x), centre(y)));
        if best.is_none_or(|(_, b)| q > b.saturating_add(plane.tie())) {
            best = Some((f as u16, q));
        }
    }
    // The edges through the pixel.
    let mut found = 0usize;
    for (e, edge) in adjacency.edges().iter().enumerate() {
        if !bit(ws.features, e) {
            continue;
        }
        let Some((a, b)) = edge_on_screen(&ctx, vertices, edge) else {
            continue;
        };
        let mut point = None;
        walk_segment(&a, &b, s, viewport.width, y..y + 1, |px| {
            if px.x == x && px.y == y {
                point = Some(px);
            }
        });
        let Some(px) = point.map(|px| px.with_slack(&ctx.view.depth_grid())) else {
            continue;
        };
        let mut in_front = 0u16;
        if settings.mode != super::DrawMode::Wireframe {
            for f in 0..mesh.face_count() {
                let own = owns(mesh, edge, f);
                if own || !bit(drawn, f) || !face_polygon(&ctx, vertices, f, &mut poly)? {
                    continue;
                }
                if !covers(&poly, px.px, px.py) {
                    continue;
                }
                let Some(plane) = DepthPlane::new(&poly, s) else {
                    continue;
                };
                // As the line pass asks it (the fan triangle's depth where the
                // face's bend could change the answer).
                let face = FaceView {
                    mesh,
                    vertices,
                    f,
                    poly: &poly,
                    plane: &plane,
                };
                let at = (px.px, px.py);
                if Bend::of(mesh.face(f).len()).nearer(&face, &px, at, REACH_COVERING) {
                    in_front = in_front.saturating_add(1);
                }
            }
        }
        if let Some(slot) = edges.get_mut(found) {
            *slot = PickedEdge {
                edge: e as u32,
                nearness: px.q,
                faces_in_front: in_front,
            };
        }
        found += 1;
    }
    need(Capacity::PickedEdges, found, edges.len())?;
    if let Some(list) = edges.get_mut(..found) {
        crate::sort::sort_by_key(list, |p| (p.faces_in_front, u32::MAX - p.nearness, p.edge));
    }
    Ok(Pick {
        face: best.map(|(f, _)| f),
        edges: found,
    })
}
