//! Newell's depth sort (list priority with Newell's tests, shuffle and split; notes
//! 002 and 004), per view, as a depth order the code-fill engine can render.
//!
//! Every frame, [`NewellOrder::sort`] sorts the faces drawn in the view (after
//! back-face culling) by their farthest depth, then makes the list a true painter's
//! order: for the farthest polygon P and each Q whose depth range overlaps P's, P may
//! be painted first when one of Newell's tests succeeds:
//!
//! 1. P's depth range lies wholly beyond Q's;
//! 2. their screen x-extents are disjoint;
//! 3. their screen y-extents are disjoint;
//! 4. P lies wholly on the far side of Q's plane (seen from the eye);
//! 5. Q lies wholly on the near side of P's plane;
//! 6. their projections do not overlap (a separating axis among their edges).
//!
//! If all fail and Q may be painted before P (tests 4 and 5 with the roles swapped),
//! Q is moved ahead of P (a *shuffle*) and marked; a marked Q that would be moved
//! again is a cycle, and so are two polygons that may each obscure the other (they
//! interpenetrate): one is *split* by the other's plane and its pieces replace it.
//! Coplanar polygons whose projections overlap go by face index: the lower one is
//! painted last (ranks nearer, [conventions](crate::conventions)).
//!
//! A convex face that is not planar enters the sort as its fan triangles, each a
//! plane (as in the BSP build; [conventions](crate::conventions) gives such a face the depth of the
//! fan triangle a ray meets). Sides of a plane (tests 4 and 5, and whether a plane
//! cuts a polygon) are decided with the BSP build's tolerance and, for a face that
//! is not planar and not convex (one plane for the whole face), its own thickness:
//! a vertex within the largest distance of the face's corners from its Newell plane
//! counts as on the plane (the face is known no better than that). A cycle that no
//! such plane cuts is cut by P's or Q's plane without the band.
//!
//! The result has the same shape as a [`BspTree`](super::BspTree)'s: fragments that
//! begin with the mesh's vertices bit for bit (split points follow), their source
//! faces, and a front-to-back rank, ready for
//! [`Visibility::Order`](crate::render::Visibility::Order) via
//! [`NewellOrder::depth_order`]. Split points are made watertight as in the BSP
//! build: every fragment edge on the same mesh edge or cut chord gets them too
//! (T-vertices), so no pixel centre falls between two fragments.
//!
//! Numbers: the plane tests and the split points are f64, the per-fragment screen
//! boxes f32. Correctness comes first: the side-of-plane decisions use the BSP
//! build's relative tolerance ([`PLANE_TOLERANCE`](super::PLANE_TOLERANCE)), whose
//! scale (a few f32 ulps of a coordinate) f32 arithmetic cannot resolve, and the split
//! points must be bit-identical to what the shared seam code expects (the same
//! `split_point` as the BSP build). On a Cortex-M4 (single-precision FPU) f64 is
//! software: the cost is the pairs that reach tests 4 to 6 and the splits, not the
//! sort, because tests 1 to 3 run on the f32 boxes. The boxes only ever rule a pair
//! out when their extents are disjoint or touch; a wrong call there moves pixels by
//! less than the f32 rounding of a screen coordinate, which is at an edge.
//!
//! No recursion, no allocation, no panic: the storage is lent ([`NewellStorage`],
//! sized with [`NewellSizes`]); the work is bounded by the storage (every split takes
//! fragment slots) and by [`NewellOptions::max_steps`].

mod obscure;
mod settle;
mod sort;
mod split;
#[cfg(test)]
mod tests;
mod view;

use crate::camera::Camera;
use crate::mesh::Mesh;
use crate::order::DepthOrder;
use crate::Error;

/// Storage the caller lends [`NewellOrder::sort`]; all slices, sizes checked.
///
/// A slice that is too small is [`Error::CapacityExceeded`] `{ needed, capacity }`.
/// For `rank` `needed` is exact; for the others, which are used while the sort runs,
/// it is a lower bound (what the sort had reached when it ran out). A *slot* is a
/// fragment made during the sort: every face is one, every split makes one per piece
/// (the split fragment's slot is not reused). [`NewellSizes::for_mesh`] gives sizes
/// that suffice for a given number of splits.
#[derive(Debug)]
pub struct NewellStorage<'s> {
    /// Out: the mesh's vertices (same indices), then the split points.
    pub vertices: &'s mut [[f32; 3]],
    /// Out: the vertex indices of the fragments, one after the other (CSR). While
    /// sorting, it also holds the fragments that were split.
    pub indices: &'s mut [u32],
    /// Out: CSR offsets, one more than the slots.
    pub offsets: &'s mut [u32],
    /// Out: `source[fragment]` = the original face id; one per slot.
    pub source: &'s mut [u16],
    /// Out: `rank[fragment]`, front to back (0 = nearest); one per fragment.
    pub rank: &'s mut [u32],
    /// Scratch: the root segment of each split point (see the BSP build's seams).
    pub seams: &'s mut [[u32; 2]],
    /// Scratch: each slot's screen box and depth range,
    /// `[x_min, x_max, y_min, y_max, depth_min, depth_max]`.
    pub boxes: &'s mut [[f32; 6]],
    /// Scratch: the list, the marks and the surfaces (one word each per slot: the
    /// first third of the slice is the list, the second the marks, the last each
    /// slot's face or fan triangle), then the split points sorted for the seams in
    /// the first third: `3 * max(slots, split points)` words.
    pub work: &'s mut [u32],
}

