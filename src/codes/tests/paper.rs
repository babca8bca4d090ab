//! The paper's worked example, fig. 2 and its Tables 1 to 3, rebuilt by the library.

use super::*;
use crate::Error;

#[test]
fn four_weight_1_codes_of_4_bits_satisfy_scheme_1() {
    let codes = [0b0001, 0b0010, 0b0100, 0b1000];
    assert_eq!(check_combination_codes::<4>(&fig_2(), &codes), Ok(()));
    let scheme = CombinationScheme::<4>::new(fig_2(), &codes).unwrap();
    assert_eq!(scheme.width(), 4);
}

#[test]
fn no_assignment_of_3_bit_codes_satisfies_scheme_1() {
    // Every one of the 8^4 assignments, zero codes included, fails the checker.
    let mut union_only = 0;
    for n in 0..8u32.pow(4) {
        let codes: [u128; 4] = core::array::from_fn(|s| u128::from((n >> (3 * s)) & 7));
        match check_combination_codes::<3>(&fig_2(), &codes) {
            Err(Error::Scheme(SchemeViolation::PathDependent { path: 0 | 1 })) => {}
            Err(Error::Scheme(SchemeViolation::PathUnionDependent {
                first: 0,
                second: 1,
            })) => union_only += 1,
            other => panic!("codes {codes:?} gave {other:?}"),
        }
    }
    // Many assignments pass Proposition 1 on both paths and fail only Proposition 2.
    assert!(union_only > 0);
    let mut codes = [0; 4];
    assert_eq!(
        find_combination_codes::<3>(&fig_2(), 3, &mut codes, u64::MAX),
        Err(Error::Scheme(SchemeViolation::NoAssignment { width: 3 }))
    );
}

#[test]
fn the_least_width_for_fig_2_is_4_bits_and_the_search_finds_the_paper_codes() {
    let graph = fig_2();
    assert_eq!((graph.longest_path(), graph.largest_union()), (3, 4));
    let mut codes = [0; 4];
    assert_eq!(
        minimal_combination_codes::<8>(&graph, &mut codes, u64::MAX),
        Ok(4)
    );
    assert_eq!(codes, [0b0001, 0b0010, 0b0100, 0b1000]);
}

#[test]
fn scheme_1_colour_table_of_fig_2() {
    let codes = [0b0001, 0b0010, 0b0100, 0b1000];
    let table = CombinationScheme::<4>::new(fig_2(), &codes)
        .unwrap()
        .colour_table::<10>()
        .unwrap();
    // Path {1,2,4}: seven combinations; path {3,4}: 3 and 3+4 (4 alone is shared).
    let expected = [
        (word("0001"), R),
        (word("0010"), B),
        (word("1000"), Y),
        (word("0011"), R),
        (word("1001"), R),
        (word("1010"), B),
        (word("1011"), R),
        (word("0000"), BLANK),
        (word("0100"), G),
        (word("1100"), G),
    ];
    assert_eq!(rows(&table), expected);
}

/// The surface codes of the paper's second system: `c1 = 0001`, `c2 = c3 = 0010`,
/// `c4 = 0100` (the OCR prints "c1 = c3"; Table 1 shows surface 3 as 0010).
const PAPER_NODE_DATA: [u128; 4] = [0b0001, 0b0010, 0b0010, 0b0100];

#[test]
fn level_codes_are_the_papers_surface_codes_of_the_second_system() {
    let mut data = [0; 4];
    level_node_codes(&fig_2(), HAMMING_8_4, &mut data).unwrap();
    assert_eq!(data, PAPER_NODE_DATA);
}

