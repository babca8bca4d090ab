//! The active edge list of the code-fill engine: the edges of every active face,
//! kept in order of their crossing on the current row.
//!
//! Records stay in place (a slot each); only a list of `u32` keys (crossing << 16 |
//! slot) is sorted, so that sorting compares and moves plain words; edges added on a
//! row are sorted apart and merged once, and the per-row insertion sort moves only
//! the few edges whose order changed.

use heapless::Vec;

use crate::scan::edge::Edge;

/// One edge of an active face.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ActiveEdge {
    pub edge: Edge,
    /// The crossing on the current row, clamped to `[0, width]`; before the edge's
    /// first row, the crossing there (the place it will take).
    pub x: u16,
    /// Index of its face in the active face table.
    pub face: u16,
    /// Scratch flag of the row's sweep.
    pub mark: bool,
}

/// A slot no edge has taken since the list was made: all zero (see [`Edge::UNSET`]);
/// `insert` writes a slot whole before it is read.
const UNUSED: ActiveEdge = ActiveEdge {
    edge: Edge::UNSET,
    x: 0,
    face: 0,
    mark: false,
};

/// Room for `N` active edges.
#[derive(Debug)]
pub(crate) struct ActiveEdges<const N: usize> {
    slots: [ActiveEdge; N],
    /// Slots never used since `clear`, from `fresh` on; released slots in `free`.
    fresh: usize,
    free: Vec<u16, N>,
    /// Keys `x << 16 | slot` of the slots in use, by crossing: the first `sorted`
    /// in order, the rest added since.
    by_x: Vec<u32, N>,
    sorted: usize,
}

/// The sort key of an edge crossing at `x` held in `slot`.
fn key(x: u16, slot: u16) -> u32 {
    u32::from(x) << 16 | u32::from(slot)
}

/// The slot of a key.
fn slot(key: u32) -> usize {
    (key & 0xFFFF) as usize
}

/// Edges added on one row that are merged into the order (more are sorted in).
const MERGE: usize = 64;

/// Insertion sort of keys.
// Indexing: 1 <= k < len and 1 <= j <= k, so k, j and j - 1 are in bounds.
#[allow(clippy::indexing_slicing)]
fn insertion_sort(keys: &mut [u32]) {
    for k in 1..keys.len() {
        let moving = keys[k];
        let mut j = k;
        while j > 0 && keys[j - 1] > moving {
            keys[j] = keys[j - 1];
            j -= 1;
        }
        keys[j] = moving;
    }
}

impl<const N: usize> ActiveEdges<N> {
    /// No edges.
    pub const fn new() -> Self {
        Self {
            slots: [UNUSED; N],
            fresh: 0,
            free: Vec::new(),
            by_x: Vec::new(),
            sorted: 0,
        }
    }

    /// Forgets every edge.
    pub fn clear(&mut self) {
        self.fresh = 0;
        self.free.clear();
        self.by_x.clear();
        self.sorted = 0;
    }

    /// Edges held.
    pub fn len(&self) -> usize {
        self.by_x.len()
    }

    /// The `k`-th edge by crossing.
    pub fn get(&self, k: usize) -> Option<&ActiveEdge> {
        self.by_x.get(k).and_then(|&i| self.slots.get(slot(i)))
    }

    /// The `k`-th edge by crossing, to change.
    pub fn get_mut(&mut self, k: usize) -> Option<&mut ActiveEdge> {
        self.by_x.get(k).and_then(|&i| self.slots.get_mut(slot(i)))
    }

    /// Adds `edge` of face `face` (DDA at its first row); it takes its place at the
    /// next `move_to_row`. `Err` when full.
    pub fn insert(&mut self, edge: Edge, face: u16, s: u32, width: u16) -> Result<(), ()> {
        let slot = match self.free.pop() {
            Some(slot) => slot,
            None if self.fresh < N => {
                self.fresh += 1;
                (self.fresh - 1) as u16
            }
            None => return Err(()),
        };
        let x = edge.crossing(s).clamp(0, i32::from(width)) as u16;
        if let Some(record) = self.slots.get_mut(usize::from(slot)) {
            *record = ActiveEdge {
                edge,
                x,
                face,
                mark: false,
            };
        }
        // Merged into the order once per row, by `move_to_row`.
        self.by_x.push(key(x, slot)).map_err(|_| ())
    }

    /// Moves the crossings to row `y` (edges that have begun) and restores the
    /// order: an insertion sort, since the order changes little between rows.
    // Indexing: old <= len; tail.len() <= MERGE; the merge writes w < len and reads
    // i - 1 < old and j - 1 < added.len() only when i > 0 and j > 0.
    #[allow(clippy::indexing_slicing)]
    pub fn move_to_row(&mut self, y: i32, s: u32, width: u16) {
        self.set_row(y, s, width);
        let len = self.by_x.len();
        let old = self.sorted.min(len);
        // The edges held before: nearly in order, an insertion sort.
        insertion_sort(&mut self.by_x[..old]);
        // The edges added since, sorted apart and merged from the back: each edge
        // held moves once, not once per edge added.
        let mut added = [0u32; MERGE];
        match self.by_x.get(old..).filter(|tail| tail.len() <= MERGE) {
            Some(tail) => {
                let added = &mut added[..tail.len()];
                added.copy_from_slice(tail);
                insertion_sort(added);
                let (mut i, mut j) = (old, added.len());
                for w in (0..len).rev() {
                    if j == 0 {
                        break;
                    }
                    if i > 0 && self.by_x[i - 1] > added[j - 1] {
                        self.by_x[w] = self.by_x[i - 1];
                        i -= 1;
                    } else {
                        self.by_x[w] = added[j - 1];
                        j -= 1;
                    }
                }
            }
            None => insertion_sort(&mut self.by_x),
        }
        self.sorted = len;
    }

    /// Moves the crossings to row `y` without restoring their order (for a
    /// representation that needs none).
    pub fn set_row(&mut self, y: i32, s: u32, width: u16) {
        for held in self.by_x.iter_mut() {
            let i = slot(*held);
            if let Some(e) = self.slots.get_mut(i) {
                if e.edge.first <= y {
                    e.x = e.edge.crossing(s).clamp(0, i32::from(width)) as u16;
                    *held = key(e.x, i as u16);
                }
            }
        }
    }

    /// Steps the edges that have begun past row `next - 1` and drops those that end
    /// there.
    // Indexing: k < len and kept <= k.
    #[allow(clippy::indexing_slicing)]
    pub fn step(&mut self, next: i32) {
        // Compacted in place (a library `retain` copies element by element through
        // a call on a Cortex-M4).
        let mut kept = 0;
        for k in 0..self.by_x.len() {
            let i = self.by_x[k];
            let Some(e) = self.slots.get_mut(slot(i)) else {
                continue;
            };
            if e.edge.end <= next {
                let _ = self.free.push(slot(i) as u16);
                continue;
            }
            if e.edge.first < next {
                e.edge.step();
            }
            self.by_x[kept] = i;
            kept += 1;
        }
        self.by_x.truncate(kept);
        self.sorted = kept;
    }
}
