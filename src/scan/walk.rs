//! Walks a polygon row by row and yields each row's edge crossings.
//!
//! Inside the guard band this is the classic scan-line structure: an edge table
//! sorted by first row, an active edge list of indices into it, and a 32-bit DDA per
//! edge. Beyond the guard band each clipped edge is evaluated exactly per row.

use fixed::types::extra::LeEqU32;
use heapless::Vec;

use crate::geometry::Subpixel;
use crate::scan::edge::{Clipped, Edge, EdgeLine, EdgeTable};
use crate::scan::RowRange;
use crate::sort::sort_by_key;
use crate::Capacity;
use crate::{Error, ScreenPoint, Viewport};

/// One edge crossing on a row: pixels from `x` on lie right of it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Crossing {
    /// First pixel right of the crossing, clamped to `[0, width]`.
    pub x: u16,
    /// +1 for a downward edge, -1 for an upward one.
    pub winding: i8,
}

/// Which arithmetic the current polygon uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// Every vertex inside the guard band: edge table and 32-bit DDAs.
    Narrow,
    /// Some vertex beyond it: exact per-row evaluation of the clipped edges.
    Wide(RowRange),
}

/// The working memory to walk one polygon: `N` edges at most.
#[derive(Debug, Clone)]
pub(crate) struct PolygonWalker<const N: usize> {
    table: EdgeTable<N>,
    /// Indices into the table of the edges crossing the current row.
    active: Vec<u16, N>,
    /// The current row's crossings.
    crossings: Vec<Crossing, N>,
    /// Next table entry to activate.
    next: usize,
    /// The row to produce next.
    row: i32,
    mode: Mode,
    viewport: Viewport,
    /// The rows walked: the viewport's, or a band of them.
    window: RowRange,
    s: u32,
}

/// The vertices of a polygon as edges in half-units, closing edge included.
fn edge_lines<Frac: LeEqU32>(points: &[ScreenPoint<Frac>]) -> impl Iterator<Item = EdgeLine> + '_ {
    let half = |p: &ScreenPoint<Frac>| (2 * i64::from(p.x.to_bits()), 2 * i64::from(p.y.to_bits()));
    let closing = points.last().into_iter().chain(points.iter());
    closing
        .zip(points.iter())
        .filter_map(move |(a, b)| EdgeLine::new(half(a), half(b)))
}

impl<const N: usize> PolygonWalker<N> {
    /// Active edges are `u16` indices into the table.
    const VALID: () = assert!(N <= u16::MAX as usize, "at most 65535 edges");

