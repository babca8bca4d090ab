//! Properties over the codes and over many small pseudo-random occlusion graphs.

use super::*;
use crate::Error;
use std::vec::Vec;

/// A small deterministic generator (xorshift), so failures can be replayed.
struct Dice(u64);

impl Dice {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// Paths of a random scene of `surfaces` surfaces: random subsets, each in the depth
/// order of one random permutation, so the orders are consistent.
fn random_paths(dice: &mut Dice, surfaces: usize, paths: usize) -> Vec<Vec<u16>> {
    let mut depth: Vec<u16> = (0..surfaces as u16).collect();
    for k in (1..surfaces).rev() {
        depth.swap(k, dice.below(k as u64 + 1) as usize);
    }
    (0..paths)
        .map(|_| {
            let keep = dice.below((1 << surfaces) - 1) + 1;
            let path: Vec<u16> = depth
                .iter()
                .enumerate()
                .filter(|&(k, _)| (keep >> k) & 1 == 1)
                .map(|(_, &s)| s)
                .collect();
            path
        })
        .collect()
}

#[test]
fn extended_hamming_codes_have_distance_4_and_zero_syndromes() {
    for hamming in [HAMMING_8_4, HAMMING_16_11] {
        assert_eq!(hamming.length(), hamming.data_bits() + hamming.order() + 1);
        for data in 0..1u128 << hamming.data_bits() {
            let word = hamming.encode(data).unwrap();
            assert!(hamming.is_codeword(word));
            assert!(data == 0 || word.count_ones() >= 4, "{data:b} -> {word:b}");
            // Flipping one digit gives a syndrome naming its position, parity set.
            for position in 0..hamming.length() {
                let flipped = word ^ (1 << (hamming.length() - 1 - position));
                let odd = 1 << hamming.order();
                assert_eq!(hamming.syndrome(flipped), position | odd);
            }
        }
    }
    let widest = ExtendedHamming::with_order(7).unwrap();
    assert_eq!((widest.length(), widest.data_bits()), (128, 120));
    let word = widest.encode((1 << 120) - 1).unwrap();
    assert!(widest.is_codeword(word));
    assert!(ExtendedHamming::with_order(1).is_none() && ExtendedHamming::with_order(8).is_none());
}

#[test]
fn reduction_gives_one_representative_per_coset() {
    let mut dice = Dice(0x9e37_79b9_7f4a_7c15);
    for _ in 0..200 {
        let mut span = Basis::<128>::new();
        let generators: Vec<u128> = (0..dice.below(12))
            .map(|_| u128::from(dice.next()) << dice.below(64))
            .collect();
        for &g in &generators {
            span.insert(g).unwrap();
        }
        let v = u128::from(dice.next()) * u128::from(dice.next());
        let member = generators
            .iter()
            .filter(|_| dice.below(2) == 1)
            .fold(0, |m, &g| m ^ g);
        assert!(span.contains(member));
        assert_eq!(span.reduce(v ^ member), span.reduce(v));
        assert_eq!(span.reduce(v) & span.pivots(), 0);
        assert_eq!(span.pivots().count_ones(), span.rank());
    }
    assert_eq!(
        Basis::<8>::new().insert(0x100),
        Err(Error::CodeTooWide {
            needed: 9,
            capacity: 8
        })
    );
}

#[test]
fn the_search_is_exhaustive_and_its_codes_pass_the_checker() {
    let mut dice = Dice(7);
    for _ in 0..60 {
        let surfaces = 2 + dice.below(3) as usize;
        let count = 1 + dice.below(3) as usize;
        let owned = random_paths(&mut dice, surfaces, count);
        let paths: Vec<&[u16]> = owned.iter().map(Vec::as_slice).collect();
        let graph = OcclusionGraph::new(surfaces, &paths).unwrap();
        let mut codes = [0; 4];
        let codes = &mut codes[..surfaces];
        let width = minimal_combination_codes::<8>(&graph, codes, u64::MAX).unwrap();
        assert!(width as usize >= graph.largest_union());
        assert_eq!(check_combination_codes::<8>(&graph, codes), Ok(()));
        // Brute force: no assignment one bit narrower passes the checker.
        let Some(narrower) = width.checked_sub(1) else {
            continue;
        };
        let values = 1u32 << narrower;
        for n in 0..values.pow(surfaces as u32) {
            let mut digits = n;
            for code in codes.iter_mut() {
                *code = u128::from(digits % values);
                digits /= values;
            }
            assert!(check_combination_codes::<8>(&graph, codes).is_err());
        }
    }
}

#[test]
fn every_colour_table_row_shows_the_nearest_surface_of_its_combination() {
    let mut dice = Dice(11);
    for _ in 0..40 {
        let surfaces = 2 + dice.below(4) as usize;
        let count = 1 + dice.below(3) as usize;
        let owned = random_paths(&mut dice, surfaces, count);
        let paths: Vec<&[u16]> = owned.iter().map(Vec::as_slice).collect();
        let graph = OcclusionGraph::new(surfaces, &paths).unwrap();
        let mut codes = [0; 5];
        let codes = &mut codes[..surfaces];
        minimal_combination_codes::<8>(&graph, codes, u64::MAX).unwrap();
        let scheme_1 = CombinationScheme::<8>::new(graph, codes).unwrap();
        let table_1 = scheme_1.colour_table::<128>().unwrap();
        let mut data = [0; 5];
        let data = &mut data[..surfaces];
        level_node_codes(&graph, HAMMING_16_11, data).unwrap();
        let mut path_codes = [0; 3];
        let path_codes = &mut path_codes[..paths.len()];
        coset_path_codes::<16>(&graph, HAMMING_16_11, data, path_codes).unwrap();
        let scheme_2 = PathScheme::<16>::new(graph, HAMMING_16_11, data, path_codes).unwrap();
        let table_2 = scheme_2.colour_table::<128>().unwrap();
        let scheme_3 = PriorityScheme::<8>::new(graph).unwrap();
        for (path, members) in paths.iter().enumerate() {
            for mask in 0..1u32 << members.len() {
                let covering: Vec<u16> = (0..members.len())
                    .filter(|k| (mask >> k) & 1 == 1)
                    .map(|k| members[k])
                    .collect();
                let nearest = covering
                    .first()
                    .map_or(Visible::Blank, |&s| Visible::Surface(s));
                let code_1 = covering.iter().fold(0, |c, &s| c ^ codes[usize::from(s)]);
                assert_eq!(table_1.lookup(code_1), Some(nearest));
                let code_2 = covering.iter().fold(path_codes[path], |c, &s| {
                    c ^ scheme_2.node_codeword(s).unwrap()
                });
                assert_eq!(table_2.lookup(code_2), Some(nearest));
                let code_3 = covering
                    .iter()
                    .fold(0, |c, &s| c ^ scheme_3.node_code(path, s).unwrap());
                assert_eq!(scheme_3.visible(path, code_3), Some(nearest));
            }
        }
    }
}

#[test]
fn codes_reach_128_bits_and_no_further() {
    static SURFACES: [u16; 129] = {
        let mut s = [0; 129];
        let mut k = 0;
        while k < 129 {
            s[k] = k as u16;
            k += 1;
        }
        s
    };
    static LONGEST: [&[u16]; 1] = [SURFACES.split_at(128).0];
    static TOO_LONG: [&[u16]; 1] = [&SURFACES];
    let graph = OcclusionGraph::new(128, &LONGEST).unwrap();
    let mut codes = [0; 128];
    assert_eq!(
        minimal_combination_codes::<128>(&graph, &mut codes, 1000),
        Ok(128)
    );
    assert_eq!(codes[127], 1 << 127);
    let scheme = PriorityScheme::<128>::new(graph).unwrap();
    assert_eq!(scheme.visible(0, 1 << 127), Some(Visible::Surface(127)));
    assert_eq!(priority(1 << 127), 128);
    let graph = OcclusionGraph::new(129, &TOO_LONG).unwrap();
    assert_eq!(
        PriorityScheme::<128>::new(graph).map(|_| ()),
        Err(Error::CodeTooWide {
            needed: 129,
            capacity: 128
        })
    );
    let mut codes = [0; 129];
    assert_eq!(
        minimal_combination_codes::<128>(&graph, &mut codes, 1000),
        Err(Error::CodeTooWide {
            needed: 129,
            capacity: 128
        })
    );
}
