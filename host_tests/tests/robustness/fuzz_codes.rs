//! Fuzzing the GF(2) coding schemes of `pbuffer::codes` as property tests (seeded,
//! fixed case counts): random occlusion graphs, valid and broken (empty paths,
//! unknown and repeated surfaces, conflicting orders), random vectors up to 128 bits,
//! random Hamming data words. Properties, each against an independent oracle:
//! - `OcclusionGraph::new` gives exactly the first documented violation, or `Ok`;
//! - the priority scheme decodes every combination of a path's surfaces to its
//!   nearest surface, or is `CodeTooWide` exactly when the longest path exceeds `W`;
//! - `Basis` ranks and `independent` agree with a plain Gaussian elimination;
//! - extended Hamming codes are linear, codewords have syndrome 0, and every word at
//!   distance 1 or 2 from a codeword has a nonzero syndrome;
//! - codes found by `find_combination_codes` pass `check_combination_codes`.

use std::time::Instant;

use host_tests::random::Rng;
use pbuffer::codes::{
    check_combination_codes, find_combination_codes, independent, Basis, ExtendedHamming,
    OcclusionGraph, PriorityScheme, Visible,
};
use pbuffer::{Error, SchemeViolation};

const GRAPH_CASES: usize = 20_000;
const VECTOR_CASES: usize = 20_000;

/// Random paths over `surfaces` surfaces; with `bad`, now and then an invalid entry.
fn random_paths(rng: &mut Rng, surfaces: usize, bad: bool) -> Vec<Vec<u16>> {
    let count = 1 + rng.below(5) as usize;
    // A hidden global depth order makes the paths agree unless broken on purpose.
    let mut order: Vec<u16> = (0..surfaces as u16).collect();
    for i in (1..order.len()).rev() {
        order.swap(i, rng.below(i as u64 + 1) as usize);
    }
    (0..count)
        .map(|_| {
            let mut p: Vec<u16> = order.iter().copied().filter(|_| rng.chance(0.5)).collect();
            if p.is_empty() && !(bad && rng.chance(0.2)) {
                p.push(order[rng.below(surfaces as u64) as usize]);
            }
            if bad && rng.chance(0.1) {
                p.push(surfaces as u16 + rng.below(3) as u16);
            }
            if bad && rng.chance(0.1) && !p.is_empty() {
                let k = p[rng.below(p.len() as u64) as usize];
                p.push(k);
            }
            if bad && rng.chance(0.1) && p.len() >= 2 {
                p.swap(0, 1);
            }
            p
        })
        .collect()
}

/// The first violation of the documented order, or None.
fn graph_oracle(surfaces: usize, paths: &[Vec<u16>]) -> Option<SchemeViolation> {
    for (path, p) in paths.iter().enumerate() {
        if p.is_empty() {
            return Some(SchemeViolation::EmptyPath { path });
        }
        for (k, &surface) in p.iter().enumerate() {
            if usize::from(surface) >= surfaces {
                return Some(SchemeViolation::UnknownSurface { path, surface });
            }
            if p[..k].contains(&surface) {
                return Some(SchemeViolation::RepeatedSurface { path, surface });
            }
        }
    }
    for first in 0..paths.len() {
        for second in first + 1..paths.len() {
            let (a, b) = (&paths[first], &paths[second]);
            let sa: Vec<u16> = a.iter().copied().filter(|s| b.contains(s)).collect();
            let sb: Vec<u16> = b.iter().copied().filter(|s| a.contains(s)).collect();
            if sa != sb {
                return Some(SchemeViolation::OrderConflict { first, second });
            }
        }
    }
    None
}

