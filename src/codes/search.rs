//! Finding scheme-1 codes: the paper's trial and error, made exhaustive and iterative.
//!
//! The conditions are linear independence, which no invertible linear map of the code
//! space changes. So the search only tries *canonical* assignments: while the codes so
//! far span exactly the lowest `r` unit vectors, the next code is either the unit
//! vector `2^r` or a value below `2^r`. Every valid assignment maps to a canonical one,
//! so "none found" proves that no assignment of that width exists.

use super::combination::first_violation;
use super::{bit_length, OcclusionGraph, SchemeViolation};
use crate::Error;

/// Fills `codes` (one per surface) with `width`-bit codes that satisfy Propositions 1
/// and 2, by exhaustive backtracking (no recursion: `codes` is the stack). Unit vectors
/// are tried first, so a width of at least the surface count succeeds at once.
///
/// Errors: [`SchemeViolation::CodeCount`] unless one code per surface;
/// [`Error::CodeTooWide`] if `width` exceeds `W` (or 128);
/// [`SchemeViolation::NoAssignment`] if no such codes exist (the search was complete);
/// [`SchemeViolation::SearchGaveUp`] after `max_trials` candidate codes. On an error
/// the contents of `codes` are unspecified.
pub fn find_combination_codes<const W: usize>(
    graph: &OcclusionGraph<'_>,
    width: u32,
    codes: &mut [u128],
    max_trials: u64,
) -> Result<(), Error> {
    let surfaces = graph.surfaces();
    if codes.len() != surfaces {
        return Err(Error::Scheme(SchemeViolation::CodeCount {
            given: codes.len(),
            expected: surfaces,
        }));
    }
    let capacity = W.min(128);
    if width as usize > capacity {
        return Err(Error::CodeTooWide {
            needed: width as usize,
            capacity,
        });
    }
    codes.fill(0);
    let mut level = 0;
    let mut trials = 0u64;
    while let Some(&current) = codes.get(level) {
        let earlier = codes.get(..level).unwrap_or(&[]);
        let rank = bit_length(earlier.iter().fold(0, |all, &c| all | c));
        let newest = u16::try_from(level).ok();
        // A surface on no path is never constrained: one candidate, no backtracking.
        let constrained = graph
            .paths()
            .iter()
            .any(|p| newest.is_some_and(|n| p.contains(&n)));
        let next = if constrained {
            next_candidate(current, rank, width)
        } else if current == 0 && width > 0 {
            Some(1)
        } else {
            None
        };
        let Some(candidate) = next else {
            if let Some(code) = codes.get_mut(level) {
                *code = 0;
            }
            if level == 0 {
                return Err(Error::Scheme(SchemeViolation::NoAssignment { width }));
            }
            level -= 1;
            continue;
        };
        if trials == max_trials {
            return Err(Error::Scheme(SchemeViolation::SearchGaveUp {
                width,
                trials,
            }));
        }
        trials += 1;
        if let Some(code) = codes.get_mut(level) {
            *code = candidate;
        }
        if first_violation::<W>(graph, codes, level + 1, newest)?.is_none() {
            level += 1;
            if let Some(code) = codes.get_mut(level) {
                *code = 0;
            }
        }
    }
    Ok(())
}

/// Finds codes of the least width that works, trying widths from the lower bound of
/// the corollary to Proposition 2 ([`OcclusionGraph::largest_union`]) upwards, with
/// [`find_combination_codes`] and a budget of `max_trials` per width. Returns the width.
///
/// Errors: [`Error::CodeTooWide`] if the lower bound exceeds `W` (or 128);
/// [`SchemeViolation::NoAssignment`] if no width up to `W` works; otherwise as
/// [`find_combination_codes`].
pub fn minimal_combination_codes<const W: usize>(
    graph: &OcclusionGraph<'_>,
    codes: &mut [u128],
    max_trials: u64,
) -> Result<u32, Error> {
    let capacity = W.min(128);
    let lower = graph.largest_union();
    if lower > capacity {
        return Err(Error::CodeTooWide {
            needed: lower,
            capacity,
        });
    }
    // Unit vectors, one per surface, always work: no need to look wider.
    let upper = capacity.min(graph.surfaces().max(lower).max(1));
    for width in lower..=upper {
        let width = width as u32;
        match find_combination_codes::<W>(graph, width, codes, max_trials) {
            Err(Error::Scheme(SchemeViolation::NoAssignment { .. })) => continue,
            Err(other) => return Err(other),
            Ok(()) => return Ok(width),
        }
    }
    Err(Error::Scheme(SchemeViolation::NoAssignment {
        width: upper as u32,
    }))
}

/// The candidate after `current` for a code whose predecessors span the lowest `rank`
/// unit vectors: 0 (nothing tried yet), then the new unit vector `2^rank` if the width
/// allows, then 1, 2, ..., `2^rank - 1` (codes in the span of the predecessors).
fn next_candidate(current: u128, rank: u32, width: u32) -> Option<u128> {
    let fresh = (rank < width).then(|| 1u128 << rank);
    let last_in_span = u128::MAX.checked_shr(128 - rank).unwrap_or(0);
    let first_in_span = (last_in_span >= 1).then_some(1);
    match current {
        0 => fresh.or(first_in_span),
        c if Some(c) == fresh => first_in_span,
        c => (c < last_in_span).then(|| c + 1),
    }
}
