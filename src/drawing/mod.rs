//! The short way to draw one mesh with the default (fast) engine.
//!
//! A [`Drawing`] bakes a mesh once ([`Drawing::bake`]: face planes, edges and
//! their kinds, hole labels) and keeps every buffer the engine needs that grows
//! with the mesh; [`FrameRows`] keeps those that grow with the display. Both are
//! sized by const generics, zero-initialised by a `const fn new`, and can live in
//! `static`s. Too small a size is [`Error::CapacityExceeded`] naming the parameter
//! ([`Capacity`]) and the size needed, never a truncated picture; several too
//! small at once are one [`Error::CapacitiesExceeded`] naming each;
//! [`Drawing::measure`] tells every size a mesh and its views need at once, and
//! [`ram`](crate::ram) what they cost.
//!
//! What the short form costs against the long one ([`FastRenderer`] with a
//! [`FastWorkspace`] sized by hand and the constants baked on the host):
//! - the baking scratch stays in the `Drawing` (48 bytes an edge and 4 a vertex),
//!   so a large mesh is better baked in a `build.rs` (`pbuffer::bake`, feature
//!   `std`, or [`BakedMesh::bake`] and [`BakedSource`]), kept in flash and drawn by a
//!   [`BakedDrawing`], which holds only the buffers of a frame;
//! - the facing bits take a word a face, and the line masks a word a row of the
//!   display, where the engine needs a bit a face and two words per 32 columns:
//!   the price of not naming derived sizes (stable Rust cannot compute them in a
//!   type). The line masks fit displays up to 16 times wider than high.
//!
//! [`BakedSource`]: crate::render::BakedSource

pub(crate) mod ram;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::BinaryColor;

use crate::mesh::{EdgeAdjacency, HalfEdgeRecord, Mesh, MeshEdge};
use crate::render::{
    BakedMesh, CompactEdge, FacePlane, FaceViews, FastRenderer, FastVertex, FastWorkspace,
    FrameNeeds, FrameProbe, MonoPalette, OneMesh, Settings, Stats,
};
use crate::subpixel::U4;
use crate::{Camera, Error, FillSolid, SpanSink, Viewport};
use crate::{Capacity, Shortfalls};

/// `Default` is `new()` for a drawing of any sizes.
macro_rules! default_is_new {
    ($drawing:ident) => {
        impl<
                'm,
                const V: usize,
                const F: usize,
                const E: usize,
                const FACETS: usize,
                const LINES: usize,
            > Default for $drawing<'m, V, F, E, FACETS, LINES>
        {
            fn default() -> Self {
                Self::new()
            }
        }
    };
}

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
    frame: FrameBuffers<V, F, E, FACETS, LINES>,
    weld: [u32; V],
    half_edges: [[HalfEdgeRecord; 2]; E],
    mesh_edges: [MeshEdge; E],
}

/// What [`Drawing::bake`] learnt.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Baked<'m> {
    mesh: Mesh<'m>,
    edges: usize,
}

