//! Ray casting: one ray per pixel centre, through a bounding-volume hierarchy over
//! the drawn faces' screen boxes, built once per frame in lent storage.
//!
//! After projection the ray through a pixel centre is the line of constant screen
//! (x, y), along which nearness `q` is affine: the ray meets a face where the face
//! covers the centre ([`covers_centre`], the scan converter's decision) and at the
//! face's plane nearness there, the very value the Z-buffer stores; a face that is
//! not planar ([`takes_fan_depth`]) at the nearness of its fan triangle that holds
//! the centre ([`fan_depth_at`], as the scan-line method asks it;
//! [conventions](crate::conventions)).
//! The cast is exact in fixed point, and it decides each pixel as the Z-buffer
//! does (32-bit depth): of the covering faces taken in index order, a later face
//! wins only when nearer by more than its tie. (A fan triangle's depth is evaluated
//! from its corners here and from its plane in the Z-buffer: the two can round
//! apart where two faces cross.) The pruning bound, a face's largest corner
//! nearness, holds its fan triangles too.
//!
//! [`fan_depth_at`]: crate::render::depth::fan::fan_depth_at
//!
//! [`covers_centre`]: crate::render::depth::coverage::covers_centre
//!
//! Pruning without losing that rule: the faces that can matter at a pixel are the
//! set H of the nearest covering faces closed under "within a tie": walking the
//! covering faces nearest first, a face joins H while its nearness reaches
//! `floor(H) = min over H of (q - tie)`. Every face of H beats every face below the
//! floor and none of those can beat a face of H, so the index-order rule over H alone
//! gives the Z-buffer's answer. The trace visits nodes nearest first and prunes a
//! node whose largest nearness is below the current floor; since the floor of a
//! partial H can end higher than the final one, the largest bound set aside is
//! remembered, and when it reaches the final floor the pixel is decided again by an
//! exhaustive pass in index order (counted in [`RaycastFigures::fallbacks`]).
//!
//! Coherence: rays are cast in 8x8 tiles. One walk of the tree lists the faces
//! whose boxes meet the tile, sorted by their largest nearness; each pixel walks
//! that list until a face's bound falls below the floor (then the floor is final).
//! A tile meeting more faces than the list holds is traced pixel by pixel through
//! the tree, nearest child first, the previous pixel's face tried first.

mod bvh;
#[cfg(test)]
mod tests;
mod trace;

use core::marker::PhantomData;

use embedded_graphics_core::pixelcolor::PixelColor;
use fixed::types::extra::LeEqU32;
use heapless::Vec;

use crate::camera::Camera;
use crate::geometry::Subpixel;
use crate::mesh::{EdgeAdjacency, Mesh};
use crate::render::band::IdBand;
use crate::render::compose::{Flat, FrameProbe, Palette};
use crate::render::depth::fan::takes_fan_depth;
use crate::render::depth::plane::{DepthPlane, RowPlane};
use crate::render::idpass::{render_ids, FrameInput, IdPass, IdWorkspace};
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::{bit, face_polygon, need, FrameCtx, Settings, Stats};
use crate::Capacity;
use crate::{Error, SpanSink};
use bvh::centre_box;

/// Pixels on a side of the tiles traced together: one walk of the tree lists the
/// faces that meet the tile, and each pixel of the tile walks that list.
const TILE: u16 = 8;

/// Most faces a tile's list holds; a tile meeting more is traced pixel by pixel.
const TILE_FACES: usize = 48;

/// One node of the bounding-volume hierarchy: the pixel centres its faces' boxes
/// reach (inclusive, clamped to the frame) and their largest nearness.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BvhNode {
    x0: u16,
    y0: u16,
    x1: u16,
    y1: u16,
    /// The largest nearness of any face below.
    q_max: u32,
    /// Inner node: the first of its two children (the second follows it). Leaf: the
    /// first of its faces in [`RaycastStorage::faces`].
    index: u32,
    /// 0 for an inner node, else the leaf's face count.
    count: u32,
}

impl BvhNode {
    fn contains(&self, x: u16, y: u16) -> bool {
        self.x0 <= x && x <= self.x1 && self.y0 <= y && y <= self.y1
    }
}

