//! Watertight fragments: the root segment of every split point, and the T-vertex
//! insertion that ends the build.
//!
//! A split point lies on one fragment edge, but the fragments on the other side of
//! that edge (of the neighbouring face, or of the same face in another subtree) still
//! have the straight edge: rounded to f32 and snapped to the sub-pixel grid, the point
//! is not exactly on that line, and a pixel centre in the sliver between the two
//! would be covered by neither fragment. So every split point records its *root
//! segment*: the original mesh edge or the cut chord it lies on, as a pair of vertex
//! indices compared by position bits (welded, [conventions](crate::conventions)). At the end, every
//! fragment edge gets, in order, every split point of its root segment that lies
//! strictly between its ends; both sides of an edge then have the same vertex
//! sequence.

use super::plane::vertex;
use crate::error::need;
use crate::sort::sort_by_key;
use crate::Capacity;
use crate::Error;

/// The split points' root segments and the vertices they index.
pub(super) struct Seams<'a> {
    /// All vertices: the mesh's, then the split points.
    pub vertices: &'a [[f32; 3]],
    /// The number of mesh vertices: split point `x` has its root at `x - base`.
    pub base: usize,
    /// `roots[x - base]`: the root segment of split point `x`, ends ordered by
    /// position bits.
    pub roots: &'a [[u32; 2]],
}

/// Where a point lies along a root segment: its start, a point strictly inside
/// (parameter, position bits), or its end. Ordered along the segment; equal keys are
/// bit-identical points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Key {
    Start,
    At(u64, [u32; 3]),
    End,
}

/// An f64 as a u64 of the same order (for finite values; -0.0 below 0.0).
fn ordered(t: f64) -> u64 {
    let b = t.to_bits();
    if b >> 63 == 1 {
        !b
    } else {
        b | (1 << 63)
    }
}

impl Seams<'_> {
    /// Position bits: bit-identical positions are one vertex (welding).
    pub fn bits(&self, v: u32) -> [u32; 3] {
        crate::mesh::weld_bits(&vertex(self.vertices, v))
    }

    fn same(&self, a: u32, b: u32) -> bool {
        self.bits(a) == self.bits(b)
    }

    /// The stored root of split point `v`; `None` for a mesh vertex.
    pub fn root_of(&self, v: u32) -> Option<[u32; 2]> {
        (v as usize)
            .checked_sub(self.base)
            .and_then(|k| self.roots.get(k))
            .copied()
    }

    /// `[a, b]` ordered by position bits (then index).
    fn ordered_pair(&self, a: u32, b: u32) -> [u32; 2] {
        if (self.bits(a), a) <= (self.bits(b), b) {
            [a, b]
        } else {
            [b, a]
        }
    }

    fn same_segment(&self, r: [u32; 2], s: [u32; 2]) -> bool {
        self.same(r[0], s[0]) && self.same(r[1], s[1])
    }

    fn is_end(&self, v: u32, r: [u32; 2]) -> bool {
        self.same(v, r[0]) || self.same(v, r[1])
    }

    /// The root segment of fragment edge `a`-`b` (either direction gives the same):
    /// the root of its split points when both lie on one, or when one is a split
    /// point and the other an end of its root; else the edge itself (a mesh edge,
    /// or a chord made by a cut).
    pub fn root(&self, a: u32, b: u32) -> [u32; 2] {
        let [a, b] = self.ordered_pair(a, b);
        let (ra, rb) = (self.root_of(a), self.root_of(b));
        if let (Some(ra), Some(rb)) = (ra, rb) {
            if self.same_segment(ra, rb) {
                return ra;
            }
        }
        if let Some(rb) = rb.filter(|&rb| self.is_end(a, rb)) {
            return rb;
        }
        if let Some(ra) = ra.filter(|&ra| self.is_end(b, ra)) {
            return ra;
        }
        [a, b]
    }

    /// Where `v` (a point of segment `r`) lies along it.
    pub fn key(&self, v: u32, r: [u32; 2]) -> Key {
        if self.same(v, r[0]) {
            return Key::Start;
        }
        if self.same(v, r[1]) {
            return Key::End;
        }
        let [p, q, x] = [r[0], r[1], v].map(|i| vertex(self.vertices, i).map(f64::from));
        let t = x
            .iter()
            .zip(&p)
            .zip(&q)
            .fold(0.0, |t, ((x, p), q)| t + (x - p) * (q - p));
        Key::At(ordered(t), self.bits(v))
    }

    /// The position bits of a segment's ends: segments with equal ones are one.
    fn segment_bits(&self, r: [u32; 2]) -> [[u32; 3]; 2] {
        r.map(|v| self.bits(v))
    }

    /// The sort key of split point `x`: its root, then its place along it, then its id.
    fn sort_key(&self, x: u32) -> ([[u32; 3]; 2], Key, u32) {
        let r = self.root_of(x).unwrap_or([x, x]);
        (self.segment_bits(r), self.key(x, r), x)
    }

    /// Sorts the split points `list` by root segment, then along it.
    pub fn sort(&self, list: &mut [u32]) {
        sort_by_key(list, |&x| self.sort_key(x));
    }

    /// The split points of `sorted` (from [`Seams::sort`]) strictly between the ends of
    /// edge `a`-`b` on its root segment, as a range of `sorted`, and whether they
    /// run from `a` to `b` in `sorted` order (else backwards).
    pub fn between(&self, sorted: &[u32], a: u32, b: u32) -> (core::ops::Range<usize>, bool) {
        let r = self.root(a, b);
        let (ka, kb) = (self.key(a, r), self.key(b, r));
        let (lo, hi) = if ka <= kb { (ka, kb) } else { (kb, ka) };
        let bits = self.segment_bits(r);
        let start = sorted.partition_point(|&x| {
            let (s, k, _) = self.sort_key(x);
            s < bits || (s == bits && k <= lo)
        });
        let end = sorted.partition_point(|&x| {
            let (s, k, _) = self.sort_key(x);
            s < bits || (s == bits && k < hi)
        });
        (start..end.max(start), ka <= kb)
    }
}

