//! The crate's one sort: small, in place, allocation-free and non-recursive.

/// Ciura's gaps, extended by a factor of 2.25 so that long slices (a mesh's
/// half-edges) do not spend their time in the small-gap passes; descending.
const GAPS: [usize; 26] = [
    1_530_668_223,
    680_296_988,
    302_354_217,
    134_379_652,
    59_724_290,
    26_544_129,
    11_797_391,
    5_243_285,
    2_330_349,
    1_035_711,
    460_316,
    204_585,
    90_927,
    40_412,
    17_961,
    7_983,
    3_548,
    1_577,
    701,
    301,
    132,
    57,
    23,
    10,
    4,
    1,
];

/// Shell sort by `key`, ascending; not stable.
///
/// Short, in place, no recursion, and small in flash, unlike the library sort;
/// with gap 1 alone it is the insertion sort that nearly sorted rows want.
// Indexing: gap <= j < len in the loop, so j - gap and j are in bounds.
#[allow(clippy::indexing_slicing)]
pub(crate) fn sort_by_key<T, K: Ord>(items: &mut [T], key: impl Fn(&T) -> K) {
    let len = items.len();
    // A polygon's few edges: straight to the insertion sort, without walking the gaps.
    let gaps = if len <= 16 {
        &GAPS[GAPS.len() - 1..]
    } else {
        &GAPS[..]
    };
    for gap in gaps.iter().copied().filter(|&g| g < len) {
        for i in gap..len {
            let mut j = i;
            while j >= gap && key(&items[j - gap]) > key(&items[j]) {
                items.swap(j - gap, j);
                j -= gap;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sorts_short_and_long_slices() {
        let mut small = [5u32, 3, 9, 1, 1, 0];
        sort_by_key(&mut small, |&x| x);
        assert_eq!(small, [0, 1, 1, 3, 5, 9]);

        // Long enough to use the extended gaps; a multiplicative hash gives disorder.
        let mut long = [0u32; 5000];
        for (i, x) in long.iter_mut().enumerate() {
            *x = (i as u32).wrapping_mul(2_654_435_761) % 1000;
        }
        sort_by_key(&mut long, |&x| x);
        assert!(long.windows(2).all(|w| w[0] <= w[1]));
    }
}