#[test]
fn table_1_node_hamming_codewords() {
    // (combination, 4-bit code, Hamming code) as in Table 1. The OCR garbles the first
    // row's Hamming code ("0 11 ~1 ~8f"); 01101001 is Table 2's first row, and it is
    // the row 1+2 (11000011) minus the row 2 (10101010).
    let table_1: [(&[u16], u128, &str); 10] = [
        (&[0], 0b0001, "01101001"),
        (&[1], 0b0010, "10101010"),
        (&[3], 0b0100, "11001100"),
        (&[0, 1], 0b0011, "11000011"),
        (&[0, 3], 0b0101, "10100101"),
        (&[1, 3], 0b0110, "01100110"),
        (&[0, 1, 3], 0b0111, "00001111"),
        (&[2], 0b0010, "10101010"),
        (&[3], 0b0100, "11001100"),
        (&[2, 3], 0b0110, "01100110"),
    ];
    for (surfaces, data, hamming) in table_1 {
        let combined = surfaces
            .iter()
            .fold(0, |d, &s| d ^ PAPER_NODE_DATA[usize::from(s)]);
        assert_eq!(combined, data, "{surfaces:?}");
        assert_eq!(HAMMING_8_4.encode(data), Ok(word(hamming)), "{surfaces:?}");
        // The code is linear: the combination's codeword is the sum of the surfaces'.
        let summed = surfaces.iter().fold(0, |w, &s| {
            w ^ HAMMING_8_4.encode(PAPER_NODE_DATA[usize::from(s)]).unwrap()
        });
        assert_eq!(summed, word(hamming));
    }
}

#[test]
fn path_codes_of_the_second_system_are_the_papers() {
    let mut paths = [u128::MAX; 2];
    coset_path_codes::<8>(&fig_2(), HAMMING_8_4, &PAPER_NODE_DATA, &mut paths).unwrap();
    assert_eq!(paths, [word("00000000"), word("00000001")]);
}

#[test]
fn table_2_colour_table_of_the_second_system() {
    let graph = fig_2();
    let mut data = [0; 4];
    let mut paths = [0; 2];
    level_node_codes(&graph, HAMMING_8_4, &mut data).unwrap();
    coset_path_codes::<8>(&graph, HAMMING_8_4, &data, &mut paths).unwrap();
    let scheme = PathScheme::<8>::new(graph, HAMMING_8_4, &data, &paths).unwrap();
    let table = scheme.colour_table::<12>().unwrap();
    // Table 2, every row legible in the OCR, in the paper's order.
    let table_2 = [
        (word("01101001"), R),
        (word("10101010"), B),
        (word("11001100"), Y),
        (word("11000011"), R),
        (word("10100101"), R),
        (word("01100110"), B),
        (word("00001111"), R),
        (word("00000000"), BLANK),
        (word("10101011"), G),
        (word("11001101"), Y),
        (word("01100111"), G),
        (word("00000001"), BLANK),
    ];
    assert_eq!(rows(&table), table_2);
}

#[test]
fn table_3_colour_table_of_the_third_system() {
    // Fig. 6: a 16-input priority encoder (4-bit priority, 0000 = blank) and 4-bit
    // path codes address a 256-word colour table.
    let scheme = PriorityScheme::<16>::with_fields(fig_2(), 4, 4).unwrap();
    let table = scheme.colour_table::<8>().unwrap();
    // Table 3: address = node (priority) then path, every row legible in the OCR.
    let table_3 = [
        (word("0001 0000"), R),
        (word("0010 0000"), B),
        (word("0011 0000"), Y),
        (word("0000 0000"), BLANK),
        (word("0001 0001"), G),
        (word("0010 0001"), Y),
        (word("0000 0001"), BLANK),
    ];
    assert_eq!(rows(&table), table_3);
}

#[test]
fn the_third_system_decodes_every_combination_to_its_nearest_surface() {
    let graph = fig_2();
    let scheme = PriorityScheme::<16>::with_fields(graph, 4, 4).unwrap();
    let table = scheme.colour_table::<8>().unwrap();
    for (path, surfaces) in graph.paths().iter().enumerate() {
        for mask in 0..1u32 << surfaces.len() {
            let covering = surfaces
                .iter()
                .enumerate()
                .filter(|&(k, _)| (mask >> k) & 1 == 1);
            let code = covering
                .clone()
                .fold(0, |c, (_, &s)| c ^ scheme.node_code(path, s).unwrap());
            let nearest = covering.map(|(_, &s)| s).next();
            let expected = nearest.map_or(Visible::Blank, Visible::Surface);
            assert_eq!(scheme.visible(path, code), Some(expected));
            assert_eq!(table.lookup(scheme.address(path, code)), Some(expected));
        }
    }
    // Surface 4 sits at depth rank 2 on path {1,2,4} and rank 1 on path {3,4}.
    assert_eq!(scheme.node_code(0, 3), Some(0b100));
    assert_eq!(scheme.node_code(1, 3), Some(0b010));
}
