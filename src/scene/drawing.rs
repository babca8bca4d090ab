//! [`SceneDrawing`]: several baked meshes, each with a pose, drawn as one frame by
//! the fast engine.
//!
//! What stays fixed while only poses change is assembled once, when an instance is
//! added: the union's corner indices and face starts (each instance's shifted by
//! the vertices before it), its face planes and planarity bits (the instances'
//! own, in their own space) and its edge list (each instance's, shifted; hole
//! labels renumbered). A frame then poses each vertex into the union's positions,
//! brings the eye into each instance's space and sets the facing bits from the
//! baked planes there, and hands the union to the engine.

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::BinaryColor;
use heapless::Vec;

use super::Pose;
use crate::bits::set_bit;
use crate::drawing::{FrameBuffers, DEFAULT_PALETTE, DEFAULT_SETTINGS};
use crate::error::need;
use crate::mesh::{EdgeKind, Mesh, Viewpoint};
use crate::render::{
    faces_view, BakedMesh, CompactEdge, FacePlane, FrameNeeds, FrameProbe, InstanceViews,
    MonoPalette, Settings, Stats, MAX_FAST_FACES, MAX_HOLES, NO_HOLE,
};
use crate::{
    Camera, Capacity, DrawingNeeds, Error, FillSolid, FrameRows, Shortfalls, SpanSink, Viewport,
    FIT_FOV_DEG, FIT_VIEW_DIRECTION,
};

/// One instance: a baked mesh and where it is.
#[derive(Debug, Clone, Copy)]
struct Instance<'m> {
    mesh: BakedMesh<'m>,
    pose: Pose,
}

/// What the assembled union holds.
#[derive(Debug, Clone, Copy, Default)]
struct Union {
    vertices: usize,
    faces: usize,
    edges: usize,
    /// Corner indices; the face starts follow them.
    corners: usize,
    /// The most corners of a face (as `Mesh::new` found it).
    max_face_len: usize,
    closed: bool,
}

/// Several baked meshes (instances), each with a [`Pose`] that may change every
/// frame, drawn as one frame by the fast engine with mutual hiding: room for `N`
/// instances and, over all of them, `V` vertices, `F` faces, `E` edges and `C`
/// corner indices and face starts (the corners, plus the faces, plus one); and
/// for `FACETS` facets and `LINES` feature lines crossing one row.
///
/// The frame is the frame of the union mesh: every instance's vertices posed
/// ([`Pose::apply`]), faces numbered in instance order (so face ids are the
/// union's), and each instance's edges as it was baked: a crease, silhouette or
/// weld never joins two instances (see [the module](crate::scene)).
///
/// ```
/// # use pbuffer::prelude::*;
/// # use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor};
/// # use pbuffer::Projection;
/// // A unit cube, baked once (at boot here; a build.rs can bake it into flash).
/// const P: [[f32; 3]; 8] = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.],
///     [0., 0., 1.], [1., 0., 1.], [1., 1., 1.], [0., 1., 1.]];
/// const I: [u32; 24] = [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 2, 3, 7, 6, 1, 2, 6, 5, 0, 4, 7, 3];
/// let mut cube = Drawing::<8, 6, 12>::new();
/// cube.bake(Mesh::new(&P, &I, &[0, 4, 8, 12, 16, 20, 24])?)?;
/// // Two instances: 16 vertices, 12 faces, 24 edges, 48 corners + 12 faces + 1.
/// let mut scene = SceneDrawing::<2, 16, 12, 24, 61>::new();
/// let near = scene.add(cube.baked()?, Pose::translation([-0.5, 0.0, 1.0]))?;
/// scene.add(cube.baked()?, Pose::from_degrees([0.0, 30.0, 0.0], [0.0, 0.0, -1.0]))?;
/// let camera = Camera::new([0.0, 2.0, 6.0], [0.0, 0.5, 0.0], [0.0, 1.0, 0.0],
///     Projection::Perspective { fov_y_deg: 40.0 }, 0.1, 100.0)?;
/// let (mut rows, mut display) = (FrameRows::<64, 64>::new(), MockDisplay::<BinaryColor>::new());
/// let stats = scene.draw(&camera, &mut rows, &mut display)?;
/// assert_eq!((stats.faces, stats.feature_edges), (12, 24));
/// // Only a pose changes between frames: nothing is baked again.
/// *scene.pose_mut(near).unwrap() = Pose::from_degrees([0.0, 0.0, 45.0], [-0.5, 0.0, 1.0]);
/// scene.draw(&camera, &mut rows, &mut MockDisplay::<BinaryColor>::new())?;
/// # Ok::<(), pbuffer::Error>(())
/// ```
#[derive(Debug)]
pub struct SceneDrawing<
    'm,
    const N: usize,
    const V: usize,
    const F: usize,
    const E: usize,
    const C: usize,
    const FACETS: usize = 32,
    const LINES: usize = 32,
