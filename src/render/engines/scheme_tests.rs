extern crate std;
use std::vec;
use std::vec::Vec;

use fixed::types::extra::U4;

use super::*;
use crate::codes::{coset_path_codes, level_node_codes, OcclusionGraph, HAMMING_8_4};
use crate::render::two_squares::{count, frame, squares};
use crate::render::MonoPalette;

/// The two squares of [`two_squares`](crate::render::two_squares), face 0 nearer (depth
/// 1 against 0), drawn with `coding`, `rows` rows of codes lent.
fn draw<const W: usize, const E: usize>(
    coding: &SchemeCoding<'_, W, E>,
    rows: usize,
) -> Result<Vec<u16>, Error> {
    let (v, idx, off) = squares(1.0, 0.0);
    frame(
        &v,
        &idx,
        &off,
        |mesh, adj, camera, settings, ws, fb, probe| {
            let mut codes = vec![0u128; 32 * rows];
            SchemeRenderer::<U4, 16, 16>::new().render(
                mesh,
                adj,
                camera,
                settings,
                ws,
                coding,
                &mut codes,
                &MonoPalette::default(),
                fb,
                probe,
            )
        },
    )
}

const OVERLAP: &[&[u16]] = &[&[0, 1]];

#[test]
fn scheme_1_shows_the_nearer_square_over_the_overlap() {
    let graph = OcclusionGraph::new(2, OVERLAP).unwrap();
    let codes = [0b01, 0b10];
    let scheme = CombinationScheme::<2>::new(graph, &codes).unwrap();
    let coding = SchemeCoding::<2, 4>::combination(scheme).unwrap();
    for rows in [1, 5, 32] {
        let ids = draw(&coding, rows).unwrap();
        assert_eq!((count(&ids, 1), count(&ids, 2), count(&ids, 0)), (16, 8, 8));
        // Nothing above or below the squares.
        assert!(ids[..4 * 32].iter().all(|&i| i == 0));
    }
}

#[test]
fn a_graph_that_omits_an_overlap_is_an_unlisted_code_not_a_picture() {
    // Two paths of one surface each: the overlap's code 0b11 is in no row.
    let graph = OcclusionGraph::new(2, &[&[0], &[1]]).unwrap();
    let codes = [0b01, 0b10];
    let scheme = CombinationScheme::<2>::new(graph, &codes).unwrap();
    let coding = SchemeCoding::<2, 4>::combination(scheme).unwrap();
    match draw(&coding, 32) {
        Err(Error::Scheme(SchemeViolation::UnlistedCode { code, x, y })) => {
            assert_eq!(code, 0b11);
            // The first overlapping pixel: the top row of the squares, column 12.
            assert_eq!((x, y), (12, 8));
        }
        other => panic!("expected an unlisted code, got {other:?}"),
    }
}

#[test]
fn codes_for_another_number_of_faces_are_refused() {
    let graph = OcclusionGraph::new(3, &[&[0, 1, 2]]).unwrap();
    let codes = [1, 2, 4];
    let scheme = CombinationScheme::<3>::new(graph, &codes).unwrap();
    let coding = SchemeCoding::<3, 8>::combination(scheme).unwrap();
    assert_eq!(
        draw(&coding, 32),
        Err(Error::Scheme(SchemeViolation::CodeCount {
            given: 3,
            expected: 2
        }))
    );
}

#[test]
fn less_than_a_row_of_codes_is_a_capacity_error() {
    let graph = OcclusionGraph::new(2, OVERLAP).unwrap();
    let codes = [1, 2];
    let scheme = CombinationScheme::<2>::new(graph, &codes).unwrap();
    let coding = SchemeCoding::<2, 4>::combination(scheme).unwrap();
    assert_eq!(
        draw(&coding, 0),
        Err(Error::CapacityExceeded {
            what: Capacity::RowCodes,
            needed: 32,
            capacity: 0
        })
    );
}

#[test]
fn scheme_2_adds_the_segment_path_code_and_decodes_the_same_picture() {
    // A second path, unused on screen, so that the path codes differ.
    const PATHS: &[&[u16]] = &[&[0, 1], &[1]];
    let graph = OcclusionGraph::new(2, PATHS).unwrap();
    let mut data = [0u128; 2];
    level_node_codes(&graph, HAMMING_8_4, &mut data).unwrap();
    let mut path_codes = [0u128; 2];
    coset_path_codes::<8>(&graph, HAMMING_8_4, &data, &mut path_codes).unwrap();
    let scheme = PathScheme::<8>::new(graph, HAMMING_8_4, &data, &path_codes).unwrap();
    let segments = OneSegment(0);
    let coding = SchemeCoding::<8, 8>::path(scheme, &segments).unwrap();
    assert_eq!(coding.width(), 8);
    let ids = draw(&coding, 3).unwrap();
    assert_eq!((count(&ids, 1), count(&ids, 2), count(&ids, 0)), (16, 8, 8));
    // On path 1 (surface 1 alone) the overlap is not listed.
    let segments = OneSegment(1);
    let coding = SchemeCoding::<8, 8>::path(scheme, &segments).unwrap();
    assert!(matches!(
        draw(&coding, 3),
        Err(Error::Scheme(SchemeViolation::UnlistedCode { .. }))
    ));
    // A segment naming a path the graph lacks.
    let segments = OneSegment(2);
    let coding = SchemeCoding::<8, 8>::path(scheme, &segments).unwrap();
    assert_eq!(
        draw(&coding, 3),
        Err(Error::Scheme(SchemeViolation::UnknownPath {
            path: 2,
            x: 0,
            y: 0
        }))
    );
}
