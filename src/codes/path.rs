//! Scheme 2: a code per path plus Hamming-coded surface codes (Proposition 3).

use super::gf2::deposit;
use super::table::combination_rows;
use super::{
    bit_length, independent, Basis, ColourTable, ExtendedHamming, OcclusionGraph, SchemeViolation,
};
use crate::Capacity;
use crate::Error;

/// Scheme 2 of the paper: each surface has a short data code, encoded by an extended
/// Hamming code into a *node codeword*; each path has a *path code* of the codeword's
/// length. A pixel holds its path's code plus the node codewords covering it, and a
/// colour table maps that to the visible surface. Surfaces on different paths may share
/// a code, so long paths need fewer bits than in scheme 1.
///
/// Exists only if Proposition 3 holds: the node codewords of each path are linearly
/// independent, and `p_i + p_j` is outside the span `C` of all node codewords for any
/// two paths.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PathScheme<'a, const W: usize> {
    graph: OcclusionGraph<'a>,
    hamming: ExtendedHamming,
    node_data: &'a [u128],
    path_codes: &'a [u128],
}

impl<'a, const W: usize> PathScheme<'a, W> {
    /// The scheme with data code `node_data[s]` for surface `s` and path code
    /// `path_codes[i]` for path `i`.
    ///
    /// Errors, the first found: [`SchemeViolation::CodeCount`] unless one data code per
    /// surface and one path code per path; [`Error::CodeTooWide`] if the Hamming code
    /// is longer than `W`, a data code wider than its data bits or a path code wider
    /// than its length; [`SchemeViolation::PathDependent`] for the first path whose
    /// node codewords are dependent; [`SchemeViolation::PathCodesInNodeSpan`] for the
    /// first pair of paths whose code sum is in `C`.
    pub fn new(
        graph: OcclusionGraph<'a>,
        hamming: ExtendedHamming,
        node_data: &'a [u128],
        path_codes: &'a [u128],
    ) -> Result<Self, Error> {
        check_counts(&graph, node_data, path_codes)?;
        let span = node_span::<W>(hamming, node_data)?;
        if let Some(&wide) = path_codes
            .iter()
            .find(|&&p| bit_length(p) > hamming.length())
        {
            return Err(Error::CodeTooWide {
                needed: bit_length(wide) as usize,
                capacity: hamming.length() as usize,
            });
        }
        let codeword = |s: u16| node_data.get(usize::from(s)).map(|&d| hamming.encode(d));
        for (path, surfaces) in graph.paths().iter().enumerate() {
            let words = surfaces.iter().filter_map(|&s| codeword(s)?.ok());
            if !independent::<W>(words)? {
                return Err(Error::Scheme(SchemeViolation::PathDependent { path }));
            }
        }
        for (first, &p) in path_codes.iter().enumerate() {
            for (second, &q) in path_codes.iter().enumerate().skip(first + 1) {
                if span.contains(p ^ q) {
                    return Err(Error::Scheme(SchemeViolation::PathCodesInNodeSpan {
                        first,
                        second,
                    }));
                }
            }
        }
        Ok(Self {
            graph,
            hamming,
            node_data,
            path_codes,
        })
    }

    /// The occlusion graph.
    pub const fn graph(&self) -> OcclusionGraph<'a> {
        self.graph
    }

    /// The Hamming code of the node codewords.
    pub const fn hamming(&self) -> ExtendedHamming {
        self.hamming
    }

    /// The node codeword of `surface`: its data code, Hamming-encoded.
    pub fn node_codeword(&self, surface: u16) -> Option<u128> {
        let data = *self.node_data.get(usize::from(surface))?;
        self.hamming.encode(data).ok()
    }

    /// The code of path `path`.
    pub fn path_code(&self, path: usize) -> Option<u128> {
        self.path_codes.get(path).copied()
    }

    /// The colour table: for each path, every combination of its surfaces plus the
    /// path code, then the path code alone (blank), `2^len` rows per path.
    ///
    /// Errors: [`Error::CapacityExceeded`] with the rows needed if more than `E`.
    pub fn colour_table<const E: usize>(&self) -> Result<ColourTable<E>, Error> {
        let mut table = ColourTable::reserve(combination_rows(&self.graph, false))?;
        let path_code = |p: usize| self.path_code(p).unwrap_or(0);
        let node_code = |s: u16| self.node_codeword(s).unwrap_or(0);
        table.add_combinations(&self.graph, path_code, node_code)?;
        Ok(table)
    }
}