> {
    instances: Vec<Instance<'m>, N>,
    /// Each instance's first face in the union.
    starts: [u16; N],
    /// The camera's viewpoint in each instance's space, this frame.
    views: [Viewpoint; N],
    /// How the frame is drawn, as a [`Drawing`](crate::Drawing)'s
    /// [`settings`](crate::Drawing::settings). `Cull::Auto` culls when every
    /// instance is closed.
    pub settings: Settings,
    /// The line colour (faces, in the surface modes, are dithered against it).
    pub palette: MonoPalette,
    union: Union,
    positions: [[f32; 3]; V],
    corners: [u32; C],
    planar: [u32; F],
    planes: [FacePlane; F],
    edges: [CompactEdge; E],
    frame: FrameBuffers<V, F, E, FACETS, LINES>,
}

impl<
        'm,
        const N: usize,
        const V: usize,
        const F: usize,
        const E: usize,
        const C: usize,
        const FACETS: usize,
        const LINES: usize,
    > Default for SceneDrawing<'m, N, V, F, E, C, FACETS, LINES>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<
        'm,
        const N: usize,
        const V: usize,
        const F: usize,
        const E: usize,
        const C: usize,
        const FACETS: usize,
        const LINES: usize,
    > SceneDrawing<'m, N, V, F, E, C, FACETS, LINES>
{
    /// No instances; all zero, so a `static` of it is `.bss`.
    pub const fn new() -> Self {
        Self {
            instances: Vec::new(),
            starts: [0; N],
            views: [Viewpoint::Perspective { eye: [0.0; 3] }; N],
            settings: DEFAULT_SETTINGS,
            palette: DEFAULT_PALETTE,
            union: Union {
                vertices: 0,
                faces: 0,
                edges: 0,
                corners: 0,
                max_face_len: 0,
                closed: true,
            },
            positions: [[0.0; 3]; V],
            corners: [0; C],
            planar: [0; F],
            planes: [FacePlane {
                normal: [0.0; 3],
                centroid: [0.0; 3],
            }; F],
            edges: [CompactEdge::EMPTY; E],
            frame: FrameBuffers::new(),
        }
    }

    /// Adds `mesh` at `pose` as the next instance (its faces numbered after the
    /// faces of those before it) and returns its number. More instances than `N`,
    /// or a union of more vertices, faces, edges or corner indices and face starts
    /// than `V`, `F`, `E`, `C`, is `CapacityExceeded` with the size needed (two or
    /// more of `V`, `F`, `E`, `C` short: `CapacitiesExceeded`, naming each); more
    /// than [`MAX_FAST_FACES`] vertices or faces is `TooManyFaces`. On an error
    /// the scene is as it was.
    pub fn add(&mut self, mesh: BakedMesh<'m>, pose: Pose) -> Result<usize, Error> {
        let inner = mesh.mesh();
        let u = self.union;
        let instances = self.instances.len() + 1;
        need(Capacity::Instances, instances, N)?;
        let (vertices, faces) = (
            u.vertices + inner.vertices().len(),
            u.faces + inner.face_count(),
        );
        let most = vertices.max(faces);
        if most > MAX_FAST_FACES {
            return Err(Error::TooManyFaces {
                faces: most,
                max: MAX_FAST_FACES,
            });
        }
        let mut short = Shortfalls::new();
        short.check(Capacity::Vertices, vertices, V);
        short.check(Capacity::Faces, faces, F);
        short.check(Capacity::Edges, u.edges + mesh.edges().len(), E);
        let corners = u.corners + inner.indices().len();
        short.check(Capacity::SceneCorners, corners + faces + 1, C);
        short.into_result()?;
        let number = self.instances.len();
        let (slot, instance) = (self.starts.get_mut(number), Instance { mesh, pose });
        if let (Some(slot), Ok(())) = (slot, self.instances.push(instance)) {
            // `faces` fits 16 bits (checked above).
            *slot = u.faces as u16;
        }
        if let Err(e) = self.assemble() {
            self.instances.pop();
            // What was assembled before assembles again.
            let _ = self.assemble();
            return Err(e);
        }
        Ok(number)
    }

    /// The camera that frames every instance at its pose in a `width` x `height`
    /// frame: [`Camera::fit`]'s rule (its direction, field of view and fill) for
    /// the vertices the instances' faces use, each posed ([`Pose::apply`]). No
    /// instance is `EmptyMesh`; a pose that puts a vertex out of `f32`'s range is
    /// `NonFinite`.
    pub fn fit_camera(&self, width: u32, height: u32) -> Result<Camera, Error> {
        self.fit_camera_along(width, height, FIT_VIEW_DIRECTION, FIT_FOV_DEG)
    }

    /// [`fit_camera`](Self::fit_camera) seen along `direction_to_eye` with a
    /// vertical field of view of `fov_y_deg` degrees, as
    /// [`Camera::fit_along`] takes them.
    pub fn fit_camera_along(
        &self,
        width: u32,
        height: u32,
        direction_to_eye: [f32; 3],
        fov_y_deg: f32,
    ) -> Result<Camera, Error> {
        let posed = self.instances.iter().flat_map(|instance| {
            let mesh = instance.mesh.mesh();
            let pose = instance.pose;
            mesh.indices().iter().filter_map(move |&i| {
                let p = mesh.vertices().get(i as usize)?;
                Some(pose.apply(*p))
            })
        });
        Camera::fit_points_along(posed, width, height, direction_to_eye, fov_y_deg)
    }

    /// Instance `instance`'s pose, to change between frames (`None` when there is
    /// no such instance).
    pub fn pose_mut(&mut self, instance: usize) -> Option<&mut Pose> {
        self.instances.get_mut(instance).map(|i| &mut i.pose)
    }

    /// The instances added so far.
    pub fn len(&self) -> usize {
        self.instances.len()
    }

    /// Are there no instances?
    pub fn is_empty(&self) -> bool {
        self.instances.is_empty()
    }

    /// Removes every instance.
    pub fn clear(&mut self) {
        self.instances.clear();
        self.union = Union {
            closed: true,
            ..Union::default()
        };
    }

    /// Draws the instances at their poses seen by `camera` into `target`, as
    /// [`Drawing::draw`](crate::Drawing::draw) draws one mesh. No instance is
    /// `Err(NothingBaked)`; a pose that is not finite, or puts a vertex out of
    /// `f32`'s range, is `NonFiniteVertex` naming the union's vertex.
    pub fn draw<D: DrawTarget<Color = BinaryColor>, const W: usize, const H: usize>(
        &mut self,
        camera: &Camera,
        rows: &mut FrameRows<W, H>,
        target: &mut D,
    ) -> Result<Stats, Error<D::Error>> {
        let mut sink = FillSolid::new(target).map_err(Error::widen)?;
        self.draw_spans(camera, rows, &mut sink, &mut (), &mut [])
    }

    /// [`draw`](Self::draw) into any [`SpanSink`], with `probe` seeing each
    /// finished row (the face ids and line masks of the `render` command's
    /// `--ids` and `--lines`); `ids` holds a row of face ids when the probe looks
    /// at them (at least the frame's width, else `CapacityExceeded`), and may be
    /// empty for `&mut ()`.
    pub fn draw_spans<
        K: SpanSink<Color = BinaryColor>,
        R: FrameProbe,
        const W: usize,
        const H: usize,
    >(
        &mut self,
        camera: &Camera,
        rows: &mut FrameRows<W, H>,
        sink: &mut K,
        probe: &mut R,
        ids: &mut [u16],
    ) -> Result<Stats, Error<K::Error>> {
        self.pose(&camera.viewpoint()).map_err(Error::widen)?;
        let Self {
            starts,
            views,
            settings,
            palette,
            frame,
            ..
        } = self;
        let n = self.instances.len();
        let views = InstanceViews {
            starts: starts.get(..n).unwrap_or(&[]),
            views: views.get(..n).unwrap_or(&[]),
        };
        let mesh = union_mesh(
            self.union,
            &self.positions,
            &self.corners,
            &self.planar,
            &self.planes,
            &self.edges,
        )
        .map_err(Error::widen)?;
        let looks = (&*settings, &*palette);
        frame.draw_in(views, (&mesh, camera, looks), rows, sink, probe, ids)
    }

    /// Every size the scene at its present poses, seen by each of `cameras` in
    /// frames of `viewport`, needs, as [`Drawing::measure`](crate::Drawing::measure)
    /// reports it for one mesh (here `vertices`, `faces` and `edges` are the
    /// union's). No instance is `Err(NothingBaked)`.
    pub fn measure<const W: usize, const H: usize>(
        &mut self,
        cameras: &[Camera],
        rows: &mut FrameRows<W, H>,
        viewport: Viewport,
    ) -> Result<DrawingNeeds, Error> {
        let mut frames = FrameNeeds::default();
        let n = self.instances.len();
        for camera in cameras {
            self.pose(&camera.viewpoint())?;
            let views = InstanceViews {
                starts: self.starts.get(..n).unwrap_or(&[]),
                views: self.views.get(..n).unwrap_or(&[]),
            };
            let mesh = union_mesh(
                self.union,
                &self.positions,
                &self.corners,
                &self.planar,
                &self.planes,
                &self.edges,
            )?;
            let one = self
                .frame
                .needs_in(views, &mesh, camera, &self.settings, rows, viewport)?;
            frames = frames.max(one);
        }
        let mesh = union_mesh(
            self.union,
            &self.positions,
            &self.corners,
            &self.planar,
            &self.planes,
            &self.edges,
        )?;
        let mut sizes = FrameBuffers::<V, F, E, FACETS, LINES>::sizes(&mesh, frames, viewport);
        // The union's edges are the instances', not half its corners.
        sizes.edges = self.union.edges;
        Ok(sizes)
    }

    /// The per-frame work of the poses: each instance's vertices posed into the
    /// union, the camera's `view` brought into its space, and its faces' facing
    /// bits set from its baked planes there.
    fn pose(&mut self, view: &Viewpoint) -> Result<(), Error> {
        if self.instances.is_empty() {
            return Err(Error::NothingBaked);
        }
        let mut first = 0usize;
        let mut face = 0usize;
        for (k, instance) in self.instances.iter().enumerate() {
            let local = instance.mesh.mesh().vertices();
            let end = first + local.len();
            let posed = self.positions.get_mut(first..end).unwrap_or_default();
            for (i, (slot, p)) in posed.iter_mut().zip(local).enumerate() {
                let q = instance.pose.apply(*p);
                if !(q[0].is_finite() && q[1].is_finite() && q[2].is_finite()) {
                    return Err(Error::NonFiniteVertex { vertex: first + i });
                }
                *slot = q;
            }
            first = end;
            let seen = instance.pose.view_in_mesh(view);
            if let Some(v) = self.views.get_mut(k) {
                *v = seen;
            }
            for plane in instance.mesh.planes() {
                set_bit(&mut self.frame.facing, face, faces_view(plane, &seen));
                face += 1;
            }
        }
        Ok(())
    }

    /// Writes the union of the instances' fixed parts: corner indices and face
    /// starts, planarity bits, planes, edges (sizes checked by `add`), and checks
    /// them once as a mesh.
    fn assemble(&mut self) -> Result<(), Error> {
        let mut u = Union {
            closed: true,
            ..Union::default()
        };
        let holes = hole_labels(&self.instances);
        let mut hole_base = 0u8;
        for instance in &self.instances {
            let mesh = instance.mesh.mesh();
            let base = u.vertices as u32;
            let corners = self.corners.get_mut(u.corners..).unwrap_or_default();
            for (slot, &v) in corners.iter_mut().zip(mesh.indices()) {
                *slot = v + base;
            }
            u.corners += mesh.indices().len();
            let planes = self.planes.get_mut(u.faces..).unwrap_or_default();
            for (f, (slot, plane)) in planes.iter_mut().zip(instance.mesh.planes()).enumerate() {
                *slot = *plane;
                let planar = mesh.kept_planarity(f).unwrap_or(true);
                set_bit(&mut self.planar, u.faces + f, planar);
            }
            let (vb, fb) = (u.vertices as u16, u.faces as u16);
            let edges = self.edges.get_mut(u.edges..).unwrap_or_default();
            let mut most = 0u8;
            for (slot, e) in edges.iter_mut().zip(instance.mesh.edges()) {
                let labelled = holes && e.hole != NO_HOLE;
                if labelled {
                    most = most.max(e.hole + 1);
                }
                *slot = CompactEdge {
                    a: e.a + vb,
                    b: e.b + vb,
                    faces: e.faces.map(|f| f + fb),
                    kind: e.kind,
                    hole: if labelled {
                        e.hole + hole_base
                    } else {
                        NO_HOLE
                    },
                };
            }
            hole_base += most;
            u.closed &= instance.mesh.is_closed();
            u.vertices += mesh.vertices().len();
            u.faces += mesh.face_count();
            u.edges += instance.mesh.edges().len();
        }
        // The face starts, after the corners.
        let starts = self.corners.get_mut(u.corners..).unwrap_or_default();
        let mut at = 0u32;
        let mut start = starts.iter_mut();
        if let Some(s) = start.next() {
            *s = 0;
        }
        for instance in &self.instances {
            let mesh = instance.mesh.mesh();
            for f in 0..mesh.face_count() {
                at += mesh.face(f).len() as u32;
                if let Some(s) = start.next() {
                    *s = at;
                }
            }
        }
        let (indices, starts) = self.corners.split_at_checked(u.corners).unwrap_or_default();
        let starts = starts.get(..=u.faces).unwrap_or(&[]);
        let positions = self.positions.get(..u.vertices).unwrap_or(&[]);
        // Positions are finite: zero, or posed by a frame that checked them.
        u.max_face_len = Mesh::new(positions, indices, starts)?.max_face_len();
        self.union = u;
        Ok(())
    }
}