impl NewellStorage<'_> {
    /// The lengths of these slices.
    pub fn sizes(&self) -> NewellSizes {
        NewellSizes {
            vertices: self.vertices.len(),
            indices: self.indices.len(),
            offsets: self.offsets.len(),
            source: self.source.len(),
            rank: self.rank.len(),
            seams: self.seams.len(),
            boxes: self.boxes.len(),
            work: self.work.len(),
        }
    }
}

/// Slice lengths for a [`NewellStorage`]; see [`NewellSizes::for_mesh`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NewellSizes {
    /// `NewellStorage::vertices`.
    pub vertices: usize,
    /// `NewellStorage::indices`.
    pub indices: usize,
    /// `NewellStorage::offsets`.
    pub offsets: usize,
    /// `NewellStorage::source`.
    pub source: usize,
    /// `NewellStorage::rank`.
    pub rank: usize,
    /// `NewellStorage::seams`.
    pub seams: usize,
    /// `NewellStorage::boxes`.
    pub boxes: usize,
    /// `NewellStorage::work`.
    pub work: usize,
}

impl NewellSizes {
    /// Sizes for a mesh of `vertices` vertices, `faces` faces and `indices` face
    /// indices, allowing `splits` splits in one view.
    ///
    /// They suffice when every split cuts a convex fragment in two (2 split points,
    /// 2 slots) and no fragment has more than 8 vertices: true for triangle and quad
    /// meshes unless one fragment is cut by more than 4 planes. They allow for every
    /// face of more than three corners being taken as its fan triangles (a face of
    /// `n` corners that is not planar: `n - 2` slots of 3 indices). A sort that needs
    /// more fails with [`Error::CapacityExceeded`]; [`NewellOrder::splits`] of a
    /// trial sort tells what a view needs.
    pub const fn for_mesh(vertices: usize, faces: usize, indices: usize, splits: usize) -> Self {
        // Fan triangles: n - 3 more slots and 2 n - 6 more indices for a face of n.
        let fanned = indices.saturating_sub(faces.saturating_mul(3));
        let slots = faces
            .saturating_add(fanned)
            .saturating_add(splits.saturating_mul(2));
        let points = splits.saturating_mul(2);
        // Each split appends two pieces of at most 8 + 2 vertices; then the seams
        // insert each split point into at most two more edges.
        let index_words = indices
            .saturating_add(fanned.saturating_mul(2))
            .saturating_add(splits.saturating_mul(20))
            .saturating_add(points.saturating_mul(2));
        let work = if slots > points {
            slots.saturating_mul(3)
        } else {
            points.saturating_mul(3)
        };
        Self {
            vertices: vertices.saturating_add(points),
            indices: index_words,
            offsets: slots.saturating_add(1),
            source: slots,
            rank: slots,
            seams: points,
            boxes: slots,
            work,
        }
    }
}

/// Bounds of the sort.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NewellOptions {
    /// The most shuffles and splits (together) one sort may make; one more is
    /// [`Error::DepthSortUnsettled`]. Without cycles a sort makes fewer shuffles than
    /// (drawn faces)^2 / 2; a sort stops at `8 n^2 + 256` steps, `n` the mesh's faces
    /// or the fragments it starts from (bent faces as fan triangles), whichever is more,
    /// whatever this allows, so that its time follows its scene.
    pub max_steps: usize,
}

impl NewellOptions {
    /// At most 2^20 shuffles and splits.
    pub const DEFAULT: Self = Self { max_steps: 1 << 20 };
}

