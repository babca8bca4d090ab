//! Planes, vertex classification and the work-stack records of the BSP build (f64).

use crate::bits::set_bit;
use crate::mesh::{planar_words, Mesh};
use crate::vector::{add, cross, dot, sub};
use crate::Capacity;
use crate::Error;

/// Where a vertex lies relative to a plane, with the build's tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Side {
    Front,
    Back,
    On,
}

/// A plane `n . p + d = 0` with an unnormalised normal `n`, and the square of the
/// relative tolerance scaled by `|n|^2`, so that classifying needs no square root.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Plane {
    pub n: [f64; 3],
    pub d: f64,
    /// `tolerance^2 * |n|^2`: a point p with `(n . p + d)^2 <= limit * m^2` is on the
    /// plane, where m is p's largest absolute coordinate: the rounding of an f32
    /// position grows with its own magnitude, not with the mesh's (nor with that of a
    /// far vertex of the plane's face).
    pub limit: f64,
}

impl Plane {
    /// The plane through the centroid of `points` with their Newell normal (summed as
    /// the fan `(p_i - p_0) x (p_(i+1) - p_0)`, as [`Mesh::face_normal`] does, but in f64).
    pub fn through(points: impl Iterator<Item = [f64; 3]>, tolerance_sq: f64) -> Self {
        let mut corners = points;
        let Some(origin) = corners.next() else {
            return Self {
                n: [0.0; 3],
                d: 0.0,
                limit: 0.0,
            };
        };
        let mut n = [0.0f64; 3];
        let mut sum = [0.0f64; 3];
        let mut count = 1.0f64;
        let mut previous: Option<[f64; 3]> = None;
        for p in corners {
            let e = sub(p, origin);
            if let Some(q) = previous {
                n = add(n, cross(q, e));
            }
            sum = add(sum, e);
            count += 1.0;
            previous = Some(e);
        }
        let centroid = add(origin, sum.map(|c| c / count));
        let nn = dot(n, n);
        Self {
            n,
            d: -dot(n, centroid),
            limit: tolerance_sq * nn,
        }
    }

    /// The plane of a work record: that of its surface (see [`Record::fan`]): the
    /// whole source face's (Newell normal, through the centroid), planar or not, or
    /// the plane of its fan triangle.
    pub fn of_record(mesh: &Mesh<'_>, word: u32, tolerance_sq: f64) -> Self {
        let corners = mesh.face(Record::face(word));
        let vertices = mesh.vertices();
        let position = move |i: &u32| vertices.get(*i as usize).map(|p| p.map(f64::from));
        match Record::fan(word) {
            0 => Self::through(corners.iter().filter_map(position), tolerance_sq),
            k => {
                let triangle = [Some(0), Some(k), k.checked_add(1)];
                let corner = move |at: Option<usize>| corners.get(at?).and_then(position);
                Self::through(triangle.into_iter().filter_map(corner), tolerance_sq)
            }
        }
    }

    /// Is point `p` on this plane within the tolerance?
    fn holds(&self, p: [f32; 3]) -> bool {
        self.side_of(self.distance(p), p) == Side::On
    }

    /// Is the normal zero (a face of no area, which cannot split space)?
    pub fn is_degenerate(&self) -> bool {
        dot(self.n, self.n).partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater)
    }

    /// Signed distance times `|n|`.
    pub fn distance(&self, p: [f32; 3]) -> f64 {
        dot(self.n, p.map(f64::from)) + self.d
    }

    /// Side of point `p` at distance `s` from [`Plane::distance`].
    pub fn side_of(&self, s: f64, p: [f32; 3]) -> Side {
        let m = p.iter().fold(0.0f64, |m, &c| m.max(f64::from(c).abs()));
        if s * s <= self.limit * m * m {
            Side::On
        } else if s > 0.0 {
            Side::Front
        } else {
            Side::Back
        }
    }

    /// The plane as `[n.x, n.y, n.z, d]`.
    pub fn coefficients(&self) -> [f64; 4] {
        [self.n[0], self.n[1], self.n[2], self.d]
    }
}

/// How the vertices of one polygon fall around a plane.
///
/// The tolerant counts (`front`, `back`, `on`) decide the polygon's [`Fate`]; a
/// polygon that must be cut is cut by the exact signs of the distances
/// (`positive`, `negative`, `zero`, `crossings`, `runs`), so that its pieces tile
/// it: a vertex within tolerance but off the plane goes to its own side, and a
/// vertex exactly on the plane to the front and to the back pieces it bounds. (Cutting by
/// tolerant sides would put every vertex
/// of a band to both halves; when the plane is nearly parallel to the polygon, the
/// band holds vertices off the cut line and the halves overlap.)
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct Tally {
    pub front: usize,
    pub back: usize,
    pub on: usize,
    pub positive: usize,
    pub negative: usize,
    pub zero: usize,
    /// Edges going from a positive to a negative distance or back (each makes a
    /// split point).
    pub crossings: usize,
    /// Stretches of consecutive vertices at negative distances (each becomes one
    /// back piece of a cut).
    pub runs: usize,
}

