//! Scheme 1: combination codes and a colour table (Propositions 1 and 2).

use super::table::combination_rows;
use super::{bit_length, independent, ColourTable, OcclusionGraph, SchemeViolation};
use crate::Error;

/// Scheme 1 of the paper: one code per surface, the filler's XOR looked up in a colour
/// table. Exists only for codes that pass [`check_combination_codes`].
///
/// ```
/// use pbuffer::codes::{CombinationScheme, OcclusionGraph, Visible};
///
/// let graph = OcclusionGraph::new(4, &[&[0, 1, 3], &[2, 3]])?;
/// let scheme = CombinationScheme::<4>::new(graph, &[0b0001, 0b0010, 0b0100, 0b1000])?;
/// let table = scheme.colour_table::<16>()?;
/// // Surfaces 0 and 3 overlap: 0 is nearer.
/// assert_eq!(table.lookup(0b1001), Some(Visible::Surface(0)));
/// # Ok::<(), pbuffer::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CombinationScheme<'a, const W: usize> {
    graph: OcclusionGraph<'a>,
    codes: &'a [u128],
}

impl<'a, const W: usize> CombinationScheme<'a, W> {
    /// The scheme with `codes[s]` for surface `s`, if Propositions 1 and 2 hold.
    ///
    /// Errors: as [`check_combination_codes`].
    pub fn new(graph: OcclusionGraph<'a>, codes: &'a [u128]) -> Result<Self, Error> {
        check_combination_codes::<W>(&graph, codes)?;
        Ok(Self { graph, codes })
    }

    /// The occlusion graph.
    pub const fn graph(&self) -> OcclusionGraph<'a> {
        self.graph
    }

    /// The surface codes.
    pub const fn codes(&self) -> &'a [u128] {
        self.codes
    }

    /// The code width in use: the bit length of the widest code.
    pub fn width(&self) -> u32 {
        bit_length(self.codes.iter().fold(0, |all, &c| all | c))
    }

    /// The colour table: every combination of surfaces on a path, and the blank code
    /// 0, with the surface it shows. A combination that two paths share is one row.
    ///
    /// Errors: [`Error::CapacityExceeded`] with the rows needed if more than `E`.
    pub fn colour_table<const E: usize>(&self) -> Result<ColourTable<E>, Error> {
        let mut table = ColourTable::reserve(combination_rows(&self.graph, true))?;
        let code = |s: u16| self.codes.get(usize::from(s)).copied().unwrap_or(0);
        table.add_combinations(&self.graph, |_| 0, code)?;
        Ok(table)
    }
}

/// Checks scheme 1's conditions for `codes[s]`, the code of surface `s`: the codes of
/// every path are linearly independent over GF(2) (Proposition 1), and so are the
/// codes of the union of every two paths (Proposition 2). Together they make every
/// combination that can occur distinct, so the colour table is never ambiguous.
///
/// Errors, the first found: [`SchemeViolation::CodeCount`] unless one code per surface;
/// [`Error::CodeTooWide`] for a code of more than `W` bits;
/// [`SchemeViolation::PathDependent`] naming the first dependent path, checked for all
/// paths first; then [`SchemeViolation::PathUnionDependent`] naming the first pair.
pub fn check_combination_codes<const W: usize>(
    graph: &OcclusionGraph<'_>,
    codes: &[u128],
) -> Result<(), Error> {
    if codes.len() != graph.surfaces() {
        return Err(Error::Scheme(SchemeViolation::CodeCount {
            given: codes.len(),
            expected: graph.surfaces(),
        }));
    }
    match first_violation::<W>(graph, codes, codes.len(), None)? {
        Some(violation) => Err(Error::Scheme(violation)),
        None => Ok(()),
    }
}

/// The first broken proposition among the codes of surfaces `0..assigned` (the others
/// are ignored), looking only at the paths that hold `newest` when it is given: so a
/// search need only recheck what its newest code can have broken.
pub(crate) fn first_violation<const W: usize>(
    graph: &OcclusionGraph<'_>,
    codes: &[u128],
    assigned: usize,
    newest: Option<u16>,
) -> Result<Option<SchemeViolation>, Error> {
    let code = |s: u16| codes.get(usize::from(s)).copied().unwrap_or(0);
    let known = |s: &u16| usize::from(*s) < assigned;
    let holds_newest = |path: usize| match (newest, graph.path(path)) {
        (Some(n), Some(p)) => p.contains(&n),
        _ => true,
    };
    let paths = graph.paths().len();
    for path in (0..paths).filter(|&p| holds_newest(p)) {
        let surfaces = graph.path(path).unwrap_or(&[]).iter().copied();
        if !independent::<W>(surfaces.filter(known).map(code))? {
            return Ok(Some(SchemeViolation::PathDependent { path }));
        }
    }
    // Pairs with a path that holds `newest`: the outer loop visits only those (a
    // search's recheck costs a row of pairs per such path, not every pair).
    for first in (0..paths).filter(|&p| holds_newest(p)) {
        for other in (0..paths).filter(|&o| o != first && !(o < first && holds_newest(o))) {
            let (first, second) = (first.min(other), first.max(other));
            let union = graph.union(first, second).filter(known).map(code);
            if !independent::<W>(union)? {
                return Ok(Some(SchemeViolation::PathUnionDependent { first, second }));
            }
        }
    }
    Ok(None)
}