/// One drawn face as the rays see it: the pixel centres its box reaches, its depth
/// plane, and whether its polygon is clipped (then the polygon is clipped again at
/// each test; an unclipped face's polygon is read from the vertex cache through the
/// mesh's indices, which costs a copy of a few vertices).
///
/// Measured (400x240, fitted camera): suzanne makes 51 thousand coverage tests a
/// frame and teapot 94 thousand, with no clipped face in either
/// ([`RaycastFigures::clipped_faces`]); a cache of clipped polygons would cost
/// `POLY` screen vertices per face for the rare near-plane cut, so they are
/// recomputed, and unclipped ones are only the mesh's indices into the vertex cache.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RayFace {
    plane: RowPlane,
    x0: u16,
    y0: u16,
    x1: u16,
    y1: u16,
    face: u16,
    clipped: bool,
    /// Not planar: its depth is its fan triangle's at each centre
    /// ([`takes_fan_depth`]).
    bent: bool,
}

impl RayFace {
    fn contains(&self, x: u16, y: u16) -> bool {
        self.x0 <= x && x <= self.x1 && self.y0 <= y && y <= self.y1
    }
}

/// Lengths of the slices of a [`RaycastStorage`] for a mesh of some face count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RaycastSizes {
    /// Nodes of the hierarchy: at most 2 faces - 1.
    pub nodes: usize,
    /// Face records: one per face (the drawn ones are kept, in the tree's order).
    pub faces: usize,
}

/// Storage the caller lends a [`RaycastRenderer`] for one frame: the hierarchy and
/// its face records (which are also the tree's face order; there is no separate
/// index array). See [`RaycastStorage::sizes`].
#[derive(Debug)]
pub struct RaycastStorage<'s> {
    /// The hierarchy's nodes, the root first.
    pub nodes: &'s mut [BvhNode],
    /// The drawn faces, in the order the leaves reference.
    pub faces: &'s mut [RayFace],
}

impl RaycastStorage<'_> {
    /// What a mesh of `faces` faces needs.
    pub const fn sizes(faces: usize) -> RaycastSizes {
        let nodes = 2 * faces;
        RaycastSizes {
            nodes: if nodes > 1 { nodes - 1 } else { 1 },
            faces,
        }
    }

    /// Bytes of the lent slices.
    pub fn bytes(&self) -> usize {
        size_of_val(self.nodes) + size_of_val(self.faces)
    }
}

/// Figures of the last frame a [`RaycastRenderer`] drew.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RaycastFigures {
    /// Faces in the hierarchy (drawn, in view, able to cover a pixel centre).
    pub faces: u32,
    /// Nodes of the hierarchy.
    pub nodes: u32,
    /// Pixels the pruned trace could not decide alone (the exhaustive pass did).
    pub fallbacks: u32,
    /// Coverage tests made (faces whose box held the pixel centre).
    pub face_tests: u64,
    /// Faces of the hierarchy whose polygon is clipped (cut again at each test).
    pub clipped_faces: u32,
    /// Pixels traced through the tree one by one (their tile met too many faces
    /// to list); the others walked their tile's face list.
    pub tree_pixels: u64,
}

/// The ray-casting engine: S = `Frac` sub-pixel bits, `POLY` vertices per clipped
/// polygon. Each frame builds a bounding-volume hierarchy over the drawn faces in a
/// lent [`RaycastStorage`], then casts one ray per pixel centre of each band.
#[derive(Debug)]
pub struct RaycastRenderer<Frac, const POLY: usize> {
    figures: RaycastFigures,
    _frac: PhantomData<Frac>,
}

default_is_new!(RaycastRenderer<POLY>);

impl<Frac: LeEqU32, const POLY: usize> RaycastRenderer<Frac, POLY> {
    /// A renderer that has drawn nothing yet.
    pub const fn new() -> Self {
        Self {
            figures: RaycastFigures {
                faces: 0,
                nodes: 0,
                fallbacks: 0,
                face_tests: 0,
                tree_pixels: 0,
                clipped_faces: 0,
            },
            _frac: PhantomData,
        }
    }

    /// Figures of the last frame.
    pub fn figures(&self) -> RaycastFigures {
        self.figures
    }