#[test]
fn occlusion_graphs_and_the_priority_scheme() {
    let t = Instant::now();
    let mut rng = Rng::new(0xC0DE_5000_0001);
    let (mut valid, mut too_wide, mut combos) = (0usize, 0usize, 0usize);
    for case in 0..GRAPH_CASES {
        let surfaces = 1 + rng.below(10) as usize;
        let bad = rng.chance(0.5);
        let paths = random_paths(&mut rng, surfaces, bad);
        let refs: Vec<&[u16]> = paths.iter().map(Vec::as_slice).collect();
        let got = OcclusionGraph::new(surfaces, &refs);
        let want = graph_oracle(surfaces, &paths);
        let graph = match (got, want) {
            (Ok(g), None) => g,
            (Err(Error::Scheme(v)), Some(w)) if v == w => continue,
            (got, want) => panic!("case {case}: got {got:?}, want {want:?}: {surfaces} {paths:?}"),
        };
        valid += 1;
        let longest = paths.iter().map(Vec::len).max().unwrap_or(0);
        match PriorityScheme::<4>::new(graph) {
            Err(Error::CodeTooWide {
                needed,
                capacity: 4,
            }) => {
                assert!(longest > 4 && needed == longest, "case {case}: {paths:?}");
                too_wide += 1;
            }
            Ok(scheme) => {
                assert!(longest <= 4, "case {case}: {paths:?}");
                for (i, p) in paths.iter().enumerate() {
                    for mask in 0u32..1 << p.len() {
                        let code = (0..p.len())
                            .filter(|k| mask >> k & 1 == 1)
                            .map(|k| scheme.node_code(i, p[k]).expect("on the path"))
                            .fold(0u128, |a, c| a ^ c);
                        let want = (0..p.len())
                            .find(|k| mask >> k & 1 == 1)
                            .map_or(Visible::Blank, |k| Visible::Surface(p[k]));
                        assert_eq!(
                            scheme.visible(i, code),
                            Some(want),
                            "case {case}: path {i}, {mask:b}"
                        );
                        combos += 1;
                    }
                }
            }
            Err(e) => {
                // The narrowest fields never put two priorities' sum in the path code.
                panic!("case {case}: {e:?}: {paths:?}")
            }
        }
    }
    println!(
        "fuzz codes: {GRAPH_CASES} graphs ({valid} valid, {too_wide} too wide for 4 bits), {combos} combinations decoded in {:.2} s",
        t.elapsed().as_secs_f64()
    );
    assert!(valid > GRAPH_CASES / 4 && too_wide > 0);
}

/// Rank by plain Gaussian elimination on `u128`s (no pivot table).
fn rank(vectors: &[u128]) -> u32 {
    let mut rows = vectors.to_vec();
    let mut r = 0;
    for bit in (0..128).rev() {
        let Some(p) = (r..rows.len()).find(|&i| rows[i] >> bit & 1 == 1) else {
            continue;
        };
        rows.swap(r, p);
        for i in 0..rows.len() {
            if i != r && rows[i] >> bit & 1 == 1 {
                rows[i] ^= rows[r];
            }
        }
        r += 1;
    }
    r as u32
}

#[test]
fn gf2_bases_and_hamming_codes() {
    let t = Instant::now();
    let mut rng = Rng::new(0xC0DE_5000_0002);
    let random = |rng: &mut Rng, bits: u32| {
        let v = u128::from(rng.next_u64()) << 64 | u128::from(rng.next_u64());
        if bits >= 128 {
            v
        } else {
            v & ((1u128 << bits) - 1)
        }
    };
    for case in 0..VECTOR_CASES {
        // Few bits make dependence likely; 128 bits reach the top slot.
        let bits = [3, 8, 17, 64, 127, 128][rng.below(6) as usize];
        let n = rng.below(10) as usize;
        let vs: Vec<u128> = (0..n).map(|_| random(&mut rng, bits)).collect();
        let mut basis = Basis::<128>::new();
        for &v in &vs {
            basis.insert(v).expect("128 bits fit");
        }
        assert_eq!(basis.rank(), rank(&vs), "case {case}: {vs:x?}");
        assert_eq!(
            independent::<128>(vs.iter().copied()),
            Ok(rank(&vs) as usize == n),
            "case {case}"
        );
        let probe = random(&mut rng, bits);
        let mut with = vs.clone();
        with.push(probe);
        assert_eq!(
            basis.contains(probe),
            rank(&with) == rank(&vs),
            "case {case}"
        );
        // A narrow basis rejects a wide vector precisely.
        let wide = 1u128 << 20 | 1;
        assert_eq!(
            Basis::<16>::new().insert(wide),
            Err(Error::CodeTooWide {
                needed: 21,
                capacity: 16
            })
        );
        // Extended Hamming (8,4), (16,11), (32,26), (64,57), (128,120).
        let order = 3 + rng.below(5) as u32;
        let code = ExtendedHamming::with_order(order).expect("orders 3 to 7 exist");
        let (a, b) = (
            random(&mut rng, code.data_bits()),
            random(&mut rng, code.data_bits()),
        );
        let (ea, eb) = (code.encode(a).expect("fits"), code.encode(b).expect("fits"));
        assert_eq!(code.encode(a ^ b), Ok(ea ^ eb), "case {case}: linear");
        assert!(code.is_codeword(ea) && code.syndrome(ea) == 0);
        let len = code.length();
        let (i, j) = (
            rng.below(u64::from(len)) as u32,
            rng.below(u64::from(len)) as u32,
        );
        assert_ne!(code.syndrome(ea ^ 1 << i), 0, "case {case}: one flip");
        if i != j {
            assert_ne!(
                code.syndrome(ea ^ 1 << i ^ 1 << j),
                0,
                "case {case}: two flips"
            );
        }
        let too_wide = 1u128 << code.data_bits();
        assert_eq!(
            code.encode(too_wide),
            Err(Error::CodeTooWide {
                needed: code.data_bits() as usize + 1,
                capacity: code.data_bits() as usize
            })
        );
    }
    println!(
        "fuzz gf2: {VECTOR_CASES} cases in {:.2} s",
        t.elapsed().as_secs_f64()
    );
}

