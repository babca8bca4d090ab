//! Cutting a polygon by a node's plane into the two child sets.

use super::output::Output;
use crate::order::plane::{exact_side, split_point, vertex, Plane, Side};
use crate::Error;

/// Appends words to a child set's area (its size was counted in pass 1).
pub(super) struct Writer<'a> {
    area: &'a mut [u32],
    at: usize,
}

impl<'a> Writer<'a> {
    pub(super) fn new(area: &'a mut [u32]) -> Self {
        Self { area, at: 0 }
    }

    pub(super) fn put(&mut self, value: u32) {
        if let Some(w) = self.area.get_mut(self.at) {
            *w = value;
        }
        self.at += 1;
    }

    pub(super) fn record(&mut self, word: u32, idx: &[u32]) {
        self.put(word);
        self.put(idx.len() as u32);
        idx.iter().for_each(|&i| self.put(i));
    }

    /// Starts a record whose length is filled in by [`Writer::end`].
    pub(super) fn begin(&mut self, word: u32) -> usize {
        self.put(word);
        let at = self.at;
        self.put(0);
        at
    }

    pub(super) fn end(&mut self, len_at: usize) {
        let len = self.at.saturating_sub(len_at + 1);
        if let Some(w) = self.area.get_mut(len_at) {
            *w = len as u32;
        }
    }
}

/// Cuts polygon `idx` by the exact signs of the distances (see
/// [`Tally`](crate::order::plane::Tally)): each edge
/// crossing the plane makes one split point. The front is one polygon
/// (Sutherland-Hodgman: the vertices in front or exactly on the plane and the split
/// points, in order); the back is one piece per stretch of vertices behind the plane,
/// from the point where the boundary enters the back (a split point, or a vertex
/// exactly on the plane) to where it leaves, closed by the chord that the front
/// polygon bridges the other way. So the pieces' boundaries add up to the polygon's
/// (the chords cancel) even when it crosses the plane more than twice and is not
/// planar, where Sutherland-Hodgman's two sets of bridges would not be the same
/// segments. All pieces keep the polygon's winding; `new` split points are made.
pub(super) fn split(
    out: &mut Output<'_>,
    plane: &Plane,
    word: u32,
    idx: &[u32],
    new: usize,
    front: &mut Writer<'_>,
    back: &mut Writer<'_>,
) -> Result<(), Error> {
    let len = idx.len();
    let at = |k: usize| idx.get(k % len.max(1)).copied().unwrap_or(0);
    let side = |out: &Output<'_>, k: usize| exact_side(plane.distance(vertex(out.vertices, at(k))));
    let crosses = |out: &Output<'_>, k: usize| {
        matches!(
            (side(out, k), side(out, k + 1)),
            (Side::Front, Side::Back) | (Side::Back, Side::Front)
        )
    };
    // The front, making the split points: the j-th crossing edge (from edge 0) makes
    // vertex `first + j`.
    let first = out.vertex_count;
    let f_len = front.begin(word);
    let mut made = 0usize;
    for k in 0..len {
        let (a, b) = (at(k), at(k + 1));
        if side(out, k) != Side::Back {
            front.put(a);
        }
        if crosses(out, k) {
            let (sa, sb) = (
                plane.distance(vertex(out.vertices, a)),
                plane.distance(vertex(out.vertices, b)),
            );
            let p = split_point(out.vertices, a, sa, b, sb);
            let root = out.seams().root(a, b);
            let x = out.push_vertex(p, root, new.saturating_sub(made + 1))?;
            made += 1;
            front.put(x);
        }
    }
    front.end(f_len);
    // The back pieces, walking from the start of a back stretch.
    let made = made.max(1);
    let split_vertex = |ordinal: usize| {
        // Vertex indices fit u32 (push_vertex checked).
        first.saturating_add(ordinal % made) as u32
    };
    let start = (0..len)
        .find(|&k| side(out, k) == Side::Back && side(out, k + len - 1) != Side::Back)
        .unwrap_or(0);
    let mut ordinal = (0..start).filter(|&k| crosses(out, k)).count();
    let mut piece = None;
    for k in start..start + len {
        if side(out, k) == Side::Back {
            let before = k + len - 1;
            if side(out, before) != Side::Back {
                piece = Some(back.begin(word));
                if side(out, before) == Side::On {
                    back.put(at(before));
                } else {
                    back.put(split_vertex(ordinal + made - 1));
                }
            }
            back.put(at(k));
            if side(out, k + 1) != Side::Back {
                if side(out, k + 1) == Side::On {
                    back.put(at(k + 1));
                } else {
                    back.put(split_vertex(ordinal));
                }
                if let Some(len_at) = piece.take() {
                    back.end(len_at);
                }
            }
        }
        if crosses(out, k) {
            ordinal += 1;
        }
    }
    Ok(())
}
