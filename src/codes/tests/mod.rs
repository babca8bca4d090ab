//! Specifications of the coding schemes: the paper's worked example first, then the
//! conditions each scheme checks, then properties over many small graphs.

extern crate std;
use std::vec::Vec;

mod conditions;
mod paper;
mod properties;

use super::*;

/// Fig. 2 of the paper with its surfaces 1..4 numbered 0..3: surface 1 occludes 2;
/// 1, 2 and 3 occlude 4. Paths {1, 2, 4} and {3, 4}, nearest first.
const FIG_2: [&[u16]; 2] = [&[0, 1, 3], &[2, 3]];

fn fig_2() -> OcclusionGraph<'static> {
    OcclusionGraph::new(4, &FIG_2).unwrap()
}

/// A binary word as the paper prints it: "0110 1001" (spaces ignored).
fn word(digits: &str) -> u128 {
    digits
        .chars()
        .filter(|c| !c.is_whitespace())
        .fold(0, |w, c| (w << 1) | u128::from(c == '1'))
}

/// The colours of the paper's example: red (1), blue (2), green (3), yellow (4).
const R: Visible = Visible::Surface(0);
const B: Visible = Visible::Surface(1);
const G: Visible = Visible::Surface(2);
const Y: Visible = Visible::Surface(3);
const BLANK: Visible = Visible::Blank;

fn rows<const E: usize>(table: &ColourTable<E>) -> Vec<(u128, Visible)> {
    table
        .entries()
        .iter()
        .map(|e| (e.code, e.visible))
        .collect()
}