/// The paper's choice of data codes for scheme 2: the unit vector of the surface's depth
/// level, nearest level in bit 0 (fig. 2: `c1 = 0001`, `c2 = c3 = 0010`, `c4 = 0100`).
/// A surface's level counts the surfaces behind it on the longest chain through the
/// paths; levels strictly fall along a path, so each path's codes are independent,
/// and surfaces on one level (never on one path) share a code.
///
/// Errors: [`SchemeViolation::CodeCount`] unless one code per surface;
/// [`SchemeViolation::CyclicOrder`]; [`Error::CodeTooWide`] with the levels needed if
/// more than the Hamming code's data bits.
pub fn level_node_codes(
    graph: &OcclusionGraph<'_>,
    hamming: ExtendedHamming,
    node_data: &mut [u128],
) -> Result<(), Error> {
    let levels = graph.depth_levels(node_data)?;
    if levels > hamming.data_bits() {
        return Err(Error::CodeTooWide {
            needed: levels as usize,
            capacity: hamming.data_bits() as usize,
        });
    }
    for code in node_data.iter_mut() {
        let bit = u128::from(levels - 1) - *code;
        *code = 1 << bit;
    }
    Ok(())
}

/// Path codes for scheme 2: one representative of a distinct coset of the span `C` of
/// the node codewords for each path, so `p_i + p_j` is never in `C`. They are the
/// smallest representatives with no pivot bit of `C` set: path 0 gets 0, and on fig. 2
/// path 1 gets `00000001`, as in the paper.
///
/// Errors: [`SchemeViolation::CodeCount`] unless one data code per surface and one path
/// code per path; [`Error::CodeTooWide`] as for [`PathScheme::new`];
/// [`Error::CapacityExceeded`] if there are more paths than cosets (16 for the full
/// (8,4) code, 32 for the (16,11) code).
pub fn coset_path_codes<const W: usize>(
    graph: &OcclusionGraph<'_>,
    hamming: ExtendedHamming,
    node_data: &[u128],
    path_codes: &mut [u128],
) -> Result<(), Error> {
    check_counts(graph, node_data, path_codes)?;
    let span = node_span::<W>(hamming, node_data)?;
    let all = u128::MAX >> (128 - hamming.length());
    let free = all & !span.pivots();
    let cosets = 1usize.checked_shl(free.count_ones()).unwrap_or(usize::MAX);
    if path_codes.len() > cosets {
        return Err(Error::CapacityExceeded {
            what: Capacity::PathCodes,
            needed: path_codes.len(),
            capacity: cosets,
        });
    }
    for (index, code) in path_codes.iter_mut().enumerate() {
        *code = deposit(index as u128, free);
    }
    Ok(())
}

/// The span `C` of the node codewords.
fn node_span<const W: usize>(
    hamming: ExtendedHamming,
    node_data: &[u128],
) -> Result<Basis<W>, Error> {
    if hamming.length() as usize > W {
        return Err(Error::CodeTooWide {
            needed: hamming.length() as usize,
            capacity: W,
        });
    }
    let mut span = Basis::<W>::new();
    for &data in node_data {
        span.insert(hamming.encode(data)?)?;
    }
    Ok(span)
}

/// One data code per surface and one path code per path.
fn check_counts(
    graph: &OcclusionGraph<'_>,
    node_data: &[u128],
    path_codes: &[u128],
) -> Result<(), Error> {
    let counts = [
        (node_data.len(), graph.surfaces()),
        (path_codes.len(), graph.paths().len()),
    ];
    match counts
        .into_iter()
        .find(|(given, expected)| given != expected)
    {
        Some((given, expected)) => Err(Error::Scheme(SchemeViolation::CodeCount {
            given,
            expected,
        })),
        None => Ok(()),
    }
}