default_is_new!(Drawing);

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
            settings: DEFAULT_SETTINGS,
            palette: DEFAULT_PALETTE,
            planes: [FacePlane {
                normal: [0.0; 3],
                centroid: [0.0; 3],
            }; F],
            edges: [CompactEdge::EMPTY; E],
            frame: FrameBuffers::new(),
            weld: [0; V],
            half_edges: [[HalfEdgeRecord::EMPTY; 2]; E],
            mesh_edges: [MeshEdge::EMPTY; E],
        }
    }

    /// Bakes `mesh` (its edges found with creases past [`CREASE_DEG`], then
    /// [`BakedMesh::bake`]) and keeps it for [`draw`](Self::draw). Too few vertices,
    /// faces or edges is `CapacityExceeded` naming the parameter's size needed
    /// (for `E`, the larger of the unique edges and half the corners), or
    /// `CapacitiesExceeded` naming every one of `V`, `F` and `E` that is short,
    /// all in one error. The unique edges are counted once `V` and half the
    /// corners fit; until then `E` is listed as needing at least half the corners
    /// ([`Shortfall::at_least`](crate::Shortfall::at_least)). On any error nothing
    /// stays baked.
    pub fn bake(&mut self, mesh: Mesh<'m>) -> Result<(), Error> {
        self.baked = None;
        let mut short = Shortfalls::new();
        short.check(Capacity::Vertices, mesh.vertices().len(), V);
        short.check(Capacity::Faces, mesh.face_count(), F);
        let half_corners = mesh.indices().len().div_ceil(2);
        short.check_at_least(Capacity::Edges, half_corners, E, true);
        short.into_result()?;
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

    /// The baked mesh, to draw elsewhere as well: as an instance of a
    /// [`SceneDrawing`](crate::SceneDrawing), say. Nothing baked is
    /// `Err(NothingBaked)`.
    pub fn baked(&self) -> Result<BakedMesh<'_>, Error> {
        baked_mesh(self.baked, &self.planes, &self.edges)
    }

    /// Draws the baked mesh seen by `camera` into `target`, whose bounding box is
    /// the frame (at most `W` x `H` of `rows`), one span at a time
    /// ([`DrawTarget::fill_solid`]). Nothing baked is `Err(NothingBaked)`. More
    /// facets or lines active on a row than `FACETS` or `LINES`, or more clipped
    /// corners than [`CLIPPED_CORNERS`], is `CapacityExceeded` with the frame's
    /// true need (its peak, counted on past the limit), and no frame; two or
    /// three of them short is `CapacitiesExceeded`, naming each with its need.
    pub fn draw<D: DrawTarget<Color = BinaryColor>, const W: usize, const H: usize>(
        &mut self,
        camera: &Camera,
        rows: &mut FrameRows<W, H>,
        target: &mut D,
    ) -> Result<Stats, Error<D::Error>> {
        let mesh = baked_mesh(self.baked, &self.planes, &self.edges).map_err(Error::widen)?;
        self.frame
            .draw(&mesh, camera, (&self.settings, &self.palette), rows, target)
    }

    /// Every size the baked mesh seen by each of `cameras` in frames of
    /// `viewport` needs: the `V`, `F`, `E`, `FACETS`, `LINES` of a `Drawing` and
    /// the `W`, `H` of its [`FrameRows`], and the clipped corners (at most
    /// [`CLIPPED_CORNERS`] fit). Nothing is drawn, and this drawing's own
    /// `FACETS` and `LINES` may be smaller than what it reports, so a large
    /// drawing on the host can size a small one for the device. `rows` must hold
    /// `viewport` (`CapacityExceeded` else); nothing baked is `Err(NothingBaked)`.
    pub fn measure<const W: usize, const H: usize>(
        &mut self,
        cameras: &[Camera],
        rows: &mut FrameRows<W, H>,
        viewport: Viewport,
    ) -> Result<DrawingNeeds, Error> {
        let mesh = baked_mesh(self.baked, &self.planes, &self.edges)?;
        self.frame
            .measure(&mesh, cameras, &self.settings, rows, viewport)
    }
}

/// A [`Drawing`]'s baked mesh: what [`Drawing::bake`] learnt, with its planes and
/// edges (a free function, so the drawing's frame buffers stay free to borrow).
fn baked_mesh<'a>(
    baked: Option<Baked<'a>>,
    planes: &'a [FacePlane],
    edges: &'a [CompactEdge],
) -> Result<BakedMesh<'a>, Error> {
    let Some(baked) = baked else {
        return Err(Error::NothingBaked);
    };
    let planes = planes.get(..baked.mesh.face_count()).unwrap_or(&[]);
    let edges = edges.get(..baked.edges).unwrap_or(&[]);
    Ok(BakedMesh::baked_here(baked.mesh, planes, edges))
}