#[test]
fn found_combination_codes_pass_their_check() {
    let t = Instant::now();
    let mut rng = Rng::new(0xC0DE_5000_0003);
    let (mut found, mut narrow, mut proved_none) = (0, 0, 0);
    for case in 0..2000 {
        let surfaces = 1 + rng.below(8) as usize;
        let paths = random_paths(&mut rng, surfaces, false);
        let refs: Vec<&[u16]> = paths.iter().map(Vec::as_slice).collect();
        let graph = OcclusionGraph::new(surfaces, &refs).expect("valid by construction");
        let mut codes = vec![0u128; surfaces];
        // The narrowest width the search finds, from 1 up: a width of the surface
        // count always succeeds at once (unit vectors), so only narrower widths make
        // the search work, and a complete search that finds none is checked by
        // brute force where that is small.
        let mut width_found = None;
        for width in 1..=surfaces as u32 {
            match find_combination_codes::<16>(&graph, width, &mut codes, 1_000_000) {
                Ok(()) => {
                    assert_eq!(
                        check_combination_codes::<16>(&graph, &codes),
                        Ok(()),
                        "case {case} width {width}"
                    );
                    width_found = Some(width);
                    break;
                }
                Err(Error::Scheme(SchemeViolation::NoAssignment { .. })) => {
                    if (width as usize) * surfaces <= 12 {
                        assert!(
                            !any_assignment(&graph, width, surfaces),
                            "case {case}: the search found no {width}-bit codes, but some exist: {paths:?}"
                        );
                        proved_none += 1;
                    }
                }
                Err(Error::Scheme(SchemeViolation::SearchGaveUp { .. })) => {}
                Err(e) => panic!("case {case} width {width}: {e:?}: {paths:?}"),
            }
        }
        let width = width_found.unwrap_or_else(|| panic!("case {case}: no width: {paths:?}"));
        narrow += usize::from((width as usize) < surfaces);
        found += 1;
    }
    println!(
        "fuzz combination codes: {found} graphs, {narrow} with codes narrower than their surface count, {proved_none} widths with none checked by brute force, in {:.2} s",
        t.elapsed().as_secs_f64()
    );
    assert!(
        narrow * 4 > found,
        "the search rarely beat the trivial width: {narrow} of {found}"
    );
    assert!(
        proved_none > 100,
        "too few complete searches checked: {proved_none}"
    );
}

/// Whether any `width`-bit codes for the graph's `surfaces` pass the check (every
/// assignment tried: `2^(width surfaces)` of them).
fn any_assignment(graph: &OcclusionGraph<'_>, width: u32, surfaces: usize) -> bool {
    let mask = (1u128 << width) - 1;
    let total = 1u64 << (width as usize * surfaces);
    let mut codes = vec![0u128; surfaces];
    (0..total).any(|n| {
        for (k, c) in codes.iter_mut().enumerate() {
            *c = (u128::from(n) >> (k as u32 * width)) & mask;
        }
        check_combination_codes::<16>(graph, &codes).is_ok()
    })
}
