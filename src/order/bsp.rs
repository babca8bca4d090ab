//! The BSP tree: types, the iterative build and the front-to-back walk.

use core::ops::Range;

use crate::error::need;
use crate::mesh::{Mesh, Viewpoint};
use crate::vector::dot;
use crate::Capacity;
use crate::Error;

/// "No child" in [`BspNode::front`] and [`BspNode::back`].
pub const NO_NODE: u32 = u32::MAX;

/// The relative tolerance of the build: a vertex whose distance to a node's plane is
/// at most `PLANE_TOLERANCE * L`, where `L` is the vertex's largest absolute
/// coordinate, counts as lying on the plane (2^-21,
/// about 8 f32 ulps of `L`: the rounding of the positions, local to them, so that
/// faces 1e-4 apart at depth 100, or small faces beside a vertex far away, are not
/// taken for coplanar).
pub const PLANE_TOLERANCE: f64 = 1.0 / 2_097_152.0;

/// One node of the tree: a plane (from its first fragment's face) and the fragments
/// lying in it.
///
/// The fragments of a node are `first..first + count` in the tree's fragment order,
/// sorted by source face id (both orientations), so that equal depth ranks the lower
/// face id first.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BspNode {
    /// `[nx, ny, nz, d]`: the plane `n . p + d = 0`; `n` is the (unnormalised)
    /// Newell normal of the splitting fragment's face, so the front is the side
    /// from which that face winds counter-clockwise.
    pub plane: [f64; 4],
    /// The subtree in front of the plane, or [`NO_NODE`].
    pub front: u32,
    /// The subtree behind the plane, or [`NO_NODE`].
    pub back: u32,
    /// The node's first fragment.
    pub first: u32,
    /// How many fragments lie in the node's plane (at least 1).
    pub count: u32,
}

impl BspNode {
    /// A node with no children and no fragments, to fill storage arrays with.
    pub const EMPTY: Self = Self {
        plane: [0.0; 4],
        front: NO_NODE,
        back: NO_NODE,
        first: 0,
        count: 0,
    };

    /// The node's fragments, as a range of fragment ids.
    pub fn fragments(&self) -> Range<usize> {
        let first = self.first as usize;
        first..first.saturating_add(self.count as usize)
    }

    /// Is the eye strictly in front of the plane? (Orthographic: does the normal
    /// point toward the eye?) False for an eye exactly on the plane.
    pub fn eye_in_front(&self, view: &Viewpoint) -> bool {
        let [nx, ny, nz, d] = self.plane;
        let n = [nx, ny, nz];
        match view {
            Viewpoint::Perspective { eye } => dot(n, eye.map(f64::from)) + d > 0.0,
            Viewpoint::Orthographic { direction_to_eye } => {
                dot(n, direction_to_eye.map(f64::from)) > 0.0
            }
        }
    }

    /// `(near, far)` children for a view: the eye's side first.
    pub fn near_far(&self, view: &Viewpoint) -> (u32, u32) {
        if self.eye_in_front(view) {
            (self.front, self.back)
        } else {
            (self.back, self.front)
        }
    }
}

/// Storage the caller lends for building a [`BspTree`]; all slices, sizes checked.
///
/// A slice that is too small is [`Error::CapacityExceeded`] `{ needed, capacity }`.
/// `vertices`, `seams` and `work` are used during the build, so for them `needed` is
/// a lower bound (what the build had reached); `nodes`, `offsets` and `source` are
/// only written, so the build runs to the end and reports their exact need (checked
/// in that order). `indices` is exact too, except when it cannot even hold the
/// fragments before the seams' split points are inserted (see [`BspTree::build_with`]):
/// then `needed` is that lower bound. [`BspSizes::for_mesh`] gives sizes that suffice.
#[derive(Debug)]
pub struct BspStorage<'s> {
    /// Out: the mesh's vertices (same indices), then the split points.
    pub vertices: &'s mut [[f32; 3]],
    /// Out: the vertex indices of the fragments, one after the other (CSR).
    pub indices: &'s mut [u32],
    /// Out: CSR offsets, one more than the fragments.
    pub offsets: &'s mut [u32],
    /// Out: `source[fragment]` = the original face id.
    pub source: &'s mut [u16],
    /// Out: the nodes; node 0 is the root.
    pub nodes: &'s mut [BspNode],
    /// Scratch: the root segment of each split point (the mesh edge or cut chord it
    /// lies on, as two vertex indices), one per split point.
    pub seams: &'s mut [[u32; 2]],
    /// Scratch for the iterative build: the stack of fragment sets still to be split,
    /// then the split points sorted along their root segments. `2 * I + 8 * F + 8`
    /// words always suffice, where `F` and `I` are the fragment and fragment-index
    /// counts of the result ([`BspTree::work_peak`] tells the exact need of a built
    /// tree).
    pub work: &'s mut [u32],
}