/// A mesh baked on the host and kept in flash (a [`BakedMesh`], as the `static`s of
/// `pbuffer::bake` give it), drawn by the fast engine with only the buffers of a
/// frame: room for `V` vertices, `F` faces and `E` edges (the generated `NAME_V`,
/// `NAME_F`, `NAME_E`), and for `FACETS` facets and `LINES` feature lines crossing
/// one row. Nothing is baked here, so it holds none of a [`Drawing`]'s baking
/// scratch, face planes or edge list.
///
/// ```
/// # use pbuffer::prelude::*;
/// # use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor};
/// use pbuffer::render::{BakedMesh, CompactEdge, FacePlane};
/// use pbuffer::BakedDrawing;
/// // In a firmware the planes and edges are `static`s a build.rs baked.
/// let square = Mesh::new(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     &[0, 1, 2, 3], &[0, 4])?;
/// let mut drawing = Drawing::<4, 1, 4>::new();
/// drawing.bake(square)?;
/// let (mut planes, mut edges) = ([FacePlane::default(); 1], [CompactEdge::EMPTY; 4]);
/// let mut store = [pbuffer::MeshEdge::EMPTY; 4];
/// let (mut weld, mut half) = ([0; 4], [pbuffer::HalfEdgeRecord::EMPTY; 4]);
/// let adjacency = pbuffer::EdgeAdjacency::build(&square, 30.0, &mut weld, &mut half, &mut store)?;
/// BakedMesh::bake(&square, &adjacency, &mut planes, &mut edges)?;
///
/// let mut baked = BakedDrawing::<4, 1, 4>::new();
/// baked.set_mesh(BakedMesh::new(square, &planes, &edges)?)?;
/// let camera = Camera::fit(&square, 64, 64)?;
/// let mut display = MockDisplay::<BinaryColor>::new();
/// let stats = baked.draw(&camera, &mut FrameRows::<64, 64>::new(), &mut display)?;
/// assert_eq!((stats.faces_drawn, stats.feature_edges), (1, 4));
/// # Ok::<(), pbuffer::Error>(())
/// ```
#[derive(Debug)]
pub struct BakedDrawing<
    'm,
    const V: usize,
    const F: usize,
    const E: usize,
    const FACETS: usize = 32,
    const LINES: usize = 32,
> {
    mesh: Option<BakedMesh<'m>>,
    /// How the frame is drawn, as a [`Drawing`]'s [`settings`](Drawing::settings).
    pub settings: Settings,
    /// The line colour (faces, in the surface modes, are dithered against it).
    pub palette: MonoPalette,
    frame: FrameBuffers<V, F, E, FACETS, LINES>,
}

default_is_new!(BakedDrawing);

impl<
        'm,
        const V: usize,
        const F: usize,
        const E: usize,
        const FACETS: usize,
        const LINES: usize,
    > BakedDrawing<'m, V, F, E, FACETS, LINES>
{
    /// No mesh yet; all zero, so a `static` of it is `.bss`.
    pub const fn new() -> Self {
        Self {
            mesh: None,
            settings: DEFAULT_SETTINGS,
            palette: DEFAULT_PALETTE,
            frame: FrameBuffers::new(),
        }
    }

    /// [`new`](Self::new) showing `mesh`: the errors of [`set_mesh`](Self::set_mesh).
    pub fn with_mesh(mesh: BakedMesh<'m>) -> Result<Self, Error> {
        let mut drawing = Self::new();
        drawing.set_mesh(mesh)?;
        Ok(drawing)
    }

    /// Keeps `mesh` for [`draw`](Self::draw). More vertices, faces or edges than
    /// `V`, `F` or `E` is `CapacityExceeded` naming the size needed (two or three
    /// of them short: `CapacitiesExceeded`, naming each), and then no mesh is
    /// kept.
    pub fn set_mesh(&mut self, mesh: BakedMesh<'m>) -> Result<(), Error> {
        self.mesh = None;
        let mut short = Shortfalls::new();
        short.check(Capacity::Vertices, mesh.mesh().vertices().len(), V);
        short.check(Capacity::Faces, mesh.mesh().face_count(), F);
        short.check(Capacity::Edges, mesh.edges().len(), E);
        short.into_result()?;
        self.mesh = Some(mesh);
        Ok(())
    }

    /// Draws the mesh seen by `camera` into `target`, as [`Drawing::draw`] does. No
    /// mesh is `Err(NothingBaked)`.
    pub fn draw<D: DrawTarget<Color = BinaryColor>, const W: usize, const H: usize>(
        &mut self,
        camera: &Camera,
        rows: &mut FrameRows<W, H>,
        target: &mut D,
    ) -> Result<Stats, Error<D::Error>> {
        let Some(mesh) = self.mesh else {
            return Err(Error::NothingBaked);
        };
        self.frame
            .draw(&mesh, camera, (&self.settings, &self.palette), rows, target)
    }

    /// Every size the mesh seen by each of `cameras` in frames of `viewport` needs,
    /// as [`Drawing::measure`] reports it. No mesh is `Err(NothingBaked)`.
    pub fn measure<const W: usize, const H: usize>(
        &mut self,
        cameras: &[Camera],
        rows: &mut FrameRows<W, H>,
        viewport: Viewport,
    ) -> Result<DrawingNeeds, Error> {
        let Some(mesh) = self.mesh else {
            return Err(Error::NothingBaked);
        };
        self.frame
            .measure(&mesh, cameras, &self.settings, rows, viewport)
    }
}

