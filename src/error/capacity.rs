//! Which fixed-size buffer ran out ([`Error::CapacityExceeded`](crate::Error::CapacityExceeded)).

use core::fmt;

/// The buffer an [`Error::CapacityExceeded`](crate::Error::CapacityExceeded) names,
/// with the stage that uses it and what to grow.
///
/// `needed` is exact unless the variant says "at least": then the stage stopped
/// where the buffer ran out, and a larger buffer may run out again further on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Capacity {
    /// Mesh vertices: [`Drawing`](crate::Drawing)'s `V`;
    /// [`FastWorkspace::vertices`](crate::render::FastWorkspace::vertices); the
    /// vertex cache lent to the other engines; `weld` of
    /// [`EdgeAdjacency::build`](crate::mesh::EdgeAdjacency::build). Exact.
    Vertices,
    /// Mesh faces: [`Drawing`](crate::Drawing)'s `F`; the face planes of
    /// [`BakedMesh::bake`](crate::render::BakedMesh::bake); the fast engine's
    /// `face_links` and `slopes`. Exact.
    Faces,
    /// Mesh edges: [`Drawing`](crate::Drawing)'s `E` (at least the unique edges and
    /// half the corners); the edge lists of
    /// [`EdgeAdjacency::build`](crate::mesh::EdgeAdjacency::build) (`out`) and
    /// [`BakedMesh::bake`](crate::render::BakedMesh::bake); the fast engine's
    /// `line_links`. Exact.
    Edges,
    /// Face corners of the mesh: `scratch` of
    /// [`EdgeAdjacency::build`](crate::mesh::EdgeAdjacency::build), one half-edge
    /// record a corner. Exact.
    HalfEdges,
    /// One bit a face, in 32-bit words: the fast engine's `facing`, the other
    /// engines' drawn bits, the planarity bits
    /// ([`planar_words`](crate::mesh::planar_words)). Exact.
    FaceBits,
    /// One bit an edge, in 32-bit words: the other engines' feature-edge bits. Exact.
    EdgeBits,
    /// Facets active on one row of the fast engine: [`Drawing`](crate::Drawing)'s
    /// `FACETS`, [`FastRenderer`](crate::render::FastRenderer)'s second const
    /// parameter. From a `Drawing` or `BakedDrawing`, exact: the frame's peak
    /// (`Stats::peak_faces` of a frame that fits); from `FastRenderer::render`, at
    /// least (one more than the table), and `FastRenderer::needs` counts the peak.
    ActiveFacets,
    /// Feature lines active on one row of the fast engine:
    /// [`Drawing`](crate::Drawing)'s `LINES`,
    /// [`FastRenderer`](crate::render::FastRenderer)'s third const parameter.
    /// Exact from a `Drawing` (`Stats::peak_edges` of a frame that fits); at least
    /// from `FastRenderer::render`, as for [`ActiveFacets`](Self::ActiveFacets).
    ActiveLines,
    /// Corners of the clipped faces of one fast-engine frame:
    /// [`FastWorkspace::pool`](crate::render::FastWorkspace::pool) (at most 65,535
    /// are used); fixed at [`CLIPPED_CORNERS`](crate::CLIPPED_CORNERS) in a
    /// [`Drawing`](crate::Drawing). Exact from a `Drawing` (the frame's total); at
    /// least from `FastRenderer::render`, as for [`ActiveFacets`](Self::ActiveFacets).
    ClippedCorners,
    /// Pixels of one row: [`FrameRows`](crate::FrameRows)' `W`; the fast
    /// engine's `row` and `ids`. Exact.
    RowWidth,
    /// Rows of the frame: [`FrameRows`](crate::FrameRows)' `H`; the fast
    /// engine's per-row list `heads` (two a row). Exact.
    Rows,
    /// The line masks of one row (two words per 32 columns, three with dashes
    /// along the edges): [`FrameRows`](crate::FrameRows)' `H` (a word a
    /// row); the fast engine's `masks`. Exact.
    LineMasks,
    /// Dash phases, one for each active line, with dashes along the edges: the
    /// fast engine's `phases` (`LINES` of them; none in a
    /// [`Drawing`](crate::Drawing), which therefore draws only screen dashes). Exact.
    DashPhases,
    /// Contour edges of one frame of hidden lines by the segment
    /// ([`SegmentLines`](crate::render::SegmentLines)' `CONTOURS`). Exact.
    ContourEdges,
    /// Crossings of drawn edges with nearer contour edges in one frame of hidden
    /// lines by the segment ([`SegmentLines`](crate::render::SegmentLines)'
    /// `CROSSINGS`). At least (the edge where it ran out).
    Crossings,
    /// Entries of the contour grid in one frame of hidden lines by the segment
    /// ([`SegmentLines`](crate::render::SegmentLines)' `CELL_ENTRIES`). Exact.
    GridEntries,
    /// Faces that do not hide one drawn edge (its own, and the faces beyond an own
    /// face collapsed on an outline): fixed at
    /// [`MAX_NOT_HIDING`](crate::render::MAX_NOT_HIDING). At least.
    NotHidingFaces,
    /// Triangles on one side (an edge's faces' and a fold's): fixed at
    /// [`MAX_SIDE_TRIANGLES`](crate::render::MAX_SIDE_TRIANGLES). At least.
    SideTriangles,
    /// Pairs of an edge and a triangle that may meet in 3-D: the piercings
    /// [`Piercing::bake`](crate::render::Piercing::bake) writes. Exact.
    Piercings,
    /// Faces around the vertices (one a face corner): the baked
    /// [`VertexFaces`](crate::render::VertexFaces). Exact.
    VertexFaces,
    /// Corners of one face: the fast engine's [`MAX_CORNERS`](crate::render::MAX_CORNERS)
    /// (fixed); the other engines' `POLY` const parameter. Exact.
    FaceCorners,
    /// Corners of one face after clipping at the view volume: fixed in the fast
    /// engine; the other engines' `POLY` const parameter. At least (the plane where
    /// it ran out; later planes may add more).
    ClippedFaceCorners,
    /// Faces active on one row of the code-fill engine: its `FACES` const
    /// parameter. At least (the row where it ran out).
    ActiveFaces,
    /// Edges active on one row of a scan-line fill (the code-fill engine's and the
    /// 2-D scan converter's `EDGES` const parameter). At least (the row where it
    /// ran out).
    ActiveEdges,
    /// The surface codes of one row: the code-fill engine's row codes, the schemes
    /// engine's `codes`. Exact.
    RowCodes,
    /// The words of one row of the XOR filler: its `WORDS` const parameter. Exact.
    RowWords,
    /// The list of faces in depth order: the code-fill engine's order, the
    /// painter's `list`. Exact.
    DepthOrder,
    /// The id (and depth) samples of a band of rows: the band engines' `samples`.
    /// Exact (one row's need).
    BandSamples,
    /// The line words of a band of rows: the band engines' `line_words`. Exact
    /// (one row's need).
    BandLineWords,
    /// The Z-buffer's list of small faces in one band (`small`). Exact (the mesh's
    /// face count always suffices).
    SmallFaces,
    /// Faces considered at one pixel by the grey coverage mode's A-buffer (fixed).
    /// At least.
    PixelCandidates,
    /// Rows of a colour table: its `E` const parameter. Exact.
    ColourTableRows,
    /// Paths that need a coset of the code (the schemes' coset path codes). Exact.
    PathCodes,
    /// Surface ids a colour table can name (16 bits). Exact.
    SurfaceIds,
    /// Faces of the ray-cast engine's storage (`faces`). Exact.
    RaycastFaces,
    /// Nodes of the ray-cast engine's bounding-volume tree (`nodes`). Exact.
    BvhNodes,
    /// Faces in view lent to the area-subdivision engine (`faces`). Exact.
    WarnockFaces,
    /// The area-subdivision engine's stack of areas (`areas`). Exact (the bound of
    /// `WarnockSizes`).
    WarnockAreas,
    /// The area-subdivision engine's face lists (`lists`). At least: the bound of
    /// `WarnockSizes` is reported.
    WarnockLists,
    /// Edges drawn through the picked pixel ([`pick`](crate::render::pick)'s
    /// `edges`). Exact.
    PickedEdges,
    /// Vertices of a depth order's storage (BSP or Newell, `vertices`): the mesh's
    /// and the split points. At least (the split where it ran out).
    SplitVertices,
    /// Vertex indices of a depth order's fragments (`indices`). Exact for the BSP
    /// build's result, at least while the Newell sort runs.
    FragmentIndices,
    /// CSR offsets of a depth order's fragments (`offsets`). Exact for the BSP
    /// build, at least for the Newell sort.
    FragmentOffsets,
    /// Source faces of a depth order's fragments (`source`). Exact for the BSP
    /// build, at least for the Newell sort.
    FragmentSources,
    /// Ranks of a depth order's fragments (`rank`). Exact.
    FragmentRanks,
    /// Root segments of a depth order's split points (`seams`). At least.
    SplitSeams,
    /// The Newell sort's screen boxes (`boxes`). At least.
    SortBoxes,
    /// Scratch words of a depth order's build (`work`, BSP or Newell), and of the
    /// seams' split points. At least.
    OrderWork,
    /// Nodes of a BSP tree (`nodes`). Exact.
    BspNodes,
    /// The stack of a BSP tree's traversal: its depth. Exact.
    BspStack,
    /// Instances of a [`SceneDrawing`](crate::SceneDrawing): its `N`. Exact.
    Instances,
    /// Corner indices and face starts of a [`SceneDrawing`](crate::SceneDrawing)'s
    /// union (its `C`): every instance's corners, plus its faces, plus one. Exact.
    SceneCorners,
    /// A count past what a 32-bit index (or a BSP node id, 31 bits) can name: the
    /// mesh or its splits are too large. Exact.
    Index32,
}

