//! The crate-wide error type.

use core::convert::Infallible;
use core::fmt;

mod capacity;
mod shortfalls;

pub use capacity::Capacity;
pub use shortfalls::{Shortfall, Shortfalls, MAX_SHORTFALLS};

/// The largest supported target side, in pixels ([`Error::ViewportTooLarge`] beyond).
pub const MAX_VIEWPORT: u32 = 8192;

/// Everything that can go wrong in pbuffer, as a value: no input panics.
///
/// `T` is the error of the span sink or draw target the spans go to; it is
/// [`Infallible`] for pure geometry and for in-memory targets such as
/// [`PackedFramebuffer`](crate::PackedFramebuffer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error<T = Infallible> {
    /// A coordinate was NaN or infinite.
    NonFinite,
    /// A finite coordinate does not fit the fixed-point type (32 bits with S fractional bits).
    OutOfRange,
    /// A polygon needs at least three vertices.
    TooFewVertices {
        /// How many vertices were given.
        found: usize,
    },
    /// A fixed-capacity buffer is too small for this input.
    CapacityExceeded {
        /// Which buffer: its doc says which stage uses it and what to grow.
        what: Capacity,
        /// The capacity this input needs (a lower bound where [`Capacity`]'s
        /// variant says "at least").
        needed: usize,
        /// The compiled capacity.
        capacity: usize,
    },
    /// Two or more fixed-capacity buffers are too small for this input, all named
    /// at once with their needs, so that one run tells every size to grow (one
    /// alone is [`CapacityExceeded`](Self::CapacityExceeded);
    /// [`Error::shortfalls`] lists either).
    CapacitiesExceeded(Shortfalls),
    /// The target is larger than [`MAX_VIEWPORT`] in some direction.
    ViewportTooLarge {
        /// Width of the target in pixels.
        width: u32,
        /// Height of the target in pixels.
        height: u32,
    },
    /// A mesh vertex has a NaN or infinite coordinate.
    NonFiniteVertex {
        /// 0-based vertex index.
        vertex: usize,
    },
    /// A face refers to a vertex that does not exist.
    IndexOutOfRange {
        /// 0-based face index.
        face: usize,
        /// The offending vertex index.
        index: u32,
    },
    /// A face has fewer than 3 vertex indices.
    DegenerateFace {
        /// 0-based face index.
        face: usize,
    },
    /// The face offsets do not start at 0, decrease, or do not end at the index count.
    BadFaceOffsets {
        /// The face whose range is wrong.
        face: usize,
    },
    /// The mesh has no faces.
    EmptyMesh,
    /// An edge list given to
    /// [`EdgeAdjacency::from_edges`](crate::mesh::EdgeAdjacency::from_edges) does not
    /// fit the mesh.
    BadEdgeList {
        /// 0-based index of the first edge that does not fit.
        edge: usize,
        /// What is wrong with it.
        problem: EdgeProblem,
    },
    /// More faces than face ids can name.
    TooManyFaces {
        /// Faces in the mesh.
        faces: usize,
        /// The most supported.
        max: usize,
    },
    /// The camera cannot make a view.
    BadCamera(CameraProblem),
    /// A depth order given to the code-fill engine was not made for this mesh (its
    /// vertices do not begin with the mesh's, or a surface has no source face or
    /// rank).
    DepthOrderMismatch,
    /// Newell's depth sort ([`NewellOrder`](crate::order::NewellOrder)) made more
    /// shuffles and splits than its bound
    /// ([`NewellOptions::max_steps`](crate::order::NewellOptions::max_steps)) without
    /// settling the order.
    DepthSortUnsettled {
        /// Shuffles and splits made when it stopped.
        steps: usize,
    },
    /// A row needs a wider surface code than the engine was compiled for.
    CodeTooWide {
        /// Bits the widest row needs.
        needed: usize,
        /// Bits compiled in.
        capacity: usize,
    },
    /// Surface codes break a condition of their coding scheme (the modulo-2 surface-filling paper).
    Scheme(SchemeViolation),
    /// Too few sub-pixel bits for a pixel's sub-samples to lie on the fixed-point grid
    /// (the grey coverage mode samples a 4 x 4 grid at eighths of a pixel).
    SubpixelTooCoarse {
        /// Sub-pixel bits compiled in.
        bits: u32,
        /// The fewest that work.
        needed: u32,
    },
    /// Baked face planes given to
    /// [`BakedMesh::new`](crate::render::BakedMesh::new) do not fit the mesh: a
    /// count that differs, or a normal or centroid that is not the face's own.
    BadFacePlanes {
        /// The first face whose plane does not fit (the plane count when short).
        face: usize,
    },
    /// A [`Drawing`](crate::Drawing) was asked to draw before a mesh was baked.
    NothingBaked,
    /// Too many sub-pixel bits for an engine whose screen coordinates are 16 bits.
    SubpixelTooFine {
        /// Sub-pixel bits compiled in.
        bits: u32,
        /// The most that work.
        max: u32,
    },
    /// The span sink or draw target failed.
    Target(T),
}