/// Makes fragments watertight (see [`Seams`]): inserts into every fragment edge the
/// split points of its root segment that lie strictly between its ends, in order.
///
/// `seams.vertices` are all vertices in use (the mesh's, then the split points from
/// `seams.base` on); the fragments are `offsets[..=fragments]` over
/// `indices[..index_count]` (CSR). Sorts the split points in `work` and rewrites the
/// CSR arrays in place, back to front. Returns the new index count and the `work`
/// words used. [`Error::CapacityExceeded`] when `work` cannot hold the split points
/// or `indices` the inserted ones (exact need).
pub(super) fn insert_seam_vertices(
    seams: Seams<'_>,
    indices: &mut [u32],
    index_count: usize,
    offsets: &mut [u32],
    fragments: usize,
    work: &mut [u32],
) -> Result<(usize, usize), Error> {
    let splits = seams.vertices.len().saturating_sub(seams.base);
    let capacity = work.len();
    let sorted = work.get_mut(..splits).ok_or(Error::CapacityExceeded {
        what: Capacity::OrderWork,
        needed: splits,
        capacity,
    })?;
    for (k, s) in sorted.iter_mut().enumerate() {
        // Vertex indices fit u32 (the split points were numbered by u32).
        *s = seams.base.saturating_add(k) as u32;
    }
    let seams = Seams {
        roots: seams.roots.get(..splits).unwrap_or(seams.roots),
        ..seams
    };
    seams.sort(sorted);
    let sorted: &[u32] = sorted;
    let broken = Error::CapacityExceeded {
        what: Capacity::FragmentIndices,
        needed: index_count,
        capacity: indices.len(),
    };
    let range = |offsets: &[u32], f: usize| -> Result<(usize, usize), Error> {
        match (offsets.get(f), offsets.get(f.saturating_add(1))) {
            (Some(&s), Some(&e)) if s <= e => Ok((s as usize, e as usize)),
            _ => Err(broken),
        }
    };
    let extra = |idx: &[u32]| -> usize {
        idx.iter()
            .enumerate()
            .map(|(k, &a)| {
                let b = idx.get(k + 1).or(idx.first()).copied().unwrap_or(a);
                seams.between(sorted, a, b).0.len()
            })
            .sum()
    };
    let mut added = 0usize;
    for f in 0..fragments {
        let (s, e) = range(offsets, f)?;
        added = added.saturating_add(extra(indices.get(s..e).ok_or(broken)?));
    }
    let total = index_count.saturating_add(added);
    need(Capacity::FragmentIndices, total, indices.len())?;
    u32::try_from(total).map_err(|_| Error::CapacityExceeded {
        what: Capacity::Index32,
        needed: total,
        capacity: u32::MAX as usize,
    })?;
    // Back to front: a fragment's new place starts at or after its old one, and
    // within it each vertex moves up, so nothing is overwritten before it is read.
    let mut end = total;
    for f in (0..fragments).rev() {
        let (s, e) = range(offsets, f)?;
        let len = e - s;
        let grow = extra(indices.get(s..e).ok_or(broken)?);
        let start = end
            .checked_sub(len.saturating_add(grow))
            .filter(|&start| start >= s)
            .ok_or(broken)?;
        let mut next = indices.get(s).copied().ok_or(broken)?;
        let mut at = end;
        for k in (s..e).rev() {
            let a = indices.get(k).copied().ok_or(broken)?;
            let (between, forward) = seams.between(sorted, a, next);
            let points = sorted.get(between).unwrap_or(&[]);
            // Written back to front: the points nearest `next` first.
            if forward {
                points.iter().rev().for_each(|&x| put(indices, &mut at, x));
            } else {
                points.iter().for_each(|&x| put(indices, &mut at, x));
            }
            put(indices, &mut at, a);
            next = a;
        }
        if at != start {
            // Unreachable: `extra` counted these very points.
            return Err(broken);
        }
        if let Some(o) = offsets.get_mut(f + 1) {
            *o = end as u32;
        }
        end = at;
    }
    Ok((total, splits))
}

/// Writes `value` just below `at` and moves `at` down.
fn put(indices: &mut [u32], at: &mut usize, value: u32) {
    *at = at.saturating_sub(1);
    if let Some(w) = indices.get_mut(*at) {
        *w = value;
    }
}
