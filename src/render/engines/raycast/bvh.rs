//! The bounding-volume hierarchy over the drawn faces' pixel-centre boxes, built
//! breadth first in the lent node array once per frame.

use super::{BvhNode, Cast};
use crate::render::need;
use crate::render::transform::ScreenVertex;
use crate::Capacity;
use crate::Error;

/// Most faces in a leaf of the hierarchy.
const LEAF: usize = 4;

/// The pixel centres inside the bounding box of `poly`, clamped to a `w` x `h`
/// frame: (x0, y0, x1, y1) inclusive, `None` when it holds none. Centre i is at
/// `(2i + 1) 2^s` half sub-pixel units; a polygon never covers a centre outside its
/// closed box.
pub(super) fn centre_box(poly: &[ScreenVertex], s: u32, w: u16, h: u16) -> Option<[u16; 4]> {
    let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
    for v in poly {
        x0 = x0.min(i64::from(v.x));
        y0 = y0.min(i64::from(v.y));
        x1 = x1.max(i64::from(v.x));
        y1 = y1.max(i64::from(v.y));
    }
    let half = 1i64 << s;
    // First centre at or right of m, last centre at or left of m.
    let lo = |m: i64| ((2 * m + half - 1) >> (s + 1)).max(0);
    let hi = |m: i64, n: u16| ((2 * m - half) >> (s + 1)).min(i64::from(n) - 1);
    let (c0, c1, r0, r1) = (lo(x0), hi(x1, w), lo(y0), hi(y1, h));
    (c0 <= c1 && r0 <= r1).then_some([c0 as u16, r0 as u16, c1 as u16, r1 as u16])
}

impl<const POLY: usize> Cast<'_, POLY> {
    /// Builds the hierarchy over the first `n` face records: breadth first, each
    /// node's faces split at the median of their box centres along the wider axis,
    /// the children appended to the node array (which is the work queue: no stack,
    /// no recursion).
    pub(super) fn build(&mut self, n: usize) -> Result<(), Error> {
        self.node_count = 0;
        if n == 0 {
            return Ok(());
        }
        need(Capacity::BvhNodes, 2 * n - 1, self.nodes.len())?;
        let root = BvhNode {
            count: n as u32,
            ..BvhNode::default()
        };
        if let Some(slot) = self.nodes.get_mut(0) {
            *slot = root;
        }
        let mut next = 1;
        let mut i = 0;
        while i < next {
            let Some(&node) = self.nodes.get(i) else {
                break;
            };
            let (first, count) = (node.index as usize, node.count as usize);
            let Some(faces) = self.faces.get_mut(first..first + count) else {
                break;
            };
            let mut b = BvhNode {
                x0: u16::MAX,
                y0: u16::MAX,
                ..node
            };
            let (mut cx0, mut cy0, mut cx1, mut cy1) = (u32::MAX, u32::MAX, 0, 0);
            for f in faces.iter() {
                b.x0 = b.x0.min(f.x0);
                b.y0 = b.y0.min(f.y0);
                b.x1 = b.x1.max(f.x1);
                b.y1 = b.y1.max(f.y1);
                b.q_max = b.q_max.max(f.plane.max_q());
                let (cx, cy) = (
                    u32::from(f.x0) + u32::from(f.x1),
                    u32::from(f.y0) + u32::from(f.y1),
                );
                cx0 = cx0.min(cx);
                cx1 = cx1.max(cx);
                cy0 = cy0.min(cy);
                cy1 = cy1.max(cy);
            }
            if count > LEAF && next + 2 <= self.nodes.len() {
                let mid = count / 2;
                if cx1 - cx0 >= cy1 - cy0 {
                    faces.select_nth_unstable_by_key(mid, |f| u32::from(f.x0) + u32::from(f.x1));
                } else {
                    faces.select_nth_unstable_by_key(mid, |f| u32::from(f.y0) + u32::from(f.y1));
                }
                let left = BvhNode {
                    index: node.index,
                    count: mid as u32,
                    ..BvhNode::default()
                };
                let right = BvhNode {
                    index: node.index + mid as u32,
                    count: (count - mid) as u32,
                    ..BvhNode::default()
                };
                if let Some([l, r]) = self.nodes.get_mut(next..next + 2) {
                    (*l, *r) = (left, right);
                }
                b.index = next as u32;
                b.count = 0;
                next += 2;
            }
            if let Some(slot) = self.nodes.get_mut(i) {
                *slot = b;
            }
            i += 1;
        }
        self.node_count = next;
        Ok(())
    }
}
