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

pub use combination::{check_combination_codes, CombinationScheme};
pub use gf2::{independent, Basis};
pub use graph::OcclusionGraph;
pub use hamming::{ExtendedHamming, HAMMING_16_11, HAMMING_8_4};
pub use path::{coset_path_codes, level_node_codes, PathScheme};
pub use priority::{priority, PriorityScheme};
pub use search::{find_combination_codes, minimal_combination_codes};
pub use table::{ColourTable, TableEntry, Visible};

/// Which condition of a coding scheme does not hold: defined beside
/// [`Error`](crate::Error) with the crate's other error details.
pub use crate::error::SchemeViolation;

/// The number of bits needed to write `value` in binary (0 for 0).
const fn bit_length(value: u128) -> u32 {
    u128::BITS - value.leading_zeros()
}