/// What happens to a polygon at a node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Fate {
    /// It lies in the node's plane (or it is the splitter itself).
    Node,
    Front,
    Back,
    /// It is cut: the vertex counts of the front piece and of the back pieces (all
    /// together), the number of back pieces and the new split points.
    Split {
        front: usize,
        back: usize,
        pieces: usize,
        new: usize,
    },
}

/// The exact side of a distance, for cutting: `On` only when exactly zero.
pub(super) fn exact_side(s: f64) -> Side {
    if s > 0.0 {
        Side::Front
    } else if s < 0.0 {
        Side::Back
    } else {
        Side::On
    }
}

impl Tally {
    /// Classifies the polygon `idx` (indices into `vertices`) against `plane`.
    pub fn of(plane: &Plane, idx: &[u32], vertices: &[[f32; 3]]) -> Self {
        let distance = |i: u32| plane.distance(vertex(vertices, i));
        let mut tally = Self::default();
        let mut previous = idx.last().map(|&i| exact_side(distance(i)));
        for &i in idx {
            let s = distance(i);
            match plane.side_of(s, vertex(vertices, i)) {
                Side::Front => tally.front += 1,
                Side::Back => tally.back += 1,
                Side::On => tally.on += 1,
            }
            let exact = exact_side(s);
            match exact {
                Side::Front => tally.positive += 1,
                Side::Back => tally.negative += 1,
                Side::On => tally.zero += 1,
            }
            if matches!(
                (previous, exact),
                (Some(Side::Front), Side::Back) | (Some(Side::Back), Side::Front)
            ) {
                tally.crossings += 1;
            }
            if exact == Side::Back && previous != Some(Side::Back) {
                tally.runs += 1;
            }
            previous = Some(exact);
        }
        tally
    }

    /// The polygon's fate; a fragment of the splitter's face always stays in its node.
    pub fn fate(&self, of_splitter: bool) -> Fate {
        if of_splitter || (self.front == 0 && self.back == 0) {
            Fate::Node
        } else if self.back == 0 {
            Fate::Front
        } else if self.front == 0 {
            Fate::Back
        } else {
            Fate::Split {
                front: self.positive + self.zero + self.crossings,
                back: self.negative + 2 * self.runs,
                pieces: self.runs,
                new: self.crossings,
            }
        }
    }
}

/// A vertex position; the origin for an index out of range (the build only makes
/// valid indices, so this is never used, but it keeps every access panic-free).
pub(super) fn vertex(vertices: &[[f32; 3]], i: u32) -> [f32; 3] {
    vertices.get(i as usize).copied().unwrap_or([0.0; 3])
}

/// The point where edge `a`-`b` meets the plane, from the signed distances `sa`,
/// `sb` of opposite signs. The endpoints are taken in index order, so the two faces
/// sharing an edge get bit-identical split points from the same plane.
pub(super) fn split_point(vertices: &[[f32; 3]], a: u32, sa: f64, b: u32, sb: f64) -> [f32; 3] {
    let ((p, sp), (q, sq)) = if a <= b {
        ((a, sa), (b, sb))
    } else {
        ((b, sb), (a, sa))
    };
    let p = vertex(vertices, p).map(f64::from);
    let q = vertex(vertices, q).map(f64::from);
    let denominator = sp - sq;
    let t = if denominator == 0.0 {
        0.5
    } else {
        (sp / denominator).clamp(0.0, 1.0)
    };
    // f64 to the nearest f32: the stored split point.
    let [px, py, pz] = p;
    let [qx, qy, qz] = q;
    [px + t * (qx - px), py + t * (qy - py), pz + t * (qz - pz)].map(|c| c as f32)
}

/// Does face `face` enter the tree as its fan triangles `(v0, vk, vk+1)` rather than
/// whole? Yes when it has four or more corners, is not planar within the tolerance,
/// and is strictly convex in its own Newell plane: every turn and every fan triangle
/// winds the way of its normal.
///
/// Why: [conventions](crate::conventions) gives a non-planar face the depth of the fan
/// triangle a ray
/// meets. Ordered as one plane, such a face misranks against a face that passes
/// through its bulge (suzanne's quads); its fan triangles are planes and order
/// exactly. The convexity keeps the coverage: the fan then tiles the polygon in its
/// own plane and in every view that does not fold it (seen nearly edge-on, where one
/// fan triangle turns its back while the face does not, the projected triangles
/// overlap and cover that overlap where the polygon's parity does not). A face that
/// is not convex keeps its polygon's coverage whole, and its plane's order.
pub(super) fn fans(mesh: &Mesh<'_>, face: usize, tolerance_sq: f64) -> bool {
    let corners = mesh.face(face);
    let vertices = mesh.vertices();
    let at = |i: u32| vertex(vertices, i);
    if corners.len() < 4 || corners.len() > usize::from(u16::MAX) {
        return false;
    }
    if is_planar(mesh, face) {
        return false;
    }
    let whole = Plane::of_record(mesh, face as u32, tolerance_sq);
    let p = |k: usize| corners.get(k).map_or([0.0; 3], |&i| at(i).map(f64::from));
    let n = corners.len();
    let winds =
        |a: [f64; 3], b: [f64; 3], c: [f64; 3]| dot(cross(sub(b, a), sub(c, b)), whole.n) > 0.0;
    let turns = (0..n).all(|k| winds(p(k), p((k + 1) % n), p((k + 2) % n)));
    let fan = (1..n - 1).all(|k| winds(p(0), p(k), p(k + 1)));
    turns && fan
}

