//! The short way to draw one mesh with the default (fast) engine.
//!
//! A [`Drawing`] bakes a mesh once ([`Drawing::bake`]: face planes, edges and
//! their kinds, hole labels) and keeps every buffer the engine needs that grows
//! with the mesh; [`FrameRows`] keeps those that grow with the display. Both are
//! sized by const generics, zero-initialised by a `const fn new`, and can live in
//! `static`s. Too small a size is [`Error::CapacityExceeded`] with the size
//! needed, never a truncated picture.
//!
//! What the short form costs against the long one ([`FastRenderer`] with a
//! [`FastWorkspace`] sized by hand and the constants baked on the host):
//! - the baking scratch stays in the `Drawing` (48 bytes an edge and 4 a vertex),
//!   so a large mesh is better baked in a `build.rs` ([`BakedMesh::bake`],
//!   [`BakedSource`]) and kept in flash;
//! - the facing bits take a word a face, and the line masks a word a row of the
//!   display, where the engine needs a bit a face and two words per 32 columns:
//!   the price of not naming derived sizes (stable Rust cannot compute them in a
//!   type). The line masks fit displays up to 16 times wider than high.
//!
//! [`BakedSource`]: crate::render::BakedSource

use crate::Capacity;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::BinaryColor;

use crate::error::need;
use crate::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use crate::render::{
    BakedMesh, CompactEdge, FacePlane, FastRenderer, FastVertex, FastWorkspace, MonoPalette,
    Settings, Stats,
};
use crate::subpixel::U4;
use crate::{Camera, Error, FillSolid, SpanSink, Viewport};

/// The crease angle [`Drawing::bake`] classifies edges with, degrees (the
/// `render` command's default).
pub const CREASE_DEG: f32 = 30.0;

/// Corners of clipped faces a [`Drawing`] holds in one frame.
pub const CLIPPED_CORNERS: usize = 64;

/// A mesh baked for the fast engine, with every buffer that grows with the mesh:
/// room for `V` vertices, `F` faces and `E` edges (at least the mesh's unique
/// edges and half its corners), and for `FACETS` facets and `LINES` feature lines
/// crossing one row.
///
/// ```
/// # use pbuffer::prelude::*;
/// // A square: 4 vertices, 1 face, 4 edges.
/// let mesh = Mesh::new(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     &[0, 1, 2, 3], &[0, 4])?;
/// let mut square = Drawing::<4, 1, 3>::new();
/// let short = Error::CapacityExceeded { what: Capacity::Edges, needed: 4, capacity: 3 };
/// assert_eq!(square.bake(mesh), Err(short));
/// assert_eq!(short.to_string(), "mesh edges (E): 4 needed, capacity 3");
/// # Ok::<(), Error>(())
/// ```
#[derive(Debug)]
pub struct Drawing<
    'm,
    const V: usize,
    const F: usize,
    const E: usize,
    const FACETS: usize = 32,
    const LINES: usize = 32,
> {
    baked: Option<Baked<'m>>,
    /// How the frame is drawn: [`Settings::default`] is dashed hidden lines, culling
    /// on for a closed mesh, the paper's pattern. Dashes along the edges
    /// ([`Dashes::Along`](crate::render::Dashes::Along)) need the dash phases of the
    /// long form ([`FastWorkspace::phases`]): here they are `CapacityExceeded`.
    pub settings: Settings,
    /// The line colour (faces, in the surface modes, are dithered against it).
    pub palette: MonoPalette,
    planes: [FacePlane; F],
    edges: [CompactEdge; E],
    vertices: [FastVertex; V],
    facing: [u32; F],
    face_lists: [[u16; 2]; F],
    line_links: [u16; E],
    pool: [FastVertex; CLIPPED_CORNERS],
    engine: FastRenderer<U4, FACETS, LINES>,
    weld: [u32; V],
    half_edges: [[HalfEdgeRecord; 2]; E],
    mesh_edges: [MeshEdge; E],
}

/// What [`Drawing::bake`] learnt.
#[derive(Debug, Clone, Copy)]
struct Baked<'m> {
    mesh: Mesh<'m>,
    edges: usize,
}