/// Why a camera was rejected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum CameraProblem {
    /// A camera parameter is NaN or infinite.
    NonFinite,
    /// The eye is at the target.
    EyeAtTarget,
    /// `up` is zero or parallel to the view direction.
    UpParallelToView,
    /// The field of view is not in (0, 180) degrees.
    FovOutOfRange,
    /// The orthographic half-height is not positive.
    HalfHeightNotPositive,
    /// `near <= 0`.
    NearNotPositive,
    /// `far <= near`.
    FarNotBeyondNear,
}

/// Which condition of a coding scheme (or of its occlusion graph) does not hold.
///
/// Paths are numbered from 0 in the order given to [`OcclusionGraph::new`](crate::codes::OcclusionGraph::new).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SchemeViolation {
    /// A path lists no surface.
    EmptyPath {
        /// The empty path.
        path: usize,
    },
    /// A path names a surface the graph does not have.
    UnknownSurface {
        /// The path.
        path: usize,
        /// The surface index, not below the surface count.
        surface: u16,
    },
    /// A path lists a surface twice.
    RepeatedSurface {
        /// The path.
        path: usize,
        /// The repeated surface.
        surface: u16,
    },
    /// Two paths put the surfaces they share in different depth orders.
    OrderConflict {
        /// The first path.
        first: usize,
        /// The second path.
        second: usize,
    },
    /// The depth orders of the paths form a cycle, so surfaces have no depth level.
    CyclicOrder,
    /// The number of codes given is not the number the graph needs.
    CodeCount {
        /// Codes given.
        given: usize,
        /// Codes needed (surfaces, or paths for path codes).
        expected: usize,
    },
    /// Proposition 1: the codes of this path are linearly dependent over GF(2), so two
    /// combinations on it give the same code.
    PathDependent {
        /// The path.
        path: usize,
    },
    /// Proposition 2: the codes of the union of these two paths are linearly
    /// dependent, so a combination on one equals a different one on the other.
    PathUnionDependent {
        /// The first path.
        first: usize,
        /// The second path.
        second: usize,
    },
    /// Proposition 3: `p_first + p_second` lies in the span of the node codewords, so a
    /// combination on one path equals a combination on the other.
    PathCodesInNodeSpan {
        /// The first path.
        first: usize,
        /// The second path.
        second: usize,
    },
    /// Proposition 4: the sum of the node codes of these two priorities is a path
    /// code, so a node on one path decodes like another node on another path.
    NodeCodesInPathCode {
        /// The first priority (0 = blank, 1 = nearest surface).
        first: u32,
        /// The second priority.
        second: u32,
    },
    /// No assignment of codes of this width satisfies Propositions 1 and 2.
    NoAssignment {
        /// The code width searched, in bits.
        width: u32,
    },
    /// The search for codes stopped after its budget of trials, undecided.
    SearchGaveUp {
        /// The code width searched, in bits.
        width: u32,
        /// Candidate codes tried.
        trials: u64,
    },
    /// A pixel's code is in no row of the colour table: the surfaces covering it are
    /// on no path of the graph (the scene has an overlap the graph omits), or the
    /// screen segment put the pixel on a path that does not hold them.
    UnlistedCode {
        /// The code the filler left at the pixel.
        code: u128,
        /// The pixel's column.
        x: u16,
        /// The pixel's row.
        y: u16,
    },
    /// A screen segment names a path the graph does not have.
    UnknownPath {
        /// The path named.
        path: usize,
        /// The pixel's column.
        x: u16,
        /// The pixel's row.
        y: u16,
    },
}