/// The fan triangles `(v0, vk, vk+1)` of `face` (its `corners`), each with its record
/// word ([`Record::of_fan`]): the surfaces a face that [`fans`] enters an order as.
pub(super) fn fan_triangles(
    face: usize,
    corners: &[u32],
) -> impl Iterator<Item = (u32, [u32; 3])> + '_ {
    let v0 = corners.first().copied().unwrap_or(0);
    let rest = corners.get(1..).unwrap_or(&[]);
    rest.windows(2)
        .enumerate()
        .filter_map(move |(k, pair)| match *pair {
            [a, b] => Some((Record::of_fan(face, k + 1), [v0, a, b])),
            _ => None,
        })
}

/// Is face `face` planar as the tree sees it (every corner on its Newell plane
/// within [`PLANE_TOLERANCE`](super::PLANE_TOLERANCE), or a zero normal)? Only the
/// fragments of a face that is not can overlap on screen (see [`fans`]).
pub(crate) fn is_planar(mesh: &Mesh<'_>, face: usize) -> bool {
    mesh.kept_planarity(face)
        .unwrap_or_else(|| test_planar(mesh, face))
}

/// Which faces of `mesh` are planar, as every renderer and the BSP build judge them
/// (each corner within [`PLANE_TOLERANCE`](super::PLANE_TOLERANCE) of the face's
/// Newell plane, in `f64`), into `bits` for
/// [`Mesh::with_planar_faces`]: bit `f % 32` of word `f / 32` set for a planar face.
/// Returns the words written, [`planar_words`]`(mesh.face_count())`;
/// [`Error::CapacityExceeded`] with that many when `bits` is shorter. Once per mesh:
/// the test is the same in every view.
pub fn planar_faces(mesh: &Mesh<'_>, bits: &mut [u32]) -> Result<usize, Error> {
    let needed = planar_words(mesh.face_count());
    let Some(words) = bits.get_mut(..needed) else {
        return Err(Error::CapacityExceeded {
            what: Capacity::FaceBits,
            needed,
            capacity: bits.len(),
        });
    };
    words.fill(0);
    for face in 0..mesh.face_count() {
        set_bit(words, face, test_planar(mesh, face));
    }
    Ok(needed)
}

/// [`is_planar`]'s test, made afresh.
fn test_planar(mesh: &Mesh<'_>, face: usize) -> bool {
    let tolerance = super::PLANE_TOLERANCE;
    let whole = Plane::of_record(mesh, face as u32, tolerance * tolerance);
    let vertices = mesh.vertices();
    whole.is_degenerate()
        || mesh
            .face(face)
            .iter()
            .all(|&i| whole.holds(vertex(vertices, i)))
}

/// Work-stack records: `[word, len, idx_0 .. idx_len-1]`, where `word` holds the
/// source face in its low 16 bits and the fan triangle in its high 16 bits (see
/// [`Record::fan`]).
pub(super) struct Record;

impl Record {
    /// Words besides the vertex indices.
    pub const HEAD: usize = 2;

    pub fn face(word: u32) -> usize {
        (word & 0xFFFF) as usize
    }

    /// 0 for a record of a whole face (or its pieces); `k` for the fan triangle
    /// `(v0, vk, vk+1)` of a face that is not planar (see [`fans`]). The whole word
    /// names the planar surface a record lies on: records of one surface share a node.
    pub fn fan(word: u32) -> usize {
        (word >> 16) as usize
    }

    /// The word of fan triangle `k` of `face`.
    pub fn of_fan(face: usize, k: usize) -> u32 {
        ((k as u32) << 16) | (face as u32 & 0xFFFF)
    }
}

/// Iterates the records of a set: `(word, indices)`; stops at a malformed tail.
#[derive(Debug, Clone)]
pub(super) struct Records<'a> {
    rest: &'a [u32],
}

impl<'a> Records<'a> {
    pub fn new(words: &'a [u32]) -> Self {
        Self { rest: words }
    }
}

impl<'a> Iterator for Records<'a> {
    type Item = (u32, &'a [u32]);

    fn next(&mut self) -> Option<Self::Item> {
        let (&word, rest) = self.rest.split_first()?;
        let (&len, rest) = rest.split_first()?;
        let idx = rest.get(..len as usize)?;
        self.rest = rest.get(len as usize..)?;
        Some((word, idx))
    }
}