impl<
        'm,
        const V: usize,
        const F: usize,
        const E: usize,
        const FACETS: usize,
        const LINES: usize,
    > Default for Drawing<'m, V, F, E, FACETS, LINES>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<
        'm,
        const V: usize,
        const F: usize,
        const E: usize,
        const FACETS: usize,
        const LINES: usize,
    > Drawing<'m, V, F, E, FACETS, LINES>
{
    /// Nothing baked yet; all zero, so a `static` of it is `.bss`.
    pub const fn new() -> Self {
        Self {
            baked: None,
            settings: Settings {
                mode: crate::DrawMode::Dashed,
                cull: crate::Cull::Auto,
                pattern: crate::Pattern::PAPER,
                dashes: crate::render::Dashes::Screen,
            },
            palette: MonoPalette {
                line: BinaryColor::On,
            },
            planes: [FacePlane {
                normal: [0.0; 3],
                centroid: [0.0; 3],
            }; F],
            edges: [CompactEdge::EMPTY; E],
            vertices: [FastVertex::ZERO; V],
            facing: [0; F],
            face_lists: [[0; 2]; F],
            line_links: [0; E],
            pool: [FastVertex::ZERO; CLIPPED_CORNERS],
            engine: FastRenderer::new(),
            weld: [0; V],
            half_edges: [[HalfEdgeRecord::EMPTY; 2]; E],
            mesh_edges: [MeshEdge::EMPTY; E],
        }
    }

    /// Bakes `mesh` (its edges found with creases past [`CREASE_DEG`], then
    /// [`BakedMesh::bake`]) and keeps it for [`draw`](Self::draw). Too few vertices,
    /// faces or edges is `CapacityExceeded` naming the parameter's size needed
    /// (for `E`, the larger of the unique edges and half the corners); on any error
    /// nothing stays baked.
    pub fn bake(&mut self, mesh: Mesh<'m>) -> Result<(), Error> {
        self.baked = None;
        need(Capacity::Vertices, mesh.vertices().len(), V)?;
        need(Capacity::Faces, mesh.face_count(), F)?;
        need(Capacity::Edges, mesh.indices().len().div_ceil(2), E)?;
        let adjacency = EdgeAdjacency::build(
            &mesh,
            CREASE_DEG,
            &mut self.weld,
            self.half_edges.as_flattened_mut(),
            &mut self.mesh_edges,
        )?;
        BakedMesh::bake(&mesh, &adjacency, &mut self.planes, &mut self.edges)?;
        self.baked = Some(Baked {
            mesh,
            edges: adjacency.edges().len(),
        });
        Ok(())
    }

    /// Draws the baked mesh seen by `camera` into `target`, whose bounding box is
    /// the frame (at most `W` x `H` of `rows`), one span at a time
    /// ([`DrawTarget::fill_solid`]). Nothing baked is `Err(NothingBaked)`.
    pub fn draw<D: DrawTarget<Color = BinaryColor>, const W: usize, const H: usize>(
        &mut self,
        camera: &Camera,
        rows: &mut FrameRows<W, H>,
        target: &mut D,
    ) -> Result<Stats, Error<D::Error>> {
        let Some(baked) = self.baked else {
            return Err(Error::NothingBaked);
        };
        let planes = self.planes.get(..baked.mesh.face_count()).unwrap_or(&[]);
        let edges = self.edges.get(..baked.edges).unwrap_or(&[]);
        let mesh = BakedMesh::baked_here(baked.mesh, planes, edges);
        let mut sink = FillSolid::new(target).map_err(Error::widen)?;
        rows.fit(sink.viewport()).map_err(Error::widen)?;
        let (face_links, slopes) = self
            .face_lists
            .as_flattened_mut()
            .split_at_mut_checked(F)
            .unwrap_or_default();
        let mut ws = FastWorkspace {
            vertices: &mut self.vertices,
            facing: &mut self.facing,
            face_links,
            line_links: &mut self.line_links,
            heads: rows.heads.as_flattened_mut(),
            row: &mut rows.row,
            masks: &mut rows.masks,
            pool: &mut self.pool,
            ids: &mut [],
            slopes,
            phases: &mut [],
        };
        self.engine.render(
            &mesh,
            camera,
            &self.settings,
            &mut ws,
            &self.palette,
            &mut sink,
            &mut (),
        )
    }
}

/// The buffers of a [`Drawing`] that grow with the display: room for frames up to
/// `W` x `H` pixels (the row, the per-row list heads, the line masks).
#[derive(Debug)]
pub struct FrameRows<const W: usize, const H: usize> {
    row: [u32; W],
    heads: [[u16; 2]; H],
    masks: [u32; H],
}

impl<const W: usize, const H: usize> Default for FrameRows<W, H> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const W: usize, const H: usize> FrameRows<W, H> {
    /// All zero, so a `static` of it is `.bss`.
    pub const fn new() -> Self {
        Self {
            row: [0; W],
            heads: [[0; 2]; H],
            masks: [0; H],
        }
    }

    /// Is a frame of `viewport` in reach? `CapacityExceeded` names the first of
    /// `W`, `H` and the line masks' `H` (two words per 32 columns) that is short.
    fn fit(&self, viewport: Viewport) -> Result<(), Error> {
        let width = usize::from(viewport.width);
        need(Capacity::RowWidth, width, W)?;
        need(Capacity::Rows, usize::from(viewport.height), H)?;
        need(Capacity::LineMasks, 2 * width.div_ceil(32), H)
    }
}
