//! The unique edges of a mesh, found by welding and sorting, in lent storage.
//!
//! Vertices at bit-identical positions are one vertex (so a seam of duplicated
//! vertices draws no line): vertex ids are sorted by coordinate bits and each
//! vertex stands for the lowest id at its position. Every face edge becomes a
//! record (lower end, higher end, face); sorting the records puts the uses of
//! one edge next to each other, and each run becomes one [`MeshEdge`].

use super::features::{classify, cos_degrees};
use super::{EdgeKind, Mesh, MeshEdge};
use crate::sort::sort_by_key;
use crate::Capacity;
use crate::{EdgeProblem, Error};

/// Scratch record for building adjacency: one use of an edge by a face. The
/// caller lends `indices.len()` of them to [`EdgeAdjacency::build`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct HalfEdgeRecord {
    /// The lower welded end.
    lo: u32,
    /// The higher welded end.
    hi: u32,
    /// The face using the edge.
    face: u32,
}

impl HalfEdgeRecord {
    /// A placeholder to fill the scratch buffer with, such as
    /// `[HalfEdgeRecord::EMPTY; N]` in a `static`.
    pub const EMPTY: Self = Self {
        lo: 0,
        hi: 0,
        face: 0,
    };
}

/// The mesh's unique edges, built once into storage the caller lends.
#[derive(Debug)]
pub struct EdgeAdjacency<'s> {
    edges: &'s [MeshEdge],
}

/// The edge being gathered from a run of records.
struct Run {
    lo: u32,
    hi: u32,
    faces: [u32; 2],
    face_count: u32,
    /// The run's latest face: records sort by face within a run, so a face seen
    /// again is the same face using the edge twice.
    last_face: u32,
}

impl Run {
    fn start(record: &HalfEdgeRecord) -> Self {
        Self {
            lo: record.lo,
            hi: record.hi,
            faces: [record.face; 2],
            face_count: 1,
            last_face: record.face,
        }
    }
}

impl<'s> EdgeAdjacency<'s> {
    /// Finds the unique edges of `mesh` and classifies them, with creases where the
    /// normals of an edge's two faces are more than `crease_deg` degrees apart
    /// (the CLI's default is 30; the angle is clamped to `[0, 180]`). Edges come out
    /// sorted by `(a, b)`.
    ///
    /// Storage: `weld` needs at least the vertex count, `scratch` at least
    /// `indices.len()`, `out` at least the number of unique edges (at most
    /// `indices.len()`). The first one too small, in that order, is reported as
    /// [`Error::CapacityExceeded`] with the exact size needed (for `out`, the exact
    /// unique-edge count). A non-finite `crease_deg` is [`Error::NonFinite`],
    /// checked before anything else. On success `weld` holds the vertex ids sorted
    /// by position.
    ///
    /// Cost: two shell sorts (vertices, then half-edges) and a binary search per
    /// corner.
    pub fn build(
        mesh: &Mesh<'_>,
        crease_deg: f32,
        weld: &mut [u32],
        scratch: &mut [HalfEdgeRecord],
        out: &'s mut [MeshEdge],
    ) -> Result<Self, Error> {
        if !crease_deg.is_finite() {
            return Err(Error::NonFinite);
        }
        let weld = lend(Capacity::Vertices, weld, mesh.vertices().len())?;
        let scratch = lend(Capacity::HalfEdges, scratch, mesh.indices().len())?;
        sort_by_position(mesh, weld);
        let records = half_edges(mesh, weld, scratch);
        sort_by_key(records, |r| (r.lo, r.hi, r.face));

        let crease_cos = cos_degrees(crease_deg);
        let capacity = out.len();
        let mut count = 0usize;
        let mut emit = |run: &Run| {
            if let Some(slot) = out.get_mut(count) {
                *slot = MeshEdge {
                    a: run.lo,
                    b: run.hi,
                    faces: run.faces,
                    face_count: run.face_count,
                    kind: classify(mesh, run.faces, run.face_count, crease_cos),
                };
            }
            // A full buffer keeps counting, to report the size needed.
            count += 1;
        };
        let mut current: Option<Run> = None;
        for record in records.iter() {
            match current.as_mut() {
                Some(run) if run.lo == record.lo && run.hi == record.hi => {
                    if record.face != run.last_face {
                        if run.face_count == 1 {
                            run.faces[1] = record.face;
                        }
                        run.face_count = run.face_count.saturating_add(1);
                        run.last_face = record.face;
                    }
                }
                _ => {
                    if let Some(run) = current.as_ref() {
                        emit(run);
                    }
                    current = Some(Run::start(record));
                }
            }
        }
        if let Some(run) = current.as_ref() {
            emit(run);
        }
        if count > capacity {
            return Err(Error::CapacityExceeded {
                what: Capacity::Edges,
                needed: count,
                capacity,
            });
        }
        let out: &'s [MeshEdge] = out;
        Ok(Self {
            edges: out.get(..count).unwrap_or(&[]),
        })
    }

