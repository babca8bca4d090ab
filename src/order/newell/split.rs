//! The cut of one fragment by a plane (as the BSP build cuts): the front piece and
//! the back pieces become new slots, the split points new vertices with their root
//! segments for the seams.

use core::ops::Range;

use super::sort::Sorter;
use crate::order::plane::{exact_side, split_point, vertex, Plane, Side};
use crate::Error;

impl Sorter<'_, '_, '_> {
    /// Cuts fragment `x` by the exact signs of the distances to `plane`, as the BSP
    /// build does: the front is one polygon (Sutherland-Hodgman), the back one piece
    /// per stretch of vertices behind, closed by the chord the front bridges the
    /// other way; all keep `x`'s winding. Returns the new slots.
    pub(super) fn split(&mut self, x: usize, plane: &Plane) -> Result<Range<usize>, Error> {
        let (s, e) = self.range(x);
        let len = e - s;
        let surface = self.surface(x);
        let at = |this: &Self, k: usize| this.indices.get(s + k % len.max(1)).copied().unwrap_or(0);
        let side =
            |this: &Self, k: usize| exact_side(plane.distance(vertex(this.vertices, at(this, k))));
        let crosses = |this: &Self, k: usize| {
            matches!(
                (side(this, k), side(this, k + 1)),
                (Side::Front, Side::Back) | (Side::Back, Side::Front)
            )
        };
        let first_slot = self.slots;
        // The front, making the split points: the j-th crossing edge (from edge 0)
        // makes vertex `first + j`.
        let first = self.vertex_count;
        let mut made = 0usize;
        for k in 0..len {
            let (a, b) = (at(self, k), at(self, k + 1));
            if side(self, k) != Side::Back {
                self.put(a)?;
            }
            if crosses(self, k) {
                let (sa, sb) = (
                    plane.distance(vertex(self.vertices, a)),
                    plane.distance(vertex(self.vertices, b)),
                );
                let p = split_point(self.vertices, a, sa, b, sb);
                let root = self.seams().root(a, b);
                let v = self.push_vertex(p, root)?;
                made += 1;
                self.put(v)?;
            }
        }
        self.new_slot(surface)?;
        // The back pieces, walking from the start of a back stretch.
        let made = made.max(1);
        // Vertex indices fit u32 (push_vertex checked).
        let split_vertex = |ordinal: usize| first.saturating_add(ordinal % made) as u32;
        let start = (0..len)
            .find(|&k| side(self, k) == Side::Back && side(self, k + len - 1) != Side::Back)
            .unwrap_or(0);
        let mut ordinal = (0..start).filter(|&k| crosses(self, k)).count();
        let mut open = false;
        for k in start..start + len {
            if side(self, k) == Side::Back {
                let before = k + len - 1;
                if side(self, before) != Side::Back {
                    open = true;
                    if side(self, before) == Side::On {
                        self.put(at(self, before))?;
                    } else {
                        self.put(split_vertex(ordinal + made - 1))?;
                    }
                }
                self.put(at(self, k))?;
                if side(self, k + 1) != Side::Back {
                    if side(self, k + 1) == Side::On {
                        self.put(at(self, k + 1))?;
                    } else {
                        self.put(split_vertex(ordinal))?;
                    }
                    if open {
                        self.new_slot(surface)?;
                        open = false;
                    }
                }
            }
            if crosses(self, k) {
                ordinal += 1;
            }
        }
        Ok(first_slot..self.slots)
    }
}
