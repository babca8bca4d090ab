//! The active facets of the fast engine: records in slots that stay put while
//! they are active (no copying on removal), visited in the order of their face
//! index, so that a facet drawn later never has a lower face index than one
//! before it in the row: the tie rule then needs one compare a pixel.

use heapless::Vec;

use super::facets::{CornerSource, Facet};
use crate::bits::{padded, vec_bytes};
use crate::Capacity;
use crate::Error;

/// Room for `N` active facets: their slots, the active ones' `face << 16 | slot`
/// in increasing order, and the free slots.
#[derive(Debug)]
pub(super) struct ActiveFacets<const N: usize> {
    slots: Vec<Facet, N>,
    order: Vec<u32, N>,
    free: Vec<u16, N>,
}

impl ActiveFacets<0> {
    /// Bytes of an `ActiveFacets<n>`.
    pub(super) const fn bytes(n: usize) -> usize {
        let fields = vec_bytes::<Facet>(n) + vec_bytes::<u32>(n) + vec_bytes::<u16>(n);
        padded(fields, align_of::<Self>())
    }
}

impl<const N: usize> ActiveFacets<N> {
    /// None active.
    pub const fn new() -> Self {
        Self {
            slots: Vec::new(),
            order: Vec::new(),
            free: Vec::new(),
        }
    }

    /// Forgets every facet.
    /// The slots stay, all free: making a 100-byte placeholder for each new slot
    /// again every frame cost suzanne's frame about 1 %.
    pub fn clear(&mut self) {
        self.order.clear();
        self.free.clear();
        for slot in (0..self.slots.len()).rev() {
            // Room: one entry a slot.
            let _ = self.free.push(slot as u16);
        }
    }

    /// Facets active.
    pub fn len(&self) -> usize {
        self.order.len()
    }

    /// Makes active, in face order, the facet that `build` writes into a free
    /// slot (`false`: there is none). Returns its steepest slope and its slot
    /// (`None` when none was made); `CapacityExceeded` when `N` are active.
    pub fn push_with(
        &mut self,
        build: impl FnOnce(&mut Facet) -> bool,
    ) -> Result<(u16, Option<u16>), Error> {
        let full = Error::CapacityExceeded {
            what: Capacity::ActiveFacets,
            needed: N + 1,
            capacity: N,
        };
        let slot = match self.free.pop() {
            Some(slot) => slot,
            None => {
                self.slots.push(Facet::EMPTY).map_err(|_| full)?;
                (self.slots.len() - 1) as u16
            }
        };
        let Some(facet) = self.slots.get_mut(usize::from(slot)) else {
            return Ok((0, None));
        };
        if !build(facet) {
            // Room: the slot was taken from the free ones or is new.
            let _ = self.free.push(slot);
            return Ok((0, None));
        }
        let (face, slope) = (u32::from(facet.face()), facet.slope());
        let key = face << 16 | u32::from(slot);
        let at = self.order.partition_point(|&k| k < key);
        // Shifted by hand, four words a pass: a few words, where a call to
        // `memmove` costs more.
        let mut carry = key;
        let mut quads = self
            .order
            .get_mut(at..)
            .unwrap_or_default()
            .chunks_exact_mut(4);
        for q in &mut quads {
            if let [k0, k1, k2, k3] = q {
                let next = *k3;
                (*k0, *k1, *k2, *k3) = (carry, *k0, *k1, *k2);
                carry = next;
            }
        }
        for k in quads.into_remainder() {
            core::mem::swap(k, &mut carry);
        }
        self.order.push(carry).map_err(|_| full)?;
        Ok((slope, Some(slot)))
    }

    /// The depth gradient of the facet in `slot` when it belongs to `face` and has
    /// one plane. (A facet that ended in this row's fill keeps its record until
    /// the next row's activations.)
    pub fn gradient(&self, slot: u16, face: u16) -> Option<(i32, i32)> {
        let facet = self.slots.get(usize::from(slot))?;
        if facet.face() != face {
            return None;
        }
        facet.gradient()
    }

    /// The steepest slope of the facet in `slot` (see [`Facet::slope`]).
    pub fn slope(&self, slot: u16) -> u16 {
        self.slots
            .get(usize::from(slot))
            .map_or(u16::MAX, Facet::slope)
    }

    /// Fills row `y` of `row` with every active facet's span(s), in face order,
    /// steps them a row and drops those that end. Returns the spans filled. Out
    /// of line: its loop keeps its values in registers.
    #[inline(never)]
    pub fn fill_row<C: CornerSource>(
        &mut self,
        src: &C,
        y: i32,
        s: u32,
        row: &mut [u32],
    ) -> Result<u32, Error> {
        let (mut spans, mut kept) = (0, 0);
        let Self {
            slots, order, free, ..
        } = self;
        // Slices, so that the loop reads no lengths back from memory.
        let slots = slots.as_mut_slice();
        let keys = order.as_mut_slice();
        for r in 0..keys.len() {
            let Some(&key) = keys.get(r) else {
                break;
            };
            let slot = (key & 0xFFFF) as u16;
            let Some(facet) = slots.get_mut(usize::from(slot)) else {
                break;
            };
            spans += if facet.holds(y) {
                facet.fill_span_row(row)
            } else {
                facet.fill_row_slow(src, y, s, row)?
            };
            if y >= facet.last {
                // Room for every slot: a slot is freed once.
                let _ = free.push(slot);
            } else {
                if let Some(k) = keys.get_mut(kept) {
                    *k = key;
                }
                kept += 1;
            }
        }
        order.truncate(kept);
        Ok(spans)
    }
}
