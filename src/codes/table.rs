//! The colour table: from the code at a pixel to the surface visible there.

use super::{OcclusionGraph, SchemeViolation};
use crate::Capacity;
use crate::Error;

/// What a pixel shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Visible {
    /// No surface covers the pixel (the background).
    Blank,
    /// The nearest surface covering the pixel.
    Surface(u16),
}

/// One row of a colour table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TableEntry {
    /// The code (or, for the priority scheme, the address) this row answers.
    pub code: u128,
    /// What a pixel with this code shows.
    pub visible: Visible,
    /// The first path on which the code occurs.
    pub path: usize,
}

impl TableEntry {
    const UNUSED: Self = Self {
        code: 0,
        visible: Visible::Blank,
        path: 0,
    };
}

/// A colour table of up to `E` rows, in the order the paper lists them: path by path,
/// single surfaces first, then pairs, ..., then the blank code of the path.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ColourTable<const E: usize> {
    entries: [TableEntry; E],
    len: usize,
}

impl<const E: usize> Default for ColourTable<E> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const E: usize> ColourTable<E> {
    /// An empty table.
    pub const fn new() -> Self {
        Self {
            entries: [TableEntry::UNUSED; E],
            len: 0,
        }
    }

    /// The rows, in table order.
    pub fn entries(&self) -> &[TableEntry] {
        self.entries.get(..self.len).unwrap_or(&[])
    }

    /// The number of rows.
    pub const fn len(&self) -> usize {
        self.len
    }

    /// Whether the table has no rows.
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// What a pixel with `code` shows; `None` for a code no combination produces.
    /// A linear search: the table is for set-up and for checking, the hardware of
    /// the paper addresses it directly.
    pub fn lookup(&self, code: u128) -> Option<Visible> {
        self.entries()
            .iter()
            .find(|e| e.code == code)
            .map(|e| e.visible)
    }

    /// Fails early, before anything is built, when `needed` rows do not fit.
    pub(crate) fn reserve(needed: usize) -> Result<Self, Error> {
        if needed > E {
            return Err(Error::CapacityExceeded {
                what: Capacity::ColourTableRows,
                needed,
                capacity: E,
            });
        }
        Ok(Self::new())
    }

    /// Adds a row; a code already present with the same answer is not repeated.
    /// A code already present with another answer means two combinations clash:
    /// the proposition the caller checked would have failed, so it is reported as such.
    pub(crate) fn push(&mut self, entry: TableEntry) -> Result<(), Error> {
        if let Some(old) = self.entries().iter().find(|e| e.code == entry.code) {
            if old.visible == entry.visible {
                return Ok(());
            }
            let violation = if old.path == entry.path {
                SchemeViolation::PathDependent { path: entry.path }
            } else {
                SchemeViolation::PathUnionDependent {
                    first: old.path,
                    second: entry.path,
                }
            };
            return Err(Error::Scheme(violation));
        }
        let slot = self
            .entries
            .get_mut(self.len)
            .ok_or(Error::CapacityExceeded {
                what: Capacity::ColourTableRows,
                needed: self.len + 1,
                capacity: E,
            })?;
        *slot = entry;
        self.len += 1;
        Ok(())
    }

    /// Adds every combination of the surfaces of each path (the XOR of their node
    /// codes plus the path's code) and the path's blank code. The nearest surface of a
    /// combination is its first in the path's depth order.
    pub(crate) fn add_combinations(
        &mut self,
        graph: &OcclusionGraph<'_>,
        path_code: impl Fn(usize) -> u128,
        node_code: impl Fn(u16) -> u128,
    ) -> Result<(), Error> {
        for (index, path) in graph.paths().iter().enumerate() {
            let base = path_code(index);
            // `reserve` has bounded 2^len by E, so the masks fit.
            let subsets = 1u64.checked_shl(path.len() as u32).unwrap_or(0);
            for size in 1..=path.len() as u32 {
                for mask in (1..subsets).filter(|m| m.count_ones() == size) {
                    let members = path
                        .iter()
                        .enumerate()
                        .filter(|&(k, _)| (mask >> k) & 1 == 1)
                        .map(|(_, &s)| s);
                    let code = members.clone().fold(base, |c, s| c ^ node_code(s));
                    let nearest = members
                        .clone()
                        .next()
                        .map_or(Visible::Blank, Visible::Surface);
                    self.push(TableEntry {
                        code,
                        visible: nearest,
                        path: index,
                    })?;
                }
            }
            self.push(TableEntry {
                code: base,
                visible: Visible::Blank,
                path: index,
            })?;
        }
        Ok(())
    }
}

/// The rows a combination table of `graph` needs. With `shared`, a combination of
/// surfaces that an earlier path also holds is one row (scheme 1, where codes do not
/// depend on the path); otherwise each path has its own `2^len` rows (scheme 2).
/// Saturates at `usize::MAX`.
pub(crate) fn combination_rows(graph: &OcclusionGraph<'_>, shared: bool) -> usize {
    // Paths longer than this are not enumerated: their own rows alone exceed any
    // table one would compile, and 2^len is then reported (a lower bound when shared).
    const ENUMERATED: usize = 20;
    let mut rows = usize::from(shared);
    for (index, path) in graph.paths().iter().enumerate() {
        let subsets = 1usize.checked_shl(path.len() as u32).unwrap_or(usize::MAX);
        if !shared || path.len() > ENUMERATED {
            rows = rows.saturating_add(subsets);
            continue;
        }
        let earlier = graph.paths().get(..index).unwrap_or(&[]);
        for mask in 1..subsets {
            let members = path
                .iter()
                .enumerate()
                .filter(|&(k, _)| (mask >> k) & 1 == 1)
                .map(|(_, s)| s);
            let seen = earlier
                .iter()
                .any(|other| members.clone().all(|s| other.contains(s)));
            if !seen {
                rows += 1;
            }
        }
    }
    rows
}