/// [`Settings::default`], in a `const fn`.
pub(crate) const DEFAULT_SETTINGS: Settings = Settings {
    mode: crate::DrawMode::Dashed,
    cull: crate::Cull::Auto,
    pattern: crate::Pattern::PAPER,
    dashes: crate::render::Dashes::Screen,
    lines: crate::render::LineVisibility::ByPixel,
};

/// Lines on.
pub(crate) const DEFAULT_PALETTE: MonoPalette = MonoPalette {
    line: BinaryColor::On,
};

/// The buffers of one frame that grow with the mesh, and the engine: what a
/// [`Drawing`], a [`BakedDrawing`] and a [`SceneDrawing`](crate::SceneDrawing)
/// share.
#[derive(Debug)]
pub(crate) struct FrameBuffers<
    const V: usize,
    const F: usize,
    const E: usize,
    const FACETS: usize,
    const LINES: usize,
> {
    vertices: [FastVertex; V],
    /// One word a face (the engine reads a bit a face): a scene sets the bits
    /// before its frame.
    pub(crate) facing: [u32; F],
    face_lists: [[u16; 2]; F],
    line_links: [u16; E],
    pool: [FastVertex; CLIPPED_CORNERS],
    engine: FastRenderer<U4, FACETS, LINES>,
}

impl<const V: usize, const F: usize, const E: usize, const FACETS: usize, const LINES: usize>
    FrameBuffers<V, F, E, FACETS, LINES>
{
    pub(crate) const fn new() -> Self {
        Self {
            vertices: [FastVertex::ZERO; V],
            facing: [0; F],
            face_lists: [[0; 2]; F],
            line_links: [0; E],
            pool: [FastVertex::ZERO; CLIPPED_CORNERS],
            engine: FastRenderer::new(),
        }
    }

    /// One frame of `mesh` into `target`, one span at a time.
    fn draw<D: DrawTarget<Color = BinaryColor>, const W: usize, const H: usize>(
        &mut self,
        mesh: &BakedMesh<'_>,
        camera: &Camera,
        looks: (&Settings, &MonoPalette),
        rows: &mut FrameRows<W, H>,
        target: &mut D,
    ) -> Result<Stats, Error<D::Error>> {
        let mut sink = FillSolid::new(target).map_err(Error::widen)?;
        let frame = (mesh, camera, looks);
        self.draw_in(OneMesh, frame, rows, &mut sink, &mut (), &mut [])
    }

    /// One frame of `mesh` seen from `views` into `sink`, `probe` seeing each
    /// finished row (`ids`, at least a row long, holds its face ids when the
    /// probe is active).
    pub(crate) fn draw_in<
        Y: FaceViews,
        K: SpanSink<Color = BinaryColor>,
        R: FrameProbe,
        const W: usize,
        const H: usize,
    >(
        &mut self,
        views: Y,
        (mesh, camera, (settings, palette)): (&BakedMesh<'_>, &Camera, (&Settings, &MonoPalette)),
        rows: &mut FrameRows<W, H>,
        sink: &mut K,
        probe: &mut R,
        ids: &mut [u16],
    ) -> Result<Stats, Error<K::Error>> {
        let viewport = sink.viewport();
        let (mut ws, engine) = self.workspace(rows, viewport).map_err(Error::widen)?;
        ws.ids = ids;
        let drawn = engine.render_in(views, mesh, camera, settings, &mut ws, palette, sink, probe);
        // A full table: the frame's true need, counted without drawing.
        drawn.map_err(|e| {
            engine.with_true_need_in(e, views, mesh, camera, settings, &mut ws, viewport)
        })
    }

    /// What `mesh` seen by each of `cameras` in frames of `viewport` needs: the
    /// peaks counted by the engine without drawing, and the mesh's and display's
    /// sizes.
    fn measure<const W: usize, const H: usize>(
        &mut self,
        mesh: &BakedMesh<'_>,
        cameras: &[Camera],
        settings: &Settings,
        rows: &mut FrameRows<W, H>,
        viewport: Viewport,
    ) -> Result<DrawingNeeds, Error> {
        let mut frames = FrameNeeds::default();
        for camera in cameras {
            let one = self.needs_in(OneMesh, mesh, camera, settings, rows, viewport)?;
            frames = frames.max(one);
        }
        Ok(Self::sizes(mesh, frames, viewport))
    }

    /// What the frame of `mesh` seen from `views` by `camera` needs of the tables
    /// the engine fills as it goes.
    pub(crate) fn needs_in<Y: FaceViews, const W: usize, const H: usize>(
        &mut self,
        views: Y,
        mesh: &BakedMesh<'_>,
        camera: &Camera,
        settings: &Settings,
        rows: &mut FrameRows<W, H>,
        viewport: Viewport,
    ) -> Result<FrameNeeds, Error> {
        let (mut ws, engine) = self.workspace(rows, viewport)?;
        engine.needs_in(views, mesh, camera, settings, &mut ws, viewport)
    }

    /// The sizes `mesh` and the peaks `frames` of its views need.
    pub(crate) fn sizes(
        mesh: &BakedMesh<'_>,
        frames: FrameNeeds,
        viewport: Viewport,
    ) -> DrawingNeeds {
        let inner = mesh.mesh();
        let width = usize::from(viewport.width);
        DrawingNeeds {
            vertices: inner.vertices().len(),
            faces: inner.face_count(),
            edges: mesh.edges().len().max(inner.indices().len().div_ceil(2)),
            facets: frames.facets,
            lines: frames.lines,
            clipped_corners: frames.clipped_corners,
            width,
            height: usize::from(viewport.height).max(2 * width.div_ceil(32)),
        }
    }

    /// The engine and its workspace for a frame of `viewport` (`rows` must hold it).
    fn workspace<'s, const W: usize, const H: usize>(
        &'s mut self,
        rows: &'s mut FrameRows<W, H>,
        viewport: Viewport,
    ) -> Result<(FastWorkspace<'s>, &'s mut FastRenderer<U4, FACETS, LINES>), Error> {
        rows.fit(viewport)?;
        let (face_links, slopes) = self
            .face_lists
            .as_flattened_mut()
            .split_at_mut_checked(F)
            .unwrap_or_default();
        let ws = FastWorkspace {
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
            segments: None,
        };
        Ok((ws, &mut self.engine))
    }
}