impl BspStorage<'_> {
    /// Slice lengths that suffice for a mesh of `vertices` vertices, `faces` faces
    /// and `indices` face indices with at most `splits` splits: [`BspSizes::for_mesh`].
    pub const fn sizes_for_mesh(
        vertices: usize,
        faces: usize,
        indices: usize,
        splits: usize,
    ) -> BspSizes {
        BspSizes::for_mesh(vertices, faces, indices, splits)
    }

    /// The lengths of these slices.
    pub fn sizes(&self) -> BspSizes {
        BspSizes {
            vertices: self.vertices.len(),
            indices: self.indices.len(),
            offsets: self.offsets.len(),
            source: self.source.len(),
            nodes: self.nodes.len(),
            seams: self.seams.len(),
            work: self.work.len(),
        }
    }
}

/// Slice lengths for a [`BspStorage`]; see [`BspSizes::for_mesh`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BspSizes {
    /// `BspStorage::vertices`.
    pub vertices: usize,
    /// `BspStorage::indices`.
    pub indices: usize,
    /// `BspStorage::offsets`.
    pub offsets: usize,
    /// `BspStorage::source`.
    pub source: usize,
    /// `BspStorage::nodes`.
    pub nodes: usize,
    /// `BspStorage::seams`.
    pub seams: usize,
    /// `BspStorage::work`.
    pub work: usize,
}

impl BspSizes {
    /// Sizes for a mesh of `vertices` vertices, `faces` faces and `indices` face
    /// indices, allowing `splits` fragment splits (each split makes one more fragment).
    ///
    /// They suffice whenever the build makes at most `splits` splits, each adding at
    /// most 2 split points, and the seams add at most 2 more indices per split point
    /// (each split point lies on one root segment, shared by at most two faces'
    /// fragments besides the two that share it already, in a manifold mesh): true for
    /// convex fragments of a manifold mesh (triangle meshes) unless a cutting plane
    /// passes within tolerance of 3 or more vertices of one fragment. The split count
    /// of a mesh is [`BspTree::splits`] of a trial build.
    pub const fn for_mesh(vertices: usize, faces: usize, indices: usize, splits: usize) -> Self {
        let fragments = faces.saturating_add(splits);
        let points = splits.saturating_mul(2);
        let fragment_indices = indices
            .saturating_add(splits.saturating_mul(4))
            .saturating_add(points.saturating_mul(2));
        Self {
            vertices: vertices.saturating_add(points),
            indices: fragment_indices,
            offsets: fragments.saturating_add(1),
            source: fragments,
            nodes: fragments,
            seams: points,
            work: work_bound(fragments, fragment_indices),
        }
    }
}

/// Work words that always suffice for a result of `fragments` fragments with
/// `indices` indices in all: `2 * indices + 8 * fragments + 8`.
pub const fn work_bound(fragments: usize, indices: usize) -> usize {
    indices
        .saturating_mul(2)
        .saturating_add(fragments.saturating_mul(8))
        .saturating_add(8)
}

/// How the build chooses a node's splitting plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BspOptions {
    /// Candidate splitters tried per node, spread evenly over the node's fragments
    /// (in their order); at least 1 is tried.
    pub candidates: u16,
    /// Cost of one split against one fragment of imbalance: a candidate scores
    /// `split_weight * splits + |front - back|` and the lowest score wins (the
    /// earliest candidate on a tie).
    pub split_weight: u32,
}

impl BspOptions {
    /// 16 candidates, a split weighing 8 fragments of imbalance.
    pub const DEFAULT: Self = Self {
        candidates: 16,
        split_weight: 8,
    };
}

impl Default for BspOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A BSP tree over a static mesh, built once, walked per viewpoint.
#[derive(Debug, Clone, Copy)]
pub struct BspTree<'s> {
    pub(super) fragments: Mesh<'s>,
    pub(super) source: &'s [u16],
    pub(super) nodes: &'s [BspNode],
    pub(super) depth: usize,
    pub(super) pieces: usize,
    pub(super) work_peak: usize,
}

impl<'s> BspTree<'s> {
    /// Builds the tree for a static mesh with [`BspOptions::DEFAULT`]; see
    /// [`BspTree::build_with`].
    pub fn build(mesh: &Mesh<'_>, storage: BspStorage<'s>) -> Result<Self, Error> {
        Self::build_with(mesh, storage, BspOptions::DEFAULT)
    }

