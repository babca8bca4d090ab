//! Scheme 3, the default: weight-1 codes, a priority encoder, the path code added
//! after decoding (Proposition 4).

use super::{bit_length, ColourTable, OcclusionGraph, SchemeViolation, TableEntry, Visible};
use crate::Error;

/// Scheme 3 of the paper: on each path the surface of depth rank `r` (0 = nearest)
/// has the weight-1 code `1 << r`, so the lowest set bit of the filler's XOR names the
/// nearest surface (a priority encoder, [`priority`]: `trailing_zeros`). The *priority* `r + 1` (0
/// for blank) is then combined with the path's number into a colour-table address,
/// `priority << path_bits | path`: one row per surface of a path, not `2^len`.
///
/// The code width is the longest path, at most `W` bits (up to 128). Exists only if
/// Proposition 4 holds: the sum of two distinct node codes (priorities, placed above
/// the path field) is never in the linear code spanned by the path numbers.
///
/// ```
/// use pbuffer::codes::{OcclusionGraph, PriorityScheme, Visible};
///
/// let graph = OcclusionGraph::new(4, &[&[0, 1, 3], &[2, 3]])?;
/// let scheme = PriorityScheme::<32>::new(graph)?;
/// assert_eq!(scheme.width(), 3);
/// // On path 0, surfaces 1 and 3 overlap: codes 010 ^ 100; surface 1 is nearer.
/// assert_eq!(scheme.visible(0, 0b110), Some(Visible::Surface(1)));
/// # Ok::<(), pbuffer::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PriorityScheme<'a, const W: usize> {
    graph: OcclusionGraph<'a>,
    node_bits: u32,
    path_bits: u32,
}

impl<'a, const W: usize> PriorityScheme<'a, W> {
    /// The scheme with the narrowest fields: enough node bits for the longest path's
    /// priorities and enough path bits for the path numbers.
    ///
    /// Errors: as [`with_fields`](Self::with_fields).
    pub fn new(graph: OcclusionGraph<'a>) -> Result<Self, Error> {
        let node_bits = bit_length(graph.longest_path() as u128);
        let path_bits = bit_length(graph.paths().len().saturating_sub(1) as u128);
        Self::with_fields(graph, node_bits, path_bits)
    }

    /// The scheme with a colour-table address of `node_bits` priority bits above
    /// `path_bits` path bits (the paper's fig. 6: 4 and 4, for a 16-input priority
    /// encoder and 16 paths).
    ///
    /// Errors, the first found: [`Error::CodeTooWide`] if the longest path needs more
    /// than `W` (or 128) code bits, the address more than 128 bits, or the priorities
    /// more than `node_bits`; [`SchemeViolation::NodeCodesInPathCode`] for the first
    /// pair of priorities whose node codes sum to a path code (path numbers that reach
    /// into the node field).
    pub fn with_fields(
        graph: OcclusionGraph<'a>,
        node_bits: u32,
        path_bits: u32,
    ) -> Result<Self, Error> {
        let longest = graph.longest_path();
        let too_wide =
            |needed: usize, capacity: usize| Err(Error::CodeTooWide { needed, capacity });
        if longest > W.min(128) {
            return too_wide(longest, W.min(128));
        }
        let address_bits = node_bits.saturating_add(path_bits);
        if address_bits > 128 {
            return too_wide(address_bits as usize, 128);
        }
        let priority_bits = bit_length(longest as u128);
        if priority_bits > node_bits {
            return too_wide(priority_bits as usize, node_bits as usize);
        }
        // The path numbers 0..m span every vector below 2^bit_length(m - 1): that is the
        // linear code P of Proposition 4.
        let path_span_bits = bit_length(graph.paths().len().saturating_sub(1) as u128);
        let in_path_code = |v: u128| bit_length(v) <= path_span_bits;
        let priorities = longest as u32;
        for first in 0..=priorities {
            for second in first + 1..=priorities {
                let sum = u128::from(first ^ second).checked_shl(path_bits);
                if sum.is_some_and(in_path_code) {
                    return Err(Error::Scheme(SchemeViolation::NodeCodesInPathCode {
                        first,
                        second,
                    }));
                }
            }
        }
        Ok(Self {
            graph,
            node_bits,
            path_bits,
        })
    }

    /// The occlusion graph.
    pub const fn graph(&self) -> OcclusionGraph<'a> {
        self.graph
    }

    /// The code width: the longest path.
    pub fn width(&self) -> u32 {
        self.graph.longest_path() as u32
    }

    /// Bits of the priority field of an address.
    pub const fn node_bits(&self) -> u32 {
        self.node_bits
    }

    /// Bits of the path field of an address.
    pub const fn path_bits(&self) -> u32 {
        self.path_bits
    }

    /// The code of `surface` on path `path`: the unit vector of its depth rank there.
    /// A surface on several paths may have a different code on each.
    pub fn node_code(&self, path: usize, surface: u16) -> Option<u128> {
        let rank = self.graph.path(path)?.iter().position(|&s| s == surface)?;
        Some(1 << rank)
    }

    /// The colour-table address of `code` on path `path`: its priority above the path
    /// number (the path code added after decoding).
    pub fn address(&self, path: usize, code: u128) -> u128 {
        let priority = u128::from(priority(code));
        priority.checked_shl(self.path_bits).unwrap_or(0) ^ path as u128
    }

    /// What a pixel with `code` on path `path` shows, decoded directly; `None` for a
    /// path that does not exist or a code with a bit beyond the path.
    pub fn visible(&self, path: usize, code: u128) -> Option<Visible> {
        let surfaces = self.graph.path(path)?;
        if code == 0 {
            return Some(Visible::Blank);
        }
        let nearest = surfaces.get(code.trailing_zeros() as usize)?;
        (bit_length(code) as usize <= surfaces.len()).then_some(Visible::Surface(*nearest))
    }

    /// The colour table of the paper's fig. 6, path by path: each surface's address in
    /// depth order, then the path's blank address; `len + 1` rows per path.
    ///
    /// Errors: [`Error::CapacityExceeded`] with the rows needed if more than `E`.
    pub fn colour_table<const E: usize>(&self) -> Result<ColourTable<E>, Error> {
        let paths = self.graph.paths();
        let rows = paths
            .iter()
            .fold(0usize, |n, p| n.saturating_add(p.len() + 1));
        let mut table = ColourTable::reserve(rows)?;
        for (path, surfaces) in paths.iter().enumerate() {
            let rows = surfaces
                .iter()
                .enumerate()
                .map(|(rank, &s)| (1 << rank, Visible::Surface(s)));
            for (code, visible) in rows.chain([(0, Visible::Blank)]) {
                table.push(TableEntry {
                    code: self.address(path, code),
                    visible,
                    path,
                })?;
            }
        }
        Ok(table)
    }
}

/// The priority encoder of scheme 3: 0 for the blank code, else 1 + the lowest set bit
/// (the depth rank of the nearest surface, counted from 1).
pub const fn priority(code: u128) -> u32 {
    if code == 0 {
        0
    } else {
        code.trailing_zeros() + 1
    }
}
