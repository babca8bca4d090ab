//! The surface-coding schemes of the modulo-2 surface-filling paper, with their
//! conditions checked when a scheme is set up.
//!
//! The filler XORs a surface's code into a row at each of its edge crossings, so a
//! pixel holds the XOR of the codes of the surfaces covering it. Which surfaces can
//! cover one pixel together is described by an [`OcclusionGraph`]: its *paths* are
//! chains of surfaces in depth order, nearest first. A code is a `u128` whose bit 0 is
//! the rightmost digit of the paper's tables.
//!
//! The three schemes, each a type that exists only if its proposition holds:
//! - [`CombinationScheme`] (scheme 1): one code per surface; a [`ColourTable`] maps
//!   every XOR combination on a path to the visible surface. Propositions 1 and 2:
//!   the codes of every path, and of the union of every two paths, are linearly
//!   independent over GF(2). [`find_combination_codes`] searches for codes.
//! - [`PathScheme`] (scheme 2): surface codes encoded by an [`ExtendedHamming`] code
//!   plus a code per path, and a colour table. Proposition 3: the node codes of each
//!   path are independent and `p_i + p_j` is outside the span of the node codes.
//! - [`PriorityScheme`] (scheme 3, the default): weight-1 codes in depth order on each
//!   path, decoded by a priority encoder (`trailing_zeros`), the path code added after
//!   decoding. Proposition 4: `c_i + c_j` is never a path code. Width = longest path.
//!
//! A broken condition is an [`Error::Scheme`](crate::Error::Scheme) naming it, never
//! a wrong picture. Nothing is allocated: capacities are const generics, `W` for the
//! code width in bits (up to 128) and `E` for colour-table entries.

mod combination;
mod gf2;
mod graph;
mod hamming;
mod path;
mod priority;
mod search;
mod table;

#[cfg(test)]
mod tests;

use core::fmt;

pub use combination::{check_combination_codes, CombinationScheme};
pub use gf2::{independent, Basis};
pub use graph::OcclusionGraph;
pub use hamming::{ExtendedHamming, HAMMING_16_11, HAMMING_8_4};
pub use path::{coset_path_codes, level_node_codes, PathScheme};
pub use priority::{priority, PriorityScheme};
pub use search::{find_combination_codes, minimal_combination_codes};
pub use table::{ColourTable, TableEntry, Visible};

/// Which condition of a coding scheme (or of its occlusion graph) does not hold.
///
/// Paths are numbered from 0 in the order given to [`OcclusionGraph::new`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SchemeViolation {
    /// A path lists no surface.
    EmptyPath {
        /// The empty path.
        path: usize,
    },
    /// A path names a surface the graph does not have.
    UnknownSurface {
        /// The path.
        path: usize,
        /// The surface index, not below the surface count.
        surface: u16,
    },
    /// A path lists a surface twice.
    RepeatedSurface {
        /// The path.
        path: usize,
        /// The repeated surface.
        surface: u16,
    },
    /// Two paths put the surfaces they share in different depth orders.
    OrderConflict {
        /// The first path.
        first: usize,
        /// The second path.
        second: usize,
    },
    /// The depth orders of the paths form a cycle, so surfaces have no depth level.
    CyclicOrder,
    /// The number of codes given is not the number the graph needs.
    CodeCount {
        /// Codes given.
        given: usize,
        /// Codes needed (surfaces, or paths for path codes).
        expected: usize,
    },
    /// Proposition 1: the codes of this path are linearly dependent over GF(2), so two
    /// combinations on it give the same code.
    PathDependent {
        /// The path.
        path: usize,
    },
    /// Proposition 2: the codes of the union of these two paths are linearly
    /// dependent, so a combination on one equals a different one on the other.
    PathUnionDependent {
        /// The first path.
        first: usize,
        /// The second path.
        second: usize,
    },
    /// Proposition 3: `p_first + p_second` lies in the span of the node codewords, so a
    /// combination on one path equals a combination on the other.
    PathCodesInNodeSpan {
        /// The first path.
        first: usize,
        /// The second path.
        second: usize,
    },
    /// Proposition 4: the sum of the node codes of these two priorities is a path
    /// code, so a node on one path decodes like another node on another path.
    NodeCodesInPathCode {
        /// The first priority (0 = blank, 1 = nearest surface).
        first: u32,
        /// The second priority.
        second: u32,
    },
    /// No assignment of codes of this width satisfies Propositions 1 and 2.
    NoAssignment {
        /// The code width searched, in bits.
        width: u32,
    },
    /// The search for codes stopped after its budget of trials, undecided.
    SearchGaveUp {
        /// The code width searched, in bits.
        width: u32,
        /// Candidate codes tried.
        trials: u64,
    },
    /// A pixel's code is in no row of the colour table: the surfaces covering it are
    /// on no path of the graph (the scene has an overlap the graph omits), or the
    /// screen segment put the pixel on a path that does not hold them.
    UnlistedCode {
        /// The code the filler left at the pixel.
        code: u128,
        /// The pixel's column.
        x: u16,
        /// The pixel's row.
        y: u16,
    },
    /// A screen segment names a path the graph does not have.
    UnknownPath {
        /// The path named.
        path: usize,
        /// The pixel's column.
        x: u16,
        /// The pixel's row.
        y: u16,
    },
}

impl fmt::Display for SchemeViolation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::EmptyPath { path } => write!(f, "path {path} is empty"),
            Self::UnknownSurface { path, surface } => {
                write!(
                    f,
                    "path {path} names surface {surface}, which does not exist"
                )
            }
            Self::RepeatedSurface { path, surface } => {
                write!(f, "path {path} lists surface {surface} twice")
            }
            Self::OrderConflict { first, second } => write!(
                f,
                "paths {first} and {second} order their shared surfaces differently"
            ),
            Self::CyclicOrder => f.write_str("the paths' depth orders form a cycle"),
            Self::CodeCount { given, expected } => {
                write!(f, "{given} codes given, {expected} needed")
            }
            Self::PathDependent { path } => write!(
                f,
                "proposition 1: the codes of path {path} are linearly dependent"
            ),
            Self::PathUnionDependent { first, second } => write!(
                f,
                "proposition 2: the codes of paths {first} and {second} together are \
                 linearly dependent"
            ),
            Self::PathCodesInNodeSpan { first, second } => write!(
                f,
                "proposition 3: the sum of the codes of paths {first} and {second} is in \
                 the span of the node codes"
            ),
            Self::NodeCodesInPathCode { first, second } => write!(
                f,
                "proposition 4: the sum of the node codes of priorities {first} and \
                 {second} is a path code"
            ),
            Self::NoAssignment { width } => {
                write!(
                    f,
                    "no assignment of {width}-bit codes satisfies propositions 1 and 2"
                )
            }
            Self::SearchGaveUp { width, trials } => write!(
                f,
                "the search for {width}-bit codes gave up after {trials} trials"
            ),
            Self::UnlistedCode { code, x, y } => write!(
                f,
                "pixel ({x}, {y}) has code {code:#b}, which is in no row of the colour \
                 table (an overlap the occlusion graph omits)"
            ),
            Self::UnknownPath { path, x, y } => write!(
                f,
                "the screen segment of pixel ({x}, {y}) names path {path}, which does \
                 not exist"
            ),
        }
    }
}

/// The number of bits needed to write `value` in binary (0 for 0).
const fn bit_length(value: u128) -> u32 {
    u128::BITS - value.leading_zeros()
}
