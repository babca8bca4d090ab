//! Each broken condition is an `Err` that names it, never a wrong table.

use super::*;
use crate::Capacity;
use crate::Error;
use std::string::ToString;

fn violation<T: core::fmt::Debug>(result: Result<T, Error>) -> SchemeViolation {
    match result {
        Err(Error::Scheme(v)) => v,
        other => panic!("expected a scheme violation, got {other:?}"),
    }
}

#[test]
fn a_graph_names_its_first_bad_path() {
    use SchemeViolation::*;
    let new = |paths: &'static [&'static [u16]]| violation(OcclusionGraph::new(4, paths));
    assert_eq!(new(&[&[0, 1], &[]]), EmptyPath { path: 1 });
    assert_eq!(
        new(&[&[0, 4]]),
        UnknownSurface {
            path: 0,
            surface: 4
        }
    );
    assert_eq!(
        new(&[&[2, 1, 2]]),
        RepeatedSurface {
            path: 0,
            surface: 2
        }
    );
    // Path 0 puts 1 in front of 3, path 2 puts 3 in front of 1.
    assert_eq!(
        new(&[&[0, 1, 3], &[2, 3], &[3, 2, 1]]),
        OrderConflict {
            first: 0,
            second: 2
        }
    );
    // Sharing surfaces in the same order is fine, and so is sharing none.
    assert!(OcclusionGraph::new(4, &[&[0, 1, 3], &[1, 3], &[2]]).is_ok());
}

#[test]
fn scheme_1_names_the_dependent_path_then_the_dependent_pair() {
    use SchemeViolation::*;
    let check = |codes: [u128; 4]| violation(check_combination_codes::<4>(&fig_2(), &codes));
    // 0001 + 0010 = 0011 on path {1,2,4}.
    assert_eq!(
        check([0b0001, 0b0010, 0b0100, 0b0011]),
        PathDependent { path: 0 }
    );
    // Surfaces 3 and 4 share a code on path {3,4}.
    assert_eq!(
        check([0b0001, 0b0010, 0b1000, 0b1000]),
        PathDependent { path: 1 }
    );
    // A zero code is dependent on its own.
    assert_eq!(
        check([0b0001, 0b0000, 0b0100, 0b1000]),
        PathDependent { path: 0 }
    );
    // Each path is independent, but 1+2 on path 1 equals 3 on path 2.
    let pair = check([0b0001, 0b0010, 0b0011, 0b0100]);
    assert_eq!(
        pair,
        PathUnionDependent {
            first: 0,
            second: 1
        }
    );
    let message = Error::<core::convert::Infallible>::Scheme(pair).to_string();
    assert!(message.contains("proposition 2") && message.contains("paths 0 and 1"));
    assert_eq!(
        check_combination_codes::<4>(&fig_2(), &[1, 2, 4]),
        Err(Error::Scheme(CodeCount {
            given: 3,
            expected: 4
        }))
    );
    assert!(CombinationScheme::<4>::new(fig_2(), &[1, 2, 3, 4]).is_err());
}

#[test]
fn codes_wider_than_the_compiled_width_are_refused_with_the_width_needed() {
    let too_wide = |needed, capacity| Err(Error::CodeTooWide { needed, capacity });
    let codes = [0b0001, 0b0010, 0b0100, 0b1000];
    assert_eq!(
        check_combination_codes::<3>(&fig_2(), &codes),
        too_wide(4, 3)
    );
    let mut found = [0; 4];
    assert_eq!(
        find_combination_codes::<3>(&fig_2(), 4, &mut found, 100),
        too_wide(4, 3)
    );
    assert_eq!(
        minimal_combination_codes::<3>(&fig_2(), &mut found, 100).map(|_| ()),
        too_wide(4, 3)
    );
    assert_eq!(
        PriorityScheme::<2>::new(fig_2()).map(|_| ()),
        too_wide(3, 2)
    );
    let (data, paths) = ([1, 2, 2, 4], [0, 1]);
    assert_eq!(
        PathScheme::<4>::new(fig_2(), HAMMING_8_4, &data, &paths).map(|_| ()),
        too_wide(8, 4)
    );
}

#[test]
fn the_search_reports_its_budget_spent() {
    let mut codes = [0; 4];
    assert_eq!(
        find_combination_codes::<4>(&fig_2(), 4, &mut codes, 2),
        Err(Error::Scheme(SchemeViolation::SearchGaveUp {
            width: 4,
            trials: 2
        }))
    );
}