impl fmt::Display for SchemeViolation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::EmptyPath { path } => write!(f, "path {path} is empty"),
            Self::UnknownSurface { path, surface } => {
                write!(
                    f,
                    "path {path} names surface {surface}, which does not exist"
                )
            }
            Self::RepeatedSurface { path, surface } => {
                write!(f, "path {path} lists surface {surface} twice")
            }
            Self::OrderConflict { first, second } => write!(
                f,
                "paths {first} and {second} order their shared surfaces differently"
            ),
            Self::CyclicOrder => f.write_str("the paths' depth orders form a cycle"),
            Self::CodeCount { given, expected } => {
                write!(f, "{given} codes given, {expected} needed")
            }
            Self::PathDependent { path } => write!(
                f,
                "proposition 1: the codes of path {path} are linearly dependent"
            ),
            Self::PathUnionDependent { first, second } => write!(
                f,
                "proposition 2: the codes of paths {first} and {second} together are \
                 linearly dependent"
            ),
            Self::PathCodesInNodeSpan { first, second } => write!(
                f,
                "proposition 3: the sum of the codes of paths {first} and {second} is in \
                 the span of the node codes"
            ),
            Self::NodeCodesInPathCode { first, second } => write!(
                f,
                "proposition 4: the sum of the node codes of priorities {first} and \
                 {second} is a path code"
            ),
            Self::NoAssignment { width } => {
                write!(
                    f,
                    "no assignment of {width}-bit codes satisfies propositions 1 and 2"
                )
            }
            Self::SearchGaveUp { width, trials } => write!(
                f,
                "the search for {width}-bit codes gave up after {trials} trials"
            ),
            Self::UnlistedCode { code, x, y } => write!(
                f,
                "pixel ({x}, {y}) has code {code:#b}, which is in no row of the colour \
                 table (an overlap the occlusion graph omits)"
            ),
            Self::UnknownPath { path, x, y } => write!(
                f,
                "the screen segment of pixel ({x}, {y}) names path {path}, which does \
                 not exist"
            ),
        }
    }
}

/// Why an edge of a prebuilt edge list was rejected
/// ([`Error::BadEdgeList`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum EdgeProblem {
    /// An end is not a vertex of the mesh.
    EndOutOfRange,
    /// The ends are not ascending (`a < b`).
    EndsNotAscending,
    /// The edge does not come strictly after the one before it by `(a, b)`.
    NotSorted,
    /// A face is not a face of the mesh.
    FaceOutOfRange,
    /// The face count, the two faces and the kind disagree: no face; one face but
    /// two different faces named, or a kind other than boundary; two or more faces
    /// not ascending; boundary or non-manifold with another count.
    FacesDisagree,
    /// A hole label on an edge that is not a boundary edge, at or above
    /// `MAX_HOLES`, or on some boundary edges and not on others.
    HoleLabel,
}

impl Error<Infallible> {
    /// Widens a geometry error to the error type of any target.
    pub fn widen<T>(self) -> Error<T> {
        match self {
            Error::NonFinite => Error::NonFinite,
            Error::OutOfRange => Error::OutOfRange,
            Error::TooFewVertices { found } => Error::TooFewVertices { found },
            Error::CapacityExceeded {
                what,
                needed,
                capacity,
            } => Error::CapacityExceeded {
                what,
                needed,
                capacity,
            },
            Error::CapacitiesExceeded(list) => Error::CapacitiesExceeded(list),
            Error::ViewportTooLarge { width, height } => Error::ViewportTooLarge { width, height },
            Error::NonFiniteVertex { vertex } => Error::NonFiniteVertex { vertex },
            Error::IndexOutOfRange { face, index } => Error::IndexOutOfRange { face, index },
            Error::DegenerateFace { face } => Error::DegenerateFace { face },
            Error::BadFaceOffsets { face } => Error::BadFaceOffsets { face },
            Error::EmptyMesh => Error::EmptyMesh,
            Error::BadEdgeList { edge, problem } => Error::BadEdgeList { edge, problem },
            Error::TooManyFaces { faces, max } => Error::TooManyFaces { faces, max },
            Error::BadCamera(p) => Error::BadCamera(p),
            Error::DepthOrderMismatch => Error::DepthOrderMismatch,
            Error::DepthSortUnsettled { steps } => Error::DepthSortUnsettled { steps },
            Error::CodeTooWide { needed, capacity } => Error::CodeTooWide { needed, capacity },
            Error::Scheme(v) => Error::Scheme(v),
            Error::SubpixelTooCoarse { bits, needed } => Error::SubpixelTooCoarse { bits, needed },
            Error::BadFacePlanes { face } => Error::BadFacePlanes { face },
            Error::NothingBaked => Error::NothingBaked,
            Error::SubpixelTooFine { bits, max } => Error::SubpixelTooFine { bits, max },
            Error::Target(never) => match never {},
        }
    }
}