    /// The edges of `mesh` that [`build`](Self::build) made before, kept where the
    /// caller likes: in flash (a `static` generated on the host, say), so that the
    /// edge list, the weld map and the half-edge records take no RAM on the target.
    ///
    /// Checked in one pass, so that no later use can index out of range or meet an
    /// edge [`build`](Self::build) would not make: ends and faces in range, ends
    /// ascending, edges strictly sorted by `(a, b)`, and face count, faces and kind
    /// agreeing ([`Error::BadEdgeList`] names the first edge that does not and why).
    /// Not checked: that the list is this mesh's (welding, the crease angle); a list
    /// built for another mesh of the same size draws the wrong lines.
    pub fn from_edges(mesh: &Mesh<'_>, edges: &'s [MeshEdge]) -> Result<Self, Error> {
        let (vertices, faces) = (mesh.vertices().len(), mesh.face_count());
        let mut previous: Option<(u32, u32)> = None;
        for (k, e) in edges.iter().enumerate() {
            let bad = |problem| Err(Error::BadEdgeList { edge: k, problem });
            if e.b as usize >= vertices {
                return bad(EdgeProblem::EndOutOfRange);
            }
            if e.a >= e.b {
                return bad(EdgeProblem::EndsNotAscending);
            }
            if previous.is_some_and(|p| p >= (e.a, e.b)) {
                return bad(EdgeProblem::NotSorted);
            }
            if e.faces.iter().any(|&f| f as usize >= faces) {
                return bad(EdgeProblem::FaceOutOfRange);
            }
            let [f0, f1] = e.faces;
            let agree = match (e.face_count, e.kind) {
                (0, _) => false,
                (1, kind) => f0 == f1 && kind == EdgeKind::Boundary,
                (2, EdgeKind::Crease | EdgeKind::Smooth | EdgeKind::Inert) => f0 < f1,
                (3.., EdgeKind::NonManifold) => f0 < f1,
                _ => false,
            };
            if !agree {
                return bad(EdgeProblem::FacesDisagree);
            }
            previous = Some((e.a, e.b));
        }
        Ok(Self { edges })
    }

    /// The unique edges, sorted by `(a, b)`.
    pub fn edges(&self) -> &'s [MeshEdge] {
        self.edges
    }

    /// Is the mesh closed: every edge used by exactly two faces?
    pub fn is_closed(&self) -> bool {
        self.edges.iter().all(|e| e.face_count == 2)
    }
}

/// The first `needed` items of a lent buffer, or the error naming its shortfall.
fn lend<T>(what: Capacity, buffer: &mut [T], needed: usize) -> Result<&mut [T], Error> {
    let capacity = buffer.len();
    buffer.get_mut(..needed).ok_or(Error::CapacityExceeded {
        what,
        needed,
        capacity,
    })
}

/// Fills `weld` with the vertex ids sorted by coordinate bits, then by id, so
/// the first id of each run of equal positions is the lowest.
fn sort_by_position(mesh: &Mesh<'_>, weld: &mut [u32]) {
    for (i, slot) in weld.iter_mut().enumerate() {
        // Ids past u32 would be vertices no index can name; a wrapped id only
        // repeats a real one, which the binary search in `welded` tolerates.
        *slot = i as u32;
    }
    sort_by_key(weld, |&v| (mesh.position_bits(v), v));
}

/// The lowest vertex id at vertex `v`'s position, by binary search in the
/// sorted `weld`.
fn welded(mesh: &Mesh<'_>, weld: &[u32], v: u32) -> u32 {
    let position = mesh.position_bits(v);
    let first = weld.partition_point(|&w| mesh.position_bits(w) < position);
    weld.get(first).copied().unwrap_or(v)
}

/// Writes one record per face edge whose welded ends differ (closing edge
/// included) and returns them. `scratch` holds `indices.len()`, enough for all.
fn half_edges<'r>(
    mesh: &Mesh<'_>,
    weld: &[u32],
    scratch: &'r mut [HalfEdgeRecord],
) -> &'r mut [HalfEdgeRecord] {
    let mut count = 0usize;
    for face in 0..mesh.face_count() {
        let corners = mesh.face(face);
        let Some(&last) = corners.last() else {
            continue;
        };
        let mut previous = welded(mesh, weld, last);
        for &corner in corners {
            let current = welded(mesh, weld, corner);
            if current != previous {
                if let Some(slot) = scratch.get_mut(count) {
                    *slot = HalfEdgeRecord {
                        lo: previous.min(current),
                        hi: previous.max(current),
                        // Faces number at most MAX_FACES, well inside u32.
                        face: face as u32,
                    };
                    count += 1;
                }
            }
            previous = current;
        }
    }
    let (records, _) = scratch.split_at_mut(count);
    records
}