/// Do the union's edges keep their hole labels? Only when every instance with
/// boundary edges has them labelled and the holes, renumbered, stay below
/// [`MAX_HOLES`]: a back face is skipped only away from every hole, so one
/// unlabelled open instance keeps every back face.
fn hole_labels(instances: &[Instance<'_>]) -> bool {
    let mut total = 0usize;
    for instance in instances {
        let boundary = instance
            .mesh
            .edges()
            .iter()
            .filter(|e| e.kind == EdgeKind::Boundary);
        let mut most = 0usize;
        for e in boundary {
            if e.hole == NO_HOLE {
                return false;
            }
            most = most.max(usize::from(e.hole) + 1);
        }
        total += most;
    }
    total <= MAX_HOLES
}

/// The union as one baked mesh for the engine.
fn union_mesh<'a>(
    u: Union,
    positions: &'a [[f32; 3]],
    corners: &'a [u32],
    planar: &'a [u32],
    planes: &'a [FacePlane],
    edges: &'a [CompactEdge],
) -> Result<BakedMesh<'a>, Error> {
    if u.faces == 0 {
        return Err(Error::NothingBaked);
    }
    let (indices, starts) = corners.split_at_checked(u.corners).unwrap_or_default();
    let starts = starts.get(..=u.faces).unwrap_or(&[]);
    let positions = positions.get(..u.vertices).unwrap_or(&[]);
    let mesh = Mesh::assembled(positions, indices, starts, u.max_face_len, planar);
    let planes = planes.get(..u.faces).unwrap_or(&[]);
    let edges = edges.get(..u.edges).unwrap_or(&[]);
    Ok(BakedMesh::baked_here(mesh, planes, edges))
}