    /// Builds the tree iteratively (an explicit work stack in `storage.work`, no
    /// recursion), splitting fragments that straddle a node's plane.
    ///
    /// Planes and split points are computed in f64 (split points stored as f32; both
    /// halves of a split share the split point's vertex index). A planar face starts
    /// as one fragment in its Newell plane through its centroid. A face that is not
    /// planar within [`PLANE_TOLERANCE`] takes its depth from its fan triangles
    /// `(v0, vk, vk+1)` ([conventions](crate::conventions)), so when it is strictly convex
    /// in its own
    /// plane it starts as those triangles, each in its own plane (each extra triangle
    /// counts in [`splits`](Self::splits)); otherwise it stays whole, in its Newell
    /// plane. The fragments of the splitter's surface (face, or fan triangle) all
    /// stay in its node. A face with a zero normal never splits space; it goes to a
    /// side like any fragment.
    ///
    /// A face's fragments tile its polygon's even-odd coverage only by parity: seen
    /// nearly edge-on, a non-planar face folds and two of its fragments overlap on
    /// screen where the face covers nothing. The engines that draw a depth order
    /// account for that (the code fill counts such a face by parity, the painter
    /// clips its fragments to its polygon).
    ///
    /// The fragments are watertight: a split point is also inserted into every other
    /// fragment edge that lies on the same mesh edge (welded: ends compared by
    /// position bits) or on the same cut chord, in order along it, so two fragments
    /// that share an edge share its whole vertex sequence and no pixel centre falls
    /// between them.
    ///
    /// Errors: [`Error::CapacityExceeded`] as described at [`BspStorage`];
    /// [`Error::TooManyFaces`] when there are more than [`MAX_FACES`](crate::MAX_FACES) fragments.
    pub fn build_with(
        mesh: &Mesh<'_>,
        storage: BspStorage<'s>,
        options: BspOptions,
    ) -> Result<Self, Error> {
        super::build::run(mesh, storage, options)
    }

    /// The fragments as a validated mesh: the original vertices (same indices), then
    /// the split points; one face per fragment, wound like its source face. Every
    /// fragment is a (convex or concave) part of exactly one source face; its edges
    /// hold every split point that lies on them (T-vertices, so it may have
    /// collinear corners).
    pub fn fragments(&self) -> Mesh<'s> {
        self.fragments
    }

    /// `source()[fragment]` is the original face id.
    pub fn source(&self) -> &'s [u16] {
        self.source
    }

    /// Number of fragments.
    pub fn fragment_count(&self) -> usize {
        self.fragments.face_count()
    }

    /// Number of nodes (node 0 is the root).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The nodes.
    pub fn nodes(&self) -> &'s [BspNode] {
        self.nodes
    }

    /// The most nodes on one root-to-leaf path: the stack the walk needs.
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// Fragment splits made: fragments minus the mesh's faces (a non-planar face
    /// that starts as `t` fan triangles counts `t - 1`).
    pub fn splits(&self) -> usize {
        self.fragment_count().saturating_sub(self.pieces)
    }

    /// The most `work` words the build used: a `work` slice this long suffices.
    pub fn work_peak(&self) -> usize {
        self.work_peak
    }

    /// Walks the tree front to back for a viewpoint, iteratively, calling `visit`
    /// with every fragment id, nearest first (the fragments of one node in source
    /// face order). At a node, the eye's side of the plane comes first; an eye
    /// exactly on the plane takes the back first (the node's fragments are edge-on).
    ///
    /// `stack.len() >= self.depth()`, else [`Error::CapacityExceeded`]
    /// `{ needed: depth, capacity }` before anything is visited.
    pub fn visit_front_to_back(
        &self,
        view: &Viewpoint,
        stack: &mut [u32],
        mut visit: impl FnMut(usize),
    ) -> Result<(), Error> {
        need(Capacity::BspStack, self.depth, stack.len())?;
        let overflow = Error::CapacityExceeded {
            what: Capacity::BspStack,
            needed: self.depth,
            capacity: stack.len(),
        };
        let mut used = 0usize;
        let mut current = if self.nodes.is_empty() { NO_NODE } else { 0 };
        loop {
            while let Some(node) = self.nodes.get(current as usize) {
                let (near, far) = node.near_far(view);
                if near == NO_NODE {
                    // Nothing nearer: visit now, no need to come back.
                    node.fragments().for_each(&mut visit);
                    current = far;
                } else {
                    *stack.get_mut(used).ok_or(overflow)? = current;
                    used += 1;
                    current = near;
                }
            }
            let Some(below) = used.checked_sub(1) else {
                return Ok(());
            };
            used = below;
            let node = stack
                .get(used)
                .and_then(|&n| self.nodes.get(n as usize))
                .ok_or(overflow)?;
            node.fragments().for_each(&mut visit);
            current = node.near_far(view).1;
        }
    }

    /// Walks the tree for a viewpoint, front to back, writing `rank[fragment] = 0, 1,
    /// 2, ...` (0 = nearest); see [`BspTree::visit_front_to_back`]. For any ray from
    /// the eye, the nearest fragment it meets has the lowest rank among those it
    /// meets; at equal depth (coplanar fragments) the lower source face id ranks
    /// lower.
    ///
    /// `stack.len() >= self.depth()` and `rank.len() >= self.fragment_count()`, else
    /// [`Error::CapacityExceeded`] with the exact need, before anything is written.
    pub fn rank_front_to_back(
        &self,
        view: &Viewpoint,
        stack: &mut [u32],
        rank: &mut [u32],
    ) -> Result<(), Error> {
        need(Capacity::BspStack, self.depth, stack.len())?;
        need(Capacity::FragmentRanks, self.fragment_count(), rank.len())?;
        let mut next = 0u32;
        self.visit_front_to_back(view, stack, |fragment| {
            if let Some(r) = rank.get_mut(fragment) {
                *r = next;
            }
            next = next.wrapping_add(1);
        })
    }
}