    /// Empty working memory.
    pub const fn new() -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::VALID;
        Self {
            table: EdgeTable::new(),
            active: Vec::new(),
            crossings: Vec::new(),
            next: 0,
            row: 0,
            mode: Mode::Narrow,
            viewport: Viewport {
                width: 0,
                height: 0,
            },
            window: RowRange { first: 0, end: 0 },
            s: 0,
        }
    }

    /// Prepares to walk `points` on rows `window` of `viewport` (the caller keeps the
    /// window inside the viewport). Fails, before anything is drawn, when the polygon
    /// has fewer than 3 vertices or needs more than `N` edges in the window.
    pub fn begin<Frac: LeEqU32>(
        &mut self,
        points: &[ScreenPoint<Frac>],
        viewport: Viewport,
        window: RowRange,
    ) -> Result<(), Error> {
        if points.len() < 3 {
            return Err(Error::TooFewVertices {
                found: points.len(),
            });
        }
        let s = Subpixel::<Frac>::BITS;
        self.s = s;
        self.viewport = viewport;
        self.window = window;
        self.table.edges.clear();
        self.active.clear();
        self.crossings.clear();
        self.next = 0;
        if points.iter().all(ScreenPoint::in_guard_band) {
            self.mode = Mode::Narrow;
            let mut needed = 0;
            for line in edge_lines(points) {
                if let Some(edge) = Edge::new(&line, line.clip(s, viewport, window), s) {
                    needed += 1;
                    // A full table keeps counting, to report the size needed.
                    let _ = self.table.edges.push(edge);
                }
            }
            check_capacity(needed, N)?;
            sort_by_key(&mut self.table.edges, |e| e.first);
            self.row = self.table.edges.first().map_or(0, |e| e.first);
        } else {
            let mut needed = 0;
            let mut rows = RowRange { first: 0, end: 0 };
            for line in edge_lines(points) {
                if let Clipped::Left(r) | Clipped::Rows(r) = line.clip(s, viewport, window) {
                    needed += 1;
                    rows = if rows.first >= rows.end {
                        r
                    } else {
                        RowRange {
                            first: rows.first.min(r.first),
                            end: rows.end.max(r.end),
                        }
                    };
                }
            }
            check_capacity(needed, N)?;
            self.row = rows.first;
            self.mode = Mode::Wide(rows);
        }
        Ok(())
    }

    /// The next row that has crossings, and its crossings, sorted by `x` when
    /// `sorted` (the order of an XOR fill does not matter); `None` when the polygon
    /// is done. `points` must be the slice given to `begin`.
    pub fn next_row<Frac: LeEqU32>(
        &mut self,
        points: &[ScreenPoint<Frac>],
        sorted: bool,
    ) -> Option<(u16, &mut [Crossing])> {
        self.crossings.clear();
        match self.mode {
            Mode::Narrow => self.next_narrow(sorted),
            Mode::Wide(rows) => {
                let row = self.next_wide(points, rows)?;
                if sorted {
                    sort_by_key(&mut self.crossings, |c| c.x);
                }
                Some((row, &mut self.crossings[..]))
            }
        }
    }

    // Indexing: 1 <= j <= i < min(len of both) in the insertion sort.
    #[allow(clippy::indexing_slicing)]
    fn next_narrow(&mut self, sorted: bool) -> Option<(u16, &mut [Crossing])> {
        let edges = &mut self.table.edges;
        let row = self.row;
        self.active
            .retain(|&i| edges.get(usize::from(i)).is_some_and(|e| e.end > row));
        if self.active.is_empty() {
            // Jump over rows where nothing is active.
            let first = edges.get(self.next)?.first;
            self.row = first;
        }
        let row = self.row;
        while let Some(edge) = edges.get(self.next) {
            if edge.first != row {
                break;
            }
            // Cannot fail: the table holds at most N <= u16::MAX edges, the list N slots.
            let _ = self.active.push(self.next as u16);
            self.next += 1;
        }
        let width = i32::from(self.viewport.width);
        let s = self.s;
        for &i in self.active.iter() {
            if let Some(edge) = edges.get_mut(usize::from(i)) {
                let x = edge.crossing(s).clamp(0, width) as u16;
                let _ = self.crossings.push(Crossing {
                    x,
                    winding: edge.winding,
                });
                edge.step();
            }
        }
        if sorted {
            // Sort the active list along with the crossings: edges keep their order
            // from row to row, so this insertion sort is linear but where edges cross.
            let (active, crossings) = (&mut self.active[..], &mut self.crossings[..]);
            for i in 1..crossings.len().min(active.len()) {
                let mut j = i;
                while j > 0 && crossings[j - 1].x > crossings[j].x {
                    crossings.swap(j - 1, j);
                    active.swap(j - 1, j);
                    j -= 1;
                }
            }
        }
        self.row += 1;
        // Rows lie in [0, height), height <= 8192.
        Some((row as u16, &mut self.crossings[..]))
    }

    /// Fills `crossings` for the next wide-mode row that has any; returns the row.
    fn next_wide<Frac: LeEqU32>(
        &mut self,
        points: &[ScreenPoint<Frac>],
        rows: RowRange,
    ) -> Option<u16> {
        let (s, viewport, window) = (self.s, self.viewport, self.window);
        while self.row < rows.end {
            let row = self.row;
            self.row += 1;
            for line in edge_lines(points) {
                let x = match line.clip(s, viewport, window) {
                    Clipped::Left(r) if r.contains(row) => 0,
                    Clipped::Rows(r) if r.contains(row) => line.crossing_at(s, row, viewport.width),
                    _ => continue,
                };
                // Cannot fail: `begin` checked that every surviving edge fits.
                let _ = self.crossings.push(Crossing {
                    x,
                    winding: line.winding,
                });
            }
            if !self.crossings.is_empty() {
                // Rows lie in [0, height), height <= 8192.
                return Some(row as u16);
            }
        }
        None
    }
}

/// `Err(CapacityExceeded)` when `needed` edges do not fit `capacity`.
fn check_capacity(needed: usize, capacity: usize) -> Result<(), Error> {
    if needed > capacity {
        return Err(Error::CapacityExceeded {
            what: Capacity::ActiveEdges,
            needed,
            capacity,
        });
    }
    Ok(())
}
