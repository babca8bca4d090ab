//! Planes, vertex classification and the work-stack records of the BSP build (f64).

use crate::mesh::Mesh;

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

    /// The plane of a work record: that of its whole source face (Newell normal,
    /// through the centroid), planar or not.
    pub fn of_record(mesh: &Mesh<'_>, word: u32, tolerance_sq: f64) -> Self {
        let corners = mesh.face(Record::face(word));
        let vertices = mesh.vertices();
        let position = move |i: &u32| vertices.get(*i as usize).map(|p| p.map(f64::from));
        Self::through(corners.iter().filter_map(position), tolerance_sq)
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
/// vertex exactly on the plane to the front and to the back pieces it bounds. (Cutting by tolerant sides would put every vertex
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

/// Work-stack records: `[word, len, idx_0 .. idx_len-1]`, where `word` holds the
/// source face in its low 16 bits.
pub(super) struct Record;

impl Record {
    /// Words besides the vertex indices.
    pub const HEAD: usize = 2;

    pub fn face(word: u32) -> usize {
        (word & 0xFFFF) as usize
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

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(super) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