impl Default for NewellOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A depth order for one view by Newell's depth sort: fragments of the mesh's faces,
/// their sources and their front-to-back ranks.
///
/// The drawn faces are sorted by farthest depth; then, for the farthest polygon P
/// and each Q whose depth range overlaps P's, P may be painted first when one of
/// Newell's tests succeeds: (1) P's depth range lies wholly beyond Q's; (2) their
/// screen x-extents or (3) y-extents are disjoint; (4) P lies wholly on the far side
/// of Q's plane; (5) Q wholly on the near side of P's plane; (6) their projections do
/// not overlap. If all fail and Q may go first, Q is moved ahead (a shuffle, marked);
/// a marked Q that must move again, or two polygons that may each obscure the other
/// (interpenetration), are a cycle: one polygon is split by another's plane.
/// Coplanar overlapping polygons: the lower face index ranks nearer. Split points are
/// made watertight with the BSP build's seam code (T-vertices).
#[derive(Debug, Clone, Copy)]
pub struct NewellOrder<'s> {
    pub(super) fragments: Mesh<'s>,
    pub(super) source: &'s [u16],
    pub(super) rank: &'s [u32],
    pub(super) drawn: usize,
    pub(super) splits: usize,
    pub(super) shuffles: usize,
    pub(super) unresolved: usize,
}

impl<'s> NewellOrder<'s> {
    /// Sorts `mesh` for the view of `camera` with [`NewellOptions::DEFAULT`]; see
    /// [`NewellOrder::sort_with`].
    pub fn sort(
        mesh: &Mesh<'_>,
        camera: &Camera,
        cull: bool,
        storage: NewellStorage<'s>,
    ) -> Result<Self, Error> {
        Self::sort_with(mesh, camera, cull, storage, NewellOptions::DEFAULT)
    }

    /// Sorts the faces of `mesh` drawn in the view of `camera` into a front-to-back
    /// order, splitting faces where no order
    /// exists. With `cull`, faces that do not face the eye
    /// ([`Mesh::faces_viewpoint`]) are left out: pass what the renderer culls
    /// ([`Cull::Auto`](crate::render::Cull::Auto) is `edges.is_closed()`). Faces left
    /// out, and faces of zero area, rank after all the others (by face index).
    ///
    /// A convex face that is not planar is taken as its fan triangles `(v0, vk,
    /// vk+1)`, each in its own plane, as the BSP build takes it
    /// ([conventions](crate::conventions) gives
    /// such a face the depth of the fan triangle a ray meets); its fragments are
    /// never ordered against each other (they overlap only where the face folds on
    /// screen, which the renderer covers by the polygon's parity). Every other face
    /// is its Newell plane through its centroid (a face that is not planar and not
    /// convex with its thickness band, below).
    ///
    /// A marked polygon that may go first but was moved ahead before in this round
    /// (the tests are conservative, so that need not be a cycle) is moved again when
    /// no plane cuts the cycle, at most once per polygon left to paint per round;
    /// beyond that the pair is left in list order and counted in
    /// [`NewellOrder::unresolved`].
    ///
    /// Errors: [`Error::CapacityExceeded`] as described at [`NewellStorage`];
    /// [`Error::DepthSortUnsettled`] beyond `options.max_steps`;
    /// [`Error::TooManyFaces`] when there are more than
    /// [`MAX_FACES`](crate::MAX_FACES) fragments.
    pub fn sort_with(
        mesh: &Mesh<'_>,
        camera: &Camera,
        cull: bool,
        storage: NewellStorage<'s>,
        options: NewellOptions,
    ) -> Result<Self, Error> {
        sort::run(mesh, camera, cull, storage, options)
    }

    /// The fragments as a validated mesh: the original vertices (same indices), then
    /// the split points; one face per fragment, wound like its source face, with
    /// every split point that lies on its edges (T-vertices).
    pub fn fragments(&self) -> Mesh<'s> {
        self.fragments
    }

    /// `source()[fragment]` is the original face id.
    pub fn source(&self) -> &'s [u16] {
        self.source
    }

    /// `rank()[fragment]`: its place front to back, 0 = nearest; a permutation of
    /// `0..fragment_count()`. Fragments drawn in the view come first.
    pub fn rank(&self) -> &'s [u32] {
        self.rank
    }

    /// The order for [`Visibility::Order`](crate::render::Visibility::Order).
    pub fn depth_order(&self) -> DepthOrder<'s> {
        DepthOrder {
            surfaces: self.fragments,
            source: self.source,
            rank: self.rank,
        }
    }

    /// Number of fragments.
    pub fn fragment_count(&self) -> usize {
        self.fragments.face_count()
    }

    /// Fragments that were sorted (drawn in the view): ranks `0..drawn()`.
    pub fn drawn(&self) -> usize {
        self.drawn
    }

    /// Splits made (one per fragment cut, whatever the pieces).
    pub fn splits(&self) -> usize {
        self.splits
    }

    /// Shuffles made (a polygon moved ahead of the list's head).
    pub fn shuffles(&self) -> usize {
        self.shuffles
    }

    /// Pairs left in list order because no plane could cut their cycle (0 unless
    /// the tolerance calls the cutting planes' candidates flat; see
    /// [`NewellOrder::sort_with`]).
    pub fn unresolved(&self) -> usize {
        self.unresolved
    }
}