/// What a baked mesh and its views need ([`Drawing::measure`]): the sizes to give
/// a [`Drawing`] and its [`FrameRows`] that draw them, each the one its
/// [`Capacity`] names when short.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct DrawingNeeds {
    /// `V`: the mesh's vertices ([`Capacity::Vertices`]).
    pub vertices: usize,
    /// `F`: the mesh's faces ([`Capacity::Faces`]).
    pub faces: usize,
    /// `E`: the larger of the unique edges and half the corners ([`Capacity::Edges`]).
    pub edges: usize,
    /// `FACETS`: the most facets active on a row in any view ([`Capacity::ActiveFacets`]).
    pub facets: usize,
    /// `LINES`: the most feature lines active on a row in any view
    /// ([`Capacity::ActiveLines`]).
    pub lines: usize,
    /// Corners of clipped faces in the worst view ([`Capacity::ClippedCorners`]):
    /// fixed at [`CLIPPED_CORNERS`] in a `Drawing`, the long form's pool otherwise.
    pub clipped_corners: usize,
    /// `W`: the frame's width ([`Capacity::RowWidth`]).
    pub width: usize,
    /// `H`: the frame's height, or the line masks' two words per 32 columns when
    /// more ([`Capacity::Rows`], [`Capacity::LineMasks`]).
    pub height: usize,
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

    /// Is a frame of `viewport` in reach? `CapacityExceeded` (or
    /// `CapacitiesExceeded`) names each of `W`, `H` and the line masks' `H` (two
    /// words per 32 columns) that is short.
    fn fit(&self, viewport: Viewport) -> Result<(), Error> {
        let (width, height) = (usize::from(viewport.width), usize::from(viewport.height));
        let masks = 2 * width.div_ceil(32);
        if width <= W && height <= H && masks <= H {
            return Ok(());
        }
        let mut short = Shortfalls::new();
        short.check(Capacity::RowWidth, width, W);
        short.check(Capacity::Rows, height, H);
        short.check(Capacity::LineMasks, masks, H);
        short.into_result()
    }
}

#[cfg(test)]
mod tests;