#[test]
fn scheme_2_names_the_dependent_path_and_the_clashing_path_codes() {
    use SchemeViolation::*;
    let new = |data: &'static [u128], paths: &'static [u128]| {
        PathScheme::<8>::new(fig_2(), HAMMING_8_4, data, paths).map(|_| ())
    };
    assert!(new(&[1, 2, 2, 4], &[0, 1]).is_ok());
    assert_eq!(
        violation(new(&[1, 2, 2, 3], &[0, 1])),
        PathDependent { path: 0 }
    );
    assert_eq!(
        violation(new(&[1, 2, 4, 4], &[0, 1])),
        PathDependent { path: 1 }
    );
    // Equal path codes: their sum 0 is in every span.
    let same = violation(new(&[1, 2, 2, 4], &[1, 1]));
    assert_eq!(
        same,
        PathCodesInNodeSpan {
            first: 0,
            second: 1
        }
    );
    // p2 = the codeword of surface 1: 3 on path 2 looks like 1 + 2 on path 1.
    let clash = violation(new(&[1, 2, 2, 4], &[0, 0b0110_1001]));
    assert_eq!(
        clash,
        PathCodesInNodeSpan {
            first: 0,
            second: 1
        }
    );
    assert!(Error::<core::convert::Infallible>::Scheme(clash)
        .to_string()
        .contains("proposition 3"));
    // A data code wider than the (8,4) code's 4 data bits, a path code wider than 8.
    let too_wide = |needed, capacity| Err(Error::CodeTooWide { needed, capacity });
    assert_eq!(new(&[1, 2, 2, 0b1_0000], &[0, 1]), too_wide(5, 4));
    assert_eq!(new(&[1, 2, 2, 4], &[0, 0x100]), too_wide(9, 8));
    assert_eq!(
        violation(new(&[1, 2, 2, 4], &[0])),
        CodeCount {
            given: 1,
            expected: 2
        }
    );
}

#[test]
fn scheme_2_has_room_for_16_paths_with_the_8_4_code_and_32_with_the_16_11_code() {
    // Full-rank node codes: C is the whole Hamming code, so the paths are its cosets.
    static EIGHT_4: [&[u16]; 17] = [&[0, 1, 2, 3]; 17];
    static SIXTEEN_11: [&[u16]; 33] = [&[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10]; 33];
    let data: [u128; 11] = core::array::from_fn(|k| 1 << k);
    let mut paths = [0; 33];
    for (hamming, all_paths, surfaces) in [
        (HAMMING_8_4, &EIGHT_4[..], 4),
        (HAMMING_16_11, &SIXTEEN_11[..], 11),
    ] {
        let room = all_paths.len() - 1;
        let data = &data[..surfaces];
        let graph = OcclusionGraph::new(surfaces, &all_paths[..room]).unwrap();
        coset_path_codes::<16>(&graph, hamming, data, &mut paths[..room]).unwrap();
        assert!(PathScheme::<16>::new(graph, hamming, data, &paths[..room]).is_ok());
        let graph = OcclusionGraph::new(surfaces, all_paths).unwrap();
        assert_eq!(
            coset_path_codes::<16>(&graph, hamming, data, &mut paths[..=room]),
            Err(Error::CapacityExceeded {
                what: Capacity::PathCodes,
                needed: room + 1,
                capacity: room
            })
        );
    }
}

#[test]
fn level_codes_need_an_order_and_enough_data_bits() {
    // Pairwise consistent, but 0 before 1 before 2 before 0.
    let cycle = OcclusionGraph::new(3, &[&[0, 1], &[1, 2], &[2, 0]]).unwrap();
    let mut data = [0; 3];
    assert_eq!(
        level_node_codes(&cycle, HAMMING_8_4, &mut data),
        Err(Error::Scheme(SchemeViolation::CyclicOrder))
    );
    let five = OcclusionGraph::new(5, &[&[0, 1, 2, 3, 4]]).unwrap();
    let mut data = [0; 5];
    assert_eq!(
        level_node_codes(&five, HAMMING_8_4, &mut data),
        Err(Error::CodeTooWide {
            needed: 5,
            capacity: 4
        })
    );
    assert!(level_node_codes(&five, HAMMING_16_11, &mut data).is_ok());
}

#[test]
fn scheme_3_needs_room_for_the_priorities_and_paths_below_the_node_field() {
    let graph = fig_2();
    let scheme = PriorityScheme::<4>::new(graph).unwrap();
    assert_eq!(
        (scheme.width(), scheme.node_bits(), scheme.path_bits()),
        (3, 2, 1)
    );
    assert_eq!(
        PriorityScheme::<4>::with_fields(graph, 1, 1).map(|_| ()),
        Err(Error::CodeTooWide {
            needed: 2,
            capacity: 1
        })
    );
    // No path bits: path 1's blank address would be priority 1 of path 0.
    let clash = violation(PriorityScheme::<4>::with_fields(graph, 2, 0));
    assert_eq!(
        clash,
        SchemeViolation::NodeCodesInPathCode {
            first: 0,
            second: 1
        }
    );
    assert!(Error::<core::convert::Infallible>::Scheme(clash)
        .to_string()
        .contains("proposition 4"));
}

#[test]
fn colour_tables_that_do_not_fit_say_how_many_rows_they_need() {
    let full = |needed, capacity| {
        Err(Error::CapacityExceeded {
            what: Capacity::ColourTableRows,
            needed,
            capacity,
        })
    };
    let codes = [0b0001, 0b0010, 0b0100, 0b1000];
    let scheme_1 = CombinationScheme::<4>::new(fig_2(), &codes).unwrap();
    assert_eq!(scheme_1.colour_table::<9>().map(|_| ()), full(10, 9));
    let (data, paths) = ([1, 2, 2, 4], [0, 1]);
    let scheme_2 = PathScheme::<8>::new(fig_2(), HAMMING_8_4, &data, &paths).unwrap();
    assert_eq!(scheme_2.colour_table::<11>().map(|_| ()), full(12, 11));
    let scheme_3 = PriorityScheme::<4>::new(fig_2()).unwrap();
    assert_eq!(scheme_3.colour_table::<6>().map(|_| ()), full(7, 6));
}