    /// Renders `mesh` seen by `camera` into `sink`. `storage` must hold
    /// [`RaycastStorage::sizes`] of the mesh's face count, else
    /// [`Error::CapacityExceeded`] with the length needed.
    #[allow(clippy::too_many_arguments)]
    pub fn render<K: SpanSink, P: Palette<Color = K::Color>, R: FrameProbe>(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &EdgeAdjacency<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut IdWorkspace<'_>,
        storage: &mut RaycastStorage<'_>,
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>>
    where
        K::Color: PixelColor,
    {
        let sizes = RaycastStorage::sizes(mesh.face_count());
        need(Capacity::RaycastFaces, sizes.faces, storage.faces.len()).map_err(Error::widen)?;
        need(Capacity::BvhNodes, sizes.nodes, storage.nodes.len()).map_err(Error::widen)?;
        let input = FrameInput::of_mesh(mesh, edges, camera, settings, Subpixel::<Frac>::BITS);
        let mut pass = Cast::<POLY> {
            nodes: storage.nodes,
            faces: storage.faces,
            node_count: 0,
            face_count: 0,
            figures: RaycastFigures::default(),
        };
        let stats =
            render_ids::<POLY, _, _, _, _>(&mut pass, &input, ws, &mut Flat(palette), sink, probe);
        self.figures = pass.figures;
        stats
    }
}

/// One frame's casting.
struct Cast<'a, const POLY: usize> {
    nodes: &'a mut [BvhNode],
    faces: &'a mut [RayFace],
    node_count: usize,
    face_count: usize,
    figures: RaycastFigures,
}

impl<const POLY: usize> IdPass for Cast<'_, POLY> {
    fn begin(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
    ) -> Result<(), Error> {
        let (w, h) = (ctx.viewport.width, ctx.viewport.height);
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        let mut n = 0;
        for f in 0..ctx.mesh.face_count() {
            if !bit(drawn, f) || !face_polygon(ctx, vertices, f, &mut poly)? {
                continue;
            }
            let Some(plane) = DepthPlane::new(&poly, ctx.s) else {
                continue;
            };
            let Some([x0, y0, x1, y1]) = centre_box(&poly, ctx.s, w, h) else {
                continue;
            };
            let clipped = ctx
                .mesh
                .face(f)
                .iter()
                .any(|&v| vertices.get(v as usize).is_none_or(|p| p.outside() != 0));
            let capacity = self.faces.len();
            let slot = self.faces.get_mut(n).ok_or(Error::CapacityExceeded {
                what: Capacity::RaycastFaces,
                needed: n + 1,
                capacity,
            })?;
            *slot = RayFace {
                plane: plane.row_plane(0),
                x0,
                y0,
                x1,
                y1,
                face: f as u16,
                clipped,
                bent: takes_fan_depth(ctx.mesh, f, &poly, &plane),
            };
            n += 1;
            self.figures.clipped_faces += u32::from(clipped);
        }
        self.face_count = n;
        self.build(n)?;
        self.figures.faces = n as u32;
        self.figures.nodes = self.node_count as u32;
        Ok(())
    }

    fn fill(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        _drawn: &[u32],
        band: &mut IdBand<'_>,
        _fresh: u16,
    ) -> Result<u32, Error> {
        let Some(&root) = self.nodes.first().filter(|_| self.node_count > 0) else {
            return Ok(0);
        };
        let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
        let mut list: Vec<u32, TILE_FACES> = Vec::new();
        let rows = band.first.max(root.y0)..(band.first + band.held).min(root.y1 + 1);
        let mut ty = rows.start;
        while ty < rows.end {
            let ty1 = (ty + TILE).min(rows.end) - 1;
            let mut tx = root.x0;
            while tx <= root.x1 {
                let tx1 = (tx + TILE - 1).min(root.x1);
                let listed = self.tile_faces([tx, ty, tx1, ty1], &mut list);
                for y in ty..=ty1 {
                    let mut hint = None;
                    for x in tx..=tx1 {
                        let hit = if listed {
                            self.trace_list(ctx, vertices, x, y, &list, &mut poly)?
                        } else {
                            self.figures.tree_pixels += 1;
                            self.trace(ctx, vertices, x, y, hint, &mut poly)?
                        };
                        hint = hit.map(|h| h.entry);
                        if let Some(slot) = band.row_mut(y).and_then(|r| r.get_mut(usize::from(x)))
                        {
                            *slot = hit.map_or(0, |h| h.face + 1);
                        }
                    }
                }
                tx = tx1 + 1;
            }
            ty = ty1 + 1;
        }
        // Runs of one face along the rows, for the statistics.
        let mut runs = 0;
        for y in rows {
            let mut last = 0;
            for &id in band.row(y) {
                runs += u32::from(id != 0 && id != last);
                last = id;
            }
        }
        Ok(runs)
    }
}