/// So that `?` turns it into a `Box<dyn Error>` and error-reporting crates take it
/// (`core::error::Error`: no `std` needed).
impl<T: fmt::Debug> core::error::Error for Error<T> {}

impl<T: fmt::Debug> fmt::Display for Error<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite => f.write_str("coordinate is NaN or infinite"),
            Error::OutOfRange => f.write_str("coordinate does not fit the fixed-point type"),
            Error::TooFewVertices { found } => {
                write!(f, "polygon has {found} vertices, at least 3 are needed")
            }
            Error::CapacityExceeded {
                what,
                needed,
                capacity,
            } => write!(f, "{what}: {needed} needed, capacity {capacity}"),
            Error::CapacitiesExceeded(list) => write!(f, "{list}"),
            Error::ViewportTooLarge { width, height } => write!(
                f,
                "target of {width}x{height} pixels exceeds the {0}x{0} maximum",
                MAX_VIEWPORT
            ),
            Error::NonFiniteVertex { vertex } => {
                write!(f, "vertex {vertex} has a NaN or infinite coordinate")
            }
            Error::IndexOutOfRange { face, index } => {
                write!(
                    f,
                    "face {face} refers to vertex {index}, which does not exist"
                )
            }
            Error::DegenerateFace { face } => {
                write!(f, "face {face} has fewer than 3 vertices")
            }
            Error::BadFaceOffsets { face } => write!(f, "face offsets are wrong at face {face}"),
            Error::EmptyMesh => f.write_str("the mesh has no faces"),
            Error::BadEdgeList { edge, problem } => {
                write!(
                    f,
                    "edge {edge} of the edge list does not fit the mesh: {problem:?}"
                )
            }
            Error::TooManyFaces { faces, max } => {
                write!(f, "the mesh has {faces} faces, at most {max} are supported")
            }
            Error::BadCamera(p) => write!(f, "bad camera: {p:?}"),
            Error::DepthOrderMismatch => f.write_str("the depth order was made for another mesh"),
            Error::DepthSortUnsettled { steps } => write!(
                f,
                "the depth sort did not settle within {steps} shuffles and splits"
            ),
            Error::CodeTooWide { needed, capacity } => write!(
                f,
                "a row needs a {needed}-bit surface code, {capacity} bits are compiled in"
            ),
            Error::Scheme(v) => write!(f, "surface codes: {v}"),
            Error::SubpixelTooCoarse { bits, needed } => write!(
                f,
                "{bits} sub-pixel bits are too few for sub-samples, at least {needed} are needed"
            ),
            Error::BadFacePlanes { face } => {
                write!(f, "baked face planes do not fit the mesh at face {face}")
            }
            Error::NothingBaked => f.write_str("nothing baked to draw: call Drawing::bake first"),
            Error::SubpixelTooFine { bits, max } => write!(
                f,
                "{bits} sub-pixel bits are too many for this engine, at most {max}"
            ),
            Error::Target(e) => write!(f, "draw target failed: {e:?}"),
        }
    }
}

/// `CapacityExceeded` naming `what` when `needed` is more than `capacity`: the one
/// check every fixed-size buffer makes.
pub(crate) fn need(what: Capacity, needed: usize, capacity: usize) -> Result<(), Error> {
    if needed > capacity {
        return Err(Error::CapacityExceeded {
            what,
            needed,
            capacity,
        });
    }
    Ok(())
}