impl Capacity {
    /// The buffer in words, with the parameter to grow where there is one.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Vertices => "mesh vertices (V)",
            Self::Faces => "mesh faces (F)",
            Self::Edges => "mesh edges (E)",
            Self::HalfEdges => "half-edge records (face corners)",
            Self::FaceBits => "face bits",
            Self::EdgeBits => "edge bits",
            Self::ActiveFacets => "active facets (FACETS)",
            Self::ActiveLines => "active lines (LINES)",
            Self::ContourEdges => "contour edges (CONTOURS)",
            Self::Crossings => "crossings (CROSSINGS)",
            Self::GridEntries => "contour grid entries (CELL_ENTRIES)",
            Self::NotHidingFaces => "faces not hiding a line (MAX_NOT_HIDING)",
            Self::VertexFaces => "faces around vertices (corners)",
            Self::Piercings => "piercing pairs",
            Self::SideTriangles => "triangles on one side (MAX_SIDE_TRIANGLES)",
            Self::ClippedCorners => "clipped corners (CLIPPED_CORNERS, pool)",
            Self::RowWidth => "row width (W)",
            Self::Rows => "rows (H, list heads)",
            Self::LineMasks => "line masks (H, masks)",
            Self::DashPhases => "dash phases",
            Self::FaceCorners => "corners of a face",
            Self::ClippedFaceCorners => "corners of a clipped face",
            Self::ActiveFaces => "active faces (code fill FACES)",
            Self::ActiveEdges => "active edges (EDGES)",
            Self::RowCodes => "row codes",
            Self::RowWords => "row words (WORDS)",
            Self::DepthOrder => "depth order list",
            Self::BandSamples => "band samples",
            Self::BandLineWords => "band line words",
            Self::SmallFaces => "small faces of a band",
            Self::PixelCandidates => "A-buffer faces at a pixel",
            Self::ColourTableRows => "colour table rows (E)",
            Self::PathCodes => "path codes (cosets)",
            Self::SurfaceIds => "surface ids",
            Self::RaycastFaces => "ray-cast faces",
            Self::BvhNodes => "BVH nodes",
            Self::WarnockFaces => "area subdivision faces",
            Self::WarnockAreas => "area subdivision areas",
            Self::WarnockLists => "area subdivision lists",
            Self::PickedEdges => "picked edges",
            Self::SplitVertices => "depth order vertices",
            Self::FragmentIndices => "fragment indices",
            Self::FragmentOffsets => "fragment offsets",
            Self::FragmentSources => "fragment sources",
            Self::FragmentRanks => "fragment ranks",
            Self::SplitSeams => "split seams",
            Self::SortBoxes => "depth sort boxes",
            Self::OrderWork => "depth order work words",
            Self::BspNodes => "BSP nodes",
            Self::BspStack => "BSP stack",
            Self::Index32 => "32-bit indices",
            Self::Instances => "scene instances (N)",
            Self::SceneCorners => "scene corners and face starts (C)",
        }
    }
}

impl fmt::Display for Capacity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::string::ToString;

    use super::Capacity;
    use crate::Error;

    #[test]
    fn a_capacity_error_says_the_buffer_its_need_and_its_capacity() {
        let e: Error = Error::CapacityExceeded {
            what: Capacity::ActiveFacets,
            needed: 128,
            capacity: 32,
        };
        assert_eq!(
            e.to_string(),
            "active facets (FACETS): 128 needed, capacity 32"
        );
        let e: Error = Error::CapacityExceeded {
            what: Capacity::ActiveLines,
            needed: 111,
            capacity: 64,
        };
        assert_eq!(
            e.to_string(),
            "active lines (LINES): 111 needed, capacity 64"
        );
        // Widening keeps the buffer named.
        assert_eq!(e.widen::<()>().to_string(), e.to_string());
    }
}
